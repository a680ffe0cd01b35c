//! Fits of scattered data on the sphere: least squares on given knots (FITPACK `sphere` with
//! `iopt = -1`, SciPy's `LSQSphereBivariateSpline`) and the smoothing condition
//! `Σ (w_k (r_k − s(θ_k, φ_k)))² ≤ s` with knots chosen as FITPACK `fpsphe` does (SciPy's
//! `SmoothSphereBivariateSpline`). `docs/theory/sphere.md#scattered`.
//!
//! The unknowns are the free coefficients of [`SphereSpace`] in the order
//! `(v₀, a₀, b₀, rows 2 … nθ−3 of n_φ each, v₁, a₁, b₁)`: every data row then touches at most
//! five consecutive θ rows, a band of width `≈ 4 n_φ + 3`, reduced to a triangle by Givens
//! rotations as the rows arrive (Dierckx 1993, §11.1.2; `O(m·n_φ²)` for `m` points).

use super::space::{SphereSpace, PI, TWO_PI};
use super::SphereFit;
use crate::basis::{basis_funs_into, BasisScratch};
use crate::error::{Error, Result};
use crate::fit::banded::BandedQr;
use crate::fit::{jump_rows, smooth_weight, Steps, SMOOTHING_RTOL};
use crate::knots::span_in;
use crate::numeric::progress::Progress;
use crate::tensor::{rotate_full, solve_triangle, RankDeficiency};
use crate::{Arg, What};

/// Scattered data on the sphere, checked: colatitudes `theta` in `[0, π]`, longitudes `phi` in
/// `[0, 2π]`, values `r`, weights `w ≥ 0` multiplying the residual (FITPACK's; 1 when `None`).
#[derive(Debug, Clone, Copy)]
pub struct SphereData<'a> {
    theta: &'a [f64],
    phi: &'a [f64],
    r: &'a [f64],
    w: Option<&'a [f64]>,
}

pub(super) fn invalid(what: impl Into<What>, reason: String) -> Error {
    Error::InvalidArgument {
        what: what.into(),
        reason,
    }
}

impl<'a> SphereData<'a> {
    /// The data, checked with SciPy's words.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] naming `w` ("w should be positive": a weight negative or not
    /// finite), `theta` ("theta should be between [0, pi]"), `phi` ("phi should be between
    /// [0, 2pi]"), every weight 0; [`Error::LengthMismatch`] for lengths that differ;
    /// [`Error::NonFinite`] for a value of `r` that is NaN or infinite; [`Error::InvalidArgument`]
    /// naming `r` for values so large that the fit's residual sum of squares overflows
    /// ([`check_scale`]); [`Error::TooFew`] for fewer than two points (FITPACK's `m >= 2`).
    pub fn new(
        theta: &'a [f64],
        phi: &'a [f64],
        r: &'a [f64],
        w: Option<&'a [f64]>,
    ) -> Result<Self> {
        if let Some(w) = w {
            if let Some(i) = w.iter().position(|v| !(*v >= 0.0 && v.is_finite())) {
                return Err(invalid(
                    What::of(Arg::DataWeights, "w"),
                    format!("w should be positive (w[{i}] = {})", w[i]),
                ));
            }
        }
        if let Some(i) = theta.iter().position(|v| !(0.0..=PI).contains(v)) {
            return Err(invalid(
                "theta",
                format!(
                    "theta should be between [0, pi] (theta[{i}] = {})",
                    theta[i]
                ),
            ));
        }
        if let Some(i) = phi.iter().position(|v| !(0.0..=TWO_PI).contains(v)) {
            return Err(invalid(
                "phi",
                format!("phi should be between [0, 2pi] (phi[{i}] = {})", phi[i]),
            ));
        }
        for (what, len) in [
            ("phi (one per theta)", phi.len()),
            ("r (one per theta)", r.len()),
        ]
        .into_iter()
        .map(|(what, len)| (What::text(what), len))
        .chain(w.map(|w| (What::of(Arg::DataWeights, "w (one per theta)"), w.len())))
        {
            if len != theta.len() {
                return Err(Error::LengthMismatch {
                    what,
                    expected: theta.len(),
                    got: len,
                });
            }
        }
        if let Some(i) = r.iter().position(|v| !v.is_finite()) {
            return Err(Error::NonFinite {
                what: "r".into(),
                index: i,
                value: r[i],
            });
        }
        check_scale(r, w)?;
        // FITPACK's `m >= 2`: no data, or one point, made a spline with fp = 0 and no error
        if theta.len() < 2 {
            return Err(Error::TooFew {
                what: "data points on the sphere (theta, phi, r)".into(),
                min: 2,
                got: theta.len(),
            });
        }
        if w.is_some_and(|w| w.iter().all(|v| *v == 0.0)) {
            return Err(invalid(
                "w",
                "every weight is 0, so no point is fitted; give at least one positive weight"
                    .to_string(),
            ));
        }
        Ok(SphereData { theta, phi, r, w })
    }

    fn weight(&self, k: usize) -> f64 {
        self.w.map_or(1.0, |w| w[k])
    }
}

/// How far the residuals of a fit may exceed the largest weighted value `|w·r|` of its data
/// before their sum of squares must still be finite: a spline through values of one size
/// overshoots them by a small factor (its Bernstein-form bound), not by four.
pub(super) const RESIDUAL_HEADROOM: f64 = 4.0;

/// The values `r` (weighted by `w`) checked against the fit's arithmetic: its rounds compare
/// residual sums of squares, up to `m·(RESIDUAL_HEADROOM·max|w·r|)²` for `m` values, and a sum
/// that overflows makes every residual infinite and the spline NaN. Values near the largest
/// double (`r * 1e300`) are refused naming `r` and the fix, a rescaling, instead of failing
/// later on the spline's coefficients.
///
/// # Errors
/// [`Error::InvalidArgument`] naming `r` and its largest value.
pub(super) fn check_scale(r: &[f64], w: Option<&[f64]>) -> Result<()> {
    let (i, big) = r
        .iter()
        .enumerate()
        .map(|(k, v)| (k, (v * w.map_or(1.0, |w| w[k])).abs()))
        .fold((0, 0.0_f64), |a, b| if b.1 > a.1 { b } else { a });
    let bound = (f64::MAX / r.len().max(1) as f64).sqrt() / RESIDUAL_HEADROOM;
    if big > bound {
        return Err(invalid(
            "r",
            format!(
                "r[{i}] = {:e}{} is too large for the fit, whose residual sum of squares \
                 overflows above |w·r| = {bound:.3e} for {} values; divide r by a power of ten \
                 (and s by its square), fit, and multiply the spline by it",
                r[i],
                if w.is_some() {
                    " (times its weight)"
                } else {
                    ""
                },
                r.len()
            ),
        ));
    }
    Ok(())
}

/// `eps` in `(0, 1)`, SciPy's words.
pub(super) fn check_eps(eps: f64) -> Result<()> {
    if eps > 0.0 && eps < 1.0 {
        Ok(())
    } else {
        Err(invalid(
            What::of(Arg::Eps, "eps"),
            format!("eps should be between (0, 1) (eps = {eps}); FITPACK's default is 1e-16"),
        ))
    }
}

/// Interior knots strictly increasing inside `(lo, hi)`, with SciPy's message `words`.
pub(super) fn check_interior(what: What, t: &[f64], lo: f64, hi: f64, words: &str) -> Result<()> {
    if let Some(i) = t.iter().position(|v| !(*v > lo && *v < hi)) {
        return Err(invalid(what, format!("{words} ({what}[{i}] = {})", t[i])));
    }
    if let Some(i) = t.windows(2).position(|p| p[1] <= p[0]) {
        return Err(invalid(
            what,
            format!(
                "the knots must increase strictly ({what}[{i}] = {}, {what}[{}] = {})",
                t[i],
                i + 1,
                t[i + 1]
            ),
        ));
    }
    Ok(())
}

/// The unknowns of a scattered fit: `npar[p]` parameters at pole `p` (1: its value; 3: value
/// and derivative), then the free rows.
struct Columns {
    npar: [usize; 2],
    n: usize,
}

impl Columns {
    fn new(sp: &SphereSpace, flat: bool) -> Self {
        let npar = [0, 1].map(|p| if sp.c1[p] && !flat { 3 } else { 1 });
        let n = npar[0] + sp.free_rows().len() * sp.npp + npar[1];
        Columns { npar, n }
    }

    fn pole_base(&self, p: usize) -> usize {
        if p == 0 {
            0
        } else {
            self.n - self.npar[1]
        }
    }

    /// Calls `f(column, factor)` for the unknowns of `c_{i,j}`.
    fn entries(&self, sp: &SphereSpace, i: usize, j: usize, mut f: impl FnMut(usize, f64)) {
        match sp.pole_row(i, j) {
            Some((p, g)) => {
                let base = self.pole_base(p);
                f(base, g[0]);
                if self.npar[p] == 3 {
                    f(base + 1, g[1]);
                    f(base + 2, g[2]);
                }
            }
            None => f(self.npar[0] + (i - sp.free_rows().start) * sp.npp + j, 1.0),
        }
    }

    /// The first and last unknown of θ row `i`.
    fn row_range(&self, sp: &SphereSpace, i: usize) -> (usize, usize) {
        let (mut lo, mut hi) = (usize::MAX, 0);
        for j in [0, sp.npp - 1] {
            self.entries(sp, i, j, |c, _| {
                lo = lo.min(c);
                hi = hi.max(c);
            });
        }
        (lo, hi)
    }

    /// The band: the widest span of unknowns over five consecutive θ rows (a data row touches
    /// four, a row of θ jumps five).
    fn band(&self, sp: &SphereSpace) -> usize {
        let ranges: Vec<(usize, usize)> = (0..sp.nt).map(|i| self.row_range(sp, i)).collect();
        ranges
            .windows(5.min(sp.nt))
            .map(|w| {
                let lo = w.iter().map(|r| r.0).min().unwrap_or(0);
                let hi = w.iter().map(|r| r.1).max().unwrap_or(0);
                hi + 1 - lo
            })
            .max()
            .unwrap_or(self.n)
            .min(self.n)
    }

    /// The tensor coefficients of the unknowns `x`.
    fn expand(&self, sp: &SphereSpace, x: &[f64]) -> Vec<f64> {
        let mut d = [0.0; 6];
        for p in 0..2 {
            let base = self.pole_base(p);
            d[3 * p..3 * p + self.npar[p]].copy_from_slice(&x[base..base + self.npar[p]]);
        }
        sp.expand(&d, &x[self.npar[0]..self.n - self.npar[1]])
    }
}

/// The data rows of one space rotated into a triangle, with what the residuals need.
struct Observation {
    cols: Columns,
    bw: usize,
    qr: BandedQr,
    /// Per point: the θ and φ spans and the four basis values in each direction.
    bases: Vec<(usize, usize, [f64; 4], [f64; 4])>,
}

impl Observation {
    fn new(sp: &SphereSpace, data: &SphereData<'_>, flat: bool) -> Result<Self> {
        let cols = Columns::new(sp, flat);
        let bw = cols.band(sp);
        let size = cols.n.saturating_mul(bw);
        if size > crate::MAX_SCALARS {
            return Err(Error::TooLarge {
                what: "triangle of the fit on the sphere (unknowns × band width)".into(),
                size,
                max: crate::MAX_SCALARS,
            });
        }
        let m = data.theta.len();
        let mut scratch = BasisScratch::new(3);
        let mut bases = Vec::with_capacity(m);
        let mut order = Vec::with_capacity(m);
        for k in 0..m {
            let (th, ph) = (data.theta[k], data.phi[k]);
            let lt = span_in(&sp.tt, 3, th);
            let lp = span_in(&sp.tp, 3, ph);
            let (mut bt, mut bp) = ([0.0; 4], [0.0; 4]);
            basis_funs_into(&sp.tt, 3, lt, th, &mut scratch, &mut bt);
            basis_funs_into(&sp.tp, 3, lp, ph, &mut scratch, &mut bp);
            bases.push((lt, lp, bt, bp));
            order.push((cols.row_range(sp, lt - 3).0, k));
        }
        order.sort_by_key(|&(first, _)| first);
        let mut qr = BandedQr::try_new(cols.n, bw, 1).ok_or_else(|| Error::InvalidArgument {
            what: "knots of the fit on the sphere (tt, tp)".into(),
            reason: format!(
                "their {} unknowns need a triangle of {size} numbers ({:.1} GB), more memory \
                 than the system gives; give fewer knots",
                cols.n,
                size as f64 * 8e-9
            ),
        })?;
        let mut h = vec![0.0; bw];
        for &(first, k) in &order {
            let w = data.weight(k);
            if w == 0.0 {
                continue;
            }
            let (lt, lp, bt, bp) = bases[k];
            let len = bw.min(cols.n - first);
            h[..len].fill(0.0);
            for (a, &va) in bt.iter().enumerate() {
                for (b, &vb) in bp.iter().enumerate() {
                    let j = (lp - 3 + b) % sp.npp;
                    cols.entries(sp, lt - 3 + a, j, |c, f| h[c - first] += f * va * vb * w);
                }
            }
            let mut y = [data.r[k] * w];
            qr.add_row(first, &mut h[..len], &mut y);
        }
        Ok(Observation {
            cols,
            bw,
            qr,
            bases,
        })
    }

    /// The weighted residual `Σ (w_k (r_k − s_k))²` of the tensor coefficients `c`, and its
    /// parts per θ span and per φ span with their first moments (FITPACK's `fpint`, `coord`).
    fn residuals(&self, sp: &SphereSpace, data: &SphereData<'_>, c: &[f64]) -> Residuals {
        let np4 = sp.npp + 3;
        let mut out = Residuals {
            fp: 0.0,
            theta: vec![(0.0, 0.0); sp.nt - 3],
            phi: vec![(0.0, 0.0); sp.npp],
        };
        for (k, &(lt, lp, bt, bp)) in self.bases.iter().enumerate() {
            let mut s = 0.0;
            for (a, &va) in bt.iter().enumerate() {
                let row = &c[(lt - 3 + a) * np4 + lp - 3..];
                s += va * bp.iter().zip(row).map(|(b, c)| b * c).sum::<f64>();
            }
            let e = (data.weight(k) * (data.r[k] - s)).powi(2);
            out.fp += e;
            let t = &mut out.theta[lt - 3];
            *t = (t.0 + e, t.1 + e * data.theta[k]);
            let f = &mut out.phi[lp - 3];
            *f = (f.0 + e, f.1 + e * data.phi[k]);
        }
        out
    }

    /// The triangle with the rows of the jumps of the third derivatives across the interior
    /// knots of each direction, divided by `p` (Dierckx §11.1.3: `s` constant along each θ
    /// row, a cubic along each φ column in the limit `p → 0`).
    fn with_jumps(&self, sp: &SphereSpace, p: f64) -> BandedQr {
        let mut qr = self.qr.clone();
        let (bw, n, npp) = (self.bw, self.cols.n, sp.npp);
        let mut h = vec![0.0; bw];
        let mut rotate = |qr: &mut BandedQr, entries: &mut Vec<(usize, f64)>| {
            let Some(first) = entries.iter().map(|e| e.0).min() else {
                return;
            };
            h.fill(0.0);
            for &(c, v) in entries.iter() {
                h[c - first] += v / p;
            }
            entries.clear();
            if first < n {
                rotate_full(qr, bw, first, &mut h, &mut [0.0]);
            }
        };
        let mut entries = Vec::new();
        if npp > 1 {
            let jp = jump_rows(&sp.tp, 3).rows;
            for (r, row) in jp.chunks_exact(5).enumerate() {
                for i in 1..sp.nt - 1 {
                    for (q, &v) in row.iter().enumerate() {
                        self.cols
                            .entries(sp, i, (r + q) % npp, |c, f| entries.push((c, f * v)));
                    }
                    rotate(&mut qr, &mut entries);
                }
            }
        }
        if sp.nt > 4 {
            let jt = jump_rows(&sp.tt, 3).rows;
            for (r, row) in jt.chunks_exact(5).enumerate() {
                for j in 0..npp {
                    for (q, &v) in row.iter().enumerate() {
                        self.cols
                            .entries(sp, r + q, j, |c, f| entries.push((c, f * v)));
                    }
                    rotate(&mut qr, &mut entries);
                }
            }
        }
        qr
    }

    /// The tensor coefficients and rank of the triangle `qr`: FITPACK's minimal-norm solution
    /// when a pivot is at most `√eps` times the largest.
    fn solve(&self, sp: &SphereSpace, qr: BandedQr, eps: f64) -> Result<(Vec<f64>, usize)> {
        let (x, rank) =
            solve_triangle(qr, self.bw, RankDeficiency::MinimumNorm { eps }).map_err(|i| {
                Error::SingularSystem {
                    reason: format!("the fit on the sphere has no pivot in unknown {i}"),
                }
            })?;
        Ok((self.cols.expand(sp, &x), rank))
    }
}

struct Residuals {
    fp: f64,
    theta: Vec<(f64, f64)>,
    phi: Vec<(f64, f64)>,
}

fn finish(sp: &SphereSpace, c: Vec<f64>, fp: f64, rank: usize, n: usize) -> Result<SphereFit> {
    Ok(SphereFit {
        spline: sp.spline(c)?,
        fp,
        rank,
        unknowns: n,
        p: None,
        limit: None,
    })
}

/// The weighted least-squares bicubic spline on the sphere with the interior knots
/// `theta_knots` (in `(0, π)`) and `phi_knots` (in `(0, 2π)`), one value at each pole and
/// continuous first derivatives across them (FITPACK `sphere`, `iopt = −1`; Dierckx §11.1).
/// Minimises `Σ (w_k (r_k − s(θ_k, φ_k)))²`; a numerically rank-deficient system gets the
/// solution of least norm with pivots at most `√eps` times the largest dropped (FITPACK
/// `fprank`). `O(m·n_φ²)` time for `m` points and `n_φ` φ spans.
///
/// ```
/// use lekalo::fit::{sphere_least_squares, SphereData};
/// // points on a spiral, the values of z² (a smooth function of the point)
/// let (theta, phi): (Vec<f64>, Vec<f64>) = (1..400)
///     .map(|k| ((1.0 - k as f64 / 200.0).acos(), (2.4 * k as f64) % std::f64::consts::TAU))
///     .unzip();
/// let r: Vec<f64> = theta.iter().map(|t| t.cos().powi(2)).collect();
/// let data = SphereData::new(&theta, &phi, &r, None)?;
/// let fit = sphere_least_squares(&data, &[0.8, 1.6, 2.4], &[1.5, 3.0, 4.5], 1e-16)?;
/// let s = |t: f64, p: f64| fit.spline.eval(&[t, p]).unwrap()[0];
/// assert!((s(0.5, 1.0) - 0.5f64.cos().powi(2)).abs() < 1e-2);
/// // one value at each pole, and periodic in φ
/// assert!((s(0.0, 0.0) - s(0.0, 3.0)).abs() < 1e-12);
/// assert!((s(1.0, 0.0) - s(1.0, std::f64::consts::TAU)).abs() < 1e-12);
/// # Ok::<(), lekalo::Error>(())
/// ```
///
/// # Errors
/// [`Error::InvalidArgument`] for knots outside their
/// interval ("tt should be between (0, pi)", "tp should be between (0, 2pi)") or not
/// increasing, `eps` outside `(0, 1)`, or knots whose triangle is more memory than the
/// system gives; [`Error::TooLarge`] for a triangle beyond [`MAX_SCALARS`](crate::MAX_SCALARS).
pub fn sphere_least_squares(
    data: &SphereData<'_>,
    theta_knots: &[f64],
    phi_knots: &[f64],
    eps: f64,
) -> Result<SphereFit> {
    check_interior(
        What::of(Arg::ColatitudeKnots, "tt"),
        theta_knots,
        0.0,
        PI,
        "tt should be between (0, pi)",
    )?;
    check_interior(
        What::of(Arg::LongitudeKnots, "tp"),
        phi_knots,
        0.0,
        TWO_PI,
        "tp should be between (0, 2pi)",
    )?;
    check_eps(eps)?;
    let sp = SphereSpace::new(theta_knots, 0.0, phi_knots, [true, true])?;
    let obs = Observation::new(&sp, data, false)?;
    let (c, rank) = obs.solve(&sp, obs.qr.clone(), eps)?;
    let fp = obs.residuals(&sp, data, &c).fp;
    finish(&sp, c, fp, rank, obs.cols.n)
}

/// The knots of FITPACK `fpsphe`'s rounds: θ knots, and the φ knots of the half period
/// `(0, π]` (the φ knots are symmetric under `φ ↦ φ + π`).
struct Knots {
    theta: Vec<f64>,
    half: Vec<f64>,
}

impl Knots {
    fn phi(&self) -> Vec<f64> {
        let mut t = self.half.clone();
        t.extend(self.half.iter().filter(|&&v| v < PI).map(|v| v + PI));
        t
    }

    /// Adds one knot where the residual is largest (FITPACK `fpsphe`: the span of largest
    /// residual among those allowed, at the residual-weighted mean of its coordinates, unless
    /// that point is more than ten times nearer one end of the span than the other; a φ knot
    /// goes in with its image `φ ± π`). `false` if no span can take one.
    fn add(&mut self, res: &mut Residuals, theta_ok: bool, phi_ok: bool) -> bool {
        loop {
            let best_t = theta_ok.then(|| argmax(&res.theta)).flatten();
            let best_p = phi_ok.then(|| argmax(&res.phi)).flatten();
            let pick_theta = match (best_t, best_p) {
                (None, None) => return false,
                (Some(_), None) => true,
                (None, Some(_)) => false,
                (Some(a), Some(b)) => res.theta[a].0 >= res.phi[b].0,
            };
            if pick_theta {
                let Some(l) = best_t else { return false };
                let (f, c) = res.theta[l];
                res.theta[l].0 = 0.0;
                let arg = c / f;
                let lo = if l == 0 { 0.0 } else { self.theta[l - 1] };
                let hi = self.theta.get(l).copied().unwrap_or(PI);
                if accept(lo, arg, hi) {
                    self.theta.insert(l, arg);
                    return true;
                }
            } else {
                let Some(l) = best_p else { return false };
                let (f, c) = res.phi[l];
                res.phi[l].0 = 0.0;
                let mut arg = c / f;
                if arg >= PI {
                    arg -= PI;
                }
                let at = self.half.partition_point(|&v| v < arg);
                let lo = if at == 0 { 0.0 } else { self.half[at - 1] };
                let hi = self.half.get(at).copied().unwrap_or(PI);
                if accept(lo, arg, hi) {
                    self.half.insert(at, arg);
                    return true;
                }
            }
        }
    }
}

fn argmax(v: &[(f64, f64)]) -> Option<usize> {
    let mut best = None;
    let mut max = 0.0;
    for (i, &(f, _)) in v.iter().enumerate() {
        if f > max {
            max = f;
            best = Some(i);
        }
    }
    best
}

/// FITPACK's test of a new knot `arg` in `(lo, hi)`: neither distance above ten times the
/// other.
fn accept(lo: f64, arg: f64, hi: f64) -> bool {
    let (a, b) = (hi - arg, arg - lo);
    !(a > 10.0 * b || b > 10.0 * a)
}

/// The largest knot count in either direction, end knots included, for `m` points: FITPACK's
/// suggestion `8 + √(m/2)`.
#[must_use]
pub fn sphere_max_knots(m: usize) -> usize {
    // m is a point count, far below 2⁵²
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    let extra = ((m as f64) / 2.0).sqrt().floor() as usize;
    8 + extra
}

/// The bicubic spline on the sphere with FITPACK `fpsphe`'s knots whose weighted residual
/// `Σ (w_k (r_k − s(θ_k, φ_k)))²` is `s` (Dierckx §11.1.3; SciPy's
/// `SmoothSphereBivariateSpline`):
///
/// 1. the least-squares function `c₁ f₁(θ) + c₂ (1 − f₁(θ))`, constant in φ and flat at the
///    poles, if its residual is at most `s`;
/// 2. otherwise least-squares splines (value and derivative free at each pole) on knots
///    added one at a time where the residual is largest, from `θ = π/2` and
///    `φ = π/2, π, 3π/2`, until the residual is at most `s`;
/// 3. then the weight `p` of the jumps of the third derivatives (the smoothest spline at
///    `p → 0`) for which the residual is `s` within `SMOOTHING_RTOL·s`, by FITPACK's rational
///    iteration.
///
/// At most [`sphere_max_knots`] knots per direction; the result's `limit` says when the rounds
/// stopped above `s` ("max-knots", "too-many-unknowns" when the unknowns outnumber the points,
/// "no-span" when no span can take a knot), and is then the least-squares spline of the last
/// knots.
///
/// # Errors
/// [`Error::InvalidArgument`] for `s` negative or not
/// finite ("s should be positive") or `eps` outside `(0, 1)`; [`Error::Cancelled`] through
/// `progress`.
pub fn sphere_smoothing(
    data: &SphereData<'_>,
    s: f64,
    eps: f64,
    progress: &Progress<'_>,
) -> Result<SphereFit> {
    if !(s >= 0.0 && s.is_finite()) {
        return Err(invalid(Arg::S, format!("s should be positive (s = {s})")));
    }
    check_eps(eps)?;
    let steps = Steps::new(progress, "smoothing on the sphere");
    let m = data.theta.len();
    let acc = SMOOTHING_RTOL * s;
    let nest = sphere_max_knots(m);
    // 1. the polynomial: no interior knots, one φ span, flat poles
    let sp0 = SphereSpace::new(&[], 0.0, &[], [true, true])?;
    let obs0 = Observation::new(&sp0, data, true)?;
    let (c0, rank0) = obs0.solve(&sp0, obs0.qr.clone(), eps)?;
    let sup = obs0.residuals(&sp0, data, &c0).fp;
    if sup - s < acc {
        return finish(&sp0, c0, sup, rank0, obs0.cols.n);
    }
    let mut knots = Knots {
        theta: vec![PI / 2.0],
        half: vec![PI / 2.0, PI],
    };
    let mut limit = None;
    if nest < 11 {
        limit = Some("max-knots");
    }
    // 2. least squares on more and more knots
    let mut last = None;
    for _ in 0..m.max(1) {
        steps.tick()?;
        let sp = SphereSpace::new(&knots.theta, 0.0, &knots.phi(), [true, true])?;
        let obs = Observation::new(&sp, data, false)?;
        let (c, rank) = obs.solve(&sp, obs.qr.clone(), eps)?;
        let mut res = obs.residuals(&sp, data, &c);
        let fp = res.fp;
        let done = (fp - s).abs() <= acc;
        let below = fp < s;
        let n = obs.cols.n;
        last = Some((sp, obs, c, fp, rank));
        if done || below || limit.is_some() {
            break;
        }
        if n > m {
            limit = Some("too-many-unknowns");
            break;
        }
        let nt = knots.theta.len() + 8;
        let np = knots.phi().len() + 8;
        if !knots.add(&mut res, nt < nest, np + 2 <= nest) {
            limit = Some(if nt >= nest && np + 2 > nest {
                "max-knots"
            } else {
                "no-span"
            });
            break;
        }
    }
    let Some((sp, obs, c, fp, rank)) = last else {
        return finish(&sp0, c0, sup, rank0, obs0.cols.n);
    };
    let n = obs.cols.n;
    if (fp - s).abs() <= acc || fp > s {
        let mut fit = finish(&sp, c, fp, rank, n)?;
        fit.limit = limit.filter(|_| fp > s);
        return Ok(fit);
    }
    // 3. the weight of the jumps
    let trace: f64 = (0..n).map(|i| obs.qr.r[i * obs.bw]).sum();
    let rank_of = std::cell::Cell::new(rank);
    let solve = |p: f64| -> Result<(Vec<f64>, f64)> {
        let (c, r) = obs.solve(&sp, obs.with_jumps(&sp, p), eps)?;
        rank_of.set(r);
        let fp = obs.residuals(&sp, data, &c).fp;
        Ok((c, fp))
    };
    match smooth_weight(&solve, n as f64 / trace, s, sup, fp, &steps)? {
        Some((p, fp, c)) => {
            let mut fit = finish(&sp, c, fp, rank_of.get(), n)?;
            fit.p = Some(p);
            Ok(fit)
        }
        None => finish(&sp, c, fp, rank, n),
    }
}
