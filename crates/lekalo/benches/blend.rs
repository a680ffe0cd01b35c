//! Blending benchmarks: the jump-smoothing polynomial `w_k`,
//! a C² deformation of two cubic Bezier curves, a blend spline through 100 points with local
//! parabolas and circular arcs (construction, then 1000 evaluations), and a corner transition.
//!
//! Run: `cargo bench -p lekalo --bench blend`. Smoke: `cargo test -p lekalo --benches`.

use std::hint::black_box;
use std::time::Duration;

use criterion::{criterion_main, BenchmarkId, Criterion, Throughput};
use lekalo::{
    BezierCurve, BlendSpline, BlendSplineOptions, CircularArcs, CornerTransition, Deformation,
    JumpPolynomial, LocalCurves, Parabolas, ParametricCurve, Points,
};

mod common;

/// Number of evaluations per batch.
const N_EVAL: usize = 1000;

fn cubic(p: [[f64; 3]; 4]) -> BezierCurve {
    BezierCurve::new(Points::from_3d(&p).expect("finite")).expect("valid cubic")
}

/// `N_EVAL` evaluations of `curve` at equally spaced parameters over its domain.
fn eval_all(curve: &impl ParametricCurve, ts: &[f64], out: &mut [f64]) {
    let dim = curve.dim();
    for (t, o) in ts.iter().zip(out.chunks_exact_mut(dim)) {
        curve
            .eval_derivatives_into(black_box(*t), 0, o)
            .expect("in domain");
    }
}

fn params(curve: &impl ParametricCurve) -> Vec<f64> {
    let (a, b) = curve.domain();
    common::sorted_params(N_EVAL)
        .into_iter()
        .map(|u| a + u * (b - a))
        .collect()
}

/// `w_k(u)` for k = 1, 3, 6 at 1000 parameters.
fn jump(c: &mut Criterion) {
    let ts = common::sorted_params(N_EVAL);
    let mut g = c.benchmark_group("jump_eval");
    g.measurement_time(Duration::from_secs(2)).sample_size(20);
    g.throughput(Throughput::Elements(N_EVAL as u64));
    for k in [1, 3, 6] {
        let w = JumpPolynomial::new(k).expect("valid k");
        g.bench_function(BenchmarkId::from_parameter(k), |b| {
            b.iter(|| {
                let mut s = 0.0;
                for &t in &ts {
                    s += w.eval(black_box(t)).expect("in [0, 1]");
                }
                s
            });
        });
    }
    g.finish();
}

/// Deformation of one cubic into another (common end points), C², 1000 evaluations; and a
/// C² corner transition between two cubics meeting at a corner.
fn deformation_and_corner(c: &mut Criterion) {
    let first = cubic([[0., 0., 0.], [1., 2., 0.], [2., 2., 1.], [3., 0., 0.]]);
    let second = cubic([[0., 0., 0.], [1., -1., 1.], [2., -2., 0.], [3., 0., 0.]]);
    let mut out = vec![0.0; N_EVAL * 3];
    let mut g = c.benchmark_group("deformation");
    g.measurement_time(Duration::from_secs(2)).sample_size(20);
    g.throughput(Throughput::Elements(N_EVAL as u64));
    let deform = Deformation::new(&first, &second, 2).expect("common end points");
    let ts = params(&deform);
    g.bench_function("eval_c2_cubics", |b| {
        b.iter(|| eval_all(&deform, &ts, &mut out));
    });
    g.finish();
    let after = cubic([[3., 0., 0.], [4., 1., 0.], [4., 2., 1.], [5., 3., 1.]]);
    let mut g = c.benchmark_group("corner_c2");
    g.measurement_time(Duration::from_secs(2)).sample_size(20);
    g.bench_function("new", |b| {
        b.iter(|| {
            CornerTransition::new(black_box(&first), 0.8, black_box(&after), 0.2, 2)
                .expect("valid corner")
        });
    });
    let corner = CornerTransition::new(&first, 0.8, &after, 0.2, 2).expect("valid corner");
    let ts = params(&corner);
    g.throughput(Throughput::Elements(N_EVAL as u64));
    g.bench_function("eval", |b| {
        b.iter(|| eval_all(&corner, &ts, &mut out));
    });
    g.finish();
}

/// Blend spline through 100 2-D points (C², uniform parameters): construction, and 1000
/// evaluations over the whole domain.
fn blend_spline(c: &mut Criterion) {
    let pts = common::walk(100, 2, 5);
    let arcs = CircularArcs::default();
    let locals: [(&str, &dyn LocalCurves); 2] = [("parabolas", &Parabolas), ("arcs", &arcs)];
    let mut out = vec![0.0; N_EVAL * 2];
    let mut g = c.benchmark_group("blend_spline_100");
    g.measurement_time(Duration::from_secs(2)).sample_size(20);
    for (name, local) in locals {
        let opts = BlendSplineOptions::default();
        g.bench_function(BenchmarkId::new("new", name), |b| {
            b.iter(|| BlendSpline::new(black_box(pts.as_view()), local, opts).expect("spline"));
        });
        let spline = BlendSpline::new(pts.as_view(), local, opts).expect("spline");
        let ts = params(&spline);
        g.bench_function(BenchmarkId::new("eval_1000", name), |b| {
            b.iter(|| eval_all(&spline, &ts, &mut out));
        });
    }
    g.finish();
}

/// All blending benchmarks (what `criterion_group!` would generate, with a doc comment).
fn benches() {
    let mut c = Criterion::default().configure_from_args();
    jump(&mut c);
    deformation_and_corner(&mut c);
    blend_spline(&mut c);
}

criterion_main!(benches);
