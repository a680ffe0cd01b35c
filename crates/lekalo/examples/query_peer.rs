//! Our side of the Open CASCADE query comparison (`bench/peers/run.sh`, just before
//! `bench/peers/occt_queries.cpp` on the same objects): the median of `REPEATS` runs of each
//! workload of `benches/query.rs` (more runs for fast ones, see `median_s`), printed in the peer's line format with the facts to compare
//! (intersection count, triangle count and the mesh's proved deviation). With `ANSWERS_DIR` it
//! writes its answers there for `bench/peers/compare_queries.py`: `lekalo_project.txt` (the
//! distance of each projected point) and `lekalo_intersect.txt` (`t_a t_b x y` of each
//! intersection point), and `lekalo_mesh.txt` (the mesh of the surface at 1e-4 for
//! `bench/peers/occt_mesh_deviation.py --lekalo-mesh`: a line `vertices triangles deviation`,
//! then `x y z u v` of each vertex and the vertex indices of each triangle).
//!
//! `cargo run --release --example query_peer -- [REPEATS [PROJECT_POINTS [ANSWERS_DIR]]]`

use std::fmt::Write as _;
use std::hint::black_box;
use std::time::Instant;

use lekalo::{Points, QueryCurve, QuerySurface};

#[path = "../benches/query_workloads/mod.rs"]
mod query_workloads;
use query_workloads::{
    arc, plane_curve, query_point, space_curve, surface, OFFSET_DISTANCE, OFFSET_TOLERANCE,
};

/// Median wall time in seconds of the runs of `f`: `repeats` runs, then more while they have
/// taken less than a second in all (at most 1,001), so that a fast workload is timed over many
/// runs on a noisy machine. `occt_queries.cpp` follows the same rule.
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

fn main() -> Result<(), lekalo::Error> {
    let mut args = std::env::args().skip(1);
    let repeats: usize = args.next().and_then(|a| a.parse().ok()).unwrap_or(5);
    let n: usize = args.next().and_then(|a| a.parse().ok()).unwrap_or(100_000);
    let answers = args.next();
    let write = |name: &str, text: String| {
        if let Some(dir) = &answers {
            std::fs::write(format!("{dir}/{name}"), text).expect("answers file");
        }
    };

    let curve = QueryCurve::from_bspline(&space_curve())?;
    let pts = Points::from_flat(3, (0..n).flat_map(query_point).collect())?;
    let mut dsum = 0.0;
    let mut dist = Vec::new();
    let t = median_s(repeats, || {
        let r = curve
            .project_batch(black_box(pts.as_view()))
            .expect("projections");
        dsum = r.iter().map(|p| p.distance).sum();
        dist = r;
    });
    write(
        "lekalo_project.txt",
        dist.iter().fold(String::new(), |mut s, p| {
            let _ = writeln!(s, "{:e}", p.distance);
            s
        }),
    );
    println!("lekalo project_1e5 {t:.6e} s per {n} points sum of distances {dsum:.12e}");
    let mut total = 0.0;
    let t = median_s(repeats, || {
        total = curve.arc_length(1e-12).expect("length").total();
    });
    println!("lekalo length_1e-12 {t:.6e} s length {total:.15e}");
    let table = curve.arc_length(1e-12)?;
    let lengths: Vec<f64> = (0..n)
        .map(|k| total * (0.618_033_988_749_895 * k as f64).fract())
        .collect();
    let mut psum = 0.0;
    let t = median_s(repeats, || {
        psum = table
            .param_at_batch(black_box(&lengths))
            .expect("params")
            .iter()
            .sum();
    });
    println!("lekalo param_at_1e5 {t:.6e} s per {n} lengths sum {psum:.12e}");
    let (a, b) = (
        QueryCurve::from_bspline(&plane_curve(0))?,
        QueryCurve::from_bspline(&plane_curve(1))?,
    );
    let mut hits = Vec::new();
    let t = median_s(repeats, || {
        hits = black_box(&a).intersect(&b, 1e-9).expect("intersections");
    });
    println!("lekalo intersect_100x100 {t:.6e} s points {}", hits.len());
    write(
        "lekalo_intersect.txt",
        hits.iter().fold(String::new(), |mut s, h| {
            if let lekalo::query::CurveIntersection::Point {
                t_a, t_b, point, ..
            } = h
            {
                let _ = writeln!(s, "{t_a:e} {t_b:e} {:e} {:e}", point[0], point[1]);
            } else {
                let _ = writeln!(s, "overlap {h:?}");
            }
            s
        }),
    );
    for (name, q) in [
        ("offset_cubic", QueryCurve::from_bspline(&plane_curve(0))?),
        ("offset_arc", QueryCurve::from_nurbs(&arc())?),
    ] {
        let mut facts = (0, 0.0);
        let t = median_s(repeats, || {
            let o = black_box(&q)
                .offset(OFFSET_DISTANCE, OFFSET_TOLERANCE)
                .expect("offset");
            facts = (o.curve.control_points().len(), o.deviation);
        });
        println!(
            "lekalo {name} {t:.6e} s control points {} deviation {:.3e}",
            facts.0, facts.1
        );
    }
    let s = QuerySurface::from_bspline(&surface())?;
    let mut facts = (0, 0, 0.0);
    let t = median_s(repeats, || {
        let m = black_box(&s).mesh(1e-4).expect("mesh");
        facts = (m.triangles.len(), m.uv.len(), m.deviation);
    });
    println!(
        "lekalo mesh_50x50 {t:.6e} s triangles {} nodes {} proved deviation {:.3e}",
        facts.0, facts.1, facts.2
    );
    if answers.is_some() {
        let m = s.mesh(1e-4)?;
        let mut text = format!("{} {} {:e}\n", m.uv.len(), m.triangles.len(), m.deviation);
        for (p, uv) in m.vertices.iter().zip(&m.uv) {
            let _ = writeln!(
                text,
                "{:e} {:e} {:e} {:e} {:e}",
                p[0], p[1], p[2], uv[0], uv[1]
            );
        }
        for t in &m.triangles {
            let _ = writeln!(text, "{} {} {}", t[0], t[1], t[2]);
        }
        write("lekalo_mesh.txt", text);
    }
    Ok(())
}
