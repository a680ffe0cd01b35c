//! Knot-span location for batches of points: per direction, the bucket table of the curve
//! evaluator ([`PieceLocator`], `curve/fast_eval/locate.rs`) over the distinct knots of the
//! domain, built once per batch in `O(|T_a|)`. A point's span then costs O(1) for spread-out
//! knots and O(log m) at worst, in any order of the points, where a binary search (P&T
//! Algorithm A2.1) costs `log2 |T_a|` unpredictable branches.

use crate::curve::PieceLocator;

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
        SpanTable {
            breaks,
            spans,
            locator,
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
        self.spans[self.locator.find(&self.breaks, t)]
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
        (0usize..=5, prop::collection::vec((0.0f64..1.0, 1usize..=3), 1..12)).prop_map(
            |(p, raw)| {
                let mut t: Vec<f64> = vec![-1.0; p + 1];
                let mut inner: Vec<(f64, usize)> = raw;
                inner.sort_by(|a, b| a.0.total_cmp(&b.0));
                for (x, m) in inner {
                    t.extend(std::iter::repeat_n(x, m.min(p + 1)));
                }
                t.extend(vec![2.0; p + 1]);
                (t, p)
            },
        )
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
