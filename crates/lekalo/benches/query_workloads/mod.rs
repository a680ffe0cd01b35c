//! Query workloads shared by `benches/query.rs` and `examples/query_peer.rs`: objects defined
//! by formulas, which `bench/peers/occt_queries.cpp` builds the same way for Open CASCADE.
#![allow(dead_code)]

use lekalo::{BSplineCurve, BSplineSurface, KnotVector, NurbsCurve, Points};

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
