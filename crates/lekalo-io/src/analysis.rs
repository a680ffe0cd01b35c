//! Uniform access to the curve objects for the writers and the CLI: domain, points,
//! derivatives, curvature, control net and knots.
//!
//! The mathematics is the library's (evaluation, derivatives, curvature); this module only
//! dispatches over the object kinds.

use lekalo::{KnotVector, Points};

use crate::object::Object;

impl Object {
    /// Dimension of the curve's points (Euclidean, without the weight).
    #[must_use]
    pub fn dim(&self) -> usize {
        match self {
            Object::Bezier(c) => c.dim(),
            Object::BSpline(c) => c.dim(),
            Object::Nurbs(c) => c.dim(),
        }
    }

    /// Degree.
    #[must_use]
    pub fn degree(&self) -> usize {
        match self {
            Object::Bezier(c) => c.degree(),
            Object::BSpline(c) => c.degree(),
            Object::Nurbs(c) => c.degree(),
        }
    }

    /// Parameter domain (`[0, 1]` for Bezier curves, `[t_p, t_{n+1}]` otherwise).
    #[must_use]
    pub fn domain(&self) -> (f64, f64) {
        match self {
            Object::Bezier(_) => (0.0, 1.0),
            Object::BSpline(c) => c.domain(),
            Object::Nurbs(c) => c.domain(),
        }
    }

    /// Euclidean control points.
    #[must_use]
    pub fn control_points(&self) -> Points {
        match self {
            Object::Bezier(c) => c.control_points().clone(),
            Object::BSpline(c) => c.control_points().clone(),
            Object::Nurbs(c) => c.control_points(),
        }
    }

    /// Weights of a rational curve, `None` for polynomial curves.
    #[must_use]
    pub fn weights(&self) -> Option<Vec<f64>> {
        match self {
            Object::Nurbs(c) => Some(c.weights()),
            _ => None,
        }
    }

    /// The knot vector; a Bezier curve of degree `n` has the equivalent clamped knots
    /// `[0]·(n+1) ++ [1]·(n+1)` (document 002, Bezier curves and B-splines: the Bernstein
    /// polynomials are the B-splines on these knots).
    #[must_use]
    pub fn knots(&self) -> KnotVector {
        match self {
            Object::Bezier(c) => bezier_knots(c.degree()),
            Object::BSpline(c) => c.knots().clone(),
            Object::Nurbs(c) => c.knots().clone(),
        }
    }

    /// Point at `t`.
    ///
    /// # Errors
    /// [`lekalo::Error::ParameterOutOfDomain`].
    pub fn eval(&self, t: f64) -> lekalo::Result<Vec<f64>> {
        match self {
            Object::Bezier(c) => c.eval(t),
            Object::BSpline(c) => c.eval(t),
            Object::Nurbs(c) => c.eval(t),
        }
    }

    /// Derivatives `C^{(k)}(t)`, `k = 0..=order`, one row each (the library's
    /// `eval_derivatives` of each curve type; rational curves by the quotient rule, P&T A4.2).
    ///
    /// # Errors
    /// [`lekalo::Error::ParameterOutOfDomain`], [`lekalo::Error::TooLarge`] for absurd orders.
    pub fn derivatives(&self, t: f64, order: usize) -> lekalo::Result<Points> {
        match self {
            Object::Bezier(c) => c.eval_derivatives(t, order),
            Object::BSpline(c) => c.eval_derivatives(t, order),
            Object::Nurbs(c) => c.eval_derivatives(t, order),
        }
    }

    /// Points at every parameter of `ts` into `out` (`ts.len() × dim`, point-major) by the
    /// library's batch evaluation (`eval_batch` of each curve type: no allocation per point,
    /// amortised span search), which agrees with [`Object::eval`] to rounding.
    ///
    /// # Errors
    /// [`lekalo::Error::ParameterOutOfDomain`], [`lekalo::Error::LengthMismatch`].
    pub fn eval_batch(&self, ts: &[f64], out: &mut [f64]) -> lekalo::Result<()> {
        match self {
            Object::Bezier(c) => c.eval_batch(ts, out),
            Object::BSpline(c) => c.eval_batch(ts, out),
            Object::Nurbs(c) => c.eval_batch(ts, out),
        }
    }

    /// `n ≥ 2` parameters evenly spaced over the domain, both ends included.
    #[must_use]
    pub fn uniform_parameters(&self, n: usize) -> Vec<f64> {
        let (a, b) = self.domain();
        uniform(a, b, n)
    }

    /// The curve sampled at `n` uniform parameters, as points.
    ///
    /// # Errors
    /// Evaluation errors (none for parameters inside the domain).
    pub fn sample(&self, n: usize) -> lekalo::Result<Points> {
        let ts = self.uniform_parameters(n);
        let mut data = Vec::with_capacity(ts.len() * self.dim());
        for t in ts {
            data.extend(self.eval(t)?);
        }
        Points::from_flat(self.dim(), data)
    }
}

/// `n` evenly spaced values from `a` to `b` inclusive (`n = 1` gives `[a]`, `n = 0` nothing).
#[must_use]
pub fn uniform(a: f64, b: f64, n: usize) -> Vec<f64> {
    match n {
        0 => Vec::new(),
        1 => vec![a],
        _ => (0..n)
            .map(|k| {
                if k == n - 1 {
                    b
                } else {
                    a + (b - a) * (k as f64 / (n - 1) as f64)
                }
            })
            .collect(),
    }
}

fn bezier_knots(degree: usize) -> KnotVector {
    let mut k = vec![0.0; degree + 1];
    k.extend(std::iter::repeat_n(1.0, degree + 1));
    // clamped [0…0, 1…1] is always a valid knot vector
    KnotVector::new(k).unwrap_or_else(|_| unreachable!("clamped Bezier knots are valid"))
}

pub use lekalo::curvature;

#[cfg(test)]
mod tests {
    use super::*;
    use lekalo::{BezierCurve, NurbsCurve};

    #[test]
    fn circle_curvature_and_rational_derivatives() {
        // quarter circle of radius 2: curvature 1/2 everywhere, |C'| from finite differences
        let w = std::f64::consts::FRAC_1_SQRT_2;
        let ctrl = Points::from_2d(&[[2.0, 0.0], [2.0, 2.0], [0.0, 2.0]]).unwrap();
        let c = Object::Nurbs(
            NurbsCurve::new(
                2,
                vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
                ctrl,
                vec![1.0, w, 1.0],
            )
            .unwrap(),
        );
        for t in [0.1, 0.5, 0.9] {
            let d = c.derivatives(t, 2).unwrap();
            let k = curvature(d.point(1), d.point(2)).unwrap();
            assert!((k - 0.5).abs() < 1e-12, "curvature {k} at {t}");
            let h = 1e-6;
            let (a, b) = (c.eval(t - h).unwrap(), c.eval(t + h).unwrap());
            for i in 0..2 {
                let fd = (b[i] - a[i]) / (2.0 * h);
                assert!((fd - d.point(1)[i]).abs() < 1e-7, "C' at {t}");
            }
            // tangent is orthogonal to the radius
            let p = d.point(0);
            assert!(
                (p[0] * d.point(1)[0] + p[1] * d.point(1)[1]).abs() < 1e-12,
                "tangent"
            );
        }
    }

    #[test]
    fn bezier_derivatives_match_hodograph() {
        // P(t) = (2t, 2t(1−t)·2): P'(t) = (2, 4 − 8t)
        let c = Object::Bezier(
            BezierCurve::new(Points::from_2d(&[[0.0, 0.0], [1.0, 2.0], [2.0, 0.0]]).unwrap())
                .unwrap(),
        );
        let d = c.derivatives(0.25, 2).unwrap();
        assert_eq!(d.point(0), c.eval(0.25).unwrap().as_slice());
        assert!(
            (d.point(1)[0] - 2.0).abs() < 1e-14 && (d.point(1)[1] - 2.0).abs() < 1e-14,
            "P'"
        );
        assert!((d.point(2)[1] + 8.0).abs() < 1e-13, "P''");
        assert!(curvature(&[0.0, 0.0], &[1.0, 0.0]).is_none());
        assert_eq!(uniform(0.0, 1.0, 3), vec![0.0, 0.5, 1.0]);
    }
}
