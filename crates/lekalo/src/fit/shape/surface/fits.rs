//! Least-squares surfaces `z(u, v)` that keep their shape, on a grid and on scattered data
//! (`docs/theory/fitting.md#shape-constraints-of-surfaces`): the unconstrained fit first, the
//! quadratic program with the cells' Bernstein rows when it breaks a constraint.

use std::collections::HashSet;

use super::super::check::SHAPE_RTOL;
use super::super::program::{failure_error, solve_sparse_scaled, Failure, SparseUpper};
use super::super::row::Row;
use super::cells::Space;
use super::check::violations;
use super::constraints::SurfaceShapeConstraints;
use crate::basis::{basis_funs_into, BasisScratch};
use crate::error::{Error, Result};
use crate::fit::surface::{scattered_normal_equations, ScatteredNormal};
use crate::fit::ScatteredSurfaceFit;
use crate::fit::{surface_grid_least_squares_at, surface_scattered_least_squares};
use crate::knots::KnotVector;
use crate::numeric::progress::Progress;
use crate::points::{Points, PointsRef};
use crate::surface::BSplineSurface;
use crate::Direction;

/// How far inside its bound every row of the program is asked to stay (rows scaled to unit
/// largest coefficient, coefficients in units of the data's spread), so that the interior
/// point's answer keeps every constraint exactly rather than to the solver's tolerance.
pub(super) const MARGIN: f64 = 1e-10;

/// The least-squares surface `z(u, v)` over a grid of values (as
/// [`surface_grid_least_squares_at`]: `nu × nv` values, value `(i, j)` at `i·nv + j`, at the
/// parameters `(uu, vv)`, degrees `(p, q)`, knots `(ku, kv)`) that keeps every shape of
/// `constraints`, each on the whole domain or on its box: the minimiser of `Σ_ij (z(u_i, v_j) − z_ij)²` over the
/// surfaces whose cells satisfy the Bernstein condition of each shape.
///
/// On a knot cell `z` is a tensor polynomial of degree `(p, q)` and `∂z/∂u` one of degree
/// `(p − 1, q)`; each shape asks the Bernstein coefficients of its function on every cell to
/// have its sign (`∂z/∂u ≥ 0` for increasing in `u`, `z − v ≥ 0` for a lower bound `v`, …;
/// on a box, the coefficients on each piece of a cell inside it),
/// linear inequalities on the control net. They are sufficient for the shape to hold
/// everywhere (the convex-hull property). They are also necessary exactly when the constrained
/// function has degree ≤ 1 in each variable on a cell — bounds for degrees `(1, 1)`,
/// monotonicity in `u` for `p ≤ 2, q ≤ 1` and in `v` for `p ≤ 1, q ≤ 2` — so that the fit is the
/// least-squares optimum among all surfaces that keep the shape; for higher degrees it is the
/// optimum of a slightly stricter problem, whose gap shrinks as the cells shrink
/// (`docs/theory/fitting.md#shape-constraints-of-surfaces`).
///
/// When the unconstrained fit already keeps every condition (to [`SHAPE_RTOL`] of the data's
/// spread, per unit of the parameter for monotonicity) it is returned unchanged. Otherwise the
/// convex quadratic program over the net, with the block-banded normal matrix
/// `(B_uᵀB_u) ⊗ (B_vᵀB_v)` passed as a sparse matrix, is solved by Clarabel (interior point)
/// with every row kept `10⁻¹⁰` inside its bound, and the answer is checked against every
/// condition.
///
/// ```
/// use lekalo::fit::{constrained_surface_grid_least_squares, surface_shape_violations, SurfaceShape, SurfaceShapeConstraints};
/// use lekalo::{Direction, KnotVector, PointsRef};
/// let u: Vec<f64> = (0..12).map(|i| i as f64 / 11.0).collect();
/// let v: Vec<f64> = (0..10).map(|j| j as f64 / 9.0).collect();
/// // a table rising in u and in v, with a ripple that makes the plain fit dip
/// let z: Vec<f64> = u.iter().flat_map(|&x| v.iter().map(move |&y| x + y + 0.2 * (9.0 * x).sin())).collect();
/// let (ku, kv) = (KnotVector::clamped_uniform(2, 6)?, KnotVector::clamped_uniform(2, 5)?);
/// let c = SurfaceShapeConstraints::new()
///     .with(SurfaceShape::Increasing(Direction::U))
///     .with(SurfaceShape::Increasing(Direction::V));
/// let s = constrained_surface_grid_least_squares(PointsRef::from_flat(1, &z)?, (12, 10), (2, 2), (&u, &v), (&ku, &kv), &c)?;
/// assert_eq!(surface_shape_violations(&s, &c)?, vec![0.0, 0.0]);
/// # Ok::<(), lekalo::Error>(())
/// ```
///
/// # Errors
/// The errors of [`surface_grid_least_squares_at`]; [`Error::Dimension`] for values that are
/// not numbers (dimension 1); [`Error::NonFinite`] / [`Error::InvalidArgument`] for a bound that
/// is not finite or monotonicity in a direction of degree 0;
/// [`Error::InfeasibleConstraints`] naming the bounds that contradict each other;
/// [`Error::IllConditioned`] if the solver stops without an answer that keeps the constraints.
pub fn constrained_surface_grid_least_squares(
    values: PointsRef<'_>,
    (nu, nv): (usize, usize),
    (p, q): (usize, usize),
    (uu, vv): (&[f64], &[f64]),
    (ku, kv): (&KnotVector, &KnotVector),
    constraints: &SurfaceShapeConstraints,
) -> Result<BSplineSurface> {
    check_values(
        values.dim(),
        1,
        "grid values of a surface z(u, v) (one number each)",
    )?;
    constraints.validate((p, q), [ku.domain(p), kv.domain(q)])?;
    let free = surface_grid_least_squares_at(values, (nu, nv), (p, q), (uu, vv), (ku, kv))?;
    let z = values.as_slice();
    let scale = Scales::of(z, (ku.domain(p), kv.domain(q)));
    let (ncu, ncv) = free.net_size();
    let space = Space {
        degrees: (p, q),
        knots: (ku.as_slice(), kv.as_slice()),
        net: (ncu, ncv),
    };
    if scale.holds(&space, free.control_points().as_slice(), constraints) {
        return Ok(free);
    }
    // ½‖(B_u ⊗ B_v)c − z‖² in c = center + Y·x: P = G_u ⊗ G_v, q = −B_uᵀ (Z − center) B_v / Y
    let (bu, gu) = basis_and_gram(ku, p, uu, ncu);
    let (bv, gv) = basis_and_gram(kv, q, vv, ncv);
    let center = z[0];
    let lin = grid_linear(z, (nu, nv), (&bu, &bv), (ncu, ncv), center, scale.y);
    let upper = kronecker_upper(&gu, &gv, (ncu, ncv), (p, q));
    let net = solve(&space, &upper, &lin, (center, &scale), constraints, None)?;
    BSplineSurface::from_knot_vectors(
        p,
        q,
        ku.clone(),
        kv.clone(),
        Points::from_flat(1, net)?,
        (ncu, ncv),
    )
}

/// The least-squares surface over scattered rows `(u_k, v_k, z_k)` of
/// [`surface_scattered_least_squares`] (weights, knots, degrees and the second-difference
/// `penalty` as there) that keeps every shape of `constraints` where it is asked. The
/// conditions, their exactness per degree, and the solution are those of
/// [`constrained_surface_grid_least_squares`]; the objective is the banded normal matrix
/// `BᵀWB + penalty·DᵀD` of the unconstrained fit, passed to Clarabel as a sparse matrix.
///
/// ```
/// use lekalo::fit::{constrained_surface_scattered_least_squares, surface_shape_violations, SurfaceShape, SurfaceShapeConstraints};
/// use lekalo::{KnotVector, PointsRef};
/// // 200 rows of a surface above 0 with noise that dips below it
/// let data: Vec<f64> = (0..200).flat_map(|k| {
///     let (u, v) = ((k as f64 * 0.618_034).fract(), (k as f64 * 0.414_214).fract());
///     [u, v, u * v + 0.05 * (37.0 * k as f64).sin()]
/// }).collect();
/// let k = KnotVector::new(vec![0.0, 0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0, 1.0])?;
/// let c = SurfaceShapeConstraints::new().with(SurfaceShape::AtLeast(0.0));
/// let f = constrained_surface_scattered_least_squares(PointsRef::from_flat(3, &data)?, None, (3, 3), (&k, &k), 0.0, &c)?;
/// assert_eq!(surface_shape_violations(&f.surface, &c)?, vec![0.0]);
/// # Ok::<(), lekalo::Error>(())
/// ```
///
/// # Errors
/// The errors of [`surface_scattered_least_squares`]; [`Error::Dimension`] for rows that are
/// not `u, v, z` (three numbers); the constraint errors of
/// [`constrained_surface_grid_least_squares`].
pub fn constrained_surface_scattered_least_squares(
    data: PointsRef<'_>,
    weights: Option<&[f64]>,
    (p, q): (usize, usize),
    (ku, kv): (&KnotVector, &KnotVector),
    penalty: f64,
    constraints: &SurfaceShapeConstraints,
) -> Result<ScatteredSurfaceFit> {
    check_values(
        data.dim(),
        3,
        "scattered rows of a surface z(u, v) (u, v, z)",
    )?;
    constraints.validate((p, q), [ku.domain(p), kv.domain(q)])?;
    let free = surface_scattered_least_squares(data, weights, (p, q), (ku, kv), penalty)?;
    let z: Vec<f64> = data.iter().map(|r| r[2]).collect();
    let scale = Scales::of(&z, (ku.domain(p), kv.domain(q)));
    let space = Space {
        degrees: (p, q),
        knots: (ku.as_slice(), kv.as_slice()),
        net: free.surface.net_size(),
    };
    if scale.holds(
        &space,
        free.surface.control_points().as_slice(),
        constraints,
    ) {
        return Ok(free);
    }
    let ScatteredNormal {
        a,
        rhs,
        center,
        net,
        ..
    } = scattered_normal_equations(data, weights, (p, q), (ku, kv), penalty, &Progress::new())?;
    let upper = SparseUpper::of_band(&a);
    let lin: Vec<f64> = rhs.iter().map(|r| -r / scale.y).collect();
    let coef = solve(&space, &upper, &lin, (center[0], &scale), constraints, None)?;
    let surface = BSplineSurface::from_knot_vectors(
        p,
        q,
        ku.clone(),
        kv.clone(),
        Points::from_flat(1, coef)?,
        net,
    )?;
    let mut residuals = Vec::with_capacity(data.len());
    let mut weighted_rss = 0.0;
    let mut out = [0.0];
    for (k, row) in data.iter().enumerate() {
        surface.eval_into(row[0], row[1], &mut out)?;
        let r = (out[0] - row[2]).abs();
        weighted_rss += weights.map_or(1.0, |w| w[k]) * r * r;
        residuals.push(r);
    }
    Ok(ScatteredSurfaceFit {
        surface,
        residuals,
        weighted_rss,
    })
}

/// Data of one value per point (`expected` numbers a row).
pub(super) fn check_values(dim: usize, expected: usize, what: &'static str) -> Result<()> {
    if dim != expected {
        return Err(Error::Dimension {
            what: what.into(),
            expected,
            got: dim,
        });
    }
    Ok(())
}

/// The scales of the problem: values in units of `Y`, the largest `|z_k − z_0|`, and
/// derivatives in `Y / L` for the domain's length `L` in their direction.
pub(super) struct Scales {
    pub(super) y: f64,
    lengths: (f64, f64),
}

impl Scales {
    pub(super) fn of(z: &[f64], (du, dv): ((f64, f64), (f64, f64))) -> Self {
        let y = z.iter().fold(0.0_f64, |m, v| m.max((v - z[0]).abs()));
        Scales {
            y: if y > 0.0 { y } else { z[0].abs().max(1.0) },
            lengths: (du.1 - du.0, dv.1 - dv.0),
        }
    }

    /// Whether the net `c` keeps every constraint to [`SHAPE_RTOL`] of its scale.
    pub(super) fn holds(
        &self,
        space: &Space<'_>,
        c: &[f64],
        constraints: &SurfaceShapeConstraints,
    ) -> bool {
        violations(space, c, constraints)
            .iter()
            .zip(&constraints.shapes)
            .all(|(v, c)| {
                let scale = match c.shape.direction() {
                    None => self.y,
                    Some(Direction::U) => self.y / self.lengths.0,
                    Some(Direction::V) => self.y / self.lengths.1,
                };
                *v <= SHAPE_RTOL * scale
            })
    }
}

/// The non-zero basis functions of one direction at each of its parameters: `(first index,
/// values)`, the rows of the direction's design matrix `B_a`.
pub(super) type BasisRows = Vec<(usize, Vec<f64>)>;

/// The non-zero basis functions at each parameter (`(first index, values)`) and the Gram
/// matrix `BᵀB` of one direction (dense, `n × n`, banded with half-width `p`).
pub(super) fn basis_and_gram(
    knots: &KnotVector,
    p: usize,
    params: &[f64],
    n: usize,
) -> (BasisRows, Vec<f64>) {
    let mut scratch = BasisScratch::new(p);
    let mut gram = vec![0.0; n * n];
    let rows: BasisRows = params
        .iter()
        .map(|&t| {
            let span = knots.span_unchecked(p, t);
            let mut b = vec![0.0; p + 1];
            basis_funs_into(knots.as_slice(), p, span, t, &mut scratch, &mut b);
            (span - p, b)
        })
        .collect();
    for (first, b) in &rows {
        for (a, x) in b.iter().enumerate() {
            for (c, y) in b.iter().enumerate() {
                gram[(first + a) * n + first + c] += x * y;
            }
        }
    }
    (rows, gram)
}

/// The linear term `−B_uᵀ (Z − center) B_v / Y` of the grid's objective in the program's
/// variables `x = (c − center)/Y` (net order `i·n_v + j`), from each direction's basis rows
/// `(first index, values)` at its parameters.
pub(super) fn grid_linear(
    z: &[f64],
    (nu, nv): (usize, usize),
    (bu, bv): (&BasisRows, &BasisRows),
    (ncu, ncv): (usize, usize),
    center: f64,
    y: f64,
) -> Vec<f64> {
    let mut t = vec![0.0; nu * ncv];
    for i in 0..nu {
        for (j, (first, b)) in bv.iter().enumerate() {
            let zc = (z[i * nv + j] - center) / y;
            for (o, w) in b.iter().enumerate() {
                t[i * ncv + first + o] += w * zc;
            }
        }
    }
    let mut lin = vec![0.0; ncu * ncv];
    for (i, (first, b)) in bu.iter().enumerate() {
        for (o, w) in b.iter().enumerate() {
            let row = (first + o) * ncv;
            for l in 0..ncv {
                lin[row + l] -= w * t[i * ncv + l];
            }
        }
    }
    lin
}

/// The upper triangle of `G_u ⊗ G_v` in the net's order `i·n_v + j`, compressed by columns:
/// entry `((i, j), (k, l))` is `G_u[i][k]·G_v[j][l]`, non-zero only for `|i − k| ≤ p` and
/// `|j − l| ≤ q` (block-banded).
pub(super) fn kronecker_upper(
    gu: &[f64],
    gv: &[f64],
    (nu, nv): (usize, usize),
    (p, q): (usize, usize),
) -> SparseUpper {
    let n = nu * nv;
    let mut colptr = Vec::with_capacity(n + 1);
    let (mut rowval, mut nzval) = (Vec::new(), Vec::new());
    colptr.push(0);
    for k in 0..nu {
        for l in 0..nv {
            for i in k.saturating_sub(p)..=k {
                let top = if i == k { l } else { (l + q).min(nv - 1) };
                for j in l.saturating_sub(q)..=top {
                    let v = gu[i * nu + k] * gv[j * nv + l];
                    if v != 0.0 {
                        rowval.push(i * nv + j);
                        nzval.push(v);
                    }
                }
            }
            colptr.push(rowval.len());
        }
    }
    SparseUpper {
        n,
        colptr,
        rowval,
        nzval,
    }
}

/// The rows `σ(b − v) ≥ 0` of every shape on every cell, in the program's variables
/// `x = (c − center)/Y`, with the index of the shape each comes from; rows equal after scaling
/// to unit largest coefficient (a corner's value is a coefficient of every cell around it)
/// kept once.
pub(super) fn program_rows(
    space: &Space<'_>,
    center: f64,
    y: f64,
    constraints: &SurfaceShapeConstraints,
) -> Vec<(Row, usize)> {
    let (p, q) = space.degrees;
    let width = p * space.net.1 + q + 1;
    let mut seen = HashSet::new();
    let mut out = Vec::new();
    for (owner, constraint) in constraints.shapes.iter().enumerate() {
        let (sigma, level) = (constraint.shape.sign(), constraint.shape.level());
        for cell in space.cell_rows(constraint) {
            let mut coef = vec![0.0; width];
            let mut sum = 0.0;
            for &(o, w) in &cell.terms {
                coef[o] = sigma * w;
                sum += w;
            }
            let row = Row {
                first: cell.first,
                coef,
                aux: None,
                constant: sigma * (center * sum - level) / y,
            };
            let m = row.max_abs();
            if m == 0.0 {
                continue;
            }
            // 10⁻¹² relative (`+ 0.0`: −0 and 0 alike): the same row computed on two cells
            // differs by rounding only
            let quantum = |v: f64| ((v / m * 1e12).round() + 0.0).to_bits();
            let key: (usize, Vec<u64>, u64) = (
                row.first,
                row.coef.iter().map(|v| quantum(*v)).collect(),
                quantum(row.constant),
            );
            if seen.insert(key) {
                out.push((row, owner));
            }
        }
    }
    out
}

/// The net (in the data's units) minimising `½xᵀPx + linᵀx` over `x = (c − center)/Y` subject
/// to every shape's rows, by Clarabel with every row kept [`MARGIN`] inside its bound (without
/// it when that leaves no room, as for equal bounds), checked against every condition. With
/// `objective` (the size of the objective at the unconstrained minimum), the program is scaled
/// by it and accepted only when fully solved ([`solve_sparse_scaled`]).
pub(super) fn solve(
    space: &Space<'_>,
    upper: &SparseUpper,
    lin: &[f64],
    (center, scale): (f64, &Scales),
    constraints: &SurfaceShapeConstraints,
    objective: Option<f64>,
) -> Result<Vec<f64>> {
    let rows = program_rows(space, center, scale.y, constraints);
    let n = upper.n;
    let mut last = None;
    for margin in [MARGIN, 0.0] {
        let tightened: Vec<(Row, usize)> = rows
            .iter()
            .map(|(r, o)| {
                let mut r = r.clone();
                r.constant -= margin * r.max_abs();
                (r, *o)
            })
            .collect();
        match solve_sparse_scaled(upper, lin, (&[], &tightened, &[]), objective) {
            Ok(x) => {
                let net: Vec<f64> = x[..n].iter().map(|v| center + scale.y * v).collect();
                if scale.holds(space, &net, constraints) {
                    return Ok(net);
                }
                last = Some(Failure::Status(
                    "an answer that breaks the constraints by more than the tolerance".into(),
                ));
            }
            Err(f) => last = Some(f),
        }
    }
    Err(failure_error(
        last.unwrap_or(Failure::Status("no answer".into())),
        |i| constraints.describe(i),
    ))
}
