//! Query workloads shared by `benches/query.rs` and `examples/query_peer.rs`: objects defined
//! by formulas, which `bench/peers/occt_queries.cpp` builds the same way for Open CASCADE.
#![allow(dead_code)]

use lekalo::{BSplineCurve, BSplineSurface, KnotVector, NurbsCurve, NurbsSurface, Points};

/// Control points of the 3-D projection curve (index `i` of `n`).
pub(crate) fn space_point(i: usize) -> [f64; 3] {
    let x = i as f64;
    [
        0.01 * x + 0.3 * (0.37 * x).sin(),
        0.5 * (0.23 * x).cos() + 0.2 * (1.7 * x).sin(),
        0.3 * (0.05 * x).sin() + 0.1 * (0.9 * x).cos(),
    ]
}

/// Control points of the planar intersection curves (`phase` 0 and 1).
pub(crate) fn plane_point(i: usize, phase: usize) -> [f64; 2] {
    let x = i as f64;
    if phase == 0 {
        [0.1 * x, (0.31 * x).sin()]
    } else {
        [
            0.1 * x + 0.05 * (0.7 * x).cos(),
            0.8 * (0.27 * x + 1.0).cos(),
        ]
    }
}

/// Height of the surface net at `(i, j)`.
pub(crate) fn height(i: usize, j: usize) -> f64 {
    let (x, y) = (i as f64, j as f64);
    0.3 * (0.4 * x).sin() * (0.3 * y).cos() + 0.1 * (0.9 * x + 0.5 * y).sin()
}

/// Query point `k` of the projection batch.
pub(crate) fn query_point(k: usize) -> [f64; 3] {
    let x = k as f64;
    [
        11.0 * ((0.618_033_988_749_895 * x).fract()),
        1.6 * ((0.754_877_666_246_693 * x).fract()) - 0.8,
        1.0 * ((0.569_840_290_998_053 * x).fract()) - 0.5,
    ]
}

pub(crate) fn space_curve() -> BSplineCurve {
    let n = 1000;
    let pts: Vec<[f64; 3]> = (0..n).map(space_point).collect();
    BSplineCurve::from_knot_vector(
        3,
        KnotVector::clamped_uniform(3, n).expect("knots"),
        Points::from_3d(&pts).expect("points"),
    )
    .expect("curve")
}

pub(crate) fn plane_curve(phase: usize) -> BSplineCurve {
    let n = 103; // 100 pieces
    let pts: Vec<[f64; 2]> = (0..n).map(|i| plane_point(i, phase)).collect();
    BSplineCurve::from_knot_vector(
        3,
        KnotVector::clamped_uniform(3, n).expect("knots"),
        Points::from_2d(&pts).expect("points"),
    )
    .expect("curve")
}

/// Distance of the offset workloads: of the planar cubic `plane_curve(0)` (whose smallest
/// radius of curvature is about 0.09) and of the arc.
pub(crate) const OFFSET_DISTANCE: f64 = 0.05;
/// Tolerance of the offset workloads.
pub(crate) const OFFSET_TOLERANCE: f64 = 1e-6;

/// The half circle of radius 1 about the origin from (1, 0) to (−1, 0), as two rational
/// quadratic quarter circles: control points (1, 0), (1, 1), (0, 1), (−1, 1), (−1, 0), weights
/// 1, 1/√2, 1, 1/√2, 1, knots 0, 0, 0, ½, ½, 1, 1, 1.
pub(crate) fn arc() -> NurbsCurve {
    let w = std::f64::consts::FRAC_1_SQRT_2;
    NurbsCurve::new(
        2,
        vec![0.0, 0.0, 0.0, 0.5, 0.5, 1.0, 1.0, 1.0],
        Points::from_2d(&[[1.0, 0.0], [1.0, 1.0], [0.0, 1.0], [-1.0, 1.0], [-1.0, 0.0]])
            .expect("points"),
        vec![1.0, w, 1.0, w, 1.0],
    )
    .expect("arc")
}

pub(crate) fn surface() -> BSplineSurface {
    let n = 53; // 50 patches per direction
    let mut net = Vec::with_capacity(n * n * 3);
    for i in 0..n {
        for j in 0..n {
            net.extend([
                i as f64 / (n - 1) as f64,
                j as f64 / (n - 1) as f64,
                height(i, j),
            ]);
        }
    }
    let k = KnotVector::clamped_uniform(3, n).expect("knots");
    BSplineSurface::from_knot_vectors(
        3,
        3,
        k.clone(),
        k,
        Points::from_flat(3, net).expect("net"),
        (n, n),
    )
    .expect("surface")
}

/// Tolerance of the surface–surface workloads (lekalo's `tolerance`, Open CASCADE's
/// `GeomAPI_IntSS` tolerance).
pub(crate) const SSI_TOLERANCE: f64 = 1e-6;

/// A surface of a surface–surface workload with the exact distance to it, for checking answers
/// without either side's projection.
pub(crate) enum Exact {
    /// Sphere of radius `r` about the origin.
    Sphere(f64),
    /// Cylinder of radius `r` about the `z` axis.
    CylinderZ(f64),
    /// Cylinder of radius `r` about the `x` axis.
    CylinderX(f64),
    /// Torus about the `z` axis, major radius `R`, minor `r`.
    Torus(f64, f64),
    /// Plane through a point with a unit normal.
    Plane([f64; 3], [f64; 3]),
}

impl Exact {
    /// Distance of `p` to the (unbounded) surface.
    pub(crate) fn distance(&self, p: &[f64; 3]) -> f64 {
        let [x, y, z] = *p;
        match *self {
            Exact::Sphere(r) => (x.hypot(y).hypot(z) - r).abs(),
            Exact::CylinderZ(r) => (x.hypot(y) - r).abs(),
            Exact::CylinderX(r) => (y.hypot(z) - r).abs(),
            Exact::Torus(big, r) => ((x.hypot(y) - big).hypot(z) - r).abs(),
            Exact::Plane(o, n) => (0..3).map(|c| n[c] * (p[c] - o[c])).sum::<f64>().abs(),
        }
    }
}

/// One surface–surface workload: the first surface, the second (a surface or a plane), the
/// exact forms of both, the exact branch count and branch length where known.
pub(crate) struct SsiCase {
    pub(crate) name: &'static str,
    pub(crate) a: NurbsSurface,
    pub(crate) a_exact: Exact,
    /// `Ok(surface)` or `Err((origin, unit normal))` for a plane section.
    pub(crate) b: Result<NurbsSurface, ([f64; 3], [f64; 3])>,
    pub(crate) b_exact: Exact,
    /// Number of branches and the length of each, when known exactly.
    pub(crate) exact: Option<(usize, f64)>,
}

/// The surface–surface workloads (exact NURBS of `NurbsSurface::sphere`, `cylinder`, `torus`):
///
/// - `ssi_sphere_cylinder`: the unit sphere and the cylinder of radius 0.6 about its axis,
///   heights ±1.2: two circles of radius 0.6 at `z = ±0.8`;
/// - `section_torus`: the torus `R = 3, r = 1` cut by the plane through `(0, 0, 0.2)` with
///   normal `(0.3, 0.1, 1)`: two loops;
/// - `ssi_cylinders`: the cylinder of radius 1 about `z` (heights ±1.5) and the cylinder of
///   radius 0.5 about `x` (heights ±2), crossing at right angles: two closed loops
///   `x = ±√(1 − y²)`, `y² + z² = 0.25`, each of length [`crossing_cylinders_loop_length`].
pub(crate) fn ssi_cases() -> Vec<SsiCase> {
    use lekalo::surface::Placement;
    use std::f64::consts::{FRAC_PI_2, TAU};
    let f = Placement::new([0.0; 3], None, None).expect("frame");
    let fx = Placement::new([0.0; 3], Some([1.0, 0.0, 0.0]), None).expect("frame");
    let n = [0.3, 0.1, 1.0];
    let nn = (0.3_f64 * 0.3 + 0.1 * 0.1 + 1.0).sqrt();
    let n = [n[0] / nn, n[1] / nn, n[2] / nn];
    vec![
        SsiCase {
            name: "ssi_sphere_cylinder",
            a: NurbsSurface::sphere(&f, 1.0, (0.0, TAU), (-FRAC_PI_2, FRAC_PI_2)).expect("sphere"),
            a_exact: Exact::Sphere(1.0),
            b: Ok(NurbsSurface::cylinder(&f, 0.6, (0.0, TAU), (-1.2, 1.2)).expect("cylinder")),
            b_exact: Exact::CylinderZ(0.6),
            exact: Some((2, TAU * 0.6)),
        },
        SsiCase {
            name: "section_torus",
            a: NurbsSurface::torus(&f, 3.0, 1.0, (0.0, TAU), (0.0, TAU)).expect("torus"),
            a_exact: Exact::Torus(3.0, 1.0),
            b: Err(([0.0, 0.0, 0.2], n)),
            b_exact: Exact::Plane([0.0, 0.0, 0.2], n),
            exact: None,
        },
        SsiCase {
            name: "ssi_cylinders",
            a: NurbsSurface::cylinder(&f, 1.0, (0.0, TAU), (-1.5, 1.5)).expect("cylinder"),
            a_exact: Exact::CylinderZ(1.0),
            b: Ok(NurbsSurface::cylinder(&fx, 0.5, (0.0, TAU), (-2.0, 2.0)).expect("cylinder")),
            b_exact: Exact::CylinderX(0.5),
            exact: Some((2, crossing_cylinders_loop_length())),
        },
    ]
}

/// Length of one loop of `x² + y² = 1`, `y² + z² = 1/4`: the curve
/// `(√(1 − cos²θ/4), cos θ / 2, sin θ / 2)`, `θ ∈ [0, 2π)`, whose speed is
/// `√(1/4 + cos²θ sin²θ / (16 (1 − cos²θ/4)))`; the trapezoid rule on 4,096 points (exact to
/// rounding for a smooth periodic integrand, Trefethen and Weideman, *SIAM Review* 56, 2014).
pub(crate) fn crossing_cylinders_loop_length() -> f64 {
    let m = 4096;
    let h = std::f64::consts::TAU / m as f64;
    (0..m)
        .map(|k| {
            let (s, c) = (k as f64 * h).sin_cos();
            (0.25 + c * c * s * s / (16.0 * (1.0 - 0.25 * c * c))).sqrt()
        })
        .sum::<f64>()
        * h
}
