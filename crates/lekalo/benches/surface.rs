//! Surface evaluation benchmarks: a bicubic 3-D B-spline surface with a 30×30 net on
//! clamped uniform knots, evaluated on a 100×100 grid (`eval_grid`) and at 10^4 scattered
//! parameters (`eval_batch`), and the same as a NURBS surface with weights in `[0.5, 1.5)`.
//!
//! Run: `cargo bench -p lekalo --bench surface`. Smoke: `cargo test -p lekalo --benches`.

use std::hint::black_box;
use std::time::Duration;

use criterion::{criterion_main, Criterion, Throughput};
use lekalo::{BSplineSurface, KnotVector, NurbsSurface};

mod common;

/// Net size per direction.
const NET: usize = 30;
/// Grid size per direction.
const GRID: usize = 100;

fn surfaces() -> (BSplineSurface, NurbsSurface) {
    let knots = KnotVector::clamped_uniform(3, NET).expect("enough control points");
    let net = common::walk(NET * NET, 3, 21);
    let s = BSplineSurface::from_knot_vectors(
        3,
        3,
        knots.clone(),
        knots.clone(),
        net.clone(),
        (NET, NET),
    )
    .expect("valid surface");
    let mut rng = common::Lcg::new(23);
    let w: Vec<f64> = (0..NET * NET).map(|_| 0.5 + rng.next_f64()).collect();
    let k = knots.as_slice().to_vec();
    let n = NurbsSurface::new(3, 3, k.clone(), k, net, w, (NET, NET)).expect("valid NURBS");
    (s, n)
}

fn evaluation(c: &mut Criterion) {
    let (s, n) = surfaces();
    let us = common::sorted_params(GRID);
    let uv: Vec<[f64; 2]> = {
        let a = common::random_params(2 * GRID * GRID);
        a.chunks_exact(2).map(|p| [p[0], p[1]]).collect()
    };
    let mut out = vec![0.0; GRID * GRID * 3];
    let mut g = c.benchmark_group("surface_eval");
    g.measurement_time(Duration::from_secs(2)).sample_size(20);
    g.throughput(Throughput::Elements((GRID * GRID) as u64));
    g.bench_function("bspline_grid_100x100", |b| {
        b.iter(|| {
            s.eval_grid(black_box(&us), &us, &mut out)
                .expect("in domain")
        });
    });
    g.bench_function("bspline_batch_10k", |b| {
        b.iter(|| s.eval_batch(black_box(&uv), &mut out).expect("in domain"));
    });
    g.bench_function("nurbs_grid_100x100", |b| {
        b.iter(|| {
            n.eval_grid(black_box(&us), &us, &mut out)
                .expect("in domain")
        });
    });
    g.bench_function("nurbs_batch_10k", |b| {
        b.iter(|| n.eval_batch(black_box(&uv), &mut out).expect("in domain"));
    });
    g.finish();
}

/// All surface benchmarks (what `criterion_group!` would generate, with a doc comment).
fn benches() {
    let mut c = Criterion::default().configure_from_args();
    evaluation(&mut c);
}

criterion_main!(benches);
