//! Tests of the implicit-knot B-splines and the analytic geometry, on small hand-written files.

use std::f64::consts::{FRAC_PI_2, PI};

use super::*;
use crate::object::Object;
use crate::shape::Surface;

fn file(data: &str) -> String {
    format!(
        "ISO-10303-21;\nHEADER;\nFILE_SCHEMA(('AUTOMOTIVE_DESIGN'));\nENDSEC;\nDATA;\n{data}\nENDSEC;\nEND-ISO-10303-21;\n"
    )
}

fn read(data: &str) -> StepRead {
    read_step(&file(data), "t.step").unwrap()
}

fn curve(r: &StepRead, id: u64) -> &Object {
    match r.shapes.iter().find(|(i, _)| *i == id) {
        Some((_, Shape::Curve(c))) => c,
        other => panic!(
            "#{id} is not a curve read: {other:?}; skipped {:?}",
            r.skipped
        ),
    }
}

fn surface(r: &StepRead, id: u64) -> &Surface {
    match r.shapes.iter().find(|(i, _)| *i == id) {
        Some((_, Shape::Surface(s))) => s,
        other => panic!(
            "#{id} is not a surface read: {other:?}; skipped {:?}",
            r.skipped
        ),
    }
}

fn close(a: &[f64], b: &[f64], tol: f64) {
    let d = a
        .iter()
        .zip(b)
        .map(|(p, q)| (p - q).abs())
        .fold(0.0, f64::max);
    assert!(d <= tol, "{a:?} vs {b:?}");
}

/// `a + (b − a)·k/n`, exactly `b` at `k = n`.
fn lerp(a: f64, b: f64, k: usize, n: usize) -> f64 {
    if k == n {
        b
    } else {
        a + (b - a) * k as f64 / n as f64
    }
}

/// Samples of a curve over its domain.
fn samples(c: &Object) -> Vec<Vec<f64>> {
    let (a, b) = c.domain();
    (0..=40)
        .map(|k| c.eval(lerp(a, b, k, 40)).unwrap())
        .collect()
}

/// Samples of a surface over its domain.
fn surface_samples(s: &Surface) -> Vec<Vec<f64>> {
    let ((u0, u1), (v0, v1)) = s.domain();
    let mut out = Vec::new();
    for i in 0..=12 {
        for j in 0..=12 {
            let (u, v) = (lerp(u0, u1, i, 12), lerp(v0, v1, j, 12));
            out.push(s.eval(u, v).unwrap());
        }
    }
    out
}

const POINTS: &str = "#1=CARTESIAN_POINT('',(0.,0.,0.));
#2=CARTESIAN_POINT('',(1.,2.,0.));
#3=CARTESIAN_POINT('',(3.,2.,0.));
#4=CARTESIAN_POINT('',(4.,0.,0.));
#5=CARTESIAN_POINT('',(5.,1.,0.));";

#[test]
fn implicit_knots_follow_iso_10303_42() {
    let r = read(&format!(
        "{POINTS}
#10=QUASI_UNIFORM_CURVE('q',2,(#1,#2,#3,#4,#5),.UNSPECIFIED.,.F.,.F.);
#11=UNIFORM_CURVE('u',2,(#1,#2,#3,#4),.UNSPECIFIED.,.F.,.F.);
#12=BEZIER_CURVE('b',2,(#1,#2,#3,#4,#5),.UNSPECIFIED.,.F.,.F.);
#13=( BOUNDED_CURVE() B_SPLINE_CURVE(2,(#1,#2,#3),.UNSPECIFIED.,.F.,.F.) CURVE()
GEOMETRIC_REPRESENTATION_ITEM() QUASI_UNIFORM_CURVE() RATIONAL_B_SPLINE_CURVE((1.,0.5,1.))
REPRESENTATION_ITEM('') );
#14=QUASI_UNIFORM_SURFACE('s',1,2,((#1,#2,#3),(#2,#3,#4)),.UNSPECIFIED.,.F.,.F.,.F.);
#15=( BOUNDED_SURFACE() B_SPLINE_SURFACE(1,1,((#1,#2),(#3,#4)),.UNSPECIFIED.,.F.,.F.,.F.)
BEZIER_SURFACE() GEOMETRIC_REPRESENTATION_ITEM() RATIONAL_B_SPLINE_SURFACE(((1.,2.),(2.,1.)))
REPRESENTATION_ITEM('') SURFACE() );"
    ));
    assert!(r.skipped.is_empty(), "{:?}", r.skipped);
    let k = |id| curve(&r, id).knots().as_slice().to_vec();
    assert_eq!(k(10), [0.0, 0.0, 0.0, 1.0, 2.0, 3.0, 3.0, 3.0]);
    assert_eq!(k(11), [-2.0, -1.0, 0.0, 1.0, 2.0, 3.0, 4.0]);
    assert_eq!(k(12), [0.0, 0.0, 0.0, 1.0, 1.0, 2.0, 2.0, 2.0]);
    assert_eq!(k(13), [0.0, 0.0, 0.0, 1.0, 1.0, 1.0]);
    assert_eq!(curve(&r, 13).weights(), Some(vec![1.0, 0.5, 1.0]));
    // a piecewise Bezier form interpolates its joints
    close(&curve(&r, 12).eval(1.0).unwrap(), &[3.0, 2.0, 0.0], 0.0);
    let s = surface(&r, 14);
    assert_eq!(s.knots().0.as_slice(), &[0.0, 0.0, 1.0, 1.0]);
    assert_eq!(s.knots().1.as_slice(), &[0.0, 0.0, 0.0, 1.0, 1.0, 1.0]);
    let s = surface(&r, 15);
    assert!(s.is_rational());
    assert_eq!(s.domain(), ((0.0, 1.0), (0.0, 1.0)));
    // a piecewise Bezier form with a count that does not fit is an error naming the entity
    let e = read_step(
        &file(&format!(
            "{POINTS}\n#10=BEZIER_CURVE('b',2,(#1,#2,#3,#4),.UNSPECIFIED.,.F.,.F.);"
        )),
        "t.step",
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.contains("#10") && e.contains("1 + 2·k control points"),
        "{e}"
    );
}

const FRAME: &str = "#20=CARTESIAN_POINT('',(1.,2.,3.));
#21=DIRECTION('',(0.,0.6,0.8));
#22=DIRECTION('',(1.,0.,0.));
#23=AXIS2_PLACEMENT_3D('',#20,#21,#22);";

/// Coordinates of `p` in the frame of [`FRAME`]: x = (1,0,0), y = z × x, z = (0, .6, .8).
fn local(p: &[f64]) -> [f64; 3] {
    let d = [p[0] - 1.0, p[1] - 2.0, p[2] - 3.0];
    let y = [0.0, 0.8, -0.6];
    [d[0], d[1] * y[1] + d[2] * y[2], d[1] * 0.6 + d[2] * 0.8]
}

#[test]
fn conics_and_lines_are_exact() {
    let r = read(&format!(
        "{FRAME}
#30=CIRCLE('',#23,2.5);
#31=ELLIPSE('',#23,3.,1.);
#32=TRIMMED_CURVE('',#33,(PARAMETER_VALUE(90.)),(PARAMETER_VALUE(0.)),.T.,.PARAMETER.);
#33=CIRCLE('',#23,2.);
#34=CARTESIAN_POINT('',(0.,0.,0.));
#35=VECTOR('',#22,2.);
#36=LINE('',#34,#35);
#37=TRIMMED_CURVE('',#36,(#38),(#39),.F.,.CARTESIAN.);
#38=CARTESIAN_POINT('',(1.,0.,0.));
#39=CARTESIAN_POINT('',(5.,0.,0.));
#40=LINE('',#20,#35);
#45=TRIMMED_CURVE('',#36,(PARAMETER_VALUE(3.)),(PARAMETER_VALUE(1.)),.F.,.PARAMETER.);
#41=( NAMED_UNIT(*) PLANE_ANGLE_UNIT() SI_UNIT($,.RADIAN.) );
#42=PLANE_ANGLE_MEASURE_WITH_UNIT(PLANE_ANGLE_MEASURE(0.0174532925199433),#41);
#43=( CONVERSION_BASED_UNIT('DEGREE',#42) NAMED_UNIT(*) PLANE_ANGLE_UNIT() );
#44=( GEOMETRIC_REPRESENTATION_CONTEXT(3) GLOBAL_UNIT_ASSIGNED_CONTEXT((#43))
REPRESENTATION_CONTEXT('','') );"
    ));
    for p in samples(curve(&r, 30)) {
        let c = local(&p);
        assert!((c[0].hypot(c[1]) - 2.5).abs() < 1e-12 * 2.5 && c[2].abs() < 1e-12);
    }
    for p in samples(curve(&r, 31)) {
        let c = local(&p);
        assert!(((c[0] / 3.0).powi(2) + c[1].powi(2) - 1.0).abs() < 1e-12);
    }
    // 90° → 0° along the circle's sense: three quarters of the turn, from the top down
    let arc = curve(&r, 32);
    let (a, b) = arc.domain();
    close(&local(&arc.eval(a).unwrap()), &[0.0, 2.0, 0.0], 1e-14);
    close(&local(&arc.eval(b).unwrap()), &[2.0, 0.0, 0.0], 1e-14);
    close(
        &local(&arc.eval(0.5 * (a + b)).unwrap()),
        &[-2.0_f64.sqrt(), -2.0_f64.sqrt(), 0.0],
        1e-14,
    );
    // trimmed by points, against the line's direction: from x = 5 back to x = 1
    let seg = curve(&r, 37);
    let (a, b) = seg.domain();
    close(&seg.eval(a).unwrap(), &[5.0, 0.0, 0.0], 1e-15);
    close(&seg.eval(b).unwrap(), &[1.0, 0.0, 0.0], 1e-15);
    // against the line from the larger trim: from trim_1 (t = 3, x = 6) to trim_2 (x = 2)
    let back = curve(&r, 45);
    let (a, b) = back.domain();
    close(&back.eval(a).unwrap(), &[6.0, 0.0, 0.0], 1e-15);
    close(&back.eval(b).unwrap(), &[2.0, 0.0, 0.0], 1e-15);
    // the trims' bases are read through their trims; an unbounded line is reported
    assert!(r.shapes.iter().all(|(i, _)| *i != 33 && *i != 36));
    let why: Vec<_> = r
        .skipped
        .iter()
        .map(|s| (s.id, s.reason.as_str()))
        .collect();
    assert_eq!(why.len(), 1, "{why:?}");
    assert_eq!(why[0].0, 40);
    assert!(why[0].1.contains("unbounded line"), "{why:?}");
}

/// A face on surface `#s` bounded by one edge loop through the points given (each edge a
/// line between consecutive vertices), ids from 100.
fn face_on(s: u64, pts: &[[f64; 3]]) -> String {
    let mut out = String::new();
    let n = pts.len();
    for (k, p) in pts.iter().enumerate() {
        out += &format!(
            "#{}=CARTESIAN_POINT('',({:?},{:?},{:?}));\n#{}=VERTEX_POINT('',#{});\n",
            100 + k,
            p[0],
            p[1],
            p[2],
            200 + k,
            100 + k
        );
    }
    let mut edges = Vec::new();
    for k in 0..n {
        let (a, b) = (k, (k + 1) % n);
        let d = [
            pts[b][0] - pts[a][0],
            pts[b][1] - pts[a][1],
            pts[b][2] - pts[a][2],
        ];
        out += &format!(
            "#{}=DIRECTION('',({:?},{:?},{:?}));\n#{}=VECTOR('',#{},1.);\n#{}=LINE('',#{},#{});\n#{}=EDGE_CURVE('',#{},#{},#{},.T.);\n#{}=ORIENTED_EDGE('',*,*,#{},.T.);\n",
            300 + k, d[0], d[1], d[2],
            400 + k, 300 + k,
            500 + k, 100 + a, 400 + k,
            600 + k, 200 + a, 200 + b, 500 + k,
            700 + k, 600 + k
        );
        edges.push(format!("#{}", 700 + k));
    }
    out += &format!(
        "#800=EDGE_LOOP('',({}));\n#801=FACE_OUTER_BOUND('',#800,.T.);\n#802=ADVANCED_FACE('',(#801),#{s},.T.);\n",
        edges.join(",")
    );
    out
}

#[test]
fn unbounded_surfaces_take_the_bounds_of_their_faces() {
    // a plane face: the square (1..3) × (−1..2) in the frame's x, y at height 0
    let corners: Vec<[f64; 3]> = [(1.0, -1.0), (3.0, -1.0), (3.0, 2.0), (1.0, 2.0)]
        .iter()
        .map(|&(x, y)| [1.0 + x, 2.0 + 0.8 * y, 3.0 - 0.6 * y])
        .collect();
    let r = read(&format!(
        "{FRAME}\n#50=PLANE('',#23);\n#51=PLANE('',#23);\n{}",
        face_on(50, &corners)
    ));
    let s = surface(&r, 50);
    let ((u0, u1), (v0, v1)) = s.domain();
    // the bounds are the corners' frame coordinates, computed with rounding
    close(&[u0, u1, v0, v1], &[1.0, 3.0, -1.0, 2.0], 1e-15 * 4.0);
    for p in surface_samples(s) {
        assert!(local(&p)[2].abs() < 1e-14);
    }
    // the edges' lines are bounded by their vertices
    let l = curve(&r, 500);
    close(&l.eval(l.domain().0).unwrap(), &corners[0], 1e-14);
    close(&l.eval(l.domain().1).unwrap(), &corners[1], 1e-14);
    let skipped: Vec<_> = r.skipped.iter().map(|s| (s.id, &s.reason)).collect();
    assert_eq!(skipped.len(), 1, "{skipped:?}");
    assert_eq!(skipped[0].0, 51);
    assert!(skipped[0].1.contains("unbounded plane without a face"));

    // a cylinder of radius 2 whose face spans heights −1 … 4 along the axis
    let on = |h: f64, a: f64| {
        let (x, y) = (2.0 * a.cos(), 2.0 * a.sin());
        [1.0 + x, 2.0 + 0.8 * y + 0.6 * h, 3.0 - 0.6 * y + 0.8 * h]
    };
    let r = read(&format!(
        "{FRAME}\n#50=CYLINDRICAL_SURFACE('',#23,2.);\n{}",
        face_on(
            50,
            &[on(-1.0, 0.0), on(4.0, 0.0), on(4.0, 1.0), on(-1.0, 1.0)]
        )
    ));
    for p in surface_samples(surface(&r, 50)) {
        let c = local(&p);
        assert!((c[0].hypot(c[1]) - 2.0).abs() < 1e-12 * 2.0, "{c:?}");
        assert!((-1.0 - 1e-12..=4.0 + 1e-12).contains(&c[2]), "{c:?}");
    }
    let hs: Vec<f64> = surface_samples(surface(&r, 50))
        .iter()
        .map(|p| local(p)[2])
        .collect();
    assert!(
        hs.iter().any(|h| (h + 1.0).abs() < 1e-12) && hs.iter().any(|h| (h - 4.0).abs() < 1e-12)
    );
}

#[test]
fn closed_and_swept_surfaces_are_exact() {
    let r = read(&format!(
        "{FRAME}
#50=SPHERICAL_SURFACE('',#23,2.);
#51=TOROIDAL_SURFACE('',#23,5.,1.5);
#52=CONICAL_SURFACE('',#23,1.,0.5);
#53=CIRCLE('',#23,1.);
#54=DIRECTION('',(0.,0.,1.));
#55=AXIS1_PLACEMENT('',#20,#21);
#56=SURFACE_OF_REVOLUTION('',#57,#55);
#57=TRIMMED_CURVE('',#58,(PARAMETER_VALUE(0.)),(PARAMETER_VALUE(1.)),.T.,.PARAMETER.);
#58=LINE('',#59,#60);
#59=CARTESIAN_POINT('',(4.,2.,3.));
#60=VECTOR('',#21,3.);
#61=COMPLEX_TRIANGULATED_FACE('',#62,3,((0.,0.,1.)),#52,(),(),((1,2,3)));
#62=COORDINATES_LIST('',3,((2.,2.,3.),(1.,2.6,3.8),(1.,3.2,4.6)));"
    ));
    for p in surface_samples(surface(&r, 50)) {
        let c = local(&p);
        assert!((c[0].hypot(c[1]).hypot(c[2]) - 2.0).abs() < 1e-12 * 2.0);
    }
    for p in surface_samples(surface(&r, 51)) {
        let c = local(&p);
        assert!(((c[0].hypot(c[1]) - 5.0).hypot(c[2]) - 1.5).abs() < 1e-12 * 5.0);
    }
    // the cone is bounded by its triangulated face: heights 0 … 2 (the points' z in the frame)
    let mut hs = (f64::INFINITY, f64::NEG_INFINITY);
    for p in surface_samples(surface(&r, 52)) {
        let c = local(&p);
        assert!((c[0].hypot(c[1]) - (1.0 + c[2] * 0.5_f64.tan())).abs() < 1e-12 * 2.0);
        hs = (hs.0.min(c[2]), hs.1.max(c[2]));
    }
    close(&[hs.0, hs.1], &[0.0, 2.0], 1e-12);
    // the segment at distance 3 along x, parallel to the axis, turned: a cylinder of radius 3
    for p in surface_samples(surface(&r, 56)) {
        let c = local(&p);
        assert!((c[0].hypot(c[1]) - 3.0).abs() < 1e-12 * 3.0);
        assert!((-1e-12..=3.0 + 1e-12).contains(&c[2]));
    }
    assert!(
        r.skipped
            .iter()
            .all(|s| s.entity == "COMPLEX_TRIANGULATED_FACE"),
        "{:?}",
        r.skipped
    );
    assert_eq!(r.skipped.len(), 1);
    let _ = (PI, FRAC_PI_2);
}

#[test]
fn an_extrusion_spans_its_faces() {
    // a circle of radius 1 about the origin in the xy plane, extruded along z by 2 per unit
    let base = "#20=CARTESIAN_POINT('',(0.,0.,0.));
#21=DIRECTION('',(0.,0.,1.));
#22=DIRECTION('',(1.,0.,0.));
#23=AXIS2_PLACEMENT_3D('',#20,#21,#22);
#30=CIRCLE('',#23,1.);
#31=VECTOR('',#21,2.);
#50=SURFACE_OF_LINEAR_EXTRUSION('',#30,#31);";
    let r = read(&format!(
        "{base}\n{}",
        face_on(50, &[[1.0, 0.0, 1.0], [0.0, 1.0, 1.0], [0.0, 1.0, 3.0]])
    ));
    let s = surface(&r, 50);
    let mut zs = (f64::INFINITY, f64::NEG_INFINITY);
    for p in surface_samples(s) {
        assert!((p[0].hypot(p[1]) - 1.0).abs() < 1e-12);
        zs = (zs.0.min(p[2]), zs.1.max(p[2]));
    }
    assert!(zs.0 <= 1.0 && zs.1 >= 3.0, "{zs:?}");
    // without a face it is reported
    let r = read(base);
    assert!(r
        .skipped
        .iter()
        .any(|s| s.id == 50 && s.reason.contains("unbounded")));
}
