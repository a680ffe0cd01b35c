//! The banded QR of periodic (closed) fits, crate-private (hand-written: it is the kernel of
//! every closed fit; `docs/theory/fitting.md#periodic`).
//!
//! A periodic spline has `np` free coefficients and every row of its least-squares problem
//! touches consecutive columns modulo `np`: a band that wraps around the corner. [`CyclicQr`]
//! keeps the first `np − nb` columns as a band of width `bw` and the last `nb` columns as a
//! dense border, as FITPACK's `fpperi` does (Dierckx 1993, §4.1.2):
//!
//! ```text
//!       | R11  R12 |   R11: banded upper triangle, (np − nb) × (np − nb), width bw
//!   R = |          |   R12: dense (np − nb) × nb
//!       |  0   R22 |   R22: dense upper triangle, nb × nb
//! ```
//!
//! Memory is O(np·(bw + nb)); no `np × np` matrix. A row that wraps has its band part at the
//! first columns; FITPACK rotates such rows through every band row (O(np) each). Here the caller
//! rotates the wrapping rows in first, so that every row's first band column is non-decreasing and
//! no rotation leaves the band: O(bw·(bw + nb)) per row.

use super::banded::RANK_RTOL;

/// Bordered banded QR by Givens rotations; see the module documentation.
#[derive(Debug, Clone)]
pub(crate) struct CyclicQr {
    np: usize,
    n_band: usize,
    bw: usize,
    nb: usize,
    ncols: usize,
    /// `r[j·bw + i] = R11[j][j + i]`.
    r: Vec<f64>,
    /// `r12[j·nb + b] = R[j][n_band + b]`.
    r12: Vec<f64>,
    /// `r22[a·nb + b] = R[n_band + a][n_band + b]`, `b ≥ a`.
    r22: Vec<f64>,
    /// `Qᵀ y`, `np × ncols`.
    z: Vec<f64>,
    /// Squares rotated out of the right-hand side.
    pub(crate) rss: f64,
    h: Vec<f64>,
    g: Vec<f64>,
}

impl CyclicQr {
    /// An empty triangle for `np` unknowns, band width `bw` and a border of `nb` columns
    /// (fewer when `np ≤ nb`: then every column is in the border).
    pub(crate) fn new(np: usize, bw: usize, nb: usize, ncols: usize) -> Self {
        let nb = nb.min(np);
        let n_band = np - nb;
        CyclicQr {
            np,
            n_band,
            bw,
            nb,
            ncols,
            r: vec![0.0; n_band * bw],
            r12: vec![0.0; n_band * nb],
            r22: vec![0.0; nb * nb],
            z: vec![0.0; np * ncols],
            rss: 0.0,
            h: vec![0.0; bw],
            g: vec![0.0; nb],
        }
    }

    /// Number of unknowns.
    pub(crate) fn n(&self) -> usize {
        self.np
    }

    /// Number of right-hand sides.
    pub(crate) fn ncols(&self) -> usize {
        self.ncols
    }

    /// Rotates in the row with the values `vals[i]` in the columns `(start + i) mod np` and the
    /// right-hand side `y` (overwritten). Entries landing on the same column add up.
    pub(crate) fn add_cyclic(&mut self, start: usize, vals: &[f64], y: &mut [f64]) {
        let np = self.np;
        self.add_entries(
            vals.iter()
                .enumerate()
                .map(move |(i, &v)| ((start + i) % np, v)),
            y,
        );
    }

    /// Rotates in a row given as `(column, value)` entries. Rows must arrive with non-decreasing
    /// first band column (the smallest column below `np − nb` among their entries).
    pub(crate) fn add_entries(
        &mut self,
        entries: impl Iterator<Item = (usize, f64)> + Clone,
        y: &mut [f64],
    ) {
        let n_band = self.n_band;
        let first = entries
            .clone()
            .filter(|&(c, _)| c < n_band)
            .map(|(c, _)| c)
            .min()
            .unwrap_or(n_band);
        self.h.fill(0.0);
        self.g.fill(0.0);
        for (c, v) in entries {
            if c < n_band {
                debug_assert!(c - first < self.bw, "row wider than the band");
                self.h[c - first] += v;
            } else {
                self.g[c - n_band] += v;
            }
        }
        self.rotate(first, y);
    }

    /// Givens rotations of the row held in `h` (band, from column `first`) and `g` (border).
    fn rotate(&mut self, first: usize, y: &mut [f64]) {
        let (bw, nb, nc, n_band) = (self.bw, self.nb, self.ncols, self.n_band);
        let CyclicQr {
            r,
            r12,
            r22,
            z,
            h,
            g,
            ..
        } = self;
        let rot = |c: f64, s: f64, a: &mut f64, b: &mut f64| {
            // b is the triangle's entry, a the row's (FITPACK fprota)
            let (va, vb) = (*a, *b);
            *b = c * vb + s * va;
            *a = c * va - s * vb;
        };
        for i in 0..bw {
            let j = first + i;
            if j >= n_band {
                break;
            }
            let piv = h[i];
            if piv == 0.0 {
                continue;
            }
            let rj = &mut r[j * bw..(j + 1) * bw];
            let (c, s) = givens(piv, &mut rj[0]);
            for k in i + 1..bw {
                rot(c, s, &mut h[k], &mut rj[k - i]);
            }
            for (a, b) in g.iter_mut().zip(&mut r12[j * nb..(j + 1) * nb]) {
                rot(c, s, a, b);
            }
            for (a, b) in y.iter_mut().zip(&mut z[j * nc..(j + 1) * nc]) {
                rot(c, s, a, b);
            }
        }
        for a in 0..nb {
            let piv = g[a];
            if piv == 0.0 {
                continue;
            }
            let row = &mut r22[a * nb..(a + 1) * nb];
            let (c, s) = givens(piv, &mut row[a]);
            for b in a + 1..nb {
                rot(c, s, &mut g[b], &mut row[b]);
            }
            let j = n_band + a;
            for (ya, zb) in y.iter_mut().zip(&mut z[j * nc..(j + 1) * nc]) {
                rot(c, s, ya, zb);
            }
        }
        self.rss += y.iter().map(|v| v * v).sum::<f64>();
    }

    /// The diagonal of `R`.
    pub(crate) fn diagonal(&self) -> impl Iterator<Item = f64> + '_ {
        (0..self.n_band)
            .map(|j| self.r[j * self.bw])
            .chain((0..self.nb).map(|a| self.r22[a * self.nb + a]))
    }

    /// Row `j` of `R` as `(column, value)` entries, and its right-hand side.
    pub(crate) fn row(&self, j: usize) -> (Vec<(usize, f64)>, &[f64]) {
        let (bw, nb, n_band) = (self.bw, self.nb, self.n_band);
        let mut e = Vec::with_capacity(bw + nb);
        if j < n_band {
            e.extend((0..bw.min(n_band - j)).map(|i| (j + i, self.r[j * bw + i])));
            e.extend((0..nb).map(|b| (n_band + b, self.r12[j * nb + b])));
        } else {
            let a = j - n_band;
            e.extend((a..nb).map(|b| (n_band + b, self.r22[a * nb + b])));
        }
        (e, &self.z[j * self.ncols..(j + 1) * self.ncols])
    }

    /// Solves `R x = z` into `x` (`np × ncols`). Returns the first column whose diagonal is zero
    /// to working precision (relative to the largest) as `Err`.
    pub(crate) fn solve(&self, x: &mut [f64]) -> Result<(), usize> {
        let (bw, nb, nc, n_band) = (self.bw, self.nb, self.ncols, self.n_band);
        let dmax = self.diagonal().fold(0.0_f64, |m, d| m.max(d.abs()));
        if let Some(j) = self
            .diagonal()
            .position(|d| d.abs() <= RANK_RTOL * dmax || d.is_nan())
        {
            return Err(j);
        }
        for a in (0..nb).rev() {
            let row = &self.r22[a * nb..(a + 1) * nb];
            for c in 0..nc {
                let mut s = self.z[(n_band + a) * nc + c];
                for b in a + 1..nb {
                    s -= row[b] * x[(n_band + b) * nc + c];
                }
                x[(n_band + a) * nc + c] = s / row[a];
            }
        }
        for j in (0..n_band).rev() {
            let row = &self.r[j * bw..(j + 1) * bw];
            let border = &self.r12[j * nb..(j + 1) * nb];
            for c in 0..nc {
                let mut s = self.z[j * nc + c];
                for i in 1..bw.min(n_band - j) {
                    s -= row[i] * x[(j + i) * nc + c];
                }
                for (b, v) in border.iter().enumerate() {
                    s -= v * x[(n_band + b) * nc + c];
                }
                x[j * nc + c] = s / row[0];
            }
        }
        Ok(())
    }

    /// `‖R x − z‖²` summed over the columns (with [`CyclicQr::rss`], the residual of `x`).
    pub(crate) fn residual_of(&self, x: &[f64]) -> f64 {
        let nc = self.ncols;
        let mut sum = 0.0;
        for j in 0..self.np {
            let (e, z) = self.row(j);
            for (c, zc) in z.iter().enumerate() {
                let v: f64 = e.iter().map(|&(col, r)| r * x[col * nc + c]).sum::<f64>() - zc;
                sum += v * v;
            }
        }
        sum
    }
}

/// The rotation that zeroes `piv` against the diagonal `r` (overwritten by the new diagonal),
/// scaled as FITPACK's `fpgivs`: the border entries of a closed fit decay geometrically along the
/// band and reach the underflow range, where `√(piv² + r²)` would give 0 and then NaN.
fn givens(piv: f64, r: &mut f64) -> (f64, f64) {
    let (a, b) = (piv.abs(), r.abs());
    let d = if a >= b {
        a * (1.0 + (b / a) * (b / a)).sqrt()
    } else {
        b * (1.0 + (a / b) * (a / b)).sqrt()
    };
    let (c, s) = (*r / d, piv / d);
    *r = d;
    (c, s)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A cyclic least-squares problem against its normal equations, dense.
    fn check(np: usize, len: usize, bw: usize, nb: usize) {
        let rows: Vec<(usize, Vec<f64>, f64)> = (0..4 * np)
            .map(|k| {
                let start = (k * 7 + 3) % np;
                let vals: Vec<f64> = (0..len)
                    .map(|i| 1.0 + ((k * 13 + i * 5) % 11) as f64 * 0.1)
                    .collect();
                (start, vals, ((k * 17) % 23) as f64 * 0.3 - 2.0)
            })
            .collect();
        // wrapping rows first, then by start
        let wraps = |s: usize| s + len > np;
        let mut order: Vec<usize> = (0..rows.len()).collect();
        order.sort_by_key(|&k| (!wraps(rows[k].0), rows[k].0));
        let mut qr = CyclicQr::new(np, bw, nb, 1);
        let mut ata = vec![0.0; np * np];
        let mut aty = vec![0.0; np];
        for &k in &order {
            let (start, vals, y) = &rows[k];
            let mut dense = vec![0.0; np];
            for (i, v) in vals.iter().enumerate() {
                dense[(start + i) % np] += v;
            }
            for a in 0..np {
                aty[a] += dense[a] * y;
                for b in 0..np {
                    ata[a * np + b] += dense[a] * dense[b];
                }
            }
            qr.add_cyclic(*start, vals, &mut [*y]);
        }
        let mut x = vec![0.0; np];
        qr.solve(&mut x).unwrap();
        for a in 0..np {
            let r: f64 = (0..np).map(|b| ata[a * np + b] * x[b]).sum();
            assert!(
                (r - aty[a]).abs() < 1e-10 * aty[a].abs().max(1.0),
                "normal equation {a} of np = {np}: {r} vs {}",
                aty[a]
            );
        }
        let rss: f64 = rows
            .iter()
            .map(|(start, vals, y)| {
                let f: f64 = vals
                    .iter()
                    .enumerate()
                    .map(|(i, v)| v * x[(start + i) % np])
                    .sum();
                (y - f) * (y - f)
            })
            .sum();
        let got = qr.rss + qr.residual_of(&x);
        assert!(
            (rss - got).abs() < 1e-9 * rss.max(1.0),
            "rss {rss} vs {got}"
        );
    }

    #[test]
    fn cyclic_qr_solves_wrapping_least_squares_problems() {
        // cubic data rows (len 4, border 3), penalty-like rows (len 5, border 4), and short
        // periods where rows wrap onto themselves
        for np in [1, 2, 3, 4, 5, 9, 20, 300] {
            check(np, 4, 4, 3);
            check(np, 5, 5, 4);
        }
    }
}
