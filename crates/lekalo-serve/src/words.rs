//! The options every front end shares, read from the library's vocabulary
//! ([`lekalo::vocabulary`]): `"knots": "at-params"`, `"parametrization": "centripetal"`,
//! `"end": "natural"`, `"rule": "greville"`. Older spellings are still read; an unknown word
//! is a 400 naming the field and listing the words.

use lekalo::vocabulary::Vocabulary;

use crate::error::{ApiError, ApiResult};

/// The value of the request field `field`, or `default` when the request leaves it out.
pub(crate) fn word<T: Copy + PartialEq + 'static>(
    vocabulary: &'static Vocabulary<T>,
    field: &str,
    text: Option<&str>,
    default: T,
) -> ApiResult<T> {
    match text {
        None => Ok(default),
        Some(t) => vocabulary.parse(t).map(|w| w.value).map_err(|_| {
            ApiError::bad(
                field,
                format!("unknown value \"{t}\"; use one of {}", vocabulary.one_of()),
            )
        }),
    }
}
