//! Cubic Hermite data (values and slopes at increasing breakpoints) written as the local power
//! coefficients of SciPy's `PPoly`, in one pass (docs/theory/pp.md#hermite-data-in-power-form):
//! the coefficients of SciPy's `CubicHermiteSpline` (and so of `CubicSpline`,
//! `PchipInterpolator` and `Akima1DInterpolator`), computed from the data by SciPy's operations,
//! so that they are SciPy's numbers and extrapolate as SciPy's do.

use super::hermite_bspline::{check_hermite_numbers, hermite_rows};
use crate::error::{Error, Result};

/// Writes the cubic Hermite spline with values `y` and slopes `dydx` (each `n` rows of `dim`
/// numbers, row-major) at the strictly increasing breakpoints `x` into `c` in SciPy's `PPoly`
/// layout: 4 rows (the powers 3, 2, 1, 0) of `n − 1` pieces of `dim` numbers,
/// `c[(m·(n − 1) + i)·dim + j]`. On piece `i`, with `h = x_{i+1} − x_i`, the secant
/// `δ = (y_{i+1} − y_i)/h` and `t = (y'_i + y'_{i+1} − 2δ)/h`:
///
/// `c_3 = y_i`, `c_2 = y'_i`, `c_1 = (δ − y'_i)/h − t`, `c_0 = t/h`
///
/// so that `p(u) = c_0 u³ + c_1 u² + c_2 u + c_3` (`u = x − x_i`) has the values and slopes of
/// the data at both ends (the Hermite basis, de Boor, *A Practical Guide to Splines*, rev. ed.,
/// ch. IV, eq. (4)). The operations are SciPy's `CubicHermiteSpline`'s in its order, so the
/// coefficients are SciPy's bits; formed from the data (not from a B-spline form), they keep
/// every digit the data determine, which matters far beyond the ends
/// (docs/theory/pp.md#extrapolation-in-pp-form). O(n·dim), one pass, no allocation.
///
/// ```
/// use lekalo::pp::cubic_hermite_power_into;
/// // y = x² on [0, 1, 2] with slopes 2x: c_0 = 0, c_1 = 1, c_2 = y', c_3 = y
/// let mut c = [0.0; 8];
/// cubic_hermite_power_into(&[0.0, 1.0, 2.0], &[0.0, 1.0, 4.0], &[0.0, 2.0, 4.0], 1, &mut c)?;
/// assert_eq!(c, [0.0, 0.0, 1.0, 1.0, 0.0, 2.0, 0.0, 1.0]);
/// # Ok::<(), lekalo::Error>(())
/// ```
///
/// # Errors
/// [`Error::TooFew`] for fewer than 2 breakpoints; [`Error::InvalidArgument`] for breakpoints
/// that are not finite and strictly increasing, or `dim = 0`; [`Error::LengthMismatch`] when
/// `y`, `dydx` or `c` do not have the lengths above; [`Error::NonFinite`] for a value or slope
/// that is not finite.
pub fn cubic_hermite_power_into(
    x: &[f64],
    y: &[f64],
    dydx: &[f64],
    dim: usize,
    c: &mut [f64],
) -> Result<()> {
    let n = x.len();
    let rows = hermite_rows(x, dim, 4)?;
    let coefficients = 4 * (n - 1) * dim;
    for (what, expected, got) in [
        ("Hermite values (breakpoints × dimension)", rows, y.len()),
        ("Hermite slopes (breakpoints × dimension)", rows, dydx.len()),
        (
            "power coefficients (4 × pieces × dimension)",
            coefficients,
            c.len(),
        ),
    ] {
        if expected != got {
            return Err(Error::LengthMismatch {
                what: what.into(),
                expected,
                got,
            });
        }
    }
    if dim == 1 {
        // the checks folded into the pass; on failure the checks below name the first bad number
        if hermite_power_scalar_pass(x, y, dydx, c) && (x[n - 1] - x[0]).is_finite() {
            return Ok(());
        }
    }
    check_hermite_numbers(x, y, dydx)?;
    write_hermite_power(x, y, dydx, dim, c);
    Ok(())
}

/// The pass of [`cubic_hermite_power_into`] on checked arrays of the right lengths (numbers
/// that are not finite propagate as in IEEE arithmetic, as in SciPy).
fn write_hermite_power(x: &[f64], y: &[f64], dydx: &[f64], dim: usize, c: &mut [f64]) {
    let pieces = x.len() - 1;
    let row = pieces * dim;
    let (c0, rest) = c.split_at_mut(row);
    let (c1, rest) = rest.split_at_mut(row);
    let (c2, c3) = rest.split_at_mut(row);
    for i in 0..pieces {
        let h = x[i + 1] - x[i];
        for j in 0..dim {
            let k = i * dim + j;
            let (y0, y1) = (y[k], y[k + dim]);
            let (d0, d1) = (dydx[k], dydx[k + dim]);
            let slope = (y1 - y0) / h;
            let t = (d0 + d1 - 2.0 * slope) / h;
            c0[k] = t / h;
            c1[k] = (slope - d0) / h - t;
            c2[k] = d0;
            c3[k] = y0;
        }
    }
}

/// [`write_hermite_power`] for values of dimension 1 with the checks folded in: returns whether
/// every step `x_{i+1} − x_i` is positive (false for NaN) and every value and slope finite
/// (`x_0`, `x_{n−1}` finite then follows from a finite `x_{n−1} − x_0`, which the caller
/// checks). The same operations, so the same bits; the four rows written as vectors.
#[inline(always)]
fn hermite_power_scalar_body(x: &[f64], y: &[f64], dydx: &[f64], c: &mut [f64]) -> bool {
    let pieces = x.len() - 1;
    let (c0, rest) = c.split_at_mut(pieces);
    let (c1, rest) = rest.split_at_mut(pieces);
    let (c2, c3) = rest.split_at_mut(pieces);
    let (xs, ys, ds) = (&x[..=pieces], &y[..=pieces], &dydx[..=pieces]);
    let mut bad = 0_u64;
    for i in 0..pieces {
        let h = xs[i + 1] - xs[i];
        let (y0, d0, d1) = (ys[i], ds[i], ds[i + 1]);
        let slope = (ys[i + 1] - y0) / h;
        let t = (d0 + d1 - 2.0 * slope) / h;
        c0[i] = t / h;
        c1[i] = (slope - d0) / h - t;
        c2[i] = d0;
        c3[i] = y0;
        bad |= u64::from(h.is_nan() | (h <= 0.0))
            | u64::from(!y0.is_finite())
            | u64::from(!d0.is_finite());
    }
    bad |= u64::from(!ys[pieces].is_finite()) | u64::from(!ds[pieces].is_finite());
    bad == 0
}

crate::numeric::isa::avx2_dispatch! {
    /// [`hermite_power_scalar_body`] compiled with AVX2 where the processor has it, else as
    /// built ([`crate::numeric::isa`]: the same bits).
    fn hermite_power_scalar_pass(x: &[f64], y: &[f64], dydx: &[f64], c: &mut [f64]) -> bool = hermite_power_scalar_body;
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::pp::{cubic_hermite_bspline_into, cubic_hermite_bspline_len};
    use crate::{BSplineCurve, KnotVector, Points};

    /// Hermite data of dimension `dim` at `x`.
    fn data(x: &[f64], dim: usize) -> (Vec<f64>, Vec<f64>) {
        let n = x.len() * dim;
        let y = (0..n).map(|i| (i as f64 * 0.7).sin()).collect();
        let d = (0..n).map(|i| (i as f64 * 1.3).cos() * 2.0).collect();
        (y, d)
    }

    #[test]
    fn the_pieces_are_the_hermite_b_spline() {
        let x = [0.0, 0.5, 1.7, 2.0, 3.5];
        for dim in [1, 3] {
            let (y, d) = data(&x, dim);
            let mut c = vec![0.0; 4 * 4 * dim];
            cubic_hermite_power_into(&x, &y, &d, dim, &mut c).unwrap();
            let (nk, nc) = cubic_hermite_bspline_len(x.len());
            let (mut t, mut b) = (vec![0.0; nk], vec![0.0; nc * dim]);
            cubic_hermite_bspline_into(&x, &y, &d, dim, &mut t, &mut b).unwrap();
            let curve = BSplineCurve::new(
                3,
                KnotVector::new(t).unwrap(),
                Points::from_flat(dim, b).unwrap(),
            )
            .unwrap();
            for i in 0..4 {
                for f in [0.0, 0.3, 0.9] {
                    let u = f * (x[i + 1] - x[i]);
                    let v = curve.eval(x[i] + u).unwrap();
                    for j in 0..dim {
                        let k = |m: usize| c[(m * 4 + i) * dim + j];
                        let p = ((k(0) * u + k(1)) * u + k(2)) * u + k(3);
                        assert!(
                            (p - v[j]).abs() < 1e-13,
                            "piece {i} at {u}: {p} vs {}",
                            v[j]
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn one_column_is_the_general_pass_bit_for_bit() {
        let x: Vec<f64> = (0..200)
            .map(|i| f64::from(i) * 0.01 + f64::from(i % 7) * 1e-3)
            .collect();
        let (y, d) = data(&x, 1);
        let mut fast = vec![0.0; 4 * 199];
        cubic_hermite_power_into(&x, &y, &d, 1, &mut fast).unwrap();
        let mut general = vec![0.0; 4 * 199];
        write_hermite_power(&x, &y, &d, 1, &mut general);
        assert!(
            fast.iter()
                .zip(&general)
                .all(|(a, b)| a.to_bits() == b.to_bits()),
            "bits"
        );
    }

    #[test]
    fn bad_data_is_refused_by_name() {
        let x = [0.0, 1.0, 2.0];
        let mut c = [0.0; 8];
        let e = cubic_hermite_power_into(&x, &[0.0, f64::NAN, 1.0], &[0.0; 3], 1, &mut c);
        assert!(matches!(e, Err(Error::NonFinite { index: 1, .. })), "{e:?}");
        let e = cubic_hermite_power_into(&x, &[0.0; 3], &[0.0, 0.0, f64::INFINITY], 1, &mut c);
        assert!(matches!(e, Err(Error::NonFinite { index: 2, .. })), "{e:?}");
        let e = cubic_hermite_power_into(&[0.0, 2.0, 1.0], &[0.0; 3], &[0.0; 3], 1, &mut c);
        assert!(matches!(e, Err(Error::InvalidArgument { .. })), "{e:?}");
        let e = cubic_hermite_power_into(&x, &[0.0; 3], &[0.0; 3], 1, &mut c[..7]);
        assert!(matches!(e, Err(Error::LengthMismatch { .. })), "{e:?}");
        let e = cubic_hermite_power_into(&x[..1], &[0.0], &[0.0], 1, &mut []);
        assert!(matches!(e, Err(Error::TooFew { .. })), "{e:?}");
        let e = cubic_hermite_power_into(&x, &[], &[], 0, &mut []);
        assert!(matches!(e, Err(Error::InvalidArgument { .. })), "{e:?}");
    }
}
