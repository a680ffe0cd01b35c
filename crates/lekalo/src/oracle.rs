//! Slow, transparent reference evaluators (compiled for tests only): the library's curves through
//! the plain-number oracles of `lekalo_testkit::oracle`, which every crate's tests share.
//!
//! - B-spline curves by the lecture's recursive Cox–de Boor definition (document 002, B-splines,
//!   the recursion of `basis::basis_function_recursive`) summed over **all** control points,
//!   with no span search and no triangular scheme. At the right end of an unclamped domain
//!   (`t = t_{n+1} < t_m`) the right-continuous definition would use the span beyond the domain,
//!   so there the oracle uses the left-continuous variant (`N_{i,0} = 1` on `(t_i, t_{i+1}]`),
//!   i.e. the left limit, which is the value the library defines at the end of the domain.
//! - Bezier curves by the Bernstein formula with explicit binomial coefficients and powers
//!   (document 002, Bezier curves): `P(t) = Σ C(n,i) t^i (1 − t)^{n−i} P_i`.
//!
//! The fast kernels (P&T A2.1/A2.2/A3.1 and de Casteljau) must agree with these to
//! [`ORACLE_TOL`] relative to the control net's scale.

use crate::curve::bezier::BezierCurve;
use crate::curve::bspline::BSplineCurve;

/// Agreement required between a fast kernel and the oracle, relative to
/// `max(1, max |P_i|)`: a few hundred rounding units of `f64`, for degrees up to 6.
pub(crate) const ORACLE_TOL: f64 = 1e-13;

/// `C(t)` by the recursive definition summed over all control points (see the module docs).
/// `t` must lie in the curve's domain.
pub(crate) fn bspline_naive(curve: &BSplineCurve, t: f64) -> Vec<f64> {
    lekalo_testkit::oracle::bspline(
        curve.knots().as_slice(),
        curve.degree(),
        curve.control_points().as_slice(),
        curve.dim(),
        t,
    )
}

/// `P(t) = Σ C(n,i) t^i (1 − t)^{n−i} P_i` term by term.
pub(crate) fn bezier_naive(curve: &BezierCurve, t: f64) -> Vec<f64> {
    lekalo_testkit::oracle::bezier(curve.control_points().as_slice(), curve.dim(), t)
}

// Binomial coefficient `C(n, i)` as a float, by the multiplicative formula.
pub(crate) use lekalo_testkit::oracle::binomial;

// Proptest configuration for the unit tests: `PROPTEST_CASES` if set (the long job of
// docs/robustness.md), else `default_cases`; the same as every crate's integration tests use.
pub(crate) use lekalo_testkit::config as proptest_config;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::points::Points;
    use proptest::prelude::*;

    fn close(a: &[f64], b: &[f64], scale: f64) -> bool {
        a.iter()
            .zip(b)
            .all(|(x, y)| (x - y).abs() <= ORACLE_TOL * scale.max(1.0))
    }

    /// Random valid B-spline: degree 0..=6, dim 1..=6, knots from gaps that are zero (multiple
    /// knots) about a quarter of the time, clamped or not.
    fn curve() -> impl Strategy<Value = BSplineCurve> {
        (0usize..=6, 1usize..=6, 0usize..=6, any::<bool>())
            .prop_flat_map(|(p, dim, extra, clamped)| {
                let n_ctrl = p + 1 + extra;
                let n_knots = n_ctrl + p + 1;
                (
                    Just((p, dim, clamped)),
                    -5.0f64..5.0,
                    prop::collection::vec(
                        prop_oneof![1 => Just(0.0), 3 => 0.25f64..2.0],
                        n_knots - 1,
                    ),
                    prop::collection::vec(-10.0f64..10.0, n_ctrl * dim),
                )
            })
            .prop_filter_map("valid knots", |((p, dim, clamped), t0, mut gaps, ctrl)| {
                if clamped {
                    let len = gaps.len();
                    gaps[..p].fill(0.0);
                    gaps[len - p..].fill(0.0);
                }
                let mut knots = vec![t0];
                for g in gaps {
                    knots.push(knots[knots.len() - 1] + g);
                }
                BSplineCurve::new(p, knots, Points::from_flat(dim, ctrl).ok()?).ok()
            })
    }

    /// Parameters in the domain: both ends, every knot inside it, and a sweep.
    fn params(c: &BSplineCurve) -> Vec<f64> {
        let (lo, hi) = c.domain();
        let mut ts: Vec<f64> = (0..=40)
            .map(|k| (lo + (hi - lo) * f64::from(k) / 40.0).min(hi))
            .collect();
        ts.extend(c.knots().as_slice().iter().filter(|&&k| k >= lo && k <= hi));
        ts.push(hi);
        ts
    }

    proptest! {
        #![proptest_config(super::proptest_config(128))]

        #[test]
        fn bspline_kernels_agree_with_cox_de_boor(c in curve()) {
            let scale = c.control_points().max_abs();
            let ts = params(&c);
            let mut batch = vec![0.0; ts.len() * c.dim()];
            c.eval_batch(&ts, &mut batch).unwrap();
            for (k, &t) in ts.iter().enumerate() {
                let fast = c.eval(t).unwrap();
                let slow = bspline_naive(&c, t);
                prop_assert!(close(&fast, &slow, scale), "t = {t}: {fast:?} vs {slow:?}");
                let d = c.eval_derivatives(t, 0).unwrap();
                prop_assert!(close(d.point(0), &slow, scale), "eval_derivatives row 0 at {t}");
                prop_assert_eq!(&batch[k * c.dim()..(k + 1) * c.dim()], fast.as_slice());
            }
        }

        #[test]
        fn bezier_kernels_agree_with_bernstein_formula(
            (dim, ctrl) in (1usize..=6, 1usize..=8).prop_flat_map(|(dim, n)| {
                (Just(dim), prop::collection::vec(-10.0f64..10.0, n * dim))
            }),
            ts in prop::collection::vec(0.0f64..=1.0, 1..10),
        ) {
            let c = BezierCurve::new(Points::from_flat(dim, ctrl).unwrap()).unwrap();
            let scale = c.control_points().max_abs();
            let mut bern = vec![0.0; dim];
            let mut all = ts.clone();
            all.extend([0.0, 1.0]);
            for &t in &all {
                let slow = bezier_naive(&c, t);
                let fast = c.eval(t).unwrap();
                c.eval_bernstein_into(t, &mut bern).unwrap();
                prop_assert!(close(&fast, &slow, scale), "de Casteljau at {t}");
                prop_assert!(close(&bern, &slow, scale), "Bernstein sum at {t}");
                let via_bspline = c.to_bspline().eval(t).unwrap();
                prop_assert!(close(&via_bspline, &slow, scale), "as B-spline at {t}");
            }
        }
    }

    /// The lecture's table (document 002, B-splines), through the oracle itself.
    #[test]
    fn oracle_reproduces_lecture_table() {
        let ctrl = Points::from_2d(&[[1.0, 1.0], [2.0, 3.0], [4.0, 3.0]]).unwrap();
        let c = BSplineCurve::new(2, vec![0.0, 0.0, 1.0, 2.0, 3.0, 3.0], ctrl).unwrap();
        assert_eq!(bspline_naive(&c, 1.0), vec![1.5, 2.0]);
        assert_eq!(bspline_naive(&c, 1.5), vec![17.0 / 8.0, 11.0 / 4.0]);
        // right end of the unclamped domain: the left limit
        assert_eq!(bspline_naive(&c, 2.0), vec![3.0, 3.0]);
        assert_eq!(binomial(5, 2), 10.0);
    }
}
