//! How the library's messages write numbers, directions and boxes: the words its errors
//! (`error.rs`) and the checks that build them share, so that every message writes `1e-300`
//! and `2nd direction` alike.

/// A number as error messages write it: as Rust writes it for `1e-5 ≤ |x| < 1e16`, zero and
/// non-finite values (`0.25`, `3`, `NaN`), in exponent notation otherwise (`1e-300`, `2.5e300`),
/// so that no message holds a 300-digit decimal.
pub(crate) struct Readable(f64);

impl std::fmt::Display for Readable {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let x = self.0;
        if x == 0.0 || !x.is_finite() || (1e-5..1e16).contains(&x.abs()) {
            write!(f, "{x}")
        } else {
            write!(f, "{x:e}")
        }
    }
}

/// A direction of a tensor-product spline as messages name it, by its ordinal counted from the
/// first (`1st direction`, `2nd direction`, ...): index `a` of the library (Python's axis `a`)
/// is the command line's direction `a + 1` (`--params-in 1=...`, the columns `x1 … xN`), and an
/// ordinal reads right in both numberings.
pub(crate) struct NthDirection(pub(crate) usize);

impl std::fmt::Display for NthDirection {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let n = self.0.saturating_add(1);
        let suffix = match (n % 10, n % 100) {
            (_, 11..=13) => "th",
            (1, _) => "st",
            (2, _) => "nd",
            (3, _) => "rd",
            _ => "th",
        };
        write!(f, "{n}{suffix} direction")
    }
}

/// A control point of a tensor-product spline in `N` variables and its support, the box
/// `Π_a [t_{a,i_a}, t_{a,i_a+p_a+1}]` where its basis function is positive
/// (the support an empty-support error names).
#[derive(Debug, Clone, PartialEq)]
pub struct ControlSupport {
    /// The control point's index in each direction.
    pub index: Vec<usize>,
    /// The lower corner of its support (one knot per direction).
    pub lower: Vec<f64>,
    /// The upper corner of its support.
    pub upper: Vec<f64>,
}

/// The box `[a_0, b_0] × … × [a_{N−1}, b_{N−1}]` of an empty-support error.
pub(crate) fn support_box(lower: &[f64], upper: &[f64]) -> String {
    let sides: Vec<String> = lower
        .iter()
        .zip(upper)
        .map(|(a, b)| format!("[{a}, {b}]", a = readable(a), b = readable(b)))
        .collect();
    sides.join(" × ")
}

/// [`Readable`] of a field (the messages of the error type take their fields by reference).
#[allow(clippy::trivially_copy_pass_by_ref)] // called with the `&f64` thiserror passes
pub(crate) fn readable(x: &f64) -> Readable {
    Readable(*x)
}
