//! Tests of the NURBS surface kernels: primal values bit for bit against
//! `NurbsSurface::eval_batch`, the JVP against central differences (relative 1e-7) in the net,
//! the weights and `(u, v)`, the VJP as its transpose, the linearisation against the JVP, and
//! the errors.

use proptest::prelude::*;

use crate::derivatives::tests::{
    assert_rel, dot, max_abs, surface_case, SurfaceCase, FD_RTOL, FD_STEP,
};
use crate::error::Error;
use crate::oracle::proptest_config;
use crate::points::Points;
use crate::surface::NurbsSurface;

/// A NURBS surface (a B-spline surface case with weights in `[0.3, 3]`), its case, and a weight
/// tangent.
fn nurbs_surface_case() -> impl Strategy<Value = (NurbsSurface, SurfaceCase, Vec<f64>)> {
    surface_case().prop_flat_map(|case| {
        let (nu, nv) = case.0.net_size();
        (
            prop::collection::vec(0.3f64..3.0, nu * nv),
            prop::collection::vec(-1.0f64..1.0, nu * nv),
        )
            .prop_map(move |(w, dw)| {
                let s = &case.0;
                let (ku, kv) = s.knots();
                let nurbs = NurbsSurface::new(
                    s.degree_u(),
                    s.degree_v(),
                    ku.as_slice().to_vec(),
                    kv.as_slice().to_vec(),
                    s.control_points().clone(),
                    w,
                    s.net_size(),
                )
                .unwrap();
                (nurbs, case.clone(), dw)
            })
    })
}

fn eval(s: &NurbsSurface, uv: &[[f64; 2]]) -> Vec<f64> {
    let mut out = vec![0.0; uv.len() * s.dim()];
    s.eval_batch(uv, &mut out).unwrap();
    out
}

fn rebuilt(s: &NurbsSurface, ctrl: Vec<f64>, w: Vec<f64>) -> NurbsSurface {
    let (ku, kv) = s.knots();
    let (ku, kv) = (ku.as_slice().to_vec(), kv.as_slice().to_vec());
    let net = Points::from_raw(ctrl, s.dim());
    NurbsSurface::new(s.degree_u(), s.degree_v(), ku, kv, net, w, s.net_size()).unwrap()
}

type Tangents<'a> = (Option<&'a [f64]>, Option<&'a [f64]>, Option<&'a [[f64; 2]]>);

fn jvp(s: &NurbsSurface, uv: &[[f64; 2]], (dp, dw, duv): Tangents<'_>) -> (Vec<f64>, Vec<f64>) {
    let mut out = vec![0.0; uv.len() * s.dim()];
    let mut tan = vec![0.0; uv.len() * s.dim()];
    s.eval_batch_jvp(uv, dp, dw, duv, &mut out, &mut tan)
        .unwrap();
    (out, tan)
}

fn central(plus: &[f64], minus: &[f64], h: f64) -> Vec<f64> {
    plus.iter()
        .zip(minus)
        .map(|(a, b)| (a - b) / (2.0 * h))
        .collect()
}

proptest! {
    #![proptest_config(proptest_config(128))]

    #[test]
    fn primal_is_eval_batch_bit_for_bit((s, (_, uv, dp, duv, _), dw) in nurbs_surface_case()) {
        let plain = eval(&s, &uv);
        let (out, _) = jvp(&s, &uv, (Some(&dp), Some(&dw), Some(&duv)));
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        prop_assert_eq!(bits(&out), bits(&plain));
        prop_assert_eq!(bits(&s.eval_batch_linearize(&uv).unwrap().values), bits(&plain));
    }

    #[test]
    fn jvp_matches_central_differences((s, (_, uv, dp, duv, _), dw) in nurbs_surface_case()) {
        let (ctrl, w) = (s.control_points().as_slice().to_vec(), s.weights());
        let floor = max_abs(&ctrl);
        let moved = |v: &[f64], d: &[f64], k: f64| v.iter().zip(d).map(|(x, y)| x + k * y).collect::<Vec<_>>();
        // linear in the net: any step
        let h = 1e-3;
        let fd = central(&eval(&rebuilt(&s, moved(&ctrl, &dp, h), w.clone()), &uv),
                         &eval(&rebuilt(&s, moved(&ctrl, &dp, -h), w.clone()), &uv), h);
        let (_, tan) = jvp(&s, &uv, (Some(&dp), None, None));
        assert_rel(&tan, &fd, FD_RTOL, floor, "JVP in the control net");
        let h = FD_STEP;
        let fd = central(&eval(&rebuilt(&s, ctrl.clone(), moved(&w, &dw, h)), &uv),
                         &eval(&rebuilt(&s, ctrl.clone(), moved(&w, &dw, -h)), &uv), h);
        let (_, tan) = jvp(&s, &uv, (None, Some(&dw), None));
        assert_rel(&tan, &fd, FD_RTOL, floor, "JVP in the weights");
        let shifted = |k: f64| uv.iter().zip(&duv)
            .map(|(a, d)| [a[0] + k * h * d[0], a[1] + k * h * d[1]]).collect::<Vec<_>>();
        let fd = central(&eval(&s, &shifted(1.0)), &eval(&s, &shifted(-1.0)), h);
        let (_, tan) = jvp(&s, &uv, (None, None, Some(&duv)));
        assert_rel(&tan, &fd, FD_RTOL, floor, "JVP in (u, v)");
    }

    #[test]
    fn vjp_is_the_transpose_of_the_jvp((s, (_, uv, dp, duv, g), dw) in nurbs_surface_case()) {
        let (_, tan) = jvp(&s, &uv, (Some(&dp), Some(&dw), Some(&duv)));
        let (mut gp, mut gw) = (vec![0.0; dp.len()], vec![0.0; dw.len()]);
        let mut guv = vec![[0.0; 2]; uv.len()];
        s.eval_batch_vjp(&uv, &g, Some(&mut gp), Some(&mut gw), Some(&mut guv)).unwrap();
        let lhs = dot(&g, &tan);
        let rhs = dot(&gp, &dp) + dot(&gw, &dw) + dot(guv.as_flattened(), duv.as_flattened());
        let scale = max_abs(&g) * (max_abs(&tan) + 1.0) * g.len() as f64;
        prop_assert!((lhs - rhs).abs() <= 1e-13 * scale, "<g, J x> = {lhs}, <J^T g, x> = {rhs}");
        // each cotangent alone is the same as all together
        let mut alone = vec![0.0; dw.len()];
        s.eval_batch_vjp(&uv, &g, None, Some(&mut alone), None).unwrap();
        prop_assert_eq!(alone, gw);
    }

    #[test]
    fn linearization_applies_as_the_jvp((s, (_, uv, dp, duv, _), dw) in nurbs_surface_case()) {
        let lin = s.eval_batch_linearize(&uv).unwrap();
        let ((p, q), dim, nv) = (s.degree(), s.dim(), s.net_size().1);
        let (ctrl, w) = (s.control_points().as_slice().to_vec(), s.weights());
        let (_, tan) = jvp(&s, &uv, (Some(&dp), Some(&dw), Some(&duv)));
        let mut applied = vec![0.0; tan.len()];
        let block = (p + 1) * (q + 1);
        for i in 0..uv.len() {
            for k in 0..=p {
                for l in 0..=q {
                    let r = lin.basis[i * block + k * (q + 1) + l];
                    let j = (lin.first_u[i] + k) * nv + lin.first_v[i] + l;
                    for d in 0..dim {
                        let pd = ctrl[j * dim + d] - lin.values[i * dim + d];
                        applied[i * dim + d] += r * dp[j * dim + d] + r * pd / w[j] * dw[j];
                    }
                }
            }
            for d in 0..dim {
                applied[i * dim + d] += lin.derivatives_u[i * dim + d] * duv[i][0]
                    + lin.derivatives_v[i * dim + d] * duv[i][1];
            }
        }
        assert_rel(&applied, &tan, 1e-12, max_abs(&tan).max(1.0), "linearisation");
    }
}

/// A bilinear patch in 3-D with weights `1, 2, 3, 4`.
fn patch() -> NurbsSurface {
    let net = Points::from_3d(&[
        [0.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [1.0, 0.0, 0.0],
        [1.0, 1.0, 1.0],
    ])
    .unwrap();
    let k = vec![0.0, 0.0, 1.0, 1.0];
    NurbsSurface::new(1, 1, k.clone(), k, net, vec![1.0, 2.0, 3.0, 4.0], (2, 2)).unwrap()
}

#[test]
fn errors_name_the_argument() {
    let s = patch();
    let (mut out, mut tan) = (vec![0.0; 3], vec![0.0; 3]);
    let uv = [[0.5, 0.5]];
    let short = |what: &str, e: Error| {
        assert!(matches!(e, Error::LengthMismatch { .. }), "{what}: {e:?}");
    };
    short(
        "net tangent",
        s.eval_batch_jvp(&uv, Some(&[0.0; 11]), None, None, &mut out, &mut tan)
            .unwrap_err(),
    );
    short(
        "weight tangent",
        s.eval_batch_jvp(&uv, None, Some(&[0.0; 3]), None, &mut out, &mut tan)
            .unwrap_err(),
    );
    short(
        "parameter tangent",
        s.eval_batch_jvp(&uv, None, None, Some(&[]), &mut out, &mut tan)
            .unwrap_err(),
    );
    short(
        "output",
        s.eval_batch_jvp(&uv, None, None, None, &mut out[..2], &mut tan)
            .unwrap_err(),
    );
    let e = s
        .eval_batch_jvp(
            &uv,
            None,
            Some(&[0.0, f64::NAN, 0.0, 0.0]),
            None,
            &mut out,
            &mut tan,
        )
        .unwrap_err();
    assert!(matches!(e, Error::NonFinite { .. }), "{e:?}");
    let e = s
        .eval_batch_jvp(&[[0.5, 1.5]], None, None, None, &mut out, &mut tan)
        .unwrap_err();
    assert!(matches!(e, Error::ParameterOutOfDomain { .. }), "{e:?}");
    let e = s
        .eval_batch_jvp(&[[f64::NAN, 0.5]], None, None, None, &mut out, &mut tan)
        .unwrap_err();
    assert!(
        matches!(
            e,
            Error::ParameterOutOfDomain { .. } | Error::NonFinite { .. }
        ),
        "{e:?}"
    );
    short(
        "cotangent",
        s.eval_batch_vjp(&uv, &[1.0, 2.0], None, None, None)
            .unwrap_err(),
    );
    let e = s
        .eval_batch_vjp(&uv, &[1.0, f64::INFINITY, 0.0], None, None, None)
        .unwrap_err();
    assert!(matches!(e, Error::NonFinite { .. }), "{e:?}");
    let mut gw = vec![0.0; 5];
    short(
        "weight cotangent",
        s.eval_batch_vjp(&uv, &[1.0; 3], None, Some(&mut gw), None)
            .unwrap_err(),
    );
    let mut gp = vec![0.0; 12];
    let e = s
        .eval_batch_vjp(&[[-0.5, 0.5]], &[1.0; 3], Some(&mut gp), None, None)
        .unwrap_err();
    assert!(matches!(e, Error::ParameterOutOfDomain { .. }), "{e:?}");
    let e = s.eval_batch_linearize(&[[0.5, 2.0]]).unwrap_err();
    assert!(matches!(e, Error::ParameterOutOfDomain { .. }), "{e:?}");
}

/// The closed forms of the bilinear patch at its centre: `W = 2.5`, `S = (A / W)`, and the
/// weight derivative `N_k M_l (P_kl − S) / W` of the last corner.
#[test]
fn bilinear_closed_forms() {
    let s = patch();
    let (mut out, mut tan) = (vec![0.0; 3], vec![0.0; 3]);
    let dw = [0.0, 0.0, 0.0, 1.0];
    s.eval_batch_jvp(&[[0.5, 0.5]], None, Some(&dw), None, &mut out, &mut tan)
        .unwrap();
    // A = ¼ (1·(0,0,0) + 2·(0,1,0) + 3·(1,0,0) + 4·(1,1,1)) = (7/4, 6/4, 4/4), W = 10/4
    let expect = [0.7, 0.6, 0.4];
    assert_rel(&out, &expect, 1e-15, 1.0, "value");
    let by_formula: Vec<f64> = expect.iter().map(|c| 0.25 * (1.0 - c) / 2.5).collect();
    assert_rel(&tan, &by_formula, 1e-15, 1.0, "weight derivative");
}
