//! Geometric-query benchmarks, on data defined by formulas so that the peer program
//! (`bench/peers/occt_queries.cpp`) builds exactly the same objects:
//!
//! - `project_1e5`: 10^5 points projected onto a 3-D cubic with 1,000 control points;
//! - `length_1e-12`: its arc-length table to 1e-12 relative; `param_at_1e5`: 10^5
//!   parameter-at-length queries on that table;
//! - `intersect_100x100`: two planar cubics with 100 pieces each;
//! - `mesh_50x50`: a bicubic surface with 50×50 patches meshed to 1e-4 of its size;
//! - `ssi_sphere_cylinder`: the unit sphere and a cylinder of radius 0.6 about its axis (exact
//!   NURBS), intersected to 1e-6 (two circles); `section_torus`: a torus cut by an oblique
//!   plane to 1e-6 (Open CASCADE's side: `occt_queries ssi`, with `query_peer ssi`).
//!
//! Run: `cargo bench -p lekalo --bench query`. Smoke: `cargo test -p lekalo --benches`.

use std::hint::black_box;
use std::time::Duration;

use criterion::{criterion_main, Criterion, Throughput};
use std::f64::consts::{FRAC_PI_2, TAU};

use lekalo::surface::Placement;
use lekalo::{NurbsSurface, Points, QueryCurve, QuerySurface};

mod query_workloads;
use query_workloads::{plane_curve, query_point, space_curve, surface};

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
    let f = Placement::new([0.0; 3], None, None).expect("frame");
    let sphere =
        NurbsSurface::sphere(&f, 1.0, (0.0, TAU), (-FRAC_PI_2, FRAC_PI_2)).expect("sphere");
    let cylinder = NurbsSurface::cylinder(&f, 0.6, (0.0, TAU), (-1.2, 1.2)).expect("cylinder");
    let torus = NurbsSurface::torus(&f, 3.0, 1.0, (0.0, TAU), (0.0, TAU)).expect("torus");
    let (qs, qc, qt) = (
        QuerySurface::from_nurbs(&sphere).expect("sphere"),
        QuerySurface::from_nurbs(&cylinder).expect("cylinder"),
        QuerySurface::from_nurbs(&torus).expect("torus"),
    );
    g.bench_function("ssi_sphere_cylinder", |b| {
        b.iter(|| {
            black_box(&qs)
                .intersect_surface(&qc, 1e-6)
                .expect("branches")
        });
    });
    g.bench_function("section_torus", |b| {
        b.iter(|| {
            black_box(&qt)
                .intersect_plane(&[0.0, 0.0, 0.2], &[0.3, 0.1, 1.0], 1e-6)
                .expect("branches")
        });
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
