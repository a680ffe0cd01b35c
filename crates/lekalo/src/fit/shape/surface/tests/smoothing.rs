//! Tests of the shape-constrained smoothing spline on a grid: its objective is the
//! unconstrained spline's (checked against an independent dense penalty), inactive constraints
//! return the unconstrained spline, active ones hold (Bernstein rows and dense samples) at a
//! KKT point of the penalised program, the smoothing condition is met, and what cannot be done
//! is refused by name.

use super::super::smoothing::{
    constrained_surface_grid_smoothing_condition, constrained_surface_grid_smoothing_spline,
};
use super::{dense_check, grid_design, kkt_parts, kkt_residual_penalised, rippled_grid};
use crate::basis::basis_derivatives;
use crate::error::Error;
use crate::fit::{surface_shape_violations, Lambda, SurfaceShape, SurfaceShapeConstraints};
use crate::knots::KnotVector;
use crate::points::PointsRef;
use crate::{tensor_grid_smoothing_spline, BSplineSurface, Direction};

/// `Ω = ∫ B'' B''ᵀ` of the cubic B-splines on `k`, by two-point Gauss on every knot interval
/// (exact: `B''` is linear there), independent of the smoothing code's banded assembly.
fn roughness(k: &KnotVector) -> Vec<Vec<f64>> {
    let t = k.as_slice();
    let n = t.len() - 4;
    let mut omega = vec![vec![0.0; n]; n];
    for w in t.windows(2) {
        let (a, b) = (w[0], w[1]);
        if b <= a {
            continue;
        }
        let (mid, half) = (0.5 * (a + b), 0.5 * (b - a));
        for x in [mid - half / 3f64.sqrt(), mid + half / 3f64.sqrt()] {
            let (span, d) = basis_derivatives(k, 3, x, 2).unwrap();
            let second = &d[8..12];
            for (r, br) in second.iter().enumerate() {
                for (c, bc) in second.iter().enumerate() {
                    omega[span - 3 + r][span - 3 + c] += half * br * bc;
                }
            }
        }
    }
    omega
}

/// The dense penalty `(G_u + λ_uΩ_u) ⊗ (G_v + λ_vΩ_v) − G_u ⊗ G_v` of the grid's smoothing
/// spline on the surface's knots, `G_a = B_aᵀB_a` from the dense design of each direction.
pub(super) fn grid_penalty(
    s: &BSplineSurface,
    u: &[f64],
    v: &[f64],
    lams: [f64; 2],
) -> Vec<Vec<f64>> {
    let (ku, kv) = s.knots();
    let gram = |k: &KnotVector, x: &[f64]| {
        let n = k.len() - 4;
        let mut g = vec![vec![0.0; n]; n];
        for &t in x {
            let (span, b) = basis_derivatives(k, 3, t, 0).unwrap();
            for (r, br) in b.iter().enumerate() {
                for (c, bc) in b.iter().enumerate() {
                    g[span - 3 + r][span - 3 + c] += br * bc;
                }
            }
        }
        g
    };
    let (gu, gv) = (gram(ku, u), gram(kv, v));
    let (ou, ov) = (roughness(ku), roughness(kv));
    let (nu, nv) = (gu.len(), gv.len());
    let mut k = vec![vec![0.0; nu * nv]; nu * nv];
    for i in 0..nu {
        for a in 0..nu {
            let pu = gu[i][a] + lams[0] * ou[i][a];
            for j in 0..nv {
                for b in 0..nv {
                    let pv = gv[j][b] + lams[1] * ov[j][b];
                    k[i * nv + j][a * nv + b] = pu * pv - gu[i][a] * gv[j][b];
                }
            }
        }
    }
    k
}

/// Slack (rows scaled to unit largest coefficient, in units of the data) up to which a row may
/// carry a multiplier in the KKT check. The interior point leaves rows of small multiplier `λ`
/// at a slack of about `μ/λ` above their bound (up to `10⁻⁴` here), so a threshold of `10⁻⁷`
/// would deny multipliers the optimum has. Any set of rows gives a valid certificate: with
/// the gradient a non-negative combination of rows, the complementarity gap `Σ λ_k g_k` the
/// check returns bounds the objective's distance to the constrained minimum.
pub(super) const ACTIVE: f64 = 1e-3;

/// The stationarity residual (relative to the gradient's terms) below which the constrained
/// spline counts as optimal, as for the least-squares fits.
pub(super) const KKT_RTOL: f64 = 1e-9;

/// The complementarity gap (relative to `½‖z‖²`) the multipliers may leave: the objective
/// within this of the constrained minimum, ten times below the `10⁻⁹` asked of the fits.
pub(super) const GAP_RTOL: f64 = 1e-10;

fn increasing_u() -> SurfaceShapeConstraints {
    SurfaceShapeConstraints::new().with(SurfaceShape::Increasing(Direction::U))
}

#[test]
fn the_penalty_is_the_unconstrained_splines() {
    // the unconstrained spline is stationary for the dense objective with the independent
    // penalty: the program's objective is the one the smoothing minimises
    let (u, v, z) = rippled_grid(12, 9);
    let values = PointsRef::from_flat(1, &z).unwrap();
    for lams in [[1e-4, 1e-3], [3e-3, 2e-5]] {
        let free = tensor_grid_smoothing_spline(
            &[&u, &v],
            values,
            &[Lambda::Given(lams[0]), Lambda::Given(lams[1])],
        )
        .unwrap();
        let s = free.spline.to_surface().unwrap();
        let (ku, kv) = s.knots();
        let design = grid_design(ku, kv, (3, 3), &u, &v);
        let penalty = grid_penalty(&s, &u, &v, lams);
        let none = SurfaceShapeConstraints::new();
        let kkt = kkt_residual_penalised(&design, &z, &s, &none, 0.0, &penalty);
        assert!(kkt < 1e-12, "λ {lams:?}: gradient {kkt}");
        // and a wrong weight is not stationary: the check can fail
        let wrong = grid_penalty(&s, &u, &v, [lams[0] * 2.0, lams[1]]);
        assert!(kkt_residual_penalised(&design, &z, &s, &none, 0.0, &wrong) > 1e-6);
    }
}

#[test]
fn active_constraints_hold_at_a_kkt_point_of_the_penalised_program() {
    let (u, v, z) = rippled_grid(16, 12);
    let values = PointsRef::from_flat(1, &z).unwrap();
    let boxed = SurfaceShapeConstraints::new()
        .with_on(
            SurfaceShape::Increasing(Direction::U),
            (0.2, 0.9),
            (0.0, 1.0),
        )
        .with(SurfaceShape::AtMost(1.6));
    for (lambdas, c) in [
        ([Lambda::Given(1e-5), Lambda::Given(1e-4)], increasing_u()),
        ([Lambda::Gcv, Lambda::Gcv], increasing_u()),
        ([Lambda::Given(1e-5), Lambda::Gcv], boxed),
    ] {
        let free = tensor_grid_smoothing_spline(&[&u, &v], values, &lambdas).unwrap();
        let plain = free.spline.to_surface().unwrap();
        let before = surface_shape_violations(&plain, &c).unwrap();
        assert!(
            before.iter().any(|b| *b > 1e-3),
            "{lambdas:?}: the unconstrained spline should break a shape: {before:?}"
        );
        let f = constrained_surface_grid_smoothing_spline(values, (&u, &v), lambdas, &c).unwrap();
        // λ of GCV is the unconstrained spline's
        assert_eq!(f.lambdas.to_vec(), free.lambdas, "{lambdas:?}");
        assert!(surface_shape_violations(&f.surface, &c)
            .unwrap()
            .iter()
            .all(|v| *v == 0.0));
        dense_check(&f.surface, &c, 0.0);
        let (ku, kv) = f.surface.knots();
        let design = grid_design(ku, kv, (3, 3), &u, &v);
        let penalty = grid_penalty(&f.surface, &u, &v, f.lambdas);
        let (kkt, gap) = kkt_parts(&design, &z, &f.surface, &c, ACTIVE, &penalty);
        assert!(kkt < KKT_RTOL, "{lambdas:?}: stationarity residual {kkt}");
        assert!(gap < GAP_RTOL, "{lambdas:?}: complementarity gap {gap}");
        // the plain fit is not a KKT point of the constrained problem (it is infeasible), and
        // the constrained residual is above the unconstrained one
        assert!(f.residual > free.residual);
    }
}

#[test]
fn inactive_constraints_return_the_unconstrained_smoothing_spline() {
    let u: Vec<f64> = (0..10).map(|i| i as f64 / 9.0).collect();
    let v: Vec<f64> = (0..8).map(|j| j as f64 / 7.0).collect();
    // a rising table with a little noise (GCV needs a residual), far inside every shape
    let z: Vec<f64> = (0..u.len() * v.len())
        .map(|k| {
            let (x, y) = (u[k / v.len()], v[k % v.len()]);
            1.0 + x + x * y + 0.3 * y + 0.003 * (k as f64 * 2.3).sin()
        })
        .collect();
    let values = PointsRef::from_flat(1, &z).unwrap();
    let c = SurfaceShapeConstraints::new()
        .with(SurfaceShape::Increasing(Direction::U))
        .with(SurfaceShape::Increasing(Direction::V))
        .with(SurfaceShape::AtLeast(0.5))
        .with(SurfaceShape::AtMost(4.0));
    for lambdas in [[Lambda::Given(1e-3), Lambda::Given(1e-2)], [Lambda::Gcv; 2]] {
        let free = tensor_grid_smoothing_spline(&[&u, &v], values, &lambdas).unwrap();
        let f = constrained_surface_grid_smoothing_spline(values, (&u, &v), lambdas, &c).unwrap();
        let plain = free.spline.to_surface().unwrap();
        for (a, b) in f
            .surface
            .control_points()
            .as_slice()
            .iter()
            .zip(plain.control_points().as_slice())
        {
            assert!((a - b).abs() <= 1e-12 * (1.0 + b.abs()), "{a} vs {b}");
        }
        assert_eq!(f.surface.knots(), plain.knots());
        assert_eq!(f.residual, free.residual);
    }
}

#[test]
fn the_smoothing_condition_is_met_in_shape() {
    let (u, v, z) = rippled_grid(14, 10);
    let values = PointsRef::from_flat(1, &z).unwrap();
    let c = increasing_u();
    let gcv =
        constrained_surface_grid_smoothing_spline(values, (&u, &v), [Lambda::Gcv; 2], &c).unwrap();
    // targets above the residual at the GCV weights (below it the constraints leave little
    // room: the least residual is refused, see `what_cannot_be_done_is_refused_by_name`)
    for s in [gcv.residual * 3.0, gcv.residual * 1.3] {
        let f = constrained_surface_grid_smoothing_condition(values, (&u, &v), s, &c).unwrap();
        assert!(
            (f.residual - s).abs() <= 1e-3 * s,
            "s {s}: residual {}",
            f.residual
        );
        // the weights keep the ratio GCV chose
        let ratio = |l: [f64; 2]| l[0] / l[1];
        assert!((ratio(f.lambdas) / ratio(gcv.lambdas) - 1.0).abs() < 1e-12);
        assert_eq!(surface_shape_violations(&f.surface, &c).unwrap(), vec![0.0]);
        dense_check(&f.surface, &c, 0.0);
        let (ku, kv) = f.surface.knots();
        let design = grid_design(ku, kv, (3, 3), &u, &v);
        let penalty = grid_penalty(&f.surface, &u, &v, f.lambdas);
        let (kkt, gap) = kkt_parts(&design, &z, &f.surface, &c, ACTIVE, &penalty);
        assert!(kkt < KKT_RTOL, "s {s}: stationarity residual {kkt}");
        assert!(gap < GAP_RTOL, "s {s}: complementarity gap {gap}");
    }
}

#[test]
fn what_cannot_be_done_is_refused_by_name() {
    let (u, v, z) = rippled_grid(8, 6);
    let values = PointsRef::from_flat(1, &z).unwrap();
    let c = increasing_u();
    for l in [-1.0, f64::NAN] {
        let e = constrained_surface_grid_smoothing_spline(
            values,
            (&u, &v),
            [Lambda::Given(1e-3), Lambda::Given(l)],
            &c,
        )
        .unwrap_err();
        assert!(matches!(e, Error::NegativeSmoothing { .. }), "{e}");
    }
    // λ = 0 is interpolation's weight, which the constrained program cannot take: named, with
    // the fix
    let e = constrained_surface_grid_smoothing_spline(
        values,
        (&u, &v),
        [Lambda::Given(0.0), Lambda::Gcv],
        &c,
    )
    .unwrap_err();
    assert!(matches!(e, Error::InvalidArgument { .. }), "{e}");
    assert!(e.to_string().contains("give λ > 0"), "{e}");
    assert_eq!(e.arg(), Some(crate::Arg::Lambda));
    let e = constrained_surface_grid_smoothing_condition(values, (&u, &v), -1.0, &c).unwrap_err();
    assert!(matches!(e, Error::NegativeSmoothing { .. }), "{e}");
    // points in space are not a table z(u, v)
    let xyz: Vec<f64> = z.iter().flat_map(|&w| [w, w, w]).collect();
    let e = constrained_surface_grid_smoothing_spline(
        PointsRef::from_flat(3, &xyz).unwrap(),
        (&u, &v),
        [Lambda::Gcv; 2],
        &c,
    )
    .unwrap_err();
    assert!(matches!(e, Error::Dimension { .. }), "{e}");
    // a residual the shape cannot reach: the least one is named
    let bounded = SurfaceShapeConstraints::new().with(SurfaceShape::AtMost(0.0));
    let e =
        constrained_surface_grid_smoothing_condition(values, (&u, &v), 1e-6, &bounded).unwrap_err();
    assert!(matches!(e, Error::InvalidArgument { .. }), "{e}");
    assert!(e.to_string().contains("give s ≥"), "{e}");
}
