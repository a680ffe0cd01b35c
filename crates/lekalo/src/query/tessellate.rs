//! Tessellation within a proved deviation: curves to polylines, surfaces to triangle meshes
//! (`docs/theory/queries.md#tessellation`).

use super::intersect::segment_distance;
use super::pieces::QueryCurve;
use super::pole_normal::MESH_NORMAL_RTOL;
use super::surface::{split_curve, QuerySurface};
use crate::error::{check_finite, readable, Error, Result};
use crate::{Arg, Points, What};

/// The tolerance of a mesh or polyline, as its errors name it.
pub(crate) const TESSELLATION_TOLERANCE: What = What::of(Arg::Tolerance, "tessellation tolerance");

/// The vertices of a mesh, as its size errors name them: their number is set by the tolerance,
/// so the errors carry its key and the front ends name their tolerance argument.
pub(crate) const MESH_VERTICES: What =
    What::of(Arg::Tolerance, "mesh vertices (make the tolerance larger)");

/// Smallest tolerance accepted, relative to the object's size: below it rounding, not the
/// geometry, would decide whether a chord is within the tolerance.
pub const MIN_RELATIVE_TOLERANCE: f64 = 1e-12;
/// Largest number of mesh vertices (a bound on the memory of [`QuerySurface::mesh`]).
pub const MAX_MESH_VERTICES: usize = 1 << 26;
/// Largest number of triangles [`QuerySurface::mesh`] sets out to make: the count is estimated
/// from the control net and the tolerance before any part is made, and a tolerance whose
/// estimate is larger is refused with the tolerance that would fit (about 100 bytes of working
/// memory per triangle: 3 GiB at the limit).
pub const MAX_MESH_TRIANGLES: usize = 1 << 25;
/// Largest number of vertices [`QueryCurve::polyline`] sets out to make, estimated from the
/// control points and the tolerance before any is made (as [`MAX_MESH_TRIANGLES`]; the
/// halving may make up to twice the estimate).
pub const MAX_POLYLINE_POINTS: usize = 1 << 24;

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

impl Mesh {
    /// Unit normal of triangle `k` with vertices `a, b, c`: `(b − a) × (c − a) / |…|`, pointing
    /// to the side from which the triangle is counter-clockwise (for a mesh of a surface, the
    /// side of `S_u × S_v`). `None` for a degenerate triangle, an index outside the mesh, or
    /// vertices that are not 3-D.
    ///
    /// ```
    /// use lekalo::query::Mesh;
    /// use lekalo::Points;
    /// let m = Mesh {
    ///     vertices: Points::from_3d(&[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]])?,
    ///     uv: vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]],
    ///     triangles: vec![[0, 1, 2]],
    ///     deviation: 0.0,
    /// };
    /// assert_eq!(m.facet_normal(0), Some([0.0, 0.0, 1.0]));
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    #[must_use]
    pub fn facet_normal(&self, k: usize) -> Option<[f64; 3]> {
        if self.vertices.dim() != 3 {
            return None;
        }
        let t = self.triangles.get(k)?;
        let p = |i: u32| -> Option<&[f64]> {
            let i = usize::try_from(i).ok()?;
            (i < self.vertices.len()).then(|| self.vertices.point(i))
        };
        let (a, b, c) = (p(t[0])?, p(t[1])?, p(t[2])?);
        let u = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
        let w = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
        let n = [
            u[1] * w[2] - u[2] * w[1],
            u[2] * w[0] - u[0] * w[2],
            u[0] * w[1] - u[1] * w[0],
        ];
        let l = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
        (l > 0.0 && l.is_finite()).then(|| [n[0] / l, n[1] / l, n[2] / l])
    }

    /// Unit normals at the vertices, one per vertex: `given[k]` scaled to unit length where it
    /// is finite and not zero; elsewhere (and for a vertex past `given`) the area-weighted
    /// average of the normals of the triangles that use the vertex, `Σ (b − a) × (c − a)`
    /// normalised (the vertex normal of Gouraud shading with weights the triangles' areas; Max,
    /// "Weights for computing vertex normals from facet normals", J. Graphics Tools 4, 1999),
    /// which turns as the triangles do; `None` where that sum is zero too (a vertex of no
    /// triangle, or only of triangles of no area). Never a non-finite value.
    ///
    /// ```
    /// use lekalo::query::Mesh;
    /// use lekalo::Points;
    /// let m = Mesh {
    ///     vertices: Points::from_3d(&[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]])?,
    ///     uv: vec![[0.0, 0.0]; 3],
    ///     triangles: vec![[0, 1, 2]],
    ///     deviation: 0.0,
    /// };
    /// let n = m.vertex_normals(&[Some([0.0, 0.0, 2.0]), Some([0.0; 3])]);
    /// assert_eq!(n, vec![Some([0.0, 0.0, 1.0]); 3]);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    #[must_use]
    pub fn vertex_normals(&self, given: &[Option<[f64; 3]>]) -> Vec<Option<[f64; 3]>> {
        let n = self.vertices.len();
        let mut out: Vec<Option<[f64; 3]>> = (0..n)
            .map(|k| given.get(k).copied().flatten().and_then(unit))
            .collect();
        if self.vertices.dim() != 3 || out.iter().all(Option::is_some) {
            return out;
        }
        let mut sum = vec![[0.0_f64; 3]; n];
        for t in &self.triangles {
            let t = t.map(|k| k as usize);
            if t.iter().any(|&k| k >= n) {
                continue;
            }
            let p = |k: usize| self.vertices.point(k);
            let (a, b, c) = (p(t[0]), p(t[1]), p(t[2]));
            let c = cross(
                [b[0] - a[0], b[1] - a[1], b[2] - a[2]],
                [c[0] - a[0], c[1] - a[1], c[2] - a[2]],
            );
            for k in t {
                let s = &mut sum[k];
                for d in 0..3 {
                    s[d] += c[d];
                }
            }
        }
        for (o, s) in out.iter_mut().zip(sum) {
            if o.is_none() {
                *o = unit(s);
            }
        }
        out
    }

    /// Unit normals at the vertices of a mesh of `surface` (its `uv` the vertices'
    /// parameters): the surface's `S_u × S_v / |S_u × S_v|` at each vertex's `(u, v)` (brought
    /// back into the domain by whole widths where the mesher unwrapped a loop across a seam,
    /// clamped where it lies outside by rounding; P&T A3.6, A4.4 for the derivatives), reversed where `same_sense` is false
    /// (a face whose normal is not its surface's, ISO 10303-42 `advanced_face.same_sense`), so
    /// that they point to the side the triangles of [`crate::topology::mesh_faces`] and
    /// [`QuerySurface::mesh`] turn about.
    ///
    /// Where the normal is undefined, a pole or a collapsed edge (`|S_u × S_v|` at most
    /// [`MESH_NORMAL_RTOL`] times `max |S_u| · max |S_v|` over the mesh's vertices: at a pole
    /// of a rational surface `S_u` is not zero but rounding, whose cross product points
    /// anywhere), a vertex where `|S_u|` or `|S_v|` is itself at most [`MESH_NORMAL_RTOL`] of
    /// its largest (a collapsed edge, not a fold) takes the limit of the normal along the
    /// non-degenerate direction,
    /// `±S_uv × S_v` on a collapsed edge `v = const` (`±S_u × S_uv` on `u = const`; the
    /// first-order expansion of `S_u` off the edge, `docs/theory/queries.md`, "Vertex normals"):
    /// at a sphere's pole the axis. Elsewhere, or where that limit is degenerate too (a
    /// collapse of higher order), it takes the mean of the surface's unit normals at the `(u, v)`
    /// centres of its triangles (off the pole: a triangle with two vertices on a pole has no
    /// area in space, but its centre is inside the patch), and where these are undefined too
    /// the area-weighted average of its triangles' normals as [`Mesh::vertex_normals`] does;
    /// `None` where that is zero too. All `None` for a surface
    /// that is not 3-D or a mesh whose `uv` does not hold a pair per vertex.
    #[must_use]
    pub fn surface_normals(
        &self,
        surface: &crate::Surface,
        same_sense: bool,
    ) -> Vec<Option<[f64; 3]>> {
        if surface.dim() != 3 || self.uv.len() != self.vertices.len() {
            return vec![None; self.vertices.len()];
        }
        let ((u0, u1), (v0, v1)) = surface.domain();
        // a vertex's (u, v) may lie a period beyond the domain, where the mesher unwrapped a
        // loop across the seam of a closed surface: brought back by whole domain widths (the
        // period of a closed direction); one outside by rounding only is clamped
        let into = |x: f64, a: f64, b: f64| {
            let w = b - a;
            if x < a - 1e-9 * w || x > b + 1e-9 * w {
                a + (x - a).rem_euclid(w)
            } else {
                x.clamp(a, b)
            }
        };
        let sign = if same_sense { 1.0 } else { -1.0 };
        let len = |a: &[f64]| a.iter().map(|x| x * x).sum::<f64>().sqrt();
        // S_u × S_v at each vertex, and the largest |S_u| and |S_v|
        let (mut su_max, mut sv_max) = (0.0_f64, 0.0_f64);
        // S_u × S_v, |S_u| and |S_v| at each vertex
        let crosses: Vec<Option<([f64; 3], f64, f64)>> = self
            .uv
            .iter()
            .map(|&[u, v]| {
                let d = surface
                    .eval_derivatives(into(u, u0, u1), into(v, v0, v1), 1)
                    .ok()?;
                let (su, sv) = (d.point(2), d.point(1));
                su_max = su_max.max(len(su));
                sv_max = sv_max.max(len(sv));
                Some((
                    cross([su[0], su[1], su[2]], [sv[0], sv[1], sv[2]]),
                    len(su),
                    len(sv),
                ))
            })
            .collect();
        let floor = MESH_NORMAL_RTOL * su_max * sv_max;
        let normal_at = |u: f64, v: f64| -> Option<[f64; 3]> {
            let d = surface
                .eval_derivatives(into(u, u0, u1), into(v, v0, v1), 1)
                .ok()?;
            let (su, sv) = (d.point(2), d.point(1));
            let c = cross([su[0], su[1], su[2]], [sv[0], sv[1], sv[2]]);
            (len(&c) > floor).then(|| c.map(|x| sign * x))
        };
        let dom = surface.domain();
        let mut given: Vec<Option<[f64; 3]>> = crosses
            .into_iter()
            .zip(&self.uv)
            .map(|(c, &[u, v])| {
                let (c, su, sv) = c?;
                if len(&c) > floor {
                    return Some(c.map(|x| sign * x));
                }
                // a pole (one derivative itself at the noise level, a collapsed edge): the
                // limit of the normal along the non-degenerate direction; S_u and S_v that
                // are merely near parallel (a fold) are left to the neighbouring samples
                if su > MESH_NORMAL_RTOL * su_max && sv > MESH_NORMAL_RTOL * sv_max {
                    return None;
                }
                let (u, v) = (into(u, u0, u1), into(v, v0, v1));
                super::pole_normal::limit_normal(surface, u, v, dom).map(|n| n.map(|x| sign * x))
            })
            .collect();
        // a degenerate vertex without a limit (a collapse of higher order): the mean of the
        // unit normals at the (u, v) centres of its
        // triangles, inside the patch where the normal is defined (a pole's triangles have
        // two vertices on the pole, no area in space, but their centres are off it)
        if given.iter().any(Option::is_none) {
            let mut sum = vec![[0.0_f64; 3]; given.len()];
            for t in &self.triangles {
                let t = t.map(|k| k as usize);
                if t.iter().any(|&k| k >= given.len()) || t.iter().all(|&k| given[k].is_some()) {
                    continue;
                }
                let c = t.map(|k| self.uv[k]);
                let centre = |d: usize| (c[0][d] + c[1][d] + c[2][d]) / 3.0;
                let Some(n) = normal_at(centre(0), centre(1)).and_then(unit) else {
                    continue;
                };
                for k in t {
                    for d in 0..3 {
                        sum[k][d] += n[d];
                    }
                }
            }
            for (g, s) in given.iter_mut().zip(sum) {
                if g.is_none() {
                    *g = unit(s);
                }
            }
        }
        self.vertex_normals(&given)
    }
}

/// `a × b`.
fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// `n / |n|`, or `None` for a zero or non-finite `n`.
fn unit(n: [f64; 3]) -> Option<[f64; 3]> {
    // directly when |n|² is a normal number (a unit normal as given stays as it is), else
    // scaled first, so that neither tiny nor huge components over- or underflow the length
    if !n.iter().all(|x| x.is_finite()) {
        return None;
    }
    let l2 = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
    if l2.is_normal() && l2.is_finite() {
        let l = l2.sqrt();
        return Some(n.map(|x| x / l));
    }
    let m = n[0].abs().max(n[1].abs()).max(n[2].abs());
    if m == 0.0 {
        return None;
    }
    let s = n.map(|x| x / m);
    let l = (s[0] * s[0] + s[1] * s[1] + s[2] * s[2]).sqrt();
    Some(s.map(|x| x / l))
}

/// [`Error::ToleranceNotMet`] for the mesh of `what` when its proved deviation bound is above
/// `tolerance` by more than rounding (bounds are computed in coordinates normalised by the
/// object's size and scaled back, a few ulps).
pub(crate) fn check_deviation(what: &str, deviation: f64, tolerance: f64) -> Result<()> {
    if deviation > tolerance * (1.0 + 8.0 * f64::EPSILON) {
        return Err(Error::ToleranceNotMet {
            what: what.into(),
            deviation,
            tolerance,
        });
    }
    Ok(())
}

pub(crate) fn check_tol(tol: f64, scale: f64) -> Result<()> {
    check_finite(TESSELLATION_TOLERANCE, &[tol])?;
    if !(tol >= MIN_RELATIVE_TOLERANCE * scale) {
        return Err(Error::InvalidArgument {
            what: TESSELLATION_TOLERANCE,
            reason: format!(
                "{} is below {} times the object's size {}, where rounding would decide the \
                 bound; use a tolerance of at least {}",
                readable(&tol),
                readable(&MIN_RELATIVE_TOLERANCE),
                readable(&scale),
                readable(&(MIN_RELATIVE_TOLERANCE * scale))
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
    /// curve's size, or NaN, or one whose polyline is estimated (before any point is made) at
    /// more than [`MAX_POLYLINE_POINTS`] vertices.
    pub fn polyline(&self, tolerance: f64) -> Result<Polyline> {
        check_tol(tolerance, self.scale)?;
        let tol = tolerance / self.scale;
        self.check_polyline_size(tolerance, tol)?;
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

impl QueryCurve {
    /// Refuses a tolerance whose polyline would be too large to make, before any point is
    /// made: a piece whose Cartesian control points have second differences up to `D` needs
    /// about `sqrt(p(p−1)·D / (4·tol))` chords (a part of relative length `h` has its control
    /// points about `p(p−1)·D·h²/4` from its chord; exactly `D·h²/2` for `p = 2`). Smooth
    /// curves need about `sqrt(1/tol)` in all; a curve of many wiggly pieces at a tiny
    /// tolerance needs far more than memory holds.
    fn check_polyline_size(&self, tolerance: f64, tol: f64) -> Result<()> {
        let (dim, hd, p) = (self.dim, self.hd, self.degree);
        if p < 2 {
            return Ok(()); // one chord per piece
        }
        #[allow(clippy::cast_precision_loss)] // degrees are small
        let pf = p as f64;
        let mut points = 0.0_f64;
        let mut cart = vec![0.0; (p + 1) * dim];
        for k in 0..self.piece_count() {
            for (q, c) in self
                .piece(k)
                .chunks_exact(hd)
                .zip(cart.chunks_exact_mut(dim))
            {
                let w = if self.rational { q[dim] } else { 1.0 };
                for d in 0..dim {
                    c[d] = q[d] / w;
                }
            }
            let mut second = 0.0_f64;
            for i in 0..p - 1 {
                let s: f64 = (0..dim)
                    .map(|d| {
                        let t = cart[(i + 2) * dim + d] - 2.0 * cart[(i + 1) * dim + d]
                            + cart[i * dim + d];
                        t * t
                    })
                    .sum();
                second = second.max(s.sqrt());
            }
            points += (pf * (pf - 1.0) * second / (4.0 * tol)).sqrt().max(1.0);
        }
        #[allow(clippy::cast_precision_loss)] // 2^25 is exact
        let max = MAX_POLYLINE_POINTS as f64;
        if points > max {
            return Err(Error::InvalidArgument {
                what: TESSELLATION_TOLERANCE,
                reason: format!(
                    "{tolerance:e} needs about {points:.1e} polyline points, more than the \
                     {MAX_POLYLINE_POINTS} a polyline may have; use a tolerance of at least {:.1e}",
                    tolerance * (points / max).powi(2)
                ),
            });
        }
        Ok(())
    }
}

impl QuerySurface {
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
pub(crate) mod tests {
    use super::*;
    use crate::{BSplineCurve, BSplineSurface};

    #[test]
    fn a_deviation_above_the_tolerance_is_an_error_naming_the_bound() {
        assert_eq!(check_deviation("surface mesh", 0.1, 0.1), Ok(()));
        // a few ulps of rounding from the normalised coordinates are not above
        let rounded = 0.1 * (1.0 + 4.0 * f64::EPSILON);
        assert_eq!(check_deviation("surface mesh", rounded, 0.1), Ok(()));
        let e = check_deviation("surface mesh", 0.13, 0.1).unwrap_err();
        assert_eq!(
            e,
            Error::ToleranceNotMet {
                what: "surface mesh".into(),
                deviation: 0.13,
                tolerance: 0.1
            }
        );
        assert!(e.to_string().contains("at least 0.13"), "{e}");
    }

    /// A refused tolerance of any query carries the key `Arg::Tolerance` (the arc length's,
    /// relative, `Arg::RelativeTolerance`), so that every front end names its own tolerance
    /// argument (`--tolerance`, `tolerance`, `rtol`), whatever the words of the message.
    #[test]
    fn every_refused_query_tolerance_carries_the_key() {
        let c = BSplineCurve::new(
            3,
            vec![0.0, 0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0, 1.0],
            Points::from_2d(&[[0.0, 0.0], [1.0, 3.0], [2.0, -2.0], [4.0, 2.0], [5.0, 0.0]])
                .unwrap(),
        )
        .unwrap();
        let q = QueryCurve::from_bspline(&c).unwrap();
        for bad in [f64::NAN, -1.0, 0.0] {
            let errors = [
                ("polyline", q.polyline(bad).map(|_| ())),
                ("offset", q.offset(0.1, bad).map(|_| ())),
                ("intersect", q.intersect(&q, bad).map(|_| ())),
                ("self_intersections", q.self_intersections(bad).map(|_| ())),
                (
                    "parametrized_spline",
                    q.arc_length(1e-12)
                        .and_then(|a| a.parametrized_spline(bad))
                        .map(|_| ()),
                ),
            ];
            for (what, r) in errors {
                let e = r.expect_err(what);
                assert_eq!(e.arg(), Some(Arg::Tolerance), "{what}({bad}): {e}");
            }
        }
        let e = q.project_all(&[1.0, 1.0], -1.0).unwrap_err();
        assert_eq!(e.arg(), Some(Arg::Tolerance), "project_all: {e}");
        for bad in [f64::NAN, -1.0, 0.0] {
            let e = q.arc_length(bad).map(|_| ()).unwrap_err();
            assert_eq!(
                e.arg(),
                Some(Arg::RelativeTolerance),
                "arc_length({bad}): {e}"
            );
        }
    }

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
    fn polylines_too_large_to_make_are_refused_before_any_point() {
        // 4,096 zigzag points of degree 2: at twice the smallest tolerance accepted each of
        // the 4,094 pieces needs ~10^4 chords, 4.5·10^7 points in all (gigabytes with the
        // work list); refused at once
        let pts: Vec<[f64; 2]> = (0..4096)
            .map(|i| [f64::from(i), f64::from(i % 2)])
            .collect();
        let c = BSplineCurve::from_knot_vector(
            2,
            crate::KnotVector::clamped_uniform(2, pts.len()).unwrap(),
            Points::from_2d(&pts).unwrap(),
        )
        .unwrap();
        let q = QueryCurve::from_bspline(&c).unwrap();
        let tiny = 2e-12 * q.scale();
        let start = std::time::Instant::now();
        let e = q.polyline(tiny).unwrap_err().to_string();
        assert!(start.elapsed().as_secs() < 5, "refused before the polyline");
        assert!(
            e.contains("tessellation tolerance") && e.contains("polyline points"),
            "{e}"
        );
        // a tolerance that fits is meshed
        let poly = q.polyline(1e-3).unwrap();
        assert!(
            poly.points.len() < MAX_POLYLINE_POINTS,
            "{}",
            poly.points.len()
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
        // adaptive: parts of different sizes meet, and the larger ones are fans through the
        // smaller ones' corners (a fan triangle has one pair of vertices on a parameter line,
        // a grid triangle two)
        let lines = |t: &[u32; 3]| {
            (0..3)
                .filter(|&e| {
                    let (a, b) = (mesh.uv[t[e] as usize], mesh.uv[t[(e + 1) % 3] as usize]);
                    a[0] == b[0] || a[1] == b[1]
                })
                .count()
        };
        assert!(mesh.triangles.iter().any(|t| lines(t) == 1), "no fan");
        assert!(mesh.triangles.iter().any(|t| lines(t) == 2), "no grid part");
        // no two triangles overlap: their parameter areas add up to the domain's
        assert_covers_the_domain(&mesh, "");
        // the same mesh on one thread
        let one = rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .build()
            .unwrap()
            .install(|| q.mesh(1e-3).unwrap());
        assert_eq!(one, mesh, "the mesh depends on the thread count");
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
    /// Every triangle counter-clockwise in the parameters and their areas adding up to the unit
    /// domain's: no two overlap and none is missing. `what` names the case in a failure.
    pub(crate) fn assert_covers_the_domain(mesh: &Mesh, what: &str) {
        let area: f64 = mesh
            .triangles
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|i| mesh.uv[i as usize]);
                0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]))
            })
            .inspect(|&a| assert!(a > 0.0, "{what}: a triangle is not counter-clockwise"))
            .sum();
        assert!((area - 1.0).abs() < 1e-12, "{what}: parameter area {area}");
    }

    pub(crate) fn assert_watertight(mesh: &Mesh) {
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

    /// The dot product of `a` and `b`.
    fn dot(a: [f64; 3], b: &[f64]) -> f64 {
        a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
    }

    /// The normals of a mesh of an eighth of a sphere, its north pole among its vertices: at
    /// every vertex but the pole the sphere's exact normal (the vertex over the radius, outward
    /// or inward as `S_u × S_v` points), at the pole (where `S_u` is rounding, whose cross
    /// product with `S_v` points anywhere) the average of its triangles' normals, near the
    /// axis; each unit, finite, and on the side every triangle turns about;
    /// reversed for a face whose sense is not its surface's.
    #[test]
    fn vertex_normals_are_the_surface_s_and_averaged_at_a_pole() {
        use crate::surface::Placement;
        use crate::{NurbsSurface, Surface};
        use std::f64::consts::FRAC_PI_2;
        let frame = Placement::new([0.0; 3], None, None).unwrap();
        let s = NurbsSurface::sphere(&frame, 1.0, (0.0, FRAC_PI_2), (0.0, FRAC_PI_2)).unwrap();
        let surface = Surface::Nurbs(s);
        let m = surface.to_query().unwrap().mesh(1e-3).unwrap();
        let normals = m.surface_normals(&surface, true);
        assert_eq!(normals.len(), m.vertices.len());
        let mut poles = 0;
        let mut outward = 0;
        for (k, n) in normals.iter().enumerate() {
            let n = n.expect("every vertex has a normal");
            assert!(n.iter().all(|x| x.is_finite()), "{n:?}");
            assert!((dot(n, &n) - 1.0).abs() < 1e-14, "unit: {n:?}");
            let p = m.vertices.point(k);
            if p[2] > 1.0 - 1e-12 {
                poles += 1;
                // the limit normal along the non-degenerate direction: the axis
                assert!(
                    (n[2].abs() - 1.0).abs() < 1e-12,
                    "the pole's limit normal {n:?}"
                );
                continue;
            }
            // the sphere's normal at p is ±p
            let d = dot(n, p);
            assert!((d.abs() - 1.0).abs() < 1e-12, "{n:?} at {p:?}");
            outward += usize::from(d > 0.0);
        }
        assert!(poles > 0, "the pole is a vertex");
        assert!(
            outward == 0 || outward == normals.len() - poles,
            "one side throughout"
        );
        // every triangle turns about the normals at its vertices
        for (t, tri) in m.triangles.iter().enumerate() {
            let Some(f) = m.facet_normal(t) else { continue };
            for &k in tri {
                let n = normals[k as usize].unwrap();
                assert!(dot(n, &f) > 0.0, "triangle {t} {f:?} against {n:?}");
            }
        }
        // a face whose normal is not its surface's: the normals reversed
        let reversed = m.surface_normals(&surface, false);
        for (k, (a, b)) in normals.iter().zip(&reversed).enumerate() {
            let (a, b) = (a.unwrap(), b.unwrap());
            if m.vertices.point(k)[2] <= 1.0 - 1e-12 {
                assert_eq!(a.map(|x| -x), b);
            }
        }
    }

    /// Given normals are made unit; a zero or non-finite one, or a vertex past them, takes
    /// the average of its triangles' normals weighted by their areas; a vertex of no triangle
    /// has none.
    #[test]
    fn given_normals_are_made_unit_and_missing_ones_averaged() {
        let m = Mesh {
            vertices: Points::from_3d(&[
                [0.0, 0.0, 0.0],
                [2.0, 0.0, 0.0],
                [0.0, 2.0, 0.0],
                [0.0, 0.0, 1.0],
                [9.0, 9.0, 9.0],
            ])
            .unwrap(),
            uv: vec![[0.0, 0.0]; 5],
            // in the plane z = 0 (area 2, normal +z) and in x = 0 (area 1, normal +x)
            triangles: vec![[0, 1, 2], [0, 2, 3]],
            deviation: 0.0,
        };
        let n = m.vertex_normals(&[
            Some([0.0; 3]),
            Some([0.0, 3e-300, 4e-300]),
            Some([f64::NAN, 0.0, 1.0]),
        ]);
        // vertex 0 of both: (0, 0, 4) + (2, 0, 0) over its length
        assert_eq!(n[0], Some([2.0, 0.0, 4.0].map(|x| x / 20f64.sqrt())));
        assert_eq!(n[1], Some([0.0, 0.6, 0.8]), "tiny but not zero");
        assert_eq!(n[2], n[0], "not finite: averaged as vertex 0, of both too");
        assert_eq!(
            n[3],
            Some([1.0, 0.0, 0.0]),
            "past the given: its triangle's"
        );
        assert_eq!(n[4], None, "of no triangle");
    }
}
