//! What a shape-constrained surface fit keeps: monotonicity per direction and bounds on the
//! values (`docs/theory/fitting.md#shape-constraints-of-surfaces`).

use crate::error::{check_finite, Error, Result};
use crate::Direction;

/// A shape that a surface `z(u, v)` keeps on its whole domain.
///
/// Each is a sign condition `σ·(∂ʳz − v) ≥ 0` for every `(u, v)` of the domain, with `∂ʳ` the
/// partial derivative in the direction named (monotonicity) or the value itself (bounds).
///
/// ```
/// use lekalo::fit::SurfaceShape;
/// use lekalo::Direction;
/// assert_eq!(SurfaceShape::Increasing(Direction::U).to_string(), "increasing in u");
/// assert_eq!(SurfaceShape::AtMost(2.5).to_string(), "max 2.5");
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SurfaceShape {
    /// `∂z/∂u ≥ 0` (or `∂z/∂v`): non-decreasing along the direction.
    Increasing(Direction),
    /// `∂z/∂u ≤ 0` (or `∂z/∂v`): non-increasing along the direction.
    Decreasing(Direction),
    /// `z ≥ v` everywhere (`AtLeast(0.0)`: non-negativity).
    AtLeast(f64),
    /// `z ≤ v` everywhere.
    AtMost(f64),
}

impl SurfaceShape {
    /// The direction differentiated (`None` for bounds).
    #[must_use]
    pub fn direction(self) -> Option<Direction> {
        match self {
            SurfaceShape::Increasing(d) | SurfaceShape::Decreasing(d) => Some(d),
            SurfaceShape::AtLeast(_) | SurfaceShape::AtMost(_) => None,
        }
    }

    /// `σ = +1` for a lower bound on the value or derivative, `−1` for an upper one.
    #[must_use]
    pub fn sign(self) -> f64 {
        match self {
            SurfaceShape::Increasing(_) | SurfaceShape::AtLeast(_) => 1.0,
            SurfaceShape::Decreasing(_) | SurfaceShape::AtMost(_) => -1.0,
        }
    }

    /// The level `v` compared with (0 for monotonicity).
    #[must_use]
    pub fn level(self) -> f64 {
        match self {
            SurfaceShape::AtLeast(v) | SurfaceShape::AtMost(v) => v,
            _ => 0.0,
        }
    }
}

impl std::fmt::Display for SurfaceShape {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            SurfaceShape::Increasing(d) => write!(f, "increasing in {d}"),
            SurfaceShape::Decreasing(d) => write!(f, "decreasing in {d}"),
            SurfaceShape::AtLeast(v) => write!(f, "min {v}"),
            SurfaceShape::AtMost(v) => write!(f, "max {v}"),
        }
    }
}

/// Every shape a constrained surface fit keeps, each on the whole domain. Built by chaining:
///
/// ```
/// use lekalo::fit::{SurfaceShape, SurfaceShapeConstraints};
/// use lekalo::Direction;
/// let c = SurfaceShapeConstraints::new()
///     .with(SurfaceShape::Increasing(Direction::U))
///     .with(SurfaceShape::Increasing(Direction::V))
///     .with(SurfaceShape::AtLeast(0.0));
/// assert_eq!(c.len(), 3);
/// assert_eq!(c.describe(1), "increasing in v");
/// ```
#[derive(Debug, Clone, Default, PartialEq)]
pub struct SurfaceShapeConstraints {
    /// The shapes.
    pub shapes: Vec<SurfaceShape>,
}

impl SurfaceShapeConstraints {
    /// No constraint.
    #[must_use]
    pub fn new() -> Self {
        Self::default()
    }

    /// Adds `shape`.
    #[must_use]
    pub fn with(mut self, shape: SurfaceShape) -> Self {
        self.shapes.push(shape);
        self
    }

    /// Number of constraints.
    #[must_use]
    pub fn len(&self) -> usize {
        self.shapes.len()
    }

    /// Whether there is no constraint.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.shapes.is_empty()
    }

    /// Constraint `i` in words, as errors name it (empty past the end).
    #[must_use]
    pub fn describe(&self, i: usize) -> String {
        self.shapes
            .get(i)
            .map(ToString::to_string)
            .unwrap_or_default()
    }

    /// Checks the levels and that the bounds leave room, for a surface of degrees `(p, q)`.
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a NaN or infinite bound; [`Error::InvalidArgument`] (key
    /// `"shape constraints"`) for monotonicity in a direction of degree 0;
    /// [`Error::InfeasibleConstraints`] for a lower bound above an upper one.
    pub(crate) fn validate(&self, (p, q): (usize, usize)) -> Result<()> {
        for s in &self.shapes {
            check_finite("shape constraint level", &[s.level()])?;
            if let Some(d) = s.direction() {
                let degree = if d == Direction::U { p } else { q };
                if degree == 0 {
                    return Err(Error::InvalidArgument {
                        what: "shape constraints".into(),
                        reason: format!(
                            "\"{s}\" asks a surface of degree 0 in {d} (piecewise constant, \
                             with jumps) to be monotone: use degree 1 or more in {d}"
                        ),
                    });
                }
            }
        }
        // the tightest lower and upper bounds: a constant between them keeps every shape
        let lower = self
            .shapes
            .iter()
            .enumerate()
            .filter(|(_, s)| matches!(s, SurfaceShape::AtLeast(_)))
            .max_by(|a, b| a.1.level().total_cmp(&b.1.level()));
        let upper = self
            .shapes
            .iter()
            .enumerate()
            .filter(|(_, s)| matches!(s, SurfaceShape::AtMost(_)))
            .min_by(|a, b| a.1.level().total_cmp(&b.1.level()));
        if let (Some((i, lo)), Some((j, hi))) = (lower, upper) {
            if lo.level() > hi.level() {
                return Err(Error::InfeasibleConstraints {
                    conflicting: vec![self.describe(i), self.describe(j)],
                });
            }
        }
        Ok(())
    }
}
