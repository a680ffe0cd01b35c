//! Non-rational B-spline curves `C(t) = Σ_i N_{i,p}(t) P_i` of any degree and dimension.
//!
//! Knot conventions are those of [`crate::knots`]: domain `[t_p, t_{n+1}]`, half-open spans,
//! the right end evaluated by the last non-empty span.

use serde::{Deserialize, Serialize};

use crate::basis::{basis_ders_into, basis_funs_into, BasisScratch};
use crate::error::{Error, Result};
use crate::knots::KnotVector;
use crate::points::Points;

/// A B-spline curve of degree `p` with control points `P_0 … P_n` on a knot vector of
/// `n + p + 2` knots. The degree is stored explicitly only to allow serialisation; it always
/// equals `knots.len() − control.len() − 1`.
///
/// ```
/// use lekalo::{BSplineCurve, Points};
/// // the lecture's example (document 002 §C.5): P(1.5) = (17/8, 11/4)
/// let ctrl = Points::from_2d(&[[1.0, 1.0], [2.0, 3.0], [4.0, 3.0]]).unwrap();
/// let c = BSplineCurve::new(2, vec![0.0, 0.0, 1.0, 2.0, 3.0, 3.0], ctrl).unwrap();
/// assert_eq!(c.domain(), (1.0, 2.0));
/// let p = c.eval(1.5).unwrap();
/// assert!((p[0] - 17.0 / 8.0).abs() < 1e-15 && (p[1] - 11.0 / 4.0).abs() < 1e-15);
/// ```
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "BSplineCurveRepr", into = "BSplineCurveRepr")]
pub struct BSplineCurve {
    degree: usize,
    knots: KnotVector,
    control: Points,
}

#[derive(Serialize, Deserialize)]
struct BSplineCurveRepr {
    degree: usize,
    knots: Vec<f64>,
    control: Points,
}

impl TryFrom<BSplineCurveRepr> for BSplineCurve {
    type Error = Error;
    fn try_from(r: BSplineCurveRepr) -> Result<Self> {
        BSplineCurve::new(r.degree, r.knots, r.control)
    }
}

impl From<BSplineCurve> for BSplineCurveRepr {
    fn from(c: BSplineCurve) -> Self {
        BSplineCurveRepr {
            degree: c.degree,
            knots: c.knots.into_vec(),
            control: c.control,
        }
    }
}

impl BSplineCurve {
    /// A B-spline curve from its degree, knots and control points.
    ///
    /// # Errors
    /// Knot errors of [`KnotVector::new`] and [`KnotVector::validate_for`]
    /// ([`Error::LengthMismatch`] if `knots.len() != n_ctrl + degree + 1`,
    /// [`Error::KnotMultiplicity`], [`Error::EmptyDomain`], [`Error::Degree`] if there are fewer
    /// than `degree + 1` control points).
    pub fn new(degree: usize, knots: impl Into<Vec<f64>>, control: Points) -> Result<Self> {
        let knots = KnotVector::new(knots.into())?;
        Self::from_knot_vector(degree, knots, control)
    }

    /// As [`BSplineCurve::new`] with an already validated [`KnotVector`].
    ///
    /// # Errors
    /// As [`KnotVector::validate_for`].
    pub fn from_knot_vector(degree: usize, knots: KnotVector, control: Points) -> Result<Self> {
        if control.is_empty() {
            return Err(Error::TooFew {
                what: "control points",
                min: degree + 1,
                got: 0,
            });
        }
        knots.validate_for(degree, control.len())?;
        Ok(BSplineCurve {
            degree,
            knots,
            control,
        })
    }

    /// Trusted constructor for results built inside the crate (debug-checked).
    pub(crate) fn from_raw(degree: usize, knots: Vec<f64>, control: Points) -> Self {
        debug_assert_eq!(
            knots.len(),
            control.len() + degree + 1,
            "raw B-spline counts"
        );
        BSplineCurve {
            degree,
            knots: KnotVector::from_raw(knots),
            control,
        }
    }

    /// Degree `p` (order `p + 1`).
    #[must_use]
    pub fn degree(&self) -> usize {
        self.degree
    }

    /// The knot vector.
    #[must_use]
    pub fn knots(&self) -> &KnotVector {
        &self.knots
    }

    /// The control points.
    #[must_use]
    pub fn control_points(&self) -> &Points {
        &self.control
    }

    /// Dimension of the curve's points.
    #[must_use]
    pub fn dim(&self) -> usize {
        self.control.dim()
    }

    /// Parameter domain `[t_p, t_{n+1}]`.
    #[must_use]
    pub fn domain(&self) -> (f64, f64) {
        self.knots.domain(self.degree)
    }

    /// Decomposes into `(degree, knots, control points)`.
    #[must_use]
    pub fn into_parts(self) -> (usize, KnotVector, Points) {
        (self.degree, self.knots, self.control)
    }

    /// Point `C(t)`.
    ///
    /// # Errors
    /// [`Error::ParameterOutOfDomain`] if `t` is outside [`BSplineCurve::domain`] or NaN.
    pub fn eval(&self, t: f64) -> Result<Vec<f64>> {
        let mut out = vec![0.0; self.dim()];
        self.eval_into(t, &mut out)?;
        Ok(out)
    }

    /// Point `C(t)` into `out` (length `dim`): span search, basis functions by the Cox–de Boor
    /// triangular scheme, and the combination of `p + 1` control points (P&T Algorithm A3.1).
    ///
    /// # Errors
    /// [`Error::ParameterOutOfDomain`]; [`Error::LengthMismatch`] if `out.len() != dim`.
    pub fn eval_into(&self, t: f64, out: &mut [f64]) -> Result<()> {
        check_out(out.len(), self.dim())?;
        let span = self.knots.find_span(self.degree, t)?;
        let mut scratch = BasisScratch::new(self.degree);
        let mut n = vec![0.0; self.degree + 1];
        self.eval_span(span, t, &mut scratch, &mut n, out);
        Ok(())
    }

    /// Evaluates at a known span with caller-provided scratch (no allocation).
    pub(crate) fn eval_span(
        &self,
        span: usize,
        t: f64,
        scratch: &mut BasisScratch,
        n: &mut [f64],
        out: &mut [f64],
    ) {
        let p = self.degree;
        let dim = self.dim();
        basis_funs_into(self.knots.as_slice(), p, span, t, scratch, n);
        out.fill(0.0);
        let ctrl = self.control.as_slice();
        for (j, &nj) in n.iter().enumerate() {
            let base = (span - p + j) * dim;
            for (o, c) in out.iter_mut().zip(&ctrl[base..base + dim]) {
                *o += nj * c;
            }
        }
    }

    /// Evaluates at every parameter of `ts` into `out` (`ts.len() × dim`, point-major), without
    /// allocating per point. Sorted parameters take the amortised O(1) span search; any order is
    /// accepted.
    ///
    /// ```
    /// use lekalo::{BSplineCurve, KnotVector, Points};
    /// let ctrl = Points::from_2d(&[[0.0, 0.0], [1.0, 2.0], [3.0, 2.0], [4.0, 0.0]]).unwrap();
    /// let c = BSplineCurve::from_knot_vector(2, KnotVector::clamped_uniform(2, 4).unwrap(), ctrl).unwrap();
    /// let ts: Vec<f64> = (0..=10).map(|k| k as f64 / 10.0).collect();
    /// let mut out = vec![0.0; ts.len() * 2];
    /// c.eval_batch(&ts, &mut out).unwrap();
    /// assert_eq!(&out[20..22], &[4.0, 0.0]);
    /// ```
    ///
    /// # Errors
    /// [`Error::LengthMismatch`] if `out.len() != ts.len() · dim`;
    /// [`Error::ParameterOutOfDomain`] at the first parameter outside the domain (nothing is
    /// guaranteed about `out` then).
    pub fn eval_batch(&self, ts: &[f64], out: &mut [f64]) -> Result<()> {
        let dim = self.dim();
        if out.len() != ts.len() * dim {
            return Err(Error::LengthMismatch {
                what: "output buffer (parameters × dimension)",
                expected: ts.len() * dim,
                got: out.len(),
            });
        }
        let mut cursor = self.knots.span_cursor(self.degree);
        let mut scratch = BasisScratch::new(self.degree);
        let mut n = vec![0.0; self.degree + 1];
        for (&t, o) in ts.iter().zip(out.chunks_exact_mut(dim)) {
            let span = cursor.find(t)?;
            self.eval_span(span, t, &mut scratch, &mut n, o);
        }
        Ok(())
    }

    /// Derivatives `C^{(k)}(t)` for `k = 0..=order` (P&T Algorithm A3.2): returns
    /// `order + 1` points, row `k` the k-th derivative. Orders above the degree are zero. At an
    /// interior knot the derivatives are right-hand ones (left-hand at the right end).
    ///
    /// # Errors
    /// [`Error::ParameterOutOfDomain`].
    pub fn eval_derivatives(&self, t: f64, order: usize) -> Result<Points> {
        let p = self.degree;
        let dim = self.dim();
        let span = self.knots.find_span(p, t)?;
        let w = p + 1;
        let mut d = vec![0.0; (order + 1) * w];
        basis_ders_into(
            self.knots.as_slice(),
            p,
            span,
            t,
            order,
            &mut BasisScratch::new(p),
            &mut d,
        );
        let mut out = Points::zeros(order + 1, dim);
        let ctrl = self.control.as_slice();
        for k in 0..=order.min(p) {
            let row = out.point_mut(k);
            for j in 0..w {
                let base = (span - p + j) * dim;
                let c = d[k * w + j];
                for (o, x) in row.iter_mut().zip(&ctrl[base..base + dim]) {
                    *o += c * x;
                }
            }
        }
        Ok(out)
    }
}

fn check_out(got: usize, dim: usize) -> Result<()> {
    if got != dim {
        return Err(Error::LengthMismatch {
            what: "output point (dimension)",
            expected: dim,
            got,
        });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::basis::basis_function_recursive;

    fn lecture() -> BSplineCurve {
        let ctrl = Points::from_2d(&[[1.0, 1.0], [2.0, 3.0], [4.0, 3.0]]).unwrap();
        BSplineCurve::new(2, vec![0.0, 0.0, 1.0, 2.0, 3.0, 3.0], ctrl).unwrap()
    }

    /// Document 002 §C.5: on [1,2) the curve is (t²/2 + 1, −t² + 4t − 1).
    #[test]
    fn lecture_curve_piece_on_domain() {
        let c = lecture();
        for k in 0..=20 {
            let t = 1.0 + k as f64 / 20.0;
            let p = c.eval(t).unwrap();
            assert!((p[0] - (0.5 * t * t + 1.0)).abs() < 1e-14, "x at {t}");
            assert!((p[1] - (-t * t + 4.0 * t - 1.0)).abs() < 1e-14, "y at {t}");
            let d = c.eval_derivatives(t, 3).unwrap();
            assert!((d.point(1)[0] - t).abs() < 1e-13, "x' at {t}");
            assert!(
                (d.point(1)[1] - (-2.0 * t + 4.0)).abs() < 1e-13,
                "y' at {t}"
            );
            assert!((d.point(2)[1] + 2.0).abs() < 1e-12, "y'' at {t}");
            assert_eq!(d.point(3), &[0.0, 0.0]);
        }
        // end points: midpoints of the control legs
        assert_eq!(c.eval(1.0).unwrap(), vec![1.5, 2.0]);
        assert_eq!(c.eval(2.0).unwrap(), vec![3.0, 3.0]);
        assert!(matches!(
            c.eval(0.5),
            Err(Error::ParameterOutOfDomain { .. })
        ));
    }

    #[test]
    fn constructor_errors() {
        let ctrl = Points::from_2d(&[[1.0, 1.0], [2.0, 3.0]]).unwrap();
        assert!(matches!(
            BSplineCurve::new(2, vec![0.0, 0.0, 0.0, 1.0, 1.0], ctrl.clone()),
            Err(Error::Degree { .. })
        ));
        assert!(matches!(
            BSplineCurve::new(1, vec![0.0, 0.0, 1.0], ctrl.clone()),
            Err(Error::LengthMismatch { .. })
        ));
        assert!(matches!(
            BSplineCurve::new(1, vec![0.0, 1.0, 0.5, 1.0], ctrl),
            Err(Error::KnotsNotSorted { .. })
        ));
        let empty = Points::new(vec![], 2).unwrap();
        assert!(matches!(
            BSplineCurve::new(1, vec![0.0, 1.0], empty),
            Err(Error::TooFew { .. })
        ));
    }

    #[test]
    fn batch_matches_single_and_oracle() {
        let ctrl = Points::new((0..21).map(|i| f64::from(i).sin()).collect(), 3).unwrap();
        let kv =
            KnotVector::new(vec![0.0, 0.0, 0.0, 0.0, 0.2, 0.2, 0.5, 1.0, 1.0, 1.0, 1.0]).unwrap();
        let c = BSplineCurve::from_knot_vector(3, kv.clone(), ctrl.clone()).unwrap();
        let ts: Vec<f64> = (0..=50).map(|k| f64::from(k) / 50.0).collect();
        let mut out = vec![0.0; ts.len() * 3];
        c.eval_batch(&ts, &mut out).unwrap();
        for (k, &t) in ts.iter().enumerate() {
            let single = c.eval(t).unwrap();
            assert_eq!(&out[3 * k..3 * k + 3], single.as_slice(), "t = {t}");
            for d in 0..3 {
                let oracle: f64 = (0..7)
                    .map(|i| basis_function_recursive(&kv, i, 3, t).unwrap() * ctrl.point(i)[d])
                    .sum();
                assert!((single[d] - oracle).abs() < 1e-13, "t = {t}");
            }
        }
        assert!(matches!(
            c.eval_batch(&ts, &mut out[1..]),
            Err(Error::LengthMismatch { .. })
        ));
        let mut o = vec![0.0; 3];
        assert!(matches!(
            c.eval_batch(&[f64::NAN], &mut o),
            Err(Error::ParameterOutOfDomain { .. })
        ));
    }

    #[test]
    fn serde_goes_through_validation() {
        let c = lecture();
        let s = serde_json::to_string(&c).unwrap();
        let back: BSplineCurve = serde_json::from_str(&s).unwrap();
        assert_eq!(back, c);
        let bad = s.replace("[0.0,0.0,1.0,2.0,3.0,3.0]", "[0.0,0.0,1.0,2.0,3.0]");
        assert!(serde_json::from_str::<BSplineCurve>(&bad).is_err());
    }
}
