//! The words of the library's choices, defined once for every front end: each option that the
//! command line, the JSON API of the editor and the Python package share has one canonical
//! spelling per value (lower case, words joined by `-`, as SciPy's `"not-a-knot"`), and the
//! older spellings of each front end are read as aliases that the front end reports as
//! deprecated (`docs/cli.md`, "The option vocabulary").
//!
//! A front end reads a word with [`Vocabulary::parse`], shows the choices with
//! [`Vocabulary::one_of`], and names a refused word by the option's key
//! ([`Vocabulary::key`]), which it maps to its own name (`--knots`, `"knots"`, `knots=`).
//!
//! ```
//! use lekalo::{vocabulary, KnotPlacement};
//! let w = vocabulary::KNOT_PLACEMENT.parse("at-params")?;
//! assert_eq!((w.value, w.old_spelling), (KnotPlacement::AtParameters, false));
//! let old = vocabulary::KNOT_PLACEMENT.parse("at_parameters")?;
//! assert_eq!((old.value, old.old_spelling), (KnotPlacement::AtParameters, true));
//! assert_eq!(KnotPlacement::AtParameters.to_string(), "at-params");
//! let e = vocabulary::KNOT_PLACEMENT.parse("everywhere").unwrap_err().to_string();
//! assert_eq!(e, "invalid knots: \"everywhere\" is not one of auto, averaged, uniform, at-params");
//! # Ok::<(), lekalo::Error>(())
//! ```

use crate::fit::KnotRounds;
use crate::Arg;
use crate::{Direction, EndCondition, Error, KnotPlacement, Parametrization, Result, TauRule};

/// One value of an option: its canonical name, the value, and what it means (for help texts).
#[derive(Debug)]
pub struct Word<T: 'static> {
    /// The canonical spelling.
    pub name: &'static str,
    /// The value it stands for.
    pub value: T,
    /// One line on what it means, for `--help` and docstrings.
    pub meaning: &'static str,
}

/// The words of one option: canonical words first, then the older spellings still read.
#[derive(Debug)]
pub struct Vocabulary<T: 'static> {
    /// The option's key: the argument of the errors it gives ([`Error::arg`]), which each
    /// front end maps to its own name for the option.
    pub key: Arg,
    /// The canonical words, in the order help texts list them.
    pub words: &'static [Word<T>],
    /// Older spellings, each with the value it stands for.
    pub aliases: &'static [(&'static str, T)],
}

/// A word read by [`Vocabulary::parse`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Spelled<T> {
    /// The value.
    pub value: T,
    /// Whether an older spelling was used (the front end says so and names the canonical one,
    /// [`Vocabulary::name`]).
    pub old_spelling: bool,
}

impl<T: Copy + PartialEq + 'static> Vocabulary<T> {
    /// Reads `text` (surrounding white space and letter case ignored).
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] about [`Vocabulary::key`] ([`Error::arg`]), listing the
    /// canonical words.
    pub fn parse(&self, text: &str) -> Result<Spelled<T>> {
        let word = text.trim().to_ascii_lowercase();
        if let Some(w) = self.words.iter().find(|w| w.name == word) {
            return Ok(Spelled {
                value: w.value,
                old_spelling: false,
            });
        }
        if let Some((_, v)) = self.aliases.iter().find(|(a, _)| *a == word) {
            return Ok(Spelled {
                value: *v,
                old_spelling: true,
            });
        }
        Err(Error::InvalidArgument {
            what: self.key.into(),
            reason: format!("\"{}\" is not one of {}", text.trim(), self.one_of()),
        })
    }

    /// The canonical name of `value`, if it has one.
    #[must_use]
    pub fn name(&self, value: T) -> Option<&'static str> {
        self.words.iter().find(|w| w.value == value).map(|w| w.name)
    }

    /// The canonical names, in order.
    #[must_use]
    pub fn names(&self) -> Vec<&'static str> {
        self.words.iter().map(|w| w.name).collect()
    }

    /// The canonical names as a list for messages: `"auto, averaged, uniform, at-params"`.
    #[must_use]
    pub fn one_of(&self) -> String {
        self.names().join(", ")
    }
}

/// Parameter values of interpolation points (document 000 §1; P&T eq. 9.4–9.6). A number is
/// read by the front ends as the exponent of [`Parametrization::Exponent`].
pub const PARAMETRIZATION: Vocabulary<Parametrization> = Vocabulary {
    key: Arg::Parametrization,
    words: &[
        Word {
            name: "uniform",
            value: Parametrization::Uniform,
            meaning: "equally spaced parameters k/n (exponent 0)",
        },
        Word {
            name: "chord",
            value: Parametrization::ChordLength,
            meaning: "chord length (exponent 1), the usual choice",
        },
        Word {
            name: "centripetal",
            value: Parametrization::Centripetal,
            meaning: "square roots of the chord lengths (exponent 1/2), for sharp turns",
        },
    ],
    aliases: &[
        ("chord-length", Parametrization::ChordLength),
        ("chord_length", Parametrization::ChordLength),
    ],
};

/// Knot placement of interpolation (document 000 eq. 2, 3, 4, 8).
pub const KNOT_PLACEMENT: Vocabulary<KnotPlacement> = Vocabulary {
    key: Arg::Knots,
    words: &[
        Word {
            name: "auto",
            value: KnotPlacement::Auto,
            meaning: "chosen by degree and end condition (averaged, or at the parameters for C² cubics with end derivatives)",
        },
        Word {
            name: "averaged",
            value: KnotPlacement::Averaged,
            meaning: "averages of the parameters (eq. 3; eq. 4 with end derivatives)",
        },
        Word {
            name: "uniform",
            value: KnotPlacement::Uniform,
            meaning: "uniform interior knots (eq. 2)",
        },
        Word {
            name: "at-params",
            value: KnotPlacement::AtParameters,
            meaning: "knots at the parameters (eq. 8, cubics with end derivatives)",
        },
    ],
    aliases: &[
        ("at_params", KnotPlacement::AtParameters),
        ("at-parameters", KnotPlacement::AtParameters),
        ("at_parameters", KnotPlacement::AtParameters),
    ],
};

/// The kind of end condition of interpolation (document 000 §1–4, closed curves); the
/// derivatives themselves are separate arguments ([`EndKind::condition`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum EndKind {
    /// [`EndCondition::Free`].
    #[default]
    Free,
    /// [`EndCondition::FirstDerivatives`].
    Derivatives,
    /// [`EndCondition::SecondDerivatives`].
    Second,
    /// [`EndCondition::Natural`].
    Natural,
    /// [`EndCondition::Periodic`].
    Periodic,
}

impl EndKind {
    /// The end condition of this kind with the derivatives at the start and the end, which
    /// [`EndKind::Derivatives`] and [`EndKind::Second`] need and the others refuse.
    ///
    /// ```
    /// use lekalo::{vocabulary::EndKind, EndCondition};
    /// let e = EndKind::Derivatives.condition(Some(vec![1.0, 0.0]), Some(vec![0.0, 1.0]))?;
    /// assert_eq!(e, EndCondition::FirstDerivatives { start: vec![1.0, 0.0], end: vec![0.0, 1.0] });
    /// assert!(EndKind::Natural.condition(Some(vec![1.0]), None).is_err());
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] about [`Arg::EndDerivatives`] when a derivative is missing
    /// for a kind that needs both or given to one that uses none.
    pub fn condition(self, start: Option<Vec<f64>>, end: Option<Vec<f64>>) -> Result<EndCondition> {
        let name = END_CONDITION.name(self).unwrap_or("free");
        let both = |start: Option<Vec<f64>>, end: Option<Vec<f64>>| match (start, end) {
            (Some(a), Some(b)) => Ok((a, b)),
            _ => Err(Error::InvalidArgument {
                what: Arg::EndDerivatives.into(),
                reason: format!(
                    "the end condition {name} needs a derivative at the start and at the end, \
                     each a vector of the points' dimension"
                ),
            }),
        };
        let unused = start.is_some() || end.is_some();
        Ok(match self {
            EndKind::Derivatives => {
                let (start, end) = both(start, end)?;
                EndCondition::FirstDerivatives { start, end }
            }
            EndKind::Second => {
                let (start, end) = both(start, end)?;
                EndCondition::SecondDerivatives { start, end }
            }
            _ if unused => {
                return Err(Error::InvalidArgument {
                    what: Arg::EndDerivatives.into(),
                    reason: format!(
                        "end derivatives are used by the end conditions derivatives and second, \
                         not by {name}"
                    ),
                })
            }
            EndKind::Free => EndCondition::Free,
            EndKind::Natural => EndCondition::Natural,
            EndKind::Periodic => EndCondition::Periodic,
        })
    }
}

/// End conditions of interpolation (document 000 §1–4).
pub const END_CONDITION: Vocabulary<EndKind> = Vocabulary {
    key: Arg::End,
    words: &[
        Word {
            name: "free",
            value: EndKind::Free,
            meaning: "no extra condition (§1)",
        },
        Word {
            name: "derivatives",
            value: EndKind::Derivatives,
            meaning: "given first derivatives at both ends (§2, §3)",
        },
        Word {
            name: "second",
            value: EndKind::Second,
            meaning: "given second derivatives at both ends (§4, cubics)",
        },
        Word {
            name: "natural",
            value: EndKind::Natural,
            meaning: "zero second derivatives: the natural cubic spline",
        },
        Word {
            name: "periodic",
            value: EndKind::Periodic,
            meaning: "a closed curve, C^(p-1) at the seam",
        },
    ],
    aliases: &[
        ("first", EndKind::Derivatives),
        ("first-derivatives", EndKind::Derivatives),
        ("first_derivatives", EndKind::Derivatives),
        ("clamped", EndKind::Derivatives),
        ("second-derivatives", EndKind::Second),
        ("second_derivatives", EndKind::Second),
    ],
};

/// The points `τ` of the de Boor–Fix functionals (document 003 §5.1, step 5).
pub const TAU_RULE: Vocabulary<TauRule> = Vocabulary {
    key: Arg::Rule,
    words: &[
        Word {
            name: "first-knot-after",
            value: TauRule::FirstKnotAfter,
            meaning: "the first knot after the left end of the support (the thesis's rule)",
        },
        Word {
            name: "left-end-of-support",
            value: TauRule::LeftEndOfSupport,
            meaning: "the left end of the support (reproduces the thesis's printed error)",
        },
        Word {
            name: "midpoint",
            value: TauRule::Midpoint,
            meaning: "the middle of the support",
        },
        Word {
            name: "greville",
            value: TauRule::Greville,
            meaning: "the Greville abscissa",
        },
        Word {
            name: "first-interval-midpoint",
            value: TauRule::FirstIntervalMidpoint,
            meaning: "the middle of the first non-empty knot interval of the support",
        },
    ],
    aliases: &[
        ("first_knot_after", TauRule::FirstKnotAfter),
        ("left_end_of_support", TauRule::LeftEndOfSupport),
        ("left_end", TauRule::LeftEndOfSupport),
        ("left-end", TauRule::LeftEndOfSupport),
        ("first_interval_midpoint", TauRule::FirstIntervalMidpoint),
    ],
};

/// How the smoothing condition's knot rounds place a round's second and later knots
/// ([`KnotRounds`]; `docs/theory/fitting.md#smoothing-condition`).
pub const KNOT_ROUNDS: Vocabulary<KnotRounds> = Vocabulary {
    key: Arg::KnotRounds,
    words: &[
        Word {
            name: "shared",
            value: KnotRounds::Shared,
            meaning: "one fit a round, a split span's residual shared between its halves (FITPACK's curfit, SciPy's splrep; the default)",
        },
        Word {
            name: "refit",
            value: KnotRounds::Refit,
            meaning: "a fit after every knot (SciPy's make_splrep and generate_knots)",
        },
    ],
    aliases: &[],
};

/// A parameter direction of a surface.
pub const DIRECTION: Vocabulary<Direction> = Vocabulary {
    key: Arg::Direction,
    words: &[
        Word {
            name: "u",
            value: Direction::U,
            meaning: "the first parameter (rows of the control net)",
        },
        Word {
            name: "v",
            value: Direction::V,
            meaning: "the second parameter (columns of the control net)",
        },
    ],
    aliases: &[],
};

/// `Display` and `FromStr` of a vocabulary's value type by its canonical words.
macro_rules! spelled_by {
    ($ty:ty, $vocabulary:expr) => {
        impl std::fmt::Display for $ty {
            fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                f.write_str($vocabulary.name(*self).unwrap_or("?"))
            }
        }

        impl std::str::FromStr for $ty {
            type Err = Error;
            fn from_str(s: &str) -> Result<Self> {
                $vocabulary.parse(s).map(|w| w.value)
            }
        }
    };
}

spelled_by!(KnotPlacement, KNOT_PLACEMENT);
spelled_by!(EndKind, END_CONDITION);
spelled_by!(TauRule, TAU_RULE);
spelled_by!(Direction, DIRECTION);
spelled_by!(KnotRounds, KNOT_ROUNDS);

impl std::fmt::Display for Parametrization {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match (PARAMETRIZATION.name(*self), self) {
            (Some(name), _) => f.write_str(name),
            (None, Parametrization::Exponent(e)) => write!(f, "{e}"),
            (None, _) => f.write_str("?"),
        }
    }
}

impl std::str::FromStr for Parametrization {
    type Err = Error;
    /// A word of [`PARAMETRIZATION`], or a number: the exponent `e` of `|ΔQ|^e`.
    fn from_str(s: &str) -> Result<Self> {
        match s.trim().parse::<f64>() {
            Ok(e) => Ok(Parametrization::Exponent(e)),
            Err(_) => PARAMETRIZATION.parse(s).map(|w| w.value),
        }
    }
}

/// Every vocabulary, by key: what the spelling test of the front ends walks.
#[must_use]
pub fn all() -> Vec<(Arg, Vec<&'static str>, Vec<&'static str>)> {
    fn entry<T: Copy + PartialEq>(
        v: &Vocabulary<T>,
    ) -> (Arg, Vec<&'static str>, Vec<&'static str>) {
        (
            v.key,
            v.names(),
            v.aliases.iter().map(|(a, _)| *a).collect(),
        )
    }
    vec![
        entry(&PARAMETRIZATION),
        entry(&KNOT_PLACEMENT),
        entry(&END_CONDITION),
        entry(&TAU_RULE),
        entry(&DIRECTION),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_word_and_alias_reads_back_to_its_value() {
        fn check<T: Copy + PartialEq + std::fmt::Debug>(v: &Vocabulary<T>) {
            for w in v.words {
                let s = v.parse(w.name).unwrap();
                assert_eq!((s.value, s.old_spelling), (w.value, false), "{}", w.name);
                assert_eq!(
                    v.name(w.value),
                    Some(w.name),
                    "canonical name of {}",
                    w.name
                );
                assert!(
                    w.name.chars().all(|c| c.is_ascii_lowercase() || c == '-'),
                    "{} is lower case joined by -",
                    w.name
                );
            }
            for (a, value) in v.aliases {
                let s = v.parse(a).unwrap();
                assert_eq!((s.value, s.old_spelling), (*value, true), "alias {a}");
                assert!(
                    v.words.iter().all(|w| w.name != *a),
                    "{a} is not also canonical"
                );
            }
            assert!(
                matches!(v.parse("nonsense"), Err(e @ Error::InvalidArgument { .. }) if e.arg() == Some(v.key))
            );
        }
        check(&PARAMETRIZATION);
        check(&KNOT_PLACEMENT);
        check(&END_CONDITION);
        check(&TAU_RULE);
        check(&DIRECTION);
    }

    #[test]
    fn display_and_from_str_use_the_canonical_words() {
        assert_eq!(KnotPlacement::AtParameters.to_string(), "at-params");
        assert_eq!(
            "AT-PARAMS".parse::<KnotPlacement>().unwrap(),
            KnotPlacement::AtParameters
        );
        assert_eq!(Parametrization::ChordLength.to_string(), "chord");
        assert_eq!(
            "0.25".parse::<Parametrization>().unwrap(),
            Parametrization::Exponent(0.25)
        );
        assert_eq!(Parametrization::Exponent(0.25).to_string(), "0.25");
        assert_eq!(TauRule::FirstKnotAfter.to_string(), "first-knot-after");
        assert_eq!("periodic".parse::<EndKind>().unwrap(), EndKind::Periodic);
        assert_eq!(Direction::V.to_string(), "v");
    }

    #[test]
    fn end_kinds_take_exactly_the_derivatives_they_use() {
        let d = || Some(vec![1.0, 2.0]);
        assert!(
            EndKind::Second.condition(d(), d()).is_ok(),
            "second with both"
        );
        assert!(
            EndKind::Second.condition(d(), None).is_err(),
            "second with one"
        );
        assert!(EndKind::Free.condition(None, d()).is_err(), "free with one");
        assert_eq!(
            EndKind::Periodic.condition(None, None).unwrap(),
            EndCondition::Periodic
        );
    }
}
