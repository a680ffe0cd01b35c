//! The fixed-size tensor kernels (scalar values in two or three directions of one degree,
//! `tensor/fixed.rs`) on a deterministic batch, for counting their instructions:
//!
//! `valgrind --tool=callgrind target/release/examples/tensor_fixed_count [2|3] [degree] [points]`
//!
//! evaluates a scalar tensor-product spline of the given number of directions (default 2) and
//! degree (default 3) on a 24-per-direction net at `points` (default 200 000) scattered points
//! with `eval_batch` (one thread), and prints a checksum of the values' bits, the same for two
//! builds whose kernels compute the same bits.

use lekalo::{Points, TensorBSpline};

fn main() -> Result<(), lekalo::Error> {
    let args: Vec<usize> = std::env::args()
        .skip(1)
        .map(|a| a.parse().unwrap_or(0))
        .collect();
    let dirs = args
        .first()
        .copied()
        .filter(|&d| d == 2 || d == 3)
        .unwrap_or(2);
    let degree = args
        .get(1)
        .copied()
        .filter(|&p| (1..=5).contains(&p))
        .unwrap_or(3);
    let points = args.get(2).copied().filter(|&n| n > 0).unwrap_or(200_000);
    let n = 24;
    // clamped knots with uneven interior spacing
    let mut knots = vec![0.0; degree + 1];
    for i in 1..n - degree {
        let u = i as f64 / (n - degree) as f64;
        knots.push(u + 0.1 * u * (1.0 - u));
    }
    knots.extend(vec![1.0; degree + 1]);
    let size = n.pow(u32::try_from(dirs).unwrap_or(2));
    let net: Vec<f64> = (0..size).map(|k| (0.37 * k as f64).sin()).collect();
    let spline = TensorBSpline::new(
        vec![degree; dirs],
        vec![knots; dirs],
        Points::from_flat(1, net)?,
    )?;
    // a low-discrepancy sequence in the unit cube (additive recurrence), deterministic
    let alpha = [
        0.754_877_666_246_692_7,
        0.569_840_290_998_053_3,
        0.438_579_574_941_402_8,
    ];
    let xs: Vec<f64> = (0..points)
        .flat_map(|k| (0..dirs).map(move |a| (0.5 + alpha[a] * k as f64).fract()))
        .collect();
    let mut out = vec![0.0; points];
    spline.eval_batch(&xs, None, &mut out)?;
    let sum = out.iter().fold(0u64, |h, v| h.rotate_left(5) ^ v.to_bits());
    println!("{dirs} directions, degree {degree}, {points} points: checksum {sum:016x}");
    Ok(())
}
