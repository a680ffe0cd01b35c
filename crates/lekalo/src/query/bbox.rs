//! Exact bounding boxes of curves from the extrema of their Bezier pieces
//! (`docs/theory/queries.md#bounding-boxes`).

use super::pieces::{bern_roots, Bern, QueryCurve};

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
}
