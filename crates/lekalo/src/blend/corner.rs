//! Corner smoothing by a deformation (document 001's conclusion names it; the construction is
//! documented on [`CornerTransition`]).

use crate::blend::bernstein as bernstein_ops;
use crate::blend::deformation::{
    bezier_as_bspline, blend_forms, check_common, check_order, check_out_len, dist, elevate,
    weights_of, BezierForm, ParametricCurve,
};
use crate::blend::jump::JumpPolynomial;
use crate::curve::bezier::check_unit;
use crate::curve::nurbs::NurbsCurve;
use crate::error::{Error, Result};
use crate::points::Points;
use crate::Arg;
use crate::BezierCurve;

/// A corner-transition piece in exact form: `form` restricted to `range` (unit parameters) plus
/// `jump(u) · offset`, where `jump` are scalar Bernstein coefficients. Polynomial:
/// `restrict(P) + jump ⊗ offset` at degree `max(d, m)`; rational `A/ω`:
/// `(A + jump·ω·offset, ω)` at degree `d + m`.
fn offset_piece(
    form: &BezierForm,
    range: (f64, f64),
    jump: &[f64],
    offset: &[f64],
) -> Result<BezierForm> {
    let (h, dim) = form.homogeneous();
    let hd = dim + 1;
    let h = bernstein_ops::restrict(&h, hd, range.0, range.1);
    let m = jump.len() - 1;
    let d = h.len() / hd - 1;
    if let BezierForm::Polynomial(_) = form {
        let euclid: Vec<f64> = h
            .chunks_exact(hd)
            .flat_map(|p| p[..dim].iter().copied())
            .collect();
        let n = d.max(m);
        let mut ctrl = elevate(&euclid, dim, n - d);
        let jump = elevate(jump, 1, n - m);
        for (p, j) in ctrl.chunks_exact_mut(dim).zip(&jump) {
            for (x, o) in p.iter_mut().zip(offset) {
                *x += j * o;
            }
        }
        return Ok(BezierForm::Polynomial(BezierCurve::from_raw(
            Points::from_flat(dim, ctrl)?,
        )));
    }
    let omega = weights_of(&h, dim);
    let jw = bernstein_ops::product(jump, &omega, 1);
    let mut ctrl = elevate(&h, hd, m);
    for (p, j) in ctrl.chunks_exact_mut(hd).zip(&jw) {
        for (x, o) in p[..dim].iter_mut().zip(offset) {
            *x += j * o;
        }
    }
    let bez = BezierCurve::from_raw(Points::from_flat(hd, ctrl)?);
    Ok(BezierForm::Rational(NurbsCurve::from_homogeneous(
        bezier_as_bspline(&bez),
    )?))
}

/// A transition that smooths the corner where curve `before` (domain `[a_1, b_1]`) ends and
/// curve `after` (domain `[a_2, b_2]`) starts, `before(b_1) = after(a_2) = X`: the pieces
/// `before|[t_1, b_1]` and `after|[a_2, t_2]` are replaced by one curve from `before(t_1)` to
/// `after(t_2)` with continuity degree `k` at both ends.
///
/// Construction (document 001 names corner smoothing as an application but gives no
/// algorithm; this one is a deformation in its sense). With `h_1 = b_1 − t_1`,
/// `h_2 = t_2 − a_2`, `D_1 = before(t_1) − X`, `D_2 = after(t_2) − X`:
///
/// ```text
/// q_1(u) = before(t_1 + u h_1) + w_k(u) D_2          (contact of order k with `before` at u = 0)
/// q_2(u) = after(a_2 + u h_2)  + (1 − w_k(u)) D_1    (contact of order k with `after` at u = 1)
/// p(u)   = (1 − w_{k−1}(u)) q_1(u) + w_{k−1}(u) q_2(u)
/// ```
///
/// `q_1, q_2` run from `before(t_1)` to `after(t_2)` (common end points), so `p` is a
/// [`Deformation`](crate::Deformation) of `q_1` into `q_2`. The correction `w_k(u) D_2` has vanishing derivatives
/// up to order `k` at `u = 0`, so `q_1` keeps `before`'s derivatives there.
///
/// **Continuity:** `p^{(l)}(0) = h_1^l before^{(l)}(t_1)` and `p^{(l)}(1) = h_2^l after^{(l)}(t_2)`
/// for `l ≤ k`. Placing `p` on a parameter interval of length `h` after `before`'s `[a_1, t_1]`
/// gives **C^k when `h_1 = h_2 = h`** (equal parameter windows) and G^k (a linear
/// reparametrisation) otherwise.
///
/// **Exact form:** when both curves are single Bezier or rational Bezier pieces,
/// [`ParametricCurve::bezier_form`] returns the transition as one (rational) Bezier curve.
///
/// ```
/// use lekalo::{BezierCurve, BezierForm, CornerTransition, ParametricCurve, Points};
/// let before = BezierCurve::new(Points::from_2d(&[[-1.0, 0.0], [0.0, 0.0]])?)?;
/// let after = BezierCurve::new(Points::from_2d(&[[0.0, 0.0], [0.0, 1.0]])?)?;
/// let c = CornerTransition::new(&before, 0.5, &after, 0.5, 2)?; // C² rounding of a right angle
/// let Some(BezierForm::Polynomial(b)) = c.bezier_form() else { unreachable!() };
/// assert_eq!(b.degree(), 8); // (2k − 1) + (2k + 1)
/// let (p, q) = (b.eval(0.3)?, c.eval(0.3)?);
/// assert!((p[0] - q[0]).abs() < 1e-15 && (p[1] - q[1]).abs() < 1e-15);
/// # Ok::<(), lekalo::Error>(())
/// ```
#[derive(Debug, Clone)]
pub struct CornerTransition<C1, C2> {
    before: C1,
    after: C2,
    t1: f64,
    t2: f64,
    continuity: usize,
    outer: JumpPolynomial,
    inner: JumpPolynomial,
    /// `D_1 = before(t_1) − X`.
    d1: Vec<f64>,
    /// `D_2 = after(t_2) − X`.
    d2: Vec<f64>,
}

impl<C1: ParametricCurve, C2: ParametricCurve> CornerTransition<C1, C2> {
    /// The transition replacing `before` on `[t_start, b_1]` and `after` on `[a_2, t_end]`.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] if `continuity == 0`, or if `t_start` is not strictly inside
    /// `before`'s domain or `t_end` not strictly inside `after`'s (name the window);
    /// [`Error::Dimension`] if the dimensions differ; [`Error::EndPointMismatch`] if `before` does
    /// not end where `after` starts; evaluation errors of the curves.
    pub fn new(before: C1, t_start: f64, after: C2, t_end: f64, continuity: usize) -> Result<Self> {
        if continuity == 0 || continuity > JumpPolynomial::MAX_K {
            return Err(Error::InvalidArgument {
                what: Arg::Continuity.into(),
                reason: format!("got {continuity}; must be in 1..={}", JumpPolynomial::MAX_K),
            });
        }
        if before.dim() != after.dim() {
            return Err(Error::Dimension {
                what: "curve after the corner (must match the one before)".into(),
                expected: before.dim(),
                got: after.dim(),
            });
        }
        let (a1, b1) = before.domain();
        let (a2, b2) = after.domain();
        if !(t_start > a1 && t_start < b1) {
            return Err(Error::InvalidArgument {
                what: "window start t_start".into(),
                reason: format!("{t_start} must lie strictly inside ({a1}, {b1})"),
            });
        }
        if !(t_end > a2 && t_end < b2) {
            return Err(Error::InvalidArgument {
                what: "window end t_end".into(),
                reason: format!("{t_end} must lie strictly inside ({a2}, {b2})"),
            });
        }
        let corner = before.eval(b1)?;
        let chord = dist(&before.eval(a1)?, &corner);
        check_common(
            "corner (end of `before`, start of `after`)",
            &corner,
            &after.eval(a2)?,
            chord,
        )?;
        let d1: Vec<f64> = before
            .eval(t_start)?
            .iter()
            .zip(&corner)
            .map(|(p, x)| p - x)
            .collect();
        let d2: Vec<f64> = after
            .eval(t_end)?
            .iter()
            .zip(&corner)
            .map(|(p, x)| p - x)
            .collect();
        Ok(CornerTransition {
            before,
            after,
            t1: t_start,
            t2: t_end,
            continuity,
            outer: JumpPolynomial::new(continuity)?,
            inner: JumpPolynomial::new(continuity - 1)?,
            d1,
            d2,
        })
    }

    /// The continuity degree `k`.
    #[must_use]
    pub fn continuity(&self) -> usize {
        self.continuity
    }

    /// The window `(t_start, t_end)`.
    #[must_use]
    pub fn window(&self) -> (f64, f64) {
        (self.t1, self.t2)
    }

    /// The parameter lengths `(h_1, h_2)` of the replaced pieces: the transition is C^k with
    /// both curves when they are equal (see the type docs).
    #[must_use]
    pub fn window_lengths(&self) -> (f64, f64) {
        (
            self.before.domain().1 - self.t1,
            self.t2 - self.after.domain().0,
        )
    }

    /// `p^{(l)}(u)`, `l = 0 … order`, as rows of [`Points`].
    ///
    /// # Errors
    /// [`Error::ParameterOutOfDomain`] unless `0 ≤ u ≤ 1`; [`Error::TooLarge`] for an order above
    /// [`MAX_DERIVATIVE_ORDER`](crate::MAX_DERIVATIVE_ORDER); errors of the curves.
    pub fn eval_derivatives(&self, u: f64, order: usize) -> Result<Points> {
        check_order(order)?;
        let dim = self.before.dim();
        let mut out = vec![0.0; (order + 1) * dim];
        self.eval_derivatives_into(u, order, &mut out)?;
        Ok(Points::from_raw(out, dim))
    }
}

impl<C1: ParametricCurve, C2: ParametricCurve> ParametricCurve for CornerTransition<C1, C2> {
    fn dim(&self) -> usize {
        self.before.dim()
    }
    fn domain(&self) -> (f64, f64) {
        (0.0, 1.0)
    }
    /// Exact form when `before` and `after` are single (rational) Bezier pieces: the windows are
    /// cut out by de Casteljau subdivision, `q_1, q_2` get their `w_k` offsets in Bernstein form
    /// and are blended as in [`Deformation::to_nurbs`](crate::Deformation::to_nurbs). Polynomial pieces of degrees `d_1, d_2`
    /// give degree `(2k − 1) + max(d_1, d_2, 2k + 1)`.
    fn bezier_form(&self) -> Option<BezierForm> {
        let (f1, f2) = (self.before.bezier_form()?, self.after.bezier_form()?);
        let (a1, b1) = self.before.domain();
        let (a2, b2) = self.after.domain();
        let r1 = ((self.t1 - a1) / (b1 - a1), 1.0);
        let r2 = (0.0, (self.t2 - a2) / (b2 - a2));
        let wk = self.outer.bernstein_coefficients_f64();
        let one_minus: Vec<f64> = wk.iter().map(|x| 1.0 - x).collect();
        let q1 = offset_piece(&f1, r1, &wk, &self.d2).ok()?;
        let q2 = offset_piece(&f2, r2, &one_minus, &self.d1).ok()?;
        blend_forms(&q1, &q2, &self.inner).ok()
    }

    fn eval_derivatives_into(&self, u: f64, order: usize, out: &mut [f64]) -> Result<()> {
        check_unit(u)?;
        let dim = self.before.dim();
        check_out_len(out, order, dim)?;
        let (h1, h2) = self.window_lengths();
        // q_1 into `out`; q_2, w_k's and w_{k−1}'s derivatives in one work slice (on the stack
        // for small orders)
        crate::blend::bernstein::with_work(out.len() + 2 * (order + 1), |work| {
            let (q2, rest) = work.split_at_mut(out.len());
            let (wk, w) = rest.split_at_mut(order + 1);
            let t = (self.t1 + u * h1).min(self.before.domain().1);
            self.before.eval_derivatives_into(t, order, out)?;
            let t = (self.after.domain().0 + u * h2).min(self.t2);
            self.after.eval_derivatives_into(t, order, q2)?;
            self.outer.eval_derivatives(u, wk)?;
            let (mut s1, mut s2) = (1.0, 1.0);
            for l in 0..=order {
                for d in 0..dim {
                    let i = l * dim + d;
                    // (1 − w_k)^{(l)} = δ_{l0} − w_k^{(l)}
                    let one_minus = if l == 0 { 1.0 - wk[0] } else { -wk[l] };
                    out[i] = s1 * out[i] + wk[l] * self.d2[d];
                    q2[i] = s2 * q2[i] + one_minus * self.d1[d];
                }
                s1 *= h1;
                s2 *= h2;
            }
            // p = q_1 + Σ C(l,i) w_{k−1}^{(i)} (q_2 − q_1)^{(l−i)}
            self.inner.eval_derivatives(u, w)?;
            crate::blend::deformation::blend_derivatives(
                out,
                q2,
                w,
                dim,
                "corner transition derivatives (overflow: rescale the curves)",
            )
        })
    }
}
