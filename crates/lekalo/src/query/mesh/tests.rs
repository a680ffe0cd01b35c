use super::bounds::triangle_bound;
use super::strips::{best_zip, chains, zip};
use super::{Rule, PATCH_WIDTH};
use crate::query::tessellate::tests::{assert_covers_the_domain, assert_watertight};
use crate::query::tessellate::Mesh;
use crate::{BSplineSurface, Points, QuerySurface};
use std::sync::atomic::AtomicUsize;

/// `|S(Σ λ_i uv_i) − Σ λ_i P_i|` at the barycentric point `l` of triangle `t` of `mesh`: the
/// parametric deviation the mesh's bound is about.
fn sampled_deviation(s: &BSplineSurface, mesh: &Mesh, t: &[u32; 3], l: &[f64; 3]) -> f64 {
    let uv = t.map(|i| mesh.uv[i as usize]);
    let p = t.map(|i| mesh.vertices.point(i as usize).to_vec());
    let x = [0, 1].map(|d| (l[0] * uv[0][d] + l[1] * uv[1][d] + l[2] * uv[2][d]).clamp(0.0, 1.0));
    let sx = s.eval(x[0], x[1]).unwrap();
    (0..3)
        .map(|d| (sx[d] - (l[0] * p[0][d] + l[1] * p[1][d] + l[2] * p[2][d])).powi(2))
        .sum::<f64>()
        .sqrt()
}

#[test]
fn tiny_tolerances_are_refused_before_meshing() {
    // z = x² + y² on [0, 1]²: a tolerance of 1e-8 asked for ~10^8 triangles and the process
    // was killed for its memory; the estimate refuses it at once, naming the tolerance
    let net = Points::from_3d(&[
        [0.0, 0.0, 0.0],
        [0.0, 0.5, 0.0],
        [0.0, 1.0, 1.0],
        [0.5, 0.0, 0.0],
        [0.5, 0.5, 0.0],
        [0.5, 1.0, 1.0],
        [1.0, 0.0, 1.0],
        [1.0, 0.5, 1.0],
        [1.0, 1.0, 2.0],
    ])
    .unwrap();
    let knots = vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0];
    let s = BSplineSurface::new(2, 2, knots.clone(), knots, net, (3, 3)).unwrap();
    let q = QuerySurface::from_bspline(&s).unwrap();
    let start = std::time::Instant::now();
    let e = q.mesh(1e-8).unwrap_err();
    assert!(start.elapsed().as_secs() < 5, "refused before meshing");
    // the key of the tolerance: each front end names its own tolerance argument
    assert_eq!(e.arg(), Some(crate::Arg::Tolerance), "{e}");
    let e = e.to_string();
    assert!(
        e.contains("tessellation tolerance")
            && e.contains("1e-8 needs about")
            && e.contains("use a tolerance of at least"),
        "{e}"
    );
    // the tolerance the message suggests is accepted, and meshes below the limit
    let at_least: f64 = e.rsplit(' ').next().unwrap().parse().unwrap();
    assert!(at_least > 1e-8 && at_least < 1e-4, "{at_least}");
    let m = q.mesh(1e-3).unwrap();
    assert!(
        m.triangles.len() < crate::query::tessellate::MAX_MESH_TRIANGLES,
        "a small mesh is made"
    );
}

/// A small deterministic generator of numbers in `[0, 1)` (xorshift).
struct Rng(u64);
impl Rng {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1_u64 << 53) as f64
    }
}

/// Barycentric points of a triangle on a grid of step `1/n`.
fn barycentric(n: usize) -> Vec<[f64; 3]> {
    let mut out = Vec::new();
    for i in 0..=n {
        for j in 0..=n - i {
            let (a, b) = (i as f64 / n as f64, j as f64 / n as f64);
            out.push([a, b, 1.0 - a - b]);
        }
    }
    out
}

#[test]
fn triangle_bound_is_attained_by_convex_quadratics_and_never_exceeded() {
    // S(x) = ½ xᵀ H_d x per coordinate d: D²S[e, e] = eᵀ H_d e is constant and
    // S − L = −½ Σ λiλj D²S[e_ij, e_ij] exactly; with one coordinate and H positive
    // definite every term has the same sign, so the bound is the maximum itself
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    let grid = barycentric(60);
    for case in 0..200 {
        let dim = if case % 2 == 0 { 1 } else { 3 };
        let hs: Vec<[f64; 3]> = (0..dim)
            .map(|_| {
                let (a, c) = (rng.next() * 4.0, rng.next() * 4.0);
                let b = if dim == 1 {
                    (2.0 * rng.next() - 1.0) * (a * c).sqrt() // positive semi-definite
                } else {
                    4.0 * rng.next() - 2.0 // indefinite too
                };
                [a, b, c]
            })
            .collect();
        let s = |x: [f64; 2]| -> Vec<f64> {
            hs.iter()
                .map(|h| 0.5 * (h[0] * x[0] * x[0] + 2.0 * h[1] * x[0] * x[1] + h[2] * x[1] * x[1]))
                .collect()
        };
        let m = |e: [f64; 2]| {
            hs.iter()
                .map(|h| {
                    (h[0] * e[0] * e[0] + 2.0 * h[1] * e[0] * e[1] + h[2] * e[1] * e[1]).powi(2)
                })
                .sum::<f64>()
                .sqrt()
        };
        let v: Vec<[f64; 2]> = (0..3).map(|_| [rng.next(), rng.next()]).collect();
        let e = |i: usize, j: usize| [v[j][0] - v[i][0], v[j][1] - v[i][1]];
        let bound = triangle_bound([m(e(0, 1)), m(e(0, 2)), m(e(1, 2))]);
        let sv: Vec<Vec<f64>> = v.iter().map(|&x| s(x)).collect();
        let mut worst = 0.0_f64;
        for l in &grid {
            let x = [0, 1].map(|d| l[0] * v[0][d] + l[1] * v[1][d] + l[2] * v[2][d]);
            let sx = s(x);
            let dev = (0..dim)
                .map(|d| (sx[d] - (l[0] * sv[0][d] + l[1] * sv[1][d] + l[2] * sv[2][d])).powi(2))
                .sum::<f64>()
                .sqrt();
            worst = worst.max(dev);
        }
        assert!(
            worst <= bound * (1.0 + 1e-12) + 1e-15,
            "case {case}: {worst} > {bound}"
        );
        if dim == 1 {
            // the grid's best point is within 1/60 of the maximum's: nearly attained
            assert!(
                worst >= 0.99 * bound,
                "case {case}: {worst} far below {bound}"
            );
        }
    }
}

#[test]
fn triangle_bound_holds_on_random_cubic_patches() {
    // random bicubic patches, random triangles inside them: M_e from the patch's combined
    // second-derivative net, the deviation sampled densely
    let mut rng = Rng(42);
    let grid = barycentric(24);
    for case in 0..40 {
        let net: Vec<f64> = (0..16)
            .flat_map(|k| [(k / 4) as f64 / 3.0, (k % 4) as f64 / 3.0, 0.0])
            .zip(std::iter::repeat_with(|| rng.next()))
            .map(|(x, r)| x + 0.6 * (r - 0.5))
            .collect();
        let knots = vec![0., 0., 0., 0., 1., 1., 1., 1.];
        let surf = BSplineSurface::new(
            3,
            3,
            knots.clone(),
            knots,
            Points::from_flat(3, net).unwrap(),
            (4, 4),
        )
        .unwrap();
        let q = QuerySurface::from_bspline(&surf).unwrap();
        let sn = q.second_nets(q.patch(0));
        for _ in 0..10 {
            let size = 0.05 + 0.9 * rng.next();
            let o = [rng.next() * (1.0 - size), rng.next() * (1.0 - size)];
            let v: Vec<[f64; 2]> = (0..3)
                .map(|_| [o[0] + size * rng.next(), o[1] + size * rng.next()])
                .collect();
            let e = |i: usize, j: usize| sn.along(v[j][0] - v[i][0], v[j][1] - v[i][1]);
            let bound = triangle_bound([e(0, 1), e(0, 2), e(1, 2)]);
            let pts: Vec<Vec<f64>> = v
                .iter()
                .map(|x| q.point_on(0, x[0], x[1], &mut Vec::new()))
                .collect();
            for l in &grid {
                let x = [0, 1].map(|d| l[0] * v[0][d] + l[1] * v[1][d] + l[2] * v[2][d]);
                let sx = q.point_on(0, x[0], x[1], &mut Vec::new());
                let dev = (0..3)
                    .map(|d| {
                        (sx[d] - (l[0] * pts[0][d] + l[1] * pts[1][d] + l[2] * pts[2][d])).powi(2)
                    })
                    .sum::<f64>()
                    .sqrt();
                assert!(
                    dev <= bound * (1.0 + 1e-9) + 1e-14,
                    "case {case}: {dev} > {bound}"
                );
            }
        }
    }
}

#[test]
fn random_surfaces_are_meshed_within_their_bound_without_cracks() {
    // bicubic 3 × 4-patch surfaces with random heights and a random twist: strips, the
    // best strips and vertex removal all occur; every triangle, densely sampled, within
    // the reported bound, the mesh closed and its parameter triangles tiling the domain
    let mut rng = Rng(7);
    let grid = barycentric(6);
    for case in 0..6 {
        let twist = 4.0 * rng.next() - 2.0;
        let s = random_surface(&mut rng, twist);
        let q = QuerySurface::from_bspline(&s).unwrap();
        let tol = [1e-3, 3e-4][case % 2];
        let mesh = q.mesh(tol).unwrap();
        assert!(mesh.deviation <= tol, "case {case}: {}", mesh.deviation);
        for t in &mesh.triangles {
            for l in &grid {
                let dev = sampled_deviation(&s, &mesh, t, l);
                assert!(
                    dev <= mesh.deviation * (1.0 + 1e-9),
                    "case {case}: {dev} > {} in {t:?}",
                    mesh.deviation
                );
            }
        }
        assert_watertight(&mesh);
        assert_covers_the_domain(&mesh, &format!("case {case}"));
        // every vertex is used
        let mut used = vec![false; mesh.uv.len()];
        for t in &mesh.triangles {
            for &i in t {
                used[i as usize] = true;
            }
        }
        assert!(used.iter().all(|&u| u), "case {case}: an unused vertex");
    }
}

/// A bicubic 3 × 4-patch surface with random heights and twist `twist`.
fn random_surface(rng: &mut Rng, twist: f64) -> BSplineSurface {
    let (nu, nv) = (6, 7);
    let mut net = Vec::new();
    for i in 0..nu {
        for j in 0..nv {
            let (x, y) = (i as f64 / 5.0, j as f64 / 6.0);
            net.extend([x, y, twist * (x - 0.5) * (y - 0.5) + 0.3 * rng.next()]);
        }
    }
    let ku = vec![0., 0., 0., 0., 0.3, 0.5, 1., 1., 1., 1.];
    let kv = vec![0., 0., 0., 0., 0.2, 0.5, 0.7, 1., 1., 1., 1.];
    BSplineSurface::new(3, 3, ku, kv, Points::from_flat(3, net).unwrap(), (nu, nv)).unwrap()
}

#[test]
fn parts_split_in_later_rounds_keep_the_mesh_closed_and_bounded() {
    // every part with points on its sides split in the first rounds (as if none of its
    // triangulations were within the tolerance), then, past the last round, every part
    // refined to (A + 2B + C)/8: the sides are matched again each round
    let mut rng = Rng(11);
    let s = random_surface(&mut rng, 1.5);
    let q = QuerySurface::from_bspline(&s).unwrap();
    let grid = super::plan::PatchGrid::new(&q);
    let tol = 3e-3;
    let plain = q.mesh(tol).unwrap();
    for forced in [2, super::MAX_ROUNDS + 1] {
        let progress = crate::Progress::new();
        let hook = super::driver::MeshProgress::new(&progress);
        let mesh = q
            .mesh_polynomial(tol / q.scale(), &grid, forced, &hook)
            .unwrap();
        assert!(mesh.deviation <= tol, "forced {forced}: {}", mesh.deviation);
        assert!(
            mesh.triangles.len() > plain.triangles.len(),
            "forced {forced}: no part was split"
        );
        assert_watertight(&mesh);
        assert_covers_the_domain(&mesh, &format!("forced {forced}"));
        // (past the last round, 46,710 triangles against 817: every 7th)
        let samples = barycentric(4);
        for t in mesh
            .triangles
            .iter()
            .step_by(if forced > 2 { 7 } else { 1 })
        {
            for l in &samples {
                let dev = sampled_deviation(&s, &mesh, t, l);
                assert!(
                    dev <= mesh.deviation * (1.0 + 1e-9),
                    "forced {forced}: {dev}"
                );
            }
        }
    }
}

#[test]
fn a_twisted_surface_takes_the_cancelling_diagonal() {
    // heights 0.2 (x² + y² − 3xy) at the Greville points of a bicubic 4 × 4-patch spline:
    // S_uv dominates and has the sign opposite S_uu and S_vv, so |S_uu + 2S_uv + S_vv| is
    // far below |S_uu| + 2|S_uv| + |S_vv|
    let n = 7;
    let knots = vec![0., 0., 0., 0., 0.25, 0.5, 0.75, 1., 1., 1., 1.];
    let greville: Vec<f64> = (0..n)
        .map(|i| (knots[i + 1] + knots[i + 2] + knots[i + 3]) / 3.0)
        .collect();
    let net: Vec<f64> = greville
        .iter()
        .flat_map(|&x| {
            greville
                .iter()
                .flat_map(move |&y| [x, y, 0.2 * (x * x + y * y - 3.0 * x * y)])
        })
        .collect();
    let s = BSplineSurface::new(
        3,
        3,
        knots.clone(),
        knots,
        Points::from_flat(3, net).unwrap(),
        (n, n),
    )
    .unwrap();
    let q = QuerySurface::from_bspline(&s).unwrap();
    let tol = 2e-5;
    let mesh = q.mesh(tol).unwrap();
    assert!(mesh.deviation <= tol, "{}", mesh.deviation);
    // the rule with the cross term at its worst sign, (A + 2B + C)/8 for every part
    // (halving), needs at least two triangles a part; this mesh, fewer than half as many
    // (8,192 triangles against 16,384 parts)
    let count = AtomicUsize::new(0);
    let whole = ((0, PATCH_WIDTH), (0, PATCH_WIDTH));
    let any: usize = (0..q.patch_count())
        .map(|k| {
            let t = tol / q.scale();
            q.poly_leaves(k, q.patch(k).to_vec(), whole, t, Rule::Any, false, &count)
                .unwrap()
                .len()
        })
        .sum();
    assert!(
        mesh.triangles.len() < any,
        "{} triangles against {} parts of the any-triangle rule",
        mesh.triangles.len(),
        any
    );
    // every triangle, densely sampled, within the bound
    let grid = barycentric(8);
    for t in &mesh.triangles {
        for l in &grid {
            let dev = sampled_deviation(&s, &mesh, t, l);
            assert!(
                dev <= mesh.deviation * (1.0 + 1e-9),
                "{dev} > {} in {t:?}",
                mesh.deviation
            );
        }
    }
    assert_watertight(&mesh);
}

#[test]
fn a_parabolic_cylinder_is_cut_into_thirds() {
    // z = x² on [0, 1]²: A = 2, B = C = 0; at tolerance 0.03 halving leaves 0.0625 and
    // thirds 2/72: three parts, six triangles, vertices at u = 1/3 and 2/3
    let net = Points::from_3d(&[
        [0., 0., 0.],
        [0., 1., 0.],
        [0.5, 0., 0.],
        [0.5, 1., 0.],
        [1., 0., 1.],
        [1., 1., 1.],
    ])
    .unwrap();
    let s = BSplineSurface::new(
        2,
        1,
        vec![0., 0., 0., 1., 1., 1.],
        vec![0., 0., 1., 1.],
        net,
        (3, 2),
    )
    .unwrap();
    let mesh = QuerySurface::from_bspline(&s).unwrap().mesh(0.03).unwrap();
    assert_eq!(mesh.triangles.len(), 6, "{mesh:?}");
    assert!(
        mesh.deviation <= 0.03 && mesh.deviation > 0.02,
        "{}",
        mesh.deviation
    );
    for third in [1.0 / 3.0, 2.0 / 3.0] {
        assert!(
            mesh.uv.iter().any(|p| (p[0] - third).abs() < 1e-12),
            "no vertex at u = {third}: {:?}",
            mesh.uv
        );
    }
    // the vertices lie on the surface
    for (p, uv) in mesh.vertices.iter().zip(&mesh.uv) {
        assert!((p[2] - uv[0] * uv[0]).abs() < 1e-15, "{p:?} at {uv:?}");
    }
}

#[test]
fn strips_cover_the_rectangle_with_proper_triangles() {
    // the unit square's boundary, counter-clockwise from (0, 0), with extra side points
    let sides: [&[f64]; 4] = [&[0.25, 0.5], &[0.5], &[0.8, 0.3, 0.1], &[]];
    let mut pts: Vec<[f64; 2]> = vec![[0.0, 0.0]];
    pts.extend(sides[0].iter().map(|&u| [u, 0.0]));
    pts.push([1.0, 0.0]);
    pts.extend(sides[1].iter().map(|&v| [1.0, v]));
    let tr = pts.len();
    pts.push([1.0, 1.0]);
    pts.extend(sides[2].iter().map(|&u| [u, 1.0]));
    pts.push([0.0, 1.0]);
    pts.extend(sides[3].iter().map(|&v| [0.0, v]));
    let ring: Vec<u32> = (0..u32::try_from(pts.len()).unwrap()).collect();
    // both pairs of opposite corners, with the moves in every order
    let br = 1 + sides[0].len();
    let tl = tr + 1 + sides[2].len();
    for (s, t) in [(0, tr), (br, tl)] {
        let (a, b) = chains(&ring, s, t);
        let steps = a.len() + b.len() - 2;
        for order in 0..1_u32 << steps {
            let moves: Vec<bool> = (0..steps).map(|k| order >> k & 1 == 1).collect();
            if moves.iter().filter(|&&m| m).count() != a.len() - 1 {
                continue;
            }
            let mut tris = Vec::new();
            zip(ring[s], ring[t], &a, &b, &moves, &mut tris);
            assert_proper_cover(&pts, &tris, ring.len());
        }
    }
}

#[test]
fn best_zip_finds_the_least_largest_cost() {
    // random costs of triangles (a function of their vertex sets): the dynamic programme's
    // strip against every order of the moves
    let mut rng = Rng(3);
    for case in 0..50_u32 {
        let (na, nb) = (1 + case % 4, 1 + (case / 4) % 4);
        let a: Vec<u32> = (1..=na).collect();
        let b: Vec<u32> = (100..100 + nb).collect();
        let (s, t) = (0_u32, 50_u32);
        let salt = rng.next();
        let cost = |x: u32, y: u32, z: u32| {
            let mut v = [x, y, z];
            v.sort_unstable();
            let h = v
                .iter()
                .fold(salt, |h, &k| (h * 7.31 + f64::from(k) * 0.123).fract());
            h
        };
        let (moves, best) = best_zip(s, t, &a, &b, &cost);
        let largest = |moves: &[bool]| {
            let mut tris = Vec::new();
            zip(s, t, &a, &b, moves, &mut tris);
            tris.iter()
                .map(|t| cost(t[0], t[1], t[2]))
                .fold(0.0, f64::max)
        };
        assert_eq!(moves.len(), (na + nb - 2) as usize, "case {case}");
        assert_eq!(largest(&moves), best, "case {case}");
        let steps = na + nb - 2;
        for order in 0..1_u32 << steps {
            let m: Vec<bool> = (0..steps).map(|k| order >> k & 1 == 1).collect();
            if m.iter().filter(|&&x| x).count() == (na - 1) as usize {
                assert!(largest(&m) >= best, "case {case}: {m:?} beats {moves:?}");
            }
        }
    }
}

/// `tris` are `n − 2` counter-clockwise triangles, none degenerate, covering the unit
/// square.
fn assert_proper_cover(pts: &[[f64; 2]], tris: &[[u32; 3]], n: usize) {
    assert_eq!(tris.len(), n - 2, "{tris:?}");
    let mut area = 0.0;
    for t in tris {
        let [a, b, c] = t.map(|i| pts[i as usize]);
        let twice = (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]);
        assert!(
            twice > 1e-3,
            "{t:?} is not a proper counter-clockwise triangle in {tris:?}"
        );
        area += 0.5 * twice;
    }
    assert!((area - 1.0).abs() < 1e-14, "area {area}");
}

/// The progress hook sees the work go from 0 to the whole without going back, the mesh is the
/// same as without it, and a set cancel flag stops the mesh with `Cancelled`, polynomial or
/// rational.
#[test]
fn mesh_progress_is_monotone_and_cancel_stops_it() {
    use std::sync::atomic::AtomicBool;
    use std::sync::Mutex;
    let mut rng = Rng(5);
    let s = random_surface(&mut rng, 1.5);
    let q = QuerySurface::from_bspline(&s).unwrap();
    let rational = QuerySurface::from_nurbs(&crate::NurbsSurface::from_bspline(&s)).unwrap();
    for q in [q, rational] {
        let seen = Mutex::new(Vec::new());
        let report = |d: u64, t: u64| seen.lock().unwrap().push((d, t));
        let plain = q.mesh(3e-3).unwrap();
        let with = q
            .mesh_with_progress(3e-3, &crate::Progress::new().with_report(&report))
            .unwrap();
        assert_eq!(with, plain);
        let seen = seen.into_inner().unwrap();
        assert!(seen.len() > 2, "{seen:?}");
        assert!(seen.windows(2).all(|w| w[0].0 <= w[1].0), "{seen:?}");
        assert_eq!(seen.first().unwrap().0, 0);
        assert_eq!(*seen.last().unwrap(), (1000, 1000));
        let cancel = AtomicBool::new(true);
        let e = q
            .mesh_with_progress(3e-3, &crate::Progress::new().with_cancel(&cancel))
            .unwrap_err();
        assert!(matches!(e, crate::Error::Cancelled { .. }), "{e}");
    }
}

/// A random rational Bezier patch of degree `(p, q)`: points in `[−1, 1]³`, weights in
/// `[w_lo, w_hi]`.
fn random_rational_patch(rng: &mut Rng, p: usize, q: usize, w: (f64, f64)) -> QuerySurface {
    let n = (p + 1) * (q + 1);
    let ctrl: Vec<f64> = (0..3 * n).map(|_| 2.0 * rng.next() - 1.0).collect();
    let weights: Vec<f64> = (0..n).map(|_| w.0 + (w.1 - w.0) * rng.next()).collect();
    let knots = |k: usize| [vec![0.0; k + 1], vec![1.0; k + 1]].concat();
    let s = crate::NurbsSurface::new(
        p,
        q,
        knots(p),
        knots(q),
        Points::from_flat(3, ctrl).unwrap(),
        weights,
        (p + 1, q + 1),
    )
    .unwrap();
    QuerySurface::from_nurbs(&s).unwrap()
}

/// The rational `(A, B, C)` of `net_bounds` bound the surface's own `|S_uu|, |S_uv|, |S_vv|`
/// (the quotient rule applied to `S − Λ`, `Λ` affine), sampled on a grid of each part, for
/// patches with weights far apart and for their quarters and sixteenths.
#[test]
fn rational_bounds_hold_for_the_second_derivatives() {
    let mut rng = Rng(41);
    for case in 0..24 {
        let (p, q) = [(2, 1), (2, 2), (3, 2), (1, 3)][case % 4];
        let w = [(0.35, 4.0), (0.7, 1.0), (0.1, 10.0)][case % 3];
        let s = random_rational_patch(&mut rng, p, q, w);
        let mut nets = vec![s.patch(0).to_vec()];
        for _ in 0..2 {
            nets = nets
                .iter()
                .flat_map(|n| {
                    let (l, h) = s.halve_u(n);
                    let (ll, lh) = s.halve_v(&l);
                    let (hl, hh) = s.halve_v(&h);
                    [ll, lh, hl, hh]
                })
                .chain(nets.iter().take(1).cloned())
                .collect();
        }
        for net in &nets {
            let (a, b, c) = s.net_bounds(net).unwrap();
            let mut seen = [0.0_f64; 3];
            for i in 0..=12 {
                for j in 0..=12 {
                    let (_, der) = s.eval_net(net, i as f64 / 12.0, j as f64 / 12.0);
                    for k in 0..3 {
                        let x = &der[(2 + k) * 3..][..3];
                        seen[k] = seen[k].max(x.iter().map(|t| t * t).sum::<f64>().sqrt());
                    }
                }
            }
            for (k, bound) in [a, b, c].into_iter().enumerate() {
                assert!(
                    seen[k] <= bound * (1.0 + 1e-9) + 1e-12,
                    "case {case}: derivative {k} reaches {} above its bound {bound}",
                    seen[k]
                );
            }
        }
    }
}

/// A rod: the quarter-arc NURBS cylinder of radius 1.0795 and length 1147.7625 (a rod of a
/// CAD part, the `v` direction straight and a thousand times its radius).
fn rod() -> crate::NurbsSurface {
    use crate::surface::Placement;
    let frame = Placement::new([0.0; 3], None, None).unwrap();
    crate::NurbsSurface::cylinder(
        &frame,
        1.0795,
        (0.0, std::f64::consts::TAU),
        (0.0, 1147.7625),
    )
    .unwrap()
}

/// The largest sampled deviation of the uniform grid of `n` steps in `u` and one in `v`
/// (two triangles a step) from `s`.
fn uniform_rod_deviation(s: &crate::NurbsSurface, n: usize) -> f64 {
    let ((u0, u1), (v0, v1)) = s.domain();
    let mut worst = 0.0_f64;
    for i in 0..n {
        let (a, b) = (
            u0 + (u1 - u0) * i as f64 / n as f64,
            u0 + (u1 - u0) * (i + 1) as f64 / n as f64,
        );
        for tri in [[[a, v0], [b, v0], [b, v1]], [[a, v0], [b, v1], [a, v1]]] {
            let p = tri.map(|x| s.eval(x[0], x[1]).unwrap());
            for l in barycentric(8) {
                let x = [0, 1].map(|d| l[0] * tri[0][d] + l[1] * tri[1][d] + l[2] * tri[2][d]);
                let sx = s.eval(x[0], x[1]).unwrap();
                let e = (0..3)
                    .map(|d| (sx[d] - (l[0] * p[0][d] + l[1] * p[1][d] + l[2] * p[2][d])).powi(2))
                    .sum::<f64>()
                    .sqrt();
                worst = worst.max(e);
            }
        }
    }
    worst
}

/// The rod meshed at 0.1 has a few times the triangles of the uniform grid whose sampled
/// deviation meets 0.1 (eight steps round, one along). With the rational bound taken about a
/// constant centre, the long straight direction entered every term (the part's radius, the
/// slopes of the interpolant along it) and the rod took 41,952 triangles.
#[test]
fn a_long_rational_rod_has_no_more_triangles_than_a_few_uniform_grids() {
    let s = rod();
    let tol = 0.1;
    let n = (1..=64)
        .find(|&n| uniform_rod_deviation(&s, n) <= tol)
        .unwrap();
    let m = QuerySurface::from_nurbs(&s).unwrap().mesh(tol).unwrap();
    assert!(m.deviation <= tol, "{}", m.deviation);
    assert!(
        m.triangles.len() <= 4 * 2 * n,
        "{} triangles, where the uniform grid of {n} steps has {} within {tol}",
        m.triangles.len(),
        2 * n
    );
    // the bound holds where sampled
    let ((u0, u1), (v0, v1)) = s.domain();
    for t in &m.triangles {
        let uv = t.map(|i| m.uv[i as usize]);
        let p = t.map(|i| m.vertices.point(i as usize).to_vec());
        for l in barycentric(6) {
            let x = [(0, u0, u1), (1, v0, v1)].map(|(d, lo, hi)| {
                (l[0] * uv[0][d] + l[1] * uv[1][d] + l[2] * uv[2][d]).clamp(lo, hi)
            });
            let sx = s.eval(x[0], x[1]).unwrap();
            let e = (0..3)
                .map(|d| (sx[d] - (l[0] * p[0][d] + l[1] * p[1][d] + l[2] * p[2][d])).powi(2))
                .sum::<f64>()
                .sqrt();
            assert!(e <= m.deviation * (1.0 + 1e-9), "{e} > {}", m.deviation);
        }
    }
}
