//! The one error type of the library.
//!
//! Every public function that takes user data validates it once, at the boundary, and returns
//! [`Error`] when it is unusable. Bad input ([`Error::NonFinite`], [`Error::KnotsNotSorted`], ...)
//! is kept apart from numerical failure ([`Error::SingularSystem`], [`Error::IllConditioned`]).
//! Each message names the argument, the offending values and, where there is one, the fix.

use crate::arg::{Arg, What};
use crate::message::support_box;
pub use crate::message::ControlSupport;
pub(crate) use crate::message::{readable, NthDirection};

/// Result alias used throughout the crate.
pub type Result<T, E = Error> = std::result::Result<T, E>;

/// Everything that can go wrong in lekalo.
///
/// Variants carry named fields so that callers can react programmatically; `Display` gives a
/// sentence that names the problem and the fix.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// A number is NaN or infinite.
    ///
    /// ```
    /// use lekalo::{Error, Points};
    /// let e = Points::from_flat(2, vec![0.0, f64::NAN]).unwrap_err();
    /// assert!(matches!(e, Error::NonFinite { index: 1, .. }));
    /// ```
    #[error("{what}[{index}] is {value}: every number must be finite (no NaN or infinity)")]
    NonFinite {
        /// Which argument holds the number (its key, [`Error::arg`], when it is one).
        what: What,
        /// Index of the number inside that argument (flat index for point data).
        index: usize,
        /// The offending value.
        value: f64,
    },

    /// An argument that needs at least some elements has too few.
    ///
    /// ```
    /// use lekalo::{Error, Points};
    /// let rows: [[f64; 2]; 0] = [];
    /// let e = Points::from_rows(&rows).unwrap_err();
    /// assert!(matches!(e, Error::TooFew { .. }));
    /// ```
    #[error("{what}: need at least {min}, got {got}")]
    TooFew {
        /// What is counted (e.g. "control points").
        what: What,
        /// The least number accepted.
        min: usize,
        /// The number given.
        got: usize,
    },

    /// Two related lengths disagree.
    ///
    /// ```
    /// use lekalo::{BSplineCurve, Error, Points};
    /// let ctrl = Points::from_flat(1, vec![0.0, 1.0, 2.0]).unwrap();
    /// // degree 2 with 3 control points needs 6 knots
    /// let e = BSplineCurve::new(2, vec![0.0, 0.0, 0.0, 1.0, 1.0], ctrl).unwrap_err();
    /// assert!(matches!(e, Error::LengthMismatch { expected: 6, got: 5, .. }));
    /// ```
    #[error("{what}: expected {expected}, got {got}")]
    LengthMismatch {
        /// Which length (names both sides, e.g. "knots (control points + degree + 1)").
        what: What,
        /// The length required.
        expected: usize,
        /// The length given.
        got: usize,
    },

    /// Point data whose dimension is wrong: zero, not dividing the data length, or different
    /// from the dimension of another argument.
    ///
    /// ```
    /// use lekalo::{Error, Points};
    /// let e = Points::from_flat(2, vec![1.0, 2.0, 3.0]).unwrap_err();
    /// assert!(matches!(e, Error::Dimension { .. }));
    /// ```
    #[error("dimension of {what}: expected {expected}, got {got}")]
    Dimension {
        /// Which argument (its key, [`Error::arg`], when it is one).
        what: What,
        /// The dimension required (0 where any positive dimension would do).
        expected: usize,
        /// The dimension (or data length) found.
        got: usize,
    },

    /// A degree outside the range the operation supports.
    ///
    /// ```
    /// use lekalo::{Error, KnotVector};
    /// // 3 control points cannot carry a cubic
    /// let e = KnotVector::clamped_uniform(3, 3).unwrap_err();
    /// assert!(matches!(e, Error::Degree { degree: 3, .. }));
    /// ```
    #[error("degree {degree} is not allowed here: {reason}")]
    Degree {
        /// The degree asked for.
        degree: usize,
        /// Why it is refused and what is allowed.
        reason: String,
    },

    /// Knots that decrease.
    ///
    /// ```
    /// use lekalo::{Error, KnotVector};
    /// let e = KnotVector::new(vec![0.0, 1.0, 0.5]).unwrap_err();
    /// assert!(matches!(e, Error::KnotsNotSorted { index: 2, .. }));
    /// ```
    #[error(
        "knots must be non-decreasing, but knot {index} = {} is less than knot {} = {}; \
         sort them (lekalo never reorders your knots)",
        readable(.value),
        index - 1,
        readable(.previous)
    )]
    KnotsNotSorted {
        /// Index of the first knot smaller than its predecessor.
        index: usize,
        /// That knot.
        value: f64,
        /// Its predecessor.
        previous: f64,
    },

    /// Parameters, abscissae or breakpoints that must be in increasing order and decrease
    /// somewhere (data that is not sorted: lekalo never reorders it, since the order is the
    /// curve's).
    ///
    /// ```
    /// use lekalo::{natural_cubic_spline, Error, Points};
    /// let y = Points::from_flat(1, vec![1.0, 3.0, 2.0]).unwrap();
    /// let e = natural_cubic_spline(&[0.0, 2.0, 1.0], y.as_view()).unwrap_err();
    /// assert!(matches!(e, Error::NotIncreasing { index: 2, .. }));
    /// assert!(e.to_string().starts_with("parameters must be in increasing order"), "{e}");
    /// ```
    #[error(
        "{what} must be in increasing order, but {what}[{index}] = {} is less than {what}[{}] = {}; sort the \
         data by them (lekalo never reorders your data)",
        readable(.value),
        index - 1,
        readable(.previous)
    )]
    NotIncreasing {
        /// Which sequence (`parameters`, `x`, `breakpoints`).
        what: What,
        /// Index of the first value smaller than its predecessor.
        index: usize,
        /// That value.
        value: f64,
        /// Its predecessor.
        previous: f64,
    },

    /// Parameters, abscissae or breakpoints that must be strictly increasing and repeat a
    /// value (two data at one parameter: an interpolant cannot take two values there).
    ///
    /// ```
    /// use lekalo::{natural_cubic_spline, Error, Points};
    /// let y = Points::from_flat(1, vec![1.0, 3.0, 2.0]).unwrap();
    /// let e = natural_cubic_spline(&[0.0, 1.0, 1.0], y.as_view()).unwrap_err();
    /// assert!(matches!(e, Error::Repeated { index: 2, .. }));
    /// assert!(e.to_string().starts_with("parameters[1] and parameters[2] are both 1"), "{e}");
    /// ```
    #[error(
        "{what}[{}] and {what}[{index}] are both {}: {what} must be strictly increasing; merge \
         the data at a repeated value into one (or fit instead of interpolating)",
        index - 1,
        readable(.value)
    )]
    Repeated {
        /// Which sequence (`parameters`, `x`, `breakpoints`).
        what: What,
        /// Index of the first value equal to its predecessor.
        index: usize,
        /// That value.
        value: f64,
    },

    /// A knot repeated more often than the degree allows.
    ///
    /// ```
    /// use lekalo::{BSplineCurve, Error, Points};
    /// let ctrl = Points::from_flat(1, vec![0.0; 5]).unwrap();
    /// let knots = vec![0.0, 0.0, 0.5, 0.5, 0.5, 0.5, 1.0, 1.0];
    /// let e = BSplineCurve::new(2, knots, ctrl).unwrap_err();
    /// assert!(matches!(e, Error::KnotMultiplicity { multiplicity: 4, max: 3, .. }));
    /// ```
    #[error(
        "knot {} has multiplicity {multiplicity}, more than {max} (degree + 1) allowed; \
         remove repeated copies of it",
        readable(.knot)
    )]
    KnotMultiplicity {
        /// The knot value.
        knot: f64,
        /// How often it occurs.
        multiplicity: usize,
        /// The largest multiplicity allowed.
        max: usize,
    },

    /// A knot vector (or parameter interval) whose domain has zero length.
    ///
    /// ```
    /// use lekalo::{BSplineCurve, Error, Points};
    /// let ctrl = Points::from_flat(1, vec![0.0, 1.0]).unwrap();
    /// let e = BSplineCurve::new(1, vec![1.0, 1.0, 1.0, 1.0], ctrl).unwrap_err();
    /// assert!(matches!(e, Error::EmptyDomain { .. }));
    /// ```
    #[error(
        "the domain [{}, {}] is empty: the knots must span an interval of positive length",
        readable(.min),
        readable(.max)
    )]
    EmptyDomain {
        /// Start of the domain.
        min: f64,
        /// End of the domain.
        max: f64,
    },

    /// A parameter outside the domain of a curve or surface (or NaN).
    ///
    /// ```
    /// use lekalo::{BezierCurve, Error, Points};
    /// let c = BezierCurve::new(Points::from_flat(1, vec![0.0, 1.0]).unwrap()).unwrap();
    /// let e = c.eval(1.5).unwrap_err();
    /// assert!(matches!(e, Error::ParameterOutOfDomain { .. }));
    /// ```
    #[error(
        "parameter {} is outside the domain [{}, {}]",
        readable(.t),
        readable(.min),
        readable(.max)
    )]
    ParameterOutOfDomain {
        /// The parameter given.
        t: f64,
        /// Start of the domain.
        min: f64,
        /// End of the domain.
        max: f64,
    },

    /// A NURBS weight that is not strictly positive.
    ///
    /// ```
    /// use lekalo::{Error, NurbsCurve, Points};
    /// let ctrl = Points::from_flat(1, vec![0.0, 1.0]).unwrap();
    /// let e = NurbsCurve::new(1, vec![0.0, 0.0, 1.0, 1.0], ctrl, vec![1.0, -1.0]).unwrap_err();
    /// assert!(matches!(e, Error::NonPositiveWeight { index: 1, .. }));
    /// ```
    #[error("weight {index} is {}: NURBS weights must be positive", readable(.weight))]
    NonPositiveWeight {
        /// Index of the weight.
        index: usize,
        /// Its value.
        weight: f64,
    },

    /// Two consecutive points coincide where distinct points are needed.
    ///
    /// ```
    /// use lekalo::{Error, Points};
    /// let e = Error::CoincidentPoints { first: 3, second: 4 };
    /// assert!(e.to_string().contains("points 3 and 4 coincide"));
    /// ```
    #[error(
        "points {first} and {second} coincide: chord-length and centripetal parameters need \
         distinct consecutive points (remove the duplicate or use uniform parameters)"
    )]
    CoincidentPoints {
        /// Index of the first point.
        first: usize,
        /// Index of the second point.
        second: usize,
    },

    /// A linear system that has no unique solution (a zero pivot, or a violated
    /// Schoenberg–Whitney condition).
    ///
    /// ```
    /// use lekalo::Error;
    /// let e = Error::SingularSystem { reason: "zero pivot in row 3".into() };
    /// assert!(e.to_string().contains("singular"));
    /// ```
    #[error("the linear system is singular: {reason}")]
    SingularSystem {
        /// What made it singular.
        reason: String,
    },

    /// A problem too ill-conditioned to solve to the promised accuracy.
    ///
    /// ```
    /// use lekalo::Error;
    /// let e = Error::IllConditioned { reason: "pivot growth 1e17".into() };
    /// assert!(e.to_string().contains("ill-conditioned"));
    /// ```
    #[error("the problem is ill-conditioned: {reason}")]
    IllConditioned {
        /// What was detected.
        reason: String,
    },

    /// Shape constraints of a fit that no spline of the space satisfies together: the
    /// constraints named carry the solver's certificate of infeasibility (a combination of them
    /// that is contradictory; not always the smallest such set).
    ///
    /// ```
    /// use lekalo::fit::{constrained_least_squares, FitData, Shape, ShapeConstraints};
    /// use lekalo::{Error, KnotVector, PointsRef};
    /// let x = [0.0, 0.25, 0.5, 0.75, 1.0];
    /// let y = [0.0, 1.0, 0.5, 2.0, 1.5];
    /// let data = FitData::new(PointsRef::from_flat(1, &y)?, &x)?;
    /// let kv = KnotVector::clamped_uniform(2, 4)?;
    /// // increasing, with y(0) = 1 and y(1) = 0: impossible
    /// let c = ShapeConstraints::new()
    ///     .with(Shape::Increasing)
    ///     .with_point(0.0, 0, 1.0)
    ///     .with_point(1.0, 0, 0.0);
    /// let e = constrained_least_squares(&data, 2, &kv, &c).unwrap_err();
    /// assert!(matches!(e, Error::InfeasibleConstraints { .. }));
    /// assert!(e.to_string().contains("increasing"));
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    #[error(
        "the shape constraints cannot all hold: {} contradict each other; drop or widen one \
         of them",
        conflicting.join(", ")
    )]
    InfeasibleConstraints {
        /// The conflicting constraints, in words (`"increasing"`, `"max 1 on [0, 2]"`,
        /// `"y(0) = 1"`).
        conflicting: Vec<String>,
    },

    /// An argument with a value the operation cannot use (the message says which and why).
    ///
    /// ```
    /// use lekalo::{Arg, Error};
    /// let e = Error::InvalidArgument { what: "tension".into(), reason: "must lie in [0, 1]".into() };
    /// assert_eq!(e.to_string(), "invalid tension: must lie in [0, 1]");
    /// // an error about an argument key names it in the key's words
    /// let e = Error::InvalidArgument { what: Arg::Knots.into(), reason: "use auto".into() };
    /// assert_eq!((e.to_string(), e.arg()), ("invalid knots: use auto".into(), Some(Arg::Knots)));
    /// ```
    #[error("invalid {what}: {reason}")]
    InvalidArgument {
        /// Which argument (its key, [`Error::arg`], when it is one).
        what: What,
        /// Why it is invalid and what would be valid.
        reason: String,
    },

    /// An exact degree reduction asked for below the real degree of the curve or surface.
    ///
    /// ```
    /// use lekalo::Error;
    /// let e = Error::DegreeReductionRefused { requested: 2, real_degree: 3, direction: "curve" };
    /// assert!(e.to_string().contains("real degree is 3"));
    /// ```
    #[error(
        "cannot reduce the {direction} to degree {requested} without changing its shape: its real \
         degree is {real_degree}; reduce to {real_degree} or more, or use an approximate reduction"
    )]
    DegreeReductionRefused {
        /// The degree asked for.
        requested: usize,
        /// The real degree found.
        real_degree: usize,
        /// "curve", "u direction" or "v direction".
        direction: &'static str,
    },

    /// A size so large that it is refused instead of attempting the allocation.
    ///
    /// ```
    /// use lekalo::Error;
    /// let e = Error::TooLarge { what: "control points".into(), size: usize::MAX, max: 1 << 28 };
    /// assert!(e.to_string().contains("too large"));
    /// ```
    #[error("{what}: size {size} is too large (at most {max})")]
    TooLarge {
        /// What is too large.
        what: What,
        /// The size asked for.
        size: usize,
        /// The largest size accepted.
        max: usize,
    },

    /// A mesh whose proved deviation bound is above the tolerance asked for: its refinement
    /// stopped at its limit (rounds or halvings) with triangles still above it. A mesh is never
    /// reported within a tolerance its bound does not prove; the fix is a larger tolerance, or
    /// the mesh as it is with this bound.
    ///
    /// ```
    /// use lekalo::Error;
    /// let e = Error::ToleranceNotMet { what: "mesh of face 3".into(), deviation: 0.25, tolerance: 0.1 };
    /// assert!(e.to_string().contains("at least 0.25"));
    /// ```
    #[error(
        "{what}: its proved deviation bound {} is above the tolerance {} (refinement \
         stopped at its limit); use a tolerance of at least {}",
        readable(.deviation), readable(.tolerance), readable(.deviation)
    )]
    ToleranceNotMet {
        /// What was meshed.
        what: String,
        /// The mesh's proved deviation bound.
        deviation: f64,
        /// The tolerance asked for.
        tolerance: f64,
    },
    // -- topology --
    /// A face's loops in its surface's `(u, v)` do not bound one region of the domain
    /// ([`Face::checked_trims`](crate::Face::checked_trims)): a pcurve outside the domain, an
    /// outer loop of no length, loops that cross themselves or each other, a hole outside the
    /// outer loop or inside another hole. `lp` is 0 for the outer loop, `i` for the `i`-th
    /// inner loop.
    ///
    /// ```
    /// use lekalo::{topology::TrimDefect, Error};
    /// let e = Error::InvalidTrim { lp: 2, defect: TrimDefect::OutsideOuter };
    /// assert!(e.to_string().starts_with("inner loop 2 is a hole outside the outer loop"));
    /// ```
    #[error("{} {defect}", crate::topology::loop_name(*.lp))]
    InvalidTrim {
        /// The loop at fault: 0 for the outer loop, `i` for the `i`-th inner loop.
        lp: usize,
        /// What is wrong with it, and what to do.
        defect: crate::topology::TrimDefect,
    },
    // -- blending --
    /// Two curves that must share an end point (a deformation's ends, or the corner of a
    /// corner transition) do not: their distance exceeds the tolerance, which is
    /// [`ENDPOINT_TOLERANCE`](crate::ENDPOINT_TOLERANCE) times the largest absolute coordinate.
    ///
    /// ```
    /// use lekalo::{BezierCurve, Deformation, Error, Points};
    /// let a = BezierCurve::new(Points::from_2d(&[[0.0, 0.0], [1.0, 0.0]]).unwrap()).unwrap();
    /// let b = BezierCurve::new(Points::from_2d(&[[0.0, 0.0], [1.0, 0.5]]).unwrap()).unwrap();
    /// let e = Deformation::new(&a, &b, 1).unwrap_err();
    /// assert!(matches!(e, Error::EndPointMismatch { end: "end (u = 1)", .. }));
    /// ```
    #[error(
        "the curves do not share their {end} point: distance {} exceeds the tolerance \
         {}; deform only curves with common end points (move one curve's end point)",
        readable(.distance),
        readable(.tolerance)
    )]
    EndPointMismatch {
        /// Which end ("start (u = 0)", "end (u = 1)" or the corner).
        end: &'static str,
        /// Distance between the two end points.
        distance: f64,
        /// The tolerance it was compared with.
        tolerance: f64,
    },
    // (fitting)
    /// The data of a least-squares fit leave a basis function without support: the
    /// Schoenberg–Whitney conditions fail (a knot span without data, or more control points than
    /// distinct data parameters), so the fit is not unique. `start..end` is the knot span that
    /// holds no data (or the support of the basis function when every span there holds some).
    ///
    /// ```
    /// use lekalo::fit::check_schoenberg_whitney;
    /// use lekalo::{Error, KnotVector};
    /// let kv = KnotVector::new(vec![0.0, 0.0, 0.0, 0.2, 0.4, 0.6, 1.0, 1.0, 1.0])?;
    /// let e = check_schoenberg_whitney(&[0.0, 0.05, 0.1, 0.15, 0.8, 1.0], 2, &kv).unwrap_err();
    /// assert!(matches!(e, Error::SchoenbergWhitney { basis: 4, .. }));
    /// assert!(e.to_string().contains("[0.4, 0.6]"));
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    #[error(
        "no data for basis function {basis}: the knot span [{start}, {end}] holds too few data \
         parameters (Schoenberg–Whitney conditions); remove knots there, use fewer control \
         points, or add data in that span"
    )]
    SchoenbergWhitney {
        /// Index of the first basis function (control point) left without a data parameter.
        basis: usize,
        /// Start of the knot span without data.
        start: f64,
        /// End of that span.
        end: f64,
    },

    /// A control point of a least-squares fit in `N` variables that the data do not determine:
    /// its support ([`ControlSupport`]: the box of knot spans where its basis function is
    /// positive) holds no data point of positive weight (`points = 0`), or too few or too
    /// nearly aligned ones (the normal matrix is singular there). The `N`-variate counterpart
    /// of [`Error::SchoenbergWhitney`]. Boxed, so that [`Error`] stays small.
    ///
    /// ```
    /// use lekalo::{tensor_scattered_least_squares, Error, KnotVector, PointsRef};
    /// // bilinear on [0, 2]², knots at 1: no data in the cell [1, 2] × [1, 2]
    /// let k = KnotVector::new(vec![0.0, 0.0, 1.0, 2.0, 2.0])?;
    /// let x = [0.2, 0.3, 0.8, 0.5, 1.5, 0.4, 0.6, 1.7, 1.2, 0.9, 0.1, 1.1];
    /// let y = [1.0, 2.0, 3.0, 4.0, 5.0, 6.0];
    /// let e = tensor_scattered_least_squares(
    ///     PointsRef::from_flat(2, &x)?, PointsRef::from_flat(1, &y)?, None, &[1, 1], vec![k.clone(), k],
    /// ).unwrap_err();
    /// assert!(matches!(e, Error::EmptySupport { ref support, points: 0 } if support.index == [2, 2]));
    /// assert!(e.to_string().contains("[1, 2] × [1, 2]"));
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    #[error(
        "control point {:?} is not determined by the data: its support {} holds {points} \
         data points of positive weight{}; remove knots there (fewer control points in that \
         region), or add data inside it",
        .support.index,
        support_box(&.support.lower, &.support.upper),
        if *.points > 0 { ", too few or too nearly aligned" } else { "" }
    )]
    EmptySupport {
        /// The control point and its support.
        support: Box<ControlSupport>,
        /// Data points of positive weight inside the support.
        points: usize,
    },

    /// A data weight that is NaN, infinite or negative, or weights that are all zero.
    ///
    /// ```
    /// use lekalo::fit::FitData;
    /// use lekalo::{Error, PointsRef};
    /// let q = [0.0, 1.0, 2.0];
    /// let data = FitData::new(PointsRef::from_flat(1, &q)?, &[0.0, 0.5, 1.0])?;
    /// let e = data.with_weights(&[1.0, f64::NAN, 1.0]).unwrap_err();
    /// assert!(matches!(e, Error::InvalidDataWeight { index: 1, .. }));
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    #[error(
        "data weight {index} is {}: weights must be finite and ≥ 0, with at least one \
         positive",
        readable(.weight)
    )]
    InvalidDataWeight {
        /// Index of the weight (0 when all are zero).
        index: usize,
        /// Its value.
        weight: f64,
    },

    /// A negative smoothing weight λ or smoothing target `s`.
    ///
    /// ```
    /// use lekalo::fit::{smoothing_spline, FitData, Lambda};
    /// use lekalo::{Error, PointsRef};
    /// let y = [0.0, 1.0, 0.0, 1.0];
    /// let data = FitData::new(PointsRef::from_flat(1, &y)?, &[0.0, 1.0, 2.0, 3.0])?;
    /// let e = smoothing_spline(&data, Lambda::Given(-1.0)).unwrap_err();
    /// assert!(matches!(e, Error::NegativeSmoothing { .. }));
    /// assert_eq!(e.arg(), Some(lekalo::Arg::Lambda));
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    #[error(
        "smoothing {what} = {}: it must be finite and ≥ 0 (0 interpolates)",
        readable(.value)
    )]
    NegativeSmoothing {
        /// [`Arg::Lambda`] (penalty weight) or [`Arg::S`] (residual target).
        what: What,
        /// The value given.
        value: f64,
    },

    /// A fitting tolerance that is not positive and finite.
    ///
    /// ```
    /// use lekalo::fit::{fit_tolerance, ToleranceOptions};
    /// use lekalo::{Error, PointsRef};
    /// let q = [0.0, 0.0, 1.0, 1.0, 2.0, 0.0, 3.0, 1.0];
    /// let e = fit_tolerance(PointsRef::from_flat(2, &q)?, &ToleranceOptions::new(3, 0.0)).unwrap_err();
    /// assert!(matches!(e, Error::NonPositiveTolerance { .. }));
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    #[error(
        "tolerance {}: it must be finite and > 0 (a distance in the data's units)",
        readable(.value)
    )]
    NonPositiveTolerance {
        /// The value given.
        value: f64,
    },

    // (geometric queries)
    /// A query point lies so far from the object (more than
    /// [`MAX_QUERY_RANGE`](crate::query::MAX_QUERY_RANGE) times its size) that squared
    /// distances would keep no digit of the object's shape.
    ///
    /// ```
    /// use lekalo::{BezierCurve, Error, Points, QueryCurve};
    /// let c = BezierCurve::new(Points::from_2d(&[[0.0, 0.0], [1.0, 1.0]]).unwrap()).unwrap();
    /// let e = QueryCurve::from_bezier(&c).unwrap().project(&[1e300, 0.0]).unwrap_err();
    /// assert!(matches!(e, Error::QueryOutOfRange { .. }));
    /// ```
    #[error(
        "the query point is {ratio:e} object sizes away, beyond {max:e}: move the point or \
         the object closer to the origin of the other"
    )]
    QueryOutOfRange {
        /// Distance of the point from the object's centre in object sizes.
        ratio: f64,
        /// The largest accepted ratio.
        max: f64,
    },

    /// Point inversion was asked for a point that is not on the curve within the tolerance.
    ///
    /// ```
    /// use lekalo::{BezierCurve, Error, Points, QueryCurve};
    /// let c = BezierCurve::new(Points::from_2d(&[[0.0, 0.0], [1.0, 0.0]]).unwrap()).unwrap();
    /// let e = QueryCurve::from_bezier(&c).unwrap().invert(&[0.5, 0.1], 1e-9).unwrap_err();
    /// assert!(matches!(e, Error::NotOnCurve { .. }));
    /// ```
    #[error(
        "the point is {distance:e} from the curve, more than the tolerance {tolerance:e}: \
         project it instead of inverting, or raise the tolerance"
    )]
    NotOnCurve {
        /// Distance from the point to the curve.
        distance: f64,
        /// The tolerance it was compared with.
        tolerance: f64,
    },
    // -- long computations --
    /// A long computation stopped because its caller asked it to (the cancel flag of its
    /// [`Progress`](crate::Progress) was set, e.g. by Ctrl-C); nothing partial is returned.
    ///
    /// ```
    /// use std::sync::atomic::AtomicBool;
    /// use lekalo::{BlendSplineOptions, BlendSplinePieces, Error, Parabolas, Points, Progress};
    /// let pts = Points::from_2d(&[[0.0, 0.0], [1.0, 1.0], [2.0, 0.0]]).unwrap();
    /// let stop = AtomicBool::new(true);
    /// let progress = Progress::new().with_cancel(&stop);
    /// let e = BlendSplinePieces::new(pts.as_view(), &Parabolas, BlendSplineOptions::default(), &progress)
    ///     .unwrap_err();
    /// assert!(matches!(e, Error::Cancelled { .. }));
    /// ```
    #[error("{what}: cancelled")]
    Cancelled {
        /// The computation that stopped.
        what: &'static str,
    },
}

impl Error {
    /// The argument the error is about, when it is one of the keys ([`Arg`]): what a front end
    /// maps to its own name for the argument (`--knots`, `"knots"`, `knots=`), never the message.
    ///
    /// ```
    /// use lekalo::{Arg, KnotVector};
    /// let e = KnotVector::new(vec![0.0, 1.0, 0.5]).unwrap_err();
    /// assert_eq!(e.arg(), Some(Arg::Knots));
    /// ```
    #[must_use]
    pub fn arg(&self) -> Option<Arg> {
        match self {
            Error::NonFinite { what, .. }
            | Error::TooFew { what, .. }
            | Error::LengthMismatch { what, .. }
            | Error::Dimension { what, .. }
            | Error::InvalidArgument { what, .. }
            | Error::TooLarge { what, .. }
            | Error::NegativeSmoothing { what, .. }
            | Error::NotIncreasing { what, .. }
            | Error::Repeated { what, .. } => what.arg(),
            Error::KnotsNotSorted { .. } | Error::KnotMultiplicity { .. } => Some(Arg::Knots),
            Error::NonPositiveWeight { .. } => Some(Arg::Weights),
            Error::NonPositiveTolerance { .. } => Some(Arg::Tolerance),
            _ => None,
        }
    }
}

/// Checks that every number in `values` is finite.
///
/// # Errors
/// [`Error::NonFinite`] naming `what` and the first bad index.
pub(crate) fn check_finite(what: impl Into<What>, values: &[f64]) -> Result<()> {
    // a branch-free pass first, the search for the first bad value only if there is one: every
    // point set passes here, and millions of numbers took milliseconds one comparison at a time.
    // `0·v` is ±0 for a finite v and NaN otherwise, and NaN stays in a sum: eight independent
    // sums the compiler keeps in vector registers
    let mut sums = [0.0_f64; 8];
    let blocks = values.chunks_exact(8);
    let tail_ok = blocks.remainder().iter().all(|v| v.is_finite());
    for b in blocks {
        for (s, v) in sums.iter_mut().zip(b) {
            *s += 0.0 * v;
        }
    }
    if tail_ok && sums.iter().all(|s| *s == 0.0) {
        return Ok(());
    }
    match values.iter().position(|v| !v.is_finite()) {
        Some(index) => Err(Error::NonFinite {
            what: what.into(),
            index,
            value: values[index],
        }),
        None => Ok(()),
    }
}

/// Largest number of scalars any single object may hold (2^31 f64 = 16 GiB): larger requests are
/// refused with [`Error::TooLarge`] instead of being allocated.
pub const MAX_SCALARS: usize = 1 << 31;

/// Largest degree accepted where the degree alone sets an allocation or the running time, i.e.
/// where no user data of that size backs it ([`KnotVector::clamped_uniform`],
/// [`KnotVector::from_parameters`], [`KnotVector::from_breakpoints`] and the order of a
/// [`PpSpace`]). Larger degrees are refused with [`Error::Degree`]: evaluation costs O(p²) per
/// point, and Bernstein/B-spline bases of degree > 1024 have no practical use.
///
/// [`KnotVector::clamped_uniform`]: crate::KnotVector::clamped_uniform
/// [`KnotVector::from_parameters`]: crate::KnotVector::from_parameters
/// [`KnotVector::from_breakpoints`]: crate::KnotVector::from_breakpoints
/// [`PpSpace`]: crate::PpSpace
pub const MAX_DEGREE: usize = 1 << 10;

/// Largest derivative order accepted by the `eval_derivatives` of curves, piecewise polynomials
/// and the basis kernels: the result has `order + 1` rows and a rational curve costs O(order²).
/// Larger orders are refused with [`Error::TooLarge`] instead of allocating the table.
/// (Polynomial derivatives above the degree are zero; rational ones past about order 170 overflow
/// because of the `k!` growth.)
pub const MAX_DERIVATIVE_ORDER: usize = 1 << 10;

/// Largest derivative order accepted by the `eval_derivatives` of surfaces: the table has
/// `(order + 1)²` entries and the rational quotient rule (P&T A4.4) costs O(order⁴).
pub const MAX_SURFACE_DERIVATIVE_ORDER: usize = 1 << 6;

/// Refuses a derivative order above `max` ([`MAX_DERIVATIVE_ORDER`] or
/// [`MAX_SURFACE_DERIVATIVE_ORDER`]).
///
/// # Errors
/// [`Error::TooLarge`] naming the derivative order.
pub(crate) fn check_derivative_order(order: usize, max: usize) -> Result<()> {
    if order > max {
        return Err(Error::TooLarge {
            what: "derivative order".into(),
            size: order,
            max,
        });
    }
    Ok(())
}

/// Refuses a degree above [`MAX_DEGREE`] where the degree alone sets the work.
///
/// # Errors
/// [`Error::Degree`].
pub(crate) fn check_degree_bound(degree: usize) -> Result<()> {
    if degree > MAX_DEGREE {
        return Err(Error::Degree {
            degree,
            reason: format!("at most {MAX_DEGREE} is supported"),
        });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn check_finite_reports_first_bad_index() {
        assert_eq!(check_finite("x", &[1.0, 2.0]), Ok(()));
        let e = check_finite("x", &[1.0, f64::INFINITY, f64::NAN]).unwrap_err();
        assert!(
            matches!(e, Error::NonFinite { what, index: 1, .. } if what.words() == "x"),
            "got {e:?}"
        );
    }

    #[test]
    fn the_degree_bound_names_the_number_not_the_constant() {
        let e = check_degree_bound(MAX_DEGREE + 1).unwrap_err().to_string();
        assert_eq!(
            e,
            format!(
                "degree {} is not allowed here: at most {MAX_DEGREE} is supported",
                MAX_DEGREE + 1
            )
        );
    }

    #[test]
    fn directions_are_named_by_ordinals() {
        let words: Vec<String> = [0, 1, 2, 3, 10, 11, 12, 20, 21, 111]
            .iter()
            .map(|&a| NthDirection(a).to_string())
            .collect();
        assert_eq!(
            words,
            [
                "1st direction",
                "2nd direction",
                "3rd direction",
                "4th direction",
                "11th direction",
                "12th direction",
                "13th direction",
                "21st direction",
                "22nd direction",
                "112th direction"
            ],
            "ordinals"
        );
    }

    #[test]
    fn messages_name_the_fix() {
        let e = Error::KnotsNotSorted {
            index: 3,
            value: 0.5,
            previous: 0.7,
        };
        let s = e.to_string();
        assert!(
            s.contains("knot 3 = 0.5") && s.contains("knot 2 = 0.7"),
            "{s}"
        );
    }

    #[test]
    fn numbers_of_any_size_are_written_readably() {
        // a tolerance of 1e-300 was written as a 300-digit decimal, 1e300 as 301 digits
        let cases = [
            (
                Error::NonPositiveTolerance { value: -1e-300 },
                "tolerance -1e-300: it must",
            ),
            (
                Error::ParameterOutOfDomain {
                    t: 1e300,
                    min: 0.0,
                    max: 0.25,
                },
                "parameter 1e300 is outside the domain [0, 0.25]",
            ),
            (
                Error::EmptyDomain { min: 3.0, max: 3.0 },
                "the domain [3, 3] is empty",
            ),
            (
                Error::KnotMultiplicity {
                    knot: 1.5e-9,
                    multiplicity: 5,
                    max: 4,
                },
                "knot 1.5e-9 has multiplicity 5",
            ),
            (
                Error::EndPointMismatch {
                    end: "start (u = 0)",
                    distance: 2e20,
                    tolerance: 1e-12,
                },
                "distance 2e20 exceeds the tolerance 1e-12",
            ),
            (
                Error::NonPositiveWeight {
                    index: 0,
                    weight: f64::NEG_INFINITY,
                },
                "weight 0 is -inf",
            ),
        ];
        for (e, want) in cases {
            let s = e.to_string();
            assert!(s.contains(want) && s.len() < 200, "{s}");
        }
    }
}
