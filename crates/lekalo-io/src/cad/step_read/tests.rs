use lekalo::{BSplineSurface, NurbsCurve, NurbsSurface, Points};

use super::parse::MAX_NESTING;
use super::*;
use crate::error::IoError;
use crate::object::Object;
use crate::shape::Surface;
use crate::StepWriter;

const OCC_STYLE: &str = "ISO-10303-21;
HEADER;
FILE_DESCRIPTION(('Open CASCADE Model'),'2;1');
FILE_NAME('x','2024-01-01T00:00:00',('Author'),(''),'Open CASCADE STEP processor 7.7','Open CASCADE 7.7','Unknown');
FILE_SCHEMA(('AUTOMOTIVE_DESIGN { 1 0 10303 214 1 1 1 1 }'));
ENDSEC;
DATA;
#1 = CARTESIAN_POINT('',(0.,0.,0.));
#2 = CARTESIAN_POINT('',(1.,2.,0.));
#3 = CARTESIAN_POINT('',(3.,2.,0.));
#4 = CARTESIAN_POINT('',(4.,0.,0.));
/* a comment */
#5 = B_SPLINE_CURVE_WITH_KNOTS('',2,(#1,#2,#3,#4),.UNSPECIFIED.,.F.,.F.,(3,1,3),(0.,0.5,1.),
  .UNSPECIFIED.);
#6 = ( BOUNDED_CURVE() B_SPLINE_CURVE(2,(#1,#2,#3),.UNSPECIFIED.,.F.,.F.)
B_SPLINE_CURVE_WITH_KNOTS((3,3),(0.,1.),.PIECEWISE_BEZIER_KNOTS.) CURVE()
GEOMETRIC_REPRESENTATION_ITEM() RATIONAL_B_SPLINE_CURVE((1.,0.5,1.)) REPRESENTATION_ITEM('') );
#7 = TRIMMED_CURVE('',#8,(PARAMETER_VALUE(0.25)),(PARAMETER_VALUE(0.75)),.T.,.PARAMETER.);
#8 = B_SPLINE_CURVE_WITH_KNOTS('',1,(#1,#4),.UNSPECIFIED.,.F.,.F.,(2,2),(0.,1.),.UNSPECIFIED.);
#9 = CIRCLE('',#10,2.);
#10 = AXIS2_PLACEMENT_3D('',#1,$,$);
#11 = ( LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT($,.METRE.) );
#12 = ( GEOMETRIC_REPRESENTATION_CONTEXT(3) GLOBAL_UNIT_ASSIGNED_CONTEXT((#11)) REPRESENTATION_CONTEXT('',''));
ENDSEC;
END-ISO-10303-21;
";

#[test]
fn reads_occ_style_entities_with_units_and_trims() {
    let r = read_step(OCC_STYLE, "occ.step").unwrap();
    assert_eq!(r.length_unit, "metre");
    assert_eq!(r.scale_to_mm, 1000.0);
    assert_eq!(
        r.schema.as_deref(),
        Some("AUTOMOTIVE_DESIGN { 1 0 10303 214 1 1 1 1 }")
    );
    let ids: Vec<u64> = r.shapes.iter().map(|(i, _)| *i).collect();
    assert_eq!(ids, [5, 6, 7, 9]);
    let Shape::Curve(Object::BSpline(c)) = &r.shapes[0].1 else {
        panic!("#5 is a B-spline curve")
    };
    assert_eq!(c.knots().as_slice(), &[0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0]);
    assert_eq!(c.control_points().point(1), &[1000.0, 2000.0, 0.0]);
    let Shape::Curve(Object::Nurbs(n)) = &r.shapes[1].1 else {
        panic!("#6 is a NURBS curve")
    };
    assert_eq!(n.weights(), vec![1.0, 0.5, 1.0]);
    let Shape::Curve(t) = &r.shapes[2].1 else {
        panic!("#7 is a curve")
    };
    assert_eq!(t.domain(), (0.25, 0.75));
    assert_eq!(t.control_points().point(0), &[1000.0, 0.0, 0.0]);
    assert!(r.skipped.is_empty(), "{:?}", r.skipped);
    // the circle of radius 2 (in metres) about the origin, in millimetres
    let Shape::Curve(circle) = &r.shapes[3].1 else {
        panic!("#9 is a curve")
    };
    for k in 0..=16 {
        let p = circle.eval(k as f64 / 16.0).unwrap();
        assert!((p[0].hypot(p[1]) - 2000.0).abs() < 1e-12 * 2000.0 && p[2] == 0.0);
    }
}

#[test]
fn our_own_files_round_trip_bit_for_bit() {
    let w = std::f64::consts::FRAC_1_SQRT_2;
    let ctrl =
        Points::from_3d(&[[1.0, 0.0, 0.1], [1.0, 1.0, 1.0 / 3.0], [0.0, 1.0, 1e-300]]).unwrap();
    let curve = Object::Nurbs(
        NurbsCurve::new(
            2,
            vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
            ctrl,
            vec![1.0, w, 1.0],
        )
        .unwrap(),
    );
    let net = Points::from_3d(&[
        [0.0, 0.0, 0.0],
        [0.0, 1.0, 0.7],
        [1.0, 0.0, -0.3],
        [1.0, 1.0, 1.0 / 7.0],
    ])
    .unwrap();
    let surf = BSplineSurface::new(
        1,
        1,
        vec![0.0, 0.0, 2.0, 2.0],
        vec![0.0, 0.0, 1.0, 1.0],
        net,
        (2, 2),
    )
    .unwrap();
    let nurbs = NurbsSurface::new(
        1,
        1,
        vec![0.0, 0.0, 2.0, 2.0],
        vec![0.0, 0.0, 1.0, 1.0],
        surf.control_points().clone(),
        vec![1.0, 0.3, 2.5, 1.0],
        (2, 2),
    )
    .unwrap();
    let mut wr = StepWriter::new("t");
    wr.add_object(&curve).unwrap();
    wr.add_any_surface(&Surface::BSpline(surf.clone())).unwrap();
    wr.add_any_surface(&Surface::Nurbs(nurbs.clone())).unwrap();
    let r = read_step(&wr.finish("2000-01-01T00:00:00"), "t.step").unwrap();
    let got: Vec<Shape> = r.shapes.into_iter().map(|(_, s)| s).collect();
    assert_eq!(
        got,
        vec![
            Shape::Curve(curve),
            Shape::Surface(Surface::BSpline(surf)),
            Shape::Surface(Surface::Nurbs(nurbs))
        ]
    );
    assert!(r.skipped.is_empty(), "{:?}", r.skipped);
    assert_eq!(r.scale_to_mm, 1.0);
}

#[test]
fn a_drawing_in_the_plane_comes_back_in_the_plane() {
    let three_d = |r: &StepRead| {
        r.shapes
            .iter()
            .all(|(_, s)| matches!(s, Shape::Curve(c) if c.dim() == 3))
    };
    let arc = Object::Nurbs(
        NurbsCurve::new(
            2,
            vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
            Points::from_2d(&[[1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]).unwrap(),
            vec![1.0, std::f64::consts::FRAC_1_SQRT_2, 1.0],
        )
        .unwrap(),
    );
    let line = Object::BSpline(
        lekalo::BSplineCurve::new(
            1,
            vec![0.0, 0.0, 1.0, 1.0],
            Points::from_2d(&[[0.0, 0.0], [3.0, -1.0 / 3.0]]).unwrap(),
        )
        .unwrap(),
    );
    let mut w = StepWriter::new("drawing");
    w.add_object(&arc).unwrap();
    w.add_object(&line).unwrap();
    let text = w.finish("2000-01-01T00:00:00");
    // padded with z = 0 for CAD systems, which read no 2-D curve from a curve set
    assert!(text.contains("CARTESIAN_POINT('',(1.,0.,0.))"), "{text}");
    let r = read_step(&text, "drawing.step").unwrap();
    let got: Vec<Shape> = r.shapes.into_iter().map(|(_, s)| s).collect();
    assert_eq!(got, vec![Shape::Curve(arc.clone()), Shape::Curve(line)]);

    // a 3-D curve in the plane z = 0 stays 3-D, and so do 2-D curves written beside it
    let flat3 = Object::BSpline(
        lekalo::BSplineCurve::new(
            1,
            vec![0.0, 0.0, 1.0, 1.0],
            Points::from_3d(&[[0.0, 0.0, 0.0], [1.0, 1.0, 0.0]]).unwrap(),
        )
        .unwrap(),
    );
    let mut w = StepWriter::new("mixed");
    w.add_object(&arc).unwrap();
    w.add_object(&flat3).unwrap();
    let r = read_step(&w.finish("2000-01-01T00:00:00"), "mixed.step").unwrap();
    assert!(three_d(&r));
    // a CAD system's curves in the plane z = 0 are read as it wrote them
    let r = read_step(OCC_STYLE, "occ.step").unwrap();
    assert!(three_d(&r));

    // a file of lekalo's drawing edited to put a point out of the plane keeps all curves 3-D
    let text = text.replace(
        "CARTESIAN_POINT('',(1.,0.,0.))",
        "CARTESIAN_POINT('',(1.,0.,5.E-1))",
    );
    let r = read_step(&text, "edited.step").unwrap();
    assert!(three_d(&r));
}

#[test]
fn errors_name_the_line_and_never_panic() {
    let e = read_step(
        "ISO-10303-21;\nDATA;\n#1=FOO(1.0E99999999999999999999);\nENDSEC;",
        "x",
    )
    .unwrap_err()
    .to_string();
    assert!(e.starts_with("x:3:"), "{e}");
    let e = read_step("hello", "x").unwrap_err().to_string();
    assert!(e.starts_with("x:1:"), "{e}");
    let e = read_step("ISO-10303-21;\nDATA;\n#1=FOO('abc);\n", "x")
        .unwrap_err()
        .to_string();
    assert!(e.contains("never closed"), "{e}");
    let bad = OCC_STYLE.replace("(3,1,3),(0.,0.5,1.)", "(3,1,3),(0.,1.5,1.)");
    let e = read_step(&bad, "b.step").unwrap_err().to_string();
    assert!(e.starts_with("b.step:13: entity #5"), "{e}");
    let e = read_step(
        "ISO-10303-21;\nDATA;\n#1=A(#99999999999999999999999);\n",
        "x",
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("#99999999999999999999999"), "{e}");
    for cut in [10, 200, 600, 900] {
        let _ = read_step(&OCC_STYLE[..cut], "cut");
    }
}

#[test]
fn numbers_a_double_cannot_hold_or_that_step_cannot_write_are_named() {
    let point =
        |x: &str| format!("ISO-10303-21;\nDATA;\n#1=CARTESIAN_POINT('',({x},0.,0.));\nENDSEC;\n");
    // beyond a double: refused by its line, the number quoted
    let e = refused(&point("1.E+400"));
    assert!(
        e.starts_with("h.step:3:") && e.contains("1.E+400 is outside the range"),
        "{e}"
    );
    // bare words where a number belongs: named, with how STEP writes numbers; a NaN was
    // "expected '(', found ','"
    for word in ["NaN", "nan", "INF", "Infinity"] {
        let e = refused(&point(word));
        assert!(
            e.starts_with("h.step:3:")
                && e.contains(&format!("{word} is not a value"))
                && e.contains("NaN and infinities have no STEP form"),
            "{e}"
        );
    }
    // a negative zero, a real without digits after the point and a tiny exponent are numbers
    for ok in ["-0.", "1.", "1.E-400", "-0.0E0"] {
        assert!(read_step(&point(ok), "ok.step").is_ok(), "{ok}");
    }
}

/// `text` with its message, for the tests of hostile files below.
fn refused(text: &str) -> String {
    read_step(text, "h.step").unwrap_err().to_string()
}

#[test]
fn deep_nesting_is_refused_without_recursion() {
    // a million '(' overflowed the stack of a recursive reader (abort, exit 134)
    let deep = format!(
        "ISO-10303-21;\nDATA;\n#1=FOO({}1{});\nENDSEC;\n",
        "(".repeat(1_000_000),
        ")".repeat(1_000_000)
    );
    let e = refused(&deep);
    assert!(
        e.starts_with("h.step:3:") && e.contains("nested more than"),
        "{e}"
    );
    // as deep as the limit is still read, typed parameters included
    let ok = format!(
        "ISO-10303-21;\nDATA;\n#1=FOO({}1{},A(B((2))));\nENDSEC;\n",
        "(".repeat(MAX_NESTING - 2),
        ")".repeat(MAX_NESTING - 2)
    );
    assert!(read_step(&ok, "ok.step").is_ok());
    // unbalanced or unterminated lists are syntax errors, not panics
    for bad in [
        "#1=FOO((1,2);",
        "#1=FOO(1,(2)));",
        "#1=FOO(A(",
        "#1=FOO(,);",
    ] {
        let e = refused(&format!("ISO-10303-21;\nDATA;\n{bad}\nENDSEC;\n"));
        assert!(e.starts_with("h.step:"), "{bad}: {e}");
    }
}

#[test]
fn knot_counts_are_checked_before_allocation() {
    let with = |mults: &str, knots: &str, degree: &str| {
        OCC_STYLE.replace(
            "2,(#1,#2,#3,#4),.UNSPECIFIED.,.F.,.F.,(3,1,3),(0.,0.5,1.)",
            &format!("{degree},(#1,#2,#3,#4),.UNSPECIFIED.,.F.,.F.,{mults},{knots}"),
        )
    };
    // one multiplicity of 2^31 - 3 asked for 16 GiB and aborted
    let e = refused(&with("(3,2147483645,3)", "(0.,0.5,1.)", "2"));
    assert!(
        e.starts_with("h.step:13: entity #5") && e.contains("add up to 2147483651 knots"),
        "{e}"
    );
    // multiplicities whose sum overflows 64 bits (8e15 bytes were asked for)
    let n = 20_000;
    let mults = format!("({})", vec!["999999999999999"; n].join(","));
    let knots = format!(
        "({})",
        (0..n)
            .map(|i| format!("{i}."))
            .collect::<Vec<_>>()
            .join(",")
    );
    let e = refused(&with(&mults, &knots, "2"));
    assert!(e.contains("more than 2^64 knots"), "{e}");
    // a degree far beyond the control points
    let e = refused(&with("(3,1,3)", "(0.,0.5,1.)", "99999999999999"));
    assert!(e.contains("degree 99999999999999 needs at least"), "{e}");
    // the same for a surface's two directions
    let surface = "ISO-10303-21;\nDATA;\n#1=CARTESIAN_POINT('',(0.,0.,0.));
#2=B_SPLINE_SURFACE_WITH_KNOTS('',1,1,((#1,#1),(#1,#1)),.UNSPECIFIED.,.F.,.F.,.F.,(2,2),(2,4294967295),(0.,1.),(0.,1.),.UNSPECIFIED.);
ENDSEC;\n";
    let e = refused(surface);
    assert!(
        e.starts_with("h.step:4: entity #2") && e.contains("v knot multiplicities add up to"),
        "{e}"
    );
}

#[test]
fn many_trims_of_one_long_basis_are_read_in_linear_time() {
    // 20,000 trims of one curve of 20,000 control points: each trim read the whole basis
    let n = 20_000;
    let mut text = String::from("ISO-10303-21;\nDATA;\n");
    let mut refs = Vec::with_capacity(n);
    for i in 0..n {
        text += &format!("#{}=CARTESIAN_POINT('',({i}.,0.,0.));\n", i + 1);
        refs.push(format!("#{}", i + 1));
    }
    let basis = n + 1;
    text += &format!(
        "#{basis}=B_SPLINE_CURVE_WITH_KNOTS('',1,({}),.UNSPECIFIED.,.F.,.F.,(2,{}2),(0.,{}1.),.UNSPECIFIED.);\n",
        refs.join(","),
        "1,".repeat(n - 2),
        (1..n - 1).map(|k| format!("{k}e-5,")).collect::<String>()
    );
    for k in 0..n {
        text += &format!(
            "#{}=TRIMMED_CURVE('',#{basis},(PARAMETER_VALUE(0.1)),(PARAMETER_VALUE(0.2)),.T.,.PARAMETER.);\n",
            basis + 1 + k
        );
    }
    text += "ENDSEC;\n";
    let start = std::time::Instant::now();
    let r = read_step(&text, "trims.step").unwrap();
    assert!(start.elapsed().as_secs() < 20, "{:?}", start.elapsed());
    // the first trims are read, the rest are listed as skipped with the reason
    let read = r.shapes.len();
    assert!(read > 0 && read < 10, "{read} trims read");
    assert_eq!(r.skipped.len(), n - read, "every other trim is listed");
    assert!(
        r.skipped.listed()[0].reason.contains("trimmed more often"),
        "{:?}",
        r.skipped.listed()[0]
    );
}

#[test]
fn units_that_are_not_positive_lengths_are_refused() {
    let with_unit = |factor: &str| {
        OCC_STYLE.replace(
            "#11 = ( LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT($,.METRE.) );",
            &format!(
                "#11 = ( CONVERSION_BASED_UNIT('INCH',#13) LENGTH_UNIT() NAMED_UNIT(*) );
#13 = LENGTH_MEASURE_WITH_UNIT(LENGTH_MEASURE({factor}),#14);
#14 = ( LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT(.MILLI.,.METRE.) );"
            ),
        )
    };
    let r = read_step(&with_unit("25.4"), "in.step").unwrap();
    assert_eq!(
        (r.length_unit.as_str(), r.scale_to_mm),
        ("INCH (25.4 mm)", 25.4)
    );
    // 0 turned every point into the origin, a negative unit mirrored the geometry
    for (factor, shown) in [("0.", "0 mm"), ("-25.4", "-25.4 mm"), ("1.E308", "inf mm")] {
        let text = with_unit(factor);
        let text = if factor == "1.E308" {
            // a finite factor whose product with the base unit is not
            text.replace("SI_UNIT(.MILLI.,.METRE.)", "SI_UNIT(.KILO.,.METRE.)")
        } else {
            text
        };
        let e = refused(&text);
        assert!(
            e.starts_with("h.step:22: entity #11") && e.contains("positive finite length"),
            "{factor}: {e}"
        );
        assert!(e.contains(shown), "{factor}: {e}");
    }
}

/// A length unit that cannot be read was taken for millimetres: an SI unit other than the metre
/// (`SI_UNIT(.MILLI.,.FURLONG.)`), an unknown prefix, a conversion referring to itself. Each is
/// refused naming its entity; `SI_UNIT(.METRE.)` without a prefix is the metre.
#[test]
fn length_units_that_cannot_be_read_are_refused_not_assumed() {
    let unit = "#11 = ( LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT($,.METRE.) );";
    for bad in [
        "#11 = ( LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT(.MILLI.,.FURLONG.) );",
        "#11 = ( LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT(.ZEPTO.,.METRE.) );",
        "#11 = ( CONVERSION_BASED_UNIT('LOOP',#13) LENGTH_UNIT() NAMED_UNIT(*) );
#13 = LENGTH_MEASURE_WITH_UNIT(LENGTH_MEASURE(2.),#11);",
        "#11 = ( CONVERSION_BASED_UNIT('INCH',#999) LENGTH_UNIT() NAMED_UNIT(*) );",
    ] {
        let e = refused(&OCC_STYLE.replace(unit, bad));
        assert!(
            e.starts_with("h.step:22: entity #11: a length unit lekalo cannot read"),
            "{bad}: {e}"
        );
    }
    let r = read_step(
        &OCC_STYLE.replace(
            unit,
            "#11 = ( LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT(.METRE.) );",
        ),
        "m.step",
    )
    .unwrap();
    assert_eq!((r.length_unit.as_str(), r.scale_to_mm), ("metre", 1000.0));
    // no unit declared: millimetres, said to be assumed
    let r = read_step(&OCC_STYLE.replace(unit, ""), "none.step").unwrap();
    assert_eq!(r.length_unit, "millimetre (assumed)");
}

/// A STEP file of `n` cubic curves (about 600 bytes each) written by [`StepWriter`].
fn many_curves(n: usize) -> String {
    let mut w = StepWriter::new("curves");
    for k in 0..n {
        let x = k as f64;
        let c = lekalo::BSplineCurve::new(
            3,
            vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0],
            Points::from_rows(&[
                vec![x, 0.0, 0.0],
                vec![x, 1.0, 0.5],
                vec![x, 2.0, -0.5],
                vec![x, 3.0, 0.0],
            ])
            .unwrap(),
        )
        .unwrap();
        w.add_object(&Object::BSpline(c)).unwrap();
    }
    w.finish("2000-01-01T00:00:00")
}

#[test]
fn progress_reports_the_bytes_then_the_entities_and_cancels() {
    use std::sync::atomic::{AtomicBool, Ordering};
    use std::sync::Mutex;

    let text = many_curves(1000);
    assert!(text.len() > 4 * (1 << 16), "the file spans several reports");
    for faces in [false, true] {
        let plain = read_step_faces(&text, "c.step", usize::MAX).unwrap();
        let seen = Mutex::new(Vec::new());
        let report = |d: u64, t: u64| seen.lock().unwrap().push((d, t));
        let stop = AtomicBool::new(false);
        let hooked = read_step_with_progress(
            &text,
            "c.step",
            usize::MAX,
            faces,
            crate::SKIPPED_LISTED,
            &lekalo::Progress::new()
                .with_report(&report)
                .with_cancel(&stop),
        )
        .unwrap();
        assert_eq!(hooked.shapes, plain.shapes, "the hook changed the curves");
        assert_eq!(
            hooked.faces.len(),
            if faces { plain.faces.len() } else { 0 }
        );
        let seen = seen.into_inner().unwrap();
        let total = 2 * text.len() as u64;
        assert!(seen.iter().all(|&(d, t)| t == total && d <= t), "{seen:?}");
        assert!(seen.windows(2).all(|w| w[0].0 <= w[1].0), "reports go back");
        // parsing reports bytes below the length, conversion above it
        assert!(
            seen.iter().any(|&(d, _)| d > 0 && d < total / 2),
            "{seen:?}"
        );
        assert!(
            seen.iter().any(|&(d, _)| d > total / 2 && d < total),
            "{seen:?}"
        );
        assert_eq!(seen.last(), Some(&(total, total)));
    }
    // a flag set from the first report on stops the read, while parsing or converting
    for after in [1, 8] {
        let stop = AtomicBool::new(false);
        let calls = Mutex::new(0);
        let report = |_: u64, _: u64| {
            let mut c = calls.lock().unwrap();
            *c += 1;
            if *c >= after {
                stop.store(true, Ordering::Relaxed);
            }
        };
        let e = read_step_with_progress(
            &text,
            "c.step",
            usize::MAX,
            true,
            crate::SKIPPED_LISTED,
            &lekalo::Progress::new()
                .with_report(&report)
                .with_cancel(&stop),
        )
        .unwrap_err();
        assert!(matches!(e, IoError::Cancelled { .. }), "{e:?}");
        assert_eq!(e.to_string(), "c.step: reading STEP: cancelled");
        assert!(!e.is_bad_input());
        assert_eq!(*calls.lock().unwrap(), after, "stopped at the first check");
    }
}

#[test]
fn instances_are_found_by_id_dense_or_sparse() {
    // ids far apart (beyond the dense table) and out of order read as the same curve
    let dense = "ISO-10303-21;HEADER;ENDSEC;DATA;
#1=CARTESIAN_POINT('',(0.,0.,0.));#2=CARTESIAN_POINT('',(1.,0.,0.));
#3=B_SPLINE_CURVE_WITH_KNOTS('',1,(#1,#2),.UNSPECIFIED.,.F.,.F.,(2,2),(0.,1.),.UNSPECIFIED.);
ENDSEC;END-ISO-10303-21;";
    let sparse = dense
        .replace("#3=", "#5=")
        .replace("#1", "#900000000000")
        .replace("#2", "#7");
    let a = read_step(dense, "a.step").unwrap();
    let b = read_step(&sparse, "b.step").unwrap();
    assert_eq!(a.shapes[0].1, b.shapes[0].1);
    assert_eq!(b.shapes[0].0, 5);
    // a repeated id is refused at its second definition, wherever the first is
    let twice = sparse.replace("#7=", "#900000000000=");
    let e = read_step(&twice, "t.step").unwrap_err().to_string();
    assert!(e.contains("#900000000000 is defined twice"), "{e}");
    assert!(e.starts_with("t.step:2:"), "{e}");
}

/// The instances of `data` (the text of a DATA section), parsed.
fn parsed(text: &str) -> super::parse::Parsed<'_> {
    let progress = lekalo::Progress::new();
    let meter = super::progress::Meter {
        progress: &progress,
        source: "p.step",
        len: text.len() as u64,
    };
    super::parse::parse(text, "p.step", usize::MAX, &meter).unwrap()
}

#[test]
fn instances_keep_their_type_and_parse_their_records_when_asked() {
    let text = "ISO-10303-21;\nDATA;\n#4=cartesian_point('p''q',(1.,-2.5E1,3));\n\
                #2=(b_spline_curve(1,(#4)) Bounded_Curve() );\n#3=();\nENDSEC;\n";
    let p = parsed(text);
    assert_eq!(p.instances.ids(), &[2, 3, 4]);
    let point = p.instances.known(&4);
    assert_eq!(point.type_name(), "CARTESIAN_POINT");
    assert_eq!(point.line(), 3);
    // the names are known without parsing, the records are parsed on demand
    assert!(point.has("CARTESIAN_POINT") && point.records.get().is_none());
    assert_eq!(
        point.get("CARTESIAN_POINT").unwrap(),
        &[
            P::Str("p'q".into()),
            P::List(vec![P::Num(1.0), P::Num(-25.0), P::Num(3.0)])
        ]
    );
    assert!(point.get("DIRECTION").is_none());
    let curve = p.instances.known(&2);
    assert_eq!(curve.type_name(), "(B_SPLINE_CURVE BOUNDED_CURVE)");
    assert_eq!(curve.line(), 4);
    assert_eq!(curve.records().len(), 2);
    assert_eq!(curve.get("BOUNDED_CURVE").unwrap(), &[]);
    assert_eq!(
        curve.get("B_SPLINE_CURVE").unwrap()[1],
        P::List(vec![P::Ref(4)])
    );
    let empty = p.instances.known(&3);
    assert_eq!((empty.type_name(), empty.records().len()), ("()".into(), 0));
    // instances of one type share it
    assert!(p.instances.any_of(&["BOUNDED_CURVE"]) && !p.instances.any_of(&["CIRCLE"]));
}

#[test]
fn numbers_read_straight_from_the_text_agree_with_the_records() {
    let cases = [
        (
            "#1 = CARTESIAN_POINT ( 'a''b' , ( 1. , -2.5E1 ,3 ) ) ;",
            Some(vec![1.0, -25.0, 3.0]),
        ),
        ("#1=DIRECTION('',(/* x */ 0.,1.));", Some(vec![0.0, 1.0])),
        ("#1=CARTESIAN_POINT('',());", Some(vec![])),
        // written otherwise: read from the records
        ("#1=CARTESIAN_POINT('',(LENGTH_MEASURE(1.),2.));", None),
        ("#1=CARTESIAN_POINT('',(1.,2.),3.);", None),
        ("#1=CARTESIAN_POINT('',(1.,$));", None),
        ("#1=(CARTESIAN_POINT('',(1.,2.)) X());", None),
    ];
    for (data, want) in cases {
        let text = format!("ISO-10303-21;\nDATA;\n{data}\nENDSEC;\n");
        let p = parsed(&text);
        let inst = p.instances.known(&1);
        assert_eq!(inst.numbers(), want, "{data}");
        if let Some(want) = want {
            let name = &inst.names()[0];
            let from_records = numbers(&inst.get(name).unwrap()[1], "x").unwrap();
            assert_eq!(from_records, want, "{data}");
        }
    }
    // a point written either way is the same control point
    let curve = |p: &str| {
        let text = format!(
            "ISO-10303-21;\nDATA;\n#1=CARTESIAN_POINT('',(0.,0.,0.));\n#2={p};\n\
             #3=B_SPLINE_CURVE_WITH_KNOTS('',1,(#1,#2),.UNSPECIFIED.,.F.,.F.,(2,2),(0.,1.),.UNSPECIFIED.);\nENDSEC;\n"
        );
        read_step(&text, "c.step").unwrap().shapes
    };
    assert_eq!(
        curve("CARTESIAN_POINT('',(1.5,2.,3.))"),
        curve("CARTESIAN_POINT('',(LENGTH_MEASURE(1.5),2.,3.))")
    );
}

#[test]
fn unsorted_ids_are_sorted_with_their_instances() {
    let text = "ISO-10303-21;\nDATA;\n#9=B();\n#1=A();\n#5=C(1.);\nENDSEC;\n";
    let p = parsed(text);
    assert_eq!(p.instances.ids(), &[1, 5, 9]);
    let names: Vec<String> = p.instances.values().map(|i| i.type_name()).collect();
    assert_eq!(names, ["A", "C", "B"]);
    assert_eq!(p.instances.known(&5).get("C").unwrap(), &[P::Num(1.0)]);
    assert_eq!(p.instances.known(&9).line(), 3);
}

/// An assembly: a bracket placed twice in the root (turned a quarter about z and moved to
/// x = 10; moved to z = 5), and a pin in a sub-assembly (pin at x = 1 in the sub-assembly,
/// written with the parent's representation first; the sub-assembly at y = 100 in the root).
const ASSEMBLY: &str = "ISO-10303-21;
HEADER;
FILE_DESCRIPTION((''),'2;1');
FILE_NAME('a','2024-01-01T00:00:00',(''),(''),'','','');
FILE_SCHEMA(('AUTOMOTIVE_DESIGN { 1 0 10303 214 1 1 1 1 }'));
ENDSEC;
DATA;
#10 = PRODUCT_DEFINITION('root','',$,$);
#11 = PRODUCT_DEFINITION('bracket','',$,$);
#12 = PRODUCT_DEFINITION('sub','',$,$);
#13 = PRODUCT_DEFINITION('pin','',$,$);
#20 = PRODUCT_DEFINITION_SHAPE('','',#10);
#21 = PRODUCT_DEFINITION_SHAPE('','',#11);
#22 = PRODUCT_DEFINITION_SHAPE('','',#12);
#23 = PRODUCT_DEFINITION_SHAPE('','',#13);
#30 = SHAPE_REPRESENTATION('root',(#100),#99);
#31 = SHAPE_REPRESENTATION('bracket',(#110),#99);
#32 = SHAPE_REPRESENTATION('sub',(#113),#99);
#33 = SHAPE_REPRESENTATION('pin',(#117,#65),#99);
#35 = GEOMETRICALLY_BOUNDED_WIREFRAME_SHAPE_REPRESENTATION('',(#60),#99);
#36 = SHAPE_REPRESENTATION_RELATIONSHIP('','',#31,#35);
#40 = SHAPE_DEFINITION_REPRESENTATION(#20,#30);
#41 = SHAPE_DEFINITION_REPRESENTATION(#21,#31);
#42 = SHAPE_DEFINITION_REPRESENTATION(#22,#32);
#43 = SHAPE_DEFINITION_REPRESENTATION(#23,#33);
#50 = NEXT_ASSEMBLY_USAGE_OCCURRENCE('1','b1','',#10,#11,$);
#51 = NEXT_ASSEMBLY_USAGE_OCCURRENCE('2','b2','',#10,#11,$);
#52 = NEXT_ASSEMBLY_USAGE_OCCURRENCE('3','s','',#10,#12,$);
#53 = NEXT_ASSEMBLY_USAGE_OCCURRENCE('4','p','',#12,#13,$);
#54 = PRODUCT_DEFINITION_SHAPE('','',#50);
#55 = PRODUCT_DEFINITION_SHAPE('','',#51);
#56 = PRODUCT_DEFINITION_SHAPE('','',#52);
#57 = PRODUCT_DEFINITION_SHAPE('','',#53);
#60 = B_SPLINE_CURVE_WITH_KNOTS('bracket edge',1,(#61,#62),.UNSPECIFIED.,.F.,.F.,(2,2),(0.,1.),.UNSPECIFIED.);
#61 = CARTESIAN_POINT('',(0.,0.,0.));
#62 = CARTESIAN_POINT('',(1.,0.,0.));
#65 = B_SPLINE_CURVE_WITH_KNOTS('pin edge',1,(#66,#67),.UNSPECIFIED.,.F.,.F.,(2,2),(0.,1.),.UNSPECIFIED.);
#66 = CARTESIAN_POINT('',(0.,0.,0.));
#67 = CARTESIAN_POINT('',(0.,0.,1.));
#70 = ITEM_DEFINED_TRANSFORMATION('','',#110,#111);
#71 = ITEM_DEFINED_TRANSFORMATION('','',#110,#112);
#72 = ITEM_DEFINED_TRANSFORMATION('','',#113,#114);
#73 = ITEM_DEFINED_TRANSFORMATION('','',#116,#117);
#80 = ( REPRESENTATION_RELATIONSHIP('','',#31,#30) REPRESENTATION_RELATIONSHIP_WITH_TRANSFORMATION(#70) SHAPE_REPRESENTATION_RELATIONSHIP() );
#81 = ( REPRESENTATION_RELATIONSHIP('','',#31,#30) REPRESENTATION_RELATIONSHIP_WITH_TRANSFORMATION(#71) SHAPE_REPRESENTATION_RELATIONSHIP() );
#82 = ( REPRESENTATION_RELATIONSHIP('','',#32,#30) REPRESENTATION_RELATIONSHIP_WITH_TRANSFORMATION(#72) SHAPE_REPRESENTATION_RELATIONSHIP() );
#83 = ( REPRESENTATION_RELATIONSHIP('','',#32,#33) REPRESENTATION_RELATIONSHIP_WITH_TRANSFORMATION(#73) SHAPE_REPRESENTATION_RELATIONSHIP() );
#90 = CONTEXT_DEPENDENT_SHAPE_REPRESENTATION(#80,#54);
#91 = CONTEXT_DEPENDENT_SHAPE_REPRESENTATION(#81,#55);
#92 = CONTEXT_DEPENDENT_SHAPE_REPRESENTATION(#82,#56);
#93 = CONTEXT_DEPENDENT_SHAPE_REPRESENTATION(#83,#57);
#97 = CARTESIAN_POINT('',(0.,0.,0.));
#98 = ( LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT(.MILLI.,.METRE.) );
#99 = ( GEOMETRIC_REPRESENTATION_CONTEXT(3) GLOBAL_UNIT_ASSIGNED_CONTEXT((#98)) REPRESENTATION_CONTEXT('','') );
#100 = AXIS2_PLACEMENT_3D('',#97,$,$);
#110 = AXIS2_PLACEMENT_3D('',#97,$,$);
#111 = AXIS2_PLACEMENT_3D('',#120,#121,#122);
#112 = AXIS2_PLACEMENT_3D('',#123,$,$);
#113 = AXIS2_PLACEMENT_3D('',#97,$,$);
#114 = AXIS2_PLACEMENT_3D('',#124,$,$);
#116 = AXIS2_PLACEMENT_3D('',#125,$,$);
#117 = AXIS2_PLACEMENT_3D('',#97,$,$);
#120 = CARTESIAN_POINT('',(10.,0.,0.));
#121 = DIRECTION('',(0.,0.,1.));
#122 = DIRECTION('',(0.,1.,0.));
#123 = CARTESIAN_POINT('',(0.,0.,5.));
#124 = CARTESIAN_POINT('',(0.,100.,0.));
#125 = CARTESIAN_POINT('',(1.,0.,0.));
ENDSEC;
END-ISO-10303-21;
";

#[test]
fn parts_of_an_assembly_are_read_at_each_of_their_placements() {
    let r = read_step(ASSEMBLY, "assembly.step").unwrap();
    let ends: Vec<(u64, Vec<f64>)> = r
        .shapes
        .iter()
        .map(|(id, s)| match s {
            Shape::Curve(Object::BSpline(c)) => (*id, c.control_points().as_slice().to_vec()),
            other => panic!("#{id}: {other:?}"),
        })
        .collect();
    let near = |a: &[f64], b: &[f64]| a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-14);
    assert_eq!(ends.len(), 3, "{ends:?}");
    // the bracket at both its occurrences, in the order written
    assert_eq!(ends[0].0, 60);
    assert!(
        near(&ends[0].1, &[10.0, 0.0, 0.0, 10.0, 1.0, 0.0]),
        "{ends:?}"
    );
    assert_eq!(ends[1].0, 60);
    assert!(
        near(&ends[1].1, &[0.0, 0.0, 5.0, 1.0, 0.0, 5.0]),
        "{ends:?}"
    );
    // the pin through the sub-assembly
    assert_eq!(ends[2].0, 65);
    assert!(
        near(&ends[2].1, &[1.0, 100.0, 0.0, 1.0, 100.0, 1.0]),
        "{ends:?}"
    );
    // without the occurrences, every instance is read once, as written
    let flat: String = ASSEMBLY
        .lines()
        .filter(|l| !l.contains("NEXT_ASSEMBLY_USAGE_OCCURRENCE"))
        .collect::<Vec<_>>()
        .join("\n");
    let r = read_step(&flat, "parts.step").unwrap();
    assert_eq!(r.shapes.len(), 2);
}
