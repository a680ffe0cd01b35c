//! The fitted curves of a traced branch (`docs/theory/queries.md#fitted-curves`): the cubic
//! Hermite spline through a subset of the marched points with the marching's own tangents, the
//! subset chosen so that the spline is within the tolerance of every marched point.
//!
//! The marching already knows, at every point, the tangent of the branch in the unknowns (the null
//! vector of the Jacobian, scaled to unit speed in space), so the data of a C¹ cubic Hermite spline
//! are there without a least-squares solve; this is how Open CASCADE returns its walking lines
//! (`ApproxInt`/`GeomInt_WLApprox` fit the walking line's points and tangents). The points are
//! parametrised by arc length (chords corrected by the turning of the tangent) and the nodes are
//! chosen greedily: from each node, a point such that the Hermite segment between them passes
//! within the tolerance of every marched point in between, at its parameter, as far as the `h⁴`
//! law of the cubic's error predicts from the candidates' measured errors (within a tenth of
//! the farthest, as the law goes).

use super::super::super::pieces::dist;
use super::march::{arc_over_chord, turn_angle, Traced};
use super::system::K;
use crate::error::Result;
use crate::interpolate::CubicHermite;
use crate::{BSplineCurve, Points};

/// Widest row: the point in space and the scaled parameters on both surfaces.
const W: usize = 7;
/// Most candidates tried for one node of the fit (each checked at every point it spans).
const PREDICTIONS: usize = 6;
/// Share of the length the `h⁴` law allows that a predicted candidate aims at.
const SAFETY: f64 = 0.95;

/// The curve in space and the parameter curves of a branch, all on the same knots, `None` when
/// the branch has fewer than two distinct points. The fitted coordinates are
/// `(x, y, z, k₁u₁, k₁v₁, k₂u₂, k₂v₂)` (the last two for two surfaces only), `kᵢ` the largest
/// `|S_u| + |S_v|` of surface `i` on the branch, so that a parameter error `δ` moves the surface
/// point by at most `kᵢδ`; the spline is within `tol` of every marched point in those
/// coordinates, at the point's arc-length parameter.
#[allow(clippy::type_complexity)]
pub(super) fn fit_branch(
    t: &Traced,
    tol: f64,
    two: bool,
) -> Result<Option<(BSplineCurve, BSplineCurve, Option<BSplineCurve>)>> {
    let width = if two { 7 } else { 5 };
    let ka = if t.reach[0] > 0.0 { t.reach[0] } else { 1.0 };
    let kb = if t.reach[1] > 0.0 { t.reach[1] } else { 1.0 };
    let row = |x: &[f64; K], p: &[f64; 3]| -> [f64; W] {
        [p[0], p[1], p[2], ka * x[0], ka * x[1], kb * x[2], kb * x[3]]
    };
    // the distinct points, in order
    let n = t.ps.len();
    let mut kept: Vec<usize> = Vec::with_capacity(n);
    for i in 0..n {
        if kept.last().is_none_or(|&j| t.ps[j] != t.ps[i]) {
            kept.push(i);
        }
    }
    let m = kept.len();
    if m < 2 {
        return Ok(None);
    }
    let rows: Vec<[f64; W]> = kept.iter().map(|&i| row(&t.xs[i], &t.ps[i])).collect();
    // unit space tangents, oriented along the branch (the chord through the neighbours), and
    // the arc length: each chord c lengthened to the arc of a circle turning by θ,
    // c·(θ/2)/sin(θ/2); a point without a tangent (an end at a tangency) marked, to take the
    // derivative of the parabola through it and its two neighbours
    let mut slopes: Vec<[f64; W]> = Vec::with_capacity(m);
    let mut missing = Vec::new();
    let mut s = Vec::with_capacity(m);
    for a in 0..m {
        match t.tangents[kept[a]] {
            Some((tx, tp)) => {
                let (lo, hi) = (a.saturating_sub(1), (a + 1).min(m - 1));
                let (r0, r1) = (&rows[lo], &rows[hi]);
                let along =
                    tp[0] * (r1[0] - r0[0]) + tp[1] * (r1[1] - r0[1]) + tp[2] * (r1[2] - r0[2]);
                let mut g = row(&tx, &tp);
                if along < 0.0 {
                    for v in &mut g {
                        *v = -*v;
                    }
                }
                slopes.push(g);
            }
            None => {
                missing.push(a);
                slopes.push([0.0; W]);
            }
        }
        s.push(if a == 0 {
            0.0
        } else {
            let c = dist(&rows[a - 1][..3], &rows[a][..3]);
            let theta = match (&t.tangents[kept[a - 1]], &t.tangents[kept[a]]) {
                (Some(_), Some(_)) => turn_angle(&slopes[a - 1][..3], &slopes[a][..3]),
                _ => 0.0,
            };
            s[a - 1] + c * arc_over_chord(theta)
        });
    }
    for a in missing {
        slopes[a] = parabola_slope(&rows, &s, a);
    }
    // the largest distance of the Hermite segment from a to b from the points in between, at
    // their parameters
    let worst = |a: usize, b: usize| -> f64 {
        if two {
            hermite_worst::<7>(&rows, &slopes, &s, a, b)
        } else {
            hermite_worst::<5>(&rows, &slopes, &s, a, b)
        }
    };
    // the last point at most at arc length `target`, strictly between `good` and `bad`
    let before = |target: f64, good: usize, bad: usize| -> Option<usize> {
        let b = s[..bad].partition_point(|&x| x <= target).saturating_sub(1);
        (b > good).then_some(b)
    };
    let mut nodes = vec![0];
    let (mut a, mut span) = (0, None);
    while a < m - 1 {
        // the next node: a point `good` whose segment passes, chosen below a point `bad` whose
        // segment fails (or the end); each candidate predicted from the last one's error by the
        // h⁴ law of the cubic's error, until the prediction gains less than a tenth
        let (mut good, mut bad) = (a + 1, m);
        let mut b = match span {
            Some(l) => before(s[a] + l, good, bad).unwrap_or(good),
            None => (a + 8).min(m - 1),
        };
        for _ in 0..PREDICTIONS {
            let e = worst(a, b);
            let passed = e <= tol;
            if passed {
                good = b;
            } else {
                bad = b;
            }
            let factor = if e > 0.0 {
                (SAFETY * (tol / e).powf(0.25)).clamp(0.5, 2.0)
            } else {
                2.0
            };
            if passed && factor < 1.1 {
                break;
            }
            let target = s[a] + factor * (s[b] - s[a]);
            let next = if passed {
                // at least the next point (a tiny last span must not hold the next one back)
                before(target, good, bad).or((good + 1 < bad).then_some(good + 1))
            } else {
                // below the failure: the prediction, or halfway to the last pass
                before(target, good, bad).or_else(|| before(0.5 * (s[good] + s[b]), good, bad))
            };
            match next {
                Some(n) => b = n,
                None => break,
            }
        }
        nodes.push(good);
        span = Some(s[good] - s[a]);
        a = good;
    }
    // parameters on [0, 1]: derivatives with respect to s / L are L times those in s
    let len = s[m - 1];
    let params: Vec<f64> = nodes.iter().map(|&a| s[a] / len).collect();
    let mut pts = Vec::with_capacity(nodes.len() * width);
    let mut ders = Vec::with_capacity(nodes.len() * width);
    for &a in &nodes {
        pts.extend_from_slice(&rows[a][..width]);
        ders.extend(slopes[a][..width].iter().map(|v| v * len));
    }
    let spline = CubicHermite::new(
        params,
        Points::from_flat(width, pts)?,
        Points::from_flat(width, ders)?,
    )?
    .to_bspline();
    let knots = spline.knots().as_slice().to_vec();
    let ctrl = spline.control_points().as_slice();
    let part = |from: usize, dim: usize, f: f64| -> Result<BSplineCurve> {
        let pts: Vec<f64> = ctrl
            .chunks_exact(width)
            .flat_map(|r| r[from..from + dim].iter().map(move |v| v / f))
            .collect();
        BSplineCurve::new(3, knots.clone(), Points::from_flat(dim, pts)?)
    };
    let space = part(0, 3, 1.0)?;
    let pa = part(3, 2, ka)?;
    let pb = if two { Some(part(5, 2, kb)?) } else { None };
    Ok(Some((space, pa, pb)))
}

/// The largest distance, in the first `WD` coordinates, of the cubic Hermite segment between
/// rows `a` and `b` (slopes with respect to arc length `s`) from the rows strictly between them,
/// each at its parameter `s[k]` (the Hermite basis, de Boor, *A Practical Guide to Splines*,
/// ch. IV).
fn hermite_worst<const WD: usize>(
    rows: &[[f64; W]],
    slopes: &[[f64; W]],
    s: &[f64],
    a: usize,
    b: usize,
) -> f64 {
    let h = s[b] - s[a];
    let (ra, rb, ga, gb) = (&rows[a], &rows[b], &slopes[a], &slopes[b]);
    let mut e2 = 0.0_f64;
    for k in a + 1..b {
        let u = (s[k] - s[a]) / h;
        let (u2, u3) = (u * u, u * u * u);
        let (h00, h10) = (2.0 * u3 - 3.0 * u2 + 1.0, u3 - 2.0 * u2 + u);
        let (h01, h11) = (3.0 * u2 - 2.0 * u3, u3 - u2);
        let mut d2 = 0.0;
        for c in 0..WD {
            let v = h00 * ra[c] + h01 * rb[c] + h * (h10 * ga[c] + h11 * gb[c]);
            d2 += (v - rows[k][c]) * (v - rows[k][c]);
        }
        e2 = e2.max(d2);
    }
    e2.sqrt()
}

/// The derivative at `s[a]` of the parabola through row `a` and its two neighbours (at an end,
/// the next two; for two rows, the chord's slope).
fn parabola_slope(rows: &[[f64; W]], s: &[f64], a: usize) -> [f64; W] {
    let m = rows.len();
    let mut out = [0.0; W];
    if m == 2 {
        let h = s[1] - s[0];
        for (c, o) in out.iter_mut().enumerate() {
            *o = (rows[1][c] - rows[0][c]) / h;
        }
        return out;
    }
    let i0 = a.saturating_sub(1).min(m - 3);
    let (t0, t1, t2) = (s[i0], s[i0 + 1], s[i0 + 2]);
    let x = s[a];
    // derivatives of the Lagrange basis at x
    let l0 = ((x - t1) + (x - t2)) / ((t0 - t1) * (t0 - t2));
    let l1 = ((x - t0) + (x - t2)) / ((t1 - t0) * (t1 - t2));
    let l2 = ((x - t0) + (x - t1)) / ((t2 - t0) * (t2 - t1));
    for (c, o) in out.iter_mut().enumerate() {
        *o = l0 * rows[i0][c] + l1 * rows[i0 + 1][c] + l2 * rows[i0 + 2][c];
    }
    out
}
