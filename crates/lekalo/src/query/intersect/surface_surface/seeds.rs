//! Starting points of the marching (`docs/theory/queries.md#starting-points`): the patches are
//! subdivided while their boxes overlap until no closed loop can hide inside a pair (the normal
//! cones are disjoint, Sederberg and Meyers 1988) or the pair is tiny; then points on the sides
//! of the pair's sub-patches (and one from the middle) are solved for by Newton's method. A
//! plane section works on the signed distance's Bernstein coefficients: exact pruning, exact
//! roots on the sides.

use super::super::super::pieces::{bern_roots, dist, dot, Bern};
use super::super::super::surface::{QuerySurface, SubNet};
use super::super::{boxes_overlap, MAX_PAIRS};
use super::system::{cross, newton, newton_within, norm, surface_jet, System, K};
use crate::error::{Error, Result};
use std::rc::Rc;

/// Sub-patch pairs whose normal cones are disjoint are searched from their sides once both are
/// at most this fraction of the scale across.
const LEAF: f64 = 0.125;
/// Pairs whose cones overlap are subdivided down to this fraction of the scale.
const TINY: f64 = 1.0 / 512.0;
/// Deepest subdivision (splits of either sub-patch).
const MAX_DEPTH: u32 = 40;
/// A leaf pair's Newton solves are given up once an iterate leaves the pair's parameter ranges
/// widened by this share of their widths on every side: a point of the intersection inside the
/// pair is reached from the pair's middles without going that far, and a point outside it is
/// the business of the pair that holds it.
const REGION: f64 = 0.5;

/// What the search found: starting points, and the middles of sub-patch pairs on which the
/// surfaces coincide.
#[derive(Debug, Default)]
pub(super) struct Found {
    pub(super) seeds: Vec<[f64; K]>,
    pub(super) overlaps: Vec<[f64; K]>,
}

/// A patch net in original coordinates (homogeneous for a rational surface).
fn original_net(s: &QuerySurface, k: usize) -> Vec<f64> {
    let mut out = s.patch(k).to_vec();
    for p in out.chunks_exact_mut(s.hd) {
        let w = if s.rational { p[s.dim] } else { 1.0 };
        for d in 0..s.dim {
            p[d] = w * s.centre[d] + s.scale * p[d];
        }
    }
    out
}

/// Control point `(i, j)` of a net, Cartesian.
fn net_point(s: &QuerySurface, net: &[f64], i: usize, j: usize) -> [f64; 3] {
    let c = &net[(i * (s.q + 1) + j) * s.hd..];
    let w = if s.rational { c[3] } else { 1.0 };
    [c[0] / w, c[1] / w, c[2] / w]
}

/// A cone holding every normal of a sub-patch: `S_u × S_v` is a combination with positive
/// weights of the products `ΔᵤPᵢⱼ × ΔᵥPₖₗ` of the net's differences, so their cone holds it
/// (for a rational net, the differences of the Cartesian points: a close bound, not a proof).
/// Its unit axis (the mean direction) and half-angle; `None` when it is not within a half-space
/// (`> 0.45π`), where it excludes nothing.
fn normal_cone(s: &QuerySurface, net: &[f64]) -> Option<([f64; 3], f64)> {
    let (p, q) = (s.p, s.q);
    let sub = |a: [f64; 3], b: [f64; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    let mut du = Vec::with_capacity(p * (q + 1));
    for i in 0..p {
        for j in 0..=q {
            du.push(sub(net_point(s, net, i + 1, j), net_point(s, net, i, j)));
        }
    }
    let mut dv = Vec::with_capacity((p + 1) * q);
    for i in 0..=p {
        for j in 0..q {
            dv.push(sub(net_point(s, net, i, j + 1), net_point(s, net, i, j)));
        }
    }
    let big = du
        .iter()
        .chain(&dv)
        .map(|d| norm(d))
        .fold(0.0_f64, f64::max);
    // the unit products, visited twice (their sum, then the widest angle from it) rather than
    // stored
    let units = || {
        du.iter().flat_map(|a| {
            dv.iter().filter_map(move |b| {
                let n = cross(a, b);
                let l = norm(&n);
                (l > 1e-12 * big * big).then(|| [n[0] / l, n[1] / l, n[2] / l])
            })
        })
    };
    let mut axis = [0.0; 3];
    for n in units() {
        for c in 0..3 {
            axis[c] += n[c];
        }
    }
    let l = norm(&axis);
    if !(l > 0.0) {
        return None;
    }
    let axis = [axis[0] / l, axis[1] / l, axis[2] / l];
    // the widest angle is that of the smallest cosine (acos decreases)
    let half = units()
        .map(|n| dot(&n, &axis).clamp(-1.0, 1.0))
        .fold(1.0_f64, f64::min)
        .acos();
    (half < 0.45 * std::f64::consts::PI).then_some((axis, half))
}

/// Whether no line is normal to both sub-patches: the double cones `±cone` are disjoint. A closed
/// intersection loop inside a pair needs a pair of parallel normals (Sederberg and Meyers 1988;
/// Hohmeyer 1991), so without one every branch in the pair reaches the side of a sub-patch.
fn loop_free(a: Option<([f64; 3], f64)>, b: Option<([f64; 3], f64)>) -> bool {
    let (Some((x, ax)), Some((y, by))) = (a, b) else {
        return false;
    };
    let theta = dot(&x, &y).clamp(-1.0, 1.0).acos();
    theta.min(std::f64::consts::PI - theta) > ax + by
}

/// A direction across a sub-patch: the cross product of its net's diagonals (the normal at its
/// middle for a flat enough patch), unit; `None` when they are parallel.
fn across(s: &QuerySurface, net: &[f64]) -> Option<[f64; 3]> {
    let (p, q) = (s.p, s.q);
    let d = |a: [f64; 3], b: [f64; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    let n = cross(
        &d(net_point(s, net, p, q), net_point(s, net, 0, 0)),
        &d(net_point(s, net, p, 0), net_point(s, net, 0, q)),
    );
    let l = norm(&n);
    (l > 0.0 && l.is_finite()).then(|| [n[0] / l, n[1] / l, n[2] / l])
}

/// The interval of `n·P` over a net's control points (Cartesian): it holds `n·S` of the whole
/// sub-patch (convex hull property; positive weights for a rational net).
fn slab(s: &QuerySurface, net: &[f64], n: &[f64; 3]) -> (f64, f64) {
    net.chunks_exact(s.hd)
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), c| {
            let w = if s.rational { c[3] } else { 1.0 };
            let x = (n[0] * c[0] + n[1] * c[1] + n[2] * c[2]) / w;
            (lo.min(x), hi.max(x))
        })
}

/// Whether a plane separates two sub-patches by more than `tol`: the slabs of their control
/// points along the direction across either one are disjoint (a separating-axis test; for a
/// sub-patch nearly flat across its own direction the slab is thin, so it prunes pairs that
/// their boxes, tilted to the axes, do not).
fn separated(sa: &QuerySurface, na: &[f64], sb: &QuerySurface, nb: &[f64], tol: f64) -> bool {
    [across(sa, na), across(sb, nb)].iter().flatten().any(|n| {
        let (a, b) = (slab(sa, na, n), slab(sb, nb, n));
        a.1 + tol < b.0 || b.1 + tol < a.0
    })
}

/// A direction across a sub-patch and the interval of its control points along it.
type Slab = ([f64; 3], (f64, f64));

/// Global parameters of local `t` in a sub-range `r` of patch range `g`.
fn global(g: (f64, f64), r: (f64, f64), t: f64) -> f64 {
    g.0 + (r.0 + t * (r.1 - r.0)) * (g.1 - g.0)
}

/// Closest point of `s` to `p` by Gauss–Newton from `(u, v)` (at most 12 steps, kept in the
/// domain): its distance, and whether the step was held at a side of the domain (the foot lies
/// beyond the surface's edge).
pub(super) fn distance_to(s: &QuerySurface, p: &[f64; 3], mut u: f64, mut v: f64) -> (f64, bool) {
    let ((u0, u1), (v0, v1)) = s.domain();
    let mut best = f64::INFINITY;
    let mut held = false;
    for _ in 0..12 {
        let Some([q, su, sv]) = surface_jet(s, u, v) else {
            break;
        };
        let r = [p[0] - q[0], p[1] - q[1], p[2] - q[2]];
        best = best.min(norm(&r));
        let (a, b, c) = (dot(&su, &su), dot(&su, &sv), dot(&sv, &sv));
        let (g0, g1) = (dot(&su, &r), dot(&sv, &r));
        let det = a * c - b * b;
        if !(det > 0.0) {
            break;
        }
        let (nu, nv) = (u + (g0 * c - g1 * b) / det, v + (a * g1 - b * g0) / det);
        held = !(nu >= u0 && nu <= u1 && nv >= v0 && nv <= v1);
        u = nu.clamp(u0, u1);
        v = nv.clamp(v0, v1);
    }
    (best, held)
}

/// Whether two sub-patches coincide within `tol`: of 3 × 3 points of each, every one within
/// `tol` of the other surface or beyond its edge, and at least one within `tol`.
#[allow(clippy::too_many_arguments)]
fn coincide(
    a: &QuerySurface,
    (ka, ua, va, na): (usize, (f64, f64), (f64, f64), &[f64]),
    b: &QuerySurface,
    (kb, ub, vb, nb): (usize, (f64, f64), (f64, f64), &[f64]),
    tol: f64,
) -> bool {
    // the middle of the other sub-patch starts each projection
    let one_way = |s: &QuerySurface, net: &[f64], o: &QuerySurface, start: (f64, f64)| {
        let mut on = 0;
        for i in 0..3 {
            for j in 0..3 {
                let (pt, _) = s.eval_net(net, f64::from(i) / 2.0, f64::from(j) / 2.0);
                let (d, beyond) = distance_to(o, &[pt[0], pt[1], pt[2]], start.0, start.1);
                if d <= tol {
                    on += 1;
                } else if !beyond {
                    return false;
                }
            }
        }
        on > 0
    };
    let (ga, gb) = (a.ranges[ka], b.ranges[kb]);
    let mid_a = (global(ga.0, ua, 0.5), global(ga.1, va, 0.5));
    let mid_b = (global(gb.0, ub, 0.5), global(gb.1, vb, 0.5));
    one_way(a, na, b, mid_b) && one_way(b, nb, a, mid_a)
}

/// A node of the search over two surfaces: patch indices, local ranges and nets of both.
struct Pair {
    ka: usize,
    a: Rc<Sub>,
    kb: usize,
    b: Rc<Sub>,
    depth: u32,
}

/// A sub-patch of the search: local ranges and net (in `.0`), and the box of its control points
/// (minima then maxima), computed once and shared by every pair it is in.
struct Sub(SubNet, [f64; 6]);

impl Sub {
    fn new(s: &QuerySurface, net: SubNet) -> Rc<Sub> {
        let mut b = [
            f64::INFINITY,
            f64::INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NEG_INFINITY,
            f64::NEG_INFINITY,
        ];
        for c in net.2.chunks_exact(s.hd) {
            let w = if s.rational { c[3] } else { 1.0 };
            for d in 0..3 {
                let x = c[d] / w;
                b[d] = b[d].min(x);
                b[3 + d] = b[3 + d].max(x);
            }
        }
        Rc::new(Sub(net, b))
    }
}

/// The starting points of the intersection of two 3-D surfaces, as the module describes, solved
/// to a residual of a hundredth of the tolerance (or `eps` if larger): most land on a branch
/// already traced and are dropped, and the marching corrects the others to `eps` first.
pub(super) fn surface_seeds(
    sa: &QuerySurface,
    sb: &QuerySurface,
    sys: &dyn System,
    tol: f64,
    scale: f64,
    eps: f64,
) -> Result<Found> {
    let mut found = Found::default();
    let nets_a: Vec<Vec<f64>> = (0..sa.patch_count()).map(|k| original_net(sa, k)).collect();
    let nets_b: Vec<Vec<f64>> = (0..sb.patch_count()).map(|k| original_net(sb, k)).collect();
    let mut stack = Vec::new();
    for (ka, na) in nets_a.iter().enumerate() {
        for (kb, nb) in nets_b.iter().enumerate() {
            stack.push(Pair {
                ka,
                a: Sub::new(sa, ((0.0, 1.0), (0.0, 1.0), na.clone())),
                kb,
                b: Sub::new(sb, ((0.0, 1.0), (0.0, 1.0), nb.clone())),
                depth: 0,
            });
        }
    }
    let mut visited = 0_usize;
    while let Some(pair) = stack.pop() {
        visited += 1;
        if visited > MAX_PAIRS {
            return Err(Error::TooLarge {
                what: "surface-surface sub-patch pairs".into(),
                size: visited,
                max: MAX_PAIRS,
            });
        }
        let (box_a, box_b) = (pair.a.1, pair.b.1);
        if !boxes_overlap(&box_a, &box_b, 3, tol)
            || separated(sa, &pair.a.0 .2, sb, &pair.b.0 .2, tol)
        {
            continue;
        }
        let da = dist(&box_a[..3], &box_a[3..]);
        let db = dist(&box_b[..3], &box_b[3..]);
        let size = da.max(db);
        // the cones decide only among pairs small enough to be leaves
        let free = size <= LEAF * scale
            && loop_free(normal_cone(sa, &pair.a.0 .2), normal_cone(sb, &pair.b.0 .2));
        if free || size <= TINY * scale || pair.depth >= MAX_DEPTH {
            leaf_seeds(
                sa,
                sb,
                (&pair, free),
                (&box_a, &box_b),
                sys,
                (1e-2 * tol).max(eps),
                tol,
                &mut found.seeds,
            );
            continue;
        }
        if !free
            && size <= LEAF * scale
            && size >= 4.0 * (tol * scale).sqrt()
            && coincide(
                sa,
                (pair.ka, pair.a.0 .0, pair.a.0 .1, &pair.a.0 .2),
                sb,
                (pair.kb, pair.b.0 .0, pair.b.0 .1, &pair.b.0 .2),
                tol,
            )
        {
            let (ga, gb) = (sa.ranges[pair.ka], sb.ranges[pair.kb]);
            found.overlaps.push([
                global(ga.0, pair.a.0 .0, 0.5),
                global(ga.1, pair.a.0 .1, 0.5),
                global(gb.0, pair.b.0 .0, 0.5),
                global(gb.1, pair.b.0 .1, 0.5),
            ]);
            continue;
        }
        let d = pair.depth + 1;
        if da >= db {
            for a in sa.split4(&pair.a.0 .2, pair.a.0 .0, pair.a.0 .1) {
                stack.push(Pair {
                    ka: pair.ka,
                    a: Sub::new(sa, a),
                    kb: pair.kb,
                    b: Rc::clone(&pair.b),
                    depth: d,
                });
            }
        } else {
            for b in sb.split4(&pair.b.0 .2, pair.b.0 .0, pair.b.0 .1) {
                stack.push(Pair {
                    ka: pair.ka,
                    a: Rc::clone(&pair.a),
                    kb: pair.kb,
                    b: Sub::new(sb, b),
                    depth: d,
                });
            }
        }
    }
    Ok(found)
}

/// Whether the side of a sub-patch net (`i = 0`, `i = p`, `j = 0`, `j = q` for `side` 0 to 3) can
/// meet the other sub-patch, whose box is `other` (minima then maxima) and whose slab across its
/// direction `n` is `(n, lo, hi)` (see [`slab`]), within `tol`: the box of the side's control
/// points holds the side (convex hull property, positive weights) and must overlap the box, and
/// their interval along `n` must meet the slab.
fn side_meets(
    s: &QuerySurface,
    net: &[f64],
    side: usize,
    (other, across): (&[f64], Option<Slab>),
    tol: f64,
) -> bool {
    let (p, q) = (s.p, s.q);
    let pts: Vec<[f64; 3]> = match side {
        0 => (0..=q).map(|j| net_point(s, net, 0, j)).collect(),
        1 => (0..=q).map(|j| net_point(s, net, p, j)).collect(),
        2 => (0..=p).map(|i| net_point(s, net, i, 0)).collect(),
        _ => (0..=p).map(|i| net_point(s, net, i, q)).collect(),
    };
    let in_box = (0..3).all(|c| {
        let lo = pts.iter().map(|x| x[c]).fold(f64::INFINITY, f64::min);
        let hi = pts.iter().map(|x| x[c]).fold(f64::NEG_INFINITY, f64::max);
        lo <= other[3 + c] + tol && other[c] <= hi + tol
    });
    in_box
        && across.is_none_or(|(n, (lo, hi))| {
            let (a, b) = pts
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| {
                    let d = dot(&n, x);
                    (a.min(d), b.max(d))
                });
            a <= hi + tol && lo <= b + tol
        })
}

/// Seeds of a leaf pair: Newton's method with one unknown held on each of the eight sides of the
/// two sub-patches (from the side's middle and the other's middle) whose control points' box
/// meets the other sub-patch's box and whose control points' interval across the other
/// sub-patch meets its slab (a side that does not cannot hold a point of the intersection), and,
/// unless the pair is `free` of closed loops (its normal cones disjoint, so that every branch in
/// it crosses a side), the free minimum-norm Newton from both middles; the points it reaches
/// within a tenth of the tolerance. Every solve is given up once it leaves the pair's ranges
/// widened by [`REGION`].
#[allow(clippy::too_many_arguments)]
fn leaf_seeds(
    sa: &QuerySurface,
    sb: &QuerySurface,
    (pair, free): (&Pair, bool),
    (box_a, box_b): (&[f64], &[f64]),
    sys: &dyn System,
    eps: f64,
    tol: f64,
    out: &mut Vec<[f64; K]>,
) {
    let (ga, gb) = (sa.ranges[pair.ka], sb.ranges[pair.kb]);
    let (ua, va) = (pair.a.0 .0, pair.a.0 .1);
    let (ub, vb) = (pair.b.0 .0, pair.b.0 .1);
    let mid = [
        global(ga.0, ua, 0.5),
        global(ga.1, va, 0.5),
        global(gb.0, ub, 0.5),
        global(gb.1, vb, 0.5),
    ];
    let sides = [
        (0, global(ga.0, ua, 0.0)),
        (0, global(ga.0, ua, 1.0)),
        (1, global(ga.1, va, 0.0)),
        (1, global(ga.1, va, 1.0)),
        (2, global(gb.0, ub, 0.0)),
        (2, global(gb.0, ub, 1.0)),
        (3, global(gb.1, vb, 0.0)),
        (3, global(gb.1, vb, 1.0)),
    ];
    // the pair's ranges widened by REGION of their widths on every side
    let widen = |t0: f64, t1: f64| {
        let w = REGION * (t1 - t0);
        (t0 - w, t1 + w)
    };
    let region = [
        widen(global(ga.0, ua, 0.0), global(ga.0, ua, 1.0)),
        widen(global(ga.1, va, 0.0), global(ga.1, va, 1.0)),
        widen(global(gb.0, ub, 0.0), global(gb.0, ub, 1.0)),
        widen(global(gb.1, vb, 0.0), global(gb.1, vb, 1.0)),
    ];
    let k = sys.k();
    let mut push = |r: Option<([f64; K], super::system::Jet)>| {
        if let Some((x, j)) = r {
            if j.gap(k) <= 0.1 * tol {
                out.push(x);
            }
        }
    };
    if !free {
        push(newton_within(sys, mid, None, None, eps, Some(&region)));
    }
    let slab_of = |s: &QuerySurface, net: &[f64]| across(s, net).map(|n| (n, slab(s, net, &n)));
    let (across_a, across_b) = (slab_of(sa, &pair.a.0 .2), slab_of(sb, &pair.b.0 .2));
    for (n, (i, value)) in sides.into_iter().enumerate() {
        let meets = if n < 4 {
            side_meets(sa, &pair.a.0 .2, n, (box_b, across_b), tol)
        } else {
            side_meets(sb, &pair.b.0 .2, n - 4, (box_a, across_a), tol)
        };
        if !meets {
            continue;
        }
        let mut x = mid;
        x[i] = value;
        push(newton_within(sys, x, Some(i), None, eps, Some(&region)));
    }
}

/// The numerator `N = Σ cᵢⱼ BᵢBⱼ` of the signed distance of a (rational) patch net to the plane:
/// `cᵢⱼ = n·(P^w)ᵢⱼ − wᵢⱼ (n·o)`, zero exactly where the patch meets the plane; `(p + 1)(q + 1)`
/// coefficients, row-major in `u`.
fn plane_coefficients(s: &QuerySurface, net: &[f64], o: &[f64; 3], n: &[f64; 3]) -> Vec<f64> {
    let no = dot(n, o);
    net.chunks_exact(s.hd)
        .map(|c| {
            let w = if s.rational { c[3] } else { 1.0 };
            n[0] * c[0] + n[1] * c[1] + n[2] * c[2] - w * no
        })
        .collect()
}

/// The starting points of a plane section: the cells of the subdivision where the coefficients
/// of `N` change sign; a cell where the `u` or the `v` differences of the coefficients all have
/// one sign (`N` monotone in one direction, so no closed contour inside) gives the roots of `N`
/// on its four sides (Bernstein polynomials: none missed); a cell at depth 24 (in each
/// direction 12 halvings) gives Newton's point from its middle; a cell whose coefficients all
/// vanish (to `64ε` of their size) lies in the plane: an overlap.
pub(super) fn plane_seeds(
    s: &QuerySurface,
    sys: &dyn System,
    o: &[f64; 3],
    n: &[f64; 3],
    eps: f64,
    tol: f64,
) -> Result<Found> {
    let mut found = Found::default();
    let (p, q) = (s.p, s.q);
    let mut stack: Vec<(usize, SubNet, u32)> = (0..s.patch_count())
        .map(|k| (k, ((0.0, 1.0), (0.0, 1.0), original_net(s, k)), 0))
        .collect();
    let mut visited = 0_usize;
    while let Some((k, (ur, vr, net), depth)) = stack.pop() {
        visited += 1;
        if visited > MAX_PAIRS {
            return Err(Error::TooLarge {
                what: "plane-section cells".into(),
                size: visited,
                max: MAX_PAIRS,
            });
        }
        let c = plane_coefficients(s, &net, o, n);
        let mag = net
            .chunks_exact(s.hd)
            .map(|x| x.iter().map(|v| v.abs()).sum::<f64>() * (1.0 + norm(o)))
            .fold(0.0_f64, f64::max);
        let zero = 64.0 * f64::EPSILON * mag;
        let g = s.ranges[k];
        if c.iter().all(|x| x.abs() <= zero) {
            found
                .overlaps
                .push([global(g.0, ur, 0.5), global(g.1, vr, 0.5), 0.0, 0.0]);
            continue;
        }
        if c.iter().all(|&x| x > zero) || c.iter().all(|&x| x < -zero) {
            continue;
        }
        let at = |i: usize, j: usize| c[i * (q + 1) + j];
        // monotone beyond rounding: differences that are rounding noise (the distance constant
        // along a line of contact) may all share a sign by chance, and the sides alone would
        // then miss the contact's double roots
        let mono =
            |diffs: Vec<f64>| diffs.iter().all(|&d| d > zero) || diffs.iter().all(|&d| d < -zero);
        let du: Vec<f64> = (0..p)
            .flat_map(|i| (0..=q).map(move |j| (i, j)))
            .map(|(i, j)| at(i + 1, j) - at(i, j))
            .collect();
        let dv: Vec<f64> = (0..=p)
            .flat_map(|i| (0..q).map(move |j| (i, j)))
            .map(|(i, j)| at(i, j + 1) - at(i, j))
            .collect();
        if mono(du) || mono(dv) {
            // the roots of N on the four sides
            let sides: [(Vec<f64>, bool, f64); 4] = [
                ((0..=q).map(|j| at(0, j)).collect(), false, 0.0),
                ((0..=q).map(|j| at(p, j)).collect(), false, 1.0),
                ((0..=p).map(|i| at(i, 0)).collect(), true, 0.0),
                ((0..=p).map(|i| at(i, q)).collect(), true, 1.0),
            ];
            for (coef, along_u, fixed) in sides {
                for t in bern_roots(&Bern(coef), zero) {
                    let (lu, lv) = if along_u { (t, fixed) } else { (fixed, t) };
                    let x = [global(g.0, ur, lu), global(g.1, vr, lv), 0.0, 0.0];
                    if let Some((x, j)) = newton(sys, x, None, None, eps) {
                        if j.gap(2) <= 0.1 * tol {
                            found.seeds.push(x);
                        }
                    }
                }
            }
            continue;
        }
        if depth >= 24 {
            let x = [global(g.0, ur, 0.5), global(g.1, vr, 0.5), 0.0, 0.0];
            if let Some((x, j)) = newton(sys, x, None, None, eps) {
                if j.gap(2) <= 0.1 * tol {
                    found.seeds.push(x);
                }
            }
            continue;
        }
        for (u, v, sub) in s.split4(&net, ur, vr) {
            stack.push((k, (u, v, sub), depth + 2));
        }
    }
    Ok(found)
}
