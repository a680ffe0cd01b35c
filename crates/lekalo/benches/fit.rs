//! Fitting benchmarks: least squares through 10^6 points with 1000 cubic control points;
//! penalised smoothing of 10^5 points with GCV; the smoothing condition on 10^5 noisy points;
//! a tolerance fit of 10^5 points; scattered-surface least squares of 10^5 points on a 30 × 30
//! cubic net. `bench/peers/fit_peers.py` times SciPy on the same data.

use criterion::{criterion_main, BenchmarkId, Criterion, Throughput};
use lekalo::fit::{
    fit_tolerance, least_squares, smoothing_condition, smoothing_spline,
    surface_scattered_least_squares, EndConstraints, FitData, Lambda, ToleranceOptions,
};
use lekalo::{KnotVector, PointsRef};

mod fit_workloads;
use fit_workloads as w;

fn lsq(c: &mut Criterion) {
    let mut g = c.benchmark_group("fit");
    g.sample_size(10);
    for n in [100_000usize, 1_000_000] {
        let (x, y) = w::noisy_function(n, 1);
        let kv = KnotVector::new(w::uniform_knots(0.0, 1.0, 1000)).expect("knots");
        let (lo, hi) = (x[0], x[n - 1]);
        let kv = KnotVector::new(kv.as_slice().iter().map(|t| lo + (hi - lo) * t).collect())
            .expect("knots");
        g.throughput(Throughput::Elements(n as u64));
        g.bench_with_input(BenchmarkId::new("lsq_1000_cubic", n), &n, |b, _| {
            let data =
                FitData::new(PointsRef::from_flat(1, &y).expect("points"), &x).expect("data");
            b.iter(|| least_squares(&data, 3, &kv, &EndConstraints::none()).expect("fit"));
        });
    }
    let n = 100_000;
    let (x, y) = w::noisy_function(n, 2);
    let data = FitData::new(PointsRef::from_flat(1, &y).expect("points"), &x).expect("data");
    g.throughput(Throughput::Elements(n as u64));
    g.bench_function(BenchmarkId::new("smoothing_gcv", n), |b| {
        b.iter(|| smoothing_spline(&data, Lambda::Gcv).expect("fit"));
    });
    let s = n as f64 * w::NOISE * w::NOISE;
    g.bench_function(BenchmarkId::new("smoothing_condition", n), |b| {
        b.iter(|| smoothing_condition(&data, 3, s).expect("fit"));
    });
    let q = w::spiral(n, 3);
    g.bench_function(BenchmarkId::new("tolerance_1e-3", n), |b| {
        b.iter(|| {
            fit_tolerance(
                PointsRef::from_flat(2, &q).expect("points"),
                &ToleranceOptions::new(3, 1e-3),
            )
            .expect("fit")
        });
    });
    let rows = w::scattered(n, 4);
    let ku = KnotVector::new(w::uniform_knots(0.0, 1.0, 30)).expect("knots");
    g.bench_function(BenchmarkId::new("scattered_surface_30x30", n), |b| {
        b.iter(|| {
            surface_scattered_least_squares(
                PointsRef::from_flat(3, &rows).expect("rows"),
                None,
                (3, 3),
                (&ku, &ku),
                0.0,
            )
            .expect("fit")
        });
    });
    g.finish();
}

/// All fitting benchmarks (what `criterion_group!` would generate, with a doc comment).
fn benches() {
    let mut c = Criterion::default().configure_from_args();
    lsq(&mut c);
}
criterion_main!(benches);
