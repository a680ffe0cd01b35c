//! The curve as every query sees it: its Bezier pieces in homogeneous form, normalised to the
//! unit box, with a bounding-volume tree over them; and the scalar Bernstein polynomials whose
//! roots the queries solve for (`docs/theory/queries.md#bezier-pieces`).

use crate::error::readable;
use crate::error::{check_finite, Error, Result};
use crate::{Arg, What};
use crate::{BSplineCurve, BezierCurve, NurbsCurve};

/// Highest degree the queries accept: their polynomials have degree up to `3p`, and the
/// Bernstein product weights `C(a, i)·C(b, j)/C(a + b, i + j)` stay finite in `f64` up to
/// `a + b ≈ 1000`.
pub const MAX_QUERY_DEGREE: usize = 256;

/// A curve prepared for geometric queries: its Bezier pieces (P&T A5.6), translated and scaled
/// so that their control points fill the box `[−1, 1]^dim` (all tolerances inside are then
/// relative to the curve's size, and squares neither overflow nor underflow for curves of size
/// 1e-150 or 1e150), and a binary tree of the pieces' control-point boxes.
///
/// Build it once per curve ([`QueryCurve::from_bspline`], [`QueryCurve::from_nurbs`],
/// [`QueryCurve::from_bezier`]) and ask it many questions: arc length, closest points,
/// intersections, tessellation, curvature, bounding boxes. Parameters are those of the original
/// curve; points and lengths are in its coordinates.
///
/// ```
/// use lekalo::{BSplineCurve, Points, QueryCurve};
/// let c = BSplineCurve::new(1, vec![0.0, 0.0, 1.0, 2.0, 2.0],
///                           Points::from_2d(&[[0.0, 0.0], [3.0, 4.0], [3.0, 0.0]])?)?;
/// let q = QueryCurve::from_bspline(&c)?;
/// assert_eq!(q.piece_count(), 2);
/// assert!((q.length()? - 9.0).abs() < 1e-14);
/// # Ok::<(), lekalo::Error>(())
/// ```
#[derive(Debug, Clone)]
pub struct QueryCurve {
    pub(crate) dim: usize,
    pub(crate) degree: usize,
    pub(crate) rational: bool,
    /// Scalars per homogeneous control point: `dim + rational`.
    pub(crate) hd: usize,
    /// Parameter interval of each piece.
    pub(crate) spans: Vec<(f64, f64)>,
    /// Normalised homogeneous control points, `(degree + 1)·hd` per piece.
    pub(crate) ctrl: Vec<f64>,
    /// Box of each piece's normalised (Cartesian) control points: `dim` minima then `dim` maxima.
    pub(crate) boxes: Vec<f64>,
    /// Tree nodes over consecutive pieces.
    pub(crate) nodes: Vec<Node>,
    /// `x_original = centre + scale · x_normalised`.
    pub(crate) centre: Vec<f64>,
    pub(crate) scale: f64,
}

/// One node of the piece tree: its first piece (the only one for a leaf), its box, its
/// children (leaves have none).
#[derive(Debug, Clone)]
pub(crate) struct Node {
    pub(crate) lo: usize,
    pub(crate) bbox: Vec<f64>,
    pub(crate) children: Option<(usize, usize)>,
}

impl QueryCurve {
    /// Prepares a B-spline curve (decomposed into Bezier pieces on its domain).
    ///
    /// # Errors
    /// [`Error::Degree`] above [`MAX_QUERY_DEGREE`].
    pub fn from_bspline(curve: &BSplineCurve) -> Result<Self> {
        let segs = curve.to_bezier_segments();
        let dim = curve.dim();
        let mut spans = Vec::with_capacity(segs.len());
        let mut ctrl = Vec::new();
        for s in &segs {
            spans.push((s.start, s.end));
            ctrl.extend_from_slice(s.curve.control_points().as_slice());
        }
        Self::build(dim, curve.degree(), false, spans, ctrl)
    }

    /// Prepares a NURBS curve (rational Bezier pieces of its homogeneous form).
    ///
    /// # Errors
    /// [`Error::Degree`] above [`MAX_QUERY_DEGREE`].
    pub fn from_nurbs(curve: &NurbsCurve) -> Result<Self> {
        let h = curve.homogeneous();
        let segs = h.to_bezier_segments();
        let mut spans = Vec::with_capacity(segs.len());
        let mut ctrl = Vec::new();
        for s in &segs {
            spans.push((s.start, s.end));
            ctrl.extend_from_slice(s.curve.control_points().as_slice());
        }
        Self::build(curve.dim(), curve.degree(), true, spans, ctrl)
    }

    /// Prepares a Bezier curve on `[0, 1]`.
    ///
    /// # Errors
    /// [`Error::Degree`] above [`MAX_QUERY_DEGREE`].
    pub fn from_bezier(curve: &BezierCurve) -> Result<Self> {
        Self::build(
            curve.dim(),
            curve.degree(),
            false,
            vec![(0.0, 1.0)],
            curve.control_points().as_slice().to_vec(),
        )
    }

    fn build(
        dim: usize,
        degree: usize,
        rational: bool,
        spans: Vec<(f64, f64)>,
        mut ctrl: Vec<f64>,
    ) -> Result<Self> {
        if degree > MAX_QUERY_DEGREE {
            return Err(Error::Degree {
                degree,
                reason: format!(
                    "geometric queries accept degree at most {MAX_QUERY_DEGREE} \
                     (lekalo::MAX_QUERY_DEGREE); reduce the degree first"
                ),
            });
        }
        check_finite(Arg::ControlPoints, &ctrl)?;
        let hd = dim + usize::from(rational);
        let (centre, scale) = normalise(&mut ctrl, dim, rational);
        let stride = (degree + 1) * hd;
        let mut boxes = Vec::with_capacity(spans.len() * 2 * dim);
        for piece in ctrl.chunks_exact(stride) {
            let mut b = vec![f64::INFINITY; dim];
            b.extend(std::iter::repeat_n(f64::NEG_INFINITY, dim));
            for p in piece.chunks_exact(hd) {
                let w = if rational { p[dim] } else { 1.0 };
                for d in 0..dim {
                    let x = p[d] / w;
                    b[d] = b[d].min(x);
                    b[dim + d] = b[dim + d].max(x);
                }
            }
            boxes.extend_from_slice(&b);
        }
        let mut q = QueryCurve {
            dim,
            degree,
            rational,
            hd,
            spans,
            ctrl,
            boxes,
            nodes: Vec::new(),
            centre,
            scale,
        };
        q.build_tree();
        Ok(q)
    }

    fn build_tree(&mut self) {
        let n = self.spans.len();
        let mut nodes = Vec::with_capacity(2 * n);
        self.tree_node(0, n, &mut nodes);
        self.nodes = nodes;
    }

    fn tree_node(&self, lo: usize, hi: usize, nodes: &mut Vec<Node>) -> usize {
        let dim = self.dim;
        let mut bbox = vec![f64::INFINITY; dim];
        bbox.extend(std::iter::repeat_n(f64::NEG_INFINITY, dim));
        for k in lo..hi {
            let b = &self.boxes[k * 2 * dim..(k + 1) * 2 * dim];
            for d in 0..dim {
                bbox[d] = bbox[d].min(b[d]);
                bbox[dim + d] = bbox[dim + d].max(b[dim + d]);
            }
        }
        let id = nodes.len();
        nodes.push(Node {
            lo,
            bbox,
            children: None,
        });
        if hi - lo > 1 {
            let mid = lo + (hi - lo) / 2;
            let a = self.tree_node(lo, mid, nodes);
            let b = self.tree_node(mid, hi, nodes);
            nodes[id].children = Some((a, b));
        }
        id
    }

    /// Number of Bezier pieces.
    #[must_use]
    pub fn piece_count(&self) -> usize {
        self.spans.len()
    }

    /// Dimension of the curve's points.
    #[must_use]
    pub fn dim(&self) -> usize {
        self.dim
    }

    /// Degree of the pieces.
    #[must_use]
    pub fn degree(&self) -> usize {
        self.degree
    }

    /// Parameter domain `[first piece's start, last piece's end]`.
    #[must_use]
    pub fn domain(&self) -> (f64, f64) {
        (self.spans[0].0, self.spans[self.spans.len() - 1].1)
    }

    /// The size the internal tolerances are relative to: half the largest extent of the control
    /// points (1 for a curve that is a single point).
    #[must_use]
    pub fn scale(&self) -> f64 {
        self.scale
    }

    /// Normalised homogeneous control points of piece `k`.
    pub(crate) fn piece(&self, k: usize) -> &[f64] {
        let stride = (self.degree + 1) * self.hd;
        &self.ctrl[k * stride..(k + 1) * stride]
    }

    /// Box of piece `k` (normalised): minima then maxima.
    pub(crate) fn piece_box(&self, k: usize) -> &[f64] {
        &self.boxes[k * 2 * self.dim..(k + 1) * 2 * self.dim]
    }

    /// The piece containing `t` (the last one at the right end; the nearest one outside).
    pub(crate) fn piece_of(&self, t: f64) -> usize {
        let k = self.spans.partition_point(|&(_, end)| end < t);
        k.min(self.spans.len() - 1)
    }

    /// Local parameter of `t` in piece `k`, clamped to `[0, 1]`.
    pub(crate) fn local(&self, k: usize, t: f64) -> f64 {
        let (a, b) = self.spans[k];
        ((t - a) / (b - a)).clamp(0.0, 1.0)
    }

    /// Global parameter of local `s` in piece `k`.
    pub(crate) fn global(&self, k: usize, s: f64) -> f64 {
        let (a, b) = self.spans[k];
        if s >= 1.0 {
            b
        } else {
            a + s * (b - a)
        }
    }

    /// Normalised point of the original coordinates `x`.
    pub(crate) fn normalise(&self, x: &[f64], out: &mut [f64]) {
        for d in 0..self.dim {
            out[d] = (x[d] - self.centre[d]) / self.scale;
        }
    }

    /// Original coordinates of the normalised point `x`.
    pub(crate) fn denormalise(&self, x: &[f64], out: &mut [f64]) {
        for d in 0..self.dim {
            out[d] = self.centre[d] + self.scale * x[d];
        }
    }

    /// Normalised point and derivatives (with respect to the local parameter `s ∈ [0, 1]`) of
    /// piece `k`: `out[0..dim]` = C, then C' and C'' when `order ≥ 1, 2`. Homogeneous de
    /// Casteljau down to three points, whose second differences give the derivatives
    /// (P&T eq. 1.9 and §4.4 for the rational quotient rule). `scratch` is resized as needed.
    pub(crate) fn eval_local(
        &self,
        k: usize,
        s: f64,
        order: usize,
        scratch: &mut Vec<f64>,
        out: &mut [f64],
    ) {
        let (dim, hd, n) = (self.dim, self.hd, self.degree);
        let piece = self.piece(k);
        scratch.clear();
        scratch.extend_from_slice(piece);
        let keep = n.min(2);
        for level in 0..n - keep {
            let m = n - level;
            for i in 0..m {
                for d in 0..hd {
                    scratch[i * hd + d] =
                        (1.0 - s) * scratch[i * hd + d] + s * scratch[(i + 1) * hd + d];
                }
            }
        }
        // homogeneous A, A', A'' (at most 4 + 4 + 4 scalars beyond dim 3 handled generically)
        let mut h = [[0.0_f64; 3]; 8];
        let nf = n as f64;
        let mut hv = vec![[0.0_f64; 3]; if hd > 8 { hd } else { 0 }];
        for d in 0..hd {
            let b0 = scratch[d];
            let (a, a1, a2) = match keep {
                0 => (b0, 0.0, 0.0),
                1 => {
                    let b1 = scratch[hd + d];
                    ((1.0 - s) * b0 + s * b1, b1 - b0, 0.0)
                }
                _ => {
                    let (b1, b2) = (scratch[hd + d], scratch[2 * hd + d]);
                    let l0 = (1.0 - s) * b0 + s * b1;
                    let l1 = (1.0 - s) * b1 + s * b2;
                    (
                        (1.0 - s) * l0 + s * l1,
                        nf * (l1 - l0),
                        nf * (nf - 1.0) * (b2 - 2.0 * b1 + b0),
                    )
                }
            };
            if hd > 8 {
                hv[d] = [a, a1, a2];
            } else {
                h[d] = [a, a1, a2];
            }
        }
        let get = |d: usize| if hd > 8 { hv[d] } else { h[d] };
        if !self.rational {
            for d in 0..dim {
                let v = get(d);
                for o in 0..=order.min(2) {
                    out[o * dim + d] = v[o];
                }
            }
            return;
        }
        let w = get(dim);
        for d in 0..dim {
            let a = get(d);
            let c = a[0] / w[0];
            out[d] = c;
            if order >= 1 {
                let c1 = (a[1] - w[1] * c) / w[0];
                out[dim + d] = c1;
                if order >= 2 {
                    out[2 * dim + d] = (a[2] - 2.0 * w[1] * c1 - w[2] * c) / w[0];
                }
            }
        }
    }

    /// Point (original coordinates) and derivatives with respect to the curve's parameter at
    /// global `t` (clamped to the domain): `order + 1` rows of `dim`, `order ≤ 2`.
    pub(crate) fn eval_global(&self, t: f64, order: usize, scratch: &mut Vec<f64>) -> Vec<f64> {
        let mut res = vec![0.0; (order + 1) * self.dim];
        self.eval_global_into(t, order, scratch, &mut res);
        res
    }

    /// [`QueryCurve::eval_global`] into `out` (at least `(order + 1)·dim` long), without
    /// allocating: the same values to the last bit.
    pub(crate) fn eval_global_into(
        &self,
        t: f64,
        order: usize,
        scratch: &mut Vec<f64>,
        out: &mut [f64],
    ) {
        let k = self.piece_of(t);
        let s = self.local(k, t);
        self.eval_local(k, s, order, scratch, out);
        let (a, b) = self.spans[k];
        let h = b - a;
        for d in 0..self.dim {
            out[d] = self.centre[d] + self.scale * out[d];
            if order >= 1 {
                out[self.dim + d] = self.scale * out[self.dim + d] / h;
            }
            if order >= 2 {
                out[2 * self.dim + d] = self.scale * out[2 * self.dim + d] / (h * h);
            }
        }
    }

    /// Point at the parameter `t` (original coordinates).
    ///
    /// # Errors
    /// [`Error::ParameterOutOfDomain`] outside the domain or for NaN.
    pub fn point(&self, t: f64) -> Result<Vec<f64>> {
        self.check_t(t)?;
        Ok(self.eval_global(t, 0, &mut Vec::new()))
    }

    pub(crate) fn check_t(&self, t: f64) -> Result<()> {
        let (min, max) = self.domain();
        if !(t >= min && t <= max) {
            return Err(Error::ParameterOutOfDomain { t, min, max });
        }
        Ok(())
    }
}

/// Binomial coefficient in `f64` (exact below 2^53, finite up to `n ≈ 1020`).
pub(crate) fn binom(n: usize, k: usize) -> f64 {
    let k = k.min(n - k);
    let mut r = 1.0_f64;
    for i in 0..k {
        r = r * (n - i) as f64 / (i + 1) as f64;
    }
    r.round()
}

/// A scalar polynomial in Bernstein form on `[0, 1]` (degree = `len − 1`).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Bern(pub(crate) Vec<f64>);

impl Bern {
    pub(crate) fn degree(&self) -> usize {
        self.0.len() - 1
    }

    /// Value at `s` by de Casteljau.
    pub(crate) fn eval(&self, s: f64) -> f64 {
        let mut b = self.0.clone();
        let n = b.len();
        for level in 1..n {
            for i in 0..n - level {
                b[i] = (1.0 - s) * b[i] + s * b[i + 1];
            }
        }
        b[0]
    }

    /// Derivative (degree one less; the zero polynomial of degree 0 for a constant).
    pub(crate) fn deriv(&self) -> Bern {
        let n = self.degree();
        if n == 0 {
            return Bern(vec![0.0]);
        }
        Bern(
            self.0
                .windows(2)
                .map(|w| n as f64 * (w[1] - w[0]))
                .collect(),
        )
    }

    /// Product of Bernstein polynomials (`docs/theory/queries.md#bezier-pieces`).
    pub(crate) fn mul(&self, o: &Bern) -> Bern {
        let (a, b) = (self.degree(), o.degree());
        let mut c = vec![0.0; a + b + 1];
        for i in 0..=a {
            let bi = binom(a, i);
            for j in 0..=b {
                c[i + j] += bi * binom(b, j) * self.0[i] * o.0[j];
            }
        }
        for (k, ck) in c.iter_mut().enumerate() {
            *ck /= binom(a + b, k);
        }
        Bern(c)
    }

    /// Degree elevated to `m ≥ degree` (P&T eq. 5.36, repeated).
    pub(crate) fn elevate(&self, m: usize) -> Bern {
        let mut c = self.0.clone();
        while c.len() - 1 < m {
            let n = c.len() - 1;
            let mut e = vec![0.0; n + 2];
            e[0] = c[0];
            e[n + 1] = c[n];
            for i in 1..=n {
                let a = i as f64 / (n + 1) as f64;
                e[i] = a * c[i - 1] + (1.0 - a) * c[i];
            }
            c = e;
        }
        Bern(c)
    }

    pub(crate) fn add(&self, o: &Bern) -> Bern {
        let m = self.degree().max(o.degree());
        let (a, b) = (self.elevate(m), o.elevate(m));
        Bern(a.0.iter().zip(&b.0).map(|(x, y)| x + y).collect())
    }

    pub(crate) fn sub(&self, o: &Bern) -> Bern {
        let m = self.degree().max(o.degree());
        let (a, b) = (self.elevate(m), o.elevate(m));
        Bern(a.0.iter().zip(&b.0).map(|(x, y)| x - y).collect())
    }

    pub(crate) fn scale(&self, f: f64) -> Bern {
        Bern(self.0.iter().map(|x| x * f).collect())
    }

    /// The two halves at `s` (de Casteljau), each again on `[0, 1]`.
    fn split(&self, s: f64) -> (Bern, Bern) {
        let n = self.0.len();
        let mut b = self.0.clone();
        let mut left = Vec::with_capacity(n);
        let mut right = vec![0.0; n];
        left.push(b[0]);
        right[n - 1] = b[n - 1];
        for level in 1..n {
            for i in 0..n - level {
                b[i] = (1.0 - s) * b[i] + s * b[i + 1];
            }
            left.push(b[0]);
            right[n - 1 - level] = b[n - 1 - level];
        }
        (Bern(left), Bern(right))
    }
}

/// Largest number of subdivision nodes [`bern_roots`] visits (a bound on its work).
const MAX_ROOT_NODES: usize = 1 << 14;

/// The roots of `p` in `[0, 1]`, sorted, within about `1e-15`: subdivision with the Bernstein
/// sign-variation count (the number of roots in an interval is at most the number of sign
/// changes of the coefficients, and of the same parity: Lane–Riesenfeld 1981, `docs/theory/queries.md#bezier-pieces`), so an
/// interval without a change holds no root and one with exactly one change holds exactly one,
/// found by a bracketed Newton–bisection. Coefficients within `zero` of 0 count as zero; a
/// polynomial that is zero throughout returns no roots (callers check [`Bern::is_zero`]). Bounded:
/// at most [`MAX_ROOT_NODES`] intervals and depth 52, where a cluster is reported by its middle.
pub(crate) fn bern_roots(p: &Bern, zero: f64) -> Vec<f64> {
    let mut roots = Vec::new();
    let mut clusters: Vec<(f64, f64)> = Vec::new();
    let mut stack = vec![(p.clone(), 0.0_f64, 1.0_f64, 0_u32)];
    let mut visited = 0;
    let sign = |c: f64| -> i8 {
        if c > zero {
            1
        } else if c < -zero {
            -1
        } else {
            0
        }
    };
    while let Some((q, a, b, depth)) = stack.pop() {
        visited += 1;
        // the signs of the coefficients, counted as they come (no allocation per interval):
        // how many are not zero, and the changes between consecutive non-zero ones
        let (first, last) = (sign(q.0[0]), sign(q.0[q.0.len() - 1]));
        let (mut nonzero, mut changes, mut prev) = (0_usize, 0_usize, 0_i8);
        for &c in &q.0 {
            let s = sign(c);
            if s != 0 {
                if prev != 0 && s != prev {
                    changes += 1;
                }
                prev = s;
                nonzero += 1;
            }
        }
        if nonzero == 0 {
            // zero within the threshold throughout: a cluster (merged with its neighbours below)
            clusters.push((a, b));
            continue;
        }
        if changes == 1 && first != 0 && last != 0 {
            roots.push(bracketed(&q, a, b));
            continue;
        }
        if changes == 0 && nonzero == q.0.len() {
            continue;
        }
        if depth >= 52 || visited >= MAX_ROOT_NODES || b - a < 1e-15 {
            clusters.push((a, b));
            continue;
        }
        let (l, r) = q.split(0.5);
        let m = 0.5 * (a + b);
        stack.push((r, m, b, depth + 1));
        stack.push((l, a, m, depth + 1));
    }
    clusters.sort_by(|x, y| x.0.total_cmp(&y.0));
    let mut merged: Vec<(f64, f64)> = Vec::new();
    for c in clusters {
        match merged.last_mut() {
            Some(m) if c.0 <= m.1 => m.1 = m.1.max(c.1),
            _ => merged.push(c),
        }
    }
    roots.extend(merged.iter().map(|&(a, b)| 0.5 * (a + b)));
    roots.sort_by(f64::total_cmp);
    roots.dedup_by(|x, y| (*x - *y).abs() <= 1e-13);
    roots
}

/// The single root of `q` (on `[0, 1]`, opposite end signs) mapped to `[a, b]`: Newton steps
/// kept inside a shrinking bracket, bisection when a step leaves it; at most 100 iterations.
fn bracketed(q: &Bern, a: f64, b: f64) -> f64 {
    let d = q.deriv();
    let (mut lo, mut hi) = (0.0_f64, 1.0_f64);
    let f_lo = q.0[0];
    let mut x = {
        let (c0, c1) = (q.0[0], q.0[q.0.len() - 1]);
        (c0 / (c0 - c1)).clamp(0.0, 1.0)
    };
    for _ in 0..100 {
        let fx = q.eval(x);
        if fx == 0.0 {
            break;
        }
        if (fx < 0.0) == (f_lo < 0.0) {
            lo = x;
        } else {
            hi = x;
        }
        let dx = d.eval(x);
        let mut next = if dx != 0.0 { x - fx / dx } else { f64::NAN };
        if !(next > lo && next < hi) {
            next = 0.5 * (lo + hi);
        }
        if (next - x).abs() <= 1e-16 || hi - lo <= 1e-16 {
            x = next;
            break;
        }
        x = next;
    }
    a + x * (b - a)
}

/// Euclidean distance from `x` to the box `b` (minima then maxima).
pub(crate) fn box_distance(x: &[f64], b: &[f64]) -> f64 {
    let dim = x.len();
    let mut s = 0.0;
    for d in 0..dim {
        let e = if x[d] < b[d] {
            b[d] - x[d]
        } else if x[d] > b[dim + d] {
            x[d] - b[dim + d]
        } else {
            0.0
        };
        s += e * e;
    }
    s.sqrt()
}

pub(crate) fn dist(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y) * (x - y))
        .sum::<f64>()
        .sqrt()
}

pub(crate) fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// Checks a tolerance: finite and positive.
pub(crate) fn check_tolerance(what: impl Into<What>, tol: f64) -> Result<()> {
    let what: What = what.into();
    if !(tol > 0.0 && tol.is_finite()) {
        return Err(Error::InvalidArgument {
            what,
            reason: format!(
                "{tol} is not a positive finite tolerance",
                tol = readable(&tol)
            ),
        });
    }
    Ok(())
}

/// Centres the Cartesian control points (homogeneous when `rational`, weight last) of `ctrl` on
/// the middle of their bounding box and divides by its largest half-extent (1 when that is zero
/// or not finite), in place; returns the centre and the scale.
pub(crate) fn normalise(ctrl: &mut [f64], dim: usize, rational: bool) -> (Vec<f64>, f64) {
    let hd = dim + usize::from(rational);
    let mut lo = vec![f64::INFINITY; dim];
    let mut hi = vec![f64::NEG_INFINITY; dim];
    for p in ctrl.chunks_exact(hd) {
        let w = if rational { p[dim] } else { 1.0 };
        for d in 0..dim {
            let x = p[d] / w;
            lo[d] = lo[d].min(x);
            hi[d] = hi[d].max(x);
        }
    }
    let centre: Vec<f64> = (0..dim).map(|d| 0.5 * lo[d] + 0.5 * hi[d]).collect();
    let half = (0..dim)
        .map(|d| 0.5 * hi[d] - 0.5 * lo[d])
        .fold(0.0_f64, f64::max);
    let scale = if half > 0.0 && half.is_finite() {
        half
    } else {
        1.0
    };
    for p in ctrl.chunks_exact_mut(hd) {
        let w = if rational { p[dim] } else { 1.0 };
        for d in 0..dim {
            p[d] = (p[d] - w * centre[d]) / scale;
        }
    }
    (centre, scale)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn roots_of_products() {
        // (s − 0.25)(s − 0.5)(s − 0.8) in Bernstein form via products of linear factors
        let lin = |r: f64| Bern(vec![-r, 1.0 - r]);
        let p = lin(0.25).mul(&lin(0.5)).mul(&lin(0.8));
        let r = bern_roots(&p, 0.0);
        assert_eq!(r.len(), 3, "{r:?}");
        for (x, e) in r.iter().zip([0.25, 0.5, 0.8]) {
            assert!((x - e).abs() < 1e-14, "{x} vs {e}");
        }
        // no roots
        assert!(
            bern_roots(&Bern(vec![1.0, 0.2, 3.0]), 0.0).is_empty(),
            "none"
        );
        // double root: reported once
        let d = lin(0.3).mul(&lin(0.3));
        let r = bern_roots(&d, 1e-15);
        assert!(
            !r.is_empty() && r.iter().all(|x| (x - 0.3).abs() < 1e-6),
            "{r:?}"
        );
    }

    #[test]
    fn elevation_keeps_values() {
        let p = Bern(vec![1.0, -2.0, 0.5]);
        let e = p.elevate(5);
        for s in [0.0, 0.3, 0.77, 1.0] {
            assert!((p.eval(s) - e.eval(s)).abs() < 1e-15, "s = {s}");
        }
    }
}
