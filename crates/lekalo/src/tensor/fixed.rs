//! The fixed-size batch kernels of scalar splines in two or three directions of one degree
//! `p ≤ 5` (a bivariate or trivariate lookup table at scattered points: SciPy's
//! `RectBivariateSpline.ev`, `NdBSpline`): the points in blocks of four, their spans by the
//! bucket search ([`SpanTable`]), the basis vectors of a direction for the whole block at once
//! ([`basis_lanes`], a point a lane) and the contraction of each point with the window's sizes
//! known at compile time ([`contract2`], [`contract3`]).
//! No scratch, no odometer, no allocation a point; the same bits as the general kernel.
//!
//! [`values2_body`] and [`values3_body`] are one algorithm written out twice, on purpose. One
//! body generic over the number of directions `N` (const generics: `[[usize; N]; 4]` spans,
//! the bases of a block by `std::array::from_fn` over the directions, the per-point value and
//! window contraction passed as `#[inline(always)]` fn items) gave the same bits but more
//! instructions, counted with `valgrind --tool=callgrind` on
//! `examples/tensor_fixed_count.rs` (release build, the AVX2 copy, the inclusive count of
//! `values2`/`values3`): 2 directions of degree 3 at 200 000 points 66.3 → 89.1 million
//! (+34 %), of degree 1 43.6 → 46.2 million (+6 %); 3 directions of degree 3 at 100 000 points
//! 71.0 → 81.6 million (+15 %), of degree 5 at 50 000 points 105.9 → 117.9 million (+11 %).
//! This is a hot kernel (SciPy's `RectBivariateSpline.ev` and `NdBSpline` run through it), so
//! the two bodies stay; a change to one is made to the other, and
//! `fixed_kernels_have_the_bits_of_the_general_kernel` (`tensor/eval_tests.rs`) checks both
//! against the general kernel bit for bit.

use crate::error::Result;
use crate::tensor::contract::{contract2, contract3};
use crate::tensor::locate::{locate, Mode, SpanTable};
use crate::tensor::view::TensorBSplineRef;

/// A batch for the fixed-size kernels: the spline, the points (`N` numbers each), what to do
/// beyond the domain, and the domains and span tables of the directions.
pub(super) struct Fixed<'a, 'b> {
    pub(super) s: &'a TensorBSplineRef<'b>,
    pub(super) xs: &'a [f64],
    pub(super) mode: Mode,
    pub(super) domains: &'a [(f64, f64)],
    pub(super) tables: &'a [SpanTable],
}

impl Fixed<'_, '_> {
    /// The values of a bivariate batch of order `W = p + 1` into `out` (one number a point).
    ///
    /// # Errors
    /// [`Error::ParameterOutOfDomain`](crate::Error::ParameterOutOfDomain) at the first point
    /// outside the domain in the refusing mode.
    pub(super) fn values2<const W: usize>(&self, out: &mut [f64]) -> Result<()> {
        values2::<W>(self, out)
    }

    /// The values of a trivariate batch of order `W = p + 1` into `out` (one number a point).
    ///
    /// # Errors
    /// As [`Fixed::values2`].
    pub(super) fn values3<const W: usize>(&self, out: &mut [f64]) -> Result<()> {
        values3::<W>(self, out)
    }
}

/// The `W = p + 1` non-zero basis functions of `L` directions at `x` (direction `l` on its
/// knots `knots[l]`, span `spans[l]`), as `out[r][l]`: P&T *The NURBS Book* Algorithm A2.2,
/// `out[0] = 1`, then for `j = 1..p` with `left_j = x − t_{s+1−j}`, `right_j = t_{s+j} − x`,
/// `temp = out[r] / (right_{r+1} + left_{j−r})`, `out[r] = saved + right_{r+1}·temp`,
/// `saved = left_{j−r}·temp`. Lane `l` performs the operations of
/// [`basis_funs_fixed`](crate::basis::basis_funs_fixed) in the same order (so the same bits);
/// written lane by lane so that the `L` directions share each vector division and
/// multiplication.
#[inline(always)]
fn basis_lanes<const W: usize, const L: usize>(
    knots: [&[f64]; L],
    spans: [usize; L],
    x: [f64; L],
) -> [[f64; L]; W] {
    let mut left = [[0.0; L]; W];
    let mut right = [[0.0; L]; W];
    let mut out = [[0.0; L]; W];
    out[0] = [1.0; L];
    for j in 1..W {
        for l in 0..L {
            left[j][l] = x[l] - knots[l][spans[l] + 1 - j];
            right[j][l] = knots[l][spans[l] + j] - x[l];
        }
        let mut saved = [0.0; L];
        for r in 0..j {
            let mut temp = [0.0; L];
            for l in 0..L {
                temp[l] = out[r][l] / (right[r + 1][l] + left[j - r][l]);
            }
            for l in 0..L {
                out[r][l] = saved[l] + right[r + 1][l] * temp[l];
                saved[l] = left[j - r][l] * temp[l];
            }
        }
        out[j] = saved;
    }
    out
}

/// Column `l` of the lanes of [`basis_lanes`]: the basis vector of direction `l`.
#[inline(always)]
fn lane<const W: usize, const L: usize>(b: &[[f64; L]; W], l: usize) -> [f64; W] {
    std::array::from_fn(|r| b[r][l])
}

/// One bivariate value of order `W` at `x` (spans found).
#[inline(always)]
fn one2<const W: usize>(s: &TensorBSplineRef<'_>, spans: [usize; 2], x: [f64; 2]) -> f64 {
    let p = W - 1;
    let b = basis_lanes::<W, 2>([s.knots[0], s.knots[1]], spans, x);
    let first = [spans[0] - p, spans[1] - p];
    contract2::<W>(s.net, first, s.stride(0), &lane(&b, 0), &lane(&b, 1))
}

/// One trivariate value of order `W` at `x` (spans found).
#[inline(always)]
fn one3<const W: usize>(s: &TensorBSplineRef<'_>, spans: [usize; 3], x: [f64; 3]) -> f64 {
    let p = W - 1;
    let k = [s.knots[0], s.knots[1], s.knots[2]];
    // a fourth lane repeats the first, so that the lanes fill whole vectors
    let b = basis_lanes::<W, 4>(
        [k[0], k[1], k[2], k[0]],
        [spans[0], spans[1], spans[2], spans[0]],
        [x[0], x[1], x[2], x[0]],
    );
    let first = [spans[0] - p, spans[1] - p, spans[2] - p];
    let strides = [s.stride(0), s.stride(1)];
    contract3::<W>(
        s.net,
        first,
        strides,
        &lane(&b, 0),
        &lane(&b, 1),
        &lane(&b, 2),
    )
}

/// Points of the bivariate batch whose bases share each [`basis_lanes`] (one lane a point).
const BLOCK2: usize = 4;

/// The bivariate batch [`BLOCK2`] points at a time: the spans of the block's points first,
/// then one [`basis_lanes`] a direction with the block's points in its lanes (one 4-wide
/// vector with AVX2), so that the points share each vector division and the two directions'
/// triangles, independent, overlap their divisions' latency (the latency of a point). A block
/// with a point that gives NaN, and the last points of a batch, take [`one2`]; the same bits
/// either way.
#[inline(always)]
fn values2_body<const W: usize>(run: &Fixed<'_, '_>, out: &mut [f64]) -> Result<()> {
    let s = run.s;
    let (k0, k1) = (s.knots[0], s.knots[1]);
    let (stride, p) = (s.stride(0), W - 1);
    let mut spans = [[0usize; 2]; BLOCK2];
    let mut xs = [[0.0; 2]; BLOCK2];
    let mut blocks = run.xs.chunks_exact(2 * BLOCK2);
    let mut outs = out.chunks_exact_mut(BLOCK2);
    for (xb, o) in (&mut blocks).zip(&mut outs) {
        let mut all = true;
        let mut ok = [false; BLOCK2];
        for (b, x) in xb.chunks_exact(2).enumerate() {
            ok[b] = locate(
                run.mode,
                x,
                run.domains,
                run.tables,
                &mut spans[b],
                &mut xs[b],
            )?;
            all &= ok[b];
        }
        if !all {
            for b in 0..BLOCK2 {
                o[b] = if ok[b] {
                    one2::<W>(s, spans[b], xs[b])
                } else {
                    f64::NAN
                };
            }
            continue;
        }
        // a triangle a direction, the block's points in its lanes
        let n0 = basis_lanes::<W, BLOCK2>([k0; BLOCK2], spans.map(|s| s[0]), xs.map(|x| x[0]));
        let n1 = basis_lanes::<W, BLOCK2>([k1; BLOCK2], spans.map(|s| s[1]), xs.map(|x| x[1]));
        for (b, o) in o.iter_mut().enumerate() {
            *o = contract2::<W>(
                s.net,
                [spans[b][0] - p, spans[b][1] - p],
                stride,
                &lane(&n0, b),
                &lane(&n1, b),
            );
        }
    }
    let (mut sa, mut xa) = ([0usize; 2], [0.0; 2]);
    for (xp, o) in blocks
        .remainder()
        .chunks_exact(2)
        .zip(outs.into_remainder())
    {
        *o = if locate(run.mode, xp, run.domains, run.tables, &mut sa, &mut xa)? {
            one2::<W>(s, sa, xa)
        } else {
            f64::NAN
        };
    }
    Ok(())
}

/// Points of the trivariate batch whose bases share each [`basis_lanes`] (one lane a point).
const BLOCK3: usize = 4;

/// The trivariate batch [`BLOCK3`] points at a time, one [`basis_lanes`] a direction with the
/// block's points in its lanes, as [`values2_body`] does in two directions; a block with a point
/// that gives NaN, and the last points of a batch, take [`one3`]. The same bits either way.
#[inline(always)]
fn values3_body<const W: usize>(run: &Fixed<'_, '_>, out: &mut [f64]) -> Result<()> {
    let s = run.s;
    let k = [s.knots[0], s.knots[1], s.knots[2]];
    let p = W - 1;
    let strides = [s.stride(0), s.stride(1)];
    let mut spans = [[0usize; 3]; BLOCK3];
    let mut xs = [[0.0; 3]; BLOCK3];
    let mut blocks = run.xs.chunks_exact(3 * BLOCK3);
    let mut outs = out.chunks_exact_mut(BLOCK3);
    for (xb, o) in (&mut blocks).zip(&mut outs) {
        let mut all = true;
        let mut ok = [false; BLOCK3];
        for (b, x) in xb.chunks_exact(3).enumerate() {
            ok[b] = locate(
                run.mode,
                x,
                run.domains,
                run.tables,
                &mut spans[b],
                &mut xs[b],
            )?;
            all &= ok[b];
        }
        if !all {
            for b in 0..BLOCK3 {
                o[b] = if ok[b] {
                    one3::<W>(s, spans[b], xs[b])
                } else {
                    f64::NAN
                };
            }
            continue;
        }
        // a triangle a direction, the block's points in its lanes
        let n: [[[f64; BLOCK3]; W]; 3] = std::array::from_fn(|a| {
            basis_lanes::<W, BLOCK3>([k[a]; BLOCK3], spans.map(|s| s[a]), xs.map(|x| x[a]))
        });
        for (b, o) in o.iter_mut().enumerate() {
            *o = contract3::<W>(
                s.net,
                [spans[b][0] - p, spans[b][1] - p, spans[b][2] - p],
                strides,
                &lane(&n[0], b),
                &lane(&n[1], b),
                &lane(&n[2], b),
            );
        }
    }
    let mut spans = [0usize; 3];
    let mut x = [0.0; 3];
    for (xp, o) in blocks
        .remainder()
        .chunks_exact(3)
        .zip(outs.into_remainder())
    {
        *o = if locate(run.mode, xp, run.domains, run.tables, &mut spans, &mut x)? {
            one3::<W>(s, spans, x)
        } else {
            f64::NAN
        };
    }
    Ok(())
}

crate::numeric::isa::avx2_dispatch! {
    /// [`values2_body`], with AVX2 where the processor has it (the same bits).
    fn values2<const W: usize>(run: &Fixed<'_, '_>, out: &mut [f64]) -> Result<()> = values2_body;
}

crate::numeric::isa::avx2_dispatch! {
    /// [`values3_body`], with AVX2 where the processor has it (the same bits).
    fn values3<const W: usize>(run: &Fixed<'_, '_>, out: &mut [f64]) -> Result<()> = values3_body;
}
