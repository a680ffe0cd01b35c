//! Breakpoints of the pp-form (document 003 §4, docs/theory/pp.md): the strict validation
//! `ξ_1 < … < ξ_{l+1}` of lekalo's own constructors, and SciPy's looser test that pieces come
//! sorted one way or the other.

use super::check_width;
use crate::error::{check_finite, readable, Error, Result};
use crate::Arg;

/// Whether the breakpoints are sorted one way: every difference `ξ_{i+1} − ξ_i ≥ 0`, or every
/// one `≤ 0` (repeated breakpoints allowed; a NaN, or a difference of equal infinities, makes
/// it false). The test of SciPy's `PPoly` and `BPoly` (`np.all(dx >= 0) or np.all(dx <= 0)`
/// on `dx = np.diff(x)`), whose pieces may be given in either order, without its temporaries:
/// with finite ends, neighbours compared in one vectorised pass (4-wide with AVX2) over blocks
/// of 1024, stopping at the first block that has both orders (between finite ends of a sorted
/// array every number is finite, so comparing is subtracting); with an infinite or NaN end,
/// the differences themselves. O(n), no allocation. Fewer than two breakpoints are sorted.
///
/// ```
/// use lekalo::breakpoints_sorted;
/// assert!(breakpoints_sorted(&[0.0, 1.0, 1.0, 2.0]));
/// assert!(breakpoints_sorted(&[3.0, 2.0, 2.0]));
/// assert!(!breakpoints_sorted(&[0.0, 2.0, 1.0]));
/// assert!(!breakpoints_sorted(&[0.0, f64::NAN, 1.0]));
/// assert!(!breakpoints_sorted(&[0.0, f64::INFINITY, f64::INFINITY]));
/// ```
#[must_use]
pub fn breakpoints_sorted(breakpoints: &[f64]) -> bool {
    let n = breakpoints.len();
    if n < 2 {
        return true;
    }
    if !(breakpoints[0].is_finite() && breakpoints[n - 1].is_finite()) {
        let mut d = breakpoints.windows(2).map(|w| w[1] - w[0]);
        return d.clone().all(|v| v >= 0.0) || d.all(|v| v <= 0.0);
    }
    sorted_one_way(breakpoints)
}

crate::numeric::isa::avx2_dispatch! {
    /// [`sorted_one_way_body`] compiled with AVX2 where the processor has it, else as built
    /// ([`crate::numeric::isa`]).
    fn sorted_one_way(x: &[f64]) -> bool = sorted_one_way_body;
}

/// Whether `x` (at least two numbers) is non-decreasing or non-increasing by comparisons of
/// neighbours (NaN compares false both ways), a block of 1024 at a time.
#[inline(always)]
fn sorted_one_way_body(x: &[f64]) -> bool {
    const BLOCK: usize = 1024;
    let n = x.len();
    // every neighbour ≥ its predecessor so far; every one ≤ it (a NaN is neither)
    let (mut ascending, mut descending) = (true, true);
    let mut start = 0;
    while start + 1 < n && (ascending || descending) {
        let end = (start + BLOCK).min(n - 1);
        let (from, to) = (&x[start..end], &x[start + 1..=end]);
        for (a, b) in from.iter().zip(to) {
            ascending &= b >= a;
            descending &= b <= a;
        }
        start = end;
    }
    ascending || descending
}

/// Validates breakpoints `ξ_1 < … < ξ_{l+1}` (document 003 §4): at least two, finite,
/// strictly increasing, with a width `ξ_{l+1} − ξ_1` that does not overflow.
///
/// # Errors
/// [`Error::TooFew`], [`Error::NonFinite`], [`Error::InvalidArgument`].
pub(crate) fn check_breakpoints(breakpoints: &[f64]) -> Result<()> {
    if breakpoints.len() < 2 {
        return Err(Error::TooFew {
            what: Arg::Breakpoints.into(),
            min: 2,
            got: breakpoints.len(),
        });
    }
    check_finite(Arg::Breakpoints, breakpoints)?;
    if let Some(i) = breakpoints.windows(2).position(|w| w[0] >= w[1]) {
        return Err(Error::InvalidArgument {
            what: Arg::Breakpoints.into(),
            reason: format!(
                "must be strictly increasing, but breakpoint {i} = {} is not less than breakpoint {} = {}",
                readable(&breakpoints[i]),
                i + 1,
                readable(&breakpoints[i + 1])
            ),
        });
    }
    check_width(
        Arg::Breakpoints,
        breakpoints[0],
        breakpoints[breakpoints.len() - 1],
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn breakpoints_sorted_is_numpys_test_of_the_differences() {
        // np.all(dx >= 0) or np.all(dx <= 0) on dx = np.diff(x), across the block size
        let naive = |x: &[f64]| {
            let d: Vec<f64> = x.windows(2).map(|w| w[1] - w[0]).collect();
            d.iter().all(|&v| v >= 0.0) || d.iter().all(|&v| v <= 0.0)
        };
        let up: Vec<f64> = (0..3000).map(|i| f64::from(i / 3)).collect();
        let down: Vec<f64> = up.iter().rev().copied().collect();
        let mut cases = vec![vec![], vec![1.0], vec![2.0, 2.0], up.clone(), down.clone()];
        for at in [1, 1023, 1024, 1025, 2999] {
            for bad in [f64::NAN, -5.0, 5000.0] {
                let mut x = up.clone();
                x[at] = bad;
                cases.push(x);
                let mut x = down.clone();
                x[at] = bad;
                cases.push(x);
            }
        }
        cases.push(vec![0.0, f64::INFINITY]);
        cases.push(vec![0.0, f64::INFINITY, f64::INFINITY]);
        cases.push(vec![f64::NEG_INFINITY, f64::NEG_INFINITY]);
        for x in &cases {
            assert_eq!(
                breakpoints_sorted(x),
                naive(x),
                "{:?}",
                &x[..x.len().min(4)]
            );
        }
    }
}
