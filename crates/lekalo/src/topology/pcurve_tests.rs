//! Pcurves by projection: faces given by their 3-D edges alone (a plane with a hole, two faces
//! of a NURBS cylinder, one across its seam, a cone through its apex) get pcurves on the
//! surface, mesh to their exact areas and meet without cracks; an edge off the surface is
//! refused; a band round a cylinder without a seam edge meshes.

use std::f64::consts::PI;

use super::super::tests::{hole, plane, square};
use super::*;
use crate::query::Mesh;
use crate::topology::mesh_faces;
use crate::{NurbsCurve, NurbsSurface};

/// The loop with its edges' 3-D curves only.
fn bare(lp: &Loop) -> Loop {
    Loop::new(
        lp.edges()
            .iter()
            .map(|e| Edge::new(e.curve().clone(), None).unwrap())
            .collect(),
    )
    .unwrap()
}

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

/// The surface at every edge's pcurve is within `tol` of the edge (the edges lie on the
/// surface), at 257 points of each edge; the loops close in `(u, v)` except at a pole.
fn check_on_surface(f: &Face, tol: f64) {
    let closure = SurfaceClosure::of(f.surface(), tol).unwrap();
    let dom = f.surface().domain();
    for lp in f.loops() {
        for e in lp.edges() {
            let p = e.pcurve().expect("a pcurve");
            let (a, b) = e.curve().domain();
            assert_eq!(
                p.domain(),
                (a, b),
                "the pcurve runs over the curve's parameters"
            );
            for k in 0..=256 {
                let t = (a + (b - a) * f64::from(k) / 256.0).min(b);
                let uv = p.eval(t).unwrap();
                let w = closure.wrap(dom, [uv[0], uv[1]]);
                let s = f.surface().eval(w[0], w[1]).unwrap();
                let c = e.curve().eval(t).unwrap();
                assert!(dist(&s, &c) <= tol, "{} at t = {t}", dist(&s, &c));
            }
        }
    }
}

#[test]
fn a_plane_with_a_hole_gets_its_pcurves_and_the_area_of_the_ring() {
    let f = Face::new(
        plane(),
        bare(&square(false)),
        vec![bare(&hole(true))],
        true,
        LOOP_CLOSURE_RTOL,
    )
    .unwrap();
    assert!(!f.has_pcurves());
    let g = f.with_projected_pcurves(1e-7).unwrap();
    assert!(g.has_pcurves());
    check_on_surface(&g, 1e-7);
    // on the plane (u, v) = (x, y)
    for lp in g.loops() {
        for e in lp.edges() {
            let (a, b) = e.curve().domain();
            for k in 0..=16 {
                let t = a + (b - a) * f64::from(k) / 16.0;
                let (uv, c) = (
                    e.pcurve().unwrap().eval(t).unwrap(),
                    e.curve().eval(t).unwrap(),
                );
                assert!((uv[0] - c[0]).abs() < 1e-6 && (uv[1] - c[1]).abs() < 1e-6);
            }
        }
    }
    // the square [0, 4]² less the unit disc: an inscribed polygon within tol of the circle
    let tol = 1e-3;
    let m = g.mesh(tol).unwrap();
    let exact = 16.0 - PI;
    let a = area3(&m);
    assert!(
        a >= exact - 1e-9 && a - exact <= 2.0 * PI * tol,
        "area {a} against {exact}"
    );
    // a face with its pcurves is returned as it is
    assert_eq!(g.with_projected_pcurves(1e-7).unwrap(), g);
}

const H: f64 = 2.0;

/// The unit cylinder about the z axis, `0 ≤ z ≤ 2`, as a NURBS surface: `u` along the circle
/// (a rational quadratic of 9 points from the x axis, over `[0, 1]`), `v = z`.
fn cylinder() -> Surface {
    let c = NurbsCurve::circle(&[0.0, 0.0, 0.0], &[1.0, 0.0, 0.0], &[0.0, 1.0, 0.0], 1.0).unwrap();
    let (pts, w) = (c.control_points(), c.weights());
    let mut net = Vec::new();
    let mut ws = Vec::new();
    for i in 0..pts.len() {
        let p = pts.point(i);
        for z in [0.0, H] {
            net.push([p[0], p[1], z]);
            ws.push(w[i]);
        }
    }
    Surface::from(
        NurbsSurface::new(
            2,
            1,
            c.knots().as_slice().to_vec(),
            vec![0.0, 0.0, H, H],
            Points::from_3d(&net).unwrap(),
            ws,
            (pts.len(), 2),
        )
        .unwrap(),
    )
}

fn arc(z: f64, from: f64, to: f64) -> Curve {
    let (lo, hi) = (from.min(to), from.max(to));
    let c = Curve::from(
        NurbsCurve::circular_arc(
            &[0.0, 0.0, z],
            &[1.0, 0.0, 0.0],
            &[0.0, 1.0, 0.0],
            1.0,
            lo,
            hi,
        )
        .unwrap(),
    );
    if from < to {
        c
    } else {
        c.reverse().unwrap()
    }
}

fn line(angle: f64, z0: f64, z1: f64) -> Curve {
    let (x, y) = (angle.cos(), angle.sin());
    Curve::from(BSplineCurve::line_segment(&[x, y, z0], &[0.0, 0.0, z1 - z0], 0.0, 1.0).unwrap())
}

fn bare_edge(c: Curve) -> Edge {
    Edge::new(c, None).unwrap()
}

/// Two faces of the cylinder between `z = 0.5` and `z = 1.5`: from angle −0.5 to 0.5 (across
/// the seam at angle 0) and the rest, sharing the lines at ±0.5, without pcurves.
fn cylinder_faces() -> (Face, Face) {
    let (a, b) = (-0.5, 0.5);
    let right = line(b, 0.5, 1.5);
    let left = line(a, 1.5, 0.5);
    let fa = Face::new(
        cylinder(),
        Loop::new(vec![
            bare_edge(arc(0.5, a, b)),
            bare_edge(right.clone()),
            bare_edge(arc(1.5, b, a)),
            bare_edge(left.clone()),
        ])
        .unwrap(),
        vec![],
        true,
        LOOP_CLOSURE_RTOL,
    )
    .unwrap();
    let fb = Face::new(
        cylinder(),
        Loop::new(vec![
            bare_edge(arc(0.5, b, 2.0 * PI + a)),
            bare_edge(left.reverse().unwrap()),
            bare_edge(arc(1.5, 2.0 * PI + a, b)),
            bare_edge(right.reverse().unwrap()),
        ])
        .unwrap(),
        vec![],
        true,
        LOOP_CLOSURE_RTOL,
    )
    .unwrap();
    (fa, fb)
}

#[test]
fn the_cylinder_closes_in_u_and_has_no_pole() {
    let c = SurfaceClosure::of(&cylinder(), 1e-9).unwrap();
    assert_eq!(c.period, [Some(1.0), None]);
    assert_eq!(c.pole, [false; 4]);
    let ((u0, u1), dv) = cylinder().domain();
    assert_eq!(c.wrap(((u0, u1), dv), [1.25, 0.5]), [0.25, 0.5]);
    assert_eq!(c.wrap(((u0, u1), dv), [-0.25, 3.0]), [0.75, H]);
}

#[test]
fn cylinder_faces_across_the_seam_mesh_to_their_areas_without_a_crack() {
    let (fa, fb) = cylinder_faces();
    let ptol = 1e-6;
    let (ga, gb) = (
        fa.with_projected_pcurves(ptol).unwrap(),
        fb.with_projected_pcurves(ptol).unwrap(),
    );
    check_on_surface(&ga, ptol);
    check_on_surface(&gb, ptol);
    // the face across the seam is one piece in (u, v): its bottom edge spans a sixth of the
    // turn, not the rest of it
    let p = ga.outer().edges()[0].pcurve().unwrap();
    let (t0, t1) = p.domain();
    let (s, e) = (p.eval(t0).unwrap(), p.eval(t1).unwrap());
    assert!((e[0] - s[0]).abs() < 0.25, "{s:?} to {e:?}");
    let tol = 1e-3;
    let ms = mesh_faces(&[&ga, &gb], tol).unwrap();
    // inscribed triangles within tol of a cylinder of radius 1 lose at most tol of the area per
    // unit area (a chord of sagitta δ is shorter than its arc by δ/3 of it), and the trims at
    // most tol times their length
    for (m, exact) in [(&ms[0], 1.0), (&ms[1], 2.0 * PI - 1.0)] {
        let perimeter = 2.0 * (exact + 1.0);
        let a = area3(m);
        assert!(
            (a - exact).abs() <= (exact + perimeter) * tol,
            "area {a} against {exact}"
        );
        // no triangle crosses the cylinder the wrong way round: every side's midpoint is
        // within the tolerance of the cylinder of radius 1 about the z axis (a side may run
        // far along a straight ruling)
        for t in &m.triangles {
            for (i, j) in [(0, 1), (1, 2), (2, 0)] {
                let (a, b) = (
                    m.vertices.point(t[i] as usize),
                    m.vertices.point(t[j] as usize),
                );
                let r = (0.25 * ((a[0] + b[0]).powi(2) + (a[1] + b[1]).powi(2))).sqrt();
                assert!(
                    r >= 1.0 - tol * (1.0 + 1e-9),
                    "a triangle side from {a:?} to {b:?} cuts the cylinder ({r})"
                );
            }
        }
    }
    // the shared lines: the same vertices in both meshes, so no crack
    for angle in [-0.5_f64, 0.5] {
        let on = |m: &Mesh| -> Vec<Vec<f64>> {
            (0..m.vertices.len())
                .map(|k| m.vertices.point(k).to_vec())
                .filter(|p| {
                    (p[0] - angle.cos()).abs() < 1e-12 && (p[1] - angle.sin()).abs() < 1e-12
                })
                .collect()
        };
        let (ea, eb) = (on(&ms[0]), on(&ms[1]));
        // a straight ruling: its two ends at least, the same in both meshes
        assert!(ea.len() >= 2, "the shared edge's ends are vertices");
        assert_eq!(ea.len(), eb.len());
        // the same points, the corners taken from one face's arc and the other's line
        for p in &ea {
            assert!(
                eb.iter().any(|q| dist(p, q) <= 1e-12),
                "{p:?} of one face is not a vertex of the other"
            );
        }
    }
}

/// At a mesh tolerance near the face's own size the pcurves are still sampled finely enough to
/// enclose the face: the coarse mesh has triangles, and its area is the face's within the
/// tolerance's bound (before, three points a circle enclosed nothing and the mesh was empty).
#[test]
fn a_coarse_tolerance_still_meshes_the_face() {
    let (fa, _) = cylinder_faces();
    for tol in [0.5, 5.0] {
        let g = fa.with_projected_pcurves(tol).unwrap();
        let ms = mesh_faces(&[&g], tol).unwrap();
        assert!(!ms[0].triangles.is_empty(), "no triangles at {tol}");
        assert!(area3(&ms[0]) > 0.5, "area {} at {tol}", area3(&ms[0]));
    }
}

/// The cone of base radius 1 at `z = 0` and apex `(0, 0, 1)`: `u` along the circle, `v` from
/// the base (0) to the apex (1), a pole.
fn cone() -> Surface {
    let c = NurbsCurve::circle(&[0.0, 0.0, 0.0], &[1.0, 0.0, 0.0], &[0.0, 1.0, 0.0], 1.0).unwrap();
    let (pts, w) = (c.control_points(), c.weights());
    let mut net = Vec::new();
    let mut ws = Vec::new();
    for i in 0..pts.len() {
        let p = pts.point(i);
        net.push([p[0], p[1], 0.0]);
        net.push([0.0, 0.0, 1.0]);
        ws.extend([w[i], w[i]]);
    }
    Surface::from(
        NurbsSurface::new(
            2,
            1,
            c.knots().as_slice().to_vec(),
            vec![0.0, 0.0, 1.0, 1.0],
            Points::from_3d(&net).unwrap(),
            ws,
            (pts.len(), 2),
        )
        .unwrap(),
    )
}

#[test]
fn a_cone_through_its_apex_goes_round_at_the_pole() {
    let s = cone();
    let c = SurfaceClosure::of(&s, 1e-9).unwrap();
    assert_eq!(c.period, [Some(1.0), None]);
    assert_eq!(c.pole, [false, false, false, true]);
    // the base circle, the seam up to the apex and back down
    let seam = Curve::from(
        BSplineCurve::line_segment(&[1.0, 0.0, 0.0], &[-1.0, 0.0, 1.0], 0.0, 1.0).unwrap(),
    );
    let f = Face::new(
        s,
        Loop::new(vec![
            bare_edge(arc(0.0, 0.0, 2.0 * PI)),
            bare_edge(seam.clone()),
            bare_edge(seam.reverse().unwrap()),
        ])
        .unwrap(),
        vec![],
        true,
        LOOP_CLOSURE_RTOL,
    )
    .unwrap();
    let g = f.with_projected_pcurves(1e-6).unwrap();
    check_on_surface(&g, 1e-6);
    let tol = 1e-3;
    let m = g.mesh(tol).unwrap();
    let slant = 2.0_f64.sqrt();
    let exact = PI * slant;
    let perimeter = 2.0 * PI + 2.0 * slant;
    let a = area3(&m);
    assert!(
        (a - exact).abs() <= (exact + perimeter) * tol,
        "area {a} against {exact}"
    );
}

#[test]
fn an_edge_off_the_surface_is_refused_with_its_distance() {
    // the square's right side bulging 0.5 above the plane at its middle
    let mut edges = bare(&square(false)).edges().to_vec();
    edges[1] = bare_edge(Curve::from(
        BSplineCurve::new(
            2,
            vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
            Points::from_3d(&[[4.0, 0.0, 0.0], [4.0, 2.0, 1.0], [4.0, 4.0, 0.0]]).unwrap(),
        )
        .unwrap(),
    ));
    let f = Face::new(
        plane(),
        Loop::new(edges).unwrap(),
        vec![],
        true,
        LOOP_CLOSURE_RTOL,
    )
    .unwrap();
    let e = f.with_projected_pcurves(1e-6).unwrap_err();
    let Error::InvalidArgument { what, reason } = e else {
        panic!("{e:?}")
    };
    assert_eq!(what.words(), "face edge");
    assert!(
        reason.contains("edge 1 of the outer loop") && reason.contains("does not lie on"),
        "{reason}"
    );
    assert!(f.with_projected_pcurves(0.0).is_err());
    assert!(f.with_projected_pcurves(f64::NAN).is_err());
}

/// A band of the cylinder between two circles, without a seam edge: each loop goes once round,
/// its pcurve ending a period from its start (the mesher cuts the face along a seam).
#[test]
fn a_loop_round_the_cylinder_without_a_seam_edge_goes_round_once() {
    let f = Face::new(
        cylinder(),
        Loop::new(vec![bare_edge(arc(0.5, 0.0, 2.0 * PI))]).unwrap(),
        vec![Loop::new(vec![bare_edge(arc(1.5, 2.0 * PI, 0.0))]).unwrap()],
        true,
        LOOP_CLOSURE_RTOL,
    )
    .unwrap();
    let g = f.with_projected_pcurves(1e-6).unwrap();
    check_on_surface(&g, 1e-6);
    for (lp, turn) in [(g.outer(), 1.0), (&g.inner()[0], -1.0)] {
        let p = lp.edges()[0].pcurve().unwrap();
        let (t0, t1) = p.domain();
        let (s, e) = (p.eval(t0).unwrap(), p.eval(t1).unwrap());
        assert!((e[0] - s[0] - turn).abs() < 1e-9, "{s:?} to {e:?}");
    }
    let m = g.mesh(1e-3).unwrap();
    let exact = 2.0 * PI;
    assert!((area3(&m) - exact).abs() <= (exact + 4.0 * PI) * 1e-3);
}

/// A quarter of a torus's tube (major radius 20.5, minor 0.5, about z) from its outer equator to
/// its top, half way round: along the top circle the foot point's Hessian is near singular and
/// Newton's first steps from the previous sample overshoot `v` by whole periods onto the same
/// point; the pcurve stays on the copy next to the previous sample, the loop does not go round,
/// and the face meshes to its area `r (R π/2 + r) π`.
#[test]
fn a_quarter_of_a_torus_tube_keeps_each_foot_point_on_the_copy_next_to_the_last() {
    use crate::surface::Placement;
    let (big, small) = (20.5, 0.5);
    let frame = Placement::new([0.0; 3], None, None).unwrap();
    let torus = Surface::from(
        NurbsSurface::torus(&frame, big, small, (0.0, 2.0 * PI), (0.0, 2.0 * PI)).unwrap(),
    );
    let circle = |z: f64, radius: f64, from: f64, to: f64| {
        let c = Curve::from(
            NurbsCurve::circular_arc(
                &[0.0, 0.0, z],
                &[1.0, 0.0, 0.0],
                &[0.0, 1.0, 0.0],
                radius,
                from.min(to),
                from.max(to),
            )
            .unwrap(),
        );
        if from < to {
            c
        } else {
            c.reverse().unwrap()
        }
    };
    let minor = |at: f64, from: f64, to: f64| {
        let (x, y) = (at.cos(), at.sin());
        let c = Curve::from(
            NurbsCurve::circular_arc(
                &[big * x, big * y, 0.0],
                &[x, y, 0.0],
                &[0.0, 0.0, 1.0],
                small,
                from.min(to),
                from.max(to),
            )
            .unwrap(),
        );
        if from < to {
            c
        } else {
            c.reverse().unwrap()
        }
    };
    let edges = vec![
        bare_edge(circle(0.0, big + small, 0.0, PI)),
        bare_edge(minor(PI, 0.0, 0.5 * PI)),
        bare_edge(circle(small, big, PI, 0.0)),
        bare_edge(minor(0.0, 0.5 * PI, 0.0)),
    ];
    let f = Face::new(
        torus,
        Loop::new(edges).unwrap(),
        vec![],
        true,
        LOOP_CLOSURE_RTOL,
    )
    .unwrap();
    let g = f.with_projected_pcurves(0.1).unwrap();
    check_on_surface(&g, 0.1);
    let m = g.mesh(1e-3).unwrap();
    let exact = small * (big * 0.5 * PI + small) * PI;
    assert!(
        (area3(&m) - exact).abs() <= exact * 1e-3,
        "{} against {exact}",
        area3(&m)
    );
}
