//! Property tests for NURBS curves and tensor-product surfaces (B-spline, NURBS, Bezier):
//! NURBS with unit weights equal the B-spline, partition of unity of the tensor basis, partial
//! and rational derivatives against finite differences, normals, affine invariance, iso-curves,
//! circles and arcs. Randomness only from proptest strategies.

use lekalo::{
    basis::{basis_function_recursive, basis_functions},
    BSplineCurve, BSplineSurface, BezierSurface, Error, NurbsCurve, NurbsSurface, Points,
};
use proptest::prelude::*;

use lekalo_testkit::{assert_near, config};
use std::f64::consts::TAU;

/// Clamped knots on `[0, 1]` for `degree` and `n` control points, with sorted random interior
/// knots drawn from `(0.05, 0.95)` and kept at least 0.02 apart (simple knots: the spline is
/// `C^{p−1}`).
fn clamped_knots(degree: usize, n: usize) -> impl Strategy<Value = Vec<f64>> {
    let interior = n - degree - 1;
    prop::collection::vec(0.05f64..0.95, interior).prop_map(move |mut xs| {
        xs.sort_by(f64::total_cmp);
        for i in 1..xs.len() {
            if xs[i] < xs[i - 1] + 0.02 {
                xs[i] = xs[i - 1] + 0.02;
            }
        }
        let mut k = vec![0.0; degree + 1];
        // shrink into (0, 1) if the spacing pushed the last knot out
        let top = xs.last().copied().unwrap_or(0.0).max(0.95);
        k.extend(xs.iter().map(|x| x * 0.95 / top));
        k.extend(std::iter::repeat_n(1.0, degree + 1));
        k
    })
}

/// A random B-spline surface: degrees in `deg`, 0–3 interior knots per direction, dimension
/// in `dims`, coordinates in [−10, 10].
fn bspline_surface(
    deg: std::ops::RangeInclusive<usize>,
    dims: std::ops::RangeInclusive<usize>,
) -> impl Strategy<Value = BSplineSurface> {
    (deg.clone(), deg, 0usize..=3, 0usize..=3, dims)
        .prop_flat_map(|(p, q, eu, ev, dim)| {
            let (nu, nv) = (p + 1 + eu, q + 1 + ev);
            (
                clamped_knots(p, nu),
                clamped_knots(q, nv),
                prop::collection::vec(-10.0f64..10.0, nu * nv * dim),
                Just((p, q, nu, nv, dim)),
            )
        })
        .prop_map(|(ku, kv, data, (p, q, nu, nv, dim))| {
            BSplineSurface::new(
                p,
                q,
                ku,
                kv,
                Points::from_flat(dim, data).unwrap(),
                (nu, nv),
            )
            .unwrap()
        })
}

/// A random NURBS surface: a B-spline surface and weights in [0.3, 3].
fn nurbs_surface(
    deg: std::ops::RangeInclusive<usize>,
    dims: std::ops::RangeInclusive<usize>,
) -> impl Strategy<Value = NurbsSurface> {
    bspline_surface(deg, dims)
        .prop_flat_map(|s| {
            let n = s.control_points().len();
            (Just(s), prop::collection::vec(0.3f64..3.0, n))
        })
        .prop_map(|(s, w)| {
            NurbsSurface::new(
                s.degree_u(),
                s.degree_v(),
                s.knots_u().as_slice().to_vec(),
                s.knots_v().as_slice().to_vec(),
                s.control_points().clone(),
                w,
                s.net_size(),
            )
            .unwrap()
        })
}

/// A random NURBS curve of degree 1–4, dimension 1–6, weights in [0.3, 3].
fn nurbs_curve() -> impl Strategy<Value = NurbsCurve> {
    (1usize..=4, 0usize..=4, 1usize..=6)
        .prop_flat_map(|(p, extra, dim)| {
            let n = p + 1 + extra;
            (
                Just((p, dim)),
                clamped_knots(p, n),
                prop::collection::vec(-10.0f64..10.0, n * dim),
                prop::collection::vec(0.3f64..3.0, n),
            )
        })
        .prop_map(|((p, dim), k, data, w)| {
            NurbsCurve::new(p, k, Points::from_flat(dim, data).unwrap(), w).unwrap()
        })
}

/// A NURBS surface with the same knots and net as `s` and unit weights, built through `new`.
fn unit_weight_nurbs(s: &BSplineSurface) -> NurbsSurface {
    NurbsSurface::new(
        s.degree_u(),
        s.degree_v(),
        s.knots_u().as_slice().to_vec(),
        s.knots_v().as_slice().to_vec(),
        s.control_points().clone(),
        vec![1.0; s.control_points().len()],
        s.net_size(),
    )
    .unwrap()
}

proptest! {
    #![proptest_config(config(64))]

    /// NURBS curves with unit weights are the B-spline: points and derivatives, dims 1..=6.
    #[test]
    fn nurbs_curve_with_unit_weights_is_the_bspline(c in nurbs_curve(), t in 0.0f64..=1.0) {
        let ctrl = c.control_points();
        let b = BSplineCurve::new(c.degree(), c.knots().as_slice().to_vec(), ctrl.clone()).unwrap();
        let n = NurbsCurve::new(c.degree(), c.knots().as_slice().to_vec(), ctrl.clone(), vec![1.0; ctrl.len()]).unwrap();
        let (db, dn) = (b.eval_derivatives(t, 3).unwrap(), n.eval_derivatives(t, 3).unwrap());
        let scale = db.max_abs().max(1.0);
        assert_near(dn.as_slice(), db.as_slice(), 1e-12 * scale, 0.0, "derivatives");
        assert_near(&n.eval(t).unwrap(), &b.eval(t).unwrap(), 1e-13 * scale, 0.0, "point");
    }

    /// Rational curve derivatives (quotient rule) against central differences of the order below.
    #[test]
    fn nurbs_curve_derivatives_match_finite_differences(c in nurbs_curve(), t in 0.01f64..0.99) {
        let h = 1e-6;
        let d = c.eval_derivatives(t, 2).unwrap();
        let lo = c.eval_derivatives(t - h, 1).unwrap();
        let hi = c.eval_derivatives(t + h, 1).unwrap();
        for k in 1..=2 {
            // differencing C^(k−1) needs it to be C¹: degree ≥ k + 1 (simple knots)
            if c.degree() < k + 1 { continue; }
            let fd: Vec<f64> = hi.point(k - 1).iter().zip(lo.point(k - 1)).map(|(a, b)| (a - b) / (2.0 * h)).collect();
            let scale = d.point(k).iter().fold(1.0f64, |m, x| m.max(x.abs()));
            assert_near(&fd, d.point(k), 1e-4 * scale, 0.0, "C^(k)");
        }
    }

    /// The batch evaluation of NURBS curves equals single evaluation.
    #[test]
    fn nurbs_curve_batch_equals_eval(c in nurbs_curve(), ts in prop::collection::vec(0.0f64..=1.0, 0..20)) {
        let dim = c.dim();
        let mut out = vec![0.0; ts.len() * dim];
        c.eval_batch(&ts, &mut out).unwrap();
        for (k, &t) in ts.iter().enumerate() {
            let p = c.eval(t).unwrap();
            assert_near(&out[k * dim..(k + 1) * dim], &p, 1e-14, 1e-14, "batch");
        }
    }

    /// NURBS surfaces with unit weights are the B-spline surface: points, partials, iso-curves.
    #[test]
    fn nurbs_surface_with_unit_weights_is_the_bspline(
        s in bspline_surface(0..=3, 1..=6), u in 0.0f64..=1.0, v in 0.0f64..=1.0,
    ) {
        let n = unit_weight_nurbs(&s);
        let (db, dn) = (s.eval_derivatives(u, v, 2).unwrap(), n.eval_derivatives(u, v, 2).unwrap());
        let scale = db.max_abs().max(1.0);
        assert_near(dn.as_slice(), db.as_slice(), 1e-12 * scale, 0.0, "partials");
        let iso = n.iso_curve_u(v).unwrap().eval(u).unwrap();
        assert_near(&iso, &s.eval(u, v).unwrap(), 1e-12 * scale, 0.0, "iso-curve");
    }

    /// Partition of unity and non-negativity of the tensor basis `N_i(u) N_j(v)`: the surface
    /// whose control point `(i, j)` is the unit vector `e_{i·nv + j}` evaluates to the vector of
    /// all tensor basis values, which must equal the products of the curve bases.
    #[test]
    fn tensor_basis_partition_of_unity(
        shape in bspline_surface(0..=3, 1..=1), u in 0.0f64..=1.0, v in 0.0f64..=1.0,
    ) {
        let (nu, nv) = shape.net_size();
        let n = nu * nv;
        let mut data = vec![0.0; n * n];
        for k in 0..n { data[k * n + k] = 1.0; }
        let s = BSplineSurface::new(
            shape.degree_u(), shape.degree_v(),
            shape.knots_u().as_slice().to_vec(), shape.knots_v().as_slice().to_vec(),
            Points::from_flat(n, data).unwrap(), (nu, nv),
        ).unwrap();
        let b = s.eval(u, v).unwrap();
        let sum: f64 = b.iter().sum();
        prop_assert!((sum - 1.0).abs() < 1e-14, "Σ N_i N_j = {sum}");
        prop_assert!(b.iter().all(|&x| x >= 0.0), "non-negative");
        let (su, bu) = basis_functions(s.knots_u(), s.degree_u(), u).unwrap();
        let (sv, bv) = basis_functions(s.knots_v(), s.degree_v(), v).unwrap();
        for i in 0..nu {
            for j in 0..nv {
                let ni = if i + s.degree_u() >= su && i <= su { bu[i + s.degree_u() - su] } else { 0.0 };
                let nj = if j + s.degree_v() >= sv && j <= sv { bv[j + s.degree_v() - sv] } else { 0.0 };
                prop_assert!((b[i * nv + j] - ni * nj).abs() < 1e-15, "N_{i} N_{j}");
            }
        }
    }

    /// B-spline surface partials `S_{u^k v^l}` (k, l ≤ 1 plus S_uu, S_vv) against central
    /// differences of the orders below; degrees ≥ 2 so that first partials are continuous.
    #[test]
    fn bspline_partials_match_finite_differences(
        s in bspline_surface(2..=4, 1..=6), u in 0.01f64..0.99, v in 0.01f64..0.99,
    ) {
        check_partials(|u, v, o| s.eval_derivatives(u, v, o).unwrap(), u, v, (s.degree_u(), s.degree_v()));
    }

    /// Rational surface partials (P&T A4.4) against central differences.
    #[test]
    fn nurbs_partials_match_finite_differences(
        s in nurbs_surface(2..=3, 1..=4), u in 0.01f64..0.99, v in 0.01f64..0.99,
    ) {
        check_partials(|u, v, o| s.eval_derivatives(u, v, o).unwrap(), u, v, (s.degree_u(), s.degree_v()));
    }

    /// Normals are unit vectors orthogonal to S_u and S_v (3-D B-spline and NURBS surfaces).
    #[test]
    fn normals_are_orthogonal_to_the_partials(
        s in nurbs_surface(1..=3, 3..=3), u in 0.0f64..=1.0, v in 0.0f64..=1.0,
    ) {
        let d = s.eval_derivatives(u, v, 1).unwrap();
        let (su, sv) = (d.point(2), d.point(1));
        let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
        match s.normal(u, v) {
            Ok(n) => {
                prop_assert!((dot(&n, &n) - 1.0).abs() < 1e-14, "unit");
                let (lu, lv) = (dot(su, su).sqrt(), dot(sv, sv).sqrt());
                prop_assert!(dot(&n, su).abs() <= 1e-13 * lu, "n·S_u");
                prop_assert!(dot(&n, sv).abs() <= 1e-13 * lv, "n·S_v");
            }
            Err(e) => prop_assert!(matches!(e, lekalo::Error::InvalidArgument { .. }), "{e}"),
        }
        // the homogeneous surface is 4-D: no normal
        let no_normal = matches!(s.homogeneous().normal(u, v), Err(lekalo::Error::Dimension { .. }));
        prop_assert!(no_normal, "4-D homogeneous surface");
    }

    /// Affine invariance: transforming the control points by `x ↦ A x + b` transforms every
    /// surface point the same way (B-spline and NURBS, weights unchanged).
    #[test]
    fn affine_invariance(
        s in nurbs_surface(0..=3, 1..=4),
        m in prop::collection::vec(-2.0f64..2.0, 16),
        shift in prop::collection::vec(-50.0f64..50.0, 4),
        u in 0.0f64..=1.0, v in 0.0f64..=1.0,
    ) {
        let dim = s.dim();
        let map = |p: &[f64]| -> Vec<f64> {
            (0..dim).map(|r| shift[r] + (0..dim).map(|c| m[r * 4 + c] * p[c]).sum::<f64>()).collect()
        };
        let ctrl = s.control_points();
        let moved: Vec<f64> = ctrl.iter().flat_map(&map).collect();
        let t = NurbsSurface::new(
            s.degree_u(), s.degree_v(),
            s.knots_u().as_slice().to_vec(), s.knots_v().as_slice().to_vec(),
            Points::from_flat(dim, moved).unwrap(), s.weights(), s.net_size(),
        ).unwrap();
        let scale = 50.0 + 8.0 * 10.0;
        assert_near(&t.eval(u, v).unwrap(), &map(&s.eval(u, v).unwrap()), 1e-13 * scale, 0.0, "NURBS");
    }

    /// Grid and list batches equal single evaluation; iso-curves in both directions trace the
    /// surface.
    #[test]
    fn batches_and_iso_curves(
        s in bspline_surface(0..=3, 1..=6),
        us in prop::collection::vec(0.0f64..=1.0, 0..6),
        vs in prop::collection::vec(0.0f64..=1.0, 0..6),
    ) {
        let dim = s.dim();
        let mut grid = vec![0.0; us.len() * vs.len() * dim];
        s.eval_grid(&us, &vs, &mut grid).unwrap();
        let pairs: Vec<[f64; 2]> = us.iter().flat_map(|&u| vs.iter().map(move |&v| [u, v])).collect();
        let mut list = vec![0.0; pairs.len() * dim];
        s.eval_batch(&pairs, &mut list).unwrap();
        for (k, &[u, v]) in pairs.iter().enumerate() {
            let p = s.eval(u, v).unwrap();
            assert_near(&grid[k * dim..(k + 1) * dim], &p, 0.0, 0.0, "grid");
            assert_near(&list[k * dim..(k + 1) * dim], &p, 0.0, 0.0, "list");
            assert_near(&s.iso_curve_u(v).unwrap().eval(u).unwrap(), &p, 1e-13, 0.0, "iso u");
            assert_near(&s.iso_curve_v(u).unwrap().eval(v).unwrap(), &p, 1e-13, 0.0, "iso v");
        }
    }

    /// Bezier surfaces: de Casteljau equals the B-spline form, for points and partials.
    #[test]
    fn bezier_surface_equals_its_bspline_form(
        nu in 1usize..=5, nv in 1usize..=5, dim in 1usize..=6,
        seed in prop::collection::vec(-10.0f64..10.0, 150),
        u in 0.0f64..=1.0, v in 0.0f64..=1.0,
    ) {
        let data = seed[..nu * nv * dim].to_vec();
        let bez = BezierSurface::new(Points::from_flat(dim, data).unwrap(), (nu, nv)).unwrap();
        let bs = bez.to_bspline();
        assert_near(&bez.eval(u, v).unwrap(), &bs.eval(u, v).unwrap(), 1e-13, 0.0, "point");
        let (a, b) = (bez.eval_derivatives(u, v, 2).unwrap(), bs.eval_derivatives(u, v, 2).unwrap());
        assert_near(a.as_slice(), b.as_slice(), 1e-11 * b.max_abs().max(1.0), 0.0, "partials");
    }

    /// Circular arcs of random centre, radius, frame and angles lie on their circle.
    #[test]
    fn random_arcs_lie_on_the_circle(
        centre in prop::collection::vec(-1e3f64..1e3, 3),
        r in 1e-3f64..1e3,
        x in prop::collection::vec(-1.0f64..1.0, 3),
        y in prop::collection::vec(-1.0f64..1.0, 3),
        start in -10.0f64..10.0,
        sweep in prop::sample::select(vec![-TAU, -3.0, -1.0, 0.3, 1.6, 3.2, 4.8, 0.999 * TAU, TAU]),
        ts in prop::collection::vec(0.0f64..=1.0, 20),
    ) {
        let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(p, q)| p * q).sum::<f64>();
        let lx = dot(&x, &x).sqrt();
        prop_assume!(lx > 1e-3);
        // make y orthogonal to x
        let c = dot(&x, &y) / (lx * lx);
        let y: Vec<f64> = y.iter().zip(&x).map(|(a, b)| a - c * b).collect();
        prop_assume!(dot(&y, &y).sqrt() > 1e-3);
        let arc = NurbsCurve::circular_arc(&centre, &x, &y, r, start, start + sweep).unwrap();
        let offset = dot(&centre, &centre).sqrt();
        let tol = 1e-14 * r + 4.0 * f64::EPSILON * offset;
        for &t in &ts {
            let p = arc.eval(t).unwrap();
            let d: Vec<f64> = p.iter().zip(&centre).map(|(a, b)| a - b).collect();
            prop_assert!((dot(&d, &d).sqrt() - r).abs() <= tol, "t = {t}");
        }
    }

    /// The arc through three points of a circle starts at a, ends at c and stays on the circle.
    #[test]
    fn random_arcs_through_points(
        centre in prop::collection::vec(-1e3f64..1e3, 2),
        r in 1e-2f64..1e3,
        ta in 0.0f64..TAU, db in 0.1f64..3.0, dc in 0.1f64..3.0,
    ) {
        let at = |th: f64| vec![centre[0] + r * th.cos(), centre[1] + r * th.sin()];
        let (a, b, c) = (at(ta), at(ta + db), at(ta + db + dc));
        let (arc, tb) = NurbsCurve::arc_through_points_with_parameter(&a, &b, &c).unwrap();
        let pb = arc.eval(tb).unwrap();
        prop_assert!((pb[0] - b[0]).hypot(pb[1] - b[1]) <= 1e-13 * r + 64.0 * f64::EPSILON * centre[0].hypot(centre[1]), "C(t_b) = b");
        prop_assert_eq!(arc.eval(0.0).unwrap(), a);
        prop_assert_eq!(arc.eval(1.0).unwrap(), c);
        let offset = centre[0].hypot(centre[1]);
        // the computed centre carries ε·scale / sin β; β ≥ 0.1 here
        let tol = 1e-13 * r + 64.0 * f64::EPSILON * offset;
        for k in 0..=20 {
            let p = arc.eval(f64::from(k) / 20.0).unwrap();
            let dist = (p[0] - centre[0]).hypot(p[1] - centre[1]);
            prop_assert!((dist - r).abs() <= tol, "{dist} vs {r}");
        }
    }
}

/// Checks the derivative table of `f(u, v, order)` (square layout) against central differences
/// of the table of one order less: entry `S_{k,l}` is differenced in `u` when it is `C¹` in `u`
/// (`k + 2 ≤ p` with simple knots), in `v` when `l + 2 ≤ q`.
fn check_partials(f: impl Fn(f64, f64, usize) -> Points, u: f64, v: f64, (p, q): (usize, usize)) {
    let h = 1e-6;
    let order = 2;
    let side = order + 1;
    let d = f(u, v, order);
    let (lu, hu) = (f(u - h, v, order - 1), f(u + h, v, order - 1));
    let (lv, hv) = (f(u, v - h, order - 1), f(u, v + h, order - 1));
    let scale = d.max_abs().max(1.0);
    let diff = |hi: &Points, lo: &Points, idx: usize| -> Vec<f64> {
        hi.point(idx)
            .iter()
            .zip(lo.point(idx))
            .map(|(a, b)| (a - b) / (2.0 * h))
            .collect()
    };
    for k in 0..order {
        for l in 0..order {
            let idx = k * order + l;
            if k + 2 <= p {
                assert_near(
                    &diff(&hu, &lu, idx),
                    d.point((k + 1) * side + l),
                    1e-4 * scale,
                    0.0,
                    "d/du",
                );
            }
            if l + 2 <= q {
                assert_near(
                    &diff(&hv, &lv, idx),
                    d.point(k * side + l + 1),
                    1e-4 * scale,
                    0.0,
                    "d/dv",
                );
            }
        }
    }
}

// ---- fixed B-spline surface: oracle, finite differences, batches, iso-curves ----

/// Degrees (3, 2), non-uniform knots with an interior double knot in u, 6 × 5 net in 3-D.
fn general() -> BSplineSurface {
    let (nu, nv) = (6, 5);
    let data: Vec<f64> = (0..90_u32)
        .map(|k| (0.37 * f64::from(k)).sin() + 0.1 * f64::from(k % 7))
        .collect();
    BSplineSurface::new(
        3,
        2,
        vec![0.0, 0.0, 0.0, 0.0, 0.3, 0.3, 1.0, 1.0, 1.0, 1.0],
        vec![-1.0, -1.0, -1.0, 0.5, 1.5, 2.0, 2.0, 2.0],
        Points::from_flat(3, data).unwrap(),
        (nu, nv),
    )
    .unwrap()
}

#[test]
fn eval_matches_cox_de_boor_oracle() {
    let s = general();
    let (nu, nv) = s.net_size();
    for a in 0..=12 {
        for b in 0..=12 {
            let u = f64::from(a) / 12.0;
            let v = -1.0 + 3.0 * f64::from(b) / 12.0;
            let p = s.eval(u, v).unwrap();
            for d in 0..3 {
                let mut oracle = 0.0;
                for i in 0..nu {
                    let bi = basis_function_recursive(s.knots_u(), i, 3, u).unwrap();
                    for j in 0..nv {
                        let bj = basis_function_recursive(s.knots_v(), j, 2, v).unwrap();
                        oracle += bi * bj * s.control_point(i, j).unwrap()[d];
                    }
                }
                assert!((p[d] - oracle).abs() < 1e-14, "({u},{v}) coordinate {d}");
            }
        }
    }
}

#[test]
fn partial_derivatives_match_finite_differences() {
    let s = general();
    let h = 1e-5;
    let order = 2;
    for &(u, v) in &[(0.1, -0.7), (0.5, 0.2), (0.8, 1.7), (0.29, 0.6)] {
        let d = s.eval_derivatives(u, v, order + 1).unwrap();
        let side = order + 2;
        assert_eq!(
            d.point(0),
            s.eval(u, v).unwrap().as_slice(),
            "S_00 is the point"
        );
        for k in 0..=order {
            for l in 0..=order {
                let lo_u = s.eval_derivatives(u - h, v, order).unwrap();
                let hi_u = s.eval_derivatives(u + h, v, order).unwrap();
                let lo_v = s.eval_derivatives(u, v - h, order).unwrap();
                let hi_v = s.eval_derivatives(u, v + h, order).unwrap();
                let idx = k * (order + 1) + l;
                for c in 0..3 {
                    let fd_u = (hi_u.point(idx)[c] - lo_u.point(idx)[c]) / (2.0 * h);
                    let fd_v = (hi_v.point(idx)[c] - lo_v.point(idx)[c]) / (2.0 * h);
                    let ex_u = d.point((k + 1) * side + l)[c];
                    let ex_v = d.point(k * side + l + 1)[c];
                    assert!(
                        (fd_u - ex_u).abs() < 1e-4 * (1.0 + ex_u.abs()),
                        "u k={k} l={l}"
                    );
                    assert!(
                        (fd_v - ex_v).abs() < 1e-4 * (1.0 + ex_v.abs()),
                        "v k={k} l={l}"
                    );
                }
            }
        }
    }
    // orders above the degree vanish
    let d = s.eval_derivatives(0.5, 0.5, 4).unwrap();
    assert_eq!(d.point(4 * 5), &[0.0; 3], "S_uuuu of a cubic");
    assert_eq!(d.point(3), &[0.0; 3], "S_vvv of a quadratic");
}

#[test]
fn grid_batch_and_single_agree() {
    let s = general();
    let us: Vec<f64> = (0..=7).map(|k| f64::from(k) / 7.0).collect();
    let vs: Vec<f64> = (0..=5).map(|k| 2.0 - 3.0 * f64::from(k) / 5.0).collect();
    let mut grid = vec![0.0; us.len() * vs.len() * 3];
    s.eval_grid(&us, &vs, &mut grid).unwrap();
    let pairs: Vec<[f64; 2]> = us
        .iter()
        .flat_map(|&u| vs.iter().map(move |&v| [u, v]))
        .collect();
    let mut list = vec![0.0; pairs.len() * 3];
    s.eval_batch(&pairs, &mut list).unwrap();
    for (k, &[u, v]) in pairs.iter().enumerate() {
        let p = s.eval(u, v).unwrap();
        assert_eq!(&grid[3 * k..3 * k + 3], p.as_slice(), "grid at ({u},{v})");
        assert_eq!(&list[3 * k..3 * k + 3], p.as_slice(), "list at ({u},{v})");
    }
    assert!(matches!(
        s.eval_grid(&us, &vs, &mut grid[1..]),
        Err(Error::LengthMismatch { .. })
    ));
    assert!(matches!(
        s.eval_batch(&pairs, &mut list[3..]),
        Err(Error::LengthMismatch { .. })
    ));
    assert!(matches!(
        s.eval_grid(&[0.5], &[2.5], &mut [0.0; 3]),
        Err(Error::ParameterOutOfDomain { t, .. }) if t == 2.5
    ));
    assert!(matches!(
        s.eval_batch(&[[f64::NAN, 0.0]], &mut [0.0; 3]),
        Err(Error::ParameterOutOfDomain { .. })
    ));
    s.eval_grid(&[], &vs, &mut []).unwrap();
}

#[test]
fn iso_curves_trace_the_surface() {
    let s = general();
    for &v in &[-1.0, 0.3, 2.0] {
        let c = s.iso_curve_u(v).unwrap();
        assert_eq!((c.degree(), c.knots()), (3, s.knots_u()));
        for k in 0..=10 {
            let u = f64::from(k) / 10.0;
            let (a, b) = (c.eval(u).unwrap(), s.eval(u, v).unwrap());
            for d in 0..3 {
                assert!((a[d] - b[d]).abs() < 1e-14, "iso_u at ({u},{v})");
            }
        }
    }
    for &u in &[0.0, 0.3, 0.77, 1.0] {
        let c = s.iso_curve_v(u).unwrap();
        assert_eq!((c.degree(), c.knots()), (2, s.knots_v()));
        for k in 0..=10 {
            let v = -1.0 + 3.0 * f64::from(k) / 10.0;
            let (a, b) = (c.eval(v).unwrap(), s.eval(u, v).unwrap());
            for d in 0..3 {
                assert!((a[d] - b[d]).abs() < 1e-14, "iso_v at ({u},{v})");
            }
        }
    }
    assert!(matches!(
        s.iso_curve_u(2.1),
        Err(Error::ParameterOutOfDomain { .. })
    ));
    assert!(matches!(
        s.iso_curve_v(-0.1),
        Err(Error::ParameterOutOfDomain { .. })
    ));
}

/// Curves and surfaces answer to the same accessor names: a surface's `degree` and `knots` are
/// the pairs of its per-direction forms, and a Bezier curve has a domain like the others.
#[test]
fn surfaces_share_the_curve_accessor_names() {
    let net = Points::from_flat(
        3,
        (0..4 * 3)
            .flat_map(|k| {
                let (i, j) = (f64::from(k / 3), f64::from(k % 3));
                [i, j, (i * j).sin()]
            })
            .collect(),
    )
    .unwrap();
    let s = BSplineSurface::new(
        2,
        1,
        vec![0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0],
        vec![0.0, 0.0, 0.5, 1.0, 1.0],
        net.clone(),
        (4, 3),
    )
    .unwrap();
    assert_eq!(s.degree(), (s.degree_u(), s.degree_v()), "B-spline degree");
    assert_eq!(s.degree(), (2, 1), "B-spline degree");
    assert_eq!(s.knots(), (s.knots_u(), s.knots_v()), "B-spline knots");
    let n = NurbsSurface::from_bspline(&s);
    assert_eq!(n.degree(), s.degree(), "NURBS degree");
    assert_eq!(n.knots(), s.knots(), "NURBS knots");
    assert_eq!(n.domain(), s.domain(), "NURBS domain");
    let b = BezierSurface::new(net, (4, 3)).unwrap();
    assert_eq!(b.degree(), (3, 2), "Bezier degree");
    assert_eq!(b.degree(), (b.degree_u(), b.degree_v()), "Bezier degree");
    let c = lekalo::BezierCurve::new(Points::from_2d(&[[0.0, 0.0], [1.0, 1.0]]).unwrap()).unwrap();
    assert_eq!(c.domain(), (0.0, 1.0), "Bezier curve domain");
}
