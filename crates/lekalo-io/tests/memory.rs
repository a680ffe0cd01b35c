//! The STEP reader's memory, counted by the allocator: reading every face of a file of B-spline
//! faces holds at most three times the file's size at its peak, the text and the result
//! included (docs/performance/data.md, "Where the memory goes": 2.6 times on a 232 MB file; a
//! reader that builds a tree of every parameter takes about 11 times).
//!
//! A test binary of its own: the counting allocator is global to a binary, and tests running
//! beside this one would add their allocations to its count.

#[global_allocator]
static ALLOCATOR: lekalo_testkit::alloc::Counting = lekalo_testkit::alloc::Counting;

use std::fmt::Write as _;

/// Side of a face's control net, and its degree.
const NET: usize = 8;
const DEGREE: usize = 3;

/// A real as Part 21 writes it (a mantissa with a decimal point and an exponent).
fn real(x: f64) -> String {
    format!("{x:.9E}")
}

/// A STEP file (AP214, millimetres) of `faces` wavy B-spline faces on a grid, each trimmed by
/// its four boundary curves with their pcurves, in open shells of 100 faces: the layout of the
/// generated files of `bench/peers/cad_read.py`.
fn step_text(faces: usize) -> String {
    let mut out = String::from(
        "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION(('lekalo memory test'),'2;1');\n\
FILE_NAME('bsplines','2000-01-01T00:00:00',('test'),('lekalo'),'','','');\n\
FILE_SCHEMA(('AUTOMOTIVE_DESIGN { 1 0 10303 214 1 1 1 1 }'));\nENDSEC;\nDATA;\n\
#20 = ( GEOMETRIC_REPRESENTATION_CONTEXT(3) GLOBAL_UNCERTAINTY_ASSIGNED_CONTEXT((#24)) \
GLOBAL_UNIT_ASSIGNED_CONTEXT((#21,#22,#23)) REPRESENTATION_CONTEXT('Context #1','3D Context') );\n\
#21 = ( LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT(.MILLI.,.METRE.) );\n\
#22 = ( NAMED_UNIT(*) PLANE_ANGLE_UNIT() SI_UNIT($,.RADIAN.) );\n\
#23 = ( NAMED_UNIT(*) SI_UNIT($,.STERADIAN.) SOLID_ANGLE_UNIT() );\n\
#24 = UNCERTAINTY_MEASURE_WITH_UNIT(LENGTH_MEASURE(1.E-07),#21,'distance_accuracy_value','');\n",
    );
    let mut id = 100_usize;
    let mut new = |out: &mut String, text: String| {
        id += 1;
        let _ = writeln!(out, "#{id} = {text};");
        id
    };
    let inner = NET - DEGREE - 1;
    let mults = format!("({},{}{})", DEGREE + 1, "1,".repeat(inner), DEGREE + 1);
    let knots = format!(
        "({})",
        (0..inner + 2)
            .map(|t| real(t as f64 / (inner + 1) as f64))
            .collect::<Vec<_>>()
            .join(",")
    );
    let mut face_ids = Vec::with_capacity(faces);
    for k in 0..faces {
        let (gx, gy) = ((k % 100) as f64, (k / 100) as f64);
        let mut pts = [[0_usize; NET]; NET];
        for (i, row) in pts.iter_mut().enumerate() {
            for (j, p) in row.iter_mut().enumerate() {
                let (a, b) = (i as f64 / (NET - 1) as f64, j as f64 / (NET - 1) as f64);
                let z = (0.37 * (gx * 7.0 + i as f64)).sin() * (0.23 * (gy * 7.0 + j as f64)).cos();
                let text = format!(
                    "CARTESIAN_POINT('',({},{},{}))",
                    real(10.0 * (gx + a)),
                    real(10.0 * (gy + b)),
                    real(z)
                );
                *p = new(&mut out, text);
            }
        }
        let net = pts
            .iter()
            .map(|row| {
                let ids: Vec<String> = row.iter().map(|p| format!("#{p}")).collect();
                format!("({})", ids.join(","))
            })
            .collect::<Vec<_>>()
            .join(",");
        let surf = new(
            &mut out,
            format!(
                "B_SPLINE_SURFACE_WITH_KNOTS('',{DEGREE},{DEGREE},({net}),.UNSPECIFIED.,.F.,.F.,.F.,{mults},{mults},{knots},{knots},.UNSPECIFIED.)"
            ),
        );
        let last = NET - 1;
        let mut corner = |out: &mut String, i: usize, j: usize| {
            new(out, format!("VERTEX_POINT('',#{})", pts[i][j]))
        };
        let c00 = corner(&mut out, 0, 0);
        let c10 = corner(&mut out, last, 0);
        let c11 = corner(&mut out, last, last);
        let c01 = corner(&mut out, 0, last);
        let column = |j: usize| (0..NET).map(|i| pts[i][j]).collect::<Vec<_>>();
        // each side: its ends, its row of the net, its line in (u, v), and its sense in the loop
        let sides = [
            (c00, c10, column(0), (0.0, 0.0), (1.0, 0.0), ".T."),
            (c10, c11, pts[last].to_vec(), (1.0, 0.0), (0.0, 1.0), ".T."),
            (c01, c11, column(last), (0.0, 1.0), (1.0, 0.0), ".F."),
            (c00, c01, pts[0].to_vec(), (0.0, 0.0), (0.0, 1.0), ".F."),
        ];
        let mut edges = Vec::with_capacity(4);
        for (a, b, row, origin, d, sense) in sides {
            let poles: Vec<String> = row.iter().map(|p| format!("#{p}")).collect();
            let curve = new(
                &mut out,
                format!(
                    "B_SPLINE_CURVE_WITH_KNOTS('',{DEGREE},({}),.UNSPECIFIED.,.F.,.F.,{mults},{knots},.UNSPECIFIED.)",
                    poles.join(",")
                ),
            );
            let o = new(
                &mut out,
                format!(
                    "CARTESIAN_POINT('',({},{}))",
                    real(origin.0),
                    real(origin.1)
                ),
            );
            let dir = new(
                &mut out,
                format!("DIRECTION('',({},{}))", real(d.0), real(d.1)),
            );
            let v = new(&mut out, format!("VECTOR('',#{dir},1.)"));
            let line = new(&mut out, format!("LINE('',#{o},#{v})"));
            let ctx = new(
                &mut out,
                "( GEOMETRIC_REPRESENTATION_CONTEXT(2) PARAMETRIC_REPRESENTATION_CONTEXT() REPRESENTATION_CONTEXT('2D SPACE','') )".to_string(),
            );
            let rep = new(
                &mut out,
                format!("DEFINITIONAL_REPRESENTATION('',(#{line}),#{ctx})"),
            );
            let pc = new(&mut out, format!("PCURVE('',#{surf},#{rep})"));
            let sc = new(
                &mut out,
                format!("SURFACE_CURVE('',#{curve},(#{pc}),.PCURVE_S1.)"),
            );
            let edge = new(&mut out, format!("EDGE_CURVE('',#{a},#{b},#{sc},.T.)"));
            edges.push(format!(
                "#{}",
                new(&mut out, format!("ORIENTED_EDGE('',*,*,#{edge},{sense})"))
            ));
        }
        let lp = new(&mut out, format!("EDGE_LOOP('',({}))", edges.join(",")));
        let bound = new(&mut out, format!("FACE_OUTER_BOUND('',#{lp},.T.)"));
        face_ids.push(new(
            &mut out,
            format!("ADVANCED_FACE('',(#{bound}),#{surf},.T.)"),
        ));
    }
    let mut shells = Vec::new();
    for chunk in face_ids.chunks(100) {
        let ids: Vec<String> = chunk.iter().map(|f| format!("#{f}")).collect();
        shells.push(format!(
            "#{}",
            new(&mut out, format!("OPEN_SHELL('',({}))", ids.join(",")))
        ));
    }
    let _ = writeln!(
        out,
        "#15 = SHELL_BASED_SURFACE_MODEL('',({}));",
        shells.join(",")
    );
    let _ = writeln!(
        out,
        "#10 = MANIFOLD_SURFACE_SHAPE_REPRESENTATION('',(#15),#20);"
    );
    out.push_str("ENDSEC;\nEND-ISO-10303-21;\n");
    out
}

#[test]
fn reading_the_faces_of_a_step_file_holds_at_most_three_times_its_size() {
    let faces = 1500;
    let text = step_text(faces);
    let before = lekalo_testkit::alloc::live();
    lekalo_testkit::alloc::reset_peak();
    let read = lekalo_io::read_step_faces(&text, "memory.stp", usize::MAX).expect("the file reads");
    let peak = lekalo_testkit::alloc::peak() - before + text.len();
    assert_eq!(read.faces.len(), faces, "every face is read");
    let ratio = peak as f64 / text.len() as f64;
    println!(
        "{:.1} MB of STEP text, {faces} faces: peak {:.1} MB, {ratio:.2} times the text",
        text.len() as f64 / 1e6,
        peak as f64 / 1e6
    );
    assert!(
        ratio <= 3.0,
        "reading {} bytes of STEP held {peak} bytes at its peak ({ratio:.2} times the file)",
        text.len()
    );
}
