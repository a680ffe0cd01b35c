//! JVP and VJP of batch evaluation with respect to the knots, for B-spline and NURBS curves,
//! B-spline and NURBS surfaces and `N`-variate tensor-product B-splines and NURBS
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
//! point). A pass costs O(m·p·(p² + p·dim)). [`KnotWeights`] holds these weights at one
//! parameter, and every object applies them to its own coefficients:
//!
//! - `curve.rs`: [`crate::BSplineCurve::eval_batch_knot_jvp`] and `_vjp`, the formula on the
//!   control points;
//! - `nurbs.rs`: [`crate::NurbsCurve::eval_batch_knot_jvp`] and `_vjp`, the formula on the
//!   homogeneous control points `(w_j P_j, w_j)`, then the quotient rule;
//! - `net.rs`: [`crate::BSplineSurface::eval_batch_knot_jvp`] and `_vjp`, and
//!   [`crate::TensorBSpline::eval_batch_knot_jvp`] and `_vjp`: one kernel for a net in `N`
//!   directions (a surface is the net of two), the formula along one direction on the
//!   coefficients that the other directions' basis functions contract the net to;
//! - `rational_net.rs`: [`crate::NurbsSurface::eval_batch_knot_jvp`] and `_vjp`, and
//!   [`crate::TensorNurbs::eval_batch_knot_jvp`] and `_vjp`: the net kernel on the
//!   homogeneous net, then the quotient rule, as for a NURBS curve;
//! - `tests.rs`, `nurbs_tests.rs`, `net_tests.rs`, `rational_net_tests.rs`: their tests.
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

mod curve;
mod net;
#[cfg(test)]
mod net_tests;
mod nurbs;
#[cfg(test)]
mod nurbs_tests;
mod rational_net;
#[cfg(test)]
mod rational_net_tests;
#[cfg(test)]
mod tests;

use crate::basis::{basis_funs_into, BasisScratch};

pub(super) use curve::knot_jvp_transposed;

/// The knot-derivative weights at one parameter: for each knot `τ_k` that moves `f(t)`, the
/// weights `w_{k,j} = −N_{j,p,τ*}(t) / (τ_{j+p} − τ_j)` of the differences `c_j − c_{j−1}`,
/// `∂f(t)/∂τ_k = Σ_j w_{k,j} (c_j − c_{j−1})`. Scratch sized once for a degree.
struct KnotWeights {
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
    fn new(degree: usize) -> Self {
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
    fn at(&mut self, knots: &[f64], n: usize, span: usize, t: f64) {
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
    fn knots(&self) -> std::ops::Range<usize> {
        self.first_knot..self.first_knot + self.count
    }

    /// `∂f(t)/∂τ_k = Σ_j w_{k,j} (c_j − c_{j−1})` for `k` in [`KnotWeights::knots`], `c` the
    /// coefficients `coefficient(j)` of `dim` numbers, added times `scale` into `out`.
    fn add_derivative<'a>(
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
    fn cotangent<'a>(&self, k: usize, g: &[f64], coefficient: impl Fn(usize) -> &'a [f64]) -> f64 {
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
