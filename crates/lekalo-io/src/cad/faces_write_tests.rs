//! Faces written to STEP and IGES and read back: the fixtures of the STEP reader's tests (a
//! plane plate with a hole, a B-spline patch, a cylinder with a seam), the files of Open
//! CASCADE under `tests/data/occ`, and a cube of six B-spline faces (a closed shell).

use lekalo::topology::{Edge, Face, Loop, LOOP_CLOSURE_RTOL};
use lekalo::{BSplineCurve, BSplineSurface, Curve, Points, Surface};

use crate::step_read::faces_tests::{file, PATCH, PLATE, TUBE};
use crate::step_read::StepFace;
use crate::{read_step_faces, StepWriter};

/// Equal within `1e-12` relative to the values' scale (knots, control points, weights): the
/// curves of a use that runs a shared edge backwards are reversed twice on the way.
fn curves_match(a: &Curve, b: &Curve) -> bool {
    let near = |x: &[f64], y: &[f64]| {
        let scale = x.iter().fold(1.0_f64, |m, v| m.max(v.abs()));
        x.len() == y.len() && x.iter().zip(y).all(|(p, q)| (p - q).abs() <= 1e-12 * scale)
    };
    a.degree() == b.degree()
        && near(a.knots().as_slice(), b.knots().as_slice())
        && near(a.control_points().as_slice(), b.control_points().as_slice())
        && match (a.weights(), b.weights()) {
            (None, None) => true,
            (Some(x), Some(y)) => near(&x, &y),
            _ => false,
        }
}

/// Same surface (bit for bit), sense, loops, and edges within [`curves_match`].
pub(crate) fn faces_match(a: &Face, b: &Face) -> bool {
    a.surface() == b.surface()
        && a.same_sense() == b.same_sense()
        && a.inner().len() == b.inner().len()
        && a.loops().zip(b.loops()).all(|(x, y)| {
            x.edges().len() == y.edges().len()
                && x.edges().iter().zip(y.edges()).all(|(e, f)| {
                    curves_match(e.curve(), f.curve())
                        && match (e.pcurve(), f.pcurve()) {
                            (None, None) => true,
                            (Some(p), Some(q)) => curves_match(p, q),
                            _ => false,
                        }
                })
        })
}

/// The partition of the edge uses into edges, as lists of `(face, loop, edge)` places: equal
/// before and after a round trip when the same edges are shared.
pub(crate) fn sharing(faces: &[StepFace]) -> Vec<Vec<(usize, usize, usize)>> {
    let mut by_id: std::collections::BTreeMap<u64, Vec<(usize, usize, usize)>> =
        std::collections::BTreeMap::new();
    for (fi, f) in faces.iter().enumerate() {
        for (li, ids) in f.edge_ids.iter().enumerate() {
            for (ei, id) in ids.iter().enumerate() {
                by_id.entry(*id).or_default().push((fi, li, ei));
            }
        }
    }
    let mut groups: Vec<_> = by_id.into_values().collect();
    groups.sort();
    groups
}

fn step_round_trip(faces: &[StepFace]) -> (String, Vec<StepFace>) {
    let mut w = StepWriter::new("faces");
    w.add_faces(faces).unwrap();
    let text = w.finish("2000-01-01T00:00:00");
    let r = read_step_faces(&text, "again.step", usize::MAX).unwrap();
    assert!(r.skipped_faces.is_empty(), "{:?}", r.skipped_faces);
    (text, r.faces)
}

/// A unit cube of six bilinear faces, each bounded by its four edges with pcurves, every loop
/// counter-clockwise seen from outside (the normals point out).
pub(crate) fn cube() -> Vec<StepFace> {
    let corner = |k: usize| [(k & 1) as f64, ((k >> 1) & 1) as f64, ((k >> 2) & 1) as f64];
    let quads = [
        [0, 2, 3, 1],
        [4, 5, 7, 6],
        [0, 1, 5, 4],
        [2, 6, 7, 3],
        [0, 4, 6, 2],
        [1, 3, 7, 5],
    ];
    let uv = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
    quads
        .iter()
        .enumerate()
        .map(|(i, q)| {
            let c = q.map(corner);
            let net = Points::from_3d(&[c[0], c[3], c[1], c[2]]).unwrap();
            let s = Surface::from(
                BSplineSurface::new(
                    1,
                    1,
                    vec![0.0, 0.0, 1.0, 1.0],
                    vec![0.0, 0.0, 1.0, 1.0],
                    net,
                    (2, 2),
                )
                .unwrap(),
            );
            let edges = (0..4)
                .map(|k| {
                    let pts = Points::from_3d(&[c[k], c[(k + 1) % 4]]).unwrap();
                    let (a, b) = (uv[k], uv[(k + 1) % 4]);
                    let p = Points::from_2d(&[a, b]).unwrap();
                    let knots = vec![0.0, 0.0, 1.0, 1.0];
                    Edge::new(
                        Curve::from(BSplineCurve::new(1, knots.clone(), pts).unwrap()),
                        Some(Curve::from(BSplineCurve::new(1, knots, p).unwrap())),
                    )
                    .unwrap()
                })
                .collect();
            let face = Face::new(
                s,
                Loop::new(edges).unwrap(),
                vec![],
                true,
                LOOP_CLOSURE_RTOL,
            )
            .unwrap();
            StepFace {
                id: 0,
                name: format!("side {i}"),
                surface_id: 0,
                face,
                edge_ids: vec![vec![0; 4]],
                pcurves: None,
            }
        })
        .collect()
}

#[test]
fn step_fixtures_round_trip() {
    let mut all = Vec::new();
    for data in [PLATE, PATCH, TUBE] {
        all.extend(
            read_step_faces(&file(data), "t.step", usize::MAX)
                .unwrap()
                .faces,
        );
    }
    for name in ["surfaces_ap214_mm.step", "mixed_ap242_m.step"] {
        let path = format!("{}/tests/data/occ/{name}", env!("CARGO_MANIFEST_DIR"));
        let text = std::fs::read_to_string(path).unwrap();
        let r = read_step_faces(&text, name, usize::MAX).unwrap();
        assert!(!r.faces.is_empty(), "{name}");
        all.extend(r.faces);
    }
    for f in &all {
        let one = std::slice::from_ref(f);
        let (text, back) = step_round_trip(one);
        assert_eq!(back.len(), 1);
        assert!(faces_match(&back[0].face, &f.face), "{}: {text}", f.name);
        assert_eq!(back[0].name, f.name);
        assert_eq!(sharing(&back), sharing(one), "{text}");
        // a face that had pcurves keeps them; the cylinder's edges have none to write
        assert_eq!(back[0].pcurves.is_none(), f.pcurves.is_none(), "{text}");
        assert!(text.contains("OPEN_SHELL") && text.contains("SHELL_BASED_SURFACE_MODEL"));
        // written again, the file is the same
        let (again, _) = step_round_trip(&back);
        assert_eq!(again, text);
    }
    // the plate's hole is one closed edge: one vertex
    let (text, _) = step_round_trip(&all[..1]);
    assert_eq!(text.matches("VERTEX_POINT").count(), 5, "{text}");
}

#[test]
fn cube_is_a_closed_shell_of_shared_edges() {
    let faces = cube();
    let (text, back) = step_round_trip(&faces);
    assert_eq!(back.len(), 6);
    for (a, b) in faces.iter().zip(&back) {
        assert!(faces_match(&a.face, &b.face), "{text}");
        assert_eq!(a.name, b.name);
    }
    assert_eq!(text.matches("EDGE_CURVE(").count(), 12);
    assert_eq!(text.matches("VERTEX_POINT(").count(), 8);
    assert_eq!(text.matches("ADVANCED_FACE(").count(), 6);
    assert!(text.contains("CLOSED_SHELL") && text.contains("MANIFOLD_SOLID_BREP"));
    assert!(text.contains("ADVANCED_BREP_SHAPE_REPRESENTATION"));
    // each edge in two faces, each way once
    let groups = sharing(&back);
    assert_eq!(groups.len(), 12);
    assert!(groups.iter().all(|g| g.len() == 2));
    // without one side the shell is open
    let (text, _) = step_round_trip(&faces[1..]);
    assert!(text.contains("OPEN_SHELL") && !text.contains("CLOSED_SHELL"));
}

#[test]
fn faces_whose_curves_of_a_shared_edge_differ_keep_their_own() {
    // the bottom face's edge from (1, 0, 0) to (0, 0, 0) bows by 1e-9 (a quadratic): the shell
    // joins it with the front face's straight edge, but each face keeps its curve
    let mut faces = cube();
    let f = &faces[0].face;
    let mut edges = f.outer().edges().to_vec();
    let bowed = Points::from_3d(&[[1.0, 0.0, 0.0], [0.5, 1e-9, 0.0], [0.0, 0.0, 0.0]]).unwrap();
    edges[3] = Edge::new(
        Curve::from(BSplineCurve::new(2, vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0], bowed).unwrap()),
        edges[3].pcurve().cloned(),
    )
    .unwrap();
    faces[0].face = Face::new(
        f.surface().clone(),
        Loop::new(edges).unwrap(),
        vec![],
        true,
        LOOP_CLOSURE_RTOL,
    )
    .unwrap();
    let (text, back) = step_round_trip(&faces);
    for (a, b) in faces.iter().zip(&back) {
        assert!(faces_match(&a.face, &b.face), "{}: {text}", a.name);
    }
    assert_eq!(text.matches("EDGE_CURVE(").count(), 13, "{text}");
    assert_eq!(text.matches("VERTEX_POINT(").count(), 8, "{text}");
    // on a domain where a0 + (a1 - a0) rounds past a1, one curve used both ways stays shared
    let domain = (0.006528133149406, 0.123620277680534);
    assert!(domain.0 + (domain.1 - domain.0) * 1.0 > domain.1);
    let mut faces = cube();
    for f in &mut faces {
        let lp = f.face.outer();
        let edges = lp
            .edges()
            .iter()
            .map(|e| {
                let c = e.curve().reparametrize(domain.0, domain.1).unwrap();
                Edge::new(c, e.pcurve().cloned()).unwrap()
            })
            .collect();
        f.face = Face::new(
            f.face.surface().clone(),
            Loop::new(edges).unwrap(),
            vec![],
            true,
            LOOP_CLOSURE_RTOL,
        )
        .unwrap();
    }
    let (text, _) = step_round_trip(&faces);
    assert_eq!(text.matches("EDGE_CURVE(").count(), 12, "{text}");
}

#[test]
fn faces_and_loose_geometry_do_not_mix() {
    let faces = cube();
    let mut w = StepWriter::new("x");
    w.add_faces(&faces).unwrap();
    assert!(w.add_faces(&faces).is_err());
    let s = faces[0].face.surface().clone();
    let e = w.add_any_surface(&s).unwrap_err().to_string();
    assert!(e.contains("holds only faces"), "{e}");
    let mut w = StepWriter::new("x");
    w.add_any_surface(&s).unwrap();
    let e = w.add_faces(&faces).unwrap_err().to_string();
    assert!(e.contains("one set of faces"), "{e}");
    assert!(StepWriter::new("x").add_faces(&[]).is_err());
}

fn iges_round_trip(faces: &[StepFace]) -> (String, Vec<StepFace>) {
    let mut w = crate::IgesWriter::new();
    w.add_faces(faces).unwrap();
    let text = w.finish("faces", "20000101.000000");
    let r = crate::read_iges_faces(&text, "again.igs", usize::MAX).unwrap();
    assert!(r.skipped_faces.is_empty(), "{:?}", r.skipped_faces);
    (text, r.faces)
}

#[test]
fn iges_round_trip_of_fixtures_and_cube() {
    let mut all = cube();
    for data in [PLATE, PATCH, TUBE] {
        all.extend(
            read_step_faces(&file(data), "t.step", usize::MAX)
                .unwrap()
                .faces,
        );
    }
    let (text, back) = iges_round_trip(&all);
    assert_eq!(back.len(), all.len());
    for l in text.lines() {
        assert_eq!(l.len(), 80, "{l}");
    }
    for (a, b) in all.iter().zip(&back) {
        // IGES has no orientation flag and no names: the rest comes back bit for bit
        assert_eq!(a.face.surface(), b.face.surface(), "{}", a.name);
        assert!(a.face.loops().eq(b.face.loops()), "{}", a.name);
        assert_eq!(a.face.inner().len(), b.face.inner().len());
        assert!(b.face.same_sense());
        assert_eq!(a.pcurves.is_none(), b.pcurves.is_none(), "{}", a.name);
    }
    // the cube: six 144s over 128s, each loop a 142 of a 102 of four 126s in space and four
    // in (u, v); the 126s of pcurves are marked 2-D parametric
    let count = |ty: &str| {
        text.lines()
            .filter(|l| l.get(72..73) == Some("D") && l[..8].trim() == ty)
            .count()
            / 2
    };
    assert_eq!(count("144"), all.len());
    assert!(text.contains("00010500D"), "{text}");
    // read again and written again: the same file
    let mut w = crate::IgesWriter::new();
    w.add_faces(&back).unwrap();
    assert_eq!(w.finish("faces", "20000101.000000"), text);
    assert!(crate::IgesWriter::new().add_faces(&[]).is_err());
}
