//! Shape-preserving slopes for piecewise cubic Hermite interpolation of functions `y(x)`:
//! [`pchip_slopes`] (`docs/theory/interpolation.md#pchip-slopes`), the PCHIP rule of Fritsch & Butland with Moler's one-sided ends (what
//! SciPy's `PchipInterpolator` and MATLAB's `pchip` use). The Hermite cubic through the data
//! with these slopes is [`crate::CubicHermite`].

use crate::error::readable;
use crate::error::{check_finite, Error, Result};
use crate::points::{Points, PointsRef};

/// PCHIP slopes `d_k` at the abscissae `x` (strictly increasing, at least 2) for the values `y`
/// (one point per abscissa, any dimension; each coordinate on its own). With the steps
/// `h_k = x_{k+1} − x_k` and secants `δ_k = (y_{k+1} − y_k)/h_k`:
///
/// - interior: `d_k = 0` where `δ_{k−1}`, `δ_k` differ in sign or one is zero, otherwise the
///   weighted harmonic mean `(w_1 + w_2)/d_k = w_1/δ_{k−1} + w_2/δ_k` with
///   `w_1 = 2h_k + h_{k−1}`, `w_2 = h_k + 2h_{k−1}` (Fritsch & Butland, SIAM J. Sci. Stat.
///   Comput. 5, 1984);
/// - ends: the one-sided three-point estimate `d_0 = ((2h_0 + h_1)δ_0 − h_0 δ_1)/(h_0 + h_1)`,
///   set to zero if its sign differs from `δ_0`'s, and to `3δ_0` if `δ_0`, `δ_1` differ in sign
///   and `|d_0| > 3|δ_0|` (Moler, *Numerical Computing with MATLAB*, §3.6, `pchiptx`); the
///   same mirrored at the right end;
/// - two points: both slopes the secant.
///
/// Monotone data give a monotone interpolant. These are the slopes of SciPy's
/// `PchipInterpolator` (`_find_derivatives`, `_edge_case`).
///
/// ```
/// use lekalo::{pchip_slopes, PointsRef};
/// let x = [0.0, 1.0, 2.0, 3.0];
/// let y = [0.0, 1.0, 1.0, 3.0];
/// let d = pchip_slopes(&x, PointsRef::from_flat(1, &y)?)?;
/// assert_eq!(d.as_slice()[1], 0.0); // a flat secant next to the point: a flat slope
/// # Ok::<(), lekalo::Error>(())
/// ```
///
/// # Errors
/// [`Error::TooFew`] for fewer than 2 points; [`Error::LengthMismatch`] if `x` and `y` differ
/// in length; [`Error::NonFinite`] for a NaN or infinite number; [`Error::InvalidArgument`] if
/// `x` is not strictly increasing.
pub fn pchip_slopes(x: &[f64], y: PointsRef<'_>) -> Result<Points> {
    check_function_data(x, y)?;
    let n = x.len();
    let dim = y.dim();
    let ys = y.as_slice();
    let mut d = vec![0.0; n * dim];
    let h: Vec<f64> = x.windows(2).map(|w| w[1] - w[0]).collect();
    for c in 0..dim {
        let m: Vec<f64> = (0..n - 1)
            .map(|k| (ys[(k + 1) * dim + c] - ys[k * dim + c]) / h[k])
            .collect();
        if n == 2 {
            d[c] = m[0];
            d[dim + c] = m[0];
            continue;
        }
        for k in 1..n - 1 {
            let (m0, m1) = (m[k - 1], m[k]);
            if sign(m0) != sign(m1) || m0 == 0.0 || m1 == 0.0 {
                continue;
            }
            let w1 = 2.0 * h[k] + h[k - 1];
            let w2 = h[k] + 2.0 * h[k - 1];
            let whmean = (w1 / m0 + w2 / m1) / (w1 + w2);
            d[k * dim + c] = 1.0 / whmean;
        }
        d[c] = edge(h[0], h[1], m[0], m[1]);
        d[(n - 1) * dim + c] = edge(h[n - 2], h[n - 3], m[n - 2], m[n - 3]);
    }
    check_finite("PCHIP slopes (overflow: rescale the data)", &d)?;
    Points::from_flat(dim, d)
}

/// [`pchip_slopes`] of values of dimension 1 written into `slopes` (`x.len()` numbers): the
/// same numbers, bit for bit, in one vectorised pass a block of points at a time (the steps and
/// secants of a block formed once, its harmonic means with 4-wide divisions where the processor
/// has AVX2), the checks of the data folded into that pass. O(n), no allocation. The kernel of
/// SciPy's `PchipInterpolator` in `lekalo.scipy`.
///
/// ```
/// use lekalo::{pchip_slopes, pchip_slopes_into, PointsRef};
/// let (x, y) = ([0.0, 1.0, 2.5, 3.0], [0.0, 1.0, 1.5, 4.0]);
/// let mut d = [0.0; 4];
/// pchip_slopes_into(&x, &y, &mut d)?;
/// assert_eq!(&d[..], pchip_slopes(&x, PointsRef::from_flat(1, &y)?)?.as_slice());
/// # Ok::<(), lekalo::Error>(())
/// ```
///
/// # Errors
/// Those of [`pchip_slopes`], and [`Error::LengthMismatch`] if `slopes` is not as long as `x`.
pub fn pchip_slopes_into(x: &[f64], y: &[f64], slopes: &mut [f64]) -> Result<()> {
    let n = x.len();
    if slopes.len() != n {
        return Err(Error::LengthMismatch {
            what: "PCHIP slopes (one per x)".into(),
            expected: n,
            got: slopes.len(),
        });
    }
    // `y` is checked where it is read (a number that is not finite named as `y`)
    let data = PointsRef::values(y);
    if n < 3 || y.len() != n {
        let d = pchip_slopes(x, data)?;
        slopes.copy_from_slice(d.as_slice());
        return Ok(());
    }
    let ok = pchip_interior(x, y, slopes) && (x[n - 1] - x[0]).is_finite();
    if !ok {
        // the first bad number named (an overflowing slope below, as pchip_slopes names it)
        check_function_data(x, data)?;
    }
    let (h0, h1) = (x[1] - x[0], x[2] - x[1]);
    let (m0, m1) = ((y[1] - y[0]) / h0, (y[2] - y[1]) / h1);
    slopes[0] = edge(h0, h1, m0, m1);
    let (h0, h1) = (x[n - 1] - x[n - 2], x[n - 2] - x[n - 3]);
    let (m0, m1) = ((y[n - 1] - y[n - 2]) / h0, (y[n - 2] - y[n - 3]) / h1);
    slopes[n - 1] = edge(h0, h1, m0, m1);
    if ok && slopes[0].is_finite() && slopes[n - 1].is_finite() {
        return Ok(());
    }
    // a value that is not finite, named as `y`; else a slope that overflowed
    check_function_data(x, data)?;
    check_finite("PCHIP slopes (overflow: rescale the data)", slopes)
}

/// Points a block of [`pchip_interior_body`].
const PCHIP_BLOCK: usize = 64;

/// The interior slopes `slopes[1 .. n − 1]` of [`pchip_slopes`] for values of dimension 1
/// (`n ≥ 3`), its arithmetic in its order. Returns whether every step is positive (false for
/// NaN), every value finite and every slope finite.
#[inline(always)]
fn pchip_interior_body(x: &[f64], y: &[f64], slopes: &mut [f64]) -> bool {
    let n = x.len();
    let mut bad = 0_u64;
    let (mut h, mut m) = ([0.0; PCHIP_BLOCK + 1], [0.0; PCHIP_BLOCK + 1]);
    let mut start = 1;
    while start + 1 < n {
        let len = PCHIP_BLOCK.min(n - 1 - start);
        // steps and secants of the intervals start − 1 ..= start + len − 1 (zipped slices of
        // one length, so that the loop is vectorised)
        let (x0, x1) = (&x[start - 1..start + len], &x[start..=start + len]);
        let (y0, y1) = (&y[start - 1..start + len], &y[start..=start + len]);
        for ((hj, mj), ((xa, xb), (ya, yb))) in h[..=len]
            .iter_mut()
            .zip(&mut m[..=len])
            .zip(x0.iter().zip(x1).zip(y0.iter().zip(y1)))
        {
            let step = xb - xa;
            *hj = step;
            *mj = (yb - ya) / step;
            bad |= u64::from(step.is_nan() | (step <= 0.0)) | u64::from(!ya.is_finite());
        }
        let out = &mut slopes[start..start + len];
        for (i, o) in out.iter_mut().enumerate() {
            let (m0, m1) = (m[i], m[i + 1]);
            let (h0, h1) = (h[i], h[i + 1]);
            let w1 = 2.0 * h1 + h0;
            let w2 = h1 + 2.0 * h0;
            let whmean = (w1 / m0 + w2 / m1) / (w1 + w2);
            // sign(m0) = sign(m1) and neither zero (NumPy's sign; NaN is caught by the flag)
            let same = (m0 > 0.0 && m1 > 0.0) || (m0 < 0.0 && m1 < 0.0);
            let d = if same { 1.0 / whmean } else { 0.0 };
            *o = d;
            bad |= u64::from(!d.is_finite());
        }
        start += len;
    }
    bad |= u64::from(!y[n - 1].is_finite());
    bad == 0
}

crate::numeric::isa::avx2_dispatch! {
    /// [`pchip_interior_body`] compiled with AVX2 where the processor has it, else as built
    /// ([`crate::numeric::isa`]: the same bits).
    fn pchip_interior(x: &[f64], y: &[f64], slopes: &mut [f64]) -> bool = pchip_interior_body;
}

/// NumPy's `sign`: −1, 0 or 1.
fn sign(v: f64) -> f64 {
    if v > 0.0 {
        1.0
    } else if v < 0.0 {
        -1.0
    } else {
        0.0
    }
}

/// Moler's shape-preserving one-sided three-point end slope (see [`pchip_slopes`]).
fn edge(h0: f64, h1: f64, m0: f64, m1: f64) -> f64 {
    let d = ((2.0 * h0 + h1) * m0 - h0 * m1) / (h0 + h1);
    if sign(d) != sign(m0) {
        0.0
    } else if sign(m0) != sign(m1) && d.abs() > 3.0 * m0.abs() {
        3.0 * m0
    } else {
        d
    }
}

/// The checks of function data `y(x)` that the slope rules share: at least two points, one
/// value per abscissa, finite numbers, strictly increasing `x`.
pub(crate) fn check_function_data(x: &[f64], y: PointsRef<'_>) -> Result<()> {
    let n = x.len();
    if n < 2 {
        return Err(Error::TooFew {
            what: "points (x)".into(),
            min: 2,
            got: n,
        });
    }
    if y.len() != n {
        return Err(Error::LengthMismatch {
            what: "y (one value per x)".into(),
            expected: n,
            got: y.len(),
        });
    }
    check_finite("x", x)?;
    check_finite("y", y.as_slice())?;
    if let Some(i) = x.windows(2).position(|w| w[1] <= w[0]) {
        return Err(Error::InvalidArgument {
            what: "x".into(),
            reason: format!(
                "must be strictly increasing, but x[{}] = {} follows x[{i}] = {}; sort the data \
                 and merge repeated abscissae",
                i + 1,
                readable(&x[i + 1]),
                readable(&x[i])
            ),
        });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn monotone_data_keep_monotone_slopes_and_errors_are_reported() {
        let x = [0.0, 0.5, 2.0, 3.0, 4.5];
        let y = [0.0, 0.1, 2.0, 2.0, 5.0];
        let d = pchip_slopes(&x, PointsRef::from_flat(1, &y).unwrap()).unwrap();
        assert!(d.as_slice().iter().all(|&s| s >= 0.0), "{d:?}");
        assert_eq!(d.as_slice()[2], 0.0, "flat secant on the right");
        assert_eq!(d.as_slice()[3], 0.0, "flat secant on the left");
        // two points: the secant
        let d = pchip_slopes(&[0.0, 2.0], PointsRef::from_flat(1, &[1.0, 5.0]).unwrap()).unwrap();
        assert_eq!(d.as_slice(), &[2.0, 2.0]);
        assert!(matches!(
            pchip_slopes(&[0.0], PointsRef::from_flat(1, &[1.0]).unwrap()),
            Err(Error::TooFew { .. })
        ));
        assert!(matches!(
            pchip_slopes(&[0.0, 0.0, 1.0], PointsRef::from_flat(1, &[1.0, 2.0, 3.0]).unwrap()),
            Err(Error::InvalidArgument { what, .. }) if what.words() == "x"
        ));
        assert!(matches!(
            pchip_slopes(
                &[0.0, f64::NAN],
                PointsRef::from_flat(1, &[1.0, 2.0]).unwrap()
            ),
            Err(Error::NonFinite { .. })
        ));
    }

    /// Data across the block size with flat stretches, sign changes and uneven steps.
    fn wiggly(n: usize) -> (Vec<f64>, Vec<f64>) {
        let x: Vec<f64> = (0..n)
            .map(|i| i as f64 + 0.4 * ((i as f64) * 2.1).sin())
            .collect();
        let y: Vec<f64> = (0..n)
            .map(|i| {
                if i % 17 < 3 {
                    1.0
                } else {
                    ((i as f64) * 0.3).sin() * 5.0
                }
            })
            .collect();
        (x, y)
    }

    #[test]
    fn slopes_into_are_pchip_slopes_bit_for_bit() {
        for n in [2, 3, 4, 64, 65, 66, 67, 200, 1001] {
            let (x, y) = wiggly(n);
            let mut d = vec![0.0; n];
            pchip_slopes_into(&x, &y, &mut d).unwrap();
            let want = pchip_slopes(&x, PointsRef::from_flat(1, &y).unwrap()).unwrap();
            let bits = |v: &[f64]| v.iter().map(|a| a.to_bits()).collect::<Vec<_>>();
            assert_eq!(bits(&d), bits(want.as_slice()), "n = {n}");
        }
    }

    #[test]
    fn slopes_into_refuse_what_pchip_slopes_refuses() {
        let (x, y) = wiggly(150);
        let mut d = vec![0.0; 150];
        let mut run = |x: &[f64], y: &[f64]| pchip_slopes_into(x, y, &mut d);
        let mut bad = y.clone();
        bad[140] = f64::NAN;
        assert!(matches!(
            run(&x, &bad),
            Err(Error::NonFinite { index: 140, .. })
        ));
        let mut xs = x.clone();
        xs[100] = xs[99];
        assert!(matches!(run(&xs, &y), Err(Error::InvalidArgument { .. })));
        xs[100] = f64::INFINITY;
        assert!(matches!(
            run(&xs, &y),
            Err(Error::NonFinite { index: 100, .. })
        ));
        assert!(matches!(
            pchip_slopes_into(&x[..1], &y[..1], &mut [0.0; 1]),
            Err(Error::TooFew { .. })
        ));
        assert!(matches!(
            run(&x, &y[..149]),
            Err(Error::LengthMismatch { .. })
        ));
        // slopes that overflow: named as pchip_slopes names them
        let (xs, ys) = ([0.0, 1e-300, 2e-300, 3e-300], [0.0, 1e300, 2e300, 2.5e300]);
        let mut d = [0.0; 4];
        let e = pchip_slopes_into(&xs, &ys, &mut d).unwrap_err();
        let want = pchip_slopes(&xs, PointsRef::from_flat(1, &ys).unwrap()).unwrap_err();
        assert_eq!(e, want);
        assert!(matches!(
            pchip_slopes_into(&xs, &ys, &mut [0.0; 3]),
            Err(Error::LengthMismatch { .. })
        ));
    }

    #[test]
    fn harmonic_mean_on_equal_steps() {
        // equal steps: w1 = w2, d = 2 δ0 δ1 / (δ0 + δ1)
        let d = pchip_slopes(
            &[0.0, 1.0, 2.0],
            PointsRef::from_flat(1, &[0.0, 1.0, 4.0]).unwrap(),
        )
        .unwrap();
        assert!((d.as_slice()[1] - 2.0 * 3.0 / 4.0).abs() < 1e-15);
    }

    /// A value that is not finite is named as `y` by the slopes written in place, wherever it
    /// lies (the ends included), as by the slopes of any dimension.
    #[test]
    fn a_value_that_is_not_finite_is_named_as_y() {
        let x = [0.0, 1.0, 2.0, 3.0, 4.0];
        for at in 0..5 {
            for bad in [f64::NAN, f64::INFINITY] {
                let mut y = [0.0, 1.0, 0.5, 2.0, 1.0];
                y[at] = bad;
                let mut d = [0.0; 5];
                let e = pchip_slopes_into(&x, &y, &mut d).unwrap_err();
                assert!(
                    matches!(&e, Error::NonFinite { index, .. } if *index == at)
                        && e.to_string().starts_with(&format!("y[{at}]")),
                    "{e}"
                );
                let e =
                    crate::interpolate::akima_slopes_into(&x, &y, at % 2 == 0, &mut d).unwrap_err();
                assert!(e.to_string().starts_with(&format!("y[{at}]")), "{e}");
            }
        }
    }
}
