//! Fitting (`docs/theory/fitting.md`): least squares on given knots, smoothing splines (λ given
//! or by GCV), the fewest knots within a residual `s` (FITPACK's `splrep`/`splprep` smoothing
//! condition), fitting to a distance tolerance, robust (IRLS) least squares, and surfaces.
//!
//! The SciPy-named functions (`make_lsq_spline`, `make_smoothing_spline`, `make_splrep`,
//! `make_splprep`) take SciPy's arguments and return the curve; the `fit_*` functions return
//! `(curve, report)` where the report is a dict of the library's `FitReport`. Every computation
//! runs with the GIL released.
//!
//! | file | what it does |
//! |---|---|
//! | `mod.rs` | the data and weights read once for every fit (and periodic data without its repeated row), the shape-constraint keywords, the report as a dict, [`register`] |
//! | `least_squares.rs` | `make_lsq_spline` (`make_lsq_spline_fp`: with FITPACK's `fp`), `fit_least_squares`, `fit_robust`, `fit_tolerance`, `place_knots` |
//! | `smoothing.rs` | `make_smoothing_spline`, `fit_smoothing`, `gcv_score`, `make_splrep`, `make_splprep`, `fit_smoothing_condition`, `generate_knots` |
//! | `surface.rs` | `fit_surface_grid`, `fit_surface_scattered` |
//! | `closed.rs` | `fit_periodic`, `fit_closed` |

mod closed;
mod least_squares;
mod smoothing;
mod surface;

use closed::{fit_closed, fit_periodic};
use least_squares::{
    fit_least_squares, fit_robust, fit_tolerance, make_lsq_spline, make_lsq_spline_fp, place_knots,
};
use smoothing::{
    fit_smoothing, fit_smoothing_condition, gcv_score, generate_knots, make_smoothing_spline,
    make_splprep, make_splrep,
};
use surface::{fit_surface_grid, fit_surface_scattered};

use lekalo::fit::{CurveFit, FitData, FitReport, ShapeConstraints};
use lekalo::{KnotVector, PointsRef};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::convert::{floats, vec1, vec_array, FloatArray};
use crate::curves::PyBSplineCurve;
use crate::error::{bad, lib_err};
use crate::shape::ShapeArgs;

/// How a weight argument enters the sum of squares.
#[derive(Clone, Copy)]
enum WeightsAre {
    /// The library's `Σ w_k |r_k|²` (and SciPy's `make_smoothing_spline`).
    Squared,
    /// SciPy's `make_lsq_spline` / `splrep` convention, `Σ (w_k |r_k|)²`: squared here.
    Linear,
}

/// Values `y` (`(n,)` or `(n, dim)`), parameters `x` (`(n,)`) and optional weights, read once.
struct Data<'py> {
    y: FloatArray<'py>,
    x: FloatArray<'py>,
    w: Option<Vec<f64>>,
}

/// Periodic data without its repeated last row: the rows, all the parameters, the weights.
type PeriodicRows<'a> = (PointsRef<'a>, &'a [f64], Option<&'a [f64]>);

impl<'py> Data<'py> {
    fn read(
        x: &Bound<'py, PyAny>,
        y: &Bound<'py, PyAny>,
        w: Option<&Bound<'py, PyAny>>,
        xname: &str,
        weights: WeightsAre,
    ) -> PyResult<Self> {
        Ok(Data {
            x: floats(x, xname)?,
            y: floats(y, "y")?,
            w: w.map(|w| weight_vec(w, weights)).transpose()?,
        })
    }

    /// Periodic data: the rows of `y` without the last, which repeats the first, all the
    /// parameters `x` (the last closes the period) and the weights of the rows kept.
    fn periodic(&self) -> PyResult<PeriodicRows<'_>> {
        let xs = self.x.vector("x")?;
        let ys = self.y.points("y")?;
        let n = periodic_rows(xs.len(), ys.len())?;
        let rows =
            PointsRef::from_flat(ys.dim(), &ys.as_slice()[..n * ys.dim()]).map_err(lib_err)?;
        let w = self.w.as_deref().map(|w| &w[..n.min(w.len())]);
        Ok((rows, xs, w))
    }

    /// The library's validated data (lengths, finiteness, weights ≥ 0). Lengths that differ
    /// are named by the arguments, as SciPy names them (`x` and `y`), not by the library's
    /// "data parameters".
    fn fit_data(&self, xname: &str) -> PyResult<FitData<'_>> {
        let d = FitData::new(self.y.points("y")?, self.x.vector(xname)?).map_err(|e| match e {
            lekalo::Error::LengthMismatch { expected, got, .. } => bad(format!(
                "{xname} and y differ in length: {xname} has {got} values, y has {expected} rows \
                 (one data point a row); give one {xname} per row of y"
            )),
            e => lib_err(e),
        })?;
        match &self.w {
            Some(w) => d.with_weights(w).map_err(lib_err),
            None => Ok(d),
        }
    }
}

/// The weights as the library takes them. Negative weights are passed on unsquared, so that the
/// library refuses them by name.
fn weight_vec(w: &Bound<'_, PyAny>, weights: WeightsAre) -> PyResult<Vec<f64>> {
    let mut v = vec1(w, "w")?;
    if let WeightsAre::Linear = weights {
        for x in v.iter_mut().filter(|x| **x >= 0.0) {
            *x *= *x;
        }
    }
    Ok(v)
}

/// A shape-constraint keyword argument of a fit (`None` when absent).
type ShapeKeyword<'a, 'py> = Option<&'a Bound<'py, PyAny>>;

/// The shape-constraint keyword arguments of a fit, `[increasing, decreasing, convex, concave,
/// min, max, through, slope_at, integral, periodic]`, read into the library's constraints
/// ([`ShapeArgs`]).
fn shape_constraints(args: [ShapeKeyword<'_, '_>; 10]) -> PyResult<ShapeConstraints> {
    let [increasing, decreasing, convex, concave, min, max, through, slope_at, integral, periodic] =
        args;
    ShapeArgs {
        increasing,
        decreasing,
        convex,
        concave,
        min,
        max,
        through,
        slope_at,
        integral,
        periodic,
    }
    .constraints()
}

/// The report of a fit as a dict: `residuals`, `max_residual`, `max_index`, `rms`,
/// `weighted_rss`, `lam` (the smoothing weight, `None` without one), `n_ctrl`.
fn report_dict<'py>(py: Python<'py>, r: &FitReport) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("residuals", vec_array(py, &r.residuals))?;
    d.set_item("max_residual", r.max_residual)?;
    d.set_item("max_index", r.max_index)?;
    d.set_item("rms", r.rms)?;
    d.set_item("weighted_rss", r.weighted_rss)?;
    d.set_item("lam", r.lambda)?;
    d.set_item("n_ctrl", r.n_ctrl)?;
    Ok(d)
}

/// `(curve, report)` of a curve fit.
fn with_report(py: Python<'_>, f: CurveFit) -> PyResult<(PyBSplineCurve, Bound<'_, PyDict>)> {
    let r = report_dict(py, &f.report)?;
    Ok((PyBSplineCurve::wrap(f.curve), r))
}

fn knot_vector(t: &Bound<'_, PyAny>) -> PyResult<KnotVector> {
    KnotVector::new(vec1(t, "t")?).map_err(lib_err)
}

/// The number of rows of periodic data without the last, which repeats the first.
fn periodic_rows(nx: usize, ny: usize) -> PyResult<usize> {
    if nx < 2 || ny != nx {
        return Err(bad(format!(
            "periodic data: x and y need the same number of rows, two or more (got {nx} and \
             {ny}); the last row repeats the first"
        )));
    }
    Ok(nx - 1)
}

/// Registers the fitting functions.
pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(make_lsq_spline, m)?)?;
    m.add_function(wrap_pyfunction!(make_lsq_spline_fp, m)?)?;
    m.add_function(wrap_pyfunction!(make_smoothing_spline, m)?)?;
    m.add_function(wrap_pyfunction!(make_splrep, m)?)?;
    m.add_function(wrap_pyfunction!(make_splprep, m)?)?;
    m.add_function(wrap_pyfunction!(fit_least_squares, m)?)?;
    m.add_function(wrap_pyfunction!(fit_smoothing, m)?)?;
    m.add_function(wrap_pyfunction!(fit_smoothing_condition, m)?)?;
    m.add_function(wrap_pyfunction!(generate_knots, m)?)?;
    m.add_function(wrap_pyfunction!(fit_tolerance, m)?)?;
    m.add_function(wrap_pyfunction!(fit_robust, m)?)?;
    m.add_function(wrap_pyfunction!(fit_periodic, m)?)?;
    m.add_function(wrap_pyfunction!(fit_closed, m)?)?;
    m.add_function(wrap_pyfunction!(gcv_score, m)?)?;
    m.add_function(wrap_pyfunction!(place_knots, m)?)?;
    m.add_function(wrap_pyfunction!(fit_surface_grid, m)?)?;
    m.add_function(wrap_pyfunction!(fit_surface_scattered, m)?)?;
    Ok(())
}
