//! Property and negative tests for knot removal, NURBS curve operations and surface operations
//! (insertion, refinement, splitting, Bezier patches, transposition, reversal). Randomness only
//! from proptest strategies.

use lekalo_testkit::config;

use lekalo::{
    BSplineCurve, BSplineSurface, BezierCurve, BezierSegment, Error, KnotVector, NurbsCurve,
    NurbsSurface, Points,
};
use proptest::prelude::*;

/// Relative tolerance for "the curve/surface is unchanged": operations that only insert knots
/// or permute data round each coordinate a few times.
const SAME_RTOL: f64 = 1e-12;

/// Knots from gaps that are zero a third of the time (multiple knots) or in `[0.25, 2)`, from a
/// start in `[-5, 5)`; clamped or not. Invalid draws are filtered by the constructors.
fn knots_from(t0: f64, gaps: &[f64], p: usize, clamped: bool) -> Vec<f64> {
    let mut gaps = gaps.to_vec();
    if clamped {
        let len = gaps.len();
        gaps[..p].fill(0.0);
        gaps[len - p..].fill(0.0);
    }
    let mut knots = vec![t0];
    for g in gaps {
        knots.push(knots[knots.len() - 1] + g);
    }
    knots
}

fn gaps(n: usize) -> impl Strategy<Value = Vec<f64>> {
    prop::collection::vec(prop_oneof![1 => Just(0.0), 2 => 0.25f64..2.0], n)
}

/// A random curve: degree in `deg`, dimension 1–4, up to 6 extra control points, coordinates
/// in `[-10, 10)`.
fn curve(
    deg: std::ops::RangeInclusive<usize>,
    clamped: bool,
) -> impl Strategy<Value = BSplineCurve> {
    (deg, 1usize..=4, 0usize..=6)
        .prop_flat_map(move |(p, dim, extra)| {
            let n = p + 1 + extra;
            (
                Just((p, dim)),
                -5.0f64..5.0,
                gaps(n + p),
                prop::collection::vec(-10.0f64..10.0, n * dim),
                if clamped {
                    Just(true).boxed()
                } else {
                    any::<bool>().boxed()
                },
            )
        })
        .prop_filter_map("valid curve", |((p, dim), t0, g, ctrl, clamped)| {
            let knots = knots_from(t0, &g, p, clamped);
            BSplineCurve::new(p, knots, Points::from_flat(dim, ctrl).ok()?).ok()
        })
}

fn nurbs(deg: std::ops::RangeInclusive<usize>) -> impl Strategy<Value = NurbsCurve> {
    curve(deg, false)
        .prop_flat_map(|c| {
            let n = c.control_points().len();
            (Just(c), prop::collection::vec(0.3f64..3.0, n))
        })
        .prop_map(|(c, w)| {
            NurbsCurve::new(
                c.degree(),
                c.knots().as_slice().to_vec(),
                c.control_points().clone(),
                w,
            )
            .unwrap()
        })
}

/// A random surface: degrees 1–4, dimension 1–4, knot vectors with multiple knots (clamped or
/// not), up to 3 extra control points per direction.
fn surface() -> impl Strategy<Value = BSplineSurface> {
    (1usize..=4, 1usize..=4, 0usize..=3, 0usize..=3, 1usize..=4)
        .prop_flat_map(|(p, q, eu, ev, dim)| {
            let (nu, nv) = (p + 1 + eu, q + 1 + ev);
            (
                Just((p, q, nu, nv, dim)),
                (-5.0f64..5.0, gaps(nu + p), any::<bool>()),
                (-5.0f64..5.0, gaps(nv + q), any::<bool>()),
                prop::collection::vec(-10.0f64..10.0, nu * nv * dim),
            )
        })
        .prop_filter_map(
            "valid surface",
            |((p, q, nu, nv, dim), (u0, gu, cu), (v0, gv, cv), data)| {
                BSplineSurface::new(
                    p,
                    q,
                    knots_from(u0, &gu, p, cu),
                    knots_from(v0, &gv, q, cv),
                    Points::from_flat(dim, data).ok()?,
                    (nu, nv),
                )
                .ok()
            },
        )
}

fn nurbs_surface() -> impl Strategy<Value = NurbsSurface> {
    surface()
        .prop_flat_map(|s| {
            let n = s.control_points().len();
            (Just(s), prop::collection::vec(0.3f64..3.0, n))
        })
        .prop_map(|(s, w)| {
            NurbsSurface::new(
                s.degree_u(),
                s.degree_v(),
                s.knots_u().as_slice().to_vec(),
                s.knots_v().as_slice().to_vec(),
                s.control_points().clone(),
                w,
                s.net_size(),
            )
            .unwrap()
        })
}

fn lerp((lo, hi): (f64, f64), f: f64) -> f64 {
    (lo + (hi - lo) * f).clamp(lo, hi)
}

/// Parameters: a sweep of the domain, its ends and every knot inside it.
fn params(domain: (f64, f64), knots: &KnotVector, count: u32) -> Vec<f64> {
    let mut ts: Vec<f64> = (0..=count)
        .map(|k| lerp(domain, f64::from(k) / f64::from(count)))
        .collect();
    ts.extend(
        knots
            .as_slice()
            .iter()
            .filter(|&&k| k >= domain.0 && k <= domain.1),
    );
    ts
}

fn dist(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y) * (x - y))
        .sum::<f64>()
        .sqrt()
}

fn max_abs_diff(a: &[f64], b: &[f64]) -> f64 {
    assert_eq!(a.len(), b.len(), "lengths");
    a.iter()
        .zip(b)
        .fold(0.0_f64, |m, (x, y)| m.max((x - y).abs()))
}

/// Largest distance between two curves over `params` of the first.
fn curve_distance(a: &BSplineCurve, b: &BSplineCurve) -> f64 {
    params(a.domain(), a.knots(), 200)
        .iter()
        .map(|&t| dist(&a.eval(t).unwrap(), &b.eval(t).unwrap()))
        .fold(0.0, f64::max)
}

fn nurbs_scale(c: &NurbsCurve) -> f64 {
    c.control_points().max_abs().max(1.0)
}

/// `other` evaluates like `c` at every parameter of `ts` that lies in `other`'s domain, except
/// at a right end of `other` inside `c`'s domain (a piece there gives the left limit, `c` the
/// right value, which differ at a jump).
fn check_same_nurbs(c: &NurbsCurve, other: &NurbsCurve, ts: &[f64]) -> Result<(), TestCaseError> {
    let (lo, hi) = other.domain();
    let end = c.domain().1;
    let tol = SAME_RTOL * nurbs_scale(c);
    for &t in ts
        .iter()
        .filter(|&&t| t >= lo && t <= hi && (t < hi || t == end))
    {
        let d = max_abs_diff(&c.eval(t).unwrap(), &other.eval(t).unwrap());
        prop_assert!(d <= tol, "at t = {t}: {d:e} > {tol:e}");
    }
    Ok(())
}

/// The `(u, v)` parameters of a grid over the domain plus the interior knots.
fn grid(s: &BSplineSurface) -> (Vec<f64>, Vec<f64>) {
    let (du, dv) = s.domain();
    (params(du, s.knots_u(), 6), params(dv, s.knots_v(), 6))
}

/// `f(u, v)` equals `s(u, v)` on the grid, where `f` returns `None` outside its piece.
fn check_same_surface(
    s: &BSplineSurface,
    mut f: impl FnMut(f64, f64) -> Option<Vec<f64>>,
    what: &str,
) -> Result<(), TestCaseError> {
    let (us, vs) = grid(s);
    let tol = SAME_RTOL * s.control_points().max_abs().max(1.0);
    for &u in &us {
        for &v in &vs {
            if let Some(got) = f(u, v) {
                let d = max_abs_diff(&got, &s.eval(u, v).unwrap());
                prop_assert!(d <= tol, "{what} at ({u}, {v}): {d:e} > {tol:e}");
            }
        }
    }
    Ok(())
}

fn check_same_nurbs_surface(
    s: &NurbsSurface,
    mut f: impl FnMut(f64, f64) -> Option<Vec<f64>>,
    what: &str,
) -> Result<(), TestCaseError> {
    let h = s.homogeneous();
    let (us, vs) = grid(h);
    let tol = SAME_RTOL * s.control_points().max_abs().max(1.0);
    for &u in &us {
        for &v in &vs {
            if let Some(got) = f(u, v) {
                let d = max_abs_diff(&got, &s.eval(u, v).unwrap());
                prop_assert!(d <= tol, "{what} at ({u}, {v}): {d:e} > {tol:e}");
            }
        }
    }
    Ok(())
}

/// Reversal rounds the knots and the mirrored parameter once each: a shift of a few ulps of
/// the domain's magnitude in `u` (resp. `v`), which moves the point by that shift times the
/// partial derivative. Checks `rev(mirror(u, v)) = orig(u, v)` within `SAME_RTOL · scale` plus
/// that first-order allowance, away from jumps (where the mirrored parameter may round to the
/// other side). `derivs(u, v)` returns `(S_u, S_v)` as max-norms.
#[allow(clippy::too_many_arguments)]
fn check_reversed(
    (us, vs): (&[f64], &[f64]),
    (du, dv): ((f64, f64), (f64, f64)),
    in_u: bool,
    scale: f64,
    orig: impl Fn(f64, f64) -> Vec<f64>,
    derivs: impl Fn(f64, f64) -> (f64, f64),
    rev: impl Fn(f64, f64) -> Vec<f64>,
    jump: impl Fn(f64, f64) -> bool,
) -> Result<(), TestCaseError> {
    let ulps = 16.0 * f64::EPSILON;
    for &u in us {
        for &v in vs {
            if jump(u, v) {
                continue;
            }
            let (su, sv) = derivs(u, v);
            let (got, allowance) = if in_u {
                let shift = ulps * du.0.abs().max(du.1.abs());
                (rev((du.0 + du.1 - u).clamp(du.0, du.1), v), shift * su)
            } else {
                let shift = ulps * dv.0.abs().max(dv.1.abs());
                (rev(u, (dv.0 + dv.1 - v).clamp(dv.0, dv.1)), shift * sv)
            };
            let d = max_abs_diff(&got, &orig(u, v));
            let tol = SAME_RTOL * scale + allowance;
            prop_assert!(d <= tol, "reverse ({in_u}) at ({u}, {v}): {d:e} > {tol:e}");
        }
    }
    Ok(())
}

fn norm_inf(x: &[f64]) -> f64 {
    x.iter().fold(0.0_f64, |m, y| m.max(y.abs()))
}

fn inside((lo, hi): (f64, f64), t: f64) -> bool {
    t >= lo && t <= hi
}

/// `t` in a piece `[lo, hi]` of `domain`, but not at its right end inside the domain (the
/// piece there gives the left limit, the whole the right value; they differ at a jump).
fn in_piece((lo, hi): (f64, f64), t: f64, domain: (f64, f64)) -> bool {
    t >= lo && t <= hi && (t < hi || t == domain.1)
}

/// `t` is a knot of multiplicity `degree + 1` inside the domain (a jump).
fn is_jump(k: &KnotVector, degree: usize, (lo, hi): (f64, f64), t: f64) -> bool {
    t > lo && t < hi && k.multiplicity(t) > degree
}

/// A parameter in the middle 60 % of a non-empty span of the domain (chosen by `index`, at
/// fraction `f`): away from the existing knots, so that `α` in removal stays away from 0 and 1.
fn inside_a_span(c: &BSplineCurve, index: prop::sample::Index, f: f64) -> f64 {
    let (lo, hi) = c.domain();
    let mut breaks: Vec<f64> = c
        .knots()
        .distinct()
        .into_iter()
        .map(|(k, _)| k)
        .filter(|&k| k > lo && k < hi)
        .collect();
    breaks.insert(0, lo);
    breaks.push(hi);
    let i = index.index(breaks.len() - 1);
    lerp((breaks[i], breaks[i + 1]), 0.2 + 0.6 * f)
}

proptest! {
    #![proptest_config(config(64))]

    /// Insertion then removal returns the original knots exactly and the control points to
    /// `1e-12` relative (P&T §5.4: removal inverts insertion).
    #[test]
    fn insert_then_remove_restores(c in curve(0..=5, false), index in any::<prop::sample::Index>(), f in 0.0f64..1.0, times in 1usize..=5) {
        let p = c.degree();
        let t = inside_a_span(&c, index, f);
        let times = times.min(p);
        prop_assume!(times > 0);
        let d = c.insert_knot(t, times).unwrap();
        let (back, removed) = d.remove_knot(t, times, d.default_removal_tolerance()).unwrap();
        prop_assert_eq!(removed, times);
        prop_assert_eq!(back.knots(), c.knots());
        let scale = c.control_points().max_abs().max(1.0);
        let diff = max_abs_diff(back.control_points().as_slice(), c.control_points().as_slice());
        prop_assert!(diff <= 1e-12 * scale, "control points off by {diff:e}");
    }

    /// Removal with any tolerance (from 1e-6 to 1 times the scale) never moves the curve by
    /// more than the tolerance (sampled on 200 parameters and all knots), for one knot and for
    /// all knots at once; and removing nothing leaves the curve identical.
    #[test]
    fn removal_stays_within_tolerance(c in curve(0..=5, false), index in any::<prop::sample::Index>(), e in -6i32..=0) {
        let tol = 10f64.powi(e) * c.control_points().extent().max(1e-3);
        let (lo, hi) = c.domain();
        let interior: Vec<(f64, usize)> = c.knots().distinct().into_iter().filter(|&(k, _)| k > lo && k < hi).collect();
        prop_assume!(!interior.is_empty());
        let (t, s) = interior[index.index(interior.len())];
        let (r, removed) = c.remove_knot(t, s, tol).unwrap();
        prop_assert_eq!(r.knots().multiplicity(t), s - removed);
        if removed == 0 {
            prop_assert_eq!(&r, &c);
        }
        // the tolerance bounds the curve; 1e-12·scale covers the rounding of the evaluation
        let slack = 1e-12 * c.control_points().max_abs().max(1.0);
        let d = curve_distance(&c, &r);
        prop_assert!(d <= tol + slack, "single knot: moved {d:e} > {tol:e}");
        let (all, count) = c.remove_all_removable_knots(tol).unwrap();
        prop_assert_eq!(all.control_points().len() + count, c.control_points().len());
        let d = curve_distance(&c, &all);
        prop_assert!(d <= tol + slack, "all knots: moved {d:e} > {tol:e}");
    }

    /// Bezier decomposition and reassembly doubles the knots; `simplify` removes exactly the
    /// added copies again (the original's knots are not removable) and keeps the curve.
    #[test]
    fn simplify_undoes_bezier_reassembly(c in curve(1..=5, true)) {
        let pieces = BSplineCurve::from_bezier_segments(&c.to_bezier_segments()).unwrap();
        let (s, removed) = pieces.simplify();
        prop_assert_eq!(removed, pieces.control_points().len() - c.control_points().len());
        prop_assert_eq!(s.knots(), c.knots());
        let scale = c.control_points().max_abs().max(1.0);
        let diff = max_abs_diff(s.control_points().as_slice(), c.control_points().as_slice());
        prop_assert!(diff <= 1e-12 * scale, "control points off by {diff:e}");
    }

    /// A planted corner (the tangent turns by at least half the scale at a join of
    /// multiplicity `p`) is not removable within 1e-6 of the scale: the knot is kept and the
    /// curve is identical.
    #[test]
    fn corner_is_kept(p in 1usize..=5, dim in 1usize..=4, a in prop::collection::vec(-10.0f64..10.0, 44), kink in prop::collection::vec(5.0f64..10.0, 4), sign in any::<bool>()) {
        let a = &a[..(2 * p + 1) * dim];
        let left = Points::from_flat(dim, a[..(p + 1) * dim].to_vec()).unwrap();
        // right piece: starts at the join, its first leg = left's last leg + a kink
        let mut right = a[p * dim..(2 * p + 1) * dim].to_vec();
        let sgn = if sign { 1.0 } else { -1.0 };
        for d in 0..dim {
            let leg = a[p * dim + d] - a[(p - 1) * dim + d];
            right[dim + d] = a[p * dim + d] + leg + sgn * kink[d];
        }
        let segs = [
            BezierSegment { start: 0.0, end: 1.0, curve: BezierCurve::new(left).unwrap() },
            BezierSegment { start: 1.0, end: 2.0, curve: BezierCurve::new(Points::from_flat(dim, right).unwrap()).unwrap() },
        ];
        let c = BSplineCurve::from_bezier_segments(&segs).unwrap();
        let tol = 1e-6 * c.control_points().extent();
        let (same, removed) = c.remove_knot(1.0, p, tol).unwrap();
        prop_assert_eq!(removed, 0);
        prop_assert_eq!(&same, &c);
        let (same, removed) = c.remove_all_removable_knots(tol).unwrap();
        prop_assert_eq!(removed, 0);
        prop_assert_eq!(&same, &c);
    }

    /// Every NURBS curve operation leaves the rational curve unchanged (1e-12 relative).
    #[test]
    fn nurbs_operations_keep_the_curve(c in nurbs(0..=5), index in any::<prop::sample::Index>(), f in 0.0f64..1.0, extra in prop::collection::vec(0.0f64..=1.0, 1..5), a in -50.0f64..50.0, len in 0.5f64..50.0) {
        let h = c.homogeneous();
        let ts = params(c.domain(), c.knots(), 60);
        let p = c.degree();
        let t = inside_a_span(h, index, f);
        if p > 0 {
            let ins = c.insert_knot(t, p).unwrap();
            check_same_nurbs(&c, &ins, &ts)?;
            let (back, removed) = ins.remove_knot(t, p, ins.default_removal_tolerance()).unwrap();
            prop_assert_eq!(removed, p);
            prop_assert_eq!(back.knots(), c.knots());
            check_same_nurbs(&c, &back, &ts)?;
            let mut x: Vec<f64> = extra.iter().map(|&g| inside_a_span(h, index, g)).collect();
            x.sort_by(f64::total_cmp);
            x.truncate(p);
            check_same_nurbs(&c, &c.refine_knots(&x).unwrap(), &ts)?;
        }
        let (l, r) = c.split_at(t).unwrap();
        check_same_nurbs(&c, &l, &ts)?;
        check_same_nurbs(&c, &r, &ts)?;
        let pieces = c.to_bezier_segments();
        for piece in &pieces {
            prop_assert_eq!(piece.control_points().len(), p + 1);
            check_same_nurbs(&c, piece, &ts)?;
        }
        let (lo, hi) = c.domain();
        let rev = c.reverse().unwrap();
        let re = c.reparametrize(a, a + len).unwrap();
        let tol = SAME_RTOL * nurbs_scale(&c);
        // reversal and reparametrisation round the knots and the mapped parameter once each:
        // a shift of a few ulps of the parameters' magnitude, in the original parameter, moves
        // the point by that shift times the speed |C'(t)|
        let ulps = 16.0 * f64::EPSILON;
        let shift_rev = ulps * lo.abs().max(hi.abs());
        let shift_re = shift_rev + ulps * a.abs().max((a + len).abs()) * (hi - lo) / len;
        let jump = |t: f64| t > lo && t < hi && c.knots().multiplicity(t) > p;
        // at a jump the mirrored or mapped parameter may round to the other side's value
        for &t in ts.iter().filter(|&&t| !jump(t)) {
            let speed = c.eval_derivatives(t, 1).unwrap();
            let speed = speed.point(1).iter().fold(0.0_f64, |m, x| m.max(x.abs()));
            let d = max_abs_diff(&rev.eval((lo + hi - t).clamp(lo, hi)).unwrap(), &c.eval(t).unwrap());
            prop_assert!(d <= tol + shift_rev * speed, "reverse at {t}: {d:e}");
            let s = (a + (t - lo) * len / (hi - lo)).clamp(a, a + len);
            let d = max_abs_diff(&re.eval(s).unwrap(), &c.eval(t).unwrap());
            prop_assert!(d <= tol + shift_re * speed, "reparametrize at {t}: {d:e}");
        }
        // removal with a tolerance moves the rational curve by at most the tolerance
        let tol = 1e-3 * c.control_points().extent().max(1e-3);
        let (lo2, hi2) = c.domain();
        if let Some((k, s)) = c.knots().distinct().into_iter().find(|&(k, _)| k > lo2 && k < hi2) {
            let (r, _) = c.remove_knot(k, s, tol).unwrap();
            let slack = 1e-12 * nurbs_scale(&c);
            for &t in &ts {
                let d = dist(&r.eval(t).unwrap(), &c.eval(t).unwrap());
                prop_assert!(d <= tol + slack, "removal moved {d:e} > {tol:e}");
            }
        }
    }
}

proptest! {
    #![proptest_config(config(48))]

    /// Knot insertion, refinement, splitting, Bezier patches, transposition and reversal leave
    /// a B-spline surface unchanged (1e-12 relative).
    #[test]
    fn surface_operations_keep_the_surface(s in surface(), fu in 0.0f64..=1.0, fv in 0.0f64..=1.0, times in 1usize..=4) {
        let (du, dv) = s.domain();
        let (u, v) = (lerp(du, fu), lerp(dv, fv));
        let (p, q) = (s.degree_u(), s.degree_v());
        let tu = times.min(p.saturating_sub(s.knots_u().multiplicity(u)));
        let ins = s.insert_knot_u(u, tu).unwrap();
        prop_assert_eq!(ins.net_size().0, s.net_size().0 + tu);
        check_same_surface(&s, |a, b| Some(ins.eval(a, b).unwrap()), "insert_knot_u")?;
        let tv = times.min(q.saturating_sub(s.knots_v().multiplicity(v)));
        let ins = s.insert_knot_v(v, tv).unwrap();
        prop_assert_eq!(ins.net_size().1, s.net_size().1 + tv);
        check_same_surface(&s, |a, b| Some(ins.eval(a, b).unwrap()), "insert_knot_v")?;
        let xu = vec![u; tu];
        let xv = vec![v; tv];
        let refined = s.refine_knots_u(&xu).unwrap().refine_knots_v(&xv).unwrap();
        check_same_surface(&s, |a, b| Some(refined.eval(a, b).unwrap()), "refine")?;
        if u > du.0 && u < du.1 {
            let (l, r) = s.split_at_u(u).unwrap();
            check_same_surface(&s, |a, b| in_piece(l.domain().0, a, du).then(|| l.eval(a, b).unwrap()), "split_u left")?;
            check_same_surface(&s, |a, b| inside(r.domain().0, a).then(|| r.eval(a, b).unwrap()), "split_u right")?;
        }
        if v > dv.0 && v < dv.1 {
            let (l, r) = s.split_at_v(v).unwrap();
            check_same_surface(&s, |a, b| in_piece(l.domain().1, b, dv).then(|| l.eval(a, b).unwrap()), "split_v left")?;
            check_same_surface(&s, |a, b| inside(r.domain().1, b).then(|| r.eval(a, b).unwrap()), "split_v right")?;
        }
        let patches = s.to_bezier_patches();
        let spans = |k: &KnotVector, d: (f64, f64)| k.distinct().into_iter().filter(|&(x, _)| x >= d.0 && x <= d.1).count() - 1;
        prop_assert_eq!(patches.len(), spans(s.knots_u(), du) * spans(s.knots_v(), dv));
        for (ur, vr, patch) in &patches {
            prop_assert_eq!(patch.net_size(), (p + 1, q + 1));
            check_same_surface(&s, |a, b| {
                (in_piece(*ur, a, du) && in_piece(*vr, b, dv)).then(|| {
                    let local = |t: f64, (lo, hi): (f64, f64)| ((t - lo) / (hi - lo)).clamp(0.0, 1.0);
                    patch.eval(local(a, *ur), local(b, *vr)).unwrap()
                })
            }, "Bezier patch")?;
        }
        let t = s.transpose();
        check_same_surface(&s, |a, b| Some(t.eval(b, a).unwrap()), "transpose")?;
        prop_assert_eq!(t.transpose(), s.clone());
        let ru = s.reverse_u().unwrap();
        let rv = s.reverse_v().unwrap();
        // the reversed knots are rounded once; compare at the mirrored parameters
        let (us, vs) = grid(&s);
        let scale = s.control_points().max_abs().max(1.0);
        let derivs = |a: f64, b: f64| {
            let d = s.eval_derivatives(a, b, 1).unwrap();
            (norm_inf(d.point(2)), norm_inf(d.point(1)))
        };
        let orig = |a: f64, b: f64| s.eval(a, b).unwrap();
        check_reversed((&us, &vs), (du, dv), true, scale, orig, derivs, |a, b| ru.eval(a, b).unwrap(), |a, _| is_jump(s.knots_u(), p, du, a))?;
        check_reversed((&us, &vs), (du, dv), false, scale, orig, derivs, |a, b| rv.eval(a, b).unwrap(), |_, b| is_jump(s.knots_v(), q, dv, b))?;
    }

    /// The same operations on a NURBS surface leave the rational surface unchanged.
    #[test]
    fn nurbs_surface_operations_keep_the_surface(s in nurbs_surface(), fu in 0.0f64..=1.0, fv in 0.0f64..=1.0) {
        let h = s.homogeneous();
        let (du, dv) = h.domain();
        let (u, v) = (lerp(du, fu), lerp(dv, fv));
        let tu = h.degree_u().saturating_sub(h.knots_u().multiplicity(u));
        let tv = h.degree_v().saturating_sub(h.knots_v().multiplicity(v));
        let ins = s.insert_knot_u(u, tu).unwrap().insert_knot_v(v, tv).unwrap();
        check_same_nurbs_surface(&s, |a, b| Some(ins.eval(a, b).unwrap()), "insert")?;
        let refined = s.refine_knots_u(&vec![u; tu]).unwrap().refine_knots_v(&vec![v; tv]).unwrap();
        check_same_nurbs_surface(&s, |a, b| Some(refined.eval(a, b).unwrap()), "refine")?;
        if u > du.0 && u < du.1 {
            let (l, r) = s.split_at_u(u).unwrap();
            check_same_nurbs_surface(&s, |a, b| in_piece(l.domain().0, a, du).then(|| l.eval(a, b).unwrap()), "split_u left")?;
            check_same_nurbs_surface(&s, |a, b| inside(r.domain().0, a).then(|| r.eval(a, b).unwrap()), "split_u right")?;
        }
        if v > dv.0 && v < dv.1 {
            let (l, r) = s.split_at_v(v).unwrap();
            check_same_nurbs_surface(&s, |a, b| in_piece(l.domain().1, b, dv).then(|| l.eval(a, b).unwrap()), "split_v left")?;
            check_same_nurbs_surface(&s, |a, b| inside(r.domain().1, b).then(|| r.eval(a, b).unwrap()), "split_v right")?;
        }
        for (ur, vr, patch) in &s.to_bezier_patches() {
            prop_assert_eq!(patch.domain(), (*ur, *vr));
            check_same_nurbs_surface(&s, |a, b| (in_piece(*ur, a, du) && in_piece(*vr, b, dv)).then(|| patch.eval(a, b).unwrap()), "rational patch")?;
        }
        let t = s.transpose();
        check_same_nurbs_surface(&s, |a, b| Some(t.eval(b, a).unwrap()), "transpose")?;
        let ru = s.reverse_u().unwrap();
        let rv = s.reverse_v().unwrap();
        let (us, vs) = grid(h);
        let scale = s.control_points().max_abs().max(1.0);
        let derivs = |a: f64, b: f64| {
            let d = s.eval_derivatives(a, b, 1).unwrap();
            (norm_inf(d.point(2)), norm_inf(d.point(1)))
        };
        let orig = |a: f64, b: f64| s.eval(a, b).unwrap();
        check_reversed((&us, &vs), (du, dv), true, scale, orig, derivs, |a, b| ru.eval(a, b).unwrap(), |a, _| is_jump(h.knots_u(), h.degree_u(), du, a))?;
        check_reversed((&us, &vs), (du, dv), false, scale, orig, derivs, |a, b| rv.eval(a, b).unwrap(), |_, b| is_jump(h.knots_v(), h.degree_v(), dv, b))?;
    }
}

// ---- golden and negative tests ----

fn quadratic() -> BSplineCurve {
    BSplineCurve::new(
        2,
        vec![0.0, 0.0, 0.0, 0.5, 0.5, 1.0, 1.0, 1.0],
        Points::from_flat(1, vec![0.0, 1.0, 3.0, 2.0, 5.0]).unwrap(),
    )
    .unwrap()
}

#[test]
fn remove_knot_errors() {
    let c = quadratic();
    assert!(matches!(
        c.remove_knot(0.5, 1, f64::NAN),
        Err(Error::NonFinite { what, .. }) if what.words() == "tolerance"
    ));
    assert!(matches!(
        c.remove_knot(0.5, 1, f64::INFINITY),
        Err(Error::NonFinite { .. })
    ));
    assert!(matches!(
        c.remove_knot(0.5, 1, -1.0),
        Err(Error::InvalidArgument { what, .. }) if what.words() == "tolerance"
    ));
    assert!(matches!(
        c.remove_knot(1.5, 1, 0.1),
        Err(Error::ParameterOutOfDomain { .. })
    ));
    assert!(matches!(
        c.remove_knot(f64::NAN, 1, 0.1),
        Err(Error::ParameterOutOfDomain { .. })
    ));
    assert!(matches!(
        c.remove_knot(1.0, 1, 0.1),
        Err(Error::InvalidArgument { what, .. }) if what.words() == "knot to remove"
    ));
    assert!(matches!(
        c.remove_knot(0.25, 1, 0.1),
        Err(Error::InvalidArgument { what, .. }) if what.words() == "knot to remove"
    ));
    assert!(matches!(
        c.remove_knot(0.5, 3, 0.1),
        Err(Error::InvalidArgument { what, .. }) if what.words() == "knot removal count"
    ));
    assert!(matches!(
        c.remove_all_removable_knots(f64::NAN),
        Err(Error::NonFinite { .. })
    ));
    assert!(matches!(
        c.remove_all_removable_knots(-0.5),
        Err(Error::InvalidArgument { .. })
    ));
    // times = 0 removes nothing
    assert_eq!(c.remove_knot(0.5, 0, 0.1).unwrap(), (c.clone(), 0));
}

#[test]
fn removal_golden_quadratic() {
    // P&T eq. 5.28 by hand: p = 2, knots [0,0,0,.5,.5,1,1,1], points 0 1 3 2 5. Removing one
    // copy of 0.5 (r = 4, s = 2) changes P_2 only: first = last = 2, the left sweep keeps
    // L_1 = P_1 = 1, the right sweep R_2 = P_3 = 2, so Q = 0 1 2 5 on [0,0,0,.5,1,1,1].
    // Re-inserting 0.5 gives 0 1 1.5 2 5 (α = 1/2): the bound is |3 − 1.5| = 1.5, attained at
    // t = 0.5 where N_2 = 1 (C(0.5) = P_2 = 3, C̃(0.5) = 1.5).
    let c = quadratic();
    let (r, removed) = c.remove_knot(0.5, 1, 1.5).unwrap();
    assert_eq!(removed, 1);
    assert_eq!(r.knots().as_slice(), &[0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0]);
    assert_eq!(r.control_points().as_slice(), &[0.0, 1.0, 2.0, 5.0]);
    assert_eq!(r.eval(0.5).unwrap(), vec![1.5]);
    assert!(
        (curve_distance(&c, &r) - 1.5).abs() < 1e-15,
        "the bound is attained"
    );
    assert_eq!(
        c.remove_knot(0.5, 1, 1.49).unwrap().1,
        0,
        "1.5 > 1.49: kept"
    );
}

#[test]
fn nurbs_errors() {
    let c = NurbsCurve::circle(&[0.0, 0.0], &[1.0, 0.0], &[0.0, 1.0], 1.0).unwrap();
    assert!(matches!(
        c.insert_knot(2.0, 1),
        Err(Error::ParameterOutOfDomain { .. })
    ));
    assert!(matches!(
        c.insert_knot(0.25, 1),
        Err(Error::InvalidArgument { .. })
    ));
    assert!(matches!(
        c.refine_knots(&[0.3, 0.1]),
        Err(Error::KnotsNotSorted { .. })
    ));
    assert!(matches!(
        c.refine_knots(&[f64::NAN]),
        Err(Error::NonFinite { .. })
    ));
    assert!(matches!(
        c.refine_knots(&[1.5]),
        Err(Error::ParameterOutOfDomain { .. })
    ));
    assert!(matches!(
        c.refine_knots(&[0.5]),
        Err(Error::InvalidArgument { .. })
    ));
    assert!(matches!(
        c.split_at(0.0),
        Err(Error::InvalidArgument { .. })
    ));
    assert!(matches!(
        c.split_at(-1.0),
        Err(Error::ParameterOutOfDomain { .. })
    ));
    assert!(matches!(
        c.reparametrize(1.0, 0.0),
        Err(Error::EmptyDomain { .. })
    ));
    assert!(matches!(
        c.reparametrize(f64::NAN, 1.0),
        Err(Error::NonFinite { .. })
    ));
    assert!(matches!(
        c.remove_knot(0.5, 1, -1.0),
        Err(Error::InvalidArgument { .. })
    ));
    assert!(matches!(
        c.remove_knot(0.5, 1, f64::NAN),
        Err(Error::NonFinite { .. })
    ));
    assert!(matches!(
        c.remove_knot(0.5, 3, 1.0),
        Err(Error::InvalidArgument { .. })
    ));
    assert!(matches!(
        c.remove_knot(0.3, 1, 1.0),
        Err(Error::InvalidArgument { .. })
    ));
    assert!(matches!(
        c.remove_knot(3.0, 1, 1.0),
        Err(Error::ParameterOutOfDomain { .. })
    ));
    assert!(matches!(
        c.remove_all_removable_knots(-1.0),
        Err(Error::InvalidArgument { .. })
    ));
    // knots 1e-20 apart merge when mirrored
    let tiny = NurbsCurve::new(
        1,
        vec![0.0, 1e-20, 2e-20, 1.0, 1.0],
        Points::from_flat(1, vec![0.0, 1.0, 2.0]).unwrap(),
        vec![1.0, 2.0, 1.0],
    )
    .unwrap();
    assert!(matches!(
        tiny.reverse(),
        Err(Error::KnotMultiplicity { .. })
    ));
}

#[test]
fn circle_pieces_and_simplification() {
    let c = NurbsCurve::circle(&[1.0, -2.0], &[1.0, 0.0], &[0.0, 1.0], 3.0).unwrap();
    let pieces = c.to_bezier_segments();
    assert_eq!(pieces.len(), 4);
    for piece in &pieces {
        let (lo, hi) = piece.domain();
        for k in 0..=10 {
            let p = piece.eval(lerp((lo, hi), f64::from(k) / 10.0)).unwrap();
            assert!(
                ((p[0] - 1.0).hypot(p[1] + 2.0) - 3.0).abs() < 1e-14,
                "on the circle"
            );
        }
    }
    // the circle's double knots are C^1 joins of exact quarter arcs: nothing is removable
    assert_eq!(c.remove_all_removable_knots(1e-6).unwrap().1, 0);
    let refined = c.refine_knots(&[0.1, 0.6, 0.6]).unwrap();
    let (back, removed) = refined
        .remove_all_removable_knots(refined.default_removal_tolerance())
        .unwrap();
    assert_eq!(removed, 3);
    assert_eq!(back.knots(), c.knots());
}

fn small_surface() -> BSplineSurface {
    let net = Points::from_flat(1, (0..4 * 3).map(|k| f64::from(k).sin()).collect()).unwrap();
    BSplineSurface::new(
        2,
        1,
        vec![0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0],
        vec![0.0, 0.0, 0.5, 1.0, 1.0],
        net,
        (4, 3),
    )
    .unwrap()
}

#[test]
fn surface_errors() {
    let s = small_surface();
    assert!(matches!(
        s.insert_knot_u(2.0, 1),
        Err(Error::ParameterOutOfDomain { .. })
    ));
    assert!(matches!(
        s.insert_knot_u(0.5, 2),
        Err(Error::InvalidArgument { .. })
    ));
    assert!(matches!(
        s.insert_knot_v(-1.0, 1),
        Err(Error::ParameterOutOfDomain { .. })
    ));
    assert!(matches!(
        s.insert_knot_v(0.5, 1),
        Err(Error::InvalidArgument { .. })
    ));
    assert!(matches!(
        s.refine_knots_u(&[0.6, 0.2]),
        Err(Error::KnotsNotSorted { .. })
    ));
    assert!(matches!(
        s.refine_knots_u(&[f64::INFINITY]),
        Err(Error::NonFinite { .. })
    ));
    assert!(matches!(
        s.refine_knots_u(&[1.5]),
        Err(Error::ParameterOutOfDomain { .. })
    ));
    assert!(matches!(
        s.refine_knots_u(&[0.5, 0.5]),
        Err(Error::InvalidArgument { .. })
    ));
    assert!(matches!(
        s.refine_knots_v(&[0.6, 0.2]),
        Err(Error::KnotsNotSorted { .. })
    ));
    assert!(matches!(
        s.refine_knots_v(&[f64::NAN]),
        Err(Error::NonFinite { .. })
    ));
    assert!(matches!(
        s.refine_knots_v(&[1.5]),
        Err(Error::ParameterOutOfDomain { .. })
    ));
    assert!(matches!(
        s.refine_knots_v(&[0.5]),
        Err(Error::InvalidArgument { .. })
    ));
    assert!(matches!(
        s.split_at_u(0.0),
        Err(Error::InvalidArgument { .. })
    ));
    assert!(matches!(
        s.split_at_u(1.5),
        Err(Error::ParameterOutOfDomain { .. })
    ));
    assert!(matches!(
        s.split_at_v(1.0),
        Err(Error::InvalidArgument { .. })
    ));
    assert!(matches!(
        s.split_at_v(f64::NAN),
        Err(Error::ParameterOutOfDomain { .. })
    ));
    // knots 1e-20 apart merge when mirrored
    let tiny = BSplineSurface::new(
        1,
        1,
        vec![0.0, 1e-20, 2e-20, 1.0, 1.0],
        vec![0.0, 1e-20, 2e-20, 1.0, 1.0],
        Points::from_flat(1, vec![0.0; 9]).unwrap(),
        (3, 3),
    )
    .unwrap();
    assert!(matches!(
        tiny.reverse_u(),
        Err(Error::KnotMultiplicity { .. })
    ));
    assert!(matches!(
        tiny.reverse_v(),
        Err(Error::KnotMultiplicity { .. })
    ));
    let w = NurbsSurface::from_bspline(&tiny);
    assert!(matches!(w.reverse_u(), Err(Error::KnotMultiplicity { .. })));
    assert!(matches!(w.reverse_v(), Err(Error::KnotMultiplicity { .. })));
    let n = NurbsSurface::from_bspline(&s);
    assert!(matches!(
        n.insert_knot_u(2.0, 1),
        Err(Error::ParameterOutOfDomain { .. })
    ));
    assert!(matches!(
        n.insert_knot_v(0.5, 1),
        Err(Error::InvalidArgument { .. })
    ));
    assert!(matches!(
        n.refine_knots_u(&[0.6, 0.2]),
        Err(Error::KnotsNotSorted { .. })
    ));
    assert!(matches!(
        n.refine_knots_v(&[f64::NAN]),
        Err(Error::NonFinite { .. })
    ));
    assert!(matches!(
        n.split_at_u(1.0),
        Err(Error::InvalidArgument { .. })
    ));
    assert!(matches!(
        n.split_at_v(2.0),
        Err(Error::ParameterOutOfDomain { .. })
    ));
}

#[test]
fn surface_golden_patches() {
    // u: [0,0,0,0.5,1,1,1] (two spans), v: [0,0,0.5,1,1] (two spans) → 4 patches, u-major
    let s = small_surface();
    let patches = s.to_bezier_patches();
    let ranges: Vec<_> = patches.iter().map(|(u, v, _)| (*u, *v)).collect();
    assert_eq!(
        ranges,
        vec![
            ((0.0, 0.5), (0.0, 0.5)),
            ((0.0, 0.5), (0.5, 1.0)),
            ((0.5, 1.0), (0.0, 0.5)),
            ((0.5, 1.0), (0.5, 1.0)),
        ]
    );
    // corners of the net are interpolated by a clamped surface: patch 0 starts at P_{0,0}
    assert_eq!(
        patches[0].2.control_point(0, 0).unwrap(),
        s.control_point(0, 0).unwrap()
    );
    assert_eq!(
        patches[3].2.control_point(2, 1).unwrap(),
        s.control_point(3, 2).unwrap()
    );
    // v is linear with a simple knot at 0.5: the v-join point is the middle column itself
    assert_eq!(
        patches[0].2.control_point(0, 1).unwrap(),
        s.control_point(0, 1).unwrap()
    );
}
