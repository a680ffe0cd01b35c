//! The data of a fit and the report of its residuals (`docs/theory/fitting.md#residuals`).

use super::rows::for_each_row;
use crate::error::{check_finite, Error, Result};
use crate::points::PointsRef;
use crate::BSplineCurve;
use crate::{Arg, What};

/// Points `Q_k` with parameters `ū_k` and optional weights `w_k`, validated once.
///
/// ```
/// use lekalo::fit::FitData;
/// use lekalo::PointsRef;
/// let q = [0.0, 1.0, 0.5, 2.0];
/// let data = FitData::new(PointsRef::from_flat(1, &q)?, &[0.0, 1.0, 2.0, 3.0])?.with_weights(&[1.0; 4])?;
/// assert_eq!(data.len(), 4);
/// # Ok::<(), lekalo::Error>(())
/// ```
#[derive(Debug, Clone, Copy)]
pub struct FitData<'a> {
    points: PointsRef<'a>,
    params: &'a [f64],
    weights: Option<&'a [f64]>,
}

impl<'a> FitData<'a> {
    /// Data points with one parameter each (any order; finite).
    ///
    /// # Errors
    /// [`Error::TooFew`] for no points; [`Error::LengthMismatch`] if `params` and `points`
    /// differ in length; [`Error::NonFinite`] for a NaN or infinite parameter.
    pub fn new(points: PointsRef<'a>, params: &'a [f64]) -> Result<Self> {
        if points.is_empty() {
            return Err(Error::TooFew {
                what: "data points to fit".into(),
                min: 1,
                got: 0,
            });
        }
        if params.len() != points.len() {
            return Err(Error::LengthMismatch {
                what: What::of(Arg::Parameters, "data parameters (one per data point)"),
                expected: points.len(),
                got: params.len(),
            });
        }
        check_finite("data parameters", params)?;
        Ok(FitData {
            points,
            params,
            weights: None,
        })
    }

    /// The same data with weights `w_k` (finite, `≥ 0`, at least one positive).
    ///
    /// # Errors
    /// [`Error::LengthMismatch`]; [`Error::InvalidDataWeight`] for a NaN, infinite or negative
    /// weight, or when every weight is zero.
    pub fn with_weights(self, weights: &'a [f64]) -> Result<Self> {
        if weights.len() != self.points.len() {
            return Err(Error::LengthMismatch {
                what: What::of(Arg::DataWeights, "data weights (one per data point)"),
                expected: self.points.len(),
                got: weights.len(),
            });
        }
        if let Some(index) = weights.iter().position(|w| !(w.is_finite() && *w >= 0.0)) {
            return Err(Error::InvalidDataWeight {
                index,
                weight: weights[index],
            });
        }
        if weights.iter().all(|&w| w == 0.0) {
            return Err(Error::InvalidDataWeight {
                index: 0,
                weight: 0.0,
            });
        }
        Ok(FitData {
            weights: Some(weights),
            ..self
        })
    }

    /// Number of data points.
    #[must_use]
    pub fn len(&self) -> usize {
        self.points.len()
    }

    /// Never true: data hold at least one point.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.points.is_empty()
    }

    /// The points.
    #[must_use]
    pub fn points(&self) -> PointsRef<'a> {
        self.points
    }

    /// The parameters.
    #[must_use]
    pub fn params(&self) -> &'a [f64] {
        self.params
    }

    /// The weights, if given (otherwise all 1).
    #[must_use]
    pub fn weights(&self) -> Option<&'a [f64]> {
        self.weights
    }

    /// Weight of point `k` (1 without weights).
    #[inline]
    pub(crate) fn weight(&self, k: usize) -> f64 {
        self.weights.map_or(1.0, |w| w[k])
    }

    /// Indices of the points by increasing parameter, or `None` when they already come sorted.
    pub(crate) fn order(&self) -> Option<Vec<usize>> {
        if self.params.windows(2).all(|w| w[0] <= w[1]) {
            return None;
        }
        let mut idx: Vec<usize> = (0..self.params.len()).collect();
        idx.sort_by(|&a, &b| self.params[a].total_cmp(&self.params[b]));
        Some(idx)
    }
}

/// How a fitted curve meets its data (`docs/theory/fitting.md#residuals`): the residual of
/// point `k` is the distance `|C(ū_k) − Q_k|` at its parameter.
#[derive(Debug, Clone, PartialEq)]
pub struct FitReport {
    /// `|C(ū_k) − Q_k|` for every data point, in data order.
    pub residuals: Vec<f64>,
    /// The largest residual.
    pub max_residual: f64,
    /// Index of the data point with the largest residual.
    pub max_index: usize,
    /// Root mean square of the residuals (unweighted).
    pub rms: f64,
    /// Weighted residual sum of squares `Σ w_k |C(ū_k) − Q_k|²`.
    pub weighted_rss: f64,
    /// The smoothing weight λ used, for penalised fits.
    pub lambda: Option<f64>,
    /// Number of control points.
    pub n_ctrl: usize,
}

impl FitReport {
    /// The report of any `curve` against `data` (residuals at the data parameters).
    ///
    /// # Errors
    /// [`Error::Dimension`] if the curve's dimension is not the data's;
    /// [`Error::ParameterOutOfDomain`] for a data parameter outside the curve's domain.
    pub fn of(curve: &BSplineCurve, data: &FitData<'_>) -> Result<Self> {
        if curve.dim() != data.points.dim() {
            return Err(Error::Dimension {
                what: "curve for a fit report (the data's dimension)".into(),
                expected: data.points.dim(),
                got: curve.dim(),
            });
        }
        check_in_domain(data.params, curve.domain())?;
        Ok(Self::new(curve, data, None))
    }

    /// The report of `curve` against `data`.
    pub(crate) fn new(curve: &BSplineCurve, data: &FitData<'_>, lambda: Option<f64>) -> Self {
        let dim = data.points.dim();
        let ctrl = curve.control_points().as_slice();
        let p = curve.degree();
        let mut residuals = vec![0.0; data.len()];
        // parameters were checked against the domain by every fitting method
        for_each_row(
            curve.knots(),
            p,
            data.params,
            0..data.len(),
            |_| 1.0,
            |k, span, nb| {
                let cs = &ctrl[(span - p) * dim..(span + 1) * dim];
                let q = data.points.point(k);
                let mut r2 = 0.0;
                for (d, &qd) in q.iter().enumerate() {
                    // C_d(ū_k) in a register
                    let mut v = 0.0;
                    for (j, &b) in nb.iter().enumerate() {
                        v += b * cs[j * dim + d];
                    }
                    r2 += (v - qd) * (v - qd);
                }
                residuals[k] = r2.sqrt();
            },
        );
        let (mut max_residual, mut max_index, mut sum2, mut weighted_rss) = (0.0, 0, 0.0, 0.0);
        for (k, &r) in residuals.iter().enumerate() {
            if r > max_residual {
                (max_residual, max_index) = (r, k);
            }
            sum2 += r * r;
            weighted_rss += data.weight(k) * r * r;
        }
        FitReport {
            rms: (sum2 / residuals.len() as f64).sqrt(),
            residuals,
            max_residual,
            max_index,
            weighted_rss,
            lambda,
            n_ctrl: curve.control_points().len(),
        }
    }
}

/// A fitted curve with its report.
#[derive(Debug, Clone, PartialEq)]
pub struct CurveFit {
    /// The fitted curve.
    pub curve: BSplineCurve,
    /// How it meets the data.
    pub report: FitReport,
}

/// Checks that every parameter lies in `[a, b]`.
///
/// # Errors
/// [`Error::ParameterOutOfDomain`] for the first parameter outside.
pub(crate) fn check_in_domain(params: &[f64], (a, b): (f64, f64)) -> Result<()> {
    match params.iter().find(|&&t| !(t >= a && t <= b)) {
        Some(&t) => Err(Error::ParameterOutOfDomain { t, min: a, max: b }),
        None => Ok(()),
    }
}
