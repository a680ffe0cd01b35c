//! The cell order of a large batch of points: the points grouped by the cell of a coarse grid
//! over the domain in which they lie (the first direction slowest, as the net), by a counting
//! sort in `O(points + cells)` (Knuth, *TAOCP* vol. 3, §5.2, "distribution counting"; no
//! comparison sort), so that a batch evaluated in that order reads the net a neighbourhood at
//! a time. `docs/theory/tensor.md#tensor-product-splines`, "Large batches in cell order".
//!
//! The order is kept as the position of every point in it (`position`) and its inverse
//! (`point`), so that the points are gathered into the cell order and the values gathered back
//! into the caller's order, both in parallel with no write shared between threads.

use rayon::prelude::*;

/// Points per cell aimed at (fewer cells for smaller batches: the counting costs
/// `O(points + cells)` and a cell of a few points gains nothing from its neighbours).
const POINTS_PER_CELL: usize = 16;
/// Most cells of the grid (their counters, 4 bytes each, stay in the second-level cache).
pub(super) const MAX_CELLS: usize = 1 << 15;
/// Points per parallel task of the key and gather passes.
const CHUNK: usize = 1 << 13;

/// The cells per direction of the grid of a batch of `points` points in `n` directions: the
/// largest `b ≥ 2` with `b^n ≤ min(points / POINTS_PER_CELL, MAX_CELLS)` (2 if none).
pub(super) fn bins_per_direction(points: usize, n: usize) -> usize {
    let cells = (points / POINTS_PER_CELL).min(MAX_CELLS);
    let fits = |b: usize| {
        let mut total = 1usize;
        for _ in 0..n {
            total = total.saturating_mul(b);
        }
        total <= cells
    };
    let mut b = 2;
    while fits(b + 1) {
        b += 1;
    }
    b
}

/// A permutation of the points of a batch into cell order.
#[derive(Debug)]
pub(super) struct CellOrder {
    /// `position[k]`: where point `k` stands in the cell order.
    position: Vec<u32>,
    /// `point[i]`: the point at position `i` of the cell order (the inverse of `position`).
    point: Vec<u32>,
}

impl CellOrder {
    /// The cell order of the points `xs` (`n` numbers each, fewer than `2^32` points) on the
    /// grid of `bins` cells per direction over `domains` (`(lo, hi)`, `lo < hi`, per direction).
    /// Cell of a coordinate `t`: `⌊(t − lo)·bins/(hi − lo)⌋` clamped to `0..bins`; a NaN
    /// coordinate goes to cell 0 (any cell would do: the order changes only the order of the
    /// work). Points of one cell keep their order (the sort is stable). Three passes: the cells
    /// in parallel, their counts, then each point at the next free position of its cell.
    pub(super) fn new(xs: &[f64], n: usize, domains: &[(f64, f64)], bins: usize) -> Self {
        let points = xs.len() / n;
        debug_assert!(u32::try_from(points).is_ok(), "fewer than 2^32 points");
        let scales: Vec<(f64, f64)> = domains
            .iter()
            .map(|&(lo, hi)| (lo, bins as f64 / (hi - lo)))
            .collect();
        let top = (bins - 1) as f64;
        let mut position = vec![0u32; points];
        position
            .par_chunks_mut(CHUNK)
            .zip(xs.par_chunks(CHUNK * n))
            .for_each(|(cells, x)| {
                for (c, x) in cells.iter_mut().zip(x.chunks_exact(n)) {
                    let mut key = 0usize;
                    for (&t, &(lo, scale)) in x.iter().zip(&scales) {
                        // a number in [0, bins − 1] (NaN saturates to 0), truncated
                        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
                        let cell = ((t - lo) * scale).clamp(0.0, top) as usize;
                        key = key * bins + cell;
                    }
                    // key < bins^n ≤ MAX_CELLS
                    #[allow(clippy::cast_possible_truncation)]
                    let key = key as u32;
                    *c = key;
                }
            });
        // the points of every cell, then the first position of each cell (prefix sums)
        let cells = (0..n).fold(1usize, |acc, _| acc * bins);
        let mut next = vec![0u32; cells];
        for &c in &position {
            next[c as usize] += 1;
        }
        let mut sum = 0u32;
        for s in &mut next {
            let count = *s;
            *s = sum;
            sum += count;
        }
        // each point at the next free position of its cell, in the order of the points
        let mut point = vec![0u32; points];
        for (k, p) in position.iter_mut().enumerate() {
            let slot = &mut next[*p as usize];
            *p = *slot;
            *slot += 1;
            // k < points < 2^32
            #[allow(clippy::cast_possible_truncation)]
            let k = k as u32;
            point[*p as usize] = k;
        }
        CellOrder { position, point }
    }

    /// The points `xs` (`n` numbers each) in cell order into `sorted`, in parallel.
    pub(super) fn gather(&self, xs: &[f64], n: usize, sorted: &mut [f64]) {
        match n {
            2 => self.gather_fixed::<2>(xs, sorted),
            3 => self.gather_fixed::<3>(xs, sorted),
            _ => sorted
                .par_chunks_mut(CHUNK * n)
                .zip(self.point.par_chunks(CHUNK))
                .for_each(|(s, ks)| {
                    for (s, &k) in s.chunks_exact_mut(n).zip(ks) {
                        let k = k as usize;
                        s.copy_from_slice(&xs[k * n..(k + 1) * n]);
                    }
                }),
        }
    }

    /// [`CellOrder::gather`] of points of `N` numbers: copies of a known size, so that the
    /// reads of several points (cache misses, the points being scattered) are under way at once.
    fn gather_fixed<const N: usize>(&self, xs: &[f64], sorted: &mut [f64]) {
        sorted
            .par_chunks_mut(CHUNK * N)
            .zip(self.point.par_chunks(CHUNK))
            .for_each(|(s, ks)| {
                for (s, &k) in s.chunks_exact_mut(N).zip(ks) {
                    let k = k as usize;
                    let x: &[f64; N] = xs[k * N..(k + 1) * N].try_into().unwrap_or(&[0.0; N]);
                    for (s, &x) in s.iter_mut().zip(x) {
                        *s = x;
                    }
                }
            });
    }

    /// The values `sorted` (`dim` numbers a point, in cell order) back in the order of the
    /// points into `out`, in parallel.
    pub(super) fn scatter_back(&self, sorted: &[f64], dim: usize, out: &mut [f64]) {
        out.par_chunks_mut(CHUNK * dim)
            .zip(self.position.par_chunks(CHUNK))
            .for_each(|(o, ps)| {
                if dim == 1 {
                    for (o, &p) in o.iter_mut().zip(ps) {
                        *o = sorted[p as usize];
                    }
                } else {
                    for (o, &p) in o.chunks_exact_mut(dim).zip(ps) {
                        let p = p as usize;
                        o.copy_from_slice(&sorted[p * dim..(p + 1) * dim]);
                    }
                }
            });
    }

    /// The position of every point in the cell order.
    #[cfg(test)]
    pub(super) fn positions(&self) -> &[u32] {
        &self.position
    }
}

#[cfg(test)]
mod tests {
    use super::{bins_per_direction, CellOrder, MAX_CELLS};

    #[test]
    fn bins_stay_within_the_cell_budget() {
        assert_eq!(bins_per_direction(1_000_000, 3), 32, "32^3 = MAX_CELLS");
        assert_eq!(bins_per_direction(1 << 14, 3), 10, "10^3 ≤ 2^10 < 11^3");
        assert_eq!(bins_per_direction(1 << 14, 2), 32);
        assert_eq!(
            bins_per_direction(10, 3),
            2,
            "at least two cells a direction"
        );
        for n in 1..=10 {
            let b = bins_per_direction(usize::MAX / 2, n);
            assert!(
                b.pow(u32::try_from(n).expect("small")) <= MAX_CELLS.max(1 << n),
                "n = {n}: {b}"
            );
        }
    }

    /// The order is a permutation, cells ascend along it (first direction slowest), points of
    /// one cell keep their order, and gathering then scattering back is the identity.
    #[test]
    fn the_order_is_a_stable_sort_by_cell() {
        let (n, bins) = (3, 4);
        let domains = [(0.0, 1.0), (-2.0, 2.0), (10.0, 11.0)];
        let mut xs = Vec::new();
        let mut seed = 7u64;
        for k in 0..2000 {
            for &(lo, hi) in &domains {
                seed = seed.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1);
                let u = (seed >> 11) as f64 / (1u64 << 53) as f64;
                // some points beyond the domain, at its ends, and NaN
                let t = match k % 97 {
                    0 => f64::NAN,
                    1 => lo - 1.0,
                    2 => hi,
                    3 => f64::INFINITY,
                    _ => lo + (hi - lo) * u,
                };
                xs.push(t);
            }
        }
        let order = CellOrder::new(&xs, n, &domains, bins);
        let pos = order.positions();
        let mut seen = vec![false; pos.len()];
        for &p in pos {
            assert!(!seen[p as usize], "position {p} taken twice");
            seen[p as usize] = true;
        }
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let cell = |x: &[f64]| {
            x.iter().zip(&domains).fold(0usize, |key, (&t, &(lo, hi))| {
                let c = ((t - lo) / (hi - lo) * bins as f64).clamp(0.0, (bins - 1) as f64);
                key * bins + if c.is_nan() { 0 } else { c as usize }
            })
        };
        let mut sorted = vec![0.0; xs.len()];
        order.gather(&xs, n, &mut sorted);
        let mut last = (0usize, 0u32);
        for (i, x) in sorted.chunks_exact(n).enumerate() {
            let k = order.point[i];
            assert!(
                x.iter()
                    .zip(&xs[k as usize * n..])
                    .all(|(a, b)| a.to_bits() == b.to_bits()),
                "position {i} holds point {k}"
            );
            let c = cell(x);
            assert!(
                i == 0 || (c, k) > last,
                "cells ascend, ranks ascend within a cell, at {i}"
            );
            last = (c, k);
        }
        let values: Vec<f64> = sorted.chunks_exact(n).flat_map(|x| [x[0], x[2]]).collect();
        let mut back = vec![0.0; 2 * pos.len()];
        order.scatter_back(&values, 2, &mut back);
        for (k, v) in back.chunks_exact(2).enumerate() {
            assert_eq!(v[0].to_bits(), xs[k * n].to_bits(), "point {k}");
            assert_eq!(v[1].to_bits(), xs[k * n + 2].to_bits(), "point {k}");
        }
    }
}
