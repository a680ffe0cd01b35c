//! Curvature analysis: curvature and torsion along curves, inflection points and curvature
//! extrema, and the principal, mean and Gaussian curvatures of surfaces
//! (`docs/theory/queries.md#curvature`).

use super::pieces::{bern_roots, Bern, QueryCurve};
use super::surface::QuerySurface;
use crate::error::readable;
use crate::error::{Error, Result};

/// Relative tolerance below which [`QueryCurve::curvature_extrema`] treats two curvatures as
/// equal: extrema that differ from their neighbours by at most this times the curve's largest
/// curvature are rounding, not extrema. `1e-10`: the curvature of an exact NURBS arc varies by
/// a few ulps (`~1e-15` relative), a real extremum by far more.
pub const CURVATURE_EXTREMUM_RTOL: f64 = 1e-10;

/// A local extremum of a curve's curvature `|κ|`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CurvatureExtremum {
    /// Parameter.
    pub t: f64,
    /// Curvature there (`≥ 0`).
    pub curvature: f64,
    /// `true` for a maximum, `false` for a minimum.
    pub maximum: bool,
}

/// Curvatures of a surface at a point (3-D).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfaceCurvature {
    /// Gaussian curvature `K = k₁k₂`.
    pub gaussian: f64,
    /// Mean curvature `H = (k₁ + k₂)/2` (sign: positive when the surface bends towards the
    /// normal `S_u × S_v`).
    pub mean: f64,
    /// Principal curvatures `k₁ ≥ k₂`.
    pub principal: (f64, f64),
}

impl QueryCurve {
    /// Derivatives `C, C', C'', C'''` (normalised, local parameter) of piece `k` at `s`:
    /// homogeneous derivatives from the differenced net (P&T eq. 3.8), then Leibniz's rule for
    /// the quotient (P&T eq. 4.8).
    pub(crate) fn ders3(&self, k: usize, s: f64) -> [Vec<f64>; 4] {
        let (dim, hd, n) = (self.dim, self.hd, self.degree);
        let mut net: Vec<f64> = self.piece(k).to_vec();
        let mut h: Vec<Vec<f64>> = Vec::with_capacity(4);
        let mut factor = 1.0;
        for order in 0..=3 {
            let m = net.len() / hd;
            if m == 0 {
                h.push(vec![0.0; hd]);
                continue;
            }
            let mut b = net.clone();
            for level in 1..m {
                for i in 0..m - level {
                    for d in 0..hd {
                        b[i * hd + d] = (1.0 - s) * b[i * hd + d] + s * b[(i + 1) * hd + d];
                    }
                }
            }
            h.push(b[..hd].iter().map(|x| x * factor).collect());
            // difference the net for the next order
            if m > 1 {
                factor *= (n - order) as f64;
                net = (0..m - 1)
                    .flat_map(|i| (0..hd).map(move |d| (i, d)))
                    .map(|(i, d)| net[(i + 1) * hd + d] - net[i * hd + d])
                    .collect();
            } else {
                net.clear();
            }
        }
        if !self.rational {
            return [
                h[0][..dim].to_vec(),
                h[1][..dim].to_vec(),
                h[2][..dim].to_vec(),
                h[3][..dim].to_vec(),
            ];
        }
        let w: Vec<f64> = h.iter().map(|x| x[dim]).collect();
        let mut c: Vec<Vec<f64>> = Vec::with_capacity(4);
        let binom = [
            [1.0, 0.0, 0.0, 0.0],
            [1.0, 1.0, 0.0, 0.0],
            [1.0, 2.0, 1.0, 0.0],
            [1.0, 3.0, 3.0, 1.0],
        ];
        for kk in 0..4 {
            let mut v: Vec<f64> = h[kk][..dim].to_vec();
            for i in 1..=kk {
                for d in 0..dim {
                    v[d] -= binom[kk][i] * w[i] * c[kk - i][d];
                }
            }
            c.push(v.iter().map(|x| x / w[0]).collect());
        }
        [c[0].clone(), c[1].clone(), c[2].clone(), c[3].clone()]
    }

    /// Curvature `|C' × C''| / |C'|³` at `t` (in the curve's units); `None` where `C' = 0`.
    ///
    /// # Errors
    /// [`Error::ParameterOutOfDomain`] outside the domain or for NaN.
    pub fn curvature_at(&self, t: f64) -> Result<Option<f64>> {
        self.check_t(t)?;
        let k = self.piece_of(t);
        let d = self.ders3(k, self.local(k, t));
        Ok(crate::curvature(&d[1], &d[2]).map(|x| x / self.scale))
    }

    /// Curvature vector `κN = (C''|C'|² − C'(C'·C''))/|C'|⁴` at `t`: length the curvature,
    /// pointing to the centre of curvature (`docs/theory/queries.md#curvature`); the teeth of a
    /// curvature comb. `None` where `C' = 0`.
    ///
    /// ```
    /// use lekalo::{NurbsCurve, QueryCurve};
    /// // a circle of radius 2 about (1, 0): κN = (centre − C)/r²
    /// let c = NurbsCurve::circle(&[1.0, 0.0], &[1.0, 0.0], &[0.0, 1.0], 2.0)?;
    /// let q = QueryCurve::from_nurbs(&c)?;
    /// let k = q.curvature_vector_at(0.3)?.unwrap();
    /// let p = q.point(0.3)?;
    /// for d in 0..2 {
    ///     assert!((k[d] - ([1.0, 0.0][d] - p[d]) / 4.0).abs() < 1e-13);
    /// }
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::ParameterOutOfDomain`] outside the domain or for NaN.
    pub fn curvature_vector_at(&self, t: f64) -> Result<Option<Vec<f64>>> {
        self.check_t(t)?;
        let k = self.piece_of(t);
        let d = self.ders3(k, self.local(k, t));
        let (a, b) = (&d[1], &d[2]);
        let aa: f64 = a.iter().map(|x| x * x).sum();
        if !(aa > 0.0) {
            return Ok(None);
        }
        let ab: f64 = a.iter().zip(b).map(|(x, y)| x * y).sum();
        Ok(Some(
            a.iter()
                .zip(b)
                .map(|(x, y)| (y * aa - x * ab) / (aa * aa) / self.scale)
                .collect(),
        ))
    }

    /// Torsion `(C' × C'')·C''' / |C' × C''|²` of a 3-D curve at `t`; `None` where the
    /// curvature is zero.
    ///
    /// # Errors
    /// [`Error::Dimension`] unless the curve is 3-D; [`Error::ParameterOutOfDomain`].
    pub fn torsion_at(&self, t: f64) -> Result<Option<f64>> {
        if self.dim != 3 {
            return Err(Error::Dimension {
                what: "curve for torsion".into(),
                expected: 3,
                got: self.dim,
            });
        }
        self.check_t(t)?;
        let k = self.piece_of(t);
        let [_, a, b, c] = self.ders3(k, self.local(k, t));
        Ok(crate::curve::torsion(&a, &b, &c).map(|tau| tau / self.scale))
    }

    fn coord_polys(&self, k: usize) -> (Vec<Bern>, Option<Bern>) {
        let (dim, hd, n) = (self.dim, self.hd, self.degree);
        let piece = self.piece(k);
        let a = (0..dim)
            .map(|d| Bern((0..=n).map(|i| piece[i * hd + d]).collect()))
            .collect();
        let w = self
            .rational
            .then(|| Bern((0..=n).map(|i| piece[i * hd + dim]).collect()));
        (a, w)
    }

    /// Inflection points of a planar curve: parameters where `C' × C''` changes sign. For a
    /// polynomial piece that is a polynomial of degree `2p − 3`; for a rational one
    /// `det[A, A', A'']` of the homogeneous coordinates (degree `3p − 3`); their roots come from
    /// the Bernstein coefficients, so none is missed.
    ///
    /// # Errors
    /// [`Error::Dimension`] unless the curve is planar.
    pub fn inflections(&self) -> Result<Vec<f64>> {
        if self.dim != 2 {
            return Err(Error::Dimension {
                what: "curve for inflections".into(),
                expected: 2,
                got: self.dim,
            });
        }
        let mut out = Vec::new();
        if self.degree < 2 {
            return Ok(out);
        }
        for k in 0..self.piece_count() {
            let (a, w) = self.coord_polys(k);
            let x = match &w {
                None => {
                    let (x1, y1) = (a[0].deriv(), a[1].deriv());
                    x1.mul(&y1.deriv()).sub(&y1.mul(&x1.deriv()))
                }
                Some(w) => {
                    let rows = [
                        [a[0].clone(), a[1].clone(), w.clone()],
                        [a[0].deriv(), a[1].deriv(), w.deriv()],
                        [
                            a[0].deriv().deriv(),
                            a[1].deriv().deriv(),
                            w.deriv().deriv(),
                        ],
                    ];
                    let m = |i: usize, j: usize, p: usize, q: usize| {
                        rows[1][i]
                            .mul(&rows[2][j])
                            .sub(&rows[1][p].mul(&rows[2][q]))
                    };
                    rows[0][0]
                        .mul(&m(1, 2, 2, 1))
                        .sub(&rows[0][1].mul(&m(0, 2, 2, 0)))
                        .add(&rows[0][2].mul(&m(0, 1, 1, 0)))
                }
            };
            let mag = x.0.iter().fold(0.0_f64, |m, c| m.max(c.abs()));
            // A piece straight to rounding (a segment of a polyline kept exactly, elevated) has
            // `C' × C''` of the size of the rounding of its control points: with coordinates of
            // size `s`, the derivatives of order j are of size `p^j s`, so the products are of
            // size `p³ s²` (`p³ s³` for the homogeneous determinant), and their rounding noise
            // changes sign at random. Such a piece has no inflection.
            let size = self.piece(k).iter().fold(0.0_f64, |m, c| m.max(c.abs()));
            #[allow(clippy::cast_precision_loss)] // a degree
            let p3 = (self.degree as f64).powi(3);
            let scale = p3 * size * size * if w.is_some() { size } else { 1.0 };
            if mag <= 1e3 * f64::EPSILON * scale {
                continue;
            }
            for s in bern_roots(&x, 1e3 * f64::EPSILON * mag) {
                // a sign change, not a touching zero
                let (l, r) = ((s - 1e-6).max(0.0), (s + 1e-6).min(1.0));
                if x.eval(l) * x.eval(r) < 0.0 {
                    let t = self.global(k, s);
                    if out.last().is_none_or(|u: &f64| (t - u).abs() > 1e-12) {
                        out.push(t);
                    }
                }
            }
        }
        Ok(out)
    }

    /// Local extrema of the curvature `|κ|` inside the pieces: the roots of
    /// `d(κ²)/dt ∝ G'|C'|² − 6G(C'·C'')` with `G = |C'|²|C''|² − (C'·C'')²`, a polynomial of
    /// degree `6p − 9` on a polynomial piece (roots from its Bernstein coefficients, none
    /// missed); on a rational piece the sign of the same expression is scanned at 64 points and
    /// its changes bisected (an extremum narrower than 1/64 of a piece can be missed there).
    /// Stationary points (`C' = 0`) are skipped. Sorted by `t`.
    ///
    /// An extremum must stand out from rounding: a root whose curvature is within
    /// [`CURVATURE_EXTREMUM_RTOL`] `× κ_max` of the curvature at a neighbouring root (or at the
    /// curve's end on that side), `κ_max` the largest curvature at the roots and the ends, is
    /// dropped. So a curve of constant curvature (an exact circular arc, whose `d(κ²)/dt` is
    /// rounding noise that changes sign many times) has no extrema, and a flat stretch of
    /// curvature between two real extrema adds none.
    ///
    /// ```
    /// use lekalo::{BSplineCurve, Points, QueryCurve};
    /// // the parabola y = x² on x ∈ [−1, 1]: curvature 2 at its vertex, the maximum
    /// let c = BSplineCurve::new(2, vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
    ///                           Points::from_2d(&[[-1.0, 1.0], [0.0, -1.0], [1.0, 1.0]])?)?;
    /// let ext = QueryCurve::from_bspline(&c)?.curvature_extrema()?;
    /// assert_eq!(ext.len(), 1);
    /// assert!(ext[0].maximum && (ext[0].t - 0.5).abs() < 1e-12 && (ext[0].curvature - 2.0).abs() < 1e-10);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// None for valid curves; kept fallible like the other queries.
    pub fn curvature_extrema(&self) -> Result<Vec<CurvatureExtremum>> {
        let mut out: Vec<CurvatureExtremum> = Vec::new();
        if self.degree < 2 {
            return Ok(out);
        }
        for k in 0..self.piece_count() {
            let roots = if self.rational {
                self.scan_extrema(k)
            } else {
                let (a, _) = self.coord_polys(k);
                let d1: Vec<Bern> = a.iter().map(Bern::deriv).collect();
                let d2: Vec<Bern> = d1.iter().map(Bern::deriv).collect();
                let d3: Vec<Bern> = d2.iter().map(Bern::deriv).collect();
                let dot = |x: &[Bern], y: &[Bern]| {
                    x.iter()
                        .zip(y)
                        .map(|(p, q)| p.mul(q))
                        .reduce(|s, t| s.add(&t))
                        .unwrap_or(Bern(vec![0.0]))
                };
                let (aa, ab, bb) = (dot(&d1, &d1), dot(&d1, &d2), dot(&d2, &d2));
                let (bc, ac) = (dot(&d2, &d3), dot(&d1, &d3));
                let g = aa.mul(&bb).sub(&ab.mul(&ab));
                let dg = aa.mul(&bc).sub(&ab.mul(&ac)).scale(2.0);
                let f = dg.mul(&aa).sub(&g.mul(&ab).scale(6.0));
                let mag = f.0.iter().fold(0.0_f64, |m, c| m.max(c.abs()));
                let f2 = f.clone();
                bern_roots(&f, 1e3 * f64::EPSILON * mag)
                    .into_iter()
                    .filter(|&s| {
                        let (l, r) = ((s - 1e-6).max(0.0), (s + 1e-6).min(1.0));
                        f2.eval(l) * f2.eval(r) < 0.0
                    })
                    .collect()
            };
            for s in roots {
                let t = self.global(k, s);
                let d = self.ders3(k, s);
                let Some(kappa) = crate::curvature(&d[1], &d[2]) else {
                    continue;
                };
                let h = 1e-4;
                let around = |x: f64| {
                    let d = self.ders3(k, x.clamp(0.0, 1.0));
                    crate::curvature(&d[1], &d[2]).unwrap_or(kappa)
                };
                let maximum = around(s - h) <= kappa && around(s + h) <= kappa;
                if out.last().is_some_and(|e| (e.t - t).abs() <= 1e-12) {
                    continue;
                }
                out.push(CurvatureExtremum {
                    t,
                    curvature: kappa / self.scale,
                    maximum,
                });
            }
        }
        Ok(self.drop_rounding_extrema(out))
    }

    /// The extrema of `found` that differ from both neighbours (the neighbouring extrema, or
    /// the curve's ends) by more than [`CURVATURE_EXTREMUM_RTOL`] `× κ_max`.
    fn drop_rounding_extrema(&self, found: Vec<CurvatureExtremum>) -> Vec<CurvatureExtremum> {
        if found.is_empty() {
            return found;
        }
        let end = |k: usize, s: f64| {
            let d = self.ders3(k, s);
            crate::curvature(&d[1], &d[2]).map(|x| x / self.scale)
        };
        let first = end(0, 0.0);
        let last = end(self.piece_count() - 1, 1.0);
        let scale = found
            .iter()
            .map(|e| e.curvature)
            .chain(first)
            .chain(last)
            .fold(0.0_f64, f64::max);
        let tol = CURVATURE_EXTREMUM_RTOL * scale;
        let near = |a: f64, b: Option<f64>| b.is_some_and(|b| (a - b).abs() <= tol);
        (0..found.len())
            .filter(|&i| {
                let k = found[i].curvature;
                let before = if i == 0 {
                    first
                } else {
                    Some(found[i - 1].curvature)
                };
                let after = found.get(i + 1).map(|e| e.curvature).or(last);
                !near(k, before) && !near(k, after)
            })
            .map(|i| found[i])
            .collect()
    }

    /// `d(κ²)/ds` up to a positive factor, from the derivatives.
    fn kappa_slope(&self, k: usize, s: f64) -> f64 {
        let d = self.ders3(k, s);
        let dot = |x: &[f64], y: &[f64]| -> f64 { x.iter().zip(y).map(|(a, b)| a * b).sum() };
        let (aa, ab, bb) = (dot(&d[1], &d[1]), dot(&d[1], &d[2]), dot(&d[2], &d[2]));
        let (bc, ac) = (dot(&d[2], &d[3]), dot(&d[1], &d[3]));
        let g = aa * bb - ab * ab;
        let dg = 2.0 * (aa * bc - ab * ac);
        dg * aa - 6.0 * g * ab
    }

    fn scan_extrema(&self, k: usize) -> Vec<f64> {
        let mut roots = Vec::new();
        let n = 64;
        let mut prev = (0.0, self.kappa_slope(k, 0.0));
        for i in 1..=n {
            let s = f64::from(i) / f64::from(n);
            let f = self.kappa_slope(k, s);
            if prev.1 * f < 0.0 {
                let (mut lo, mut hi) = (prev.0, s);
                for _ in 0..60 {
                    let m = 0.5 * (lo + hi);
                    if (self.kappa_slope(k, m) < 0.0) == (prev.1 < 0.0) {
                        lo = m;
                    } else {
                        hi = m;
                    }
                }
                roots.push(0.5 * (lo + hi));
            }
            prev = (s, f);
        }
        roots
    }
}

impl QuerySurface {
    /// The patch and local parameters of `(u, v)`.
    pub(crate) fn locate(&self, u: f64, v: f64) -> Result<(usize, f64, f64)> {
        let first = self.ranges[0];
        let last = self.ranges[self.ranges.len() - 1];
        let (umin, umax, vmin, vmax) = (first.0 .0, last.0 .1, first.1 .0, last.1 .1);
        if !(u >= umin && u <= umax) {
            return Err(Error::ParameterOutOfDomain {
                t: u,
                min: umin,
                max: umax,
            });
        }
        if !(v >= vmin && v <= vmax) {
            return Err(Error::ParameterOutOfDomain {
                t: v,
                min: vmin,
                max: vmax,
            });
        }
        let k = self
            .ranges
            .iter()
            .position(|((u0, u1), (v0, v1))| u >= *u0 && u <= *u1 && v >= *v0 && v <= *v1)
            .unwrap_or(0);
        let ((u0, u1), (v0, v1)) = self.ranges[k];
        Ok((
            k,
            ((u - u0) / (u1 - u0)).clamp(0.0, 1.0),
            ((v - v0) / (v1 - v0)).clamp(0.0, 1.0),
        ))
    }

    /// Gaussian, mean and principal curvatures of a 3-D surface at `(u, v)` from the first and
    /// second fundamental forms (do Carmo §3-3). The normal is `S_u × S_v`.
    ///
    /// ```
    /// use lekalo::{NurbsSurface, Points, QuerySurface};
    /// // a cylinder of radius 2 (a quarter): K = 0, |H| = 1/4
    /// const H: f64 = std::f64::consts::FRAC_1_SQRT_2;
    /// let net = Points::from_3d(&[[2.0, 0.0, 0.0], [2.0, 0.0, 1.0], [2.0, 2.0, 0.0], [2.0, 2.0, 1.0],
    ///                             [0.0, 2.0, 0.0], [0.0, 2.0, 1.0]])?;
    /// let s = NurbsSurface::new(2, 1, vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0], vec![0.0, 0.0, 1.0, 1.0],
    ///                           net, vec![1.0, 1.0, H, H, 1.0, 1.0], (3, 2))?;
    /// let c = QuerySurface::from_nurbs(&s)?.curvature(0.3, 0.6)?;
    /// assert!(c.gaussian.abs() < 1e-12 && (c.mean.abs() - 0.25).abs() < 1e-12);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::Dimension`] unless 3-D; [`Error::ParameterOutOfDomain`]; [`Error::InvalidArgument`]
    /// at a singular point (`S_u × S_v = 0`).
    pub fn curvature(&self, u: f64, v: f64) -> Result<SurfaceCurvature> {
        if self.dim != 3 {
            return Err(Error::Dimension {
                what: "surface for curvature".into(),
                expected: 3,
                got: self.dim,
            });
        }
        let (k, lu, lv) = self.locate(u, v)?;
        let (_, d) = self.eval_patch(k, lu, lv);
        let (su, sv, suu, suv, svv) = (&d[0..3], &d[3..6], &d[6..9], &d[9..12], &d[12..15]);
        let n = [
            su[1] * sv[2] - su[2] * sv[1],
            su[2] * sv[0] - su[0] * sv[2],
            su[0] * sv[1] - su[1] * sv[0],
        ];
        let nl = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
        if !(nl > 0.0) {
            return Err(Error::InvalidArgument {
                what: "surface point".into(),
                reason: format!(
                    "S_u × S_v = 0 at ({u}, {v}): the surface is singular there",
                    u = readable(&u),
                    v = readable(&v)
                ),
            });
        }
        let n = [n[0] / nl, n[1] / nl, n[2] / nl];
        let dot = |a: &[f64], b: &[f64]| -> f64 { a.iter().zip(b).map(|(x, y)| x * y).sum() };
        let (e, f, g) = (dot(su, su), dot(su, sv), dot(sv, sv));
        let (l, m, nn) = (dot(suu, &n), dot(suv, &n), dot(svv, &n));
        let det = e * g - f * f;
        let kg = (l * nn - m * m) / det / (self.scale * self.scale);
        let h = (e * nn - 2.0 * f * m + g * l) / (2.0 * det) / self.scale;
        let disc = (h * h - kg).max(0.0).sqrt();
        Ok(SurfaceCurvature {
            gaussian: kg,
            mean: h,
            principal: (h + disc, h - disc),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{BSplineCurve, NurbsCurve, Points};

    #[test]
    fn circle_curvature_and_helix_like_torsion() {
        let c = NurbsCurve::circle(&[0.0, 0.0], &[1.0, 0.0], &[0.0, 1.0], 4.0).unwrap();
        let q = QueryCurve::from_nurbs(&c).unwrap();
        for t in [0.0, 0.1, 0.33, 0.9] {
            let k = q.curvature_at(t).unwrap().unwrap();
            assert!((k - 0.25).abs() < 1e-13, "{t}: {k}");
        }
        // a planar 3-D curve has no torsion
        let c3 =
            NurbsCurve::circle(&[0.0, 0.0, 1.0], &[1.0, 0.0, 0.0], &[0.0, 1.0, 0.0], 2.0).unwrap();
        let q3 = QueryCurve::from_nurbs(&c3).unwrap();
        assert!(q3.torsion_at(0.4).unwrap().unwrap().abs() < 1e-12, "planar");
    }

    #[test]
    fn exact_arcs_have_no_curvature_extrema() {
        // the arc of `lekalo make nurbs --help`: d(κ²)/dt is rounding noise there
        let arc = NurbsCurve::new(
            2,
            vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
            Points::from_2d(&[[1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]).unwrap(),
            vec![1.0, std::f64::consts::FRAC_1_SQRT_2, 1.0],
        )
        .unwrap();
        let ext = QueryCurve::from_nurbs(&arc)
            .unwrap()
            .curvature_extrema()
            .unwrap();
        assert!(ext.is_empty(), "{ext:?}");
        // a full circle of four pieces, radius 3, and a scaled-up one
        for r in [3.0, 1e6] {
            let c = NurbsCurve::circle(&[1.0, 2.0], &[1.0, 0.0], &[0.0, 1.0], r).unwrap();
            let ext = QueryCurve::from_nurbs(&c)
                .unwrap()
                .curvature_extrema()
                .unwrap();
            assert!(ext.is_empty(), "{r}: {ext:?}");
        }
        // an elliptic arc keeps its extremum
        let ellipse = NurbsCurve::new(
            2,
            vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
            Points::from_2d(&[[2.0, -1.0], [4.0, 0.3], [2.0, 1.0]]).unwrap(),
            vec![1.0, 0.5, 1.0],
        )
        .unwrap();
        let ext = QueryCurve::from_nurbs(&ellipse)
            .unwrap()
            .curvature_extrema()
            .unwrap();
        assert_eq!(ext.len(), 1, "{ext:?}");
    }

    #[test]
    fn straight_stretches_have_no_inflection() {
        // a line elevated to degree 5 and joined to a bend: the straight pieces' C' × C'' is
        // rounding noise; only real sign changes count (this curve turns one way)
        let pts = crate::Points::from_2d(&[[1.0, 1.0], [2.0, 3.0], [4.0, 3.0]]).unwrap();
        let s =
            crate::smooth_polyline_corners(pts.as_view(), crate::CornerWindow::Fraction(0.25), 2)
                .unwrap();
        let q = QueryCurve::from_bspline(s.curve()).unwrap();
        assert_eq!(q.inflections().unwrap(), Vec::<f64>::new());
    }

    #[test]
    fn s_curve_has_one_inflection() {
        let c = BSplineCurve::new(
            3,
            vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0],
            Points::from_2d(&[[0.0, 0.0], [1.0, 1.0], [2.0, -1.0], [3.0, 0.0]]).unwrap(),
        )
        .unwrap();
        let q = QueryCurve::from_bspline(&c).unwrap();
        let inf = q.inflections().unwrap();
        assert_eq!(inf.len(), 1, "{inf:?}");
        assert!((inf[0] - 0.5).abs() < 1e-12, "{inf:?}");
        // curvature extrema: two maxima (one per lobe) and the zero at the inflection
        let ext = q.curvature_extrema().unwrap();
        assert!(ext.iter().filter(|e| e.maximum).count() == 2, "{ext:?}");
    }
}
