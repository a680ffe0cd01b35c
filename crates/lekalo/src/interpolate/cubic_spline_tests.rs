//! Tests of `cubic_spline.rs`: the slopes are checked against the conditions that define the
//! spline (interpolation, `C²` at the interior breakpoints, the end conditions), which have one
//! solution, so a kernel that passes them computes the spline.

use proptest::prelude::*;

use super::*;

/// The power coefficients of the spline (SciPy's layout, 4 × pieces × dim).
fn spline(x: &[f64], y: &[f64], dim: usize, ends: [CubicSplineEnd<'_>; 2]) -> Vec<f64> {
    let mut c = vec![0.0; 4 * (x.len() - 1) * dim];
    cubic_spline_power_into(x, y, dim, ends[0], ends[1], &mut c).unwrap();
    c
}

/// The `r`-th derivative of piece `i`, column `j`, at `u = x − x_i`.
fn derivative(c: &[f64], pieces: usize, dim: usize, i: usize, j: usize, r: usize, u: f64) -> f64 {
    let k = |m: usize| c[(m * pieces + i) * dim + j];
    match r {
        0 => ((k(0) * u + k(1)) * u + k(2)) * u + k(3),
        1 => (3.0 * k(0) * u + 2.0 * k(1)) * u + k(2),
        2 => 6.0 * k(0) * u + 2.0 * k(1),
        _ => 6.0 * k(0),
    }
}

/// Checks the defining conditions at a tolerance relative to the data's scale.
fn check_conditions(x: &[f64], y: &[f64], dim: usize, ends: [CubicSplineEnd<'_>; 2], c: &[f64]) {
    let n = x.len();
    let p = n - 1;
    let scale = y.iter().fold(1.0_f64, |m, v| m.max(v.abs()));
    let hmin = x
        .windows(2)
        .map(|w| w[1] - w[0])
        .fold(f64::INFINITY, f64::min);
    let span = x[n - 1] - x[0];
    // rounding of the data's scale, amplified by the spread of the steps, in units of the
    // r-th derivative of a piece of the shortest step
    let tol = |r: usize| 1e-12 * scale * (span / hmin) / hmin.powi(i32::try_from(r).unwrap_or(3));
    for j in 0..dim {
        for i in 0..p {
            let h = x[i + 1] - x[i];
            let at = |r| derivative(c, p, dim, i, j, r, h);
            assert!(
                (derivative(c, p, dim, i, j, 0, 0.0) - y[i * dim + j]).abs() <= tol(0),
                "value"
            );
            assert!(
                (at(0) - y[(i + 1) * dim + j]).abs() <= tol(0),
                "value at the right end"
            );
            if i + 1 < p {
                for r in 1..=2 {
                    let next = derivative(c, p, dim, i + 1, j, r, 0.0);
                    assert!((at(r) - next).abs() <= tol(r), "C{r} at {}", i + 1);
                }
            }
        }
        let h_last = x[n - 1] - x[n - 2];
        for (e, (i, u, third_piece)) in ends
            .iter()
            .zip([(0, 0.0, 1), (p - 1, h_last, p.saturating_sub(2))])
        {
            match *e {
                CubicSplineEnd::FirstDerivative(v) => {
                    assert!(
                        (derivative(c, p, dim, i, j, 1, u) - v[j]).abs() <= tol(1),
                        "y'"
                    );
                }
                CubicSplineEnd::SecondDerivative(v) => {
                    assert!(
                        (derivative(c, p, dim, i, j, 2, u) - v[j]).abs() <= tol(2),
                        "y''"
                    );
                }
                CubicSplineEnd::NotAKnot if n > 3 => {
                    let (a, b) = (
                        derivative(c, p, dim, i, j, 3, 0.0),
                        derivative(c, p, dim, third_piece, j, 3, 0.0),
                    );
                    assert!((a - b).abs() <= tol(3), "not-a-knot: y''' {a} vs {b}");
                }
                CubicSplineEnd::Periodic => {
                    for r in 1..=2 {
                        let (a, b) = (
                            derivative(c, p, dim, 0, j, r, 0.0),
                            derivative(c, p, dim, p - 1, j, r, h_last),
                        );
                        assert!((a - b).abs() <= tol(r), "periodic y^({r})");
                    }
                }
                CubicSplineEnd::NotAKnot => {}
            }
        }
    }
}

#[test]
fn not_a_knot_reproduces_a_cubic() {
    let x = [0.0, 0.4, 1.0, 1.3, 2.5, 3.0];
    let y: Vec<f64> = x.iter().map(|t| 2.0 * t * t * t - t * t + 0.5).collect();
    let c = spline(&x, &y, 1, [CubicSplineEnd::NotAKnot; 2]);
    for i in 0..5 {
        assert!(
            (c[i] - 2.0).abs() < 1e-12,
            "cubic coefficient of piece {i}: {}",
            c[i]
        );
    }
}

#[test]
fn every_kind_of_end_meets_its_conditions() {
    let x = [0.0, 0.3, 1.0, 1.1, 2.0, 4.0, 4.5];
    let y: Vec<f64> = (0..14).map(|i| (f64::from(i) * 0.9).sin()).collect();
    let (a, b) = ([0.5, -1.0], [2.0, 0.25]);
    let kinds = [
        CubicSplineEnd::NotAKnot,
        CubicSplineEnd::FirstDerivative(&a),
        CubicSplineEnd::SecondDerivative(&b),
    ];
    for n in [2, 3, 4, 7] {
        for s in kinds {
            for e in kinds {
                let (xs, ys) = (&x[..n], &y[..2 * n]);
                let c = spline(xs, ys, 2, [s, e]);
                check_conditions(xs, ys, 2, [s, e], &c);
            }
        }
    }
}

#[test]
fn periodic_data_close_smoothly() {
    for n in [2, 3, 4, 5, 9] {
        let x: Vec<f64> = (0..n)
            .map(|i| f64::from(i) + 0.3 * f64::from(i * i % 3))
            .collect();
        let period = x[n as usize - 1] - x[0];
        let y: Vec<f64> = x
            .iter()
            .flat_map(|t| {
                let a = std::f64::consts::TAU * (t - x[0]) / period;
                [a.sin(), a.cos()]
            })
            .collect();
        let mut y = y;
        let last = y.len() - 2;
        y[last] = y[0];
        y[last + 1] = y[1];
        let c = spline(&x, &y, 2, [CubicSplineEnd::Periodic; 2]);
        check_conditions(&x, &y, 2, [CubicSplineEnd::Periodic; 2], &c);
    }
}

#[test]
fn hostile_arguments_are_refused_by_name() {
    let x = [0.0, 1.0, 2.0, 3.0];
    let y = [0.0, 1.0, 0.0, 1.0];
    let mut s = [0.0; 4];
    let one =
        |start, end, y: &[f64], s: &mut [f64]| cubic_spline_slopes_into(&x, y, 1, start, end, s);
    let e = one(
        CubicSplineEnd::Periodic,
        CubicSplineEnd::NotAKnot,
        &y,
        &mut s,
    )
    .unwrap_err();
    assert!(
        matches!(e, Error::InvalidArgument { .. }) && e.to_string().contains("both"),
        "{e}"
    );
    let e = one(
        CubicSplineEnd::Periodic,
        CubicSplineEnd::Periodic,
        &y,
        &mut s,
    )
    .unwrap_err();
    assert!(e.to_string().contains("repeats its first value"), "{e}");
    let e = one(
        CubicSplineEnd::FirstDerivative(&[1.0, 2.0]),
        CubicSplineEnd::NotAKnot,
        &y,
        &mut s,
    );
    assert!(
        matches!(
            e,
            Err(Error::LengthMismatch {
                expected: 1,
                got: 2,
                ..
            })
        ),
        "{e:?}"
    );
    let e = one(
        CubicSplineEnd::NotAKnot,
        CubicSplineEnd::NotAKnot,
        &[0.0, f64::NAN, 0.0, 1.0],
        &mut s,
    );
    assert!(matches!(e, Err(Error::NonFinite { index: 1, .. })), "{e:?}");
    let e = one(
        CubicSplineEnd::NotAKnot,
        CubicSplineEnd::NotAKnot,
        &y,
        &mut s[..3],
    );
    assert!(matches!(e, Err(Error::LengthMismatch { .. })), "{e:?}");
    let e = cubic_spline_slopes_into(
        &[0.0, 2.0, 1.0],
        &[0.0; 3],
        1,
        CubicSplineEnd::NotAKnot,
        CubicSplineEnd::NotAKnot,
        &mut s[..3],
    );
    assert!(matches!(e, Err(Error::InvalidArgument { .. })), "{e:?}");
    let e = cubic_spline_slopes_into(
        &[0.0],
        &[0.0],
        1,
        CubicSplineEnd::NotAKnot,
        CubicSplineEnd::NotAKnot,
        &mut s[..1],
    );
    assert!(matches!(e, Err(Error::TooFew { .. })), "{e:?}");
    let e = cubic_spline_slopes_into(
        &x,
        &[],
        0,
        CubicSplineEnd::NotAKnot,
        CubicSplineEnd::NotAKnot,
        &mut [],
    );
    assert!(matches!(e, Err(Error::InvalidArgument { .. })), "{e:?}");
    let mut c = [0.0; 11];
    let e = cubic_spline_power_into(
        &x,
        &y,
        1,
        CubicSplineEnd::NotAKnot,
        CubicSplineEnd::NotAKnot,
        &mut c,
    );
    assert!(
        matches!(e, Err(Error::LengthMismatch { expected: 12, .. })),
        "{e:?}"
    );
}

#[test]
fn non_finite_slopes_are_refused() {
    let x = [0.0, 1.0, 2.0, 3.0];
    let mut c = [0.0; 12];
    let nan = [f64::NAN];
    let e = CubicSplineEnd::FirstDerivative(&nan);
    let r = cubic_spline_power_into(
        &x,
        &[0.0, 1.0, 0.0, 1.0],
        1,
        e,
        CubicSplineEnd::NotAKnot,
        &mut c,
    );
    assert!(matches!(r, Err(Error::NonFinite { index: 0, .. })), "{r:?}");
}

proptest! {
    #[test]
    fn random_data_meet_the_conditions(
        steps in prop::collection::vec(0.05_f64..3.0, 1..40),
        values in prop::collection::vec(-5.0_f64..5.0, 41),
        kind in 0_usize..4,
    ) {
        let mut x = vec![0.0];
        for h in &steps {
            x.push(x[x.len() - 1] + h);
        }
        let n = x.len();
        let mut y = values[..n].to_vec();
        let (v1, v2) = ([values[40]], [values[39]]);
        let ends = match kind {
            0 => [CubicSplineEnd::NotAKnot; 2],
            1 => [CubicSplineEnd::FirstDerivative(&v1), CubicSplineEnd::SecondDerivative(&v2)],
            2 => [CubicSplineEnd::SecondDerivative(&v2), CubicSplineEnd::NotAKnot],
            _ => {
                y[n - 1] = y[0];
                [CubicSplineEnd::Periodic; 2]
            }
        };
        let c = spline(&x, &y, 1, ends);
        check_conditions(&x, &y, 1, ends, &c);
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    /// Data long enough for the partitioned elimination, on steps of any size up to 1e6
    /// apart: still the spline of the conditions (where the partitions do not meet, the
    /// elimination from both ends solves it).
    #[test]
    fn long_data_meet_the_conditions(
        steps in prop::collection::vec(1e-3_f64..3.0, PARTITIONED_ROWS..2 * PARTITIONED_ROWS),
        jumps in prop::collection::vec((0_usize..1 << 20, 1e-6_f64..1e3), 0..6),
        kind in 0_usize..3,
    ) {
        let mut steps = steps;
        for (at, h) in jumps {
            let i = at % steps.len();
            steps[i] = h;
        }
        let mut x = vec![0.0];
        for h in &steps {
            x.push(x[x.len() - 1] + h);
        }
        let y: Vec<f64> = x.iter().map(|v| (0.7 * v).sin() + 0.1 * v).collect();
        let (v1, v2) = ([0.25], [-1.5]);
        let ends = match kind {
            0 => [CubicSplineEnd::NotAKnot; 2],
            1 => [CubicSplineEnd::FirstDerivative(&v1), CubicSplineEnd::SecondDerivative(&v2)],
            _ => [CubicSplineEnd::SecondDerivative(&v2), CubicSplineEnd::NotAKnot],
        };
        let c = spline(&x, &y, 1, ends);
        check_conditions(&x, &y, 1, ends, &c);
    }
}

proptest! {
    /// The rows formed where the solver reads them are SciPy's stored bands, entry for entry:
    /// the slopes equal, bit for bit, those of the bands written out and solved by the same
    /// elimination (in partitions or from both ends for one column, with row swaps when a
    /// pivot is not positive), for one column and three, with the power form's scratch or
    /// without, on short data and on data long enough for the partitions.
    #[test]
    fn rows_read_in_place_are_the_stored_bands(
        steps in prop_oneof![
            prop::collection::vec(1e-6_f64..3.0, 2..60),
            prop::collection::vec(1e-6_f64..3.0, PARTITIONED_ROWS..PARTITIONED_ROWS + 200),
        ],
        values in prop::collection::vec(-5.0_f64..5.0, 3 * (PARTITIONED_ROWS + 201) + 2),
        kinds in (0_usize..3, 0_usize..3),
    ) {
        let last = values.len() - 2;
        let mut x = vec![-1.5];
        for h in &steps {
            x.push(x[x.len() - 1] + h);
        }
        let n = x.len();
        let (v1, v2) = (values[last], values[last + 1]);
        for dim in [1, 3] {
            let y = &values[..n * dim];
            let (d1, d2) = (vec![v1; dim], vec![v2; dim]);
            let (start, stop) = (end_of(kinds.0, &d1), end_of(kinds.1, &d2));
            if n == 3 && start == CubicSplineEnd::NotAKnot && stop == CubicSplineEnd::NotAKnot {
                continue;
            }
            let mut fused = vec![0.0; n * dim];
            cubic_spline_slopes_into(&x, y, dim, start, stop, &mut fused).unwrap();
            let rows = SplineRows::new(&x, start, stop);
            let mut stored = vec![0.0; n * dim];
            rows.right_hand_side(y, dim, [start, stop], &mut stored, None);
            let (mut dl, mut d, mut du) = rows.stored();
            // one column in partitions, else from both ends, else row swaps; several by `solve`
            let bands = StoredBands { dl: &dl, d: &d, du: &du };
            let partitioned = dim == 1
                && n >= PARTITIONED_ROWS
                && solve_partitioned(&bands, &mut stored, &mut vec![0.0; n]);
            if dim == 1 && !partitioned && n >= PARTITIONED_ROWS {
                rows.right_hand_side(y, dim, [start, stop], &mut stored, None);
            }
            let twisted = dim == 1
                && (partitioned || solve_twisted(&bands, &mut stored, &mut vec![0.0; n]));
            if dim == 1 && !twisted {
                rows.right_hand_side(y, dim, [start, stop], &mut stored, None);
                let m = Tridiagonal { dl: &mut dl, d: &mut d, du: &mut du };
                solve_tridiagonal(m, &mut stored, dim).unwrap();
            } else if dim > 1 {
                solve(Tridiagonal { dl: &mut dl, d: &mut d, du: &mut du }, &mut stored, dim).unwrap();
            }
            for (a, b) in fused.iter().zip(&stored) {
                prop_assert_eq!(a.to_bits(), b.to_bits());
            }
            // through the power form, the pivots in `c`: the same slopes (row 2 of `c`)
            let mut c = vec![0.0; 4 * (n - 1) * dim];
            cubic_spline_power_into(&x, y, dim, start, stop, &mut c).unwrap();
            let m = (n - 1) * dim;
            for (a, b) in c[2 * m..3 * m].iter().zip(&fused) {
                prop_assert_eq!(a.to_bits(), b.to_bits());
            }
        }
    }
}

/// A non-periodic end condition by number: not-a-knot, a first or a second derivative `v`.
fn end_of(kind: usize, v: &[f64]) -> CubicSplineEnd<'_> {
    match kind {
        0 => CubicSplineEnd::NotAKnot,
        1 => CubicSplineEnd::FirstDerivative(v),
        _ => CubicSplineEnd::SecondDerivative(v),
    }
}

proptest! {
    /// One column's pieces, from the secants kept by the solve and the reciprocal of each step,
    /// are SciPy's Hermite pass on the same slopes to a few units in the last place of each
    /// coefficient's terms, on steps a million times apart, for every non-periodic end.
    #[test]
    fn one_column_pieces_are_the_hermite_pass_to_rounding(
        steps in prop::collection::vec(1e-6_f64..3.0, 3..80),
        values in prop::collection::vec(-5.0_f64..5.0, 83),
        kinds in (0_usize..3, 0_usize..3),
    ) {
        let mut x = vec![0.25];
        for h in &steps {
            x.push(x[x.len() - 1] + h);
        }
        let n = x.len();
        let y = &values[..n];
        let (d1, d2) = ([values[81]], [values[82]]);
        let (start, stop) = (end_of(kinds.0, &d1), end_of(kinds.1, &d2));
        let mut c = vec![0.0; 4 * (n - 1)];
        cubic_spline_power_into(&x, y, 1, start, stop, &mut c).unwrap();
        let mut s = vec![0.0; n];
        cubic_spline_slopes_into(&x, y, 1, start, stop, &mut s).unwrap();
        let mut want = vec![0.0; 4 * (n - 1)];
        crate::pp::cubic_hermite_power_into(&x, y, &s, 1, &mut want).unwrap();
        let p = n - 1;
        for i in 0..p {
            let h = x[i + 1] - x[i];
            let secant = (y[i + 1] - y[i]) / h;
            // the size of the terms of t = (s_i + s_{i+1} − 2δ)/h, of c_0 = t/h and c_1
            let t_terms = (s[i].abs() + s[i + 1].abs() + 2.0 * secant.abs()) / h;
            let scale = [t_terms / h, t_terms + (secant.abs() + s[i].abs()) / h, 0.0, 0.0];
            for (m, size) in scale.iter().enumerate() {
                let (a, b) = (c[m * p + i], want[m * p + i]);
                prop_assert!((a - b).abs() <= 8.0 * f64::EPSILON * size, "c{m}[{i}]: {a} vs {b}");
            }
        }
    }
}
