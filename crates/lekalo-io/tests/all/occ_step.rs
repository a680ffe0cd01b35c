//! STEP and IGES files written by Open CASCADE (`scripts/occ_step_files.py write`): every
//! B-spline and NURBS curve and surface Open CASCADE reads from them is read here too, bit for
//! bit (both parse the same decimal text, correctly rounded), including the files in metres
//! (scaled to millimetres as Open CASCADE does). Then read-modify-write-read: a knot inserted
//! into every curve, a surface split, written by `StepWriter`, read back unchanged.

use lekalo::{BSplineCurve, BSplineSurface, NurbsCurve, NurbsSurface, Points};
use lekalo_io::{read_iges, read_step, Object, Shape, StepWriter, Surface};
use serde_json::Value;

const DATA: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/occ");
const FILES: [&str; 3] = ["curves_ap214_mm", "surfaces_ap214_mm", "mixed_ap242_m"];
/// IGES files: curves as entity 126, faces as entity 144 over entity 128.
const IGES_FILES: [&str; 2] = ["mixed_iges_mm", "mixed_iges_m"];

fn floats(v: &Value) -> Vec<f64> {
    v.as_array()
        .expect("an array")
        .iter()
        .map(|x| x.as_f64().expect("a number"))
        .collect()
}

fn points(v: &Value) -> Points {
    let rows: Vec<Vec<f64>> = v.as_array().expect("rows").iter().map(floats).collect();
    Points::from_rows(&rows).expect("points")
}

fn usize_of(v: &Value) -> usize {
    usize::try_from(v.as_u64().expect("an integer")).expect("small")
}

/// The object Open CASCADE read, as a lekalo shape.
fn expected(e: &Value) -> Shape {
    if e["kind"] == "curve" {
        let (p, k, c) = (
            usize_of(&e["degree"]),
            floats(&e["knots"]),
            points(&e["control"]),
        );
        return Shape::Curve(match e.get("weights") {
            None => Object::BSpline(BSplineCurve::new(p, k, c).expect("curve")),
            Some(w) => Object::Nurbs(NurbsCurve::new(p, k, c, floats(w)).expect("nurbs")),
        });
    }
    let (p, q) = (usize_of(&e["degree"][0]), usize_of(&e["degree"][1]));
    let (ku, kv) = (floats(&e["knots_u"]), floats(&e["knots_v"]));
    let net = (usize_of(&e["net"][0]), usize_of(&e["net"][1]));
    let c = points(&e["control"]);
    Shape::Surface(match e.get("weights") {
        None => Surface::BSpline(BSplineSurface::new(p, q, ku, kv, c, net).expect("surface")),
        Some(w) => {
            Surface::Nurbs(NurbsSurface::new(p, q, ku, kv, c, floats(w), net).expect("nurbs"))
        }
    })
}

/// What Open CASCADE read from the file `name`.
fn expectations(name: &str) -> Vec<Shape> {
    let expect: Value = serde_json::from_str(
        &std::fs::read_to_string(format!("{DATA}/{name}.expect.json")).expect("expectations"),
    )
    .expect("json");
    expect
        .as_array()
        .expect("list")
        .iter()
        .map(expected)
        .collect()
}

fn read(name: &str) -> (lekalo_io::StepRead, Vec<Shape>) {
    let text = std::fs::read_to_string(format!("{DATA}/{name}.step")).expect("test data");
    (read_step(&text, name).expect("read"), expectations(name))
}

#[test]
fn what_open_cascade_reads_from_its_iges_files_we_read_bit_for_bit() {
    for name in IGES_FILES {
        let text = std::fs::read_to_string(format!("{DATA}/{name}.igs")).expect("test data");
        let r = read_iges(&text, name).expect("read");
        let expect = expectations(name);
        assert_eq!(expect.len(), 5, "{name}: three curves and two surfaces");
        // the same objects in the same order, nothing more: the faces (entity 144) are
        // reported as skipped, their surfaces (entity 128) read
        let got: Vec<&Shape> = r.shapes.iter().map(|(_, s)| s).collect();
        assert_eq!(got, expect.iter().collect::<Vec<_>>(), "{name}");
        assert_eq!(
            r.skipped
                .iter()
                .map(|s| s.entity.as_str())
                .collect::<Vec<_>>(),
            ["IGES entity 144", "IGES entity 144"],
            "{name}"
        );
        let metres = name.ends_with("_m");
        assert_eq!(r.scale_to_mm, if metres { 1000.0 } else { 1.0 }, "{name}");
        assert_eq!(r.length_unit, if metres { "M" } else { "MM" }, "{name}");
    }
}

#[test]
fn what_open_cascade_reads_we_read_bit_for_bit() {
    for name in FILES {
        let (r, expect) = read(name);
        assert!(!expect.is_empty(), "{name}: no expectations");
        for e in &expect {
            assert!(
                r.shapes.iter().any(|(_, s)| s == e),
                "{name}: Open CASCADE's {} is not among the {} shapes read",
                e.type_name(),
                r.shapes.len()
            );
        }
        let metres = name.ends_with("_m");
        assert_eq!(r.scale_to_mm, if metres { 1000.0 } else { 1.0 }, "{name}");
        // the faces' boundary lines are reported, not silently dropped
        if name.starts_with("surfaces") {
            assert!(
                r.skipped.iter().any(|s| s.entity == "LINE"),
                "{:?}",
                r.skipped
            );
        }
    }
}

#[test]
fn read_modify_write_read() {
    for name in FILES {
        let (r, _) = read(name);
        let mut modified = Vec::new();
        for (_, s) in &r.shapes {
            modified.push(match s {
                Shape::Curve(Object::BSpline(c)) => {
                    let (a, b) = c.domain();
                    Shape::Curve(Object::BSpline(
                        c.insert_knot(0.5 * (a + b), 1).expect("insert"),
                    ))
                }
                Shape::Curve(Object::Nurbs(c)) => {
                    let (a, b) = c.domain();
                    Shape::Curve(Object::Nurbs(
                        c.insert_knot(0.5 * (a + b), 2).expect("insert"),
                    ))
                }
                Shape::Surface(Surface::BSpline(f)) => {
                    let ((a, b), _) = f.domain();
                    Shape::Surface(Surface::BSpline(
                        f.insert_knot_u(0.25 * (a + 3.0 * b), 1).expect("insert"),
                    ))
                }
                other => other.clone(),
            });
        }
        let text = write(name, &modified);
        let again = read_step(&text, "again").expect("read back");
        let got: Vec<Shape> = again.shapes.into_iter().map(|(_, s)| s).collect();
        // the file is a fixed point: read and written again, the same text
        assert_eq!(write(name, &got), text, "{name}");
        // 2-D parameter-space curves are written padded to 3-D; compare the 3-D ones. Polynomial
        // objects come back bit for bit; rational ones are stored homogeneous (w·P), and STEP
        // carries P and w, so w·(w·P / w) may differ from w·P in the last bit.
        let three_d: Vec<&Shape> = modified
            .iter()
            .filter(|s| !matches!(s, Shape::Curve(o) if o.dim() != 3))
            .collect();
        assert_eq!(got.len(), three_d.len(), "{name}");
        for (g, m) in got.iter().zip(three_d) {
            match (g, m) {
                (Shape::Curve(Object::Nurbs(a)), Shape::Curve(Object::Nurbs(b))) => {
                    assert_eq!(a.knots(), b.knots(), "{name}");
                    assert_eq!(a.weights(), b.weights(), "{name}");
                    close(a.control_points().as_slice(), b.control_points().as_slice());
                }
                (Shape::Surface(Surface::Nurbs(a)), Shape::Surface(Surface::Nurbs(b))) => {
                    assert_eq!(a.weights(), b.weights(), "{name}");
                    close(a.control_points().as_slice(), b.control_points().as_slice());
                }
                _ => assert_eq!(g, m, "{name}"),
            }
        }
    }
}

/// Equal to two rounding units (the written decimal text read back).
fn close(a: &[f64], b: &[f64]) {
    lekalo_testkit::assert_close_relative(a, b, 2.0 * f64::EPSILON, "control points");
}

fn write(name: &str, shapes: &[Shape]) -> String {
    let mut w = StepWriter::new(name);
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
