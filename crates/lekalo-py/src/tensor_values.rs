//! Values of a tensor-product B-spline given as SciPy's arrays `(t, c, k)`, evaluated in place:
//! the knots and coefficients are borrowed from NumPy for the call (`lekalo::TensorBSplineRef`,
//! checked in `O(Σ|t_a|)`, the coefficients never copied), so that an object of `lekalo.scipy`
//! keeps no second copy and sees its arrays changed in place. Points beyond the domain follow
//! one of the `Beyond` rules: `"continue"` (the end spans' polynomials), `"clamp"` (FITPACK:
//! the coordinate taken at the domain's end, an infinite one too) or `"nan"`; a NaN coordinate
//! gives NaN, and so does an infinite one but under `"clamp"`.
//! The value at one point (`tensor_value`, the scalar calls) reads only the numbers it needs
//! (`lekalo::tensor::tensor_value_by`), with no check of the whole arrays.

use lekalo::tensor::{tensor_value_by, Beyond};
use lekalo::TensorBSplineRef;
use numpy::{PyArray1, PyArrayMethods, PyUntypedArrayMethods};
use pyo3::prelude::*;

use crate::convert::{check_size, counts, filled, floats, FloatArray, IntArg};
use crate::error::{bad, lib_err, named};
use crate::tensor::degrees_arg;

/// The knot arrays of `t`, one 1-D float64 array per variable, borrowed.
fn knot_arrays<'py>(t: &Bound<'py, PyAny>) -> PyResult<Vec<FloatArray<'py>>> {
    let items: Vec<Bound<'py, PyAny>> = t
        .try_iter()
        .map_err(|_| bad("t: expected a sequence of 1-D arrays, one per variable".into()))?
        .collect::<PyResult<_>>()?;
    items
        .iter()
        .enumerate()
        .map(|(a, x)| {
            let what = format!("t[{a}]");
            let arr = floats(x, &what)?;
            if arr.shape().len() != 1 {
                return Err(bad(format!(
                    "{what}: expected a 1-D array of knots, got shape {:?}",
                    arr.shape()
                )));
            }
            Ok(arr)
        })
        .collect()
}

/// The borrowed spline of `(t, c, k)` (`c` of shape `(n_1, …, n_N, *trailing)`), with the
/// trailing axes; every axis of `c` checked against the knots and degrees.
fn spline_ref<'a>(
    knots: &'a [FloatArray<'_>],
    degrees: &'a [usize],
    c: &'a FloatArray<'_>,
) -> PyResult<(TensorBSplineRef<'a>, Vec<usize>)> {
    let n = knots.len();
    let shape = c.shape();
    if shape.len() < n {
        return Err(bad(format!(
            "c: shape {shape:?} has fewer axes than the {n} variables; c has shape (n_1, …, n_N, *trailing)"
        )));
    }
    for (a, (kv, &p)) in knots.iter().zip(degrees).enumerate() {
        let want = kv.data().len().saturating_sub(p + 1);
        if shape[a] != want {
            return Err(bad(format!(
                "c: axis {a} has {} coefficients, but t[{a}] ({} knots) and k[{a}] = {p} give {want}",
                shape[a],
                kv.data().len()
            )));
        }
    }
    let trailing = shape[n..].to_vec();
    let dim: usize = trailing.iter().product();
    if dim == 0 {
        return Err(bad(format!(
            "c: a trailing axis of shape {shape:?} is empty"
        )));
    }
    let slices = knots.iter().map(FloatArray::data).collect();
    let s = TensorBSplineRef::new(degrees, slices, c.data(), dim).map_err(|e| {
        let what = match e {
            lekalo::Error::Degree { .. } => "k",
            lekalo::Error::LengthMismatch { .. } | lekalo::Error::TooLarge { .. } => "c",
            _ => "t",
        };
        named(what, &e)
    })?;
    Ok((s, trailing))
}

/// Derivative orders `nu` (one per variable; all zero is the values).
fn orders(nu: Option<Vec<IntArg>>, n: usize) -> PyResult<Option<Vec<usize>>> {
    match nu.map(|v| counts(&v, "nu")).transpose()? {
        Some(v) if v.len() != n => Err(bad(format!(
            "nu: {} orders for {n} variables; give one derivative order per variable",
            v.len()
        ))),
        Some(v) if v.iter().all(|&o| o == 0) => Ok(None),
        other => Ok(other),
    }
}

/// `tensor_values(t, c, k, x, nu=None, beyond="continue")`: the spline `(t, c, k)` (or its
/// partial derivative of orders `nu`) at the points `x` of shape `(..., N)`, shape
/// `(..., *trailing)`; `beyond` is `"continue"`, `"clamp"` or `"nan"` for a point outside the
/// domain (`TensorBSplineRef::par_eval_batch_beyond`), and a NaN coordinate gives NaN (an
/// infinite one too, but under `"clamp"`, which takes it at the domain's end). Nothing of `t`, `c` or `x` is copied.
#[pyfunction]
#[pyo3(signature = (t, c, k, x, nu = None, beyond = "continue"))]
pub(crate) fn tensor_values(
    py: Python<'_>,
    t: &Bound<'_, PyAny>,
    c: &Bound<'_, PyAny>,
    k: &Bound<'_, PyAny>,
    x: &Bound<'_, PyAny>,
    nu: Option<Vec<IntArg>>,
    beyond: &str,
) -> PyResult<Py<PyAny>> {
    let rule = beyond_arg(beyond)?;
    let knots = knot_arrays(t)?;
    let n = knots.len();
    let degrees = degrees_arg(k, n)?;
    let ca = floats(c, "c")?;
    let (s, trailing) = spline_ref(&knots, &degrees, &ca)?;
    let orders = orders(nu, n)?;
    let xa = floats(x, "x")?;
    let shape = xa.shape();
    if shape.last() != Some(&n) {
        return Err(bad(format!(
            "x: shape {shape:?}; the last axis must hold the {n} coordinates of a point"
        )));
    }
    let lead = &shape[..shape.len() - 1];
    check_size("x", &[lead.iter().product(), s.dim()])?;
    let out_shape = [lead, &trailing].concat();
    let xs = xa.data();
    let out = filled(py, &out_shape, |out| {
        s.par_eval_batch_beyond(xs, orders.as_deref(), rule, out)
    })?;
    Ok(out.unbind())
}

/// `tensor_grid_values(t, c, k, axes, nu=None, clamp=False)`: the spline `(t, c, k)` (or its
/// partial derivative of orders `nu`) on the grid `axes[0] × … × axes[N-1]` (each inside its
/// domain, or with `clamp` each parameter taken at the nearest end of its domain first, as
/// FITPACK's `bispev`), shape `(len(axes[0]), …, len(axes[N-1]), *trailing)`, by sum
/// factorisation (`TensorBSplineRef::eval_grid`). Nothing of `t` or `c` is copied.
#[pyfunction]
#[pyo3(signature = (t, c, k, axes, nu = None, clamp = false))]
pub(crate) fn tensor_grid_values(
    py: Python<'_>,
    t: &Bound<'_, PyAny>,
    c: &Bound<'_, PyAny>,
    k: &Bound<'_, PyAny>,
    axes: &Bound<'_, PyAny>,
    nu: Option<Vec<IntArg>>,
    clamp: bool,
) -> PyResult<Py<PyAny>> {
    let knots = knot_arrays(t)?;
    let n = knots.len();
    let degrees = degrees_arg(k, n)?;
    let ca = floats(c, "c")?;
    let (s, trailing) = spline_ref(&knots, &degrees, &ca)?;
    let orders = orders(nu, n)?;
    let lists: Vec<FloatArray<'_>> = axes
        .try_iter()
        .map_err(|_| bad("axes: expected a sequence of 1-D arrays, one per variable".into()))?
        .enumerate()
        .map(|(a, x)| floats(&x?, &format!("axes[{a}]")))
        .collect::<PyResult<_>>()?;
    if lists.len() != n {
        return Err(bad(format!(
            "axes: {} parameter lists for {n} variables; pass one 1-D array per variable",
            lists.len()
        )));
    }
    let lead: Vec<usize> = lists.iter().map(|l| l.data().len()).collect();
    check_size("axes", &[&lead[..], &[s.dim()]].concat())?;
    let clamped: Vec<Vec<f64>> = if clamp {
        lists
            .iter()
            .zip(s.domain())
            .map(|(l, (lo, hi))| l.data().iter().map(|t| t.clamp(lo, hi)).collect())
            .collect()
    } else {
        Vec::new()
    };
    let refs: Vec<&[f64]> = if clamp {
        clamped.iter().map(Vec::as_slice).collect()
    } else {
        lists.iter().map(FloatArray::data).collect()
    };
    let out = filled(py, &[&lead[..], &trailing].concat(), |out| {
        s.eval_grid(&refs, orders.as_deref(), out)
    })?;
    Ok(out.unbind())
}

/// The rule of `beyond` (`"continue"`, `"clamp"` or `"nan"`).
fn beyond_arg(beyond: &str) -> PyResult<Beyond> {
    match beyond {
        "continue" => Ok(Beyond::Continue),
        "clamp" => Ok(Beyond::Clamp),
        "nan" => Ok(Beyond::Nan),
        other => Err(bad(format!(
            "beyond: {other:?} is not one of continue, clamp, nan"
        ))),
    }
}

/// `tensor_value(t, c, k, x, beyond="continue")`: the scalar spline `(t, c, k)` at the one
/// point `x` (`N` numbers), as a float. `t` holds one 1-D float64 array per variable; `c` is a
/// 1-D float64 array whose first `Π_a n_a` numbers are the net in row-major order (SciPy's
/// `(n_1, …, n_N)` array flattened as a view, or FITPACK's flat, padded `c`); `beyond` as in
/// `tensor_values`. Only the `O(Σ_a log|t_a| + Π_a (k_a + 1))` numbers the value needs are read,
/// in place and without borrowing the arrays (`lekalo::tensor::tensor_value_by`): the knots are
/// not checked sorted, as SciPy does not check them at a call; unsorted knots give some number,
/// never a crash.
#[pyfunction]
#[pyo3(signature = (t, c, k, x, beyond = "continue"))]
pub(crate) fn tensor_value(
    t: &Bound<'_, PyAny>,
    c: &Bound<'_, PyAny>,
    k: &Bound<'_, PyAny>,
    x: Vec<f64>,
    beyond: &str,
) -> PyResult<f64> {
    let rule = beyond_arg(beyond)?;
    let knots = knot_vectors(t)?;
    let degrees = degrees_arg(k, knots.len())?;
    let c = flat_coefficients(c)?;
    value_at(&knots, &c, &degrees, &x, rule)
}

/// The knot vectors of `t`, one 1-D float64 array per variable, held (not borrowed).
fn knot_vectors<'py>(t: &Bound<'py, PyAny>) -> PyResult<Vec<Bound<'py, PyArray1<f64>>>> {
    t.try_iter()
        .map_err(|_| bad("t: expected a sequence of 1-D arrays, one per variable".into()))?
        .enumerate()
        .map(|(a, item)| {
            item?.cast_into::<PyArray1<f64>>().map_err(|_| {
                bad(format!(
                    "t[{a}]: expected a 1-D float64 array; convert with np.asarray(t[{a}], dtype=np.float64)"
                ))
            })
        })
        .collect()
}

/// The coefficients `c` as one 1-D float64 array, held (not borrowed).
fn flat_coefficients<'py>(c: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyArray1<f64>>> {
    c.cast::<PyArray1<f64>>().cloned().map_err(|_| {
        bad(
            "c: expected a 1-D float64 array; pass c.reshape(-1) of a C-contiguous float64 array"
                .into(),
        )
    })
}

/// The value of `tensor_value`: the few numbers the value needs, read in place (no copy, no
/// borrow of the arrays).
fn value_at(
    knots: &[Bound<'_, PyArray1<f64>>],
    c: &Bound<'_, PyArray1<f64>>,
    degrees: &[usize],
    x: &[f64],
    rule: Beyond,
) -> PyResult<f64> {
    let lens: Vec<usize> = knots.iter().map(|k| k.len()).collect();
    tensor_value_by(
        degrees,
        &lens,
        |a, i| knots[a].get_owned(i).unwrap_or(f64::NAN),
        c.len(),
        |f| c.get_owned(f).unwrap_or(f64::NAN),
        x,
        rule,
    )
    .map_err(lib_err)
}

/// `TensorValueAt(t, c, k)`: the scalar spline `(t, c, k)` of `tensor_value`, its arrays
/// checked for type and held once (not copied), so that a call at one point (`value`) only
/// converts the point: the scalar calls of `lekalo.scipy.NdBSpline`. The arrays are read in
/// place at every call, so changes made to them in place are seen.
#[pyclass(module = "lekalo._lekalo", name = "TensorValueAt", frozen)]
pub(crate) struct TensorValueAt {
    knots: Vec<Py<PyArray1<f64>>>,
    c: Py<PyArray1<f64>>,
    degrees: Vec<usize>,
}

#[pymethods]
impl TensorValueAt {
    #[new]
    fn new(t: &Bound<'_, PyAny>, c: &Bound<'_, PyAny>, k: &Bound<'_, PyAny>) -> PyResult<Self> {
        let knots = knot_vectors(t)?;
        let degrees = degrees_arg(k, knots.len())?;
        let c = flat_coefficients(c)?;
        Ok(TensorValueAt {
            knots: knots.into_iter().map(Bound::unbind).collect(),
            c: c.unbind(),
            degrees,
        })
    }

    /// The value at the point `x` (`N` numbers): the end polynomials continued beyond the box
    /// (`extrapolate`) or NaN, and NaN at a NaN or infinite coordinate, as `tensor_value`.
    #[pyo3(signature = (x, extrapolate = true))]
    fn value(&self, py: Python<'_>, x: Vec<f64>, extrapolate: bool) -> PyResult<f64> {
        let knots: Vec<Bound<'_, PyArray1<f64>>> =
            self.knots.iter().map(|k| k.bind(py).clone()).collect();
        let rule = if extrapolate {
            Beyond::Continue
        } else {
            Beyond::Nan
        };
        value_at(&knots, self.c.bind(py), &self.degrees, &x, rule)
    }

    /// Pickled by its constructor's arguments (the arrays it holds).
    #[allow(clippy::type_complexity)]
    fn __reduce__<'py>(
        &self,
        py: Python<'py>,
    ) -> (
        Bound<'py, PyAny>,
        (Vec<Py<PyArray1<f64>>>, Py<PyArray1<f64>>, Vec<usize>),
    ) {
        (
            py.get_type::<Self>().into_any(),
            (
                self.knots.iter().map(|k| k.clone_ref(py)).collect(),
                self.c.clone_ref(py),
                self.degrees.clone(),
            ),
        )
    }
}

/// Registers the in-place evaluation of `(t, c, k)` splines.
pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(tensor_value, m)?)?;
    m.add_function(wrap_pyfunction!(tensor_values, m)?)?;
    m.add_function(wrap_pyfunction!(tensor_grid_values, m)?)?;
    m.add_class::<TensorValueAt>()?;
    Ok(())
}
