//! Piece location: a bucket table over the domain that gives, for any parameter, the few
//! polynomial pieces it can fall in (O(1) for spread-out knots, O(log m) at worst), and the
//! inner balls that let sorted batches skip the search.

/// Buckets of the piece-location table per polynomial piece.
const BUCKETS_PER_PIECE: usize = 4;

/// Largest candidate range searched linearly; wider ones (very uneven knots) are bisected.
const LINEAR_SEARCH_MAX: usize = 8;

/// Finds the polynomial piece of a parameter in O(1) for spread-out knots.
///
/// Bucket `b` covers the parameters with `β(t) = min(⌊(t − x_0)·s⌋, nb − 1) = b`. As `β` is
/// non-decreasing in `t` (rounding is monotone), `t` lies in a piece `j` with
/// `lo_b ≤ j ≤ hi_b`, where `lo_b` is the last piece whose start maps below `b` and `hi_b` the
/// last whose start maps to at most `b`: the table is exact despite rounding.
#[derive(Debug, Clone)]
pub(crate) struct PieceLocator {
    x0: f64,
    scale: f64,
    /// `(lo_b, hi_b)` per bucket.
    range: Vec<(usize, usize)>,
}

impl PieceLocator {
    pub(crate) fn new(breaks: &[f64]) -> Self {
        let pieces = breaks.len() - 1;
        let nb = pieces * BUCKETS_PER_PIECE;
        let x0 = breaks[0];
        // may be 0 (range overflows) or +inf (subnormal range): β stays monotone either way
        let scale = nb as f64 / (breaks[pieces] - x0);
        let mut loc = PieceLocator {
            x0,
            scale,
            range: vec![(0, 0); nb],
        };
        let starts: Vec<usize> = breaks[..pieces].iter().map(|&x| loc.bucket(x)).collect();
        // sweep: lo_b = last j with start_j < b, hi_b = last j with start_j ≤ b
        let (mut below, mut at_most) = (0usize, 0usize);
        for b in 0..nb {
            while below + 1 < pieces && starts[below + 1] < b {
                below += 1;
            }
            while at_most + 1 < pieces && starts[at_most + 1] <= b {
                at_most += 1;
            }
            loc.range[b] = (below, at_most.max(below));
        }
        loc
    }

    /// The candidate pieces `(lo_b, hi_b)` of every bucket, in the order of the buckets (for
    /// tables that keep more per bucket, the tensor span search's).
    pub(crate) fn ranges(&self) -> &[(usize, usize)] {
        &self.range
    }

    /// The bucket `β(t)` of `t` (see the type's docs).
    #[inline(always)]
    pub(crate) fn bucket(&self, t: f64) -> usize {
        // saturating float-to-int cast: monotone, NaN → 0 (NaN never gets here)
        #[allow(clippy::cast_possible_truncation)]
        let b = ((t - self.x0) * self.scale) as usize;
        b.min(self.range.len() - 1)
    }

    /// Piece `j` with `x_j ≤ t < x_{j+1}` (the last piece at `t = x_m`); `t` in the domain.
    #[inline(always)]
    pub(crate) fn find(&self, breaks: &[f64], t: f64) -> usize {
        let (lo, hi) = self.range[self.bucket(t)];
        if hi - lo <= 1 {
            // the common case, without a branch on t (random parameters mispredict it)
            lo + usize::from((hi > lo) & (breaks[lo + 1] <= t))
        } else if hi - lo <= LINEAR_SEARCH_MAX {
            let mut j = lo;
            while j < hi && breaks[j + 1] <= t {
                j += 1;
            }
            j
        } else {
            lo + breaks[lo + 1..=hi].partition_point(|&x| x <= t)
        }
    }

    /// The table as a [`SplitLocator`] when every bucket holds at most two pieces (the common
    /// case of spread-out breakpoints), else `None`. O(buckets).
    pub(crate) fn split_table(&self, breaks: &[f64]) -> Option<SplitLocator> {
        let entries = self
            .range
            .iter()
            .map(|&(lo, hi)| match hi - lo {
                0 => Some(Split { at: f64::NAN, lo }),
                1 => Some(Split {
                    at: breaks[lo + 1],
                    lo,
                }),
                _ => None,
            })
            .collect::<Option<Vec<Split>>>()?;
        Some(SplitLocator {
            x0: self.x0,
            scale: self.scale,
            entries,
        })
    }
}

/// One bucket of a [`SplitLocator`]: its first candidate piece `lo`, and the breakpoint `at`
/// from which the next one starts (NaN when the bucket holds one piece: no comparison is true).
#[derive(Debug, Clone, Copy)]
struct Split {
    at: f64,
    lo: usize,
}

/// A [`PieceLocator`] whose buckets hold at most two pieces each, stored as one entry a bucket
/// (the first piece and the breakpoint of the second), so that a point costs one table read
/// and one comparison, without a branch: `j = lo_b + [t ≥ x_{lo_b + 1}]`. For `t` in the
/// domain it finds [`PieceLocator::find`]'s piece (the same bucket, the same comparison); for
/// any other `t` (beyond the ends, infinite, NaN) some piece `j < pieces`: below the domain the
/// first, from its end on the last (the buckets are clamped, and `t` is then at or beyond every
/// breakpoint), at NaN the first bucket's.
#[derive(Debug, Clone)]
pub(crate) struct SplitLocator {
    x0: f64,
    scale: f64,
    entries: Vec<Split>,
}

impl SplitLocator {
    /// The piece of `t`: see the type's documentation. O(1).
    #[inline(always)]
    pub(crate) fn find(&self, t: f64) -> usize {
        // the bucket of PieceLocator::bucket, the same operations
        #[allow(clippy::cast_possible_truncation)]
        let b = (((t - self.x0) * self.scale) as usize).min(self.entries.len() - 1);
        let Split { at, lo } = self.entries[b];
        lo + usize::from(t >= at)
    }
}

/// Centre `m` and radius `r` of a ball inside the open interval `(a, b)` such that the computed
/// test `fl(|fl(t − m)|) < r` implies `a < t < b` exactly. With `M, H` the true midpoint and
/// half-width, the computed `m, h` (halving first, so nothing overflows) are within
/// `ε(|M| + H)` of them and `fl(t − m)` within `ε/2` relative of `t − m`; shrinking the radius
/// by `8ε(|m| + h)` (plus the smallest normal number, for subnormal knots) absorbs all of it, so the test gives `|t − M| < H`. Pieces narrower than
/// the rounding of their position get `r ≤ 0`: never inside, always located exactly.
pub(super) fn inner_ball(a: f64, b: f64) -> (f64, f64) {
    let m = 0.5 * a + 0.5 * b;
    let h = 0.5 * b - 0.5 * a;
    // MIN_POSITIVE covers the absolute rounding of halving subnormal knots
    (
        m,
        h - 8.0 * f64::EPSILON * (m.abs() + h) - f64::MIN_POSITIVE,
    )
}
