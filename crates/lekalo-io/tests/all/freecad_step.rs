//! STEP as FreeCAD writes it: FreeCAD exports through Open CASCADE's STEP processor, with its own
//! header (`FILE_DESCRIPTION(('FreeCAD Model'),'2;1')`, originating system `'FreeCAD'`), the
//! AP214 IS schema `AUTOMOTIVE_DESIGN { 1 0 10303 214 1 1 1 1 }`, a `PRODUCT_CONTEXT`, a unit
//! context in millimetres, and the entity layout of Open CASCADE: a plain
//! `B_SPLINE_CURVE_WITH_KNOTS`/`B_SPLINE_SURFACE_WITH_KNOTS` for polynomial splines and a
//! complex instance (`BOUNDED_CURVE() B_SPLINE_CURVE(…) … RATIONAL_B_SPLINE_CURVE(…)`) for
//! rational ones. The fixture `tests/data/freecad/bsplines_ap214_mm.step` is written by hand
//! after that structure (header, contexts and line breaks inside complex instances as FreeCAD
//! files have them), with one curve and one surface of each kind; every value is read exactly,
//! and a write-read round trip keeps them.

use lekalo::{BSplineCurve, BSplineSurface, NurbsCurve, NurbsSurface, Points};
use lekalo_io::{read_step, Object, Shape, StepWriter, Surface};

const FILE: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/tests/data/freecad/bsplines_ap214_mm.step"
);

fn pts(rows: &[[f64; 3]]) -> Points {
    Points::from_rows(&rows.iter().map(|r| r.to_vec()).collect::<Vec<_>>()).expect("points")
}

/// The four shapes of the fixture, from its text.
fn expected() -> Vec<Shape> {
    // the file's 12-digit weight of a quarter circle, as Open CASCADE writes it: not 1/√2
    #[allow(clippy::approx_constant)]
    let w = 0.707_106_781_187;
    let cubic = BSplineCurve::new(
        3,
        vec![0.0, 0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0, 1.0],
        pts(&[
            [0.0, 0.0, 0.0],
            [10.0, 20.0, 0.0],
            [25.0, -5.0, 2.5],
            [40.0, 15.0, 0.0],
            [50.0, 0.0, -1e-2],
        ]),
    )
    .expect("cubic");
    let arc = NurbsCurve::new(
        2,
        vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
        pts(&[[10.0, 0.0, 0.0], [10.0, 10.0, 0.0], [0.0, 10.0, 0.0]]),
        vec![1.0, w, 1.0],
    )
    .expect("arc");
    let ku = vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0];
    let bump = BSplineSurface::new(
        2,
        1,
        ku.clone(),
        vec![0.0, 0.0, 5.0, 5.0],
        pts(&[
            [0.0, 0.0, 0.0],
            [0.0, 5.0, 0.0],
            [5.0, 0.0, 3.0],
            [5.0, 5.0, 3.0],
            [10.0, 0.0, 0.0],
            [10.0, 5.0, 0.0],
        ]),
        (3, 2),
    )
    .expect("surface");
    let cylinder = NurbsSurface::new(
        2,
        1,
        ku,
        vec![0.0, 0.0, 1.0, 1.0],
        pts(&[
            [1.0, 0.0, 0.0],
            [1.0, 0.0, 4.0],
            [1.0, 1.0, 0.0],
            [1.0, 1.0, 4.0],
            [0.0, 1.0, 0.0],
            [0.0, 1.0, 4.0],
        ]),
        vec![1.0, 1.0, w, w, 1.0, 1.0],
        (3, 2),
    )
    .expect("quarter cylinder");
    vec![
        Shape::Curve(Object::BSpline(cubic)),
        Shape::Curve(Object::Nurbs(arc)),
        Shape::Surface(Surface::BSpline(bump)),
        Shape::Surface(Surface::Nurbs(cylinder)),
    ]
}

fn write(shapes: &[Shape]) -> String {
    let mut w = StepWriter::new("freecad");
    for s in shapes {
        match s {
            Shape::Curve(o) => {
                w.add_object(o).expect("curve");
            }
            Shape::Surface(f) => {
                w.add_any_surface(f).expect("surface");
            }
            _ => unreachable!("STEP gives curves and surfaces"),
        }
    }
    w.finish("2000-01-01T00:00:00")
}

#[test]
fn freecad_file_is_read_exactly() {
    let text = std::fs::read_to_string(FILE).expect("fixture");
    let r = read_step(&text, "bsplines_ap214_mm.step").expect("read");
    assert!(
        r.schema.as_deref().is_some_and(|s| s.contains("10303 214")),
        "{:?}",
        r.schema
    );
    assert_eq!(r.length_unit, "millimetre");
    assert_eq!(r.scale_to_mm.to_bits(), 1.0_f64.to_bits(), "no scaling");
    let got: Vec<Shape> = r.shapes.iter().map(|(_, s)| s.clone()).collect();
    assert_eq!(got, expected(), "skipped: {:?}", r.skipped);
    let ids: Vec<u64> = r.shapes.iter().map(|(id, _)| *id).collect();
    assert_eq!(ids, [16, 22, 30, 50]);
    assert!(
        r.skipped.iter().all(|s| !s.entity.contains("SPLINE")),
        "no spline skipped: {:?}",
        r.skipped
    );
    // written by lekalo and read again: the same shapes, bit for bit
    let again = read_step(&write(&got), "again").expect("read back");
    let back: Vec<Shape> = again.shapes.into_iter().map(|(_, s)| s).collect();
    assert_eq!(back, got);
}
