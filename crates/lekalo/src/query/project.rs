//! Closest points: a point projected onto a curve or a surface, every minimum within a
//! tolerance on request, parallel batches, and point inversion
//! (`docs/theory/queries.md#closest-points`).
//!
//! Curves: best-first search of the piece tree by the distance to the pieces' control-point
//! boxes (a lower bound, by the convex-hull property), and on each piece that may still hold a
//! closer point, every root of `g(s) = C'(s)·(C(s) − Q)` from its Bernstein coefficients
//! (subdivision and sign counts, [`super::pieces`]), polished by Newton's method on the curve.
//! The piece ends are candidates too, so points beyond the ends, corners and cusps are found.
//!
//! Surfaces: best-first subdivision of the Bezier patches, pruned by the distance to the
//! sub-patch boxes, then a clamped Newton iteration from each surviving small sub-patch.

use crate::error::readable;
use crate::{Arg, What};
use std::cmp::Ordering;
use std::collections::BinaryHeap;

use rayon::prelude::*;

use super::pieces::{bern_roots, binom, box_distance, dist, Bern, QueryCurve};
use super::surface::QuerySurface;
use crate::error::{check_finite, Error, Result};
use crate::PointsRef;

/// A query point farther than this many curve sizes from the curve is refused
/// ([`Error::QueryOutOfRange`]): squared distances would lose all digits of the curve.
pub const MAX_QUERY_RANGE: f64 = 1e100;

/// The closest point found on a curve.
#[derive(Debug, Clone, PartialEq)]
pub struct CurveProjection {
    /// Parameter of the closest point.
    pub t: f64,
    /// The closest point.
    pub point: Vec<f64>,
    /// Its distance to the query point.
    pub distance: f64,
}

/// The closest point found on a surface.
#[derive(Debug, Clone, PartialEq)]
pub struct SurfaceProjection {
    /// Parameters `(u, v)` of the closest point.
    pub uv: (f64, f64),
    /// The closest point.
    pub point: Vec<f64>,
    /// Its distance to the query point.
    pub distance: f64,
}

/// Heap entry ordered by its lower bound, smallest first.
#[derive(PartialEq)]
pub(crate) struct ByBound<T: PartialEq>(pub(crate) f64, pub(crate) T);

impl<T: PartialEq> Eq for ByBound<T> {}
impl<T: PartialEq> PartialOrd for ByBound<T> {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}
impl<T: PartialEq> Ord for ByBound<T> {
    fn cmp(&self, other: &Self) -> Ordering {
        other.0.total_cmp(&self.0)
    }
}

/// A candidate: piece, local parameter, normalised distance.
#[derive(Debug, Clone, Copy)]
struct Cand {
    k: usize,
    s: f64,
    d: f64,
}

/// The buffers of curve projections, kept between calls so that a caller projecting many
/// points (a batch, or the gap tests of an intersection) allocates them once: the normalised
/// query, an evaluation, the candidates, the search heap and the foot polynomial's coefficients.
#[derive(Default)]
pub(crate) struct ProjectScratch {
    scratch: Vec<f64>,
    q: Vec<f64>,
    buf: Vec<f64>,
    found: Vec<Cand>,
    heap: BinaryHeap<ByBound<usize>>,
    coef: Vec<f64>,
    mag: Vec<f64>,
    nodes: Vec<usize>,
}

pub(crate) fn check_query(what: impl Into<What>, point: &[f64], dim: usize) -> Result<()> {
    let what: What = what.into();
    if point.len() != dim {
        return Err(Error::Dimension {
            what,
            expected: dim,
            got: point.len(),
        });
    }
    check_finite(what, point)
}

impl QueryCurve {
    /// Normalised query point, refusing far queries.
    fn query(&self, point: &[f64]) -> Result<Vec<f64>> {
        let mut q = Vec::new();
        self.query_into(point, &mut q)?;
        Ok(q)
    }

    /// [`QueryCurve::query`] into `q` (resized to the dimension).
    fn query_into(&self, point: &[f64], q: &mut Vec<f64>) -> Result<()> {
        check_query("query point", point, self.dim)?;
        q.clear();
        q.resize(self.dim, 0.0);
        self.normalise(point, q);
        let r = q.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
        if !(r <= MAX_QUERY_RANGE) {
            return Err(Error::QueryOutOfRange {
                ratio: r,
                max: MAX_QUERY_RANGE,
            });
        }
        Ok(())
    }

    /// Bernstein coefficients of `g(s) = C'(s)·(C(s) − q)` on piece `k` (times `w³` for a
    /// rational piece, which keeps the sign) and a threshold under which a coefficient is zero
    /// to rounding.
    /// The polynomial's coefficients are built in `c` (and `mag`), whose allocations are
    /// taken and may be given back.
    fn foot_polynomial(
        &self,
        k: usize,
        q: &[f64],
        c: &mut Vec<f64>,
        mag: &mut Vec<f64>,
    ) -> (Bern, f64) {
        let (dim, hd, n) = (self.dim, self.hd, self.degree);
        let piece = self.piece(k);
        if n == 0 {
            return (Bern(vec![0.0]), 0.0);
        }
        if !self.rational {
            // c_k = Σ_{i+j=k} C(n−1,i) C(n,j) / C(2n−1,k) · D_i·E_j, D_i = n ΔP_i, E_j = P_j − q
            let m = 2 * n - 1;
            let mut c = std::mem::take(c);
            c.clear();
            c.resize(m + 1, 0.0);
            mag.clear();
            mag.resize(m + 1, 0.0);
            for i in 0..n {
                let wi = binom(n - 1, i) * n as f64;
                for j in 0..=n {
                    let mut s = 0.0;
                    let mut a = 0.0;
                    for d in 0..dim {
                        let di = piece[(i + 1) * hd + d] - piece[i * hd + d];
                        let e = piece[j * hd + d] - q[d];
                        s += di * e;
                        a += (di * e).abs();
                    }
                    let w = wi * binom(n, j);
                    c[i + j] += w * s;
                    mag[i + j] += w * a;
                }
            }
            let mut zero = 0.0_f64;
            for k2 in 0..=m {
                let b = binom(m, k2);
                c[k2] /= b;
                zero = zero.max(mag[k2] / b);
            }
            return (Bern(c), 64.0 * f64::EPSILON * zero);
        }
        // rational: Σ_d (A_d' w − A_d w') (A_d − q_d w)
        let w = Bern((0..=n).map(|i| piece[i * hd + dim]).collect());
        let dw = w.deriv();
        let mut total: Option<Bern> = None;
        let mut zero = 0.0_f64;
        for d in 0..dim {
            let a = Bern((0..=n).map(|i| piece[i * hd + d]).collect());
            let num = a.deriv().mul(&w).sub(&a.mul(&dw));
            let e = a.sub(&w.scale(q[d]));
            let t = num.mul(&e);
            let mag = num.0.iter().fold(0.0_f64, |m, x| m.max(x.abs()))
                * e.0.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
            zero = zero.max(mag);
            total = Some(match total {
                None => t,
                Some(s) => s.add(&t),
            });
        }
        (
            total.unwrap_or(Bern(vec![0.0])),
            256.0 * f64::EPSILON * zero,
        )
    }

    /// Normalised distance from `q` to piece `k` at `s`.
    fn dist_at(&self, k: usize, s: f64, q: &[f64], scratch: &mut Vec<f64>, buf: &mut [f64]) -> f64 {
        self.eval_local(k, s, 0, scratch, buf);
        dist(&buf[..self.dim], q)
    }

    /// Newton's method on `g(s)` with the curve's own derivatives, at most 4 steps, kept in
    /// `[0, 1]` and only while the distance decreases.
    fn polish(
        &self,
        k: usize,
        s0: f64,
        q: &[f64],
        scratch: &mut Vec<f64>,
        buf: &mut [f64],
    ) -> Cand {
        let dim = self.dim;
        let mut s = s0;
        let mut d = self.dist_at(k, s, q, scratch, buf);
        for _ in 0..4 {
            self.eval_local(k, s, 2, scratch, buf);
            let (mut g, mut dg) = (0.0, 0.0);
            for i in 0..dim {
                let r = buf[i] - q[i];
                g += buf[dim + i] * r;
                dg += buf[2 * dim + i] * r + buf[dim + i] * buf[dim + i];
            }
            if dg <= 0.0 || !dg.is_finite() {
                break;
            }
            let next = (s - g / dg).clamp(0.0, 1.0);
            let dn = self.dist_at(k, next, q, scratch, buf);
            if !(dn <= d) || next == s {
                break;
            }
            s = next;
            d = dn;
        }
        Cand { k, s, d }
    }

    /// Candidates on piece `k`: its ends and the polished roots of `g`.
    fn piece_candidates(&self, k: usize, q: &[f64], w: &mut ProjectScratch) {
        let (scratch, buf, out) = (&mut w.scratch, &mut w.buf[..], &mut w.found);
        for s in [0.0, 1.0] {
            let d = self.dist_at(k, s, q, scratch, buf);
            out.push(Cand { k, s, d });
        }
        let (g, zero) = self.foot_polynomial(k, q, &mut w.coef, &mut w.mag);
        for r in bern_roots(&g, zero) {
            out.push(self.polish(k, r, q, scratch, buf));
        }
        // the coefficients' allocation, for the next piece
        w.coef = g.0;
    }

    /// All candidates within `slack` of the least distance, by best-first search of the tree.
    fn candidates(&self, q: &[f64], slack: f64, scratch: &mut Vec<f64>) -> Vec<Cand> {
        let mut w = ProjectScratch {
            scratch: std::mem::take(scratch),
            ..ProjectScratch::default()
        };
        self.candidates_in(q, slack, &mut w);
        *scratch = w.scratch;
        w.found
    }

    /// [`QueryCurve::candidates`] into `w.found`, with `w`'s buffers.
    fn candidates_in(&self, q: &[f64], slack: f64, w: &mut ProjectScratch) {
        w.buf.clear();
        w.buf.resize(3 * self.dim, 0.0);
        w.found.clear();
        let mut best = f64::INFINITY;
        let mut heap = std::mem::take(&mut w.heap);
        heap.clear();
        heap.push(ByBound(box_distance(q, &self.nodes[0].bbox), 0_usize));
        // bounded: every node is pushed at most once
        while let Some(ByBound(lb, id)) = heap.pop() {
            if lb > best + slack {
                break;
            }
            let node = &self.nodes[id];
            match node.children {
                Some((a, b)) => {
                    for c in [a, b] {
                        heap.push(ByBound(box_distance(q, &self.nodes[c].bbox), c));
                    }
                }
                None => {
                    let start = w.found.len();
                    self.piece_candidates(node.lo, q, w);
                    for c in &w.found[start..] {
                        best = best.min(c.d);
                    }
                }
            }
        }
        w.heap = heap;
        w.found.retain(|c| c.d <= best + slack);
        w.found.sort_by(|a, b| {
            a.d.total_cmp(&b.d)
                .then(a.k.cmp(&b.k))
                .then(a.s.total_cmp(&b.s))
        });
    }

    fn to_projection(&self, c: Cand, scratch: &mut Vec<f64>) -> CurveProjection {
        let t = self.global(c.k, c.s);
        let mut buf = vec![0.0; 3 * self.dim];
        self.eval_local(c.k, c.s, 0, scratch, &mut buf);
        let mut point = vec![0.0; self.dim];
        self.denormalise(&buf[..self.dim], &mut point);
        CurveProjection {
            t,
            point,
            distance: c.d * self.scale,
        }
    }

    fn project_with(&self, point: &[f64], w: &mut ProjectScratch) -> Result<CurveProjection> {
        let c = self.closest_in(point, w)?;
        Ok(self.to_projection(c, &mut w.scratch))
    }

    /// The closest candidate to `point`, with `w`'s buffers.
    fn closest_in(&self, point: &[f64], w: &mut ProjectScratch) -> Result<Cand> {
        let mut q = std::mem::take(&mut w.q);
        let found = self
            .query_into(point, &mut q)
            .map(|()| self.candidates_in(&q, 0.0, w));
        w.q = q;
        found.map(|()| w.found[0])
    }

    /// Whether `point` is proven farther than `limit` (absolute, in the curve's units) from the
    /// curve, without projecting it: a lower bound of its distance to each piece — the distance
    /// to the box of the piece's control points, and for a planar curve the distance to the band
    /// about the piece's chord that holds them (the fat line of Sederberg–Nishita 1990); the
    /// piece lies in both, by the convex-hull property (positive weights) — over the piece tree,
    /// whose boxes prune the pieces farther than the limit. A margin of rounding
    /// (`1e-12` of the limit and `1e-13` of the curve's size) keeps a yes in agreement with
    /// [`QueryCurve::project`]'s distance; a no means "not proven", not "within".
    pub(crate) fn farther_than(&self, point: &[f64], limit: f64, w: &mut ProjectScratch) -> bool {
        let lim = limit / self.scale * (1.0 + 1e-12) + 1e-13;
        if !lim.is_finite() || self.query_into(point, &mut w.q).is_err() {
            return false;
        }
        let (q, stack) = (&w.q, &mut w.nodes);
        stack.clear();
        stack.push(0);
        while let Some(id) = stack.pop() {
            let node = &self.nodes[id];
            if box_distance(q, &node.bbox) > lim {
                continue;
            }
            match node.children {
                Some((a, b)) => stack.extend([a, b]),
                None => {
                    if !(self.dim == 2 && self.band_distance(node.lo, q) > lim) {
                        return false;
                    }
                }
            }
        }
        true
    }

    /// Distance (normalised) from the planar point `q` to the band about the chord of piece
    /// `k` that holds its control points; 0 when the chord's ends coincide.
    fn band_distance(&self, k: usize, q: &[f64]) -> f64 {
        let (hd, n) = (self.hd, self.degree);
        let piece = self.piece(k);
        let cart = |i: usize| {
            let w = if self.rational {
                piece[i * hd + 2]
            } else {
                1.0
            };
            [piece[i * hd] / w, piece[i * hd + 1] / w]
        };
        let (a, b) = (cart(0), cart(n));
        let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
        let len = dx.hypot(dy);
        if !(len > 0.0) {
            return 0.0;
        }
        let nrm = [-dy / len, dx / len];
        let (mut lo, mut hi) = (0.0_f64, 0.0_f64);
        for i in 1..=n {
            let p = cart(i);
            let e = nrm[0] * (p[0] - a[0]) + nrm[1] * (p[1] - a[1]);
            lo = lo.min(e);
            hi = hi.max(e);
        }
        let e = nrm[0] * (q[0] - a[0]) + nrm[1] * (q[1] - a[1]);
        (e - hi).max(lo - e).max(0.0)
    }

    /// The parameter and the distance of [`QueryCurve::project`], the same to the last bit,
    /// with buffers kept by the caller (no allocation once they have grown): for callers that
    /// only compare gaps.
    ///
    /// # Errors
    /// As [`QueryCurve::project`].
    pub(crate) fn project_reusing(
        &self,
        point: &[f64],
        w: &mut ProjectScratch,
    ) -> Result<(f64, f64)> {
        let c = self.closest_in(point, w)?;
        Ok((self.global(c.k, c.s), c.d * self.scale))
    }

    /// The closest point of the curve to `point` (the one with the smallest parameter among
    /// equally close ones). Beyond the ends it is the nearer end; at a cusp or a corner it may be
    /// the cusp; on a closed curve the start is reported rather than the equal end.
    ///
    /// ```
    /// use lekalo::{NurbsCurve, QueryCurve};
    /// let circle = NurbsCurve::circle(&[0.0, 0.0], &[1.0, 0.0], &[0.0, 1.0], 2.0)?;
    /// let q = QueryCurve::from_nurbs(&circle)?;
    /// let p = q.project(&[3.0, 3.0])?;
    /// assert!((p.distance - (18f64.sqrt() - 2.0)).abs() < 1e-14);
    /// assert!((p.point[0] - 2f64.sqrt()).abs() < 1e-14);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::Dimension`] for a point of another dimension; [`Error::NonFinite`] for NaN or
    /// infinity; [`Error::QueryOutOfRange`] for a point more than [`MAX_QUERY_RANGE`] curve sizes
    /// away.
    pub fn project(&self, point: &[f64]) -> Result<CurveProjection> {
        self.project_with(point, &mut ProjectScratch::default())
    }

    /// Every local minimum of the distance whose distance is within `tolerance` (absolute, in
    /// the curve's units) of the least, sorted by distance: the branches a query equidistant
    /// from several parts of the curve sees. Minima closer together than `1e-9` curve sizes are
    /// reported once; at a point equidistant from a whole arc (a circle's centre) the arc's
    /// piece ends and the roots found are reported.
    ///
    /// ```
    /// use lekalo::{BSplineCurve, Points, QueryCurve};
    /// // a parabola y = x², x ∈ [−2, 2]; (0, 2) sees two closest points (±√1.5, 1.5)
    /// let c = BSplineCurve::new(2, vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
    ///                           Points::from_2d(&[[-2.0, 4.0], [0.0, -4.0], [2.0, 4.0]])?)?;
    /// let all = QueryCurve::from_bspline(&c)?.project_all(&[0.0, 2.0], 1e-9)?;
    /// assert_eq!(all.len(), 2);
    /// assert!((all[0].point[0].abs() - 1.5f64.sqrt()).abs() < 1e-12);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// As [`QueryCurve::project`]; [`Error::InvalidArgument`] for a negative or NaN tolerance.
    pub fn project_all(&self, point: &[f64], tolerance: f64) -> Result<Vec<CurveProjection>> {
        if !(tolerance >= 0.0 && tolerance.is_finite()) {
            return Err(Error::InvalidArgument {
                what: What::of(Arg::Tolerance, "projection tolerance"),
                reason: format!(
                    "{tolerance} is not a non-negative finite distance",
                    tolerance = readable(&tolerance)
                ),
            });
        }
        let q = self.query(point)?;
        let mut scratch = Vec::new();
        let mut buf = vec![0.0; 3 * self.dim];
        let found = self.candidates(&q, tolerance / self.scale, &mut scratch);
        let (lo, hi) = self.domain();
        let mut out: Vec<CurveProjection> = Vec::new();
        for c in found {
            // a local minimum: no closer point a little way to either side
            let p = self.to_projection(c, &mut scratch);
            let step = 1e-7 * (hi - lo);
            let is_min = [p.t - step, p.t + step].iter().all(|&t| {
                if t < lo || t > hi {
                    return true;
                }
                let k = self.piece_of(t);
                self.dist_at(k, self.local(k, t), &q, &mut scratch, &mut buf) >= c.d
            });
            let dup = out
                .iter()
                .any(|o| dist(&o.point, &p.point) <= 1e-9 * self.scale);
            if is_min && !dup {
                out.push(p);
            }
        }
        Ok(out)
    }

    /// [`QueryCurve::project`] for every point of `points`, in parallel; each point is solved on
    /// its own, so the results do not depend on the number of threads.
    ///
    /// # Errors
    /// As [`QueryCurve::project`], for the first bad point.
    pub fn project_batch(&self, points: PointsRef<'_>) -> Result<Vec<CurveProjection>> {
        if points.dim() != self.dim {
            return Err(Error::Dimension {
                what: "query points".into(),
                expected: self.dim,
                got: points.dim(),
            });
        }
        points
            .as_slice()
            .par_chunks_exact(self.dim)
            .map_init(ProjectScratch::default, |w, p| self.project_with(p, w))
            .collect()
    }

    /// Point inversion: the parameter of a point that lies on the curve (its projection),
    /// refused when the point is farther than `tolerance` from the curve.
    ///
    /// # Errors
    /// As [`QueryCurve::project`]; [`Error::NotOnCurve`] when the distance exceeds `tolerance`.
    pub fn invert(&self, point: &[f64], tolerance: f64) -> Result<f64> {
        let p = self.project(point)?;
        if !(p.distance <= tolerance) {
            return Err(Error::NotOnCurve {
                distance: p.distance,
                tolerance,
            });
        }
        Ok(p.t)
    }
}

/// Most sub-patches one surface projection visits.
const MAX_SURFACE_NODES: usize = 1 << 13;

/// A sub-patch in the surface search: patch, local `u` and `v` ranges, its net.
#[derive(PartialEq)]
struct SubPatch {
    k: usize,
    u: (f64, f64),
    v: (f64, f64),
    net: Vec<f64>,
    depth: u32,
}

impl QuerySurface {
    /// The closest point of the surface to `point` (3-D or any dimension).
    ///
    /// ```
    /// use lekalo::{BSplineSurface, Points, QuerySurface};
    /// // the bilinear patch z = xy on [0, 1]²
    /// let net = Points::from_3d(&[[0.0, 0.0, 0.0], [0.0, 1.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 1.0]])?;
    /// let s = BSplineSurface::new(1, 1, vec![0.0, 0.0, 1.0, 1.0], vec![0.0, 0.0, 1.0, 1.0], net, (2, 2))?;
    /// let p = QuerySurface::from_bspline(&s)?.project(&[0.5, 0.5, 1.0])?;
    /// // the residual is normal to the surface
    /// let (u, v) = p.uv;
    /// let r = [0.5 - p.point[0], 0.5 - p.point[1], 1.0 - p.point[2]];
    /// assert!((r[0] - (-v) * r[2]).abs() < 1e-9 && (r[1] - (-u) * r[2]).abs() < 1e-9);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::Dimension`], [`Error::NonFinite`], [`Error::QueryOutOfRange`] as for curves.
    pub fn project(&self, point: &[f64]) -> Result<SurfaceProjection> {
        check_query("query point", point, self.dim)?;
        let mut q = vec![0.0; self.dim];
        self.normalise(point, &mut q);
        let r = q.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
        if !(r <= MAX_QUERY_RANGE) {
            return Err(Error::QueryOutOfRange {
                ratio: r,
                max: MAX_QUERY_RANGE,
            });
        }
        let mut best = (f64::INFINITY, 0_usize, 0.0, 0.0);
        let mut heap = BinaryHeap::new();
        for k in 0..self.patch_count() {
            let net = self.patch(k).to_vec();
            let lb = box_distance(&q, &self.net_box(&net));
            heap.push(ByBound(
                lb,
                SubPatch {
                    k,
                    u: (0.0, 1.0),
                    v: (0.0, 1.0),
                    net,
                    depth: 0,
                },
            ));
        }
        let mut visited = 0;
        while let Some(ByBound(lb, sp)) = heap.pop() {
            if lb > best.0 {
                break;
            }
            visited += 1;
            // the corners lie on the surface
            for (cu, cv) in [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (1.0, 1.0)] {
                let (u, v) = (
                    sp.u.0 + cu * (sp.u.1 - sp.u.0),
                    sp.v.0 + cv * (sp.v.1 - sp.v.0),
                );
                let d = dist(&self.eval_patch(sp.k, u, v).0, &q);
                if d < best.0 {
                    best = (d, sp.k, u, v);
                }
            }
            let b = self.net_box(&sp.net);
            let diag = dist(&b[..self.dim], &b[self.dim..]);
            if diag <= 0.25 * lb.max(1e-3) || sp.depth >= 16 || visited >= MAX_SURFACE_NODES {
                let u0 = 0.5 * (sp.u.0 + sp.u.1);
                let v0 = 0.5 * (sp.v.0 + sp.v.1);
                let (d, u, v) = self.newton(sp.k, u0, v0, &q);
                if d < best.0 {
                    best = (d, sp.k, u, v);
                }
                continue;
            }
            for (u, v, net) in self.split4(&sp.net, sp.u, sp.v) {
                let lb = box_distance(&q, &self.net_box(&net));
                if lb <= best.0 {
                    heap.push(ByBound(
                        lb,
                        SubPatch {
                            k: sp.k,
                            u,
                            v,
                            net,
                            depth: sp.depth + 1,
                        },
                    ));
                }
            }
        }
        let (d, k, u, v) = best;
        let (pn, _) = self.eval_patch(k, u, v);
        let mut point = vec![0.0; self.dim];
        self.denormalise(&pn, &mut point);
        Ok(SurfaceProjection {
            uv: self.global_uv(k, u, v),
            point,
            distance: d * self.scale,
        })
    }

    /// Newton's method for `(S − q)·S_u = (S − q)·S_v = 0` on patch `k`, clamped to the patch
    /// (a clamped coordinate stays fixed while the other moves); at most 30 steps, each kept only
    /// if the distance does not grow. Returns the distance and local `(u, v)`.
    fn newton(&self, k: usize, u0: f64, v0: f64, q: &[f64]) -> (f64, f64, f64) {
        let dim = self.dim;
        let (mut u, mut v) = (u0, v0);
        let (p, _) = self.eval_patch(k, u, v);
        let mut d = dist(&p, q);
        for _ in 0..30 {
            let (p, der) = self.eval_patch(k, u, v);
            let r: Vec<f64> = (0..dim).map(|i| p[i] - q[i]).collect();
            let (su, sv, suu, suv, svv) = (
                &der[0..dim],
                &der[dim..2 * dim],
                &der[2 * dim..3 * dim],
                &der[3 * dim..4 * dim],
                &der[4 * dim..5 * dim],
            );
            let f = super::pieces::dot(&r, su);
            let g = super::pieces::dot(&r, sv);
            let a = super::pieces::dot(su, su) + super::pieces::dot(&r, suu);
            let b = super::pieces::dot(su, sv) + super::pieces::dot(&r, suv);
            let c = super::pieces::dot(sv, sv) + super::pieces::dot(&r, svv);
            let det = a * c - b * b;
            let (mut du, mut dv) = if det > 0.0 && a > 0.0 {
                ((c * f - b * g) / det, (a * g - b * f) / det)
            } else {
                // not positive definite: a gradient step scaled by the first fundamental form
                let e = super::pieces::dot(su, su).max(1e-300);
                let h = super::pieces::dot(sv, sv).max(1e-300);
                (f / e, g / h)
            };
            // a coordinate pushed against its bound is fixed; the other moves alone
            if (u <= 0.0 && du > 0.0) || (u >= 1.0 && du < 0.0) {
                du = 0.0;
                dv = if c > 0.0 { g / c } else { dv };
            }
            if (v <= 0.0 && dv > 0.0) || (v >= 1.0 && dv < 0.0) {
                dv = 0.0;
                if du != 0.0 {
                    du = if a > 0.0 { f / a } else { du };
                }
            }
            let (nu, nv) = ((u - du).clamp(0.0, 1.0), (v - dv).clamp(0.0, 1.0));
            let (pn, _) = self.eval_patch(k, nu, nv);
            let dn = dist(&pn, q);
            if !(dn <= d) {
                break;
            }
            let moved = (nu - u).abs() + (nv - v).abs();
            u = nu;
            v = nv;
            d = dn;
            if moved <= 1e-15 {
                break;
            }
        }
        (d, u, v)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{BSplineCurve, NurbsCurve, Points};

    fn wiggle() -> QueryCurve {
        let pts: Vec<[f64; 2]> = (0..12)
            .map(|i| {
                let x = f64::from(i);
                [x, (x * 1.3).sin() * 2.0]
            })
            .collect();
        let n = pts.len();
        let mut knots = vec![0.0; 4];
        for i in 1..n - 3 {
            knots.push(i as f64 / (n - 3) as f64);
        }
        knots.extend([1.0; 4]);
        let c = BSplineCurve::new(3, knots, Points::from_2d(&pts).unwrap()).unwrap();
        QueryCurve::from_bspline(&c).unwrap()
    }

    #[test]
    fn beyond_the_ends_is_the_end() {
        let q = wiggle();
        let p = q.project(&[-5.0, 0.0]).unwrap();
        assert_eq!(p.t, 0.0);
        let p = q.project(&[30.0, 1.0]).unwrap();
        assert_eq!(p.t, 1.0);
    }

    #[test]
    fn residual_is_normal_and_no_sample_is_closer() {
        let q = wiggle();
        let mut scratch = Vec::new();
        for (x, y) in [(3.3, 4.0), (5.0, -1.0), (8.2, 0.3), (1.0, 1.0), (6.0, 10.0)] {
            let p = q.project(&[x, y]).unwrap();
            let der = q.eval_global(p.t, 1, &mut scratch);
            let r = [x - p.point[0], y - p.point[1]];
            let tn = der[2].hypot(der[3]);
            let cos = (r[0] * der[2] + r[1] * der[3]) / (tn * p.distance);
            if p.t > 0.0 && p.t < 1.0 {
                assert!(cos.abs() < 1e-9, "({x}, {y}): cos {cos}");
            }
            for i in 0..=2000 {
                let s = q.eval_global(f64::from(i) / 2000.0, 0, &mut scratch);
                assert!(dist(&s, &[x, y]) >= p.distance - 1e-12, "sample closer");
            }
        }
    }

    #[test]
    fn degenerate_and_bad_queries() {
        let c = BSplineCurve::new(
            2,
            vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
            Points::from_2d(&[[1.0, 2.0]; 3]).unwrap(),
        )
        .unwrap();
        let q = QueryCurve::from_bspline(&c).unwrap();
        let p = q.project(&[4.0, 6.0]).unwrap();
        assert!((p.distance - 5.0).abs() < 1e-15, "{p:?}");
        assert!(matches!(
            q.project(&[f64::NAN, 0.0]),
            Err(Error::NonFinite { .. })
        ));
        assert!(matches!(q.project(&[0.0]), Err(Error::Dimension { .. })));
        assert!(matches!(
            wiggle().project(&[1e200, 0.0]),
            Err(Error::QueryOutOfRange { .. })
        ));
        assert!(matches!(
            wiggle().invert(&[3.0, 100.0], 1e-9),
            Err(Error::NotOnCurve { .. })
        ));
    }

    #[test]
    fn circle_centre_and_tiny_scale() {
        let circle = NurbsCurve::circle(&[0.0, 0.0], &[1.0, 0.0], &[0.0, 1.0], 1e-120).unwrap();
        let q = QueryCurve::from_nurbs(&circle).unwrap();
        let p = q.project(&[3e-120, 4e-120]).unwrap();
        assert!((p.distance - 4e-120).abs() < 1e-134, "{p:?}");
        let c = q.project(&[0.0, 0.0]).unwrap();
        assert!((c.distance - 1e-120).abs() < 1e-134, "{c:?}");
        let t = q.invert(&p.point, 1e-130).unwrap();
        assert!((t - p.t).abs() < 1e-12, "{t}");
    }

    #[test]
    fn batch_equals_single() {
        let q = wiggle();
        let pts: Vec<f64> = (0..200)
            .flat_map(|i| {
                let x = f64::from(i) * 0.06;
                [x, (x * 3.1).cos() * 3.0]
            })
            .collect();
        let batch = q
            .project_batch(Points::from_flat(2, pts.clone()).unwrap().as_view())
            .unwrap();
        for (i, b) in batch.iter().enumerate() {
            assert_eq!(*b, q.project(&pts[2 * i..2 * i + 2]).unwrap(), "point {i}");
        }
    }
}
