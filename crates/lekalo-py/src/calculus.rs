//! Calculus of B-spline curves for Python: antiderivatives, definite integrals and evaluation
//! continued beyond the domain (the library's `curve/integral.rs`,
//! `docs/theory/curves.md#antiderivatives-integrals-and-extrapolation`), as methods of
//! `BSplineCurve`.

use lekalo::{BSplineCurve, Beyond};
use numpy::{PyArray1, PyArrayMethods, PyUntypedArrayMethods};
use pyo3::prelude::*;

use crate::convert::out_shape;
use crate::convert::IntArg;
use crate::convert::{array, check_size, filled, floats};
use crate::curves::{basis_kernel, PyBSplineCurve, PAR_MIN};
use crate::error::{bad, lib_err};

#[pymethods]
impl PyBSplineCurve {
    /// The `n`-th antiderivative, degree `p + n` (de Boor ch. X; SciPy's `splantider`).
    #[pyo3(signature = (n = IntArg::of(1)), text_signature = "($self, n=1)")]
    fn antiderivative(&self, py: Python<'_>, n: IntArg) -> PyResult<Self> {
        let n = n.count("n")?;
        antiderivative(py, &self.inner, n).map(Self::wrap)
    }

    /// `∫_a^b C(t) dt`, shape `(dim,)`; `extrapolate=True` continues the end polynomials.
    #[pyo3(signature = (a, b, extrapolate = false))]
    fn integrate<'py>(
        &self,
        py: Python<'py>,
        a: f64,
        b: f64,
        extrapolate: bool,
    ) -> PyResult<Bound<'py, PyAny>> {
        integrate(py, &self.inner, a, b, extrapolate)
    }

    /// The `nu`-th derivative at `t` (`t.shape + (dim,)`), anywhere on the real line, with
    /// the kept fast evaluator's basis kernel (`CurveEvaluator::eval_batch_beyond`; on the
    /// rayon pool for large batches): outside the domain the end polynomials continued (`extrapolate=True`)
    /// or NaN, NaN at NaN or infinite parameters. SciPy's `BSpline.__call__` in one pass.
    #[pyo3(signature = (t, nu = IntArg::of(0), extrapolate = true), text_signature = "($self, t, nu=0, extrapolate=True)")]
    fn eval_beyond<'py>(
        &self,
        py: Python<'py>,
        t: &Bound<'py, PyAny>,
        nu: IntArg,
        extrapolate: bool,
    ) -> PyResult<Bound<'py, PyAny>> {
        let nu = nu.count("nu")?;
        let dim = self.inner.dim();
        let ta = floats(t, "t")?;
        let ts = ta.data();
        check_size("t", &[ts.len(), dim])?;
        let beyond = if extrapolate {
            Beyond::Continue
        } else {
            Beyond::Nan
        };
        let shape = out_shape(&ta, &[dim]);
        if nu > self.inner.degree() {
            // zero inside, and where continued; NaN where SciPy gives NaN
            let (lo, hi) = self.inner.domain();
            return filled(py, &shape, |buf| {
                for (&x, o) in ts.iter().zip(buf.chunks_exact_mut(dim.max(1))) {
                    let defined = x.is_finite() && (extrapolate || (lo <= x && x <= hi));
                    o.fill(if defined { 0.0 } else { f64::NAN });
                }
                Ok(())
            });
        }
        let derived;
        let curve = if nu == 0 {
            &self.inner
        } else {
            let mut d = self.inner.derivative().map_err(lib_err)?;
            for _ in 1..nu {
                d = d.derivative().map_err(lib_err)?;
            }
            derived = d;
            &derived
        };
        if ts.len() < 3 * curve.control_points().len() {
            // fewer points than it takes to pay for an evaluator (its tables cost about three
            // points' evaluations a piece): the reference path, point by point
            let (lo, hi) = curve.domain();
            if ts
                .iter()
                .all(|&x| x.is_finite() && (extrapolate || (lo <= x && x <= hi)))
            {
                // every point defined: one pass, its span search walking on from the last span
                return filled(py, &shape, |buf| curve.eval_batch_extrapolated(ts, buf));
            }
            return filled(py, &shape, |buf| {
                for (&x, o) in ts.iter().zip(buf.chunks_exact_mut(dim)) {
                    if x.is_finite() && (extrapolate || (lo <= x && x <= hi)) {
                        curve.eval_batch_extrapolated(&[x], o)?;
                    } else {
                        o.fill(f64::NAN);
                    }
                }
                Ok(())
            });
        }
        let kept;
        let ev = if nu == 0 {
            self.basis_evaluator()
        } else {
            kept = basis_kernel(curve);
            &kept
        };
        filled(py, &shape, |buf| {
            if ts.len() >= PAR_MIN {
                ev.par_eval_batch_beyond(ts, beyond, buf)
            } else {
                ev.eval_batch_beyond(ts, beyond, buf)
            }
        })
    }

    /// The `nu`-th derivative at `t` (`t.shape + (dim,)`), continued beyond the domain.
    #[pyo3(signature = (t, nu = IntArg::of(0)), text_signature = "($self, t, nu=0)")]
    fn eval_extrapolated<'py>(
        &self,
        py: Python<'py>,
        t: &Bound<'py, PyAny>,
        nu: IntArg,
    ) -> PyResult<Bound<'py, PyAny>> {
        let nu = nu.count("nu")?;
        eval_extrapolated(py, &self.inner, t, nu)
    }
}

/// The value at the number `x` of the scalar spline on the knots `t`, degree `k`, coefficients
/// `c` (1-D float64 arrays, read in place): `lekalo::bspline_value_by`, no curve
/// built. The end polynomials are continued outside the domain (`extrapolate=True`), or NaN is
/// given; NaN at a NaN or infinite `x`. The scalar call of SciPy's `BSpline` and `splev`.
#[pyfunction]
#[pyo3(signature = (t, k, c, x, extrapolate = true))]
pub(crate) fn bspline_value(
    t: &Bound<'_, PyAny>,
    k: IntArg,
    c: &Bound<'_, PyAny>,
    x: f64,
    extrapolate: bool,
) -> PyResult<f64> {
    let k = k.count("k")?;
    let beyond = if extrapolate {
        Beyond::Continue
    } else {
        Beyond::Nan
    };
    let t = vector_1d(t, "t")?;
    let c = vector_1d(c, "c")?;
    // the few numbers the evaluation needs, read in place (no copy, no borrow of the arrays)
    let read = |a: &Bound<'_, PyArray1<f64>>, i: usize| a.get_owned(i).unwrap_or(f64::NAN);
    lekalo::bspline_value_by(
        t.len(),
        |i| read(t, i),
        k,
        c.len(),
        |i| read(c, i),
        x,
        beyond,
    )
    .map_err(lib_err)
}

/// A 1-D float64 array, or the error naming `what` and the fix.
fn vector_1d<'a, 'py>(
    obj: &'a Bound<'py, PyAny>,
    what: &str,
) -> PyResult<&'a Bound<'py, PyArray1<f64>>> {
    obj.cast::<PyArray1<f64>>().map_err(|_| {
        bad(format!(
            "{what}: expected a 1-D float64 array; convert with np.asarray({what}, dtype=np.float64)"
        ))
    })
}

/// The `n`-th antiderivative (degree `p + n`, vanishing at the first knot).
fn antiderivative(py: Python<'_>, c: &BSplineCurve, n: usize) -> PyResult<BSplineCurve> {
    py.detach(|| c.antiderivative(n)).map_err(lib_err)
}

/// `∫_a^b C(t) dt` as a `(dim,)` array; with `extrapolate`, the end polynomials continue the
/// curve beyond its domain, without it a limit outside the domain raises `lekalo.Error`.
fn integrate<'py>(
    py: Python<'py>,
    c: &BSplineCurve,
    a: f64,
    b: f64,
    extrapolate: bool,
) -> PyResult<Bound<'py, PyAny>> {
    let v = py
        .detach(|| {
            if extrapolate {
                c.integral_extrapolated(a, b)
            } else {
                c.integral(a, b)
            }
        })
        .map_err(lib_err)?;
    let dim = v.len();
    array(py, v, &[dim])
}

/// The `nu`-th derivative at `t` (any shape, result `t.shape + (dim,)`), the end polynomials
/// continuing the curve beyond its domain; orders above the degree give zeros.
fn eval_extrapolated<'py>(
    py: Python<'py>,
    c: &BSplineCurve,
    t: &Bound<'py, PyAny>,
    nu: usize,
) -> PyResult<Bound<'py, PyAny>> {
    let dim = c.dim();
    let ta = floats(t, "t")?;
    let ts = ta.data();
    check_size("t", &[ts.len(), dim])?;
    let curve = if nu == 0 {
        None
    } else if nu > c.degree() {
        return filled(py, &out_shape(&ta, &[dim]), |buf| {
            buf.fill(0.0);
            Ok(())
        });
    } else {
        let mut d = c.derivative().map_err(lib_err)?;
        for _ in 1..nu {
            d = d.derivative().map_err(lib_err)?;
        }
        Some(d)
    };
    let curve = curve.as_ref().unwrap_or(c);
    filled(py, &out_shape(&ta, &[dim]), |buf| {
        curve.eval_batch_extrapolated(ts, buf)
    })
}
