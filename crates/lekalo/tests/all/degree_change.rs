//! Degree ("order") change of Bezier curves and surfaces (document 004; docs/theory/degree.md).
//!
//! Golden tests: the paper's Examples 1 and 2, every matrix compared exactly in rational
//! arithmetic (docs/theory/degree.md#worked-examples). Property tests
//! (dimensions 1 to 6): elevation keeps the curve or surface, reduction inverts elevation,
//! one-step elevation equals repeated eq. 6, monomial round trip, reductions below the real
//! degree are refused.

use lekalo_testkit::config;

use lekalo::{
    bernstein_monomial_matrix, bernstein_monomial_matrix_inverse, bezier_net_change_degree,
    bezier_net_elevate, bezier_net_real_degrees, bezier_net_real_degrees_monomial, elevation_block,
    order_change_matrix, reduction_block, BSplineCurve, BezierCurve, ElevationPlan, EndConditions,
    Error, KnotVector, Points, RationalMatrix, DEFAULT_DEGREE_TOLERANCE,
};
use num_bigint::BigInt;
use num_rational::BigRational;
use proptest::prelude::*;

/// A matrix from entries written as in the paper ("1/3", "0.4" is written "2/5").
fn matrix(rows: usize, cols: usize, entries: &[&str]) -> Vec<BigRational> {
    assert_eq!(entries.len(), rows * cols, "entry count");
    entries
        .iter()
        .map(|e| e.parse::<BigRational>().expect("rational literal"))
        .collect()
}

fn entries(m: &RationalMatrix) -> Vec<BigRational> {
    let mut out = Vec::new();
    for i in 0..m.rows() {
        for j in 0..m.cols() {
            out.push(m.get(i, j).expect("in range").clone());
        }
    }
    out
}

fn int(v: i64) -> BigRational {
    BigRational::from_integer(BigInt::from(v))
}

/// Largest coordinate difference between two curves at 201 parameters.
fn curve_dev(a: &BezierCurve, b: &BezierCurve) -> f64 {
    let mut m = 0.0_f64;
    for k in 0..=200 {
        let t = f64::from(k) / 200.0;
        let (pa, pb) = (
            a.eval(t).expect("t in [0,1]"),
            b.eval(t).expect("t in [0,1]"),
        );
        for (x, y) in pa.iter().zip(&pb) {
            m = m.max((x - y).abs());
        }
    }
    m
}

fn max_diff(a: &[f64], b: &[f64]) -> f64 {
    assert_eq!(a.len(), b.len(), "lengths");
    a.iter().zip(b).fold(0.0, |m, (x, y)| m.max((x - y).abs()))
}

/// Surface point through public curve evaluation: the rows of the net are the control points
/// of one curve of dimension (m+1)·dim along u, then a curve along v.
fn surface_eval(net: &Points, m: usize, u: f64, v: f64) -> Vec<f64> {
    let dim = net.dim();
    let rows = Points::from_flat((m + 1) * dim, net.as_slice().to_vec()).expect("net rows");
    let row = BezierCurve::new(rows).expect("curve").eval(u).expect("u");
    BezierCurve::new(Points::from_flat(dim, row).expect("row"))
        .expect("curve")
        .eval(v)
        .expect("v")
}

fn surface_dev(a: &Points, ma: usize, b: &Points, mb: usize) -> f64 {
    let mut m = 0.0_f64;
    for k in 0..=10 {
        for l in 0..=10 {
            let (u, v) = (f64::from(k) / 10.0, f64::from(l) / 10.0);
            m = m.max(max_diff(
                &surface_eval(a, ma, u, v),
                &surface_eval(b, mb, u, v),
            ));
        }
    }
    m
}

// ------------------------------------------------------------------------------------------
// Golden: document 004, Example 1 (eq. (7)–(8))
// ------------------------------------------------------------------------------------------

#[test]
fn example_1_task_1_quadratic_to_cubic() {
    let h2 = bernstein_monomial_matrix(2).unwrap();
    assert_eq!(
        entries(&h2),
        matrix(3, 3, &["1", "-2", "1", "0", "2", "-2", "0", "0", "1"])
    );
    let h3 = bernstein_monomial_matrix(3).unwrap();
    assert_eq!(
        entries(&h3),
        matrix(
            4,
            4,
            &["1", "-3", "3", "-1", "0", "3", "-6", "3", "0", "0", "3", "-3", "0", "0", "0", "1"]
        )
    );
    let h3i = bernstein_monomial_matrix_inverse(3).unwrap();
    assert_eq!(
        entries(&h3i),
        matrix(
            4,
            4,
            &[
                "1", "1", "1", "1", "0", "1/3", "2/3", "1", "0", "0", "1/3", "1", "0", "0", "0",
                "1"
            ]
        )
    );
    let k23 = elevation_block(2, 3).unwrap();
    assert_eq!(
        entries(&k23),
        matrix(
            3,
            4,
            &["1", "1", "1", "1", "0", "1/3", "2/3", "1", "0", "0", "1/3", "1"]
        )
    );
    let hk = h2.mul(&k23).unwrap();
    assert_eq!(
        entries(&hk),
        matrix(
            3,
            4,
            &["1", "1/3", "0", "0", "0", "2/3", "2/3", "0", "0", "0", "1/3", "1"]
        )
    );
    assert_eq!(hk, order_change_matrix(2, 3).unwrap(), "eq. 10 = eq. 7");
    // u'_1 = u_0/3 + 2u_1/3, u'_2 = 2u_1/3 + u_2/3 on a concrete polygon
    let c =
        BezierCurve::new(Points::from_2d(&[[0.0, 0.0], [3.0, 6.0], [9.0, 3.0]]).unwrap()).unwrap();
    let up = c.elevate_degree(1).unwrap();
    let expect = [0.0, 0.0, 2.0, 4.0, 5.0, 5.0, 9.0, 3.0];
    assert!(
        max_diff(up.control_points().as_slice(), &expect) < 1e-15,
        "task 1 points"
    );
    assert_eq!(
        up.control_points(),
        c.elevate_degree_once().control_points(),
        "eq. 6"
    );
}

#[test]
fn example_1_task_2_cubic_to_quartic() {
    let h4 = bernstein_monomial_matrix(4).unwrap();
    assert_eq!(
        entries(&h4),
        matrix(
            5,
            5,
            &[
                "1", "-4", "6", "-4", "1", "0", "4", "-12", "12", "-4", "0", "0", "6", "-12", "6",
                "0", "0", "0", "4", "-4", "0", "0", "0", "0", "1"
            ]
        )
    );
    let h4i = bernstein_monomial_matrix_inverse(4).unwrap();
    assert_eq!(
        entries(&h4i),
        matrix(
            5,
            5,
            &[
                "1", "1", "1", "1", "1", "0", "1/4", "1/2", "3/4", "1", "0", "0", "1/6", "1/2",
                "1", "0", "0", "0", "1/4", "1", "0", "0", "0", "0", "1"
            ]
        )
    );
    let k34 = elevation_block(3, 4).unwrap();
    assert_eq!(entries(&k34), entries(&h4i)[..20].to_vec(), "first 4 rows");
    let hk = bernstein_monomial_matrix(3).unwrap().mul(&k34).unwrap();
    assert_eq!(
        entries(&hk),
        matrix(
            4,
            5,
            &[
                "1", "1/4", "0", "0", "0", "0", "3/4", "1/2", "0", "0", "0", "0", "1/2", "3/4",
                "0", "0", "0", "0", "1/4", "1"
            ]
        )
    );
}

#[test]
fn example_1_task_3_cubic_to_quintic_in_one_step() {
    let h5 = bernstein_monomial_matrix(5).unwrap();
    assert_eq!(
        entries(&h5),
        matrix(
            6,
            6,
            &[
                "1", "-5", "10", "-10", "5", "-1", "0", "5", "-20", "30", "-20", "5", "0", "0",
                "10", "-30", "30", "-10", "0", "0", "0", "10", "-20", "10", "0", "0", "0", "0",
                "5", "-5", "0", "0", "0", "0", "0", "1"
            ]
        )
    );
    let h5i = bernstein_monomial_matrix_inverse(5).unwrap();
    assert_eq!(
        entries(&h5i),
        matrix(
            6,
            6,
            &[
                "1", "1", "1", "1", "1", "1", "0", "1/5", "2/5", "3/5", "4/5", "1", "0", "0",
                "1/10", "3/10", "3/5", "1", "0", "0", "0", "1/10", "2/5", "1", "0", "0", "0", "0",
                "1/5", "1", "0", "0", "0", "0", "0", "1"
            ]
        )
    );
    let hk = bernstein_monomial_matrix(3)
        .unwrap()
        .mul(&elevation_block(3, 5).unwrap())
        .unwrap();
    // printed as decimals: 0.4 = 2/5, 0.1 = 1/10, 0.6 = 3/5, 0.3 = 3/10
    assert_eq!(
        entries(&hk),
        matrix(
            4,
            6,
            &[
                "1", "2/5", "1/10", "0", "0", "0", "0", "3/5", "3/5", "3/10", "0", "0", "0", "0",
                "3/10", "3/5", "3/5", "0", "0", "0", "0", "1/10", "2/5", "1"
            ]
        )
    );
    // "instead of two successive transformations by (6), the six-point polygon is created at once"
    let c = BezierCurve::new(
        Points::from_3d(&[
            [1.0, 0.0, 2.0],
            [4.0, 5.0, -1.0],
            [7.0, -3.0, 0.5],
            [2.0, 2.0, 8.0],
        ])
        .unwrap(),
    )
    .unwrap();
    let one = c.elevate_degree(2).unwrap();
    let two = c.elevate_degree_once().elevate_degree_once();
    assert!(
        max_diff(
            one.control_points().as_slice(),
            two.control_points().as_slice()
        ) < 1e-14,
        "eq. 8 = eq. 6 twice"
    );
    // u'_2 = (u_0 + 6u_1 + 3u_2)/10
    let u = c.control_points();
    for k in 0..3 {
        let e = (u.point(0)[k] + 6.0 * u.point(1)[k] + 3.0 * u.point(2)[k]) / 10.0;
        assert!((one.control_points().point(2)[k] - e).abs() < 1e-14, "u'_2");
    }
}

// ------------------------------------------------------------------------------------------
// Golden: document 004, Example 2 (eq. (9)–(10))
// ------------------------------------------------------------------------------------------

const EXAMPLE_2: [[f64; 2]; 6] = [
    [10.0, 0.0],
    [22.0, 6.0],
    [19.0, 12.0],
    [11.0, 15.0],
    [8.0, 12.0],
    [20.0, 0.0],
];
const EXAMPLE_2_CUBIC: [f64; 8] = [10.0, 0.0, 30.0, 10.0, 0.0, 20.0, 20.0, 0.0];

#[test]
fn example_2_exact_matrices() {
    let u: Vec<BigRational> = [10, 0, 22, 6, 19, 12, 11, 15, 8, 12, 20, 0]
        .iter()
        .map(|&x| int(x))
        .collect();
    // S_5 = U_5 H_5, points as columns: apply H_5 to the points
    let s = bernstein_monomial_matrix(5)
        .unwrap()
        .apply_to_points(&u, 2)
        .unwrap();
    let expect_s: Vec<BigRational> = [10, 0, 60, 30, -150, 0, 100, -30, 0, 0, 0, 0]
        .iter()
        .map(|&v| int(v))
        .collect();
    assert_eq!(
        s, expect_s,
        "S_5 (x row 10 60 −150 100 0 0, y row 0 30 0 −30 0 0)"
    );
    let g = reduction_block(5, 3).unwrap();
    assert_eq!(
        entries(&g),
        matrix(
            6,
            4,
            &[
                "1", "-5", "10", "-10", "0", "5", "-20", "30", "0", "0", "10", "-30", "0", "0",
                "0", "10", "0", "0", "0", "0", "0", "0", "0", "0"
            ]
        )
    );
    let gh = g
        .mul(&bernstein_monomial_matrix_inverse(3).unwrap())
        .unwrap();
    assert_eq!(
        entries(&gh),
        matrix(
            6,
            4,
            &[
                "1", "-2/3", "1", "-4", "0", "5/3", "-10/3", "15", "0", "0", "10/3", "-20", "0",
                "0", "0", "10", "0", "0", "0", "0", "0", "0", "0", "0"
            ]
        )
    );
    let cubic = gh.apply_to_points(&u, 2).unwrap();
    let expect: Vec<BigRational> = [10, 0, 30, 10, 0, 20, 20, 0]
        .iter()
        .map(|&x| int(x))
        .collect();
    assert_eq!(cubic, expect, "(10,0) (30,10) (0,20) (20,0) exactly");
    assert_eq!(gh, order_change_matrix(5, 3).unwrap(), "eq. 9 = eq. 10");
}

#[test]
fn example_2_floating_point_paths() {
    let quintic = BezierCurve::new(Points::from_2d(&EXAMPLE_2).unwrap()).unwrap();
    assert_eq!(quintic.real_degree(), 3, "real degree n' = 3");
    assert_eq!(quintic.degree_defect(), 2, "defect d = 2");
    assert_eq!(
        quintic
            .real_degree_monomial(DEFAULT_DEGREE_TOLERANCE)
            .unwrap(),
        3,
        "paper's rule: two zero columns of S_5"
    );
    let s = quintic.to_monomial().unwrap();
    assert_eq!(
        s.as_slice(),
        &[10.0, 0.0, 60.0, 30.0, -150.0, 0.0, 100.0, -30.0, 0.0, 0.0, 0.0, 0.0]
    );
    let stable = quintic.change_degree(3).unwrap();
    assert!(
        max_diff(stable.control_points().as_slice(), &EXAMPLE_2_CUBIC) < 1e-13,
        "stable path: {:?}",
        stable.control_points()
    );
    assert_eq!(
        quintic.reduce_degree_exact().control_points(),
        stable.control_points()
    );
    let literal = quintic
        .change_degree_by_matrix(3, DEFAULT_DEGREE_TOLERANCE)
        .unwrap();
    assert_eq!(
        literal.control_points().as_slice(),
        &EXAMPLE_2_CUBIC,
        "eq. 9 in f64 is exact on integers"
    );
    // "the cubic coincides completely with the formally quintic original"
    assert!(curve_dev(&quintic, &stable) < 1e-13, "same curve");
    // reduction below the real degree is refused, naming it
    for target in [0, 1, 2] {
        for r in [
            quintic.change_degree(target),
            quintic.change_degree_by_matrix(target, DEFAULT_DEGREE_TOLERANCE),
        ] {
            let e = r.unwrap_err();
            assert_eq!(
                e,
                Error::DegreeReductionRefused {
                    requested: target,
                    real_degree: 3,
                    direction: "curve"
                }
            );
            assert!(e.to_string().contains("real degree is 3"), "{e}");
        }
    }
    // degree 4 is also exact (defect 2 ≥ 1)
    let quartic = quintic.change_degree(4).unwrap();
    assert!(curve_dev(&quintic, &quartic) < 1e-13, "quartic");
}

/// Document 004, Fig. 5 (docs/theory/degree.md#degree-change-of-surfaces): a (4, 3) net with one
/// zero bottom row of S has real u-order 3; (3, 3), (3, 6) and (4, 6) keep the shape, (6, 2) lowers
/// m without a defect and is refused.
#[test]
fn figure_5_surface_order_change() {
    let base: Vec<f64> = (0..16 * 3)
        .map(|i| f64::from((i * 7 + 3) % 13) - 6.0)
        .collect();
    let base = Points::from_flat(3, base).unwrap(); // degrees (3, 3)
    let net = bezier_net_elevate(&base, 3, 3, 1, 0).unwrap(); // (4, 3)
    assert_eq!(bezier_net_real_degrees(&net, 4, 3, 1e-10).unwrap(), (3, 3));
    assert_eq!(
        bezier_net_real_degrees_monomial(&net, 4, 3, 1e-10).unwrap(),
        (3, 3)
    );
    let scale = net.max_abs();
    for (nu, nv) in [(3, 3), (3, 6), (4, 6)] {
        let c = bezier_net_change_degree(&net, 4, 3, nu, nv, 1e-10).unwrap();
        assert!(surface_dev(&net, 3, &c, nv) < 1e-13 * scale, "({nu}, {nv})");
    }
    assert_eq!(
        bezier_net_change_degree(&net, 4, 3, 6, 2, 1e-10).unwrap_err(),
        Error::DegreeReductionRefused {
            requested: 2,
            real_degree: 3,
            direction: "v direction"
        }
    );
}

// ------------------------------------------------------------------------------------------
// Properties
// ------------------------------------------------------------------------------------------

/// (dim, degree, control points in [−10, 10]).
fn curve_strategy(max_degree: usize) -> impl Strategy<Value = BezierCurve> {
    (1usize..=6, 0usize..=max_degree).prop_flat_map(|(dim, n)| {
        prop::collection::vec(-10.0f64..10.0, (n + 1) * dim).prop_map(move |data| {
            BezierCurve::new(Points::from_flat(dim, data).expect("finite")).expect("non-empty")
        })
    })
}

/// A curve whose real degree is exactly `k` by construction: monomial coefficients with the
/// first coordinate of `s_k` at least 1 in magnitude (real degree = index of the last non-zero
/// monomial coefficient, docs/theory/degree.md#degree-defect-and-real-degree). Degrees up to 8,
/// where the power basis is accurate.
fn planted_degree_strategy() -> impl Strategy<Value = (BezierCurve, usize)> {
    (1usize..=6, 1usize..=8).prop_flat_map(|(dim, k)| {
        (
            prop::collection::vec(-10.0f64..10.0, (k + 1) * dim),
            1.0f64..10.0,
            any::<bool>(),
        )
            .prop_map(move |(mut s, lead, negative)| {
                s[k * dim] = if negative { -lead } else { lead };
                let c = BezierCurve::from_monomial(Points::from_flat(dim, s).expect("finite"))
                    .expect("degree ≤ 8");
                (c, k)
            })
    })
}

fn scale(c: &BezierCurve) -> f64 {
    c.control_points().max_abs().max(f64::MIN_POSITIVE)
}

proptest! {
    #![proptest_config(config(64))]

    /// Elevation leaves the curve unchanged to 1e-13 relative (degrees up to 40, by up to 20).
    #[test]
    fn elevation_keeps_the_curve(c in curve_strategy(40), r in 1usize..=20) {
        let up = c.elevate_degree(r).unwrap();
        prop_assert_eq!(up.degree(), c.degree() + r);
        let d = curve_dev(&c, &up);
        prop_assert!(d <= 1e-13 * scale(&c), "deviation {:e}", d);
    }

    /// Exact reduction inverts elevation, to 1e-10 relative up to degree 40 (elevated by up
    /// to 20: the condition number of the 40→60 elevation is 2e5).
    #[test]
    fn reduction_inverts_elevation(c in curve_strategy(40), r in 1usize..=20) {
        let up = c.elevate_degree(r).unwrap();
        let down = up.change_degree(c.degree()).unwrap();
        let d = max_diff(down.control_points().as_slice(), c.control_points().as_slice());
        prop_assert!(d <= 1e-10 * scale(&c), "net error {:e}", d);
    }

    /// One-step elevation by r (eq. 7–8) equals r single elevations (eq. 6).
    #[test]
    fn one_step_equals_repeated(c in curve_strategy(20), r in 1usize..=10) {
        let one = c.elevate_degree(r).unwrap();
        let mut rep = c.clone();
        for _ in 0..r {
            rep = rep.elevate_degree_once();
        }
        let d = max_diff(one.control_points().as_slice(), rep.control_points().as_slice());
        prop_assert!(d <= 1e-13 * scale(&c), "difference {:e}", d);
    }

    /// Bernstein → monomial → Bernstein. The error bound is ‖H_n‖∞‖H_n^{-1}‖∞ ε ≤ 3^n (n+1) ε
    /// relative (‖H_n‖∞ = max_i C(n,i) 2^(n−i) ≤ 3^n, ‖H_n^{-1}‖∞ = max_i (n+1)/(i+1)).
    #[test]
    fn monomial_round_trip(c in curve_strategy(10)) {
        let back = BezierCurve::from_monomial(c.to_monomial().unwrap()).unwrap();
        let n = c.degree();
        let bound = 3f64.powi(i32::try_from(n).unwrap()) * (n as f64 + 1.0) * f64::EPSILON;
        let d = max_diff(back.control_points().as_slice(), c.control_points().as_slice());
        prop_assert!(d <= bound * scale(&c), "error {:e}, bound {:e}", d, bound);
    }

    /// Reductions below the real degree are refused and name it; reductions to it succeed.
    #[test]
    fn reduction_below_real_degree_refused((c, k) in planted_degree_strategy(), r in 0usize..=10) {
        let up = c.elevate_degree(r).unwrap();
        prop_assert_eq!(up.real_degree(), k);
        prop_assert_eq!(up.degree_defect(), r);
        let e = up.change_degree(k - 1).unwrap_err();
        prop_assert_eq!(e, Error::DegreeReductionRefused {
            requested: k - 1, real_degree: k, direction: "curve"
        });
        let down = up.change_degree(k).unwrap();
        let d = curve_dev(&c, &down);
        prop_assert!(d <= 1e-12 * scale(&c), "reduced curve deviation {:e}", d);
    }

    /// Surfaces: elevation keeps the surface to 1e-13 relative; a planted defect is found and
    /// every raise/keep/lower combination down to it keeps the surface.
    #[test]
    fn surface_order_change(
        (dim, n, m, data) in (1usize..=6, 0usize..=5, 0usize..=5).prop_flat_map(|(dim, n, m)| {
            (Just(dim), Just(n), Just(m),
             prop::collection::vec(-10.0f64..10.0, (n + 1) * (m + 1) * dim))
        }),
        (au, av) in (0usize..=3, 0usize..=3),
        (tu, tv) in (0usize..=6, 0usize..=6),
    ) {
        let base = Points::from_flat(dim, data).unwrap();
        let net = bezier_net_elevate(&base, n, m, au, av).unwrap();
        let s = base.max_abs().max(f64::MIN_POSITIVE);
        prop_assert!(surface_dev(&base, m, &net, m + av) <= 1e-13 * s, "elevation");
        let (ru, rv) = bezier_net_real_degrees(&net, n + au, m + av, 1e-10).unwrap();
        prop_assert!(ru <= n && rv <= m, "defects found: ({}, {})", ru, rv);
        let (nu, nv) = (ru + tu, rv + tv);
        let c = bezier_net_change_degree(&net, n + au, m + av, nu, nv, 1e-10).unwrap();
        prop_assert!(surface_dev(&base, m, &c, nv) <= 1e-12 * s, "change to ({}, {})", nu, nv);
        if ru > 0 {
            let refused = matches!(
                bezier_net_change_degree(&net, n + au, m + av, ru - 1, nv, 1e-10),
                Err(Error::DegreeReductionRefused { direction: "u direction", .. })
            );
            prop_assert!(refused, "u below the real degree");
        }
    }
}

/// A clamped B-spline of degree 1..=4 with 1..=4 interior knots (some repeated), dims 1..=6.
fn bspline_strategy() -> impl Strategy<Value = BSplineCurve> {
    (
        1usize..=6,
        1usize..=4,
        prop::collection::vec(0.05f64..0.95, 1..=4),
        any::<bool>(),
    )
        .prop_flat_map(|(dim, p, mut inner, repeat)| {
            inner.sort_by(f64::total_cmp);
            if repeat && p >= 2 {
                inner.push(inner[0]); // a double knot: lower continuity there
                inner.sort_by(f64::total_cmp);
            }
            let n_ctrl = p + 1 + inner.len();
            prop::collection::vec(-10.0f64..10.0, n_ctrl * dim).prop_map(move |data| {
                let mut knots = vec![0.0; p + 1];
                knots.extend_from_slice(&inner);
                knots.extend(std::iter::repeat_n(1.0, p + 1));
                let kv = KnotVector::new(knots).expect("sorted");
                BSplineCurve::from_knot_vector(p, kv, Points::from_flat(dim, data).expect("finite"))
                    .expect("valid clamped B-spline")
            })
        })
}

fn bspline_dev(a: &BSplineCurve, b: &BSplineCurve) -> f64 {
    (0..=200)
        .map(|k| {
            let t = f64::from(k) / 200.0;
            max_diff(
                &a.eval(t).expect("in domain"),
                &b.eval(t).expect("in domain"),
            )
        })
        .fold(0.0, f64::max)
}

/// Found by the long property-test job (`PROPTEST_CASES=1000`): two knots 8e-6 apart. The
/// blossoms of the elevation were first taken on the tiny interval between them, at arguments
/// thousands of its lengths away, which amplified rounding to 1e-9 of the scale.
#[test]
fn bspline_elevation_with_two_close_knots() {
    let c = BSplineCurve::new(
        3,
        vec![
            0.0,
            0.0,
            0.0,
            0.0,
            0.4037810824558112,
            0.4037891742170899,
            1.0,
            1.0,
            1.0,
            1.0,
        ],
        Points::from_flat(1, vec![0.0, 0.0, 0.0, -5.268960839437541, 0.0, 0.0]).unwrap(),
    )
    .unwrap();
    for r in 1..=3 {
        let up = c.elevate_degree(r).unwrap();
        let dev = bspline_dev(&c, &up);
        assert!(
            dev <= 1e-13 * 5.268960839437541,
            "r = {r}: deviation {dev:e}"
        );
    }
}

proptest! {
    #![proptest_config(config(64))]

    /// B-spline elevation per Bezier piece keeps the curve; exact reduction returns it.
    #[test]
    fn bspline_elevation_and_reduction(c in bspline_strategy(), r in 1usize..=4) {
        let s = c.control_points().max_abs().max(f64::MIN_POSITIVE);
        let up = c.elevate_degree(r).unwrap();
        prop_assert_eq!(up.degree(), c.degree() + r);
        prop_assert!(bspline_dev(&c, &up) <= 1e-13 * s, "elevation");
        // the knots of P&T A5.9: interior multiplicity m becomes m + r, the ends p + r + 1
        let (a, b) = c.domain();
        let want: Vec<(f64, usize)> = c
            .knots()
            .distinct()
            .into_iter()
            .filter(|&(t, _)| t >= a && t <= b)
            .map(|(t, m)| (t, if t == a || t == b { c.degree() + r + 1 } else { m.min(c.degree()) + r }))
            .collect();
        prop_assert_eq!(up.knots().distinct(), want);
        let down = up.change_degree(c.degree()).unwrap();
        prop_assert!(bspline_dev(&c, &down) <= 1e-12 * s, "reduction");
    }

    /// The precomputed plan gives exactly the one-step elevation.
    #[test]
    fn plan_equals_elevate_degree(c in curve_strategy(15), r in 0usize..=15) {
        let plan = ElevationPlan::new(c.degree(), c.degree() + r).unwrap();
        prop_assert_eq!(plan.apply(&c).unwrap(), c.elevate_degree(r).unwrap());
    }

    /// Approximate reduction: the bound is an upper bound of the sampled deviation, the end
    /// conditions hold, and a curve with a defect is reduced exactly.
    #[test]
    fn approximate_reduction(c in curve_strategy(12), r in 0usize..=3, drop in 1usize..=4) {
        let s = scale(&c);
        let n = c.degree();
        let up = c.elevate_degree(r).unwrap();
        let exact = up.reduce_degree_approx(n, EndConditions::Free).unwrap();
        prop_assert!(exact.max_deviation_bound <= 1e-11 * s, "defect: exact {:e}", exact.max_deviation_bound);
        let target = n.saturating_sub(drop).max(3);
        if target < n {
            let t = c.reduce_degree_approx(target, EndConditions::Tangents).unwrap();
            prop_assert!(t.max_deviation_sampled <= t.max_deviation_bound * (1.0 + 1e-12) + 1e-14 * s);
            let (p, q) = (c.control_points(), t.curve.control_points());
            let (nf, kf) = (n as f64, target as f64);
            for k in 0..c.dim() {
                prop_assert!((p.point(0)[k] - q.point(0)[k]).abs() <= 1e-14 * s, "start");
                prop_assert!((p.point(n)[k] - q.point(target)[k]).abs() <= 1e-14 * s, "end");
                let d0 = nf * (p.point(1)[k] - p.point(0)[k]) - kf * (q.point(1)[k] - q.point(0)[k]);
                prop_assert!(d0.abs() <= 1e-12 * s, "start tangent {:e}", d0);
            }
        }
    }
}
