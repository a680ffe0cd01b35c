//! Piecewise polynomials in pp-form, the spaces `P_{k,ξ,ν}` and quasi-interpolation
//! (document 003, docs/theory/pp.md).

use lekalo::pp::{BernsteinBasis, PieceBasis, PiecewiseRef, PowerBasis, Solution};
use lekalo::{Beyond, PiecewisePolynomial, PpSpace, Tau, TauRule};
use lekalo_io::Shape;
use pyo3::prelude::*;
use pyo3::types::PyTuple;

use crate::convert::{
    array, check_size, filled, floats, points_into_array, vec1, vec_array, FloatArray,
};
use crate::convert::{counts, out_shape, reduce, IntArg};
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

    /// The same function from pieces given on strictly decreasing breakpoints `x_0 > … > x_l`,
    /// piece `i` on `[x_{i+1}, x_i]` written about its right end `x_i` (coefficients `(pieces,
    /// order, dim)`, lowest power first; SciPy's `PPoly` with decreasing `x`). The result has
    /// the increasing breakpoints (`lekalo::PiecewisePolynomial::from_decreasing`, a Taylor
    /// shift of each piece).
    #[staticmethod]
    fn from_decreasing(
        py: Python<'_>,
        breakpoints: &Bound<'_, PyAny>,
        coefficients: &Bound<'_, PyAny>,
    ) -> PyResult<Self> {
        let x = vec1(breakpoints, "breakpoints")?;
        let c = floats(coefficients, "coefficients")?;
        let s = c.shape();
        if s.len() != 3 || s[0] + 1 != x.len() {
            return Err(bad(format!(
                "coefficients: expected shape (pieces, order, dim) with pieces = {} for {} breakpoints, got {s:?}",
                x.len().saturating_sub(1),
                x.len()
            )));
        }
        let data = c.data();
        let p = py
            .detach(|| PiecewisePolynomial::from_decreasing(&x, s[1], s[2], data))
            .map_err(lib_err)?;
        Ok(Self { inner: p })
    }

    /// `(breakpoints, coefficients)` on the breakpoints in decreasing order, each piece written
    /// about its right end (its left limits there), coefficients `(pieces, order, dim)`: the
    /// inverse of `from_decreasing`.
    fn to_decreasing<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyTuple>> {
        let p = &self.inner;
        let (x, c) = p.to_decreasing();
        let c = array(py, c, &[p.n_pieces(), p.order(), p.dim()])?;
        PyTuple::new(py, [vec_array(py, &x), c])
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
    #[pyo3(signature = (x, nu = IntArg::of(0)))]
    fn __call__(&self, py: Python<'_>, x: &Bound<'_, PyAny>, nu: IntArg) -> PyResult<Py<PyAny>> {
        let nu = nu.count("nu")?;
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

    /// The `nu`-th derivative at `x` (any shape, result `x.shape + (dim,)`), the end pieces
    /// continued beyond the breakpoints (SciPy's `PPoly` with `extrapolate=True`); Horner's
    /// rule on the pp-form (`lekalo::PiecewisePolynomial::eval_extrapolated_into`).
    #[pyo3(signature = (x, nu = IntArg::of(0)), text_signature = "($self, x, nu=0)")]
    fn eval_extrapolated<'py>(
        &self,
        py: Python<'py>,
        x: &Bound<'py, PyAny>,
        nu: IntArg,
    ) -> PyResult<Bound<'py, PyAny>> {
        let nu = nu.count("nu")?;
        let xa = floats(x, "x")?;
        let xs = xa.data();
        let dim = self.inner.dim();
        check_size("x", &[xs.len(), dim])?;
        filled(py, &out_shape(&xa, &[dim]), |out| {
            xs.iter()
                .zip(out.chunks_exact_mut(dim))
                .try_for_each(|(&x, o)| self.inner.eval_extrapolated_into(x, nu, o))
        })
    }

    /// The `n`-th antiderivative (order `k + n`, continuous), its derivatives of orders
    /// `0 … n − 1` zero at `anchor` (default: the first breakpoint); in pp-form, as SciPy's
    /// `PPoly.antiderivative` (`lekalo::PiecewisePolynomial::antiderivative`).
    #[pyo3(
        signature = (n = IntArg::of(1), anchor = None),
        text_signature = "($self, n=1, anchor=None)"
    )]
    fn antiderivative(&self, py: Python<'_>, n: IntArg, anchor: Option<f64>) -> PyResult<Self> {
        let n = n.count("n")?;
        let at = anchor.unwrap_or(self.inner.breakpoints()[0]);
        let p = py
            .detach(|| self.inner.antiderivative(n, at))
            .map_err(lib_err)?;
        Ok(Self { inner: p })
    }

    /// `∫_a^b f` as a `(dim,)` array, the end pieces continued beyond the breakpoints
    /// (`lekalo::PiecewisePolynomial::integral_extrapolated`; SciPy's `PPoly.integrate`).
    fn integral_extrapolated<'py>(
        &self,
        py: Python<'py>,
        a: f64,
        b: f64,
    ) -> PyResult<Bound<'py, PyAny>> {
        let v = py
            .detach(|| self.inner.integral_extrapolated(a, b))
            .map_err(lib_err)?;
        let dim = v.len();
        array(py, v, &[dim])
    }

    /// The `j`-th derivative as a piecewise polynomial.
    #[pyo3(signature = (j = IntArg::of(1)), text_signature = "($self, j=1)")]
    fn derivative(&self, j: IntArg) -> PyResult<Self> {
        Ok(Self {
            inner: self.inner.derivative(j.count("j")?),
        })
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
    fn jump<'py>(&self, py: Python<'py>, i: IntArg, j: IntArg) -> PyResult<Bound<'py, PyAny>> {
        let (i, j) = (i.count("i")?, j.count("j")?);
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
        order: IntArg,
        continuity: Option<Vec<IntArg>>,
    ) -> PyResult<Self> {
        let order = order.count("order")?;
        let continuity = continuity.map(|v| counts(&v, "continuity")).transpose()?;
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

/// The Bernstein coefficients on `[a, b]` of the polynomial of least degree with the
/// derivatives `at_a` at `a` and `at_b` at `b` (rows: value, first derivative, …; `(n, dim)` or
/// `(n,)`). Returns `(n_a + n_b, dim)` (`lekalo::hermite_bernstein`; SciPy's
/// `BPoly._construct_from_derivatives`).
///
/// >>> import lekalo
/// >>> lekalo.hermite_bernstein(0.0, 1.0, [2.0, 3.0], [1.0])
/// array([[2. ],
///        [3.5],
///        [1. ]])
#[pyfunction]
pub(crate) fn hermite_bernstein<'py>(
    py: Python<'py>,
    a: f64,
    b: f64,
    at_a: &Bound<'py, PyAny>,
    at_b: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyAny>> {
    let ya = floats(at_a, "at_a")?;
    let yb = floats(at_b, "at_b")?;
    let (ra, rb) = (ya.points("at_a")?, yb.points("at_b")?);
    let c = py
        .detach(|| lekalo::hermite_bernstein(a, b, ra, rb))
        .map_err(lib_err)?;
    points_into_array(py, c)
}

/// The piecewise polynomial on increasing `breakpoints` with the derivatives `derivatives[i]`
/// at breakpoint `i` (a list of arrays `(n_i, dim)` or `(n_i,)`: value, first derivative, …),
/// optionally of the degree `orders[i]` on piece `i`: a `BSplineCurve` whose breakpoints all
/// have multiplicity degree + 1, its control points the Bernstein coefficients piece after
/// piece (`lekalo::piecewise_hermite_bernstein`; SciPy's `BPoly.from_derivatives`).
///
/// >>> import lekalo
/// >>> f = lekalo.piecewise_hermite_bernstein([0.0, 1.0, 2.0], [[0.0, 1.0], [0.0], [2.0]])
/// >>> f.degree, f(0.5)
/// (2, array([0.25]))
#[pyfunction]
#[pyo3(signature = (breakpoints, derivatives, orders = None))]
pub(crate) fn piecewise_hermite_bernstein(
    py: Python<'_>,
    breakpoints: &Bound<'_, PyAny>,
    derivatives: Vec<Bound<'_, PyAny>>,
    orders: Option<Vec<usize>>,
) -> PyResult<PyBSplineCurve> {
    let x = vec1(breakpoints, "breakpoints")?;
    let arrays = derivatives
        .iter()
        .map(|d| floats(d, "derivatives"))
        .collect::<PyResult<Vec<_>>>()?;
    let refs = arrays
        .iter()
        .map(|a| a.points("derivatives"))
        .collect::<PyResult<Vec<_>>>()?;
    let curve = py
        .detach(|| lekalo::piecewise_hermite_bernstein(&x, &refs, orders.as_deref()))
        .map_err(lib_err)?;
    Ok(PyBSplineCurve::wrap(curve))
}

/// SciPy's coefficient array `c` (`order·pieces·dim` numbers) and breakpoints `x`, read in
/// place.
struct ScipyArrays<'a> {
    c: &'a [f64],
    x: &'a [f64],
    order: usize,
    dim: usize,
}

/// Checks the shapes of SciPy's `c` (`(k, pieces)` or `(k, pieces, dim)`, float64) and `x`
/// (`pieces + 1` breakpoints).
fn scipy_arrays<'a>(ca: &'a FloatArray<'_>, xa: &'a FloatArray<'_>) -> PyResult<ScipyArrays<'a>> {
    let (order, pieces, dim) = match ca.shape()[..] {
        [order, pieces] => (order, pieces, 1),
        [order, pieces, dim] => (order, pieces, dim),
        _ => {
            return Err(bad(format!(
                "c: shape {:?}; expected (k, pieces) or (k, pieces, dim)",
                ca.shape()
            )))
        }
    };
    if xa.shape() != [pieces + 1] {
        return Err(bad(format!(
            "x: shape {:?}; expected {} breakpoints for {pieces} pieces",
            xa.shape(),
            pieces + 1
        )));
    }
    Ok(ScipyArrays {
        c: ca.data(),
        x: xa.data(),
        order,
        dim,
    })
}

/// SciPy's `extrapolate` (a bool) as the library's [`Beyond`].
fn beyond(extrapolate: bool) -> Beyond {
    if extrapolate {
        Beyond::Continue
    } else {
        Beyond::Nan
    }
}

/// An evaluator of SciPy's arrays in place: `(arrays, points, nu, beyond, out)`.
type InPlace = fn(&ScipyArrays<'_>, &[f64], usize, Beyond, &mut [f64]) -> lekalo::Result<()>;

/// SciPy's arrays evaluated in place in the basis `B` (`lekalo::pp::PiecewiseRef`), with
/// SciPy's values at infinities and overflows (`par_eval_as_scipy`).
fn in_place<B: PieceBasis>(
    a: &ScipyArrays<'_>,
    xs: &[f64],
    nu: usize,
    beyond: Beyond,
    out: &mut [f64],
) -> lekalo::Result<()> {
    PiecewiseRef::<B>::new(a.c, a.order, a.x, a.dim)?.par_eval_as_scipy(xs, nu, beyond, out)
}

/// `then` on the arrays `c` and `x` read in place, their shapes checked ([`scipy_arrays`]).
fn with_scipy_arrays<R>(
    (c, x): (&Bound<'_, PyAny>, &Bound<'_, PyAny>),
    then: impl FnOnce(&ScipyArrays<'_>) -> PyResult<R>,
) -> PyResult<R> {
    let (ca, xa) = (floats(c, "c")?, floats(x, "x")?);
    then(&scipy_arrays(&ca, &xa)?)
}

/// The values at `xp` (any shape, result `xp.shape + (dim,)`) by `eval`, the arrays read in
/// place, the result written once into NumPy's array.
fn values_in_place<'py>(
    py: Python<'py>,
    (c, x, xp): (&Bound<'py, PyAny>, &Bound<'py, PyAny>, &Bound<'py, PyAny>),
    nu: usize,
    extrapolate: bool,
    eval: InPlace,
) -> PyResult<Bound<'py, PyAny>> {
    with_scipy_arrays((c, x), |arrays| {
        let pa = floats(xp, "xp")?;
        let xs = pa.data();
        let dim = arrays.dim;
        check_size("xp", &[xs.len(), dim])?;
        filled(py, &out_shape(&pa, &[dim]), |out| {
            eval(arrays, xs, nu, beyond(extrapolate), out)
        })
    })
}

/// The value at the number `xp` by `eval` of a scalar piecewise polynomial (`dim` 1), the
/// arrays read in place.
fn value_in_place(
    (c, x): (&Bound<'_, PyAny>, &Bound<'_, PyAny>),
    xp: f64,
    nu: usize,
    extrapolate: bool,
    eval: InPlace,
) -> PyResult<f64> {
    with_scipy_arrays((c, x), |arrays| {
        if arrays.dim != 1 {
            return Err(bad(format!(
                "c: {} values a point; the scalar call takes c of shape (k, pieces)",
                arrays.dim
            )));
        }
        let mut out = [0.0];
        eval(arrays, &[xp], nu, beyond(extrapolate), &mut out).map_err(lib_err)?;
        Ok(out[0])
    })
}

/// `ppoly_values(c, x, xp, nu=0, extrapolate=True)`: the `nu`-th derivative of SciPy's `PPoly`
/// with coefficients `c` (shape `(k, pieces)` or `(k, pieces, dim)`, float64, the highest power
/// first) on the non-decreasing breakpoints `x` at the points `xp` (any shape, result
/// `xp.shape + (dim,)`), the end pieces continued or NaN outside, NaN at NaN points, SciPy's
/// values at infinite points and where a value overflows (`lekalo::pp::PowerFormRef`,
/// `PiecewiseRef::par_eval_as_scipy`: Horner's rule on the arrays in place, nothing copied).
#[pyfunction]
#[pyo3(signature = (c, x, xp, nu = 0, extrapolate = true))]
pub(crate) fn ppoly_values<'py>(
    py: Python<'py>,
    c: &Bound<'py, PyAny>,
    x: &Bound<'py, PyAny>,
    xp: &Bound<'py, PyAny>,
    nu: usize,
    extrapolate: bool,
) -> PyResult<Bound<'py, PyAny>> {
    values_in_place(py, (c, x, xp), nu, extrapolate, in_place::<PowerBasis>)
}

/// `ppoly_value(c, x, xp, nu=0, extrapolate=True)`: [`ppoly_values`] at one number `xp` of a
/// scalar `PPoly` (`c` of shape `(k, pieces)`), a float.
#[pyfunction]
#[pyo3(signature = (c, x, xp, nu = 0, extrapolate = true))]
pub(crate) fn ppoly_value(
    c: &Bound<'_, PyAny>,
    x: &Bound<'_, PyAny>,
    xp: f64,
    nu: usize,
    extrapolate: bool,
) -> PyResult<f64> {
    value_in_place((c, x), xp, nu, extrapolate, in_place::<PowerBasis>)
}

/// `bpoly_values(c, x, xp, nu=0, extrapolate=True)`: the `nu`-th derivative of SciPy's `BPoly`
/// with Bernstein coefficients `c` (shape `(k + 1, pieces)` or `(k + 1, pieces, dim)`, float64)
/// on the non-decreasing breakpoints `x` at the points `xp` (any shape, result
/// `xp.shape + (dim,)`), the end pieces continued or NaN outside, NaN at NaN points, SciPy's
/// values at infinite points and where a value overflows (`lekalo::pp::BernsteinFormRef`,
/// `PiecewiseRef::par_eval_as_scipy`: the Bernstein sum in each piece on the arrays in place,
/// nothing copied).
#[pyfunction]
#[pyo3(signature = (c, x, xp, nu = 0, extrapolate = true))]
pub(crate) fn bpoly_values<'py>(
    py: Python<'py>,
    c: &Bound<'py, PyAny>,
    x: &Bound<'py, PyAny>,
    xp: &Bound<'py, PyAny>,
    nu: usize,
    extrapolate: bool,
) -> PyResult<Bound<'py, PyAny>> {
    values_in_place(py, (c, x, xp), nu, extrapolate, in_place::<BernsteinBasis>)
}

/// `bpoly_value(c, x, xp, nu=0, extrapolate=True)`: [`bpoly_values`] at one number `xp` of a
/// scalar `BPoly` (`c` of shape `(k + 1, pieces)`), a float.
#[pyfunction]
#[pyo3(signature = (c, x, xp, nu = 0, extrapolate = true))]
pub(crate) fn bpoly_value(
    c: &Bound<'_, PyAny>,
    x: &Bound<'_, PyAny>,
    xp: f64,
    nu: usize,
    extrapolate: bool,
) -> PyResult<f64> {
    value_in_place((c, x), xp, nu, extrapolate, in_place::<BernsteinBasis>)
}
