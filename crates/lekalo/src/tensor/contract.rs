//! The contraction of a tensor-product B-spline at a point (sum factorisation over the window
//! of the spans): the scratch sized once for a spline, the basis vectors of every direction,
//! the general window contraction and the fixed-size kernels of bivariate and trivariate scalar
//! splines.
//! Formulas: `docs/theory/tensor.md#tensor-product-splines`.

use crate::basis::{basis_ders_into, basis_funs_into, BasisScratch};
use crate::error::{check_derivative_order, Result, MAX_DERIVATIVE_ORDER};
use crate::tensor::spline::check_len;
use crate::tensor::view::TensorBSplineRef;

/// Scratch for point evaluation, sized once for a spline (and derivative orders): basis
/// scratch, the basis vectors of each direction, the contraction stages.
#[derive(Debug, Clone)]
pub(crate) struct TensorScratch {
    basis: Vec<BasisScratch>,
    /// Derivative table of one direction (`(k_a + 1) × (p_a + 1)`), for `eval_partial`.
    ders: Vec<f64>,
    pub(crate) spans: Vec<usize>,
    /// The basis vector (or its `k_a`-th derivative) of direction `a` at `offsets[a]..`.
    pub(crate) values: Vec<f64>,
    pub(crate) offsets: Vec<usize>,
    /// Stage `a` of the contraction: `Π_{b > a}(p_b + 1)·dim` numbers.
    stages: Vec<Vec<f64>>,
    odometer: Vec<usize>,
    /// [`TensorBSplineRef::stride`] of every direction.
    strides: Vec<usize>,
}

impl TensorScratch {
    /// # Errors
    /// [`Error::LengthMismatch`] if `orders` does not have one order per direction;
    /// [`Error::TooLarge`] for an order above [`MAX_DERIVATIVE_ORDER`].
    pub(crate) fn new(s: &TensorBSplineRef<'_>, orders: Option<&[usize]>) -> Result<Self> {
        let n = s.n_vars();
        let mut ders_len = 0;
        if let Some(k) = orders {
            check_len("derivative orders (one per direction)", n, k.len())?;
            for (&k, &p) in k.iter().zip(s.degrees) {
                check_derivative_order(k, MAX_DERIVATIVE_ORDER)?;
                ders_len = ders_len.max((k.min(p) + 1) * (p + 1));
            }
        }
        let mut offsets = Vec::with_capacity(n);
        let mut total = 0;
        for &p in s.degrees {
            offsets.push(total);
            total += p + 1;
        }
        let dim = s.dim;
        let stages = (1..n)
            .map(|a| vec![0.0; s.degrees[a..].iter().map(|p| p + 1).product::<usize>() * dim])
            .collect();
        Ok(TensorScratch {
            basis: s.degrees.iter().map(|&p| BasisScratch::new(p)).collect(),
            ders: vec![0.0; ders_len],
            spans: vec![0; n],
            values: vec![0.0; total],
            offsets,
            stages,
            odometer: vec![0; n],
            strides: (0..n).map(|a| s.stride(a)).collect(),
        })
    }

    /// The basis vectors of every direction at `x` (spans already in `self.spans`).
    pub(crate) fn fill_bases(
        &mut self,
        s: &TensorBSplineRef<'_>,
        x: &[f64],
        orders: Option<&[usize]>,
    ) {
        for a in 0..s.n_vars() {
            let p = s.degrees[a];
            let out = &mut self.values[self.offsets[a]..self.offsets[a] + p + 1];
            let k = orders.map_or(0, |k| k[a]);
            basis_vector(
                s.knots[a],
                p,
                self.spans[a],
                x[a],
                k,
                &mut self.basis[a],
                &mut self.ders,
                out,
            );
        }
    }
}

/// The `k`-th derivatives of the `p + 1` non-zero basis functions at `t` into `out`: A2.2 for
/// `k = 0`, row `k` of A2.3 for `0 < k ≤ p`, zeros above `p`.
#[allow(clippy::too_many_arguments)]
pub(crate) fn basis_vector(
    knots: &[f64],
    p: usize,
    span: usize,
    t: f64,
    k: usize,
    scratch: &mut BasisScratch,
    ders: &mut [f64],
    out: &mut [f64],
) {
    if k == 0 {
        basis_funs_into(knots, p, span, t, scratch, out);
    } else if k > p {
        out.fill(0.0);
    } else {
        let table = &mut ders[..(k + 1) * (p + 1)];
        basis_ders_into(knots, p, span, t, k, scratch, table);
        out.copy_from_slice(&table[k * (p + 1)..]);
    }
}

/// `acc ← n·x` (first term) or `acc ← acc + n·x`, element by element: the one accumulation
/// step of every contraction in this module, so that the point, grid and slice paths perform
/// the same operations on each number.
#[inline(always)]
pub(crate) fn accumulate(acc: &mut [f64], n: f64, x: &[f64], first: bool) {
    if first {
        for (a, v) in acc.iter_mut().zip(x) {
            *a = n * v;
        }
    } else {
        for (a, v) in acc.iter_mut().zip(x) {
            *a += n * v;
        }
    }
}

impl TensorBSplineRef<'_> {
    /// The contraction of the window ([`contract_window`]) with the spans and basis vectors
    /// already in `scratch`.
    pub(crate) fn contract_prepared(&self, scratch: &mut TensorScratch, out: &mut [f64]) {
        let TensorScratch {
            spans,
            values,
            offsets,
            stages,
            odometer,
            strides,
            ..
        } = scratch;
        let window = Window {
            spans,
            values,
            offsets,
            strides,
        };
        contract_window(self, &window, stages, odometer, out);
    }
}

/// The point's window: spans, basis vectors (direction `a` at `offsets[a]..`) and the net's
/// strides.
#[derive(Clone, Copy)]
struct Window<'a> {
    spans: &'a [usize],
    values: &'a [f64],
    offsets: &'a [usize],
    strides: &'a [usize],
}

/// Sum factorisation over the window of the spans: stage 1 contracts direction 0 straight
/// from the net, `B_1[r] = Σ_j N_0[j]·P[(s_0 − p_0 + j), r]` for `r` in the window of
/// directions `1…N−1` (walked by an odometer, the last direction contiguous); stage `a + 1`
/// contracts direction `a` of the dense stage `a`. The grid path performs the same operations
/// on each number (`grid_eval.rs`).
fn contract_window(
    s: &TensorBSplineRef<'_>,
    w: &Window<'_>,
    stages: &mut [Vec<f64>],
    odometer: &mut [usize],
    out: &mut [f64],
) {
    let Window {
        spans,
        values,
        offsets,
        strides,
    } = *w;
    let n = s.n_vars();
    let dim = s.dim;
    let net = s.net;
    let p0 = s.degrees[0];
    let n0 = &values[offsets[0]..offsets[0] + p0 + 1];
    let first0 = spans[0] - p0;
    let stride0 = strides[0];
    if (n == 2 || n == 3) && dim == 1 {
        if let Some(v) = contract_scalar_fixed(s, w) {
            out[0] = v;
            return;
        }
    }
    if n == 1 {
        for (j, &v) in n0.iter().enumerate() {
            let at = (first0 + j) * dim;
            accumulate(out, v, &net[at..at + dim], j == 0);
        }
        return;
    }
    // stage 1: odometer over the window of directions 1..n−1 except the last, runs of
    // (p_last + 1)·dim contiguous numbers
    let last = n - 1;
    let run = (s.degrees[last] + 1) * dim;
    let run_start = (spans[last] - s.degrees[last]) * dim;
    let stage1 = &mut stages[0];
    odometer.fill(0);
    let mut pos = 0;
    loop {
        let mut base = run_start;
        for b in 1..last {
            base += (spans[b] - s.degrees[b] + odometer[b]) * strides[b];
        }
        let acc = &mut stage1[pos..pos + run];
        for (j, &v) in n0.iter().enumerate() {
            let at = (first0 + j) * stride0 + base;
            accumulate(acc, v, &net[at..at + run], j == 0);
        }
        pos += run;
        // advance directions last−1 … 1
        let mut b = last;
        loop {
            b -= 1;
            if b == 0 {
                break;
            }
            odometer[b] += 1;
            if odometer[b] <= s.degrees[b] {
                break;
            }
            odometer[b] = 0;
        }
        if b == 0 {
            break;
        }
    }
    // stages 2..n: dense contractions of the leading direction of stage a into stage a + 1,
    // the last into `out`
    let contract = |a: usize, src: &[f64], dst: &mut [f64]| {
        let p = s.degrees[a];
        let na = &values[offsets[a]..offsets[a] + p + 1];
        let len = src.len() / (p + 1);
        for (j, &v) in na.iter().enumerate() {
            accumulate(dst, v, &src[j * len..(j + 1) * len], j == 0);
        }
    };
    for a in 1..last {
        let (done, next) = stages.split_at_mut(a);
        contract(a, &done[a - 1], &mut next[0]);
    }
    contract(last, &stages[last - 1], out);
}

/// [`contract_window`] for two or three directions, scalar values and one degree `p ≤ 5` in
/// every direction, with the window's sizes known at compile time: the same operations on each
/// number in the same order (so the same bits), without the odometer and the run-length loops.
/// Written out by hand because this contraction is the whole cost of a point of a bivariate or
/// trivariate lookup table; `None` for the other cases.
fn contract_scalar_fixed(s: &TensorBSplineRef<'_>, w: &Window<'_>) -> Option<f64> {
    let d = s.degrees;
    if d.iter().any(|&p| p != d[0]) {
        return None;
    }
    let basis = |a: usize| &w.values[w.offsets[a]..w.offsets[a] + d[a] + 1];
    if d.len() == 2 {
        let first = [w.spans[0] - d[0], w.spans[1] - d[1]];
        let (b0, b1, stride) = (basis(0), basis(1), w.strides[0]);
        return Some(match d[0] {
            1 => contract2::<2>(s.net, first, stride, b0, b1),
            2 => contract2::<3>(s.net, first, stride, b0, b1),
            3 => contract2::<4>(s.net, first, stride, b0, b1),
            4 => contract2::<5>(s.net, first, stride, b0, b1),
            5 => contract2::<6>(s.net, first, stride, b0, b1),
            _ => return None,
        });
    }
    let first = [w.spans[0] - d[0], w.spans[1] - d[1], w.spans[2] - d[2]];
    let (b0, b1, b2) = (basis(0), basis(1), basis(2));
    let strides = [w.strides[0], w.strides[1]];
    Some(match d[0] {
        1 => contract3::<2>(s.net, first, strides, b0, b1, b2),
        2 => contract3::<3>(s.net, first, strides, b0, b1, b2),
        3 => contract3::<4>(s.net, first, strides, b0, b1, b2),
        4 => contract3::<5>(s.net, first, strides, b0, b1, b2),
        5 => contract3::<6>(s.net, first, strides, b0, b1, b2),
        _ => return None,
    })
}

/// The two stages of [`contract_window`] for `Q = p + 1` basis functions per direction and
/// `dim = 1`: `B_1[i] = Σ_j N_0[j]·P[f_0 + j][f_1 + i]`, then `Σ_j N_1[j]·B_1[j]`, each sum from
/// `j = 0` up ([`accumulate`]'s order). `stride` is the distance between consecutive indices of
/// direction 0 in the net. `Q²` multiply-adds on `Q` runs of `Q` contiguous numbers.
#[inline(always)]
pub(super) fn contract2<const Q: usize>(
    net: &[f64],
    first: [usize; 2],
    stride: usize,
    n0: &[f64],
    n1: &[f64],
) -> f64 {
    let (n0, n1): (&[f64; Q], &[f64; Q]) = (
        n0.try_into().expect("Q basis functions"),
        n1.try_into().expect("Q basis functions"),
    );
    let mut b1 = [0.0; Q];
    for (j, &v) in n0.iter().enumerate() {
        let at = (first[0] + j) * stride + first[1];
        let p: &[f64; Q] = net[at..at + Q].try_into().expect("a run of Q numbers");
        if j == 0 {
            for (r, x) in b1.iter_mut().zip(p) {
                *r = v * x;
            }
        } else {
            for (r, x) in b1.iter_mut().zip(p) {
                *r += v * x;
            }
        }
    }
    let mut r = n1[0] * b1[0];
    for j in 1..Q {
        r += n1[j] * b1[j];
    }
    r
}

/// The three stages of [`contract_window`] for `Q = p + 1` basis functions per direction and
/// `dim = 1`: `B_1[i_1][i_2] = Σ_j N_0[j]·P[f_0 + j][f_1 + i_1][f_2 + i_2]`, then
/// `B_2[i_2] = Σ_j N_1[j]·B_1[j][i_2]`, then `Σ_j N_2[j]·B_2[j]`, each sum from `j = 0` up
/// ([`accumulate`]'s order).
#[inline(always)]
pub(super) fn contract3<const Q: usize>(
    net: &[f64],
    first: [usize; 3],
    strides: [usize; 2],
    n0: &[f64],
    n1: &[f64],
    n2: &[f64],
) -> f64 {
    let (n0, n1, n2): (&[f64; Q], &[f64; Q], &[f64; Q]) = (
        n0.try_into().expect("Q basis functions"),
        n1.try_into().expect("Q basis functions"),
        n2.try_into().expect("Q basis functions"),
    );
    let mut b1 = [[0.0; Q]; Q];
    for (i1, row) in b1.iter_mut().enumerate() {
        let base = first[2] + (first[1] + i1) * strides[1];
        for (j, &v) in n0.iter().enumerate() {
            let at = (first[0] + j) * strides[0] + base;
            let p: &[f64; Q] = net[at..at + Q].try_into().expect("a run of Q numbers");
            if j == 0 {
                for (r, x) in row.iter_mut().zip(p) {
                    *r = v * x;
                }
            } else {
                for (r, x) in row.iter_mut().zip(p) {
                    *r += v * x;
                }
            }
        }
    }
    let mut b2 = [0.0; Q];
    for (j, (&v, row)) in n1.iter().zip(&b1).enumerate() {
        if j == 0 {
            for (r, x) in b2.iter_mut().zip(row) {
                *r = v * x;
            }
        } else {
            for (r, x) in b2.iter_mut().zip(row) {
                *r += v * x;
            }
        }
    }
    let mut r = n2[0] * b2[0];
    for j in 1..Q {
        r += n2[j] * b2[j];
    }
    r
}
