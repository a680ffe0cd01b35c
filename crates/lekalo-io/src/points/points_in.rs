//! Points from text: CSV, whitespace-separated columns or JSON, one point per row.
//!
//! - **CSV / whitespace:** one point per line, coordinates separated by commas or by blanks;
//!   blank lines and lines starting with `#` are skipped; a first line on which no field is a
//!   number is a header naming the columns (`x,y,z`) ([`Header::Auto`]; [`Header::Yes`] and
//!   [`Header::No`] decide it instead). A line mixing numbers and text is an error naming the
//!   line and the field, never a header silently dropped. A UTF-8 byte-order mark is skipped.
//! - **JSON:** an array of rows `[[x, y], …]`, the flat form `{"dim": 2, "data": [x0, y0, …]}`,
//!   or `{"points": [[x, y], …]}`.
//!
//! The format is recognised from the first non-blank character (`[` or `{` means JSON).
//! Errors name the source, the line and the field (column), e.g.
//! `data.csv:3: field `y`: cannot read "abc" as a number`.

use lekalo::Points;
use serde::de::DeserializeSeed;

use crate::error::{IoError, IoResult, Location};
use crate::flat::{self, PointsSeed};

pub use crate::text_points::Header;

/// Reads points from `text`; `source` names the input in messages (a path or `<stdin>`).
///
/// ```
/// let p = lekalo_io::read_points("x,y\n0,0\n3,4\n", "pts.csv").unwrap();
/// assert_eq!(p.len(), 2);
/// assert_eq!(p.point(1), &[3.0, 4.0]);
/// let e = lekalo_io::read_points("x,y\n0,0\n3,oops\n", "pts.csv").unwrap_err();
/// assert_eq!(e.to_string(), "pts.csv:3: field `y`: cannot read \"oops\" as a number");
/// ```
///
/// # Errors
/// [`IoError::Syntax`] for a field that is not a finite number, rows of different lengths, no
/// points, or malformed JSON; [`IoError::Invalid`] if the library rejects the points.
pub fn read_points(text: &str, source: &str) -> IoResult<Points> {
    read_points_with(text, source, Header::Auto)
}

/// [`read_points`] with the header rule given.
///
/// ```
/// use lekalo_io::{read_points_with, Header};
/// let e = read_points_with("0,0a\n1,1\n", "p.csv", Header::Auto).unwrap_err();
/// assert!(e.to_string().starts_with("p.csv:1: field `2`: cannot read \"0a\""), "{e}");
/// let p = read_points_with("0,0a\n1,1\n", "p.csv", Header::Yes).unwrap();
/// assert_eq!(p.len(), 1);
/// ```
///
/// # Errors
/// As [`read_points`].
pub fn read_points_with(text: &str, source: &str, header_rule: Header) -> IoResult<Points> {
    let text = crate::atomic::strip_bom_str(text);
    let first = text.trim_start().chars().next();
    if matches!(first, Some('[' | '{')) {
        return read_points_json(text, source);
    }
    crate::text_points::read_delimited(text.as_bytes(), source, header_rule)
}

/// [`read_points_with`] from the bytes of a file (as [`crate::read_input_bytes`] gives them):
/// CSV and whitespace text are checked as UTF-8 part by part while they are parsed on all cores,
/// instead of whole before; the result, and the error of text that is not UTF-8, are those of
/// [`crate::read_input`] and [`read_points_with`].
///
/// ```
/// use lekalo_io::{read_points_bytes, Header};
/// let p = read_points_bytes(b"\xef\xbb\xbfx,y\n0,1\n2,3\n", "p.csv", Header::Auto).unwrap();
/// assert_eq!(p.point(1), &[2.0, 3.0]);
/// let e = read_points_bytes(b"0,1\n2,\xff\n", "p.csv", Header::Auto).unwrap_err();
/// assert!(e.to_string().contains("not UTF-8 text at line 2, column 3 (byte 6)"), "{e}");
/// ```
///
/// # Errors
/// As [`read_points_with`], and [`IoError::Read`] for text that is not UTF-8.
pub fn read_points_bytes(bytes: &[u8], source: &str, header_rule: Header) -> IoResult<Points> {
    let whole = || {
        let text = std::str::from_utf8(bytes)
            .map_err(|e| crate::atomic::not_utf8(source, bytes, e.valid_up_to()))?;
        read_points_with(text, source, header_rule)
    };
    // the white space of `str::trim_start` in ASCII (with the vertical tab)
    match bytes.iter().find(|b| !matches!(b, b' ' | b'\t'..=b'\r')) {
        // JSON, a byte-order mark, or text starting with a character outside ASCII: checked
        // whole, as read_input does
        Some(b'[' | b'{' | 128..) => whole(),
        _ => crate::text_points::read_delimited(bytes, source, header_rule),
    }
}

/// The line (counted from 1) of a points file that holds point `index` (counted from 0), for
/// messages about points the library names by index: CSV and whitespace text by the rules of
/// [`read_points_with`] (blank and `#` lines skipped, the header by `header_rule`); `None` for
/// JSON, or past the last point.
///
/// ```
/// use lekalo_io::{line_of_point, Header};
/// let text = b"x,y\n0,0\n\n# a comment\n1,1\n1,1\n";
/// assert_eq!(line_of_point(text, Header::Auto, 0), Some(2));
/// assert_eq!(line_of_point(text, Header::Auto, 2), Some(6));
/// assert_eq!(line_of_point(text, Header::Auto, 3), None);
/// assert_eq!(line_of_point(b"[[0, 0], [1, 1]]", Header::Auto, 1), None);
/// ```
#[must_use]
pub fn line_of_point(bytes: &[u8], header_rule: Header, index: usize) -> Option<usize> {
    let bytes = bytes.strip_prefix(b"\xef\xbb\xbf").unwrap_or(bytes);
    match bytes.iter().find(|b| !b.is_ascii_whitespace()) {
        Some(b'[' | b'{') | None => None,
        _ => crate::text_points::line_of_point(bytes, header_rule, index),
    }
}

fn read_points_json(text: &str, source: &str) -> IoResult<Points> {
    let at = Location::new(source);
    let mut de = serde_json::Deserializer::from_str(text);
    let flat = PointsSeed {
        field: "",
        allow_points_key: true,
    }
    .deserialize(&mut de)
    .and_then(|p| de.end().map(|()| p))
    .map_err(|e| {
        let loc = at.clone().at_line(e.line());
        if e.is_data() {
            IoError::syntax(loc, flat::message(&e))
        } else {
            IoError::syntax(loc, format!("not valid JSON: {e}"))
        }
    })?;
    flat.into_points()
        .map_err(|e| IoError::Invalid { at, error: e })
}

/// Parses a list of numbers written `0, 0.5, 1` or `0 0.5 1` (command-line arguments).
///
/// # Errors
/// [`IoError::Syntax`] naming the position of a value that is not a finite number.
pub fn parse_number_list(text: &str, what: &str) -> IoResult<Vec<f64>> {
    text.split([',', ' ', '\t', '\n'])
        .filter(|s| !s.trim().is_empty())
        .enumerate()
        .map(|(i, s)| {
            s.trim()
                .parse::<f64>()
                .ok()
                .filter(|v| v.is_finite())
                .ok_or_else(|| {
                    IoError::syntax(
                        Location::new(what).at_field(format!("{}", i + 1)),
                        format!("cannot read \"{}\" as a finite number", s.trim()),
                    )
                })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The line-by-line reader the one-pass reader replaced: the reference its results and
    /// messages are compared with.
    pub(super) fn reference(text: &str, source: &str, header_rule: Header) -> IoResult<Points> {
        let text = crate::atomic::strip_bom_str(text);
        let mut header: Option<Vec<String>> = None;
        let mut dim: Option<(usize, usize)> = None; // (dim, line where it was set)
        let mut data = Vec::new();
        for (i, raw) in text.lines().enumerate() {
            let line_no = i + 1;
            let line = raw.trim();
            if line.is_empty() || line.starts_with('#') {
                continue;
            }
            let fields: Vec<&str> = if line.contains(',') || line.contains(';') {
                line.split([',', ';']).map(str::trim).collect()
            } else {
                line.split_whitespace().collect()
            };
            let first_line = dim.is_none() && header.is_none();
            let is_header = first_line
                && match header_rule {
                    Header::Yes => true,
                    Header::No => false,
                    Header::Auto => fields.iter().all(|f| f.parse::<f64>().is_err()),
                };
            if is_header {
                header = Some(fields.iter().map(|f| f.to_string()).collect());
                continue;
            }
            let at = Location::new(source).at_line(line_no);
            if dim.is_none() && line.contains(';') && line.contains(',') {
                return Err(crate::text_points::decimal_commas(source, line_no, line));
            }
            match dim {
            None => dim = Some((fields.len(), line_no)),
            Some((d, first_line)) if d != fields.len() => {
                return Err(IoError::syntax(
                    at,
                    format!(
                        "{} fields, but line {first_line} has {d}; every point needs the same number of coordinates",
                        fields.len()
                    ),
                ))
            }
            Some(_) => {}
        }
            for (k, f) in fields.iter().enumerate() {
                let name = header
                    .as_ref()
                    .and_then(|h| h.get(k).cloned())
                    .unwrap_or_else(|| format!("{}", k + 1));
                let v: f64 = f.parse().map_err(|_| {
                    IoError::syntax(
                        at.clone().at_field(name.clone()),
                        format!("cannot read \"{f}\" as a number"),
                    )
                })?;
                if !v.is_finite() {
                    return Err(IoError::syntax(
                        at.clone().at_field(name),
                        format!("\"{f}\" is not finite; every coordinate must be a finite number"),
                    ));
                }
                data.push(v);
            }
        }
        let Some((dim, _)) = dim else {
            return Err(IoError::syntax(
                Location::new(source),
                "no points found; write one point per line, e.g. `1.0, 2.0`",
            ));
        };
        Points::from_flat(dim, data).map_err(|e| IoError::Invalid {
            at: Location::new(source),
            error: e,
        })
    }

    #[test]
    fn decimal_commas_are_refused_with_the_fix() {
        let e = read_points("x;y\n1,5;2,0\n3,0;4,5\n", "eu.csv").unwrap_err();
        assert_eq!(
            e.to_string(),
            "eu.csv:2: `1,5;2,0` has both `;` and `,`: decimal commas? lekalo reads `.` as the \
             decimal point and `,`, `;` or blanks between coordinates; write `1.5;2.0` or `1.5,2.0`"
        );
        let slow = reference("1,5;2,0\n", "eu.csv", Header::Auto).unwrap_err();
        assert_eq!(
            read_points("1,5;2,0\n", "eu.csv").unwrap_err().to_string(),
            slow.to_string(),
            "the line reader agrees"
        );
        // one separator a line is read as before
        assert_eq!(read_points("1.5;2\n3;4\n", "p.csv").unwrap().dim(), 2);
    }

    #[test]
    fn csv_whitespace_and_json_agree() {
        let csv = "# P&T Example 9.1\nx, y\n0,0\n3,4\n-1,4\n";
        let ws = "0 0\n\n3\t4\n-1   4\n";
        let json = "[[0,0],[3,4],[-1,4]]";
        let flat = r#"{"dim":2,"data":[0,0,3,4,-1,4]}"#;
        let named = r#"{"points":[[0,0],[3,4],[-1,4]]}"#;
        let a = read_points(csv, "a").unwrap();
        assert_eq!(a.as_slice(), &[0.0, 0.0, 3.0, 4.0, -1.0, 4.0]);
        for t in [ws, json, flat, named] {
            assert_eq!(read_points(t, "b").unwrap(), a, "{t}");
        }
    }

    #[test]
    fn errors_name_line_and_field() {
        let e = read_points("0 0\n1 2 3\n", "p.txt")
            .unwrap_err()
            .to_string();
        assert_eq!(
            e,
            "p.txt:2: 3 fields, but line 1 has 2; every point needs the same number of coordinates"
        );
        let e = read_points("1,2\n1,x\n", "p.csv").unwrap_err().to_string();
        assert_eq!(e, "p.csv:2: field `2`: cannot read \"x\" as a number");
        let e = read_points("1,2\n1,NaN\n", "p.csv")
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with("p.csv:2: field `2`: \"NaN\" is not finite"),
            "{e}"
        );
        let e = read_points("# nothing\n", "p.csv").unwrap_err().to_string();
        assert!(e.starts_with("p.csv: no points found"), "{e}");
        let e = read_points("[[0,0],\n [1,\"a\"]]", "p.json")
            .unwrap_err()
            .to_string();
        assert_eq!(e, "p.json:2: field `[1][1]`: \"a\" is not a number");
        let e = read_points("{\"points\": [\n[0,0],\n[1],\n[2,2]]}", "p.json")
            .unwrap_err()
            .to_string();
        assert_eq!(
            e,
            "p.json:3: field `[1]`: point 1 has 1 coordinates, point 0 has 2; every point needs the same number"
        );
        let e = read_points("[[0,0],\n[1", "p.json")
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("p.json:2: not valid JSON"), "{e}");
        let e = read_points("{\"dim\":0,\"data\":[]}", "p.json")
            .unwrap_err()
            .to_string();
        assert!(e.contains("dimension of points"), "{e}");
    }

    #[test]
    fn headers_boms_and_mixed_lines() {
        // a line with a number on it is data, never a header: refused, not dropped
        let e = read_points("0,0a\n1,1\n2,0\n", "h.csv")
            .unwrap_err()
            .to_string();
        assert_eq!(e, "h.csv:1: field `2`: cannot read \"0a\" as a number");
        assert_eq!(read_points("x,y\n1,1\n", "h.csv").unwrap().len(), 1);
        assert_eq!(
            read_points_with("0,0a\n1,1\n2,0\n", "h.csv", Header::Yes)
                .unwrap()
                .len(),
            2
        );
        let e = read_points_with("x,y\n1,1\n", "h.csv", Header::No).unwrap_err();
        assert!(e.to_string().starts_with("h.csv:1: field `1`"), "{e}");
        // a byte-order mark is not part of the first field
        let p = read_points("\u{feff}0,0\n1,1\n", "b.csv").unwrap();
        assert_eq!(p.len(), 2);
        let p = read_points("\u{feff}[[0,0],[1,1]]", "b.json").unwrap();
        assert_eq!(p.len(), 2);
        let e = read_points(r#"{"dim": 2, "dim": 3, "data": [1, 2]}"#, "d.json").unwrap_err();
        assert!(e.to_string().contains("duplicate key `dim`"), "{e}");
    }

    #[test]
    fn number_lists() {
        assert_eq!(
            parse_number_list("0, 0.5 1", "--at").unwrap(),
            vec![0.0, 0.5, 1.0]
        );
        let e = parse_number_list("0, x", "--at").unwrap_err().to_string();
        assert_eq!(e, "--at: field `2`: cannot read \"x\" as a finite number");
    }
}

#[cfg(test)]
mod one_pass {
    use super::tests::reference;
    use super::*;
    use proptest::prelude::*;

    /// Lines of numbers, words, blanks, comments and separators, joined by `\n` or `\r\n`.
    fn text() -> impl Strategy<Value = String> {
        let field = prop_oneof![
            (-1e6f64..1e6).prop_map(|v| v.to_string()),
            Just("1e400".to_string()),
            Just("x".to_string()),
            Just("NaN".to_string()),
            Just(" 2.5 ".to_string()),
            Just(String::new()),
            Just("# c".to_string()),
            Just("\u{a0}3".to_string()),
            // every number the parsers may read, in every spelling, and near-numbers
            any::<u64>().prop_map(|b| f64::from_bits(b).to_string()),
            any::<u64>().prop_map(|b| format!("{:e}", f64::from_bits(b))),
            "[-+]?[0-9]{0,3}[.]?[0-9]{0,3}([eE][-+]?[0-9]{0,4})?",
            "[-+]?(inf|infinity|nan|NaN|INF|0x1|1_0|1\\.2\\.3|1e|\\.|-)",
        ];
        let line = (
            proptest::collection::vec(field, 0..4),
            prop_oneof![Just(","), Just(";"), Just(" "), Just("\t")],
        )
            .prop_map(|(f, sep)| f.join(sep));
        (
            proptest::collection::vec(line, 0..40),
            prop_oneof![Just("\n"), Just("\r\n")],
        )
            .prop_map(|(l, nl)| l.join(nl))
    }

    proptest! {
        #[test]
        fn same_points_and_messages_as_the_line_reader(t in text(), rule in 0..3u8) {
            let rule = [Header::Auto, Header::Yes, Header::No][usize::from(rule)];
            let fast = read_points_with(&t, "p.csv", rule).map_err(|e| e.to_string());
            let slow = reference(&t, "p.csv", rule).map_err(|e| e.to_string());
            prop_assert_eq!(&fast, &slow, "{:?}", t);
            // from the bytes of a file, after white space that decides between CSV and JSON
            for lead in ["", " \x0b\t", "\x0b[", "\u{feff}", "\u{a0}"] {
                let t = format!("{lead}{t}");
                let bytes = read_points_bytes(t.as_bytes(), "p.csv", rule).map_err(|e| e.to_string());
                let text = read_points_with(&t, "p.csv", rule).map_err(|e| e.to_string());
                prop_assert_eq!(&bytes, &text, "from bytes: {:?}", t);
            }
            // the same text cut in parts read on several threads
            let text = crate::atomic::strip_bom_str(&t);
            let parts = crate::text_points::read_delimited_from(text.as_bytes(), "p.csv", rule, 0)
                .map_err(|e| e.to_string());
            prop_assert_eq!(&parts, &slow, "in parts: {:?}", t);
        }
    }
}
