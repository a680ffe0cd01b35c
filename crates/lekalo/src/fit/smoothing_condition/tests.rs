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
