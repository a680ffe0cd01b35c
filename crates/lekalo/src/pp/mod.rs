//! Piecewise polynomials and their B-spline bases (document 003).
//!
//! - `divided_difference.rs`: divided differences ([`divided_difference`], [`NewtonForm`]) and
//!   the B-spline as a divided difference of truncated powers.
//! - `ppform.rs`: [`PiecewisePolynomial`] (pp-form) and the spaces [`PpSpace`].
//! - `decreasing.rs`: piecewise polynomials given on decreasing breakpoints
//!   ([`PiecewisePolynomial::from_decreasing`], [`PiecewisePolynomial::to_decreasing`]).
//! - `extrapolation.rs`: evaluation with the end pieces continued
//!   ([`PiecewisePolynomial::eval_extrapolated_into`]).
//! - `piecewise_ref.rs`: [`PiecewiseRef`], SciPy's coefficient arrays evaluated in place,
//!   generic over the basis of the pieces ([`PieceBasis`]): the checks of the arrays and the
//!   batch drivers (derivative order, the end pieces continued or NaN, kernels of fixed order,
//!   the thread pool), written once; its tests in `piecewise_ref_tests.rs`.
//! - `power_form.rs`: [`PowerBasis`] (Horner's rule in `x − x_j`), [`PowerFormRef`] for
//!   SciPy's `PPoly`.
//! - `bernstein_form.rs`: [`BernsteinBasis`] (the Bernstein sum or de Casteljau in
//!   `(x − x_j)/h_j`), [`BernsteinFormRef`] for SciPy's `BPoly`.
//! - `piece_search.rs`: the piece of a point on breakpoints read in place (the B-spline
//!   evaluator's bucket table or a binary search) and the batch loop over the points.
//! - `hermite_bernstein.rs`: Hermite interpolation in Bernstein form with derivatives of any
//!   order at the breakpoints ([`hermite_bernstein`], [`piecewise_hermite_bernstein`]).
//! - `hermite_bspline.rs`: cubic Hermite data written into the knots and coefficients of a
//!   B-spline with double knots in one pass ([`cubic_hermite_bspline_into`]).
//! - `hermite_power.rs`: cubic Hermite data written as SciPy's `PPoly` coefficients in one
//!   pass ([`cubic_hermite_power_into`]), SciPy's numbers.
//! - `integral.rs`: antiderivatives and integrals in pp-form
//!   ([`PiecewisePolynomial::antiderivative`], [`PiecewisePolynomial::integral_extrapolated`]).
//! - `roots.rs`: the real solutions of `f(x) = y` ([`PiecewisePolynomial::solve`], [`Solution`]).
//! - `quasi_interpolation.rs`: the de Boor–Fix dual functionals: pp-form to B-spline
//!   conversion and [`quasi_interpolate`].

mod bernstein_form;
mod decreasing;
mod divided_difference;
mod expression;
mod extrapolation;
mod hermite_bernstein;
mod hermite_bspline;
mod hermite_power;
mod integral;
mod piece_search;
mod piecewise_ref;
#[cfg(test)]
mod piecewise_ref_tests;
mod power_form;
pub(crate) mod ppform;
mod quasi_interpolation;
mod roots;

pub use bernstein_form::{BernsteinBasis, BernsteinFormRef};
pub use divided_difference::{
    bspline_divided_difference, divided_difference, divided_difference_explicit, truncated_power,
    NewtonForm,
};
pub use expression::{Expression, MAX_EXPRESSION_LEN, MAX_EXPRESSION_ORDER};
pub use hermite_bernstein::{hermite_bernstein, piecewise_hermite_bernstein, MAX_HERMITE_DEGREE};
pub use hermite_bspline::{cubic_hermite_bspline_into, cubic_hermite_bspline_len};
pub use hermite_power::cubic_hermite_power_into;
pub use piecewise_ref::{Piece, PieceBasis, PiecewiseRef, FIXED_ORDER_MAX};
pub use power_form::{PowerBasis, PowerFormRef};
pub use ppform::{PiecewisePolynomial, PpSpace, DEFAULT_CONTINUITY_RTOL};
pub use quasi_interpolation::{
    quasi_interpolate, quasi_interpolate_expression, sample_quasi_interpolant,
    sample_quasi_interpolant_expression, QuasiSamples, Tau, TauRule,
};
pub use roots::Solution;
