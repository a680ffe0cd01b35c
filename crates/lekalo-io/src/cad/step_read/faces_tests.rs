//! Tests of the faces, on small hand-written files: a plate with a round hole on a plane, a
//! B-spline patch with pcurves, a cylinder with a seam, and faces that cannot be read.

use super::*;
use crate::error::IoError;

pub(crate) fn file(data: &str) -> String {
    format!(
        "ISO-10303-21;\nHEADER;\nFILE_SCHEMA(('AUTOMOTIVE_DESIGN'));\nENDSEC;\nDATA;\n{data}\nENDSEC;\nEND-ISO-10303-21;\n"
    )
}

fn read(data: &str) -> StepRead {
    read_step_faces(&file(data), "t.step", usize::MAX).unwrap()
}

fn face(r: &StepRead, id: u64) -> &StepFace {
    r.faces
        .iter()
        .find(|f| f.id == id)
        .unwrap_or_else(|| panic!("face #{id} not read; skipped {:?}", r.skipped_faces))
}

fn close(a: &[f64], b: &[f64]) -> bool {
    a.len() == b.len() && a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-12)
}

fn ends(c: &lekalo::Curve) -> (Vec<f64>, Vec<f64>) {
    let (a, b) = c.domain();
    (c.eval(a).unwrap(), c.eval(b).unwrap())
}

/// A square plate 10 × 10 on the plane z = 0 with a hole of radius 2 about (5, 5): the top and
/// left edges are used backwards, the hole's circle is one closed edge used backwards.
pub(crate) const PLATE: &str = "
#1=CARTESIAN_POINT('',(0.,0.,0.));
#2=DIRECTION('',(0.,0.,1.));
#3=DIRECTION('',(1.,0.,0.));
#4=AXIS2_PLACEMENT_3D('',#1,#2,#3);
#5=PLANE('',#4);
#11=CARTESIAN_POINT('',(0.,0.,0.));
#12=CARTESIAN_POINT('',(10.,0.,0.));
#13=CARTESIAN_POINT('',(10.,10.,0.));
#14=CARTESIAN_POINT('',(0.,10.,0.));
#21=VERTEX_POINT('',#11);
#22=VERTEX_POINT('',#12);
#23=VERTEX_POINT('',#13);
#24=VERTEX_POINT('',#14);
#30=DIRECTION('',(1.,0.,0.));
#31=VECTOR('',#30,1.);
#32=LINE('',#11,#31);
#33=DIRECTION('',(0.,1.,0.));
#34=VECTOR('',#33,1.);
#35=LINE('',#12,#34);
#36=LINE('',#14,#31);
#37=LINE('',#11,#34);
#41=EDGE_CURVE('',#21,#22,#32,.T.);
#42=EDGE_CURVE('',#22,#23,#35,.T.);
#43=EDGE_CURVE('',#24,#23,#36,.T.);
#44=EDGE_CURVE('',#21,#24,#37,.T.);
#51=ORIENTED_EDGE('',*,*,#41,.T.);
#52=ORIENTED_EDGE('',*,*,#42,.T.);
#53=ORIENTED_EDGE('',*,*,#43,.F.);
#54=ORIENTED_EDGE('',*,*,#44,.F.);
#55=EDGE_LOOP('',(#51,#52,#53,#54));
#56=FACE_OUTER_BOUND('',#55,.T.);
#60=CARTESIAN_POINT('',(5.,5.,0.));
#61=AXIS2_PLACEMENT_3D('',#60,#2,#3);
#62=CIRCLE('',#61,2.);
#63=CARTESIAN_POINT('',(7.,5.,0.));
#64=VERTEX_POINT('',#63);
#65=EDGE_CURVE('',#64,#64,#62,.T.);
#66=ORIENTED_EDGE('',*,*,#65,.F.);
#67=EDGE_LOOP('',(#66));
#68=FACE_BOUND('',#67,.T.);
#70=ADVANCED_FACE('plate',(#56,#68),#5,.T.);
";

#[test]
fn plate_with_a_hole() {
    let r = read(PLATE);
    assert!(r.skipped_faces.is_empty(), "{:?}", r.skipped_faces);
    let f = face(&r, 70);
    assert_eq!((f.name.as_str(), f.surface_id), ("plate", 5));
    assert_eq!(f.edge_ids, vec![vec![41, 42, 43, 44], vec![65]]);
    assert_eq!(f.pcurves, None);
    assert_eq!(f.face.inner().len(), 1);
    // every edge runs along the loop: the top edge (used backwards) from (10, 10) to (0, 10)
    let top = &f.face.outer().edges()[2];
    let (a, b) = ends(top.curve());
    assert!(
        close(&a, &[10.0, 10.0, 0.0]) && close(&b, &[0.0, 10.0, 0.0]),
        "{a:?} {b:?}"
    );
    let (a, b) = ends(top.pcurve().unwrap());
    assert!(
        close(&a, &[10.0, 10.0]) && close(&b, &[0.0, 10.0]),
        "{a:?} {b:?}"
    );
    // the hole, used backwards, runs clockwise
    let hole = &f.face.inner()[0].edges()[0];
    assert_eq!(hole.pcurve().unwrap().dim(), 2);
    let q = hole.curve().eval(hole.curve().domain().0 + 0.1).unwrap();
    assert!(q[1] < 5.0, "clockwise from (7, 5) goes down first: {q:?}");
    let region = f.face.trim_region().unwrap();
    assert!(region.contains(1.0, 1.0) && region.contains(7.5, 5.0));
    assert!(!region.contains(5.0, 5.0) && !region.contains(6.5, 5.0));
    assert!(!region.contains(11.0, 5.0) && !region.contains(5.0, -0.5));
    // read_step does not read faces
    assert!(read_step(&file(PLATE), "t.step").unwrap().faces.is_empty());
}

#[test]
fn plate_in_metres_is_in_millimetres() {
    let metre = "#900=(LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT($,.METRE.));\n";
    let r = read_step_faces(&file(&format!("{metre}{PLATE}")), "t.step", usize::MAX).unwrap();
    let f = face(&r, 70);
    let region = f.face.trim_region().unwrap();
    assert!(region.contains(1000.0, 1000.0) && !region.contains(5000.0, 5000.0));
}

/// A bilinear B-spline patch over (0..10) × (0..10) with its corner (10, 10) raised, bounded by
/// its four boundary curves with pcurves; one surface curve is a complex instance.
pub(crate) const PATCH: &str = "
#101=CARTESIAN_POINT('',(0.,0.,0.));
#102=CARTESIAN_POINT('',(0.,10.,0.));
#103=CARTESIAN_POINT('',(10.,0.,0.));
#104=CARTESIAN_POINT('',(10.,10.,5.));
#105=B_SPLINE_SURFACE_WITH_KNOTS('',1,1,((#101,#102),(#103,#104)),.UNSPECIFIED.,.F.,.F.,.F.,(2,2),(2,2),(0.,1.),(0.,1.),.UNSPECIFIED.);
#111=VERTEX_POINT('',#101);
#112=VERTEX_POINT('',#103);
#113=VERTEX_POINT('',#104);
#114=VERTEX_POINT('',#102);
#121=B_SPLINE_CURVE_WITH_KNOTS('',1,(#101,#103),.UNSPECIFIED.,.F.,.F.,(2,2),(0.,1.),.UNSPECIFIED.);
#122=B_SPLINE_CURVE_WITH_KNOTS('',1,(#103,#104),.UNSPECIFIED.,.F.,.F.,(2,2),(0.,1.),.UNSPECIFIED.);
#123=B_SPLINE_CURVE_WITH_KNOTS('',1,(#102,#104),.UNSPECIFIED.,.F.,.F.,(2,2),(0.,1.),.UNSPECIFIED.);
#124=B_SPLINE_CURVE_WITH_KNOTS('',1,(#101,#102),.UNSPECIFIED.,.F.,.F.,(2,2),(0.,1.),.UNSPECIFIED.);
#131=CARTESIAN_POINT('',(0.,0.));
#132=CARTESIAN_POINT('',(1.,0.));
#133=CARTESIAN_POINT('',(1.,1.));
#134=CARTESIAN_POINT('',(0.,1.));
#141=B_SPLINE_CURVE_WITH_KNOTS('',1,(#131,#132),.UNSPECIFIED.,.F.,.F.,(2,2),(0.,1.),.UNSPECIFIED.);
#142=B_SPLINE_CURVE_WITH_KNOTS('',1,(#132,#133),.UNSPECIFIED.,.F.,.F.,(2,2),(0.,1.),.UNSPECIFIED.);
#143=B_SPLINE_CURVE_WITH_KNOTS('',1,(#134,#133),.UNSPECIFIED.,.F.,.F.,(2,2),(0.,1.),.UNSPECIFIED.);
#144=B_SPLINE_CURVE_WITH_KNOTS('',1,(#131,#134),.UNSPECIFIED.,.F.,.F.,(2,2),(0.,1.),.UNSPECIFIED.);
#150=(GEOMETRIC_REPRESENTATION_CONTEXT(2) PARAMETRIC_REPRESENTATION_CONTEXT() REPRESENTATION_CONTEXT('',''));
#151=DEFINITIONAL_REPRESENTATION('',(#141),#150);
#152=DEFINITIONAL_REPRESENTATION('',(#142),#150);
#153=DEFINITIONAL_REPRESENTATION('',(#143),#150);
#154=DEFINITIONAL_REPRESENTATION('',(#144),#150);
#161=PCURVE('',#105,#151);
#162=PCURVE('',#105,#152);
#163=PCURVE('',#105,#153);
#164=PCURVE('',#105,#154);
#171=SURFACE_CURVE('',#121,(#161),.PCURVE_S1.);
#172=SURFACE_CURVE('',#122,(#162),.PCURVE_S1.);
#173=(BOUNDED_CURVE() CURVE() GEOMETRIC_REPRESENTATION_ITEM() REPRESENTATION_ITEM('') SURFACE_CURVE(#123,(#163),.PCURVE_S1.));
#174=SURFACE_CURVE('',#124,(#164),.PCURVE_S1.);
#181=EDGE_CURVE('',#111,#112,#171,.T.);
#182=EDGE_CURVE('',#112,#113,#172,.T.);
#183=EDGE_CURVE('',#114,#113,#173,.T.);
#184=EDGE_CURVE('',#111,#114,#174,.T.);
#191=ORIENTED_EDGE('',*,*,#181,.T.);
#192=ORIENTED_EDGE('',*,*,#182,.T.);
#193=ORIENTED_EDGE('',*,*,#183,.F.);
#194=ORIENTED_EDGE('',*,*,#184,.F.);
#195=EDGE_LOOP('',(#191,#192,#193,#194));
#196=FACE_OUTER_BOUND('',#195,.T.);
#197=ADVANCED_FACE('patch',(#196),#105,.F.);
";

#[test]
fn bspline_patch_keeps_its_pcurves_in_2d() {
    let r = read(PATCH);
    let f = face(&r, 197);
    assert_eq!((f.name.as_str(), f.pcurves.as_deref()), ("patch", None));
    assert!(!f.face.same_sense());
    let edges = f.face.outer().edges();
    assert!(edges
        .iter()
        .all(|e| e.pcurve().is_some_and(|p| p.dim() == 2)));
    // the top edge (a complex SURFACE_CURVE, used backwards) runs from (1, 1) to (0, 1)
    let (a, b) = ends(edges[2].pcurve().unwrap());
    assert!(
        close(&a, &[1.0, 1.0]) && close(&b, &[0.0, 1.0]),
        "{a:?} {b:?}"
    );
    let (a, b) = ends(edges[2].curve());
    assert!(
        close(&a, &[10.0, 10.0, 5.0]) && close(&b, &[0.0, 10.0, 0.0]),
        "{a:?} {b:?}"
    );
    // each pcurve lies under its edge: S(p(t)) = C(t)
    for e in edges {
        let (p, c) = (e.pcurve().unwrap(), e.curve());
        for t in [0.25, 0.5] {
            let uv = p.eval(t).unwrap();
            let on = f.face.surface().eval(uv[0], uv[1]).unwrap();
            assert!(close(&on, &c.eval(t).unwrap()), "{on:?}");
        }
    }
    let region = f.face.trim_region().unwrap();
    assert!(region.contains(0.5, 0.5) && !region.contains(1.5, 0.5));
}

/// A cylinder of radius 1 and height 2: the bottom and top circles and the seam, used up and
/// down.
pub(crate) const TUBE: &str = "
#150=(GEOMETRIC_REPRESENTATION_CONTEXT(2) PARAMETRIC_REPRESENTATION_CONTEXT() REPRESENTATION_CONTEXT('',''));
#201=CARTESIAN_POINT('',(0.,0.,0.));
#202=DIRECTION('',(0.,0.,1.));
#203=DIRECTION('',(1.,0.,0.));
#204=AXIS2_PLACEMENT_3D('',#201,#202,#203);
#205=CYLINDRICAL_SURFACE('',#204,1.);
#206=CARTESIAN_POINT('',(0.,0.,2.));
#207=AXIS2_PLACEMENT_3D('',#206,#202,#203);
#208=CIRCLE('',#204,1.);
#209=CIRCLE('',#207,1.);
#210=CARTESIAN_POINT('',(1.,0.,0.));
#211=CARTESIAN_POINT('',(1.,0.,2.));
#212=VERTEX_POINT('',#210);
#213=VERTEX_POINT('',#211);
#214=VECTOR('',#202,1.);
#215=LINE('',#210,#214);
#217=CARTESIAN_POINT('',(0.,0.));
#218=DIRECTION('',(0.,1.));
#219=VECTOR('',#218,1.);
#222=LINE('',#217,#219);
#223=CARTESIAN_POINT('',(6.28318530718,0.));
#224=LINE('',#223,#219);
#225=DEFINITIONAL_REPRESENTATION('',(#222),#150);
#226=DEFINITIONAL_REPRESENTATION('',(#224),#150);
#220=PCURVE('',#205,#225);
#221=PCURVE('',#205,#226);
#216=SEAM_CURVE('',#215,(#220,#221),.PCURVE_S1.);
#230=EDGE_CURVE('',#212,#212,#208,.T.);
#231=EDGE_CURVE('',#213,#213,#209,.T.);
#232=EDGE_CURVE('',#212,#213,#216,.T.);
#240=ORIENTED_EDGE('',*,*,#230,.T.);
#241=ORIENTED_EDGE('',*,*,#232,.T.);
#242=ORIENTED_EDGE('',*,*,#231,.F.);
#243=ORIENTED_EDGE('',*,*,#232,.F.);
#244=EDGE_LOOP('',(#240,#241,#242,#243));
#245=FACE_OUTER_BOUND('',#244,.T.);
#246=ADVANCED_FACE('tube',(#245),#205,.T.);
";

#[test]
fn cylinder_with_a_seam() {
    let r = read(TUBE);
    let f = face(&r, 246);
    assert_eq!(f.edge_ids, vec![vec![230, 232, 231, 232]]);
    let edges = f.face.outer().edges();
    // the seam up, then down
    let (a, b) = ends(edges[1].curve());
    assert!(
        close(&a, &[1.0, 0.0, 0.0]) && close(&b, &[1.0, 0.0, 2.0]),
        "{a:?} {b:?}"
    );
    let (a, b) = ends(edges[3].curve());
    assert!(
        close(&a, &[1.0, 0.0, 2.0]) && close(&b, &[1.0, 0.0, 0.0]),
        "{a:?} {b:?}"
    );
    // the file's pcurves are in angles, not in the parameters of the NURBS cylinder
    assert!(edges.iter().all(|e| e.pcurve().is_none()));
    let why = f.pcurves.as_deref().unwrap();
    assert!(why.contains("CYLINDRICAL_SURFACE"), "{why}");
    assert!(
        why.contains("the file's pcurves are in the parameters"),
        "{why}"
    );
    assert!(f.face.trim_region().is_err());
    // the seam as a bare line, without the pcurves: the face says the file gives none
    let bare = TUBE.replace(
        "#232=EDGE_CURVE('',#212,#213,#216,.T.);",
        "#232=EDGE_CURVE('',#212,#213,#215,.T.);",
    );
    let why = face(&read(&bare), 246).pcurves.clone().unwrap();
    assert!(
        why.contains("the file gives none") && why.contains("CYLINDRICAL_SURFACE"),
        "{why}"
    );
}

#[test]
fn a_loop_closed_by_its_shared_vertices_tolerates_curves_that_miss_them() {
    // the right edge's line runs at x = 10.03, 0.03 off its vertices (10, 0) and (10, 10):
    // gaps of 2.1e-3 of the model size (the diagonal, 14.2), above STEP_LOOP_RTOL
    let off = PLATE.replace(
        "#35=LINE('',#12,#34);",
        "#35=LINE('',#15,#34);\n#15=CARTESIAN_POINT('',(10.03,0.,0.));",
    );
    let r = read(&off);
    assert!(r.skipped_faces.is_empty(), "{:?}", r.skipped_faces);
    let f = face(&r, 70);
    // the curve is the file's, cut at the vertices' projections: it keeps its offset
    let right = &f.face.outer().edges()[1];
    let (a, b) = ends(right.curve());
    assert!(
        close(&a, &[10.03, 0.0, 0.0]) && close(&b, &[10.03, 10.0, 0.0]),
        "{a:?} {b:?}"
    );
    let gap = f.face.outer().largest_gap(false).unwrap().unwrap().0;
    assert!(
        gap > STEP_LOOP_RTOL * f.face.model_size()
            && gap < STEP_SHARED_VERTEX_RTOL * f.face.model_size(),
        "{gap}"
    );
    // the same gap where the right edge starts at a vertex of its own (at the same point):
    // the vertices do not close the loop, which is held to STEP_LOOP_RTOL
    let apart = off
        .replace(
            "#42=EDGE_CURVE('',#22,#23,#35,.T.);",
            "#42=EDGE_CURVE('',#25,#23,#35,.T.);",
        )
        .replace(
            "#24=VERTEX_POINT('',#14);",
            "#24=VERTEX_POINT('',#14);\n#25=VERTEX_POINT('',#12);",
        );
    let r = read(&apart);
    assert!(r.faces.is_empty());
    let why = &r.skipped_faces.listed()[0].reason;
    assert!(why.contains("outer loop does not close"), "{why}");
}

#[test]
fn faces_that_cannot_be_read_are_skipped_with_the_reason() {
    // a loop naming an edge that is not in the file
    let missing = PLATE.replace(
        "#55=EDGE_LOOP('',(#51,#52,#53,#54));",
        "#55=EDGE_LOOP('',(#51,#52,#53,#999));",
    );
    let r = read(&missing);
    assert!(r.faces.is_empty());
    assert_eq!(r.skipped_faces.len(), 1);
    assert_eq!(
        (
            r.skipped_faces.listed()[0].id,
            r.skipped_faces.listed()[0].entity.as_str()
        ),
        (70, "ADVANCED_FACE")
    );
    assert!(
        r.skipped_faces.listed()[0]
            .reason
            .contains("#999 of a loop is not defined"),
        "{:?}",
        r.skipped_faces
    );
    // edges out of order do not close the loop
    let shuffled = PLATE.replace("(#51,#52,#53,#54)", "(#51,#53,#52,#54)");
    let why = read(&shuffled).skipped_faces.listed()[0].reason.clone();
    assert!(why.contains("outer loop does not close"), "{why}");
    // a surface curve whose 3-D curve is itself: a cycle of references
    let cyclic = PATCH.replace("#171=SURFACE_CURVE('',#121,", "#171=SURFACE_CURVE('',#171,");
    let why = read(&cyclic).skipped_faces.listed()[0].reason.clone();
    assert!(why.contains("a cycle of references"), "{why}");
    // a face on a surface lekalo does not read
    let offset = PATCH.replace(
        "#197=ADVANCED_FACE('patch',(#196),#105,.F.);",
        "#198=OFFSET_SURFACE('',#105,1.,.F.);\n#197=ADVANCED_FACE('patch',(#196),#198,.F.);",
    );
    let r = read(&offset);
    assert!(
        r.skipped_faces.listed()[0]
            .reason
            .contains("its surface #198 was not read"),
        "{:?}",
        r.skipped_faces
    );
    // a bound that is not a face bound, a face without loops
    let r = read(&PATCH.replace("(#196),#105", "(#105),#105"));
    assert!(
        r.skipped_faces.listed()[0]
            .reason
            .contains("not a FACE_BOUND"),
        "{:?}",
        r.skipped_faces
    );
    let r = read(&PATCH.replace("(#196),#105", "(),#105"));
    assert!(
        r.skipped_faces.listed()[0].reason.contains("no EDGE_LOOP"),
        "{:?}",
        r.skipped_faces
    );
}

#[test]
fn faces_keep_to_the_size_limit() {
    let e = read_step_faces(&file(PATCH), "t.step", 20).unwrap_err();
    assert!(matches!(e, IoError::OverLimit { .. }), "{e}");
    // a multiplicity of 2^40 in an edge refuses the file before allocating
    let huge = PATCH.replace(
        "#121=B_SPLINE_CURVE_WITH_KNOTS('',1,(#101,#103),.UNSPECIFIED.,.F.,.F.,(2,2)",
        "#121=B_SPLINE_CURVE_WITH_KNOTS('',1,(#101,#103),.UNSPECIFIED.,.F.,.F.,(1099511627776,2)",
    );
    assert!(read_step_faces(&file(&huge), "t.step", 1000).is_err());
}

#[test]
fn faces_round_trip_through_json() {
    for (data, id) in [(PLATE, 70), (PATCH, 197), (TUBE, 246)] {
        let r = read(data);
        let f = face(&r, id);
        let line = crate::face_to_json_line(f);
        assert!(!line.contains('\n') && line.starts_with(r#"{"lekalo":1,"type":"face","#));
        let back = crate::read_face(&line, "f.jsonl").unwrap();
        assert_eq!(crate::face_to_json_line(&back), line);
        assert_eq!(
            (back.id, &back.name, &back.edge_ids),
            (f.id, &f.name, &f.edge_ids)
        );
    }
}

#[test]
fn face_json_errors_name_the_field() {
    let line = crate::face_to_json_line(face(&read(PATCH), 197));
    let v: serde_json::Value = serde_json::from_str(&line).unwrap();
    let with = |f: &dyn Fn(&mut serde_json::Value)| {
        let mut w = v.clone();
        f(&mut w);
        crate::read_face(&w.to_string(), "f.jsonl")
            .unwrap_err()
            .to_string()
    };
    let e = with(&|w| w["type"] = "bspline_surface".into());
    assert!(e.contains("field `type`"), "{e}");
    let e = with(&|w| {
        w.as_object_mut().unwrap().remove("surface");
    });
    assert!(e.contains("field `surface`"), "{e}");
    // a pcurve of three coordinates
    let e = with(&|w| w["outer"][1]["pcurve"] = w["outer"][1]["curve"].clone());
    assert!(
        e.contains("outer[1].pcurve") && e.contains("expected 2, got 3"),
        "{e}"
    );
    // two edges swapped: the loop does not close
    let e = with(&|w| {
        let a = w["outer"][1].clone();
        w["outer"][1] = w["outer"][2].clone();
        w["outer"][2] = a;
    });
    assert!(e.contains("does not close"), "{e}");
    let e = with(&|w| w["outer"] = serde_json::json!([]));
    assert!(
        e.contains("field `outer`") && e.contains("edges in a loop"),
        "{e}"
    );
    // an optional field of the wrong type, or an id beyond 64 bits, is named, not defaulted
    // (an id of 10^30 was read as 0)
    let huge: serde_json::Value = serde_json::from_str("1e30").unwrap();
    type Change<'a> = &'a dyn Fn(&mut serde_json::Value);
    let cases: [(&str, Change<'_>); 8] = [
        ("field `id`", &|w| w["id"] = huge.clone()),
        ("field `id`", &|w| w["id"] = serde_json::json!(-1)),
        ("field `surface_id`", &|w| w["surface_id"] = "5".into()),
        ("field `outer[0].edge_id`", &|w| {
            w["outer"][0]["edge_id"] = 1.5.into()
        }),
        ("field `name`", &|w| w["name"] = serde_json::json!(["a"])),
        ("field `same_sense`", &|w| w["same_sense"] = 1.into()),
        ("field `pcurves`", &|w| w["pcurves"] = true.into()),
        ("field `inner`", &|w| w["inner"] = serde_json::json!({})),
    ];
    for (needle, f) in cases {
        let e = with(f);
        assert!(e.contains(needle), "{needle}: {e}");
    }
    // left out or null: the defaults
    let mut w = v.clone();
    for key in ["id", "name", "surface_id", "same_sense", "pcurves"] {
        w[key] = serde_json::Value::Null;
    }
    let f = crate::read_face(&w.to_string(), "f.jsonl").unwrap();
    assert_eq!((f.id, f.name.as_str()), (0, ""));
}

/// Open CASCADE writes the pcurves of B-spline faces as 2-D lines on the edges' parameters:
/// they are read, and the surface at each pcurve's points is the edge's curve.
#[test]
fn line_pcurves_of_open_cascade_lie_under_their_edges() {
    let text = include_str!("../../../tests/data/occ/mixed_ap242_m.step");
    let r = read_step_faces(text, "mixed_ap242_m.step", usize::MAX).unwrap();
    assert_eq!((r.faces.len(), r.skipped_faces.len()), (2, 0));
    for f in &r.faces {
        assert_eq!(f.pcurves, None, "face #{}", f.id);
        let size = f.face.model_size();
        for e in f.face.outer().edges() {
            let (p, c) = (e.pcurve().unwrap(), e.curve());
            // both run from the edge's start to its end
            let (pa, pb) = p.domain();
            let (ca, cb) = c.domain();
            for (s, t) in [(pa, ca), (pb, cb)] {
                let uv = p.eval(s).unwrap();
                let on = f.face.surface().eval(uv[0], uv[1]).unwrap();
                let q = c.eval(t).unwrap();
                let d: f64 = on
                    .iter()
                    .zip(&q)
                    .map(|(x, y)| (x - y) * (x - y))
                    .sum::<f64>()
                    .sqrt();
                assert!(d <= 1e-6 * size, "face #{} {d}", f.id);
            }
        }
        let region = f.face.trim_region().unwrap();
        let ((u0, u1), (v0, v1)) = f.face.surface().domain();
        assert!(region.contains(0.5 * (u0 + u1), 0.5 * (v0 + v1)));
    }
}

#[test]
fn faces_of_triangles_are_read_as_meshes_beside_the_faces() {
    // the plate and, beside it, faces of one triangle on the plate's plane (AP242)
    let r = read(&format!(
        "{PLATE}
#200=COORDINATES_LIST('',3,((0.,0.,0.),(1.,0.,0.),(0.,1.,0.)));
#201=COMPLEX_TRIANGULATED_FACE('',#200,3,((0.,0.,1.)),#5,(),(),((1,2,3)));
#202=TRIANGULATED_FACE('',#200,3,((0.,0.,1.)),#5,(),((1,2,3)));"
    ));
    assert_eq!(r.faces.len(), 1, "the plate");
    assert!(r.skipped_faces.is_empty(), "{:?}", r.skipped_faces);
    let read: Vec<(u64, &str, Option<u64>, usize)> = r
        .triangulations
        .iter()
        .map(|t| (t.id, t.entity.as_str(), t.link, t.triangles.len()))
        .collect();
    assert_eq!(
        read,
        vec![
            (201, "COMPLEX_TRIANGULATED_FACE", Some(5), 1),
            (202, "TRIANGULATED_FACE", Some(5), 1)
        ]
    );
}
