//! The observation matrix of a scattered fit in `N` variables reduced to a banded triangle by
//! Givens rotations (FITPACK `fpsurf`, Dierckx, *Curve and Surface Fitting with Splines*, 1993,
//! §9.1–9.2), the rows of the derivative jumps rotated into a copy of it for a smoothing weight,
//! and the solve of the triangle: back substitution, or the minimal-norm solution of a
//! numerically rank-deficient triangle (FITPACK `fprank`, Dierckx §9.2.2).
//! `docs/theory/tensor.md#smoothing-scattered-data`.

use crate::basis::{basis_funs_into, BasisScratch};
use crate::error::readable;
use crate::error::{Error, Result, MAX_SCALARS};
use crate::fit::banded::{BandedQr, RANK_RTOL};
use crate::fit::jump_rows;
use crate::knots::KnotVector;
use crate::points::PointsRef;
use crate::Arg;

/// What a scattered least-squares fit does with a control point the data do not determine (no
/// data point of positive weight under its basis function, or too few or too nearly aligned).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum RankDeficiency {
    /// Refuse the fit with [`Error::EmptySupport`] naming the control point (lekalo's default:
    /// the caller chose knots the data cannot carry).
    Refuse,
    /// FITPACK's answer (`fprank`): a diagonal element of the triangle of the observation matrix
    /// at most `√eps` times the largest counts as zero, and the coefficients are the solution
    /// of least norm of the system without those pivots (`eps` in `(0, 1)`, FITPACK's default
    /// `1e-16`). The fit reports its rank.
    MinimumNorm {
        /// The rank threshold `eps` (its square root multiplies the largest diagonal element).
        eps: f64,
    },
}

impl RankDeficiency {
    /// `eps` in `(0, 1)` for [`RankDeficiency::MinimumNorm`].
    pub(super) fn check(self) -> Result<()> {
        match self {
            RankDeficiency::MinimumNorm { eps } if !(eps > 0.0 && eps < 1.0) => {
                Err(Error::InvalidArgument {
                    what: Arg::Eps.into(),
                    reason: format!(
                        "the rank threshold eps = {eps} is outside (0, 1); FITPACK's default is \
                         1e-16",
                        eps = readable(&eps)
                    ),
                })
            }
            _ => Ok(()),
        }
    }
}

/// The order of the coefficients in the triangle: the directions in `order` (the last fastest),
/// `shape` and `stride` in that order.
#[derive(Debug, Clone)]
pub(super) struct Layout {
    pub(super) order: Vec<usize>,
    shape: Vec<usize>,
    stride: Vec<usize>,
}

impl Layout {
    /// The layout of the net `shape` (natural order) with the directions in `order`.
    pub(super) fn new(order: Vec<usize>, shape: &[usize]) -> Self {
        let s: Vec<usize> = order.iter().map(|&a| shape[a]).collect();
        let mut stride = vec![1usize; s.len()];
        for b in (0..s.len().saturating_sub(1)).rev() {
            stride[b] = stride[b + 1] * s[b + 1];
        }
        Layout {
            order,
            shape: s,
            stride,
        }
    }

    /// The half-bandwidth plus one of the data rows, `Σ_b k_b σ_b + 1`.
    fn data_band(&self, degrees: &[usize]) -> usize {
        self.order
            .iter()
            .zip(&self.stride)
            .map(|(&a, &s)| degrees[a] * s)
            .sum::<usize>()
            + 1
    }

    /// The order of least band for the net `shape` (FITPACK interchanges `x` and `y` when that
    /// narrows the band; in `N` directions the band `Σ_b k_b σ_b` is least with the directions
    /// sorted by `k_a/(n_a − 1)`, by the exchange of neighbours), keeping `current` unless
    /// another order is strictly narrower.
    pub(super) fn least_band(current: &[usize], shape: &[usize], degrees: &[usize]) -> Self {
        let now = Layout::new(current.to_vec(), shape);
        let mut sorted = current.to_vec();
        // k_a/(n_a − 1) < k_b/(n_b − 1), cross-multiplied (n ≥ k + 1 ≥ 2)
        sorted.sort_by(|&a, &b| (degrees[a] * (shape[b] - 1)).cmp(&(degrees[b] * (shape[a] - 1))));
        let best = Layout::new(sorted, shape);
        if best.data_band(degrees) < now.data_band(degrees) {
            best
        } else {
            now
        }
    }

    /// The natural (first direction slowest) flat index of the coefficient at `i` here.
    pub(super) fn natural(&self, i: usize, natural_shape: &[usize]) -> usize {
        let n = natural_shape.len();
        let mut index = vec![0usize; n];
        let mut rest = i;
        for b in (0..n).rev() {
            index[self.order[b]] = rest % self.shape[b];
            rest /= self.shape[b];
        }
        index
            .iter()
            .zip(natural_shape)
            .fold(0, |acc, (&j, &m)| acc * m + j)
    }
}

/// The triangle of the data rows of a scattered fit on given knots.
pub(super) struct Observation {
    pub(super) layout: Layout,
    pub(super) qr: BandedQr,
    /// Width of the rows of the triangle (room for the rows of the jumps).
    pub(super) bw: usize,
    /// Data points of positive weight and positive basis value under each coefficient (layout
    /// order).
    pub(super) support: Vec<usize>,
}

/// Rotates the data rows `√w_k (B(x_k), y_k)` into a banded triangle, the points taken in the
/// order of their first coefficient so that no rotation fills in beyond a row (FITPACK
/// `fporde` + `fpsurf`). With `penalty` the triangle is wide enough for the rows of the jumps.
///
/// # Errors
/// [`Error::TooLarge`] if the triangle exceeds [`MAX_SCALARS`].
pub(super) fn observe(
    x: PointsRef<'_>,
    values: PointsRef<'_>,
    weights: Option<&[f64]>,
    degrees: &[usize],
    knots: &[KnotVector],
    layout: Layout,
    penalty: bool,
) -> Result<Observation> {
    let n_vars = degrees.len();
    let n: usize = layout.shape.iter().product();
    let data_bw = layout.data_band(degrees);
    let bw = if penalty {
        layout
            .order
            .iter()
            .zip(&layout.stride)
            .map(|(&a, &s)| (degrees[a] + 1) * s + 1)
            .fold(data_bw, usize::max)
    } else {
        data_bw
    };
    let size = n.saturating_mul(bw);
    if size > MAX_SCALARS {
        return Err(Error::TooLarge {
            what: "triangle of the scattered fit (control points × band width)".into(),
            size,
            max: MAX_SCALARS,
        });
    }
    let dim = values.dim();
    // the stride of each natural direction in the layout
    let mut stride = vec![0usize; n_vars];
    for (b, &a) in layout.order.iter().enumerate() {
        stride[a] = layout.stride[b];
    }
    let window: usize = degrees.iter().map(|p| p + 1).product();
    // (first coefficient, point) and each point's window, flat
    let mut firsts = Vec::with_capacity(x.len());
    let mut offsets = Vec::with_capacity(x.len() * window);
    let mut products = Vec::with_capacity(x.len() * window);
    let mut row_products = RowProducts::new(degrees);
    let mut support = vec![0usize; n];
    for (k, row) in x.iter().enumerate() {
        let (idx, val) = row_products.fill(knots, degrees, &stride, row);
        let w = weights.map_or(1.0, |w| w[k]);
        let first = idx.iter().copied().min().unwrap_or(0);
        if w > 0.0 {
            for (&i, &v) in idx.iter().zip(val) {
                if v > 0.0 {
                    support[i] += 1;
                }
            }
        }
        firsts.push((first, k));
        offsets.extend(idx.iter().map(|&i| i - first));
        products.extend(val.iter().map(|&v| v * w.sqrt()));
    }
    firsts.sort_by_key(|&(f, _)| f);
    let mut qr = BandedQr::new(n, bw, dim);
    let mut h = vec![0.0; data_bw];
    let mut y = vec![0.0; dim];
    for &(first, k) in &firsts {
        let w = weights.map_or(1.0, |w| w[k]);
        if w == 0.0 {
            continue;
        }
        h.fill(0.0);
        let window_of = k * window..(k + 1) * window;
        for (&o, &v) in offsets[window_of.clone()].iter().zip(&products[window_of]) {
            h[o] += v;
        }
        for (o, &v) in y.iter_mut().zip(values.point(k)) {
            *o = v * w.sqrt();
        }
        qr.add_row(first, &mut h, &mut y);
    }
    Ok(Observation {
        layout,
        qr,
        bw,
        support,
    })
}

/// Rotates the row `h` (`bw` entries from column `first`) and its right-hand side `y` into the
/// triangle, with the fill-in the row takes up from the rows below (FITPACK's rotation of the
/// rows of the jumps in `fpsurf`, and of a dropped row in `fprank`). `h` and `y` are
/// overwritten.
pub(crate) fn rotate_full(
    qr: &mut BandedQr,
    bw: usize,
    first: usize,
    h: &mut [f64],
    y: &mut [f64],
) {
    let n = qr.n();
    let nc = y.len();
    for j in first..n {
        if h.iter().all(|&v| v == 0.0) {
            break;
        }
        let piv = h[0];
        if piv != 0.0 {
            let rj = &mut qr.r[j * bw..(j + 1) * bw];
            let d = (piv * piv + rj[0] * rj[0]).sqrt();
            if d > 0.0 {
                let (c, s) = (rj[0] / d, piv / d);
                rj[0] = d;
                for k in 1..bw.min(n - j) {
                    let (a, b) = (h[k], rj[k]);
                    rj[k] = c * b + s * a;
                    h[k] = c * a - s * b;
                }
                let zj = &mut qr.z[j * nc..(j + 1) * nc];
                for (a, b) in y.iter_mut().zip(zj.iter_mut()) {
                    let (ya, zb) = (*a, *b);
                    *b = c * zb + s * ya;
                    *a = c * ya - s * zb;
                }
            }
        }
        h.copy_within(1.., 0);
        h[bw - 1] = 0.0;
    }
    qr.rss += y.iter().map(|v| v * v).sum::<f64>();
}

/// A copy of the data triangle with the rows `B_a/p` of the jumps of the `k_a`-th derivative
/// across the interior knots of each direction `a` (FITPACK `fpdisc`), each row repeated for
/// every coefficient index of the other directions (Dierckx §9.2.1).
pub(super) fn with_jumps(
    obs: &Observation,
    degrees: &[usize],
    knots: &[KnotVector],
    p: f64,
) -> BandedQr {
    let mut qr = obs.qr.clone();
    let bw = obs.bw;
    let nc = qr.z.len() / qr.n().max(1);
    let lay = &obs.layout;
    let mut h = vec![0.0; bw];
    let mut y = vec![0.0; nc];
    for (b, &a) in lay.order.iter().enumerate().rev() {
        let k = degrees[a];
        let t = knots[a].as_slice();
        if t.len() <= 2 * k + 2 {
            continue;
        }
        let jumps = jump_rows(t, k).rows;
        let sigma = lay.stride[b];
        let others: usize = lay.shape.iter().product::<usize>() / lay.shape[b];
        for (j, row) in jumps.chunks_exact(k + 2).enumerate() {
            for o in 0..others {
                // o runs over the other directions: below σ_b, and the rest above
                let first = (o / sigma) * sigma * lay.shape[b] + o % sigma + j * sigma;
                h.fill(0.0);
                for (l, &v) in row.iter().enumerate() {
                    h[l * sigma] = v / p;
                }
                y.fill(0.0);
                rotate_full(&mut qr, bw, first, &mut h, &mut y);
            }
        }
    }
    qr
}

/// The coefficients (layout order, `n × dim`) of the triangle and its rank: back substitution
/// at full rank, [`RankDeficiency::Refuse`] failing with the layout index of the first pivot
/// below `RANK_RTOL` times the largest, [`RankDeficiency::MinimumNorm`] the solution of least
/// norm with the pivots at most `√eps` times the largest set to zero (FITPACK `fprank`).
pub(crate) fn solve(
    mut qr: BandedQr,
    bw: usize,
    rank: RankDeficiency,
) -> std::result::Result<(Vec<f64>, usize), usize> {
    let n = qr.n();
    let nc = qr.z.len() / n.max(1);
    let dmax = (0..n).fold(0.0_f64, |m, i| m.max(qr.r[i * bw]));
    let tol = match rank {
        RankDeficiency::Refuse => {
            if let Some(i) =
                (0..n).find(|&i| qr.r[i * bw] <= RANK_RTOL * dmax || qr.r[i * bw].is_nan())
            {
                return Err(i);
            }
            0.0
        }
        RankDeficiency::MinimumNorm { eps } => eps.sqrt() * dmax,
    };
    if (0..n).all(|i| qr.r[i * bw] > tol) {
        return Ok((back_substitute(&qr, bw, n, nc), n));
    }
    // a row with a pivot at most tol is dropped: the rest of it is rotated into the rows below
    let mut h = vec![0.0; bw];
    let mut y = vec![0.0; nc];
    for i in 0..n {
        if qr.r[i * bw] > tol {
            continue;
        }
        h[..bw - 1].copy_from_slice(&qr.r[i * bw + 1..(i + 1) * bw]);
        h[bw - 1] = 0.0;
        y.copy_from_slice(&qr.z[i * nc..(i + 1) * nc]);
        qr.r[i * bw..(i + 1) * bw].fill(0.0);
        qr.z[i * nc..(i + 1) * nc].fill(0.0);
        if i + 1 < n {
            rotate_full(&mut qr, bw, i + 1, &mut h, &mut y);
        }
    }
    // B: the kept rows (full rank, upper trapezoidal); c = Bᵀ (B Bᵀ)⁻¹ g with B Bᵀ = Tᵀ T from
    // the QR factorisation of Bᵀ, whose rows (the columns of B) arrive in band order
    let kept: Vec<usize> = (0..n).filter(|&i| qr.r[i * bw] > tol).collect();
    let r = kept.len();
    if r == 0 {
        return Ok((vec![0.0; n * nc], 0));
    }
    let mut t = BandedQr::new(r, bw, 0);
    let mut col = vec![0.0; bw];
    let mut lo = 0usize;
    for j in 0..n {
        while lo < r && kept[lo] + bw <= j {
            lo += 1;
        }
        let hi = kept.partition_point(|&i| i <= j);
        if hi <= lo {
            continue;
        }
        for (slot, &i) in col.iter_mut().zip(&kept[lo..hi]) {
            *slot = qr.r[i * bw + (j - i)];
        }
        t.add_row(lo, &mut col[..hi - lo], &mut []);
    }
    let mut c = vec![0.0; n * nc];
    let mut v = vec![0.0; r];
    for d in 0..nc {
        // Tᵀ u = g (forward), T v = u (back)
        for a in 0..r {
            let mut s = qr.z[kept[a] * nc + d];
            for l in 1..bw.min(a + 1) {
                s -= t.r[(a - l) * bw + l] * v[a - l];
            }
            v[a] = s / t.r[a * bw];
        }
        for a in (0..r).rev() {
            let mut s = v[a];
            for l in 1..bw.min(r - a) {
                s -= t.r[a * bw + l] * v[a + l];
            }
            v[a] = s / t.r[a * bw];
        }
        for (a, &i) in kept.iter().enumerate() {
            for l in 0..bw.min(n - i) {
                c[(i + l) * nc + d] += qr.r[i * bw + l] * v[a];
            }
        }
    }
    Ok((c, r))
}

/// `R c = z` by back substitution (all pivots positive).
fn back_substitute(qr: &BandedQr, bw: usize, n: usize, nc: usize) -> Vec<f64> {
    let mut x = vec![0.0; n * nc];
    for i in (0..n).rev() {
        let row = &qr.r[i * bw..(i + 1) * bw];
        for c in 0..nc {
            let mut s = qr.z[i * nc + c];
            for k in 1..bw.min(n - i) {
                s -= row[k] * x[(i + k) * nc + c];
            }
            x[i * nc + c] = s / row[0];
        }
    }
    x
}

/// The coefficients of the layout order in the natural order (first direction slowest).
pub(super) fn to_natural(c: &[f64], layout: &Layout, shape: &[usize], dim: usize) -> Vec<f64> {
    let mut out = vec![0.0; c.len()];
    for (i, row) in c.chunks_exact(dim).enumerate() {
        let j = layout.natural(i, shape);
        out[j * dim..(j + 1) * dim].copy_from_slice(row);
    }
    out
}

/// The non-zero basis products of one point of a tensor-product space: the Kronecker
/// product of the one-direction basis rows (P&T Algorithm A2.2 in each direction), the first
/// direction slowest, with their indices in a net of the given strides.
pub(super) struct RowProducts {
    scratch: Vec<BasisScratch>,
    bases: Vec<Vec<f64>>,
    idx: Vec<usize>,
    val: Vec<f64>,
    idx2: Vec<usize>,
    val2: Vec<f64>,
}

impl RowProducts {
    /// Buffers for the degrees `degrees`.
    pub(super) fn new(degrees: &[usize]) -> Self {
        let window: usize = degrees.iter().map(|p| p + 1).product();
        RowProducts {
            scratch: degrees.iter().map(|&p| BasisScratch::new(p)).collect(),
            bases: degrees.iter().map(|&p| vec![0.0; p + 1]).collect(),
            idx: Vec::with_capacity(window),
            val: Vec::with_capacity(window),
            idx2: Vec::with_capacity(window),
            val2: Vec::with_capacity(window),
        }
    }

    /// The indices and products at `row` (inside every knot vector's domain).
    pub(super) fn fill(
        &mut self,
        knots: &[KnotVector],
        degrees: &[usize],
        stride: &[usize],
        row: &[f64],
    ) -> (&[usize], &[f64]) {
        self.idx.clear();
        self.val.clear();
        self.idx.push(0);
        self.val.push(1.0);
        for (a, (kv, &p)) in knots.iter().zip(degrees).enumerate() {
            let span = kv.span_unchecked(p, row[a]);
            basis_funs_into(
                kv.as_slice(),
                p,
                span,
                row[a],
                &mut self.scratch[a],
                &mut self.bases[a],
            );
            self.idx2.clear();
            self.val2.clear();
            for (&i, &v) in self.idx.iter().zip(&self.val) {
                for (j, &b) in self.bases[a].iter().enumerate() {
                    self.idx2.push(i + (span - p + j) * stride[a]);
                    self.val2.push(v * b);
                }
            }
            std::mem::swap(&mut self.idx, &mut self.idx2);
            std::mem::swap(&mut self.val, &mut self.val2);
        }
        (&self.idx, &self.val)
    }
}
