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
