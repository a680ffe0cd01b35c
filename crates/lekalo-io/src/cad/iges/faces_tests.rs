//! Trimmed surfaces (144) with curves on surfaces (142), composite curves (102) and
//! parameter-space B-splines (126) read as faces.

use lekalo::{BSplineCurve, BSplineSurface, Points};

use super::{read_iges, read_iges_faces, IgesWriter};
use crate::object::Object;
use crate::shape::Surface;

fn polyline(pts: &[[f64; 2]], scale: f64, three_d: bool) -> Object {
    let n = pts.len();
    let mut knots = vec![0.0];
    knots.extend((0..n).map(|i| i as f64));
    knots.push((n - 1) as f64);
    let rows: Vec<Vec<f64>> = pts
        .iter()
        .map(|p| {
            let mut r = vec![p[0] * scale, p[1] * scale];
            if three_d {
                r.push(0.0);
            }
            r
        })
        .collect();
    Object::BSpline(BSplineCurve::new(1, knots, Points::from_rows(&rows).unwrap()).unwrap())
}

/// A 10 mm square plate `S(u, v) = (10 u, 10 v, 0)` on `[0, 1]²` (D1); its outer boundary
/// as composite curves of four lines in space and in `(u, v)` (142 at D23); a square hole
/// `[0.3, 0.7]²` as one closed 126 in space and one in `(u, v)` (142 at D29); then the
/// entities `faces` (trimmed and bounded surfaces, boundaries; from D31 on).
fn plate(faces: &[&str]) -> String {
    let mut w = IgesWriter::new();
    let net = Points::from_3d(&[
        [0.0, 0.0, 0.0],
        [0.0, 10.0, 0.0],
        [10.0, 0.0, 0.0],
        [10.0, 10.0, 0.0],
    ])
    .unwrap();
    let s = BSplineSurface::new(
        1,
        1,
        vec![0.0, 0.0, 1.0, 1.0],
        vec![0.0, 0.0, 1.0, 1.0],
        net,
        (2, 2),
    )
    .unwrap();
    w.add_surface(&Surface::BSpline(s)).unwrap();
    let square = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0], [0.0, 0.0]];
    for (scale, three_d) in [(10.0, true), (1.0, false)] {
        for k in 0..4 {
            w.add_object(&polyline(&square[k..k + 2], scale, three_d))
                .unwrap();
        }
    }
    let raw = |w: &mut IgesWriter, ty: u32, text: &str| {
        let t = text.split(',').map(String::from).collect();
        w.entities.push((ty, 0, t, "00000000"));
    };
    raw(&mut w, 102, "102,4,3,5,7,9");
    raw(&mut w, 102, "102,4,11,13,15,17");
    raw(&mut w, 142, "142,0,1,21,19,1");
    let hole = [[0.3, 0.3], [0.3, 0.7], [0.7, 0.7], [0.7, 0.3], [0.3, 0.3]];
    w.add_object(&polyline(&hole, 10.0, true)).unwrap();
    w.add_object(&polyline(&hole, 1.0, false)).unwrap();
    raw(&mut w, 142, "142,0,1,27,25,1");
    for f in faces {
        let ty = f.split(',').next().and_then(|t| t.parse().ok()).unwrap();
        raw(&mut w, ty, f);
    }
    w.finish("plate.igs", "20000101.000000")
}

#[test]
fn a_trimmed_plate_with_a_hole_reads_as_a_face_with_pcurves() {
    let text = plate(&["144,1,1,1,23,29"]);
    let r = read_iges_faces(&text, "plate.igs", usize::MAX).unwrap();
    assert!(r.skipped_faces.is_empty(), "{:?}", r.skipped_faces);
    let [f] = r.faces.as_slice() else {
        panic!("one face: {:?}", r.faces)
    };
    assert_eq!((f.id, f.surface_id, f.pcurves.as_deref()), (31, 1, None));
    assert_eq!(f.edge_ids, vec![vec![3, 5, 7, 9], vec![25]]);
    assert_eq!(f.face.outer().edges().len(), 4);
    assert_eq!(f.face.inner().len(), 1);
    // each pcurve maps onto its edge through the surface
    for e in f.face.loops().flat_map(|l| l.edges()) {
        let p = e.pcurve().expect("a pcurve");
        assert_eq!(p.dim(), 2);
        let (a, b) = p.domain();
        for t in [a, 0.5 * (a + b), b] {
            let uv = p.eval(t).unwrap();
            let s = f.face.surface().eval(uv[0], uv[1]).unwrap();
            let c = e.curve().eval(t).unwrap();
            let d: f64 = s.iter().zip(&c).map(|(x, y)| (x - y).abs()).sum();
            assert!(d < 1e-12, "S(pcurve({t})) = {s:?}, curve({t}) = {c:?}");
        }
    }
    let region = f.face.trim_region().unwrap();
    assert!(region.contains(0.1, 0.1));
    assert!(!region.contains(0.5, 0.5), "inside the hole");
    // read_iges still lists the topology entities as not read
    let plain = read_iges(&text, "plate.igs").unwrap();
    assert!(plain.faces.is_empty());
    assert!(plain.skipped.iter().any(|s| s.entity == "IGES entity 144"));
    assert_eq!(plain.shapes, r.shapes);
}

#[test]
fn an_untrimmed_outer_boundary_is_the_domain_of_the_surface() {
    let text = plate(&["144,1,0,1,0,29"]);
    let r = read_iges_faces(&text, "plate.igs", usize::MAX).unwrap();
    let [f] = r.faces.as_slice() else {
        panic!("one face: {:?}", r.skipped_faces)
    };
    assert_eq!(f.edge_ids[0], vec![0; 4]);
    let outer = f.face.outer();
    assert_eq!(outer.largest_gap(true).unwrap().unwrap().0, 0.0);
    let starts: Vec<Vec<f64>> = outer
        .edges()
        .iter()
        .map(|e| {
            let p = e.pcurve().unwrap();
            p.eval(p.domain().0).unwrap()
        })
        .collect();
    assert_eq!(
        starts,
        vec![
            vec![0.0, 0.0],
            vec![1.0, 0.0],
            vec![1.0, 1.0],
            vec![0.0, 1.0]
        ]
    );
    let region = f.face.trim_region().unwrap();
    assert!(region.contains(0.05, 0.95) && !region.contains(0.5, 0.5));
}

#[test]
fn faces_pointing_at_missing_or_wrong_entities_are_skipped_with_the_reason() {
    let text = plate(&[
        "144,99,1,0,23",
        "144,1,1,1,23,3",
        "144,1,1,0,7",
        "144,1,1,3,23,29",
        "144,1,1,0,x",
    ]);
    let r = read_iges_faces(&text, "plate.igs", usize::MAX).unwrap();
    assert!(r.faces.is_empty());
    let reasons: Vec<(u64, &str)> = r
        .skipped_faces
        .iter()
        .map(|s| (s.id, s.reason.as_str()))
        .collect();
    assert_eq!(reasons.len(), 5, "{reasons:?}");
    assert!(
        reasons[0].1.contains("surface D99 is not an entity"),
        "{reasons:?}"
    );
    assert!(
        reasons[1].1.contains("D3 is a curve, not a boundary"),
        "{reasons:?}"
    );
    assert!(
        reasons[2].1.contains("D7 is a curve, not a boundary"),
        "{reasons:?}"
    );
    assert!(
        reasons[3].1.contains("N2 = 3 inner boundaries and lists 1"),
        "{reasons:?}"
    );
    assert!(reasons[4].1.contains("\"x\", not a pointer"), "{reasons:?}");
    assert_eq!(
        reasons.iter().map(|r| r.0).collect::<Vec<_>>(),
        vec![31, 33, 35, 37, 39]
    );
}

#[test]
fn a_loop_that_does_not_close_skips_the_face() {
    // the composite outer boundary without its last line
    let text = plate(&["144,1,1,0,23"]).replacen("102,4,3,5,7,9;", "102,3,3,5,7;  ", 1);
    let r = read_iges_faces(&text, "plate.igs", usize::MAX).unwrap();
    let [s] = r.skipped_faces.listed() else {
        panic!("{r:?}")
    };
    assert!(s.reason.contains("does not close"), "{}", s.reason);
}

/// A bilinear surface with the corners `(u, v) = (0, 1)` and `(1, 1)` at `top` (D1); its
/// boundary (142, D21) as three lines in space around the triangle `(0, 0)`, `(10, 0)`,
/// `(5, 10)` and the four sides of the unit square in `(u, v)`; the trimmed surface (D23).
fn triangle(top: [[f64; 3]; 2]) -> String {
    let mut w = IgesWriter::new();
    let net = Points::from_3d(&[[0.0, 0.0, 0.0], top[0], [10.0, 0.0, 0.0], top[1]]).unwrap();
    let s = BSplineSurface::new(
        1,
        1,
        vec![0.0, 0.0, 1.0, 1.0],
        vec![0.0, 0.0, 1.0, 1.0],
        net,
        (2, 2),
    )
    .unwrap();
    w.add_surface(&Surface::BSpline(s)).unwrap();
    let triangle = [[0.0, 0.0], [10.0, 0.0], [5.0, 10.0], [0.0, 0.0]];
    for k in 0..3 {
        w.add_object(&polyline(&triangle[k..k + 2], 1.0, true))
            .unwrap();
    }
    let square = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0], [0.0, 0.0]];
    for k in 0..4 {
        w.add_object(&polyline(&square[k..k + 2], 1.0, false))
            .unwrap();
    }
    for (ty, text) in [
        (102, "102,3,3,5,7"),
        (102, "102,4,9,11,13,15"),
        (142, "142,0,1,19,17,1"),
        (144, "144,1,1,0,21"),
    ] {
        w.entities.push((
            ty,
            0,
            text.split(',').map(String::from).collect(),
            "00000000",
        ));
    }
    w.finish("pole.igs", "20000101.000000")
}

#[test]
fn an_edge_left_out_at_a_pole_is_a_degenerate_edge() {
    // the side v = 1 collapsed to the point (5, 10, 0): the model-space boundary has three
    // lines, the parameter-space boundary four
    let apex = [5.0, 10.0, 0.0];
    let r = read_iges_faces(&triangle([apex, apex]), "pole.igs", usize::MAX).unwrap();
    let [f] = r.faces.as_slice() else {
        panic!("{:?}", r.skipped_faces)
    };
    assert_eq!(f.pcurves, None);
    assert_eq!(f.edge_ids, vec![vec![3, 5, 0, 7]]);
    let pole = &f.face.outer().edges()[2];
    let (a, b) = pole.curve().domain();
    for t in [a, b] {
        assert_eq!(pole.curve().eval(t).unwrap(), apex.to_vec());
    }
    // no pole (the side v = 1 from (4, 10) to (6, 10)): the pieces do not pair, the edges
    // keep no pcurves and say why
    let r = read_iges_faces(
        &triangle([[4.0, 10.0, 0.0], [6.0, 10.0, 0.0]]),
        "pole.igs",
        usize::MAX,
    )
    .unwrap();
    let [f] = r.faces.as_slice() else {
        panic!("{:?}", r.skipped_faces)
    };
    let why = f.pcurves.as_deref().unwrap_or_default();
    assert!(
        why.contains("parameter-space curve has 4 pieces, the model-space curve 3"),
        "{why}"
    );
    assert!(f.face.loops().all(|l| !l.has_pcurves()));
}

#[test]
fn a_bounded_surface_reads_its_boundaries_each_curve_in_its_sense() {
    // 141 boundaries: the composite outer curve as written, the hole reversed (SENSE = 2)
    let text = plate(&[
        "141,1,1,1,1,19,1,1,21",
        "141,1,1,1,1,25,2,1,27",
        "143,1,1,2,31,33",
        "143,1,1,1,3",
    ]);
    let r = read_iges_faces(&text, "plate.igs", usize::MAX).unwrap();
    let [f] = r.faces.as_slice() else {
        panic!("one face: {:?}", r.skipped_faces)
    };
    assert_eq!((f.id, f.surface_id, f.pcurves.as_deref()), (35, 1, None));
    assert_eq!(f.edge_ids, vec![vec![3, 5, 7, 9], vec![25]]);
    let hole = &f.face.inner()[0].edges()[0];
    let (a, _) = hole.curve().domain();
    // the hole runs (0.3, 0.3) -> (0.3, 0.7) -> ... as written; reversed it starts towards (0.7, 0.3)
    let p = hole.pcurve().unwrap();
    let after = p.eval(a + 0.5).unwrap();
    assert!(
        (after[0] - 0.5).abs() < 1e-12 && (after[1] - 0.3).abs() < 1e-12,
        "{after:?}"
    );
    assert_eq!(hole.curve().eval(a + 0.5).unwrap(), vec![5.0, 3.0, 0.0]);
    let region = f.face.trim_region().unwrap();
    assert!(region.contains(0.1, 0.1) && !region.contains(0.5, 0.5));
    let [s] = r.skipped_faces.listed() else {
        panic!("{:?}", r.skipped_faces)
    };
    assert_eq!((s.id, s.entity.as_str()), (37, "IGES entity 143"));
    assert!(
        s.reason.contains("D3 is a curve, not a boundary"),
        "{}",
        s.reason
    );
}

/// The plate with its hole as the Python package's tests read it
/// (`crates/lekalo-py/tests/data/plate_144.igs`): this test fails when the file differs from
/// what `plate` writes, and rewrites it when `LEKALO_WRITE_FIXTURES` is set.
#[test]
fn the_python_fixture_is_the_plate() {
    let text = plate(&["144,1,1,1,23,29"]);
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../lekalo-py/tests/data/plate_144.igs");
    if std::env::var_os("LEKALO_WRITE_FIXTURES").is_some() {
        std::fs::write(&path, &text).unwrap();
    }
    assert_eq!(std::fs::read_to_string(&path).unwrap(), text);
}

/// The reason face `id` of `text` was skipped.
fn skip_reason(text: &str, id: u64) -> String {
    let r = read_iges_faces(text, "plate.igs", usize::MAX).unwrap();
    let s = r.skipped_faces.iter().find(|s| s.id == id);
    s.unwrap_or_else(|| panic!("face D{id} not skipped: {r:?}"))
        .reason
        .clone()
}

/// Composite curves that contain themselves, directly or through others, and a trimmed surface
/// whose boundary refers back to it: each face skipped, naming the entities of the cycle in
/// order; never a stack overflow or an endless loop.
#[test]
fn reference_cycles_are_refused_naming_their_entities() {
    // D31 lists a line and itself
    let own = plate(&["102,2,3,31", "142,0,1,21,31,1", "144,1,1,0,33"]);
    let why = skip_reason(&own, 35);
    assert!(
        why.contains("composite curve D31 contains itself: D31 → D31"),
        "{why}"
    );
    // D31 lists D33, which lists D31, below the 142's model-space curve
    let two = plate(&["102,1,33", "102,2,3,31", "142,0,1,21,31,1", "144,1,1,0,35"]);
    let why = skip_reason(&two, 37);
    assert!(why.contains("D31 → D33 → D31"), "{why}");
    assert!(why.starts_with("boundary D35: "), "{why}");
    // the boundary's model-space curve is the trimmed surface itself
    let back = plate(&["142,0,1,21,33,1", "144,1,1,0,31"]);
    let why = skip_reason(&back, 33);
    assert!(why.contains("D33 is an entity 144, not a curve"), "{why}");
    // a bounded surface (143) whose boundary (141) lists a cycle of composite curves
    let bounded = plate(&[
        "102,1,33",
        "102,1,31",
        "141,0,0,1,1,31,1,1,21",
        "143,0,1,1,35",
    ]);
    let why = skip_reason(&bounded, 37);
    assert!(why.contains("D31 → D33 → D31"), "{why}");
}

/// A chain of 100,000 composite curves, each listing the next: refused at the nesting limit,
/// naming where it starts, in well under a second of work per face.
#[test]
fn a_chain_of_100000_composite_curves_is_refused_at_the_nesting_limit() {
    let n = 100_000u64;
    let mut entities: Vec<String> = (0..n)
        .map(|k| {
            if k + 1 == n {
                "102,1,3".to_string()
            } else {
                format!("102,1,{}", 31 + 2 * (k + 1))
            }
        })
        .collect();
    let boundary = 31 + 2 * n;
    entities.push("142,0,1,21,31,1".into());
    entities.push(format!("144,1,1,0,{boundary}"));
    let refs: Vec<&str> = entities.iter().map(String::as_str).collect();
    let text = plate(&refs);
    let start = std::time::Instant::now();
    let why = skip_reason(&text, boundary + 2);
    assert!(
        why.contains("composite curves nested more than 8 deep (D31 → D33 → … → D"),
        "{why}"
    );
    assert!(start.elapsed().as_secs() < 30, "{:?}", start.elapsed());
}

/// Composite curves that list the next one twenty times over, seven deep (20^7 copies of one
/// line): the copies count against the size limit and the read fails with `OverLimit` naming
/// `--max-size` once past it, instead of expanding them; within the limit the same
/// references (listed twice, three deep) are read.
#[test]
fn composite_curves_listed_many_times_over_stop_at_the_size_limit() {
    let chain = |times: usize, depth: u64| {
        let mut entities: Vec<String> = (0..depth)
            .map(|k| {
                let next = if k + 1 == depth { 3 } else { 31 + 2 * (k + 1) };
                let list = vec![next.to_string(); times].join(",");
                format!("102,{times},{list}")
            })
            .collect();
        entities.push("142,0,1,21,31,1".into());
        entities.push(format!("144,1,1,0,{}", 31 + 2 * depth));
        entities
    };
    let entities = chain(20, 7);
    let refs: Vec<&str> = entities.iter().map(String::as_str).collect();
    let start = std::time::Instant::now();
    let e = read_iges_faces(&plate(&refs), "plate.igs", 1_000_000).unwrap_err();
    assert!(matches!(e, crate::IoError::OverLimit { .. }), "{e}");
    let msg = e.to_string();
    assert!(
        msg.contains("face D47") && msg.contains("above the size limit 1000000"),
        "{msg}"
    );
    assert!(msg.contains("--max-size"), "{msg}");
    assert!(start.elapsed().as_secs() < 30, "{:?}", start.elapsed());
    // small repetitions read (the loop does not close, which is the face's own matter)
    let entities = chain(2, 3);
    let refs: Vec<&str> = entities.iter().map(String::as_str).collect();
    let why = skip_reason(&plate(&refs), 39);
    assert!(!why.contains("size limit"), "{why}");
}

/// An entity 114 of one bicubic patch `S(u, v) = (10 u, 10 v, z)` on `[0, 1]²` (IGES 5.3
/// §4.19: `CTYPE, PTYPE, M, N`, the breakpoints, then 16 coefficients of `u^a v^b` at
/// `4 b + a` per coordinate).
fn patch_114(z: f64) -> Vec<String> {
    let mut c = vec!["0.".to_string(); 48];
    c[1] = "10.".into();
    c[16 + 4] = "10.".into();
    c[32] = format!("{z:?}");
    let mut f: Vec<String> = "114,3,0,1,1,0.,1.,0.,1."
        .split(',')
        .map(String::from)
        .collect();
    f.extend(c);
    f
}

#[test]
fn an_independent_surface_nothing_trims_is_an_untrimmed_face() {
    let mut w = IgesWriter::new();
    // D1 independent; D3 physically dependent (subordinate switch 01): a part of something
    // else, not a face
    w.entities.push((114, 0, patch_114(0.0), "00000000"));
    w.entities.push((114, 0, patch_114(5.0), "00010000"));
    let text = w.finish("patches.igs", "20000101.000000");
    let r = read_iges_faces(&text, "patches.igs", usize::MAX).unwrap();
    assert_eq!(r.shapes.len(), 2, "both read as surfaces");
    assert!(r.skipped_faces.is_empty(), "{:?}", r.skipped_faces);
    let [f] = r.faces.as_slice() else {
        panic!("one face, of D1: {:?}", r.faces.len())
    };
    assert_eq!((f.id, f.surface_id), (1, 1));
    assert_eq!(f.edge_ids, vec![vec![0; 4]]);
    assert_eq!(f.face.loops().count(), 1, "no inner loops");
    let corners: Vec<Vec<f64>> = f
        .face
        .outer()
        .edges()
        .iter()
        .map(|e| e.curve().eval(e.curve().domain().0).unwrap())
        .collect();
    let want = [[0.0, 0.0], [10.0, 0.0], [10.0, 10.0], [0.0, 10.0]];
    for (got, want) in corners.iter().zip(want) {
        assert!(
            (got[0] - want[0]).abs() < 1e-12 && (got[1] - want[1]).abs() < 1e-12 && got[2] == 0.0,
            "corners {corners:?}"
        );
    }
    assert_eq!(f.face.outer().largest_gap(true).unwrap().unwrap().0, 0.0);
    // the surfaces the plate's trimmed surface or its boundaries refer to are no faces of
    // their own
    let plate = read_iges_faces(&plate(&["144,1,1,1,23,29"]), "plate.igs", usize::MAX).unwrap();
    assert_eq!(plate.faces.len(), 1, "the trimmed plate only");
}
