//! Exact bounding boxes of curves from the extrema of their Bezier pieces
//! (`docs/theory/queries.md#bounding-boxes`).

use super::pieces::{bern_roots, Bern, QueryCurve};
use super::surface::QuerySurface;

/// Tolerance of [`QuerySurface::bounding_box`], relative to the surface's size: each side of the
/// box is a coordinate of a point of the surface, at most this much inside the true extreme.
pub const SURFACE_BOX_RTOL: f64 = 1e-12;
/// Most halvings of a patch while a side of its box is refined.
const SURFACE_BOX_LEVELS: u32 = 48;
/// Most parts refined for one side of the box.
const SURFACE_BOX_PARTS: usize = 1 << 20;

impl QueryCurve {
    /// The smallest axis-aligned box containing the curve (not its control points): in each
    /// coordinate the extremes are at the ends of the domain or at roots of the coordinate's
    /// derivative (`x'` for a polynomial piece, `x'w − xw'` for a rational one), found from their
    /// Bernstein coefficients. A piece whose control points lie inside the box found so far is
    /// skipped (convex hull). Returns `(minima, maxima)` in the curve's coordinates.
    ///
    /// ```
    /// use lekalo::{NurbsCurve, QueryCurve};
    /// let c = NurbsCurve::circle(&[1.0, 2.0], &[1.0, 1.0], &[-1.0, 1.0], 3.0)?;
    /// let (lo, hi) = QueryCurve::from_nurbs(&c)?.bounding_box();
    /// for d in 0..2 {
    ///     assert!((lo[d] - ([1.0, 2.0][d] - 3.0)).abs() < 1e-14);
    ///     assert!((hi[d] - ([1.0, 2.0][d] + 3.0)).abs() < 1e-14);
    /// }
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    #[must_use]
    pub fn bounding_box(&self) -> (Vec<f64>, Vec<f64>) {
        let (dim, hd, n) = (self.dim, self.hd, self.degree);
        let mut lo = vec![f64::INFINITY; dim];
        let mut hi = vec![f64::NEG_INFINITY; dim];
        let mut scratch = Vec::new();
        let mut buf = vec![0.0; 3 * dim];
        let mut take = |k: usize, s: f64, lo: &mut Vec<f64>, hi: &mut Vec<f64>| {
            self.eval_local(k, s, 0, &mut scratch, &mut buf);
            for d in 0..dim {
                lo[d] = lo[d].min(buf[d]);
                hi[d] = hi[d].max(buf[d]);
            }
        };
        for k in 0..self.piece_count() {
            take(k, 0.0, &mut lo, &mut hi);
            take(k, 1.0, &mut lo, &mut hi);
        }
        for k in 0..self.piece_count() {
            let b = self.piece_box(k);
            let piece = self.piece(k);
            for d in 0..dim {
                if b[d] >= lo[d] && b[dim + d] <= hi[d] {
                    continue;
                }
                let a = Bern((0..=n).map(|i| piece[i * hd + d]).collect());
                let (der, mag) = if self.rational {
                    let w = Bern((0..=n).map(|i| piece[i * hd + dim]).collect());
                    let num = a.deriv().mul(&w).sub(&a.mul(&w.deriv()));
                    let m = num.0.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
                    (num, m)
                } else {
                    let der = a.deriv();
                    let m = der.0.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
                    (der, m)
                };
                for s in bern_roots(&der, 16.0 * f64::EPSILON * mag) {
                    take(k, s, &mut lo, &mut hi);
                }
            }
        }
        let mut l = vec![0.0; dim];
        let mut h = vec![0.0; dim];
        self.denormalise(&lo, &mut l);
        self.denormalise(&hi, &mut h);
        (l, h)
    }
}

impl QuerySurface {
    /// The smallest axis-aligned box containing the surface (not its control net), to
    /// [`SURFACE_BOX_RTOL`] of its size: branch and bound on the patches' nets
    /// (`docs/theory/queries.md#bounding-boxes`). For each side, the best value so far is the
    /// extreme coordinate of the parts' corners (points of the surface); a part whose Cartesian
    /// control points (convex hull) cannot beat it by more than the tolerance is dropped, any
    /// other is halved by de Casteljau across the direction(s) in which the coordinate changes,
    /// at most [`SURFACE_BOX_LEVELS`] times and for at most [`SURFACE_BOX_PARTS`] parts a side
    /// (beyond, the parts' hull values close the box: it still contains the surface). Each side
    /// is therefore attained by a point of the surface and lies within `SURFACE_BOX_RTOL · size`
    /// of the true extreme. Returns `(minima, maxima)` in the surface's coordinates.
    ///
    /// ```
    /// use lekalo::{BSplineSurface, Points, QuerySurface};
    /// // z = 4u(1 − u): the net reaches z = 2, the surface only z = 1
    /// let net = Points::from_3d(&[[0., 0., 0.], [0., 1., 0.], [0.5, 0., 2.], [0.5, 1., 2.], [1., 0., 0.], [1., 1., 0.]])?;
    /// let s = BSplineSurface::new(2, 1, vec![0., 0., 0., 1., 1., 1.], vec![0., 0., 1., 1.], net, (3, 2))?;
    /// let (lo, hi) = QuerySurface::from_bspline(&s)?.bounding_box();
    /// assert!((hi[2] - 1.0).abs() < 1e-12 && lo[2] == 0.0);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    #[must_use]
    pub fn bounding_box(&self) -> (Vec<f64>, Vec<f64>) {
        let (p, q, hd, dim) = (self.p, self.q, self.hd, self.dim);
        let cart = |net: &[f64], i: usize, d: usize| {
            let x = &net[i * hd..];
            if self.rational {
                x[d] / x[dim]
            } else {
                x[d]
            }
        };
        let corners = [0, p * (q + 1), p * (q + 1) + q, q];
        let count = (p + 1) * (q + 1);
        let mut lo = vec![0.0; dim];
        let mut hi = vec![0.0; dim];
        for d in 0..dim {
            for (sign, out) in [(1.0, &mut hi), (-1.0, &mut lo)] {
                // the largest sign·x_d over the surface
                let mut best = f64::NEG_INFINITY;
                for k in 0..self.patch_count() {
                    for &c in &corners {
                        best = best.max(sign * cart(self.patch(k), c, d));
                    }
                }
                let net_max = |net: &[f64]| {
                    (0..count)
                        .map(|i| sign * cart(net, i, d))
                        .fold(f64::NEG_INFINITY, f64::max)
                };
                // the largest change of x_d between neighbours along u and along v
                let spread = |net: &[f64]| {
                    let (mut su, mut sv) = (0.0_f64, 0.0_f64);
                    for i in 0..=p {
                        for j in 0..=q {
                            let x = cart(net, i * (q + 1) + j, d);
                            if i < p {
                                su = su.max((cart(net, (i + 1) * (q + 1) + j, d) - x).abs());
                            }
                            if j < q {
                                sv = sv.max((cart(net, i * (q + 1) + j + 1, d) - x).abs());
                            }
                        }
                    }
                    (su, sv)
                };
                let mut stack: Vec<(Vec<f64>, u32)> = (0..self.patch_count())
                    .map(|k| (self.patch(k).to_vec(), 0))
                    .collect();
                let mut parts = 0_usize;
                while let Some((net, level)) = stack.pop() {
                    let m = net_max(&net);
                    if m <= best + SURFACE_BOX_RTOL {
                        continue;
                    }
                    parts += 1;
                    if level >= SURFACE_BOX_LEVELS || parts > SURFACE_BOX_PARTS {
                        // the hull's value keeps the box closed around the surface
                        best = best.max(m);
                        continue;
                    }
                    // halve along the direction(s) in which x_d changes: a ridge along v is
                    // halved across it only
                    let (su, sv) = spread(&net);
                    let mut subs = vec![net];
                    if su >= 0.5 * sv {
                        subs = subs
                            .iter()
                            .flat_map(|n| <[Vec<f64>; 2]>::from(self.halve_u(n)))
                            .collect();
                    }
                    if sv >= 0.5 * su {
                        subs = subs
                            .iter()
                            .flat_map(|n| <[Vec<f64>; 2]>::from(self.halve_v(n)))
                            .collect();
                    }
                    for sub in subs {
                        for &c in &corners {
                            best = best.max(sign * cart(&sub, c, d));
                        }
                        stack.push((sub, level + 1));
                    }
                }
                out[d] = sign * best;
            }
        }
        let mut l = vec![0.0; dim];
        let mut h = vec![0.0; dim];
        self.denormalise(&lo, &mut l);
        self.denormalise(&hi, &mut h);
        (l, h)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{BSplineCurve, Points};

    #[test]
    fn cubic_box_is_tighter_than_the_net_and_exact() {
        // x = t, y = 3t(1 − t)²·... : control points (0,0), (1,3), (2,-3), (3,0)
        let c = BSplineCurve::new(
            3,
            vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0],
            Points::from_2d(&[[0.0, 0.0], [1.0, 3.0], [2.0, -3.0], [3.0, 0.0]]).unwrap(),
        )
        .unwrap();
        let (lo, hi) = QueryCurve::from_bspline(&c).unwrap().bounding_box();
        // y(t) = 9t(1−t)² − 9t²(1−t) = 9t(1−t)(1−2t); extremes at t = (3 ± √3)/6
        let t: f64 = (3.0 - 3f64.sqrt()) / 6.0;
        let ymax = 9.0 * t * (1.0 - t) * (1.0 - 2.0 * t);
        assert!(
            (hi[1] - ymax).abs() < 1e-14 && (lo[1] + ymax).abs() < 1e-14,
            "{lo:?} {hi:?}"
        );
        assert!(lo[0] == 0.0 && hi[0] == 3.0, "x range");
    }

    #[test]
    fn surface_box_is_the_surface_not_the_net() {
        // a rational patch: the octant of the unit sphere; its net reaches (1, 1, 1)
        let h = std::f64::consts::FRAC_1_SQRT_2;
        let arc = [([1.0, 0.0], 1.0), ([1.0, 1.0], h), ([0.0, 1.0], 1.0)];
        let (mut ctrl, mut weights) = (Vec::new(), Vec::new());
        for ([r, z], wm) in arc {
            for ([c, s], wt) in arc {
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
        let (lo, hi) = QuerySurface::from_nurbs(&s).unwrap().bounding_box();
        for d in 0..3 {
            assert!(
                lo[d].abs() < 1e-15 && (hi[d] - 1.0).abs() < 2e-12,
                "{lo:?} {hi:?}"
            );
            assert!(
                hi[d] <= 1.0 + 1e-15,
                "side {d} beyond the sphere: {}",
                hi[d]
            );
        }
        // a bicubic bump whose top is inside a patch: the box side is a critical value
        let net: Vec<f64> = (0..4)
            .flat_map(|i| {
                (0..4).flat_map(move |j| {
                    [
                        f64::from(i),
                        f64::from(j),
                        if (1..3).contains(&i) && (1..3).contains(&j) {
                            1.0
                        } else {
                            0.0
                        },
                    ]
                })
            })
            .collect();
        let k = vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0];
        let b = crate::BSplineSurface::new(
            3,
            3,
            k.clone(),
            k,
            Points::from_flat(3, net).unwrap(),
            (4, 4),
        )
        .unwrap();
        let (_, hi) = QuerySurface::from_bspline(&b).unwrap().bounding_box();
        // z(1/2, 1/2) = (2·3/8)² = 9/16, the maximum by symmetry and the Bernstein form
        assert!((hi[2] - 0.5625).abs() < 1e-11, "{}", hi[2]);
    }
}
