//! Our side of the peer comparison (`bench/peers/run.sh`): writes the shared workload data to a
//! directory as little-endian `f64` files and times lekalo on it, medians in ns per point, into
//! `ours.json` in the same directory. The Python script then times the peers on the same files.
//!
//! `cargo run --release --example peer_bench -- DIR [REPEATS]`

use std::path::{Path, PathBuf};
use std::time::Instant;

#[path = "../benches/common/mod.rs"]
mod common;

/// Curve of the evaluation workload: cubic, 3-D, 1000 control points.
const DEGREE: usize = 3;
const DIM: usize = 3;
const N_CTRL: usize = 1000;
/// Parameters per evaluation workload.
const N: usize = 1_000_000;

fn write_f64(dir: &Path, name: &str, v: &[f64]) -> std::io::Result<()> {
    let bytes: Vec<u8> = v.iter().flat_map(|x| x.to_le_bytes()).collect();
    std::fs::write(dir.join(name), bytes)
}

/// Median wall time of `repeats` runs of `f`, in ns per point.
fn median_ns(repeats: usize, points: usize, mut f: impl FnMut()) -> f64 {
    f(); // warm-up
    let mut times: Vec<f64> = (0..repeats)
        .map(|_| {
            let t0 = Instant::now();
            f();
            t0.elapsed().as_secs_f64()
        })
        .collect();
    times.sort_by(f64::total_cmp);
    times[times.len() / 2] * 1e9 / points as f64
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let dir = PathBuf::from(args.next().ok_or("usage: peer_bench DIR [REPEATS]")?);
    let repeats: usize = args.next().map_or(Ok(7), |s| s.parse())?;
    std::fs::create_dir_all(&dir)?;

    let curve = common::curve(DEGREE, N_CTRL, DIM);
    let sorted = common::sorted_params(N);
    let random = common::random_params(N);
    write_f64(&dir, "knots.bin", curve.knots().as_slice())?;
    write_f64(&dir, "ctrl.bin", curve.control_points().as_slice())?;
    write_f64(&dir, "ts_sorted.bin", &sorted)?;
    write_f64(&dir, "ts_random.bin", &random)?;

    let fast = curve.evaluator();
    let pool = rayon::ThreadPoolBuilder::new().num_threads(2).build()?;
    let mut out = vec![0.0; N * DIM];
    let mut results = serde_json::Map::new();
    for (name, ts) in [("eval_sorted", &sorted), ("eval_random", &random)] {
        let reference = median_ns(repeats, N, || {
            curve.eval_batch(ts, &mut out).expect("in domain")
        });
        let ours = median_ns(repeats, N, || {
            fast.eval_batch(ts, &mut out).expect("in domain")
        });
        write_f64(&dir, &format!("ours_{name}.bin"), &out)?;
        let par = median_ns(repeats, N, || {
            pool.install(|| fast.par_eval_batch(ts, &mut out))
                .expect("in domain");
        });
        println!("{name}: reference {reference:.1} ns/pt, fast {ours:.1}, parallel(2) {par:.1}");
        results.insert(
            name.into(),
            serde_json::json!({"reference": reference, "fast": ours, "parallel_2": par}),
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
    write_f64(&dir, "ours_deriv1_sorted.bin", &d1)?;
    println!("deriv1_sorted: fast {deriv:.1} ns/pt");
    results.insert("deriv1_sorted".into(), serde_json::json!({"fast": deriv}));
    let meta = serde_json::json!({
        "degree": DEGREE, "dim": DIM, "n_ctrl": N_CTRL, "n": N, "repeats": repeats,
        "results": results,
    });
    std::fs::write(dir.join("ours.json"), serde_json::to_string_pretty(&meta)?)?;
    Ok(())
}
