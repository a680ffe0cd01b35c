//! Tests of the `.npy` reader and writer. The fixtures are built byte by byte here, laid out
//! as numpy's `np.save` lays them out (magic, version, little-endian header length, a dict
//! literal padded with spaces to 64 bytes and ending in `\n`, then the data).

use super::*;

/// A `.npy` file of `version` with the header dict `dict` and the raw `data`.
fn fixture(version: u8, dict: &str, data: &[u8]) -> Vec<u8> {
    let prefix = if version == 1 { 10 } else { 12 };
    let mut header = dict.to_string();
    let unpadded = prefix + header.len() + 1;
    header.push_str(&" ".repeat((64 - unpadded % 64) % 64));
    header.push('\n');
    let mut out = b"\x93NUMPY".to_vec();
    out.extend_from_slice(&[version, 0]);
    if version == 1 {
        out.extend_from_slice(&u16::try_from(header.len()).unwrap().to_le_bytes());
    } else {
        out.extend_from_slice(&u32::try_from(header.len()).unwrap().to_le_bytes());
    }
    out.extend_from_slice(header.as_bytes());
    out.extend_from_slice(data);
    out
}

fn le(values: &[f64]) -> Vec<u8> {
    values.iter().flat_map(|v| v.to_le_bytes()).collect()
}

fn be(values: &[f64]) -> Vec<u8> {
    values.iter().flat_map(|v| v.to_be_bytes()).collect()
}

/// The points (0, 10), (1, 11), (2, 12) in row-major order.
const ROWS: [f64; 6] = [0.0, 10.0, 1.0, 11.0, 2.0, 12.0];
/// The same points column by column (Fortran order).
const COLS: [f64; 6] = [0.0, 1.0, 2.0, 10.0, 11.0, 12.0];

fn syntax_field(e: &IoError) -> (String, Option<String>) {
    match e {
        IoError::Syntax { at, .. } => (at.source.clone(), at.field.clone()),
        other => panic!("expected a syntax error, got {other:?}"),
    }
}

#[test]
fn npy_reads_every_layout_to_the_same_points() {
    let c = "{'descr': '<f8', 'fortran_order': False, 'shape': (3, 2), }";
    let f = "{'descr': '<f8', 'fortran_order': True, 'shape': (3, 2), }";
    let c_be = "{'descr': '>f8', 'fortran_order': False, 'shape': (3, 2), }";
    let f_be = "{'descr': '>f8', 'fortran_order': True, 'shape': (3, 2), }";
    let files = [
        fixture(1, c, &le(&ROWS)),
        fixture(2, c, &le(&ROWS)),
        fixture(3, c, &le(&ROWS)),
        fixture(1, f, &le(&COLS)),
        fixture(1, c_be, &be(&ROWS)),
        fixture(1, f_be, &be(&COLS)),
        // keys in another order, double quotes, no trailing comma
        fixture(
            1,
            "{\"shape\": (3,2), \"fortran_order\": False, \"descr\": \"<f8\"}",
            &le(&ROWS),
        ),
    ];
    for (k, bytes) in files.iter().enumerate() {
        let p = read_npy_points(bytes, "p.npy").unwrap();
        assert_eq!(p.dim(), 2, "file {k}");
        assert_eq!(p.as_slice(), &ROWS, "file {k}");
    }
}

#[test]
fn npy_one_dimensional_array_is_points_of_dimension_one() {
    let b = fixture(
        1,
        "{'descr': '<f8', 'fortran_order': False, 'shape': (3,), }",
        &le(&[1.0, 2.0, 4.0]),
    );
    let p = read_npy_points(&b, "v.npy").unwrap();
    assert_eq!((p.len(), p.dim()), (3, 1), "3 points of dimension 1");
    assert_eq!(p.as_slice(), &[1.0, 2.0, 4.0]);
}

#[test]
fn npy_round_trip_is_bit_exact() {
    let values = [
        0.1,
        -0.0,
        f64::MIN_POSITIVE,
        5e-324,
        f64::MAX,
        -1.0 / 3.0,
        std::f64::consts::PI,
        1e300,
        -2.5e-17,
    ];
    let b = npy_bytes(3, 3, &values).unwrap();
    assert_eq!((b.len() - 9 * 8) % 64, 0, "header padded to 64 bytes");
    assert_eq!(
        b,
        fixture(
            1,
            "{'descr': '<f8', 'fortran_order': False, 'shape': (3, 3), }",
            &le(&values)
        ),
        "the writer lays the file out as np.save does"
    );
    let p = read_npy_points(&b, "r.npy").unwrap();
    let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    assert_eq!(bits(p.as_slice()), bits(&values));
}

#[test]
fn sample_table_to_npy_keeps_columns_and_marks_undefined_as_nan() {
    let t = SampleTable {
        header: vec!["t".into(), "x".into(), "curvature".into()],
        rows: vec![
            vec![Some(0.0), Some(1.5), None],
            vec![Some(1.0), Some(2.0), Some(0.25)],
        ],
    };
    let b = t.to_npy().unwrap();
    let header_len = usize::from(u16::from_le_bytes([b[8], b[9]]));
    let data: Vec<f64> = b[10 + header_len..]
        .chunks_exact(8)
        .map(|c| f64::from_le_bytes(c.try_into().unwrap()))
        .collect();
    assert_eq!(&data[..2], &[0.0, 1.5]);
    assert!(data[2].is_nan(), "undefined curvature is NaN");
    assert_eq!(&data[3..], &[1.0, 2.0, 0.25]);
    assert!(std::str::from_utf8(&b[10..10 + header_len])
        .unwrap()
        .contains("'shape': (2, 3)"));
}

#[test]
fn npy_malformed_files_give_named_errors() {
    let good = fixture(
        1,
        "{'descr': '<f8', 'fortran_order': False, 'shape': (3, 2), }",
        &le(&ROWS),
    );
    let dict = |descr: &str, shape: &str| {
        format!("{{'descr': {descr}, 'fortran_order': False, 'shape': {shape}, }}")
    };
    let cases: Vec<(&str, Vec<u8>, &str, &str)> = vec![
        (
            "bad magic",
            b"x,y\n0,0\n".to_vec(),
            "magic",
            "not a NumPy .npy file",
        ),
        ("empty", Vec::new(), "magic", "not a NumPy"),
        (
            "no version",
            good[..7].to_vec(),
            "version",
            "ends inside the header",
        ),
        (
            "version 4",
            {
                let mut b = good.clone();
                b[6] = 4;
                b
            },
            "version",
            "4.0 is not supported",
        ),
        (
            "no length",
            good[..9].to_vec(),
            "header",
            "no header length",
        ),
        (
            "truncated header",
            good[..40].to_vec(),
            "header",
            "the file is truncated",
        ),
        (
            "int32",
            fixture(1, &dict("'<i4'", "(3, 2)"), &[0; 24]),
            "descr",
            "'<i4' is not float64",
        ),
        (
            "float32",
            fixture(1, &dict("'<f4'", "(3, 2)"), &[0; 24]),
            "descr",
            "'<f4' is not float64",
        ),
        (
            "object",
            fixture(1, &dict("'|O'", "(3, 2)"), &[0; 48]),
            "descr",
            "'|O' is not float64",
        ),
        (
            "structured",
            fixture(1, &dict("[('x', '<f8'), ('y', '<f8')]", "(3,)"), &le(&ROWS)),
            "descr",
            "[('x', '<f8'), ('y', '<f8')] is not float64",
        ),
        (
            "3-D",
            fixture(1, &dict("'<f8'", "(3, 1, 2)"), &le(&ROWS)),
            "shape",
            "(3, 1, 2) is not (n, d)",
        ),
        (
            "scalar",
            fixture(1, &dict("'<f8'", "()"), &le(&[1.0])),
            "shape",
            "() is not (n, d)",
        ),
        (
            "no rows",
            fixture(1, &dict("'<f8'", "(0, 2)"), &[]),
            "shape",
            "holds no points",
        ),
        (
            "short data",
            fixture(1, &dict("'<f8'", "(3, 2)"), &le(&ROWS[..5])),
            "data",
            "needs 48 bytes of float64 data, the file has 40",
        ),
        (
            "long data",
            fixture(1, &dict("'<f8'", "(2, 2)"), &le(&ROWS)),
            "data",
            "needs 32 bytes",
        ),
        (
            "NaN",
            fixture(
                1,
                &dict("'<f8'", "(3, 2)"),
                &le(&[0.0, 1.0, 2.0, f64::NAN, 4.0, 5.0]),
            ),
            "[1, 1]",
            "NaN is not finite",
        ),
        (
            "inf",
            fixture(
                1,
                &dict("'>f8'", "(3, 2)"),
                &be(&[0.0, 1.0, 2.0, 3.0, f64::NEG_INFINITY, 5.0]),
            ),
            "[2, 0]",
            "-inf is not finite",
        ),
        (
            "no shape",
            fixture(1, "{'descr': '<f8', 'fortran_order': False}", &le(&ROWS)),
            "shape",
            "no 'shape' entry",
        ),
        (
            "fortran not bool",
            fixture(
                1,
                "{'descr': '<f8', 'fortran_order': 0, 'shape': (3, 2)}",
                &le(&ROWS),
            ),
            "fortran_order",
            "0 is not True or False",
        ),
        (
            "not a dict",
            fixture(1, "descr <f8", &le(&ROWS)),
            "header",
            "not a dict literal",
        ),
        (
            "garbage in dict",
            fixture(1, "{'descr': '<f8' 'shape': (3, 2)}", &le(&ROWS)),
            "header",
            "expected ','",
        ),
        // lying headers: never unpickled, never allocated from the header's word
        (
            "object array holding a pickle",
            fixture(
                1,
                &dict("'|O'", "(3, 2)"),
                b"\x80\x04\x95cos\nsystem\n(S'rm -rf ~'\ntR.",
            ),
            "descr",
            "'|O' is not float64",
        ),
        (
            "a billion rows on 48 bytes",
            fixture(1, &dict("'<f8'", "(1000000000, 2)"), &le(&ROWS)),
            "data",
            "needs 16000000000 bytes of float64 data, the file has 48",
        ),
        (
            "a shape whose product overflows",
            fixture(1, &dict("'<f8'", "(4611686018427387904, 4)"), &le(&ROWS)),
            "shape",
            "is too large to address",
        ),
        (
            "a negative size",
            fixture(1, &dict("'<f8'", "(-3, 2)"), &le(&ROWS)),
            "header",
            "cannot read the value of 'shape'",
        ),
        (
            "5000 nested parentheses",
            fixture(
                1,
                &dict(
                    "'<f8'",
                    &format!("{}3, 2{}", "(".repeat(5000), ")".repeat(5000)),
                ),
                &le(&ROWS),
            ),
            "header",
            "cannot read the value of 'shape'",
        ),
        (
            "a version 2 header length of 4 GiB",
            {
                let mut b = fixture(2, &dict("'<f8'", "(3, 2)"), &le(&ROWS));
                b[8..12].copy_from_slice(&0xFFFF_FFF0u32.to_le_bytes());
                b
            },
            "header",
            "4294967280 bytes long but the file ends",
        ),
    ];
    for (what, bytes, field, message) in cases {
        let e = read_npy_points(&bytes, "bad.npy").unwrap_err();
        let (source, got_field) = syntax_field(&e);
        assert_eq!(source, "bad.npy", "{what}: the file is named");
        assert_eq!(got_field.as_deref(), Some(field), "{what}: {e}");
        assert!(e.to_string().contains(message), "{what}: {e}");
    }
}

#[test]
fn npy_repeated_header_key_is_refused_by_name() {
    // Python keeps the last of repeated keys; reading the first would give another array than
    // NumPy's, so neither is taken
    for dict in [
        "{'descr': '<f8', 'fortran_order': False, 'shape': (3, 2), 'shape': (2, 3), }",
        "{'descr': '>f8', 'descr': '<f8', 'fortran_order': False, 'shape': (3, 2), }",
    ] {
        let e = read_npy_points(&fixture(1, dict, &le(&ROWS)), "twice.npy").unwrap_err();
        assert_eq!(
            syntax_field(&e),
            ("twice.npy".to_string(), Some("header".to_string())),
            "{e}"
        );
        assert!(e.to_string().contains("appears twice"), "{e}");
    }
}

#[test]
fn npy_writer_rejects_a_wrong_count() {
    assert!(
        matches!(npy_bytes(2, 2, &[1.0]), Err(IoError::Unsupported { .. })),
        "3 numbers short"
    );
}

#[test]
fn npy_file_errors_name_the_path() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("missing.npy");
    let e = read_npy_file(&path).unwrap_err();
    assert!(matches!(e, IoError::Read { .. }), "{e:?}");
    let path = dir.path().join("p.npy");
    std::fs::write(&path, npy_bytes(3, 2, &ROWS).unwrap()).unwrap();
    let (p, name) = read_npy_file(&path).unwrap();
    assert_eq!(p.as_slice(), &ROWS);
    assert!(name.ends_with("p.npy"), "{name}");
}

/// A file read piece by piece gives what its bytes read whole give: points or the same error,
/// for data spread over many pieces (a piece boundary inside an element), either endianness and
/// order, a header longer than the first piece, and files cut short or too long.
#[test]
fn npy_file_read_in_pieces_is_the_file_read_whole() {
    let n: usize = 30_001; // 30_001 × 3 × 8 bytes: many pieces, the first ending inside an element
    let values: Vec<f64> = (0..3 * 30_001u32)
        .map(|i| f64::from(i) * 0.37 - 5.0)
        .collect();
    let long_dict = format!(
        "{{'descr': '<f8', 'fortran_order': False, 'shape': ({n}, 3), }}{}",
        " ".repeat(70_000)
    );
    let bad = {
        let mut v = values.clone();
        v[3 * n - 2] = f64::NAN;
        v
    };
    let files = [
        npy_bytes(n, 3, &values).unwrap(),
        fixture(
            1,
            &format!("{{'descr': '<f8', 'fortran_order': False, 'shape': ({n}, 3), }}"),
            &le(&values),
        ),
        fixture(
            2,
            &format!("{{'descr': '>f8', 'fortran_order': True, 'shape': ({n}, 3), }}"),
            &be(&values),
        ),
        fixture(3, &long_dict, &le(&values)),
        fixture(
            1,
            &format!("{{'descr': '<f8', 'fortran_order': False, 'shape': ({n}, 3), }}"),
            &le(&bad),
        ),
        fixture(
            1,
            &format!("{{'descr': '<f8', 'fortran_order': False, 'shape': ({n}, 3), }}"),
            &le(&values[1..]),
        ),
        fixture(
            1,
            &format!("{{'descr': '<f8', 'fortran_order': False, 'shape': ({n}, 3), }}"),
            &le(&[values.as_slice(), &[1.0]].concat()),
        ),
        b"\x93NUMPY\x09\x00".to_vec(),
    ];
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("p.npy");
    for (k, bytes) in files.iter().enumerate() {
        std::fs::write(&path, bytes).unwrap();
        let name = path.display().to_string();
        let whole = read_npy_points(bytes, &name).map_err(|e| e.to_string());
        let pieces = read_npy_file(&path)
            .map(|(p, _)| p)
            .map_err(|e| e.to_string());
        assert_eq!(pieces, whole, "file {k}");
        assert_eq!(whole.is_ok(), k < 4, "file {k}: {whole:?}");
    }
}
