//! Basis functions: Bernstein polynomials and B-splines.
//!
//! - Bernstein polynomials `b_{n,i}(t) = C(n,i) t^i (1−t)^{n−i}` (document 002, Bezier curves,
//!   document 004 eq. 1) and their derivatives.
//! - All non-zero B-spline basis functions of degree `p` at `t` by the Cox–de Boor triangular
//!   scheme (P&T Algorithm A2.2) and their derivatives (A2.3).
//! - A single `N_{i,p}(t)` by the lecture's recursive definition (document 002, B-splines), the
//!   slow textbook oracle for the fast kernels.
//!
//! The B-spline as a divided difference of truncated powers (document 003 eq. 4) lives with the
//! divided differences in `divdiff`.
//!
//! Conventions: `N_{i,0}` is the indicator of the half-open `[t_i, t_{i+1})`, except that at the
//! last knot the last non-empty interval is closed, so that splines evaluate at their right end.
//! Terms with a zero denominator are zero.

use crate::error::{check_derivative_order, Error, Result, MAX_DERIVATIVE_ORDER};
use crate::knots::KnotVector;

/// Bernstein polynomial `b_{n,i}(t) = C(n,i) t^i (1 − t)^{n−i}`; zero for `i > n`.
///
/// Computed by the triangular recurrence `b_{j,i} = (1−t) b_{j−1,i} + t b_{j−1,i−1}` (P&T A1.2),
/// which is stable for every `t ∈ [0, 1]`. O(n²).
///
/// ```
/// use lekalo::basis::bernstein;
/// assert!((bernstein(3, 1, 0.5) - 0.375).abs() < 1e-15);
/// let sum: f64 = (0..=7).map(|i| bernstein(7, i, 0.3)).sum();
/// assert!((sum - 1.0).abs() < 1e-15);
/// ```
#[must_use]
pub fn bernstein(n: usize, i: usize, t: f64) -> f64 {
    if i > n {
        return 0.0;
    }
    let mut tmp = vec![0.0; n + 1];
    tmp[n - i] = 1.0;
    let t1 = 1.0 - t;
    for k in 1..=n {
        for j in (k..=n).rev() {
            tmp[j] = t1 * tmp[j] + t * tmp[j - 1];
        }
    }
    tmp[n]
}

/// All Bernstein polynomials `b_{n,0..=n}(t)` into `out` (length `n + 1`), P&T Algorithm A1.3.
/// O(n²), no allocation.
///
/// # Errors
/// [`Error::LengthMismatch`] if `out.len() != n + 1`.
pub fn bernstein_all(n: usize, t: f64, out: &mut [f64]) -> Result<()> {
    if n.checked_add(1) != Some(out.len()) {
        return Err(Error::LengthMismatch {
            what: "output buffer (degree + 1)".into(),
            expected: n.saturating_add(1),
            got: out.len(),
        });
    }
    bernstein_all_unchecked(n, t, out);
    Ok(())
}

#[inline]
pub(crate) fn bernstein_all_unchecked(n: usize, t: f64, out: &mut [f64]) {
    out[0] = 1.0;
    let t1 = 1.0 - t;
    for j in 1..=n {
        let mut saved = 0.0;
        for o in out.iter_mut().take(j) {
            let temp = *o;
            *o = saved + t1 * temp;
            saved = t * temp;
        }
        out[j] = saved;
    }
}

/// Derivatives of all Bernstein polynomials of degree `n` at `t`, orders `0..=order`.
///
/// Uses `b_{n,i}^{(r)} = n!/(n−r)! Σ_j (−1)^{r−j} C(r,j) b_{n−r,i−j}` (the r-th forward
/// difference of the lower-degree basis). Returns `(order + 1) × (n + 1)` values row by row:
/// row `r` holds `b_{n,0..=n}^{(r)}(t)`; orders above `n` give zero rows.
///
/// ```
/// use lekalo::basis::bernstein_derivatives;
/// // b_{2,1}(t) = 2t(1 − t): derivative 2 − 4t, second derivative −4
/// let d = bernstein_derivatives(2, 0.25, 2)?;
/// assert!((d[3 + 1] - 1.0).abs() < 1e-15);
/// assert!((d[6 + 1] + 4.0).abs() < 1e-15);
/// # Ok::<(), lekalo::Error>(())
/// ```
///
/// # Errors
/// [`Error::TooLarge`] if `order` exceeds
/// [`MAX_DERIVATIVE_ORDER`].
pub fn bernstein_derivatives(n: usize, t: f64, order: usize) -> Result<Vec<f64>> {
    check_derivative_order(order, MAX_DERIVATIVE_ORDER)?;
    let w = n + 1;
    let mut out = vec![0.0; (order + 1) * w];
    let mut lower = vec![0.0; w];
    for r in 0..=order.min(n) {
        let m = n - r;
        bernstein_all_unchecked(m, t, &mut lower[..=m]);
        let falling: f64 = (m + 1..=n).map(|x| x as f64).product();
        let row = &mut out[r * w..(r + 1) * w];
        // row[i] = falling * Σ_j (−1)^{r−j} C(r,j) lower[i−j], 0 ≤ i − j ≤ m
        let mut binom = 1.0;
        for j in 0..=r {
            let sign = if (r - j) % 2 == 0 { 1.0 } else { -1.0 };
            for (l, &b) in lower[..=m].iter().enumerate() {
                row[l + j] += falling * sign * binom * b;
            }
            binom = binom * (r - j) as f64 / (j + 1) as f64;
        }
    }
    Ok(out)
}

/// Scratch space for the B-spline basis kernels, sized once for a degree so that batch
/// evaluation does not allocate per point.
#[derive(Debug, Clone)]
pub(crate) struct BasisScratch {
    left: Vec<f64>,
    right: Vec<f64>,
    ndu: Vec<f64>,
    a: Vec<f64>,
}

impl BasisScratch {
    pub(crate) fn new(degree: usize) -> Self {
        let w = degree + 1;
        BasisScratch {
            left: vec![0.0; w],
            right: vec![0.0; w],
            ndu: vec![0.0; w * w],
            a: vec![0.0; 2 * w],
        }
    }
}

/// The `p + 1` non-zero basis functions `N_{span−p..=span, p}(t)` into `out`, by the Cox–de Boor
/// triangular scheme (P&T Algorithm A2.2). `span` must be the span of `t` (see
/// [`KnotVector::find_span`]); then every denominator is positive. O(p²), no allocation.
#[inline]
pub(crate) fn basis_funs_into(
    knots: &[f64],
    degree: usize,
    span: usize,
    t: f64,
    scratch: &mut BasisScratch,
    out: &mut [f64],
) {
    let (left, right) = (&mut scratch.left, &mut scratch.right);
    out[0] = 1.0;
    for j in 1..=degree {
        left[j] = t - knots[span + 1 - j];
        right[j] = knots[span + j] - t;
        let mut saved = 0.0;
        for r in 0..j {
            let temp = out[r] / (right[r + 1] + left[j - r]);
            out[r] = saved + right[r + 1] * temp;
            saved = left[j - r] * temp;
        }
        out[j] = saved;
    }
}

/// [`basis_funs_into`] for a degree known at compile time (`W = p + 1`): the same operations
/// in the same order (P&T Algorithm A2.2), so the same bits, with the scratch on the stack and
/// the loops unrolled. Batch evaluation of low-degree curves spends most of its time here.
/// The scheme is written out again rather than shared with [`basis_funs_into`] through an
/// inlined helper: that form compiled to slower code (17.2 against 14.9 ns a cubic sample in
/// 3-D, measured).
#[inline]
pub(crate) fn basis_funs_fixed<const W: usize>(knots: &[f64], span: usize, t: f64) -> [f64; W] {
    let mut left = [0.0; W];
    let mut right = [0.0; W];
    let mut out = [0.0; W];
    out[0] = 1.0;
    for j in 1..W {
        left[j] = t - knots[span + 1 - j];
        right[j] = knots[span + j] - t;
        let mut saved = 0.0;
        for r in 0..j {
            let temp = out[r] / (right[r + 1] + left[j - r]);
            out[r] = saved + right[r + 1] * temp;
            saved = left[j - r] * temp;
        }
        out[j] = saved;
    }
    out
}

/// The non-zero basis functions of order `W` (degree `p = W − 1`) on one knot span, for many
/// parameters in it: the Cox–de Boor scheme of [`basis_funs_into`] (P&T A2.2) with the
/// reciprocals of its denominators `t_{span+r+1} − t_{span+r+1−j}` (`1 ≤ j ≤ p`, `0 ≤ r < j`),
/// which do not depend on the parameter, computed once per span. An evaluation then has no
/// division and, the order being a constant, unrolled loops: for sorted parameters (a fitting
/// pass) the span changes rarely. The values agree with [`basis_funs_into`] to 5p ulps: each
/// scheme is within 5p·u of the exact values (non-negative terms, five roundings a level).
#[derive(Debug, Clone)]
pub(crate) struct SpanBasis<const W: usize> {
    span: Option<usize>,
    /// `t_{span+1−j}` at `j` (`1 ≤ j ≤ p`).
    below: [f64; W],
    /// `t_{span+j}` at `j` (`1 ≤ j ≤ p`).
    above: [f64; W],
    /// `1/(t_{span+r+1} − t_{span+r+1−j})` at `[j][r]`.
    inv: [[f64; W]; W],
}

impl<const W: usize> SpanBasis<W> {
    pub(crate) fn new() -> Self {
        SpanBasis {
            span: None,
            below: [0.0; W],
            above: [0.0; W],
            inv: [[0.0; W]; W],
        }
    }

    /// Prepares the span (`t_span < t_{span+1}`, `p ≤ span < len − p − 1`); nothing to do when it
    /// is the current one.
    #[inline]
    pub(crate) fn set_span(&mut self, knots: &[f64], span: usize) {
        if self.span == Some(span) {
            return;
        }
        self.span = Some(span);
        for j in 1..W {
            self.below[j] = knots[span + 1 - j];
            self.above[j] = knots[span + j];
            for r in 0..j {
                self.inv[j][r] = 1.0 / (knots[span + r + 1] - knots[span + r + 1 - j]);
            }
        }
    }

    /// `scale·N_{span−p..=span, p}(t)` into `out[..W]` for `t` in the span of
    /// [`SpanBasis::set_span`] (the scheme is linear in its starting value `N_{span,0} = 1`, so
    /// it starts from `scale`).
    #[inline]
    pub(crate) fn eval(&self, t: f64, scale: f64, out: &mut [f64]) {
        let out = &mut out[..W];
        out[0] = scale;
        for j in 1..W {
            let mut saved = 0.0;
            for r in 0..j {
                // left_{j−r} = t − t_{span+1−j+r}, right_{r+1} = t_{span+r+1} − t
                let temp = out[r] * self.inv[j][r];
                out[r] = saved + (self.above[r + 1] - t) * temp;
                saved = (t - self.below[j - r]) * temp;
            }
            out[j] = saved;
        }
    }
}

/// Derivatives of orders `0..=n_ders` of the `p + 1` non-zero basis functions at `t`, into `out`
/// laid out row by row (`(n_ders + 1) × (p + 1)`); P&T Algorithm A2.3. Orders above `p` are zero.
/// O((`n_ders` + 1)·p²), no allocation.
#[inline]
pub(crate) fn basis_ders_into(
    knots: &[f64],
    degree: usize,
    span: usize,
    t: f64,
    n_ders: usize,
    scratch: &mut BasisScratch,
    out: &mut [f64],
) {
    let p = degree;
    let w = p + 1;
    let BasisScratch {
        left,
        right,
        ndu,
        a,
    } = scratch;
    // ndu[j*w + r]: upper triangle basis values, lower triangle knot differences
    ndu[0] = 1.0;
    for j in 1..=p {
        left[j] = t - knots[span + 1 - j];
        right[j] = knots[span + j] - t;
        let mut saved = 0.0;
        for r in 0..j {
            ndu[j * w + r] = right[r + 1] + left[j - r];
            let temp = ndu[r * w + (j - 1)] / ndu[j * w + r];
            ndu[r * w + j] = saved + right[r + 1] * temp;
            saved = left[j - r] * temp;
        }
        ndu[j * w + j] = saved;
    }
    out.fill(0.0);
    for j in 0..=p {
        out[j] = ndu[j * w + p];
    }
    let kmax = n_ders.min(p);
    // a holds two rows of coefficients, alternating
    for r in 0..=p {
        let (mut s1, mut s2) = (0usize, 1usize);
        a[0] = 1.0;
        for k in 1..=kmax {
            let mut d = 0.0;
            let rk = r as isize - k as isize;
            let pk = p - k;
            if r >= k {
                let idx = s2 * w;
                a[idx] = a[s1 * w] / ndu[(pk + 1) * w + r - k];
                d = a[idx] * ndu[(r - k) * w + pk];
            }
            let j1: usize = if rk >= -1 { 1 } else { (-rk) as usize };
            let j2: usize = if r <= pk { k - 1 } else { p - r };
            for j in j1..=j2 {
                let col = (rk + j as isize) as usize;
                a[s2 * w + j] = (a[s1 * w + j] - a[s1 * w + j - 1]) / ndu[(pk + 1) * w + col];
                d += a[s2 * w + j] * ndu[col * w + pk];
            }
            if r <= pk {
                a[s2 * w + k] = -a[s1 * w + k - 1] / ndu[(pk + 1) * w + r];
                d += a[s2 * w + k] * ndu[r * w + pk];
            }
            out[k * w + r] = d;
            std::mem::swap(&mut s1, &mut s2);
        }
    }
    // multiply by p!/(p−k)!
    let mut factor = p as f64;
    for k in 1..=kmax {
        for j in 0..=p {
            out[k * w + j] *= factor;
        }
        factor *= (p - k) as f64;
    }
}

/// The non-zero B-spline basis functions of `degree` at `t`: returns the span `i` and
/// `[N_{i−p,p}(t), …, N_{i,p}(t)]` (Cox–de Boor triangular scheme, P&T Algorithm A2.2).
///
/// ```
/// use lekalo::{basis::basis_functions, KnotVector};
/// let kv = KnotVector::new(vec![0.0, 0.0, 0.0, 1.0, 2.0, 3.0, 4.0, 4.0, 5.0, 5.0, 5.0]).unwrap();
/// let (span, n) = basis_functions(&kv, 2, 2.5).unwrap(); // P&T Example 2.3
/// assert_eq!(span, 4);
/// assert!((n[0] - 1.0 / 8.0).abs() < 1e-15 && (n[1] - 6.0 / 8.0).abs() < 1e-15);
/// assert!((n.iter().sum::<f64>() - 1.0).abs() < 1e-15);
/// ```
///
/// # Errors
/// [`Error::ParameterOutOfDomain`] or [`Error::Degree`] as [`KnotVector::find_span`].
pub fn basis_functions(knots: &KnotVector, degree: usize, t: f64) -> Result<(usize, Vec<f64>)> {
    let span = knots.find_span(degree, t)?;
    let mut out = vec![0.0; degree + 1];
    basis_funs_into(
        knots.as_slice(),
        degree,
        span,
        t,
        &mut BasisScratch::new(degree),
        &mut out,
    );
    Ok((span, out))
}

/// The non-zero basis functions of `degree` at many parameters: for each `t[j]` its span
/// `spans[j]` and `values[j·(p+1)..(j+1)·(p+1)] = [N_{span−p,p}(t_j), …, N_{span,p}(t_j)]`, the
/// banded form of the collocation ("design") matrix `N_{i,p}(t_j)`. The same Cox–de Boor scheme
/// as [`basis_functions`] (P&T Algorithm A2.2), bit for bit, with one scratch space for the
/// batch and a [`SpanCursor`](crate::SpanCursor): amortised O(1) span search for sorted
/// parameters, O(log n) otherwise, and no allocation per parameter.
///
/// ```
/// use lekalo::{basis::{basis_functions, basis_functions_many}, KnotVector};
/// let kv = KnotVector::new(vec![0.0, 0.0, 0.0, 1.0, 2.0, 3.0, 4.0, 4.0, 5.0, 5.0, 5.0]).unwrap();
/// let (spans, values) = basis_functions_many(&kv, 2, &[0.5, 2.5, 5.0]).unwrap();
/// assert_eq!(spans, [2, 4, 7]);
/// assert_eq!(values[3..6], basis_functions(&kv, 2, 2.5).unwrap().1[..]); // P&T Example 2.3
/// # Ok::<(), lekalo::Error>(())
/// ```
///
/// # Errors
/// As [`basis_functions`] for the first parameter outside the domain (or NaN), or a degree the
/// knots cannot carry; [`Error::TooLarge`] beyond [`MAX_SCALARS`](crate::error::MAX_SCALARS)
/// values.
pub fn basis_functions_many(
    knots: &KnotVector,
    degree: usize,
    t: &[f64],
) -> Result<(Vec<usize>, Vec<f64>)> {
    // the degree is checked against the knots before anything is sized from it
    knots.check_degree(degree)?;
    let w = degree + 1;
    let total = t.len().saturating_mul(w);
    if total > crate::error::MAX_SCALARS {
        return Err(Error::TooLarge {
            what: "basis values".into(),
            size: total,
            max: crate::error::MAX_SCALARS,
        });
    }
    let mut cursor = knots.span_cursor(degree);
    let mut scratch = BasisScratch::new(degree);
    let mut spans = Vec::with_capacity(t.len());
    let mut values = vec![0.0; total];
    for (&tj, out) in t.iter().zip(values.chunks_exact_mut(w)) {
        let span = cursor.find(tj)?;
        basis_funs_into(knots.as_slice(), degree, span, tj, &mut scratch, out);
        spans.push(span);
    }
    Ok((spans, values))
}

/// The design (collocation) matrix `B_{j,i} = N_{i,p}(t_j)` of the spline space of `degree` on
/// `knots` at the parameters `t`, in compressed rows written into the caller's buffers: row `j`
/// holds its `p + 1` non-zero entries `N_{s−p..=s,p}(t_j)` (`s` the span of `t_j`) in
/// `values[j·(p+1)..(j+1)·(p+1)]`, and `first_column(j, s − p)` is called with the column of
/// the first of them (a CSR matrix's column indices are `s − p, …, s`; its row pointers
/// `0, p + 1, 2(p + 1), …`). Inside the domain the numbers are those of
/// [`basis_functions_many`], bit for bit (the same span search and Cox–de Boor scheme, P&T
/// Algorithm A2.2). With `extrapolate`, a parameter beyond `[t_p, t_n]` takes the basis
/// polynomials of the end span continued: the same recurrence on that span at `t_j` (its
/// denominators are knot differences, positive whatever `t_j`), as SciPy's
/// `BSpline.design_matrix(extrapolate=True)`. O(m·p²) for `m` parameters, no allocation.
///
/// ```
/// use lekalo::{basis::{basis_functions_many, design_matrix_into}, KnotVector};
/// let kv = KnotVector::new(vec![0.0, 0.0, 0.0, 1.0, 2.0, 3.0, 3.0, 3.0]).unwrap();
/// let mut values = [0.0; 9];
/// let mut first = [0; 3];
/// design_matrix_into(&kv, 2, &[0.5, 3.0, 4.0], true, &mut values, |j, c| first[j] = c)?;
/// assert_eq!(first, [0, 2, 2]);
/// assert_eq!(values[..6], basis_functions_many(&kv, 2, &[0.5, 3.0])?.1[..]);
/// // beyond the end: the last span's polynomials at 4, which still sum to one
/// assert!((values[6..].iter().sum::<f64>() - 1.0).abs() < 1e-15);
/// # Ok::<(), lekalo::Error>(())
/// ```
///
/// # Errors
/// [`Error::Degree`] for a degree the knots cannot carry; [`Error::LengthMismatch`] if
/// `values` does not hold `t.len()·(p + 1)` numbers; [`Error::NonFinite`] for the first NaN or
/// infinite parameter; without `extrapolate`, [`Error::ParameterOutOfDomain`] for the first
/// parameter outside `[t_p, t_n]`.
pub fn design_matrix_into(
    knots: &KnotVector,
    degree: usize,
    t: &[f64],
    extrapolate: bool,
    values: &mut [f64],
    mut first_column: impl FnMut(usize, usize),
) -> Result<()> {
    knots.check_degree(degree)?;
    let w = degree + 1;
    let expected = t.len().saturating_mul(w);
    if values.len() != expected {
        return Err(Error::LengthMismatch {
            what: "design matrix values (parameters × (degree + 1))".into(),
            expected,
            got: values.len(),
        });
    }
    let located = match w {
        2 => design_rows_located::<2>(knots, t, extrapolate, values, &mut first_column),
        3 => design_rows_located::<3>(knots, t, extrapolate, values, &mut first_column),
        4 => design_rows_located::<4>(knots, t, extrapolate, values, &mut first_column),
        5 => design_rows_located::<5>(knots, t, extrapolate, values, &mut first_column),
        6 => design_rows_located::<6>(knots, t, extrapolate, values, &mut first_column),
        _ => None,
    };
    if let Some(done) = located {
        return done;
    }
    let (lo, hi) = knots.domain(degree);
    let mut cursor = knots.span_cursor(degree);
    let mut scratch = BasisScratch::new(degree);
    for (j, (&tj, out)) in t.iter().zip(values.chunks_exact_mut(w)).enumerate() {
        if !tj.is_finite() {
            return Err(Error::NonFinite {
                what: "x".into(),
                index: j,
                value: tj,
            });
        }
        // beyond the domain (extrapolating): the end span, found at the nearest end
        let at = if extrapolate { tj.max(lo).min(hi) } else { tj };
        let span = cursor.find(at)?;
        basis_funs_into(knots.as_slice(), degree, span, tj, &mut scratch, out);
        first_column(j, span - degree);
    }
    Ok(())
}

/// The rows of [`design_matrix_into`] for the order `W = p + 1` known at compile time, the
/// spans found by the bucket table of the B-spline evaluator
/// ([`PieceLocator`](crate::curve::fast_eval::locate::PieceLocator): O(1) a parameter for
/// spread-out knots and no branch to mispredict on unsorted parameters, where the span cursor
/// searches from the previous span) and the values by [`basis_funs_fixed`] (the operations of
/// [`basis_funs_into`] in the same order: the same bits). The same spans as the cursor: the
/// piece `j` with `x_j ≤ t < x_{j+1}` of the distinct knots of the domain is the span of its
/// last knot `x_j`, the last piece at the right end. `None` (nothing written) where the table
/// would cost more than it saves: fewer parameters than pieces, or a domain of one point.
fn design_rows_located<const W: usize>(
    knots: &KnotVector,
    t: &[f64],
    extrapolate: bool,
    values: &mut [f64],
    first_column: &mut impl FnMut(usize, usize),
) -> Option<Result<()>> {
    let p = W - 1;
    let k = knots.as_slice();
    let n = k.len() - W;
    let (mut breaks, mut spans) = (Vec::new(), Vec::new());
    for i in p..n {
        if k[i] < k[i + 1] {
            breaks.push(k[i]);
            spans.push(i);
        }
    }
    if spans.is_empty() || t.len() < spans.len() {
        return None;
    }
    breaks.push(k[n]);
    let locator = crate::curve::fast_eval::locate::PieceLocator::new(&breaks);
    let (lo, hi) = knots.domain(p);
    for (j, (&tj, out)) in t.iter().zip(values.chunks_exact_mut(W)).enumerate() {
        if !tj.is_finite() {
            return Some(Err(Error::NonFinite {
                what: "x".into(),
                index: j,
                value: tj,
            }));
        }
        let at = if extrapolate {
            tj.max(lo).min(hi)
        } else if lo <= tj && tj <= hi {
            tj
        } else {
            return Some(Err(Error::ParameterOutOfDomain {
                t: tj,
                min: lo,
                max: hi,
            }));
        };
        let span = spans[locator.find(&breaks, at)];
        out.copy_from_slice(&basis_funs_fixed::<W>(k, span, tj));
        first_column(j, span - p);
    }
    Some(Ok(()))
}

/// Derivatives of orders `0..=n_ders` of the non-zero basis functions at `t` (P&T Algorithm
/// A2.3): returns the span `i` and `(n_ders + 1) × (p + 1)` values row by row; row `k` holds
/// `N^{(k)}_{i−p..=i,p}(t)`. Orders above `p` are zero. At a knot the derivatives are the
/// right-hand ones (left-hand at the right end of the domain).
///
/// # Errors
/// As [`basis_functions`]; [`Error::TooLarge`] if `n_ders > MAX_DERIVATIVE_ORDER`.
pub fn basis_derivatives(
    knots: &KnotVector,
    degree: usize,
    t: f64,
    n_ders: usize,
) -> Result<(usize, Vec<f64>)> {
    let span = knots.find_span(degree, t)?;
    check_derivative_order(n_ders, MAX_DERIVATIVE_ORDER)?;
    let mut out = vec![0.0; (n_ders + 1) * (degree + 1)];
    basis_ders_into(
        knots.as_slice(),
        degree,
        span,
        t,
        n_ders,
        &mut BasisScratch::new(degree),
        &mut out,
    );
    Ok((span, out))
}

/// Every B-spline `N_{i,p}(t)`, `i = 0 … m − p − 1`, at `t` anywhere on the whole knot range
/// `[t_0, t_m]` (not only the spline's domain, where they sum to 1): the Cox–de Boor recursion
/// of the lecture (document 002) evaluated as a triangular table from degree 0 upwards over the
/// non-zero functions only (de Boor, *A Practical Guide to Splines*, `BSPLVB`), terms with a
/// zero denominator taken as 0 and the last non-empty interval closed at `t_m`, as
/// [`basis_function_recursive`]. O(p²) per `t`, where the recursion is O(2^p); what figures of
/// the basis functions over all their knots draw.
///
/// ```
/// use lekalo::{basis::{basis_function_recursive, basis_functions_full_range}, KnotVector};
/// let kv = KnotVector::new(vec![0.0, 0.0, 1.0, 2.0, 3.0, 3.0]).unwrap();
/// let all = basis_functions_full_range(&kv, 2, 0.5).unwrap();
/// assert_eq!(all.len(), 3);
/// assert!((all[0] - basis_function_recursive(&kv, 0, 2, 0.5).unwrap()).abs() < 1e-15);
/// ```
///
/// # Errors
/// [`Error::Degree`] if the knots carry no function of degree `p`;
/// [`Error::ParameterOutOfDomain`] if `t` is outside `[t_0, t_m]` or NaN.
pub fn basis_functions_full_range(knots: &KnotVector, p: usize, t: f64) -> Result<Vec<f64>> {
    let k = knots.as_slice();
    let m = k.len() - 1;
    let count = m
        .checked_sub(p)
        .filter(|c| *c > 0)
        .ok_or_else(|| Error::Degree {
            degree: p,
            reason: format!("{} knots carry no basis function of this degree", k.len()),
        })?;
    let (min, max) = (k[0], k[m]);
    if !(t >= min && t <= max) {
        return Err(Error::ParameterOutOfDomain { t, min, max });
    }
    // the interval [t_j, t_{j+1}) holding t (the last non-empty one at t = t_m)
    let j = if t == max {
        (0..m).rev().find(|&j| k[j] < k[j + 1])
    } else {
        (0..m).rev().find(|&j| k[j] <= t && t < k[j + 1])
    };
    let mut out = vec![0.0; count];
    let Some(j) = j else {
        return Ok(out); // all knots equal: every function is 0
    };
    // n[d][r] = N_{j−d+r, d}(t), r = 0 … d; indices outside 0 … m − d − 1 are 0
    let mut row = vec![1.0];
    for d in 1..=p {
        let mut next = vec![0.0; d + 1];
        for (r, slot) in next.iter_mut().enumerate() {
            let Some(i) = (j + r).checked_sub(d) else {
                continue;
            };
            if i + d + 1 > m {
                continue;
            }
            let mut v = 0.0;
            // N_{i,d−1} is row[r − 1] when r ≥ 1, N_{i+1,d−1} is row[r] when r < d
            if r >= 1 {
                let den = k[i + d] - k[i];
                if den != 0.0 {
                    v += (t - k[i]) / den * row[r - 1];
                }
            }
            if r < d {
                let den = k[i + d + 1] - k[i + 1];
                if den != 0.0 {
                    v += (k[i + d + 1] - t) / den * row[r];
                }
            }
            *slot = v;
        }
        row = next;
    }
    for (r, v) in row.into_iter().enumerate() {
        if let Some(i) = (j + r).checked_sub(p) {
            if i < count {
                out[i] = v;
            }
        }
    }
    Ok(out)
}

/// One B-spline `N_{i,p}(t)` by the recursive definition of the lecture (document 002, B-splines,
/// Cox–de Boor):
/// `N_{i,0}(t) = 1` on `[t_i, t_{i+1})`,
/// `N_{i,p}(t) = (t − t_i)/(t_{i+p} − t_i) · N_{i,p−1}(t) + (t_{i+p+1} − t)/(t_{i+p+1} − t_{i+1}) · N_{i+1,p−1}(t)`,
/// terms with a zero denominator taken as 0. At the last knot the last non-empty interval counts
/// as closed. Exponential in `p`; meant as a transparent oracle and for teaching, defined on the
/// whole range `[t_0, t_m]` (not only the spline's domain).
///
/// ```
/// use lekalo::{basis::basis_function_recursive, KnotVector};
/// // the lecture's example: knots [0,0,1,2,3,3], N_{0,2}(t) = 2t − 3t²/2 on [0,1)
/// let kv = KnotVector::new(vec![0.0, 0.0, 1.0, 2.0, 3.0, 3.0]).unwrap();
/// let v = basis_function_recursive(&kv, 0, 2, 0.5).unwrap();
/// assert!((v - 0.625).abs() < 1e-15);
/// ```
///
/// # Errors
/// [`Error::InvalidArgument`] if `i + p + 1` exceeds the last knot index;
/// [`Error::ParameterOutOfDomain`] if `t` is outside `[t_0, t_m]` or NaN.
pub fn basis_function_recursive(knots: &KnotVector, i: usize, p: usize, t: f64) -> Result<f64> {
    let k = knots.as_slice();
    let last_needed = i.checked_add(p).and_then(|v| v.checked_add(1));
    if last_needed.is_none_or(|end| end >= k.len()) {
        return Err(Error::InvalidArgument {
            what: "basis function index".into(),
            reason: format!(
                "N_{{{i},{p}}} needs knots up to index {}, but the last knot index is {}",
                i.saturating_add(p).saturating_add(1),
                k.len() - 1
            ),
        });
    }
    let (min, max) = (k[0], k[k.len() - 1]);
    if !(t >= min && t <= max) {
        return Err(Error::ParameterOutOfDomain { t, min, max });
    }
    Ok(cox_de_boor(k, i, p, t))
}

fn cox_de_boor(k: &[f64], i: usize, p: usize, t: f64) -> f64 {
    if p == 0 {
        let last = k[k.len() - 1];
        if k[i] <= t && t < k[i + 1] {
            return 1.0;
        }
        // closed last non-empty interval at t = t_max
        if t == last && k[i] < k[i + 1] && k[i + 1] == last {
            return 1.0;
        }
        return 0.0;
    }
    let mut v = 0.0;
    let d1 = k[i + p] - k[i];
    if d1 != 0.0 {
        v += (t - k[i]) / d1 * cox_de_boor(k, i, p - 1, t);
    }
    let d2 = k[i + p + 1] - k[i + 1];
    if d2 != 0.0 {
        v += (k[i + p + 1] - t) / d2 * cox_de_boor(k, i + 1, p - 1, t);
    }
    v
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        #[test]
        fn the_full_range_table_is_the_recursion(
            gaps in prop::collection::vec(prop_oneof![Just(0.0), 0.1..2.0_f64], 3..12),
            p in 0usize..5,
            s in 0.0..=1.0_f64,
        ) {
            let mut knots = vec![0.0];
            for g in &gaps {
                knots.push(knots[knots.len() - 1] + g);
            }
            prop_assume!(knots.len() > p + 1 && knots[knots.len() - 1] > knots[0]);
            let kv = KnotVector::new(knots.clone()).unwrap();
            let t = knots[0] + s * (knots[knots.len() - 1] - knots[0]);
            let all = basis_functions_full_range(&kv, p, t).unwrap();
            prop_assert_eq!(all.len(), knots.len() - p - 1);
            for (i, v) in all.iter().enumerate() {
                let r = basis_function_recursive(&kv, i, p, t).unwrap();
                prop_assert!((v - r).abs() <= 1e-14, "N_{{{},{}}}({}) = {} against {}", i, p, t, v, r);
            }
        }
    }

    proptest! {
        /// Inside the domain the rows are `basis_functions_many`'s, bit for bit; beyond it the end
        /// span's polynomials keep the partition of unity and reproduce `x` from the Greville
        /// abscissae (Marsden's identity holds for the polynomial pieces, continued or not).
        #[test]
        fn design_rows_are_the_basis_and_continue_the_end_polynomials(
            gaps in prop::collection::vec(0.1..2.0_f64, 2..9),
            p in 1usize..5,
            s in prop::collection::vec(-0.5..=1.5_f64, 1..20),
        ) {
            let mut inner = vec![0.0];
            for g in &gaps {
                inner.push(inner[inner.len() - 1] + g);
            }
            let (a, b) = (inner[0], inner[inner.len() - 1]);
            let knots: Vec<f64> = std::iter::repeat_n(a, p)
                .chain(inner.iter().copied())
                .chain(std::iter::repeat_n(b, p))
                .collect();
            let kv = KnotVector::new(knots.clone()).unwrap();
            let x: Vec<f64> = s.iter().map(|s| a + s * (b - a)).collect();
            let w = p + 1;
            let mut values = vec![0.0; x.len() * w];
            let mut first = vec![usize::MAX; x.len()];
            design_matrix_into(&kv, p, &x, true, &mut values, |j, c| first[j] = c).unwrap();
            let greville = |i: usize| knots[i + 1..=i + p].iter().sum::<f64>() / p as f64;
            for (j, &xj) in x.iter().enumerate() {
                let row = &values[j * w..(j + 1) * w];
                if (a..=b).contains(&xj) {
                    let (spans, inside) = basis_functions_many(&kv, p, &[xj]).unwrap();
                    prop_assert_eq!(first[j], spans[0] - p);
                    prop_assert_eq!(row, &inside[..]);
                }
                // rounding relative to the terms summed (beyond the domain they grow like
                // (distance / knot gap)^p and cancel)
                let size: f64 = row.iter().map(|v| v.abs()).sum();
                prop_assert!((row.iter().sum::<f64>() - 1.0).abs() <= 1e-13 * size);
                let terms = row.iter().enumerate().map(|(i, v)| v * greville(first[j] + i));
                let linear: f64 = terms.clone().sum();
                let linear_size: f64 = terms.map(f64::abs).sum::<f64>() + xj.abs();
                prop_assert!((linear - xj).abs() <= 1e-13 * linear_size, "{} against {}", linear, xj);
            }
        }
    }

    /// Many unsorted parameters (the bucket table's spans, orders 2–6; order 7 by the span
    /// cursor) give the rows of `basis_functions_many` bit for bit, on knots with a double
    /// interior knot, at every knot and at both ends; beyond the domain, the end span's.
    #[test]
    fn design_rows_of_many_unsorted_parameters_are_the_basis_bit_for_bit() {
        for p in 1..=6 {
            let mut knots = vec![0.0; p + 1];
            knots.extend([0.3, 0.7, 0.7, 1.1, 2.0, 2.05, 3.5]);
            knots.extend(vec![4.0; p + 1]);
            let kv = KnotVector::new(knots.clone()).unwrap();
            // a fixed scramble of the domain, every knot, and the ends
            let mut x: Vec<f64> = (0..500)
                .map(|i| ((i * 7919) % 500) as f64 * 0.008)
                .collect();
            x.extend_from_slice(&knots);
            let w = p + 1;
            let mut values = vec![0.0; x.len() * w];
            let mut first = vec![usize::MAX; x.len()];
            design_matrix_into(&kv, p, &x, false, &mut values, |j, c| first[j] = c).unwrap();
            let (spans, want) = basis_functions_many(&kv, p, &x).unwrap();
            assert_eq!(
                values, want,
                "degree {p}: the values of basis_functions_many"
            );
            let firsts: Vec<usize> = spans.iter().map(|s| s - p).collect();
            assert_eq!(first, firsts, "degree {p}: the first columns");
            // beyond the ends: the end spans' polynomials, as the cursor's path gives them
            let beyond = [-0.5, 4.5, -1e-9, 4.0 + 1e-9];
            let mut many = x.clone();
            many.extend_from_slice(&beyond);
            let mut values = vec![0.0; many.len() * w];
            let mut first = vec![usize::MAX; many.len()];
            design_matrix_into(&kv, p, &many, true, &mut values, |j, c| first[j] = c).unwrap();
            let mut few = [0.0; 4 * 7];
            let mut few_first = [usize::MAX; 4];
            // four parameters, fewer than the pieces: the span cursor's path
            design_matrix_into(&kv, p, &beyond, true, &mut few[..4 * w], |j, c| {
                few_first[j] = c;
            })
            .unwrap();
            assert_eq!(&values[x.len() * w..], &few[..4 * w], "degree {p} beyond");
            assert_eq!(&first[x.len()..], &few_first, "degree {p} beyond");
            // refused: the first NaN and the first parameter outside, by index
            let mut bad = x.clone();
            bad[300] = f64::NAN;
            let e = design_matrix_into(
                &kv,
                p,
                &bad,
                false,
                &mut vec![0.0; bad.len() * w],
                |_, _| {},
            );
            assert!(
                matches!(e, Err(Error::NonFinite { index: 300, .. })),
                "{e:?}"
            );
            bad[300] = 4.5;
            let e = design_matrix_into(
                &kv,
                p,
                &bad,
                false,
                &mut vec![0.0; bad.len() * w],
                |_, _| {},
            );
            assert!(
                matches!(e, Err(Error::ParameterOutOfDomain { t, .. }) if t == 4.5),
                "{e:?}"
            );
        }
    }

    #[test]
    fn design_rows_refuse_what_they_cannot_write() {
        let kv = KnotVector::new(vec![0.0, 0.0, 1.0, 2.0, 2.0]).unwrap();
        let mut values = [0.0; 4];
        let e = design_matrix_into(&kv, 1, &[0.5], false, &mut values, |_, _| {});
        assert!(
            matches!(
                e,
                Err(Error::LengthMismatch {
                    expected: 2,
                    got: 4,
                    ..
                })
            ),
            "{e:?}"
        );
        let e = design_matrix_into(&kv, 1, &[0.5, f64::NAN], true, &mut values, |_, _| {});
        assert!(matches!(e, Err(Error::NonFinite { index: 1, .. })), "{e:?}");
        let e = design_matrix_into(&kv, 1, &[0.5, 2.5], false, &mut values, |_, _| {});
        assert!(
            matches!(e, Err(Error::ParameterOutOfDomain { .. })),
            "{e:?}"
        );
        let e = design_matrix_into(&kv, 2, &[0.5], false, &mut [0.0; 3], |_, _| {});
        assert!(matches!(e, Err(Error::Degree { .. })), "{e:?}");
    }

    fn binom(n: usize, k: usize) -> f64 {
        (0..k).fold(1.0, |acc, j| acc * (n - j) as f64 / (j + 1) as f64)
    }

    #[test]
    fn bernstein_closed_form() {
        for n in 0..8 {
            let mut all = vec![0.0; n + 1];
            for &t in &[0.0, 0.2, 0.5, 0.9, 1.0] {
                bernstein_all(n, t, &mut all).unwrap();
                for i in 0..=n {
                    let exact = binom(n, i) * t.powf(i as f64) * (1.0 - t).powf((n - i) as f64);
                    assert!((bernstein(n, i, t) - exact).abs() < 1e-14, "n={n} i={i}");
                    assert!((all[i] - exact).abs() < 1e-14, "n={n} i={i}");
                }
            }
        }
        assert_eq!(bernstein(3, 4, 0.5), 0.0);
        assert!(matches!(
            bernstein_all(3, 0.5, &mut [0.0; 3]),
            Err(Error::LengthMismatch { .. })
        ));
    }

    #[test]
    fn bernstein_derivatives_match_finite_differences() {
        let (n, t, h) = (6, 0.37, 1e-5);
        let d = bernstein_derivatives(n, t, 3).unwrap();
        let w = n + 1;
        for i in 0..=n {
            let fd1 = (bernstein(n, i, t + h) - bernstein(n, i, t - h)) / (2.0 * h);
            assert!((d[w + i] - fd1).abs() < 1e-8, "first derivative i={i}");
            let fd2 = (bernstein(n, i, t + h) - 2.0 * bernstein(n, i, t) + bernstein(n, i, t - h))
                / (h * h);
            assert!((d[2 * w + i] - fd2).abs() < 1e-4, "second derivative i={i}");
        }
        // orders above n vanish
        let d = bernstein_derivatives(2, 0.3, 4).unwrap();
        assert!(matches!(
            bernstein_derivatives(2, 0.3, usize::MAX),
            Err(Error::TooLarge { .. })
        ));
        assert!(matches!(
            basis_derivatives(
                &KnotVector::clamped_uniform(2, 4).unwrap(),
                2,
                0.5,
                usize::MAX
            ),
            Err(Error::TooLarge { .. })
        ));
        assert!(d[9..].iter().all(|&v| v == 0.0), "orders above n must be 0");
    }

    /// The lecture's worked example (docs/theory/foundations.md#the-lectures-worked-example),
    /// completed: piecewise formulas of N_{i,1} and N_{i,2} on knots [0,0,1,2,3,3].
    #[test]
    fn lecture_example_piecewise_formulas() {
        let kv = KnotVector::new(vec![0.0, 0.0, 1.0, 2.0, 3.0, 3.0]).unwrap();
        type F = fn(f64) -> f64;
        // (i, p, formula on [0,1), [1,2), [2,3))
        let table: [(usize, usize, [F; 3]); 7] = [
            (0, 1, [|t| 1.0 - t, |_| 0.0, |_| 0.0]),
            (1, 1, [|t| t, |t| 2.0 - t, |_| 0.0]),
            (2, 1, [|_| 0.0, |t| t - 1.0, |t| 3.0 - t]),
            (3, 1, [|_| 0.0, |_| 0.0, |t| t - 2.0]),
            (
                0,
                2,
                [
                    |t| 2.0 * t - 1.5 * t * t,
                    |t| 0.5 * (2.0 - t) * (2.0 - t),
                    |_| 0.0,
                ],
            ),
            (
                1,
                2,
                [
                    |t| 0.5 * t * t,
                    |t| -t * t + 3.0 * t - 1.5,
                    |t| 0.5 * (3.0 - t) * (3.0 - t),
                ],
            ),
            (
                2,
                2,
                [
                    |_| 0.0,
                    |t| 0.5 * (t - 1.0) * (t - 1.0),
                    |t| -1.5 * t * t + 7.0 * t - 7.5,
                ],
            ),
        ];
        for (i, p, pieces) in table {
            for step in 0..300 {
                let t = step as f64 / 100.0;
                let piece = pieces[(step / 100).min(2)];
                let got = basis_function_recursive(&kv, i, p, t).unwrap();
                assert!((got - piece(t)).abs() < 1e-14, "N_{i},{p}({t}) = {got}");
            }
        }
        // sample table: t = 1.5 gives (1/8, 3/4, 1/8) and the curve point (17/8, 11/4)
        let (span, n) = basis_functions(&kv, 2, 1.5).unwrap();
        assert_eq!(span, 2);
        let expect = [0.125, 0.75, 0.125];
        for j in 0..3 {
            assert!((n[j] - expect[j]).abs() < 1e-15, "N at 1.5");
        }
        // sum of the degree-2 functions is 2t − t² on [0,1): not a partition of unity there
        let s: f64 = (0..3)
            .map(|i| basis_function_recursive(&kv, i, 2, 0.5).unwrap())
            .sum();
        assert!((s - 0.75).abs() < 1e-15, "sum at 0.5 is {s}");
        // the fast kernel refuses t outside the domain [1, 2]
        assert!(matches!(
            basis_functions(&kv, 2, 0.5),
            Err(Error::ParameterOutOfDomain { .. })
        ));
        assert!(basis_function_recursive(&kv, 3, 2, 0.5).is_err());
        assert!(basis_function_recursive(&kv, 0, 2, 3.5).is_err());
    }

    #[test]
    fn many_parameters_refuse_what_one_parameter_refuses() {
        let kv = KnotVector::new(vec![0.0, 0.0, 1.0, 2.0, 2.0]).unwrap();
        assert_eq!(basis_functions_many(&kv, 1, &[]).unwrap(), (vec![], vec![]));
        assert!(matches!(
            basis_functions_many(&kv, 1, &[0.5, f64::NAN]),
            Err(Error::ParameterOutOfDomain { .. })
        ));
        assert!(matches!(
            basis_functions_many(&kv, 1, &[2.5]),
            Err(Error::ParameterOutOfDomain { .. })
        ));
        // a degree the knots cannot carry is refused before anything is sized from it
        for degree in [2, usize::MAX] {
            assert!(matches!(
                basis_functions_many(&kv, degree, &[0.5]),
                Err(Error::Degree { .. })
            ));
        }
    }

    /// A case where the two schemes differ by exactly 4ε (found by the property test below):
    /// degree 5, one interior knot, a parameter near the start.
    #[test]
    fn span_basis_agrees_within_its_rounding_bound_on_a_degree_five_case() {
        let mut knots = vec![0.0; 6];
        knots.push(0.3);
        knots.extend([1.0; 6]);
        let kv = KnotVector::new(knots).unwrap();
        let s = 0.011_519_290_513_072_35;
        let (span, n) = basis_functions(&kv, 5, s).unwrap();
        let mut sb = SpanBasis::<6>::new();
        sb.set_span(kv.as_slice(), span);
        let mut out = [0.0; 6];
        sb.eval(s, 1.0, &mut out);
        let worst = (0..6).map(|j| (out[j] - n[j]).abs()).fold(0.0, f64::max);
        assert!(worst <= 25.0 * f64::EPSILON, "{worst:e}");
        assert!((out.iter().sum::<f64>() - 1.0).abs() <= 25.0 * f64::EPSILON);
    }

    fn knot_vector_strategy() -> impl Strategy<Value = (KnotVector, usize)> {
        // degree 0..=5, interior knots on a coarse grid so multiple knots occur
        (0usize..=5, 1usize..=8).prop_flat_map(|(p, pieces)| {
            proptest::collection::vec(0u32..=10, pieces.saturating_sub(1)..=pieces + 3).prop_map(
                move |mut interior| {
                    interior.sort_unstable();
                    let mut k = vec![0.0; p + 1];
                    let mut counts = std::collections::HashMap::new();
                    for v in interior {
                        let c = counts.entry(v).or_insert(0usize);
                        if *c < p.max(1) && v > 0 && v < 10 {
                            *c += 1;
                            k.push(f64::from(v) / 10.0);
                        }
                    }
                    k.extend(std::iter::repeat_n(1.0, p + 1));
                    (KnotVector::new(k).unwrap(), p)
                },
            )
        })
    }

    proptest! {
        #[test]
        fn fast_basis_matches_recursive_oracle((kv, p) in knot_vector_strategy(), s in 0.0f64..=1.0) {
            let (span, n) = basis_functions(&kv, p, s).unwrap();
            for j in 0..=p {
                let oracle = basis_function_recursive(&kv, span - p + j, p, s).unwrap();
                prop_assert!((n[j] - oracle).abs() < 1e-12, "j={} fast={} oracle={}", j, n[j], oracle);
            }
            // partition of unity and non-negativity
            prop_assert!((n.iter().sum::<f64>() - 1.0).abs() < 1e-13);
            prop_assert!(n.iter().all(|&v| v >= -1e-15));
            // local support: every other basis function vanishes at s
            let n_ctrl = kv.len() - p - 1;
            for i in 0..n_ctrl {
                if i + p < span || i > span {
                    prop_assert_eq!(basis_function_recursive(&kv, i, p, s).unwrap(), 0.0);
                }
            }
        }

        #[test]
        fn span_basis_matches_the_division_kernel((kv, p) in knot_vector_strategy(), s in 0.0f64..=1.0) {
            let (span, n) = basis_functions(&kv, p, s).unwrap();
            let mut out = vec![0.0; p + 1];
            // a stale span first: set_span must replace it
            let other = if span > p { span - 1 } else { span };
            fn run<const W: usize>(t: &[f64], spans: [usize; 2], s: f64, out: &mut [f64]) {
                let mut sb = SpanBasis::<W>::new();
                sb.set_span(t, spans[0]);
                sb.set_span(t, spans[1]);
                sb.eval(s, 1.0, out);
            }
            let t = kv.as_slice();
            match p {
                0 => run::<1>(t, [other, span], s, &mut out),
                1 => run::<2>(t, [other, span], s, &mut out),
                2 => run::<3>(t, [other, span], s, &mut out),
                3 => run::<4>(t, [other, span], s, &mut out),
                4 => run::<5>(t, [other, span], s, &mut out),
                _ => run::<6>(t, [other, span], s, &mut out),
            }
            // Both schemes build each value through p levels of the triangle from non-negative
            // terms; a level costs each at most five roundings (a knot difference, the division
            // or the stored reciprocal and its own difference, a product, a sum), so each value
            // is within 5p·u relative of the exact one (u = ε/2) and the two within 5p·ε of each
            // other, the values being at most 1.
            let bound = (5 * p).max(1) as f64 * f64::EPSILON;
            for j in 0..=p {
                prop_assert!((out[j] - n[j]).abs() <= bound, "j={} span basis={} kernel={}", j, out[j], n[j]);
            }
        }

        #[test]
        fn many_parameters_give_the_single_kernel_bit_for_bit(
            (kv, p) in knot_vector_strategy(),
            mut ts in proptest::collection::vec(0.0f64..=1.0, 0..40),
            sorted in proptest::bool::ANY,
        ) {
            // sorted (the cursor walks) or in any order (it searches)
            if sorted {
                ts.sort_by(f64::total_cmp);
            }
            ts.push(1.0);
            let (spans, values) = basis_functions_many(&kv, p, &ts).unwrap();
            prop_assert_eq!(spans.len(), ts.len());
            prop_assert_eq!(values.len(), ts.len() * (p + 1));
            for (j, &t) in ts.iter().enumerate() {
                let (span, n) = basis_functions(&kv, p, t).unwrap();
                prop_assert_eq!(spans[j], span);
                let row: Vec<u64> = values[j * (p + 1)..][..=p].iter().map(|v| v.to_bits()).collect();
                let one: Vec<u64> = n.iter().map(|v| v.to_bits()).collect();
                prop_assert_eq!(row, one);
            }
        }

        #[test]
        fn basis_derivatives_match_finite_differences((kv, p) in knot_vector_strategy(), s in 0.05f64..0.95) {
            let (span, d) = basis_derivatives(&kv, p, s, 2).unwrap();
            let w = p + 1;
            let (_, n) = basis_functions(&kv, p, s).unwrap();
            for j in 0..w {
                prop_assert!((d[j] - n[j]).abs() < 1e-14);
            }
            // finite differences only inside the span (away from knots where derivatives jump)
            let k = kv.as_slice();
            let h = 1e-6;
            if s - h > k[span] && s + h < k[span + 1] {
                let (_, np) = basis_functions(&kv, p, s + h).unwrap();
                let (_, nm) = basis_functions(&kv, p, s - h).unwrap();
                for j in 0..w {
                    let fd = (np[j] - nm[j]) / (2.0 * h);
                    let scale = 1.0 + d[w + j].abs();
                    prop_assert!((d[w + j] - fd).abs() < 1e-5 * scale, "j={} d={} fd={}", j, d[w + j], fd);
                }
            }
            // derivatives of a partition of unity sum to zero
            prop_assert!(d[w..2 * w].iter().sum::<f64>().abs() < 1e-9 * (1.0 + d[w..2*w].iter().map(|v| v.abs()).sum::<f64>()));
        }
    }
}
