//! Marching along a branch of a section (`docs/theory/queries.md#marching`): predictor along the
//! tangent, Newton corrector on the plane through the predicted point orthogonal to the tangent,
//! step length from the turning of the tangent, stops at the sides of the parameter box, at a
//! tangency of the surfaces or where the branch closes (Barnhill and Kersey 1990).

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

/// A traced branch: unknowns and points, how each end stopped.
#[derive(Debug, Clone)]
pub(super) struct Traced {
    pub(super) xs: Vec<[f64; K]>,
    pub(super) ps: Vec<[f64; 3]>,
    pub(super) stops: [Stop; 2],
}

/// The marching's settings: tolerance, scale.
pub(super) struct March<'a> {
    pub(super) sys: &'a dyn System,
    pub(super) tol: f64,
    pub(super) scale: f64,
}

impl March<'_> {
    /// Residual to which points are corrected: a thousandth of the tolerance, at least the
    /// rounding of the scale.
    pub(super) fn eps(&self) -> f64 {
        (1e-3 * self.tol).max(1e-14 * self.scale)
    }

    /// The branch through the point `x0` (on the section): marched forwards; unless that closes
    /// it, marched backwards from `x0` too and the two joined.
    pub(super) fn branch(&self, x0: [f64; K], j0: &Jet) -> Result<Traced> {
        let (fx, fp, fstop) = self.walk(x0, j0, 1.0)?;
        if fstop == Stop::Closed {
            return Ok(Traced {
                xs: fx,
                ps: fp,
                stops: [Stop::Closed, Stop::Closed],
            });
        }
        let (mut bx, mut bp, bstop) = self.walk(x0, j0, -1.0)?;
        bx.reverse();
        bp.reverse();
        bx.pop();
        bp.pop();
        bx.extend(fx);
        bp.extend(fp);
        if bx.len() > MAX_BRANCH_POINTS {
            return Err(Error::TooLarge {
                what: "points of an intersection branch",
                size: bx.len(),
                max: MAX_BRANCH_POINTS,
            });
        }
        Ok(Traced {
            xs: bx,
            ps: bp,
            stops: [bstop, fstop],
        })
    }

    /// One direction of marching from `x0` (`sign` ±1 along the tangent), `x0` first.
    #[allow(clippy::type_complexity)]
    fn walk(
        &self,
        x0: [f64; K],
        j0: &Jet,
        sign: f64,
    ) -> Result<(Vec<[f64; K]>, Vec<[f64; 3]>, Stop)> {
        let k = self.sys.k();
        let bounds = self.sys.bounds();
        let mut xs = vec![x0];
        let mut ps = vec![j0.p];
        let Some((mut tx, mut tp)) = tangent(j0, k) else {
            return Ok((xs, ps, Stop::Tangent));
        };
        for i in 0..K {
            tx[i] *= sign;
        }
        for c in &mut tp {
            *c *= sign;
        }
        let (hmax, hmin) = (MAX_STEP * self.scale, MIN_STEP * self.scale);
        let mut h = hmax;
        let (mut x, mut jet) = (x0, j0.clone());
        let mut prev_sin = jet.sin;
        loop {
            if xs.len() > MAX_BRANCH_POINTS {
                return Err(Error::TooLarge {
                    what: "points of an intersection branch",
                    size: xs.len(),
                    max: MAX_BRANCH_POINTS,
                });
            }
            if h < hmin {
                let stop = self.end_tangent(&mut xs, &mut ps, &tx, prev_sin, &jet);
                return Ok((xs, ps, stop));
            }
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
                    return Ok((xs, ps, Stop::Boundary));
                }
                let mut xp = x;
                for c in 0..k {
                    xp[c] += frac * h * tx[c];
                }
                xp[i] = l;
                match newton(self.sys, xp, Some(i), None, self.eps()) {
                    Some((xn, jn))
                        if jn.gap(k) <= 0.1 * self.tol
                            && self.turn_ok(&tp, &jn, k, dist(&jn.p, &jet.p)) =>
                    {
                        xs.push(xn);
                        ps.push(jn.p);
                        return Ok((xs, ps, Stop::Boundary));
                    }
                    _ => {
                        h *= 0.5;
                        continue;
                    }
                }
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
            // the chord of an arc turning by θ over length h deviates from it by ≈ hθ/8
            let sag = step * turn / 8.0;
            if turn > MAX_TURN || sag > self.tol {
                h *= 0.5;
                continue;
            }
            // closed: the start lies between the last point and this one
            if xs.len() >= 3 {
                let start = ps[0];
                let near =
                    segment_distance3(&start, &jet.p, &jn.p) <= 2.0 * self.tol + 1e-12 * self.scale;
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
                    xs[0][c] >= x[c].min(xn[c]) - slack && xs[0][c] <= x[c].max(xn[c]) + slack
                });
                if near && between && same {
                    xs.push(xs[0]);
                    ps.push(start);
                    return Ok((xs, ps, Stop::Closed));
                }
            }
            xs.push(xn);
            ps.push(jn.p);
            prev_sin = jet.sin;
            x = xn;
            jet = jn;
            tx = ntx;
            tp = ntp;
            if jet.sin < SIN_STOP {
                let stop = self.end_tangent(&mut xs, &mut ps, &tx, prev_sin, &jet);
                return Ok((xs, ps, stop));
            }
            // next step from the discrete curvature κ ≈ θ/h: sagitta h²κ/8 at the tolerance
            let grow = if turn > 0.0 {
                (8.0 * self.tol / (turn / step)).sqrt() / h
            } else {
                2.0
            };
            h = (h * grow.clamp(0.5, 2.0) * 0.9).clamp(hmin, hmax);
        }
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
        xs: &mut Vec<[f64; K]>,
        ps: &mut Vec<[f64; 3]>,
        tx: &[f64; K],
        prev_sin: f64,
        jet: &Jet,
    ) -> Stop {
        let k = self.sys.k();
        let n = ps.len();
        if n >= 2 && prev_sin > jet.sin {
            let h = dist(&ps[n - 1], &ps[n - 2]);
            let s = jet.sin * h / (prev_sin - jet.sin);
            if s.is_finite() && s <= 4.0 * h + self.tol {
                let mut xe = xs[n - 1];
                for c in 0..k {
                    xe[c] += s * tx[c];
                }
                if let Some((xq, jq)) = newton(self.sys, xe, None, None, self.eps()) {
                    if jq.gap(k) <= 0.1 * self.tol && dist(&jq.p, &ps[n - 1]) <= 2.0 * s + self.tol
                    {
                        xs.push(xq);
                        ps.push(jq.p);
                    }
                }
            }
        }
        Stop::Tangent
    }
}
