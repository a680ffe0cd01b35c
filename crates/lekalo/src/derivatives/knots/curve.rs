//! The knot derivatives of B-spline curve evaluation: [`KnotWeights`] applied to the control
//! points (`docs/theory/derivatives.md`, "Knots").

use super::KnotWeights;
use crate::curve::BSplineCurve;
use crate::derivatives::checks::{check_input, check_len};
use crate::derivatives::curve::{combine, PointBasis};
use crate::error::{check_finite, Result};
use crate::knots::KnotVector;

impl BSplineCurve {
    /// Forward-mode derivative (JVP) of [`BSplineCurve::eval_batch`] with respect to the
    /// knots: `out` receives `C(t_i)` (bit-for-bit `eval_batch`) and `tangent_out`
    ///
    /// `Ċ_i = Σ_k τ̇_k ∂C(t_i)/∂τ_k`, `∂C(t)/∂τ_k = − Σ_{j=k−p}^{k} (P_j − P_{j−1}) / (τ_{j+p} − τ_j) · N_{j,p,τ*}(t)`
    ///
    /// for a knot tangent `τ̇` (`knot_tangent`, one number a knot), `τ*` the knots with `τ_k`
    /// inserted once more: the derivative of knot insertion's identity (Boehm, P&T eq. 5.10;
    /// Lyche & Mørken, *Spline Methods*; `docs/theory/derivatives.md`, "Knots"). Only the
    /// interior knots `τ_{p+1} … τ_{n−1}` count: the tangents of the `p + 1` first and last
    /// knots, which bound the domain, are ignored (held fixed). At a knot of multiplicity
    /// `μ > 1` the derivative is one-sided (the first copy's decreasing it, the last copy's
    /// increasing it; the copies' sum moves them together). O(m·p·(p² + p·dim)).
    ///
    /// ```
    /// use lekalo::{BSplineCurve, Points};
    /// // degree 1: moving the interior knot moves the corner P_1 of the polyline sideways
    /// let ctrl = Points::from_flat(1, vec![0.0, 1.0, 0.0])?;
    /// let c = BSplineCurve::new(1, vec![0.0, 0.0, 0.5, 1.0, 1.0], ctrl)?;
    /// let (mut out, mut tan) = (vec![0.0; 1], vec![0.0; 1]);
    /// c.eval_batch_knot_jvp(&[0.25], &[0.0, 0.0, 1.0, 0.0, 0.0], &mut out, &mut tan)?;
    /// // C(0.25) = 0.25 / τ_2, so ∂C/∂τ_2 = −0.25 / τ_2² = −1
    /// assert_eq!((out[0], tan[0]), (0.5, -1.0));
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`crate::Error::LengthMismatch`] for a buffer of the wrong length (`out` and
    /// `tangent_out`: `ts.len() · dim`; `knot_tangent`: as the knots);
    /// [`crate::Error::NonFinite`] for a non-finite tangent;
    /// [`crate::Error::ParameterOutOfDomain`] at the first parameter outside the domain.
    pub fn eval_batch_knot_jvp(
        &self,
        ts: &[f64],
        knot_tangent: &[f64],
        out: &mut [f64],
        tangent_out: &mut [f64],
    ) -> Result<()> {
        let (p, dim) = (self.degree(), self.dim());
        let (knots, ctrl) = (self.knots().as_slice(), self.control_points().as_slice());
        let n = self.control_points().len();
        let m = ts.len().saturating_mul(dim);
        check_len("output buffer (parameters × dimension)", m, out.len())?;
        check_len(
            "tangent output buffer (parameters × dimension)",
            m,
            tangent_out.len(),
        )?;
        check_input("knot tangent (one a knot)", knots.len(), Some(knot_tangent))?;
        let mut cursor = self.knots().span_cursor(p);
        let mut basis = PointBasis::new(p);
        let mut weights = KnotWeights::new(p);
        let point = move |j: usize| &ctrl[j * dim..(j + 1) * dim];
        let points = out
            .chunks_exact_mut(dim)
            .zip(tangent_out.chunks_exact_mut(dim));
        for (&t, (o, d)) in ts.iter().zip(points) {
            let span = cursor.find(t)?;
            let first = basis.at(knots, p, span, t);
            combine(ctrl, dim, first, basis.values(), o);
            d.fill(0.0);
            weights.at(knots, n, span, t);
            for k in weights.knots() {
                if knot_tangent[k] != 0.0 {
                    weights.add_derivative(k, knot_tangent[k], point, d);
                }
            }
        }
        Ok(())
    }

    /// Reverse-mode derivative (VJP) of [`BSplineCurve::eval_batch`] with respect to the knots:
    /// for a cotangent `ḡ` (`ts.len() × dim`, point-major), `τ̄_k = Σ_i ḡ_i · ∂C(t_i)/∂τ_k`
    /// into `knot_cotangent` (one a knot, overwritten), with the derivative of
    /// [`BSplineCurve::eval_batch_knot_jvp`] (`docs/theory/derivatives.md`, "Knots"); its
    /// transpose: `⟨ḡ, J τ̇⟩ = ⟨Jᵀ ḡ, τ̇⟩`. The `p + 1` first and last knots get zero.
    /// O(m·p·(p² + p·dim)).
    ///
    /// ```
    /// use lekalo::{BSplineCurve, Points};
    /// let ctrl = Points::from_flat(1, vec![0.0, 1.0, 0.0])?;
    /// let c = BSplineCurve::new(1, vec![0.0, 0.0, 0.5, 1.0, 1.0], ctrl)?;
    /// let mut grad = vec![0.0; 5];
    /// c.eval_batch_knot_vjp(&[0.25, 0.75], &[1.0, 1.0], &mut grad)?;
    /// // the corner moving right raises the curve at 0.75 as much as it lowers it at 0.25
    /// assert_eq!(grad, vec![0.0, 0.0, 0.0, 0.0, 0.0]);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`crate::Error::LengthMismatch`] for a buffer of the wrong length;
    /// [`crate::Error::NonFinite`] for a non-finite cotangent;
    /// [`crate::Error::ParameterOutOfDomain`] at the first parameter outside the domain.
    pub fn eval_batch_knot_vjp(
        &self,
        ts: &[f64],
        cotangent: &[f64],
        knot_cotangent: &mut [f64],
    ) -> Result<()> {
        let (p, dim) = (self.degree(), self.dim());
        let (knots, ctrl) = (self.knots().as_slice(), self.control_points().as_slice());
        let n = self.control_points().len();
        check_len(
            "cotangent (parameters × dimension)",
            ts.len().saturating_mul(dim),
            cotangent.len(),
        )?;
        check_finite("cotangent", cotangent)?;
        check_len(
            "knot cotangent buffer (one a knot)",
            knots.len(),
            knot_cotangent.len(),
        )?;
        knot_cotangent.fill(0.0);
        let mut cursor = self.knots().span_cursor(p);
        let mut weights = KnotWeights::new(p);
        let point = move |j: usize| &ctrl[j * dim..(j + 1) * dim];
        for (&t, g) in ts.iter().zip(cotangent.chunks_exact(dim)) {
            let span = cursor.find(t)?;
            weights.at(knots, n, span, t);
            for k in weights.knots() {
                knot_cotangent[k] += weights.cotangent(k, g, point);
            }
        }
        Ok(())
    }
}

/// The transpose, in the coefficients, of the knot JVP of evaluation at `ts`: for a knot
/// tangent `τ̇` the knot JVP is linear in the coefficients, `Ċ(t_i) = Σ_j Ḃ_{ij} c_j` with
/// `Ḃ = Σ_k τ̇_k ∂B/∂τ_k` (the derivative of the basis matrix `B_{ij} = N_{j,p}(t_i)`), and this
/// returns `Ḃᵀ v` (`n × dim`, point-major) for `v` of `ts.len() × dim`. The weights are those of
/// [`KnotWeights`]: `∂C(t)/∂τ_k = Σ_j w_{k,j} (c_j − c_{j−1})`, so `w_{k,j}` goes to `c_j`
/// and `−w_{k,j}` to `c_{j−1}` (`docs/theory/derivatives.md`, "Knots of the fits"). The
/// conventions of [`BSplineCurve::eval_batch_knot_jvp`] (interior knots only, one-sided at
/// multiple knots). O(m·p·(p² + p·dim)).
///
/// # Errors
/// [`crate::Error::ParameterOutOfDomain`] at the first parameter outside the domain.
pub(in crate::derivatives) fn knot_jvp_transposed(
    knots: &KnotVector,
    degree: usize,
    ts: &[f64],
    knot_tangent: &[f64],
    v: &[f64],
    dim: usize,
) -> Result<Vec<f64>> {
    let t = knots.as_slice();
    let n = t.len() - degree - 1;
    let w = degree + 2;
    let mut out = vec![0.0; n * dim];
    let mut cursor = knots.span_cursor(degree);
    let mut weights = KnotWeights::new(degree);
    for (&x, vi) in ts.iter().zip(v.chunks_exact(dim)) {
        let span = cursor.find(x)?;
        weights.at(t, n, span, x);
        for k in weights.knots() {
            let tk = knot_tangent[k];
            if tk == 0.0 {
                continue;
            }
            let row =
                &weights.weights[(k - weights.first_knot) * w..(k - weights.first_knot + 1) * w];
            for (jj, &wk) in row.iter().enumerate() {
                if wk == 0.0 {
                    continue;
                }
                let j = weights.first_diff + jj; // j ≥ k − p ≥ 1
                let s = tk * wk;
                for (c, &vc) in vi.iter().enumerate() {
                    out[j * dim + c] += s * vc;
                    out[(j - 1) * dim + c] -= s * vc;
                }
            }
        }
    }
    Ok(out)
}
