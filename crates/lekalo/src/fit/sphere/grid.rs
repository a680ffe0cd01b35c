//! Fits of data on a grid of the sphere (FITPACK `spgrid`/`fpspgr`/`fpopsp`/`fpgrsp`, SciPy's
//! `RectSphereBivariateSpline`): colatitudes `u` in `(0, π)`, longitudes `v` over at most one
//! period from `v₀ ∈ [−π, π)`, values `r` on `u × v`. `docs/theory/sphere.md#grid`.
//!
//! On given knots and weight `p` the fit minimises
//! `‖(A_u ⊗ A_v) c − r‖² + (pole priors)` where `A_u = [B_u; J_u/p]`, `A_v = [B_v; J_v/p]`
//! stack the basis values at the grid lines and the jumps of the third derivatives (Dierckx
//! 1993, §10.3 and §11.2). The pole rows of `c` are affine in the pole parameters `d`
//! ([`SphereSpace`]); moved to the right-hand side, they leave a Kronecker least-squares
//! problem in the free rows, solved by one banded QR along `u` and one cyclic banded QR along
//! `v` (`O(m_u·m_v·(n_u + n_φ))` for an `m_u × m_v` grid). The residual is affine in the free pole
//! parameters: the same two sweeps carry one right-hand side per free parameter, the Gram matrix
//! of the residual parts gives the optimal parameters exactly (FITPACK `fpopsp` fits the same
//! quadratic by finite differences).

use super::scattered::invalid;
use super::space::{PoleCondition, SphereSpace, PI, TWO_PI};
use super::SphereFit;
use crate::basis::{basis_funs_into, BasisScratch};
use crate::error::{Error, Result};
use crate::fit::banded::{BandedQr, RANK_RTOL};
use crate::fit::cyclic::CyclicQr;
use crate::fit::{
    accepts_least_squares, jump_rows, next_nplus, smooth_weight, Steps, SMOOTHING_RTOL,
};
use crate::knots::span_in;
use crate::numeric::progress::Progress;
use crate::tensor::rotate_full;
use crate::{Arg, What};

/// Data on a grid of the sphere, checked.
#[derive(Debug, Clone, Copy)]
pub struct SphereGrid<'a> {
    u: &'a [f64],
    v: &'a [f64],
    r: &'a [f64],
}

impl<'a> SphereGrid<'a> {
    /// The grid `u × v` with the values `r` (`u.len() · v.len()`, `u` slowest), checked with
    /// SciPy's words.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] naming `u` ("u should be between (0, pi)", "u must be
    /// strictly increasing"), `v` ("v[0] should be between [-pi, pi)", "v[-1] should be
    /// v[0] + 2pi or less", "v must be strictly increasing"); [`Error::LengthMismatch`] if `r`
    /// does not hold one value per grid node; [`Error::NonFinite`] for a value of `r` that is
    /// NaN or infinite, and [`Error::InvalidArgument`] naming `r` for values so large that the
    /// fit's residual sum of squares overflows; [`Error::TooFew`] for an empty grid or fewer
    /// than four longitudes.
    pub fn new(u: &'a [f64], v: &'a [f64], r: &'a [f64]) -> Result<Self> {
        let (Some(&u0), Some(&u1), Some(&v0), Some(&v1)) =
            (u.first(), u.last(), v.first(), v.last())
        else {
            return Err(Error::TooFew {
                what: "grid lines (u and v)".into(),
                min: 1,
                got: 0,
            });
        };
        if !(u0 > 0.0 && u1 < PI) {
            return Err(invalid(
                What::of(Arg::Colatitudes, "u"),
                format!("u should be between (0, pi) (u = {u0} … {u1})"),
            ));
        }
        if !(-PI..PI).contains(&v0) {
            return Err(invalid(
                What::of(Arg::Longitudes, "v"),
                format!("v[0] should be between [-pi, pi) (v[0] = {v0})"),
            ));
        }
        if v1 >= v0 + TWO_PI || v1.is_nan() {
            return Err(invalid(
                What::of(Arg::Longitudes, "v"),
                format!(
                    "v[-1] should be v[0] + 2pi or less; v[-1] = {v1} reaches v[0] + 2pi, the \
                     same meridian as v[0]: give it once"
                ),
            ));
        }
        for (key, what, x) in [(Arg::Colatitudes, "u", u), (Arg::Longitudes, "v", v)] {
            // not greater, or not comparable: a NaN between the ends is refused too
            if let Some(i) = x
                .windows(2)
                .position(|p| p[1].partial_cmp(&p[0]) != Some(std::cmp::Ordering::Greater))
            {
                return Err(invalid(
                    What::of(key, what),
                    format!(
                        "{what} must be strictly increasing ({what}[{}] = {})",
                        i + 1,
                        x[i + 1]
                    ),
                ));
            }
        }
        if v.len() < 4 {
            return Err(Error::TooFew {
                what: What::of(
                    Arg::Longitudes,
                    "longitudes v (a periodic cubic needs four)",
                ),
                min: 4,
                got: v.len(),
            });
        }
        if r.len() != u.len() * v.len() {
            return Err(Error::LengthMismatch {
                what: "r (one value per node of u × v)".into(),
                expected: u.len() * v.len(),
                got: r.len(),
            });
        }
        if let Some(i) = r.iter().position(|x| !x.is_finite()) {
            return Err(Error::NonFinite {
                what: "r".into(),
                index: i,
                value: r[i],
            });
        }
        super::scattered::check_scale(r, None)?;
        Ok(SphereGrid { u, v, r })
    }
}

/// A pole parameter: fixed, or free with an optional prior value counted as one more datum.
#[derive(Debug, Clone, Copy)]
enum Param {
    Fixed(f64),
    Free(Option<f64>),
}

/// The six parameters `(v₀, a₀, b₀, v₁, a₁, b₁)` of the conditions; `exact_given` makes every
/// given value exact (FITPACK's interpolation does).
fn params(sp: &SphereSpace, poles: &[PoleCondition; 2], exact_given: bool) -> [Param; 6] {
    let mut out = [Param::Fixed(0.0); 6];
    for (p, pole) in poles.iter().enumerate() {
        out[3 * p] = match pole.value {
            Some(v) if pole.exact || exact_given => Param::Fixed(v),
            Some(v) => Param::Free(Some(v)),
            None => Param::Free(None),
        };
        if sp.c1[p] && !pole.flat && sp.npp >= 4 {
            out[3 * p + 1] = Param::Free(None);
            out[3 * p + 2] = Param::Free(None);
        }
    }
    out
}

/// One row along a direction: its first coefficient and up to five values.
#[derive(Debug, Clone, Copy)]
struct Row {
    first: usize,
    len: usize,
    val: [f64; 5],
}

/// The rows `[B; J/p]` of a direction: the cubic basis at `x` and, for finite `p`, the jumps.
fn rows_of(t: &[f64], x: &[f64], p: f64) -> Vec<Row> {
    let mut scratch = BasisScratch::new(3);
    let mut rows: Vec<Row> = x
        .iter()
        .map(|&x| {
            let l = span_in(t, 3, x);
            let mut val = [0.0; 5];
            basis_funs_into(t, 3, l, x, &mut scratch, &mut val[..4]);
            Row {
                first: l - 3,
                len: 4,
                val,
            }
        })
        .collect();
    if p.is_finite() && t.len() > 8 {
        for (r, jr) in jump_rows(t, 3).rows.chunks_exact(5).enumerate() {
            let mut val = [0.0; 5];
            for (o, v) in val.iter_mut().zip(jr) {
                *o = v / p;
            }
            rows.push(Row {
                first: r,
                len: 5,
                val,
            });
        }
    }
    rows
}

/// A fit on given knots: tensor coefficients, pole parameters, data residual and the
/// residual of the whole system.
struct Solved {
    c: Vec<f64>,
    d: [f64; 6],
    fp: f64,
}

/// The fit on the knots of `sp` with weight `p` (`∞`: least squares) and the pole parameters
/// `par` (module docs).
fn solve(grid: &SphereGrid<'_>, sp: &SphereSpace, par: &[Param; 6], p: f64) -> Result<Solved> {
    let (mu, mv, npp) = (grid.u.len(), grid.v.len(), sp.npp);
    let rows = sp.free_rows();
    let nuu = rows.len();
    let free: Vec<usize> = (0..6)
        .filter(|&q| matches!(par[q], Param::Free(_)))
        .collect();
    let nl = 1 + free.len();
    let urows = rows_of(&sp.tt, grid.u, p);
    let vrows = rows_of(&sp.tp, grid.v, p);
    let nvr = vrows.len();
    let size = (urows.len().max(npp) + nuu).saturating_mul(nl * nvr.max(nuu));
    if size > crate::MAX_SCALARS {
        return Err(Error::TooLarge {
            what: "right-hand sides of the fit on the sphere".into(),
            size,
            max: crate::MAX_SCALARS,
        });
    }
    // Σ_j V[b, j]·(1, γ_j, σ_j) for each v row b
    let vsum: Vec<[f64; 3]> = vrows
        .iter()
        .map(|row| {
            let mut s = [0.0; 3];
            for (q, &x) in row.val[..row.len].iter().enumerate() {
                let [g, si] = sp.cos_sin[(row.first + q) % npp];
                s[0] += x;
                s[1] += x * g;
                s[2] += x * si;
            }
            s
        })
        .collect();
    // ∂(model)/∂d_q at (a, b) = Σ_i U[a, i] ∂c_{i,·}/∂d_q contracted with V[b, ·]
    let pole_terms = |row: &Row| -> [[f64; 2]; 2] {
        let mut t = [[0.0; 2]; 2];
        for (q, &x) in row.val[..row.len].iter().enumerate() {
            let i = row.first + q;
            if let Some((pole, _)) = sp.pole_row(i, 0) {
                t[pole][0] += x;
                if sp.derivative_row(pole) == Some(i) {
                    t[pole][1] += x * sp.derivative_factor(pole);
                }
            }
        }
        t
    };
    let coef = |l: usize, q: usize| -> f64 {
        if l == 0 {
            match par[q] {
                Param::Fixed(v) => v,
                Param::Free(_) => 0.0,
            }
        } else if free[l - 1] == q {
            1.0
        } else {
            0.0
        }
    };
    let mut gram = vec![0.0; nl * nl];
    let mut add_gram = |y: &[f64], per: usize| {
        for l1 in 0..nl {
            for l2 in 0..=l1 {
                let s: f64 = y[l1 * per..(l1 + 1) * per]
                    .iter()
                    .zip(&y[l2 * per..(l2 + 1) * per])
                    .map(|(a, b)| a * b)
                    .sum();
                gram[l1 * nl + l2] += s;
            }
        }
    };
    // sweep along u
    let nc_u = nl * nvr;
    let mut qr_u = BandedQr::new(nuu, 5, nc_u);
    let mut y = vec![0.0; nc_u];
    let mut h = [0.0; 5];
    for (a, row) in urows.iter().enumerate() {
        let t = pole_terms(row);
        for l in 0..nl {
            for (b, vs) in vsum.iter().enumerate() {
                let mut x = if l == 0 && a < mu && b < mv {
                    grid.r[a * mv + b]
                } else {
                    0.0
                };
                for pole in 0..2 {
                    x -= coef(l, 3 * pole) * t[pole][0] * vs[0];
                    x -= t[pole][1]
                        * (coef(l, 3 * pole + 1) * vs[1] + coef(l, 3 * pole + 2) * vs[2]);
                }
                y[l * nvr + b] = x;
            }
        }
        h.fill(0.0);
        let lo = row.first.max(rows.start);
        let hi = (row.first + row.len).min(rows.end);
        if lo < hi {
            for i in lo..hi {
                h[i - lo] = row.val[i - row.first];
            }
            rotate_full(&mut qr_u, 5, lo - rows.start, &mut h, &mut y);
        }
        add_gram(&y, nvr);
    }
    // sweep along v on Qᵀ r, the rows ordered by their first band column
    let mut cc = vec![0.0; nl * nuu * npp];
    if nuu > 0 {
        let nb = 4.min(npp);
        let n_band = npp - nb;
        let key = |row: &Row| {
            (0..row.len)
                .map(|q| (row.first + q) % npp)
                .filter(|&c| c < n_band)
                .min()
                .unwrap_or(n_band)
        };
        let mut order: Vec<usize> = (0..nvr).collect();
        order.sort_by_key(|&b| key(&vrows[b]));
        let nc_v = nl * nuu;
        let mut cyc = CyclicQr::new(npp, 5, nb, nc_v);
        let mut yv = vec![0.0; nc_v];
        for &b in &order {
            for l in 0..nl {
                for i in 0..nuu {
                    yv[l * nuu + i] = qr_u.z[i * nc_u + l * nvr + b];
                }
            }
            let row = &vrows[b];
            cyc.add_cyclic(row.first % npp, &row.val[..row.len], &mut yv);
            add_gram(&yv, nuu);
        }
        let mut x = vec![0.0; npp * nc_v];
        cyc.solve(&mut x).map_err(|j| Error::SingularSystem {
            reason: format!("the fit on the sphere has no pivot in longitude coefficient {j}"),
        })?;
        // back substitution along u: R_u cc = x for each layer and longitude
        let dmax = (0..nuu).fold(0.0_f64, |m, i| m.max(qr_u.r[i * 5].abs()));
        if let Some(i) =
            (0..nuu).find(|&i| qr_u.r[i * 5].abs() <= RANK_RTOL * dmax || qr_u.r[i * 5].is_nan())
        {
            return Err(Error::SingularSystem {
                reason: format!(
                    "the fit on the sphere has no pivot in colatitude row {}; the grid cannot \
                     carry these knots",
                    i + rows.start
                ),
            });
        }
        for l in 0..nl {
            for j in 0..npp {
                let col = |i: usize| (l * nuu + i) * npp + j;
                for i in (0..nuu).rev() {
                    let mut s = x[j * nc_v + l * nuu + i];
                    for k in 1..5.min(nuu - i) {
                        s -= qr_u.r[i * 5 + k] * cc[col(i + k)];
                    }
                    cc[col(i)] = s / qr_u.r[i * 5];
                }
            }
        }
    }
    // the optimal free parameters: minimise [1, d]ᵀ G [1, d] + Σ (prior − d)²
    for l1 in 0..nl {
        for l2 in l1 + 1..nl {
            gram[l1 * nl + l2] = gram[l2 * nl + l1];
        }
    }
    let nf = free.len();
    let mut a = vec![0.0; nf * nf];
    let mut rhs = vec![0.0; nf];
    for k in 0..nf {
        for m in 0..nf {
            a[k * nf + m] = gram[(k + 1) * nl + m + 1];
        }
        rhs[k] = -gram[(k + 1) * nl];
        if let Param::Free(Some(prior)) = par[free[k]] {
            a[k * nf + k] += 1.0;
            rhs[k] += prior;
        }
    }
    let dfree = solve_small(&mut a, &mut rhs, nf);
    let mut d = [0.0; 6];
    for (q, dq) in d.iter_mut().enumerate() {
        if let Param::Fixed(v) = par[q] {
            *dq = v;
        }
    }
    for (k, &q) in free.iter().enumerate() {
        d[q] = dfree[k];
    }
    let mut free_rows = cc[..nuu * npp].to_vec();
    for (k, &dk) in dfree.iter().enumerate() {
        let layer = &cc[(k + 1) * nuu * npp..(k + 2) * nuu * npp];
        for (o, v) in free_rows.iter_mut().zip(layer) {
            *o += dk * v;
        }
    }
    let c = sp.expand(&d, &free_rows);
    let spline = sp.spline(c.clone())?;
    let mut vals = vec![0.0; mu * mv];
    spline.eval_grid(&[grid.u, grid.v], None, &mut vals)?;
    let fp = vals
        .iter()
        .zip(grid.r)
        .map(|(s, r)| (r - s) * (r - s))
        .sum();
    Ok(Solved { c, d, fp })
}

/// `A x = b` for the small symmetric positive semi-definite `A` (`n × n`, `n ≤ 6`) by Cholesky;
/// a pivot at most `RANK_RTOL` times the largest diagonal entry leaves its unknown at zero (the
/// residual does not depend on it, as the derivative at a pole of a spline with too few
/// longitude spans).
fn solve_small(a: &mut [f64], b: &mut [f64], n: usize) -> Vec<f64> {
    let dmax = (0..n).fold(0.0_f64, |m, i| m.max(a[i * n + i]));
    let mut skip = vec![false; n];
    for k in 0..n {
        let mut dk = a[k * n + k];
        for j in 0..k {
            dk -= a[k * n + j] * a[k * n + j];
        }
        if dk <= RANK_RTOL * dmax || dk.is_nan() {
            skip[k] = true;
            for i in k..n {
                a[i * n + k] = 0.0;
            }
            continue;
        }
        let dk = dk.sqrt();
        a[k * n + k] = dk;
        for i in k + 1..n {
            let mut s = a[i * n + k];
            for j in 0..k {
                s -= a[i * n + j] * a[k * n + j];
            }
            a[i * n + k] = s / dk;
        }
    }
    let mut x = b.to_vec();
    for i in 0..n {
        if skip[i] {
            x[i] = 0.0;
            continue;
        }
        let mut s = x[i];
        for j in 0..i {
            s -= a[i * n + j] * x[j];
        }
        x[i] = s / a[i * n + i];
    }
    for i in (0..n).rev() {
        if skip[i] {
            x[i] = 0.0;
            continue;
        }
        let mut s = x[i];
        for j in i + 1..n {
            s -= a[j * n + i] * x[j];
        }
        x[i] = s / a[i * n + i];
    }
    x
}

/// Interior colatitude knots of interpolation (FITPACK `fpspgr` with `s = 0`): the grid
/// colatitudes from the second (the first with continuity at `θ = 0`) to the last but one
/// (the last with continuity at `θ = π`).
fn interpolation_knots(u: &[f64], c1: [bool; 2]) -> Vec<f64> {
    let lo = usize::from(!c1[0]);
    let hi = u.len() - usize::from(!c1[1]);
    u[lo..hi].to_vec()
}

/// The longitude knots of interpolation: every grid longitude after the first.
fn interpolation_phi(v: &[f64]) -> Vec<f64> {
    v[1..].to_vec()
}

/// The spline on the grid `u × v` of the sphere whose residual sum of squares
/// `Σ (r_ij − s(u_i, v_j))²` is `s` (`s = 0`: interpolation), with the pole conditions `poles`
/// (at `θ = 0` and `θ = π`), on the knots FITPACK `fpspgr` chooses (Dierckx 1993, §11.2;
/// SciPy's `RectSphereBivariateSpline`):
///
/// - `s = 0`: knots at the grid lines; pole values or derivatives left free are first fitted
///   by least squares on every other colatitude, then imposed on the interpolation;
/// - `s > 0`: least squares from the spline without interior knots, adding knots at the
///   middle grid line of the knot span of largest residual (as many per round as FITPACK's
///   rule asks) until the residual is at most `s`; then the weight `p` of the jumps of the
///   third derivatives for which it is `s` within `SMOOTHING_RTOL·s`.
///
/// Free pole parameters are optimal for each solve (module docs).
///
/// ```
/// use lekalo::fit::{sphere_grid_smoothing, PoleCondition, SphereGrid};
/// use lekalo::Progress;
/// let u: Vec<f64> = (1..8).map(|i| 0.4 * i as f64).collect();
/// let v: Vec<f64> = (0..10).map(|j| -3.0 + 0.6 * j as f64).collect();
/// let r: Vec<f64> = u.iter().flat_map(|a| v.iter().map(move |b| a.cos() + a.sin() * b.cos())).collect();
/// let grid = SphereGrid::new(&u, &v, &r)?;
/// let smooth = PoleCondition { continuity: true, ..PoleCondition::default() };
/// let fit = sphere_grid_smoothing(&grid, 0.0, [smooth; 2], &Progress::new())?;
/// // s = 0 interpolates, and the pole at θ = 0 has one value
/// let s = |t: f64, p: f64| fit.spline.eval(&[t, p]).unwrap()[0];
/// assert!((s(u[2], v[3]) - r[2 * v.len() + 3]).abs() < 1e-12);
/// assert!((s(0.0, -3.0) - s(0.0, 1.0)).abs() < 1e-12);
/// # Ok::<(), lekalo::Error>(())
/// ```
///
/// # Errors
/// [`Error::InvalidArgument`] for `s` negative or not
/// finite ("s should be positive"), a pole flat without continuity ("if `pole_continuity` is
/// False, so must be `pole_flat`") or a pole value not finite; [`Error::SingularSystem`] if the
/// grid cannot carry the knots; [`Error::Cancelled`] through `progress`.
pub fn sphere_grid_smoothing(
    grid: &SphereGrid<'_>,
    s: f64,
    poles: [PoleCondition; 2],
    progress: &Progress<'_>,
) -> Result<SphereFit> {
    if !(s >= 0.0 && s.is_finite()) {
        return Err(invalid(Arg::S, format!("s should be positive (s = {s})")));
    }
    for pole in &poles {
        if pole.flat && !pole.continuity {
            return Err(invalid(
                Arg::PoleFlat,
                "if pole_continuity is False, so must be pole_flat".into(),
            ));
        }
        if pole.value.is_some_and(|v| !v.is_finite()) {
            return Err(invalid(
                Arg::PoleValues,
                "a pole value must be finite".into(),
            ));
        }
    }
    let steps = Steps::new(progress, "smoothing on a grid of the sphere");
    let (u, v) = (grid.u, grid.v);
    let c1 = [poles[0].continuity, poles[1].continuity];
    let v0 = v[0];
    let nfull = interpolation_knots(u, c1).len() + 8;
    let interpolate = || -> Result<SphereFit> {
        let phi = interpolation_phi(v);
        let sp = SphereSpace::new(&interpolation_knots(u, c1), v0, &phi, c1)?;
        let mut par = params(&sp, &poles, true);
        if par.iter().any(|q| matches!(q, Param::Free(_))) {
            // the free pole parameters from least squares on every other colatitude
            let coarse: Vec<f64> = (2..u.len().saturating_sub(2))
                .step_by(2)
                .map(|i| u[i])
                .collect();
            let pre = SphereSpace::new(&coarse, v0, &phi, c1)?;
            let pre_par = params(&pre, &poles, true);
            let fit = solve(grid, &pre, &pre_par, f64::INFINITY)?;
            let d = fit.d;
            for (q, x) in par.iter_mut().enumerate() {
                if matches!(x, Param::Free(_)) {
                    *x = Param::Fixed(d[q]);
                }
            }
        }
        let fit = solve(grid, &sp, &par, f64::INFINITY)?;
        result(&sp, fit, None)
    };
    if s == 0.0 {
        steps.tick()?;
        return interpolate();
    }
    let acc = SMOOTHING_RTOL * s;
    let mut ku = Axis::new(
        u,
        usize::from(!c1[0]),
        u.len() - usize::from(!c1[1]),
        0.0,
        PI,
    );
    let mut kv = Axis::new(v, 1, v.len(), v0, v0 + TWO_PI);
    let (mut nplus_u, mut nplus_v) = (0usize, 0usize);
    let (mut reduce_u, mut reduce_v) = (0.0, 0.0);
    let mut last_dir = 0i8;
    let mut fp_old = 0.0;
    let mut fp0 = None;
    for _ in 0..u.len() + v.len() {
        steps.tick()?;
        let first_round = fp0.is_none();
        let sp = SphereSpace::new(&ku.interior, v0, &kv.interior, c1)?;
        let mut par = params(&sp, &poles, false);
        if first_round {
            // the spline without interior knots: flat at the poles (FITPACK)
            for p in 0..2 {
                par[3 * p + 1] = Param::Fixed(0.0);
                par[3 * p + 2] = Param::Fixed(0.0);
            }
        }
        let fit = solve(grid, &sp, &par, f64::INFINITY)?;
        let fp = fit.fp;
        let fp0v = *fp0.get_or_insert(fp);
        let fpms = fp - s;
        if accepts_least_squares(fpms, acc) {
            return result(&sp, fit, None);
        }
        if fpms < 0.0 {
            if first_round {
                return result(&sp, fit, None);
            }
            // the weight of the jumps on these knots
            let solve_p = |p: f64| -> Result<(Vec<f64>, f64)> {
                let f = solve(grid, &sp, &par, p)?;
                Ok((f.c, f.fp))
            };
            return match smooth_weight(&solve_p, 1.0, s, fp0v, fp, &steps)? {
                Some((p, fp, c)) => {
                    let mut out = result(&sp, Solved { c, d: [0.0; 6], fp }, None)?;
                    out.p = Some(p);
                    Ok(out)
                }
                None => result(&sp, fit, None),
            };
        }
        if ku.interior.len() + 8 >= nfull && kv.interior.len() + 1 >= v.len() {
            return interpolate();
        }
        // the residual per knot span of each direction
        let spline = sp.spline(fit.c.clone())?;
        let mut vals = vec![0.0; u.len() * v.len()];
        spline.eval_grid(&[u, v], None, &mut vals)?;
        let mv = v.len();
        let mut ru = vec![0.0; u.len()];
        let mut rv = vec![0.0; mv];
        for (k, (sv, r)) in vals.iter().zip(grid.r).enumerate() {
            let e = (r - sv) * (r - sv);
            ru[k / mv] += e;
            rv[k % mv] += e;
        }
        ku.span_sums(&ru);
        kv.span_sums(&rv);
        // FITPACK's choice of direction and number of knots
        match last_dir {
            -1 => reduce_u = fp_old - fp,
            1 => reduce_v = fp_old - fp,
            _ => {}
        }
        fp_old = fp;
        let nplu = if ku.interior.is_empty() {
            1
        } else {
            next_nplus(nplus_u, fpms, reduce_u, acc)
        };
        let nplv = if kv.interior.is_empty() {
            3
        } else {
            next_nplus(nplus_v, fpms, reduce_v, acc)
        };
        let u_full = ku.full() || ku.interior.len() + 8 >= nfull;
        let v_full = kv.full();
        // the first addition goes along v (three knots), as FITPACK's
        let along_u =
            last_dir != 0 && !u_full && (v_full || nplu < nplv || (nplu == nplv && last_dir >= 0));
        if along_u {
            last_dir = -1;
            nplus_u = nplu;
            for _ in 0..nplu {
                if !ku.add_knot() || ku.interior.len() + 8 >= nfull {
                    break;
                }
            }
        } else if !v_full {
            last_dir = 1;
            nplus_v = nplv;
            for _ in 0..nplv {
                if !kv.add_knot() {
                    break;
                }
            }
        } else {
            return interpolate();
        }
    }
    interpolate()
}

fn result(sp: &SphereSpace, fit: Solved, p: Option<f64>) -> Result<SphereFit> {
    let unknowns = sp.free_rows().len() * sp.npp + 2;
    Ok(SphereFit {
        spline: sp.spline(fit.c)?,
        fp: fit.fp,
        rank: unknowns,
        unknowns,
        p,
        limit: None,
    })
}

/// One direction of the grid and its interior knots, as FITPACK's `fpknot` keeps them: the
/// coordinates `x[lo..hi]` that may become knots, the number of them strictly inside each
/// knot span and the residual per span.
struct Axis<'a> {
    x: &'a [f64],
    lo: usize,
    hi: usize,
    start: f64,
    end: f64,
    interior: Vec<f64>,
    span_residual: Vec<f64>,
    stuck: bool,
}

impl<'a> Axis<'a> {
    fn new(x: &'a [f64], lo: usize, hi: usize, start: f64, end: f64) -> Self {
        Axis {
            x,
            lo,
            hi,
            start,
            end,
            interior: Vec::new(),
            span_residual: vec![0.0],
            stuck: false,
        }
    }

    fn full(&self) -> bool {
        self.stuck || self.interior.len() >= self.hi.saturating_sub(self.lo)
    }

    /// The residual per knot span from the residual per grid line `r`; a line on a knot gives
    /// half to each side (FITPACK `fpgrsp`).
    fn span_sums(&mut self, r: &[f64]) {
        let mut sums = vec![0.0; self.interior.len() + 1];
        for (&x, &e) in self.x.iter().zip(r) {
            let span = self.interior.partition_point(|&t| t <= x);
            if span > 0 && self.interior[span - 1] == x {
                sums[span] += 0.5 * e;
                sums[span - 1] += 0.5 * e;
            } else {
                sums[span] += e;
            }
        }
        self.span_residual = sums;
    }

    /// Adds one knot (FITPACK `fpknot`): at the middle candidate coordinate strictly inside
    /// the span of largest residual that holds one. `false` if none does.
    fn add_knot(&mut self) -> bool {
        let cand = &self.x[self.lo..self.hi];
        let mut best: Option<(usize, f64)> = None;
        for (j, &f) in self.span_residual.iter().enumerate() {
            let a = if j == 0 {
                self.start
            } else {
                self.interior[j - 1]
            };
            let b = self.interior.get(j).copied().unwrap_or(self.end);
            let inside = cand.iter().filter(|&&x| x > a && x < b).count();
            if inside > 0 && best.is_none_or(|(_, m)| f > m) {
                best = Some((j, f));
            }
        }
        let Some((j, f)) = best else {
            self.stuck = true;
            return false;
        };
        let a = if j == 0 {
            self.start
        } else {
            self.interior[j - 1]
        };
        let b = self.interior.get(j).copied().unwrap_or(self.end);
        let inside: Vec<f64> = cand.iter().copied().filter(|&x| x > a && x < b).collect();
        let knot = inside[inside.len() / 2];
        self.interior.insert(j, knot);
        self.span_residual[j] = 0.5 * f;
        self.span_residual.insert(j + 1, 0.5 * f);
        true
    }
}
