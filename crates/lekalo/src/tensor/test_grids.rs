//! Grids for the tests of the grid fits (`grid_smoothing.rs`, `grid_penalized.rs`).

/// `m` coordinates on `[0, 1]`, warped by `warp` (not equally spaced for `warp ≠ 0`).
pub(super) fn axis(m: usize, warp: f64) -> Vec<f64> {
    (0..m)
        .map(|i| {
            let t = i as f64 / (m - 1) as f64;
            t + warp * t * (1.0 - t)
        })
        .collect()
}

/// `f` at every node of the grid `xs`, the last direction fastest.
pub(super) fn sample(xs: &[&[f64]], f: impl Fn(&[f64]) -> f64) -> Vec<f64> {
    let total: usize = xs.iter().map(|x| x.len()).product();
    let mut out = Vec::with_capacity(total);
    let mut index = vec![0usize; xs.len()];
    for _ in 0..total {
        let p: Vec<f64> = index.iter().zip(xs).map(|(&i, x)| x[i]).collect();
        out.push(f(&p));
        for a in (0..xs.len()).rev() {
            index[a] += 1;
            if index[a] < xs[a].len() {
                break;
            }
            index[a] = 0;
        }
    }
    out
}
