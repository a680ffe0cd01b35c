//! Tests of the `.npz` curve archive: round trips bit for bit and named errors.

use super::*;
use crate::npy::{le_bytes, write_npy};

fn bspline() -> Object {
    let ctrl =
        Points::from_2d(&[[0.1, 0.0], [1.0 / 3.0, 2.0], [2.0, -1e-300], [3.5, 1e300]]).unwrap();
    Object::BSpline(BSplineCurve::new(2, vec![0.0, 0.0, 0.0, 0.7, 1.0, 1.0, 1.0], ctrl).unwrap())
}

fn nurbs() -> Object {
    // weights and coordinates exact in binary, so w·P / w gives P back exactly
    let ctrl = Points::from_2d(&[[1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]).unwrap();
    Object::Nurbs(
        NurbsCurve::new(
            2,
            vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
            ctrl,
            vec![1.0, 0.5, 1.0],
        )
        .unwrap(),
    )
}

#[test]
fn npz_round_trips_are_bit_exact() {
    for obj in [bspline(), nurbs()] {
        let bytes = curve_to_npz(&obj).unwrap();
        let back = read_npz_curve(&bytes, "c.npz").unwrap();
        assert_eq!(back, obj, "{}", obj.type_name());
        assert_eq!(
            curve_to_npz(&back).unwrap(),
            bytes,
            "the archive is reproducible"
        );
    }
}

#[test]
fn npz_members_are_the_documented_arrays() {
    let bytes = curve_to_npz(&nurbs()).unwrap();
    let mut z = ZipArchive::new(Cursor::new(&bytes[..])).unwrap();
    let mut names: Vec<String> = z.file_names().map(String::from).collect();
    names.sort();
    assert_eq!(
        names,
        [
            "control_points.npy",
            "degree.npy",
            "knots.npy",
            "weights.npy"
        ]
    );
    let mut read = |name: &str| {
        let mut f = z.by_name(name).unwrap();
        assert_eq!(f.compression(), CompressionMethod::Stored, "{name}");
        let mut b = Vec::new();
        f.read_to_end(&mut b).unwrap();
        b
    };
    let degree = read("degree.npy");
    let header = String::from_utf8_lossy(&degree[10..degree.len() - 8]).to_string();
    assert!(
        header.starts_with("{'descr': '<i8', 'fortran_order': False, 'shape': (), }"),
        "{header}"
    );
    assert_eq!(degree[degree.len() - 8..], 2i64.to_le_bytes());
    let (shape, w) = read_array(&read("weights.npy"), "w", false).unwrap();
    assert_eq!((shape, w), (vec![3], vec![1.0, 0.5, 1.0]));
    let (shape, _) = read_array(&read("control_points.npy"), "p", false).unwrap();
    assert_eq!(shape, vec![3, 2]);
}

#[test]
fn npz_bezier_reads_back_as_the_same_curve_in_bspline_form() {
    let ctrl = Points::from_2d(&[[0.0, 0.0], [1.0, 2.0], [2.0, 0.0]]).unwrap();
    let bez = Object::Bezier(lekalo::BezierCurve::new(ctrl.clone()).unwrap());
    let back = read_npz_curve(&curve_to_npz(&bez).unwrap(), "b.npz").unwrap();
    let expect = BSplineCurve::new(2, vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0], ctrl).unwrap();
    assert_eq!(back, Object::BSpline(expect));
}

/// An archive of the given stored members.
fn archive(members: &[(&str, Vec<u8>)], method: CompressionMethod) -> Vec<u8> {
    let mut z = ZipWriter::new(Cursor::new(Vec::new()));
    let opts = SimpleFileOptions::default().compression_method(method);
    for (name, b) in members {
        z.start_file(*name, opts).unwrap();
        z.write_all(b).unwrap();
    }
    z.finish().unwrap().into_inner()
}

/// An archive with two members of one name (NumPy reads the last, the zip crate kept one of
/// them silently) is refused, naming the member, whichever it is and wherever the copies are.
#[test]
fn npz_members_of_one_name_are_refused() {
    let f8 = |v: &[f64]| -> Vec<u8> { v.iter().flat_map(|x| x.to_le_bytes()).collect() };
    let deg = |p: i64| write_npy("<i8", &[], &p.to_le_bytes()).unwrap();
    let knots = write_npy("<f8", &[4], &f8(&[0.0, 0.0, 1.0, 1.0])).unwrap();
    let ctrl = write_npy("<f8", &[2, 2], &f8(&[0.0, 0.0, 1.0, 1.0])).unwrap();
    // the zip writer refuses a repeated name: the second is written under a name of the same
    // length, then renamed in the bytes (the checksums cover the data, not the names)
    let renamed = |members: &[(&str, Vec<u8>)], from: &str, to: &str| {
        let mut b = archive(members, CompressionMethod::Stored);
        let (from, to) = (from.as_bytes(), to.as_bytes());
        let mut p = 0;
        while let Some(i) = b[p..].windows(from.len()).position(|w| w == from) {
            b[p + i..p + i + from.len()].copy_from_slice(to);
            p += i + from.len();
        }
        b
    };
    let two_degrees = renamed(
        &[
            ("degree.npy", deg(1)),
            ("knots.npy", knots.clone()),
            ("control_points.npy", ctrl.clone()),
            ("degreX.npy", deg(2)),
        ],
        "degreX.npy",
        "degree.npy",
    );
    let e = read_npz_curve(&two_degrees, "c.npz")
        .unwrap_err()
        .to_string();
    assert!(
        e.starts_with("c.npz: field `degree`: the archive has two members named degree.npy"),
        "{e}"
    );
    let two_knots = renamed(
        &[
            ("knots.npy", knots.clone()),
            ("degree.npy", deg(1)),
            ("knotX.npy", knots),
            ("control_points.npy", ctrl),
        ],
        "knotX.npy",
        "knots.npy",
    );
    let e = read_npz_curve(&two_knots, "c.npz").unwrap_err().to_string();
    assert!(e.contains("two members named knots.npy"), "{e}");
}

#[test]
fn npz_malformed_archives_give_named_errors() {
    let f8 = |v: &[f64]| -> Vec<u8> { v.iter().flat_map(|x| x.to_le_bytes()).collect() };
    let deg = |p: i64| write_npy("<i8", &[], &p.to_le_bytes()).unwrap();
    let knots = write_npy("<f8", &[4], &f8(&[0.0, 0.0, 1.0, 1.0])).unwrap();
    let ctrl = write_npy("<f8", &[2, 2], &f8(&[0.0, 0.0, 1.0, 1.0])).unwrap();
    let stored = CompressionMethod::Stored;
    let ok = archive(
        &[
            ("degree.npy", deg(1)),
            ("knots.npy", knots.clone()),
            ("control_points.npy", ctrl.clone()),
        ],
        stored,
    );
    assert!(
        read_npz_curve(&ok, "ok.npz").is_ok(),
        "the reference archive reads"
    );
    let cases: Vec<(&str, Vec<u8>, &str)> = vec![
        (
            "not zip",
            b"\x93NUMPY".to_vec(),
            "c.npz: not a NumPy .npz archive",
        ),
        (
            "no knots",
            archive(
                &[("degree.npy", deg(1)), ("control_points.npy", ctrl.clone())],
                stored,
            ),
            "c.npz: field `knots`: the archive has no member knots.npy",
        ),
        (
            "negative degree",
            archive(
                &[
                    ("degree.npy", deg(-1)),
                    ("knots.npy", knots.clone()),
                    ("control_points.npy", ctrl.clone()),
                ],
                stored,
            ),
            "c.npz: degree.npy: field `[]`: -1 is not a degree",
        ),
        (
            "float32 knots",
            archive(
                &[
                    ("degree.npy", deg(1)),
                    ("knots.npy", write_npy("<f4", &[4], &[0; 16]).unwrap()),
                    ("control_points.npy", ctrl.clone()),
                ],
                stored,
            ),
            "c.npz: knots.npy: field `descr`: dtype '<f4' is not float64",
        ),
        (
            "int64 control points",
            archive(
                &[
                    ("degree.npy", deg(1)),
                    ("knots.npy", knots.clone()),
                    (
                        "control_points.npy",
                        write_npy("<i8", &[2, 2], &[0; 32]).unwrap(),
                    ),
                ],
                stored,
            ),
            "c.npz: control_points.npy: field `descr`: dtype '<i8' is not float64",
        ),
        (
            "2-D knots",
            archive(
                &[
                    ("degree.npy", deg(1)),
                    (
                        "knots.npy",
                        write_npy("<f8", &[2, 2], &f8(&[0.0, 0.0, 1.0, 1.0])).unwrap(),
                    ),
                    ("control_points.npy", ctrl.clone()),
                ],
                stored,
            ),
            "c.npz: knots.npy: field `shape`: knots must be a 1-D array",
        ),
        (
            "truncated member",
            archive(
                &[
                    ("degree.npy", deg(1)),
                    ("knots.npy", knots[..knots.len() - 3].to_vec()),
                    ("control_points.npy", ctrl.clone()),
                ],
                stored,
            ),
            "c.npz: knots.npy: field `data`: the header's shape (4,) needs 32 bytes",
        ),
        (
            "wrong knot count",
            archive(
                &[
                    ("degree.npy", deg(2)),
                    ("knots.npy", knots.clone()),
                    ("control_points.npy", ctrl.clone()),
                ],
                stored,
            ),
            "c.npz: ",
        ),
    ];
    for (what, bytes, message) in cases {
        let e = read_npz_curve(&bytes, "c.npz").unwrap_err();
        assert!(e.to_string().starts_with(message), "{what}: {e}");
        assert!(e.is_bad_input(), "{what}");
    }
}

#[test]
fn npz_compressed_members_are_refused_with_the_fix() {
    let mut bytes = curve_to_npz(&bspline()).unwrap();
    // mark every member as deflated (method 8), as numpy.savez_compressed writes them: the
    // method field is at offset 8 of a local header (PK\x03\x04), 10 of a central one (PK\x01\x02)
    let mut patched = 0;
    for i in 0..bytes.len() - 4 {
        let at = match &bytes[i..i + 4] {
            b"PK\x03\x04" => i + 8,
            b"PK\x01\x02" => i + 10,
            _ => continue,
        };
        bytes[at..at + 2].copy_from_slice(&8u16.to_le_bytes());
        patched += 1;
    }
    assert_eq!(patched, 6, "3 local and 3 central headers");
    let e = read_npz_curve(&bytes, "z.npz").unwrap_err();
    let m = e.to_string();
    assert!(
        m.starts_with("z.npz: field `degree`: cannot read member degree.npy"),
        "{m}"
    );
    assert!(m.contains("numpy.savez (not savez_compressed)"), "{m}");
}

/// The archive made whole in memory, member by member: what the streamed writer must give.
fn archive_in_memory(obj: &Object) -> Vec<u8> {
    let (degree, knots, control, weights) = match obj {
        Object::Bezier(c) => {
            let p = c.degree();
            let knots = [vec![0.0; p + 1], vec![1.0; p + 1]].concat();
            (p, knots, c.control_points().clone(), None)
        }
        Object::BSpline(c) => (
            c.degree(),
            c.knots().as_slice().to_vec(),
            c.control_points().clone(),
            None,
        ),
        Object::Nurbs(c) => (
            c.degree(),
            c.knots().as_slice().to_vec(),
            c.control_points(),
            Some(c.weights()),
        ),
    };
    let degree = i64::try_from(degree).unwrap();
    let mut members = vec![
        (
            "degree.npy",
            write_npy("<i8", &[], &degree.to_le_bytes()).unwrap(),
        ),
        (
            "knots.npy",
            write_npy("<f8", &[knots.len()], &le_bytes(&knots)).unwrap(),
        ),
        (
            "control_points.npy",
            write_npy(
                "<f8",
                &[control.len(), control.dim()],
                &le_bytes(control.as_slice()),
            )
            .unwrap(),
        ),
    ];
    if let Some(w) = weights {
        members.push((
            "weights.npy",
            write_npy("<f8", &[w.len()], &le_bytes(&w)).unwrap(),
        ));
    }
    let mut z = ZipWriter::new(Cursor::new(Vec::new()));
    let opts = SimpleFileOptions::default()
        .compression_method(CompressionMethod::Stored)
        .large_file(false);
    for (name, bytes) in members {
        z.start_file(name, opts).unwrap();
        z.write_all(&bytes).unwrap();
    }
    z.finish().unwrap().into_inner()
}

#[test]
fn streamed_archive_is_the_archive_made_in_memory() {
    // a curve long enough that its arrays are written in several chunks
    let n = 20_000;
    let pts: Vec<[f64; 3]> = (0..n)
        .map(|i| {
            let t = f64::from(i) * 1e-3;
            [t.cos(), t.sin(), t / 7.0]
        })
        .collect();
    let ctrl = Points::from_3d(&pts).unwrap();
    let mut knots = vec![0.0; 4];
    knots.extend((1..n - 3).map(f64::from));
    knots.extend([f64::from(n - 3); 4]);
    let long = Object::BSpline(BSplineCurve::new(3, knots, ctrl).unwrap());
    let bezier = Object::Bezier(
        lekalo::BezierCurve::new(Points::from_2d(&[[0.0, 0.0], [1.0, 2.0], [3.0, 1.0]]).unwrap())
            .unwrap(),
    );
    for obj in [bspline(), nurbs(), long, bezier] {
        let want = archive_in_memory(&obj);
        assert_eq!(curve_to_npz(&obj).unwrap(), want, "{}", obj.type_name());
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("c.npz");
        crate::write_atomic_seek(&path, &[], crate::WriteOptions::default(), |w| {
            write_npz_curve(&obj, w)
        })
        .unwrap();
        assert_eq!(std::fs::read(&path).unwrap(), want, "{}", obj.type_name());
    }
}
