//! The cone program of a shape-constrained fit and its solution by Clarabel
//! (`docs/theory/fitting.md#shape-constraints`): minimise `½ cᵀPc + qᵀc` over the coefficients
//! `c` and one auxiliary variable per second-order cone, subject to linear equalities, linear
//! inequalities and three-dimensional second-order cones (two per cubic, one per quadratic that
//! must be non-negative on a piece), all rows local to a knot span.
//!
//! `P` is the banded matrix of the normal equations ([`SymBand`], half-bandwidth `p`), passed to
//! the solver as a sparse upper triangle: Clarabel's sparse `LDLᵀ` of the KKT matrix then costs
//! O(n) per interior-point iteration for `n` coefficients, whatever the number of data points.

use super::super::banded::SymBand;
use super::bernstein::{argmin_on_unit, bernstein_weights, interior_min};
use super::face_rows::{distinct, independent};
use super::row::{add_rows, Row};
use crate::error::{Error, Result};
use crate::fit::progress::Steps;
use clarabel::algebra::CscMatrix;
use clarabel::solver::{
    DefaultSettingsBuilder, DefaultSolver, IPSolver, SolverStatus, SupportedConeT,
};

/// The program: objective, rows, and the index of the user's constraint each row comes from.
#[derive(Debug)]
pub(crate) struct ConeProgram {
    /// `P` (upper band).
    pub(crate) p: SymBand,
    /// `q`.
    pub(crate) q: Vec<f64>,
    /// `g(x) = 0`.
    pub(crate) equalities: Vec<(Row, usize)>,
    /// `g(x) ≥ 0`.
    pub(crate) inequalities: Vec<(Row, usize)>,
    /// Bernstein coefficients `(b₀, …, b_d)` of a quadratic or cubic that must be `≥ 0` on
    /// `[0, 1]`. A quadratic becomes `b₁ + s ≥ 0` and the cone `‖(b₀ − b₂, 2s)‖ ≤ b₀ + b₂`
    /// with an auxiliary variable `s` (so `s² ≤ b₀b₂`, `b₀, b₂ ≥ 0`). A cubic becomes
    /// `τ·q₁(τ) + (1 − τ)·q₂(τ)` with quadratics `q₁ = (3b₁ − 2a, s, b₃)` and
    /// `q₂ = (b₀, a, 3b₂ − 2s)` (Bernstein coefficients, auxiliary variables `a`, `s`), each
    /// non-negative on the whole line: `‖(u₀ − u₂, 2u₁)‖ ≤ u₀ + u₂` (Markov–Lukács: every cubic
    /// non-negative on `[0, 1]` is such a sum, so the condition is exact).
    pub(crate) polys: Vec<(Vec<Row>, usize)>,
}

/// How a cone program failed: the constraints whose rows carry the certificate of
/// infeasibility, or a solver status.
#[derive(Debug)]
pub(crate) enum Failure {
    /// Owners (indices of the user's constraints) that together admit no solution.
    Infeasible(Vec<usize>),
    /// Any other status.
    Status(String),
}

/// Relative tolerances handed to Clarabel (gap and feasibility), on a problem scaled to unit
/// data and unit rows; the accepted answer is then checked exactly by the caller.
const SOLVER_TOL: f64 = 1e-12;

/// Value (rows scaled to unit largest coefficient, coefficients in units of the data) below
/// which an inequality counts as active for the polish.
const ACTIVE_TOL: f64 = 1e-7;

/// Share of the largest multiplier by which a multiplier of an inequality made equal may be
/// negative (rounding) before the polished face is refused.
const SIGN_RTOL: f64 = 1e-9;

/// Secant steps for the touching points of quadratics and cubics in the polish.
const TOUCH_ROUNDS: usize = 8;

/// First step of the secant method for a touching point (in `τ ∈ [0, 1]`).
const TOUCH_STEP: f64 = 1e-6;

/// Rounds of the active-set method in the polish (each drops one row).
const POLISH_ROUNDS: usize = 8;

/// Share of the largest certificate entry above which a row counts as part of the conflict.
const CERTIFICATE_RTOL: f64 = 1e-6;

impl ConeProgram {
    /// An empty program with objective `½ cᵀPc + qᵀc`.
    pub(crate) fn new(p: SymBand, q: Vec<f64>) -> Self {
        ConeProgram {
            p,
            q,
            equalities: Vec::new(),
            inequalities: Vec::new(),
            polys: Vec::new(),
        }
    }

    /// Solves the program by the interior-point method, every inequality tightened by
    /// `margin` (`g ≥ margin`; quadratics and cubics `≥ margin` on `[0, 1]`); the coefficients
    /// or why not.
    pub(crate) fn solve(&self, margin: f64) -> std::result::Result<Vec<f64>, Failure> {
        let tighten = |r: &Row| {
            let mut r = r.clone();
            r.constant -= margin * r.max_abs();
            r
        };
        let mut inequalities: Vec<(Row, usize)> = self
            .inequalities
            .iter()
            .map(|(r, o)| (tighten(r), *o))
            .collect();
        let mut cones: Vec<([Row; 3], usize)> = Vec::with_capacity(2 * self.polys.len());
        for (poly, o) in &self.polys {
            // a constant's Bernstein coefficients are that constant: one margin for all
            let m = poly.iter().fold(0.0_f64, |m, r| m.max(r.max_abs()));
            let b: Vec<Row> = poly
                .iter()
                .map(|r| {
                    let mut r = r.clone();
                    r.constant -= margin * m;
                    r
                })
                .collect();
            // f·x_aux alone, and `row` plus f·x_aux
            let only = |k: usize, f: f64| Row {
                first: b[0].first,
                coef: vec![0.0; b[0].coef.len()],
                aux: Some((k, f)),
                constant: 0.0,
            };
            let plus = |mut row: Row, k: usize, f: f64| {
                row.aux = Some((k, f));
                row
            };
            if let [b0, b1, b2] = &b[..] {
                let k = cones.len();
                inequalities.push((plus(b1.clone(), k, 1.0), *o));
                cones.push((
                    [add_rows(b0, b2, 1.0), add_rows(b0, b2, -1.0), only(k, 2.0)],
                    *o,
                ));
            } else if let [b0, b1, b2, b3] = &b[..] {
                let (ka, ks) = (cones.len(), cones.len() + 1);
                // q₁ = (u₀, s, b₃) with u₀ = 3b₁ − 2a: (u₀ + b₃, u₀ − b₃, 2s)
                let mut u0 = b1.clone();
                u0.scale(3.0);
                cones.push((
                    [
                        plus(add_rows(&u0, b3, 1.0), ka, -2.0),
                        plus(add_rows(&u0, b3, -1.0), ka, -2.0),
                        only(ks, 2.0),
                    ],
                    *o,
                ));
                // q₂ = (b₀, a, w₂) with w₂ = 3b₂ − 2s: (b₀ + w₂, b₀ − w₂, 2a)
                cones.push((
                    [
                        plus(add_rows(b0, b2, 3.0), ks, -2.0),
                        plus(add_rows(b0, b2, -3.0), ks, 2.0),
                        only(ka, 2.0),
                    ],
                    *o,
                ));
            }
        }
        let mut x = self.run(&self.equalities, &inequalities, &cones)?;
        x.truncate(self.p.n);
        Ok(x)
    }

    /// `½ cᵀPc + qᵀc`.
    pub(crate) fn objective(&self, c: &[f64]) -> f64 {
        let (n, b) = (self.p.n, self.p.b);
        let w = b + 1;
        let mut s = 0.0;
        for i in 0..n {
            s += self.q[i] * c[i] + 0.5 * self.p.a[i * w] * c[i] * c[i];
            for k in 1..w.min(n - i) {
                s += self.p.a[i * w + k] * c[i] * c[i + k];
            }
        }
        s
    }

    /// The exact optimum on the face the interior-point answer `c` lies on (active-set
    /// polishing): every row within [`ACTIVE_TOL`] of its bound is made an equality, and so is
    /// every quadratic or cubic whose minimum on `[0, 1]` is within it (the Bernstein coefficients that
    /// vanish at an end, or value and slope at the touching point `τ*` inside), duplicates
    /// dropped, and the equality-constrained quadratic program solved. `None` when a multiplier of a made-equal row has the wrong sign (the face
    /// guessed is not the optimal one) or the solve fails; the caller also checks the answer
    /// against every constraint exactly. With `margin > 0` every row made equal that comes from
    /// an inequality is set to `margin` instead of zero (rows scaled to unit largest
    /// coefficient): the optimum on the same face of the program tightened as in
    /// [`ConeProgram::solve`], for answers that the rounding of the face's solve leaves a few
    /// ulps outside a constraint.
    ///
    /// # Errors
    /// [`Error::Cancelled`] when `steps`' hook is cancelled (checked between rounds, and at
    /// every row of a degenerate face's independence test).
    pub(crate) fn polish(
        &self,
        c: &[f64],
        margin: f64,
        steps: &Steps<'_, '_>,
    ) -> Result<Option<Vec<f64>>> {
        let n = self.p.n;
        let unit = |r: &Row| {
            let m = r.max_abs();
            let mut r = r.clone();
            if m > 0.0 {
                r.scale(1.0 / m);
            }
            r
        };
        // (row, from an inequality)
        let mut fixed: Vec<(Row, bool)> = self
            .equalities
            .iter()
            .map(|(r, _)| (unit(r), false))
            .collect();
        for (r, _) in &self.inequalities {
            let r = unit(r);
            if r.eval(c, n) <= ACTIVE_TOL {
                fixed.push((r, true));
            }
        }
        // polynomials touching zero inside: (index, τ*)
        let mut touches: Vec<(usize, f64)> = Vec::new();
        for (qi, (poly, _)) in self.polys.iter().enumerate() {
            let m = poly.iter().fold(0.0_f64, |m, r| m.max(r.max_abs()));
            if m == 0.0 {
                continue;
            }
            let b: Vec<f64> = poly.iter().map(|r| r.eval(c, n) / m).collect();
            let d = b.len() - 1;
            let near: Vec<bool> = b.iter().map(|v| v.abs() <= ACTIVE_TOL).collect();
            // zero at an end (b₀ or b_d), with the next coefficients zero too for a root of
            // higher order there (zero slope), or flat (all of them)
            for (j, r) in poly.iter().enumerate() {
                if near[..=j].iter().all(|v| *v) || near[j..].iter().all(|v| *v) {
                    fixed.push((unit(r), true));
                }
            }
            let (tau, value) = argmin_on_unit(&b);
            if !near[0] && !near[d] && value <= ACTIVE_TOL {
                touches.push((qi, tau));
            } else if let Some((tau, value)) = interior_min(&b).filter(|_| d == 3) {
                // a cubic vanishing at an end may touch zero inside too (a quadratic cannot)
                if value <= ACTIVE_TOL {
                    touches.push((qi, tau));
                }
            }
        }
        // A double root inside, at the touching point τ: the value there is zero and so is the
        // slope. For a given τ that is a linear face; the optimal τ is where the slope row's
        // multiplier vanishes (it is the derivative of the optimum in τ, up to a positive
        // factor), found by the secant method from the interior-point answer's τ.
        let mut previous: Vec<Option<(f64, f64)>> = vec![None; touches.len()];
        let mut answer = None;
        for _ in 0..TOUCH_ROUNDS {
            let mut rows = fixed.clone();
            let mut slope_of = vec![None; rows.len()];
            for (k, &(qi, tau)) in touches.iter().enumerate() {
                let (value, slope) = self.touch_rows(qi, tau);
                rows.push((value, true));
                slope_of.push(None);
                rows.push((slope, false));
                slope_of.push(Some(k));
            }
            steps.tick()?;
            let Some((x, nu)) = self.solve_face(rows, slope_of, margin, steps)? else {
                return Ok(None);
            };
            let scale = nu.iter().flatten().fold(0.0_f64, |m, v| m.max(v.abs()));
            answer = Some(x);
            if touches.is_empty() || scale == 0.0 {
                break;
            }
            let mut moved = false;
            for (k, t) in touches.iter_mut().enumerate() {
                let Some(v) = nu[k] else { continue };
                let next = match previous[k] {
                    Some((t0, v0)) if v != v0 => t.1 - v * (t.1 - t0) / (v - v0),
                    _ => t.1 + TOUCH_STEP,
                };
                previous[k] = Some((t.1, v));
                let next = next.clamp(0.0, 1.0);
                moved |= (next - t.1).abs() > 1e-15;
                t.1 = next;
            }
            if !moved {
                break;
            }
        }
        Ok(answer)
    }

    /// The rows "value = 0" and "slope = 0" at `τ` of polynomial `qi`, each scaled by the
    /// polynomial's largest coefficient (the same for every `τ`, so that multipliers compare).
    fn touch_rows(&self, qi: usize, tau: f64) -> (Row, Row) {
        let poly = &self.polys[qi].0;
        let m = poly.iter().fold(0.0_f64, |m, r| m.max(r.max_abs()));
        let combine = |w: &[f64]| {
            let mut row = poly[0].clone();
            for (i, v) in row.coef.iter_mut().enumerate() {
                *v = poly
                    .iter()
                    .zip(w)
                    .map(|(r, wj)| wj * r.coef[i])
                    .sum::<f64>()
                    / m;
            }
            row.constant = poly
                .iter()
                .zip(w)
                .map(|(r, wj)| wj * r.constant)
                .sum::<f64>()
                / m;
            row
        };
        let (value, slope) = bernstein_weights(poly.len() - 1, tau);
        (combine(&value), combine(&slope))
    }

    /// The optimum on the face where every row given is zero, rows equal to an earlier one
    /// dropped, and rows from inequalities whose multipliers come out negative dropped one at a
    /// time (the active-set method); the coefficients and, for each slope row tagged, its
    /// multiplier (`None` if it was dropped). Rows from inequalities are set to `margin`
    /// instead of zero.
    fn solve_face(
        &self,
        rows: Vec<(Row, bool)>,
        tags: Vec<Option<usize>>,
        margin: f64,
        steps: &Steps<'_, '_>,
    ) -> Result<Option<FaceOptimum>> {
        let n = self.p.n;
        let n_tags = tags.iter().flatten().count();
        let tagged: Vec<(Row, bool, Option<usize>)> = rows
            .into_iter()
            .zip(tags)
            .map(|((r, ineq), tag)| (r, ineq, tag))
            .collect();
        // the rows of shapes and points span at most p + 1 columns (P's band)
        let band = self.p.b + 1;
        let mut kept = distinct(tagged, n, band);
        if kept.len() > n {
            // a degenerate face (a flat stretch keeps value, slope and curvature rows at
            // once): more rows than coefficients, so some depend on the others
            kept = independent(kept, n, band, steps)?;
        }
        for (r, ineq, _) in &mut kept {
            if *ineq {
                r.constant -= margin;
            }
        }
        for _ in 0..POLISH_ROUNDS {
            let eq: Vec<(Row, usize)> = kept.iter().map(|(r, _, _)| (r.clone(), 0)).collect();
            let Ok(sol) = self.run(&eq, &[], &[]) else {
                return Ok(None);
            };
            let (x, z) = sol.split_at(n);
            let zmax = z.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
            let worst = kept
                .iter()
                .zip(z)
                .enumerate()
                .filter(|(_, ((_, ineq, _), zi))| *ineq && **zi < -SIGN_RTOL * zmax)
                .min_by(|a, b| a.1 .1.total_cmp(b.1 .1))
                .map(|(i, _)| i);
            match worst {
                None => {
                    // the solver scaled each row to unit largest coefficient: undo it
                    let mut nu = vec![None; n_tags];
                    for ((r, _, tag), zi) in kept.iter().zip(z) {
                        if let Some(k) = tag {
                            let m = r.max_abs();
                            nu[*k] = Some(if m > 0.0 { zi / m } else { 0.0 });
                        }
                    }
                    return Ok(Some((x.to_vec(), nu)));
                }
                Some(i) => {
                    kept.remove(i);
                }
            }
        }
        Ok(None)
    }

    /// Clarabel on the objective with the rows given; the variables (coefficients, then one
    /// auxiliary per cone).
    fn run(
        &self,
        equalities: &[(Row, usize)],
        inequalities: &[(Row, usize)],
        cone_rows: &[([Row; 3], usize)],
    ) -> std::result::Result<Vec<f64>, Failure> {
        let upper = SparseUpper::of_band(&self.p);
        solve_sparse(&upper, &self.q, equalities, inequalities, cone_rows)
    }
}

/// The upper triangle of a symmetric `n × n` matrix in compressed columns (rows sorted within
/// each column): the objective of a program whose normal matrix is not banded, as a surface's
/// (block-banded, `docs/theory/fitting.md#shape-constraints-of-surfaces`).
#[derive(Debug, Clone)]
pub(crate) struct SparseUpper {
    pub(crate) n: usize,
    pub(crate) colptr: Vec<usize>,
    pub(crate) rowval: Vec<usize>,
    pub(crate) nzval: Vec<f64>,
}

impl SparseUpper {
    /// The upper triangle of the symmetric band `p`, column by column, its zeros left out.
    pub(crate) fn of_band(p: &SymBand) -> Self {
        let (n, w) = (p.n, p.b + 1);
        let mut colptr = Vec::with_capacity(n + 1);
        let (mut rowval, mut nzval) = (Vec::new(), Vec::new());
        colptr.push(0);
        for j in 0..n {
            for i in j.saturating_sub(p.b)..=j {
                let v = p.a[i * w + j - i];
                if v != 0.0 {
                    rowval.push(i);
                    nzval.push(v);
                }
            }
            colptr.push(rowval.len());
        }
        SparseUpper {
            n,
            colptr,
            rowval,
            nzval,
        }
    }
}

/// Clarabel on `½ xᵀPx + qᵀx` over the `P.n` variables and one auxiliary per cone, with the
/// rows given (each scaled to unit largest coefficient, `P` and `q` by `P`'s largest diagonal
/// entry); the variables, then the multipliers of the rows in the order given (equalities,
/// inequalities, cones), or why not.
pub(crate) fn solve_sparse(
    upper: &SparseUpper,
    q: &[f64],
    equalities: &[(Row, usize)],
    inequalities: &[(Row, usize)],
    cone_rows: &[([Row; 3], usize)],
) -> std::result::Result<Vec<f64>, Failure> {
    solve_sparse_scaled(upper, q, (equalities, inequalities, cone_rows), None)
}

/// The rows of a program, each with the constraint it comes from: equalities, inequalities,
/// and second-order cones of three rows.
pub(crate) type ProgramRows<'a> = (
    &'a [(Row, usize)],
    &'a [(Row, usize)],
    &'a [([Row; 3], usize)],
);

/// [`solve_sparse`], with `P` and `q` divided by `objective` when it is given: the size of the
/// objective at the unconstrained minimum, `|½ qᵀx₀|`, for programs whose Hessian has
/// eigenvalues many orders apart (a heavy penalty beside the data's flat directions). Scaled
/// by `P`'s largest entry, such an objective is tiny, and the solver's absolute gap tolerance
/// would accept an answer far from the minimum; scaled by its own size, the tolerances are
/// relative to it. Only a fully solved program is then accepted: Clarabel's `AlmostSolved`
/// (the reduced tolerances it falls back to when its steps stall) is reported as a failure.
pub(crate) fn solve_sparse_scaled(
    upper: &SparseUpper,
    q: &[f64],
    (equalities, inequalities, cone_rows): ProgramRows<'_>,
    objective: Option<f64>,
) -> std::result::Result<Vec<f64>, Failure> {
    let n = upper.n;
    let nv = n + cone_rows.len();
    let pmax = (0..n).fold(0.0_f64, |m, j| {
        (upper.colptr[j]..upper.colptr[j + 1])
            .filter(|&k| upper.rowval[k] == j)
            .fold(m, |m, k| m.max(upper.nzval[k].abs()))
    });
    let objective = objective.filter(|f| *f > 0.0 && f.is_finite());
    let pscale = match objective {
        Some(f) => 1.0 / f,
        None if pmax > 0.0 => 1.0 / pmax,
        None => 1.0,
    };
    let mut colptr = upper.colptr.clone();
    colptr.resize(nv + 1, upper.rowval.len());
    let pm = CscMatrix::new(
        nv,
        nv,
        colptr,
        upper.rowval.clone(),
        upper.nzval.iter().map(|v| v * pscale).collect(),
    );
    let mut q: Vec<f64> = q.iter().map(|v| v * pscale).collect();
    q.resize(nv, 0.0);
    // rows: equalities, inequalities, cones; each row (cone) scaled to unit largest entry
    let mut rows: Vec<Row> = Vec::new();
    let mut owners = Vec::new();
    let unit = |mut r: Row| {
        let m = r.max_abs();
        if m > 0.0 {
            r.scale(1.0 / m);
        }
        r
    };
    for (r, o) in equalities.iter().chain(inequalities) {
        rows.push(unit(r.clone()));
        owners.push(*o);
    }
    for (cone, o) in cone_rows {
        let m = cone.iter().fold(0.0_f64, |m, r| m.max(r.max_abs()));
        for r in cone {
            let mut r = r.clone();
            if m > 0.0 {
                r.scale(1.0 / m);
            }
            rows.push(r);
            owners.push(*o);
        }
    }
    // A x + s = b with s = g(x): A = −coef, b = constant
    let mut ii = Vec::new();
    let mut jj = Vec::new();
    let mut vv = Vec::new();
    let mut bvec = Vec::with_capacity(rows.len());
    for (k, r) in rows.iter().enumerate() {
        for (i, &c) in r.coef.iter().enumerate() {
            if c != 0.0 {
                ii.push(k);
                jj.push(r.first + i);
                vv.push(-c);
            }
        }
        if let Some((a, c)) = r.aux {
            ii.push(k);
            jj.push(n + a);
            vv.push(-c);
        }
        bvec.push(r.constant);
    }
    let am = CscMatrix::new_from_triplets(rows.len(), nv, ii, jj, vv);
    let mut cones = Vec::new();
    if !equalities.is_empty() {
        cones.push(SupportedConeT::ZeroConeT(equalities.len()));
    }
    if !inequalities.is_empty() {
        cones.push(SupportedConeT::NonnegativeConeT(inequalities.len()));
    }
    cones.extend(
        cone_rows
            .iter()
            .map(|_| SupportedConeT::SecondOrderConeT(3)),
    );
    // an equality-constrained run (the polish) is one Newton step: refine its linear solve
    // to the last digit
    let polish = inequalities.is_empty() && cone_rows.is_empty();
    let refine = if polish { 1e-16 } else { 1e-13 };
    let settings = DefaultSettingsBuilder::default()
        .verbose(false)
        .iterative_refinement_reltol(refine)
        .iterative_refinement_abstol(refine)
        .iterative_refinement_max_iter(if polish { 50 } else { 10 })
        .tol_gap_abs(SOLVER_TOL)
        .tol_gap_rel(SOLVER_TOL)
        .tol_feas(SOLVER_TOL)
        .tol_infeas_abs(1e-10)
        .tol_infeas_rel(1e-10)
        .max_iter(400)
        .build()
        .map_err(|e| Failure::Status(format!("solver settings: {e:?}")))?;
    let mut solver = DefaultSolver::new(&pm, &q, &am, &bvec, &cones, settings)
        .map_err(|e| Failure::Status(format!("solver set-up: {e}")))?;
    solver.solve();
    let sol = &solver.solution;
    match sol.status {
        SolverStatus::AlmostSolved if objective.is_some() => Err(Failure::Status(
            "only to reduced accuracy (AlmostSolved)".into(),
        )),
        SolverStatus::Solved | SolverStatus::AlmostSolved => {
            let mut out = sol.x.clone();
            // the multipliers of the rows, in the order given (for the polish's signs)
            out.extend(&sol.z);
            Ok(out)
        }
        SolverStatus::PrimalInfeasible | SolverStatus::AlmostPrimalInfeasible => {
            let zmax = sol.z.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
            let mut conflict: Vec<usize> = sol
                .z
                .iter()
                .zip(&owners)
                .filter(|(z, _)| z.abs() > CERTIFICATE_RTOL * zmax)
                .map(|(_, &o)| o)
                .collect();
            conflict.sort_unstable();
            conflict.dedup();
            Err(Failure::Infeasible(conflict))
        }
        s => Err(Failure::Status(format!("{s:?}"))),
    }
}

/// The optimum on a face: the coefficients, and the multiplier of each tagged slope row (`None`
/// if it was dropped).
type FaceOptimum = (Vec<f64>, Vec<Option<f64>>);

/// The upper band of `RᵀR` for the banded triangle `R` (`r[i·bw + k] = R[i][i + k]`):
/// the normal-equations matrix of a least-squares problem, half-bandwidth `bw − 1`. O(n·bw²).
pub(crate) fn gram_of_triangle(r: &[f64], n: usize, bw: usize) -> SymBand {
    let mut g = SymBand::zeros(n, bw.saturating_sub(1));
    // (RᵀR)_ij = Σ_k R_ki R_kj, k ≤ i ≤ j < k + bw
    for k in 0..n {
        let row = &r[k * bw..(k + 1) * bw];
        for a in 0..bw.min(n - k) {
            for c in a..bw.min(n - k) {
                let v = row[a] * row[c];
                if v != 0.0 {
                    g.add(k + a, k + c, v);
                }
            }
        }
    }
    g
}

/// `Rᵀ z` for the banded triangle `R` and one right-hand side `z`.
pub(crate) fn triangle_transpose_times(r: &[f64], z: &[f64], n: usize, bw: usize) -> Vec<f64> {
    let mut out = vec![0.0; n];
    for k in 0..n {
        for a in 0..bw.min(n - k) {
            out[k + a] += r[k * bw + a] * z[k];
        }
    }
    out
}

/// The error for a failed program: the conflicting constraints by name, or the status.
pub(crate) fn failure_error(f: Failure, describe: impl Fn(usize) -> String) -> Error {
    match f {
        Failure::Infeasible(owners) => Error::InfeasibleConstraints {
            conflicting: owners.into_iter().map(describe).collect(),
        },
        Failure::Status(s) => Error::IllConditioned {
            reason: format!(
                "the cone program of the shape constraints stopped without a solution ({s}); \
                 rescale the data or use fewer knots"
            ),
        },
    }
}
