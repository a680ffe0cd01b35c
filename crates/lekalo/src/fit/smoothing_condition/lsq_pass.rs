//! The data of the smoothing condition as rows of the least-squares problem, the residual no
//! spline gets below, and one least-squares pass over the data for a knot vector
//! (`docs/theory/fitting.md#smoothing-condition`, `#banded-qr`).

use crate::basis::{basis_funs_into, BasisScratch, SpanBasis};
use crate::error::{readable, Error, Result};
use crate::fit::banded::{BandedQr, QrRows};
use crate::fit::data::FitData;
use crate::Arg;

/// The data sorted by parameter, relative to the first point and weighted for the rows of the
/// least-squares problem.
pub(in crate::fit) struct Observations {
    /// Parameters, increasing.
    pub(in crate::fit) x: Vec<f64>,
    /// `√w` (FITPACK's weight).
    pub(in crate::fit) wf: Vec<f64>,
    /// `√w·(Q − Q_first)`, `dim` per point.
    pub(in crate::fit) y: Vec<f64>,
    pub(in crate::fit) dim: usize,
    pub(in crate::fit) center: Vec<f64>,
    /// The distinct parameters.
    pub(in crate::fit) sites: Vec<f64>,
}

impl Observations {
    pub(in crate::fit) fn new(data: &FitData<'_>) -> Self {
        let pts = data.points();
        let dim = pts.dim();
        let center = pts.point(0).to_vec();
        let order: Vec<usize> = data.order().unwrap_or_else(|| (0..data.len()).collect());
        let params = data.params();
        let x: Vec<f64> = order.iter().map(|&i| params[i]).collect();
        let wf: Vec<f64> = order.iter().map(|&i| data.weight(i).sqrt()).collect();
        let mut y = Vec::with_capacity(x.len() * dim);
        for (&i, &w) in order.iter().zip(&wf) {
            y.extend(pts.point(i).iter().zip(&center).map(|(q, o)| w * (q - o)));
        }
        let mut sites = x.clone();
        sites.dedup();
        Observations {
            x,
            wf,
            y,
            dim,
            center,
            sites,
        }
    }
}

/// The least weighted residual sum of squares any function of the parameter leaves on the data
/// `obs`: for each group of points with the same parameter, `Σ_i w_i |Q_i − Q̄|²` about the
/// group's weighted mean `Q̄ = Σ w_i Q_i / Σ w_i` (the minimum of `Σ_i w_i |v − Q_i|²` over one
/// value `v`); 0 when the parameters are distinct. The least-squares spline on the knots of
/// interpolation at the distinct parameters reaches it (it passes through every group's mean).
/// Computed from the rows `√w_i·(Q_i − Q_first)`: `√w_i·(Q_i − Q̄) = y_i − √w_i·Q̄`.
pub(in crate::fit) fn reachable_floor(obs: &Observations) -> f64 {
    let dim = obs.dim;
    let mut floor = 0.0;
    let mut mean = vec![0.0; dim];
    let mut start = 0;
    while start < obs.x.len() {
        let end = start + obs.x[start..].partition_point(|&u| u == obs.x[start]);
        if end - start > 1 {
            // Σ w·Q = Σ √w·y, Σ w = Σ √w²
            let total: f64 = obs.wf[start..end].iter().map(|w| w * w).sum();
            if total > 0.0 {
                mean.fill(0.0);
                for i in start..end {
                    for (m, y) in mean.iter_mut().zip(&obs.y[i * dim..(i + 1) * dim]) {
                        *m += obs.wf[i] * y;
                    }
                }
                mean.iter_mut().for_each(|m| *m /= total);
                for i in start..end {
                    for (m, y) in mean.iter().zip(&obs.y[i * dim..(i + 1) * dim]) {
                        let r = y - obs.wf[i] * m;
                        floor += r * r;
                    }
                }
            }
        }
        start = end;
    }
    floor
}

/// Refuses a target `s` below [`reachable_floor`]: no spline (no function) has a residual that
/// small, so the smoothing condition has no answer.
pub(in crate::fit) fn check_reachable(obs: &Observations, s: f64) -> Result<()> {
    let floor = reachable_floor(obs);
    if floor > s {
        return Err(Error::InvalidArgument {
            what: Arg::S.into(),
            reason: format!(
                "s = {} is below {}, the weighted residual sum of squares that every function \
                 leaves where points share a parameter (x) with different values (at best it \
                 passes through each group's weighted mean): give s ≥ {}, or average the points \
                 with a repeated parameter",
                readable(&s),
                readable(&floor),
                readable(&floor)
            ),
        });
    }
    Ok(())
}

/// One least-squares pass over the data for a knot vector, keeping each row's first column and
/// weighted basis values for the span residuals.
pub(in crate::fit) struct LsqPass {
    pub(in crate::fit) k: usize,
    pub(in crate::fit) first: Vec<usize>,
    pub(in crate::fit) rows: Vec<f64>,
    /// `Σ_d (√w_i·(C_d(ū_i) − Q_{i,d}))²` per point, from [`LsqPass::residuals`].
    pub(in crate::fit) res: Vec<f64>,
}

impl LsqPass {
    pub(in crate::fit) fn new(obs: &Observations, k: usize) -> Self {
        LsqPass {
            k,
            first: vec![0; obs.x.len()],
            rows: vec![0.0; obs.x.len() * (k + 1)],
            res: vec![0.0; obs.x.len()],
        }
    }

    /// The banded triangle of `min Σ w |C(ū) − Q|²` for the clamped knots `t` (FITPACK's
    /// observation matrix, reduced as it is built: [`QrRows`]).
    pub(in crate::fit) fn run(&mut self, obs: &Observations, t: &[f64]) -> BandedQr {
        let k = self.k;
        let mut qr = QrRows::new(t.len() - k - 1, k + 1, obs.dim);
        self.fill(obs, t, |i, first, h| {
            qr.push(first, h, &obs.y[i * obs.dim..(i + 1) * obs.dim]);
        });
        qr.finish()
    }

    /// Every row `√w_i·N_{first..first+k}(ū_i)` for the knots `t` (`t.len() − k − 1` basis
    /// functions, spans found by walking the sorted parameters), kept and passed to
    /// `sink(i, first, row)`. The degrees up to 5 get an unrolled kernel ([`SpanBasis`]).
    pub(in crate::fit) fn fill(
        &mut self,
        obs: &Observations,
        t: &[f64],
        sink: impl FnMut(usize, usize, &[f64]),
    ) {
        match self.k + 1 {
            2 => self.fill_order::<2>(obs, t, sink),
            3 => self.fill_order::<3>(obs, t, sink),
            4 => self.fill_order::<4>(obs, t, sink),
            5 => self.fill_order::<5>(obs, t, sink),
            6 => self.fill_order::<6>(obs, t, sink),
            _ => self.fill_order::<0>(obs, t, sink),
        }
    }

    /// [`LsqPass::fill`] with the order `W = k + 1` known at compile time (`0`: any order).
    fn fill_order<const W: usize>(
        &mut self,
        obs: &Observations,
        t: &[f64],
        mut sink: impl FnMut(usize, usize, &[f64]),
    ) {
        let k = self.k;
        let w = if W == 0 { k + 1 } else { W };
        let nk1 = t.len() - k - 1;
        let mut basis = SpanBasis::<W>::new();
        let mut scratch = BasisScratch::new(if W == 0 { k } else { 0 });
        let mut span = k;
        basis.set_span(t, span);
        let rows = self.rows.chunks_exact_mut(w);
        for (i, ((h, first), (&u, &wf))) in rows
            .zip(self.first.iter_mut())
            .zip(obs.x.iter().zip(&obs.wf))
            .enumerate()
        {
            if span + 1 < nk1 && u >= t[span + 1] {
                while span + 1 < nk1 && u >= t[span + 1] {
                    span += 1;
                }
                basis.set_span(t, span);
            }
            if W == 0 {
                basis_funs_into(t, k, span, u, &mut scratch, h);
                h.iter_mut().for_each(|v| *v *= wf);
            } else {
                basis.eval(u, wf, h);
            }
            *first = span - k;
            sink(i, span - k, h);
        }
    }

    /// [`LsqPass::res`] for the coefficients `c` (`dim` per basis function; for closed fits the
    /// repeated ones included).
    pub(in crate::fit) fn residuals(&mut self, obs: &Observations, c: &[f64]) {
        match self.k + 1 {
            2 => self.residuals_order::<2>(obs, c),
            3 => self.residuals_order::<3>(obs, c),
            4 => self.residuals_order::<4>(obs, c),
            5 => self.residuals_order::<5>(obs, c),
            6 => self.residuals_order::<6>(obs, c),
            _ => self.residuals_order::<0>(obs, c),
        }
    }

    fn residuals_order<const W: usize>(&mut self, obs: &Observations, c: &[f64]) {
        let (w, dim) = (if W == 0 { self.k + 1 } else { W }, obs.dim);
        let rows = self.rows.chunks_exact(w).zip(&self.first);
        for ((r, (h, &f)), y) in self.res.iter_mut().zip(rows).zip(obs.y.chunks_exact(dim)) {
            let cs = &c[f * dim..(f + w) * dim];
            *r = (0..dim)
                .map(|d| {
                    let v: f64 = h.iter().enumerate().map(|(j, b)| b * cs[j * dim + d]).sum();
                    (v - y[d]) * (v - y[d])
                })
                .sum();
        }
    }
}

/// Back substitution in the triangle, a zero pivot (a coefficient without data) as an error.
pub(in crate::fit) fn back_substitute(qr: &BandedQr) -> Result<Vec<f64>> {
    let mut c = vec![0.0; qr.z.len()];
    qr.solve(&mut c).map_err(|col| Error::SingularSystem {
        reason: format!(
            "control point {col} has no data of positive weight under its basis function; \
             give those points a positive weight or remove them"
        ),
    })?;
    Ok(c)
}
