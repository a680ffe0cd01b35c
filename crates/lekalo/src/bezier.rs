//! Bezier curves `P(t) = Σ_{i=0}^{n} b_{n,i}(t) P_i`, `t ∈ [0, 1]` (document 002 §C.4, document
//! 004 eq. 1), of any degree and dimension.

use serde::{Deserialize, Serialize};

use crate::basis::bernstein_all_unchecked;
use crate::error::{Error, Result};
use crate::points::Points;

/// A Bezier curve of degree `n` with control points `P_0 … P_n` on the domain `[0, 1]`.
///
/// ```
/// use lekalo::{BezierCurve, Points};
/// let c = BezierCurve::new(Points::from_2d(&[[0.0, 0.0], [1.0, 2.0], [2.0, 0.0]]).unwrap()).unwrap();
/// assert_eq!(c.degree(), 2);
/// assert_eq!(c.eval(0.5).unwrap(), vec![1.0, 1.0]);
/// ```
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "BezierCurveRepr", into = "BezierCurveRepr")]
pub struct BezierCurve {
    control: Points,
}

#[derive(Serialize, Deserialize)]
struct BezierCurveRepr {
    control: Points,
}

impl TryFrom<BezierCurveRepr> for BezierCurve {
    type Error = Error;
    fn try_from(r: BezierCurveRepr) -> Result<Self> {
        BezierCurve::new(r.control)
    }
}

impl From<BezierCurve> for BezierCurveRepr {
    fn from(c: BezierCurve) -> Self {
        BezierCurveRepr { control: c.control }
    }
}

impl BezierCurve {
    /// A Bezier curve from its control points (degree = number of points − 1).
    ///
    /// # Errors
    /// [`Error::TooFew`] if there are no control points.
    pub fn new(control: Points) -> Result<Self> {
        if control.is_empty() {
            return Err(Error::TooFew {
                what: "Bezier control points",
                min: 1,
                got: 0,
            });
        }
        Ok(BezierCurve { control })
    }

    /// Trusted constructor for internal results.
    #[allow(dead_code)] // used by subdivision and degree change
    pub(crate) fn from_raw(control: Points) -> Self {
        debug_assert!(!control.is_empty(), "raw Bezier needs control points");
        BezierCurve { control }
    }

    /// Degree `n` (number of control points − 1).
    #[must_use]
    pub fn degree(&self) -> usize {
        self.control.len() - 1
    }

    /// Dimension of the points.
    #[must_use]
    pub fn dim(&self) -> usize {
        self.control.dim()
    }

    /// The control points.
    #[must_use]
    pub fn control_points(&self) -> &Points {
        &self.control
    }

    /// The control points, owned.
    #[must_use]
    pub fn into_control_points(self) -> Points {
        self.control
    }

    /// Point `P(t)` by de Casteljau's algorithm (P&T Algorithm A1.5): repeated linear
    /// interpolation of the control polygon, O(n²·dim), stable.
    ///
    /// # Errors
    /// [`Error::ParameterOutOfDomain`] unless `0 ≤ t ≤ 1`.
    pub fn eval(&self, t: f64) -> Result<Vec<f64>> {
        check_unit(t)?;
        let dim = self.dim();
        let mut q = self.control.as_slice().to_vec();
        let n = self.degree();
        for k in 1..=n {
            for i in 0..=(n - k) {
                for d in 0..dim {
                    q[i * dim + d] = (1.0 - t) * q[i * dim + d] + t * q[(i + 1) * dim + d];
                }
            }
        }
        q.truncate(dim);
        Ok(q)
    }

    /// Point `P(t)` by the Bernstein sum `Σ b_{n,i}(t) P_i` (document 002 §C.4), into `out`.
    ///
    /// # Errors
    /// [`Error::ParameterOutOfDomain`]; [`Error::LengthMismatch`] if `out.len() != dim`.
    pub fn eval_bernstein_into(&self, t: f64, out: &mut [f64]) -> Result<()> {
        check_unit(t)?;
        let dim = self.dim();
        if out.len() != dim {
            return Err(Error::LengthMismatch {
                what: "output point (dimension)",
                expected: dim,
                got: out.len(),
            });
        }
        let n = self.degree();
        let mut b = vec![0.0; n + 1];
        bernstein_all_unchecked(n, t, &mut b);
        out.fill(0.0);
        for (bi, p) in b.iter().zip(self.control.iter()) {
            for (o, x) in out.iter_mut().zip(p) {
                *o += bi * x;
            }
        }
        Ok(())
    }
}

/// Checks `t ∈ [0, 1]` (NaN fails).
pub(crate) fn check_unit(t: f64) -> Result<()> {
    if !(0.0..=1.0).contains(&t) {
        return Err(Error::ParameterOutOfDomain {
            t,
            min: 0.0,
            max: 1.0,
        });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn de_casteljau_equals_bernstein_sum() {
        let ctrl = Points::new((0..18).map(|i| (f64::from(i) * 0.7).cos()).collect(), 3).unwrap();
        let c = BezierCurve::new(ctrl).unwrap();
        let mut out = vec![0.0; 3];
        for k in 0..=10 {
            let t = f64::from(k) / 10.0;
            let a = c.eval(t).unwrap();
            c.eval_bernstein_into(t, &mut out).unwrap();
            for d in 0..3 {
                assert!((a[d] - out[d]).abs() < 1e-14, "t={t}");
            }
        }
        assert!(c.eval(-0.1).is_err() && c.eval(f64::NAN).is_err());
        assert!(matches!(
            BezierCurve::new(Points::new(vec![], 2).unwrap()),
            Err(Error::TooFew { .. })
        ));
        assert!(matches!(
            c.eval_bernstein_into(0.5, &mut [0.0; 2]),
            Err(Error::LengthMismatch { .. })
        ));
    }

    /// Document 002 §C.4: the cubic written out.
    #[test]
    fn cubic_formula() {
        let c = BezierCurve::new(Points::new(vec![1.0, 5.0, -2.0, 3.0], 1).unwrap()).unwrap();
        let t: f64 = 0.3;
        let s = 1.0 - t;
        let expect = s.powi(3) + 3.0 * 5.0 * t * s * s + 3.0 * -2.0 * t * t * s + 3.0 * t.powi(3);
        assert!((c.eval(t).unwrap()[0] - expect).abs() < 1e-14, "cubic");
    }
}
