//! Our side of the peer comparison (`bench/peers/run.sh`): writes the shared workload data to a
//! directory as little-endian `f64` files and times lekalo on it, medians into `ours.json` in
//! the same directory. The Python script then times the peers on the same files, and runs this
//! program once more with a third argument, a results file name (`ours_after.json`): then only
//! the timings are taken and written there, so that lekalo is timed both before and after the
//! peers. A fourth argument, a comma list of workload names (`interp_1000000`,
//! `eval_sorted`, ...), times only those: `peers.py` times each workload this way just before
//! and just after its peers, so that both sides of a ratio fall in the same few seconds of
//! this shared machine.
//!
//! Workloads: curve evaluation (ns per parameter), cubic curve interpolation through `n` 3-D
//! points (ns per point), bicubic surface interpolation of `n × n` grids (ns per grid point) and
//! Bezier degree elevation of one 3-D curve (ns per curve).
//!
//! `cargo run --release --example peer_bench -- DIR [REPEATS [RESULTS [WORKLOADS]]]`

use std::hint::black_box;
use std::path::{Path, PathBuf};
use std::time::Instant;

use lekalo::{
    parametrize, BezierCurve, CurveInterpolation, ElevationPlan, InterpolationWorkspace,
    Parametrization, SurfaceInterpolation,
};

#[path = "../benches/common/mod.rs"]
mod common;

/// Curve of the evaluation workload: cubic, 3-D, 1000 control points.
const DEGREE: usize = 3;
const DIM: usize = 3;
const N_CTRL: usize = 1000;
/// Parameters per evaluation workload.
const N: usize = 1_000_000;
/// Point counts of the curve interpolation workload.
const INTERP_SIZES: [usize; 4] = [1_000, 10_000, 100_000, 1_000_000];
/// Grid sides of the surface interpolation workload.
const SURFACE_SIZES: [usize; 3] = [100, 200, 400];
/// Bezier degree elevations `(from, to)`.
const ELEVATIONS: [(usize, usize); 2] = [(10, 20), (50, 100)];
/// Shortest time of one timed sample, in ns: quick calls are repeated inside a sample up to this.
const MIN_SAMPLE_NANOS: u128 = 20_000_000;

/// Where the workload data go: `dir`, or nowhere when only timings are wanted; and which
/// workloads are timed (all when `only` is empty).
struct Data<'a> {
    dir: &'a Path,
    write: bool,
    only: Vec<String>,
}

impl Data<'_> {
    /// Whether the workload `name` is timed in this run.
    fn wants(&self, name: &str) -> bool {
        self.only.is_empty() || self.only.iter().any(|w| w == name)
    }

    /// Writes `v` to `dir/name` as little-endian `f64`, synced to the disk before returning.
    fn f64s(&self, name: &str, v: &[f64]) -> std::io::Result<()> {
        use std::io::Write;
        if !self.write {
            return Ok(());
        }
        let bytes: Vec<u8> = v.iter().flat_map(|x| x.to_le_bytes()).collect();
        let mut file = std::fs::File::create(self.dir.join(name))?;
        file.write_all(&bytes)?;
        // written through to the disk now: otherwise the kernel writes the dirty pages back
        // while the next timings run, on one of this 2-vCPU machine's processors
        file.sync_all()
    }
}

/// Median wall time of `repeats` samples of `f`, in ns per point (`points` per call). The
/// warm-up call sets how many calls make one sample (at least [`MIN_SAMPLE_NANOS`]), so that
/// sub-millisecond calls are timed over many repetitions; the Python side does the same.
fn median_ns(repeats: usize, points: usize, mut f: impl FnMut()) -> f64 {
    let t0 = Instant::now();
    f(); // warm-up
    let once = t0.elapsed().as_nanos().max(1);
    let inner = usize::try_from(MIN_SAMPLE_NANOS.div_ceil(once)).map_or(1, |k| k.max(1));
    let mut times: Vec<f64> = (0..repeats.max(1))
        .map(|_| {
            let t0 = Instant::now();
            for _ in 0..inner {
                f();
            }
            t0.elapsed().as_secs_f64() / inner as f64
        })
        .collect();
    times.sort_by(f64::total_cmp);
    times[times.len() / 2] * 1e9 / points as f64
}

type Results = serde_json::Map<String, serde_json::Value>;
type Res<T> = Result<T, Box<dyn std::error::Error>>;

/// Cubic chord-length interpolation through the helix, fresh and with a reused workspace; writes
/// the points, our parameters, knots and control points.
fn interpolation(data: &Data<'_>, repeats: usize, results: &mut Results) -> Res<()> {
    for n in INTERP_SIZES {
        if !data.wants(&format!("interp_{n}")) {
            continue;
        }
        let q = common::helix(n);
        let params = parametrize(q.as_view(), Parametrization::ChordLength)?;
        let curve = CurveInterpolation::new(3).interpolate(q.as_view())?;
        data.f64s(&format!("interp_q_{n}.bin"), q.as_slice())?;
        data.f64s(&format!("interp_t_{n}.bin"), &params)?;
        data.f64s(&format!("interp_knots_{n}.bin"), curve.knots().as_slice())?;
        data.f64s(
            &format!("interp_ctrl_{n}.bin"),
            curve.control_points().as_slice(),
        )?;
        let fresh = median_ns(repeats, n, || {
            black_box(
                CurveInterpolation::new(3)
                    .interpolate(black_box(q.as_view()))
                    .expect("interpolation"),
            );
        });
        let mut ws = InterpolationWorkspace::new();
        let reused = median_ns(repeats, n, || {
            let c = CurveInterpolation::new(3)
                .interpolate_with(black_box(q.as_view()), &mut ws)
                .expect("interpolation");
            ws.recycle(black_box(c));
        });
        println!("interp_{n}: fresh {fresh:.1} ns/pt, workspace {reused:.1}");
        results.insert(
            format!("interp_{n}"),
            serde_json::json!({"fresh": fresh, "workspace": reused}),
        );
    }
    Ok(())
}

/// Bicubic chord-length surface interpolation of the `n × n` grid; writes the grid, our
/// parameters, knots and control net.
fn surface(data: &Data<'_>, repeats: usize, results: &mut Results) -> Res<()> {
    for n in SURFACE_SIZES {
        if !data.wants(&format!("surface_{n}")) {
            continue;
        }
        let g = common::grid(n);
        let fit = SurfaceInterpolation::new(3, 3).parametrization(Parametrization::ChordLength);
        let (s, report) = fit.interpolate_with_report(g.as_view(), n, n)?;
        let (knots_u, knots_v) = s.knots();
        data.f64s(&format!("surf_q_{n}.bin"), g.as_slice())?;
        data.f64s(&format!("surf_u_{n}.bin"), report.params_u())?;
        data.f64s(&format!("surf_v_{n}.bin"), report.params_v())?;
        data.f64s(&format!("surf_ku_{n}.bin"), knots_u.as_slice())?;
        data.f64s(&format!("surf_kv_{n}.bin"), knots_v.as_slice())?;
        data.f64s(&format!("surf_ctrl_{n}.bin"), s.control_points().as_slice())?;
        let fresh = median_ns(repeats, n * n, || {
            black_box(
                fit.interpolate(black_box(g.as_view()), n, n)
                    .expect("surface"),
            );
        });
        println!("surface_{n}: {fresh:.1} ns/pt");
        results.insert(format!("surface_{n}"), serde_json::json!({"fresh": fresh}));
    }
    Ok(())
}

/// Bezier degree elevation of one 3-D curve: [`ElevationPlan::apply_into`] into a reused
/// buffer and [`BezierCurve::elevate_degree`] (allocating), ns per curve.
fn elevation(data: &Data<'_>, repeats: usize, results: &mut Results) -> Res<()> {
    for (from, to) in ELEVATIONS {
        if !data.wants(&format!("elevate_{from}_{to}")) {
            continue;
        }
        let ctrl = common::walk(from + 1, DIM, 21 + from as u64);
        let bez = BezierCurve::new(ctrl.clone())?;
        let plan = ElevationPlan::new(from, to)?;
        let mut out = vec![0.0; (to + 1) * DIM];
        let planned = median_ns(repeats, 1, || {
            plan.apply_into(black_box(ctrl.as_slice()), DIM, &mut out)
                .expect("sizes match");
            black_box(&mut out);
        });
        let once = median_ns(repeats, 1, || {
            black_box(
                black_box(&bez)
                    .elevate_degree(to - from)
                    .expect("elevation"),
            );
        });
        let elevated = bez.elevate_degree(to - from)?;
        data.f64s(&format!("elev_in_{from}_{to}.bin"), ctrl.as_slice())?;
        data.f64s(
            &format!("elev_out_{from}_{to}.bin"),
            elevated.control_points().as_slice(),
        )?;
        println!("elevate_{from}_{to}: plan {planned:.1} ns/curve, elevate_degree {once:.1}");
        results.insert(
            format!("elevate_{from}_{to}"),
            serde_json::json!({"plan": planned, "elevate_degree": once}),
        );
    }
    Ok(())
}

fn main() -> Res<()> {
    let mut args = std::env::args().skip(1);
    let dir = PathBuf::from(
        args.next()
            .ok_or("usage: peer_bench DIR [REPEATS [RESULTS [WORKLOADS]]]")?,
    );
    let repeats: usize = args.next().map_or(Ok(7), |s| s.parse())?;
    let results_name = args.next().unwrap_or_else(|| "ours.json".into());
    let only: Vec<String> = args.next().map_or_else(Vec::new, |list| {
        list.split(',')
            .filter(|w| !w.is_empty())
            .map(String::from)
            .collect()
    });
    std::fs::create_dir_all(&dir)?;
    let write = results_name == "ours.json";
    if write && !only.is_empty() {
        return Err("a workload list times only: give a results name other than ours.json".into());
    }
    let data = Data {
        dir: &dir,
        write,
        only,
    };
    let mut results = Results::new();
    if ["eval_sorted", "eval_random", "deriv1_sorted"]
        .iter()
        .any(|w| data.wants(w))
    {
        evaluation(&data, repeats, &mut results)?;
    }
    interpolation(&data, repeats, &mut results)?;
    surface(&data, repeats, &mut results)?;
    elevation(&data, repeats, &mut results)?;
    let meta = serde_json::json!({
        "degree": DEGREE, "dim": DIM, "n_ctrl": N_CTRL, "n": N, "repeats": repeats,
        "interp_sizes": INTERP_SIZES, "surface_sizes": SURFACE_SIZES, "elevations": ELEVATIONS,
        "results": results,
    });
    std::fs::write(dir.join(results_name), serde_json::to_string_pretty(&meta)?)?;
    Ok(())
}

/// Evaluation of the cubic 3-D curve at 10^6 sorted and random parameters (reference, fast
/// sequential, 2 threads pinned and unpinned) and of point and first derivative at the sorted
/// ones; writes the curve, the parameters and our results.
fn evaluation(data: &Data<'_>, repeats: usize, results: &mut Results) -> Res<()> {
    let curve = common::curve(DEGREE, N_CTRL, DIM);
    let sorted = common::sorted_params(N);
    let random = common::random_params(N);
    data.f64s("knots.bin", curve.knots().as_slice())?;
    data.f64s("ctrl.bin", curve.control_points().as_slice())?;
    data.f64s("ts_sorted.bin", &sorted)?;
    data.f64s("ts_random.bin", &random)?;

    let fast = curve.evaluator();
    let pool = common::rayon_pool(2, true);
    let free = common::rayon_pool(2, false);
    let mut out = vec![0.0; N * DIM];
    for (name, ts) in [("eval_sorted", &sorted), ("eval_random", &random)] {
        let reference = median_ns(repeats, N, || {
            curve.eval_batch(ts, &mut out).expect("in domain")
        });
        let ours = median_ns(repeats, N, || {
            fast.eval_batch(ts, &mut out).expect("in domain")
        });
        data.f64s(&format!("ours_{name}.bin"), &out)?;
        let mut parallel = |pool: &rayon::ThreadPool| {
            median_ns(repeats, N, || {
                pool.install(|| fast.par_eval_batch(ts, &mut out))
                    .expect("in domain");
            })
        };
        let (par, par_free) = (parallel(&pool), parallel(&free));
        println!(
            "{name}: reference {reference:.1} ns/pt, fast {ours:.1}, parallel(2, pinned) {par:.1}, \
             parallel(2, unpinned) {par_free:.1}"
        );
        results.insert(
            name.into(),
            serde_json::json!({"reference": reference, "fast": ours, "parallel_2": par,
                               "parallel_2_unpinned": par_free}),
        );
    }
    // first derivative (with the point) at sorted parameters
    let mut d = vec![0.0; N * 2 * DIM];
    let deriv = median_ns(repeats, N, || {
        fast.eval_derivatives_batch(&sorted, 1, &mut d)
            .expect("in domain");
    });
    let d1: Vec<f64> = d
        .chunks_exact(2 * DIM)
        .flat_map(|r| r[DIM..].to_vec())
        .collect();
    data.f64s("ours_deriv1_sorted.bin", &d1)?;
    println!("deriv1_sorted: fast {deriv:.1} ns/pt");
    results.insert("deriv1_sorted".into(), serde_json::json!({"fast": deriv}));
    Ok(())
}
