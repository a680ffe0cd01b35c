//! What a shape-constrained fit is asked to keep: the constraints and their validation
//! (`docs/theory/fitting.md#shape-constraints`).

use crate::error::readable;
use crate::error::{check_finite, Error, Result};

/// A shape that `y(x)` keeps on an interval: a sign of a derivative, or a bound on the values.
///
/// Each is `σ·(y⁽ʳ⁾(x) − v) ≥ 0` for every `x` of the interval, with the derivative order `r`,
/// sign `σ` and level `v` of [`Shape::derivative_order`], [`Shape::sign`] and [`Shape::level`].
///
/// ```
/// use lekalo::fit::Shape;
/// assert_eq!(Shape::Convex.derivative_order(), 2);
/// assert_eq!((Shape::AtMost(3.0).sign(), Shape::AtMost(3.0).level()), (-1.0, 3.0));
/// assert_eq!(Shape::Decreasing.to_string(), "decreasing");
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Shape {
    /// `y' ≥ 0` (non-decreasing).
    Increasing,
    /// `y' ≤ 0` (non-increasing).
    Decreasing,
    /// `y'' ≥ 0`.
    Convex,
    /// `y'' ≤ 0`.
    Concave,
    /// `y ≥ v` (a lower bound; `AtLeast(0.0)` is non-negativity).
    AtLeast(f64),
    /// `y ≤ v` (an upper bound).
    AtMost(f64),
}

impl Shape {
    /// The order `r` of the derivative the shape constrains (0 for bounds).
    #[must_use]
    pub fn derivative_order(self) -> usize {
        match self {
            Shape::Increasing | Shape::Decreasing => 1,
            Shape::Convex | Shape::Concave => 2,
            Shape::AtLeast(_) | Shape::AtMost(_) => 0,
        }
    }

    /// `σ = +1` for a lower bound on `y⁽ʳ⁾`, `−1` for an upper one.
    #[must_use]
    pub fn sign(self) -> f64 {
        match self {
            Shape::Increasing | Shape::Convex | Shape::AtLeast(_) => 1.0,
            Shape::Decreasing | Shape::Concave | Shape::AtMost(_) => -1.0,
        }
    }

    /// The level `v` the derivative is compared with (0 for the derivative shapes).
    #[must_use]
    pub fn level(self) -> f64 {
        match self {
            Shape::AtLeast(v) | Shape::AtMost(v) => v,
            _ => 0.0,
        }
    }
}

impl std::fmt::Display for Shape {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Shape::Increasing => write!(f, "increasing"),
            Shape::Decreasing => write!(f, "decreasing"),
            Shape::Convex => write!(f, "convex"),
            Shape::Concave => write!(f, "concave"),
            Shape::AtLeast(v) => write!(f, "min {v}"),
            Shape::AtMost(v) => write!(f, "max {v}"),
        }
    }
}

/// A [`Shape`] on the whole domain of the fit (`interval: None`) or on `[a, b]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShapeConstraint {
    /// The shape kept.
    pub shape: Shape,
    /// Where: `None` for the whole domain, else `[a, b]` with `a ≤ b` inside the domain (`a = b`:
    /// at the point `a` only, e.g. a bound on the value at a given `x`).
    pub interval: Option<(f64, f64)>,
}

impl std::fmt::Display for ShapeConstraint {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self.interval {
            None => write!(f, "{}", self.shape),
            Some((a, b)) if a == b => write!(f, "{} at {a}", self.shape),
            Some((a, b)) => write!(f, "{} on [{a}, {b}]", self.shape),
        }
    }
}

/// An equality at a point: `y⁽ʳ⁾(x) = value` (`r = derivative`, 0 for a value).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointCondition {
    /// Where, inside the domain of the fit.
    pub x: f64,
    /// The derivative order `r` (0: the value), at most the degree.
    pub derivative: usize,
    /// The value `y⁽ʳ⁾(x)` must take.
    pub value: f64,
}

impl std::fmt::Display for PointCondition {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let primes = "'".repeat(self.derivative.min(3));
        match self.derivative {
            0..=3 => write!(f, "y{primes}({}) = {}", self.x, self.value),
            r => write!(f, "y^({r})({}) = {}", self.x, self.value),
        }
    }
}

/// An equality of an integral: `∫_a^b y(x) dx = value`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct IntegralCondition {
    /// The interval `[a, b]`, `a < b`, inside the domain of the fit.
    pub interval: (f64, f64),
    /// The value the integral must take.
    pub value: f64,
}

impl std::fmt::Display for IntegralCondition {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let (a, b) = self.interval;
        write!(f, "integral over [{a}, {b}] = {}", self.value)
    }
}

/// Everything a shape-constrained fit keeps: shapes on intervals, equalities at points, of
/// integrals and periodicity, in any combination. Built by chaining:
///
/// ```
/// use lekalo::fit::{Shape, ShapeConstraints};
/// let c = ShapeConstraints::new()
///     .with(Shape::Increasing)
///     .with_on(Shape::Concave, 0.5, 1.0)
///     .with(Shape::AtLeast(0.0))
///     .with_on(Shape::AtMost(2.0), 0.25, 0.25)
///     .with_point(0.0, 0, 0.0);
/// assert_eq!(c.len(), 5);
/// assert_eq!(c.describe(1), "concave on [0.5, 1]");
/// assert_eq!(c.describe(3), "max 2 at 0.25");
/// assert_eq!(c.describe(4), "y(0) = 0");
/// let c = c.with_integral(0.0, 1.0, 0.5).with_periodicity();
/// assert_eq!(c.describe(5), "integral over [0, 1] = 0.5");
/// assert_eq!(c.describe(6), "periodic");
/// ```
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ShapeConstraints {
    /// The shapes, each on its interval.
    pub shapes: Vec<ShapeConstraint>,
    /// The equalities at points.
    pub points: Vec<PointCondition>,
    /// The equalities of integrals.
    pub integrals: Vec<IntegralCondition>,
    /// Periodicity: `y⁽ʳ⁾` equal at both ends of the domain for `r = 0 … p − 1` (a function
    /// that continues periodically with continuous derivatives up to order `p − 1`).
    pub periodic: bool,
}

impl ShapeConstraints {
    /// No constraint.
    #[must_use]
    pub fn new() -> Self {
        Self::default()
    }

    /// Adds `shape` on the whole domain.
    #[must_use]
    pub fn with(mut self, shape: Shape) -> Self {
        self.shapes.push(ShapeConstraint {
            shape,
            interval: None,
        });
        self
    }

    /// Adds `shape` on `[a, b]` (`a = b`: at the point `a`).
    #[must_use]
    pub fn with_on(mut self, shape: Shape, a: f64, b: f64) -> Self {
        self.shapes.push(ShapeConstraint {
            shape,
            interval: Some((a, b)),
        });
        self
    }

    /// Adds the equality `y⁽ʳ⁾(x) = value` with `r = derivative`.
    #[must_use]
    pub fn with_point(mut self, x: f64, derivative: usize, value: f64) -> Self {
        self.points.push(PointCondition {
            x,
            derivative,
            value,
        });
        self
    }

    /// Adds `∫_a^b y(x) dx = value`.
    #[must_use]
    pub fn with_integral(mut self, a: f64, b: f64, value: f64) -> Self {
        self.integrals.push(IntegralCondition {
            interval: (a, b),
            value,
        });
        self
    }

    /// Adds periodicity (see [`ShapeConstraints::periodic`]).
    #[must_use]
    pub fn with_periodicity(mut self) -> Self {
        self.periodic = true;
        self
    }

    /// Number of constraints (shapes, points, integrals, then periodicity).
    #[must_use]
    pub fn len(&self) -> usize {
        self.shapes.len() + self.points.len() + self.integrals.len() + usize::from(self.periodic)
    }

    /// Whether there is no constraint.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Constraint `i` (shapes, points, integrals, then periodicity) in words, as errors name it.
    #[must_use]
    pub fn describe(&self, i: usize) -> String {
        let (ns, np, ni) = (self.shapes.len(), self.points.len(), self.integrals.len());
        if i < ns {
            self.shapes[i].to_string()
        } else if i < ns + np {
            self.points[i - ns].to_string()
        } else if i < ns + np + ni {
            self.integrals[i - ns - np].to_string()
        } else if self.periodic && i == ns + np + ni {
            "periodic".into()
        } else {
            String::new()
        }
    }

    /// Checks every number and interval against the domain `[lo, hi]` and the degree.
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a NaN or infinite level, end or point;
    /// [`Error::InvalidArgument`] (key `"shape constraints"`) for an interval that ends before it
    /// starts or leaves the domain, a point outside it, or a derivative order above the degree.
    pub(crate) fn validate(&self, (lo, hi): (f64, f64), degree: usize) -> Result<()> {
        let bad = |reason: String| Error::InvalidArgument {
            what: "shape constraints".into(),
            reason,
        };
        for s in &self.shapes {
            check_finite("shape constraint level", &[s.shape.level()])?;
            if let Some((a, b)) = s.interval {
                check_finite("shape constraint interval", &[a, b])?;
                if a > b {
                    return Err(bad(format!(
                        "the interval [{a}, {b}] of \"{s}\" ends before it starts: give its \
                         start first (or one number twice for a single point)",
                        a = readable(&a),
                        b = readable(&b)
                    )));
                }
                if a < lo || b > hi {
                    return Err(bad(format!(
                        "the interval [{a}, {b}] of \"{s}\" leaves the domain [{lo}, {hi}] of the \
                         fit: shrink it to the domain",
                        a = readable(&a),
                        b = readable(&b),
                        lo = readable(&lo),
                        hi = readable(&hi)
                    )));
                }
            }
        }
        for g in &self.integrals {
            let (a, b) = g.interval;
            check_finite("integral condition", &[a, b, g.value])?;
            if a >= b || a < lo || b > hi {
                return Err(bad(format!(
                    "the interval [{a}, {b}] of \"{g}\" is empty or leaves the domain [{lo}, \
                     {hi}] of the fit: give a < b inside the domain",
                    a = readable(&a),
                    b = readable(&b),
                    lo = readable(&lo),
                    hi = readable(&hi)
                )));
            }
        }
        for q in &self.points {
            check_finite("point condition", &[q.x, q.value])?;
            if q.x < lo || q.x > hi {
                return Err(bad(format!(
                    "the point of \"{q}\" is outside the domain [{lo}, {hi}] of the fit",
                    lo = readable(&lo),
                    hi = readable(&hi)
                )));
            }
            if q.derivative > degree {
                return Err(bad(format!(
                    "\"{q}\" asks for derivative {} of a spline of degree {degree}: use an order \
                     up to the degree",
                    q.derivative
                )));
            }
        }
        Ok(())
    }
}
