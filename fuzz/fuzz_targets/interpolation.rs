//! Interpolation entry points with hostile numbers and sizes: `CurveInterpolation` with every
//! parametrisation, knot placement and end condition (also at given parameters),
//! `SurfaceInterpolation`, `natural_cubic_spline` and `CubicHermite`.
#![no_main]

#[path = "common.rs"]
mod common;

use arbitrary::Arbitrary;
use common::{Num, Size};
use lekalo::{
    natural_cubic_spline, CubicHermite, CurveInterpolation, EndCondition, KnotPlacement,
    Parametrization, Points, SurfaceInterpolation, TangentEstimate,
};
use libfuzzer_sys::fuzz_target;

/// Interpolation solves a banded system per call; keep the point count modest so each input is
/// fast (sizes beyond this are the `TooLarge` checks, fuzzed in `curves`).
const MAX_POINTS: usize = 64;

#[derive(Debug, Arbitrary)]
struct Input {
    coords: Vec<Num>,
    dim: u8,
    degree: Size,
    param: u8,
    exponent: Num,
    knots: u8,
    end: u8,
    derivs: [Num; 6],
    drop: bool,
    params: Vec<Num>,
    sort: bool,
    nu: u8,
    nv: u8,
    degree_v: Size,
    estimate: u8,
    tension: Num,
    ts: Vec<Num>,
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
    let view = points.as_view();
    let parametrization = match input.param % 4 {
        0 => Parametrization::Uniform,
        1 => Parametrization::ChordLength,
        2 => Parametrization::Centripetal,
        _ => Parametrization::Exponent(input.exponent.0),
    };
    let placement = match input.knots % 4 {
        0 => KnotPlacement::Auto,
        1 => KnotPlacement::Averaged,
        2 => KnotPlacement::Uniform,
        _ => KnotPlacement::AtParameters,
    };
    let d = common::floats(&input.derivs);
    let (start, end) = (d[..dim.min(3)].to_vec(), d[3..3 + dim.min(3)].to_vec());
    let end_condition = match input.end % 5 {
        0 => EndCondition::Free,
        1 => EndCondition::FirstDerivatives { start, end },
        2 => EndCondition::SecondDerivatives { start, end },
        3 => EndCondition::Natural,
        _ => EndCondition::Periodic,
    };
    let degree = input.degree.0;
    let interp = CurveInterpolation::new(degree)
        .parametrization(parametrization)
        .knot_placement(placement)
        .end_condition(end_condition)
        .drop_duplicates(input.drop);
    let finite = points.iter().all(|q| q.iter().all(|x| x.is_finite()));
    let parameters = common::maybe_sorted(&input.params, input.sort);
    for c in [interp.interpolate(view), interp.interpolate_at(view, &parameters)]
        .into_iter()
        .flatten()
    {
        if finite {
            common::assert_no_nan("interpolated control points", c.control_points().as_slice());
        }
        common::exercise_bspline(&c, &input.ts, Size(1), Size(1));
    }
    if let Ok(c) = natural_cubic_spline(&parameters, view) {
        if finite {
            common::assert_no_nan("natural_cubic_spline", c.control_points().as_slice());
        }
        common::exercise_bspline(&c, &input.ts, Size(2), Size(1));
    }
    let estimate = match input.estimate % 4 {
        0 => TangentEstimate::FiniteDifference,
        1 => TangentEstimate::CatmullRom,
        2 => TangentEstimate::Cardinal {
            tension: input.tension.0,
        },
        _ => TangentEstimate::Monotone,
    };
    let hermites = [
        CubicHermite::from_points(view, parametrization, estimate),
        CubicHermite::function(&parameters, view, estimate),
        CubicHermite::new(parameters.clone(), points.clone(), points.clone()),
    ];
    for h in hermites.into_iter().flatten() {
        if finite {
            common::assert_no_nan("CubicHermite tangents", h.tangents().as_slice());
        }
        for t in common::params(h.domain(), &input.ts) {
            if let Ok(p) = h.eval(t) {
                common::assert_no_nan("CubicHermite::eval", &p);
            }
        }
        let b = h.to_bspline();
        let _ = b.eval(b.domain().0);
        let _ = h.to_bezier_segments();
    }
    let (nu, nv) = (usize::from(input.nu % 12), usize::from(input.nv % 12));
    let fit = SurfaceInterpolation::new(degree, input.degree_v.0).parametrization(parametrization);
    if let Ok(s) = fit.interpolate(view, nu, nv) {
        if finite {
            common::assert_no_nan("SurfaceInterpolation", s.control_points().as_slice());
        }
        common::exercise_bspline_surface(&s, &input.ts, Size(1));
    }
});
