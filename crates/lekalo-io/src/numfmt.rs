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
/// the last digit may differ by one; both read back to `x`), with no allocation: the shortest
/// digits come from `zmij` (the formatter `serde_json` uses, several times faster than
/// `core::fmt`), then are laid out plain or in exponent notation as [`fmt_number`] does.
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
    let (negative, text) = match text.split_first() {
        Some((b'-', rest)) => (true, rest),
        _ => (false, text),
    };
    // `text` is `d.ddd`, `ddd` or `0.000ddd`, with an optional `e±n`
    let (mantissa, exp) = match text.iter().position(|&b| b == b'e') {
        Some(i) => (&text[..i], parse_exponent(&text[i + 1..])),
        None => (text, 0),
    };
    // significant digits `sig` and the exponent `e` of the first: x = d0.d1d2… × 10^e
    let mut sig = [0u8; 24];
    let mut n = 0usize;
    let mut point = mantissa.len();
    let mut lead = 0i32; // zeros before the first significant digit, after the point
    for (i, &b) in mantissa.iter().enumerate() {
        if b == b'.' {
            point = i;
        } else if n == 0 && b == b'0' {
            if point < i {
                lead += 1;
            }
        } else if n < sig.len() {
            sig[n] = b;
            n += 1;
        }
    }
    while n > 1 && sig[n - 1] == b'0' {
        n -= 1;
    }
    let int_digits = i32::try_from(point).unwrap_or(0);
    let e = if int_digits > 0 && mantissa[0] != b'0' {
        exp + int_digits - 1
    } else {
        exp - lead - 1
    };
    let sig = &sig[..n];
    if negative {
        out.push(b'-');
    }
    if (SMALL..LARGE).contains(&x.abs()) {
        match usize::try_from(e) {
            Ok(e) if sig.len() <= e + 1 => {
                out.extend_from_slice(sig);
                out.resize(out.len() + e + 1 - sig.len(), b'0');
            }
            Ok(e) => {
                out.extend_from_slice(&sig[..=e]);
                out.push(b'.');
                out.extend_from_slice(&sig[e + 1..]);
            }
            Err(_) => {
                out.extend_from_slice(b"0.");
                let zeros = usize::try_from(-e - 1).unwrap_or(0);
                out.resize(out.len() + zeros, b'0');
                out.extend_from_slice(sig);
            }
        }
    } else {
        out.push(sig[0]);
        if sig.len() > 1 {
            out.push(b'.');
            out.extend_from_slice(&sig[1..]);
        }
        out.push(b'e');
        let mut itoa = [0u8; 8];
        let mut k = itoa.len();
        let mut m = e.unsigned_abs();
        loop {
            k -= 1;
            itoa[k] = b'0' + u8::try_from(m % 10).unwrap_or(0);
            m /= 10;
            if m == 0 {
                break;
            }
        }
        if e < 0 {
            out.push(b'-');
        }
        out.extend_from_slice(&itoa[k..]);
    }
}

/// The exponent after `e` in the formatter's output (`-7`, `+20`, `300`).
fn parse_exponent(text: &[u8]) -> i32 {
    let (sign, digits) = match text.split_first() {
        Some((b'-', rest)) => (-1, rest),
        Some((b'+', rest)) => (1, rest),
        _ => (1, text),
    };
    sign * digits
        .iter()
        .fold(0i32, |acc, &d| acc * 10 + i32::from(d - b'0'))
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
