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

/// The points of the `VERTEX_POINT`s at the ends of each `EDGE_CURVE` of a STEP text, by the
/// edge's id.
fn edge_vertex_points(text: &str) -> std::collections::HashMap<u64, [Vec<f64>; 2]> {
    let mut line_of = std::collections::HashMap::new();
    for l in text.lines() {
        if let Some((id, rest)) = l.strip_prefix('#').and_then(|l| l.split_once('=')) {
            if let Ok(id) = id.parse::<u64>() {
                line_of.insert(id, rest.to_string());
            }
        }
    }
    let refs = |s: &str| -> Vec<u64> {
        s.split('#')
            .skip(1)
            .filter_map(|r| {
                let digits: String = r.chars().take_while(char::is_ascii_digit).collect();
                digits.parse().ok()
            })
            .collect()
    };
    let point = |vertex: u64| -> Vec<f64> {
        let pt = refs(&line_of[&vertex])[0];
        let l = &line_of[&pt];
        let inner = &l[l.rfind('(').unwrap() + 1..l.find(')').unwrap()];
        inner
            .split(',')
            .map(|x| x.trim().parse::<f64>().unwrap())
            .collect()
    };
    line_of
        .iter()
        .filter(|(_, l)| l.starts_with("EDGE_CURVE("))
        .map(|(&id, l)| {
            let r = refs(l);
            (id, [point(r[0]), point(r[1])])
        })
        .collect()
}

/// A square whose edges meet within the loop's tolerance but not exactly, each edge starting
/// `1e-6` back along its own direction from the corner where the edge before it ends (as an
/// IGES file's trimming curves meet): written to STEP, every vertex lies past the ends of its
/// edges' curves, so that a reader trimming each edge at the nearest point of its curve to the
/// vertex keeps the whole curve, and the vertex's distance to each end is the gap.
#[test]
fn a_vertex_between_edge_ends_that_differ_lies_past_every_end() {
    let c = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
    let gap = 1e-6;
    let segs: Vec<_> = (0..4)
        .map(|k| {
            let (a, b) = (c[k], c[(k + 1) % 4]);
            let d = [b[0] - a[0], b[1] - a[1]];
            ([a[0] - gap * d[0], a[1] - gap * d[1]], b)
        })
        .collect();
    let faces = vec![StepFace {
        id: 0,
        name: "gapped square".into(),
        surface_id: 0,
        face: segments_face(0.0, 0.0, &segs),
        edge_ids: vec![vec![0; 4]],
        pcurves: None,
    }];
    let (text, back) = step_round_trip(&faces);
    assert!(faces_match(&faces[0].face, &back[0].face), "curves kept");
    let (meets, own) = check_vertices_keep_curves(&text, &back, gap);
    assert_eq!(
        (meets, own),
        (8, 0),
        "every corner one vertex past both ends"
    );
}

/// Checks that every vertex of every edge of `back` (read from `text`) is past the nearer end
/// of the edge's curve or at it, within `10 gap` of it; counts the vertices past an end and
/// those at one.
fn check_vertices_keep_curves(text: &str, back: &[StepFace], gap: f64) -> (usize, usize) {
    let vertices = edge_vertex_points(text);
    let (mut past, mut at) = (0, 0);
    for f in back {
        for (lp, ids) in f.face.loops().zip(&f.edge_ids) {
            for (e, id) in lp.edges().iter().zip(ids) {
                let curve = e.curve();
                let (t0, t1) = curve.domain();
                for v in &vertices[id] {
                    // the end nearer the vertex, and the direction the curve leaves it in
                    let ends = [(t0, -1.0), (t1, 1.0)].map(|(t, sign)| {
                        let d = curve.eval_derivatives(t, 1).unwrap();
                        (
                            d.point(0).to_vec(),
                            d.point(1).iter().map(|x| sign * x).collect::<Vec<_>>(),
                        )
                    });
                    let dist = |p: &[f64]| {
                        p.iter()
                            .zip(v)
                            .map(|(a, b)| (a - b).powi(2))
                            .sum::<f64>()
                            .sqrt()
                    };
                    let (p, out) = if dist(&ends[0].0) <= dist(&ends[1].0) {
                        &ends[0]
                    } else {
                        &ends[1]
                    };
                    let along: f64 = v
                        .iter()
                        .zip(p)
                        .zip(out)
                        .map(|((x, y), o)| (x - y) * o)
                        .sum();
                    if dist(p) == 0.0 {
                        at += 1;
                    } else {
                        assert!(
                            along > 0.0,
                            "vertex {v:?} not past the end {p:?} of edge #{id}"
                        );
                        past += 1;
                    }
                    assert!(dist(p) < 10.0 * gap, "vertex {v:?} far from the end {p:?}");
                }
            }
        }
    }
    (past, at)
}

/// A plane face of `[x0 - 0.5, x0 + 1.5] × [y0 - 0.5, y0 + 1.5]` bounded by the segments
/// `segs` in order (each an edge with its pcurve; the end of one may miss the start of the
/// next), to build faces sharing edges by their curves.
fn segments_face(x0: f64, y0: f64, segs: &[([f64; 2], [f64; 2])]) -> Face {
    let uv = |p: [f64; 2]| [(p[0] - x0 + 0.5) / 2.0, (p[1] - y0 + 0.5) / 2.0];
    let knots = vec![0.0, 0.0, 1.0, 1.0];
    let edges = segs
        .iter()
        .map(|&(a, b)| {
            let xyz = Points::from_3d(&[[a[0], a[1], 0.0], [b[0], b[1], 0.0]]).unwrap();
            let p = Points::from_2d(&[uv(a), uv(b)]).unwrap();
            Edge::new(
                Curve::from(BSplineCurve::new(1, knots.clone(), xyz).unwrap()),
                Some(Curve::from(BSplineCurve::new(1, knots.clone(), p).unwrap())),
            )
            .unwrap()
        })
        .collect();
    let (xa, xb, ya, yb) = (x0 - 0.5, x0 + 1.5, y0 - 0.5, y0 + 1.5);
    let net =
        Points::from_3d(&[[xa, ya, 0.0], [xa, yb, 0.0], [xb, ya, 0.0], [xb, yb, 0.0]]).unwrap();
    let s = BSplineSurface::new(1, 1, knots.clone(), knots, net, (2, 2)).unwrap();
    Face::new(
        Surface::from(s),
        Loop::new(edges).unwrap(),
        vec![],
        true,
        LOOP_CLOSURE_RTOL,
    )
    .unwrap()
}

/// Four squares meeting at a crossing whose horizontal arms overlap by `2e-6` (the left arm
/// ends past the start of the right one): no point is past the ends of both, so each edge is
/// written with a vertex of its own at its curve's end there, and its curve is kept whole.
#[test]
fn edges_overlapping_at_a_vertex_keep_their_own_ends() {
    let e = 1e-6;
    // the arms' ends at the crossing: left and right overlap along x
    let (l, r, d, u) = (
        [1.0 + e, 1.0],
        [1.0 - e, 1.0],
        [1.0, 1.0 - e],
        [1.0, 1.0 + e],
    );
    let (arm_d, arm_l) = (([1.0, 0.0], d), ([0.0, 1.0], l));
    let (arm_r, arm_u) = ((r, [2.0, 1.0]), (u, [1.0, 2.0]));
    let rev = |(a, b): ([f64; 2], [f64; 2])| (b, a);
    let faces = [
        segments_face(
            0.0,
            0.0,
            &[
                ([0.0, 0.0], [1.0, 0.0]),
                arm_d,
                rev(arm_l),
                ([0.0, 1.0], [0.0, 0.0]),
            ],
        ),
        segments_face(
            1.0,
            0.0,
            &[
                ([1.0, 0.0], [2.0, 0.0]),
                ([2.0, 0.0], [2.0, 1.0]),
                rev(arm_r),
                rev(arm_d),
            ],
        ),
        segments_face(
            1.0,
            1.0,
            &[
                arm_r,
                ([2.0, 1.0], [2.0, 2.0]),
                ([2.0, 2.0], [1.0, 2.0]),
                rev(arm_u),
            ],
        ),
        segments_face(
            0.0,
            1.0,
            &[
                arm_l,
                arm_u,
                ([1.0, 2.0], [0.0, 2.0]),
                ([0.0, 2.0], [0.0, 1.0]),
            ],
        ),
    ];
    let faces: Vec<StepFace> = faces
        .into_iter()
        .enumerate()
        .map(|(i, face)| StepFace {
            id: 0,
            name: format!("quarter {i}"),
            surface_id: 0,
            face,
            edge_ids: vec![vec![0; 4]],
            pcurves: None,
        })
        .collect();
    let (text, back) = step_round_trip(&faces);
    for (a, b) in faces.iter().zip(&back) {
        assert!(faces_match(&a.face, &b.face), "{}", a.name);
    }
    assert_eq!(
        sharing(&back).iter().filter(|g| g.len() == 2).count(),
        4,
        "the arms shared"
    );
    let (_, at) = check_vertices_keep_curves(&text, &back, e);
    assert!(
        at >= 4,
        "the arms' ends at the crossing are their own vertices: {at}"
    );
}
