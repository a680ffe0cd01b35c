//! The exact check of a curve against shape constraints (`docs/theory/fitting.md#shape-constraints`):
//! the least value of each shape's Bernstein coefficients on every piece of a knot span, and the
//! scales the violations are measured in.

use super::bernstein::{bernstein_rows, min_on_unit, pieces};
use super::constraints::ShapeConstraints;
use crate::basis::BasisScratch;
use crate::error::{Error, Result};
use crate::fit::data::FitData;
use crate::BSplineCurve;

/// Violation, relative to the data's scale, below which a constraint counts as holding when the
/// unconstrained fit is tested (then it is returned unchanged) and when the constrained one is
/// checked. The scale of `y⁽ʳ⁾` is `Y / L^r`, `Y` the largest `|y_k − y_0|` and `L` the length
/// of the domain.
pub const SHAPE_RTOL: f64 = 5e-13;

/// For each constraint (shapes, points, integrals, then periodicity), by how much `curve`
/// violates it (0 when it holds): `max(0, −min σ(y⁽ʳ⁾ − v))` over the interval for a shape,
/// `|y⁽ʳ⁾(x) − value|` for a point, `|∫_a^b y − value| / (b − a)` for an integral (in units of
/// `y`), and `max_r L^r |y⁽ʳ⁾(end) − y⁽ʳ⁾(start)|` over `r < p` for periodicity (`L` the
/// domain's length).
/// The minimum on each piece of a knot span is exact for `d = p − r ≤ 3` (end values and the
/// roots of the derivative by the quadratic formula) and a lower bound for `d ≥ 4` (least
/// Bernstein coefficient on 64 sub-pieces), so a reported 0 always means the shape holds.
///
/// # Errors
/// [`Error::Dimension`] for a curve that is not 1-D; the constraint errors of
/// [`constrained_least_squares`](super::constrained_least_squares).
pub fn shape_violations(curve: &BSplineCurve, constraints: &ShapeConstraints) -> Result<Vec<f64>> {
    if curve.dim() != 1 {
        return Err(Error::Dimension {
            what: "curve checked against shape constraints (a function y(x))".into(),
            expected: 1,
            got: curve.dim(),
        });
    }
    constraints.validate(curve.domain(), curve.degree())?;
    ShapeCheck::new(curve, constraints).violations(curve, constraints)
}

/// The Bernstein rows of every shape's pieces ([`bernstein_rows`]), computed once from the
/// degree and knots: the exact check of [`shape_violations`] for any control points on them.
pub(super) struct ShapeCheck {
    shapes: Vec<ShapeRows>,
}

/// One shape's check: `σ(y⁽ʳ⁾ − v)` with `r` above the degree (`y⁽ʳ⁾ ≡ 0`, the violation
/// known), or the rows of each piece with the index of its first control point.
enum ShapeRows {
    Constant(f64),
    Pieces {
        sigma: f64,
        level: f64,
        rows: Vec<(usize, Vec<Vec<f64>>)>,
    },
}

impl ShapeCheck {
    pub(super) fn new(curve: &BSplineCurve, constraints: &ShapeConstraints) -> Self {
        let p = curve.degree();
        let t = curve.knots().as_slice();
        let n_ctrl = curve.control_points().len();
        let domain = curve.domain();
        let mut scratch = BasisScratch::new(p);
        let shapes = constraints
            .shapes
            .iter()
            .map(|s| {
                let r = s.shape.derivative_order();
                let (sigma, level) = (s.shape.sign(), s.shape.level());
                if r > p {
                    return ShapeRows::Constant((sigma * level).max(0.0));
                }
                let (a, b) = s.interval.unwrap_or(domain);
                let rows = pieces(t, p, n_ctrl, a, b)
                    .into_iter()
                    .map(|(span, lo, hi)| {
                        (
                            span - p,
                            bernstein_rows(t, p, span, lo, hi, r, &mut scratch),
                        )
                    })
                    .collect();
                ShapeRows::Pieces { sigma, level, rows }
            })
            .collect();
        ShapeCheck { shapes }
    }

    /// [`shape_violations`] of `curve` (on the degree and knots this check was made for).
    fn violations(&self, curve: &BSplineCurve, constraints: &ShapeConstraints) -> Result<Vec<f64>> {
        let ctrl = curve.control_points().as_slice();
        let mut out = Vec::with_capacity(constraints.len());
        let mut bc = Vec::new();
        for s in &self.shapes {
            out.push(match s {
                ShapeRows::Constant(v) => *v,
                ShapeRows::Pieces { sigma, level, rows } => {
                    let mut worst = 0.0_f64;
                    for (first, m) in rows {
                        bc.clear();
                        bc.extend(m.iter().map(|row| {
                            let y: f64 = row.iter().zip(&ctrl[*first..]).map(|(a, c)| a * c).sum();
                            sigma * (y - level)
                        }));
                        worst = worst.max(-min_on_unit(&bc));
                    }
                    worst
                }
            });
        }
        for q in &constraints.points {
            let y = curve
                .eval_derivatives(q.x, q.derivative)?
                .point(q.derivative)[0];
            out.push((y - q.value).abs());
        }
        for g in &constraints.integrals {
            let (a, b) = g.interval;
            out.push((curve.integral(a, b)?[0] - g.value).abs() / (b - a));
        }
        if constraints.periodic {
            let (lo, hi) = curve.domain();
            let p = curve.degree();
            let top = p.saturating_sub(1);
            let (d0, d1) = (
                curve.eval_derivatives(lo, top)?,
                curve.eval_derivatives(hi, top)?,
            );
            let mut worst = 0.0_f64;
            let mut length_r = 1.0;
            for r in 0..p {
                worst = worst.max((d1.point(r)[0] - d0.point(r)[0]).abs() * length_r);
                length_r *= hi - lo;
            }
            out.push(worst);
        }
        Ok(out)
    }
}

/// The scales of the problem: values in units of `y`, derivatives of order `r` in `y / L^r`.
pub(super) struct Scale {
    pub(super) y: f64,
    pub(super) length: f64,
}

impl Scale {
    pub(super) fn of(data: &FitData<'_>, (lo, hi): (f64, f64)) -> Self {
        let v = data.points().as_slice();
        let y = v.iter().fold(0.0_f64, |m, q| m.max((q - v[0]).abs()));
        Scale {
            y: if y > 0.0 { y } else { v[0].abs().max(1.0) },
            length: hi - lo,
        }
    }

    /// The scale of `y⁽ʳ⁾`.
    pub(super) fn of_derivative(&self, r: usize) -> f64 {
        (0..r).fold(self.y, |s, _| s / self.length)
    }
}

/// Whether `curve` keeps every constraint to [`SHAPE_RTOL`] of the scale.
pub(super) fn holds(
    curve: &BSplineCurve,
    constraints: &ShapeConstraints,
    scale: &Scale,
) -> Result<bool> {
    holds_by(
        &ShapeCheck::new(curve, constraints),
        curve,
        constraints,
        scale,
    )
}

/// [`holds`] with the rows of a check made once for the curve's degree and knots.
pub(super) fn holds_by(
    check: &ShapeCheck,
    curve: &BSplineCurve,
    constraints: &ShapeConstraints,
    scale: &Scale,
) -> Result<bool> {
    let v = check.violations(curve, constraints)?;
    let orders = constraints
        .shapes
        .iter()
        .map(|s| s.shape.derivative_order())
        .chain(constraints.points.iter().map(|q| q.derivative))
        // integrals and periodicity are reported in units of y
        .chain(constraints.integrals.iter().map(|_| 0))
        .chain(constraints.periodic.then_some(0));
    Ok(v.iter()
        .zip(orders)
        .all(|(v, r)| *v <= SHAPE_RTOL * scale.of_derivative(r)))
}
