//! [`Curve`]: one value for a curve of any kind (Bezier, B-spline, NURBS), with every shared
//! capability delegated once, so that no layer above the library matches on curve kinds to
//! perform an operation.
//!
//! Conventions (`docs/theory.md`, "Curves and surfaces of any kind"):
//! - A Bezier curve of degree `n` is the B-spline on the clamped knots `[0]·(n+1) ++ [1]·(n+1)`
//!   (document 002: the Bernstein polynomials are the B-splines on these knots), so its domain
//!   is `[0, 1]` and [`Curve::knots`] gives those knots.
//! - Knot operations (insertion, refinement, removal, splitting, reversal, reparametrisation,
//!   Bezier decomposition) keep a NURBS curve rational and give a polynomial curve back as a
//!   B-spline: a Bezier curve is first written as its B-spline on `[0, 1]`.

use std::borrow::Cow;

use serde::{Deserialize, Serialize};

use crate::curve::{BSplineCurve, BezierCurve, BezierSegment, NurbsCurve};
use crate::{Error, KnotVector, Points, Progress, QueryCurve, Result};

/// A curve of any kind.
///
/// Serialised with its kind in a `type` field (`"bezier_curve"`, `"bspline_curve"`,
/// `"nurbs_curve"`) beside the fields of the kind, and read back through the kind's validating
/// constructor.
///
/// ```
/// use lekalo::{BSplineCurve, Curve, Points};
/// let ctrl = Points::from_2d(&[[1.0, 1.0], [2.0, 3.0], [4.0, 3.0]])?;
/// let c = Curve::from(BSplineCurve::new(2, vec![0.0, 0.0, 1.0, 2.0, 3.0, 3.0], ctrl)?);
/// assert_eq!(c.domain(), (1.0, 2.0));
/// assert_eq!(c.eval(1.5)?, vec![2.125, 2.75]); // document 002: P(1.5) = (17/8, 11/4)
/// let (left, right) = c.split_at(1.5)?;
/// assert_eq!((left.domain(), right.domain()), ((1.0, 1.5), (1.5, 2.0)));
/// # Ok::<(), lekalo::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "type")]
pub enum Curve {
    /// A Bezier curve on `[0, 1]`.
    #[serde(rename = "bezier_curve")]
    Bezier(BezierCurve),
    /// A B-spline curve.
    #[serde(rename = "bspline_curve")]
    BSpline(BSplineCurve),
    /// A NURBS curve.
    #[serde(rename = "nurbs_curve")]
    Nurbs(NurbsCurve),
}

impl From<BezierCurve> for Curve {
    fn from(c: BezierCurve) -> Self {
        Curve::Bezier(c)
    }
}

impl From<BSplineCurve> for Curve {
    fn from(c: BSplineCurve) -> Self {
        Curve::BSpline(c)
    }
}

impl From<NurbsCurve> for Curve {
    fn from(c: NurbsCurve) -> Self {
        Curve::Nurbs(c)
    }
}

/// A curve for the knot operations: polynomial curves as B-splines, rational as NURBS.
enum Spline<'a> {
    Poly(Cow<'a, BSplineCurve>),
    Rational(&'a NurbsCurve),
}

/// Applies the same operation to the two spline kinds (their methods share names and
/// signatures), giving each result back as a [`Curve`].
macro_rules! on_spline {
    ($self:expr, |$c:ident| $body:expr) => {
        match $self.spline() {
            Spline::Poly($c) => $body.map(Curve::BSpline),
            Spline::Rational($c) => $body.map(Curve::Nurbs),
        }
    };
}

impl Curve {
    /// The kind's name in the JSON envelope: `"bezier_curve"`, `"bspline_curve"` or
    /// `"nurbs_curve"` (`docs/formats.md`).
    #[must_use]
    pub fn type_name(&self) -> &'static str {
        match self {
            Curve::Bezier(_) => "bezier_curve",
            Curve::BSpline(_) => "bspline_curve",
            Curve::Nurbs(_) => "nurbs_curve",
        }
    }

    /// The kind's name for people: "Bezier curve", "B-spline curve", "NURBS curve".
    #[must_use]
    pub fn display_name(&self) -> &'static str {
        match self {
            Curve::Bezier(_) => "Bezier curve",
            Curve::BSpline(_) => "B-spline curve",
            Curve::Nurbs(_) => "NURBS curve",
        }
    }

    /// Whether the curve is rational (NURBS).
    #[must_use]
    pub fn is_rational(&self) -> bool {
        matches!(self, Curve::Nurbs(_))
    }

    /// Dimension of the curve's points (Euclidean, without the weight).
    #[must_use]
    pub fn dim(&self) -> usize {
        match self {
            Curve::Bezier(c) => c.dim(),
            Curve::BSpline(c) => c.dim(),
            Curve::Nurbs(c) => c.dim(),
        }
    }

    /// Degree.
    #[must_use]
    pub fn degree(&self) -> usize {
        match self {
            Curve::Bezier(c) => c.degree(),
            Curve::BSpline(c) => c.degree(),
            Curve::Nurbs(c) => c.degree(),
        }
    }

    /// Parameter domain: `[0, 1]` for a Bezier curve, `[t_p, t_{n+1}]` otherwise (where the
    /// basis is a partition of unity, document 002).
    #[must_use]
    pub fn domain(&self) -> (f64, f64) {
        match self {
            Curve::Bezier(c) => c.domain(),
            Curve::BSpline(c) => c.domain(),
            Curve::Nurbs(c) => c.domain(),
        }
    }

    /// Euclidean control points (a NURBS curve's are computed from its homogeneous points).
    #[must_use]
    pub fn control_points(&self) -> Cow<'_, Points> {
        match self {
            Curve::Bezier(c) => Cow::Borrowed(c.control_points()),
            Curve::BSpline(c) => Cow::Borrowed(c.control_points()),
            Curve::Nurbs(c) => Cow::Owned(c.control_points()),
        }
    }

    /// Weights of a rational curve, `None` for polynomial curves.
    #[must_use]
    pub fn weights(&self) -> Option<Vec<f64>> {
        match self {
            Curve::Nurbs(c) => Some(c.weights()),
            _ => None,
        }
    }

    /// The knot vector; a Bezier curve of degree `n` has the clamped knots
    /// `[0]·(n+1) ++ [1]·(n+1)`.
    #[must_use]
    pub fn knots(&self) -> Cow<'_, KnotVector> {
        match self {
            Curve::Bezier(c) => Cow::Owned(KnotVector::clamped_bezier(c.degree())),
            Curve::BSpline(c) => Cow::Borrowed(c.knots()),
            Curve::Nurbs(c) => Cow::Borrowed(c.knots()),
        }
    }

    /// The knot vector when the kind stores one (B-spline, NURBS); `None` for a Bezier curve,
    /// whose knots are implied by its degree (what the file formats write).
    #[must_use]
    pub fn explicit_knots(&self) -> Option<&KnotVector> {
        match self {
            Curve::Bezier(_) => None,
            Curve::BSpline(c) => Some(c.knots()),
            Curve::Nurbs(c) => Some(c.knots()),
        }
    }

    /// Point at `t` (de Casteljau for Bezier curves, Cox–de Boor, P&T A3.1 / A4.1 otherwise).
    ///
    /// # Errors
    /// [`Error::ParameterOutOfDomain`].
    pub fn eval(&self, t: f64) -> Result<Vec<f64>> {
        match self {
            Curve::Bezier(c) => c.eval(t),
            Curve::BSpline(c) => c.eval(t),
            Curve::Nurbs(c) => c.eval(t),
        }
    }

    /// Point at `t` written into `out` (`dim` values), without allocating.
    ///
    /// # Errors
    /// [`Error::ParameterOutOfDomain`], [`Error::LengthMismatch`] for a wrong `out` length.
    pub fn eval_into(&self, t: f64, out: &mut [f64]) -> Result<()> {
        match self {
            Curve::Bezier(c) => c.eval_into(t, out),
            Curve::BSpline(c) => c.eval_into(t, out),
            Curve::Nurbs(c) => c.eval_into(t, out),
        }
    }

    /// Derivatives `C^{(k)}(t)`, `k = 0..=order`, one row each (rational curves by the
    /// quotient rule, P&T A4.2).
    ///
    /// # Errors
    /// [`Error::ParameterOutOfDomain`], [`Error::TooLarge`] for absurd orders.
    pub fn eval_derivatives(&self, t: f64, order: usize) -> Result<Points> {
        match self {
            Curve::Bezier(c) => c.eval_derivatives(t, order),
            Curve::BSpline(c) => c.eval_derivatives(t, order),
            Curve::Nurbs(c) => c.eval_derivatives(t, order),
        }
    }

    /// Points at every parameter of `ts` into `out` (`ts.len() × dim`, point-major) by the
    /// kind's batch evaluation (no allocation per point, amortised span search).
    ///
    /// # Errors
    /// [`Error::ParameterOutOfDomain`], [`Error::LengthMismatch`].
    pub fn eval_batch(&self, ts: &[f64], out: &mut [f64]) -> Result<()> {
        match self {
            Curve::Bezier(c) => c.eval_batch(ts, out),
            Curve::BSpline(c) => c.eval_batch(ts, out),
            Curve::Nurbs(c) => c.eval_batch(ts, out),
        }
    }

    /// [`Curve::eval_batch`] reporting to `progress` and stopping when it is cancelled (the
    /// kind's `eval_batch_with_progress`); the points are bit-for-bit those of
    /// [`Curve::eval_batch`].
    ///
    /// # Errors
    /// As [`Curve::eval_batch`]; [`Error::Cancelled`] when `progress` is cancelled.
    pub fn eval_batch_with_progress(
        &self,
        ts: &[f64],
        out: &mut [f64],
        progress: &Progress<'_>,
    ) -> Result<()> {
        match self {
            Curve::Bezier(c) => c.eval_batch_with_progress(ts, out, progress),
            Curve::BSpline(c) => c.eval_batch_with_progress(ts, out, progress),
            Curve::Nurbs(c) => c.eval_batch_with_progress(ts, out, progress),
        }
    }

    /// `n` parameters evenly spaced over the domain, both ends included exactly (`n = 1` gives
    /// the start, `n = 0` nothing).
    #[must_use]
    pub fn uniform_parameters(&self, n: usize) -> Vec<f64> {
        let (a, b) = self.domain();
        crate::knots::uniform_parameters(a, b, n)
    }

    /// The curve at `n` uniform parameters ([`Curve::uniform_parameters`]), by
    /// [`Curve::eval_batch`].
    ///
    /// # Errors
    /// [`Error::TooLarge`] when `n × dim` values cannot be held.
    pub fn sample(&self, n: usize) -> Result<Points> {
        self.sample_with_progress(n, &Progress::new())
    }

    /// [`Curve::sample`] reporting to `progress` and stopping when it is cancelled
    /// ([`Curve::eval_batch_with_progress`]); the points are bit-for-bit those of
    /// [`Curve::sample`].
    ///
    /// # Errors
    /// As [`Curve::sample`]; [`Error::Cancelled`] when `progress` is cancelled.
    pub fn sample_with_progress(&self, n: usize, progress: &Progress<'_>) -> Result<Points> {
        if n > crate::MAX_SCALARS {
            return Err(Error::TooLarge {
                what: "curve samples".into(),
                size: n,
                max: crate::MAX_SCALARS,
            });
        }
        let ts = self.uniform_parameters(n);
        let len = ts.len().saturating_mul(self.dim());
        if len > crate::MAX_SCALARS {
            return Err(Error::TooLarge {
                what: "curve samples".into(),
                size: len,
                max: crate::MAX_SCALARS,
            });
        }
        let mut data = vec![0.0; len];
        self.eval_batch_with_progress(&ts, &mut data, progress)?;
        Points::from_flat(self.dim(), data)
    }

    /// The curve of the same kind, degree, knots and weights on other control points, of any
    /// dimension. A spline's coordinates are independent combinations of the same basis
    /// functions (`docs/theory.md`, "Curves and surfaces of any kind"), so a map applied to the
    /// control points alone gives that map of the curve for every linear map, e.g. dropping a
    /// coordinate projects the curve onto the remaining axes (for NURBS, a map that commutes
    /// with the rational combination: linear and affine ones).
    ///
    /// ```
    /// use lekalo::{BSplineCurve, Curve, Points};
    /// let ctrl = Points::from_flat(3, vec![1.0, 1.0, 0.0, 2.0, 3.0, 0.0, 4.0, 3.0, 0.0])?;
    /// let c = Curve::from(BSplineCurve::new(2, vec![0.0, 0.0, 1.0, 2.0, 3.0, 3.0], ctrl)?);
    /// let flat = c.with_control_points(Points::from_2d(&[[1.0, 1.0], [2.0, 3.0], [4.0, 3.0]])?)?;
    /// assert_eq!(flat.eval(1.5)?, vec![2.125, 2.75]);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::LengthMismatch`] when the number of points differs from the curve's; as the
    /// kind's constructor for non-finite points.
    pub fn with_control_points(&self, points: Points) -> Result<Curve> {
        if points.len() != self.control_points().len() {
            return Err(Error::LengthMismatch {
                what: "control points (one for each of the curve's)".into(),
                expected: self.control_points().len(),
                got: points.len(),
            });
        }
        Ok(match self {
            Curve::Bezier(_) => Curve::Bezier(BezierCurve::new(points)?),
            Curve::BSpline(c) => Curve::BSpline(BSplineCurve::new(
                c.degree(),
                c.knots().as_slice().to_vec(),
                points,
            )?),
            Curve::Nurbs(c) => Curve::Nurbs(NurbsCurve::new(
                c.degree(),
                c.knots().as_slice().to_vec(),
                points,
                c.weights(),
            )?),
        })
    }

    /// The axis-aligned box of the control points `(min, max)`, which holds the curve (convex
    /// hull property; for NURBS with positive weights as well).
    #[must_use]
    pub fn bounding_box(&self) -> (Vec<f64>, Vec<f64>) {
        let p = self.control_points();
        let dim = p.dim();
        let mut lo = vec![f64::INFINITY; dim];
        let mut hi = vec![f64::NEG_INFINITY; dim];
        for q in p.iter() {
            for k in 0..dim {
                lo[k] = lo[k].min(q[k]);
                hi[k] = hi[k].max(q[k]);
            }
        }
        (lo, hi)
    }

    /// The curve prepared for geometric queries (length, projection, intersection): its
    /// Bezier pieces with a bounding-box tree ([`QueryCurve`]).
    ///
    /// # Errors
    /// [`Error::Degree`] above the query degree limit.
    pub fn to_query(&self) -> Result<QueryCurve> {
        match self {
            Curve::Bezier(c) => QueryCurve::from_bezier(c),
            Curve::BSpline(c) => QueryCurve::from_bspline(c),
            Curve::Nurbs(c) => QueryCurve::from_nurbs(c),
        }
    }

    /// The curve as a B-spline or NURBS curve, for the knot operations.
    fn spline(&self) -> Spline<'_> {
        match self {
            Curve::Bezier(c) => Spline::Poly(Cow::Owned(c.to_bspline())),
            Curve::BSpline(c) => Spline::Poly(Cow::Borrowed(c)),
            Curve::Nurbs(c) => Spline::Rational(c),
        }
    }

    /// The same curve as a B-spline or NURBS curve (a Bezier curve on clamped knots over
    /// `[0, 1]`); B-spline and NURBS curves are returned unchanged.
    #[must_use]
    pub fn to_spline(&self) -> Curve {
        match self {
            Curve::Bezier(c) => Curve::BSpline(c.to_bspline()),
            other => other.clone(),
        }
    }

    /// The same polynomial curve as a B-spline (a Bezier curve on clamped knots over `[0, 1]`,
    /// [`BezierCurve::to_bspline`]); `None` for a NURBS curve, which is not polynomial.
    #[must_use]
    pub fn to_bspline(&self) -> Option<BSplineCurve> {
        match self.spline() {
            Spline::Poly(c) => Some(c.into_owned()),
            Spline::Rational(_) => None,
        }
    }

    /// The same curve as a NURBS curve: a polynomial curve is the rational curve with unit
    /// weights (P&T §4.2, [`NurbsCurve::from_bspline`]); a NURBS curve is returned unchanged.
    #[must_use]
    pub fn to_nurbs(&self) -> NurbsCurve {
        match self.spline() {
            Spline::Poly(c) => NurbsCurve::from_bspline(&c),
            Spline::Rational(c) => c.clone(),
        }
    }

    /// The `order`-th antiderivative as a B-spline of degree `p + order`
    /// ([`BSplineCurve::antiderivative`]; a Bezier curve as its B-spline on `[0, 1]`).
    ///
    /// # Errors
    /// As [`BSplineCurve::antiderivative`]; [`Error::InvalidArgument`] for a NURBS curve (the
    /// integral of a rational function is not a spline).
    pub fn antiderivative(&self, order: usize) -> Result<Curve> {
        match self.spline() {
            Spline::Poly(c) => c.antiderivative(order).map(Curve::BSpline),
            Spline::Rational(_) => Err(rational_integral()),
        }
    }

    /// `∫_a^b C(t) dt` for `a`, `b` in the domain ([`BSplineCurve::integral`]).
    ///
    /// # Errors
    /// As [`BSplineCurve::integral`]; [`Error::InvalidArgument`] for a NURBS curve.
    pub fn integral(&self, a: f64, b: f64) -> Result<Vec<f64>> {
        match self.spline() {
            Spline::Poly(c) => c.integral(a, b),
            Spline::Rational(_) => Err(rational_integral()),
        }
    }

    /// Inserts the knot `t` `times` times (Boehm; P&T A5.1), the shape unchanged.
    ///
    /// # Errors
    /// As [`BSplineCurve::insert_knot`].
    pub fn insert_knot(&self, t: f64, times: usize) -> Result<Curve> {
        on_spline!(self, |c| c.insert_knot(t, times))
    }

    /// Inserts all knots of the sorted `x` at once (Oslo-type refinement; P&T A5.4).
    ///
    /// # Errors
    /// As [`BSplineCurve::refine_knots`].
    pub fn refine_knots(&self, x: &[f64]) -> Result<Curve> {
        on_spline!(self, |c| c.refine_knots(x))
    }

    /// Splits at `t` into the curves on `[a, t]` and `[t, b]` (knot insertion to full
    /// multiplicity, P&T §5.3).
    ///
    /// # Errors
    /// As [`BSplineCurve::split_at`].
    pub fn split_at(&self, t: f64) -> Result<(Curve, Curve)> {
        match self.spline() {
            Spline::Poly(c) => c
                .split_at(t)
                .map(|(l, r)| (Curve::BSpline(l), Curve::BSpline(r))),
            Spline::Rational(c) => c
                .split_at(t)
                .map(|(l, r)| (Curve::Nurbs(l), Curve::Nurbs(r))),
        }
    }

    /// The same point set traversed backwards, `C(a + b − t)` (knots reflected).
    ///
    /// # Errors
    /// As [`BSplineCurve::reverse`].
    pub fn reverse(&self) -> Result<Curve> {
        on_spline!(self, |c| c.reverse())
    }

    /// The same curve on the domain `[a, b]` (an affine change of parameter).
    ///
    /// # Errors
    /// As [`BSplineCurve::reparametrize`].
    pub fn reparametrize(&self, a: f64, b: f64) -> Result<Curve> {
        on_spline!(self, |c| c.reparametrize(a, b))
    }

    /// The tolerance [`Curve::remove_knot`] uses when none is given: relative to the size of
    /// the control polygon (`DEFAULT_REMOVAL_RTOL`).
    #[must_use]
    pub fn default_removal_tolerance(&self) -> f64 {
        match self.spline() {
            Spline::Poly(c) => c.default_removal_tolerance(),
            Spline::Rational(c) => c.default_removal_tolerance(),
        }
    }

    /// Removes the knot `t` up to `times` times where the curve moves by at most `tolerance`
    /// (Tiller's algorithm, P&T A5.8); returns the curve and how many copies went.
    ///
    /// # Errors
    /// As [`BSplineCurve::remove_knot`].
    pub fn remove_knot(&self, t: f64, times: usize, tolerance: f64) -> Result<(Curve, usize)> {
        match self.spline() {
            Spline::Poly(c) => c
                .remove_knot(t, times, tolerance)
                .map(|(c, n)| (Curve::BSpline(c), n)),
            Spline::Rational(c) => c
                .remove_knot(t, times, tolerance)
                .map(|(c, n)| (Curve::Nurbs(c), n)),
        }
    }

    /// Removes every interior knot copy that can go within `tolerance` (P&T A5.8 repeated);
    /// returns the curve and how many copies went.
    ///
    /// # Errors
    /// As [`BSplineCurve::remove_all_removable_knots`].
    pub fn remove_all_removable_knots(&self, tolerance: f64) -> Result<(Curve, usize)> {
        match self.spline() {
            Spline::Poly(c) => c
                .remove_all_removable_knots(tolerance)
                .map(|(c, n)| (Curve::BSpline(c), n)),
            Spline::Rational(c) => c
                .remove_all_removable_knots(tolerance)
                .map(|(c, n)| (Curve::Nurbs(c), n)),
        }
    }

    /// The curve's Bezier pieces over its non-empty knot spans (P&T A5.6), each a curve of
    /// one segment on its own span: B-splines on clamped knots `[a]·(p+1) ++ [b]·(p+1)` for a
    /// polynomial curve, NURBS for a rational one. [`Curve::join`] puts them back together.
    ///
    /// # Errors
    /// As [`BSplineCurve::from_bezier_segments`] (none for a valid curve).
    pub fn to_bezier_pieces(&self) -> Result<Vec<Curve>> {
        match self.spline() {
            Spline::Poly(c) => c
                .to_bezier_segments()
                .into_iter()
                .map(|seg| {
                    BSplineCurve::from_bezier_segments(std::slice::from_ref(&seg))
                        .map(Curve::BSpline)
                })
                .collect(),
            Spline::Rational(c) => Ok(c
                .to_bezier_segments()
                .into_iter()
                .map(Curve::Nurbs)
                .collect()),
        }
    }

    /// One curve from single-segment pieces in order, each ending where the next starts (the
    /// inverse of [`Curve::to_bezier_pieces`]): the B-spline of the Bezier segments
    /// ([`BSplineCurve::from_bezier_segments`]), joined in homogeneous coordinates when the
    /// pieces are rational.
    ///
    /// # Errors
    /// [`Error::TooFew`] for no piece; [`Error::InvalidArgument`] (`what` = `"pieces"`) for a
    /// piece that is not one clamped segment (an unclamped span's control points are not its
    /// Bezier points) or a mix of rational and polynomial pieces; as
    /// [`BSplineCurve::from_bezier_segments`] for pieces that do not meet.
    pub fn join(pieces: &[Curve]) -> Result<Curve> {
        let Some(first) = pieces.first() else {
            return Err(Error::TooFew {
                what: "pieces to join".into(),
                min: 1,
                got: 0,
            });
        };
        let rational = first.is_rational();
        let mut segs = Vec::with_capacity(pieces.len());
        for (k, piece) in pieces.iter().enumerate() {
            if piece.is_rational() != rational {
                return Err(Error::InvalidArgument {
                    what: "pieces".into(),
                    reason: format!(
                        "piece {} is {} where the first is {}; make them all NURBS",
                        k + 1,
                        if piece.is_rational() {
                            "rational"
                        } else {
                            "polynomial"
                        },
                        if rational { "rational" } else { "polynomial" },
                    ),
                });
            }
            let hom = match piece.spline() {
                Spline::Poly(c) => c.into_owned(),
                Spline::Rational(c) => c.homogeneous().clone(),
            };
            let p = hom.degree();
            let n = hom.control_points().len();
            // one clamped segment: then, and only then, the control points are the Bezier points
            if n != p + 1 || !hom.knots().is_clamped(p) {
                return Err(Error::InvalidArgument {
                    what: "pieces".into(),
                    reason: format!(
                        "piece {} is not a single Bezier segment ({n} control points for degree \
                         {p}); decompose it into its Bezier pieces first",
                        k + 1
                    ),
                });
            }
            let (start, end) = hom.domain();
            let (_, _, control) = hom.into_parts();
            segs.push(BezierSegment {
                start,
                end,
                curve: BezierCurve::new(control)?,
            });
        }
        let joined = BSplineCurve::from_bezier_segments(&segs)?;
        if rational {
            NurbsCurve::from_homogeneous(joined).map(Curve::Nurbs)
        } else {
            Ok(Curve::BSpline(joined))
        }
    }
}

/// The refusal of antiderivatives and integrals of rational curves.
fn rational_integral() -> Error {
    Error::InvalidArgument {
        what: "curve".into(),
        reason: "the integral of a NURBS (rational) curve is not a spline; integrate a \
                 polynomial (Bezier or B-spline) curve"
            .into(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn lecture() -> BSplineCurve {
        let ctrl = Points::from_2d(&[[1.0, 1.0], [2.0, 3.0], [4.0, 3.0]]).unwrap();
        BSplineCurve::new(2, vec![0.0, 0.0, 1.0, 2.0, 3.0, 3.0], ctrl).unwrap()
    }

    fn quarter_circle() -> NurbsCurve {
        let w = std::f64::consts::FRAC_1_SQRT_2;
        let ctrl = Points::from_2d(&[[1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]).unwrap();
        NurbsCurve::new(
            2,
            vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
            ctrl,
            vec![1.0, w, 1.0],
        )
        .unwrap()
    }

    fn bezier() -> BezierCurve {
        BezierCurve::new(
            Points::from_2d(&[[0.0, 0.0], [1.0, 2.0], [3.0, 2.0], [4.0, 0.0]]).unwrap(),
        )
        .unwrap()
    }

    fn all() -> Vec<Curve> {
        vec![
            Curve::from(bezier()),
            Curve::from(lecture()),
            Curve::from(quarter_circle()),
        ]
    }

    #[test]
    fn delegation_agrees_with_each_kind() {
        let (b, s, n) = (bezier(), lecture(), quarter_circle());
        let c = all();
        assert_eq!(
            c[0].eval(0.3).unwrap(),
            b.eval(0.3).unwrap(),
            "Bezier point"
        );
        assert_eq!(
            c[1].eval(1.5).unwrap(),
            vec![2.125, 2.75],
            "document 002: P(1.5)"
        );
        assert_eq!(c[2].eval(0.4).unwrap(), n.eval(0.4).unwrap(), "NURBS point");
        assert_eq!(
            c[1].eval_derivatives(1.2, 2).unwrap(),
            s.eval_derivatives(1.2, 2).unwrap(),
            "derivatives"
        );
        assert_eq!(
            c[0].knots().as_slice(),
            &[0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0],
            "Bezier knots"
        );
        assert_eq!(c[2].weights().unwrap(), n.weights(), "weights");
        assert_eq!(c[1].weights(), None, "polynomial has no weights");
        assert_eq!(
            c.iter().map(Curve::type_name).collect::<Vec<_>>(),
            ["bezier_curve", "bspline_curve", "nurbs_curve"],
            "type names"
        );
    }

    #[test]
    fn conversions_keep_the_points() {
        for c in all() {
            let nurbs = c.to_nurbs();
            let poly = c.to_bspline();
            assert_eq!(poly.is_some(), !c.is_rational(), "{}", c.type_name());
            let (a, b) = c.domain();
            for k in 0..=8 {
                let t = a + (b - a) * f64::from(k) / 8.0;
                let want = c.eval(t).unwrap();
                let got = nurbs.eval(t).unwrap();
                for (x, y) in got.iter().zip(&want) {
                    assert!(
                        (x - y).abs() <= 1e-15 * (1.0 + y.abs()),
                        "NURBS of {}",
                        c.type_name()
                    );
                }
                if let Some(p) = &poly {
                    for (x, y) in p.eval(t).unwrap().iter().zip(&want) {
                        assert!(
                            (x - y).abs() <= 1e-15 * (1.0 + y.abs()),
                            "B-spline of {}",
                            c.type_name()
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn sample_and_batch_equal_single_evaluation() {
        for c in all() {
            let p = c.sample(7).unwrap();
            for (k, t) in c.uniform_parameters(7).into_iter().enumerate() {
                let single = c.eval(t).unwrap();
                for (a, b) in p.point(k).iter().zip(&single) {
                    assert!(
                        (a - b).abs() <= 1e-15 * (1.0 + b.abs()),
                        "{} at {t}",
                        c.type_name()
                    );
                }
            }
        }
    }

    #[test]
    fn knot_operations_keep_the_shape_and_the_kind() {
        for c in all() {
            let (a, b) = c.domain();
            let mid = 0.5 * (a + b);
            let inserted = c.insert_knot(mid, 1).unwrap();
            assert_eq!(inserted.is_rational(), c.is_rational(), "kind kept");
            assert!(
                !matches!(inserted, Curve::Bezier(_)),
                "Bezier becomes a B-spline"
            );
            let t = a + 0.3 * (b - a);
            let (p, q) = (c.eval(t).unwrap(), inserted.eval(t).unwrap());
            for (x, y) in p.iter().zip(&q) {
                assert!((x - y).abs() < 1e-14, "insertion moved the curve");
            }
            let rev = c.reverse().unwrap();
            let (p, q) = (c.eval(t).unwrap(), rev.eval(a + b - t).unwrap());
            for (x, y) in p.iter().zip(&q) {
                assert!((x - y).abs() < 1e-14, "reversal");
            }
            let (l, r) = c.split_at(mid).unwrap();
            assert_eq!(
                (l.domain(), r.domain()),
                ((a, mid), (mid, b)),
                "split domains"
            );
        }
    }

    #[test]
    fn bezier_pieces_join_back() {
        for (c, spans) in [
            (Curve::from(lecture()), 1),
            (Curve::from(lecture().insert_knot(1.5, 1).unwrap()), 2),
            (
                Curve::from(quarter_circle().insert_knot(0.5, 1).unwrap()),
                2,
            ),
        ] {
            let pieces = c.to_bezier_pieces().unwrap();
            assert_eq!(pieces.len(), spans, "one piece per non-empty span");
            let joined = Curve::join(&pieces).unwrap();
            let (a, b) = c.domain();
            for k in 0..=10 {
                let t = a + (b - a) * f64::from(k) / 10.0;
                let (p, q) = (c.eval(t).unwrap(), joined.eval(t).unwrap());
                for (x, y) in p.iter().zip(&q) {
                    assert!((x - y).abs() < 1e-14, "join at {t}");
                }
            }
        }
        let mixed = [
            Curve::from(lecture()).to_bezier_pieces().unwrap()[0].clone(),
            Curve::from(quarter_circle()),
        ];
        assert!(
            matches!(
                Curve::join(&mixed),
                Err(Error::InvalidArgument { what, .. }) if what.words() == "pieces"
            ),
            "mixed kinds"
        );
        assert!(
            matches!(
                Curve::join(&[Curve::from(lecture().insert_knot(1.5, 1).unwrap())]),
                Err(Error::InvalidArgument { .. })
            ),
            "not one segment"
        );
        assert!(
            matches!(Curve::join(&[]), Err(Error::TooFew { .. })),
            "no piece"
        );
    }

    #[test]
    fn serde_tags_the_kind_and_validates() {
        for c in all() {
            let text = serde_json::to_string(&c).unwrap();
            assert!(
                text.contains(&format!("\"type\":\"{}\"", c.type_name())),
                "{text}"
            );
            assert_eq!(
                serde_json::from_str::<Curve>(&text).unwrap(),
                c,
                "round trip"
            );
        }
        let bad = serde_json::to_string(&Curve::from(lecture()))
            .unwrap()
            .replace("[0.0,0.0,1.0,2.0,3.0,3.0]", "[0.0,0.0,2.0,1.0,3.0,3.0]");
        assert!(
            serde_json::from_str::<Curve>(&bad).is_err(),
            "unsorted knots refused: {bad}"
        );
    }

    #[test]
    fn query_curve_of_every_kind() {
        for c in all() {
            let q = c.to_query().unwrap();
            assert_eq!(q.dim(), 2, "{}", c.type_name());
        }
    }
}
