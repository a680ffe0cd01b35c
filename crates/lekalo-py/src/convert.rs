//! NumPy arrays in and out: dtype, layout and shape checks with named errors, borrowing the
//! caller's memory when the layout allows.
//!
//! Inputs are float64 arrays (or sequences of numbers, converted once by NumPy). A C-contiguous
//! float64 array is borrowed, never copied; a Fortran-ordered one or any other strided view (a
//! column `y[:, 0]`, a stepped or reversed slice) is copied once into the point-major layout
//! the library works in. Integer and narrower float arrays (`int64`,
//! `float32`) are converted once to float64, as SciPy converts them; complex, object, string
//! and boolean arrays are refused, naming the dtype.

use lekalo::{Points, PointsRef, MAX_SCALARS};
use numpy::{
    PyArray1, PyArrayDescrMethods, PyArrayDyn, PyArrayMethods, PyReadonlyArrayDyn, PyUntypedArray,
    PyUntypedArrayMethods,
};
use pyo3::exceptions::PyMemoryError;
use pyo3::prelude::*;
use pyo3::types::{PyFloat, PyInt, PyTuple};

use crate::error::{bad, lib_err};

/// A float64 array argument: borrowed from NumPy when C-contiguous, else a C-order copy.
pub(crate) struct FloatArray<'py> {
    borrowed: Option<PyReadonlyArrayDyn<'py, f64>>,
    owned: Vec<f64>,
    shape: Vec<usize>,
    /// The argument was a Python number, not an array.
    pub(crate) scalar: bool,
}

impl FloatArray<'_> {
    /// The numbers in C (row-major) order.
    pub(crate) fn data(&self) -> &[f64] {
        match &self.borrowed {
            // a C-contiguous array always gives its slice
            Some(a) => a.as_slice().unwrap_or(&[]),
            None => &self.owned,
        }
    }

    /// The array's shape.
    pub(crate) fn shape(&self) -> &[usize] {
        &self.shape
    }

    /// The array as points: the last axis is the dimension (`(n, d)`), a 1-D array is `n`
    /// points of dimension 1.
    pub(crate) fn points(&self, what: &'static str) -> PyResult<PointsRef<'_>> {
        let dim = match self.shape.len() {
            1 => 1,
            2 => self.shape[1],
            n => {
                return Err(bad(format!(
                    "{what}: expected a 2-D array (points, dimension) or a 1-D array of values, got {n} dimensions"
                )))
            }
        };
        if dim == 0 {
            return Err(bad(format!("{what}: the dimension (last axis) is 0")));
        }
        PointsRef::from_flat(dim, self.data())
            .map_err(|e| match e {
                // the number named by the argument it was given as, not the library's view of it
                lekalo::Error::NonFinite { index, value, .. } => lekalo::Error::NonFinite {
                    what: what.into(),
                    index,
                    value,
                },
                e => e,
            })
            .map_err(lib_err)
    }

    /// [`FloatArray::points`] of a curve's data, which needs at least `needed` points: an array
    /// of fewer rows than that but enough columns, with at most 3 rows, is SciPy's list of
    /// coordinate arrays (`[x, y]`, shape `(dim, n)`), refused with the call that reads it.
    pub(crate) fn curve_points(
        &self,
        what: &'static str,
        needed: usize,
    ) -> PyResult<PointsRef<'_>> {
        if let [rows, cols] = self.shape[..] {
            if rows < needed && cols >= needed && rows <= 3 {
                return Err(bad(format!(
                    "{what}: shape ({rows}, {cols}) reads as {rows} points of dimension {cols}, \
                     fewer than the {needed} needed; lekalo takes points as rows, shape \
                     (n, dim): for SciPy's coordinate arrays [x, y] pass np.column_stack([x, y]) \
                     (or use lekalo.scipy, which takes SciPy's form)"
                )));
            }
        }
        self.points(what)
    }

    /// The array as a 1-D list of numbers, its finiteness left to the library call that
    /// takes it (one that checks every number it reads, as its documentation says), so that the
    /// data are read once.
    pub(crate) fn vector_for_checking_call(&self, what: &str) -> PyResult<&[f64]> {
        if self.shape.len() != 1 {
            return Err(bad(format!(
                "{what}: expected a 1-D array, got shape {:?}",
                self.shape
            )));
        }
        Ok(self.data())
    }

    /// The array as a 1-D list of numbers, checked finite.
    pub(crate) fn vector(&self, what: &str) -> PyResult<&[f64]> {
        if self.shape.len() != 1 {
            return Err(bad(format!(
                "{what}: expected a 1-D array, got shape {:?}",
                self.shape
            )));
        }
        finite(self.data(), what)?;
        Ok(self.data())
    }
}

/// A grid of points `(nu, nv, dim)` (the last axis is the dimension): the points in grid order
/// and `(nu, nv)`.
pub(crate) fn grid_points<'a>(
    a: &'a FloatArray<'_>,
    what: &str,
) -> PyResult<(PointsRef<'a>, (usize, usize))> {
    let s = a.shape();
    if s.len() != 3 {
        return Err(bad(format!(
            "{what}: expected a 3-D array (nu, nv, dim), got shape {s:?}"
        )));
    }
    let p = PointsRef::from_flat(s[2], a.data()).map_err(lib_err)?;
    Ok((p, (s[0], s[1])))
}

/// Surface parameters from two arguments `u`, `v` of one shape (arrays or numbers): the pairs
/// `(u, v)` in C order, and `u`'s array, whose shape the result takes.
pub(crate) fn uv_args<'py>(
    u: &Bound<'py, PyAny>,
    v: &Bound<'py, PyAny>,
) -> PyResult<(FloatArray<'py>, Vec<[f64; 2]>)> {
    let (ua, va) = (floats(u, "u")?, floats(v, "v")?);
    if ua.shape() != va.shape() {
        return Err(bad(format!(
            "u and v: shapes differ ({:?} and {:?}); pass arrays of one shape (np.meshgrid for a tensor grid)",
            ua.shape(),
            va.shape()
        )));
    }
    let pairs = ua.data().iter().zip(va.data()).map(|(&a, &b)| [a, b]);
    let pairs = pairs.collect();
    Ok((ua, pairs))
}

/// Refuses NaN and infinity with the index of the first offender.
pub(crate) fn finite(data: &[f64], what: &str) -> PyResult<()> {
    match data.iter().position(|v| !v.is_finite()) {
        Some(i) => Err(bad(format!(
            "{what}[{i}] is {}: every number must be finite (no NaN or infinity)",
            data[i]
        ))),
        None => Ok(()),
    }
}

/// Reads a float64 argument. `what` names it in errors.
pub(crate) fn floats<'py>(obj: &Bound<'py, PyAny>, what: &str) -> PyResult<FloatArray<'py>> {
    if let Ok(a) = obj.cast::<PyArrayDyn<f64>>() {
        let shape = a.shape().to_vec();
        let ro = a.try_readonly().map_err(|e| {
            bad(format!(
                "{what}: the array is being written elsewhere ({e}); pass a copy"
            ))
        })?;
        if a.is_c_contiguous() {
            return Ok(FloatArray {
                borrowed: Some(ro),
                owned: Vec::new(),
                shape,
                scalar: false,
            });
        }
        // Fortran order or a strided view (a column `y[:, 0]`, a reversed or stepped slice):
        // one copy in C order, the library's point-major layout, as NumPy's own functions
        // copy what they cannot read in place. A view can be far larger than the memory behind
        // it (`np.broadcast_to(0.0, (2000,) * 3)` is 8 bytes for 6.4e10 bytes of values): the
        // copy is checked against the size limit and reserved fallibly, so that it raises
        // instead of aborting the interpreter
        let owned = c_order_copy(&ro, what)?;
        return Ok(FloatArray {
            borrowed: None,
            owned,
            shape,
            scalar: false,
        });
    }
    if let Ok(a) = obj.cast::<PyUntypedArray>() {
        let dtype = a.dtype();
        // integers and narrower floats are real numbers: converted once, as SciPy does
        if !matches!(dtype.kind(), b'i' | b'u' | b'f') {
            return Err(bad(format!(
                "{what}: dtype {dtype} is not a real number type (integers and floats are \
                 read); pass real coordinates, e.g. np.asarray({what}, dtype=np.float64)"
            )));
        }
        let arr = obj
            .py()
            .import("numpy")?
            .call_method1("asarray", (obj, "float64"))
            .map_err(|e| {
                bad(format!(
                    "{what}: dtype {dtype} cannot be read as float64 ({e})"
                ))
            })?;
        return floats(&arr, what);
    }
    if obj.is_instance_of::<PyFloat>() || obj.is_instance_of::<PyInt>() {
        let v: f64 = obj.extract()?;
        return Ok(FloatArray {
            borrowed: None,
            owned: vec![v],
            shape: Vec::new(),
            scalar: true,
        });
    }
    let np = obj.py().import("numpy")?;
    let arr = np.call_method1("asarray", (obj, "float64")).map_err(|e| {
        bad(format!(
            "{what}: expected a float64 NumPy array or a sequence of numbers ({e})"
        ))
    })?;
    floats(&arr, what)
}

/// The values of the strided array `a` in C order, refused above [`MAX_SCALARS`] (`InputError`)
/// or when the memory cannot be reserved (`MemoryError`), before anything is copied.
fn c_order_copy(a: &PyReadonlyArrayDyn<'_, f64>, what: &str) -> PyResult<Vec<f64>> {
    let view = a.as_array();
    let n = view.len();
    if n > MAX_SCALARS {
        return Err(bad(format!(
            "{what}: an array of shape {:?} that is not C-contiguous is copied to be read, and \
             its {n} values are above the size limit {MAX_SCALARS}; pass a smaller array",
            view.shape()
        )));
    }
    let mut owned = Vec::new();
    owned.try_reserve_exact(n).map_err(|_| {
        PyMemoryError::new_err(format!(
            "{what}: cannot reserve memory for a C-order copy of {n} values ({} bytes) of an \
             array of shape {:?} that is not C-contiguous; pass a smaller array",
            n.saturating_mul(8),
            view.shape()
        ))
    })?;
    owned.extend(view.iter().copied());
    Ok(owned)
}

/// Reads points `(n, d)` (or `(n,)` for dimension 1) into owned [`Points`].
pub(crate) fn owned_points(obj: &Bound<'_, PyAny>, what: &'static str) -> PyResult<Points> {
    let a = floats(obj, what)?;
    Ok(a.points(what)?.to_owned())
}

/// Reads a 1-D float vector into a `Vec`.
pub(crate) fn vec1(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<Vec<f64>> {
    Ok(floats(obj, what)?.vector(what)?.to_vec())
}

/// An integer argument (a degree), read without failing so that the function can say what
/// went wrong in its own words ([`IntArg::get`]): SciPy users pass arrays where lekalo takes
/// the degree (`BSpline(t, c, k)` against `BSplineCurve(k, t, c)`), which NumPy would report as
/// "only integer scalar arrays can be converted to a scalar index".
pub(crate) struct IntArg(Result<usize, String>);

impl IntArg {
    /// The default value `n`.
    pub(crate) const fn of(n: usize) -> Self {
        Self(Ok(n))
    }

    /// The integer, or `lekalo.Error` naming the argument, what was given and `hint` (the
    /// lekalo call, and SciPy's where they differ).
    pub(crate) fn get(&self, name: &str, hint: &str) -> PyResult<usize> {
        self.0.clone().map_err(|got| {
            bad(format!(
                "{name} must be a non-negative integer, got {got}; {hint}"
            ))
        })
    }

    /// The count, order or degree argument `name` (`nu`, `order`, `n`, `times`, `k`), or
    /// `lekalo.InputError` naming it and what is allowed: every such argument of the binding
    /// is read here, so that `-1` is refused in these words rather than as Python's
    /// "can't convert negative int to unsigned".
    pub(crate) fn count(&self, name: &str) -> PyResult<usize> {
        self.0.clone().map_err(|got| {
            bad(format!(
                "{name} must be a whole number 0, 1, 2, ..., got {got}"
            ))
        })
    }
}

/// A list of counts or orders `name` (`nu`, `continuity`), each read as [`IntArg::count`]
/// naming its index (`nu[0] must be a whole number …`), so that a negative or huge entry is
/// `lekalo.InputError` rather than Python's `OverflowError`.
pub(crate) fn counts(v: &[IntArg], name: &str) -> PyResult<Vec<usize>> {
    v.iter()
        .enumerate()
        .map(|(i, n)| n.count(&format!("{name}[{i}]")))
        .collect()
}

impl<'a, 'py> FromPyObject<'a, 'py> for IntArg {
    type Error = PyErr;

    fn extract(obj: Borrowed<'a, 'py, PyAny>) -> PyResult<Self> {
        if let Ok(n) = obj.extract::<usize>() {
            return Ok(Self(Ok(n)));
        }
        // a NumPy scalar such as np.int64(-1) has the shape (): it is shown as a number
        let array_shape = obj
            .getattr("shape")
            .ok()
            .filter(|s| s.len().is_ok_and(|n| n > 0));
        let got = if let Some(shape) = array_shape {
            format!("an array of shape {}", shape.str()?)
        } else if let Ok(n) = obj.len() {
            format!("a {} of {n} items", obj.get_type().name()?)
        } else {
            let r = obj.repr()?.to_string();
            r.chars().take(40).collect()
        };
        Ok(Self(Err(got)))
    }
}

/// A pair of counts (the degrees `(3, 3)` of a surface, its control net `(nu, nv)`), read as
/// [`IntArg`] is: [`IntPair::count`] names the argument when it is not two whole numbers.
pub(crate) struct IntPair(Result<(usize, usize), String>);

impl IntPair {
    /// The default value `(a, b)`.
    pub(crate) const fn of(a: usize, b: usize) -> Self {
        Self(Ok((a, b)))
    }

    /// The pair, or `lekalo.InputError` naming the argument `name` and what is allowed.
    pub(crate) fn count(&self, name: &str) -> PyResult<(usize, usize)> {
        self.0.clone().map_err(|got| {
            bad(format!(
                "{name} must be a pair of whole numbers 0, 1, 2, ... (for u and v), got {got}"
            ))
        })
    }
}

impl<'a, 'py> FromPyObject<'a, 'py> for IntPair {
    type Error = PyErr;

    fn extract(obj: Borrowed<'a, 'py, PyAny>) -> PyResult<Self> {
        if let Ok(pair) = obj.extract::<(usize, usize)>() {
            return Ok(Self(Ok(pair)));
        }
        let r = obj.repr()?.to_string();
        Ok(Self(Err(r.chars().take(40).collect())))
    }
}

/// Refuses outputs past the library's size limit before allocating them.
pub(crate) fn check_size(what: &str, counts: &[usize]) -> PyResult<usize> {
    let mut n: usize = 1;
    for &c in counts {
        n = n.saturating_mul(c);
    }
    if n > MAX_SCALARS {
        // the library's message, prefixed with the argument (not the Python error's repr,
        // which would repeat the class name inside the message)
        let e = lekalo::Error::TooLarge {
            what: "output".into(),
            size: n,
            max: MAX_SCALARS,
        };
        return Err(bad(format!("{what}: {e}")));
    }
    Ok(n)
}

/// A caller's output array `out` of exactly `shape`, float64 and C-contiguous, borrowed for
/// writing (NumPy's `out=`): results go straight into it, with no allocation. An `out` that is
/// also an input is refused by the borrow check.
pub(crate) fn out_array<'py>(
    out: &Bound<'py, PyAny>,
    shape: &[usize],
) -> PyResult<numpy::PyReadwriteArrayDyn<'py, f64>> {
    let a = out
        .cast::<PyArrayDyn<f64>>()
        .map_err(|_| bad("out: expected a float64 NumPy array (np.empty(shape))".into()))?;
    if a.shape() != shape {
        return Err(bad(format!(
            "out: expected shape {shape:?}, got {:?}",
            a.shape()
        )));
    }
    if !a.is_c_contiguous() {
        return Err(bad("out: the array must be C-contiguous".into()));
    }
    a.try_readwrite().map_err(|e| {
        bad(format!(
            "out: the array is in use elsewhere, or is also an input ({e}); pass another array"
        ))
    })
}

/// Results of at least this many numbers (256 KiB) are allocated by `numpy.empty`, smaller ones
/// by the C API's zeros (which saves a Python call).
const EMPTY_MIN: usize = 1 << 15;

/// A new float64 array of `shape`, owned by NumPy from the start and written in place by `fill`
/// (the whole array in C order) with the GIL released; `fill` must write every number. A large
/// result comes from `numpy.empty`, so memory about to be overwritten is not first swept with
/// zeros (a block the allocator reuses is not cleared at all; fresh memory costs its page
/// faults only, on huge pages from 4 MiB, which NumPy asks for), and nothing is copied after.
pub(crate) fn filled<'py, F>(
    py: Python<'py>,
    shape: &[usize],
    fill: F,
) -> PyResult<Bound<'py, PyAny>>
where
    F: FnOnce(&mut [f64]) -> lekalo::Result<()> + Send,
{
    let arr = new_array(py, shape)?;
    {
        let mut rw = arr.readwrite();
        let buf = rw.as_slice_mut().map_err(|e| bad(format!("result: {e}")))?;
        py.detach(|| fill(buf)).map_err(lib_err)?;
    }
    Ok(arr.into_any())
}

/// [`filled`] for two results written by one call (a spline's knots and coefficients): both
/// arrays allocated as [`filled`]'s, then `fill` with the GIL released.
pub(crate) fn filled_pair<'py, F>(
    py: Python<'py>,
    shapes: [&[usize]; 2],
    fill: F,
) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>)>
where
    F: FnOnce(&mut [f64], &mut [f64]) -> lekalo::Result<()> + Send,
{
    let (a, b) = (new_array(py, shapes[0])?, new_array(py, shapes[1])?);
    {
        let (mut wa, mut wb) = (a.readwrite(), b.readwrite());
        let sa = wa.as_slice_mut().map_err(|e| bad(format!("result: {e}")))?;
        let sb = wb.as_slice_mut().map_err(|e| bad(format!("result: {e}")))?;
        py.detach(|| fill(sa, sb)).map_err(lib_err)?;
    }
    Ok((a.into_any(), b.into_any()))
}

/// A new C-ordered float64 array of `shape` for a result: `numpy.empty` from [`EMPTY_MIN`]
/// numbers on (not swept with zeros), the C API's zeros below.
fn new_array<'py>(py: Python<'py>, shape: &[usize]) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
    let n = shape.iter().product::<usize>();
    Ok(if n >= EMPTY_MIN {
        let empty = py.import("numpy")?.getattr("empty")?;
        empty
            .call1((PyTuple::new(py, shape)?,))?
            .cast_into::<PyArrayDyn<f64>>()?
    } else {
        PyArrayDyn::<f64>::zeros(py, shape, false)
    })
}

/// A NumPy array of the given shape over `data` (moved, not copied).
pub(crate) fn array<'py>(
    py: Python<'py>,
    data: Vec<f64>,
    shape: &[usize],
) -> PyResult<Bound<'py, PyAny>> {
    let a = PyArray1::from_vec(py, data);
    if shape.len() == 1 {
        return Ok(a.into_any());
    }
    Ok(a.reshape(shape.to_vec())?.into_any())
}

/// Points as an `(n, d)` array.
pub(crate) fn points_array<'py>(py: Python<'py>, p: &Points) -> PyResult<Bound<'py, PyAny>> {
    array(py, p.as_slice().to_vec(), &[p.len(), p.dim()])
}

/// Moves points into an `(n, d)` array.
pub(crate) fn points_into_array(py: Python<'_>, p: Points) -> PyResult<Bound<'_, PyAny>> {
    let (n, d) = (p.len(), p.dim());
    array(py, p.into_vec(), &[n, d])
}

/// A 1-D array copy of a slice.
pub(crate) fn vec_array<'py>(py: Python<'py>, v: &[f64]) -> Bound<'py, PyAny> {
    PyArray1::from_slice(py, v).into_any()
}

/// `t.shape + tail` for an evaluation result.
pub(crate) fn out_shape(t: &FloatArray<'_>, tail: &[usize]) -> Vec<usize> {
    let mut s = t.shape().to_vec();
    s.extend_from_slice(tail);
    s
}

/// `__reduce__` for pickling: `(lekalo._lekalo.from_json, (json,))`. The JSON holds every
/// number with its shortest round-trip text, so the object comes back bit for bit.
pub(crate) fn reduce<'py>(py: Python<'py>, json: String) -> PyResult<Bound<'py, PyTuple>> {
    let f = py.import("lekalo._lekalo")?.getattr("from_json")?;
    PyTuple::new(py, [f.into_any(), PyTuple::new(py, [json])?.into_any()])
}

pub(crate) fn from_json_shape(text: &str) -> PyResult<lekalo_io::Shape> {
    lekalo_io::Shape::from_json_str(text, "json").map_err(crate::error::io_err)
}
