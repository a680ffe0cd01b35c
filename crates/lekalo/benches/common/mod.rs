//! Workloads shared by the criterion benches and `examples/peer_bench.rs`: deterministic data
//! (a fixed linear congruential generator, no randomness), so that every run and every peer
//! sees the same curves and parameters.
#![allow(dead_code)]

use lekalo::{BSplineCurve, KnotVector, NurbsCurve, Points};

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

/// Control points of a smooth random walk in `dim` dimensions (coordinates of order 10).
pub(crate) fn walk(n: usize, dim: usize, seed: u64) -> Points {
    let mut rng = Lcg::new(seed);
    let mut p = vec![0.0; dim];
    let mut data = Vec::with_capacity(n * dim);
    for _ in 0..n {
        for x in &mut p {
            *x += rng.next_f64() - 0.5;
        }
        data.extend_from_slice(&p);
    }
    Points::from_flat(dim, data).expect("finite walk")
}

/// The evaluation workload of the benchmarks and the peer comparison: a B-spline of `degree` with `n_ctrl` control points in
/// `dim` dimensions on clamped uniform knots over `[0, 1]`.
pub(crate) fn curve(degree: usize, n_ctrl: usize, dim: usize) -> BSplineCurve {
    let knots = KnotVector::clamped_uniform(degree, n_ctrl).expect("enough control points");
    BSplineCurve::from_knot_vector(degree, knots, walk(n_ctrl, dim, 7)).expect("valid curve")
}

/// A NURBS version of [`curve`] with weights in `[0.5, 1.5)`.
pub(crate) fn nurbs(degree: usize, n_ctrl: usize, dim: usize) -> NurbsCurve {
    let c = curve(degree, n_ctrl, dim);
    let mut rng = Lcg::new(11);
    let w: Vec<f64> = (0..n_ctrl).map(|_| 0.5 + rng.next_f64()).collect();
    NurbsCurve::new(
        degree,
        c.knots().as_slice().to_vec(),
        c.control_points().clone(),
        w,
    )
    .expect("valid NURBS")
}

/// `n` equally spaced parameters over `[0, 1]`.
pub(crate) fn sorted_params(n: usize) -> Vec<f64> {
    (0..n).map(|i| i as f64 / (n - 1) as f64).collect()
}

/// `n` uniformly distributed parameters in `[0, 1)`, in random order.
pub(crate) fn random_params(n: usize) -> Vec<f64> {
    let mut rng = Lcg::new(12_345);
    (0..n).map(|_| rng.next_f64()).collect()
}

/// `n` points of a wobbly 3-D helix, unevenly spaced: the curve interpolation workload.
pub(crate) fn helix(n: usize) -> Points {
    let mut data = Vec::with_capacity(3 * n);
    for i in 0..n {
        let s = i as f64 * 0.01;
        let w = s + 0.003 * (7.0 * s).sin();
        data.extend([w.cos(), w.sin(), 0.1 * w + 0.01 * (3.0 * w).cos()]);
    }
    Points::from_flat(3, data).expect("finite helix")
}

/// An `n × n` grid of 3-D points on a smooth, slightly sheared surface, point `(k, l)` at
/// `(k·n + l)·3`: the surface interpolation workload.
pub(crate) fn grid(n: usize) -> Points {
    let mut data = Vec::with_capacity(n * n * 3);
    for k in 0..n {
        for l in 0..n {
            let (x, y) = (k as f64 / n as f64, l as f64 / n as f64);
            data.extend([x + 0.01 * y, y, (3.0 * x).sin() * (2.0 * y).cos()]);
        }
    }
    Points::from_flat(3, data).expect("finite grid")
}

/// A rayon pool of `threads` workers, worker `i` pinned to the `i`-th processor the process may
/// run on (`core_affinity`), or left to the scheduler if `pinned` is false.
///
/// Why pin: on the 2-vCPU CI machine, Linux sometimes queues both workers on one processor (the
/// one that woke the second worker, while the caller's processor was still busy) and, as both
/// are cache-hot, does not move one for milliseconds, so a 10 ms batch runs at one thread's
/// speed. Pinned workers cannot share a processor; `docs/performance/kernels.md` ("Parallel
/// evaluation and thread placement") has the measurements of both pools.
pub(crate) fn rayon_pool(threads: usize, pinned: bool) -> rayon::ThreadPool {
    let cores = if pinned {
        core_affinity::get_core_ids().unwrap_or_default()
    } else {
        Vec::new()
    };
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .start_handler(move |i| {
            if let Some(&core) = cores.get(i % cores.len().max(1)) {
                // best effort: an unpinned worker is only slower
                let _ = core_affinity::set_for_current(core);
            }
        })
        .build()
        .expect("a rayon pool")
}
