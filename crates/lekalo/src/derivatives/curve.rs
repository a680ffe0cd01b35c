//! JVP, VJP and linearisation of B-spline curve batch evaluation `C(t_i) = Σ_j N_{j,p}(t_i) P_j`
//! with respect to the control points `P` and the parameters `t` (`docs/theory/derivatives.md`).

use super::checks::{check_input, check_len, check_output, check_scalars, zeroed_output};
use super::control_cotangent::control_cotangent_large;
use super::slopes::basis_with_slopes;
use crate::curve::BSplineCurve;
use crate::error::{check_finite, Result};

/// The linearisation of a curve's batch evaluation at parameters `t_0 … t_{m−1}`: what
/// [`BSplineCurve::eval_batch_linearize`] returns, enough to apply the Jacobian and its transpose
/// without calling the library again (an automatic-differentiation framework builds its linear
/// map from these arrays).
///
/// Row `i` of the basis matrix has its `p + 1` non-zero entries `N_{first_i + k, p}(t_i)`,
/// `k = 0..=p`, at `basis[i·(p + 1) + k]`; `C(t_i) = Σ_k basis[i·(p+1)+k] · P_{first_i + k}`.
#[derive(Debug, Clone, PartialEq)]
pub struct CurveLinearization {
    /// `C(t_i)`, point-major (`m × dim`): bit-for-bit [`BSplineCurve::eval_batch`].
    pub values: Vec<f64>,
    /// `C'(t_i)`, point-major (`m × dim`): right-hand derivatives at interior knots
    /// (left-hand at the right end of the domain).
    pub derivatives: Vec<f64>,
    /// Index of the first control point with a non-zero basis function at `t_i` (`span − p`).
    pub first: Vec<usize>,
    /// The `p + 1` non-zero basis functions at each `t_i` (`m × (p + 1)`).
    pub basis: Vec<f64>,
}

/// Basis values and first derivatives at one parameter, for one curve: scratch sized once.
pub(super) struct PointBasis {
    left: Vec<f64>,
    right: Vec<f64>,
    /// `N_{span−p..=span, p}(t)`.
    values: Vec<f64>,
    /// Their derivatives.
    slopes: Vec<f64>,
}

impl PointBasis {
    pub(super) fn new(degree: usize) -> Self {
        let w = degree + 1;
        PointBasis {
            left: vec![0.0; w],
            right: vec![0.0; w],
            values: vec![0.0; w],
            slopes: vec![0.0; w],
        }
    }

    /// Fills the basis values and derivatives at `t` in `span` ([`basis_with_slopes`]: the
    /// values bit-for-bit the A2.2 basis of `eval_batch`); returns the index of the first
    /// control point.
    pub(super) fn at(&mut self, knots: &[f64], degree: usize, span: usize, t: f64) -> usize {
        basis_with_slopes(
            knots,
            degree,
            span,
            t,
            &mut self.left,
            &mut self.right,
            &mut self.values,
            &mut self.slopes,
        );
        span - degree
    }

    pub(super) fn values(&self) -> &[f64] {
        &self.values
    }

    pub(super) fn slopes(&self) -> &[f64] {
        &self.slopes
    }
}

/// `out = Σ_k n_k · net[first + k]` (points of `dim` numbers), summed from zero in the order of
/// `k`: the order of the forward evaluation, so the same bits.
pub(super) fn combine(net: &[f64], dim: usize, first: usize, n: &[f64], out: &mut [f64]) {
    out.fill(0.0);
    let net = &net[first * dim..(first + n.len()) * dim];
    for (nk, c) in n.iter().zip(net.chunks_exact(dim)) {
        for (o, x) in out.iter_mut().zip(c) {
            *o += nk * x;
        }
    }
}

/// The buffers of a curve's JVP ([`BSplineCurve::eval_batch_jvp`] and the borrowed curve's):
/// the tangent output `ts_len × dim`, the control-point tangent as the control points
/// (`control_len` numbers) and the parameter tangent one a parameter, the tangents finite.
pub(super) fn check_jvp_buffers(
    (ts_len, dim, control_len): (usize, usize, usize),
    control_tangent: Option<&[f64]>,
    parameter_tangent: Option<&[f64]>,
    tangent_out: &[f64],
) -> Result<()> {
    check_len(
        "tangent output buffer (parameters × dimension)",
        ts_len.saturating_mul(dim),
        tangent_out.len(),
    )?;
    check_input(
        "control-point tangent (as the control points)",
        control_len,
        control_tangent,
    )?;
    check_input(
        "parameter tangent (one a parameter)",
        ts_len,
        parameter_tangent,
    )
}

/// The buffers of a curve's VJP ([`BSplineCurve::eval_batch_vjp`] and the borrowed curve's):
/// the cotangent `ts_len × dim`, the control-point cotangent as the control points
/// (`control_len` numbers, zeroed here) and the parameter cotangent one a parameter. The
/// cotangent's finiteness is the caller's (the large-batch path reads it from its sums).
pub(super) fn check_vjp_buffers(
    (ts_len, dim, control_len): (usize, usize, usize),
    cotangent: &[f64],
    control_cotangent: Option<&mut [f64]>,
    parameter_cotangent: Option<&[f64]>,
) -> Result<()> {
    check_len(
        "cotangent (parameters × dimension)",
        ts_len.saturating_mul(dim),
        cotangent.len(),
    )?;
    zeroed_output(
        "control-point cotangent buffer (as the control points)",
        control_len,
        control_cotangent,
    )?;
    check_output(
        "parameter cotangent buffer (one a parameter)",
        ts_len,
        parameter_cotangent,
    )
}

/// The tangent at one parameter, `d = Σ_k N_k Ṗ_{first+k} + C'(t) ṫ` (`dt` the parameter's
/// tangent `ṫ`; `None` tangents are zero), from its basis (`first` the span's first control
/// point, `slope` scratch of `dim` numbers): the body of every curve JVP loop, so that the built
/// and the borrowed curve sum in the same order (the same bits).
#[inline(always)]
#[allow(clippy::too_many_arguments)] // a net, its layout, a basis, two tangents and two buffers
pub(super) fn jvp_point(
    ctrl: &[f64],
    dim: usize,
    first: usize,
    basis: &PointBasis,
    control_tangent: Option<&[f64]>,
    dt: Option<f64>,
    slope: &mut [f64],
    d: &mut [f64],
) {
    match control_tangent {
        Some(dp) => combine(dp, dim, first, basis.values(), d),
        None => d.fill(0.0),
    }
    if let Some(dt) = dt {
        combine(ctrl, dim, first, basis.slopes(), slope);
        for (x, s) in d.iter_mut().zip(slope.iter()) {
            *x += s * dt;
        }
    }
}

/// The cotangents of one parameter for its output cotangent `g`: `N_k g` summed into the
/// control points `first ..= first + p` of `control_cotangent`, and `g · C'(t)` into
/// `parameter` (each when given; `slope` scratch of `dim` numbers): the body of every curve VJP
/// loop, shared as [`jvp_point`] is.
#[inline(always)]
#[allow(clippy::too_many_arguments)] // a net, its layout, a basis, a cotangent and three buffers
pub(super) fn vjp_point(
    ctrl: &[f64],
    dim: usize,
    first: usize,
    basis: &PointBasis,
    g: &[f64],
    control_cotangent: Option<&mut [f64]>,
    parameter: Option<&mut f64>,
    slope: &mut [f64],
) {
    if let Some(gp) = control_cotangent {
        let net = &mut gp[first * dim..(first + basis.values().len()) * dim];
        for (nk, c) in basis.values().iter().zip(net.chunks_exact_mut(dim)) {
            for (x, gi) in c.iter_mut().zip(g) {
                *x += nk * gi;
            }
        }
    }
    if let Some(gt) = parameter {
        combine(ctrl, dim, first, basis.slopes(), slope);
        *gt = slope.iter().zip(g).map(|(s, gi)| s * gi).sum();
    }
}

impl BSplineCurve {
    /// Checks `ts` and the point-major output `out` (`ts.len() × dim`).
    fn check_batch(&self, ts_len: usize, out_len: usize) -> Result<usize> {
        let dim = self.dim();
        check_len(
            "output buffer (parameters × dimension)",
            ts_len.saturating_mul(dim),
            out_len,
        )?;
        Ok(dim)
    }

    /// Forward-mode derivative (Jacobian-vector product) of [`BSplineCurve::eval_batch`]:
    /// `out` receives `C(t_i)` (bit-for-bit `eval_batch`) and `tangent_out` receives
    ///
    /// `Ċ_i = Σ_j N_{j,p}(t_i) Ṗ_j + C'(t_i) ṫ_i`
    ///
    /// for a control-point tangent `Ṗ` (`control_tangent`, point-major like the control
    /// points; `None` is zero) and a parameter tangent `ṫ` (`parameter_tangent`, one number a
    /// parameter; `None` is zero). The basis functions and their derivatives come from
    /// P&T Algorithm A2.3 (`docs/theory/derivatives.md`); each parameter
    /// touches `p + 1` control points. O(m·(p² + p·dim)), no allocation per point.
    ///
    /// At an interior knot where `C'` jumps, the derivative used is the right-hand one (the
    /// left-hand one at the right end), as in [`BSplineCurve::eval_derivatives`].
    ///
    /// ```
    /// use lekalo::{BSplineCurve, KnotVector, Points};
    /// let ctrl = Points::from_2d(&[[0.0, 0.0], [1.0, 2.0], [3.0, 2.0], [4.0, 0.0]])?;
    /// let c = BSplineCurve::from_knot_vector(3, KnotVector::clamped_uniform(3, 4)?, ctrl)?;
    /// // moving every control point by (1, 0) moves every point of the curve by (1, 0)
    /// let shift = [1.0, 0.0].repeat(4);
    /// let (mut out, mut tan) = (vec![0.0; 4], vec![0.0; 4]);
    /// c.eval_batch_jvp(&[0.25, 0.5], Some(&shift), None, &mut out, &mut tan)?;
    /// assert!(tan.chunks(2).all(|d| (d[0] - 1.0).abs() < 1e-15 && d[1].abs() < 1e-15));
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`crate::Error::LengthMismatch`] for a buffer of the wrong length (`out` and
    /// `tangent_out`: `ts.len() · dim`; `control_tangent`: as the control points;
    /// `parameter_tangent`: `ts.len()`); [`crate::Error::NonFinite`] for a non-finite tangent;
    /// [`crate::Error::ParameterOutOfDomain`] at the first parameter outside the domain.
    pub fn eval_batch_jvp(
        &self,
        ts: &[f64],
        control_tangent: Option<&[f64]>,
        parameter_tangent: Option<&[f64]>,
        out: &mut [f64],
        tangent_out: &mut [f64],
    ) -> Result<()> {
        let dim = self.check_batch(ts.len(), out.len())?;
        let ctrl_len = self.control_points().as_slice().len();
        let sizes = (ts.len(), dim, ctrl_len);
        check_jvp_buffers(sizes, control_tangent, parameter_tangent, tangent_out)?;
        let (p, knots, ctrl) = (
            self.degree(),
            self.knots().as_slice(),
            self.control_points().as_slice(),
        );
        let mut cursor = self.knots().span_cursor(p);
        let mut basis = PointBasis::new(p);
        let mut slope = vec![0.0; dim];
        let points = out
            .chunks_exact_mut(dim)
            .zip(tangent_out.chunks_exact_mut(dim));
        for (i, (&t, (o, d))) in ts.iter().zip(points).enumerate() {
            let first = basis.at(knots, p, cursor.find(t)?, t);
            combine(ctrl, dim, first, basis.values(), o);
            let dt = parameter_tangent.map(|dt| dt[i]);
            jvp_point(ctrl, dim, first, &basis, control_tangent, dt, &mut slope, d);
        }
        Ok(())
    }

    /// Reverse-mode derivative (vector-Jacobian product) of [`BSplineCurve::eval_batch`]: for a
    /// cotangent `ḡ` of the output (`cotangent`, `ts.len() × dim`, point-major),
    ///
    /// `P̄_j = Σ_i N_{j,p}(t_i) ḡ_i` into `control_cotangent` (as the control points) and
    /// `t̄_i = ḡ_i · C'(t_i)` into `parameter_cotangent` (one a parameter),
    ///
    /// each when given (`None` skips it). The buffers are overwritten. This is the transpose of
    /// [`BSplineCurve::eval_batch_jvp`]: `⟨ḡ, J ẋ⟩ = ⟨Jᵀ ḡ, ẋ⟩`. Basis functions by P&T
    /// A2.3; each parameter scatters into `p + 1` control points. O(m·(p² + p·dim)) plus the
    /// zeroing of `control_cotangent`. The control cotangent alone, for at least as many
    /// parameters as control points (a gradient with respect to the control points), takes a
    /// division-free path, the same sums to rounding: each parameter's span from a bucket table
    /// of the pieces (O(1) for spread-out knots, in any order), then per-piece power sums for
    /// degree ≤ [`crate::POWER_FORM_MAX_DEGREE`] (the transpose of the power-form evaluation,
    /// `power_sums.rs`), A2.2 with the reciprocals of the knot differences computed once a span
    /// above it (`control_cotangent.rs`); the cotangent's finiteness is then read from the sums.
    ///
    /// ```
    /// use lekalo::{BSplineCurve, KnotVector, Points};
    /// let ctrl = Points::from_flat(1, vec![0.0, 1.0, 3.0, 4.0])?;
    /// let c = BSplineCurve::from_knot_vector(2, KnotVector::clamped_uniform(2, 4)?, ctrl)?;
    /// // a cotangent of ones sums the basis rows: partition of unity gives m in total
    /// let mut grad = vec![0.0; 4];
    /// c.eval_batch_vjp(&[0.1, 0.5, 0.9], &[1.0; 3], Some(&mut grad), None)?;
    /// assert!((grad.iter().sum::<f64>() - 3.0).abs() < 1e-14);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`crate::Error::LengthMismatch`] for a buffer of the wrong length;
    /// [`crate::Error::NonFinite`] for a non-finite cotangent;
    /// [`crate::Error::ParameterOutOfDomain`] at the first parameter outside the domain (the
    /// output buffers are then unspecified).
    pub fn eval_batch_vjp(
        &self,
        ts: &[f64],
        cotangent: &[f64],
        mut control_cotangent: Option<&mut [f64]>,
        mut parameter_cotangent: Option<&mut [f64]>,
    ) -> Result<()> {
        let dim = self.dim();
        let ctrl = self.control_points().as_slice();
        check_vjp_buffers(
            (ts.len(), dim, ctrl.len()),
            cotangent,
            control_cotangent.as_deref_mut(),
            parameter_cotangent.as_deref(),
        )?;
        if let (Some(gp), None) = (control_cotangent.as_deref_mut(), &parameter_cotangent) {
            if ts.len() >= self.control_points().len() {
                // checks the cotangent finite from the sums
                return control_cotangent_large(self, ts, cotangent, gp);
            }
        }
        check_finite("cotangent", cotangent)?;
        let (p, knots) = (self.degree(), self.knots().as_slice());
        let mut cursor = self.knots().span_cursor(p);
        let mut basis = PointBasis::new(p);
        let mut slope = vec![0.0; dim];
        for (i, (&t, g)) in ts.iter().zip(cotangent.chunks_exact(dim)).enumerate() {
            let first = basis.at(knots, p, cursor.find(t)?, t);
            let gt = parameter_cotangent.as_deref_mut().map(|gt| &mut gt[i]);
            let gp = control_cotangent.as_deref_mut();
            vjp_point(ctrl, dim, first, &basis, g, gp, gt, &mut slope);
        }
        Ok(())
    }

    /// The linearisation of [`BSplineCurve::eval_batch`] at `ts`: the values `C(t_i)`
    /// (bit-for-bit `eval_batch`), the derivatives `C'(t_i)`, and the sparse rows of the basis
    /// matrix `N_{j,p}(t_i)` (the Jacobian with respect to every coordinate of the control
    /// points), as a [`CurveLinearization`]. From these, the JVP and VJP of
    /// [`BSplineCurve::eval_batch_jvp`] and [`BSplineCurve::eval_batch_vjp`] are a gather and a
    /// scatter. P&T A2.3; O(m·(p² + p·dim)).
    ///
    /// ```
    /// use lekalo::{BSplineCurve, KnotVector, Points};
    /// let ctrl = Points::from_2d(&[[0.0, 0.0], [1.0, 2.0], [3.0, 2.0], [4.0, 0.0]])?;
    /// let c = BSplineCurve::from_knot_vector(3, KnotVector::clamped_uniform(3, 4)?, ctrl)?;
    /// let lin = c.eval_batch_linearize(&[0.0, 0.5])?;
    /// assert_eq!(lin.first, vec![0, 0]);
    /// assert_eq!(&lin.basis[..4], &[1.0, 0.0, 0.0, 0.0]);     // C(0) = P_0
    /// assert!((lin.basis[4..].iter().sum::<f64>() - 1.0).abs() < 1e-15);
    /// assert_eq!(&lin.derivatives[..2], &[3.0, 6.0]);          // C'(0) = p (P_1 − P_0)
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`crate::Error::TooLarge`] if the arrays would exceed [`crate::MAX_SCALARS`];
    /// [`crate::Error::ParameterOutOfDomain`] at the first parameter outside the domain.
    pub fn eval_batch_linearize(&self, ts: &[f64]) -> Result<CurveLinearization> {
        let (p, dim) = (self.degree(), self.dim());
        let w = p + 1;
        check_scalars("linearisation (parameters × dimension)", ts.len(), dim)?;
        check_scalars("linearisation (parameters × (degree + 1))", ts.len(), w)?;
        let (knots, ctrl) = (self.knots().as_slice(), self.control_points().as_slice());
        let mut lin = CurveLinearization {
            values: vec![0.0; ts.len() * dim],
            derivatives: vec![0.0; ts.len() * dim],
            first: vec![0; ts.len()],
            basis: vec![0.0; ts.len() * w],
        };
        let mut cursor = self.knots().span_cursor(p);
        let mut basis = PointBasis::new(p);
        let rows = lin
            .values
            .chunks_exact_mut(dim)
            .zip(lin.derivatives.chunks_exact_mut(dim))
            .zip(lin.first.iter_mut().zip(lin.basis.chunks_exact_mut(w)));
        for (&t, ((o, d), (f, b))) in ts.iter().zip(rows) {
            let first = basis.at(knots, p, cursor.find(t)?, t);
            combine(ctrl, dim, first, basis.values(), o);
            combine(ctrl, dim, first, basis.slopes(), d);
            *f = first;
            b.copy_from_slice(basis.values());
        }
        Ok(lin)
    }
}
