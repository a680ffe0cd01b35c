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
//!
//! `cargo run --release --example query_peer -- ssi REPEATS DIR [CASE]`: the surface–surface
//! workloads only (`query_workloads::ssi_cases`; only the one named CASE if given, e.g. to count
//! its instructions with `valgrind --tool=callgrind`): writes each case's surfaces to `DIR/ssi_NAME.txt` for
//! `occt_queries ssi REPEATS DIR` (degrees, net size, full knot vectors, then `x y z w` of each
//! control point, `(i, j)` at line `i·nv + j`; or a line `plane ox oy oz nx ny nz`), times the
//! intersection (median of `REPEATS` runs, more for a fast one) and prints the branches: their
//! count, length, whether closed, and the largest exact distance of their points to both
//! surfaces (`query_workloads::Exact`); writes the points to `DIR/lekalo_ssi_NAME.txt` (a line
//! `branch K` before each branch) for `occt_queries` to measure with its projection. When
//! `DIR/occt_ssi_NAME.txt` (Open CASCADE's sampled branches, same format) exists, the largest
//! exact distance of its points is printed too.

use std::fmt::Write as _;
use std::hint::black_box;
use std::time::Instant;

use lekalo::{Points, QueryCurve, QuerySurface};

#[path = "../benches/query_workloads/mod.rs"]
mod query_workloads;
use query_workloads::{
    arc, plane_curve, query_point, space_curve, ssi_cases, surface, Exact, OFFSET_DISTANCE,
    OFFSET_TOLERANCE, SSI_TOLERANCE,
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

/// The net of a NURBS surface in the text format `occt_queries.cpp` reads.
fn surface_text(s: &lekalo::NurbsSurface) -> String {
    let (nu, nv) = s.net_size();
    let mut t = format!("{} {} {nu} {nv}\n", s.degree_u(), s.degree_v());
    for k in [s.knots_u(), s.knots_v()] {
        let line: Vec<String> = k.as_slice().iter().map(|x| format!("{x:.17e}")).collect();
        t += &line.join(" ");
        t.push('\n');
    }
    let (p, w) = (s.control_points(), s.weights());
    for (i, wi) in w.iter().enumerate() {
        let q = p.point(i);
        let _ = writeln!(t, "{:.17e} {:.17e} {:.17e} {wi:.17e}", q[0], q[1], q[2]);
    }
    t
}

/// Branches in the answers' text format: a line `branch K`, then `x y z` of each point.
fn read_branches(text: &str) -> Vec<Vec<[f64; 3]>> {
    let mut out: Vec<Vec<[f64; 3]>> = Vec::new();
    for line in text.lines() {
        if line.starts_with("branch") {
            out.push(Vec::new());
        } else if let Some(b) = out.last_mut() {
            let v: Vec<f64> = line
                .split_whitespace()
                .filter_map(|x| x.parse().ok())
                .collect();
            if v.len() == 3 {
                b.push([v[0], v[1], v[2]]);
            }
        }
    }
    out
}

/// The pieces (points, length) chained end to end into loops, as `occt_queries.cpp` does (ends
/// within 1e-5; a branch split where it crosses the seam of a closed surface is one loop): the
/// count and each chain's length, `closed` when its ends meet.
fn chain(pieces: &[(Vec<[f64; 3]>, f64)]) -> String {
    let near =
        |a: &[f64; 3], b: &[f64; 3]| (0..3).map(|c| (a[c] - b[c]).powi(2)).sum::<f64>() <= 1e-10;
    let mut used = vec![false; pieces.len()];
    let mut out = Vec::new();
    for s in 0..pieces.len() {
        if used[s] || pieces[s].0.is_empty() {
            continue;
        }
        used[s] = true;
        let (head, mut tail, mut len) = (
            pieces[s].0[0],
            *pieces[s].0.last().expect("points"),
            pieces[s].1,
        );
        while !near(&head, &tail) {
            let next = (0..pieces.len()).find(|&j| {
                !used[j]
                    && !pieces[j].0.is_empty()
                    && (near(&pieces[j].0[0], &tail)
                        || near(pieces[j].0.last().expect("points"), &tail))
            });
            let Some(j) = next else { break };
            used[j] = true;
            let p = &pieces[j].0;
            tail = if near(&p[0], &tail) {
                *p.last().expect("points")
            } else {
                p[0]
            };
            len += pieces[j].1;
        }
        out.push(format!(
            " {len:.9}{}",
            if near(&head, &tail) { " closed" } else { "" }
        ));
    }
    format!(" {}:{}", out.len(), out.concat())
}

/// The surface–surface workloads (see the module's doc).
fn ssi(repeats: usize, dir: &str, only: Option<&str>) -> Result<(), lekalo::Error> {
    std::fs::create_dir_all(dir).expect("answers directory");
    for case in ssi_cases() {
        if only.is_some_and(|name| name != case.name) {
            continue;
        }
        let mut text = format!("case {} {:e}\n", case.name, SSI_TOLERANCE);
        text += &surface_text(&case.a);
        match &case.b {
            Ok(b) => text += &surface_text(b),
            Err((o, n)) => {
                let _ = writeln!(
                    text,
                    "plane {:.17e} {:.17e} {:.17e} {:.17e} {:.17e} {:.17e}",
                    o[0], o[1], o[2], n[0], n[1], n[2]
                );
            }
        }
        std::fs::write(format!("{dir}/ssi_{}.txt", case.name), text).expect("surfaces file");
        let a = QuerySurface::from_nurbs(&case.a)?;
        let b = match &case.b {
            Ok(b) => Some(QuerySurface::from_nurbs(b)?),
            Err(_) => None,
        };
        let mut branches = Vec::new();
        let t = median_s(repeats, || {
            branches = match (&b, &case.b) {
                (Some(b), _) => black_box(&a).intersect_surface(b, SSI_TOLERANCE),
                (None, Err((o, n))) => black_box(&a).intersect_plane(o, n, SSI_TOLERANCE),
                _ => unreachable!("a plane case has a plane"),
            }
            .expect("branches");
        });
        let worst =
            |pts: &[[f64; 3]], e: &Exact| pts.iter().map(|p| e.distance(p)).fold(0.0, f64::max);
        let mut facts = String::new();
        let mut out = String::new();
        let mut dmax = (0.0_f64, 0.0_f64);
        for (k, br) in branches.iter().enumerate() {
            let _ = write!(
                facts,
                " [{:?}{} {} points length {:.9} curve {} control points]",
                br.kind,
                if br.closed { " closed" } else { "" },
                br.points.len(),
                br.length(),
                br.curve.as_ref().map_or(0, |c| c.control_points().len())
            );
            dmax.0 = dmax.0.max(worst(&br.points, &case.a_exact));
            dmax.1 = dmax.1.max(worst(&br.points, &case.b_exact));
            let _ = writeln!(out, "branch {k}");
            for p in &br.points {
                let _ = writeln!(out, "{:.17e} {:.17e} {:.17e}", p[0], p[1], p[2]);
            }
        }
        std::fs::write(format!("{dir}/lekalo_ssi_{}.txt", case.name), out).expect("answers");
        let pieces: Vec<(Vec<[f64; 3]>, f64)> = branches
            .iter()
            .map(|b| (b.points.clone(), b.length()))
            .collect();
        let _ = write!(facts, " chained into{}", chain(&pieces));
        let exact = case.exact.map_or(String::new(), |(n, len)| {
            format!(" exact: {n} branches of length {len:.9}")
        });
        println!(
            "lekalo {} {t:.6e} s branches {}{facts} max distance to A {:.3e} to B {:.3e}{exact}",
            case.name,
            branches.len(),
            dmax.0,
            dmax.1
        );
        if let Ok(text) = std::fs::read_to_string(format!("{dir}/occt_ssi_{}.txt", case.name)) {
            let occ = read_branches(&text);
            let (mut da, mut db, mut np) = (0.0_f64, 0.0_f64, 0);
            for br in &occ {
                da = da.max(worst(br, &case.a_exact));
                db = db.max(worst(br, &case.b_exact));
                np += br.len();
            }
            println!(
                "lekalo-check {} Open CASCADE's {} branches, {np} sampled points: max exact distance to A {da:.3e} to B {db:.3e}",
                case.name,
                occ.len()
            );
        }
    }
    Ok(())
}

fn main() -> Result<(), lekalo::Error> {
    let mut args = std::env::args().skip(1).peekable();
    if args.peek().map(String::as_str) == Some("ssi") {
        args.next();
        let repeats: usize = args.next().and_then(|a| a.parse().ok()).unwrap_or(5);
        let dir = args
            .next()
            .unwrap_or_else(|| "target/peers-occt/answers".into());
        let only = args.next();
        return ssi(repeats, &dir, only.as_deref());
    }
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
