//! criterion benches of the derivative kernels of evaluation (`lekalo::derivatives`): a cubic
//! 3-D curve with 1000 control points at 10^6 sorted parameters, the plain batch evaluation
//! beside its JVP (values only, control-point tangent, parameter tangent), its VJP (control
//! points and parameters) and its linearisation; and the derivatives of fits with respect to
//! the data beside the fits themselves: least squares of 10^5 3-D points on 1000 cubic control
//! points, the smoothing spline of 10^5 3-D points (factor once, then JVP and VJP).
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

/// Data points of the fit benches.
const N_FIT: usize = 100_000;

fn fits(c: &mut Criterion) {
    use lekalo::derivatives::{LeastSquaresMap, SmoothingMap};
    use lekalo::fit::{least_squares, smoothing_spline, EndConstraints, FitData, Lambda};
    let curve = common::curve(3, 1000, 3);
    let ts = common::sorted_params(N_FIT);
    let mut q = vec![0.0; N_FIT * 3];
    curve.eval_batch(&ts, &mut q).expect("in domain");
    let data = FitData::new(lekalo::PointsRef::from_flat(3, &q).expect("finite"), &ts)
        .expect("valid data");
    let knots = curve.knots();
    let g_ctrl = vec![1.0; 1000 * 3];
    let mut group = c.benchmark_group("fit_derivatives");
    group.throughput(Throughput::Elements(N_FIT as u64));
    group.sample_size(10);
    group.bench_function("least_squares_fit", |b| {
        b.iter(|| least_squares(black_box(&data), 3, knots, &EndConstraints::none()).expect("fit"));
    });
    group.bench_function("least_squares_map_new", |b| {
        b.iter(|| LeastSquaresMap::new(3, knots, black_box(&ts), None).expect("map"));
    });
    let map = LeastSquaresMap::new(3, knots, &ts, None).expect("map");
    group.bench_function("least_squares_jvp", |b| {
        b.iter(|| map.jvp(black_box(&q), 3).expect("jvp"));
    });
    group.bench_function("least_squares_vjp", |b| {
        b.iter(|| map.vjp(black_box(&g_ctrl), 3).expect("vjp"));
    });
    group.bench_function("smoothing_fit", |b| {
        b.iter(|| smoothing_spline(black_box(&data), Lambda::Given(1e-6)).expect("fit"));
    });
    let smooth = SmoothingMap::new(&ts, 1e-6, None).expect("map");
    group.bench_function("smoothing_jvp", |b| {
        b.iter(|| smooth.jvp(black_box(&q), 3).expect("jvp"));
    });
    let g_smooth = vec![1.0; (N_FIT + 2) * 3];
    group.bench_function("smoothing_vjp", |b| {
        b.iter(|| smooth.vjp(black_box(&g_smooth), 3).expect("vjp"));
    });
    group.finish();
}

fn benches() {
    let mut c = Criterion::default().configure_from_args();
    curve(&mut c);
    fits(&mut c);
}

criterion_main!(benches);
