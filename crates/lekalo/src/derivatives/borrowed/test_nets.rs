//! Knot vectors and nets of the property tests of the borrowed surface and tensor paths.

/// Clamped knots of degree `p` for `n` control points on `[0, n − p]`, interior knots from
/// `gaps` (a zero gap repeats a knot, at most `p` times).
pub(super) fn knots(p: usize, n: usize, gaps: &[f64]) -> Vec<f64> {
    let mut k = vec![0.0; p + 1];
    let mut x = 0.0;
    for j in 0..n - p - 1 {
        let run = k.iter().rev().take_while(|&&v| v == x).count();
        let g = gaps[j % gaps.len()];
        x += if g == 0.0 && run >= p { 0.5 } else { g };
        k.push(x);
    }
    x += 1.0;
    k.extend(vec![x; p + 1]);
    k
}

/// `len` smooth pseudo-random numbers of size about 3, different for each `seed`.
#[allow(clippy::cast_precision_loss)]
pub(super) fn net(len: usize, seed: f64) -> Vec<f64> {
    (0..len)
        .map(|i| (i as f64 * 0.7 + seed).sin() * 3.0)
        .collect()
}
