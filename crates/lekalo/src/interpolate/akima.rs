//! Akima's slopes for Hermite interpolation of functions `y(x)`: [`akima_slopes`]
//! (`docs/theory/interpolation.md#akima-slopes`), the local rule
//! of Akima (J. ACM 17, 1970) and its modified form ("makima", Moler 2019), as SciPy's
//! `Akima1DInterpolator` computes them. The Hermite cubic with these slopes is
//! [`crate::CubicHermite`].

use crate::error::{check_finite, Error, Result};
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

/// [`akima_slopes`] of values of dimension 1 written into `slopes` (`x.len()` numbers): the same
/// numbers, bit for bit, in three vectorised passes (the secants, with 4-wide divisions where
/// the processor has AVX2; the largest weight sum; the slopes), the checks of the data folded
/// into the first and of the slopes into the last. O(n), one scratch array of `n + 3`
/// secants. The kernel of SciPy's `Akima1DInterpolator` in `lekalo.scipy`.
///
/// ```
/// use lekalo::{akima_slopes, akima_slopes_into, PointsRef};
/// let (x, y) = ([0.0, 1.0, 2.5, 3.0, 4.0], [0.0, 1.0, 1.5, 4.0, 4.5]);
/// let mut d = [0.0; 5];
/// akima_slopes_into(&x, &y, true, &mut d)?;
/// assert_eq!(&d[..], akima_slopes(&x, PointsRef::from_flat(1, &y)?, true)?.as_slice());
/// # Ok::<(), lekalo::Error>(())
/// ```
///
/// # Errors
/// Those of [`akima_slopes`], and [`Error::LengthMismatch`] if `slopes` is not as long as `x`.
pub fn akima_slopes_into(x: &[f64], y: &[f64], modified: bool, slopes: &mut [f64]) -> Result<()> {
    let n = x.len();
    if slopes.len() != n {
        return Err(Error::LengthMismatch {
            what: "Akima slopes (one per x)".into(),
            expected: n,
            got: slopes.len(),
        });
    }
    // `y` is checked where it is read (a number that is not finite named as `y`)
    let data = PointsRef::values(y);
    if n < 3 || y.len() != n {
        let d = akima_slopes(x, data, modified)?;
        slopes.copy_from_slice(d.as_slice());
        return Ok(());
    }
    // extended secants, index j + 2 the secant of interval j, as in akima_slopes
    let mut m = vec![0.0; n + 3];
    if !(akima_secants(x, y, &mut m[2..n + 1]) && (x[n - 1] - x[0]).is_finite()) {
        crate::interpolate::pchip::check_function_data(x, data)?;
    }
    m[1] = 2.0 * m[2] - m[3];
    m[0] = 2.0 * m[1] - m[2];
    m[n + 1] = 2.0 * m[n] - m[n - 1];
    m[n + 2] = 2.0 * m[n + 1] - m[n];
    let fmax = akima_weight_max(&m, modified);
    if !akima_finish(&m, modified, fmax, slopes) {
        check_finite("Akima slopes (overflow: rescale the data)", slopes)?;
    }
    Ok(())
}

/// Akima's weight `|a − b|`, with `modified` plus `|a + b|/2` (see [`akima_slopes`]).
#[inline(always)]
fn weight(a: f64, b: f64, modified: bool) -> f64 {
    let dm = (a - b).abs();
    if modified {
        dm + 0.5 * (a + b).abs()
    } else {
        dm
    }
}

/// The secants `(y_{j+1} − y_j)/(x_{j+1} − x_j)` into `m` (`n − 1` numbers). Returns whether
/// every step is positive (false for NaN) and every value finite.
#[inline(always)]
fn akima_secants_body(x: &[f64], y: &[f64], m: &mut [f64]) -> bool {
    let n = x.len();
    let mut bad = 0_u64;
    let (x0, x1) = (&x[..n - 1], &x[1..]);
    let (y0, y1) = (&y[..n - 1], &y[1..]);
    let m = &mut m[..n - 1];
    for j in 0..n - 1 {
        let h = x1[j] - x0[j];
        m[j] = (y1[j] - y0[j]) / h;
        bad |= u64::from(h.is_nan() | (h <= 0.0)) | u64::from(!y0[j].is_finite());
    }
    bad |= u64::from(!y[n - 1].is_finite());
    bad == 0
}

crate::numeric::isa::avx2_dispatch! {
    /// [`akima_secants_body`] compiled with AVX2 where the processor has it, else as built
    /// ([`crate::numeric::isa`]: the same bits).
    fn akima_secants(x: &[f64], y: &[f64], m: &mut [f64]) -> bool = akima_secants_body;
}

/// The largest `f_1 + f_2` over the points (the extended secants `m`, `n + 3` numbers), in
/// eight running maxima (`f64::max`, which passes over NaN as `akima_slopes`' does; the
/// maximum of a set does not depend on the order).
fn akima_weight_max(m: &[f64], modified: bool) -> f64 {
    let n = m.len() - 3;
    let mut lanes = [f64::NEG_INFINITY; 8];
    let (a, b, c, d) = (&m[3..n + 3], &m[2..n + 2], &m[1..n + 1], &m[..n]);
    let blocks = n / 8;
    for i in 0..blocks {
        for (l, lane) in lanes.iter_mut().enumerate() {
            let k = 8 * i + l;
            *lane = lane.max(weight(a[k], b[k], modified) + weight(c[k], d[k], modified));
        }
    }
    let mut fmax = lanes.iter().fold(f64::NEG_INFINITY, |acc, &v| acc.max(v));
    for k in 8 * blocks..n {
        fmax = fmax.max(weight(a[k], b[k], modified) + weight(c[k], d[k], modified));
    }
    fmax
}

/// The slopes from the extended secants `m` and the largest weight sum, the arithmetic of
/// [`akima_slopes`]. Returns whether every slope is finite.
#[inline(always)]
fn akima_finish_body(m: &[f64], modified: bool, fmax: f64, slopes: &mut [f64]) -> bool {
    let n = slopes.len();
    let (a, b, c, d) = (&m[3..n + 3], &m[2..n + 2], &m[1..n + 1], &m[..n]);
    let cut = 1e-9 * fmax;
    let mut bad = 0_u64;
    for k in 0..n {
        let (f1, f2) = (weight(a[k], b[k], modified), weight(c[k], d[k], modified));
        let f12 = f1 + f2;
        let (m1, m2) = (c[k], b[k]);
        let s = if f12 > cut {
            m1 + (f2 / f12) * (m2 - m1)
        } else {
            0.5 * (a[k] + d[k])
        };
        slopes[k] = s;
        bad |= u64::from(!s.is_finite());
    }
    bad == 0
}

crate::numeric::isa::avx2_dispatch! {
    /// [`akima_finish_body`] compiled with AVX2 where the processor has it, else as built
    /// ([`crate::numeric::isa`]: the same bits).
    fn akima_finish(m: &[f64], modified: bool, fmax: f64, slopes: &mut [f64]) -> bool = akima_finish_body;
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::error::Error;

    #[test]
    fn slopes_into_are_akima_slopes_bit_for_bit() {
        for n in [2, 3, 4, 5, 8, 9, 64, 65, 200, 1001] {
            let x: Vec<f64> = (0..n)
                .map(|i| i as f64 + 0.4 * ((i as f64) * 2.1).sin())
                .collect();
            // flat stretches (zero weights, the cut-off's branch) and sign changes
            let y: Vec<f64> = (0..n)
                .map(|i| {
                    if i % 13 < 4 {
                        2.0
                    } else {
                        ((i as f64) * 0.3).sin() * 5.0
                    }
                })
                .collect();
            for modified in [false, true] {
                let mut d = vec![0.0; n];
                akima_slopes_into(&x, &y, modified, &mut d).unwrap();
                let want =
                    akima_slopes(&x, PointsRef::from_flat(1, &y).unwrap(), modified).unwrap();
                let bits = |v: &[f64]| v.iter().map(|a| a.to_bits()).collect::<Vec<_>>();
                assert_eq!(
                    bits(&d),
                    bits(want.as_slice()),
                    "n = {n}, modified {modified}"
                );
            }
        }
    }

    #[test]
    fn slopes_into_refuse_what_akima_slopes_refuses() {
        let x: Vec<f64> = (0..50).map(f64::from).collect();
        let y: Vec<f64> = x.iter().map(|v| v.sin()).collect();
        let mut d = vec![0.0; 50];
        let mut run = |x: &[f64], y: &[f64]| akima_slopes_into(x, y, false, &mut d);
        let mut bad = y.clone();
        bad[49] = f64::NAN;
        assert!(matches!(
            run(&x, &bad),
            Err(Error::NonFinite { index: 49, .. })
        ));
        let mut xs = x.clone();
        xs[10] = xs[9];
        assert!(matches!(run(&xs, &y), Err(Error::InvalidArgument { .. })));
        assert!(matches!(
            akima_slopes_into(&x[..1], &y[..1], false, &mut [0.0; 1]),
            Err(Error::TooFew { .. })
        ));
        assert!(matches!(
            run(&x, &y[..3]),
            Err(Error::LengthMismatch { .. })
        ));
        assert!(matches!(
            akima_slopes_into(&x, &y, true, &mut [0.0; 3]),
            Err(Error::LengthMismatch { .. })
        ));
    }

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
