//! Tessellation within a proved deviation: curves to polylines, surfaces to triangle meshes
//! (`docs/theory/queries.md#tessellation`).

use super::intersect::segment_distance;
use super::pieces::{QueryCurve, MAX_QUERY_DEGREE};
use super::surface::{split_curve, QuerySurface};
use crate::error::{check_finite, Error, Result};
use crate::Points;

/// Smallest tolerance accepted, relative to the object's size: below it rounding, not the
/// geometry, would decide whether a chord is within the tolerance.
pub const MIN_RELATIVE_TOLERANCE: f64 = 1e-12;
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
    /// Second-derivative bounds `(M_uu, M_uv, M_vv)` of patch `k` (normalised, local
    /// parameters) from the differences of its net: `|S_uu| ≤ p(p−1)·max|Δ²_u P|`,
    /// `|S_uv| ≤ pq·max|Δ_uΔ_v P|`, `|S_vv| ≤ q(q−1)·max|Δ²_v P|` (the derivatives are Bezier
    /// patches with those nets; convex hull).
    fn second_bounds(&self, k: usize) -> (f64, f64, f64) {
        let (p, q, hd) = (self.p, self.q, self.hd);
        let net = self.patch(k);
        let at = |i: usize, j: usize, d: usize| net[(i * (q + 1) + j) * hd + d];
        let norm = |f: &dyn Fn(usize) -> f64| -> f64 {
            (0..self.dim).map(|d| f(d) * f(d)).sum::<f64>().sqrt()
        };
        let (mut uu, mut uv, mut vv) = (0.0_f64, 0.0_f64, 0.0_f64);
        for i in 0..=p {
            for j in 0..=q {
                if i + 2 <= p {
                    uu = uu.max(norm(&|d| {
                        at(i + 2, j, d) - 2.0 * at(i + 1, j, d) + at(i, j, d)
                    }));
                }
                if j + 2 <= q {
                    vv = vv.max(norm(&|d| {
                        at(i, j + 2, d) - 2.0 * at(i, j + 1, d) + at(i, j, d)
                    }));
                }
                if i < p && j < q {
                    uv = uv.max(norm(&|d| {
                        at(i + 1, j + 1, d) - at(i + 1, j, d) - at(i, j + 1, d) + at(i, j, d)
                    }));
                }
            }
        }
        let (pf, qf) = (p as f64, q as f64);
        (pf * (pf - 1.0) * uu, pf * qf * uv, qf * (qf - 1.0) * vv)
    }

    /// A triangle mesh within `tolerance` of a polynomial surface. Each patch gets an `m × k`
    /// grid split into triangles; the linear interpolant over a triangle of a grid with steps
    /// `h_u, h_v` deviates from the patch by at most
    /// `(h_u² M_uu + 2 h_u h_v M_uv + h_v² M_vv) / 8` (Filip, Magedson & Markot 1986), with the
    /// `M` bounds from the net's second differences, so `m` and `k` are the least that make this
    /// at most `tolerance` — proved from the control points, not sampled
    /// (`docs/theory/queries.md#tessellation`). Patches in one `u` strip share `m`, patches in
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
    /// [`Error::InvalidArgument`] for a rational surface (its derivative bounds are not
    /// implemented here; mesh a polynomial approximation) or a tolerance below
    /// [`MIN_RELATIVE_TOLERANCE`] times the size; [`Error::TooLarge`] beyond
    /// [`MAX_MESH_VERTICES`].
    pub fn mesh(&self, tolerance: f64) -> Result<Mesh> {
        check_tol(tolerance, self.scale)?;
        if self.rational {
            return Err(Error::InvalidArgument {
                what: "surface to mesh",
                reason: "meshing within a proved bound needs a polynomial (non-rational) \
                         surface"
                    .into(),
            });
        }
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
            .map(|k| self.second_bounds(k))
            .collect();
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
        // |S − L| at points inside every triangle (barycentric samples)
        for t in mesh.triangles.iter().step_by(7) {
            for (a, b) in [(0.2, 0.3), (0.5, 0.25), (1.0 / 3.0, 1.0 / 3.0)] {
                let c = 1.0 - a - b;
                let w = [a, b, c];
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
                let p = s.eval(uv[0], uv[1]).unwrap();
                let e = super::super::pieces::dist(&p, &l);
                assert!(
                    e <= mesh.deviation * (1.0 + 1e-9),
                    "{e} > {}",
                    mesh.deviation
                );
            }
        }
    }
}
