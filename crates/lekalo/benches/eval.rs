//! criterion benches of curve evaluation: batch evaluation at sorted and random parameters
//! (reference `BSplineCurve::eval_batch`, the fast `CurveEvaluator` kernels, the parallel path on
//! two threads), derivatives, NURBS, span search and basis functions.
//!
//! Run: `cargo bench --bench eval` (one group: `cargo bench --bench eval -- eval_sorted`).
//! Smoke (each benchmark once, test profile): `cargo test -p lekalo --benches`.

use std::hint::black_box;

use criterion::{criterion_main, Criterion, Throughput};
use lekalo::basis::{basis_derivatives, basis_functions};
use lekalo::{CurveEvaluator, EvalKernel};

mod common;

/// Batch size for curve evaluation (as in the peer comparison).
const N_BATCH: usize = 1_000_000;
/// Batch size of the per-point reference loops (derivatives, NURBS, search, basis).
const N_POINTS: usize = 100_000;

/// Cubic 3-D curve with 1000 control points at 10^6 parameters.
fn batch(c: &mut Criterion) {
    let curve = common::curve(3, 1000, 3);
    let power = CurveEvaluator::with_kernel(&curve, EvalKernel::PowerForm).expect("power form");
    let basis = CurveEvaluator::with_kernel(&curve, EvalKernel::Basis).expect("basis kernel");
    let pinned = common::rayon_pool(2, true);
    let free = common::rayon_pool(2, false);
    let mut out = vec![0.0; N_BATCH * 3];
    for (order, ts) in [
        ("sorted", common::sorted_params(N_BATCH)),
        ("random", common::random_params(N_BATCH)),
    ] {
        let mut g = c.benchmark_group(format!("eval_{order}"));
        g.throughput(Throughput::Elements(N_BATCH as u64));
        g.sample_size(10);
        g.bench_function("reference", |b| {
            b.iter(|| {
                curve
                    .eval_batch(black_box(&ts), &mut out)
                    .expect("in domain")
            });
        });
        g.bench_function("fast_power_form", |b| {
            b.iter(|| {
                power
                    .eval_batch(black_box(&ts), &mut out)
                    .expect("in domain")
            });
        });
        g.bench_function("fast_basis", |b| {
            b.iter(|| {
                basis
                    .eval_batch(black_box(&ts), &mut out)
                    .expect("in domain")
            });
        });
        for (name, pool) in [
            ("parallel_2_threads", &pinned),
            ("parallel_2_threads_unpinned", &free),
        ] {
            g.bench_function(name, |b| {
                b.iter(|| {
                    pool.install(|| power.par_eval_batch(black_box(&ts), &mut out))
                        .expect("in domain");
                });
            });
        }
        g.finish();
    }
}

/// Point, first and second derivative of the cubic at 10^5 sorted parameters.
fn derivatives(c: &mut Criterion) {
    let curve = common::curve(3, 1000, 3);
    let ev = curve.evaluator();
    let ts = common::sorted_params(N_POINTS);
    let mut out = vec![0.0; N_POINTS * 3 * 3];
    let mut g = c.benchmark_group("derivatives_order2");
    g.throughput(Throughput::Elements(N_POINTS as u64));
    g.sample_size(10);
    g.bench_function("reference", |b| {
        b.iter(|| {
            for &t in &ts {
                black_box(curve.eval_derivatives(black_box(t), 2).expect("in domain"));
            }
        });
    });
    g.bench_function("fast", |b| {
        b.iter(|| {
            ev.eval_derivatives_batch(black_box(&ts), 2, &mut out)
                .expect("in domain")
        });
    });
    g.finish();
}

/// Cubic 3-D NURBS with 1000 control points at 10^5 random parameters.
fn nurbs(c: &mut Criterion) {
    let curve = common::nurbs(3, 1000, 3);
    let ev = curve.evaluator();
    let pool = common::rayon_pool(2, true);
    let ts = common::random_params(N_POINTS);
    let mut out = vec![0.0; N_POINTS * 3];
    let mut g = c.benchmark_group("nurbs_random");
    g.throughput(Throughput::Elements(N_POINTS as u64));
    g.sample_size(10);
    g.bench_function("reference", |b| {
        b.iter(|| {
            for &t in &ts {
                black_box(curve.eval(black_box(t)).expect("in domain"));
            }
        });
    });
    g.bench_function("fast", |b| {
        b.iter(|| ev.eval_batch(black_box(&ts), &mut out).expect("in domain"));
    });
    g.bench_function("parallel_2_threads", |b| {
        b.iter(|| {
            pool.install(|| ev.par_eval_batch(black_box(&ts), &mut out))
                .expect("in domain")
        });
    });
    g.finish();
}

/// Span search among 1004 knots at 10^5 parameters.
fn span_search(c: &mut Criterion) {
    let curve = common::curve(3, 1000, 3);
    let knots = curve.knots();
    let ev = curve.evaluator();
    let sorted = common::sorted_params(N_POINTS);
    let random = common::random_params(N_POINTS);
    let mut g = c.benchmark_group("span_search");
    g.throughput(Throughput::Elements(N_POINTS as u64));
    g.sample_size(10);
    g.bench_function("binary_random", |b| {
        b.iter(|| {
            random
                .iter()
                .map(|&t| knots.find_span(3, t).expect("in domain"))
                .sum::<usize>()
        });
    });
    g.bench_function("cursor_sorted", |b| {
        b.iter(|| {
            let mut cursor = knots.span_cursor(3);
            sorted
                .iter()
                .map(|&t| cursor.find(t).expect("in domain"))
                .sum::<usize>()
        });
    });
    g.bench_function("bucket_random", |b| {
        b.iter(|| {
            random
                .iter()
                .map(|&t| ev.find_span(t).expect("in domain"))
                .sum::<usize>()
        });
    });
    g.finish();
}

/// Cubic basis functions and their derivatives at 10^5 random parameters.
fn basis(c: &mut Criterion) {
    let curve = common::curve(3, 1000, 3);
    let knots = curve.knots();
    let ts = common::random_params(N_POINTS);
    let mut g = c.benchmark_group("basis_cubic");
    g.throughput(Throughput::Elements(N_POINTS as u64));
    g.sample_size(10);
    g.bench_function("values", |b| {
        b.iter(|| {
            for &t in &ts {
                black_box(basis_functions(knots, 3, black_box(t)).expect("in domain"));
            }
        });
    });
    g.bench_function("derivatives_order2", |b| {
        b.iter(|| {
            for &t in &ts {
                black_box(basis_derivatives(knots, 3, black_box(t), 2).expect("in domain"));
            }
        });
    });
    g.finish();
}

/// The benchmark groups (a module, as `criterion_group!` makes an undocumented `pub fn`).
#[allow(missing_docs)]
mod groups {
    use super::{basis, batch, derivatives, nurbs, span_search};
    criterion::criterion_group!(benches, batch, derivatives, nurbs, span_search, basis);
}
criterion_main!(groups::benches);
