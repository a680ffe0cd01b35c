//! Hermite interpolation in Bernstein form: the polynomial of least degree with given
//! derivatives at both ends of an interval ([`hermite_bernstein`]), and the piecewise polynomial
//! with given derivatives of any order at every breakpoint ([`piecewise_hermite_bernstein`],
//! SciPy's `BPoly.from_derivatives`), docs/theory/pp.md#hermite-interpolation-in-bernstein-form.
//!
//! On `[a, b]` with `h = b − a`, the polynomial `B = Σ_{i≤N} c_i b_{i,N}` has
//! `B^{(q)}(a) = N!/(N−q)! · h^{−q} · Δ^q c_0` and `B^{(q)}(b) = N!/(N−q)! · h^{−q} · Δ^q c_{N−q}`
//! (forward differences). Given `n_a` derivatives at `a` and `n_b` at `b`, `N = n_a + n_b − 1`:
//! the left conditions fix `c_0 … c_{n_a−1}` one at a time from the left, the right ones
//! `c_N … c_{n_a}` from the right, and the two sets do not meet.

use crate::curve::bspline::BSplineCurve;
use crate::degree::elevation::elevate;
use crate::error::readable;
use crate::error::{check_finite, Error, Result, MAX_SCALARS};
use crate::knots::check_breakpoints;
use crate::points::{Points, PointsRef};

/// Highest degree [`hermite_bernstein`] builds: its coefficients carry binomials `C(q, j)` and
/// the factors `(N−q)!/N!`, which stay representable and accurate far beyond any practical degree
/// at this bound.
pub const MAX_HERMITE_DEGREE: usize = 64;

/// The Bernstein coefficients on `[a, b]` of the polynomial of least degree `N = n_a + n_b − 1`
/// whose derivatives of orders `0 … n_a − 1` at `a` are the rows of `at_a` and of orders
/// `0 … n_b − 1` at `b` the rows of `at_b` (row `q` is the `q`-th derivative, values first).
/// `N + 1` rows of the common dimension; the recurrence of the module docs
/// (docs/theory/pp.md#hermite-interpolation-in-bernstein-form; SciPy's
/// `BPoly._construct_from_derivatives`).
///
/// ```
/// use lekalo::{hermite_bernstein, PointsRef};
/// // f(0) = 2, f'(0) = 3, f(1) = 1: the quadratic 2 b0 + 3.5 b1 + 1 b2
/// let c = hermite_bernstein(
///     0.0,
///     1.0,
///     PointsRef::from_flat(1, &[2.0, 3.0])?,
///     PointsRef::from_flat(1, &[1.0])?,
/// )?;
/// assert_eq!(c.as_slice(), &[2.0, 3.5, 1.0]);
/// # Ok::<(), lekalo::Error>(())
/// ```
///
/// # Errors
/// [`Error::InvalidArgument`] unless `a < b` are finite; [`Error::TooFew`] if no derivative is
/// given at either end; [`Error::Dimension`] if the two ends differ in dimension;
/// [`Error::Degree`] above [`MAX_HERMITE_DEGREE`].
pub fn hermite_bernstein(
    a: f64,
    b: f64,
    at_a: PointsRef<'_>,
    at_b: PointsRef<'_>,
) -> Result<Points> {
    if !(a.is_finite() && b.is_finite() && a < b) {
        return Err(Error::InvalidArgument {
            what: "Hermite interval".into(),
            reason: format!(
                "the ends must be finite with a < b, got a = {a}, b = {b}",
                a = readable(&a),
                b = readable(&b)
            ),
        });
    }
    if at_a.dim() != at_b.dim() {
        return Err(Error::Dimension {
            what: "derivatives at the right end (as at the left end)".into(),
            expected: at_a.dim(),
            got: at_b.dim(),
        });
    }
    let n = at_a.len() + at_b.len();
    if n == 0 {
        return Err(Error::TooFew {
            what: "derivatives at the two ends of a Hermite piece".into(),
            min: 1,
            got: 0,
        });
    }
    let degree = n - 1;
    if degree > MAX_HERMITE_DEGREE {
        return Err(Error::Degree {
            degree,
            reason: format!(
                "Hermite interpolation builds degrees up to {MAX_HERMITE_DEGREE}; give fewer derivatives"
            ),
        });
    }
    let dim = at_a.dim();
    let h = b - a;
    let mut c = vec![0.0; n * dim];
    let binom = binomials(degree);
    // left end: c_q = y_q h^q (N−q)!/N! − Σ_{j<q} (−1)^{q−j} C(q,j) c_j
    let mut scale = 1.0;
    for q in 0..at_a.len() {
        if q > 0 {
            scale *= h / (degree + 1 - q) as f64;
        }
        for d in 0..dim {
            let mut v = at_a.point(q)[d] * scale;
            for j in 0..q {
                let sign = if (q - j) % 2 == 0 { 1.0 } else { -1.0 };
                v -= sign * binom[q][j] * c[j * dim + d];
            }
            c[q * dim + d] = v;
        }
    }
    // right end: Δ^q c_{N−q} = y_q h^q (N−q)!/N!, solved for c_{N−q} (coefficient (−1)^q)
    let mut scale = 1.0;
    for q in 0..at_b.len() {
        if q > 0 {
            scale *= h / (degree + 1 - q) as f64;
        }
        let sign_q = if q % 2 == 0 { 1.0 } else { -1.0 };
        for d in 0..dim {
            let mut v = at_b.point(q)[d] * scale;
            for j in 1..=q {
                let sign = if (q - j) % 2 == 0 { 1.0 } else { -1.0 };
                v -= sign * binom[q][j] * c[(degree - q + j) * dim + d];
            }
            c[(degree - q) * dim + d] = sign_q * v;
        }
    }
    check_finite("Hermite Bernstein coefficients", &c)?;
    Ok(Points::from_raw(c, dim))
}

/// Pascal's triangle up to row `n`.
fn binomials(n: usize) -> Vec<Vec<f64>> {
    let mut rows: Vec<Vec<f64>> = Vec::with_capacity(n + 1);
    for q in 0..=n {
        let mut row = vec![1.0; q + 1];
        for j in 1..q {
            row[j] = rows[q - 1][j - 1] + rows[q - 1][j];
        }
        rows.push(row);
    }
    rows
}

/// How many derivatives piece `[ξ_i, ξ_{i+1}]` takes from each end, given `len_a` derivatives at
/// `ξ_i`, `len_b` at `ξ_{i+1}` and an optional local degree `order` (SciPy's `orders`, the
/// degree of the piece): all of them without it; with it, `order + 1` in all, half from each end
/// and the odd one from the right, the rest from the other end when one end has too few.
///
/// # Errors
/// [`Error::InvalidArgument`] if `order + 1` exceeds `len_a + len_b`.
fn counts(len_a: usize, len_b: usize, order: Option<usize>, at: f64) -> Result<(usize, usize)> {
    let Some(order) = order else {
        return Ok((len_a, len_b));
    };
    let n = order.saturating_add(1);
    if n > len_a + len_b {
        return Err(Error::InvalidArgument {
            what: "orders".into(),
            reason: format!(
                "the piece starting at {at} has {len_a} derivatives at its left end and {len_b} at \
                 its right end, too few for degree {order}; give a degree of at most {}",
                (len_a + len_b).saturating_sub(1)
            ),
        });
    }
    let n_a = (n / 2).min(len_a);
    let n_b = (n - n_a).min(len_b);
    Ok((n - n_b, n_b))
}

/// The piecewise polynomial on the breakpoints `ξ_0 < … < ξ_m` whose derivatives of orders
/// `0, 1, …` at `ξ_i` are the rows of `derivatives[i]` (any number per point, values first):
/// on each piece [`hermite_bernstein`] of the derivatives at its two ends (all of them, or with
/// `orders` the `orders[i] + 1` chosen by the rule of
/// docs/theory/pp.md#hermite-interpolation-in-bernstein-form), every piece raised to the
/// largest degree among them (Bernstein degree elevation, document 004, eq. 8). The result is
/// the B-spline of that degree `p` with every breakpoint of multiplicity `p + 1`, whose control
/// points are the Bernstein coefficients piece after piece; it is `k − 1` times continuously
/// differentiable at a breakpoint where `k` derivatives are used on both sides. SciPy's
/// `BPoly.from_derivatives`.
///
/// ```
/// use lekalo::{piecewise_hermite_bernstein, PointsRef};
/// // f(0) = 0, f'(0) = 1, f(1) = 0, f(2) = 2: x(1 − x) on [0, 1], then 2(x − 1)
/// let d = [PointsRef::from_flat(1, &[0.0, 1.0])?, PointsRef::from_flat(1, &[0.0])?, PointsRef::from_flat(1, &[2.0])?];
/// let f = piecewise_hermite_bernstein(&[0.0, 1.0, 2.0], &d, None)?;
/// assert_eq!(f.degree(), 2);
/// assert!((f.eval(0.5)?[0] - 0.25).abs() < 1e-15);
/// assert!((f.eval(1.5)?[0] - 1.0).abs() < 1e-15);
/// # Ok::<(), lekalo::Error>(())
/// ```
///
/// # Errors
/// [`Error::TooFew`] for fewer than two breakpoints, or a piece with no derivative at either end;
/// [`Error::LengthMismatch`] if `derivatives` (or `orders`) does not have one entry per point
/// (per piece); [`Error::InvalidArgument`] for breakpoints that are not strictly increasing or an
/// order that asks for more derivatives than a piece has; [`Error::Dimension`] for points of
/// different dimensions; [`Error::Degree`] above [`MAX_HERMITE_DEGREE`]; [`Error::TooLarge`].
pub fn piecewise_hermite_bernstein(
    breakpoints: &[f64],
    derivatives: &[PointsRef<'_>],
    orders: Option<&[usize]>,
) -> Result<BSplineCurve> {
    check_breakpoints(breakpoints)?;
    let pieces = breakpoints.len() - 1;
    if derivatives.len() != breakpoints.len() {
        return Err(Error::LengthMismatch {
            what: "derivatives (one set per breakpoint)".into(),
            expected: breakpoints.len(),
            got: derivatives.len(),
        });
    }
    if let Some(o) = orders {
        if o.len() != pieces {
            return Err(Error::LengthMismatch {
                what: "orders (one per piece)".into(),
                expected: pieces,
                got: o.len(),
            });
        }
    }
    let dim = derivatives[0].dim();
    if let Some(bad) = derivatives.iter().find(|p| p.dim() != dim) {
        return Err(Error::Dimension {
            what: "derivatives at a breakpoint (as at the first)".into(),
            expected: dim,
            got: bad.dim(),
        });
    }
    let mut local = Vec::with_capacity(pieces);
    for i in 0..pieces {
        let (a, b) = (derivatives[i], derivatives[i + 1]);
        let (n_a, n_b) = counts(a.len(), b.len(), orders.map(|o| o[i]), breakpoints[i])?;
        let at_a = PointsRef::from_flat(dim, &a.as_slice()[..n_a * dim])?;
        let at_b = PointsRef::from_flat(dim, &b.as_slice()[..n_b * dim])?;
        local.push(hermite_bernstein(
            breakpoints[i],
            breakpoints[i + 1],
            at_a,
            at_b,
        )?);
    }
    let order = local.iter().map(Points::len).max().unwrap_or(1);
    let size = pieces
        .checked_mul(order)
        .and_then(|v| v.checked_mul(dim + 1));
    if size.is_none_or(|s| s > MAX_SCALARS) {
        return Err(Error::TooLarge {
            what: "piecewise Hermite coefficients".into(),
            size: size.unwrap_or(usize::MAX),
            max: MAX_SCALARS,
        });
    }
    let mut control = Vec::with_capacity(pieces * order * dim);
    let mut knots = Vec::with_capacity((pieces + 1) * order);
    for c in &local {
        if c.len() == order {
            control.extend_from_slice(c.as_slice());
        } else {
            control.extend(elevate(c.as_slice(), dim, order - c.len()));
        }
    }
    for &x in breakpoints {
        knots.extend(std::iter::repeat_n(x, order));
    }
    BSplineCurve::new(order - 1, knots, Points::from_flat(dim, control)?)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pts(v: &[f64]) -> PointsRef<'_> {
        PointsRef::from_flat(1, v).unwrap()
    }

    /// SciPy's `test_make_poly_*` values (exact Bernstein coefficients, checked by hand above).
    #[test]
    fn scipy_make_poly_values() {
        let cases: [(&[f64], &[f64], &[f64]); 6] = [
            (&[2.0], &[3.0], &[2.0, 3.0]),
            (&[1.0, 0.0], &[1.0], &[1.0, 1.0, 1.0]),
            (&[2.0, 3.0], &[1.0], &[2.0, 3.5, 1.0]),
            (&[2.0], &[1.0, 3.0], &[2.0, -0.5, 1.0]),
            (&[1.0, 2.0, 3.0], &[4.0], &[1.0, 5.0 / 3.0, 17.0 / 6.0, 4.0]),
            (
                &[1.0],
                &[4.0, 2.0, 3.0],
                &[1.0, 19.0 / 6.0, 10.0 / 3.0, 4.0],
            ),
        ];
        for (ya, yb, want) in cases {
            let c = hermite_bernstein(0.0, 1.0, pts(ya), pts(yb)).unwrap();
            for (g, w) in c.as_slice().iter().zip(want) {
                assert!((g - w).abs() < 1e-14, "{ya:?} {yb:?}: {g} vs {w}");
            }
        }
    }

    /// The derivatives of the result at both ends are the ones given (degree 11 on [1, 4]).
    #[test]
    fn derivatives_are_reproduced() {
        let ya = [0.3, -1.0, 2.0, 0.5, -0.25, 4.0];
        let yb = [1.0, 0.0, -3.0, 1.5, 2.0, -1.0];
        let c = hermite_bernstein(1.0, 4.0, pts(&ya), pts(&yb)).unwrap();
        let n = c.len();
        let curve = BSplineCurve::new(n - 1, [vec![1.0; n], vec![4.0; n]].concat(), c).unwrap();
        let da = curve.eval_derivatives(1.0, 5).unwrap();
        let db = curve.eval_derivatives(4.0, 5).unwrap();
        for q in 0..6 {
            let (ga, gb) = (da.point(q)[0], db.point(q)[0]);
            assert!(
                (ga - ya[q]).abs() < 1e-9 * (1.0 + ya[q].abs()),
                "left {q}: {ga}"
            );
            assert!(
                (gb - yb[q]).abs() < 1e-9 * (1.0 + yb[q].abs()),
                "right {q}: {gb}"
            );
        }
    }

    /// SciPy's example: x(1 − x) then 2(x − 1); pieces raised to the common degree 2.
    #[test]
    fn piecewise_example_and_orders() {
        let d = [pts(&[0.0, 1.0]), pts(&[0.0]), pts(&[2.0])];
        let f = piecewise_hermite_bernstein(&[0.0, 1.0, 2.0], &d, None).unwrap();
        assert_eq!(f.degree(), 2);
        assert_eq!(f.knots().len(), 9);
        for x in [0.0, 0.25, 0.9] {
            assert!(
                (f.eval(x).unwrap()[0] - x * (1.0 - x)).abs() < 1e-15,
                "x = {x}"
            );
        }
        assert!(
            (f.eval(1.75).unwrap()[0] - 1.5).abs() < 1e-15,
            "second piece"
        );
        // degree 1 on each piece: only the values
        let g = piecewise_hermite_bernstein(&[0.0, 1.0, 2.0], &d, Some(&[1, 1])).unwrap();
        assert_eq!(g.degree(), 1);
        assert!(
            (g.eval(0.5).unwrap()[0]).abs() < 1e-15,
            "linear between the values"
        );
        let e = piecewise_hermite_bernstein(&[0.0, 1.0, 2.0], &d, Some(&[1, 2])).unwrap_err();
        assert!(
            matches!(e, Error::InvalidArgument { what, .. } if what.words() == "orders"),
            "{e}"
        );
    }

    /// The counting rule: half from each end, the odd one from the right, the rest from the
    /// other end.
    #[test]
    fn counts_rule() {
        assert_eq!(counts(3, 3, None, 0.0).unwrap(), (3, 3));
        assert_eq!(counts(3, 3, Some(4), 0.0).unwrap(), (2, 3));
        assert_eq!(counts(3, 3, Some(3), 0.0).unwrap(), (2, 2));
        assert_eq!(counts(5, 1, Some(3), 0.0).unwrap(), (3, 1));
        assert_eq!(counts(1, 5, Some(3), 0.0).unwrap(), (1, 3));
        assert!(
            counts(2, 2, Some(4), 0.0).is_err(),
            "five derivatives from four"
        );
    }

    #[test]
    fn refusals() {
        let e = hermite_bernstein(1.0, 1.0, pts(&[1.0]), pts(&[1.0])).unwrap_err();
        assert!(matches!(e, Error::InvalidArgument { .. }), "{e}");
        let e = hermite_bernstein(0.0, 1.0, pts(&[]), pts(&[])).unwrap_err();
        assert!(matches!(e, Error::TooFew { .. }), "{e}");
        let d = [pts(&[0.0]), pts(&[1.0])];
        let e = piecewise_hermite_bernstein(&[0.0, 1.0, 2.0], &d, None).unwrap_err();
        assert!(matches!(e, Error::LengthMismatch { .. }), "{e}");
        let e = piecewise_hermite_bernstein(&[1.0, 0.0], &d, None).unwrap_err();
        assert!(matches!(e, Error::InvalidArgument { .. }), "{e}");
    }
}
