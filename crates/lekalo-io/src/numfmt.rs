//! Numbers in text and CSV output: the shortest decimal that reads back to the same `f64`,
//! in exponent notation when plain notation would be long.

/// Below this magnitude (and above zero) a number is written in exponent notation.
const SMALL: f64 = 1e-5;
/// From this magnitude on a number is written in exponent notation.
const LARGE: f64 = 1e16;

/// The shortest text that parses back to exactly `x`: plain (`0.125`, `-3`) for
/// `1e-5 ≤ |x| < 1e16` and zero, exponent notation (`1e-20`, `2.5e300`) otherwise; `NaN`, `inf`
/// and `-inf` as Rust writes them.
///
/// ```
/// use lekalo_io::fmt_number;
/// assert_eq!(fmt_number(0.1), "0.1");
/// assert_eq!(fmt_number(1e-20), "1e-20");
/// assert_eq!(fmt_number(-2.5e300), "-2.5e300");
/// assert_eq!(fmt_number(3.0), "3");
/// assert_eq!(fmt_number(1.0 / 3.0).parse::<f64>().unwrap(), 1.0 / 3.0);
/// ```
#[must_use]
pub fn fmt_number(x: f64) -> String {
    let a = x.abs();
    if x == 0.0 || !x.is_finite() || (SMALL..LARGE).contains(&a) {
        format!("{x}")
    } else {
        format!("{x:e}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn round_trips_at_the_switch_points() {
        for x in [
            1e-5,
            9.999_999_999_999_999e-6,
            1e16,
            9_999_999_999_999_998.0,
            f64::MIN_POSITIVE,
            5e-324,
            f64::MAX,
            -0.0,
            0.1 + 0.2,
        ] {
            let s = fmt_number(x);
            assert_eq!(s.parse::<f64>().unwrap().to_bits(), x.to_bits(), "{x}: {s}");
        }
        assert_eq!(fmt_number(1e16), "1e16");
        assert_eq!(fmt_number(1e-5), "0.00001");
        assert_eq!(fmt_number(f64::NAN), "NaN");
    }
}
