//! The smoothing spline on a grid `z(u, v)` that keeps its shape
//! (`docs/theory/fitting.md#shape-constrained-smoothing-of-surfaces`): the penalised objective of
//! [`tensor_grid_smoothing_spline`] as the quadratic program's objective, with the weights
//! given, chosen by GCV for the unconstrained spline, or scaled together until the residual is
//! `s`.

use super::super::fits::{
    bisect_condition, digits_down, digits_up, least_residual_error, CONDITION_DECADES,
    CONDITION_RTOL,
};
use super::cells::Space;
use super::constraints::SurfaceShapeConstraints;
use super::fits::{
    basis_and_gram, check_values, grid_linear, kronecker_upper, solve, BasisRows, Scales,
};
use super::whitened::{solve_whitened, Factor};
use crate::error::{Error, Result};
use crate::fit::{FitData, Lambda, Smoother};
use crate::knots::KnotVector;
use crate::message::readable;
use crate::points::{Points, PointsRef};
use crate::surface::BSplineSurface;
use crate::{tensor_grid_smoothing_spline, TensorGridSmoothingSpline};
use crate::{Arg, What};

/// The result of [`constrained_surface_grid_smoothing_spline`] and
/// [`constrained_surface_grid_smoothing_condition`].
#[derive(Debug, Clone, PartialEq)]
pub struct SurfaceGridSmoothing {
    /// The fitted surface: bicubic, with a knot at every grid coordinate (`(n_u + 2) × (n_v + 2)`
    /// control points), the space of [`tensor_grid_smoothing_spline`].
    pub surface: BSplineSurface,
    /// The penalty weights `(λ_u, λ_v)` of the fit (given, chosen by GCV for the unconstrained
    /// spline, or scaled to meet the smoothing condition).
    pub lambdas: [f64; 2],
    /// `RSS = Σ_ij (z(u_i, v_j) − z_ij)²` over the nodes.
    pub residual: f64,
}

/// The smoothing spline on the grid `uu × vv` of values `z_ij` (one number a node, value
/// `(i, j)` at `i·n_v + j`) with the penalty weights `(λ_u, λ_v)` of
/// [`tensor_grid_smoothing_spline`], that keeps every shape of `constraints` (each on the
/// whole domain or on its box). It minimises that spline's objective
///
/// `‖(B_u ⊗ B_v) c − z‖² + cᵀ((G_u + λ_uΩ_u) ⊗ (G_v + λ_vΩ_v) − G_u ⊗ G_v) c`
///
/// (`G_a = B_aᵀB_a`, `Ω_a = ∫ B_a'' B_a''ᵀ`, clamped cubic B-splines with a knot at every grid
/// coordinate), whose Hessian `(G_u + λ_uΩ_u) ⊗ (G_v + λ_vΩ_v)` is whitened by each
/// direction's banded factors about the unconstrained minimum before Clarabel sees it (so
/// that heavy and light weights are solved alike), over the surfaces whose cells satisfy the Bernstein
/// condition of each shape (as [`constrained_surface_grid_least_squares`](super::constrained_surface_grid_least_squares):
/// sufficient everywhere; for bicubic cells a slightly stricter problem than the shape itself).
///
/// With [`Lambda::Gcv`] in a direction, its weight is the one generalised cross-validation
/// chooses for the **unconstrained** spline ([`tensor_grid_smoothing_spline`] with the same
/// weights); the constrained optimum is then taken at those weights, as the curves'
/// [`constrained_smoothing_spline`](crate::fit::constrained_smoothing_spline) does. When the
/// unconstrained spline already keeps every condition (to
/// [`SHAPE_RTOL`](crate::fit::SHAPE_RTOL)) it is returned unchanged
/// (`docs/theory/fitting.md#shape-constrained-smoothing-of-surfaces`).
///
/// ```
/// use lekalo::fit::{constrained_surface_grid_smoothing_spline, surface_shape_violations, Lambda, SurfaceShape, SurfaceShapeConstraints};
/// use lekalo::{Direction, PointsRef};
/// let u: Vec<f64> = (0..14).map(|i| i as f64 / 13.0).collect();
/// let v: Vec<f64> = (0..10).map(|j| j as f64 / 9.0).collect();
/// // rising in u, with a ripple that makes the smoothing spline dip
/// let z: Vec<f64> = u.iter().flat_map(|&x| v.iter().map(move |&y| x + y * y + 0.2 * (11.0 * x).sin())).collect();
/// let c = SurfaceShapeConstraints::new().with(SurfaceShape::Increasing(Direction::U));
/// let f = constrained_surface_grid_smoothing_spline(PointsRef::from_flat(1, &z)?, (&u, &v), [Lambda::Given(1e-5), Lambda::Gcv], &c)?;
/// assert_eq!(surface_shape_violations(&f.surface, &c)?, vec![0.0]);
/// assert_eq!(f.surface.net_size(), (16, 12));
/// # Ok::<(), lekalo::Error>(())
/// ```
///
/// # Errors
/// The errors of [`tensor_grid_smoothing_spline`]; [`Error::Dimension`] for values that are not
/// numbers; [`Error::NegativeSmoothing`] for a given `λ_a < 0` or not finite,
/// [`Error::InvalidArgument`] for `λ_a = 0` (the constrained program needs the penalty in both
/// directions), and for weights so light in both directions that the interior point cannot
/// solve the program to full accuracy (`docs/theory/fitting.md#shape-constrained-smoothing-of-surfaces`;
/// the message names the weights and asks for a heavier one); the constraint errors of
/// [`constrained_surface_grid_least_squares`](super::constrained_surface_grid_least_squares).
pub fn constrained_surface_grid_smoothing_spline(
    values: PointsRef<'_>,
    (uu, vv): (&[f64], &[f64]),
    lambdas: [Lambda; 2],
    constraints: &SurfaceShapeConstraints,
) -> Result<SurfaceGridSmoothing> {
    check_values(
        values.dim(),
        1,
        "grid values of a surface z(u, v) (one number each)",
    )?;
    for l in lambdas {
        if let Lambda::Given(l) = l {
            if !(l >= 0.0 && l.is_finite()) {
                return Err(Error::NegativeSmoothing {
                    what: Arg::Lambda.into(),
                    value: l,
                });
            }
            if l == 0.0 {
                // the space has two coefficients a direction more than the grid has lines: only
                // the penalty makes the program's Hessian definite
                return Err(Error::InvalidArgument {
                    what: What::of(Arg::Lambda, "λ (penalty weight)"),
                    reason: "0 with shape constraints: the spline with a knot at every grid                              line has more coefficients than the grid has nodes, and only the                              penalty decides between them; give λ > 0 in each direction (or                              GCV's)"
                        .into(),
                });
            }
        }
    }
    let free = tensor_grid_smoothing_spline(&[uu, vv], values, &lambdas)?;
    let grid = Grid::new(values, (uu, vv), constraints)?;
    let lams = [free.lambdas[0], free.lambdas[1]];
    grid.fit(lams, Some(free), constraints)
}

/// The shape-constrained smoothing spline on a grid of
/// [`constrained_surface_grid_smoothing_spline`] whose residual `Σ_ij (z(u_i, v_j) − z_ij)²` is
/// `s`: Reinsch's smoothing condition on the space of the grid's smoothing spline (a knot at
/// every grid coordinate), as the curves'
/// [`constrained_smoothing_condition`](crate::fit::constrained_smoothing_condition). The two
/// weights move together along the ray `t·(λ_u*, λ_v*)` from the weights `λ*` that generalised
/// cross-validation chooses for the unconstrained spline (their ratio kept): `t` is bracketed
/// by factors of ten from `t = 1`, then found by bisection in `log t` until the residual of the
/// constrained optimum is within [`CONDITION_RTOL`] of `s`. Where even the largest `t` tried
/// leaves less than `s`, that fit is returned (its residual below `s`).
///
/// ```
/// use lekalo::fit::{constrained_surface_grid_smoothing_condition, surface_shape_violations, SurfaceShape, SurfaceShapeConstraints};
/// use lekalo::{Direction, PointsRef};
/// let u: Vec<f64> = (0..14).map(|i| i as f64 / 13.0).collect();
/// let v: Vec<f64> = (0..10).map(|j| j as f64 / 9.0).collect();
/// // rising in u, with a ripple that makes the smoothing spline dip
/// let z: Vec<f64> = (0..140).map(|k| {
///     let (i, j) = (k / 10, k % 10);
///     let (x, y) = (u[i], v[j]);
///     x + 0.5 * y * y + 0.25 * (9.0 * x).sin() + 0.15 * ((7 * i + 3 * j) as f64 * 1.7).sin()
/// }).collect();
/// let c = SurfaceShapeConstraints::new().with(SurfaceShape::Increasing(Direction::U));
/// let f = constrained_surface_grid_smoothing_condition(PointsRef::from_flat(1, &z)?, (&u, &v), 1.5, &c)?;
/// assert!((f.residual - 1.5).abs() <= 1e-3 * 1.5);
/// assert_eq!(surface_shape_violations(&f.surface, &c)?, vec![0.0]);
/// # Ok::<(), lekalo::Error>(())
/// ```
///
/// # Errors
/// Those of [`constrained_surface_grid_smoothing_spline`]; [`Error::NegativeSmoothing`] for
/// `s < 0` or not finite; [`Error::InvalidArgument`] when the constraints leave a residual above
/// `s` at every weight tried (the message gives the least residual they allow).
pub fn constrained_surface_grid_smoothing_condition(
    values: PointsRef<'_>,
    (uu, vv): (&[f64], &[f64]),
    s: f64,
    constraints: &SurfaceShapeConstraints,
) -> Result<SurfaceGridSmoothing> {
    if !(s >= 0.0 && s.is_finite()) {
        return Err(Error::NegativeSmoothing {
            what: Arg::S.into(),
            value: s,
        });
    }
    let start =
        constrained_surface_grid_smoothing_spline(values, (uu, vv), [Lambda::Gcv; 2], constraints)?;
    let lam0 = start.lambdas;
    if !lam0.iter().all(|l| *l > 0.0 && l.is_finite()) {
        return Ok(start);
    }
    let grid = Grid::new(values, (uu, vv), constraints)?;
    let fit_at = |t: f64| grid.fit([t * lam0[0], t * lam0[1]], None, constraints);
    let close = |f: &SurfaceGridSmoothing| (f.residual - s).abs() <= CONDITION_RTOL * s;
    if close(&start) {
        return Ok(start);
    }
    // bracket: (t, fit) with the residual below s and above it
    let below = start.residual < s;
    let mut near = (1.0, start);
    let mut stopped = false;
    for _ in 0..CONDITION_DECADES {
        let t = if below { near.0 * 10.0 } else { near.0 / 10.0 };
        let f = match fit_at(t) {
            Ok(f) => f,
            // weights so small (or large) that the program cannot be solved: the search ends
            // at the last one solved, and says so
            Err(e)
                if matches!(
                    e,
                    Error::SingularSystem { .. } | Error::IllConditioned { .. }
                ) || e.arg() == Some(Arg::Lambda) =>
            {
                stopped = true;
                break;
            }
            Err(e) => return Err(e),
        };
        if close(&f) {
            return Ok(f);
        }
        if (f.residual < s) != below {
            let bracket = if below {
                (near, (t, f))
            } else {
                ((t, f), near)
            };
            return bisect_condition(bracket, s, &fit_at, &close, |f| f.residual);
        }
        near = (t, f);
    }
    if below && stopped {
        let most = digits_down(near.1.residual);
        return Err(Error::InvalidArgument {
            what: What::of(Arg::S, "s (smoothing condition)"),
            reason: format!(
                "the shape-constrained program can be solved up to a residual sum of squares of \
                 about {most} (heavier weights make it too ill-conditioned), below s = {s}; \
                 give s ≤ {most}, or λ",
                most = readable(&most),
                s = readable(&s)
            ),
        });
    }
    if below {
        // even the smoothest fit tried stays below s
        return Ok(near.1);
    }
    let least = digits_up(near.1.residual);
    if stopped {
        return Err(Error::InvalidArgument {
            what: What::of(Arg::S, "s (smoothing condition)"),
            reason: format!(
                "the shape-constrained program can be solved down to a residual sum of squares \
                 of about {least} (lighter weights make it too ill-conditioned), above s = {s}; \
                 give s ≥ {least}, or λ",
                least = readable(&least),
                s = readable(&s)
            ),
        });
    }
    Err(least_residual_error(near.1.residual, s))
}

/// The pieces of the program every weight shares: the values, the knots of the grid's
/// smoothing spline, each direction's basis rows, Gram matrix `G_a` and roughness `Ω_a`
/// (dense, banded with half-width 3), and the scales.
struct Grid<'a> {
    values: PointsRef<'a>,
    params: (&'a [f64], &'a [f64]),
    knots: (KnotVector, KnotVector),
    rows: [BasisRows; 2],
    gram: [Vec<f64>; 2],
    omega: [Vec<f64>; 2],
    scale: Scales,
}

impl<'a> Grid<'a> {
    fn new(
        values: PointsRef<'a>,
        (uu, vv): (&'a [f64], &'a [f64]),
        constraints: &SurfaceShapeConstraints,
    ) -> Result<Self> {
        let axis = |x: &[f64]| -> Result<(KnotVector, BasisRows, Vec<f64>, Vec<f64>)> {
            let zeros = vec![0.0; x.len()];
            let sm = Smoother::new(&FitData::new(PointsRef::from_flat(1, &zeros)?, x)?)?;
            let k = KnotVector::new(sm.knots.clone())?;
            let n = k.len() - 4;
            let (rows, gram) = basis_and_gram(&k, 3, x, n);
            let mut omega = vec![0.0; n * n];
            let b = sm.omega.b;
            for i in 0..n {
                for o in 0..=b.min(n - 1 - i) {
                    let w = sm.omega.a[i * (b + 1) + o];
                    omega[i * n + i + o] = w;
                    omega[(i + o) * n + i] = w;
                }
            }
            Ok((k, rows, gram, omega))
        };
        let (ku, ru, gu, ou) = axis(uu)?;
        let (kv, rv, gv, ov) = axis(vv)?;
        constraints.validate((3, 3), [ku.domain(3), kv.domain(3)])?;
        let scale = Scales::of(values.as_slice(), (ku.domain(3), kv.domain(3)));
        Ok(Grid {
            values,
            params: (uu, vv),
            knots: (ku, kv),
            rows: [ru, rv],
            gram: [gu, gv],
            omega: [ou, ov],
            scale,
        })
    }

    /// The constrained optimum at the weights `lams`: the unconstrained spline (`free`, or fitted
    /// here) when it keeps every condition, the quadratic program's answer otherwise.
    fn fit(
        &self,
        lams: [f64; 2],
        free: Option<TensorGridSmoothingSpline>,
        constraints: &SurfaceShapeConstraints,
    ) -> Result<SurfaceGridSmoothing> {
        let (uu, vv) = self.params;
        let free = match free {
            Some(f) => f,
            None => tensor_grid_smoothing_spline(
                &[uu, vv],
                self.values,
                &[Lambda::Given(lams[0]), Lambda::Given(lams[1])],
            )?,
        };
        let plain = free.spline.to_surface()?;
        let (ku, kv) = (&self.knots.0, &self.knots.1);
        let (ncu, ncv) = (ku.len() - 4, kv.len() - 4);
        let space = Space {
            degrees: (3, 3),
            knots: (ku.as_slice(), kv.as_slice()),
            net: (ncu, ncv),
        };
        if self
            .scale
            .holds(&space, plain.control_points().as_slice(), constraints)
        {
            return Ok(SurfaceGridSmoothing {
                surface: plain,
                lambdas: lams,
                residual: free.residual,
            });
        }
        // ½xᵀ((G_u + λ_uΩ_u) ⊗ (G_v + λ_vΩ_v))x + qᵀx in x = (c − center)/Y, whitened by each
        // direction's factors about the unconstrained minimum x₀
        let factor = |a: usize, n: usize, whiten: Option<bool>| {
            Factor::new(&self.gram[a], &self.omega[a], lams[a], n, whiten).map_err(|_| {
                Error::InvalidArgument {
                    what: What::of(Arg::Lambda, "λ (penalty weight)"),
                    reason: format!(
                        "{} in {} with shape constraints: so light that the penalty no longer \
                         decides the two coefficients the grid leaves free in that direction \
                         (its factor loses its pivots); give a heavier weight there",
                        readable(&lams[a]),
                        ["u", "v"][a]
                    ),
                }
            })
        };
        let z = self.values.as_slice();
        let center = z[0];
        let x0: Vec<f64> = plain
            .control_points()
            .as_slice()
            .iter()
            .map(|c| (c - center) / self.scale.y)
            .collect();
        // each direction whitened where its penalty is the stiffer part; should the interior
        // point stop short there, no direction whitened, then both
        let auto = (factor(0, ncu, None)?, factor(1, ncv, None)?);
        let chosen = [auto.0.whitened(), auto.1.whitened()];
        let mut tried = vec![chosen];
        let mut result = solve_whitened(
            &space,
            (&auto.0, &auto.1),
            &x0,
            (center, &self.scale),
            constraints,
        );
        for whiten in [false, true] {
            if !matches!(result, Err(Error::IllConditioned { .. }))
                || tried.contains(&[whiten, whiten])
            {
                continue;
            }
            tried.push([whiten, whiten]);
            let (fu, fv) = (factor(0, ncu, Some(whiten))?, factor(1, ncv, Some(whiten))?);
            result = solve_whitened(&space, (&fu, &fv), &x0, (center, &self.scale), constraints);
        }
        if matches!(result, Err(Error::IllConditioned { .. })) {
            // last, the net itself with the Hessian `(G_u + λ_uΩ_u) ⊗ (G_v + λ_vΩ_v)`, scaled
            // by the objective at the unconstrained minimum: very light weights in both
            // directions, whose flat directions the whitened rows cannot resolve
            let penalised = |a: usize| -> Vec<f64> {
                self.gram[a]
                    .iter()
                    .zip(&self.omega[a])
                    .map(|(g, o)| g + lams[a] * o)
                    .collect()
            };
            let upper = kronecker_upper(&penalised(0), &penalised(1), (ncu, ncv), (3, 3));
            let lin = grid_linear(
                z,
                (uu.len(), vv.len()),
                (&self.rows[0], &self.rows[1]),
                (ncu, ncv),
                center,
                self.scale.y,
            );
            let objective = x0.iter().zip(&lin).map(|(x, l)| l * x).sum::<f64>().abs() * 0.5;
            result = solve(
                &space,
                &upper,
                &lin,
                (center, &self.scale),
                constraints,
                Some(objective),
            );
        }
        let net = result.map_err(|e| match e {
            Error::IllConditioned { .. } => Error::InvalidArgument {
                what: What::of(Arg::Lambda, "λ (penalty weight)"),
                reason: format!(
                    "({}, {}) with shape constraints: the interior point cannot solve the \
                     program to full accuracy at these weights (whitened or not); give a \
                     heavier weight in a direction whose weight is very light (the spline then \
                     all but interpolates the grid there)",
                    readable(&lams[0]),
                    readable(&lams[1])
                ),
            },
            e => e,
        })?;
        let surface = BSplineSurface::from_knot_vectors(
            3,
            3,
            ku.clone(),
            kv.clone(),
            Points::from_flat(1, net)?,
            (ncu, ncv),
        )?;
        let mut at = vec![0.0; z.len()];
        surface.eval_grid(uu, vv, &mut at)?;
        let residual = at.iter().zip(z).map(|(f, y)| (f - y) * (f - y)).sum();
        Ok(SurfaceGridSmoothing {
            surface,
            lambdas: lams,
            residual,
        })
    }
}
