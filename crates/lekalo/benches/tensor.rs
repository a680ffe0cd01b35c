//! N-variate evaluation benchmarks: a trivariate cubic lookup table (nets of 20³ and 128³
//! coefficients) at 10^5 random points, by the owned spline's extrapolating batch and by the
//! borrowed spline ([`TensorBSplineRef`], what `lekalo.scipy.NdBSpline` calls on SciPy's arrays
//! in place); and a bicubic spline of 100 × 100 coefficients on a 316 × 316 grid (sum
//! factorisation, what `RectBivariateSpline.__call__` and `bisplev` call). SciPy's side of the
//! same workloads: `bench/python/scipy_bench.py` and `bench/python/tensor_bench.py`.
//!
//! Run: `cargo bench -p lekalo --bench tensor`. Smoke: `cargo test -p lekalo --benches`.

use std::hint::black_box;
use std::time::Duration;

use criterion::{criterion_main, BenchmarkId, Criterion, Throughput};
use lekalo::tensor::Beyond;
use lekalo::{Points, TensorBSpline};

/// Points of the batches.
const POINTS: usize = 100_000;

/// Clamped uniform cubic knots on `[0, 1]` for `n` coefficients.
fn knots(n: usize) -> Vec<f64> {
    let p = 3;
    (0..n + p + 1)
        .map(|i| (i.saturating_sub(p).min(n - p)) as f64 / (n - p) as f64)
        .collect()
}

/// A spline of `n` coefficients in each of `vars` directions, coefficients from a fixed
/// pseudo-random sequence.
fn spline(n: usize, vars: usize) -> TensorBSpline {
    let count = n.pow(u32::try_from(vars).expect("few directions"));
    let net: Vec<f64> = (0..count)
        .map(|i| ((i * 7919) % 1013) as f64 / 1013.0 - 0.5)
        .collect();
    TensorBSpline::new(
        vec![3; vars],
        vec![knots(n); vars],
        Points::from_flat(1, net).expect("a scalar net"),
    )
    .expect("a valid spline")
}

/// `count` pseudo-random numbers in `[0, 1)`.
fn uniform(count: usize) -> Vec<f64> {
    let mut state = 0x9e37_79b9_7f4a_7c15u64;
    (0..count)
        .map(|_| {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        })
        .collect()
}

fn trivariate(c: &mut Criterion) {
    let mut g = c.benchmark_group("tensor_eval");
    g.measurement_time(Duration::from_secs(3)).sample_size(20);
    g.throughput(Throughput::Elements(POINTS as u64));
    let xs = uniform(3 * POINTS);
    let mut out = vec![0.0; POINTS];
    for n in [20, 128] {
        let s = spline(n, 3);
        g.bench_function(BenchmarkId::new("owned_extrapolated", n), |b| {
            b.iter(|| {
                s.par_eval_batch_extrapolated(black_box(&xs), None, &mut out)
                    .expect("finite points");
            });
        });
        g.bench_function(BenchmarkId::new("borrowed_beyond", n), |b| {
            b.iter(|| {
                s.view()
                    .par_eval_batch_beyond(black_box(&xs), None, Beyond::Continue, &mut out)
                    .expect("sizes agree");
            });
        });
    }
    g.finish();
}

fn grid(c: &mut Criterion) {
    let mut g = c.benchmark_group("tensor_grid");
    g.measurement_time(Duration::from_secs(3)).sample_size(20);
    let m = 316;
    g.throughput(Throughput::Elements((m * m) as u64));
    let s = spline(100, 2);
    let axis: Vec<f64> = (0..m).map(|i| i as f64 / (m - 1) as f64).collect();
    let mut out = vec![0.0; m * m];
    g.bench_function(BenchmarkId::new("bicubic_100x100_on_grid", m), |b| {
        b.iter(|| {
            s.eval_grid(black_box(&[&axis, &axis]), None, &mut out)
                .expect("inside the domain");
        });
    });
    g.finish();
}

/// All tensor benchmarks (what `criterion_group!` would generate, with a doc comment).
fn benches() {
    let mut c = Criterion::default().configure_from_args();
    trivariate(&mut c);
    grid(&mut c);
}

criterion_main!(benches);
