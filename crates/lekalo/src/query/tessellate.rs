//! Tessellation within a proved deviation: curves to polylines, surfaces to triangle meshes
//! (`docs/theory/queries.md#tessellation`).

use super::intersect::segment_distance;
use super::pieces::{QueryCurve, MAX_QUERY_DEGREE};
use super::surface::{split_curve, QuerySurface, SubNet};
use crate::error::{check_finite, Error, Result};
use crate::Points;

/// Smallest tolerance accepted, relative to the object's size: below it rounding, not the
/// geometry, would decide whether a chord is within the tolerance.
pub const MIN_RELATIVE_TOLERANCE: f64 = 1e-12;
/// Levels of halving of a patch (in both directions) before its control net bounds the
/// derivatives that fix the mesh's steps: 4^2 sub-patches, whose nets lie closer to the surface
/// than the patch's, so the bounds and the triangle counts are smaller.
const BOUND_LEVELS: u32 = 2;
/// Levels of halving of each patch into the strips of the mesh's grid (each strip gets its own
/// steps, so flat parts of a patch are not meshed as finely as curved ones).
const MESH_LEVELS: u32 = 1;
/// Largest number of mesh vertices (a bound on the memory of [`QuerySurface::mesh`]).
pub const MAX_MESH_VERTICES: usize = 1 << 26;

/// A polyline approximating a curve.
#[derive(Debug, Clone, PartialEq)]
pub struct Polyline {
    /// Parameters of the vertices (increasing; the curve's points).
    pub params: Vec<f64>,
    /// The vertices.
    pub points: Points,
    /// Proved bound on the distance from any point of the curve to the polyline.
    pub deviation: f64,
}

/// A triangle mesh approximating a surface.
#[derive(Debug, Clone, PartialEq)]
pub struct Mesh {
    /// Vertex positions (points of the surface).
    pub vertices: Points,
    /// Parameters `(u, v)` of the vertices.
    pub uv: Vec<[f64; 2]>,
    /// Triangles as vertex indices, counter-clockwise in `(u, v)`.
    pub triangles: Vec<[u32; 3]>,
    /// Proved bound on `|S(u, v) − L(u, v)|`, `L` the mesh's linear interpolant over the same
    /// parameter triangles, hence on the distance from the surface to the mesh.
    pub deviation: f64,
}

fn check_tol(tol: f64, scale: f64) -> Result<()> {
    check_finite("tessellation tolerance", &[tol])?;
    if !(tol >= MIN_RELATIVE_TOLERANCE * scale) {
        return Err(Error::InvalidArgument {
            what: "tessellation tolerance",
            reason: format!(
                "{tol} is below {MIN_RELATIVE_TOLERANCE:e} times the object's size {scale}; \
                 rounding would decide the bound"
            ),
        });
    }
    Ok(())
}

impl QueryCurve {
    /// A polyline within `tolerance` of the curve: each piece is halved (de Casteljau) until
    /// every control point of a part lies within `tolerance` of the chord joining its ends;
    /// by the convex-hull property the part then lies within that distance of the chord,
    /// which is the bound reported (`docs/theory/queries.md#tessellation`). At most 50 halvings
    /// deep.
    ///
    /// ```
    /// use lekalo::{NurbsCurve, QueryCurve};
    /// let c = NurbsCurve::circle(&[0.0, 0.0], &[1.0, 0.0], &[0.0, 1.0], 1.0)?;
    /// let poly = QueryCurve::from_nurbs(&c)?.polyline(1e-3)?;
    /// assert!(poly.deviation <= 1e-3);
    /// // a chord of the unit circle within 1e-3 spans at most 2·acos(1 − 1e-3) ≈ 0.0894 rad
    /// assert!(poly.points.len() >= 71);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for a tolerance below [`MIN_RELATIVE_TOLERANCE`] times the
    /// curve's size, or NaN.
    pub fn polyline(&self, tolerance: f64) -> Result<Polyline> {
        check_tol(tolerance, self.scale)?;
        let tol = tolerance / self.scale;
        let (dim, hd, n) = (self.dim, self.hd, self.degree);
        let cart = |p: &[f64]| -> Vec<f64> {
            let w = if self.rational { p[dim] } else { 1.0 };
            p[..dim].iter().map(|x| x / w).collect()
        };
        let mut params = Vec::new();
        let mut pts = Vec::new();
        let mut worst = 0.0_f64;
        let mut buf = vec![0.0; dim];
        for k in 0..self.piece_count() {
            let mut stack = vec![(self.piece(k).to_vec(), 0.0_f64, 1.0_f64, 0_u32)];
            if k == 0 {
                params.push(self.global(0, 0.0));
                self.denormalise(&cart(&self.piece(0)[..hd]), &mut buf);
                pts.extend_from_slice(&buf);
            } else if self.spans[k].0 != self.spans[k - 1].1 {
                // a gap in the domain cannot happen for splines; a jump (multiplicity p + 1) is
                // joined by a segment like any other
            }
            while let Some((net, a, b, depth)) = stack.pop() {
                let first = cart(&net[..hd]);
                let last = cart(&net[n * hd..]);
                let flat = net
                    .chunks_exact(hd)
                    .map(|p| segment_distance(&cart(p), &first, &last))
                    .fold(0.0, f64::max);
                if flat <= tol || depth >= 50 || n == 0 {
                    worst = worst.max(flat);
                    params.push(self.global(k, b));
                    self.denormalise(&last, &mut buf);
                    pts.extend_from_slice(&buf);
                } else {
                    let (l, r) = split_curve(&net, hd, n);
                    let m = 0.5 * (a + b);
                    stack.push((r, m, b, depth + 1));
                    stack.push((l, a, m, depth + 1));
                }
            }
        }
        Ok(Polyline {
            params,
            points: Points::from_flat(dim, pts)?,
            deviation: worst * self.scale,
        })
    }
}

impl QuerySurface {
    /// Bounds `(A, B, C)` of patch `k` (normalised, local parameters) such that the linear
    /// interpolant over a grid triangle with steps `h_u, h_v` deviates from the patch by at
    /// most `(h_u² A + 2 h_u h_v B + h_v² C) / 8` (`docs/theory/queries.md#tessellation`).
    ///
    /// Polynomial patch: the second-derivative bounds `|S_uu| ≤ p(p−1)·max|Δ²_u P|`,
    /// `|S_uv| ≤ pq·max|Δ_uΔ_v P|`, `|S_vv| ≤ q(q−1)·max|Δ²_v P|` (the derivatives are Bezier
    /// patches with those nets; convex hull).
    ///
    /// Rational patch `S = P/w` (homogeneous net, translated to the centre `c` of its
    /// Cartesian control points, weights `w ≥ w_min > 0`): on a triangle with interpolant `L`,
    /// `S − L = f/w` with `f = (P − c w) − w (L − c)`, which vanishes at the vertices, so the
    /// same grid bound applies to `f`, divided by `w_min`. By Leibniz (`L` is linear),
    /// `f_uu = P_uu − w_uu (L − c) − 2 w_u L_u` and
    /// `f_uv = P_uv − w_uv (L − c) − w_u L_v − w_v L_u`, bounded with `|L − c| ≤ R` (the radius
    /// of the Cartesian net about `c`) and `|L_u| ≤ max|S_u| ≤ (|P_u| + |w_u| R) / w_min` (a
    /// grid triangle's edges lie along `u` and `v`). `None` if a weight is not positive.
    fn deviation_bounds(&self, k: usize) -> Option<(f64, f64, f64)> {
        let (p, q, hd, dim) = (self.p, self.q, self.hd, self.dim);
        // the patch's 4^BOUND_LEVELS sub-patches: their nets hug the patch, so the maxima of
        // their differences (scaled back to the patch's parameters) are tighter bounds
        let mut nets = vec![self.patch(k).to_vec()];
        for _ in 0..BOUND_LEVELS {
            nets = nets
                .iter()
                .flat_map(|n| self.split4(n, (0.0, 1.0), (0.0, 1.0)))
                .map(|sub| sub.2)
                .collect();
        }
        let weight = |net: &[f64], i: usize, j: usize| {
            if self.rational {
                net[(i * (q + 1) + j) * hd + dim]
            } else {
                1.0
            }
        };
        let mut w_min = f64::INFINITY;
        let mut centre = vec![0.0; dim];
        if self.rational {
            let mut b = self.net_box(&nets[0]);
            for n in &nets[1..] {
                let c = self.net_box(n);
                for d in 0..dim {
                    b[d] = b[d].min(c[d]);
                    b[dim + d] = b[dim + d].max(c[dim + d]);
                }
            }
            for d in 0..dim {
                centre[d] = 0.5 * (b[d] + b[dim + d]);
            }
        }
        let mut radius = 0.0_f64;
        for net in &nets {
            for (i, j) in (0..=p).flat_map(|i| (0..=q).map(move |j| (i, j))) {
                let w = weight(net, i, j);
                w_min = w_min.min(w);
                let r2: f64 = (0..dim)
                    .map(|d| (net[(i * (q + 1) + j) * hd + d] / w - centre[d]).powi(2))
                    .sum();
                radius = radius.max(r2.sqrt());
            }
        }
        if !(w_min > 0.0) {
            return None;
        }
        let norm =
            |f: &dyn Fn(usize) -> f64| -> f64 { (0..dim).map(|d| f(d) * f(d)).sum::<f64>().sqrt() };
        // [|Δ²_u|, |Δ_uΔ_v|, |Δ²_v|, |Δ_u|, |Δ_v|] of the point part, then of the weight
        let mut pt = [0.0_f64; 5];
        let mut wt = [0.0_f64; 5];
        for net in &nets {
            // coordinate d of the translated homogeneous net P − c w; the weight as coordinate dim
            let at = |i: usize, j: usize, d: usize| {
                if d == dim {
                    weight(net, i, j)
                } else {
                    net[(i * (q + 1) + j) * hd + d] - centre[d] * weight(net, i, j)
                }
            };
            for i in 0..=p {
                for j in 0..=q {
                    let diffs: [(bool, &dyn Fn(usize) -> f64); 5] = [
                        (i + 2 <= p, &|d| {
                            at(i + 2, j, d) - 2.0 * at(i + 1, j, d) + at(i, j, d)
                        }),
                        (i < p && j < q, &|d| {
                            at(i + 1, j + 1, d) - at(i + 1, j, d) - at(i, j + 1, d) + at(i, j, d)
                        }),
                        (j + 2 <= q, &|d| {
                            at(i, j + 2, d) - 2.0 * at(i, j + 1, d) + at(i, j, d)
                        }),
                        (i < p, &|d| at(i + 1, j, d) - at(i, j, d)),
                        (j < q, &|d| at(i, j + 1, d) - at(i, j, d)),
                    ];
                    for (m, (ok, f)) in diffs.iter().enumerate() {
                        if *ok {
                            pt[m] = pt[m].max(norm(f));
                            wt[m] = wt[m].max(f(dim).abs());
                        }
                    }
                }
            }
        }
        // a derivative in a sub-patch's parameter is 2^−BOUND_LEVELS times the patch's, per order
        let fast = f64::from(1_u32 << BOUND_LEVELS);
        for m in 0..5 {
            let f = if m < 3 { fast * fast } else { fast };
            pt[m] *= f;
            wt[m] *= f;
        }
        let (pf, qf) = (p as f64, q as f64);
        let factors = [pf * (pf - 1.0), pf * qf, qf * (qf - 1.0), pf, qf];
        let (mut pd, mut wd) = ([0.0; 5], [0.0; 5]);
        for m in 0..5 {
            pd[m] = factors[m] * pt[m];
            wd[m] = factors[m] * wt[m];
        }
        // slopes of S (hence of L): |S_u| ≤ (|P_u| + |w_u| R) / w_min
        let gu = (pd[3] + wd[3] * radius) / w_min;
        let gv = (pd[4] + wd[4] * radius) / w_min;
        Some((
            (pd[0] + wd[0] * radius + 2.0 * wd[3] * gu) / w_min,
            (pd[1] + wd[1] * radius + wd[3] * gv + wd[4] * gu) / w_min,
            (pd[2] + wd[2] * radius + 2.0 * wd[4] * gv) / w_min,
        ))
    }

    /// A triangle mesh within `tolerance` of a surface, polynomial or rational. Each patch gets
    /// an `m × k` grid split into triangles; the linear interpolant over a triangle of a grid
    /// with steps `h_u, h_v` deviates from a polynomial patch by at most
    /// `(h_u² M_uu + 2 h_u h_v M_uv + h_v² M_vv) / 8` (Filip, Magedson & Markot 1986), with the
    /// `M` bounds from the net's second differences, and from a rational patch by the same
    /// expression in bounds that also carry the weights' differences and their least value, so
    /// `m` and `k` are the least that make this at most `tolerance` — proved from the control
    /// points, not sampled (`docs/theory/queries.md#tessellation`). Patches in one `u` strip share `m`, patches in
    /// one `v` strip share `k`, so neighbouring grids match and the mesh has no cracks.
    ///
    /// ```
    /// use lekalo::{BSplineSurface, Points, QuerySurface};
    /// // z = x² on [0, 1]²: M_uu = 2, so a step h gives 2h²/8 ≤ 1e-3 ⇒ h ≤ 0.0632, 16 steps in u
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
    /// a tolerance below [`MIN_RELATIVE_TOLERANCE`] times the size; [`Error::TooLarge`] beyond
    /// [`MAX_MESH_VERTICES`].
    pub fn mesh(&self, tolerance: f64) -> Result<Mesh> {
        check_tol(tolerance, self.scale)?;
        self.refined(MESH_LEVELS).mesh_grid(tolerance)
    }

    /// The same surface with every patch halved `levels` times in each direction of degree at
    /// least 2 (de Casteljau at the halves; a linear direction gains nothing from it), in
    /// `u`-major order of the ranges: the strips of the mesh's grid, each with its own steps and
    /// its own derivative bounds.
    fn refined(&self, levels: u32) -> QuerySurface {
        let (p, q, hd) = (self.p, self.q, self.hd);
        let mut subs: Vec<SubNet> = Vec::new();
        for (k, &(ur, vr)) in self.ranges.iter().enumerate() {
            let mut parts = vec![(ur, vr, self.patch(k).to_vec())];
            for _ in 0..levels {
                if p >= 2 {
                    // the rows form a curve of (q + 1)·hd-points
                    parts = parts
                        .into_iter()
                        .flat_map(|(u, v, n)| {
                            let m = 0.5 * (u.0 + u.1);
                            let (a, b) = split_curve(&n, (q + 1) * hd, p);
                            [((u.0, m), v, a), ((m, u.1), v, b)]
                        })
                        .collect();
                }
                if q >= 2 {
                    parts = parts
                        .into_iter()
                        .flat_map(|(u, v, n)| {
                            let m = 0.5 * (v.0 + v.1);
                            let (mut a, mut b) = (Vec::new(), Vec::new());
                            for row in n.chunks_exact((q + 1) * hd) {
                                let (l, h) = split_curve(row, hd, q);
                                a.extend(l);
                                b.extend(h);
                            }
                            [(u, (v.0, m), a), (u, (m, v.1), b)]
                        })
                        .collect();
                }
            }
            subs.extend(parts);
        }
        subs.sort_by(|a, b| a.0 .0.total_cmp(&b.0 .0).then(a.1 .0.total_cmp(&b.1 .0)));
        QuerySurface {
            ranges: subs.iter().map(|s| (s.0, s.1)).collect(),
            nets: subs.into_iter().flat_map(|s| s.2).collect(),
            centre: self.centre.clone(),
            ..*self
        }
    }

    /// [`QuerySurface::mesh`] on the grid whose strips are this surface's patches.
    fn mesh_grid(&self, tolerance: f64) -> Result<Mesh> {
        debug_assert!(self.p <= MAX_QUERY_DEGREE, "degree checked at construction");
        let tol = tolerance / self.scale;
        // strips: distinct u ranges and v ranges in order
        let mut us: Vec<(f64, f64)> = self.ranges.iter().map(|r| r.0).collect();
        us.dedup();
        let mut vs: Vec<(f64, f64)> = self.ranges.iter().map(|r| r.1).collect();
        vs.sort_by(|a, b| a.0.total_cmp(&b.0));
        vs.dedup();
        let ui = |u: (f64, f64)| us.partition_point(|x| x.0 < u.0);
        let vi = |v: (f64, f64)| vs.partition_point(|x| x.0 < v.0);
        let bounds: Vec<(f64, f64, f64)> = (0..self.patch_count())
            .map(|k| {
                self.deviation_bounds(k)
                    .ok_or_else(|| Error::InvalidArgument {
                        what: "surface to mesh",
                        reason: format!(
                            "patch {k} has a weight that is not positive; the deviation bound \
                         needs positive weights"
                        ),
                    })
            })
            .collect::<Result<_>>()?;
        #[allow(clippy::cast_possible_truncation)] // a whole number in [1, 1e9]
        let steps = |m: f64| -> usize {
            let s = m.ceil().max(1.0);
            if s > 1e9 {
                1_000_000_000
            } else {
                s as usize
            }
        };
        let mut mu = vec![1_usize; us.len()];
        let mut mv = vec![1_usize; vs.len()];
        for (k, &(a, _, c)) in bounds.iter().enumerate() {
            let (i, j) = (ui(self.ranges[k].0), vi(self.ranges[k].1));
            // the least steps for the pure terms alone; the loop below adds for the sum
            mu[i] = mu[i].max(steps((a / (8.0 * tol)).sqrt()));
            mv[j] = mv[j].max(steps((c / (8.0 * tol)).sqrt()));
        }
        let bound = |k: usize, mu: &[usize], mv: &[usize]| {
            let (a, b, c) = bounds[k];
            let (i, j) = (ui(self.ranges[k].0), vi(self.ranges[k].1));
            let (hu, hv) = (1.0 / mu[i] as f64, 1.0 / mv[j] as f64);
            (hu * hu * a + 2.0 * hu * hv * b + hv * hv * c) / 8.0
        };
        // the mixed term: refine both directions of a patch that is still above (bounded loop)
        for _ in 0..64 {
            let mut ok = true;
            for k in 0..self.patch_count() {
                let e = bound(k, &mu, &mv);
                if e > tol {
                    ok = false;
                    let f = (e / tol).sqrt() * 1.0001;
                    let (i, j) = (ui(self.ranges[k].0), vi(self.ranges[k].1));
                    // refine only a direction whose steps enter the bound
                    let (a, b, c) = bounds[k];
                    if a > 0.0 || b > 0.0 {
                        mu[i] = steps(mu[i] as f64 * f);
                    }
                    if c > 0.0 || b > 0.0 {
                        mv[j] = steps(mv[j] as f64 * f);
                    }
                }
            }
            if ok {
                break;
            }
        }
        let nu: usize = mu.iter().sum::<usize>() + 1;
        let nv: usize = mv.iter().sum::<usize>() + 1;
        if nu.saturating_mul(nv) > MAX_MESH_VERTICES {
            return Err(Error::TooLarge {
                what: "mesh vertices",
                size: nu.saturating_mul(nv),
                max: MAX_MESH_VERTICES,
            });
        }
        let deviation = (0..self.patch_count())
            .map(|k| bound(k, &mu, &mv))
            .fold(0.0, f64::max);
        // global parameter lines
        let lines = |strips: &[(f64, f64)], m: &[usize]| {
            let mut out = Vec::new();
            for (s, &(a, b)) in strips.iter().enumerate() {
                for i in 0..m[s] {
                    out.push((
                        s,
                        a + (b - a) * i as f64 / m[s] as f64,
                        i as f64 / m[s] as f64,
                    ));
                }
            }
            let last = strips.len() - 1;
            out.push((last, strips[last].1, 1.0));
            out
        };
        let (ul, vl) = (lines(&us, &mu), lines(&vs, &mv));
        // patch index of strip pair (i, j)
        let mut patch_of = vec![usize::MAX; us.len() * vs.len()];
        for k in 0..self.patch_count() {
            patch_of[ui(self.ranges[k].0) * vs.len() + vi(self.ranges[k].1)] = k;
        }
        let dim = self.dim;
        let mut verts = Vec::with_capacity(nu * nv * dim);
        let mut uv = Vec::with_capacity(nu * nv);
        let mut scratch = Vec::new();
        let mut buf = vec![0.0; dim];
        for &(si, u, lu) in &ul {
            for &(sj, v, lv) in &vl {
                let k = patch_of[si * vs.len() + sj];
                let p = self.point_on(k, lu, lv, &mut scratch);
                self.denormalise(&p, &mut buf);
                verts.extend_from_slice(&buf);
                uv.push([u, v]);
            }
        }
        let mut triangles = Vec::with_capacity(2 * (nu - 1) * (nv - 1));
        let idx = |a: usize, b: usize| u32::try_from(a * nv + b).unwrap_or(u32::MAX);
        for a in 0..nu - 1 {
            for b in 0..nv - 1 {
                triangles.push([idx(a, b), idx(a + 1, b), idx(a + 1, b + 1)]);
                triangles.push([idx(a, b), idx(a + 1, b + 1), idx(a, b + 1)]);
            }
        }
        Ok(Mesh {
            vertices: Points::from_flat(dim, verts)?,
            uv,
            triangles,
            deviation: deviation * self.scale,
        })
    }

    /// Normalised point of patch `k` at local `(u, v)` (tensor de Casteljau, no derivatives).
    pub(crate) fn point_on(&self, k: usize, u: f64, v: f64, scratch: &mut Vec<f64>) -> Vec<f64> {
        let (p, q, hd, dim) = (self.p, self.q, self.hd, self.dim);
        let net = self.patch(k);
        scratch.clear();
        scratch.resize((p + 1) * hd, 0.0);
        let mut row = vec![0.0; (q + 1) * hd];
        for i in 0..=p {
            row.copy_from_slice(&net[i * (q + 1) * hd..(i + 1) * (q + 1) * hd]);
            for level in 1..=q {
                for j in 0..=q - level {
                    for d in 0..hd {
                        row[j * hd + d] = (1.0 - v) * row[j * hd + d] + v * row[(j + 1) * hd + d];
                    }
                }
            }
            scratch[i * hd..(i + 1) * hd].copy_from_slice(&row[..hd]);
        }
        for level in 1..=p {
            for i in 0..=p - level {
                for d in 0..hd {
                    scratch[i * hd + d] =
                        (1.0 - u) * scratch[i * hd + d] + u * scratch[(i + 1) * hd + d];
                }
            }
        }
        let w = if self.rational { scratch[dim] } else { 1.0 };
        scratch[..dim].iter().map(|x| x / w).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{BSplineCurve, BSplineSurface};

    #[test]
    fn polyline_deviation_holds_on_samples() {
        let c = BSplineCurve::new(
            3,
            vec![0.0, 0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0, 1.0],
            Points::from_2d(&[[0.0, 0.0], [1.0, 3.0], [2.0, -2.0], [4.0, 2.0], [5.0, 0.0]])
                .unwrap(),
        )
        .unwrap();
        let q = QueryCurve::from_bspline(&c).unwrap();
        let poly = q.polyline(1e-4).unwrap();
        assert!(poly.deviation <= 1e-4, "{}", poly.deviation);
        let pts: Vec<&[f64]> = poly.points.iter().collect();
        for i in 0..=3000 {
            let p = c.eval(f64::from(i) / 3000.0).unwrap();
            let d = pts
                .windows(2)
                .map(|w| segment_distance(&p, w[0], w[1]))
                .fold(f64::INFINITY, f64::min);
            assert!(d <= 1e-4 * (1.0 + 1e-12), "sample {i}: {d}");
        }
        assert!(
            q.polyline(0.0).is_err() && q.polyline(f64::NAN).is_err(),
            "bad tolerances"
        );
    }

    #[test]
    fn mesh_deviation_holds_on_samples() {
        // a bicubic bump, 2 × 3 patches
        let (nu, nv) = (5, 6);
        let net: Vec<f64> = (0..nu)
            .flat_map(|i| {
                (0..nv).flat_map(move |j| {
                    let (x, y) = (i as f64, j as f64);
                    [x, y, (x * 0.9).sin() * (y * 0.7).cos()]
                })
            })
            .collect();
        let s = BSplineSurface::new(
            3,
            3,
            vec![0.0, 0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0, 1.0],
            vec![0.0, 0.0, 0.0, 0.0, 0.3, 0.6, 1.0, 1.0, 1.0, 1.0],
            Points::from_flat(3, net).unwrap(),
            (nu, nv),
        )
        .unwrap();
        let q = QuerySurface::from_bspline(&s).unwrap();
        let mesh = q.mesh(1e-3).unwrap();
        assert!(mesh.deviation <= 1e-3, "{}", mesh.deviation);
        assert_bound_holds(&mesh, 7, |u, v| s.eval(u, v).unwrap());
        assert_watertight(&mesh);
    }

    /// `|S − L|` at points inside every `step`-th triangle (barycentric samples) is within the
    /// mesh's deviation.
    fn assert_bound_holds(mesh: &Mesh, step: usize, eval: impl Fn(f64, f64) -> Vec<f64>) {
        for t in mesh.triangles.iter().step_by(step) {
            for (a, b) in [(0.2, 0.3), (0.5, 0.25), (1.0 / 3.0, 1.0 / 3.0), (0.5, 0.5)] {
                let w = [a, b, 1.0 - a - b];
                let mut uv = [0.0; 2];
                let mut l = [0.0; 3];
                for (k, &vi) in t.iter().enumerate() {
                    let vi = vi as usize;
                    for d in 0..2 {
                        uv[d] += w[k] * mesh.uv[vi][d];
                    }
                    for d in 0..3 {
                        l[d] += w[k] * mesh.vertices.point(vi)[d];
                    }
                }
                let e = super::super::pieces::dist(&eval(uv[0], uv[1]), &l);
                assert!(
                    e <= mesh.deviation * (1.0 + 1e-9),
                    "{e} > {}",
                    mesh.deviation
                );
            }
        }
    }

    /// Every edge is shared by two triangles except those on the boundary of the parameter
    /// rectangle, and no two vertices have the same parameters: no cracks, no T-junctions.
    fn assert_watertight(mesh: &Mesh) {
        use std::collections::HashMap;
        let mut uses: HashMap<(u32, u32), usize> = HashMap::new();
        for t in &mesh.triangles {
            for e in 0..3 {
                let (a, b) = (t[e], t[(e + 1) % 3]);
                *uses.entry((a.min(b), a.max(b))).or_default() += 1;
            }
        }
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for p in &mesh.uv {
            for d in 0..2 {
                lo[d] = lo[d].min(p[d]);
                hi[d] = hi[d].max(p[d]);
            }
        }
        let on_side = |i: u32, j: u32| {
            let (a, b) = (mesh.uv[i as usize], mesh.uv[j as usize]);
            (0..2).any(|d| (a[d] == b[d]) && (a[d] == lo[d] || a[d] == hi[d]))
        };
        for (&(a, b), &n) in &uses {
            let want = if on_side(a, b) { 1 } else { 2 };
            assert_eq!(n, want, "edge {a}-{b} used by {n} triangles");
        }
        let mut seen: Vec<[u64; 2]> = mesh.uv.iter().map(|p| p.map(f64::to_bits)).collect();
        seen.sort_unstable();
        seen.dedup();
        assert_eq!(seen.len(), mesh.uv.len(), "duplicate vertices");
    }

    #[test]
    fn rational_mesh_of_a_sphere_octant_is_within_its_bound() {
        // the meridian quarter circle (r, z) revolved a quarter turn about z: a biquadratic patch
        let h = std::f64::consts::FRAC_1_SQRT_2;
        let meridian = [([1.0, 0.0], 1.0), ([1.0, 1.0], h), ([0.0, 1.0], 1.0)];
        let turn = [([1.0, 0.0], 1.0), ([1.0, 1.0], h), ([0.0, 1.0], 1.0)];
        let mut ctrl = Vec::new();
        let mut weights = Vec::new();
        for ([r, z], wm) in meridian {
            for ([c, s], wt) in turn {
                ctrl.extend([r * c, r * s, z]);
                weights.push(wm * wt);
            }
        }
        let knots = vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0];
        let s = crate::NurbsSurface::new(
            2,
            2,
            knots.clone(),
            knots,
            Points::from_flat(3, ctrl).unwrap(),
            weights,
            (3, 3),
        )
        .unwrap();
        let q = QuerySurface::from_nurbs(&s).unwrap();
        let mesh = q.mesh(1e-3).unwrap();
        assert!(mesh.deviation <= 1e-3, "{}", mesh.deviation);
        assert_bound_holds(&mesh, 1, |u, v| s.eval(u, v).unwrap());
        assert_watertight(&mesh);
        // every vertex on the unit sphere; the mesh lies within the bound of it
        for p in mesh.vertices.iter() {
            let r = p.iter().map(|x| x * x).sum::<f64>().sqrt();
            assert!((r - 1.0).abs() < 1e-14, "vertex at radius {r}");
        }
    }
}
