//! Step 3 of [`smoothing_condition`](super::smoothing_condition): on the final knots, the
//! smoothing weight `p` of the jump rows (FITPACK `fpdisc`) found by rational interpolation
//! (FITPACK `fprati`; `docs/theory/fitting.md#smoothing-condition`).

use super::lsq_pass::{back_substitute, Observations};
use super::SMOOTHING_RTOL;
use crate::error::{Error, Result};
use crate::fit::banded::BandedQr;
use crate::fit::progress::Steps;

/// Iterations of the smoothing weight `p` on the final knots (FITPACK's `maxit`, 20 in SciPy).
pub(super) const MAX_P_ITERATIONS: usize = 20;
/// Step 3 of [`smoothing_condition`](super::smoothing_condition) on the knots `t` with the data's least-squares triangle
/// `qr`: the coefficients whose residual is `s` within [`SMOOTHING_RTOL`] and never above, and
/// the jump weight λ; the least-squares coefficients and no λ when no weight reaches `s` from
/// below. `fp0` and `fp_inf` are the residuals of the polynomial (`p = 0`) and of the
/// least-squares spline (`p = ∞`). Each weight tried is a step of `steps`.
#[allow(clippy::too_many_arguments)]
pub(in crate::fit) fn smooth_on(
    obs: &Observations,
    k: usize,
    t: &[f64],
    qr: &BandedQr,
    s: f64,
    fp0: f64,
    fp_inf: f64,
    steps: &Steps<'_, '_>,
) -> Result<(Vec<f64>, Option<f64>)> {
    let pen = jump_rows(t, k);
    // the triangle of [R; B/p] from scratch in column order (R's row j, then the penalty row
    // starting at column j): O(n·k²) per p, no pass over the data
    let (n, k1, k2, dim) = (qr.n(), k + 1, k + 2, obs.dim);
    let n8 = pen.rows.len() / k2;
    let solve = |p: f64| -> Result<(Vec<f64>, f64)> {
        let mut g = BandedQr::new(n, k2, dim);
        let mut h = vec![0.0; k2];
        let mut y = vec![0.0; dim];
        for j in 0..n {
            let len = k1.min(n - j);
            h[..len].copy_from_slice(&qr.r[j * k1..j * k1 + len]);
            y.copy_from_slice(&qr.z[j * dim..(j + 1) * dim]);
            g.add_row(j, &mut h[..len], &mut y);
            if j < n8 {
                for (hv, v) in h.iter_mut().zip(&pen.rows[j * k2..(j + 1) * k2]) {
                    *hv = v / p;
                }
                y.fill(0.0);
                g.add_row(j, &mut h, &mut y);
            }
        }
        let c = back_substitute(&g)?;
        let fp = qr.rss + qr.residual_of(&c);
        Ok((c, fp))
    };
    // p → 0: the least-squares polynomial (fp0); p → ∞: the least-squares spline (fp_inf)
    let trace: f64 = qr.r.chunks_exact(k + 1).map(|row| row[0]).sum();
    match smooth_weight(&solve, n as f64 / trace, s, fp0, fp_inf, steps)? {
        Some((p, _, c)) => Ok((c, Some((p * pen.scale).powi(-2)))),
        // no weight reached s from below: the least-squares spline on these knots
        None => Ok((back_substitute(qr)?, None)),
    }
}

/// The smoothing weight `p` on the final knots (step 3): FITPACK's iteration from `p0`, between
/// the polynomial's residual `fp0` (`p = 0`) and the least-squares spline's `fp_inf`
/// (`p = ∞`), continued towards `s − SMOOTHING_RTOL·s/2` if it ends above `s` and that target
/// is above `fp_inf` (otherwise the least-squares spline, `None` here, is within
/// `SMOOTHING_RTOL·s/2` of `s`). Returns the
/// result with the largest residual `≤ s`, if any. Each weight tried is a step of `steps`.
pub(crate) fn smooth_weight(
    solve: &impl Fn(f64) -> Result<(Vec<f64>, f64)>,
    p0: f64,
    s: f64,
    fp0: f64,
    fp_inf: f64,
    steps: &Steps<'_, '_>,
) -> Result<Option<Below>> {
    let solve = |p: f64| {
        steps.tick()?;
        solve(p)
    };
    let acc = SMOOTHING_RTOL * s;
    let mut it = PIteration {
        p: p0,
        limit: s,
        low: (0.0, fp0),
        high: (-1.0, fp_inf),
    };
    let mut below = None;
    let last = it.run(&solve, s, acc, &mut below)?;
    // a target below the least-squares spline's residual is out of reach (the iteration would
    // drive p to 0 and the system to singular); that spline is then within the accuracy of s
    if last.1 > s && s - 0.5 * acc > fp_inf {
        it.run(&solve, s - 0.5 * acc, 0.5 * acc, &mut below)?;
    }
    Ok(below)
}
/// FITPACK's discontinuity rows (`fpdisc`): for each interior knot `t_l`, the jump of the
/// `k`-th derivative of the `k + 2` B-splines `N_{l−k−1..=l}` there, divided by `scale`.
pub(crate) struct JumpRows {
    /// `k + 2` entries per interior knot; row `j` starts at coefficient `j`.
    pub(crate) rows: Vec<f64>,
    /// `k!·(spans/length)^k`.
    pub(crate) scale: f64,
}

pub(crate) fn jump_rows(t: &[f64], k: usize) -> JumpRows {
    let n = t.len();
    let nk1 = n - k - 1;
    let spans = nk1 - k;
    let fac = spans as f64 / (t[nk1] - t[k]);
    let mut rows = Vec::with_capacity((nk1 - k - 1) * (k + 2));
    let mut h = vec![0.0; 2 * k + 2];
    for l in k + 1..nk1 {
        // differences from t_l to the k + 1 knots before it and the k + 1 after it
        for i in 0..=k {
            h[i] = t[l] - t[l - k - 1 + i];
            h[k + 1 + i] = t[l] - t[l + 1 + i];
        }
        let r = l - k - 1;
        for j in 0..k + 2 {
            let prod = h[j..=j + k].iter().skip(1).fold(h[j], |a, v| a * v * fac);
            rows.push((t[r + j + k + 1] - t[r + j]) / prod);
        }
    }
    let factorial: f64 = (1..=k).map(|v| v as f64).product();
    JumpRows {
        rows,
        scale: factorial * fac.powi(i32::try_from(k).unwrap_or(i32::MAX)),
    }
}
/// A smoothed result `(p, fp, c)`.
pub(crate) type Below = (f64, f64, Vec<f64>);

/// FITPACK's iteration for the smoothing weight `p`: `fp(p)` decreases from the polynomial's
/// residual (`p = 0`) to the least-squares spline's (`p = ∞`, marked `-1`); `low`/`high` hold
/// `(p, fp)` with `fp` above/below the target.
pub(super) struct PIteration {
    p: f64,
    /// Results above `limit` (the caller's `s`) are never kept.
    limit: f64,
    low: (f64, f64),
    high: (f64, f64),
}

impl PIteration {
    /// Iterates until `|fp − target| < acc` or [`MAX_P_ITERATIONS`]; returns the last
    /// `(p, fp)` and keeps in `below` the result with the largest `fp ≤ limit`.
    fn run(
        &mut self,
        solve: &impl Fn(f64) -> Result<(Vec<f64>, f64)>,
        target: f64,
        acc: f64,
        below: &mut Option<Below>,
    ) -> Result<(f64, f64)> {
        const SHRINK: f64 = 0.04;
        let (mut f1, mut f3) = (self.low.1 - target, self.high.1 - target);
        let (mut p1, mut p3) = (self.low.0, self.high.0);
        let (mut ich1, mut ich3) = (false, false);
        let mut last = None;
        for iter in 1..=MAX_P_ITERATIONS {
            let p = self.p;
            let (c, fp) = solve(p)?;
            let f2 = fp - target;
            last = Some((p, fp));
            if fp <= self.limit && below.as_ref().is_none_or(|b| fp > b.1) {
                *below = Some((p, fp, c));
            }
            if f2.abs() < acc || iter == MAX_P_ITERATIONS {
                break;
            }
            if !ich3 {
                if f2 - f3 <= acc {
                    // p too large
                    (p3, f3) = (p, f2);
                    self.p = p * SHRINK;
                    if self.p <= p1 {
                        self.p = p1 * 0.9 + p * 0.1;
                    }
                    continue;
                }
                ich3 = f2 < 0.0;
            }
            if !ich1 {
                if f1 - f2 <= acc {
                    // p too small
                    (p1, f1) = (p, f2);
                    self.p = p / SHRINK;
                    if p3 >= 0.0 && self.p >= p3 {
                        self.p = p * 0.1 + p3 * 0.9;
                    }
                    continue;
                }
                ich1 = f2 > 0.0;
            }
            if f2 >= f1 || f2 <= f3 {
                // not the expected convex decrease (rounding): keep the last value
                break;
            }
            self.p = rational_root(p1, f1, p, f2, p3, f3);
            if f2 < 0.0 {
                (p3, f3) = (p, f2);
            } else {
                (p1, f1) = (p, f2);
            }
        }
        self.low = (p1, f1 + target);
        self.high = (p3, f3 + target);
        last.ok_or_else(|| Error::SingularSystem {
            reason: "the smoothing iteration made no step".into(),
        })
    }
}

/// The zero of the rational function `r(p) = (u·p + v)/(p + w)` through `(p1, f1)`,
/// `(p2, f2)`, `(p3, f3)`; `p3 < 0` stands for `p3 = ∞` (FITPACK `fprati`).
pub(super) fn rational_root(p1: f64, f1: f64, p2: f64, f2: f64, p3: f64, f3: f64) -> f64 {
    if p3 < 0.0 {
        return (p1 * (f1 - f3) * f2 - p2 * (f2 - f3) * f1) / ((f1 - f2) * f3);
    }
    let h1 = f1 * (f2 - f3);
    let h2 = f2 * (f3 - f1);
    let h3 = f3 * (f1 - f2);
    -(p1 * p2 * h3 + p2 * p3 * h1 + p3 * p1 * h2) / (p1 * h1 + p2 * h2 + p3 * h3)
}
