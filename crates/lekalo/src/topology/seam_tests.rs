//! Bands and caps without a seam edge: faces of NURBS cylinders, cones, spheres and tori bounded
//! by circles round their axis, given by their 3-D edges alone, mesh to their exact areas,
//! without a crack along the cut, with the face's normals; a loop round twice, two loops round
//! in the same sense and a cap without a pole are refused.

use std::f64::consts::{FRAC_PI_2, FRAC_PI_4, PI, TAU};

use crate::query::Mesh;
use crate::surface::Placement;
use crate::topology::{Edge, Face, Loop, LOOP_CLOSURE_RTOL};
use crate::{Curve, Error, NurbsCurve, NurbsSurface, Surface};

/// The circle of radius `r` about the z axis at height `z`, counter-clockwise seen from +z
/// (`up`) or clockwise.
fn circle(r: f64, z: f64, up: bool) -> Edge {
    let c = Curve::from(
        NurbsCurve::circle(&[0.0, 0.0, z], &[1.0, 0.0, 0.0], &[0.0, 1.0, 0.0], r).unwrap(),
    );
    Edge::new(if up { c } else { c.reverse().unwrap() }, None).unwrap()
}

fn face(s: NurbsSurface, outer: Vec<Edge>, inner: Vec<Vec<Edge>>) -> Face {
    Face::new(
        Surface::from(s),
        Loop::new(outer).unwrap(),
        inner.into_iter().map(|l| Loop::new(l).unwrap()).collect(),
        true,
        LOOP_CLOSURE_RTOL,
    )
    .unwrap()
}

fn frame() -> Placement {
    Placement::new([0.0; 3], None, None).unwrap()
}

fn cross(a: &[f64], b: &[f64], c: &[f64]) -> [f64; 3] {
    let e = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let f = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
    [
        e[1] * f[2] - e[2] * f[1],
        e[2] * f[0] - e[0] * f[2],
        e[0] * f[1] - e[1] * f[0],
    ]
}

fn area3(m: &Mesh) -> f64 {
    let v = |k: u32| m.vertices.point(k as usize);
    m.triangles
        .iter()
        .map(|t| {
            let n = cross(v(t[0]), v(t[1]), v(t[2]));
            0.5 * (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt()
        })
        .sum()
}

/// The edges of the mesh used by one triangle only, the vertices taken by their 3-D points
/// (bit for bit): a crack along the cut would leave such edges away from the face's loops.
fn open_edges(m: &Mesh) -> Vec<[Vec<f64>; 2]> {
    let key = |k: u32| -> Vec<u64> {
        m.vertices
            .point(k as usize)
            .iter()
            .map(|x| x.to_bits())
            .collect()
    };
    let mut count: std::collections::HashMap<(Vec<u64>, Vec<u64>), usize> =
        std::collections::HashMap::new();
    for t in &m.triangles {
        for (i, j) in [(0, 1), (1, 2), (2, 0)] {
            let (a, b) = (key(t[i]), key(t[j]));
            let k = if a < b { (a, b) } else { (b, a) };
            *count.entry(k).or_default() += 1;
        }
    }
    let back = |k: &[u64]| k.iter().map(|b| f64::from_bits(*b)).collect::<Vec<_>>();
    count
        .into_iter()
        .filter(|(_, n)| *n == 1)
        .map(|((a, b), _)| [back(&a), back(&b)])
        .collect()
}

/// Meshes `f` (its pcurves projected) within `tol` and checks: the area is `exact` within
/// `(exact + perimeter)·tol` (inscribed triangles within `tol` of a surface whose radii of
/// curvature are at least 1 lose at most `tol` of the area per unit area, the trims at most
/// `tol` times their length), every open edge of the mesh lies on a loop (`on_loop` of both
/// ends: no crack along the cut), and `outward` of each triangle's centroid and normal is
/// positive (the face's normals).
fn check(
    f: &Face,
    tol: f64,
    exact: f64,
    perimeter: f64,
    on_loop: &dyn Fn(&[f64]) -> bool,
    outward: &dyn Fn(&[f64; 3], &[f64; 3]) -> f64,
) -> Mesh {
    let g = f.with_projected_pcurves(1e-7).unwrap();
    let m = g.mesh(tol).unwrap();
    let a = area3(&m);
    assert!(
        (a - exact).abs() <= (exact + perimeter) * tol,
        "area {a} against {exact}"
    );
    let open = open_edges(&m);
    assert!(!open.is_empty());
    for [p, q] in &open {
        assert!(
            on_loop(p) && on_loop(q),
            "an open edge {p:?}–{q:?} off the loops"
        );
    }
    for t in &m.triangles {
        let v = |k: u32| m.vertices.point(k as usize);
        let n = cross(v(t[0]), v(t[1]), v(t[2]));
        let c: [f64; 3] = std::array::from_fn(|i| (v(t[0])[i] + v(t[1])[i] + v(t[2])[i]) / 3.0);
        assert!(outward(&c, &n) > 0.0, "a triangle at {c:?} faces in");
    }
    m
}

fn radial(c: &[f64; 3], n: &[f64; 3]) -> f64 {
    c[0] * n[0] + c[1] * n[1]
}

#[test]
fn a_cylinder_band_between_two_circles_has_the_area_2_pi_r_h() {
    let s = NurbsSurface::cylinder(&frame(), 1.0, (0.0, TAU), (0.0, 3.0)).unwrap();
    // the face on the left of each circle, outward: up at z = 0.5, down at z = 2.5
    let f = face(
        s,
        vec![circle(1.0, 0.5, true)],
        vec![vec![circle(1.0, 2.5, false)]],
    );
    let on = |p: &[f64]| (p[2] - 0.5).abs() < 1e-9 || (p[2] - 2.5).abs() < 1e-9;
    for tol in [1e-2, 1e-3] {
        check(&f, tol, TAU * 2.0, 2.0 * TAU, &on, &radial);
    }
}

#[test]
fn a_cone_band_has_the_area_of_its_frustum() {
    // radius 1 + z at height z: the band from z = 0.5 to 1.5, radii 1.5 and 2.5
    let s = NurbsSurface::cone(&frame(), 1.0, FRAC_PI_4, (0.0, TAU), (0.0, 2.0)).unwrap();
    let f = face(
        s,
        vec![circle(2.5, 1.5, false)],
        vec![vec![circle(1.5, 0.5, true)]],
    );
    let exact = PI * (1.5 + 2.5) * 2.0_f64.sqrt();
    let on = |p: &[f64]| (p[2] - 0.5).abs() < 1e-9 || (p[2] - 1.5).abs() < 1e-9;
    check(&f, 1e-3, exact, TAU * 4.0, &on, &|c, n| {
        radial(c, n) - n[2] * c[0].hypot(c[1])
    });
}

#[test]
fn a_sphere_cap_round_a_pole_has_the_area_2_pi_r2_1_minus_cos_theta() {
    let s = NurbsSurface::sphere(&frame(), 1.0, (0.0, TAU), (-FRAC_PI_2, FRAC_PI_2)).unwrap();
    let lat = 0.3_f64;
    let (r, z) = (lat.cos(), lat.sin());
    let on = |p: &[f64]| (p[2] - z).abs() < 1e-9;
    let out = |c: &[f64; 3], n: &[f64; 3]| c[0] * n[0] + c[1] * n[1] + c[2] * n[2];
    // counter-clockwise from above: the cap round the north pole, colatitude θ = π/2 − lat
    let north = face(s.clone(), vec![circle(r, z, true)], vec![]);
    let m = check(&north, 1e-3, TAU * (1.0 - z), TAU * r, &on, &out);
    assert!(m.vertices.as_slice().chunks(3).any(|p| p[2] == 1.0));
    // clockwise: the rest of the sphere, round the south pole
    let south = face(s, vec![circle(r, z, false)], vec![]);
    let m = check(&south, 1e-3, TAU * (1.0 + z), TAU * r, &on, &out);
    assert!(m.vertices.as_slice().chunks(3).all(|p| p[2] < z + 1e-9));
}

#[test]
fn a_torus_band_is_the_side_its_loops_bound() {
    let (big, small) = (3.0, 1.0);
    let s = NurbsSurface::torus(&frame(), big, small, (0.0, TAU), (0.0, TAU)).unwrap();
    let v = 0.5_f64;
    let (r, z) = (big + small * v.cos(), small * v.sin());
    let on = |p: &[f64]| (p[2].abs() - z).abs() < 1e-9;
    // the normal away from the tube's centre circle
    let out = |c: &[f64; 3], n: &[f64; 3]| {
        let h = c[0].hypot(c[1]);
        let d = [c[0] - big * c[0] / h, c[1] - big * c[1] / h, c[2]];
        d[0] * n[0] + d[1] * n[1] + d[2] * n[2]
    };
    // the outer band, minor angles −v to v: ∫ 2π (R + r cos φ) r dφ
    let outer = face(
        s.clone(),
        vec![circle(r, -z, true)],
        vec![vec![circle(r, z, false)]],
    );
    let exact = TAU * small * (big * 2.0 * v + small * 2.0 * v.sin());
    check(&outer, 1e-3, exact, 2.0 * TAU * r, &on, &out);
    // the same circles the other way round: the rest of the torus, v to 2π − v
    let rest = face(
        s,
        vec![circle(r, z, true)],
        vec![vec![circle(r, -z, false)]],
    );
    let exact = TAU * small * (big * (TAU - 2.0 * v) - small * 2.0 * v.sin());
    check(&rest, 1e-3, exact, 2.0 * TAU * r, &on, &out);
}

fn refusal(e: Error) -> String {
    let Error::InvalidArgument { what, reason } = e else {
        panic!("{e:?}")
    };
    assert_eq!(what.words(), "face loop");
    reason
}

#[test]
fn a_loop_round_twice_is_refused() {
    let s = NurbsSurface::cylinder(&frame(), 1.0, (0.0, TAU), (0.0, 3.0)).unwrap();
    let f = face(
        s,
        vec![circle(1.0, 0.5, true), circle(1.0, 0.5, true)],
        vec![vec![circle(1.0, 2.5, false)]],
    );
    let r = refusal(f.with_projected_pcurves(1e-7).unwrap_err());
    assert!(
        r.contains("the outer loop goes round") && r.contains("2 times"),
        "{r}"
    );
}

#[test]
fn loops_round_in_the_same_sense_and_a_cap_without_a_pole_are_refused() {
    let s = NurbsSurface::cylinder(&frame(), 1.0, (0.0, TAU), (0.0, 3.0)).unwrap();
    let same = face(
        s.clone(),
        vec![circle(1.0, 0.5, true)],
        vec![vec![circle(1.0, 2.5, true)]],
    );
    let g = same.with_projected_pcurves(1e-7).unwrap();
    let r = refusal(g.mesh(1e-3).unwrap_err());
    assert!(r.contains("same sense"), "{r}");
    // the band's loops swapped: the face would be below the lower circle and above the upper
    let swapped = face(
        s.clone(),
        vec![circle(1.0, 0.5, false)],
        vec![vec![circle(1.0, 2.5, true)]],
    );
    let g = swapped.with_projected_pcurves(1e-7).unwrap();
    let r = refusal(g.mesh(1e-3).unwrap_err());
    assert!(r.contains("away from the face"), "{r}");
    let cap = face(s, vec![circle(1.0, 0.5, true)], vec![]);
    let g = cap.with_projected_pcurves(1e-7).unwrap();
    let r = refusal(g.mesh(1e-3).unwrap_err());
    assert!(r.contains("no pole"), "{r}");
}
