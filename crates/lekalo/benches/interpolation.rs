//! Interpolation benchmarks: cubic global curve interpolation through `n` 3-D points
//! (chord length, averaged knots) for `n = 10^3 … 10^6`, and bicubic surface interpolation of
//! `n × n` grids for `n = 50 … 400`. Throughput is per point, so ns/point reads off directly.
//! Curves are timed twice: `fresh` (every result in newly allocated memory, as
//! `CurveInterpolation::interpolate`) and `workspace` (`interpolate_with` reusing the previous
//! result's buffers), which separates the arithmetic from the operating system's page faults.

use criterion::{criterion_main, BenchmarkId, Criterion, Throughput};
use lekalo::{CurveInterpolation, InterpolationWorkspace, Parametrization, SurfaceInterpolation};

mod common;

fn curve_interpolation(c: &mut Criterion) {
    let mut group = c.benchmark_group("curve_interpolation_cubic_3d");
    for n in [1_000, 10_000, 100_000, 1_000_000] {
        let q = common::helix(n);
        group.throughput(Throughput::Elements(n as u64));
        if n >= 100_000 {
            group.sample_size(10);
        }
        group.bench_with_input(BenchmarkId::new("fresh", n), &q, |b, q| {
            b.iter(|| {
                CurveInterpolation::new(3)
                    .interpolate(q.as_view())
                    .expect("interpolation")
            });
        });
        // the same curve with the buffers of the previous result reused: no page faults
        let mut ws = InterpolationWorkspace::new();
        group.bench_with_input(BenchmarkId::new("workspace", n), &q, |b, q| {
            b.iter(|| {
                let c = CurveInterpolation::new(3)
                    .interpolate_with(q.as_view(), &mut ws)
                    .expect("interpolation");
                ws.recycle(c);
            });
        });
    }
    group.finish();
}

fn surface_interpolation(c: &mut Criterion) {
    let mut group = c.benchmark_group("surface_interpolation_bicubic");
    group.sample_size(10);
    for n in [50, 100, 200, 400] {
        let g = common::grid(n);
        group.throughput(Throughput::Elements((n * n) as u64));
        group.bench_with_input(BenchmarkId::from_parameter(n), &g, |b, g| {
            b.iter(|| {
                SurfaceInterpolation::new(3, 3)
                    .parametrization(Parametrization::ChordLength)
                    .interpolate(g.as_view(), n, n)
                    .expect("surface")
            });
        });
    }
    group.finish();
}

/// All interpolation benchmarks (what `criterion_group!` would generate, with a doc comment).
fn benches() {
    let mut c = Criterion::default().configure_from_args();
    curve_interpolation(&mut c);
    surface_interpolation(&mut c);
}

criterion_main!(benches);
