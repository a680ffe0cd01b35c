//! What a shape-constrained surface fit keeps: monotonicity per direction and bounds on the
//! values, on the whole domain or on boxes of it (`docs/theory/fitting.md#shape-constraints-of-surfaces`).

use crate::error::{check_finite, Error, Result};
use crate::Direction;

/// A shape that a surface `z(u, v)` keeps, on its whole domain or on a box of it
/// ([`SurfaceShapeConstraint`]).
///
/// Each is a sign condition `σ·(∂ʳz − v) ≥ 0` for every `(u, v)` of its region, with `∂ʳ` the
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

/// One shape kept on a box of the domain, or on all of it.
///
/// ```
/// use lekalo::fit::{SurfaceShape, SurfaceShapeConstraint};
/// use lekalo::Direction;
/// let c = SurfaceShapeConstraint { shape: SurfaceShape::AtLeast(0.0), region: Some([(0.0, 0.5), (0.25, 1.0)]) };
/// assert_eq!(c.to_string(), "min 0 on [0, 0.5] × [0.25, 1]");
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfaceShapeConstraint {
    /// The shape kept.
    pub shape: SurfaceShape,
    /// Where: `None` for the whole domain, else the box `[u₀, u₁] × [v₀, v₁]` inside the domain
    /// (`u₀ ≤ u₁`, `v₀ ≤ v₁`; an equal pair is a line of the domain, both equal a point).
    pub region: Option<[(f64, f64); 2]>,
}

impl std::fmt::Display for SurfaceShapeConstraint {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self.region {
            None => write!(f, "{}", self.shape),
            Some([(a, b), (c, d)]) => write!(f, "{} on [{a}, {b}] × [{c}, {d}]", self.shape),
        }
    }
}

impl SurfaceShapeConstraint {
    /// The region as a box, the whole `domain` when none is given.
    pub(crate) fn region_or(&self, domain: [(f64, f64); 2]) -> [(f64, f64); 2] {
        self.region.unwrap_or(domain)
    }
}

/// Every shape a constrained surface fit keeps, each on the whole domain or on a box of it.
/// Built by chaining:
///
/// ```
/// use lekalo::fit::{SurfaceShape, SurfaceShapeConstraints};
/// use lekalo::Direction;
/// let c = SurfaceShapeConstraints::new()
///     .with(SurfaceShape::Increasing(Direction::U))
///     .with(SurfaceShape::Increasing(Direction::V))
///     .with_on(SurfaceShape::AtLeast(0.0), (0.0, 0.5), (0.0, 1.0));
/// assert_eq!(c.len(), 3);
/// assert_eq!(c.describe(1), "increasing in v");
/// assert_eq!(c.describe(2), "min 0 on [0, 0.5] × [0, 1]");
/// ```
#[derive(Debug, Clone, Default, PartialEq)]
pub struct SurfaceShapeConstraints {
    /// The shapes with where each holds.
    pub shapes: Vec<SurfaceShapeConstraint>,
}

impl SurfaceShapeConstraints {
    /// No constraint.
    #[must_use]
    pub fn new() -> Self {
        Self::default()
    }

    /// Adds `shape` on the whole domain.
    #[must_use]
    pub fn with(mut self, shape: SurfaceShape) -> Self {
        self.shapes.push(SurfaceShapeConstraint {
            shape,
            region: None,
        });
        self
    }

    /// Adds `shape` on the box `[u₀, u₁] × [v₀, v₁]` of the domain.
    #[must_use]
    pub fn with_on(mut self, shape: SurfaceShape, u: (f64, f64), v: (f64, f64)) -> Self {
        self.shapes.push(SurfaceShapeConstraint {
            shape,
            region: Some([u, v]),
        });
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

    /// Checks the levels and the boxes (finite, ordered, inside `domain`), and that the bounds
    /// leave room where their boxes meet, for a surface of degrees `(p, q)`.
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a NaN or infinite bound or box corner;
    /// [`Error::InvalidArgument`] (key `"shape constraints"`) for monotonicity in a direction of
    /// degree 0, or a box that ends before it starts or leaves the domain;
    /// [`Error::InfeasibleConstraints`] for a lower bound above an upper one on boxes that meet.
    pub(crate) fn validate(&self, (p, q): (usize, usize), domain: [(f64, f64); 2]) -> Result<()> {
        for c in &self.shapes {
            let s = c.shape;
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
            if let Some(region) = c.region {
                for (((a, b), (lo, hi)), name) in region.into_iter().zip(domain).zip(["u", "v"]) {
                    check_finite("shape constraint box", &[a, b])?;
                    if a > b {
                        return Err(Error::InvalidArgument {
                            what: "shape constraints".into(),
                            reason: format!(
                                "the {name} range [{a}, {b}] of \"{c}\" ends before it starts: \
                                 give the smaller {name} first"
                            ),
                        });
                    }
                    if a < lo || b > hi {
                        return Err(Error::InvalidArgument {
                            what: "shape constraints".into(),
                            reason: format!(
                                "the {name} range [{a}, {b}] of \"{c}\" leaves the domain \
                                 [{lo}, {hi}] of the fit in {name}: shrink it to the domain"
                            ),
                        });
                    }
                }
            }
        }
        // a lower bound above an upper one where their boxes meet; elsewhere a surface may
        // pass from one level to the other between the boxes
        let bound = |lower: bool| {
            self.shapes.iter().enumerate().filter(move |(_, c)| {
                matches!(
                    (c.shape, lower),
                    (SurfaceShape::AtLeast(_), true) | (SurfaceShape::AtMost(_), false)
                )
            })
        };
        for (i, lo) in bound(true) {
            for (j, hi) in bound(false) {
                let (a, b) = (lo.region_or(domain), hi.region_or(domain));
                let meet = a.iter().zip(&b).all(|(x, y)| x.0.max(y.0) <= x.1.min(y.1));
                if meet && lo.shape.level() > hi.shape.level() {
                    return Err(Error::InfeasibleConstraints {
                        conflicting: vec![self.describe(i), self.describe(j)],
                    });
                }
            }
        }
        Ok(())
    }
}
