//! The size limit of the CAD readers ([`read_step_limited`], [`read_iges_limited`]) on files
//! generated here: a file within the limit reads as without it; one past it, by its entities or
//! by its control points and knots, is refused with the count and `--max-size`.

use crate::shape::Surface;
use crate::{read_iges, read_iges_limited, read_step, read_step_limited, IoError, Object};
use crate::{IgesWriter, StepWriter};
use lekalo::{BSplineCurve, BSplineSurface, KnotVector, Points};

/// A cubic curve of `n` control points and a bicubic surface of `m × m`.
fn shapes(n: usize, m: usize) -> (Object, Surface) {
    let rows: Vec<Vec<f64>> = (0..n)
        .map(|i| vec![i as f64, (i as f64 * 0.3).sin(), 0.0])
        .collect();
    let curve = BSplineCurve::new(
        3,
        KnotVector::clamped_uniform(3, n).unwrap().into_vec(),
        Points::from_rows(&rows).unwrap(),
    )
    .unwrap();
    let net: Vec<Vec<f64>> = (0..m * m)
        .map(|k| vec![(k / m) as f64, (k % m) as f64, ((k * 7) % 5) as f64])
        .collect();
    let kv = KnotVector::clamped_uniform(3, m).unwrap().into_vec();
    let surface = BSplineSurface::new(
        3,
        3,
        kv.clone(),
        kv,
        Points::from_rows(&net).unwrap(),
        (m, m),
    )
    .unwrap();
    (Object::BSpline(curve), Surface::BSpline(surface))
}

fn step_text(curve: &Object, surface: Option<&Surface>) -> String {
    let mut w = StepWriter::new("limits");
    w.add_object(curve).unwrap();
    if let Some(s) = surface {
        w.add_any_surface(s).unwrap();
    }
    w.finish("2000-01-01T00:00:00")
}

fn iges_text((curve, surface): &(Object, Surface)) -> String {
    let mut w = IgesWriter::new();
    w.add_object(curve).unwrap();
    w.add_surface(surface).unwrap();
    w.finish("limits.igs", "2000-01-01T00:00:00")
}

/// The message of a refusal by the size limit.
fn too_large(e: IoError) -> String {
    assert!(matches!(e, IoError::OverLimit { .. }), "{e}");
    e.to_string()
}

#[test]
fn step_files_past_the_size_limit_are_refused_with_the_count() {
    // 300 control points + 304 knots (about 320 entity instances); 20 × 20 = 400 points +
    // 2 × 24 knots (about 400 instances more)
    let (curve, surface) = shapes(300, 20);
    let text = step_text(&curve, Some(&surface));
    let all = read_step(&text, "l.step").unwrap();
    assert_eq!(all.shapes.len(), 2);
    // within the limit: the same shapes
    let within = read_step_limited(&text, "l.step", 10_000).unwrap();
    assert_eq!(within.shapes, all.shapes);
    // the curve alone passes 500: refused at its knots, naming the count
    let alone = step_text(&curve, None);
    let msg = too_large(read_step_limited(&alone, "c.step", 500).unwrap_err());
    assert!(msg.contains("604 control points and knots"), "{msg}");
    assert!(
        msg.contains("--max-size 604") && msg.starts_with("c.step"),
        "{msg}"
    );
    // the curve fits, the surface's net does not: refused at the row that passes the limit
    let msg = too_large(read_step_limited(&text, "l.step", 900).unwrap_err());
    assert!(msg.contains("904 control points and knots"), "{msg}");
    assert!(msg.contains("above the size limit 900"), "{msg}");
    // the entity instances (one per control point, and more) past the limit: refused while
    // parsing, before any geometry
    let msg = too_large(read_step_limited(&text, "l.step", 200).unwrap_err());
    assert!(msg.contains("more than 200 entity instances"), "{msg}");
    assert!(msg.contains("--max-size"), "{msg}");
}

#[test]
fn iges_files_past_the_size_limit_are_refused_with_the_count() {
    let text = iges_text(&shapes(300, 20));
    let all = read_iges(&text, "l.igs").unwrap();
    assert_eq!(all.shapes.len(), 2);
    let within = read_iges_limited(&text, "l.igs", 10_000).unwrap();
    assert_eq!(within.shapes, all.shapes);
    // entity 126: 300 control points and 304 knots
    let msg = too_large(read_iges_limited(&text, "l.igs", 500).unwrap_err());
    assert!(msg.contains("604 control points and knots"), "{msg}");
    assert!(
        msg.contains("--max-size 604") && msg.starts_with("l.igs"),
        "{msg}"
    );
    // entity 128 after it: 400 + 48 more
    let msg = too_large(read_iges_limited(&text, "l.igs", 1000).unwrap_err());
    assert!(msg.contains("1052 control points and knots"), "{msg}");
    // more directory entries than the limit
    let msg = too_large(read_iges_limited(&text, "l.igs", 1).unwrap_err());
    assert!(
        msg.contains("2 entities") && msg.contains("--max-size 2"),
        "{msg}"
    );
}
