//! Tests of the `.npz` archive of tensor splines: round trips bit for bit and named errors.

use super::*;
use crate::tensor_type_name;
use zip::ZipArchive;

/// A B-spline in `n` parameters of degrees 2, 1, 3, 1, … with `dim`-valued control points
/// whose coordinates are not exact in binary.
fn bspline(n: usize, dim: usize) -> TensorBSpline {
    let mut degrees = Vec::new();
    let mut knots = Vec::new();
    let mut count = 1;
    for d in 0..n {
        let p = [2, 1, 3, 1][d % 4];
        let mut k = vec![0.0; p + 1];
        k.push(0.3 + 0.1 / (d as f64 + 3.0));
        k.extend(vec![1.0; p + 1]);
        count *= k.len() - p - 1;
        degrees.push(p);
        knots.push(k);
    }
    let flat: Vec<f64> = (0..count * dim)
        .map(|i| (i as f64 + 0.1).sqrt() / 3.0 - 1e-300 * (i % 2) as f64)
        .collect();
    TensorBSpline::new(degrees, knots, Points::from_flat(dim, flat).unwrap()).unwrap()
}

/// A NURBS with weights and coordinates exact in binary, so `w·P / w` gives `P` back exactly.
fn nurbs(n: usize, dim: usize) -> TensorNurbs {
    let b = bspline(n, dim);
    let count = b.control_points().len();
    let flat: Vec<f64> = (0..count * dim).map(|i| (i % 7) as f64 * 0.25).collect();
    let w: Vec<f64> = (0..count).map(|i| [1.0, 0.5, 2.0, 0.75][i % 4]).collect();
    TensorNurbs::new(
        b.degrees().to_vec(),
        b.knots().iter().map(|k| k.as_slice().to_vec()).collect(),
        Points::from_flat(dim, flat).unwrap(),
        &w,
    )
    .unwrap()
}

fn all() -> Vec<Tensor> {
    let mut v = Vec::new();
    for n in [3, 4] {
        for dim in [1, 3] {
            v.push(Tensor::BSpline(bspline(n, dim)));
            v.push(Tensor::Nurbs(nurbs(n, dim)));
        }
    }
    v
}

/// The archive of members `(name, .npy bytes)`, stored uncompressed.
fn archive(members: &[(&str, Vec<u8>)]) -> Vec<u8> {
    let mut z = ZipWriter::new(Cursor::new(Vec::new()));
    let opts = SimpleFileOptions::default().compression_method(CompressionMethod::Stored);
    for (name, b) in members {
        z.start_file(*name, opts).unwrap();
        z.write_all(b).unwrap();
    }
    z.finish().unwrap().into_inner()
}

fn members_of(bytes: &[u8]) -> Vec<(String, Vec<u8>)> {
    use std::io::Read;
    let mut z = ZipArchive::new(Cursor::new(bytes)).unwrap();
    let names: Vec<String> = z.file_names().map(String::from).collect();
    names
        .into_iter()
        .map(|n| {
            let mut b = Vec::new();
            z.by_name(&n).unwrap().read_to_end(&mut b).unwrap();
            (n, b)
        })
        .collect()
}

/// `members` with `name` replaced by `b` (or removed for `None`).
fn with(members: &[(String, Vec<u8>)], name: &str, b: Option<Vec<u8>>) -> Vec<u8> {
    let list: Vec<(&str, Vec<u8>)> = members
        .iter()
        .filter_map(|(n, old)| {
            if n == name {
                b.clone().map(|b| (n.as_str(), b))
            } else {
                Some((n.as_str(), old.clone()))
            }
        })
        .collect();
    archive(&list)
}

fn f8(shape: &[usize], v: &[f64]) -> Vec<u8> {
    let mut b = npy_header("<f8", shape).unwrap();
    v.iter().for_each(|x| b.extend_from_slice(&x.to_le_bytes()));
    b
}

fn i8s(shape: &[usize], v: &[i64]) -> Vec<u8> {
    let mut b = npy_header("<i8", shape).unwrap();
    v.iter().for_each(|x| b.extend_from_slice(&x.to_le_bytes()));
    b
}

#[test]
fn tensor_npz_round_trips_are_bit_exact() {
    for t in all() {
        let bytes = tensor_to_npz(&t).unwrap();
        let back = read_npz_tensor(&bytes, "t.npz").unwrap();
        assert_eq!(
            back,
            t,
            "{} N={} dim={}",
            tensor_type_name(&t),
            t.n_vars(),
            t.dim()
        );
        for (a, b) in back
            .control_points()
            .as_slice()
            .iter()
            .zip(t.control_points().as_slice())
        {
            assert_eq!(a.to_bits(), b.to_bits());
        }
        assert_eq!(tensor_to_npz(&back).unwrap(), bytes, "reproducible");
        let Shape::Tensor(s) = read_npz(&bytes, "t.npz").unwrap() else {
            panic!("read_npz gives the tensor");
        };
        assert_eq!(s, t);
    }
}

#[test]
fn tensor_npz_members_have_scipy_shapes() {
    let t = Tensor::Nurbs(nurbs(3, 2));
    let m = members_of(&tensor_to_npz(&t).unwrap());
    let mut names: Vec<&str> = m.iter().map(|(n, _)| n.as_str()).collect();
    names.sort_unstable();
    assert_eq!(
        names,
        [
            "control_points.npy",
            "degrees.npy",
            "knots_0.npy",
            "knots_1.npy",
            "knots_2.npy",
            "weights.npy"
        ]
    );
    let get = |n: &str| &m.iter().find(|(k, _)| k == n).unwrap().1;
    let net = t.shape().to_vec();
    let mut with_dim = net.clone();
    with_dim.push(2);
    assert_eq!(
        read_array_shape(get("control_points.npy"), "c", false).unwrap(),
        with_dim
    );
    assert_eq!(
        read_array_shape(get("weights.npy"), "w", false).unwrap(),
        net
    );
    assert_eq!(
        read_array(get("degrees.npy"), "d", true).unwrap(),
        (vec![3], vec![2.0, 1.0, 3.0])
    );
    let scalar = members_of(&tensor_to_npz(&Tensor::BSpline(bspline(3, 1))).unwrap());
    let c = &scalar
        .iter()
        .find(|(k, _)| k == "control_points.npy")
        .unwrap()
        .1;
    assert_eq!(
        read_array_shape(c, "c", false).unwrap(),
        net,
        "scalar values: no trailing axis"
    );
}

/// The message of a refused archive, which must be a syntax error naming `field`.
fn refused(bytes: &[u8], field: &str) -> String {
    let e = read_npz_tensor(bytes, "t.npz").unwrap_err();
    let text = e.to_string();
    assert!(
        matches!(e, IoError::Syntax { .. } | IoError::Invalid { .. }) && text.contains(field),
        "{field}: {text}"
    );
    text
}

#[test]
fn hostile_tensor_archives_are_refused_by_name() {
    let t = Tensor::Nurbs(nurbs(3, 2));
    let m = members_of(&tensor_to_npz(&t).unwrap());
    let net = t.shape().to_vec();
    // missing members
    for name in ["degrees", "knots_1", "control_points"] {
        let text = refused(&with(&m, &format!("{name}.npy"), None), name);
        assert!(text.contains("no member"), "{text}");
    }
    // degrees: not 1-D, empty, negative, fractional
    refused(&with(&m, "degrees.npy", Some(f8(&[], &[2.0]))), "degrees");
    refused(&with(&m, "degrees.npy", Some(f8(&[0], &[]))), "degrees");
    refused(
        &with(&m, "degrees.npy", Some(f8(&[3], &[2.0, -1.0, 3.0]))),
        "degree",
    );
    refused(
        &with(&m, "degrees.npy", Some(f8(&[3], &[2.0, 1.5, 3.0]))),
        "degree",
    );
    // more degrees than knot members
    let text = refused(
        &with(&m, "degrees.npy", Some(f8(&[4], &[2.0, 1.0, 3.0, 1.0]))),
        "knots_3",
    );
    assert!(text.contains("no member"), "{text}");
    // knots: 2-D, too short for the degree
    refused(
        &with(&m, "knots_0.npy", Some(f8(&[2, 2], &[0.0, 0.0, 1.0, 1.0]))),
        "knots_0",
    );
    refused(
        &with(&m, "knots_2.npy", Some(f8(&[3], &[0.0, 0.5, 1.0]))),
        "knots_2",
    );
    // control points of the wrong net, dimension 0, transposed
    refused(
        &with(&m, "control_points.npy", Some(f8(&[2, 2], &[0.0; 4]))),
        "control_points",
    );
    let mut zero_dim = net.clone();
    zero_dim.push(0);
    refused(
        &with(&m, "control_points.npy", Some(f8(&zero_dim, &[]))),
        "control_points",
    );
    let mut rev: Vec<usize> = net.iter().rev().copied().collect();
    rev.push(2);
    if rev[..3] != net[..] {
        let n: usize = rev.iter().product();
        refused(
            &with(&m, "control_points.npy", Some(f8(&rev, &vec![0.0; n]))),
            "control_points",
        );
    }
    // a huge declared shape with few bytes: refused from the header, nothing reserved
    let mut huge = npy_header("<f8", &[1 << 40, 1 << 20, 1 << 3, 2]).unwrap();
    huge.extend_from_slice(&[0; 64]);
    refused(
        &with(&m, "control_points.npy", Some(huge.clone())),
        "control_points",
    );
    refused(&with(&m, "weights.npy", Some(huge)), "weights");
    let mut huge_degrees = npy_header("<i8", &[1 << 50]).unwrap();
    huge_degrees.extend_from_slice(&[0; 16]);
    refused(&with(&m, "degrees.npy", Some(huge_degrees)), "degrees");
    // weights of the wrong shape, non-positive, integer dtype of control points
    refused(
        &with(&m, "weights.npy", Some(f8(&[2], &[1.0, 1.0]))),
        "weights",
    );
    let n: usize = net.iter().product();
    refused(
        &with(&m, "weights.npy", Some(f8(&net, &vec![-1.0; n]))),
        "weights",
    );
    let mut int_shape = net.clone();
    int_shape.push(2);
    let ints = i8s(&int_shape, &vec![1; 2 * n]);
    refused(
        &with(&m, "control_points.npy", Some(ints)),
        "control_points",
    );
    // not a zip; a repeated member
    assert!(read_npz_tensor(b"PK no zip", "t.npz").is_err());
    let mut list: Vec<(&str, Vec<u8>)> = m.iter().map(|(n, b)| (n.as_str(), b.clone())).collect();
    list.push(("degrees.npy", f8(&[3], &[1.0, 1.0, 1.0])));
    let mut z = ZipWriter::new(Cursor::new(Vec::new()));
    let opts = SimpleFileOptions::default().compression_method(CompressionMethod::Stored);
    for (name, b) in &list {
        // the zip crate refuses a repeated name; build it under another name of equal length
        let name = if std::ptr::eq(*name, list.last().unwrap().0) {
            "degreez.npy"
        } else {
            name
        };
        z.start_file(name, opts).unwrap();
        z.write_all(b).unwrap();
    }
    let mut bytes = z.finish().unwrap().into_inner();
    let at = bytes
        .windows(11)
        .rposition(|w| w == b"degreez.npy")
        .unwrap();
    bytes[at..at + 11].copy_from_slice(b"degrees.npy");
    refused(&bytes, "degrees");
}

#[test]
fn read_npz_tells_curves_from_tensors() {
    use crate::CurveJson;
    let obj = crate::Object::from_json_str(
        r#"{"lekalo":1,"type":"bspline_curve","degree":1,"knots":[0,0,1,1],"control":[[0,0],[1,2]]}"#,
        "c.json",
    )
    .unwrap();
    let bytes = crate::curve_to_npz(&obj).unwrap();
    assert!(matches!(read_npz(&bytes, "c.npz").unwrap(), Shape::Curve(o) if o == obj));
    assert!(read_npz_tensor(&bytes, "c.npz")
        .unwrap_err()
        .to_string()
        .contains("degrees"));
}
