//! Fitting workloads shared by `benches/fit.rs` and `examples/fit_peer.rs`: deterministic data
//! (a fixed linear congruential generator), the same files for SciPy in
//! `bench/peers/fit_peers.py`.
#![allow(dead_code)]

/// Knuth's MMIX linear congruential generator: deterministic uniform numbers in `[0, 1)`.
pub(crate) struct Lcg(u64);

impl Lcg {
    pub(crate) fn new(seed: u64) -> Self {
        Lcg(seed)
    }

    pub(crate) fn next_f64(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// Standard deviation of the noise of every workload.
pub(crate) const NOISE: f64 = 0.05;

/// `n` noisy samples `(x_k, y_k)` of `sin(20 x)·(1 + x)` on sorted, jittered `x` in `[0, 1]`.
pub(crate) fn noisy_function(n: usize, seed: u64) -> (Vec<f64>, Vec<f64>) {
    let mut rng = Lcg::new(seed);
    let x: Vec<f64> = (0..n)
        .map(|k| (k as f64 + 0.5 * rng.next_f64()) / n as f64)
        .collect();
    // uniform noise of standard deviation NOISE
    let y = x
        .iter()
        .map(|t| (20.0 * t).sin() * (1.0 + t) + NOISE * 12f64.sqrt() * (rng.next_f64() - 0.5))
        .collect();
    (x, y)
}

/// Clamped uniform cubic knots on `[lo, hi]` for `n_ctrl` control points.
pub(crate) fn uniform_knots(lo: f64, hi: f64, n_ctrl: usize) -> Vec<f64> {
    let pieces = n_ctrl - 3;
    let mut k = vec![lo; 4];
    k.extend((1..pieces).map(|j| lo + (hi - lo) * j as f64 / pieces as f64));
    k.extend([hi; 4]);
    k
}

/// `n` points near a plane spiral (2-D, coordinates of order 1), flat `x0 y0 x1 y1 …`.
pub(crate) fn spiral(n: usize, seed: u64) -> Vec<f64> {
    let mut rng = Lcg::new(seed);
    (0..n)
        .flat_map(|k| {
            let t = 6.0 * k as f64 / (n - 1) as f64;
            let r = 1.0 + 0.2 * t;
            let e = 1e-4 * (rng.next_f64() - 0.5);
            [r * t.cos() + e, r * t.sin() - e]
        })
        .collect()
}

/// `n` scattered rows `(u, v, z)` on `[0, 1]²`, `z = sin(3u) cos(2v) + noise`.
pub(crate) fn scattered(n: usize, seed: u64) -> Vec<f64> {
    let mut rng = Lcg::new(seed);
    (0..n)
        .flat_map(|_| {
            let (u, v) = (rng.next_f64(), rng.next_f64());
            let z =
                (3.0 * u).sin() * (2.0 * v).cos() + NOISE * 12f64.sqrt() * (rng.next_f64() - 0.5);
            [u, v, z]
        })
        .collect()
}
