//! The equations of a section, in the form the marching and the Newton solvers share
//! (`docs/theory/queries.md#surface-surface-intersection`): `k` unknowns (2 for a plane section,
//! `(u, v)`; 4 for two surfaces, `(u₁, v₁, u₂, v₂)`) and `k − 1` equations, with the point of the
//! first surface and its derivatives.

use super::super::super::pieces::dot;
use super::super::super::surface::QuerySurface;

/// The most unknowns of a section (two surfaces).
pub(super) const K: usize = 4;

/// What a section's equations give at a point of its parameter box.
#[derive(Debug, Clone)]
pub(super) struct Jet {
    /// The point of the first surface.
    pub(super) p: [f64; 3],
    /// The residual (`k − 1` entries used): `S₁ − S₂`, or the signed distance to the plane.
    pub(super) f: [f64; 3],
    /// Its Jacobian, `k − 1` rows of `k` columns.
    pub(super) j: [[f64; K]; 3],
    /// `∂p/∂xᵢ` for the `k` unknowns (zero for the second surface's).
    pub(super) dp: [[f64; 3]; K],
    /// Sine of the angle between the two normals (0 where the surfaces are tangent).
    pub(super) sin: f64,
}

impl Jet {
    /// The length of the residual (a distance in the surfaces' units).
    pub(super) fn gap(&self, k: usize) -> f64 {
        self.f[..k - 1].iter().map(|x| x * x).sum::<f64>().sqrt()
    }
}

/// A section's equations.
pub(super) trait System: Sync {
    /// Number of unknowns (2 or 4).
    fn k(&self) -> usize;
    /// The parameter box, one interval per unknown.
    fn bounds(&self) -> [(f64, f64); K];
    /// The jet at `x` (inside the bounds), `None` where a surface is degenerate.
    fn jet(&self, x: &[f64; K]) -> Option<Jet>;
    /// The first surface (whose point the jet gives).
    fn first(&self) -> &QuerySurface;
}

/// Patches of degree up to this in both directions are evaluated on the stack
/// ([`patch_first_order`]); higher degrees by `QuerySurface::eval_patch`.
const STACK_DEGREE: usize = 7;

/// The Bernstein polynomials `Bᵢⁿ(t)`, `i = 0..=n` (`n ≤ STACK_DEGREE`), and their derivatives
/// `n (Bᵢ₋₁ⁿ⁻¹(t) − Bᵢⁿ⁻¹(t))` (P&T §1.3, eqs. 1.7 and 1.9): the triangle
/// `Bⱼˡ = (1 − t) Bⱼˡ⁻¹ + t Bⱼ₋₁ˡ⁻¹` of positive terms on `[0, 1]`, computed once per direction
/// of a patch and shared by all its control points.
#[inline(always)]
fn bernstein_first(n: usize, t: f64) -> ([f64; STACK_DEGREE + 1], [f64; STACK_DEGREE + 1]) {
    let mut b = [0.0; STACK_DEGREE + 1];
    let mut d = [0.0; STACK_DEGREE + 1];
    b[0] = 1.0;
    let s = 1.0 - t;
    for level in 1..=n {
        if level == n {
            // b holds degree n − 1 here
            let nf = n as f64;
            for i in 0..=n {
                let lo = if i > 0 { b[i - 1] } else { 0.0 };
                let hi = if i < n { b[i] } else { 0.0 };
                d[i] = nf * (lo - hi);
            }
        }
        let mut prev = 0.0;
        for bj in b.iter_mut().take(level + 1) {
            let cur = *bj;
            *bj = s * cur + t * prev;
            prev = cur;
        }
    }
    (b, d)
}

/// Normalised point and local first derivatives of a (homogeneous, `hd` scalars a point) Bézier
/// patch net of degrees `(p, q) ≤ STACK_DEGREE` at local `(u, v)`, without allocating: the
/// Bernstein polynomials of both directions and their derivatives ([`bernstein_first`]), every
/// row's value and `v` derivative, then their combinations in `u` (the tensor product,
/// P&T §3.4 and eq. 3.17), then the quotient rule for a rational patch (P&T eq. 4.20).
fn patch_first_order(
    net: &[f64],
    (p, q, hd): (usize, usize, usize),
    rational: bool,
    u: f64,
    v: f64,
) -> [[f64; 3]; 3] {
    if hd == 4 {
        patch_first_order_n::<4>(net, (p, q), rational, u, v)
    } else {
        patch_first_order_n::<3>(net, (p, q), rational, u, v)
    }
}

/// [`patch_first_order`] for points of `HD` scalars (3: polynomial, 4: rational): the degrees
/// of the planes, cylinders, spheres, tori and bicubics met most are passed as constants, so
/// that the loops of [`tensor_first_order`] are unrolled for them.
fn patch_first_order_n<const HD: usize>(
    net: &[f64],
    (p, q): (usize, usize),
    rational: bool,
    u: f64,
    v: f64,
) -> [[f64; 3]; 3] {
    match (p, q) {
        (1, 1) => tensor_first_order::<HD>(net, (1, 1), rational, u, v),
        (2, 1) => tensor_first_order::<HD>(net, (2, 1), rational, u, v),
        (1, 2) => tensor_first_order::<HD>(net, (1, 2), rational, u, v),
        (2, 2) => tensor_first_order::<HD>(net, (2, 2), rational, u, v),
        (3, 3) => tensor_first_order::<HD>(net, (3, 3), rational, u, v),
        _ => tensor_first_order::<HD>(net, (p, q), rational, u, v),
    }
}

/// The body of [`patch_first_order_n`], inlined into each of its cases.
#[inline(always)]
fn tensor_first_order<const HD: usize>(
    net: &[f64],
    (p, q): (usize, usize),
    rational: bool,
    u: f64,
    v: f64,
) -> [[f64; 3]; 3] {
    let (bu, du) = bernstein_first(p, u);
    let (bv, dv) = bernstein_first(q, v);
    let (mut s, mut su, mut sv) = ([0.0; HD], [0.0; HD], [0.0; HD]);
    for (i, row) in net.chunks_exact((q + 1) * HD).take(p + 1).enumerate() {
        let (mut r, mut rv) = ([0.0; HD], [0.0; HD]);
        for (j, c) in row.chunks_exact(HD).enumerate() {
            for d in 0..HD {
                r[d] += bv[j] * c[d];
                rv[d] += dv[j] * c[d];
            }
        }
        for d in 0..HD {
            s[d] += bu[i] * r[d];
            su[d] += du[i] * r[d];
            sv[d] += bu[i] * rv[d];
        }
    }
    if !rational || HD < 4 {
        return [
            [s[0], s[1], s[2]],
            [su[0], su[1], su[2]],
            [sv[0], sv[1], sv[2]],
        ];
    }
    // the weight is the last scalar (HD = 4 here)
    let w = s[HD - 1];
    let pt = [s[0] / w, s[1] / w, s[2] / w];
    let mut out = [pt, [0.0; 3], [0.0; 3]];
    for d in 0..3 {
        out[1][d] = (su[d] - su[HD - 1] * pt[d]) / w;
        out[2][d] = (sv[d] - sv[HD - 1] * pt[d]) / w;
    }
    out
}

/// Point, `S_u` and `S_v` of a surface at global `(u, v)` (original coordinates): the patch
/// holding it (`QuerySurface::locate`) and its local derivatives over the patch's widths.
pub(super) fn surface_jet(s: &QuerySurface, u: f64, v: f64) -> Option<[[f64; 3]; 3]> {
    let (k, lu, lv) = s.locate(u, v).ok()?;
    let ((u0, u1), (v0, v1)) = s.ranges[k];
    let [pt, du, dv] =
        if s.p <= STACK_DEGREE && s.q <= STACK_DEGREE && (s.hd == 3 || s.hd == 4) && s.dim == 3 {
            patch_first_order(s.patch(k), (s.p, s.q, s.hd), s.rational, lu, lv)
        } else {
            let (p, d) = s.eval_patch(k, lu, lv);
            [[p[0], p[1], p[2]], [d[0], d[1], d[2]], [d[3], d[4], d[5]]]
        };
    let mut out = [[0.0; 3]; 3];
    s.denormalise(&pt, &mut out[0]);
    for c in 0..3 {
        out[1][c] = du[c] * s.scale / (u1 - u0);
        out[2][c] = dv[c] * s.scale / (v1 - v0);
    }
    Some(out)
}

pub(super) fn cross(a: &[f64; 3], b: &[f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

pub(super) fn norm(a: &[f64]) -> f64 {
    dot(a, a).sqrt()
}

/// Sine of the angle between `a` and `b` (0 when either vanishes).
fn sine(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    let (na, nb) = (norm(a), norm(b));
    if na > 0.0 && nb > 0.0 {
        norm(&cross(a, b)) / (na * nb)
    } else {
        0.0
    }
}

/// Two surfaces: `F(u₁, v₁, u₂, v₂) = S₁(u₁, v₁) − S₂(u₂, v₂)`.
pub(super) struct TwoSurfaces<'a> {
    a: &'a QuerySurface,
    b: &'a QuerySurface,
    /// The parameter box, computed once (every Newton solve clamps to it).
    bounds: [(f64, f64); K],
}

impl<'a> TwoSurfaces<'a> {
    pub(super) fn new(a: &'a QuerySurface, b: &'a QuerySurface) -> Self {
        let (ua, va) = a.domain();
        let (ub, vb) = b.domain();
        TwoSurfaces {
            a,
            b,
            bounds: [ua, va, ub, vb],
        }
    }
}

impl System for TwoSurfaces<'_> {
    fn k(&self) -> usize {
        4
    }

    fn first(&self) -> &QuerySurface {
        self.a
    }

    fn bounds(&self) -> [(f64, f64); K] {
        self.bounds
    }

    fn jet(&self, x: &[f64; K]) -> Option<Jet> {
        let [p, su, sv] = surface_jet(self.a, x[0], x[1])?;
        let [q, tu, tv] = surface_jet(self.b, x[2], x[3])?;
        let mut j = [[0.0; K]; 3];
        for (r, row) in j.iter_mut().enumerate() {
            *row = [su[r], sv[r], -tu[r], -tv[r]];
        }
        Some(Jet {
            p,
            f: [p[0] - q[0], p[1] - q[1], p[2] - q[2]],
            j,
            dp: [su, sv, [0.0; 3], [0.0; 3]],
            sin: sine(&cross(&su, &sv), &cross(&tu, &tv)),
        })
    }
}

/// A surface and a plane: `f(u, v) = n·(S(u, v) − o)`, `n` a unit normal.
pub(super) struct PlaneSection<'a> {
    s: &'a QuerySurface,
    origin: [f64; 3],
    normal: [f64; 3],
    /// The parameter box, computed once.
    bounds: [(f64, f64); K],
}

impl<'a> PlaneSection<'a> {
    pub(super) fn new(s: &'a QuerySurface, origin: [f64; 3], normal: [f64; 3]) -> Self {
        let (u, v) = s.domain();
        PlaneSection {
            s,
            origin,
            normal,
            bounds: [u, v, (0.0, 0.0), (0.0, 0.0)],
        }
    }
}

impl System for PlaneSection<'_> {
    fn k(&self) -> usize {
        2
    }

    fn first(&self) -> &QuerySurface {
        self.s
    }

    fn bounds(&self) -> [(f64, f64); K] {
        self.bounds
    }

    fn jet(&self, x: &[f64; K]) -> Option<Jet> {
        let [p, su, sv] = surface_jet(self.s, x[0], x[1])?;
        let n = &self.normal;
        let d = [
            p[0] - self.origin[0],
            p[1] - self.origin[1],
            p[2] - self.origin[2],
        ];
        let mut j = [[0.0; K]; 3];
        j[0][0] = dot(n, &su);
        j[0][1] = dot(n, &sv);
        Some(Jet {
            p,
            f: [dot(n, &d), 0.0, 0.0],
            j,
            dp: [su, sv, [0.0; 3], [0.0; 3]],
            sin: sine(n, &cross(&su, &sv)),
        })
    }
}

/// Solves the `n × n` system `a x = b` (`n ≤ 4`) by Gaussian elimination with partial pivoting;
/// `None` when a pivot vanishes relative to the matrix's size.
pub(super) fn solve(mut a: [[f64; K]; K], mut b: [f64; K], n: usize) -> Option<[f64; K]> {
    let size = a
        .iter()
        .take(n)
        .flat_map(|r| r[..n].iter())
        .fold(0.0_f64, |m, v| m.max(v.abs()));
    if !(size > 0.0 && size.is_finite()) {
        return None;
    }
    for c in 0..n {
        let piv = (c..n).max_by(|&i, &j| a[i][c].abs().total_cmp(&a[j][c].abs()))?;
        if !(a[piv][c].abs() > 1e-300_f64.max(f64::EPSILON * 1e-6 * size)) {
            return None;
        }
        a.swap(c, piv);
        b.swap(c, piv);
        for r in c + 1..n {
            let m = a[r][c] / a[c][c];
            for cc in c..n {
                a[r][cc] -= m * a[c][cc];
            }
            b[r] -= m * b[c];
        }
    }
    let mut x = [0.0; K];
    for c in (0..n).rev() {
        let s: f64 = (c + 1..n).map(|cc| a[c][cc] * x[cc]).sum();
        x[c] = (b[c] - s) / a[c][c];
    }
    x.iter().all(|v| v.is_finite()).then_some(x)
}

/// The tangent of the solution curve in the unknowns: the null vector of the `(k − 1) × k`
/// Jacobian by cofactors (`tᵢ = (−1)ⁱ det Jᵢ`, `Jᵢ` without column `i`; the generalised cross
/// product), scaled so that the point of the first surface moves at unit speed along it.
/// `None` at a tangency of the surfaces, where the null space is not a line.
pub(super) fn tangent(jet: &Jet, k: usize) -> Option<([f64; K], [f64; 3])> {
    let mut t = [0.0; K];
    for (i, ti) in t.iter_mut().enumerate().take(k) {
        // the columns other than i
        let mut cols = [0; K];
        for (n, c) in (0..k).filter(|&c| c != i).enumerate() {
            cols[n] = c;
        }
        let det = if k == 2 {
            jet.j[0][cols[0]]
        } else {
            let m = |r: usize, c: usize| jet.j[r][cols[c]];
            m(0, 0) * (m(1, 1) * m(2, 2) - m(1, 2) * m(2, 1))
                - m(0, 1) * (m(1, 0) * m(2, 2) - m(1, 2) * m(2, 0))
                + m(0, 2) * (m(1, 0) * m(2, 1) - m(1, 1) * m(2, 0))
        };
        *ti = if i % 2 == 0 { det } else { -det };
    }
    let mut dir = [0.0; 3];
    for (i, ti) in t.iter().enumerate().take(k) {
        for (c, d) in dir.iter_mut().enumerate() {
            *d += jet.dp[i][c] * ti;
        }
    }
    let len = norm(&dir);
    if !(len > 0.0 && len.is_finite()) {
        return None;
    }
    for ti in &mut t {
        *ti /= len;
    }
    Some((t, [dir[0] / len, dir[1] / len, dir[2] / len]))
}

/// Clamps `x` into the box.
pub(super) fn clamp(x: &mut [f64; K], bounds: &[(f64, f64); K], k: usize) {
    for i in 0..k {
        x[i] = x[i].clamp(bounds[i].0, bounds[i].1);
    }
}

/// Most Newton steps of a correction (quadratic convergence needs a handful; the free solve at
/// a tangency converges linearly).
const NEWTON_STEPS: usize = 60;

/// Newton's method on the section's equations from `x`, kept in the box, to a residual of at
/// most `eps`: with `fixed = Some(i)` the unknown `i` stays put (a square system, a point on a
/// side of the box); with a plane `(t, p)` the extra equation `t·(P(x) − p) = 0` makes it square
/// (the marching corrector); with neither, the minimum-norm step `−Jᵀ(JJᵀ + μI)⁻¹F` (μ a
/// relative `10⁻¹⁴` of the trace, so tangencies, where `J` loses rank, converge linearly).
/// Returns the best point and its jet.
pub(super) fn newton(
    sys: &dyn System,
    x0: [f64; K],
    fixed: Option<usize>,
    plane: Option<([f64; 3], [f64; 3])>,
    eps: f64,
) -> Option<([f64; K], Jet)> {
    newton_within(sys, x0, fixed, plane, eps, None)
}

/// [`newton`], given up (`None`) as soon as an iterate leaves `region` (one interval per
/// unknown): a search for a point near `x0` that need not follow Newton's method elsewhere.
pub(super) fn newton_within(
    sys: &dyn System,
    x0: [f64; K],
    fixed: Option<usize>,
    plane: Option<([f64; 3], [f64; 3])>,
    eps: f64,
    region: Option<&[(f64, f64); K]>,
) -> Option<([f64; K], Jet)> {
    let k = sys.k();
    let bounds = sys.bounds();
    let mut x = x0;
    clamp(&mut x, &bounds, k);
    let mut jet = sys.jet(&x)?;
    let mut best = (jet.gap(k), x, jet.clone());
    let steps = if fixed.is_none() && plane.is_none() {
        NEWTON_STEPS
    } else {
        16
    };
    for _ in 0..steps {
        let extra = plane.map_or(0.0, |(t, p)| {
            dot(&t, &[jet.p[0] - p[0], jet.p[1] - p[1], jet.p[2] - p[2]])
        });
        if jet.gap(k) <= eps && extra.abs() <= eps {
            break;
        }
        let m = k - 1;
        let dx = if let Some(i) = fixed {
            let mut all = [0; K];
            for (n, c) in (0..k).filter(|&c| c != i).enumerate() {
                all[n] = c;
            }
            let cols = &all[..m];
            let mut a = [[0.0; K]; K];
            let mut b = [0.0; K];
            for r in 0..m {
                for (c, &cc) in cols.iter().enumerate() {
                    a[r][c] = jet.j[r][cc];
                }
                b[r] = -jet.f[r];
            }
            let s = solve(a, b, m)?;
            let mut dx = [0.0; K];
            for (c, &cc) in cols.iter().enumerate() {
                dx[cc] = s[c];
            }
            dx
        } else if let Some((t, _)) = plane {
            let mut a = [[0.0; K]; K];
            let mut b = [0.0; K];
            for r in 0..m {
                a[r][..k].copy_from_slice(&jet.j[r][..k]);
                b[r] = -jet.f[r];
            }
            for c in 0..k {
                a[m][c] = dot(&t, &jet.dp[c]);
            }
            b[m] = -extra;
            solve(a, b, k)?
        } else {
            // (JJᵀ + μI) y = −F, dx = Jᵀy
            let mut a = [[0.0; K]; K];
            let mut b = [0.0; K];
            let mut trace = 0.0;
            for r in 0..m {
                for c in 0..m {
                    a[r][c] = dot(&jet.j[r][..k], &jet.j[c][..k]);
                }
                trace += a[r][r];
                b[r] = -jet.f[r];
            }
            for (r, row) in a.iter_mut().enumerate().take(m) {
                row[r] += 1e-14 * trace;
            }
            let y = solve(a, b, m)?;
            let mut dx = [0.0; K];
            for (c, d) in dx.iter_mut().enumerate().take(k) {
                *d = (0..m).map(|r| jet.j[r][c] * y[r]).sum();
            }
            dx
        };
        let mut next = x;
        for i in 0..k {
            next[i] += dx[i];
        }
        clamp(&mut next, &bounds, k);
        if next == x {
            break;
        }
        if region.is_some_and(|r| (0..k).any(|i| !(next[i] >= r[i].0 && next[i] <= r[i].1))) {
            return None;
        }
        x = next;
        jet = sys.jet(&x)?;
        let g = jet.gap(k);
        if g < best.0 || (g == best.0 && plane.is_some()) {
            best = (g, x, jet.clone());
        }
    }
    Some((best.1, best.2))
}

#[cfg(test)]
mod tests {
    use super::{patch_first_order, surface_jet};
    use crate::surface::Placement;
    use crate::{BSplineSurface, KnotVector, NurbsSurface, Points, QuerySurface};

    /// The stack evaluation agrees with the general one (`eval_patch`, second derivatives and
    /// allocation) on a rational torus and a bicubic net, at points over several patches.
    #[test]
    fn first_order_matches_general_evaluation() {
        let f = Placement::new([0.3, -0.2, 0.1], None, None).unwrap();
        let torus = NurbsSurface::torus(&f, 3.0, 1.0, (0.0, 6.0), (0.0, 5.0)).unwrap();
        let net: Vec<f64> = (0..6 * 5)
            .flat_map(|k| {
                let (i, j) = ((k / 5) as f64, (k % 5) as f64);
                [i, j, (0.7 * i).sin() * (0.4 * j).cos()]
            })
            .collect();
        let bicubic = BSplineSurface::from_knot_vectors(
            3,
            3,
            KnotVector::clamped_uniform(3, 6).unwrap(),
            KnotVector::clamped_uniform(3, 5).unwrap(),
            Points::from_flat(3, net).unwrap(),
            (6, 5),
        )
        .unwrap();
        for s in [
            QuerySurface::from_nurbs(&torus).unwrap(),
            QuerySurface::from_bspline(&bicubic).unwrap(),
        ] {
            let ((u0, u1), (v0, v1)) = s.domain();
            for k in 0..50 {
                let (a, b) = (
                    (0.618_033_988_749_895 * f64::from(k)).fract(),
                    (0.754_877_666_246_693 * f64::from(k)).fract(),
                );
                let (u, v) = (u0 + a * (u1 - u0), v0 + b * (v1 - v0));
                let (patch, lu, lv) = s.locate(u, v).unwrap();
                let fast = patch_first_order(s.patch(patch), (s.p, s.q, s.hd), s.rational, lu, lv);
                let (p, d) = s.eval_patch(patch, lu, lv);
                for c in 0..3 {
                    assert!((fast[0][c] - p[c]).abs() <= 1e-14, "{k} {c}");
                    assert!((fast[1][c] - d[c]).abs() <= 1e-13 * (1.0 + d[c].abs()));
                    assert!((fast[2][c] - d[3 + c]).abs() <= 1e-13 * (1.0 + d[3 + c].abs()));
                }
                assert!(surface_jet(&s, u, v).is_some());
            }
        }
    }
}
