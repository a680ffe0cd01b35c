//! Our side of the curve–curve peer comparison on the exact-answer suite
//! (`bench/peers/intersect_exact_peers.py`, run by `bench/peers/run.sh`): every case of
//! `tests/data/intersect_exact.json` (planar Bezier pairs whose intersections were computed with
//! rational and 60-digit arithmetic by `tests/data/intersect_exact.py`) is intersected with
//! `QueryCurve::intersect` at tolerance 1e-9 (Bezier clipping with Newton refinement,
//! `docs/theory/queries.md`), timed as the median of `REPEATS` runs (more while they have taken
//! less than a second in all), and printed as one line a case for the script to check against the
//! exact answers:
//!
//! `lekalo K SECONDS N t_a t_b x y ...` (case index, median seconds, number of points found,
//! then the parameters and the point of each; an overlap is printed as its two ends' midpoint
//! with `N` counting it once).
//!
//! `cargo run --release -p lekalo --example intersect_exact_peer -- [REPEATS [CASE]]` (CASE: only
//! that case's index, e.g. under `perf record`)

use std::hint::black_box;
use std::time::Instant;

use lekalo::query::CurveIntersection;
use lekalo::{BSplineCurve, Points, QueryCurve};
use serde_json::Value;

/// Median wall time in seconds of the runs of `f`: `repeats` runs, then more while they have
/// taken less than a second in all (at most 1,001), as in `query_peer.rs`;
/// `intersect_exact_peers.py` and `occt_queries.cpp` follow the same rule.
fn median_s(repeats: usize, mut f: impl FnMut()) -> f64 {
    let start = Instant::now();
    let mut t: Vec<f64> = Vec::new();
    while t.len() < repeats.max(1) || (start.elapsed().as_secs_f64() < 1.0 && t.len() < 1001) {
        let a = Instant::now();
        f();
        t.push(a.elapsed().as_secs_f64());
    }
    t.sort_by(f64::total_cmp);
    t[t.len() / 2]
}

/// The Bezier curve of the control points `v` (a JSON array of `[x, y]`), as the tests build it.
fn bezier(v: &Value) -> Result<QueryCurve, String> {
    let pts: Vec<Vec<f64>> = v
        .as_array()
        .ok_or("control points are not an array")?
        .iter()
        .map(|p| {
            p.as_array()
                .ok_or("a control point is not an array")?
                .iter()
                .map(|x| x.as_f64().ok_or("a coordinate is not a number"))
                .collect::<Result<Vec<f64>, _>>()
        })
        .collect::<Result<_, _>>()?;
    let n = pts.len();
    let mut knots = vec![0.0; n];
    knots.extend(vec![1.0; n]);
    let rows = Points::from_rows(&pts).map_err(|e| e.to_string())?;
    let c = BSplineCurve::new(n - 1, knots, rows).map_err(|e| e.to_string())?;
    QueryCurve::from_bspline(&c).map_err(|e| e.to_string())
}

fn main() -> Result<(), String> {
    let repeats: usize = std::env::args()
        .nth(1)
        .map(|r| {
            r.parse()
                .map_err(|_| format!("REPEATS {r:?} is not a count"))
        })
        .transpose()?
        .unwrap_or(7);
    let only: Option<usize> = std::env::args()
        .nth(2)
        .map(|c| c.parse().map_err(|_| format!("CASE {c:?} is not an index")))
        .transpose()?;
    let cases: Value = serde_json::from_str(include_str!("../tests/data/intersect_exact.json"))
        .map_err(|e| e.to_string())?;
    for (k, case) in cases.as_array().ok_or("no cases")?.iter().enumerate() {
        if only.is_some_and(|o| o != k) {
            continue;
        }
        let (a, b) = (bezier(&case["a"])?, bezier(&case["b"])?);
        let mut hits = Vec::new();
        let t = median_s(repeats, || {
            hits = black_box(&a)
                .intersect(black_box(&b), 1e-9)
                .expect("intersection");
        });
        let mut line = format!("lekalo {k} {t:.6e} {}", hits.len());
        for h in &hits {
            let (ta, tb) = match h {
                CurveIntersection::Point { t_a, t_b, .. } => (*t_a, *t_b),
                CurveIntersection::Overlap { a, b } => (0.5 * (a.0 + a.1), 0.5 * (b.0 + b.1)),
            };
            let p = a.point(ta).map_err(|e| e.to_string())?;
            line += &format!(" {ta:.17e} {tb:.17e} {:.17e} {:.17e}", p[0], p[1]);
        }
        println!("{line}");
    }
    Ok(())
}
