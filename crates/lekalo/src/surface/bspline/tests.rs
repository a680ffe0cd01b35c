use super::*;

pub(super) fn bilinear() -> BSplineSurface {
    let net = Points::from_3d(&[
        [0.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [1.0, 0.0, 0.0],
        [1.0, 1.0, 1.0],
    ])
    .unwrap();
    BSplineSurface::new(
        1,
        1,
        vec![0.0, 0.0, 1.0, 1.0],
        vec![0.0, 0.0, 1.0, 1.0],
        net,
        (2, 2),
    )
    .unwrap()
}

/// Degrees (3, 2), non-uniform knots with an interior double knot in u, 6 × 5 net in 3-D.
fn general() -> BSplineSurface {
    let (nu, nv) = (6, 5);
    let data: Vec<f64> = (0..90_u32)
        .map(|k| (0.37 * f64::from(k)).sin() + 0.1 * f64::from(k % 7))
        .collect();
    BSplineSurface::new(
        3,
        2,
        vec![0.0, 0.0, 0.0, 0.0, 0.3, 0.3, 1.0, 1.0, 1.0, 1.0],
        vec![-1.0, -1.0, -1.0, 0.5, 1.5, 2.0, 2.0, 2.0],
        Points::from_flat(3, data).unwrap(),
        (nu, nv),
    )
    .unwrap()
}

/// Golden: the bilinear patch through (0,0,0), (0,1,0), (1,0,0), (1,1,1) is (u, v, uv), with
/// normal (−v, −u, 1)/√(1 + u² + v²).
#[test]
fn bilinear_patch_closed_form() {
    let s = bilinear();
    for a in 0..=10 {
        for b in 0..=10 {
            let (u, v) = (f64::from(a) / 10.0, f64::from(b) / 10.0);
            let p = s.eval(u, v).unwrap();
            assert!(
                (p[0] - u).abs() < 1e-15 && (p[1] - v).abs() < 1e-15,
                "({u},{v})"
            );
            assert!((p[2] - u * v).abs() < 1e-15, "z at ({u},{v})");
            let n = s.normal(u, v).unwrap();
            let len = (1.0 + u * u + v * v).sqrt();
            let want = [-v / len, -u / len, 1.0 / len];
            for k in 0..3 {
                assert!((n[k] - want[k]).abs() < 1e-15, "normal at ({u},{v})");
            }
            let d = s.eval_derivatives(u, v, 2).unwrap();
            // S_uu = S_vv = 0, S_uv = (0,0,1), S_uuv... = 0
            assert_eq!(d.point(6), &[0.0; 3], "S_uu");
            assert_eq!(d.point(2), &[0.0; 3], "S_vv");
            assert!((d.point(4)[2] - 1.0).abs() < 1e-15, "S_uv");
        }
    }
}

#[test]
fn accessors() {
    let s = general();
    assert_eq!((s.degree_u(), s.degree_v()), (3, 2));
    assert_eq!(s.net_size(), (6, 5));
    assert_eq!(s.domain(), ((0.0, 1.0), (-1.0, 2.0)));
    assert_eq!(s.dim(), 3);
    assert_eq!(s.control_point(1, 2), Some(s.control_points().point(7)));
    assert_eq!(s.control_point(6, 0), None);
    assert_eq!(s.control_point(0, 5), None);
    assert!(matches!(
        s.eval_into(0.5, 0.5, &mut [0.0; 2]),
        Err(Error::LengthMismatch { .. })
    ));
}

#[test]
fn constructor_errors_name_the_direction() {
    let net = Points::from_flat(1, vec![0.0; 6]).unwrap();
    let k2 = vec![0.0, 0.0, 1.0, 1.0];
    let k3 = vec![0.0, 0.0, 0.5, 1.0, 1.0];
    // 6 points is 2 × 3, not 2 × 2
    assert!(matches!(
        BSplineSurface::new(1, 1, k2.clone(), k2.clone(), net.clone(), (2, 2)),
        Err(Error::LengthMismatch {
            expected: 4,
            got: 6,
            ..
        })
    ));
    assert!(matches!(
        BSplineSurface::new(1, 1, k2.clone(), k3.clone(), net.clone(), (0, 3)),
        Err(Error::TooFew { .. })
    ));
    assert!(matches!(
        BSplineSurface::new(1, 1, k2.clone(), k3.clone(), net.clone(), (usize::MAX, 3)),
        Err(Error::TooLarge { .. })
    ));
    // knots_v has 4 knots but 3 + 1 + 1 = 5 are needed
    let e = BSplineSurface::new(1, 1, k2.clone(), k2.clone(), net.clone(), (2, 3)).unwrap_err();
    assert!(
        matches!(
            e,
            Error::LengthMismatch { what, expected: 5, got: 4 } if what.words().starts_with("knots in v")
        ),
        "{e}"
    );
    let e = BSplineSurface::new(1, 1, k3.clone(), k3.clone(), net.clone(), (2, 3)).unwrap_err();
    assert!(
        matches!(e, Error::LengthMismatch { what, .. } if what.words().starts_with("knots in u")),
        "{e}"
    );
    // degree 2 in u with 2 rows
    let e = BSplineSurface::new(
        2,
        1,
        vec![0.0, 0.0, 0.0, 1.0, 1.0],
        k3.clone(),
        net.clone(),
        (2, 3),
    )
    .unwrap_err();
    assert!(
        matches!(&e, Error::Degree { degree: 2, reason } if reason.contains("u direction")),
        "{e}"
    );
    assert!(matches!(
        BSplineSurface::new(1, 1, vec![0.0, 0.0, f64::NAN, 1.0], k3.clone(), net.clone(), (2, 3)),
        Err(Error::NonFinite { what, .. }) if what.words() == "knots_u"
    ));
    assert!(matches!(
        BSplineSurface::new(1, 1, k2.clone(), vec![0.0], net.clone(), (2, 3)),
        Err(Error::TooFew { what, .. }) if what.words() == "knots_v"
    ));
    assert!(matches!(
        BSplineSurface::new(
            1,
            1,
            k2.clone(),
            vec![0.0, 0.0, 1.0, 0.5, 1.0],
            net.clone(),
            (2, 3)
        ),
        Err(Error::KnotsNotSorted { .. })
    ));
    assert!(matches!(
        BSplineSurface::new(
            1,
            1,
            k2.clone(),
            vec![0.0, 0.5, 0.5, 0.5, 1.0],
            net.clone(),
            (2, 3)
        ),
        Err(Error::KnotMultiplicity { .. })
    ));
    assert!(matches!(
        BSplineSurface::new(1, 2, k2, vec![0.0, 1.0, 1.0, 1.0, 2.0, 2.0], net, (2, 3)),
        Err(Error::EmptyDomain { .. })
    ));
}

#[test]
fn serde_goes_through_validation() {
    // dyadic coordinates: serde_json (without its `float_roundtrip` feature) may change the
    // last bit of other decimals
    let g = general();
    let data: Vec<f64> = g
        .control_points()
        .iter()
        .flatten()
        .map(|x| (x * 64.0).round() / 64.0)
        .collect();
    let s = BSplineSurface::new(
        3,
        2,
        g.knots_u().as_slice().to_vec(),
        g.knots_v().as_slice().to_vec(),
        Points::from_flat(3, data).unwrap(),
        (6, 5),
    )
    .unwrap();
    let json = serde_json::to_string(&s).unwrap();
    let back: BSplineSurface = serde_json::from_str(&json).unwrap();
    assert_eq!(back, s);
    let bad = json.replace("\"net_size\":[6,5]", "\"net_size\":[5,6]");
    assert_ne!(bad, json, "the replacement must hit");
    let e = serde_json::from_str::<BSplineSurface>(&bad).unwrap_err();
    assert!(e.to_string().contains("knots in u"), "{e}");
}
