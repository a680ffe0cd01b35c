//! Blending with hostile numbers and sizes: `JumpPolynomial`, `Deformation`, `BlendSpline`
//! with each built-in `LocalCurves` family, and `CornerTransition`.
#![no_main]

#[path = "common.rs"]
mod common;

use arbitrary::Arbitrary;
use common::{Num, Size};
use lekalo::{
    ArcParametrization, BezierCurve, BlendSpline, BlendSplineOptions, CircularArcs,
    CornerTransition, Deformation, JumpPolynomial, LocalCurves, Parabolas, ParametricCurve,
    Points, SplineParameters,
};
use libfuzzer_sys::fuzz_target;

/// Spline points / control points: blending evaluates every segment, so keep inputs modest.
const MAX_POINTS: usize = 32;
/// Continuity degrees and derivative orders up to this are exercised, plus absurd ones
/// (≥ 2^31, which must be refused quickly).
const MAX_ORDER: usize = 24;

fn size(s: Size) -> Option<usize> {
    (s.0 <= MAX_ORDER || s.0 >= 1 << 31).then_some(s.0)
}

#[derive(Debug, Arbitrary)]
struct Input {
    coords: Vec<Num>,
    dim: u8,
    split: u8,
    k: Size,
    order: Size,
    closed: bool,
    params: u8,
    family: u8,
    window: (Num, Num),
    us: Vec<Num>,
}

fn check_curve(what: &str, finite: bool, c: &dyn ParametricCurve, us: &[f64], order: usize) {
    let (a, b) = c.domain();
    let mut out = vec![0.0; c.dim() * (order.clamp(1, MAX_ORDER) + 1)];
    for t in common::params((a, b), &[]).into_iter().chain(us.iter().copied()) {
        for k in [0, 1, order] {
            if k > MAX_ORDER {
                let _ = c.eval_derivatives_into(t, k, &mut out);
                continue;
            }
            let n = c.dim() * (k + 1);
            if c.eval_derivatives_into(t, k, &mut out[..n]).is_ok() && finite && t.is_finite() {
                common::assert_no_nan(what, &out[..n]);
            }
        }
    }
}

fuzz_target!(|input: Input| {
    let us = common::floats(&input.us);
    let (Some(k), Some(order)) = (size(input.k), size(input.order)) else {
        return;
    };
    if let Ok(j) = JumpPolynomial::new(k) {
        let _ = j.bernstein_coefficients_f64();
        let _ = j.integral_to_half_f64();
        let mut out = vec![0.0; order.min(MAX_ORDER) + 1];
        for &u in us.iter().chain(&[0.0, 0.5, 1.0]) {
            if let Ok(v) = j.eval(u) {
                assert!(!v.is_nan() || u.is_nan(), "JumpPolynomial::eval({u}) = NaN");
            }
            if j.eval_derivatives(u, &mut out).is_ok() && u.is_finite() {
                common::assert_no_nan("JumpPolynomial::eval_derivatives", &out);
            }
        }
    }
    let dim = usize::from(input.dim % 3) + 1;
    let ctrl = common::floats(&input.coords);
    if ctrl.len() > MAX_POINTS * dim {
        return;
    }
    let Ok(points) = Points::from_flat(dim, ctrl[..ctrl.len() - ctrl.len() % dim].to_vec()) else {
        return;
    };
    let finite = points.iter().all(|q| q.iter().all(|x| x.is_finite()));
    let split = usize::from(input.split).min(points.len());
    let halves = (
        Points::from_flat(dim, points.as_slice()[..split * dim].to_vec()),
        Points::from_flat(dim, points.as_slice()[split * dim..].to_vec()),
    );
    if let (Ok(a), Ok(b)) = halves {
        if let (Ok(a), Ok(b)) = (BezierCurve::new(a), BezierCurve::new(b)) {
            if let Ok(d) = Deformation::new(&a, &b, k) {
                check_curve("Deformation", finite, &d, &us, order);
                let _ = d.eval_derivatives(0.5, order);
            }
            let (t0, t1) = (input.window.0 .0, input.window.1 .0);
            if let Ok(c) = CornerTransition::new(&a, t0, &b, t1, k) {
                let _ = c.window();
                let _ = c.window_lengths();
                let _ = c.eval_derivatives(c.domain().0, order);
                check_curve("CornerTransition", finite, &c, &us, order);
            }
        }
    }
    let parameters = match input.params % 3 {
        0 => SplineParameters::Uniform,
        1 => SplineParameters::ChordLength,
        _ => SplineParameters::Centripetal,
    };
    let local: &dyn LocalCurves = match input.family % 4 {
        0 => &Parabolas,
        1 => &CircularArcs {
            parametrization: ArcParametrization::UniformAngle,
        },
        2 => &CircularArcs {
            parametrization: ArcParametrization::RationalQuadratic,
        },
        _ => &CircularArcs {
            parametrization: ArcParametrization::GlobalAngle,
        },
    };
    let options = BlendSplineOptions {
        continuity: k,
        closed: input.closed,
        parameters,
    };
    if let Ok(s) = BlendSpline::new(points.as_view(), local, options) {
        check_curve("BlendSpline", finite, &s, &us, order);
        for i in 0..s.segment_count() {
            let _ = s.segment_derivatives(i, 0.5, order);
        }
        let _ = s.to_bezier_segments();
        if let Ok(n) = s.to_nurbs() {
            if finite {
                common::assert_no_nan("BlendSpline::to_nurbs", n.control_points().as_slice());
            }
        }
    }
});
