//! Times shape-constrained fits at thousands of coefficients, where the polish's active face is
//! degenerate (flat stretches of a monotone fit to noise keep value, slope and curvature rows at
//! once): the time after the pass over the data, as the number of coefficients grows.
//!
//! Usage: `cargo run --release -p lekalo --example shape_scale -- lsq POINTS COEFFICIENTS` (an
//! increasing cubic least-squares fit) or `... -- smooth POINTS LAMBDA` (an increasing cubic
//! smoothing spline, one coefficient per point plus two). Prints one JSON line.

use std::time::Instant;

use lekalo::fit::{
    constrained_least_squares, constrained_smoothing_spline, least_squares, shape_violations,
    EndConstraints, FitData, Lambda, Shape, ShapeConstraints,
};
use lekalo::{KnotVector, PointsRef};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let usage = "usage: shape_scale lsq POINTS COEFFICIENTS | smooth POINTS (LAMBDA | gcv)";
    let mode = args.get(1).expect(usage).as_str();
    let n: usize = args.get(2).expect(usage).parse().expect(usage);
    let x: Vec<f64> = (0..n).map(|k| k as f64 / (n - 1) as f64).collect();
    // a rising wave with dips and deterministic pseudo-noise: kept increasing, the fit is flat
    // on many stretches
    let y: Vec<f64> = x
        .iter()
        .enumerate()
        .map(|(k, &t)| {
            t + 0.2 * (25.0 * t).sin() + 0.05 * (((k * 7919) % 1009) as f64 / 504.5 - 1.0)
        })
        .collect();
    let data = FitData::new(PointsRef::from_flat(1, &y).expect("points"), &x).expect("data");
    let cons = ShapeConstraints::new().with(Shape::Increasing);
    let (label, free_s, shape_s, fit) = match mode {
        "lsq" => {
            let m: usize = args.get(3).expect(usage).parse().expect(usage);
            let kv = KnotVector::clamped_uniform(3, m).expect("knots");
            let t0 = Instant::now();
            least_squares(&data, 3, &kv, &EndConstraints::none()).expect("free fit");
            let free_s = t0.elapsed().as_secs_f64();
            let t0 = Instant::now();
            let fit = constrained_least_squares(&data, 3, &kv, &cons).expect("fit");
            (
                format!("lsq {n} points {m} coefficients"),
                free_s,
                t0.elapsed().as_secs_f64(),
                fit,
            )
        }
        "smooth" => {
            let lam = match args.get(3).expect(usage).as_str() {
                "gcv" => Lambda::Gcv,
                given => Lambda::Given(given.parse().expect(usage)),
            };
            let t0 = Instant::now();
            let fit = constrained_smoothing_spline(&data, lam, &cons).expect("fit");
            (
                format!("smooth {n} points lambda {lam:?}"),
                0.0,
                t0.elapsed().as_secs_f64(),
                fit,
            )
        }
        _ => panic!("{usage}"),
    };
    let v = shape_violations(&fit.curve, &cons).expect("check");
    println!(
        "{{\"case\": \"{label}\", \"coefficients\": {}, \"unconstrained_s\": {free_s:.4}, \
         \"constrained_s\": {shape_s:.4}, \"violation\": {:e}, \"weighted_rss\": {:.12e}}}",
        fit.curve.control_points().len(),
        v[0],
        fit.report.weighted_rss
    );
}
