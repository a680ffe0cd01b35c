//! Timing of cubic global curve interpolation and bicubic surface interpolation.
//!
//! `cargo run --release --example interp_timing -- [n ...]` prints, for each `n`, the CPU time
//! per point (from `/proc/self/schedstat`, so other load on the machine matters less than with
//! wall-clock time), the wall time and the peak resident memory added by the call relative to
//! the input's size (`VmHWM` of `/proc/self/status`; run one `n` per process for a clean figure).
//! `surface` as an argument times the 400×400 bicubic grid instead.

use std::time::Instant;

use lekalo::{CurveInterpolation, InterpolationWorkspace, Parametrization, SurfaceInterpolation};

#[path = "../benches/common/mod.rs"]
mod common;

/// CPU time of this thread in nanoseconds (0 where `/proc` is unavailable).
fn cpu_ns() -> u64 {
    std::fs::read_to_string("/proc/thread-self/schedstat")
        .ok()
        .and_then(|s| s.split_whitespace().next().and_then(|v| v.parse().ok()))
        .unwrap_or(0)
}

/// A `/proc/self/status` field in kB (0 where unavailable).
fn status_kb(field: &str) -> u64 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with(field))
                .and_then(|l| l.split_whitespace().nth(1).and_then(|v| v.parse().ok()))
        })
        .unwrap_or(0)
}

/// Minor page faults of this process so far (`/proc/self/stat` field 10; 0 where unavailable).
fn minor_faults() -> u64 {
    std::fs::read_to_string("/proc/self/stat")
        .ok()
        .and_then(|s| {
            // the fields after the parenthesised command name; minflt is the 10th field
            let rest = s.rsplit_once(')')?.1;
            rest.split_whitespace().nth(7).and_then(|v| v.parse().ok())
        })
        .unwrap_or(0)
}

fn time_curve(n: usize, reps: usize) {
    let q = common::helix(n);
    let base_kb = status_kb("VmRSS:");
    let mut best_wall = f64::MAX;
    let f0 = minor_faults();
    let c0 = cpu_ns();
    for _ in 0..reps {
        let w0 = Instant::now();
        let c = CurveInterpolation::new(3)
            .interpolate(q.as_view())
            .expect("interpolation");
        let wall = w0.elapsed().as_secs_f64();
        std::hint::black_box(&c);
        drop(c);
        best_wall = best_wall.min(wall);
    }
    let mean_cpu = (cpu_ns() - c0) as f64 / reps as f64;
    let faults = (minor_faults() - f0) as f64 / reps as f64;
    let peak_kb = status_kb("VmHWM:");
    let input_kb = (n * 3 * 8) as f64 / 1024.0;
    println!(
        "curve n = {n:>8}: {:>6.1} ns/point CPU (mean), {:>6.1} ns/point wall (min), peak above input {:.2}× input, {faults:.0} page faults a call",
        mean_cpu / n as f64,
        best_wall * 1e9 / n as f64,
        (peak_kb.saturating_sub(base_kb)) as f64 / input_kb
    );
    // the same with a reused workspace (no fresh memory after the first call)
    let interp = CurveInterpolation::new(3);
    let mut ws = InterpolationWorkspace::new();
    let mut best_wall = f64::MAX;
    let c0 = cpu_ns();
    for _ in 0..reps {
        let w0 = Instant::now();
        let c = interp
            .interpolate_with(q.as_view(), &mut ws)
            .expect("interpolation");
        let wall = w0.elapsed().as_secs_f64();
        std::hint::black_box(&c);
        ws.recycle(c);
        best_wall = best_wall.min(wall);
    }
    let mean_cpu = (cpu_ns() - c0) as f64 / reps as f64;
    println!(
        "  with a workspace: {:>6.1} ns/point CPU (mean), {:>6.1} ns/point wall (min)",
        mean_cpu / n as f64,
        best_wall * 1e9 / n as f64,
    );
}

fn time_surface(n: usize, reps: usize) {
    let g = common::grid(n);
    let mut best_wall = f64::MAX;
    let f0 = minor_faults();
    let c0 = cpu_ns();
    for _ in 0..reps {
        let w0 = Instant::now();
        let s = SurfaceInterpolation::new(3, 3)
            .parametrization(Parametrization::ChordLength)
            .interpolate(g.as_view(), n, n)
            .expect("surface");
        let wall = w0.elapsed().as_secs_f64();
        best_wall = best_wall.min(wall);
        std::hint::black_box(&s);
    }
    let mean_cpu = (cpu_ns() - c0) as f64 / reps as f64;
    let faults = (minor_faults() - f0) as f64 / reps as f64;
    println!(
        "surface {n}×{n}: {:.2} ms CPU (mean), {:.2} ms wall (min), {faults:.0} page faults a call",
        mean_cpu * 1e-6,
        best_wall * 1e3
    );
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if args.iter().any(|a| a == "surface") {
        time_surface(400, 40);
        return;
    }
    let sizes: Vec<usize> = if args.is_empty() {
        vec![1_000, 10_000, 100_000, 1_000_000]
    } else {
        args.iter().filter_map(|a| a.parse().ok()).collect()
    };
    for n in sizes {
        let reps = (30_000_000 / n).clamp(10, 3000);
        time_curve(n, reps);
    }
}
