//! Intersections: planar curve–curve (with tangential contact and overlaps), self-intersections
//! of a planar curve, curve–plane and curve–surface (`docs/theory/queries.md#intersections`).
//!
//! Curve–curve: pairs of sub-curves whose control-point boxes overlap are halved (de Casteljau)
//! until both are flat, then a damped Gauss–Newton (Levenberg–Marquardt) iteration solves
//! `A(s) = B(u)` from the middle of each flat pair. Solutions that the curves join between
//! (the middle of their parameters on `A` is within the tolerance of `B`) are one answer: the
//! point of least gap for a tangential contact, an interval for an overlap.

use super::pieces::{bern_roots, check_tolerance, dist, Bern, QueryCurve};
use super::project::{check_query, CurveProjection};
use super::surface::{split_curve, QuerySurface};
use crate::error::{Error, Result};

/// Most sub-curve pairs one intersection visits (a bound on its work; reaching it is
/// [`Error::TooLarge`]).
const MAX_PAIRS: usize = 1 << 20;
/// Deepest halving of a sub-curve.
const MAX_DEPTH: u32 = 48;

/// A curve–surface intersection: the curve's parameter, the surface's `(u, v)` and the point.
pub type SurfaceHit = (f64, (f64, f64), Vec<f64>);

/// One intersection of two curves.
#[derive(Debug, Clone, PartialEq)]
pub enum CurveIntersection {
    /// The curves meet at a point (crossing or touching): parameters on both and the point
    /// (the first curve's point).
    Point {
        /// Parameter on the first curve.
        t_a: f64,
        /// Parameter on the second curve.
        t_b: f64,
        /// The common point.
        point: Vec<f64>,
    },
    /// The curves coincide (within rounding) over an interval of each.
    Overlap {
        /// Parameter interval on the first curve.
        a: (f64, f64),
        /// The corresponding interval on the second (its ends in the order matching `a`).
        b: (f64, f64),
    },
}

/// A sub-curve: piece, local parameter range, net in the common frame (homogeneous).
#[derive(Debug, Clone)]
struct Sub {
    k: usize,
    s: (f64, f64),
    net: Vec<f64>,
}

/// A curve's pieces re-expressed in a common normalised frame.
struct Framed<'a> {
    c: &'a QueryCurve,
    centre: Vec<f64>,
    scale: f64,
}

impl Framed<'_> {
    fn sub(&self, k: usize) -> Sub {
        let c = self.c;
        let mut net = c.piece(k).to_vec();
        for p in net.chunks_exact_mut(c.hd) {
            let w = if c.rational { p[c.dim] } else { 1.0 };
            for d in 0..c.dim {
                p[d] = (w * (c.centre[d] - self.centre[d]) + c.scale * p[d]) / self.scale;
            }
        }
        Sub {
            k,
            s: (0.0, 1.0),
            net,
        }
    }

    fn cart(&self, p: &[f64]) -> Vec<f64> {
        let c = self.c;
        let w = if c.rational { p[c.dim] } else { 1.0 };
        p[..c.dim].iter().map(|x| x / w).collect()
    }

    fn bbox(&self, net: &[f64]) -> Vec<f64> {
        let dim = self.c.dim;
        let mut b = vec![f64::INFINITY; dim];
        b.extend(std::iter::repeat_n(f64::NEG_INFINITY, dim));
        for p in net.chunks_exact(self.c.hd) {
            let x = self.cart(p);
            for d in 0..dim {
                b[d] = b[d].min(x[d]);
                b[dim + d] = b[dim + d].max(x[d]);
            }
        }
        b
    }

    /// Largest distance of the control points from the chord (convex hull ⇒ the curve is that
    /// close to the chord).
    fn flatness(&self, net: &[f64]) -> f64 {
        let hd = self.c.hd;
        let n = net.len() / hd - 1;
        let a = self.cart(&net[..hd]);
        let b = self.cart(&net[n * hd..]);
        net.chunks_exact(hd)
            .map(|p| segment_distance(&self.cart(p), &a, &b))
            .fold(0.0, f64::max)
    }

    /// Point and first derivative (local parameter) in the common frame.
    fn eval(&self, k: usize, s: f64, scratch: &mut Vec<f64>) -> (Vec<f64>, Vec<f64>) {
        let c = self.c;
        let mut buf = vec![0.0; 3 * c.dim];
        c.eval_local(k, s, 1, scratch, &mut buf);
        let f = c.scale / self.scale;
        let p = (0..c.dim)
            .map(|d| (c.centre[d] - self.centre[d]) / self.scale + f * buf[d])
            .collect();
        let dp = (0..c.dim).map(|d| f * buf[c.dim + d]).collect();
        (p, dp)
    }
}

/// Distance from `x` to the segment `[a, b]`.
pub(crate) fn segment_distance(x: &[f64], a: &[f64], b: &[f64]) -> f64 {
    let ab: Vec<f64> = a.iter().zip(b).map(|(p, q)| q - p).collect();
    let ax: Vec<f64> = a.iter().zip(x).map(|(p, q)| q - p).collect();
    let l2: f64 = ab.iter().map(|v| v * v).sum();
    let t = if l2 > 0.0 {
        (ax.iter().zip(&ab).map(|(p, q)| p * q).sum::<f64>() / l2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    ax.iter()
        .zip(&ab)
        .map(|(p, q)| (p - t * q) * (p - t * q))
        .sum::<f64>()
        .sqrt()
}

fn boxes_overlap(a: &[f64], b: &[f64], dim: usize, slack: f64) -> bool {
    (0..dim).all(|d| a[d] <= b[dim + d] + slack && b[d] <= a[dim + d] + slack)
}

fn halve(f: &Framed<'_>, s: &Sub) -> (Sub, Sub) {
    let n = s.net.len() / f.c.hd - 1;
    let (l, r) = split_curve(&s.net, f.c.hd, n);
    let m = 0.5 * (s.s.0 + s.s.1);
    (
        Sub {
            k: s.k,
            s: (s.s.0, m),
            net: l,
        },
        Sub {
            k: s.k,
            s: (m, s.s.1),
            net: r,
        },
    )
}

/// Levenberg–Marquardt for `A(s) = B(u)` on local parameters in `[0, 1]²`, at most 60 steps.
/// Returns `(s, u, gap)`.
fn solve_pair(
    fa: &Framed<'_>,
    ka: usize,
    fb: &Framed<'_>,
    kb: usize,
    s0: f64,
    u0: f64,
) -> (f64, f64, f64) {
    let mut scratch = Vec::new();
    let (mut s, mut u) = (s0, u0);
    let (pa, _) = fa.eval(ka, s, &mut scratch);
    let (pb, _) = fb.eval(kb, u, &mut scratch);
    let mut gap = dist(&pa, &pb);
    let mut lambda = 1e-12;
    for _ in 0..60 {
        let (pa, da) = fa.eval(ka, s, &mut scratch);
        let (pb, db) = fb.eval(kb, u, &mut scratch);
        let r: Vec<f64> = pa.iter().zip(&pb).map(|(x, y)| x - y).collect();
        // J = [da, −db]; normal equations (JᵀJ + λ diag) δ = −Jᵀ r
        let (a11, a12, a22) = (
            super::pieces::dot(&da, &da),
            -super::pieces::dot(&da, &db),
            super::pieces::dot(&db, &db),
        );
        let (g1, g2) = (super::pieces::dot(&da, &r), -super::pieces::dot(&db, &r));
        let mut improved = false;
        for _ in 0..20 {
            let (b11, b22) = (a11 * (1.0 + lambda) + 1e-300, a22 * (1.0 + lambda) + 1e-300);
            let det = b11 * b22 - a12 * a12;
            if !(det > 0.0) {
                lambda *= 10.0;
                continue;
            }
            let ds = -(b22 * g1 - a12 * g2) / det;
            let du = -(b11 * g2 - a12 * g1) / det;
            let (ns, nu) = ((s + ds).clamp(0.0, 1.0), (u + du).clamp(0.0, 1.0));
            let (qa, _) = fa.eval(ka, ns, &mut scratch);
            let (qb, _) = fb.eval(kb, nu, &mut scratch);
            let g = dist(&qa, &qb);
            if g < gap || (g == gap && (ns != s || nu != u) && g == 0.0) {
                let moved = (ns - s).abs() + (nu - u).abs();
                s = ns;
                u = nu;
                gap = g;
                lambda = (lambda * 0.1).max(1e-15);
                improved = moved > 1e-16;
                break;
            }
            lambda *= 10.0;
            if lambda > 1e12 {
                break;
            }
        }
        if !improved || gap == 0.0 {
            break;
        }
    }
    (s, u, gap)
}

impl QueryCurve {
    /// The common frame of two curves: the first one's centre, the larger scale.
    fn frame_with<'a>(&'a self, other: &'a QueryCurve) -> (Framed<'a>, Framed<'a>) {
        let scale = self.scale.max(other.scale);
        let centre = self.centre.clone();
        (
            Framed {
                c: self,
                centre: centre.clone(),
                scale,
            },
            Framed {
                c: other,
                centre,
                scale,
            },
        )
    }

    /// Every intersection of this planar curve with `other`, in the order of this curve's
    /// parameter. Points closer than `tolerance` (absolute, in the curves' units) count as
    /// common; a tangential contact is one [`CurveIntersection::Point`] (where the gap is least);
    /// stretches where the curves coincide to rounding are [`CurveIntersection::Overlap`]s.
    ///
    /// ```
    /// use lekalo::query::CurveIntersection;
    /// use lekalo::{BSplineCurve, NurbsCurve, Points, QueryCurve};
    /// let circle = QueryCurve::from_nurbs(&NurbsCurve::circle(&[0.0, 0.0], &[1.0, 0.0], &[0.0, 1.0], 1.0)?)?;
    /// let line = BSplineCurve::new(1, vec![0.0, 0.0, 1.0, 1.0], Points::from_2d(&[[-2.0, 0.5], [2.0, 0.5]])?)?;
    /// let hits = circle.intersect(&QueryCurve::from_bspline(&line)?, 1e-10)?;
    /// assert_eq!(hits.len(), 2);
    /// if let CurveIntersection::Point { point, .. } = &hits[0] {
    ///     assert!((point[0] - 0.75f64.sqrt()).abs() < 1e-12 && (point[1] - 0.5).abs() < 1e-12);
    /// }
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::Dimension`] unless both curves are planar; [`Error::InvalidArgument`] for a bad
    /// tolerance; [`Error::TooLarge`] if more than 2^20 sub-curve pairs would be examined.
    pub fn intersect(&self, other: &QueryCurve, tolerance: f64) -> Result<Vec<CurveIntersection>> {
        self.check_planar(other)?;
        check_tolerance("intersection tolerance", tolerance)?;
        let (fa, fb) = self.frame_with(other);
        let a: Vec<Sub> = (0..self.piece_count()).map(|k| fa.sub(k)).collect();
        let b: Vec<Sub> = (0..other.piece_count()).map(|k| fb.sub(k)).collect();
        let tol = tolerance / fa.scale;
        let raw = sub_pairs(&fa, &fb, pairs_from(&a, &b, &fa, &fb, tol), tol)?
            .into_iter()
            .map(|(ka, sa, kb, sb, g)| (self.global(ka, sa), other.global(kb, sb), g))
            .collect();
        Ok(self.assemble_global(other, raw, tolerance))
    }

    /// Self-intersections of a planar curve: each point where two different parameters meet,
    /// as [`CurveIntersection::Point`] with `t_a < t_b` (and overlaps of the curve with itself
    /// as intervals). Pieces whose hodograph does not lie in an open half-plane (which may loop)
    /// are halved until it does, so every loop is found; the shared ends of consecutive
    /// sub-curves, and a closed curve's start and end, are not intersections.
    ///
    /// # Errors
    /// As [`QueryCurve::intersect`].
    pub fn self_intersections(&self, tolerance: f64) -> Result<Vec<CurveIntersection>> {
        self.check_planar(self)?;
        check_tolerance("intersection tolerance", tolerance)?;
        let (fa, fb) = self.frame_with(self);
        let mut subs = Vec::new();
        for k in 0..self.piece_count() {
            let mut stack = vec![(fa.sub(k), 0_u32)];
            let mut done = Vec::new();
            while let Some((s, depth)) = stack.pop() {
                if depth >= 12 || hodograph_in_half_plane(&fa, &s.net) {
                    done.push(s);
                } else {
                    let (l, r) = halve(&fa, &s);
                    stack.push((r, depth + 1));
                    stack.push((l, depth + 1));
                }
            }
            subs.extend(done);
        }
        let tol = tolerance / fa.scale;
        let mut pairs = Vec::new();
        for i in 0..subs.len() {
            for j in i + 1..subs.len() {
                let (x, y) = (&subs[i], &subs[j]);
                if boxes_overlap(&fa.bbox(&x.net), &fb.bbox(&y.net), self.dim, tol) {
                    pairs.push((i, j, x.clone(), y.clone()));
                }
            }
        }
        let raw = sub_pairs(&fa, &fb, pairs, tol)?;
        let (lo, hi) = self.domain();
        let closed = dist(&self.point(lo)?, &self.point(hi)?) <= tolerance;
        let span = hi - lo;
        let keep = |&(ta, tb, _): &(f64, f64, f64)| {
            // a meeting of neighbouring parameters is the curve itself, not a crossing
            let (ta, tb) = (ta.min(tb), ta.max(tb));
            let trivial = tb - ta <= 1e-9 * span
                || (closed && ta - lo <= 1e-9 * span && hi - tb <= 1e-9 * span);
            !trivial
        };
        let mut raw: Vec<(f64, f64, f64)> = raw
            .into_iter()
            .map(|(ka, sa, kb, sb, g)| (self.global(ka, sa), self.global(kb, sb), g))
            .filter(|x| keep(x))
            .map(|(ta, tb, g)| (ta.min(tb), ta.max(tb), g))
            .collect();
        // one answer per crossing: solutions from several sub-curve pairs that meet at the same
        // pair of parameters (the gap to the curve itself cannot group them, it is zero)
        raw.sort_by(|x, y| x.0.total_cmp(&y.0).then(x.1.total_cmp(&y.1)));
        let mut out: Vec<(f64, f64, f64)> = Vec::new();
        for r in raw {
            if let Some(o) = out
                .iter_mut()
                .find(|o| (o.0 - r.0).abs() <= 1e-6 * span && (o.1 - r.1).abs() <= 1e-6 * span)
            {
                if r.2 < o.2 {
                    *o = r;
                }
                continue;
            }
            out.push(r);
        }
        Ok(out
            .into_iter()
            .map(|(t_a, t_b, _)| CurveIntersection::Point {
                t_a,
                t_b,
                point: self.point(t_a).unwrap_or_default(),
            })
            .collect())
    }

    fn check_planar(&self, other: &QueryCurve) -> Result<()> {
        for c in [self, other] {
            if c.dim != 2 {
                return Err(Error::Dimension {
                    what: "curves for a planar intersection",
                    expected: 2,
                    got: c.dim,
                });
            }
        }
        Ok(())
    }

    /// Groups raw solutions `(t_a, t_b, gap)` into answers: sorted by `t_a`, neighbours joined
    /// when the curve between them stays within the tolerance of `other`; a group whose gap
    /// stays below `tolerance / 100` over its extent (grown to where the gap exceeds the
    /// tolerance) is an overlap, otherwise its point of least gap is the answer.
    fn assemble_global(
        &self,
        other: &QueryCurve,
        mut raw: Vec<(f64, f64, f64)>,
        tolerance: f64,
    ) -> Vec<CurveIntersection> {
        raw.sort_by(|x, y| x.0.total_cmp(&y.0).then(x.1.total_cmp(&y.1)));
        let gap = |t: f64| -> (f64, CurveProjection) {
            let p = self.point(t).unwrap_or_default();
            match other.project(&p) {
                Ok(pr) => (pr.distance, pr),
                Err(_) => (
                    f64::INFINITY,
                    CurveProjection {
                        t: 0.0,
                        point: p,
                        distance: f64::INFINITY,
                    },
                ),
            }
        };
        let mut groups: Vec<Vec<(f64, f64, f64)>> = Vec::new();
        for r in raw {
            if let Some(g) = groups.last_mut() {
                let last = g[g.len() - 1];
                let same_b = (last.1 - r.1).abs() <= 0.5 * (other.domain().1 - other.domain().0);
                if same_b && gap(0.5 * (last.0 + r.0)).0 <= tolerance {
                    g.push(r);
                    continue;
                }
            }
            groups.push(vec![r]);
        }
        let (lo, hi) = self.domain();
        let mut out = Vec::new();
        for (gi, g) in groups.iter().enumerate() {
            let (mut a0, mut a1) = (g[0].0, g[g.len() - 1].0);
            // a single solution may still sit in an overlap or a tangential contact: the gap
            // stays tiny a little way to either side
            let probe = || {
                let h = 1e-6 * (hi - lo);
                [a0 - h, a1 + h]
                    .iter()
                    .filter(|t| **t >= lo && **t <= hi)
                    .all(|&t| gap(t).0 <= tolerance / 100.0)
            };
            if (g.len() > 1 && a1 > a0) || probe() {
                // grow to where the gap exceeds the tolerance (bisection, 60 steps each side)
                let left_lim = if gi > 0 {
                    groups[gi - 1][groups[gi - 1].len() - 1].0
                } else {
                    lo
                };
                let right_lim = groups.get(gi + 1).map_or(hi, |n| n[0].0);
                a0 = grow(a0, left_lim, |t| gap(t).0 <= tolerance);
                a1 = grow(a1, right_lim, |t| gap(t).0 <= tolerance);
                let coincide = (1..10).all(|i| {
                    let t = a0 + (a1 - a0) * f64::from(i) / 10.0;
                    gap(t).0 <= tolerance / 100.0
                });
                if coincide {
                    let (b0, b1) = (gap(a0).1.t, gap(a1).1.t);
                    out.push(CurveIntersection::Overlap {
                        a: (a0, a1),
                        b: (b0, b1),
                    });
                    continue;
                }
                // one contact: the least gap, by golden-section search on [a0, a1] (80 steps)
                let t = golden_min(a0, a1, |t| gap(t).0);
                let (_, pr) = gap(t);
                out.push(CurveIntersection::Point {
                    t_a: t,
                    t_b: pr.t,
                    point: self.point(t).unwrap_or_default(),
                });
                continue;
            }
            let best = g.iter().fold(g[0], |b, r| if r.2 < b.2 { *r } else { b });
            out.push(CurveIntersection::Point {
                t_a: best.0,
                t_b: best.1,
                point: self.point(best.0).unwrap_or_default(),
            });
        }
        out
    }

    /// Points where the curve meets the plane (hyperplane) through `origin` with normal
    /// `normal`: the roots of the signed distance `(C(s) − origin)·n`, whose Bernstein
    /// coefficients are those of the control points, so none is missed; a touching root is one
    /// answer. Returns `(t, point)` sorted by `t`; a curve lying in the plane gives its pieces'
    /// middles.
    ///
    /// # Errors
    /// [`Error::Dimension`] / [`Error::NonFinite`] for bad plane data; [`Error::InvalidArgument`]
    /// for a zero normal.
    pub fn intersect_plane(&self, origin: &[f64], normal: &[f64]) -> Result<Vec<(f64, Vec<f64>)>> {
        check_query("plane origin", origin, self.dim)?;
        check_query("plane normal", normal, self.dim)?;
        let nn = normal.iter().map(|x| x * x).sum::<f64>().sqrt();
        if !(nn > 0.0) {
            return Err(Error::InvalidArgument {
                what: "plane normal",
                reason: "it is the zero vector".into(),
            });
        }
        let n: Vec<f64> = normal.iter().map(|x| x / nn).collect();
        let mut o = vec![0.0; self.dim];
        self.normalise(origin, &mut o);
        let mut out: Vec<(f64, Vec<f64>)> = Vec::new();
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
            for s in bern_roots(&Bern(coef), 64.0 * f64::EPSILON * mag) {
                let t = self.global(k, s);
                if out
                    .last()
                    .is_some_and(|(u, _)| (t - u).abs() <= 1e-12 * (1.0 + t.abs()))
                {
                    continue;
                }
                out.push((t, self.eval_global(t, 0, &mut scratch)));
            }
        }
        Ok(out)
    }

    /// Points where the curve meets a surface within `tolerance`: subdivision of the curve's
    /// pieces and the surface's patches while their boxes overlap, then Levenberg–Marquardt on
    /// `C(t) = S(u, v)`. Returns `(t, (u, v), point)` sorted by `t`, nearby solutions (closer
    /// than the tolerance) merged.
    ///
    /// # Errors
    /// [`Error::Dimension`] for different dimensions; [`Error::InvalidArgument`] for a bad
    /// tolerance; [`Error::TooLarge`] beyond 2^20 examined pairs.
    pub fn intersect_surface(
        &self,
        surface: &QuerySurface,
        tolerance: f64,
    ) -> Result<Vec<SurfaceHit>> {
        if surface.dim != self.dim {
            return Err(Error::Dimension {
                what: "surface for a curve–surface intersection",
                expected: self.dim,
                got: surface.dim,
            });
        }
        check_tolerance("intersection tolerance", tolerance)?;
        let mut found: Vec<(f64, (f64, f64), Vec<f64>)> = Vec::new();
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
                            what: "curve-surface sub-pairs",
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
                        if let Some((t, u, v, p)) =
                            self.curve_surface_newton(k, surface, pk, x0, &mut scratch)
                        {
                            if dist(&p.0, &p.1) <= tolerance {
                                found.push((t, surface.global_uv(pk, u, v), p.0));
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
        let mut out: Vec<(f64, (f64, f64), Vec<f64>)> = Vec::new();
        for f in found {
            if out.last().is_some_and(|o| dist(&o.2, &f.2) <= tolerance) {
                continue;
            }
            out.push(f);
        }
        Ok(out)
    }

    /// Levenberg–Marquardt for `C(s) = S(u, v)` (local parameters of piece `k` and patch `pk`),
    /// at most 60 steps; returns the global `t`, local `(u, v)` and both points (original
    /// coordinates).
    #[allow(clippy::type_complexity)]
    fn curve_surface_newton(
        &self,
        k: usize,
        surf: &QuerySurface,
        pk: usize,
        x0: [f64; 3],
        scratch: &mut Vec<f64>,
    ) -> Option<(f64, f64, f64, (Vec<f64>, Vec<f64>))> {
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
        let mut x = x0;
        let (c, s, ..) = eval(&x, scratch);
        let mut gap = dist(&c, &s);
        let mut lambda = 1e-12;
        for _ in 0..60 {
            let (c, s, dc, su, sv) = eval(&x, scratch);
            let r: Vec<f64> = c.iter().zip(&s).map(|(a, b)| a - b).collect();
            let cols = [
                dc,
                su.iter().map(|v| -v).collect::<Vec<_>>(),
                sv.iter().map(|v| -v).collect(),
            ];
            let mut a = [[0.0; 3]; 3];
            let mut g = [0.0; 3];
            for i in 0..3 {
                for j in 0..3 {
                    a[i][j] = super::pieces::dot(&cols[i], &cols[j]);
                }
                g[i] = super::pieces::dot(&cols[i], &r);
            }
            let mut improved = false;
            for _ in 0..20 {
                let mut m = a;
                for i in 0..3 {
                    m[i][i] = a[i][i] * (1.0 + lambda) + 1e-300;
                }
                let Some(d) = solve3(m, [-g[0], -g[1], -g[2]]) else {
                    lambda *= 10.0;
                    continue;
                };
                let nx = [
                    (x[0] + d[0]).clamp(0.0, 1.0),
                    (x[1] + d[1]).clamp(0.0, 1.0),
                    (x[2] + d[2]).clamp(0.0, 1.0),
                ];
                let (c2, s2, ..) = eval(&nx, scratch);
                let g2 = dist(&c2, &s2);
                if g2 < gap {
                    let moved: f64 = (0..3).map(|i| (nx[i] - x[i]).abs()).sum();
                    x = nx;
                    gap = g2;
                    lambda = (lambda * 0.1).max(1e-15);
                    improved = moved > 1e-16;
                    break;
                }
                lambda *= 10.0;
                if lambda > 1e12 {
                    break;
                }
            }
            if !improved || gap == 0.0 {
                break;
            }
        }
        let (c, s, ..) = eval(&x, scratch);
        Some((self.global(k, x[0]), x[1], x[2], (c, s)))
    }
}

/// Solves a 3×3 system by Cramer's rule (None when singular).
fn solve3(m: [[f64; 3]; 3], b: [f64; 3]) -> Option<[f64; 3]> {
    let det = |m: &[[f64; 3]; 3]| {
        m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
            - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
            + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
    };
    let d = det(&m);
    if !(d.abs() > 0.0) || !d.is_finite() {
        return None;
    }
    let mut x = [0.0; 3];
    for i in 0..3 {
        let mut mi = m;
        for r in 0..3 {
            mi[r][i] = b[r];
        }
        x[i] = det(&mi) / d;
    }
    Some(x)
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

/// Whether every hodograph vector (differences of the control points) lies in one open
/// half-plane: then the sub-curve turns by less than π and cannot cross itself.
fn hodograph_in_half_plane(f: &Framed<'_>, net: &[f64]) -> bool {
    let hd = f.c.hd;
    let pts: Vec<Vec<f64>> = net.chunks_exact(hd).map(|p| f.cart(p)).collect();
    let diffs: Vec<[f64; 2]> = pts
        .windows(2)
        .map(|w| [w[1][0] - w[0][0], w[1][1] - w[0][1]])
        .filter(|d| d[0] != 0.0 || d[1] != 0.0)
        .collect();
    if diffs.is_empty() {
        return true;
    }
    // the half-plane test: the angular spread of the directions is below π
    let mut angles: Vec<f64> = diffs.iter().map(|d| d[1].atan2(d[0])).collect();
    angles.sort_by(f64::total_cmp);
    let n = angles.len();
    let mut max_gap = angles[0] + std::f64::consts::TAU - angles[n - 1];
    for w in angles.windows(2) {
        max_gap = max_gap.max(w[1] - w[0]);
    }
    max_gap > std::f64::consts::PI + 1e-12
}

/// The piece pairs of two curves whose boxes overlap (within `tol`).
#[allow(clippy::type_complexity)]
fn pairs_from(
    a: &[Sub],
    b: &[Sub],
    fa: &Framed<'_>,
    fb: &Framed<'_>,
    tol: f64,
) -> Vec<(usize, usize, Sub, Sub)> {
    let bb: Vec<Vec<f64>> = b.iter().map(|y| fb.bbox(&y.net)).collect();
    let mut out = Vec::new();
    for (i, x) in a.iter().enumerate() {
        let xb = fa.bbox(&x.net);
        for (j, y) in b.iter().enumerate() {
            if boxes_overlap(&xb, &bb[j], fa.c.dim, tol) {
                out.push((i, j, x.clone(), y.clone()));
            }
        }
    }
    out
}

/// Subdivides overlapping pairs until both are flat, then solves each flat pair; returns
/// `(piece a, s, piece b, u, gap)` of the solutions within `tol` (normalised).
#[allow(clippy::type_complexity)]
fn sub_pairs(
    fa: &Framed<'_>,
    fb: &Framed<'_>,
    pairs: Vec<(usize, usize, Sub, Sub)>,
    tol: f64,
) -> Result<Vec<(usize, f64, usize, f64, f64)>> {
    let dim = fa.c.dim;
    let mut stack: Vec<(Sub, Sub, u32)> = pairs.into_iter().map(|(_, _, x, y)| (x, y, 0)).collect();
    let mut visited = 0_usize;
    let mut out = Vec::new();
    while let Some((x, y, depth)) = stack.pop() {
        visited += 1;
        if visited > MAX_PAIRS {
            return Err(Error::TooLarge {
                what: "sub-curve pairs examined by the intersection",
                size: visited,
                max: MAX_PAIRS,
            });
        }
        let (xb, yb) = (fa.bbox(&x.net), fb.bbox(&y.net));
        if !boxes_overlap(&xb, &yb, dim, tol) {
            continue;
        }
        let (xd, yd) = (dist(&xb[..dim], &xb[dim..]), dist(&yb[..dim], &yb[dim..]));
        let x_flat = xd <= tol || fa.flatness(&x.net) <= 1e-2 * xd;
        let y_flat = yd <= tol || fb.flatness(&y.net) <= 1e-2 * yd;
        if (x_flat && y_flat) || depth >= MAX_DEPTH {
            let s0 = 0.5 * (x.s.0 + x.s.1);
            let u0 = 0.5 * (y.s.0 + y.s.1);
            let (s, u, gap) = solve_pair(fa, x.k, fb, y.k, s0, u0);
            if gap <= tol {
                out.push((x.k, s, y.k, u, gap));
            }
            continue;
        }
        if !x_flat && (y_flat || xd >= yd) {
            let (l, r) = halve(fa, &x);
            stack.push((l, y.clone(), depth + 1));
            stack.push((r, y, depth + 1));
        } else {
            let (l, r) = halve(fb, &y);
            stack.push((x.clone(), l, depth + 1));
            stack.push((x, r, depth + 1));
        }
    }
    Ok(out)
}

/// Moves `from` towards `limit` while `ok` holds: steps doubling from `1e-12·|limit − from|`
/// (at most 64) find the first point where it fails, then bisection (60 steps) the last point
/// where it holds. Returns `from` when it fails at once.
fn grow(from: f64, limit: f64, ok: impl Fn(f64) -> bool) -> f64 {
    let span = limit - from;
    if span == 0.0 {
        return from;
    }
    let mut good = from;
    let mut h = 1e-12 * span;
    let mut bad = limit;
    let mut reached = true;
    for _ in 0..64 {
        let t = from + h;
        if (span > 0.0 && t >= limit) || (span < 0.0 && t <= limit) {
            break;
        }
        if ok(t) {
            good = t;
            h *= 2.0;
        } else {
            bad = t;
            reached = false;
            break;
        }
    }
    if reached && ok(limit) {
        return limit;
    }
    for _ in 0..60 {
        let m = 0.5 * (good + bad);
        if m == good || m == bad {
            break;
        }
        if ok(m) {
            good = m;
        } else {
            bad = m;
        }
    }
    good
}

/// Minimum of `f` on `[a, b]` by golden-section search, 80 steps.
fn golden_min(a: f64, b: f64, f: impl Fn(f64) -> f64) -> f64 {
    let r = 0.5 * (5f64.sqrt() - 1.0);
    let (mut a, mut b) = (a, b);
    let mut c = b - r * (b - a);
    let mut d = a + r * (b - a);
    let (mut fc, mut fd) = (f(c), f(d));
    for _ in 0..80 {
        if fc <= fd {
            b = d;
            d = c;
            fd = fc;
            c = b - r * (b - a);
            fc = f(c);
        } else {
            a = c;
            c = d;
            fc = fd;
            d = a + r * (b - a);
            fd = f(d);
        }
        if b - a <= 1e-16 * (1.0 + a.abs()) {
            break;
        }
    }
    0.5 * (a + b)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{BSplineCurve, NurbsCurve, Points};

    fn line(a: [f64; 2], b: [f64; 2]) -> QueryCurve {
        let c = BSplineCurve::new(
            1,
            vec![0.0, 0.0, 1.0, 1.0],
            Points::from_2d(&[a, b]).unwrap(),
        )
        .unwrap();
        QueryCurve::from_bspline(&c).unwrap()
    }

    fn circle(r: f64) -> QueryCurve {
        QueryCurve::from_nurbs(
            &NurbsCurve::circle(&[0.0, 0.0], &[1.0, 0.0], &[0.0, 1.0], r).unwrap(),
        )
        .unwrap()
    }

    #[test]
    fn tangent_line_gives_one_point() {
        let hits = circle(1.0)
            .intersect(&line([-2.0, 1.0], [2.0, 1.0]), 1e-9)
            .unwrap();
        assert_eq!(hits.len(), 1, "{hits:?}");
        match &hits[0] {
            CurveIntersection::Point { point, .. } => {
                assert!(
                    point[0].abs() < 1e-4 && (point[1] - 1.0).abs() < 1e-8,
                    "{point:?}"
                );
            }
            CurveIntersection::Overlap { .. } => panic!("tangency reported as overlap"),
        }
    }

    #[test]
    fn overlapping_lines_give_an_interval() {
        let hits = line([0.0, 0.0], [2.0, 0.0])
            .intersect(&line([1.0, 0.0], [3.0, 0.0]), 1e-9)
            .unwrap();
        assert_eq!(hits.len(), 1, "{hits:?}");
        match hits[0] {
            CurveIntersection::Overlap { a, b } => {
                assert!(
                    (a.0 - 0.5).abs() < 1e-9 && (a.1 - 1.0).abs() < 1e-12,
                    "{a:?}"
                );
                assert!(b.0.abs() < 1e-9 && (b.1 - 0.5).abs() < 1e-9, "{b:?}");
            }
            CurveIntersection::Point { .. } => panic!("overlap reported as a point"),
        }
    }

    #[test]
    fn crossing_points_lie_on_both() {
        let a = circle(1.0);
        let b = circle(1.2);
        assert!(a.intersect(&b, 1e-9).unwrap().is_empty(), "concentric");
        let shifted = QueryCurve::from_nurbs(
            &NurbsCurve::circle(&[1.0, 0.3], &[1.0, 0.0], &[0.0, 1.0], 1.0).unwrap(),
        )
        .unwrap();
        let hits = a.intersect(&shifted, 1e-10).unwrap();
        assert_eq!(hits.len(), 2, "{hits:?}");
        for h in hits {
            let CurveIntersection::Point { t_a, t_b, point } = h else {
                panic!("not a point")
            };
            assert!(dist(&a.point(t_a).unwrap(), &point) < 1e-12, "on a");
            assert!(dist(&shifted.point(t_b).unwrap(), &point) < 1e-10, "on b");
        }
    }

    #[test]
    fn loop_of_a_cubic() {
        let c = BSplineCurve::new(
            3,
            vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0],
            Points::from_2d(&[[0.0, 0.0], [3.0, 2.0], [-1.0, 2.0], [2.0, 0.0]]).unwrap(),
        )
        .unwrap();
        let q = QueryCurve::from_bspline(&c).unwrap();
        let hits = q.self_intersections(1e-10).unwrap();
        assert_eq!(hits.len(), 1, "{hits:?}");
        let CurveIntersection::Point { t_a, t_b, .. } = hits[0] else {
            panic!("not a point")
        };
        assert!(t_a < t_b, "ordered");
        assert!(
            dist(&q.point(t_a).unwrap(), &q.point(t_b).unwrap()) < 1e-9,
            "same point"
        );
        // a circle does not cross itself
        assert!(
            circle(1.0).self_intersections(1e-10).unwrap().is_empty(),
            "circle"
        );
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
        for (_, p) in &hits {
            assert!(p[2].abs() < 1e-15, "{p:?}");
        }
        // touching the plane z = 1 at the top: one answer
        let touch = q
            .intersect_plane(&[0.0, 0.0, 1.0], &[0.0, 0.0, 1.0])
            .unwrap();
        assert_eq!(touch.len(), 1, "{touch:?}");
        assert!((touch[0].0 - 0.5).abs() < 1e-6, "{touch:?}");
    }
}
