//! Unit tests of the fast kernels against the reference paths (and of their private parts:
//! the bucket table, the inner balls, the generic kernels).

use super::*;
use crate::{KnotVector, NurbsCurve, Points};

/// Deterministic, irregular values in [−1, 1].
fn wave(i: usize) -> f64 {
    (i as f64 * 0.731 + 0.3).sin() * (i as f64 * 0.117).cos()
}

fn curve(p: usize, n: usize, dim: usize) -> BSplineCurve {
    let ctrl = Points::from_flat(dim, (0..n * dim).map(wave).collect()).unwrap();
    BSplineCurve::from_knot_vector(p, KnotVector::clamped_uniform(p, n).unwrap(), ctrl).unwrap()
}

fn params(n: usize, shuffled: bool) -> Vec<f64> {
    (0..n)
        .map(|i| {
            let k = if shuffled { (i * 7919) % n } else { i };
            k as f64 / (n - 1) as f64
        })
        .collect()
}

fn max_diff(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

#[test]
fn locator_is_exact_for_uneven_and_extreme_breaks() {
    let cases: Vec<Vec<f64>> = vec![
        vec![0.0, 1.0],
        vec![0.0, 1e-9, 2e-9, 0.5, 0.5 + 1e-12, 1.0],
        (0..40).map(|i| 1.0 - 0.7f64.powi(i)).collect(),
        vec![-1e308, -1.0, 0.0, 1e-300, 1e308],
        vec![1e6, 1e6 + 1e-9, 1e6 + 1.0, 1e6 + 1000.0],
        vec![0.0, 5e-324, 1e-323],
    ];
    for breaks in cases {
        let loc = PieceLocator::new(&breaks);
        let m = breaks.len() - 1;
        let mut ts: Vec<f64> = breaks.clone();
        for w in breaks.windows(2) {
            ts.extend([w[0] + (w[1] - w[0]) * 0.25, w[0] + (w[1] - w[0]) * 0.75]);
            for x in [w[0], w[1]] {
                for k in 1..4 {
                    ts.push(f64::from_bits(x.to_bits().wrapping_sub(k)));
                    ts.push(f64::from_bits(x.to_bits().wrapping_add(k)));
                }
            }
        }
        ts.retain(|&t| t >= breaks[0] && t <= breaks[m]);
        for &t in &ts {
            let want = (breaks.partition_point(|&x| x <= t) - 1).min(m - 1);
            assert_eq!(loc.find(&breaks, t), want, "t = {t:e} in {breaks:?}");
        }
        // the inner balls never claim a parameter outside their open interval
        for w in breaks.windows(2) {
            let (mid, radius) = inner_ball(w[0], w[1]);
            for &t in &ts {
                if (t - mid).abs() < radius {
                    assert!(w[0] < t && t < w[1], "ball of {w:?} claims {t:e}");
                }
            }
        }
    }
}

/// The split form of the table finds the table's piece for every parameter of the domain,
/// the end pieces beyond it, and some piece at NaN and ±∞; it exists only when no bucket holds
/// more than two pieces.
#[test]
fn split_table_finds_the_pieces_of_the_table() {
    let cases: Vec<Vec<f64>> = vec![
        vec![0.0, 1.0],
        vec![0.0, 1.0, 2.0],
        (0..50)
            .map(|i| f64::from(i) + 0.3 * (f64::from(i) * 1.7).sin())
            .collect(),
        vec![1e6, 1e6 + 1.0, 1e6 + 1.5, 1e6 + 3.0],
    ];
    for breaks in cases {
        let loc = PieceLocator::new(&breaks);
        let split = loc
            .split_table(&breaks)
            .expect("spread-out breakpoints: a split table");
        let m = breaks.len() - 1;
        let (lo, hi) = (breaks[0], breaks[m]);
        let mut ts: Vec<f64> = breaks.clone();
        for i in 0..=997 {
            ts.push(lo + (hi - lo) * f64::from(i) / 997.0);
        }
        for &x in &breaks {
            for k in 1..4 {
                ts.push(f64::from_bits(x.to_bits().wrapping_sub(k)));
                ts.push(f64::from_bits(x.to_bits().wrapping_add(k)));
            }
        }
        for &t in &ts {
            let got = split.find(t);
            if t < lo {
                assert_eq!(got, 0, "below the domain, t = {t:e}");
            } else if t >= hi {
                assert_eq!(got, m - 1, "at or beyond the end, t = {t:e}");
            } else {
                assert_eq!(got, loc.find(&breaks, t), "t = {t:e} in {breaks:?}");
            }
        }
        for t in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY, -1e300, 1e300] {
            assert!(split.find(t) < m, "a piece at {t}");
        }
    }
    // buckets of more than two pieces (clustered breakpoints): no split table
    let clustered = [0.0, 1e-9, 2e-9, 3e-9, 1.0];
    assert!(
        PieceLocator::new(&clustered)
            .split_table(&clustered)
            .is_none(),
        "clustered"
    );
}

#[test]
fn find_span_matches_knot_vector() {
    let kv = KnotVector::new(vec![0.0, 0.0, 0.0, 0.1, 0.1, 0.4, 0.45, 0.9, 1.0, 1.0, 1.0]).unwrap();
    let ctrl = Points::from_flat(2, (0..16).map(wave).collect()).unwrap();
    let c = BSplineCurve::from_knot_vector(2, kv.clone(), ctrl).unwrap();
    let ev = c.evaluator();
    assert_eq!(ev.pieces(), 5);
    for t in params(1001, false)
        .into_iter()
        .chain(kv.as_slice().iter().copied())
    {
        assert_eq!(
            ev.find_span(t).unwrap(),
            kv.find_span(2, t).unwrap(),
            "t = {t}"
        );
    }
    assert!(matches!(
        ev.find_span(f64::NAN),
        Err(Error::ParameterOutOfDomain { .. })
    ));
}

#[test]
fn kernels_agree_with_reference_sorted_and_shuffled() {
    for (p, dim) in [
        (0, 2),
        (1, 3),
        (2, 2),
        (3, 1),
        (3, 3),
        (3, 4),
        (3, 5),
        (4, 3),
        (7, 2),
    ] {
        let c = curve(p, 40, dim);
        let scale = c.control_points().max_abs();
        for shuffled in [false, true] {
            let ts = params(997, shuffled);
            let mut want = vec![0.0; ts.len() * dim];
            c.eval_batch(&ts, &mut want).unwrap();
            for kernel in [EvalKernel::Auto, EvalKernel::PowerForm, EvalKernel::Basis] {
                if kernel == EvalKernel::PowerForm && p > POWER_FORM_MAX_DEGREE {
                    continue; // not promised to 1e-14 (see POWER_FORM_MAX_DEGREE)
                }
                let ev = CurveEvaluator::with_kernel(&c, kernel).unwrap();
                let mut got = vec![0.0; ts.len() * dim];
                ev.eval_batch(&ts, &mut got).unwrap();
                let err = max_diff(&got, &want);
                assert!(err <= 1e-14 * scale, "p {p} dim {dim} {kernel:?}: {err:e}");
            }
        }
    }
}

#[test]
fn fixed_kernels_match_generic_bit_for_bit() {
    for (p, dim) in [(3, 3), (5, 2), (7, 3), (2, 3), (3, 4), (3, 2), (2, 2)] {
        let c = curve(p, 30, dim);
        let ts = params(501, true);
        for kernel in [EvalKernel::PowerForm, EvalKernel::Basis] {
            let ev = CurveEvaluator::with_kernel(&c, kernel).unwrap();
            let mut fast = vec![0.0; ts.len() * dim];
            ev.eval_batch(&ts, &mut fast).unwrap();
            let mut generic = vec![0.0; ts.len() * dim];
            let mut n = vec![0.0; 3 * (p + 1)];
            ev.drive(&ts, &mut generic, dim, None, |j, t, o| match &ev.kernel {
                KernelData::Power { coef } => power_dyn(p, coef, j, t, o),
                KernelData::Basis {
                    knots,
                    control,
                    recip,
                } => ev.basis_point(knots, control, recip, j, t, &mut n, o),
            })
            .unwrap();
            assert!(
                fast.iter()
                    .zip(&generic)
                    .all(|(a, b)| a.to_bits() == b.to_bits()),
                "p {p} dim {dim} {kernel:?}"
            );
            // orders 1 and 2 take the kernels with the order fixed too (degree 2–3, 2-D/3-D),
            // order 3 the ones with a run-time order
            for order in 1..=3 {
                let KernelData::Power { coef } = &ev.kernel else {
                    break;
                };
                let row = (order + 1) * dim;
                let mut fast = vec![0.0; ts.len() * row];
                ev.eval_derivatives_batch(&ts, order, &mut fast).unwrap();
                let mut generic = vec![f64::NAN; ts.len() * row];
                let mut a = vec![0.0; p + 1];
                ev.drive(&ts, &mut generic, row, None, |j, t, o| {
                    power_ders(&mut a, dim, coef, j, t, order.min(p), o);
                })
                .unwrap();
                assert!(
                    fast.iter()
                        .zip(&generic)
                        .all(|(a, b)| a.to_bits() == b.to_bits()),
                    "derivatives p {p} dim {dim} order {order}"
                );
            }
        }
    }
}

#[test]
fn auto_kernel_choice() {
    assert_eq!(curve(3, 10, 3).evaluator().kernel(), EvalKernel::PowerForm);
    assert_eq!(
        curve(POWER_FORM_MAX_DEGREE + 1, 10, 3).evaluator().kernel(),
        EvalKernel::Basis
    );
}

#[test]
fn parallel_is_bit_identical() {
    let c = curve(3, 200, 3);
    let ev = c.evaluator();
    let eb = CurveEvaluator::with_kernel(&c, EvalKernel::Basis).unwrap();
    let n = 3 * PAR_CHUNK + 17;
    for shuffled in [false, true] {
        let ts = params(n, shuffled);
        for e in [&ev, &eb] {
            let (mut a, mut b) = (vec![0.0; n * 3], vec![1.0; n * 3]);
            e.eval_batch(&ts, &mut a).unwrap();
            e.par_eval_batch(&ts, &mut b).unwrap();
            assert!(
                a.iter().zip(&b).all(|(x, y)| x.to_bits() == y.to_bits()),
                "{:?}",
                e.kernel()
            );
        }
    }
    let mut bad = params(n, false);
    bad[2 * PAR_CHUNK + 5] = 2.0;
    bad[PAR_CHUNK + 1] = -1.0;
    let mut out = vec![0.0; n * 3];
    assert_eq!(
        ev.par_eval_batch(&bad, &mut out),
        Err(Error::ParameterOutOfDomain {
            t: -1.0,
            min: 0.0,
            max: 1.0
        })
    );
}

#[test]
fn derivatives_agree_with_reference() {
    for (p, dim) in [(1, 2), (2, 3), (3, 3), (5, 2)] {
        let c = curve(p, 30, dim);
        let ts = params(301, true);
        let order = p + 1;
        let row = (order + 1) * dim;
        for kernel in [EvalKernel::PowerForm, EvalKernel::Basis] {
            let ev = CurveEvaluator::with_kernel(&c, kernel).unwrap();
            let mut got = vec![0.0; ts.len() * row];
            ev.eval_derivatives_batch(&ts, order, &mut got).unwrap();
            // scale of the k-th derivative: control scale × (p / h_min)^k
            let pieces = ev.pieces() as f64;
            for (i, &t) in ts.iter().enumerate() {
                let want = c.eval_derivatives(t, order).unwrap();
                for k in 0..=order {
                    let scale = c.control_points().max_abs()
                        * (2.0 * p as f64 * pieces).powi(i32::try_from(k).unwrap());
                    let g = &got[i * row + k * dim..i * row + (k + 1) * dim];
                    let err = max_diff(g, want.point(k));
                    assert!(
                        err <= 1e-14 * scale,
                        "p {p} {kernel:?} k {k} t {t}: {err:e}"
                    );
                }
            }
        }
    }
}

#[test]
fn nurbs_agrees_with_reference() {
    for (p, dim) in [(2, 2), (2, 3), (3, 2), (3, 3), (3, 4), (5, 3)] {
        let b = curve(p, 25, dim);
        let weights: Vec<f64> = (0..25).map(|i| 1.5 + wave(i + 100)).collect();
        let n = NurbsCurve::new(
            p,
            b.knots().as_slice().to_vec(),
            b.control_points().clone(),
            weights,
        )
        .unwrap();
        let ts = params(401, true);
        let ev = n.evaluator();
        let mut got = vec![0.0; ts.len() * dim];
        ev.eval_batch(&ts, &mut got).unwrap();
        let mut par = vec![0.0; ts.len() * dim];
        ev.par_eval_batch(&ts, &mut par).unwrap();
        assert_eq!(got, par);
        let scale = b.control_points().max_abs();
        for (i, &t) in ts.iter().enumerate() {
            let want = n.eval(t).unwrap();
            let err = max_diff(&got[i * dim..(i + 1) * dim], &want);
            assert!(err <= 1e-14 * scale, "p {p} dim {dim} t {t}: {err:e}");
        }
    }
}

#[test]
fn errors() {
    let c = curve(3, 10, 3);
    let ev = c.evaluator();
    let mut out = vec![0.0; 5];
    assert!(matches!(
        ev.eval_batch(&[0.5, 0.6], &mut out),
        Err(Error::LengthMismatch {
            expected: 6,
            got: 5,
            ..
        })
    ));
    assert!(matches!(
        ev.eval_derivatives_batch(&[0.5], 1, &mut out),
        Err(Error::LengthMismatch {
            expected: 6,
            got: 5,
            ..
        })
    ));
    let mut out = vec![0.0; 6];
    for bad in [f64::NAN, -0.1, 1.5, f64::INFINITY] {
        assert!(
            matches!(
                ev.eval_batch(&[0.5, bad], &mut out),
                Err(Error::ParameterOutOfDomain { .. })
            ),
            "{bad}"
        );
        assert!(matches!(
            ev.eval_derivatives_batch(&[bad], 1, &mut out),
            Err(Error::ParameterOutOfDomain { .. })
        ));
    }
    // the right end is in the domain
    ev.eval_batch(&[1.0, 0.0], &mut out).unwrap();
    assert!(max_diff(&out[..3], c.control_points().point(9)) <= 1e-15);
    let huge = Points::from_flat(
        3,
        (0..12)
            .map(|i| if i % 2 == 0 { 1e308 } else { -1e308 })
            .collect(),
    )
    .unwrap();
    let h = BSplineCurve::from_knot_vector(3, KnotVector::clamped_uniform(3, 4).unwrap(), huge)
        .unwrap();
    assert!(matches!(
        CurveEvaluator::with_kernel(&h, EvalKernel::PowerForm),
        Err(Error::InvalidArgument { .. })
    ));
    assert_eq!(h.evaluator().kernel(), EvalKernel::Basis);
}

/// Beyond the domain: `Continue` is `eval_batch_extrapolated` (the end polynomials), `Nan`
/// gives NaN there; inside both are `eval_batch`; NaN and infinite parameters give NaN; the
/// parallel path gives the same bits.
#[test]
fn beyond_continues_or_gives_nan() {
    for (p, dim) in [(1, 1), (2, 1), (3, 1), (3, 2), (3, 3), (4, 1), (5, 2)] {
        let c = curve(p, 12, dim);
        let mut ts = params(301, true);
        ts.extend([
            -0.7,
            -1e-9,
            1.0 + 1e-9,
            1.4,
            3.0,
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
        ]);
        let outside = |t: f64| !(0.0..=1.0).contains(&t);
        for kernel in [EvalKernel::PowerForm, EvalKernel::Basis] {
            let ev = CurveEvaluator::with_kernel(&c, kernel).unwrap();
            let finite: Vec<f64> = ts.iter().copied().filter(|t| t.is_finite()).collect();
            let mut want = vec![0.0; finite.len() * dim];
            c.eval_batch_extrapolated(&finite, &mut want).unwrap();
            for beyond in [Beyond::Continue, Beyond::Nan] {
                let mut got = vec![0.0; ts.len() * dim];
                ev.eval_batch_beyond(&ts, beyond, &mut got).unwrap();
                let mut par = vec![0.0; ts.len() * dim];
                ev.par_eval_batch_beyond(&ts, beyond, &mut par).unwrap();
                assert!(got
                    .iter()
                    .zip(&par)
                    .all(|(a, b)| a.to_bits() == b.to_bits()));
                let mut w = want.chunks_exact(dim);
                for (&t, g) in ts.iter().zip(got.chunks_exact(dim)) {
                    if !t.is_finite() {
                        assert!(g.iter().all(|v| v.is_nan()), "t = {t}");
                        continue;
                    }
                    let r = w.next().unwrap();
                    if beyond == Beyond::Nan && outside(t) {
                        assert!(g.iter().all(|v| v.is_nan()), "t = {t}");
                    } else {
                        // rounding relative to the control net (1) inside, to the value
                        // beyond the ends, where the end polynomial grows like |u|^p in the
                        // piece's local parameter
                        let scale = r.iter().fold(1.0_f64, |m, v| m.max(v.abs()));
                        assert!(
                            max_diff(g, r) <= 1e-13 * scale,
                            "p {p} dim {dim} {kernel:?} t {t}: {g:?} {r:?}"
                        );
                    }
                }
            }
        }
    }
    let mut short = [0.0; 1];
    assert!(curve(3, 6, 1)
        .evaluator()
        .eval_batch_beyond(&[0.5, 0.6], Beyond::Continue, &mut short)
        .is_err());
}
