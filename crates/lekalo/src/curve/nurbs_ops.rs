//! Operations on NURBS curves by way of their homogeneous B-spline `(w·P, w)` (P&T §5.2–5.4:
//! knot insertion, refinement, splitting, decomposition and removal apply unchanged to the
//! homogeneous control points, and the rational curve `A(t)/w(t)` is unchanged because both `A`
//! and `w` are).

use crate::curve::bspline::BSplineCurve;
use crate::curve::knot_removal::{check_tolerance, default_tolerance};
use crate::curve::nurbs::NurbsCurve;
use crate::error::Result;
use crate::points::Points;

impl NurbsCurve {
    /// Inserts the knot `t` `times` times (Boehm; P&T Algorithm A5.1 on the homogeneous
    /// points, §5.2). The rational curve is unchanged; the new weights are convex combinations
    /// of the old ones, so they stay positive.
    ///
    /// ```
    /// use lekalo::NurbsCurve;
    /// let c = NurbsCurve::circle(&[0.0, 0.0], &[1.0, 0.0], &[0.0, 1.0], 2.0)?;
    /// let d = c.insert_knot(0.1, 1)?;
    /// let (a, b) = (c.eval(0.3)?, d.eval(0.3)?);
    /// assert!((a[0] - b[0]).abs() < 1e-15 && (a[1] - b[1]).abs() < 1e-15);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// As [`BSplineCurve::insert_knot`].
    pub fn insert_knot(&self, t: f64, times: usize) -> Result<NurbsCurve> {
        let h = self.homogeneous().insert_knot(t, times)?;
        Ok(NurbsCurve::from_homogeneous_unchecked(h))
    }

    /// Knot refinement (P&T Algorithm A5.4 on the homogeneous points): inserts all of `x`.
    ///
    /// # Errors
    /// As [`BSplineCurve::refine_knots`].
    pub fn refine_knots(&self, x: &[f64]) -> Result<NurbsCurve> {
        let h = self.homogeneous().refine_knots(x)?;
        Ok(NurbsCurve::from_homogeneous_unchecked(h))
    }

    /// Splits at `t` into the curves on `[t_min, t]` and `[t, t_max]` (P&T §5.2, by knot
    /// insertion on the homogeneous points); the pieces keep the original parameters.
    ///
    /// # Errors
    /// As [`BSplineCurve::split_at`].
    pub fn split_at(&self, t: f64) -> Result<(NurbsCurve, NurbsCurve)> {
        let (a, b) = self.homogeneous().split_at(t)?;
        Ok((
            NurbsCurve::from_homogeneous_unchecked(a),
            NurbsCurve::from_homogeneous_unchecked(b),
        ))
    }

    /// Decomposition into rational Bezier segments (P&T Algorithm A5.6 on the homogeneous
    /// points): one NURBS per non-empty knot span `[t_k, t_{k+1}]` of the domain, each of degree
    /// `p` with `p + 1` control points and weights on the knots `[t_k^{(p+1)}, t_{k+1}^{(p+1)}]`
    /// — a rational Bezier curve that keeps the original parameter, so `piece.eval(t)` equals
    /// `self.eval(t)` on its span. O(n·p·dim).
    ///
    /// ```
    /// use lekalo::NurbsCurve;
    /// let c = NurbsCurve::circle(&[0.0, 0.0], &[1.0, 0.0], &[0.0, 1.0], 1.0)?;
    /// let pieces = c.to_bezier_segments();
    /// assert_eq!(pieces.len(), 4);
    /// let (lo, hi) = pieces[1].domain();
    /// let t = 0.5 * (lo + hi);
    /// let (a, b) = (pieces[1].eval(t)?, c.eval(t)?);
    /// assert!((a[0] - b[0]).abs() < 1e-15 && (a[1] - b[1]).abs() < 1e-15);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    #[must_use]
    pub fn to_bezier_segments(&self) -> Vec<NurbsCurve> {
        let h = self.homogeneous();
        let p = h.degree();
        let hd = h.dim();
        h.to_bezier_segments()
            .into_iter()
            .map(|seg| {
                let mut knots = vec![seg.start; p + 1];
                knots.extend(std::iter::repeat_n(seg.end, p + 1));
                let ctrl = seg.curve.control_points().as_slice().to_vec();
                NurbsCurve::from_homogeneous_unchecked(BSplineCurve::from_raw(
                    p,
                    knots,
                    Points::from_raw(ctrl, hd),
                ))
            })
            .collect()
    }

    /// The reversed curve `C(a + b − t)` on the same domain (see [`BSplineCurve::reverse`];
    /// weights reversed with the points).
    ///
    /// # Errors
    /// As [`BSplineCurve::reverse`].
    pub fn reverse(&self) -> Result<NurbsCurve> {
        let h = self.homogeneous().reverse()?;
        Ok(NurbsCurve::from_homogeneous_unchecked(h))
    }

    /// The same curve on the domain `[a, b]` by the affine change of parameter (see
    /// [`BSplineCurve::reparametrize`]); points and weights are unchanged.
    ///
    /// # Errors
    /// As [`BSplineCurve::reparametrize`].
    pub fn reparametrize(&self, a: f64, b: f64) -> Result<NurbsCurve> {
        let h = self.homogeneous().reparametrize(a, b)?;
        Ok(NurbsCurve::from_homogeneous_unchecked(h))
    }

    /// The default knot-removal tolerance: as [`BSplineCurve::default_removal_tolerance`] for
    /// the Euclidean control points.
    #[must_use]
    pub fn default_removal_tolerance(&self) -> f64 {
        default_tolerance(&self.control_points())
    }

    /// Removes the interior knot `t` up to `times` times keeping the **rational** curve within
    /// the Euclidean distance `tolerance` (P&T §5.4, Algorithm A5.8 on the homogeneous points).
    /// Returns the new curve and the number of copies removed.
    ///
    /// The homogeneous removal runs with `TOL = d·w_min / (1 + |P|_max + d)` (`d = tolerance`,
    /// `w_min` the least weight, `|P|_max` the largest distance of a control point from the
    /// origin) — a variant of the tolerance P&T §5.4 gives for rational curves, derived here: if `|(A, w) − (Ã, w̃)| ≤ TOL` everywhere, then
    /// `C − C̃ = ((A − Ã) − C (w − w̃)) / w̃` with `|C| ≤ |P|_max` and `w̃ ≥ w_min − TOL`
    /// gives `|C − C̃| ≤ TOL (1 + |P|_max) / (w_min − TOL) = d`. A removal that would make a
    /// weight non-positive is not made.
    ///
    /// ```
    /// use lekalo::NurbsCurve;
    /// let c = NurbsCurve::circle(&[0.0, 0.0], &[1.0, 0.0], &[0.0, 1.0], 1.0)?;
    /// let d = c.insert_knot(0.1, 2)?;
    /// let (back, removed) = d.remove_knot(0.1, 2, 1e-12)?;
    /// assert_eq!(removed, 2);
    /// assert_eq!(back.knots(), c.knots());
    /// // the circle's own knots (double, C^1) are not removable
    /// assert_eq!(c.remove_knot(0.25, 1, 1e-6)?.1, 0);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// As [`BSplineCurve::remove_knot`].
    pub fn remove_knot(&self, t: f64, times: usize, tolerance: f64) -> Result<(NurbsCurve, usize)> {
        check_tolerance(tolerance)?;
        let tol_h = self.homogeneous_tolerance(tolerance);
        let mut times = times;
        loop {
            let (h, removed) = self.homogeneous().remove_knot(t, times, tol_h)?;
            if removed == 0 || weights_positive(&h) {
                return Ok((NurbsCurve::from_homogeneous_unchecked(h), removed));
            }
            times = removed - 1;
        }
    }

    /// Removes every interior knot copy whose removal keeps the rational curve within the
    /// Euclidean distance `tolerance` ([`BSplineCurve::remove_all_removable_knots`] on the
    /// homogeneous points with the tolerance of [`NurbsCurve::remove_knot`]). If the result
    /// had a non-positive weight (possible only for large tolerances) the curve is returned
    /// unchanged with 0 removed.
    ///
    /// # Errors
    /// As [`BSplineCurve::remove_all_removable_knots`].
    pub fn remove_all_removable_knots(&self, tolerance: f64) -> Result<(NurbsCurve, usize)> {
        check_tolerance(tolerance)?;
        let (h, removed) = self
            .homogeneous()
            .remove_all_removable_knots(self.homogeneous_tolerance(tolerance))?;
        if weights_positive(&h) {
            Ok((NurbsCurve::from_homogeneous_unchecked(h), removed))
        } else {
            Ok((self.clone(), 0))
        }
    }

    /// `TOL = d·w_min / (1 + |P|_max + d)` (see [`NurbsCurve::remove_knot`]).
    fn homogeneous_tolerance(&self, d: f64) -> f64 {
        let w_min = self.weights().into_iter().fold(f64::INFINITY, f64::min);
        let p_max = self
            .control_points()
            .iter()
            .map(|p| p.iter().map(|x| x * x).sum::<f64>().sqrt())
            .fold(0.0_f64, f64::max);
        d * w_min / (1.0 + p_max + d)
    }
}

/// All weights (last homogeneous coordinates) strictly positive.
fn weights_positive(h: &BSplineCurve) -> bool {
    let hd = h.dim();
    h.control_points().iter().all(|p| p[hd - 1] > 0.0)
}
