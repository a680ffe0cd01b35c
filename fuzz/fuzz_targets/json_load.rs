//! Loads every JSON object lekalo deserialises (through the validating constructors) from
//! arbitrary bytes, then evaluates and inspects whatever loaded.
#![no_main]

#[path = "common.rs"]
mod common;

use common::{Num, Size};
use lekalo::{
    BSplineCurve, BSplineSurface, BezierCurve, BezierSegment, BezierSurface, KnotVector,
    NurbsCurve, NurbsSurface, PiecewisePolynomial, Points, PpSpace,
};
use libfuzzer_sys::fuzz_target;

const EXTRA: [Num; 3] = [Num(f64::NAN), Num(-1e300), Num(0.3)];

fuzz_target!(|data: &[u8]| {
    // the first byte picks the type (so that the corpus of each type stays close to valid JSON)
    let Some((&tag, json)) = data.split_first() else {
        return;
    };
    let order = Size(usize::from(tag >> 4) * 3);
    match tag % 11 {
        0 => {
            if let Ok(p) = serde_json::from_slice::<Points>(json) {
                common::exercise_points(&p);
                round_trip(&p);
            }
        }
        1 => {
            if let Ok(k) = serde_json::from_slice::<KnotVector>(json) {
                let ts = common::params((k.as_slice()[0], k.as_slice()[k.len() - 1]), &EXTRA);
                common::exercise_knots(&k, Size(usize::from(tag >> 4)), &ts);
                round_trip(&k);
            }
        }
        2 => {
            if let Ok(c) = serde_json::from_slice::<BSplineCurve>(json) {
                common::exercise_bspline(&c, &EXTRA, order, Size(1));
                round_trip(&c);
            }
        }
        3 => {
            if let Ok(c) = serde_json::from_slice::<BezierCurve>(json) {
                common::exercise_bezier(&c, &EXTRA, order);
                round_trip(&c);
            }
        }
        4 => {
            if let Ok(c) = serde_json::from_slice::<NurbsCurve>(json) {
                common::exercise_nurbs(&c, &EXTRA, order, Size(1));
                round_trip(&c);
            }
        }
        5 => {
            if let Ok(s) = serde_json::from_slice::<BSplineSurface>(json) {
                common::exercise_bspline_surface(&s, &EXTRA, order);
                round_trip(&s);
            }
        }
        6 => {
            if let Ok(s) = serde_json::from_slice::<BezierSurface>(json) {
                common::exercise_bezier_surface(&s, &EXTRA, order);
                round_trip(&s);
            }
        }
        7 => {
            if let Ok(s) = serde_json::from_slice::<NurbsSurface>(json) {
                common::exercise_nurbs_surface(&s, &EXTRA, order);
                round_trip(&s);
            }
        }
        8 => {
            if let Ok(f) = serde_json::from_slice::<PiecewisePolynomial>(json) {
                common::exercise_pp(&f, &EXTRA, order);
                round_trip(&f);
            }
        }
        9 => {
            if let Ok(s) = serde_json::from_slice::<PpSpace>(json) {
                common::exercise_space(&s, None);
                round_trip(&s);
            }
        }
        _ => {
            if let Ok(s) = serde_json::from_slice::<BezierSegment>(json) {
                let _ = s.eval(0.5);
                let _ = s.eval(f64::NAN);
                let _ = BSplineCurve::from_bezier_segments(&[s.clone(), s]);
            }
        }
    }
});

/// Whatever loaded serialises and loads back to an equal value.
fn round_trip<T>(v: &T)
where
    T: serde::Serialize + serde::de::DeserializeOwned + PartialEq + std::fmt::Debug,
{
    let s = serde_json::to_string(v).expect("a loaded value serialises");
    let back: T = serde_json::from_str(&s).expect("a serialised value loads back");
    assert_eq!(&back, v, "JSON round trip changed the value");
}
