//! A face through both poles of a closed surface, read from STEP with its edges' 3-D curves only
//! (no pcurves): a half sphere bounded by two meridians and a round hole, as I-DEAS writes it.

use super::faces_tests::file;
use super::*;

/// The half `z ≥ 0` of the sphere of radius 5.9 about the origin (a rational biquadratic
/// B-spline: three arcs of 120° round the `y` axis from its seam near `−z`, two arcs from pole to
/// pole along `y`), bounded by the two meridians in the plane `z = 0` (from pole to pole, one
/// through `−x` and one through `+x`) and by the circle of radius 1.8 at `z = 5.6187` round the
/// top: an I-DEAS face with its normal into the sphere (`same_sense` `.F.`, each bound `.F.`).
/// `SENSE` stands for the three orientations: all `T` is the same half with its normal out.
const HALF_SPHERE: &str = "
#1=CARTESIAN_POINT('',(2.452527E-15,-5.900000000000000,-6.399899E-16));
#2=VERTEX_POINT('',#1);
#3=CARTESIAN_POINT('',(2.588610E-15,5.900000000000004,-1.320404E-15));
#4=VERTEX_POINT('',#3);
#5=CARTESIAN_POINT('',(3.213416E-15,-5.900000000000000,0.0));
#6=CARTESIAN_POINT('',(-10.219099764656370,-5.899999999999993,0.0));
#7=CARTESIAN_POINT('',(-5.109549882328180,2.949999999999997,0.0));
#8=CARTESIAN_POINT('',(-3.406366588218784,5.899999999999993,0.0));
#9=CARTESIAN_POINT('',(3.932040E-15,5.899999999999992,0.0));
#10=(BOUNDED_CURVE()B_SPLINE_CURVE(2,(#5,#6,#7,#8,#9),.CIRCULAR_ARC.,.F.,.U.)B_SPLINE_CURVE_WITH_KNOTS((3,2,3),(0.0,0.666666666666667,1.0),.UNSPECIFIED.)CURVE() GEOMETRIC_REPRESENTATION_ITEM()RATIONAL_B_SPLINE_CURVE((1.0,0.500000000000000,1.0,0.750000000000000,0.750000000000000)) REPRESENTATION_ITEM(''));
#11=EDGE_CURVE('',#2,#4,#10,.T.);
#12=ORIENTED_EDGE('',*,*,#11,.F.);
#13=CARTESIAN_POINT('',(3.932040E-15,5.899999999999992,0.0));
#14=CARTESIAN_POINT('',(3.406366588218795,5.899999999999992,0.0));
#15=CARTESIAN_POINT('',(5.109549882328189,2.949999999999992,0.0));
#16=CARTESIAN_POINT('',(10.219099764656372,-5.900000000000001,0.0));
#17=CARTESIAN_POINT('',(3.213416E-15,-5.900000000000000,0.0));
#18=(BOUNDED_CURVE()B_SPLINE_CURVE(2,(#13,#14,#15,#16,#17),.CIRCULAR_ARC.,.F.,.U.)B_SPLINE_CURVE_WITH_KNOTS((3,2,3),(0.0,0.333333333333333,1.0),.UNSPECIFIED.)CURVE() GEOMETRIC_REPRESENTATION_ITEM()RATIONAL_B_SPLINE_CURVE((0.750000000000000,0.750000000000000,1.0,0.500000000000000,1.0)) REPRESENTATION_ITEM(''));
#19=EDGE_CURVE('',#4,#2,#18,.T.);
#20=ORIENTED_EDGE('',*,*,#19,.F.);
#21=EDGE_LOOP('',(#12,#20));
#22=FACE_OUTER_BOUND('',#21,.SENSE.);
#23=CARTESIAN_POINT('',(8.260841E-16,1.799999999999998,5.618718735094131));
#24=VERTEX_POINT('',#23);
#25=CARTESIAN_POINT('',(8.260841E-16,1.799999999999998,5.618718735094131));
#26=CARTESIAN_POINT('',(-3.117691453623979,1.799999999999995,5.618718735094130));
#27=CARTESIAN_POINT('',(-1.558845726811988,-0.900000000000002,5.618718735094131));
#28=CARTESIAN_POINT('',(2.585897E-15,-3.600000000000000,5.618718735094130));
#29=CARTESIAN_POINT('',(1.558845726811991,-0.900000000000001,5.618718735094131));
#30=CARTESIAN_POINT('',(3.117691453623978,1.799999999999998,5.618718735094130));
#31=CARTESIAN_POINT('',(8.260841E-16,1.799999999999998,5.618718735094131));
#32=(BOUNDED_CURVE()B_SPLINE_CURVE(2,(#25,#26,#27,#28,#29,#30,#31),.CIRCULAR_ARC.,.T.,.U.) B_SPLINE_CURVE_WITH_KNOTS((3,2,2,3),(0.0,0.793264142243830,1.586528284487660,2.379792426731490),.UNSPECIFIED.)CURVE() GEOMETRIC_REPRESENTATION_ITEM()RATIONAL_B_SPLINE_CURVE((1.0,0.500000000000000,1.0,0.500000000000000,1.0,0.500000000000000,1.0))REPRESENTATION_ITEM(''));
#33=EDGE_CURVE('',#24,#24,#32,.T.);
#34=ORIENTED_EDGE('',*,*,#33,.F.);
#35=EDGE_LOOP('',(#34));
#36=FACE_BOUND('',#35,.SENSE.);
#37=CARTESIAN_POINT('',(2.452527E-15,-5.900000000000000,-6.399899E-16));
#38=CARTESIAN_POINT('',(1.157085197315294,-5.900000000000002,-5.785425986576434));
#39=CARTESIAN_POINT('',(1.157085197315294,-2.081668E-15,-5.785425986576432));
#40=CARTESIAN_POINT('',(1.157085197315293,5.899999999999999,-5.785425986576429));
#41=CARTESIAN_POINT('',(2.588610E-15,5.900000000000004,-1.320404E-15));
#42=CARTESIAN_POINT('',(-1.629960E-15,-5.900000000000001,-1.456487E-15));
#43=CARTESIAN_POINT('',(-8.863566554864388,-5.900000000000003,-7.789556337012377));
#44=CARTESIAN_POINT('',(-8.863566554864384,-1.965781E-15,-7.789556337012375));
#45=CARTESIAN_POINT('',(-8.863566554864382,5.899999999999999,-7.789556337012372));
#46=CARTESIAN_POINT('',(-2.854706E-15,5.900000000000005,-2.409068E-15));
#47=CARTESIAN_POINT('',(-4.052136E-16,-5.900000000000000,3.034249E-15));
#48=CARTESIAN_POINT('',(-5.588868474747486,-5.900000000000002,1.890647818070246));
#49=CARTESIAN_POINT('',(-5.588868474747484,-2.023725E-15,1.890647818070245));
#50=CARTESIAN_POINT('',(-5.588868474747483,5.899999999999999,1.890647818070244));
#51=CARTESIAN_POINT('',(-1.153670E-15,5.900000000000004,3.238373E-15));
#52=CARTESIAN_POINT('',(8.195326E-16,-5.900000000000001,7.524984E-15));
#53=CARTESIAN_POINT('',(-2.314170394630587,-5.900000000000003,11.570851973152870));
#54=CARTESIAN_POINT('',(-2.314170394630585,-2.081668E-15,11.570851973152866));
#55=CARTESIAN_POINT('',(-2.314170394630585,5.899999999999999,11.570851973152863));
#56=CARTESIAN_POINT('',(5.473668E-16,5.900000000000005,8.885813E-15));
#57=CARTESIAN_POINT('',(3.677274E-15,-5.900000000000000,3.850746E-15));
#58=CARTESIAN_POINT('',(4.431783277432197,-5.900000000000002,3.894778168506195));
#59=CARTESIAN_POINT('',(4.431783277432194,-2.139612E-15,3.894778168506194));
#60=CARTESIAN_POINT('',(4.431783277432193,5.899999999999999,3.894778168506193));
#61=CARTESIAN_POINT('',(4.289647E-15,5.900000000000004,4.327036E-15));
#62=CARTESIAN_POINT('',(6.535015E-15,-5.900000000000001,1.765075E-16));
#63=CARTESIAN_POINT('',(11.177736949494978,-5.900000000000003,-3.781295636140479));
#64=CARTESIAN_POINT('',(11.177736949494973,-2.197555E-15,-3.781295636140478));
#65=CARTESIAN_POINT('',(11.177736949494971,5.899999999999999,-3.781295636140476));
#66=CARTESIAN_POINT('',(8.031927E-15,5.900000000000005,-2.317412E-16));
#67=CARTESIAN_POINT('',(2.452527E-15,-5.900000000000000,-6.399899E-16));
#68=CARTESIAN_POINT('',(1.157085197315294,-5.900000000000002,-5.785425986576434));
#69=CARTESIAN_POINT('',(1.157085197315294,-2.081668E-15,-5.785425986576432));
#70=CARTESIAN_POINT('',(1.157085197315293,5.899999999999999,-5.785425986576429));
#71=CARTESIAN_POINT('',(2.588610E-15,5.900000000000004,-1.320404E-15));
#72=(BOUNDED_SURFACE()B_SPLINE_SURFACE(2,2,((#37,#38,#39,#40,#41),(#42,#43,#44,#45,#46),(#47,#48,#49,#50,#51),(#52,#53,#54,#55,#56),(#57,#58,#59,#60,#61),(#62,#63,#64,#65,#66),(#67,#68,#69,#70,#71)),.SPHERICAL_SURF.,.T.,.F.,.U.) B_SPLINE_SURFACE_WITH_KNOTS((3,2,2,3),(3,2,3),(1.800000000000000,2.533333333333333,3.266666666666667,4.0),(0.0,1.0,2.0),.UNSPECIFIED.)GEOMETRIC_REPRESENTATION_ITEM() RATIONAL_B_SPLINE_SURFACE(((1.0,1.0,2.0,1.0,1.0),(0.500000000000000,0.500000000000000,1.000000000000000,0.500000000000000,0.500000000000000),(1.0,1.0,2.0,1.0,1.0),(0.500000000000000,0.500000000000000,1.000000000000000,0.500000000000000,0.500000000000000),(1.0,1.0,2.0,1.0,1.0),(0.500000000000000,0.500000000000000,1.000000000000000,0.500000000000000,0.500000000000000),(1.0,1.0,2.0,1.0,1.0))) REPRESENTATION_ITEM('')SURFACE());
#73=ADVANCED_FACE('half sphere',(#22,#36),#72,.SENSE.);
";

/// The mesh of the half sphere whose orientations are all `sense` (`T` or `F`).
fn mesh(sense: &str, tol: f64) -> lekalo::query::Mesh {
    let r = read_step_faces(
        &file(&HALF_SPHERE.replace("SENSE", sense)),
        "t.step",
        usize::MAX,
    )
    .unwrap();
    assert!(r.skipped_faces.is_empty(), "{:?}", r.skipped_faces);
    let f = &r.faces[0];
    assert_eq!(f.face.same_sense(), sense == "T", "the face's sense");
    assert!(!f.face.has_pcurves(), "the file gives no pcurves");
    f.face
        .with_projected_pcurves(tol)
        .unwrap()
        .mesh(tol)
        .unwrap()
}

/// A loop from pole to pole along one meridian and back along another bounds either half of the
/// sphere in `(u, v)`, by which way it runs along each pole; the face is on the left of its loop
/// seen from its normal. The mesh covers the half `z ≥ 0` without the hole, whichever way the
/// file orients it, with the area `2πRh` of the zone between the equator and the hole's circle.
#[test]
fn a_half_sphere_bounded_by_two_meridians_is_meshed_on_its_own_half() {
    let (radius, h, hole) = (5.9, 5.618_718_735_094_13, 1.8);
    let tol = 1e-2;
    for sense in ["F", "T"] {
        let m = mesh(sense, tol);
        assert!(m.deviation <= tol, "{}", m.deviation);
        let v = |k: u32| m.vertices.point(k as usize).to_vec();
        let mut area = 0.0;
        for t in &m.triangles {
            let (a, b, c) = (v(t[0]), v(t[1]), v(t[2]));
            let centroid: Vec<f64> = (0..3).map(|i| (a[i] + b[i] + c[i]) / 3.0).collect();
            assert!(
                centroid[2] >= -tol,
                "sense {sense}: a triangle at {centroid:?} on the other half of the sphere"
            );
            assert!(
                centroid[2] <= h + tol,
                "sense {sense}: a triangle at {centroid:?} in the hole"
            );
            let e = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
            let g = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
            let n = [
                e[1] * g[2] - e[2] * g[1],
                e[2] * g[0] - e[0] * g[2],
                e[0] * g[1] - e[1] * g[0],
            ];
            area += 0.5 * (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
        }
        // the mesh's vertices on the sphere and its triangles within `tol` of it: its area is
        // that of the zone within the shrinking of the triangles towards the centre and the
        // strips along the loops (their length times `tol`)
        let exact = 2.0 * std::f64::consts::PI * radius * h;
        let shrink = 1.0 - ((radius - tol) / radius).powi(2);
        let strips = 2.0 * std::f64::consts::PI * (radius + hole) * tol;
        assert!(
            (area - exact).abs() <= exact * shrink + strips,
            "sense {sense}: area {area}, the zone's {exact}"
        );
    }
}
