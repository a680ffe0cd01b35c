//! Pcurves by projection (`docs/theory/topology.md`, "Pcurves by projection"): the curve of an
//! edge in its face's `(u, v)` when the file gives only the 3-D curve. The edge is sampled
//! adaptively, each sample projected onto the surface (Newton's method for the foot point,
//! Piegl & Tiller, *The NURBS Book*, 2nd ed., §6.1, warm-started from the previous sample so
//! the projection follows the edge, with the global closest-point query as the fallback; Hu &
//! Wallner, "A second order algorithm for orthogonal projection onto curves and surfaces",
//! CAGD 22 (2005) 251–260), and the projected parameters joined into a degree-1 B-spline,
//! unwrapped across the seams of closed surfaces and kept continuous through poles.

use super::face::{Edge, Face, Loop, LOOP_CLOSURE_RTOL};
use crate::error::readable;
use crate::query::QuerySurface;
use crate::{Arg, BSplineCurve, Curve, Error, Points, Result, Surface, What};

/// Samples per knot span of an edge's curve before bisection.
const START_SAMPLES_PER_SPAN: usize = 4;
/// Most bisections of one segment of an edge.
const MAX_DEPTH: u32 = 24;
/// Most points of one projected pcurve.
pub const MAX_PCURVE_POINTS: usize = 1 << 16;
/// The coarsest sampling of a projected pcurve, relative to the face's model size: a pcurve is
/// geometry, not a mesh, and a loop sampled at a mesh tolerance near the face's own size has too
/// few points to enclose its region in `(u, v)` (a circle of three points), which left such faces
/// without triangles. The mesher samples the pcurves again at its own tolerance.
pub const PCURVE_SAMPLING_RTOL: f64 = 1e-3;
/// Points along each side of a surface compared for closure and poles.
const SIDE_SAMPLES: usize = 17;
/// Most Newton steps of one warm-started projection.
const NEWTON_STEPS: usize = 16;
/// A loop's step along a pole within this fraction of a period of whole periods is no run
/// along the pole (the loop leaves the pole where it arrived).
const POLE_RUN_RTOL: f64 = 1e-9;

/// How the sides of a surface meet, within a tolerance: the periods of the directions in
/// which it closes (`S(u₀, v) = S(u₁, v)` for every `v`, a cylinder's seam) and the sides that
/// collapse to a point (poles, a cone's apex), both tested at [`SIDE_SAMPLES`] points per
/// side.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfaceClosure {
    /// `Some(u₁ − u₀)` when the surface closes in `u`, and likewise in `v`.
    pub period: [Option<f64>; 2],
    /// The sides `u = u₀`, `u = u₁`, `v = v₀`, `v = v₁` that are one point.
    pub pole: [bool; 4],
}

impl SurfaceClosure {
    /// The closure of `surface` within the distance `tol`.
    ///
    /// # Errors
    /// As [`Surface::eval`] (not expected on the surface's own domain).
    pub fn of(surface: &Surface, tol: f64) -> Result<Self> {
        let ((u0, u1), (v0, v1)) = surface.domain();
        #[allow(clippy::cast_precision_loss)] // a small count
        let at = |a: f64, b: f64, k: usize| {
            // `a + (b − a)·1` may round past `b`
            (a + (b - a) * k as f64 / (SIDE_SAMPLES - 1) as f64).clamp(a, b)
        };
        let side = |fixed_u: Option<f64>, fixed_v: Option<f64>| -> Result<Vec<Vec<f64>>> {
            (0..SIDE_SAMPLES)
                .map(|k| match (fixed_u, fixed_v) {
                    (Some(u), _) => surface.eval(u, at(v0, v1, k)),
                    (_, Some(v)) => surface.eval(at(u0, u1, k), v),
                    _ => unreachable!("one parameter is fixed"),
                })
                .collect()
        };
        let sides = [
            side(Some(u0), None)?,
            side(Some(u1), None)?,
            side(None, Some(v0))?,
            side(None, Some(v1))?,
        ];
        let same = |a: &[Vec<f64>], b: &[Vec<f64>]| a.iter().zip(b).all(|(p, q)| dist(p, q) <= tol);
        let point = |a: &[Vec<f64>]| a.iter().all(|p| dist(p, &a[0]) <= tol);
        let period = [
            (u1 > u0 && same(&sides[0], &sides[1])).then_some(u1 - u0),
            (v1 > v0 && same(&sides[2], &sides[3])).then_some(v1 - v0),
        ];
        let pole = [
            point(&sides[0]),
            point(&sides[1]),
            point(&sides[2]),
            point(&sides[3]),
        ];
        Ok(SurfaceClosure { period, pole })
    }

    /// `uv` brought into the surface's domain: by whole periods in a closed direction, to the
    /// nearest bound in the other.
    #[must_use]
    pub fn wrap(&self, domain: ((f64, f64), (f64, f64)), uv: [f64; 2]) -> [f64; 2] {
        let dom = [domain.0, domain.1];
        let mut out = uv;
        for d in 0..2 {
            let (a, b) = dom[d];
            if let Some(p) = self.period[d] {
                if out[d] < a || out[d] > b {
                    out[d] = a + (out[d] - a).rem_euclid(p);
                }
            }
            out[d] = out[d].clamp(a, b);
        }
        out
    }
}

/// The projection of the points of one face's edges onto its surface.
struct Projector<'a> {
    surface: &'a Surface,
    query: QuerySurface,
    domain: ((f64, f64), (f64, f64)),
    closure: SurfaceClosure,
    /// Each pole's point and the parameter (0 = `u`, 1 = `v`) free along it.
    poles: Vec<(Vec<f64>, usize)>,
    /// Accuracy of the pcurves: the surface at the pcurve within this of the projected edge.
    tol: f64,
    /// Largest distance of an edge from the surface.
    on_surface: f64,
}

/// One projected sample: the curve's parameter, `(u, v)` (unwrapped) and whether it is at a
/// pole (its free parameter taken from its neighbours).
#[derive(Debug, Clone, Copy)]
struct Sample {
    t: f64,
    uv: [f64; 2],
    pole: Option<usize>,
}

impl<'a> Projector<'a> {
    fn new(surface: &'a Surface, tol: f64, on_surface: f64) -> Result<Self> {
        let closure = SurfaceClosure::of(surface, tol)?;
        let domain = surface.domain();
        let ((u0, u1), (v0, v1)) = domain;
        let mut poles = Vec::new();
        for (k, &p) in closure.pole.iter().enumerate() {
            if p {
                let (at, free) = match k {
                    0 => ((u0, v0), 1),
                    1 => ((u1, v0), 1),
                    2 => ((u0, v0), 0),
                    _ => ((u0, v1), 0),
                };
                poles.push((surface.eval(at.0, at.1)?, free));
            }
        }
        Ok(Projector {
            surface,
            query: surface.to_query()?,
            domain,
            closure,
            poles,
            tol,
            on_surface,
        })
    }

    fn eval(&self, uv: [f64; 2]) -> Result<Vec<f64>> {
        let w = self.closure.wrap(self.domain, uv);
        self.surface.eval(w[0], w[1])
    }

    /// Newton's method for the foot point, `(S − x)·S_u = (S − x)·S_v = 0` (P&T §6.1), from
    /// `start`, in unwrapped parameters in a closed direction and clamped to the domain in the
    /// other; a step that does not bring the surface closer is halved (at most 4 times).
    /// Returns the parameters and the distance.
    fn newton(&self, x: &[f64], start: [f64; 2]) -> Result<([f64; 2], f64)> {
        let ((u0, u1), (v0, v1)) = self.domain;
        let dom = [(u0, u1), (v0, v1)];
        let keep = |uv: [f64; 2]| -> [f64; 2] {
            let mut o = uv;
            for d in 0..2 {
                if self.closure.period[d].is_none() {
                    o[d] = o[d].clamp(dom[d].0, dom[d].1);
                }
            }
            o
        };
        let mut uv = keep(start);
        let mut d = dist(&self.eval(uv)?, x);
        let dim = self.surface.dim();
        for _ in 0..NEWTON_STEPS {
            let w = self.closure.wrap(self.domain, uv);
            let der = self.surface.eval_derivatives(w[0], w[1], 2)?;
            // the table of S_{u^k v^l} at k·3 + l
            let (s, sv, svv, su, suv, suu) = (
                der.point(0),
                der.point(1),
                der.point(2),
                der.point(3),
                der.point(4),
                der.point(6),
            );
            let r: Vec<f64> = (0..dim).map(|i| s[i] - x[i]).collect();
            let f = dot(&r, su);
            let g = dot(&r, sv);
            let a = dot(su, su) + dot(&r, suu);
            let b = dot(su, sv) + dot(&r, suv);
            let c = dot(sv, sv) + dot(&r, svv);
            let det = a * c - b * b;
            let (du, dv) = if det > 0.0 && a > 0.0 {
                ((c * f - b * g) / det, (a * g - b * f) / det)
            } else {
                (
                    f / dot(su, su).max(f64::MIN_POSITIVE),
                    g / dot(sv, sv).max(f64::MIN_POSITIVE),
                )
            };
            if !(du.is_finite() && dv.is_finite()) {
                break;
            }
            let mut step = 1.0;
            let mut moved = false;
            for _ in 0..5 {
                let next = keep([uv[0] - step * du, uv[1] - step * dv]);
                let dn = dist(&self.eval(next)?, x);
                if dn <= d {
                    let change = (next[0] - uv[0]).abs() / (u1 - u0).max(f64::MIN_POSITIVE)
                        + (next[1] - uv[1]).abs() / (v1 - v0).max(f64::MIN_POSITIVE);
                    uv = next;
                    d = dn;
                    moved = change > 1e-15;
                    break;
                }
                step *= 0.5;
            }
            if !moved {
                break;
            }
        }
        Ok((uv, d))
    }

    /// The foot of `x` on the surface near `warm` (Newton from there, accepted within
    /// `on_surface`), else the closest point of the whole surface; either way its closed
    /// parameters moved by whole periods to the copy nearest `warm`. A point at a pole takes its free parameter
    /// from `warm`.
    fn project(&self, x: &[f64], warm: Option<[f64; 2]>) -> Result<([f64; 2], f64, Option<usize>)> {
        let mut found = None;
        if let Some(w) = warm {
            let (uv, d) = self.newton(x, w)?;
            if d <= self.on_surface {
                found = Some((uv, d));
            }
        }
        let (mut uv, d) = match found {
            Some(f) => f,
            None => {
                let p = self.query.project(x)?;
                ([p.uv.0, p.uv.1], p.distance)
            }
        };
        // the copy nearest `warm`: Newton's steps are not bounded in a closed direction, and a
        // step that overshoots by whole periods still brings the surface closer (a torus's
        // tube, where the Hessian is near singular), landing on the foot point in another copy
        if let Some(w) = warm {
            for k in 0..2 {
                if let Some(per) = self.closure.period[k] {
                    uv[k] += per * ((w[k] - uv[k]) / per).round();
                }
            }
        }
        let foot = self.eval(uv)?;
        let pole = self
            .poles
            .iter()
            .find(|(p, _)| dist(p, &foot) <= self.tol)
            .map(|&(_, free)| free);
        if let (Some(free), Some(w)) = (pole, warm) {
            uv[free] = w[free];
        }
        Ok((uv, d, pole))
    }

    /// The samples of `curve` projected, from `warm` (the previous edge's end in the loop):
    /// [`START_SAMPLES_PER_SPAN`] per knot span, a segment halved while the surface at the
    /// middle of its `(u, v)` chord is farther than `tol` from the projection of the curve's
    /// middle. `which` names the edge in errors.
    fn edge(
        &self,
        curve: &Curve,
        warm: Option<[f64; 2]>,
        which: &dyn Fn() -> String,
    ) -> Result<Vec<Sample>> {
        let (a, b) = curve.domain();
        let spans = curve.knots().distinct().len().saturating_sub(1).max(1);
        let n0 = spans.saturating_mul(START_SAMPLES_PER_SPAN).max(2);
        if n0 > MAX_PCURVE_POINTS {
            return Err(Error::TooLarge {
                what: "points of a projected pcurve".into(),
                size: n0,
                max: MAX_PCURVE_POINTS,
            });
        }
        let far = |t: f64, d: f64| {
            Error::InvalidArgument {
            what: "face edge".into(),
            reason: format!(
                "{} does not lie on the face's surface: its point at t = {t} is {d:.3e} from it (tolerance {:.3e}); the edge belongs to another surface, or the model was sewn with a larger tolerance",
                which(),
                self.on_surface, t = readable(&t)),
        }
        };
        let at = |s: f64| (a + (b - a) * s).clamp(a, b);
        let point = |t: f64, warm: Option<[f64; 2]>| -> Result<([f64; 2], Option<usize>)> {
            let x = curve.eval(t)?;
            let (uv, d, pole) = self.project(&x, warm)?;
            if d.is_nan() || d > self.on_surface {
                return Err(far(t, d));
            }
            Ok((uv, pole))
        };
        let (uv, pole) = point(a, warm)?;
        let mut out = vec![Sample { t: a, uv, pole }];
        #[allow(clippy::cast_precision_loss)] // counts below MAX_PCURVE_POINTS
        for k in 0..n0 {
            let mut stack = vec![(at((k + 1) as f64 / n0 as f64), 0u32)];
            while let Some(&(t, depth)) = stack.last() {
                let last = out[out.len() - 1];
                let (uv, pole) = point(t, Some(last.uv))?;
                let tm = 0.5 * (last.t + t);
                if depth < MAX_DEPTH && tm > last.t && tm < t {
                    let (um, _) = point(tm, Some(last.uv))?;
                    let chord = [0.5 * (last.uv[0] + uv[0]), 0.5 * (last.uv[1] + uv[1])];
                    if dist(&self.eval(chord)?, &self.eval(um)?) > self.tol {
                        stack.push((tm, depth + 1));
                        continue;
                    }
                }
                stack.pop();
                out.push(Sample { t, uv, pole });
                if out.len() > MAX_PCURVE_POINTS {
                    return Err(Error::TooLarge {
                        what: What::of(
                            Arg::Tolerance,
                            "points of a projected pcurve (make the tolerance larger)",
                        ),
                        size: out.len(),
                        max: MAX_PCURVE_POINTS,
                    });
                }
            }
        }
        fill_poles(&mut out);
        Ok(out)
    }
}

/// A run of samples at a pole takes its free parameter from the sample before it, or, at the
/// start of the edge, from the first sample after it that is not at a pole.
fn fill_poles(s: &mut [Sample]) {
    let Some(first) = s.iter().position(|x| x.pole.is_none()) else {
        return;
    };
    for k in 0..first {
        if let Some(free) = s[k].pole {
            s[k].uv[free] = s[first].uv[free];
        }
    }
}

/// An edge's pcurve while its loop is made: given by the file, or projected samples.
enum Made {
    Given(Curve),
    Projected(Vec<Sample>),
}

impl Made {
    fn ends(&self) -> Result<([f64; 2], [f64; 2])> {
        match self {
            Made::Given(c) => {
                let (a, b) = c.domain();
                let (p, q) = (c.eval(a)?, c.eval(b)?);
                Ok(([p[0], p[1]], [q[0], q[1]]))
            }
            Made::Projected(s) => Ok((s[0].uv, s[s.len() - 1].uv)),
        }
    }

    fn shift(&mut self, by: [f64; 2]) {
        if let Made::Projected(s) = self {
            for x in s {
                x.uv[0] += by[0];
                x.uv[1] += by[1];
            }
        }
    }

    fn curve(self) -> Result<Curve> {
        match self {
            Made::Given(c) => Ok(c),
            Made::Projected(s) => {
                let mut knots = Vec::with_capacity(s.len() + 2);
                knots.push(s[0].t);
                knots.extend(s.iter().map(|x| x.t));
                knots.push(s[s.len() - 1].t);
                let pts: Vec<[f64; 2]> = s.iter().map(|x| x.uv).collect();
                Ok(Curve::from(BSplineCurve::new(
                    1,
                    knots,
                    Points::from_2d(&pts)?,
                )?))
            }
        }
    }
}

impl Face {
    /// The face with a pcurve for every edge: an edge given without one gets the projection
    /// of its 3-D curve onto the surface (`docs/theory/topology.md`, "Pcurves by projection";
    /// Piegl & Tiller §6.1 for the foot points), a degree-1 B-spline over the curve's own
    /// parameters whose image on the surface is within `tolerance` of the projected edge (and
    /// within [`PCURVE_SAMPLING_RTOL`] times the model size, for a coarse `tolerance`).
    /// Each sample's projection starts from the previous one's `(u, v)`, so the pcurve follows
    /// the edge; across the seam of a closed surface the parameters are unwrapped by the
    /// period (so a pcurve may leave the domain by whole periods, as
    /// [`SurfaceClosure::wrap`] brings back), a sample at a pole takes its free parameter from
    /// its neighbours, each edge starts where the one before ends in the loop, and an inner
    /// loop is moved by whole periods next to the outer one. Edges with a pcurve keep it.
    ///
    /// An edge may lie off the surface by `max(tolerance, LOOP_CLOSURE_RTOL · model size)`
    /// (a sewing gap of the file, [`LOOP_CLOSURE_RTOL`]).
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for a `tolerance` that is not positive and finite; (`what`
    /// "face edge") naming the loop, the edge, the parameter and the distance when an edge is
    /// farther from the surface; (`what` "face loop") when a loop goes round a closed surface
    /// more than once (a loop going round once, of a band or a cap without a seam edge, is
    /// kept: its end a period from its start, and the mesher cuts the face along a seam);
    /// [`Error::TooLarge`] when a
    /// pcurve would have more than [`MAX_PCURVE_POINTS`] points.
    pub fn with_projected_pcurves(&self, tolerance: f64) -> Result<Face> {
        if !(tolerance.is_finite() && tolerance > 0.0) {
            return Err(Error::InvalidArgument {
                what: What::of(Arg::Tolerance, "pcurve tolerance"),
                reason: format!(
                    "{tolerance} must be finite and positive",
                    tolerance = readable(&tolerance)
                ),
            });
        }
        if self.has_pcurves() {
            return Ok(self.clone());
        }
        let size = self.model_size();
        let on_surface = tolerance.max(LOOP_CLOSURE_RTOL * size);
        let sampling = tolerance.min(PCURVE_SAMPLING_RTOL * size);
        let proj = Projector::new(self.surface(), sampling, on_surface)?;
        let mut loops: Vec<Vec<Made>> = Vec::new();
        for (li, lp) in self.loops().enumerate() {
            loops.push(project_loop(&proj, lp, li, self.same_sense())?);
        }
        // the outer loop about the domain, each inner loop by whole periods next to it
        let ((u0, u1), (v0, v1)) = self.surface().domain();
        let centre = |m: &[Made]| -> Result<[f64; 2]> {
            let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
            for e in m {
                let (a, b) = e.ends()?;
                for p in [a, b] {
                    for d in 0..2 {
                        lo[d] = lo[d].min(p[d]);
                        hi[d] = hi[d].max(p[d]);
                    }
                }
            }
            Ok([0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1])])
        };
        let mut target = [0.5 * (u0 + u1), 0.5 * (v0 + v1)];
        for (li, m) in loops.iter_mut().enumerate() {
            if m.iter().any(|e| matches!(e, Made::Given(_))) {
                if li == 0 {
                    target = centre(m)?;
                }
                continue;
            }
            let c = centre(m)?;
            let mut by = [0.0; 2];
            for d in 0..2 {
                if let Some(p) = proj.closure.period[d] {
                    by[d] = p * ((target[d] - c[d]) / p).round();
                }
            }
            for e in m.iter_mut() {
                e.shift(by);
            }
            if li == 0 {
                target = [c[0] + by[0], c[1] + by[1]];
            }
        }
        let mut made = loops.into_iter();
        let mk = |m: Vec<Made>, lp: &Loop| -> Result<Loop> {
            let edges = m
                .into_iter()
                .zip(lp.edges())
                .map(|(p, e)| Edge::new(e.curve().clone(), Some(p.curve()?)))
                .collect::<Result<Vec<_>>>()?;
            Loop::new(edges)
        };
        let outer = mk(made.next().unwrap_or_default(), self.outer())?;
        let inner = made
            .zip(self.inner())
            .map(|(m, lp)| mk(m, lp))
            .collect::<Result<Vec<_>>>()?;
        Ok(Face::from_parts(
            self.surface().clone(),
            outer,
            inner,
            self.same_sense(),
        ))
    }
}

/// The pcurves of one loop: from its first edge with a pcurve (or its first edge), each
/// missing one projected starting from the end of the one before; the loop must close in the
/// closed directions (not go round the surface). `left`: the face is on the left of the loop in
/// `(u, v)` (its normal is the surface's, `same_sense`), which decides the runs along poles
/// ([`orient_pole_runs`]).
fn project_loop(proj: &Projector<'_>, lp: &Loop, li: usize, left: bool) -> Result<Vec<Made>> {
    let n = lp.edges().len();
    let start = lp
        .edges()
        .iter()
        .position(|e| e.pcurve().is_some())
        .unwrap_or(0);
    let mut made: Vec<Option<Made>> = (0..n).map(|_| None).collect();
    let mut prev: Option<[f64; 2]> = None;
    let name = |k: usize| {
        if li == 0 {
            format!("edge {k} of the outer loop")
        } else {
            format!("edge {k} of inner loop {li}")
        }
    };
    for j in 0..n {
        let k = (start + j) % n;
        let e = &lp.edges()[k];
        let m = match e.pcurve() {
            Some(p) => Made::Given(p.clone()),
            None => Made::Projected(proj.edge(e.curve(), prev, &|| name(k))?),
        };
        prev = Some(m.ends()?.1);
        made[k] = Some(m);
    }
    let mut made: Vec<Made> = made.into_iter().flatten().collect();
    let first = made[start].ends()?.0;
    let last = made[(start + n - 1) % n].ends()?.1;
    // a loop through a pole (a cone's apex) may go round the surface there, where the pole's
    // free parameter changes along a side that is one point: the edges from the first one
    // leaving a pole to the loop's end move back by the whole periods the loop went round
    let leaves_pole = (1..n)
        .map(|j| (start + j) % n)
        .find(|&k| matches!(&made[k], Made::Projected(s) if s[0].pole.is_some()));
    let mut turns = [0.0; 2];
    for d in 0..2 {
        if let Some(p) = proj.closure.period[d] {
            turns[d] = p * ((last[d] - first[d]) / p).round();
        }
    }
    if let (Some(k0), true) = (leaves_pole, turns != [0.0; 2]) {
        let j0 = (k0 + n - start) % n;
        for j in j0..n {
            made[(start + j) % n].shift([-turns[0], -turns[1]]);
        }
    }
    orient_pole_runs(proj, &mut made, start, left)?;
    // a loop going once round (a band's, a cap's) is cut along a seam by the mesher; more
    // than once, it does not bound a face
    let last = made[(start + n - 1) % n].ends()?.1;
    for d in 0..2 {
        if let Some(p) = proj.closure.period[d] {
            let times = ((last[d] - first[d]) / p).round().abs();
            if times >= 2.0 {
                let which = if li == 0 {
                    "the outer loop".to_string()
                } else {
                    format!("inner loop {li}")
                };
                return Err(Error::InvalidArgument {
                    what: "face loop".into(),
                    reason: format!(
                        "{which} goes round the closed surface in {} {times} times; a loop of a face goes round it at most once (a band or a cap, cut along a seam to be meshed)",
                        if d == 0 { "u" } else { "v" }
                    ),
                });
            }
        }
    }
    Ok(made)
}

/// The runs of a loop along poles turned to the face's side: a loop reaching a pole by one edge
/// and leaving it by the next runs along the pole, one point in space, from the free parameter
/// it arrives at to the one it leaves at; in a closed free direction that run may go either
/// way round, a period apart, and each way bounds another region of `(u, v)` (a half sphere
/// bounded by two meridians through both poles is either half). The face is on the left of its
/// loops (ISO 10303-42 `face_bound`, seen from the face's normal), so along the pole
/// `v = v₀` (the domain above it) the run goes towards `+u` when the face's normal is the
/// surface's (`left`), and within one period; likewise `−u` along `v = v₁`, `−v` along
/// `u = u₀`, `+v` along `u = u₁`, each reversed when not `left`. Each run but the one closing
/// the loop is set so by moving the edges after it by whole periods; the runs are kept as
/// projected when the loop then does not close with a run of its own sense (a loop's
/// orientation reversed in the file) or not in the same place, or when an edge has a pcurve of
/// the file (which no period moves).
fn orient_pole_runs(
    proj: &Projector<'_>,
    made: &mut [Made],
    start: usize,
    left: bool,
) -> Result<()> {
    let n = made.len();
    if made.iter().any(|m| matches!(m, Made::Given(_))) {
        return Ok(());
    }
    let ((u0, u1), (v0, v1)) = proj.domain;
    let bounds = [(u0, u1), (v0, v1)];
    // the run into edge k: (free parameter, its signed step, the period) when edge k starts
    // at a pole and the free direction closes
    let run = |made: &[Made], k: usize| -> Result<Option<(usize, f64, f64)>> {
        let Made::Projected(s) = &made[k] else {
            return Ok(None);
        };
        let Some(free) = s[0].pole else {
            return Ok(None);
        };
        let Some(period) = proj.closure.period[free] else {
            return Ok(None);
        };
        let fixed = 1 - free;
        let (lo, hi) = bounds[fixed];
        let at = proj.closure.wrap(proj.domain, s[0].uv)[fixed];
        let low_side = (at - lo).abs() <= (at - hi).abs();
        // the domain's side of the pole is on the left of a run towards +free along the
        // low side of v (free u) or the high side of u (free v)
        let plus = low_side == (free == 0);
        let sense = if plus == left { 1.0 } else { -1.0 };
        let from = made[(k + n - 1) % n].ends()?.1[free];
        let to = s[0].uv[free];
        let step = to - from;
        // within rounding of whole periods, the loop leaves where it arrives: no run to turn
        let r = (sense * step).rem_euclid(period);
        if r <= POLE_RUN_RTOL * period || r >= (1.0 - POLE_RUN_RTOL) * period {
            return Ok(Some((free, 0.0, period)));
        }
        Ok(Some((free, sense * r - step, period)))
    };
    let before: Vec<[f64; 2]> = made
        .iter()
        .map(|m| m.ends().map(|e| e.0))
        .collect::<Result<_>>()?;
    let turns_of = |made: &[Made]| -> Result<[f64; 2]> {
        let first = made[start].ends()?.0;
        let last = made[(start + n - 1) % n].ends()?.1;
        Ok([0, 1]
            .map(|d| proj.closure.period[d].map_or(0.0, |p| ((last[d] - first[d]) / p).round())))
    };
    let turns = turns_of(made)?;
    let mut moved = false;
    for j in 1..n {
        let k = (start + j) % n;
        if let Some((free, by, period)) = run(made, k)? {
            // no run (the loop leaves where it arrives, by whole periods) is left as it is
            let rest = (by / period).round();
            if rest != 0.0 {
                let mut shift = [0.0; 2];
                shift[free] = rest * period;
                for i in j..n {
                    made[(start + i) % n].shift(shift);
                }
                moved = true;
            }
        }
    }
    if !moved {
        return Ok(());
    }
    // the loop must close as it did: by its own run at a pole where it starts at one, else
    // with the same turns
    let closes = match run(made, start)? {
        Some((_, by, period)) => (by / period).round() == 0.0,
        None => turns_of(made)? == turns,
    };
    if !closes {
        for (m, b) in made.iter_mut().zip(&before) {
            let now = m.ends()?.0;
            m.shift([b[0] - now[0], b[1] - now[1]]);
        }
    }
    Ok(())
}

fn dist(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y) * (x - y))
        .sum::<f64>()
        .sqrt()
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

#[cfg(test)]
#[path = "pcurve_tests.rs"]
mod tests;
