//! Curve–plane and curve–surface intersections (`docs/theory/queries.md#intersections`).

use super::super::pieces::{bern_roots, check_tolerance, dist, dot, Bern, QueryCurve};
use super::super::project::check_query;
use super::super::surface::{split_curve, QuerySurface};
use super::refine::order_from_growth;
use super::{
    boxes_overlap, Contact, PlaneIntersection, SurfaceIntersection, MAX_DEPTH, MAX_PAIRS,
    TOUCH_RTOL,
};

/// A curve–surface solution: the curve's parameter, the surface's `(u, v)`, the point and
/// whether the curve crosses the surface transversally there.
type SurfaceSolution = (f64, (f64, f64), Vec<f64>, bool);

/// Probe step (fraction of the curve's domain) of the transversality and overlap tests, as for
/// two curves.
const PROBE: f64 = 1e-6;
/// Farthest (as a fraction of the curve's domain) a contact's refinement may move it.
const REFINE_REACH: f64 = 1e-3;
use crate::error::{Error, Result};
use crate::numeric::damped::{levenberg_marquardt, Residual};
use crate::{Arg, What};

impl QueryCurve {
    /// Where the curve meets the plane (hyperplane) through `origin` with normal `normal`: the
    /// roots of the signed distance `f(s) = (C(s) − origin)·n`, whose Bernstein coefficients are
    /// those of the control points, so none is missed (`docs/theory/queries.md#intersections`).
    /// A piece whose coefficients all vanish (to `64·ε` of their magnitude) lies in the plane: it
    /// is an [`PlaneIntersection::Overlap`], consecutive ones joined into one interval. A root
    /// where `f'` is below `4·√(2·zero·|f''|)` (a root cluster of the touching kind) is a
    /// [`Contact::Tangent`], refined by Newton's method on `f' = 0` (at most 40 steps) to full
    /// precision, with its order from the growth of `|f|` at probes (`|f(2h)/f(h)| ≈ 2^(order+1)`);
    /// a root at an end of the domain (within `10⁻¹²` of its length) is a [`Contact::End`]; any
    /// other is a [`Contact::Crossing`]. Answers are sorted by `t`.
    ///
    /// ```
    /// use lekalo::query::{Contact, PlaneIntersection};
    /// use lekalo::{BSplineCurve, Points, QueryCurve};
    /// // a cubic in the plane z = 2: it lies in that plane over its whole domain
    /// let c = BSplineCurve::new(3, vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0],
    ///     Points::from_3d(&[[0.0, 0.0, 2.0], [1.0, 2.0, 2.0], [2.0, -1.0, 2.0], [3.0, 0.0, 2.0]])?)?;
    /// let q = QueryCurve::from_bspline(&c)?;
    /// let hits = q.intersect_plane(&[0.0, 0.0, 2.0], &[0.0, 0.0, 1.0])?;
    /// assert_eq!(hits, vec![PlaneIntersection::Overlap { t: (0.0, 1.0) }]);
    /// // the plane x = 1.5 crosses it once
    /// let hits = q.intersect_plane(&[1.5, 0.0, 0.0], &[1.0, 0.0, 0.0])?;
    /// assert_eq!(hits.len(), 1);
    /// assert_eq!(hits[0].contact(), Contact::Crossing);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::Dimension`] / [`Error::NonFinite`] for bad plane data; [`Error::InvalidArgument`]
    /// for a zero normal.
    pub fn intersect_plane(
        &self,
        origin: &[f64],
        normal: &[f64],
    ) -> Result<Vec<PlaneIntersection>> {
        check_query("plane origin", origin, self.dim)?;
        check_query("plane normal", normal, self.dim)?;
        let nn = normal.iter().map(|x| x * x).sum::<f64>().sqrt();
        if !(nn > 0.0) {
            return Err(Error::InvalidArgument {
                what: "plane normal".into(),
                reason: "it is the zero vector".into(),
            });
        }
        let n: Vec<f64> = normal.iter().map(|x| x / nn).collect();
        let mut o = vec![0.0; self.dim];
        self.normalise(origin, &mut o);
        let (lo, hi) = self.domain();
        let at_end =
            |t: f64| (t - lo).abs() <= 1e-12 * (hi - lo) || (hi - t).abs() <= 1e-12 * (hi - lo);
        let mut out: Vec<PlaneIntersection> = Vec::new();
        let mut scratch = Vec::new();
        for k in 0..self.piece_count() {
            let piece = self.piece(k);
            let mut mag = 0.0_f64;
            let coef: Vec<f64> = piece
                .chunks_exact(self.hd)
                .map(|p| {
                    let w = if self.rational { p[self.dim] } else { 1.0 };
                    let v: f64 = (0..self.dim).map(|d| (p[d] - w * o[d]) * n[d]).sum();
                    mag = mag.max(
                        (0..self.dim).map(|d| (p[d] * n[d]).abs()).sum::<f64>()
                            + w * o.iter().map(|x| x.abs()).sum::<f64>(),
                    );
                    v
                })
                .collect();
            let zero = 64.0 * f64::EPSILON * mag;
            let (a, b) = self.spans[k];
            if coef.iter().all(|c| c.abs() <= zero) {
                // the piece lies in the plane: join it to an overlap ending where it starts
                if let Some(PlaneIntersection::Overlap { t }) = out.last_mut() {
                    if t.1 == a {
                        t.1 = b;
                        continue;
                    }
                }
                // a root at the piece's start belongs to the overlap
                if out.last().is_some_and(|x| match x {
                    PlaneIntersection::Point { t, .. } => *t == a,
                    PlaneIntersection::Overlap { .. } => false,
                }) {
                    out.pop();
                }
                out.push(PlaneIntersection::Overlap { t: (a, b) });
                continue;
            }
            let f = Bern(coef);
            let (d1, d2) = (f.deriv(), f.deriv().deriv());
            for s in bern_roots(&f, zero) {
                let mut s = s;
                let slope = d1.eval(s).abs();
                let tangent = slope <= 4.0 * (2.0 * zero * d2.eval(s).abs()).sqrt();
                if tangent {
                    s = touching_root(&f, &d1, &d2, s, zero);
                }
                let t = self.global(k, s);
                let covered = out.last().is_some_and(|x| match x {
                    PlaneIntersection::Point { t: u, .. } => {
                        (t - u).abs() <= 1e-12 * (1.0 + t.abs())
                    }
                    PlaneIntersection::Overlap { t: (_, e) } => t <= *e + 1e-12 * (hi - lo),
                });
                if covered {
                    continue;
                }
                let contact = if at_end(t) {
                    Contact::End
                } else if tangent {
                    Contact::Tangent {
                        order: bern_order(&f, s),
                    }
                } else {
                    Contact::Crossing
                };
                out.push(PlaneIntersection::Point {
                    t,
                    point: self.eval_global(t, 0, &mut scratch),
                    contact,
                });
            }
        }
        Ok(out)
    }

    /// Where the curve meets a surface within `tolerance`: subdivision of the curve's pieces
    /// and the surface's patches while their boxes overlap, then Levenberg–Marquardt on
    /// `C(t) = S(u, v)` (`docs/theory/queries.md#intersections`). The solutions, sorted by `t`,
    /// are grouped as for two curves: neighbours are joined when the curve between them stays
    /// within the tolerance of the surface (its middle projected); a group of more than one, or
    /// a solution whose gap stays below `tolerance / 100` at probes `10⁻⁶` of the domain either
    /// side, is grown to where the gap exceeds the tolerance and is an
    /// [`SurfaceIntersection::Overlap`] if the gap stays below `tolerance / 100` across it (the
    /// curve lies on the surface, as an iso-curve does; an end within the tolerance of the
    /// curve's end is put there). Otherwise one point per group: [`Contact::Crossing`] when the
    /// first-order gap `|C'|·h·sin θ` (`θ` the angle between the curve and the tangent plane,
    /// `h` the probe) is at least ten times the tolerance, [`Contact::End`] at an end of the
    /// curve, a [`Contact::NearMiss`] when the gap exceeds [`super::TOUCH_RTOL`] times the
    /// larger scale, else a [`Contact::Tangent`] with its order from the growth of the gap. A
    /// point that is not a crossing, on a 3-D curve, is refined on the tangency system
    /// `((C − S)·S_u, (C − S)·S_v, C'·(S_u × S_v)) = 0` to full precision.
    ///
    /// ```
    /// use lekalo::query::SurfaceIntersection;
    /// use lekalo::{BSplineCurve, BSplineSurface, Points, QueryCurve, QuerySurface};
    /// // the bilinear patch z = xy on [0, 1]² and its iso-curve u = 1/2: the line x = 1/2, z = y/2
    /// let net = Points::from_3d(&[[0.0, 0.0, 0.0], [0.0, 1.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 1.0]])?;
    /// let s = BSplineSurface::new(1, 1, vec![0.0, 0.0, 1.0, 1.0], vec![0.0, 0.0, 1.0, 1.0], net, (2, 2))?;
    /// let iso = BSplineCurve::new(1, vec![0.0, 0.0, 1.0, 1.0],
    ///                             Points::from_3d(&[[0.5, 0.0, 0.0], [0.5, 1.0, 0.5]])?)?;
    /// let hits = QueryCurve::from_bspline(&iso)?.intersect_surface(&QuerySurface::from_bspline(&s)?, 1e-9)?;
    /// assert_eq!(hits.len(), 1);
    /// let SurfaceIntersection::Overlap { t, .. } = hits[0] else { panic!("not an overlap") };
    /// assert_eq!(t, (0.0, 1.0));
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::Dimension`] for different dimensions; [`Error::InvalidArgument`] for a bad
    /// tolerance; [`Error::TooLarge`] beyond 2^20 examined pairs.
    pub fn intersect_surface(
        &self,
        surface: &QuerySurface,
        tolerance: f64,
    ) -> Result<Vec<SurfaceIntersection>> {
        if surface.dim != self.dim {
            return Err(Error::Dimension {
                what: "surface for a curve–surface intersection".into(),
                expected: self.dim,
                got: surface.dim,
            });
        }
        check_tolerance(
            What::of(Arg::Tolerance, "intersection tolerance"),
            tolerance,
        )?;
        // (t, (u, v), point, transversal)
        let mut found: Vec<SurfaceSolution> = Vec::new();
        let h = PROBE * (self.domain().1 - self.domain().0);
        let mut scratch = Vec::new();
        let mut visited = 0;
        for k in 0..self.piece_count() {
            for pk in 0..surface.patch_count() {
                // both in original coordinates: sub-curve nets and sub-patch nets
                let cnet = to_original(
                    self.piece(k),
                    self.hd,
                    self.dim,
                    self.rational,
                    &self.centre,
                    self.scale,
                );
                let snet = to_original(
                    surface.patch(pk),
                    surface.hd,
                    surface.dim,
                    surface.rational,
                    &surface.centre,
                    surface.scale,
                );
                let mut stack = vec![((0.0, 1.0), cnet, (0.0, 1.0), (0.0, 1.0), snet, 0_u32)];
                while let Some((cs, cn, us, vs, sn, depth)) = stack.pop() {
                    visited += 1;
                    if visited > MAX_PAIRS {
                        return Err(Error::TooLarge {
                            what: "curve-surface sub-pairs".into(),
                            size: visited,
                            max: MAX_PAIRS,
                        });
                    }
                    let cb = cart_box(&cn, self.hd, self.dim, self.rational);
                    let sb = cart_box(&sn, surface.hd, surface.dim, surface.rational);
                    if !boxes_overlap(&cb, &sb, self.dim, tolerance) {
                        continue;
                    }
                    let cd = dist(&cb[..self.dim], &cb[self.dim..]);
                    let sd = dist(&sb[..self.dim], &sb[self.dim..]);
                    let big = cd.max(sd);
                    if big <= 1e-2 * self.scale.max(surface.scale) || depth >= MAX_DEPTH {
                        let x0 = [
                            0.5 * (cs.0 + cs.1),
                            0.5 * (us.0 + us.1),
                            0.5 * (vs.0 + vs.1),
                        ];
                        if let Some((t, u, v, p, across)) =
                            self.curve_surface_newton(k, surface, pk, x0, &mut scratch)
                        {
                            if dist(&p.0, &p.1) <= tolerance {
                                let transversal = across * h >= 10.0 * tolerance;
                                found.push((t, surface.global_uv(pk, u, v), p.0, transversal));
                            }
                        }
                        continue;
                    }
                    if cd >= sd {
                        let n = cn.len() / self.hd - 1;
                        let (l, r) = split_curve(&cn, self.hd, n);
                        let m = 0.5 * (cs.0 + cs.1);
                        stack.push(((cs.0, m), l, us, vs, sn.clone(), depth + 1));
                        stack.push(((m, cs.1), r, us, vs, sn, depth + 1));
                    } else {
                        for (u, v, net) in surface.split4(&sn, us, vs) {
                            stack.push((cs, cn.clone(), u, v, net, depth + 1));
                        }
                    }
                }
            }
        }
        found.sort_by(|a, b| a.0.total_cmp(&b.0));
        Ok(self.assemble_surface(surface, found, tolerance))
    }

    /// Groups the curve–surface solutions `(t, uv, point, transversal)` (sorted by `t`) into
    /// answers, as [`QueryCurve::intersect_surface`] describes.
    fn assemble_surface(
        &self,
        surface: &QuerySurface,
        found: Vec<SurfaceSolution>,
        tolerance: f64,
    ) -> Vec<SurfaceIntersection> {
        let gap = |t: f64| -> (f64, (f64, f64)) {
            let p = self.point(t).unwrap_or_default();
            surface
                .project(&p)
                .map_or((f64::INFINITY, (f64::NAN, f64::NAN)), |pr| {
                    (pr.distance, pr.uv)
                })
        };
        let mut groups: Vec<Vec<SurfaceSolution>> = Vec::new();
        for f in found {
            if let Some(g) = groups.last_mut() {
                let last = &g[g.len() - 1];
                let joined = if last.3 && f.3 {
                    dist(&last.2, &f.2) <= tolerance
                } else {
                    gap(0.5 * (last.0 + f.0)).0 <= tolerance
                };
                if joined {
                    g.push(f);
                    continue;
                }
            }
            groups.push(vec![f]);
        }
        let (lo, hi) = self.domain();
        let touch = TOUCH_RTOL * self.scale.max(surface.scale);
        // a contact refined on the tangency system, kept when it stays near and its gap is no
        // larger (two crossings close together have a least unsigned gap of zero between them
        // but an extremum of the signed gap that is not: those keep the search's point)
        let refined = |t: f64, uv: (f64, f64), point: Vec<f64>, d: f64| match self
            .refine_surface_contact(surface, t, uv)
        {
            Some(r) if r.3 <= d.max(touch) && (r.0 - t).abs() <= REFINE_REACH * (hi - lo) => r,
            _ => (t, uv, point, d),
        };
        let mut out = Vec::new();
        for (gi, g) in groups.iter().enumerate() {
            let (mut a0, mut a1) = (g[0].0, g[g.len() - 1].0);
            let transversal = g.iter().all(|f| f.3);
            let probe = || {
                let h = PROBE * (hi - lo);
                [a0 - h, a1 + h]
                    .iter()
                    .filter(|t| **t >= lo && **t <= hi)
                    .all(|&t| gap(t).0 <= tolerance / 100.0)
            };
            if !transversal && ((g.len() > 1 && a1 > a0) || probe()) {
                let left_lim = if gi > 0 {
                    groups[gi - 1][groups[gi - 1].len() - 1].0
                } else {
                    lo
                };
                let right_lim = groups.get(gi + 1).map_or(hi, |n| n[0].0);
                a0 = super::curves::grow(a0, left_lim, |t| gap(t).0 <= tolerance);
                a1 = super::curves::grow(a1, right_lim, |t| gap(t).0 <= tolerance);
                let coincide = (1..10).all(|i| {
                    let t = a0 + (a1 - a0) * f64::from(i) / 10.0;
                    gap(t).0 <= tolerance / 100.0
                });
                if coincide {
                    // an end within the tolerance (along the curve) of the curve's end is there
                    let snap = |t: f64, e: f64| {
                        let near = self
                            .point(t)
                            .ok()
                            .zip(self.point(e).ok())
                            .is_some_and(|(p, q)| dist(&p, &q) <= 2.0 * tolerance);
                        if near {
                            e
                        } else {
                            t
                        }
                    };
                    let (a0, a1) = (snap(a0, lo), snap(a1, hi));
                    out.push(SurfaceIntersection::Overlap {
                        t: (a0, a1),
                        uv: (gap(a0).1, gap(a1).1),
                    });
                    continue;
                }
                let t = super::curves::golden_min(a0, a1, |t| gap(t).0);
                let (d, uv) = gap(t);
                let point = self.point(t).unwrap_or_default();
                let (t, uv, point, d) = refined(t, uv, point, d);
                out.push(SurfaceIntersection::Point {
                    t,
                    uv,
                    contact: self.surface_contact(surface, &point, t, d, touch, tolerance),
                    point,
                });
                continue;
            }
            let best = g
                .iter()
                .min_by(|x, y| gap(x.0).0.total_cmp(&gap(y.0).0))
                .unwrap_or(&g[0]);
            let (d, _) = gap(best.0);
            if transversal {
                let contact = if self.is_curve_end(&best.2, tolerance) {
                    Contact::End
                } else {
                    Contact::Crossing
                };
                out.push(SurfaceIntersection::Point {
                    t: best.0,
                    uv: best.1,
                    point: best.2.clone(),
                    contact,
                });
                continue;
            }
            let (t, uv, point, d) = refined(best.0, best.1, best.2.clone(), d);
            out.push(SurfaceIntersection::Point {
                t,
                uv,
                contact: self.surface_contact(surface, &point, t, d, touch, tolerance),
                point,
            });
        }
        out
    }

    /// Whether `point` is within `tolerance` of an end point of this curve.
    fn is_curve_end(&self, point: &[f64], tolerance: f64) -> bool {
        let (lo, hi) = self.domain();
        [lo, hi]
            .iter()
            .any(|&e| self.point(e).is_ok_and(|q| dist(&q, point) <= tolerance))
    }

    /// The kind of a non-transversal curve–surface contact at `t` with least gap `gap`.
    fn surface_contact(
        &self,
        surface: &QuerySurface,
        point: &[f64],
        t: f64,
        gap: f64,
        touch: f64,
        tolerance: f64,
    ) -> Contact {
        if self.is_curve_end(point, tolerance) {
            return Contact::End;
        }
        if gap > touch {
            return Contact::NearMiss { gap };
        }
        let (lo, hi) = self.domain();
        let h = 1e-3 * (hi - lo);
        let sign = if t + 2.0 * h <= hi { 1.0 } else { -1.0 };
        let g = |x: f64| {
            self.point(x.clamp(lo, hi))
                .ok()
                .and_then(|p| surface.project(&p).ok())
                .map_or(f64::INFINITY, |pr| pr.distance)
        };
        Contact::Tangent {
            order: order_from_growth(g(t + sign * h), g(t + 2.0 * sign * h)),
        }
    }

    /// Levenberg–Marquardt for `C(s) = S(u, v)` (local parameters of piece `k` and patch `pk`;
    /// `numeric::damped`, with its bounds on steps and trials); returns the global `t`, local `(u, v)` and both points (original
    /// coordinates).
    #[allow(clippy::type_complexity)]
    fn curve_surface_newton(
        &self,
        k: usize,
        surf: &QuerySurface,
        pk: usize,
        x0: [f64; 3],
        scratch: &mut Vec<f64>,
    ) -> Option<(f64, f64, f64, (Vec<f64>, Vec<f64>), f64)> {
        let dim = self.dim;
        let eval = |x: &[f64; 3], scratch: &mut Vec<f64>| {
            let mut buf = vec![0.0; 3 * dim];
            self.eval_local(k, x[0], 1, scratch, &mut buf);
            let (sp, sd) = surf.eval_patch(pk, x[1], x[2]);
            let mut c = vec![0.0; dim];
            let mut s = vec![0.0; dim];
            self.denormalise(&buf[..dim], &mut c);
            surf.denormalise(&sp, &mut s);
            let dc: Vec<f64> = buf[dim..2 * dim].iter().map(|v| v * self.scale).collect();
            let su: Vec<f64> = sd[..dim].iter().map(|v| v * surf.scale).collect();
            let sv: Vec<f64> = sd[dim..2 * dim].iter().map(|v| v * surf.scale).collect();
            (c, s, dc, su, sv)
        };
        let (x, _) = levenberg_marquardt(x0, |x| {
            let (c, s, dc, su, sv) = eval(x, scratch);
            let r: Vec<f64> = c.iter().zip(&s).map(|(a, b)| a - b).collect();
            // J = [C', −S_u, −S_v]
            let cols = [
                dc,
                su.iter().map(|v| -v).collect::<Vec<_>>(),
                sv.iter().map(|v| -v).collect(),
            ];
            let mut normal = [[0.0; 3]; 3];
            let mut gradient = [0.0; 3];
            for i in 0..3 {
                for j in 0..3 {
                    normal[i][j] = dot(&cols[i], &cols[j]);
                }
                gradient[i] = dot(&cols[i], &r);
            }
            Residual {
                gap: dist(&c, &s),
                normal,
                gradient,
            }
        });
        let (c, s, dc, su, sv) = eval(&x, scratch);
        // |C'| sin θ per unit of the global parameter: the part of C' off the tangent plane
        // (least squares on S_u, S_v)
        let (a, b, e) = (dot(&su, &su), dot(&su, &sv), dot(&sv, &sv));
        let (p, q) = (dot(&su, &dc), dot(&sv, &dc));
        let det = a * e - b * b;
        let off: Vec<f64> = if det > 0.0 {
            let (al, be) = ((p * e - q * b) / det, (a * q - b * p) / det);
            (0..dim).map(|d| dc[d] - al * su[d] - be * sv[d]).collect()
        } else {
            vec![0.0; dim]
        };
        let (a0, a1) = self.spans[k];
        let across = dot(&off, &off).sqrt() / (a1 - a0);
        Some((self.global(k, x[0]), x[1], x[2], (c, s), across))
    }
}

/// A touching root of `f` near `s`, to full precision: Newton's method on `f' = 0` (its
/// extremum; at most 40 steps, kept in `[0, 1]`), kept only while `|f|` stays at most `zero`.
fn touching_root(f: &Bern, d1: &Bern, d2: &Bern, s: f64, zero: f64) -> f64 {
    let mut x = s;
    for _ in 0..40 {
        let (g, h) = (d1.eval(x), d2.eval(x));
        if !(h != 0.0 && h.is_finite()) {
            break;
        }
        let next = (x - g / h).clamp(0.0, 1.0);
        if next == x || !(f.eval(next).abs() <= zero.max(f.eval(x).abs())) {
            break;
        }
        x = next;
    }
    x
}

/// The order of contact of the Bernstein polynomial `f` with zero at its root `s`: the growth of
/// `|f|` at probes `h = 10⁻³` and `2h` on the side with room, `|f(2h)/f(h)| ≈ 2^(order + 1)`; at
/// least 1, at most 6.
fn bern_order(f: &Bern, s: f64) -> u32 {
    let h = if s + 2e-3 <= 1.0 { 1e-3 } else { -1e-3 };
    order_from_growth(f.eval(s + h).abs(), f.eval(s + 2.0 * h).abs())
}

fn to_original(
    net: &[f64],
    hd: usize,
    dim: usize,
    rational: bool,
    centre: &[f64],
    scale: f64,
) -> Vec<f64> {
    let mut out = net.to_vec();
    for p in out.chunks_exact_mut(hd) {
        let w = if rational { p[dim] } else { 1.0 };
        for d in 0..dim {
            p[d] = w * centre[d] + scale * p[d];
        }
    }
    out
}

fn cart_box(net: &[f64], hd: usize, dim: usize, rational: bool) -> Vec<f64> {
    let mut b = vec![f64::INFINITY; dim];
    b.extend(std::iter::repeat_n(f64::NEG_INFINITY, dim));
    for p in net.chunks_exact(hd) {
        let w = if rational { p[dim] } else { 1.0 };
        for d in 0..dim {
            b[d] = b[d].min(p[d] / w);
            b[dim + d] = b[dim + d].max(p[d] / w);
        }
    }
    b
}

#[cfg(test)]
mod tests {
    use std::f64::consts::{FRAC_PI_2, TAU};

    use crate::query::{Contact, PlaneIntersection, SurfaceIntersection};
    use crate::surface::Placement;
    use crate::{BSplineCurve, NurbsSurface, Points, QueryCurve, QuerySurface};

    /// A line touching the unit sphere (exact NURBS) at `(0.48, 0.64, 0.6)`, inside a patch:
    /// one tangent contact of order 1, its parameter within 16 ulps of the closest approach of
    /// the line to the centre (computed from the line's own rounded ends), the surface point on
    /// the curve's.
    #[test]
    fn a_line_touching_a_sphere_is_found_to_full_precision() {
        let f = Placement::new([0.0; 3], Some([0.0, 0.0, 1.0]), Some([1.0, 0.0, 0.0])).unwrap();
        let sphere = QuerySurface::from_nurbs(
            &NurbsSurface::sphere(&f, 1.0, (0.0, TAU), (-FRAC_PI_2, FRAC_PI_2)).unwrap(),
        )
        .unwrap();
        // p − d and p + 3d with d = (0.64, −0.48, 0) orthogonal to p: the touch at t = 1/4
        let (a, b) = ([-0.16, 1.12, 0.6], [2.4, -0.8, 0.6]);
        let c = BSplineCurve::new(
            1,
            vec![0.0, 0.0, 1.0, 1.0],
            Points::from_3d(&[a, b]).unwrap(),
        )
        .unwrap();
        let hits = QueryCurve::from_bspline(&c)
            .unwrap()
            .intersect_surface(&sphere, 1e-9)
            .unwrap();
        assert_eq!(hits.len(), 1, "{hits:?}");
        let SurfaceIntersection::Point {
            t, point, contact, ..
        } = &hits[0]
        else {
            panic!("{hits:?}")
        };
        assert_eq!(*contact, Contact::Tangent { order: 1 }, "{hits:?}");
        let d: Vec<f64> = (0..3).map(|i| b[i] - a[i]).collect();
        let exact =
            -(0..3).map(|i| a[i] * d[i]).sum::<f64>() / (0..3).map(|i| d[i] * d[i]).sum::<f64>();
        let ulps = (t - exact).abs() / (exact * f64::EPSILON);
        assert!(
            ulps <= 16.0,
            "t = {t}, closest approach at {exact}: {ulps} ulps"
        );
        let r = point.iter().map(|x| x * x).sum::<f64>().sqrt();
        assert!((r - 1.0).abs() <= 4.0 * f64::EPSILON, "{point:?}");
    }

    #[test]
    fn plane_crossings() {
        let c = BSplineCurve::new(
            2,
            vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
            Points::from_3d(&[[0.0, 0.0, -1.0], [1.0, 0.0, 3.0], [2.0, 0.0, -1.0]]).unwrap(),
        )
        .unwrap();
        let q = QueryCurve::from_bspline(&c).unwrap();
        let hits = q
            .intersect_plane(&[0.0, 0.0, 0.0], &[0.0, 0.0, 2.0])
            .unwrap();
        assert_eq!(hits.len(), 2, "{hits:?}");
        for h in &hits {
            let PlaneIntersection::Point { point, contact, .. } = h else {
                panic!("{hits:?}")
            };
            assert!(point[2].abs() < 1e-15, "{point:?}");
            assert_eq!(*contact, Contact::Crossing, "{hits:?}");
        }
        // touching the plane z = 1 at the top (z = −1 + 8t(1 − t)... peak 1 at t = 1/2): one
        // tangent answer, exact
        let touch = q
            .intersect_plane(&[0.0, 0.0, 1.0], &[0.0, 0.0, 1.0])
            .unwrap();
        assert_eq!(touch.len(), 1, "{touch:?}");
        let PlaneIntersection::Point { t, contact, .. } = touch[0] else {
            panic!("{touch:?}")
        };
        assert_eq!(t, 0.5, "{touch:?}");
        assert_eq!(contact, Contact::Tangent { order: 1 }, "{touch:?}");
    }
}
