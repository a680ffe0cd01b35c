//! NURBS curves: a B-spline curve over homogeneous control points `(w·x, w·y, …, w)` in
//! dimension `dim + 1`, so that every B-spline algorithm applies unchanged; the rational curve is
//! the projection `C(t) = A(t) / w(t)`.

use serde::{Deserialize, Serialize};

use crate::bspline::BSplineCurve;
use crate::error::{check_finite, Error, Result};
use crate::points::Points;

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
    homogeneous: BSplineCurve,
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
        if weights.len() != control.len() {
            return Err(Error::LengthMismatch {
                what: "weights (one per control point)",
                expected: control.len(),
                got: weights.len(),
            });
        }
        check_finite("weights", &weights)?;
        if let Some(index) = weights.iter().position(|&w| w <= 0.0) {
            return Err(Error::NonPositiveWeight {
                index,
                weight: weights[index],
            });
        }
        let dim = control.dim();
        let mut h = Vec::with_capacity(control.len() * (dim + 1));
        for (p, &w) in control.iter().zip(&weights) {
            h.extend(p.iter().map(|x| x * w));
            h.push(w);
        }
        // w·x can overflow for huge coordinates and weights
        let homogeneous_points = Points::new(h, dim + 1)?;
        let homogeneous = BSplineCurve::new(degree, knots, homogeneous_points)?;
        Ok(NurbsCurve { homogeneous })
    }

    /// A NURBS curve from a B-spline in homogeneous coordinates (last coordinate the weight).
    ///
    /// # Errors
    /// [`Error::Dimension`] if the dimension is below 2; [`Error::NonPositiveWeight`].
    pub fn from_homogeneous(homogeneous: BSplineCurve) -> Result<Self> {
        let hd = homogeneous.dim();
        if hd < 2 {
            return Err(Error::Dimension {
                what: "homogeneous control points (dim + 1 for the weight)",
                expected: 2,
                got: hd,
            });
        }
        for (index, p) in homogeneous.control_points().iter().enumerate() {
            let weight = p[hd - 1];
            if weight <= 0.0 {
                return Err(Error::NonPositiveWeight { index, weight });
            }
        }
        Ok(NurbsCurve { homogeneous })
    }

    /// The same curve with unit weights: the non-rational B-spline as a NURBS.
    #[must_use]
    pub fn from_bspline(curve: &BSplineCurve) -> Self {
        let dim = curve.dim();
        let mut h = Vec::with_capacity(curve.control_points().len() * (dim + 1));
        for p in curve.control_points().iter() {
            h.extend_from_slice(p);
            h.push(1.0);
        }
        let homogeneous = BSplineCurve::from_raw(
            curve.degree(),
            curve.knots().as_slice().to_vec(),
            Points::from_raw(h, dim + 1),
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
        let hd = self.homogeneous.dim();
        self.homogeneous
            .control_points()
            .iter()
            .map(|p| p[hd - 1])
            .collect()
    }

    /// Euclidean control points `P_i = (w·P_i) / w_i`.
    #[must_use]
    pub fn control_points(&self) -> Points {
        let hd = self.homogeneous.dim();
        let mut out = Vec::with_capacity(self.homogeneous.control_points().len() * (hd - 1));
        for p in self.homogeneous.control_points().iter() {
            let w = p[hd - 1];
            out.extend(p[..hd - 1].iter().map(|x| x / w));
        }
        Points::from_raw(out, hd - 1)
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
}
