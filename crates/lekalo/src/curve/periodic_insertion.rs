//! Knot insertion into a spline given by its raw knots and coefficients, as FITPACK's `fpinst`
//! does it (Dierckx, *Curve and Surface Fitting with Splines*, 1993): for a periodic spline
//! with its periodic extension (`iopt = 1`, docs/theory/curves.md#periodic-knot-insertion),
//! and without it, at any multiplicity (`iopt = 0`,
//! docs/theory/curves.md#knot-insertion-on-raw-knots).

use crate::error::readable;
use crate::error::{check_finite, Error, Result, MAX_SCALARS};
use crate::knots::{check_gap, KnotVector};
use crate::points::{Points, PointsRef};
use crate::Arg;

/// Inserts `x` `times` times into the periodic spline of degree `k` with the knots `knots`
/// (`n` of them, base interval `[t_k, t_{n−k−1}]`) and the `n − k − 1` coefficients `control`,
/// one knot at a time: Boehm's insertion of `x` in its knot interval `t_l ≤ x < t_{l+1}`
/// (`t_{n−k−2} ≤ x ≤ t_{n−k−1}` at the right end), then the periodic extension restored. If
/// the new knot lies among the last `k + 1` knot intervals of the base interval, the first `k`
/// coefficients are set to the `k` that follow the base interval's period, and the `k` knots
/// before the base interval to the `k` before its end minus the period `T = t_{n−k−1} − t_k`;
/// otherwise, if it lies among the first `k + 1`, the `k` coefficients after the period and the
/// `k` knots after the base interval are set from the first ones (plus `T`). A spline whose
/// knots and coefficients are periodic in this sense stays the same function; on others the
/// result is FITPACK's (`scipy.interpolate.insert(..., per=True)`,
/// `BSpline.insert_knot` with `extrapolate="periodic"`). Returns the `n + times` knots and the
/// `n + times − k − 1` coefficients.
///
/// ```
/// use lekalo::{insert_knot_periodic, PointsRef};
/// // the periodic linear spline with coefficients 0, 1, 0 over the period [0, 2]
/// let t = [-1.0, 0.0, 1.0, 2.0, 3.0];
/// let c = [1.0, 0.0, 1.0];
/// let (t2, c2) = insert_knot_periodic(1, &t, PointsRef::from_flat(1, &c)?, 0.5, 1)?;
/// // the knot after the period follows the new one: 0.5 + 2
/// assert_eq!(t2, vec![-1.0, 0.0, 0.5, 1.0, 2.0, 2.5]);
/// assert_eq!(c2.as_slice(), &[1.0, 0.5, 0.0, 1.0]);
/// # Ok::<(), lekalo::Error>(())
/// ```
///
/// # Errors
/// [`Error::Degree`] for `k = 0` or too few knots for degree `k`; knot-vector errors
/// ([`Error::KnotsNotSorted`], [`Error::NonFinite`]); [`Error::LengthMismatch`] unless there
/// are `n − k − 1` coefficients; [`Error::ParameterOutOfDomain`] for `x` outside the base
/// interval; [`Error::InvalidArgument`] if `x` falls in an empty knot interval, or if there are
/// too few interior knots on either side of it to restore the periodic extension (the new knot
/// must have more than `2k` knots before it or more than `2k` after it); [`Error::TooLarge`].
pub fn insert_knot_periodic(
    k: usize,
    knots: &[f64],
    control: PointsRef<'_>,
    x: f64,
    times: usize,
) -> Result<(Vec<f64>, Points)> {
    insert_repeatedly(k, knots, control, x, times, true)
}

/// Inserts `x` `times` times into the spline of degree `k` with the knots `knots` (`n` of them,
/// base interval `[t_k, t_{n−k−1}]`) and the `n − k − 1` coefficients `control`, one knot at a
/// time by Boehm's insertion in the knot interval `t_l ≤ x < t_{l+1}` (`t_{n−k−2} ≤ x ≤
/// t_{n−k−1}` at the right end; where that interval is empty, `t_l < x ≤ t_{l+1}`, so that the
/// right end can be inserted again): FITPACK's `insert` and `fpinst` with `iopt = 0`
/// (docs/theory/curves.md#knot-insertion-on-raw-knots), `scipy.interpolate.insert`. Unlike
/// [`BSplineCurve::insert_knot`](crate::BSplineCurve::insert_knot) it puts no bound on the
/// multiplicity: at an end of the base interval the knot may pass multiplicity `k + 1` (the
/// function on the base interval is unchanged; the new knots lie at the end and the new
/// coefficients continue the end coefficient), and inside it may pass `k` (the spline stays the
/// same function, piecewise; its continuity at `x` is what the knots say). Returns the
/// `n + times` knots and the `n + times − k − 1` coefficients.
///
/// ```
/// use lekalo::{insert_knot_raw, PointsRef};
/// // the linear spline 0 → 1 on [0, 1], the knot 0 inserted past multiplicity k + 1 = 2
/// let t = [0.0, 0.0, 1.0, 1.0];
/// let c = [0.0, 1.0];
/// let (t2, c2) = insert_knot_raw(1, &t, PointsRef::from_flat(1, &c)?, 0.0, 1)?;
/// assert_eq!(t2, vec![0.0, 0.0, 0.0, 1.0, 1.0]);
/// assert_eq!(c2.as_slice(), &[0.0, 0.0, 1.0]);
/// # Ok::<(), lekalo::Error>(())
/// ```
///
/// # Errors
/// [`Error::Degree`] for `k = 0` or too few knots for degree `k`; knot-vector errors
/// ([`Error::KnotsNotSorted`], [`Error::NonFinite`]); [`Error::LengthMismatch`] unless there
/// are `n − k − 1` coefficients; [`Error::ParameterOutOfDomain`] for `x` outside the base
/// interval; [`Error::InvalidArgument`] if `x` falls in an empty knot interval;
/// [`Error::TooLarge`].
pub fn insert_knot_raw(
    k: usize,
    knots: &[f64],
    control: PointsRef<'_>,
    x: f64,
    times: usize,
) -> Result<(Vec<f64>, Points)> {
    insert_repeatedly(k, knots, control, x, times, false)
}

/// The checks and the loop of [`insert_knot_periodic`] and [`insert_knot_raw`].
fn insert_repeatedly(
    k: usize,
    knots: &[f64],
    control: PointsRef<'_>,
    x: f64,
    times: usize,
    periodic: bool,
) -> Result<(Vec<f64>, Points)> {
    check_insertion(
        k,
        knots,
        (control.len(), control.dim()),
        times,
        Checks::Whole,
    )?;
    let (n, dim) = (knots.len(), control.dim());
    let mut t = vec![0.0; n + times];
    let mut c = vec![0.0; (n + times - k - 1) * dim];
    insert_checked_into(
        k,
        knots,
        control.as_slice(),
        dim,
        x,
        times,
        periodic,
        Checks::Whole,
        &mut t,
        &mut c,
    )?;
    Ok((t, Points::from_raw(c, dim)))
}

/// What the insertion functions check of the spline they are given.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Checks {
    /// The whole knot vector (finite, sorted, a non-empty domain) and every coefficient of the
    /// result finite: the functions that return a new spline.
    Whole,
    /// What the insertion reads: the knots of the interval of `x` and the `2k` around it that
    /// Boehm's weights use (and, periodic, the `2k + 2` at each end that carry the period),
    /// finite and non-decreasing, and the `k` new coefficients finite; the others are copied
    /// as they are, as FITPACK copies them (SciPy's `insert` layout, O(k) checks on top of
    /// the copy).
    Read,
}

/// The checks of the insertion functions: degree, knots ([`Checks`]), coefficient count,
/// result size.
fn check_insertion(
    k: usize,
    knots: &[f64],
    (rows, dim): (usize, usize),
    times: usize,
    checks: Checks,
) -> Result<()> {
    let n = knots.len();
    if k == 0 || n < 2 * k + 2 {
        return Err(Error::Degree {
            degree: k,
            reason: format!(
                "knot insertion needs degree k ≥ 1 and at least 2k + 2 knots, got {n} knots"
            ),
        });
    }
    if checks == Checks::Whole {
        KnotVector::check_values(knots)?;
    }
    if rows != n - k - 1 {
        return Err(Error::LengthMismatch {
            what: "coefficients (knots − degree − 1)".into(),
            expected: n - k - 1,
            got: rows,
        });
    }
    let total = n
        .checked_add(times)
        .filter(|v| v.checked_mul(dim + 1).is_some_and(|s| s <= MAX_SCALARS));
    if total.is_none() {
        return Err(Error::TooLarge {
            what: "knots after insertion".into(),
            size: usize::MAX,
            max: MAX_SCALARS,
        });
    }
    Ok(())
}

/// [`insert_knot_raw`] (or, with `periodic`, [`insert_knot_periodic`]) written into the caller's
/// buffers, SciPy's layout: the coefficients `control` are `n − k − 1` rows of `dim` numbers
/// (SciPy's array, not a checked [`PointsRef`]); `out_knots` takes the `n + times` knots,
/// `out_control` at least `n + times − k − 1` rows, the new coefficients and then zeros
/// (`scipy.interpolate.insert` pads the coefficients to the knots' length). The spline is read
/// in place; with `times = 1` nothing else is allocated. What the insertion reads is checked,
/// not the whole spline: the knots of the interval of `x` and the `2k` around it (with
/// `periodic`, also the `2k + 2` at each end), and the `k` new coefficients; the other knots
/// and coefficients are copied as they are, as FITPACK's `insert` copies them, so that the call
/// is the copy plus O(k log n) work (on knots that are not sorted elsewhere the interval found
/// is not `x`'s: sort them first).
///
/// ```
/// use lekalo::insert_knot_into;
/// let t = [0.0, 0.0, 1.0, 1.0];
/// let (mut t2, mut c2) = ([0.0; 5], [f64::NAN; 5]);
/// insert_knot_into(1, &t, &[0.0, 1.0], 1, 0.5, 1, false, &mut t2, &mut c2)?;
/// assert_eq!(t2, [0.0, 0.0, 0.5, 1.0, 1.0]);
/// assert_eq!(c2, [0.0, 0.5, 1.0, 0.0, 0.0]);
/// # Ok::<(), lekalo::Error>(())
/// ```
///
/// # Errors
/// As [`insert_knot_raw`], the knot-vector errors ([`Error::KnotsNotSorted`],
/// [`Error::NonFinite`]) for the knots read and [`Error::NonFinite`] for a new coefficient;
/// [`Error::Dimension`] for `dim = 0` or coefficients that are not whole rows;
/// [`Error::LengthMismatch`] for buffers of other sizes.
#[allow(clippy::too_many_arguments)] // the spline, the insertion and the two buffers
pub fn insert_knot_into(
    k: usize,
    knots: &[f64],
    control: &[f64],
    dim: usize,
    x: f64,
    times: usize,
    periodic: bool,
    out_knots: &mut [f64],
    out_control: &mut [f64],
) -> Result<()> {
    if dim == 0 || control.len() % dim != 0 {
        return Err(Error::Dimension {
            what: "coefficients (length is not a multiple of the dimension)".into(),
            expected: dim.max(1),
            got: control.len(),
        });
    }
    check_insertion(k, knots, (control.len() / dim, dim), times, Checks::Read)?;
    let n = knots.len();
    let rows = n + times - k - 1;
    if out_knots.len() != n + times {
        return Err(Error::LengthMismatch {
            what: "knot buffer (knots + insertions)".into(),
            expected: n + times,
            got: out_knots.len(),
        });
    }
    if out_control.len() < rows * dim || out_control.len() % dim != 0 {
        return Err(Error::LengthMismatch {
            what: "coefficient buffer (rows × dimension, at least the coefficients)".into(),
            expected: rows * dim,
            got: out_control.len(),
        });
    }
    let (head, tail) = out_control.split_at_mut(rows * dim);
    tail.fill(0.0);
    insert_checked_into(
        k,
        knots,
        control,
        dim,
        x,
        times,
        periodic,
        Checks::Read,
        out_knots,
        head,
    )
}

/// `times` insertions of `x` into checked input, the last one into `out_t` and `out_c` (of
/// exactly `n + times` knots and `n + times − k − 1` rows), the others into held buffers.
#[allow(clippy::too_many_arguments)]
fn insert_checked_into(
    k: usize,
    knots: &[f64],
    control: &[f64],
    dim: usize,
    x: f64,
    times: usize,
    periodic: bool,
    checks: Checks,
    out_t: &mut [f64],
    out_c: &mut [f64],
) -> Result<()> {
    if times == 0 {
        out_t.copy_from_slice(knots);
        out_c.copy_from_slice(control);
        return Ok(());
    }
    let mut held: Option<(Vec<f64>, Vec<f64>)> = None;
    for _ in 1..times {
        let (t, c) = held
            .as_ref()
            .map_or((knots, control), |(t, c)| (t.as_slice(), c.as_slice()));
        let mut tt = vec![0.0; t.len() + 1];
        let mut cc = vec![0.0; c.len() + dim];
        insert_once_into(k, t, c, dim, x, periodic, checks, &mut tt, &mut cc)?;
        held = Some((tt, cc));
    }
    let (t, c) = held
        .as_ref()
        .map_or((knots, control), |(t, c)| (t.as_slice(), c.as_slice()));
    insert_once_into(k, t, c, dim, x, periodic, checks, out_t, out_c)?;
    if checks == Checks::Whole {
        check_finite("coefficients after insertion", out_c)?;
    }
    Ok(())
}

/// The knots `t[from..to]` finite and non-decreasing, or the error naming the first that is
/// not (its index in the whole vector).
fn check_knot_window(t: &[f64], from: usize, to: usize) -> Result<()> {
    let window = &t[from..to];
    if let Some(i) = window.iter().position(|v| !v.is_finite()) {
        return Err(Error::NonFinite {
            what: Arg::Knots.into(),
            index: from + i,
            value: window[i],
        });
    }
    if let Some(i) = window.windows(2).position(|w| w[1] < w[0]) {
        return Err(Error::KnotsNotSorted {
            index: from + i + 1,
            value: window[i + 1],
            previous: window[i],
        });
    }
    Ok(())
}

/// One insertion (FITPACK's `insert` and `fpinst` with `iopt = 1` when `periodic`, else
/// `iopt = 0`), in 0-based indices: `l` is the knot interval `t_l ≤ x < t_{l+1}`,
/// `k ≤ l ≤ n − k − 2`.
#[allow(clippy::too_many_arguments)]
fn insert_once_into(
    k: usize,
    t: &[f64],
    c: &[f64],
    dim: usize,
    x: f64,
    periodic: bool,
    checks: Checks,
    tt: &mut [f64],
    cc: &mut [f64],
) -> Result<()> {
    let n = t.len();
    let (min, max) = (t[k], t[n - k - 1]);
    if !(x >= min && x <= max) {
        return Err(Error::ParameterOutOfDomain { t: x, min, max });
    }
    // FITPACK's linear search for the first l ≥ k with x < t_{l+1} (or l = last), as a binary
    // search on the sorted knots (the same l: every knot before it is ≤ x)
    let last = n - k - 2;
    let inner = &t[k + 1..=last];
    let mut l = k + inner.partition_point(|&v| v <= x);
    if t[l] >= t[l + 1] {
        // FITPACK's `insert` then searches the other way, t_l < x ≤ t_{l+1}: x at the end of
        // an interval followed by repeated knots (a second insertion at the right end)
        l = k + inner.partition_point(|&v| v < x);
    }
    if checks == Checks::Read {
        // the knots Boehm's weights read (t_{l+1−k} … t_{l+k}, the interval's two among them;
        // l + k ≤ n − 2), and those that carry the period
        check_knot_window(t, l + 1 - k, l + k + 1)?;
        if periodic {
            check_knot_window(t, 0, 2 * k + 2)?;
            check_knot_window(t, n - 2 * k - 2, n)?;
        }
    }
    if t[l] >= t[l + 1] {
        return Err(Error::InvalidArgument {
            what: Arg::Knot.into(),
            reason: format!(
                "{x} lies in an empty knot interval [{}, {}]",
                readable(&t[l]),
                readable(&t[l + 1]),
                x = readable(&x)
            ),
        });
    }
    check_gap(Arg::Knot, t[l], x)?;
    check_gap(Arg::Knot, x, t[l + 1])?;
    // 1-based l of FITPACK is l + 1: refused when l + 1 ≤ 2k and l + 1 ≥ n − 2k
    if periodic && l < 2 * k && l + 1 + 2 * k >= n {
        return Err(Error::InvalidArgument {
            what: Arg::Knot.into(),
            reason: format!(
                "{x} lies in knot interval {l} of {n} knots; to carry the periodic extension \
                 (degree {k}) the interval must be at least {} or at most {}: insert into a \
                 spline with more interior knots",
                2 * k,
                n - 2 * k - 2,
                x = readable(&x)
            ),
        });
    }
    // Boehm's insertion: knots t_0..t_l, x, t_{l+1}..; coefficients c_0..c_{l−k}, the k new
    // ones, c_l..
    // `tt` holds n + 1 knots, `cc` n − k rows
    tt[..=l].copy_from_slice(&t[..=l]);
    tt[l + 1] = x;
    tt[l + 2..].copy_from_slice(&t[l + 1..]);
    cc[..(l + 1 - k) * dim].copy_from_slice(&c[..(l + 1 - k) * dim]);
    cc[(l + 1) * dim..].copy_from_slice(&c[l * dim..]);
    for i in l + 1 - k..=l {
        let fac = (x - tt[i]) / (tt[i + k + 1] - tt[i]);
        for d in 0..dim {
            cc[i * dim + d] = fac * c[i * dim + d] + (1.0 - fac) * c[(i - 1) * dim + d];
        }
    }
    if checks == Checks::Read {
        let new_rows = &cc[(l + 1 - k) * dim..(l + 1) * dim];
        if let Some(i) = new_rows.iter().position(|v| !v.is_finite()) {
            return Err(Error::NonFinite {
                what: "coefficients after insertion".into(),
                index: (l + 1 - k) * dim + i,
                value: new_rows[i],
            });
        }
    }
    if !periodic {
        return Ok(());
    }
    // the periodic extension (FITPACK's nk, nl, per in 0-based form)
    let nn = n + 1;
    let nk = nn - k - 1; // index of the base interval's right end
    let nl = nk - k; // coefficients per period
    let period = tt[nk] - tt[k];
    let new = l + 1; // index of the new knot
    if new + 1 > nl {
        for m in 0..k {
            for d in 0..dim {
                cc[m * dim + d] = cc[(m + nl) * dim + d];
            }
            tt[k - 1 - m] = tt[nk - 1 - m] - period;
        }
    } else if new < 2 * k + 1 {
        for m in 0..k {
            for d in 0..dim {
                cc[(m + nl) * dim + d] = cc[m * dim + d];
            }
            tt[nk + 1 + m] = tt[k + 1 + m] + period;
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::curve::bspline::BSplineCurve;

    /// The periodic cubic on uniform knots with period 6: inserting anywhere keeps the function
    /// on the base interval and keeps knots and coefficients periodic.
    #[test]
    fn periodic_spline_is_unchanged() {
        let k = 3;
        let t: Vec<f64> = (-3..=9).map(f64::from).collect(); // base interval [0, 6]
        let per = [0.5, 2.0, -1.0, 0.25, 1.5, -0.75];
        let c: Vec<f64> = (0..t.len() - k - 1).map(|i| per[i % 6]).collect();
        let before =
            BSplineCurve::new(k, t.clone(), Points::from_flat(1, c.clone()).unwrap()).unwrap();
        for x in [0.0, 0.3, 1.0, 2.5, 4.2, 5.9, 6.0] {
            // (at the right end the first insertion leaves an empty last interval: once only)
            let times = if x == 6.0 { 1 } else { 2 };
            let view = PointsRef::from_flat(1, &c).unwrap();
            let (t2, c2) = insert_knot_periodic(k, &t, view, x, times).unwrap();
            assert_eq!(t2.len(), t.len() + times);
            let after = BSplineCurve::new(k, t2.clone(), c2.clone()).unwrap();
            for s in [0.0, 0.7, 2.2, 3.0, 5.5, 6.0] {
                let (a, b) = (before.eval(s).unwrap()[0], after.eval(s).unwrap()[0]);
                assert!((a - b).abs() < 1e-14, "insert {x}, eval {s}: {a} vs {b}");
            }
            let n = t2.len();
            let nl = n - 2 * k - 1; // coefficients per period
            for m in 0..k {
                let (a, b) = (c2.point(m)[0], c2.point(m + nl)[0]);
                assert!(
                    (a - b).abs() < 1e-14,
                    "insert {x}: coefficient {m} not periodic"
                );
            }
            let period = t2[n - k - 1] - t2[k];
            assert!((period - 6.0).abs() < 1e-15, "period kept");
        }
    }

    /// de Boor's algorithm on raw knots (any multiplicity) in the interval `t_l ≤ s < t_{l+1}`
    /// of the base interval (the last non-empty one at its right end).
    fn de_boor(k: usize, t: &[f64], c: &[f64], s: f64) -> f64 {
        let n = t.len();
        let mut l = k;
        while l < n - k - 2 && (s >= t[l + 1] || t[l] >= t[l + 1]) {
            l += 1;
        }
        while t[l] >= t[l + 1] {
            l -= 1;
        }
        let mut d: Vec<f64> = (0..=k).map(|j| c[j + l - k]).collect();
        for r in 1..=k {
            for j in (r..=k).rev() {
                let i = j + l - k;
                let a = (s - t[i]) / (t[i + k + 1 - r] - t[i]);
                d[j] = (1.0 - a) * d[j - 1] + a * d[j];
            }
        }
        d[k]
    }

    /// Raw insertion keeps the function on the base interval, also past multiplicity k + 1 at
    /// the ends and past k inside (there the spline may jump, but each piece is kept).
    #[test]
    fn raw_insertion_keeps_the_function() {
        let k = 3;
        let t = [0.0, 0.0, 0.0, 0.0, 1.0, 2.5, 3.0, 4.0, 4.0, 4.0, 4.0];
        let c = [0.5, -1.0, 2.0, 1.0, 0.25, 3.0, -0.5];
        let before =
            BSplineCurve::new(k, t.to_vec(), Points::from_flat(1, c.to_vec()).unwrap()).unwrap();
        for (x, times) in [(0.0, 2), (4.0, 3), (2.5, 4), (1.7, 5), (0.0, 1), (4.0, 1)] {
            let view = PointsRef::from_flat(1, &c).unwrap();
            let (t2, c2) = insert_knot_raw(k, &t, view, x, times).unwrap();
            assert_eq!(t2.len(), t.len() + times);
            assert_eq!(c2.len(), c.len() + times);
            assert_eq!(
                t2.iter().filter(|&&v| v == x).count(),
                t.iter().filter(|&&v| v == x).count() + times
            );
            // evaluate each piece inside its own interval, away from the inserted knot
            let after = |s: f64| de_boor(k, &t2, c2.as_slice(), s);
            for s in [0.0, 0.3, 0.99, 1.2, 2.0, 2.49, 2.51, 3.5, 4.0] {
                if (s - x).abs() < 1e-9 && x > 0.0 && x < 4.0 {
                    continue;
                }
                let a = before.eval(s).unwrap()[0];
                let b = after(s);
                assert!(
                    (a - b).abs() < 1e-13,
                    "insert {x}×{times}, eval {s}: {a} vs {b}"
                );
            }
        }
        let view = PointsRef::from_flat(1, &c).unwrap();
        assert!(matches!(
            insert_knot_raw(k, &t, view, 4.5, 1),
            Err(Error::ParameterOutOfDomain { .. })
        ));
    }

    /// FITPACK's refusal: two interior knots on each side of the new one are too few for k = 3.
    #[test]
    fn too_few_interior_knots_and_domain() {
        let k = 3;
        let t = [0.0, 0.0, 0.0, 0.0, 2.0, 3.0, 4.0, 5.0, 7.0, 7.0, 7.0, 7.0];
        let c = [1.0; 8];
        let view = PointsRef::from_flat(1, &c).unwrap();
        let e = insert_knot_periodic(k, &t, view, 3.5, 1).unwrap_err();
        assert!(matches!(e, Error::InvalidArgument { .. }), "{e}");
        let e = insert_knot_periodic(k, &t, view, 7.5, 1).unwrap_err();
        assert!(matches!(e, Error::ParameterOutOfDomain { .. }), "{e}");
        let e = insert_knot_periodic(k, &t, PointsRef::from_flat(1, &c[..7]).unwrap(), 1.0, 1)
            .unwrap_err();
        assert!(matches!(e, Error::LengthMismatch { .. }), "{e}");
    }

    /// `insert_knot_into` checks what it reads: on a valid spline it gives the bits of
    /// `insert_knot_raw` (which checks everything); a NaN coefficient or knot away from `x` is
    /// copied as FITPACK copies it, one among the coefficients or knots the insertion reads is
    /// refused, unsorted knots away from `x` give a result, not a panic, and coefficients that
    /// are not whole rows are refused.
    #[test]
    fn insert_into_checks_what_it_reads() {
        let k = 3;
        let t: Vec<f64> = [0.0; 3]
            .into_iter()
            .chain((0..=20).map(f64::from))
            .chain([20.0; 3])
            .collect();
        let n = t.len();
        let c: Vec<f64> = (0..n - k - 1).map(|i| (i as f64 * 0.7).sin()).collect();
        let run = |t: &[f64], c: &[f64], x: f64, times: usize| {
            let mut tt = vec![f64::NAN; t.len() + times];
            let mut cc = vec![f64::NAN; t.len() + times];
            insert_knot_into(k, t, c, 1, x, times, false, &mut tt, &mut cc).map(|()| (tt, cc))
        };
        for (x, times) in [(0.0, 1), (4.5, 1), (4.5, 3), (11.0, 2), (20.0, 1)] {
            let (tt, cc) = run(&t, &c, x, times).unwrap();
            let view = PointsRef::from_flat(1, &c).unwrap();
            let (t2, c2) = insert_knot_raw(k, &t, view, x, times).unwrap();
            assert_eq!(tt, t2, "knots at {x}");
            let m = c2.as_slice().len();
            assert_eq!(&cc[..m], c2.as_slice(), "coefficients at {x}");
            assert!(cc[m..].iter().all(|&v| v == 0.0), "padding at {x}");
        }
        // a NaN coefficient far from x: copied; among the k + 1 that x's interval reads: refused
        let mut bad = c.clone();
        bad[18] = f64::NAN;
        let (_, cc) = run(&t, &bad, 4.5, 1).unwrap();
        assert!(cc[19].is_nan() && cc[..19].iter().all(|v| v.is_finite()));
        let e = run(&t, &bad, 16.5, 1).unwrap_err();
        assert!(matches!(e, Error::NonFinite { .. }), "{e}");
        // a NaN knot, or a knot out of order, far from x: copied; near it: refused
        for v in [f64::NAN, 6.0] {
            let mut tb = t.clone();
            tb[18] = v;
            let (tt, _) = run(&tb, &c, 4.5, 1).unwrap();
            assert_eq!(tt[19].to_bits(), v.to_bits());
            let e = run(&tb, &c, 14.5, 1).unwrap_err();
            assert!(
                matches!(e, Error::NonFinite { .. } | Error::KnotsNotSorted { .. }),
                "{e}"
            );
        }
        // knots reversed: whatever interval the search finds, no panic
        let reversed: Vec<f64> = t.iter().rev().copied().collect();
        for x in [0.0, 3.0, 10.0, 20.0] {
            let _ = run(&reversed, &c, x, 2);
        }
        // a periodic insertion reads the period's ends: a NaN there is refused
        let mut tp = t.clone();
        tp[n - 1] = f64::NAN;
        let mut tt = vec![0.0; n + 1];
        let mut cc = vec![0.0; n + 1];
        let e = insert_knot_into(k, &tp, &c, 1, 10.5, 1, true, &mut tt, &mut cc).unwrap_err();
        assert!(matches!(e, Error::NonFinite { .. }), "{e}");
        for dim in [0, 2] {
            let e = insert_knot_into(k, &t, &c, dim, 10.5, 1, false, &mut tt, &mut cc).unwrap_err();
            assert!(matches!(e, Error::Dimension { .. }), "{e}");
        }
    }
}
