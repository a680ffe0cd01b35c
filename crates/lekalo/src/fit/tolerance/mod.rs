//! Fitting to a tolerance: a B-spline within `tol` of every point with few control points
//! (`docs/theory/fitting.md#tolerance`).
//!
//! | file | what it does |
//! |---|---|
//! | `mod.rs` | the options, the result and [`fit_tolerance`] |
//! | `refine.rs` | the rounds of knot insertion and removal (each removal a local least-squares refit), on a sample of the data first when the data are many |
//! | `deviation.rs` | the deviations of the points: at their parameters, by projection (Newton), and kept up to date through local changes of the curve |

mod deviation;
mod refine;
#[cfg(test)]
mod tests;

use deviation::{deviations_full_with_feet, smaller};
use refine::{fit_sample_first, refine, SAMPLE_ABOVE, SAMPLE_SIZE};

use crate::error::{readable, Error, Result};
use crate::fit::{FitData, FitReport};
use crate::interpolate::{parametrize, Parametrization};
use crate::numeric::progress::Progress;
use crate::points::PointsRef;
use crate::BSplineCurve;

/// How the deviation of a data point from the curve is measured.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Deviation {
    /// The distance to the curve: `min_u |C(u) − Q_k|`, by a closest-point projection (Newton's
    /// method on `(C(u) − Q_k)·C'(u) = 0` from the data parameter, kept in the domain).
    #[default]
    Distance,
    /// The distance at the data parameter, `|C(ū_k) − Q_k|` (larger or equal).
    Parameter,
}

/// Options of [`fit_tolerance`].
#[derive(Debug, Clone, PartialEq)]
pub struct ToleranceOptions {
    /// Degree of the curve.
    pub degree: usize,
    /// Largest accepted deviation, a distance in the data's units (`> 0`).
    pub tol: f64,
    /// How the deviation is measured.
    pub deviation: Deviation,
    /// Data parameters.
    pub parametrization: Parametrization,
}

impl ToleranceOptions {
    /// Degree and tolerance; distance deviation and chord-length parameters.
    #[must_use]
    pub fn new(degree: usize, tol: f64) -> Self {
        ToleranceOptions {
            degree,
            tol,
            deviation: Deviation::Distance,
            parametrization: Parametrization::ChordLength,
        }
    }
}

/// The result of [`fit_tolerance`].
#[derive(Debug, Clone, PartialEq)]
pub struct ToleranceFit {
    /// The curve; it starts at the first point and ends at the last.
    pub curve: BSplineCurve,
    /// The data parameters used.
    pub params: Vec<f64>,
    /// The curve parameter at which each point's deviation is measured: of its closest point
    /// found on the curve ([`Deviation::Distance`]), or its data parameter
    /// ([`Deviation::Parameter`]). The residuals at these parameters are the deviations, so a
    /// report of the fit at them (e.g. [`FitReport::of`](crate::fit::FitReport::of)) shows
    /// every residual within `tol`.
    pub closest_params: Vec<f64>,
    /// Deviation of every point, `|C(closest_params[k]) − Q_k|` (as measured by
    /// [`ToleranceOptions::deviation`]).
    pub deviations: Vec<f64>,
    /// The largest deviation (`≤ tol`).
    pub max_deviation: f64,
    /// Index of the point where it occurs.
    pub worst_index: usize,
    /// Curve parameter of the closest point to that data point (`closest_params[worst_index]`).
    pub worst_param: f64,
}

/// A B-spline of the requested degree within `tol` of every point, with few control points (the
/// operation of Open CASCADE's `GeomAPI_PointsToBSpline` and geomdl's `approximate_curve`).
///
/// 1. Parameters by [`ToleranceOptions::parametrization`]; start with a single Bezier piece.
/// 2. Least squares with both end points interpolated ([`least_squares`]); measure every
///    deviation; split every knot span holding a point with deviation `> tol` at its middle data
///    parameter; repeat. Each split keeps data in every span (Schoenberg–Whitney), and at worst
///    the knots reach the data parameters, where the fit interpolates.
/// 3. Remove knots while the bound holds: with `m` the largest deviation, every knot whose
///    removal moves the curve by at most `tol − m` is removed
///    ([`BSplineCurve::remove_all_removable_knots`], whose bound is exact), so by the triangle
///    inequality the deviation stays `≤ tol`; then each remaining interior knot is tried once
///    more by a local refit without it (six control points on either side of the
///    ones the knot touches are refitted to the data under them, the others kept), kept out
///    when the points under the changed part of the curve are still within `tol`. Outside that
///    part the curve is unchanged, so each trial costs the data near the knot, not all of it.
///
/// 4. Above 2^18 points, steps 1–3 run on a sample of about 2^17 of them (every `s`-th point and
///    the last); the sample's curve is measured against all points and returned when every one is
///    within `tol`; otherwise step 2 continues on all points from the sample's knots and step 3
///    tries the added knots and their neighbours (`docs/theory/fitting.md#tolerance`).
///
/// Deviation is the distance to the curve ([`Deviation::Distance`], a closest-point projection
/// per point) or at the data parameter ([`Deviation::Parameter`]). O(rounds·N·p²) plus the
/// projections; the rounds double the knots, so they are about `log₂` of the control points.
///
/// ```
/// use lekalo::fit::{fit_tolerance, ToleranceOptions};
/// use lekalo::PointsRef;
/// let q: Vec<f64> = (0..200).flat_map(|k| { let t = k as f64 / 199.0 * 3.0; [t, t.sin()] }).collect();
/// let fit = fit_tolerance(PointsRef::from_flat(2, &q)?, &ToleranceOptions::new(3, 1e-4))?;
/// assert!(fit.max_deviation <= 1e-4);
/// assert!(fit.curve.control_points().len() < 20);
/// # Ok::<(), lekalo::Error>(())
/// ```
///
/// # Errors
/// [`Error::NonPositiveTolerance`] for `tol ≤ 0` or NaN; [`Error::Degree`] for degree 0;
/// [`Error::TooFew`] for fewer than `degree + 1` points; the parametrisation's errors (e.g.
/// [`Error::CoincidentPoints`] for chord-length parameters of repeated points);
/// [`Error::IllConditioned`] if even interpolation misses `tol` (a tolerance below the data's
/// rounding).
pub fn fit_tolerance(points: PointsRef<'_>, opts: &ToleranceOptions) -> Result<ToleranceFit> {
    fit_tolerance_with_progress(points, opts, &Progress::new())
}

/// [`fit_tolerance`] reporting to `progress` after each round of knot insertion (`done` the
/// round, `total` one more: the rounds' number is not known ahead) and after each knot tried for
/// removal (`done` of `total` knots), and stopping with [`Error::Cancelled`] when its cancel flag
/// is set. The result is the same with or without the hook.
///
/// # Errors
/// As [`fit_tolerance`], and [`Error::Cancelled`].
pub fn fit_tolerance_with_progress(
    points: PointsRef<'_>,
    opts: &ToleranceOptions,
    progress: &Progress<'_>,
) -> Result<ToleranceFit> {
    let tol = opts.tol;
    if !(tol > 0.0 && tol.is_finite()) {
        return Err(Error::NonPositiveTolerance { value: tol });
    }
    let p = opts.degree;
    crate::error::check_degree_bound(p)?;
    if p == 0 {
        return Err(Error::Degree {
            degree: p,
            reason: "a tolerance fit needs degree ≥ 1".into(),
        });
    }
    if points.len() < p + 1 {
        return Err(Error::TooFew {
            what: "points for a tolerance fit (degree + 1)".into(),
            min: p + 1,
            got: points.len(),
        });
    }
    let params = parametrize(points, opts.parametrization)?;
    let (curve, dev, feet) = if points.len() > SAMPLE_ABOVE {
        fit_sample_first(points, &params, opts, progress, SAMPLE_SIZE)?
    } else {
        let (curve, dev, feet) = refine(points, &params, opts, progress, &[])?;
        // the distances of the final curve from every data parameter; the removal kept upper
        // bounds (distances to points of this same curve), so each point keeps the smaller
        if opts.deviation == Deviation::Distance {
            let fresh = deviations_full_with_feet(&curve, points, &params, opts.deviation, -1.0)?;
            let (dev, feet) = smaller((dev, feet), fresh);
            (curve, dev, feet)
        } else {
            (curve, dev, feet)
        }
    };
    // each deviation measured again on the whole curve at the parameter where it was found (the
    // removal measured some on a piece of the curve, equal to it up to rounding), as the report
    // of a fit measures residuals: the deviations are the residuals at `closest_params`, bit for
    // bit, and the bound below holds for what a report shows
    let closest_params: Vec<f64> = feet
        .iter()
        .zip(&params)
        .map(|(&f, &u)| if f.is_nan() { u } else { f })
        .collect();
    debug_assert_eq!(dev.len(), points.len(), "a deviation per point");
    let dev = FitReport::of(&curve, &FitData::new(points, &closest_params)?)?.residuals;
    let (mut worst_index, mut max_deviation) = (0, 0.0);
    for (i, &d) in dev.iter().enumerate() {
        if d > max_deviation {
            (worst_index, max_deviation) = (i, d);
        }
    }
    if max_deviation > tol || max_deviation.is_nan() {
        // every site carries a knot (interpolation) and rounding still exceeds tol
        return Err(Error::IllConditioned {
            reason: format!(
                "the closest fit found deviates by {} at point {worst_index}, more than the \
                 tolerance {}; raise the tolerance above the data's rounding",
                readable(&max_deviation),
                readable(&tol)
            ),
        });
    }
    let worst_param = closest_params[worst_index];
    Ok(ToleranceFit {
        curve,
        params,
        closest_params,
        deviations: dev,
        max_deviation,
        worst_index,
        worst_param,
    })
}
