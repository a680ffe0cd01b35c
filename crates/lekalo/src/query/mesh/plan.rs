//! The patches' places on the global lattice, and how each polynomial part is triangulated
//! through the points on its sides: two triangles, a strip, a fan about its centre, or split
//! again.

use super::bounds::triangle_bound;
#[cfg(doc)]
use super::bounds::SecondNets;
use super::strips::{best_zip, chains, zip, Lattice};
use super::{Leaf, Rect, PATCH_WIDTH};
use crate::query::surface::QuerySurface;

/// The patches' places on the global lattice: patch `(i, j)` (the `i`-th `u` interval, the
/// `j`-th `v` interval) covers the integers `[i, i + 1]·PATCH_WIDTH × [j, j + 1]·PATCH_WIDTH`.
pub(super) struct PatchGrid {
    us: Vec<(f64, f64)>,
    vs: Vec<(f64, f64)>,
    origin: Vec<(u64, u64)>,
}

impl PatchGrid {
    pub(super) fn new(s: &QuerySurface) -> Self {
        let mut us: Vec<(f64, f64)> = s.ranges.iter().map(|r| r.0).collect();
        us.sort_by(|a, b| a.0.total_cmp(&b.0));
        us.dedup();
        let mut vs: Vec<(f64, f64)> = s.ranges.iter().map(|r| r.1).collect();
        vs.sort_by(|a, b| a.0.total_cmp(&b.0));
        vs.dedup();
        let origin = s
            .ranges
            .iter()
            .map(|(u, v)| {
                let i = us.partition_point(|x| x.0 < u.0) as u64;
                let j = vs.partition_point(|x| x.0 < v.0) as u64;
                (i * PATCH_WIDTH, j * PATCH_WIDTH)
            })
            .collect();
        PatchGrid { us, vs, origin }
    }

    pub(super) fn rect(&self, l: &Leaf) -> Rect {
        let (ou, ov) = self.origin[l.patch];
        ((ou + l.u.0, ou + l.u.1), (ov + l.v.0, ov + l.v.1))
    }

    /// The surface parameters of the lattice point `(u, v)`.
    pub(super) fn param(&self, u: u64, v: u64) -> [f64; 2] {
        let at = |g: u64, ranges: &[(f64, f64)]| {
            let i = usize::try_from(g / PATCH_WIDTH).unwrap_or(usize::MAX);
            let f = (g % PATCH_WIDTH) as f64 / PATCH_WIDTH as f64;
            match ranges.get(i) {
                Some(r) => r.0 + (r.1 - r.0) * f,
                None => ranges[ranges.len() - 1].1,
            }
        };
        [at(u, &self.us), at(v, &self.vs)]
    }
}

/// How a polynomial part is triangulated, with the largest bound of its triangles.
pub(super) enum Plan {
    /// Two triangles (no extra point on its sides), along its diagonal.
    Two,
    /// A strip through the extra points on its sides.
    Strip(Vec<[u32; 3]>),
    /// A fan about its centre (a new vertex) through the points on its sides.
    Fan,
    /// None is within the tolerance: the part is split and the sides matched again.
    Split,
}
impl QuerySurface {
    /// How part `l` (global integer ranges `r`) is triangulated through the lattice points on
    /// its sides, and the largest bound of its triangles. Two triangles where there are none;
    /// otherwise a strip ([`zip`]) with rungs along the part's diagonal, advancing on the chain
    /// whose next point comes first along that diagonal; each triangle's bound is the least of
    /// [`triangle_bound`] with its own edge vectors (`M_e` from the part's [`SecondNets`]) and
    /// `(A + 2B + C)/8`; if one is above `tol`, the strip of least largest bound of either
    /// diagonal ([`best_zip`]), else a fan about the centre, else ([`Plan::Split`], if
    /// `may_split` and the part is more than two units wide) a split; a split whenever it can
    /// if `force` (tests).
    pub(super) fn plan_part(
        &self,
        l: &Leaf,
        r: Rect,
        lat: &Lattice,
        tol: f64,
        may_split: bool,
        force: bool,
    ) -> (Plan, f64) {
        let mut ring = Vec::new();
        let [br, tr, tl] = lat.ring(r, &mut ring);
        if ring.len() == 4 {
            return (Plan::Two, l.bound);
        }
        let ((u0, u1), (v0, v1)) = r;
        if force && (u1 - u0 > 2 || v1 - v0 > 2) {
            return (Plan::Split, f64::INFINITY);
        }
        let net = self.sub_net(l.patch, l.u, l.v);
        let sn = self.second_nets(&net);
        let (a, b, c) = self.net_bounds(&net).unwrap_or((0.0, 0.0, 0.0));
        let any = (a + 2.0 * b + c) / 8.0;
        let (du, dv) = ((u1 - u0) as f64, (v1 - v0) as f64);
        let at = |u: u64, v: u64| ((u - u0) as f64 / du, (v - v0) as f64 / dv);
        let local = |i: u32| {
            let k = &lat.keys[i as usize];
            at(k.0, k.1)
        };
        let tri = |x: (f64, f64), y: (f64, f64), z: (f64, f64)| {
            let m = |p: (f64, f64), q: (f64, f64)| sn.along(q.0 - p.0, q.1 - p.1);
            any.min(triangle_bound([m(x, y), m(x, z), m(y, z)]))
        };
        let cost = |i: u32, j: u32, k: u32| tri(local(i), local(j), local(k));
        // the strip with rungs along the part's diagonal: from (u0, v0) to (u1, v1) for the
        // diagonal (1, −1), from (u1, v0) to (u0, v1) for (1, 1)
        let (s, t) = if l.anti { (0, tr) } else { (br, tl) };
        let progress = |i: u32| {
            let (x, y) = local(i);
            if l.anti {
                x + y
            } else {
                1.0 - x + y
            }
        };
        let (ca, cb) = chains(&ring, s, t);
        let mut moves = Vec::with_capacity(ca.len() + cb.len());
        let (mut i, mut j) = (0, 0);
        while i + 1 < ca.len() || j + 1 < cb.len() {
            let take_a = j + 1 >= cb.len()
                || (i + 1 < ca.len() && progress(ca[i + 1]) <= progress(cb[j + 1]));
            moves.push(take_a);
            if take_a {
                i += 1;
            } else {
                j += 1;
            }
        }
        let mut tris = Vec::with_capacity(ring.len() - 2);
        zip(ring[s], ring[t], &ca, &cb, &moves, &mut tris);
        let bound = tris
            .iter()
            .map(|t| cost(t[0], t[1], t[2]))
            .fold(0.0, f64::max);
        if bound <= tol {
            return (Plan::Strip(tris), bound);
        }
        let mut best = (Plan::Strip(tris), bound);
        for (s, t) in [(0, tr), (br, tl)] {
            let (ca, cb) = chains(&ring, s, t);
            let (moves, b) = best_zip(ring[s], ring[t], &ca, &cb, &cost);
            if b < best.1 {
                let mut tris = Vec::with_capacity(ring.len() - 2);
                zip(ring[s], ring[t], &ca, &cb, &moves, &mut tris);
                best = (Plan::Strip(tris), b);
            }
        }
        if best.1 <= tol {
            return best;
        }
        let centre = at((u0 + u1) / 2, (v0 + v1) / 2);
        let fan = (0..ring.len())
            .map(|i| tri(centre, local(ring[i]), local(ring[(i + 1) % ring.len()])))
            .fold(0.0, f64::max);
        // the centre strictly inside (a part one unit wide, after odd cuts, has none)
        if fan < best.1 && u1 - u0 >= 2 && v1 - v0 >= 2 {
            best = (Plan::Fan, fan);
        }
        if best.1 <= tol || !may_split || (u1 - u0 <= 2 && v1 - v0 <= 2) {
            return best;
        }
        (Plan::Split, best.1)
    }
}
