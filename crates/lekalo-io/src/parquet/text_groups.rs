//! Point sets from a text table with a key column: the long layout of a Parquet batch written
//! as CSV (`group,x,y` then one row a point), so that a batch can be made from text
//! (`lekalo convert scans.csv -o scans.parquet`).
//!
//! The rules are those of a points file ([`crate::points_in`]): blank and `#` lines skipped,
//! fields split at `,`/`;` when the line has one, else at blanks, each trimmed; here the first
//! other line must be a header naming the columns, one of them the key. The keys are integers
//! when every key is one (as `i64`), strings otherwise; the other columns are the coordinates,
//! in the file's order, every one finite. The rows of a group are consecutive.

use lekalo::Points;

use super::GroupKey;
use crate::error::{IoError, IoResult, Location};
use crate::text_points::Fields;

/// The coordinate columns' names and the keyed point sets of a table.
pub type TextPointGroups = (Vec<String>, Vec<(GroupKey, Points)>);

/// The coordinate columns' names and the point sets of `text` (named `source` in errors),
/// keyed by its column `key`, in the order of their first rows.
///
/// # Errors
/// [`IoError::Syntax`] naming the line (and column): no header, no column `key` in it, a row
/// with another number of fields than the header, a coordinate that is not a finite number, a
/// key that comes back after other keys, no coordinate column or no row.
pub fn read_text_point_groups(text: &str, source: &str, key: &str) -> IoResult<TextPointGroups> {
    let at = |line: usize| Location::new(source).at_line(line);
    let mut lines = text
        .lines()
        .enumerate()
        .map(|(i, l)| (i + 1, l.trim()))
        .filter(|(_, l)| !l.is_empty() && !l.starts_with('#'));
    let Some((header_no, header)) = lines.next() else {
        return Err(IoError::syntax(
            Location::new(source),
            format!("no rows; write a header `{key},x,y` and then one row a point"),
        ));
    };
    let names: Vec<&str> = Fields::of(header).collect();
    let Some(key_col) = names.iter().position(|n| *n == key) else {
        return Err(IoError::syntax(
            at(header_no),
            format!(
                "the header `{header}` has no key column `{key}`; name the column that groups \
                 the points `{key}`, or give its name with --group-column NAME"
            ),
        ));
    };
    let coords: Vec<String> = names
        .iter()
        .enumerate()
        .filter(|(k, _)| *k != key_col)
        .map(|(_, n)| (*n).to_string())
        .collect();
    if coords.is_empty() {
        return Err(IoError::syntax(
            at(header_no),
            format!("the header `{header}` has no coordinate column; write `{key},x,y`"),
        ));
    }
    // each row's key text, its line, and its coordinates into one flat buffer
    let mut keys: Vec<(String, usize, usize)> = Vec::new(); // key, line, rows of the run
    let mut data: Vec<f64> = Vec::new();
    for (line_no, line) in lines {
        let mut n = 0usize;
        let mut row_key = None;
        for (k, field) in Fields::of(line).enumerate() {
            n += 1;
            if k == key_col {
                row_key = Some(field);
            } else if k < names.len() {
                match field.parse::<f64>() {
                    Ok(v) if v.is_finite() => data.push(v),
                    _ => {
                        return Err(IoError::syntax(
                            at(line_no).at_field(names[k]),
                            format!("cannot read \"{field}\" as a finite number"),
                        ))
                    }
                }
            }
        }
        if n != names.len() {
            return Err(IoError::syntax(
                at(line_no),
                format!(
                    "{n} fields, but the header names {}; every row needs a key and the same \
                     coordinates",
                    names.len()
                ),
            ));
        }
        let row_key = row_key.unwrap_or_default();
        match keys.last_mut() {
            Some((last, _, rows)) if last == row_key => *rows += 1,
            _ => {
                if let Some((_, first, _)) = keys.iter().find(|(k, _, _)| k == row_key) {
                    return Err(IoError::syntax(
                        at(line_no).at_field(key),
                        format!(
                            "the key {row_key} comes back after other keys (its rows began at \
                             line {first}); the rows of a group must be consecutive: sort the \
                             rows by the key"
                        ),
                    ));
                }
                keys.push((row_key.to_string(), line_no, 1));
            }
        }
    }
    if keys.is_empty() {
        return Err(IoError::syntax(
            at(header_no),
            "a header but no rows; write one row a point under it",
        ));
    }
    let ints: Option<Vec<i64>> = keys.iter().map(|(k, _, _)| k.parse().ok()).collect();
    let dim = coords.len();
    let mut groups = Vec::with_capacity(keys.len());
    let mut start = 0usize;
    for (i, (k, line, rows)) in keys.iter().enumerate() {
        let end = start + rows * dim;
        let points = Points::from_flat(dim, data[start..end].to_vec()).map_err(|error| {
            IoError::Invalid {
                at: at(*line),
                error,
            }
        })?;
        let key = match &ints {
            Some(v) => GroupKey::Int(v[i]),
            None => GroupKey::Str(k.clone()),
        };
        groups.push((key, points));
        start = end;
    }
    Ok((coords, groups))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rows_become_groups_in_order_with_integer_or_string_keys() {
        let (names, g) = read_text_point_groups(
            "# scans\ngroup,x,y\n1,0,0\n1,1,2\n\n2,5,5\n",
            "s.csv",
            "group",
        )
        .unwrap();
        assert_eq!(names, ["x", "y"]);
        assert_eq!(g.len(), 2);
        assert_eq!(g[0].0, GroupKey::Int(1));
        assert_eq!(g[0].1.as_slice(), &[0.0, 0.0, 1.0, 2.0]);
        assert_eq!((g[1].0.clone(), g[1].1.len()), (GroupKey::Int(2), 1));
        // the key may be any column; a key that is not an integer makes every key a string
        let (names, g) =
            read_text_point_groups("x y id\n0 0 a\n1 1 a\n2 2 7\n", "s.txt", "id").unwrap();
        assert_eq!(names, ["x", "y"]);
        assert_eq!(g[0].0, GroupKey::Str("a".into()));
        assert_eq!(g[1].0, GroupKey::Str("7".into()));
    }

    #[test]
    fn errors_name_the_line_the_column_and_the_fix() {
        let cases = [
            ("", "no rows"),
            (
                "x,y\n0,0\n",
                "s.csv:1: the header `x,y` has no key column `group`",
            ),
            ("group\n1\n", "no coordinate column"),
            ("group,x,y\n", "a header but no rows"),
            (
                "group,x,y\n1,0\n",
                "s.csv:2: 2 fields, but the header names 3",
            ),
            (
                "group,x,y\n1,0,nan\n",
                "s.csv:2: field `y`: cannot read \"nan\"",
            ),
            (
                "group,x,y\n1,0,0\n2,0,0\n1,1,1\n",
                "s.csv:4: field `group`: the key 1 comes back after other keys (its rows began \
                 at line 2)",
            ),
        ];
        for (text, want) in cases {
            let e = read_text_point_groups(text, "s.csv", "group").unwrap_err();
            assert!(e.to_string().contains(want), "{text:?}: {e}");
        }
    }
}
