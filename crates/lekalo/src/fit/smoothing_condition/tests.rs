//! Tests of the smoothing condition's pieces.

use super::lsq_pass::reachable_floor;
use super::weight::rational_root;
use super::*;
use crate::basis::basis_ders_into;
use crate::basis::BasisScratch;
use crate::Arg;

#[test]
fn jump_rows_are_the_scaled_jumps_of_the_top_derivative() {
    let k = 3;
    let t = [0.0, 0.0, 0.0, 0.0, 0.3, 0.45, 1.1, 2.0, 2.0, 2.0, 2.0];
    let rows = jump_rows(&t, k);
    let mut scratch = BasisScratch::new(k);
    let mut ders = vec![0.0; (k + 1) * (k + 1)];
    let mut top = |span: usize| {
        let mid = 0.5 * (t[span] + t[span + 1]);
        basis_ders_into(&t, k, span, mid, k, &mut scratch, &mut ders);
        ders[k * (k + 1)..].to_vec()
    };
    for (r, row) in rows.rows.chunks_exact(k + 2).enumerate() {
        let l = r + k + 1;
        let (left, right) = (top(l - 1), top(l));
        // one sign for the whole row
        let sign = (row[0] * (-left[0])).signum();
        for j in 0..k + 2 {
            let jl = if j <= k { left[j] } else { 0.0 };
            let jr = if j >= 1 { right[j - 1] } else { 0.0 };
            let jump = jr - jl;
            let got = sign * row[j] * rows.scale;
            assert!(
                (got - jump).abs() <= 1e-9 * jump.abs().max(1.0),
                "knot {l}, B-spline {j}: {got} vs jump {jump}"
            );
        }
    }
}

/// The data of a SciPy `make_splrep` test with a repeated x: the two points at x = 310.1
/// with values 7.2 and 3.6 leave every function `2·w·1.8² = 12.47…`, so `s = 12` is refused
/// (as SciPy's `make_splrep` refuses it) and `s = 13` is met.
#[test]
fn s_below_the_spread_of_repeated_parameters_is_refused() {
    let x = [
        20.00, 153.81, 175.57, 202.47, 237.11, 253.61, 258.56, 273.40, 284.54, 293.61, 298.56,
        301.86, 305.57, 307.22, 308.45, 310.10, 310.10, 310.50,
    ];
    let y = [
        53.00, 49.50, 48.60, 46.80, 43.20, 40.32, 39.60, 36.00, 32.40, 28.80, 25.20, 21.60, 18.00,
        14.40, 10.80, 7.20, 3.60, 0.0,
    ];
    let w = [1.38723f64 * 1.38723; 18];
    let data = FitData::new(crate::PointsRef::from_flat(1, &y).unwrap(), &x)
        .unwrap()
        .with_weights(&w)
        .unwrap();
    let floor = 2.0 * w[0] * 1.8 * 1.8;
    let obs = Observations::new(&data);
    assert!(
        (reachable_floor(&obs) - floor).abs() <= 1e-12 * floor,
        "floor {} vs {floor}",
        reachable_floor(&obs)
    );
    let e = smoothing_condition(&data, 2, 12.0).unwrap_err();
    assert!(
        matches!(&e, Error::InvalidArgument { what, reason } if reason.contains("12.47") && what.arg() == Some(Arg::S)),
        "{e}"
    );
    for s in [13.0, 20.0] {
        let fit = smoothing_condition(&data, 2, s).unwrap();
        assert!(
            fit.report.weighted_rss <= s,
            "s = {s}: residual {}",
            fit.report.weighted_rss
        );
    }
    // distinct parameters: nothing is out of reach
    let data = FitData::new(crate::PointsRef::from_flat(1, &y).unwrap(), &y).unwrap();
    assert_eq!(reachable_floor(&Observations::new(&data)), 0.0);
}

#[test]
fn rational_root_of_a_rational_function_is_exact() {
    // r(p) = (2p − 3)/(p + 1): zero at 1.5
    let r = |p: f64| (2.0 * p - 3.0) / (p + 1.0);
    let got = rational_root(0.5, r(0.5), 1.0, r(1.0), 4.0, r(4.0));
    assert!((got - 1.5).abs() < 1e-12, "root {got}");
}

/// Noisy samples of a sine on `[0, 10]`: the noise a fixed pseudo-random sequence in
/// `[−0.1, 0.1]`.
fn noisy_sine(m: usize) -> (Vec<f64>, Vec<f64>) {
    let x: Vec<f64> = (0..m).map(|i| 10.0 * i as f64 / (m - 1) as f64).collect();
    let y = x
        .iter()
        .enumerate()
        .map(|(i, t)| t.sin() + 0.1 * (((i * 7919 + 3) % 17) as f64 / 8.0 - 1.0))
        .collect();
    (x, y)
}

/// The least-squares spline of the round that reaches `n` knots: the rounds stopped there.
fn round_fit(data: &FitData<'_>, k: usize, s: f64, n: usize) -> CurveFit {
    let quiet = Progress::new();
    smoothing_condition_with_limit(
        data,
        k,
        s,
        None,
        KnotRounds::Shared,
        KnotLimit::Stop(n),
        &quiet,
    )
    .unwrap()
}

/// FITPACK's `fpcurf` accepts a round's least-squares spline whose residual is within
/// `SMOOTHING_RTOL·s` of `s` on either side, also above `s`, instead of adding knots: with `s`
/// just below the residual of a round (the polynomial's, and a later one's), that round is the
/// answer, unsmoothed, in both ways of placing knots.
#[test]
fn a_round_within_the_tolerance_above_s_is_the_answer() {
    let (x, y) = noisy_sine(50);
    let data = FitData::new(crate::PointsRef::from_flat(1, &y).unwrap(), &x).unwrap();
    let k = 3;
    let seq = smoothing_knot_sequence(&data, k, 0.01, None, KnotRounds::Shared).unwrap();
    assert!(seq.len() >= 4, "{} rounds", seq.len());
    for round in [0, 3] {
        let n = seq[round].len();
        let fp = round_fit(&data, k, 0.01, n).report.weighted_rss;
        let s = fp / (1.0 + 0.5 * SMOOTHING_RTOL);
        for rounds in [KnotRounds::Shared, KnotRounds::Refit] {
            let quiet = Progress::new();
            let fit = smoothing_condition_with_rounds(&data, k, s, None, rounds, &quiet).unwrap();
            let want = smoothing_knot_sequence(&data, k, s, None, rounds).unwrap();
            let want = want.last().unwrap();
            assert_eq!(
                fit.curve.knots().as_slice(),
                &want[..],
                "{rounds:?}, round {round}"
            );
            if rounds == KnotRounds::Shared {
                assert_eq!(
                    fit.curve.knots().as_slice(),
                    &seq[round][..],
                    "round {round}"
                );
            }
            assert_eq!(
                fit.report.lambda, None,
                "{rounds:?}, round {round}: smoothed"
            );
            let rss = fit.report.weighted_rss;
            assert!(
                rss > s && rss < s * (1.0 + SMOOTHING_RTOL),
                "{rounds:?}: {rss} for s = {s}"
            );
        }
        // just beyond the tolerance the rounds go on
        let s = fp / (1.0 + 2.0 * SMOOTHING_RTOL);
        let fit = smoothing_condition(&data, k, s).unwrap();
        assert!(
            fit.curve.knots().len() > n,
            "round {round}: {} knots",
            fit.curve.knots().len()
        );
    }
}

/// SciPy's `UnivariateSpline` stops the rounds at `nest = max(m/2, 2k + 2)` knots and goes on
/// from the knots reached ([`KnotLimit::Resume`]), one knot in the next round: the knots of the
/// stopped rounds are kept, the knots are SciPy's, the rounds end within the tolerance of `s`,
/// with other knots than unlimited rounds (SciPy's `splrep`: 20 breakpoints against 16).
#[test]
fn resumed_rounds_go_on_from_the_knots_of_the_limit() {
    let (x, y) = noisy_sine(40);
    let data = FitData::new(crate::PointsRef::from_flat(1, &y).unwrap(), &x).unwrap();
    let (k, s) = (3, 0.05);
    let quiet = Progress::new();
    let fit = |limit| {
        smoothing_condition_with_limit(&data, k, s, None, KnotRounds::Shared, limit, &quiet)
            .unwrap()
    };
    let stopped = fit(KnotLimit::Stop(20));
    assert_eq!(stopped.curve.knots().len(), 20);
    assert!(stopped.report.weighted_rss > s);
    let resumed = fit(KnotLimit::Resume(20));
    let t = resumed.curve.knots().as_slice();
    assert!(t.len() > 20, "{} knots", t.len());
    assert!(resumed.report.weighted_rss < s * (1.0 + SMOOTHING_RTOL));
    for u in &stopped.curve.knots().as_slice()[k + 1..16] {
        assert!(t.contains(u), "knot {u} of the stopped rounds lost");
    }
    // SciPy 1.17's `UnivariateSpline(x, y, s=0.05).get_knots()`: the data at these indices
    let scipy = [0, 3, 5, 8, 10, 13, 15, 18, 20, 23, 25, 28, 30, 35, 37, 39];
    let breaks: Vec<f64> = scipy.iter().map(|&i| x[i]).collect();
    assert_eq!(&t[k..t.len() - k], &breaks[..], "SciPy's knots");
    let unlimited = fit(KnotLimit::Unlimited);
    assert_ne!(unlimited.curve.knots().as_slice(), t);
    // a limit no round reaches changes nothing
    assert_eq!(
        fit(KnotLimit::Resume(x.len() + k + 1))
            .curve
            .knots()
            .as_slice(),
        unlimited.curve.knots().as_slice()
    );
    // a limit below the polynomial's knots is refused
    assert!(matches!(
        smoothing_condition_with_limit(
            &data,
            k,
            s,
            None,
            KnotRounds::Shared,
            KnotLimit::Resume(7),
            &quiet
        ),
        Err(Error::TooFew { .. })
    ));
}

/// The data of the continuation tests: 200 points `x_i = i/20` of a chirp with a deterministic
/// ripple, as the SciPy script that produced the stored knots builds them.
fn chirp() -> (Vec<f64>, Vec<f64>) {
    let x: Vec<f64> = (0..200).map(|i| f64::from(i) / 20.0).collect();
    let y = (0..200u32)
        .zip(&x)
        .map(|(i, &t)| {
            let ripple = f64::from(i * 7919 % 13) - 6.0;
            t.sin() * (0.3 * t * t).cos() + 0.05 * ripple / 6.0
        })
        .collect();
    (x, y)
}

/// The rounds of `s_first` with SciPy's `UnivariateSpline` limit (`Resume(m/2)`), then
/// continued with `s`: the fit and the two states.
fn continued(
    data: &FitData<'_>,
    s_first: f64,
    s: f64,
) -> (CurveFit, CurveFit, RoundsState, RoundsState) {
    let quiet = Progress::new();
    let fit = |s, start| {
        smoothing_condition_from(data, 3, s, None, KnotRounds::Shared, start, &quiet).unwrap()
    };
    let (first, state) = fit(s_first, RoundsStart::Fresh(KnotLimit::Resume(100)));
    let (then, state2) = fit(s, RoundsStart::Continue(&state));
    (first, then, state, state2)
}

/// SciPy 1.17's `UnivariateSpline(x, y, s=s_first)` followed by `set_smoothing_factor(s)`
/// (FITPACK `curfit` with `iopt = 1`): the knots, as indices of the data, differ from a fresh
/// fit with `s`, because the first rounds added other counts of knots on the way.
#[test]
fn continued_rounds_give_fitpacks_knots_for_the_new_s() {
    let (x, y) = chirp();
    let data = FitData::new(crate::PointsRef::from_flat(1, &y).unwrap(), &x).unwrap();
    let cases: [(f64, f64, &[usize], &[usize]); 2] = [
        (
            20.0,
            1.0,
            &[
                13, 25, 50, 63, 75, 88, 100, 113, 125, 132, 138, 144, 150, 157, 163, 169, 175, 187,
            ],
            &[
                25, 50, 63, 75, 88, 100, 107, 113, 119, 125, 138, 150, 157, 163, 169, 175, 187,
            ],
        ),
        (
            5.0,
            0.5,
            &[
                25, 50, 63, 75, 88, 100, 107, 113, 125, 132, 138, 150, 157, 163, 169, 175, 181, 187,
            ],
            &[
                25, 50, 63, 75, 88, 100, 107, 113, 119, 125, 138, 144, 150, 157, 163, 169, 175,
                181, 187,
            ],
        ),
    ];
    let quiet = Progress::new();
    for (s_first, s, scipy, fresh) in cases {
        let (first, then, state, _) = continued(&data, s_first, s);
        let interior = |f: &CurveFit| {
            let t = f.curve.knots().as_slice();
            t[4..t.len() - 4].to_vec()
        };
        let at: Vec<f64> = scipy.iter().map(|&i| x[i]).collect();
        assert_eq!(interior(&then), at, "s = {s_first} then {s}: SciPy's knots");
        assert_eq!(state.interior, interior(&first), "the state's knots");
        // knots are only added
        assert!(state.interior.iter().all(|u| at.contains(u)), "knots lost");
        assert!(then.report.weighted_rss < s * (1.0 + SMOOTHING_RTOL));
        // a fresh fit with s takes other knots (SciPy's too)
        let limit = KnotLimit::Resume(100);
        let fresh_fit =
            smoothing_condition_with_limit(&data, 3, s, None, KnotRounds::Shared, limit, &quiet)
                .unwrap();
        let at: Vec<f64> = fresh.iter().map(|&i| x[i]).collect();
        assert_eq!(interior(&fresh_fit), at, "s = {s}: SciPy's fresh knots");
    }
}

/// A continuation with the `s` of the earlier fit repeats its last pass: the same fit; with a
/// larger `s` below `fp0` it keeps the knots and smooths more; with `s ≥ fp0` it starts over
/// (the polynomial, as a fresh fit).
#[test]
fn continued_rounds_keep_or_smooth_on_the_knots_reached() {
    let (x, y) = chirp();
    let data = FitData::new(crate::PointsRef::from_flat(1, &y).unwrap(), &x).unwrap();
    let (first, same, state, state2) = continued(&data, 1.0, 1.0);
    assert_eq!(same.curve.knots(), first.curve.knots(), "knots");
    assert_eq!(same.curve, first.curve, "the same fit");
    assert_eq!(state2, state, "the same state");
    let (first, looser, state, _) = continued(&data, 1.0, 3.0);
    assert_eq!(looser.curve.knots(), first.curve.knots(), "knots kept");
    let rss = looser.report.weighted_rss;
    assert!(rss > 1.5 && rss <= 3.0, "smoothed to {rss}");
    assert!(state.fp0 > 3.0, "fp0 = {}", state.fp0);
    let (_, poly, _, state2) = continued(&data, 1.0, state.fp0 * 1.5);
    assert_eq!(poly.curve.knots().len(), 8, "the polynomial");
    assert!(state2.interior.is_empty() && state2.restart, "{state2:?}");
}

/// A [`KnotLimit::Stop`] reached leaves a state that restarts (FITPACK's `ier = 1`) under the
/// same limit, so that a continuation stops there again; a [`KnotLimit::Resume`] passed leaves
/// no limit.
#[test]
fn the_state_carries_the_limit_left() {
    let (x, y) = chirp();
    let data = FitData::new(crate::PointsRef::from_flat(1, &y).unwrap(), &x).unwrap();
    let quiet = Progress::new();
    let fit = |s, start| {
        smoothing_condition_from(&data, 3, s, None, KnotRounds::Shared, start, &quiet).unwrap()
    };
    let (stopped, state) = fit(0.1, RoundsStart::Fresh(KnotLimit::Stop(20)));
    assert_eq!(stopped.curve.knots().len(), 20);
    assert!(
        state.restart && state.limit == KnotLimit::Stop(20),
        "{state:?}"
    );
    let (again, _) = fit(0.1, RoundsStart::Continue(&state));
    assert_eq!(again.curve.knots(), stopped.curve.knots());
    let (resumed, state) = fit(0.1, RoundsStart::Fresh(KnotLimit::Resume(20)));
    assert!(resumed.curve.knots().len() > 20);
    assert_eq!(state.limit, KnotLimit::Unlimited);
    let (_, state) = fit(5.0, RoundsStart::Fresh(KnotLimit::Resume(100)));
    assert_eq!(state.limit, KnotLimit::Resume(100), "limit not reached");
}

#[test]
fn a_state_that_does_not_fit_the_data_is_refused() {
    let (x, y) = chirp();
    let data = FitData::new(crate::PointsRef::from_flat(1, &y).unwrap(), &x).unwrap();
    let quiet = Progress::new();
    let (_, state) = smoothing_condition_from(
        &data,
        3,
        1.0,
        None,
        KnotRounds::Shared,
        RoundsStart::Fresh(KnotLimit::Unlimited),
        &quiet,
    )
    .unwrap();
    let from = |st: &RoundsState| {
        let start = RoundsStart::Continue(st);
        smoothing_condition_from(&data, 3, 0.5, None, KnotRounds::Shared, start, &quiet)
    };
    assert!(from(&state).is_ok());
    let mut off = state.clone();
    off.interior[0] += 0.01;
    assert!(
        matches!(from(&off), Err(Error::InvalidArgument { ref reason, .. }) if reason.contains("not a data parameter")),
        "{:?}",
        from(&off)
    );
    let mut unsorted = state.clone();
    unsorted.interior.swap(0, 1);
    assert!(matches!(
        from(&unsorted),
        Err(Error::InvalidArgument { .. })
    ));
    let mut outside = state.clone();
    outside.interior.push(x[199]);
    assert!(matches!(from(&outside), Err(Error::InvalidArgument { .. })));
    let mut nan = state;
    nan.fp0 = f64::NAN;
    assert!(matches!(from(&nan), Err(Error::NonFinite { .. })));
}
