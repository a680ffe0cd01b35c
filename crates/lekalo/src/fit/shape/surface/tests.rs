//! Tests of the shape-constrained surface fits: the shapes hold (Bernstein conditions and dense
//! samples), inactive constraints change nothing, infeasible bounds are named, and the answer
//! meets the optimality (KKT) conditions of its quadratic program, checked by an independent
//! dense computation.

use super::cells::Space;
use super::*;
use crate::basis::{basis_funs_into, BasisScratch};
use crate::error::Error;
use crate::fit::{surface_grid_least_squares_at, surface_scattered_least_squares};
use crate::knots::KnotVector;
use crate::points::PointsRef;
use crate::{BSplineSurface, Direction};

/// A table rising in `u` and `v`, with a ripple in `u` strong enough to make the plain fit dip.
fn rippled_grid(nu: usize, nv: usize) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
    let u: Vec<f64> = (0..nu).map(|i| i as f64 / (nu - 1) as f64).collect();
    let v: Vec<f64> = (0..nv).map(|j| j as f64 / (nv - 1) as f64).collect();
    let mut z = Vec::with_capacity(nu * nv);
    for (i, &x) in u.iter().enumerate() {
        for (j, &y) in v.iter().enumerate() {
            let noise = 0.15 * ((7 * i + 3 * j) as f64 * 1.7).sin();
            z.push(x + 0.5 * y * y + 0.25 * (9.0 * x).sin() + noise);
        }
    }
    (u, v, z)
}

fn both_increasing() -> SurfaceShapeConstraints {
    SurfaceShapeConstraints::new()
        .with(SurfaceShape::Increasing(Direction::U))
        .with(SurfaceShape::Increasing(Direction::V))
}

/// Values on a dense grid of each constraint's region (the domain, or its box): every step
/// along `u` and along `v` of the right sign, every value within the bounds.
fn dense_check(s: &BSplineSurface, c: &SurfaceShapeConstraints, slack: f64) {
    let m = 121;
    let ((du0, du1), (dv0, dv1)) = s.domain();
    for constraint in &c.shapes {
        let [(u0, u1), (v0, v1)] = constraint.region_or([(du0, du1), (dv0, dv1)]);
        let us: Vec<f64> = (0..m)
            .map(|k| u0 + (u1 - u0) * k as f64 / (m - 1) as f64)
            .collect();
        let vs: Vec<f64> = (0..m)
            .map(|k| v0 + (v1 - v0) * k as f64 / (m - 1) as f64)
            .collect();
        let mut z = vec![0.0; m * m];
        s.eval_grid(&us, &vs, &mut z).unwrap();
        let shape = &constraint.shape;
        for i in 0..m {
            for j in 0..m {
                let here = z[i * m + j];
                let ok = match shape {
                    SurfaceShape::Increasing(Direction::U) if i + 1 < m => {
                        z[(i + 1) * m + j] >= here - slack
                    }
                    SurfaceShape::Decreasing(Direction::U) if i + 1 < m => {
                        z[(i + 1) * m + j] <= here + slack
                    }
                    SurfaceShape::Increasing(Direction::V) if j + 1 < m => {
                        z[i * m + j + 1] >= here - slack
                    }
                    SurfaceShape::Decreasing(Direction::V) if j + 1 < m => {
                        z[i * m + j + 1] <= here + slack
                    }
                    SurfaceShape::AtLeast(v) => here >= v - slack,
                    SurfaceShape::AtMost(v) => here <= v + slack,
                    _ => true,
                };
                assert!(ok, "{shape} broken at ({}, {}): {here}", us[i], vs[j]);
            }
        }
    }
}

/// The dense observation matrix of a grid (rows `(i, j)`, columns the net `k·n_v + l`).
fn grid_design(
    ku: &KnotVector,
    kv: &KnotVector,
    (p, q): (usize, usize),
    u: &[f64],
    v: &[f64],
) -> Vec<Vec<f64>> {
    let (ncu, ncv) = (ku.len() - p - 1, kv.len() - q - 1);
    let row_of = |k: &KnotVector, d: usize, n: usize, t: f64| {
        let mut s = BasisScratch::new(d);
        let span = k.span_unchecked(d, t);
        let mut b = vec![0.0; d + 1];
        basis_funs_into(k.as_slice(), d, span, t, &mut s, &mut b);
        let mut full = vec![0.0; n];
        full[span - d..=span].copy_from_slice(&b);
        full
    };
    let mut out = Vec::new();
    for &x in u {
        let a = row_of(ku, p, ncu, x);
        for &y in v {
            let b = row_of(kv, q, ncv, y);
            out.push(
                a.iter()
                    .flat_map(|ai| b.iter().map(move |bj| ai * bj))
                    .collect(),
            );
        }
    }
    out
}

/// The KKT conditions of `min ½‖Bc − z‖²` subject to `σ(b_cell(c) − v) ≥ 0`, checked densely:
/// every row feasible; the gradient `Bᵀ(Bc − z)` a non-negative combination of the rows within
/// `active` of their bound (non-negative least squares by projected gradient, a method
/// independent of the interior point), so that no feasible direction decreases the objective.
/// Returns the stationarity residual relative to `‖Bᵀz‖`.
fn kkt_residual(
    design: &[Vec<f64>],
    z: &[f64],
    s: &BSplineSurface,
    c: &SurfaceShapeConstraints,
    active: f64,
) -> f64 {
    kkt_residual_penalised(design, z, s, c, active, &[])
}

/// [`kkt_residual`] of `min ½‖Bc − z‖² + ½cᵀKc` with the dense penalty matrix `K` (none when
/// empty): the gradient `Bᵀ(Bc − z) + Kc`.
fn kkt_residual_penalised(
    design: &[Vec<f64>],
    z: &[f64],
    s: &BSplineSurface,
    c: &SurfaceShapeConstraints,
    active: f64,
    penalty: &[Vec<f64>],
) -> f64 {
    kkt_parts(design, z, s, c, active, penalty).0
}

/// The two parts of [`kkt_residual_penalised`]'s check: the stationarity residual, and the
/// complementarity gap `Σ λ_k g_k` of the multipliers found over the rows' slacks `g_k`,
/// relative to `½‖z‖²`. With rows counted active up to a slack `active`, a multiplier on a row
/// of positive slack is allowed; the gap bounds what that costs: the objective is within
/// `gap·½‖z‖²` (plus what the stationarity residual leaves) of the constrained minimum
/// (weak duality of the convex program).
fn kkt_parts(
    design: &[Vec<f64>],
    z: &[f64],
    s: &BSplineSurface,
    c: &SurfaceShapeConstraints,
    active: f64,
    penalty: &[Vec<f64>],
) -> (f64, f64) {
    let (ku, kv) = s.knots();
    let space = Space {
        degrees: s.degree(),
        knots: (ku.as_slice(), kv.as_slice()),
        net: s.net_size(),
    };
    let x = s.control_points().as_slice();
    let n = x.len();
    // gradient
    let mut grad = vec![0.0; n];
    let mut scale = vec![0.0; n];
    for (row, zk) in design.iter().zip(z) {
        let r: f64 = row.iter().zip(x).map(|(a, b)| a * b).sum::<f64>() - zk;
        for k in 0..n {
            grad[k] += row[k] * r;
            scale[k] += row[k] * zk;
        }
    }
    for (g, row) in grad.iter_mut().zip(penalty) {
        *g += row.iter().zip(x).map(|(a, b)| a * b).sum::<f64>();
    }
    // the active rows as dense vectors (σ·∂b/∂c)
    let mut rows: Vec<Vec<f64>> = Vec::new();
    let mut slacks: Vec<f64> = Vec::new();
    for constraint in &c.shapes {
        let shape = constraint.shape;
        let (sigma, level) = (shape.sign(), shape.level());
        for r in space.cell_rows(constraint) {
            let g = sigma * (r.eval(x) - level);
            assert!(g >= -1e-12, "{shape}: row infeasible by {g}");
            let mut dense = vec![0.0; n];
            for &(o, w) in &r.terms {
                dense[r.first + o] = sigma * w;
            }
            let norm = dense.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
            if g <= active * norm {
                rows.push(dense.iter().map(|v| v / norm).collect());
                slacks.push(g / norm);
            }
        }
    }
    // min ½‖Aᵀλ − grad‖² over λ ≥ 0 by accelerated projected gradient
    let m = rows.len();
    // the step: Gershgorin's bound on the largest eigenvalue of AAᵀ, max_i Σ_j |r_i·r_j| ≤
    // max_i Σ_k |r_ik| Σ_j |r_jk|, far below the sum of the rows' squares on banded rows
    let lip = {
        let mut column = vec![0.0; n];
        for r in &rows {
            for (ck, rk) in column.iter_mut().zip(r) {
                *ck += rk.abs();
            }
        }
        rows.iter()
            .map(|r| r.iter().zip(&column).map(|(a, b)| a.abs() * b).sum::<f64>())
            .fold(f64::MIN_POSITIVE, f64::max)
    };
    let mut lam = vec![0.0; m];
    let mut y = lam.clone();
    let mut t = 1.0_f64;
    let at = |l: &[f64]| -> Vec<f64> {
        let mut out = vec![0.0; n];
        for (r, li) in rows.iter().zip(l) {
            for k in 0..n {
                out[k] += r[k] * li;
            }
        }
        out
    };
    for _ in 0..20000 {
        let res: Vec<f64> = at(&y).iter().zip(&grad).map(|(a, g)| a - g).collect();
        let next: Vec<f64> = rows
            .iter()
            .zip(&y)
            .map(|(r, yi)| {
                (yi - r.iter().zip(&res).map(|(a, b)| a * b).sum::<f64>() / lip).max(0.0)
            })
            .collect();
        // adaptive restart (O'Donoghue & Candès 2015): the momentum is dropped when it points
        // uphill, which keeps the accelerated rate on the degenerate faces of many active rows
        let uphill: f64 = y
            .iter()
            .zip(&next)
            .zip(&lam)
            .map(|((yi, ni), li)| (yi - ni) * (ni - li))
            .sum();
        if uphill > 0.0 {
            t = 1.0;
        }
        let t1 = 0.5 * (1.0 + (1.0 + 4.0 * t * t).sqrt());
        y = next
            .iter()
            .zip(&lam)
            .map(|(a, b)| a + (t - 1.0) / t1 * (a - b))
            .collect();
        lam = next;
        t = t1;
    }
    let res = at(&lam)
        .iter()
        .zip(&grad)
        .map(|(a, g)| (a - g) * (a - g))
        .sum::<f64>()
        .sqrt();
    let gap: f64 = lam.iter().zip(&slacks).map(|(l, g)| l * g).sum();
    (
        res / scale.iter().map(|v| v * v).sum::<f64>().sqrt(),
        gap / (0.5 * z.iter().map(|v| v * v).sum::<f64>()),
    )
}

#[test]
fn monotone_grid_fit_keeps_its_shape_and_is_optimal() {
    let (u, v, z) = rippled_grid(16, 12);
    for (p, q, ncu, ncv) in [(2, 2, 6, 5), (1, 1, 7, 5), (3, 2, 7, 5)] {
        let (ku, kv) = (
            KnotVector::clamped_uniform(p, ncu).unwrap(),
            KnotVector::clamped_uniform(q, ncv).unwrap(),
        );
        let values = PointsRef::from_flat(1, &z).unwrap();
        let c = both_increasing();
        let free =
            surface_grid_least_squares_at(values, (16, 12), (p, q), (&u, &v), (&ku, &kv)).unwrap();
        let before = surface_shape_violations(&free, &c).unwrap();
        assert!(
            before[0] > 1e-3,
            "the plain fit should dip in u: {before:?}"
        );
        let s = constrained_surface_grid_least_squares(
            values,
            (16, 12),
            (p, q),
            (&u, &v),
            (&ku, &kv),
            &c,
        )
        .unwrap();
        assert_eq!(surface_shape_violations(&s, &c).unwrap(), vec![0.0, 0.0]);
        dense_check(&s, &c, 0.0);
        // optimal: the KKT conditions, and its residual no smaller than the plain fit's
        let design = grid_design(&ku, &kv, (p, q), &u, &v);
        let kkt = kkt_residual(&design, &z, &s, &c, 1e-7);
        assert!(
            kkt < 1e-9,
            "degrees ({p}, {q}): stationarity residual {kkt}"
        );
        let rss = |s: &BSplineSurface| {
            let mut out = vec![0.0; z.len()];
            s.eval_grid(&u, &v, &mut out).unwrap();
            out.iter()
                .zip(&z)
                .map(|(a, b)| (a - b) * (a - b))
                .sum::<f64>()
        };
        assert!(rss(&s) >= rss(&free), "{} < {}", rss(&s), rss(&free));
        // a feasible point nearby is no better: the constrained fit moved a little towards the
        // plain one breaks a constraint
        let mix: Vec<f64> = s
            .control_points()
            .as_slice()
            .iter()
            .zip(free.control_points().as_slice())
            .map(|(a, b)| a + 0.01 * (b - a))
            .collect();
        let moved = BSplineSurface::from_knot_vectors(
            p,
            q,
            ku.clone(),
            kv.clone(),
            crate::Points::from_flat(1, mix).unwrap(),
            (ncu, ncv),
        )
        .unwrap();
        assert!(surface_shape_violations(&moved, &c)
            .unwrap()
            .iter()
            .any(|v| *v > 0.0));
    }
}

#[test]
fn a_kkt_check_refuses_a_feasible_point_that_is_not_optimal() {
    // the check itself: a surface that keeps the shapes but is not the optimum fails it
    let (u, v, z) = rippled_grid(16, 12);
    let (ku, kv) = (
        KnotVector::clamped_uniform(2, 6).unwrap(),
        KnotVector::clamped_uniform(2, 5).unwrap(),
    );
    let values = PointsRef::from_flat(1, &z).unwrap();
    let c = both_increasing();
    let s =
        constrained_surface_grid_least_squares(values, (16, 12), (2, 2), (&u, &v), (&ku, &kv), &c)
            .unwrap();
    let shrunk: Vec<f64> = s
        .control_points()
        .as_slice()
        .iter()
        .map(|a| 0.9 * a)
        .collect();
    let worse = BSplineSurface::from_knot_vectors(
        2,
        2,
        ku.clone(),
        kv.clone(),
        crate::Points::from_flat(1, shrunk).unwrap(),
        (6, 5),
    )
    .unwrap();
    assert_eq!(
        surface_shape_violations(&worse, &c).unwrap(),
        vec![0.0, 0.0]
    );
    let design = grid_design(&ku, &kv, (2, 2), &u, &v);
    assert!(kkt_residual(&design, &z, &worse, &c, 1e-7) > 1e-3);
}

#[test]
fn inactive_constraints_return_the_plain_fit() {
    let u: Vec<f64> = (0..10).map(|i| i as f64 / 9.0).collect();
    let v: Vec<f64> = (0..8).map(|j| j as f64 / 7.0).collect();
    let z: Vec<f64> = u
        .iter()
        .flat_map(|&x| v.iter().map(move |&y| 1.0 + x + x * y + 0.3 * y))
        .collect();
    let (ku, kv) = (
        KnotVector::clamped_uniform(3, 6).unwrap(),
        KnotVector::clamped_uniform(2, 4).unwrap(),
    );
    let values = PointsRef::from_flat(1, &z).unwrap();
    let c = both_increasing()
        .with(SurfaceShape::AtLeast(0.5))
        .with(SurfaceShape::AtMost(4.0));
    let free =
        surface_grid_least_squares_at(values, (10, 8), (3, 2), (&u, &v), (&ku, &kv)).unwrap();
    let s =
        constrained_surface_grid_least_squares(values, (10, 8), (3, 2), (&u, &v), (&ku, &kv), &c)
            .unwrap();
    for (a, b) in s
        .control_points()
        .as_slice()
        .iter()
        .zip(free.control_points().as_slice())
    {
        assert!((a - b).abs() <= 1e-12, "{a} vs {b}");
    }
    // scattered too
    let data: Vec<f64> = (0..150)
        .flat_map(|k| {
            let (x, y) = (
                (k as f64 * 0.618_034).fract(),
                (k as f64 * 0.414_214).fract(),
            );
            [x, y, 1.0 + x + x * y + 0.3 * y]
        })
        .collect();
    let pts = PointsRef::from_flat(3, &data).unwrap();
    let free = surface_scattered_least_squares(pts, None, (3, 2), (&ku, &kv), 0.0).unwrap();
    let f = constrained_surface_scattered_least_squares(pts, None, (3, 2), (&ku, &kv), 0.0, &c)
        .unwrap();
    assert_eq!(f, free);
}

#[test]
fn bounds_hold_on_the_grid_and_on_scattered_data() {
    let (u, v, z) = rippled_grid(16, 12);
    let (ku, kv) = (
        KnotVector::clamped_uniform(2, 6).unwrap(),
        KnotVector::clamped_uniform(2, 5).unwrap(),
    );
    let values = PointsRef::from_flat(1, &z).unwrap();
    let c = SurfaceShapeConstraints::new()
        .with(SurfaceShape::AtLeast(0.0))
        .with(SurfaceShape::AtMost(1.2));
    let free =
        surface_grid_least_squares_at(values, (16, 12), (2, 2), (&u, &v), (&ku, &kv)).unwrap();
    let before = surface_shape_violations(&free, &c).unwrap();
    assert!(before.iter().all(|v| *v > 1e-2), "{before:?}");
    let s =
        constrained_surface_grid_least_squares(values, (16, 12), (2, 2), (&u, &v), (&ku, &kv), &c)
            .unwrap();
    assert_eq!(surface_shape_violations(&s, &c).unwrap(), vec![0.0, 0.0]);
    dense_check(&s, &c, 0.0);
    let design = grid_design(&ku, &kv, (2, 2), &u, &v);
    assert!(kkt_residual(&design, &z, &s, &c, 1e-7) < 1e-9);
    // scattered, with weights and with a penalty, decreasing in v and non-negative
    let data: Vec<f64> = (0..300)
        .flat_map(|k| {
            let (x, y) = (
                (k as f64 * 0.618_034).fract(),
                (k as f64 * 0.414_214).fract(),
            );
            [x, y, x * (1.0 - y) + 0.2 * (31.0 * k as f64).sin()]
        })
        .collect();
    let w: Vec<f64> = (0..300).map(|k| 1.0 + (k % 3) as f64).collect();
    let pts = PointsRef::from_flat(3, &data).unwrap();
    let c = SurfaceShapeConstraints::new()
        .with(SurfaceShape::Decreasing(Direction::V))
        .with(SurfaceShape::AtLeast(0.0));
    let k = KnotVector::new(vec![0.0, 0.0, 0.0, 0.0, 0.4, 0.7, 1.0, 1.0, 1.0, 1.0]).unwrap();
    for penalty in [0.0, 1e-2] {
        let free =
            surface_scattered_least_squares(pts, Some(&w), (3, 3), (&k, &k), penalty).unwrap();
        assert!(surface_shape_violations(&free.surface, &c)
            .unwrap()
            .iter()
            .any(|v| *v > 1e-3));
        let f = constrained_surface_scattered_least_squares(
            pts,
            Some(&w),
            (3, 3),
            (&k, &k),
            penalty,
            &c,
        )
        .unwrap();
        assert_eq!(
            surface_shape_violations(&f.surface, &c).unwrap(),
            vec![0.0, 0.0]
        );
        dense_check(&f.surface, &c, 0.0);
        assert!(f.weighted_rss >= free.weighted_rss);
        assert_eq!(f.residuals.len(), 300);
    }
}

#[test]
fn contradictory_or_unusable_constraints_are_named() {
    let (u, v, z) = rippled_grid(8, 8);
    let k = KnotVector::clamped_uniform(2, 4).unwrap();
    let values = PointsRef::from_flat(1, &z).unwrap();
    let c = SurfaceShapeConstraints::new()
        .with(SurfaceShape::AtLeast(2.0))
        .with(SurfaceShape::Increasing(Direction::U))
        .with(SurfaceShape::AtMost(1.0));
    let e = constrained_surface_grid_least_squares(values, (8, 8), (2, 2), (&u, &v), (&k, &k), &c)
        .unwrap_err();
    assert_eq!(
        e,
        Error::InfeasibleConstraints {
            conflicting: vec!["min 2".into(), "max 1".into()]
        }
    );
    // equal bounds leave one surface: the constant
    let c = SurfaceShapeConstraints::new()
        .with(SurfaceShape::AtLeast(0.5))
        .with(SurfaceShape::AtMost(0.5));
    let s = constrained_surface_grid_least_squares(values, (8, 8), (2, 2), (&u, &v), (&k, &k), &c)
        .unwrap();
    assert!(s
        .control_points()
        .as_slice()
        .iter()
        .all(|c| (c - 0.5).abs() < 1e-9));
    let c = SurfaceShapeConstraints::new().with(SurfaceShape::AtLeast(f64::NAN));
    assert!(matches!(
        constrained_surface_grid_least_squares(values, (8, 8), (2, 2), (&u, &v), (&k, &k), &c),
        Err(Error::NonFinite { .. })
    ));
    let points: Vec<f64> = z.iter().flat_map(|v| [*v, *v]).collect();
    assert!(matches!(
        constrained_surface_grid_least_squares(
            PointsRef::from_flat(2, &points).unwrap(),
            (8, 8),
            (2, 2),
            (&u, &v),
            (&k, &k),
            &both_increasing()
        ),
        Err(Error::Dimension { .. })
    ));
}

#[test]
fn the_condition_is_exact_for_bilinear_cells_and_sufficient_above() {
    // degree (1, 1): the coefficients are the corner values, so the least coefficient is the
    // surface's minimum; degree (2, 2): a surface can be positive with a negative coefficient
    let k1 = KnotVector::clamped_uniform(1, 2).unwrap();
    let s = BSplineSurface::from_knot_vectors(
        1,
        1,
        k1.clone(),
        k1,
        crate::Points::from_flat(1, vec![0.3, -0.2, 0.5, 0.1]).unwrap(),
        (2, 2),
    )
    .unwrap();
    let c = SurfaceShapeConstraints::new().with(SurfaceShape::AtLeast(0.0));
    assert!((surface_shape_violations(&s, &c).unwrap()[0] - 0.2).abs() < 1e-15);
    let k2 = KnotVector::clamped_uniform(2, 3).unwrap();
    // z = (2u − 1)² + 0.1 in u, constant in v: Bernstein (1.1, −0.9, 1.1), minimum 0.1
    let net: Vec<f64> = [1.1, -0.9, 1.1].iter().flat_map(|&a| [a; 3]).collect();
    let s = BSplineSurface::from_knot_vectors(
        2,
        2,
        k2.clone(),
        k2,
        crate::Points::from_flat(1, net).unwrap(),
        (3, 3),
    )
    .unwrap();
    assert!(surface_shape_violations(&s, &c).unwrap()[0] > 0.0);
    dense_check(&s, &c, 0.0);
}

/// A table that falls in `u` on `[0, 0.4]` and rises after, with a ripple: increasing in `u`
/// holds for the data only on the right part of the domain.
fn valley_grid(nu: usize, nv: usize) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
    let u: Vec<f64> = (0..nu).map(|i| i as f64 / (nu - 1) as f64).collect();
    let v: Vec<f64> = (0..nv).map(|j| j as f64 / (nv - 1) as f64).collect();
    let mut z = Vec::with_capacity(nu * nv);
    for &x in &u {
        for &y in &v {
            z.push((x - 0.4) * (x - 0.4) + 0.3 * y + 0.08 * (23.0 * x + 5.0 * y).sin());
        }
    }
    (u, v, z)
}

#[test]
fn a_shape_on_a_box_holds_there_and_leaves_the_rest_free() {
    let (u, v, z) = valley_grid(21, 11);
    let values = PointsRef::from_flat(1, &z).unwrap();
    // a box whose u-edges cut knot cells (knots at multiples of 1/6), and a line v = 0.3
    let boxed = [((0.45, 1.0), (0.1, 0.9)), ((0.5, 0.95), (0.3, 0.3))];
    for (p, q) in [(1, 1), (2, 2), (3, 2)] {
        let (ku, kv) = (
            KnotVector::clamped_uniform(p, 6 + p).unwrap(),
            KnotVector::clamped_uniform(q, 4 + q).unwrap(),
        );
        let free =
            surface_grid_least_squares_at(values, (21, 11), (p, q), (&u, &v), (&ku, &kv)).unwrap();
        for (bu, bv) in boxed {
            let c = SurfaceShapeConstraints::new().with_on(
                SurfaceShape::Increasing(Direction::U),
                bu,
                bv,
            );
            assert!(
                surface_shape_violations(&free, &c).unwrap()[0] > 1e-3,
                "the plain fit should dip in u inside the box"
            );
            let s = constrained_surface_grid_least_squares(
                values,
                (21, 11),
                (p, q),
                (&u, &v),
                (&ku, &kv),
                &c,
            )
            .unwrap();
            assert_eq!(surface_shape_violations(&s, &c).unwrap(), vec![0.0]);
            dense_check(&s, &c, 0.0);
            // optimal for the rows of the box alone
            let design = grid_design(&ku, &kv, (p, q), &u, &v);
            let kkt = kkt_residual(&design, &z, &s, &c, 1e-7);
            assert!(kkt < 1e-9, "degrees ({p}, {q}), box {bu:?} × {bv:?}: {kkt}");
            // outside the box the surface still falls in u, as the data do
            let (mut a, mut b) = ([0.0], [0.0]);
            s.eval_into(0.05, 0.5, &mut a).unwrap();
            s.eval_into(0.3, 0.5, &mut b).unwrap();
            assert!(
                b[0] < a[0],
                "left of the box the fit should fall: {a:?} {b:?}"
            );
            // and the whole-domain constraint is a different, stricter problem
            let whole = SurfaceShapeConstraints::new().with(SurfaceShape::Increasing(Direction::U));
            assert!(surface_shape_violations(&s, &whole).unwrap()[0] > 0.0);
        }
    }
}

#[test]
fn a_box_the_plain_fit_already_keeps_returns_it_unchanged() {
    let (u, v, z) = valley_grid(21, 11);
    let values = PointsRef::from_flat(1, &z).unwrap();
    let (ku, kv) = (
        KnotVector::clamped_uniform(3, 9).unwrap(),
        KnotVector::clamped_uniform(2, 6).unwrap(),
    );
    let free =
        surface_grid_least_squares_at(values, (21, 11), (3, 2), (&u, &v), (&ku, &kv)).unwrap();
    // the values lie in [-0.1, 0.8], rising in u right of the valley's floor
    let c = SurfaceShapeConstraints::new()
        .with_on(SurfaceShape::AtMost(2.0), (0.0, 0.5), (0.0, 1.0))
        .with_on(SurfaceShape::AtLeast(-0.5), (0.2, 0.9), (0.1, 0.3));
    assert_eq!(surface_shape_violations(&free, &c).unwrap(), vec![0.0, 0.0]);
    let s =
        constrained_surface_grid_least_squares(values, (21, 11), (3, 2), (&u, &v), (&ku, &kv), &c)
            .unwrap();
    assert_eq!(s, free);
}

#[test]
fn bounds_on_boxes_conflict_only_where_the_boxes_meet() {
    let (u, v, z) = valley_grid(9, 7);
    let values = PointsRef::from_flat(1, &z).unwrap();
    let k = KnotVector::clamped_uniform(1, 4).unwrap();
    let fit = |c: &SurfaceShapeConstraints| {
        constrained_surface_grid_least_squares(values, (9, 7), (1, 1), (&u, &v), (&k, &k), c)
    };
    // min 1 on the left third, max 0 on the right third: a surface can do both
    let apart = SurfaceShapeConstraints::new()
        .with_on(SurfaceShape::AtLeast(1.0), (0.0, 1.0 / 3.0), (0.0, 1.0))
        .with_on(SurfaceShape::AtMost(0.0), (2.0 / 3.0, 1.0), (0.0, 1.0));
    let s = fit(&apart).unwrap();
    assert_eq!(
        surface_shape_violations(&s, &apart).unwrap(),
        vec![0.0, 0.0]
    );
    dense_check(&s, &apart, 0.0);
    // boxes that share the line u = 0.5 cannot
    let meet = SurfaceShapeConstraints::new()
        .with_on(SurfaceShape::AtLeast(1.0), (0.0, 0.5), (0.0, 1.0))
        .with_on(SurfaceShape::AtMost(0.0), (0.5, 1.0), (0.0, 0.5));
    assert_eq!(
        fit(&meet).unwrap_err(),
        Error::InfeasibleConstraints {
            conflicting: vec![
                "min 1 on [0, 0.5] × [0, 1]".into(),
                "max 0 on [0.5, 1] × [0, 0.5]".into()
            ]
        }
    );
    // boxes that leave the domain, or run backwards, are named with the fix
    for (bu, bv, words) in [
        (
            (0.0, 1.5),
            (0.0, 1.0),
            "leaves the domain [0, 1] of the fit in u",
        ),
        ((0.0, 1.0), (0.8, 0.2), "the v range [0.8, 0.2]"),
    ] {
        let c = SurfaceShapeConstraints::new().with_on(SurfaceShape::AtLeast(0.0), bu, bv);
        let e = fit(&c).unwrap_err().to_string();
        assert!(e.contains(words), "{e}");
    }
    let c = SurfaceShapeConstraints::new().with_on(
        SurfaceShape::AtLeast(0.0),
        (f64::NAN, 1.0),
        (0.0, 1.0),
    );
    assert!(matches!(fit(&c), Err(Error::NonFinite { .. })));
}

#[test]
fn a_monotone_surface_between_boxed_bounds_that_contradict_it_is_named() {
    // at least 1 on the left, at most 0 on the right, and increasing in u: no surface does all
    let (u, v, z) = valley_grid(9, 7);
    let values = PointsRef::from_flat(1, &z).unwrap();
    let k = KnotVector::clamped_uniform(2, 5).unwrap();
    let c = SurfaceShapeConstraints::new()
        .with_on(SurfaceShape::AtLeast(1.0), (0.0, 0.25), (0.0, 1.0))
        .with_on(SurfaceShape::AtMost(0.0), (0.75, 1.0), (0.0, 1.0))
        .with(SurfaceShape::Increasing(Direction::U));
    let e = constrained_surface_grid_least_squares(values, (9, 7), (2, 2), (&u, &v), (&k, &k), &c)
        .unwrap_err();
    let Error::InfeasibleConstraints { conflicting } = &e else {
        panic!("expected the conflicting constraints, got {e}");
    };
    assert!(
        conflicting.len() >= 2
            && conflicting
                .iter()
                .all(|w| (0..3).any(|i| c.describe(i) == *w)),
        "{conflicting:?}"
    );
}

mod smoothing;
mod weights;
