//! The parts of a polynomial patch: halved in the direction whose halves' bound is the smaller,
//! or cut into a few equal parts, until within the tolerance.

use std::sync::atomic::{AtomicUsize, Ordering};

use super::bounds::SecondNets;
#[cfg(doc)]
use super::MAX_LEVELS;
use super::{Leaf, Rule, MAX_DIRECT_PARTS, PATCH_WIDTH};
use crate::error::{Error, Result};
use crate::query::surface::QuerySurface;
use crate::query::tessellate::{MAX_MESH_VERTICES, MESH_VERTICES};

impl QuerySurface {
    /// The net of the part `u × v` (integer ranges) of patch `k` (de Casteljau at its ends).
    pub(super) fn sub_net(&self, k: usize, u: (u64, u64), v: (u64, u64)) -> Vec<f64> {
        let mut net = self.patch(k).to_vec();
        let w = PATCH_WIDTH;
        if u.0 > 0 {
            net = self.split_u_at(&net, u.0 as f64 / w as f64).1;
        }
        if u.1 < w {
            net = self
                .split_u_at(&net, (u.1 - u.0) as f64 / (w - u.0) as f64)
                .0;
        }
        if v.0 > 0 {
            net = self.split_v_at(&net, v.0 as f64 / w as f64).1;
        }
        if v.1 < w {
            net = self
                .split_v_at(&net, (v.1 - v.0) as f64 / (w - v.0) as f64)
                .0;
        }
        net
    }

    /// The parts of the polynomial (sub-)patch `net` over the integer ranges `u × v` of patch
    /// `k` within the normalised tolerance `tol` under `rule`, split at least once if `force`.
    /// A part whose bound is above `tol` is cut into the fewest equal parts, three to
    /// [`MAX_DIRECT_PARTS`] (not four or eight, which halving reaches with the parts' own,
    /// tighter nets), whose bounds from this net ([`SecondNets::cut_bound`]) are within `tol`
    /// when halving's are not; otherwise halved (de Casteljau at the middle) in the direction
    /// whose halves' bound is the smaller; at most [`MAX_LEVELS`] times in each direction.
    /// `count` is the number of parts so far: past [`MAX_MESH_VERTICES`] this stops with
    /// [`Error::TooLarge`].
    #[allow(clippy::too_many_arguments)]
    pub(super) fn poly_leaves(
        &self,
        k: usize,
        net: Vec<f64>,
        range: ((u64, u64), (u64, u64)),
        tol: f64,
        rule: Rule,
        force: bool,
        count: &AtomicUsize,
    ) -> Result<Vec<Leaf>> {
        let (p, q, dim) = (self.p, self.q, self.dim);
        let mut out = Vec::new();
        let mut stack = vec![(net, range.0, range.1, force)];
        while let Some((net, u, v, force)) = stack.pop() {
            let sn = self.second_nets(&net);
            let (two, anti) = sn.two_triangles();
            let (can_u, can_v) = (u.1 - u.0 > 2, v.1 - v.0 > 2);
            let (bound, accept) = match rule {
                Rule::Edges => (two, two <= tol),
                Rule::Any => {
                    let (a, b, c) = self.net_bounds(&net).unwrap_or((0.0, 0.0, 0.0));
                    let any = (a + 2.0 * b + c) / 8.0;
                    (two.min(any), any <= tol)
                }
            };
            if (accept && !force) || !(can_u || can_v) {
                let n = count.fetch_add(1, Ordering::Relaxed) + 1;
                if n > MAX_MESH_VERTICES {
                    return Err(Error::TooLarge {
                        what: MESH_VERTICES,
                        size: n,
                        max: MAX_MESH_VERTICES,
                    });
                }
                let mut corners = Vec::with_capacity(4 * dim);
                for (i, j) in [(0, 0), (p, 0), (p, q), (0, q)] {
                    corners.extend_from_slice(&net[(i * (q + 1) + j) * dim..][..dim]);
                }
                out.push(Leaf {
                    patch: k,
                    u,
                    v,
                    bound,
                    anti,
                    corners,
                });
                continue;
            }
            let (ku, kv) = match rule {
                Rule::Edges => self.choose_cut(&sn, tol, (u.1 - u.0, v.1 - v.0)),
                Rule::Any => {
                    let (a, b, c) = self.net_bounds(&net).unwrap_or((0.0, 0.0, 0.0));
                    if (a + b >= c + b && can_u) || !can_v {
                        (2, 1)
                    } else {
                        (1, 2)
                    }
                }
            };
            let mut parts = Vec::with_capacity(ku * kv);
            for (n_u, pu) in self.split_evenly(net, u, ku, true) {
                parts.extend(
                    self.split_evenly(n_u, v, kv, false)
                        .into_iter()
                        .map(|(n, pv)| (n, pu, pv, false)),
                );
            }
            stack.extend(parts);
        }
        Ok(out)
    }

    /// The cut `k_u × k_v` of a part above the tolerance with second-derivative nets `sn` and
    /// integer widths `widths`: halving in the direction whose halves' bound is the smaller,
    /// unless both are above `tol` and a cut into 3, 5, 6, 7 or 9 equal parts (the fewest, then
    /// the smallest bound) is within it; no part under two units wide.
    fn choose_cut(&self, sn: &SecondNets, tol: f64, widths: (u64, u64)) -> (usize, usize) {
        let ac = (sn.along(1.0, 0.0), sn.along(0.0, 1.0));
        let fits = |ku: usize, kv: usize| 2 * ku as u64 <= widths.0 && 2 * kv as u64 <= widths.1;
        let bu = if fits(2, 1) {
            sn.cut_bound(ac, 2, 1, tol)
        } else {
            f64::INFINITY
        };
        let bv = if fits(1, 2) {
            sn.cut_bound(ac, 1, 2, tol)
        } else {
            f64::INFINITY
        };
        let halve = if bu <= bv { (2, 1) } else { (1, 2) };
        if bu.min(bv) <= tol {
            return halve;
        }
        for n in [3, 4, 5, 6, 7, 8, 9] {
            if n > MAX_DIRECT_PARTS {
                break;
            }
            let mut best: Option<((usize, usize), f64)> = None;
            for ku in (1..=n).filter(|ku| n % ku == 0) {
                let kv = n / ku;
                if !fits(ku, kv) {
                    continue;
                }
                let b = sn.cut_bound(ac, ku, kv, tol);
                if b <= tol && best.is_none_or(|(_, x)| b < x) {
                    best = Some(((ku, kv), b));
                }
            }
            if let Some((cut, _)) = best {
                // four and eight parts: halving gets there with the halves' own nets
                return if n == 4 || n == 8 { halve } else { cut };
            }
        }
        halve
    }

    /// A net over the integer range `r` cut into `k` parts at `r.0 + i·(r.1 − r.0)/k` (integer
    /// division; de Casteljau at each cut in turn), along `u` or `v`: the parts with their
    /// ranges, in order.
    fn split_evenly(
        &self,
        net: Vec<f64>,
        r: (u64, u64),
        k: usize,
        along_u: bool,
    ) -> Vec<(Vec<f64>, (u64, u64))> {
        let mut out = Vec::with_capacity(k);
        let (mut rest, mut from) = (net, r.0);
        let w = r.1 - r.0;
        for i in 1..k as u64 {
            let cut = r.0 + i * w / k as u64;
            let t = (cut - from) as f64 / (r.1 - from) as f64;
            let (lo, hi) = if along_u {
                self.halve_or_split(&rest, t, true)
            } else {
                self.halve_or_split(&rest, t, false)
            };
            out.push((lo, (from, cut)));
            rest = hi;
            from = cut;
        }
        out.push((rest, (from, r.1)));
        out
    }

    fn halve_or_split(&self, net: &[f64], t: f64, along_u: bool) -> (Vec<f64>, Vec<f64>) {
        match (t == 0.5, along_u) {
            (true, true) => self.halve_u(net),
            (true, false) => self.halve_v(net),
            (false, true) => self.split_u_at(net, t),
            (false, false) => self.split_v_at(net, t),
        }
    }
}
