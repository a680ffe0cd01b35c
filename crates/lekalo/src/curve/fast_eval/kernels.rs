//! The per-point kernels: each written once for any degree and dimension, and its fixed twin
//! (degree and dimension constants) calling it inlined on arrays, so that the monomorphised
//! code keeps its numbers in registers and performs the same operations in the same order.

/// Horner's scheme on piece `j` with degree `P` and dimension `D` fixed at compile time:
/// [`power_dyn`] inlined on an array of length `D`, so the same operations in the same order,
/// the accumulator in registers.
#[inline(always)]
pub(super) fn power_fixed<const P: usize, const D: usize>(
    coef: &[f64],
    j: usize,
    t: f64,
    o: &mut [f64],
) {
    let mut acc = [0.0; D];
    power_dyn(P, coef, j, t, &mut acc);
    o[..D].copy_from_slice(&acc);
}

/// [`CurveEvaluator::basis_point`] with the order `W = p + 1` and dimension `D` fixed at
/// compile time, so that the triangle lives in registers; the same operations in the same
/// order.
#[inline(always)]
pub(super) fn basis_fixed<const W: usize, const D: usize>(
    knots: &[f64],
    control: &[f64],
    recip: &[f64],
    span: usize,
    j: usize,
    t: f64,
    o: &mut [f64],
) {
    let p = W - 1;
    let tri = p * W / 2;
    let nv = basis_by_reciprocals::<W>(knots, &recip[j * tri..(j + 1) * tri], span, t);
    let mut acc = [0.0; D];
    let c = &control[(span - p) * D..(span + 1) * D];
    for r in 0..W {
        for d in 0..D {
            acc[d] += nv[r] * c[r * D + d];
        }
    }
    o[..D].copy_from_slice(&acc);
}

/// Appends the reciprocals `1 / (t_{i+r+1} − t_{i+r+1−l})` of span `i`, level `l = 1..=p`,
/// `r = 0..l`, at `[l(l−1)/2 + r]` of the span's triangle: the denominators of P&T Algorithm
/// A2.2, computed once a span so that a point costs no division. For a non-empty span each
/// interval `[t_{i+r+1−l}, t_{i+r+1}]` contains `[t_i, t_{i+1}]`, so the differences are
/// positive.
pub(crate) fn push_span_reciprocals(knots: &[f64], p: usize, i: usize, out: &mut Vec<f64>) {
    for l in 1..=p {
        for r in 0..l {
            out.push(1.0 / (knots[i + r + 1] - knots[i + r + 1 - l]));
        }
    }
}

/// The `W = p + 1` non-zero basis functions at `t` in `span` by P&T Algorithm A2.2, with the
/// span's reciprocals `rc` ([`push_span_reciprocals`]) in place of its divisions; the order is
/// fixed at compile time so that the triangle stays in registers: [`basis_by_reciprocals_dyn`]
/// on arrays of length `W`, inlined, so the same operations in the same order.
#[inline(always)]
pub(crate) fn basis_by_reciprocals<const W: usize>(
    knots: &[f64],
    rc: &[f64],
    span: usize,
    t: f64,
) -> [f64; W] {
    let (mut nv, mut left, mut right) = ([0.0; W], [0.0; W], [0.0; W]);
    triangle_by_reciprocals(knots, rc, W - 1, span, t, &mut nv, &mut left, &mut right);
    nv
}

/// [`basis_by_reciprocals`] for any degree `p`: the values into `n[..=p]`, `n` scratch of
/// length `3(p + 1)`.
#[inline(always)]
pub(crate) fn basis_by_reciprocals_dyn(
    knots: &[f64],
    rc: &[f64],
    p: usize,
    span: usize,
    t: f64,
    n: &mut [f64],
) {
    let (nv, rest) = n.split_at_mut(p + 1);
    let (left, right) = rest.split_at_mut(p + 1);
    triangle_by_reciprocals(knots, rc, p, span, t, nv, left, right);
}

/// The triangle of P&T Algorithm A2.2 at `t` in `span`, degree `p`, each division a product by
/// the reciprocal `rc[l(l−1)/2 + r]`: the basis values into `nv[..=p]`, `left` and `right`
/// scratch of length `p + 1`. Inlined into both callers, so that with `p` a constant and arrays
/// for the slices the loops unroll into registers.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn triangle_by_reciprocals(
    knots: &[f64],
    rc: &[f64],
    p: usize,
    span: usize,
    t: f64,
    nv: &mut [f64],
    left: &mut [f64],
    right: &mut [f64],
) {
    nv[0] = 1.0;
    let mut off = 0;
    // `1..p + 1`, not `1..=p`: the inclusive range's exhaustion flag keeps LLVM from unrolling
    // the loop when `p` is a constant (measured: 44 % more instructions in the fixed kernels)
    for l in 1..p + 1 {
        left[l] = t - knots[span + 1 - l];
        right[l] = knots[span + l] - t;
        let mut saved = 0.0;
        for r in 0..l {
            let temp = nv[r] * rc[off + r];
            nv[r] = saved + right[r + 1] * temp;
            saved = left[l - r] * temp;
        }
        nv[l] = saved;
        off += l;
    }
}

/// Derivatives of orders `0..=kmax` on piece `j` by repeated synthetic division (Knuth, TAOCP
/// vol. 2, §4.6.4); `a` is scratch of length `p + 1` (an array when the caller knows `p`, so
/// that it lives in registers), `o` a row of `(order + 1)·dim` values, zero above `kmax`.
#[inline(always)]
pub(super) fn power_ders(
    a: &mut [f64],
    dim: usize,
    coef: &[f64],
    j: usize,
    t: f64,
    kmax: usize,
    o: &mut [f64],
) {
    let p = a.len() - 1;
    let stride = 2 + (p + 1) * dim;
    let block = &coef[j * stride..(j + 1) * stride];
    let (x, inv) = (block[0], block[1]);
    let u = (t - x) * inv;
    o[(kmax + 1) * dim..].fill(0.0);
    for d in 0..dim {
        // a[i]: coefficient of u^i, coordinate d (lowest power first)
        for (i, ai) in a.iter_mut().enumerate() {
            *ai = block[2 + (p - i) * dim + d];
        }
        let mut scale = 1.0; // k! / h^k
        for k in 0..=kmax {
            // synthetic division by (x − u): afterwards a[k] is the k-th Taylor coefficient at u
            for i in (k..p).rev() {
                a[i] += u * a[i + 1];
            }
            o[k * dim + d] = a[k] * scale;
            scale *= (k + 1) as f64 * inv;
        }
    }
}

/// Horner's scheme on piece `j`, any degree and dimension.
#[inline(always)]
pub(super) fn power_dyn(p: usize, coef: &[f64], j: usize, t: f64, o: &mut [f64]) {
    let dim = o.len();
    let stride = 2 + (p + 1) * dim;
    let block = &coef[j * stride..(j + 1) * stride];
    let u = (t - block[0]) * block[1];
    let c = &block[2..];
    o.copy_from_slice(&c[..dim]);
    for k in 1..=p {
        for (x, &ck) in o.iter_mut().zip(&c[k * dim..(k + 1) * dim]) {
            *x = *x * u + ck;
        }
    }
}
