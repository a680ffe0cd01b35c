//! Adaptive triangle meshes of surfaces within a proved deviation
//! (`docs/theory/queries.md#tessellation`): each patch is cut into parts, halved in `u` or in
//! `v` or near the end cut into a few equal parts, until the bound of every part is within the
//! tolerance; the parts' sides are then matched across parts and patches, so the mesh has no
//! cracks, and a part with extra points on its sides is a strip (polynomial, its triangles'
//! own bounds checked, the part split again where none of its triangulations is within the
//! tolerance) or a fan (rational) through them; the polynomial mesh is then thinned by removing
//! vertices where the fan of the polygon around one stays within the tolerance.

use std::sync::atomic::{AtomicUsize, Ordering};

use rayon::prelude::*;

use super::surface::QuerySurface;
use super::tessellate::{check_tol, Mesh, MAX_MESH_TRIANGLES, MAX_MESH_VERTICES};
use crate::error::{Error, Result};
use crate::Points;

/// Most halvings of a patch in one direction. A part's corners are integers in
/// `[0, 2^(MAX_LEVELS + 1)]` along each direction of its patch, so every part is at least two
/// units wide and its centre is an integer too.
const MAX_LEVELS: u32 = 40;
/// Integer width of a patch along each direction.
const PATCH_WIDTH: u64 = 1 << (MAX_LEVELS + 1);
/// Most parts a part is cut into at once ([`QuerySurface::poly_leaves`]).
const MAX_DIRECT_PARTS: usize = 9;
/// Most rounds of matching the parts' sides and splitting the parts none of whose
/// triangulations is within the tolerance, before every part is refined to the bound that
/// holds for any triangle inside it ([`QuerySurface::mesh_polynomial`]).
const MAX_ROUNDS: usize = 12;

/// A part's integer ranges on the global lattice: `((u0, u1), (v0, v1))`.
type Rect = ((u64, u64), (u64, u64));

/// A part of a patch that is meshed as a whole: its patch, its integer ranges inside the patch,
/// its deviation bound as two triangles, the diagonal of those (`anti`: from `(u1, v0)` to
/// `(u0, v1)`, otherwise from `(u0, v0)` to `(u1, v1)`), and its four corners (`(u0, v0)`,
/// `(u1, v0)`, `(u1, v1)`, `(u0, v1)`, normalised Cartesian points).
struct Leaf {
    patch: usize,
    u: (u64, u64),
    v: (u64, u64),
    bound: f64,
    anti: bool,
    corners: Vec<f64>,
}

/// Which bound a polynomial part must meet to be accepted.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Rule {
    /// Its two triangles' edge bound ([`triangle_bound`]), along the better diagonal.
    Edges,
    /// `(A + 2B + C)/8` ([`QuerySurface::net_bounds`]), which holds for every triangle inside
    /// the part.
    Any,
}

/// The Bezier nets of `S_uu`, `S_uv`, `S_vv` of a polynomial (sub-)patch in its own parameters
/// `[0, 1]²`, each degree-elevated to `(p, q)` and interleaved per control point
/// (`[U_ij, W_ij, V_ij]`, `dim` scalars each). The directional second derivative
/// `D²S[e, e] = e_u² S_uu + 2 e_u e_v S_uv + e_v² S_vv` is then the Bezier patch with net
/// `e_u² U_ij + 2 e_u e_v W_ij + e_v² V_ij`, so the largest norm of those points bounds
/// `|D²S[e, e]|` over the part (convex hull), for any `e`, with the cancellation between the
/// terms kept (`docs/theory/queries.md#tessellation`).
pub(crate) struct SecondNets {
    dim: usize,
    pts: Vec<f64>,
}

impl SecondNets {
    /// `M(e) ≥ max |D²S[e, e]|` over the part: the largest norm of the points
    /// `e_u² U_ij + 2 e_u e_v W_ij + e_v² V_ij`.
    pub(crate) fn along(&self, eu: f64, ev: f64) -> f64 {
        let (a, b, c) = (eu * eu, 2.0 * eu * ev, ev * ev);
        let dim = self.dim;
        let mut m = 0.0_f64;
        for x in self.pts.chunks_exact(3 * dim) {
            let mut s = 0.0;
            for d in 0..dim {
                let t = a * x[d] + b * x[dim + d] + c * x[2 * dim + d];
                s += t * t;
            }
            m = m.max(s);
        }
        m.sqrt()
    }

    /// The bound of the part as the two triangles of its diagonal along `(1, ±1)` (the `−`
    /// one, `anti`, when its bound is the smaller): [`triangle_bound`] of
    /// `M(1, 0)`, `M(0, 1)`, `M(1, ±1)`.
    fn two_triangles(&self) -> (f64, bool) {
        let (a, c) = (self.along(1.0, 0.0), self.along(0.0, 1.0));
        let main = triangle_bound([a, c, self.along(1.0, 1.0)]);
        let anti = triangle_bound([a, c, self.along(1.0, -1.0)]);
        if anti < main {
            (anti, true)
        } else {
            (main, false)
        }
    }

    /// The bound of every part of a cut into `k_u × k_v` equal parts as two triangles, from
    /// this net: a part's second-derivative nets lie in the convex hull of these with `e`
    /// scaled by `(1/k_u, 1/k_v)`, so its `M(1, 0) ≤ M(1, 0)/k_u²`, `M(0, 1) ≤ M(0, 1)/k_v²` and
    /// `M(1, ±1) ≤ M(1/k_u, ±1/k_v)`. `ac` is `(M(1, 0), M(0, 1))`.
    fn cut_bound(&self, ac: (f64, f64), ku: usize, kv: usize, tol: f64) -> f64 {
        let (fu, fv) = (ku as f64, kv as f64);
        let (a, c) = (ac.0 / (fu * fu), ac.1 / (fv * fv));
        // every triangle bound is at least a quarter of its largest side term, halved
        if a.max(c) / 8.0 > tol {
            return a.max(c) / 8.0;
        }
        let main = triangle_bound([a, c, self.along(1.0 / fu, 1.0 / fv)]);
        if main <= tol {
            return main;
        }
        main.min(triangle_bound([a, c, self.along(1.0 / fu, -1.0 / fv)]))
    }
}

/// `½ max (λ0 λ1 m01 + λ0 λ2 m02 + λ1 λ2 m12)` over the barycentric coordinates of a
/// triangle, for `m = [m01, m02, m12]` (any order): with `m_ij ≥ max |D²S[e_ij, e_ij]|` over
/// the triangle for its edge vectors `e_ij = P_j − P_i`, a bound on `|S − L|` over it, `L` the
/// linear interpolant at the vertices (`docs/theory/queries.md#tessellation`). The maximum is
/// at an edge's midpoint, `max m / 4`, unless with `a ≥ b, c` the three are "acute"
/// (`d = b + c − a > 0`), where it is the interior critical point, `abc / (4bc − d²)` (half the
/// squared circumradius of a triangle with squared sides `a, b, c`; `4bc − d² ≥ 3bc` there, so
/// the quotient loses no accuracy).
pub(crate) fn triangle_bound(m: [f64; 3]) -> f64 {
    let [x, y, z] = m;
    let (a, b, c) = if x >= y && x >= z {
        (x, y, z)
    } else if y >= z {
        (y, x, z)
    } else {
        (z, x, y)
    };
    let d = b + c - a;
    if d > 0.0 {
        0.5 * a * b * c / (4.0 * b * c - d * d)
    } else {
        a / 8.0
    }
}

/// Weights of the degree elevation of a Bezier curve from degree `n` to `n + r`:
/// `Q_k = Σ_j C(n, j) C(r, k − j) / C(n + r, k) P_j` (Farin §6.1), row `k`, column `j`; each
/// row is a convex combination.
fn elevation_weights(n: usize, r: usize) -> Vec<f64> {
    let binom = |n: usize, k: usize| (0..k).fold(1.0, |b, i| b * (n - i) as f64 / (i + 1) as f64);
    let mut w = vec![0.0; (n + r + 1) * (n + 1)];
    for k in 0..=n + r {
        for j in k.saturating_sub(r)..=n.min(k) {
            w[k * (n + 1) + j] = binom(n, j) * binom(r, k - j) / binom(n + r, k);
        }
    }
    w
}

/// A tensor Bezier net of degree `n = (n_u, n_v)` (row-major in `u`, `dim` scalars a point)
/// elevated by `r = (r_u, r_v)`.
fn elevate(net: &[f64], n: (usize, usize), r: (usize, usize), dim: usize) -> Vec<f64> {
    let (mu, mv) = (n.0 + r.0, n.1 + r.1);
    let (wu, wv) = (elevation_weights(n.0, r.0), elevation_weights(n.1, r.1));
    let mut rows = vec![0.0; (n.0 + 1) * (mv + 1) * dim];
    for i in 0..=n.0 {
        for l in 0..=mv {
            let out = &mut rows[(i * (mv + 1) + l) * dim..][..dim];
            for j in 0..=n.1 {
                let w = wv[l * (n.1 + 1) + j];
                if w != 0.0 {
                    let x = &net[(i * (n.1 + 1) + j) * dim..][..dim];
                    for d in 0..dim {
                        out[d] += w * x[d];
                    }
                }
            }
        }
    }
    let mut out = vec![0.0; (mu + 1) * (mv + 1) * dim];
    for k in 0..=mu {
        for i in 0..=n.0 {
            let w = wu[k * (n.0 + 1) + i];
            if w != 0.0 {
                for l in 0..(mv + 1) * dim {
                    out[k * (mv + 1) * dim + l] += w * rows[i * (mv + 1) * dim + l];
                }
            }
        }
    }
    out
}

/// The parts' corners on the global integer lattice: the mesh's vertices, one a point, each
/// with the part and corner it comes from, sorted by `(u, v)`, and the same sorted by `(v, u)`,
/// from which each part's boundary with every corner on its sides is read.
struct Lattice {
    keys: Vec<(u64, u64, u32, u8)>,
    by_v: Vec<(u64, u64, u32)>,
}

impl Lattice {
    #[allow(clippy::cast_possible_truncation)] // vertex indices: below MAX_MESH_VERTICES < 2^32
    fn new(rects: impl Iterator<Item = Rect>) -> Result<Self> {
        let mut keys: Vec<(u64, u64, u32, u8)> = Vec::new();
        for (n, (gu, gv)) in rects.enumerate() {
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
    fn ring(&self, ((u0, u1), (v0, v1)): Rect, ring: &mut Vec<u32>) -> [usize; 3] {
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
fn chains(ring: &[u32], s: usize, t: usize) -> (Vec<u32>, Vec<u32>) {
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
fn zip(s: u32, t: u32, a: &[u32], b: &[u32], moves: &[bool], out: &mut Vec<[u32; 3]>) {
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
fn best_zip(
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
}

impl QuerySurface {
    /// The nets of `S_uu`, `S_uv`, `S_vv` of the polynomial (sub-)patch with net `net`
    /// (`p(p−1) Δ²_u P`, `pq Δ_uΔ_v P`, `q(q−1) Δ²_v P`), each elevated to degree `(p, q)`
    /// ([`SecondNets`]).
    pub(crate) fn second_nets(&self, net: &[f64]) -> SecondNets {
        let (p, q, dim) = (self.p, self.q, self.dim);
        let at = |i: usize, j: usize, d: usize| net[(i * (q + 1) + j) * dim + d];
        let (pf, qf) = (p as f64, q as f64);
        let mut pts = vec![0.0; (p + 1) * (q + 1) * 3 * dim];
        let mut put = |slot: usize, elevated: Vec<f64>| {
            for (k, x) in elevated.chunks_exact(dim).enumerate() {
                pts[(3 * k + slot) * dim..][..dim].copy_from_slice(x);
            }
        };
        if p >= 2 {
            let mut uu = Vec::with_capacity((p - 1) * (q + 1) * dim);
            for i in 0..=p - 2 {
                for j in 0..=q {
                    for d in 0..dim {
                        uu.push(
                            pf * (pf - 1.0)
                                * (at(i + 2, j, d) - 2.0 * at(i + 1, j, d) + at(i, j, d)),
                        );
                    }
                }
            }
            put(0, elevate(&uu, (p - 2, q), (2, 0), dim));
        }
        if p >= 1 && q >= 1 {
            let mut uv = Vec::with_capacity(p * q * dim);
            for i in 0..p {
                for j in 0..q {
                    for d in 0..dim {
                        uv.push(
                            pf * qf
                                * (at(i + 1, j + 1, d) - at(i + 1, j, d) - at(i, j + 1, d)
                                    + at(i, j, d)),
                        );
                    }
                }
            }
            put(1, elevate(&uv, (p - 1, q - 1), (1, 1), dim));
        }
        if q >= 2 {
            let mut vv = Vec::with_capacity((p + 1) * (q - 1) * dim);
            for i in 0..=p {
                for j in 0..=q - 2 {
                    for d in 0..dim {
                        vv.push(
                            qf * (qf - 1.0)
                                * (at(i, j + 2, d) - 2.0 * at(i, j + 1, d) + at(i, j, d)),
                        );
                    }
                }
            }
            put(2, elevate(&vv, (p, q - 2), (0, 2), dim));
        }
        SecondNets { dim, pts }
    }

    /// The net of the part `u × v` (integer ranges) of patch `k` (de Casteljau at its ends).
    fn sub_net(&self, k: usize, u: (u64, u64), v: (u64, u64)) -> Vec<f64> {
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
    fn poly_leaves(
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
                        what: "mesh vertices",
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

/// The patches' places on the global lattice: patch `(i, j)` (the `i`-th `u` interval, the
/// `j`-th `v` interval) covers the integers `[i, i + 1]·PATCH_WIDTH × [j, j + 1]·PATCH_WIDTH`.
struct PatchGrid {
    us: Vec<(f64, f64)>,
    vs: Vec<(f64, f64)>,
    origin: Vec<(u64, u64)>,
}

impl PatchGrid {
    fn new(s: &QuerySurface) -> Self {
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

    fn rect(&self, l: &Leaf) -> Rect {
        let (ou, ov) = self.origin[l.patch];
        ((ou + l.u.0, ou + l.u.1), (ov + l.v.0, ov + l.v.1))
    }

    /// The surface parameters of the lattice point `(u, v)`.
    fn param(&self, u: u64, v: u64) -> [f64; 2] {
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
enum Plan {
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
    /// The parts of patch `k` of a rational surface within the normalised tolerance `tol`:
    /// halved (de Casteljau at the middle) in the direction whose terms dominate the bound
    /// `(A + 2B + C)/8` ([`QuerySurface::net_bounds`]), at most [`MAX_LEVELS`] times in each
    /// direction. `count` is the number of parts of every patch so far: past
    /// [`MAX_MESH_VERTICES`] this stops with [`Error::TooLarge`].
    fn rational_leaves(&self, k: usize, tol: f64, count: &AtomicUsize) -> Result<Vec<Leaf>> {
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
                    corners.extend(x[..dim].iter().map(|c| c / x[dim]));
                }
                out.push(Leaf {
                    patch: k,
                    u,
                    v,
                    bound,
                    anti: false,
                    corners,
                });
                continue;
            }
            let (l, h, u_parts, v_parts) = if split_u {
                let m = (u.0 + u.1) / 2;
                let (l, h) = self.halve_u(&net);
                (l, h, [(u.0, m), (m, u.1)], [v, v])
            } else {
                let m = (v.0 + v.1) / 2;
                let (l, h) = self.halve_v(&net);
                (l, h, [u, u], [(v.0, m), (m, v.1)])
            };
            stack.push((l, u_parts[0], v_parts[0]));
            stack.push((h, u_parts[1], v_parts[1]));
        }
        Ok(out)
    }

    /// A triangle mesh within `tolerance` of a surface, polynomial or rational, adaptive
    /// (`docs/theory/queries.md#tessellation`), so flat regions get large triangles and curved
    /// ones small. Each patch is cut into parts until every part is within `tolerance` as two
    /// triangles:
    ///
    /// * polynomial: a triangle whose edge vectors `e` have `M_e ≥ max |D²S[e, e]|` over it
    ///   deviates by at most `½ max (λ0 λ1 M01 + λ0 λ2 M02 + λ1 λ2 M12)` over its barycentric
    ///   coordinates ([`triangle_bound`]), and `M_e` comes for any `e` from the part's nets of
    ///   `S_uu`, `S_uv`, `S_vv` elevated to one degree ([`SecondNets`]), so the cross term
    ///   cancels where it can: each part takes the diagonal, `(1, 1)` or `(1, −1)`, with the
    ///   smaller bound; it is halved in the direction whose halves' bound is the smaller, or
    ///   cut into the fewest equal parts (at most nine) once that reaches the tolerance and
    ///   halving would not;
    /// * rational: `(A + 2B + C)/8` from its own net's differences (Leibniz for the weight,
    ///   [`QuerySurface::net_bounds`]), halved in `u` where the `u` terms dominate, in `v`
    ///   otherwise.
    ///
    /// Parts are matched along their sides, across patches too: a part whose sides carry
    /// corners of smaller neighbours is meshed through all of them, any other as two
    /// triangles, so the mesh has no cracks and no T-junctions. On a polynomial surface such a
    /// part is a strip of triangles between its sides with no interior point, its rungs along
    /// its diagonal, each triangle's bound computed from its own edge vectors; where one is
    /// above the tolerance the strip whose largest bound is least is taken (of either
    /// diagonal), else a fan about the part's centre, else the part is split and the sides
    /// matched again (at most [`MAX_ROUNDS`] rounds, then every part is cut until
    /// `(A + 2B + C)/8`, which holds for any triangle inside it, is within the tolerance). The
    /// polynomial mesh is then thinned: a vertex is removed, its polygon fanned from one corner,
    /// where every new triangle is within the tolerance with `M_e` the largest of the parts it
    /// covers ([`QuerySurface::decimate`]). On a rational surface, whose bound needs triangles
    /// no steeper than the part's diagonal, such a part is a fan about its centre. Vertices are
    /// the parts' corner control points (points of the surface) and the fans' centres. The
    /// reported deviation is the largest triangle bound. Patches are split in parallel; the
    /// mesh does not depend on the thread count.
    ///
    /// ```
    /// use lekalo::{BSplineSurface, Points, QuerySurface};
    /// // z = x² on [0, 1]²: M along (1, 0) and the diagonals 2, along (0, 1) 0: two triangles
    /// // deviate by 2/8, so 2/(8·4^k) ≤ 1e-3 after k = 4 halvings in u, none in v
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
    /// a tolerance below [`super::MIN_RELATIVE_TOLERANCE`] times the size, or a tolerance whose
    /// mesh is estimated (before meshing) at more than [`MAX_MESH_TRIANGLES`] triangles;
    /// [`Error::TooLarge`] beyond [`MAX_MESH_VERTICES`].
    pub fn mesh(&self, tolerance: f64) -> Result<Mesh> {
        check_tol(tolerance, self.scale)?;
        let tol = tolerance / self.scale;
        self.check_mesh_size(tolerance, tol)?;
        let grid = PatchGrid::new(self);
        if self.rational {
            self.mesh_rational(tol, &grid)
        } else {
            self.mesh_polynomial(tol, &grid, 0)
        }
    }

    /// Refuses a tolerance whose mesh would be too large to make, before any part is made:
    /// each patch is estimated at the `(A + 2B + C) / (8·tol)` parts (two triangles each) of
    /// its uniform split within the normalised tolerance `tol`, the bounds of
    /// [`Self::net_bounds`] shrinking with the square of a part's size. The adaptive split
    /// needs no more than a few times fewer where the curvature is concentrated.
    fn check_mesh_size(&self, tolerance: f64, tol: f64) -> Result<()> {
        let parts: f64 = (0..self.patch_count())
            .map(|k| {
                self.net_bounds(self.patch(k))
                    .map_or(1.0, |(a, b, c)| ((a + 2.0 * b + c) / (8.0 * tol)).max(1.0))
            })
            .sum();
        let triangles = 2.0 * parts;
        #[allow(clippy::cast_precision_loss)] // 2^25 is exact
        let max = MAX_MESH_TRIANGLES as f64;
        if triangles > max {
            return Err(Error::InvalidArgument {
                what: "tessellation tolerance",
                reason: format!(
                    "{tolerance:e} needs about {triangles:.1e} triangles, more than the \
                     {MAX_MESH_TRIANGLES} a mesh may have; use a tolerance of at least {:.1e}",
                    tolerance * triangles / max
                ),
            });
        }
        Ok(())
    }

    /// The vertices of the lattice (the corners of the parts they come from) and their
    /// parameters.
    fn lattice_vertices(
        &self,
        grid: &PatchGrid,
        lat: &Lattice,
        leaves: &[Leaf],
    ) -> (Vec<f64>, Vec<[f64; 2]>) {
        let dim = self.dim;
        let mut verts = Vec::with_capacity(dim * (lat.keys.len() + leaves.len() / 4));
        let mut uv = Vec::with_capacity(lat.keys.len() + leaves.len() / 4);
        let mut buf = vec![0.0; dim];
        for &(u, v, n, c) in &lat.keys {
            let l = &leaves[n as usize];
            self.denormalise(&l.corners[c as usize * dim..][..dim], &mut buf);
            verts.extend_from_slice(&buf);
            uv.push(grid.param(u, v));
        }
        (verts, uv)
    }

    /// A new vertex at the centre of part `l` (integer, so on the lattice): its index.
    fn centre_vertex(
        &self,
        grid: &PatchGrid,
        l: &Leaf,
        verts: &mut Vec<f64>,
        uv: &mut Vec<[f64; 2]>,
    ) -> Result<u32> {
        let centre = u32::try_from(uv.len()).map_err(|_| Error::TooLarge {
            what: "mesh vertices",
            size: uv.len(),
            max: MAX_MESH_VERTICES,
        })?;
        let ((u0, u1), (v0, v1)) = grid.rect(l);
        let (cu, cv) = ((u0 + u1) / 2, (v0 + v1) / 2);
        let local = |g: u64| (g % PATCH_WIDTH) as f64 / PATCH_WIDTH as f64;
        let mut scratch = Vec::new();
        let pt = self.point_on(l.patch, local(cu), local(cv), &mut scratch);
        let mut buf = vec![0.0; self.dim];
        self.denormalise(&pt, &mut buf);
        verts.extend_from_slice(&buf);
        uv.push(grid.param(cu, cv));
        Ok(centre)
    }

    fn finish(
        &self,
        verts: Vec<f64>,
        uv: Vec<[f64; 2]>,
        triangles: Vec<[u32; 3]>,
        deviation: f64,
    ) -> Result<Mesh> {
        if uv.len() > MAX_MESH_VERTICES {
            return Err(Error::TooLarge {
                what: "mesh vertices",
                size: uv.len(),
                max: MAX_MESH_VERTICES,
            });
        }
        Ok(Mesh {
            vertices: Points::from_flat(self.dim, verts)?,
            uv,
            triangles,
            deviation: deviation * self.scale,
        })
    }

    fn mesh_rational(&self, tol: f64, grid: &PatchGrid) -> Result<Mesh> {
        let count = AtomicUsize::new(0);
        let leaves: Vec<Leaf> = (0..self.patch_count())
            .into_par_iter()
            .map(|k| self.rational_leaves(k, tol, &count))
            .collect::<Result<Vec<_>>>()?
            .into_iter()
            .flatten()
            .collect();
        let lat = Lattice::new(leaves.iter().map(|l| grid.rect(l)))?;
        let (mut verts, mut uv) = self.lattice_vertices(grid, &lat, &leaves);
        let mut triangles = Vec::with_capacity(2 * leaves.len());
        let mut ring: Vec<u32> = Vec::new();
        let mut deviation = 0.0_f64;
        for l in &leaves {
            deviation = deviation.max(l.bound);
            lat.ring(grid.rect(l), &mut ring);
            if ring.len() == 4 {
                triangles.push([ring[0], ring[1], ring[2]]);
                triangles.push([ring[0], ring[2], ring[3]]);
                continue;
            }
            // the bound needs triangles no steeper than the diagonal: a fan about the centre
            let centre = self.centre_vertex(grid, l, &mut verts, &mut uv)?;
            for i in 0..ring.len() {
                triangles.push([centre, ring[i], ring[(i + 1) % ring.len()]]);
            }
        }
        self.finish(verts, uv, triangles, deviation)
    }

    /// The polynomial mesh: parts under [`Rule::Edges`], their sides matched, each part planned
    /// ([`QuerySurface::plan_part`]); the parts to split are split (at least once each) and
    /// the round repeated, at most [`MAX_ROUNDS`] times, then every part is refined under
    /// [`Rule::Any`], whose strips are all within the tolerance, for a last round. In the first
    /// `forced` rounds every part with points on its sides is split (tests of the rounds).
    fn mesh_polynomial(&self, tol: f64, grid: &PatchGrid, forced: usize) -> Result<Mesh> {
        let count = AtomicUsize::new(0);
        let whole = ((0, PATCH_WIDTH), (0, PATCH_WIDTH));
        let mut leaves: Vec<Leaf> = (0..self.patch_count())
            .into_par_iter()
            .map(|k| {
                let net = self.patch(k).to_vec();
                self.poly_leaves(k, net, whole, tol, Rule::Edges, false, &count)
            })
            .collect::<Result<Vec<_>>>()?
            .into_iter()
            .flatten()
            .collect();
        let mut rule = Rule::Edges;
        for round in 0..=MAX_ROUNDS {
            let lat = Lattice::new(leaves.iter().map(|l| grid.rect(l)))?;
            let may_split = rule == Rule::Edges;
            let force = may_split && round < forced;
            let plans: Vec<(Plan, f64)> = leaves
                .par_iter()
                .map(|l| self.plan_part(l, grid.rect(l), &lat, tol, may_split, force))
                .collect();
            let split: Vec<bool> = plans.iter().map(|p| matches!(p.0, Plan::Split)).collect();
            if !split.contains(&true) {
                return self.emit(grid, &lat, &leaves, plans, tol);
            }
            let refine_all = round + 1 >= MAX_ROUNDS;
            if refine_all {
                rule = Rule::Any;
            }
            let old = std::mem::take(&mut leaves);
            let refined: Vec<Vec<Leaf>> = old
                .into_par_iter()
                .zip(split.into_par_iter())
                .map(|(l, s)| {
                    if !(s || refine_all) {
                        return Ok(vec![l]);
                    }
                    count.fetch_sub(1, Ordering::Relaxed);
                    let net = self.sub_net(l.patch, l.u, l.v);
                    self.poly_leaves(l.patch, net, (l.u, l.v), tol, rule, s, &count)
                })
                .collect::<Result<_>>()?;
            leaves = refined.into_iter().flatten().collect();
        }
        unreachable!("the last round (Rule::Any) splits no part")
    }

    /// How part `l` (global integer ranges `r`) is triangulated through the lattice points on
    /// its sides, and the largest bound of its triangles. Two triangles where there are none;
    /// otherwise a strip ([`zip`]) with rungs along the part's diagonal, advancing on the chain
    /// whose next point comes first along that diagonal; each triangle's bound is the least of
    /// [`triangle_bound`] with its own edge vectors (`M_e` from the part's [`SecondNets`]) and
    /// `(A + 2B + C)/8`; if one is above `tol`, the strip of least largest bound of either
    /// diagonal ([`best_zip`]), else a fan about the centre, else ([`Plan::Split`], if
    /// `may_split` and the part is more than two units wide) a split; a split whenever it can
    /// if `force` (tests).
    fn plan_part(
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

    /// The mesh of the planned parts, then [`QuerySurface::decimate`]d.
    fn emit(
        &self,
        grid: &PatchGrid,
        lat: &Lattice,
        leaves: &[Leaf],
        plans: Vec<(Plan, f64)>,
        tol: f64,
    ) -> Result<Mesh> {
        let (mut verts, mut uv) = self.lattice_vertices(grid, lat, leaves);
        let mut at: Vec<(u64, u64)> = lat.keys.iter().map(|k| (k.0, k.1)).collect();
        let mut triangles = Vec::with_capacity(2 * leaves.len());
        let mut owner: Vec<u32> = Vec::with_capacity(2 * leaves.len());
        let mut ring: Vec<u32> = Vec::new();
        let mut deviation = 0.0_f64;
        for (n, (l, (plan, bound))) in leaves.iter().zip(plans).enumerate() {
            deviation = deviation.max(bound);
            match plan {
                Plan::Two => {
                    lat.ring(grid.rect(l), &mut ring);
                    let [a, b, c, d] = [ring[0], ring[1], ring[2], ring[3]];
                    if l.anti {
                        triangles.extend([[a, b, d], [b, c, d]]);
                    } else {
                        triangles.extend([[a, b, c], [a, c, d]]);
                    }
                }
                Plan::Strip(t) => triangles.extend(t),
                Plan::Fan => {
                    let r = grid.rect(l);
                    lat.ring(r, &mut ring);
                    let centre = self.centre_vertex(grid, l, &mut verts, &mut uv)?;
                    at.push(((r.0 .0 + r.0 .1) / 2, (r.1 .0 + r.1 .1) / 2));
                    for i in 0..ring.len() {
                        triangles.push([centre, ring[i], ring[(i + 1) % ring.len()]]);
                    }
                }
                Plan::Split => unreachable!("emitted only when no part is to be split"),
            }
            #[allow(clippy::cast_possible_truncation)] // parts: below MAX_MESH_VERTICES < 2^32
            owner.resize(triangles.len(), n as u32);
        }
        {
            let worst = self.decimate(leaves, &at, &mut triangles, &owner, tol);
            deviation = deviation.max(worst);
            // drop the vertices no triangle uses any more
            let mut map = vec![u32::MAX; uv.len()];
            for t in &triangles {
                for &i in t {
                    map[i as usize] = 0;
                }
            }
            let mut next = 0_u32;
            let dim = self.dim;
            let mut kept_v = Vec::with_capacity(verts.len());
            let mut kept_uv = Vec::with_capacity(uv.len());
            for i in 0..uv.len() {
                if map[i] == 0 {
                    map[i] = next;
                    next += 1;
                    kept_v.extend_from_slice(&verts[i * dim..(i + 1) * dim]);
                    kept_uv.push(uv[i]);
                }
            }
            for t in &mut triangles {
                for i in t.iter_mut() {
                    *i = map[*i as usize];
                }
            }
            verts = kept_v;
            uv = kept_uv;
        }
        self.finish(verts, uv, triangles, deviation)
    }

    /// Removes vertices while the mesh stays within `tol`: for each vertex in turn whose
    /// triangles all lie in parts of one patch (`owner`: the part of each triangle) and close
    /// around it, the fan of the polygon around it from the corner whose fan has the least
    /// largest bound replaces them (two triangles fewer) if every fan triangle is
    /// counter-clockwise with positive area (the fan then covers the same polygon) and within
    /// `tol`. A new triangle lies inside the removed ones, hence inside their parts, so
    /// `M_e` over it is at most the largest of those parts' `M_e` ([`SecondNets`]); its parts
    /// are theirs (`docs/theory/queries.md#tessellation`). Returns the largest bound of a new
    /// triangle.
    // triangles, parts and vertices: each below 4·MAX_MESH_VERTICES < 2^32, and a removal
    // adds at most ten
    #[allow(clippy::cast_possible_truncation)]
    fn decimate(
        &self,
        leaves: &[Leaf],
        at: &[(u64, u64)],
        triangles: &mut Vec<[u32; 3]>,
        owner: &[u32],
        tol: f64,
    ) -> f64 {
        use std::collections::HashMap;
        let nl = leaves.len();
        // the parts of each triangle: its owner, or a set in `unions` for new triangles
        let mut part: Vec<u32> = owner.to_vec();
        let mut unions: Vec<Vec<u32>> = Vec::new();
        let mut alive = vec![true; triangles.len()];
        let mut inc: Vec<Vec<u32>> = vec![Vec::new(); at.len()];
        for (t, tri) in triangles.iter().enumerate() {
            for &v in tri {
                inc[v as usize].push(t as u32);
            }
        }
        let mut cache: HashMap<u32, SecondNets> = HashMap::new();
        let mut worst = 0.0_f64;
        let mut parts: Vec<u32> = Vec::new();
        let mut next: HashMap<u32, u32> = HashMap::new();
        let mut memo: Vec<f64> = Vec::new();
        for h in 0..at.len() {
            let ts = &inc[h];
            if ts.len() < 3 || ts.len() > 12 {
                continue;
            }
            parts.clear();
            for &t in ts {
                let p = part[t as usize] as usize;
                if p < nl {
                    parts.push(p as u32);
                } else {
                    parts.extend_from_slice(&unions[p - nl]);
                }
            }
            parts.sort_unstable();
            parts.dedup();
            let patch = leaves[parts[0] as usize].patch;
            if parts.len() > 16 || parts.iter().any(|&p| leaves[p as usize].patch != patch) {
                continue;
            }
            // the polygon around h, counter-clockwise
            next.clear();
            let mut ok = true;
            for &t in ts {
                let [a, b, c] = triangles[t as usize];
                let h32 = h as u32;
                let (x, y) = if a == h32 {
                    (b, c)
                } else if b == h32 {
                    (c, a)
                } else {
                    (a, b)
                };
                if next.insert(x, y).is_some() {
                    ok = false;
                }
            }
            if !ok {
                continue;
            }
            let m = ts.len();
            let mut poly = Vec::with_capacity(m);
            let start = triangles[ts[0] as usize]
                .into_iter()
                .find(|&v| v as usize != h)
                .expect("a triangle has other vertices");
            let mut cur = start;
            for k in 0..m {
                poly.push(cur);
                match next.get(&cur) {
                    // one cycle through all m: back at the start only after the last
                    Some(&n) if (n == start) == (k + 1 == m) => cur = n,
                    _ => {
                        ok = false;
                        break;
                    }
                }
            }
            if !ok {
                continue;
            }
            if cache.len() > 4096 {
                cache.clear();
            }
            for &p in &parts {
                cache.entry(p).or_insert_with(|| {
                    let l = &leaves[p as usize];
                    self.second_nets(&self.sub_net(l.patch, l.u, l.v))
                });
            }
            let sns: Vec<(&SecondNets, f64, f64)> = parts
                .iter()
                .map(|p| {
                    let l = &leaves[*p as usize];
                    (&cache[p], (l.u.1 - l.u.0) as f64, (l.v.1 - l.v.0) as f64)
                })
                .collect();
            // M along each segment between two corners of the polygon, on demand
            memo.clear();
            memo.resize(m * m, f64::NAN);
            let mut edge = |i: usize, j: usize| {
                let (i, j) = (i.min(j), i.max(j));
                if memo[i * m + j].is_nan() {
                    let (a, b) = (at[poly[i] as usize], at[poly[j] as usize]);
                    let (du, dv) = (b.0 as f64 - a.0 as f64, b.1 as f64 - a.1 as f64);
                    memo[i * m + j] = sns
                        .iter()
                        .map(|(sn, wu, wv)| sn.along(du / wu, dv / wv))
                        .fold(0.0, f64::max);
                }
                memo[i * m + j]
            };
            let area = |i: u32, j: u32, k: u32| {
                let (a, b, c) = (at[i as usize], at[j as usize], at[k as usize]);
                let d = |x: u64, y: u64| i128::from(x) - i128::from(y);
                d(b.0, a.0) * d(c.1, a.1) - d(c.0, a.0) * d(b.1, a.1)
            };
            let mut best: Option<(usize, f64)> = None;
            'apex: for i in 0..m {
                let mut worst_here = 0.0_f64;
                for j in 1..m - 1 {
                    let (x, y, z) = (poly[i], poly[(i + j) % m], poly[(i + j + 1) % m]);
                    if area(x, y, z) <= 0 {
                        continue 'apex;
                    }
                }
                for j in 1..m - 1 {
                    let (y, z) = ((i + j) % m, (i + j + 1) % m);
                    let b = triangle_bound([edge(i, y), edge(i, z), edge(y, z)]);
                    worst_here = worst_here.max(b);
                    if worst_here > tol || best.is_some_and(|(_, w)| worst_here >= w) {
                        continue 'apex;
                    }
                }
                best = Some((i, worst_here));
            }
            let Some((i, b)) = best else { continue };
            worst = worst.max(b);
            let old: Vec<u32> = inc[h].drain(..).collect();
            for &t in &old {
                alive[t as usize] = false;
                for v in triangles[t as usize] {
                    inc[v as usize].retain(|&x| x != t);
                }
            }
            unions.push(parts.clone());
            let id = (nl + unions.len() - 1) as u32;
            for j in 1..m - 1 {
                let tri = [poly[i], poly[(i + j) % m], poly[(i + j + 1) % m]];
                let t = triangles.len() as u32;
                triangles.push(tri);
                alive.push(true);
                part.push(id);
                for v in tri {
                    inc[v as usize].push(t);
                }
            }
        }
        let mut k = 0;
        triangles.retain(|_| {
            k += 1;
            alive[k - 1]
        });
        worst
    }
}

#[cfg(test)]
mod tests {
    use super::{best_zip, chains, triangle_bound, zip, Rule, PATCH_WIDTH};
    use crate::query::tessellate::tests::{assert_covers_the_domain, assert_watertight};
    use crate::query::tessellate::Mesh;
    use crate::{BSplineSurface, Points, QuerySurface};
    use std::sync::atomic::AtomicUsize;

    /// `|S(Σ λ_i uv_i) − Σ λ_i P_i|` at the barycentric point `l` of triangle `t` of `mesh`: the
    /// parametric deviation the mesh's bound is about.
    fn sampled_deviation(s: &BSplineSurface, mesh: &Mesh, t: &[u32; 3], l: &[f64; 3]) -> f64 {
        let uv = t.map(|i| mesh.uv[i as usize]);
        let p = t.map(|i| mesh.vertices.point(i as usize).to_vec());
        let x =
            [0, 1].map(|d| (l[0] * uv[0][d] + l[1] * uv[1][d] + l[2] * uv[2][d]).clamp(0.0, 1.0));
        let sx = s.eval(x[0], x[1]).unwrap();
        (0..3)
            .map(|d| (sx[d] - (l[0] * p[0][d] + l[1] * p[1][d] + l[2] * p[2][d])).powi(2))
            .sum::<f64>()
            .sqrt()
    }

    #[test]
    fn tiny_tolerances_are_refused_before_meshing() {
        // z = x² + y² on [0, 1]²: a tolerance of 1e-8 asked for ~10^8 triangles and the process
        // was killed for its memory; the estimate refuses it at once, naming the tolerance
        let net = Points::from_3d(&[
            [0.0, 0.0, 0.0],
            [0.0, 0.5, 0.0],
            [0.0, 1.0, 1.0],
            [0.5, 0.0, 0.0],
            [0.5, 0.5, 0.0],
            [0.5, 1.0, 1.0],
            [1.0, 0.0, 1.0],
            [1.0, 0.5, 1.0],
            [1.0, 1.0, 2.0],
        ])
        .unwrap();
        let knots = vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0];
        let s = BSplineSurface::new(2, 2, knots.clone(), knots, net, (3, 3)).unwrap();
        let q = QuerySurface::from_bspline(&s).unwrap();
        let start = std::time::Instant::now();
        let e = q.mesh(1e-8).unwrap_err().to_string();
        assert!(start.elapsed().as_secs() < 5, "refused before meshing");
        assert!(
            e.contains("tessellation tolerance")
                && e.contains("1e-8 needs about")
                && e.contains("use a tolerance of at least"),
            "{e}"
        );
        // the tolerance the message suggests is accepted, and meshes below the limit
        let at_least: f64 = e.rsplit(' ').next().unwrap().parse().unwrap();
        assert!(at_least > 1e-8 && at_least < 1e-4, "{at_least}");
        let m = q.mesh(1e-3).unwrap();
        assert!(
            m.triangles.len() < super::MAX_MESH_TRIANGLES,
            "a small mesh is made"
        );
    }

    /// A small deterministic generator of numbers in `[0, 1)` (xorshift).
    struct Rng(u64);
    impl Rng {
        fn next(&mut self) -> f64 {
            self.0 ^= self.0 << 13;
            self.0 ^= self.0 >> 7;
            self.0 ^= self.0 << 17;
            (self.0 >> 11) as f64 / (1_u64 << 53) as f64
        }
    }

    /// Barycentric points of a triangle on a grid of step `1/n`.
    fn barycentric(n: usize) -> Vec<[f64; 3]> {
        let mut out = Vec::new();
        for i in 0..=n {
            for j in 0..=n - i {
                let (a, b) = (i as f64 / n as f64, j as f64 / n as f64);
                out.push([a, b, 1.0 - a - b]);
            }
        }
        out
    }

    #[test]
    fn triangle_bound_is_attained_by_convex_quadratics_and_never_exceeded() {
        // S(x) = ½ xᵀ H_d x per coordinate d: D²S[e, e] = eᵀ H_d e is constant and
        // S − L = −½ Σ λiλj D²S[e_ij, e_ij] exactly; with one coordinate and H positive
        // definite every term has the same sign, so the bound is the maximum itself
        let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
        let grid = barycentric(60);
        for case in 0..200 {
            let dim = if case % 2 == 0 { 1 } else { 3 };
            let hs: Vec<[f64; 3]> = (0..dim)
                .map(|_| {
                    let (a, c) = (rng.next() * 4.0, rng.next() * 4.0);
                    let b = if dim == 1 {
                        (2.0 * rng.next() - 1.0) * (a * c).sqrt() // positive semi-definite
                    } else {
                        4.0 * rng.next() - 2.0 // indefinite too
                    };
                    [a, b, c]
                })
                .collect();
            let s = |x: [f64; 2]| -> Vec<f64> {
                hs.iter()
                    .map(|h| {
                        0.5 * (h[0] * x[0] * x[0] + 2.0 * h[1] * x[0] * x[1] + h[2] * x[1] * x[1])
                    })
                    .collect()
            };
            let m = |e: [f64; 2]| {
                hs.iter()
                    .map(|h| {
                        (h[0] * e[0] * e[0] + 2.0 * h[1] * e[0] * e[1] + h[2] * e[1] * e[1]).powi(2)
                    })
                    .sum::<f64>()
                    .sqrt()
            };
            let v: Vec<[f64; 2]> = (0..3).map(|_| [rng.next(), rng.next()]).collect();
            let e = |i: usize, j: usize| [v[j][0] - v[i][0], v[j][1] - v[i][1]];
            let bound = triangle_bound([m(e(0, 1)), m(e(0, 2)), m(e(1, 2))]);
            let sv: Vec<Vec<f64>> = v.iter().map(|&x| s(x)).collect();
            let mut worst = 0.0_f64;
            for l in &grid {
                let x = [0, 1].map(|d| l[0] * v[0][d] + l[1] * v[1][d] + l[2] * v[2][d]);
                let sx = s(x);
                let dev = (0..dim)
                    .map(|d| {
                        (sx[d] - (l[0] * sv[0][d] + l[1] * sv[1][d] + l[2] * sv[2][d])).powi(2)
                    })
                    .sum::<f64>()
                    .sqrt();
                worst = worst.max(dev);
            }
            assert!(
                worst <= bound * (1.0 + 1e-12) + 1e-15,
                "case {case}: {worst} > {bound}"
            );
            if dim == 1 {
                // the grid's best point is within 1/60 of the maximum's: nearly attained
                assert!(
                    worst >= 0.99 * bound,
                    "case {case}: {worst} far below {bound}"
                );
            }
        }
    }

    #[test]
    fn triangle_bound_holds_on_random_cubic_patches() {
        // random bicubic patches, random triangles inside them: M_e from the patch's combined
        // second-derivative net, the deviation sampled densely
        let mut rng = Rng(42);
        let grid = barycentric(24);
        for case in 0..40 {
            let net: Vec<f64> = (0..16)
                .flat_map(|k| [(k / 4) as f64 / 3.0, (k % 4) as f64 / 3.0, 0.0])
                .zip(std::iter::repeat_with(|| rng.next()))
                .map(|(x, r)| x + 0.6 * (r - 0.5))
                .collect();
            let knots = vec![0., 0., 0., 0., 1., 1., 1., 1.];
            let surf = BSplineSurface::new(
                3,
                3,
                knots.clone(),
                knots,
                Points::from_flat(3, net).unwrap(),
                (4, 4),
            )
            .unwrap();
            let q = QuerySurface::from_bspline(&surf).unwrap();
            let sn = q.second_nets(q.patch(0));
            for _ in 0..10 {
                let size = 0.05 + 0.9 * rng.next();
                let o = [rng.next() * (1.0 - size), rng.next() * (1.0 - size)];
                let v: Vec<[f64; 2]> = (0..3)
                    .map(|_| [o[0] + size * rng.next(), o[1] + size * rng.next()])
                    .collect();
                let e = |i: usize, j: usize| sn.along(v[j][0] - v[i][0], v[j][1] - v[i][1]);
                let bound = triangle_bound([e(0, 1), e(0, 2), e(1, 2)]);
                let pts: Vec<Vec<f64>> = v
                    .iter()
                    .map(|x| q.point_on(0, x[0], x[1], &mut Vec::new()))
                    .collect();
                for l in &grid {
                    let x = [0, 1].map(|d| l[0] * v[0][d] + l[1] * v[1][d] + l[2] * v[2][d]);
                    let sx = q.point_on(0, x[0], x[1], &mut Vec::new());
                    let dev = (0..3)
                        .map(|d| {
                            (sx[d] - (l[0] * pts[0][d] + l[1] * pts[1][d] + l[2] * pts[2][d]))
                                .powi(2)
                        })
                        .sum::<f64>()
                        .sqrt();
                    assert!(
                        dev <= bound * (1.0 + 1e-9) + 1e-14,
                        "case {case}: {dev} > {bound}"
                    );
                }
            }
        }
    }

    #[test]
    fn random_surfaces_are_meshed_within_their_bound_without_cracks() {
        // bicubic 3 × 4-patch surfaces with random heights and a random twist: strips, the
        // best strips and vertex removal all occur; every triangle, densely sampled, within
        // the reported bound, the mesh closed and its parameter triangles tiling the domain
        let mut rng = Rng(7);
        let grid = barycentric(6);
        for case in 0..6 {
            let twist = 4.0 * rng.next() - 2.0;
            let s = random_surface(&mut rng, twist);
            let q = QuerySurface::from_bspline(&s).unwrap();
            let tol = [1e-3, 3e-4][case % 2];
            let mesh = q.mesh(tol).unwrap();
            assert!(mesh.deviation <= tol, "case {case}: {}", mesh.deviation);
            for t in &mesh.triangles {
                for l in &grid {
                    let dev = sampled_deviation(&s, &mesh, t, l);
                    assert!(
                        dev <= mesh.deviation * (1.0 + 1e-9),
                        "case {case}: {dev} > {} in {t:?}",
                        mesh.deviation
                    );
                }
            }
            assert_watertight(&mesh);
            assert_covers_the_domain(&mesh, &format!("case {case}"));
            // every vertex is used
            let mut used = vec![false; mesh.uv.len()];
            for t in &mesh.triangles {
                for &i in t {
                    used[i as usize] = true;
                }
            }
            assert!(used.iter().all(|&u| u), "case {case}: an unused vertex");
        }
    }

    /// A bicubic 3 × 4-patch surface with random heights and twist `twist`.
    fn random_surface(rng: &mut Rng, twist: f64) -> BSplineSurface {
        let (nu, nv) = (6, 7);
        let mut net = Vec::new();
        for i in 0..nu {
            for j in 0..nv {
                let (x, y) = (i as f64 / 5.0, j as f64 / 6.0);
                net.extend([x, y, twist * (x - 0.5) * (y - 0.5) + 0.3 * rng.next()]);
            }
        }
        let ku = vec![0., 0., 0., 0., 0.3, 0.5, 1., 1., 1., 1.];
        let kv = vec![0., 0., 0., 0., 0.2, 0.5, 0.7, 1., 1., 1., 1.];
        BSplineSurface::new(3, 3, ku, kv, Points::from_flat(3, net).unwrap(), (nu, nv)).unwrap()
    }

    #[test]
    fn parts_split_in_later_rounds_keep_the_mesh_closed_and_bounded() {
        // every part with points on its sides split in the first rounds (as if none of its
        // triangulations were within the tolerance), then, past the last round, every part
        // refined to (A + 2B + C)/8: the sides are matched again each round
        let mut rng = Rng(11);
        let s = random_surface(&mut rng, 1.5);
        let q = QuerySurface::from_bspline(&s).unwrap();
        let grid = super::PatchGrid::new(&q);
        let tol = 3e-3;
        let plain = q.mesh(tol).unwrap();
        for forced in [2, super::MAX_ROUNDS + 1] {
            let mesh = q.mesh_polynomial(tol / q.scale(), &grid, forced).unwrap();
            assert!(mesh.deviation <= tol, "forced {forced}: {}", mesh.deviation);
            assert!(
                mesh.triangles.len() > plain.triangles.len(),
                "forced {forced}: no part was split"
            );
            assert_watertight(&mesh);
            assert_covers_the_domain(&mesh, &format!("forced {forced}"));
            // (past the last round, 46,710 triangles against 817: every 7th)
            let samples = barycentric(4);
            for t in mesh
                .triangles
                .iter()
                .step_by(if forced > 2 { 7 } else { 1 })
            {
                for l in &samples {
                    let dev = sampled_deviation(&s, &mesh, t, l);
                    assert!(
                        dev <= mesh.deviation * (1.0 + 1e-9),
                        "forced {forced}: {dev}"
                    );
                }
            }
        }
    }

    #[test]
    fn a_twisted_surface_takes_the_cancelling_diagonal() {
        // heights 0.2 (x² + y² − 3xy) at the Greville points of a bicubic 4 × 4-patch spline:
        // S_uv dominates and has the sign opposite S_uu and S_vv, so |S_uu + 2S_uv + S_vv| is
        // far below |S_uu| + 2|S_uv| + |S_vv|
        let n = 7;
        let knots = vec![0., 0., 0., 0., 0.25, 0.5, 0.75, 1., 1., 1., 1.];
        let greville: Vec<f64> = (0..n)
            .map(|i| (knots[i + 1] + knots[i + 2] + knots[i + 3]) / 3.0)
            .collect();
        let net: Vec<f64> = greville
            .iter()
            .flat_map(|&x| {
                greville
                    .iter()
                    .flat_map(move |&y| [x, y, 0.2 * (x * x + y * y - 3.0 * x * y)])
            })
            .collect();
        let s = BSplineSurface::new(
            3,
            3,
            knots.clone(),
            knots,
            Points::from_flat(3, net).unwrap(),
            (n, n),
        )
        .unwrap();
        let q = QuerySurface::from_bspline(&s).unwrap();
        let tol = 2e-5;
        let mesh = q.mesh(tol).unwrap();
        assert!(mesh.deviation <= tol, "{}", mesh.deviation);
        // the rule with the cross term at its worst sign, (A + 2B + C)/8 for every part
        // (halving), needs at least two triangles a part; this mesh, fewer than half as many
        // (8,192 triangles against 16,384 parts)
        let count = AtomicUsize::new(0);
        let whole = ((0, PATCH_WIDTH), (0, PATCH_WIDTH));
        let any: usize = (0..q.patch_count())
            .map(|k| {
                let t = tol / q.scale();
                q.poly_leaves(k, q.patch(k).to_vec(), whole, t, Rule::Any, false, &count)
                    .unwrap()
                    .len()
            })
            .sum();
        assert!(
            mesh.triangles.len() < any,
            "{} triangles against {} parts of the any-triangle rule",
            mesh.triangles.len(),
            any
        );
        // every triangle, densely sampled, within the bound
        let grid = barycentric(8);
        for t in &mesh.triangles {
            for l in &grid {
                let dev = sampled_deviation(&s, &mesh, t, l);
                assert!(
                    dev <= mesh.deviation * (1.0 + 1e-9),
                    "{dev} > {} in {t:?}",
                    mesh.deviation
                );
            }
        }
        assert_watertight(&mesh);
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
    fn strips_cover_the_rectangle_with_proper_triangles() {
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
        // both pairs of opposite corners, with the moves in every order
        let br = 1 + sides[0].len();
        let tl = tr + 1 + sides[2].len();
        for (s, t) in [(0, tr), (br, tl)] {
            let (a, b) = chains(&ring, s, t);
            let steps = a.len() + b.len() - 2;
            for order in 0..1_u32 << steps {
                let moves: Vec<bool> = (0..steps).map(|k| order >> k & 1 == 1).collect();
                if moves.iter().filter(|&&m| m).count() != a.len() - 1 {
                    continue;
                }
                let mut tris = Vec::new();
                zip(ring[s], ring[t], &a, &b, &moves, &mut tris);
                assert_proper_cover(&pts, &tris, ring.len());
            }
        }
    }

    #[test]
    fn best_zip_finds_the_least_largest_cost() {
        // random costs of triangles (a function of their vertex sets): the dynamic programme's
        // strip against every order of the moves
        let mut rng = Rng(3);
        for case in 0..50_u32 {
            let (na, nb) = (1 + case % 4, 1 + (case / 4) % 4);
            let a: Vec<u32> = (1..=na).collect();
            let b: Vec<u32> = (100..100 + nb).collect();
            let (s, t) = (0_u32, 50_u32);
            let salt = rng.next();
            let cost = |x: u32, y: u32, z: u32| {
                let mut v = [x, y, z];
                v.sort_unstable();
                let h = v
                    .iter()
                    .fold(salt, |h, &k| (h * 7.31 + f64::from(k) * 0.123).fract());
                h
            };
            let (moves, best) = best_zip(s, t, &a, &b, &cost);
            let largest = |moves: &[bool]| {
                let mut tris = Vec::new();
                zip(s, t, &a, &b, moves, &mut tris);
                tris.iter()
                    .map(|t| cost(t[0], t[1], t[2]))
                    .fold(0.0, f64::max)
            };
            assert_eq!(moves.len(), (na + nb - 2) as usize, "case {case}");
            assert_eq!(largest(&moves), best, "case {case}");
            let steps = na + nb - 2;
            for order in 0..1_u32 << steps {
                let m: Vec<bool> = (0..steps).map(|k| order >> k & 1 == 1).collect();
                if m.iter().filter(|&&x| x).count() == (na - 1) as usize {
                    assert!(largest(&m) >= best, "case {case}: {m:?} beats {moves:?}");
                }
            }
        }
    }

    /// `tris` are `n − 2` counter-clockwise triangles, none degenerate, covering the unit
    /// square.
    fn assert_proper_cover(pts: &[[f64; 2]], tris: &[[u32; 3]], n: usize) {
        assert_eq!(tris.len(), n - 2, "{tris:?}");
        let mut area = 0.0;
        for t in tris {
            let [a, b, c] = t.map(|i| pts[i as usize]);
            let twice = (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]);
            assert!(
                twice > 1e-3,
                "{t:?} is not a proper counter-clockwise triangle in {tris:?}"
            );
            area += 0.5 * twice;
        }
        assert!((area - 1.0).abs() < 1e-14, "area {area}");
    }
}
