//! Interpolation as a differentiable function of the data values `Q` and of the parameters
//! `x`: the control points solve `A(x) P = Q`, `A[r][i] = N_{i,p}(x_r)`, so differentiating
//! `Σ_i N_{i,p}(x_r) P_i = Q_r` gives `A Ṗ + C'(x_r) ẋ_r = Q̇_r`, that is
//!
//! `Ṗ = A⁻¹ (Q̇ − diag(ẋ) C'(x))` (JVP), and its transpose
//! `Q̄ = A⁻ᵀ P̄`, `x̄_r = −C'(x_r) · Q̄_r` (VJP),
//!
//! with `C` the interpolant (`docs/theory/derivatives.md`, "Interpolation"). The solves are
//! [`InterpolationMap`]'s, with the one banded factorisation of `A`; `C'(x_r)` comes from
//! [`BSplineCurve::eval_batch_jvp`] (the right-hand derivative at an interior knot where `C'`
//! jumps).

use super::checks::check_input;
use super::interpolation::InterpolationMap;
use crate::curve::BSplineCurve;
use crate::error::{Error, Result};
use crate::knots::KnotVector;
use crate::points::Points;

/// The interpolant of degree `p` on given knots through `m` points at `m` parameters, with the
/// factorisation of its collocation matrix kept for its derivatives with respect to the data
/// and the parameters (module docs).
///
/// ```
/// use lekalo::derivatives::Interpolant;
/// let knots = [0.0, 0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0, 1.0];
/// let params = [0.0, 0.2, 0.5, 0.8, 1.0];
/// let points = [0.0, 1.0, 0.5, 2.0, 1.5];
/// let it = Interpolant::new(3, &knots, &params, &points, 1)?;
/// // moving every data value by 1 moves every control point by 1 (partition of unity)
/// let dp = it.jvp(Some(&[1.0; 5]), None)?;
/// assert!(dp.iter().all(|x| (x - 1.0).abs() < 1e-14));
/// # Ok::<(), lekalo::Error>(())
/// ```
#[derive(Debug, Clone)]
pub struct Interpolant {
    pub(super) map: InterpolationMap,
    pub(super) curve: BSplineCurve,
    pub(super) params: Vec<f64>,
}

impl Interpolant {
    /// Interpolates `points` (`m × dim`, point-major) at the sorted `params` (`m`) with degree
    /// `degree` on `knots` (`m + degree + 1`): the control points are
    /// [`InterpolationMap::jvp`] of the points, bit for bit.
    ///
    /// # Errors
    /// As [`KnotVector::new`] and [`InterpolationMap::new`]; [`Error::LengthMismatch`] unless
    /// `points.len() == m · dim`; [`Error::Dimension`] for `dim = 0`; [`Error::NonFinite`] for a
    /// non-finite point.
    pub fn new(
        degree: usize,
        knots: &[f64],
        params: &[f64],
        points: &[f64],
        dim: usize,
    ) -> Result<Self> {
        if dim == 0 {
            return Err(Error::Dimension {
                what: "points".into(),
                expected: 1,
                got: 0,
            });
        }
        let knots = KnotVector::new(knots.to_vec())?;
        let map = InterpolationMap::new(degree, &knots, params)?;
        let control = map.jvp(points, dim)?;
        let curve =
            BSplineCurve::from_knot_vector(degree, knots, Points::from_flat(dim, control)?)?;
        Ok(Interpolant {
            map,
            curve,
            params: params.to_vec(),
        })
    }

    /// The control points `P` (`m × dim`, point-major).
    #[must_use]
    pub fn control_points(&self) -> &[f64] {
        self.curve.control_points().as_slice()
    }

    /// `C'(x_r)`, `m × dim`.
    fn slopes(&self) -> Result<Vec<f64>> {
        let len = self.control_points().len();
        let (mut values, mut slopes) = (vec![0.0; len], vec![0.0; len]);
        let ones = vec![1.0; self.params.len()];
        self.curve
            .eval_batch_jvp(&self.params, None, Some(&ones), &mut values, &mut slopes)?;
        Ok(slopes)
    }

    /// The control-point tangent `Ṗ = A⁻¹ (Q̇ − diag(ẋ) C'(x))` for a data tangent `Q̇`
    /// (`m × dim`) and a parameter tangent `ẋ` (`m`), `None` being zero.
    ///
    /// # Errors
    /// [`Error::LengthMismatch`] for a tangent of the wrong length; [`Error::NonFinite`] for a
    /// non-finite tangent.
    pub fn jvp(
        &self,
        data_tangent: Option<&[f64]>,
        parameter_tangent: Option<&[f64]>,
    ) -> Result<Vec<f64>> {
        let (m, dim) = (self.params.len(), self.curve.dim());
        check_input("data tangent (as the points)", m * dim, data_tangent)?;
        check_input("parameter tangent (one a parameter)", m, parameter_tangent)?;
        let mut rhs = data_tangent.map_or_else(|| vec![0.0; m * dim], <[f64]>::to_vec);
        if let Some(dx) = parameter_tangent {
            let slopes = self.slopes()?;
            for ((row, s), d) in rhs
                .chunks_exact_mut(dim)
                .zip(slopes.chunks_exact(dim))
                .zip(dx)
            {
                for (r, si) in row.iter_mut().zip(s) {
                    *r -= si * d;
                }
            }
        }
        self.map.jvp(&rhs, dim)
    }

    /// The cotangents of the data `Q̄ = A⁻ᵀ P̄` (`m × dim`) and of the parameters
    /// `x̄_r = −C'(x_r) · Q̄_r` (`m`) for a control-point cotangent `P̄` (`m × dim`); the second
    /// only when `with_parameters`.
    ///
    /// # Errors
    /// [`Error::LengthMismatch`] for a cotangent of the wrong length; [`Error::NonFinite`] for a
    /// non-finite one.
    pub fn vjp(
        &self,
        control_cotangent: &[f64],
        with_parameters: bool,
    ) -> Result<(Vec<f64>, Option<Vec<f64>>)> {
        let dim = self.curve.dim();
        let data = self.map.vjp(control_cotangent, dim)?;
        if !with_parameters {
            return Ok((data, None));
        }
        let slopes = self.slopes()?;
        let params = data
            .chunks_exact(dim)
            .zip(slopes.chunks_exact(dim))
            .map(|(q, s)| -q.iter().zip(s).map(|(a, b)| a * b).sum::<f64>())
            .collect();
        Ok((data, Some(params)))
    }
}

#[cfg(test)]
mod tests {
    use super::Interpolant;

    /// A cubic interpolant on 9 points in 2-D.
    fn sample() -> (Vec<f64>, Vec<f64>, Vec<f64>) {
        let params: Vec<f64> = [0.0, 0.1, 0.25, 0.4, 0.5, 0.62, 0.75, 0.9, 1.0].to_vec();
        let mut knots = vec![0.0; 4];
        for j in 1..params.len() - 3 {
            knots.push(params[j..j + 3].iter().sum::<f64>() / 3.0);
        }
        knots.extend([1.0; 4]);
        let points = params
            .iter()
            .flat_map(|x| [(3.0 * x).sin(), x * x - 0.5])
            .collect();
        (knots, params, points)
    }

    /// The JVP against central differences of the control points, in the data and in the
    /// parameters, and the VJP its transpose.
    #[test]
    fn derivatives_match_differences_and_transpose() {
        let (knots, params, points) = sample();
        let it = Interpolant::new(3, &knots, &params, &points, 2).unwrap();
        let dq: Vec<f64> = (0..points.len()).map(|i| (i as f64).cos()).collect();
        let mut dx: Vec<f64> = (0..params.len()).map(|i| (i as f64 * 0.3).sin()).collect();
        (dx[0], dx[8]) = (0.0, 0.0); // the end parameters sit on the end knots
        let jvp = it.jvp(Some(&dq), Some(&dx)).unwrap();
        let h = 1e-6;
        let at = |s: f64| {
            let q: Vec<f64> = points.iter().zip(&dq).map(|(a, b)| a + s * b).collect();
            let x: Vec<f64> = params.iter().zip(&dx).map(|(a, b)| a + s * b).collect();
            Interpolant::new(3, &knots, &x, &q, 2)
                .unwrap()
                .control_points()
                .to_vec()
        };
        let (plus, minus) = (at(h), at(-h));
        for (j, d) in jvp.iter().enumerate() {
            let fd = (plus[j] - minus[j]) / (2.0 * h);
            assert!((d - fd).abs() < 1e-7 * (1.0 + fd.abs()), "{j}: {d} vs {fd}");
        }
        let g: Vec<f64> = (0..points.len()).map(|i| (i as f64 * 0.7).sin()).collect();
        let (gq, gx) = it.vjp(&g, true).unwrap();
        let gx = gx.unwrap();
        let lhs: f64 = g.iter().zip(&jvp).map(|(a, b)| a * b).sum();
        let rhs: f64 = gq.iter().zip(&dq).map(|(a, b)| a * b).sum::<f64>()
            + gx.iter().zip(&dx).map(|(a, b)| a * b).sum::<f64>();
        assert!(
            (lhs - rhs).abs() < 1e-12 * (1.0 + lhs.abs()),
            "{lhs} vs {rhs}"
        );
    }

    /// Wrong lengths, non-finite data and parameters violating Schoenberg–Whitney are errors.
    #[test]
    fn bad_input_is_refused() {
        let (knots, params, points) = sample();
        assert!(Interpolant::new(3, &knots, &params, &points[1..], 2).is_err());
        assert!(Interpolant::new(3, &knots, &params, &points, 0).is_err());
        let mut q = points.clone();
        q[3] = f64::NAN;
        assert!(Interpolant::new(3, &knots, &params, &q, 2).is_err());
        let mut x = params.clone();
        x[4] = 0.05;
        assert!(Interpolant::new(3, &knots, &x, &points, 2).is_err());
        let it = Interpolant::new(3, &knots, &params, &points, 2).unwrap();
        assert!(it.jvp(Some(&points[1..]), None).is_err());
        assert!(it.jvp(None, Some(&[f64::NAN; 9])).is_err());
        assert!(it.vjp(&points[2..], false).is_err());
    }
}
