//! Tests of the faces of triangles, on small hand-written AP242 files in inches: explicit
//! triangles, strips and fans with and without `pnindex`, orientations, and files that are
//! refused.

use super::faces_tests::file;
use super::*;
use crate::error::IoError;

/// The unit context of the files below: the inch, 25.4 mm.
const INCH: &str = "
#90=( LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT(.MILLI.,.METRE.) );
#91=LENGTH_MEASURE_WITH_UNIT(LENGTH_MEASURE(25.4),#90);
#92=( CONVERSION_BASED_UNIT('INCH',#91) LENGTH_UNIT() NAMED_UNIT(*) );
#93=( GEOMETRIC_REPRESENTATION_CONTEXT(3) GLOBAL_UNIT_ASSIGNED_CONTEXT((#92)) REPRESENTATION_CONTEXT('',''));";

/// Six points in the plane z = 1 (inches): a row 1..4 along x at y = 0 and y = 1, zig-zag.
const POINTS: &str = "#1=COORDINATES_LIST('',6,((0.,0.,1.),(0.,1.,1.),(1.,0.,1.),(1.,1.,1.),(2.,0.,1.),(2.,1.,1.)));";

fn read(data: &str) -> StepRead {
    read_step_faces(
        &file(&format!("{INCH}\n{POINTS}\n{data}")),
        "t.stp",
        usize::MAX,
    )
    .unwrap()
}

fn only(r: &StepRead) -> &StepTriangulation {
    let [t] = &r.triangulations[..] else {
        panic!(
            "one triangulation: {:?}; skipped {:?}",
            r.triangulations, r.skipped_faces
        )
    };
    t
}

/// The reason the one face of `data` was not read.
fn refused(data: &str) -> String {
    let r = read(data);
    assert!(r.triangulations.is_empty(), "{:?}", r.triangulations);
    let [s] = r.skipped_faces.listed() else {
        panic!("one skipped face: {:?}", r.skipped_faces)
    };
    assert_eq!(s.id, 10, "the face is named");
    s.reason.clone()
}

/// The z of the normal of each triangle (`(b − a) × (c − a)`), in order.
fn turns(t: &StepTriangulation) -> Vec<f64> {
    let p = |k: u32| t.vertices.point(k as usize).to_vec();
    t.triangles
        .iter()
        .map(|&[a, b, c]| {
            let (a, b, c) = (p(a), p(b), p(c));
            (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
        })
        .collect()
}

#[test]
fn explicit_triangles_are_read_in_millimetres_as_written() {
    let r = read(
        "#10=TRIANGULATED_FACE('tri',#1,6,((0.,0.,1.)),$,(),((1,3,2),(2,3,4),(3,5,4),(4,5,6)));",
    );
    assert_eq!(r.length_unit, "INCH (25.4 mm)");
    let t = only(&r);
    assert_eq!(
        (t.id, t.entity.as_str(), t.name.as_str()),
        (10, "TRIANGULATED_FACE", "tri")
    );
    assert_eq!(t.link, None);
    assert_eq!(t.vertices.len(), 6);
    assert_eq!(t.vertices.point(5), &[2.0 * 25.4, 25.4, 25.4]);
    assert_eq!(
        t.triangles,
        vec![[0, 2, 1], [1, 2, 3], [2, 4, 3], [3, 4, 5]]
    );
    assert!(turns(t).iter().all(|&z| z > 0.0), "{:?}", turns(t));
    // the normal is a direction: not scaled
    assert_eq!(t.normals, vec![[0.0, 0.0, 1.0]]);
    assert_eq!(t.dropped, 0);
    let m = t.to_mesh();
    assert_eq!((m.vertices.len(), m.uv.len(), m.triangles.len()), (6, 6, 4));
    assert_eq!(m.facet_normal(0), Some([0.0, 0.0, 1.0]));
}

#[test]
fn a_strip_alternates_and_a_fan_turns_about_its_first_point() {
    // a strip of 4 points: (1,3,2), then (2,3,4), turned as the first; a fan of 4 points
    // about point 3: (3,5,6), (3,6,4)
    let r = read("#10=COMPLEX_TRIANGULATED_FACE('',#1,6,(),$,(),((1,3,2,4)),((3,5,6,4)));");
    let t = only(&r);
    assert_eq!(t.entity, "COMPLEX_TRIANGULATED_FACE");
    assert_eq!(
        t.triangles,
        vec![[0, 2, 1], [1, 2, 3], [2, 4, 5], [2, 5, 3]]
    );
    let z = turns(t);
    assert!(
        z.iter().all(|&z| z > 0.0),
        "every triangle turns as the first: {z:?}"
    );
    // the four triangles cover the 2 × 1 rectangle once: areas add up
    let area: f64 = z.iter().map(|z| z / 2.0).sum();
    assert!((area - 2.0 * 25.4 * 25.4).abs() < 1e-9, "{area}");
    assert!(t.normals.is_empty());
}

#[test]
fn pnindex_names_the_points_in_the_coordinates_list() {
    // the face uses points 6, 4, 5, 3 of the list as its points 1..4; a strip of 4 and a fan
    // of 4 over them, with one normal per point
    let r = read(
        "#10=COMPLEX_TRIANGULATED_FACE('',#1,4,((0.,0.,1.),(0.,0.,1.),(0.,0.,1.),(0.,0.,1.)),$,(6,4,5,3),((1,2,3,4)),((3,1,2,4)));",
    );
    let t = only(&r);
    let want: Vec<[f64; 3]> = [[2.0, 1.0], [1.0, 1.0], [2.0, 0.0], [1.0, 0.0]]
        .iter()
        .map(|[x, y]| [x * 25.4, y * 25.4, 25.4])
        .collect();
    let got: Vec<[f64; 3]> = t.vertices.iter().map(|p| [p[0], p[1], p[2]]).collect();
    assert_eq!(got, want);
    // strip (1,2,3), (3,2,4); fan (3,1,2), (3,2,4)
    assert_eq!(
        t.triangles,
        vec![[0, 1, 2], [2, 1, 3], [2, 0, 1], [2, 1, 3]]
    );
    assert_eq!(t.normals.len(), 4);
    // (1,2,3) = ((2,1), (1,1), (2,0)) turns counter-clockwise seen from +z: all the others too
    assert!(turns(t).iter().all(|&z| z > 0.0), "{:?}", turns(t));
}

#[test]
fn triangles_of_two_equal_indices_are_dropped_and_counted() {
    // a strip that repeats 4 to turn: (1,3,2), (3,2,4)→(2,3,4), (3,4,4) dropped, (4,4,5)
    // dropped, (4,5,6)
    let r = read("#10=COMPLEX_TRIANGULATED_FACE('',#1,6,(),$,(),((1,3,2,4,4,5,6)),());");
    let t = only(&r);
    assert_eq!(t.dropped, 2);
    assert_eq!(t.triangles.len(), 3);
}

#[test]
fn surface_sets_are_read_and_shells_are_not_read_twice() {
    let r = read(
        "#10=TRIANGULATED_SURFACE_SET('set',#1,6,(),(),((1,3,2),(2,3,4)));
#11=COMPLEX_TRIANGULATED_SURFACE_SET('',#1,6,(),(),((3,5,4,6)),());
#12=TESSELLATED_SHELL('',(#10,#11),$);",
    );
    let got: Vec<(u64, usize)> = r
        .triangulations
        .iter()
        .map(|t| (t.id, t.triangles.len()))
        .collect();
    assert_eq!(got, vec![(10, 2), (11, 2)]);
    assert_eq!(r.triangulations[0].name, "set");
}

#[test]
fn faces_of_triangles_are_read_with_faces_only() {
    let text = file(&format!(
        "{INCH}\n{POINTS}\n#10=TRIANGULATED_FACE('',#1,6,(),$,(),((1,3,2)));"
    ));
    let r = read_step(&text, "t.stp").unwrap();
    assert!(r.triangulations.is_empty());
    assert_eq!(r.skipped.len(), 1, "listed as tessellated geometry");
    assert!(r.skipped.listed()[0].reason.contains("--faces"));
}

#[test]
fn hostile_faces_are_refused_with_the_reason() {
    let face = |pnmax: &str, normals: &str, pnindex: &str, strips: &str, fans: &str| {
        format!("#10=COMPLEX_TRIANGULATED_FACE('',#1,{pnmax},({normals}),$,({pnindex}),({strips}),({fans}));")
    };
    let cases = [
        (
            face("6", "", "", "(1,0,2)", ""),
            "triangle strip 1 has index 0 at position 2: indices start at 1",
        ),
        (
            face("6", "", "", "(1,2,7)", ""),
            "triangle strip 1 has index 7 at position 3, past pnmax 6",
        ),
        (
            face("3", "", "1,2,9", "(1,2,3)", ""),
            "pnindex has index 9 at position 3, past the 6 points of COORDINATES_LIST #1",
        ),
        (
            face("6", "", "", "", "(1,2)"),
            "triangle fan 1 has 2 indices, fewer than 3",
        ),
        (
            face("6", "", "", "(1,2.5,3)", ""),
            "triangle strip 1 has a value at position 2 that is not a positive integer",
        ),
        (
            face("6", "", "", "(1,-2,3)", ""),
            "position 2 that is not a positive integer",
        ),
        (
            face("4", "", "", "(1,2,3)", ""),
            "pnmax 4 without pnindex, but COORDINATES_LIST #1 has 6 points",
        ),
        (
            face("3", "", "1,2", "(1,2,3)", ""),
            "pnmax 3, but pnindex lists 2 points",
        ),
        (
            face("6", "(0.,0.,1.),(0.,0.,1.)", "", "(1,2,3)", ""),
            "2 normals for pnmax 6 points",
        ),
        (
            face("6", "(0.,1.)", "", "(1,2,3)", ""),
            "normal 1 has 2 numbers, not 3",
        ),
        (
            face("6", "", "", "(1,1,2)", ""),
            "no triangle of any area (1 with two equal indices)",
        ),
        (
            face("6", "", "", "", ""),
            "no triangle of any area (0 with two equal indices)",
        ),
        (
            "#10=COMPLEX_TRIANGULATED_FACE('',#1,6,(),$,(),((1,2,3)));".into(),
            "7 attributes, a COMPLEX_TRIANGULATED_FACE has 8",
        ),
        (
            "#10=TRIANGULATED_FACE('',#1,6,(),$,(),((1,2,3,4)));".into(),
            "triangle 1 has 4 indices, not 3",
        ),
        (
            "#10=TRIANGULATED_FACE('',#2,6,(),$,(),((1,2,3)));#2=CARTESIAN_POINT('',(0.,0.,0.));"
                .into(),
            "its coordinates #2 are a CARTESIAN_POINT, not a COORDINATES_LIST",
        ),
        (
            "#10=TRIANGULATED_FACE('',#3,6,(),$,(),((1,2,3)));".into(),
            "its coordinates #3 are not defined",
        ),
    ];
    for (data, want) in cases {
        let why = refused(&data);
        assert!(why.contains(want), "{data}\n  gave: {why}\n  want: {want}");
    }
}

#[test]
fn numbers_past_the_range_of_doubles_are_refused_by_the_parser() {
    let text = file(&format!(
        "{INCH}\n{POINTS}\n#10=TRIANGULATED_FACE('',#1,6,((0.,1.E999,0.)),$,(),((1,3,2)));"
    ));
    let e = read_step_faces(&text, "t.stp", usize::MAX).unwrap_err();
    assert!(matches!(e, IoError::Syntax { .. }), "{e}");
}

#[test]
fn hostile_coordinate_lists_are_refused_with_the_reason() {
    let cases = [
        (
            "#2=COORDINATES_LIST('',3,((0.,0.,0.),(1.,0.,0.)));",
            "COORDINATES_LIST #2 declares 3 points and lists 2",
        ),
        (
            "#2=COORDINATES_LIST('',0,());",
            "COORDINATES_LIST #2 declares 0 points and lists 0",
        ),
        (
            "#2=COORDINATES_LIST('',3,((0.,0.,0.),(1.,0.),(0.,1.,0.)));",
            "point 2 of COORDINATES_LIST #2 has 2 numbers, not 3",
        ),
        (
            "#2=COORDINATES_LIST('',3,((0.,0.,0.),(1.,0.,0.),(0.,1.,1.E308)));",
            "point 3 of COORDINATES_LIST #2 is not finite in millimetres",
        ),
    ];
    for (list, want) in cases {
        let why = refused(&format!(
            "{list}\n#10=TRIANGULATED_FACE('',#2,3,(),$,(),((1,2,3)));"
        ));
        assert!(why.contains(want), "{list}\n  gave: {why}\n  want: {want}");
    }
}

#[test]
fn the_size_limit_is_checked_before_the_mesh_is_made() {
    let text = file(&format!(
        "{INCH}\n{POINTS}\n#10=COMPLEX_TRIANGULATED_FACE('',#1,6,(),$,(),((1,3,2,4,3,5,4,6)),());"
    ));
    // 6 coordinates, then 6 points and 6 triangles
    assert!(read_step_faces(&text, "t.stp", 18).is_ok());
    let e = read_step_faces(&text, "t.stp", 17).unwrap_err();
    assert!(
        matches!(e, IoError::OverLimit { .. })
            && e.to_string().contains("12 mesh points and triangles"),
        "{e}"
    );
}

/// The normals of the vertices, for mesh files: the file's made unit (a planar face's one for
/// every vertex), a zero one the average of its triangles' (which turn about +z here), none
/// when the file gives none.
#[test]
fn vertex_normals_are_the_file_s_made_unit() {
    let r = read(
        "#10=TRIANGULATED_FACE('',#1,6,((0.,0.,2.),(0.,0.6,0.8),(0.,0.,0.),(0.,0.,1.),(3.,0.,4.),(0.,0.,1.)),$,(),((1,3,2),(2,3,4),(3,5,4),(4,5,6)));",
    );
    let n = only(&r).vertex_normals();
    assert_eq!(n.len(), 6);
    let near = |k: usize, want: [f64; 3]| {
        let got = n[k].expect("a normal");
        assert!(
            (0..3).all(|d| (got[d] - want[d]).abs() <= 1e-15),
            "vertex {k}: {got:?} against {want:?}"
        );
    };
    near(0, [0.0, 0.0, 1.0]); // scaled to unit length
    near(1, [0.0, 0.6, 0.8]); // kept
    near(2, [0.0, 0.0, 1.0]); // zero: its triangles', all +z
    near(4, [0.6, 0.0, 0.8]);
    let r = read("#10=TRIANGULATED_FACE('',#1,6,((0.,0.,-3.)),$,(),((1,2,3),(2,4,3)));");
    assert_eq!(
        only(&r).vertex_normals(),
        vec![Some([0.0, 0.0, -1.0]); 6],
        "a planar face's one normal at every vertex"
    );
    let r = read("#10=TRIANGULATED_FACE('',#1,6,(),$,(),((1,3,2)));");
    assert!(only(&r).vertex_normals().is_empty(), "none given");
}
