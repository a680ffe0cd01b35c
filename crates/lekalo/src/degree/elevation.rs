//! Degree elevation of Bezier curves in the Bernstein basis (document 004 eq. 8, in closed
//! form): `u'_j = Σ_i C(n,i) C(r,j−i) / C(n+r,j) u_i`, a convex combination of the old control
//! points (Farin, *Curves and Surfaces for CAGD*, §5.1). The binomial table, the elevation
//! weights, and the banded kernel shared by [`BezierCurve::elevate_degree`] and
//! [`ElevationPlan`] (kernels on flat point-major slices; callers validate).

use crate::What;
use std::cell::RefCell;

use crate::error::{Error, Result, MAX_SCALARS};
#[cfg(doc)]
use crate::{BezierCurve, ElevationPlan};

/// Largest `n` for which every binomial coefficient `C(n, k)` is an integer below `2^53`, so exact
/// in `f64` (`C(56, 28) ≈ 7.65·10^15 < 2^53 ≈ 9.01·10^15 < C(57, 28)`).
const EXACT_BINOMIAL_MAX: usize = 56;

/// Largest `n` of the binomial table: every `C(n, k)` up to `C(131, 65) ≈ 1.9·10^38` is an exact
/// `u128` at compile time, stored correctly rounded to `f64` (exact up to
/// [`EXACT_BINOMIAL_MAX`]).
pub(crate) const BINOMIAL_TABLE_MAX: usize = 131;

/// Entries of the triangle `0 ≤ k ≤ n ≤ BINOMIAL_TABLE_MAX`.
const BINOMIAL_ENTRIES: usize = (BINOMIAL_TABLE_MAX + 1) * (BINOMIAL_TABLE_MAX + 2) / 2;

/// Pascal's triangle row after row: `C(n, k)` at `n(n+1)/2 + k`.
static BINOMIAL: [f64; BINOMIAL_ENTRIES] = pascal();

/// Pascal's triangle by `C(n, k) = C(n−1, k−1) + C(n−1, k)` in `u128` (exact), at compile time,
/// each entry then rounded to the nearest `f64`.
const fn pascal() -> [f64; BINOMIAL_ENTRIES] {
    let mut exact = [0_u128; BINOMIAL_ENTRIES];
    let mut rounded = [0.0_f64; BINOMIAL_ENTRIES];
    let mut n = 0;
    while n <= BINOMIAL_TABLE_MAX {
        let row = n * (n + 1) / 2;
        let mut k = 0;
        while k <= n {
            exact[row + k] = if k == 0 || k == n {
                1
            } else {
                let prev = (n - 1) * n / 2;
                exact[prev + k - 1] + exact[prev + k]
            };
            rounded[row + k] = exact[row + k] as f64;
            k += 1;
        }
        n += 1;
    }
    rounded
}

/// The row `C(n, 0 ..= n)` of the binomial table (correctly rounded, exact up to `n = 56`), or
/// `None` above [`BINOMIAL_TABLE_MAX`].
pub(crate) fn binomial_row(n: usize) -> Option<&'static [f64]> {
    (n <= BINOMIAL_TABLE_MAX).then(|| &BINOMIAL[n * (n + 1) / 2..=n * (n + 1) / 2 + n])
}

/// Binomial coefficients `C(n, 0..=n)` in `f64` (exact up to `n = 56`, a few ulps beyond).
pub(crate) fn binomials(n: usize) -> Vec<f64> {
    let mut c = Vec::with_capacity(n + 1);
    let mut v = 1.0_f64;
    c.push(v);
    for j in 1..=n {
        v = v * (n + 1 - j) as f64 / j as f64;
        c.push(v);
    }
    for j in 0..=n / 2 {
        c[n - j] = c[j];
    }
    c
}

/// Weights `w_i = C(n,i) C(r,j−i) / C(n+r,j)` of point `u_i` in the elevated point `u'_j`, for
/// `i = lo..=hi` with `lo = max(0, j−r)`, `hi = min(j, n)`, written to `out[..=hi−lo]`. Returns
/// `lo`.
///
/// Up to `n + r = 56` ([`EXACT_BINOMIAL_MAX`]) the binomials come from a table and are exact,
/// and so is the numerator (`C(n,i) C(r,j−i) ≤ C(n+r,j) < 2^53` by Vandermonde's identity): each
/// weight is the correctly rounded quotient of two exact integers, one division. Above, the
/// weights are hypergeometric probabilities built from their ratios starting at the mode (so
/// nothing overflows at any degree) and normalised by their sum, which is exactly 1
/// (Vandermonde's identity); each weight is then accurate to a few ulps.
pub(crate) fn elevation_weights_into(n: usize, r: usize, j: usize, out: &mut [f64]) -> usize {
    let lo = j.saturating_sub(r);
    let hi = j.min(n);
    debug_assert!(lo <= hi && out.len() > hi - lo, "weights buffer too short");
    if let (true, Some(row_n), Some(row_r), Some(row_nr)) = (
        n + r <= EXACT_BINOMIAL_MAX,
        binomial_row(n),
        binomial_row(r),
        binomial_row(n + r),
    ) {
        let total = row_nr[j];
        for (w, i) in out.iter_mut().zip(lo..=hi) {
            // the product is an exact integer below 2^53
            *w = row_n[i] * row_r[j - i] / total;
        }
        return lo;
    }
    ratio_weights_into(n, r, j, out)
}

/// The weights of [`elevation_weights_into`] from their ratios, for any degree.
fn ratio_weights_into(n: usize, r: usize, j: usize, out: &mut [f64]) -> usize {
    let lo = j.saturating_sub(r);
    let hi = j.min(n);
    // mode of the hypergeometric distribution (population n + r, n successes, j draws)
    let mode = ((j + 1) * (n + 1) / (n + r + 2)).clamp(lo, hi);
    out[mode - lo] = 1.0;
    for i in mode..hi {
        // w(i+1)/w(i) = (n−i)(j−i) / ((i+1)(r−j+i+1))
        let ratio = ((n - i) * (j - i)) as f64 / ((i + 1) * (r + i + 1 - j)) as f64;
        out[i + 1 - lo] = out[i - lo] * ratio;
    }
    for i in (lo + 1..=mode).rev() {
        // w(i−1)/w(i) = i(r−j+i) / ((n−i+1)(j−i+1))
        let ratio = (i * (r + i - j)) as f64 / ((n - i + 1) * (j - i + 1)) as f64;
        out[i - 1 - lo] = out[i - lo] * ratio;
    }
    let sum: f64 = out[..=hi - lo].iter().sum();
    for w in &mut out[..=hi - lo] {
        *w /= sum;
    }
    lo
}

/// Largest band (in numbers) [`elevate`] keeps between calls: 64 Ki numbers, 512 KiB.
const KEPT_BAND_MAX: usize = 1 << 16;

thread_local! {
    /// `(n, r, band)` of this thread's last one-step elevation ([`elevate`]).
    static LAST_BAND: RefCell<(usize, usize, Vec<f64>)> =
        const { RefCell::new((usize::MAX, 0, Vec::new())) };
}

/// One-step elevation by `r` into a new vector (document 004 eq. 8 in closed form): the band of
/// weights ([`elevation_band`]) applied to `src` (`n + 1` points of `dim` coordinates).
/// O((n+1)(r+1)·dim), the same arithmetic as an [`ElevationPlan`](crate::ElevationPlan).
///
/// The band depends on `(n, r)` only, and forming it (`n + r + 1` divisions, `(n+1)(r+1)`
/// products) costs more than applying it to a 3-D curve: 0.38 µs a call against the plan's
/// 0.10 µs for 10 → 20. So the last band of each thread (up to [`KEPT_BAND_MAX`] numbers) is kept,
/// and a run of elevations between the same degrees forms it once. The numbers are the same
/// either way (tested).
pub(crate) fn elevate(src: &[f64], dim: usize, r: usize) -> Vec<f64> {
    let n_pts = src.len() / dim;
    let mut out = vec![0.0; (n_pts + r) * dim];
    if n_pts == 0 {
        return out;
    }
    let n = n_pts - 1;
    let kept = (n + 1).saturating_mul(band_stride(r)) <= KEPT_BAND_MAX
        && LAST_BAND
            .try_with(|slot| {
                // (a slot in use or a thread being torn down: form the band afresh)
                let Ok(mut slot) = slot.try_borrow_mut() else {
                    return false;
                };
                if (slot.0, slot.1) != (n, r) {
                    *slot = (n, r, elevation_band(n, r));
                }
                apply_band(&slot.2, r, src, dim, &mut out);
                true
            })
            .unwrap_or(false);
    if !kept {
        apply_band(&elevation_band(n, r), r, src, dim, &mut out);
    }
    out
}

/// Checks that `points × dim` scalars can be allocated.
pub(crate) fn check_size(what: impl Into<What>, points: usize, dim: usize) -> Result<()> {
    let what: What = what.into();
    match points.checked_mul(dim) {
        Some(size) if size <= MAX_SCALARS => Ok(()),
        other => Err(Error::TooLarge {
            what,
            size: other.unwrap_or(usize::MAX),
            max: MAX_SCALARS,
        }),
    }
}

/// Zeros on each side of a row of an [`elevation_band`]: one fewer than [`BLOCK`], so that a
/// block of new points reads its weights from any old point's row without a bounds case.
pub(crate) const BAND_PAD: usize = BLOCK - 1;

/// New points [`gather_band`] sums at once, per coordinate (two 4-wide vectors).
const BLOCK: usize = 8;

/// Length of a row of an [`elevation_band`] for elevation by `r`.
pub(crate) fn band_stride(r: usize) -> usize {
    r + 1 + 2 * BAND_PAD
}

/// The weights of elevation from degree `n` by `r` as a zero-padded band: row `i` (of
/// [`band_stride`]`(r)` numbers) holds [`BAND_PAD`] zeros, the weights `C(n,i) C(r,l) /
/// C(n+r,i+l)` of old point `i` in new points `i + l`, `l = 0 … r` (document 004 eq. 8), and
/// [`BAND_PAD`] zeros.
///
/// Up to `n + r = 131` from the binomial table, with the reciprocal of each denominator
/// computed once (`n + r + 1` divisions in all): up to `n + r = 56` the table and the numerator
/// are exact integers, so each weight is within an ulp (two roundings); above, the three
/// binomials are correctly rounded and each weight is within about three ulps. Beyond 131, row
/// by row with [`elevation_weights_into`].
pub(crate) fn elevation_band(n: usize, r: usize) -> Vec<f64> {
    let stride = band_stride(r);
    let mut band = vec![0.0; (n + 1) * stride];
    if let (Some(row_n), Some(row_r), Some(row_nr)) =
        (binomial_row(n), binomial_row(r), binomial_row(n + r))
    {
        let inv: Vec<f64> = row_nr[..=n + r].iter().map(|c| 1.0 / c).collect();
        for ((row, &cn), inv) in band
            .chunks_exact_mut(stride)
            .zip(&row_n[..=n])
            .zip(inv.windows(r + 1))
        {
            for ((x, &cr), &v) in row[BAND_PAD..].iter_mut().zip(&row_r[..=r]).zip(inv) {
                *x = cn * cr * v;
            }
        }
        return band;
    }
    let mut scratch = vec![0.0; n + 1];
    for j in 0..=n + r {
        let lo = elevation_weights_into(n, r, j, &mut scratch);
        for i in lo..=j.min(n) {
            band[i * stride + BAND_PAD + (j - i)] = scratch[i - lo];
        }
    }
    band
}

/// Applies an [`elevation_band`] for elevation by `r` to `control` (point-major, `dim ≥ 1`
/// coordinates), overwriting `out`. Every new point is summed over the old points in increasing
/// order, one multiply and one add a term, as a direct evaluation of eq. 8 would. Dimensions 1
/// to 4 take [`gather_band`]; others scatter each old point into its `r + 1` new points (the
/// same sums, tested). The caller checks the lengths.
pub(crate) fn apply_band(band: &[f64], r: usize, control: &[f64], dim: usize, out: &mut [f64]) {
    match dim {
        1 => gather_band::<1>(band, r, control, out),
        2 => gather_band::<2>(band, r, control, out),
        3 => gather_band::<3>(band, r, control, out),
        4 => gather_band::<4>(band, r, control, out),
        _ => scatter_band(band, r, control, dim, out),
    }
}

/// The point-major scatter of [`apply_band`]: old point `i` times each weight of its row, added
/// to the new points `i … i + r` (document 004 eq. 8 term by term).
pub(crate) fn scatter_band(band: &[f64], r: usize, control: &[f64], dim: usize, out: &mut [f64]) {
    let width = r + 1;
    out.fill(0.0);
    for (i, (p, row)) in control
        .chunks_exact(dim)
        .zip(band.chunks_exact(band_stride(r)))
        .enumerate()
    {
        let o = &mut out[i * dim..(i + width) * dim];
        for (oc, &wl) in o
            .chunks_exact_mut(dim)
            .zip(&row[BAND_PAD..BAND_PAD + width])
        {
            for (x, y) in oc.iter_mut().zip(p) {
                *x += wl * y;
            }
        }
    }
}

crate::numeric::isa::avx2_dispatch! {
    /// [`gather_band_body`] compiled with AVX2 where the processor has it, else as built
    /// ([`crate::numeric::isa`]: the same bits, tested).
    fn gather_band<const D: usize>(band: &[f64], r: usize, control: &[f64], out: &mut [f64])
        = gather_band_body;
}

/// [`apply_band`] for `D` coordinates known at compile time: the new points a [`BLOCK`] at a
/// time, each block's `D × BLOCK` sums held in registers while the old points that reach it
/// (`i = j₀ − r … j₀ + BLOCK − 1`) are added in increasing order, the block's weights of old
/// point `i` being `BLOCK` consecutive numbers of its padded row.
///
/// Why not the scatter: its three coordinates a weight are scalar read-modify-writes of memory
/// (about one multiply-add a cycle). A vector axpy of a row into coordinate-major
/// accumulators was tried and was slower (10 → 20 in 3-D: 96 → 244 ns): the windows of
/// consecutive rows overlap by all but one number, so each vector load straddles two earlier
/// stores and store-to-load forwarding fails. Held in registers, the sums touch memory once.
///
/// The same bits as the scatter for finite input: each sum adds its products in increasing `i`
/// from `+0.0`; the extra terms are the padding's zeros times a finite coordinate, `±0.0`,
/// which leave a sum that starts at `+0.0` unchanged. (A non-finite coordinate spreads to the
/// whole blocks it reaches, up to [`BAND_PAD`] new points beyond those the scatter would spoil.)
#[inline(always)]
pub(crate) fn gather_band_body<const D: usize>(
    band: &[f64],
    r: usize,
    control: &[f64],
    out: &mut [f64],
) {
    let stride = band_stride(r);
    let last_old = (control.len() / D).saturating_sub(1);
    for (b, block) in out.chunks_mut(BLOCK * D).enumerate() {
        let j0 = b * BLOCK;
        let mut acc = [[0.0_f64; BLOCK]; D];
        for i in j0.saturating_sub(r)..=(j0 + BLOCK - 1).min(last_old) {
            // the weights of old point i in new points j0 … j0 + BLOCK − 1: positions
            // j0 − i ≥ −BAND_PAD … of its row, within the padding on both sides
            let base = i * stride + BAND_PAD + j0 - i;
            let w = &band[base..base + BLOCK];
            let p = &control[i * D..i * D + D];
            for (a, &s) in acc.iter_mut().zip(p) {
                for (x, &wt) in a.iter_mut().zip(w) {
                    *x += wt * s;
                }
            }
        }
        for (t, o) in block.chunks_exact_mut(D).enumerate() {
            for (x, a) in o.iter_mut().zip(&acc) {
                *x = a[t];
            }
        }
    }
}

#[cfg(test)]
mod tests {
    /// The kept band gives the numbers a freshly formed band gives, whichever elevation came
    /// before, and a band over the limit is formed every time.
    #[test]
    fn kept_elevation_band_changes_nothing() {
        use super::{apply_band, elevate, elevation_band, KEPT_BAND_MAX};
        let fresh = |src: &[f64], dim: usize, r: usize| {
            let mut out = vec![0.0; (src.len() / dim + r) * dim];
            apply_band(
                &elevation_band(src.len() / dim - 1, r),
                r,
                src,
                dim,
                &mut out,
            );
            out
        };
        let net = |pts: usize, dim: usize| -> Vec<f64> {
            (0..pts * dim)
                .map(|i| (i as f64 * 0.7).sin() * 3.0 + 1.0)
                .collect()
        };
        // alternate degrees and elevations so that the slot both hits and misses
        for (pts, dim, r) in [
            (11, 3, 10),
            (11, 3, 10),
            (5, 2, 3),
            (11, 3, 10),
            (11, 2, 4),
            (5, 2, 3),
        ] {
            let src = net(pts, dim);
            assert_eq!(
                elevate(&src, dim, r),
                fresh(&src, dim, r),
                "{pts} points by {r}"
            );
        }
        // too large to keep: (n + 1) rows of r + 1 + 2·BAND_PAD numbers above the limit
        let (pts, r) = (300, KEPT_BAND_MAX / 300);
        let src = net(pts, 1);
        assert_eq!(elevate(&src, 1, r), fresh(&src, 1, r), "large band");
        // and the kept slot still serves the small one afterwards
        let src = net(11, 3);
        assert_eq!(
            elevate(&src, 3, 10),
            fresh(&src, 3, 10),
            "after the large band"
        );
    }

    #[test]
    fn exact_binomial_weights_agree_with_the_ratio_weights() {
        use super::{binomial_row, elevation_weights_into, ratio_weights_into, EXACT_BINOMIAL_MAX};
        // the table is Pascal's triangle, exact up to C(56, 28) (below 2^53), rounded beyond
        let row = |n| binomial_row(n).unwrap();
        assert_eq!(row(56)[28], 7_648_690_600_760_440.0);
        assert!(row(56)[28] < 2.0_f64.powi(53));
        assert_eq!(row(10)[3], 120.0);
        assert_eq!(row(10).len(), 11);
        // C(131, 65) = 188694833082770476622296176145946360850 (exact, rounded once)
        assert_eq!(
            row(131)[65],
            188_694_833_082_770_476_622_296_176_145_946_360_850_u128 as f64
        );
        assert!(binomial_row(132).is_none());
        let (mut a, mut b) = ([0.0; 64], [0.0; 64]);
        for n in 0..=EXACT_BINOMIAL_MAX {
            for r in 0..=EXACT_BINOMIAL_MAX - n {
                for j in 0..=n + r {
                    let lo = elevation_weights_into(n, r, j, &mut a);
                    assert_eq!(lo, ratio_weights_into(n, r, j, &mut b));
                    let count = j.min(n) - lo + 1;
                    let sum: f64 = a[..count].iter().sum();
                    assert!((sum - 1.0).abs() <= 64.0 * f64::EPSILON, "sum {sum}");
                    for (x, y) in a[..count].iter().zip(&b[..count]) {
                        assert!(
                            (x - y).abs() <= 8.0 * f64::EPSILON * x.max(*y),
                            "n {n}, r {r}, j {j}: {x} vs {y}"
                        );
                    }
                }
            }
        }
    }
}
