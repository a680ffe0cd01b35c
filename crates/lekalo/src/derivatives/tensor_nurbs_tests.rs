//! Tests of the tensor NURBS kernels in 1 to 4 directions: primal values bit for bit against
//! `TensorNurbs::eval_batch`, the JVP against central differences (relative 1e-7) in the net,
//! the weights and the points, the VJP as its transpose, the linearisation against the JVP,
//! the two-direction case against the NURBS surface's kernels, and the errors.

use proptest::prelude::*;

use crate::derivatives::tests::{assert_rel, dot, max_abs, FD_RTOL, FD_STEP};
use crate::error::Error;
use crate::oracle::proptest_config;
use crate::points::Points;
use crate::tensor::TensorNurbs;

/// A NURBS of `degrees` with interior knots at 0.3 and 0.7, clamped on `[0, 1]`, with net and
/// weights (in `[0.3, 3]`) from `seed`.
fn spline(degrees: &[usize], dim: usize, seed: &[f64]) -> TensorNurbs {
    let knots: Vec<Vec<f64>> = degrees
        .iter()
        .map(|&p| [vec![0.0; p + 1], vec![0.3, 0.7], vec![1.0; p + 1]].concat())
        .collect();
    let count: usize = degrees.iter().map(|p| p + 3).product();
    let net = (0..count * dim)
        .map(|i| seed[i % seed.len()] + (i % 7) as f64 * 0.1)
        .collect();
    let w: Vec<f64> = (0..count)
        .map(|i| 1.65 + 1.35 * seed[(3 * i + 1) % seed.len()])
        .collect();
    TensorNurbs::new(
        degrees.to_vec(),
        knots,
        Points::from_flat(dim, net).unwrap(),
        &w,
    )
    .unwrap()
}

fn rebuilt(s: &TensorNurbs, ctrl: Vec<f64>, w: &[f64]) -> TensorNurbs {
    let knots = s.knots().iter().map(|k| k.as_slice().to_vec()).collect();
    let net = Points::from_flat(s.dim(), ctrl).unwrap();
    TensorNurbs::new(s.degrees().to_vec(), knots, net, w).unwrap()
}

fn eval(s: &TensorNurbs, xs: &[f64]) -> Vec<f64> {
    let mut out = vec![0.0; xs.len() / s.n_vars() * s.dim()];
    s.eval_batch(xs, &mut out).unwrap();
    out
}

type Tangents<'a> = (Option<&'a [f64]>, Option<&'a [f64]>, Option<&'a [f64]>);

fn jvp(s: &TensorNurbs, xs: &[f64], (dp, dw, dx): Tangents<'_>) -> (Vec<f64>, Vec<f64>) {
    let len = xs.len() / s.n_vars() * s.dim();
    let (mut out, mut tan) = (vec![0.0; len], vec![0.0; len]);
    s.eval_batch_jvp(xs, dp, dw, dx, &mut out, &mut tan)
        .unwrap();
    (out, tan)
}

fn central(plus: &[f64], minus: &[f64], h: f64) -> Vec<f64> {
    plus.iter()
        .zip(minus)
        .map(|(a, b)| (a - b) / (2.0 * h))
        .collect()
}

/// Tangents of every kind from a pattern.
fn pattern(len: usize, a: usize, b: usize) -> Vec<f64> {
    (0..len)
        .map(|i| ((i * a % b) as f64 - (b / 2) as f64) / (b / 2) as f64)
        .collect()
}

proptest! {
    #![proptest_config(proptest_config(48))]

    #[test]
    fn jvp_matches_differences_and_vjp_is_its_transpose(
        degrees in prop::collection::vec(0usize..=3, 1..=4),
        dim in 1usize..=2,
        seed in prop::collection::vec(-1.0f64..1.0, 64),
        pts in prop::collection::vec(0.02f64..0.27, 12),
    ) {
        let s = spline(&degrees, dim, &seed);
        let n = degrees.len();
        // coordinates in [0.02, 0.27] + {0, 0.35, 0.72}: at least 0.02 from every knot
        let xs: Vec<f64> = pts.iter().take(3 * n).enumerate()
            .map(|(i, v)| v + [0.0, 0.35, 0.72][i % 3]).collect();
        let m = xs.len() / n;
        let (ctrl, w) = (s.control_points().as_slice().to_vec(), s.weights());
        let (dp, dw, dx) = (pattern(ctrl.len(), 37, 11), pattern(w.len(), 7, 5), pattern(xs.len(), 13, 7));
        let (out, tan) = jvp(&s, &xs, (Some(&dp), Some(&dw), Some(&dx)));
        let plain = eval(&s, &xs);
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        prop_assert_eq!(bits(&out), bits(&plain));
        let floor = max_abs(&ctrl);
        let moved = |v: &[f64], d: &[f64], k: f64| v.iter().zip(d).map(|(x, y)| x + k * y).collect::<Vec<_>>();
        let h = 1e-3;
        let fd = central(&eval(&rebuilt(&s, moved(&ctrl, &dp, h), &w), &xs),
                         &eval(&rebuilt(&s, moved(&ctrl, &dp, -h), &w), &xs), h);
        assert_rel(&jvp(&s, &xs, (Some(&dp), None, None)).1, &fd, FD_RTOL, floor, "JVP in the net");
        let h = FD_STEP;
        let fd = central(&eval(&rebuilt(&s, ctrl.clone(), &moved(&w, &dw, h)), &xs),
                         &eval(&rebuilt(&s, ctrl.clone(), &moved(&w, &dw, -h)), &xs), h);
        assert_rel(&jvp(&s, &xs, (None, Some(&dw), None)).1, &fd, FD_RTOL, floor, "JVP in the weights");
        let fd = central(&eval(&s, &moved(&xs, &dx, h)), &eval(&s, &moved(&xs, &dx, -h)), h);
        assert_rel(&jvp(&s, &xs, (None, None, Some(&dx))).1, &fd, FD_RTOL, floor, "JVP in the points");

        let g = pattern(m * dim, 5, 9);
        let (mut gp, mut gw, mut gx) = (vec![0.0; ctrl.len()], vec![0.0; w.len()], vec![0.0; xs.len()]);
        s.eval_batch_vjp(&xs, &g, Some(&mut gp), Some(&mut gw), Some(&mut gx)).unwrap();
        let lhs = dot(&g, &tan);
        let rhs = dot(&gp, &dp) + dot(&gw, &dw) + dot(&gx, &dx);
        let scale = max_abs(&g) * (max_abs(&tan) + 1.0) * g.len() as f64;
        prop_assert!((lhs - rhs).abs() <= 1e-13 * scale, "<g, J x> = {lhs}, <J^T g, x> = {rhs}");

        // the linearisation applies as the JVP
        let lin = s.eval_batch_linearize(&xs).unwrap();
        prop_assert_eq!(bits(&lin.values), bits(&plain));
        let block: usize = degrees.iter().map(|p| p + 1).product();
        let shape = s.shape();
        let mut applied = vec![0.0; tan.len()];
        for r in 0..m {
            for c in 0..block {
                // the multi-index of cell c, the last direction fastest
                let (mut rest, mut j) = (c, 0);
                let mut k = vec![0; n];
                for a in (0..n).rev() {
                    k[a] = rest % (degrees[a] + 1);
                    rest /= degrees[a] + 1;
                }
                for a in 0..n {
                    j = j * shape[a] + lin.first[r * n + a] + k[a];
                }
                let rk = lin.basis[r * block + c];
                for d in 0..dim {
                    let pd = ctrl[j * dim + d] - lin.values[r * dim + d];
                    applied[r * dim + d] += rk * dp[j * dim + d] + rk * pd / w[j] * dw[j];
                }
            }
            for a in 0..n {
                for d in 0..dim {
                    applied[r * dim + d] += lin.partials[(r * n + a) * dim + d] * dx[r * n + a];
                }
            }
        }
        assert_rel(&applied, &tan, 1e-12, max_abs(&tan).max(1.0), "linearisation");
    }

    /// In two directions the kernels agree with the NURBS surface's (the same homogeneous net).
    #[test]
    fn two_directions_agree_with_the_surface(
        p in 0usize..=3, q in 0usize..=3,
        seed in prop::collection::vec(-1.0f64..1.0, 64),
        pts in prop::collection::vec(0.02f64..0.27, 6),
    ) {
        let s = spline(&[p, q], 3, &seed);
        let surface = s.to_nurbs_surface().unwrap();
        let xs: Vec<f64> = pts.iter().enumerate().map(|(i, v)| v + [0.0, 0.35, 0.72][i % 3]).collect();
        let uv: Vec<[f64; 2]> = xs.chunks_exact(2).map(|c| [c[0], c[1]]).collect();
        let (ctrl, w) = (s.control_points().as_slice().to_vec(), s.weights());
        let (dp, dw, dx) = (pattern(ctrl.len(), 37, 11), pattern(w.len(), 7, 5), pattern(xs.len(), 13, 7));
        let (out, tan) = jvp(&s, &xs, (Some(&dp), Some(&dw), Some(&dx)));
        let duv: Vec<[f64; 2]> = dx.chunks_exact(2).map(|c| [c[0], c[1]]).collect();
        let (mut so, mut st) = (vec![0.0; out.len()], vec![0.0; out.len()]);
        surface.eval_batch_jvp(&uv, Some(&dp), Some(&dw), Some(&duv), &mut so, &mut st).unwrap();
        assert_rel(&out, &so, 1e-14, 1.0, "values");
        assert_rel(&tan, &st, 1e-13, max_abs(&st).max(1.0), "tangents");
    }
}

#[test]
fn errors_name_the_argument() {
    let s = spline(&[1, 2], 1, &[0.5, -0.25]);
    let (mut out, mut tan) = ([0.0], [0.0]);
    let e = s
        .eval_batch_jvp(&[0.5, 0.5, 0.5], None, None, None, &mut out, &mut tan)
        .unwrap_err();
    assert!(matches!(e, Error::LengthMismatch { .. }), "{e:?}");
    let e = s
        .eval_batch_jvp(&[0.5, 1.5], None, None, None, &mut out, &mut tan)
        .unwrap_err();
    assert!(matches!(e, Error::ParameterOutOfDomain { .. }), "{e:?}");
    let e = s
        .eval_batch_jvp(&[0.5, 0.5], None, Some(&[0.0; 3]), None, &mut out, &mut tan)
        .unwrap_err();
    assert!(matches!(e, Error::LengthMismatch { .. }), "{e:?}");
    let mut dw = vec![0.0; s.weights().len()];
    dw[2] = f64::NAN;
    let e = s
        .eval_batch_jvp(&[0.5, 0.5], None, Some(&dw), None, &mut out, &mut tan)
        .unwrap_err();
    assert!(matches!(e, Error::NonFinite { .. }), "{e:?}");
    let e = s
        .eval_batch_jvp(
            &[0.5, 0.5],
            None,
            None,
            Some(&[f64::INFINITY, 0.0]),
            &mut out,
            &mut tan,
        )
        .unwrap_err();
    assert!(matches!(e, Error::NonFinite { .. }), "{e:?}");
    let e = s
        .eval_batch_vjp(&[0.5, 0.5], &[1.0, 2.0], None, None, None)
        .unwrap_err();
    assert!(matches!(e, Error::LengthMismatch { .. }), "{e:?}");
    let mut gw = vec![0.0; 3];
    let e = s
        .eval_batch_vjp(&[0.5, 0.5], &[1.0], None, Some(&mut gw), None)
        .unwrap_err();
    assert!(matches!(e, Error::LengthMismatch { .. }), "{e:?}");
    let mut gx = vec![0.0; 2];
    let e = s
        .eval_batch_vjp(&[-0.5, 0.5], &[1.0], None, None, Some(&mut gx))
        .unwrap_err();
    assert!(matches!(e, Error::ParameterOutOfDomain { .. }), "{e:?}");
    let e = s.eval_batch_linearize(&[0.5]).unwrap_err();
    assert!(matches!(e, Error::LengthMismatch { .. }), "{e:?}");
}
