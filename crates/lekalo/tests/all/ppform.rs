//! Piecewise polynomials, Curry–Schoenberg bases and the de Boor–Fix functionals (document 003,
//! §4–5; docs/theory/pp.md): round trips on random spaces and the thesis's practical task.

use lekalo_testkit::config;

use lekalo::{
    quasi_interpolate, sample_quasi_interpolant, BSplineCurve, Error, PiecewisePolynomial, Points,
    PpSpace, TauRule, DEFAULT_CONTINUITY_RTOL,
};
use proptest::prelude::*;

const RULES: [TauRule; 5] = [
    TauRule::FirstKnotAfter,
    TauRule::LeftEndOfSupport,
    TauRule::Midpoint,
    TauRule::Greville,
    TauRule::FirstIntervalMidpoint,
];

// f(x) = x cos x and its derivatives (document 003, eq. 12).
fn xcosx(x: f64, r: usize) -> f64 {
    let (s, c) = x.sin_cos();
    match r {
        0 => x * c,
        1 => c - x * s,
        2 => -2.0 * s - x * c,
        _ => -3.0 * c + x * s,
    }
}

const THESIS_BREAKPOINTS: [f64; 7] = [0.0, 0.5, 0.9, 1.4, 2.1, 2.7, 3.0];

fn thesis_space() -> PpSpace {
    PpSpace::new(&THESIS_BREAKPOINTS, &[2; 5], 3).unwrap()
}

// Document 003 §5.3: knots, n = 8, and the maximum errors on the 61-point grid of step 0.05.
// Reference figures: an independent Python implementation (Cox–de Boor by the recursive
// definition, ψ_i expanded as a polynomial, grid j·0.05; tests/data/quasi_tau_rules.py), which
// agrees with these to 1e-15.
// Thesis's printed figure: 0.204831.
#[test]
fn thesis_practical_task() {
    let space = thesis_space();
    assert_eq!(
        space.knots().as_slice(),
        &[0.0, 0.0, 0.0, 0.5, 0.9, 1.4, 2.1, 2.7, 3.0, 3.0, 3.0]
    );
    assert_eq!(space.dimension(), 8);
    let cases = [
        // (rule, max error, where)
        (TauRule::FirstKnotAfter, 0.054_848_910_118_148_3, 0.0),
        (TauRule::LeftEndOfSupport, 0.204_831_219_164_730_35, 2.75),
        (TauRule::Midpoint, 0.026_644_954_337_416_76, 2.55),
        (TauRule::Greville, 0.012_633_072_704_255_177, 2.6),
        (
            TauRule::FirstIntervalMidpoint,
            0.031_743_745_560_113_28,
            2.75,
        ),
    ];
    for (rule, want, at) in cases {
        let s = sample_quasi_interpolant(&space, rule, xcosx, 60).unwrap();
        assert_eq!(s.t.len(), 61);
        assert_eq!((s.t[0], s.t[60]), (0.0, 3.0));
        assert!((s.t[55] - 2.75).abs() < 1e-15, "grid step 0.05");
        let err = s.max_error();
        assert!((err - want).abs() < 1e-12, "{rule:?}: {err} vs {want}");
        let j = s
            .exact
            .iter()
            .zip(&s.approx)
            .map(|(a, b)| (a - b).abs())
            .enumerate()
            .max_by(|a, b| a.1.total_cmp(&b.1))
            .unwrap()
            .0;
        assert!(
            (s.t[j] - at).abs() < 1e-12,
            "{rule:?} maximum at {}",
            s.t[j]
        );
    }
    // the printed figure, to its 6 decimals
    let s = sample_quasi_interpolant(&space, TauRule::LeftEndOfSupport, xcosx, 60).unwrap();
    assert_eq!(format!("{:.6}", s.max_error()), "0.204831");
}

// The coefficients of the stated rule (τ = 0.5, 0.5, 0.5, 0.9, 1.4, 2.1, 2.7, 3), from the
// k = 3 formula of docs/theory/pp.md#de-boor-fix-functionals: c_i = f(τ) + ((x_{i+1}+x_{i+2})/2 −
// τ) f'(τ) + (x_{i+1} − τ)(x_{i+2} − τ)/2 · f''(τ).
#[test]
fn thesis_coefficients_closed_form() {
    let space = thesis_space();
    let x = space.knots().as_slice();
    let tau = TauRule::FirstKnotAfter.points(space.knots(), 3).unwrap();
    assert_eq!(tau, vec![0.5, 0.5, 0.5, 0.9, 1.4, 2.1, 2.7, 3.0]);
    let q = quasi_interpolate(&space, TauRule::FirstKnotAfter, xcosx).unwrap();
    for (i, (&c, &t)) in q.control_points().as_slice().iter().zip(&tau).enumerate() {
        let (a, b) = (x[i + 1], x[i + 2]);
        let want =
            xcosx(t, 0) + ((a + b) / 2.0 - t) * xcosx(t, 1) + (a - t) * (b - t) / 2.0 * xcosx(t, 2);
        assert!((c - want).abs() < 1e-14, "c_{i}: {c} vs {want}");
    }
}

// Quasi-interpolation reproduces polynomials of order k (they lie in every P_{k,ξ,ν}).
#[test]
fn quasi_interpolation_reproduces_polynomials() {
    for k in 1..=5 {
        let space = PpSpace::new(&[0.0, 0.3, 1.0, 1.2, 2.0], &[k - 1; 3], k).unwrap();
        // p(x) = Σ_s (s+1)(−0.7)^s x^s, degree k − 1
        let coef: Vec<f64> = (0..k)
            .map(|s| (s + 1) as f64 * (-0.7f64).powi(i32::try_from(s).unwrap()))
            .collect();
        let p = |x: f64, r: usize| -> f64 {
            (r..k)
                .map(|s| {
                    coef[s]
                        * (s - r + 1..=s).map(|v| v as f64).product::<f64>()
                        * x.powi(i32::try_from(s - r).unwrap())
                })
                .sum()
        };
        for rule in RULES {
            let q = quasi_interpolate(&space, rule, p).unwrap();
            for j in 0..=40 {
                let t = 0.05 * j as f64;
                let got = q.eval(t).unwrap()[0];
                assert!((got - p(t, 0)).abs() < 1e-12, "k={k} {rule:?} t={t}");
            }
        }
    }
}

// A random space: order k, breakpoints with gaps in [0.2, 1.5], ν_i < k, dimension 1..=3.
fn space_strategy() -> impl Strategy<Value = (PpSpace, usize)> {
    (1usize..=5, 1usize..=5, 1usize..=3)
        .prop_flat_map(|(k, l, dim)| {
            (
                Just(k),
                prop::collection::vec(0.2f64..1.5, l),
                prop::collection::vec(0..k, l - 1),
                Just(dim),
                -1.0f64..1.0,
            )
        })
        .prop_map(|(k, gaps, nu, dim, start)| {
            let mut xi = vec![start];
            for g in gaps {
                let last = xi[xi.len() - 1];
                xi.push(last + g);
            }
            (PpSpace::new(&xi, &nu, k).unwrap(), dim)
        })
}

fn rel_close(a: &[f64], b: &[f64], rtol: f64) -> bool {
    let scale = a.iter().chain(b).fold(1e-300f64, |m, v| m.max(v.abs()));
    a.iter().zip(b).all(|(x, y)| (x - y).abs() <= rtol * scale) && a.len() == b.len()
}

proptest! {
    #![proptest_config(config(64))]

    // Curry–Schoenberg (Theorem 4.5): n = dim P_{k,ξ,ν} B-splines; B-spline → pp → B-spline is
    // the identity for every τ rule (de Boor–Fix, λ_i b_j = δ_ij), and the pp is in the space.
    #[test]
    fn bspline_pp_bspline_identity(
        (space, dim) in space_strategy(),
        seed in prop::collection::vec(-1.0f64..1.0, 200),
        rule_index in 0usize..4,
    ) {
        let k = space.order();
        let n = space.knots().len() - k;
        prop_assert_eq!(n, space.dimension());
        let coef: Vec<f64> = seed.iter().cycle().take(n * dim).copied().collect();
        let b = BSplineCurve::from_knot_vector(k - 1, space.knots().clone(), Points::from_flat(dim, coef.clone()).unwrap()).unwrap();
        let pp = PiecewisePolynomial::from_bspline(&b).unwrap();
        prop_assert_eq!(pp.breakpoints(), space.breakpoints());
        prop_assert!(space.contains(&pp, DEFAULT_CONTINUITY_RTOL));
        // the jumps of lower derivatives vanish (eq. 9)
        for (m, &nu) in space.continuity().iter().enumerate() {
            for j in 0..nu {
                let jump = pp.jump(m + 1, j).unwrap();
                prop_assert!(jump.iter().all(|v| v.abs() < 1e-9), "jump D^{} at {}: {:?}", j, m + 1, jump);
            }
        }
        let back = pp.to_bspline(&space, RULES[rule_index]).unwrap();
        prop_assert!(rel_close(back.control_points().as_slice(), &coef, 1e-12),
            "{:?}: {:?} vs {:?}", RULES[rule_index], back.control_points().as_slice(), coef);
    }

    // pp → B-spline → pp is the identity, for a random element of P_{k,ξ,ν} built from the
    // truncated-power basis (Theorem 4.3), independent of B-splines; the B-spline agrees with the
    // pp everywhere.
    #[test]
    fn pp_bspline_pp_identity(
        (space, dim) in space_strategy(),
        seed in prop::collection::vec(-1.0f64..1.0, 200),
        rule_index in 0usize..4,
    ) {
        let k = space.order();
        let basis = space.truncated_power_basis();
        prop_assert_eq!(basis.len(), space.dimension());
        let l = space.breakpoints().len() - 1;
        let mut c = vec![0.0; l * k * dim];
        for (m, phi) in basis.iter().enumerate() {
            for (idx, &v) in phi.coefficients().iter().enumerate() {
                for d in 0..dim {
                    c[idx * dim + d] += v * seed[(m * dim + d) % seed.len()];
                }
            }
        }
        let f = PiecewisePolynomial::new(space.breakpoints().to_vec(), k, dim, c).unwrap();
        let b = f.to_bspline(&space, RULES[rule_index]).unwrap();
        let (a, z) = f.domain();
        // values on a grid, compared relative to the largest value (the data's scale)
        let (mut got, mut want) = (Vec::new(), Vec::new());
        let mut point = vec![0.0; dim];
        for j in 0..=50 {
            let t = if j == 50 { z } else { a + (z - a) * j as f64 / 50.0 };
            b.eval_into(t, &mut point).unwrap();
            got.extend_from_slice(&point);
            want.extend(f.eval(t).unwrap());
        }
        prop_assert!(rel_close(&got, &want, 1e-11), "{:?} vs {:?}", got, want);
        let g = PiecewisePolynomial::from_bspline(&b).unwrap();
        prop_assert_eq!(g.breakpoints(), f.breakpoints());
        // coefficient c_{j,r} of (x − ξ_j)^r contributes c_{j,r} h_j^r on a piece of width h_j:
        // compare on that scale (derivatives of order r amplify rounding by h^{−r})
        let scaled = |p: &PiecewisePolynomial| -> Vec<f64> {
            let xi = p.breakpoints();
            p.coefficients().iter().enumerate().map(|(idx, c)| {
                let (piece, r) = (idx / (k * dim), (idx / dim) % k);
                c * (xi[piece + 1] - xi[piece]).powi(i32::try_from(r).unwrap())
            }).collect()
        };
        prop_assert!(rel_close(&scaled(&g), &scaled(&f), 1e-12),
            "{:?} vs {:?}", g.coefficients(), f.coefficients());
    }
}

// Lemma 3.9: at a knot of multiplicity m the B-spline of order k is C^{k−1−m}, and its
// derivative of order k − m jumps.
#[test]
fn smoothness_follows_multiplicity() {
    // order 4, breakpoint 1 with ν = 1 (multiplicity 3), breakpoint 2 with ν = 3 (simple)
    let space = PpSpace::new(&[0.0, 1.0, 2.0, 3.0], &[1, 3], 4).unwrap();
    let n = space.dimension();
    assert_eq!(n, 4 + 3 + 1);
    // b_3 (0-based) has knots 0 1 1 1 2: multiplicity 3 at 1, simple at 2
    let mut unit = vec![0.0; n];
    unit[3] = 1.0;
    let b = BSplineCurve::from_knot_vector(
        3,
        space.knots().clone(),
        Points::from_flat(1, unit).unwrap(),
    )
    .unwrap();
    let pp = PiecewisePolynomial::from_bspline(&b).unwrap();
    assert!(
        pp.jump(1, 0).unwrap()[0].abs() < 1e-14,
        "C⁰ at the triple knot"
    );
    assert!(
        pp.jump(1, 1).unwrap()[0].abs() > 0.1,
        "C¹ fails at the triple knot"
    );
    for j in 0..3 {
        assert!(
            pp.jump(2, j).unwrap()[0].abs() < 1e-13,
            "C² at the simple knot"
        );
    }
    assert!(
        pp.jump(2, 3).unwrap()[0].abs() > 0.1,
        "third derivative jumps"
    );
}

#[test]
fn space_errors() {
    assert!(matches!(
        PpSpace::new(&[0.0, 1.0, 2.0], &[4], 3),
        Err(Error::InvalidArgument { .. })
    ));
    assert!(matches!(
        PpSpace::new(&[0.0, 1.0, 2.0], &[1, 1], 3),
        Err(Error::LengthMismatch { .. })
    ));
    assert!(matches!(
        PpSpace::new(&[0.0], &[], 3),
        Err(Error::TooFew { .. })
    ));
    // a pp on other breakpoints is not in the space
    let f = PiecewisePolynomial::new(vec![0.0, 3.0], 3, 1, vec![1.0, 0.0, 0.0]).unwrap();
    assert!(!thesis_space().contains(&f, DEFAULT_CONTINUITY_RTOL));
    assert!(matches!(
        f.to_bspline(&thesis_space(), TauRule::Midpoint),
        Err(Error::InvalidArgument { .. })
    ));
}
