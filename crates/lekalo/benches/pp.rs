//! Piecewise-polynomial benchmarks: B-spline → pp form
//! (`PiecewisePolynomial::from_bspline`) and pp → B-spline by de Boor–Fix functionals
//! (`PiecewisePolynomial::to_bspline`) for cubic C² 3-D splines of 10, 100 and 1000 pieces,
//! and `quasi_interpolate` of `x cos x` on the same spaces (scalar); evaluation of a scalar
//! cubic of 1000 pieces at 10^5 points with the end pieces continued, by the pp-form
//! (`eval_extrapolated_into`) and by SciPy's `PPoly` arrays read in place (`PowerFormRef`, what
//! `lekalo.scipy.PPoly.__call__` calls; SciPy's side in `bench/python/scipy_bench.py`).
//!
//! Run: `cargo bench -p lekalo --bench pp`. Smoke: `cargo test -p lekalo --benches`.

use std::hint::black_box;
use std::time::Duration;

use criterion::{criterion_main, BenchmarkId, Criterion, Throughput};
use lekalo::pp::PowerFormRef;
use lekalo::{quasi_interpolate, PiecewisePolynomial, PpSpace, TauRule};

mod common;

/// Numbers of pieces.
const PIECES: [usize; 3] = [10, 100, 1000];

/// The cubic C² space on `pieces` uniform pieces of `[0, 1]` and a 3-D spline in it.
fn workload(pieces: usize) -> (PpSpace, lekalo::BSplineCurve) {
    let curve = common::curve(3, pieces + 3, 3);
    let breaks = common::sorted_params(pieces + 1);
    let space = PpSpace::new(&breaks, &vec![3; pieces - 1], 4).expect("valid space");
    (space, curve)
}

fn conversions(c: &mut Criterion) {
    let mut g = c.benchmark_group("pp_convert");
    g.measurement_time(Duration::from_secs(2)).sample_size(20);
    for n in PIECES {
        let (space, curve) = workload(n);
        let pp = PiecewisePolynomial::from_bspline(&curve).expect("pp form");
        g.throughput(Throughput::Elements(n as u64));
        g.bench_function(BenchmarkId::new("from_bspline", n), |b| {
            b.iter(|| PiecewisePolynomial::from_bspline(black_box(&curve)).expect("pp form"));
        });
        g.bench_function(BenchmarkId::new("to_bspline", n), |b| {
            b.iter(|| {
                black_box(&pp)
                    .to_bspline(&space, TauRule::Midpoint)
                    .expect("in the space")
            });
        });
        g.bench_function(BenchmarkId::new("quasi_interpolate", n), |b| {
            b.iter(|| {
                quasi_interpolate(&space, TauRule::FirstKnotAfter, |x, r| match r {
                    0 => x * x.cos(),
                    1 => x.cos() - x * x.sin(),
                    2 => -2.0 * x.sin() - x * x.cos(),
                    _ => -3.0 * x.cos() + x * x.sin(),
                })
                .expect("finite")
            });
        });
    }
    g.finish();
}

fn evaluation(c: &mut Criterion) {
    let mut g = c.benchmark_group("pp_eval");
    g.measurement_time(Duration::from_secs(2)).sample_size(20);
    let (pieces, order, points) = (1000, 4, 100_000);
    let breaks: Vec<f64> = (0..=pieces).map(|i| i as f64 / pieces as f64).collect();
    // SciPy's layout (order, pieces), the highest power first, and the pp-form's (pieces,
    // order), the lowest first
    let scipy: Vec<f64> = (0..order * pieces)
        .map(|i| ((i * 31) % 97) as f64 / 97.0 - 0.5)
        .collect();
    let mut local = vec![0.0; order * pieces];
    for m in 0..order {
        for j in 0..pieces {
            local[j * order + (order - 1 - m)] = scipy[m * pieces + j];
        }
    }
    let pp = PiecewisePolynomial::new(breaks.clone(), order, 1, local).expect("valid pp-form");
    let xs: Vec<f64> = (0..points)
        .map(|i| ((i * 7919) % 10007) as f64 / 10007.0 * 1.2 - 0.1)
        .collect();
    let mut out = vec![0.0; points];
    g.throughput(Throughput::Elements(points as u64));
    g.bench_function(BenchmarkId::new("pp_form_extrapolated", pieces), |b| {
        b.iter(|| {
            for (&x, o) in black_box(&xs).iter().zip(out.chunks_exact_mut(1)) {
                pp.eval_extrapolated_into(x, 0, o).expect("finite");
            }
        });
    });
    g.bench_function(BenchmarkId::new("power_form_in_place", pieces), |b| {
        b.iter(|| {
            PowerFormRef::new(black_box(&scipy), order, &breaks, 1)
                .expect("valid arrays")
                .par_eval_extrapolated(&xs, 0, &mut out)
                .expect("finite");
        });
    });
    g.finish();
}

/// All pp benchmarks (what `criterion_group!` would generate, with a doc comment).
fn benches() {
    let mut c = Criterion::default().configure_from_args();
    conversions(&mut c);
    evaluation(&mut c);
}

criterion_main!(benches);
