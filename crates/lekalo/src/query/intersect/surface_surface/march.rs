//! Marching along a branch of a section (`docs/theory/queries.md#marching`): predictor along the
//! tangent, Newton corrector on the plane through the predicted point orthogonal to the tangent,
//! step length from the error of the cubic Hermite interpolant of the step's ends, the points in
//! between filled from the cubics of corrected points, stops at the sides of the parameter box,
//! at a tangency of the surfaces or where the branch closes (Barnhill and Kersey 1990).

use super::super::super::pieces::{dist, dot};
use super::segment_distance3;
use super::system::{newton, tangent, Jet, System, K};
use crate::error::{Error, Result};

/// Most points of one branch (reaching it is [`Error::TooLarge`]).
pub(super) const MAX_BRANCH_POINTS: usize = 1 << 20;
/// Longest step, relative to the surfaces' scale.
pub(super) const MAX_STEP: f64 = 0.05;
/// Shortest step, relative to the scale: a step halved below it ends the branch.
const MIN_STEP: f64 = 1e-9;
/// Largest turning of the tangent over one step (radians): a step turning more is halved, so a
/// corrector never jumps to a neighbouring branch.
const MAX_TURN: f64 = 0.2;
/// Below this sine of the angle between the normals the surfaces count as tangent: the marching
/// stops there.
pub(super) const SIN_STOP: f64 = 1e-4;

/// Share of the tolerance the cubic Hermite step may deviate from the branch (in the fitted
/// coordinates, at the filled points): the rest is the margin of the fit, which measures every
/// point.
const HERMITE_SHARE: f64 = 0.5;
/// Share of the tolerance the halves of a cubic Hermite step may deviate from the branch (at
/// their corrected middles): the filled points, on the quarters' cubics, are closer still, so
/// every point of a branch is within this share of the tolerance of both surfaces.
const INTERP_SHARE: f64 = 0.1;
/// Share of the tolerance the chords between filled points aim at.
const CHORD_SHARE: f64 = 0.9;
/// Share of the tolerance every chord's sagitta is checked against (the rest is the margin for
/// the quarter cubics' error).
const CHORD_CHECK: f64 = 0.95;
/// Most points filled into one step.
const MAX_FILL: usize = 1 << 14;
/// Points a walk makes room for at its start (a closed curve of a few unit radii at a
/// tolerance of `10⁻⁶` has a few thousand), so that a walk of that size copies none of them
/// while it grows.
const TRAIL_CAPACITY: usize = 2048;

/// A point of a branch with its unit tangent (in the unknowns and in space).
struct Node {
    x: [f64; K],
    p: [f64; 3],
    tx: [f64; K],
    tp: [f64; 3],
}

/// The outcome of filling a step ([`March::fill`]): the largest distance of the cubic Hermite
/// step from the branch; `refused` when the step's middle alone missed [`HERMITE_SHARE`] of the
/// tolerance (no points filled then).
#[derive(Default)]
struct Fill {
    err: f64,
    refused: bool,
}

/// The points of a walk so far, with their unknowns and tangents: the marched points and the
/// points filled between them, written in place (a refused step is cut off again), so that a
/// step costs no allocation of its own.
struct Trail {
    xs: Vec<[f64; K]>,
    ps: Vec<[f64; 3]>,
    ts: Vec<Tangent>,
}

impl Trail {
    fn len(&self) -> usize {
        self.xs.len()
    }

    fn push(&mut self, x: [f64; K], p: [f64; 3], t: Tangent) {
        self.xs.push(x);
        self.ps.push(p);
        self.ts.push(t);
    }

    /// Cuts the trail back to its first `n` points (a refused step's filled points).
    fn truncate(&mut self, n: usize) {
        self.xs.truncate(n);
        self.ps.truncate(n);
        self.ts.truncate(n);
    }
}

/// A tangent turned to agree with `along`.
fn oriented(t: Option<([f64; K], [f64; 3])>, along: &[f64; 3]) -> Tangent {
    t.map(|(mut a, mut b)| {
        if dot(&b, along) < 0.0 {
            for c in a.iter_mut().chain(b.iter_mut()) {
                *c = -*c;
            }
        }
        (a, b)
    })
}

/// How a traced piece of a branch ended.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Stop {
    /// It reached a side of a parameter box.
    Boundary,
    /// It came back to its start.
    Closed,
    /// It ran into a tangency of the surfaces (the point where it stopped, refined).
    Tangent,
}

/// A point's tangent: in the unknowns and in space, at unit speed in space, oriented along the
/// branch (`None` at an end at a tangency, where the normals are parallel).
pub(super) type Tangent = Option<Unit>;

/// A unit tangent: in the unknowns and in space.
pub(super) type Unit = ([f64; K], [f64; 3]);

/// A corrected point of a cubic step: its parameter on the step, unknowns, point and tangent.
type Sample = (f64, [f64; K], [f64; 3], Unit);

/// A traced branch: unknowns, points and tangents, how each end stopped, and the largest
/// `|S_u| + |S_v|` of each surface on it (0 for a plane).
#[derive(Debug, Clone)]
pub(super) struct Traced {
    pub(super) xs: Vec<[f64; K]>,
    pub(super) ps: Vec<[f64; 3]>,
    pub(super) tangents: Vec<Tangent>,
    pub(super) stops: [Stop; 2],
    pub(super) reach: [f64; 2],
}

/// One direction of marching: what [`Traced`] holds, one stop.
struct Walk {
    xs: Vec<[f64; K]>,
    ps: Vec<[f64; 3]>,
    ts: Vec<Tangent>,
    stop: Stop,
    reach: [f64; 2],
}

/// `|S_u| + |S_v|` of both surfaces at a jet (the second's derivatives are the Jacobian's last
/// two columns; zero for a plane section).
fn reach_of(jet: &Jet) -> [f64; 2] {
    let col = |c: usize| [jet.j[0][c], jet.j[1][c], jet.j[2][c]];
    [
        norm3(&jet.dp[0]) + norm3(&jet.dp[1]),
        norm3(&col(2)) + norm3(&col(3)),
    ]
}

fn norm3(a: &[f64; 3]) -> f64 {
    dot(a, a).sqrt()
}

/// The marching's settings: tolerance, scale.
pub(super) struct March<'a> {
    pub(super) sys: &'a dyn System,
    pub(super) tol: f64,
    pub(super) scale: f64,
}

impl March<'_> {
    /// Residual to which points are corrected: a millionth of the tolerance, at least the
    /// rounding of the scale. Newton's method converges quadratically from the marching's
    /// predictions, so the last step that brings a point within a thousandth of the tolerance
    /// usually brings it to rounding: asking for a millionth costs at most that one step and
    /// keeps the points on both surfaces to about 1e-12 of the scale.
    pub(super) fn eps(&self) -> f64 {
        (1e-6 * self.tol).max(1e-14 * self.scale)
    }

    /// The branch through the point `x0` (on the section): marched forwards; unless that closes
    /// it, marched backwards from `x0` too and the two joined.
    pub(super) fn branch(&self, x0: [f64; K], j0: &Jet) -> Result<Traced> {
        let f = self.walk(x0, j0, 1.0)?;
        if f.stop == Stop::Closed {
            return Ok(Traced {
                xs: f.xs,
                ps: f.ps,
                tangents: f.ts,
                stops: [Stop::Closed, Stop::Closed],
                reach: f.reach,
            });
        }
        let b = self.walk(x0, j0, -1.0)?;
        let (mut bx, mut bp, mut bt) = (b.xs, b.ps, b.ts);
        bx.reverse();
        bp.reverse();
        bt.reverse();
        bx.pop();
        bp.pop();
        bt.pop();
        // the backward walk's tangents point backwards
        for (tx, tp) in bt.iter_mut().flatten() {
            for c in tx.iter_mut().chain(tp.iter_mut()) {
                *c = -*c;
            }
        }
        bx.extend(f.xs);
        bp.extend(f.ps);
        bt.extend(f.ts);
        if bx.len() > MAX_BRANCH_POINTS {
            return Err(Error::TooLarge {
                what: "points of an intersection branch".into(),
                size: bx.len(),
                max: MAX_BRANCH_POINTS,
            });
        }
        Ok(Traced {
            xs: bx,
            ps: bp,
            tangents: bt,
            stops: [b.stop, f.stop],
            reach: [f.reach[0].max(b.reach[0]), f.reach[1].max(b.reach[1])],
        })
    }

    /// One direction of marching from `x0` (`sign` ±1 along the tangent), `x0` first.
    fn walk(&self, x0: [f64; K], j0: &Jet, sign: f64) -> Result<Walk> {
        let k = self.sys.k();
        let bounds = self.sys.bounds();
        let mut tr = Trail {
            xs: Vec::with_capacity(TRAIL_CAPACITY),
            ps: Vec::with_capacity(TRAIL_CAPACITY),
            ts: Vec::with_capacity(TRAIL_CAPACITY),
        };
        tr.xs.push(x0);
        tr.ps.push(j0.p);
        let mut reach = reach_of(j0);
        let done = |tr: Trail, stop, reach| {
            Ok(Walk {
                xs: tr.xs,
                ps: tr.ps,
                ts: tr.ts,
                stop,
                reach,
            })
        };
        let Some((mut tx, mut tp)) = tangent(j0, k) else {
            tr.ts.push(None);
            return done(tr, Stop::Tangent, reach);
        };
        for i in 0..K {
            tx[i] *= sign;
        }
        for c in &mut tp {
            *c *= sign;
        }
        tr.ts.push(Some((tx, tp)));
        let (hmax, hmin) = (MAX_STEP * self.scale, MIN_STEP * self.scale);
        let mut h = hmax;
        let (mut x, mut jet) = (x0, j0.clone());
        let mut prev_sin = jet.sin;
        let mut prev_p = jet.p;
        let mut steps = 0_usize;
        loop {
            if tr.len() > MAX_BRANCH_POINTS {
                return Err(Error::TooLarge {
                    what: "points of an intersection branch".into(),
                    size: tr.len(),
                    max: MAX_BRANCH_POINTS,
                });
            }
            if h < hmin {
                let stop = self.end_tangent(&mut tr, &tx, (prev_sin, &prev_p), &jet);
                return done(tr, stop, reach);
            }
            // the trail's length before this step: a refused step's filled points are cut
            let mark = tr.len();
            // predictor, cut at the first side of the box it would cross
            let mut frac = 1.0_f64;
            let mut side = None;
            for i in 0..k {
                let d = h * tx[i];
                let to = x[i] + d;
                let lim = if to > bounds[i].1 {
                    Some(bounds[i].1)
                } else if to < bounds[i].0 {
                    Some(bounds[i].0)
                } else {
                    None
                };
                if let Some(l) = lim {
                    let f = ((l - x[i]) / d).clamp(0.0, 1.0);
                    if f < frac {
                        frac = f;
                        side = Some((i, l));
                    }
                }
            }
            if let Some((i, l)) = side {
                if frac * h <= 1e-12 * self.scale {
                    // on the side already, heading out
                    return done(tr, Stop::Boundary, reach);
                }
                let mut xp = x;
                for c in 0..k {
                    xp[c] += frac * h * tx[c];
                }
                xp[i] = l;
                let Some((xn, jn)) = newton(self.sys, xp, Some(i), None, self.eps()) else {
                    h *= 0.5;
                    continue;
                };
                if !(jn.gap(k) <= 0.1 * self.tol) {
                    h *= 0.5;
                    continue;
                }
                let end = oriented(tangent(&jn, k), &tp);
                let ok = match end {
                    // a side point where the normals are parallel ends the branch by a chord
                    None => self.turn_ok(&tp, &jn, k, dist(&jn.p, &jet.p)),
                    Some((ntx, ntp)) => {
                        let turn = dot(&ntp, &tp).clamp(-1.0, 1.0).acos();
                        let a = Node {
                            x,
                            p: jet.p,
                            tx,
                            tp,
                        };
                        let b = Node {
                            x: xn,
                            p: jn.p,
                            tx: ntx,
                            tp: ntp,
                        };
                        turn <= MAX_TURN
                            && self
                                .fill(&a, &b, reach, &mut tr)
                                .is_some_and(|f| !f.refused && f.err <= self.tol)
                    }
                };
                if !ok {
                    tr.truncate(mark);
                    h *= 0.5;
                    continue;
                }
                tr.push(xn, jn.p, end);
                let r = reach_of(&jn);
                reach = [reach[0].max(r[0]), reach[1].max(r[1])];
                return done(tr, Stop::Boundary, reach);
            }
            let mut xp = x;
            for c in 0..k {
                xp[c] += h * tx[c];
            }
            let target = [
                jet.p[0] + h * tp[0],
                jet.p[1] + h * tp[1],
                jet.p[2] + h * tp[2],
            ];
            let Some((xn, jn)) = newton(self.sys, xp, None, Some((tp, target)), self.eps()) else {
                h *= 0.5;
                continue;
            };
            let step = dist(&jn.p, &jet.p);
            if !(jn.gap(k) <= 0.1 * self.tol) || !(step <= 2.0 * h) || step == 0.0 {
                h *= 0.5;
                continue;
            }
            let Some((mut ntx, mut ntp)) = tangent(&jn, k) else {
                h *= 0.5;
                continue;
            };
            if dot(&ntp, &tp) < 0.0 {
                for c in &mut ntx {
                    *c = -*c;
                }
                for c in &mut ntp {
                    *c = -*c;
                }
            }
            let turn = dot(&ntp, &tp).clamp(-1.0, 1.0).acos();
            if turn > MAX_TURN {
                h *= 0.5;
                continue;
            }
            let a = Node {
                x,
                p: jet.p,
                tx,
                tp,
            };
            // closed: the start lies between the last point and this one (near their chord,
            // which deviates from the branch by about hθ/8)
            if steps >= 2 {
                let start = tr.ps[0];
                let near = segment_distance3(&start, &jet.p, &jn.p)
                    <= 2.0 * self.tol + step * turn / 4.0 + 1e-12 * self.scale;
                let between = dot(
                    &[
                        start[0] - jet.p[0],
                        start[1] - jet.p[1],
                        start[2] - jet.p[2],
                    ],
                    &[jn.p[0] - start[0], jn.p[1] - start[1], jn.p[2] - start[2]],
                ) >= 0.0;
                let same = (0..k).all(|c| {
                    let slack = 1e-6 * (bounds[c].1 - bounds[c].0);
                    let s = tr.xs[0][c];
                    s >= x[c].min(xn[c]) - slack && s <= x[c].max(xn[c]) + slack
                });
                if near && between && same {
                    let Some((sx, sp)) = tr.ts[0] else {
                        return done(tr, Stop::Tangent, reach);
                    };
                    let (x_start, t_start) = (tr.xs[0], tr.ts[0]);
                    let b = Node {
                        x: x_start,
                        p: start,
                        tx: sx,
                        tp: sp,
                    };
                    if !self
                        .fill(&a, &b, reach, &mut tr)
                        .is_some_and(|f| !f.refused && f.err <= self.tol)
                    {
                        tr.truncate(mark);
                        h *= 0.5;
                        continue;
                    }
                    tr.push(x_start, start, t_start);
                    return done(tr, Stop::Closed, reach);
                }
            }
            let b = Node {
                x: xn,
                p: jn.p,
                tx: ntx,
                tp: ntp,
            };
            let Some(fill) = self.fill(&a, &b, reach, &mut tr) else {
                tr.truncate(mark);
                h *= 0.5;
                continue;
            };
            if fill.refused || fill.err > self.tol {
                tr.truncate(mark);
                // the cubic's error grows like h⁴
                h *= (0.9 * (HERMITE_SHARE * self.tol / fill.err).powf(0.25)).clamp(0.1, 0.5);
                continue;
            }
            steps += 1;
            let err = fill.err;
            tr.push(xn, jn.p, Some((ntx, ntp)));
            let r = reach_of(&jn);
            reach = [reach[0].max(r[0]), reach[1].max(r[1])];
            prev_sin = jet.sin;
            prev_p = jet.p;
            x = xn;
            jet = jn;
            tx = ntx;
            tp = ntp;
            if jet.sin < SIN_STOP {
                let stop = self.end_tangent(&mut tr, &tx, (prev_sin, &prev_p), &jet);
                return done(tr, stop, reach);
            }
            // next step: the cubic's error, measured at the filled points, grows like h⁴
            let grow = if err > 0.0 {
                (HERMITE_SHARE * self.tol / err).powf(0.25)
            } else {
                2.0
            };
            h = (h * grow.clamp(0.5, 2.0) * 0.9).clamp(hmin, hmax);
        }
    }

    /// The points between two marched points `a` and `b` at which the chords are within the
    /// tolerance of the branch. The cubic Hermite interpolant of the two in the unknowns and in
    /// space ([`hermite`]) has its middle corrected onto the section (Newton's method on the
    /// plane through it orthogonal to the cubic's tangent); the distance moved (in the fitted
    /// coordinates of `fit.rs`, `reach` scaling the parameters) is the step's error, and a step
    /// whose middle misses [`HERMITE_SHARE`] of the tolerance is refused there. The middles of
    /// the two halves (the cubics of the ends and the corrected middle) are corrected the same
    /// way: their distances measure the halves' error, and a step whose halves miss
    /// [`INTERP_SHARE`] of the tolerance is refused too (with an error 16 times theirs, the
    /// `h⁴` law). The points in between are then the four quarter cubics' points, not corrected:
    /// each quarter's cubic interpolates corrected points a quarter of the step apart, closer to
    /// the branch than the halves' measured error (about 1/16 of it, by the same law), so every
    /// point is within [`INTERP_SHARE`] of the tolerance of both surfaces. They are placed at
    /// equal parameter steps, `m` a quarter from the chords' sagitta `(c/m)(θ/m)/8` at
    /// [`CHORD_SHARE`] of the tolerance; every chord is then checked by the turning of the
    /// cubic's tangents at its ends (`cθ/8`, against [`CHORD_CHECK`] of it, the rest left for
    /// the cubic's error), and a point halfway (in the cubic's parameter) is added where it
    /// fails. The points are appended to `tr` (none when the step is refused); `None` when a
    /// correction fails or more than [`MAX_FILL`] points would be needed (the points appended
    /// so far are then the caller's to cut).
    fn fill(&self, a: &Node, b: &Node, reach: [f64; 2], tr: &mut Trail) -> Option<Fill> {
        if dist(&a.p, &b.p) == 0.0 {
            return Some(Fill::default());
        }
        let scale = [
            if reach[0] > 0.0 { reach[0] } else { 1.0 },
            if reach[1] > 0.0 { reach[1] } else { 1.0 },
        ];
        let (m, err) = self.correct_middle(a, b, scale)?;
        if err > HERMITE_SHARE * self.tol {
            return Some(Fill { err, refused: true });
        }
        let (q1, e1) = self.correct_middle(a, &m, scale)?;
        let (q3, e3) = self.correct_middle(&m, b, scale)?;
        let halves = e1.max(e3);
        if halves > INTERP_SHARE * self.tol {
            return Some(Fill {
                err: err.max(16.0 * halves),
                refused: true,
            });
        }
        let base = tr.len();
        let mut todo = Vec::new();
        let nodes = [a, &q1, &m, &q3, b];
        for (i, w) in nodes.windows(2).enumerate() {
            self.fill_quarter(w[0], w[1], (tr, base), &mut todo)?;
            if i < 3 {
                let n = w[1];
                tr.push(n.x, n.p, Some((n.tx, n.tp)));
            }
        }
        Some(Fill {
            err,
            refused: false,
        })
    }

    /// The middle of the cubic Hermite interpolant of `a` and `b`, corrected onto the section,
    /// with its tangent, and the distance it moved in the fitted coordinates (`scale` the
    /// factors of the two surfaces' parameters).
    fn correct_middle(&self, a: &Node, b: &Node, scale: [f64; 2]) -> Option<(Node, f64)> {
        let k = self.sys.k();
        let len = step_length(a, b);
        let (xh, ph, _, dp) = hermite(a, b, len, 0.5);
        let l = dot(&dp, &dp).sqrt();
        if !(l > 0.0) {
            return None;
        }
        let dir = [dp[0] / l, dp[1] / l, dp[2] / l];
        let (xq, jq) = newton(self.sys, xh, None, Some((dir, ph)), self.eps())?;
        if !(jq.gap(k) <= 0.1 * self.tol) {
            return None;
        }
        let (tx, tp) = oriented(tangent(&jq, k), &dir)?;
        let f = [scale[0], scale[0], scale[1], scale[1]];
        let mut d2: f64 = (0..3).map(|i| (jq.p[i] - ph[i]).powi(2)).sum();
        for i in 0..k {
            d2 += (f[i] * (xq[i] - xh[i])).powi(2);
        }
        Some((
            Node {
                x: xq,
                p: jq.p,
                tx,
                tp,
            },
            d2.sqrt(),
        ))
    }

    /// The points of the cubic Hermite interpolant of `a` and `b` (corrected points a quarter
    /// of a step apart) strictly between them, appended to `tr` (see [`March::fill`]; `base` the
    /// trail's length before the step, `todo` a scratch stack).
    fn fill_quarter(
        &self,
        a: &Node,
        b: &Node,
        (tr, base): (&mut Trail, usize),
        todo: &mut Vec<Sample>,
    ) -> Option<()> {
        let c = dist(&a.p, &b.p);
        if c == 0.0 {
            return Some(());
        }
        let turn = turn_angle(&a.tp, &b.tp);
        let len = c * arc_over_chord(turn);
        let want = (c * turn / (8.0 * CHORD_SHARE * self.tol))
            .sqrt()
            .ceil()
            .min(MAX_FILL as f64);
        // `want` is a whole number in [0, MAX_FILL]
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let m = (want as usize).max(1);
        let at = |u: f64| -> Option<Sample> {
            let (x, p, dx, dp) = hermite(a, b, len, u);
            let l = dot(&dp, &dp).sqrt();
            if !(l > 0.0) {
                return None;
            }
            let tx = std::array::from_fn(|i| dx[i] / l);
            Some((u, x, p, (tx, [dp[0] / l, dp[1] / l, dp[2] / l])))
        };
        // (u, unknowns, point, tangent) of the last point placed; the points still to place,
        // nearest last
        let mut last: Sample = (0.0, a.x, a.p, (a.tx, a.tp));
        todo.clear();
        for i in 1..=m {
            todo.push(if i == m {
                (1.0, b.x, b.p, (b.tx, b.tp))
            } else {
                at(i as f64 / m as f64)?
            });
            // place it, with points halfway in between while a chord's sagitta (cθ/8, θ the
            // turning of the cubic's tangents) exceeds its share of the tolerance
            while let Some(&next) = todo.last() {
                let th = turn_bound(&last.3 .1, &next.3 .1);
                if dist(&last.2, &next.2) * th / 8.0 <= CHORD_CHECK * self.tol {
                    todo.pop();
                    if next.0 < 1.0 {
                        tr.push(next.1, next.2, Some(next.3));
                    }
                    last = next;
                    continue;
                }
                if tr.len() - base + todo.len() > MAX_FILL || !(next.0 - last.0 > 1e-9) {
                    return None;
                }
                todo.push(at(0.5 * (last.0 + next.0))?);
            }
        }
        Some(())
    }

    /// Whether a point reached on a side continues the branch as a step of the marching
    /// would: turned by at most [`MAX_TURN`], its chord within the tolerance (`hθ/8`).
    fn turn_ok(&self, tp: &[f64; 3], jn: &Jet, k: usize, step: f64) -> bool {
        if step == 0.0 {
            return true;
        }
        tangent(jn, k).is_none_or(|(_, t)| {
            let turn = dot(&t, tp).abs().clamp(-1.0, 1.0).acos();
            turn <= MAX_TURN && step * turn / 8.0 <= self.tol
        })
    }

    /// The end of a walk that ran into a tangency (the sine of the normals' angle falling to
    /// [`SIN_STOP`], or steps halved to nothing): the sine, about linear in arc length through
    /// the contact, is extrapolated to zero from its last two values and the point there
    /// corrected onto the section (free Newton); it is appended when it lies ahead within that
    /// distance.
    fn end_tangent(
        &self,
        tr: &mut Trail,
        tx: &[f64; K],
        (prev_sin, prev_p): (f64, &[f64; 3]),
        jet: &Jet,
    ) -> Stop {
        let k = self.sys.k();
        let n = tr.len();
        if n >= 2 && prev_sin > jet.sin {
            let h = dist(&tr.ps[n - 1], prev_p);
            let s = jet.sin * h / (prev_sin - jet.sin);
            if s.is_finite() && s <= 4.0 * h + self.tol {
                let mut xe = tr.xs[n - 1];
                for c in 0..k {
                    xe[c] += s * tx[c];
                }
                if let Some((xq, jq)) = newton(self.sys, xe, None, None, self.eps()) {
                    if jq.gap(k) <= 0.1 * self.tol
                        && dist(&jq.p, &tr.ps[n - 1]) <= 2.0 * s + self.tol
                    {
                        tr.push(xq, jq.p, None);
                    }
                }
            }
        }
        Stop::Tangent
    }
}

/// An upper bound of the angle `θ` between the unit vectors `a` and `b`, tight to `δ⁵` for
/// small angles, without a call to `acos`: with `δ = |a − b| = 2 sin(θ/2)`,
/// `θ = 2 asin(δ/2) ≤ δ + δ³/(24(1 − δ²/4))` (the Maclaurin coefficients of `asin` after the
/// first are at most 1/6), and `2 asin(δ/2)` itself from `δ = 1/2` on.
pub(super) fn turn_bound(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    let d = dist(a, b);
    if d < 0.5 {
        d + d * d * d / (24.0 * (1.0 - 0.25 * d * d))
    } else {
        2.0 * (0.5 * d).min(1.0).asin()
    }
}

/// The angle between the unit vectors `a` and `b` (as slices of at least three), from the
/// chord `δ = |a − b|`: `2 asin(δ/2)`, for small `δ` its Maclaurin series
/// `δ + δ³/24 + 3δ⁵/640 + 5δ⁷/7168` (relative error below `10⁻¹⁴` for `δ < 0.01`), accurate
/// where `acos` of the dot product loses half the digits.
pub(super) fn turn_angle(a: &[f64], b: &[f64]) -> f64 {
    let d = (0..3)
        .map(|c| (a[c] - b[c]) * (a[c] - b[c]))
        .sum::<f64>()
        .sqrt();
    if d < 0.01 {
        let d2 = d * d;
        d * (1.0 + d2 * (1.0 / 24.0 + d2 * (3.0 / 640.0 + d2 * 5.0 / 7168.0)))
    } else {
        2.0 * (0.5 * d).min(1.0).asin()
    }
}

/// The ratio of arc to chord of a circular arc turning by `theta`: `(θ/2)/sin(θ/2)`
/// (for `θ < 0.01` its Maclaurin series `1 + θ²/24 + 7θ⁴/5760 + 31θ⁶/967680`, exact to
/// rounding there, where the quotient loses digits and costs a call to `sin`).
pub(super) fn arc_over_chord(theta: f64) -> f64 {
    if theta < 1e-2 {
        let t2 = theta * theta;
        1.0 + t2 * (1.0 / 24.0 + t2 * (7.0 / 5760.0 + t2 * 31.0 / 967_680.0))
    } else {
        (0.5 * theta) / (0.5 * theta).sin()
    }
}

/// The length of the cubic Hermite step from `a` to `b`: the chord lengthened to the arc of a
/// circle turning by the angle between their tangents.
fn step_length(a: &Node, b: &Node) -> f64 {
    let turn = turn_angle(&a.tp, &b.tp);
    dist(&a.p, &b.p) * arc_over_chord(turn)
}

/// The cubic Hermite interpolant of `a` and `b` (ends and unit tangents, the tangents scaled by
/// the step's length `len`) at `u` in `[0, 1]`: the unknowns, the point, and their derivatives
/// in `u` (the Hermite basis, de Boor, *A Practical Guide to Splines*, ch. IV).
fn hermite(a: &Node, b: &Node, len: f64, u: f64) -> ([f64; K], [f64; 3], [f64; K], [f64; 3]) {
    let (u2, u3) = (u * u, u * u * u);
    let (h00, h10) = (2.0 * u3 - 3.0 * u2 + 1.0, u3 - 2.0 * u2 + u);
    let (h01, h11) = (3.0 * u2 - 2.0 * u3, u3 - u2);
    let (d00, d10) = (6.0 * u2 - 6.0 * u, 3.0 * u2 - 4.0 * u + 1.0);
    let (d01, d11) = (6.0 * u - 6.0 * u2, 3.0 * u2 - 2.0 * u);
    let x = std::array::from_fn(|i| {
        h00 * a.x[i] + h01 * b.x[i] + len * (h10 * a.tx[i] + h11 * b.tx[i])
    });
    let dx = std::array::from_fn(|i| {
        d00 * a.x[i] + d01 * b.x[i] + len * (d10 * a.tx[i] + d11 * b.tx[i])
    });
    let p = std::array::from_fn(|i| {
        h00 * a.p[i] + h01 * b.p[i] + len * (h10 * a.tp[i] + h11 * b.tp[i])
    });
    let dp = std::array::from_fn(|i| {
        d00 * a.p[i] + d01 * b.p[i] + len * (d10 * a.tp[i] + d11 * b.tp[i])
    });
    (x, p, dx, dp)
}
