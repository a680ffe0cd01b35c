//! NURBS curves: a B-spline curve over homogeneous control points `(w·x, w·y, …, w)` in
//! dimension `dim + 1`, so that every B-spline algorithm applies unchanged; the rational curve is
//! the projection `C(t) = A(t) / w(t)`. Exact circles and arcs are in `conics.rs`.

use serde::{Deserialize, Serialize};

use crate::basis::{basis_funs_into, BasisScratch};
use crate::curve::bspline::BSplineCurve;
use crate::error::{check_derivative_order, Error, Result, MAX_DERIVATIVE_ORDER};
use crate::numeric::progress::Progress;
use crate::points::{
    check_homogeneous, dehomogenize, homogenize, weights_of, with_unit_weights, Points,
};

/// A rational B-spline curve.
///
/// ```
/// use lekalo::{NurbsCurve, Points};
/// // quarter circle: weights 1, 1/√2, 1
/// let ctrl = Points::from_2d(&[[1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]).unwrap();
/// let w = std::f64::consts::FRAC_1_SQRT_2;
/// let c = NurbsCurve::new(2, vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0], ctrl, vec![1.0, w, 1.0]).unwrap();
/// let p = c.eval(0.3).unwrap();
/// assert!((p[0].hypot(p[1]) - 1.0).abs() < 1e-15);
/// ```
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "NurbsCurveRepr", into = "NurbsCurveRepr")]
pub struct NurbsCurve {
    /// The B-spline in homogeneous coordinates (dimension `dim + 1`, weight last).
    pub(super) homogeneous: BSplineCurve,
}

#[derive(Serialize, Deserialize)]
struct NurbsCurveRepr {
    degree: usize,
    knots: Vec<f64>,
    control: Points,
    weights: Vec<f64>,
}

impl TryFrom<NurbsCurveRepr> for NurbsCurve {
    type Error = Error;
    fn try_from(r: NurbsCurveRepr) -> Result<Self> {
        NurbsCurve::new(r.degree, r.knots, r.control, r.weights)
    }
}

impl From<NurbsCurve> for NurbsCurveRepr {
    fn from(c: NurbsCurve) -> Self {
        let control = c.control_points();
        let weights = c.weights();
        let (degree, knots, _) = c.homogeneous.into_parts();
        NurbsCurveRepr {
            degree,
            knots: knots.into_vec(),
            control,
            weights,
        }
    }
}

impl NurbsCurve {
    /// A NURBS curve from degree, knots, Euclidean control points and positive weights.
    ///
    /// # Errors
    /// [`Error::LengthMismatch`] if there is not one weight per control point;
    /// [`Error::NonFinite`]; [`Error::NonPositiveWeight`]; knot errors as
    /// [`BSplineCurve::new`].
    pub fn new(
        degree: usize,
        knots: impl Into<Vec<f64>>,
        control: Points,
        weights: Vec<f64>,
    ) -> Result<Self> {
        // w·x can overflow for huge coordinates and weights: homogenize checks that too
        let homogeneous_points = homogenize(&control, &weights)?;
        let homogeneous = BSplineCurve::new(degree, knots, homogeneous_points)?;
        Ok(NurbsCurve { homogeneous })
    }

    /// A NURBS curve from a B-spline in homogeneous coordinates (last coordinate the weight).
    ///
    /// # Errors
    /// [`Error::Dimension`] if the dimension is below 2; [`Error::NonPositiveWeight`].
    pub fn from_homogeneous(homogeneous: BSplineCurve) -> Result<Self> {
        check_homogeneous(homogeneous.control_points())?;
        Ok(NurbsCurve { homogeneous })
    }

    /// Trusted constructor for homogeneous curves built inside the crate, whose weights are
    /// positive by construction (debug-checked).
    pub(crate) fn from_homogeneous_unchecked(homogeneous: BSplineCurve) -> Self {
        debug_assert!(
            Self::from_homogeneous(homogeneous.clone()).is_ok(),
            "raw homogeneous NURBS curve"
        );
        NurbsCurve { homogeneous }
    }

    /// The same curve with unit weights: the non-rational B-spline as a NURBS.
    #[must_use]
    pub fn from_bspline(curve: &BSplineCurve) -> Self {
        let homogeneous = BSplineCurve::from_raw(
            curve.degree(),
            curve.knots().as_slice().to_vec(),
            with_unit_weights(curve.control_points()),
        );
        NurbsCurve { homogeneous }
    }

    /// The homogeneous B-spline `(w·P, w)`.
    #[must_use]
    pub fn homogeneous(&self) -> &BSplineCurve {
        &self.homogeneous
    }

    /// Degree.
    #[must_use]
    pub fn degree(&self) -> usize {
        self.homogeneous.degree()
    }

    /// Euclidean dimension.
    #[must_use]
    pub fn dim(&self) -> usize {
        self.homogeneous.dim() - 1
    }

    /// Parameter domain.
    #[must_use]
    pub fn domain(&self) -> (f64, f64) {
        self.homogeneous.domain()
    }

    /// The knot vector.
    #[must_use]
    pub fn knots(&self) -> &crate::KnotVector {
        self.homogeneous.knots()
    }

    /// Weights.
    #[must_use]
    pub fn weights(&self) -> Vec<f64> {
        weights_of(self.homogeneous.control_points())
    }

    /// Euclidean control points `P_i = (w·P_i) / w_i`.
    #[must_use]
    pub fn control_points(&self) -> Points {
        dehomogenize(self.homogeneous.control_points())
    }

    /// Point `C(t) = A(t) / w(t)` (P&T Algorithm A4.1).
    ///
    /// # Errors
    /// [`Error::ParameterOutOfDomain`].
    pub fn eval(&self, t: f64) -> Result<Vec<f64>> {
        let mut h = self.homogeneous.eval(t)?;
        let w = h.pop().unwrap_or(1.0);
        for x in &mut h {
            *x /= w;
        }
        Ok(h)
    }

    /// Point `C(t)` into `out` (length `dim`), as [`NurbsCurve::eval`] without allocating the
    /// result.
    ///
    /// # Errors
    /// [`Error::ParameterOutOfDomain`]; [`Error::LengthMismatch`] if `out.len() != dim`.
    pub fn eval_into(&self, t: f64, out: &mut [f64]) -> Result<()> {
        let dim = self.dim();
        if out.len() != dim {
            return Err(Error::LengthMismatch {
                what: "output point (dimension)".into(),
                expected: dim,
                got: out.len(),
            });
        }
        let p = self.degree();
        let span = self.knots().find_span(p, t)?;
        let mut scratch = BasisScratch::new(p);
        let mut n = vec![0.0; p + 1];
        self.eval_span(span, t, &mut scratch, &mut n, out);
        Ok(())
    }

    /// Evaluates at every parameter of `ts` into `out` (`ts.len() × dim`, point-major): one
    /// scratch buffer for the whole batch and the span cursor of [`crate::KnotVector::span_cursor`]
    /// (amortised O(1) span search for sorted parameters). O(p² + p·dim) per point, no allocation
    /// per point.
    ///
    /// ```
    /// use lekalo::NurbsCurve;
    /// let c = NurbsCurve::circle(&[0.0, 0.0], &[1.0, 0.0], &[0.0, 1.0], 2.0).unwrap();
    /// let ts: Vec<f64> = (0..=8).map(|k| k as f64 / 8.0).collect();
    /// let mut out = vec![0.0; 2 * ts.len()];
    /// c.eval_batch(&ts, &mut out).unwrap();
    /// for p in out.chunks_exact(2) {
    ///     assert!((p[0].hypot(p[1]) - 2.0).abs() < 1e-14);
    /// }
    /// ```
    ///
    /// # Errors
    /// [`Error::LengthMismatch`] if `out.len() != ts.len() · dim`;
    /// [`Error::ParameterOutOfDomain`] at the first parameter outside the domain (the contents of
    /// `out` are then unspecified).
    pub fn eval_batch(&self, ts: &[f64], out: &mut [f64]) -> Result<()> {
        self.eval_batch_with_progress(ts, out, &Progress::new())
    }

    /// [`NurbsCurve::eval_batch`] reporting to `progress` (`done` of `ts.len()` parameters)
    /// and stopping when it is cancelled, about every [`Progress::STRIDE`] operations. The
    /// points are bit-for-bit those of [`NurbsCurve::eval_batch`].
    ///
    /// # Errors
    /// As [`NurbsCurve::eval_batch`]; [`Error::Cancelled`] when `progress` is cancelled.
    pub fn eval_batch_with_progress(
        &self,
        ts: &[f64],
        out: &mut [f64],
        progress: &Progress<'_>,
    ) -> Result<()> {
        let dim = self.dim();
        if out.len() != ts.len() * dim {
            return Err(Error::LengthMismatch {
                what: "output buffer (parameters × dimension)".into(),
                expected: ts.len() * dim,
                got: out.len(),
            });
        }
        let p = self.degree();
        let mut cursor = self.knots().span_cursor(p);
        let mut scratch = BasisScratch::new(p);
        let mut n = vec![0.0; p + 1];
        let mut outs = out.chunks_exact_mut(dim);
        let cost = self.homogeneous.point_cost();
        progress.chunks("NURBS curve evaluation", ts, cost, |ts| {
            for (&t, o) in ts.iter().zip(&mut outs) {
                let span = cursor.find(t)?;
                self.eval_span(span, t, &mut scratch, &mut n, o);
            }
            Ok(())
        })
    }

    /// `C(t) = Σ N_i w_i P_i / Σ N_i w_i` at a known span, with caller scratch (no allocation).
    fn eval_span(
        &self,
        span: usize,
        t: f64,
        scratch: &mut BasisScratch,
        n: &mut [f64],
        out: &mut [f64],
    ) {
        let p = self.degree();
        let hd = self.homogeneous.dim();
        basis_funs_into(self.knots().as_slice(), p, span, t, scratch, n);
        out.fill(0.0);
        let mut w = 0.0;
        let ctrl = self.homogeneous.control_points().as_slice();
        for (j, &nj) in n.iter().enumerate() {
            let base = (span - p + j) * hd;
            let pt = &ctrl[base..base + hd];
            for (o, c) in out.iter_mut().zip(pt) {
                *o += nj * c;
            }
            w += nj * pt[hd - 1];
        }
        for o in out.iter_mut() {
            *o /= w;
        }
    }

    /// Derivatives `C^{(k)}(t)` for `k = 0..=order`: row `k` of the result is the k-th derivative.
    ///
    /// The homogeneous derivatives `A^{(k)}, w^{(k)}` come from the B-spline in dimension
    /// `dim + 1` (P&T A3.2); the rational ones from the quotient rule (P&T eq. 4.8, Algorithm
    /// A4.2): `C^{(k)} = (A^{(k)} − Σ_{i=1}^{k} C(k,i) w^{(i)} C^{(k−i)}) / w`. Unlike the
    /// polynomial case, orders above the degree are in general non-zero. At an interior knot
    /// the derivatives are right-hand ones (left-hand at the right end). O(order² · dim + order·p²).
    ///
    /// ```
    /// use lekalo::NurbsCurve;
    /// // unit circle: |C'| is constant on each quarter only up to the rational speed, but
    /// // C' is always perpendicular to C
    /// let c = NurbsCurve::circle(&[0.0, 0.0], &[1.0, 0.0], &[0.0, 1.0], 1.0).unwrap();
    /// let d = c.eval_derivatives(0.3, 2).unwrap();
    /// let (p, v) = (d.point(0), d.point(1));
    /// assert!((p[0] * v[0] + p[1] * v[1]).abs() < 1e-14);
    /// ```
    ///
    /// # Errors
    /// [`Error::ParameterOutOfDomain`]; [`Error::TooLarge`] if `order > MAX_DERIVATIVE_ORDER`; [`Error::NonFinite`] if a derivative overflows.
    pub fn eval_derivatives(&self, t: f64, order: usize) -> Result<Points> {
        check_derivative_order(order, MAX_DERIVATIVE_ORDER)?;
        let a = self.homogeneous.eval_derivatives(t, order)?;
        let dim = self.dim();
        let mut out = vec![0.0; (order + 1) * dim];
        rational_derivatives(a.as_slice(), dim, order, &mut out);
        Points::from_flat(dim, out)
    }
}

/// Quotient rule for the derivatives of `C = A / w` (P&T eq. 4.8, Algorithm A4.2).
///
/// `hom` holds `order + 1` homogeneous derivative rows of length `dim + 1` (`A^{(k)}` then
/// `w^{(k)}`); `out` receives `order + 1` rows of length `dim`.
fn rational_derivatives(hom: &[f64], dim: usize, order: usize, out: &mut [f64]) {
    let hd = dim + 1;
    let w0 = hom[dim];
    debug_assert!(w0 > 0.0, "weights are positive, so w(t) > 0");
    for k in 0..=order {
        let (done, rest) = out.split_at_mut(k * dim);
        let row = &mut rest[..dim];
        row.copy_from_slice(&hom[k * hd..k * hd + dim]);
        // binom = C(k, i), updated multiplicatively
        let mut binom = 1.0;
        for i in 1..=k {
            binom = binom * (k + 1 - i) as f64 / i as f64;
            let c = binom * hom[i * hd + dim];
            let prev = &done[(k - i) * dim..(k - i + 1) * dim];
            for (r, x) in row.iter_mut().zip(prev) {
                *r -= c * x;
            }
        }
        for r in row.iter_mut() {
            *r /= w0;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unit_weights_equal_bspline() {
        let ctrl = Points::from_2d(&[[0.0, 0.0], [1.0, 3.0], [2.0, -1.0], [4.0, 0.5]]).unwrap();
        let knots = vec![0.0, 0.0, 0.0, 0.4, 1.0, 1.0, 1.0];
        let b = BSplineCurve::new(2, knots.clone(), ctrl.clone()).unwrap();
        let n = NurbsCurve::new(2, knots, ctrl, vec![1.0; 4]).unwrap();
        assert_eq!(n, NurbsCurve::from_bspline(&b));
        for k in 0..=10 {
            let t = f64::from(k) / 10.0;
            // w(t) = Σ N_i = 1 up to rounding, so agreement is to a few ulps
            let (a, c) = (n.eval(t).unwrap(), b.eval(t).unwrap());
            for d in 0..2 {
                assert!((a[d] - c[d]).abs() < 4.0 * f64::EPSILON * 4.0, "t = {t}");
            }
        }
    }

    #[test]
    fn rejects_bad_weights() {
        let ctrl = Points::from_2d(&[[0.0, 0.0], [1.0, 1.0]]).unwrap();
        let k = vec![0.0, 0.0, 1.0, 1.0];
        assert!(matches!(
            NurbsCurve::new(1, k.clone(), ctrl.clone(), vec![1.0]),
            Err(Error::LengthMismatch { .. })
        ));
        assert!(matches!(
            NurbsCurve::new(1, k.clone(), ctrl.clone(), vec![1.0, 0.0]),
            Err(Error::NonPositiveWeight { index: 1, .. })
        ));
        assert!(matches!(
            NurbsCurve::new(1, k, ctrl, vec![1.0, f64::NAN]),
            Err(Error::NonFinite { .. })
        ));
    }

    fn rational_cubic() -> NurbsCurve {
        let ctrl = Points::from_flat(
            3,
            vec![
                0.0, 0.0, 1.0, 1.0, 3.0, -1.0, 2.0, 0.5, 4.0, 2.0, 6.0, 1.0, 5.0, 3.0, 7.0,
            ],
        )
        .unwrap();
        let knots = vec![0.0, 0.0, 0.0, 0.0, 0.4, 1.0, 1.0, 1.0, 1.0];
        NurbsCurve::new(3, knots, ctrl, vec![1.0, 0.5, 2.0, 0.8, 1.5]).unwrap()
    }

    #[test]
    fn rational_derivatives_match_finite_differences() {
        let c = rational_cubic();
        let h = 1e-5;
        for &t in &[0.1, 0.35, 0.55, 0.9] {
            let d = c.eval_derivatives(t, 3).unwrap();
            assert_eq!(
                d.point(0),
                c.eval(t).unwrap().as_slice(),
                "row 0 is the point"
            );
            for (k, tol) in [(1, 1e-5), (2, 1e-4), (3, 1e-3)] {
                // central difference of the (k−1)-th derivative
                let lo = c.eval_derivatives(t - h, k - 1).unwrap();
                let hi = c.eval_derivatives(t + h, k - 1).unwrap();
                for j in 0..3 {
                    let fd = (hi.point(k - 1)[j] - lo.point(k - 1)[j]) / (2.0 * h);
                    let scale = 1.0 + d.point(k)[j].abs();
                    assert!(
                        (fd - d.point(k)[j]).abs() < tol * scale,
                        "t={t} k={k} j={j}: {fd} vs {}",
                        d.point(k)[j]
                    );
                }
            }
        }
        // rational: the derivative of order degree + 1 is not zero in general
        let d = c.eval_derivatives(0.5, 4).unwrap();
        assert!(d.point(4).iter().any(|x| x.abs() > 1e-3), "4th derivative");
        assert!(matches!(
            c.eval_derivatives(1.5, 1),
            Err(Error::ParameterOutOfDomain { .. })
        ));
        assert!(matches!(
            c.eval_derivatives(0.5, usize::MAX),
            Err(Error::TooLarge { .. })
        ));
    }

    #[test]
    fn circle_derivatives_are_exact() {
        // C' ⊥ C − centre and |C''| consistent with curvature 1/r: |C' × C''| = |C'|³ / r
        let r = 3.0;
        let c = NurbsCurve::circle(&[1.0, -2.0], &[1.0, 0.0], &[0.0, 1.0], r).unwrap();
        for k in 0..=40 {
            let t = f64::from(k) / 40.0;
            let d = c.eval_derivatives(t, 2).unwrap();
            let (p, v, a) = (d.point(0), d.point(1), d.point(2));
            let rel = [p[0] - 1.0, p[1] + 2.0];
            let speed = v[0].hypot(v[1]);
            assert!(
                (rel[0] * v[0] + rel[1] * v[1]).abs() < 1e-13 * speed * r,
                "t={t}"
            );
            let cross = v[0] * a[1] - v[1] * a[0];
            assert!(
                (cross - speed.powi(3) / r).abs() < 1e-12 * speed.powi(3),
                "t={t}"
            );
        }
    }

    #[test]
    fn unit_weight_derivatives_equal_bspline() {
        let ctrl = Points::from_flat(2, (0..12).map(|i| f64::from(i).cos()).collect()).unwrap();
        let knots = vec![0.0, 0.0, 0.0, 0.0, 0.3, 0.6, 1.0, 1.0, 1.0, 1.0];
        let b = BSplineCurve::new(3, knots, ctrl).unwrap();
        let n = NurbsCurve::from_bspline(&b);
        for &t in &[0.0, 0.2, 0.3, 0.77, 1.0] {
            let (db, dn) = (
                b.eval_derivatives(t, 4).unwrap(),
                n.eval_derivatives(t, 4).unwrap(),
            );
            // rounding relative to the largest derivative (orders above 3 are 0 vs ~1e-12)
            let scale = db.max_abs();
            for (x, y) in db.as_slice().iter().zip(dn.as_slice()) {
                assert!((x - y).abs() < 1e-13 * scale, "t={t}: {x} vs {y}");
            }
        }
    }

    #[test]
    fn batch_and_into_match_eval() {
        let c = rational_cubic();
        let ts: Vec<f64> = (0..=30).map(|k| f64::from(k) / 30.0).collect();
        let mut out = vec![0.0; ts.len() * 3];
        c.eval_batch(&ts, &mut out).unwrap();
        let mut one = [0.0; 3];
        for (k, &t) in ts.iter().enumerate() {
            let e = c.eval(t).unwrap();
            c.eval_into(t, &mut one).unwrap();
            for j in 0..3 {
                assert!(
                    (out[3 * k + j] - e[j]).abs() < 1e-15 * (1.0 + e[j].abs()),
                    "t={t}"
                );
                assert!((one[j] - e[j]).abs() < 1e-15 * (1.0 + e[j].abs()), "t={t}");
            }
        }
        assert!(matches!(
            c.eval_batch(&ts, &mut out[1..]),
            Err(Error::LengthMismatch { .. })
        ));
        assert!(matches!(
            c.eval_into(0.5, &mut [0.0; 2]),
            Err(Error::LengthMismatch { .. })
        ));
        assert!(matches!(
            c.eval_batch(&[0.5, 2.0], &mut [0.0; 6]),
            Err(Error::ParameterOutOfDomain { .. })
        ));
    }
}
