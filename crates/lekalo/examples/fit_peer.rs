//! Writes the fitting workloads of `benches/fit.rs` to `DIR/*.bin` (little-endian f64) and times
//! lekalo on them (median of `REPEATS` runs), printing JSON for `bench/peers/fit_peers.py`.
//!
//! Usage: `cargo run --release -p lekalo --example fit_peer -- DIR [REPEATS]`

use std::time::Instant;

use lekalo::fit::{
    fit_tolerance, least_squares, smoothing_condition, smoothing_spline,
    surface_scattered_least_squares, EndConstraints, FitData, Lambda, ToleranceOptions,
};
use lekalo::{KnotVector, PointsRef};

#[path = "../benches/fit_workloads/mod.rs"]
mod fit_workloads;
use fit_workloads as w;

fn write(dir: &str, name: &str, v: &[f64]) {
    let bytes: Vec<u8> = v.iter().flat_map(|x| x.to_le_bytes()).collect();
    std::fs::write(format!("{dir}/{name}.bin"), bytes).expect("write workload");
}

fn median_secs<T>(repeats: usize, mut f: impl FnMut() -> T) -> (f64, T) {
    let mut out = f();
    let mut times = Vec::new();
    for _ in 0..repeats {
        let t0 = Instant::now();
        out = f();
        times.push(t0.elapsed().as_secs_f64());
    }
    times.sort_by(f64::total_cmp);
    (times[times.len() / 2], out)
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let dir = args.get(1).map_or("target/fit-peers", String::as_str);
    let repeats: usize = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(5);
    std::fs::create_dir_all(dir).expect("data directory");
    let mut results = Vec::new();

    // least squares, 10^6 points, 1000 cubic control points
    let n = 1_000_000;
    let (x, y) = w::noisy_function(n, 1);
    write(dir, "lsq_x", &x);
    write(dir, "lsq_y", &y);
    let (lo, hi) = (x[0], x[n - 1]);
    let t = w::uniform_knots(lo, hi, 1000);
    write(dir, "lsq_t", &t);
    let kv = KnotVector::new(t).expect("knots");
    let data = FitData::new(PointsRef::from_flat(1, &y).expect("points"), &x).expect("data");
    let (secs, fit) = median_secs(repeats, || {
        least_squares(&data, 3, &kv, &EndConstraints::none()).expect("fit")
    });
    write(dir, "lsq_c_lekalo", fit.curve.control_points().as_slice());
    results.push(format!(
        "\"lsq\": {{\"secs\": {secs}, \"rss\": {}}}",
        fit.report.weighted_rss
    ));

    // smoothing with GCV, 10^5 points
    let n = 100_000;
    let (x, y) = w::noisy_function(n, 2);
    write(dir, "smooth_x", &x);
    write(dir, "smooth_y", &y);
    let data = FitData::new(PointsRef::from_flat(1, &y).expect("points"), &x).expect("data");
    let (secs, fit) = median_secs(repeats, || {
        smoothing_spline(&data, Lambda::Gcv).expect("fit")
    });
    results.push(format!(
        "\"gcv\": {{\"secs\": {secs}, \"lambda\": {}, \"rss\": {}}}",
        fit.report.lambda.unwrap_or(f64::NAN),
        fit.report.weighted_rss
    ));
    let (secs, fit) = median_secs(repeats, || {
        smoothing_spline(&data, Lambda::Given(1e-6)).expect("fit")
    });
    results.push(format!(
        "\"smooth_lam\": {{\"secs\": {secs}, \"lambda\": 1e-6, \"rss\": {}}}",
        fit.report.weighted_rss
    ));

    // smoothing condition, same data
    let s = n as f64 * w::NOISE * w::NOISE;
    let (secs, fit) = median_secs(repeats, || smoothing_condition(&data, 3, s).expect("fit"));
    results.push(format!(
        "\"splrep\": {{\"secs\": {secs}, \"s\": {s}, \"rss\": {}, \"n_knots\": {}}}",
        fit.report.weighted_rss,
        fit.curve.knots().len()
    ));

    // tolerance fit, 10^5 points of a spiral
    let q = w::spiral(n, 3);
    write(dir, "tol_q", &q);
    let (secs, fit) = median_secs(repeats.min(3), || {
        fit_tolerance(
            PointsRef::from_flat(2, &q).expect("points"),
            &ToleranceOptions::new(3, 1e-3),
        )
        .expect("fit")
    });
    results.push(format!(
        "\"tolerance\": {{\"secs\": {secs}, \"tol\": 1e-3, \"max_deviation\": {}, \"n_ctrl\": {}}}",
        fit.max_deviation,
        fit.curve.control_points().len()
    ));

    // scattered surface, 10^5 rows, 30 x 30 cubic net
    let rows = w::scattered(n, 4);
    write(dir, "surf_rows", &rows);
    let t = w::uniform_knots(0.0, 1.0, 30);
    write(dir, "surf_t", &t);
    let ku = KnotVector::new(t).expect("knots");
    let (secs, fit) = median_secs(repeats, || {
        surface_scattered_least_squares(
            PointsRef::from_flat(3, &rows).expect("rows"),
            None,
            (3, 3),
            (&ku, &ku),
            0.0,
        )
        .expect("fit")
    });
    write(
        dir,
        "surf_c_lekalo",
        fit.surface.control_points().as_slice(),
    );
    results.push(format!(
        "\"surface\": {{\"secs\": {secs}, \"rss\": {}}}",
        fit.weighted_rss
    ));

    println!("{{{}}}", results.join(", "));
}
