//! Property tests of the curve kernels (B-spline and Bezier): each law is written once as a
//! checker and driven by proptest strategies (randomness only from proptest, so failures shrink
//! and replay). Dimensions 1 to 6, degrees 0 to 6, random knot vectors with multiple knots (up to
//! multiplicity p + 1), clamped and unclamped.
//!
//! Tolerances (all relative to the data's scale, see each constant):
//! - [`SAME_CURVE_TOL`]: operations that must leave the curve unchanged (knot insertion and
//!   refinement, Bezier decomposition, splitting, subdivision, reversal, reparametrisation) are
//!   compared at many parameters to `1e-12 · max(1, max |P_i|)`.
//! - [`FD_TOL`]: derivatives against central differences, see [`check_finite_differences`].

use lekalo_testkit::config;

use lekalo::basis::{basis_function_recursive, basis_functions};
use lekalo::{BSplineCurve, BezierCurve, BezierSegment, Error, Points};
use proptest::prelude::*;

/// Curves that must be identical are compared to this, times `max(1, max |P_i|)`.
const SAME_CURVE_TOL: f64 = 1e-12;

/// Relative tolerance of the central-difference check: the step is `1e-4` of the span's width,
/// so the truncation error (`h²/6 · |C^{(k+2)}|`) and the rounding error (`ε · |C^{(k−1)}| / h`)
/// are both well below `1e-6` times the derivative scale defined in
/// [`check_finite_differences`].
const FD_TOL: f64 = 1e-6;

/// Relative step of the central differences, as a fraction of the span's width.
const FD_STEP: f64 = 1e-4;

// ---------------------------------------------------------------------------------------------
// strategies

/// Knots from a start in `[-5, 5)` and gaps that are zero a quarter of the time (multiple knots)
/// or in `[0.25, 2)`, all times a scale `10^e`, `e ∈ [-4, 4]`; optionally clamped. Control
/// coordinates in `[-10, 10)` times `10^f`, `f ∈ [-3, 6]`. Invalid draws (multiplicity > p + 1,
/// empty domain) are filtered out by `BSplineCurve::new` itself.
fn curve_with(degrees: std::ops::RangeInclusive<usize>) -> impl Strategy<Value = BSplineCurve> {
    (
        degrees,
        1usize..=6,
        0usize..=6,
        any::<bool>(),
        -4i32..=4,
        -3i32..=6,
    )
        .prop_flat_map(|(p, dim, extra, clamped, knot_exp, ctrl_exp)| {
            let n_ctrl = p + 1 + extra;
            let n_knots = n_ctrl + p + 1;
            (
                Just((p, dim, clamped, 10f64.powi(knot_exp), 10f64.powi(ctrl_exp))),
                -5.0f64..5.0,
                prop::collection::vec(prop_oneof![1 => Just(0.0), 3 => 0.25f64..2.0], n_knots - 1),
                prop::collection::vec(-10.0f64..10.0, n_ctrl * dim),
            )
        })
        .prop_filter_map(
            "valid knots",
            |((p, dim, clamped, knot_scale, ctrl_scale), t0, mut gaps, ctrl)| {
                if clamped {
                    let len = gaps.len();
                    gaps[..p].fill(0.0);
                    gaps[len - p..].fill(0.0);
                }
                let mut knots = vec![t0 * knot_scale];
                for g in gaps {
                    knots.push(knots[knots.len() - 1] + g * knot_scale);
                }
                let ctrl = ctrl.into_iter().map(|x| x * ctrl_scale).collect();
                BSplineCurve::new(p, knots, Points::from_flat(dim, ctrl).ok()?).ok()
            },
        )
}

fn curve() -> impl Strategy<Value = BSplineCurve> {
    curve_with(0..=6)
}

fn bezier() -> impl Strategy<Value = BezierCurve> {
    (1usize..=6, 1usize..=8)
        .prop_flat_map(|(dim, n)| (Just(dim), prop::collection::vec(-10.0f64..10.0, n * dim)))
        .prop_map(|(dim, ctrl)| BezierCurve::new(Points::from_flat(dim, ctrl).unwrap()).unwrap())
}

/// A parameter in the domain given by a fraction in `[0, 1]`.
fn at(c: &BSplineCurve, f: f64) -> f64 {
    let (lo, hi) = c.domain();
    (lo + (hi - lo) * f).clamp(lo, hi)
}

/// Parameters in the domain: a uniform sweep, both ends and every knot inside the domain.
fn params(c: &BSplineCurve) -> Vec<f64> {
    let mut ts: Vec<f64> = (0..=50).map(|k| at(c, f64::from(k) / 50.0)).collect();
    let (lo, hi) = c.domain();
    ts.extend(c.knots().as_slice().iter().filter(|&&k| k >= lo && k <= hi));
    ts
}

fn scale(c: &BSplineCurve) -> f64 {
    c.control_points().max_abs().max(1.0)
}

fn max_diff(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).fold(0.0, |m, (x, y)| m.max((x - y).abs()))
}

// ---------------------------------------------------------------------------------------------
// checkers

/// `a` and `b` agree at the parameters `ts` to `SAME_CURVE_TOL · scale`.
fn check_same_at(
    a: &BSplineCurve,
    b: &BSplineCurve,
    ts: &[f64],
    scale: f64,
) -> Result<(), TestCaseError> {
    for &t in ts {
        let (pa, pb) = (a.eval(t).unwrap(), b.eval(t).unwrap());
        let d = max_diff(&pa, &pb);
        prop_assert!(
            d <= SAME_CURVE_TOL * scale,
            "t = {t}: {pa:?} vs {pb:?} (diff {d:e})"
        );
    }
    Ok(())
}

/// `b` has the domain of `a` and the same values on it.
fn check_same_curve(a: &BSplineCurve, b: &BSplineCurve) -> Result<(), TestCaseError> {
    prop_assert_eq!(a.domain(), b.domain());
    prop_assert_eq!(a.degree(), b.degree());
    prop_assert!(b
        .knots()
        .validate_for(b.degree(), b.control_points().len())
        .is_ok());
    let mut ts = params(a);
    ts.extend(params(b));
    check_same_at(a, b, &ts, scale(a))
}

/// Every non-zero derivative `C^{(k)}`, `k = 1..=p`, from `eval_derivatives`, against the central
/// difference of `C^{(k−1)}` with step `h = FD_STEP · w` at points in the middle 60 % of each
/// non-empty span of width `w` (away from the knots, where the curve is a polynomial). The
/// tolerance is `FD_TOL · Σ_{j=k−1}^{k+2} σ_j w^{j−k}` with `σ_j` the largest control point of the
/// j-th derivative curve (a bound of `|C^{(j)}|` by the convex-hull property), i.e. the error
/// terms measured in units of the k-th derivative.
fn check_finite_differences(c: &BSplineCurve, fractions: &[f64]) -> Result<(), TestCaseError> {
    let p = c.degree();
    let mut sigma = vec![c.control_points().max_abs()];
    let mut d = c.clone();
    for _ in 0..p {
        d = d.derivative().unwrap();
        sigma.push(d.control_points().max_abs());
    }
    sigma.extend([0.0, 0.0, 0.0]);
    let k = c.knots().as_slice();
    let (lo, hi) = c.domain();
    for s in p..k.len() - p - 1 {
        if !(k[s] < k[s + 1] && k[s] >= lo && k[s + 1] <= hi) {
            continue;
        }
        let w = k[s + 1] - k[s];
        let h = FD_STEP * w;
        for &f in fractions {
            let t = k[s] + w * (0.2 + 0.6 * f);
            let d0 = c.eval_derivatives(t, p).unwrap();
            let dp = c.eval_derivatives(t + h, p).unwrap();
            let dm = c.eval_derivatives(t - h, p).unwrap();
            for order in 1..=p {
                let tol = FD_TOL
                    * (sigma[order - 1] / w
                        + sigma[order]
                        + sigma[order + 1] * w
                        + sigma[order + 2] * w * w)
                        .max(1e-300);
                for dd in 0..c.dim() {
                    let fd = (dp.point(order - 1)[dd] - dm.point(order - 1)[dd]) / (2.0 * h);
                    let exact = d0.point(order)[dd];
                    prop_assert!(
                        (fd - exact).abs() <= tol,
                        "order {order} at t = {t}: {exact} vs finite difference {fd} (tol {tol:e})"
                    );
                }
            }
        }
    }
    Ok(())
}

// ---------------------------------------------------------------------------------------------
// basis laws

proptest! {
    #![proptest_config(config(64))]

    /// Partition of unity, non-negativity and local support of the basis on the domain
    /// (P&T §2.2; document 003 Lemmas 3.1, 3.5, 3.8).
    #[test]
    fn basis_partition_nonnegative_local(c in curve()) {
        let p = c.degree();
        let kv = c.knots();
        for t in params(&c) {
            let (span, n) = basis_functions(kv, p, t).unwrap();
            prop_assert!(n.iter().all(|&v| v >= 0.0), "negative basis value at {t}: {n:?}");
            let sum: f64 = n.iter().sum();
            prop_assert!((sum - 1.0).abs() <= 1e-14 * (p + 1) as f64, "sum {sum} at {t}");
            // local support: the other B-splines vanish (away from the right end of an unclamped
            // domain, where the recursive definition is right-continuous)
            if t < c.domain().1 {
                for i in 0..c.control_points().len() {
                    if i + p < span || i > span {
                        prop_assert_eq!(basis_function_recursive(kv, i, p, t).unwrap(), 0.0);
                    }
                }
            }
        }
    }

    /// Moving `P_j` changes the curve only on `[t_j, t_{j+p+1})`.
    #[test]
    fn curve_local_support(c in curve(), j_index in any::<prop::sample::Index>(), delta in prop::collection::vec(-5.0f64..5.0, 6)) {
        let n = c.control_points().len();
        let j = j_index.index(n);
        let p = c.degree();
        let dim = c.dim();
        let mut data = c.control_points().as_slice().to_vec();
        for d in 0..dim {
            data[j * dim + d] += delta[d];
        }
        let moved = BSplineCurve::new(p, c.knots().as_slice().to_vec(), Points::from_flat(dim, data).unwrap()).unwrap();
        let k = c.knots().as_slice();
        for t in params(&c) {
            if t < k[j] || t > k[j + p + 1] {
                prop_assert_eq!(c.eval(t).unwrap(), moved.eval(t).unwrap(), "t = {}", t);
            }
        }
    }

    /// Affine invariance: the curve of `A P_i + b` is `A C(t) + b`.
    #[test]
    fn affine_invariance(
        c in curve(),
        a in prop::collection::vec(-2.0f64..2.0, 36),
        b in prop::collection::vec(-10.0f64..10.0, 6),
    ) {
        let dim = c.dim();
        let map = |x: &[f64]| -> Vec<f64> {
            (0..dim).map(|r| b[r] + (0..dim).map(|s| a[r * 6 + s] * x[s]).sum::<f64>()).collect()
        };
        let data: Vec<f64> = c.control_points().iter().flat_map(map).collect();
        let mapped = BSplineCurve::new(c.degree(), c.knots().as_slice().to_vec(), Points::from_flat(dim, data).unwrap()).unwrap();
        let tol = SAME_CURVE_TOL * (1.0 + 2.0 * dim as f64 * scale(&c) + 10.0);
        for t in params(&c) {
            let lhs = mapped.eval(t).unwrap();
            let rhs = map(&c.eval(t).unwrap());
            prop_assert!(max_diff(&lhs, &rhs) <= tol, "t = {t}: {lhs:?} vs {rhs:?}");
        }
    }

    /// Strong convex hull (P&T §3.2): `C(t)` lies in the box of the active control points
    /// `P_{k−p} … P_k` of its span `k`.
    #[test]
    fn convex_hull(c in curve()) {
        let p = c.degree();
        let dim = c.dim();
        let tol = SAME_CURVE_TOL * scale(&c);
        for t in params(&c) {
            let span = c.knots().find_span(p, t).unwrap();
            let pt = c.eval(t).unwrap();
            for d in 0..dim {
                let coords = (span - p..=span).map(|i| c.control_points().point(i)[d]);
                let lo = coords.clone().fold(f64::INFINITY, f64::min);
                let hi = coords.fold(f64::NEG_INFINITY, f64::max);
                prop_assert!(pt[d] >= lo - tol && pt[d] <= hi + tol, "t = {t}, coordinate {d}");
            }
            let (blo, bhi) = c.bounding_box();
            prop_assert!((0..dim).all(|d| pt[d] >= blo[d] - tol && pt[d] <= bhi[d] + tol));
        }
    }

    /// Derivatives against central differences away from the knots.
    #[test]
    fn derivatives_match_finite_differences(c in curve(), fs in prop::collection::vec(0.0f64..=1.0, 2)) {
        check_finite_differences(&c, &fs)?;
    }

    /// The derivative curve (P&T §3.3, A3.3) equals `eval_derivatives`, order by order, including at
    /// knots (right-hand derivatives) and at the ends.
    #[test]
    fn derivative_curve_matches_eval_derivatives(c in curve_with(1..=6)) {
        let p = c.degree();
        let mut d = c.clone();
        for order in 1..=p {
            d = d.derivative().unwrap();
            prop_assert_eq!(d.degree(), p - order);
            prop_assert_eq!(d.domain(), c.domain());
            prop_assert!(d.knots().validate_for(d.degree(), d.control_points().len()).is_ok());
            let tol = SAME_CURVE_TOL * d.control_points().max_abs().max(1.0);
            for t in params(&c) {
                let via_curve = d.eval(t).unwrap();
                let direct = c.eval_derivatives(t, order).unwrap();
                let diff = max_diff(&via_curve, direct.point(order));
                prop_assert!(diff <= tol, "order {order}, t = {t}: {via_curve:?} vs {:?}", direct.point(order));
            }
        }
    }

    /// Batch evaluation is bit-for-bit single evaluation, for sorted and unsorted parameters.
    #[test]
    fn batch_equals_single(c in curve(), fs in prop::collection::vec(0.0f64..=1.0, 0..30)) {
        let mut ts: Vec<f64> = fs.iter().map(|&f| at(&c, f)).collect();
        ts.extend(params(&c));
        let mut out = vec![0.0; ts.len() * c.dim()];
        c.eval_batch(&ts, &mut out).unwrap();
        for (k, &t) in ts.iter().enumerate() {
            let single = c.eval(t).unwrap();
            prop_assert_eq!(&out[k * c.dim()..(k + 1) * c.dim()], single.as_slice());
        }
    }
}

// ---------------------------------------------------------------------------------------------
// operations that leave the curve unchanged

proptest! {
    #![proptest_config(config(64))]

    #[test]
    fn knot_insertion_keeps_curve(c in curve_with(1..=6), f in 0.0f64..=1.0, knot_index in any::<prop::sample::Index>(), times in 1usize..=6, at_knot in any::<bool>(), end in 0usize..3) {
        let (lo, hi) = c.domain();
        let t = match (at_knot, end) {
            (_, 1) => lo,
            (_, 2) => hi,
            (true, _) => {
                let inside: Vec<f64> = c.knots().as_slice().iter().copied().filter(|&k| k >= lo && k <= hi).collect();
                inside[knot_index.index(inside.len())]
            }
            (false, _) => at(&c, f),
        };
        let s = c.knots().multiplicity(t);
        match c.insert_knot(t, times) {
            Ok(d) => {
                prop_assert!(s + times <= c.degree());
                prop_assert_eq!(d.knots().multiplicity(t), s + times);
                prop_assert_eq!(d.control_points().len(), c.control_points().len() + times);
                check_same_curve(&c, &d)?;
            }
            Err(e) => {
                prop_assert!(s + times > c.degree(), "unexpected error {e:?}");
                prop_assert!(matches!(e, Error::InvalidArgument { .. }), "{e:?}");
            }
        }
    }

    /// Refinement keeps the curve and equals repeated single insertion.
    #[test]
    fn knot_refinement_keeps_curve(c in curve_with(1..=6), fs in prop::collection::vec(0.0f64..=1.0, 1..8), ends in any::<(bool, bool)>()) {
        let p = c.degree();
        let mut x: Vec<f64> = fs.iter().map(|&f| at(&c, f)).collect();
        let (lo, hi) = c.domain();
        if ends.0 { x.push(lo); }
        if ends.1 { x.push(hi); }
        x.sort_by(f64::total_cmp);
        // keep each knot's final multiplicity ≤ p
        let mut kept: Vec<f64> = Vec::new();
        for t in x {
            let already = kept.iter().filter(|&&k| k == t).count();
            if c.knots().multiplicity(t) + already < p {
                kept.push(t);
            }
        }
        let refined = c.refine_knots(&kept).unwrap();
        prop_assert_eq!(refined.control_points().len(), c.control_points().len() + kept.len());
        check_same_curve(&c, &refined)?;
        let mut one_by_one = c.clone();
        for &t in &kept {
            one_by_one = one_by_one.insert_knot(t, 1).unwrap();
        }
        prop_assert_eq!(one_by_one.knots(), refined.knots());
        let d = max_diff(one_by_one.control_points().as_slice(), refined.control_points().as_slice());
        prop_assert!(d <= SAME_CURVE_TOL * scale(&c), "A5.4 vs A5.1 control points differ by {d:e}");
    }

    /// Bezier decomposition: pieces cover the domain, reproduce the curve, and rebuild it.
    #[test]
    fn bezier_decomposition_keeps_curve(c in curve()) {
        let p = c.degree();
        let pieces = c.to_bezier_segments();
        let (lo, hi) = c.domain();
        prop_assert_eq!(pieces[0].start, lo);
        prop_assert_eq!(pieces[pieces.len() - 1].end, hi);
        let tol = SAME_CURVE_TOL * scale(&c);
        for (i, seg) in pieces.iter().enumerate() {
            prop_assert_eq!(seg.curve.degree(), p);
            if i > 0 {
                prop_assert_eq!(seg.start, pieces[i - 1].end);
            }
            for k in 0..=10 {
                let t = (seg.start + (seg.end - seg.start) * f64::from(k) / 10.0).min(seg.end);
                // at an interior end the spline is right-continuous; the piece gives its left limit
                if t == seg.end && i + 1 < pieces.len() {
                    continue;
                }
                let d = max_diff(&seg.eval(t).unwrap(), &c.eval(t).unwrap());
                prop_assert!(d <= tol, "segment {i} at t = {t}: diff {d:e}");
            }
        }
        let rebuilt = BSplineCurve::from_bezier_segments(&pieces).unwrap();
        prop_assert!(rebuilt.is_clamped());
        check_same_curve(&c, &rebuilt)?;
        // a clamped curve whose knots all have multiplicity p (or p + 1) round-trips exactly
        let again = BSplineCurve::from_bezier_segments(&rebuilt.to_bezier_segments()).unwrap();
        prop_assert_eq!(again, rebuilt);
    }

    /// Splitting: the left piece is the curve on `[lo, t)` (its value at `t` is the left limit),
    /// the right piece on `[t, hi]`.
    #[test]
    fn split_keeps_curve(c in curve(), f in 0.01f64..0.99, at_knot in any::<bool>(), knot_index in any::<prop::sample::Index>()) {
        let (lo, hi) = c.domain();
        let interior: Vec<f64> = c.knots().as_slice().iter().copied().filter(|&k| k > lo && k < hi).collect();
        // at an existing knot (of any multiplicity up to p + 1, i.e. also at a jump) or anywhere
        let t = if at_knot && !interior.is_empty() {
            interior[knot_index.index(interior.len())]
        } else {
            at(&c, f)
        };
        prop_assume!(t > lo && t < hi);
        let (left, right) = c.split_at(t).unwrap();
        prop_assert_eq!(left.domain(), (lo, t));
        prop_assert_eq!(right.domain(), (t, hi));
        prop_assert!(left.knots().validate_for(left.degree(), left.control_points().len()).is_ok());
        prop_assert!(right.knots().validate_for(right.degree(), right.control_points().len()).is_ok());
        let ts = params(&c);
        let lts: Vec<f64> = ts.iter().copied().filter(|&s| s < t).chain(params(&left).into_iter().filter(|&s| s < t)).collect();
        let rts: Vec<f64> = ts.iter().copied().filter(|&s| s >= t).chain(params(&right)).collect();
        check_same_at(&left, &c, &lts, scale(&c))?;
        check_same_at(&right, &c, &rts, scale(&c))?;
    }

    /// Reversal and reparametrisation: `rev(a + b − t) = C(t)`, `C̃(a' + (t − a)·s) = C(t)`.
    /// Knots and parameters are mapped with one or two roundings each, i.e. moved by up to
    /// `δ = 4ε·(|t_min| + |t_max| + |a'| + |b'|)` in domain units, which moves the curve by up to
    /// `(p + 1)·δ·σ_1` (σ_1: largest control point of the derivative curve, a bound of `|C'|`);
    /// the tolerance is that plus [`SAME_CURVE_TOL`]. At a jump the two sides differ, so knots of
    /// multiplicity `p + 1` are skipped.
    #[test]
    fn reverse_and_reparametrize(c in curve(), a in -100.0f64..100.0, len in 0.1f64..100.0) {
        let p = c.degree();
        let (lo, hi) = c.domain();
        let b = a + len;
        let sigma1 = c.derivative().map_or(0.0, |d| d.control_points().max_abs());
        let shift = 4.0 * f64::EPSILON * (lo.abs() + hi.abs());
        let r = c.reverse().unwrap();
        prop_assert_eq!(r.domain(), (lo, hi));
        let tol = SAME_CURVE_TOL * scale(&c) + (p + 1) as f64 * shift * sigma1;
        for t in params(&c) {
            if c.knots().multiplicity(t) > p {
                continue;
            }
            let u = (lo + hi - t).clamp(lo, hi);
            let d = max_diff(&r.eval(u).unwrap(), &c.eval(t).unwrap());
            prop_assert!(d <= tol, "reverse at {t}: diff {d:e} > {tol:e}");
        }
        let q = c.reparametrize(a, b).unwrap();
        prop_assert_eq!(q.domain(), (a, b));
        // shifts in the new parameter, measured in old units
        let shift_new = 4.0 * f64::EPSILON * (a.abs() + b.abs()) * (hi - lo) / (b - a);
        let tol = SAME_CURVE_TOL * scale(&c) + (p + 1) as f64 * (shift + shift_new) * sigma1;
        for t in params(&c) {
            if c.knots().multiplicity(t) > p {
                continue;
            }
            let s = (a + (t - lo) * (b - a) / (hi - lo)).clamp(a, b);
            let d = max_diff(&q.eval(s).unwrap(), &c.eval(t).unwrap());
            prop_assert!(d <= tol, "reparametrize at {t}: diff {d:e} > {tol:e}");
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Bezier laws

proptest! {
    #![proptest_config(config(64))]

    #[test]
    fn bezier_de_casteljau_equals_bernstein_and_batch(c in bezier(), ts in prop::collection::vec(0.0f64..=1.0, 0..20)) {
        let mut all = ts.clone();
        all.extend([0.0, 1.0]);
        let dim = c.dim();
        let tol = SAME_CURVE_TOL * c.control_points().max_abs().max(1.0);
        let mut out = vec![0.0; all.len() * dim];
        c.eval_batch(&all, &mut out).unwrap();
        let mut bern = vec![0.0; dim];
        for (k, &t) in all.iter().enumerate() {
            let single = c.eval(t).unwrap();
            prop_assert_eq!(&out[k * dim..(k + 1) * dim], single.as_slice());
            c.eval_bernstein_into(t, &mut bern).unwrap();
            prop_assert!(max_diff(&single, &bern) <= tol, "t = {t}");
        }
    }

    #[test]
    fn bezier_subdivision_keeps_curve(c in bezier(), s in 0.01f64..0.99, ts in prop::collection::vec(0.0f64..=1.0, 1..20)) {
        let (left, right) = c.split_at(s).unwrap();
        let tol = SAME_CURVE_TOL * c.control_points().max_abs().max(1.0);
        for &u in &ts {
            let l = left.eval(u).unwrap();
            let r = right.eval(u).unwrap();
            let dl = max_diff(&l, &c.eval(s * u).unwrap());
            let dr = max_diff(&r, &c.eval((s + (1.0 - s) * u).min(1.0)).unwrap());
            prop_assert!(dl <= tol && dr <= tol, "u = {u}: {dl:e} {dr:e}");
        }
    }

    #[test]
    fn bezier_derivatives(c in bezier(), ts in prop::collection::vec(0.0f64..=1.0, 1..10)) {
        let n = c.degree();
        let d = c.derivative();
        prop_assert_eq!(d.degree(), n.saturating_sub(1));
        let mut hodographs = vec![c.clone()];
        for k in 1..=n + 1 {
            hodographs.push(hodographs[k - 1].derivative());
        }
        for &t in &ts {
            let rows = c.eval_derivatives(t, n + 1).unwrap();
            for (k, h) in hodographs.iter().enumerate() {
                let tol = SAME_CURVE_TOL * h.control_points().max_abs().max(1.0);
                prop_assert!(max_diff(rows.point(k), &h.eval(t).unwrap()) <= tol, "order {k} at {t}");
            }
            prop_assert!(rows.point(n + 1).iter().all(|&v| v == 0.0), "order above degree");
        }
        // the B-spline form has the same derivatives
        let b = c.to_bspline();
        check_finite_differences(&b, &[0.1, 0.5, 0.9])?;
        for &t in &ts {
            let via_b = b.eval_derivatives(t, n).unwrap();
            let direct = c.eval_derivatives(t, n).unwrap();
            for k in 0..=n {
                let tol = SAME_CURVE_TOL * hodographs[k].control_points().max_abs().max(1.0);
                prop_assert!(max_diff(via_b.point(k), direct.point(k)) <= tol, "order {k} at {t}");
            }
        }
    }
}

// ---------------------------------------------------------------------------------------------
// golden examples and errors

fn lecture() -> BSplineCurve {
    let ctrl = Points::from_2d(&[[1.0, 1.0], [2.0, 3.0], [4.0, 3.0]]).unwrap();
    BSplineCurve::new(2, vec![0.0, 0.0, 1.0, 2.0, 3.0, 3.0], ctrl).unwrap()
}

/// Document 002, B-splines: the unclamped lecture curve decomposes into one quadratic on its domain
/// [1, 2], from (3/2, 2) to (3, 3), with middle control point `P_1 = (2, 3)`: on [1, 2] the curve
/// is (t²/2 + 1, −t² + 4t − 1), whose Bezier points are C(1), C(1) + C'(1)/2, C(2).
#[test]
fn lecture_example_decomposes_on_its_domain() {
    let c = lecture();
    assert!(!c.is_clamped());
    let pieces = c.to_bezier_segments();
    assert_eq!(pieces.len(), 1);
    assert_eq!((pieces[0].start, pieces[0].end), (1.0, 2.0));
    assert_eq!(
        pieces[0].curve.control_points().as_slice(),
        &[1.5, 2.0, 2.0, 3.0, 3.0, 3.0]
    );
    assert_eq!(pieces[0].eval(1.5).unwrap(), vec![17.0 / 8.0, 11.0 / 4.0]);
    let (left, right) = c.split_at(1.5).unwrap();
    assert_eq!(left.eval(1.5).unwrap(), vec![17.0 / 8.0, 11.0 / 4.0]);
    assert_eq!(right.eval(1.5).unwrap(), vec![17.0 / 8.0, 11.0 / 4.0]);
    // clamped at the split, unclamped at the outer ends as the original
    assert_eq!(left.knots().as_slice(), &[0.0, 0.0, 1.0, 1.5, 1.5, 1.5]);
    assert_eq!(right.knots().as_slice(), &[1.5, 1.5, 1.5, 2.0, 3.0, 3.0]);
    assert!(!left.is_clamped() && !right.is_clamped());
    assert_eq!(c.bounding_box(), (vec![1.0, 1.0], vec![4.0, 3.0]));
}

#[test]
fn insert_and_refine_errors() {
    let c = lecture();
    assert!(matches!(
        c.insert_knot(0.5, 1),
        Err(Error::ParameterOutOfDomain { .. })
    ));
    assert!(matches!(
        c.insert_knot(f64::NAN, 1),
        Err(Error::ParameterOutOfDomain { .. })
    ));
    assert!(matches!(
        c.insert_knot(1.5, 3),
        Err(Error::InvalidArgument { .. })
    ));
    assert!(matches!(
        c.insert_knot(1.0, 2),
        Err(Error::InvalidArgument { .. })
    ));
    assert!(matches!(
        c.insert_knot(1.5, usize::MAX),
        Err(Error::InvalidArgument { .. })
    ));
    assert_eq!(c.insert_knot(1.5, 0).unwrap(), c);
    assert!(matches!(
        c.refine_knots(&[1.2, f64::INFINITY]),
        Err(Error::NonFinite { index: 1, .. })
    ));
    assert!(matches!(
        c.refine_knots(&[1.5, 1.2]),
        Err(Error::KnotsNotSorted { index: 1, .. })
    ));
    assert!(matches!(
        c.refine_knots(&[1.5, 2.5]),
        Err(Error::ParameterOutOfDomain { .. })
    ));
    assert!(matches!(
        c.refine_knots(&[1.5, 1.5, 1.5]),
        Err(Error::InvalidArgument { .. })
    ));
    assert_eq!(c.refine_knots(&[]).unwrap(), c);
}

#[test]
fn split_errors() {
    let c = lecture();
    assert!(matches!(
        c.split_at(2.5),
        Err(Error::ParameterOutOfDomain { .. })
    ));
    assert!(matches!(
        c.split_at(1.0),
        Err(Error::InvalidArgument { .. })
    ));
    assert!(matches!(
        c.split_at(2.0),
        Err(Error::InvalidArgument { .. })
    ));
    let b = BezierCurve::new(Points::from_flat(1, vec![0.0, 1.0, 3.0]).unwrap()).unwrap();
    assert!(matches!(
        b.split_at(1.5),
        Err(Error::ParameterOutOfDomain { .. })
    ));
    assert!(matches!(
        b.split_at(f64::NAN),
        Err(Error::ParameterOutOfDomain { .. })
    ));
    assert!(matches!(
        b.split_at(0.0),
        Err(Error::InvalidArgument { .. })
    ));
    assert!(matches!(
        b.split_at(1.0),
        Err(Error::InvalidArgument { .. })
    ));
}

#[test]
fn derivative_of_degree_zero() {
    let c = BSplineCurve::new(
        0,
        vec![0.0, 1.0, 2.0],
        Points::from_flat(1, vec![3.0, 4.0]).unwrap(),
    )
    .unwrap();
    assert!(matches!(
        c.derivative(),
        Err(Error::Degree { degree: 0, .. })
    ));
    let b = BezierCurve::new(Points::from_flat(2, vec![3.0, 4.0]).unwrap()).unwrap();
    assert_eq!(b.derivative().control_points().as_slice(), &[0.0, 0.0]);
}

/// A knot of multiplicity p + 1 inside the domain: the curve jumps; the derivative curve drops
/// the vanishing basis function.
#[test]
fn derivative_across_a_jump() {
    let ctrl = Points::from_flat(1, vec![0.0, 1.0, 2.0, 5.0, 7.0, 6.0]).unwrap();
    let c = BSplineCurve::new(2, vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 2.0, 2.0, 2.0], ctrl).unwrap();
    let d = c.derivative().unwrap();
    assert_eq!(d.knots().as_slice(), &[0.0, 0.0, 1.0, 1.0, 2.0, 2.0]);
    assert_eq!(d.control_points().as_slice(), &[2.0, 2.0, 4.0, -2.0]);
    assert_eq!(c.eval(1.0).unwrap(), vec![5.0]);
    assert_eq!(
        d.eval(1.0).unwrap(),
        c.eval_derivatives(1.0, 1).unwrap().point(1)
    );
}

#[test]
fn from_bezier_segments_errors() {
    let q = |v: &[f64]| BezierCurve::new(Points::from_flat(1, v.to_vec()).unwrap()).unwrap();
    let seg = |s: f64, e: f64, c: BezierCurve| BezierSegment {
        start: s,
        end: e,
        curve: c,
    };
    assert!(matches!(
        BSplineCurve::from_bezier_segments(&[]),
        Err(Error::TooFew { .. })
    ));
    assert!(matches!(
        BSplineCurve::from_bezier_segments(&[seg(0.0, f64::NAN, q(&[1.0, 2.0]))]),
        Err(Error::NonFinite { index: 0, .. })
    ));
    assert!(matches!(
        BSplineCurve::from_bezier_segments(&[seg(1.0, 1.0, q(&[1.0, 2.0]))]),
        Err(Error::EmptyDomain { .. })
    ));
    assert!(matches!(
        BSplineCurve::from_bezier_segments(&[
            seg(0.0, 1.0, q(&[1.0, 2.0])),
            seg(1.5, 2.0, q(&[2.0, 3.0]))
        ]),
        Err(Error::InvalidArgument { .. })
    ));
    assert!(matches!(
        BSplineCurve::from_bezier_segments(&[
            seg(0.0, 1.0, q(&[1.0, 2.0])),
            seg(1.0, 2.0, q(&[2.0, 3.0, 4.0]))
        ]),
        Err(Error::Degree { degree: 2, .. })
    ));
    let planar = BezierCurve::new(Points::from_flat(2, vec![2.0, 0.0, 3.0, 0.0]).unwrap()).unwrap();
    assert!(matches!(
        BSplineCurve::from_bezier_segments(&[seg(0.0, 1.0, q(&[1.0, 2.0])), seg(1.0, 2.0, planar)]),
        Err(Error::Dimension {
            expected: 1,
            got: 2,
            ..
        })
    ));
    // a jump between pieces is kept, with a knot of multiplicity p + 1
    let c = BSplineCurve::from_bezier_segments(&[
        seg(0.0, 1.0, q(&[1.0, 2.0])),
        seg(1.0, 2.0, q(&[5.0, 3.0])),
    ])
    .unwrap();
    assert_eq!(c.knots().as_slice(), &[0.0, 0.0, 1.0, 1.0, 2.0, 2.0]);
    assert_eq!(c.eval(1.0).unwrap(), vec![5.0]);
    assert_eq!(c.eval(0.5).unwrap(), vec![1.5]);
}

#[test]
fn reverse_and_reparametrize_errors() {
    let c = lecture();
    assert!(matches!(
        c.reparametrize(1.0, 1.0),
        Err(Error::EmptyDomain { .. })
    ));
    assert!(matches!(
        c.reparametrize(f64::NAN, 1.0),
        Err(Error::NonFinite { .. })
    ));
    // knots spread over 1e300 on a domain of length 1: the mapped knots overflow
    assert!(matches!(
        c.reparametrize(0.0, 1e308),
        Err(Error::NonFinite { .. })
    ));
    // knots 1e-20 apart next to a domain of length 1 merge when mapped to 1 − t
    let ctrl = Points::from_flat(1, vec![0.0, 1.0, 2.0]).unwrap();
    let tiny = BSplineCurve::new(1, vec![0.0, 1e-20, 2e-20, 1.0, 1.0], ctrl.clone());
    // (the knot vector itself is fine)
    let tiny = tiny.unwrap();
    assert!(matches!(
        tiny.reverse(),
        Err(Error::KnotMultiplicity { .. })
    ));
    assert!(matches!(
        tiny.reparametrize(1.0, 2.0),
        Err(Error::KnotMultiplicity { .. })
    ));
}

#[test]
fn bezier_batch_and_eval_errors() {
    let b = BezierCurve::new(Points::from_flat(2, vec![0.0, 1.0, 3.0, 2.0]).unwrap()).unwrap();
    let mut out = vec![0.0; 4];
    assert!(matches!(
        b.eval_batch(&[0.5], &mut out),
        Err(Error::LengthMismatch {
            expected: 2,
            got: 4,
            ..
        })
    ));
    assert!(matches!(
        b.eval_batch(&[0.5, 2.0], &mut out),
        Err(Error::ParameterOutOfDomain { .. })
    ));
    assert!(matches!(
        b.eval_into(0.5, &mut out),
        Err(Error::LengthMismatch { .. })
    ));
    assert!(matches!(
        b.eval_derivatives(-0.5, 1),
        Err(Error::ParameterOutOfDomain { .. })
    ));
    let seg = BezierSegment {
        start: 1.0,
        end: 3.0,
        curve: b,
    };
    assert!(matches!(
        seg.eval(0.5),
        Err(Error::ParameterOutOfDomain { .. })
    ));
    assert_eq!(seg.eval(3.0).unwrap(), vec![3.0, 2.0]);
}

/// Boehm insertion into a quadratic Bezier (as a clamped B-spline) at 1/2 gives the de Casteljau
/// midpoints `P_0, (P_0 + P_1)/2, (P_1 + P_2)/2, P_2` (P&T §5.2), exactly in binary floats.
#[test]
fn insertion_golden_quadratic() {
    let ctrl = Points::from_2d(&[[0.0, 0.0], [2.0, 4.0], [6.0, 2.0]]).unwrap();
    let c = BezierCurve::new(ctrl).unwrap().to_bspline();
    let d = c.insert_knot(0.5, 1).unwrap();
    assert_eq!(d.knots().as_slice(), &[0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0]);
    assert_eq!(
        d.control_points().as_slice(),
        &[0.0, 0.0, 1.0, 2.0, 4.0, 3.0, 6.0, 2.0]
    );
    let twice = c.insert_knot(0.5, 2).unwrap();
    assert_eq!(
        twice.control_points().as_slice(),
        &[0.0, 0.0, 1.0, 2.0, 2.5, 2.5, 4.0, 3.0, 6.0, 2.0]
    );
    assert_eq!(c.refine_knots(&[0.5, 0.5]).unwrap(), twice);
}

/// A clamped quadratic with one interior knot (P&T §5.3): the pieces share the midpoint of
/// `P_1 P_2`, and each interior control point is kept.
#[test]
fn decomposition_golden_clamped_quadratic() {
    let ctrl = Points::from_flat(1, vec![0.0, 2.0, 4.0, 8.0]).unwrap();
    let c = BSplineCurve::new(2, vec![0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0], ctrl).unwrap();
    assert!(c.is_clamped());
    let pieces = c.to_bezier_segments();
    assert_eq!(pieces.len(), 2);
    assert_eq!((pieces[0].start, pieces[0].end), (0.0, 0.5));
    assert_eq!((pieces[1].start, pieces[1].end), (0.5, 1.0));
    assert_eq!(
        pieces[0].curve.control_points().as_slice(),
        &[0.0, 2.0, 3.0]
    );
    assert_eq!(
        pieces[1].curve.control_points().as_slice(),
        &[3.0, 4.0, 8.0]
    );
    let back = BSplineCurve::from_bezier_segments(&pieces).unwrap();
    assert_eq!(
        back.knots().as_slice(),
        &[0.0, 0.0, 0.0, 0.5, 0.5, 1.0, 1.0, 1.0]
    );
    // degree 0: one piece per non-empty span, the constant control point
    let steps = BSplineCurve::new(
        0,
        vec![0.0, 1.0, 2.5, 3.0],
        Points::from_flat(1, vec![5.0, 6.0, 7.0]).unwrap(),
    )
    .unwrap();
    let pieces = steps.to_bezier_segments();
    assert_eq!(pieces.len(), 3);
    assert_eq!((pieces[1].start, pieces[1].end), (1.0, 2.5));
    assert_eq!(pieces[2].curve.control_points().as_slice(), &[7.0]);
    assert_eq!(BSplineCurve::from_bezier_segments(&pieces).unwrap(), steps);
}

#[test]
fn reverse_overflow_is_an_error() {
    // knots whose width overflows are refused when the curve is built
    let ctrl = Points::from_flat(1, vec![0.0, 1.0]).unwrap();
    assert!(matches!(
        BSplineCurve::new(1, vec![-1.7e308, 1e308, 1.5e308, 1.7e308], ctrl.clone()),
        Err(Error::InvalidArgument { what, .. }) if what.words() == "knots"
    ));
    // domain [1e308, 1.5e308]: a + b overflows when the knots are mirrored
    let c = BSplineCurve::new(1, vec![0.0, 1e308, 1.5e308, 1.7e308], ctrl).unwrap();
    assert!(matches!(c.reverse(), Err(Error::NonFinite { .. })));
}

proptest! {
    #![proptest_config(config(64))]

    /// Document 003 Lemma 3.9 (P&T §2.2): at an interior knot of multiplicity `m ≤ p` the
    /// curve is `C^{p−m}`. Left-hand derivatives come from the left piece of a split there
    /// (evaluated at its right end), right-hand ones from the curve itself. Tolerance:
    /// `1e-10 · σ_k` with `σ_k` the largest control point of the k-th derivative curve of either
    /// piece (the derivative's scale): each derivative order differences the rounding of the
    /// insertion once more; the largest ratio seen over 3000 cases was 1.3e-12 (order 4).
    #[test]
    fn smoothness_at_knots_follows_multiplicity(c in curve_with(1..=6)) {
        let p = c.degree();
        let (lo, hi) = c.domain();
        for (u, m) in c.knots().distinct() {
            if !(u > lo && u < hi) || m > p {
                continue;
            }
            let (left, _) = c.split_at(u).unwrap();
            let order = p - m;
            let from_left = left.eval_derivatives(u, order).unwrap();
            let from_right = c.eval_derivatives(u, order).unwrap();
            let (mut dl, mut dc) = (left.clone(), c.clone());
            for k in 0..=order {
                let sigma = dl.control_points().max_abs().max(dc.control_points().max_abs()).max(1e-300);
                let diff = max_diff(from_left.point(k), from_right.point(k));
                prop_assert!(diff <= 1e-10 * sigma, "knot {u} (multiplicity {m}), order {k}: diff {diff:e}, scale {sigma:e}");
                if k < order {
                    dl = dl.derivative().unwrap();
                    dc = dc.derivative().unwrap();
                }
            }
        }
    }
}

/// A cubic with a jump at 1 (multiplicity p + 1 = 4): two independent Bezier pieces; the
/// decomposition and its inverse are exact, splitting at the jump separates them, and insertion
/// next to the jump keeps the curve.
#[test]
fn cubic_with_a_jump() {
    let ctrl = Points::from_flat(1, vec![0.0, 1.0, 2.0, 3.0, 10.0, 9.0, 8.0, 7.0]).unwrap();
    let knots = vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0, 2.0, 2.0, 2.0, 2.0];
    let c = BSplineCurve::new(3, knots, ctrl).unwrap();
    let pieces = c.to_bezier_segments();
    assert_eq!(pieces.len(), 2);
    assert_eq!(
        pieces[0].curve.control_points().as_slice(),
        &[0.0, 1.0, 2.0, 3.0]
    );
    assert_eq!(
        pieces[1].curve.control_points().as_slice(),
        &[10.0, 9.0, 8.0, 7.0]
    );
    assert_eq!(BSplineCurve::from_bezier_segments(&pieces).unwrap(), c);
    let (left, right) = c.split_at(1.0).unwrap();
    assert_eq!(left.eval(1.0).unwrap(), vec![3.0]);
    assert_eq!(right.eval(1.0).unwrap(), vec![10.0]);
    assert_eq!(c.eval(1.0).unwrap(), vec![10.0]);
    assert!(matches!(
        c.insert_knot(1.0, 1),
        Err(Error::InvalidArgument { .. })
    ));
    let d = c.insert_knot(0.5, 3).unwrap();
    for k in 0..=20 {
        let t = f64::from(k) / 10.0;
        let diff = max_diff(&c.eval(t).unwrap(), &d.eval(t).unwrap());
        assert!(diff <= 1e-14, "t = {t}: {diff:e}");
    }
    let der = c.derivative().unwrap();
    assert_eq!(
        der.knots().as_slice(),
        &[0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 2.0, 2.0, 2.0]
    );
    assert_eq!(
        der.control_points().as_slice(),
        &[3.0, 3.0, 3.0, -3.0, -3.0, -3.0]
    );
}
