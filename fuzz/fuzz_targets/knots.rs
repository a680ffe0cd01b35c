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
    // at most 16 parameters: the kernels below are O(p²)..O(p³) per parameter
    let ts: Vec<f64> = common::floats(&input.ts).into_iter().take(16).collect();
    // a control point count is backed by data the caller holds: MAX_SCALARS (2^31 scalars) is the
    // library's limit, above the fuzzer's 2 GiB RSS limit, so counts in (2^20, MAX_SCALARS] are
    // not requested here (see docs/robustness.md)
    let n_ctrl = match input.n_ctrl.0 {
        n if n <= 1 << 20 || n > lekalo::MAX_SCALARS => n,
        n => n % (1 << 20),
    };
    let candidates = [
        KnotVector::new(v.clone()),
        KnotVector::clamped_uniform(p, n_ctrl),
        KnotVector::averaged(&v, p),
        KnotVector::averaged_with_end_derivatives(&v, p),
        KnotVector::from_parameters(&v, p),
        KnotVector::from_breakpoints(&v, &nu, p),
        KnotVector::from_breakpoints(&v, &vec![1; v.len().saturating_sub(2)], p),
    ];
    for kv in candidates.into_iter().flatten() {
        let _ = kv.validate_for(p, n_ctrl);
        common::exercise_knots(&kv, input.degree, &ts);
        // evaluation costs O(p²) per parameter (derivatives O(p³)) by design; degrees up to
        // MAX_DEGREE are accepted, but the fuzzer evaluates only moderate ones to keep its speed
        if p > 64 {
            continue;
        }
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
        if p <= 64 {
            let _ = bernstein(p, input.index.0, t);
            let mut out = vec![0.0; p + 1];
            let _ = bernstein_all(p, t, &mut out);
        }
    }
});
