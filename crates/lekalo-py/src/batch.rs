//! The batch API: many small curves in one call, as flat arrays plus offsets (ragged).
//!
//! Curves are stored as `knots` (all knot vectors end to end) with `knot_offsets`, and
//! `control` `(total, dim)` with `control_offsets`; curve `i` owns
//! `knots[knot_offsets[i]:knot_offsets[i + 1]]` and likewise for the control points. No Python
//! object is made per curve. The curves are processed in parallel on the rayon pool, each
//! independently of the others, and gathered in input order, so the numbers do not depend on
//! the thread count.
//!
//! Adding an operation (a fit, a query) is one call of [`curves_from_ragged`] with a closure
//! that maps one curve's points to a `BSplineCurve`.

use std::collections::HashMap;
use std::sync::{Arc, Mutex, OnceLock};

use lekalo::{BSplineCurve, CurveInterpolation, PointsRef, MAX_SCALARS};
use numpy::{PyArray1, PyReadonlyArray1, PyUntypedArray, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use rayon::prelude::*;

use crate::convert::IntArg;
use crate::convert::{array, floats};
use crate::error::bad;
use crate::interp::{end_arg, knots_arg, parametrization_arg};

/// Runs `f` on a pool of `threads` workers (kept for reuse), or on the global pool. A count
/// above the machine's processors is lowered to them: the work is computation, so more
/// workers would only wait, and `threads=2**40` would start threads until the machine stops
/// answering (and keep one pool per distinct count).
pub(crate) fn on_pool<R: Send>(
    threads: Option<usize>,
    f: impl FnOnce() -> R + Send,
) -> PyResult<R> {
    let Some(n) = threads else { return Ok(f()) };
    if n == 0 {
        return Err(bad("threads: must be at least 1".into()));
    }
    let n = n.min(std::thread::available_parallelism().map_or(1, std::num::NonZeroUsize::get));
    static POOLS: OnceLock<Mutex<HashMap<usize, Arc<rayon::ThreadPool>>>> = OnceLock::new();
    let pool = {
        let mut pools = POOLS
            .get_or_init(|| Mutex::new(HashMap::new()))
            .lock()
            .map_err(|_| bad("threads: the pool registry is poisoned".into()))?;
        match pools.get(&n) {
            Some(p) => Arc::clone(p),
            None => {
                let p = Arc::new(
                    rayon::ThreadPoolBuilder::new()
                        .num_threads(n)
                        .build()
                        .map_err(|e| bad(format!("threads: cannot start {n} threads: {e}")))?,
                );
                pools.insert(n, Arc::clone(&p));
                p
            }
        }
    };
    Ok(pool.install(f))
}

/// Offsets: a 1-D integer array (or sequence), starting at 0, non-decreasing, ending at `total`.
pub(crate) fn offsets_arg(
    obj: &Bound<'_, PyAny>,
    what: &str,
    total: usize,
) -> PyResult<Vec<usize>> {
    let v: Vec<i64> = if let Ok(a) = obj.extract::<PyReadonlyArray1<'_, i64>>() {
        a.as_slice()
            .map(<[i64]>::to_vec)
            .unwrap_or_else(|_| a.as_array().iter().copied().collect())
    } else if let Ok(a) = obj.cast::<PyUntypedArray>() {
        // an int64 array of another shape fails the extraction above too: say which is wrong
        if a.ndim() != 1 {
            return Err(bad(format!(
                "{what}: expected a 1-D array of offsets, got {} dimensions (shape {:?}); \
                 pass one offset per curve boundary, e.g. np.ravel({what})",
                a.ndim(),
                a.shape()
            )));
        }
        return Err(bad(format!(
            "{what}: dtype {} is not int64; convert with np.asarray({what}, dtype=np.int64)",
            a.dtype()
        )));
    } else {
        obj.extract::<Vec<i64>>()
            .map_err(|_| bad(format!("{what}: expected a 1-D int64 array of offsets")))?
    };
    if v.is_empty() {
        return Err(bad(format!("{what}: empty; need at least [0]")));
    }
    if v[0] != 0 {
        return Err(bad(format!("{what}[0] is {}: offsets start at 0", v[0])));
    }
    let mut out = Vec::with_capacity(v.len());
    for (i, &o) in v.iter().enumerate() {
        let prev = out.last().copied().unwrap_or(0);
        let o = usize::try_from(o)
            .ok()
            .filter(|&o| o >= prev)
            .ok_or_else(|| {
                bad(format!(
                    "{what}[{i}] is {o}: offsets must be non-decreasing (after {prev})"
                ))
            })?;
        out.push(o);
    }
    let last = out[out.len() - 1];
    if last != total {
        return Err(bad(format!(
            "{what}: the last offset is {last}, but the data hold {total} rows"
        )));
    }
    Ok(out)
}

/// Curves, concatenated: knots, knot offsets, control `(total, dim)`, control offsets.
pub(crate) struct Ragged {
    pub(crate) knots: Vec<f64>,
    pub(crate) knot_offsets: Vec<i64>,
    pub(crate) control: Vec<f64>,
    pub(crate) control_offsets: Vec<i64>,
    pub(crate) dim: usize,
}

/// Builds one curve per ragged group of points with `make`, in parallel, and concatenates the
/// results in input order. A failing curve fails the call with its index in the message.
pub(crate) fn curves_from_ragged<F>(
    points: PointsRef<'_>,
    offsets: &[usize],
    make: F,
) -> Result<Ragged, String>
where
    F: Fn(PointsRef<'_>) -> lekalo::Result<BSplineCurve> + Sync,
{
    let dim = points.dim();
    let data = points.as_slice();
    let curves: Vec<lekalo::Result<BSplineCurve>> = (0..offsets.len() - 1)
        .into_par_iter()
        .map(|i| {
            let part = &data[offsets[i] * dim..offsets[i + 1] * dim];
            make(PointsRef::from_flat(dim, part)?)
        })
        .collect();
    let mut r = Ragged {
        knots: Vec::new(),
        knot_offsets: vec![0],
        control: Vec::new(),
        control_offsets: vec![0],
        dim,
    };
    for (i, c) in curves.into_iter().enumerate() {
        let c =
            c.map_err(|e| format!("curve {i} (rows {}..{}): {e}", offsets[i], offsets[i + 1]))?;
        r.knots.extend_from_slice(c.knots().as_slice());
        r.control.extend_from_slice(c.control_points().as_slice());
        r.knot_offsets.push(len_i64(r.knots.len()));
        r.control_offsets.push(len_i64(r.control.len() / dim));
    }
    Ok(r)
}

fn len_i64(n: usize) -> i64 {
    // lengths are bounded by MAX_SCALARS (2^31), far below i64::MAX
    i64::try_from(n).unwrap_or(i64::MAX)
}

/// The result dictionary `{"degree", "knots", "knot_offsets", "control", "control_offsets"}`.
pub(crate) fn ragged_dict<'py>(
    py: Python<'py>,
    degree: usize,
    r: Ragged,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    let n_ctrl = r.control.len() / r.dim;
    d.set_item("degree", degree)?;
    d.set_item("knots", PyArray1::from_vec(py, r.knots))?;
    d.set_item("knot_offsets", PyArray1::from_vec(py, r.knot_offsets))?;
    d.set_item("control", array(py, r.control, &[n_ctrl, r.dim])?)?;
    d.set_item("control_offsets", PyArray1::from_vec(py, r.control_offsets))?;
    Ok(d)
}

/// Interpolates one curve through each group of points: `points` `(total, dim)` (or
/// `(total,)`), `offsets` `(n_curves + 1,)` int64 with `points[offsets[i]:offsets[i + 1]]` the
/// points of curve `i`. Options as in `interpolate`. Returns the curves as a dict of flat
/// arrays: `degree`, `knots`, `knot_offsets`, `control` `(total, dim)`, `control_offsets`.
/// `threads` runs the batch on a pool of that many workers (default: all processors, or
/// `RAYON_NUM_THREADS`; more than the processors are lowered to them); the result is the same
/// for every thread count.
#[pyfunction]
#[pyo3(signature = (points, offsets, degree = IntArg::of(3), *, parametrization = None, knots = "auto",
                    end = "free", threads = None), text_signature = "(points, offsets, degree=3, *, parametrization=None, knots=\"auto\", end=\"free\", threads=None)")]
#[allow(clippy::too_many_arguments)]
pub(crate) fn interpolate_batch<'py>(
    py: Python<'py>,
    points: &Bound<'py, PyAny>,
    offsets: &Bound<'py, PyAny>,
    degree: IntArg,
    parametrization: Option<&Bound<'py, PyAny>>,
    knots: &str,
    end: &str,
    threads: Option<IntArg>,
) -> PyResult<Bound<'py, PyDict>> {
    let threads = threads.map(|n| n.count("threads")).transpose()?;
    let degree = degree.count("degree")?;
    let mut ci = CurveInterpolation::new(degree)
        .knot_placement(knots_arg(knots)?)
        .end_condition(end_arg(end, None, None)?);
    if let Some(p) = parametrization {
        ci = ci.parametrization(parametrization_arg(p)?);
    }
    let pa = floats(points, "points")?;
    let pts = pa.points("points")?;
    let offs = offsets_arg(offsets, "offsets", pts.len())?;
    let r = py
        .detach(|| {
            on_pool(threads, || {
                curves_from_ragged(pts, &offs, |p| ci.interpolate(p))
            })
        })?
        .map_err(bad)?;
    ragged_dict(py, degree, r)
}

/// Evaluates many B-spline curves (the ragged form that `interpolate_batch` returns) at many
/// parameters: `t` flat with `t_offsets` (`t[t_offsets[i]:t_offsets[i + 1]]` for curve `i`).
/// Returns `(len(t), dim)` points, in parallel, independent of the thread count.
#[pyfunction]
#[pyo3(signature = (degree, knots, knot_offsets, control, control_offsets, t, t_offsets, *, threads = None))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn evaluate_batch<'py>(
    py: Python<'py>,
    degree: IntArg,
    knots: &Bound<'py, PyAny>,
    knot_offsets: &Bound<'py, PyAny>,
    control: &Bound<'py, PyAny>,
    control_offsets: &Bound<'py, PyAny>,
    t: &Bound<'py, PyAny>,
    t_offsets: &Bound<'py, PyAny>,
    threads: Option<IntArg>,
) -> PyResult<Bound<'py, PyAny>> {
    let threads = threads.map(|n| n.count("threads")).transpose()?;
    let degree = degree.count("degree")?;
    let ka = floats(knots, "knots")?;
    let k = ka.vector("knots")?;
    let ca = floats(control, "control")?;
    let c = ca.points("control")?;
    let ta = floats(t, "t")?;
    let ts = ta.vector("t")?;
    let ko = offsets_arg(knot_offsets, "knot_offsets", k.len())?;
    let co = offsets_arg(control_offsets, "control_offsets", c.len())?;
    let to = offsets_arg(t_offsets, "t_offsets", ts.len())?;
    if ko.len() != co.len() || ko.len() != to.len() {
        return Err(bad(format!(
            "knot_offsets, control_offsets and t_offsets must describe the same number of curves (got {}, {}, {})",
            ko.len() - 1,
            co.len() - 1,
            to.len() - 1
        )));
    }
    let dim = c.dim();
    if ts.len().saturating_mul(dim) > MAX_SCALARS {
        return Err(bad(format!(
            "t: {} parameters of dimension {dim} exceed the size limit {MAX_SCALARS}",
            ts.len()
        )));
    }
    let mut out = vec![0.0; ts.len() * dim];
    let cd = c.as_slice();
    let res: Result<(), String> = py.detach(|| {
        on_pool(threads, || {
            // split the output by curve, then evaluate the curves in parallel
            let mut parts: Vec<(usize, &mut [f64])> = Vec::with_capacity(to.len() - 1);
            let mut rest: &mut [f64] = &mut out;
            for i in 0..to.len() - 1 {
                let (head, tail) = rest.split_at_mut((to[i + 1] - to[i]) * dim);
                parts.push((i, head));
                rest = tail;
            }
            parts.into_par_iter().try_for_each(|(i, o)| {
                let curve = BSplineCurve::new(
                    degree,
                    k[ko[i]..ko[i + 1]].to_vec(),
                    lekalo::Points::from_flat(dim, cd[co[i] * dim..co[i + 1] * dim].to_vec())
                        .map_err(|e| format!("curve {i}: {e}"))?,
                )
                .map_err(|e| format!("curve {i}: {e}"))?;
                curve
                    .evaluator()
                    .eval_batch(&ts[to[i]..to[i + 1]], o)
                    .map_err(|e| format!("curve {i}: {e}"))
            })
        })
        .map_err(|e| e.to_string())?
    });
    res.map_err(bad)?;
    array(py, out, &[ts.len(), dim])
}
