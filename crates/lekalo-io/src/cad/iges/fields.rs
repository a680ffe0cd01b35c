//! The lexical layer of IGES: parameter fields split at the delimiters (Hollerith strings kept
//! whole), reals with `D` exponents, counts, and the units of the Global section (IGES 5.3
//! §2.2.2, §2.2.4.3).

/// Splits a parameter text at `delim` outside Hollerith strings, up to the record delimiter.
/// A Hollerith count beyond the text (up to 2^64 − 1, or more digits than that) takes the rest
/// of the text.
pub(super) fn fields(text: &str, delim: char, record: char) -> Vec<String> {
    let chars: Vec<char> = text.chars().collect();
    let mut out = Vec::new();
    let mut cur = String::new();
    // whether `cur` holds only blanks so far: a Hollerith count can start only there. Kept as
    // a flag so that a long field is not scanned again for every character (that was
    // quadratic in the field's length).
    let mut blank = true;
    let mut i = 0;
    while i < chars.len() {
        let c = chars[i];
        if c.is_ascii_digit() && blank {
            // a Hollerith string nHxxx: digits then H then n characters
            let mut j = i;
            while j < chars.len() && chars[j].is_ascii_digit() {
                j += 1;
            }
            if j < chars.len() && chars[j] == 'H' {
                let n: usize = chars[i..j]
                    .iter()
                    .collect::<String>()
                    .parse()
                    .unwrap_or(usize::MAX);
                let end = (j + 1).saturating_add(n).min(chars.len());
                cur = chars[j + 1..end].iter().collect();
                blank = cur.trim().is_empty();
                i = end;
                continue;
            }
        }
        if c == delim {
            out.push(std::mem::take(&mut cur));
            blank = true;
        } else if c == record {
            out.push(std::mem::take(&mut cur));
            return out;
        } else {
            cur.push(c);
            blank &= c.is_whitespace();
        }
        i += 1;
    }
    out.push(cur);
    out
}

pub(super) fn real(s: &str) -> Option<f64> {
    let t = s.trim().replace(['D', 'd'], "E");
    if t.is_empty() {
        return Some(0.0);
    }
    t.parse::<f64>().ok().filter(|x| x.is_finite())
}

pub(super) fn count(s: &str) -> Option<usize> {
    let t = s.trim();
    if t.is_empty() {
        return Some(0);
    }
    t.parse::<usize>().ok()
}

/// The unit of flag `f` (IGES 5.3 §2.2.4.3, field 14) in millimetres, and its name.
pub(super) fn unit(flag: usize, name: &str) -> Option<(String, f64)> {
    let mm = match flag {
        1 => 25.4,
        2 => 1.0,
        4 => 304.8,
        5 => 1_609_344.0,
        6 => 1000.0,
        7 => 1e6,
        8 => 0.0254,
        9 => 1e-3,
        10 => 10.0,
        11 => 2.54e-5,
        3 => match name.trim().to_ascii_uppercase().as_str() {
            "MM" => 1.0,
            "IN" | "INCH" => 25.4,
            "M" => 1000.0,
            "CM" => 10.0,
            _ => return None,
        },
        _ => return None,
    };
    Some((name.trim().to_string(), mm))
}

/// Parameter `k` of an entity's fields as a real ([`real`]), or why it is not one, named by its
/// position (IGES 5.3 §2.2.2.4: reals as `1.5`, `-2.E-3`, `1.D0`).
pub(super) fn real_at(f: &[String], k: usize) -> Result<f64, String> {
    let Some(text) = f.get(k) else {
        return Err(format!("parameter {k} is missing"));
    };
    real(text).ok_or_else(|| {
        let t = text.trim();
        let digits = t.bytes().any(|b| b.is_ascii_digit());
        if digits && t.replace(['D', 'd'], "E").parse::<f64>().is_ok_and(f64::is_infinite) {
            format!("parameter {k} is {t}, outside the range of a double")
        } else {
            format!("parameter {k} is \"{t}\", not a number (IGES writes reals as 1.5, -2.E-3 or 1.D0; NaN and infinities have no IGES form)")
        }
    })
}
