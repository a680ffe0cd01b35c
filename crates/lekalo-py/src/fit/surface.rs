//! Surface fits from Python (`docs/theory/fitting.md#surfaces`): least squares over a grid of
//! points and over scattered points.

use lekalo::fit::{
    constrained_surface_grid_least_squares, constrained_surface_scattered_least_squares,
    place_knots as lk_place_knots, surface_grid_least_squares_at, surface_grid_parameters,
    surface_scattered_least_squares,
};
use lekalo::KnotVector;
use pyo3::prelude::*;

use super::knot_vector;
use crate::convert::IntPair;
use crate::convert::{floats, grid_points, vec1, vec_array};
use crate::error::{bad, lib_err, named};
use crate::interp::parametrization_or_chord;
use crate::shape::SurfaceShapeArgs;
use crate::surfaces::PyBSplineSurface;

/// Least-squares surface over a grid of points `(nu, nv, dim)` with a net of `n_ctrl =
/// (ncu, ncv)` control points of degrees `degree = (p, q)` (P&T §9.4.3,
/// `docs/theory/fitting.md#surfaces`). The parameters of the grid rows and columns are those of
/// `parametrization` averaged over the grid lines, or given (`u`: `nu` numbers, `v`: `nv`); the
/// knots are placed over them for `n_ctrl`, or given (`tu`, `tv`, which then set the net's size).
/// A table of values `z(u, v)` (`dim = 1`, with its coordinates `u` and `v`) may keep shapes on
/// the whole domain or on boxes of it (`docs/theory/fitting.md#shape-constraints-of-surfaces`):
/// `increasing` / `decreasing` a direction `"u"` or `"v"`, `True` for both,
/// `(direction, (u0, u1), (v0, v1))` on a box, or a sequence of those; `min`, `max` a number
/// bounding the values everywhere, `(value, (u0, u1), (v0, v1))` on a box, or a list of boxed
/// bounds.
#[pyfunction]
#[pyo3(signature = (grid, n_ctrl = None, degree = IntPair::of(3, 3), *, parametrization = None, u = None, v = None, tu = None, tv = None, increasing = None, decreasing = None, min = None, max = None),
       text_signature = "(grid, n_ctrl=None, degree=(3, 3), *, parametrization=None, u=None, v=None, tu=None, tv=None, increasing=None, decreasing=None, min=None, max=None)")]
#[allow(clippy::too_many_arguments)]
pub(crate) fn fit_surface_grid(
    py: Python<'_>,
    grid: &Bound<'_, PyAny>,
    n_ctrl: Option<IntPair>,
    degree: IntPair,
    parametrization: Option<&Bound<'_, PyAny>>,
    u: Option<&Bound<'_, PyAny>>,
    v: Option<&Bound<'_, PyAny>>,
    tu: Option<&Bound<'_, PyAny>>,
    tv: Option<&Bound<'_, PyAny>>,
    increasing: Option<&Bound<'_, PyAny>>,
    decreasing: Option<&Bound<'_, PyAny>>,
    min: Option<&Bound<'_, PyAny>>,
    max: Option<&Bound<'_, PyAny>>,
) -> PyResult<PyBSplineSurface> {
    let shapes = SurfaceShapeArgs {
        increasing,
        decreasing,
        min,
        max,
    }
    .constraints()?;
    let n_ctrl = n_ctrl.map(|n| n.count("n_ctrl")).transpose()?;
    let degree = degree.count("degree")?;
    let m = parametrization_or_chord(parametrization)?;
    let ga = floats(grid, "grid")?;
    let (pts, (nu, nv)) = grid_points(&ga, "grid")?;
    let given_params = (
        u.map(|x| vec1(x, "u")).transpose()?,
        v.map(|x| vec1(x, "v")).transpose()?,
    );
    let given_knots = (
        tu.map(|t| KnotVector::new(vec1(t, "tu")?).map_err(|e| named("tu", &e)))
            .transpose()?,
        tv.map(|t| KnotVector::new(vec1(t, "tv")?).map_err(|e| named("tv", &e)))
            .transpose()?,
    );
    let need_count = |given: &Option<KnotVector>, name: &str| -> PyResult<()> {
        if given.is_none() && n_ctrl.is_none() {
            return Err(bad(format!(
                "n_ctrl: give the net's size (ncu, ncv), or the knots {name} of that direction"
            )));
        }
        Ok(())
    };
    need_count(&given_knots.0, "tu")?;
    need_count(&given_knots.1, "tv")?;
    if !shapes.is_empty() && (given_params.0.is_none() || given_params.1.is_none()) {
        return Err(bad(
            "increasing, decreasing, min, max: a shape is kept by a table z(u, v); give its \
             coordinates u= and v= (and a grid of shape (nu, nv, 1))"
                .into(),
        ));
    }
    let inner = py
        .detach(|| {
            let computed = match &given_params {
                (Some(_), Some(_)) => None,
                _ => Some(surface_grid_parameters(pts, (nu, nv), m)?),
            };
            let uu = given_params
                .0
                .as_deref()
                .unwrap_or_else(|| &computed.as_ref().expect("computed when not given").0);
            let vv = given_params
                .1
                .as_deref()
                .unwrap_or_else(|| &computed.as_ref().expect("computed when not given").1);
            let (ncu, ncv) = n_ctrl.unwrap_or((0, 0));
            let ku = match &given_knots.0 {
                Some(k) => k.clone(),
                None => lk_place_knots(uu, degree.0, ncu)?,
            };
            let kv = match &given_knots.1 {
                Some(k) => k.clone(),
                None => lk_place_knots(vv, degree.1, ncv)?,
            };
            if shapes.is_empty() {
                surface_grid_least_squares_at(pts, (nu, nv), degree, (uu, vv), (&ku, &kv))
            } else {
                constrained_surface_grid_least_squares(
                    pts,
                    (nu, nv),
                    degree,
                    (uu, vv),
                    (&ku, &kv),
                    &shapes,
                )
            }
        })
        .map_err(lib_err)?;
    Ok(PyBSplineSurface { inner })
}

/// Least squares over scattered data: rows `(u, v, z...)` of `data` (`(n, 2 + values)`, at
/// least one value) on the full knot vectors `tu`, `tv` with degrees `degree = (p, q)`, optional
/// weights and a second-difference `penalty` (SciPy's `LSQBivariateSpline(x, y, z, tx, ty,
/// bbox, kx=p, ky=q)` for `penalty = 0` is `tu` = `p + 1` copies of `bbox[0]`, `tx`, `p + 1`
/// copies of `bbox[1]`, and `tv` likewise;
/// `docs/theory/fitting.md#surfaces`). Returns `(surface, residuals, weighted_rss)`. Rows
/// `(u, v, z)` may keep shapes on the whole domain or on boxes as in [`fit_surface_grid`]: `increasing`,
/// `decreasing` (`"u"`, `"v"`, both, or `True`), `min`, `max`
/// (`docs/theory/fitting.md#shape-constraints-of-surfaces`).
#[pyfunction]
#[pyo3(signature = (data, tu, tv, degree = IntPair::of(3, 3), *, w = None, penalty = 0.0, increasing = None, decreasing = None, min = None, max = None),
       text_signature = "(data, tu, tv, degree=(3, 3), *, w=None, penalty=0.0, increasing=None, decreasing=None, min=None, max=None)")]
#[allow(clippy::too_many_arguments)]
pub(crate) fn fit_surface_scattered<'py>(
    py: Python<'py>,
    data: &Bound<'py, PyAny>,
    tu: &Bound<'py, PyAny>,
    tv: &Bound<'py, PyAny>,
    degree: IntPair,
    w: Option<&Bound<'py, PyAny>>,
    penalty: f64,
    increasing: Option<&Bound<'py, PyAny>>,
    decreasing: Option<&Bound<'py, PyAny>>,
    min: Option<&Bound<'py, PyAny>>,
    max: Option<&Bound<'py, PyAny>>,
) -> PyResult<(PyBSplineSurface, Bound<'py, PyAny>, f64)> {
    let shapes = SurfaceShapeArgs {
        increasing,
        decreasing,
        min,
        max,
    }
    .constraints()?;
    let degree = degree.count("degree")?;
    let da = floats(data, "data")?;
    let pts = da.points("data")?;
    let wa = w.map(|w| floats(w, "w")).transpose()?;
    let wv = wa.as_ref().map(|w| w.vector("w")).transpose()?;
    let (ku, kv) = (knot_vector(tu)?, knot_vector(tv)?);
    let f = py
        .detach(|| {
            if shapes.is_empty() {
                surface_scattered_least_squares(pts, wv, degree, (&ku, &kv), penalty)
            } else {
                constrained_surface_scattered_least_squares(
                    pts,
                    wv,
                    degree,
                    (&ku, &kv),
                    penalty,
                    &shapes,
                )
            }
        })
        .map_err(lib_err)?;
    Ok((
        PyBSplineSurface { inner: f.surface },
        vec_array(py, &f.residuals),
        f.weighted_rss,
    ))
}
