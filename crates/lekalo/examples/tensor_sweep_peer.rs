//! Cubic interpolation of an `n³` grid of scalars (default 128³, SciPy's not-a-knot knots in
//! every direction): lekalo's [`TensorInterpolation`] beside a hand-written sweep of the same
//! banded solves, side by side in one process.
//!
//! `RAYON_NUM_THREADS=1 cargo run --release -p lekalo --example tensor_sweep_peer -- [n] [repeats]`
//!
//! The hand-written sweep is the textbook one (`docs/theory/tensor.md#interpolation-on-grids`):
//! per direction the collocation matrix of the basis at the grid's coordinates, factored by
//! Gaussian elimination without pivoting (it is totally positive: de Boor, *A Practical Guide to
//! Splines*, XIII), then for every block of the grid along that direction, the last direction
//! first, forward and back substitution on whole rows of the block (each row a contiguous run
//! of the faster directions, so every operation is an `axpy` the compiler vectorises), in
//! place. Nothing of lekalo is used but the basis values that build the matrices, outside the
//! timed sweep.
//!
//! Printed: the CPU time of the whole process per construction (`/proc/self/stat`, user plus
//! system, so every thread counts and the machine's other load counts less than in wall
//! time) and the wall time, each the median of `repeats` alternating pairs, their ratio, and
//! the largest relative difference of the two nets.

use std::time::Instant;

use lekalo::{basis::basis_functions, KnotVector, PointsRef, TensorInterpolation};

/// User plus system CPU time of this process in seconds (`/proc/self/stat` fields 14 and 15).
fn cpu_s() -> f64 {
    let s = std::fs::read_to_string("/proc/self/stat").unwrap_or_default();
    let rest = s.rsplit_once(')').map_or("", |r| r.1);
    let f: Vec<f64> = rest
        .split_whitespace()
        .skip(11)
        .take(2)
        .filter_map(|v| v.parse().ok())
        .collect();
    // the kernel's clock tick, USER_HZ, is 100 on Linux
    f.iter().sum::<f64>() / 100.0
}

/// Uneven coordinates on [0, 1]: the uniform grid with its interior nodes moved by up to 30 %
/// of a spacing (a fixed linear congruential sequence).
fn axis(n: usize, seed: u64) -> Vec<f64> {
    let mut state = seed;
    (0..n)
        .map(|i| {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            let jitter = ((state >> 11) as f64 / (1u64 << 53) as f64 - 0.5) * 0.6;
            let x = i as f64 / (n - 1) as f64;
            if i == 0 || i == n - 1 {
                x
            } else {
                x + jitter / (n - 1) as f64
            }
        })
        .collect()
}

/// The not-a-knot knots of cubic interpolation at `x` (SciPy's `make_interp_spline(k=3)`).
fn not_a_knot(x: &[f64]) -> KnotVector {
    let n = x.len();
    let mut t = vec![x[0]; 4];
    t.extend_from_slice(&x[2..n - 2]);
    t.extend(vec![x[n - 1]; 4]);
    KnotVector::new(t).expect("knots")
}

/// The LU factors (no pivoting) of the collocation matrix of `knots` at `x`, kept as dense rows
/// with the bandwidths below and above the diagonal.
struct Lu {
    a: Vec<Vec<f64>>,
    below: usize,
    above: usize,
}

impl Lu {
    fn new(knots: &KnotVector, x: &[f64]) -> Lu {
        let n = x.len();
        let mut a = vec![vec![0.0; n]; n];
        for (row, &t) in a.iter_mut().zip(x) {
            let (span, b) = basis_functions(knots, 3, t).expect("basis");
            row[span - 3..=span].copy_from_slice(&b);
        }
        let (mut below, mut above) = (0, 0);
        for (i, row) in a.iter().enumerate() {
            for (j, &v) in row.iter().enumerate() {
                if v != 0.0 {
                    below = below.max(i.saturating_sub(j));
                    above = above.max(j.saturating_sub(i));
                }
            }
        }
        // elimination within the band (no fill outside it without pivoting)
        for k in 0..n {
            for i in k + 1..(k + below + 1).min(n) {
                let l = a[i][k] / a[k][k];
                a[i][k] = l;
                for j in k + 1..(k + above + 1).min(n) {
                    let u = a[k][j];
                    a[i][j] -= l * u;
                }
            }
        }
        Lu { a, below, above }
    }

    /// Solves in place for the `m` rows of `inner` numbers each of `block`.
    fn solve(&self, block: &mut [f64], inner: usize) {
        let m = self.a.len();
        for i in 1..m {
            let (done, rest) = block.split_at_mut(i * inner);
            let row = &mut rest[..inner];
            for j in i.saturating_sub(self.below)..i {
                let l = self.a[i][j];
                for (r, &p) in row.iter_mut().zip(&done[j * inner..(j + 1) * inner]) {
                    *r -= l * p;
                }
            }
        }
        for i in (0..m).rev() {
            let (head, tail) = block.split_at_mut((i + 1) * inner);
            let row = &mut head[i * inner..];
            for j in i + 1..(i + self.above + 1).min(m) {
                let u = self.a[i][j];
                let k = j - i - 1;
                for (r, &p) in row.iter_mut().zip(&tail[k * inner..(k + 1) * inner]) {
                    *r -= u * p;
                }
            }
            let d = 1.0 / self.a[i][i];
            row.iter_mut().for_each(|r| *r *= d);
        }
    }
}

/// The hand-written sweep: a copy of the values solved in place along each direction.
fn hand_sweep(values: &[f64], shape: &[usize], lus: &[Lu]) -> Vec<f64> {
    let mut c = values.to_vec();
    for a in (0..shape.len()).rev() {
        let inner: usize = shape[a + 1..].iter().product();
        for block in c.chunks_exact_mut(shape[a] * inner) {
            lus[a].solve(block, inner);
        }
    }
    c
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn main() {
    let args: Vec<usize> = std::env::args()
        .skip(1)
        .filter_map(|a| a.parse().ok())
        .collect();
    let n = args.first().copied().unwrap_or(128);
    let repeats = args.get(1).copied().unwrap_or(7);
    let axes: Vec<Vec<f64>> = (0..3).map(|a| axis(n, 7 + a)).collect();
    let mut values = Vec::with_capacity(n * n * n);
    for &x in &axes[0] {
        for &y in &axes[1] {
            for &z in &axes[2] {
                values.push((3.0 * x).cos() * (3.0 * y + 1.0).cos() * (3.0 * z + 2.0).cos() + 10.0);
            }
        }
    }
    let knots: Vec<KnotVector> = axes.iter().map(|x| not_a_knot(x)).collect();
    let refs: Vec<&[f64]> = axes.iter().map(Vec::as_slice).collect();
    let lekalo = || {
        TensorInterpolation::new(vec![3; 3])
            .knot_vectors(knots.iter().cloned().map(Some).collect())
            .interpolate_at(&refs, PointsRef::from_flat(1, &values).expect("values"))
            .expect("interpolation")
    };
    let shape = [n; 3];
    // the hand-written side's factorisations are made once, outside its timing
    let lus: Vec<Lu> = axes
        .iter()
        .zip(&knots)
        .map(|(x, k)| Lu::new(k, x))
        .collect();
    let ours = lekalo();
    let theirs = hand_sweep(&values, &shape, &lus);
    let scale = theirs.iter().fold(0.0f64, |m, c| m.max(c.abs()));
    let diff = ours
        .control_points()
        .as_slice()
        .iter()
        .zip(&theirs)
        .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()))
        / scale;
    let time = |f: &dyn Fn()| {
        let (c0, w0) = (cpu_s(), Instant::now());
        // enough calls for the 10 ms clock tick of the CPU time
        let mut calls = 0;
        while cpu_s() - c0 < 0.3 || calls < 2 {
            f();
            calls += 1;
        }
        (
            (cpu_s() - c0) / f64::from(calls),
            w0.elapsed().as_secs_f64() / f64::from(calls),
        )
    };
    let (mut cpu, mut wall) = ([Vec::new(), Vec::new()], [Vec::new(), Vec::new()]);
    for _ in 0..repeats {
        let (c, w) = time(&|| {
            std::hint::black_box(lekalo());
        });
        cpu[0].push(c);
        wall[0].push(w);
        let (c, w) = time(&|| {
            std::hint::black_box(hand_sweep(&values, &shape, &lus));
        });
        cpu[1].push(c);
        wall[1].push(w);
    }
    let [c_ours, c_hand] = cpu.map(median);
    let [w_ours, w_hand] = wall.map(median);
    println!(
        "{n}^3 cubic interpolation, median of {repeats}: lekalo {:.1} ms CPU ({:.1} ms wall), \
         hand-written sweep {:.1} ms CPU ({:.1} ms wall); lekalo / hand: {:.2}x CPU, {:.2}x wall; \
         nets within {diff:.1e} relative",
        c_ours * 1e3,
        w_ours * 1e3,
        c_hand * 1e3,
        w_hand * 1e3,
        c_ours / c_hand,
        w_ours / w_hand
    );
}
