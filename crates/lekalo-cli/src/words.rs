//! The options that every front end shares, read from the library's vocabulary
//! ([`lekalo::vocabulary`]): `--knots at-params`, `--param centripetal`, `--end natural`,
//! `--rule greville`, `--dir v`. The possible values in `--help` are the vocabulary's canonical
//! words with their meanings; an older spelling is still read, with a note on standard error
//! naming the canonical one.

use std::ffi::OsStr;

use clap::builder::{PossibleValue, TypedValueParser};
use clap::error::{ContextKind, ContextValue, ErrorKind};
use lekalo::vocabulary::Vocabulary;
use lekalo::{Arg, Error};

/// A clap value parser of one vocabulary.
#[derive(Clone, Copy)]
pub(crate) struct Words<T: 'static>(pub(crate) &'static Vocabulary<T>);

impl<T> TypedValueParser for Words<T>
where
    T: Copy + PartialEq + Send + Sync + 'static,
{
    type Value = T;

    fn parse_ref(
        &self,
        cmd: &clap::Command,
        arg: Option<&clap::Arg>,
        value: &OsStr,
    ) -> Result<T, clap::Error> {
        let text = value.to_string_lossy();
        let option = arg
            .and_then(clap::Arg::get_long)
            .map_or_else(|| self.0.key.to_string(), |long| format!("--{long}"));
        match self.0.parse(&text) {
            Ok(w) => {
                if w.old_spelling {
                    if let Some(name) = self.0.name(w.value) {
                        crate::output::report(&format!(
                            "note: {option} {text} is an older spelling; write {option} {name}"
                        ));
                    }
                }
                Ok(w.value)
            }
            Err(_) => {
                let mut e = clap::Error::new(ErrorKind::InvalidValue).with_cmd(cmd);
                e.insert(ContextKind::InvalidArg, ContextValue::String(option));
                e.insert(
                    ContextKind::InvalidValue,
                    ContextValue::String(text.into_owned()),
                );
                e.insert(
                    ContextKind::ValidValue,
                    ContextValue::Strings(
                        self.0.names().iter().map(|s| (*s).to_string()).collect(),
                    ),
                );
                Err(e)
            }
        }
    }

    fn possible_values(&self) -> Option<Box<dyn Iterator<Item = PossibleValue> + '_>> {
        Some(Box::new(
            self.0
                .words
                .iter()
                .map(|w| PossibleValue::new(w.name).help(w.meaning)),
        ))
    }
}

/// The command line's name of each argument key of the library's errors ([`Error::arg`]): the
/// one table from the library's keys to the options, `None` for an argument that no option of
/// the command line sets (or that different commands spell differently), whose errors are
/// written in the library's words; each such key is listed with its reason in `WITHOUT_OPTION`
/// (beside the tests). Exhaustive, so that a new key does not compile until it is named here.
pub(crate) const fn option(arg: Arg) -> Option<&'static str> {
    Some(match arg {
        Arg::Knots => "--knots",
        Arg::Parametrization | Arg::Exponent => "--param",
        // `interpolate --params` (the parameters of the points, given)
        Arg::Parameters => "--params",
        // `interpolate --tangents` (a Hermite spline's tangents)
        Arg::Tangents => "--tangents",
        // `fit --weights` (data weights; `make --weights` sets NURBS weights, `Arg::Weights`)
        Arg::DataWeights => "--weights",
        Arg::End => "--end",
        Arg::EndDerivatives => "--start-derivative/--end-derivative",
        Arg::StartDerivative => "--start-derivative",
        Arg::EndDerivative => "--end-derivative",
        Arg::Rule => "--rule",
        Arg::Direction => "--dir",
        Arg::Expression => "--function",
        Arg::Continuity | Arg::ContinuityConditions => "--continuity",
        Arg::CornerWindow | Arg::CornerFraction | Arg::CornerLength => "--window",
        Arg::S => "--s",
        Arg::KnotRounds => "--knot-rounds",
        Arg::Tolerance => "--tolerance",
        // `measure --rtol`: the arc length's relative tolerance
        Arg::RelativeTolerance => "--rtol",
        Arg::Times => "--times",
        Arg::Knot => "--at",
        Arg::Bbox => "--bbox",
        // `fit --sphere`: the interior knots in θ and φ, the grid's colatitudes and longitudes
        Arg::ColatitudeKnots => "--knots-u",
        Arg::LongitudeKnots => "--knots-v",
        Arg::Colatitudes => "--params-u",
        Arg::Longitudes => "--params-v",
        Arg::PoleValues => "--pole-values",
        Arg::PoleFlat => "--pole-flat",
        Arg::Weights
        | Arg::ControlPoints
        | Arg::Breakpoints
        | Arg::Lambda
        | Arg::Eps
        | Arg::MaxKnots => return None,
    })
}

/// The keys without an option ([`option`] is `None`), each with the reason; the table test
/// fails for a key that has neither an option nor a line here.
#[cfg(test)]
const WITHOUT_OPTION: &[(Arg, &str)] = &[
    (
        Arg::Weights,
        "`make --weights` sets NURBS weights, `fit --weights` data weights; the library's \
         weights also come from curves it builds itself",
    ),
    (
        Arg::ControlPoints,
        "`make --control` is one source; `fit --ctrl` (a count) and the curves the library \
         builds are others",
    ),
    (
        Arg::Breakpoints,
        "`pp quasi --breakpoints`, but also the breakpoints a closed fit and a pp-form file give",
    ),
    (
        Arg::Lambda,
        "`fit --smooth` for curves, `fit --penalty` for scattered data on given knots",
    ),
    (
        Arg::Eps,
        "no option sets the rank threshold (Python's `eps`)",
    ),
    (
        Arg::MaxKnots,
        "no option sets the knot budget (Python's `max_knots`)",
    ),
];

/// The message of a failed command: a library error about an argument the command line has an
/// option for is written under that option: a refused value with the library's reason
/// (`--knots: …`), any other error about it whole (`--tolerance: tolerance -1: it must be …`);
/// any other error as it is, with its context (`file: …`).
pub(crate) fn message(e: &anyhow::Error) -> String {
    let mut parts: Vec<String> = Vec::new();
    for cause in e.chain() {
        if let Some(lib) = cause.downcast_ref::<Error>() {
            if let Some(option) = lib.arg().and_then(option) {
                parts.push(match lib {
                    Error::InvalidArgument { reason, .. } => format!("{option}: {reason}"),
                    _ => format!("{option}: {lib}"),
                });
                break;
            }
        }
        parts.push(cause.to_string());
    }
    format!("error: {}", parts.join(": "))
}

/// A library error about the input `path` (a file, or `-`): the error stays in the chain under
/// the path, so that [`message`] names the option of its argument key and the exit code is
/// that of bad input.
pub(crate) fn in_file(path: &std::path::Path, e: Error) -> anyhow::Error {
    anyhow::Error::from(e).context(path.display().to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_vocabulary_key_has_an_option() {
        for (key, _, _) in lekalo::vocabulary::all() {
            assert!(option(key).is_some(), "no option for the key {key}");
        }
    }

    /// Every key has an option, or is listed in `WITHOUT_OPTION` with the reason: a new key, or
    /// a key whose option is forgotten, fails here.
    #[test]
    fn every_key_has_an_option_or_a_reason() {
        for &arg in Arg::ALL {
            let listed = WITHOUT_OPTION.iter().any(|(a, _)| *a == arg);
            match option(arg) {
                Some(o) => assert!(!listed, "{arg:?} has the option {o} and a reason for none"),
                None => assert!(
                    listed,
                    "{arg:?} has no option of the command line and no reason"
                ),
            }
        }
        assert_eq!(option(Arg::Tolerance), Some("--tolerance"));
    }

    /// An error about a key that is not a refused value is written whole under the option.
    #[test]
    fn other_errors_about_a_key_name_its_option() {
        let e = in_file(
            std::path::Path::new("pts.csv"),
            Error::NonPositiveTolerance { value: -1.0 },
        );
        assert_eq!(
            message(&e),
            "error: pts.csv: --tolerance: tolerance -1: it must be finite and > 0 (a distance in \
             the data's units)"
        );
        assert_eq!(crate::exit::exit_code(&e), crate::exit::EXIT_BAD_INPUT);
    }

    /// Each key the command line names: a library error refusing it is written with the
    /// option, also under a context; a key without an option keeps the library's words.
    #[test]
    fn errors_about_a_key_name_its_option() {
        for &arg in Arg::ALL {
            let e = anyhow::Error::from(Error::InvalidArgument {
                what: arg.into(),
                reason: "why".into(),
            });
            let wrapped = anyhow::Error::from(Error::InvalidArgument {
                what: arg.into(),
                reason: "why".into(),
            })
            .context("pts.csv");
            match option(arg) {
                Some(o) => {
                    assert!(o.starts_with("--"), "{o}");
                    assert_eq!(message(&e), format!("error: {o}: why"));
                    assert_eq!(message(&wrapped), format!("error: pts.csv: {o}: why"));
                }
                None => assert_eq!(message(&e), format!("error: invalid {arg}: why")),
            }
        }
        let e = lekalo::vocabulary::KNOT_PLACEMENT
            .parse("everywhere")
            .unwrap_err();
        assert_eq!(
            message(&anyhow::Error::from(e)),
            "error: --knots: \"everywhere\" is not one of auto, averaged, uniform, at-params"
        );
        let other = anyhow::Error::from(Error::InvalidArgument {
            what: "something else".into(),
            reason: "why".into(),
        });
        assert_eq!(message(&other), "error: invalid something else: why");
    }

    /// Every option of every subcommand that chooses among the words of a vocabulary offers
    /// exactly the vocabulary's canonical words: a command that spells one differently (its
    /// own `ValueEnum`, a renamed value) fails here.
    #[test]
    fn the_options_speak_the_vocabulary() {
        use clap::CommandFactory;
        let vocabularies = lekalo::vocabulary::all();
        let mut checked = 0;
        let mut stack = vec![crate::Cli::command()];
        while let Some(cmd) = stack.pop() {
            for arg in cmd.get_arguments() {
                let Some(long) = arg.get_long() else { continue };
                let Some((_, words, _)) = vocabularies
                    .iter()
                    .find(|(key, _, _)| option(*key) == Some(&format!("--{long}")))
                else {
                    continue;
                };
                let offered: Vec<String> = arg
                    .get_possible_values()
                    .iter()
                    .map(|v| v.get_name().to_string())
                    .collect();
                if offered.is_empty() {
                    continue; // the same option name taking numbers (`make bspline --knots 0,0,1,1`)
                }
                assert_eq!(offered, *words, "{} --{long}", cmd.get_name());
                checked += 1;
            }
            stack.extend(cmd.get_subcommands().cloned());
        }
        assert!(checked >= 5, "only {checked} options checked");
    }
}
