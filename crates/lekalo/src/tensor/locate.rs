//! Knot-span location for batches of points, and what a batch does at a point beyond the
//! domain ([`Beyond`], the spans and coordinates of a point under a batch's rule, `locate`).
//! Per direction, the bucket table of the curve
//! evaluator ([`PieceLocator`], `curve/fast_eval/locate.rs`) over the distinct knots of the
//! domain, built once per batch in `O(|T_a|)`. A point's span then costs O(1) for spread-out
//! knots and O(log m) at worst, in any order of the points, where a binary search (P&T
//! Algorithm A2.1) costs `log2 |T_a|` unpredictable branches.

use crate::curve::PieceLocator;
use crate::error::{Error, Result};

/// What a batch does at a point outside the domain (or with a coordinate that is not finite):
/// [`TensorBSplineRef::par_eval_batch_beyond`]. A point with a NaN coordinate gets `NaN` values
/// in every mode, one with an infinite coordinate in every mode but [`Beyond::Clamp`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Beyond {
    /// The polynomials of the end spans continued (SciPy's `NdBSpline(..., extrapolate=True)`).
    Continue,
    /// Each coordinate taken at the nearest end of its domain, `±∞` included (FITPACK's
    /// `fpbisp`, SciPy's `bisplev` and `RectBivariateSpline.ev`).
    Clamp,
    /// `NaN` values (SciPy's `extrapolate=False`).
    Nan,
}

/// How a batch treats the points: refuse those outside the domain, continue the end spans
/// (points checked finite before), or one of the [`Beyond`] rules.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Mode {
    Refuse,
    Extrapolate,
    Beyond(Beyond),
}

/// The span search of one direction: [`SpanTable::find`] gives the span of
/// [`span_in`](crate::knots::span_in) (`t_i ≤ t < t_{i+1}`, the last non-empty span at the right
/// end) through the bucket table of the pieces.
#[derive(Debug, Clone)]
pub(crate) struct SpanTable {
    /// Distinct knots of the domain `x_0 < … < x_m`.
    breaks: Vec<f64>,
    /// Knot span index `i` (`t_i = x_j < t_{i+1}`) of piece `j`.
    spans: Vec<usize>,
    locator: PieceLocator,
    /// The answer of every bucket of `locator` whose parameters fall in at most two pieces.
    buckets: Vec<Bucket>,
}

/// What a bucket of the span table answers without reading the pieces: the break `x_{j+1}`
/// between its two candidate pieces `j`, `j + 1` (`+∞` for a bucket inside one piece) and the
/// spans of both, so that a parameter's span is one read of the table and one comparison
/// instead of three dependent reads (bucket, break, span). `break_at` is NaN for a bucket with
/// more candidates (very uneven knots), which the piece search answers.
#[derive(Debug, Clone, Copy)]
struct Bucket {
    break_at: f64,
    below: u32,
    above: u32,
}

impl SpanTable {
    /// The table of the sorted knots `knots` of a direction of degree `p` (validated: at least
    /// `2p + 2` knots, a non-empty domain `[t_p, t_{n}]`, `n = |T| − p − 1`). O(|T|).
    pub(crate) fn new(knots: &[f64], p: usize) -> Self {
        let n = knots.len() - p - 1;
        let mut breaks = Vec::with_capacity(n - p + 1);
        let mut spans = Vec::with_capacity(n - p);
        for i in p..n {
            if knots[i] < knots[i + 1] {
                breaks.push(knots[i]);
                spans.push(i);
            }
        }
        debug_assert!(!spans.is_empty(), "validated knots have a non-empty domain");
        breaks.push(knots[n]);
        let locator = PieceLocator::new(&breaks);
        let buckets = locator
            .ranges()
            .iter()
            .map(|&(lo, hi)| {
                let span = |j: usize| u32::try_from(spans[j]).ok();
                match (span(lo), span(hi)) {
                    (Some(below), Some(above)) if hi - lo <= 1 => Bucket {
                        break_at: if hi > lo {
                            breaks[lo + 1]
                        } else {
                            f64::INFINITY
                        },
                        below,
                        above,
                    },
                    _ => Bucket {
                        break_at: f64::NAN,
                        below: 0,
                        above: 0,
                    },
                }
            })
            .collect();
        SpanTable {
            breaks,
            spans,
            locator,
            buckets,
        }
    }

    /// The span of `t`, which lies in the domain `[t_p, t_n]`: the span of
    /// [`span_in`](crate::knots::span_in).
    #[inline(always)]
    pub(crate) fn find(&self, t: f64) -> usize {
        debug_assert!(
            t >= self.breaks[0] && t <= self.breaks[self.breaks.len() - 1],
            "t in the domain"
        );
        let b = self.buckets[self.locator.bucket(t)];
        if b.break_at.is_nan() {
            return self.spans[self.locator.find(&self.breaks, t)];
        }
        // u32 spans widen losslessly
        (if b.break_at <= t { b.above } else { b.below }) as usize
    }
}

/// The spans of the point `x` into `spans` and the coordinates at which the basis functions are
/// evaluated into `point`: `false` when the point's values are `NaN` ([`Beyond`] rules).
/// Inside the domain every mode finds the span of [`span_in`] (by the bucket search of
/// [`SpanTable`]) and evaluates at `x`.
///
/// # Errors
/// [`Error::ParameterOutOfDomain`] outside the domain in the refusing mode.
#[inline(always)]
pub(super) fn locate(
    mode: Mode,
    x: &[f64],
    domains: &[(f64, f64)],
    tables: &[SpanTable],
    spans: &mut [usize],
    point: &mut [f64],
) -> Result<bool> {
    if let Mode::Beyond(b) = mode {
        for (&t, &(lo, hi)) in x.iter().zip(domains) {
            if !beyond_defined(t, b, lo, hi) {
                return Ok(false);
            }
        }
    }
    for (a, table) in tables.iter().enumerate() {
        let (lo, hi) = domains[a];
        let t = x[a];
        spans[a] = match mode {
            Mode::Refuse if !(t >= lo && t <= hi) => {
                return Err(Error::ParameterOutOfDomain {
                    t,
                    min: lo,
                    max: hi,
                })
            }
            Mode::Refuse => table.find(t),
            // checked (finite, or infinite and clamped): the span of the nearest domain end
            _ => table.find(t.clamp(lo, hi)),
        };
        point[a] = if mode == Mode::Beyond(Beyond::Clamp) {
            t.clamp(lo, hi)
        } else {
            t
        };
    }
    Ok(true)
}

/// Whether a coordinate `t` has values under the rule `beyond` on the domain `[lo, hi]`: not
/// NaN; finite unless clamped (an infinite coordinate is taken at its end, as FITPACK's
/// `fpbisp` takes it); inside the domain for [`Beyond::Nan`].
#[inline(always)]
pub(super) fn beyond_defined(t: f64, beyond: Beyond, lo: f64, hi: f64) -> bool {
    match beyond {
        Beyond::Clamp => !t.is_nan(),
        Beyond::Continue => t.is_finite(),
        Beyond::Nan => t >= lo && t <= hi,
    }
}

#[cfg(test)]
mod tests {
    use proptest::prelude::*;

    use super::SpanTable;
    use crate::knots::span_in;
    use crate::oracle::proptest_config;

    /// Knots of degree `p`: clamped or not, with repeated interior knots, uneven spacing.
    fn knots() -> impl Strategy<Value = (Vec<f64>, usize)> {
        (
            0usize..=5,
            prop::collection::vec((0.0f64..1.0, 1usize..=3), 1..12),
        )
            .prop_map(|(p, raw)| {
                let mut t: Vec<f64> = vec![-1.0; p + 1];
                let mut inner: Vec<(f64, usize)> = raw;
                inner.sort_by(|a, b| a.0.total_cmp(&b.0));
                for (x, m) in inner {
                    t.extend(std::iter::repeat_n(x, m.min(p + 1)));
                }
                t.extend(vec![2.0; p + 1]);
                (t, p)
            })
    }

    /// Knots crowded at one end (thousands of pieces in the first bucket, where the bucket
    /// table defers to the piece search) and spread at the other: the binary search's span.
    #[test]
    fn span_table_of_crowded_knots_finds_the_binary_search_span() {
        for p in 0..=5 {
            let mut t = vec![0.0; p + 1];
            t.extend((1..3000).map(|i| f64::from(i) * 1e-9));
            t.extend((1..40).map(|i| f64::from(i) / 40.0));
            t.extend(vec![1.0; p + 1]);
            let table = SpanTable::new(&t, p);
            let mut xs: Vec<f64> = (0..=4000).map(|i| f64::from(i) / 4000.0).collect();
            xs.extend((0..=3000).map(|i| f64::from(i) * 1e-9));
            for &k in &t {
                xs.extend([k, k.next_down(), k.next_up()]);
            }
            xs.retain(|&x| (0.0..=1.0).contains(&x));
            for x in xs {
                assert_eq!(table.find(x), span_in(&t, p, x), "p = {p}, t = {x:e}");
            }
        }
    }

    proptest! {
        #![proptest_config(proptest_config(128))]

        /// The bucket search finds the span of the binary search at every knot, next to every
        /// knot (one ulp either side) and between knots.
        #[test]
        fn span_table_finds_the_binary_search_span((t, p) in knots(), u in prop::collection::vec(0.0f64..1.0, 16)) {
            let table = SpanTable::new(&t, p);
            let (lo, hi) = (t[p], t[t.len() - p - 1]);
            let mut xs: Vec<f64> = u.iter().map(|u| lo + (hi - lo) * u).collect();
            for &k in &t {
                xs.extend([k, k.next_down(), k.next_up()]);
            }
            xs.retain(|&x| x >= lo && x <= hi);
            for x in xs {
                prop_assert_eq!(table.find(x), span_in(&t, p, x), "t = {:e}", x);
            }
        }
    }
}
