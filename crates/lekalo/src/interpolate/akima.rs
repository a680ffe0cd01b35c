//! Akima's slopes for Hermite interpolation of functions `y(x)`: [`akima_slopes`]
//! (`docs/theory/interpolation.md#akima-slopes`), the local rule
//! of Akima (J. ACM 17, 1970) and its modified form ("makima", Moler 2019), as SciPy's
//! `Akima1DInterpolator` computes them. The Hermite cubic with these slopes is
//! [`crate::CubicHermite`].

use crate::error::{check_finite, Result};
use crate::points::{Points, PointsRef};

/// Akima slopes `d_k` at the abscissae `x` (strictly increasing, at least 2) for the values `y`
/// (any dimension). With the secants `m_k = (y_{k+1} − y_k)/(x_{k+1} − x_k)`, extended by two
/// on each side linearly (`m_{−1} = 2m_0 − m_1`, `m_{−2} = 2m_{−1} − m_0`, the same on the
/// right), and the weights
///
/// `f_1 = |m_{k+1} − m_k|`, `f_2 = |m_{k−1} − m_{k−2}|` (Akima), or with `modified`
/// `f_1 = |m_{k+1} − m_k| + |m_{k+1} + m_k|/2`, `f_2 = |m_{k−1} − m_{k−2}| + |m_{k−1} + m_{k−2}|/2`
/// (Moler's "makima", which avoids overshoot where the data are flat),
///
/// the slope is `d_k = m_{k−1} + f_2/(f_1 + f_2)·(m_k − m_{k−1})`, and `(m_{k−1} + m_k)/2` where
/// `f_1 + f_2 ≤ 10⁻⁹ · max(f_1 + f_2)` (the maximum over all points and coordinates, SciPy's
/// cut-off). Two points give the secant at both. These are the slopes of SciPy's
/// `Akima1DInterpolator(method="akima" | "makima")`.
///
/// ```
/// use lekalo::{akima_slopes, PointsRef};
/// // data on a line keep its slope
/// let x = [0.0, 1.0, 3.0, 4.0, 6.0];
/// let y = [1.0, 3.0, 7.0, 9.0, 13.0];
/// let d = akima_slopes(&x, PointsRef::from_flat(1, &y)?, false)?;
/// assert!(d.as_slice().iter().all(|&s| (s - 2.0).abs() < 1e-15));
/// # Ok::<(), lekalo::Error>(())
/// ```
///
/// # Errors
/// [`Error::TooFew`] for fewer than 2 points; [`Error::LengthMismatch`] if `x` and `y` differ
/// in length; [`Error::NonFinite`] for a NaN or infinite number (or an overflowing slope);
/// [`Error::InvalidArgument`] if `x` is not strictly increasing.
pub fn akima_slopes(x: &[f64], y: PointsRef<'_>, modified: bool) -> Result<Points> {
    crate::interpolate::pchip::check_function_data(x, y)?;
    let n = x.len();
    let dim = y.dim();
    let ys = y.as_slice();
    // extended secants m[0 .. n + 3) per coordinate (index j + 2 is the secant of interval j)
    let mut m = vec![0.0; (n + 3) * dim];
    for c in 0..dim {
        for j in 0..n - 1 {
            m[(j + 2) * dim + c] = (ys[(j + 1) * dim + c] - ys[j * dim + c]) / (x[j + 1] - x[j]);
        }
    }
    let mut d = vec![0.0; n * dim];
    if n == 2 {
        for c in 0..dim {
            d[c] = m[2 * dim + c];
            d[dim + c] = m[2 * dim + c];
        }
        check_finite("Akima slopes (overflow: rescale the data)", &d)?;
        return Points::from_flat(dim, d);
    }
    for c in 0..dim {
        let at = |k: usize| k * dim + c;
        m[at(1)] = 2.0 * m[at(2)] - m[at(3)];
        m[at(0)] = 2.0 * m[at(1)] - m[at(2)];
        m[at(n + 1)] = 2.0 * m[at(n)] - m[at(n - 1)];
        m[at(n + 2)] = 2.0 * m[at(n + 1)] - m[at(n)];
    }
    // weights f1, f2 at each point and coordinate
    let weight = |a: f64, b: f64| {
        let dm = (a - b).abs();
        if modified {
            dm + 0.5 * (a + b).abs()
        } else {
            dm
        }
    };
    let mut f1 = vec![0.0; n * dim];
    let mut f2 = vec![0.0; n * dim];
    let mut fmax = f64::NEG_INFINITY;
    for k in 0..n {
        for c in 0..dim {
            let mm = |j: usize| m[j * dim + c];
            let a = weight(mm(k + 3), mm(k + 2));
            let b = weight(mm(k + 1), mm(k));
            f1[k * dim + c] = a;
            f2[k * dim + c] = b;
            fmax = fmax.max(a + b);
        }
    }
    for k in 0..n {
        for c in 0..dim {
            let (m1, m2) = (m[(k + 1) * dim + c], m[(k + 2) * dim + c]);
            let (a, b) = (f1[k * dim + c], f2[k * dim + c]);
            let f12 = a + b;
            d[k * dim + c] = if f12 > 1e-9 * fmax {
                m1 + (b / f12) * (m2 - m1)
            } else {
                0.5 * (m[(k + 3) * dim + c] + m[k * dim + c])
            };
        }
    }
    check_finite("Akima slopes (overflow: rescale the data)", &d)?;
    Points::from_flat(dim, d)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::error::Error;

    #[test]
    fn flat_data_stay_flat_and_errors_are_reported() {
        // Akima's classic property: a flat stretch between changes stays flat at its points
        let x = [0.0, 1.0, 2.0, 3.0, 4.0, 5.0];
        let y = [0.0, 0.0, 0.0, 1.0, 1.0, 1.0];
        for modified in [false, true] {
            let d = akima_slopes(&x, PointsRef::from_flat(1, &y).unwrap(), modified).unwrap();
            assert_eq!(d.as_slice()[1], 0.0, "modified {modified}");
            assert_eq!(d.as_slice()[4], 0.0, "modified {modified}");
        }
        let d = akima_slopes(
            &[0.0, 2.0],
            PointsRef::from_flat(1, &[1.0, 5.0]).unwrap(),
            false,
        )
        .unwrap();
        assert_eq!(d.as_slice(), &[2.0, 2.0]);
        assert!(matches!(
            akima_slopes(&[1.0], PointsRef::from_flat(1, &[1.0]).unwrap(), false),
            Err(Error::TooFew { .. })
        ));
        assert!(matches!(
            akima_slopes(&[0.0, 0.0], PointsRef::from_flat(1, &[1.0, 2.0]).unwrap(), true),
            Err(Error::InvalidArgument { what, .. }) if what.words() == "x"
        ));
    }
}
