//! Faces cut along a seam (`docs/theory/topology.md`, "Bands and caps without a seam edge"):
//! a face of a closed surface whose loops go once round the closed direction (a band of a
//! cylinder between two circles, a cap of a sphere round a pole) bounds no region of `(u, v)`
//! by its loops alone; cut at a common parameter `u₀`, its loops and the seam lines `u = u₀`
//! and `u = u₀ + P` (and for a cap the pole line) bound a strip that meshes as any region, the
//! usual treatment of a periodic face cut along its seam (Piegl & Tiller, *The NURBS Book*,
//! 2nd ed., §12.5 on surfaces of revolution and their seams; Open CASCADE's `BRepMesh`, which
//! meshes a closed face between the two uses of its seam edge).

use super::pcurve::SurfaceClosure;
use crate::{Error, Result};

/// A loop sampled as a polygon in `(u, v)`, each point with its 3-D point.
pub(super) type Polygon = Vec<([f64; 2], Vec<f64>)>;

/// Candidate seam parameters tried over one period.
const SEAM_CANDIDATES: usize = 64;

/// What the mesher knows of a face's surface for the cut.
pub(super) struct SeamPlan<'a> {
    pub closure: &'a SurfaceClosure,
    pub domain: ((f64, f64), (f64, f64)),
    /// Whether the face's normal is the surface's (`advanced_face.same_sense`).
    pub same_sense: bool,
    /// Largest step along a seam or pole line, in `u` and `v` (the mesher's grid spacing).
    pub h: [f64; 2],
    /// The surface at a point of `(u, v)`.
    pub eval: &'a dyn Fn([f64; 2]) -> Result<Vec<f64>>,
}

fn refuse(reason: String) -> Error {
    Error::InvalidArgument {
        what: "face loop".into(),
        reason,
    }
}

fn loop_name(k: usize) -> String {
    if k == 0 {
        "the outer loop".into()
    } else {
        format!("inner loop {k}")
    }
}

/// The loops of a face as polygons bounding its region in `(u, v)`, the first the outer one:
/// `loops` unchanged when every loop closes in `(u, v)`; else, for loops going once round the
/// closed direction `d` (the last point of the polygon a period `P` from the first, the closing
/// segment jumping back), the face cut along a seam: a band (two such loops, going round in
/// opposite senses) becomes the polygon of the first loop from `u₀` to `u₀ ± P`, the seam line
/// at `u₀ ± P`, the second loop back to `u₀` and the seam line at `u₀`; a cap (one such loop)
/// closes with the seam lines and the pole line on the face's side. The face's side is on the
/// left of a loop going round in `+u` (`(u, v)` counter-clockwise) when the face's normal is the
/// surface's, on the right otherwise. `u₀` is chosen among [`SEAM_CANDIDATES`] values over the
/// period where each loop crosses it once, no other loop spans it, and the loops are farthest
/// apart (from each other, or from the pole). The points of the two seam lines are the same
/// 3-D points, computed once, so the mesh has no crack along the cut; the other loops are moved
/// by whole periods into the strip.
///
/// # Errors
/// [`Error::InvalidArgument`] (`what` "face loop") for a loop going round more than once or in
/// both directions, more than two loops going round, two going round in the same sense, a
/// band whose loops are on the wrong sides of each other, a cap without a pole on its side,
/// or no seam parameter that each loop crosses once clear of the other loops.
pub(super) fn cut_along_seam(plan: &SeamPlan<'_>, loops: Vec<Polygon>) -> Result<Vec<Polygon>> {
    let period = plan.closure.period;
    // each loop's turns: its last point against its first, in whole periods
    let mut turns = Vec::with_capacity(loops.len());
    for (k, l) in loops.iter().enumerate() {
        let mut t = [0_i64; 2];
        if let (Some(first), Some(last)) = (l.first(), l.last()) {
            for d in 0..2 {
                if let Some(p) = period[d] {
                    #[allow(clippy::cast_possible_truncation)] // checked below
                    let n = ((last.0[d] - first.0[d]) / p).round() as i64;
                    if n.abs() > 1 {
                        return Err(refuse(format!(
                            "{} goes round the closed surface in {} {} times; a loop of a face goes round it at most once",
                            loop_name(k),
                            ["u", "v"][d],
                            n.abs()
                        )));
                    }
                    t[d] = n;
                }
            }
        }
        if t[0] != 0 && t[1] != 0 {
            return Err(refuse(format!(
                "{} goes round the closed surface in both u and v, so it bounds no region of (u, v)",
                loop_name(k)
            )));
        }
        turns.push(t);
    }
    let Some(d) = (0..2).find(|&d| turns.iter().any(|t| t[d] != 0)) else {
        return Ok(loops);
    };
    if turns.iter().any(|t| t[1 - d] != 0) {
        return Err(refuse(
            "the face's loops go round the closed surface in both u and v, so they bound no region of (u, v)".into(),
        ));
    }
    let dn = ["u", "v"][d];
    let round: Vec<usize> = (0..loops.len()).filter(|&k| turns[k][d] != 0).collect();
    if round.len() > 2 {
        return Err(refuse(format!(
            "{} loops go round the closed surface in {dn}; a face between loops round it has two (a band) or one and a pole (a cap)",
            round.len()
        )));
    }
    let p = period[d].unwrap_or(0.0);
    // coordinates (a, b): a along the closed direction, b across; swapping u and v reverses
    // the orientation of (u, v)
    let ab = |uv: [f64; 2]| if d == 0 { uv } else { [uv[1], uv[0]] };
    let uv_of = |a: f64, b: f64| if d == 0 { [a, b] } else { [b, a] };
    let left = plan.same_sense != (d == 1);
    let dom = [plan.domain.0, plan.domain.1];
    let (b_lo, b_hi) = dom[1 - d];
    let pb = period[1 - d];
    let (ha, hb) = (plan.h[d], plan.h[1 - d]);
    // each loop in (a, b), its ring closed by its first point moved by its turn
    let ring = |k: usize| -> Vec<([f64; 2], &[f64])> {
        let l = &loops[k];
        let mut r: Vec<([f64; 2], &[f64])> = l.iter().map(|(x, y)| (ab(*x), &y[..])).collect();
        #[allow(clippy::cast_precision_loss)] // −1, 0 or 1
        let by = turns[k][d] as f64 * p;
        r.push(([r[0].0[0] + by, r[0].0[1]], r[0].1));
        r
    };
    let rings: Vec<Vec<([f64; 2], &[f64])>> = (0..loops.len()).map(ring).collect();
    // where a ring crosses a ≡ c (mod p): (segment, fraction, m) with a = c + m p
    let crossings = |r: &[([f64; 2], &[f64])], c: f64| -> Vec<(usize, f64, f64)> {
        let mut out = Vec::new();
        for k in 0..r.len() - 1 {
            let (a0, a1) = (r[k].0[0], r[k + 1].0[0]);
            // each value counted once: in (a0, a1] going up, in [a1, a0) going down
            let mut m = if a1 > a0 {
                ((a0 - c) / p).floor() + 1.0
            } else {
                ((a1 - c) / p).ceil()
            };
            loop {
                let x = c + m * p;
                let within = if a1 > a0 {
                    x > a0 && x <= a1
                } else {
                    a1 < a0 && x >= a1 && x < a0
                };
                if !within {
                    break;
                }
                out.push((k, (x - a0) / (a1 - a0), m));
                m += 1.0;
            }
        }
        out
    };
    let b_at = |r: &[([f64; 2], &[f64])], (k, t, _): (usize, f64, f64)| {
        r[k].0[1] + t * (r[k + 1].0[1] - r[k].0[1])
    };
    let mean_b = |k: usize| {
        let l = &rings[k];
        #[allow(clippy::cast_precision_loss)] // a polygon's size
        let n = (l.len() - 1).max(1) as f64;
        l[..l.len() - 1].iter().map(|x| x.0[1]).sum::<f64>() / n
    };
    // the band's or the cap's side: L₊ goes round in +a; the face is on +b of it when `left`
    let (lp, lm) = match round.as_slice() {
        [k] if turns[*k][d] > 0 => (Some(*k), None),
        [k] => (None, Some(*k)),
        [i, j] => {
            if turns[*i][d] == turns[*j][d] {
                return Err(refuse(format!(
                    "{} and {} go round the closed surface in {dn} in the same sense, so they do not bound a band between them; a band's loops go round in opposite senses",
                    loop_name(*i),
                    loop_name(*j)
                )));
            }
            if turns[*i][d] > 0 {
                (Some(*i), Some(*j))
            } else {
                (Some(*j), Some(*i))
            }
        }
        _ => unreachable!("one or two loops go round"),
    };
    let side = if left { 1.0 } else { -1.0 };
    // the second loop of a band moved by whole periods in b to the face's side of the first
    let mut shift_b = 0.0;
    let pole_b = match (lp, lm) {
        (Some(i), Some(j)) => {
            let gap = (mean_b(j) - mean_b(i)) * side;
            if let Some(q) = pb {
                shift_b = side * q * ((-gap / q).floor() + 1.0);
                if (mean_b(j) + shift_b - mean_b(i)) * side >= q {
                    shift_b -= side * q;
                }
            } else if gap <= 0.0 {
                return Err(refuse(format!(
                    "{} goes round the closed surface in +{dn} and {} in −{dn}, but the second is on the side of the first away from the face (by the loops' senses and the face's normal), so they do not bound a band; a loop's orientation in the file is reversed",
                    loop_name(i),
                    loop_name(j)
                )));
            }
            None
        }
        (Some(k), None) | (None, Some(k)) => {
            // the cap's region is on +b of a loop going round in +a when `left`
            let up = left == lp.is_some();
            let pole = plan.closure.pole[2 * (1 - d) + usize::from(up)];
            if !pole {
                return Err(refuse(format!(
                    "{} goes round the closed surface in {dn} and no other loop does, and the surface has no pole on the face's side of it ({} = {}) to close the face",
                    loop_name(k),
                    ["u", "v"][1 - d],
                    if up { b_hi } else { b_lo }
                )));
            }
            Some(if up { b_hi } else { b_lo })
        }
        (None, None) => unreachable!("one loop goes round"),
    };
    // the seam parameter: each loop round crosses it once, the others do not span it, the
    // loops (or the loop and the pole) farthest apart there
    let a_ref = rings[round[0]][0].0[0];
    let spans: Vec<(usize, f64, f64)> = (0..loops.len())
        .filter(|k| !round.contains(k))
        .map(|k| {
            let (lo, hi) = rings[k]
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), x| {
                    (lo.min(x.0[0]), hi.max(x.0[0]))
                });
            (k, lo, hi)
        })
        .collect();
    let mut best: Option<(f64, f64)> = None;
    #[allow(clippy::cast_precision_loss)] // a small count
    for j in 0..SEAM_CANDIDATES {
        let c = a_ref + p * (j as f64 + 0.5) / SEAM_CANDIDATES as f64;
        let mut bs = Vec::with_capacity(2);
        let mut ok = true;
        for &k in &round {
            let x = crossings(&rings[k], c);
            if x.len() != 1 {
                ok = false;
                break;
            }
            bs.push(b_at(&rings[k], x[0]) + if Some(k) == lm { shift_b } else { 0.0 });
        }
        let clear = spans
            .iter()
            .all(|&(_, lo, hi)| (hi - lo) < p && ((lo - c) / p).floor() == ((hi - c) / p).floor());
        if !(ok && clear) {
            continue;
        }
        let gap = match (bs.as_slice(), pole_b) {
            ([x, y], _) => (x - y).abs(),
            ([x], Some(pb)) => (x - pb).abs(),
            _ => 0.0,
        };
        if best.is_none_or(|(g, _)| gap > g) {
            best = Some((gap, c));
        }
    }
    let Some((_, c)) = best else {
        return Err(refuse(format!(
            "the loops going round the closed surface in {dn} cross every seam parameter tried more than once, or another loop spans it, so the face cannot be cut along a seam"
        )));
    };
    // a loop round cut at c: from c to c ± p, moved by whole periods to start at c (ending at
    // c + p for L₊; L₋ from c + p to c), and by `by_b` in b
    let cut = |k: usize, start: f64, by_b: f64| -> Vec<([f64; 2], Vec<f64>)> {
        let r = &rings[k];
        let (seg, t, m) = crossings(r, c)[0];
        let n = r.len() - 1;
        let turn = r[n].0[0] - r[0].0[0];
        let lerp = |x: &[f64], y: &[f64]| -> Vec<f64> {
            x.iter().zip(y).map(|(a, b)| a + t * (b - a)).collect()
        };
        let xb = r[seg].0[1] + t * (r[seg + 1].0[1] - r[seg].0[1]);
        let xp = lerp(r[seg].1, r[seg + 1].1);
        let shift = start - (c + m * p);
        let mut out = vec![([start, xb + by_b], xp.clone())];
        // the ring's points after the crossing, round to it again
        let eps = 1e-9;
        let from = if t > 1.0 - eps { seg + 2 } else { seg + 1 };
        let to = if t < eps { seg } else { seg + 1 };
        for i in from..n + to {
            let (q, x) = if i < n {
                (r[i].0, r[i].1)
            } else {
                let w = r[i - n].0;
                ([w[0] + turn, w[1]], r[i - n].1)
            };
            out.push(([q[0] + shift, q[1] + by_b], x.to_vec()));
        }
        out.push(([start + turn, xb + by_b], xp));
        out
    };
    // points of a seam line at a from b0 to b1 (without its ends), their 3-D points
    let steps = |len: f64, h: f64| {
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)] // a small count
        let n = (len.abs() / h).ceil().clamp(1.0, 1e6) as usize;
        n
    };
    let seam_line = |b0: f64, b1: f64| -> Result<Vec<(f64, Vec<f64>)>> {
        let n = steps(b1 - b0, hb);
        #[allow(clippy::cast_precision_loss)] // a small count
        (1..n)
            .map(|i| {
                let b = b0 + (b1 - b0) * i as f64 / n as f64;
                Ok((b, (plan.eval)(uv_of(c, b))?))
            })
            .collect()
    };
    let mut strip: Polygon = Vec::new();
    let push = |strip: &mut Polygon, a: f64, b: f64, x: Vec<f64>| strip.push((uv_of(a, b), x));
    let extend = |strip: &mut Polygon, l: Vec<([f64; 2], Vec<f64>)>| {
        for (q, x) in l {
            strip.push((uv_of(q[0], q[1]), x));
        }
    };
    match (lp, lm, pole_b) {
        (Some(i), Some(j), _) => {
            let a = cut(i, c, 0.0);
            let b = cut(j, c + p, shift_b);
            let (ba, bb) = (a[0].0[1], b[0].0[1]);
            // up at c + p from L₊'s end to L₋'s start, down at c from L₋'s end to L₊'s start
            let line = seam_line(ba, bb)?;
            extend(&mut strip, a);
            for (bv, x) in &line {
                push(&mut strip, c + p, *bv, x.clone());
            }
            extend(&mut strip, b);
            for (bv, x) in line.into_iter().rev() {
                push(&mut strip, c, bv, x);
            }
        }
        (k0, k1, Some(pole)) => {
            let (k, start) = match (k0, k1) {
                (Some(k), _) => (k, c),
                (_, Some(k)) => (k, c + p),
                _ => unreachable!("one loop goes round"),
            };
            let l = cut(k, start, 0.0);
            let bl = l[0].0[1];
            let end = l[l.len() - 1].0[0];
            let line = seam_line(bl, pole)?;
            let x_pole = (plan.eval)(uv_of(c, pole))?;
            extend(&mut strip, l);
            for (bv, x) in &line {
                push(&mut strip, end, *bv, x.clone());
            }
            let n = steps(p, ha);
            #[allow(clippy::cast_precision_loss)] // a small count
            for i in 0..=n {
                let a = end + (start - end) * i as f64 / n as f64;
                push(&mut strip, a, pole, x_pole.clone());
            }
            for (bv, x) in line.into_iter().rev() {
                push(&mut strip, start, bv, x);
            }
        }
        _ => unreachable!("a band or a cap"),
    }
    // the other loops by whole periods into [c, c + p]
    let mut out = vec![strip];
    for &(k, lo, _) in &spans {
        let by = -p * ((lo - c) / p).floor();
        out.push(
            loops[k]
                .iter()
                .map(|(q, x)| {
                    let w = ab(*q);
                    (uv_of(w[0] + by, w[1]), x.clone())
                })
                .collect(),
        );
    }
    Ok(out)
}

#[cfg(test)]
#[path = "seam_tests.rs"]
mod tests;
