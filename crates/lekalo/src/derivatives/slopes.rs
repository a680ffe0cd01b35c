//! The `p + 1` non-zero B-spline basis functions of degree `p` at `t` and their first
//! derivatives in one Cox–de Boor pass: the triangle of P&T Algorithm A2.2, whose last level
//! already divides each degree-`(p − 1)` function by the knot difference that the derivative
//! formula needs (P&T eq. 2.9):
//!
//! `N'_{i,p}(t) = p · (N_{i,p−1}(t) / (t_{i+p} − t_i) − N_{i+1,p−1}(t) / (t_{i+p+1} − t_{i+1}))`.
//!
//! The values are bit-for-bit those of `basis_funs_into` (the same operations in the same
//! order); the derivatives cost `p` more subtractions and products. P&T A2.3 gives the same
//! derivatives for any order, at several times the cost for the first.

/// Values into `values[..=p]` and first derivatives into `slopes[..=p]` at `t` in `span`
/// (`t_span ≤ t < t_{span+1}`, or the last non-empty span at the right end). `left`, `right`
/// are scratch of length `p + 1`. O(p²), no allocation.
#[allow(clippy::too_many_arguments)] // knots, degree, span, t, two scratch rows, two outputs
#[inline]
pub(super) fn basis_with_slopes(
    knots: &[f64],
    degree: usize,
    span: usize,
    t: f64,
    left: &mut [f64],
    right: &mut [f64],
    values: &mut [f64],
    slopes: &mut [f64],
) {
    values[0] = 1.0;
    slopes[0] = 0.0;
    for j in 1..=degree {
        left[j] = t - knots[span + 1 - j];
        right[j] = knots[span + j] - t;
        let last = j == degree;
        let mut saved = 0.0;
        // at the last level, `temp` is N_{span−p+1+r, p−1} / (t_{span+r+1} − t_{span+r+1−p})
        let mut previous_temp = 0.0;
        for r in 0..j {
            let temp = values[r] / (right[r + 1] + left[j - r]);
            values[r] = saved + right[r + 1] * temp;
            saved = left[j - r] * temp;
            if last {
                slopes[r] = previous_temp - temp;
                previous_temp = temp;
            }
        }
        values[j] = saved;
        if last {
            slopes[j] = previous_temp;
        }
    }
    if degree > 0 {
        #[allow(clippy::cast_precision_loss)] // a degree
        let p = degree as f64;
        for s in &mut slopes[..=degree] {
            *s *= p;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::basis_with_slopes;
    use crate::basis::{basis_ders_into, basis_funs_into, BasisScratch};
    use crate::knots::KnotVector;
    use crate::oracle::proptest_config;
    use proptest::prelude::*;

    proptest! {
        #![proptest_config(proptest_config(256))]

        /// Values bit for bit A2.2, derivatives A2.3 to rounding, for degrees 0..=7 on knots
        /// with repeated interior knots.
        #[test]
        fn agrees_with_a2_2_and_a2_3(
            p in 0usize..=7,
            gaps in prop::collection::vec((0.05f64..1.0, 1usize..=7), 2..10),
            x in 0.0f64..=1.0,
        ) {
            // interior knots of multiplicity up to p (at least 1), clamped ends
            let mut knots = vec![0.0; p + 1];
            let mut t = 0.0;
            for (i, &(g, m)) in gaps.iter().enumerate() {
                t += g;
                let m = if i + 1 == gaps.len() { p + 1 } else { m.min(p.max(1)) };
                knots.extend(std::iter::repeat_n(t, m));
            }
            let kv = KnotVector::new(knots.clone()).unwrap();
            let n = knots.len() - p - 1;
            kv.validate_for(p, n).unwrap();
            let (a, b) = kv.domain(p);
            let tt = a + x * (b - a);
            let span = kv.find_span(p, tt).unwrap();
            let w = p + 1;
            let (mut left, mut right) = (vec![0.0; w], vec![0.0; w]);
            let (mut values, mut slopes) = (vec![0.0; w], vec![0.0; w]);
            basis_with_slopes(&knots, p, span, tt, &mut left, &mut right, &mut values, &mut slopes);
            let mut plain = vec![0.0; w];
            basis_funs_into(&knots, p, span, tt, &mut BasisScratch::new(p), &mut plain);
            prop_assert_eq!(&values, &plain);
            let mut ders = vec![0.0; 2 * w];
            basis_ders_into(&knots, p, span, tt, 1, &mut BasisScratch::new(p), &mut ders);
            let scale = ders[w..].iter().fold(1.0f64, |m, d| m.max(d.abs()));
            for (s, d) in slopes.iter().zip(&ders[w..]) {
                prop_assert!((s - d).abs() <= 1e-13 * scale, "{} against {}", s, d);
            }
        }
    }
}
