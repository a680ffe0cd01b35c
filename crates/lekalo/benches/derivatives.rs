//! criterion benches of the derivative kernels of evaluation (`lekalo::derivatives`): a cubic
//! 3-D curve with 1000 control points at 10^6 sorted parameters, the plain batch evaluation
//! beside its JVP (values only, control-point tangent, parameter tangent), its VJP (control
//! points and parameters) and its linearisation.
//!
//! Run: `cargo bench --bench derivatives`.
//! Smoke (each benchmark once, test profile): `cargo test -p lekalo --benches`.

use std::hint::black_box;

use criterion::{criterion_main, Criterion, Throughput};

mod common;

/// Batch size.
const N_BATCH: usize = 1_000_000;

fn curve(c: &mut Criterion) {
    let curve = common::curve(3, 1000, 3);
    let ts = common::sorted_params(N_BATCH);
    let dim = curve.dim();
    let dp = vec![0.5; curve.control_points().as_slice().len()];
    let dt = vec![0.25; N_BATCH];
    let g = vec![1.0; N_BATCH * dim];
    let (mut out, mut tan) = (vec![0.0; N_BATCH * dim], vec![0.0; N_BATCH * dim]);
    let (mut gp, mut gt) = (vec![0.0; dp.len()], vec![0.0; N_BATCH]);
    let mut group = c.benchmark_group("curve_derivatives");
    group.throughput(Throughput::Elements(N_BATCH as u64));
    group.sample_size(10);
    group.bench_function("eval_batch", |b| {
        b.iter(|| {
            curve
                .eval_batch(black_box(&ts), &mut out)
                .expect("in domain")
        });
    });
    group.bench_function("jvp_values_only", |b| {
        b.iter(|| {
            curve
                .eval_batch_jvp(black_box(&ts), None, None, &mut out, &mut tan)
                .expect("in domain")
        });
    });
    group.bench_function("jvp_control", |b| {
        b.iter(|| {
            curve
                .eval_batch_jvp(black_box(&ts), Some(&dp), None, &mut out, &mut tan)
                .expect("in domain")
        });
    });
    group.bench_function("jvp_parameters", |b| {
        b.iter(|| {
            curve
                .eval_batch_jvp(black_box(&ts), None, Some(&dt), &mut out, &mut tan)
                .expect("in domain")
        });
    });
    group.bench_function("vjp_control_and_parameters", |b| {
        b.iter(|| {
            curve
                .eval_batch_vjp(black_box(&ts), &g, Some(&mut gp), Some(&mut gt))
                .expect("in domain")
        });
    });
    group.bench_function("linearize", |b| {
        b.iter(|| {
            curve
                .eval_batch_linearize(black_box(&ts))
                .expect("in domain")
        });
    });
    group.finish();
}

fn benches() {
    let mut c = Criterion::default().configure_from_args();
    curve(&mut c);
}

criterion_main!(benches);
