//! Evaluation, JVP and VJP of a few parameters on borrowed knots, control points (and weights):
//! nothing is copied and only the numbers the values need are read and checked
//! (`docs/theory/derivatives.md`). Building a curve validates every knot and control point,
//! O(n) work a call, which dominates when a handful of parameters is evaluated on a long curve;
//! here each parameter reads and checks its span's `2p + 2` knots and `p + 1` control points.
//!
//! - `curve.rs`: [`BorrowedCurve`], a B-spline curve;
//! - `nurbs.rs`: [`BorrowedNurbs`], a NURBS curve (also its `p + 1` weights a parameter);
//! - `surface.rs`: [`BorrowedSurface`], a tensor-product B-spline surface (a pair reads
//!   `2p + 2` and `2q + 2` knots and a `(p + 1) × (q + 1)` block of the net);
//! - `tensor.rs`: [`BorrowedTensor`], a tensor-product B-spline in `N` variables (a point
//!   reads `2p_a + 2` knots a direction and a `Π_a (p_a + 1)` block of the net);
//! - `test_nets.rs` (tests only): the knot vectors and nets of the surface and tensor tests.
//!
//! What they share is here: the O(1) checks of a curve's counts, the location of a parameter's
//! span with the checks of its knots, and the gather and scatter of a block of a net.

mod curve;
mod nurbs;
mod surface;
mod tensor;
#[cfg(test)]
mod test_nets;

pub use curve::BorrowedCurve;
pub use nurbs::BorrowedNurbs;
pub use surface::BorrowedSurface;
pub use tensor::BorrowedTensor;

use crate::derivatives::checks::check_len;
use crate::error::{Error, Result};
use crate::knots::{span_by, too_few_for_degree};
use crate::{Arg, What};

/// The number of control points `n` of `control` (`dim` numbers a point) after the O(1) checks
/// of the counts: `dim ≥ 1`, whole points, `n ≥ p + 1`, `n + p + 1` knots.
///
/// # Errors
/// [`Error::Dimension`] for `dim = 0`; [`Error::LengthMismatch`] for a partial point or a
/// wrong number of knots; [`Error::Degree`] for fewer than `p + 1` control points.
fn window_counts(degree: usize, knots: &[f64], control: &[f64], dim: usize) -> Result<usize> {
    if dim == 0 {
        return Err(Error::Dimension {
            what: Arg::ControlPoints.into(),
            expected: 1,
            got: 0,
        });
    }
    let n = control.len() / dim;
    check_len(Arg::ControlPoints, n * dim, control.len())?;
    if n <= degree {
        return Err(too_few_for_degree(n, degree));
    }
    let expected = n.saturating_add(degree).saturating_add(1);
    check_len(
        What::of(Arg::Knots, "knots (control points + degree + 1)"),
        expected,
        knots.len(),
    )?;
    Ok(n)
}

/// The span `i` of `t` (`t_i ≤ t ≤ t_{i+1}`, `t_i < t_{i+1}`) on `knots` (`n + p + 1`, checked
/// by [`window_counts`]) after checking `t` in the domain `[t_p, t_n]` and the span's knots
/// `t_{i−p} ..= t_{i+p+1}` finite and non-decreasing. The errors are local (the caller
/// explains them by the whole input's): [`Error::ParameterOutOfDomain`], or
/// [`invalid_span`].
#[allow(clippy::neg_cmp_op_on_partial_ord)] // NaN must fail every comparison
fn locate_span(k: &[f64], p: usize, n: usize, t: f64) -> Result<usize> {
    let (min, max) = (k[p], k[n]);
    if !(min < max && t >= min && t <= max) {
        return Err(Error::ParameterOutOfDomain { t, min, max });
    }
    let i = span_by(&|j| k[j], p, n, t);
    // i in p..n, so i − p ≥ 0 and i + p + 1 ≤ n + p = len − 1
    let window = &k[i - p..=i + p + 1];
    let sorted = window.iter().all(|x| x.is_finite())
        && window.windows(2).all(|w| w[0] <= w[1])
        && k[i] < k[i + 1]
        && k[i] <= t
        && (t < k[i + 1] || t == max);
    if !sorted {
        return Err(invalid_span(t));
    }
    Ok(i)
}

/// The local error of a span whose knots or control points are not valid.
fn invalid_span(t: f64) -> Error {
    Error::InvalidArgument {
        what: Arg::Knots.into(),
        reason: format!("the knots around t = {t} are not a valid span"),
    }
}

/// Calls `f(offset, k)` for the `k`-th point of the block `first_a ..= first_a + widths_a − 1`
/// (every direction `a`) of a point-major net whose direction `a` has `strides[a]` numbers
/// between consecutive indices, in the net's order (the last direction fastest): `offset` is
/// the point's first number in the net. The block is in the net (the spans located by
/// [`locate_span`] keep `first_a + widths_a ≤ n_a`).
fn for_each_block_point(
    first: &[usize],
    widths: &[usize],
    strides: &[usize],
    mut f: impl FnMut(usize, usize),
) {
    let mut odometer = vec![0usize; first.len()];
    let mut k = 0;
    loop {
        let offset = odometer
            .iter()
            .zip(first)
            .zip(strides)
            .map(|((i, f), s)| (f + i) * s)
            .sum();
        f(offset, k);
        k += 1;
        // advance the last direction fastest
        let mut a = odometer.len();
        loop {
            if a == 0 {
                return;
            }
            a -= 1;
            odometer[a] += 1;
            if odometer[a] < widths[a] {
                break;
            }
            odometer[a] = 0;
        }
    }
}

/// The block of the net `net` at `first` of `widths` points a direction (`dim` numbers a
/// point, `strides` as [`for_each_block_point`]), copied in the net's order: the net of the
/// local spline.
fn gather_block(
    net: &[f64],
    dim: usize,
    first: &[usize],
    widths: &[usize],
    strides: &[usize],
) -> Vec<f64> {
    let mut block = Vec::with_capacity(widths.iter().product::<usize>() * dim);
    for_each_block_point(first, widths, strides, |o, _| {
        block.extend_from_slice(&net[o..o + dim]);
    });
    block
}

/// `net[block] += local`: a local net's cotangent summed into the whole net's, point by point
/// (as [`gather_block`] lays the block out).
fn add_block(
    local: &[f64],
    dim: usize,
    first: &[usize],
    widths: &[usize],
    strides: &[usize],
    net: &mut [f64],
) {
    for_each_block_point(first, widths, strides, |o, k| {
        for (x, l) in net[o..o + dim]
            .iter_mut()
            .zip(&local[k * dim..(k + 1) * dim])
        {
            *x += l;
        }
    });
}
