//! Closeness of computed and expected coordinates, with a message naming the quantity, the
//! component and both values.

/// `|got_i − want_i| ≤ tol` for every component `i` (absolute tolerance), and equal lengths.
///
/// # Panics
/// When the lengths differ or a component is farther than `tol` (or is NaN).
#[track_caller]
pub fn assert_close(got: &[f64], want: &[f64], tol: f64, what: &str) {
    assert_eq!(got.len(), want.len(), "{what}: lengths");
    for (i, (g, w)) in got.iter().zip(want).enumerate() {
        assert!(
            (g - w).abs() <= tol,
            "{what}[{i}]: got {g:e}, want {w:e}, |diff| {:e} > tol {tol:e}",
            (g - w).abs()
        );
    }
}

/// `|got_i − want_i| ≤ abs + rel·|want_i|` for every component `i` (absolute plus relative
/// tolerance), and equal lengths.
///
/// # Panics
/// When the lengths differ or a component is farther than its tolerance (or is NaN).
#[track_caller]
pub fn assert_near(got: &[f64], want: &[f64], abs: f64, rel: f64, what: &str) {
    assert_eq!(got.len(), want.len(), "{what}: lengths");
    for (i, (g, w)) in got.iter().zip(want).enumerate() {
        assert!(
            (g - w).abs() <= abs + rel * w.abs(),
            "{what}[{i}]: got {g}, want {w} (abs {abs:e}, rel {rel:e})"
        );
    }
}

/// `|got_i − want_i| ≤ rel·max(|got_i|, |want_i|)` for every component `i` (relative tolerance:
/// `rel = k·f64::EPSILON` allows `k` rounding units), and equal lengths.
///
/// # Panics
/// When the lengths differ or a component is farther than its tolerance (or is NaN).
#[track_caller]
pub fn assert_close_relative(got: &[f64], want: &[f64], rel: f64, what: &str) {
    assert_eq!(got.len(), want.len(), "{what}: lengths");
    for (i, (g, w)) in got.iter().zip(want).enumerate() {
        assert!(
            (g - w).abs() <= rel * g.abs().max(w.abs()),
            "{what}[{i}]: got {g}, want {w} (rel {rel:e})"
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tolerances_are_inclusive() {
        assert_close(&[1.0, 2.0], &[1.5, 2.0], 0.5, "abs");
        assert_near(&[11.0], &[10.0], 0.5, 0.05, "abs + rel");
        assert_close_relative(&[1.0 + f64::EPSILON], &[1.0], f64::EPSILON, "rel");
    }

    #[test]
    #[should_panic(expected = "abs[1]")]
    fn a_far_component_is_named() {
        assert_close(&[1.0, 2.0], &[1.0, 2.1], 0.05, "abs");
    }

    #[test]
    #[should_panic(expected = "lengths")]
    fn lengths_must_agree() {
        assert_near(&[1.0], &[1.0, 2.0], 1.0, 0.0, "lengths");
    }

    #[test]
    #[should_panic(expected = "rel[0]")]
    fn nan_is_never_close() {
        assert_close_relative(&[f64::NAN], &[1.0], 1.0, "rel");
    }
}
