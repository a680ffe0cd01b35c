//! Numbers of a request in the editor's words. serde names the Rust type it expected
//! ("expected usize", "expected f64"), which means nothing next to the degree field of a web
//! page; these readers take the same JSON and say "a whole number ≥ 0" and "a number" instead.
//! Each is a `#[serde(deserialize_with = …)]` of a request field, so the fields keep their
//! types. Fractional counts such as `2.0` are read as the whole number they are (JavaScript's
//! numbers have no integer type).

use std::fmt;

use serde::de::{self, Deserialize, Deserializer, Unexpected, Visitor};

/// A count, size or order: a whole number ≥ 0.
struct Count(usize);

/// A number: any finite or infinite JSON number (finiteness is checked where it is used).
struct Num(f64);

struct CountVisitor;

impl Visitor<'_> for CountVisitor {
    type Value = Count;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("a whole number ≥ 0 (0, 1, 2, …)")
    }

    fn visit_u64<E: de::Error>(self, v: u64) -> Result<Count, E> {
        usize::try_from(v)
            .map(Count)
            .map_err(|_| E::invalid_value(Unexpected::Unsigned(v), &self))
    }

    fn visit_i64<E: de::Error>(self, v: i64) -> Result<Count, E> {
        usize::try_from(v)
            .map(Count)
            .map_err(|_| E::invalid_value(Unexpected::Signed(v), &self))
    }

    fn visit_f64<E: de::Error>(self, v: f64) -> Result<Count, E> {
        // a whole number written with a fraction part (2.0) is that number; the bound keeps
        // the conversion exact
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        if v.fract() == 0.0 && (0.0..9.0e15).contains(&v) {
            return Ok(Count(v as usize));
        }
        Err(E::invalid_value(Unexpected::Float(v), &self))
    }
}

impl<'de> Deserialize<'de> for Count {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_any(CountVisitor)
    }
}

struct NumVisitor;

impl Visitor<'_> for NumVisitor {
    type Value = Num;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("a number")
    }

    #[allow(clippy::cast_precision_loss)] // JSON integers are read as doubles, as JavaScript does
    fn visit_u64<E: de::Error>(self, v: u64) -> Result<Num, E> {
        Ok(Num(v as f64))
    }

    #[allow(clippy::cast_precision_loss)]
    fn visit_i64<E: de::Error>(self, v: i64) -> Result<Num, E> {
        Ok(Num(v as f64))
    }

    fn visit_f64<E: de::Error>(self, v: f64) -> Result<Num, E> {
        Ok(Num(v))
    }
}

impl<'de> Deserialize<'de> for Num {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_any(NumVisitor)
    }
}

/// A field whose value is one word of a short list (`"smoothing": "gcv"`), read by [`choice`]:
/// a misspelt word is answered in the editor's words, as [`crate::words`] answers the
/// library's vocabularies, not in serde's ("unknown variant").
pub(crate) trait Choice: Sized + Copy + 'static {
    /// The words and the values they name, in the order the message lists them.
    const WORDS: &'static [(&'static str, Self)];
}

struct ChoiceVisitor<T>(std::marker::PhantomData<T>);

impl<T: Choice> Visitor<'_> for ChoiceVisitor<T> {
    type Value = T;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "one of {}", words_of::<T>())
    }

    fn visit_str<E: de::Error>(self, v: &str) -> Result<T, E> {
        T::WORDS
            .iter()
            .find(|(w, _)| *w == v)
            .map(|(_, value)| *value)
            .ok_or_else(|| {
                E::custom(format!(
                    "unknown value \"{v}\"; use one of {}",
                    words_of::<T>()
                ))
            })
    }
}

fn words_of<T: Choice>() -> String {
    let words: Vec<&str> = T::WORDS.iter().map(|(w, _)| *w).collect();
    words.join(", ")
}

/// One word of `T`'s list ([`Choice`]).
pub(crate) fn choice<'de, D: Deserializer<'de>, T: Choice>(d: D) -> Result<T, D::Error> {
    d.deserialize_str(ChoiceVisitor(std::marker::PhantomData))
}

/// A whole number ≥ 0.
pub(crate) fn count<'de, D: Deserializer<'de>>(d: D) -> Result<usize, D::Error> {
    Count::deserialize(d).map(|c| c.0)
}

/// An optional whole number ≥ 0 (`null` is none).
pub(crate) fn opt_count<'de, D: Deserializer<'de>>(d: D) -> Result<Option<usize>, D::Error> {
    Option::<Count>::deserialize(d).map(|c| c.map(|c| c.0))
}

/// An optional list of whole numbers ≥ 0.
pub(crate) fn opt_counts<'de, D: Deserializer<'de>>(d: D) -> Result<Option<Vec<usize>>, D::Error> {
    Option::<Vec<Count>>::deserialize(d).map(|v| v.map(|v| v.into_iter().map(|c| c.0).collect()))
}

/// A number.
pub(crate) fn number<'de, D: Deserializer<'de>>(d: D) -> Result<f64, D::Error> {
    Num::deserialize(d).map(|n| n.0)
}

/// An optional number (`null` is none).
pub(crate) fn opt_number<'de, D: Deserializer<'de>>(d: D) -> Result<Option<f64>, D::Error> {
    Option::<Num>::deserialize(d).map(|n| n.map(|n| n.0))
}

/// A list of numbers.
pub(crate) fn numbers<'de, D: Deserializer<'de>>(d: D) -> Result<Vec<f64>, D::Error> {
    Vec::<Num>::deserialize(d).map(|v| v.into_iter().map(|n| n.0).collect())
}

/// An optional list of numbers.
pub(crate) fn opt_numbers<'de, D: Deserializer<'de>>(d: D) -> Result<Option<Vec<f64>>, D::Error> {
    Option::<Vec<Num>>::deserialize(d).map(|v| v.map(|v| v.into_iter().map(|n| n.0).collect()))
}

/// Points: a list of rows of numbers.
pub(crate) fn rows<'de, D: Deserializer<'de>>(d: D) -> Result<Vec<Vec<f64>>, D::Error> {
    Vec::<Vec<Num>>::deserialize(d).map(|v| {
        v.into_iter()
            .map(|r| r.into_iter().map(|n| n.0).collect())
            .collect()
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(Debug, serde::Deserialize)]
    struct R {
        #[serde(deserialize_with = "count")]
        degree: usize,
        #[serde(default, deserialize_with = "rows")]
        points: Vec<Vec<f64>>,
    }

    #[derive(Debug, Clone, Copy, PartialEq, Eq)]
    enum Side {
        Left,
        Right,
    }

    impl Choice for Side {
        const WORDS: &'static [(&'static str, Self)] =
            &[("left", Self::Left), ("right", Self::Right)];
    }

    #[derive(Debug, serde::Deserialize)]
    struct S {
        #[serde(deserialize_with = "choice")]
        side: Side,
    }

    #[test]
    fn a_choice_is_read_and_a_misspelt_word_refused_with_the_words() {
        let s: S = serde_json::from_str(r#"{"side": "right"}"#).expect("a word of the list");
        assert_eq!(s.side, Side::Right, "the value of the word");
        for (text, needle) in [
            (
                r#"{"side": "rigth"}"#,
                "unknown value \"rigth\"; use one of left, right",
            ),
            (r#"{"side": 2}"#, "expected one of left, right"),
        ] {
            let e = serde_json::from_str::<S>(text)
                .expect_err("refused")
                .to_string();
            assert!(e.contains(needle), "{text}: {e}");
            assert!(!e.contains("variant"), "{text}: serde's word: {e}");
        }
    }

    fn message(text: &str) -> String {
        serde_json::from_str::<R>(text)
            .map(|r| format!("{r:?}"))
            .unwrap_or_else(|e| e.to_string())
    }

    #[test]
    fn counts_and_numbers_are_read_and_refused_in_the_editor_s_words() {
        let r: R = serde_json::from_str(r#"{"degree": 3, "points": [[0, 1.5], [-2, 1e3]]}"#)
            .expect("a valid request");
        assert_eq!(r.degree, 3, "an integer");
        assert_eq!(
            r.points,
            vec![vec![0.0, 1.5], vec![-2.0, 1000.0]],
            "the points"
        );
        let r: R = serde_json::from_str(r#"{"degree": 2.0}"#).expect("2.0 is a whole number");
        assert_eq!(r.degree, 2, "a whole number with a fraction part");
        for (text, says) in [
            (
                r#"{"degree": 2.5}"#,
                "floating point `2.5`, expected a whole number ≥ 0",
            ),
            (
                r#"{"degree": -1}"#,
                "integer `-1`, expected a whole number ≥ 0",
            ),
            (
                r#"{"degree": "3"}"#,
                "string \"3\", expected a whole number ≥ 0",
            ),
            (
                r#"{"degree": 1, "points": [[0, "a"]]}"#,
                "string \"a\", expected a number",
            ),
        ] {
            let m = message(text);
            assert!(m.contains(says), "{text}: {m}");
            assert!(!m.contains("usize") && !m.contains("f64"), "{text}: {m}");
        }
    }
}
