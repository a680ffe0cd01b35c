//! The quadratic program of the grid's shape-constrained smoothing spline in whitened
//! variables (`docs/theory/fitting.md#shape-constrained-smoothing-of-surfaces`): the Hessian
//! `H = A_u ⊗ A_v`, `A_a = G_a + λ_aΩ_a`, is factored direction by direction,
//! `A_a = U_aᵀ D_a U_a` (banded, half-width 3), and the net is written as the unconstrained
//! minimum plus a correction, `x = x₀ + δ·(M_u ⊗ M_v) ê` with `M_a = U_a⁻¹ D_a^{-1/2}`. Then
//! `½xᵀHx + qᵀx = ½δ²‖ê‖² + const`: the program Clarabel sees has the identity for its
//! Hessian whatever the weights, its rows are the Bernstein rows mapped through `M_u ⊗ M_v`,
//! and `δ` (the least distance, in the metric of `H`, from `x₀` to a violated row's half-space)
//! makes the correction of order one, so that the solver's absolute tolerances are relative to
//! it.

use super::super::program::{failure_error, solve_sparse_scaled, Failure, SparseUpper};
use super::super::row::Row;
use super::cells::Space;
use super::constraints::SurfaceShapeConstraints;
use super::fits::{kronecker_upper, program_rows, Scales, MARGIN};
use crate::error::Result;
use crate::fit::banded::SymBand;

/// Share of a mapped row's largest entry below which its entries are left out of the program:
/// `M_u ⊗ M_v` fills a local row towards the end of the net, with entries that decay away
/// from it; those below the rounding of the others change no product by more than it.
const DROP_RTOL: f64 = 1e-17;

/// One direction's factors `A_a = Uᵀ D U` of `G_a + λ_aΩ_a` (dense `n × n` inputs, banded
/// with half-width 3).
pub(super) struct Factor {
    band: SymBand,
    /// Whether the direction is whitened: its penalty at least as stiff as its data
    /// ([`Factor::new`]); otherwise `M_a = I` and `A_a` stays in the program's Hessian.
    whiten: bool,
    /// `A_a`, dense `n × n`, for the Hessian of a direction left as it is.
    dense: Vec<f64>,
}

impl Factor {
    /// Factors `gram + lam·omega`; `Err(i)` when the pivot of row `i` is not positive (the
    /// weight too light for the penalty to decide the coefficients the data leave free).
    ///
    /// With `whiten` given, the direction is whitened or not as it says; otherwise it is
    /// whitened when its penalty is at least as stiff as its data at the finest
    /// scale (`λ_a·max Ω_a,ii ≥ max G_a,ii`): there the eigenvalues of `A_a` run up to `λ_a/h³`
    /// while the penalty's null space keeps those of `G_a`. A lighter weight leaves `A_a`'s
    /// spread to the few coefficients the grid leaves free (eigenvalues `~λ_a`), where the
    /// whitened rows would need the correction to more digits than the interior point gives:
    /// such a direction keeps its coefficients, and `A_a` enters the Hessian.
    pub(super) fn new(
        gram: &[f64],
        omega: &[f64],
        lam: f64,
        n: usize,
        whiten: Option<bool>,
    ) -> std::result::Result<Self, usize> {
        let b = 3;
        let dense: Vec<f64> = gram.iter().zip(omega).map(|(g, o)| g + lam * o).collect();
        let mut band = SymBand::zeros(n, b);
        for i in 0..n {
            for j in i..(i + b + 1).min(n) {
                band.add(i, j, dense[i * n + j]);
            }
        }
        let diag = |m: &[f64]| (0..n).fold(0.0_f64, |a, i| a.max(m[i * n + i]));
        let whiten = whiten.unwrap_or(lam * diag(omega) >= diag(gram));
        if whiten {
            band.factor()?;
        }
        Ok(Factor {
            band,
            whiten,
            dense,
        })
    }

    /// Whether the direction is whitened.
    pub(super) fn whitened(&self) -> bool {
        self.whiten
    }

    /// The direction's block of the program's Hessian: `I` when whitened, `A_a` otherwise.
    fn hessian(&self) -> Vec<f64> {
        let n = self.band.n;
        if self.whiten {
            (0..n * n)
                .map(|k| if k / n == k % n { 1.0 } else { 0.0 })
                .collect()
        } else {
            self.dense.clone()
        }
    }

    /// `t ← D^{-1/2} U⁻ᵀ t` for the `n` entries at `t[k·stride]` (a row of the constraint
    /// mapped to the whitened variables: `Mᵀ t`).
    fn forward(&self, t: &mut [f64], stride: usize) {
        if !self.whiten {
            return;
        }
        let (n, b) = (self.band.n, self.band.b);
        let w = b + 1;
        let a = &self.band.a;
        for i in 0..n {
            let mut s = t[i * stride];
            for k in i.saturating_sub(b)..i {
                s -= a[k * w + i - k] * t[k * stride];
            }
            t[i * stride] = s;
        }
        for i in 0..n {
            t[i * stride] /= a[i * w].sqrt();
        }
    }

    /// `t ← U⁻¹ D^{-1/2} t` (`M t`: a whitened correction back to the net).
    fn backward(&self, t: &mut [f64], stride: usize) {
        if !self.whiten {
            return;
        }
        let (n, b) = (self.band.n, self.band.b);
        let w = b + 1;
        let a = &self.band.a;
        for i in 0..n {
            t[i * stride] /= a[i * w].sqrt();
        }
        for i in (0..n).rev() {
            let mut s = t[i * stride];
            for k in i + 1..(i + b + 1).min(n) {
                s -= a[i * w + k - i] * t[k * stride];
            }
            t[i * stride] = s;
        }
    }
}

/// `(F_u ⊗ F_v)` applied to the net `t` (`n_u × n_v`, row-major) by one direction's map `f`.
fn both(
    (fu, fv): (&Factor, &Factor),
    t: &mut [f64],
    (nu, nv): (usize, usize),
    f: fn(&Factor, &mut [f64], usize),
) {
    for i in 0..nu {
        f(fv, &mut t[i * nv..(i + 1) * nv], 1);
    }
    for j in 0..nv {
        f(fu, &mut t[j..], nv);
    }
}

/// The constrained minimum, in scaled net units `x = (c − center)/Y`, of `½xᵀ(A_u ⊗ A_v)x +
/// qᵀx` whose unconstrained minimum is `x0`, subject to every shape's rows: solved by Clarabel
/// in the whitened correction `ê` with every row kept [`MARGIN`] inside its bound (without it
/// when that leaves no room), the answer checked against every condition. The net in the data's
/// units.
pub(super) fn solve_whitened(
    space: &Space<'_>,
    factors: (&Factor, &Factor),
    x0: &[f64],
    (center, scale): (f64, &Scales),
    constraints: &SurfaceShapeConstraints,
) -> Result<Vec<f64>> {
    let (nu, nv) = space.net;
    let n = nu * nv;
    // each row unit in its largest coefficient, its value at x₀, and its map Mᵀρ
    let mut mapped: Vec<(Vec<f64>, f64, usize)> = Vec::new();
    let mut delta = 0.0_f64;
    for (row, owner) in program_rows(space, center, scale.y, constraints) {
        let m = row.max_abs();
        let mut t = vec![0.0; n];
        for (k, c) in row.coef.iter().enumerate() {
            if row.first + k < n {
                t[row.first + k] = c / m;
            }
        }
        let g0 = row.eval(x0, n) / m;
        both(factors, &mut t, (nu, nv), Factor::forward);
        let norm = t.iter().map(|v| v * v).sum::<f64>().sqrt();
        if norm > 0.0 {
            delta = delta.max(-g0 / norm);
        }
        mapped.push((t, g0, owner));
    }
    if !(delta > 0.0 && delta.is_finite()) {
        delta = 1.0;
    }
    let hessian = kronecker_upper(&factors.0.hessian(), &factors.1.hessian(), (nu, nv), (3, 3));
    // the Hessian's size: the program is scaled by it, and only a fully solved one accepted
    let size = (0..n).fold(0.0_f64, |m, j| {
        (hessian.colptr[j]..hessian.colptr[j + 1])
            .filter(|&k| hessian.rowval[k] == j)
            .fold(m, |m, k| m.max(hessian.nzval[k].abs()))
    });
    let mut last = None;
    for margin in [MARGIN, 0.0] {
        // δ·(Mᵀρ)·ê + g₀ − margin ≥ 0
        let rows: Vec<(Row, usize)> = mapped
            .iter()
            .filter_map(|(t, g0, owner)| {
                let big = t.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
                let keep = |v: &f64| v.abs() > DROP_RTOL * big;
                let first = t.iter().position(keep)?;
                let end = t.iter().rposition(keep)? + 1;
                Some((
                    Row {
                        first,
                        coef: t[first..end]
                            .iter()
                            .map(|v| if keep(v) { delta * v } else { 0.0 })
                            .collect(),
                        aux: None,
                        constant: g0 - margin,
                    },
                    *owner,
                ))
            })
            .collect();
        match solve_by_own_objective(&hessian, &rows, size) {
            Ok(e) => {
                let mut dx: Vec<f64> = e[..n].iter().map(|v| delta * v).collect();
                both(factors, &mut dx, (nu, nv), Factor::backward);
                let net: Vec<f64> = x0
                    .iter()
                    .zip(&dx)
                    .map(|(a, d)| center + scale.y * (a + d))
                    .collect();
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

/// Clarabel on `½ êᵀPê` (no linear term: `ê = 0` is the unconstrained minimum) with `rows`,
/// scaled by `size` (`P`'s largest entry) and accepted only fully solved; when it stops short,
/// the objective at the optimum is many orders below `size` (a correction along the Hessian's
/// flat directions), so the program is solved again scaled by the objective of the answer the
/// solver reached at reduced accuracy, as the tolerances then ask of the optimum itself.
fn solve_by_own_objective(
    hessian: &SparseUpper,
    rows: &[(Row, usize)],
    size: f64,
) -> std::result::Result<Vec<f64>, Failure> {
    let n = hessian.n;
    let zero = vec![0.0; n];
    let program = (&[][..], rows, &[][..]);
    match solve_sparse_scaled(hessian, &zero, program, Some(size)) {
        Err(Failure::Status(_)) => {
            let rough = solve_sparse_scaled(hessian, &zero, program, None)?;
            let mut f = 0.0;
            for j in 0..n {
                for k in hessian.colptr[j]..hessian.colptr[j + 1] {
                    let i = hessian.rowval[k];
                    let w = if i == j { 0.5 } else { 1.0 };
                    f += w * hessian.nzval[k] * rough[i] * rough[j];
                }
            }
            solve_sparse_scaled(hessian, &zero, program, Some(f))
        }
        other => other,
    }
}
