//! The rows of the observation matrix: at each data parameter, the `p + 1` non-zero B-splines
//! (crate-private kernel of the least-squares passes and the fit reports;
//! `docs/theory/fitting.md#banded-qr`).

use crate::basis::{basis_funs_into, BasisScratch, SpanBasis};
use crate::knots::KnotVector;

/// Calls `f(k, span, row)` for every index `k` of `indices`, in that order, with
/// `row = scale(k)·N_{span−p..=span, p}(params[k])` (P&T A2.2). The spans are found from the
/// previous one ([`KnotVector::span_cursor`]), and the basis functions of a span share the
/// reciprocals of its knot differences ([`SpanBasis`], unrolled for degrees up to 5), so sorted
/// parameters cost no search and no division. Every parameter must lie in the knots' domain.
pub(crate) fn for_each_row(
    knots: &KnotVector,
    degree: usize,
    params: &[f64],
    indices: impl IntoIterator<Item = usize>,
    scale: impl Fn(usize) -> f64,
    f: impl FnMut(usize, usize, &[f64]),
) {
    match degree + 1 {
        2 => rows_of_order::<2>(knots, degree, params, indices, scale, f),
        3 => rows_of_order::<3>(knots, degree, params, indices, scale, f),
        4 => rows_of_order::<4>(knots, degree, params, indices, scale, f),
        5 => rows_of_order::<5>(knots, degree, params, indices, scale, f),
        6 => rows_of_order::<6>(knots, degree, params, indices, scale, f),
        _ => rows_of_order::<0>(knots, degree, params, indices, scale, f),
    }
}

/// [`for_each_row`] with the order `W = p + 1` known at compile time, or `W = 0` for any degree
/// (then by [`basis_funs_into`]).
fn rows_of_order<const W: usize>(
    knots: &KnotVector,
    degree: usize,
    params: &[f64],
    indices: impl IntoIterator<Item = usize>,
    scale: impl Fn(usize) -> f64,
    mut f: impl FnMut(usize, usize, &[f64]),
) {
    let t = knots.as_slice();
    let mut cursor = knots.span_cursor(degree);
    let mut basis = SpanBasis::<W>::new();
    let mut scratch = BasisScratch::new(if W == 0 { degree } else { 0 });
    let mut row = vec![0.0; degree + 1];
    for k in indices {
        let u = params[k];
        let span = cursor.find_unchecked(u);
        let s = scale(k);
        if W == 0 {
            basis_funs_into(t, degree, span, u, &mut scratch, &mut row);
            row.iter_mut().for_each(|v| *v *= s);
        } else {
            basis.set_span(t, span);
            basis.eval(u, s, &mut row);
        }
        f(k, span, &row);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rows_are_the_scaled_basis_functions_in_any_order() {
        for degree in [1, 3, 6] {
            let kv = KnotVector::new(
                [
                    vec![0.0; degree + 1],
                    vec![0.2, 0.2, 0.5, 0.9],
                    vec![1.0; degree + 1],
                ]
                .concat(),
            )
            .unwrap();
            let params = [0.0, 0.1, 0.2, 0.35, 0.5, 0.95, 1.0, 0.3];
            // sorted, then reversed (every span change searched)
            for indices in [(0..8).collect::<Vec<_>>(), (0..8).rev().collect()] {
                let mut seen = Vec::new();
                for_each_row(
                    &kv,
                    degree,
                    &params,
                    indices.clone(),
                    |k| k as f64 + 1.0,
                    |k, span, row| {
                        let (want_span, want) =
                            crate::basis::basis_functions(&kv, degree, params[k]).unwrap();
                        assert_eq!(span, want_span, "span of parameter {k}");
                        for (j, (a, b)) in row.iter().zip(&want).enumerate() {
                            let b = b * (k as f64 + 1.0);
                            assert!(
                                (a - b).abs() <= 1e-14 * b.abs().max(1.0),
                                "degree {degree}, parameter {k}, function {j}: {a} vs {b}"
                            );
                        }
                        seen.push(k);
                    },
                );
                assert_eq!(seen, indices, "rows in the order of the indices");
            }
        }
    }
}
