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
fn span_search_edges() {
    let kv = KnotVector::new(vec![0.0, 0.0, 0.0, 0.5, 0.5, 1.0, 1.0, 1.0]).unwrap();
    assert_eq!(kv.find_span(2, 0.0).unwrap(), 2);
    assert_eq!(kv.find_span(2, 0.49).unwrap(), 2);
    assert_eq!(kv.find_span(2, 0.5).unwrap(), 4);
    assert_eq!(kv.find_span(2, 1.0).unwrap(), 4);
    assert!(matches!(
        kv.find_span(2, 1.0 + 1e-12),
        Err(Error::ParameterOutOfDomain { .. })
    ));
    assert!(matches!(
        kv.find_span(2, f64::NAN),
        Err(Error::ParameterOutOfDomain { .. })
    ));
    assert!(matches!(kv.find_span(4, 0.5), Err(Error::Degree { .. })));
}

#[test]
fn empty_last_span_is_never_returned() {
    // degree 2, 6 control points, domain [t_2, t_6] = [0, 1]; span 5 = [1, 1) is empty
    let kv = KnotVector::new(vec![0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0, 2.0, 2.0]).unwrap();
    kv.validate_for(2, 6).unwrap();
    assert_eq!(kv.find_span(2, 1.0).unwrap(), 3);
    let mut c = kv.span_cursor(2);
    for t in [0.0, 0.6, 1.0, 0.2, 1.0] {
        let s = c.find(t).unwrap();
        assert!(
            kv.as_slice()[s] < kv.as_slice()[s + 1],
            "empty span {s} at t = {t}"
        );
        assert_eq!(s, kv.find_span(2, t).unwrap(), "t = {t}");
    }
}

#[test]
fn cursor_agrees_with_binary_search_in_any_order() {
    let kv = KnotVector::new(vec![0.0, 0.0, 0.1, 0.1, 0.3, 0.7, 0.7, 0.9, 1.0, 1.0]).unwrap();
    let mut c = kv.span_cursor(1);
    let ts = [
        0.0, 0.05, 0.1, 0.2, 0.3, 0.69, 0.7, 0.95, 1.0, 0.0, 0.5, 1.0, 0.1,
    ];
    for t in ts {
        assert_eq!(c.find(t).unwrap(), kv.find_span(1, t).unwrap(), "t = {t}");
    }
    assert!(c.find(-0.1).is_err());
}

#[test]
fn breakpoints_sorted_is_numpys_test_of_the_differences() {
    // np.all(dx >= 0) or np.all(dx <= 0) on dx = np.diff(x), across the block size
    let naive = |x: &[f64]| {
        let d: Vec<f64> = x.windows(2).map(|w| w[1] - w[0]).collect();
        d.iter().all(|&v| v >= 0.0) || d.iter().all(|&v| v <= 0.0)
    };
    let up: Vec<f64> = (0..3000).map(|i| f64::from(i / 3)).collect();
    let down: Vec<f64> = up.iter().rev().copied().collect();
    let mut cases = vec![vec![], vec![1.0], vec![2.0, 2.0], up.clone(), down.clone()];
    for at in [1, 1023, 1024, 1025, 2999] {
        for bad in [f64::NAN, -5.0, 5000.0] {
            let mut x = up.clone();
            x[at] = bad;
            cases.push(x);
            let mut x = down.clone();
            x[at] = bad;
            cases.push(x);
        }
    }
    cases.push(vec![0.0, f64::INFINITY]);
    cases.push(vec![0.0, f64::INFINITY, f64::INFINITY]);
    cases.push(vec![f64::NEG_INFINITY, f64::NEG_INFINITY]);
    for x in &cases {
        assert_eq!(
            breakpoints_sorted(x),
            naive(x),
            "{:?}",
            &x[..x.len().min(4)]
        );
    }
}
