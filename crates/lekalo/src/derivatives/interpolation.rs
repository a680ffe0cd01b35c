//! Derivatives of interpolation at fixed parameters and knots with respect to the data:
//! the control points solve the collocation system `A P = Q`, `A[r][i] = N_{i,p}(t̄_r)`, so
//! `Ṗ = A⁻¹ Q̇` (JVP) and `Q̄ = A⁻ᵀ P̄` (VJP, the adjoint solve), both with the one banded
//! factorisation of `A` that interpolation uses (`docs/theory/derivatives.md`,
//! "Interpolation").

use super::checks::check_len;
use crate::error::{Error, Result};
use crate::interpolate::collocation::{factor_collocation, Factors};
use crate::knots::{check_parameters, KnotVector};
use crate::numeric::linalg::BandedCrout;
use crate::What;

/// The linear map from data values to control points of interpolation with a given degree,
/// knot vector and parameters (no end derivatives: as many parameters as control points),
/// factored once: [`InterpolationMap::jvp`] applies `A⁻¹`, [`InterpolationMap::vjp`] its
/// transpose `A⁻ᵀ`. Elimination without pivoting of the totally positive banded collocation
/// matrix (de Boor 1977; `docs/theory/interpolation.md`); each application costs
/// O(n·p·dim).
///
/// ```
/// use lekalo::derivatives::InterpolationMap;
/// use lekalo::KnotVector;
/// let knots = KnotVector::new(vec![0.0, 0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0, 1.0])?;
/// let map = InterpolationMap::new(3, &knots, &[0.0, 0.2, 0.5, 0.8, 1.0])?;
/// // the cotangent of the first control point lands on the first data point only (C(0) = P_0)
/// let g = map.vjp(&[1.0, 0.0, 0.0, 0.0, 0.0], 1)?;
/// assert!((g[0] - 1.0).abs() < 1e-15 && g[1..].iter().all(|x| x.abs() < 1e-15));
/// # Ok::<(), lekalo::Error>(())
/// ```
#[derive(Debug, Clone)]
pub struct InterpolationMap {
    lu: BandedCrout,
    n: usize,
}

impl InterpolationMap {
    /// Factors the collocation matrix of `degree` on `knots` at the sorted `params` (one a
    /// control point: `knots.len() == params.len() + degree + 1`).
    ///
    /// # Errors
    /// As [`KnotVector::validate_for`] and [`check_parameters`];
    /// [`Error::ParameterOutOfDomain`] for a parameter outside the knots' domain;
    /// [`Error::SingularSystem`] when the parameters violate the Schoenberg–Whitney condition
    /// (a parameter outside the support of its basis function).
    pub fn new(degree: usize, knots: &KnotVector, params: &[f64]) -> Result<Self> {
        check_parameters(params)?;
        knots.validate_for(degree, params.len())?;
        for &t in [params[0], params[params.len() - 1]].iter() {
            knots.find_span(degree, t)?;
        }
        let lu = factor_collocation(knots, degree, params, Factors::Keep)?;
        Ok(InterpolationMap {
            lu,
            n: params.len(),
        })
    }

    /// Forward-mode derivative: the control-point tangent `Ṗ = A⁻¹ Q̇` for a data tangent `Q̇`
    /// (`n × dim`, point-major). Interpolation is linear in the data, so this is also the
    /// interpolant of `Q̇` itself.
    ///
    /// # Errors
    /// [`Error::LengthMismatch`] unless `data_tangent.len() == n · dim`;
    /// [`Error::NonFinite`] for a non-finite value.
    pub fn jvp(&self, data_tangent: &[f64], dim: usize) -> Result<Vec<f64>> {
        self.check(data_tangent, dim, "data tangent (points × dimension)")?;
        let mut x = data_tangent.to_vec();
        self.lu.solve(&mut x, dim);
        Ok(x)
    }

    /// Reverse-mode derivative: the data cotangent `Q̄ = A⁻ᵀ P̄` for a control-point cotangent
    /// `P̄` (`n × dim`, point-major): one transposed solve a coordinate with the kept factors.
    ///
    /// # Errors
    /// [`Error::LengthMismatch`] unless `control_cotangent.len() == n · dim`;
    /// [`Error::NonFinite`] for a non-finite value.
    pub fn vjp(&self, control_cotangent: &[f64], dim: usize) -> Result<Vec<f64>> {
        self.check(
            control_cotangent,
            dim,
            "control-point cotangent (points × dimension)",
        )?;
        let mut out = vec![0.0; control_cotangent.len()];
        let mut column = vec![0.0; self.n];
        for d in 0..dim {
            for (c, row) in column.iter_mut().zip(control_cotangent.chunks_exact(dim)) {
                *c = row[d];
            }
            self.lu.solve_transposed(&mut column);
            for (c, row) in column.iter().zip(out.chunks_exact_mut(dim)) {
                row[d] = *c;
            }
        }
        Ok(out)
    }

    fn check(&self, v: &[f64], dim: usize, what: impl Into<What>) -> Result<()> {
        let what: What = what.into();
        if dim == 0 {
            return Err(Error::Dimension {
                what,
                expected: 0,
                got: 0,
            });
        }
        check_len(what, self.n.saturating_mul(dim), v.len())?;
        crate::error::check_finite(what, v)
    }
}

#[cfg(test)]
mod tests {
    use super::InterpolationMap;
    use crate::curve::bspline::BSplineCurve;
    use crate::error::Error;
    use crate::knots::KnotVector;
    use crate::oracle::proptest_config;
    use crate::points::Points;
    use proptest::prelude::*;

    /// Averaged knots (de Boor) for sorted parameters: Schoenberg–Whitney holds.
    fn averaged(p: usize, ts: &[f64]) -> Vec<f64> {
        let n = ts.len();
        let mut k = vec![ts[0]; p + 1];
        for j in 1..n - p {
            #[allow(clippy::cast_precision_loss)]
            k.push(ts[j..j + p].iter().sum::<f64>() / p as f64);
        }
        k.extend(std::iter::repeat_n(ts[n - 1], p + 1));
        k
    }

    proptest! {
        #![proptest_config(proptest_config(128))]

        /// The JVP interpolates its tangent (so it is `A⁻¹`), and the VJP is its transpose.
        #[test]
        fn jvp_interpolates_and_vjp_is_its_transpose(
            p in 1usize..=5,
            gaps in prop::collection::vec(0.05f64..1.0, 6..14),
            dim in 1usize..=3,
            seed in prop::collection::vec(-1.0f64..1.0, 14 * 3 * 2),
        ) {
            let mut ts = vec![0.0];
            for g in &gaps {
                ts.push(ts[ts.len() - 1] + g);
            }
            let n = ts.len();
            prop_assume!(n > p);
            let kv = KnotVector::new(averaged(p, &ts)).unwrap();
            let map = InterpolationMap::new(p, &kv, &ts).unwrap();
            let (dq, g) = (&seed[..n * dim], &seed[n * dim..2 * n * dim]);
            let dp = map.jvp(dq, dim).unwrap();
            let curve = BSplineCurve::from_knot_vector(p, kv.clone(), Points::from_raw(dp.clone(), dim)).unwrap();
            let mut back = vec![0.0; n * dim];
            curve.eval_batch(&ts, &mut back).unwrap();
            let scale = dp.iter().fold(1.0f64, |m, x| m.max(x.abs()));
            for (a, b) in back.iter().zip(dq) {
                prop_assert!((a - b).abs() <= 1e-12 * scale, "{} against {}", a, b);
            }
            let gq = map.vjp(g, dim).unwrap();
            let lhs: f64 = g.iter().zip(&dp).map(|(a, b)| a * b).sum();
            let rhs: f64 = gq.iter().zip(dq).map(|(a, b)| a * b).sum();
            let size = gq.iter().chain(g).fold(1.0f64, |m, x| m.max(x.abs())) * scale * (n * dim) as f64;
            prop_assert!((lhs - rhs).abs() <= 1e-12 * size, "<g, A^-1 q> = {lhs}, <A^-T g, q> = {rhs}");
        }
    }

    #[test]
    fn errors_name_the_argument() {
        let kv = KnotVector::new(vec![0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0]).unwrap();
        let map = InterpolationMap::new(2, &kv, &[0.0, 0.3, 0.7, 1.0]).unwrap();
        let e = map.vjp(&[1.0; 3], 1).unwrap_err();
        assert!(
            matches!(
                e,
                Error::LengthMismatch {
                    expected: 4,
                    got: 3,
                    ..
                }
            ),
            "{e:?}"
        );
        let e = map.jvp(&[1.0, f64::NAN, 0.0, 0.0], 1).unwrap_err();
        assert!(matches!(e, Error::NonFinite { index: 1, .. }), "{e:?}");
        let e = map.jvp(&[], 0).unwrap_err();
        assert!(matches!(e, Error::Dimension { .. }), "{e:?}");
        let e = InterpolationMap::new(2, &kv, &[0.0, 0.3, 0.7]).unwrap_err();
        assert!(matches!(e, Error::LengthMismatch { .. }), "{e:?}");
        let e = InterpolationMap::new(2, &kv, &[0.0, 0.3, 0.7, 1.5]).unwrap_err();
        assert!(matches!(e, Error::ParameterOutOfDomain { .. }), "{e:?}");
        // Schoenberg–Whitney: three parameters in the first span, none in the last
        let e = InterpolationMap::new(2, &kv, &[0.0, 0.1, 0.2, 0.3]).unwrap_err();
        assert!(matches!(e, Error::SingularSystem { .. }), "{e:?}");
    }
}
