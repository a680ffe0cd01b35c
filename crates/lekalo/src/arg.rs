//! The arguments that errors name, as typed keys.
//!
//! An error about an argument the caller chose (the knot placement, the smoothing weight λ, the
//! corner window, ...) carries an [`Arg`] in its `what` ([`What`]), so that each front end
//! names the argument in its own words (`--knots`, `"knots"`, `knots=`) from one exhaustive
//! table, never from the message. `What` keeps the words the message uses: the key's own words
//! ([`Arg::words`]) or a fuller description of the same argument ("knots (control points +
//! degree + 1)"). Errors about data the library reads for itself (output buffers, the pieces of
//! an intersection) carry a description without a key.
//!
//! ```
//! use lekalo::{Arg, Error, KnotVector};
//! let e = KnotVector::new(vec![0.0, f64::NAN]).unwrap_err();
//! assert_eq!(e.arg(), Some(Arg::Knots));
//! assert_eq!(e.to_string(), "knots[1] is NaN: every number must be finite (no NaN or infinity)");
//! ```
//!
//! `Arg` is not `#[non_exhaustive]` on purpose: a front end maps it with an exhaustive `match`,
//! so that a new key does not compile until every front end has named it.

/// Declares [`Arg`], its words and [`Arg::ALL`] from one list.
macro_rules! args {
    ($($(#[$doc:meta])* $name:ident => $words:literal,)*) => {
        /// An argument of the library's public functions that errors name (module docs).
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
        pub enum Arg {
            $($(#[$doc])* $name,)*
        }

        impl Arg {
            /// Every key, in declaration order (what the front ends' table tests walk).
            pub const ALL: &'static [Arg] = &[$(Arg::$name,)*];

            /// The words the library's messages use for the argument.
            #[must_use]
            pub const fn words(self) -> &'static str {
                match self {
                    $(Arg::$name => $words,)*
                }
            }
        }
    };
}

args! {
    /// A knot vector, or the knot placement of interpolation ([`crate::vocabulary::KNOT_PLACEMENT`]).
    Knots => "knots",
    /// NURBS weights (one per control point).
    Weights => "weights",
    /// Control points of a curve or surface.
    ControlPoints => "control points",
    /// The parametrization of interpolation points ([`crate::vocabulary::PARAMETRIZATION`]).
    Parametrization => "parametrization",
    /// The parameters of data points, one per point (of interpolation, of a Hermite spline, of
    /// a fit), given by the caller.
    Parameters => "parameters",
    /// The tangents of a Hermite spline, one per point.
    Tangents => "tangents",
    /// The weights of data points in a fit (one per data point), not NURBS [`Arg::Weights`].
    DataWeights => "data weights",
    /// The exponent `e` of a parametrization `|ΔQ|^e` ([`crate::Parametrization::Exponent`]).
    Exponent => "parametrisation exponent",
    /// The end condition of interpolation ([`crate::vocabulary::END_CONDITION`]).
    End => "end",
    /// The end derivatives of an end condition, both together ([`crate::vocabulary::EndKind::condition`]).
    EndDerivatives => "end derivatives",
    /// The derivative (first or second) at the start of an interpolating curve.
    StartDerivative => "start derivative",
    /// The derivative (first or second) at the end of an interpolating or fitted curve.
    EndDerivative => "end derivative",
    /// The rule of the de Boor–Fix points `τ` ([`crate::vocabulary::TAU_RULE`]).
    Rule => "rule",
    /// A parameter direction of a surface ([`crate::vocabulary::DIRECTION`]).
    Direction => "direction",
    /// A function given as an expression ([`crate::pp::Expression`]).
    Expression => "expression",
    /// The breakpoints of a piecewise polynomial space.
    Breakpoints => "breakpoints",
    /// The continuity conditions at the interior breakpoints of a piecewise polynomial space.
    ContinuityConditions => "continuity conditions",
    /// The continuity degree `k` of a blend (document 001).
    Continuity => "continuity degree k",
    /// The corner window of a polyline's corner transitions, however it is given.
    CornerWindow => "corner window",
    /// The corner window as a fraction of the shorter segment.
    CornerFraction => "corner window fraction",
    /// The corner window as a length.
    CornerLength => "corner window length",
    /// The smoothing weight λ of a smoothing spline.
    Lambda => "λ",
    /// The residual target `s` of a smoothing condition.
    S => "s",
    /// How the smoothing condition's rounds place their knots ([`crate::vocabulary::KNOT_ROUNDS`]).
    KnotRounds => "knot rounds",
    /// An absolute tolerance, a distance in the data's units: of a fit, a query, a tessellation
    /// or a knot removal.
    Tolerance => "tolerance",
    /// A relative tolerance, a ratio to the quantity computed: of the arc length's adaptive
    /// quadrature ([`crate::QueryCurve::arc_length`]).
    RelativeTolerance => "relative tolerance",
    /// How many times a knot is inserted or removed.
    Times => "knot insertion count",
    /// The knot to insert or remove.
    Knot => "knot to insert",
    /// The relative rank threshold of a scattered least-squares fit.
    Eps => "eps",
    /// The knot budget of a scattered smoothing fit.
    MaxKnots => "max_knots",
    /// The box of a scattered or grid smoothing fit.
    Bbox => "bbox",
    /// The interior colatitude knots `tt` of a least-squares fit on the sphere
    /// ([`crate::fit::sphere_least_squares`]).
    ColatitudeKnots => "tt",
    /// The interior longitude knots `tp` of a least-squares fit on the sphere.
    LongitudeKnots => "tp",
    /// The colatitudes `u` of the grid lines of a fit on a grid of the sphere
    /// ([`crate::fit::SphereGrid`]).
    Colatitudes => "u",
    /// The longitudes `v` of the grid lines of a fit on a grid of the sphere.
    Longitudes => "v",
    /// The values at the poles of a fit on a grid of the sphere
    /// ([`crate::fit::PoleCondition::value`], SciPy's `pole_values`).
    PoleValues => "pole_values",
    /// Flatness at a pole of a fit on a grid of the sphere
    /// ([`crate::fit::PoleCondition::flat`], SciPy's `pole_flat`).
    PoleFlat => "pole_flat",
}

impl std::fmt::Display for Arg {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.words())
    }
}

/// What an error is about: the words its message uses, and the argument key when it is about
/// one. `Display` writes the words only, so messages read as before.
///
/// ```
/// use lekalo::{Arg, What};
/// let w = What::of(Arg::Knots, "knots (control points + degree + 1)");
/// assert_eq!((w.arg(), w.to_string()), (Some(Arg::Knots), "knots (control points + degree + 1)".into()));
/// assert_eq!(What::from(Arg::Lambda).to_string(), "λ");
/// assert_eq!(What::from("output buffer").arg(), None);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct What {
    words: &'static str,
    arg: Option<Arg>,
}

impl What {
    /// Something that is not an argument key (a buffer, an intermediate result), in words.
    #[must_use]
    pub const fn text(words: &'static str) -> Self {
        What { words, arg: None }
    }

    /// The argument `arg`, described in `words` (e.g. "weights (one per control point)").
    #[must_use]
    pub const fn of(arg: Arg, words: &'static str) -> Self {
        What {
            words,
            arg: Some(arg),
        }
    }

    /// The argument key, if the error is about one.
    #[must_use]
    pub const fn arg(self) -> Option<Arg> {
        self.arg
    }

    /// The words of the message.
    #[must_use]
    pub const fn words(self) -> &'static str {
        self.words
    }
}

impl From<Arg> for What {
    fn from(arg: Arg) -> Self {
        What::of(arg, arg.words())
    }
}

impl From<&'static str> for What {
    fn from(words: &'static str) -> Self {
        What::text(words)
    }
}

impl std::fmt::Display for What {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.words)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_key_has_distinct_words() {
        for (i, a) in Arg::ALL.iter().enumerate() {
            assert!(!a.words().is_empty(), "{a:?} has words");
            assert!(
                Arg::ALL[..i].iter().all(|b| b.words() != a.words()),
                "{a:?} shares its words"
            );
            assert_eq!(What::from(*a).arg(), Some(*a), "{a:?} round trip");
        }
    }
}
