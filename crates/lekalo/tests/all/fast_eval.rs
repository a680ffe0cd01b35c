//! The fast evaluation paths agree with the reference `BSplineCurve::eval_batch` to 1e-14
//! relative to the control net's scale, for any degree, dimension, knot vector (multiple and
//! unevenly spaced knots, unclamped ends, large offsets) and parameter order; the parallel path
//! is bit-identical to the sequential one.

use lekalo_testkit::config;

use lekalo::{BSplineCurve, CurveEvaluator, EvalKernel, Points};
use proptest::prelude::*;

/// Agreement promised between the fast kernels and the reference, relative to the control net's
/// scale (largest absolute control coordinate).
const REL_TOL: f64 = 1e-14;

fn arb_curve() -> impl Strategy<Value = BSplineCurve> {
    (
        0usize..=6,
        1usize..=4,
        0usize..=12,
        prop::bool::ANY,
        prop::bool::ANY,
    )
        .prop_flat_map(|(p, dim, extra, clamped, offset)| {
            let n = p + 1 + extra;
            let n_knots = n + p + 1;
            (
                prop::collection::vec(-1.0f64..1.0, n * dim),
                // knot increments; zeros make multiple knots
                prop::collection::vec(
                    prop_oneof![Just(0.0), 1e-6f64..1.0, 0.1f64..10.0],
                    n_knots - 1,
                ),
                Just((p, dim, clamped, offset)),
            )
        })
        .prop_filter_map(
            "valid knot vector",
            |(ctrl, steps, (p, dim, clamped, offset))| {
                let shift = if offset { 1e6 } else { 0.0 };
                let mut knots = vec![shift];
                for s in &steps {
                    knots.push(knots[knots.len() - 1] + s);
                }
                if clamped {
                    let m = knots.len();
                    let (a, b) = (knots[p], knots[m - p - 1]);
                    knots[..p].fill(a);
                    knots[m - p..].fill(b);
                }
                let ctrl: Vec<f64> = ctrl.iter().map(|x| x * 1e3 + shift).collect();
                BSplineCurve::new(p, knots, Points::from_flat(dim, ctrl).ok()?).ok()
            },
        )
}

fn check(curve: &BSplineCurve, fracs: &[f64]) -> Result<(), TestCaseError> {
    let (a, b) = curve.domain();
    let mut ts: Vec<f64> = fracs.iter().map(|f| (a + (b - a) * f).min(b)).collect();
    ts.extend(
        curve
            .knots()
            .as_slice()
            .iter()
            .filter(|&&k| k >= a && k <= b),
    );
    let dim = curve.dim();
    let mut want = vec![0.0; ts.len() * dim];
    curve.eval_batch(&ts, &mut want).unwrap();
    let scale = curve.control_points().max_abs();
    for kernel in [EvalKernel::Auto, EvalKernel::Basis, EvalKernel::PowerForm] {
        let ev = CurveEvaluator::with_kernel(curve, kernel).unwrap();
        let is_default = kernel == EvalKernel::Auto || ev.kernel() == curve.evaluator().kernel();
        let mut got = vec![0.0; ts.len() * dim];
        ev.eval_batch(&ts, &mut got).unwrap();
        let err = got
            .iter()
            .zip(&want)
            .map(|(x, y)| (x - y).abs())
            .fold(0.0, f64::max);
        // the power form is promised only where it is the default (degree ≤ 3)
        if is_default {
            prop_assert!(
                err <= REL_TOL * scale,
                "{kernel:?} err {err:e}, scale {scale:e}"
            );
        }
        let mut par = vec![0.0; ts.len() * dim];
        ev.par_eval_batch(&ts, &mut par).unwrap();
        prop_assert!(par
            .iter()
            .zip(&got)
            .all(|(x, y)| x.to_bits() == y.to_bits()));
    }
    Ok(())
}

proptest! {
    #![proptest_config(config(96))]
    #[test]
    fn fast_paths_agree_with_reference(
        curve in arb_curve(),
        fracs in prop::collection::vec(0.0f64..=1.0, 1..200),
    ) {
        check(&curve, &fracs)?;
    }
}
