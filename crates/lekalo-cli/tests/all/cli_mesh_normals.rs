//! End-to-end tests of the normals `lekalo mesh` writes: the exact normals of a meshed face
//! (a spherical cap round its pole, either sense), the file's normals of faces of triangles,
//! each unit and on the side its triangles turn about, and STL's facet normals on that side.

#![allow(clippy::missing_assert_message)] // assert_cmd's assertions print the output

use std::fs;

use crate::common;
use common::{dir_with, lekalo, p};

/// A cap of the sphere of radius 5 about the origin above z = 3, bounded by the circle of
/// radius 4 there (no seam edge: cut by the mesher); `@SENSE@` the face's sense, `@BOUND@` its
/// loop's (the cap either way: its normal outward with `.T.`, inward with `.F.` and the loop
/// reversed).
const CAP: &str = "ISO-10303-21;
HEADER;
FILE_SCHEMA(('AUTOMOTIVE_DESIGN'));
ENDSEC;
DATA;
#1=CARTESIAN_POINT('',(0.,0.,0.));
#2=DIRECTION('',(0.,0.,1.));
#3=DIRECTION('',(1.,0.,0.));
#4=AXIS2_PLACEMENT_3D('',#1,#2,#3);
#5=SPHERICAL_SURFACE('',#4,5.);
#6=CARTESIAN_POINT('',(0.,0.,3.));
#7=AXIS2_PLACEMENT_3D('',#6,#2,#3);
#8=CIRCLE('',#7,4.);
#9=CARTESIAN_POINT('',(4.,0.,3.));
#10=VERTEX_POINT('',#9);
#11=EDGE_CURVE('',#10,#10,#8,.T.);
#12=ORIENTED_EDGE('',*,*,#11,.T.);
#13=EDGE_LOOP('',(#12));
#14=FACE_OUTER_BOUND('',#13,@BOUND@);
#15=ADVANCED_FACE('cap',(#14),#5,@SENSE@);
ENDSEC;
END-ISO-10303-21;
";

/// Faces of triangles in millimetres: a square whose one normal (planar) is given, not of
/// unit length; a square with a normal per point, one of them zero; a square with none.
const TRIANGLES: &str = "ISO-10303-21;
HEADER;
FILE_SCHEMA(('AP242_MANAGED_MODEL_BASED_3D_ENGINEERING_MIM_LF'));
ENDSEC;
DATA;
#1=COORDINATES_LIST('',4,((0.,0.,0.),(1.,0.,0.),(1.,1.,0.),(0.,1.,0.)));
#2=TRIANGULATED_FACE('planar',#1,4,((0.,0.,2.)),$,(),((1,2,3),(1,3,4)));
#3=COORDINATES_LIST('',4,((2.,0.,0.),(3.,0.,0.),(3.,1.,0.),(2.,1.,0.)));
#4=TRIANGULATED_FACE('each',#3,4,((0.,0.,1.),(0.,0.6,0.8),(0.,0.,0.),(0.6,0.,0.8)),$,(),((1,2,3),(1,3,4)));
#5=TRIANGULATED_FACE('none',#3,4,(),$,(),((1,2,3)));
ENDSEC;
END-ISO-10303-21;
";

/// An OBJ file: its vertices, its normals, and each face's vertex and normal indices
/// (0-based; the normal `None` for `f i j k`).
struct Obj {
    v: Vec<[f64; 3]>,
    vn: Vec<[f64; 3]>,
    f: Vec<[(usize, Option<usize>); 3]>,
}

fn read_obj(text: &str) -> Obj {
    let mut o = Obj {
        v: Vec::new(),
        vn: Vec::new(),
        f: Vec::new(),
    };
    let xyz = |w: &[&str]| [1, 2, 3].map(|k| w[k].parse::<f64>().unwrap());
    for l in text.lines() {
        let w: Vec<&str> = l.split_whitespace().collect();
        match w.first() {
            Some(&"v") => o.v.push(xyz(&w)),
            Some(&"vn") => o.vn.push(xyz(&w)),
            Some(&"f") => o.f.push([1, 2, 3].map(|k| {
                let mut s = w[k].split("//");
                let i = s.next().unwrap().parse::<usize>().unwrap() - 1;
                (i, s.next().map(|n| n.parse::<usize>().unwrap() - 1))
            })),
            _ => {}
        }
    }
    o
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// `(b − a) × (c − a)` of triangle `t`.
fn turn(o: &Obj, t: &[(usize, Option<usize>); 3]) -> [f64; 3] {
    let [a, b, c] = t.map(|(i, _)| o.v[i]);
    cross(sub(b, a), sub(c, a))
}

/// Meshes `file` (written as `name`) to `out`, returning the output's text.
fn mesh(file: &str, name: &str, out: &str) -> String {
    let d = dir_with(&[(name, file)]);
    lekalo()
        .args(["mesh", "--tolerance", "1e-3", "-q"])
        .arg(p(&d, name))
        .arg("-o")
        .arg(p(&d, out))
        .assert()
        .success();
    fs::read_to_string(p(&d, out)).unwrap()
}

#[test]
fn a_meshed_face_carries_its_surface_s_normals_turned_with_its_sense() {
    for (sense, bound, outward) in [(".T.", ".T.", 1.0), (".F.", ".F.", -1.0)] {
        let file = CAP.replace("@SENSE@", sense).replace("@BOUND@", bound);
        let o = read_obj(&mesh(&file, "cap.stp", "cap.obj"));
        assert!(o.f.len() > 100, "{} triangles", o.f.len());
        // a normal for every vertex of a triangle, each vertex always with the same one
        let mut normal_of = vec![None; o.v.len()];
        for &(i, n) in o.f.iter().flatten() {
            let n = n.expect("every triangle's vertices carry normals");
            assert!(
                normal_of[i].is_none_or(|m| m == n),
                "vertex {i}: normals {n}, {normal_of:?}"
            );
            normal_of[i] = Some(n);
        }
        let used: Vec<(usize, usize)> = normal_of
            .iter()
            .enumerate()
            .filter_map(|(i, n)| n.map(|n| (i, n)))
            .collect();
        // every vertex has its normal, the mesher's copies of the pole in no triangle too
        assert_eq!(o.vn.len(), o.v.len());
        let mut pole = 0;
        for (p, n) in used.iter().map(|&(i, n)| (&o.v[i], &o.vn[n])) {
            assert!((dot(*n, *n) - 1.0).abs() < 1e-12, "unit: {n:?}");
            assert!(p[2] > 3.0 - 1e-9, "on the cap: {p:?}");
            if (p[2] - 5.0).abs() < 1e-9 {
                // the pole, where S_u = 0: the limit normal along the collapsed edge, the axis
                pole += 1;
                assert!(
                    (outward * n[2] - 1.0).abs() < 1e-12 && n[0].hypot(n[1]) < 1e-12,
                    "{n:?} at the pole, sense {sense}"
                );
                continue;
            }
            // the sphere's normal: the point over the radius, outward or inward
            let exact = p.map(|x| outward * x / 5.0);
            let err = sub(*n, exact).iter().fold(0.0_f64, |m, x| m.max(x.abs()));
            assert!(
                err < 1e-9,
                "{n:?} against {exact:?} at {p:?}, sense {sense}"
            );
        }
        assert!(pole > 0, "the pole is a vertex");
        // every triangle turns about the normals of its vertices
        for t in &o.f {
            let c = turn(&o, t);
            for (_, n) in t {
                assert!(
                    dot(o.vn[n.unwrap()], c) > 0.0,
                    "{t:?} turns against, sense {sense}"
                );
            }
        }
        // STL's facet normals are the triangles' own, on the side of the OBJ's vertex normals
        let stl = mesh(&file, "cap.stp", "cap.stl");
        let facets: Vec<[f64; 3]> = stl
            .lines()
            .filter_map(|l| l.strip_prefix("facet normal "))
            .map(|l| {
                let w: Vec<f64> = l.split(' ').map(|x| x.parse().unwrap()).collect();
                [w[0], w[1], w[2]]
            })
            .collect();
        assert_eq!(facets.len(), o.f.len());
        for (t, f) in o.f.iter().zip(&facets) {
            for (_, n) in t {
                assert!(dot(o.vn[n.unwrap()], *f) > 0.0, "{f:?}, sense {sense}");
            }
        }
    }
}

#[test]
fn faces_of_triangles_carry_the_file_s_normals_made_unit() {
    let o = read_obj(&mesh(TRIANGLES, "tri.stp", "tri.obj"));
    assert_eq!((o.v.len(), o.f.len()), (12, 5));
    // the planar face's normal at its 4 points, the other's 4: the third face has none
    assert_eq!(o.vn.len(), 8);
    let want = [
        [0.0, 0.0, 1.0],
        [0.0, 0.0, 1.0],
        [0.0, 0.0, 1.0],
        [0.0, 0.0, 1.0],
        [0.0, 0.0, 1.0],
        [0.0, 0.6, 0.8],
        // the zero normal: its triangles' (both turn about +z)
        [0.0, 0.0, 1.0],
        [0.6, 0.0, 0.8],
    ];
    for (got, want) in o.vn.iter().zip(want) {
        let err = sub(*got, want).iter().fold(0.0_f64, |m, x| m.max(x.abs()));
        assert!(err <= 1e-15, "{got:?} against {want:?}");
    }
    for t in &o.f[..4] {
        let c = turn(&o, t);
        for (_, n) in t {
            let n = o.vn[n.expect("the file gives normals")];
            assert!(dot(n, c) > 0.0, "{t:?}");
        }
    }
    assert!(o.f[4].iter().all(|(_, n)| n.is_none()), "{:?}", o.f[4]);
    // PLY: not every vertex has a normal, so none; with the two faces that give them, all
    let ply = mesh(TRIANGLES, "tri.stp", "tri.ply");
    assert!(!ply.contains("property double nx"), "{ply}");
    let two = TRIANGLES.replace("#5=TRIANGULATED_FACE('none',#3,4,(),$,(),((1,2,3)));\n", "");
    let ply = mesh(&two, "tri.stp", "tri.ply");
    assert!(ply.contains("property double nx"), "{ply}");
    assert!(ply.contains("\n2 1 0 0.6"), "{ply}");
}
