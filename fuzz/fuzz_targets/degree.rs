//! Bezier and B-spline degree change with hostile numbers and sizes: `elevate_degree`,
//! `real_degree`, `change_degree`, `reduce_degree_exact`, `reduce_degree_approx`,
//! `ElevationPlan`, B-spline `elevate_degree` / `change_degree` / `reduce_degree_approx`, and
//! Bezier surface `change_degree`.
#![no_main]

#[path = "common.rs"]
mod common;

use arbitrary::Arbitrary;
use common::{Num, Size};
use lekalo::{
    BSplineCurve, BezierCurve, BezierSurface, ElevationPlan, EndConditions, KnotVector, Points,
};
use libfuzzer_sys::fuzz_target;

/// Control points per object: the degree-change algorithms are quadratic (the exact-rational
/// matrix form worse), so larger inputs only slow the fuzzer down.
const MAX_POINTS: usize = 48;
/// Degrees up to this are exercised; absurd ones (≥ 2^31, which must be refused quickly) too;
/// those in between are legitimate but slow, and skipped.
const MAX_DEGREE: usize = 64;

fn size(s: Size) -> Option<usize> {
    (s.0 <= MAX_DEGREE || s.0 >= 1 << 31).then_some(s.0)
}

#[derive(Debug, Arbitrary)]
struct Input {
    coords: Vec<Num>,
    dim: u8,
    by: Size,
    target: Size,
    tolerance: Num,
    ends: u8,
    degree: Size,
    net: (u8, u8),
    new: (Size, Size),
}

fn check_bezier(what: &str, finite: bool, c: &BezierCurve) {
    if finite {
        common::assert_no_nan(what, c.control_points().as_slice());
    }
}

fn check_bspline(what: &str, finite: bool, c: &BSplineCurve) {
    if finite {
        common::assert_no_nan(what, c.control_points().as_slice());
    }
}

fuzz_target!(|input: Input| {
    let dim = usize::from(input.dim % 4).max(1);
    let ctrl = common::floats(&input.coords);
    if ctrl.len() > MAX_POINTS * dim {
        return;
    }
    let Ok(points) = Points::from_flat(dim, ctrl[..ctrl.len() - ctrl.len() % dim].to_vec()) else {
        return;
    };
    let finite = points.iter().all(|q| q.iter().all(|x| x.is_finite()));
    let (Some(by), Some(target)) = (size(input.by), size(input.target)) else {
        return;
    };
    let tol = input.tolerance.0;
    let ends = match input.ends % 3 {
        0 => EndConditions::Free,
        1 => EndConditions::Points,
        _ => EndConditions::Tangents,
    };
    if let Ok(c) = BezierCurve::new(points.clone()) {
        if let Ok(e) = c.elevate_degree(by) {
            check_bezier("elevate_degree", finite, &e);
        }
        let _ = c.real_degree();
        let _ = c.real_degree_with_tolerance(tol);
        let _ = c.real_degree_monomial(tol);
        if let Ok(e) = c.change_degree(target) {
            check_bezier("change_degree", finite, &e);
        }
        let _ = c.change_degree_with_tolerance(target, tol);
        if target <= 24 && c.degree() <= 24 {
            let _ = c.change_degree_by_matrix(target, tol);
        }
        check_bezier("reduce_degree_exact", finite, &c.reduce_degree_exact());
        if let Ok(r) = c.reduce_degree_approx(target, ends) {
            check_bezier("reduce_degree_approx", finite, &r.curve);
        }
        if let Ok(plan) = ElevationPlan::new(c.degree(), c.degree().saturating_add(by)) {
            if let Ok(e) = plan.apply(&c) {
                check_bezier("ElevationPlan::apply", finite, &e);
            }
        }
        if let Ok(plan) = ElevationPlan::new(c.degree(), target) {
            let mut out = vec![0.0; (target.min(MAX_DEGREE) + 1) * dim];
            let _ = plan.apply_into(points.as_slice(), dim, &mut out);
            let _ = plan.apply(&c);
        }
    }
    if let Some(p) = size(input.degree) {
        if let Ok(kv) = KnotVector::clamped_uniform(p, points.len()) {
            if let Ok(c) = BSplineCurve::from_knot_vector(p, kv, points.clone()) {
                if let Ok(e) = c.elevate_degree(by) {
                    check_bspline("BSplineCurve::elevate_degree", finite, &e);
                }
                if let Ok(e) = c.change_degree(target) {
                    check_bspline("BSplineCurve::change_degree", finite, &e);
                }
                if let Ok(r) = c.reduce_degree_approx(target, ends) {
                    check_bspline("BSplineCurve::reduce_degree_approx", finite, &r.curve);
                }
            }
        }
    }
    let net = (usize::from(input.net.0 % 8), usize::from(input.net.1 % 8));
    if let (Ok(s), Some(nu), Some(nv)) = (
        BezierSurface::new(points.clone(), net),
        size(input.new.0),
        size(input.new.1),
    ) {
        if let Ok(e) = s.change_degree(nu, nv) {
            if finite {
                common::assert_no_nan("BezierSurface::change_degree", e.control_points().as_slice());
            }
        }
        let _ = s.elevate_degree(by, by);
        let _ = s.real_degrees_with_tolerance(tol);
    }
});
