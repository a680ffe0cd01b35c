//! Banded linear systems solved by elimination without pivoting (crate-private).
//!
//! B-spline collocation matrices are banded and totally positive (de Boor, "Total positivity of
//! the spline collocation matrix", Indiana Univ. Math. J. 26, 1977); Gaussian elimination without
//! pivoting is then stable (de Boor & Pinkus, "Backward error analysis for totally positive
//! linear systems", Numer. Math. 27, 1977). Document 000 (§1, step 4) prescribes exactly
//! this: "banded Gaussian elimination without pivoting".
//!
//! [`BandedCrout`] eliminates one row at a time (Crout form `A = L·U`, `U` unit upper
//! triangular), so a caller can build each matrix row straight from the basis kernel into a
//! small buffer and never store the matrix. With `kl = ku = 1` the sweep is the Thomas algorithm
//! ("progonka", docs/theory/interpolation.md#thomas-algorithm): `m = β_i − α_i γ'_{i−1}`, `γ'_i =
//! γ_i / m`, `r'_i = (r_i − α_i r'_{i−1}) / m`, then `x_i = r'_i − γ'_i x_{i+1}`.
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
pub(crate) const SINGULAR_PIVOT: f64 = 64.0 * f64::EPSILON;

/// Largest accepted growth of the factors' entries relative to the largest matrix entry. For
/// totally positive matrices the growth is at most 1; a growth beyond this means the system is
/// too ill-conditioned to solve to the promised accuracy without pivoting.
pub(crate) const MAX_GROWTH: f64 = 1e8;

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

/// Euclidean norm, scaled by the largest magnitude against overflow and underflow (the
/// largest magnitude itself when it is zero or not finite).
pub(crate) fn norm2(v: &[f64]) -> f64 {
    let m = v.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    if m == 0.0 || !m.is_finite() {
        return m;
    }
    m * v.iter().map(|x| (x / m) * (x / m)).sum::<f64>().sqrt()
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
mod tests;
