//! The two banded kernels of the fitting methods (crate-private; hand-written because they are
//! the product: every fit is a pass of one of them over the data).
//!
//! - [`BandedQr`]: a least-squares problem `min ‖A x − y‖²` whose rows have at most `bw`
//!   consecutive non-zeros, reduced to a banded upper triangle `R` as the rows arrive (the matrix
//!   `A` is never stored). A single row is rotated in by Givens rotations, as FITPACK's
//!   `fpgivs`/`fprota` do (Dierckx, *Curve and Surface Fitting with Splines*, 1993, §4.1), in
//!   O(bw·(bw + ncols)) time. Many rows are gathered by [`QrRows`] into blocks of one first
//!   column and length and reflected in by Householder transformations (Golub & Van Loan,
//!   *Matrix Computations*, 4th ed., §5.2.2), the same triangle for a fraction of the time:
//!   a row rotation waits on a square root and a division per column, a block needs them once
//!   per column for the whole block. Rows must arrive with non-decreasing first and last
//!   columns (then no fill-in leaves the band: `docs/theory/fitting.md#banded-qr`).
//! - [`SymBand`]: a symmetric positive definite banded matrix factored as `Uᵀ D U` (`U` unit
//!   upper triangular, half-bandwidth `b`), with the entries of the inverse inside the band by
//!   the recursion of Hutchinson & de Hoog (1985), for the trace of the smoother matrix in
//!   generalised cross-validation (`docs/theory/fitting.md#gcv`).

/// Relative size below which a diagonal entry of `R` or `D` counts as zero (≈ 64 ulp).
pub(crate) const RANK_RTOL: f64 = 64.0 * f64::EPSILON;

/// Rows per Householder block of [`QrRows`]: the block (`bw + ncols` columns) stays in the
/// first-level cache, and the square roots and divisions are paid once per block and column.
const BLOCK_ROWS: usize = 128;

/// Banded QR by Givens rotations or Householder blocks; see the module documentation.
#[derive(Debug, Clone)]
pub(crate) struct BandedQr {
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

impl BandedQr {
    /// An empty triangle for `n` unknowns, rows of at most `bw` consecutive non-zeros and `ncols`
    /// right-hand sides.
    pub(crate) fn new(n: usize, bw: usize, ncols: usize) -> Self {
        BandedQr {
            n,
            bw,
            ncols,
            r: vec![0.0; n * bw],
            z: vec![0.0; n * ncols],
            rss: 0.0,
        }
    }

    /// As [`BandedQr::new`], with the memory reserved fallibly: `None` if the system refuses
    /// it (a size within [`crate::MAX_SCALARS`] can still be more than the machine has, and an
    /// allocation that fails aborts the process, the Python interpreter with it).
    pub(crate) fn try_new(n: usize, bw: usize, ncols: usize) -> Option<Self> {
        let zeros = |len: usize| {
            let mut v = Vec::new();
            v.try_reserve_exact(len).ok()?;
            v.resize(len, 0.0);
            Some(v)
        };
        Some(BandedQr {
            n,
            bw,
            ncols,
            r: zeros(n.checked_mul(bw)?)?,
            z: zeros(n.checked_mul(ncols)?)?,
            rss: 0.0,
        })
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
            if d == 0.0 {
                // |piv| below 1e-154 against an empty row: the square underflows, and the
                // rotation of a rounding remnant would divide by zero; it is dropped as zero
                continue;
            }
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

    /// `‖R x − z‖²` summed over the columns: with [`BandedQr::rss`], the squared residual of `x`
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

impl BandedQr {
    /// Reflects `m` rows with non-zeros in columns `first .. first + len` into the triangle by
    /// `len` Householder transformations of the stacked matrix `[R_sub; H]`, `R_sub` the
    /// `len × len` triangle of `R` at `first` (Golub & Van Loan §5.2.2). `h` holds the rows
    /// column by column (`h[c·stride + i]`, entry `c` of row `i`), `y` their right-hand sides
    /// the same way; both are overwritten. By the column order of the rows, the rows of
    /// `R_sub` have no non-zero right of column `first + len − 1` yet, so nothing leaves the
    /// band. Each reflection is `v = (r − β, x)` with `β = +√(r² + ‖x‖²)` and
    /// `r − β = −‖x‖²/(r + β)` for `r ≥ 0` (Parlett's form, no cancellation): the diagonal stays
    /// positive, as with [`BandedQr::add_row`], and the triangle is the same to rounding.
    fn reflect_block(
        &mut self,
        first: usize,
        len: usize,
        m: usize,
        h: &mut [f64],
        y: &mut [f64],
        stride: usize,
    ) {
        let (bw, nc) = (self.bw, self.ncols);
        let len = len.min(self.n.saturating_sub(first));
        for i in 0..len {
            let (x, rest) = h[i * stride..].split_at_mut(stride);
            let x = &x[..m];
            let sigma = dot(x, x);
            if sigma == 0.0 {
                continue;
            }
            let j = first + i;
            let rj = &mut self.r[j * bw..(j + 1) * bw];
            let alpha = rj[0];
            let beta = (alpha * alpha + sigma).sqrt();
            let v0 = if alpha > 0.0 {
                -sigma / (alpha + beta)
            } else {
                alpha - beta
            };
            // H = I − g v vᵀ, g = 2/(vᵀv)
            let g = 2.0 / (v0 * v0 + sigma);
            rj[0] = beta;
            let reflect = |top: &mut f64, col: &mut [f64]| {
                let f = g * (v0 * *top + dot(x, col));
                *top -= f * v0;
                col.iter_mut().zip(x).for_each(|(b, a)| *b -= f * a);
            };
            for c in i + 1..len {
                let col = &mut rest[(c - i - 1) * stride..][..m];
                reflect(&mut rj[c - i], col);
            }
            let zj = &mut self.z[j * nc..(j + 1) * nc];
            for (d, top) in zj.iter_mut().enumerate() {
                reflect(top, &mut y[d * stride..][..m]);
            }
        }
        self.rss += (0..nc)
            .map(|d| {
                let yd = &y[d * stride..][..m];
                dot(yd, yd)
            })
            .sum::<f64>();
    }
}

/// `Σ a_i b_i` in four interleaved partial sums (the additions of one sum wait on each other;
/// four run side by side).
#[inline]
fn dot(a: &[f64], b: &[f64]) -> f64 {
    let mut acc = [0.0; 4];
    let (ac, bc) = (a.chunks_exact(4), b.chunks_exact(4));
    let tail: f64 = ac
        .remainder()
        .iter()
        .zip(bc.remainder())
        .map(|(x, y)| x * y)
        .sum();
    for (x, y) in ac.zip(bc) {
        for l in 0..4 {
            acc[l] += x[l] * y[l];
        }
    }
    (acc[0] + acc[1]) + (acc[2] + acc[3]) + tail
}

/// Rows gathered for a [`BandedQr`]: consecutive rows of one first column and length are
/// reflected in together ([`BandedQr::reflect_block`], up to [`BLOCK_ROWS`] at a time); a change
/// of first column or length, a full block or [`QrRows::finish`] reflects the rows waiting.
#[derive(Debug, Clone)]
pub(crate) struct QrRows {
    qr: BandedQr,
    first: usize,
    len: usize,
    m: usize,
    /// `h[c·BLOCK_ROWS + i]`: entry `c` of waiting row `i`.
    h: Vec<f64>,
    /// `y[d·BLOCK_ROWS + i]`: right-hand side `d` of waiting row `i`.
    y: Vec<f64>,
}

impl QrRows {
    /// An empty triangle for `n` unknowns, rows of at most `bw` consecutive non-zeros and `ncols`
    /// right-hand sides.
    pub(crate) fn new(n: usize, bw: usize, ncols: usize) -> Self {
        QrRows {
            qr: BandedQr::new(n, bw, ncols),
            first: 0,
            len: 0,
            m: 0,
            h: vec![0.0; bw * BLOCK_ROWS],
            y: vec![0.0; ncols * BLOCK_ROWS],
        }
    }

    /// Adds the row `h` (non-zeros in columns `first .. first + h.len()`, `h.len() ≤ bw`) with
    /// right-hand side `y`; `first` and `first + h.len()` must not decrease from row to row.
    #[inline]
    pub(crate) fn push(&mut self, first: usize, h: &[f64], y: &[f64]) {
        debug_assert!(h.len() <= self.qr.bw, "row longer than the band");
        if self.m == BLOCK_ROWS || (self.m > 0 && (first != self.first || h.len() != self.len)) {
            self.flush();
        }
        if self.m == 0 {
            (self.first, self.len) = (first, h.len());
        }
        let i = self.m;
        for (c, &v) in h.iter().enumerate() {
            self.h[c * BLOCK_ROWS + i] = v;
        }
        for (d, &v) in y.iter().enumerate() {
            self.y[d * BLOCK_ROWS + i] = v;
        }
        self.m += 1;
    }

    /// Adds `Σ y²` of a row without unknowns to the residual.
    pub(crate) fn add_residual(&mut self, y: &[f64]) {
        self.qr.rss += y.iter().map(|v| v * v).sum::<f64>();
    }

    fn flush(&mut self) {
        if self.m > 0 {
            let (first, len, m) = (self.first, self.len, self.m);
            self.qr
                .reflect_block(first, len, m, &mut self.h, &mut self.y, BLOCK_ROWS);
            self.m = 0;
        }
    }

    /// The triangle of all rows added.
    pub(crate) fn finish(mut self) -> BandedQr {
        self.flush();
        self.qr
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
        // `before_row` never fails here
        self.factor_with(|_| Ok(())).unwrap_or(Ok(()))
    }

    /// [`SymBand::factor`] calling `before_row(i)` before row `i` (a progress hook): its error
    /// stops the factorisation, leaving the matrix half factored, and is returned as the outer
    /// `Err`.
    pub(crate) fn factor_with(
        &mut self,
        mut before_row: impl FnMut(usize) -> crate::error::Result<()>,
    ) -> crate::error::Result<Result<(), usize>> {
        let (n, b) = (self.n, self.b);
        let w = b + 1;
        let dmax = (0..n).fold(0.0_f64, |m, i| m.max(self.a[i * w].abs()));
        for i in 0..n {
            before_row(i)?;
            // D_i = A_ii − Σ_k U_ki² D_k
            let lo = i.saturating_sub(b);
            let mut d = self.a[i * w];
            for k in lo..i {
                let u = self.a[k * w + i - k];
                d -= u * u * self.a[k * w];
            }
            if d <= RANK_RTOL * dmax || d.is_nan() {
                return Ok(Err(i));
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
        Ok(Ok(()))
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
    use proptest::prelude::*;

    /// Rows `(first, h, y)` of a banded problem with `n` unknowns, band `bw` and `nc` right-hand
    /// sides, sorted by first and last column: runs of equal rows longer than a block, shorter
    /// rows at both ends (as end conditions make them) and an all-zero row.
    fn banded_rows(
        n: usize,
        bw: usize,
        nc: usize,
        per_col: usize,
        seed: u64,
    ) -> Vec<(usize, Vec<f64>, Vec<f64>)> {
        let mut state = seed;
        let mut next = move || {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            (state >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        let mut rows = Vec::new();
        for first in 0..=n - bw {
            let count = if first == 1 { BLOCK_ROWS + 7 } else { per_col };
            for i in 0..count {
                // a short row before the full ones at the start, truncated ones at the end
                let len = if first == 0 && i < per_col / 2 {
                    bw - 1
                } else {
                    bw
                };
                let h: Vec<f64> = (0..len).map(|_| next()).collect();
                rows.push((first, h, (0..nc).map(|_| next()).collect()));
            }
        }
        rows.push((n - bw, vec![0.0; bw], (0..nc).map(|_| next()).collect()));
        for len in (1..bw).rev() {
            for _ in 0..per_col {
                let h: Vec<f64> = (0..len).map(|_| next()).collect();
                rows.push((n - len, h, (0..nc).map(|_| next()).collect()));
            }
        }
        rows
    }

    proptest! {
        /// The Householder blocks give the triangle of the Givens rotations: the same `R`
        /// (positive diagonal), `Qᵀy` and residual, to rounding.
        #[test]
        fn blocks_give_the_triangle_of_row_rotations(
            n in 4usize..12,
            bw in 1usize..5,
            nc in 1usize..3,
            per_col in 1usize..20,
            seed in 0u64..1000,
        ) {
            let bw = bw.min(n);
            let rows = banded_rows(n, bw, nc, per_col, seed);
            let mut givens = BandedQr::new(n, bw, nc);
            let mut blocks = QrRows::new(n, bw, nc);
            for (first, h, y) in &rows {
                blocks.push(*first, h, y);
                let (mut h, mut y) = (h.clone(), y.clone());
                givens.add_row(*first, &mut h, &mut y);
            }
            let blocks = blocks.finish();
            let scale = givens.r.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
            for (i, (a, b)) in blocks.r.iter().zip(&givens.r).enumerate() {
                prop_assert!((a - b).abs() <= 1e-13 * scale, "R entry {i}: {a} vs {b}");
            }
            let zscale = givens.z.iter().fold(1.0_f64, |m, v| m.max(v.abs()));
            for (i, (a, b)) in blocks.z.iter().zip(&givens.z).enumerate() {
                prop_assert!((a - b).abs() <= 1e-13 * zscale, "z entry {i}: {a} vs {b}");
            }
            let total: f64 = rows.iter().flat_map(|r| r.2.iter()).map(|v| v * v).sum();
            prop_assert!(
                (blocks.rss - givens.rss).abs() <= 1e-13 * total,
                "rss {} vs {}", blocks.rss, givens.rss
            );
        }
    }

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
        let mut qr = BandedQr::new(n, 2, 1);
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
