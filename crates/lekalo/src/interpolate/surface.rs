//! Interpolation of a grid of points by a tensor-product B-spline surface (document 000 §5,
//! eq. 16–18): row and column parameters averaged, knots by averaging, curve interpolation in
//! both directions with one factorisation per direction, applied in two sweeps over the grid.
//! The averaged parameters of the rows and columns are computed in `surface/grid_params.rs`.

use self::grid_params::averaged_params;
use crate::error::{Error, Result};
use crate::interpolate::collocation::{check_condition_limit, factor_collocation, Factors};
use crate::interpolate::parametrization::{check_strictly_increasing, Parametrization};
use crate::knots::KnotVector;
use crate::numeric::linalg::BandedCrout;
use crate::points::{Points, PointsRef};
use crate::surface::bspline::BSplineSurface;

/// Global interpolation of a grid of points by a tensor-product B-spline surface: document
/// 000 §A.5, eq. (16)–(18), Algorithm A.5. The surface counterpart of
/// [`CurveInterpolation`](crate::CurveInterpolation): set the degrees and the options, then
/// [`SurfaceInterpolation::interpolate`] returns the [`BSplineSurface`];
/// [`SurfaceInterpolation::interpolate_with_report`] also returns the grid parameters and the
/// condition estimate.
///
/// The grid is `nu × nv` points `q_kl`, flat and point-major, point `(k, l)` at
/// `(k·nv + l)·dim` (`k` along `u`). Parameters: for each column `l` the [`Parametrization`] of
/// `q_0l … q_{nu−1,l}`, averaged over the columns (`ū_k = Σ_l ū_k^{(l)} / nv`, P&T §9.2.5),
/// likewise `v̄_l` over the rows; knots by averaging (eq. 3). Then curve interpolation down
/// every column and along every row, each direction's banded collocation matrix factored once;
/// the two solves commute, and are interleaved so that the grid is swept twice (see
/// `solve_grid` in the source). O(nu·nv·(p + q)·dim) after the factorisations'
/// O(nu·p² + nv·q²).
///
/// ```
/// use lekalo::{Parametrization, Points, SurfaceInterpolation};
/// // a 4×3 grid on z = x·y
/// let mut data = Vec::new();
/// for k in 0..4 { for l in 0..3 { let (x, y) = (k as f64, l as f64); data.extend([x, y, x * y]); } }
/// let grid = Points::from_flat(3, data)?;
/// let fit = SurfaceInterpolation::new(3, 2).parametrization(Parametrization::Uniform);
/// let s = fit.interpolate(grid.as_view(), 4, 3)?;
/// assert_eq!(s.net_size(), (4, 3));
/// assert_eq!(s.control_points().point(0), &[0.0, 0.0, 0.0]);
/// // the parameters of the grid, on request
/// let (s, report) = fit.interpolate_with_report(grid.as_view(), 4, 3)?;
/// let (u, v) = (report.params_u()[2], report.params_v()[1]);
/// let p = s.eval(u, v)?;
/// assert!((p[0] - 2.0).abs() < 1e-14 && (p[1] - 1.0).abs() < 1e-14 && (p[2] - 2.0).abs() < 1e-14);
/// assert!(report.condition() >= 1.0);
/// # Ok::<(), lekalo::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct SurfaceInterpolation {
    degree_u: usize,
    degree_v: usize,
    parametrization: Parametrization,
    max_condition: Option<f64>,
}

impl SurfaceInterpolation {
    /// Interpolation of degrees `(degree_u, degree_v)` with chord-length parameters (as
    /// [`CurveInterpolation::new`](crate::CurveInterpolation::new)) and no condition limit.
    #[must_use]
    pub fn new(degree_u: usize, degree_v: usize) -> Self {
        SurfaceInterpolation {
            degree_u,
            degree_v,
            parametrization: Parametrization::ChordLength,
            max_condition: None,
        }
    }

    /// Sets the parametrisation of the rows and columns.
    #[must_use]
    pub fn parametrization(mut self, parametrization: Parametrization) -> Self {
        self.parametrization = parametrization;
        self
    }

    /// Refuses, with [`Error::IllConditioned`], a system whose 1-norm condition number is
    /// estimated above `limit` (a number ≥ 1, e.g. `1e8`): see
    /// [`SurfaceInterpolation::condition`] for the estimate. The surface, when there is one, is
    /// the same bit for bit as without the limit; the estimate adds a few banded solves per
    /// direction.
    ///
    /// ```
    /// use lekalo::{Error, Parametrization, Points, SurfaceInterpolation};
    /// // a 6×4 grid whose rows 2 and 3 nearly coincide
    /// let mut data = Vec::new();
    /// for x in [0.0, 1.0, 2.0, 2.0 + 1e-10, 3.0, 4.0] {
    ///     for y in 0..4 { let y = f64::from(y); data.extend([x, y, (x * y).sin()]); }
    /// }
    /// let grid = Points::from_flat(3, data)?;
    /// let strict = SurfaceInterpolation::new(3, 3).max_condition(1e8);
    /// assert!(matches!(strict.interpolate(grid.as_view(), 6, 4), Err(Error::IllConditioned { .. })));
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    #[must_use]
    pub fn max_condition(mut self, limit: f64) -> Self {
        self.max_condition = Some(limit);
        self
    }

    /// The B-spline surface through the `nu × nv` grid.
    ///
    /// # Errors
    /// [`Error::LengthMismatch`] if the grid does not hold `nu·nv` points; [`Error::TooFew`] if
    /// `nu` or `nv` is below 2; [`Error::Degree`] if `p ≥ nu`, `q ≥ nv` or a degree is 0;
    /// [`Error::CoincidentPoints`] (flat point indices) for a zero step in a row or column;
    /// [`Error::InvalidArgument`] (also for a condition limit that is NaN or below 1);
    /// [`Error::SingularSystem`] / [`Error::IllConditioned`] (also for an estimate above the
    /// limit of [`SurfaceInterpolation::max_condition`]).
    pub fn interpolate(&self, grid: PointsRef<'_>, nu: usize, nv: usize) -> Result<BSplineSurface> {
        self.solve(grid, nu, nv, false).map(|(s, _)| s.surface)
    }

    /// [`SurfaceInterpolation::interpolate`], and what went into it: the parameters of the
    /// grid's rows and columns and the condition estimate of the system (see
    /// [`SurfaceInterpolation::condition`]). The surface is the same bit for bit.
    ///
    /// # Errors
    /// As [`SurfaceInterpolation::interpolate`].
    pub fn interpolate_with_report(
        &self,
        grid: PointsRef<'_>,
        nu: usize,
        nv: usize,
    ) -> Result<(BSplineSurface, SurfaceInterpolationReport)> {
        let (s, kappa) = self.solve(grid, nu, nv, true)?;
        let report = SurfaceInterpolationReport {
            params_u: s.params_u,
            params_v: s.params_v,
            condition: kappa,
        };
        Ok((s.surface, report))
    }

    /// Estimate of the 1-norm condition number `κ_1` of the linear system that
    /// [`SurfaceInterpolation::interpolate`] solves for the grid. The system is the Kronecker
    /// product `A_u ⊗ A_v` of the two curve collocation matrices, and
    /// `κ_1(A_u ⊗ A_v) = κ_1(A_u)·κ_1(A_v)` (both `‖·‖_1` and the inverse factor over `⊗`: Horn &
    /// Johnson, *Topics in Matrix Analysis*, §4.2), so the result is the product of the two
    /// directions' estimates, each by Higham's refinement of Hager's method (ACM TOMS 14 (1988),
    /// Algorithm 4.1; LAPACK `dgbcon`), see
    /// [`CurveInterpolation::condition`](crate::CurveInterpolation::condition). A lower bound,
    /// usually exact.
    ///
    /// ```
    /// use lekalo::{Parametrization, Points, SurfaceInterpolation};
    /// let mut data = Vec::new();
    /// for k in 0..10 { for l in 0..8 { let (x, y) = (f64::from(k), f64::from(l)); data.extend([x, y, x * y]); } }
    /// let grid = Points::from_flat(3, data)?;
    /// let kappa = SurfaceInterpolation::new(3, 3)
    ///     .parametrization(Parametrization::Uniform)
    ///     .condition(grid.as_view(), 10, 8)?;
    /// assert!(kappa >= 1.0 && kappa < 100.0);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// As [`SurfaceInterpolation::interpolate`] (it performs the same solve), but never the
    /// limit of [`SurfaceInterpolation::max_condition`].
    pub fn condition(&self, grid: PointsRef<'_>, nu: usize, nv: usize) -> Result<f64> {
        let grid = Grid {
            points: grid,
            nu,
            nv,
        };
        let mut kappa = 1.0;
        surface(
            grid,
            self.degree_u,
            self.degree_v,
            self.parametrization,
            Some(&mut kappa),
        )?;
        Ok(kappa)
    }

    /// The solve, with the limit applied; with `estimate` (or a limit) the condition estimate
    /// is made and returned, else 1.
    fn solve(
        &self,
        points: PointsRef<'_>,
        nu: usize,
        nv: usize,
        estimate: bool,
    ) -> Result<(Solved, f64)> {
        let grid = Grid { points, nu, nv };
        let (p, q, param) = (self.degree_u, self.degree_v, self.parametrization);
        if let Some(limit) = self.max_condition {
            check_condition_limit(limit)?;
        }
        if !estimate && self.max_condition.is_none() {
            return surface(grid, p, q, param, None).map(|s| (s, 1.0));
        }
        let mut kappa = 1.0;
        let s = surface(grid, p, q, param, Some(&mut kappa))?;
        match self.max_condition {
            Some(limit) if kappa > limit => Err(condition_exceeded(kappa, limit)),
            _ => Ok((s, kappa)),
        }
    }
}

/// What went into a surface interpolation, from
/// [`SurfaceInterpolation::interpolate_with_report`].
#[derive(Debug, Clone, PartialEq)]
pub struct SurfaceInterpolationReport {
    params_u: Vec<f64>,
    params_v: Vec<f64>,
    condition: f64,
}

impl SurfaceInterpolationReport {
    /// Parameters `ū_k` of the grid rows (`nu` of them, from 0 to 1): the surface passes
    /// through point `(k, l)` at `(ū_k, v̄_l)`.
    #[must_use]
    pub fn params_u(&self) -> &[f64] {
        &self.params_u
    }

    /// Parameters `v̄_l` of the grid columns (`nv` of them, from 0 to 1).
    #[must_use]
    pub fn params_v(&self) -> &[f64] {
        &self.params_v
    }

    /// Estimate of the 1-norm condition number of the system solved (see
    /// [`SurfaceInterpolation::condition`]).
    #[must_use]
    pub fn condition(&self) -> f64 {
        self.condition
    }
}

/// The interpolating surface and the grid parameters.
struct Solved {
    surface: BSplineSurface,
    params_u: Vec<f64>,
    params_v: Vec<f64>,
}

/// Parts of a tensor-product B-spline surface `S(u, v) = Σ_i Σ_j N_{i,p}(u) N_{j,q}(v) P_ij`
/// with the grid parameters; `control[(i*nv + j)*dim + k]`. [`SurfaceInterpolant::into_surface`]
/// gives the [`BSplineSurface`].
#[deprecated(
    note = "use SurfaceInterpolation, whose interpolate returns the BSplineSurface \
            (interpolate_with_report gives the parameters)"
)]
#[derive(Debug, Clone, PartialEq)]
pub struct SurfaceInterpolant {
    /// Degree `p` in `u`.
    pub degree_u: usize,
    /// Degree `q` in `v`.
    pub degree_v: usize,
    /// Knots in `u` (`nu + p + 1`).
    pub knots_u: KnotVector,
    /// Knots in `v` (`nv + q + 1`).
    pub knots_v: KnotVector,
    /// Control net, flat, `nu × nv` points, point `(i, j)` at `(i*nv + j)*dim`.
    pub control: Points,
    /// Number of control points in `u`.
    pub nu: usize,
    /// Number of control points in `v`.
    pub nv: usize,
    /// Parameters `ū_k` of the grid rows.
    pub params_u: Vec<f64>,
    /// Parameters `v̄_l` of the grid columns.
    pub params_v: Vec<f64>,
}

#[allow(deprecated)]
impl SurfaceInterpolant {
    /// The interpolating surface as a [`BSplineSurface`].
    #[must_use]
    pub fn into_surface(self) -> BSplineSurface {
        BSplineSurface::from_raw(
            self.degree_u,
            self.degree_v,
            self.knots_u,
            self.knots_v,
            self.control,
        )
    }

    fn from_solved(s: Solved) -> Self {
        let (nu, nv) = s.surface.net_size();
        SurfaceInterpolant {
            degree_u: s.surface.degree_u(),
            degree_v: s.surface.degree_v(),
            knots_u: s.surface.knots_u().clone(),
            knots_v: s.surface.knots_v().clone(),
            control: s.surface.control_points().clone(),
            nu,
            nv,
            params_u: s.params_u,
            params_v: s.params_v,
        }
    }
}

/// Interpolates an `nu × nv` grid of points by a B-spline surface of degrees `(p, q)`:
/// [`SurfaceInterpolation`] with the parts of the surface and the parameters as public fields.
///
/// # Errors
/// As [`SurfaceInterpolation::interpolate`].
#[deprecated(
    note = "use SurfaceInterpolation::new(degree_u, degree_v).parametrization(p).interpolate(grid, nu, nv)"
)]
#[allow(deprecated)]
pub fn interpolate_surface(
    grid: PointsRef<'_>,
    nu: usize,
    nv: usize,
    degree_u: usize,
    degree_v: usize,
    parametrization: Parametrization,
) -> Result<SurfaceInterpolant> {
    SurfaceInterpolation::new(degree_u, degree_v)
        .parametrization(parametrization)
        .solve(grid, nu, nv, false)
        .map(|(s, _)| SurfaceInterpolant::from_solved(s))
}

/// [`interpolate_surface`] with a condition limit: see
/// [`SurfaceInterpolation::max_condition`].
///
/// # Errors
/// As [`SurfaceInterpolation::interpolate`].
#[deprecated(
    note = "use SurfaceInterpolation::new(degree_u, degree_v).parametrization(p).max_condition(limit).interpolate(grid, nu, nv)"
)]
#[allow(deprecated)]
pub fn interpolate_surface_max_condition(
    grid: PointsRef<'_>,
    nu: usize,
    nv: usize,
    degree_u: usize,
    degree_v: usize,
    parametrization: Parametrization,
    max_condition: f64,
) -> Result<SurfaceInterpolant> {
    SurfaceInterpolation::new(degree_u, degree_v)
        .parametrization(parametrization)
        .max_condition(max_condition)
        .solve(grid, nu, nv, false)
        .map(|(s, _)| SurfaceInterpolant::from_solved(s))
}

/// The condition estimate of [`interpolate_surface`]'s system: see
/// [`SurfaceInterpolation::condition`].
///
/// # Errors
/// As [`SurfaceInterpolation::condition`].
#[deprecated(
    note = "use SurfaceInterpolation::new(degree_u, degree_v).parametrization(p).condition(grid, nu, nv)"
)]
pub fn interpolate_surface_condition(
    grid: PointsRef<'_>,
    nu: usize,
    nv: usize,
    degree_u: usize,
    degree_v: usize,
    parametrization: Parametrization,
) -> Result<f64> {
    SurfaceInterpolation::new(degree_u, degree_v)
        .parametrization(parametrization)
        .condition(grid, nu, nv)
}

#[cold]
fn condition_exceeded(kappa: f64, limit: f64) -> Error {
    Error::IllConditioned {
        reason: format!(
            "the surface collocation system has an estimated condition number κ_1 ≈ \
             {kappa:.3e}, above the limit {limit:e} set by max_condition: grid rows or columns \
             crowd together (nearly coincident parameters) or the spacing is too uneven for the \
             degrees; use centripetal or uniform parameters, drop near-duplicate rows or \
             columns, or lower the degrees"
        ),
    }
}

/// The grid of a surface interpolation: `nu × nv` points.
#[derive(Clone, Copy)]
struct Grid<'a> {
    points: PointsRef<'a>,
    nu: usize,
    nv: usize,
}

/// The body of [`SurfaceInterpolation::interpolate`]; with `kappa`, the product of the two directions'
/// condition estimates goes there.
fn surface(
    grid: Grid<'_>,
    degree_u: usize,
    degree_v: usize,
    parametrization: Parametrization,
    kappa: Option<&mut f64>,
) -> Result<Solved> {
    let Grid {
        points: grid,
        nu,
        nv,
    } = grid;
    let total = nu.checked_mul(nv).ok_or(Error::TooLarge {
        what: "grid size".into(),
        size: usize::MAX,
        max: crate::error::MAX_SCALARS,
    })?;
    if grid.len() != total {
        return Err(Error::LengthMismatch {
            what: "grid points (nu × nv)".into(),
            expected: total,
            got: grid.len(),
        });
    }
    for (n, what) in [(nu, "grid rows (nu)"), (nv, "grid columns (nv)")] {
        if n < 2 {
            return Err(Error::TooFew {
                what: what.into(),
                min: 2,
                got: n,
            });
        }
    }
    for (deg, n) in [(degree_u, nu), (degree_v, nv)] {
        if deg == 0 || deg >= n {
            return Err(Error::Degree {
                degree: deg,
                reason: format!(
                    "a direction with {n} points takes a degree from 1 to {}",
                    n - 1
                ),
            });
        }
    }
    let e = parametrization.exponent()?;
    let dim = grid.dim();
    let data = grid.as_slice();
    let (params_u, params_v) = averaged_params(data, nu, nv, dim, e)?;
    check_strictly_increasing(&params_u)?;
    check_strictly_increasing(&params_v)?;
    let knots_u = KnotVector::averaged(&params_u, degree_u)?;
    let knots_v = KnotVector::averaged(&params_v, degree_v)?;
    // both factorisations first (small: nu and nv rows), then the grid in two sweeps
    let factors = if kappa.is_some() {
        Factors::Estimate
    } else {
        Factors::Keep
    };
    let lu_u = factor_collocation(&knots_u, degree_u, &params_u, factors)?;
    let lu_v = factor_collocation(&knots_v, degree_v, &params_v, factors)?;
    if let Some(k) = kappa {
        let (ku, kv) = (lu_u.condition_estimate(), lu_v.condition_estimate());
        *k = ku.unwrap_or(1.0) * kv.unwrap_or(1.0);
    }
    let control = solve_grid(data, nu, nv, dim, &lu_u, &lu_v)?;
    let surface = BSplineSurface::from_raw(
        degree_u,
        degree_v,
        knots_u,
        knots_v,
        Points::from_raw(control, dim),
    );
    Ok(Solved {
        surface,
        params_u,
        params_v,
    })
}

crate::numeric::isa::avx2_dispatch! {
    /// The control net `P = A_u⁻¹ (Q − q_00) A_vᵀ⁻¹ + q_00` of the grid `Q` (`nu` rows of `nv`
    /// points), given the factored collocation matrices of both directions (document 000 §5,
    /// eq. 17–18: a curve interpolation down every column, then along every row).
    ///
    /// The two directions' solves are linear maps acting on different indices of the grid, so they
    /// commute; this applies them in the order that reads the grid least. Sweep 1, row by row in
    /// order: centre the row on `q_00` (affine invariance, and no cancellation for grids far from
    /// the origin), solve it along `v` (`nv × dim` block, [`BandedCrout::solve`]) while it is in
    /// the L1 cache, and forward-eliminate it along `u` (`L_u`, with the earlier rows as
    /// right-hand-side columns, [`BandedCrout::solve`]'s forward sweep over `nv·dim` columns).
    /// Sweep 2, rows in reverse: back-substitute along `u` (`U_u`), and add `q_00` back to each row
    /// as soon as no later row needs it. Each grid number is read twice and written twice
    /// (instead of the eight sweeps of a pass-by-pass solve), and the arithmetic is that of the
    /// two passes: the same operations per number, in a different order, so the result agrees with
    /// the pass-by-pass solve to rounding (tested against it at 1e-14 of the net's size).
    ///
    /// # Errors
    /// [`Error::IllConditioned`] if a control-net number overflows (data near the largest `f64`).
    ///
    /// Compiled with AVX2 where the processor has it ([`crate::numeric::isa`]: the same bits, tested).
    fn solve_grid(
        data: &[f64],
        nu: usize,
        nv: usize,
        dim: usize,
        lu_u: &BandedCrout,
        lu_v: &BandedCrout,
    ) -> Result<Vec<f64>> = solve_grid_body;
}

/// The body of [`solve_grid`], inlined into its baseline and AVX2 copies.
#[inline(always)]
fn solve_grid_body(
    data: &[f64],
    nu: usize,
    nv: usize,
    dim: usize,
    lu_u: &BandedCrout,
    lu_v: &BandedCrout,
) -> Result<Vec<f64>> {
    let row_len = nv * dim;
    let reference = &data[..dim];
    let ref_row: Vec<f64> = reference.iter().copied().cycle().take(row_len).collect();
    // grown row by row in sweep 1 (no zero-fill first: the allocator may hand back used memory)
    let mut control = crate::numeric::large_buffer::with_capacity(data.len());
    let (kl, ku) = (lu_u.kl(), lu_u.ku());
    for (k, q) in data.chunks_exact(row_len).enumerate() {
        control.extend(q.iter().zip(&ref_row).map(|(x, r)| x - r));
        let (done, row) = control.split_at_mut(k * row_len);
        lu_v.solve(row, dim);
        let l = lu_u.lower_row(k);
        let prev = |j: usize| &done[j * row_len..(j + 1) * row_len];
        match (kl, k >= kl) {
            (1, true) => combine_rows(row, [prev(k - 1)], [l[0]], l[1]),
            (2, true) => combine_rows(row, [prev(k - 2), prev(k - 1)], [l[0], l[1]], l[2]),
            (3, true) => combine_rows(
                row,
                [prev(k - 3), prev(k - 2), prev(k - 1)],
                [l[0], l[1], l[2]],
                l[3],
            ),
            _ => {
                // the first rows (entries of L left of column 0 are skipped) and wide bands
                for m in kl.saturating_sub(k)..kl {
                    combine_rows(row, [prev(k + m - kl)], [l[m]], 1.0);
                }
                scale_row(row, l[kl]);
            }
        }
    }
    // sweep 2: x_k = y_k − Σ_t U[k][k+1+t]·x_{k+1+t}; row k+ku is final after row k
    let mut poison = [0.0_f64; 4];
    for k in (0..nu).rev() {
        let (head, tail) = control.split_at_mut((k + 1) * row_len);
        let row = &mut head[k * row_len..];
        let u = lu_u.upper_row(k);
        let next = |t: usize| &tail[t * row_len..(t + 1) * row_len];
        let live = ku.min(nu - 1 - k);
        match (ku, live == ku) {
            (1, true) => combine_rows(row, [next(0)], [u[0]], 1.0),
            (2, true) => combine_rows(row, [next(0), next(1)], [u[0], u[1]], 1.0),
            (3, true) => combine_rows(row, [next(0), next(1), next(2)], [u[0], u[1], u[2]], 1.0),
            _ => {
                for (t, &ut) in u[..live].iter().enumerate() {
                    combine_rows(row, [next(t)], [ut], 1.0);
                }
            }
        }
        if ku == 0 {
            uncentre_row(row, &ref_row, &mut poison);
        } else if k + ku < nu {
            uncentre_row(
                &mut tail[(ku - 1) * row_len..ku * row_len],
                &ref_row,
                &mut poison,
            );
        }
    }
    for row in control.chunks_exact_mut(row_len).take(ku.min(nu)) {
        uncentre_row(row, &ref_row, &mut poison);
    }
    // data near the largest f64 overflow in the centring or the solves (found by the
    // `interpolation` fuzz target): an error, never a NaN control net inside an Ok
    if poison.iter().any(|v| *v != 0.0) {
        let i = control.iter().position(|v| !v.is_finite()).unwrap_or(0);
        return Err(Error::IllConditioned {
            reason: format!(
                "control net coordinate {i} overflowed to {:e}: the grid's coordinates are too \
                 close to the largest f64 (or differ by more than it); rescale the data",
                control[i]
            ),
        });
    }
    Ok(control)
}

/// `x ← (x − Σ_m c_m·y_m)·s` element by element, the terms subtracted in the order given (the
/// order of [`BandedCrout::solve`]'s row operations); `s = 1` (exact) when there is no scale.
/// One pass over the row with `K` fixed, so the compiler keeps the coefficients in registers
/// and vectorises.
#[inline(always)]
fn combine_rows<const K: usize>(x: &mut [f64], ys: [&[f64]; K], c: [f64; K], s: f64) {
    let n = x.len();
    let ys = ys.map(|y| &y[..n]);
    for (i, xi) in x.iter_mut().enumerate() {
        let mut v = *xi;
        for m in 0..K {
            v -= c[m] * ys[m][i];
        }
        *xi = v * s;
    }
}

/// `x ← x·s` element by element.
#[inline(always)]
fn scale_row(x: &mut [f64], s: f64) {
    for v in x {
        *v *= s;
    }
}

/// Adds the reference row back (`x ← x + r`) and accumulates `x·0` into `poison`, four lanes
/// so that the loop vectorises: a lane stays 0 unless some `x` is infinite or NaN.
#[inline(always)]
fn uncentre_row(x: &mut [f64], r: &[f64], poison: &mut [f64; 4]) {
    let mut xs = x.chunks_exact_mut(4);
    let mut rs = r.chunks_exact(4);
    for (xc, rc) in (&mut xs).zip(&mut rs) {
        for i in 0..4 {
            xc[i] += rc[i];
            poison[i] += xc[i] * 0.0;
        }
    }
    for (xi, ri) in xs.into_remainder().iter_mut().zip(rs.remainder()) {
        *xi += ri;
        poison[0] += *xi * 0.0;
    }
}

mod grid_params;

#[cfg(test)]
mod tests;
