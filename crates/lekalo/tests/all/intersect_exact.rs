//! Intersections against exact answers (`tests/data/intersect_exact.json`, made by
//! `tests/data/intersect_exact.py` with rational and 60-digit arithmetic): parameters within
//! 16 units in the last place for crossings and 64 for tangent contacts, and the kind of each
//! contact; then contacts and overlaps built with known answers, and property tests.

use lekalo::query::{Contact, CurveIntersection, PlaneIntersection, SurfaceIntersection};
use lekalo::{BSplineCurve, BSplineSurface, NurbsCurve, Points, QueryCurve, QuerySurface};
use proptest::prelude::*;
use serde_json::Value;

/// Units in the last place between `x` and the exact `exact`: the difference over the spacing
/// of doubles at `exact` (the larger spacing either side, so that a power of two is fair).
fn ulps(x: f64, exact: f64) -> f64 {
    let bits = exact.abs().to_bits();
    let up = f64::from_bits(bits + 1) - exact.abs();
    let down = exact.abs() - f64::from_bits(bits.saturating_sub(1));
    let spacing = if exact == 0.0 {
        f64::MIN_POSITIVE
    } else {
        up.max(down)
    };
    (x - exact).abs() / spacing
}

fn bezier(pts: &[Vec<f64>]) -> QueryCurve {
    let n = pts.len();
    let mut knots = vec![0.0; n];
    knots.extend(vec![1.0; n]);
    let c =
        BSplineCurve::new(n - 1, knots, Points::from_rows(pts).expect("points")).expect("curve");
    QueryCurve::from_bspline(&c).expect("query curve")
}

fn rows(v: &Value) -> Vec<Vec<f64>> {
    v.as_array()
        .expect("points")
        .iter()
        .map(|p| {
            p.as_array()
                .expect("point")
                .iter()
                .map(|x| x.as_f64().expect("coordinate"))
                .collect()
        })
        .collect()
}

fn circle(centre: [f64; 2], r: f64) -> QueryCurve {
    QueryCurve::from_nurbs(
        &NurbsCurve::circle(&centre, &[1.0, 0.0], &[0.0, 1.0], r).expect("circle"),
    )
    .expect("query curve")
}

#[test]
fn golden_cases_to_the_last_bits() {
    let cases: Value =
        serde_json::from_str(include_str!("../data/intersect_exact.json")).expect("golden parses");
    let mut worst = (0.0_f64, 0.0_f64);
    for case in cases.as_array().expect("cases") {
        let name = case["name"].as_str().expect("name");
        let (a, b) = (bezier(&rows(&case["a"])), bezier(&rows(&case["b"])));
        let hits = a.intersect(&b, 1e-9).expect("intersection");
        let want = case["hits"].as_array().expect("hits");
        assert_eq!(hits.len(), want.len(), "{name}: {hits:?}");
        for (h, w) in hits.iter().zip(want) {
            let CurveIntersection::Point {
                t_a, t_b, contact, ..
            } = h
            else {
                panic!("{name}: an overlap {hits:?}")
            };
            let kind = w["kind"].as_str().expect("kind");
            assert_eq!(contact.name(), kind, "{name}: {h:?}");
            if let Some(order) = w.get("order") {
                assert_eq!(
                    contact.order(),
                    order.as_u64().and_then(|o| u32::try_from(o).ok()),
                    "{name}: {h:?}"
                );
            }
            let limit = if kind == "tangent" { 64.0 } else { 16.0 };
            let (ea, eb) = (
                w["t_a"].as_f64().expect("t_a"),
                w["t_b"].as_f64().expect("t_b"),
            );
            let (ua, ub) = (ulps(*t_a, ea), ulps(*t_b, eb));
            assert!(
                ua <= limit && ub <= limit,
                "{name}: t_a {t_a} vs {ea} ({ua} ulps), t_b {t_b} vs {eb} ({ub} ulps)"
            );
            if kind == "tangent" {
                worst.0 = worst.0.max(ua.max(ub));
            } else {
                worst.1 = worst.1.max(ua.max(ub));
            }
        }
    }
    eprintln!("worst ulps: tangent {}, crossing {}", worst.0, worst.1);
}

#[test]
fn touching_circles_are_one_tangent_point_at_the_knot() {
    // the unit circle and the circle of radius 1 about (0, 2) touch at (0, 1): the knot 1/4 of
    // the first (its quarter point) and 3/4 of the second
    let hits = circle([0.0, 0.0], 1.0)
        .intersect(&circle([0.0, 2.0], 1.0), 1e-9)
        .expect("x");
    assert_eq!(hits.len(), 1, "{hits:?}");
    let CurveIntersection::Point {
        t_a,
        t_b,
        point,
        contact,
    } = &hits[0]
    else {
        panic!("{hits:?}")
    };
    assert_eq!(*contact, Contact::Tangent { order: 1 }, "{hits:?}");
    assert!(
        ulps(*t_a, 0.25) <= 64.0 && ulps(*t_b, 0.75) <= 64.0,
        "{t_a} {t_b}"
    );
    assert!(
        point[0].abs() <= 1e-15 && (point[1] - 1.0).abs() <= 4.0 * f64::EPSILON,
        "{point:?}"
    );
    // inside: the circle of radius 2 about (0, -1) touches the unit circle at (0, 1) from outside
    let hits = circle([0.0, 0.0], 1.0)
        .intersect(&circle([0.0, -1.0], 2.0), 1e-9)
        .expect("x");
    assert_eq!(hits.len(), 1, "{hits:?}");
    assert_eq!(hits[0].contact(), Contact::Tangent { order: 1 }, "{hits:?}");
}

#[test]
fn near_tangent_pairs_are_told_apart() {
    // the parabola y = x² and the lines y = c near its tangent y = 0 at its vertex
    let parabola = bezier(&[vec![-1.0, 1.0], vec![0.0, -1.0], vec![1.0, 1.0]]);
    let line = |c: f64| bezier(&[vec![-2.0, c], vec![2.0, c]]);
    // a touch
    let hits = parabola.intersect(&line(0.0), 1e-9).expect("x");
    assert_eq!(hits.len(), 1, "{hits:?}");
    assert_eq!(hits[0].contact(), Contact::Tangent { order: 1 }, "{hits:?}");
    // a near miss 1e-11 below: its gap
    let hits = parabola.intersect(&line(-1e-11), 1e-9).expect("x");
    assert_eq!(hits.len(), 1, "{hits:?}");
    let Contact::NearMiss { gap } = hits[0].contact() else {
        panic!("{hits:?}")
    };
    assert!((gap - 1e-11).abs() <= 1e-20, "{gap}");
    // 1e-12 above: two crossings at x = ±1e-6, t = (1 ± 1e-6)/2
    let hits = parabola.intersect(&line(1e-12), 1e-9).expect("x");
    assert_eq!(hits.len(), 2, "{hits:?}");
    for (h, x) in hits.iter().zip([-1e-6, 1e-6]) {
        let CurveIntersection::Point { point, contact, .. } = h else {
            panic!("{hits:?}")
        };
        assert_eq!(*contact, Contact::Crossing, "{hits:?}");
        assert!(
            (point[0] - x).abs() <= 1e-15 && (point[1] - 1e-12).abs() <= 1e-20,
            "{point:?}"
        );
    }
    // farther than the tolerance: nothing
    assert!(parabola
        .intersect(&line(-1e-8), 1e-9)
        .expect("x")
        .is_empty());
}

#[test]
fn end_to_end_contact_is_an_end() {
    let a = bezier(&[vec![0.0, 0.0], vec![1.0, 1.0]]);
    let b = bezier(&[vec![1.0, 1.0], vec![2.0, 0.0]]);
    let hits = a.intersect(&b, 1e-9).expect("x");
    assert_eq!(hits.len(), 1, "{hits:?}");
    assert_eq!(hits[0].contact(), Contact::End, "{hits:?}");
    // a T: the second ends on the first's middle
    let c = bezier(&[vec![0.5, 0.5], vec![1.0, 0.0]]);
    assert_eq!(a.intersect(&c, 1e-9).expect("x")[0].contact(), Contact::End);
}

fn cubic_3d() -> Vec<[f64; 3]> {
    vec![
        [0.0, 0.0, 2.0],
        [1.0, 2.0, 2.0],
        [2.0, -1.0, 2.0],
        [3.0, 0.5, 2.0],
    ]
}

fn bspline_3d(pts: &[[f64; 3]]) -> BSplineCurve {
    let n = pts.len();
    let mut knots = vec![0.0; n];
    knots.extend(vec![1.0; n]);
    BSplineCurve::new(n - 1, knots, Points::from_3d(pts).expect("points")).expect("curve")
}

#[test]
fn a_cubic_in_a_plane_overlaps_it_over_its_domain() {
    let q = QueryCurve::from_bspline(&bspline_3d(&cubic_3d())).expect("q");
    let hits = q
        .intersect_plane(&[5.0, -7.0, 2.0], &[0.0, 0.0, 3.0])
        .expect("x");
    assert_eq!(hits, vec![PlaneIntersection::Overlap { t: (0.0, 1.0) }]);
    // a B-spline of two pieces, the second leaving the plane: the overlap is the first piece
    let c = BSplineCurve::new(
        1,
        vec![0.0, 0.0, 0.5, 1.0, 1.0],
        Points::from_3d(&[[0.0, 0.0, 2.0], [1.0, 0.0, 2.0], [1.0, 0.0, 3.0]]).expect("p"),
    )
    .expect("c");
    let hits = QueryCurve::from_bspline(&c)
        .expect("q")
        .intersect_plane(&[0.0, 0.0, 2.0], &[0.0, 0.0, 1.0])
        .expect("x");
    assert_eq!(hits, vec![PlaneIntersection::Overlap { t: (0.0, 0.5) }]);
}

#[test]
fn space_curves_overlap_on_their_common_part() {
    // the cubic and its part over [1/4, 1] (de Casteljau split, exact in binary; the part keeps
    // the cubic's parameter): an overlap of [1/4, 1] on both
    let c = bspline_3d(&cubic_3d());
    let part = c.split_at(0.25).expect("split").1;
    let (qa, qb) = (
        QueryCurve::from_bspline(&c).expect("a"),
        QueryCurve::from_bspline(&part).expect("b"),
    );
    let hits = qa.intersect(&qb, 1e-9).expect("x");
    assert_eq!(hits.len(), 1, "{hits:?}");
    let CurveIntersection::Overlap { a, b } = hits[0] else {
        panic!("{hits:?}")
    };
    assert!(
        (a.0 - 0.25).abs() <= 1e-14 && (a.1 - 1.0).abs() <= 1e-14,
        "{a:?}"
    );
    assert!(
        (b.0 - 0.25).abs() <= 1e-14 && (b.1 - 1.0).abs() <= 1e-14,
        "{b:?}"
    );
    // a space line through the cubic's point at t = 1/2, across it: one crossing
    let p = qa.point(0.5).expect("p");
    let across = bspline_3d(&[
        [p[0], p[1] - 1.0, p[2] - 1.0],
        [p[0], p[1] + 1.0, p[2] + 1.0],
    ]);
    let hits = qa
        .intersect(&QueryCurve::from_bspline(&across).expect("q"), 1e-9)
        .expect("x");
    assert_eq!(hits.len(), 1, "{hits:?}");
    let CurveIntersection::Point {
        t_a, t_b, contact, ..
    } = hits[0]
    else {
        panic!("{hits:?}")
    };
    assert_eq!(contact, Contact::Crossing);
    assert!(
        (t_a - 0.5).abs() <= 1e-12 && (t_b - 0.5).abs() <= 1e-12,
        "{t_a} {t_b}"
    );
}

#[test]
fn an_iso_curve_overlaps_its_surface() {
    // a bicubic patch and its iso-curve u = 1/2 (the net's columns evaluated at 1/2 exactly)
    let mut net = Vec::new();
    for i in 0..4 {
        for j in 0..4 {
            let (x, y) = (f64::from(i), f64::from(j));
            net.push([x, y, ((i * 3 + j * 5) % 4) as f64 - 1.5]);
        }
    }
    let knots = vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0];
    let s = BSplineSurface::new(
        3,
        3,
        knots.clone(),
        knots,
        Points::from_3d(&net).expect("net"),
        (4, 4),
    )
    .expect("surface");
    let iso: Vec<[f64; 3]> = (0..4)
        .map(|j| {
            let col = |i: usize| net[i * 4 + j];
            let w = [0.125, 0.375, 0.375, 0.125];
            let mut p = [0.0; 3];
            for (i, wi) in w.iter().enumerate() {
                for d in 0..3 {
                    p[d] += wi * col(i)[d];
                }
            }
            p
        })
        .collect();
    let qs = QuerySurface::from_bspline(&s).expect("qs");
    let hits = QueryCurve::from_bspline(&bspline_3d(&iso))
        .expect("q")
        .intersect_surface(&qs, 1e-9)
        .expect("x");
    assert_eq!(hits.len(), 1, "{hits:?}");
    let SurfaceIntersection::Overlap { t, uv } = hits[0] else {
        panic!("{hits:?}")
    };
    assert_eq!(t, (0.0, 1.0));
    assert!(
        (uv.0 .0 - 0.5).abs() <= 1e-9 && uv.0 .1.abs() <= 1e-9,
        "{uv:?}"
    );
    assert!(
        (uv.1 .0 - 0.5).abs() <= 1e-9 && (uv.1 .1 - 1.0).abs() <= 1e-9,
        "{uv:?}"
    );
    // a line through the patch: one crossing
    let p = qs.project(&[1.5, 1.5, 0.0]).expect("p").point;
    let line = bspline_3d(&[
        [p[0] + 0.1, p[1], p[2] - 3.0],
        [p[0] - 0.1, p[1], p[2] + 3.0],
    ]);
    let hits = QueryCurve::from_bspline(&line)
        .expect("q")
        .intersect_surface(&qs, 1e-9)
        .expect("x");
    assert_eq!(hits.len(), 1, "{hits:?}");
    assert_eq!(hits[0].contact(), Contact::Crossing, "{hits:?}");
}

proptest! {
    #![proptest_config(lekalo_testkit::config(48))]

    /// A cubic and a copy of it moved along itself (its part over [s, 1] against its part over
    /// [0, e], e > s): one overlap, whose ends are the parts' shared stretch.
    #[test]
    fn a_curve_and_a_shifted_part_of_itself_overlap(
        ctrl in proptest::collection::vec(proptest::array::uniform2(-10.0..10.0_f64), 4),
        s in 0.1..0.4_f64,
        e in 0.6..0.9_f64,
    ) {
        let rows: Vec<[f64; 2]> = ctrl.clone();
        let c = BSplineCurve::new(3, vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0], Points::from_2d(&rows).expect("p")).expect("c");
        let length = QueryCurve::from_bspline(&c).expect("q").length().expect("length");
        prop_assume!(length > 1.0);
        let right = c.split_at(s).expect("split").1;
        let left = c.split_at(e).expect("split").0;
        let (qa, qb) = (QueryCurve::from_bspline(&right).expect("a"), QueryCurve::from_bspline(&left).expect("b"));
        let hits = qa.intersect(&qb, 1e-9).expect("x");
        // the parts keep the cubic's parameter: the shared stretch is [s, e] on both; a
        // self-crossing of the cubic may add points
        let overlaps: Vec<_> = hits.iter().filter_map(|h| match h {
            CurveIntersection::Overlap { a, b } => Some((*a, *b)),
            CurveIntersection::Point { .. } => None,
        }).collect();
        prop_assert_eq!(overlaps.len(), 1, "{:?}", hits);
        let (a, b) = overlaps[0];
        prop_assert!((a.0 - s).abs() <= 1e-12 && (a.1 - e).abs() <= 1e-12, "{:?}", a);
        prop_assert!((b.0 - s).abs() <= 1e-12 && (b.1 - e).abs() <= 1e-12, "{:?}", b);
    }

    /// A random quadratic and a line through one of its points: a crossing there, whose residual
    /// is within the tolerance, named a crossing when the angle is clear.
    #[test]
    fn transversal_pairs_report_crossings(
        a in proptest::array::uniform2(-10.0..10.0_f64),
        b in proptest::array::uniform2(-10.0..10.0_f64),
        f in 0.1..0.9_f64,
        g in 0.1..0.9_f64,
        angle in 0.3..2.8_f64,
        bend in proptest::array::uniform2(-3.0..3.0_f64),
    ) {
        // a quadratic through a and b, and a line through its point at f at `angle` to its chord
        let mid = [0.5 * (a[0] + b[0]) + bend[0], 0.5 * (a[1] + b[1]) + bend[1]];
        let curve = bezier(&[a.to_vec(), mid.to_vec(), b.to_vec()]);
        let p = curve.point(f).expect("p");
        let d = [angle.cos(), angle.sin()];
        let line = bezier(&[vec![p[0] - g * 4.0 * d[0], p[1] - g * 4.0 * d[1]], vec![p[0] + (1.0 - g) * 4.0 * d[0], p[1] + (1.0 - g) * 4.0 * d[1]]]);
        let hits = curve.intersect(&line, 1e-9).expect("x");
        prop_assert!(!hits.is_empty(), "{:?}", hits);
        let crossing = hits.iter().find_map(|h| match h {
            CurveIntersection::Point { t_a, t_b, contact, .. } if (t_a - f).abs() < 1e-6 => Some((*t_a, *t_b, *contact)),
            _ => None,
        });
        let Some((t_a, t_b, contact)) = crossing else { return Err(TestCaseError::fail(format!("{hits:?}"))) };
        let (pa, pb) = (curve.point(t_a).expect("a"), line.point(t_b).expect("b"));
        prop_assert!(((pa[0] - pb[0]).hypot(pa[1] - pb[1])) <= 1e-9, "{:?} {:?}", pa, pb);
        // the curve's tangent there, 2((1 − f)(mid − a) + f(b − mid)): a clear angle is a crossing
        let tng = [0, 1].map(|k| 2.0 * ((1.0 - f) * (mid[k] - a[k]) + f * (b[k] - mid[k])));
        let sin = (tng[0] * d[1] - tng[1] * d[0]).abs() / tng[0].hypot(tng[1]);
        prop_assume!(sin > 0.05);
        prop_assert_eq!(contact, Contact::Crossing, "{:?}", hits);
    }
}

/// A cubic with a loop, against two parts of itself that share a stretch holding the loop's one
/// end (found by the property test above): the overlap ends where the parts' common stretch
/// does, not at the loop's crossing just beyond it, and the crossing is its own answer.
#[test]
fn a_loop_beside_an_overlap_stays_a_crossing() {
    let rows = [
        [-1.5874826489728704, -5.345856120628807],
        [-8.369822536531217, 1.5474634385036552],
        [9.585109293054469, 4.290459156069245],
        [-6.360091724388338, -1.6951257718199502],
    ];
    let knots = vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0];
    let c = BSplineCurve::new(3, knots, Points::from_2d(&rows).expect("p")).expect("c");
    let loop_at = QueryCurve::from_bspline(&c)
        .expect("q")
        .self_intersections(1e-9)
        .expect("self");
    let [CurveIntersection::Point {
        t_a: l0, t_b: l1, ..
    }] = loop_at[..]
    else {
        panic!("one loop: {loop_at:?}")
    };
    let e = 0.884_449_197_476_832_1;
    let right = QueryCurve::from_bspline(&c.split_at(0.1).expect("s").1).expect("a");
    let left = QueryCurve::from_bspline(&c.split_at(e).expect("s").0).expect("b");
    let hits = right.intersect(&left, 1e-9).expect("x");
    assert_eq!(hits.len(), 2, "{hits:?}");
    let CurveIntersection::Overlap { a, b } = hits[0] else {
        panic!("{hits:?}")
    };
    assert!(
        (a.0 - 0.1).abs() <= 1e-12 && (a.1 - e).abs() <= 1e-12,
        "{a:?}"
    );
    assert!(
        (b.0 - 0.1).abs() <= 1e-12 && (b.1 - e).abs() <= 1e-12,
        "{b:?}"
    );
    let CurveIntersection::Point {
        t_a, t_b, contact, ..
    } = hits[1]
    else {
        panic!("{hits:?}")
    };
    assert_eq!(contact, Contact::Crossing);
    assert!(
        (t_a - l1).abs() <= 1e-12 && (t_b - l0).abs() <= 1e-12,
        "{hits:?} vs {loop_at:?}"
    );
}

/// A cubic that crosses itself inside the stretch two of its parts share: the overlap runs on
/// past the crossing of its other stretch (which stays a crossing) to the shared stretch's end.
#[test]
fn an_overlap_runs_past_a_crossing_inside_it() {
    let rows = [
        [3.8845311756995566, 1.9533238654014282],
        [-3.6077730828797305, -4.006867790025332],
        [1.3399947061843052, -7.595205710776024],
        [1.8709825906676303, 8.47527125069541],
    ];
    let (s, e) = (0.1, 0.6839355105326358);
    let knots = vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0];
    let c = BSplineCurve::new(3, knots, Points::from_2d(&rows).expect("p")).expect("c");
    let right = QueryCurve::from_bspline(&c.split_at(s).expect("split").1).expect("a");
    let left = QueryCurve::from_bspline(&c.split_at(e).expect("split").0).expect("b");
    let hits = right.intersect(&left, 1e-9).expect("x");
    let overlaps: Vec<_> = hits
        .iter()
        .filter_map(|h| match h {
            CurveIntersection::Overlap { a, b } => Some((*a, *b)),
            CurveIntersection::Point { .. } => None,
        })
        .collect();
    assert_eq!(overlaps.len(), 1, "{hits:?}");
    let (a, b) = overlaps[0];
    assert!(
        (a.0 - s).abs() <= 1e-12 && (a.1 - e).abs() <= 1e-12,
        "{a:?}"
    );
    assert!(
        (b.0 - s).abs() <= 1e-12 && (b.1 - e).abs() <= 1e-12,
        "{b:?}"
    );
    // the cubic's own crossing (t = 0.68 on one stretch, 0.22 on the other) is still there
    assert!(
        hits.iter()
            .any(|h| matches!(h, CurveIntersection::Point { t_a, t_b, .. }
            if (t_a - 0.6816).abs() < 1e-3 && (t_b - 0.2202).abs() < 1e-3)),
        "{hits:?}"
    );
}
