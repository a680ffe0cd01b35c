//! Tests of the IGES reader and writer: round trips, hostile files, size limits, progress.

use lekalo::{BSplineCurve, BSplineSurface, NurbsCurve, NurbsSurface, Points, Progress};

use super::*;
use crate::error::IoError;
use crate::object::Object;
use crate::shape::Surface;

/// The file name goes into the Global section as Hollerith strings, whose counts are bytes:
/// non-ASCII and control characters are written `?`, and a name longer than a line continues
/// on the next; every line keeps its 80 columns and the file reads back.
#[test]
fn names_of_any_characters_and_length_keep_the_columns() {
    let c = Object::BSpline(
        BSplineCurve::new(
            1,
            vec![0.0, 0.0, 1.0, 1.0],
            Points::from_2d(&[[0.0, 0.0], [1.0, 2.0]]).unwrap(),
        )
        .unwrap(),
    );
    let long = format!("{},;H'é", "x".repeat(150));
    for name in ["q'é☃.igs", "a\nb\r,;.igs", long.as_str(), ""] {
        let mut w = IgesWriter::new();
        w.add_object(&c).unwrap();
        let text = w.finish(name, "20000101.000000");
        for l in text.lines() {
            assert_eq!(l.len(), 80, "{name:?}: {l}");
        }
        let r = read_iges(&text, "t.igs").unwrap_or_else(|e| panic!("{name:?}: {e}"));
        assert_eq!(r.shapes.len(), 1, "{name:?}");
    }
}

#[test]
fn round_trip_every_kind_bit_for_bit() {
    let w = std::f64::consts::FRAC_1_SQRT_2;
    let ctrl =
        Points::from_3d(&[[1.0, 0.0, 0.1], [1.0, 1.0, 1.0 / 3.0], [0.0, 1.0, 1e-300]]).unwrap();
    let nurbs = Object::Nurbs(
        NurbsCurve::new(
            2,
            vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
            ctrl.clone(),
            vec![1.0, w, 1.0],
        )
        .unwrap(),
    );
    let bs =
        Object::BSpline(BSplineCurve::new(2, vec![0.5, 0.5, 0.5, 2.0, 2.0, 2.0], ctrl).unwrap());
    let net = Points::from_3d(&[
        [0.0, 0.0, 0.0],
        [0.0, 1.0, 0.7],
        [0.0, 2.0, 0.1],
        [1.0, 0.0, -0.3],
        [1.0, 1.0, 1.0 / 7.0],
        [1.0, 2.0, 0.0],
    ])
    .unwrap();
    let s = Surface::BSpline(
        BSplineSurface::new(
            1,
            2,
            vec![0.0, 0.0, 2.0, 2.0],
            vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
            net.clone(),
            (2, 3),
        )
        .unwrap(),
    );
    let n = Surface::Nurbs(
        NurbsSurface::new(
            1,
            2,
            vec![0.0, 0.0, 2.0, 2.0],
            vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
            net,
            vec![1.0, 0.5, 2.0, 1.5, 1.0, 0.25],
            (2, 3),
        )
        .unwrap(),
    );
    let mut wr = IgesWriter::new();
    wr.add_object(&nurbs).unwrap();
    wr.add_object(&bs).unwrap();
    wr.add_surface(&s).unwrap();
    wr.add_surface(&n).unwrap();
    let text = wr.finish("t", "20000101.000000");
    for l in text.lines() {
        assert_eq!(l.len(), 80, "{l}");
    }
    let r = read_iges(&text, "t.igs").unwrap();
    let got: Vec<Shape> = r.shapes.into_iter().map(|(_, s)| s).collect();
    assert_eq!(got[0], Shape::Curve(nurbs));
    assert_eq!(got[1], Shape::Curve(bs));
    assert_eq!(got[2], Shape::Surface(s));
    let (Shape::Surface(Surface::Nurbs(a)), Surface::Nurbs(b)) = (&got[3], &n) else {
        panic!("a NURBS surface")
    };
    assert_eq!(a.weights(), b.weights());
    assert_eq!(a.control_points(), b.control_points());
    assert_eq!(r.scale_to_mm, 1.0);
}

#[test]
fn errors_name_the_line() {
    let e = read_iges("short line\n", "x.igs").unwrap_err().to_string();
    assert!(e.starts_with("x.igs:1:"), "{e}");
    let mut wr = IgesWriter::new();
    let c = Object::BSpline(
        BSplineCurve::new(
            1,
            vec![0.0, 0.0, 1.0, 1.0],
            Points::from_2d(&[[0.0, 0.0], [1.0, 1.0]]).unwrap(),
        )
        .unwrap(),
    );
    wr.add_object(&c).unwrap();
    let text = wr.finish("t", "20000101.000000").replace(
        "126,1,1,1,0,1,0,0.,0.,1.,1.,",
        "126,1,1,1,0,1,0,0.,2.,1.,1.,",
    );
    assert!(text.contains("0.,2.,1.,1."), "{text}");
    let e = read_iges(&text, "x.igs").unwrap_err().to_string();
    assert!(e.contains("entity 126"), "{e}");
}

/// An IGES file with the Global section `global` and one entity of type `ty` whose parameter
/// data is `params`, laid out in 80-column records as a writer would.
pub(super) fn one_entity(global: &str, ty: u32, params: &str) -> String {
    let mut out = format!("{:<72}S{:>7}\n", "hostile", 1);
    // padded by bytes: the reader finds the section letter at byte 72
    let pad = 72usize.saturating_sub(global.len());
    out += &format!("{global}{}G{:>7}\n", " ".repeat(pad), 1);
    let lines: Vec<&str> = params
        .as_bytes()
        .chunks(64)
        .map(|c| std::str::from_utf8(c).unwrap())
        .collect();
    let d = |fields: [String; 9], seq: usize| {
        let mut l: String = fields.iter().map(|f| format!("{f:>8}")).collect();
        l += &format!("D{seq:>7}\n");
        l
    };
    let s = |x: usize| x.to_string();
    out += &d(
        [
            ty.to_string(),
            s(1),
            s(0),
            s(0),
            s(0),
            s(0),
            s(0),
            s(0),
            "00000000".into(),
        ],
        1,
    );
    out += &d(
        [
            ty.to_string(),
            s(0),
            s(0),
            s(lines.len()),
            s(0),
            String::new(),
            String::new(),
            String::new(),
            s(0),
        ],
        2,
    );
    for (i, l) in lines.iter().enumerate() {
        out += &format!("{l:<64}{:>8}P{:>7}\n", 1, i + 1);
    }
    out += &format!("{:<72}T{:>7}\n", "S      1G      1D      2P      1", 1);
    out
}

const SEGMENT: &str = "126,1,1,0,0,1,0,0.,0.,1.,1.,1.,1.,0.,0.,0.,1.,1.,0.,0.,1.,0.,0.,1.;";

/// Numbers a double cannot hold (`1.D+400`) and words (`NaN`, `inf`) where a coordinate
/// belongs are named with what is written; they were "parameter 20 is missing or not a
/// number". A negative zero and `1.D0` are numbers.
#[test]
fn numbers_out_of_range_and_words_are_quoted() {
    let c = Object::BSpline(
        BSplineCurve::new(
            1,
            vec![0.0, 0.0, 1.0, 1.0],
            Points::from_2d(&[[0.0, 0.0], [7.0, 2.0]]).unwrap(),
        )
        .unwrap(),
    );
    let mut w = IgesWriter::new();
    w.add_object(&c).unwrap();
    let text = w.finish("n.igs", "20000101.000000");
    // the parameter lines rewritten with the point's x (7.) at the start of the second line,
    // where a longer number has room in the 64 columns
    let p1 = text.lines().find(|l| l.ends_with("P      1")).expect("P 1");
    let p2 = text.lines().find(|l| l.ends_with("P      2")).expect("P 2");
    assert!(
        p1.starts_with("126,1,1,1,0,1,0,0.,0.,1.,1.,1.,1.,0.,0.,0.,7.,2.,"),
        "{p1}"
    );
    let with = |x: &str| {
        let first = format!(
            "{:<64}{}",
            "126,1,1,1,0,1,0,0.,0.,1.,1.,1.,1.,0.,0.,0.,",
            &p1[64..]
        );
        let second = format!("{:<64}{}", format!("{x},2.,0.,0.,1.,0.,0.,1.;"), &p2[64..]);
        text.replacen(p1, &first, 1).replacen(p2, &second, 1)
    };
    let e = read_iges(&with("1.D+400"), "n.igs")
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("is 1.D+400, outside the range of a double"),
        "{e}"
    );
    for word in ["NaN", "inf", "1.E"] {
        let e = read_iges(&with(word), "n.igs").unwrap_err().to_string();
        assert!(e.contains(&format!("is \"{word}\", not a number")), "{e}");
    }
    for ok in ["-0.", "7.D0", "7"] {
        assert!(read_iges(&with(ok), "n.igs").is_ok(), "{ok}");
    }
}

#[test]
fn hostile_global_sections_are_read_without_panics() {
    let r = read_iges(&one_entity("1H,,1H;;", 126, SEGMENT), "ok.igs").unwrap();
    assert_eq!(r.shapes.len(), 1, "the file of the tests below reads");
    // a Hollerith count of 2^64 - 1 overflowed the end index; one with more digits than
    // that parsed as 0; a multi-byte delimiter after 1H was sliced inside its bytes
    for global in [
        "18446744073709551615Habc;",
        "1H,,1H;,99999999999999999999999Habc;",
        "1H,,1Hé,3Habc;",
        "é,1H;;",
    ] {
        let r = read_iges(&one_entity(global, 126, SEGMENT), "g.igs");
        assert!(r.is_ok(), "{global}: {r:?}");
    }
    // é as the parameter delimiter: read as such (here the data use ',', so entity 126
    // has no readable counts, a named error)
    let e = read_iges(&one_entity("1Hé,1H;;", 126, SEGMENT), "g.igs").unwrap_err();
    assert!(e.to_string().starts_with("g.igs:5: entity 126"), "{e}");
    // in the parameter data too
    let text = one_entity("1H,,1H;;", 126, "126,18446744073709551615H1,1;");
    let e = read_iges(&text, "p.igs").unwrap_err().to_string();
    assert!(e.starts_with("p.igs:5: entity 126"), "{e}");
}

#[test]
fn reading_is_linear_in_long_fields_and_shared_parameter_lines() {
    // a field of 200,000 digits was scanned again for every digit (quadratic)
    let long = format!(
        "126,{}1,1,0,0,1,0;",
        " ".repeat(100_000) + &"7".repeat(200_000)
    );
    let start = std::time::Instant::now();
    let e = read_iges(&one_entity("1H,,1H;;", 126, &long), "long.igs").unwrap_err();
    assert!(start.elapsed().as_secs() < 5, "{:?}", start.elapsed());
    assert!(e.to_string().contains("parameter 1"), "{e}");
    // many directory entries pointing at the same parameter lines would read them once
    // per entry: refused
    let one = one_entity("1H,,1H;;", 126, SEGMENT);
    let d: Vec<&str> = one.lines().filter(|l| l.get(72..73) == Some("D")).collect();
    let again: String = d
        .iter()
        .enumerate()
        .map(|(k, l)| format!("{}{:>7}\n", &l[..73], k + 3))
        .collect();
    let shared = one.replacen(&format!("{}\n", d[1]), &format!("{}\n{again}", d[1]), 1);
    let e = read_iges(&shared, "shared.igs").unwrap_err().to_string();
    assert!(e.contains("also another entity's"), "{e}");
}

#[test]
fn declared_sizes_the_file_cannot_hold_are_refused_before_allocation() {
    let refused = |ty: u32, params: &str| {
        read_iges(&one_entity("1H,,1H;;", ty, params), "h.igs")
            .unwrap_err()
            .to_string()
    };
    // a 23170 x 23170 net (2^31 points) in a few bytes aborted on allocation
    let e = refused(128, "128,23169,23169,1,1,0,0,1,0,0,0.,0.,1.,1.;");
    assert!(
        e.starts_with("h.igs:5: entity 128")
            && e.contains("need 2147441958 parameters, the entity has 14"),
        "{e}"
    );
    // counts whose sums or products overflow
    for (ty, params) in [
        (128, "128,18446744073709551615,1,1,1,0,0,1,0,0;"),
        (128, "128,4294967296,4294967296,1,1,0,0,1,0,0;"),
        (126, "126,18446744073709551615,1,0,0,1,0;"),
        (126, "126,1,18446744073709551614,0,0,1,0;"),
    ] {
        let e = refused(ty, params);
        assert!(
            e.contains("more parameters than any file holds"),
            "{params}: {e}"
        );
    }
    // a curve whose counts promise more numbers than it has
    let e = refused(126, "126,3,1,0,0,1,0,0.,0.,1.,1.;");
    assert!(
        e.contains("K = 3, M = 1") && e.contains("need 31 parameters"),
        "{e}"
    );
}
#[test]
fn progress_reports_the_entities_and_cancels() {
    use std::sync::atomic::{AtomicBool, Ordering};
    use std::sync::Mutex;

    let mut w = IgesWriter::new();
    for k in 0..3000 {
        let x = f64::from(k);
        let c = BSplineCurve::new(
            1,
            vec![0.0, 0.0, 1.0, 1.0],
            Points::from_rows(&[vec![x, 0.0, 0.0], vec![x, 1.0, 0.0]]).unwrap(),
        )
        .unwrap();
        w.add_object(&Object::BSpline(c)).unwrap();
    }
    let text = w.finish("lines.igs", "20000101.000000");
    let plain = read_iges(&text, "l.igs").unwrap();
    let seen = Mutex::new(Vec::new());
    let report = |d: u64, t: u64| seen.lock().unwrap().push((d, t));
    let hooked = read_iges_with_progress(
        &text,
        "l.igs",
        usize::MAX,
        false,
        crate::SKIPPED_LISTED,
        &Progress::new().with_report(&report),
    )
    .unwrap();
    assert_eq!(hooked, plain, "the hook changed the result");
    let seen = seen.into_inner().unwrap();
    assert_eq!(
        seen,
        vec![(0, 3000), (1024, 3000), (2048, 3000), (3000, 3000)]
    );
    let stop = AtomicBool::new(false);
    let report = |d: u64, _: u64| stop.store(d >= 1024, Ordering::Relaxed);
    for faces in [false, true] {
        let e = read_iges_with_progress(
            &text,
            "l.igs",
            usize::MAX,
            faces,
            crate::SKIPPED_LISTED,
            &Progress::new().with_report(&report).with_cancel(&stop),
        )
        .unwrap_err();
        assert!(matches!(e, IoError::Cancelled { .. }), "{e:?}");
        assert_eq!(e.to_string(), "l.igs: reading IGES: cancelled");
    }
}
