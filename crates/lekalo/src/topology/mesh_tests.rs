//! Meshes of trimmed faces: a square with a round hole (area and hole), a curved B-spline
//! face with a corner cut off, two faces sharing an edge (no crack).

use super::super::mesh::MAX_REFINE_ROUNDS;
use super::super::tests::{hole, plane, square};
use super::edge_sampling::dist;
use super::*;
use crate::topology::{join_meshes, mesh_faces, mesh_faces_each, FaceMeshes};
use crate::topology::{Edge, Loop, LOOP_CLOSURE_RTOL};
use crate::{BSplineCurve, BSplineSurface, Curve, Surface};
use proptest::prelude::*;

fn area3(m: &Mesh) -> f64 {
    let v = |k: u32| m.vertices.point(k as usize).to_vec();
    m.triangles
        .iter()
        .map(|t| {
            let (a, b, c) = (v(t[0]), v(t[1]), v(t[2]));
            let e = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
            let f = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
            let n = [
                e[1] * f[2] - e[2] * f[1],
                e[2] * f[0] - e[0] * f[2],
                e[0] * f[1] - e[1] * f[0],
            ];
            0.5 * (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt()
        })
        .sum()
}

/// The square `[0, 4]²` with the hole of radius 1 about `(2, 2)`, meshed within `tol`: no
/// triangle's centroid is in the hole, the area is `16 − π` within the area between the
/// circle and a polygon inscribed within `tol` (at most its length `2π` times `tol`), and every
/// triangle faces `+z`.
fn check_holed_square(tol: f64) {
    let f = Face::new(
        plane(),
        square(false),
        vec![hole(true)],
        true,
        LOOP_CLOSURE_RTOL,
    )
    .unwrap();
    let m = f.mesh(tol).unwrap();
    assert!(m.deviation <= tol, "{} > {tol}", m.deviation);
    for t in &m.triangles {
        let c = t.iter().fold([0.0, 0.0], |c, &k| {
            let uv = m.uv[k as usize];
            [c[0] + uv[0] / 3.0, c[1] + uv[1] / 3.0]
        });
        let r = ((c[0] - 2.0).powi(2) + (c[1] - 2.0).powi(2)).sqrt();
        assert!(r >= 1.0 - tol, "centroid {c:?} in the hole");
    }
    for k in 0..m.triangles.len() {
        let n = m.facet_normal(k).unwrap();
        assert!(n[2] > 0.999, "triangle {k} faces {n:?}");
    }
    let exact = 16.0 - std::f64::consts::PI;
    let a = area3(&m);
    assert!(
        a >= exact - 1e-12 && a - exact <= 2.0 * std::f64::consts::PI * tol,
        "area {a} against {exact}"
    );
}

#[test]
fn square_with_a_hole_has_the_area_of_the_ring() {
    check_holed_square(1e-3);
    check_holed_square(1e-5);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(12))]
    #[test]
    fn the_hole_stays_empty_at_any_tolerance(e in 2.0f64..6.0) {
        check_holed_square(10f64.powf(-e));
    }
}

/// `S(u, v) = (u, v, u² − v²)` on `[0, 1]²`: biquadratic, so a line in `(u, v)` is a
/// quadratic curve in space.
fn saddle() -> Surface {
    let mut pts = Vec::new();
    for i in 0..3 {
        for j in 0..3 {
            let z = f64::from(u8::from(i == 2)) - f64::from(u8::from(j == 2));
            pts.push([f64::from(i) / 2.0, f64::from(j) / 2.0, z]);
        }
    }
    let k = vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0];
    Surface::from(
        BSplineSurface::new(2, 2, k.clone(), k, Points::from_3d(&pts).unwrap(), (3, 3)).unwrap(),
    )
}

/// The edge of the saddle along the line from `a` to `b` in `(u, v)`: its 3-D curve the exact
/// image (a quadratic Bezier curve), its pcurve the line.
fn saddle_edge(a: [f64; 2], b: [f64; 2]) -> Edge {
    let d = [b[0] - a[0], b[1] - a[1]];
    let z = |p: [f64; 2]| p[0] * p[0] - p[1] * p[1];
    let p1 = [
        a[0] + d[0] / 2.0,
        a[1] + d[1] / 2.0,
        z(a) + a[0] * d[0] - a[1] * d[1],
    ];
    let pts = Points::from_3d(&[[a[0], a[1], z(a)], p1, [b[0], b[1], z(b)]]).unwrap();
    Edge::new(
        Curve::from(BSplineCurve::new(2, vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0], pts).unwrap()),
        Some(Curve::from(
            BSplineCurve::line_segment(&a, &d, 0.0, 1.0).unwrap(),
        )),
    )
    .unwrap()
}

fn saddle_loop(c: &[[f64; 2]]) -> Loop {
    Loop::new(
        (0..c.len())
            .map(|k| saddle_edge(c[k], c[(k + 1) % c.len()]))
            .collect(),
    )
    .unwrap()
}

#[test]
fn a_curved_face_with_a_corner_cut_off() {
    let c = [[0.0, 0.0], [1.0, 0.0], [1.0, 0.6], [0.6, 1.0], [0.0, 1.0]];
    let f = Face::new(saddle(), saddle_loop(&c), vec![], true, LOOP_CLOSURE_RTOL).unwrap();
    let tol = 1e-4;
    let m = f.mesh(tol).unwrap();
    assert!(
        m.deviation <= tol,
        "{} {} {}",
        m.deviation,
        m.vertices.len(),
        m.triangles.len()
    );
    let s = f.surface();
    let mut area = 0.0;
    for t in &m.triangles {
        let p = t.map(|k| m.uv[k as usize]);
        area += 0.5
            * ((p[1][0] - p[0][0]) * (p[2][1] - p[0][1])
                - (p[2][0] - p[0][0]) * (p[1][1] - p[0][1]));
        let c = [
            (p[0][0] + p[1][0] + p[2][0]) / 3.0,
            (p[0][1] + p[1][1] + p[2][1]) / 3.0,
        ];
        assert!(c[0] + c[1] <= 1.6, "centroid {c:?} in the cut corner");
        // the surface at the centroid against the triangle's plane point there
        let x = s.eval(c[0], c[1]).unwrap();
        let lin: Vec<f64> = (0..3)
            .map(|d| {
                t.iter()
                    .map(|&k| m.vertices.point(k as usize)[d])
                    .sum::<f64>()
                    / 3.0
            })
            .collect();
        assert!(dist(&x, &lin) <= tol, "{} off at {c:?}", dist(&x, &lin));
    }
    // the triangles cover the pentagon in (u, v), counter-clockwise
    assert!((area - (1.0 - 0.08)).abs() < 1e-9, "area {area}");
}

#[test]
fn two_faces_sharing_an_edge_meet_at_the_same_points() {
    let a = saddle_loop(&[[0.0, 0.0], [0.5, 0.0], [0.5, 1.0], [0.0, 1.0]]);
    // the second face runs the shared edge backwards, with the first face's curve reversed
    let shared = &a.edges()[1];
    let back = Edge::new(
        shared.curve().reverse().unwrap(),
        Some(shared.pcurve().unwrap().reverse().unwrap()),
    )
    .unwrap();
    let b = Loop::new(vec![
        saddle_edge([0.5, 0.0], [1.0, 0.0]),
        saddle_edge([1.0, 0.0], [1.0, 1.0]),
        saddle_edge([1.0, 1.0], [0.5, 1.0]),
        back,
    ])
    .unwrap();
    let fa = Face::new(saddle(), a, vec![], true, LOOP_CLOSURE_RTOL).unwrap();
    let fb = Face::new(saddle(), b, vec![], true, LOOP_CLOSURE_RTOL).unwrap();
    let tol = 1e-4;
    let ms = mesh_faces(&[&fa, &fb], tol).unwrap();
    let on_edge = |m: &Mesh| -> Vec<Vec<f64>> {
        (0..m.vertices.len())
            .filter(|&k| (m.uv[k][0] - 0.5).abs() < 1e-12)
            .map(|k| m.vertices.point(k).to_vec())
            .collect()
    };
    let (ea, eb) = (on_edge(&ms[0]), on_edge(&ms[1]));
    assert!(ea.len() > 2, "the shared edge is sampled");
    assert_eq!(ea.len(), eb.len());
    for p in &ea {
        assert!(
            eb.contains(p),
            "{p:?} of the first face is not a vertex of the second"
        );
    }
    // each face alone samples its edge for itself; the joined mesh keeps all vertices
    let joined = join_meshes(&ms).unwrap();
    assert_eq!(
        joined.vertices.len(),
        ms[0].vertices.len() + ms[1].vertices.len()
    );
    assert!(joined.deviation <= tol);
}

#[test]
fn a_tolerance_too_small_for_the_grid_is_refused_with_the_tolerance() {
    let f = Face::new(
        saddle(),
        saddle_loop(&[[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]),
        vec![],
        true,
        LOOP_CLOSURE_RTOL,
    )
    .unwrap();
    let e = f.mesh(1e-11).unwrap_err();
    // the key of the tolerance: each front end names its own tolerance argument
    assert_eq!(e.arg(), Some(crate::Arg::Tolerance), "{e}");
    let e = e.to_string();
    assert!(e.contains("1e-11") && e.contains("points"), "{e}");
    let nan = f.mesh(f64::NAN).unwrap_err();
    assert_eq!(nan.arg(), Some(crate::Arg::Tolerance), "{nan}");
    for bad in [0.0, -1.0, f64::NAN] {
        let e = mesh_faces(&[&f], bad).unwrap_err();
        assert_eq!(
            e.arg(),
            Some(crate::Arg::Tolerance),
            "mesh_faces({bad}): {e}"
        );
    }
}

/// A CAD system's pcurves leave the surface's domain by their rounding (here by 4e-16 at
/// two corners): the face is meshed, the surface taken at the nearest point of its domain.
#[test]
fn pcurves_past_the_domain_by_rounding_are_meshed() {
    let e = 4e-16;
    let c = [[-e, -e], [1.0 + e, 0.0], [1.0, 1.0], [0.0, 1.0]];
    let f = Face::new(saddle(), saddle_loop(&c), vec![], true, LOOP_CLOSURE_RTOL).unwrap();
    let m = f.mesh(1e-3).unwrap();
    assert!(m.deviation <= 1e-3);
    let area: f64 = m
        .triangles
        .iter()
        .map(|t| {
            let p = t.map(|k| m.uv[k as usize]);
            0.5 * ((p[1][0] - p[0][0]) * (p[2][1] - p[0][1])
                - (p[2][0] - p[0][0]) * (p[1][1] - p[0][1]))
        })
        .sum();
    assert!((area - 1.0).abs() < 1e-9, "area {area}");
}

/// The saddle's face left of `x = 0.5` and the one right of it, which runs their shared edge
/// backwards; with `pcurve_off` the right face's first edge has no pcurve.
fn two_saddle_faces(pcurve_off: bool) -> (Face, Face) {
    let a = saddle_loop(&[[0.0, 0.0], [0.5, 0.0], [0.5, 1.0], [0.0, 1.0]]);
    let shared = &a.edges()[1];
    let back = Edge::new(
        shared.curve().reverse().unwrap(),
        Some(shared.pcurve().unwrap().reverse().unwrap()),
    )
    .unwrap();
    let mut first = saddle_edge([0.5, 0.0], [1.0, 0.0]);
    if pcurve_off {
        first = Edge::new(first.curve().clone(), None).unwrap();
    }
    let b = Loop::new(vec![
        first,
        saddle_edge([1.0, 0.0], [1.0, 1.0]),
        saddle_edge([1.0, 1.0], [0.5, 1.0]),
        back,
    ])
    .unwrap();
    (
        Face::new(saddle(), a, vec![], true, LOOP_CLOSURE_RTOL).unwrap(),
        Face::new(saddle(), b, vec![], true, LOOP_CLOSURE_RTOL).unwrap(),
    )
}

/// A face that fails while its edges are sampled (an edge without pcurve), sharing an edge
/// with another: the others are meshed once each, exactly as they are without it, and the
/// failure names the face by its index.
#[test]
fn a_face_failing_on_its_edges_leaves_the_others_as_without_it_each_meshed_once() {
    let (fa, bad) = two_saddle_faces(true);
    let fc = Face::new(
        saddle(),
        saddle_loop(&[[0.0, 0.0], [0.3, 0.1], [0.2, 0.4]]),
        vec![],
        true,
        LOOP_CLOSURE_RTOL,
    )
    .unwrap();
    let tol = 1e-4;
    let (r, meshed) =
        super::super::mesh_set::mesh_counted(&[&fa, &bad, &fc], tol, MAX_REFINE_ROUNDS).unwrap();
    assert_eq!(meshed, 2, "each face that can be meshed is meshed once");
    assert_eq!(r.failures.len(), 1, "{:?}", r.failures);
    assert_eq!(
        r.failures[0].0, 1,
        "the face without a pcurve is the second"
    );
    assert!(
        matches!(&r.failures[0].1, Error::InvalidArgument { what, reason } if reason.contains("no curve in the surface's (u, v)") && what.words() == "face loop"),
        "{:?}",
        r.failures[0].1
    );
    let without = mesh_faces_each(&[&fa, &fc], tol).unwrap();
    assert!(without.failures.is_empty(), "{:?}", without.failures);
    let index: Vec<usize> = r.meshes.iter().map(|(i, _)| *i).collect();
    assert_eq!(index, [0, 2]);
    assert_eq!(r.meshes[0].1, without.meshes[0].1);
    assert_eq!(r.meshes[1].1, without.meshes[1].1);
    // the set as one: the failing face's error
    assert_eq!(
        mesh_faces(&[&fa, &bad, &fc], tol).unwrap_err(),
        r.failures[0].1
    );
    // without the failure, the shared edge is sampled for both faces, which meet along it
    let (good_a, good_b) = two_saddle_faces(false);
    let (r, meshed) =
        super::super::mesh_set::mesh_counted(&[&good_a, &good_b], tol, MAX_REFINE_ROUNDS).unwrap();
    assert_eq!(meshed, 2);
    assert!(r.failures.is_empty());
}

/// A face that fails when it is meshed (a band of a cylinder whose two circles run the same
/// way, refused by the cut along a seam), sharing its circle with a good band: the good faces
/// are as they are without it, and none is meshed again since the failed face's use did not
/// change the samples of their shared circle.
#[test]
fn a_face_failing_when_meshed_leaves_the_others_as_without_it() {
    use crate::surface::Placement;
    use crate::{NurbsCurve, NurbsSurface};
    use std::f64::consts::TAU;
    let circle = |z: f64, up: bool| {
        let c = Curve::from(
            NurbsCurve::circle(&[0.0, 0.0, z], &[1.0, 0.0, 0.0], &[0.0, 1.0, 0.0], 1.0).unwrap(),
        );
        Edge::new(if up { c } else { c.reverse().unwrap() }, None).unwrap()
    };
    let frame = Placement::new([0.0; 3], None, None).unwrap();
    let cyl = Surface::from(NurbsSurface::cylinder(&frame, 1.0, (0.0, TAU), (0.0, 3.0)).unwrap());
    let band = |lo: Edge, hi: Edge| {
        Face::new(
            cyl.clone(),
            Loop::new(vec![lo]).unwrap(),
            vec![Loop::new(vec![hi]).unwrap()],
            true,
            LOOP_CLOSURE_RTOL,
        )
        .unwrap()
        .with_projected_pcurves(1e-7)
        .unwrap()
    };
    let good = band(circle(0.5, true), circle(2.5, false));
    // the circle at z = 2.5 run up: the same edge as the good band's, the other way
    let bad = band(circle(2.5, true), circle(2.9, true));
    let (other, _) = two_saddle_faces(false);
    let tol = 1e-3;
    let (r, meshed) =
        super::super::mesh_set::mesh_counted(&[&good, &bad, &other], tol, MAX_REFINE_ROUNDS)
            .unwrap();
    assert_eq!(r.failures.len(), 1, "{:?}", r.failures);
    assert_eq!(r.failures[0].0, 1);
    assert!(
        r.failures[0].1.to_string().contains("same sense"),
        "{}",
        r.failures[0].1
    );
    let without = mesh_faces_each(&[&good, &other], tol).unwrap();
    assert_eq!(r.meshes.len(), 2);
    assert_eq!(r.meshes[0], (0, without.meshes[0].1.clone()));
    assert_eq!(r.meshes[1], (2, without.meshes[1].1.clone()));
    // both bands on one cylinder: the failed band's use samples the circle as the good
    // band's does, so the good band keeps its mesh and every face is meshed once
    assert_eq!(meshed, 3, "a face meshed twice");
}

/// The edge of `s` along the parameter line from `a` to `b` (one parameter fixed): its 3-D
/// curve the iso-parametric curve (reversed when running back), its pcurve the line.
fn iso_edge(s: &Surface, a: [f64; 2], b: [f64; 2]) -> Edge {
    use crate::Direction;
    let (dir, value, back) = if a[1] == b[1] {
        (Direction::U, a[1], b[0] < a[0])
    } else {
        (Direction::V, a[0], b[1] < a[1])
    };
    let c = s.iso_curve(dir, value).unwrap();
    let c = if back { c.reverse().unwrap() } else { c };
    let d = [b[0] - a[0], b[1] - a[1]];
    Edge::new(
        c,
        Some(Curve::from(
            BSplineCurve::line_segment(&a, &d, 0.0, 1.0).unwrap(),
        )),
    )
    .unwrap()
}

/// The face of `s` bounded by the parameter lines from each of `corners` to the next (the
/// last to the first when `closed`; else the loop closes in space, through a pole).
fn domain_face(s: Surface, corners: &[[f64; 2]], closed: bool) -> Face {
    let n = corners.len() - usize::from(!closed);
    let edges = (0..n)
        .map(|k| iso_edge(&s, corners[k], corners[(k + 1) % corners.len()]))
        .collect();
    Face::new(
        s,
        Loop::new(edges).unwrap(),
        vec![],
        true,
        LOOP_CLOSURE_RTOL,
    )
    .unwrap()
}

/// A ruled surface over `[0, 1]²`, `S(u, v) = (x(u), v, z(u))` with `x(u) = u` (the control
/// points at the Greville abscissae), quadratic in `u` with a short first knot span
/// `[0, 0.01]` where `z` bends sharply (`|z''|` near 10³ there, near 0.4 on the long span):
/// the bound of each patch is its own, so the short span gets its small steps and the long
/// one large steps. With the largest bound over the surface everywhere, the grid alone was
/// 2,200 columns (some 4,400 triangles); with each span's own bound it is about 60.
#[test]
fn a_short_knot_span_refines_its_own_span_only() {
    let x = [0.0, 0.005, 0.505, 1.0];
    let z = [0.0, 0.05, 0.0, 0.0];
    let mut pts = Vec::new();
    for i in 0..4 {
        for v in [0.0, 1.0] {
            pts.push([x[i], v, z[i]]);
        }
    }
    let s = Surface::from(
        BSplineSurface::new(
            2,
            1,
            vec![0.0, 0.0, 0.0, 0.01, 1.0, 1.0, 1.0],
            vec![0.0, 0.0, 1.0, 1.0],
            Points::from_3d(&pts).unwrap(),
            (4, 2),
        )
        .unwrap(),
    );
    let f = domain_face(
        s.clone(),
        &[[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]],
        true,
    );
    let tol = 1e-4;
    let m = f.mesh(tol).unwrap();
    assert!(m.deviation <= tol, "bound {} above {tol}", m.deviation);
    assert!(
        m.triangles.len() < 400,
        "{} triangles: the short span's bound spread over the face",
        m.triangles.len()
    );
    // the short span has the most vertices per unit of u
    let (short, long) = m.uv.iter().fold(
        (0, 0),
        |(a, b), p| {
            if p[0] < 0.01 {
                (a + 1, b)
            } else {
                (a, b + 1)
            }
        },
    );
    assert!(
        short * 10 > long,
        "{short} vertices on the short span, {long} on the long one"
    );
    // the vertices are on the surface and the triangles' midpoints within the bound
    for t in &m.triangles {
        let c = t.iter().fold([0.0; 5], |c, &k| {
            let (p, q) = (m.uv[k as usize], m.vertices.point(k as usize));
            [
                c[0] + p[0] / 3.0,
                c[1] + p[1] / 3.0,
                c[2] + q[0] / 3.0,
                c[3] + q[1] / 3.0,
                c[4] + q[2] / 3.0,
            ]
        });
        let on = s.eval(c[0], c[1]).unwrap();
        let d = ((on[0] - c[2]).powi(2) + (on[1] - c[3]).powi(2) + (on[2] - c[4]).powi(2)).sqrt();
        assert!(d <= m.deviation + 1e-12, "centroid {d} off the surface");
    }
}

/// A planar sector with a collapsed edge: `S(u, v) = u·A(v)`, `A` a quadratic B-spline arc
/// round three quarters of a turn, so the side `u = 0` is one point (a pole). Its loop (out
/// along `v = 0`, round `u = 1`, back along `v = 1`) reaches the pole at `v = 1` and leaves it
/// at `v = 0`: in `(u, v)` it runs along the pole between them. That run, taken as one segment
/// (or cut off by the polygon), kept triangles whose bound no refinement could lower: the
/// mesh reported a deviation far above the tolerance. Points along the pole (one point in
/// space) bring it within.
#[test]
fn a_loop_along_a_pole_is_meshed_within_the_tolerance() {
    let arc = [
        [1.0, 0.0],
        [1.0, 1.0],
        [-1.0, 1.0],
        [-1.0, -1.0],
        [0.0, -1.0],
    ];
    let mut pts = Vec::new();
    for r in [0.0, 1.0] {
        for a in arc {
            pts.push([r * a[0], r * a[1], 0.0]);
        }
    }
    let s = Surface::from(
        BSplineSurface::new(
            1,
            2,
            vec![0.0, 0.0, 1.0, 1.0],
            vec![0.0, 0.0, 0.0, 1.0 / 3.0, 2.0 / 3.0, 1.0, 1.0, 1.0],
            Points::from_3d(&pts).unwrap(),
            (2, 5),
        )
        .unwrap(),
    );
    let f = domain_face(s, &[[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]], false);
    for tol in [1e-2, 1e-3] {
        let m = f.mesh(tol).unwrap();
        assert!(m.deviation <= tol, "bound {} above {tol}", m.deviation);
        // the sector's area: the mesh's within its length times the tolerance
        let a = area3(&m);
        assert!(a > 1.0, "area {a}: the sector is not covered");
    }
}

/// Every mesh of `r` is within `tol` or named in `above_tolerance` with its bound.
fn check_reported(r: &FaceMeshes, tol: f64) {
    for (i, m) in &r.meshes {
        let listed = r.above_tolerance.iter().find(|(k, _)| k == i);
        match listed {
            None => assert!(m.deviation <= tol, "face {i}: {} unreported", m.deviation),
            Some((_, e)) => assert_eq!(
                e,
                &Error::ToleranceNotMet {
                    what: "the face's mesh".into(),
                    deviation: m.deviation,
                    tolerance: tol,
                }
            ),
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(16))]
    /// Whatever the rounds of refinement, each face's mesh is within the tolerance or reported.
    #[test]
    fn every_mesh_is_within_its_tolerance_or_reported(
        e in 1.5f64..4.0,
        rounds in 0usize..4,
        cut in 0.3f64..0.9,
    ) {
        let c = [[0.0, 0.0], [1.0, 0.0], [1.0, cut], [cut, 1.0], [0.0, 1.0]];
        let f = Face::new(saddle(), saddle_loop(&c), vec![], true, LOOP_CLOSURE_RTOL).unwrap();
        let tol = 10f64.powf(-e);
        let (r, _) = super::super::mesh_set::mesh_counted(&[&f], tol, rounds).unwrap();
        check_reported(&r, tol);
    }
}

/// A small bicubic patch of a bearing exported from a CAD system (its net copied here), the
/// face bounded by its domain's four sides. At a tolerance far above its curvature's bound one
/// cell of the grid meets it, and the mesh has no more triangles than the uniform grid whose
/// triangles meet the tolerance by the same bound (`Curvature::triangle`). Each edge started
/// at four segments per knot span whatever the tolerance: 14 triangles where 2 do, on each of
/// a hundred such faces of the part.
#[test]
fn a_single_patch_face_has_no_more_triangles_than_the_uniform_grid_needs() {
    let net = [
        [-0.004492467, -0.02130646, 0.01790605],
        [-0.003696251, -0.02156766, 0.01789697],
        [-0.003145416, -0.02229409, 0.01795252],
        [-0.003112558, -0.02312631, 0.01804525],
        [-0.004544573, -0.02143059, 0.01681363],
        [-0.003748849, -0.02169207, 0.01680459],
        [-0.003198486, -0.02241827, 0.01686014],
        [-0.003165644, -0.02325012, 0.01695282],
        [-0.004596675, -0.02155471, 0.0157212],
        [-0.003801435, -0.02181648, 0.01571221],
        [-0.003251562, -0.02254244, 0.01576776],
        [-0.003218729, -0.02337392, 0.01586039],
        [-0.004648815, -0.02167881, 0.01462876],
        [-0.003854049, -0.02194086, 0.01461984],
        [-0.003304633, -0.02266659, 0.01467537],
        [-0.003271815, -0.0234977, 0.01476796],
    ];
    let knots = vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0];
    let s = Surface::from(
        BSplineSurface::new(
            3,
            3,
            knots.clone(),
            knots,
            Points::from_3d(&net).unwrap(),
            (4, 4),
        )
        .unwrap(),
    );
    let corners = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
    let f = domain_face(s, &corners, true);
    for tol in [0.1, 1e-4, 1e-5] {
        let m = f.mesh(tol).unwrap();
        assert!(m.deviation <= tol, "{} > {tol}", m.deviation);
        // the fewest n × n cells whose triangles are within tol by the mesh's own bound
        let (plan, _) = plan_face(&f, tol, MAX_REFINE_ROUNDS).unwrap();
        let n = (1..=64)
            .find(|&n| {
                let h = 1.0 / n as f64;
                (0..n).all(|i| {
                    (0..n).all(|j| {
                        let (u0, v0) = (i as f64 * h, j as f64 * h);
                        let (a, b, c, d) = ([u0, v0], [u0 + h, v0], [u0 + h, v0 + h], [u0, v0 + h]);
                        plan.curv.triangle([a, b, c]) <= tol && plan.curv.triangle([a, c, d]) <= tol
                    })
                })
            })
            .unwrap();
        assert!(
            m.triangles.len() <= 2 * n * n,
            "{} triangles at {tol}, where the uniform {n} × {n} grid's {} are within it",
            m.triangles.len(),
            2 * n * n
        );
    }
}

/// A rod of a CAD part as a face: the quarter-arc NURBS cylinder of radius 1.0795 and length
/// 1147.7625 bounded by its end circles, meshed at 0.1. Its grid follows the rational bounds
/// of `Curvature`: taken about a constant centre, the long straight direction entered every
/// term and the face took some 10⁵ triangles, where eight steps round and one along are within
/// 0.1 (the chord of an eighth of the circle deviates by `r (1 − cos(π/8)) ≈ 0.082`).
#[test]
fn a_long_rational_rod_face_has_no_more_triangles_than_a_few_uniform_grids() {
    use crate::surface::Placement;
    use crate::{NurbsCurve, NurbsSurface};
    use std::f64::consts::{PI, TAU};
    let (r, length, tol) = (1.0795, 1147.7625, 0.1);
    let circle = |z: f64, up: bool| {
        let c = Curve::from(
            NurbsCurve::circle(&[0.0, 0.0, z], &[1.0, 0.0, 0.0], &[0.0, 1.0, 0.0], r).unwrap(),
        );
        Edge::new(if up { c } else { c.reverse().unwrap() }, None).unwrap()
    };
    let frame = Placement::new([0.0; 3], None, None).unwrap();
    let rod = Surface::from(NurbsSurface::cylinder(&frame, r, (0.0, TAU), (0.0, length)).unwrap());
    let f = Face::new(
        rod,
        Loop::new(vec![circle(0.0, true)]).unwrap(),
        vec![Loop::new(vec![circle(length, false)]).unwrap()],
        true,
        LOOP_CLOSURE_RTOL,
    )
    .unwrap()
    .with_projected_pcurves(1e-7)
    .unwrap();
    // the fewest equal steps round whose chords are within the tolerance
    let n = (3..64)
        .find(|&n| r * (1.0 - (PI / n as f64).cos()) <= tol)
        .unwrap();
    assert_eq!(n, 8);
    let m = f.mesh(tol).unwrap();
    assert!(m.deviation <= tol, "{}", m.deviation);
    assert!(
        m.triangles.len() <= 4 * 2 * n,
        "{} triangles, where {} of a uniform grid are within {tol}",
        m.triangles.len(),
        2 * n
    );
}

/// Two squares of the plane `z = 0`, `[0, 2]²` and `[2, 4] × [0, 2]`, sharing the edge
/// `x = 2`; at its end `(2, 2)` the first face's next edge starts at `(2 − 5e-5, 2)` and the
/// second face's edge before it ends at `(2 + 5e-5, 2)`, 1e-4 apart, as a file's edges meet
/// within its tolerance. Each face closes its loop at the corner's vertex (one point for both),
/// so their meshes have the same points along the shared edge; a face closing its loop at its
/// own next edge's start left a crack whose gap the measure of the shared edge took as the
/// edge's whole length.
#[test]
fn faces_whose_edges_meet_within_a_tolerance_close_their_loops_at_the_shared_vertex() {
    use super::super::tests::segment;
    let gap = 5e-5;
    let shared = segment([2.0, 0.0], [2.0, 2.0]);
    let back = Edge::new(
        shared.curve().reverse().unwrap(),
        Some(shared.pcurve().unwrap().reverse().unwrap()),
    )
    .unwrap();
    let a = Loop::new(vec![
        segment([0.0, 0.0], [2.0, 0.0]),
        shared,
        segment([2.0 - gap, 2.0], [0.0, 2.0]),
        segment([0.0, 2.0], [0.0, 0.0]),
    ])
    .unwrap();
    let b = Loop::new(vec![
        segment([2.0, 0.0], [4.0, 0.0]),
        segment([4.0, 0.0], [4.0, 2.0]),
        segment([4.0, 2.0], [2.0 + gap, 2.0]),
        back,
    ])
    .unwrap();
    let fa = Face::new(plane(), a, vec![], true, LOOP_CLOSURE_RTOL).unwrap();
    let fb = Face::new(plane(), b, vec![], true, LOOP_CLOSURE_RTOL).unwrap();
    let tol = 1e-3;
    let ms = mesh_faces(&[&fa, &fb], tol).unwrap();
    // the points of a mesh within the tolerance of the shared edge
    let along = |m: &Mesh| -> Vec<Vec<f64>> {
        (0..m.vertices.len())
            .map(|k| m.vertices.point(k).to_vec())
            .filter(|p| (p[0] - 2.0).abs() <= tol && p[1] >= -tol && p[1] <= 2.0 + tol)
            .collect()
    };
    let (ea, eb) = (along(&ms[0]), along(&ms[1]));
    assert!(ea.len() >= 2, "the shared edge's ends: {ea:?}");
    for (p, q, which) in [(&ea, &eb, "first"), (&eb, &ea, "second")] {
        for x in p {
            assert!(
                q.contains(x),
                "{x:?} of the {which} face's mesh along the shared edge is no vertex of the other's: a crack at the corner"
            );
        }
    }
    // the corner is one point, near both ends
    let top: Vec<&Vec<f64>> = ea.iter().filter(|p| p[1] > 2.0 - tol).collect();
    assert_eq!(top.len(), 1, "one corner point: {top:?}");
    assert!(dist(top[0], &[2.0, 2.0, 0.0]) <= 2.0 * gap, "{:?}", top[0]);
    for m in &ms {
        assert!(m.deviation <= tol, "{}", m.deviation);
    }
}

/// The normals of a set of faces' joined mesh: each vertex's the exact unit normal of the
/// saddle `z = u² − v²`, `(−2u, 2v, 1) / |…|`, turned for the face whose sense is reversed, so
/// every vertex's normal is on the side its triangles turn about; a face past the set given
/// has none.
#[test]
fn the_normals_of_a_set_of_faces_are_their_surfaces_turned_by_their_sense() {
    let a = saddle_loop(&[[0.0, 0.0], [0.5, 0.0], [0.5, 1.0], [0.0, 1.0]]);
    // the right half with the face's normal against the surface's: its loop runs clockwise
    let b = saddle_loop(&[[0.5, 0.0], [0.5, 1.0], [1.0, 1.0], [1.0, 0.0]]);
    let fa = Face::new(saddle(), a, vec![], true, LOOP_CLOSURE_RTOL).unwrap();
    let fb = Face::new(saddle(), b, vec![], false, LOOP_CLOSURE_RTOL).unwrap();
    let r = mesh_faces_each(&[&fa, &fb], 1e-3).unwrap();
    assert!(r.failures.is_empty());
    let joined = r.join().unwrap();
    let normals = r.surface_normals(&[&fa, &fb]);
    assert_eq!(normals.len(), joined.vertices.len());
    let first = r.meshes[0].1.vertices.len();
    for (k, n) in normals.iter().enumerate() {
        let n = n.unwrap();
        let [u, v] = joined.uv[k];
        let l = (4.0 * u * u + 4.0 * v * v + 1.0).sqrt();
        let sign = if k < first { 1.0 } else { -1.0 };
        let exact = [-2.0 * u / l, 2.0 * v / l, 1.0 / l].map(|x| sign * x);
        for d in 0..3 {
            assert!(
                (n[d] - exact[d]).abs() < 1e-12,
                "vertex {k}: {n:?}, not {exact:?}"
            );
        }
    }
    for (t, tri) in joined.triangles.iter().enumerate() {
        let f = joined.facet_normal(t).unwrap();
        for &k in tri {
            let n = normals[k as usize].unwrap();
            let dot: f64 = (0..3).map(|d| f[d] * n[d]).sum();
            assert!(dot > 0.0, "triangle {t} turns against vertex {k}'s normal");
        }
    }
    // the set given shorter than the set meshed: the missing face's vertices have none
    let short = r.surface_normals(&[&fa]);
    assert_eq!(short[..first], normals[..first]);
    assert!(short[first..].iter().all(Option::is_none));
}
