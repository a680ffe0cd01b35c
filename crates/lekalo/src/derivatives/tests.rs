//! Tests of the derivative kernels: primal values bit for bit against `eval_batch` (every
//! degree and dimension, so also the fixed-size kernels), JVPs against central finite
//! differences (relative 1e-7) for B-spline curves, NURBS curves (also in the weights) and
//! surfaces, VJPs as the exact transposes of the JVPs, the linearisation
//! against the JVP, and a negative test for every error.

use proptest::prelude::*;

use crate::curve::bspline::BSplineCurve;
use crate::curve::NurbsCurve;
use crate::error::Error;
use crate::oracle::proptest_config;
use crate::points::Points;
use crate::surface::bspline::BSplineSurface;

/// Relative tolerance of the finite-difference comparisons.
pub(super) const FD_RTOL: f64 = 1e-7;

/// Step of the central differences in the parameter (knot gaps are at least 0.2, parameters at
/// least 0.02 from a knot, so both points of a difference lie in one polynomial piece).
pub(super) const FD_STEP: f64 = 1e-6;

pub(super) fn max_abs(v: &[f64]) -> f64 {
    v.iter().fold(0.0, |m, x| m.max(x.abs()))
}

/// `‖a − b‖_∞ ≤ rtol · max(‖b‖_∞, floor)`.
pub(super) fn assert_rel(a: &[f64], b: &[f64], rtol: f64, floor: f64, what: &str) {
    assert_eq!(a.len(), b.len(), "{what}: lengths");
    let err = a
        .iter()
        .zip(b)
        .fold(0.0, |m: f64, (x, y)| m.max((x - y).abs()));
    let scale = max_abs(b).max(floor);
    assert!(
        err <= rtol * scale,
        "{what}: error {err:e} above {rtol:e} × {scale:e}\n{a:?}\n{b:?}"
    );
}

pub(super) fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// A knot vector of `n + p + 1` knots from gaps in `[0.2, 1]` (clamped: `p + 1` equal knots at
/// each end), and parameters in the domain at least 2 % of a span from every knot.
fn knots_and_params(
    p: usize,
    n: usize,
    clamped: bool,
    gaps: &[f64],
    xs: &[(usize, f64)],
) -> (Vec<f64>, Vec<f64>) {
    let len = n + p + 1;
    let mut knots = Vec::with_capacity(len);
    let mut t = 0.0;
    if clamped {
        knots.extend(std::iter::repeat_n(0.0, p + 1));
        for g in &gaps[..n - p] {
            t += g;
            knots.push(t);
        }
        knots.extend(std::iter::repeat_n(t, p));
    } else {
        knots.push(0.0);
        for g in &gaps[..len - 1] {
            t += g;
            knots.push(t);
        }
    }
    let spans = n - p; // non-empty spans p..n of the domain
    let ts = xs
        .iter()
        .map(|&(j, x)| {
            let s = p + j % spans;
            knots[s] + (0.02 + 0.96 * x) * (knots[s + 1] - knots[s])
        })
        .collect();
    (knots, ts)
}

/// A curve, parameters, a control-point tangent, a parameter tangent and a cotangent.
type CurveCase = (BSplineCurve, Vec<f64>, Vec<f64>, Vec<f64>, Vec<f64>);

/// A B-spline curve of degree 0..=5, dimension 1..=4, 1 to 7 more control points than the
/// order, clamped or not, with parameters off its knots and tangents and cotangents.
fn curve_case() -> impl Strategy<Value = CurveCase> {
    (0usize..=5, 0usize..7, 1usize..=4, any::<bool>(), 1usize..12).prop_flat_map(
        |(p, extra, dim, clamped, m)| {
            let n = p + 1 + extra;
            (
                prop::collection::vec(0.2f64..1.0, 2 * p + 9),
                prop::collection::vec(-1.0f64..1.0, n * dim),
                prop::collection::vec(-1.0f64..1.0, n * dim),
                prop::collection::vec((0usize..64, 0.0f64..1.0), m),
                prop::collection::vec(-1.0f64..1.0, m),
                prop::collection::vec(-1.0f64..1.0, m * dim),
            )
                .prop_map(move |(gaps, ctrl, dctrl, xs, dt, g)| {
                    let (knots, ts) = knots_and_params(p, n, clamped, &gaps, &xs);
                    let curve = BSplineCurve::new(p, knots, Points::from_raw(ctrl, dim)).unwrap();
                    (curve, ts, dctrl, dt, g)
                })
        },
    )
}

fn eval(c: &BSplineCurve, ts: &[f64]) -> Vec<f64> {
    let mut out = vec![0.0; ts.len() * c.dim()];
    c.eval_batch(ts, &mut out).unwrap();
    out
}

fn with_control(c: &BSplineCurve, ctrl: Vec<f64>) -> BSplineCurve {
    BSplineCurve::new(
        c.degree(),
        c.knots().as_slice().to_vec(),
        Points::from_raw(ctrl, c.dim()),
    )
    .unwrap()
}

fn curve_jvp(
    c: &BSplineCurve,
    ts: &[f64],
    dp: Option<&[f64]>,
    dt: Option<&[f64]>,
) -> (Vec<f64>, Vec<f64>) {
    let mut out = vec![0.0; ts.len() * c.dim()];
    let mut tan = vec![0.0; ts.len() * c.dim()];
    c.eval_batch_jvp(ts, dp, dt, &mut out, &mut tan).unwrap();
    (out, tan)
}

proptest! {
    #![proptest_config(proptest_config(256))]

    #[test]
    fn curve_primal_is_eval_batch_bit_for_bit((c, ts, dp, dt, _g) in curve_case()) {
        let plain = eval(&c, &ts);
        let (out, _) = curve_jvp(&c, &ts, Some(&dp), Some(&dt));
        prop_assert_eq!(&out, &plain);
        prop_assert_eq!(&c.eval_batch_linearize(&ts).unwrap().values, &plain);
    }

    #[test]
    fn curve_jvp_matches_central_differences((c, ts, dp, dt, _g) in curve_case()) {
        let ctrl = c.control_points().as_slice();
        let floor = max_abs(ctrl);
        // control points: the curve is linear in them, the difference is exact up to rounding
        let h = 1e-3;
        let shifted = |s: f64| ctrl.iter().zip(&dp).map(|(x, d)| x + s * h * d).collect::<Vec<_>>();
        let (plus, minus) = (eval(&with_control(&c, shifted(1.0)), &ts), eval(&with_control(&c, shifted(-1.0)), &ts));
        let fd: Vec<f64> = plus.iter().zip(&minus).map(|(a, b)| (a - b) / (2.0 * h)).collect();
        let (_, tan) = curve_jvp(&c, &ts, Some(&dp), None);
        assert_rel(&tan, &fd, FD_RTOL, floor, "JVP in the control points");
        // parameters
        let moved = |s: f64| ts.iter().zip(&dt).map(|(t, d)| t + s * FD_STEP * d).collect::<Vec<_>>();
        let (plus, minus) = (eval(&c, &moved(1.0)), eval(&c, &moved(-1.0)));
        let fd: Vec<f64> = plus.iter().zip(&minus).map(|(a, b)| (a - b) / (2.0 * FD_STEP)).collect();
        let (_, tan) = curve_jvp(&c, &ts, None, Some(&dt));
        assert_rel(&tan, &fd, FD_RTOL, floor, "JVP in the parameters");
        // both at once: the sum
        let (_, both) = curve_jvp(&c, &ts, Some(&dp), Some(&dt));
        let (_, a) = curve_jvp(&c, &ts, Some(&dp), None);
        let sum: Vec<f64> = a.iter().zip(&tan).map(|(x, y)| x + y).collect();
        assert_rel(&both, &sum, 1e-14, floor, "JVP in both");
    }

    #[test]
    fn curve_vjp_is_the_transpose_of_the_jvp((c, ts, dp, dt, g) in curve_case()) {
        let (_, tan) = curve_jvp(&c, &ts, Some(&dp), Some(&dt));
        let mut gp = vec![0.0; dp.len()];
        let mut gt = vec![0.0; ts.len()];
        c.eval_batch_vjp(&ts, &g, Some(&mut gp), Some(&mut gt)).unwrap();
        let lhs = dot(&g, &tan);
        let rhs = dot(&gp, &dp) + dot(&gt, &dt);
        let scale = max_abs(&g) * (max_abs(&tan) + 1.0) * g.len() as f64;
        prop_assert!((lhs - rhs).abs() <= 1e-13 * scale, "<g, J x> = {lhs}, <J^T g, x> = {rhs}");
        // each output alone
        // (with at least as many parameters as control points, the control cotangent alone
        // takes the division-free path: the same sums to rounding)
        let mut gp1 = vec![0.0; dp.len()];
        c.eval_batch_vjp(&ts, &g, Some(&mut gp1), None).unwrap();
        assert_rel(&gp1, &gp, 1e-13, max_abs(&g), "control cotangent alone");
        let mut gt1 = vec![0.0; ts.len()];
        c.eval_batch_vjp(&ts, &g, None, Some(&mut gt1)).unwrap();
        prop_assert_eq!(&gt1, &gt);
    }

    /// The division-free paths of the control cotangent (many parameters, no parameter
    /// cotangent: power sums up to degree 3, reciprocals above) against the general one, on
    /// the parameters repeated to outnumber the control points, in every degree and dimension
    /// of the cases (so each monomorphised order and dimension and the generic kernels).
    #[test]
    fn curve_control_cotangent_by_reciprocals_matches_the_general_path(
        (c, ts, _dp, _dt, g) in curve_case()
    ) {
        let n = c.control_points().len();
        let reps = n.div_ceil(ts.len());
        let (ts, g) = (ts.repeat(reps), g.repeat(reps));
        prop_assert!(ts.len() >= n, "the fast path needs m >= n");
        let (mut fast, mut general) = (vec![0.0; n * c.dim()], vec![0.0; n * c.dim()]);
        c.eval_batch_vjp(&ts, &g, Some(&mut fast), None).unwrap();
        c.eval_batch_vjp(&ts, &g, Some(&mut general), Some(&mut vec![0.0; ts.len()])).unwrap();
        assert_rel(&fast, &general, 1e-13, max_abs(&g), "control cotangent by reciprocals");
    }

    #[test]
    fn curve_linearization_applies_as_the_jvp((c, ts, dp, dt, _g) in curve_case()) {
        let lin = c.eval_batch_linearize(&ts).unwrap();
        let (dim, w) = (c.dim(), c.degree() + 1);
        let (_, tan) = curve_jvp(&c, &ts, Some(&dp), Some(&dt));
        let mut applied = vec![0.0; tan.len()];
        for i in 0..ts.len() {
            for k in 0..w {
                for d in 0..dim {
                    applied[i * dim + d] += lin.basis[i * w + k] * dp[(lin.first[i] + k) * dim + d];
                }
            }
            for d in 0..dim {
                applied[i * dim + d] += lin.derivatives[i * dim + d] * dt[i];
            }
        }
        assert_rel(&applied, &tan, 1e-14, max_abs(&tan).max(1.0), "linearisation");
    }
}

/// A surface, pairs, a net tangent, pair tangents and a cotangent.
pub(super) type SurfaceCase = (
    BSplineSurface,
    Vec<[f64; 2]>,
    Vec<f64>,
    Vec<[f64; 2]>,
    Vec<f64>,
);

/// A B-spline surface of degrees 0..=4 × 0..=4, dimension 1..=3, with pairs off its knots.
pub(super) fn surface_case() -> impl Strategy<Value = SurfaceCase> {
    (
        (0usize..=4, 0usize..=4, 0usize..4, 0usize..4),
        1usize..=3,
        any::<bool>(),
        1usize..8,
    )
        .prop_flat_map(|((p, q, eu, ev), dim, clamped, m)| {
            let (nu, nv) = (p + 1 + eu, q + 1 + ev);
            (
                (
                    prop::collection::vec(0.2f64..1.0, 2 * p + 6),
                    prop::collection::vec(0.2f64..1.0, 2 * q + 6),
                ),
                prop::collection::vec(-1.0f64..1.0, nu * nv * dim),
                prop::collection::vec(-1.0f64..1.0, nu * nv * dim),
                prop::collection::vec(((0usize..64, 0.0f64..1.0), (0usize..64, 0.0f64..1.0)), m),
                prop::collection::vec(prop::array::uniform2(-1.0f64..1.0), m),
                prop::collection::vec(-1.0f64..1.0, m * dim),
            )
                .prop_map(move |((gu, gv), ctrl, dctrl, xs, duv, g)| {
                    let (xu, xv): (Vec<_>, Vec<_>) = xs.into_iter().unzip();
                    let (ku, us) = knots_and_params(p, nu, clamped, &gu, &xu);
                    let (kv, vs) = knots_and_params(q, nv, clamped, &gv, &xv);
                    let net = Points::from_raw(ctrl, dim);
                    let s = BSplineSurface::new(p, q, ku, kv, net, (nu, nv)).unwrap();
                    let uv = us.into_iter().zip(vs).map(|(u, v)| [u, v]).collect();
                    (s, uv, dctrl, duv, g)
                })
        })
}

fn eval_s(s: &BSplineSurface, uv: &[[f64; 2]]) -> Vec<f64> {
    let mut out = vec![0.0; uv.len() * s.dim()];
    s.eval_batch(uv, &mut out).unwrap();
    out
}

fn surface_jvp(
    s: &BSplineSurface,
    uv: &[[f64; 2]],
    dp: Option<&[f64]>,
    duv: Option<&[[f64; 2]]>,
) -> (Vec<f64>, Vec<f64>) {
    let mut out = vec![0.0; uv.len() * s.dim()];
    let mut tan = vec![0.0; uv.len() * s.dim()];
    s.eval_batch_jvp(uv, dp, duv, &mut out, &mut tan).unwrap();
    (out, tan)
}

proptest! {
    #![proptest_config(proptest_config(128))]

    #[test]
    fn surface_primal_is_eval_batch_bit_for_bit((s, uv, dp, duv, _g) in surface_case()) {
        let plain = eval_s(&s, &uv);
        let (out, _) = surface_jvp(&s, &uv, Some(&dp), Some(&duv));
        prop_assert_eq!(&out, &plain);
        prop_assert_eq!(&s.eval_batch_linearize(&uv).unwrap().values, &plain);
    }

    #[test]
    fn surface_jvp_matches_central_differences((s, uv, dp, duv, _g) in surface_case()) {
        let ctrl = s.control_points().as_slice();
        let floor = max_abs(ctrl);
        let ((p, q), (ku, kv)) = (s.degree(), s.knots());
        let rebuilt = |c: Vec<f64>| BSplineSurface::new(p, q, ku.as_slice().to_vec(), kv.as_slice().to_vec(),
            Points::from_raw(c, s.dim()), s.net_size()).unwrap();
        let h = 1e-3;
        let shifted = |k: f64| ctrl.iter().zip(&dp).map(|(x, d)| x + k * h * d).collect::<Vec<_>>();
        let (plus, minus) = (eval_s(&rebuilt(shifted(1.0)), &uv), eval_s(&rebuilt(shifted(-1.0)), &uv));
        let fd: Vec<f64> = plus.iter().zip(&minus).map(|(a, b)| (a - b) / (2.0 * h)).collect();
        let (_, tan) = surface_jvp(&s, &uv, Some(&dp), None);
        assert_rel(&tan, &fd, FD_RTOL, floor, "JVP in the control net");
        let moved = |k: f64| uv.iter().zip(&duv)
            .map(|(a, d)| [a[0] + k * FD_STEP * d[0], a[1] + k * FD_STEP * d[1]]).collect::<Vec<_>>();
        let (plus, minus) = (eval_s(&s, &moved(1.0)), eval_s(&s, &moved(-1.0)));
        let fd: Vec<f64> = plus.iter().zip(&minus).map(|(a, b)| (a - b) / (2.0 * FD_STEP)).collect();
        let (_, tan) = surface_jvp(&s, &uv, None, Some(&duv));
        assert_rel(&tan, &fd, FD_RTOL, floor, "JVP in (u, v)");
    }

    #[test]
    fn surface_vjp_is_the_transpose_of_the_jvp((s, uv, dp, duv, g) in surface_case()) {
        let (_, tan) = surface_jvp(&s, &uv, Some(&dp), Some(&duv));
        let mut gp = vec![0.0; dp.len()];
        let mut guv = vec![[0.0; 2]; uv.len()];
        s.eval_batch_vjp(&uv, &g, Some(&mut gp), Some(&mut guv)).unwrap();
        let lhs = dot(&g, &tan);
        let rhs = dot(&gp, &dp) + dot(guv.as_flattened(), duv.as_flattened());
        let scale = max_abs(&g) * (max_abs(&tan) + 1.0) * g.len() as f64;
        prop_assert!((lhs - rhs).abs() <= 1e-13 * scale, "<g, J x> = {lhs}, <J^T g, x> = {rhs}");
    }

    #[test]
    fn surface_linearization_applies_as_the_jvp((s, uv, dp, duv, _g) in surface_case()) {
        let lin = s.eval_batch_linearize(&uv).unwrap();
        let ((p, q), dim, nv) = (s.degree(), s.dim(), s.net_size().1);
        let (_, tan) = surface_jvp(&s, &uv, Some(&dp), Some(&duv));
        let mut applied = vec![0.0; tan.len()];
        for i in 0..uv.len() {
            for k in 0..=p {
                for l in 0..=q {
                    let w = lin.basis_u[i * (p + 1) + k] * lin.basis_v[i * (q + 1) + l];
                    let cell = ((lin.first_u[i] + k) * nv + lin.first_v[i] + l) * dim;
                    for d in 0..dim {
                        applied[i * dim + d] += w * dp[cell + d];
                    }
                }
            }
            for d in 0..dim {
                applied[i * dim + d] += lin.derivatives_u[i * dim + d] * duv[i][0]
                    + lin.derivatives_v[i * dim + d] * duv[i][1];
            }
        }
        assert_rel(&applied, &tan, 1e-13, max_abs(&tan).max(1.0), "linearisation");
    }
}

fn cubic() -> BSplineCurve {
    let ctrl = Points::from_2d(&[[0.0, 0.0], [1.0, 2.0], [3.0, 2.0], [4.0, 0.0]]).unwrap();
    BSplineCurve::new(3, vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0], ctrl).unwrap()
}

fn bilinear() -> BSplineSurface {
    let net = Points::from_raw(vec![0.0, 1.0, 2.0, 3.0], 1);
    BSplineSurface::new(
        1,
        1,
        vec![0.0, 0.0, 1.0, 1.0],
        vec![0.0, 0.0, 1.0, 1.0],
        net,
        (2, 2),
    )
    .unwrap()
}

#[test]
fn curve_errors_name_the_argument() {
    let c = cubic();
    let (mut out, mut tan) = (vec![0.0; 4], vec![0.0; 4]);
    let e = c
        .eval_batch_jvp(&[0.5, 0.6], Some(&[0.0; 7]), None, &mut out, &mut tan)
        .unwrap_err();
    assert!(
        matches!(
            e,
            Error::LengthMismatch {
                expected: 8,
                got: 7,
                ..
            }
        ),
        "{e:?}"
    );
    let e = c
        .eval_batch_jvp(&[0.5, 0.6], None, Some(&[0.0]), &mut out, &mut tan)
        .unwrap_err();
    assert!(
        matches!(
            e,
            Error::LengthMismatch {
                expected: 2,
                got: 1,
                ..
            }
        ),
        "{e:?}"
    );
    let e = c
        .eval_batch_jvp(&[0.5, 0.6], None, None, &mut out, &mut tan[..3])
        .unwrap_err();
    assert!(
        matches!(
            e,
            Error::LengthMismatch {
                expected: 4,
                got: 3,
                ..
            }
        ),
        "{e:?}"
    );
    let e = c
        .eval_batch_jvp(
            &[0.5, 0.6],
            None,
            Some(&[0.0, f64::NAN]),
            &mut out,
            &mut tan,
        )
        .unwrap_err();
    assert!(matches!(e, Error::NonFinite { index: 1, .. }), "{e:?}");
    let e = c
        .eval_batch_jvp(&[0.5, 1.5], None, None, &mut out, &mut tan)
        .unwrap_err();
    assert!(matches!(e, Error::ParameterOutOfDomain { .. }), "{e:?}");
    let mut gp = vec![0.0; 8];
    let e = c
        .eval_batch_vjp(&[0.5], &[1.0, f64::INFINITY], Some(&mut gp), None)
        .unwrap_err();
    assert!(matches!(e, Error::NonFinite { .. }), "{e:?}");
    let e = c
        .eval_batch_vjp(&[0.5], &[1.0], Some(&mut gp), None)
        .unwrap_err();
    assert!(
        matches!(
            e,
            Error::LengthMismatch {
                expected: 2,
                got: 1,
                ..
            }
        ),
        "{e:?}"
    );
    let e = c
        .eval_batch_vjp(&[0.5], &[1.0, 1.0], Some(&mut gp[..6]), None)
        .unwrap_err();
    assert!(
        matches!(
            e,
            Error::LengthMismatch {
                expected: 8,
                got: 6,
                ..
            }
        ),
        "{e:?}"
    );
    let e = c
        .eval_batch_vjp(&[0.5], &[1.0, 1.0], None, Some(&mut [0.0; 2]))
        .unwrap_err();
    assert!(
        matches!(
            e,
            Error::LengthMismatch {
                expected: 1,
                got: 2,
                ..
            }
        ),
        "{e:?}"
    );
    let e = c
        .eval_batch_vjp(&[f64::NAN], &[1.0, 1.0], Some(&mut gp), None)
        .unwrap_err();
    assert!(matches!(e, Error::ParameterOutOfDomain { .. }), "{e:?}");
    // the division-free path (as many parameters as control points) checks the domain too
    let many = vec![0.5; gp.len()];
    let mut bad = many.clone();
    bad[1] = 1.5;
    let ones = vec![1.0; many.len() * 2];
    c.eval_batch_vjp(&many, &ones, Some(&mut gp), None).unwrap();
    let e = c
        .eval_batch_vjp(&bad, &ones, Some(&mut gp), None)
        .unwrap_err();
    assert!(
        matches!(e, Error::ParameterOutOfDomain { t, .. } if t == 1.5),
        "{e:?}"
    );
    let e = c.eval_batch_linearize(&[-0.1]).unwrap_err();
    assert!(matches!(e, Error::ParameterOutOfDomain { .. }), "{e:?}");
}

/// The division-free control cotangent (at least as many parameters as control points) reads
/// the cotangent's finiteness from its sums instead of checking it first: a non-finite
/// cotangent is still refused with its index, also before a parameter outside the domain, in
/// the power-sum kernel (degree 3) and the reciprocal one (degree 5), while finite numbers
/// whose sums overflow are no error.
#[test]
fn curve_large_batch_control_cotangent_checks_the_cotangent() {
    for p in [3, 5] {
        let n = 2 * p + 2;
        let ctrl = Points::from_flat(2, (0..2 * n).map(|i| i as f64).collect()).unwrap();
        let knots = crate::knots::KnotVector::clamped_uniform(p, n).unwrap();
        let c = BSplineCurve::from_knot_vector(p, knots, ctrl).unwrap();
        let ts: Vec<f64> = (0..3 * n).map(|i| i as f64 / (3 * n - 1) as f64).collect();
        let mut gp = vec![0.0; 2 * n];
        for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            let mut g = vec![1.0; 2 * ts.len()];
            g[7] = bad;
            let e = c.eval_batch_vjp(&ts, &g, Some(&mut gp), None).unwrap_err();
            assert!(
                matches!(e, Error::NonFinite { index: 7, .. }),
                "degree {p}: {e:?}"
            );
            let mut outside = ts.clone();
            outside[0] = 2.0;
            let e = c
                .eval_batch_vjp(&outside, &g, Some(&mut gp), None)
                .unwrap_err();
            assert!(
                matches!(e, Error::NonFinite { index: 7, .. }),
                "degree {p}: {e:?}"
            );
        }
        let huge = vec![f64::MAX; 2 * ts.len()];
        c.eval_batch_vjp(&ts, &huge, Some(&mut gp), None).unwrap();
        assert!(gp.iter().any(|v| !v.is_finite()), "degree {p}: overflowed");
    }
}

#[test]
fn surface_errors_name_the_argument() {
    let s = bilinear();
    let (mut out, mut tan) = (vec![0.0; 1], vec![0.0; 1]);
    let uv = [[0.5, 0.5]];
    let e = s
        .eval_batch_jvp(&uv, Some(&[0.0; 3]), None, &mut out, &mut tan)
        .unwrap_err();
    assert!(
        matches!(
            e,
            Error::LengthMismatch {
                expected: 4,
                got: 3,
                ..
            }
        ),
        "{e:?}"
    );
    let e = s
        .eval_batch_jvp(&uv, None, Some(&[[0.0, f64::NAN]]), &mut out, &mut tan)
        .unwrap_err();
    assert!(matches!(e, Error::NonFinite { .. }), "{e:?}");
    let e = s
        .eval_batch_jvp(&uv, None, None, &mut [], &mut tan)
        .unwrap_err();
    assert!(
        matches!(
            e,
            Error::LengthMismatch {
                expected: 1,
                got: 0,
                ..
            }
        ),
        "{e:?}"
    );
    let e = s
        .eval_batch_jvp(&[[0.5, 2.0]], None, None, &mut out, &mut tan)
        .unwrap_err();
    assert!(matches!(e, Error::ParameterOutOfDomain { .. }), "{e:?}");
    let e = s
        .eval_batch_vjp(&uv, &[1.0], Some(&mut [0.0; 5]), None)
        .unwrap_err();
    assert!(
        matches!(
            e,
            Error::LengthMismatch {
                expected: 4,
                got: 5,
                ..
            }
        ),
        "{e:?}"
    );
    let e = s.eval_batch_vjp(&uv, &[f64::NAN], None, None).unwrap_err();
    assert!(matches!(e, Error::NonFinite { .. }), "{e:?}");
    let e = s
        .eval_batch_vjp(&uv, &[1.0], None, Some(&mut []))
        .unwrap_err();
    assert!(
        matches!(
            e,
            Error::LengthMismatch {
                expected: 1,
                got: 0,
                ..
            }
        ),
        "{e:?}"
    );
    let e = s.eval_batch_linearize(&[[-1.0, 0.5]]).unwrap_err();
    assert!(matches!(e, Error::ParameterOutOfDomain { .. }), "{e:?}");
}

/// `S(u, v) = u + 2v + u v` on the bilinear net (0, 1; 2, 3): closed forms.
#[test]
fn surface_bilinear_closed_forms() {
    let s = bilinear();
    let mut g = vec![0.0; 4];
    let mut guv = vec![[0.0; 2]; 1];
    s.eval_batch_vjp(&[[0.25, 0.5]], &[2.0], Some(&mut g), Some(&mut guv))
        .unwrap();
    // P̄_kl = 2·N_k(u) N_l(v): N(0.25) = (0.75, 0.25), N(0.5) = (0.5, 0.5)
    assert_eq!(g, vec![0.75, 0.75, 0.25, 0.25]);
    // S_u = 2 + (3 − 2 − 1 + 0)·v = 2, S_v = 1 + 0·u: ū = 2·2, v̄ = 2·1
    assert_eq!(guv, vec![[4.0, 2.0]]);
}

/// A NURBS curve (a curve case with weights in `[0.3, 3]`) and a weight tangent.
fn nurbs_case() -> impl Strategy<Value = (NurbsCurve, CurveCase, Vec<f64>)> {
    curve_case().prop_flat_map(|case| {
        let n = case.0.control_points().len();
        (
            prop::collection::vec(0.3f64..3.0, n),
            prop::collection::vec(-1.0f64..1.0, n),
        )
            .prop_map(move |(w, dw)| {
                let c = &case.0;
                let nurbs = NurbsCurve::new(
                    c.degree(),
                    c.knots().as_slice().to_vec(),
                    c.control_points().clone(),
                    w,
                )
                .unwrap();
                (nurbs, case.clone(), dw)
            })
    })
}

fn eval_n(c: &NurbsCurve, ts: &[f64]) -> Vec<f64> {
    let mut out = vec![0.0; ts.len() * c.dim()];
    c.eval_batch(ts, &mut out).unwrap();
    out
}

fn rebuilt(c: &NurbsCurve, ctrl: Vec<f64>, w: Vec<f64>) -> NurbsCurve {
    let k = c.knots().as_slice().to_vec();
    NurbsCurve::new(c.degree(), k, Points::from_raw(ctrl, c.dim()), w).unwrap()
}

type Tangents<'a> = (Option<&'a [f64]>, Option<&'a [f64]>, Option<&'a [f64]>);

fn nurbs_jvp(c: &NurbsCurve, ts: &[f64], (dp, dw, dt): Tangents<'_>) -> (Vec<f64>, Vec<f64>) {
    let mut out = vec![0.0; ts.len() * c.dim()];
    let mut tan = vec![0.0; ts.len() * c.dim()];
    c.eval_batch_jvp(ts, dp, dw, dt, &mut out, &mut tan)
        .unwrap();
    (out, tan)
}

proptest! {
    #![proptest_config(proptest_config(256))]

    #[test]
    fn nurbs_primal_is_eval_batch_bit_for_bit((c, (_, ts, dp, dt, _), dw) in nurbs_case()) {
        let plain = eval_n(&c, &ts);
        let (out, _) = nurbs_jvp(&c, &ts, (Some(&dp), Some(&dw), Some(&dt)));
        prop_assert_eq!(&out, &plain);
        prop_assert_eq!(&c.eval_batch_linearize(&ts).unwrap().values, &plain);
    }

    #[test]
    fn nurbs_jvp_matches_central_differences((c, (_, ts, dp, dt, _), dw) in nurbs_case()) {
        let (ctrl, w) = (c.control_points().as_slice().to_vec(), c.weights());
        let floor = max_abs(&ctrl);
        let moved = |v: &[f64], d: &[f64], s: f64| v.iter().zip(d).map(|(x, y)| x + s * y).collect::<Vec<_>>();
        let fd = |plus: Vec<f64>, minus: Vec<f64>, h: f64| {
            plus.iter().zip(&minus).map(|(a, b)| (a - b) / (2.0 * h)).collect::<Vec<_>>()
        };
        let h = 1e-3;
        let d = fd(eval_n(&rebuilt(&c, moved(&ctrl, &dp, h), w.clone()), &ts),
                   eval_n(&rebuilt(&c, moved(&ctrl, &dp, -h), w.clone()), &ts), h);
        let (_, tan) = nurbs_jvp(&c, &ts, (Some(&dp), None, None));
        assert_rel(&tan, &d, FD_RTOL, floor, "JVP in the control points");
        let h = FD_STEP;
        let d = fd(eval_n(&rebuilt(&c, ctrl.clone(), moved(&w, &dw, h)), &ts),
                   eval_n(&rebuilt(&c, ctrl.clone(), moved(&w, &dw, -h)), &ts), h);
        let (_, tan) = nurbs_jvp(&c, &ts, (None, Some(&dw), None));
        assert_rel(&tan, &d, FD_RTOL, floor, "JVP in the weights");
        let d = fd(eval_n(&c, &moved(&ts, &dt, h)), eval_n(&c, &moved(&ts, &dt, -h)), h);
        let (_, tan) = nurbs_jvp(&c, &ts, (None, None, Some(&dt)));
        assert_rel(&tan, &d, FD_RTOL, floor, "JVP in the parameters");
    }

    #[test]
    fn nurbs_vjp_is_the_transpose_of_the_jvp((c, (_, ts, dp, dt, g), dw) in nurbs_case()) {
        let (_, tan) = nurbs_jvp(&c, &ts, (Some(&dp), Some(&dw), Some(&dt)));
        let (mut gp, mut gw, mut gt) = (vec![0.0; dp.len()], vec![0.0; dw.len()], vec![0.0; ts.len()]);
        c.eval_batch_vjp(&ts, &g, Some(&mut gp), Some(&mut gw), Some(&mut gt)).unwrap();
        let lhs = dot(&g, &tan);
        let rhs = dot(&gp, &dp) + dot(&gw, &dw) + dot(&gt, &dt);
        let scale = max_abs(&g) * (max_abs(&tan) + 1.0) * g.len() as f64;
        prop_assert!((lhs - rhs).abs() <= 1e-13 * scale, "<g, J x> = {lhs}, <J^T g, x> = {rhs}");
    }

    #[test]
    fn nurbs_linearization_applies_as_the_jvp((c, (_, ts, dp, dt, _), dw) in nurbs_case()) {
        let lin = c.eval_batch_linearize(&ts).unwrap();
        let (dim, wd) = (c.dim(), c.degree() + 1);
        let (ctrl, w) = (c.control_points().as_slice().to_vec(), c.weights());
        let (_, tan) = nurbs_jvp(&c, &ts, (Some(&dp), Some(&dw), Some(&dt)));
        let mut applied = vec![0.0; tan.len()];
        for i in 0..ts.len() {
            for k in 0..wd {
                let (j, r) = (lin.first[i] + k, lin.basis[i * wd + k]);
                for d in 0..dim {
                    let rel = ctrl[j * dim + d] - lin.values[i * dim + d];
                    applied[i * dim + d] += r * dp[j * dim + d] + r / w[j] * rel * dw[j];
                }
            }
            for d in 0..dim {
                applied[i * dim + d] += lin.derivatives[i * dim + d] * dt[i];
            }
        }
        assert_rel(&applied, &tan, 1e-12, max_abs(&tan).max(1.0), "linearisation");
    }
}

#[test]
fn nurbs_errors_name_the_argument() {
    let c = NurbsCurve::circle(&[0.0, 0.0], &[1.0, 0.0], &[0.0, 1.0], 1.0).unwrap();
    let n = c.weights().len();
    let (mut out, mut tan) = (vec![0.0; 2], vec![0.0; 2]);
    let e = c.eval_batch_jvp(
        &[0.5],
        None,
        Some(&vec![0.0; n + 1]),
        None,
        &mut out,
        &mut tan,
    );
    assert!(
        matches!(e, Err(Error::LengthMismatch { got, .. }) if got == n + 1),
        "{e:?}"
    );
    let e = c.eval_batch_jvp(
        &[0.5],
        Some(&[f64::NAN; 1][..0]),
        None,
        None,
        &mut out,
        &mut tan,
    );
    assert!(
        matches!(e, Err(Error::LengthMismatch { got: 0, .. })),
        "{e:?}"
    );
    let mut dp = vec![0.0; 2 * n];
    dp[3] = f64::INFINITY;
    let e = c.eval_batch_jvp(&[0.5], Some(&dp), None, None, &mut out, &mut tan);
    assert!(matches!(e, Err(Error::NonFinite { index: 3, .. })), "{e:?}");
    let e = c.eval_batch_jvp(&[2.0], None, None, None, &mut out, &mut tan);
    assert!(
        matches!(e, Err(Error::ParameterOutOfDomain { .. })),
        "{e:?}"
    );
    let e = c.eval_batch_vjp(&[0.5], &[1.0, 1.0], None, Some(&mut vec![0.0; n - 1]), None);
    assert!(matches!(e, Err(Error::LengthMismatch { .. })), "{e:?}");
    let e = c.eval_batch_vjp(&[0.5], &[1.0, f64::NAN], None, None, None);
    assert!(matches!(e, Err(Error::NonFinite { .. })), "{e:?}");
    let e = c.eval_batch_linearize(&[-1.0]);
    assert!(
        matches!(e, Err(Error::ParameterOutOfDomain { .. })),
        "{e:?}"
    );
}
