//! Least-squares surfaces: a grid of points with fewer control points (P&T §9.4.3), and
//! scattered `(u, v, z)` data on given tensor-product knots with weights and a smoothing penalty
//! (`docs/theory/fitting.md#surfaces`).

use crate::Arg;
use std::cell::Cell;

use super::banded::SymBand;
use super::data::FitData;
use super::knot_placement::place_knots;
use super::lsq::{least_squares, EndConstraints};
use super::progress::checked_rows;
use crate::basis::{basis_funs_into, BasisScratch};
use crate::error::{Error, Result};
use crate::interpolate::{parametrize, Parametrization};
use crate::knots::KnotVector;
use crate::numeric::progress::Progress;
use crate::points::{Points, PointsRef};
use crate::surface::BSplineSurface;

/// Least-squares surface through a grid of `nu × nv` points (point `(i, j)` at `i·nv + j`) with
/// `n_ctrl_u × n_ctrl_v` control points (P&T §9.4.3): parameters are the averages over the grid
/// lines of `parametrization`, knots by [`place_knots`]; every grid row is fitted by curve least
/// squares in `u` to give intermediate points, and every column of those in `v` — the tensor
/// product of the two one-dimensional least-squares projectors, which is the least-squares
/// solution over the whole grid. O(nu·nv·(p + q)).
///
/// ```
/// use lekalo::fit::surface_grid_least_squares;
/// use lekalo::{Parametrization, PointsRef};
/// let grid: Vec<f64> = (0..20).flat_map(|i| (0..15).flat_map(move |j| {
///     let (x, y) = (i as f64, j as f64); [x, y, (x * 0.3).sin() * (y * 0.2).cos()] })).collect();
/// let s = surface_grid_least_squares(PointsRef::from_flat(3, &grid)?, (20, 15), (3, 3), (8, 6), Parametrization::ChordLength)?;
/// assert_eq!(s.net_size(), (8, 6));
/// # Ok::<(), lekalo::Error>(())
/// ```
///
/// # Errors
/// [`Error::LengthMismatch`] if the grid does not hold `nu·nv` points; the errors of
/// [`place_knots`] and [`least_squares`] per direction; parametrisation errors.
pub fn surface_grid_least_squares(
    grid: PointsRef<'_>,
    (nu, nv): (usize, usize),
    (p, q): (usize, usize),
    (ncu, ncv): (usize, usize),
    parametrization: Parametrization,
) -> Result<BSplineSurface> {
    let (uu, vv) = surface_grid_parameters(grid, (nu, nv), parametrization)?;
    let ku = place_knots(&uu, p, ncu)?;
    let kv = place_knots(&vv, q, ncv)?;
    surface_grid_least_squares_at(grid, (nu, nv), (p, q), (&uu, &vv), (&ku, &kv))
}

/// The parameters [`surface_grid_least_squares`] gives a grid of `nu × nv` points: in each
/// direction the average over the grid lines of `parametrization`, the ends pinned to 0 and 1
/// (P&T §9.2.5).
///
/// # Errors
/// [`Error::LengthMismatch`] if the grid does not hold `nu·nv` points (each at least 2);
/// parametrisation errors.
pub fn surface_grid_parameters(
    grid: PointsRef<'_>,
    (nu, nv): (usize, usize),
    parametrization: Parametrization,
) -> Result<(Vec<f64>, Vec<f64>)> {
    check_grid(grid, (nu, nv))?;
    let dim = grid.dim();
    let data = grid.as_slice();
    // averaged parameters over the grid lines
    let average = |lines: Vec<Vec<f64>>, len: usize| -> Result<Vec<f64>> {
        let mut acc = vec![0.0; len];
        let count = lines.len() as f64;
        for line in lines {
            let pts = PointsRef::from_flat(dim, &line)?;
            for (a, u) in acc.iter_mut().zip(parametrize(pts, parametrization)?) {
                *a += u / count;
            }
        }
        acc[0] = 0.0;
        acc[len - 1] = 1.0;
        Ok(acc)
    };
    let rows_u: Vec<Vec<f64>> = (0..nv)
        .map(|j| {
            (0..nu)
                .flat_map(|i| grid.point(i * nv + j).to_vec())
                .collect()
        })
        .collect();
    let rows_v: Vec<Vec<f64>> = (0..nu)
        .map(|i| data[i * nv * dim..(i + 1) * nv * dim].to_vec())
        .collect();
    Ok((average(rows_u, nu)?, average(rows_v, nv)?))
}

/// [`surface_grid_least_squares`] at given parameters `(u, v)` (`nu` and `nv` of them, strictly
/// increasing) on given knots `(ku, kv)` of degrees `(p, q)`: every grid column (fixed `v`) is
/// fitted by curve least squares in `u`, then every row of those points in `v` (P&T §9.4.3, the
/// tensor product of the two projectors). The net has `ku.len() − p − 1` by `kv.len() − q − 1`
/// control points. `O(nu·nv·(p + q))`.
///
/// ```
/// use lekalo::fit::surface_grid_least_squares_at;
/// use lekalo::{KnotVector, PointsRef};
/// // z = u² − uv on a 9 × 7 grid, fitted by a 5 × 4 net of degree 2: recovered
/// let (u, v): (Vec<f64>, Vec<f64>) = ((0..9).map(|i| i as f64 / 8.0).collect(), (0..7).map(|j| j as f64 / 6.0).collect());
/// let grid: Vec<f64> = u.iter().flat_map(|&x| v.iter().flat_map(move |&y| [x, y, x * x - x * y])).collect();
/// let (ku, kv) = (KnotVector::clamped_uniform(2, 5)?, KnotVector::clamped_uniform(2, 4)?);
/// let s = surface_grid_least_squares_at(PointsRef::from_flat(3, &grid)?, (9, 7), (2, 2), (&u, &v), (&ku, &kv))?;
/// assert_eq!(s.net_size(), (5, 4));
/// let z = s.eval(0.3, 0.6)?[2];
/// assert!((z - (0.09 - 0.18)).abs() < 1e-13);
/// # Ok::<(), lekalo::Error>(())
/// ```
///
/// # Errors
/// [`Error::LengthMismatch`] if the grid does not hold `nu·nv` points or a parameter list does
/// not have `nu` (`nv`) entries; the errors of [`least_squares`] per direction (degree,
/// parameters outside the knots' domain, Schoenberg–Whitney).
pub fn surface_grid_least_squares_at(
    grid: PointsRef<'_>,
    (nu, nv): (usize, usize),
    (p, q): (usize, usize),
    (uu, vv): (&[f64], &[f64]),
    (ku, kv): (&KnotVector, &KnotVector),
) -> Result<BSplineSurface> {
    check_grid(grid, (nu, nv))?;
    for (what, params, n) in [
        ("u parameters (one per grid row)", uu, nu),
        ("v parameters (one per grid column)", vv, nv),
    ] {
        if params.len() != n {
            return Err(Error::LengthMismatch {
                what: what.into(),
                expected: n,
                got: params.len(),
            });
        }
    }
    let dim = grid.dim();
    let (ncu, ncv) = (
        ku.len().saturating_sub(p + 1),
        kv.len().saturating_sub(q + 1),
    );
    // u direction: each grid column (fixed j) → ncu points
    let mut mid = vec![0.0; ncu * nv * dim];
    let mut line = Vec::with_capacity(nu * dim);
    for j in 0..nv {
        line.clear();
        for i in 0..nu {
            line.extend_from_slice(grid.point(i * nv + j));
        }
        let d = FitData::new(PointsRef::from_flat(dim, &line)?, uu)?;
        let f = least_squares(&d, p, ku, &EndConstraints::none())?;
        for (i, c) in f.curve.control_points().iter().enumerate() {
            mid[(i * nv + j) * dim..(i * nv + j + 1) * dim].copy_from_slice(c);
        }
    }
    let mut net = vec![0.0; ncu * ncv * dim];
    for i in 0..ncu {
        let line = &mid[i * nv * dim..(i + 1) * nv * dim];
        let d = FitData::new(PointsRef::from_flat(dim, line)?, vv)?;
        let f = least_squares(&d, q, kv, &EndConstraints::none())?;
        net[i * ncv * dim..(i + 1) * ncv * dim]
            .copy_from_slice(f.curve.control_points().as_slice());
    }
    BSplineSurface::from_knot_vectors(
        p,
        q,
        ku.clone(),
        kv.clone(),
        Points::from_flat(dim, net)?,
        (ncu, ncv),
    )
}

/// A grid of `nu × nv ≥ 2 × 2` points.
fn check_grid(grid: PointsRef<'_>, (nu, nv): (usize, usize)) -> Result<()> {
    if nu.checked_mul(nv) != Some(grid.len()) || nu < 2 || nv < 2 {
        return Err(Error::LengthMismatch {
            what: "grid points (nu · nv, each at least 2)".into(),
            expected: nu.saturating_mul(nv),
            got: grid.len(),
        });
    }
    Ok(())
}

/// The result of [`surface_scattered_least_squares`].
#[derive(Debug, Clone, PartialEq)]
pub struct ScatteredSurfaceFit {
    /// The surface `z(u, v)` (control points of dimension `dim − 2`).
    pub surface: BSplineSurface,
    /// `|S(u_k, v_k) − z_k|` for every point.
    pub residuals: Vec<f64>,
    /// Weighted residual sum of squares.
    pub weighted_rss: f64,
}

/// Least squares over scattered data `(u_k, v_k, z_k)` (rows of `data`: `u, v` then the values,
/// any number of them) on given tensor-product knots, with optional weights and a smoothing
/// penalty (SciPy's `LSQBivariateSpline` for `penalty = 0`): minimises
/// `Σ_k w_k |S(u_k, v_k) − z_k|² + penalty · Σ (second differences of the net along u and v)²`.
///
/// The normal matrix, in the order `i·n_v + j`, is symmetric and banded with half-bandwidth
/// `p·n_v + q`; it is assembled point by point and factored by the banded `UᵀDU` of the curve
/// smoothing (O(`n_u n_v (p n_v + q)²`), no dense matrix; fill inside the band is unavoidable for
/// a direct solver in this ordering). The values are shifted by the first point's before the
/// solve. A knot cell without data leaves the matrix singular: with `penalty = 0` this is
/// [`Error::SchoenbergWhitney`] whose `basis` is the net index `i·n_v + j` of the first control
/// point without data and whose span is that point's support in `u`; a positive penalty (the discrete
/// second-difference penalty of Eilers & Marx's P-splines) fills such cells smoothly from
/// their neighbours.
///
/// # Errors
/// [`Error::Dimension`] for rows with fewer than 3 numbers; [`Error::LengthMismatch`] /
/// [`Error::InvalidDataWeight`] for bad weights; [`Error::ParameterOutOfDomain`] for a point
/// outside the knots' domain; [`Error::NegativeSmoothing`] for a negative penalty;
/// [`Error::SchoenbergWhitney`] as above; the knot errors of [`KnotVector::validate_for`];
/// [`Error::TooLarge`] when the banded normal matrix (`n_u n_v × (p n_v + q + 1)` numbers)
/// would hold more than [`MAX_SCALARS`](crate::error::MAX_SCALARS).
pub fn surface_scattered_least_squares(
    data: PointsRef<'_>,
    weights: Option<&[f64]>,
    degrees: (usize, usize),
    knots: (&KnotVector, &KnotVector),
    penalty: f64,
) -> Result<ScatteredSurfaceFit> {
    surface_scattered_least_squares_with_progress(
        data,
        weights,
        degrees,
        knots,
        penalty,
        &Progress::new(),
    )
}

/// [`surface_scattered_least_squares`] reporting to `progress` as the data points are added to
/// the normal matrix and as its rows are factored (`done` of `total` = points + control points,
/// a report every few thousand operations' worth of rows), and stopping with
/// [`Error::Cancelled`] between two blocks of rows when its cancel flag is set. The result is
/// the same with or without the hook.
///
/// # Errors
/// As [`surface_scattered_least_squares`], and [`Error::Cancelled`].
pub fn surface_scattered_least_squares_with_progress(
    data: PointsRef<'_>,
    weights: Option<&[f64]>,
    (p, q): (usize, usize),
    (ku, kv): (&KnotVector, &KnotVector),
    penalty: f64,
    progress: &Progress<'_>,
) -> Result<ScatteredSurfaceFit> {
    let ScatteredNormal {
        a,
        mut rhs,
        center,
        net: (nu, nv),
        band,
    } = scattered_normal_equations(data, weights, (p, q), (ku, kv), penalty, progress)?;
    let (n, vd, tu) = (data.len(), data.dim() - 2, ku.as_slice());
    let total = n.saturating_add(nu * nv);
    let mut f = a;
    let every = Progress::items_per_step(((band + 1) * (band + 1)) as u64);
    let factored = f.factor_with(|i| {
        if i % every == 0 {
            progress.step(WORK, (n + i) as u64, total as u64)
        } else {
            Ok(())
        }
    })?;
    if let Err(i) = factored {
        let ci = i / nv;
        return Err(Error::SchoenbergWhitney {
            basis: i,
            start: tu[ci],
            end: tu[ci + p + 1],
        });
    }
    f.solve(&mut rhs, vd);
    for c in rhs.chunks_exact_mut(vd) {
        for (x, o) in c.iter_mut().zip(&center) {
            *x += o;
        }
    }
    let surface = BSplineSurface::from_knot_vectors(
        p,
        q,
        ku.clone(),
        kv.clone(),
        Points::from_flat(vd, rhs)?,
        (nu, nv),
    )?;
    let mut residuals = Vec::with_capacity(n);
    let mut weighted_rss = 0.0;
    let mut out = vec![0.0; vd];
    for (k, row) in data.iter().enumerate() {
        surface.eval_into(row[0], row[1], &mut out)?;
        let r: f64 = out
            .iter()
            .zip(&row[2..])
            .map(|(s, z)| (s - z) * (s - z))
            .sum::<f64>();
        weighted_rss += weights.map_or(1.0, |w| w[k]) * r;
        residuals.push(r.sqrt());
    }
    // the fit is complete: a flag set this late does not discard it
    let _ = progress.step(WORK, total as u64, total as u64);
    Ok(ScatteredSurfaceFit {
        surface,
        residuals,
        weighted_rss,
    })
}

/// What scattered least squares reports its steps as.
const WORK: &str = "scattered surface fit (points, then rows of the normal matrix)";

/// The normal equations of [`surface_scattered_least_squares`]: `BᵀWB + penalty·DᵀD` (upper
/// band, order `i·n_v + j`), `BᵀW(z − center)` with one column per value, the values' shift
/// (the first point's), the net's size and the band's half-width.
pub(crate) struct ScatteredNormal {
    pub(crate) a: SymBand,
    pub(crate) rhs: Vec<f64>,
    pub(crate) center: Vec<f64>,
    pub(crate) net: (usize, usize),
    pub(crate) band: usize,
}

/// The normal equations of [`surface_scattered_least_squares`] after checking its arguments,
/// reporting each point added to `progress` (the first `data.len()` of `data.len() + n_u n_v`
/// steps).
///
/// # Errors
/// The argument errors of [`surface_scattered_least_squares`] and [`Error::Cancelled`].
pub(crate) fn scattered_normal_equations(
    data: PointsRef<'_>,
    weights: Option<&[f64]>,
    (p, q): (usize, usize),
    (ku, kv): (&KnotVector, &KnotVector),
    penalty: f64,
    progress: &Progress<'_>,
) -> Result<ScatteredNormal> {
    let dim = data.dim();
    if dim < 3 {
        return Err(Error::Dimension {
            what: "scattered surface data (u, v, then at least one value per row)".into(),
            expected: 3,
            got: dim,
        });
    }
    if !(penalty >= 0.0 && penalty.is_finite()) {
        return Err(Error::NegativeSmoothing {
            what: Arg::Lambda.into(),
            value: penalty,
        });
    }
    let vd = dim - 2;
    let nu = ku.len().saturating_sub(p + 1);
    let nv = kv.len().saturating_sub(q + 1);
    ku.validate_for(p, nu)?;
    kv.validate_for(q, nv)?;
    let n = data.len();
    if let Some(w) = weights {
        // the same checks as curve data
        let dummy: Vec<f64> = vec![0.0; n];
        FitData::new(PointsRef::from_flat(1, &dummy)?, &dummy)?.with_weights(w)?;
    }
    let (du, dv) = (ku.domain(p), kv.domain(q));
    for row in data.iter() {
        let (u, v) = (row[0], row[1]);
        if !(u >= du.0 && u <= du.1) {
            return Err(Error::ParameterOutOfDomain {
                t: u,
                min: du.0,
                max: du.1,
            });
        }
        if !(v >= dv.0 && v <= dv.1) {
            return Err(Error::ParameterOutOfDomain {
                t: v,
                min: dv.0,
                max: dv.1,
            });
        }
    }
    let m = nu.saturating_mul(nv);
    // Solver choice. The issue's candidates were faer's sparse Cholesky and sparse QR. QR of the
    // N × m observation matrix would not square the condition number, but it stores or streams
    // N rows of (p+1)(q+1) entries through a multifrontal factor, several times the work of
    // assembling the normal matrix once (each point adds (p+1)²(q+1)² products and is
    // forgotten); B-spline normal matrices are well conditioned when every cell holds data, and
    // the data are shifted by their first value, so the squaring costs few digits here. A
    // general sparse Cholesky (faer, with a fill-reducing ordering) would beat the band only for
    // large nets: in the order i·n_v + j the factor fills the band anyway, and for the nets of
    // interest (30 × 30: m = 900, band 93) the banded UᵀDU is about m·b² ≈ 8·10⁶ flops, below
    // the assembly, with no symbolic analysis and no dependency. Nested dissection would pay
    // from nets of a few hundred per side.
    // the second differences along u couple rows i and i + 2
    let band = if penalty > 0.0 {
        (p * nv + q).max(2 * nv)
    } else {
        p * nv + q
    };
    // the band is m × (band + 1) numbers: a net of 3000 × 3000 asked for 648 GB and aborted
    let size = m.saturating_mul(band.saturating_add(1));
    if size > crate::error::MAX_SCALARS {
        return Err(Error::TooLarge {
            what: "normal matrix of the scattered fit (control points × band width)".into(),
            size,
            max: crate::error::MAX_SCALARS,
        });
    }
    let mut a = SymBand::zeros(m, band);
    let mut rhs = vec![0.0; m * vd];
    let center: Vec<f64> = data.point(0)[2..].to_vec();
    let (mut su, mut sv) = (BasisScratch::new(p), BasisScratch::new(q));
    let (mut bu, mut bv) = (vec![0.0; p + 1], vec![0.0; q + 1]);
    let mut idx = Vec::with_capacity((p + 1) * (q + 1));
    let mut val = Vec::with_capacity((p + 1) * (q + 1));
    let (tu, tv) = (ku.as_slice(), kv.as_slice());
    let total = n.saturating_add(m);
    let stopped = Cell::new(None);
    let cost = ((p + 1) * (q + 1)).pow(2) as u64;
    for k in checked_rows(progress, WORK, total, cost, 0..n, &stopped) {
        let row = data.point(k);
        let w = weights.map_or(1.0, |w| w[k]);
        let (u, v) = (row[0], row[1]);
        let (iu, iv) = (ku.span_unchecked(p, u), kv.span_unchecked(q, v));
        if w == 0.0 {
            continue;
        }
        basis_funs_into(tu, p, iu, u, &mut su, &mut bu);
        basis_funs_into(tv, q, iv, v, &mut sv, &mut bv);
        idx.clear();
        val.clear();
        for (a_, &x) in bu.iter().enumerate() {
            for (b_, &y) in bv.iter().enumerate() {
                idx.push((iu - p + a_) * nv + iv - q + b_);
                val.push(x * y);
            }
        }
        for r in 0..idx.len() {
            let wr = w * val[r];
            for c in r..idx.len() {
                let (i, j) = if idx[r] <= idx[c] {
                    (idx[r], idx[c])
                } else {
                    (idx[c], idx[r])
                };
                let v2 = wr * val[c];
                a.add(i, j, v2);
            }
            for (c, (z, o)) in row[2..].iter().zip(&center).enumerate() {
                rhs[idx[r] * vd + c] += wr * (z - o);
            }
        }
    }
    if penalty > 0.0 {
        // second differences along u (stride nv) and along v (stride 1)
        for (count, stride, ok) in [(nu, nv, true), (nv, 1, false)] {
            if count < 3 {
                continue;
            }
            for other in 0..(if ok { nv } else { nu }) {
                for s in 0..count - 2 {
                    let base = if ok { s * nv + other } else { other * nv + s };
                    let ids = [base, base + stride, base + 2 * stride];
                    let coef = [1.0, -2.0, 1.0];
                    for r in 0..3 {
                        for c in r..3 {
                            let v2 = penalty * coef[r] * coef[c];
                            a.add(ids[r], ids[c], v2);
                        }
                    }
                }
            }
        }
    }
    if let Some(e) = stopped.take() {
        return Err(e);
    }
    Ok(ScatteredNormal {
        a,
        rhs,
        center,
        net: (nu, nv),
        band,
    })
}
