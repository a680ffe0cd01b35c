use super::*;

#[test]
fn new_rejects_each_bad_input() {
    assert!(matches!(
        KnotVector::new(vec![0.0]),
        Err(Error::TooFew { .. })
    ));
    assert!(matches!(
        KnotVector::new(vec![0.0, f64::NAN]),
        Err(Error::NonFinite { .. })
    ));
    assert!(matches!(
        KnotVector::new(vec![0.0, 2.0, 1.0]),
        Err(Error::KnotsNotSorted { index: 2, .. })
    ));
    assert!(matches!(
        KnotVector::new(vec![1.0, 1.0]),
        Err(Error::EmptyDomain { .. })
    ));
}

#[test]
fn validate_for_checks_counts_and_multiplicity() {
    let kv = KnotVector::new(vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0]).unwrap();
    assert_eq!(kv.validate_for(2, 3), Ok(()));
    assert!(matches!(
        kv.validate_for(2, 4),
        Err(Error::LengthMismatch { .. })
    ));
    assert!(matches!(kv.validate_for(3, 3), Err(Error::Degree { .. })));
    assert!(matches!(
        kv.validate_for(1, 4),
        Err(Error::KnotMultiplicity {
            multiplicity: 3,
            max: 2,
            ..
        })
    ));
    // domain [t_1, t_3] = [0, 0] is empty
    let kv = KnotVector::new(vec![0.0, 0.0, 0.0, 0.0, 1.0]).unwrap();
    assert!(matches!(
        kv.validate_for(1, 3),
        Err(Error::KnotMultiplicity { .. })
    ));
    let kv = KnotVector::new(vec![0.0, 0.0, 0.0, 1.0, 1.0]).unwrap();
    assert!(matches!(kv.validate_for(2, 2), Err(Error::Degree { .. })));
}

#[test]
fn averaged_matches_example_9_1() {
    let t = [0.0, 5.0 / 17.0, 9.0 / 17.0, 14.0 / 17.0, 1.0];
    let kv = KnotVector::averaged(&t, 3).unwrap();
    let expect = [0.0, 0.0, 0.0, 0.0, 28.0 / 51.0, 1.0, 1.0, 1.0, 1.0];
    assert_eq!(kv.len(), expect.len());
    for (a, b) in kv.as_slice().iter().zip(expect) {
        assert!((a - b).abs() < 1e-15, "{a} vs {b}");
    }
    let kv = KnotVector::averaged(&t, 2).unwrap();
    let expect = [0.0, 0.0, 0.0, 7.0 / 17.0, 23.0 / 34.0, 1.0, 1.0, 1.0];
    for (a, b) in kv.as_slice().iter().zip(expect) {
        assert!((a - b).abs() < 1e-15, "{a} vs {b}");
    }
    assert!(matches!(
        KnotVector::averaged(&t, 5),
        Err(Error::Degree { .. })
    ));
    assert!(matches!(
        KnotVector::averaged(&t, 0),
        Err(Error::Degree { .. })
    ));
}

#[test]
fn averaged_with_end_derivatives_matches_example_9_1() {
    let t = [0.0, 5.0 / 17.0, 9.0 / 17.0, 14.0 / 17.0, 1.0];
    let kv = KnotVector::averaged_with_end_derivatives(&t, 3).unwrap();
    let expect = [
        0.0,
        0.0,
        0.0,
        0.0,
        14.0 / 51.0,
        28.0 / 51.0,
        40.0 / 51.0,
        1.0,
        1.0,
        1.0,
        1.0,
    ];
    assert_eq!(kv.len(), expect.len());
    for (a, b) in kv.as_slice().iter().zip(expect) {
        assert!((a - b).abs() < 1e-15, "{a} vs {b}");
    }
    let kv = KnotVector::averaged_with_end_derivatives(&t, 2).unwrap();
    let expect = [
        0.0,
        0.0,
        0.0,
        5.0 / 34.0,
        7.0 / 17.0,
        23.0 / 34.0,
        31.0 / 34.0,
        1.0,
        1.0,
        1.0,
    ];
    for (a, b) in kv.as_slice().iter().zip(expect) {
        assert!((a - b).abs() < 1e-15, "{a} vs {b}");
    }
}

#[test]
fn end_derivative_knots_for_the_highest_degree() {
    // two points and two end derivatives determine a cubic: no interior knots
    let kv = KnotVector::averaged_with_end_derivatives(&[0.0, 1.0], 3).unwrap();
    assert_eq!(kv.as_slice(), &[0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0]);
    assert!(matches!(
        KnotVector::averaged_with_end_derivatives(&[0.0, 1.0], 4),
        Err(Error::Degree { .. })
    ));
}

#[test]
fn from_parameters_is_eq8() {
    let t = [0.0, 5.0 / 17.0, 9.0 / 17.0, 14.0 / 17.0, 1.0];
    let kv = KnotVector::from_parameters(&t, 3).unwrap();
    assert_eq!(kv.len(), 4 + 7);
    assert_eq!(&kv.as_slice()[4..7], &t[1..4]);
    assert!(kv.is_clamped(3));
}

#[test]
fn curry_schoenberg_counts_and_errors() {
    let xi = [0.0, 1.0, 2.0, 3.0];
    let kv = KnotVector::from_breakpoints(&xi, &[0, 4], 4).unwrap();
    // 4 + (4 - 0) + (4 - 4) + 4 knots
    assert_eq!(kv.len(), 12);
    assert_eq!(kv.multiplicity(1.0), 4);
    assert_eq!(kv.multiplicity(2.0), 0);
    assert!(matches!(
        KnotVector::from_breakpoints(&xi, &[1], 4),
        Err(Error::LengthMismatch { .. })
    ));
    assert!(matches!(
        KnotVector::from_breakpoints(&xi, &[1, 5], 4),
        Err(Error::InvalidArgument { .. })
    ));
    assert!(matches!(
        KnotVector::from_breakpoints(&[0.0, 0.0], &[], 2),
        Err(Error::InvalidArgument { .. })
    ));
    assert!(matches!(
        KnotVector::from_breakpoints(&xi, &[1, 1], 0),
        Err(Error::Degree { .. })
    ));
}

#[test]
fn knots_closer_than_the_smallest_normal_number_are_refused() {
    let tiny = f64::from_bits(1); // 5e-324, subnormal
    let e = KnotVector::new(vec![0.0, 0.0, tiny, 1.0, 1.0]).unwrap_err();
    assert!(matches!(e, Error::InvalidArgument { .. }), "{e:?}");
    assert!(e.to_string().contains("smallest normal number"), "{e}");
    // equal knots and the smallest normal gap pass
    assert!(KnotVector::new(vec![0.0, 0.0, f64::MIN_POSITIVE, 1.0, 1.0]).is_ok());
    assert!(KnotVector::new(vec![0.0, 0.0, 0.0, 1.0, 1.0]).is_ok());
    // an unsorted vector is still named as such, wherever the subnormal gap is
    assert!(matches!(
        KnotVector::new(vec![0.0, tiny, 1.0, 0.5]),
        Err(Error::InvalidArgument { .. })
    ));
    assert!(matches!(
        KnotVector::new(vec![0.0, 1.0, 0.5, 0.5 + 1e-300]),
        Err(Error::KnotsNotSorted { index: 2, .. })
    ));
}

#[test]
fn insertion_never_makes_a_span_too_narrow_to_evaluate() {
    use crate::{BSplineCurve, Points};
    let tiny = f64::from_bits(1);
    let ctrl = Points::from_2d(&[[0.0, 0.0], [1.0, 2.0], [3.0, 2.0], [4.0, 0.0]]).unwrap();
    let c = BSplineCurve::from_knot_vector(3, KnotVector::clamped_uniform(3, 4).unwrap(), ctrl)
        .unwrap();
    for t in [tiny, f64::MIN_POSITIVE / 2.0] {
        assert!(matches!(
            c.insert_knot(t, 1),
            Err(Error::InvalidArgument { .. })
        ));
        assert!(matches!(
            c.refine_knots(&[t]),
            Err(Error::InvalidArgument { .. })
        ));
        assert!(c.split_at(t).is_err());
    }
    // two new knots too close to each other, each far enough from the old ones
    let m = f64::MIN_POSITIVE;
    assert!(matches!(
        c.refine_knots(&[m, m + tiny]),
        Err(Error::InvalidArgument { .. })
    ));
    assert!(c.refine_knots(&[m, 2.0 * m]).is_ok());
    // a normal gap still inserts, and evaluates to finite values on both sides
    let d = c.insert_knot(f64::MIN_POSITIVE, 1).unwrap();
    for x in [0.0, f64::MIN_POSITIVE, 1e-300, 0.5, 1.0] {
        assert!(d.eval(x).unwrap().iter().all(|v| v.is_finite()), "{x}");
    }
}
