//! The cone program of a shape-constrained fit solved on a working set of pieces
//! (`docs/theory/fitting.md#shape-constraints`): the pieces near or past their bounds enter the
//! program, which is solved again with more pieces until its optimum keeps every row; then the
//! polish on the active face and the exact check.

use super::bernstein::{bernstein_rows, min_on_unit, pieces};
use super::check::{holds_by, Scale, ShapeCheck};
use super::constraints::ShapeConstraints;
use super::program::{failure_error, ConeProgram};
use super::row::Row;
use crate::basis::{basis_ders_into, BasisScratch};
use crate::error::Result;
use crate::fit::banded::SymBand;
use crate::fit::progress::Steps;
use crate::knots::KnotVector;
use crate::points::Points;
use crate::BSplineCurve;

/// Which rows of the cone program are solved: a working set of pieces grown until the answer
/// keeps every row (what the fits use), or every row at once (crate-private, so that tests can
/// compare the two).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Rows {
    /// The working set (`docs/theory/fitting.md#shape-constraints`).
    WorkingSet,
    /// The whole program.
    All,
}

/// The rows of one shape on one piece of a knot span: the unit the working set adds.
struct Piece {
    /// The index of the user's constraint.
    owner: usize,
    /// `d + 1` inequalities (`d ≤ 1` or `d ≥ 4`) or the Bernstein coefficients of a quadratic
    /// or cubic.
    rows: PieceRows,
}

/// The conditions of a [`Piece`] (`docs/theory/fitting.md#shape-constraints`, the table by `d`).
enum PieceRows {
    /// `b_j ≥ 0` for `d ≤ 1` (exact) and `d ≥ 4` (sufficient).
    Linear(Vec<Row>),
    /// `(b₀, …, b_d)` of a quadratic or cubic `≥ 0` on `[0, 1]` (cones in the program, exact).
    Cone(Vec<Row>),
}

impl Piece {
    /// The least value of the piece's conditions at the coefficients `c`, rows scaled to unit
    /// largest coefficient as the solver sees them: the least row for linear conditions, the
    /// exact minimum on `[0, 1]` of the quadratic or cubic (its coefficients scaled together).
    fn slack(&self, c: &[f64], n: usize) -> f64 {
        let unit = |r: &Row, m: f64| r.eval(c, n) / if m > 0.0 { m } else { 1.0 };
        match &self.rows {
            PieceRows::Linear(rows) => rows
                .iter()
                .map(|r| unit(r, r.max_abs()))
                .fold(f64::INFINITY, f64::min),
            PieceRows::Cone(b) => {
                let m = b.iter().fold(0.0_f64, |m, r| m.max(r.max_abs()));
                min_on_unit(&b.iter().map(|r| unit(r, m)).collect::<Vec<_>>())
            }
        }
    }
}

/// Slack (rows scaled to unit largest coefficient, coefficients in units of the data) below
/// which a piece joins the working set: above the polish's activity threshold, so that every
/// row the polish of the whole program would make an equality is in the working set.
const WORKING_MARGIN: f64 = 1e-6;

/// Rounds of the working set before the whole program is solved instead.
const WORKING_ROUNDS: usize = 12;

/// Builds and solves the cone program of the constraints for the objective `½cᵀPc + qᵀc` in
/// scaled coefficients `c = (control − center)/Y`; returns the scaled coefficients. With
/// [`Rows::WorkingSet`], `start` (the unconstrained optimum, scaled) chooses the first pieces.
#[allow(clippy::too_many_arguments)] // objective (two), knots, degree, constraints, scales (two), start, strategy
pub(super) fn solve_program(
    p: SymBand,
    q: Vec<f64>,
    knots: &[f64],
    degree: usize,
    constraints: &ShapeConstraints,
    scale: &Scale,
    center: f64,
    start: &[f64],
    strategy: Rows,
    steps: &Steps<'_, '_>,
) -> Result<Vec<f64>> {
    let n = p.n;
    let mut scratch = BasisScratch::new(degree);
    let domain = (knots[degree], knots[n]);
    let mut pieces_all: Vec<Piece> = Vec::new();
    for (owner, s) in constraints.shapes.iter().enumerate() {
        let r = s.shape.derivative_order();
        if r > degree {
            // y⁽ʳ⁾ ≡ 0 satisfies every derivative shape (levels are 0)
            continue;
        }
        let sigma = s.shape.sign();
        // σ(y⁽ʳ⁾ − v) in scaled units: y⁽ʳ⁾ = Y·c⁽ʳ⁾ + center·[r = 0]
        let level = (s.shape.level() - if r == 0 { center } else { 0.0 }) / scale.y;
        let (a, b) = s.interval.unwrap_or(domain);
        let d = degree - r;
        for (span, lo, hi) in pieces(knots, degree, n, a, b) {
            let m = bernstein_rows(knots, degree, span, lo, hi, r, &mut scratch);
            let first = span - degree;
            let row = |j: usize| Row {
                first,
                coef: m[j].iter().map(|v| sigma * v).collect(),
                aux: None,
                constant: -sigma * level,
            };
            let rows = if lo == hi {
                // a shape at one point: every Bernstein coefficient is the value there
                PieceRows::Linear(vec![row(0)])
            } else if d == 2 || d == 3 {
                PieceRows::Cone((0..=d).map(row).collect())
            } else {
                PieceRows::Linear((0..=d).map(row).collect())
            };
            pieces_all.push(Piece { owner, rows });
        }
    }
    let n_shapes = constraints.shapes.len();
    let kv = KnotVector::from_raw(knots.to_vec());
    let mut equalities = Vec::with_capacity(constraints.points.len());
    for (i, c) in constraints.points.iter().enumerate() {
        let span = kv.find_span(degree, c.x)?;
        let w = degree + 1;
        let mut ders = vec![0.0; w * w];
        basis_ders_into(knots, degree, span, c.x, degree, &mut scratch, &mut ders);
        let r = c.derivative;
        let value = (c.value - if r == 0 { center } else { 0.0 }) / scale.y;
        equalities.push((
            Row {
                first: span - degree,
                coef: ders[r * w..(r + 1) * w].to_vec(),
                aux: None,
                constant: -value,
            },
            n_shapes + i,
        ));
    }
    integral_and_periodic_rows(
        &mut equalities,
        (knots, degree, &kv),
        constraints,
        (scale, center),
        &mut scratch,
    )?;
    let program = |chosen: &[bool]| {
        let mut prog = ConeProgram::new(p.clone(), q.clone());
        prog.equalities.clone_from(&equalities);
        for (piece, _) in pieces_all.iter().zip(chosen).filter(|(_, c)| **c) {
            match &piece.rows {
                PieceRows::Linear(rows) => prog
                    .inequalities
                    .extend(rows.iter().map(|r| (r.clone(), piece.owner))),
                PieceRows::Cone(b) => prog.polys.push((b.clone(), piece.owner)),
            }
        }
        prog
    };
    let finish = |prog: &ConeProgram, interior: Vec<f64>| {
        finish_program(
            prog,
            interior,
            (degree, knots),
            constraints,
            (scale, center),
            steps,
        )
    };
    let fail = |f| failure_error(f, |i| constraints.describe(i));
    let all = vec![true; pieces_all.len()];
    if strategy == Rows::All || start.len() != n {
        let prog = program(&all);
        let interior = prog.solve(0.0).map_err(fail)?;
        return finish(&prog, interior);
    }
    // The working set: the pieces the unconstrained optimum violates or nearly violates, and
    // their neighbours of the same constraint; grown by the pieces each answer violates. An
    // answer of the relaxation that keeps every row of the whole program is its optimum.
    let mut chosen = vec![false; pieces_all.len()];
    let grow = |chosen: &mut [bool], c: &[f64]| {
        let mut added = false;
        for i in 0..pieces_all.len() {
            if chosen[i] || pieces_all[i].slack(c, n) >= WORKING_MARGIN {
                continue;
            }
            added = true;
            chosen[i] = true;
            let owner = pieces_all[i].owner;
            for j in [i.wrapping_sub(1), i + 1] {
                if pieces_all.get(j).is_some_and(|pj| pj.owner == owner) {
                    chosen[j] = true;
                }
            }
        }
        added
    };
    grow(&mut chosen, start);
    if equalities.is_empty() && !chosen.contains(&true) {
        // nothing near a bound (the unconstrained fit failed the exact check by rounding only):
        // the program needs a row, and the whole one is small enough then
        chosen.fill(true);
    }
    for _ in 0..WORKING_ROUNDS {
        steps.tick()?;
        let prog = program(&chosen);
        let interior = prog.solve(0.0).map_err(fail)?;
        if grow(&mut chosen, &interior) {
            continue;
        }
        let c = finish(&prog, interior)?;
        if !grow(&mut chosen, &c) {
            return Ok(c);
        }
    }
    let prog = program(&all);
    let interior = prog.solve(0.0).map_err(fail)?;
    finish(&prog, interior)
}

/// The equalities of integrals and of periodicity (owners after the shapes and points), in
/// scaled coefficients `c = (control − center)/Y`. `∫_α^β y` on a piece of a span is `h/(p + 1)`
/// times the sum of its Bernstein coefficients (each Bernstein polynomial integrates to
/// `1/(p + 1)` on `[0, 1]`), and the basis sums to 1, so `∫_a^b y = Y·w·c + center·(b − a)`.
/// Periodicity is `y⁽ʳ⁾(end) − y⁽ʳ⁾(start) = 0` for `r < p`, one row over the first and last
/// `p + 1` coefficients each (the center cancels).
fn integral_and_periodic_rows(
    equalities: &mut Vec<(Row, usize)>,
    (knots, degree, kv): (&[f64], usize, &KnotVector),
    constraints: &ShapeConstraints,
    (scale, center): (&Scale, f64),
    scratch: &mut BasisScratch,
) -> Result<()> {
    let n = knots.len() - degree - 1;
    let owner = constraints.shapes.len() + constraints.points.len();
    for (i, g) in constraints.integrals.iter().enumerate() {
        let (a, b) = g.interval;
        let ps = pieces(knots, degree, n, a, b);
        let (Some(&(s0, _, _)), Some(&(s1, _, _))) = (ps.first(), ps.last()) else {
            continue;
        };
        let first = s0 - degree;
        let mut coef = vec![0.0; s1 + 1 - first];
        for (span, lo, hi) in ps {
            let m = bernstein_rows(knots, degree, span, lo, hi, 0, scratch);
            let f = (hi - lo) / (degree + 1) as f64;
            for row in &m {
                for (k, v) in row.iter().enumerate() {
                    coef[span - degree + k - first] += f * v;
                }
            }
        }
        let constant = -(g.value - center * (b - a)) / scale.y;
        equalities.push((
            Row {
                first,
                coef,
                aux: None,
                constant,
            },
            owner + i,
        ));
    }
    if constraints.periodic {
        let w = degree + 1;
        let (lo, hi) = (knots[degree], knots[n]);
        let ders_at = |x: f64, scratch: &mut BasisScratch| -> Result<(usize, Vec<f64>)> {
            let span = kv.find_span(degree, x)?;
            let mut d = vec![0.0; w * w];
            basis_ders_into(knots, degree, span, x, degree, scratch, &mut d);
            Ok((span - degree, d))
        };
        let (f0, d0) = ders_at(lo, scratch)?;
        let (f1, d1) = ders_at(hi, scratch)?;
        for r in 0..degree {
            let mut coef = vec![0.0; n];
            for k in 0..w {
                coef[f0 + k] -= d0[r * w + k];
                coef[f1 + k] += d1[r * w + k];
            }
            equalities.push((
                Row {
                    first: 0,
                    coef,
                    aux: None,
                    constant: 0.0,
                },
                owner + constraints.integrals.len(),
            ));
        }
    }
    Ok(())
}

/// The exact answer from the interior-point answer `interior` of `prog`: its polish on the
/// active face, checked against every constraint exactly
/// (`docs/theory/fitting.md#shape-constraints`).
fn finish_program(
    prog: &ConeProgram,
    interior: Vec<f64>,
    (degree, knots): (usize, &[f64]),
    constraints: &ShapeConstraints,
    (scale, center): (&Scale, f64),
    steps: &Steps<'_, '_>,
) -> Result<Vec<f64>> {
    let n = prog.p.n;
    let rows = ShapeCheck::new(
        &curve_of(degree, knots.to_vec(), &interior[..n], scale, center),
        constraints,
    );
    let check = |c: &[f64]| {
        holds_by(
            &rows,
            &curve_of(degree, knots.to_vec(), c, scale, center),
            constraints,
            scale,
        )
    };
    // polish on the active face, kept only if it keeps every constraint exactly and does not
    // raise the objective; when the face's own rounding leaves it a few ulps outside a
    // constraint, polish the same face tightened by the margin
    let bound = prog.objective(&interior) + POLISH_RTOL * (1.0 + prog.objective(&interior).abs());
    let mut start = interior.clone();
    for margin in [0.0, ROUNDING_MARGIN, FEASIBILITY_MARGIN] {
        let (exact, last) = polish_exact(prog, &start, (margin, bound), &check, steps)?;
        if let Some(c) = exact {
            return Ok(c);
        }
        // the tightened face is polished from where the first polish ended
        start = last;
    }
    if check(&interior)? {
        return Ok(interior);
    }
    // the interior-point answer misses a constraint by its rounding and the polish found no
    // face: solve again with every inequality tightened by a margin above that rounding
    if let Ok(c) = prog.solve(FEASIBILITY_MARGIN) {
        if check(&c)? {
            return Ok(c);
        }
    }
    Ok(interior)
}

/// The polished answer from `start` (up to four rounds while a touching point of a quadratic
/// or cubic moves), if one keeps every constraint exactly (`check`) with an objective at most `bound`;
/// and the last answer polished (or `start`).
fn polish_exact(
    prog: &ConeProgram,
    start: &[f64],
    (margin, bound): (f64, f64),
    check: &dyn Fn(&[f64]) -> Result<bool>,
    steps: &Steps<'_, '_>,
) -> Result<(Option<Vec<f64>>, Vec<f64>)> {
    let mut best = None;
    let mut current = start.to_vec();
    for _ in 0..4 {
        steps.tick()?;
        let Some(c) = prog.polish(&current, margin, steps)? else {
            break;
        };
        let moved = c
            .iter()
            .zip(&current)
            .any(|(a, b)| (a - b).abs() > 1e-15 * (1.0 + a.abs()));
        if prog.objective(&c) <= bound && check(&c)? {
            best = Some(c.clone());
        }
        current = c;
        if !moved {
            break;
        }
    }
    Ok((best, current))
}

/// Margin (rows scaled to unit largest coefficient, coefficients in units of the data) by which
/// inequalities are tightened when neither the interior-point answer nor its polish keeps them
/// exactly; the answer moves by about this much.
const FEASIBILITY_MARGIN: f64 = 1e-10;

/// Margin (as [`FEASIBILITY_MARGIN`]) of the first tightened polish: above the rounding of a
/// face's solve (a few ulps of rows whose largest coefficient is up to `1/h^r` for spans `h`),
/// small enough that the objective rises by far less than [`POLISH_RTOL`].
const ROUNDING_MARGIN: f64 = 1e-13;

/// Relative rise of the objective above the interior-point answer's that a polished answer may
/// show (rounding) and still be taken.
const POLISH_RTOL: f64 = 1e-11;

/// The scaled coefficients `(control − center)/Y` of `curve` (the inverse of [`curve_of`]).
pub(super) fn scaled(curve: &BSplineCurve, scale: &Scale, center: f64) -> Vec<f64> {
    curve
        .control_points()
        .as_slice()
        .iter()
        .map(|v| (v - center) / scale.y)
        .collect()
}

/// The curve of scaled coefficients `c`: control points `center + Y·c`.
pub(super) fn curve_of(
    degree: usize,
    knots: Vec<f64>,
    c: &[f64],
    scale: &Scale,
    center: f64,
) -> BSplineCurve {
    let ctrl: Vec<f64> = c.iter().map(|v| center + scale.y * v).collect();
    BSplineCurve::from_raw(degree, knots, Points::from_raw(ctrl, 1))
}
