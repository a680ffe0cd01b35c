//! The C² cubic spline of a function `y(x)` through its data by its slopes, SciPy's
//! `CubicSpline` (`docs/theory/interpolation.md#slopes-of-the-c2-cubic`): one tridiagonal
//! system for the slopes `s_i = S'(x_i)` with SciPy's end rows (not-a-knot, first or second
//! derivative, periodic), solved for every column of the data at once
//! ([`crate::numeric::tridiagonal`]; one column from both ends at once,
//! [`crate::numeric::twisted`]), then the pieces in SciPy's power form
//! ([`crate::pp::cubic_hermite_power_into`]).

use crate::error::{check_finite, Error, Result, MAX_SCALARS};
use crate::knots::check_breakpoints;
use crate::numeric::partitioned::{solve_partitioned, MIN_ROWS as PARTITIONED_ROWS};
use crate::numeric::tridiagonal::{
    solve_tridiagonal, solve_unpivoted, Bands, StoredBands, Tridiagonal,
};
use crate::numeric::twisted::solve_twisted;
use crate::pp::cubic_hermite_power_into;

/// The condition at one end of a C² cubic spline (SciPy's `bc_type` entries).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum CubicSplineEnd<'a> {
    /// The third derivative continuous across the second (or next-to-last) breakpoint.
    NotAKnot,
    /// The first derivative at the end, one number a column.
    FirstDerivative(&'a [f64]),
    /// The second derivative at the end, one number a column (zeros: the natural spline).
    SecondDerivative(&'a [f64]),
    /// Periodic: the first and second derivatives equal at both ends; both ends must say so,
    /// and the data's last row must repeat its first.
    Periodic,
}

/// Writes the slopes `s_i = S'(x_i)` (`n` rows of `dim`, row-major) of the C² cubic spline `S`
/// with the values `y` (`n` rows of `dim`) at the strictly increasing `x` and the end conditions
/// `start`, `end`. With `h_i = x_{i+1} − x_i` and the secants `δ_i = (y_{i+1} − y_i)/h_i`, the
/// interior rows are the continuity of `S''`:
///
/// `h_i s_{i−1} + 2(h_{i−1} + h_i) s_i + h_{i−1} s_{i+1} = 3(h_i δ_{i−1} + h_{i−1} δ_i)`
///
/// (de Boor, *A Practical Guide to Splines*, rev. ed., ch. IV, eq. (8)), closed by SciPy's end
/// rows: not-a-knot `h_1 s_0 + (x_2 − x_0) s_1 = ((h_0 + 2(x_2 − x_0)) h_1 δ_0 + h_0² δ_1)/(x_2 − x_0)`,
/// a first derivative `s_0 = v`, a second `2h_0 s_0 + h_0 s_1 = −v h_0²/2 + 3(y_1 − y_0)`
/// (mirrored at the end); periodic: the cyclic system of `n − 1` slopes reduced to the
/// tridiagonal one of `n − 2` and a rank-one correction (SciPy's "condensed" system). Two
/// points: a not-a-knot or periodic end takes the chord's slope; three points not-a-knot at both
/// ends: the parabola through them (a 3 × 3 system); three points periodic: the weighted mean
/// `Σ δ_i/h_i / Σ 1/h_i` everywhere. These are SciPy's rows, formed by SciPy's operations in its
/// order; the system is solved by elimination without row swaps when its pivots are positive
/// (they are on strictly increasing breakpoints; the interior rows are diagonally dominant), with
/// the dependent chains of the elimination cut short (`numeric/tridiagonal.rs`), else by LAPACK's
/// `dgtsv` (partial pivoting), which SciPy calls: SciPy's slopes to rounding. O(n·dim) time,
/// O(n·dim) scratch.
///
/// Non-finite end derivatives give non-finite slopes (which
/// [`cubic_spline_power_into`] refuses, as SciPy's `CubicSpline` does).
///
/// ```
/// use lekalo::interpolate::{cubic_spline_slopes_into, CubicSplineEnd};
/// // y = x³ with its end slopes: the spline is x³ itself
/// let x = [0.0, 1.0, 2.0, 3.0];
/// let y = [0.0, 1.0, 8.0, 27.0];
/// let mut s = [0.0; 4];
/// let ends = (CubicSplineEnd::FirstDerivative(&[0.0]), CubicSplineEnd::FirstDerivative(&[27.0]));
/// cubic_spline_slopes_into(&x, &y, 1, ends.0, ends.1, &mut s)?;
/// assert_eq!(s, [0.0, 3.0, 12.0, 27.0]);
/// # Ok::<(), lekalo::Error>(())
/// ```
///
/// # Errors
/// [`Error::TooFew`], [`Error::NonFinite`] or [`Error::InvalidArgument`] for breakpoints that
/// are fewer than 2, not finite or not strictly increasing; [`Error::InvalidArgument`] for
/// `dim = 0`, a periodic condition at one end only, or periodic data whose last row differs
/// from the first (beyond SciPy's `1e-15` relative and absolute); [`Error::LengthMismatch`]
/// when `y`, `slopes` or a derivative value has the wrong length; [`Error::NonFinite`] for a
/// value that is not finite; [`Error::SingularSystem`] for a zero pivot.
pub fn cubic_spline_slopes_into(
    x: &[f64],
    y: &[f64],
    dim: usize,
    start: CubicSplineEnd<'_>,
    end: CubicSplineEnd<'_>,
    slopes: &mut [f64],
) -> Result<()> {
    slopes_with_scratch(x, y, dim, [start, end], slopes, None).map(|_| ())
}

/// [`cubic_spline_slopes_into`] with `scratch` (at least `n` numbers, else allocated) for the
/// solve's pivots; with at least `4(n − 1)` numbers and one column, the system's secants
/// `δ_i` are kept in `scratch[2(n − 1)..3(n − 1)]` where the answer is `true` (not for two
/// or three points or periodic data).
fn slopes_with_scratch(
    x: &[f64],
    y: &[f64],
    dim: usize,
    [start, end]: [CubicSplineEnd<'_>; 2],
    slopes: &mut [f64],
    scratch: Option<&mut [f64]>,
) -> Result<bool> {
    check_data(x, y, dim, [start, end], slopes.len())?;
    let n = x.len();
    let periodic = match (start, end) {
        (CubicSplineEnd::Periodic, CubicSplineEnd::Periodic) => true,
        (CubicSplineEnd::Periodic, _) | (_, CubicSplineEnd::Periodic) => {
            return Err(Error::InvalidArgument {
                what: "end conditions".into(),
                reason: "'periodic' holds at both ends or at neither; give it for both".into(),
            })
        }
        _ => false,
    };
    if periodic {
        check_periodic_data(y, dim)?;
    }
    let h = |i: usize| x[i + 1] - x[i];
    let secant = |i: usize, j: usize| (y[(i + 1) * dim + j] - y[i * dim + j]) / h(i);
    if n == 2 {
        // the chord's slope for a not-a-knot or periodic end
        for j in 0..dim {
            let chord = secant(0, j);
            slopes[j] = end_slope(start, j, chord);
            slopes[dim + j] = end_slope(end, j, chord);
        }
        return two_point_system(x, y, dim, start, end, slopes).map(|()| false);
    }
    if n == 3 && periodic {
        for j in 0..dim {
            let (h0, h1) = (h(0), h(1));
            let t = (secant(0, j) / h0 + secant(1, j) / h1) / (1.0 / h0 + 1.0 / h1);
            for i in 0..3 {
                slopes[i * dim + j] = t;
            }
        }
        return Ok(false);
    }
    if n == 3 && start == CubicSplineEnd::NotAKnot && end == CubicSplineEnd::NotAKnot {
        return parabola_slopes(x, y, dim, slopes).map(|()| false);
    }
    if periodic {
        return periodic_slopes(x, y, dim, slopes).map(|()| false);
    }
    let rows = SplineRows::new(x, start, end);
    let mut own = Vec::new();
    // the pivots' reciprocals in the scratch's first n numbers, the secants of one column in
    // its third quarter (n ≤ 2(n − 1) from n = 2)
    let (recip, secants) = match scratch {
        Some(s) if s.len() >= 4 * (n - 1) => {
            let (a, b) = s.split_at_mut(2 * (n - 1));
            (&mut a[..n], Some(&mut b[..n - 1]))
        }
        Some(s) if s.len() >= n => (&mut s[..n], None),
        _ => {
            own.resize(n, 0.0);
            (&mut own[..], None)
        }
    };
    let kept = dim == 1 && secants.is_some();
    rows.right_hand_side(y, dim, [start, end], slopes, secants);
    if dim == 1 {
        // one column: eliminated in eight partitions at once where they meet, else from both
        // ends at once (two dependent chains of half the length); either leaves partial work
        // when it gives up, so the right-hand side is formed again after it
        if n >= PARTITIONED_ROWS {
            if solve_partitioned(&rows, slopes, recip) {
                return Ok(kept);
            }
            rows.right_hand_side(y, dim, [start, end], slopes, None);
        }
        if solve_twisted(&rows, slopes, recip) {
            return Ok(kept);
        }
        rows.right_hand_side(y, dim, [start, end], slopes, None);
    } else if solve_unpivoted(&rows, slopes, dim, recip) {
        return Ok(false);
    }
    // a pivot that is not positive (not on strictly increasing breakpoints): the stored bands,
    // eliminated with LAPACK's row swaps
    let (mut dl, mut d, mut du) = rows.stored();
    solve_tridiagonal(
        Tridiagonal {
            dl: &mut dl,
            d: &mut d,
            du: &mut du,
        },
        slopes,
        dim,
    )?;
    Ok(kept)
}

/// SciPy's `CubicSpline` matrix on `n ≥ 3` breakpoints with ends that are not periodic, its
/// entries formed from the breakpoints where the solver reads them (three bands never written
/// out: the solve's only scratch is its `n` pivots): row `i` of the interior is
/// `(h_i, 2(h_{i−1} + h_i), h_{i−1})` with `h_i = x_{i+1} − x_i`, SciPy's operations in its
/// order; the first and last rows are the end conditions' ([`cubic_spline_slopes_into`]).
struct SplineRows<'a> {
    x: &'a [f64],
    /// `d[0]`, `du[0]`.
    first: (f64, f64),
    /// `dl[n − 2]`, `d[n − 1]`.
    last: (f64, f64),
}

impl<'a> SplineRows<'a> {
    fn new(x: &'a [f64], start: CubicSplineEnd<'_>, end: CubicSplineEnd<'_>) -> Self {
        let n = x.len();
        let h = |i: usize| x[i + 1] - x[i];
        let first = match start {
            CubicSplineEnd::NotAKnot | CubicSplineEnd::Periodic => (h(1), x[2] - x[0]),
            CubicSplineEnd::FirstDerivative(_) => (1.0, 0.0),
            CubicSplineEnd::SecondDerivative(_) => (2.0 * h(0), h(0)),
        };
        let last = match end {
            CubicSplineEnd::NotAKnot | CubicSplineEnd::Periodic => (x[n - 1] - x[n - 3], h(n - 3)),
            CubicSplineEnd::FirstDerivative(_) => (0.0, 1.0),
            CubicSplineEnd::SecondDerivative(_) => (h(n - 2), 2.0 * h(n - 2)),
        };
        SplineRows { x, first, last }
    }

    /// SciPy's right-hand side into `b` (`n` rows of `dim`): `3(h_i δ_{i−1} + h_{i−1} δ_i)`
    /// inside, with the secants `δ_i = (y_{i+1} − y_i)/h_i` formed where they are used (one
    /// column with `secants`, at least `n − 1` numbers: each formed once, kept there), and the
    /// end conditions' rows.
    fn right_hand_side(
        &self,
        y: &[f64],
        dim: usize,
        [start, end]: [CubicSplineEnd<'_>; 2],
        b: &mut [f64],
        secants: Option<&mut [f64]>,
    ) {
        let x = self.x;
        let n = x.len();
        let h = |i: usize| x[i + 1] - x[i];
        let secant = |i: usize, j: usize| (y[(i + 1) * dim + j] - y[i * dim + j]) / h(i);
        if let (1, Some(sec)) = (dim, secants) {
            secant_rows(x, y, sec, b);
        } else if dim == 1 {
            let inner = b[1..n - 1].iter_mut().zip(x.windows(3)).zip(y.windows(3));
            for ((b, xw), yw) in inner {
                let (h0, h1) = (xw[1] - xw[0], xw[2] - xw[1]);
                *b = 3.0 * (h1 * ((yw[1] - yw[0]) / h0) + h0 * ((yw[2] - yw[1]) / h1));
            }
        } else {
            for i in 1..n - 1 {
                for j in 0..dim {
                    b[i * dim + j] = 3.0 * (h(i) * secant(i - 1, j) + h(i - 1) * secant(i, j));
                }
            }
        }
        let (h0, h1) = (h(0), h(1));
        match start {
            CubicSplineEnd::NotAKnot | CubicSplineEnd::Periodic => {
                let w = x[2] - x[0];
                for j in 0..dim {
                    b[j] = ((h0 + 2.0 * w) * h1 * secant(0, j) + h0 * h0 * secant(1, j)) / w;
                }
            }
            CubicSplineEnd::FirstDerivative(v) => b[..dim].copy_from_slice(v),
            CubicSplineEnd::SecondDerivative(v) => {
                let h0sq = h0 * h0;
                for j in 0..dim {
                    b[j] = -0.5 * v[j] * h0sq + 3.0 * (y[dim + j] - y[j]);
                }
            }
        }
        let (hl, hm) = (h(n - 2), h(n - 3));
        let last = (n - 1) * dim;
        match end {
            CubicSplineEnd::NotAKnot | CubicSplineEnd::Periodic => {
                let w = x[n - 1] - x[n - 3];
                for j in 0..dim {
                    b[last + j] =
                        (hl * hl * secant(n - 3, j) + (2.0 * w + hl) * hm * secant(n - 2, j)) / w;
                }
            }
            CubicSplineEnd::FirstDerivative(v) => b[last..].copy_from_slice(v),
            CubicSplineEnd::SecondDerivative(v) => {
                let hlsq = hl * hl;
                for j in 0..dim {
                    b[last + j] = 0.5 * v[j] * hlsq + 3.0 * (y[last + j] - y[last - dim + j]);
                }
            }
        }
    }

    /// The three bands written out (`dl`, `d`, `du`), for the elimination with row swaps.
    fn stored(&self) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
        let n = self.len();
        (
            (0..n - 1).map(|i| self.lower(i)).collect(),
            (0..n).map(|i| self.diag(i)).collect(),
            (0..n - 1).map(|i| self.upper(i)).collect(),
        )
    }
}

impl Bands for SplineRows<'_> {
    fn len(&self) -> usize {
        self.x.len()
    }

    #[inline]
    fn diag(&self, i: usize) -> f64 {
        let x = self.x;
        if i == 0 {
            self.first.0
        } else if i + 1 == x.len() {
            self.last.1
        } else {
            2.0 * ((x[i] - x[i - 1]) + (x[i + 1] - x[i]))
        }
    }

    #[inline]
    fn lower(&self, i: usize) -> f64 {
        if i + 2 == self.x.len() {
            self.last.0
        } else {
            self.x[i + 2] - self.x[i + 1]
        }
    }

    #[inline]
    fn upper(&self, i: usize) -> f64 {
        if i == 0 {
            self.first.1
        } else {
            self.x[i] - self.x[i - 1]
        }
    }

    /// The entries of [`SplineRows::lower`], [`SplineRows::diag`] and [`SplineRows::upper`]
    /// by the same operations, an interior row's two steps formed once.
    #[inline]
    fn row(&self, i: usize) -> [f64; 3] {
        let x = self.x;
        if i == 0 {
            return [0.0, self.first.0, self.first.1];
        }
        if i + 1 == x.len() {
            return [self.last.0, self.last.1, 0.0];
        }
        let w = &x[i - 1..i + 2];
        let (h0, h1) = (w[1] - w[0], w[2] - w[1]);
        [h1, 2.0 * (h0 + h1), h0]
    }
}

/// The interior rows of SciPy's right-hand side for one column, `3(h_i δ_{i−1} + h_{i−1} δ_i)`
/// into `b[1..n − 1]`, and the secants `δ_i = (y_{i+1} − y_i)/h_i` into `sec` (at least
/// `n − 1`): each secant divided once (a division is the costliest operation of the pass), the
/// same operations as [`SplineRows::right_hand_side`]'s other branches.
#[inline(always)]
fn secant_rows_body(x: &[f64], y: &[f64], sec: &mut [f64], b: &mut [f64]) {
    let p = x.len() - 1;
    let (sec, xs, ys) = (&mut sec[..p], &x[..=p], &y[..=p]);
    for i in 0..p {
        sec[i] = (ys[i + 1] - ys[i]) / (xs[i + 1] - xs[i]);
    }
    let inner = &mut b[1..p];
    for (k, v) in inner.iter_mut().enumerate() {
        let (h0, h1) = (xs[k + 1] - xs[k], xs[k + 2] - xs[k + 1]);
        *v = 3.0 * (h1 * sec[k] + h0 * sec[k + 1]);
    }
}

crate::numeric::isa::avx2_dispatch! {
    /// [`secant_rows_body`] compiled with AVX2 where the processor has it (four divisions at
    /// once), else as built ([`crate::numeric::isa`]: the same bits).
    fn secant_rows(x: &[f64], y: &[f64], sec: &mut [f64], b: &mut [f64]) = secant_rows_body;
}

/// SciPy's `dx` (`n − 1` steps) and `slope` (`n − 1` rows of `dim` secants `(y_{i+1} − y_i)/h_i`).
fn steps_and_secants(x: &[f64], y: &[f64], dim: usize) -> (Vec<f64>, Vec<f64>) {
    let hs: Vec<f64> = x.windows(2).map(|w| w[1] - w[0]).collect();
    let secants = if dim == 1 {
        y.windows(2)
            .zip(&hs)
            .map(|(w, h)| (w[1] - w[0]) / h)
            .collect()
    } else {
        (0..hs.len() * dim)
            .map(|k| (y[k + dim] - y[k]) / hs[k / dim])
            .collect()
    };
    (hs, secants)
}

/// The tridiagonal solve: without row swaps when every pivot is positive (SciPy's system on
/// strictly increasing breakpoints; [`solve_unpivoted`], the same solution to rounding), else
/// with LAPACK `dgtsv`'s partial pivoting ([`solve_tridiagonal`]).
fn solve(m: Tridiagonal<'_>, b: &mut [f64], ncols: usize) -> Result<()> {
    let mut recip = vec![0.0; m.d.len()];
    let stored = StoredBands {
        dl: m.dl,
        d: m.d,
        du: m.du,
    };
    if solve_unpivoted(&stored, b, ncols, &mut recip) {
        return Ok(());
    }
    solve_tridiagonal(m, b, ncols)
}

/// Writes SciPy's `CubicSpline` coefficients: the slopes of [`cubic_spline_slopes_into`], then
/// the pieces in SciPy's power form by [`crate::pp::cubic_hermite_power_into`] (`c`: 4 rows of
/// `n − 1` pieces of `dim`, the highest power first). O(n·dim); the slopes in one scratch array.
///
/// ```
/// use lekalo::interpolate::{cubic_spline_power_into, CubicSplineEnd};
/// // natural spline through three points of a line: the line, to rounding (the solve
/// // multiplies by the pivots' reciprocals, so a slope may be off by an ulp)
/// let mut c = [0.0; 8];
/// let zero = [0.0];
/// let natural = CubicSplineEnd::SecondDerivative(&zero);
/// cubic_spline_power_into(&[0.0, 1.0, 2.0], &[1.0, 3.0, 5.0], 1, natural, natural, &mut c)?;
/// let line = [0.0, 0.0, 0.0, 0.0, 2.0, 2.0, 1.0, 3.0];
/// assert!(c.iter().zip(line).all(|(a, b)| (a - b).abs() <= 4.0 * f64::EPSILON));
/// # Ok::<(), lekalo::Error>(())
/// ```
///
/// # Errors
/// Those of [`cubic_spline_slopes_into`]; [`Error::TooLarge`] for data beyond the size limit;
/// those of [`crate::pp::cubic_hermite_power_into`]: [`Error::LengthMismatch`] when `c` is not
/// `4·(n − 1)·dim` long, [`Error::NonFinite`] for a slope that is not finite (a non-finite end
/// derivative, or an overflow).
pub fn cubic_spline_power_into(
    x: &[f64],
    y: &[f64],
    dim: usize,
    start: CubicSplineEnd<'_>,
    end: CubicSplineEnd<'_>,
    c: &mut [f64],
) -> Result<()> {
    let Some(rows) = x.len().checked_mul(dim).filter(|&r| r <= MAX_SCALARS / 4) else {
        return Err(Error::TooLarge {
            what: "cubic spline data".into(),
            size: x.len().saturating_mul(dim),
            max: MAX_SCALARS / 4,
        });
    };
    let mut slopes = vec![0.0; rows];
    // `c` is written over by the power form: it holds the solve's pivots and the secants
    // until then
    let c_len = c.len();
    let scratch = (c_len == 4 * (x.len().saturating_sub(1)) * dim).then_some(&mut *c);
    let kept = slopes_with_scratch(x, y, dim, [start, end], &mut slopes, scratch)?;
    if kept && spline_power_pass(x, y, &slopes, c) {
        return Ok(());
    }
    // SciPy's Hermite pass, which names a slope that is not finite
    cubic_hermite_power_into(x, y, &slopes, dim, c)
}

/// The pieces of one column in SciPy's power form (`c`: 4 rows of `n − 1`) from the slopes
/// `s` and the secants `δ_i` that [`slopes_with_scratch`] left in `c`'s third row, as
/// [`crate::pp::cubic_hermite_power_into`] with the reciprocal `r = 1/h` of each step instead
/// of three divisions by it: `t = (s_i + s_{i+1} − 2δ_i)·r`, `c_0 = t·r`,
/// `c_1 = (δ_i − s_i)·r − t`, `c_2 = s_i`, `c_3 = y_i` (the secant itself SciPy's quotient).
/// The slopes are SciPy's to rounding only (the solve's), so its bits are not to keep here,
/// and a division costs several multiplications. `false` when a slope is not finite.
#[inline(always)]
fn spline_power_body(x: &[f64], y: &[f64], s: &[f64], c: &mut [f64]) -> bool {
    let p = x.len() - 1;
    let (c0, rest) = c.split_at_mut(p);
    let (c1, rest) = rest.split_at_mut(p);
    let (c2, c3) = rest.split_at_mut(p);
    let (xs, ys, ss) = (&x[..=p], &y[..=p], &s[..=p]);
    let (c1, c2, c3) = (&mut c1[..p], &mut c2[..p], &mut c3[..p]);
    let mut bad = 0_u64;
    for i in 0..p {
        let r = 1.0 / (xs[i + 1] - xs[i]);
        let (slope, d0, d1) = (c2[i], ss[i], ss[i + 1]);
        let t = (d0 + d1 - 2.0 * slope) * r;
        c0[i] = t * r;
        c1[i] = (slope - d0) * r - t;
        c2[i] = d0;
        c3[i] = ys[i];
        bad |= u64::from(!d0.is_finite());
    }
    bad == 0 && ss[p].is_finite()
}

crate::numeric::isa::avx2_dispatch! {
    /// [`spline_power_body`] compiled with AVX2 where the processor has it, else as built
    /// ([`crate::numeric::isa`]: the same bits).
    fn spline_power_pass(x: &[f64], y: &[f64], s: &[f64], c: &mut [f64]) -> bool = spline_power_body;
}

/// The checks of [`cubic_spline_slopes_into`]'s arguments, before anything is allocated.
fn check_data(
    x: &[f64],
    y: &[f64],
    dim: usize,
    ends: [CubicSplineEnd<'_>; 2],
    slopes_len: usize,
) -> Result<()> {
    check_breakpoints(x)?;
    if dim == 0 {
        return Err(Error::InvalidArgument {
            what: "cubic spline values".into(),
            reason: "the dimension is 0; pass at least one column of values".into(),
        });
    }
    let Some(rows) = x.len().checked_mul(dim).filter(|&r| r <= MAX_SCALARS) else {
        return Err(Error::TooLarge {
            what: "cubic spline data".into(),
            size: x.len().saturating_mul(dim),
            max: MAX_SCALARS,
        });
    };
    for (what, got) in [
        ("cubic spline values (breakpoints × dimension)", y.len()),
        ("cubic spline slopes (breakpoints × dimension)", slopes_len),
    ] {
        if got != rows {
            return Err(Error::LengthMismatch {
                what: what.into(),
                expected: rows,
                got,
            });
        }
    }
    for e in ends {
        if let CubicSplineEnd::FirstDerivative(v) | CubicSplineEnd::SecondDerivative(v) = e {
            if v.len() != dim {
                return Err(Error::LengthMismatch {
                    what: "end derivative (one number a column)".into(),
                    expected: dim,
                    got: v.len(),
                });
            }
        }
    }
    check_finite("cubic spline values", y)
}

/// SciPy's test of periodic data: `|y_{n−1} − y_0| ≤ 1e−15 + 1e−15·|y_0|` in every column
/// (`np.allclose(y[0], y[-1], rtol=1e-15, atol=1e-15)`).
fn check_periodic_data(y: &[f64], dim: usize) -> Result<()> {
    let (first, last) = (&y[..dim], &y[y.len() - dim..]);
    for (j, (a, b)) in first.iter().zip(last).enumerate() {
        if (b - a).abs() > 1e-15 + 1e-15 * a.abs() {
            return Err(Error::InvalidArgument {
                what: "periodic cubic spline values".into(),
                reason: format!(
                    "the last value {b} of column {j} differs from the first {a}; a periodic \
                     spline repeats its first value at the end"
                ),
            });
        }
    }
    Ok(())
}

/// The slope at a two-point end: the chord's for a not-a-knot or periodic end, else what the
/// first row of the 2 × 2 system is solved for (filled in by [`two_point_system`]).
fn end_slope(e: CubicSplineEnd<'_>, j: usize, chord: f64) -> f64 {
    match e {
        CubicSplineEnd::NotAKnot | CubicSplineEnd::Periodic => chord,
        CubicSplineEnd::FirstDerivative(v) => v[j],
        CubicSplineEnd::SecondDerivative(_) => 0.0,
    }
}

/// Two points: SciPy's 2 × 2 system, each end a first derivative (the chord's for not-a-knot
/// and periodic) or a second derivative row; `slopes` holds the first derivatives already.
fn two_point_system(
    x: &[f64],
    y: &[f64],
    dim: usize,
    start: CubicSplineEnd<'_>,
    end: CubicSplineEnd<'_>,
    slopes: &mut [f64],
) -> Result<()> {
    let h = x[1] - x[0];
    let hsq = h * h;
    let (mut d, mut dl, mut du) = ([1.0, 1.0], [0.0], [0.0]);
    if let CubicSplineEnd::SecondDerivative(v) = start {
        d[0] = 2.0 * h;
        du[0] = h;
        for j in 0..dim {
            slopes[j] = -0.5 * v[j] * hsq + 3.0 * (y[dim + j] - y[j]);
        }
    }
    if let CubicSplineEnd::SecondDerivative(v) = end {
        d[1] = 2.0 * h;
        dl[0] = h;
        for j in 0..dim {
            slopes[dim + j] = 0.5 * v[j] * hsq + 3.0 * (y[dim + j] - y[j]);
        }
    }
    let m = Tridiagonal {
        dl: &mut dl,
        d: &mut d,
        du: &mut du,
    };
    solve_tridiagonal(m, slopes, dim)
}

/// Three points, not-a-knot at both ends: the slopes of the parabola through them, SciPy's
/// 3 × 3 system `[[1, 1, 0], [h_1, 2(h_0 + h_1), h_0], [0, 1, 1]]·s = [2δ_0, 3(h_0 δ_1 + h_1 δ_0), 2δ_1]`
/// by elimination with partial pivoting (SciPy's `solve`, LAPACK `dgesv`; the same numbers to
/// rounding).
fn parabola_slopes(x: &[f64], y: &[f64], dim: usize, slopes: &mut [f64]) -> Result<()> {
    let (h0, h1) = (x[1] - x[0], x[2] - x[1]);
    for j in 0..dim {
        let d0 = (y[dim + j] - y[j]) / h0;
        let d1 = (y[2 * dim + j] - y[dim + j]) / h1;
        let mut a = [[1.0, 1.0, 0.0], [h1, 2.0 * (h0 + h1), h0], [0.0, 1.0, 1.0]];
        let mut b = [2.0 * d0, 3.0 * (h0 * d1 + h1 * d0), 2.0 * d1];
        for col in 0..3 {
            let p = (col..3)
                .max_by(|&r, &s| a[r][col].abs().total_cmp(&a[s][col].abs()))
                .unwrap_or(col);
            a.swap(col, p);
            b.swap(col, p);
            if a[col][col] == 0.0 {
                return Err(Error::SingularSystem {
                    reason: "the three-point not-a-knot system has a zero pivot".into(),
                });
            }
            for r in col + 1..3 {
                let f = a[r][col] / a[col][col];
                for k in col..3 {
                    a[r][k] -= f * a[col][k];
                }
                b[r] -= f * b[col];
            }
        }
        for r in (0..3).rev() {
            let mut v = b[r];
            for k in r + 1..3 {
                v -= a[r][k] * b[k];
            }
            b[r] = v / a[r][r];
        }
        for (i, v) in b.iter().enumerate() {
            slopes[i * dim + j] = *v;
        }
    }
    Ok(())
}

/// Periodic data at `n ≥ 4` points: SciPy's cyclic system of the `n − 1` slopes `s_0 …
/// s_{n−2}` (`s_{n−1} = s_0`), solved as the tridiagonal system of the first `n − 2` rows and
/// columns for the right-hand side and for the last column's entries (`s1`, `s2`), then
/// `s_{n−2} = (b_{n−2} − h_{n−3} s1_0 − h_{n−2} s1_{n−3}) / (2(h_{n−2} + h_{n−3}) + h_{n−3} s2_0 + h_{n−2} s2_{n−3})`
/// and `s_i = s1_i + s_{n−2} s2_i`.
fn periodic_slopes(x: &[f64], y: &[f64], dim: usize, slopes: &mut [f64]) -> Result<()> {
    let n = x.len();
    let m = n - 2;
    let (hs, secants) = steps_and_secants(x, y, dim);
    let h = |i: usize| hs[i];
    let secant = |i: usize, j: usize| secants[i * dim + j];
    let (hl, hm) = (h(n - 2), h(n - 3));
    // the condensed matrix: rows and columns 0 … n − 3 of the cyclic one
    let mut band = vec![0.0; 3 * m - 2];
    let (d, rest) = band.split_at_mut(m);
    let (dl, du) = rest.split_at_mut(m - 1);
    d[0] = 2.0 * (hl + h(0));
    for i in 1..m {
        d[i] = 2.0 * (h(i - 1) + h(i));
    }
    du[0] = hl;
    for i in 1..m - 1 {
        du[i] = h(i - 1);
    }
    for (i, v) in dl.iter_mut().enumerate() {
        *v = h(i + 1);
    }
    // right-hand sides: b1 (the data) in slopes' first m rows, b2 (the last column) apart
    for j in 0..dim {
        slopes[j] = 3.0 * (h(0) * secant(n - 2, j) + hl * secant(0, j));
    }
    for i in 1..m {
        for j in 0..dim {
            slopes[i * dim + j] = 3.0 * (h(i) * secant(i - 1, j) + h(i - 1) * secant(i, j));
        }
    }
    let mut b2 = vec![0.0; m];
    b2[0] = -h(0);
    b2[m - 1] = -h(n - 4);
    let (mut dl2, mut d2, mut du2) = (dl.to_vec(), d.to_vec(), du.to_vec());
    solve(Tridiagonal { dl, d, du }, &mut slopes[..m * dim], dim)?;
    let m2 = Tridiagonal {
        dl: &mut dl2,
        d: &mut d2,
        du: &mut du2,
    };
    solve(m2, &mut b2, 1)?;
    let denominator = 2.0 * (hl + hm) + hm * b2[0] + hl * b2[m - 1];
    for j in 0..dim {
        let b_last = 3.0 * (hl * secant(n - 3, j) + hm * secant(n - 2, j));
        let s_last = (b_last - hm * slopes[j] - hl * slopes[(m - 1) * dim + j]) / denominator;
        for i in 0..m {
            slopes[i * dim + j] += s_last * b2[i];
        }
        slopes[m * dim + j] = s_last;
        slopes[(n - 1) * dim + j] = slopes[j];
    }
    Ok(())
}

#[cfg(test)]
#[path = "cubic_spline_tests.rs"]
mod tests;
