//! A contact of two curves refined to full precision and named
//! (`docs/theory/queries.md#kinds-of-contact`): Newton's method on the system that defines a
//! tangency, the order of contact from the growth of the gap, and a near-tangent pair told apart
//! as two crossings, a touch or a near miss.

use super::super::pieces::{dist, dot, QueryCurve};
use super::super::project::ProjectScratch;
use super::super::surface::QuerySurface;
use super::{Contact, TOUCH_RTOL};

/// Most Newton steps of a refinement (quadratic convergence needs a handful; the distance
/// gradient at an exact tangency in space converges linearly, halving the error per step).
const REFINE_STEPS: usize = 80;
/// Probe step for the order of contact, as a fraction of the first curve's domain.
const ORDER_PROBE: f64 = 1e-3;
/// Highest order of contact reported (the probes cannot tell higher ones apart).
const MAX_ORDER: u32 = 6;

/// Point and first and second derivatives of a curve at global `t` (original coordinates),
/// viewed in `buf` (`3·dim` long, reused between steps).
struct Jet<'a> {
    p: &'a [f64],
    d1: &'a [f64],
    d2: &'a [f64],
}

fn jet<'a>(c: &QueryCurve, t: f64, scratch: &mut Vec<f64>, buf: &'a mut [f64]) -> Jet<'a> {
    c.eval_global_into(t, 2, scratch, buf);
    let d = c.dim;
    Jet {
        p: &buf[..d],
        d1: &buf[d..2 * d],
        d2: &buf[2 * d..3 * d],
    }
}

/// The order of contact from the gaps `g1` at a probe `h` and `g2` at `2h` from the contact:
/// `g2 / g1 ≈ 2^(order + 1)`, the nearest such order (the ratio compared with `2^(order + 1.5)`);
/// 1 when the gaps say nothing (zero or not finite), at most 6.
pub(super) fn order_from_growth(g1: f64, g2: f64) -> u32 {
    let ratio = g2 / g1;
    if !(g1 > 0.0 && ratio.is_finite()) {
        return 1;
    }
    (1..MAX_ORDER)
        .find(|&order| ratio < 2f64.powf(f64::from(order) + 1.5))
        .unwrap_or(MAX_ORDER)
}

fn cross2(a: &[f64], b: &[f64]) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}

fn clamp_to(c: &QueryCurve, t: f64) -> f64 {
    let (lo, hi) = c.domain();
    t.clamp(lo, hi)
}

impl QueryCurve {
    /// The point of a tangential contact (or closest approach) of this curve and `other` near
    /// `(ta, tb)`, to full precision: Newton's method on the critical points of the distance
    /// `½‖A(s) − B(u)‖²`. In the plane that is the square system
    /// `F(s, u) = (T·(A(s) − B(u)), A'(s) × B'(u)) = 0` (`T` the unit tangent of `A`, frozen in
    /// each step): the points are joined along the normal and the tangents are parallel, whose
    /// Jacobian `[[T·A', −T·B'], [A''×B', A'×B'']]` is regular at a contact of order 1 even where
    /// the gap vanishes, so convergence is quadratic. In space the gradient
    /// `((A − B)·A', −(A − B)·B')` is solved with its full Hessian (linear convergence at an
    /// exact tangency, where the Hessian is singular). At most 80 steps, kept in the domains; the
    /// best point (least residual) is returned.
    pub(super) fn refine_contact(&self, other: &QueryCurve, ta: f64, tb: f64) -> (f64, f64) {
        let mut scratch = Vec::new();
        let (mut bufa, mut bufb) = (vec![0.0; 3 * self.dim], vec![0.0; 3 * other.dim]);
        let mut r = vec![0.0; self.dim];
        let (mut s, mut u) = (ta, tb);
        let mut best = (f64::INFINITY, s, u);
        for _ in 0..REFINE_STEPS {
            let a = jet(self, s, &mut scratch, &mut bufa);
            let b = jet(other, u, &mut scratch, &mut bufb);
            for (r, (x, y)) in r.iter_mut().zip(a.p.iter().zip(b.p)) {
                *r = x - y;
            }
            let (la, lb) = (dot(a.d1, a.d1).sqrt(), dot(b.d1, b.d1).sqrt());
            if !(la > 0.0 && lb > 0.0) {
                break;
            }
            // residual F and Jacobian J = [[j00, j01], [j10, j11]]
            let (f, j) = if self.dim == 2 {
                let tng = [a.d1[0] / la, a.d1[1] / la];
                (
                    [dot(&tng, &r), cross2(a.d1, b.d1)],
                    [
                        [la, -dot(&tng, b.d1)],
                        [cross2(a.d2, b.d1), cross2(a.d1, b.d2)],
                    ],
                )
            } else {
                let ab = -dot(a.d1, b.d1);
                (
                    [dot(&r, a.d1), -dot(&r, b.d1)],
                    [[la * la + dot(&r, a.d2), ab], [ab, lb * lb - dot(&r, b.d2)]],
                )
            };
            // the residual in units of length: the cross product over |B'|, the gradient over
            // the speeds
            let size = if self.dim == 2 {
                (f[0] * f[0] + (f[1] / lb).powi(2)).sqrt()
            } else {
                (f[0] / la).hypot(f[1] / lb)
            };
            if size < best.0 {
                best = (size, s, u);
            }
            if size == 0.0 {
                break;
            }
            let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
            if !(det != 0.0 && det.is_finite()) {
                break;
            }
            let ds = (f[0] * j[1][1] - f[1] * j[0][1]) / det;
            let du = (j[0][0] * f[1] - j[1][0] * f[0]) / det;
            let (ns, nu) = (clamp_to(self, s - ds), clamp_to(other, u - du));
            if ns == s && nu == u {
                break;
            }
            s = ns;
            u = nu;
        }
        (best.1, best.2)
    }

    /// Newton's method on `A(s) = B(u)` (planar curves, global parameters) from `(ta, tb)`,
    /// kept in the domains: the crossing it converges to, if its gap is at most `touch`.
    fn crossing_from(
        &self,
        other: &QueryCurve,
        ta: f64,
        tb: f64,
        touch: f64,
    ) -> Option<(f64, f64)> {
        let mut scratch = Vec::new();
        let (mut s, mut u) = (ta, tb);
        let mut best = (f64::INFINITY, s, u);
        let (mut a, mut b) = ([0.0; 4], [0.0; 4]);
        for _ in 0..REFINE_STEPS {
            self.eval_global_into(s, 1, &mut scratch, &mut a);
            other.eval_global_into(u, 1, &mut scratch, &mut b);
            let r = [a[0] - b[0], a[1] - b[1]];
            let gap = r[0].hypot(r[1]);
            if gap < best.0 {
                best = (gap, s, u);
            }
            let (da, db) = ([a[2], a[3]], [b[2], b[3]]);
            let det = cross2(&db, &da);
            if gap == 0.0 || !(det != 0.0 && det.is_finite()) {
                break;
            }
            let ds = (r[0] * db[1] - r[1] * db[0]) / det;
            let du = (r[0] * da[1] - r[1] * da[0]) / det;
            let (ns, nu) = (clamp_to(self, s + ds), clamp_to(other, u + du));
            if ns == s && nu == u {
                break;
            }
            s = ns;
            u = nu;
        }
        (best.0 <= touch).then_some((best.1, best.2))
    }

    /// The order of contact at `t` on this curve with `other`, from the growth of the gap
    /// (distance to `other`) at probes `h` and `2h` away (`h` a thousandth of the domain, on the
    /// side with room): `gap(2h) / gap(h) ≈ 2^(order + 1)`. At least 1, at most 6.
    pub(super) fn contact_order(&self, other: &QueryCurve, t: f64) -> u32 {
        let (lo, hi) = self.domain();
        let h = ORDER_PROBE * (hi - lo);
        let sign = if t + 2.0 * h <= hi { 1.0 } else { -1.0 };
        // the projections reuse one set of buffers (the same distances as `project`'s)
        let (mut w, mut scratch, mut p) =
            (ProjectScratch::default(), Vec::new(), vec![0.0; self.dim]);
        let mut gap = |x: f64| {
            self.eval_global_into(clamp_to(self, x), 0, &mut scratch, &mut p);
            other
                .project_reusing(&p, &mut w)
                .map_or(f64::INFINITY, |(_, d)| d)
        };
        let (g1, g2) = (gap(t + sign * h), gap(t + 2.0 * sign * h));
        if !(g1 > 0.0 && g2.is_finite()) {
            return 1;
        }
        order_from_growth(g1, g2)
    }

    /// Whether `point` is within `tolerance` of an end point of this curve or `other` (a closed
    /// curve, whose ends are within the tolerance of each other, has none).
    pub(super) fn at_an_end(&self, other: &QueryCurve, point: &[f64], tolerance: f64) -> bool {
        [self, other].iter().any(|c| {
            let (lo, hi) = c.domain();
            let (Ok(p), Ok(q)) = (c.point(lo), c.point(hi)) else {
                return false;
            };
            dist(&p, &q) > tolerance
                && (dist(&p, point) <= tolerance || dist(&q, point) <= tolerance)
        })
    }

    /// The answers for a tangential contact or near miss of this curve and `other` near
    /// `(ta, tb)`: refined by [`QueryCurve::refine_contact`], then, with `touch` =
    /// [`TOUCH_RTOL`] times the larger scale, a touch ([`Contact::Tangent`] with its order, or
    /// [`Contact::End`]) when the least gap is at most `touch`; else, for planar curves, two
    /// crossings when the signed gap and the relative curvature have opposite signs (Newton's
    /// method on `A = B` from `√(2|g|/|c|)` either side, `c` the second difference of the signed
    /// gap); else, for planar curves, one crossing when Newton's method on `A = B` from
    /// `(ta, tb)` reaches a gap of at most `touch` (a shallow crossing, with no closest approach
    /// beside it); else a [`Contact::NearMiss`] with its gap. Each answer is
    /// `(t_a, t_b, contact)`.
    pub(super) fn classify_contact(
        &self,
        other: &QueryCurve,
        ta: f64,
        tb: f64,
        tolerance: f64,
    ) -> Vec<(f64, f64, Contact)> {
        let touch = TOUCH_RTOL * self.scale.max(other.scale);
        let (ta0, tb0) = (ta, tb);
        let (ta, tb) = self.refine_contact(other, ta, tb);
        let pa = self.point(ta).unwrap_or_default();
        let pb = other.point(tb).unwrap_or_default();
        let gap = dist(&pa, &pb);
        let end = |p: &[f64]| self.at_an_end(other, p, tolerance);
        if gap <= touch {
            let contact = if end(&pa) {
                Contact::End
            } else {
                Contact::Tangent {
                    order: self.contact_order(other, ta),
                }
            };
            return vec![(ta, tb, contact)];
        }
        if self.dim == 2 {
            if let Some(two) = self.two_crossings(other, ta, tb, touch) {
                return two
                    .into_iter()
                    .map(|(s, u)| {
                        let p = self.point(s).unwrap_or_default();
                        (
                            s,
                            u,
                            if end(&p) {
                                Contact::End
                            } else {
                                Contact::Crossing
                            },
                        )
                    })
                    .collect();
            }
        }
        if self.dim == 2 {
            // a shallow single crossing has no closest approach nearby: Newton's method on
            // A = B from where the search left it
            if let Some((s, u)) = self.crossing_from(other, ta0, tb0, touch) {
                let p = self.point(s).unwrap_or_default();
                return vec![(
                    s,
                    u,
                    if end(&p) {
                        Contact::End
                    } else {
                        Contact::Crossing
                    },
                )];
            }
        }
        let contact = if end(&pa) {
            Contact::End
        } else {
            Contact::NearMiss { gap }
        };
        vec![(ta, tb, contact)]
    }

    /// The two crossings beside the closest approach `(ta, tb)` of planar curves, if they cross
    /// there (see [`QueryCurve::classify_contact`]).
    fn two_crossings(
        &self,
        other: &QueryCurve,
        ta: f64,
        tb: f64,
        touch: f64,
    ) -> Option<[(f64, f64); 2]> {
        let (lo, hi) = self.domain();
        let h = ORDER_PROBE * (hi - lo);
        // the signed gap along A: its distance to B, with the sign of the side of B's normal
        let mut scratch = Vec::new();
        let b = other.eval_global(tb, 1, &mut scratch);
        let nrm = [-b[3], b[2]];
        let signed = |t: f64| {
            let p = self.point(clamp_to(self, t)).unwrap_or_default();
            let pr = other.project(&p).ok()?;
            let side = (p[0] - pr.point[0]) * nrm[0] + (p[1] - pr.point[1]) * nrm[1];
            Some(pr.distance.copysign(side))
        };
        let (g0, gl, gr) = (signed(ta)?, signed(ta - h)?, signed(ta + h)?);
        let c = (gl + gr - 2.0 * g0) / (h * h);
        if !(c != 0.0 && c.is_finite()) || (g0 > 0.0) == (c > 0.0) {
            return None;
        }
        let d = (-2.0 * g0 / c).sqrt();
        // B's parameter beside: its speed ratio carries the step over
        let a1 = self.eval_global(ta, 1, &mut scratch);
        let ratio = dot(&a1[2..4], &b[2..4]) / dot(&b[2..4], &b[2..4]);
        let left = self.crossing_from(other, ta - d, tb - ratio * d, touch)?;
        let right = self.crossing_from(other, ta + d, tb + ratio * d, touch)?;
        (left.0 < ta && right.0 > ta).then_some([left, right])
    }
}

/// `a × b` of two 3-vectors.
fn cross3(a: &[f64], b: &[f64]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// The solution of the 3 × 3 system `j x = f` by Cramer's rule; `None` when `j` is singular.
fn solve3(j: &[[f64; 3]; 3], f: &[f64; 3]) -> Option<[f64; 3]> {
    let det = dot(&j[0], &cross3(&j[1], &j[2]));
    if !(det != 0.0 && det.is_finite()) {
        return None;
    }
    // the columns of j
    let c = |k: usize| [j[0][k], j[1][k], j[2][k]];
    let (c0, c1, c2) = (c(0), c(1), c(2));
    Some([
        dot(f, &cross3(&c1, &c2)) / det,
        dot(&c0, &cross3(f, &c2)) / det,
        dot(&c0, &cross3(&c1, f)) / det,
    ])
}

/// A refined contact of a curve and a surface: `(t, (u, v), the curve's point C(t), the gap
/// |C(t) − S(u, v)|)` ([`QueryCurve::refine_surface_contact`]).
pub(super) type SurfaceContact = (f64, (f64, f64), Vec<f64>, f64);

impl QueryCurve {
    /// The point of a tangential contact (or closest approach) of this 3-D curve and `surface`
    /// near `(t, uv)`, to full precision (`docs/theory/queries.md#intersections`): Newton's
    /// method on the square system
    /// `F(t, u, v) = ((C − S)·S_u, (C − S)·S_v, C'·(S_u × S_v)) = 0`: `S(u, v)` is the foot of
    /// `C(t)` on the surface and the curve's tangent lies in the tangent plane, i.e. `t` is a
    /// critical point of the signed distance `g(t)` to the surface. The third row's derivative
    /// along the solutions of the first two is `g''`, so the Jacobian is regular at a contact
    /// of order 1 even where the gap vanishes and convergence is quadratic. At most 80 steps,
    /// `t` kept in the curve's domain; the best point (least residual, in units of length) is
    /// returned as `(t, uv, the curve's point, the gap |C − S|)`; `None` for a curve that is not
    /// 3-D or a start that cannot be evaluated (outside the surface's domain, a zero derivative
    /// of the curve or the surface there). A step that would leave the surface's domain ends
    /// the iteration.
    pub(super) fn refine_surface_contact(
        &self,
        surface: &QuerySurface,
        t: f64,
        uv: (f64, f64),
    ) -> Option<SurfaceContact> {
        if self.dim != 3 {
            return None;
        }
        let mut scratch = Vec::new();
        let ((ul, uh), (vl, vh)) = surface.domain();
        let (mut t, mut u, mut v) = (t, uv.0, uv.1);
        let mut best: Option<(f64, f64, f64, f64)> = None;
        for _ in 0..REFINE_STEPS {
            let c = self.eval_global(t, 2, &mut scratch);
            let (c0, c1, c2) = (&c[..3], &c[3..6], &c[6..9]);
            let Some((s, d)) = surface.eval_global(u, v) else {
                break;
            };
            let (su, sv, suu, suv, svv) = (&d[..3], &d[3..6], &d[6..9], &d[9..12], &d[12..15]);
            let r: Vec<f64> = c0.iter().zip(&s).map(|(x, y)| x - y).collect();
            let n = cross3(su, sv);
            let (lc, lu, lv, ln) = (
                dot(c1, c1).sqrt(),
                dot(su, su).sqrt(),
                dot(sv, sv).sqrt(),
                dot(&n, &n).sqrt(),
            );
            if !(lc > 0.0 && lu > 0.0 && lv > 0.0 && ln > 0.0) {
                break;
            }
            let f = [dot(&r, su), dot(&r, sv), dot(c1, &n)];
            // the residual in units of length: the foot conditions over the speeds, the sine of
            // the tangent's angle with the tangent plane times the gap's scale
            let size =
                (f[0] / lu).abs() + (f[1] / lv).abs() + (f[2] / (lc * ln)).abs() * self.scale;
            if best.is_none_or(|b| size < b.0) {
                best = Some((size, t, u, v));
            }
            if size == 0.0 {
                break;
            }
            // the normal's derivatives N_u = S_uu × S_v + S_u × S_uv, N_v = S_uv × S_v + S_u × S_vv
            let add = |a: [f64; 3], b: [f64; 3]| [a[0] + b[0], a[1] + b[1], a[2] + b[2]];
            let nu = add(cross3(suu, sv), cross3(su, suv));
            let nv = add(cross3(suv, sv), cross3(su, svv));
            let j = [
                [
                    dot(c1, su),
                    dot(&r, suu) - lu * lu,
                    dot(&r, suv) - dot(su, sv),
                ],
                [
                    dot(c1, sv),
                    dot(&r, suv) - dot(su, sv),
                    dot(&r, svv) - lv * lv,
                ],
                [dot(c2, &n), dot(c1, &nu), dot(c1, &nv)],
            ];
            let Some(step) = solve3(&j, &f) else {
                break;
            };
            let next = (clamp_to(self, t - step[0]), u - step[1], v - step[2]);
            if !((ul..=uh).contains(&next.1) && (vl..=vh).contains(&next.2)) || next == (t, u, v) {
                break;
            }
            (t, u, v) = next;
        }
        let (_, t, u, v) = best?;
        let p = self.eval_global(t, 0, &mut scratch);
        let (s, _) = surface.eval_global(u, v)?;
        let gap = dist(&p, &s);
        Some((t, (u, v), p, gap))
    }
}
