//! Derivatives of interpolation and of the least-squares fit with respect to the knots
//! (`docs/theory/derivatives.md`, "Knots of the fits"). Both fits solve normal equations whose
//! matrix depends on the knots through the basis matrix `B(τ)`, `B[k][i] = N_{i,p,τ}(ū_k)`:
//!
//! - interpolation, `A P = Q` with `A = B` square: `A Ṗ + Ȧ P = 0`, so
//!   `Ṗ = −A⁻¹ (Ȧ P)` (JVP) and `τ̄ = −Jᵀ_P (A⁻ᵀ P̄)` (VJP);
//! - least squares, `BᵀW (B P − Q) = 0`: `G Ṗ = −BᵀW (Ḃ P) − Ḃᵀ W r` with `G = BᵀWB` and the
//!   residual `r = B P − Q`, so `Ṗ = −G⁻¹ (BᵀW Ḃ P + Ḃᵀ W r)` (JVP) and, with `z = G⁻¹ P̄`,
//!   `τ̄ = −Jᵀ_P (W B z) − Jᵀ_z (W r)` (VJP).
//!
//! `Ḃ c = Σ_k τ̇_k ∂(B c)/∂τ_k` is the knot JVP of evaluating the spline of coefficients `c` at
//! the parameters, and `Jᵀ_c ḡ` its knot VJP for the cotangent `ḡ`
//! ([`crate::BSplineCurve::eval_batch_knot_jvp`] and `_vjp`); `Ḃᵀ v` is the same derivative
//! transposed in the coefficients ([`knot_jvp_transposed`]). The solves use the fits' own
//! banded factorisations ([`InterpolationMap`], [`LeastSquaresMap`]), forward and adjoint. The
//! knots' conventions are the evaluation's: only the interior knots move, one-sided at a
//! multiple knot. The data, parameters and weights are constants here.

use super::checks::{check_input, check_len};
use super::fits::LeastSquaresFit;
use super::interpolant::Interpolant;
use super::knots::knot_jvp_transposed;
use crate::curve::BSplineCurve;
use crate::error::{check_finite, Result};
use crate::points::Points;

impl Interpolant {
    /// The control-point tangent `Ṗ = −A⁻¹ (Ȧ P)` (`m × dim`) for a knot tangent `τ̇` (one
    /// number a knot; the `p + 1` first and last are ignored), `Ȧ P` the knot JVP of the
    /// interpolant at the parameters (module docs).
    ///
    /// ```
    /// use lekalo::derivatives::Interpolant;
    /// let knots = [0.0, 0.0, 0.0, 0.0, 0.45, 1.0, 1.0, 1.0, 1.0];
    /// let params = [0.0, 0.2, 0.5, 0.8, 1.0];
    /// // data on the line y = x: the interpolant is that line on any knots, its control points
    /// // the Greville abscissae (τ_{i+1} + τ_{i+2} + τ_{i+3}) / 3, so moving τ_4 moves the three
    /// // inner ones by 1/3 and the end ones not at all
    /// let points = [0.0, 0.2, 0.5, 0.8, 1.0];
    /// let it = Interpolant::new(3, &knots, &params, &points, 1)?;
    /// let dp = it.knot_jvp(&[0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0])?;
    /// let third = 1.0 / 3.0;
    /// for (d, want) in dp.iter().zip([0.0, third, third, third, 0.0]) {
    ///     assert!((d - want).abs() < 1e-14, "{d} vs {want}");
    /// }
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`crate::Error::LengthMismatch`] unless the tangent has one number a knot;
    /// [`crate::Error::NonFinite`] for a non-finite one.
    pub fn knot_jvp(&self, knot_tangent: &[f64]) -> Result<Vec<f64>> {
        let (m, dim) = (self.params.len(), self.curve.dim());
        let n_knots = self.curve.knots().len();
        check_input("knot tangent (one a knot)", n_knots, Some(knot_tangent))?;
        let (mut values, mut rhs) = (vec![0.0; m * dim], vec![0.0; m * dim]);
        self.curve
            .eval_batch_knot_jvp(&self.params, knot_tangent, &mut values, &mut rhs)?;
        let mut dp = self.map.jvp(&rhs, dim)?;
        negate(&mut dp);
        Ok(dp)
    }

    /// The knot cotangent `τ̄ = −Jᵀ_P (A⁻ᵀ P̄)` (one a knot, zero for the `p + 1` first and
    /// last) for a control-point cotangent `P̄` (`m × dim`): the transpose of
    /// [`Interpolant::knot_jvp`].
    ///
    /// # Errors
    /// [`crate::Error::LengthMismatch`] for a cotangent of the wrong length;
    /// [`crate::Error::NonFinite`] for a non-finite one.
    pub fn knot_vjp(&self, control_cotangent: &[f64]) -> Result<Vec<f64>> {
        let dim = self.curve.dim();
        let data = self.map.vjp(control_cotangent, dim)?;
        let mut out = vec![0.0; self.curve.knots().len()];
        self.curve
            .eval_batch_knot_vjp(&self.params, &data, &mut out)?;
        negate(&mut out);
        Ok(out)
    }
}

impl LeastSquaresFit<'_> {
    /// The fit's control points `P` (`n × dim`, bit for bit
    /// [`LeastSquaresFit::control_points`]) and their tangent
    /// `Ṗ = −G⁻¹ (BᵀW Ḃ P + Ḃᵀ W r)` for a knot tangent `τ̇` (one number a knot; the `p + 1`
    /// first and last are ignored), `r = B P − Q` the residual (module docs). One banded QR.
    ///
    /// # Errors
    /// As [`LeastSquaresFit::control_points_and_map`];
    /// [`crate::Error::LengthMismatch`] unless the tangent has one number a knot;
    /// [`crate::Error::NonFinite`] for a non-finite one.
    pub fn knot_jvp(&self, knot_tangent: &[f64]) -> Result<(Vec<f64>, Vec<f64>)> {
        check_input(
            "knot tangent (one a knot)",
            self.knots.len(),
            Some(knot_tangent),
        )?;
        let (control, map) = self.control_points_and_map()?;
        let dim = self.data.points().dim();
        let params = self.data.params();
        let curve = self.curve(control.clone(), dim)?;
        let m = params.len() * dim;
        let (mut values, mut moved) = (vec![0.0; m], vec![0.0; m]);
        curve.eval_batch_knot_jvp(params, knot_tangent, &mut values, &mut moved)?;
        let weighted_residual = self.weighted_residual(&values, map.weights());
        let mut rhs = map.transpose_weighted(&moved, dim);
        let transposed = knot_jvp_transposed(
            &self.knots,
            self.degree,
            params,
            knot_tangent,
            &weighted_residual,
            dim,
        )?;
        for (a, b) in rhs.iter_mut().zip(&transposed) {
            *a += b;
        }
        map.solve_normal(&mut rhs, dim);
        negate(&mut rhs);
        Ok((control, rhs))
    }

    /// The knot cotangent `τ̄ = −Jᵀ_P (W B z) − Jᵀ_z (W r)`, `z = G⁻¹ P̄`, for a control-point
    /// cotangent `P̄` (`n × dim`): the transpose of [`LeastSquaresFit::knot_jvp`] (one a knot,
    /// zero for the `p + 1` first and last).
    ///
    /// # Errors
    /// As [`LeastSquaresFit::control_points_and_map`];
    /// [`crate::Error::LengthMismatch`] for a cotangent of the wrong length;
    /// [`crate::Error::NonFinite`] for a non-finite one.
    pub fn knot_vjp(&self, control_cotangent: &[f64]) -> Result<Vec<f64>> {
        let dim = self.data.points().dim();
        check_len(
            "control-point cotangent (points × dimension)",
            self.n_ctrl().saturating_mul(dim),
            control_cotangent.len(),
        )?;
        check_finite("control-point cotangent", control_cotangent)?;
        let (control, map) = self.control_points_and_map()?;
        let params = self.data.params();
        let curve = self.curve(control, dim)?;
        let mut values = vec![0.0; params.len() * dim];
        curve.eval_batch(params, &mut values)?;
        let weighted_residual = self.weighted_residual(&values, map.weights());
        let mut z = control_cotangent.to_vec();
        map.solve_normal(&mut z, dim);
        let u = map.weighted(&z, dim);
        let mut out = vec![0.0; self.knots.len()];
        curve.eval_batch_knot_vjp(params, &u, &mut out)?;
        let mut second = vec![0.0; self.knots.len()];
        self.curve(z, dim)?
            .eval_batch_knot_vjp(params, &weighted_residual, &mut second)?;
        for (a, b) in out.iter_mut().zip(&second) {
            *a = -(*a + b);
        }
        Ok(out)
    }

    /// The spline of coefficients `c` (`n × dim`) on the fit's knots.
    fn curve(&self, c: Vec<f64>, dim: usize) -> Result<BSplineCurve> {
        BSplineCurve::from_knot_vector(self.degree, self.knots.clone(), Points::from_flat(dim, c)?)
    }

    /// `W r = W (B P − Q)` from the fitted values `B P` (`m × dim`) and the map's weights.
    fn weighted_residual(&self, values: &[f64], weights: &[f64]) -> Vec<f64> {
        let dim = self.data.points().dim();
        let q = self.data.points().as_slice();
        let mut out = vec![0.0; values.len()];
        for (k, ((o, v), y)) in out
            .chunks_exact_mut(dim)
            .zip(values.chunks_exact(dim))
            .zip(q.chunks_exact(dim))
            .enumerate()
        {
            for ((oc, vc), yc) in o.iter_mut().zip(v).zip(y) {
                *oc = weights[k] * (vc - yc);
            }
        }
        out
    }
}

fn negate(v: &mut [f64]) {
    for x in v {
        *x = -*x;
    }
}
