//! The point of a vertex whose edge ends do not coincide (`docs/theory/topology.md`, "The point
//! of a vertex"): a file's edges meet within its tolerance, not exactly, and one point must
//! stand for all the ends joined there, leaving each edge's curve as it is.
//!
//! An edge whose curve `C` on `[a, b]` ends at `C(b)` has `C(b)` as its nearest point to every
//! point `V` near `C(b)` with `(V − C(b)) · C'(b) ≥ 0` (the curve runs away from `V` at its end:
//! the first-order condition of the foot of the perpendicular, Piegl & Tiller, *The NURBS Book*,
//! 2nd ed., §6.1, with the foot clamped to the domain); likewise `(V − C(a)) · C'(a) ≤ 0` at its
//! start. A reader that trims an edge at the nearest point of its curve to each vertex (as ISO
//! 10303-42 `edge_curve` readers do: the vertex lies on the curve within the model's
//! uncertainty) then keeps the whole curve when every end meets its half-space: the vertex is put
//! in the intersection of the half-spaces of all the ends joined there, the gap between the
//! ends being its distance to each.

/// The margin of each half-space condition, as a fraction of the largest distance between two
/// ends of the vertex: the foot of the perpendicular then lies past the end by a distinct
/// amount, not by a rounding.
pub(crate) const VERTEX_MARGIN: f64 = 1e-2;

/// Sweeps of cyclic projection onto the half-spaces before giving up.
const SWEEPS: usize = 64;

/// One end of an edge at a vertex: its point and the unit direction pointing away from the
/// curve (`C'(b)/|C'(b)|` at an end, `−C'(a)/|C'(a)|` at a start; zero when the curve does not
/// move there).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct EdgeEnd {
    pub(crate) point: Vec<f64>,
    pub(crate) outward: Vec<f64>,
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

fn distance(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y) * (x - y))
        .sum::<f64>()
        .sqrt()
}

/// The point of a vertex joining `ends` (see the module docs): the first end's point when all
/// ends are that point; else a point `V` with `(V − P_i) · d_i ≥ m` for every end `(P_i, d_i)`,
/// `m` = [`VERTEX_MARGIN`] times the ends' spread, found by cyclic projection onto the
/// half-spaces (Agmon 1954; Motzkin & Schoenberg 1954: it converges to a point of the
/// intersection when there is one) from the ends' centroid, kept when within ten spreads of
/// every end; else (no such point, as where two edges overlap along one line) the first end's
/// point. `O(k)` per sweep for `k` ends, at most 64 sweeps. The flag is true when the point
/// meets every end (the ends coincide, or the half-space point was found).
pub(crate) fn vertex_point(ends: &[EdgeEnd]) -> (Vec<f64>, bool) {
    let Some(first) = ends.first() else {
        return (Vec::new(), true);
    };
    let spread = ends
        .iter()
        .map(|e| distance(&e.point, &first.point))
        .fold(0.0_f64, f64::max);
    if spread == 0.0 {
        return (first.point.clone(), true);
    }
    if !spread.is_finite() {
        return (first.point.clone(), false);
    }
    let dim = first.point.len();
    let mut v = vec![0.0; dim];
    for e in ends {
        for (x, p) in v.iter_mut().zip(&e.point) {
            *x += p / ends.len() as f64;
        }
    }
    let margin = VERTEX_MARGIN * spread;
    // the conditions asked with a little more margin than checked, so that the last
    // projection's rounding does not undo one
    let ask = 1.5 * margin;
    let meets = |v: &[f64], e: &EdgeEnd, m: f64| {
        let d: Vec<f64> = v.iter().zip(&e.point).map(|(x, p)| x - p).collect();
        dot(&d, &e.outward) >= m
    };
    for _ in 0..SWEEPS {
        if ends.iter().all(|e| meets(&v, e, margin)) {
            break;
        }
        for e in ends {
            let d: Vec<f64> = v.iter().zip(&e.point).map(|(x, p)| x - p).collect();
            let short = ask - dot(&d, &e.outward);
            if short > 0.0 {
                for (x, n) in v.iter_mut().zip(&e.outward) {
                    *x += short * n;
                }
            }
        }
    }
    let feasible = ends
        .iter()
        .all(|e| meets(&v, e, margin) && distance(&v, &e.point) <= 10.0 * spread);
    if feasible {
        (v, true)
    } else {
        (first.point.clone(), false)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn end(point: [f64; 3], outward: [f64; 3]) -> EdgeEnd {
        let n = dot(&outward, &outward).sqrt();
        EdgeEnd {
            point: point.to_vec(),
            outward: outward.iter().map(|x| x / n).collect(),
        }
    }

    #[test]
    fn ends_at_one_point_give_that_point() {
        let p = [1.0, 2.0, 3.0];
        let v = vertex_point(&[end(p, [1.0, 0.0, 0.0]), end(p, [0.0, 1.0, 0.0])]);
        assert_eq!(v, (p.to_vec(), true), "no gap: the ends' own point");
    }

    #[test]
    fn a_corner_with_a_gap_gets_a_point_past_both_ends() {
        // an edge along +x ending at the origin, the next along +y starting 1e-4 away
        let a = end([0.0, 0.0, 0.0], [1.0, 0.0, 0.0]);
        let b = end([1e-4, 0.5e-4, 0.0], [0.0, -1.0, 0.0]);
        let (v, meets) = vertex_point(&[a.clone(), b.clone()]);
        assert!(meets, "a point past both ends exists");
        for e in [&a, &b] {
            let d: Vec<f64> = v.iter().zip(&e.point).map(|(x, p)| x - p).collect();
            assert!(dot(&d, &e.outward) > 0.0, "past the end: {v:?}");
            assert!(distance(&v, &e.point) < 1e-3, "near the ends: {v:?}");
        }
    }

    #[test]
    fn a_gap_along_a_smooth_join_is_bridged_in_between() {
        // two edges along +x, the first ending at 0, the next starting at 1e-5
        let a = end([0.0, 0.0, 0.0], [1.0, 0.0, 0.0]);
        let b = end([1e-5, 0.0, 0.0], [-1.0, 0.0, 0.0]);
        let (v, meets) = vertex_point(&[a, b]);
        assert!(
            meets && v[0] > 0.0 && v[0] < 1e-5,
            "between the ends: {v:?}"
        );
    }

    #[test]
    fn overlapping_ends_keep_the_first_end() {
        // the first edge runs past the start of the next along one line: no point is past both
        let a = end([1e-5, 0.0, 0.0], [1.0, 0.0, 0.0]);
        let b = end([0.0, 0.0, 0.0], [-1.0, 0.0, 0.0]);
        assert_eq!(
            vertex_point(&[a.clone(), b]),
            (a.point, false),
            "the first end"
        );
    }
}
