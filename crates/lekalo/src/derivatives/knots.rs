//! JVP and VJP of B-spline curve and surface batch evaluation with respect to the knots
//! (`docs/theory/derivatives.md`, "Knots").
//!
//! Moving one knot `τ_k` changes the spline `f = Σ_i c_i N_{i,p,τ}`; differentiating the
//! identity between knot insertion into the moved and into the original knots (Boehm's
//! coefficients, P&T eq. 5.10) gives
//!
//! `∂f(t)/∂τ_k = − Σ_{j=k−p}^{k} (c_j − c_{j−1}) / (τ_{j+p} − τ_j) · N_{j,p,τ*}(t)`,
//!
//! with `τ*` the knots `τ` with `τ_k` inserted once more (Lyche & Mørken, *Spline Methods*,
//! the knot derivative of a spline by knot insertion). At a parameter `t` in span `s` only the
//! knots `τ_{s−p+1} … τ_{s+p}` move `f(t)`; each needs the `p + 1` non-zero basis functions of
//! `τ*` at `t`, a Cox–de Boor triangle on a window of `2p + 3` refined knots (no allocation a
//! point). A pass costs O(m·p·(p² + p·dim)).
//!
//! Conventions (the derivation's, documented there):
//! - only the interior knots `τ_{p+1} … τ_{n−1}` are differentiated: the `p + 1` first and last
//!   knots bound the domain (and clamp the curve to its end control points); they are held
//!   fixed, their tangents are ignored and their cotangents are zero;
//! - at a knot of multiplicity `μ > 1` the derivative is one-sided: the first copy's value is
//!   the derivative of decreasing it, the last copy's of increasing it (the two moves that keep
//!   the knots sorted), and the sum over the `μ` copies is the derivative of moving them
//!   together;
//! - at a parameter on a knot, `N_{j,p,τ*}` is the right-continuous basis, as evaluation's
//!   (left-continuous at the right end of the domain); where that basis jumps (`τ_k` of
//!   multiplicity `p` in `τ`, so `p + 1` in `τ*`) the value is that of `t` moving to the right.

use super::checks::{check_input, check_len, zeroed_output};
use super::curve::{combine, PointBasis};
use super::surface::combine as combine_net;
use crate::basis::{basis_funs_into, BasisScratch};
use crate::curve::BSplineCurve;
use crate::error::{check_finite, Result};
use crate::surface::BSplineSurface;

/// The knot-derivative weights at one parameter: for each knot `τ_k` that moves `f(t)`, the
/// weights `w_{k,j} = −N_{j,p,τ*}(t) / (τ_{j+p} − τ_j)` of the differences `c_j − c_{j−1}`,
/// `∂f(t)/∂τ_k = Σ_j w_{k,j} (c_j − c_{j−1})`. Scratch sized once for a degree.
pub(super) struct KnotWeights {
    degree: usize,
    /// The refined knots `τ*` around the span (`2p + 3`).
    window: Vec<f64>,
    scratch: BasisScratch,
    /// The `p + 1` non-zero basis functions of `τ*` at `t`.
    values: Vec<f64>,
    /// `w_{k,j}` for `k = first_knot …` (`count` of them) and `j = first_diff … first_diff + p + 1`
    /// (`p + 2` a knot, zero outside `k − p ≤ j ≤ k`).
    weights: Vec<f64>,
    first_knot: usize,
    count: usize,
    first_diff: usize,
}

impl KnotWeights {
    pub(super) fn new(degree: usize) -> Self {
        let w = degree + 2;
        KnotWeights {
            degree,
            window: vec![0.0; 2 * degree + 3],
            scratch: BasisScratch::new(degree),
            values: vec![0.0; degree + 1],
            weights: vec![0.0; 2 * degree.max(1) * w],
            first_knot: 0,
            count: 0,
            first_diff: 0,
        }
    }

    /// Fills the weights at `t` in `span` (`τ_span ≤ t < τ_{span+1}`, or the last non-empty
    /// span at the right end) of `knots` (`n + p + 1` of them, `n` coefficients).
    pub(super) fn at(&mut self, knots: &[f64], n: usize, span: usize, t: f64) {
        let p = self.degree;
        let w = p + 2;
        // the interior knots whose move changes f(t): k in s−p+1 ..= s+p and p+1 ..= n−1
        let first = (p + 1).max((span + 1).saturating_sub(p));
        let last = (n - 1).min(span + p);
        let base = span - p; // window[i] is τ*_{base + i} before the inserted knot
        self.first_knot = first;
        self.first_diff = base;
        self.count = (last + 1).saturating_sub(first);
        self.weights[..self.count * w].fill(0.0);
        for (row, k) in (first..=last).enumerate() {
            // τ* = τ with τ_k inserted after τ_k: the window τ_{s−p} ..= τ_{s+p+1} with it
            let at = k - base + 1;
            let local = &knots[base..=span + p + 1];
            self.window[..at].copy_from_slice(&local[..at]);
            self.window[at] = knots[k];
            self.window[at + 1..].copy_from_slice(&local[at..]);
            // t's span in τ*: one further when the inserted knot lies at or before τ_s
            let span_star = if k <= span { span + 1 } else { span };
            basis_funs_into(
                &self.window,
                p,
                span_star - base,
                t,
                &mut self.scratch,
                &mut self.values,
            );
            let weights = &mut self.weights[row * w..(row + 1) * w];
            for (r, &b) in self.values.iter().enumerate() {
                let j = span_star - p + r;
                if j + p < k || j > k {
                    continue;
                }
                let gap = knots[j + p] - knots[j];
                // a zero gap means τ*'s function j is zero (p + 2 equal knots): no term
                if gap > 0.0 {
                    weights[j - base] = -b / gap;
                }
            }
        }
    }

    /// The knots `first_knot … first_knot + count − 1` the weights are for.
    pub(super) fn knots(&self) -> std::ops::Range<usize> {
        self.first_knot..self.first_knot + self.count
    }

    /// `∂f(t)/∂τ_k = Σ_j w_{k,j} (c_j − c_{j−1})` for `k` in [`KnotWeights::knots`], `c` the
    /// coefficients `coefficient(j)` of `dim` numbers, added times `scale` into `out`.
    pub(super) fn add_derivative<'a>(
        &self,
        k: usize,
        scale: f64,
        coefficient: impl Fn(usize) -> &'a [f64],
        out: &mut [f64],
    ) {
        let w = self.degree + 2;
        let row = &self.weights[(k - self.first_knot) * w..(k - self.first_knot + 1) * w];
        for (jj, &wk) in row.iter().enumerate() {
            if wk == 0.0 {
                continue;
            }
            let j = self.first_diff + jj; // j ≥ k − p ≥ 1
            let (a, b) = (coefficient(j), coefficient(j - 1));
            for ((o, x), y) in out.iter_mut().zip(a).zip(b) {
                *o += scale * wk * (x - y);
            }
        }
    }

    /// `ḡ · ∂f(t)/∂τ_k` for `k` in [`KnotWeights::knots`].
    pub(super) fn cotangent<'a>(
        &self,
        k: usize,
        g: &[f64],
        coefficient: impl Fn(usize) -> &'a [f64],
    ) -> f64 {
        let w = self.degree + 2;
        let row = &self.weights[(k - self.first_knot) * w..(k - self.first_knot + 1) * w];
        let mut sum = 0.0;
        for (jj, &wk) in row.iter().enumerate() {
            if wk == 0.0 {
                continue;
            }
            let j = self.first_diff + jj;
            let (a, b) = (coefficient(j), coefficient(j - 1));
            let d: f64 = g
                .iter()
                .zip(a)
                .zip(b)
                .map(|((gi, x), y)| gi * (x - y))
                .sum();
            sum += wk * d;
        }
        sum
    }
}

/// The `p + 3` coefficients `j = s − p − 1 ..= s + 1` (clipped to the net) of the curve along
/// one direction of a surface at the other parameter: `Q_j = Σ_l N_l P_{j,l}` (along `u`, the
/// rows contracted with the `v` basis) or `Σ_k N_k P_{k,j}` (along `v`), into `out`
/// (`(p + 3) × dim`, index `j − (s − p − 1)`, unset entries zero).
#[allow(clippy::too_many_arguments)] // a net and its layout, a span, the other basis and a buffer
fn columns(
    net: &[f64],
    (nu, nv, dim): (usize, usize, usize),
    along_u: bool,
    (span, p): (usize, usize),
    other_first: usize,
    other: &[f64],
    out: &mut [f64],
) {
    out.fill(0.0);
    let n = if along_u { nu } else { nv };
    let lo = span.saturating_sub(p + 1);
    let hi = (span + 1).min(n - 1);
    for j in lo..=hi {
        let slot = j + p + 1 - span; // j ≥ s − p − 1
        let q = &mut out[slot * dim..(slot + 1) * dim];
        for (l, &b) in other.iter().enumerate() {
            let (row, col) = if along_u {
                (j, other_first + l)
            } else {
                (other_first + l, j)
            };
            let c = &net[(row * nv + col) * dim..(row * nv + col + 1) * dim];
            for (x, y) in q.iter_mut().zip(c) {
                *x += b * y;
            }
        }
    }
}

impl BSplineCurve {
    /// Forward-mode derivative (JVP) of [`BSplineCurve::eval_batch`] with respect to the
    /// knots: `out` receives `C(t_i)` (bit-for-bit `eval_batch`) and `tangent_out`
    ///
    /// `Ċ_i = Σ_k τ̇_k ∂C(t_i)/∂τ_k`, `∂C(t)/∂τ_k = − Σ_{j=k−p}^{k} (P_j − P_{j−1}) / (τ_{j+p} − τ_j) · N_{j,p,τ*}(t)`
    ///
    /// for a knot tangent `τ̇` (`knot_tangent`, one number a knot), `τ*` the knots with `τ_k`
    /// inserted once more: the derivative of knot insertion's identity (Boehm, P&T eq. 5.10;
    /// Lyche & Mørken, *Spline Methods*; `docs/theory/derivatives.md`, "Knots"). Only the
    /// interior knots `τ_{p+1} … τ_{n−1}` count: the tangents of the `p + 1` first and last
    /// knots, which bound the domain, are ignored (held fixed). At a knot of multiplicity
    /// `μ > 1` the derivative is one-sided (the first copy's decreasing it, the last copy's
    /// increasing it; the copies' sum moves them together). O(m·p·(p² + p·dim)).
    ///
    /// ```
    /// use lekalo::{BSplineCurve, Points};
    /// // degree 1: moving the interior knot moves the corner P_1 of the polyline sideways
    /// let ctrl = Points::from_flat(1, vec![0.0, 1.0, 0.0])?;
    /// let c = BSplineCurve::new(1, vec![0.0, 0.0, 0.5, 1.0, 1.0], ctrl)?;
    /// let (mut out, mut tan) = (vec![0.0; 1], vec![0.0; 1]);
    /// c.eval_batch_knot_jvp(&[0.25], &[0.0, 0.0, 1.0, 0.0, 0.0], &mut out, &mut tan)?;
    /// // C(0.25) = 0.25 / τ_2, so ∂C/∂τ_2 = −0.25 / τ_2² = −1
    /// assert_eq!((out[0], tan[0]), (0.5, -1.0));
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`crate::Error::LengthMismatch`] for a buffer of the wrong length (`out` and
    /// `tangent_out`: `ts.len() · dim`; `knot_tangent`: as the knots);
    /// [`crate::Error::NonFinite`] for a non-finite tangent;
    /// [`crate::Error::ParameterOutOfDomain`] at the first parameter outside the domain.
    pub fn eval_batch_knot_jvp(
        &self,
        ts: &[f64],
        knot_tangent: &[f64],
        out: &mut [f64],
        tangent_out: &mut [f64],
    ) -> Result<()> {
        let (p, dim) = (self.degree(), self.dim());
        let (knots, ctrl) = (self.knots().as_slice(), self.control_points().as_slice());
        let n = self.control_points().len();
        let m = ts.len().saturating_mul(dim);
        check_len("output buffer (parameters × dimension)", m, out.len())?;
        check_len(
            "tangent output buffer (parameters × dimension)",
            m,
            tangent_out.len(),
        )?;
        check_input("knot tangent (one a knot)", knots.len(), Some(knot_tangent))?;
        let mut cursor = self.knots().span_cursor(p);
        let mut basis = PointBasis::new(p);
        let mut weights = KnotWeights::new(p);
        let point = move |j: usize| &ctrl[j * dim..(j + 1) * dim];
        let points = out
            .chunks_exact_mut(dim)
            .zip(tangent_out.chunks_exact_mut(dim));
        for (&t, (o, d)) in ts.iter().zip(points) {
            let span = cursor.find(t)?;
            let first = basis.at(knots, p, span, t);
            combine(ctrl, dim, first, basis.values(), o);
            d.fill(0.0);
            weights.at(knots, n, span, t);
            for k in weights.knots() {
                if knot_tangent[k] != 0.0 {
                    weights.add_derivative(k, knot_tangent[k], point, d);
                }
            }
        }
        Ok(())
    }

    /// Reverse-mode derivative (VJP) of [`BSplineCurve::eval_batch`] with respect to the knots:
    /// for a cotangent `ḡ` (`ts.len() × dim`, point-major), `τ̄_k = Σ_i ḡ_i · ∂C(t_i)/∂τ_k`
    /// into `knot_cotangent` (one a knot, overwritten), with the derivative of
    /// [`BSplineCurve::eval_batch_knot_jvp`] (`docs/theory/derivatives.md`, "Knots"); its
    /// transpose: `⟨ḡ, J τ̇⟩ = ⟨Jᵀ ḡ, τ̇⟩`. The `p + 1` first and last knots get zero.
    /// O(m·p·(p² + p·dim)).
    ///
    /// ```
    /// use lekalo::{BSplineCurve, Points};
    /// let ctrl = Points::from_flat(1, vec![0.0, 1.0, 0.0])?;
    /// let c = BSplineCurve::new(1, vec![0.0, 0.0, 0.5, 1.0, 1.0], ctrl)?;
    /// let mut grad = vec![0.0; 5];
    /// c.eval_batch_knot_vjp(&[0.25, 0.75], &[1.0, 1.0], &mut grad)?;
    /// // the corner moving right raises the curve at 0.75 as much as it lowers it at 0.25
    /// assert_eq!(grad, vec![0.0, 0.0, 0.0, 0.0, 0.0]);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`crate::Error::LengthMismatch`] for a buffer of the wrong length;
    /// [`crate::Error::NonFinite`] for a non-finite cotangent;
    /// [`crate::Error::ParameterOutOfDomain`] at the first parameter outside the domain.
    pub fn eval_batch_knot_vjp(
        &self,
        ts: &[f64],
        cotangent: &[f64],
        knot_cotangent: &mut [f64],
    ) -> Result<()> {
        let (p, dim) = (self.degree(), self.dim());
        let (knots, ctrl) = (self.knots().as_slice(), self.control_points().as_slice());
        let n = self.control_points().len();
        check_len(
            "cotangent (parameters × dimension)",
            ts.len().saturating_mul(dim),
            cotangent.len(),
        )?;
        check_finite("cotangent", cotangent)?;
        check_len(
            "knot cotangent buffer (one a knot)",
            knots.len(),
            knot_cotangent.len(),
        )?;
        knot_cotangent.fill(0.0);
        let mut cursor = self.knots().span_cursor(p);
        let mut weights = KnotWeights::new(p);
        let point = move |j: usize| &ctrl[j * dim..(j + 1) * dim];
        for (&t, g) in ts.iter().zip(cotangent.chunks_exact(dim)) {
            let span = cursor.find(t)?;
            weights.at(knots, n, span, t);
            for k in weights.knots() {
                knot_cotangent[k] += weights.cotangent(k, g, point);
            }
        }
        Ok(())
    }
}

/// Per-direction scratch of a surface's knot derivatives at one pair.
struct SurfaceKnotScratch {
    u: PointBasis,
    v: PointBasis,
    wu: KnotWeights,
    wv: KnotWeights,
    /// The curve along `u` (`p + 3` coefficients) and along `v` (`q + 3`).
    cols_u: Vec<f64>,
    cols_v: Vec<f64>,
    tmp: Vec<f64>,
}

impl SurfaceKnotScratch {
    fn new(s: &BSplineSurface) -> Self {
        let ((p, q), dim) = (s.degree(), s.dim());
        SurfaceKnotScratch {
            u: PointBasis::new(p),
            v: PointBasis::new(q),
            wu: KnotWeights::new(p),
            wv: KnotWeights::new(q),
            cols_u: vec![0.0; (p + 3) * dim],
            cols_v: vec![0.0; (q + 3) * dim],
            tmp: vec![0.0; dim],
        }
    }
}

impl BSplineSurface {
    /// Spans, bases, knot weights and the two directions' curves at one pair, for the
    /// directions asked (`(u, v)`); returns the net's corner.
    fn knot_pair(
        &self,
        cursors: &mut (crate::SpanCursor<'_>, crate::SpanCursor<'_>),
        [u, v]: [f64; 2],
        (want_u, want_v): (bool, bool),
        sc: &mut SurfaceKnotScratch,
    ) -> Result<(usize, usize)> {
        let ((p, q), dim) = (self.degree(), self.dim());
        let (nu, nv) = self.net_size();
        let (ku, kv) = (self.knots_u().as_slice(), self.knots_v().as_slice());
        let net = self.control_points().as_slice();
        let (su, sv) = (cursors.0.find(u)?, cursors.1.find(v)?);
        let fu = sc.u.at(ku, p, su, u);
        let fv = sc.v.at(kv, q, sv, v);
        if want_u {
            sc.wu.at(ku, nu, su, u);
            let b = sc.v.values();
            columns(net, (nu, nv, dim), true, (su, p), fv, b, &mut sc.cols_u);
        }
        if want_v {
            sc.wv.at(kv, nv, sv, v);
            let b = sc.u.values();
            columns(net, (nu, nv, dim), false, (sv, q), fu, b, &mut sc.cols_v);
        }
        Ok((fu, fv))
    }

    /// Forward-mode derivative (JVP) of [`BSplineSurface::eval_batch`] with respect to the
    /// knots of each direction: `out` receives `S(u_i, v_i)` (bit-for-bit `eval_batch`) and
    /// `tangent_out` `Ṡ_i = Σ_k τ̇ᵘ_k ∂S/∂τᵘ_k + Σ_l τ̇ᵛ_l ∂S/∂τᵛ_l`. Along `u`, `S(·, v)` is the
    /// curve with coefficients `Q_j(v) = Σ_l N_{l,q}(v) P_{jl}`, so
    /// `∂S/∂τᵘ_k = − Σ_{j=k−p}^{k} (Q_j − Q_{j−1}) / (τᵘ_{j+p} − τᵘ_j) · N_{j,p,τᵘ*}(u)`,
    /// the curve formula of [`BSplineCurve::eval_batch_knot_jvp`]
    /// (`docs/theory/derivatives.md`, "Knots"), and along `v` likewise. `knot_tangent_u`
    /// (`knot_tangent_v`) has one number a knot of that direction (`None` is zero); the tangents
    /// of each direction's `p + 1` first and last knots are ignored.
    /// O(m·(p³ + q³ + (p + q)·(p + q)·dim)).
    ///
    /// # Errors
    /// [`crate::Error::LengthMismatch`] for a buffer of the wrong length;
    /// [`crate::Error::NonFinite`] for a non-finite tangent;
    /// [`crate::Error::ParameterOutOfDomain`] at the first pair outside the domain.
    pub fn eval_batch_knot_jvp(
        &self,
        uv: &[[f64; 2]],
        knot_tangent_u: Option<&[f64]>,
        knot_tangent_v: Option<&[f64]>,
        out: &mut [f64],
        tangent_out: &mut [f64],
    ) -> Result<()> {
        let dim = self.dim();
        let m = uv.len().saturating_mul(dim);
        check_len("output buffer (parameter pairs × dimension)", m, out.len())?;
        check_len(
            "tangent output buffer (parameter pairs × dimension)",
            m,
            tangent_out.len(),
        )?;
        let (ku, kv) = (self.knots_u().len(), self.knots_v().len());
        check_input("u knot tangent (one a u knot)", ku, knot_tangent_u)?;
        check_input("v knot tangent (one a v knot)", kv, knot_tangent_v)?;
        let ((p, q), nv) = (self.degree(), self.net_size().1);
        let net = self.control_points().as_slice();
        let mut cursors = (self.knots_u().span_cursor(p), self.knots_v().span_cursor(q));
        let mut sc = SurfaceKnotScratch::new(self);
        let want = (knot_tangent_u.is_some(), knot_tangent_v.is_some());
        let points = out
            .chunks_exact_mut(dim)
            .zip(tangent_out.chunks_exact_mut(dim));
        for (&pair, (o, d)) in uv.iter().zip(points) {
            let corner = self.knot_pair(&mut cursors, pair, want, &mut sc)?;
            let (bu, bv) = (sc.u.values(), sc.v.values());
            combine_net(net, nv, dim, corner, bu, bv, &mut sc.tmp, o);
            d.fill(0.0);
            let directions = [
                (knot_tangent_u, &sc.wu, &sc.cols_u),
                (knot_tangent_v, &sc.wv, &sc.cols_v),
            ];
            for (tangent, weights, cols) in directions {
                let Some(tangent) = tangent else { continue };
                // column j is at slot j − (s − p − 1) = j − first_diff + 1
                let base = weights.first_diff;
                let col = move |j: usize| &cols[(j + 1 - base) * dim..(j + 2 - base) * dim];
                for k in weights.knots() {
                    if tangent[k] != 0.0 {
                        weights.add_derivative(k, tangent[k], col, d);
                    }
                }
            }
        }
        Ok(())
    }

    /// Reverse-mode derivative (VJP) of [`BSplineSurface::eval_batch`] with respect to the
    /// knots: for a cotangent `ḡ` (`uv.len() × dim`), `τ̄ᵘ_k = Σ_i ḡ_i · ∂S(u_i, v_i)/∂τᵘ_k`
    /// into `knot_cotangent_u` and likewise along `v` (each when given; overwritten), with the
    /// derivatives of [`BSplineSurface::eval_batch_knot_jvp`], whose transpose this is
    /// (`docs/theory/derivatives.md`, "Knots"). Each direction's `p + 1` first and last knots
    /// get zero. O(m·(p³ + q³ + (p + q)·(p + q)·dim)).
    ///
    /// # Errors
    /// [`crate::Error::LengthMismatch`] for a buffer of the wrong length;
    /// [`crate::Error::NonFinite`] for a non-finite cotangent;
    /// [`crate::Error::ParameterOutOfDomain`] at the first pair outside the domain.
    pub fn eval_batch_knot_vjp(
        &self,
        uv: &[[f64; 2]],
        cotangent: &[f64],
        mut knot_cotangent_u: Option<&mut [f64]>,
        mut knot_cotangent_v: Option<&mut [f64]>,
    ) -> Result<()> {
        let dim = self.dim();
        check_len(
            "cotangent (parameter pairs × dimension)",
            uv.len().saturating_mul(dim),
            cotangent.len(),
        )?;
        check_finite("cotangent", cotangent)?;
        let (ku, kv) = (self.knots_u().len(), self.knots_v().len());
        zeroed_output(
            "u knot cotangent buffer (one a u knot)",
            ku,
            knot_cotangent_u.as_deref_mut(),
        )?;
        zeroed_output(
            "v knot cotangent buffer (one a v knot)",
            kv,
            knot_cotangent_v.as_deref_mut(),
        )?;
        let (p, q) = self.degree();
        let mut cursors = (self.knots_u().span_cursor(p), self.knots_v().span_cursor(q));
        let mut sc = SurfaceKnotScratch::new(self);
        let want = (knot_cotangent_u.is_some(), knot_cotangent_v.is_some());
        for (&pair, g) in uv.iter().zip(cotangent.chunks_exact(dim)) {
            self.knot_pair(&mut cursors, pair, want, &mut sc)?;
            let directions = [
                (knot_cotangent_u.as_deref_mut(), &sc.wu, &sc.cols_u),
                (knot_cotangent_v.as_deref_mut(), &sc.wv, &sc.cols_v),
            ];
            for (buf, weights, cols) in directions {
                let Some(buf) = buf else { continue };
                let base = weights.first_diff;
                let col = move |j: usize| &cols[(j + 1 - base) * dim..(j + 2 - base) * dim];
                for k in weights.knots() {
                    buf[k] += weights.cotangent(k, g, col);
                }
            }
        }
        Ok(())
    }
}
