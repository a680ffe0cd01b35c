//! Geometric-query benchmarks, on data defined by formulas so that the peer program
//! (`bench/peers/occt_queries.cpp`) builds exactly the same objects:
//!
//! - `project_1e5`: 10^5 points projected onto a 3-D cubic with 1,000 control points;
//! - `length_1e-12`: its arc-length table to 1e-12 relative; `param_at_1e5`: 10^5
//!   parameter-at-length queries on that table;
//! - `intersect_100x100`: two planar cubics with 100 pieces each;
//! - `mesh_50x50`: a bicubic surface with 50×50 patches meshed to 1e-4 of its size.
//!
//! Run: `cargo bench -p lekalo --bench query`. Smoke: `cargo test -p lekalo --benches`.

use std::hint::black_box;
use std::time::Duration;

use criterion::{criterion_main, Criterion, Throughput};
use lekalo::{BSplineCurve, BSplineSurface, KnotVector, Points, QueryCurve, QuerySurface};

/// Control points of the 3-D projection curve (index `i` of `n`).
fn space_point(i: usize) -> [f64; 3] {
    let x = i as f64;
    [
        0.01 * x + 0.3 * (0.37 * x).sin(),
        0.5 * (0.23 * x).cos() + 0.2 * (1.7 * x).sin(),
        0.3 * (0.05 * x).sin() + 0.1 * (0.9 * x).cos(),
    ]
}

/// Control points of the planar intersection curves (`phase` 0 and 1).
fn plane_point(i: usize, phase: usize) -> [f64; 2] {
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
fn height(i: usize, j: usize) -> f64 {
    let (x, y) = (i as f64, j as f64);
    0.3 * (0.4 * x).sin() * (0.3 * y).cos() + 0.1 * (0.9 * x + 0.5 * y).sin()
}

/// Query point `k` of the projection batch.
fn query_point(k: usize) -> [f64; 3] {
    let x = k as f64;
    [
        11.0 * ((0.618_033_988_749_895 * x).fract()),
        1.6 * ((0.754_877_666_246_693 * x).fract()) - 0.8,
        1.0 * ((0.569_840_290_998_053 * x).fract()) - 0.5,
    ]
}

fn space_curve() -> BSplineCurve {
    let n = 1000;
    let pts: Vec<[f64; 3]> = (0..n).map(space_point).collect();
    BSplineCurve::from_knot_vector(
        3,
        KnotVector::clamped_uniform(3, n).expect("knots"),
        Points::from_3d(&pts).expect("points"),
    )
    .expect("curve")
}

fn plane_curve(phase: usize) -> BSplineCurve {
    let n = 103; // 100 pieces
    let pts: Vec<[f64; 2]> = (0..n).map(|i| plane_point(i, phase)).collect();
    BSplineCurve::from_knot_vector(
        3,
        KnotVector::clamped_uniform(3, n).expect("knots"),
        Points::from_2d(&pts).expect("points"),
    )
    .expect("curve")
}

fn surface() -> BSplineSurface {
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

fn queries(c: &mut Criterion) {
    let curve = QueryCurve::from_bspline(&space_curve()).expect("query curve");
    let pts: Vec<f64> = (0..100_000).flat_map(query_point).collect();
    let pts = Points::from_flat(3, pts).expect("queries");
    let mut g = c.benchmark_group("query");
    g.measurement_time(Duration::from_secs(3)).sample_size(10);
    g.throughput(Throughput::Elements(100_000));
    g.bench_function("project_1e5", |b| {
        b.iter(|| {
            curve
                .project_batch(black_box(pts.as_view()))
                .expect("projections")
        });
    });
    g.throughput(Throughput::Elements(1));
    g.bench_function("length_1e-12", |b| {
        b.iter(|| black_box(&curve).arc_length(1e-12).expect("length").total());
    });
    let table = curve.arc_length(1e-12).expect("table");
    let total = table.total();
    let lengths: Vec<f64> = (0..100_000)
        .map(|k| total * (0.618_033_988_749_895 * k as f64).fract())
        .collect();
    g.throughput(Throughput::Elements(100_000));
    g.bench_function("param_at_1e5", |b| {
        b.iter(|| table.param_at_batch(black_box(&lengths)).expect("params"));
    });
    let (a, bb) = (
        QueryCurve::from_bspline(&plane_curve(0)).expect("a"),
        QueryCurve::from_bspline(&plane_curve(1)).expect("b"),
    );
    g.throughput(Throughput::Elements(1));
    g.bench_function("intersect_100x100", |b| {
        b.iter(|| black_box(&a).intersect(&bb, 1e-9).expect("intersections"));
    });
    let s = QuerySurface::from_bspline(&surface()).expect("surface");
    g.bench_function("mesh_50x50", |b| {
        // 1e-4 of the size: the net spans the unit square
        b.iter(|| black_box(&s).mesh(1e-4).expect("mesh"));
    });
    g.finish();
    let mesh = s.mesh(1e-4).expect("mesh");
    eprintln!(
        "query bench facts: {} intersections; mesh {} triangles, bound {:.3e}; length {total}",
        a.intersect(&bb, 1e-9).expect("x").len(),
        mesh.triangles.len(),
        mesh.deviation
    );
}

/// All query benchmarks (what `criterion_group!` would generate, with a doc comment).
fn benches() {
    let mut c = Criterion::default().configure_from_args();
    queries(&mut c);
}

criterion_main!(benches);
