//! Piecewise polynomials in pp-form, the spaces `P_{k,ξ,ν}` and quasi-interpolation
//! (document 003, docs/theory/pp.md).

use lekalo::pp::Solution;
use lekalo::{PiecewisePolynomial, PpSpace, Tau, TauRule};
use lekalo_io::Shape;
use pyo3::prelude::*;
use pyo3::types::PyTuple;

use crate::convert::{array, check_size, filled, floats, vec1, vec_array};
use crate::convert::{out_shape, reduce};
use crate::curves::PyBSplineCurve;
use crate::error::{bad, io_err, lib_err};
use crate::words::word;

/// A `rule` argument: the name of a τ rule, or explicit τ values (one per B-spline, each in
/// its support `[x_i, x_{i+k}]`; docs/theory/pp.md#explicit-tau-values).
enum TauArg {
    Rule(TauRule),
    Values(Vec<f64>),
}

impl TauArg {
    /// Reads the argument; absent, the default rule (document 003's first knot after `x_i`).
    fn read(obj: Option<&Bound<'_, PyAny>>) -> PyResult<Self> {
        let Some(obj) = obj else {
            return Ok(Self::Rule(TauRule::FirstKnotAfter));
        };
        if let Ok(s) = obj.extract::<String>() {
            return word(&lekalo::vocabulary::TAU_RULE, "rule", &s).map(Self::Rule);
        }
        Ok(Self::Values(vec1(obj, "rule")?))
    }

    /// The library's view of the choice.
    fn tau(&self) -> Tau<'_> {
        match self {
            Self::Rule(r) => Tau::Rule(*r),
            Self::Values(v) => Tau::Values(v),
        }
    }
}

/// A piecewise polynomial: on piece `j`, `f(x) = Σ_r c[j, r] (x − ξ_j)^r` (local power
/// coefficients about the left breakpoint; right-continuous, the last piece closed).
///
/// `coefficients` has shape `(pieces, order, dim)`. SciPy's `PPoly` stores the same numbers
/// highest power first, `c[order − 1 − r, j]`: `lekalo.from_scipy` / `to_scipy` convert.
///
/// >>> import lekalo
/// >>> f = lekalo.PiecewisePolynomial([-1, 0, 1], [[[1], [-1]], [[0], [1]]])  # |x|
/// >>> f(-0.5)
/// array([0.5])
#[pyclass(module = "lekalo", name = "PiecewisePolynomial", frozen, eq)]
#[derive(PartialEq)]
pub(crate) struct PyPiecewisePolynomial {
    pub(crate) inner: PiecewisePolynomial,
}

#[pymethods]
impl PyPiecewisePolynomial {
    #[new]
    fn new(breakpoints: &Bound<'_, PyAny>, coefficients: &Bound<'_, PyAny>) -> PyResult<Self> {
        let x = vec1(breakpoints, "breakpoints")?;
        let c = floats(coefficients, "coefficients")?;
        let s = c.shape();
        if s.len() != 3 {
            return Err(bad(format!(
                "coefficients: expected a 3-D array (pieces, order, dim), got shape {s:?}"
            )));
        }
        if s[0] + 1 != x.len() {
            return Err(bad(format!(
                "coefficients: {} pieces need {} breakpoints, got {}",
                s[0],
                s[0] + 1,
                x.len()
            )));
        }
        let p = PiecewisePolynomial::new(x, s[1], s[2], c.data().to_vec()).map_err(lib_err)?;
        Ok(Self { inner: p })
    }

    /// The breakpoints `ξ`.
    #[getter]
    fn breakpoints<'py>(&self, py: Python<'py>) -> Bound<'py, PyAny> {
        vec_array(py, self.inner.breakpoints())
    }

    /// The coefficients `(pieces, order, dim)`.
    #[getter]
    fn coefficients<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let p = &self.inner;
        array(
            py,
            p.coefficients().to_vec(),
            &[p.n_pieces(), p.order(), p.dim()],
        )
    }

    /// The order `k` (degree `< k`).
    #[getter]
    fn order(&self) -> usize {
        self.inner.order()
    }

    /// The dimension of the values.
    #[getter]
    fn dim(&self) -> usize {
        self.inner.dim()
    }

    /// The domain `(ξ_1, ξ_{l+1})`.
    #[getter]
    fn domain(&self) -> (f64, f64) {
        self.inner.domain()
    }

    /// Values at `x` (any shape): `x.shape + (dim,)`; `nu > 0` gives the `nu`-th derivative.
    #[pyo3(signature = (x, nu = 0))]
    fn __call__(&self, py: Python<'_>, x: &Bound<'_, PyAny>, nu: usize) -> PyResult<Py<PyAny>> {
        let xa = floats(x, "x")?;
        let xs = xa.data();
        let dim = self.inner.dim();
        check_size("x", &[xs.len(), dim])?;
        let out = filled(py, &out_shape(&xa, &[dim]), |out| {
            let d;
            let f = if nu == 0 {
                &self.inner
            } else {
                d = self.inner.derivative(nu);
                &d
            };
            xs.iter()
                .zip(out.chunks_exact_mut(dim))
                .try_for_each(|(&x, o)| f.eval_into(x, o))
        })?;
        Ok(out.unbind())
    }

    /// The `j`-th derivative as a piecewise polynomial.
    #[pyo3(signature = (j = 1))]
    fn derivative(&self, j: usize) -> Self {
        Self {
            inner: self.inner.derivative(j),
        }
    }

    /// The real solutions of `f(x) = y`, one float array per coordinate, increasing piece by
    /// piece (docs/theory/pp.md#roots): a piece identically equal to `y` appears as its left
    /// breakpoint followed by `nan` (SciPy's `PPoly.solve` convention); `discontinuity` reports
    /// breakpoints where `f − y` changes sign across a jump; `extrapolate` searches the first
    /// and last pieces' polynomials beyond the breakpoints.
    ///
    /// >>> import numpy as np, lekalo
    /// >>> f = lekalo.PiecewisePolynomial([0.0, 1.0, 2.0], np.array([[[-0.5], [1.0]], [[0.5], [-2.0]]]))
    /// >>> [r.tolist() for r in f.solve(0.0, extrapolate=False)]
    /// [[0.5, 1.25]]
    #[pyo3(signature = (y = 0.0, discontinuity = true, extrapolate = true))]
    fn solve<'py>(
        &self,
        py: Python<'py>,
        y: f64,
        discontinuity: bool,
        extrapolate: bool,
    ) -> Vec<Bound<'py, PyAny>> {
        let sols = py.detach(|| self.inner.solve(y, discontinuity, extrapolate));
        sols.iter()
            .map(|v| {
                let flat: Vec<f64> = v
                    .iter()
                    .flat_map(|s| match *s {
                        Solution::At(x) => vec![x],
                        Solution::Piece { start, .. } => vec![start, f64::NAN],
                    })
                    .collect();
                vec_array(py, &flat)
            })
            .collect()
    }

    /// The jump of the `j`-th derivative at interior breakpoint `i` (1-based as in the
    /// document: breakpoint `ξ_{i+1}`, see the library's `jump`).
    fn jump<'py>(&self, py: Python<'py>, i: usize, j: usize) -> PyResult<Bound<'py, PyAny>> {
        Ok(vec_array(py, &self.inner.jump(i, j).map_err(lib_err)?))
    }

    /// The B-spline form in `space` by the de Boor–Fix functionals at the points `τ` of
    /// `rule`: `'first-knot-after'` (default), `'left-end-of-support'`, `'midpoint'`, `'greville'`,
    /// `'first-interval-midpoint'` (docs/theory/pp.md#the-two-tau-rules), or an array of τ
    /// values, one per B-spline, each in its support.
    #[pyo3(signature = (space, rule = None))]
    fn to_bspline(
        &self,
        py: Python<'_>,
        space: &PyPpSpace,
        rule: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<PyBSplineCurve> {
        let r = TauArg::read(rule)?;
        let c = py
            .detach(|| self.inner.to_bspline(&space.inner, r.tau()))
            .map_err(lib_err)?;
        Ok(PyBSplineCurve::wrap(c))
    }

    /// The pp-form of a B-spline curve.
    #[staticmethod]
    fn from_bspline(py: Python<'_>, curve: &PyBSplineCurve) -> PyResult<Self> {
        let p = py
            .detach(|| PiecewisePolynomial::from_bspline(&curve.inner))
            .map_err(lib_err)?;
        Ok(Self { inner: p })
    }

    /// JSON text in the command-line tool's format.
    fn to_json(&self) -> String {
        Shape::Pp(self.inner.clone()).to_json_pretty()
    }

    /// Reads a piecewise polynomial from JSON text.
    #[staticmethod]
    fn from_json(text: &str) -> PyResult<Self> {
        match Shape::from_json_str(text, "json").map_err(io_err)? {
            Shape::Pp(p) => Ok(Self { inner: p }),
            other => Err(bad(format!(
                "expected a piecewise_polynomial, got {}",
                other.type_name()
            ))),
        }
    }

    fn __reduce__<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyTuple>> {
        reduce(py, self.to_json())
    }

    fn __repr__(&self) -> String {
        format!(
            "PiecewisePolynomial(pieces={}, order={}, dim={})",
            self.inner.n_pieces(),
            self.inner.order(),
            self.inner.dim()
        )
    }
}

// the pp-form of a B-spline curve is a method of `BSplineCurve` written here, beside the
// conversion back, so that the curve classes need not know the pp-form's class
#[pymethods]
impl PyBSplineCurve {
    /// The piecewise-polynomial (pp) form over the distinct knots of the domain.
    fn to_pp(&self, py: Python<'_>) -> PyResult<PyPiecewisePolynomial> {
        let p = py
            .detach(|| PiecewisePolynomial::from_bspline(&self.inner))
            .map_err(lib_err)?;
        Ok(PyPiecewisePolynomial { inner: p })
    }
}

/// The space `P_{k,ξ,ν}` of piecewise polynomials of order `k` on breakpoints `ξ` with
/// `ν_i` continuity conditions at interior breakpoint `i` (Curry–Schoenberg; document 003).
#[pyclass(module = "lekalo", name = "PpSpace", frozen, eq)]
#[derive(PartialEq)]
pub(crate) struct PyPpSpace {
    pub(crate) inner: PpSpace,
}

#[pymethods]
impl PyPpSpace {
    #[new]
    #[pyo3(signature = (breakpoints, order, continuity = None))]
    fn new(
        breakpoints: &Bound<'_, PyAny>,
        order: usize,
        continuity: Option<Vec<usize>>,
    ) -> PyResult<Self> {
        let x = vec1(breakpoints, "breakpoints")?;
        let s = match continuity {
            Some(nu) => PpSpace::new(&x, &nu, order),
            None => PpSpace::unconstrained(&x, order),
        }
        .map_err(lib_err)?;
        Ok(Self { inner: s })
    }

    /// The dimension of the space (the number of B-splines).
    #[getter]
    fn dimension(&self) -> usize {
        self.inner.dimension()
    }

    /// The order `k`.
    #[getter]
    fn order(&self) -> usize {
        self.inner.order()
    }

    /// The breakpoints.
    #[getter]
    fn breakpoints<'py>(&self, py: Python<'py>) -> Bound<'py, PyAny> {
        vec_array(py, self.inner.breakpoints())
    }

    /// The continuity conditions `ν`.
    #[getter]
    fn continuity(&self) -> Vec<usize> {
        self.inner.continuity().to_vec()
    }

    /// The Curry–Schoenberg knot vector of the space.
    #[getter]
    fn knots<'py>(&self, py: Python<'py>) -> Bound<'py, PyAny> {
        vec_array(py, self.inner.knots().as_slice())
    }

    /// Whether `f` lies in the space (jumps below `rtol` relative to the derivatives).
    #[pyo3(signature = (f, rtol = lekalo::DEFAULT_CONTINUITY_RTOL))]
    fn contains(&self, f: &PyPiecewisePolynomial, rtol: f64) -> bool {
        self.inner.contains(&f.inner, rtol)
    }

    /// The truncated power basis of the space as piecewise polynomials.
    fn truncated_power_basis(&self) -> Vec<PyPiecewisePolynomial> {
        self.inner
            .truncated_power_basis()
            .into_iter()
            .map(|p| PyPiecewisePolynomial { inner: p })
            .collect()
    }

    fn __reduce__<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyTuple>> {
        let cls = py.get_type::<Self>();
        let args = PyTuple::new(
            py,
            [
                self.breakpoints(py),
                self.inner.order().into_pyobject(py)?.into_any(),
                self.continuity().into_pyobject(py)?.into_any(),
            ],
        )?;
        PyTuple::new(py, [cls.into_any(), args.into_any()])
    }

    fn __repr__(&self) -> String {
        format!(
            "PpSpace(order={}, dimension={})",
            self.inner.order(),
            self.inner.dimension()
        )
    }
}

/// Quasi-interpolation (de Boor–Fix, document 003 §D.5): the B-spline in `space` whose
/// coefficients are the dual functionals applied to `f`, where `f(t, r)` returns the `r`-th
/// derivative of the function at `t`. `f` is Python code, so the GIL is held while it runs.
/// `rule` chooses the points `τ` as in `PiecewisePolynomial.to_bspline`: a rule's name or an
/// array of τ values.
#[pyfunction]
#[pyo3(signature = (space, f, rule = None))]
pub(crate) fn quasi_interpolate(
    space: &PyPpSpace,
    f: &Bound<'_, PyAny>,
    rule: Option<&Bound<'_, PyAny>>,
) -> PyResult<PyBSplineCurve> {
    let r = TauArg::read(rule)?;
    let mut failure: Option<PyErr> = None;
    let c = lekalo::quasi_interpolate(&space.inner, r.tau(), |t, k| {
        if failure.is_some() {
            return 0.0;
        }
        match f.call1((t, k)).and_then(|v| v.extract::<f64>()) {
            Ok(v) => v,
            Err(e) => {
                failure = Some(e);
                0.0
            }
        }
    });
    if let Some(e) = failure {
        return Err(e);
    }
    Ok(PyBSplineCurve::wrap(c.map_err(lib_err)?))
}
