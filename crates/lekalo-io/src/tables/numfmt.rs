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

/// Appends [`fmt_number`]'s text of `x` to `out` (in an exact tie between two shortest decimals
/// the last digit may differ by one; both read back to `x`), with no allocation. The shortest
/// digits come from `zmij` (the formatter `serde_json` uses, several times faster than
/// `core::fmt`), which already switches to exponent notation exactly where [`fmt_number`] does
/// (a shortest decimal exponent outside `-5..=15`, i.e. `|x|` outside `[1e-5, 1e16)`); only its
/// spelling differs: `3.0` for `3` and `1e+16` for `1e16`, mended here.
pub(crate) fn push_number(out: &mut Vec<u8>, digits: &mut zmij::Buffer, x: f64) {
    if x == 0.0 || !x.is_finite() {
        out.extend_from_slice(match x {
            v if v.is_nan() => b"NaN",
            f64::INFINITY => b"inf",
            f64::NEG_INFINITY => b"-inf",
            v if v.is_sign_negative() => b"-0",
            _ => b"0",
        });
        return;
    }
    let text = digits.format_finite(x).as_bytes();
    if (SMALL..LARGE).contains(&x.abs()) {
        out.extend_from_slice(text.strip_suffix(b".0").unwrap_or(text));
    } else {
        // `d.ddde+n` or `d.ddde-n`: the `+` is dropped
        for &b in text {
            if b != b'+' {
                out.push(b);
            }
        }
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

    fn pushed(x: f64) -> String {
        let mut out = Vec::new();
        push_number(&mut out, &mut zmij::Buffer::new(), x);
        String::from_utf8(out).unwrap()
    }

    #[test]
    fn push_number_writes_fmt_number() {
        for x in [
            0.0,
            -0.0,
            1.0,
            -3.0,
            0.1,
            0.125,
            1e-5,
            1e-6,
            1.5e-7,
            1e15,
            1e16,
            1.2345e16,
            123.456,
            1e300,
            -2.5e300,
            5e-324,
            f64::MAX,
            f64::MIN_POSITIVE,
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            100.0,
            1e5,
            0.001,
            9.999_999_999_999_999e-6,
            1.0 / 3.0,
        ] {
            assert_eq!(pushed(x), fmt_number(x), "{x:e}");
        }
    }

    /// `push_number`'s text of `x` is `fmt_number`'s, except where `x` lies exactly halfway
    /// between two shortest decimals (its exact expansion is one digit longer, ending in 5, e.g.
    /// 17526159967286.8125): there both texts have the same length and read back to `x`, and
    /// they differ by one unit in the last digit.
    fn same_or_tie(x: f64) -> Result<(), proptest::test_runner::TestCaseError> {
        let (got, want) = (pushed(x), fmt_number(x));
        if got != want {
            proptest::prop_assert_eq!(got.len(), want.len(), "{:e}", x);
            proptest::prop_assert_eq!(got.parse::<f64>().unwrap().to_bits(), x.to_bits());
            let (a, b) = (got.as_bytes(), want.as_bytes());
            let last = a.len() - 1;
            proptest::prop_assert_eq!(&a[..last], &b[..last], "{:e}", x);
            proptest::prop_assert_eq!(a[last].abs_diff(b[last]), 1, "{:e}", x);
        }
        Ok(())
    }

    proptest::proptest! {
        #[test]
        fn push_number_matches_fmt_number_on_any_bits(bits in proptest::prelude::any::<u64>()) {
            same_or_tie(f64::from_bits(bits))?;
        }

        /// Plain magnitudes up to 1e24, where ties are common.
        #[test]
        fn push_number_matches_on_plain_magnitudes(m in -1e6f64..1e6, k in -8i32..18) {
            same_or_tie(m * 10f64.powi(k))?;
        }
    }
}
