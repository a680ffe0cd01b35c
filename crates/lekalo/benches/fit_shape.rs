//! Shape-constrained least squares against the unconstrained fit on the same data, side by side:
//! 10^5 noisy samples of a rising curve with a dip, 200 cubic coefficients, increasing and convex
//! with a lower bound (`docs/theory/fitting.md#shape-constraints`).

use criterion::{criterion_main, Criterion, Throughput};
use lekalo::fit::{
    constrained_least_squares, least_squares, EndConstraints, FitData, Shape, ShapeConstraints,
};
use lekalo::{KnotVector, PointsRef};

fn shape(c: &mut Criterion) {
    let n = 100_000usize;
    let x: Vec<f64> = (0..n).map(|k| k as f64 / (n - 1) as f64).collect();
    // deterministic pseudo-noise (no randomness in benchmarks either)
    let y: Vec<f64> = x
        .iter()
        .enumerate()
        .map(|(k, &t)| {
            t * t + 0.05 * (9.0 * t).sin() + 0.02 * (((k * 7919) % 1009) as f64 / 504.5 - 1.0)
        })
        .collect();
    let data = FitData::new(PointsRef::from_flat(1, &y).expect("points"), &x).expect("data");
    let kv = KnotVector::clamped_uniform(3, 200).expect("knots");
    let cons = ShapeConstraints::new()
        .with(Shape::Increasing)
        .with(Shape::Convex)
        .with(Shape::AtLeast(0.0));
    let mut g = c.benchmark_group("fit_shape");
    g.sample_size(10);
    g.throughput(Throughput::Elements(n as u64));
    g.bench_function("lsq_200_cubic_unconstrained", |b| {
        b.iter(|| least_squares(&data, 3, &kv, &EndConstraints::none()).expect("fit"));
    });
    g.bench_function("lsq_200_cubic_increasing_convex_min", |b| {
        b.iter(|| constrained_least_squares(&data, 3, &kv, &cons).expect("fit"));
    });
    g.finish();
}

/// The benchmark (what `criterion_group!` would generate, with a doc comment).
fn benches() {
    let mut c = Criterion::default().configure_from_args();
    shape(&mut c);
}
criterion_main!(benches);
