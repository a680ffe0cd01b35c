//! Numerical extremes: data offset by 1e8, scaled by 1e-8 and 1e8, nearly coincident
//! knots, knot multiplicities at the limit, degrees up to 20 against the slow recursive oracle,
//! NURBS weight ratios from 1e-6 to 1e6. Every result keeps its relative accuracy, or the call
//! fails with a clear error.
//!
//! ## The bound, and why it is the right one
//! Every evaluation kernel here (de Boor, de Casteljau, Cox–de Boor bases, the rational quotient)
//! forms **convex combinations** of the control points: the weights `N_i(t)` (or `N_i w_i / Σ N_j
//! w_j`) are non-negative and sum to one. Each of the `p` levels of a triangular scheme, and each
//! term of the basis recurrence, adds at most a few roundings of relative size `ε = 2^-52`, and
//! a convex combination does not amplify them. So the computed point differs from the exact one
//! by at most
//!
//! `|C̃(t) − C(t)| ≤ K·(p + 1)·ε·max_i |P_i|`,    [`EVAL_K`] = 4,
//!
//! with `max |P_i|` the size of the data *as stored* (including an offset: `1e8 + x` is only
//! known to `ε·1e8`, so no algorithm can do better than `ε·max|P_i|` absolutely). The bound does
//! not depend on the weight ratio of a NURBS curve nor on the knot spacing, and the tests show
//! that: they would fail by orders of magnitude if, e.g., the rational quotient were evaluated
//! through an unnormalised power form or the basis through explicit divided differences.
//!
//! Derivatives are not convex combinations: `C^{(k)}(t) = Σ N_i^{(k)}(t) P_i` cancels, and its
//! condition number is `Σ |N_i^{(k)}(t)|·|P_i|`. The bound used for them is
//! `K·(p + 1)·ε·Σ_i |N_i^{(k)}(t)|·max|P_i|` ([`deriv_bound`]), which is what backward stability of
//! the sum gives; a translation of the data by `1e8` therefore costs `ε·1e8·Σ|N'|` absolutely in
//! the derivative, and no more.
//!
//! Shifting the *parameter* domain to `[1e8, 1e8 + 1]` loses `ulp(1e8) ≈ 1.5e-8` in `t` itself;
//! the point then moves by up to `|C'(t)|·ulp(1e8)`. That is the conditioning of the input, not
//! an algorithmic loss, and [`parameter_shift_costs_only_the_representation_of_t`] tests exactly
//! that bound.
//!
//! The property tests at the end draw random curves and compare with the slow recursive oracle
//! (`lekalo_testkit::oracle`, the Cox–de Boor recursion) on many cases; their number follows the
//! standard `PROPTEST_CASES` environment variable (default 64 here), see `docs/robustness.md`.

use lekalo::basis::{basis_derivatives, basis_functions};
use lekalo::{BSplineCurve, BezierCurve, Error, NurbsCurve, Points};
use proptest::prelude::*;

use lekalo_testkit::{assert_close, config, oracle};

/// The constant `K` of the evaluation bound `K·(p + 1)·ε·max|P_i|` (see the module docs).
const EVAL_K: f64 = 4.0;

/// Number of parameters per test curve.
const N_PARAMS: usize = 41;

/// Deterministic, irregular data: `sin` of a scrambled index, in `[-1, 1]`.
fn wobble(i: usize, salt: f64) -> f64 {
    ((i as f64 + 1.0) * 12.9898 + salt * 78.233).sin()
}

/// Control points in `[-1, 1]^dim`, deterministic.
fn ctrl(n: usize, dim: usize, salt: f64) -> Vec<f64> {
    (0..n * dim).map(|i| wobble(i, salt)).collect()
}

/// Clamped knots on `[0, 1]` with irregular interior knots.
fn irregular_knots(p: usize, n_ctrl: usize) -> Vec<f64> {
    let interior = n_ctrl - p - 1;
    let mut gaps: Vec<f64> = (0..=interior).map(|i| 1.5 + wobble(i, 3.0)).collect();
    let total: f64 = gaps.iter().sum();
    gaps.iter_mut().for_each(|g| *g /= total);
    let mut knots = vec![0.0; p + 1];
    let mut acc = 0.0;
    for g in &gaps[..interior] {
        acc += g;
        knots.push(acc);
    }
    knots.extend(std::iter::repeat_n(1.0, p + 1));
    knots
}

fn params(a: f64, b: f64) -> Vec<f64> {
    (0..N_PARAMS)
        .map(|i| {
            let s = i as f64 / (N_PARAMS - 1) as f64;
            (a + s * (b - a)).clamp(a, b)
        })
        .collect()
}

fn max_abs(v: &[f64]) -> f64 {
    v.iter().fold(0.0, |m, x| m.max(x.abs()))
}

fn eval_bound(p: usize, scale: f64) -> f64 {
    EVAL_K * (p as f64 + 1.0) * f64::EPSILON * scale
}

/// `K·(p + 1)·ε·Σ_i |N_i^{(k)}(t)|·max|P_i|` for the derivative of order `k` at `t`.
fn deriv_bound(curve: &BSplineCurve, t: f64, k: usize, scale: f64) -> f64 {
    let p = curve.degree();
    let (_, d) = basis_derivatives(curve.knots(), p, t, k).expect("t in the domain");
    let row: f64 = d[k * (p + 1)..(k + 1) * (p + 1)]
        .iter()
        .map(|x| x.abs())
        .sum();
    EVAL_K * (p as f64 + 1.0) * f64::EPSILON * row.max(1.0) * scale
}

/// The curve through the slow oracle: `Σ_i N_{i,p}(t) P_i` with the recursive definition.
fn oracle_eval(curve: &BSplineCurve, t: f64) -> Vec<f64> {
    oracle::bspline(
        curve.knots().as_slice(),
        curve.degree(),
        curve.control_points().as_slice(),
        curve.dim(),
        t,
    )
}

fn transformed(c: &BSplineCurve, f: impl Fn(f64) -> f64) -> BSplineCurve {
    let data: Vec<f64> = c
        .control_points()
        .as_slice()
        .iter()
        .map(|&x| f(x))
        .collect();
    BSplineCurve::new(
        c.degree(),
        c.knots().as_slice().to_vec(),
        Points::from_flat(c.dim(), data).expect("finite data"),
    )
    .expect("same knots")
}

fn base_curve(p: usize, n_ctrl: usize, dim: usize) -> BSplineCurve {
    BSplineCurve::new(
        p,
        irregular_knots(p, n_ctrl),
        Points::from_flat(dim, ctrl(n_ctrl, dim, p as f64)).expect("finite data"),
    )
    .expect("valid curve")
}

// -------------------------------------------------------------------------------------------
// offset by 1e8, scaled by 1e-8 and 1e8

#[test]
fn offset_by_1e8_keeps_absolute_accuracy_of_the_stored_data() {
    const OFFSET: f64 = 1e8;
    for p in [1, 2, 3, 5, 8] {
        let c = base_curve(p, p + 7, 3);
        let moved = transformed(&c, |x| x + OFFSET);
        let scale = max_abs(moved.control_points().as_slice());
        for t in params(0.0, 1.0) {
            let want: Vec<f64> = c.eval(t).unwrap().iter().map(|x| x + OFFSET).collect();
            // the reference itself is rounded once when OFFSET is added: ε·scale more
            let tol = eval_bound(p, scale) + f64::EPSILON * scale;
            assert_close(&moved.eval(t).unwrap(), &want, tol, &format!("p={p} t={t}"));
            assert_close(
                &moved.eval(t).unwrap(),
                &oracle_eval(&moved, t),
                2.0 * tol,
                "oracle",
            );
            // derivatives are translation invariant; cancellation costs ε·1e8·Σ|N'|
            let d = moved.eval_derivatives(t, 2).unwrap();
            let d0 = c.eval_derivatives(t, 2).unwrap();
            for k in 1..=2.min(p) {
                let tol = deriv_bound(&moved, t, k, scale);
                assert_close(d.point(k), d0.point(k), tol, &format!("p={p} t={t} d{k}"));
            }
        }
    }
}

#[test]
fn scaling_by_1e8_and_1e_minus_8_keeps_relative_accuracy() {
    for s in [1e-8, 1e8, 1e-150, 1e150] {
        for p in [1, 3, 6] {
            let c = base_curve(p, p + 6, 2);
            let scaled = transformed(&c, |x| x * s);
            let scale = max_abs(scaled.control_points().as_slice());
            for t in params(0.0, 1.0) {
                let want: Vec<f64> = c.eval(t).unwrap().iter().map(|x| x * s).collect();
                let tol = eval_bound(p, scale) + f64::EPSILON * scale;
                assert_close(
                    &scaled.eval(t).unwrap(),
                    &want,
                    tol,
                    &format!("s={s} p={p}"),
                );
                let d = scaled.eval_derivatives(t, 1).unwrap();
                let d0 = c.eval_derivatives(t, 1).unwrap();
                let want: Vec<f64> = d0.point(1).iter().map(|x| x * s).collect();
                let tol = deriv_bound(&scaled, t, 1, scale) + f64::EPSILON * max_abs(&want);
                assert_close(d.point(1), &want, tol, &format!("s={s} p={p} d1"));
            }
        }
    }
}

#[test]
fn knot_insertion_and_bezier_decomposition_at_extreme_offsets_and_scales() {
    type Map = (&'static str, fn(f64) -> f64);
    let maps: [Map; 3] = [
        ("offset 1e8", |x| x + 1e8),
        ("scale 1e-8", |x| x * 1e-8),
        ("scale 1e8", |x| x * 1e8),
    ];
    for (name, f) in maps {
        for p in [2, 3, 5] {
            let c = transformed(&base_curve(p, p + 6, 3), f);
            let scale = max_abs(c.control_points().as_slice());
            // knot insertion (A5.1) forms convex combinations of neighbouring points too
            let ins = c.insert_knot(0.37, p).unwrap();
            let refined = c.refine_knots(&[0.1, 0.2, 0.2, 0.55, 0.9]).unwrap();
            let segs = c.to_bezier_segments();
            assert_eq!(segs.len(), c.knots().distinct().len() - 1, "{name}");
            for t in params(0.0, 1.0) {
                let want = c.eval(t).unwrap();
                // the inserted curve evaluates through one more convex scheme: twice the bound
                let tol = 2.0 * eval_bound(p, scale);
                assert_close(&ins.eval(t).unwrap(), &want, tol, &format!("{name} insert"));
                assert_close(
                    &refined.eval(t).unwrap(),
                    &want,
                    tol,
                    &format!("{name} refine"),
                );
                let seg = segs
                    .iter()
                    .find(|s| s.start <= t && t <= s.end)
                    .expect("segments cover the domain");
                // the local parameter (t − a)/(b − a) is rounded once: |C'|·ε·|t| more
                let d1 = max_abs(c.eval_derivatives(t, 1).unwrap().point(1));
                let tol = 2.0 * eval_bound(p, scale) + 4.0 * d1 * f64::EPSILON;
                assert_close(&seg.eval(t).unwrap(), &want, tol, &format!("{name} bezier"));
            }
        }
    }
}

#[test]
fn parameter_shift_costs_only_the_representation_of_t() {
    // knots on [1e8, 1e8 + 1]: nearly coincident in relative terms (gaps ~1e-9 relative)
    const SHIFT: f64 = 1e8;
    let ulp = SHIFT * f64::EPSILON; // spacing of doubles near 1e8 (within a factor 2)
    for p in [2, 3, 5] {
        let c = base_curve(p, p + 6, 2);
        let shifted = BSplineCurve::new(
            p,
            c.knots()
                .as_slice()
                .iter()
                .map(|k| k + SHIFT)
                .collect::<Vec<_>>(),
            c.control_points().clone(),
        )
        .unwrap();
        let scale = max_abs(c.control_points().as_slice());
        for u in params(0.0, 1.0) {
            let t = SHIFT + u;
            let u_stored = t - SHIFT; // exact (Sterbenz): the parameter actually evaluated
            let want = c.eval(u_stored).unwrap();
            let d1 = max_abs(c.eval_derivatives(u_stored, 1).unwrap().point(1));
            // knots k + SHIFT are each rounded by ≤ ulp/2: they move the curve like a parameter
            // error of ulp, times the local knot-sensitivity ~ p·|C'|
            let tol = eval_bound(p, scale) + 2.0 * (p as f64) * d1 * ulp;
            assert_close(
                &shifted.eval(t).unwrap(),
                &want,
                tol,
                &format!("p={p} u={u}"),
            );
        }
    }
}

// -------------------------------------------------------------------------------------------
// nearly coincident knots and multiplicities at the limit

#[test]
fn nearly_coincident_knots_agree_with_the_oracle() {
    for gap in [1e-6, 1e-10, 1e-13, 1e-15] {
        for p in [2, 3, 4] {
            let mut knots = vec![0.0; p + 1];
            knots.extend([0.3, 0.5, 0.5 + gap, 0.5 + 2.0 * gap, 0.8]);
            knots.extend(std::iter::repeat_n(1.0, p + 1));
            let n = knots.len() - p - 1;
            let c = BSplineCurve::new(p, knots, Points::from_flat(2, ctrl(n, 2, gap)).unwrap())
                .unwrap();
            let scale = max_abs(c.control_points().as_slice());
            let mut ts = params(0.0, 1.0);
            ts.extend([
                0.5,
                0.5 + 0.5 * gap,
                0.5 + gap,
                0.5 + 1.5 * gap,
                0.5 + 2.0 * gap,
            ]);
            for t in ts {
                let got = c.eval(t).unwrap();
                // both are convex schemes: each within the bound of the exact value
                assert_close(
                    &got,
                    &oracle_eval(&c, t),
                    2.0 * eval_bound(p, scale),
                    "oracle",
                );
                let (_, b) = basis_functions(c.knots(), p, t).unwrap();
                let sum: f64 = b.iter().sum();
                assert!(
                    (sum - 1.0).abs() <= eval_bound(p, 1.0),
                    "gap={gap} p={p} t={t}: partition of unity {sum}"
                );
                assert!(b.iter().all(|&x| x >= 0.0), "non-negative basis at t={t}");
            }
            // inserting a knot inside the tiny interval leaves the curve unchanged
            let ins = c.insert_knot(0.5 + 0.5 * gap, 1).unwrap();
            for t in params(0.0, 1.0) {
                assert_close(
                    &ins.eval(t).unwrap(),
                    &c.eval(t).unwrap(),
                    2.0 * eval_bound(p, scale),
                    &format!("gap={gap} insert"),
                );
            }
        }
    }
}

#[test]
fn multiplicity_p_plus_one_inside_and_at_the_ends() {
    for p in [1, 2, 3, 5] {
        // interior knot 0.5 with multiplicity p + 1: two independent pieces
        let mut knots = vec![0.0; p + 1];
        knots.extend(std::iter::repeat_n(0.5, p + 1));
        knots.extend(std::iter::repeat_n(1.0, p + 1));
        let n = 2 * (p + 1);
        let data = ctrl(n, 2, 7.0);
        let c = BSplineCurve::new(p, knots, Points::from_flat(2, data.clone()).unwrap()).unwrap();
        // ends interpolate the end points; at 0.5 the curve is right-continuous: P_{p+1}
        assert_eq!(c.eval(0.0).unwrap(), &data[..2], "p={p} start");
        assert_eq!(c.eval(1.0).unwrap(), &data[2 * n - 2..], "p={p} end");
        assert_eq!(
            c.eval(0.5).unwrap(),
            &data[2 * (p + 1)..2 * (p + 2)],
            "p={p} at 0.5"
        );
        // left of 0.5 the curve tends to P_p
        let left = c.eval(0.5 - 1e-12).unwrap();
        let tol = 1e-9 * max_abs(&data);
        assert_close(
            &left,
            &data[2 * p..2 * (p + 1)],
            tol,
            &format!("p={p} left limit"),
        );
        // no further insertion is possible there: a clear error
        assert!(matches!(
            c.insert_knot(0.5, 1),
            Err(Error::InvalidArgument { .. })
        ));
        // Bezier decomposition gives the two pieces unchanged
        let segs = c.to_bezier_segments();
        assert_eq!(segs.len(), 2, "p={p}");
        assert_eq!(
            segs[0].curve.control_points().as_slice(),
            &data[..2 * (p + 1)]
        );
        assert_eq!(
            segs[1].curve.control_points().as_slice(),
            &data[2 * (p + 1)..]
        );
        // multiplicity p + 2 is refused with a clear error
        let mut bad = vec![0.0; p + 1];
        bad.extend(std::iter::repeat_n(0.5, p + 2));
        bad.extend(std::iter::repeat_n(1.0, p + 1));
        let m = bad.len() - p - 1;
        let r = BSplineCurve::new(p, bad, Points::from_flat(2, ctrl(m, 2, 1.0)).unwrap());
        assert!(
            matches!(r, Err(Error::KnotMultiplicity { multiplicity, max, .. }) if multiplicity == p + 2 && max == p + 1),
            "p={p}: {r:?}"
        );
    }
}

// -------------------------------------------------------------------------------------------
// high degree

#[test]
fn degree_up_to_20_matches_the_recursive_oracle() {
    for p in [10, 15, 20] {
        // clamped knots with 2 interior knots: the oracle is exponential in p, few spans
        let n_ctrl = p + 3;
        let c = base_curve(p, n_ctrl, 2);
        let scale = max_abs(c.control_points().as_slice());
        for t in [0.0, 0.13, 0.5, 0.77, 1.0] {
            let got = c.eval(t).unwrap();
            assert_close(
                &got,
                &oracle_eval(&c, t),
                2.0 * eval_bound(p, scale),
                &format!("p={p}"),
            );
        }
    }
}

fn binomial(n: usize, k: usize) -> f64 {
    (0..k).fold(1.0, |acc, j| acc * (n - j) as f64 / (j + 1) as f64)
}

#[test]
fn bezier_degree_up_to_20_matches_explicit_bernstein_sum() {
    for n in [5, 10, 15, 20] {
        let data = ctrl(n + 1, 3, n as f64);
        let c = BezierCurve::new(Points::from_flat(3, data.clone()).unwrap()).unwrap();
        let scale = max_abs(&data);
        for t in params(0.0, 1.0) {
            // independent oracle: C(n,i) t^i (1−t)^(n−i), each term positive
            let mut want = [0.0; 3];
            for i in 0..=n {
                let (e1, e2) = (
                    i32::try_from(i).expect("small"),
                    i32::try_from(n - i).expect("small"),
                );
                let b = binomial(n, i) * t.powi(e1) * (1.0 - t).powi(e2);
                for d in 0..3 {
                    want[d] += b * data[3 * i + d];
                }
            }
            // the explicit sum has its own error ~ (n+1)·ε·scale: both within the bound
            let tol = 2.0 * eval_bound(n, scale);
            assert_close(&c.eval(t).unwrap(), &want, tol, &format!("n={n} t={t}"));
            let mut bern = [0.0; 3];
            c.eval_bernstein_into(t, &mut bern).unwrap();
            assert_close(&bern, &want, tol, &format!("n={n} t={t} bernstein"));
        }
    }
}

// -------------------------------------------------------------------------------------------
// NURBS weights from 1e-6 to 1e6

/// The rational curve through the slow oracle: `Σ N_{i,p} w_i P_i / Σ N_{i,p} w_i`.
fn nurbs_oracle(c: &NurbsCurve, t: f64) -> Vec<f64> {
    oracle::nurbs(
        c.knots().as_slice(),
        c.degree(),
        c.control_points().as_slice(),
        &c.weights(),
        c.dim(),
        t,
    )
}

#[test]
fn nurbs_extreme_weight_ratios_keep_relative_accuracy() {
    for ratio in [1e-6f64, 1e-3, 1e3, 1e6] {
        for p in [2, 3, 4] {
            let n = p + 6;
            let knots = irregular_knots(p, n);
            let data = ctrl(n, 2, ratio.log10());
            // weights alternate between 1 and `ratio`, with a sweep in between
            let weights: Vec<f64> = (0..n)
                .map(|i| {
                    if i % 2 == 0 {
                        1.0
                    } else {
                        ratio.powf((i % 3) as f64 / 2.0)
                    }
                })
                .collect();
            let c = NurbsCurve::new(
                p,
                knots.clone(),
                Points::from_flat(2, data.clone()).unwrap(),
                weights.clone(),
            )
            .unwrap();
            let scale = max_abs(&data);
            // the weights N_i w_i / Σ N_j w_j are convex: the bound does not depend on the ratio;
            // w·P is rounded once when the homogeneous points are formed: 2ε more
            let tol = 2.0 * eval_bound(p, scale) + 2.0 * f64::EPSILON * scale;
            // multiplying every weight by a constant leaves the curve unchanged
            let lifted: Vec<f64> = weights.iter().map(|w| w * 1e6).collect();
            let c2 =
                NurbsCurve::new(p, knots, Points::from_flat(2, data).unwrap(), lifted).unwrap();
            for t in params(0.0, 1.0) {
                let got = c.eval(t).unwrap();
                assert_close(
                    &got,
                    &nurbs_oracle(&c, t),
                    tol,
                    &format!("ratio={ratio} p={p}"),
                );
                assert_close(&c2.eval(t).unwrap(), &got, 2.0 * tol, "weights times 1e6");
                let mut batch = vec![0.0; 2];
                c.eval_batch(&[t], &mut batch).unwrap();
                assert_eq!(batch, got, "batch = single");
            }
        }
    }
}

#[test]
fn nurbs_overflowing_homogeneous_points_fail_clearly() {
    let data = Points::from_2d(&[[1e300, 0.0], [0.0, 1.0], [1.0, 1.0]]).unwrap();
    let r = NurbsCurve::new(
        2,
        vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
        data,
        vec![1e10, 1.0, 1.0],
    );
    assert!(matches!(r, Err(Error::NonFinite { .. })), "{r:?}");
    // a weight that underflows is refused as non-positive, never divided by
    let data = Points::from_2d(&[[0.0, 0.0], [0.0, 1.0], [1.0, 1.0]]).unwrap();
    let r = NurbsCurve::new(
        2,
        vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
        data,
        vec![1.0, 1e-320 * 0.0, 1.0],
    );
    assert!(
        matches!(r, Err(Error::NonPositiveWeight { index: 1, .. })),
        "{r:?}"
    );
}

// -------------------------------------------------------------------------------------------
// property tests against the slow oracle (PROPTEST_CASES sets the count; 64 by default)

/// A clamped B-spline of degree 1..=8 whose data are offset by `10^e_off` and scaled by
/// `10^e_scale`, with irregular knots that may repeat up to multiplicity `p`.
fn extreme_curve() -> impl Strategy<Value = BSplineCurve> {
    (
        1usize..=8,
        0usize..=6,
        1usize..=3,
        -8i32..=8,
        prop::bool::ANY,
        0i32..=8,
    )
        .prop_flat_map(|(p, extra, dim, e_scale, offset, e_off)| {
            let n = p + 1 + extra;
            (
                Just((p, dim, e_scale, offset, e_off)),
                prop::collection::vec(prop_oneof![1 => Just(0.0), 4 => 1e-9f64..1.0], extra + 1),
                prop::collection::vec(-1.0f64..1.0, n * dim),
            )
        })
        .prop_filter_map("valid", |((p, dim, e_scale, offset, e_off), gaps, data)| {
            let total: f64 = gaps.iter().sum();
            if total <= 0.0 {
                return None;
            }
            let mut knots = vec![0.0; p + 1];
            let mut acc = 0.0;
            for g in &gaps[..gaps.len() - 1] {
                acc += g / total;
                knots.push(acc.min(1.0));
            }
            knots.extend(std::iter::repeat_n(1.0, p + 1));
            let s = 10f64.powi(e_scale);
            let off = if offset { 10f64.powi(e_off) } else { 0.0 };
            let data: Vec<f64> = data.iter().map(|x| x * s + off).collect();
            BSplineCurve::new(p, knots, Points::from_flat(dim, data).ok()?).ok()
        })
}

proptest! {
    #![proptest_config(config(64))]

    /// Fast kernel (A2.2 + de Boor) against the recursive definition, at extreme offsets and
    /// scales, within `K·(p + 1)·ε·max|P|` (module docs).
    #[test]
    fn eval_matches_recursive_oracle(c in extreme_curve(), u in prop::collection::vec(0.0f64..=1.0, 8)) {
        let p = c.degree();
        let scale = max_abs(c.control_points().as_slice());
        let mut batch = vec![0.0; u.len() * c.dim()];
        c.eval_batch(&u, &mut batch).unwrap();
        for (j, &t) in u.iter().enumerate() {
            let got = c.eval(t).unwrap();
            let want = oracle_eval(&c, t);
            for (g, w) in got.iter().zip(&want) {
                prop_assert!((g - w).abs() <= 2.0 * eval_bound(p, scale),
                    "p={} t={} got {:e} want {:e}", p, t, g, w);
            }
            prop_assert_eq!(&batch[j * c.dim()..(j + 1) * c.dim()], &got[..]);
        }
    }

    /// Knot insertion and Bezier decomposition leave the curve unchanged within the bound.
    #[test]
    fn insertion_and_decomposition_keep_the_curve(c in extreme_curve(), x in 0.0f64..=1.0) {
        let p = c.degree();
        let scale = max_abs(c.control_points().as_slice());
        let segs = c.to_bezier_segments();
        let ins = match c.insert_knot(x, 1) {
            Ok(ins) => Some(ins),
            Err(Error::InvalidArgument { .. }) => None, // already multiplicity p
            Err(e) => return Err(TestCaseError::fail(format!("insert_knot: {e}"))),
        };
        for t in params(0.0, 1.0) {
            let want = c.eval(t).unwrap();
            if let Some(ins) = &ins {
                for (g, w) in ins.eval(t).unwrap().iter().zip(&want) {
                    prop_assert!((g - w).abs() <= 2.0 * eval_bound(p, scale), "insert {}: {:e} vs {:e}", t, g, w);
                }
            }
            let seg = segs.iter().find(|s| s.start <= t && t <= s.end).unwrap();
            let d1 = max_abs(c.eval_derivatives(t, 1).unwrap().point(1));
            let tol = 2.0 * eval_bound(p, scale) + 4.0 * d1 * f64::EPSILON;
            for (g, w) in seg.eval(t).unwrap().iter().zip(&want) {
                prop_assert!((g - w).abs() <= tol, "bezier {}: {:e} vs {:e}", t, g, w);
            }
        }
    }
}
