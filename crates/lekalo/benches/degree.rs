//! Degree-change benchmarks: Bezier elevation 10→20 and 50→100 in 3-D, per curve
//! (`BezierCurve::elevate_degree`, allocating, and a precomputed `ElevationPlan::apply_into`
//! into a reused buffer), exact reduction of an elevated curve back to its real degree
//! (`reduce_degree_exact`, `change_degree`), approximate reduction with tangent end conditions,
//! and B-spline elevation by one (cubic 3-D, 1000 control points).
//!
//! Run: `cargo bench -p lekalo --bench degree`. Smoke: `cargo test -p lekalo --benches`.

use std::hint::black_box;
use std::time::Duration;

use criterion::{criterion_main, BenchmarkId, Criterion};
use lekalo::{BezierCurve, ElevationPlan, EndConditions};

mod common;

/// A 3-D Bezier curve of degree `n` with random-walk control points.
fn bezier(n: usize) -> BezierCurve {
    BezierCurve::new(common::walk(n + 1, 3, 3)).expect("valid Bezier curve")
}

/// Elevation `from → to`, both ways, per curve.
fn elevation(c: &mut Criterion) {
    let mut g = c.benchmark_group("bezier_elevate");
    g.measurement_time(Duration::from_secs(2)).sample_size(20);
    for (from, to) in [(10, 20), (50, 100)] {
        let curve = bezier(from);
        let id = format!("{from}to{to}");
        g.bench_function(BenchmarkId::new("elevate_degree", &id), |b| {
            b.iter(|| {
                black_box(&curve)
                    .elevate_degree(to - from)
                    .expect("elevation")
            });
        });
        let plan = ElevationPlan::new(from, to).expect("plan");
        let mut out = vec![0.0; (to + 1) * 3];
        g.bench_function(BenchmarkId::new("plan_apply_into", &id), |b| {
            b.iter(|| {
                plan.apply_into(black_box(curve.control_points().as_slice()), 3, &mut out)
                    .expect("buffer lengths");
            });
        });
    }
    g.finish();
}

/// Reduction of 10→20 and 50→100 elevated curves: exact (back to the real degree) and
/// approximate (by half the degree, tangents kept at the ends).
fn reduction(c: &mut Criterion) {
    let mut g = c.benchmark_group("bezier_reduce");
    g.measurement_time(Duration::from_secs(2)).sample_size(20);
    for (from, to) in [(10, 20), (50, 100)] {
        let elevated = bezier(from).elevate_degree(to - from).expect("elevation");
        let id = format!("{to}to{from}");
        g.bench_function(BenchmarkId::new("reduce_degree_exact", &id), |b| {
            b.iter(|| black_box(&elevated).reduce_degree_exact());
        });
        g.bench_function(BenchmarkId::new("change_degree", &id), |b| {
            b.iter(|| {
                black_box(&elevated)
                    .change_degree(from)
                    .expect("exact reduction")
            });
        });
    }
    let deg20 = bezier(20);
    g.bench_function(BenchmarkId::new("reduce_degree_approx", "20to10"), |b| {
        b.iter(|| {
            black_box(&deg20)
                .reduce_degree_approx(10, EndConditions::Tangents)
                .expect("approximate reduction")
        });
    });
    g.finish();
}

/// B-spline elevation by one: cubic 3-D curve with 1000 control points.
fn bspline_elevation(c: &mut Criterion) {
    let curve = common::curve(3, 1000, 3);
    let mut g = c.benchmark_group("bspline_elevate");
    g.measurement_time(Duration::from_secs(2)).sample_size(10);
    g.bench_function("cubic_1000_by1", |b| {
        b.iter(|| black_box(&curve).elevate_degree(1).expect("elevation"));
    });
    g.finish();
}

/// All degree benchmarks (what `criterion_group!` would generate, with a doc comment).
fn benches() {
    let mut c = Criterion::default().configure_from_args();
    elevation(&mut c);
    reduction(&mut c);
    bspline_elevation(&mut c);
}

criterion_main!(benches);
