//! Points from text: CSV, whitespace-separated columns or JSON, one point per row.
//!
//! - **CSV / whitespace:** one point per line, coordinates separated by commas or by blanks;
//!   blank lines and lines starting with `#` are skipped; a first line that is not numeric is a
//!   header naming the columns (`x,y,z`).
//! - **JSON:** an array of rows `[[x, y], …]`, the flat form `{"dim": 2, "data": [x0, y0, …]}`,
//!   or `{"points": [[x, y], …]}`.
//!
//! The format is recognised from the first non-blank character (`[` or `{` means JSON).
//! Errors name the source, the line and the field (column), e.g.
//! `data.csv:3: field `y`: cannot read "abc" as a number`.

use lekalo::Points;
use serde_json::Value;

use crate::error::{IoError, IoResult, Location};

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
    let first = text.trim_start().chars().next();
    if matches!(first, Some('[' | '{')) {
        return read_points_json(text, source);
    }
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
        let is_header =
            dim.is_none() && header.is_none() && fields.iter().any(|f| f.parse::<f64>().is_err());
        if is_header {
            header = Some(fields.iter().map(|f| f.to_string()).collect());
            continue;
        }
        let at = Location::new(source).at_line(line_no);
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

fn read_points_json(text: &str, source: &str) -> IoResult<Points> {
    let at = Location::new(source);
    let value: Value = serde_json::from_str(text).map_err(|e| {
        IoError::syntax(at.clone().at_line(e.line()), format!("not valid JSON: {e}"))
    })?;
    let rows = match value {
        Value::Array(rows) => rows,
        Value::Object(mut m) => {
            if let Some(Value::Array(rows)) = m.remove("points") {
                rows
            } else {
                let dim = m.get("dim").and_then(Value::as_u64);
                let data = m.get("data").and_then(Value::as_array);
                let (Some(dim), Some(data)) = (dim, data) else {
                    return Err(IoError::syntax(
                        at,
                        "expected [[x, y], …], {\"points\": [[x, y], …]} or {\"dim\": 2, \"data\": [x0, y0, …]}",
                    ));
                };
                let mut flat = Vec::with_capacity(data.len());
                for (i, v) in data.iter().enumerate() {
                    flat.push(v.as_f64().ok_or_else(|| {
                        IoError::syntax(
                            at.clone().at_field(format!("data[{i}]")),
                            format!("{v} is not a number"),
                        )
                    })?);
                }
                let dim = usize::try_from(dim).unwrap_or(usize::MAX);
                return Points::from_flat(dim, flat).map_err(|e| IoError::Invalid { at, error: e });
            }
        }
        _ => {
            return Err(IoError::syntax(
                at,
                "expected an array of points [[x, y], …]",
            ))
        }
    };
    let lines = row_lines(text);
    let row_at = |i: usize| {
        let mut loc = at.clone();
        loc.line = lines.get(i).copied();
        loc
    };
    let mut out: Vec<Vec<f64>> = Vec::with_capacity(rows.len());
    for (i, row) in rows.iter().enumerate() {
        let Value::Array(coords) = row else {
            return Err(IoError::syntax(
                row_at(i).at_field(format!("[{i}]")),
                format!("point {i} is {row}, not an array of coordinates"),
            ));
        };
        let mut p = Vec::with_capacity(coords.len());
        for (k, c) in coords.iter().enumerate() {
            p.push(c.as_f64().ok_or_else(|| {
                IoError::syntax(
                    row_at(i).at_field(format!("[{i}][{k}]")),
                    format!("{c} is not a number"),
                )
            })?);
        }
        out.push(p);
    }
    if let Some(i) = out.iter().position(|r| r.len() != out[0].len()) {
        return Err(IoError::syntax(
            row_at(i),
            format!(
                "point {i} has {} coordinates, point 0 has {}; every point needs the same number",
                out[i].len(),
                out[0].len()
            ),
        ));
    }
    Points::from_rows(&out).map_err(|e| IoError::Invalid { at, error: e })
}

/// 1-based line of each innermost JSON array (`[` followed by `]` before any other `[`), in
/// order: the line of point `i` in `[[x, y], …]`, used only to point error messages at a line.
fn row_lines(text: &str) -> Vec<usize> {
    let mut out = Vec::new();
    let mut line = 1;
    let bytes = text.as_bytes();
    for (pos, &b) in bytes.iter().enumerate() {
        match b {
            b'\n' => line += 1,
            b'[' => {
                let innermost = bytes[pos + 1..]
                    .iter()
                    .find(|&&c| c == b'[' || c == b']')
                    .is_some_and(|&c| c == b']');
                if innermost {
                    out.push(line);
                }
            }
            _ => {}
        }
    }
    out
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
            "p.json:3: point 1 has 1 coordinates, point 0 has 2; every point needs the same number"
        );
        assert_eq!(row_lines("[[1,2],\n[3,4]]"), vec![1, 2]);
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
    fn number_lists() {
        assert_eq!(
            parse_number_list("0, 0.5 1", "--at").unwrap(),
            vec![0.0, 0.5, 1.0]
        );
        let e = parse_number_list("0, x", "--at").unwrap_err().to_string();
        assert_eq!(e, "--at: field `2`: cannot read \"x\" as a finite number");
    }
}
