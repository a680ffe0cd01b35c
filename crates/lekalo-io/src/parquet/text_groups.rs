//! Point sets from a text table with a key column: the long layout of a Parquet batch written
//! as CSV (`group,x,y` then one row a point), so that a batch can be made from text
//! (`lekalo convert scans.csv -o scans.parquet`).
//!
//! The rules are those of a points file ([`crate::points_in`]): blank and `#` lines skipped,
//! fields split at `,`/`;` when the line has one, else at blanks, each trimmed; here the first
//! other line must be a header naming the columns, one of them the key. The keys are integers
//! when every key is one (as `i64`), strings otherwise; the other columns are the coordinates,
//! in the file's order, every one finite. The rows of a group are consecutive.

use std::collections::HashMap;

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
    // a Parquet column per name: two of one name (`group,x,x`, or the key again, `group,group,x`)
    // made a file whose columns cannot be told apart, or stopped the writer on the key's
    // integer encoding asked of a column of numbers
    let mut columns: HashMap<&str, usize> = HashMap::with_capacity(names.len());
    for (k, n) in names.iter().enumerate() {
        if let Some(&j) = columns.get(n) {
            return Err(IoError::syntax(
                at(header_no).at_field(*n),
                format!(
                    "the header `{header}` names `{n}` twice (columns {} and {}); give every \
                     column its own name",
                    j + 1,
                    k + 1
                ),
            ));
        }
        columns.insert(n, k);
    }
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
    // each row's key text, its line, and its coordinates into one flat buffer; the keys seen,
    // with their first lines, in a map (a table of 10^6 groups was quadratic with a search)
    let mut keys: Vec<(String, usize, usize)> = Vec::new(); // key, line, rows of the run
    let mut seen: HashMap<String, usize> = HashMap::new();
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
                if let Some(first) = seen.get(row_key) {
                    return Err(IoError::syntax(
                        at(line_no).at_field(key),
                        format!(
                            "the key {row_key} comes back after other keys (its rows began at \
                             line {first}); the rows of a group must be consecutive: sort the \
                             rows by the key"
                        ),
                    ));
                }
                seen.insert(row_key.to_string(), line_no);
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
    drop(seen);
    let ints: Option<Vec<i64>> = keys.iter().map(|(k, _, _)| k.parse().ok()).collect();
    if let Some(ints) = &ints {
        same_integer(ints, &keys, source, key)?;
    }
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

/// An error if two keys written differently are one integer (`1`, `01`, `+1`), which would
/// make two groups of one key in the output: the rows of a group must be consecutive, and its
/// key written one way.
fn same_integer(
    ints: &[i64],
    keys: &[(String, usize, usize)],
    source: &str,
    key: &str,
) -> IoResult<()> {
    let mut first: HashMap<i64, usize> = HashMap::with_capacity(ints.len());
    for (i, &v) in ints.iter().enumerate() {
        if let Some(&j) = first.get(&v) {
            let ((a, a_line, _), (b, b_line, _)) = (&keys[j], &keys[i]);
            return Err(IoError::syntax(
                Location::new(source).at_line(*b_line).at_field(key),
                format!(
                    "the key {b} is the integer {v}, as is the key {a} of line {a_line}: two \
                     groups would have one key; write the key of a group one way, and its rows \
                     one after another"
                ),
            ));
        }
        first.insert(v, i);
    }
    Ok(())
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
            (
                "group,x,x\n1,0,0\n",
                "s.csv:1: field `x`: the header `group,x,x` names `x` twice (columns 2 and 3)",
            ),
            (
                "group,group,x\n1,0,0\n",
                "s.csv:1: field `group`: the header `group,group,x` names `group` twice",
            ),
            (
                "group,x,y\n1,0,0\n01,1,1\n",
                "s.csv:3: field `group`: the key 01 is the integer 1, as is the key 1 of line 2",
            ),
            (
                "group,x,y\n-0,0,0\n+7,1,1\n0,2,2\n",
                "s.csv:4: field `group`: the key 0 is the integer 0, as is the key -0 of line 2",
            ),
        ];
        for (text, want) in cases {
            let e = read_text_point_groups(text, "s.csv", "group").unwrap_err();
            assert!(e.to_string().contains(want), "{text:?}: {e}");
        }
    }

    /// A key column of 200,000 distinct keys: each new key was searched for among all before
    /// it (quadratic: this test took minutes, 10^6 keys did not finish); with the keys in a
    /// map every group is made and a key that comes back after 199,999 others is still found.
    #[test]
    fn many_distinct_keys_read_in_linear_time() {
        let n = 200_000;
        let mut text = String::from("group,x,y\n");
        for i in 0..n {
            text.push_str(&format!("{i},{i},1\n"));
        }
        let (_, g) = read_text_point_groups(&text, "s.csv", "group").unwrap();
        assert_eq!(g.len(), n);
        assert_eq!(g[n - 1].0, GroupKey::Int(199_999));
        text.push_str("0,5,5\n");
        let e = read_text_point_groups(&text, "s.csv", "group").unwrap_err();
        assert!(e.to_string().contains("the key 0 comes back"), "{e}");
    }
}
