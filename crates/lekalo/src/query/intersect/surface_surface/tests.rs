//! Sections and intersections with exact answers: conics of the quadrics, Steinmetz curves,
//! a small closed loop, contacts, overlaps and misses.

use std::f64::consts::{FRAC_PI_2, FRAC_PI_4, TAU};

use super::IntersectionBranch;
use crate::query::Contact;
use crate::surface::Placement;
use crate::{BSplineSurface, NurbsSurface, Points, QuerySurface};

const TOL: f64 = 1e-6;

fn frame(origin: [f64; 3], axis: [f64; 3], x: [f64; 3]) -> Placement {
    Placement::new(origin, Some(axis), Some(x)).unwrap()
}

fn plane(origin: [f64; 3], axis: [f64; 3], x: [f64; 3], half: f64) -> QuerySurface {
    let s =
        BSplineSurface::plane_patch(&frame(origin, axis, x), (-half, half), (-half, half)).unwrap();
    QuerySurface::from_bspline(&s).unwrap()
}

/// Every point of every branch within `TOL` of both surfaces (by the implicit equations).
/// An implicit equation: zero on the surface, a distance near it.
type Implicit<'a> = &'a dyn Fn(&[f64; 3]) -> f64;

fn check_points(branches: &[IntersectionBranch], eqs: &[Implicit<'_>]) {
    for b in branches {
        for p in &b.points {
            for (i, e) in eqs.iter().enumerate() {
                assert!(e(p).abs() <= TOL, "equation {i} at {p:?}: {}", e(p));
            }
        }
    }
}

/// Whether `p` is within `d` of a chord of some crossing branch.
fn covered(branches: &[IntersectionBranch], p: &[f64; 3], d: f64) -> bool {
    branches.iter().any(|b| {
        b.points
            .windows(2)
            .any(|w| super::segment_distance3(p, &w[0], &w[1]) <= d)
    })
}

fn crossings(branches: &[IntersectionBranch]) -> Vec<&IntersectionBranch> {
    branches
        .iter()
        .filter(|b| b.kind == Contact::Crossing)
        .collect()
}

/// The fitted curves: the space curve and the surfaces at the parameter curves within the
/// tolerance of every point (at their chord-length parameters, checked through the projection
/// of the space curve's points).
fn check_fit(b: &IntersectionBranch, a: &QuerySurface, other: Option<&QuerySurface>) {
    let c = b.curve.as_ref().unwrap();
    let ca = b.curve_uv_a.as_ref().unwrap();
    let (lo, hi) = c.domain();
    for i in 0..=40 {
        let t = lo + (hi - lo) * f64::from(i) / 40.0;
        let p = c.eval(t).unwrap();
        let uv = ca.eval(t).unwrap();
        let q = super::surface_jet(a, uv[0], uv[1]).unwrap()[0];
        let d = (0..3).map(|k| (p[k] - q[k]).powi(2)).sum::<f64>().sqrt();
        assert!(d <= 4.0 * TOL, "space curve vs S₁(uv curve) at {t}: {d}");
        if let (Some(o), Some(cb)) = (other, b.curve_uv_b.as_ref()) {
            let uv = cb.eval(t).unwrap();
            let q = super::surface_jet(o, uv[0], uv[1]).unwrap()[0];
            let d = (0..3).map(|k| (p[k] - q[k]).powi(2)).sum::<f64>().sqrt();
            assert!(d <= 4.0 * TOL, "space curve vs S₂(uv curve) at {t}: {d}");
        }
    }
}

fn sphere(r: f64) -> QuerySurface {
    let f = frame([0.0; 3], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]);
    QuerySurface::from_nurbs(
        &NurbsSurface::sphere(&f, r, (0.0, TAU), (-FRAC_PI_2, FRAC_PI_2)).unwrap(),
    )
    .unwrap()
}

#[test]
fn plane_sphere_circle() {
    let s = sphere(2.0);
    for (o, n) in [
        ([0.0, 0.0, 1.0], [0.0, 0.0, 1.0]),
        ([0.3, 0.2, 0.1], [1.0, 2.0, 3.0]),
    ] {
        let b = s.intersect_plane(&o, &n, TOL).unwrap();
        let nn = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
        let on_plane = |p: &[f64; 3]| (0..3).map(|k| (p[k] - o[k]) * n[k]).sum::<f64>() / nn;
        let on_sphere = |p: &[f64; 3]| (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt() - 2.0;
        check_points(&b, &[&on_plane, &on_sphere]);
        let c = crossings(&b);
        assert!(!c.is_empty(), "{b:?}");
        // the circle: centre the foot of the origin on the plane, radius √(4 − d²)
        let d = (0..3).map(|k| o[k] * n[k]).sum::<f64>() / nn;
        let r = (4.0 - d * d).sqrt();
        let total: f64 = c.iter().map(|x| x.length()).sum();
        assert!(
            (total - TAU * r).abs() <= 1e-3 * r,
            "{total} vs {}",
            TAU * r
        );
        for x in &c {
            check_fit(x, &s, None);
        }
        // the same circle from the plane as a surface
        let m = [n[0] / nn, n[1] / nn, n[2] / nn];
        let across = if m[0].abs() < 0.9 {
            [1.0, 0.0, 0.0]
        } else {
            [0.0, 1.0, 0.0]
        };
        let p = plane(o, m, across, 4.0);
        let b2 = s.intersect_surface(&p, TOL).unwrap();
        check_points(&b2, &[&on_plane, &on_sphere]);
        let total2: f64 = crossings(&b2).iter().map(|x| x.length()).sum();
        assert!((total2 - TAU * r).abs() <= 1e-3 * r, "{total2}");
        for x in crossings(&b2) {
            check_fit(x, &s, Some(&p));
        }
    }
}

#[test]
fn plane_cylinder_ellipse_and_lines() {
    let f = frame([0.0; 3], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]);
    let cyl = QuerySurface::from_nurbs(
        &NurbsSurface::cylinder(&f, 1.0, (0.0, TAU), (-3.0, 3.0)).unwrap(),
    )
    .unwrap();
    let on_cyl = |p: &[f64; 3]| p[0].hypot(p[1]) - 1.0;
    // z = 0.5 x: an ellipse with semi-axes √1.25 and 1
    let b = cyl
        .intersect_plane(&[0.0; 3], &[0.5, 0.0, -1.0], TOL)
        .unwrap();
    let on_plane = |p: &[f64; 3]| (0.5 * p[0] - p[2]) / 1.25_f64.sqrt();
    check_points(&b, &[&on_cyl, &on_plane]);
    assert_eq!(b.len(), 1, "{b:?}");
    assert!(b[0].closed);
    // the ellipse's points are all reached
    for i in 0..32 {
        let a = TAU * f64::from(i) / 32.0;
        let p = [a.cos(), a.sin(), 0.5 * a.cos()];
        assert!(covered(&b, &p, 2.0 * TOL), "{p:?}");
    }
    // x = 0.5: two lines parallel to the axis, open, from bottom to top
    let b = cyl
        .intersect_plane(&[0.5, 0.0, 0.0], &[1.0, 0.0, 0.0], TOL)
        .unwrap();
    check_points(&b, &[&on_cyl, &|p: &[f64; 3]| p[0] - 0.5]);
    assert_eq!(b.len(), 2, "{b:?}");
    for x in &b {
        assert!(!x.closed);
        assert!((x.length() - 6.0).abs() <= 1e-9, "{}", x.length());
    }
}

#[test]
fn plane_cone_circle_and_generators() {
    let f = frame([0.0; 3], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]);
    let cone = QuerySurface::from_nurbs(
        &NurbsSurface::cone(&f, 1.0, FRAC_PI_4, (0.0, TAU), (0.0, 2.0)).unwrap(),
    )
    .unwrap();
    // radius 1 + z
    let on_cone = |p: &[f64; 3]| p[0].hypot(p[1]) - (1.0 + p[2]);
    let b = cone
        .intersect_plane(&[0.0, 0.0, 1.0], &[0.0, 0.0, 1.0], TOL)
        .unwrap();
    check_points(&b, &[&on_cone, &|p: &[f64; 3]| p[2] - 1.0]);
    let total: f64 = b.iter().map(IntersectionBranch::length).sum();
    assert!((total - TAU * 2.0).abs() <= 2e-3, "{total}");
    // the plane y = 0 holds two generators, each of length 2√2
    let b = cone
        .intersect_plane(&[0.0; 3], &[0.0, 1.0, 0.0], TOL)
        .unwrap();
    check_points(&b, &[&on_cone, &|p: &[f64; 3]| p[1]]);
    let total: f64 = b.iter().map(IntersectionBranch::length).sum();
    assert!(
        (total - 4.0 * 2.0_f64.sqrt()).abs() <= 1e-9,
        "{total} {b:?}"
    );
}

fn cylinder(axis: [f64; 3], x: [f64; 3], r: f64, h: f64) -> QuerySurface {
    QuerySurface::from_nurbs(
        &NurbsSurface::cylinder(&frame([0.0; 3], axis, x), r, (0.0, TAU), (-h, h)).unwrap(),
    )
    .unwrap()
}

#[test]
fn steinmetz_two_loops() {
    // x² + y² = 1 and x² + z² = 1.5²: two closed loops, z = ±√(2.25 − x²)
    let a = cylinder([0.0, 0.0, 1.0], [1.0, 0.0, 0.0], 1.0, 3.0);
    let b = cylinder([0.0, 1.0, 0.0], [0.0, 0.0, 1.0], 1.5, 3.0);
    let br = a.intersect_surface(&b, TOL).unwrap();
    let on_a = |p: &[f64; 3]| p[0].hypot(p[1]) - 1.0;
    let on_b = |p: &[f64; 3]| p[0].hypot(p[2]) - 1.5;
    check_points(&br, &[&on_a, &on_b]);
    assert!(br.iter().all(|x| x.kind == Contact::Crossing), "{br:?}");
    for i in 0..64 {
        let t = TAU * f64::from(i) / 64.0;
        let (x, y) = (t.cos(), t.sin());
        let z = (2.25 - x * x).sqrt();
        for p in [[x, y, z], [x, y, -z]] {
            assert!(covered(&br, &p, 2.0 * TOL), "{p:?} missed");
        }
    }
    for x in &br {
        check_fit(x, &a, Some(&b));
    }
}

#[test]
fn steinmetz_equal_radii_meet_at_tangent_points() {
    // x² + y² = 1 and x² + z² = 1: the ellipses y = ±z, crossing at (±1, 0, 0), where the
    // normals are parallel; seams turned away from there
    let a = cylinder([0.0, 0.0, 1.0], [0.0, 1.0, 0.0], 1.0, 2.0);
    let b = cylinder([0.0, 1.0, 0.0], [0.0, 0.0, 1.0], 1.0, 2.0);
    let br = a.intersect_surface(&b, TOL).unwrap();
    let on_a = |p: &[f64; 3]| p[0].hypot(p[1]) - 1.0;
    let on_b = |p: &[f64; 3]| p[0].hypot(p[2]) - 1.0;
    check_points(&br, &[&on_a, &on_b]);
    let tangents: Vec<&IntersectionBranch> = br
        .iter()
        .filter(|x| matches!(x.kind, Contact::Tangent { .. }))
        .collect();
    assert_eq!(tangents.len(), 2, "{br:?}");
    for x in [-1.0, 1.0] {
        assert!(
            tangents
                .iter()
                .any(|t| super::super::super::pieces::dist(&t.points[0], &[x, 0.0, 0.0]) <= 1e-3),
            "{tangents:?}"
        );
    }
    // the ellipses are reached away from the contacts
    for i in 0..32 {
        let t = TAU * (f64::from(i) + 0.5) / 32.0;
        if t.sin().abs() < 0.05 {
            continue;
        }
        let (x, y) = (t.cos(), t.sin());
        for p in [[x, y, y], [x, y, -y]] {
            assert!(covered(&br, &p, 2.0 * TOL), "{p:?} missed");
        }
    }
}

/// A bicubic bump over `[−1, 1]²`: flat rim at height `base`, middle control points at `top`.
fn bump(base: f64, top: f64) -> QuerySurface {
    let mut pts = Vec::new();
    for i in 0..5 {
        for j in 0..5 {
            let x = -1.0 + 0.5 * f64::from(i);
            let y = -1.0 + 0.5 * f64::from(j);
            let z = if (1..4).contains(&i) && (1..4).contains(&j) {
                if i == 2 && j == 2 {
                    top
                } else {
                    base + 0.5 * (top - base)
                }
            } else {
                base
            };
            pts.push([x, y, z]);
        }
    }
    let k = vec![0.0, 0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0, 1.0];
    let s =
        BSplineSurface::new(3, 3, k.clone(), k, Points::from_3d(&pts).unwrap(), (5, 5)).unwrap();
    QuerySurface::from_bspline(&s).unwrap()
}

#[test]
fn small_closed_loop_is_found() {
    // a bump up to 0.625 and an upside-down bump down to 0.6 overlap in a small region: the
    // intersection is one small closed loop in the middle
    let a = bump(0.0, 1.0);
    let b = bump(1.0, 0.36);
    let br = a.intersect_surface(&b, 1e-7).unwrap();
    assert_eq!(br.len(), 1, "{br:?}");
    assert_eq!(br[0].kind, Contact::Crossing);
    assert!(br[0].closed, "{br:?}");
    let ext = br[0]
        .points
        .iter()
        .map(|p| p[0].hypot(p[1]))
        .fold(0.0_f64, f64::max);
    assert!(ext < 0.5, "a small loop: {ext}");
    for (p, x) in br[0].points.iter().zip(&br[0].uv_a) {
        let q = super::surface_jet(&a, x[0], x[1]).unwrap()[0];
        assert!(super::super::super::pieces::dist(p, &q) <= 1e-7);
    }
}

/// Two bicubic bumps side by side over `[−1.5, 1.5] × [−1, 1]` (peaks about 0.298 high at
/// `x ≈ ±0.47`, the saddle between them 1/6 high).
fn twin_bumps() -> QuerySurface {
    let mut pts = Vec::new();
    for i in 0..7 {
        for j in 0..5 {
            let z = if (i == 2 || i == 4) && j == 2 {
                1.0
            } else {
                0.0
            };
            pts.push([-1.5 + 0.5 * f64::from(i), -1.0 + 0.5 * f64::from(j), z]);
        }
    }
    let ku = vec![0.0, 0.0, 0.0, 0.0, 0.25, 0.5, 0.75, 1.0, 1.0, 1.0, 1.0];
    let kv = vec![0.0, 0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0, 1.0];
    let s = BSplineSurface::new(3, 3, ku, kv, Points::from_3d(&pts).unwrap(), (7, 5)).unwrap();
    QuerySurface::from_bspline(&s).unwrap()
}

#[test]
fn a_small_loop_beside_a_traced_one_is_found() {
    // the plane z = 0.2, a little above the saddle, cuts each bump in a small closed loop; the
    // loops come within a few tenths of each other over the saddle, so the second is searched
    // for next to the first, already traced
    let a = twin_bumps();
    let b = plane([0.0, 0.0, 0.2], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0], 2.0);
    for br in [
        a.intersect_surface(&b, TOL).unwrap(),
        a.intersect_plane(&[0.0, 0.0, 0.2], &[0.0, 0.0, 1.0], TOL)
            .unwrap(),
    ] {
        assert_eq!(br.len(), 2, "{br:?}");
        let mut sides = Vec::new();
        for b in &br {
            assert_eq!(b.kind, Contact::Crossing);
            assert!(b.closed, "{b:?}");
            let x = b.points.iter().map(|p| p[0]);
            let (lo, hi) = x.fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), v| {
                (l.min(v), h.max(v))
            });
            assert!(lo * hi > 0.0 && hi - lo < 1.0, "one loop a side: {lo} {hi}");
            sides.push(lo.signum());
            for (p, x) in b.points.iter().zip(&b.uv_a) {
                assert!((p[2] - 0.2).abs() <= TOL / 10.0, "{p:?}");
                let q = super::surface_jet(&a, x[0], x[1]).unwrap()[0];
                assert!(super::super::super::pieces::dist(p, &q) <= TOL / 10.0);
            }
            check_fit(b, &a, None);
        }
        sides.sort_by(f64::total_cmp);
        assert_eq!(sides, vec![-1.0, 1.0]);
    }
}

#[test]
fn tangent_plane_touches() {
    let s = sphere(1.0);
    // the plane x = 1 touches the sphere at (1, 0, 0)
    let b = s
        .intersect_plane(&[1.0, 0.0, 0.0], &[1.0, 0.0, 0.0], TOL)
        .unwrap();
    assert_eq!(b.len(), 1, "{b:?}");
    assert_eq!(b[0].kind, Contact::Tangent { order: 1 }, "{b:?}");
    let p = b[0].points[0];
    assert!(
        (p[0] - 1.0).abs() <= 1e-9 && p[1].hypot(p[2]) <= 1e-3,
        "{p:?}"
    );
    // the same plane as a surface
    let pl = plane([1.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], 2.0);
    let b = s.intersect_surface(&pl, TOL).unwrap();
    assert_eq!(b.len(), 1, "{b:?}");
    assert!(matches!(b[0].kind, Contact::Tangent { .. }), "{b:?}");
    assert!(b[0].points[0][1].hypot(b[0].points[0][2]) <= 1e-3, "{b:?}");
}

#[test]
fn misses_and_overlaps() {
    let s = sphere(1.0);
    assert!(s
        .intersect_plane(&[0.0, 0.0, 1.5], &[0.0, 0.0, 1.0], TOL)
        .unwrap()
        .is_empty());
    let far = plane([0.0, 0.0, 3.0], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0], 1.0);
    assert!(s.intersect_surface(&far, TOL).unwrap().is_empty());
    // a plane patch and a plane section in its own plane: an overlap
    let p = plane([0.0; 3], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0], 1.0);
    let b = p.intersect_plane(&[0.0; 3], &[0.0, 0.0, 1.0], TOL).unwrap();
    assert_eq!(b.len(), 1, "{b:?}");
    assert_eq!(b[0].kind, Contact::Overlap);
    // two overlapping patches of one plane
    let q = plane([0.5, 0.0, 0.0], [0.0, 0.0, 1.0], [1.0, 1.0, 0.0], 1.0);
    let b = p.intersect_surface(&q, TOL).unwrap();
    assert!(b.iter().any(|x| x.kind == Contact::Overlap), "{b:?}");
}

#[test]
fn bad_input_is_refused() {
    use crate::Error;
    let s = sphere(1.0);
    assert!(matches!(
        s.intersect_plane(&[0.0; 3], &[0.0; 3], TOL),
        Err(Error::InvalidArgument { .. })
    ));
    assert!(matches!(
        s.intersect_plane(&[0.0; 2], &[0.0, 0.0, 1.0], TOL),
        Err(Error::Dimension { .. })
    ));
    assert!(s.intersect_surface(&s, -1.0).is_err());
    assert!(s.intersect_surface(&s, f64::NAN).is_err());
    // a tolerance comparable to the surfaces' size cannot tell branches apart: refused, naming
    // the largest it takes (a crossing of a plane and the sphere)
    let p = plane([0.0, 0.0, 0.2], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0], 2.0);
    for tol in [1.0, 10.0] {
        let e = s.intersect_surface(&p, tol).unwrap_err();
        assert_eq!(e.arg(), Some(crate::Arg::Tolerance), "{e}");
        assert!(e.to_string().contains("give at most"), "{e}");
        assert!(s
            .intersect_plane(&[0.0, 0.0, 0.2], &[0.0, 0.0, 1.0], tol)
            .is_err());
    }
    assert_eq!(s.intersect_surface(&p, 1e-3).unwrap().len(), 1);
    let flat = BSplineSurface::new(
        1,
        1,
        vec![0.0, 0.0, 1.0, 1.0],
        vec![0.0, 0.0, 1.0, 1.0],
        Points::from_flat(2, vec![0.0, 0.0, 0.0, 1.0, 1.0, 0.0, 1.0, 1.0]).unwrap(),
        (2, 2),
    )
    .unwrap();
    let flat = QuerySurface::from_bspline(&flat).unwrap();
    assert!(matches!(
        s.intersect_surface(&flat, TOL),
        Err(Error::Dimension { .. })
    ));
}

/// The nearest distance from `p` to a fitted curve: the closest of 4,096 samples a span, then
/// golden-section refinement around it (the curve's points are a few thousandths apart per
/// sample, so the bracket holds the nearest point).
fn distance_to_curve(c: &crate::BSplineCurve, p: &[f64; 3], samples: &[(f64, [f64; 3])]) -> f64 {
    let d = |x: &[f64]| (0..3).map(|k| (x[k] - p[k]).powi(2)).sum::<f64>().sqrt();
    let (i, _) = samples
        .iter()
        .enumerate()
        .map(|(i, (_, q))| (i, d(q)))
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .unwrap();
    let (mut lo, mut hi) = (
        samples[i.saturating_sub(1)].0,
        samples[(i + 1).min(samples.len() - 1)].0,
    );
    let f = |t: f64| d(&c.eval(t).unwrap());
    let g = 0.5 * (5.0_f64.sqrt() - 1.0);
    for _ in 0..60 {
        let (a, b) = (hi - g * (hi - lo), lo + g * (hi - lo));
        if f(a) <= f(b) {
            hi = b;
        } else {
            lo = a;
        }
    }
    f(0.5 * (lo + hi))
}

#[test]
fn torus_section_points_and_fitted_curves_within_the_tolerance() {
    // the oblique section of the benchmark: the torus R = 3, r = 1 and the plane through
    // (0, 0, 0.2) with normal (0.3, 0.1, 1): one closed loop, cut at the torus's seams
    let f = frame([0.0; 3], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]);
    let torus = QuerySurface::from_nurbs(
        &NurbsSurface::torus(&f, 3.0, 1.0, (0.0, TAU), (0.0, TAU)).unwrap(),
    )
    .unwrap();
    let (o, n) = ([0.0, 0.0, 0.2], [0.3, 0.1, 1.0]);
    let nn = (0.3_f64 * 0.3 + 0.1 * 0.1 + 1.0).sqrt();
    let b = torus.intersect_plane(&o, &n, TOL).unwrap();
    let on_plane = |p: &[f64; 3]| (0..3).map(|k| (p[k] - o[k]) * n[k]).sum::<f64>() / nn;
    let on_torus = |p: &[f64; 3]| (p[0].hypot(p[1]) - 3.0).hypot(p[2]) - 1.0;
    for x in &b {
        assert_eq!(x.kind, Contact::Crossing);
        for p in &x.points {
            assert!(on_plane(p).abs() <= TOL / 10.0 && on_torus(p).abs() <= TOL / 10.0);
        }
        // every point within the tolerance of the fitted curve in space, and the curve on
        // the torus through its parameter curve
        let c = x.curve.as_ref().unwrap();
        let (lo, hi) = c.domain();
        let m = 4096 * c.control_points().len();
        let samples: Vec<(f64, [f64; 3])> = (0..=m)
            .map(|i| {
                let t = lo + (hi - lo) * i as f64 / m as f64;
                let q = c.eval(t).unwrap();
                (t, [q[0], q[1], q[2]])
            })
            .collect();
        for p in x.points.iter().step_by(7) {
            let d = distance_to_curve(c, p, &samples);
            assert!(d <= TOL, "point {p:?} is {d} from the fitted curve");
        }
        check_fit(x, &torus, None);
    }
    // the pieces chain into one closed loop of the length Open CASCADE's fitted lines have
    let total: f64 = b.iter().map(IntersectionBranch::length).sum();
    assert!((total - 32.576_785_5).abs() <= 1e-5, "{total}");
    let ends: Vec<[f64; 3]> = b
        .iter()
        .flat_map(|x| [x.points[0], x.points[x.points.len() - 1]])
        .collect();
    for e in &ends {
        let partners = ends
            .iter()
            .filter(|f| super::super::super::pieces::dist(e, &f[..]) <= 1e-5)
            .count();
        assert!(partners >= 2, "an end without a partner: {e:?}");
    }
}

#[test]
fn the_segment_grid_agrees_with_every_segment() {
    // a helix of 2,000 segments (runs of up to 64 segments a cube) and points scattered around
    // it: covered exactly when within `cover` of some segment
    let ps: Vec<[f64; 3]> = (0..2001)
        .map(|i| {
            let t = f64::from(i) * 0.004;
            [t.cos(), t.sin(), 0.05 * t]
        })
        .collect();
    let traced = vec![super::march::Traced {
        xs: vec![[0.0; 4]; ps.len()],
        ps: ps.clone(),
        tangents: vec![None; ps.len()],
        stops: [super::march::Stop::Boundary; 2],
        reach: [1.0, 0.0],
    }];
    let cover = 1e-3;
    let mut grid = super::SegmentGrid::new(cover, 0.1);
    grid.insert(0, &ps);
    let mut near = 0;
    for k in 0..4000 {
        let (a, b, c) = (
            (0.618_033_988_749_895 * f64::from(k)).fract(),
            (0.754_877_666_246_693 * f64::from(k)).fract(),
            (0.569_840_290_998_053 * f64::from(k)).fract(),
        );
        let t = 8.0 * a;
        // within a few covers of the helix, on both sides of the threshold
        let r = 1.0 + 4.0 * cover * (b - 0.5);
        let p = [r * t.cos(), r * t.sin(), 0.05 * t + 4.0 * cover * (c - 0.5)];
        let brute = ps
            .windows(2)
            .any(|w| super::segment_distance3(&p, &w[0], &w[1]) <= cover);
        assert_eq!(grid.covers(&p, &traced), brute, "{p:?}");
        near += usize::from(brute);
    }
    assert!(near > 500 && near < 3500, "both sides tested: {near}");
}

#[test]
fn turn_angles_match_the_dot_product() {
    use super::march::{turn_angle, turn_bound};
    for k in 0..200 {
        let theta = 3.1 * f64::from(k) / 200.0 + 1e-7 * f64::from(k % 3);
        let a = [1.0, 0.0, 0.0];
        let b = [theta.cos(), theta.sin(), 0.0];
        let exact = theta;
        assert!(
            (turn_angle(&a, &b) - exact).abs() <= 1e-14 * (1.0 + exact),
            "{theta}"
        );
        // the series of arc over chord against the quotient, on both sides of its threshold
        let t = 0.02 * f64::from(k) / 200.0 + 1e-3;
        let quotient = (0.5 * t) / (0.5 * t).sin();
        assert!(
            (super::march::arc_over_chord(t) - quotient).abs() <= 4e-16,
            "{t}"
        );
        let bound = turn_bound(&a, &b);
        assert!(
            bound >= exact * (1.0 - 1e-15) && bound <= exact * (1.0 + 1e-2) + 1e-15,
            "{theta}"
        );
    }
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(12))]
    /// Every point of every branch is within the tolerance of both surfaces, for planes in
    /// any position through a torus.
    #[test]
    fn points_on_both_surfaces(
        oz in -0.5f64..0.5,
        nx in -1.0f64..1.0,
        ny in -1.0f64..1.0,
    ) {
        let f = frame([0.0; 3], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]);
        let torus = QuerySurface::from_nurbs(&NurbsSurface::torus(&f, 3.0, 1.0, (0.0, TAU), (0.0, TAU)).unwrap()).unwrap();
        let n = [nx, ny, 1.0];
        let o = [0.0, 0.0, oz];
        let b = torus.intersect_plane(&o, &n, TOL).unwrap();
        let nn = (nx * nx + ny * ny + 1.0f64).sqrt();
        for x in &b {
            for p in &x.points {
                let plane = (0..3).map(|k| (p[k] - o[k]) * n[k]).sum::<f64>() / nn;
                let torus = (p[0].hypot(p[1]) - 3.0).hypot(p[2]) - 1.0;
                proptest::prop_assert!(plane.abs() <= TOL && torus.abs() <= TOL, "{p:?}");
            }
        }
        proptest::prop_assert!(!b.is_empty());
    }
}
