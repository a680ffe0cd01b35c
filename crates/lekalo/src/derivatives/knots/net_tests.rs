//! Tests of `net.rs` on `N`-variate tensor splines (the surfaces' are in `tests.rs`): the knot
//! JVP against central differences of evaluation in each interior knot of each direction
//! (relative 1e-7), and at a double knot against central differences of the pair moved
//! together and one-sided ones of each copy; the VJP the JVP's exact transpose (the adjoint
//! identity to 1e-12 relative); the primal values bit for bit `eval_batch`; one direction the
//! B-spline curve's kernel and two the surface's, bit for bit; a negative test for every error.

use proptest::prelude::*;

use super::tests::{
    assert_adjoint, assert_rel, curve, dot, knot_jvp, knots_and_params, max_abs, unit, FD_RTOL,
    FD_STEP,
};
use crate::error::Error;
use crate::oracle::proptest_config;
use crate::points::Points;
use crate::surface::BSplineSurface;
use crate::tensor::TensorBSpline;

fn spline(degrees: &[usize], knots: Vec<Vec<f64>>, net: Vec<f64>, dim: usize) -> TensorBSpline {
    TensorBSpline::new(degrees.to_vec(), knots, Points::from_raw(net, dim)).unwrap()
}

fn knot_vectors(s: &TensorBSpline) -> Vec<Vec<f64>> {
    s.knots().iter().map(|k| k.as_slice().to_vec()).collect()
}

fn eval(s: &TensorBSpline, xs: &[f64]) -> Vec<f64> {
    let mut out = vec![0.0; xs.len() / s.n_vars() * s.dim()];
    s.eval_batch(xs, None, &mut out).unwrap();
    out
}

/// `S(xs)` on the knots moved by `(+a, −b) · e` in direction `axis`, differenced.
fn difference(
    s: &TensorBSpline,
    xs: &[f64],
    axis: usize,
    e: &[f64],
    (a, b): (f64, f64),
) -> Vec<f64> {
    let moved = |h: f64| {
        let mut knots = knot_vectors(s);
        for (k, d) in knots[axis].iter_mut().zip(e) {
            *k += h * d;
        }
        let net = s.control_points().as_slice().to_vec();
        eval(&spline(s.degrees(), knots, net, s.dim()), xs)
    };
    let (f, g) = (moved(a), moved(-b));
    f.iter().zip(&g).map(|(x, y)| (x - y) / (a + b)).collect()
}

fn knot_jvp_n(s: &TensorBSpline, xs: &[f64], tangents: &[Option<&[f64]>]) -> (Vec<f64>, Vec<f64>) {
    let len = xs.len() / s.n_vars() * s.dim();
    let (mut out, mut tan) = (vec![0.0; len], vec![0.0; len]);
    s.eval_batch_knot_jvp(xs, tangents, &mut out, &mut tan)
        .unwrap();
    (out, tan)
}

/// The JVP's tangent for the knot tangent `e` of direction `axis`, the others `None`.
fn along(s: &TensorBSpline, xs: &[f64], axis: usize, e: &[f64]) -> Vec<f64> {
    let mut tangents: Vec<Option<&[f64]>> = vec![None; s.n_vars()];
    tangents[axis] = Some(e);
    knot_jvp_n(s, xs, &tangents).1
}

/// A spline in 1..=3 directions of degrees 1..=3 (each direction 1 to 3 spans), dimension
/// 1..=2, clamped or not, points off its knots, knot tangents and a cotangent.
pub(super) type NetCase = (TensorBSpline, Vec<f64>, Vec<Vec<f64>>, Vec<f64>);

pub(super) fn net_case() -> impl Strategy<Value = NetCase> {
    (
        prop::collection::vec((1usize..=3, 0usize..3), 1..=3),
        1usize..=2,
        any::<bool>(),
        1usize..6,
    )
        .prop_flat_map(|(dirs, dim, clamped, m)| {
            let n_vars = dirs.len();
            let size: usize = dirs.iter().map(|&(p, extra)| p + 1 + extra).product();
            let knot_len: usize = dirs.iter().map(|&(p, extra)| 2 * p + 2 + extra).sum();
            (
                prop::collection::vec(prop::collection::vec(0.2f64..1.0, 10), n_vars),
                prop::collection::vec(-1.0f64..1.0, size * dim),
                prop::collection::vec(prop::collection::vec((0usize..64, 0.0f64..1.0), m), n_vars),
                prop::collection::vec(-1.0f64..1.0, knot_len),
                prop::collection::vec(-1.0f64..1.0, m * dim),
            )
                .prop_map(move |(gaps, net, coords, flat_dk, g)| {
                    let (mut knots, mut axes) = (Vec::new(), Vec::new());
                    for ((&(p, extra), gaps), coords) in dirs.iter().zip(&gaps).zip(&coords) {
                        let (k, x) = knots_and_params(p, p + 1 + extra, clamped, gaps, coords);
                        knots.push(k);
                        axes.push(x);
                    }
                    // the points: coordinate a of point r is axes[a][r]
                    let xs = (0..m)
                        .flat_map(|r| axes.iter().map(move |x| x[r]))
                        .collect();
                    let mut dk = Vec::new();
                    let mut rest = &flat_dk[..];
                    for k in &knots {
                        let (head, tail) = rest.split_at(k.len());
                        dk.push(head.to_vec());
                        rest = tail;
                    }
                    let degrees: Vec<usize> = dirs.iter().map(|d| d.0).collect();
                    (spline(&degrees, knots, net, dim), xs, dk, g)
                })
        })
}

proptest! {
    #![proptest_config(proptest_config(96))]

    /// The JVP's values are `eval_batch`'s bits.
    #[test]
    fn tensor_primal_is_eval_batch_bit_for_bit((s, xs, dk, _g) in net_case()) {
        let tangents: Vec<Option<&[f64]>> = dk.iter().map(|d| Some(&d[..])).collect();
        let (out, _) = knot_jvp_n(&s, &xs, &tangents);
        prop_assert_eq!(out, eval(&s, &xs));
    }

    /// Each interior knot of each direction against central differences; the end knots'
    /// tangents are ignored.
    #[test]
    fn tensor_knot_jvp_matches_central_differences((s, xs, _dk, _g) in net_case()) {
        let scale = max_abs(s.control_points().as_slice());
        for (axis, (kv, &p)) in s.knots().iter().zip(s.degrees()).enumerate() {
            let len = kv.len();
            for k in p + 1..len - p - 1 {
                let e = unit(len, k);
                let tan = along(&s, &xs, axis, &e);
                let fd = difference(&s, &xs, axis, &e, (FD_STEP, FD_STEP));
                assert_rel(&tan, &fd, FD_RTOL, scale, &format!("direction {axis}, knot {k}"));
            }
            for k in (0..=p).chain(len - p - 1..len) {
                let tan = along(&s, &xs, axis, &unit(len, k));
                prop_assert!(tan.iter().all(|&x| x == 0.0), "end knot {} of {} moved", k, axis);
            }
        }
    }

    /// The VJP is the JVP's transpose in all directions at once (1e-12 relative), the end
    /// knots' cotangents are zero, and one direction asked alone gives the same numbers.
    #[test]
    fn tensor_knot_vjp_is_the_transpose_of_the_jvp((s, xs, dk, g) in net_case()) {
        let tangents: Vec<Option<&[f64]>> = dk.iter().map(|d| Some(&d[..])).collect();
        let (_, tan) = knot_jvp_n(&s, &xs, &tangents);
        let mut gk: Vec<Vec<f64>> = dk.iter().map(|d| vec![f64::NAN; d.len()]).collect();
        let mut bufs: Vec<Option<&mut [f64]>> = gk.iter_mut().map(|b| Some(&mut b[..])).collect();
        s.eval_batch_knot_vjp(&xs, &g, &mut bufs).unwrap();
        let mut scale: f64 = tan.iter().zip(&g).map(|(a, b)| (a * b).abs()).sum();
        let mut rhs = 0.0;
        for ((gka, dka), &p) in gk.iter().zip(&dk).zip(s.degrees()) {
            let len = gka.len();
            prop_assert!(gka[..=p].iter().chain(&gka[len - p - 1..]).all(|&x| x == 0.0));
            scale += gka.iter().zip(dka).map(|(a, b)| (a * b).abs()).sum::<f64>();
            rhs += dot(gka, dka);
        }
        assert_adjoint(dot(&tan, &g), rhs, scale, "tensor");
        let last = s.n_vars() - 1;
        let mut alone = vec![0.0; dk[last].len()];
        let mut bufs: Vec<Option<&mut [f64]>> = (0..s.n_vars()).map(|_| None).collect();
        bufs[last] = Some(&mut alone);
        s.eval_batch_knot_vjp(&xs, &g, &mut bufs).unwrap();
        prop_assert_eq!(&alone, &gk[last]);
    }

    /// In one direction the net's kernel is the curve's, and in two the surface's, bit for bit
    /// (the same weights on the same coefficients: `Q_j = 1·P_j` in one direction).
    #[test]
    fn one_direction_is_the_curve_and_two_the_surface((s, xs, dk, g) in net_case()) {
        let (knots, dim) = (knot_vectors(&s), s.dim());
        let net = s.control_points().as_slice().to_vec();
        let tangents: Vec<Option<&[f64]>> = dk.iter().map(|d| Some(&d[..])).collect();
        let (_, tan) = knot_jvp_n(&s, &xs, &tangents);
        let mut gk: Vec<Vec<f64>> = dk.iter().map(|d| vec![0.0; d.len()]).collect();
        let mut bufs: Vec<Option<&mut [f64]>> = gk.iter_mut().map(|b| Some(&mut b[..])).collect();
        s.eval_batch_knot_vjp(&xs, &g, &mut bufs).unwrap();
        match *s.degrees() {
            [p] => {
                let c = curve(p, knots[0].clone(), net, dim);
                prop_assert_eq!(&tan, &knot_jvp(&c, &xs, &dk[0]).1);
                let mut want = vec![0.0; dk[0].len()];
                c.eval_batch_knot_vjp(&xs, &g, &mut want).unwrap();
                prop_assert_eq!(&gk[0], &want);
            }
            [p, q] => {
                let (ku, kv) = (knots[0].clone(), knots[1].clone());
                let size = (s.shape()[0], s.shape()[1]);
                let surface =
                    BSplineSurface::new(p, q, ku, kv, Points::from_raw(net, dim), size).unwrap();
                let uv: Vec<[f64; 2]> = xs.chunks_exact(2).map(|x| [x[0], x[1]]).collect();
                let (mut out, mut want) = (vec![0.0; tan.len()], vec![0.0; tan.len()]);
                surface
                    .eval_batch_knot_jvp(&uv, Some(&dk[0]), Some(&dk[1]), &mut out, &mut want)
                    .unwrap();
                prop_assert_eq!(&tan, &want);
                let (mut gu, mut gv) = (vec![0.0; dk[0].len()], vec![0.0; dk[1].len()]);
                surface.eval_batch_knot_vjp(&uv, &g, Some(&mut gu), Some(&mut gv)).unwrap();
                prop_assert_eq!((&gk[0], &gk[1]), (&gu, &gv));
            }
            _ => {}
        }
    }
}

/// A spline in two directions, the first a cubic with a double interior knot, and points on
/// both sides of it.
fn double_knot() -> (TensorBSpline, Vec<f64>) {
    let k0 = vec![0.0, 0.0, 0.0, 0.0, 0.3, 0.6, 0.6, 0.9, 1.2, 1.2, 1.2, 1.2];
    let k1 = vec![0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0];
    let net = (0..8 * 4 * 2)
        .map(|i| ((i * 5 + 1) as f64 * 0.73).sin())
        .collect();
    let xs = vec![
        0.1, 0.2, 0.5, 0.7, 0.58, 0.45, 0.62, 0.9, 0.75, 0.05, 1.15, 0.6,
    ];
    (spline(&[3, 2], vec![k0, k1], net, 2), xs)
}

/// At the double knot: the pair moved together against central differences (relative 1e-7),
/// each copy against the one-sided differences of the move that keeps the knots sorted, and
/// the copies' sum the pair's.
#[test]
fn double_knot_central_for_the_pair_one_sided_for_each_copy() {
    let (s, xs) = double_knot();
    let len = s.knots()[0].len();
    let scale = max_abs(s.control_points().as_slice());
    let mut pair = vec![0.0; len];
    pair[5] = 1.0;
    pair[6] = 1.0;
    let together = along(&s, &xs, 0, &pair);
    let fd = difference(&s, &xs, 0, &pair, (FD_STEP, FD_STEP));
    assert_rel(&together, &fd, FD_RTOL, scale, "the pair together");
    // forward differences with a smaller step: one-sided truncation error O(h)
    let h = 1e-8;
    let first = along(&s, &xs, 0, &unit(len, 5));
    let decreasing = difference(&s, &xs, 0, &unit(len, 5), (0.0, h));
    assert_rel(&first, &decreasing, 1e-5, scale, "first copy, decreasing");
    let last = along(&s, &xs, 0, &unit(len, 6));
    let increasing = difference(&s, &xs, 0, &unit(len, 6), (h, 0.0));
    assert_rel(&last, &increasing, 1e-5, scale, "last copy, increasing");
    let sum: Vec<f64> = first.iter().zip(&last).map(|(a, b)| a + b).collect();
    assert_rel(&sum, &together, 1e-14, scale, "the copies sum to the pair");
    let gap = first
        .iter()
        .zip(&last)
        .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
    assert!(gap > 1e-3, "{gap}");
}

#[test]
fn tensor_errors_name_the_argument() {
    let (s, _) = double_knot();
    let (l0, l1) = (s.knots()[0].len(), s.knots()[1].len());
    let (d0, d1) = (vec![0.0; l0], vec![0.0; l1]);
    let (mut out, mut tan) = (vec![0.0; 2], vec![0.0; 2]);
    let x = [0.1, 0.2];
    let mismatch = |e: Result<(), Error>, want: (usize, usize)| {
        assert!(
            matches!(e, Err(Error::LengthMismatch { expected, got, .. }) if (expected, got) == want),
            "{e:?}"
        );
    };
    mismatch(
        s.eval_batch_knot_jvp(&x, &[Some(&d0)], &mut out, &mut tan),
        (2, 1),
    );
    mismatch(
        s.eval_batch_knot_jvp(&x, &[None, Some(&d1[1..])], &mut out, &mut tan),
        (l1, l1 - 1),
    );
    mismatch(
        s.eval_batch_knot_jvp(&x[..1], &[None, None], &mut out, &mut tan),
        (2, 1),
    );
    mismatch(
        s.eval_batch_knot_jvp(&x, &[None, None], &mut out[..1], &mut tan),
        (2, 1),
    );
    mismatch(
        s.eval_batch_knot_jvp(&x, &[None, None], &mut out, &mut []),
        (2, 0),
    );
    let mut bad = d1.clone();
    bad[4] = f64::NAN;
    let e = s.eval_batch_knot_jvp(&x, &[Some(&d0), Some(&bad)], &mut out, &mut tan);
    assert!(matches!(e, Err(Error::NonFinite { index: 4, .. })), "{e:?}");
    let e = s.eval_batch_knot_jvp(&[0.1, 1.2], &[Some(&d0), None], &mut out, &mut tan);
    assert!(
        matches!(e, Err(Error::ParameterOutOfDomain { .. })),
        "{e:?}"
    );
    let (mut g0, mut g1) = (vec![0.0; l0], vec![0.0; l1]);
    mismatch(
        s.eval_batch_knot_vjp(&x, &[1.0], &mut [Some(&mut g0), None]),
        (2, 1),
    );
    mismatch(
        s.eval_batch_knot_vjp(&x, &[1.0, 1.0], &mut [Some(&mut g0)]),
        (2, 1),
    );
    mismatch(
        s.eval_batch_knot_vjp(&x, &[1.0, 1.0], &mut [None, Some(&mut g1[1..])]),
        (l1, l1 - 1),
    );
    let e = s.eval_batch_knot_vjp(&x, &[1.0, f64::INFINITY], &mut [None, Some(&mut g1)]);
    assert!(matches!(e, Err(Error::NonFinite { index: 1, .. })), "{e:?}");
    let e = s.eval_batch_knot_vjp(&[-0.1, 0.2], &[1.0, 1.0], &mut [Some(&mut g0), None]);
    assert!(
        matches!(e, Err(Error::ParameterOutOfDomain { .. })),
        "{e:?}"
    );
}
