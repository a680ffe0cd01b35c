//! Banded linear systems solved by elimination without pivoting (crate-private).
//!
//! B-spline collocation matrices are banded and totally positive (de Boor, "Total positivity of
//! the spline collocation matrix", Indiana Univ. Math. J. 26, 1977); Gaussian elimination without
//! pivoting is then stable (de Boor & Pinkus, "Backward error analysis for totally positive
//! linear systems", Numer. Math. 27, 1977). Document 000 (digest §A.1, step 4) prescribes exactly
//! this: "banded Gaussian elimination without pivoting".
//!
//! [`BandedCrout`] eliminates one row at a time (Crout form `A = L·U`, `U` unit upper
//! triangular), so a caller can build each matrix row straight from the basis kernel into a
//! small buffer and never store the matrix. With `kl = ku = 1` the sweep is the Thomas algorithm
//! ("progonka", digest §A.3): `m = β_i − α_i γ'_{i−1}`, `γ'_i = γ_i / m`,
//! `r'_i = (r_i − α_i r'_{i−1}) / m`, then `x_i = r'_i − γ'_i x_{i+1}`.
//!
//! The right-hand side is an `m × ncols` row-major block: every coordinate of the data (and, for
//! surfaces, every row of the grid) is one column, so one factorisation serves them all.
//!
//! Cost: O(m·kl·(ku + ncols)) time; memory `m·ku` for `U`, plus `m·(kl + 1)` when the factors are
//! kept for further right-hand sides.
//!
//! On request ([`BandedCrout::new_estimating`]) the factorisation also accumulates `‖A‖_1` as the
//! rows arrive and [`BandedCrout::condition_estimate`] estimates `κ_1(A) = ‖A‖_1·‖A⁻¹‖_1` by
//! Hager's method as refined by Higham (LAPACK `dgbcon`), with solves by the stored factors:
//! O(m·(kl + ku)) more time and O(m) more memory, nothing for the default factorisation.

use crate::error::{Error, Result};

/// A pivot smaller than this times the largest entry of its original row counts as zero:
/// the matrix is singular to working precision (≈ 64 ulp).
const SINGULAR_PIVOT: f64 = 64.0 * f64::EPSILON;

/// Largest accepted growth of the factors' entries relative to the largest matrix entry. For
/// totally positive matrices the growth is at most 1; a growth beyond this means the system is
/// too ill-conditioned to solve to the promised accuracy without pivoting.
const MAX_GROWTH: f64 = 1e8;

/// Row-by-row banded elimination without pivoting (Crout), see the module documentation.
#[derive(Debug, Clone)]
pub(crate) struct BandedCrout {
    kl: usize,
    ku: usize,
    rows: usize,
    /// Row `r`: `U[r][r+1..=r+ku]` (unit diagonal implied), `ku` entries per row.
    upper: Vec<f64>,
    /// Row `r`: `L[r][r−kl..r]`, `kl` entries per row, then `1 / L[r][r]` (only when kept).
    lower: Option<Vec<f64>>,
    /// Largest absolute entry of the matrix rows seen so far.
    max_entry: f64,
    /// Largest absolute entry of the factors so far.
    max_factor: f64,
    /// With a condition estimate: `‖A‖_1` accumulated as the rows arrive.
    col_sums: Option<ColumnSums>,
}

impl BandedCrout {
    /// An empty factorisation for up to `capacity` rows with `kl` sub- and `ku` super-diagonals.
    /// `keep_lower` keeps `L` so that [`BandedCrout::solve`] can take further right-hand sides.
    pub(crate) fn new(capacity: usize, kl: usize, ku: usize, keep_lower: bool) -> Self {
        BandedCrout {
            kl,
            ku,
            rows: 0,
            upper: Vec::with_capacity(capacity * ku),
            lower: keep_lower.then(|| Vec::with_capacity(capacity * (kl + 1))),
            max_entry: 0.0,
            max_factor: 0.0,
            col_sums: None,
        }
    }

    /// As [`BandedCrout::new`] with `L` kept and the column sums of `|A|` accumulated, so that
    /// [`BandedCrout::condition_estimate`] can be called once the rows are pushed.
    pub(crate) fn new_estimating(capacity: usize, kl: usize, ku: usize) -> Self {
        let mut lu = BandedCrout::new(capacity, kl, ku, true);
        lu.col_sums = Some(ColumnSums {
            open: vec![0.0; kl + 1 + ku],
            closed_max: 0.0,
        });
        lu
    }

    /// Width of a row buffer: `kl + 1 + ku`, the diagonal at index `kl`.
    pub(crate) fn width(&self) -> usize {
        self.kl + 1 + self.ku
    }

    /// Eliminates the next row `r = self.rows()`.
    ///
    /// `row` (length [`BandedCrout::width`]) holds `A[r][r−kl..=r+ku]`, the diagonal at `kl`;
    /// entries left of column 0 must be zero. `rhs` is the `ncols`-wide right-hand-side block
    /// whose rows `0..r` were forward-solved by earlier calls; row `r` is forward-solved here.
    /// `row` is overwritten. The pivot is judged against the larger of the row's largest entry
    /// and `row_scale` (pass 1 for B-spline collocation rows, whose full rows sum to 1 even when
    /// some entries were moved to the right-hand side; 0 to use the row alone).
    ///
    /// # Errors
    /// [`Error::SingularSystem`] on a zero (or non-finite) pivot; [`Error::IllConditioned`] if
    /// the factors grow beyond [`MAX_GROWTH`] times the matrix entries.
    pub(crate) fn push_row(
        &mut self,
        row: &mut [f64],
        rhs: &mut [f64],
        ncols: usize,
        row_scale: f64,
    ) -> Result<()> {
        // constant band widths and column counts let the compiler unroll the common cases
        // (cubic and quadratic curves in 1–3 dimensions); the arithmetic is the same
        macro_rules! fixed {
            ($kl:literal, $ku:literal, $nc:literal) => {
                self.push_row_impl(row, rhs, $kl, $ku, $nc, row_scale)
            };
        }
        match (self.kl, self.ku, ncols) {
            (1, 1, 1) => fixed!(1, 1, 1),
            (1, 1, 2) => fixed!(1, 1, 2),
            (1, 1, 3) => fixed!(1, 1, 3),
            (2, 2, 1) => fixed!(2, 2, 1),
            (2, 2, 2) => fixed!(2, 2, 2),
            (2, 2, 3) => fixed!(2, 2, 3),
            (kl, ku, nc) => self.push_row_impl(row, rhs, kl, ku, nc, row_scale),
        }
    }

    #[inline(always)]
    fn push_row_impl(
        &mut self,
        row: &mut [f64],
        rhs: &mut [f64],
        kl: usize,
        ku: usize,
        ncols: usize,
        row_scale: f64,
    ) -> Result<()> {
        let r = self.rows;
        debug_assert_eq!(row.len(), kl + 1 + ku, "row buffer width");
        debug_assert!(self.kl == kl && self.ku == ku, "band widths");
        let row = &mut row[..kl + 1 + ku];
        if let Some(sums) = &mut self.col_sums {
            sums.add_row(row, r);
        }
        let row_max = row.iter().fold(row_scale, |m, v| m.max(v.abs()));
        self.max_entry = self.max_entry.max(row_max);
        let (done, current) = rhs.split_at_mut(r * ncols);
        let current = &mut current[..ncols];
        // L[r][j] for j = r − kl + m is the reduced row[m]; subtract L[r][j]·U[j][·].
        for m in kl.saturating_sub(r)..kl {
            let j = r + m - kl;
            let l = row[m];
            let u = &self.upper[j * ku..(j + 1) * ku];
            for (x, uj) in row[m + 1..m + 1 + ku].iter_mut().zip(u) {
                *x -= l * uj;
            }
            for (x, y) in current.iter_mut().zip(&done[j * ncols..(j + 1) * ncols]) {
                *x -= l * y;
            }
        }
        let pivot = row[kl];
        if !pivot.is_finite() || pivot.abs() <= SINGULAR_PIVOT * row_max {
            return Err(singular(pivot, r, row_max));
        }
        let inv = 1.0 / pivot;
        // growth: the largest entry of the reduced row (L part, pivot and unscaled U part)
        let growth = row.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        if growth > self.max_factor {
            self.max_factor = growth;
            if self.max_factor > MAX_GROWTH * self.max_entry {
                return Err(ill_conditioned(self.max_factor / self.max_entry, r));
            }
        }
        for x in current.iter_mut() {
            *x *= inv;
        }
        for x in &row[kl + 1..] {
            self.upper.push(x * inv);
        }
        if let Some(lower) = &mut self.lower {
            lower.extend_from_slice(&row[..kl]);
            lower.push(inv);
        }
        self.rows += 1;
        Ok(())
    }

    /// Back substitution `U·x = y` in place on the `rows × ncols` block `rhs`.
    pub(crate) fn back_substitute(&self, rhs: &mut [f64], ncols: usize) {
        match (self.ku, ncols) {
            (1, 3) => self.back_substitute_impl(rhs, 1, 3),
            (2, 3) => self.back_substitute_impl(rhs, 2, 3),
            (2, 2) => self.back_substitute_impl(rhs, 2, 2),
            (ku, nc) => self.back_substitute_impl(rhs, ku, nc),
        }
    }

    #[inline(always)]
    fn back_substitute_impl(&self, rhs: &mut [f64], ku: usize, ncols: usize) {
        debug_assert_eq!(self.ku, ku, "band width");
        let rows = self.rows;
        for r in (0..rows).rev() {
            let (head, tail) = rhs.split_at_mut((r + 1) * ncols);
            let x = &mut head[r * ncols..];
            let u = &self.upper[r * ku..(r + 1) * ku];
            // entries beyond the last row are zero by construction
            let live = ku.min(rows - 1 - r);
            for (t, &ut) in u[..live].iter().enumerate() {
                let y = &tail[t * ncols..(t + 1) * ncols];
                for (a, b) in x.iter_mut().zip(y) {
                    *a -= ut * b;
                }
            }
        }
    }

    /// Solves `A·X = B` in place for a further right-hand side (`rows × ncols`, row-major). Only
    /// for a factorisation made with `keep_lower`.
    pub(crate) fn solve(&self, rhs: &mut [f64], ncols: usize) {
        // constant band widths and column counts for the common cases (bicubic and biquadratic
        // surfaces in 1–4 dimensions, many small blocks each, and the condition estimate's
        // single columns); the arithmetic is the same
        debug_assert_eq!(rhs.len(), self.rows * ncols, "rhs block size");
        let Some(lower) = &self.lower else {
            debug_assert!(false, "solve needs the kept lower factor");
            return;
        };
        macro_rules! fixed {
            ($kl:literal, $ku:literal, $nc:literal) => {
                self.solve_block_fixed::<$kl, $ku, $nc>(lower, rhs)
            };
        }
        match (self.kl, self.ku, ncols) {
            (1, 1, 1) => fixed!(1, 1, 1),
            (1, 1, 2) => fixed!(1, 1, 2),
            (1, 1, 3) => fixed!(1, 1, 3),
            (1, 1, 4) => fixed!(1, 1, 4),
            (2, 2, 1) => fixed!(2, 2, 1),
            (2, 2, 2) => fixed!(2, 2, 2),
            (2, 2, 3) => fixed!(2, 2, 3),
            (2, 2, 4) => fixed!(2, 2, 4),
            (1, 2, 1) => fixed!(1, 2, 1),
            (2, 1, 1) => fixed!(2, 1, 1),
            (3, 3, 1) => fixed!(3, 3, 1),
            (4, 4, 1) => fixed!(4, 4, 1),
            (1, 2, 3) => fixed!(1, 2, 3),
            (2, 1, 3) => fixed!(2, 1, 3),
            (kl, _, nc) => self.solve_impl(rhs, kl, nc),
        }
    }

    /// [`BandedCrout::solve`] for fixed band widths and column count, row-oriented with the last
    /// `KL` (`KU`) solved rows in registers: the rows of a small block (or of a single column)
    /// are a latency-bound recurrence, and reloading a row just stored would add the
    /// store-forwarding delay to each. The same operations in the same
    /// order as [`BandedCrout::solve_impl`], except that the zero entries of `L` left of column
    /// 0 and of `U` beyond the last row are multiplied (by the zero initial windows) instead of
    /// skipped, which leaves every finite value unchanged.
    fn solve_block_fixed<const KL: usize, const KU: usize, const NC: usize>(
        &self,
        lower: &[f64],
        rhs: &mut [f64],
    ) {
        let rows = self.rows;
        let mut win = [[0.0_f64; NC]; KL];
        // the factors hold exactly `rows` rows, so the zips need no `take`
        debug_assert_eq!(lower.len(), rows * (KL + 1), "lower factor size");
        debug_assert_eq!(self.upper.len(), rows * KU, "upper factor size");
        for (x, l) in rhs.chunks_exact_mut(NC).zip(lower.chunks_exact(KL + 1)) {
            let mut v = [0.0_f64; NC];
            v.copy_from_slice(x);
            for m in 0..KL {
                for c in 0..NC {
                    v[c] -= l[m] * win[m][c];
                }
            }
            for c in 0..NC {
                v[c] *= l[KL];
            }
            x.copy_from_slice(&v);
            push_back(&mut win, v);
        }
        let mut win = [[0.0_f64; NC]; KU];
        for (x, u) in rhs
            .chunks_exact_mut(NC)
            .zip(self.upper.chunks_exact(KU))
            .rev()
        {
            let mut v = [0.0_f64; NC];
            v.copy_from_slice(x);
            for t in 0..KU {
                for c in 0..NC {
                    v[c] -= u[t] * win[t][c];
                }
            }
            x.copy_from_slice(&v);
            push_front(&mut win, v);
        }
    }

    /// Row `r` of the kept lower factor: `L[r][r−kl..r]` (zeros left of column 0), then
    /// `1 / L[r][r]`. Only for a factorisation made with `keep_lower`.
    pub(crate) fn lower_row(&self, r: usize) -> &[f64] {
        let kl = self.kl;
        self.lower
            .as_deref()
            .map_or(&[], |l| &l[r * (kl + 1)..(r + 1) * (kl + 1)])
    }

    /// Row `r` of the unit upper factor: `U[r][r+1..=r+ku]` (zeros beyond the last row).
    pub(crate) fn upper_row(&self, r: usize) -> &[f64] {
        &self.upper[r * self.ku..(r + 1) * self.ku]
    }

    /// Number of sub-diagonals `kl` of the band.
    pub(crate) fn kl(&self) -> usize {
        self.kl
    }

    /// Number of super-diagonals `ku` of the band.
    pub(crate) fn ku(&self) -> usize {
        self.ku
    }

    /// [`BandedCrout::solve`] by its general loop only (the reference for the fixed kernels).
    #[cfg(test)]
    pub(crate) fn solve_general(&self, rhs: &mut [f64], ncols: usize) {
        self.solve_impl(rhs, self.kl, ncols);
    }

    #[inline(always)]
    fn solve_impl(&self, rhs: &mut [f64], kl: usize, ncols: usize) {
        debug_assert_eq!(rhs.len(), self.rows * ncols, "rhs block size");
        debug_assert_eq!(self.kl, kl, "band width");
        let Some(lower) = &self.lower else {
            debug_assert!(false, "solve needs the kept lower factor");
            return;
        };
        for r in 0..self.rows {
            let (done, current) = rhs.split_at_mut(r * ncols);
            let current = &mut current[..ncols];
            let l = &lower[r * (kl + 1)..(r + 1) * (kl + 1)];
            for m in kl.saturating_sub(r)..kl {
                let lm = l[m];
                if lm == 0.0 {
                    continue;
                }
                let j = r + m - kl;
                for (x, y) in current.iter_mut().zip(&done[j * ncols..(j + 1) * ncols]) {
                    *x -= lm * y;
                }
            }
            for x in current.iter_mut() {
                *x *= l[kl];
            }
        }
        self.back_substitute(rhs, ncols);
    }

    /// Solves the transposed system `Aᵀ·x = b` in place (one right-hand side) with the kept
    /// factors: `Aᵀ = Uᵀ·Lᵀ`, so a forward sweep with the unit lower triangular `Uᵀ` and a
    /// backward sweep with the upper triangular `Lᵀ`. Column `j` of `Uᵀ` (of `Lᵀ`) is row `j` of
    /// `U` (of `L`), so both sweeps read the stored rows in order (column-oriented substitution,
    /// Golub & Van Loan §3.1.4). O(m·(kl + ku)).
    pub(crate) fn solve_transposed(&self, x: &mut [f64]) {
        debug_assert_eq!(x.len(), self.rows, "rhs length");
        let Some(lower) = &self.lower else {
            debug_assert!(false, "solve_transposed needs the kept lower factor");
            return;
        };
        match (self.kl, self.ku) {
            (1, 1) => self.solve_transposed_fixed::<1, 1>(lower, x),
            (2, 2) => self.solve_transposed_fixed::<2, 2>(lower, x),
            (1, 2) => self.solve_transposed_fixed::<1, 2>(lower, x),
            (2, 1) => self.solve_transposed_fixed::<2, 1>(lower, x),
            (3, 3) => self.solve_transposed_fixed::<3, 3>(lower, x),
            (4, 4) => self.solve_transposed_fixed::<4, 4>(lower, x),
            (kl, ku) => self.solve_transposed_impl(lower, x, kl, ku),
        }
    }

    #[inline(always)]
    fn solve_transposed_impl(&self, lower: &[f64], x: &mut [f64], kl: usize, ku: usize) {
        let rows = self.rows;
        // Uᵀ·z = b: z_j is final once the columns before it are subtracted
        for j in 0..rows {
            let zj = x[j];
            let u = &self.upper[j * ku..(j + 1) * ku];
            if j + ku < rows {
                for (xi, uj) in x[j + 1..j + 1 + ku].iter_mut().zip(u) {
                    *xi -= uj * zj;
                }
            } else {
                // entries beyond the last row are zero by construction
                for (xi, uj) in x[j + 1..].iter_mut().zip(u) {
                    *xi -= uj * zj;
                }
            }
        }
        // Lᵀ·x = z: row i of L holds L[i][i−kl..i] and 1 / L[i][i]
        for i in (0..rows).rev() {
            let l = &lower[i * (kl + 1)..(i + 1) * (kl + 1)];
            let xi = x[i] * l[kl];
            x[i] = xi;
            if i >= kl {
                for (xc, lm) in x[i - kl..i].iter_mut().zip(l) {
                    *xc -= lm * xi;
                }
            } else {
                for (xc, lm) in x[..i].iter_mut().zip(&l[kl - i..kl]) {
                    *xc -= lm * xi;
                }
            }
        }
    }

    /// [`BandedCrout::solve`] for one right-hand side (the condition estimate's solves, whose
    /// band widths [`BandedCrout::solve`] fixes at compile time for the common cases).
    fn solve_vector(&self, x: &mut [f64]) {
        self.solve(x, 1);
    }

    /// [`BandedCrout::solve_transposed`] for fixed band widths, row-oriented with the last
    /// solution values in registers (see [`BandedCrout::solve_block_fixed`]): row `r` of `Uᵀ`
    /// holds `U[r−1−t][t]`, row `i` of `Lᵀ` holds `L[i+1+t][i]` for `t = 0, 1, …`.
    fn solve_transposed_fixed<const KL: usize, const KU: usize>(
        &self,
        lower: &[f64],
        x: &mut [f64],
    ) {
        let rows = self.rows;
        let upper = &self.upper[..rows * KU];
        // Uᵀ·z = b; win[t] = z_{r−1−t}
        let mut win = [0.0_f64; KU];
        let head = KU.min(rows);
        for r in 0..head {
            let mut v = x[r];
            for t in 0..r {
                v -= upper[(r - 1 - t) * KU + t] * win[t];
            }
            x[r] = v;
            push_front(&mut win, v);
        }
        // the full rows: fixed trip counts, unrolled
        for r in head..rows {
            let mut v = x[r];
            for t in 0..KU {
                v -= upper[(r - 1 - t) * KU + t] * win[t];
            }
            x[r] = v;
            push_front(&mut win, v);
        }
        // Lᵀ·x = z; win[t] = x_{i+1+t}; L[i+1+t][i] at lower[(i+1+t)·(KL+1) + KL−1−t]
        let lower = &lower[..rows * (KL + 1)];
        let mut win = [0.0_f64; KL];
        let tail = rows.saturating_sub(KL);
        for i in (tail..rows).rev() {
            let mut v = x[i];
            for t in 0..rows - 1 - i {
                v -= lower[(i + 1 + t) * (KL + 1) + KL - 1 - t] * win[t];
            }
            v *= lower[i * (KL + 1) + KL];
            x[i] = v;
            push_front(&mut win, v);
        }
        for i in (0..tail).rev() {
            let mut v = x[i];
            for t in 0..KL {
                v -= lower[(i + 1 + t) * (KL + 1) + KL - 1 - t] * win[t];
            }
            v *= lower[i * (KL + 1) + KL];
            x[i] = v;
            push_front(&mut win, v);
        }
    }

    /// `‖A‖_1`, the largest column sum of `|A|` over the rows pushed so far; `None` unless made
    /// by [`BandedCrout::new_estimating`].
    pub(crate) fn norm1(&self) -> Option<f64> {
        self.col_sums.as_ref().map(ColumnSums::norm1)
    }

    /// Estimate of the 1-norm condition number `κ_1(A) = ‖A‖_1·‖A⁻¹‖_1` of the factored
    /// (square, `rows × rows`) matrix; `None` unless made by [`BandedCrout::new_estimating`].
    ///
    /// `‖A⁻¹‖_1` comes from Hager's estimator as refined by Higham: N. J. Higham, "FORTRAN codes
    /// for estimating the one-norm of a real or complex matrix, with applications to condition
    /// estimation", ACM TOMS 14 (1988) 381–396, Algorithm 4.1 — the algorithm of LAPACK's
    /// `dlacn2`, which `dgbcon` applies to a banded LU. It needs products with `A⁻¹` and `A⁻ᵀ`
    /// only (single-vector [`BandedCrout::solve`] and [`BandedCrout::solve_transposed`]): at
    /// most 5 iterations, usually 2 or 3 — about four solves with `A` and two with `Aᵀ` — so
    /// O(m·(kl + ku)) time, one O(m) buffer and `m` sign flags. Every value it forms is
    /// `‖A⁻¹·x‖_1 / ‖x‖_1` for some `x`, so the estimate is a lower bound of `κ_1` (up to
    /// rounding in the solves); it is usually exact, and in Higham's experiments rarely low by
    /// more than a factor of 3 (tested here against the dense `κ_1`). Of the last two
    /// iterates the larger is kept (Algorithm 4.1 keeps the last), still a lower bound.
    ///
    /// Returns 1 for an empty system (LAPACK's convention) and `∞` when the solves overflow.
    pub(crate) fn condition_estimate(&self) -> Option<f64> {
        let norm = self.norm1()?;
        let rows = self.rows;
        if rows == 0 {
            return Some(1.0);
        }
        let inv = self.inverse_norm1_estimate();
        let kappa = norm * inv;
        Some(if kappa.is_finite() {
            kappa
        } else {
            f64::INFINITY
        })
    }

    /// Higham's Algorithm 4.1 (see [`BandedCrout::condition_estimate`]) for `B = A⁻¹`, in the
    /// order of LAPACK's `dlacn2` (`ITMAX = 5`, `sign(0) = +1`, the first largest entry).
    fn inverse_norm1_estimate(&self) -> f64 {
        const MAX_ITERATIONS: usize = 5;
        let n = self.rows;
        let sign = |non_negative: bool| if non_negative { 1.0 } else { -1.0 };
        let first_largest = |x: &[f64]| {
            let mut j = 0;
            for (i, v) in x.iter().enumerate() {
                if v.abs() > x[j].abs() {
                    j = i;
                }
            }
            j
        };
        let norm = |x: &[f64]| x.iter().map(|v| v.abs()).sum::<f64>();
        // v = B·(e/n)
        let mut x = vec![1.0 / n as f64; n];
        self.solve_vector(&mut x);
        if n == 1 {
            return x[0].abs();
        }
        let mut est = norm(&x);
        if !est.is_finite() {
            // the solves overflowed: numerically singular
            return f64::INFINITY;
        }
        // ξ = sign(v) as `v ≥ 0` flags (n bytes rather than n numbers)
        let mut xi: Vec<bool> = x.iter().map(|&v| v >= 0.0).collect();
        for (v, &s) in x.iter_mut().zip(&xi) {
            *v = sign(s);
        }
        self.solve_transposed(&mut x);
        let mut j = first_largest(&x);
        let mut iteration = 2;
        loop {
            // v = B·e_j
            x.fill(0.0);
            x[j] = 1.0;
            self.solve_vector(&mut x);
            let previous = est;
            est = norm(&x);
            if !est.is_finite() {
                return f64::INFINITY;
            }
            let repeated = x.iter().zip(&xi).all(|(&v, &s)| (v >= 0.0) == s);
            if repeated || est <= previous {
                est = est.max(previous);
                break;
            }
            for (s, v) in xi.iter_mut().zip(x.iter_mut()) {
                *s = *v >= 0.0;
                *v = sign(*s);
            }
            self.solve_transposed(&mut x);
            let last = j;
            j = first_largest(&x);
            if x[last] == x[j].abs() || iteration >= MAX_ITERATIONS {
                break;
            }
            iteration += 1;
        }
        // the alternating test vector x_i = (−1)^i·(1 + i/(n−1)), ‖x‖_1 = 3n/2
        let mut alt = 1.0;
        for (i, v) in x.iter_mut().enumerate() {
            *v = alt * (1.0 + i as f64 / (n - 1) as f64);
            alt = -alt;
        }
        self.solve_vector(&mut x);
        let temp = 2.0 * norm(&x) / (3 * n) as f64;
        if temp.is_nan() || temp > est {
            est = temp;
        }
        est
    }
}

/// Shifts the window one place towards index 0 and puts `v` last (no-op for `N = 0`).
/// Written out (not `rotate_left`, which is not inlined) so that it stays in registers.
#[inline(always)]
fn push_back<T: Copy, const N: usize>(win: &mut [T; N], v: T) {
    if N > 0 {
        for m in 1..N {
            win[m - 1] = win[m];
        }
        win[N - 1] = v;
    }
}

/// Shifts the window one place away from index 0 and puts `v` first (no-op for `N = 0`).
#[inline(always)]
fn push_front<T: Copy, const N: usize>(win: &mut [T; N], v: T) {
    if N > 0 {
        for m in (1..N).rev() {
            win[m] = win[m - 1];
        }
        win[0] = v;
    }
}

/// `‖A‖_1 = max_c Σ_r |A[r][c]|` of a banded matrix whose rows arrive one at a time, in
/// O(kl + ku) memory: row `r` touches columns `r − kl ..= r + ku` only, so column `c` is complete
/// once row `c + kl` is in. The `kl + 1 + ku` open columns live in a ring (column `c` at slot
/// `(c + kl) mod width`); a completed column's sum goes into `closed_max` and its slot is reused
/// by the column that the next row opens.
#[derive(Debug, Clone)]
struct ColumnSums {
    open: Vec<f64>,
    closed_max: f64,
}

impl ColumnSums {
    /// Adds `|row|` (row `r`, columns `r − kl ..= r + ku` at `row[0..]`; those left of column 0
    /// are zero). Kept out of line: only the estimating factorisation takes it.
    #[inline(never)]
    fn add_row(&mut self, row: &[f64], r: usize) {
        let width = self.open.len();
        debug_assert_eq!(row.len(), width, "row width");
        // the slot of column r − kl − 1 (complete now) is that of column r + ku (opened now)
        let last = (r + width - 1) % width;
        self.closed_max = self.closed_max.max(self.open[last]);
        self.open[last] = 0.0;
        for (m, v) in row.iter().enumerate() {
            let slot = (r + m) % width;
            self.open[slot] += v.abs();
        }
    }

    fn norm1(&self) -> f64 {
        self.open.iter().fold(self.closed_max, |m, v| m.max(*v))
    }
}

/// Number of knots whose reciprocals [`ReciprocalBlock`] holds at a time.
const RECIPROCAL_BLOCK: usize = 256;

/// Reciprocals `1/(u_{c+m} − u_c)`, `m = 1, 2, 3`, of the knot differences that start at the
/// knots `c` of a block `base ..` (the denominators of Cox–de Boor for the cubic, see
/// [`cubic_basis`]), stored by difference (structure of arrays) so that a block is filled by
/// vectorised divisions: the divider's throughput bounds the fused forward sweep. Infinite for
/// a zero difference, which no span of positive length uses.
struct ReciprocalBlock {
    base: usize,
    len: usize,
    /// `1/(u_{c+m} − u_c)` for `m = 1, 2, 3` at `c = base + i`.
    by_gap: [[f64; RECIPROCAL_BLOCK]; 3],
}

impl ReciprocalBlock {
    #[inline(always)]
    fn new(knots: &[f64], base: usize) -> Self {
        let mut block = ReciprocalBlock {
            base,
            len: 0,
            by_gap: [[0.0; RECIPROCAL_BLOCK]; 3],
        };
        block.fill(knots, base);
        block
    }

    /// Whether knots `span − 2 ..= span` are in the block.
    #[inline(always)]
    fn covers(&self, span: usize) -> bool {
        span >= self.base + 2 && span < self.base + self.len
    }

    /// Fills the block from knot `base` on ([`fill_reciprocals`]).
    #[inline(always)]
    fn fill(&mut self, knots: &[f64], base: usize) {
        fill_reciprocals(self, knots, base);
    }

    /// The reciprocals of knots `span − 2`, `span − 1`, `span` (see [`cubic_basis`]).
    #[inline(always)]
    fn window(&self, span: usize) -> [[f64; 3]; 3] {
        let i = span - self.base;
        let at = |c: usize| [self.by_gap[0][c], self.by_gap[1][c], self.by_gap[2][c]];
        [at(i - 2), at(i - 1), at(i)]
    }
}

/// The body of [`fill_reciprocals`]: `RECIPROCAL_BLOCK` knots' reciprocals, one difference
/// `m` at a time so that the divisions vectorise.
#[inline(always)]
fn fill_reciprocals_body(block: &mut ReciprocalBlock, knots: &[f64], base: usize) {
    let len = RECIPROCAL_BLOCK.min(knots.len().saturating_sub(3 + base));
    for (m, out) in block.by_gap.iter_mut().enumerate() {
        let from = &knots[base..base + len];
        let to = &knots[base + m + 1..base + m + 1 + len];
        for ((o, a), b) in out[..len].iter_mut().zip(to).zip(from) {
            *o = 1.0 / (a - b);
        }
    }
    (block.base, block.len) = (base, len);
}

crate::isa::avx2_dispatch! {
    /// Fills a [`ReciprocalBlock`] from knot `base` on, compiled with AVX2 (4-wide divisions)
    /// where the processor has it ([`crate::isa`]; the same bits either way). Kept out of line:
    /// inlined, it slowed the sweep that calls it once per block.
    #[inline(never)]
    fn fill_reciprocals(block: &mut ReciprocalBlock, knots: &[f64], base: usize) = fill_reciprocals_body;
}

/// The four non-zero cubic basis functions `N_{span−3..=span, 3}(t)`: P&T Algorithm A2.2
/// (Cox–de Boor, [`crate::basis::basis_funs_into`]) unrolled for `p = 3` with every
/// intermediate in registers, each division by a knot difference replaced by a product with
/// its reciprocal. `recip[i]` holds the reciprocals of the differences from knot `span − 2 + i`
/// ([`ReciprocalBlock::window`]); consecutive rows share them, so a collocation sweep forms
/// three reciprocals per knot (vectorised, a block at a time) instead of six quotients per row.
/// The divisions were the bottleneck of the fused solve's forward sweep (measured 14.5 → 8.5 ns
/// a row without them). The A2.2 denominator `right + left` is the knot difference
/// rounded twice instead of once, so the values agree with A2.2 to a few ulps (tested) rather
/// than bit for bit. `span` must be the span of `t`.
#[inline(always)]
pub(crate) fn cubic_basis(knots: &[f64], recip: &[[f64; 3]; 3], span: usize, t: f64) -> [f64; 4] {
    debug_assert!(span >= 3 && span + 3 < knots.len(), "cubic span {span}");
    let k = &knots[span - 2..span + 4];
    // left[j] = t − u[span+1−j], right[j] = u[span+j] − t
    let (l1, l2, l3) = (t - k[2], t - k[1], t - k[0]);
    let (r1, r2, r3) = (k[3] - t, k[4] - t, k[5] - t);
    // j = 1: 1/(u_{s+1} − u_s)
    let temp = recip[2][0];
    let (n0, n1) = (r1 * temp, l1 * temp);
    // j = 2: 1/(u_{s+1} − u_{s−1}), 1/(u_{s+2} − u_s)
    let temp = n0 * recip[1][1];
    let m0 = r1 * temp;
    let saved = l2 * temp;
    let temp = n1 * recip[2][1];
    let m1 = saved + r2 * temp;
    let m2 = l1 * temp;
    // j = 3: 1/(u_{s+1} − u_{s−2}), 1/(u_{s+2} − u_{s−1}), 1/(u_{s+3} − u_s)
    let temp = m0 * recip[0][2];
    let o0 = r1 * temp;
    let saved = l3 * temp;
    let temp = m1 * recip[1][2];
    let o1 = saved + r2 * temp;
    let saved = l2 * temp;
    let temp = m2 * recip[2][2];
    let o2 = saved + r3 * temp;
    let o3 = l1 * temp;
    [o0, o1, o2, o3]
}

/// `max(a, b)` by one comparison (`maxsd`): `b` when `a < b` is false, so a NaN `a` gives `b`
/// and a NaN `b` gives `b`. For running maxima whose NaNs are caught elsewhere.
#[inline(always)]
fn max_num(a: f64, b: f64) -> f64 {
    if a > b {
        a
    } else {
        b
    }
}

crate::isa::avx2_dispatch! {
    /// [`solve_free_cubic_body`] compiled with AVX2 where the processor has it, else as built
    /// ([`crate::isa`]: the same bits, tested in `interpolate_fast`).
    pub(crate) fn solve_free_cubic<const D: usize>(
        q: &[f64],
        knots: &[f64],
        control: &mut [f64],
        upper: &mut Vec<[f64; 2]>,
    ) -> bool = solve_free_cubic_body;
}

/// Fused collocation solve of the free-end cubic interpolant with averaged knots (document 000
/// §A.1 eq. 1 and 3, P&T Algorithm A9.1): the fast path of [`BandedCrout::push_row`] +
/// [`BandedCrout::back_substitute`] with Cox–de Boor rows (P&T A2.2, see [`cubic_basis`]).
///
/// `q` holds the `n + 1` points (`D` coordinates each) and `knots` the `n + 5` averaged knots;
/// `control` (`(n + 1)·D` numbers) holds on entry the parameter `t̄_r` of point `r` in
/// `control[r·D]` (the other entries are ignored) and on return the control points
/// (`P_0 = q_0`, `P_n = q_n`). Returns `false` when a row does not fit the band `kl = ku = 2`,
/// a pivot or the growth fails the checks of [`BandedCrout`], or a result overflows (data near
/// the largest `f64`): the caller then takes the general path, which reports the precise error.
///
/// The rows are built and eliminated as the parameters are swept; only the two previous rows
/// of `U` and of the forward-solved right-hand side are live during the sweep (in registers).
/// Row `r` of the forward-solved right-hand side replaces `t̄_r`, which is read just before,
/// so the parameters need no buffer of their own; `U` (two numbers a row, in `upper`, grown to
/// `n` rows if shorter and otherwise reused as it is: every row read is written first) is stored
/// for the back substitution, which writes the final, un-centred control points in place. The data are
/// centred on `q_0` (see [`crate::interpolate`]). The elimination is that of the general path
/// operation by operation (the terms the general path skips are products with zero); the rows
/// differ from its Cox–de Boor rows by a few ulps (shared reciprocals, see [`cubic_basis`]), so
/// the control points agree with the general path's to rounding amplified by the condition
/// number (tested: within `κ·ε` of the data's extent, and 1e-14 of the net on smooth data).
/// Time O(n), memory `2·n` numbers besides the result.
///
/// This is the body, inlined into both copies of [`solve_free_cubic`].
#[inline(always)]
pub(crate) fn solve_free_cubic_body<const D: usize>(
    q: &[f64],
    knots: &[f64],
    control: &mut [f64],
    upper: &mut Vec<[f64; 2]>,
) -> bool {
    let n = (q.len() / D).saturating_sub(1);
    if n < 4 || q.len() != (n + 1) * D || knots.len() != n + 5 || control.len() != q.len() {
        return false;
    }
    let point = |i: usize| -> [f64; D] {
        let mut v = [0.0; D];
        v.copy_from_slice(&q[i * D..(i + 1) * D]);
        v
    };
    let q0 = point(0);
    let mut qn = point(n);
    for (a, b) in qn.iter_mut().zip(&q0) {
        *a -= b;
    }
    if upper.len() < n {
        // fresh zero pages (no zeroing pass) unless the workspace already holds the room
        *upper = crate::large_buffer::reuse_or_zeroed(upper, n);
    }
    // rows r − 2 and r − 1 of U and of the forward-solved right-hand side
    let (mut u2, mut u1) = ([0.0_f64; 2], [0.0_f64; 2]);
    let (mut y2, mut y1) = ([0.0_f64; D], [0.0_f64; D]);
    let mut growth = 0.0_f64;
    let mut span = 3;
    // reciprocals of the knot differences, a block of knots at a time
    let mut block = ReciprocalBlock::new(knots, 1);
    for r in 1..n {
        let t = control[r * D];
        while knots[span + 1] <= t {
            span += 1;
        }
        if !block.covers(span) {
            block.fill(knots, span - 2);
        }
        let basis = cubic_basis(knots, &block.window(span), span, t);
        // band positions 0..5 are the columns r − 2 ..= r + 2; basis j is column span − 3 + j
        let mut b = point(r);
        for (x, c) in b.iter_mut().zip(&q0) {
            *x -= c;
        }
        let [n0, n1, n2, n3] = basis;
        // the usual rows: no known column (0 or n) and the basis at a fixed place in the band
        // (fixed indices keep the row in registers)
        let mut a = match span.wrapping_sub(r + 1) {
            0 if span >= 4 && span < n => [n0, n1, n2, n3, 0.0],
            1 if span >= 4 && span < n => [0.0, n0, n1, n2, n3],
            _ => [0.0_f64; 5],
        };
        let usual = span >= 4 && span < n && span.wrapping_sub(r + 1) <= 1;
        for (j, &v) in basis.iter().enumerate() {
            if usual {
                break;
            }
            let col = span - 3 + j;
            if col == 0 {
                // P_0 − q_0 = 0
                continue;
            }
            if col == n {
                for (x, c) in b.iter_mut().zip(&qn) {
                    *x -= v * c;
                }
                continue;
            }
            // constant indices only, so that `a` is never addressed through memory
            match (col + 2).checked_sub(r) {
                Some(0) => a[0] = v,
                Some(1) => a[1] = v,
                Some(2) => a[2] = v,
                Some(3) => a[3] = v,
                Some(4) => a[4] = v,
                _ if v == 0.0 => {}
                _ => return false,
            }
        }
        // Schoenberg–Whitney: N_r(t̄_r) > 0 (else the general path reports the failure)
        if a[2] <= 0.0 {
            return false;
        }
        // subtract L[r][j]·U[j][·] for j = r − 2, r − 1 (as BandedCrout::push_row)
        let l = a[0];
        a[1] -= l * u2[0];
        a[2] -= l * u2[1];
        for (x, y) in b.iter_mut().zip(&y2) {
            *x -= l * y;
        }
        let l = a[1];
        a[2] -= l * u1[0];
        a[3] -= l * u1[1];
        for (x, y) in b.iter_mut().zip(&y1) {
            *x -= l * y;
        }
        let pivot = a[2];
        // the rows' largest entry is at most 1 (basis values), the row scale is 1
        if !pivot.is_finite() || pivot.abs() <= SINGULAR_PIVOT {
            return false;
        }
        // a[0] and a[4] are basis values (≤ 1) left as they were. Plain comparisons (one
        // `maxsd` each) instead of `f64::max`'s NaN handling: the pivot was checked finite, and
        // a NaN in a[1] or a[3] reaches the control points, whose finiteness is checked below
        growth = max_num(max_num(max_num(growth, a[1].abs()), a[2].abs()), a[3].abs());
        let inv = 1.0 / pivot;
        for x in &mut b {
            *x *= inv;
        }
        let u = [a[3] * inv, a[4] * inv];
        control[r * D..(r + 1) * D].copy_from_slice(&b);
        upper[r] = u;
        (u2, u1) = (u1, u);
        (y2, y1) = (y1, b);
    }
    if growth > MAX_GROWTH {
        return false;
    }
    control[n * D..].copy_from_slice(&q[n * D..]);
    // back substitution x_r = y_r − U[r][0]·x_{r+1} − U[r][1]·x_{r+2}, x_n = x_{n+1} = 0 for
    // the unknowns (P_n was moved to the right-hand side), then P_r = x_r + q_0
    let (mut x1, mut x2) = ([0.0_f64; D], [0.0_f64; D]);
    // data near the largest f64 can overflow in the centring or the solve: then decline, and
    // the general path reports it
    // (`poison` stays 0 unless an infinity or NaN is multiplied into it: one multiply-add a
    // coordinate, one accumulator per coordinate so that no chain crosses coordinates)
    let mut poison = [0.0_f64; D];
    for (p, v) in poison.iter_mut().zip(&qn) {
        *p += v * 0.0;
    }
    for (row, u) in control[D..n * D]
        .chunks_exact_mut(D)
        .zip(&upper[1..n])
        .rev()
    {
        let mut x = [0.0_f64; D];
        for k in 0..D {
            let mut v = row[k];
            v -= u[0] * x1[k];
            v -= u[1] * x2[k];
            x[k] = v;
            row[k] = v + q0[k];
            poison[k] += row[k] * 0.0;
        }
        (x2, x1) = (x1, x);
    }
    control[..D].copy_from_slice(&q0);
    poison.iter().all(|p| *p == 0.0)
}

#[cold]
fn singular(pivot: f64, r: usize, row_max: f64) -> Error {
    Error::SingularSystem {
        reason: format!(
            "pivot {pivot:e} in row {r} vanishes against the row's largest entry {row_max:e}; \
             the interpolation conditions are not independent (check that the parameters are \
             distinct and the degree fits the data)"
        ),
    }
}

#[cold]
fn ill_conditioned(growth: f64, r: usize) -> Error {
    Error::IllConditioned {
        reason: format!(
            "elimination without pivoting grew the factors to {growth:e} times the matrix \
             entries (limit {MAX_GROWTH:e}) at row {r}; the parameters or knots are too unevenly \
             spaced for this degree"
        ),
    }
}

/// Solves the small dense system `A·X = B` (`A` is `n × n` row-major, `B` is `n × ncols`) in
/// place by Gaussian elimination with partial pivoting (Golub & Van Loan, Algorithm 3.4.1).
/// Used for the `p × p` Schur complement of periodic interpolation.
///
/// # Errors
/// [`Error::SingularSystem`] if a pivot vanishes against the matrix scale.
pub(crate) fn solve_dense(a: &mut [f64], b: &mut [f64], n: usize, ncols: usize) -> Result<()> {
    let scale = a.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    for k in 0..n {
        let mut best = k;
        for i in k + 1..n {
            if a[i * n + k].abs() > a[best * n + k].abs() {
                best = i;
            }
        }
        let pivot = a[best * n + k];
        if !pivot.is_finite() || pivot.abs() <= SINGULAR_PIVOT * scale {
            return Err(Error::SingularSystem {
                reason: format!(
                    "the periodic coupling block has a vanishing pivot {pivot:e} (scale \
                     {scale:e}); the closed-curve conditions are not independent"
                ),
            });
        }
        if best != k {
            for j in 0..n {
                a.swap(k * n + j, best * n + j);
            }
            for j in 0..ncols {
                b.swap(k * ncols + j, best * ncols + j);
            }
        }
        for i in k + 1..n {
            let f = a[i * n + k] / pivot;
            if f == 0.0 {
                continue;
            }
            for j in k..n {
                a[i * n + j] -= f * a[k * n + j];
            }
            for j in 0..ncols {
                b[i * ncols + j] -= f * b[k * ncols + j];
            }
        }
    }
    for k in (0..n).rev() {
        for j in 0..ncols {
            let mut s = b[k * ncols + j];
            for i in k + 1..n {
                s -= a[k * n + i] * b[i * ncols + j];
            }
            b[k * ncols + j] = s / a[k * n + k];
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The AVX2 copy of a reciprocal block holds the baseline's bits, for a block in the
    /// middle of the knots and a short one at their end.
    #[cfg(target_arch = "x86_64")]
    #[test]
    fn reciprocal_blocks_agree_bit_for_bit() {
        if !crate::isa::has_avx2() {
            return;
        }
        let mut u = 0.0_f64;
        let knots: Vec<f64> = (0..700)
            .map(|i| {
                u += 0.01 + (f64::from(i) * 0.37).sin().abs() * 1e-3;
                u
            })
            .collect();
        for base in [0, 100, 500, 690] {
            let mut a = ReciprocalBlock::new(&knots, 0);
            let mut b = ReciprocalBlock::new(&knots, 0);
            fill_reciprocals_body(&mut a, &knots, base);
            // the dispatched fill takes the AVX2 copy here
            b.fill(&knots, base);
            assert_eq!((a.base, a.len), (b.base, b.len), "block extent");
            for m in 0..3 {
                let bits = |blk: &ReciprocalBlock| -> Vec<u64> {
                    blk.by_gap[m][..blk.len]
                        .iter()
                        .map(|x| x.to_bits())
                        .collect()
                };
                assert_eq!(
                    bits(&a),
                    bits(&b),
                    "reciprocals of gap {} from knot {base}",
                    m + 1
                );
            }
        }
    }

    /// Dense reference: `A·x` for a banded matrix given by rows of `(first column, values)`.
    fn mat_vec(rows: &[(usize, Vec<f64>)], x: &[f64], ncols: usize) -> Vec<f64> {
        let mut out = vec![0.0; rows.len() * ncols];
        for (r, (c0, vals)) in rows.iter().enumerate() {
            for (t, v) in vals.iter().enumerate() {
                for k in 0..ncols {
                    out[r * ncols + k] += v * x[(c0 + t) * ncols + k];
                }
            }
        }
        out
    }

    fn factor_rows(
        rows: &[(usize, Vec<f64>)],
        kl: usize,
        ku: usize,
        rhs: &mut [f64],
        ncols: usize,
        keep: bool,
    ) -> Result<BandedCrout> {
        let mut lu = BandedCrout::new(rows.len(), kl, ku, keep);
        let mut buf = vec![0.0; lu.width()];
        for (r, (c0, vals)) in rows.iter().enumerate() {
            buf.fill(0.0);
            for (t, v) in vals.iter().enumerate() {
                buf[c0 + t + kl - r] = *v;
            }
            lu.push_row(&mut buf, rhs, ncols, 0.0)?;
        }
        Ok(lu)
    }

    #[test]
    fn solves_the_digest_uniform_collocation_matrix() {
        // digest T.1: exact matrix of (1) for uniform parameters, p = 3
        let rows = vec![
            (0, vec![1.0]),
            (0, vec![1.0 / 8.0, 19.0 / 32.0, 1.0 / 4.0, 1.0 / 32.0]),
            (1, vec![1.0 / 4.0, 1.0 / 2.0, 1.0 / 4.0]),
            (1, vec![1.0 / 32.0, 1.0 / 4.0, 19.0 / 32.0, 1.0 / 8.0]),
            (4, vec![1.0]),
        ];
        let q = [0.0, 0.0, 3.0, 4.0, -1.0, 4.0, -4.0, 0.0, -4.0, -3.0];
        let mut x = q.to_vec();
        let lu = factor_rows(&rows, 2, 2, &mut x, 2, false).unwrap();
        lu.back_substitute(&mut x, 2);
        let expect = [
            0.0,
            0.0,
            58.0 / 9.0,
            67.0 / 18.0,
            -8.0 / 3.0,
            7.5,
            -46.0 / 9.0,
            -49.0 / 18.0,
            -4.0,
            -3.0,
        ];
        for (a, b) in x.iter().zip(expect) {
            assert!((a - b).abs() < 1e-14, "{a} vs {b}");
        }
        let back = mat_vec(&rows, &x, 2);
        for (a, b) in back.iter().zip(q) {
            assert!((a - b).abs() < 1e-14, "residual {a} vs {b}");
        }
    }

    #[test]
    fn kept_factors_solve_further_rhs_and_thomas_matches() {
        // tridiagonal (Thomas) system with a known solution
        let n = 7;
        let rows: Vec<(usize, Vec<f64>)> = (0..n)
            .map(|r| match r {
                0 => (0, vec![4.0, 1.0]),
                r if r == n - 1 => (r - 1, vec![1.0, 3.0]),
                r => (r - 1, vec![1.0, 5.0, 2.0]),
            })
            .collect();
        let x_true: Vec<f64> = (0..n).map(|i| (i as f64).sin() + 2.0).collect();
        let b = mat_vec(&rows, &x_true, 1);
        let mut first = b.clone();
        let lu = factor_rows(&rows, 1, 1, &mut first, 1, true).unwrap();
        lu.back_substitute(&mut first, 1);
        let mut again = b.clone();
        lu.solve(&mut again, 1);
        for i in 0..n {
            assert!((first[i] - x_true[i]).abs() < 1e-14, "fused {i}");
            assert!((again[i] - x_true[i]).abs() < 1e-14, "kept {i}");
        }
    }

    #[test]
    fn zero_pivot_is_singular_system() {
        let rows = vec![(0, vec![1.0, 1.0]), (0, vec![1.0, 1.0])];
        let mut rhs = vec![1.0, 2.0];
        let e = factor_rows(&rows, 1, 1, &mut rhs, 1, false).unwrap_err();
        assert!(matches!(e, Error::SingularSystem { .. }), "{e:?}");
    }

    #[test]
    fn pivot_growth_is_ill_conditioned() {
        // tiny first pivot: no pivoting makes the factors explode
        let rows = vec![(0, vec![1e-12, 1.0]), (0, vec![1.0, 1.0])];
        let mut rhs = vec![1.0, 2.0];
        let e = factor_rows(&rows, 1, 1, &mut rhs, 1, false).unwrap_err();
        assert!(matches!(e, Error::IllConditioned { .. }), "{e:?}");
    }

    /// Dense `n × n` matrix of banded rows `(first column, values)`, row-major.
    fn dense(rows: &[(usize, Vec<f64>)]) -> Vec<f64> {
        let n = rows.len();
        let mut a = vec![0.0; n * n];
        for (r, (c0, vals)) in rows.iter().enumerate() {
            for (t, v) in vals.iter().enumerate() {
                a[r * n + c0 + t] = *v;
            }
        }
        a
    }

    /// Exact (to rounding) `κ_1 = ‖A‖_1·‖A⁻¹‖_1` of a dense matrix: the inverse by Gauss–Jordan
    /// elimination with partial pivoting (test-only reference, O(n³)).
    fn dense_kappa1(a: &[f64], n: usize) -> f64 {
        let col_norm = |m: &[f64]| {
            (0..n)
                .map(|c| (0..n).map(|r| m[r * n + c].abs()).sum::<f64>())
                .fold(0.0_f64, f64::max)
        };
        let mut inv = vec![0.0; n * n];
        for c in 0..n {
            // column c of A⁻¹: solve A·x = e_c with the pivoting dense solver
            let mut m = a.to_vec();
            let mut e = vec![0.0; n];
            e[c] = 1.0;
            solve_dense(&mut m, &mut e, n, 1).unwrap();
            for r in 0..n {
                inv[r * n + c] = e[r];
            }
        }
        col_norm(a) * col_norm(&inv)
    }

    fn estimate(rows: &[(usize, Vec<f64>)], kl: usize, ku: usize) -> Result<f64> {
        let mut lu = BandedCrout::new_estimating(rows.len(), kl, ku);
        let mut buf = vec![0.0; lu.width()];
        let mut rhs = vec![0.0; rows.len()];
        for (r, (c0, vals)) in rows.iter().enumerate() {
            buf.fill(0.0);
            for (t, v) in vals.iter().enumerate() {
                buf[c0 + t + kl - r] = *v;
            }
            lu.push_row(&mut buf, &mut rhs, 1, 0.0)?;
        }
        Ok(lu.condition_estimate().unwrap())
    }

    /// Banded rows with `kl`, `ku` from row-major band values `band[r][0..kl+1+ku]`.
    fn band_rows(band: &[Vec<f64>], kl: usize) -> Vec<(usize, Vec<f64>)> {
        let n = band.len();
        band.iter()
            .enumerate()
            .map(|(r, b)| {
                let c0 = r.saturating_sub(kl);
                let skip = c0 + kl - r;
                let end = (b.len()).min(n + kl - r);
                (c0, b[skip..end].to_vec())
            })
            .collect()
    }

    #[test]
    fn single_vector_and_transposed_solves_match_the_dense_matrix() {
        // nonsymmetric; band widths with fixed kernels and without (generic loops)
        let n = 9;
        for (kl, ku) in [(2, 1), (1, 1), (2, 2), (3, 2), (0, 2), (4, 4), (1, 0)] {
            let band: Vec<Vec<f64>> = (0..n)
                .map(|r| {
                    let x = r as f64;
                    (0..kl + 1 + ku)
                        .map(|m| {
                            if m == kl {
                                6.0 + x.cos()
                            } else {
                                (x * 0.7 + m as f64).sin()
                            }
                        })
                        .collect()
                })
                .collect();
            let rows = band_rows(&band, kl);
            let a = dense(&rows);
            let mut rhs = vec![0.0; n];
            let lu = factor_rows(&rows, kl, ku, &mut rhs, 1, true).unwrap();
            let x_true: Vec<f64> = (0..n).map(|i| 1.0 + (i as f64 * 0.7).cos()).collect();
            // b = A·x and c = Aᵀ·x
            let (mut b, mut c) = (vec![0.0; n], vec![0.0; n]);
            for r in 0..n {
                for col in 0..n {
                    b[r] += a[r * n + col] * x_true[col];
                    c[col] += a[r * n + col] * x_true[r];
                }
            }
            lu.solve_vector(&mut b);
            lu.solve_transposed(&mut c);
            for i in 0..n {
                assert!(
                    (b[i] - x_true[i]).abs() < 1e-14,
                    "({kl}, {ku}) A: x[{i}] = {}",
                    b[i]
                );
                assert!(
                    (c[i] - x_true[i]).abs() < 1e-14,
                    "({kl}, {ku}) Aᵀ: x[{i}] = {}",
                    c[i]
                );
            }
        }
    }

    #[test]
    fn condition_estimate_of_the_second_difference_matrix_is_exact() {
        // T = tridiag(−1, 2, −1): (T⁻¹)_ij = min(i,j)·(n+1−max(i,j))/(n+1) (1-based), so
        // ‖T‖_1 = 4 and ‖T⁻¹‖_1 = max_j j·(n+1−j)/2: κ_1 = 2·⌊(n+1)/2⌋·⌈(n+1)/2⌉ ~ n²/2
        for n in [3usize, 4, 10, 31, 100] {
            let rows: Vec<(usize, Vec<f64>)> = (0..n)
                .map(|r| match r {
                    0 => (0, vec![2.0, -1.0]),
                    r if r == n - 1 => (r - 1, vec![-1.0, 2.0]),
                    r => (r - 1, vec![-1.0, 2.0, -1.0]),
                })
                .collect();
            let half = n.div_ceil(2);
            let closed = 2.0 * (half * (n + 1 - half)) as f64;
            let exact = dense_kappa1(&dense(&rows), n);
            assert!(
                (exact - closed).abs() <= 1e-12 * closed,
                "dense {exact} vs {closed}"
            );
            let est = estimate(&rows, 1, 1).unwrap();
            assert!(
                est >= exact / 3.0 && est <= exact * (1.0 + 1e-12),
                "n {n}: estimate {est}, exact {exact}"
            );
        }
    }

    #[test]
    fn condition_estimate_of_small_systems() {
        // 1 × 1: κ = 1; 0 rows: 1 by convention; identity: 1
        assert_eq!(estimate(&[(0, vec![-3.0])], 0, 0).unwrap(), 1.0);
        assert_eq!(estimate(&[], 1, 1).unwrap(), 1.0);
        let eye: Vec<(usize, Vec<f64>)> = (0..5).map(|r| (r, vec![1.0])).collect();
        assert_eq!(estimate(&eye, 2, 2).unwrap(), 1.0);
        // without the estimating constructor there is no estimate
        let lu = BandedCrout::new(3, 1, 1, true);
        assert!(lu.condition_estimate().is_none());
    }

    #[test]
    fn condition_estimate_of_a_nearly_singular_collocation_pair() {
        // two rows that differ by 1e-10: κ_1 ≈ 2e10, which the estimate finds
        let rows = vec![
            (0, vec![1.0, 0.0, 0.0]),
            (0, vec![0.25, 0.5, 0.25]),
            (0, vec![0.25, 0.5 + 1e-10, 0.25 - 1e-10]),
        ];
        let exact = dense_kappa1(&dense(&rows), 3);
        let est = estimate(&rows, 2, 2).unwrap();
        assert!(exact > 1e10, "{exact}");
        assert!(
            est >= exact / 3.0 && est <= exact * (1.0 + 1e-5),
            "{est} vs {exact}"
        );
    }

    /// A random banded matrix, diagonally dominant by the factor `dom` (so that elimination
    /// without pivoting applies and `κ_1` is moderate): rows of `kl + 1 + ku` band entries.
    fn dominant_band(kl: usize, ku: usize, raw: &[(Vec<f64>, f64, bool)]) -> Vec<Vec<f64>> {
        raw.iter()
            .map(|(v, dom, neg)| {
                let mut b: Vec<f64> = v[3 - kl..4 + ku].to_vec();
                let off: f64 = b.iter().map(|x| x.abs()).sum::<f64>() - b[kl].abs();
                let d = dom * off.max(0.1);
                b[kl] = if *neg { -d } else { d };
                b
            })
            .collect()
    }

    /// The estimate is a lower bound of the dense `κ_1` by construction (it is `‖A‖_1` times the
    /// norm of a computed column combination of A⁻¹), and `‖A‖_1` is exact. How close the bound
    /// comes is not guaranteed (Higham 1988 shows matrices where Hager's method is off by any
    /// factor), so the quality is checked on a fixed sample in
    /// `condition_estimate_is_usually_within_three`, not per random case.
    fn check_estimate(band: &[Vec<f64>], kl: usize, ku: usize) -> (f64, f64) {
        let n = band.len();
        let rows = band_rows(band, kl);
        let a = dense(&rows);
        let exact = dense_kappa1(&a, n);
        let est = estimate(&rows, kl, ku).unwrap();
        let mut lu = BandedCrout::new_estimating(n, kl, ku);
        let mut rhs = vec![0.0; n];
        for (r, b) in band.iter().enumerate() {
            let mut row: Vec<f64> = b.clone();
            for (m, v) in row.iter_mut().enumerate() {
                if r + m < kl || r + m >= n + kl {
                    *v = 0.0;
                }
            }
            lu.push_row(&mut row, &mut rhs, 1, 0.0).unwrap();
        }
        let dense_norm = (0..n)
            .map(|c| (0..n).map(|r| a[r * n + c].abs()).sum::<f64>())
            .fold(0.0_f64, f64::max);
        // ‖A‖_1 from the ring of open column sums: the same sums as the dense ones
        assert_eq!(lu.norm1(), Some(dense_norm));
        assert!(
            est <= exact * (1.0 + 1e-12),
            "estimate {est} above exact {exact}"
        );
        (est, exact)
    }

    proptest::proptest! {
        #![proptest_config(crate::oracle::proptest_config(64))]

        /// Random banded matrices: `‖A‖_1` exact, the estimate never above the dense `κ_1`.
        #[test]
        fn condition_estimate_is_a_lower_bound(
            kl in 0usize..4,
            ku in 0usize..4,
            raw in proptest::collection::vec(
                (proptest::collection::vec(-1.0_f64..1.0, 7), 1.01_f64..3.0, proptest::bool::ANY),
                1..25,
            ),
        ) {
            check_estimate(&dominant_band(kl, ku, &raw), kl, ku);
        }
    }

    /// On a fixed sample of 2000 random banded matrices (a deterministic generator), the
    /// estimate is within a factor 3 of the dense `κ_1` in at least 99 % of cases and within a
    /// factor 10 in all (Higham's observation for Hager's method). Measured: all 2000 within 3,
    /// worst ratio 0.36; a random draw once gave 0.30, which is why the per-case property
    /// test checks only the lower-bound side.
    #[test]
    fn condition_estimate_is_usually_within_three() {
        let mut state: u64 = 0x2545_f491_4f6c_dd1d;
        let mut next = move || {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            state >> 11
        };
        let scale = 1.0 / (1u64 << 53) as f64;
        let (mut within3, mut worst) = (0, f64::INFINITY);
        let cases = 2000;
        for _ in 0..cases {
            let kl = usize::try_from(next() % 4).unwrap_or(0);
            let ku = usize::try_from(next() % 4).unwrap_or(0);
            let n = 1 + usize::try_from(next() % 24).unwrap_or(0);
            let raw: Vec<(Vec<f64>, f64, bool)> = (0..n)
                .map(|_| {
                    let v = (0..7)
                        .map(|_| 2.0 * (next() as f64 * scale) - 1.0)
                        .collect();
                    (
                        v,
                        1.01 + 1.99 * (next() as f64 * scale),
                        (next() as f64 * scale) < 0.5,
                    )
                })
                .collect();
            let (est, exact) = check_estimate(&dominant_band(kl, ku, &raw), kl, ku);
            let ratio = est / exact;
            worst = worst.min(ratio);
            if ratio >= 1.0 / 3.0 {
                within3 += 1;
            }
        }
        assert!(
            within3 * 100 >= cases * 99,
            "{within3} of {cases} within 3; worst {worst}"
        );
        assert!(worst >= 0.1, "worst ratio {worst}");
    }

    #[test]
    fn cubic_basis_matches_cox_de_boor() {
        use crate::basis::{basis_funs_into, BasisScratch};
        // uneven knots on four scales, down to 1e-60 and up to 1e60
        let base = [
            0.0, 0.0, 0.0, 0.0, 0.1, 0.13, 0.4, 0.41, 0.7, 1.0, 1.0, 1.0, 1.0,
        ];
        let mut scratch = BasisScratch::new(3);
        let mut reference = [0.0; 4];
        for scale in [1.0, 1e-8, 1e-60, 1e60] {
            let knots: Vec<f64> = base.iter().map(|u| u * scale).collect();
            for span in 3..knots.len() - 4 {
                for k in 0..=16 {
                    let s = f64::from(k) / 16.0;
                    let t = knots[span] + s * (knots[span + 1] - knots[span]);
                    if t >= knots[span + 1] {
                        continue;
                    }
                    basis_funs_into(&knots, 3, span, t, &mut scratch, &mut reference);
                    let recip = ReciprocalBlock::new(&knots, span - 2).window(span);
                    let fast = cubic_basis(&knots, &recip, span, t);
                    for (f, e) in fast.iter().zip(&reference) {
                        // a few ulps of the partition of unity's scale (the values sum to 1)
                        assert!(
                            (f - e).abs() <= 8.0 * f64::EPSILON,
                            "span {span}, t {t}: {fast:?} vs {reference:?}"
                        );
                    }
                    let sum: f64 = fast.iter().sum();
                    assert!(
                        (sum - 1.0).abs() <= 4.0 * f64::EPSILON,
                        "partition of unity {sum}"
                    );
                }
            }
        }
    }

    #[test]
    fn dense_solver_pivots_and_detects_singularity() {
        let mut a = vec![0.0, 1.0, 2.0, 1.0];
        let mut b = vec![3.0, 5.0];
        solve_dense(&mut a, &mut b, 2, 1).unwrap();
        // x + 2·y... rows: [0 1; 2 1] x = [3; 5] → y = 3, x = 1
        assert!(
            (b[0] - 1.0).abs() < 1e-15 && (b[1] - 3.0).abs() < 1e-15,
            "{b:?}"
        );
        let mut a = vec![1.0, 2.0, 2.0, 4.0];
        let mut b = vec![1.0, 1.0];
        assert!(matches!(
            solve_dense(&mut a, &mut b, 2, 1),
            Err(Error::SingularSystem { .. })
        ));
    }
}
