//! Cubic Hermite data (values and slopes at increasing breakpoints) written straight into the
//! arrays of a cubic B-spline with double interior knots, in one pass
//! (docs/theory/interpolation.md#hermite-splines-and-tangent-estimates): the kernel of SciPy's
//! `CubicHermiteSpline`, `PchipInterpolator` and `Akima1DInterpolator` in `lekalo.scipy`, the
//! same numbers as [`crate::CubicHermite::to_bspline`] without the curve, its copies or its
//! checks of the output.

use crate::error::{Error, Result, MAX_SCALARS};
use crate::knots::check_breakpoints;

/// The number of knots and of control points of the cubic B-spline of Hermite data at `n`
/// breakpoints: `2n + 4` knots (`x_0` and `x_{n−1}` four times, every other breakpoint twice)
/// and `2n` control points.
#[must_use]
pub fn cubic_hermite_bspline_len(n: usize) -> (usize, usize) {
    (2 * n + 4, 2 * n)
}

/// Writes the cubic Hermite spline with values `y` and slopes `dydx` (each `n` rows of `dim`
/// numbers, row-major) at the strictly increasing breakpoints `x` as a cubic B-spline: the knots
/// `x_0` (×4), `x_1 … x_{n−2}` (×2 each, hence C¹), `x_{n−1}` (×4) into `knots` (length
/// `2n + 4`), and into `control` (`2n` rows of `dim`) the points `y_0`, then on every piece
/// `[x_k, x_{k+1}]` with `h_k = x_{k+1} − x_k` its two inner Bézier points
/// `y_k + h_k y'_k / 3` and `y_{k+1} − h_k y'_{k+1} / 3`, then `y_{n−1}` (Farin, *Curves and
/// Surfaces for CAGD*, 5th ed., §7.1: a C¹ piecewise cubic's B-spline coefficients on double
/// knots are its Bézier points without the junctions). O(n·dim), one pass, no allocation.
///
/// ```
/// use lekalo::pp::cubic_hermite_bspline_into;
/// // y = x² on [0, 1, 2], slopes 2x
/// let (mut t, mut c) = (vec![0.0; 10], vec![0.0; 6]);
/// cubic_hermite_bspline_into(&[0.0, 1.0, 2.0], &[0.0, 1.0, 4.0], &[0.0, 2.0, 4.0], 1, &mut t, &mut c)?;
/// assert_eq!(t, [0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 2.0, 2.0, 2.0, 2.0]);
/// assert_eq!(c, [0.0, 0.0, 1.0 - 2.0 / 3.0, 1.0 + 2.0 / 3.0, 4.0 - 4.0 / 3.0, 4.0]);
/// # Ok::<(), lekalo::Error>(())
/// ```
///
/// # Errors
/// [`Error::TooFew`] for fewer than 2 breakpoints; [`Error::InvalidArgument`] for breakpoints
/// that are not finite and strictly increasing, or `dim = 0`; [`Error::LengthMismatch`] when
/// `y`, `dydx`, `knots` or `control` do not have the lengths above; [`Error::NonFinite`] for a
/// value or slope that is not finite.
pub fn cubic_hermite_bspline_into(
    x: &[f64],
    y: &[f64],
    dydx: &[f64],
    dim: usize,
    knots: &mut [f64],
    control: &mut [f64],
) -> Result<()> {
    let n = x.len();
    let rows = hermite_rows(x, dim, 2)?;
    let (n_knots, n_ctrl) = cubic_hermite_bspline_len(n);
    for (what, expected, got) in [
        ("Hermite values (breakpoints × dimension)", rows, y.len()),
        ("Hermite slopes (breakpoints × dimension)", rows, dydx.len()),
        ("B-spline knots (2 × breakpoints + 4)", n_knots, knots.len()),
        (
            "B-spline coefficients (2 × breakpoints × dimension)",
            n_ctrl * dim,
            control.len(),
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
    knots[..4].fill(x[0]);
    for (pair, &b) in knots[4..n_knots - 4].chunks_exact_mut(2).zip(&x[1..n - 1]) {
        pair.fill(b);
    }
    knots[n_knots - 4..].fill(x[n - 1]);
    if dim == 1 {
        // the checks folded into the pass that writes the coefficients; on failure the
        // checks below name the first bad number
        if hermite_scalar_pass(x, y, dydx, control) && (x[n - 1] - x[0]).is_finite() {
            return Ok(());
        }
    }
    check_hermite_numbers(x, y, dydx)?;
    control[..dim].copy_from_slice(&y[..dim]);
    let inner = &mut control[dim..(n_ctrl - 1) * dim];
    for (k, seg) in inner.chunks_exact_mut(2 * dim).enumerate() {
        let h = x[k + 1] - x[k];
        let (y0, y1) = (&y[k * dim..(k + 1) * dim], &y[(k + 1) * dim..(k + 2) * dim]);
        let (d0, d1) = (
            &dydx[k * dim..(k + 1) * dim],
            &dydx[(k + 1) * dim..(k + 2) * dim],
        );
        let (b1, b2) = seg.split_at_mut(dim);
        for i in 0..dim {
            // the arithmetic of CubicHermite::to_bspline, so that both give the same numbers
            b1[i] = y0[i] + h * d0[i] / 3.0;
            b2[i] = y1[i] - h * d1[i] / 3.0;
        }
    }
    control[(n_ctrl - 1) * dim..].copy_from_slice(&y[(n - 1) * dim..]);
    Ok(())
}

/// Pieces a block of [`hermite_scalar_body`]: the inner Bézier points of this many pieces are
/// formed in two stack arrays (4-wide divisions with AVX2), then interleaved into the output.
const HERMITE_BLOCK: usize = 64;

/// The coefficients of values of dimension 1 (`control`: `2n` numbers), the arithmetic of the
/// general loop of [`cubic_hermite_bspline_into`] (the same bits), a block of pieces at a
/// time so that the two divisions a piece are vectorised. Returns whether every step
/// `x_{k+1} − x_k` is positive (false for NaN) and every value and slope finite; `x_0` and
/// `x_{n−1}` finite then follows from a finite `x_{n−1} − x_0`, which the caller checks.
#[inline(always)]
fn hermite_scalar_body(x: &[f64], y: &[f64], dydx: &[f64], control: &mut [f64]) -> bool {
    let n = x.len();
    let mut bad = 0_u64;
    let (mut b1, mut b2) = ([0.0; HERMITE_BLOCK], [0.0; HERMITE_BLOCK]);
    let mut start = 0;
    while start + 1 < n {
        let m = HERMITE_BLOCK.min(n - 1 - start);
        let xs = &x[start..=start + m];
        let ys = &y[start..=start + m];
        let ds = &dydx[start..=start + m];
        for i in 0..m {
            let h = xs[i + 1] - xs[i];
            b1[i] = ys[i] + h * ds[i] / 3.0;
            b2[i] = ys[i + 1] - h * ds[i + 1] / 3.0;
            bad |= u64::from(h.is_nan() | (h <= 0.0))
                | u64::from(!ys[i].is_finite())
                | u64::from(!ds[i].is_finite());
        }
        let out = &mut control[2 * start + 1..2 * (start + m) + 1];
        for (pair, (p, q)) in out.chunks_exact_mut(2).zip(b1[..m].iter().zip(&b2[..m])) {
            pair[0] = *p;
            pair[1] = *q;
        }
        start += m;
    }
    bad |= u64::from(!y[n - 1].is_finite()) | u64::from(!dydx[n - 1].is_finite());
    control[0] = y[0];
    control[2 * n - 1] = y[n - 1];
    bad == 0
}

crate::numeric::isa::avx2_dispatch! {
    /// [`hermite_scalar_body`] compiled with AVX2 where the processor has it, else as built
    /// ([`crate::numeric::isa`]: the same bits).
    fn hermite_scalar_pass(x: &[f64], y: &[f64], dydx: &[f64], control: &mut [f64]) -> bool = hermite_scalar_body;
}

/// The number of scalars in `y` (and in `dydx`) of Hermite data at the breakpoints `x` of
/// dimension `dim`, checked before anything is allocated or written: at least 2 breakpoints,
/// `dim ≥ 1`, and `n·dim·per_row` within [`MAX_SCALARS`] (`per_row`: the output's scalars per
/// input scalar), shared by the Hermite kernels of this folder.
///
/// # Errors
/// [`Error::TooFew`] or [`Error::InvalidArgument`] as [`check_breakpoints`] for fewer than 2
/// breakpoints; [`Error::InvalidArgument`] for `dim = 0` or a size over the limit.
pub(super) fn hermite_rows(x: &[f64], dim: usize, per_row: usize) -> Result<usize> {
    let n = x.len();
    if n < 2 {
        check_breakpoints(x)?;
    }
    if dim == 0 {
        return Err(Error::InvalidArgument {
            what: "Hermite values".into(),
            reason: "the dimension is 0; pass at least one column of values".into(),
        });
    }
    let rows = n.checked_mul(dim).filter(|&r| r <= MAX_SCALARS / per_row);
    rows.ok_or_else(|| Error::InvalidArgument {
        what: "Hermite values".into(),
        reason: format!("{n} breakpoints of dimension {dim} exceed the size limit"),
    })
}

/// The checks of Hermite data's numbers that the kernels' passes do not fold in: breakpoints
/// finite and strictly increasing ([`check_breakpoints`]), then every value and slope finite,
/// the first bad one named.
///
/// # Errors
/// As [`check_breakpoints`]; [`Error::NonFinite`] for a value or slope that is not finite.
pub(super) fn check_hermite_numbers(x: &[f64], y: &[f64], dydx: &[f64]) -> Result<()> {
    check_breakpoints(x)?;
    for (what, v) in [("Hermite values", y), ("Hermite slopes", dydx)] {
        if let Some(index) = v.iter().position(|a| !a.is_finite()) {
            return Err(Error::NonFinite {
                what: what.into(),
                index,
                value: v[index],
            });
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{CubicHermite, Points};

    #[test]
    fn same_numbers_as_the_hermite_curve() {
        let x = [0.0, 0.5, 1.7, 2.0, 3.5];
        let y: Vec<f64> = (0..10).map(|i| f64::from(i).sin()).collect();
        let d: Vec<f64> = (0..10).map(|i| f64::from(i).cos() * 3.0).collect();
        let curve = CubicHermite::new(
            x.to_vec(),
            Points::from_flat(2, y.clone()).unwrap(),
            Points::from_flat(2, d.clone()).unwrap(),
        )
        .unwrap()
        .to_bspline();
        let (nk, nc) = cubic_hermite_bspline_len(5);
        let (mut t, mut c) = (vec![0.0; nk], vec![0.0; nc * 2]);
        cubic_hermite_bspline_into(&x, &y, &d, 2, &mut t, &mut c).unwrap();
        assert_eq!(t.as_slice(), curve.knots().as_slice());
        assert_eq!(c.as_slice(), curve.control_points().as_slice());
    }

    #[test]
    fn the_pass_of_dimension_one_is_the_general_loop_bit_for_bit() {
        // a dimension-2 call takes the general loop: two equal columns give the numbers the
        // one-column pass must give; lengths across the block size
        for n in [2, 3, 64, 65, 66, 130, 200] {
            let x: Vec<f64> = (0..n)
                .map(|i| f64::from(i) * 0.7 + (f64::from(i) * 1.3).sin() * 0.2)
                .collect();
            let y: Vec<f64> = (0..n).map(|i| (f64::from(i) * 0.37).cos() * 1e3).collect();
            let d: Vec<f64> = (0..n).map(|i| (f64::from(i) * 0.11).sin() / 7.0).collect();
            let twice = |v: &[f64]| v.iter().flat_map(|&a| [a, a]).collect::<Vec<_>>();
            let (nk, nc) = cubic_hermite_bspline_len(n as usize);
            let (mut t1, mut c1) = (vec![0.0; nk], vec![0.0; nc]);
            let (mut t2, mut c2) = (vec![0.0; nk], vec![0.0; 2 * nc]);
            cubic_hermite_bspline_into(&x, &y, &d, 1, &mut t1, &mut c1).unwrap();
            cubic_hermite_bspline_into(&x, &twice(&y), &twice(&d), 2, &mut t2, &mut c2).unwrap();
            assert_eq!(t1, t2, "n = {n}");
            let first: Vec<f64> = c2.iter().step_by(2).copied().collect();
            assert_eq!(
                c1.iter().map(|v| v.to_bits()).collect::<Vec<_>>(),
                first.iter().map(|v| v.to_bits()).collect::<Vec<_>>(),
                "n = {n}"
            );
        }
    }

    #[test]
    fn the_pass_of_dimension_one_names_the_first_bad_number() {
        let n = 100;
        let x: Vec<f64> = (0..n).map(f64::from).collect();
        let ok = vec![1.0; n as usize];
        let (nk, nc) = cubic_hermite_bspline_len(n as usize);
        let (mut t, mut c) = (vec![0.0; nk], vec![0.0; nc]);
        let mut run = |x: &[f64], y: &[f64], d: &[f64]| {
            cubic_hermite_bspline_into(x, y, d, 1, &mut t, &mut c)
        };
        let mut bad = ok.clone();
        bad[70] = f64::INFINITY;
        assert!(matches!(
            run(&x, &bad, &ok),
            Err(Error::NonFinite { index: 70, .. })
        ));
        bad[99] = f64::NAN;
        bad[70] = 1.0;
        assert!(matches!(
            run(&x, &ok, &bad),
            Err(Error::NonFinite { index: 99, .. })
        ));
        let mut xs = x.clone();
        xs[80] = xs[79];
        assert!(matches!(
            run(&xs, &ok, &ok),
            Err(Error::InvalidArgument { .. })
        ));
        xs[80] = f64::NAN;
        assert!(matches!(
            run(&xs, &ok, &ok),
            Err(Error::NonFinite { index: 80, .. })
        ));
        let mut xs = x.clone();
        xs[0] = f64::NEG_INFINITY;
        assert!(run(&xs, &ok, &ok).is_err());
        xs[0] = -1.7e308;
        xs[99] = 1.7e308;
        assert!(
            matches!(run(&xs, &ok, &ok), Err(Error::InvalidArgument { .. })),
            "the width overflows"
        );
    }

    #[test]
    fn two_breakpoints_make_one_bezier_piece() {
        let (mut t, mut c) = (vec![0.0; 8], vec![0.0; 4]);
        cubic_hermite_bspline_into(&[1.0, 4.0], &[2.0, 5.0], &[3.0, 0.0], 1, &mut t, &mut c)
            .unwrap();
        assert_eq!(t, [1.0, 1.0, 1.0, 1.0, 4.0, 4.0, 4.0, 4.0]);
        assert_eq!(c, [2.0, 5.0, 5.0, 5.0]);
    }

    #[test]
    fn refuses_bad_input() {
        let (mut t, mut c) = (vec![0.0; 10], vec![0.0; 6]);
        let x = [0.0, 1.0, 2.0];
        let ok = [0.0, 1.0, 2.0];
        let err = |x: &[f64], y: &[f64], d: &[f64], t: &mut [f64], c: &mut [f64]| {
            cubic_hermite_bspline_into(x, y, d, 1, t, c).unwrap_err()
        };
        assert!(matches!(
            err(&[0.0, 0.0, 1.0], &ok, &ok, &mut t, &mut c),
            Error::InvalidArgument { .. }
        ));
        assert!(matches!(
            err(&[0.0], &ok[..1], &ok[..1], &mut t, &mut c),
            Error::TooFew { .. }
        ));
        assert!(matches!(
            err(&x, &ok[..2], &ok, &mut t, &mut c),
            Error::LengthMismatch { .. }
        ));
        assert!(matches!(
            err(&x, &ok, &[0.0, f64::NAN, 0.0], &mut t, &mut c),
            Error::NonFinite { index: 1, .. }
        ));
        assert!(matches!(
            err(&x, &ok, &ok, &mut t[..9], &mut c),
            Error::LengthMismatch { .. }
        ));
        assert!(matches!(
            cubic_hermite_bspline_into(&x, &[], &[], 0, &mut t, &mut c),
            Err(Error::InvalidArgument { .. })
        ));
    }
}
