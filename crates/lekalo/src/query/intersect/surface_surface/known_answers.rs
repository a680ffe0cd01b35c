//! More sections with exact answers: two spheres (a circle), Viviani's curve (a sphere and a
//! cylinder tangent at the curve's double point), a torus touched along a circle by a plane,
//! and the Villarceau circles of a bitangent plane through the torus's centre (two circles
//! crossing at the plane's two points of contact).

use std::f64::consts::{FRAC_PI_2, TAU};

use super::IntersectionBranch;
use crate::query::Contact;
use crate::surface::Placement;
use crate::{NurbsSurface, QuerySurface};

const TOL: f64 = 1e-6;

fn frame(origin: [f64; 3], axis: [f64; 3], x: [f64; 3]) -> Placement {
    Placement::new(origin, Some(axis), Some(x)).unwrap()
}

fn sphere_at(o: [f64; 3], r: f64) -> QuerySurface {
    let f = frame(o, [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]);
    QuerySurface::from_nurbs(
        &NurbsSurface::sphere(&f, r, (0.0, TAU), (-FRAC_PI_2, FRAC_PI_2)).unwrap(),
    )
    .unwrap()
}

fn torus() -> QuerySurface {
    let f = frame([0.0; 3], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]);
    QuerySurface::from_nurbs(&NurbsSurface::torus(&f, 3.0, 1.0, (0.0, TAU), (0.0, TAU)).unwrap())
        .unwrap()
}

fn on_torus(p: &[f64; 3]) -> f64 {
    (p[0].hypot(p[1]) - 3.0).hypot(p[2]) - 1.0
}

/// An implicit equation: zero on the surface, a distance near it.
type Implicit<'a> = &'a dyn Fn(&[f64; 3]) -> f64;

/// Every point of every branch within `tol` of the zero sets of `eqs`.
fn check_points(branches: &[IntersectionBranch], eqs: &[Implicit<'_>], tol: f64) {
    for b in branches {
        for p in &b.points {
            for (i, e) in eqs.iter().enumerate() {
                assert!(
                    e(p).abs() <= tol,
                    "equation {i} at {p:?}: {} ({:?})",
                    e(p),
                    b.kind
                );
            }
        }
    }
}

/// Whether `p` is within `d` of a point or a chord of some branch.
fn covered(branches: &[IntersectionBranch], p: &[f64; 3], d: f64) -> bool {
    branches.iter().any(|b| {
        b.points.iter().any(|q| super::dist(p, q) <= d)
            || b.points
                .windows(2)
                .any(|w| super::segment_distance3(p, &w[0], &w[1]) <= d)
    })
}

#[test]
fn two_spheres_meet_in_a_circle() {
    // |x| = 2 and |x − (0, 0, 2)| = 1.5: the circle z = 23/16, ρ² = 4 − (23/16)²
    let a = sphere_at([0.0; 3], 2.0);
    let b = sphere_at([0.0, 0.0, 2.0], 1.5);
    let br = a.intersect_surface(&b, TOL).unwrap();
    let on_a = |p: &[f64; 3]| p[0].hypot(p[1]).hypot(p[2]) - 2.0;
    let on_b = |p: &[f64; 3]| p[0].hypot(p[1]).hypot(p[2] - 2.0) - 1.5;
    check_points(&br, &[&on_a, &on_b], TOL);
    assert!(br.iter().all(|x| x.kind == Contact::Crossing), "{br:?}");
    let (z, rho) = (23.0 / 16.0, (4.0 - (23.0_f64 / 16.0).powi(2)).sqrt());
    for i in 0..64 {
        let t = TAU * f64::from(i) / 64.0;
        let p = [rho * t.cos(), rho * t.sin(), z];
        assert!(covered(&br, &p, 2.0 * TOL), "{p:?} missed: {br:?}");
    }
    let total: f64 = br.iter().map(IntersectionBranch::length).sum();
    assert!(
        (total - TAU * rho).abs() <= 1e-3 * rho,
        "{total} vs {}",
        TAU * rho
    );
}

#[test]
fn viviani_figure_eight_through_the_point_of_contact() {
    // the sphere |x| = 2 and the cylinder (x − 1)² + y² = 1: Viviani's curve
    // (1 + cos t, sin t, 2 sin(t/2)), a figure eight whose double point (2, 0, 0) is where the
    // surfaces touch (both normals along x)
    let s = sphere_at([0.0; 3], 2.0);
    let c = QuerySurface::from_nurbs(
        &NurbsSurface::cylinder(
            &frame([1.0, 0.0, 0.0], [0.0, 0.0, 1.0], [-1.0, 0.0, 0.0]),
            1.0,
            (0.0, TAU),
            (-3.0, 3.0),
        )
        .unwrap(),
    )
    .unwrap();
    let br = s.intersect_surface(&c, TOL).unwrap();
    let on_s = |p: &[f64; 3]| p[0].hypot(p[1]).hypot(p[2]) - 2.0;
    let on_c = |p: &[f64; 3]| (p[0] - 1.0).hypot(p[1]) - 1.0;
    // near the contact the points are found to the square root of the tolerance
    check_points(&br, &[&on_s, &on_c], TOL);
    for i in 0..128 {
        let t = 2.0 * TAU * (f64::from(i) + 0.5) / 128.0;
        let p = [1.0 + t.cos(), t.sin(), 2.0 * (t / 2.0).sin()];
        if super::dist(&p, &[2.0, 0.0, 0.0]) < 0.05 {
            continue;
        }
        assert!(
            covered(&br, &p, 2.0 * TOL),
            "{p:?} (t = {t}) missed: {br:?}"
        );
    }
    let total: f64 = br
        .iter()
        .filter(|x| x.kind == Contact::Crossing)
        .map(IntersectionBranch::length)
        .sum();
    // the length of Viviani's curve: ∫₀^{4π} √(1 + cos²(t/2)) dt = 8 E(−1)… numerically
    let exact: f64 = {
        let n = 200_000;
        let h = 2.0 * TAU / f64::from(n);
        (0..n)
            .map(|i| {
                let t = (f64::from(i) + 0.5) * h;
                (1.0 + (t / 2.0).cos().powi(2)).sqrt() * h
            })
            .sum()
    };
    assert!((total - exact).abs() <= 1e-2, "{total} vs {exact}: {br:?}");
    assert!(
        !br.iter().any(|x| x.kind == Contact::Overlap),
        "no overlap: {br:?}"
    );
    // the double point, where the surfaces touch, is a tangent contact
    assert!(
        br.iter().any(|x| matches!(x.kind, Contact::Tangent { .. })
            && x.points
                .iter()
                .any(|y| super::dist(y, &[2.0, 0.0, 0.0]) <= 1e-3)),
        "the contact at (2, 0, 0) is missing: {br:?}"
    );
}

#[test]
fn a_plane_touches_the_torus_along_its_top_circle() {
    // z = 1 touches the torus (R = 3, r = 1) along the circle ρ = 3: a line of contact
    let t = torus();
    let br = t
        .intersect_plane(&[0.0, 0.0, 1.0], &[0.0, 0.0, 1.0], TOL)
        .unwrap();
    // one closed line of contact, its points in order around the circle
    assert_eq!(br.len(), 1, "{br:?}");
    assert!(matches!(br[0].kind, Contact::Tangent { .. }), "{br:?}");
    assert!(br[0].closed, "the line of contact closes");
    let steps = br[0]
        .points
        .windows(2)
        .filter(|w| super::dist(&w[0], &w[1]) > 0.1)
        .count();
    assert_eq!(steps, 0, "points out of order along the circle");
    for b in &br {
        for p in &b.points {
            assert!(
                (p[2] - 1.0).abs() <= TOL && on_torus(p).abs() <= TOL,
                "{p:?}"
            );
        }
    }
    for i in 0..32 {
        let a = TAU * f64::from(i) / 32.0;
        let p = [3.0 * a.cos(), 3.0 * a.sin(), 1.0];
        assert!(covered(&br, &p, 0.05), "{p:?} missed: {br:?}");
    }
    // the same plane as a surface: the circle is covered by contacts only
    let f = frame([0.0, 0.0, 1.0], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]);
    let pl = QuerySurface::from_bspline(
        &crate::BSplineSurface::plane_patch(&f, (-5.0, 5.0), (-5.0, 5.0)).unwrap(),
    )
    .unwrap();
    let br = t.intersect_surface(&pl, TOL).unwrap();
    assert!(
        br.iter().all(|x| matches!(x.kind, Contact::Tangent { .. })),
        "{br:?}"
    );
    for i in 0..32 {
        let a = TAU * f64::from(i) / 32.0;
        let p = [3.0 * a.cos(), 3.0 * a.sin(), 1.0];
        assert!(covered(&br, &p, 0.05), "{p:?} missed: {br:?}");
    }
}

#[test]
fn villarceau_circles_cross_at_the_points_of_contact() {
    // the plane through the centre with normal (−sin α, 0, cos α)·, sin α = r/R = 1/3, touches
    // the torus at two points and cuts it in two circles of radius R = 3 centred at (0, ±1, 0)
    let t = torus();
    let (s, c) = (1.0 / 3.0, (8.0_f64).sqrt() / 3.0);
    let n = [-s, 0.0, c];
    let br = t.intersect_plane(&[0.0; 3], &n, TOL).unwrap();
    let on_plane = |p: &[f64; 3]| -s * p[0] + c * p[2];
    check_points(&br, &[&on_plane, &on_torus], TOL);
    // in the plane's frame e₁ = (c, 0, s), e₂ = (0, 1, 0): the circles |q − (0, ±1)| = 3
    for sign in [-1.0, 1.0] {
        for i in 0..64 {
            let a = TAU * (f64::from(i) + 0.5) / 64.0;
            let (q1, q2) = (3.0 * a.cos(), sign + 3.0 * a.sin());
            let p = [c * q1, q2, s * q1];
            // the circles cross at q = (±√8, 0), where the plane touches the torus
            if q2.abs() < 0.05 {
                continue;
            }
            assert!(covered(&br, &p, 2.0 * TOL), "{p:?} missed: {br:?}");
        }
    }
    let total: f64 = br
        .iter()
        .filter(|x| x.kind == Contact::Crossing)
        .map(IntersectionBranch::length)
        .sum();
    assert!((total - 2.0 * TAU * 3.0).abs() <= 0.05, "{total}: {br:?}");
    // the two points of contact, q = (±√8, 0), reported as tangent contacts
    for side in [-1.0, 1.0] {
        let q = side * 8.0_f64.sqrt();
        let p = [c * q, 0.0, s * q];
        assert!(
            br.iter().any(|x| matches!(x.kind, Contact::Tangent { .. })
                && x.points.iter().any(|y| super::dist(y, &p) <= 1e-3)),
            "the contact at {p:?} is missing: {br:?}"
        );
    }
}
