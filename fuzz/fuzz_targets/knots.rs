//! Every knot-vector constructor and the basis kernels with hostile numbers and sizes.
#![no_main]

#[path = "common.rs"]
mod common;

use arbitrary::Arbitrary;
use common::{Num, Size};
use lekalo::basis::{
    basis_derivatives, basis_function_recursive, basis_functions, bernstein, bernstein_all,
};
use lekalo::{check_parameters, KnotVector};
use libfuzzer_sys::fuzz_target;

#[derive(Debug, Arbitrary)]
struct Input {
    values: Vec<Num>,
    sort: bool,
    degree: Size,
    n_ctrl: Size,
    continuity: Vec<Size>,
    ts: Vec<Num>,
    n_ders: Size,
    index: Size,
}

fuzz_target!(|input: Input| {
    let v = common::maybe_sorted(&input.values, input.sort);
    let p = input.degree.0;
    let _ = check_parameters(&v);
    let nu: Vec<usize> = input.continuity.iter().map(|s| s.0).collect();
    let ts = common::floats(&input.ts);
    let candidates = [
        KnotVector::new(v.clone()),
        KnotVector::clamped_uniform(p, input.n_ctrl.0),
        KnotVector::averaged(&v, p),
        KnotVector::averaged_with_end_derivatives(&v, p),
        KnotVector::from_parameters(&v, p),
        KnotVector::from_breakpoints(&v, &nu, p),
        KnotVector::from_breakpoints(&v, &vec![1; v.len().saturating_sub(2)], p),
    ];
    for kv in candidates.into_iter().flatten() {
        let _ = kv.validate_for(p, input.n_ctrl.0);
        common::exercise_knots(&kv, input.degree, &ts);
        for &t in &ts {
            if let Ok((_, n)) = basis_functions(&kv, p, t) {
                common::assert_no_nan("basis_functions", &n);
            }
            let _ = basis_derivatives(&kv, p, t, input.n_ders.0);
            // the recursive oracle is exponential in the degree by design: keep it small
            if p <= 10 {
                let _ = basis_function_recursive(&kv, input.index.0, p, t);
            }
            let _ = lekalo::bspline_divided_difference(&kv, input.index.0, p, t);
        }
    }
    for &t in &ts {
        // Bernstein kernels are O(n²) in the degree: keep it moderate
        if p <= 300 {
            let _ = bernstein(p, input.index.0, t);
            let mut out = vec![0.0; p + 1];
            let _ = bernstein_all(p, t, &mut out);
        }
    }
});
