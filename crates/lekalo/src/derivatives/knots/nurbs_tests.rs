//! Tests of `nurbs.rs`: the knot JVP of NURBS curves against central differences of
//! evaluation in each interior knot (relative 1e-7), and at a double knot against central
//! differences of the pair moved together and one-sided ones of each copy; the VJP the JVP's
//! exact transpose (the adjoint identity to 1e-12 relative); the primal values bit for bit
//! `eval_batch`; equal weights giving the B-spline's derivative; a negative test for every
//! error.

use proptest::prelude::*;

use super::tests::{
    assert_adjoint, assert_rel, curve, dot, knot_jvp, knots_and_params, max_abs, unit, FD_RTOL,
    FD_STEP,
};
use crate::curve::NurbsCurve;
use crate::error::Error;
use crate::oracle::proptest_config;
use crate::points::Points;

/// A NURBS curve with the inputs it was built from (to rebuild it on moved knots).
#[derive(Debug, Clone)]
struct Nurbs {
    degree: usize,
    knots: Vec<f64>,
    ctrl: Vec<f64>,
    weights: Vec<f64>,
    dim: usize,
}

impl Nurbs {
    fn curve(&self) -> NurbsCurve {
        self.with_knots(self.knots.clone())
    }

    fn with_knots(&self, knots: Vec<f64>) -> NurbsCurve {
        let ctrl = Points::from_raw(self.ctrl.clone(), self.dim);
        NurbsCurve::new(self.degree, knots, ctrl, self.weights.clone()).unwrap()
    }

    fn eval_on(&self, knots: Vec<f64>, ts: &[f64]) -> Vec<f64> {
        let mut out = vec![0.0; ts.len() * self.dim];
        self.with_knots(knots).eval_batch(ts, &mut out).unwrap();
        out
    }

    /// `(C(τ + a·e) − C(τ − b·e)) / (a + b)` for the knot direction `e`.
    fn difference(&self, ts: &[f64], e: &[f64], (a, b): (f64, f64)) -> Vec<f64> {
        let up = self.knots.iter().zip(e).map(|(k, d)| k + a * d).collect();
        let down = self.knots.iter().zip(e).map(|(k, d)| k - b * d).collect();
        let (f, g) = (self.eval_on(up, ts), self.eval_on(down, ts));
        f.iter().zip(&g).map(|(x, y)| (x - y) / (a + b)).collect()
    }

    fn knot_jvp(&self, ts: &[f64], dk: &[f64]) -> (Vec<f64>, Vec<f64>) {
        let mut out = vec![0.0; ts.len() * self.dim];
        let mut tan = vec![0.0; ts.len() * self.dim];
        self.curve()
            .eval_batch_knot_jvp(ts, dk, &mut out, &mut tan)
            .unwrap();
        (out, tan)
    }

    fn knot_vjp(&self, ts: &[f64], g: &[f64]) -> Vec<f64> {
        let mut gk = vec![f64::NAN; self.knots.len()];
        self.curve().eval_batch_knot_vjp(ts, g, &mut gk).unwrap();
        gk
    }
}

/// A NURBS curve of degree 1..=5, dimension 1..=3, weights in `[0.2, 4]`, clamped or not,
/// parameters off its knots, a knot tangent and a cotangent.
fn nurbs_case() -> impl Strategy<Value = (Nurbs, Vec<f64>, Vec<f64>, Vec<f64>)> {
    (1usize..=5, 0usize..7, 1usize..=3, any::<bool>(), 1usize..12).prop_flat_map(
        |(p, extra, dim, clamped, m)| {
            let n = p + 1 + extra;
            (
                prop::collection::vec(0.2f64..1.0, 2 * p + 9),
                prop::collection::vec(-1.0f64..1.0, n * dim),
                prop::collection::vec(0.2f64..4.0, n),
                prop::collection::vec((0usize..64, 0.0f64..1.0), m),
                prop::collection::vec(-1.0f64..1.0, n + p + 1),
                prop::collection::vec(-1.0f64..1.0, m * dim),
            )
                .prop_map(move |(gaps, ctrl, weights, xs, dk, g)| {
                    let (knots, ts) = knots_and_params(p, n, clamped, &gaps, &xs);
                    let c = Nurbs {
                        degree: p,
                        knots,
                        ctrl,
                        weights,
                        dim,
                    };
                    (c, ts, dk, g)
                })
        },
    )
}

proptest! {
    #![proptest_config(proptest_config(128))]

    /// The JVP's values are `eval_batch`'s bits.
    #[test]
    fn nurbs_primal_is_eval_batch_bit_for_bit((c, ts, dk, _g) in nurbs_case()) {
        let (out, _) = c.knot_jvp(&ts, &dk);
        prop_assert_eq!(out, c.eval_on(c.knots.clone(), &ts));
    }

    /// Each interior knot's JVP column against central differences; the end knots' tangents
    /// are ignored.
    #[test]
    fn nurbs_knot_jvp_matches_central_differences((c, ts, _dk, _g) in nurbs_case()) {
        let (p, len) = (c.degree, c.knots.len());
        let scale = max_abs(&c.ctrl);
        for k in p + 1..len - p - 1 {
            let e = unit(len, k);
            let (_, tan) = c.knot_jvp(&ts, &e);
            let fd = c.difference(&ts, &e, (FD_STEP, FD_STEP));
            assert_rel(&tan, &fd, FD_RTOL, scale, &format!("knot {k}"));
        }
        for k in (0..=p).chain(len - p - 1..len) {
            let (_, tan) = c.knot_jvp(&ts, &unit(len, k));
            prop_assert!(tan.iter().all(|&x| x == 0.0), "end knot {} moved the curve", k);
        }
    }

    /// `⟨ḡ, J τ̇⟩ = ⟨Jᵀ ḡ, τ̇⟩` to 1e-12 relative, and the end knots' cotangents zero.
    #[test]
    fn nurbs_knot_vjp_is_the_transpose_of_the_jvp((c, ts, dk, g) in nurbs_case()) {
        let (_, tan) = c.knot_jvp(&ts, &dk);
        let gk = c.knot_vjp(&ts, &g);
        let (p, len) = (c.degree, gk.len());
        prop_assert!(gk[..=p].iter().chain(&gk[len - p - 1..]).all(|&x| x == 0.0));
        let scale: f64 = tan.iter().zip(&g).map(|(a, b)| (a * b).abs()).sum::<f64>()
            + gk.iter().zip(&dk).map(|(a, b)| (a * b).abs()).sum::<f64>();
        assert_adjoint(dot(&tan, &g), dot(&gk, &dk), scale, "NURBS");
    }

    /// With all weights equal the NURBS curve is the B-spline curve of its control points, and
    /// its knot derivative the B-spline's (to rounding: `C` and `W` are formed, then divided).
    #[test]
    fn equal_weights_give_the_bspline_derivative(
        (c, ts, dk, _g) in nurbs_case(),
        w in 0.2f64..4.0,
    ) {
        let c = Nurbs { weights: vec![w; c.weights.len()], ..c };
        let (_, tan) = c.knot_jvp(&ts, &dk);
        let b = curve(c.degree, c.knots.clone(), c.ctrl.clone(), c.dim);
        let (_, want) = knot_jvp(&b, &ts, &dk);
        assert_rel(&tan, &want, 1e-13, max_abs(&c.ctrl), "equal weights");
    }
}

/// A rational cubic with a double interior knot, and parameters on both sides of it.
fn double_knot() -> (Nurbs, Vec<f64>) {
    let knots = vec![0.0, 0.0, 0.0, 0.0, 0.3, 0.6, 0.6, 0.9, 1.2, 1.2, 1.2, 1.2];
    let n = knots.len() - 4;
    let c = Nurbs {
        degree: 3,
        knots,
        ctrl: (0..2 * n)
            .map(|i| ((i * 5 + 1) as f64 * 0.73).sin())
            .collect(),
        weights: (0..n).map(|i| 1.0 + 0.6 * ((i * 3) as f64).cos()).collect(),
        dim: 2,
    };
    (c, vec![0.1, 0.35, 0.5, 0.58, 0.62, 0.75, 1.0, 1.15])
}

/// At the double knot: the pair moved together against central differences (relative 1e-7),
/// each copy against the one-sided differences of the move that keeps the knots sorted, and
/// the copies' sum the pair's.
#[test]
fn double_knot_central_for_the_pair_one_sided_for_each_copy() {
    let (c, ts) = double_knot();
    let len = c.knots.len();
    let scale = max_abs(&c.ctrl);
    let mut pair = vec![0.0; len];
    pair[5] = 1.0;
    pair[6] = 1.0;
    let (_, together) = c.knot_jvp(&ts, &pair);
    let fd = c.difference(&ts, &pair, (FD_STEP, FD_STEP));
    assert_rel(&together, &fd, FD_RTOL, scale, "the pair together");
    // forward differences with a smaller step: one-sided truncation error O(h)
    let h = 1e-8;
    let (_, first) = c.knot_jvp(&ts, &unit(len, 5));
    let decreasing = c.difference(&ts, &unit(len, 5), (0.0, h));
    assert_rel(&first, &decreasing, 1e-5, scale, "first copy, decreasing");
    let (_, last) = c.knot_jvp(&ts, &unit(len, 6));
    let increasing = c.difference(&ts, &unit(len, 6), (h, 0.0));
    assert_rel(&last, &increasing, 1e-5, scale, "last copy, increasing");
    let sum: Vec<f64> = first.iter().zip(&last).map(|(a, b)| a + b).collect();
    assert_rel(&sum, &together, 1e-14, scale, "the copies sum to the pair");
    // and the test could tell the one-sided values apart
    let gap = first
        .iter()
        .zip(&last)
        .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
    assert!(gap > 1e-3, "{gap}");
    // the interior knots of the VJP against the JVP's columns
    let g: Vec<f64> = (0..ts.len() * 2)
        .map(|i| ((i * 7 % 5) as f64 - 2.0) / 2.0)
        .collect();
    let gk = c.knot_vjp(&ts, &g);
    for k in 4..len - 4 {
        let (_, col) = c.knot_jvp(&ts, &unit(len, k));
        let want = dot(&col, &g);
        assert!(
            (gk[k] - want).abs() <= 1e-13 * scale.max(want.abs()),
            "knot {k}"
        );
    }
}

#[test]
fn nurbs_errors_name_the_argument() {
    let (c, _) = double_knot();
    let curve = c.curve();
    let len = c.knots.len();
    let (mut out, mut tan) = (vec![0.0; 4], vec![0.0; 4]);
    let dk = vec![0.0; len];
    let e = curve.eval_batch_knot_jvp(&[0.1, 0.2], &dk[..len - 1], &mut out, &mut tan);
    assert!(
        matches!(e, Err(Error::LengthMismatch { expected, got, .. }) if expected == len && got == len - 1),
        "{e:?}"
    );
    let e = curve.eval_batch_knot_jvp(&[0.1, 0.2], &dk, &mut out[..3], &mut tan);
    assert!(
        matches!(
            e,
            Err(Error::LengthMismatch {
                expected: 4,
                got: 3,
                ..
            })
        ),
        "{e:?}"
    );
    let e = curve.eval_batch_knot_jvp(&[0.1, 0.2], &dk, &mut out, &mut tan[..2]);
    assert!(
        matches!(
            e,
            Err(Error::LengthMismatch {
                expected: 4,
                got: 2,
                ..
            })
        ),
        "{e:?}"
    );
    let mut bad = dk.clone();
    bad[5] = f64::INFINITY;
    let e = curve.eval_batch_knot_jvp(&[0.1, 0.2], &bad, &mut out, &mut tan);
    assert!(matches!(e, Err(Error::NonFinite { index: 5, .. })), "{e:?}");
    let e = curve.eval_batch_knot_jvp(&[0.1, 1.5], &dk, &mut out, &mut tan);
    assert!(
        matches!(e, Err(Error::ParameterOutOfDomain { .. })),
        "{e:?}"
    );
    let mut gk = vec![0.0; len];
    let e = curve.eval_batch_knot_vjp(&[0.1, 0.2], &[1.0, 1.0, 1.0], &mut gk);
    assert!(
        matches!(
            e,
            Err(Error::LengthMismatch {
                expected: 4,
                got: 3,
                ..
            })
        ),
        "{e:?}"
    );
    let e = curve.eval_batch_knot_vjp(&[0.1, 0.2], &[1.0, 1.0, f64::NAN, 1.0], &mut gk);
    assert!(matches!(e, Err(Error::NonFinite { index: 2, .. })), "{e:?}");
    let e = curve.eval_batch_knot_vjp(&[0.1, 0.2], &[1.0; 4], &mut gk[..3]);
    assert!(
        matches!(e, Err(Error::LengthMismatch { expected, got: 3, .. }) if expected == len),
        "{e:?}"
    );
    let e = curve.eval_batch_knot_vjp(&[-0.5], &[1.0, 1.0], &mut gk);
    assert!(
        matches!(e, Err(Error::ParameterOutOfDomain { .. })),
        "{e:?}"
    );
}
