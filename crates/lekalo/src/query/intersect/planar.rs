//! The search behind planar curve–curve intersection (`docs/theory/queries.md#intersections`):
//! both curves' pieces in one frame as homogeneous `(x, y, w)` nets, the piece pairs whose boxes
//! overlap (sort and sweep), then per pair of sub-curves: box test, Bezier clipping against
//! the other's fat line, halving, and Newton's method once both are flat.
//!
//! Nothing here allocates per sub-curve: nets live in buffers recycled through a pool.

use super::super::pieces::QueryCurve;
use super::{MAX_DEPTH, MAX_PAIRS};
use crate::error::{Error, Result};
use crate::numeric::damped::{levenberg_marquardt, Residual};

/// Scalars per homogeneous planar point: `x·w, y·w, w`.
const H: usize = 3;
/// Clipping shorter than this fraction of a sub-curve's interval is applied; a clip that keeps
/// more is skipped and the larger sub-curve is halved instead (Sederberg–Nishita's 20% rule).
const CLIP_KEEP: f64 = 0.8;
/// Slack added to every fat line and box, in the frame's units (coordinates are `O(1)` there):
/// the rounding of the control points' distances, so that clipping never drops a solution.
const ROUND: f64 = 1e-13;
/// Newton steps from a flat pair before the Levenberg–Marquardt fallback.
const NEWTON_STEPS: usize = 12;
/// How far (in a piece's parameter) a solution may lie outside the intervals of a pair that
/// must hold a crossing and still count as the pair's: the rounding of a crossing at their
/// shared end (such a crossing is transversal, so its parameters are accurate).
const IN_PAIR: f64 = 1e-9;
/// Nets of up to this many points (degree 7) are evaluated on the stack.
const STACK_POINTS: usize = 8;

/// The pieces of a planar curve in a common frame `x_frame = (x − centre) / scale`, each a
/// homogeneous net of `degree + 1` points `(x·w, y·w, w)` (`w = 1` for a polynomial curve).
pub(super) struct PlaneNets {
    degree: usize,
    ctrl: Vec<f64>,
}

impl PlaneNets {
    /// The pieces of the planar curve `c` in the frame with `centre` and `scale`.
    pub(super) fn new(c: &QueryCurve, centre: &[f64], scale: f64) -> Self {
        debug_assert!(c.dim == 2, "planar curve");
        let f = c.scale / scale;
        let shift = [
            (c.centre[0] - centre[0]) / scale,
            (c.centre[1] - centre[1]) / scale,
        ];
        let mut ctrl = Vec::with_capacity(c.ctrl.len() / c.hd * H);
        for p in c.ctrl.chunks_exact(c.hd) {
            let w = if c.rational { p[2] } else { 1.0 };
            ctrl.extend([w * shift[0] + f * p[0], w * shift[1] + f * p[1], w]);
        }
        PlaneNets {
            degree: c.degree,
            ctrl,
        }
    }

    fn stride(&self) -> usize {
        (self.degree + 1) * H
    }

    pub(super) fn piece_count(&self) -> usize {
        self.ctrl.len() / self.stride()
    }

    pub(super) fn piece(&self, k: usize) -> &[f64] {
        let s = self.stride();
        &self.ctrl[k * s..(k + 1) * s]
    }

    /// Point and derivative (local parameter) of piece `k` at `s`: homogeneous de Casteljau
    /// down to two points, then the quotient rule (P&T eq. 1.9, §4.4).
    pub(super) fn eval(&self, k: usize, s: f64, scratch: &mut Vec<f64>) -> ([f64; 2], [f64; 2]) {
        eval_net(self.piece(k), s, scratch)
    }
}

/// Point and derivative of the homogeneous planar net at `s` (see [`PlaneNets::eval`]); nets of
/// up to [`STACK_POINTS`] points are worked on the stack.
fn eval_net(net: &[f64], s: f64, scratch: &mut Vec<f64>) -> ([f64; 2], [f64; 2]) {
    let mut stack = [0.0; STACK_POINTS * H];
    let b: &mut [f64] = if net.len() <= stack.len() {
        let b = &mut stack[..net.len()];
        b.copy_from_slice(net);
        b
    } else {
        scratch.clear();
        scratch.extend_from_slice(net);
        scratch
    };
    let n = b.len() / H - 1;
    if n == 0 {
        return ([b[0] / b[2], b[1] / b[2]], [0.0; 2]);
    }
    for level in 0..n - 1 {
        for i in 0..(n - level) * H {
            b[i] = (1.0 - s) * b[i] + s * b[i + H];
        }
    }
    let nf = n as f64;
    let mut h = [0.0; H];
    let mut dh = [0.0; H];
    for d in 0..H {
        h[d] = (1.0 - s) * b[d] + s * b[H + d];
        dh[d] = nf * (b[H + d] - b[d]);
    }
    let p = [h[0] / h[2], h[1] / h[2]];
    (
        p,
        [(dh[0] - dh[2] * p[0]) / h[2], (dh[1] - dh[2] * p[1]) / h[2]],
    )
}

/// Cartesian point `i` of a homogeneous planar net.
fn cart(net: &[f64], i: usize) -> [f64; 2] {
    let w = net[i * H + 2];
    [net[i * H] / w, net[i * H + 1] / w]
}

/// Box of a net's Cartesian control points: `[min x, min y, max x, max y]` (it holds the
/// sub-curve: convex hull, positive weights).
pub(super) fn net_box(net: &[f64]) -> [f64; 4] {
    let mut b = [
        f64::INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::NEG_INFINITY,
    ];
    for i in 0..net.len() / H {
        let p = cart(net, i);
        b[0] = b[0].min(p[0]);
        b[1] = b[1].min(p[1]);
        b[2] = b[2].max(p[0]);
        b[3] = b[3].max(p[1]);
    }
    b
}

fn overlap(a: &[f64; 4], b: &[f64; 4], slack: f64) -> bool {
    a[0] <= b[2] + slack && b[0] <= a[2] + slack && a[1] <= b[3] + slack && b[1] <= a[3] + slack
}

/// Largest distance of the Cartesian control points from the chord (the sub-curve is that
/// close to it: convex hull).
fn flatness(net: &[f64]) -> f64 {
    let n = net.len() / H - 1;
    let (a, b) = (cart(net, 0), cart(net, n));
    let ab = [b[0] - a[0], b[1] - a[1]];
    let l2 = ab[0] * ab[0] + ab[1] * ab[1];
    let mut worst = 0.0_f64;
    for i in 1..n {
        let p = cart(net, i);
        let ap = [p[0] - a[0], p[1] - a[1]];
        let t = if l2 > 0.0 {
            ((ap[0] * ab[0] + ap[1] * ab[1]) / l2).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let (dx, dy) = (ap[0] - t * ab[0], ap[1] - t * ab[1]);
        worst = worst.max(dx * dx + dy * dy);
    }
    worst.sqrt()
}

/// The fat line of a net (Sederberg–Nishita 1990): the unit normal `n` and offset `c` of the
/// line through its end points, and the least and greatest signed distance `n·x + c` of its
/// control points, widened by `slack`; the sub-curve lies in that band (convex hull). `None`
/// when the end points coincide.
fn fat_line(net: &[f64], slack: f64) -> Option<([f64; 2], f64, f64, f64)> {
    let n = net.len() / H - 1;
    let (a, b) = (cart(net, 0), cart(net, n));
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let len = norm([dx, dy]);
    if !(len > 0.0) {
        return None;
    }
    let nrm = [-dy / len, dx / len];
    let c = -(nrm[0] * a[0] + nrm[1] * a[1]);
    let (mut lo, mut hi) = (0.0_f64, 0.0_f64);
    for i in 1..n {
        let p = cart(net, i);
        let d = nrm[0] * p[0] + nrm[1] * p[1] + c;
        lo = lo.min(d);
        hi = hi.max(d);
    }
    Some((nrm, c, lo - slack, hi + slack))
}

/// The axis (unit chord) of a net and the tangent of the half-angle of a cone about it that
/// holds every difference `P_j − P_i` (`i < j`) of its Cartesian control points, hence every
/// tangent of its sub-curve (a positive combination of those differences, polynomial or
/// rational: Floater, "Derivatives of rational Bézier curves", CAGD 9, 1992). `None` when a
/// difference points against the chord (no such cone under a right angle) or the end points
/// coincide.
fn tangent_cone(net: &[f64]) -> Option<([f64; 2], f64)> {
    let n = net.len() / H - 1;
    let (a, b) = (cart(net, 0), cart(net, n));
    let len = norm([b[0] - a[0], b[1] - a[1]]);
    if !(len > 0.0) {
        return None;
    }
    let axis = [(b[0] - a[0]) / len, (b[1] - a[1]) / len];
    let mut half = 0.0_f64;
    for i in 0..n {
        let p = cart(net, i);
        for j in i + 1..=n {
            let q = cart(net, j);
            let d = [q[0] - p[0], q[1] - p[1]];
            let along = d[0] * axis[0] + d[1] * axis[1];
            let across = (d[0] * axis[1] - d[1] * axis[0]).abs();
            if along <= 0.0 {
                if along == 0.0 && across == 0.0 {
                    continue; // a repeated control point
                }
                return None;
            }
            half = half.max(across / along);
        }
    }
    Some((axis, half))
}

/// True when two sub-curves cross at most once: their tangent cones, taken as double cones
/// (lines), are apart. Two crossings would make the chord between them a direction of both.
///
/// With the half-angles `α`, `β` (tangents `a`, `b`) and the angle `θ ≤ π/2` between the axes
/// (`tan θ = |sin| / |cos|`), the cones are apart when `θ > α + β`: impossible when
/// `α + β ≥ π/2` (`ab ≥ 1`), otherwise, tan being increasing below `π/2`,
/// `|sin|·(1 − ab) > (a + b)·|cos|` (the tangent addition formula, cleared of its
/// denominators; no arc tangents).
fn at_most_one_crossing(x: &[f64], y: &[f64]) -> bool {
    let (Some((ex, a)), Some((ey, b))) = (tangent_cone(x), tangent_cone(y)) else {
        return false;
    };
    let sin = (ex[0] * ey[1] - ex[1] * ey[0]).abs();
    let cos = (ex[0] * ey[0] + ex[1] * ey[1]).abs();
    let ab = a * b;
    ab < 1.0 && sin * (1.0 - ab) > (a + b) * cos
}

/// True when the control points of `net` leave the fat line of `other` (widened by `slack`)
/// on one side, then the other, then the first again: the sub-curve may cross the band, and
/// so the other sub-curve, twice or more (variation diminishing; points inside the band do not
/// count, so coinciding sub-curves are not split for it).
fn crosses_band_twice(net: &[f64], other: &[f64], slack: f64) -> bool {
    let Some((nrm, c, lo, hi)) = fat_line(other, slack) else {
        return false;
    };
    let mut changes = 0;
    let mut last = 0_i8;
    for i in 0..net.len() / H {
        let w = net[i * H + 2];
        let e = nrm[0] * net[i * H] + nrm[1] * net[i * H + 1] + c * w;
        let side = if e > hi * w {
            1
        } else if e < lo * w {
            -1
        } else {
            0
        };
        if side != 0 {
            if last != 0 && side != last {
                changes += 1;
            }
            last = side;
        }
    }
    changes >= 2
}

/// True when the end points of `net` lie on opposite sides outside the fat line of `other`
/// (widened by `slack`): the sub-curve crosses that band.
fn ends_apart(net: &[f64], other: &[f64], slack: f64) -> bool {
    let Some((nrm, c, lo, hi)) = fat_line(other, slack) else {
        return false;
    };
    let side = |p: [f64; 2]| {
        let d = nrm[0] * p[0] + nrm[1] * p[1] + c;
        if d > hi {
            1
        } else if d < lo {
            -1
        } else {
            0
        }
    };
    let (a, b) = (side(cart(net, 0)), side(cart(net, net.len() / H - 1)));
    a * b < 0
}

/// The abscissae `[lo, hi]` where the convex hull of the points `(i/m, f(i))`, `i = 0..=m`,
/// reaches `y ≤ 0`: the extremes over the points below the axis and the axis crossings of every
/// segment between two points (the hull's edges among them). A Bernstein polynomial with
/// coefficients `f(i)` is positive outside (convex hull property).
fn below_range(m: usize, f: impl Fn(usize) -> f64) -> Option<(f64, f64)> {
    if m == 0 {
        return (f(0) <= 0.0).then_some((0.0, 1.0));
    }
    let mf = m as f64;
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for i in 0..=m {
        let fi = f(i);
        if fi <= 0.0 {
            let t = i as f64 / mf;
            lo = lo.min(t);
            hi = hi.max(t);
        }
        for j in i + 1..=m {
            let fj = f(j);
            if (fi <= 0.0) != (fj <= 0.0) {
                let t = (i as f64 + (j - i) as f64 * fi / (fi - fj)) / mf;
                lo = lo.min(t);
                hi = hi.max(t);
            }
        }
    }
    (lo <= hi).then_some((lo, hi))
}

/// Bezier clipping (Sederberg–Nishita 1990): the parameter range of `net` (a fraction of its
/// interval) outside which its curve lies outside the band `lo ≤ n·x + c ≤ hi`. For a rational
/// net the band condition is `lo·w ≤ n·X + c·w ≤ hi·w` on the homogeneous coordinates, two
/// polynomial conditions whose Bernstein coefficients are those of the control points. `None`
/// when the curve misses the band.
fn clip(net: &[f64], line: &([f64; 2], f64, f64, f64)) -> Option<(f64, f64)> {
    let (nrm, c, lo, hi) = *line;
    let m = net.len() / H - 1;
    let e = |i: usize| nrm[0] * net[i * H] + nrm[1] * net[i * H + 1] + c * net[i * H + 2];
    let (a0, a1) = below_range(m, |i| e(i) - hi * net[i * H + 2])?;
    let (b0, b1) = below_range(m, |i| lo * net[i * H + 2] - e(i))?;
    let (r0, r1) = (a0.max(b0), a1.min(b1));
    // a little wider than computed, against the rounding of the crossings
    (r0 <= r1).then(|| ((r0 - 1e-12).max(0.0), (r1 + 1e-12).min(1.0)))
}

/// The left part `[0, t]` of a net, in place (de Casteljau, the first point of each level).
fn keep_left(net: &mut [f64], t: f64) {
    let n = net.len() / H - 1;
    for level in 1..=n {
        for i in (level..=n).rev() {
            for d in 0..H {
                net[i * H + d] = (1.0 - t) * net[(i - 1) * H + d] + t * net[i * H + d];
            }
        }
    }
}

/// The right part `[t, 1]` of a net, in place (de Casteljau, the last point of each level).
fn keep_right(net: &mut [f64], t: f64) {
    let n = net.len() / H - 1;
    for level in 1..=n {
        for i in 0..=n - level {
            for d in 0..H {
                net[i * H + d] = (1.0 - t) * net[i * H + d] + t * net[(i + 1) * H + d];
            }
        }
    }
}

/// A sub-curve: its piece, its local parameter interval and its net.
pub(super) struct Sub {
    pub(super) k: usize,
    pub(super) s: (f64, f64),
    pub(super) net: Vec<f64>,
}

impl Sub {
    /// Restricts the sub-curve to the fraction `[lo, hi]` of its interval.
    fn restrict(&mut self, lo: f64, hi: f64) {
        if hi < 1.0 {
            keep_left(&mut self.net, hi);
        }
        if lo > 0.0 {
            if hi > 0.0 {
                keep_right(&mut self.net, (lo / hi).min(1.0));
            } else {
                let p = [self.net[0], self.net[1], self.net[2]];
                for q in self.net.chunks_exact_mut(H) {
                    q.copy_from_slice(&p);
                }
            }
        }
        let w = self.s.1 - self.s.0;
        self.s = (self.s.0 + lo * w, self.s.0 + hi * w);
    }
}

/// A solution of `A(s) = B(u)` on pieces `ka`, `kb` (local parameters), with its gap, the sine
/// of the angle between the tangents there and `|A'|` (frame units per local parameter).
#[derive(Debug, Clone, Copy)]
pub(super) struct Raw {
    pub(super) ka: usize,
    pub(super) s: f64,
    pub(super) kb: usize,
    pub(super) u: f64,
    pub(super) gap: f64,
    pub(super) sin: f64,
    pub(super) speed_a: f64,
}

/// The pairs `(i, j)` of boxes (one from each list) that overlap within `slack`: sort and sweep
/// along `x` (O((n + m) log(n + m) + pairs tested)); `i < j` only when `upper` (one list
/// against itself).
pub(super) fn overlapping_pairs(
    a: &[[f64; 4]],
    b: &[[f64; 4]],
    slack: f64,
    upper: bool,
) -> Vec<(usize, usize)> {
    // events: (x min, list, index); the active lists hold boxes whose x max is not yet passed
    let mut events: Vec<(f64, bool, usize)> = a
        .iter()
        .enumerate()
        .map(|(i, x)| (x[0], false, i))
        .chain(b.iter().enumerate().map(|(j, y)| (y[0], true, j)))
        .collect();
    events.sort_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)).then(x.2.cmp(&y.2)));
    let (mut act_a, mut act_b): (Vec<usize>, Vec<usize>) = (Vec::new(), Vec::new());
    let mut out = Vec::new();
    for (x0, in_b, i) in events {
        if in_b {
            act_a.retain(|&p| a[p][2] + slack >= x0);
            let y = &b[i];
            for &p in &act_a {
                if overlap(&a[p], y, slack) && (!upper || p < i) {
                    out.push((p, i));
                }
            }
            act_b.push(i);
        } else {
            act_b.retain(|&q| b[q][2] + slack >= x0);
            let x = &a[i];
            for &q in &act_b {
                if overlap(x, &b[q], slack) && (!upper || i < q) {
                    out.push((i, q));
                }
            }
            act_a.push(i);
        }
    }
    out.sort_unstable();
    out
}

/// The search over sub-curve pairs of two curves' [`PlaneNets`] (the same for a
/// self-intersection), with a pool of net buffers.
pub(super) struct Search<'a> {
    a: &'a PlaneNets,
    b: &'a PlaneNets,
    tol: f64,
    pool: Vec<Vec<f64>>,
    scratch: Vec<f64>,
}

impl<'a> Search<'a> {
    /// `tol`: the distance below which points are common, in the frame's units.
    pub(super) fn new(a: &'a PlaneNets, b: &'a PlaneNets, tol: f64) -> Self {
        Search {
            a,
            b,
            tol,
            pool: Vec::new(),
            scratch: Vec::new(),
        }
    }

    fn buffer(&mut self, from: &[f64]) -> Vec<f64> {
        let mut v = self.pool.pop().unwrap_or_default();
        v.clear();
        v.extend_from_slice(from);
        v
    }

    /// The whole piece `k` of the first curve (`second = false`) or the second.
    pub(super) fn piece(&mut self, second: bool, k: usize) -> Sub {
        let net = if second { self.b } else { self.a }.piece(k);
        let net = self.buffer(net);
        Sub {
            k,
            s: (0.0, 1.0),
            net,
        }
    }

    fn copy(&mut self, x: &Sub) -> Sub {
        Sub {
            k: x.k,
            s: x.s,
            net: self.buffer(&x.net),
        }
    }

    fn recycle(&mut self, x: Sub) {
        self.pool.push(x.net);
    }

    /// The halves of a sub-curve (one de Casteljau pass: the left half into a pooled buffer,
    /// the right in place).
    pub(super) fn halve(&mut self, mut x: Sub) -> (Sub, Sub) {
        let n = x.net.len() / H - 1;
        let mut left = self.pool.pop().unwrap_or_default();
        left.clear();
        left.extend_from_slice(&x.net[..H]);
        for level in 1..=n {
            for i in 0..(n + 1 - level) * H {
                x.net[i] = 0.5 * (x.net[i] + x.net[i + H]);
            }
            left.extend_from_slice(&x.net[..H]);
        }
        let m = 0.5 * (x.s.0 + x.s.1);
        let l = Sub {
            k: x.k,
            s: (x.s.0, m),
            net: left,
        };
        x.s.0 = m;
        (l, x)
    }

    /// Whether a sub-curve's hodograph (its control points' differences) lies in an open
    /// half-plane: then it turns by less than π and cannot cross itself.
    pub(super) fn turns_less_than_pi(x: &Sub) -> bool {
        let n = x.net.len() / H - 1;
        let mut angles: Vec<f64> = (0..n)
            .map(|i| {
                let (p, q) = (cart(&x.net, i), cart(&x.net, i + 1));
                [q[0] - p[0], q[1] - p[1]]
            })
            .filter(|d| d[0] != 0.0 || d[1] != 0.0)
            .map(|d| d[1].atan2(d[0]))
            .collect();
        if angles.is_empty() {
            return true;
        }
        angles.sort_by(f64::total_cmp);
        let n = angles.len();
        let mut max_gap = angles[0] + std::f64::consts::TAU - angles[n - 1];
        for w in angles.windows(2) {
            max_gap = max_gap.max(w[1] - w[0]);
        }
        max_gap > std::f64::consts::PI + 1e-12
    }

    /// Box of a sub-curve.
    pub(super) fn sub_box(x: &Sub) -> [f64; 4] {
        net_box(&x.net)
    }

    /// Every solution within the tolerance reached from `pairs`: while the boxes of a pair
    /// overlap, each sub-curve is clipped to the other's fat line (kept when it drops at least
    /// a fifth of the interval, and then clipped again); when neither clip bites the larger
    /// sub-curve that is not flat is halved; once both are flat (every control point within 1%
    /// of the box's diagonal from the chord, or the box within the tolerance) or at depth
    /// [`MAX_DEPTH`], Newton's method runs from the chords' crossing. Two flat sub-curves are
    /// halved further when they may cross twice (their tangent cones meet and one leaves the
    /// other's fat line on both sides and comes back), and when Newton's method and its
    /// fallback fail from their chords although one runs from one side of the other's fat line
    /// to the other (a shallow crossing, whose chords meet far from it), until a sub-curve is
    /// within the tolerance or at [`MAX_DEPTH`].
    ///
    /// # Errors
    /// [`Error::TooLarge`] beyond [`MAX_PAIRS`] examined pairs.
    pub(super) fn run(&mut self, pairs: Vec<(Sub, Sub)>) -> Result<Vec<Raw>> {
        let tol = self.tol;
        let slack = tol + ROUND;
        let mut stack: Vec<(Sub, Sub, u32)> = pairs.into_iter().map(|(x, y)| (x, y, 0)).collect();
        let mut visited = 0_usize;
        let mut out = Vec::new();
        while let Some((mut x, mut y, depth)) = stack.pop() {
            visited += 1;
            if visited > MAX_PAIRS {
                return Err(Error::TooLarge {
                    what: "sub-curve pairs examined by the intersection".into(),
                    size: visited,
                    max: MAX_PAIRS,
                });
            }
            let (mut xb, mut yb) = (net_box(&x.net), net_box(&y.net));
            if !overlap(&xb, &yb, slack) {
                self.recycle(x);
                self.recycle(y);
                continue;
            }
            let mut clipped = false;
            if depth < MAX_DEPTH {
                let mut missed = false;
                for turn in 0..2 {
                    let (me, other) = if turn == 0 {
                        (&mut x, &y)
                    } else {
                        (&mut y, &x)
                    };
                    let Some(line) = fat_line(&other.net, slack) else {
                        continue;
                    };
                    match clip(&me.net, &line) {
                        None => {
                            missed = true;
                            break;
                        }
                        Some((lo, hi)) if hi - lo <= CLIP_KEEP => {
                            me.restrict(lo, hi);
                            clipped = true;
                        }
                        Some(_) => {}
                    }
                }
                if missed {
                    self.recycle(x);
                    self.recycle(y);
                    continue;
                }
                if clipped {
                    xb = net_box(&x.net);
                    yb = net_box(&y.net);
                }
            }
            let (xd, yd) = (diagonal(&xb), diagonal(&yb));
            let mut x_flat = xd <= tol || flatness(&x.net) <= 1e-2 * xd;
            let mut y_flat = yd <= tol || flatness(&y.net) <= 1e-2 * yd;
            if x_flat && y_flat && depth < MAX_DEPTH && !at_most_one_crossing(&x.net, &y.net) {
                // flat, but one may cross the other's band twice (a shallow dip through a
                // line): halved until each crossing has a pair of its own
                x_flat = x_flat && !(xd > tol && crosses_band_twice(&x.net, &y.net, slack));
                y_flat = y_flat && !(yd > tol && crosses_band_twice(&y.net, &x.net, slack));
            }
            let halve_x = if (x_flat && y_flat) || depth >= MAX_DEPTH {
                let must_cross =
                    ends_apart(&x.net, &y.net, slack) || ends_apart(&y.net, &x.net, slack);
                // Newton's method is not confined to the pair's intervals: where the pair must
                // hold a crossing, a solution outside them is another pair's, not its own
                let inside = |v: f64, r: (f64, f64)| v >= r.0 - IN_PAIR && v <= r.1 + IN_PAIR;
                let solved = self
                    .solve(&x, &y)
                    .filter(|r| !must_cross || (inside(r.s, x.s) && inside(r.u, y.s)));
                let found = solved.is_some();
                out.extend(solved);
                if found || !must_cross || depth >= MAX_DEPTH || xd.max(yd) <= tol {
                    self.recycle(x);
                    self.recycle(y);
                    continue;
                }
                // Newton's method and the least-squares fallback found no crossing of the pair
                // from the chords' crossing, yet one sub-curve runs from one side of the other's fat line to the
                // other side: at a shallow crossing a flat sub-curve's chord can put that start
                // far from the root, so the pair is halved again (clipping then narrows it)
                // rather than given up. (A near miss, a contact or an overlap has no such
                // sub-curve, and is not halved for it.)
                xd >= yd
            } else if clipped {
                stack.push((x, y, depth + 1));
                continue;
            } else {
                !x_flat && (y_flat || xd >= yd)
            };
            if halve_x {
                let (l, r) = self.halve(x);
                let y2 = self.copy(&y);
                stack.push((l, y, depth + 1));
                stack.push((r, y2, depth + 1));
            } else {
                let (l, r) = self.halve(y);
                let x2 = self.copy(&x);
                stack.push((x, l, depth + 1));
                stack.push((x2, r, depth + 1));
            }
        }
        Ok(out)
    }

    /// Newton's method on `A(s) = B(u)` (the pieces' local parameters, clamped to `[0, 1]`)
    /// from the crossing of the two sub-curves' chords (their middles when the chords are
    /// parallel), then Levenberg–Marquardt from the best point when Newton's method has not
    /// reached the tolerance (a tangential contact, where the Jacobian is singular). `None`
    /// when the least gap found exceeds the tolerance.
    fn solve(&mut self, x: &Sub, y: &Sub) -> Option<Raw> {
        let (s0, u0) = chord_crossing(x, y);
        let (mut s, mut u) = (s0, u0);
        let mut best = (f64::INFINITY, s, u);
        for _ in 0..NEWTON_STEPS {
            let (pa, da) = self.a.eval(x.k, s, &mut self.scratch);
            let (pb, db) = self.b.eval(y.k, u, &mut self.scratch);
            let r = [pa[0] - pb[0], pa[1] - pb[1]];
            let gap = norm(r);
            if gap < best.0 {
                best = (gap, s, u);
            } else if best.0 <= self.tol {
                // converged: rounding no longer lets the gap fall
                break;
            }
            if gap == 0.0 {
                break;
            }
            // [da, −db] (δs, δu) = −r
            let det = db[0] * da[1] - da[0] * db[1];
            if !(det.abs() > 1e-14 * norm(da) * norm(db)) {
                break;
            }
            let ds = (r[0] * db[1] - r[1] * db[0]) / det;
            let du = (r[0] * da[1] - r[1] * da[0]) / det;
            let (ns, nu) = ((s + ds).clamp(0.0, 1.0), (u + du).clamp(0.0, 1.0));
            let moved = (ns - s).abs() + (nu - u).abs();
            s = ns;
            u = nu;
            if moved <= 4.0 * f64::EPSILON {
                break;
            }
        }
        let (mut gap, mut s, mut u) = best;
        if gap > self.tol {
            (s, u, gap) = self.least_squares(x.k, y.k, s, u);
        }
        if !(gap <= self.tol) {
            return None;
        }
        let (_, da) = self.a.eval(x.k, s, &mut self.scratch);
        let (_, db) = self.b.eval(y.k, u, &mut self.scratch);
        let (la, lb) = (norm(da), norm(db));
        let sin = if la > 0.0 && lb > 0.0 {
            ((da[0] * db[1] - da[1] * db[0]) / (la * lb)).abs()
        } else {
            0.0
        };
        Some(Raw {
            ka: x.k,
            s,
            kb: y.k,
            u,
            gap,
            sin,
            speed_a: la,
        })
    }

    /// Levenberg–Marquardt for `A(s) = B(u)` on pieces `ka`, `kb` from `(s0, u0)`, in `[0, 1]²`
    /// (`numeric::damped`, with its bounds on steps and trials); returns `(s, u, gap)`.
    fn least_squares(&mut self, ka: usize, kb: usize, s0: f64, u0: f64) -> (f64, f64, f64) {
        let mut scratch = std::mem::take(&mut self.scratch);
        let ([s, u], gap) = levenberg_marquardt([s0, u0], |&[s, u]| {
            let (pa, da) = self.a.eval(ka, s, &mut scratch);
            let (pb, db) = self.b.eval(kb, u, &mut scratch);
            let r = [pa[0] - pb[0], pa[1] - pb[1]];
            // J = [da, −db]
            let cross = -(da[0] * db[0] + da[1] * db[1]);
            Residual {
                gap: norm(r),
                normal: [
                    [da[0] * da[0] + da[1] * da[1], cross],
                    [cross, db[0] * db[0] + db[1] * db[1]],
                ],
                gradient: [da[0] * r[0] + da[1] * r[1], -(db[0] * r[0] + db[1] * r[1])],
            }
        });
        self.scratch = scratch;
        (s, u, gap)
    }
}

fn diagonal(b: &[f64; 4]) -> f64 {
    norm([b[2] - b[0], b[3] - b[1]])
}

/// Euclidean length (no overflow in the frame, where coordinates are `O(1)`).
fn norm(v: [f64; 2]) -> f64 {
    (v[0] * v[0] + v[1] * v[1]).sqrt()
}

/// Local parameters on the two sub-curves' pieces where their chords cross (clamped to the
/// sub-curves), or their middles when the chords are parallel.
fn chord_crossing(x: &Sub, y: &Sub) -> (f64, f64) {
    let (p0, p1) = (cart(&x.net, 0), cart(&x.net, x.net.len() / H - 1));
    let (q0, q1) = (cart(&y.net, 0), cart(&y.net, y.net.len() / H - 1));
    let (d, e) = (
        [p1[0] - p0[0], p1[1] - p0[1]],
        [q1[0] - q0[0], q1[1] - q0[1]],
    );
    let r = [q0[0] - p0[0], q0[1] - p0[1]];
    let den = d[0] * e[1] - d[1] * e[0];
    let (mut a, mut b) = (0.5, 0.5);
    if den != 0.0 {
        let (ta, tb) = (
            (r[0] * e[1] - r[1] * e[0]) / den,
            (r[0] * d[1] - r[1] * d[0]) / den,
        );
        if ta.is_finite() && tb.is_finite() {
            (a, b) = (ta.clamp(0.0, 1.0), tb.clamp(0.0, 1.0));
        }
    }
    (x.s.0 + a * (x.s.1 - x.s.0), y.s.0 + b * (y.s.1 - y.s.0))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn net(pts: &[[f64; 3]]) -> Vec<f64> {
        pts.iter().flatten().copied().collect()
    }

    #[test]
    fn restrict_matches_evaluation() {
        // a rational quadratic and a cubic: the restricted net evaluates to the original curve
        // at the mapped parameters
        for n in [
            net(&[[0.0, 0.0, 1.0], [0.7, 1.4, 0.7], [2.0, 0.0, 1.0]]),
            net(&[
                [0.0, 0.0, 1.0],
                [1.0, 2.0, 1.0],
                [2.0, -1.0, 1.0],
                [3.0, 1.0, 1.0],
            ]),
        ] {
            let mut x = Sub {
                k: 0,
                s: (0.0, 1.0),
                net: n.clone(),
            };
            x.restrict(0.2, 0.7);
            assert!(
                (x.s.0 - 0.2).abs() < 1e-15 && (x.s.1 - 0.7).abs() < 1e-15,
                "{:?}",
                x.s
            );
            let mut scratch = Vec::new();
            for f in [0.0, 0.3, 1.0] {
                let (p, _) = eval_net(&x.net, f, &mut scratch);
                let (q, _) = eval_net(&n, 0.2 + 0.5 * f, &mut scratch);
                assert!(
                    (p[0] - q[0]).abs() < 1e-14 && (p[1] - q[1]).abs() < 1e-14,
                    "{p:?} {q:?}"
                );
            }
        }
    }

    #[test]
    fn clip_keeps_the_band_crossing() {
        // the cubic y = 3 t (1 − t)·… crosses the band |y − 0.5| ≤ 0.01 near two parameters;
        // the clip interval holds both and every parameter outside it maps outside the band
        let n = net(&[
            [0.0, 0.0, 1.0],
            [1.0, 1.0, 1.0],
            [2.0, 1.0, 1.0],
            [3.0, 0.0, 1.0],
        ]);
        let line = ([0.0, 1.0], -0.5, -0.01, 0.01);
        let (lo, hi) = clip(&n, &line).expect("crosses");
        let mut scratch = Vec::new();
        for i in 0..=1000 {
            let t = f64::from(i) / 1000.0;
            let (p, _) = eval_net(&n, t, &mut scratch);
            if (p[1] - 0.5).abs() <= 0.01 {
                assert!(
                    t >= lo && t <= hi,
                    "t {t} in the band but outside [{lo}, {hi}]"
                );
            }
        }
        assert!(hi - lo < 1.0, "[{lo}, {hi}] should drop the ends");
        // a band the curve misses
        assert!(
            clip(&n, &([0.0, 1.0], -2.0, -0.01, 0.01)).is_none(),
            "y = 2 missed"
        );
    }

    #[test]
    fn sweep_finds_the_same_pairs_as_all_pairs() {
        let boxes = |seed: f64| -> Vec<[f64; 4]> {
            (0..40)
                .map(|i| {
                    let x = (f64::from(i) * seed).sin() * 3.0;
                    let y = (f64::from(i) * seed * 1.7).cos() * 3.0;
                    let (w, h) = (0.1 + (f64::from(i) * 0.37).sin().abs(), 0.2);
                    [x, y, x + w, y + h]
                })
                .collect()
        };
        let (a, b) = (boxes(0.9), boxes(1.3));
        let mut all = Vec::new();
        for i in 0..a.len() {
            for j in 0..b.len() {
                if overlap(&a[i], &b[j], 0.01) {
                    all.push((i, j));
                }
            }
        }
        assert!(!all.is_empty(), "the test needs overlaps");
        assert_eq!(overlapping_pairs(&a, &b, 0.01, false), all);
        let upper: Vec<(usize, usize)> = (0..a.len())
            .flat_map(|i| (i + 1..a.len()).map(move |j| (i, j)))
            .filter(|&(i, j)| overlap(&a[i], &a[j], 0.01))
            .collect();
        assert_eq!(overlapping_pairs(&a, &a, 0.01, true), upper);
    }
}
