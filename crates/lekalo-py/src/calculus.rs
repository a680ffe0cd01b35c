//! Calculus of B-spline curves for Python: antiderivatives, definite integrals and evaluation
//! continued beyond the domain (the library's `curve/integral.rs`,
//! `docs/theory/curves.md#antiderivatives-integrals-and-extrapolation`), as methods of
//! `BSplineCurve`.

use lekalo::BSplineCurve;
use pyo3::prelude::*;

use crate::convert::out_shape;
use crate::convert::{array, check_size, filled, floats};
use crate::curves::PyBSplineCurve;
use crate::error::lib_err;

#[pymethods]
impl PyBSplineCurve {
    /// The `n`-th antiderivative, degree `p + n` (de Boor ch. X; SciPy's `splantider`).
    #[pyo3(signature = (n = 1))]
    fn antiderivative(&self, py: Python<'_>, n: usize) -> PyResult<Self> {
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

    /// The `nu`-th derivative at `t` (`t.shape + (dim,)`), continued beyond the domain.
    #[pyo3(signature = (t, nu = 0))]
    fn eval_extrapolated<'py>(
        &self,
        py: Python<'py>,
        t: &Bound<'py, PyAny>,
        nu: usize,
    ) -> PyResult<Bound<'py, PyAny>> {
        eval_extrapolated(py, &self.inner, t, nu)
    }
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
