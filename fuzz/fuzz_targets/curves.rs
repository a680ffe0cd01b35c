//! B-spline, Bezier and NURBS curve constructors and every operation, with hostile numbers,
//! sizes and parameters.
#![no_main]

#[path = "common.rs"]
mod common;

use arbitrary::Arbitrary;
use common::{Num, Size};
use lekalo::{BSplineCurve, BezierCurve, NurbsCurve, Points};
use libfuzzer_sys::fuzz_target;

#[derive(Debug, Arbitrary)]
struct Input {
    degree: Size,
    dim: u8,
    knots: Vec<Num>,
    sort_knots: bool,
    control: Vec<Num>,
    weights: Vec<Num>,
    ts: Vec<Num>,
    order: Size,
    times: Size,
    arc: [Num; 9],
    angles: [Num; 2],
}

fuzz_target!(|input: Input| {
    let dim = usize::from(input.dim % 5);
    let knots = common::maybe_sorted(&input.knots, input.sort_knots);
    let ctrl = common::floats(&input.control);
    let weights = common::floats(&input.weights);
    let Ok(points) = Points::from_flat(dim, ctrl.clone()) else {
        // still try the other constructors with the raw data
        let _ = Points::from_flat(dim.max(1), ctrl);
        return;
    };
    common::exercise_points(&points);
    let p = input.degree.0;
    if let Ok(c) = BSplineCurve::new(p, knots.clone(), points.clone()) {
        common::exercise_bspline(&c, &input.ts, input.order, input.times);
    }
    // a valid clamped knot vector, so that the operations (not only validation) get fuzzed
    if let Ok(kv) = lekalo::KnotVector::clamped_uniform(p, points.len()) {
        if let Ok(c) = BSplineCurve::from_knot_vector(p, kv, points.clone()) {
            common::exercise_bspline(&c, &input.ts, input.order, input.times);
        }
    }
    if let Ok(c) = BezierCurve::new(points.clone()) {
        common::exercise_bezier(&c, &input.ts, input.order);
    }
    if let Ok(c) = NurbsCurve::new(p, knots, points.clone(), weights.clone()) {
        common::exercise_nurbs(&c, &input.ts, input.order, input.times);
    }
    if let Ok(kv) = lekalo::KnotVector::clamped_uniform(p, points.len()) {
        if let Ok(c) = NurbsCurve::new(p, kv.into_vec(), points, weights) {
            common::exercise_nurbs(&c, &input.ts, input.order, input.times);
        }
    }
    let a = common::floats(&input.arc);
    let d = dim.clamp(1, 3);
    if let Ok(c) = NurbsCurve::circle(&a[0..d], &a[3..3 + d], &a[6..6 + d], a[8]) {
        common::exercise_nurbs(&c, &input.ts, input.order, input.times);
    }
    if let Ok(c) = NurbsCurve::circular_arc(
        &a[0..d],
        &a[3..3 + d],
        &a[6..6 + d],
        a[8],
        input.angles[0].0,
        input.angles[1].0,
    ) {
        common::exercise_nurbs(&c, &input.ts, input.order, input.times);
    }
    if let Ok(c) = NurbsCurve::arc_through_points(&a[0..d], &a[3..3 + d], &a[6..6 + d]) {
        common::exercise_nurbs(&c, &input.ts, input.order, input.times);
    }
});
