//! Piecewise-polynomial benchmarks: B-spline → pp form
//! (`PiecewisePolynomial::from_bspline`) and pp → B-spline by de Boor–Fix functionals
//! (`PiecewisePolynomial::to_bspline`) for cubic C² 3-D splines of 10, 100 and 1000 pieces,
//! and `quasi_interpolate` of `x cos x` on the same spaces (scalar).
//!
//! Run: `cargo bench -p lekalo --bench pp`. Smoke: `cargo test -p lekalo --benches`.

use std::hint::black_box;
use std::time::Duration;

use criterion::{criterion_main, BenchmarkId, Criterion, Throughput};
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

/// All pp benchmarks (what `criterion_group!` would generate, with a doc comment).
fn benches() {
    let mut c = Criterion::default().configure_from_args();
    conversions(&mut c);
}

criterion_main!(benches);
