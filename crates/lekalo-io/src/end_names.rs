//! The names of the interpolation end conditions, as `lekalo interpolate --end` and the
//! editor's API (`"end"`) spell them, and the condition each name stands for
//! (`lekalo::EndCondition`, document 000 §1–4). One table, read by both front-ends.

use std::fmt;
use std::str::FromStr;

use lekalo::EndCondition;

/// An end condition by name: the condition without its derivative values.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum EndName {
    /// `free`: no extra condition (§1).
    #[default]
    Free,
    /// `derivatives`: given first derivatives at both ends (§2, §3).
    Derivatives,
    /// `second`: given second derivatives at both ends (§4, cubic).
    Second,
    /// `natural`: zero second derivatives, the natural cubic spline.
    Natural,
    /// `periodic`: a closed curve, `C^(p−1)` at the seam.
    Periodic,
}

impl EndName {
    /// Every name with its variant, in the order of the documentation.
    pub const ALL: [(&'static str, EndName); 5] = [
        ("free", EndName::Free),
        ("derivatives", EndName::Derivatives),
        ("second", EndName::Second),
        ("natural", EndName::Natural),
        ("periodic", EndName::Periodic),
    ];

    /// The name (`"derivatives"`).
    #[must_use]
    pub fn name(self) -> &'static str {
        Self::ALL
            .iter()
            .find(|(_, e)| *e == self)
            .map_or("free", |(n, _)| n)
    }

    /// Whether the condition carries a start and an end derivative.
    #[must_use]
    pub fn takes_derivatives(self) -> bool {
        matches!(self, EndName::Derivatives | EndName::Second)
    }

    /// The library's condition, with the derivatives `(start, end)` for `derivatives` and
    /// `second`; `None` when the derivatives are missing (the caller names its own fields in
    /// the message). Derivatives given to a condition without them are ignored here; front-ends
    /// refuse them with their own wording.
    #[must_use]
    pub fn condition(self, derivatives: Option<(Vec<f64>, Vec<f64>)>) -> Option<EndCondition> {
        Some(match self {
            EndName::Free => EndCondition::Free,
            EndName::Derivatives => {
                let (start, end) = derivatives?;
                EndCondition::FirstDerivatives { start, end }
            }
            EndName::Second => {
                let (start, end) = derivatives?;
                EndCondition::SecondDerivatives { start, end }
            }
            EndName::Natural => EndCondition::Natural,
            EndName::Periodic => EndCondition::Periodic,
        })
    }
}

impl fmt::Display for EndName {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for EndName {
    type Err = String;

    /// The variant of a name; the error lists the names.
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Self::ALL
            .iter()
            .find(|(n, _)| *n == s)
            .map(|&(_, e)| e)
            .ok_or_else(|| {
                let names: Vec<&str> = Self::ALL.iter().map(|(n, _)| *n).collect();
                format!(
                    "unknown end condition `{s}`; use one of {}",
                    names.join(", ")
                )
            })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip_and_unknown_names_are_listed() {
        for (n, e) in EndName::ALL {
            assert_eq!(n.parse::<EndName>(), Ok(e), "{n}");
            assert_eq!(e.to_string(), n, "{n}");
        }
        let err = "clamped".parse::<EndName>().expect_err("unknown");
        assert!(
            err.contains("free, derivatives, second, natural, periodic"),
            "{err}"
        );
    }

    #[test]
    fn conditions_carry_their_derivatives() {
        let d = Some((vec![1.0, 0.0], vec![0.0, -1.0]));
        assert_eq!(
            EndName::Derivatives.condition(d.clone()),
            Some(EndCondition::FirstDerivatives {
                start: vec![1.0, 0.0],
                end: vec![0.0, -1.0]
            })
        );
        assert_eq!(
            EndName::Second.condition(d.clone()),
            Some(EndCondition::SecondDerivatives {
                start: vec![1.0, 0.0],
                end: vec![0.0, -1.0]
            })
        );
        assert_eq!(EndName::Second.condition(None), None, "second needs values");
        assert_eq!(
            EndName::Derivatives.condition(None),
            None,
            "derivatives needs values"
        );
        assert_eq!(
            EndName::Natural.condition(None),
            Some(EndCondition::Natural)
        );
        assert_eq!(EndName::Periodic.condition(d), Some(EndCondition::Periodic));
        assert_eq!(EndName::Free.condition(None), Some(EndCondition::Free));
        assert!(EndName::Second.takes_derivatives() && !EndName::Natural.takes_derivatives());
    }
}
