//! Streaming JSON readers for point lists: rows `[[x, y], …]` or the flat form
//! `{"dim": 2, "data": [x0, y0, …]}` go straight into one flat `Vec<f64>` as the parser meets
//! the numbers, without the tree of `serde_json::Value`s (about 80 bytes a number) or a
//! `Vec` per row. Peak memory is the flat buffer (8 bytes a number) next to the text.

use std::fmt;

use serde::de::{
    DeserializeSeed, Deserializer, Error as _, IgnoredAny, MapAccess, SeqAccess, Visitor,
};

/// Points read from JSON: `rows` points of dimension `dim`, point-major in `data`.
#[derive(Debug, Default)]
pub(crate) struct FlatPoints {
    /// Dimension (0 when there are no rows).
    pub(crate) dim: usize,
    /// Coordinates, point-major.
    pub(crate) data: Vec<f64>,
    /// Given as `{"dim", "data"}` (the dimension is the file's, even with no data).
    pub(crate) flat_form: bool,
}

impl FlatPoints {
    /// The library's points (its constructor checks the dimension and the values).
    pub(crate) fn into_points(self) -> lekalo::Result<lekalo::Points> {
        if self.data.is_empty() && !self.flat_form {
            return lekalo::Points::from_rows::<Vec<f64>>(&[]);
        }
        lekalo::Points::from_flat(self.dim, self.data)
    }
}

/// Reads rows or the flat form; `field` names the value in messages (`control`, or empty for a
/// whole points file).
pub(crate) struct PointsSeed {
    pub(crate) field: &'static str,
    /// Accept `{"points": [...]}` too (points files).
    pub(crate) allow_points_key: bool,
}

fn at(field: &str, index: &str) -> String {
    if field.is_empty() {
        format!("field `{index}`")
    } else {
        format!("field `{field}{index}`")
    }
}

impl<'de> DeserializeSeed<'de> for PointsSeed {
    type Value = FlatPoints;
    fn deserialize<D: Deserializer<'de>>(self, d: D) -> Result<FlatPoints, D::Error> {
        d.deserialize_any(self)
    }
}

impl<'de> Visitor<'de> for PointsSeed {
    type Value = FlatPoints;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("points as rows [[x, y], …] or {\"dim\": 2, \"data\": [x0, y0, …]}")
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<FlatPoints, A::Error> {
        let mut out = FlatPoints::default();
        if let Some(n) = seq.size_hint() {
            out.data
                .try_reserve(n)
                .map_err(|_| A::Error::custom("out of memory for the points"))?;
        }
        let mut i = 0usize;
        while let Some(k) = seq.next_element_seed(RowSeed {
            field: self.field,
            row: i,
            expect: (i > 0).then_some(out.dim),
            out: &mut out.data,
        })? {
            if i == 0 {
                out.dim = k;
            }
            i += 1;
        }
        Ok(out)
    }

    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<FlatPoints, A::Error> {
        let mut dim: Option<usize> = None;
        let mut data: Option<Vec<f64>> = None;
        let mut rows: Option<FlatPoints> = None;
        while let Some(key) = map.next_key::<String>()? {
            match key.as_str() {
                "dim" if dim.is_none() => dim = Some(map.next_value()?),
                "data" if data.is_none() => data = Some(map.next_value()?),
                "points" if self.allow_points_key && rows.is_none() => {
                    rows = Some(map.next_value_seed(PointsSeed {
                        field: self.field,
                        allow_points_key: false,
                    })?);
                }
                "dim" | "data" | "points" => {
                    return Err(A::Error::custom(format!(
                        "{}: duplicate key `{key}`; each key may appear once",
                        at(self.field, &format!(".{key}"))
                    )))
                }
                other => {
                    map.next_value::<IgnoredAny>()?;
                    return Err(A::Error::custom(format!(
                        "{}: unknown key `{other}`; expected \"dim\" and \"data\"{}",
                        at(self.field, &format!(".{other}")),
                        if self.allow_points_key {
                            ", or \"points\""
                        } else {
                            ""
                        }
                    )));
                }
            }
        }
        match (dim, data, rows) {
            (None, None, Some(r)) => Ok(r),
            (Some(dim), Some(data), None) => Ok(FlatPoints {
                dim,
                data,
                flat_form: true,
            }),
            _ => Err(A::Error::custom(format!(
                "{}expected [[x, y], …]{} or {{\"dim\": 2, \"data\": [x0, y0, …]}}",
                if self.field.is_empty() {
                    String::new()
                } else {
                    format!("{}: ", at(self.field, ""))
                },
                if self.allow_points_key {
                    ", {\"points\": [[x, y], …]}"
                } else {
                    ""
                }
            ))),
        }
    }
}

/// One row, appended to `out`; its value is the row's length.
struct RowSeed<'a> {
    field: &'static str,
    row: usize,
    /// The dimension of point 0, for every later point.
    expect: Option<usize>,
    out: &'a mut Vec<f64>,
}

impl<'de> DeserializeSeed<'de> for RowSeed<'_> {
    type Value = usize;
    fn deserialize<D: Deserializer<'de>>(self, d: D) -> Result<usize, D::Error> {
        d.deserialize_any(self)
    }
}

impl<'de> Visitor<'de> for RowSeed<'_> {
    type Value = usize;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "point {} as an array of coordinates ({})",
            self.row,
            at(self.field, &format!("[{}]", self.row))
        )
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<usize, A::Error> {
        let mut k = 0usize;
        while let Some(v) = seq.next_element_seed(Number {
            field: self.field,
            row: self.row,
            col: k,
        })? {
            if self.out.len() == self.out.capacity() {
                self.out
                    .try_reserve(self.out.len().max(16))
                    .map_err(|_| A::Error::custom("out of memory for the points"))?;
            }
            self.out.push(v);
            k += 1;
        }
        match self.expect {
            Some(d) if d != k => Err(A::Error::custom(format!(
                "{}: point {} has {k} coordinates, point 0 has {d}; every point needs the same number",
                at(self.field, &format!("[{}]", self.row)),
                self.row
            ))),
            _ => Ok(k),
        }
    }

    fn visit_f64<E: serde::de::Error>(self, v: f64) -> Result<usize, E> {
        Err(self.not_a_row(&v.to_string()))
    }
    fn visit_u64<E: serde::de::Error>(self, v: u64) -> Result<usize, E> {
        Err(self.not_a_row(&v.to_string()))
    }
    fn visit_i64<E: serde::de::Error>(self, v: i64) -> Result<usize, E> {
        Err(self.not_a_row(&v.to_string()))
    }
    fn visit_str<E: serde::de::Error>(self, v: &str) -> Result<usize, E> {
        Err(self.not_a_row(&format!("{v:?}")))
    }
    fn visit_bool<E: serde::de::Error>(self, v: bool) -> Result<usize, E> {
        Err(self.not_a_row(&v.to_string()))
    }
    fn visit_unit<E: serde::de::Error>(self) -> Result<usize, E> {
        Err(self.not_a_row("null"))
    }
    fn visit_map<A: MapAccess<'de>>(self, _: A) -> Result<usize, A::Error> {
        Err(self.not_a_row("an object"))
    }
}

impl RowSeed<'_> {
    fn not_a_row<E: serde::de::Error>(&self, what: &str) -> E {
        E::custom(format!(
            "{}: point {} is {what}, not an array of coordinates",
            at(self.field, &format!("[{}]", self.row)),
            self.row
        ))
    }
}

/// One coordinate: a JSON number.
struct Number {
    field: &'static str,
    row: usize,
    col: usize,
}

impl<'de> DeserializeSeed<'de> for Number {
    type Value = f64;
    fn deserialize<D: Deserializer<'de>>(self, d: D) -> Result<f64, D::Error> {
        d.deserialize_any(self)
    }
}

impl Number {
    fn not_a_number<E: serde::de::Error>(&self, what: &str) -> E {
        E::custom(format!(
            "{}: {what} is not a number",
            at(self.field, &format!("[{}][{}]", self.row, self.col))
        ))
    }
}

impl<'de> Visitor<'de> for Number {
    type Value = f64;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("a number")
    }
    fn visit_f64<E: serde::de::Error>(self, v: f64) -> Result<f64, E> {
        Ok(v)
    }
    #[allow(clippy::cast_precision_loss)] // JSON integers are read as the nearest f64
    fn visit_u64<E: serde::de::Error>(self, v: u64) -> Result<f64, E> {
        Ok(v as f64)
    }
    #[allow(clippy::cast_precision_loss)] // JSON integers are read as the nearest f64
    fn visit_i64<E: serde::de::Error>(self, v: i64) -> Result<f64, E> {
        Ok(v as f64)
    }
    fn visit_str<E: serde::de::Error>(self, v: &str) -> Result<f64, E> {
        Err(self.not_a_number(&format!("{v:?}")))
    }
    fn visit_bool<E: serde::de::Error>(self, v: bool) -> Result<f64, E> {
        Err(self.not_a_number(&v.to_string()))
    }
    fn visit_unit<E: serde::de::Error>(self) -> Result<f64, E> {
        Err(self.not_a_number("null"))
    }
    fn visit_seq<A: SeqAccess<'de>>(self, _: A) -> Result<f64, A::Error> {
        Err(self.not_a_number("an array"))
    }
    fn visit_map<A: MapAccess<'de>>(self, _: A) -> Result<f64, A::Error> {
        Err(self.not_a_number("an object"))
    }
}

/// `deserialize_with` for a `control` field.
pub(crate) fn control<'de, D: Deserializer<'de>>(d: D) -> Result<FlatPoints, D::Error> {
    PointsSeed {
        field: "control",
        allow_points_key: false,
    }
    .deserialize(d)
}

/// The message of a `serde_json` error without its " at line L column C" suffix.
pub(crate) fn message(e: &serde_json::Error) -> String {
    let s = e.to_string();
    match s.rfind(" at line ") {
        Some(i) => s[..i].to_string(),
        None => s,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn read(text: &str) -> Result<FlatPoints, String> {
        let mut de = serde_json::Deserializer::from_str(text);
        PointsSeed {
            field: "",
            allow_points_key: true,
        }
        .deserialize(&mut de)
        .map_err(|e| format!("{}: {}", e.line(), message(&e)))
    }

    #[test]
    fn rows_flat_and_named_forms() {
        let r = read("[[1, 2], [3, 4.5]]").unwrap();
        assert_eq!((r.dim, r.data), (2, vec![1.0, 2.0, 3.0, 4.5]));
        let r = read(r#"{"dim": 3, "data": [1, 2, 3]}"#).unwrap();
        assert_eq!((r.dim, r.data), (3, vec![1.0, 2.0, 3.0]));
        let r = read(r#"{"points": [[-1], [2]]}"#).unwrap();
        assert_eq!((r.dim, r.data), (1, vec![-1.0, 2.0]));
        assert!(read("[]").unwrap().into_points().is_err(), "no points");
    }

    #[test]
    fn errors_name_line_and_field() {
        assert_eq!(
            read("[[0,0],\n [1,\"a\"]]").unwrap_err(),
            "2: field `[1][1]`: \"a\" is not a number"
        );
        assert_eq!(
            read("[[0,0],\n[1]]").unwrap_err(),
            "2: field `[1]`: point 1 has 1 coordinates, point 0 has 2; every point needs the same number"
        );
        assert!(read("[[0,0], 3]").unwrap_err().contains("point 1 is 3"));
        let e = read(r#"{"dim": 2, "dim": 2, "data": []}"#).unwrap_err();
        assert!(e.contains("duplicate key `dim`"), "{e}");
        let e = read(r#"{"dims": 2}"#).unwrap_err();
        assert!(e.contains("unknown key `dims`"), "{e}");
    }
}
