//! Fits of bicubic splines on the sphere (`lekalo::fit::sphere_*`,
//! `docs/theory/sphere.md`): scattered data by least squares on given knots or by the smoothing
//! condition, and data on a grid with pole conditions. Each returns the spline as a
//! `TensorBSpline` in `(theta, phi)` of degrees `(3, 3)`; the arguments keep SciPy's names.

use lekalo::fit::{
    sphere_grid_smoothing, sphere_least_squares, sphere_smoothing, PoleCondition, SphereData,
    SphereFit, SphereGrid,
};
use lekalo::Progress;
use pyo3::prelude::*;

use crate::convert::floats;
use crate::error::{bad, lib_err};
use crate::tensor::PyTensorBSpline;

/// `(spline, fp, p, rank, limit)` of a fit on the sphere.
type Fit = (
    PyTensorBSpline,
    f64,
    Option<f64>,
    usize,
    Option<&'static str>,
);

fn out(f: SphereFit) -> Fit {
    (
        PyTensorBSpline::scalar(f.spline),
        f.fp,
        f.p,
        f.rank,
        f.limit,
    )
}

/// The weighted least-squares spline on the sphere of the values `r` at the colatitudes
/// `theta` (in `[0, pi]`) and longitudes `phi` (in `[0, 2 pi]`), with the interior knots `tt`
/// (in `(0, pi)`) and `tp` (in `(0, 2 pi)`), one value at each pole and continuous
/// derivatives across them (`sphere_least_squares`). Weights `w` multiply the residuals
/// (FITPACK's); `eps` is the rank threshold of FITPACK's minimal-norm solution. Returns
/// `(spline, fp, p, rank, limit)` with `p` and `limit` `None`.
#[pyfunction]
#[pyo3(signature = (theta, phi, r, tt, tp, *, w = None, eps = 1e-16))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn fit_sphere_least_squares(
    py: Python<'_>,
    theta: &Bound<'_, PyAny>,
    phi: &Bound<'_, PyAny>,
    r: &Bound<'_, PyAny>,
    tt: &Bound<'_, PyAny>,
    tp: &Bound<'_, PyAny>,
    w: Option<&Bound<'_, PyAny>>,
    eps: f64,
) -> PyResult<Fit> {
    let (ta, pa, ra) = (
        floats(theta, "theta")?,
        floats(phi, "phi")?,
        floats(r, "r")?,
    );
    let (tta, tpa) = (floats(tt, "tt")?, floats(tp, "tp")?);
    let wa = w.map(|w| floats(w, "w")).transpose()?;
    let wv = wa.as_ref().map(|w| w.vector("w")).transpose()?;
    let (tv, pv, rv) = (ta.vector("theta")?, pa.vector("phi")?, ra.vector("r")?);
    let (ttv, tpv) = (tta.vector("tt")?, tpa.vector("tp")?);
    py.detach(|| {
        let data = SphereData::new(tv, pv, rv, wv)?;
        sphere_least_squares(&data, ttv, tpv, eps)
    })
    .map(out)
    .map_err(lib_err)
}

/// The spline on the sphere with FITPACK's knots whose weighted residual sum of squares
/// `sum((w (r - s))**2)` is `s` (`sphere_smoothing`: the smoothest spline for which it is).
/// Returns `(spline, fp, p, rank, limit)`: `p` the weight of the smoothing (`None` for a
/// least-squares result), `limit` why the knot rounds stopped above `s` (`None`,
/// `"max-knots"`, `"too-many-unknowns"`, `"no-span"`).
#[pyfunction]
#[pyo3(signature = (theta, phi, r, s, *, w = None, eps = 1e-16))]
pub(crate) fn fit_sphere_smoothing(
    py: Python<'_>,
    theta: &Bound<'_, PyAny>,
    phi: &Bound<'_, PyAny>,
    r: &Bound<'_, PyAny>,
    s: f64,
    w: Option<&Bound<'_, PyAny>>,
    eps: f64,
) -> PyResult<Fit> {
    let (ta, pa, ra) = (
        floats(theta, "theta")?,
        floats(phi, "phi")?,
        floats(r, "r")?,
    );
    let wa = w.map(|w| floats(w, "w")).transpose()?;
    let wv = wa.as_ref().map(|w| w.vector("w")).transpose()?;
    let (tv, pv, rv) = (ta.vector("theta")?, pa.vector("phi")?, ra.vector("r")?);
    py.detach(|| {
        let data = SphereData::new(tv, pv, rv, wv)?;
        sphere_smoothing(&data, s, eps, &Progress::new())
    })
    .map(out)
    .map_err(lib_err)
}

/// The spline on the grid `u x v` of the sphere (colatitudes `u` in `(0, pi)`, longitudes `v`
/// from `v[0]` in `[-pi, pi)` over less than a period) of the values `r` (shape
/// `(len(u), len(v))`) whose residual sum of squares is `s` (`0`: interpolation), with the
/// pole conditions of SciPy's `RectSphereBivariateSpline`, each a pair for `theta = 0` and
/// `theta = pi`: `pole_values` (`None`: fitted), `pole_exact`, `pole_continuity`, `pole_flat`
/// (`sphere_grid_smoothing`). Returns `(spline, fp, p, rank, limit)`.
#[pyfunction]
#[pyo3(signature = (u, v, r, s = 0.0, *, pole_values = (None, None), pole_exact = (false, false),
    pole_continuity = (false, false), pole_flat = (false, false)),
    text_signature = "(u, v, r, s=0.0, *, pole_values=(None, None), pole_exact=(False, False), \
        pole_continuity=(False, False), pole_flat=(False, False))")]
#[allow(clippy::too_many_arguments)]
pub(crate) fn fit_sphere_grid(
    py: Python<'_>,
    u: &Bound<'_, PyAny>,
    v: &Bound<'_, PyAny>,
    r: &Bound<'_, PyAny>,
    s: f64,
    pole_values: (Option<f64>, Option<f64>),
    pole_exact: (bool, bool),
    pole_continuity: (bool, bool),
    pole_flat: (bool, bool),
) -> PyResult<Fit> {
    let (ua, va, ra) = (floats(u, "u")?, floats(v, "v")?, floats(r, "r")?);
    let (uv, vv) = (ua.vector("u")?, va.vector("v")?);
    // a grid of the right count in the wrong shape (`r.T`) was read row by row as if it were
    // `(len(u), len(v))`: a fit of other data, with success
    if ra.shape().len() > 1 && ra.shape() != [uv.len(), vv.len()] {
        return Err(bad(format!(
            "r has shape {:?}; it must hold one value per node of u × v, in the shape (len(u), \
             len(v)) = ({}, {}): one row per colatitude u",
            ra.shape(),
            uv.len(),
            vv.len()
        )));
    }
    let rv = ra.data();
    let pole = |value, exact, continuity, flat| PoleCondition {
        value,
        exact,
        continuity,
        flat,
    };
    let poles = [
        pole(pole_values.0, pole_exact.0, pole_continuity.0, pole_flat.0),
        pole(pole_values.1, pole_exact.1, pole_continuity.1, pole_flat.1),
    ];
    py.detach(|| {
        let grid = SphereGrid::new(uv, vv, rv)?;
        sphere_grid_smoothing(&grid, s, poles, &Progress::new())
    })
    .map(out)
    .map_err(lib_err)
}

pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(fit_sphere_least_squares, m)?)?;
    m.add_function(wrap_pyfunction!(fit_sphere_smoothing, m)?)?;
    m.add_function(wrap_pyfunction!(fit_sphere_grid, m)?)?;
    Ok(())
}
