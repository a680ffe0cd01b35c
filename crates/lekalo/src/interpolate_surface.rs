//! Interpolation of a grid of points by a tensor-product B-spline surface (document 000 §A.5,
//! eq. 16–18): row and column parameters averaged, knots by averaging, two passes of curve
//! interpolation with one factorisation per direction.

use crate::error::{Error, Result};
use crate::interpolate::{
    add_reference, check_strictly_increasing, distance, parametrize_into, solve_collocation,
    Factors, Parametrization,
};
use crate::knots::KnotVector;
use crate::points::{Points, PointsRef};
use crate::surface::BSplineSurface;

/// Parts of a tensor-product B-spline surface `S(u, v) = Σ_i Σ_j N_{i,p}(u) N_{j,q}(v) P_ij`
/// with the grid parameters; `control[(i*nv + j)*dim + k]`. [`SurfaceInterpolant::into_surface`]
/// gives the [`BSplineSurface`].
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
}

/// Interpolates an `nu × nv` grid of points `q_kl` (flat, point `(k, l)` at
/// `(k*nv + l)*dim`) by a B-spline surface of degrees `(p, q)`: document 000 §A.5, eq. (16)–(18),
/// Algorithm A.5.
///
/// Parameters: for each column `l` the [`Parametrization`] of `q_0l … q_{n,l}`, averaged over the
/// columns (`ū_k = Σ_l ū_k^{(l)} / (m + 1)`, P&T §9.2.5), likewise `v̄_l` over the rows; knots by
/// averaging (eq. 3). Then two passes of curve interpolation, each with one matrix factored once:
/// the `u` pass solves all `nv·dim` columns of the grid together, the `v` pass reuses the `v`
/// factorisation for each of the `nu` rows. O(nu·nv·(p² + q²)·dim).
///
/// ```
/// use lekalo::{interpolate_surface, Parametrization, Points};
/// // a 4×3 grid on z = x·y
/// let mut data = Vec::new();
/// for k in 0..4 { for l in 0..3 { let (x, y) = (k as f64, l as f64); data.extend([x, y, x * y]); } }
/// let grid = Points::new(data, 3)?;
/// let s = interpolate_surface(grid.as_view(), 4, 3, 3, 2, Parametrization::Uniform)?;
/// assert_eq!((s.nu, s.nv), (4, 3));
/// assert_eq!(s.control.point(0), &[0.0, 0.0, 0.0]);
/// let (u, v) = (s.params_u[2], s.params_v[1]);
/// let p = s.into_surface().eval(u, v)?;
/// assert!((p[0] - 2.0).abs() < 1e-14 && (p[1] - 1.0).abs() < 1e-14 && (p[2] - 2.0).abs() < 1e-14);
/// # Ok::<(), lekalo::Error>(())
/// ```
///
/// # Errors
/// [`Error::LengthMismatch`] if the grid does not hold `nu·nv` points; [`Error::TooFew`] if `nu`
/// or `nv` is below 2; [`Error::Degree`] if `p ≥ nu`, `q ≥ nv` or a degree is 0;
/// [`Error::CoincidentPoints`] (flat point indices) for a zero step in a row or column;
/// [`Error::InvalidArgument`]; [`Error::SingularSystem`] / [`Error::IllConditioned`].
pub fn interpolate_surface(
    grid: PointsRef<'_>,
    nu: usize,
    nv: usize,
    degree_u: usize,
    degree_v: usize,
    parametrization: Parametrization,
) -> Result<SurfaceInterpolant> {
    let grid = Grid {
        points: grid,
        nu,
        nv,
    };
    surface(grid, degree_u, degree_v, parametrization, None)
}

/// [`interpolate_surface`] refusing, with [`Error::IllConditioned`], a system whose 1-norm
/// condition number is estimated above `max_condition` (a number ≥ 1, e.g. `1e8`): see
/// [`interpolate_surface_condition`] for the estimate. The result, when there is one, is that
/// of [`interpolate_surface`] bit for bit; the estimate adds a few banded solves per direction.
///
/// ```
/// use lekalo::{interpolate_surface_max_condition, Error, Parametrization, Points};
/// // a 6×4 grid whose rows 2 and 3 nearly coincide
/// let mut data = Vec::new();
/// for x in [0.0, 1.0, 2.0, 2.0 + 1e-10, 3.0, 4.0] {
///     for y in 0..4 { let y = f64::from(y); data.extend([x, y, (x * y).sin()]); }
/// }
/// let grid = Points::new(data, 3)?;
/// let e = interpolate_surface_max_condition(grid.as_view(), 6, 4, 3, 3, Parametrization::ChordLength, 1e8);
/// assert!(matches!(e, Err(Error::IllConditioned { .. })));
/// # Ok::<(), lekalo::Error>(())
/// ```
///
/// # Errors
/// As [`interpolate_surface`]; [`Error::IllConditioned`] for an estimate above the limit;
/// [`Error::InvalidArgument`] if `max_condition` is NaN or below 1.
pub fn interpolate_surface_max_condition(
    grid: PointsRef<'_>,
    nu: usize,
    nv: usize,
    degree_u: usize,
    degree_v: usize,
    parametrization: Parametrization,
    max_condition: f64,
) -> Result<SurfaceInterpolant> {
    crate::interpolate::check_condition_limit(max_condition)?;
    let (s, kappa) = surface_estimating(grid, nu, nv, degree_u, degree_v, parametrization)?;
    if kappa > max_condition {
        return Err(condition_exceeded(kappa, max_condition));
    }
    Ok(s)
}

/// Estimate of the 1-norm condition number `κ_1` of the linear system that
/// [`interpolate_surface`] solves for the grid. The system is the Kronecker product `A_u ⊗ A_v`
/// of the two curve collocation matrices, and `κ_1(A_u ⊗ A_v) = κ_1(A_u)·κ_1(A_v)` (both
/// `‖·‖_1` and the inverse factor over `⊗`: Horn & Johnson, *Topics in Matrix Analysis*, §4.2),
/// so the result is the product of the two directions' estimates, each by Higham's refinement
/// of Hager's method (ACM TOMS 14 (1988), Algorithm 4.1; LAPACK `dgbcon`), see
/// [`CurveInterpolation::condition`](crate::CurveInterpolation::condition). A lower bound,
/// usually exact.
///
/// ```
/// use lekalo::{interpolate_surface_condition, Parametrization, Points};
/// let mut data = Vec::new();
/// for k in 0..10 { for l in 0..8 { let (x, y) = (f64::from(k), f64::from(l)); data.extend([x, y, x * y]); } }
/// let grid = Points::new(data, 3)?;
/// let kappa = interpolate_surface_condition(grid.as_view(), 10, 8, 3, 3, Parametrization::Uniform)?;
/// assert!(kappa >= 1.0 && kappa < 100.0);
/// # Ok::<(), lekalo::Error>(())
/// ```
///
/// # Errors
/// As [`interpolate_surface`] (it performs the same solve).
pub fn interpolate_surface_condition(
    grid: PointsRef<'_>,
    nu: usize,
    nv: usize,
    degree_u: usize,
    degree_v: usize,
    parametrization: Parametrization,
) -> Result<f64> {
    surface_estimating(grid, nu, nv, degree_u, degree_v, parametrization).map(|(_, k)| k)
}

/// The interpolant and the estimate of `κ_1` of its system (see
/// [`interpolate_surface_condition`]).
fn surface_estimating(
    points: PointsRef<'_>,
    nu: usize,
    nv: usize,
    degree_u: usize,
    degree_v: usize,
    parametrization: Parametrization,
) -> Result<(SurfaceInterpolant, f64)> {
    let grid = Grid { points, nu, nv };
    let mut kappa = 1.0;
    let s = surface(grid, degree_u, degree_v, parametrization, Some(&mut kappa))?;
    Ok((s, kappa))
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

/// The grid of [`interpolate_surface`]: `nu × nv` points.
#[derive(Clone, Copy)]
struct Grid<'a> {
    points: PointsRef<'a>,
    nu: usize,
    nv: usize,
}

/// The body of [`interpolate_surface`]; with `kappa`, the product of the two directions'
/// condition estimates goes there.
fn surface(
    grid: Grid<'_>,
    degree_u: usize,
    degree_v: usize,
    parametrization: Parametrization,
    kappa: Option<&mut f64>,
) -> Result<SurfaceInterpolant> {
    let Grid {
        points: grid,
        nu,
        nv,
    } = grid;
    let total = nu.checked_mul(nv).ok_or(Error::TooLarge {
        what: "grid size",
        size: usize::MAX,
        max: crate::error::MAX_SCALARS,
    })?;
    if grid.len() != total {
        return Err(Error::LengthMismatch {
            what: "grid points (nu × nv)",
            expected: total,
            got: grid.len(),
        });
    }
    for (n, what) in [(nu, "grid rows (nu)"), (nv, "grid columns (nv)")] {
        if n < 2 {
            return Err(Error::TooFew {
                what,
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
    let pt = |k: usize, l: usize| &data[(k * nv + l) * dim..(k * nv + l + 1) * dim];
    let mut params_u = vec![0.0; nu];
    let mut params_v = vec![0.0; nv];
    let mut tmp = vec![0.0; nu.max(nv)];
    let fast_u = e == 1.0 && chord_params_u(data, nu, nv, dim, &mut params_u);
    for l in (0..nv).filter(|_| !fast_u) {
        parametrize_into(
            nu - 1,
            |k| pt(k, l),
            e,
            |k| (k * nv + l, (k + 1) * nv + l),
            &mut tmp[..nu],
        )?;
        for (a, b) in params_u.iter_mut().zip(&tmp) {
            *a += b;
        }
    }
    let fast_v = e == 1.0 && chord_params_v(data, nu, nv, dim, &mut params_v, &mut tmp[..nv]);
    if !fast_v {
        params_v.fill(0.0);
    }
    for k in (0..nu).filter(|_| !fast_v) {
        parametrize_into(
            nv - 1,
            |l| pt(k, l),
            e,
            |l| (k * nv + l, k * nv + l + 1),
            &mut tmp[..nv],
        )?;
        for (a, b) in params_v.iter_mut().zip(&tmp) {
            *a += b;
        }
    }
    finish_average(&mut params_u, nv);
    finish_average(&mut params_v, nu);
    check_strictly_increasing(&params_u)?;
    check_strictly_increasing(&params_v)?;
    let knots_u = KnotVector::averaged(&params_u, degree_u)?;
    let knots_v = KnotVector::averaged(&params_v, degree_v)?;
    let reference = pt(0, 0).to_vec();
    // the centred grid in one pass (no copy first)
    let mut control = Vec::with_capacity(data.len());
    for q in data.chunks_exact(dim) {
        control.extend(q.iter().zip(&reference).map(|(x, r)| x - r));
    }
    // u pass: rows k of the grid, all nv·dim numbers of a row as right-hand-side columns
    let factors = if kappa.is_some() {
        Factors::Estimate
    } else {
        Factors::Discard
    };
    let lu_u = solve_collocation(
        &knots_u,
        degree_u,
        &params_u,
        0,
        &mut control,
        nv * dim,
        factors,
    )?;
    // v pass: for each i, an nv × dim block; factor once, reuse
    let (first, rest) = control.split_at_mut(nv * dim);
    let lu = solve_collocation(
        &knots_v,
        degree_v,
        &params_v,
        0,
        first,
        dim,
        Factors::Keep.or(factors),
    )?;
    if let Some(k) = kappa {
        let (ku, kv) = (lu_u.condition_estimate(), lu.condition_estimate());
        *k = ku.unwrap_or(1.0) * kv.unwrap_or(1.0);
    }
    // the reference is added back to each row while it is still in cache; the first row was
    // solved above
    add_reference(first, &reference);
    for block in rest.chunks_exact_mut(nv * dim) {
        lu.solve(block, dim);
        add_reference(block, &reference);
    }
    // data near the largest f64 overflow in the centring or the solves (found by the
    // `interpolation` fuzz target): an error, never a NaN control net inside an Ok
    if let Some(i) = control.iter().position(|v| !v.is_finite()) {
        return Err(Error::IllConditioned {
            reason: format!(
                "control net coordinate {i} overflowed to {:e}: the grid's coordinates are too \
                 close to the largest f64 (or differ by more than it); rescale the data",
                control[i]
            ),
        });
    }
    Ok(SurfaceInterpolant {
        degree_u,
        degree_v,
        knots_u,
        knots_v,
        control: Points::from_raw(control, dim),
        nu,
        nv,
        params_u,
        params_v,
    })
}

/// The sums over the columns `l` of the chord-length parameters `ū_k^{(l)}` of
/// `q_0l … q_{nu−1,l}` added into `params_u` (zero on entry): the same numbers, in the same
/// order, as [`parametrize_into`] with exponent 1 column by column (P&T eq. 9.5), but computed
/// row pair by row pair so that the grid is read contiguously (the column walk strides over
/// whole rows and misses the cache at every point). `false`, with `params_u` to be discarded,
/// when a distance is zero or not finite, a column's length overflows or its parameters are not
/// strictly increasing: the caller then takes the column loop, which reports the problem.
fn chord_params_u(data: &[f64], nu: usize, nv: usize, dim: usize, params_u: &mut [f64]) -> bool {
    let row_len = nv * dim;
    let pairs = || {
        data.chunks_exact(row_len)
            .zip(data.chunks_exact(row_len).skip(1))
    };
    let mut total = vec![0.0_f64; nv];
    // the distances of the first pass, reused by the second (the same numbers)
    let mut dist = Vec::with_capacity((nu - 1) * nv);
    for (a, b) in pairs() {
        for ((s, p), q) in total
            .iter_mut()
            .zip(a.chunks_exact(dim))
            .zip(b.chunks_exact(dim))
        {
            let d = distance(p, q);
            if d == 0.0 || !d.is_finite() {
                return false;
            }
            *s += d;
            dist.push(d);
        }
    }
    if !total.iter().all(|s| s.is_finite()) {
        return false;
    }
    let inv: Vec<f64> = total.iter().map(|s| 1.0 / s).collect();
    // running sums and the previous parameter of each column
    let mut acc = vec![0.0_f64; nv];
    let mut prev = vec![0.0_f64; nv];
    for (k, row) in dist.chunks_exact(nv).enumerate().map(|(i, r)| (i + 1, r)) {
        let out = &mut params_u[k];
        for (l, &d) in row.iter().enumerate() {
            acc[l] += d;
            let t = if k + 1 < nu { acc[l] * inv[l] } else { 1.0 };
            if t <= prev[l] {
                return false;
            }
            prev[l] = t;
            *out += t;
        }
    }
    true
}

/// The sums over the rows `k` of the chord-length parameters `v̄_l^{(k)}` of
/// `q_k0 … q_{k,nv−1}` added into `params_v` (zero on entry; `tmp` holds `nv` numbers of
/// scratch): the same numbers, in the same order, as [`parametrize_into`] with exponent 1 row by
/// row (P&T eq. 9.5), without its per-point closures. `false`, with `params_v` to be discarded,
/// when a distance is zero or not finite, a row's length overflows or its parameters are not
/// strictly increasing: the caller then takes the general loop, which reports the problem.
fn chord_params_v(
    data: &[f64],
    nu: usize,
    nv: usize,
    dim: usize,
    params_v: &mut [f64],
    tmp: &mut [f64],
) -> bool {
    debug_assert_eq!(tmp.len(), nv, "scratch for one row");
    for row in data.chunks_exact(nv * dim).take(nu) {
        let mut sum = 0.0;
        tmp[0] = 0.0;
        for (l, (p, q)) in row
            .chunks_exact(dim)
            .zip(row.chunks_exact(dim).skip(1))
            .enumerate()
        {
            let d = distance(p, q);
            if d == 0.0 || !d.is_finite() {
                return false;
            }
            sum += d;
            tmp[l + 1] = sum;
        }
        if !sum.is_finite() {
            return false;
        }
        let inv = 1.0 / sum;
        for l in 1..nv - 1 {
            tmp[l] *= inv;
            if tmp[l] <= tmp[l - 1] {
                return false;
            }
        }
        tmp[nv - 1] = 1.0;
        if tmp[nv - 1] <= tmp[nv - 2] {
            return false;
        }
        for (a, b) in params_v.iter_mut().zip(tmp.iter()) {
            *a += b;
        }
    }
    true
}

/// Divides the summed parameters by their count and pins the ends to exactly 0 and 1.
fn finish_average(params: &mut [f64], count: usize) {
    let inv = 1.0 / count as f64;
    for t in params.iter_mut() {
        *t *= inv;
    }
    params[0] = 0.0;
    if let Some(last) = params.last_mut() {
        *last = 1.0;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The sums of [`parametrize_into`] with exponent 1, column by column (`along_u`, the
    /// reference for [`chord_params_u`]) or row by row (the reference for [`chord_params_v`]).
    fn general_loop(data: &[f64], nu: usize, nv: usize, dim: usize, along_u: bool) -> Vec<f64> {
        let (lines, len) = if along_u { (nv, nu) } else { (nu, nv) };
        let at = |line: usize, i: usize| {
            if along_u {
                i * nv + line
            } else {
                line * nv + i
            }
        };
        let mut sums = vec![0.0; len];
        let mut tmp = vec![0.0; len];
        for line in 0..lines {
            parametrize_into(
                len - 1,
                |i| &data[at(line, i) * dim..(at(line, i) + 1) * dim],
                1.0,
                |i| (i, i + 1),
                &mut tmp,
            )
            .unwrap();
            for (a, b) in sums.iter_mut().zip(&tmp) {
                *a += b;
            }
        }
        sums
    }

    #[test]
    fn row_pair_chord_parameters_equal_the_column_loop() {
        for (nu, nv, dim) in [(2, 2, 1), (5, 3, 3), (17, 11, 2), (40, 7, 3)] {
            let data: Vec<f64> = (0..nu * nv * dim)
                .map(|i| {
                    let x = i as f64;
                    (i / (nv * dim)) as f64 + 0.3 * (1.7 * x).sin() + 1e8
                })
                .collect();
            let mut fast = vec![0.0; nu];
            assert!(chord_params_u(&data, nu, nv, dim, &mut fast), "{nu}×{nv}");
            assert_eq!(
                fast,
                general_loop(&data, nu, nv, dim, true),
                "{nu}×{nv}×{dim}"
            );
        }
        // a zero step declines (the column loop reports it)
        let mut data = vec![0.0, 1.0, 2.0, 3.0, 2.0, 5.0];
        data[4] = data[2];
        let mut out = vec![0.0; 3];
        assert!(!chord_params_u(&data, 3, 2, 1, &mut out));
    }

    #[test]
    fn row_chord_parameters_equal_the_row_loop() {
        for (nu, nv, dim) in [(2, 2, 1), (3, 5, 3), (11, 17, 2), (7, 40, 3)] {
            let data: Vec<f64> = (0..nu * nv * dim)
                .map(|i| {
                    let x = i as f64;
                    ((i / dim) % nv) as f64 + 0.3 * (1.7 * x).sin() + 1e8
                })
                .collect();
            let (mut fast, mut tmp) = (vec![0.0; nv], vec![0.0; nv]);
            assert!(
                chord_params_v(&data, nu, nv, dim, &mut fast, &mut tmp),
                "{nu}×{nv}"
            );
            assert_eq!(
                fast,
                general_loop(&data, nu, nv, dim, false),
                "{nu}×{nv}×{dim}"
            );
        }
        // a zero step declines (the row loop reports it)
        let data = vec![0.0, 1.0, 1.0, 2.0, 3.0, 4.0];
        let (mut out, mut tmp) = (vec![0.0; 3], vec![0.0; 3]);
        assert!(!chord_params_v(&data, 2, 3, 1, &mut out, &mut tmp));
    }
}
