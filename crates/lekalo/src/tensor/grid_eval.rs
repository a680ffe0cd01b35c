//! Evaluation of a [`TensorBSpline`] on the grid `X_0 × ⋯ × X_{N−1}` (the outer product of
//! one parameter list per direction) without forming the grid's points:
//! `docs/theory/tensor.md#evaluation-on-grids`.

use rayon::prelude::*;

use crate::basis::basis_funs_fixed;
use crate::error::{Error, Result};
use crate::knots::SpanCursor;
use crate::tensor::contract::{accumulate, basis_vector, TensorScratch};
use crate::tensor::spline::{checked_size, TensorBSpline};
use crate::tensor::view::TensorBSplineRef;

/// Basis vectors and spans of one direction at every parameter of its list.
struct AxisTable {
    spans: Vec<usize>,
    /// `(p + 1)` numbers a parameter.
    values: Vec<f64>,
}

impl TensorBSpline {
    /// `S` (or the partial derivative of `orders`, see [`TensorBSpline::eval_partial`]) at every
    /// point of the grid `axes[0] × ⋯ × axes[N−1]` into `out`, point `(i_0, …, i_{N−1})` at
    /// `((…(i_0·m_1 + i_1)…)·m_{N−1} + i_{N−1})·dim` (`m_a = axes[a].len()`, the first direction
    /// slowest, as the control net). The parameter lists may come in any order.
    ///
    /// The basis vectors of each direction are computed once per parameter (`Σ_a m_a`
    /// evaluations instead of `N·Π_a m_a`). Then, when it is cheaper than point by point, sum
    /// factorisation over the whole net, depth first: for each `i_0`, direction 0 is contracted
    /// into `C_1 = Σ_j N_{0,j}(x_{0,i_0})·P_{j,·}` (`Π_{a≥1} n_a·dim` numbers), for each `i_1`
    /// direction 1 of `C_1` into `C_2`, and so on; cost `Σ_a (Π_{b≤a} m_b)·(p_a + 1)·Π_{b>a} n_b·dim`
    /// against `Π_a m_a·Π_a (p_a + 1)·dim` point by point, memory `Σ_a Π_{b>a} n_b·dim`
    /// (`docs/theory/tensor.md#evaluation-on-grids`). Either way each value is computed by the
    /// same operations on the same numbers as [`TensorBSpline::eval`] (or `eval_partial`) at that
    /// point: the result is the same bit for bit (tested).
    ///
    /// ```
    /// use lekalo::{Points, TensorBSpline};
    /// // f(x, y, z) = x + 2y + 3z, trilinear on [0, 1]³
    /// let mut net = Vec::new();
    /// for i in 0..2 { for j in 0..2 { for k in 0..2 { net.push(f64::from(i + 2 * j + 3 * k)); } } }
    /// let k = vec![0.0, 0.0, 1.0, 1.0];
    /// let s = TensorBSpline::new(vec![1, 1, 1], vec![k.clone(), k.clone(), k], Points::from_flat(1, net)?)?;
    /// let (xs, ys, zs) = ([0.0, 0.5, 1.0], [0.25, 0.75], [0.5]);
    /// let mut out = vec![0.0; 3 * 2 * 1];
    /// s.eval_grid(&[&xs, &ys, &zs], None, &mut out)?;
    /// assert_eq!(out[1 * 2 + 1], 0.5 + 2.0 * 0.75 + 3.0 * 0.5);
    /// assert_eq!(out[1 * 2 + 1], s.eval(&[0.5, 0.75, 0.5])?[0]);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::LengthMismatch`] if `axes.len() != N`, `orders.len() != N` or `out` does not
    /// hold `Π_a m_a·dim` numbers; [`Error::TooLarge`] if that product overflows or exceeds
    /// [`MAX_SCALARS`](crate::MAX_SCALARS) (checked before anything is computed);
    /// [`Error::ParameterOutOfDomain`] for a parameter outside its direction's domain;
    /// [`Error::TooLarge`] for a derivative order above
    /// [`MAX_DERIVATIVE_ORDER`](crate::MAX_DERIVATIVE_ORDER).
    pub fn eval_grid(
        &self,
        axes: &[&[f64]],
        orders: Option<&[usize]>,
        out: &mut [f64],
    ) -> Result<()> {
        self.view().eval_grid(axes, orders, out)
    }
}

impl TensorBSplineRef<'_> {
    /// As [`TensorBSpline::eval_grid`].
    ///
    /// # Errors
    /// As [`TensorBSpline::eval_grid`].
    pub fn eval_grid(
        &self,
        axes: &[&[f64]],
        orders: Option<&[usize]>,
        out: &mut [f64],
    ) -> Result<()> {
        let n = self.n_vars();
        let dim = self.dim();
        if axes.len() != n {
            return Err(Error::LengthMismatch {
                what: "grid parameter lists (one per direction)".into(),
                expected: n,
                got: axes.len(),
            });
        }
        let m: Vec<usize> = axes.iter().map(|a| a.len()).collect();
        let size = checked_size("grid values (product of the list lengths × dim)", &m, dim)?;
        if out.len() != size {
            return Err(Error::LengthMismatch {
                what: "grid output (product of the list lengths × dim)".into(),
                expected: size,
                got: out.len(),
            });
        }
        let mut scratch = TensorScratch::new(self, orders)?;
        if size == 0 {
            return Ok(());
        }
        let tables = self.axis_tables(axes, orders)?;
        if self.grid_cost(&m) < self.pointwise_cost(&m) {
            if n == 2 && dim == 1 {
                // blocks of rows of direction 0, on the thread pool when the grid is large
                let rows = ROWS * PAR_ROW_BLOCKS;
                let (t0, t1) = (&tables[0], &tables[1]);
                let w = self.degrees[0] + 1;
                let block = |(i, o): (usize, &mut [f64])| {
                    let at = i * rows;
                    let count = o.len() / m[1];
                    let spans = &t0.spans[at..at + count];
                    last_two(
                        self,
                        self.net,
                        spans,
                        &t0.values[at * w..(at + count) * w],
                        t1,
                        o,
                    );
                };
                if size >= PAR_MIN_VALUES {
                    out.par_chunks_mut(rows * m[1]).enumerate().for_each(block);
                } else {
                    out.chunks_mut(rows * m[1]).enumerate().for_each(block);
                }
            } else if n > 1 && size >= PAR_MIN_VALUES {
                // the rows of the first direction on the thread pool, each with its buffers
                let row = size / m[0];
                let table = &tables[0];
                let p = self.degrees[0];
                let len = self.stride(0);
                out.par_chunks_mut(row)
                    .zip(table.spans.par_iter())
                    .zip(table.values.par_chunks_exact(p + 1))
                    .for_each_init(
                        || -> Vec<Vec<f64>> {
                            (1..n).map(|a| vec![0.0; self.stride(a - 1)]).collect()
                        },
                        |buffers, ((o, &span), nv)| {
                            let (buf, rest) = buffers
                                .split_first_mut()
                                .expect("a buffer per direction after the first");
                            for (j, &v) in nv.iter().enumerate() {
                                let at = (span - p + j) * len;
                                accumulate(buf, v, &self.net[at..at + len], j == 0);
                            }
                            grid_rec(self, 1, buf, &tables, rest, o);
                        },
                    );
            } else {
                let mut buffers: Vec<Vec<f64>> =
                    (1..n).map(|a| vec![0.0; self.stride(a - 1)]).collect();
                grid_rec(self, 0, self.net, &tables, &mut buffers, out);
            }
        } else {
            self.grid_pointwise(&m, &tables, &mut scratch, out);
        }
        Ok(())
    }

    /// Spans and basis vectors of every direction at its parameters.
    fn axis_tables(&self, axes: &[&[f64]], orders: Option<&[usize]>) -> Result<Vec<AxisTable>> {
        let mut tables = Vec::with_capacity(axes.len());
        for (a, xs) in axes.iter().enumerate() {
            let p = self.degrees[a];
            let knots = self.knots[a];
            let mut cursor = SpanCursor::over(knots, p);
            let mut spans = Vec::with_capacity(xs.len());
            let mut values = vec![0.0; xs.len() * (p + 1)];
            let k = orders.map_or(0, |k| k[a]);
            let mut basis = crate::basis::BasisScratch::new(p);
            let mut ders = vec![0.0; (k.min(p) + 1) * (p + 1)];
            for (&x, v) in xs.iter().zip(values.chunks_exact_mut(p + 1)) {
                let span = cursor.find(x)?;
                // values of degree ≤ 5: the fixed-order triangle (the same operations, so the
                // same bits), the general one otherwise
                match (k, p) {
                    (0, 1) => v.copy_from_slice(&basis_funs_fixed::<2>(knots, span, x)),
                    (0, 2) => v.copy_from_slice(&basis_funs_fixed::<3>(knots, span, x)),
                    (0, 3) => v.copy_from_slice(&basis_funs_fixed::<4>(knots, span, x)),
                    (0, 4) => v.copy_from_slice(&basis_funs_fixed::<5>(knots, span, x)),
                    (0, 5) => v.copy_from_slice(&basis_funs_fixed::<6>(knots, span, x)),
                    _ => basis_vector(knots, p, span, x, k, &mut basis, &mut ders, v),
                }
                spans.push(span);
            }
            tables.push(AxisTable { spans, values });
        }
        Ok(tables)
    }

    /// Multiply-adds of the depth-first sum factorisation (saturating: an estimate).
    fn grid_cost(&self, m: &[usize]) -> usize {
        let mut points = 1usize;
        let mut cost = 0usize;
        for a in 0..m.len() {
            points = points.saturating_mul(m[a]);
            cost = cost.saturating_add(
                points
                    .saturating_mul(self.degrees[a] + 1)
                    .saturating_mul(self.stride(a)),
            );
        }
        cost
    }

    /// Multiply-adds point by point (saturating: an estimate).
    fn pointwise_cost(&self, m: &[usize]) -> usize {
        let window: usize = self
            .degrees
            .iter()
            .fold(self.dim(), |w, p| w.saturating_mul(p + 1));
        m.iter().fold(window, |c, &k| c.saturating_mul(k))
    }

    /// The grid point by point with the tabulated bases (the kernel of
    /// [`TensorBSpline::eval`]).
    fn grid_pointwise(
        &self,
        m: &[usize],
        tables: &[AxisTable],
        scratch: &mut TensorScratch,
        out: &mut [f64],
    ) {
        let n = self.n_vars();
        let mut index = vec![0usize; n];
        for o in out.chunks_exact_mut(self.dim()) {
            for a in 0..n {
                let w = self.degrees[a] + 1;
                scratch.spans[a] = tables[a].spans[index[a]];
                let at = scratch.offsets[a];
                scratch.values[at..at + w]
                    .copy_from_slice(&tables[a].values[index[a] * w..(index[a] + 1) * w]);
            }
            self.contract_prepared(scratch, o);
            for a in (0..n).rev() {
                index[a] += 1;
                if index[a] < m[a] {
                    break;
                }
                index[a] = 0;
            }
        }
    }
}

/// Grids of at least this many numbers have the rows of their first direction computed on
/// the thread pool.
const PAR_MIN_VALUES: usize = 1 << 14;

/// Contracts direction `a` of `src` (the net of directions `a…N−1`, full size) at every
/// parameter of the direction, recursing into the next direction; at the last direction the
/// values go to `out` (the sub-grid of directions `a…N−1`). Scalar values in the last
/// direction are one dot product of `p + 1` numbers a parameter, summed from the first term
/// as [`accumulate`] does.
fn grid_rec(
    s: &TensorBSplineRef<'_>,
    a: usize,
    src: &[f64],
    tables: &[AxisTable],
    buffers: &mut [Vec<f64>],
    out: &mut [f64],
) {
    let p = s.degrees[a];
    let table = &tables[a];
    let len = s.stride(a);
    if buffers.len() == 1 && s.dim() == 1 {
        // directions N − 2 and N − 1 of scalar values, rows of direction N − 2 in blocks
        last_two(s, src, &table.spans, &table.values, &tables[a + 1], out);
        return;
    }
    if buffers.is_empty() && len == 1 {
        for ((o, &span), nv) in out
            .iter_mut()
            .zip(&table.spans)
            .zip(table.values.chunks_exact(p + 1))
        {
            let w = &src[span - p..=span];
            let mut acc = nv[0] * w[0];
            for j in 1..=p {
                acc += nv[j] * w[j];
            }
            *o = acc;
        }
        return;
    }
    let points = table.spans.len();
    let sub = out.len() / points.max(1);
    for (i, (&span, nv)) in table
        .spans
        .iter()
        .zip(table.values.chunks_exact(p + 1))
        .enumerate()
    {
        let first = span - p;
        if let Some((buf, rest)) = buffers.split_first_mut() {
            for (j, &v) in nv.iter().enumerate() {
                let at = (first + j) * len;
                accumulate(buf, v, &src[at..at + len], j == 0);
            }
            grid_rec(
                s,
                a + 1,
                buf,
                tables,
                rest,
                &mut out[i * sub..(i + 1) * sub],
            );
        } else {
            let o = &mut out[i * sub..(i + 1) * sub];
            for (j, &v) in nv.iter().enumerate() {
                let at = (first + j) * len;
                accumulate(o, v, &src[at..at + len], j == 0);
            }
        }
    }
}

/// Rows of direction `N − 2` per block of [`last_two`].
const ROWS: usize = 4;
/// Blocks of [`ROWS`] rows per task of the parallel 2-D grid.
const PAR_ROW_BLOCKS: usize = 4;

/// The last two directions `a = N − 2`, `b = N − 1` of a scalar spline on the grid
/// `X_a × X_b`: `src` is the net of directions `a, b` (`n_a × n_b` numbers), `spans` and
/// `values` the spans and basis vectors of direction `a` at the rows to compute, `out` their
/// values (`spans.len() × m_b`). The operations of [`grid_rec`] on each number in the same order
/// (so the same bits): for a row `x_a`, `C[k] = Σ_j N_{a,j}(x_a)·src[f + j][k]` summed from the
/// first term; for each `x_b` the dot product `Σ_r N_{b,r}(x_b)·C[g + r]` summed from the
/// first term. The rows go in blocks of [`ROWS`], their `C` stored interleaved (`C[k]` of the
/// block's rows side by side), so that each `x_b` computes [`ROWS`] values with whole-vector
/// operations on neighbouring numbers instead of [`ROWS`] dot products of scattered ones.
/// Compiled again with AVX2 ([`last_two`]), 4-wide vectors, the same bits.
#[inline(always)]
fn last_two_body(
    s: &TensorBSplineRef<'_>,
    src: &[f64],
    spans: &[usize],
    values: &[f64],
    last: &AxisTable,
    out: &mut [f64],
) {
    let n = s.n_vars();
    let (pa, pb) = (s.degrees[n - 2], s.degrees[n - 1]);
    let len = s.shape()[n - 1];
    let m = last.spans.len();
    let mut row = vec![0.0; len];
    let mut c = vec![0.0; len * ROWS];
    let mut tile = vec![0.0; m * ROWS];
    for ((block_spans, block_values), o) in spans
        .chunks(ROWS)
        .zip(values.chunks(ROWS * (pa + 1)))
        .zip(out.chunks_mut(ROWS * m))
    {
        for (r, (&span, nv)) in block_spans
            .iter()
            .zip(block_values.chunks_exact(pa + 1))
            .enumerate()
        {
            for (j, &v) in nv.iter().enumerate() {
                let at = (span - pa + j) * len;
                accumulate(&mut row, v, &src[at..at + len], j == 0);
            }
            for (k, &x) in row.iter().enumerate() {
                c[k * ROWS + r] = x;
            }
        }
        let rows = block_spans.len();
        match pb {
            0 => dots::<1>(&c, last, rows, &mut tile, o),
            1 => dots::<2>(&c, last, rows, &mut tile, o),
            2 => dots::<3>(&c, last, rows, &mut tile, o),
            3 => dots::<4>(&c, last, rows, &mut tile, o),
            4 => dots::<5>(&c, last, rows, &mut tile, o),
            5 => dots::<6>(&c, last, rows, &mut tile, o),
            _ => {
                for (j, (&span, nv)) in last
                    .spans
                    .iter()
                    .zip(last.values.chunks_exact(pb + 1))
                    .enumerate()
                {
                    for r in 0..rows {
                        let at = |q: usize| c[(span - pb + q) * ROWS + r];
                        let mut acc = nv[0] * at(0);
                        for q in 1..=pb {
                            acc += nv[q] * at(q);
                        }
                        o[r * m + j] = acc;
                    }
                }
            }
        }
    }
}

/// The dot products of [`last_two`] for `W = p_b + 1` basis functions: value `(r, j)` of the
/// block is `Σ_q N_{b,q}(x_j)·C_r[g_j + q]`, summed from `q = 0`, for the block's `rows ≤
/// ROWS` rows at once. The values of a column are computed together, as one vector of
/// [`ROWS`] numbers (the runs of `C` are interleaved), and stored together into `tile`
/// (`ROWS` numbers a column); the block's rows are then copied out of `tile`, so that no
/// value is extracted from a vector on its own.
#[inline(always)]
fn dots<const W: usize>(
    c: &[f64],
    last: &AxisTable,
    rows: usize,
    tile: &mut [f64],
    out: &mut [f64],
) {
    let m = last.spans.len();
    let columns = last.spans.iter().zip(last.values.chunks_exact(W));
    for (t, (&span, nv)) in tile.chunks_exact_mut(ROWS).zip(columns) {
        let base = (span + 1 - W) * ROWS;
        let win = &c[base..base + W * ROWS];
        let nv: &[f64; W] = nv.try_into().expect("W basis functions");
        let mut acc = [0.0; ROWS];
        for r in 0..ROWS {
            acc[r] = nv[0] * win[r];
        }
        for q in 1..W {
            for r in 0..ROWS {
                acc[r] += nv[q] * win[q * ROWS + r];
            }
        }
        t.copy_from_slice(&acc);
    }
    for (r, o) in out.chunks_exact_mut(m).take(rows).enumerate() {
        for (o, t) in o.iter_mut().zip(tile.chunks_exact(ROWS)) {
            *o = t[r];
        }
    }
}

crate::numeric::isa::avx2_dispatch! {
    /// [`last_two_body`], with AVX2 where the processor has it (the same bits).
    fn last_two(
        s: &TensorBSplineRef<'_>,
        src: &[f64],
        spans: &[usize],
        values: &[f64],
        last: &AxisTable,
        out: &mut [f64],
    ) = last_two_body;
}
