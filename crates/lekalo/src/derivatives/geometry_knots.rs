//! The knot derivatives of `geometry.rs`'s two queries
//! (`docs/theory/derivatives.md#arc-length-and-closest-points`, "With respect to the knots"):
//!
//! - both queries are invariant (the length) or equivariant (the closest parameter, which maps
//!   with the parameter) under an affine map of all the knots, which only reparameterises the
//!   curve. A knot tangent `τ̇` splits into the affine map `ℓ` that moves the domain ends
//!   `a = τ_p`, `b = τ_n` as `τ̇_p`, `τ̇_n` (`ℓ(t) = τ̇_p (b − t)/(b − a) + τ̇_n (t − a)/(b − a)`,
//!   the `p` knots outside each end following it) and the rest `r = τ̇ − ℓ(τ)`, zero at the
//!   ends, which moves interior knots only: `L̇ = ∂L/∂τ_int · r` and `ṫ = ℓ(t*) + ∂t*/∂τ_int · r`;
//! - with the domain fixed, `∂C/∂τ_k` is the knot-insertion formula
//!   ([`crate::BSplineCurve::eval_batch_knot_jvp`]) and `∂C'/∂τ_k` that of the derivative curve
//!   `C' = Σ_i N_{i,p−1} Q_i`, `Q_i = p (P_{i+1} − P_i)/(τ_{i+p+1} − τ_{i+1})`, on the knots
//!   `τ_1 … τ_{n+p−1}`, plus its control points' dependence on `τ` ([`SpeedKnots`]).

use super::{dot, ArcLengthGradient, ClosestParameters};
use crate::curve::BSplineCurve;
use crate::derivatives::checks::{check_input, check_len};
use crate::derivatives::curve::{combine, PointBasis};
use crate::error::{check_finite, Error, Result};
use crate::points::Points;

/// The derivative curve `C'` of a curve of degree `p ≥ 1` on the knots `τ_1 … τ_{n+p−1}`
/// (every control point kept, so that `Q_i` is index `i`), and `∂C'(t)/∂τ_k` for the interior
/// knots with the domain fixed: the derivative curve's knot derivative (its knot `k − 1`) plus
/// `Σ_i N_{i,p−1}(t) ∂Q_i/∂τ_k`, `∂Q_i/∂τ_{i+1} = Q_i/g_i = −∂Q_i/∂τ_{i+p+1}`,
/// `g_i = τ_{i+p+1} − τ_{i+1}`.
#[derive(Debug, Clone)]
pub(super) struct SpeedKnots {
    degree: usize,
    n: usize,
    deriv: BSplineCurve,
    /// `1/g_i`, 0 where `g_i = 0`.
    inverse_gaps: Vec<f64>,
}

impl SpeedKnots {
    pub(super) fn new(curve: &BSplineCurve) -> Result<Self> {
        let (p, dim, n) = (curve.degree(), curve.dim(), curve.control_points().len());
        if p == 0 {
            return Err(Error::Degree {
                degree: 0,
                reason: "a piecewise constant curve has no derivative in its knots here; use \
                         degree 1 or more"
                    .into(),
            });
        }
        let (knots, ctrl) = (curve.knots().as_slice(), curve.control_points().as_slice());
        let mut q = vec![0.0; (n - 1) * dim];
        let mut inverse_gaps = vec![0.0; n - 1];
        for i in 0..n - 1 {
            let gap = knots[i + p + 1] - knots[i + 1];
            if gap > 0.0 {
                inverse_gaps[i] = 1.0 / gap;
                let s = p as f64 / gap;
                for d in 0..dim {
                    q[i * dim + d] = s * (ctrl[(i + 1) * dim + d] - ctrl[i * dim + d]);
                }
            }
        }
        check_finite(
            "derivative control points (overflow: rescale the control points)",
            &q,
        )?;
        let inner = knots[1..knots.len() - 1].to_vec();
        let deriv = BSplineCurve::new(p - 1, inner, Points::from_flat(dim, q)?).map_err(|_| {
            Error::InvalidArgument {
                what: "knots".into(),
                reason: format!(
                    "a knot of multiplicity {} (degree + 1) inside the domain: the curve jumps \
                     there and its derivative in the knots does not exist; use multiplicities \
                     of at most {p} inside the domain",
                    p + 1
                ),
            }
        })?;
        Ok(SpeedKnots {
            degree: p,
            n,
            deriv,
            inverse_gaps,
        })
    }

    fn interior(&self) -> std::ops::RangeInclusive<usize> {
        self.degree + 1..=self.n - 1
    }

    /// `∂C'(t_i)/∂τ · r` for a knot tangent `r` zero outside the interior knots (`m × dim`).
    pub(super) fn jvp(&self, ts: &[f64], r: &[f64]) -> Result<Vec<f64>> {
        let (p, dim) = (self.degree, self.deriv.dim());
        let m = ts.len() * dim;
        let (mut out, mut tangent, mut more) = (vec![0.0; m], vec![0.0; m], vec![0.0; m]);
        self.deriv
            .eval_batch_knot_jvp(ts, &r[1..r.len() - 1], &mut out, &mut tangent)?;
        let q = self.deriv.control_points().as_slice();
        let mut qdot = vec![0.0; q.len()];
        for (i, &ig) in self.inverse_gaps.iter().enumerate() {
            let s = -(r[i + p + 1] - r[i + 1]) * ig;
            for d in 0..dim {
                qdot[i * dim + d] = s * q[i * dim + d];
            }
        }
        self.deriv
            .eval_batch_jvp(ts, Some(&qdot), None, &mut out, &mut more)?;
        for (a, b) in tangent.iter_mut().zip(&more) {
            *a += b;
        }
        Ok(tangent)
    }

    /// Adds `Σ_i g_i · ∂C'(t_i)/∂τ_k` into `knot_cotangent[k]` for the interior knots `k`.
    pub(super) fn vjp(&self, ts: &[f64], g: &[f64], knot_cotangent: &mut [f64]) -> Result<()> {
        let (p, dim) = (self.degree, self.deriv.dim());
        let q = self.deriv.control_points().as_slice();
        let mut inner = vec![0.0; knot_cotangent.len() - 2];
        self.deriv.eval_batch_knot_vjp(ts, g, &mut inner)?;
        let mut qbar = vec![0.0; q.len()];
        self.deriv.eval_batch_vjp(ts, g, Some(&mut qbar), None)?;
        let mut add = vec![0.0; knot_cotangent.len()];
        for (k, v) in inner.iter().enumerate() {
            add[k + 1] += v;
        }
        for (i, &ig) in self.inverse_gaps.iter().enumerate() {
            let row = i * dim..(i + 1) * dim;
            let c: f64 = qbar[row.clone()]
                .iter()
                .zip(&q[row])
                .map(|(a, b)| a * b)
                .sum::<f64>()
                * ig;
            add[i + p + 1] -= c;
            add[i + 1] += c;
        }
        for k in self.interior() {
            knot_cotangent[k] += add[k];
        }
        Ok(())
    }
}

/// The domain `[a, b] = [τ_p, τ_n]` and the knot-tangent split of the module's map.
struct Domain {
    p: usize,
    n: usize,
    a: f64,
    b: f64,
}

impl Domain {
    fn of(curve: &BSplineCurve) -> Self {
        let (p, n) = (curve.degree(), curve.control_points().len());
        let knots = curve.knots().as_slice();
        Domain {
            p,
            n,
            a: knots[p],
            b: knots[n],
        }
    }

    /// `(b − t)/(b − a)` and `(t − a)/(b − a)`: the affine map's weights of `τ̇_p` and `τ̇_n`.
    fn ends(&self, t: f64) -> (f64, f64) {
        let h = self.b - self.a;
        ((self.b - t) / h, (t - self.a) / h)
    }

    /// `r = τ̇ − ℓ(τ)` on the interior knots, zero elsewhere.
    fn residual(&self, knots: &[f64], tangent: &[f64]) -> Vec<f64> {
        let (da, db) = (tangent[self.p], tangent[self.n]);
        let mut r = vec![0.0; knots.len()];
        for k in self.p + 1..self.n {
            let (wa, wb) = self.ends(knots[k]);
            r[k] = tangent[k] - (da * wa + db * wb);
        }
        r
    }

    /// The transpose of [`Domain::residual`] applied in place to an interior cotangent: the
    /// ends receive `−Σ_k r̄_k (b − τ_k)/(b − a)` and `−Σ_k r̄_k (τ_k − a)/(b − a)`.
    fn fold(&self, knots: &[f64], cotangent: &mut [f64]) {
        let (mut ga, mut gb) = (0.0, 0.0);
        for k in self.p + 1..self.n {
            let (wa, wb) = self.ends(knots[k]);
            ga -= cotangent[k] * wa;
            gb -= cotangent[k] * wb;
        }
        cotangent[self.p] += ga;
        cotangent[self.n] += gb;
    }
}

fn check_knot_tangent(expected: usize, tangent: &[f64]) -> Result<()> {
    check_input("knot tangent (one a knot)", expected, Some(tangent))
}

fn norm(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

impl ArcLengthGradient {
    /// As [`ArcLengthGradient::new`], with the gradient in the knots too
    /// ([`ArcLengthGradient::knot_gradient`]; `docs/theory/derivatives.md`, "Arc length and
    /// closest points"): with the domain ends fixed, `∂L/∂τ_k = Σ_nodes weight · T(t) ·
    /// ∂C'(t)/∂τ_k` on the quadrature's nodes, plus `(|C'(ξ⁻)| − |C'(ξ⁺)|)/μ` where `τ_k = ξ` is
    /// a knot of multiplicity `μ ≥ p` at which `C'` jumps; the ends by the length's invariance
    /// under an affine map of the knots, `∂L/∂τ_p = −Σ_k ∂L/∂τ_k (b − τ_k)/(b − a)` and
    /// `∂L/∂τ_n = −Σ_k ∂L/∂τ_k (τ_k − a)/(b − a)` (the `p` knots outside each end move with
    /// it: their entries are zero). Degree 0 has length 0 and a zero gradient.
    ///
    /// ```
    /// use lekalo::derivatives::ArcLengthGradient;
    /// use lekalo::{BSplineCurve, Points};
    /// // a polyline's length does not depend on its knots
    /// let c = BSplineCurve::new(1, vec![0.0, 0.0, 0.3, 1.0, 1.0], Points::from_2d(&[[0.0, 0.0], [3.0, 4.0], [3.0, 0.0]])?)?;
    /// let g = ArcLengthGradient::with_knots(&c)?;
    /// assert!((g.length() - 9.0).abs() < 1e-13);
    /// assert!(g.knot_gradient().unwrap().iter().all(|v| v.abs() < 1e-12));
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// As [`ArcLengthGradient::new`]; [`Error::InvalidArgument`] for a knot of multiplicity
    /// `p + 1` inside the domain (the curve jumps there).
    pub fn with_knots(curve: &BSplineCurve) -> Result<Self> {
        let (mut g, nodes, cot) = Self::build(curve, true)?;
        let knots = curve.knots().as_slice();
        let mut kg = vec![0.0; knots.len()];
        if curve.degree() > 0 {
            SpeedKnots::new(curve)?.vjp(&nodes, &cot, &mut kg)?;
            add_jumps(curve, &mut kg);
            Domain::of(curve).fold(knots, &mut kg);
        }
        g.knot_gradient = Some(kg);
        Ok(g)
    }

    /// `∂L/∂τ` (one a knot) when built by [`ArcLengthGradient::with_knots`].
    #[must_use]
    pub fn knot_gradient(&self) -> Option<&[f64]> {
        self.knot_gradient.as_deref()
    }

    fn knots_or_err(&self) -> Result<&[f64]> {
        self.knot_gradient().ok_or_else(|| Error::InvalidArgument {
            what: "knot derivative of the arc length".into(),
            reason: "this gradient was built without it; build it with \
                     ArcLengthGradient::with_knots"
                .into(),
        })
    }

    /// Forward-mode derivative in the knots: `L̇ = Σ_k ∂L/∂τ_k τ̇_k`.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] unless built by [`ArcLengthGradient::with_knots`];
    /// [`Error::LengthMismatch`] unless `knot_tangent` has one number a knot;
    /// [`Error::NonFinite`].
    pub fn knot_jvp(&self, knot_tangent: &[f64]) -> Result<f64> {
        let g = self.knots_or_err()?;
        check_knot_tangent(g.len(), knot_tangent)?;
        Ok(g.iter().zip(knot_tangent).map(|(a, b)| a * b).sum())
    }

    /// Reverse-mode derivative in the knots: `τ̄ = L̄ ∂L/∂τ`.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] unless built by [`ArcLengthGradient::with_knots`];
    /// [`Error::NonFinite`] for a cotangent that is not finite.
    pub fn knot_vjp(&self, cotangent: f64) -> Result<Vec<f64>> {
        let g = self.knots_or_err()?;
        check_finite("length cotangent", &[cotangent])?;
        Ok(g.iter().map(|v| cotangent * v).collect())
    }
}

/// `(|C'(ξ⁻)| − |C'(ξ⁺)|)/μ` into each copy of every interior knot value `ξ` of multiplicity
/// `μ ≥ p`, where `C'` may jump: the moving end points of the two pieces' integrals.
fn add_jumps(curve: &BSplineCurve, kg: &mut [f64]) {
    let (p, dim, n) = (curve.degree(), curve.dim(), curve.control_points().len());
    let (knots, ctrl) = (curve.knots().as_slice(), curve.control_points().as_slice());
    let mut basis = PointBasis::new(p);
    let (mut left, mut right) = (vec![0.0; dim], vec![0.0; dim]);
    let mut k = p + 1;
    while k < n {
        let xi = knots[k];
        let mut last = k;
        while last + 1 < n && knots[last + 1] == xi {
            last += 1;
        }
        let mu = last - k + 1;
        if mu >= p {
            let first = basis.at(knots, p, k - 1, xi);
            combine(ctrl, dim, first, basis.slopes(), &mut left);
            let first = basis.at(knots, p, last, xi);
            combine(ctrl, dim, first, basis.slopes(), &mut right);
            let jump = (norm(&left) - norm(&right)) / mu as f64;
            for v in &mut kg[k..=last] {
                *v += jump;
            }
        }
        k = last + 1;
    }
}

/// What [`ClosestParameters::knot_jvp`] and `_vjp` need beyond the control-point derivatives.
#[derive(Debug, Clone)]
pub(super) struct ClosestKnots {
    curve: BSplineCurve,
    speed: SpeedKnots,
}

impl ClosestParameters {
    /// As [`ClosestParameters::new`], with the derivatives in the knots too
    /// ([`ClosestParameters::knot_jvp`], [`ClosestParameters::knot_vjp`]).
    ///
    /// ```
    /// use lekalo::derivatives::ClosestParameters;
    /// use lekalo::{BSplineCurve, Points};
    /// // the segment from (0, 0) to (2, 0) on [0, 1]: t* = x/2 on [0, 1]; on [0, b], t* = b x/2
    /// let c = BSplineCurve::new(1, vec![0.0, 0.0, 1.0, 1.0], Points::from_2d(&[[0.0, 0.0], [2.0, 0.0]])?)?;
    /// let cp = ClosestParameters::with_knots(&c, &[0.5, 1.0])?;
    /// let dt = cp.knot_jvp(&[0.0, 0.0, 1.0, 1.0])?; // moving the end b by 1
    /// assert!((dt[0] - 0.25).abs() < 1e-15);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// As [`ClosestParameters::new`]; [`Error::Degree`] for degree 0;
    /// [`Error::InvalidArgument`] for a knot of multiplicity `p + 1` inside the domain.
    pub fn with_knots(curve: &BSplineCurve, points: &[f64]) -> Result<Self> {
        let mut cp = Self::new(curve, points)?;
        cp.knots = Some(Box::new(ClosestKnots {
            curve: curve.clone(),
            speed: SpeedKnots::new(curve)?,
        }));
        Ok(cp)
    }

    fn knot_part(&self) -> Result<&ClosestKnots> {
        self.knots.as_deref().ok_or_else(|| Error::InvalidArgument {
            what: "knot derivative of the closest parameters".into(),
            reason: "these were built without it; build them with ClosestParameters::with_knots"
                .into(),
        })
    }

    /// Forward-mode derivative in the knots (`docs/theory/derivatives.md`, "Arc length and
    /// closest points"): for a knot tangent `τ̇` (one a knot), `ṫ_i = ℓ(t*_i) − (C'·∂C/∂τ·r +
    /// (C − x_i)·∂C'/∂τ·r) / g'(t*_i)` with `ℓ` the affine map moving the ends `τ_p`, `τ_n` as
    /// `τ̇_p`, `τ̇_n` and `r = τ̇ − ℓ(τ)` on the interior knots (the `p` knots outside each end
    /// follow it: their tangents are ignored). At an end of the domain `ṫ_i` is that end's
    /// tangent; at a corner (a knot `ξ` where `C'` jumps) the mean of its copies' tangents (the
    /// closest point stays on the corner, which moves with `ξ`).
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] unless built by [`ClosestParameters::with_knots`];
    /// [`Error::LengthMismatch`] unless the tangent has one number a knot; [`Error::NonFinite`].
    pub fn knot_jvp(&self, knot_tangent: &[f64]) -> Result<Vec<f64>> {
        let part = self.knot_part()?;
        let knots = part.curve.knots().as_slice();
        check_knot_tangent(knots.len(), knot_tangent)?;
        let domain = Domain::of(&part.curve);
        let r = domain.residual(knots, knot_tangent);
        let (m, dim) = (self.params.len(), self.dim);
        let (mut at, mut dc) = (vec![0.0; m * dim], vec![0.0; m * dim]);
        part.curve
            .eval_batch_knot_jvp(&self.params, &r, &mut at, &mut dc)?;
        let dd = part.speed.jvp(&self.params, &r)?;
        let (ta, tb) = (knot_tangent[domain.p], knot_tangent[domain.n]);
        Ok((0..m)
            .map(|i| {
                if let Some((first, last)) = self.corners[i] {
                    let copies = &knot_tangent[first..=last];
                    return copies.iter().sum::<f64>() / copies.len() as f64;
                }
                let (wa, wb) = domain.ends(self.params[i]);
                let moved = ta * wa + tb * wb;
                if self.inverse[i] == 0.0 {
                    return moved;
                }
                let rows = i * dim..(i + 1) * dim;
                let gdot = dot(self.row(&self.tangent, i), &dc[rows.clone()])
                    + dot(self.row(&self.offset, i), &dd[rows]);
                moved - gdot * self.inverse[i]
            })
            .collect())
    }

    /// Reverse-mode derivative in the knots, the transpose of [`ClosestParameters::knot_jvp`]:
    /// for a cotangent `t̄` (one a point), `τ̄` (one a knot; zero on the `p` knots outside each
    /// end).
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] unless built by [`ClosestParameters::with_knots`];
    /// [`Error::LengthMismatch`] unless `cotangent` has one number a point; [`Error::NonFinite`].
    pub fn knot_vjp(&self, cotangent: &[f64]) -> Result<Vec<f64>> {
        let part = self.knot_part()?;
        let (m, dim) = (self.params.len(), self.dim);
        check_len("parameter cotangent (one a point)", m, cotangent.len())?;
        check_finite("parameter cotangent", cotangent)?;
        let knots = part.curve.knots().as_slice();
        let domain = Domain::of(&part.curve);
        let (mut gc, mut gd) = (vec![0.0; m * dim], vec![0.0; m * dim]);
        let (mut ga, mut gb) = (0.0, 0.0);
        for (i, &g) in cotangent.iter().enumerate() {
            if self.corners[i].is_some() {
                continue;
            }
            let (wa, wb) = domain.ends(self.params[i]);
            ga += g * wa;
            gb += g * wb;
            let s = -g * self.inverse[i];
            let rows = i * dim..(i + 1) * dim;
            for ((c, d), (e, o)) in gc[rows.clone()].iter_mut().zip(&mut gd[rows]).zip(
                self.row(&self.tangent, i)
                    .iter()
                    .zip(self.row(&self.offset, i)),
            ) {
                *c = s * e;
                *d = s * o;
            }
        }
        let mut out = vec![0.0; knots.len()];
        part.curve
            .eval_batch_knot_vjp(&self.params, &gc, &mut out)?;
        part.speed.vjp(&self.params, &gd, &mut out)?;
        domain.fold(knots, &mut out);
        out[domain.p] += ga;
        out[domain.n] += gb;
        for (corner, &g) in self.corners.iter().zip(cotangent) {
            if let Some((first, last)) = *corner {
                let share = g / (last + 1 - first) as f64;
                for v in &mut out[first..=last] {
                    *v += share;
                }
            }
        }
        Ok(out)
    }
}
