//! Analytic surfaces (190–198 over points 116 and directions 123), bounded planes (108) and
//! copious data paths (106) read as exact NURBS, placed, bounded by their faces, and refused
//! with the reason.

use super::{read_iges, read_iges_faces, read_iges_limited};
use crate::error::IoError;
use crate::object::Object;
use crate::shape::{Shape, Surface};

/// An IGES file of the given entities (type, form, matrix pointer, parameters), each with its
/// own parameter lines and directory entries `2k + 1`, with the Global section `global`.
fn file_in(global: &str, entities: &[(u32, i32, u32, &str)]) -> String {
    let mut out = format!("{:<72}S{:>7}\n", "analytic", 1);
    out += &format!("{global:<72}G{:>7}\n", 1);
    let (mut d, mut p) = (String::new(), String::new());
    let mut line = 1;
    for (k, (ty, form, matrix, params)) in entities.iter().enumerate() {
        let chunks: Vec<&str> = params
            .as_bytes()
            .chunks(64)
            .map(|c| std::str::from_utf8(c).unwrap())
            .collect();
        let seq = 2 * k + 1;
        d += &format!(
            "{ty:>8}{line:>8}{:>8}{:>8}{:>8}{:>8}{matrix:>8}{:>8}{:>8}D{seq:>7}\n",
            0, 0, 0, 0, 0, "00000000"
        );
        d += &format!(
            "{ty:>8}{:>8}{:>8}{:>8}{form:>8}{:>8}{:>8}{:>8}{:>8}D{:>7}\n",
            0,
            0,
            chunks.len(),
            "",
            "",
            "",
            0,
            seq + 1
        );
        for c in chunks {
            p += &format!("{c:<64}{seq:>8}P{line:>7}\n");
            line += 1;
        }
    }
    out += &d;
    out += &p;
    let t = format!("S      1G      1D{:>7}P{:>7}", 2 * entities.len(), line - 1);
    out += &format!("{t:<72}T{:>7}\n", 1);
    out
}

/// [`file_in`] in millimetres.
fn file(entities: &[(u32, i32, u32, &str)]) -> String {
    file_in("1H,,1H;;", entities)
}

fn surfaces(text: &str) -> Vec<Surface> {
    let r = read_iges(text, "a.igs").unwrap();
    assert!(r.skipped.is_empty(), "{:?}", r.skipped);
    r.shapes
        .into_iter()
        .filter_map(|(_, s)| match s {
            Shape::Surface(s) => Some(s),
            _ => None,
        })
        .collect()
}

/// The reason the last entity of the file was skipped (the file read).
fn skip_reason(text: &str) -> String {
    let r = read_iges(text, "a.igs").unwrap();
    let listed = r.skipped.listed();
    assert_eq!(listed.len(), 1, "{listed:?}");
    listed[0].reason.clone()
}

/// `n × n` samples over the surface's domain.
fn samples(s: &Surface, n: u32) -> Vec<Vec<f64>> {
    let ((u0, u1), (v0, v1)) = s.domain();
    let mut out = Vec::new();
    for i in 0..=n {
        for j in 0..=n {
            let u = u0 + (u1 - u0) * f64::from(i) / f64::from(n);
            let v = v0 + (v1 - v0) * f64::from(j) / f64::from(n);
            out.push(s.eval(u, v).unwrap());
        }
    }
    out
}

fn sub(a: &[f64], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn norm(a: [f64; 3]) -> f64 {
    a[0].hypot(a[1]).hypot(a[2])
}

/// Spheres, form 0 (about z) and form 1 (about the axis it points at): every sample at the
/// radius from the centre, the pole of the form 1 sphere on its axis.
#[test]
fn spheres_lie_at_their_radius_about_their_axis() {
    let text = file(&[
        (116, 0, 0, "116,1.,2.,3.;"),
        (196, 0, 0, "196,1,2.5;"),
        (123, 0, 0, "123,2.,0.,0.;"),
        (123, 0, 0, "123,0.,1.,0.;"),
        (196, 1, 0, "196,1,4.,5,7;"),
    ]);
    let s = surfaces(&text);
    assert_eq!(s.len(), 2);
    for (s, r) in s.iter().zip([2.5, 4.0]) {
        for p in samples(s, 12) {
            assert!((norm(sub(&p, [1.0, 2.0, 3.0])) - r).abs() < 1e-13, "{p:?}");
        }
    }
    let ((u0, _), (v0, v1)) = s[1].domain();
    let poles = [s[1].eval(u0, v0).unwrap(), s[1].eval(u0, v1).unwrap()];
    assert!(
        (poles[1][0] - 5.0).abs() < 1e-13 && (poles[1][1] - 2.0).abs() < 1e-13,
        "{poles:?}"
    );
    assert!((poles[0][0] + 3.0).abs() < 1e-13, "{poles:?}");
}

/// A torus about the axis (0, 1, 0) through (0, 0, 1): every sample at the minor radius from
/// the circle of the major radius.
#[test]
fn a_torus_lies_about_its_major_circle() {
    let text = file(&[
        (116, 0, 0, "116,0.,0.,1.;"),
        (123, 0, 0, "123,0.,3.,0.;"),
        (198, 0, 0, "198,1,3,5.,1.5;"),
    ]);
    let s = surfaces(&text);
    assert_eq!(s.len(), 1);
    for p in samples(&s[0], 12) {
        let (x, y, z) = (p[0], p[1], p[2] - 1.0);
        let d = (x.hypot(z) - 5.0).hypot(y);
        assert!((d - 1.5).abs() < 1e-13, "{p:?}");
    }
}

/// A sphere in inches is read in millimetres, and a sphere whose directory entry points at a
/// matrix is moved by it.
#[test]
fn spheres_follow_the_unit_and_their_matrix() {
    let inches = format!("1H,,1H;{}1.,1,2HIN;", ",".repeat(11));
    let text = file_in(
        &inches,
        &[(116, 0, 0, "116,0.,0.,1.;"), (196, 0, 0, "196,1,2.;")],
    );
    let s = surfaces(&text);
    for p in samples(&s[0], 8) {
        assert!(
            (norm(sub(&p, [0.0, 0.0, 25.4])) - 50.8).abs() < 1e-12,
            "{p:?}"
        );
    }
    let text = file(&[
        (124, 0, 0, "124,0.,-1.,0.,10.,1.,0.,0.,0.,0.,0.,1.,0.;"),
        (116, 0, 0, "116,1.,0.,0.;"),
        (196, 0, 1, "196,3,1.;"),
    ]);
    let s = surfaces(&text);
    // the centre (1, 0, 0) turned a quarter about z and moved by 10 along x: (10, 1, 0)
    for p in samples(&s[0], 8) {
        assert!(
            (norm(sub(&p, [10.0, 1.0, 0.0])) - 1.0).abs() < 1e-13,
            "{p:?}"
        );
    }
}

/// A quarter of the surface of revolution between the circles of radius `r0` at `z0` and
/// `r1` at `z1` about z as a composite curve (arcs as rational 126, lines 110), from D`at`
/// on: 4 curves and the composite (at `at + 8`).
fn quarter_loop(r0: f64, z0: f64, r1: f64, z1: f64, at: u32) -> Vec<String> {
    let w = std::f64::consts::FRAC_1_SQRT_2;
    let arc = |a: [f64; 3], c: [f64; 3], b: [f64; 3]| {
        format!(
            "126,2,2,1,0,0,0,0.,0.,0.,1.,1.,1.,1.,{w},1.,{},{},{},{},{},{},{},{},{},0.,1.,0.,0.,1.;",
            a[0], a[1], a[2], c[0], c[1], c[2], b[0], b[1], b[2]
        )
    };
    let line = |a: [f64; 3], b: [f64; 3]| {
        format!("110,{},{},{},{},{},{};", a[0], a[1], a[2], b[0], b[1], b[2])
    };
    vec![
        arc([r0, 0.0, z0], [r0, r0, z0], [0.0, r0, z0]),
        line([0.0, r0, z0], [0.0, r1, z1]),
        arc([0.0, r1, z1], [r1, r1, z1], [r1, 0.0, z1]),
        line([r1, 0.0, z1], [r0, 0.0, z0]),
        format!("102,4,{},{},{},{};", at, at + 2, at + 4, at + 6),
    ]
}

/// The entities of a trimmed face on the surface D`surface`, from D`at` on: the loop's curves
/// and composite, the 142 and the 144.
fn face_on(surface: u32, loop_: &[String], at: u32) -> Vec<(u32, i32, u32, String)> {
    let mut out: Vec<(u32, i32, u32, String)> = loop_
        .iter()
        .map(|p| (p[..3].parse().unwrap(), 0, 0, p.clone()))
        .collect();
    let composite = at + 2 * (u32::try_from(loop_.len()).unwrap() - 1);
    out.push((142, 0, 0, format!("142,0,{surface},0,{composite},1;")));
    out.push((144, 0, 0, format!("144,{surface},1,0,{};", composite + 2)));
    out
}

fn faces_of(entities: &[(u32, i32, u32, String)]) -> crate::IgesRead {
    let e: Vec<(u32, i32, u32, &str)> = entities
        .iter()
        .map(|(t, f, m, p)| (*t, *f, *m, p.as_str()))
        .collect();
    read_iges_faces(&file(&e), "a.igs", usize::MAX).unwrap()
}

/// A cylinder and a cone bounded by the faces on them: the surface spans the faces' heights
/// exactly, every sample on the analytic surface; the edges are kept without pcurves, with the
/// reason. Alone, they are skipped as unbounded.
#[test]
fn cylinders_and_cones_take_their_extent_from_their_faces() {
    let (tan, deg) = (0.5f64, 0.5f64.atan().to_degrees());
    for (cone, r1) in [(false, 2.0), (true, 2.0 + 5.0 * tan)] {
        let surface = if cone {
            format!("194,1,3,2.,{deg};")
        } else {
            "192,1,3,2.;".to_string()
        };
        let mut e: Vec<(u32, i32, u32, String)> = vec![
            (116, 0, 0, "116,0.,0.,0.;".into()),
            (123, 0, 0, "123,0.,0.,1.;".into()),
            (if cone { 194 } else { 192 }, 0, 0, surface.clone()),
        ];
        e.extend(face_on(5, &quarter_loop(2.0, 0.0, r1, 5.0, 7), 7));
        let r = faces_of(&e);
        assert!(r.skipped_faces.is_empty(), "{:?}", r.skipped_faces);
        assert_eq!(r.faces.len(), 1);
        let f = &r.faces[0];
        assert_eq!(f.surface_id, 5);
        assert!(f
            .pcurves
            .as_deref()
            .is_some_and(|w| w.contains("parameters are not IGES's")));
        let s = f.face.surface();
        let ((u0, _), (v0, v1)) = s.domain();
        assert_eq!(s.eval(u0, v0).unwrap()[2], 0.0);
        assert!((s.eval(u0, v1).unwrap()[2] - 5.0).abs() < 1e-14);
        for p in samples(s, 12) {
            let want = 2.0 + if cone { tan * p[2] } else { 0.0 };
            assert!((p[0].hypot(p[1]) - want).abs() < 1e-13, "{p:?}");
        }
        // standing alone (without faces) it has no extent
        let alone = file(&[
            (116, 0, 0, "116,0.,0.,0.;"),
            (123, 0, 0, "123,0.,0.,1.;"),
            (if cone { 194 } else { 192 }, 0, 0, &surface),
        ]);
        let why = skip_reason(&alone);
        let kind = if cone {
            "unbounded cone"
        } else {
            "unbounded cylinder"
        };
        assert!(why.contains(kind) && why.contains("--faces"), "{why}");
    }
}

/// A plane surface (190, form 1) bounded by a square face: the patch is the square.
#[test]
fn a_plane_surface_spans_its_face() {
    let line = |a: [f64; 2], b: [f64; 2]| format!("110,{},{},7.,{},{},7.;", a[0], a[1], b[0], b[1]);
    let loop_ = vec![
        line([1.0, 1.0], [4.0, 1.0]),
        line([4.0, 1.0], [4.0, 3.0]),
        line([4.0, 3.0], [1.0, 3.0]),
        line([1.0, 3.0], [1.0, 1.0]),
        "102,4,9,11,13,15;".to_string(),
    ];
    let mut e: Vec<(u32, i32, u32, String)> = vec![
        (116, 0, 0, "116,0.,0.,7.;".into()),
        (123, 0, 0, "123,0.,0.,2.;".into()),
        (123, 0, 0, "123,1.,0.,0.;".into()),
        (190, 1, 0, "190,1,3,5;".into()),
    ];
    e.extend(face_on(7, &loop_, 9));
    let r = faces_of(&e);
    assert!(r.skipped_faces.is_empty(), "{:?}", r.skipped_faces);
    let s = r.faces[0].face.surface();
    let ((u0, u1), (v0, v1)) = s.domain();
    assert_eq!(s.eval(u0, v0).unwrap(), vec![1.0, 1.0, 7.0]);
    assert_eq!(s.eval(u1, v1).unwrap(), vec![4.0, 3.0, 7.0]);
    // a plane with a zero normal is refused before its extent is looked for
    let zero = file(&[
        (116, 0, 0, "116,0.,0.,7.;"),
        (123, 0, 0, "123,0.,0.,0.;"),
        (190, 0, 0, "190,1,3;"),
    ]);
    let why = skip_reason(&zero);
    assert!(why.contains("frame") && why.contains("axis"), "{why}");
}

/// Entity 108 form 1 over a circle of radius 2 about (1, 1) in z = 3: the patch is the
/// circle's bounding square; form 0 (unbounded) and undefined forms are skipped naming why.
#[test]
fn a_bounded_plane_spans_its_bounding_curve() {
    let text = file(&[
        (100, 0, 0, "100,3.,1.,1.,3.,1.,3.,1.;"),
        (108, 1, 0, "108,0.,0.,2.,6.,1,0.,0.,0.,0.;"),
    ]);
    let r = read_iges(&text, "a.igs").unwrap();
    assert!(r.skipped.is_empty(), "{:?}", r.skipped);
    let Some((_, Shape::Surface(s))) = r.shapes.iter().find(|(id, _)| *id == 3) else {
        panic!("{:?}", r.shapes);
    };
    let ((u0, u1), (v0, v1)) = s.domain();
    for (u, v, x, y) in [(u0, v0, -1.0, -1.0), (u1, v1, 3.0, 3.0)] {
        let p = s.eval(u, v).unwrap();
        assert!(
            (p[0] - x).abs() < 1e-14 && (p[1] - y).abs() < 1e-14 && (p[2] - 3.0).abs() < 1e-15,
            "{p:?}"
        );
    }
    let why = skip_reason(&file(&[(108, 0, 0, "108,0.,0.,1.,0.,0,0.,0.,0.,0.;")]));
    assert!(why.contains("unbounded plane (form 0)"), "{why}");
    let why = skip_reason(&file(&[(108, 2, 0, "108,0.,0.,1.,0.,1,0.,0.,0.,0.;")]));
    assert!(why.contains("form 2 is not a form of entity 108"), "{why}");
    let why = skip_reason(&file(&[(108, -1, 0, "108,0.,0.,1.,0.,9,0.,0.,0.,0.;")]));
    assert!(why.contains("bounding curve D9"), "{why}");
}

/// Copious data: a 2-D path (form 11) in its plane, a 3-D path (12), a closed planar curve
/// (63) closed back to its start; the points exactly, one segment between each.
#[test]
fn copious_data_paths_are_polylines() {
    let curve = |params: &str, form: i32| {
        let r = read_iges(&file(&[(106, form, 0, params)]), "a.igs").unwrap();
        assert!(r.skipped.is_empty(), "{:?}", r.skipped);
        match r.shapes.as_slice() {
            [(_, Shape::Curve(Object::BSpline(c)))] => c.clone(),
            other => panic!("{other:?}"),
        }
    };
    let c = curve("106,1,3,2.,0.,0.,1.,0.,1.,1.;", 11);
    assert_eq!(c.degree(), 1);
    assert_eq!(
        c.control_points().as_slice(),
        &[0.0, 0.0, 2.0, 1.0, 0.0, 2.0, 1.0, 1.0, 2.0]
    );
    assert_eq!(c.eval(1.5).unwrap(), vec![1.0, 0.5, 2.0]);
    let c = curve("106,2,2,1.,2.,3.,4.,5.,6.;", 12);
    assert_eq!(
        c.control_points().as_slice(),
        &[1.0, 2.0, 3.0, 4.0, 5.0, 6.0]
    );
    let c = curve("106,1,3,0.,0.,0.,1.,0.,0.,1.;", 63);
    assert_eq!(c.control_points().len(), 4);
    assert_eq!(c.eval(c.domain().1).unwrap(), vec![0.0, 0.0, 0.0]);
}

#[test]
fn copious_data_that_is_no_path_is_skipped_naming_why() {
    for (form, params, want) in [
        (1, "106,1,2,0.,0.,0.,1.,1.;", "form 1 holds data points"),
        (40, "106,1,2,0.,0.,0.,1.,1.;", "form 40 is a drafting"),
        (12, "106,1,2,0.,0.,0.,1.,1.;", "IP = 2"),
        (
            12,
            "106,2,1000000,0.,0.,0.;",
            "N = 1000000 points need 3000003",
        ),
        (12, "106,2,1,0.,0.,0.;", "at least 2 points"),
    ] {
        let why = skip_reason(&file(&[(106, form, 0, params)]));
        assert!(why.contains(want), "{form}: {why}");
    }
    // the points count against the size limit
    let text = file(&[(106, 12, 0, "106,2,3,0.,0.,0.,1.,0.,0.,1.,1.,0.;")]);
    let e = read_iges_limited(&text, "a.igs", 5).unwrap_err();
    assert!(matches!(e, IoError::OverLimit { .. }), "{e}");
}

/// Hostile values: negative radii, a semi-angle of 90°, a NaN, pointers at nothing or not
/// pointers, undefined forms: each skipped with its reason, nothing panics.
#[test]
fn analytic_surfaces_that_are_none_are_skipped_naming_why() {
    let base = [(116, 0, 0, "116,0.,0.,0.;"), (123, 0, 0, "123,0.,0.,1.;")];
    for (ty, form, params, want) in [
        (196, 0, "196,1,-1.;", "radius -1 mm"),
        (198, 0, "198,1,3,1.,-2.;", "minor radius -2 mm"),
        (196, 0, "196,1,NaN;", "\"NaN\", not a number"),
        (196, 0, "196,9,1.;", "D9 is not a point (entity 116)"),
        (
            198,
            0,
            "198,1,1,5.,1.;",
            "D1 is not a direction (entity 123)",
        ),
        (196, 0, "196,x,1.;", "not a pointer to a directory entry"),
        (196, 3, "196,1,1.;", "form 3 is not a form of entity 196"),
        (196, 1, "196,1,1.;", "parameter 3"),
    ] {
        let mut e = base.to_vec();
        e.push((ty, form, 0, params));
        let why = skip_reason(&file(&e));
        assert!(why.contains(want), "{params}: {why}");
    }
    // a cone of semi-angle 90° in a face: refused with the angle in the file's degrees
    let mut e: Vec<(u32, i32, u32, String)> = vec![
        (116, 0, 0, "116,0.,0.,0.;".into()),
        (123, 0, 0, "123,0.,0.,1.;".into()),
        (194, 0, 0, "194,1,3,2.,90.;".into()),
    ];
    e.extend(face_on(5, &quarter_loop(2.0, 0.0, 3.0, 5.0, 7), 7));
    let r = faces_of(&e);
    let why = &r.skipped.listed()[0].reason;
    assert!(why.contains("semi-angle 90°"), "{why}");
}

/// Offset curves and surfaces are listed as skipped with why they are not NURBS.
#[test]
fn offsets_are_skipped_naming_why() {
    let why = skip_reason(&file(&[(
        130,
        0,
        0,
        "130,1,1,0,0,0,0,1.,0.,1.,0.,0.,0.,1.,0.,1.;",
    )]));
    assert!(
        why.contains("offset curve") && why.contains("no NURBS"),
        "{why}"
    );
    let why = skip_reason(&file(&[(140, 0, 0, "140,0.,0.,1.,1.,1;")]));
    assert!(why.contains("offset surface"), "{why}");
}
