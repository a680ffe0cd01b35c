//! The fused cubic collocation sweep of global interpolation (crate-private): reciprocals of
//! knot differences a block at a time, the four cubic basis functions of a row by Cox–de Boor
//! with those reciprocals, and the forward elimination and back substitution of the pentadiagonal
//! system fused with the row construction. The fast path of [`crate::numeric::linalg::BandedCrout`] for
//! the free-end cubic with averaged knots (document 000 §1), used by `interpolate_fast`.

use crate::numeric::linalg::{MAX_GROWTH, SINGULAR_PIVOT};

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

crate::numeric::isa::avx2_dispatch! {
    /// Fills a [`ReciprocalBlock`] from knot `base` on, compiled with AVX2 (4-wide divisions)
    /// where the processor has it ([`crate::numeric::isa`]; the same bits either way). Kept out of line:
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
fn cubic_basis(knots: &[f64], recip: &[[f64; 3]; 3], span: usize, t: f64) -> [f64; 4] {
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

crate::numeric::isa::avx2_dispatch! {
    /// [`solve_free_cubic_body`] compiled with AVX2 where the processor has it, else as built
    /// ([`crate::numeric::isa`]: the same bits, tested in `interpolate_fast`).
    pub(crate) fn solve_free_cubic<const D: usize>(
        q: &[f64],
        knots: &[f64],
        control: &mut [f64],
        upper: &mut Vec<[f64; 2]>,
    ) -> bool = solve_free_cubic_body;
}

/// Fused collocation solve of the free-end cubic interpolant with averaged knots (document 000
/// §1 eq. 1 and 3, P&T Algorithm A9.1): the fast path of
/// [`crate::numeric::linalg::BandedCrout::push_row`] +
/// [`crate::numeric::linalg::BandedCrout::back_substitute`] with Cox–de Boor rows (P&T A2.2, see [`cubic_basis`]).
///
/// `q` holds the `n + 1` points (`D` coordinates each) and `knots` the `n + 5` averaged knots;
/// `control` (`(n + 1)·D` numbers) holds on entry the parameter `t̄_r` of point `r` in
/// `control[r·D]` (the other entries are ignored) and on return the control points
/// (`P_0 = q_0`, `P_n = q_n`). Returns `false` when a row does not fit the band `kl = ku = 2`,
/// a pivot or the growth fails the checks of [`crate::numeric::linalg::BandedCrout`], or a result overflows (data near
/// the largest `f64`): the caller then takes the general path, which reports the precise error.
///
/// The rows are built and eliminated as the parameters are swept; only the two previous rows
/// of `U` and of the forward-solved right-hand side are live during the sweep (in registers).
/// Row `r` of the forward-solved right-hand side replaces `t̄_r`, which is read just before,
/// so the parameters need no buffer of their own; `U` (two numbers a row, in `upper`, grown to
/// `n` rows if shorter and otherwise reused as it is: every row read is written first) is stored
/// for the back substitution, which writes the final, un-centred control points in place. The data are
/// centred on `q_0` (see [`crate::interpolate::curve`]). The elimination is that of the general path
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
        *upper = crate::numeric::large_buffer::reuse_or_zeroed(upper, n);
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

#[cfg(test)]
mod tests {
    use super::*;

    /// The AVX2 copy of a reciprocal block holds the baseline's bits, for a block in the
    /// middle of the knots and a short one at their end.
    #[cfg(target_arch = "x86_64")]
    #[test]
    fn reciprocal_blocks_agree_bit_for_bit() {
        if !crate::numeric::isa::has_avx2() {
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
}
