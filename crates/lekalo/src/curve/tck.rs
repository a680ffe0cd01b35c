//! Calculus on a spline given as arrays — knots `t`, coefficients `c` (`n × dim`, one row a
//! coefficient) and degree `k`, SciPy's `(t, c, k)` — read in place and written into the
//! caller's buffers, without building a [`BSplineCurve`](crate::BSplineCurve): the derivative
//! and antiderivative coefficients and the definite integral
//! (`docs/theory/curves.md#antiderivatives-integrals-and-extrapolation`). The arithmetic is that
//! of [`BSplineCurve::derivative`](crate::BSplineCurve::derivative) and
//! [`BSplineCurve::antiderivative`](crate::BSplineCurve::antiderivative), so the numbers are
//! the same; what is saved is the copies of the arrays, their validation as a curve, and the
//! fresh memory of intermediate results (for millions of coefficients the page faults of that
//! memory cost more than the arithmetic).

use crate::basis::{basis_funs_into, BasisScratch};
use crate::error::{check_degree_bound, check_finite, Error, Result};
use crate::Arg;

/// The checks shared by the functions of this module: `t.len() ≥ 2k + 2`, `dim ≥ 1`, at least
/// `n = t.len() − k − 1` coefficient rows in `c`; returns `n`.
fn coefficient_count(t: &[f64], k: usize, c: &[f64], dim: usize) -> Result<usize> {
    if dim == 0 {
        return Err(invalid_spline(
            "the coefficients have no column (dimension 0)".into(),
        ));
    }
    let n = basis_count(t, k)?;
    if c.len() < n * dim {
        return Err(invalid_spline(format!(
            "{} coefficient rows for {} knots of degree {k}: at least {n} are needed",
            c.len() / dim,
            t.len()
        )));
    }
    Ok(n)
}

/// The number `n = t.len() − k − 1` of B-splines of degree `k` on the knots `t`, which must be
/// at least `2k + 2`.
fn basis_count(t: &[f64], k: usize) -> Result<usize> {
    let need = k.checked_mul(2).and_then(|v| v.checked_add(2));
    if need.is_none_or(|need| t.len() < need) {
        return Err(invalid_spline(format!(
            "{} knots for degree {k}: at least 2k + 2 are needed",
            t.len()
        )));
    }
    Ok(t.len() - k - 1)
}

fn invalid_spline(reason: String) -> Error {
    Error::InvalidArgument {
        what: "spline (knots, degree, coefficients)".into(),
        reason,
    }
}

/// A buffer of the wrong size: the caller's mistake, named.
fn buffer_size(expected: usize, got: usize) -> Error {
    Error::LengthMismatch {
        what: "result buffer (rows × dimension)".into(),
        expected,
        got,
    }
}

/// The coefficients of the `nu`-th derivative of the spline `(t, c, k)` into `out`, on the knots
/// `t[nu .. t.len() − nu]` and of degree `k − nu`, in SciPy's layout (`splder`): `out` holds
/// `t.len() − 2nu` rows of `dim` numbers, the first `n − nu` the coefficients
/// `c'_i = p (c_{i+1} − c_i) / (t_{i+p+1} − t_{i+1})` applied `nu` times (P&T eq. 3.7; the
/// arithmetic of [`BSplineCurve::derivative`](crate::BSplineCurve::derivative)), the others
/// zero. Only the first `n = t.len() − k − 1` rows of `c` are read. O(nu · n · dim).
///
/// ```
/// use lekalo::curve::derivative_coefficients_into;
/// // t² on [0, 1] as a clamped quadratic: coefficients 0, 0, 1; the derivative 2t is 0, 2
/// let t = [0.0, 0.0, 0.0, 1.0, 1.0, 1.0];
/// let mut out = [f64::NAN; 4];
/// derivative_coefficients_into(&t, 2, &[0.0, 0.0, 1.0], 1, 1, &mut out)?;
/// assert_eq!(out, [0.0, 2.0, 0.0, 0.0]);
/// # Ok::<(), lekalo::Error>(())
/// ```
///
/// # Errors
/// [`Error::InvalidArgument`] for fewer than `2k + 2` knots, fewer coefficients than `n`, no
/// column, `nu > k`, or a knot repeated so often inside that the spline is not differentiable
/// `nu` times (a zero denominator `t_{i+p+1} − t_{i+1}`); [`Error::LengthMismatch`] for `out`
/// not of `(t.len() − 2nu) · dim` numbers; [`Error::NonFinite`] on overflow.
pub fn derivative_coefficients_into(
    t: &[f64],
    k: usize,
    c: &[f64],
    dim: usize,
    nu: usize,
    out: &mut [f64],
) -> Result<()> {
    let n = coefficient_count(t, k, c, dim)?;
    if nu > k {
        return Err(Error::InvalidArgument {
            what: "derivative order".into(),
            reason: format!("order {nu} exceeds the degree {k}: use orders 0 … {k}"),
        });
    }
    let rows = t.len() - 2 * nu;
    if out.len() != rows * dim {
        return Err(buffer_size(rows * dim, out.len()));
    }
    let m = n - nu; // coefficients of the result
    match nu {
        0 => {
            out[..n * dim].copy_from_slice(&c[..n * dim]);
            check_finite(
                "derivative coefficients (overflow: rescale the coefficients)",
                &out[..n * dim],
            )?;
        }
        // one step straight from the input
        1 => derivative_step(t, k, nu, dim, &c[..n * dim], &mut out[..m * dim])?,
        // the result may have fewer rows than the steps before it: the steps in a work copy,
        // each in place (row i reads rows i and i + 1)
        _ => {
            let mut work = c[..n * dim].to_vec();
            for step in 0..nu {
                let rows = n - step;
                derivative_step_in_place(
                    &t[step..t.len() - step],
                    k - step,
                    nu,
                    dim,
                    &mut work[..rows * dim],
                )?;
            }
            out[..m * dim].copy_from_slice(&work[..m * dim]);
            check_finite(
                "derivative coefficients (overflow: rescale the coefficients)",
                &out[..m * dim],
            )?;
        }
    }
    out[m * dim..].fill(0.0);
    Ok(())
}

/// `p / (u_{i+p+1} − u_{i+1})`, the factor of derivative row `i` on the knots `u` of degree `p`,
/// or the error of a knot repeated `p + 1` times (a zero denominator; NaN knots too).
fn derivative_factor(u: &[f64], p: usize, i: usize, nu: usize) -> Result<f64> {
    let denom = u[i + p + 1] - u[i + 1];
    if denom.is_nan() || denom <= 0.0 {
        return Err(Error::InvalidArgument {
            what: Arg::Knots.into(),
            reason: format!(
                "knot {} is repeated {} times or more: the spline is not differentiable {nu} \
                 times there; take fewer derivatives",
                u[i + 1],
                p + 1
            ),
        });
    }
    Ok(p as f64 / denom)
}

/// One derivative step on the knots `u` of degree `p`: `dst` (one row fewer than `src`) from
/// `src`, `dst_i = p (src_{i+1} − src_i) / (u_{i+p+1} − u_{i+1})`, the rows checked finite. The
/// denominators and the results are checked without a branch a row (the error searched for only
/// when one fails), so that the step is a straight loop the compiler vectorises.
fn derivative_step(
    u: &[f64],
    p: usize,
    nu: usize,
    dim: usize,
    src: &[f64],
    dst: &mut [f64],
) -> Result<()> {
    let rows = dst.len() / dim;
    let (lo, hi) = (&u[1..=rows], &u[p + 1..=rows + p]);
    let pf = p as f64;
    if dim == 1 {
        // one pass: the quotients written, the denominators' signs and the results'
        // finiteness gathered without a branch
        if !quotient_pass(lo, hi, &src[..rows], &src[1..=rows], pf, dst) {
            for i in 0..rows {
                derivative_factor(u, p, i, nu)?;
            }
            return check_finite(
                "derivative coefficients (overflow: rescale the coefficients)",
                dst,
            );
        }
        return Ok(());
    }
    let ok = lo
        .iter()
        .zip(hi)
        .fold(true, |ok, (a, b)| ok & (b - a > 0.0));
    if !ok {
        for i in 0..rows {
            derivative_factor(u, p, i, nu)?;
        }
    }
    for (i, row) in dst.chunks_exact_mut(dim).enumerate() {
        let s = pf / (hi[i] - lo[i]);
        let (a, b) = (
            &src[i * dim..(i + 1) * dim],
            &src[(i + 1) * dim..(i + 2) * dim],
        );
        for ((o, x0), x1) in row.iter_mut().zip(a).zip(b) {
            *o = s * (x1 - x0);
        }
    }
    check_finite(
        "derivative coefficients (overflow: rescale the coefficients)",
        dst,
    )
}

/// `dst_i = pf / (hi_i − lo_i) · (x1_i − x0_i)`; whether every denominator is positive and
/// every quotient finite (`|v| < ∞` is false for ±∞ and NaN), gathered as one flag.
#[inline(always)]
fn quotient_pass_body(
    lo: &[f64],
    hi: &[f64],
    x0: &[f64],
    x1: &[f64],
    pf: f64,
    dst: &mut [f64],
) -> bool {
    let mut ok = true;
    for ((((o, a), b), c0), c1) in dst.iter_mut().zip(lo).zip(hi).zip(x0).zip(x1) {
        let denom = b - a;
        let v = pf / denom * (c1 - c0);
        ok &= (denom > 0.0) & (v.abs() < f64::INFINITY);
        *o = v;
    }
    ok
}

crate::numeric::isa::avx2_dispatch! {
    /// [`quotient_pass_body`], compiled with AVX2 (4-wide divisions, the loop's bound) where
    /// the processor has it ([`crate::numeric::isa`]; the same IEEE operations, the same bits).
    #[inline(never)]
    fn quotient_pass(lo: &[f64], hi: &[f64], x0: &[f64], x1: &[f64], pf: f64, dst: &mut [f64]) -> bool = quotient_pass_body;
}

/// [`derivative_step`] in place: the first `rows − 1` rows of `buf` replaced by the step's
/// coefficients (row `i` reads rows `i` and `i + 1`, so going up reads before writing).
fn derivative_step_in_place(
    u: &[f64],
    p: usize,
    nu: usize,
    dim: usize,
    buf: &mut [f64],
) -> Result<()> {
    let rows = buf.len() / dim;
    for i in 0..rows - 1 {
        let s = derivative_factor(u, p, i, nu)?;
        for d in 0..dim {
            buf[i * dim + d] = s * (buf[(i + 1) * dim + d] - buf[i * dim + d]);
        }
    }
    Ok(())
}

/// The coefficients of the `nu`-th antiderivative of the spline `(t, c, k)` into `out`, of
/// degree `k + nu` on the knots `t` with each end knot repeated `nu` times more, in SciPy's
/// layout (`splantider`): `out` holds `t.len() + 2nu` rows of `dim` numbers, the first `n + nu`
/// the coefficients of `nu` steps of `P̃_0 = 0`, `P̃_{i+1} = Σ_{j≤i} c_j (t_{j+p+1} − t_j)/(p + 1)`
/// (de Boor, *A Practical Guide to Splines*, ch. X, eq. (31); the arithmetic of
/// [`BSplineCurve::antiderivative`](crate::BSplineCurve::antiderivative)), the others copies
/// of the last. Only the first `n` rows of `c` are read. O(nu · n · dim).
///
/// ```
/// use lekalo::curve::antiderivative_coefficients_into;
/// // 1 on [0, 1] (degree 0): the antiderivative x has coefficients 0, 1 on knots 0, 0, 1, 1
/// let mut out = [f64::NAN; 4];
/// antiderivative_coefficients_into(&[0.0, 1.0], 0, &[1.0], 1, 1, &mut out)?;
/// assert_eq!(out, [0.0, 1.0, 1.0, 1.0]);
/// # Ok::<(), lekalo::Error>(())
/// ```
///
/// # Errors
/// [`Error::InvalidArgument`] for fewer than `2k + 2` knots, fewer coefficients than `n` or no
/// column; [`Error::Degree`] if `k + nu` exceeds [`crate::MAX_DEGREE`];
/// [`Error::LengthMismatch`] for `out` not of `(t.len() + 2nu) · dim` numbers;
/// [`Error::NonFinite`] on overflow.
pub fn antiderivative_coefficients_into(
    t: &[f64],
    k: usize,
    c: &[f64],
    dim: usize,
    nu: usize,
    out: &mut [f64],
) -> Result<()> {
    let n = coefficient_count(t, k, c, dim)?;
    check_degree_bound(k.saturating_add(nu))?;
    let rows = t.len() + 2 * nu;
    if out.len() != rows * dim {
        return Err(buffer_size(rows * dim, out.len()));
    }
    let (first, last) = (t[0], t[t.len() - 1]);
    if nu == 0 {
        out[..n * dim].copy_from_slice(&c[..n * dim]);
    } else {
        // the first step straight from `c` (its knots are `t`), the running sums written
        // as they grow
        let scale = 1.0 / (k as f64 + 1.0);
        let (lo, hi) = (&t[..n], &t[k + 1..=n + k]);
        if dim == 1 {
            let mut acc = 0.0;
            for (((o, x), a), b) in out[..n].iter_mut().zip(&c[..n]).zip(lo).zip(hi) {
                *o = acc;
                acc += x * ((b - a) * scale);
            }
            out[n] = acc;
        } else {
            let mut acc = vec![0.0; dim];
            for (j, (a, b)) in lo.iter().zip(hi).enumerate() {
                let w = (b - a) * scale;
                let row = &mut out[j * dim..(j + 1) * dim];
                for ((o, s), x) in row.iter_mut().zip(acc.iter_mut()).zip(&c[j * dim..]) {
                    *o = *s;
                    *s += x * w;
                }
            }
            out[n * dim..(n + 1) * dim].copy_from_slice(&acc);
        }
    }
    let mut acc = vec![0.0; dim];
    for step in 1..nu {
        // the knots of this step: t with each end knot repeated `step` times more
        let u = |i: usize| {
            if i < step {
                first
            } else if i - step < t.len() {
                t[i - step]
            } else {
                last
            }
        };
        let p = k + step;
        let scale = 1.0 / (p as f64 + 1.0);
        let m = n + step; // coefficients of this step
        acc.fill(0.0);
        for j in 0..m {
            let w = (u(j + p + 1) - u(j)) * scale;
            let row = &mut out[j * dim..(j + 1) * dim];
            for (o, s) in row.iter_mut().zip(acc.iter_mut()) {
                let x = *o;
                *o = *s;
                *s += x * w;
            }
        }
        out[m * dim..(m + 1) * dim].copy_from_slice(&acc);
    }
    let m = n + nu;
    // with nu ≥ 1 every row is a partial sum of the last step, whose last row is the whole sum:
    // a sum that once meets ±∞ or NaN stays ±∞ or NaN (∞ + finite = ∞, ∞ − ∞ = NaN), so the rows
    // are all finite when the last one is, and the whole check is needed only to name the first
    // that is not (nu = 0 copies the coefficients: all of them checked)
    if nu == 0 || !out[(m - 1) * dim..m * dim].iter().all(|v| v.is_finite()) {
        check_finite(
            "antiderivative coefficients (overflow: rescale the coefficients)",
            &out[..m * dim],
        )?;
    }
    let (filled, rest) = out.split_at_mut(m * dim);
    let last_row = &filled[(m - 1) * dim..];
    for row in rest.chunks_exact_mut(dim) {
        row.copy_from_slice(last_row);
    }
    Ok(())
}

/// The knots of the `nu`-th antiderivative of a spline on the knots `t` into `out`: `t` with
/// its first and last knots each repeated `nu` times more (`t.len() + 2nu` numbers), the knots
/// of [`antiderivative_coefficients_into`] (SciPy's `splantider`).
///
/// ```
/// use lekalo::curve::antiderivative_knots_into;
/// let mut out = [f64::NAN; 6];
/// antiderivative_knots_into(&[0.0, 0.0, 1.0, 1.0], 1, &mut out)?;
/// assert_eq!(out, [0.0, 0.0, 0.0, 1.0, 1.0, 1.0]);
/// # Ok::<(), lekalo::Error>(())
/// ```
///
/// # Errors
/// [`Error::InvalidArgument`] for an empty `t`; [`Error::LengthMismatch`] for `out` not of
/// `t.len() + 2nu` numbers.
pub fn antiderivative_knots_into(t: &[f64], nu: usize, out: &mut [f64]) -> Result<()> {
    let (Some(&first), Some(&last)) = (t.first(), t.last()) else {
        return Err(invalid_spline("no knots".into()));
    };
    let len = nu
        .checked_mul(2)
        .and_then(|v| v.checked_add(t.len()))
        .ok_or_else(|| invalid_spline(format!("antiderivative order {nu} is too large")))?;
    if out.len() != len {
        return Err(Error::LengthMismatch {
            what: "knot buffer (knots + 2 × order)".into(),
            expected: len,
            got: out.len(),
        });
    }
    let (head, rest) = out.split_at_mut(nu);
    let (middle, tail) = rest.split_at_mut(t.len());
    head.fill(first);
    middle.copy_from_slice(t);
    tail.fill(last);
    Ok(())
}

/// The span `s` of `x` for the spline `(t, k)` with `n` coefficients: `t_s ≤ x < t_{s+1}`,
/// `k ≤ s < n`, non-empty; below the domain the first non-empty span, from `t_n` on the last
/// (the end polynomials continued, as [`crate::bspline_value`]).
fn span_of(t: &[f64], k: usize, n: usize, x: f64) -> usize {
    // the last s in k..n with t_s ≤ x (k when none): a binary search over k + 1 .. n
    let (mut a, mut b) = (k + 1, n);
    while a < b {
        let m = a + (b - a) / 2;
        if t[m] <= x {
            a = m + 1;
        } else {
            b = m;
        }
    }
    let mut s = a - 1;
    // empty spans: down to the last non-empty one (x at or beyond t_n, or on repeated knots),
    // up from k at the left end
    while s > k && t[s] >= t[s + 1] {
        s -= 1;
    }
    while s + 1 < n && t[s] >= t[s + 1] {
        s += 1;
    }
    s
}

/// `∫_a^b S(x) dx` of the spline `(t, c, k)` into `out` (`dim` numbers), the end polynomials
/// continued beyond the domain `[t_k, t_n]` (so that inside it this is the plain integral):
/// `A(b) − A(a)` with `A = Σ_l P̃_l Ñ_l` the antiderivative of
/// [`antiderivative_coefficients_into`] (de Boor, ch. X, eq. (31)). Since the `Ñ_l` sum to one,
/// the prefix sums `P̃_l` may start at the first B-spline that is non-zero at `a`: only the
/// coefficients between the spans of `a` and `b` are read, and nothing is allocated beyond
/// `O(k · dim)`. `a > b` gives the negative of `∫_b^a`. SciPy's `BSpline.integrate` and
/// `splint` (with the limits first clipped to the domain when not extrapolating).
///
/// ```
/// use lekalo::curve::integral_into;
/// // t² on [0, 1] (coefficients 0, 0, 1): ∫_0^1 = 1/3; continued, ∫_{-1}^{2} t² = 3
/// let t = [0.0, 0.0, 0.0, 1.0, 1.0, 1.0];
/// let mut out = [0.0];
/// integral_into(&t, 2, &[0.0, 0.0, 1.0], 1, 0.0, 1.0, &mut out)?;
/// assert!((out[0] - 1.0 / 3.0).abs() < 1e-15);
/// integral_into(&t, 2, &[0.0, 0.0, 1.0], 1, -1.0, 2.0, &mut out)?;
/// assert!((out[0] - 3.0).abs() < 1e-14);
/// # Ok::<(), lekalo::Error>(())
/// ```
///
/// # Errors
/// [`Error::InvalidArgument`] for fewer than `2k + 2` knots, fewer coefficients than `n`, no
/// column, or an empty domain; [`Error::Degree`] if `k + 1` exceeds [`crate::MAX_DEGREE`];
/// [`Error::NonFinite`] for a non-finite limit or a result that overflows inside the domain;
/// [`Error::InvalidArgument`] naming the limits for one that overflows beyond it (the end
/// polynomials continued); [`Error::LengthMismatch`] for `out` not of `dim` numbers.
#[allow(clippy::neg_cmp_op_on_partial_ord)] // NaN knots must read as an empty domain
pub fn integral_into(
    t: &[f64],
    k: usize,
    c: &[f64],
    dim: usize,
    a: f64,
    b: f64,
    out: &mut [f64],
) -> Result<()> {
    let n = coefficient_count(t, k, c, dim)?;
    check_degree_bound(k.saturating_add(1))?;
    if out.len() != dim {
        return Err(buffer_size(dim, out.len()));
    }
    check_finite("integration limits [a, b]", &[a, b])?;
    if !(t[k] < t[n]) {
        return Err(Error::InvalidArgument {
            what: "spline (knots, degree, coefficients)".into(),
            reason: format!("the domain [t_k, t_n] = [{}, {}] is empty", t[k], t[n]),
        });
    }
    let limits = (a, b);
    let (a, b, sign) = if b < a { (b, a, -1.0) } else { (a, b, 1.0) };
    let q = k + 1;
    // the extended knots t̃ (each end knot once more): t̃_0 = t_0, t̃_i = t_{i−1}, t̃_{len+1} = t_last
    let ext = |i: usize| t[i.saturating_sub(1).min(t.len() - 1)];
    let mut scratch = BasisScratch::new(q);
    let mut window = vec![0.0; 2 * q];
    let mut basis_at = |x: f64, sigma: usize, basis: &mut [f64]| {
        // Ñ_{σ−q ..= σ}(x) by Cox–de Boor on the knots t̃_{σ−q+1 ..= σ+q}
        for (i, w) in window.iter_mut().enumerate() {
            *w = ext(sigma + 1 + i - q);
        }
        basis_funs_into(&window, q, q - 1, x, &mut scratch, basis);
    };
    // the span of t̃ is one more than that of t (same domain, one more knot in front)
    let sigma_a = span_of(t, k, n, a) + 1;
    let sigma_b = span_of(t, k, n, b) + 1;
    let mut na = vec![0.0; q + 1];
    let mut nb = vec![0.0; q + 1];
    basis_at(a, sigma_a, &mut na);
    basis_at(b, sigma_b, &mut nb);
    // D_l = P̃_l − P̃_L = Σ_{L ≤ j < l} c_j w_j, L = σ_a − q; the result Σ D_l Ñ_l(b) − Σ D_l Ñ_l(a)
    let base = sigma_a - q;
    let scale = 1.0 / (q as f64);
    let mut acc = vec![0.0; dim];
    out.fill(0.0);
    let b_first = sigma_b - q; // the first B-spline non-zero at b (≥ base, as b ≥ a)
    let mut l = base;
    while l <= sigma_b {
        if l > sigma_a && l < b_first {
            // between the two windows only the running sum grows: one tight pass
            running_sum(t, k, c, dim, l, b_first, scale, &mut acc);
            l = b_first;
            continue;
        }
        if l <= sigma_a {
            let v = na[l - base];
            for (o, d) in out.iter_mut().zip(&acc) {
                *o -= v * d;
            }
        }
        if l + q >= sigma_b {
            let v = nb[l + q - sigma_b];
            for (o, d) in out.iter_mut().zip(&acc) {
                *o += v * d;
            }
        }
        if l < sigma_b {
            running_sum(t, k, c, dim, l, l + 1, scale, &mut acc);
        }
        l += 1;
    }
    for o in out.iter_mut() {
        *o *= sign;
    }
    crate::curve::integral::check_integral(
        out,
        limits.0,
        limits.1,
        t[k],
        t[n],
        "integral (overflow: rescale the coefficients)",
    )
}

/// The integrals `∫_a^b N_{i,k}(x) dx` of the `n = t.len() − k − 1` B-splines of degree `k`
/// on the knots `t` into `out` (FITPACK's `fpintb`, what SciPy's `splint(..., full_output=1)`
/// returns), for limits in the domain `[t_k, t_n]`: with `Ñ_l` the B-splines of degree `k + 1`
/// on the knots `t̃` of [`antiderivative_coefficients_into`] (each end knot once more),
/// `∫_{t_0}^x N_{i,k} = (t_{i+k+1} − t_i)/(k + 1) · Σ_{l>i} Ñ_l(x)` (de Boor, *A Practical
/// Guide to Splines*, ch. X, eq. (31) for the unit coefficient vector `e_i`), and inside the
/// domain the tail sums are 1 left of the window of `x` and 0 right of it. `a > b` gives the
/// negatives. O(n + k²).
///
/// ```
/// use lekalo::curve::basis_integrals_into;
/// // the quadratic B-splines on [0, 1] (Bernstein): each integrates to 1/3
/// let t = [0.0, 0.0, 0.0, 1.0, 1.0, 1.0];
/// let mut out = [0.0; 3];
/// basis_integrals_into(&t, 2, 0.0, 1.0, &mut out)?;
/// assert!(out.iter().all(|v| (v - 1.0 / 3.0).abs() < 1e-15));
/// # Ok::<(), lekalo::Error>(())
/// ```
///
/// # Errors
/// [`Error::InvalidArgument`] for fewer than `2k + 2` knots or an empty domain;
/// [`Error::Degree`] if `k + 1` exceeds [`crate::MAX_DEGREE`];
/// [`Error::ParameterOutOfDomain`] for a limit outside the domain or NaN;
/// [`Error::LengthMismatch`] for `out` not of `n` numbers.
#[allow(clippy::neg_cmp_op_on_partial_ord)] // NaN knots must read as an empty domain
pub fn basis_integrals_into(t: &[f64], k: usize, a: f64, b: f64, out: &mut [f64]) -> Result<()> {
    let n = basis_count(t, k)?;
    check_degree_bound(k.saturating_add(1))?;
    if out.len() != n {
        return Err(buffer_size(n, out.len()));
    }
    if !(t[k] < t[n]) {
        return Err(Error::InvalidArgument {
            what: "spline (knots, degree)".into(),
            reason: format!("the domain [t_k, t_n] = [{}, {}] is empty", t[k], t[n]),
        });
    }
    for x in [a, b] {
        if !(x >= t[k] && x <= t[n]) {
            return Err(Error::ParameterOutOfDomain {
                t: x,
                min: t[k],
                max: t[n],
            });
        }
    }
    let (a, b, sign) = if b < a { (b, a, -1.0) } else { (a, b, 1.0) };
    let q = k + 1;
    let ext = |i: usize| t[i.saturating_sub(1).min(t.len() - 1)];
    let mut scratch = BasisScratch::new(q);
    let mut window = vec![0.0; 2 * q];
    // the span σ of x in t̃ and the tails Σ_{l ≥ σ−q+j} Ñ_l(x), j = 0 ..= q (tail[q + 1] = 0)
    let mut tails_at = |x: f64| {
        let sigma = span_of(t, k, n, x) + 1;
        for (i, w) in window.iter_mut().enumerate() {
            *w = ext(sigma + 1 + i - q);
        }
        let mut basis = vec![0.0; q + 1];
        basis_funs_into(&window, q, q - 1, x, &mut scratch, &mut basis);
        let mut tail = vec![0.0; q + 2];
        for j in (0..=q).rev() {
            tail[j] = tail[j + 1] + basis[j];
        }
        (sigma, tail)
    };
    let (sa, ta) = tails_at(a);
    let (sb, tb) = tails_at(b);
    // Σ_{l>i} Ñ_l(x): 1 for i < σ − q, 0 for i ≥ σ, the window's tail between
    let tail = |i: usize, sigma: usize, tails: &[f64]| {
        if i + q < sigma {
            1.0
        } else if i >= sigma {
            0.0
        } else {
            tails[i + 1 + q - sigma]
        }
    };
    let scale = 1.0 / (q as f64);
    for (i, o) in out.iter_mut().enumerate() {
        let w = (t[i + q] - t[i]) * scale;
        *o = sign * w * (tail(i, sb, &tb) - tail(i, sa, &ta));
    }
    Ok(())
}

/// `acc += Σ_{j=from}^{to−1} c_j (t_{j+k+1} − t_j) · scale`; one column in four independent
/// sums.
#[allow(clippy::too_many_arguments)]
fn running_sum(
    t: &[f64],
    k: usize,
    c: &[f64],
    dim: usize,
    from: usize,
    to: usize,
    scale: f64,
    acc: &mut [f64],
) {
    if dim == 1 {
        let (cs, lo, hi) = (&c[from..to], &t[from..to], &t[from + k + 1..to + k + 1]);
        acc[0] += weighted_sum(cs, lo, hi) * scale;
        return;
    }
    for j in from..to {
        let w = (t[j + k + 1] - t[j]) * scale;
        for (s, x) in acc.iter_mut().zip(&c[j * dim..(j + 1) * dim]) {
            *s += x * w;
        }
    }
}

/// `Σ_j c_j (hi_j − lo_j)` in four interleaved partial sums (lane `r` takes the terms
/// `j ≡ r mod 4`), joined as `(s_0 + s_1) + (s_2 + s_3)`, then the terms past the last multiple
/// of four in order.
#[inline(always)]
fn weighted_sum_body(cs: &[f64], lo: &[f64], hi: &[f64]) -> f64 {
    let mut s = [0.0; 4];
    let mut chunks = cs
        .chunks_exact(4)
        .zip(lo.chunks_exact(4).zip(hi.chunks_exact(4)));
    for (x, (a, b)) in chunks.by_ref() {
        for r in 0..4 {
            s[r] += x[r] * (b[r] - a[r]);
        }
    }
    let done = cs.len() / 4 * 4;
    let mut tail = 0.0;
    for j in done..cs.len() {
        tail += cs[j] * (hi[j] - lo[j]);
    }
    (s[0] + s[1]) + (s[2] + s[3]) + tail
}

crate::numeric::isa::avx2_dispatch! {
    /// [`weighted_sum_body`], its four lanes one AVX2 vector where the processor has it
    /// ([`crate::numeric::isa`]; the same operations in the same order, the same bits).
    #[inline(never)]
    fn weighted_sum(cs: &[f64], lo: &[f64], hi: &[f64]) -> f64 = weighted_sum_body;
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{BSplineCurve, Points};
    use proptest::prelude::*;

    fn curve(t: &[f64], k: usize, c: &[f64], dim: usize) -> BSplineCurve {
        BSplineCurve::new(k, t.to_vec(), Points::from_flat(dim, c.to_vec()).unwrap()).unwrap()
    }

    /// A clamped knot vector on [0, 10] with jittered interior knots, and coefficients.
    fn spline(k: usize, n: usize, dim: usize, seed: u64) -> (Vec<f64>, Vec<f64>) {
        let mut s = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        let mut next = || {
            s = s
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (s >> 11) as f64 / (1u64 << 53) as f64
        };
        let inner = n - k - 1;
        let mut t = vec![0.0; k + 1];
        for i in 1..=inner {
            t.push((i as f64 + 0.4 * (next() - 0.5)) * 10.0 / (inner + 1) as f64);
        }
        t.extend(std::iter::repeat_n(10.0, k + 1));
        let c = (0..n * dim).map(|_| next() * 2.0 - 1.0).collect();
        (t, c)
    }

    proptest! {
        /// The derivative coefficients are those of the derivative curve, bit for bit, and the
        /// rows past them are zero.
        #[test]
        fn derivative_matches_the_curve(k in 1usize..6, extra in 0usize..20, dim in 1usize..4, seed in any::<u64>(), nu in 1usize..6) {
            let n = k + 1 + extra;
            let (t, c) = spline(k, n, dim, seed);
            let nu = nu.min(k);
            let mut out = vec![f64::NAN; (t.len() - 2 * nu) * dim];
            derivative_coefficients_into(&t, k, &c, dim, nu, &mut out).unwrap();
            let mut d = curve(&t, k, &c, dim);
            for _ in 0..nu {
                d = d.derivative().unwrap();
            }
            let m = d.control_points().as_slice().len();
            prop_assert_eq!(&out[..m], d.control_points().as_slice());
            prop_assert!(out[m..].iter().all(|&v| v == 0.0));
            prop_assert_eq!(d.knots().as_slice(), &t[nu..t.len() - nu]);
        }

        /// The antiderivative coefficients are those of the antiderivative curve, bit for bit,
        /// the rows past them copies of the last.
        #[test]
        fn antiderivative_matches_the_curve(k in 0usize..6, extra in 0usize..20, dim in 1usize..4, seed in any::<u64>(), nu in 1usize..3) {
            let n = k + 1 + extra;
            let (t, c) = spline(k, n, dim, seed);
            let mut out = vec![f64::NAN; (t.len() + 2 * nu) * dim];
            antiderivative_coefficients_into(&t, k, &c, dim, nu, &mut out).unwrap();
            let a = curve(&t, k, &c, dim).antiderivative(nu).unwrap();
            let m = a.control_points().as_slice().len();
            prop_assert_eq!(&out[..m], a.control_points().as_slice());
            let last = &out[m - dim..m];
            prop_assert!(out[m..].chunks_exact(dim).all(|r| r == last));
        }

        /// The integral agrees with the difference of the antiderivative curve's values, inside
        /// the domain and continued beyond it, to rounding of the data's scale.
        #[test]
        fn integral_matches_the_antiderivative(k in 0usize..6, extra in 0usize..30, dim in 1usize..3, seed in any::<u64>(), a in -2.0f64..12.0, b in -2.0f64..12.0) {
            let n = k + 1 + extra;
            let (t, c) = spline(k, n, dim, seed);
            let mut out = vec![f64::NAN; dim];
            integral_into(&t, k, &c, dim, a, b, &mut out).unwrap();
            let want = curve(&t, k, &c, dim).integral_extrapolated(a, b).unwrap();
            // |∫| ≤ |b − a| · max|c| with |c| ≤ 1 inside; beyond, the end polynomials grow
            let scale = 1.0 + (b - a).abs() * (1.0 + 12f64.powf(k as f64 + 1.0));
            for (o, w) in out.iter().zip(&want) {
                prop_assert!((o - w).abs() <= 1e-12 * scale, "{} against {}", o, w);
            }
        }

        /// Each basis integral is the integral of the spline with that unit coefficient vector
        /// (one column a B-spline: the identity as coefficients), and inside the domain they add
        /// up to `b − a` (the B-splines sum to one).
        #[test]
        fn basis_integrals_are_the_integrals_of_unit_coefficients(k in 0usize..6, extra in 0usize..12, seed in any::<u64>(), a in 0.0f64..10.0, b in 0.0f64..10.0) {
            let n = k + 1 + extra;
            let (t, _) = spline(k, n, 1, seed);
            let mut out = vec![f64::NAN; n];
            basis_integrals_into(&t, k, a, b, &mut out).unwrap();
            let identity: Vec<f64> = (0..n * n).map(|i| f64::from(u8::from(i / n == i % n))).collect();
            let mut want = vec![f64::NAN; n];
            integral_into(&t, k, &identity, n, a, b, &mut want).unwrap();
            for (o, w) in out.iter().zip(&want) {
                prop_assert!((o - w).abs() <= 1e-14 * 10.0, "{} against {}", o, w);
            }
            let total: f64 = out.iter().sum();
            prop_assert!((total - (b - a)).abs() <= 1e-13 * 10.0, "sum {} for b − a = {}", total, b - a);
        }
    }

    #[test]
    fn basis_integrals_refuse_limits_outside_the_domain() {
        let t = [0.0, 0.0, 1.0, 2.0, 2.0];
        let mut out = [0.0; 3];
        for x in [-0.5, 2.5, f64::NAN] {
            assert!(matches!(
                basis_integrals_into(&t, 1, x, 1.0, &mut out),
                Err(Error::ParameterOutOfDomain { .. })
            ));
        }
        assert!(matches!(
            basis_integrals_into(&t, 1, 0.0, 1.0, &mut out[..2]),
            Err(Error::LengthMismatch { .. })
        ));
        assert!(matches!(
            basis_integrals_into(&t[..3], 1, 0.0, 1.0, &mut out),
            Err(Error::InvalidArgument { .. })
        ));
        // the hat functions on 0, 1, 2: ∫_0^1 gives 1/2, 1/2, 0; reversed limits the negatives
        basis_integrals_into(&t, 1, 1.0, 0.0, &mut out).unwrap();
        assert_eq!(out, [-0.5, -0.5, 0.0]);
    }

    #[test]
    fn refusals_name_the_problem() {
        let t = [0.0, 0.0, 1.0, 1.0];
        let mut out = [0.0; 4];
        assert!(matches!(
            derivative_coefficients_into(&t, 1, &[0.0, 1.0], 1, 2, &mut out),
            Err(Error::InvalidArgument { .. })
        ));
        assert!(matches!(
            derivative_coefficients_into(&t, 1, &[0.0, 1.0], 1, 1, &mut out[..1]),
            Err(Error::LengthMismatch { .. })
        ));
        // a knot of multiplicity k inside: the cubic is C⁰ there, not twice differentiable
        let t = [0.0, 0.0, 0.0, 0.0, 0.5, 0.5, 0.5, 1.0, 1.0, 1.0, 1.0];
        let c = [0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0];
        let mut out = [0.0; 7];
        assert!(derivative_coefficients_into(&t, 3, &c, 1, 2, &mut out).is_err());
        assert!(matches!(
            integral_into(&[0.0, 0.0, 1.0, 1.0], 1, &[0.0], 1, 0.0, 1.0, &mut [0.0]),
            Err(Error::InvalidArgument { .. })
        ));
        assert!(matches!(
            integral_into(
                &[0.0, 0.0, 1.0, 1.0],
                1,
                &[0.0, 1.0],
                1,
                f64::NAN,
                1.0,
                &mut [0.0]
            ),
            Err(Error::NonFinite { .. })
        ));
    }

    /// The AVX2 copies of the two kernels ([`quotient_pass`], [`weighted_sum`]) return the
    /// bits of the baseline ones, on lengths around the vector width.
    #[test]
    fn avx2_kernels_match_the_baseline_bit_for_bit() {
        for len in [0usize, 1, 3, 4, 5, 7, 8, 9, 63, 64, 65, 1000] {
            let (t, c) = spline(3, len + 5, 1, len as u64);
            let (lo, hi) = (&t[1..=len], &t[4..len + 4]);
            let (x0, x1) = (&c[..len], &c[1..=len]);
            let (mut a, mut b) = (vec![0.0; len], vec![0.0; len]);
            let ok_a = quotient_pass_body(lo, hi, x0, x1, 3.0, &mut a);
            let ok_b = quotient_pass(lo, hi, x0, x1, 3.0, &mut b);
            assert_eq!(ok_a, ok_b, "flags at {len}");
            assert!(
                a.iter().zip(&b).all(|(u, v)| u.to_bits() == v.to_bits()),
                "quotients at {len}"
            );
            let (u, v) = (weighted_sum_body(x0, lo, hi), weighted_sum(x0, lo, hi));
            assert_eq!(u.to_bits(), v.to_bits(), "sums at {len}");
        }
    }

    /// Results that overflow are refused, naming the first row that did, whichever check
    /// found them (the fused flag of the derivative's pass, the antiderivative's last row);
    /// a NaN coefficient is refused the same way.
    #[test]
    fn overflow_and_nan_are_refused_at_their_row() {
        let (t, mut c) = spline(3, 200, 1, 7);
        // a huge coefficient: its differences over knot gaps below 3 overflow, first at row 119
        c[120] = f64::MAX;
        c[121] = -f64::MAX;
        let mut out = vec![0.0; t.len() - 2];
        match derivative_coefficients_into(&t, 3, &c, 1, 1, &mut out) {
            Err(Error::NonFinite { index, .. }) => assert_eq!(index, 119),
            other => panic!("expected NonFinite at 119, got {other:?}"),
        }
        // the running sum of a hundred huge terms of one sign passes f64::MAX
        c[100..].fill(f64::MAX);
        let mut out = vec![0.0; t.len() + 2];
        let err = antiderivative_coefficients_into(&t, 3, &c, 1, 1, &mut out).unwrap_err();
        assert!(matches!(err, Error::NonFinite { .. }), "{err:?}");
        let (t, mut c) = spline(2, 100, 2, 3);
        c[2 * 50 + 1] = f64::NAN;
        let mut out = vec![0.0; (t.len() + 2) * 2];
        match antiderivative_coefficients_into(&t, 2, &c, 2, 1, &mut out) {
            Err(Error::NonFinite { index, .. }) => assert_eq!(index, 2 * 51 + 1),
            other => panic!("expected NonFinite at row 51, got {other:?}"),
        }
        let mut out = vec![0.0; (t.len() - 2) * 2];
        assert!(matches!(
            derivative_coefficients_into(&t, 2, &c, 2, 1, &mut out),
            Err(Error::NonFinite { .. })
        ));
        // order 0 copies the coefficients, NaN and all: refused at its index either way
        let mut out = vec![0.0; t.len() * 2];
        for result in [
            antiderivative_coefficients_into(&t, 2, &c, 2, 0, &mut out),
            derivative_coefficients_into(&t, 2, &c, 2, 0, &mut out),
        ] {
            match result {
                Err(Error::NonFinite { index, .. }) => assert_eq!(index, 2 * 50 + 1),
                other => panic!("expected NonFinite at row 50, got {other:?}"),
            }
        }
        let mut out = vec![0.0; t.len() - 2];
        let mut c1: Vec<f64> = c.iter().step_by(2).copied().collect();
        c1[60] = f64::NAN;
        match derivative_coefficients_into(&t, 2, &c1, 1, 1, &mut out) {
            Err(Error::NonFinite { index, .. }) => assert_eq!(index, 59),
            other => panic!("expected NonFinite at 59, got {other:?}"),
        }
    }

    #[test]
    fn antiderivative_knots_repeat_the_ends() {
        let mut out = [f64::NAN; 8];
        antiderivative_knots_into(&[0.0, 1.0, 2.0, 3.0], 2, &mut out).unwrap();
        assert_eq!(out, [0.0, 0.0, 0.0, 1.0, 2.0, 3.0, 3.0, 3.0]);
        assert!(matches!(
            antiderivative_knots_into(&[0.0, 1.0], 1, &mut out),
            Err(Error::LengthMismatch { .. })
        ));
        assert!(antiderivative_knots_into(&[], 1, &mut out[..2]).is_err());
        assert!(antiderivative_knots_into(&[0.0], usize::MAX, &mut out).is_err());
    }
}
