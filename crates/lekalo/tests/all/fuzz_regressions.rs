//! One test per crash, hang or huge allocation ever found by the fuzz targets in `fuzz/` (or by
//! the audit that followed a fuzz finding of the same class).
//!
//! Each test names where it came from and the commit that fixed it; every one failed (panicked
//! on an integer overflow, or tried to allocate gigabytes) before the fix. Tests run in the debug
//! profile, so integer overflow panics here exactly as it does under the fuzzer.

use lekalo::basis::{basis_derivatives, basis_function_recursive, bernstein_all};
use lekalo::{
    bspline_divided_difference, BSplineCurve, BSplineSurface, BezierCurve, BezierSurface, Error,
    KnotVector, NurbsCurve, NurbsSurface, PiecewisePolynomial, Points, PpSpace, TauRule,
    MAX_DEGREE, MAX_DERIVATIVE_ORDER, MAX_SURFACE_DERIVATIVE_ORDER,
};

/// Absurd sizes the fuzzer's `Size` generator produces.
const ABSURD: [usize; 5] = [
    usize::MAX,
    usize::MAX / 2 + 1,
    1 << 40,
    1_000_000_000_000,
    1_000_000_000,
];

fn cubic() -> BSplineCurve {
    let ctrl = Points::from_2d(&[[0.0, 0.0], [1.0, 2.0], [3.0, 2.0], [4.0, 0.0], [5.0, 1.0]])
        .expect("finite points");
    BSplineCurve::from_knot_vector(
        3,
        KnotVector::clamped_uniform(3, 5).expect("valid knots"),
        ctrl,
    )
    .expect("valid curve")
}

fn assert_too_large(r: Result<Points, Error>, what: &str) {
    match r {
        Err(Error::TooLarge { what, .. }) if what.words() == "derivative order" => {}
        other => panic!("{what}: expected TooLarge(derivative order), got {other:?}"),
    }
}

// fuzz target `knots`, first run: `clamped_uniform(usize::MAX, _)` panicked with "attempt to add
// with overflow" at `n_ctrl < degree + 1`; degree 10^9 asked for 2·10^9 knots (16 GB).
#[test]
fn clamped_uniform_refuses_absurd_degrees() {
    for d in ABSURD {
        for n in [0, 5, d, d.saturating_add(1)] {
            let r = KnotVector::clamped_uniform(d, n);
            assert!(
                matches!(r, Err(Error::Degree { degree, .. }) if degree == d),
                "clamped_uniform({d}, {n}): {r:?}"
            );
        }
    }
    assert!(KnotVector::clamped_uniform(MAX_DEGREE, MAX_DEGREE + 1).is_ok());
    assert!(matches!(
        KnotVector::clamped_uniform(MAX_DEGREE + 1, MAX_DEGREE + 2),
        Err(Error::Degree { .. })
    ));
    // a huge control point count is refused as too large, not allocated
    assert!(matches!(
        KnotVector::clamped_uniform(3, usize::MAX),
        Err(Error::TooLarge { .. })
    ));
}

// audit after the clamped_uniform finding: every other knot constructor with a bare degree
#[test]
fn knot_constructors_refuse_absurd_degrees() {
    let params = [0.0, 0.25, 0.5, 1.0];
    for d in ABSURD {
        for r in [
            KnotVector::from_parameters(&params, d),
            KnotVector::averaged(&params, d),
            KnotVector::averaged_with_end_derivatives(&params, d),
        ] {
            assert!(matches!(r, Err(Error::Degree { .. })), "degree {d}: {r:?}");
        }
        let r = KnotVector::from_breakpoints(&[0.0, 1.0], &[], d);
        assert!(matches!(r, Err(Error::Degree { .. })), "order {d}: {r:?}");
        let r = PpSpace::unconstrained(&[0.0, 1.0], d);
        assert!(matches!(r, Err(Error::Degree { .. })), "order {d}: {r:?}");
    }
}

// audit: `find_span`, `SpanCursor::find`, `is_clamped` and `validate_for` computed
// `2·degree + 2` / `n_ctrl + degree + 1` and overflowed for a huge degree
#[test]
fn span_search_and_validation_survive_absurd_degrees() {
    let kv = KnotVector::clamped_uniform(2, 6).expect("valid knots");
    for d in ABSURD {
        assert!(matches!(kv.find_span(d, 0.5), Err(Error::Degree { .. })));
        assert!(matches!(
            kv.span_cursor(d).find(0.5),
            Err(Error::Degree { .. })
        ));
        assert!(!kv.is_clamped(d));
        assert!(kv.validate_for(d, 3).is_err());
        assert!(kv.validate_for(2, d).is_err());
        assert!(kv.validate_for(d, d).is_err());
        assert!(TauRule::Greville.points(&kv, d).is_err());
        let ctrl = Points::from_flat(1, vec![0.0; 6]).expect("finite points");
        assert!(BSplineCurve::new(d, kv.as_slice().to_vec(), ctrl).is_err());
    }
}

// audit: basis kernels with absurd indices, degrees and derivative orders
#[test]
fn basis_kernels_refuse_absurd_sizes() {
    let kv = KnotVector::clamped_uniform(2, 6).expect("valid knots");
    for d in ABSURD {
        assert!(matches!(
            bernstein_all(d, 0.5, &mut [0.0; 3]),
            Err(Error::LengthMismatch { .. })
        ));
        assert!(matches!(
            basis_function_recursive(&kv, d, 1, 0.5),
            Err(Error::InvalidArgument { .. })
        ));
        assert!(matches!(
            basis_function_recursive(&kv, 0, d, 0.5),
            Err(Error::InvalidArgument { .. })
        ));
        assert!(matches!(
            bspline_divided_difference(&kv, 0, d, 0.5),
            Err(Error::InvalidArgument { .. })
        ));
        assert!(matches!(
            bspline_divided_difference(&kv, d, 1, 0.5),
            Err(Error::InvalidArgument { .. })
        ));
        let r = basis_derivatives(&kv, 2, 0.5, d);
        assert!(
            matches!(r, Err(Error::TooLarge { .. })),
            "n_ders {d}: {r:?}"
        );
    }
    assert!(basis_derivatives(&kv, 2, 0.5, MAX_DERIVATIVE_ORDER).is_ok());
}

// audit: every `eval_derivatives` allocated `order + 1` rows (or `(order + 1)²` for surfaces)
// from a bare number: order 10^12 asked for terabytes, usize::MAX overflowed
#[test]
fn derivative_orders_are_bounded() {
    let c = cubic();
    let nurbs = NurbsCurve::new(
        3,
        c.knots().as_slice().to_vec(),
        c.control_points().clone(),
        vec![1.0, 2.0, 0.5, 1.0, 3.0],
    )
    .expect("valid NURBS");
    let bez = BezierCurve::new(c.control_points().clone()).expect("valid Bezier");
    let pp = PiecewisePolynomial::from_bspline(&c).expect("pp form");
    let net = Points::from_flat(3, (0..12).map(f64::from).collect()).expect("finite points");
    let surf = BSplineSurface::new(
        1,
        1,
        [0.0, 0.0, 1.0, 1.0],
        [0.0, 0.0, 1.0, 1.0],
        net.clone(),
        (2, 2),
    )
    .expect("valid surface");
    let nsurf = NurbsSurface::new(
        1,
        1,
        [0.0, 0.0, 1.0, 1.0],
        [0.0, 0.0, 1.0, 1.0],
        net.clone(),
        vec![1.0, 2.0, 3.0, 4.0],
        (2, 2),
    )
    .expect("valid NURBS surface");
    let bsurf = BezierSurface::new(net, (2, 2)).expect("valid Bezier surface");
    for k in ABSURD.into_iter().chain([MAX_DERIVATIVE_ORDER + 1]) {
        assert_too_large(c.eval_derivatives(0.5, k), "BSplineCurve");
        assert_too_large(nurbs.eval_derivatives(0.5, k), "NurbsCurve");
        assert_too_large(bez.eval_derivatives(0.5, k), "BezierCurve");
        assert_too_large(pp.eval_derivatives(0.5, k), "PiecewisePolynomial");
        assert_too_large(
            pp.eval_derivatives_left(0.5, k),
            "PiecewisePolynomial (left)",
        );
    }
    for k in ABSURD.into_iter().chain([MAX_SURFACE_DERIVATIVE_ORDER + 1]) {
        assert_too_large(surf.eval_derivatives(0.5, 0.5, k), "BSplineSurface");
        assert_too_large(nsurf.eval_derivatives(0.5, 0.5, k), "NurbsSurface");
        assert_too_large(bsurf.eval_derivatives(0.5, 0.5, k), "BezierSurface");
    }
    // the limits themselves are accepted, and orders above the degree are exact zeros
    let d = c
        .eval_derivatives(0.5, MAX_DERIVATIVE_ORDER)
        .expect("at the limit");
    assert_eq!(d.len(), MAX_DERIVATIVE_ORDER + 1);
    assert!(d.as_slice()[4 * 2..].iter().all(|&x| x == 0.0));
    assert!(nurbs.eval_derivatives(0.5, 8).is_ok());
    let s = surf
        .eval_derivatives(0.5, 0.5, MAX_SURFACE_DERIVATIVE_ORDER)
        .expect("at the limit");
    assert_eq!(s.len(), (MAX_SURFACE_DERIVATIVE_ORDER + 1).pow(2));
    assert!(nsurf
        .eval_derivatives(0.5, 0.5, MAX_SURFACE_DERIVATIVE_ORDER)
        .is_ok());
}

// fuzz target `curves`, artifact crash-ea7bfcd8: `BSplineCurve::new(usize::MAX, knots, <no
// points>)` panicked with "attempt to add with overflow" building the TooFew message
// (`min: degree + 1`).
#[test]
fn empty_control_points_with_absurd_degree() {
    let empty = Points::from_flat(2, Vec::new()).expect("empty points are valid");
    for d in ABSURD {
        let r = BSplineCurve::new(d, vec![0.0, 1.0], empty.clone());
        assert!(
            matches!(r, Err(Error::TooFew { min, got: 0, .. }) if min == d.saturating_add(1)),
            "degree {d}: {r:?}"
        );
        let r = NurbsCurve::new(d, vec![0.0, 1.0], empty.clone(), Vec::new());
        assert!(r.is_err(), "degree {d}: {r:?}");
    }
}

// fuzz target `knots`, artifact crash-aa8f007b: `averaged_with_end_derivatives` of 2 parameters
// with degree 3 (allowed: n + 3 = 4 control points) underflowed at `n + 1 − degree`.
#[test]
fn averaged_with_end_derivatives_with_the_fewest_parameters() {
    let kv = KnotVector::averaged_with_end_derivatives(&[1e8, 1.5e8], 3).expect("n + 2 = p");
    assert_eq!(
        kv.as_slice(),
        &[1e8, 1e8, 1e8, 1e8, 1.5e8, 1.5e8, 1.5e8, 1.5e8]
    );
    kv.validate_for(3, 4)
        .expect("n + 3 control points of degree 3");
    // one parameter fewer than that is refused
    assert!(matches!(
        KnotVector::averaged_with_end_derivatives(&[0.0, 1.0], 4),
        Err(Error::Degree { .. })
    ));
}

// fuzz target `ppform`, artifact crash-787b71a9: breakpoints [−f64::MAX, 1e300] were accepted,
// and `eval` returned NaN as `Ok` (the local variable x − ξ_j overflowed). The same width
// overflow made a B-spline on knots [−MAX, −MAX, MAX, MAX] evaluate to 0 instead of 0.5 (every
// basis function divided by an infinite knot difference): silently wrong.
#[test]
fn overflowing_widths_are_refused() {
    let r = PiecewisePolynomial::new(vec![-f64::MAX, 1e300], 2, 1, vec![1.0, 1.0]);
    assert!(
        matches!(r, Err(Error::InvalidArgument { what, .. }) if what.words() == "breakpoints"),
        "{r:?}"
    );
    let r = KnotVector::new(vec![-f64::MAX, -f64::MAX, f64::MAX, f64::MAX]);
    assert!(
        matches!(r, Err(Error::InvalidArgument { what, .. }) if what.words() == "knots"),
        "{r:?}"
    );
    let r = KnotVector::averaged(&[-f64::MAX, 0.0, f64::MAX], 1);
    assert!(
        matches!(r, Err(Error::InvalidArgument { what, .. }) if what.words() == "parameters"),
        "{r:?}"
    );
    let r = PpSpace::unconstrained(&[-f64::MAX, f64::MAX], 2);
    assert!(
        matches!(r, Err(Error::InvalidArgument { what, .. }) if what.words() == "breakpoints"),
        "{r:?}"
    );
    // the widest finite interval is still accepted
    assert!(KnotVector::new(vec![-f64::MAX / 2.0, f64::MAX / 2.0]).is_ok());
}

// same finding, the other route to NaN: a value that overflows inside Horner's rule
#[test]
fn overflowing_pp_values_are_reported() {
    // −1e300·u² at u = 1e200 overflows to −∞ inside Horner's rule
    let f = PiecewisePolynomial::new(vec![0.0, 1e200], 3, 1, vec![0.0, 1e300, -1e300])
        .expect("finite data");
    let r = f.eval(1e200);
    assert!(matches!(r, Err(Error::NonFinite { .. })), "{r:?}");
    assert!(f.eval(0.0).is_ok());
}

// fuzz target `knots`, artifact crash-dbf6ef33: the averaged knots of parameters near f64::MAX
// overflowed to ∞ ((1e300 + MAX) / 2), giving unsorted knots behind the debug assertion of the
// trusted constructor (in release: an infinite knot).
#[test]
fn averaged_knots_of_huge_parameters_stay_finite_and_sorted() {
    let params = [-1e-300, 1e300, f64::MAX];
    for kv in [
        KnotVector::averaged_with_end_derivatives(&params, 2),
        KnotVector::averaged(&params, 2),
        KnotVector::averaged(&[0.0, f64::MAX / 2.0, f64::MAX * 0.75, f64::MAX], 2),
    ] {
        let kv = kv.expect("finite parameters with a finite width");
        let k = kv.as_slice();
        assert!(k.iter().all(|x| x.is_finite()), "{k:?}");
        assert!(k.windows(2).all(|w| w[0] <= w[1]), "{k:?}");
    }
}

// audit after the NaN finding in the pp-form: derivatives of data near f64::MAX overflow.
// BezierCurve::eval_derivatives returned NaN as Ok, BSplineCurve::eval_derivatives ∞ as Ok, and
// BSplineCurve::derivative built a curve with infinite control points (surfaces and NURBS
// already reported NonFinite).
#[test]
fn overflowing_derivatives_are_reported() {
    let m = f64::MAX;
    let data = Points::from_flat(1, vec![m, -m, m]).expect("finite");
    let c = BSplineCurve::new(2, vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0], data.clone()).expect("valid");
    let b = BezierCurve::new(data).expect("valid");
    assert!(matches!(
        c.eval_derivatives(0.5, 2),
        Err(Error::NonFinite { .. })
    ));
    assert!(matches!(
        b.eval_derivatives(0.5, 2),
        Err(Error::NonFinite { .. })
    ));
    assert!(matches!(c.derivative(), Err(Error::NonFinite { .. })));
    let pp =
        PiecewisePolynomial::new(vec![0.0, 1e200], 3, 1, vec![0.0, 1e300, 1e300]).expect("finite");
    assert!(matches!(
        pp.eval_derivatives(1e200, 1),
        Err(Error::NonFinite { .. })
    ));
    assert!(matches!(
        pp.eval_derivatives_left(1e200, 1),
        Err(Error::NonFinite { .. })
    ));
    // the values themselves are fine: a convex combination of finite points
    assert_eq!(c.eval(0.5).expect("finite"), vec![0.0]);
    assert_eq!(b.eval(0.5).expect("finite"), vec![0.0]);
}

/// Fuzz target `degree` (crash-a86069e4…): `ElevationPlan::new(0, usize::MAX)` overflowed at
/// `r + 1` before the size check could refuse it.
#[test]
fn elevation_plan_to_absurd_degree_is_too_large() {
    for to in ABSURD.into_iter().filter(|&to| to > lekalo::MAX_SCALARS) {
        assert!(matches!(
            lekalo::ElevationPlan::new(0, to),
            Err(Error::TooLarge { .. })
        ));
    }
    assert!(matches!(
        lekalo::ElevationPlan::new(usize::MAX, usize::MAX),
        Err(Error::TooLarge { .. })
    ));
}

/// Fuzz target `interpolation` (crash-03b418a4…): finite points near `-f64::MAX` gave
/// `CubicHermite::from_points` tangents `[-0.75, -inf, NaN, inf]` inside an `Ok`.
#[test]
fn hermite_tangents_that_overflow_are_reported() {
    let p = Points::from_flat(1, vec![2.2250738585072014e-308, -0.25, -f64::MAX, -2.0])
        .expect("finite");
    for estimate in [
        lekalo::TangentEstimate::FiniteDifference,
        lekalo::TangentEstimate::CatmullRom,
        lekalo::TangentEstimate::Monotone,
    ] {
        assert!(matches!(
            lekalo::CubicHermite::from_points(
                p.as_view(),
                lekalo::Parametrization::Uniform,
                estimate
            ),
            Err(Error::NonFinite { .. })
        ));
    }
}

/// Found while writing the test above: `ElevationPlan::new(0, 10^9)` passed the size check,
/// then allocated 8 GB and looped 10^9 times. Degrees above `MAX_DEGREE` are refused.
#[test]
fn elevation_plan_above_max_degree_is_refused_at_once() {
    assert!(matches!(
        lekalo::ElevationPlan::new(0, 1_000_000_000),
        Err(Error::TooLarge { .. })
    ));
    assert!(lekalo::ElevationPlan::new(0, lekalo::MAX_DEGREE).is_ok());
}

/// Fuzz target `interpolation` (crash-b140087b…): periodic interpolation with degree
/// `usize::MAX` overflowed at `p + 1` in the degree check.
#[test]
fn periodic_interpolation_with_absurd_degree_is_refused() {
    let pts = Points::from_2d(&[[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]).expect("finite");
    let e = lekalo::CurveInterpolation::new(usize::MAX)
        .end_condition(lekalo::EndCondition::Periodic)
        .interpolate(pts.as_view());
    assert!(e.is_err(), "got {e:?}");
}

/// Fuzz target `blending` (crash-0f61523a…): a deformation of finite Bezier curves near
/// `f64::MAX` returned derivatives `[.., inf, NaN, ..]` inside an `Ok`.
#[test]
fn deformation_that_overflows_is_reported() {
    use lekalo::ParametricCurve;
    let m = f64::MAX;
    let c1 = lekalo::BezierCurve::new(Points::from_flat(1, vec![0.0, -m, 1.0]).expect("finite"))
        .expect("curve");
    let c2 = lekalo::BezierCurve::new(Points::from_flat(1, vec![0.0, m, 1.0]).expect("finite"))
        .expect("curve");
    let d = lekalo::Deformation::new(c1, c2, 2).expect("common end points");
    let mut out = [0.0; 3];
    let r = d.eval_derivatives_into(0.5, 2, &mut out);
    assert!(
        matches!(r, Err(Error::NonFinite { .. })),
        "got {r:?} {out:?}"
    );
}

/// Fuzz target `degree` (crash-af0d9c0b…): elevating a degree-0 B-spline (a step
/// function: every interior knot a discontinuity, multiplicity `p + 1`) dropped its interior
/// knots and tripped a debug assertion in the blossoming elevation. Discontinuities of higher
/// degrees (multiplicity `p + 1`) must stay discontinuities, with each side reproduced.
#[test]
fn elevating_discontinuous_bsplines_keeps_both_sides() {
    let step = BSplineCurve::new(
        0,
        vec![0.0, 0.5, 1.0],
        Points::from_flat(1, vec![-1.5, 1e300]).expect("finite"),
    )
    .expect("valid step");
    for by in [0, 1, 2] {
        let e = step.elevate_degree(by).expect("elevation");
        assert_eq!(e.degree(), by);
        for t in [0.0, 0.25, 0.4999, 0.5, 0.75, 1.0] {
            assert_eq!(
                e.eval(t).expect("in domain"),
                step.eval(t).expect("in domain"),
                "t {t}"
            );
        }
    }
    assert!(step.change_degree(0).is_ok());
    // a polyline with a jump at 1 (knot of multiplicity 2 = p + 1)
    let jump = BSplineCurve::new(
        1,
        vec![0.0, 0.0, 1.0, 1.0, 2.0, 2.0],
        Points::from_2d(&[[0.0, 0.0], [1.0, 1.0], [5.0, 5.0], [6.0, 4.0]]).expect("finite"),
    )
    .expect("valid polyline");
    let e = jump.elevate_degree(2).expect("elevation");
    assert_eq!(
        e.knots().as_slice(),
        &[0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0, 2.0, 2.0, 2.0, 2.0]
    );
    for t in [0.0, 0.3, 0.999, 1.0, 1.5, 2.0] {
        let (a, b) = (
            jump.eval(t).expect("in domain"),
            e.eval(t).expect("in domain"),
        );
        assert!(
            a.iter().zip(&b).all(|(x, y)| (x - y).abs() <= 1e-14 * 6.0),
            "t {t}: {a:?} vs {b:?}"
        );
    }
}

/// Fuzz target `interpolation` (crash-a6af776d…): 1-D data from −3e305 to `f64::MAX`
/// (uniform parameters, degree 1, averaged knots). Centring on the first point overflowed, and
/// the curve came back as `Ok` with control points `[.., 0, inf, ..]` (NaN between them).
#[test]
fn interpolation_of_data_spanning_beyond_f64_is_refused() {
    let q = Points::from_flat(1, vec![-3.0417986395407823e305, 1e8, f64::MAX, 1e300, 0.25])
        .expect("finite");
    for degree in [1, 2, 3] {
        let r = lekalo::CurveInterpolation::new(degree)
            .parametrization(lekalo::Parametrization::Uniform)
            .knot_placement(lekalo::KnotPlacement::Averaged)
            .interpolate(q.as_view());
        assert!(
            matches!(r, Err(Error::InvalidArgument { what, .. }) if what.words() == "points"),
            "degree {degree}: {r:?}"
        );
    }
}

/// Fuzz target `blending` (crash-c955576e…): a corner transition of a 1-D Bezier
/// curve whose control points start at `f64::MAX` returned `[MAX, 0, NaN, NaN]` as `Ok` for the
/// point and three derivatives (the second derivative of the curve overflows).
#[test]
fn corner_transition_that_overflows_is_reported() {
    use lekalo::ParametricCurve;
    let m = f64::MAX;
    let tiny = f64::MIN_POSITIVE;
    let before = BezierCurve::new(
        Points::from_flat(
            1,
            vec![m, m, tiny, tiny, -2.0, -2.0, -2.0, 0.9999999999999999],
        )
        .expect("finite"),
    )
    .expect("curve");
    let after = BezierCurve::new(Points::from_flat(1, vec![-2.0]).expect("finite")).expect("curve");
    let c = lekalo::CornerTransition::new(&before, tiny, &after, tiny, 5).expect("corner");
    let mut out = [0.0; 4];
    let r = c.eval_derivatives_into(c.domain().0, 3, &mut out);
    assert!(
        matches!(r, Err(Error::NonFinite { .. })),
        "got {r:?} {out:?}"
    );
}

/// Fuzz target `interpolation` (crash-7fbdc617…): chord-length parameters of
/// `[2.2e-308, -1.5, -2, f64::MAX]` are subnormal (`1.5 / f64::MAX`); the rounded Cox–de Boor
/// values put a non-zero outside the band the exact basis allows, and the collocation solve
/// indexed past its row buffer.
#[test]
fn interpolation_with_subnormal_parameter_spacing_is_an_error() {
    let q = Points::from_flat(1, vec![f64::MIN_POSITIVE, -1.5, -2.0, f64::MAX]).expect("finite");
    for placement in [
        lekalo::KnotPlacement::Averaged,
        lekalo::KnotPlacement::Uniform,
    ] {
        for degree in [1, 2] {
            let r = lekalo::CurveInterpolation::new(degree)
                .knot_placement(placement)
                .interpolate(q.as_view());
            if let Ok(c) = &r {
                // an accepted curve passes the residual check: finite and through the data
                assert!(c.control_points().as_slice().iter().all(|v| v.is_finite()));
            }
        }
    }
    let r = lekalo::CurveInterpolation::new(1)
        .knot_placement(lekalo::KnotPlacement::Averaged)
        .interpolate(q.as_view());
    assert!(r.is_err(), "{r:?}");
}

/// Fuzz target `blending` (crash-aaedb770…): a closed blend spline of circular arcs
/// with a segment of length ~1e-13 (points 1e-127 apart, centripetal parameters); its 8th
/// derivative scale `Δ^{−8}` overflowed and `inf · 0` came back as NaN inside an `Ok`.
#[test]
fn blend_spline_derivatives_that_overflow_are_reported() {
    use lekalo::{
        ArcParametrization, BlendSpline, BlendSplineOptions, CircularArcs, ParametricCurve,
        SplineParameters,
    };
    let q = Points::from_flat(
        1,
        vec![
            -2.4983353906818427e-127,
            -2.4983353906949635e-127,
            -2.4983800935480445e-127,
            1.5,
            0.9999999999999999,
            0.5,
            1e8,
        ],
    )
    .expect("finite");
    let arcs = CircularArcs {
        parametrization: ArcParametrization::UniformAngle,
    };
    let options = BlendSplineOptions {
        continuity: 8,
        closed: true,
        parameters: SplineParameters::Centripetal,
    };
    let s = BlendSpline::new(q.as_view(), &arcs, options).expect("blend spline");
    let (a, b) = s.domain();
    let mut out = vec![0.0; 9];
    let mut errors = 0;
    for t in [
        a,
        b,
        0.5 * (a + b),
        a + 0.25 * (b - a),
        b - 1e-3 * (b - a),
        0.9999999999999999,
    ] {
        for order in [0, 1, 8] {
            let n = order + 1;
            match s.eval_derivatives_into(t, order, &mut out[..n]) {
                Ok(()) => assert!(out[..n].iter().all(|v| !v.is_nan()), "t {t}: {out:?}"),
                Err(Error::NonFinite { .. }) => errors += 1,
                Err(e) => assert!(matches!(e, Error::ParameterOutOfDomain { .. }), "{e}"),
            }
        }
    }
    assert!(errors > 0, "the overflow is reported as NonFinite");
}

/// Fuzz target `interpolation` (crash-b6a8a44b…): Hermite curves through
/// `[MIN_POSITIVE, 1e300, f64::MAX]` on parameters `[−2, −1.75, f64::MAX]` (tangents as large as
/// the points): `h·D` overflows and `CubicHermite::eval` returned NaN inside an `Ok`.
#[test]
fn hermite_evaluation_that_overflows_is_reported() {
    use lekalo::{CubicHermite, Parametrization, TangentEstimate};
    let q = Points::from_flat(1, vec![f64::MIN_POSITIVE, 1e300, f64::MAX]).expect("finite");
    let params = vec![-2.0, -1.75, f64::MAX];
    let candidates = [
        CubicHermite::from_points(
            q.as_view(),
            Parametrization::Uniform,
            TangentEstimate::CatmullRom,
        ),
        CubicHermite::function(&params, q.as_view(), TangentEstimate::CatmullRom),
        CubicHermite::new(params.clone(), q.clone(), q.clone()),
    ];
    let mut overflow = 0;
    for h in candidates.into_iter().flatten() {
        let (a, b) = h.domain();
        for t in [
            a,
            b,
            0.5 * a + 0.5 * b,
            a + 0.25 * (b - a),
            b - 1e-3 * (b - a),
        ] {
            match h.eval(t) {
                Ok(p) => assert!(p.iter().all(|v| !v.is_nan()), "t {t}: {p:?}"),
                Err(Error::NonFinite { .. }) => overflow += 1,
                Err(e) => panic!("t {t}: {e}"),
            }
        }
    }
    assert!(overflow > 0, "the overflow is reported as NonFinite");
}

/// Fuzz target `interpolation` (crash-4aba54b3…): an 8 × 7 grid of 1-D values,
/// mostly `1 − ε/2`, with `f64::MAX`, −6e66 and 1e300 among them (uniform parameters, degrees
/// 7 and 3): surface interpolation returned a control net full of NaN inside an `Ok`.
#[test]
fn surface_interpolation_that_overflows_is_reported() {
    let mut values = vec![0.9999999999999999; 56];
    values[..3].copy_from_slice(&[-2.0, f64::MAX, 0.0]);
    values[18] = 1.0000000000000002;
    values[30] = -6.27743856100529e66;
    values[49..].copy_from_slice(&[0.0, 1e300, -2.0, -1.5, 1e8, 1e8, 1e8]);
    let grid = Points::from_flat(1, values).expect("finite");
    let r = lekalo::SurfaceInterpolation::new(7, 3)
        .parametrization(lekalo::Parametrization::Uniform)
        .interpolate(grid.as_view(), 8, 7);
    assert!(matches!(r, Err(Error::IllConditioned { .. })), "{r:?}");
}
