//! The two banded kernels of the fitting methods (crate-private; hand-written because they are
//! the product: every fit is a pass of one of them over the data).
//!
//! - [`GivensQr`]: a least-squares problem `min ‖A x − y‖²` whose rows have at most `bw`
//!   consecutive non-zeros, reduced row by row to a banded upper triangle `R` by Givens rotations,
//!   as FITPACK's `fpgivs`/`fprota` do (Dierckx, *Curve and Surface Fitting with Splines*, 1993,
//!   §4.1). The matrix `A` is never stored: each data row is rotated into `R` as it arrives, in
//!   O(bw·(bw + ncols)) time. Rows must arrive with non-decreasing first columns (then no fill-in
//!   leaves the band: `docs/theory/fitting.md#banded-qr`).
//! - [`SymBand`]: a symmetric positive definite banded matrix factored as `Uᵀ D U` (`U` unit
//!   upper triangular, half-bandwidth `b`), with the entries of the inverse inside the band by
//!   the recursion of Hutchinson & de Hoog (1985), for the trace of the smoother matrix in
//!   generalised cross-validation (`docs/theory/fitting.md#gcv`).

/// Relative size below which a diagonal entry of `R` or `D` counts as zero (≈ 64 ulp).
pub(crate) const RANK_RTOL: f64 = 64.0 * f64::EPSILON;

/// Banded QR by Givens rotations; see the module documentation.
#[derive(Debug, Clone)]
pub(crate) struct GivensQr {
    n: usize,
    bw: usize,
    ncols: usize,
    /// `r[i·bw + k] = R[i][i + k]`.
    pub(crate) r: Vec<f64>,
    /// `Qᵀ y`, `n × ncols` row-major.
    pub(crate) z: Vec<f64>,
    /// Sum of the squares rotated out of the right-hand side (the residual of the least-squares
    /// solution, summed over the columns).
    pub(crate) rss: f64,
}

impl GivensQr {
    /// An empty triangle for `n` unknowns, rows of at most `bw` consecutive non-zeros and `ncols`
    /// right-hand sides.
    pub(crate) fn new(n: usize, bw: usize, ncols: usize) -> Self {
        GivensQr {
            n,
            bw,
            ncols,
            r: vec![0.0; n * bw],
            z: vec![0.0; n * ncols],
            rss: 0.0,
        }
    }

    /// Number of unknowns.
    pub(crate) fn n(&self) -> usize {
        self.n
    }

    /// Rotates the row `h` (non-zeros in columns `first .. first + h.len()`, `h.len() ≤ bw`) with
    /// right-hand side `y` into the triangle. `h` and `y` are overwritten. FITPACK `fpgivs` +
    /// `fprota`: `d = √(piv² + r²)`, `cos = r/d`, `sin = piv/d`.
    #[inline]
    pub(crate) fn add_row(&mut self, first: usize, h: &mut [f64], y: &mut [f64]) {
        let (bw, nc) = (self.bw, self.ncols);
        let len = h.len();
        debug_assert!(len <= bw, "row longer than the band");
        for i in 0..len {
            let j = first + i;
            if j >= self.n {
                break;
            }
            let piv = h[i];
            if piv == 0.0 {
                continue;
            }
            let rj = &mut self.r[j * bw..(j + 1) * bw];
            let d = (piv * piv + rj[0] * rj[0]).sqrt();
            let inv = 1.0 / d;
            let (c, s) = (rj[0] * inv, piv * inv);
            rj[0] = d;
            for k in i + 1..len {
                let (a, b) = (h[k], rj[k - i]);
                rj[k - i] = c * b + s * a;
                h[k] = c * a - s * b;
            }
            let zj = &mut self.z[j * nc..(j + 1) * nc];
            for (a, b) in y.iter_mut().zip(zj.iter_mut()) {
                let (ya, zb) = (*a, *b);
                *b = c * zb + s * ya;
                *a = c * ya - s * zb;
            }
        }
        self.rss += y.iter().map(|v| v * v).sum::<f64>();
    }

    /// Solves `R x = z` by back substitution into `x` (`n × ncols`). Returns the first column
    /// whose diagonal is zero to working precision (relative to the largest diagonal) as `Err`.
    pub(crate) fn solve(&self, x: &mut [f64]) -> Result<(), usize> {
        let (n, bw, nc) = (self.n, self.bw, self.ncols);
        let dmax = (0..n).fold(0.0_f64, |m, i| m.max(self.r[i * bw].abs()));
        if let Some(i) =
            (0..n).find(|&i| self.r[i * bw].abs() <= RANK_RTOL * dmax || self.r[i * bw].is_nan())
        {
            return Err(i);
        }
        for i in (0..n).rev() {
            let row = &self.r[i * bw..(i + 1) * bw];
            for c in 0..nc {
                let mut s = self.z[i * nc + c];
                for k in 1..bw.min(n - i) {
                    s -= row[k] * x[(i + k) * nc + c];
                }
                x[i * nc + c] = s / row[0];
            }
        }
        Ok(())
    }

    /// `‖R x − z‖²` summed over the columns: with [`GivensQr::rss`], the squared residual of `x`
    /// for the rows rotated in so far.
    pub(crate) fn residual_of(&self, x: &[f64]) -> f64 {
        let (n, bw, nc) = (self.n, self.bw, self.ncols);
        let mut sum = 0.0;
        for i in 0..n {
            let row = &self.r[i * bw..(i + 1) * bw];
            for c in 0..nc {
                let mut s = -self.z[i * nc + c];
                for k in 0..bw.min(n - i) {
                    s += row[k] * x[(i + k) * nc + c];
                }
                sum += s * s;
            }
        }
        sum
    }
}

/// Symmetric positive definite banded matrix, `Uᵀ D U` after [`SymBand::factor`].
#[derive(Debug, Clone)]
pub(crate) struct SymBand {
    pub(crate) n: usize,
    /// Half-bandwidth `b`.
    pub(crate) b: usize,
    /// `a[i·(b+1) + k] = A[i][i + k]`, `k = 0..=b`; after factoring, `D[i]` at `k = 0` and
    /// `U[i][i+k]` at `k ≥ 1`.
    pub(crate) a: Vec<f64>,
}

impl SymBand {
    /// A zero matrix of order `n` and half-bandwidth `b`.
    pub(crate) fn zeros(n: usize, b: usize) -> Self {
        SymBand {
            n,
            b,
            a: vec![0.0; n * (b + 1)],
        }
    }

    /// `A[i][j] += v` for `j ≥ i` (upper triangle; `j − i ≤ b`).
    #[inline]
    pub(crate) fn add(&mut self, i: usize, j: usize, v: f64) {
        debug_assert!(j >= i && j - i <= self.b, "entry outside the upper band");
        self.a[i * (self.b + 1) + j - i] += v;
    }

    /// Factors in place, `A = Uᵀ D U`, O(n·b²). Returns the first index whose pivot is not
    /// positive (relative to the largest diagonal entry) as `Err`.
    pub(crate) fn factor(&mut self) -> Result<(), usize> {
        let (n, b) = (self.n, self.b);
        let w = b + 1;
        let dmax = (0..n).fold(0.0_f64, |m, i| m.max(self.a[i * w].abs()));
        for i in 0..n {
            // D_i = A_ii − Σ_k U_ki² D_k
            let lo = i.saturating_sub(b);
            let mut d = self.a[i * w];
            for k in lo..i {
                let u = self.a[k * w + i - k];
                d -= u * u * self.a[k * w];
            }
            if d <= RANK_RTOL * dmax || d.is_nan() {
                return Err(i);
            }
            self.a[i * w] = d;
            for j in i + 1..(i + b + 1).min(n) {
                let mut s = self.a[i * w + j - i];
                for k in j.saturating_sub(b)..i {
                    s -= self.a[k * w + i - k] * self.a[k * w + j - k] * self.a[k * w];
                }
                self.a[i * w + j - i] = s / d;
            }
        }
        Ok(())
    }

    /// Solves `A x = y` with the factors, `x` overwriting `y` (`n × ncols`).
    pub(crate) fn solve(&self, y: &mut [f64], ncols: usize) {
        let (n, b) = (self.n, self.b);
        let w = b + 1;
        // Uᵀ v = y (forward), v /= D, U x = v (backward)
        for i in 0..n {
            for k in i.saturating_sub(b)..i {
                let u = self.a[k * w + i - k];
                for c in 0..ncols {
                    y[i * ncols + c] -= u * y[k * ncols + c];
                }
            }
        }
        for i in 0..n {
            let d = self.a[i * w];
            for c in 0..ncols {
                y[i * ncols + c] /= d;
            }
        }
        for i in (0..n).rev() {
            for k in i + 1..(i + b + 1).min(n) {
                let u = self.a[i * w + k - i];
                for c in 0..ncols {
                    y[i * ncols + c] -= u * y[k * ncols + c];
                }
            }
        }
    }

    /// The entries of `A⁻¹` inside the band, in the same layout as `a` (Hutchinson & de Hoog
    /// 1985): from `U Σ = D⁻¹ U⁻ᵀ`, `Σ_ij = δ_ij / D_i − Σ_{k=i+1}^{i+b} U_ik Σ_kj` for `j ≥ i`,
    /// rows from the last up. O(n·b²). Call after [`SymBand::factor`].
    pub(crate) fn inverse_band(&self) -> Vec<f64> {
        let (n, b) = (self.n, self.b);
        let w = b + 1;
        let mut s = vec![0.0; n * w];
        // Σ_kj for k > i, j ≥ i, both within the band: stored at (min, max)
        let get = |s: &[f64], k: usize, j: usize| {
            let (lo, hi) = if k <= j { (k, j) } else { (j, k) };
            s[lo * w + hi - lo]
        };
        for i in (0..n).rev() {
            let top = (i + b).min(n - 1);
            for j in (i..=top).rev() {
                let mut v = if j == i { 1.0 / self.a[i * w] } else { 0.0 };
                for k in i + 1..=top {
                    v -= self.a[i * w + k - i] * get(&s, k, j);
                }
                s[i * w + j - i] = v;
            }
        }
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Dense reference: `A` from its upper band.
    fn dense(m: &SymBand) -> Vec<f64> {
        let (n, w) = (m.n, m.b + 1);
        let mut d = vec![0.0; n * n];
        for i in 0..n {
            for k in 0..w {
                if i + k < n {
                    d[i * n + i + k] = m.a[i * w + k];
                    d[(i + k) * n + i] = m.a[i * w + k];
                }
            }
        }
        d
    }

    #[test]
    fn ldl_solve_and_inverse_band_match_dense() {
        let (n, b) = (9, 2);
        let mut m = SymBand::zeros(n, b);
        for i in 0..n {
            m.add(i, i, 5.0 + i as f64 * 0.1);
            if i + 1 < n {
                m.add(i, i + 1, -1.0 + 0.05 * i as f64);
            }
            if i + 2 < n {
                m.add(i, i + 2, 0.3);
            }
        }
        let a = dense(&m);
        let mut f = m.clone();
        f.factor().unwrap();
        // A · A⁻¹ e_j = e_j, column by column
        let inv = f.inverse_band();
        for j in 0..n {
            let mut e = vec![0.0; n];
            e[j] = 1.0;
            f.solve(&mut e, 1);
            for i in 0..n {
                let r: f64 = (0..n).map(|k| a[i * n + k] * e[k]).sum();
                let want = if i == j { 1.0 } else { 0.0 };
                assert!((r - want).abs() < 1e-13, "A·x at ({i},{j}) = {r}");
                if i <= j && j - i <= b {
                    let got = inv[i * (b + 1) + j - i];
                    assert!(
                        (got - e[i]).abs() < 1e-14,
                        "inverse ({i},{j}): {got} vs {}",
                        e[i]
                    );
                }
            }
        }
    }

    #[test]
    fn givens_qr_solves_a_banded_least_squares_problem() {
        // rows (1, 1, 0), (0, 1, 1), (1, 0, 0)·…: overdetermined, compare with normal equations
        let rows: [(usize, [f64; 2], f64); 5] = [
            (0, [1.0, 0.5], 1.0),
            (0, [0.2, 1.0], 2.0),
            (1, [1.0, 0.3], 0.5),
            (1, [0.4, 1.0], -1.0),
            (2, [1.0, 0.0], 3.0),
        ];
        let n = 3;
        let mut qr = GivensQr::new(n, 2, 1);
        let mut ata = [0.0; 9];
        let mut aty = [0.0; 3];
        for &(first, h, y) in &rows {
            for a in 0..2 {
                for c in 0..2 {
                    if first + a < n && first + c < n {
                        ata[(first + a) * n + first + c] += h[a] * h[c];
                    }
                }
                if first + a < n {
                    aty[first + a] += h[a] * y;
                }
            }
            let (mut hh, mut yy) = (h, [y]);
            let len = 2.min(n - first);
            qr.add_row(first, &mut hh[..len], &mut yy);
        }
        let mut x = [0.0; 3];
        qr.solve(&mut x).unwrap();
        for i in 0..n {
            let r: f64 = (0..n).map(|k| ata[i * n + k] * x[k]).sum();
            assert!(
                (r - aty[i]).abs() < 1e-13,
                "normal equation {i}: {r} vs {}",
                aty[i]
            );
        }
        // the rotated-out residual is the residual of the solution
        let rss: f64 = rows
            .iter()
            .map(|&(first, h, y)| {
                let f: f64 = (0..2)
                    .filter(|&a| first + a < n)
                    .map(|a| h[a] * x[first + a])
                    .sum();
                (y - f) * (y - f)
            })
            .sum();
        assert!(
            (rss - qr.rss - qr.residual_of(&x)).abs() < 1e-13,
            "rss {rss} vs {}",
            qr.rss
        );
    }
}
