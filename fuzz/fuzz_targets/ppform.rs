//! Divided differences, piecewise polynomials, P_{k,ξ,ν} spaces and quasi-interpolation with
//! hostile numbers and sizes.
#![no_main]

#[path = "common.rs"]
mod common;

use arbitrary::Arbitrary;
use common::{Num, Size};
use lekalo::{
    divided_difference, divided_difference_explicit, truncated_power, NewtonForm,
    PiecewisePolynomial, PpSpace,
};
use libfuzzer_sys::fuzz_target;

#[derive(Debug, Arbitrary)]
struct Input {
    points: Vec<Num>,
    values: Vec<Num>,
    breakpoints: Vec<Num>,
    sort: bool,
    order: Size,
    dim: Size,
    continuity: Vec<Size>,
    coefficients: Vec<Num>,
    xs: Vec<Num>,
    deriv: Size,
}

fuzz_target!(|input: Input| {
    let x = common::floats(&input.points);
    let y = common::floats(&input.values);
    let _ = divided_difference_explicit(&x, &y);
    // confluent points ask for derivatives f^{(r)}: exp has all of them
    let _ = divided_difference(&x, |t, _r| t.exp());
    if let Ok(nf) = NewtonForm::new(&x, |t, r| if r == 0 { t.sin() } else { 0.0 }) {
        for &z in &common::floats(&input.xs) {
            let _ = nf.eval(z);
        }
        let _ = nf.nodes();
        let _ = nf.coefficients();
    }
    for &z in &common::floats(&input.xs) {
        let _ = truncated_power(x.first().copied().unwrap_or(0.0), z, input.order.0);
    }
    let bp = common::maybe_sorted(&input.breakpoints, input.sort);
    let mut bp_strict = bp.clone();
    bp_strict.dedup();
    let k = input.order.0;
    let nu: Vec<usize> = input.continuity.iter().map(|s| s.0).collect();
    let coeffs = common::floats(&input.coefficients);
    let f = PiecewisePolynomial::new(bp_strict.clone(), k, input.dim.0, coeffs.clone()).ok();
    if let Some(f) = &f {
        common::exercise_pp(f, &input.xs, input.deriv);
    }
    // a coefficient vector of the right length, cycled from the fuzzed one
    let dim = input.dim.0 % 4 + 1;
    let kk = k % 12 + 1;
    let need = bp_strict.len().saturating_sub(1) * kk * dim;
    let g = if need > 0 && need <= 4096 && !coeffs.is_empty() {
        let c: Vec<f64> = coeffs.iter().copied().cycle().take(need).collect();
        PiecewisePolynomial::new(bp_strict.clone(), kk, dim, c).ok()
    } else {
        None
    };
    if let Some(g) = &g {
        common::exercise_pp(g, &input.xs, input.deriv);
    }
    for space in [
        PpSpace::new(&bp, &nu, k),
        PpSpace::new(&bp_strict, &nu, k),
        PpSpace::unconstrained(&bp_strict, k),
        PpSpace::unconstrained(&bp_strict, kk),
        PpSpace::new(
            &bp_strict,
            &vec![kk - 1; bp_strict.len().saturating_sub(2)],
            kk,
        ),
    ]
    .into_iter()
    .flatten()
    {
        common::exercise_space(&space, g.as_ref().or(f.as_ref()));
    }
});
