//! Adaptive triangle meshes of surfaces within a proved deviation
//! (`docs/theory/queries.md#tessellation`): each patch is halved, in `u` or in `v`, or near the
//! end cut into a few equal parts, until the bound of every part is within the tolerance; the parts' sides are then matched across
//! parts and patches, so the mesh has no cracks, and a part with extra points on its sides is a
//! strip (polynomial) or a fan (rational) through them.

use std::sync::atomic::{AtomicUsize, Ordering};

use rayon::prelude::*;

use super::surface::QuerySurface;
use super::tessellate::{check_tol, Mesh, MAX_MESH_VERTICES};
use crate::error::{Error, Result};
use crate::Points;

/// Most halvings of a patch in one direction. A part's corners are integers in
/// `[0, 2^(MAX_LEVELS + 1)]` along each direction of its patch, so every part is at least two
/// units wide and its centre is an integer too.
const MAX_LEVELS: u32 = 40;
/// Integer width of a patch along each direction.
const PATCH_WIDTH: u64 = 1 << (MAX_LEVELS + 1);

/// A part of a patch that is meshed as a whole: its patch, its integer ranges inside the patch,
/// its deviation bound and its four corners (`(u0, v0)`, `(u1, v0)`, `(u1, v1)`, `(u0, v1)`,
/// normalised Cartesian points).
struct Leaf {
    patch: usize,
    u: (u64, u64),
    v: (u64, u64),
    bound: f64,
    corners: Vec<f64>,
}

impl QuerySurface {
    /// Bounds `(A, B, C)` on `|S_uu|`, `|S_uv|`, `|S_vv|` of the (sub-)patch with homogeneous net
    /// `net`, in its own parameters `[0, 1]²`, such that the linear interpolant over any triangle
    /// of the part's grid split (two triangles) or of its fan about the centre deviates from the
    /// part by at most `(A + 2B + C) / 8` (`docs/theory/queries.md#tessellation`).
    ///
    /// Polynomial: `A = p(p−1)·max|Δ²_u P|`, `B = pq·max|Δ_uΔ_v P|`, `C = q(q−1)·max|Δ²_v P|`
    /// (the derivatives are Bezier patches with those nets; convex hull).
    ///
    /// Rational `S = P/w` (weights `w ≥ w_min > 0`, net translated to the centre `c` of its
    /// Cartesian points, `R` their largest distance from `c`): on a triangle with interpolant
    /// `L`, `S − L = f/w` with `f = (P − c w) − w (L − c)` vanishing at the vertices, and by
    /// Leibniz `f_uu = P_uu − w_uu (L − c) − 2 w_u L_u`,
    /// `f_uv = P_uv − w_uv (L − c) − w_u L_v − w_v L_u`, with `|L − c| ≤ R` and, for the
    /// triangles used (a leg along `u` or `v`, the others no steeper than the diagonal),
    /// `|L_u| ≤ G_u + 2 G_v`, `|L_v| ≤ G_v + 2 G_u`, `G_u ≥ max|S_u|`. `None` if a weight is not
    /// positive.
    pub(crate) fn net_bounds(&self, net: &[f64]) -> Option<(f64, f64, f64)> {
        let (p, q, hd, dim) = (self.p, self.q, self.hd, self.dim);
        let at = |i: usize, j: usize| (i * (q + 1) + j) * hd;
        let (pf, qf) = (p as f64, q as f64);
        if !self.rational {
            // hand-written: this loop is the mesher's inner kernel
            let (mut a, mut b, mut c) = (0.0_f64, 0.0_f64, 0.0_f64);
            for i in 0..=p {
                for j in 0..=q {
                    let (mut sa, mut sb, mut sc) = (0.0, 0.0, 0.0);
                    for d in 0..dim {
                        let x = net[at(i, j) + d];
                        if i + 2 <= p {
                            let t = net[at(i + 2, j) + d] - 2.0 * net[at(i + 1, j) + d] + x;
                            sa += t * t;
                        }
                        if i < p && j < q {
                            let t = net[at(i + 1, j + 1) + d]
                                - net[at(i + 1, j) + d]
                                - net[at(i, j + 1) + d]
                                + x;
                            sb += t * t;
                        }
                        if j + 2 <= q {
                            let t = net[at(i, j + 2) + d] - 2.0 * net[at(i, j + 1) + d] + x;
                            sc += t * t;
                        }
                    }
                    a = a.max(sa);
                    b = b.max(sb);
                    c = c.max(sc);
                }
            }
            return Some((
                pf * (pf - 1.0).max(0.0) * a.sqrt(),
                pf * qf * b.sqrt(),
                qf * (qf - 1.0).max(0.0) * c.sqrt(),
            ));
        }
        let w = |i: usize, j: usize| net[at(i, j) + dim];
        let mut w_min = f64::INFINITY;
        let (mut lo, mut hi) = (vec![f64::INFINITY; dim], vec![f64::NEG_INFINITY; dim]);
        for i in 0..=p {
            for j in 0..=q {
                let wij = w(i, j);
                w_min = w_min.min(wij);
                for d in 0..dim {
                    let x = net[at(i, j) + d] / wij;
                    lo[d] = lo[d].min(x);
                    hi[d] = hi[d].max(x);
                }
            }
        }
        if !(w_min > 0.0) {
            return None;
        }
        let centre: Vec<f64> = lo.iter().zip(&hi).map(|(l, h)| 0.5 * (l + h)).collect();
        let mut radius = 0.0_f64;
        for i in 0..=p {
            for j in 0..=q {
                let r2: f64 = (0..dim)
                    .map(|d| (net[at(i, j) + d] / w(i, j) - centre[d]).powi(2))
                    .sum();
                radius = radius.max(r2.sqrt());
            }
        }
        // coordinate d of the translated homogeneous net P − c w; the weight as coordinate dim
        let x = |i: usize, j: usize, d: usize| {
            if d == dim {
                w(i, j)
            } else {
                net[at(i, j) + d] - centre[d] * w(i, j)
            }
        };
        // [|Δ²_u|, |Δ_uΔ_v|, |Δ²_v|, |Δ_u|, |Δ_v|] of the point part, then of the weight
        let mut pt = [0.0_f64; 5];
        let mut wt = [0.0_f64; 5];
        for i in 0..=p {
            for j in 0..=q {
                let mut s = [0.0_f64; 5];
                for d in 0..=dim {
                    let diffs = [
                        (i + 2 <= p).then(|| x(i + 2, j, d) - 2.0 * x(i + 1, j, d) + x(i, j, d)),
                        (i < p && j < q).then(|| {
                            x(i + 1, j + 1, d) - x(i + 1, j, d) - x(i, j + 1, d) + x(i, j, d)
                        }),
                        (j + 2 <= q).then(|| x(i, j + 2, d) - 2.0 * x(i, j + 1, d) + x(i, j, d)),
                        (i < p).then(|| x(i + 1, j, d) - x(i, j, d)),
                        (j < q).then(|| x(i, j + 1, d) - x(i, j, d)),
                    ];
                    for (m, t) in diffs.iter().enumerate() {
                        if let Some(t) = t {
                            if d == dim {
                                wt[m] = wt[m].max(t.abs());
                            } else {
                                s[m] += t * t;
                            }
                        }
                    }
                }
                for m in 0..5 {
                    pt[m] = pt[m].max(s[m].sqrt());
                }
            }
        }
        let factors = [
            pf * (pf - 1.0).max(0.0),
            pf * qf,
            qf * (qf - 1.0).max(0.0),
            pf,
            qf,
        ];
        let (mut pd, mut wd) = ([0.0; 5], [0.0; 5]);
        for m in 0..5 {
            pd[m] = factors[m] * pt[m];
            wd[m] = factors[m] * wt[m];
        }
        // slopes of S: |S_u| ≤ (|P_u| + |w_u| R) / w_min; of L on the part's triangles
        let su = (pd[3] + wd[3] * radius) / w_min;
        let sv = (pd[4] + wd[4] * radius) / w_min;
        let (gu, gv) = (su + 2.0 * sv, sv + 2.0 * su);
        Some((
            (pd[0] + wd[0] * radius + 2.0 * wd[3] * gu) / w_min,
            (pd[1] + wd[1] * radius + wd[3] * gv + wd[4] * gu) / w_min,
            (pd[2] + wd[2] * radius + 2.0 * wd[4] * gv) / w_min,
        ))
    }

    /// The parts of patch `k` within the normalised tolerance `tol`: halved (de Casteljau at the
    /// middle) in the direction whose terms dominate the bound, at most [`MAX_LEVELS`] times
    /// in each direction; on a polynomial surface a part that halving would leave above the
    /// tolerance but a cut into at most [`MAX_DIRECT_PARTS`] equal parts would not is cut so
    /// ([`direct_split`]). `count` is the number of parts of every patch so far: past
    /// [`MAX_MESH_VERTICES`] this stops with [`Error::TooLarge`].
    fn patch_leaves(&self, k: usize, tol: f64, count: &AtomicUsize) -> Result<Vec<Leaf>> {
        let (p, q, hd, dim) = (self.p, self.q, self.hd, self.dim);
        let mut out = Vec::new();
        let mut stack = vec![(self.patch(k).to_vec(), (0, PATCH_WIDTH), (0, PATCH_WIDTH))];
        while let Some((net, u, v)) = stack.pop() {
            let (a, b, c) = self
                .net_bounds(&net)
                .ok_or_else(|| Error::InvalidArgument {
                    what: "surface to mesh",
                    reason: format!(
                        "patch {k} has a weight that is not positive; the deviation bound needs \
                     positive weights"
                    ),
                })?;
            let bound = (a + 2.0 * b + c) / 8.0;
            let (eu, ev) = (a + b, c + b);
            let (can_u, can_v) = (u.1 - u.0 > 2, v.1 - v.0 > 2);
            // one direction at a time: each halving then cuts the bound by less than a
            // quartering would, so the parts end closer to the tolerance (fewer triangles)
            let split_u = can_u && eu > 0.0 && (eu >= ev || !can_v);
            let split_v = can_v && ev > 0.0 && !split_u;
            if bound <= tol || !(split_u || split_v) {
                let n = count.fetch_add(1, Ordering::Relaxed) + 1;
                if n > MAX_MESH_VERTICES {
                    return Err(Error::TooLarge {
                        what: "mesh vertices",
                        size: n,
                        max: MAX_MESH_VERTICES,
                    });
                }
                let mut corners = Vec::with_capacity(4 * dim);
                for (i, j) in [(0, 0), (p, 0), (p, q), (0, q)] {
                    let x = &net[(i * (q + 1) + j) * hd..][..hd];
                    let w = if self.rational { x[dim] } else { 1.0 };
                    corners.extend(x[..dim].iter().map(|c| c / w));
                }
                out.push(Leaf {
                    patch: k,
                    u,
                    v,
                    bound,
                    corners,
                });
                continue;
            }
            if !self.rational {
                if let Some((ku, kv)) = direct_split((a, b, c), tol, (u.1 - u.0, v.1 - v.0)) {
                    let mut parts = Vec::with_capacity(ku * kv);
                    for (n_u, pu) in self.split_evenly(net, u, ku, true) {
                        parts.extend(
                            self.split_evenly(n_u, v, kv, false)
                                .into_iter()
                                .map(|(n, pv)| (n, pu, pv)),
                        );
                    }
                    stack.extend(parts);
                    continue;
                }
            }
            let mut parts = vec![(net, u, v)];
            if split_u {
                parts = parts
                    .into_iter()
                    .flat_map(|(n, u, v)| {
                        let m = (u.0 + u.1) / 2;
                        let (l, h) = self.halve_u(&n);
                        [(l, (u.0, m), v), (h, (m, u.1), v)]
                    })
                    .collect();
            }
            if split_v {
                parts = parts
                    .into_iter()
                    .flat_map(|(n, u, v)| {
                        let m = (v.0 + v.1) / 2;
                        let (l, h) = self.halve_v(&n);
                        [(l, u, (v.0, m)), (h, u, (m, v.1))]
                    })
                    .collect();
            }
            stack.extend(parts);
        }
        Ok(out)
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
                self.split_u_at(&rest, t)
            } else {
                self.split_v_at(&rest, t)
            };
            out.push((lo, (from, cut)));
            rest = hi;
            from = cut;
        }
        out.push((rest, (from, r.1)));
        out
    }

    /// A triangle mesh within `tolerance` of a surface, polynomial or rational, adaptive: each
    /// patch is halved — in `u` where the `u` terms of its bound dominate, in `v` where the `v`
    /// terms do; on a polynomial surface cut into the fewest equal parts (at most nine) once
    /// that reaches the tolerance and halving would not — until every part's bound
    /// `(A + 2B + C) / 8` from its own net's differences is within `tolerance`
    /// (`docs/theory/queries.md#tessellation`), so flat regions get large triangles and curved
    /// ones small. Parts are matched along their sides, across patches too: a part whose sides
    /// carry corners of smaller neighbours is meshed through all of them, any other as two
    /// triangles, so the mesh has no cracks and no T-junctions. On a polynomial surface such a
    /// part is a strip of triangles between its sides with no interior point (every triangle
    /// inside a part's rectangle is within its bound); on a rational one, whose bound needs
    /// triangles no steeper than the part's diagonal, a fan about its centre. Vertices are the
    /// parts' corner control points (points of the surface) and the fans' centres.
    /// Patches are split in parallel; the mesh does not depend on the thread count.
    ///
    /// ```
    /// use lekalo::{BSplineSurface, Points, QuerySurface};
    /// // z = x² on [0, 1]²: A = 2, so 2/(8·4^k) ≤ 1e-3 after k = 4 halvings in u, none in v
    /// let net = Points::from_3d(&[[0., 0., 0.], [0., 1., 0.], [0.5, 0., 0.], [0.5, 1., 0.], [1., 0., 1.], [1., 1., 1.]])?;
    /// let s = BSplineSurface::new(2, 1, vec![0., 0., 0., 1., 1., 1.], vec![0., 0., 1., 1.], net, (3, 2))?;
    /// let mesh = QuerySurface::from_bspline(&s)?.mesh(1e-3)?;
    /// assert!(mesh.deviation <= 1e-3);
    /// assert_eq!(mesh.triangles.len(), 2 * 16);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for a rational surface with a weight that is not positive, or
    /// a tolerance below [`super::MIN_RELATIVE_TOLERANCE`] times the size; [`Error::TooLarge`]
    /// beyond [`MAX_MESH_VERTICES`].
    #[allow(clippy::cast_possible_truncation)] // vertex indices: at most 4·MAX_MESH_VERTICES < 2^32
    pub fn mesh(&self, tolerance: f64) -> Result<Mesh> {
        check_tol(tolerance, self.scale)?;
        let tol = tolerance / self.scale;
        let dim = self.dim;
        // the patches' ranges in order: patch (i, j) covers integers [i, i + 1]·PATCH_WIDTH
        let mut us: Vec<(f64, f64)> = self.ranges.iter().map(|r| r.0).collect();
        us.sort_by(|a, b| a.0.total_cmp(&b.0));
        us.dedup();
        let mut vs: Vec<(f64, f64)> = self.ranges.iter().map(|r| r.1).collect();
        vs.sort_by(|a, b| a.0.total_cmp(&b.0));
        vs.dedup();
        let origin = |k: usize| {
            let (u, v) = self.ranges[k];
            let i = us.partition_point(|x| x.0 < u.0) as u64;
            let j = vs.partition_point(|x| x.0 < v.0) as u64;
            (i * PATCH_WIDTH, j * PATCH_WIDTH)
        };
        let count = AtomicUsize::new(0);
        let leaves: Vec<Leaf> = (0..self.patch_count())
            .into_par_iter()
            .map(|k| self.patch_leaves(k, tol, &count))
            .collect::<Result<Vec<_>>>()?
            .into_iter()
            .flatten()
            .collect();
        // global integer corners, each with the leaf and corner it comes from
        let global = |l: &Leaf| {
            let (ou, ov) = origin(l.patch);
            ((ou + l.u.0, ou + l.u.1), (ov + l.v.0, ov + l.v.1))
        };
        let mut keys: Vec<(u64, u64, u32, u8)> = Vec::with_capacity(4 * leaves.len());
        for (n, l) in leaves.iter().enumerate() {
            let (gu, gv) = global(l);
            let n = u32::try_from(n).map_err(|_| Error::TooLarge {
                what: "mesh vertices",
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
        // vertices sorted by (u, v); the same by (v, u) for the horizontal sides
        let by_v = {
            let mut t: Vec<(u64, u64, u32)> = keys
                .iter()
                .enumerate()
                .map(|(i, k)| (k.1, k.0, i as u32))
                .collect();
            t.sort_unstable();
            t
        };
        let param = |g: u64, ranges: &[(f64, f64)]| {
            let i = usize::try_from(g / PATCH_WIDTH).unwrap_or(usize::MAX);
            let f = (g % PATCH_WIDTH) as f64 / PATCH_WIDTH as f64;
            match ranges.get(i) {
                Some(r) => r.0 + (r.1 - r.0) * f,
                None => ranges[ranges.len() - 1].1,
            }
        };
        let mut verts = Vec::with_capacity(dim * (keys.len() + leaves.len() / 4));
        let mut uv = Vec::with_capacity(keys.len() + leaves.len() / 4);
        let mut buf = vec![0.0; dim];
        for &(u, v, n, c) in &keys {
            let l = &leaves[n as usize];
            self.denormalise(&l.corners[c as usize * dim..][..dim], &mut buf);
            verts.extend_from_slice(&buf);
            uv.push([param(u, &us), param(v, &vs)]);
        }
        let by_u_range = |u: u64, v0: u64, v1: u64| {
            let a = keys.partition_point(|k| (k.0, k.1) < (u, v0));
            let b = keys.partition_point(|k| (k.0, k.1) < (u, v1));
            (a..b).map(|i| i as u32)
        };
        let by_v_range = |v: u64, u0: u64, u1: u64| {
            let a = by_v.partition_point(|k| (k.0, k.1) < (v, u0));
            let b = by_v.partition_point(|k| (k.0, k.1) < (v, u1));
            by_v[a..b].iter().map(|k| k.2)
        };
        let mut triangles = Vec::with_capacity(2 * leaves.len());
        let mut ring: Vec<u32> = Vec::new();
        let mut scratch = Vec::new();
        let mut deviation = 0.0_f64;
        for l in &leaves {
            deviation = deviation.max(l.bound);
            let ((u0, u1), (v0, v1)) = global(l);
            // the boundary counter-clockwise, each side without its last vertex
            ring.clear();
            ring.extend(by_v_range(v0, u0, u1));
            ring.extend(by_u_range(u1, v0, v1));
            let top = ring.len();
            ring.extend(by_v_range(v1, u0 + 1, u1 + 1));
            ring[top..].reverse();
            let left = ring.len();
            ring.extend(by_u_range(u0, v0 + 1, v1 + 1));
            ring[left..].reverse();
            if ring.len() == 4 {
                triangles.push([ring[0], ring[1], ring[2]]);
                triangles.push([ring[0], ring[2], ring[3]]);
                continue;
            }
            if !self.rational {
                // any triangle in the part's rectangle is within its bound: a strip without
                // the centre (docs/theory/queries.md#tessellation)
                let (du, dv) = ((u1 - u0) as f64, (v1 - v0) as f64);
                let progress = |i: u32| {
                    let k = &keys[i as usize];
                    (k.0 - u0) as f64 / du + (k.1 - v0) as f64 / dv
                };
                let tr = by_v_range(v0, u0, u1).count() + by_u_range(u1, v0, v1).len();
                strip(&ring, tr, progress, &mut triangles);
                continue;
            }
            let centre = u32::try_from(uv.len()).map_err(|_| Error::TooLarge {
                what: "mesh vertices",
                size: uv.len(),
                max: MAX_MESH_VERTICES,
            })?;
            let (cu, cv) = ((u0 + u1) / 2, (v0 + v1) / 2);
            let local = |g: u64| (g % PATCH_WIDTH) as f64 / PATCH_WIDTH as f64;
            let pt = self.point_on(l.patch, local(cu), local(cv), &mut scratch);
            self.denormalise(&pt, &mut buf);
            verts.extend_from_slice(&buf);
            uv.push([param(cu, &us), param(cv, &vs)]);
            for i in 0..ring.len() {
                triangles.push([centre, ring[i], ring[(i + 1) % ring.len()]]);
            }
        }
        if uv.len() > MAX_MESH_VERTICES {
            return Err(Error::TooLarge {
                what: "mesh vertices",
                size: uv.len(),
                max: MAX_MESH_VERTICES,
            });
        }
        Ok(Mesh {
            vertices: Points::from_flat(dim, verts)?,
            uv,
            triangles,
            deviation: deviation * self.scale,
        })
    }
}

/// Most parts a part is cut into at once by [`direct_split`].
const MAX_DIRECT_PARTS: usize = 9;

/// The cut of a part with bound terms `(A, B, C)` into `k_u × k_v` equal parts, `2 < k_u·k_v ≤`
/// [`MAX_DIRECT_PARTS`], fewest first, whose bounds `(A/k_u² + 2B/(k_u k_v) + C/k_v²)/8` are
/// within `tol`: the parts' second-derivative nets lie in the convex hull of the part's, scaled
/// by `1/k_u²`, `1/(k_u k_v)`, `1/k_v²`, so each part's own bound is at most that. Where halving
/// would leave parts above the tolerance and a cut into three (or a few more) would not, this
/// gives fewer parts than halving twice. `None` when two parts suffice (halving), when no such
/// cut exists, or when a part would be under two integer units wide (`widths`).
fn direct_split(abc: (f64, f64, f64), tol: f64, widths: (u64, u64)) -> Option<(usize, usize)> {
    let (a, b, c) = abc;
    let mut best: Option<(usize, usize)> = None;
    for ku in 1..=MAX_DIRECT_PARTS {
        for kv in 1..=MAX_DIRECT_PARTS / ku {
            let n = ku * kv;
            let (fu, fv) = (ku as f64, kv as f64);
            let bound = (a / (fu * fu) + 2.0 * b / (fu * fv) + c / (fv * fv)) / 8.0;
            let fits = 2 * ku as u64 <= widths.0 && 2 * kv as u64 <= widths.1;
            if fits && bound <= tol && best.is_none_or(|(bu, bv)| n < bu * bv) {
                best = Some((ku, kv));
            }
        }
    }
    best.filter(|&(ku, kv)| ku * kv > 2)
}

/// Triangles of a rectangle whose boundary `ring` (counter-clockwise from the bottom-left
/// corner, the top-right corner at index `tr`) carries extra points on its sides, without an
/// interior point: the chains from the bottom-left to the top-right corner, along the bottom
/// and right sides and along the left and top sides, are joined by a strip whose triangles
/// each have one edge on a chain, advancing on the chain whose next point comes first along the
/// diagonal (`progress`: `(u − u0)/(u1 − u0) + (v − v0)/(v1 − v0)`), with one triangle at
/// each corner. `ring.len() − 2` counter-clockwise triangles, none degenerate: the interior
/// points of one chain lie on neither side of the other.
fn strip(ring: &[u32], tr: usize, progress: impl Fn(u32) -> f64, out: &mut Vec<[u32; 3]>) {
    let n = ring.len();
    debug_assert!(tr >= 2 && n >= tr + 2, "both chains have an interior point");
    // interior points of the chains: a along the bottom and right, b along the left and top
    let a = &ring[1..tr];
    let b: Vec<u32> = ring[tr + 1..].iter().rev().copied().collect();
    out.push([ring[0], a[0], b[0]]);
    let (mut i, mut j) = (0, 0);
    while i + 1 < a.len() || j + 1 < b.len() {
        let take_a =
            j + 1 >= b.len() || (i + 1 < a.len() && progress(a[i + 1]) <= progress(b[j + 1]));
        if take_a {
            out.push([a[i], a[i + 1], b[j]]);
            i += 1;
        } else {
            out.push([b[j + 1], b[j], a[i]]);
            j += 1;
        }
    }
    out.push([a[a.len() - 1], ring[tr], b[b.len() - 1]]);
}

#[cfg(test)]
mod tests {
    use super::{direct_split, strip};
    use crate::{BSplineSurface, Points, QuerySurface};

    #[test]
    fn direct_split_takes_three_where_halving_leaves_too_much() {
        // A = 2 alone: halves have bound 2/32 = 0.0625, thirds 2/72 ≈ 0.028
        assert_eq!(
            direct_split((2.0, 0.0, 0.0), 0.03, (1 << 20, 1 << 20)),
            Some((3, 1))
        );
        assert_eq!(
            direct_split((0.0, 0.0, 2.0), 0.03, (1 << 20, 1 << 20)),
            Some((1, 3))
        );
        // halving is enough: no direct cut
        assert_eq!(
            direct_split((2.0, 0.0, 0.0), 0.07, (1 << 20, 1 << 20)),
            None
        );
        // both directions: A = C = 2, B = 0.5: 3 × 3 parts (bound ≈ 0.0694 · 8 / 8)
        assert_eq!(
            direct_split((2.0, 0.5, 2.0), 0.0721, (1 << 20, 1 << 20)),
            Some((3, 3))
        );
        // too narrow to cut into three
        assert_eq!(direct_split((2.0, 0.0, 0.0), 0.03, (5, 1 << 20)), None);
        // nothing within nine parts reaches the tolerance
        assert_eq!(
            direct_split((2.0, 0.0, 0.0), 1e-4, (1 << 20, 1 << 20)),
            None
        );
    }

    #[test]
    fn a_parabolic_cylinder_is_cut_into_thirds() {
        // z = x² on [0, 1]²: A = 2, B = C = 0; at tolerance 0.03 halving leaves 0.0625 and
        // thirds 2/72: three parts, six triangles, vertices at u = 1/3 and 2/3
        let net = Points::from_3d(&[
            [0., 0., 0.],
            [0., 1., 0.],
            [0.5, 0., 0.],
            [0.5, 1., 0.],
            [1., 0., 1.],
            [1., 1., 1.],
        ])
        .unwrap();
        let s = BSplineSurface::new(
            2,
            1,
            vec![0., 0., 0., 1., 1., 1.],
            vec![0., 0., 1., 1.],
            net,
            (3, 2),
        )
        .unwrap();
        let mesh = QuerySurface::from_bspline(&s).unwrap().mesh(0.03).unwrap();
        assert_eq!(mesh.triangles.len(), 6, "{mesh:?}");
        assert!(
            mesh.deviation <= 0.03 && mesh.deviation > 0.02,
            "{}",
            mesh.deviation
        );
        for third in [1.0 / 3.0, 2.0 / 3.0] {
            assert!(
                mesh.uv.iter().any(|p| (p[0] - third).abs() < 1e-12),
                "no vertex at u = {third}: {:?}",
                mesh.uv
            );
        }
        // the vertices lie on the surface
        for (p, uv) in mesh.vertices.iter().zip(&mesh.uv) {
            assert!((p[2] - uv[0] * uv[0]).abs() < 1e-15, "{p:?} at {uv:?}");
        }
    }

    #[test]
    fn strip_covers_the_rectangle_with_proper_triangles() {
        // the unit square's boundary, counter-clockwise from (0, 0), with extra side points
        let sides: [&[f64]; 4] = [&[0.25, 0.5], &[0.5], &[0.8, 0.3, 0.1], &[]];
        let mut pts: Vec<[f64; 2]> = vec![[0.0, 0.0]];
        pts.extend(sides[0].iter().map(|&u| [u, 0.0]));
        pts.push([1.0, 0.0]);
        pts.extend(sides[1].iter().map(|&v| [1.0, v]));
        let tr = pts.len();
        pts.push([1.0, 1.0]);
        pts.extend(sides[2].iter().map(|&u| [u, 1.0]));
        pts.push([0.0, 1.0]);
        pts.extend(sides[3].iter().map(|&v| [0.0, v]));
        let ring: Vec<u32> = (0..u32::try_from(pts.len()).unwrap()).collect();
        let mut tris = Vec::new();
        strip(
            &ring,
            tr,
            |i| pts[i as usize][0] + pts[i as usize][1],
            &mut tris,
        );
        assert_eq!(tris.len(), ring.len() - 2, "{tris:?}");
        let mut area = 0.0;
        for t in &tris {
            let [a, b, c] = t.map(|i| pts[i as usize]);
            let twice = (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]);
            assert!(
                twice > 1e-3,
                "{t:?} is not a proper counter-clockwise triangle"
            );
            area += 0.5 * twice;
        }
        assert!((area - 1.0).abs() < 1e-14, "area {area}");
    }
}
