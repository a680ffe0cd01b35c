//! Tests of `rational_net.rs`: the knot JVP of tensor NURBS in 1 to 3 directions against
//! central differences of evaluation in each interior knot of each direction (relative 1e-7);
//! the VJP the JVP's transpose (the adjoint identity to 1e-12 relative); the primal values bit
//! for bit `eval_batch`; equal weights giving the B-spline's derivative; a NURBS surface the
//! tensor NURBS of two directions; one direction the NURBS curve; a negative test for every
//! error.

use proptest::prelude::*;

use super::net_tests::{net_case, NetCase};
use super::tests::{assert_adjoint, assert_rel, dot, max_abs, unit, FD_RTOL, FD_STEP};
use crate::curve::NurbsCurve;
use crate::error::Error;
use crate::oracle::proptest_config;
use crate::points::Points;
use crate::surface::NurbsSurface;
use crate::tensor::{TensorBSpline, TensorNurbs};

fn knot_vectors(s: &TensorNurbs) -> Vec<Vec<f64>> {
    s.knots().iter().map(|k| k.as_slice().to_vec()).collect()
}

fn rebuilt(s: &TensorNurbs, knots: Vec<Vec<f64>>) -> TensorNurbs {
    TensorNurbs::new(
        s.degrees().to_vec(),
        knots,
        s.control_points(),
        &s.weights(),
    )
    .unwrap()
}

fn eval(s: &TensorNurbs, xs: &[f64]) -> Vec<f64> {
    let mut out = vec![0.0; xs.len() / s.n_vars() * s.dim()];
    s.eval_batch(xs, &mut out).unwrap();
    out
}

/// `R(xs)` on the knots of direction `axis` moved by `(+h, −h) · e`, centrally differenced.
fn difference(s: &TensorNurbs, xs: &[f64], axis: usize, e: &[f64]) -> Vec<f64> {
    let moved = |h: f64| {
        let mut knots = knot_vectors(s);
        for (k, d) in knots[axis].iter_mut().zip(e) {
            *k += h * d;
        }
        eval(&rebuilt(s, knots), xs)
    };
    let (f, g) = (moved(FD_STEP), moved(-FD_STEP));
    f.iter()
        .zip(&g)
        .map(|(x, y)| (x - y) / (2.0 * FD_STEP))
        .collect()
}

fn knot_jvp(s: &TensorNurbs, xs: &[f64], tangents: &[Option<&[f64]>]) -> (Vec<f64>, Vec<f64>) {
    let len = xs.len() / s.n_vars() * s.dim();
    let (mut out, mut tan) = (vec![0.0; len], vec![0.0; len]);
    s.eval_batch_knot_jvp(xs, tangents, &mut out, &mut tan)
        .unwrap();
    (out, tan)
}

/// The JVP's tangent for the knot tangent `e` of direction `axis`, the others `None`.
fn along(s: &TensorNurbs, xs: &[f64], axis: usize, e: &[f64]) -> Vec<f64> {
    let mut tangents: Vec<Option<&[f64]>> = vec![None; s.n_vars()];
    tangents[axis] = Some(e);
    knot_jvp(s, xs, &tangents).1
}

fn knot_vjp(s: &TensorNurbs, xs: &[f64], g: &[f64]) -> Vec<Vec<f64>> {
    let mut gk: Vec<Vec<f64>> = s.knots().iter().map(|k| vec![f64::NAN; k.len()]).collect();
    let mut bufs: Vec<Option<&mut [f64]>> = gk.iter_mut().map(|b| Some(&mut b[..])).collect();
    s.eval_batch_knot_vjp(xs, g, &mut bufs).unwrap();
    gk
}

/// The net case with weights in `[0.3, 3]` (a rational spline far from the B-spline).
fn rational_case() -> impl Strategy<Value = (TensorNurbs, Vec<f64>, Vec<Vec<f64>>, Vec<f64>)> {
    net_case().prop_flat_map(|(s, xs, dk, g): NetCase| {
        let size: usize = s.shape().iter().product();
        prop::collection::vec(0.3f64..3.0, size).prop_map(move |w| {
            let r = TensorNurbs::new(
                s.degrees().to_vec(),
                s.knots().iter().map(|k| k.as_slice().to_vec()).collect(),
                s.control_points().clone(),
                &w,
            )
            .unwrap();
            (r, xs.clone(), dk.clone(), g.clone())
        })
    })
}

proptest! {
    #![proptest_config(proptest_config(64))]

    /// The JVP's values are `eval_batch`'s bits.
    #[test]
    fn primal_is_eval_batch_bit_for_bit((s, xs, dk, _g) in rational_case()) {
        let tangents: Vec<Option<&[f64]>> = dk.iter().map(|d| Some(&d[..])).collect();
        prop_assert_eq!(knot_jvp(&s, &xs, &tangents).0, eval(&s, &xs));
    }

    /// Each interior knot of each direction against central differences; the end knots'
    /// tangents are ignored.
    #[test]
    fn knot_jvp_matches_central_differences((s, xs, _dk, _g) in rational_case()) {
        let scale = max_abs(s.control_points().as_slice());
        for (axis, (kv, &p)) in s.knots().iter().zip(s.degrees()).enumerate() {
            let len = kv.len();
            for k in p + 1..len - p - 1 {
                let e = unit(len, k);
                let tan = along(&s, &xs, axis, &e);
                let fd = difference(&s, &xs, axis, &e);
                assert_rel(&tan, &fd, FD_RTOL, scale, &format!("direction {axis}, knot {k}"));
            }
            for k in (0..=p).chain(len - p - 1..len) {
                let tan = along(&s, &xs, axis, &unit(len, k));
                prop_assert!(tan.iter().all(|&x| x == 0.0), "end knot {} of {} moved", k, axis);
            }
        }
    }

    /// The VJP is the JVP's transpose (1e-12 relative); the end knots' cotangents are zero.
    #[test]
    fn knot_vjp_is_the_transpose_of_the_jvp((s, xs, dk, g) in rational_case()) {
        let tangents: Vec<Option<&[f64]>> = dk.iter().map(|d| Some(&d[..])).collect();
        let (_, tan) = knot_jvp(&s, &xs, &tangents);
        let gk = knot_vjp(&s, &xs, &g);
        let mut scale: f64 = tan.iter().zip(&g).map(|(a, b)| (a * b).abs()).sum();
        let mut rhs = 0.0;
        for ((gka, dka), &p) in gk.iter().zip(&dk).zip(s.degrees()) {
            let len = gka.len();
            prop_assert!(gka[..=p].iter().chain(&gka[len - p - 1..]).all(|&x| x == 0.0));
            scale += gka.iter().zip(dka).map(|(a, b)| (a * b).abs()).sum::<f64>();
            rhs += dot(gka, dka);
        }
        assert_adjoint(dot(&tan, &g), rhs, scale, "tensor NURBS");
    }

    /// With equal weights the rational spline is the B-spline, and so are its knot derivatives
    /// (to rounding: the quotient divides by a constant).
    #[test]
    fn equal_weights_give_the_bspline((b, xs, dk, g) in net_case()) {
        let size: usize = b.shape().iter().product();
        let knots: Vec<Vec<f64>> = b.knots().iter().map(|k| k.as_slice().to_vec()).collect();
        let r = TensorNurbs::new(
            b.degrees().to_vec(),
            knots,
            b.control_points().clone(),
            &vec![2.5; size],
        )
        .unwrap();
        let tangents: Vec<Option<&[f64]>> = dk.iter().map(|d| Some(&d[..])).collect();
        let (_, tan) = knot_jvp(&r, &xs, &tangents);
        let len = tan.len();
        let (mut out, mut want) = (vec![0.0; len], vec![0.0; len]);
        b.eval_batch_knot_jvp(&xs, &tangents, &mut out, &mut want).unwrap();
        let scale = max_abs(b.control_points().as_slice()).max(max_abs(&want));
        assert_rel(&tan, &want, 1e-12, scale, "jvp");
        let gk = knot_vjp(&r, &xs, &g);
        let mut want: Vec<Vec<f64>> = dk.iter().map(|d| vec![0.0; d.len()]).collect();
        let mut bufs: Vec<Option<&mut [f64]>> = want.iter_mut().map(|b| Some(&mut b[..])).collect();
        b.eval_batch_knot_vjp(&xs, &g, &mut bufs).unwrap();
        for (a, w) in gk.iter().zip(&want) {
            assert_rel(a, w, 1e-12, max_abs(w).max(1.0), "vjp");
        }
    }

    /// In two directions the NURBS surface's derivatives are the tensor NURBS's, and in one
    /// the NURBS curve's (to rounding: the three evaluate by different paths).
    #[test]
    fn two_directions_are_the_surface_and_one_the_curve((s, xs, dk, g) in rational_case()) {
        let tangents: Vec<Option<&[f64]>> = dk.iter().map(|d| Some(&d[..])).collect();
        let (out, tan) = knot_jvp(&s, &xs, &tangents);
        let gk = knot_vjp(&s, &xs, &g);
        let knots = knot_vectors(&s);
        let scale = max_abs(&tan).max(max_abs(&out)).max(1.0);
        match *s.degrees() {
            [p] => {
                let c = NurbsCurve::new(p, knots[0].clone(), s.control_points(), s.weights())
                    .unwrap();
                let (mut o, mut want) = (vec![0.0; tan.len()], vec![0.0; tan.len()]);
                c.eval_batch_knot_jvp(&xs, &dk[0], &mut o, &mut want).unwrap();
                assert_rel(&tan, &want, 1e-12, scale, "curve jvp");
                let mut gc = vec![0.0; dk[0].len()];
                c.eval_batch_knot_vjp(&xs, &g, &mut gc).unwrap();
                assert_rel(&gk[0], &gc, 1e-12, max_abs(&gc).max(1.0), "curve vjp");
            }
            [p, q] => {
                let size = (s.shape()[0], s.shape()[1]);
                let (ku, kv) = (knots[0].clone(), knots[1].clone());
                let surface =
                    NurbsSurface::new(p, q, ku, kv, s.control_points(), s.weights(), size)
                        .unwrap();
                let uv: Vec<[f64; 2]> = xs.chunks_exact(2).map(|x| [x[0], x[1]]).collect();
                let (mut o, mut want) = (vec![0.0; tan.len()], vec![0.0; tan.len()]);
                surface
                    .eval_batch_knot_jvp(&uv, Some(&dk[0]), Some(&dk[1]), &mut o, &mut want)
                    .unwrap();
                let mut direct = vec![0.0; o.len()];
                surface.eval_batch(&uv, &mut direct).unwrap();
                prop_assert_eq!(&o, &direct);
                assert_rel(&tan, &want, 1e-12, scale, "surface jvp");
                let (mut gu, mut gv) = (vec![0.0; dk[0].len()], vec![0.0; dk[1].len()]);
                surface.eval_batch_knot_vjp(&uv, &g, Some(&mut gu), Some(&mut gv)).unwrap();
                assert_rel(&gk[0], &gu, 1e-12, max_abs(&gu).max(1.0), "surface vjp u");
                assert_rel(&gk[1], &gv, 1e-12, max_abs(&gv).max(1.0), "surface vjp v");
            }
            _ => {}
        }
    }
}

/// A rational surface with a double interior knot in `u`: the pair moved together against
/// central differences, its copies summing to the pair.
#[test]
fn surface_double_knot_pair_and_copies() {
    let ku = vec![0.0, 0.0, 0.0, 0.4, 0.4, 1.0, 1.0, 1.0];
    let kv = vec![0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0];
    let net: Vec<f64> = (0..5 * 4 * 3)
        .map(|i| ((i * 7 + 2) as f64 * 0.61).sin())
        .collect();
    let w: Vec<f64> = (0..20)
        .map(|i| 1.0 + 0.8 * (i as f64 * 1.3).cos())
        .collect();
    let surface = |ku: Vec<f64>| {
        let ctrl = Points::from_raw(net.clone(), 3);
        NurbsSurface::new(2, 2, ku, kv.clone(), ctrl, w.clone(), (5, 4)).unwrap()
    };
    let s = surface(ku.clone());
    let uv = [[0.1, 0.2], [0.35, 0.7], [0.55, 0.45], [0.9, 0.95]];
    let jvp = |e: &[f64]| {
        let (mut out, mut tan) = (vec![0.0; 12], vec![0.0; 12]);
        s.eval_batch_knot_jvp(&uv, Some(e), None, &mut out, &mut tan)
            .unwrap();
        tan
    };
    let mut pair = vec![0.0; ku.len()];
    pair[3] = 1.0;
    pair[4] = 1.0;
    let moved = |h: f64| {
        let k: Vec<f64> = ku.iter().zip(&pair).map(|(k, d)| k + h * d).collect();
        let mut out = vec![0.0; 12];
        surface(k).eval_batch(&uv, &mut out).unwrap();
        out
    };
    let (f, g) = (moved(FD_STEP), moved(-FD_STEP));
    let fd: Vec<f64> = f
        .iter()
        .zip(&g)
        .map(|(a, b)| (a - b) / (2.0 * FD_STEP))
        .collect();
    let together = jvp(&pair);
    assert_rel(&together, &fd, FD_RTOL, max_abs(&net), "the pair together");
    let (first, last) = (jvp(&unit(ku.len(), 3)), jvp(&unit(ku.len(), 4)));
    let sum: Vec<f64> = first.iter().zip(&last).map(|(a, b)| a + b).collect();
    assert_rel(
        &sum,
        &together,
        1e-14,
        max_abs(&net),
        "the copies sum to the pair",
    );
}

#[test]
fn errors_name_the_argument() {
    let b = TensorBSpline::new(
        vec![1, 1],
        vec![vec![0.0, 0.0, 0.5, 1.0, 1.0], vec![0.0, 0.0, 1.0, 1.0]],
        Points::from_raw(vec![0.0, 0.0, 1.0, 1.0, 0.0, 0.0], 1),
    )
    .unwrap();
    let w = [1.0, 2.0, 1.0, 2.0, 1.0, 2.0];
    let t = TensorNurbs::new(
        vec![1, 1],
        vec![vec![0.0, 0.0, 0.5, 1.0, 1.0], vec![0.0, 0.0, 1.0, 1.0]],
        b.control_points().clone(),
        &w,
    )
    .unwrap();
    let s = t.to_nurbs_surface().unwrap();
    let (d0, d1) = (vec![0.0; 5], vec![0.0; 4]);
    let (mut out, mut tan) = ([0.0], [0.0]);
    let mismatch = |e: Result<(), Error>, want: (usize, usize)| {
        assert!(
            matches!(e, Err(Error::LengthMismatch { expected, got, .. }) if (expected, got) == want),
            "{e:?}"
        );
    };
    let x = [0.25, 0.5];
    mismatch(
        t.eval_batch_knot_jvp(&x, &[Some(&d0)], &mut out, &mut tan),
        (2, 1),
    );
    mismatch(
        t.eval_batch_knot_jvp(&x, &[None, Some(&d1[1..])], &mut out, &mut tan),
        (4, 3),
    );
    mismatch(
        t.eval_batch_knot_jvp(&x, &[None, None], &mut out, &mut []),
        (1, 0),
    );
    mismatch(
        s.eval_batch_knot_jvp(&[[0.25, 0.5]], Some(&d0[1..]), None, &mut out, &mut tan),
        (5, 4),
    );
    mismatch(
        s.eval_batch_knot_jvp(&[[0.25, 0.5]], None, None, &mut [], &mut tan),
        (1, 0),
    );
    let mut bad = d0.clone();
    bad[2] = f64::NAN;
    let e = s.eval_batch_knot_jvp(&[[0.25, 0.5]], Some(&bad), None, &mut out, &mut tan);
    assert!(matches!(e, Err(Error::NonFinite { index: 2, .. })), "{e:?}");
    let e = t.eval_batch_knot_jvp(&[1.5, 0.5], &[Some(&d0), None], &mut out, &mut tan);
    assert!(
        matches!(e, Err(Error::ParameterOutOfDomain { .. })),
        "{e:?}"
    );
    let (mut g0, mut g1) = (vec![0.0; 5], vec![0.0; 4]);
    mismatch(
        t.eval_batch_knot_vjp(&x, &[1.0, 2.0], &mut [Some(&mut g0), None]),
        (1, 2),
    );
    mismatch(
        s.eval_batch_knot_vjp(&[[0.25, 0.5]], &[1.0], None, Some(&mut g1[1..])),
        (4, 3),
    );
    let e = s.eval_batch_knot_vjp(&[[0.25, 0.5]], &[f64::NAN], Some(&mut g0), None);
    assert!(matches!(e, Err(Error::NonFinite { index: 0, .. })), "{e:?}");
    let e = s.eval_batch_knot_vjp(&[[0.25, -0.5]], &[1.0], Some(&mut g0), None);
    assert!(
        matches!(e, Err(Error::ParameterOutOfDomain { .. })),
        "{e:?}"
    );
}
