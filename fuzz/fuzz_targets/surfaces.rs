//! B-spline, NURBS and Bezier surface constructors and operations with hostile input.
#![no_main]

#[path = "common.rs"]
mod common;

use arbitrary::Arbitrary;
use common::{Num, Size};
use lekalo::{BSplineSurface, BezierSurface, KnotVector, NurbsSurface, Points};
use libfuzzer_sys::fuzz_target;

#[derive(Debug, Arbitrary)]
struct Input {
    degree_u: Size,
    degree_v: Size,
    net: (Size, Size),
    dim: u8,
    knots_u: Vec<Num>,
    knots_v: Vec<Num>,
    sort: bool,
    control: Vec<Num>,
    weights: Vec<Num>,
    uv: Vec<Num>,
    order: Size,
}

fuzz_target!(|input: Input| {
    let dim = usize::from(input.dim % 4).max(1);
    let Ok(points) = Points::from_flat(dim, common::floats(&input.control)) else {
        return;
    };
    let (pu, pv) = (input.degree_u.0, input.degree_v.0);
    let net = (input.net.0 .0, input.net.1 .0);
    let ku = common::maybe_sorted(&input.knots_u, input.sort);
    let kv = common::maybe_sorted(&input.knots_v, input.sort);
    let w = common::floats(&input.weights);
    if let Ok(s) = BSplineSurface::new(pu, pv, ku.clone(), kv.clone(), points.clone(), net) {
        common::exercise_bspline_surface(&s, &input.uv, input.order);
    }
    if let Ok(s) = NurbsSurface::new(pu, pv, ku, kv, points.clone(), w.clone(), net) {
        common::exercise_nurbs_surface(&s, &input.uv, input.order);
    }
    if let Ok(s) = BezierSurface::new(points.clone(), net) {
        common::exercise_bezier_surface(&s, &input.uv, input.order);
    }
    // valid clamped knots for a net that fits the data, so that evaluation gets fuzzed
    let n = points.len();
    let nu = (net.0 % 6).clamp(1, n.max(1));
    let nv = n / nu;
    if nv == 0 || nu * nv != n {
        return;
    }
    let (pu, pv) = (pu % nu.max(1), pv % nv.max(1));
    if let (Ok(a), Ok(b)) = (
        KnotVector::clamped_uniform(pu, nu),
        KnotVector::clamped_uniform(pv, nv),
    ) {
        if let Ok(s) = BSplineSurface::from_knot_vectors(
            pu,
            pv,
            a.clone(),
            b.clone(),
            points.clone(),
            (nu, nv),
        ) {
            common::exercise_bspline_surface(&s, &input.uv, input.order);
            let _ = NurbsSurface::from_bspline(&s).eval(0.5, 0.5);
        }
        if let Ok(s) = NurbsSurface::new(
            pu,
            pv,
            a.into_vec(),
            b.into_vec(),
            points.clone(),
            w,
            (nu, nv),
        ) {
            common::exercise_nurbs_surface(&s, &input.uv, input.order);
        }
    }
    if let Ok(s) = BezierSurface::new(points, (nu, nv)) {
        common::exercise_bezier_surface(&s, &input.uv, input.order);
    }
});
