//! Faces with bad trims, each built in code on the plane `[0, 4]²` (the identity in `(u, v)`):
//! refused with the loop and the defect, or repaired and reported.

use super::super::tests::{hole, plane, square};
use super::*;
use crate::topology::{mesh_faces_each, Edge, Face, Loop};
use crate::{BSplineCurve, Curve, Error, Points};

/// One edge through `pts` in order, degree 1, on the plane (3-D curve `(u, v, 0)`).
fn polyline(pts: &[[f64; 2]]) -> Edge {
    let n = pts.len();
    let mut knots = vec![0.0];
    #[allow(clippy::cast_precision_loss)] // a few points
    knots.extend((0..n).map(|k| k as f64));
    #[allow(clippy::cast_precision_loss)]
    knots.push((n - 1) as f64);
    let p2 = Points::from_2d(pts).unwrap();
    let p3 = Points::from_3d(&pts.iter().map(|p| [p[0], p[1], 0.0]).collect::<Vec<_>>()).unwrap();
    Edge::new(
        Curve::from(BSplineCurve::new(1, knots.clone(), p3).unwrap()),
        Some(Curve::from(BSplineCurve::new(1, knots, p2).unwrap())),
    )
    .unwrap()
}

/// A loop of straight edges through the corners `c` (closed back to the first).
fn polygon(c: &[[f64; 2]]) -> Loop {
    let n = c.len();
    Loop::new((0..n).map(|k| polyline(&[c[k], c[(k + 1) % n]])).collect()).unwrap()
}

fn face(outer: Loop, inner: Vec<Loop>) -> Face {
    Face::new(plane(), outer, inner, true, LOOP_CLOSURE_RTOL).unwrap()
}

fn defect(f: &Face) -> (usize, TrimDefect) {
    match f.checked_trims() {
        Err(Error::InvalidTrim { lp, defect }) => (lp, defect),
        other => panic!("expected InvalidTrim, got {other:?}"),
    }
}

fn area_uv(f: &Face) -> f64 {
    let m = f.mesh(1e-3).unwrap();
    m.triangles
        .iter()
        .map(|t| {
            let p = t.map(|k| m.uv[k as usize]);
            0.5 * ((p[1][0] - p[0][0]) * (p[2][1] - p[0][1])
                - (p[2][0] - p[0][0]) * (p[1][1] - p[0][1]))
        })
        .sum()
}

#[test]
fn a_valid_face_passes_unchanged() {
    let f = face(square(false), vec![hole(true)]);
    assert_eq!(f.checked_trims().unwrap(), (None, vec![]));
}

#[test]
fn a_trim_partly_outside_the_domain_is_refused_with_its_edge() {
    let f = face(
        polygon(&[[1.0, 1.0], [5.0, 1.0], [5.0, 3.0], [1.0, 3.0]]),
        vec![],
    );
    let (lp, d) = defect(&f);
    assert_eq!(lp, 0);
    assert!(
        matches!(d, TrimDefect::OutsideDomain { edge: 0, at, .. } if at[0] > 4.0),
        "{d:?}"
    );
    let e = f.mesh(1e-3).unwrap_err();
    let msg = e.to_string();
    assert!(
        msg.starts_with("the outer loop leaves the surface's domain: edge 0's curve in (u, v) reaches (5, 1), past its side u = 4")
            && msg.contains("lekalo projects the edges"),
        "{msg}"
    );
}

#[test]
fn a_trim_wholly_outside_the_domain_is_refused() {
    let f = face(polygon(&[[10.0, 10.0], [12.0, 10.0], [12.0, 12.0]]), vec![]);
    assert!(matches!(
        defect(&f),
        (0, TrimDefect::OutsideDomain { edge: 0, .. })
    ));
    let r = mesh_faces_each(&[&f], 1e-3).unwrap();
    assert!(r.meshes.is_empty() && r.failures.len() == 1, "{r:?}");
}

#[test]
fn a_trim_past_the_domain_within_the_tolerance_is_clipped_and_reported() {
    // the tolerance is 1e-4 of the width 4: 4e-4
    let e = 3e-4;
    let f = face(
        polygon(&[[-e, -e], [4.0 + e, -e], [4.0 + e, 4.0], [-e, 4.0]]),
        vec![],
    );
    let (g, r) = f.checked_trims().unwrap();
    assert!(g.is_none());
    assert_eq!(r.len(), 1);
    assert!(
        matches!(r[0], TrimRepair::Clipped { lp: 0, by } if (by - e).abs() < 1e-12),
        "{r:?}"
    );
    // meshed up to the domain's sides: the area of the domain, every (u, v) in it
    assert!((area_uv(&f) - 16.0).abs() < 1e-9, "{}", area_uv(&f));
    let m = f.mesh(1e-3).unwrap();
    assert!(m
        .uv
        .iter()
        .all(|p| (0.0..=4.0).contains(&p[0]) && (0.0..=4.0).contains(&p[1])));
    let set = mesh_faces_each(&[&f], 1e-3).unwrap();
    assert_eq!(set.repairs, vec![(0, r[0].clone())]);
    // just past the tolerance: refused
    let e = 5e-4;
    let f = face(
        polygon(&[[-e, 0.0], [4.0, 0.0], [4.0, 4.0], [0.0, 4.0]]),
        vec![],
    );
    assert!(matches!(
        defect(&f),
        (0, TrimDefect::OutsideDomain { edge: 0, .. })
    ));
}

#[test]
fn a_bow_tie_is_refused_naming_the_crossing_edges() {
    let f = face(
        polygon(&[[0.0, 0.0], [4.0, 4.0], [4.0, 0.0], [0.0, 4.0]]),
        vec![],
    );
    let (lp, d) = defect(&f);
    assert_eq!(lp, 0);
    match d {
        TrimDefect::SelfCrossing { edges, at } => {
            assert_eq!(edges, [0, 2]);
            assert!((at[0] - 2.0).abs() < 1e-12 && (at[1] - 2.0).abs() < 1e-12);
        }
        d => panic!("{d:?}"),
    }
    // one edge crossing itself (a bow tie drawn as one polyline)
    let f = face(
        Loop::new(vec![polyline(&[
            [0.0, 0.0],
            [4.0, 4.0],
            [4.0, 0.0],
            [0.0, 4.0],
            [0.0, 0.0],
        ])])
        .unwrap(),
        vec![],
    );
    let (lp, d) = defect(&f);
    assert_eq!(lp, 0);
    assert!(
        matches!(d, TrimDefect::SelfCrossing { edges: [0, 0], .. }),
        "{d:?}"
    );
    assert!(Error::InvalidTrim { lp, defect: d }
        .to_string()
        .starts_with("the outer loop crosses itself: edge 0 crosses itself near (u, v) = (2, 2)"),);
}

#[test]
fn a_loop_touching_itself_is_not_a_crossing() {
    // two squares meeting at the corner (2, 2): touching, not crossing
    let f = face(
        polygon(&[
            [0.0, 0.0],
            [2.0, 0.0],
            [2.0, 2.0],
            [4.0, 2.0],
            [4.0, 4.0],
            [2.0, 4.0],
            [2.0, 2.0],
            [0.0, 2.0],
        ]),
        vec![],
    );
    assert_eq!(f.checked_trims().unwrap(), (None, vec![]));
}

#[test]
fn an_outer_loop_of_one_point_is_refused() {
    let f = face(polygon(&[[1.0, 1.0]]), vec![]);
    assert_eq!(defect(&f), (0, TrimDefect::ZeroLength));
    assert!(f
        .mesh(1e-3)
        .unwrap_err()
        .to_string()
        .contains("bounds no region"));
}

#[test]
fn a_hole_of_one_point_is_dropped_and_reported() {
    let with = face(square(false), vec![polygon(&[[2.0, 2.0]])]);
    let (g, r) = with.checked_trims().unwrap();
    assert_eq!(r, vec![TrimRepair::DroppedLoop { lp: 1 }]);
    let without = face(square(false), vec![]);
    assert_eq!(g.as_ref(), Some(&without));
    assert_eq!(with.mesh(1e-3).unwrap(), without.mesh(1e-3).unwrap());
    assert_eq!(
        r[0].to_string(),
        "inner loop 1 has no length (a hole of one point): dropped"
    );
}

#[test]
fn an_edge_of_no_length_is_dropped_and_reported() {
    let c = [[0.0, 0.0], [4.0, 0.0], [4.0, 4.0], [0.0, 4.0]];
    let mut edges: Vec<Edge> = (0..4).map(|k| polyline(&[c[k], c[(k + 1) % 4]])).collect();
    edges.insert(2, polyline(&[[4.0, 4.0], [4.0, 4.0]]));
    let f = face(Loop::new(edges).unwrap(), vec![]);
    let (g, r) = f.checked_trims().unwrap();
    assert_eq!(r, vec![TrimRepair::DroppedEdge { lp: 0, edge: 2 }]);
    let g = g.unwrap();
    assert_eq!(g.outer().edges().len(), 4);
    assert_eq!(g, face(polygon(&c), vec![]));
    assert!((area_uv(&f) - 16.0).abs() < 1e-9);
}

#[test]
fn a_hole_crossing_the_outer_loop_is_refused() {
    let f = face(
        square(false),
        vec![polygon(&[[3.0, 1.0], [3.0, 3.0], [5.0, 3.0], [5.0, 1.0]])],
    );
    // refused for its domain first: the hole leaves it
    assert!(matches!(
        defect(&f),
        (1, TrimDefect::OutsideDomain { edge: 1, .. })
    ));
    // inside the domain, across a smaller outer loop
    let f = face(
        polygon(&[[0.0, 0.0], [3.0, 0.0], [3.0, 3.0], [0.0, 3.0]]),
        vec![polygon(&[[2.0, 1.0], [2.0, 2.0], [3.5, 2.0], [3.5, 1.0]])],
    );
    let (lp, d) = defect(&f);
    assert_eq!(lp, 1);
    assert!(
        matches!(d, TrimDefect::CrossesLoop { other: 0, at } if (at[0] - 3.0).abs() < 1e-12),
        "{d:?}"
    );
}

#[test]
fn holes_crossing_each_other_are_refused() {
    let f = face(
        square(false),
        vec![
            polygon(&[[1.0, 1.0], [1.0, 2.0], [2.0, 2.0], [2.0, 1.0]]),
            polygon(&[[1.5, 1.5], [1.5, 3.0], [3.0, 3.0], [3.0, 1.5]]),
        ],
    );
    assert!(matches!(
        defect(&f),
        (2, TrimDefect::CrossesLoop { other: 1, .. })
    ));
}

#[test]
fn a_hole_outside_its_outer_loop_is_refused() {
    let f = face(
        polygon(&[[0.0, 0.0], [2.0, 0.0], [2.0, 2.0], [0.0, 2.0]]),
        vec![polygon(&[[3.0, 3.0], [3.5, 3.0], [3.5, 3.5]])],
    );
    assert_eq!(defect(&f), (1, TrimDefect::OutsideOuter));
    // the outer loop inside the hole (the loops given the wrong way round)
    let f = face(
        polygon(&[[1.0, 1.0], [2.0, 1.0], [2.0, 2.0]]),
        vec![square(false)],
    );
    assert_eq!(defect(&f), (1, TrimDefect::OutsideOuter));
}

#[test]
fn a_hole_inside_a_hole_is_refused() {
    let f = face(
        square(false),
        vec![
            polygon(&[[1.0, 1.0], [3.0, 1.0], [3.0, 3.0], [1.0, 3.0]]),
            polygon(&[[1.5, 1.5], [2.5, 1.5], [2.5, 2.5]]),
        ],
    );
    assert_eq!(defect(&f), (2, TrimDefect::InsideHole { other: 1 }));
}

/// A set with one bad face: the bad one listed with its defect, the good ones meshed as they
/// are without it.
#[test]
fn a_face_with_bad_trims_fails_alone_in_a_set() {
    let good = face(square(false), vec![hole(true)]);
    let bad = face(
        polygon(&[[0.0, 0.0], [4.0, 4.0], [4.0, 0.0], [0.0, 4.0]]),
        vec![],
    );
    let r = mesh_faces_each(&[&good, &bad], 1e-3).unwrap();
    assert_eq!(r.failures.len(), 1);
    assert_eq!(r.failures[0].0, 1);
    assert!(matches!(
        r.failures[0].1,
        Error::InvalidTrim {
            lp: 0,
            defect: TrimDefect::SelfCrossing { .. }
        }
    ));
    assert_eq!(r.meshes.len(), 1);
    assert_eq!(r.meshes[0].1, good.mesh(1e-3).unwrap());
}

/// Two edges meeting at a vertex within the tolerance, the first running a little past the
/// second (a sewing gap of the file, or each edge projected onto the surface on its own): their
/// last segments cross within the tolerance of the vertex, which is a touch, and the face keeps
/// its area; the same edges crossing far from the vertex still cross.
#[test]
fn consecutive_edges_poking_across_at_their_vertex_touch_but_crossing_away_from_it_cross() {
    let lp = Loop::new(vec![
        polyline(&[[1.0, 1.0], [3.0 + 2e-5, 1.0]]),
        polyline(&[[3.0, 1.0 - 1e-5], [3.0, 3.0]]),
        polyline(&[[3.0, 3.0], [1.0, 3.0]]),
        polyline(&[[1.0, 3.0], [1.0, 1.0]]),
    ])
    .unwrap();
    let f = face(lp, vec![]);
    assert_eq!(f.checked_trims().unwrap(), (None, vec![]));
    assert!((area_uv(&f) - 4.0).abs() < 1e-3, "{}", area_uv(&f));
    let far = face(
        Loop::new(vec![
            polyline(&[[1.0, 1.0], [3.0, 1.0]]),
            polyline(&[[3.0, 1.0], [2.5, 0.5], [2.5, 1.5], [3.0, 3.0]]),
            polyline(&[[3.0, 3.0], [1.0, 3.0]]),
            polyline(&[[1.0, 3.0], [1.0, 1.0]]),
        ])
        .unwrap(),
        vec![],
    );
    let (lp, d) = defect(&far);
    assert_eq!(lp, 0);
    assert!(
        matches!(d, TrimDefect::SelfCrossing { edges: [0, 1], at } if (at[0] - 2.5).abs() < 1e-9),
        "{d:?}"
    );
}
