//! Deviation bounds of parts and triangles: the second-derivative nets of a polynomial part,
//! the bound of one triangle from its edge vectors, `(A + 2B + C)/8` of a (rational) net, and
//! the degree elevation the nets need.

use crate::query::surface::QuerySurface;

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
    pub(super) fn two_triangles(&self) -> (f64, bool) {
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
    pub(super) fn cut_bound(&self, ac: (f64, f64), ku: usize, kv: usize, tol: f64) -> f64 {
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

impl QuerySurface {
    /// Bounds `(A, B, C)` on `|S_uu|`, `|S_uv|`, `|S_vv|` of the (sub-)patch with homogeneous net
    /// `net`, in its own parameters `[0, 1]²`, such that the linear interpolant over any triangle
    /// of the part's grid split (two triangles) or of its fan about the centre deviates from the
    /// part by at most `(A + 2B + C) / 8` (`docs/theory/queries.md#tessellation`).
    ///
    /// Polynomial: `A = p(p−1)·max|Δ²_u P|`, `B = pq·max|Δ_uΔ_v P|`, `C = q(q−1)·max|Δ²_v P|`
    /// (the derivatives are Bezier patches with those nets; convex hull).
    ///
    /// Rational `S = P/w` (weights `w ≥ w_min > 0`; the standard quotient-rule estimates,
    /// Floater, *Derivatives of rational Bézier curves*, CAGD 9, 1992, and Zheng & Sederberg,
    /// *Estimating tessellation parameter intervals for rational curves and surfaces*, ACM TOG
    /// 19, 2000, applied to the surface less an affine map): with `Λ = c + a u + b v` the affine
    /// map fitted to the part's four corners (points of the surface) and `h = S − Λ = g/w`,
    /// `g = P − wΛ` is a polynomial whose Bezier net of degree `(p + 1, q + 1)` is formed
    /// exactly (`u·B_i^p = (i + 1)/(p + 1)·B_{i+1}^{p+1}`, then degree elevation), so its
    /// differences keep the cancellation of a part that is straight in one direction. `Λ` is
    /// affine, so `S_uu = h_uu` and by Leibniz
    /// `h_uu = (g_uu − 2 w_u h_u − w_uu h)/w`, `h_uv = (g_uv − w_u h_v − w_v h_u − w_uv h)/w`,
    /// `h_u = (g_u − w_u h)/w`, with `|h| ≤ R = max |g_ij|/w'_ij` (`w'` the weights elevated
    /// alike; convex hull). These bound the surface's own second derivatives, so they hold for
    /// any triangle inside the part, and shrink to them as the part does (`R`, `h_u`, `h_v`
    /// are of second and first order in its size; `docs/theory/queries.md#tessellation`).
    /// `None` if a weight is not positive.
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
        for i in 0..=p {
            for j in 0..=q {
                w_min = w_min.min(w(i, j));
            }
        }
        if !(w_min > 0.0) {
            return None;
        }
        // Λ = c + a u + b v: the least-squares affine fit to the four corners
        let corner = |i: usize, j: usize, d: usize| net[at(i, j) + d] / w(i, j);
        let (mut a, mut b, mut c) = (vec![0.0; dim], vec![0.0; dim], vec![0.0; dim]);
        for d in 0..dim {
            let (s00, s10) = (corner(0, 0, d), corner(p, 0, d));
            let (s01, s11) = (corner(0, q, d), corner(p, q, d));
            a[d] = 0.5 * ((s10 - s00) + (s11 - s01));
            b[d] = 0.5 * ((s01 - s00) + (s11 - s10));
            c[d] = 0.25 * (s00 + s10 + s01 + s11) - 0.5 * (a[d] + b[d]);
        }
        // the nets of u·w (degree (p + 1, q)) and v·w (degree (p, q + 1)), both elevated to
        // (p + 1, q + 1), as is the homogeneous net
        let (pe, qe) = (p + 1, q + 1);
        let mut uw = vec![0.0; (pe + 1) * (q + 1)];
        for k in 1..=pe {
            for j in 0..=q {
                uw[k * (q + 1) + j] = k as f64 / pe as f64 * w(k - 1, j);
            }
        }
        let uw = elevate(&uw, (pe, q), (0, 1), 1);
        let mut vw = vec![0.0; (p + 1) * (qe + 1)];
        for i in 0..=p {
            for l in 1..=qe {
                vw[i * (qe + 1) + l] = l as f64 / qe as f64 * w(i, l - 1);
            }
        }
        let vw = elevate(&vw, (p, qe), (1, 0), 1);
        let elevated = elevate(net, (p, q), (1, 1), hd);
        // g = P − wΛ, and R ≥ |g/w|
        let mut g = vec![0.0; (pe + 1) * (qe + 1) * dim];
        let mut radius = 0.0_f64;
        for (k, x) in elevated.chunks_exact(hd).enumerate() {
            let mut r2 = 0.0;
            for d in 0..dim {
                let t = x[d] - c[d] * x[dim] - a[d] * uw[k] - b[d] * vw[k];
                g[k * dim + d] = t;
                r2 += t * t;
            }
            // an elevated weight is a convex combination of weights, at least w_min
            radius = radius.max(r2.sqrt() / x[dim]);
        }
        let gd = difference_bounds(&g, (pe, qe), dim);
        let weights: Vec<f64> = net.chunks_exact(hd).map(|x| x[dim]).collect();
        let wd = difference_bounds(&weights, (p, q), 1);
        // |h_u|, |h_v|
        let hu = (gd[3] + wd[3] * radius) / w_min;
        let hv = (gd[4] + wd[4] * radius) / w_min;
        Some((
            (gd[0] + 2.0 * wd[3] * hu + wd[0] * radius) / w_min,
            (gd[1] + wd[3] * hv + wd[4] * hu + wd[1] * radius) / w_min,
            (gd[2] + 2.0 * wd[4] * hv + wd[2] * radius) / w_min,
        ))
    }
}

/// Bounds on `|F_uu|, |F_uv|, |F_vv|, |F_u|, |F_v|` over `[0, 1]²` of the tensor Bezier patch
/// `F` of degree `n` with net `net` (`dim` scalars a point): the largest norms of the net's
/// differences `Δ²_u`, `Δ_uΔ_v`, `Δ²_v`, `Δ_u`, `Δ_v` times `n_u(n_u − 1)`, `n_u n_v`,
/// `n_v(n_v − 1)`, `n_u`, `n_v` (the derivatives are Bezier patches with those nets; convex
/// hull).
fn difference_bounds(net: &[f64], n: (usize, usize), dim: usize) -> [f64; 5] {
    let (p, q) = n;
    let x = |i: usize, j: usize, d: usize| net[(i * (q + 1) + j) * dim + d];
    let mut m = [0.0_f64; 5];
    for i in 0..=p {
        for j in 0..=q {
            let mut s = [0.0_f64; 5];
            for d in 0..dim {
                let diffs = [
                    (i + 2 <= p).then(|| x(i + 2, j, d) - 2.0 * x(i + 1, j, d) + x(i, j, d)),
                    (i < p && j < q)
                        .then(|| x(i + 1, j + 1, d) - x(i + 1, j, d) - x(i, j + 1, d) + x(i, j, d)),
                    (j + 2 <= q).then(|| x(i, j + 2, d) - 2.0 * x(i, j + 1, d) + x(i, j, d)),
                    (i < p).then(|| x(i + 1, j, d) - x(i, j, d)),
                    (j < q).then(|| x(i, j + 1, d) - x(i, j, d)),
                ];
                for (k, t) in diffs.iter().enumerate() {
                    if let Some(t) = t {
                        s[k] += t * t;
                    }
                }
            }
            for (x, s) in m.iter_mut().zip(s) {
                *x = x.max(s.sqrt());
            }
        }
    }
    let (pf, qf) = (p as f64, q as f64);
    let factors = [
        pf * (pf - 1.0).max(0.0),
        pf * qf,
        qf * (qf - 1.0).max(0.0),
        pf,
        qf,
    ];
    for (x, f) in m.iter_mut().zip(factors) {
        *x *= f;
    }
    m
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
}
