//! Outlier-resistant least squares by iteratively reweighted least squares
//! (`docs/theory/fitting.md#robust`).

use super::data::{CurveFit, FitData};
use super::lsq::{least_squares, EndConstraints};
use crate::error::readable;
use crate::error::{Error, Result};
use crate::knots::KnotVector;

/// The loss of a robust fit, with its tuning constant `c` in units of the robust scale
/// `σ = 1.4826 · median_k |r_k|` (the median absolute residual, consistent for Gaussian noise).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum RobustLoss {
    /// Huber: weight `1` for `|r| ≤ cσ`, `cσ/|r|` beyond (convex; `c = 1.345` is 95 % efficient).
    Huber(f64),
    /// Tukey's biweight: weight `(1 − (r/cσ)²)²` for `|r| < cσ`, `0` beyond (rejects outliers;
    /// `c = 4.685` is 95 % efficient).
    Tukey(f64),
}

impl RobustLoss {
    fn weight(self, u: f64) -> f64 {
        match self {
            RobustLoss::Huber(c) => {
                if u.abs() <= c {
                    1.0
                } else {
                    c / u.abs()
                }
            }
            RobustLoss::Tukey(c) => {
                let v = u / c;
                if v.abs() < 1.0 {
                    (1.0 - v * v) * (1.0 - v * v)
                } else {
                    0.0
                }
            }
        }
    }
}

/// Smallest robust scale, relative to the largest absolute data coordinate: residuals below it
/// are the rounding of a fit that reproduces the data (about `1e-16` relative), not noise. Without
/// this floor such a fit's rounding became the scale `σ`, and the next round rejected inliers at
/// random, down to a span without data.
pub const ROBUST_SCALE_RTOL: f64 = 1e-12;

/// The result of [`robust_least_squares`].
#[derive(Debug, Clone, PartialEq)]
pub struct RobustFit {
    /// The final fit (its report's weighted sum uses the data weights times the robust weights).
    pub fit: CurveFit,
    /// The final robust weight of every point, in `[0, 1]` (multiplies the data weight).
    pub weights: Vec<f64>,
    /// The robust scale σ of the last iteration.
    pub scale: f64,
    /// Number of reweighted fits.
    pub iterations: usize,
}

/// Least squares with given knots that resists outliers: iteratively reweighted least squares
/// (Holland & Welsch 1977). Each round fits by [`least_squares`] with weights `w_k·ρ_k`, where
/// `ρ_k` is the loss's weight of the residual `|C(ū_k) − Q_k|/σ`, and stops when no `ρ_k`
/// changes by more than `1e-6` or after `max_iter` rounds. `σ` is at least
/// [`ROBUST_SCALE_RTOL`] times the largest absolute data coordinate.
///
/// ```
/// use lekalo::fit::{robust_least_squares, FitData, RobustLoss};
/// use lekalo::{KnotVector, PointsRef};
/// let x: Vec<f64> = (0..60).map(|k| k as f64 / 59.0).collect();
/// let mut y: Vec<f64> = x.iter().map(|t| 2.0 * t).collect();
/// y[30] = 50.0; // an outlier
/// let data = FitData::new(PointsRef::from_flat(1, &y)?, &x)?;
/// let r = robust_least_squares(&data, 3, &KnotVector::clamped_uniform(3, 6)?, RobustLoss::Tukey(4.685), 50)?;
/// assert_eq!(r.weights[30], 0.0);
/// assert!((r.fit.curve.eval(0.5)?[0] - 1.0).abs() < 1e-6);
/// # Ok::<(), lekalo::Error>(())
/// ```
///
/// # Errors
/// As [`least_squares`] (a Tukey loss can leave a span without weight:
/// [`Error::SchoenbergWhitney`]); [`Error::InvalidArgument`] for a tuning constant that is not
/// positive and finite.
pub fn robust_least_squares(
    data: &FitData<'_>,
    degree: usize,
    knots: &KnotVector,
    loss: RobustLoss,
    max_iter: usize,
) -> Result<RobustFit> {
    let c = match loss {
        RobustLoss::Huber(c) | RobustLoss::Tukey(c) => c,
    };
    if !(c > 0.0 && c.is_finite()) {
        return Err(Error::InvalidArgument {
            what: "robust tuning constant".into(),
            reason: format!(
                "{c}: it must be positive and finite (1.345 for Huber, 4.685 for Tukey)",
                c = readable(&c)
            ),
        });
    }
    let ends = EndConstraints::none();
    let n = data.len();
    let base: Vec<f64> = (0..n).map(|k| data.weight(k)).collect();
    let mut rho = vec![1.0; n];
    let mut fit = least_squares(data, degree, knots, &ends)?;
    let floor = ROBUST_SCALE_RTOL
        * data
            .points()
            .as_slice()
            .iter()
            .fold(0.0_f64, |m, v| m.max(v.abs()));
    let mut scale = 0.0;
    let mut iterations = 1;
    while iterations < max_iter.max(1) {
        let mut abs: Vec<f64> = fit.report.residuals.clone();
        abs.sort_by(f64::total_cmp);
        scale = (1.4826 * abs[n / 2]).max(floor);
        if scale <= 0.0 || scale.is_nan() {
            break;
        }
        let new: Vec<f64> = fit
            .report
            .residuals
            .iter()
            .map(|&r| loss.weight(r / scale))
            .collect();
        let change = new
            .iter()
            .zip(&rho)
            .fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()));
        rho = new;
        let w: Vec<f64> = base.iter().zip(&rho).map(|(a, b)| a * b).collect();
        let reweighted = data.with_weights(&w)?;
        fit = least_squares(&reweighted, degree, knots, &ends)?;
        iterations += 1;
        if change <= 1e-6 {
            break;
        }
    }
    Ok(RobustFit {
        fit,
        weights: rho,
        scale,
        iterations,
    })
}
