//! Interpolation: golden numbers of P&T Example 9.1 (docs/theory/interpolation.md#test-vectors;
//! document 000 has no numeric example, so these were computed independently and cross-checked with
//! SciPy), residuals at the data, prescribed derivatives, offset/scale invariance, closed curves,
//! surfaces, Hermite, one negative test per error, and proptest invariants.

use lekalo::{
    cubic_through_four_points, four_point_cubic_coefficients, hermite_segment_coefficients,
    natural_cubic_spline, parametrize, BSplineCurve, BSplineSurface, CubicHermite,
    CurveInterpolation, EndCondition, Error, KnotPlacement, Parametrization, Points, PointsRef,
    SurfaceInterpolation, SurfaceInterpolationReport, TangentEstimate,
};
use proptest::prelude::*;

use lekalo_testkit::vectors::example_9_1;
use lekalo_testkit::{assert_close, config};

/// Residual tolerance relative to the data's extent (what an interpolant must meet at its data).
const REL: f64 = 1e-12;

/// P&T Example 9.1 (docs/theory/interpolation.md#test-vectors).
fn example() -> Points {
    Points::from_2d(&example_9_1::POINTS).unwrap()
}

fn chord() -> Vec<f64> {
    example_9_1::CHORD_PARAMETERS.to_vec()
}

fn flat(p: &[[f64; 2]]) -> Vec<f64> {
    p.iter().flatten().copied().collect()
}

/// Largest distance between the curve at `params` and the points, and the bound it must meet:
/// `REL · extent` plus the rounding of the coordinates themselves (a few ulp of the largest
/// coordinate, which no representation in f64 can beat for data far from the origin).
fn residual(c: &BSplineCurve, points: &Points, params: &[f64]) -> (f64, f64) {
    let mut worst = 0.0_f64;
    for (k, &t) in params.iter().enumerate() {
        let r = c.eval(t).unwrap();
        for (a, b) in r.iter().zip(points.point(k)) {
            worst = worst.max((a - b).abs());
        }
    }
    let bound = REL * points.extent() + 8.0 * f64::EPSILON * points.max_abs();
    (worst, bound)
}

fn derivative(c: &BSplineCurve, t: f64, order: usize) -> Vec<f64> {
    c.eval_derivatives(t, order).unwrap().point(order).to_vec()
}

// ---------------------------------------------------------------- golden numbers, P&T Example 9.1

#[test]
fn example_9_1_free_cubic_three_parametrisations() {
    let q = example();
    let cases: [(Parametrization, f64, [[f64; 2]; 3]); 2] = [
        (
            Parametrization::ChordLength,
            28.0 / 51.0,
            [
                [7.316964, 3.686778],
                [-2.958131, 6.678277],
                [-4.494953, -0.673692],
            ],
        ),
        (
            Parametrization::Centripetal,
            0.525921,
            [
                [6.844809, 3.683071],
                [-2.780244, 7.092664],
                [-4.754979, -1.614238],
            ],
        ),
    ];
    for (method, knot, inner) in cases {
        let c = CurveInterpolation::new(3)
            .parametrization(method)
            .interpolate(q.as_view())
            .unwrap();
        assert_close(&c.knots().as_slice()[4..5], &[knot], 1e-6, "interior knot");
        let mut expect = vec![[0.0, 0.0]];
        expect.extend(inner);
        expect.push([-4.0, -3.0]);
        assert_close(
            c.control_points().as_slice(),
            &flat(&expect),
            1e-6,
            "control points",
        );
        let t = parametrize(q.as_view(), method).unwrap();
        let (worst, bound) = residual(&c, &q, &t);
        assert!(worst <= bound, "{method:?}: residual {worst}");
    }
    let t = parametrize(q.as_view(), Parametrization::Centripetal).unwrap();
    assert_close(
        &t,
        &[0.0, 0.272552, 0.516330, 0.788882, 1.0],
        1e-6,
        "centripetal parameters",
    );
    // uniform: exact control points
    let c = CurveInterpolation::new(3)
        .parametrization(Parametrization::Uniform)
        .interpolate(q.as_view())
        .unwrap();
    assert_close(
        c.knots().as_slice(),
        &[0., 0., 0., 0., 0.5, 1., 1., 1., 1.],
        0.0,
        "knots",
    );
    let expect = [
        [0.0, 0.0],
        [58.0 / 9.0, 67.0 / 18.0],
        [-8.0 / 3.0, 7.5],
        [-46.0 / 9.0, -49.0 / 18.0],
        [-4.0, -3.0],
    ];
    assert_close(
        c.control_points().as_slice(),
        &flat(&expect),
        1e-14,
        "uniform control",
    );
}

#[test]
fn example_9_1_chord_curve_values_and_quadratic() {
    let q = example();
    let c = CurveInterpolation::new(3).interpolate(q.as_view()).unwrap();
    for (t, e) in example_9_1::CUBIC_CHORD_VALUES {
        assert_close(&c.eval(t).unwrap(), &e, example_9_1::DECIMALS, "r(t)");
    }
    let c = CurveInterpolation::new(2).interpolate(q.as_view()).unwrap();
    assert_close(
        c.knots().as_slice(),
        &example_9_1::QUADRATIC_CHORD_KNOTS,
        1e-15,
        "quadratic knots",
    );
    assert_close(
        c.control_points().as_slice(),
        &flat(&example_9_1::QUADRATIC_CHORD_CONTROL),
        example_9_1::DECIMALS,
        "quadratic control",
    );
}

fn first_derivatives() -> EndCondition {
    EndCondition::FirstDerivatives {
        start: vec![1.0, 2.0],
        end: vec![-3.0, -1.0],
    }
}

#[test]
fn example_9_1_end_derivatives_any_degree() {
    let q = example();
    let cases: [(usize, Vec<f64>, [[f64; 2]; 7]); 2] = [
        (
            3,
            vec![
                0.,
                0.,
                0.,
                0.,
                14. / 51.,
                28. / 51.,
                40. / 51.,
                1.,
                1.,
                1.,
                1.,
            ],
            [
                [0.0, 0.0],
                [0.091503, 0.183007],
                [5.814921, 5.233246],
                [-1.946712, 4.199996],
                [-4.505986, 1.863104],
                [-3.784314, -2.928105],
                [-4.0, -3.0],
            ],
        ),
        (
            2,
            vec![
                0.,
                0.,
                0.,
                5. / 34.,
                7. / 17.,
                23. / 34.,
                31. / 34.,
                1.,
                1.,
                1.,
            ],
            [
                [0.0, 0.0],
                [0.073529, 0.147059],
                [4.523123, 4.612808],
                [-1.685332, 4.316488],
                [-4.293624, 0.852796],
                [-3.867647, -2.955882],
                [-4.0, -3.0],
            ],
        ),
    ];
    for (p, knots, ctrl) in cases {
        let c = CurveInterpolation::new(p)
            .end_condition(first_derivatives())
            .knot_placement(KnotPlacement::Averaged)
            .interpolate(q.as_view())
            .unwrap();
        assert_close(c.knots().as_slice(), &knots, 1e-15, "eq. 4 knots");
        assert_close(
            c.control_points().as_slice(),
            &flat(&ctrl),
            1e-6,
            "A.2 control",
        );
        assert_close(&derivative(&c, 0.0, 1), &[1.0, 2.0], 1e-12, "d0");
        assert_close(&derivative(&c, 1.0, 1), &[-3.0, -1.0], 1e-12, "dn");
        let (worst, bound) = residual(&c, &q, &chord());
        assert!(worst <= bound, "A.2 p={p}: residual {worst}");
    }
}

#[test]
fn example_9_1_cubic_knots_at_parameters() {
    let q = example();
    // Auto picks §3 for cubics with first derivatives
    let c = CurveInterpolation::new(3)
        .end_condition(first_derivatives())
        .interpolate(q.as_view())
        .unwrap();
    let mut knots = vec![0.0; 4];
    knots.extend(&chord()[1..4]);
    knots.extend([1.0; 4]);
    assert_close(c.knots().as_slice(), &knots, 0.0, "eq. 8 knots");
    let expect = [
        [0.0, 0.0],
        [0.098039, 0.196078],
        [5.671017, 5.171684],
        [-2.242701, 4.219889],
        [-4.453199, 1.460911],
        [-3.823529, -2.941176],
        [-4.0, -3.0],
    ];
    assert_close(
        c.control_points().as_slice(),
        &flat(&expect),
        1e-6,
        "A.3 control",
    );
    // p_1 = q_0 + 5/51 d_0 and p_5 = q_4 − 1/17 d_4 exactly
    assert_close(
        c.control_points().point(1),
        &[5.0 / 51.0, 10.0 / 51.0],
        1e-15,
        "p1",
    );
    assert_close(
        c.control_points().point(5),
        &[-4.0 + 3.0 / 17.0, -3.0 + 1.0 / 17.0],
        1e-15,
        "p5",
    );
    // the tridiagonal rows (a_k, b_k, c_k) of eq. 11
    let kv = c.knots();
    for (k, abc) in [
        (1, [0.197531, 0.604056, 0.198413]),
        (2, [0.198413, 0.653439, 0.148148]),
        (3, [0.093750, 0.515625, 0.390625]),
    ] {
        let (span, n) = lekalo::basis::basis_functions(kv, 3, chord()[k]).unwrap();
        assert_eq!(span, k + 3, "data parameter {k} starts span k + 3");
        assert_close(&n[..3], &abc, 1e-6, "a_k, b_k, c_k");
        assert_eq!(n[3], 0.0, "N_(k+3) vanishes at its first knot");
    }
    assert_close(&derivative(&c, 0.0, 1), &[1.0, 2.0], 1e-12, "d0");
    assert_close(&derivative(&c, 1.0, 1), &[-3.0, -1.0], 1e-12, "dn");
    // C² at the interior knots: left and right second derivatives agree
    for &t in &chord()[1..4] {
        let right = derivative(&c, t, 2);
        let left = derivative(&c, t - 1e-12, 2);
        assert_close(&left, &right, 1e-7, "C² at a knot");
    }
}

#[test]
fn example_9_1_second_derivatives_and_natural() {
    let q = example();
    let c = CurveInterpolation::new(3)
        .end_condition(EndCondition::SecondDerivatives {
            start: vec![2.0, -1.0],
            end: vec![0.5, 4.0],
        })
        .interpolate(q.as_view())
        .unwrap();
    let expect = [
        [0.0, 0.0],
        [1.792028, 1.645498],
        [5.069581, 4.581444],
        [-2.098122, 4.573864],
        [-4.285399, 0.690131],
        [-4.079724, -2.008700],
        [-4.0, -3.0],
    ];
    assert_close(
        c.control_points().as_slice(),
        &flat(&expect),
        1e-6,
        "A.4 control",
    );
    assert_close(&derivative(&c, 0.0, 2), &[2.0, -1.0], 1e-11, "d''0");
    assert_close(&derivative(&c, 1.0, 2), &[0.5, 4.0], 1e-11, "d''n");
    let (worst, bound) = residual(&c, &q, &chord());
    assert!(worst <= bound, "A.4 residual {worst}");
    // document 000's b_0, c_0, a_n, b_n are the unscaled rows (13), (14): check via the knots
    let k = c.knots().as_slice();
    let (t4, t5, tn1, tn2) = (k[4], k[5], k[5], k[6]);
    assert_close(
        &[
            -(1.0 / t4 + 1.0 / t5),
            1.0 / t5,
            1.0 / (1.0 - tn1),
            -(1.0 / (1.0 - tn1) + 1.0 / (1.0 - tn2)),
        ],
        &[-5.288889, 1.888889, 2.125, -7.791667],
        1e-6,
        "b0, c0, an, bn",
    );

    let c = CurveInterpolation::new(3)
        .end_condition(EndCondition::Natural)
        .interpolate(q.as_view())
        .unwrap();
    let expect = [
        [0.0, 0.0],
        [1.808397, 1.637040],
        [5.063510, 4.583713],
        [-2.095936, 4.575376],
        [-4.286914, 0.680423],
        [-4.078249, -1.996248],
        [-4.0, -3.0],
    ];
    assert_close(
        c.control_points().as_slice(),
        &flat(&expect),
        1e-6,
        "natural control",
    );
    assert_close(&derivative(&c, 0.0, 2), &[0.0, 0.0], 1e-11, "natural start");
    assert_close(&derivative(&c, 1.0, 2), &[0.0, 0.0], 1e-11, "natural end");
}

#[test]
fn natural_function_reproduces_lines_and_matches_the_parametric_form() {
    // a natural spline through collinear data is the line itself
    let x = [-2.0, -0.5, 0.1, 1.0, 3.5];
    let y: Vec<f64> = x.iter().map(|v| 3.0 * v - 1.0).collect();
    let s = natural_cubic_spline(&x, Points::from_flat(1, y).unwrap().as_view()).unwrap();
    for k in 0..=40 {
        let t = -2.0 + 5.5 * f64::from(k) / 40.0;
        assert!(
            (s.eval(t).unwrap()[0] - (3.0 * t - 1.0)).abs() < 1e-13,
            "line at {t}"
        );
    }
    // the function form with x = chord parameters equals the parametric natural spline
    let q = example();
    let f = natural_cubic_spline(&chord(), q.as_view()).unwrap();
    let c = CurveInterpolation::new(3)
        .end_condition(EndCondition::Natural)
        .interpolate(q.as_view())
        .unwrap();
    assert_close(
        f.control_points().as_slice(),
        c.control_points().as_slice(),
        1e-14,
        "same",
    );
}

// ---------------------------------------------------------------- offset and scale

fn wavy(n: usize, offset: f64, scale: f64) -> Points {
    let data = (0..n)
        .flat_map(|k| {
            let s = k as f64 * 0.37;
            [
                offset + scale * (s + 0.3 * s.sin()),
                offset + scale * s.cos(),
                offset + scale * 0.2 * s,
            ]
        })
        .collect();
    Points::from_flat(3, data).unwrap()
}

#[test]
fn offset_and_scaled_data_meet_the_residual_bound() {
    for (offset, scale) in [
        (0.0, 1.0),
        (1e8, 1.0),
        (1e8, 1e6),
        (0.0, 1e-8),
        (-3e7, 1e-3),
    ] {
        let q = wavy(200, offset, scale);
        let base = wavy(200, 0.0, 1.0);
        for end in [
            EndCondition::Free,
            EndCondition::Natural,
            first_derivatives_3d(scale),
        ] {
            let interp = CurveInterpolation::new(3).end_condition(end.clone());
            let c = interp.interpolate(q.as_view()).unwrap();
            let t = parametrize(q.as_view(), Parametrization::ChordLength).unwrap();
            let (worst, bound) = residual(&c, &q, &t);
            assert!(
                worst <= bound,
                "offset {offset} scale {scale} {end:?}: {worst} > {bound}"
            );
            // parameters do not depend on offset or scale
            let t0 = parametrize(base.as_view(), Parametrization::ChordLength).unwrap();
            let dev = t
                .iter()
                .zip(&t0)
                .fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()));
            // only the rounding of the offset coordinates may move them
            let limit = 64.0 * f64::EPSILON * (1.0 + offset.abs() / scale);
            assert!(dev <= limit, "parameters moved {dev} > {limit}");
        }
    }
}

fn first_derivatives_3d(scale: f64) -> EndCondition {
    EndCondition::FirstDerivatives {
        start: vec![scale, -scale, 0.5 * scale],
        end: vec![0.0, scale, 2.0 * scale],
    }
}

#[test]
fn large_input_is_fast_enough_in_debug_and_exact_at_the_ends() {
    let q = wavy(20_000, 0.0, 1.0);
    let c = CurveInterpolation::new(3).interpolate(q.as_view()).unwrap();
    assert_eq!(c.control_points().point(0), q.point(0), "P_0 = q_0 exactly");
    assert_eq!(
        c.control_points().point(19_999),
        q.point(19_999),
        "P_n = q_n exactly"
    );
    let t = parametrize(q.as_view(), Parametrization::ChordLength).unwrap();
    let (worst, bound) = residual(&c, &q, &t);
    assert!(worst <= bound, "residual {worst}");
}

// ---------------------------------------------------------------- closed curves

fn closure_error(c: &BSplineCurve) -> f64 {
    let (a, b) = c.domain();
    let mut worst = 0.0_f64;
    for r in 0..c.degree() {
        let da = derivative(c, a, r);
        let db = derivative(c, b, r);
        let mag = 1.0 + da.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        for (x, y) in da.iter().zip(&db) {
            worst = worst.max((x - y).abs() / mag);
        }
    }
    worst
}

#[test]
fn periodic_curves_close_smoothly_for_every_degree() {
    let square = Points::from_2d(&[
        [0.0, 0.0],
        [2.0, 0.0],
        [2.0, 1.0],
        [0.5, 1.5],
        [-0.5, 0.8],
        [0.0, 0.0],
    ])
    .unwrap();
    for p in 1..=4 {
        let c = CurveInterpolation::new(p)
            .end_condition(EndCondition::Periodic)
            .interpolate(square.as_view())
            .unwrap();
        // the duplicated closing point was dropped: 5 corners, 5 + p control points
        assert_eq!(c.control_points().len(), 5 + p, "degree {p}");
        let mut t = parametrize(
            Points::from_2d(&[
                [0.0, 0.0],
                [2.0, 0.0],
                [2.0, 1.0],
                [0.5, 1.5],
                [-0.5, 0.8],
                [0.0, 0.0],
            ])
            .unwrap()
            .as_view(),
            Parametrization::ChordLength,
        )
        .unwrap();
        t.pop();
        let corners = Points::from_flat(2, square.as_slice()[..10].to_vec()).unwrap();
        let (worst, bound) = residual(&c, &corners, &t);
        assert!(worst <= bound, "degree {p}: residual {worst}");
        assert!(
            closure_error(&c) < 1e-12,
            "degree {p}: seam error {}",
            closure_error(&c)
        );
        let (a, b) = c.domain();
        assert!(((b - a) - 1.0).abs() < 1e-15, "period 1");
    }
}

#[test]
fn periodic_cubic_of_a_regular_polygon_is_symmetric() {
    // 8 points on a circle: the periodic cubic stays within 1e-3 of the circle
    let pts: Vec<[f64; 2]> = (0..8)
        .map(|k| {
            let a = std::f64::consts::TAU * f64::from(k) / 8.0;
            [a.cos(), a.sin()]
        })
        .collect();
    let c = CurveInterpolation::new(3)
        .end_condition(EndCondition::Periodic)
        .interpolate(Points::from_2d(&pts).unwrap().as_view())
        .unwrap();
    for k in 0..=100 {
        let r = c.eval(f64::from(k) / 100.0).unwrap();
        let rad = (r[0] * r[0] + r[1] * r[1]).sqrt();
        assert!((rad - 1.0).abs() < 2e-3, "radius {rad}");
    }
}

// ---------------------------------------------------------------- surfaces

fn grid(nu: usize, nv: usize, offset: f64) -> Points {
    let mut data = Vec::new();
    for k in 0..nu {
        for l in 0..nv {
            let (x, y) = (
                k as f64 + 0.1 * (l as f64).sin(),
                l as f64 * 0.7 + 0.05 * k as f64,
            );
            data.extend([
                offset + x,
                offset + y,
                offset + (0.3 * x).sin() * (0.5 * y).cos(),
            ]);
        }
    }
    Points::from_flat(3, data).unwrap()
}

/// The surface through a grid, with its parameters.
fn surface_through(
    g: &Points,
    nu: usize,
    nv: usize,
    (p, q): (usize, usize),
    parametrization: Parametrization,
) -> lekalo::Result<(BSplineSurface, SurfaceInterpolationReport)> {
    SurfaceInterpolation::new(p, q)
        .parametrization(parametrization)
        .interpolate_with_report(g.as_view(), nu, nv)
}

#[test]
fn surface_hits_the_grid_and_equals_the_kronecker_solve() {
    for offset in [0.0, 1e8] {
        let (nu, nv) = (7, 5);
        let g = grid(nu, nv, offset);
        let (s, report) =
            surface_through(&g, nu, nv, (3, 2), Parametrization::ChordLength).unwrap();
        let (params_u, params_v) = (report.params_u(), report.params_v());
        assert_eq!(s.net_size(), (nu, nv), "net size");
        let bound = REL * g.extent() + 16.0 * f64::EPSILON * g.max_abs();
        for k in 0..nu {
            for l in 0..nv {
                let r = s.eval(params_u[k], params_v[l]).unwrap();
                for (a, b) in r.iter().zip(g.point(k * nv + l)) {
                    assert!((a - b).abs() <= bound, "({k},{l}): {a} vs {b}");
                }
            }
        }
        if offset == 0.0 {
            // direct Kronecker solve (A_u ⊗ A_v) vec(P) = vec(Q), dense, for this small case
            let n = nu * nv;
            let mut a = vec![0.0; n * n];
            for k in 0..nu {
                for l in 0..nv {
                    for i in 0..nu {
                        for j in 0..nv {
                            let bu = lekalo::basis::basis_function_recursive(
                                s.knots_u(),
                                i,
                                3,
                                params_u[k],
                            )
                            .unwrap();
                            let bv = lekalo::basis::basis_function_recursive(
                                s.knots_v(),
                                j,
                                2,
                                params_v[l],
                            )
                            .unwrap();
                            a[(k * nv + l) * n + i * nv + j] = bu * bv;
                        }
                    }
                }
            }
            let x = dense_solve(a, g.as_slice().to_vec(), n, 3);
            assert_close(s.control_points().as_slice(), &x, 1e-12, "Kronecker");
        }
    }
}

/// Gaussian elimination with partial pivoting, test oracle only.
fn dense_solve(mut a: Vec<f64>, mut b: Vec<f64>, n: usize, m: usize) -> Vec<f64> {
    for k in 0..n {
        let piv = (k..n)
            .max_by(|&i, &j| a[i * n + k].abs().total_cmp(&a[j * n + k].abs()))
            .unwrap();
        for j in 0..n {
            a.swap(k * n + j, piv * n + j);
        }
        for j in 0..m {
            b.swap(k * m + j, piv * m + j);
        }
        for i in k + 1..n {
            let f = a[i * n + k] / a[k * n + k];
            for j in k..n {
                a[i * n + j] -= f * a[k * n + j];
            }
            for j in 0..m {
                b[i * m + j] -= f * b[k * m + j];
            }
        }
    }
    for k in (0..n).rev() {
        for j in 0..m {
            let mut s = b[k * m + j];
            for i in k + 1..n {
                s -= a[k * n + i] * b[i * m + j];
            }
            b[k * m + j] = s / a[k * n + k];
        }
    }
    b
}

#[test]
fn surface_parameters_are_row_and_column_averages() {
    let (nu, nv) = (4, 3);
    let g = grid(nu, nv, 0.0);
    let (_, report) = surface_through(&g, nu, nv, (2, 2), Parametrization::ChordLength).unwrap();
    let mut expect = vec![0.0; nu];
    for l in 0..nv {
        let col: Vec<f64> = (0..nu).flat_map(|k| g.point(k * nv + l).to_vec()).collect();
        let t = parametrize(
            Points::from_flat(3, col).unwrap().as_view(),
            Parametrization::ChordLength,
        )
        .unwrap();
        for (e, v) in expect.iter_mut().zip(t) {
            *e += v / nv as f64;
        }
    }
    assert_close(report.params_u(), &expect, 1e-15, "ū averaged over columns");
}

/// The grid functions kept for code written before `SurfaceInterpolation` give its surface,
/// parameters and condition estimate, and refuse what it refuses.
#[test]
#[allow(deprecated)]
fn deprecated_surface_functions_match_the_builder() {
    let (nu, nv) = (6, 5);
    let g = grid(nu, nv, 0.0);
    let param = Parametrization::Centripetal;
    let fit = SurfaceInterpolation::new(3, 2).parametrization(param);
    let (s, report) = fit.interpolate_with_report(g.as_view(), nu, nv).unwrap();
    let old = lekalo::interpolate_surface(g.as_view(), nu, nv, 3, 2, param).unwrap();
    assert_eq!((old.nu, old.nv), (nu, nv), "net size");
    assert_eq!(old.params_u, report.params_u(), "row parameters");
    assert_eq!(old.params_v, report.params_v(), "column parameters");
    assert_eq!(old.into_surface(), s, "surface");
    let kappa = lekalo::interpolate_surface_condition(g.as_view(), nu, nv, 3, 2, param).unwrap();
    assert_eq!(kappa, report.condition(), "condition estimate");
    let limited =
        lekalo::interpolate_surface_max_condition(g.as_view(), nu, nv, 3, 2, param, 1e12).unwrap();
    assert_eq!(limited.into_surface(), s, "surface under a limit");
    assert!(matches!(
        lekalo::interpolate_surface_max_condition(g.as_view(), nu, nv, 3, 2, param, 1.0),
        Err(Error::IllConditioned { .. })
    ));
    assert!(matches!(
        lekalo::interpolate_surface(g.as_view(), nu, nv, 6, 2, param),
        Err(Error::Degree { .. })
    ));
}

// ---------------------------------------------------------------- Hermite and document 002,
// four-point cubic

#[test]
fn four_point_cubic_matches_the_lecture() {
    let p = Points::from_2d(&[[0.0, 1.0], [1.0, 3.0], [2.5, 2.0], [3.0, -1.0]]).unwrap();
    let c = cubic_through_four_points(p.as_view()).unwrap();
    let coef = four_point_cubic_coefficients(p.as_view()).unwrap();
    for (k, u) in [0.0, 1.0 / 3.0, 2.0 / 3.0, 1.0].into_iter().enumerate() {
        assert_close(&c.eval(u).unwrap(), p.point(k), 1e-14, "through p_k");
    }
    for k in 0..=10 {
        let u = f64::from(k) / 10.0;
        let power: Vec<f64> = (0..2)
            .map(|d| {
                let [a, b, cc, dd] = [0, 1, 2, 3].map(|r| coef.point(r)[d]);
                ((a * u + b) * u + cc) * u + dd
            })
            .collect();
        assert_close(&c.eval(u).unwrap(), &power, 1e-13, "power = Bezier form");
    }
}

#[test]
fn hermite_segment_is_the_lecture_matrix() {
    let (p0, p1, d0, d1) = ([1.0, 2.0], [4.0, -1.0], [0.5, 3.0], [-2.0, 1.0]);
    let c = hermite_segment_coefficients(&p0, &p1, &d0, &d1).unwrap();
    let h = CubicHermite::new(
        vec![0.0, 1.0],
        Points::from_2d(&[p0, p1]).unwrap(),
        Points::from_2d(&[d0, d1]).unwrap(),
    )
    .unwrap();
    for k in 0..=8 {
        let u = f64::from(k) / 8.0;
        let power: Vec<f64> = (0..2)
            .map(|d| {
                let [a, b, cc, dd] = [0, 1, 2, 3].map(|r| c.point(r)[d]);
                ((a * u + b) * u + cc) * u + dd
            })
            .collect();
        assert_close(&h.eval(u).unwrap(), &power, 1e-14, "Hermite basis = M_H");
    }
    // P'(1) = 3a + 2b + c = d1 (the corrected forward row [3 2 1 0])
    for d in 0..2 {
        let v = 3.0 * c.point(0)[d] + 2.0 * c.point(1)[d] + c.point(2)[d];
        assert!((v - d1[d]).abs() < 1e-14, "P'(1)");
    }
}

#[test]
fn hermite_conversions_agree_and_are_c1() {
    let q = example();
    for est in [
        TangentEstimate::FiniteDifference,
        TangentEstimate::CatmullRom,
        TangentEstimate::Cardinal { tension: 0.3 },
        TangentEstimate::Monotone,
    ] {
        let h = CubicHermite::from_points(q.as_view(), Parametrization::ChordLength, est).unwrap();
        let b = h.to_bspline();
        let segs = h.to_bezier_segments();
        let t = h.params().to_vec();
        for k in 0..=50 {
            let s = f64::from(k) / 50.0;
            let e = h.eval(s).unwrap();
            assert_close(&b.eval(s).unwrap(), &e, 1e-13, "B-spline form");
            let seg = (t.partition_point(|&x| x <= s) - 1).min(3);
            let u = (s - t[seg]) / (t[seg + 1] - t[seg]);
            assert_close(
                &segs[seg].eval(u.clamp(0.0, 1.0)).unwrap(),
                &e,
                1e-13,
                "Bezier form",
            );
        }
        for (k, &tk) in t.iter().enumerate() {
            assert_close(&h.eval(tk).unwrap(), q.point(k), 1e-14, "through the data");
            assert_close(
                &derivative(&b, tk, 1),
                h.tangents().point(k),
                1e-12,
                "tangent",
            );
        }
    }
    // Catmull–Rom with uniform parameters is (p_{k+1} − p_{k−1})/2 per unit parameter
    let h = CubicHermite::from_points(
        q.as_view(),
        Parametrization::Uniform,
        TangentEstimate::CatmullRom,
    )
    .unwrap();
    assert_close(
        h.tangents().point(2),
        &[(-4.0 - 3.0) * 2.0, (0.0 - 4.0) * 2.0],
        1e-13,
        "CR",
    );
    let card = CubicHermite::from_points(
        q.as_view(),
        Parametrization::Uniform,
        TangentEstimate::Cardinal { tension: 1.0 },
    )
    .unwrap();
    assert!(
        card.tangents().as_slice().iter().all(|&v| v == 0.0),
        "tension 1: zero tangents"
    );
}

#[test]
fn monotone_hermite_preserves_monotonicity() {
    // Akima's classic non-smooth monotone data
    let x = [0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0];
    let y = [0.0, 0.0, 0.0, 0.1, 5.0, 5.0, 5.1, 9.0, 9.0];
    let h = CubicHermite::function(
        &x,
        Points::from_flat(1, y.to_vec()).unwrap().as_view(),
        TangentEstimate::Monotone,
    )
    .unwrap();
    let mut prev = f64::NEG_INFINITY;
    for k in 0..=800 {
        let v = h.eval(8.0 * f64::from(k) / 800.0).unwrap()[0];
        assert!(v >= prev - 1e-14, "decrease at {k}: {v} < {prev}");
        prev = v;
    }
    // the finite-difference tangents are not monotone on the same data
    let fd = CubicHermite::function(
        &x,
        Points::from_flat(1, y.to_vec()).unwrap().as_view(),
        TangentEstimate::FiniteDifference,
    )
    .unwrap();
    let values: Vec<f64> = (0..=800)
        .map(|k| fd.eval(8.0 * f64::from(k) / 800.0).unwrap()[0])
        .collect();
    let overshoot = values.windows(2).any(|w| w[1] < w[0] - 1e-6);
    assert!(
        overshoot,
        "finite differences should overshoot here (the test data would be too easy)"
    );
}

// ---------------------------------------------------------------- errors

fn pts(v: &[[f64; 2]]) -> Points {
    Points::from_2d(v).unwrap()
}

#[test]
fn error_coincident_points_and_dropping_them() {
    let q = pts(&[[0.0, 0.0], [1.0, 1.0], [1.0, 1.0], [2.0, 0.0]]);
    let e = CurveInterpolation::new(2)
        .interpolate(q.as_view())
        .unwrap_err();
    assert_eq!(
        e,
        Error::CoincidentPoints {
            first: 1,
            second: 2
        }
    );
    let c = CurveInterpolation::new(2)
        .drop_duplicates(true)
        .interpolate(q.as_view())
        .unwrap();
    assert_eq!(c.control_points().len(), 3, "one duplicate dropped");
    // uniform parameters accept the duplicate: the curve visits the point twice
    let c = CurveInterpolation::new(2)
        .parametrization(Parametrization::Uniform)
        .interpolate(q.as_view())
        .unwrap();
    assert_close(
        &c.eval(1.0 / 3.0).unwrap(),
        &[1.0, 1.0],
        1e-14,
        "first visit",
    );
    assert_close(
        &c.eval(2.0 / 3.0).unwrap(),
        &[1.0, 1.0],
        1e-14,
        "second visit",
    );
    // closed curves check the closing chord too
    let e = CurveInterpolation::new(1)
        .end_condition(EndCondition::Periodic)
        .interpolate(pts(&[[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [1.0, 1.0], [0.0, 1.0]]).as_view())
        .unwrap_err();
    assert_eq!(
        e,
        Error::CoincidentPoints {
            first: 2,
            second: 3
        }
    );
    let e = SurfaceInterpolation::new(1, 1)
        .interpolate(
            Points::from_flat(2, vec![0.0, 0.0, 1.0, 1.0, 0.0, 0.0, 2.0, 2.0])
                .unwrap()
                .as_view(),
            2,
            2,
        )
        .unwrap_err();
    assert_eq!(
        e,
        Error::CoincidentPoints {
            first: 0,
            second: 2
        }
    );
}

#[test]
fn error_singular_system_with_uniform_knots() {
    // eq. (2) with chord-length parameters: t̄_1 ≈ 0.95 lies outside the support [0, 0.5] of
    // N_1, the Schoenberg–Whitney condition fails (the source's warning)
    let q = pts(&[
        [0.0, 0.0],
        [100.0, 0.0],
        [101.0, 0.0],
        [102.0, 0.0],
        [103.0, 0.0],
        [104.0, 0.0],
        [105.0, 0.0],
    ]);
    let e = CurveInterpolation::new(3)
        .knot_placement(KnotPlacement::Uniform)
        .interpolate(q.as_view())
        .unwrap_err();
    assert!(matches!(e, Error::SingularSystem { .. }), "{e:?}");
    // averaged knots handle the same data
    let c = CurveInterpolation::new(3).interpolate(q.as_view()).unwrap();
    let t = parametrize(q.as_view(), Parametrization::ChordLength).unwrap();
    let (worst, bound) = residual(&c, &q, &t);
    assert!(worst <= bound, "averaged knots: residual {worst}");
}

#[test]
fn error_ill_conditioned_parameters() {
    // parameters so uneven that the collocation factors grow past the limit
    let q = Points::from_flat(1, vec![0.0, 1.0, 2.0, 3.0, 4.0, 5.0]).unwrap();
    let t = [0.0, 1e-13, 2e-13, 0.5, 1.0 - 1e-13, 1.0];
    let r = CurveInterpolation::new(3).interpolate_at(q.as_view(), &t);
    assert!(
        matches!(
            r,
            Err(Error::IllConditioned { .. } | Error::SingularSystem { .. })
        ),
        "{r:?}"
    );
}

#[test]
fn error_degree_dimension_counts_and_arguments() {
    let q = example();
    let v = q.as_view();
    let degree =
        |r: Result<BSplineCurve, Error>| assert!(matches!(r, Err(Error::Degree { .. })), "{r:?}");
    degree(CurveInterpolation::new(0).interpolate(v));
    degree(CurveInterpolation::new(5).interpolate(v));
    degree(
        CurveInterpolation::new(1)
            .end_condition(first_derivatives())
            .knot_placement(KnotPlacement::Averaged)
            .interpolate(v),
    );
    degree(
        CurveInterpolation::new(4)
            .end_condition(EndCondition::Natural)
            .interpolate(v),
    );
    degree(
        CurveInterpolation::new(2)
            .end_condition(first_derivatives())
            .knot_placement(KnotPlacement::AtParameters)
            .interpolate(v),
    );
    // a closed curve takes any degree (its basis functions wrap around the period), up to the
    // library's bound
    assert!(CurveInterpolation::new(5)
        .end_condition(EndCondition::Periodic)
        .interpolate(v)
        .is_ok());
    degree(
        CurveInterpolation::new(lekalo::MAX_DEGREE + 1)
            .end_condition(EndCondition::Periodic)
            .interpolate(v),
    );
    let e = CurveInterpolation::new(3)
        .end_condition(EndCondition::FirstDerivatives {
            start: vec![1.0],
            end: vec![0.0, 0.0],
        })
        .interpolate(v)
        .unwrap_err();
    assert!(
        matches!(
            e,
            Error::Dimension {
                expected: 2,
                got: 1,
                ..
            }
        ),
        "{e:?}"
    );
    let e = CurveInterpolation::new(3)
        .end_condition(EndCondition::SecondDerivatives {
            start: vec![f64::NAN, 0.0],
            end: vec![0.0, 0.0],
        })
        .interpolate(v)
        .unwrap_err();
    assert!(matches!(e, Error::NonFinite { .. }), "{e:?}");
    let one = pts(&[[1.0, 1.0]]);
    assert!(matches!(
        CurveInterpolation::new(1).interpolate(one.as_view()),
        Err(Error::TooFew { .. })
    ));
    assert!(matches!(
        CurveInterpolation::new(3).interpolate_at(v, &[0.0, 1.0]),
        Err(Error::LengthMismatch {
            expected: 5,
            got: 2,
            ..
        })
    ));
    assert!(matches!(
        CurveInterpolation::new(3).interpolate_at(v, &[0.0, 0.5, 0.4, 0.8, 1.0]),
        Err(Error::NotIncreasing { index: 2, .. })
    ));
    let invalid = |r: Result<BSplineCurve, Error>| {
        assert!(matches!(r, Err(Error::InvalidArgument { .. })), "{r:?}")
    };
    assert!(matches!(
        CurveInterpolation::new(3).interpolate_at(v, &[0.0, 0.5, 0.5, 0.8, 1.0]),
        Err(Error::Repeated { index: 2, .. })
    ));
    invalid(
        CurveInterpolation::new(3)
            .parametrization(Parametrization::Exponent(-1.0))
            .interpolate(v),
    );
    invalid(
        CurveInterpolation::new(3)
            .knot_placement(KnotPlacement::AtParameters)
            .interpolate(v),
    );
    invalid(
        CurveInterpolation::new(3)
            .end_condition(EndCondition::Natural)
            .knot_placement(KnotPlacement::Averaged)
            .interpolate(v),
    );
    invalid(
        CurveInterpolation::new(3)
            .end_condition(EndCondition::Periodic)
            .knot_placement(KnotPlacement::Averaged)
            .interpolate(v),
    );
    invalid(
        CurveInterpolation::new(3)
            .end_condition(first_derivatives())
            .knot_placement(KnotPlacement::Uniform)
            .interpolate(v),
    );
    // surfaces
    let g = grid(4, 3, 0.0);
    assert!(matches!(
        surface_through(&g, 4, 4, (2, 2), Parametrization::Uniform),
        Err(Error::LengthMismatch { .. })
    ));
    assert!(matches!(
        surface_through(&g, 4, 3, (4, 2), Parametrization::Uniform),
        Err(Error::Degree { .. })
    ));
    let line = Points::from_flat(1, vec![0.0, 1.0]).unwrap();
    assert!(matches!(
        surface_through(&line, 1, 2, (1, 1), Parametrization::Uniform),
        Err(Error::TooFew { .. })
    ));
    // Hermite
    let e = CubicHermite::from_points(
        v,
        Parametrization::Uniform,
        TangentEstimate::Cardinal { tension: 1.5 },
    )
    .unwrap_err();
    assert!(
        matches!(e, Error::InvalidArgument { what, .. } if what.words() == "tension"),
        "{e:?}"
    );
    let e = CubicHermite::new(
        vec![0.0, 1.0],
        pts(&[[0.0, 0.0], [1.0, 1.0]]),
        pts(&[[0.0, 0.0]]),
    )
    .unwrap_err();
    assert!(matches!(e, Error::LengthMismatch { .. }), "{e:?}");
    let e = CubicHermite::new(
        vec![0.0, 1.0],
        pts(&[[0.0, 0.0], [1.0, 1.0]]),
        Points::from_flat(1, vec![0.0, 0.0]).unwrap(),
    )
    .unwrap_err();
    assert!(matches!(e, Error::Dimension { .. }), "{e:?}");
    let h = CubicHermite::function(
        &[0.0, 1.0],
        Points::from_flat(1, vec![0.0, 1.0]).unwrap().as_view(),
        TangentEstimate::CatmullRom,
    )
    .unwrap();
    assert!(matches!(
        h.eval(1.5),
        Err(Error::ParameterOutOfDomain { .. })
    ));
    assert!(matches!(
        cubic_through_four_points(v),
        Err(Error::LengthMismatch {
            expected: 4,
            got: 5,
            ..
        })
    ));
    assert!(matches!(
        hermite_segment_coefficients(&[0.0], &[1.0, 2.0], &[0.0], &[0.0]),
        Err(Error::Dimension { .. })
    ));
}

// ---------------------------------------------------------------- proptest invariants

/// Points with steps bounded away from zero: a random walk with step lengths in [0.1, 1].
fn walk(dim: usize, min_n: usize, max_n: usize) -> impl Strategy<Value = Points> {
    prop::collection::vec(
        (prop::collection::vec(-1.0..1.0_f64, dim), 0.1..1.0_f64),
        min_n..max_n,
    )
    .prop_map(move |steps| {
        let mut data = vec![0.0; dim];
        let mut cur = vec![0.0; dim];
        for (dir, len) in steps {
            let norm = dir.iter().map(|x| x * x).sum::<f64>().sqrt().max(1e-3);
            for (c, d) in cur.iter_mut().zip(&dir) {
                *c += len * d / norm + 0.05;
            }
            data.extend_from_slice(&cur);
        }
        Points::from_flat(dim, data).unwrap()
    })
}

fn method() -> impl Strategy<Value = Parametrization> {
    prop_oneof![
        Just(Parametrization::Uniform),
        Just(Parametrization::ChordLength),
        Just(Parametrization::Centripetal),
        (0.0..1.5_f64).prop_map(Parametrization::Exponent),
    ]
}

fn params_of(q: PointsRef<'_>, m: Parametrization) -> Vec<f64> {
    parametrize(q, m).unwrap()
}

proptest! {
    #![proptest_config(config(64))]

    #[test]
    fn interpolants_hit_the_data(q in (1usize..5).prop_flat_map(|d| walk(d, 1, 40)), p in 1usize..6, m in method()) {
        let r = CurveInterpolation::new(p).parametrization(m).interpolate(q.as_view());
        if p >= q.len() {
            prop_assert!(matches!(r, Err(Error::Degree { .. })), "{:?}", r);
            return Ok(());
        }
        let c = r.unwrap();
        let t = params_of(q.as_view(), m);
        let (worst, bound) = residual(&c, &q, &t);
        prop_assert!(worst <= bound, "residual {} > {}", worst, bound);
    }

    #[test]
    fn end_derivatives_are_met(q in walk(3, 1, 30), p in 2usize..6, d in prop::collection::vec(-3.0..3.0_f64, 6), at_params in any::<bool>()) {
        let end = EndCondition::FirstDerivatives { start: d[..3].to_vec(), end: d[3..].to_vec() };
        let p = if at_params { 3 } else { p };
        let placement = if at_params { KnotPlacement::AtParameters } else { KnotPlacement::Averaged };
        let r = CurveInterpolation::new(p).end_condition(end).knot_placement(placement).interpolate(q.as_view());
        // n + 1 points and two derivatives carry a degree of at most n + 2
        if p > q.len() + 1 {
            prop_assert!(matches!(r, Err(Error::Degree { .. })), "{:?}", r);
            return Ok(());
        }
        let c = r.unwrap();
        let t = params_of(q.as_view(), Parametrization::ChordLength);
        let (worst, bound) = residual(&c, &q, &t);
        prop_assert!(worst <= bound, "residual {}", worst);
        let scale = q.extent().max(1.0);
        for (a, b) in derivative(&c, 0.0, 1).iter().zip(&d[..3]) {
            prop_assert!((a - b).abs() <= 1e-11 * scale, "d0 {} vs {}", a, b);
        }
        for (a, b) in derivative(&c, 1.0, 1).iter().zip(&d[3..]) {
            prop_assert!((a - b).abs() <= 1e-11 * scale, "dn {} vs {}", a, b);
        }
    }

    #[test]
    fn second_derivatives_are_met(q in walk(2, 1, 30), d in prop::collection::vec(-3.0..3.0_f64, 4)) {
        let end = EndCondition::SecondDerivatives { start: d[..2].to_vec(), end: d[2..].to_vec() };
        let c = CurveInterpolation::new(3).end_condition(end).interpolate(q.as_view()).unwrap();
        let t = params_of(q.as_view(), Parametrization::ChordLength);
        let (worst, bound) = residual(&c, &q, &t);
        prop_assert!(worst <= bound, "residual {}", worst);
        let scale = q.extent().max(1.0) * (q.len() as f64).powi(2);
        for (a, b) in derivative(&c, 0.0, 2).iter().zip(&d[..2]) {
            prop_assert!((a - b).abs() <= 1e-11 * scale, "d''0 {} vs {}", a, b);
        }
        for (a, b) in derivative(&c, 1.0, 2).iter().zip(&d[2..]) {
            prop_assert!((a - b).abs() <= 1e-11 * scale, "d''n {} vs {}", a, b);
        }
    }

    #[test]
    fn periodic_closure_is_c_p_minus_1(q in walk(2, 6, 30), p in 1usize..6, m in method()) {
        let c = CurveInterpolation::new(p).parametrization(m).end_condition(EndCondition::Periodic).interpolate(q.as_view()).unwrap();
        prop_assert!(closure_error(&c) < 1e-9, "seam error {}", closure_error(&c));
        let mut closed = q.as_slice().to_vec();
        closed.extend_from_slice(q.point(0));
        let t = params_of(Points::from_flat(2, closed).unwrap().as_view(), m);
        let (a, _) = c.domain();
        // even degrees: the domain starts before 0; q_0 sits at parameter 0 either way
        prop_assert!(a <= 0.0);
        let (worst, bound) = residual(&c, &q, &t[..q.len()]);
        prop_assert!(worst <= bound, "residual {}", worst);
    }

    #[test]
    fn surfaces_hit_their_grids(
        (nu, nv, dim) in (2usize..12, 2usize..12, 1usize..5),
        noise in prop::collection::vec(-0.3..0.3_f64, 11 * 11 * 4),
        (p, q) in (1usize..6, 1usize..6),
        m in method(),
        offset in prop_oneof![Just(0.0), Just(1e6)],
    ) {
        // a perturbed lattice: rows along the first coordinate, columns along the second (a
        // 1-D grid increases along both), the other coordinates free
        let mut data = Vec::with_capacity(nu * nv * dim);
        for k in 0..nu {
            for l in 0..nv {
                let e = &noise[((k * 11 + l) * 4)..((k * 11 + l) * 4 + 4)];
                let (x, y) = (k as f64, l as f64);
                let coords = if dim == 1 {
                    vec![(k * nv + l) as f64 + e[0]]
                } else {
                    let mut c = vec![x + e[0], y + e[1]];
                    c.extend(e[2..].iter().take(dim - 2).map(|v| 3.0 * v));
                    c
                };
                data.extend(coords.iter().map(|v| v + offset));
            }
        }
        let g = Points::from_flat(dim, data).unwrap();
        let r = surface_through(&g, nu, nv, (p, q), m);
        if p >= nu || q >= nv {
            prop_assert!(matches!(r, Err(Error::Degree { .. })), "{:?}", r);
            return Ok(());
        }
        let (s, report) = r.unwrap();
        let bound = REL * g.extent() + 16.0 * f64::EPSILON * g.max_abs();
        for k in 0..nu {
            for l in 0..nv {
                let at = s.eval(report.params_u()[k], report.params_v()[l]).unwrap();
                for (a, b) in at.iter().zip(g.point(k * nv + l)) {
                    prop_assert!((a - b).abs() <= bound, "({}, {}): {} vs {}", k, l, a, b);
                }
            }
        }
    }

    #[test]
    fn offset_does_not_change_the_shape(q in walk(2, 5, 20), off in -1_000_000i32..1_000_000) {
        // coordinates on a 2^-20 grid and an integer offset: the moved data are exact, so
        // only the final addition of the offset may round
        let grid = |v: f64| (v * 1_048_576.0).round() / 1_048_576.0;
        let q = Points::from_flat(2, q.as_slice().iter().map(|&v| grid(v)).collect()).unwrap();
        let off = f64::from(off);
        let moved = Points::from_flat(2, q.as_slice().iter().map(|v| v + off).collect()).unwrap();
        let a = CurveInterpolation::new(3).interpolate(q.as_view()).unwrap();
        let b = CurveInterpolation::new(3).interpolate(moved.as_view()).unwrap();
        let tol = 4.0 * f64::EPSILON * moved.max_abs();
        for (x, y) in a.control_points().as_slice().iter().zip(b.control_points().as_slice()) {
            prop_assert!((x + off - y).abs() <= tol, "{} vs {}", x + off, y);
        }
    }
}

// ---------------------------------------------------------------- independent implementation

/// Values printed by `tests/data/interpolation_scipy.py` (SciPy `make_interp_spline`, which
/// solves the collocation system by banded LU with pivoting, and `CubicSpline`), for the same
/// data, parameters and knots built from their definitions.
#[test]
fn scipy_agreement() {
    let data: Vec<f64> = (0..10)
        .flat_map(|k| {
            let k = f64::from(k);
            [k + 0.3 * (1.7 * k).sin(), (0.9 * k).cos(), 0.02 * k * k]
        })
        .collect();
    let q = Points::from_flat(3, data).unwrap();
    let ends = EndCondition::FirstDerivatives {
        start: vec![1.0, -0.5, 0.25],
        end: vec![0.5, 2.0, -1.0],
    };
    type Case = (&'static str, CurveInterpolation, [(f64, [f64; 3]); 4]);
    let cases: [Case; 6] = [
        (
            "free cubic",
            CurveInterpolation::new(3),
            [
                (
                    0.05,
                    [0.6662183970690504, 1.011754006238226, 0.002049312014172655],
                ),
                (
                    0.37,
                    [3.353554868571237, -1.0268033445408447, 0.24339406261218227],
                ),
                (
                    0.81,
                    [7.487086737118963, 0.931774761176388, 1.1141308241269392],
                ),
                (
                    0.999,
                    [9.11316289024844, -0.2344573255097861, 1.6160640667572437],
                ),
            ],
        ),
        (
            "free quintic",
            CurveInterpolation::new(5),
            [
                (
                    0.05,
                    [0.6997349421871283, 0.9709953241596508, 0.010228437433895482],
                ),
                (
                    0.37,
                    [3.345064403477189, -1.020305065947227, 0.24408087405140463],
                ),
                (
                    0.81,
                    [7.55172586500367, 0.8893186222713646, 1.11873548457168],
                ),
                (
                    0.999,
                    [9.103964817831551, -0.22843863348329968, 1.615412274240218],
                ),
            ],
        ),
        (
            "A.2 quartic",
            CurveInterpolation::new(4).end_condition(ends.clone()),
            [
                (
                    0.05,
                    [
                        0.41358114125898726,
                        0.9461893490894357,
                        0.0070091972935875935,
                    ],
                ),
                (
                    0.37,
                    [3.361521660266643, -1.0205631788715177, 0.24358386889175743],
                ),
                (
                    0.81,
                    [7.46550797432058, 0.9919633044789423, 1.0853091376912687],
                ),
                (
                    0.999,
                    [9.118410130568284, -0.24536303006013396, 1.6209249993837078],
                ),
            ],
        ),
        (
            "A.3 clamped cubic",
            CurveInterpolation::new(3).end_condition(ends),
            [
                (
                    0.05,
                    [0.3667971337174509, 0.9347842227045636, 0.007716851879445942],
                ),
                (
                    0.37,
                    [3.3625183758679875, -1.0222739842248065, 0.24247528429547405],
                ),
                (
                    0.81,
                    [7.453509976908036, 0.9941926465235043, 1.085633460282981],
                ),
                (
                    0.999,
                    [9.11842446677464, -0.24538855133536852, 1.6209360840931741],
                ),
            ],
        ),
        (
            "natural cubic",
            CurveInterpolation::new(3).end_condition(EndCondition::Natural),
            [
                (
                    0.05,
                    [
                        0.5887555914648147,
                        0.9177174840012001,
                        0.0038756781738846858,
                    ],
                ),
                (
                    0.37,
                    [3.358173011960798, -1.0221989698045821, 0.24266525388716603],
                ),
                (
                    0.81,
                    [7.489285819802053, 0.9371263782674826, 1.1090728821335543],
                ),
                (
                    0.999,
                    [9.112045760803086, -0.23522053829190182, 1.6167598861060013],
                ),
            ],
        ),
        (
            "periodic cubic",
            CurveInterpolation::new(3).end_condition(EndCondition::Periodic),
            [
                (
                    0.05,
                    [0.9944570160024777, 0.7921556929379101, 0.005481213753872394],
                ),
                (
                    0.37,
                    [6.063263345775079, 0.8236434936311472, 0.8039093650784801],
                ),
                (
                    0.81,
                    [2.7772592955176494, -0.00740257265677613, 0.8788219794482659],
                ),
                (
                    0.999,
                    [
                        -0.014103613853421848,
                        1.0006120275604342,
                        0.0010016885610628634,
                    ],
                ),
            ],
        ),
    ];
    // 1e-13 relative to the extent (≈ 9.5): both sides carry rounding of a few ulp per step
    let tol = 1e-13 * q.extent();
    for (name, interp, values) in cases {
        let c = interp.interpolate(q.as_view()).unwrap();
        for (u, e) in values {
            assert_close(&c.eval(u).unwrap(), &e, tol, name);
        }
    }
}

#[test]
fn end_derivatives_with_the_fewest_points() {
    // two points and two derivatives determine a cubic (the Hermite segment); p = n + 2
    let q = pts(&[[0.0, 0.0], [1.0, 1.0]]);
    for placement in [KnotPlacement::Averaged, KnotPlacement::AtParameters] {
        let c = CurveInterpolation::new(3)
            .end_condition(first_derivatives())
            .knot_placement(placement)
            .interpolate(q.as_view())
            .unwrap();
        let h =
            CubicHermite::new(vec![0.0, 1.0], q.clone(), pts(&[[1.0, 2.0], [-3.0, -1.0]])).unwrap();
        for k in 0..=10 {
            let t = f64::from(k) / 10.0;
            assert_close(
                &c.eval(t).unwrap(),
                &h.eval(t).unwrap(),
                1e-14,
                "Hermite segment",
            );
        }
    }
    // quadratic with two points and two derivatives: 4 control points
    let c = CurveInterpolation::new(2)
        .end_condition(first_derivatives())
        .interpolate(q.as_view())
        .unwrap();
    assert_close(&derivative(&c, 0.0, 1), &[1.0, 2.0], 1e-13, "d0");
    assert_close(&derivative(&c, 1.0, 1), &[-3.0, -1.0], 1e-13, "dn");
    assert_close(&c.eval(1.0).unwrap(), &[1.0, 1.0], 0.0, "end");
}
