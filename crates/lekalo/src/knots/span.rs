//! Knot span search: the span `i` with `t_i ≤ t < t_{i+1}` that holds a parameter, the last
//! non-empty span at the right end of the domain. Binary search (Piegl & Tiller, *The NURBS
//! Book*, 2nd ed., Algorithm A2.1), O(log n), and a cursor that walks forward from the previous
//! span for sorted batches, amortised O(1).

use super::KnotVector;
use crate::error::{Error, Result};

impl KnotVector {
    /// Knot span index `i` with `t_i ≤ t < t_{i+1}` for a spline of `degree`; at the right end of
    /// the domain, the last non-empty span. Binary search (P&T Algorithm A2.1), O(log n).
    ///
    /// # Errors
    /// [`Error::ParameterOutOfDomain`] if `t` is outside `[t_p, t_{n+1}]` or NaN;
    /// [`Error::Degree`] if the knots are too few for `degree`.
    pub fn find_span(&self, degree: usize, t: f64) -> Result<usize> {
        self.check_degree(degree)?;
        let (min, max) = self.domain(degree);
        if !(t >= min && t <= max) || min >= max {
            return Err(Error::ParameterOutOfDomain { t, min, max });
        }
        Ok(self.span_unchecked(degree, t))
    }

    /// `Ok` if the knots carry a spline of `degree`: at least `2·degree + 2` of them (a single
    /// control point of that degree).
    ///
    /// # Errors
    /// [`Error::Degree`] naming the largest degree the knots carry.
    pub(crate) fn check_degree(&self, degree: usize) -> Result<()> {
        // len < 2·degree + 2, without overflow
        if self.knots.len() / 2 <= degree {
            return Err(Error::Degree {
                degree,
                reason: format!(
                    "{} knots carry a degree of at most {}",
                    self.knots.len(),
                    (self.knots.len() / 2).saturating_sub(1)
                ),
            });
        }
        Ok(())
    }

    /// Span search without domain checks; `t` must lie in the non-empty domain.
    #[inline]
    pub(crate) fn span_unchecked(&self, degree: usize, t: f64) -> usize {
        span_in(&self.knots, degree, t)
    }

    /// A cursor for span search over a batch of parameters: amortised O(1) per parameter when
    /// they come sorted (it walks forward from the previous span), O(log n) otherwise.
    ///
    /// ```
    /// use lekalo::KnotVector;
    /// let kv = KnotVector::clamped_uniform(3, 10).unwrap();
    /// let mut cursor = kv.span_cursor(3);
    /// for k in 0..=100 {
    ///     let t = k as f64 / 100.0;
    ///     assert_eq!(cursor.find(t).unwrap(), kv.find_span(3, t).unwrap());
    /// }
    /// ```
    #[must_use]
    pub fn span_cursor(&self, degree: usize) -> SpanCursor<'_> {
        SpanCursor::over(&self.knots, degree)
    }
}

/// The span `i` in `p..size` of `t` in the domain: the last `i` with `t_i ≤ t`, by binary search
/// over `p + 1..size` (Algorithm A2.1), then the nearest non-empty span (below it at the right
/// end and in runs of repeated knots, above it at the left end); always in `p..size`, whatever
/// the knots.
#[allow(clippy::neg_cmp_op_on_partial_ord)] // NaN knots must read as an empty span
pub(crate) fn span_by(knot: &impl Fn(usize) -> f64, p: usize, size: usize, t: f64) -> usize {
    let (mut a, mut b) = (p + 1, size);
    while a < b {
        let m = a + (b - a) / 2;
        if knot(m) <= t {
            a = m + 1;
        } else {
            b = m;
        }
    }
    let mut i = (a - 1).clamp(p, size - 1);
    while i > p && !(knot(i) < knot(i + 1)) {
        i -= 1;
    }
    while i < size - 1 && !(knot(i) < knot(i + 1)) {
        i += 1;
    }
    i
}

/// [`KnotVector::span_unchecked`] on sorted knots given as a slice (at least `2·degree + 2`
/// of them, `t` in the non-empty domain): the span `i` with `t_i ≤ t < t_{i+1}`, at the right
/// end the last non-empty span (P&T Algorithm A2.1 by binary search).
#[inline]
pub(crate) fn span_in(knots: &[f64], degree: usize, t: f64) -> usize {
    let n = knots.len() - degree - 2; // last control point index
    let end = knots[n + 1];
    if t >= end {
        // right end: last non-empty span
        let mut i = n;
        while i > degree && knots[i] >= end {
            i -= 1;
        }
        return i;
    }
    let first_greater = knots.partition_point(|&k| k <= t);
    (first_greater - 1).clamp(degree, n)
}

/// Span search with memory of the previous span (see [`KnotVector::span_cursor`]).
#[derive(Debug, Clone)]
pub struct SpanCursor<'a> {
    knots: &'a [f64],
    degree: usize,
    span: usize,
}

impl<'a> SpanCursor<'a> {
    /// Longest forward walk before falling back to binary search.
    const MAX_WALK: usize = 8;

    /// A cursor over sorted knots given as a slice (validated by the caller, as a
    /// [`KnotVector`]'s are).
    pub(crate) fn over(knots: &'a [f64], degree: usize) -> Self {
        SpanCursor {
            knots,
            degree,
            span: degree,
        }
    }

    /// Span of `t`, as [`KnotVector::find_span`].
    ///
    /// # Errors
    /// As [`KnotVector::find_span`].
    pub fn find(&mut self, t: f64) -> Result<usize> {
        let k = self.knots;
        let p = self.degree;
        if k.len() / 2 <= p {
            return Err(Error::Degree {
                degree: p,
                reason: format!(
                    "{} knots carry a degree of at most {}",
                    k.len(),
                    (k.len() / 2).saturating_sub(1)
                ),
            });
        }
        let (min, max) = (k[p], k[k.len() - p - 1]);
        if !(t >= min && t <= max) || min >= max {
            return Err(Error::ParameterOutOfDomain { t, min, max });
        }
        Ok(self.find_unchecked(t))
    }

    /// Span of `t` already known to be in the domain.
    #[inline]
    pub(crate) fn find_unchecked(&mut self, t: f64) -> usize {
        let k = self.knots;
        let n = k.len() - self.degree - 2;
        let s = self.span;
        // the cursor only ever holds non-empty spans; the right end belongs to span n only when
        // span n is non-empty (otherwise to the last non-empty span, found below)
        if k[s] <= t && (t < k[s + 1] || (s == n && t == k[s + 1] && k[s] < k[s + 1])) {
            return s;
        }
        if t > k[s] {
            let mut i = s;
            for _ in 0..Self::MAX_WALK {
                if i >= n {
                    break;
                }
                i += 1;
                if k[i] <= t && t < k[i + 1] {
                    self.span = i;
                    return i;
                }
            }
        }
        self.span = span_in(k, self.degree, t);
        self.span
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn span_search_edges() {
        let kv = KnotVector::new(vec![0.0, 0.0, 0.0, 0.5, 0.5, 1.0, 1.0, 1.0]).unwrap();
        assert_eq!(kv.find_span(2, 0.0).unwrap(), 2);
        assert_eq!(kv.find_span(2, 0.49).unwrap(), 2);
        assert_eq!(kv.find_span(2, 0.5).unwrap(), 4);
        assert_eq!(kv.find_span(2, 1.0).unwrap(), 4);
        assert!(matches!(
            kv.find_span(2, 1.0 + 1e-12),
            Err(Error::ParameterOutOfDomain { .. })
        ));
        assert!(matches!(
            kv.find_span(2, f64::NAN),
            Err(Error::ParameterOutOfDomain { .. })
        ));
        assert!(matches!(kv.find_span(4, 0.5), Err(Error::Degree { .. })));
    }

    #[test]
    fn empty_last_span_is_never_returned() {
        // degree 2, 6 control points, domain [t_2, t_6] = [0, 1]; span 5 = [1, 1) is empty
        let kv = KnotVector::new(vec![0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0, 2.0, 2.0]).unwrap();
        kv.validate_for(2, 6).unwrap();
        assert_eq!(kv.find_span(2, 1.0).unwrap(), 3);
        let mut c = kv.span_cursor(2);
        for t in [0.0, 0.6, 1.0, 0.2, 1.0] {
            let s = c.find(t).unwrap();
            assert!(
                kv.as_slice()[s] < kv.as_slice()[s + 1],
                "empty span {s} at t = {t}"
            );
            assert_eq!(s, kv.find_span(2, t).unwrap(), "t = {t}");
        }
    }

    #[test]
    fn cursor_agrees_with_binary_search_in_any_order() {
        let kv = KnotVector::new(vec![0.0, 0.0, 0.1, 0.1, 0.3, 0.7, 0.7, 0.9, 1.0, 1.0]).unwrap();
        let mut c = kv.span_cursor(1);
        let ts = [
            0.0, 0.05, 0.1, 0.2, 0.3, 0.69, 0.7, 0.95, 1.0, 0.0, 0.5, 1.0, 0.1,
        ];
        for t in ts {
            assert_eq!(c.find(t).unwrap(), kv.find_span(1, t).unwrap(), "t = {t}");
        }
        assert!(c.find(-0.1).is_err());
    }
}
