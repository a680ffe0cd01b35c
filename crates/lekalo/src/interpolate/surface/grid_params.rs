//! The parameters of a grid of points (document 000 §5, eq. 16–17): each column's and each row's
//! parameters, averaged over the lines, in one pass over the grid for chord lengths.

use crate::error::Result;
use crate::interpolate::parametrization::{distances, parametrize_into};

/// The averaged parameters of the grid's columns (`ū_k`, length `nu`) and rows (`v̄_l`, length
/// `nv`), document 000 eq. 16–17: the parameters of every line by the exponent `e`
/// (`docs/theory.md`, P&T eq. 9.5 for `e = 1`) summed, divided by the number of lines, and the
/// ends pinned to exactly 0 and 1. Chord lengths (`e = 1`) take the one-pass [`chord_params`];
/// any other exponent, or a grid it refuses, takes [`line_params`], which reports the problem.
///
/// # Errors
/// Those of [`parametrize_into`]: coincident points, overflow, a non-finite distance.
pub(super) fn averaged_params(
    data: &[f64],
    nu: usize,
    nv: usize,
    dim: usize,
    e: f64,
) -> Result<(Vec<f64>, Vec<f64>)> {
    let mut params_u = vec![0.0; nu];
    let mut params_v = vec![0.0; nv];
    let fast = e == 1.0 && chord_params(data, nu, nv, dim, &mut params_u, &mut params_v);
    if !fast {
        params_u.fill(0.0);
        params_v.fill(0.0);
        line_params(data, nu, nv, dim, e, &mut params_u, &mut params_v)?;
    }
    finish_average(&mut params_u, nv);
    finish_average(&mut params_v, nu);
    Ok((params_u, params_v))
}

/// The summed parameters of every column (`params_u`) and every row (`params_v`) by
/// [`parametrize_into`] (any exponent), which reports coincident points and overflow.
pub(super) fn line_params(
    data: &[f64],
    nu: usize,
    nv: usize,
    dim: usize,
    e: f64,
    params_u: &mut [f64],
    params_v: &mut [f64],
) -> Result<()> {
    let pt = |k: usize, l: usize| &data[(k * nv + l) * dim..(k * nv + l + 1) * dim];
    let mut tmp = vec![0.0; nu.max(nv)];
    for l in 0..nv {
        parametrize_into(
            nu - 1,
            |k| pt(k, l),
            e,
            |k| (k * nv + l, (k + 1) * nv + l),
            &mut tmp[..nu],
        )?;
        for (a, b) in params_u.iter_mut().zip(&tmp) {
            *a += b;
        }
    }
    for k in 0..nu {
        parametrize_into(
            nv - 1,
            |l| pt(k, l),
            e,
            |l| (k * nv + l, k * nv + l + 1),
            &mut tmp[..nv],
        )?;
        for (a, b) in params_v.iter_mut().zip(&tmp) {
            *a += b;
        }
    }
    Ok(())
}

crate::numeric::isa::avx2_dispatch! {
    /// The sums over the columns `l` of the chord-length parameters `ū_k^{(l)}` of
    /// `q_0l … q_{nu−1,l}` into `params_u`, and over the rows `k` of the parameters `v̄_l^{(k)}`
    /// of `q_k0 … q_{k,nv−1}` into `params_v` (both zero on entry): the same numbers, in the same
    /// order, as [`line_params`] with exponent 1 (P&T eq. 9.5), but in one pass over the grid that
    /// reads each row once (the column walk strides over whole rows and misses the cache at every
    /// point) with the dimension fixed at compile time for 2-D and 3-D. `false`, with the sums to
    /// be discarded, when a distance is zero or not finite, a line's length overflows or its
    /// parameters are not strictly increasing: the caller then takes [`line_params`], which
    /// reports the problem.
    ///
    /// Compiled with AVX2 where the processor has it ([`crate::numeric::isa`]: the same bits, tested).
    pub(super) fn chord_params(
        data: &[f64],
        nu: usize,
        nv: usize,
        dim: usize,
        params_u: &mut [f64],
        params_v: &mut [f64],
    ) -> bool = chord_params_body;
}

/// The body of [`chord_params`], inlined into its baseline and AVX2 copies.
#[inline(always)]
pub(super) fn chord_params_body(
    data: &[f64],
    nu: usize,
    nv: usize,
    dim: usize,
    params_u: &mut [f64],
    params_v: &mut [f64],
) -> bool {
    match dim {
        2 => chord_params_fixed::<2>(data, nu, nv, dim, params_u, params_v),
        3 => chord_params_fixed::<3>(data, nu, nv, dim, params_u, params_v),
        _ => chord_params_fixed::<0>(data, nu, nv, dim, params_u, params_v),
    }
}

/// [`chord_params`] for the dimension `D` (`0`: `dim` at run time). The validity tests are
/// accumulated without branches and looked at once per row.
#[inline(always)]
fn chord_params_fixed<const D: usize>(
    data: &[f64],
    nu: usize,
    nv: usize,
    dim: usize,
    params_u: &mut [f64],
    params_v: &mut [f64],
) -> bool {
    let dim = if D == 0 { dim } else { D };
    let row_len = nv * dim;
    // column lengths, and the distances down the columns for the second pass
    let mut total = vec![0.0_f64; nv];
    let mut dist = vec![0.0_f64; (nu - 1) * nv];
    // distances, then running sums, along the current row
    let mut run = vec![0.0_f64; nv];
    let rows = data.chunks_exact(row_len);
    let next_rows = data.chunks_exact(row_len).skip(1).map(Some).chain([None]);
    for (k, (row, next)) in rows.zip(next_rows).enumerate() {
        let mut ok = true;
        distances::<D>(&row[..row_len - dim], &row[dim..], dim, &mut run[1..]);
        let mut sum = 0.0;
        for s in &mut run[1..] {
            // a NaN or infinite distance makes the row's sum non-finite (tested below)
            ok &= *s > 0.0;
            sum += *s;
            *s = sum;
        }
        ok &= sum.is_finite();
        // v̄ of this row: t_l = s_l / s (ends exactly 0 and 1), strictly increasing
        let inv = 1.0 / sum;
        let mut prev = 0.0;
        for (a, &s) in params_v[1..nv - 1].iter_mut().zip(&run[1..nv - 1]) {
            let t = s * inv;
            ok &= t > prev;
            prev = t;
            *a += t;
        }
        ok &= 1.0 > prev;
        params_v[nv - 1] += 1.0;
        if let Some(next) = next {
            let down = &mut dist[k * nv..(k + 1) * nv];
            distances::<D>(row, next, dim, down);
            for (s, &d) in total.iter_mut().zip(down.iter()) {
                // a NaN or infinite distance makes the column's length non-finite (tested
                // after the pass)
                ok &= d > 0.0;
                *s += d;
            }
        }
        if !ok {
            return false;
        }
    }
    if !total.iter().all(|s| s.is_finite()) {
        return false;
    }
    let inv: Vec<f64> = total.iter().map(|s| 1.0 / s).collect();
    // running sums and the previous parameter of each column
    run.fill(0.0);
    let mut prev = vec![0.0_f64; nv];
    let mut ok = true;
    for (k, row) in dist.chunks_exact(nv).enumerate().map(|(i, r)| (i + 1, r)) {
        let out = &mut params_u[k];
        if k + 1 < nu {
            for (((&d, acc), &iv), pr) in row.iter().zip(&mut run).zip(&inv).zip(&mut prev) {
                *acc += d;
                let t = *acc * iv;
                ok &= t > *pr;
                *pr = t;
                *out += t;
            }
        } else {
            for pr in &prev {
                ok &= 1.0 > *pr;
                *out += 1.0;
            }
        }
    }
    ok
}

/// Divides the summed parameters by their count and pins the ends to exactly 0 and 1.
fn finish_average(params: &mut [f64], count: usize) {
    let inv = 1.0 / count as f64;
    for t in params.iter_mut() {
        *t *= inv;
    }
    params[0] = 0.0;
    if let Some(last) = params.last_mut() {
        *last = 1.0;
    }
}
