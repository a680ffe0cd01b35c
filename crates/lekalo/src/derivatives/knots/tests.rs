//! Tests of `curve.rs`, and of `net.rs` on surfaces: the knot JVPs of curves and surfaces
//! against central differences of evaluation in each interior knot (relative 1e-7), the VJPs
//! their exact transposes (the adjoint identity to 1e-12 relative), the primal values bit for
//! bit `eval_batch`, the one-sided conventions at multiple knots and at parameters on a knot,
//! the fixed end knots, and a negative test for every error. The helpers here serve
//! `nurbs_tests.rs` and `net_tests.rs` too.

use proptest::prelude::*;

use crate::curve::bspline::BSplineCurve;
use crate::error::Error;
use crate::oracle::proptest_config;
use crate::points::Points;
use crate::surface::bspline::BSplineSurface;

/// Relative tolerance of the finite-difference comparisons.
pub(super) const FD_RTOL: f64 = 1e-7;

/// Step of the differences in a knot (knot gaps are at least 0.2 and parameters at least
/// 0.004 from every knot, so the moved knot never crosses a parameter).
pub(super) const FD_STEP: f64 = 1e-6;

/// Relative tolerance of the adjoint identity `⟨ḡ, J τ̇⟩ = ⟨Jᵀ ḡ, τ̇⟩`.
pub(super) const ADJOINT_RTOL: f64 = 1e-12;

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

/// `|a − b| ≤ rtol · scale`, the scale the sum of the terms' magnitudes.
pub(super) fn assert_adjoint(a: f64, b: f64, scale: f64, what: &str) {
    assert!(
        (a - b).abs() <= ADJOINT_RTOL * scale.max(1e-300),
        "{what}: {a:e} against {b:e} (scale {scale:e})"
    );
}

/// Knots of a degree-`p` spline with `n` coefficients from gaps in `[0.2, 1]` (clamped or not),
/// interior knots repeated by `mult` (each at most `p`), and parameters at least 2 % of a span
/// from every knot.
pub(super) fn knots_and_params(
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
    let spans = n - p;
    let ts = xs
        .iter()
        .map(|&(j, x)| {
            let s = p + j % spans;
            knots[s] + (0.02 + 0.96 * x) * (knots[s + 1] - knots[s])
        })
        .collect();
    (knots, ts)
}

pub(super) fn curve(p: usize, knots: Vec<f64>, ctrl: Vec<f64>, dim: usize) -> BSplineCurve {
    BSplineCurve::new(p, knots, Points::from_raw(ctrl, dim)).unwrap()
}

fn with_knots(c: &BSplineCurve, knots: Vec<f64>) -> BSplineCurve {
    let ctrl = c.control_points().as_slice().to_vec();
    curve(c.degree(), knots, ctrl, c.dim())
}

pub(super) fn eval(c: &BSplineCurve, ts: &[f64]) -> Vec<f64> {
    let mut out = vec![0.0; ts.len() * c.dim()];
    c.eval_batch(ts, &mut out).unwrap();
    out
}

pub(super) fn knot_jvp(c: &BSplineCurve, ts: &[f64], dk: &[f64]) -> (Vec<f64>, Vec<f64>) {
    let mut out = vec![0.0; ts.len() * c.dim()];
    let mut tan = vec![0.0; ts.len() * c.dim()];
    c.eval_batch_knot_jvp(ts, dk, &mut out, &mut tan).unwrap();
    (out, tan)
}

fn knot_vjp(c: &BSplineCurve, ts: &[f64], g: &[f64]) -> Vec<f64> {
    let mut gk = vec![f64::NAN; c.knots().len()];
    c.eval_batch_knot_vjp(ts, g, &mut gk).unwrap();
    gk
}

/// The derivative of `C(ts)` in knot `k` from `(C(τ + a e_k) − C(τ − b e_k)) / (a + b)`.
fn difference(c: &BSplineCurve, ts: &[f64], k: usize, (a, b): (f64, f64)) -> Vec<f64> {
    let (mut up, mut down) = (c.knots().as_slice().to_vec(), c.knots().as_slice().to_vec());
    up[k] += a;
    down[k] -= b;
    let (f, g) = (eval(&with_knots(c, up), ts), eval(&with_knots(c, down), ts));
    f.iter().zip(&g).map(|(x, y)| (x - y) / (a + b)).collect()
}

/// The unit tangent of knot `k`.
pub(super) fn unit(len: usize, k: usize) -> Vec<f64> {
    let mut e = vec![0.0; len];
    e[k] = 1.0;
    e
}

/// A curve of degree 1..=5, dimension 1..=3, clamped or not, parameters off its knots, a knot
/// tangent and a cotangent.
type CurveCase = (BSplineCurve, Vec<f64>, Vec<f64>, Vec<f64>);

fn curve_case() -> impl Strategy<Value = CurveCase> {
    (1usize..=5, 0usize..7, 1usize..=3, any::<bool>(), 1usize..12).prop_flat_map(
        |(p, extra, dim, clamped, m)| {
            let n = p + 1 + extra;
            (
                prop::collection::vec(0.2f64..1.0, 2 * p + 9),
                prop::collection::vec(-1.0f64..1.0, n * dim),
                prop::collection::vec((0usize..64, 0.0f64..1.0), m),
                prop::collection::vec(-1.0f64..1.0, n + p + 1),
                prop::collection::vec(-1.0f64..1.0, m * dim),
            )
                .prop_map(move |(gaps, ctrl, xs, dk, g)| {
                    let (knots, ts) = knots_and_params(p, n, clamped, &gaps, &xs);
                    (curve(p, knots, ctrl, dim), ts, dk, g)
                })
        },
    )
}

proptest! {
    #![proptest_config(proptest_config(128))]

    /// The JVP's values are `eval_batch`'s bits.
    #[test]
    fn curve_primal_is_eval_batch_bit_for_bit((c, ts, dk, _g) in curve_case()) {
        let (out, _) = knot_jvp(&c, &ts, &dk);
        prop_assert_eq!(out, eval(&c, &ts));
    }

    /// Each interior knot's JVP column against central differences; the end knots' tangents
    /// are ignored.
    #[test]
    fn curve_knot_jvp_matches_central_differences((c, ts, _dk, _g) in curve_case()) {
        let (p, len) = (c.degree(), c.knots().len());
        let scale = max_abs(c.control_points().as_slice());
        for k in p + 1..len - p - 1 {
            let (_, tan) = knot_jvp(&c, &ts, &unit(len, k));
            let fd = difference(&c, &ts, k, (FD_STEP, FD_STEP));
            assert_rel(&tan, &fd, FD_RTOL, scale, &format!("knot {k}"));
        }
        for k in (0..=p).chain(len - p - 1..len) {
            let (_, tan) = knot_jvp(&c, &ts, &unit(len, k));
            prop_assert!(tan.iter().all(|&x| x == 0.0), "end knot {} moved the curve", k);
        }
    }

    /// `⟨ḡ, J τ̇⟩ = ⟨Jᵀ ḡ, τ̇⟩` to 1e-12 relative, and the end knots' cotangents zero.
    #[test]
    fn curve_knot_vjp_is_the_transpose_of_the_jvp((c, ts, dk, g) in curve_case()) {
        let (_, tan) = knot_jvp(&c, &ts, &dk);
        let gk = knot_vjp(&c, &ts, &g);
        let p = c.degree();
        let len = gk.len();
        prop_assert!(gk[..=p].iter().chain(&gk[len - p - 1..]).all(|&x| x == 0.0));
        let scale: f64 = tan.iter().zip(&g).map(|(a, b)| (a * b).abs()).sum::<f64>()
            + gk.iter().zip(&dk).map(|(a, b)| (a * b).abs()).sum::<f64>();
        assert_adjoint(dot(&tan, &g), dot(&gk, &dk), scale, "curve");
    }
}

/// A cubic with a double and a triple interior knot and parameters on both sides of them.
fn multiple_knots() -> (BSplineCurve, Vec<f64>) {
    let knots = vec![
        0.0, 0.0, 0.0, 0.0, 0.3, 0.5, 0.5, 0.8, 1.1, 1.1, 1.1, 1.4, 1.4, 1.4, 1.4,
    ];
    let n = knots.len() - 4;
    let ctrl: Vec<f64> = (0..2 * n)
        .map(|i| ((i * 5 + 1) as f64 * 0.73).sin())
        .collect();
    let ts = vec![0.1, 0.42, 0.47, 0.55, 0.7, 0.95, 1.05, 1.15, 1.3];
    (curve(3, knots, ctrl, 2), ts)
}

/// At a knot of multiplicity 2 and 3: the first copy's value is the derivative of decreasing
/// it, the last copy's of increasing it, and the copies' sum that of moving them together.
#[test]
fn multiple_knots_are_one_sided_and_sum_to_the_group() {
    let (c, ts) = multiple_knots();
    let len = c.knots().len();
    let scale = max_abs(c.control_points().as_slice());
    // forward differences with a smaller step: one-sided truncation error O(h)
    let h = 1e-8;
    for copies in [5usize..=6, 8..=10] {
        let (first, last) = (*copies.start(), *copies.end());
        let (_, left) = knot_jvp(&c, &ts, &unit(len, first));
        let fd_left = difference(&c, &ts, first, (0.0, h));
        assert_rel(&left, &fd_left, 1e-5, scale, "first copy, decreasing");
        let (_, right) = knot_jvp(&c, &ts, &unit(len, last));
        let fd_right = difference(&c, &ts, last, (h, 0.0));
        assert_rel(&right, &fd_right, 1e-5, scale, "last copy, increasing");
        // the group moved together, by central differences
        let mut all = vec![0.0; len];
        for k in copies.clone() {
            all[k] = 1.0;
        }
        let (_, group) = knot_jvp(&c, &ts, &all);
        let (mut up, mut down) = (c.knots().as_slice().to_vec(), c.knots().as_slice().to_vec());
        for k in copies.clone() {
            up[k] += FD_STEP;
            down[k] -= FD_STEP;
        }
        let (f, g) = (
            eval(&with_knots(&c, up), &ts),
            eval(&with_knots(&c, down), &ts),
        );
        let fd: Vec<f64> = f
            .iter()
            .zip(&g)
            .map(|(x, y)| (x - y) / (2.0 * FD_STEP))
            .collect();
        assert_rel(&group, &fd, FD_RTOL, scale, "the copies together");
        // and the one-sided values differ: the test could tell them apart
        assert!(
            max_abs(
                &left
                    .iter()
                    .zip(&right)
                    .map(|(a, b)| a - b)
                    .collect::<Vec<_>>()
            ) > 1e-3
        );
    }
}

/// A parameter on a simple interior knot: for degree ≥ 2 the derivative exists and matches
/// the differences from both sides (one-sided, with a step of 1e-8: the curve is only `C¹` in
/// the knot there for degree 2, so even central differences are only O(h) accurate); for
/// degree 1 it is one-sided, and the value is that of the right-continuous basis: the
/// derivative of decreasing the knot.
#[test]
fn parameters_on_a_knot() {
    let knots = |p: usize| {
        let mut k = vec![0.0; p + 1];
        k.extend([0.25, 0.5, 0.75]);
        k.extend(vec![1.0; p + 1]);
        k
    };
    for p in 1..=4 {
        let n = 3 + p + 1;
        let ctrl: Vec<f64> = (0..n).map(|i| ((i * 3 + 2) as f64 * 0.91).cos()).collect();
        let c = curve(p, knots(p), ctrl, 1);
        let len = c.knots().len();
        for k in p + 1..=p + 3 {
            let ts = [c.knots().as_slice()[k]];
            let (_, tan) = knot_jvp(&c, &ts, &unit(len, k));
            let decreasing = difference(&c, &ts, k, (0.0, 1e-8));
            assert_rel(
                &tan,
                &decreasing,
                1e-6,
                1.0,
                &format!("degree {p}, knot {k} down"),
            );
            if p > 1 {
                let increasing = difference(&c, &ts, k, (1e-8, 0.0));
                assert_rel(
                    &tan,
                    &increasing,
                    1e-6,
                    1.0,
                    &format!("degree {p}, knot {k} up"),
                );
            } else {
                // and degree 1 is really one-sided: increasing the knot differs
                let increasing = difference(&c, &ts, k, (1e-8, 0.0));
                assert!((tan[0] - increasing[0]).abs() > 0.1, "degree 1, knot {k}");
            }
        }
    }
    // the right end of the domain, with the last interior knot moving
    let c = curve(2, knots(2), vec![0.3, -0.2, 0.9, 0.1, 0.4, -0.6], 1);
    let (_, tan) = knot_jvp(&c, &[1.0], &unit(9, 5));
    let fd = difference(&c, &[1.0], 5, (FD_STEP, FD_STEP));
    assert_rel(&tan, &fd, FD_RTOL, 1.0, "right end");
}

/// The doctest's closed form, and the linear spline's corner moving sideways: on each side of
/// the knot the derivative is minus the slope times the hat function of the refined knots.
#[test]
fn linear_spline_closed_form() {
    let c = curve(1, vec![0.0, 0.0, 0.4, 1.0, 1.0], vec![0.0, 2.0, 1.0], 1);
    let ts = [0.1, 0.3, 0.5, 0.9];
    let (_, tan) = knot_jvp(&c, &ts, &unit(5, 2));
    // left piece: slope 5, hat t / 0.4; right piece: slope −1/0.6, hat (1 − t) / 0.6
    let want = [
        -5.0 * 0.1 / 0.4,
        -5.0 * 0.3 / 0.4,
        (1.0 / 0.6) * (0.5 / 0.6),
        (1.0 / 0.6) * (0.1 / 0.6),
    ];
    assert_rel(&tan, &want, 1e-14, 1.0, "linear spline");
}

#[test]
fn curve_errors_name_the_argument() {
    let c = curve(
        2,
        vec![0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0],
        vec![0.0, 1.0, 0.5, 2.0],
        1,
    );
    let (mut out, mut tan) = (vec![0.0; 2], vec![0.0; 2]);
    let dk = vec![0.0; 7];
    let e = c.eval_batch_knot_jvp(&[0.1, 0.2], &dk[..6], &mut out, &mut tan);
    assert!(
        matches!(
            e,
            Err(Error::LengthMismatch {
                expected: 7,
                got: 6,
                ..
            })
        ),
        "{e:?}"
    );
    let e = c.eval_batch_knot_jvp(&[0.1, 0.2], &dk, &mut out[..1], &mut tan);
    assert!(
        matches!(
            e,
            Err(Error::LengthMismatch {
                expected: 2,
                got: 1,
                ..
            })
        ),
        "{e:?}"
    );
    let e = c.eval_batch_knot_jvp(&[0.1, 0.2], &dk, &mut out, &mut tan[..1]);
    assert!(
        matches!(
            e,
            Err(Error::LengthMismatch {
                expected: 2,
                got: 1,
                ..
            })
        ),
        "{e:?}"
    );
    let mut bad = dk.clone();
    bad[3] = f64::NAN;
    let e = c.eval_batch_knot_jvp(&[0.1, 0.2], &bad, &mut out, &mut tan);
    assert!(matches!(e, Err(Error::NonFinite { index: 3, .. })), "{e:?}");
    let e = c.eval_batch_knot_jvp(&[0.1, 1.5], &dk, &mut out, &mut tan);
    assert!(
        matches!(e, Err(Error::ParameterOutOfDomain { .. })),
        "{e:?}"
    );
    let mut gk = vec![0.0; 7];
    let e = c.eval_batch_knot_vjp(&[0.1, 0.2], &[1.0], &mut gk);
    assert!(
        matches!(
            e,
            Err(Error::LengthMismatch {
                expected: 2,
                got: 1,
                ..
            })
        ),
        "{e:?}"
    );
    let e = c.eval_batch_knot_vjp(&[0.1, 0.2], &[1.0, f64::INFINITY], &mut gk);
    assert!(matches!(e, Err(Error::NonFinite { index: 1, .. })), "{e:?}");
    let e = c.eval_batch_knot_vjp(&[0.1, 0.2], &[1.0, 1.0], &mut gk[..5]);
    assert!(
        matches!(
            e,
            Err(Error::LengthMismatch {
                expected: 7,
                got: 5,
                ..
            })
        ),
        "{e:?}"
    );
    let e = c.eval_batch_knot_vjp(&[-0.5], &[1.0], &mut gk);
    assert!(
        matches!(e, Err(Error::ParameterOutOfDomain { .. })),
        "{e:?}"
    );
}

/// A surface, pairs, `u` and `v` knot tangents and a cotangent.
type SurfaceCase = (BSplineSurface, Vec<[f64; 2]>, Vec<f64>, Vec<f64>, Vec<f64>);

/// A surface of degrees 1..=4 × 1..=4, dimension 1..=3, clamped or not, pairs off its knots.
fn surface_case() -> impl Strategy<Value = SurfaceCase> {
    (
        (1usize..=4, 1usize..=4, 0usize..4, 0usize..4),
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
                prop::collection::vec(((0usize..64, 0.0f64..1.0), (0usize..64, 0.0f64..1.0)), m),
                (
                    prop::collection::vec(-1.0f64..1.0, nu + p + 1),
                    prop::collection::vec(-1.0f64..1.0, nv + q + 1),
                ),
                prop::collection::vec(-1.0f64..1.0, m * dim),
            )
                .prop_map(move |((gu, gv), ctrl, xs, (dku, dkv), g)| {
                    let (xu, xv): (Vec<_>, Vec<_>) = xs.into_iter().unzip();
                    let (ku, us) = knots_and_params(p, nu, clamped, &gu, &xu);
                    let (kv, vs) = knots_and_params(q, nv, clamped, &gv, &xv);
                    let net = Points::from_raw(ctrl, dim);
                    let s = BSplineSurface::new(p, q, ku, kv, net, (nu, nv)).unwrap();
                    let uv = us.into_iter().zip(vs).map(|(u, v)| [u, v]).collect();
                    (s, uv, dku, dkv, g)
                })
        })
}

fn eval_s(s: &BSplineSurface, uv: &[[f64; 2]]) -> Vec<f64> {
    let mut out = vec![0.0; uv.len() * s.dim()];
    s.eval_batch(uv, &mut out).unwrap();
    out
}

fn with_knots_s(s: &BSplineSurface, ku: Vec<f64>, kv: Vec<f64>) -> BSplineSurface {
    let (p, q) = s.degree();
    let net = s.control_points().clone();
    BSplineSurface::new(p, q, ku, kv, net, s.net_size()).unwrap()
}

fn surface_knot_jvp(
    s: &BSplineSurface,
    uv: &[[f64; 2]],
    du: Option<&[f64]>,
    dv: Option<&[f64]>,
) -> (Vec<f64>, Vec<f64>) {
    let mut out = vec![0.0; uv.len() * s.dim()];
    let mut tan = vec![0.0; uv.len() * s.dim()];
    s.eval_batch_knot_jvp(uv, du, dv, &mut out, &mut tan)
        .unwrap();
    (out, tan)
}

proptest! {
    #![proptest_config(proptest_config(96))]

    #[test]
    fn surface_primal_is_eval_batch_bit_for_bit((s, uv, du, dv, _g) in surface_case()) {
        let (out, _) = surface_knot_jvp(&s, &uv, Some(&du), Some(&dv));
        prop_assert_eq!(out, eval_s(&s, &uv));
    }

    /// Each interior knot of each direction against central differences.
    #[test]
    fn surface_knot_jvp_matches_central_differences((s, uv, _du, _dv, _g) in surface_case()) {
        let (p, q) = s.degree();
        let (ku, kv) = (s.knots_u().as_slice().to_vec(), s.knots_v().as_slice().to_vec());
        let scale = max_abs(s.control_points().as_slice());
        for (along_u, deg, knots) in [(true, p, &ku), (false, q, &kv)] {
            for k in deg + 1..knots.len() - deg - 1 {
                let e = unit(knots.len(), k);
                let (_, tan) = if along_u {
                    surface_knot_jvp(&s, &uv, Some(&e), None)
                } else {
                    surface_knot_jvp(&s, &uv, None, Some(&e))
                };
                let (mut up, mut down) = (knots.clone(), knots.clone());
                up[k] += FD_STEP;
                down[k] -= FD_STEP;
                let (a, b) = if along_u {
                    (with_knots_s(&s, up, kv.clone()), with_knots_s(&s, down, kv.clone()))
                } else {
                    (with_knots_s(&s, ku.clone(), up), with_knots_s(&s, ku.clone(), down))
                };
                let (f, g) = (eval_s(&a, &uv), eval_s(&b, &uv));
                let fd: Vec<f64> =
                    f.iter().zip(&g).map(|(x, y)| (x - y) / (2.0 * FD_STEP)).collect();
                assert_rel(&tan, &fd, FD_RTOL, scale, &format!("u {along_u}, knot {k}"));
            }
        }
    }

    /// The VJP is the JVP's transpose in both directions at once (1e-12 relative).
    #[test]
    fn surface_knot_vjp_is_the_transpose_of_the_jvp((s, uv, du, dv, g) in surface_case()) {
        let (_, tan) = surface_knot_jvp(&s, &uv, Some(&du), Some(&dv));
        let (mut gu, mut gv) = (vec![f64::NAN; du.len()], vec![f64::NAN; dv.len()]);
        s.eval_batch_knot_vjp(&uv, &g, Some(&mut gu), Some(&mut gv)).unwrap();
        let scale: f64 = tan.iter().zip(&g).map(|(a, b)| (a * b).abs()).sum::<f64>()
            + gu.iter().zip(&du).map(|(a, b)| (a * b).abs()).sum::<f64>()
            + gv.iter().zip(&dv).map(|(a, b)| (a * b).abs()).sum::<f64>();
        assert_adjoint(dot(&tan, &g), dot(&gu, &du) + dot(&gv, &dv), scale, "surface");
        // one direction alone gives the same numbers
        let mut gu_alone = vec![0.0; du.len()];
        s.eval_batch_knot_vjp(&uv, &g, Some(&mut gu_alone), None).unwrap();
        prop_assert_eq!(gu_alone, gu);
    }
}

#[test]
fn surface_errors_name_the_argument() {
    let net = Points::from_raw((0..9).map(f64::from).collect(), 1);
    let k = vec![0.0, 0.0, 0.5, 1.0, 1.0];
    let s = BSplineSurface::new(1, 1, k.clone(), k, net, (3, 3)).unwrap();
    let (mut out, mut tan) = (vec![0.0; 1], vec![0.0; 1]);
    let e = s.eval_batch_knot_jvp(&[[0.2, 0.3]], Some(&[0.0; 4]), None, &mut out, &mut tan);
    assert!(
        matches!(
            e,
            Err(Error::LengthMismatch {
                expected: 5,
                got: 4,
                ..
            })
        ),
        "{e:?}"
    );
    let e = s.eval_batch_knot_jvp(
        &[[0.2, 0.3]],
        None,
        Some(&[f64::NAN; 5]),
        &mut out,
        &mut tan,
    );
    assert!(matches!(e, Err(Error::NonFinite { .. })), "{e:?}");
    let e = s.eval_batch_knot_jvp(&[[0.2, 0.3]], None, None, &mut out, &mut []);
    assert!(
        matches!(
            e,
            Err(Error::LengthMismatch {
                expected: 1,
                got: 0,
                ..
            })
        ),
        "{e:?}"
    );
    let e = s.eval_batch_knot_jvp(&[[0.2, 1.3]], None, None, &mut out, &mut tan);
    assert!(
        matches!(e, Err(Error::ParameterOutOfDomain { .. })),
        "{e:?}"
    );
    let mut gv = vec![0.0; 3];
    let e = s.eval_batch_knot_vjp(&[[0.2, 0.3]], &[1.0], None, Some(&mut gv));
    assert!(
        matches!(
            e,
            Err(Error::LengthMismatch {
                expected: 5,
                got: 3,
                ..
            })
        ),
        "{e:?}"
    );
    let e = s.eval_batch_knot_vjp(&[[0.2, 0.3]], &[f64::NAN], None, None);
    assert!(matches!(e, Err(Error::NonFinite { .. })), "{e:?}");
    let e = s.eval_batch_knot_vjp(&[[0.2, 0.3]], &[1.0, 2.0], None, None);
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
}
