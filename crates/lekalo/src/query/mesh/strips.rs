//! The parts' corners on the global lattice, each part's boundary read from them, and strips of
//! triangles between two chains of a boundary.

use super::Rect;
use crate::error::{Error, Result};
use crate::query::tessellate::{MAX_MESH_VERTICES, MESH_VERTICES};

/// The parts' corners on the global integer lattice: the mesh's vertices, one a point, each
/// with the part and corner it comes from, sorted by `(u, v)`, and the same sorted by `(v, u)`,
/// from which each part's boundary with every corner on its sides is read.
pub(super) struct Lattice {
    pub(super) keys: Vec<(u64, u64, u32, u8)>,
    by_v: Vec<(u64, u64, u32)>,
}

impl Lattice {
    #[allow(clippy::cast_possible_truncation)] // vertex indices: below MAX_MESH_VERTICES < 2^32
    pub(super) fn new(rects: impl Iterator<Item = Rect>) -> Result<Self> {
        let mut keys: Vec<(u64, u64, u32, u8)> = Vec::new();
        for (n, (gu, gv)) in rects.enumerate() {
            let n = u32::try_from(n).map_err(|_| Error::TooLarge {
                what: MESH_VERTICES,
                size: n,
                max: MAX_MESH_VERTICES,
            })?;
            for (c, (u, v)) in [(gu.0, gv.0), (gu.1, gv.0), (gu.1, gv.1), (gu.0, gv.1)]
                .into_iter()
                .enumerate()
            {
                keys.push((u, v, n, c as u8));
            }
        }
        keys.sort_unstable();
        keys.dedup_by_key(|k| (k.0, k.1));
        let mut by_v: Vec<(u64, u64, u32)> = keys
            .iter()
            .enumerate()
            .map(|(i, k)| (k.1, k.0, i as u32))
            .collect();
        by_v.sort_unstable();
        Ok(Lattice { keys, by_v })
    }

    /// The boundary of the part `(u, v)`, counter-clockwise from `(u0, v0)`, every lattice
    /// vertex on it, into `ring`; the indices in `ring` of its corners `(u1, v0)`, `(u1, v1)`,
    /// `(u0, v1)` (the first is at 0).
    #[allow(clippy::cast_possible_truncation)] // vertex indices: below MAX_MESH_VERTICES < 2^32
    pub(super) fn ring(&self, ((u0, u1), (v0, v1)): Rect, ring: &mut Vec<u32>) -> [usize; 3] {
        let by_u_range = |u: u64, a: u64, b: u64| {
            let i = self.keys.partition_point(|k| (k.0, k.1) < (u, a));
            let j = self.keys.partition_point(|k| (k.0, k.1) < (u, b));
            (i..j).map(|i| i as u32)
        };
        let by_v_range = |v: u64, a: u64, b: u64| {
            let i = self.by_v.partition_point(|k| (k.0, k.1) < (v, a));
            let j = self.by_v.partition_point(|k| (k.0, k.1) < (v, b));
            self.by_v[i..j].iter().map(|k| k.2)
        };
        // each side without its last vertex
        ring.clear();
        ring.extend(by_v_range(v0, u0, u1));
        let br = ring.len();
        ring.extend(by_u_range(u1, v0, v1));
        let tr = ring.len();
        ring.extend(by_v_range(v1, u0 + 1, u1 + 1));
        ring[tr..].reverse();
        let tl = ring.len();
        ring.extend(by_u_range(u0, v0 + 1, v1 + 1));
        ring[tl..].reverse();
        [br, tr, tl]
    }
}

/// The two chains of `ring` between its corners at `s` and `t` (interior points, both
/// non-empty): from `s` forwards to `t`, and from `s` backwards to `t`.
pub(super) fn chains(ring: &[u32], s: usize, t: usize) -> (Vec<u32>, Vec<u32>) {
    let n = ring.len();
    let fwd = (t + n - s) % n - 1;
    let bwd = (s + n - t) % n - 1;
    (
        (1..=fwd).map(|i| ring[(s + i) % n]).collect(),
        (1..=bwd).map(|i| ring[(s + n - i) % n]).collect(),
    )
}

/// A strip between the chains `a` and `b` of a convex polygon's boundary from the corner `s` to
/// the corner `t` ([`chains`]): `[s, a_0, b_0]`, then at each step `[a_i, a_{i+1}, b_j]`
/// (`moves[k]`, advance on `a`) or `[b_{j+1}, b_j, a_i]`, then `[a_last, t, b_last]`;
/// `a.len() + b.len()` counter-clockwise triangles. Any order of the moves gives a
/// triangulation with no degenerate triangle when the points of each chain lie on at most two
/// sides of a rectangle, the chains' corners being `s` and `t` opposite each other: three
/// vertices of a triangle are never on one side.
pub(super) fn zip(s: u32, t: u32, a: &[u32], b: &[u32], moves: &[bool], out: &mut Vec<[u32; 3]>) {
    out.push([s, a[0], b[0]]);
    let (mut i, mut j) = (0, 0);
    for &take_a in moves {
        if take_a {
            out.push([a[i], a[i + 1], b[j]]);
            i += 1;
        } else {
            out.push([b[j + 1], b[j], a[i]]);
            j += 1;
        }
    }
    out.push([a[a.len() - 1], t, b[b.len() - 1]]);
}

/// The moves of [`zip`] whose largest triangle `cost` is least (dynamic programming over the
/// rungs `(a_i, b_j)`, `O(|a|·|b|)` costs), with that cost.
pub(super) fn best_zip(
    s: u32,
    t: u32,
    a: &[u32],
    b: &[u32],
    cost: &impl Fn(u32, u32, u32) -> f64,
) -> (Vec<bool>, f64) {
    let (na, nb) = (a.len(), b.len());
    // best[i·nb + j]: least largest cost of a strip up to the rung (a_i, b_j); from_a: its last
    // move advanced on a
    let mut best = vec![f64::INFINITY; na * nb];
    let mut from_a = vec![false; na * nb];
    best[0] = cost(s, a[0], b[0]);
    for i in 0..na {
        for j in 0..nb {
            if i > 0 {
                let c = best[(i - 1) * nb + j].max(cost(a[i - 1], a[i], b[j]));
                if c < best[i * nb + j] {
                    best[i * nb + j] = c;
                    from_a[i * nb + j] = true;
                }
            }
            if j > 0 {
                let c = best[i * nb + j - 1].max(cost(b[j], b[j - 1], a[i]));
                if c < best[i * nb + j] {
                    best[i * nb + j] = c;
                    from_a[i * nb + j] = false;
                }
            }
        }
    }
    let total = best[na * nb - 1].max(cost(a[na - 1], t, b[nb - 1]));
    let mut moves = Vec::with_capacity(na + nb - 2);
    let (mut i, mut j) = (na - 1, nb - 1);
    while i + j > 0 {
        let m = from_a[i * nb + j];
        moves.push(m);
        if m {
            i -= 1;
        } else {
            j -= 1;
        }
    }
    moves.reverse();
    (moves, total)
}
