//! Tests of the tensor-product splines: the naive sum of products (the oracle), the curve and
//! surface paths bit for bit, derivatives against finite differences and the surface, grid and
//! batch evaluation against the point kernel bit for bit, interpolation in 3 and 4 variables,
//! and a negative test for every error.

use proptest::prelude::*;

use crate::curve::bspline::BSplineCurve;
use crate::error::Error;
use crate::interpolate::{
    CurveInterpolation, EndCondition, KnotPlacement, Parametrization, SurfaceInterpolation,
};
use crate::knots::KnotVector;
use crate::oracle::{bspline_naive, proptest_config};
use crate::points::{Points, PointsRef};
use crate::surface::bspline::BSplineSurface;
use crate::tensor::{TensorBSpline, TensorInterpolation, TensorNurbs};

/// `|a − b| ≤ tol·scale` for every pair.
fn assert_near(a: &[f64], b: &[f64], tol: f64, scale: f64, what: &str) {
    assert_eq!(a.len(), b.len(), "{what}: lengths");
    for (i, (x, y)) in a.iter().zip(b).enumerate() {
        assert!(
            (x - y).abs() <= tol * scale.max(f64::MIN_POSITIVE),
            "{what}[{i}]: {x} against {y} (tolerance {tol} × {scale})"
        );
    }
}

/// Every basis function `N_{i,p}(t)` of a direction by the oracle: the naive curve evaluator
/// on the identity net (point `i` is the unit vector `e_i`).
fn naive_basis(kv: &KnotVector, p: usize, t: f64) -> Vec<f64> {
    let n = kv.len() - p - 1;
    let mut id = vec![0.0; n * n];
    for i in 0..n {
        id[i * n + i] = 1.0;
    }
    let curve = BSplineCurve::from_raw(p, kv.as_slice().to_vec(), Points::from_raw(id, n));
    bspline_naive(&curve, t)
}

/// `S(x) = Σ_i Π_a N_{i_a}(x_a)·P_i` summed over the whole net, no span search.
pub(super) fn naive_eval(s: &TensorBSpline, x: &[f64]) -> Vec<f64> {
    let bases: Vec<Vec<f64>> = (0..s.n_vars())
        .map(|a| naive_basis(&s.knots()[a], s.degrees()[a], x[a]))
        .collect();
    let dim = s.dim();
    let mut out = vec![0.0; dim];
    let mut index = vec![0usize; s.n_vars()];
    for pt in s.control_points().iter() {
        let w: f64 = index
            .iter()
            .enumerate()
            .map(|(a, &i)| bases[a][i])
            .product();
        for (o, v) in out.iter_mut().zip(pt) {
            *o += w * v;
        }
        for a in (0..index.len()).rev() {
            index[a] += 1;
            if index[a] < s.shape()[a] {
                break;
            }
            index[a] = 0;
        }
    }
    out
}

/// A random spline: `N` in 1..=4, degree 0..=3 and up to 3 extra control points per direction,
/// knots clamped or not with multiple interior knots now and then, dim 1..=3.
pub(super) fn spline() -> impl Strategy<Value = TensorBSpline> {
    (1usize..=4, 1usize..=3)
        .prop_flat_map(|(n, dim)| {
            (
                Just(dim),
                prop::collection::vec((0usize..=3, 0usize..=3, any::<bool>()), n),
            )
        })
        .prop_flat_map(|(dim, dirs)| {
            let knots: Vec<_> = dirs
                .iter()
                .map(|&(p, extra, clamped)| {
                    let n_knots = 2 * p + 2 + extra;
                    (
                        Just((p, clamped)),
                        -2.0f64..2.0,
                        prop::collection::vec(
                            prop_oneof![1 => Just(0.0), 3 => 0.25f64..2.0],
                            n_knots - 1,
                        ),
                    )
                })
                .collect();
            let count: usize = dirs.iter().map(|&(p, extra, _)| p + 1 + extra).product();
            (
                knots,
                prop::collection::vec(-10.0f64..10.0, count * dim),
                Just(dim),
            )
        })
        .prop_filter_map("valid knots", |(dirs, net, dim)| {
            let mut degrees = Vec::new();
            let mut knots = Vec::new();
            for ((p, clamped), t0, mut gaps) in dirs {
                if clamped {
                    let len = gaps.len();
                    gaps[..p].fill(0.0);
                    gaps[len - p..].fill(0.0);
                }
                let mut k = vec![t0];
                for g in gaps {
                    k.push(k[k.len() - 1] + g);
                }
                degrees.push(p);
                knots.push(k);
            }
            TensorBSpline::new(degrees, knots, Points::from_flat(dim, net).ok()?).ok()
        })
}

/// Parameters of each direction: both ends, the knots inside the domain, a sweep.
fn axis_params(s: &TensorBSpline, a: usize, count: u32) -> Vec<f64> {
    let (lo, hi) = s.domain()[a];
    let mut ts: Vec<f64> = (0..=count)
        .map(|k| (lo + (hi - lo) * f64::from(k) / f64::from(count)).min(hi))
        .collect();
    ts.extend(
        s.knots()[a]
            .as_slice()
            .iter()
            .filter(|&&k| k >= lo && k <= hi),
    );
    ts
}

/// The grid of `lists` as flat points (first direction slowest).
fn grid_points(lists: &[Vec<f64>]) -> Vec<f64> {
    let mut pts = vec![Vec::new()];
    for l in lists {
        pts = pts
            .into_iter()
            .flat_map(|p: Vec<f64>| {
                l.iter().map(move |&t| {
                    let mut q = p.clone();
                    q.push(t);
                    q
                })
            })
            .collect();
    }
    pts.concat()
}

proptest! {
    #![proptest_config(proptest_config(64))]

    #[test]
    fn eval_agrees_with_the_naive_sum_of_products(s in spline()) {
        let scale = s.control_points().max_abs().max(1.0);
        let lists: Vec<Vec<f64>> = (0..s.n_vars()).map(|a| axis_params(&s, a, 3)).collect();
        let xs = grid_points(&lists);
        for x in xs.chunks_exact(s.n_vars()) {
            let fast = s.eval(x).unwrap();
            assert_near(&fast, &naive_eval(&s, x), 1e-13, scale, "eval against the oracle");
        }
    }

    #[test]
    fn grid_and_batches_equal_the_point_kernel_bitwise(s in spline(), order in 0usize..=2) {
        let lists: Vec<Vec<f64>> = (0..s.n_vars()).map(|a| axis_params(&s, a, 2)).collect();
        let axes: Vec<&[f64]> = lists.iter().map(Vec::as_slice).collect();
        let orders: Vec<usize> = (0..s.n_vars()).map(|a| (order + a) % 3).collect();
        let xs = grid_points(&lists);
        let points = xs.len() / s.n_vars();
        let dim = s.dim();
        for ord in [None, Some(orders.as_slice())] {
            let mut grid = vec![0.0; points * dim];
            s.eval_grid(&axes, ord, &mut grid).unwrap();
            let mut batch = vec![0.0; points * dim];
            s.eval_batch(&xs, ord, &mut batch).unwrap();
            let mut par = vec![0.0; points * dim];
            s.par_eval_batch(&xs, ord, &mut par).unwrap();
            for (k, x) in xs.chunks_exact(s.n_vars()).enumerate() {
                let single = match ord {
                    None => s.eval(x).unwrap(),
                    Some(o) => s.eval_partial(x, o).unwrap(),
                };
                let bits = |v: &[f64]| v.iter().map(|f| f.to_bits()).collect::<Vec<_>>();
                prop_assert_eq!(bits(&grid[k * dim..(k + 1) * dim]), bits(&single), "grid");
                prop_assert_eq!(bits(&batch[k * dim..(k + 1) * dim]), bits(&single), "batch");
                prop_assert_eq!(bits(&par[k * dim..(k + 1) * dim]), bits(&single), "parallel");
            }
        }
    }

    #[test]
    fn knot_insertion_and_slices_keep_the_spline(s in spline(), f in 0.05f64..0.95) {
        let scale = s.control_points().max_abs().max(1.0);
        let lists: Vec<Vec<f64>> = (0..s.n_vars()).map(|a| axis_params(&s, a, 2)).collect();
        let xs = grid_points(&lists);
        let n = s.n_vars();
        for a in 0..n {
            let (lo, hi) = s.domain()[a];
            let t = lo + (hi - lo) * f;
            let times = s.degrees()[a].saturating_sub(s.knots()[a].multiplicity(t)).min(2);
            let r = s.insert_knot(a, t, times).unwrap();
            prop_assert_eq!(r.shape()[a], s.shape()[a] + times);
            let mut fixed = vec![None; n];
            if n > 1 {
                fixed[a] = Some(t);
            }
            let sliced = if n > 1 { Some(s.slice(&fixed).unwrap()) } else { None };
            for x in xs.chunks_exact(n) {
                let want = s.eval(x).unwrap();
                assert_near(&r.eval(x).unwrap(), &want, 1e-12, scale, "knot insertion");
                if let Some(sl) = &sliced {
                    let mut y = x.to_vec();
                    y[a] = t;
                    let rest: Vec<f64> = (0..n).filter(|&b| b != a).map(|b| y[b]).collect();
                    assert_near(&sl.eval(&rest).unwrap(), &s.eval(&y).unwrap(), 1e-12, scale, "slice");
                }
            }
        }
    }

    #[test]
    fn partial_derivatives_agree_with_finite_differences(s in spline()) {
        // central differences of the first partials at interior points away from the knots
        let n = s.n_vars();
        let scale = s.control_points().max_abs().max(1.0);
        let dom = s.domain();
        let x: Vec<f64> = dom.iter().map(|&(lo, hi)| lo + 0.37 * (hi - lo)).collect();
        for a in 0..n {
            let (lo, hi) = dom[a];
            let h = 1e-6 * (hi - lo);
            let near_knot = s.knots()[a].as_slice().iter().any(|&k| (k - x[a]).abs() < 2.0 * h);
            if near_knot || s.degrees()[a] < 2 {
                continue;
            }
            let mut orders = vec![0; n];
            orders[a] = 1;
            let d = s.eval_partial(&x, &orders).unwrap();
            let (mut xp, mut xm) = (x.clone(), x.clone());
            xp[a] += h;
            xm[a] -= h;
            let (fp, fm) = (s.eval(&xp).unwrap(), s.eval(&xm).unwrap());
            let fd: Vec<f64> = fp.iter().zip(&fm).map(|(p, m)| (p - m) / (2.0 * h)).collect();
            assert_near(&d, &fd, 1e-5, scale / (hi - lo), "∂S/∂x_a");
        }
    }

    #[test]
    fn two_variables_are_the_surface_interpolation_bitwise(
        nu in 2usize..9, nv in 2usize..9, dim in 1usize..=3, pu in 1usize..=4, pv in 1usize..=4,
        param in 0usize..3, seed in prop::collection::vec(-1.0f64..1.0, 8 * 8 * 3),
    ) {
        prop_assume!(pu < nu && pv < nv);
        let param = [Parametrization::Uniform, Parametrization::ChordLength, Parametrization::Centripetal][param];
        // a graph over an uneven grid (distinct neighbours), plus noise
        let mut data = Vec::new();
        for k in 0..nu {
            for l in 0..nv {
                let (x, y) = (k as f64 + 0.3 * seed[k] , (l * l) as f64 + 0.2 * seed[l + 8]);
                let q = [x, y, (x * 0.7 + y).sin() + seed[(k * 8 + l) * 3 % seed.len()]];
                data.extend_from_slice(&q[3 - dim..]);
            }
        }
        let grid = PointsRef::from_flat(dim, &data).unwrap();
        let surf = SurfaceInterpolation::new(pu, pv).parametrization(param).interpolate(grid, nu, nv);
        let tens = TensorInterpolation::new(vec![pu, pv]).parametrization(param).interpolate(grid, &[nu, nv]);
        match (surf, tens) {
            (Ok(s), Ok(t)) => {
                let t = t.to_surface().unwrap();
                prop_assert_eq!(t.knots_u(), s.knots_u());
                prop_assert_eq!(t.knots_v(), s.knots_v());
                prop_assert_eq!(t.control_points(), s.control_points());
            }
            (Err(a), Err(b)) => prop_assert_eq!(a, b),
            (a, b) => prop_assert!(false, "surface {a:?} against tensor {b:?}"),
        }
    }

    #[test]
    fn one_variable_is_the_curve_interpolation_bitwise(
        n in 2usize..12, dim in 1usize..=3, p in 1usize..=5, param in 0usize..3,
        ys in prop::collection::vec(-5.0f64..5.0, 12 * 3),
    ) {
        prop_assume!(p < n);
        let param = [Parametrization::Uniform, Parametrization::ChordLength, Parametrization::Centripetal][param];
        let mut data = Vec::new();
        for k in 0..n {
            data.push(k as f64);
            data.extend_from_slice(&ys[k * 3..k * 3 + dim - 1]);
        }
        let q = PointsRef::from_flat(dim, &data).unwrap();
        let c = CurveInterpolation::new(p).parametrization(param).interpolate(q).unwrap();
        let t = TensorInterpolation::new(vec![p]).parametrization(param).interpolate(q, &[n]).unwrap();
        prop_assert_eq!(t.to_curve().unwrap(), c);
    }
}

#[test]
fn curve_options_pass_through_in_one_variable() {
    let q = Points::from_2d(&[[0.0, 0.0], [1.0, 2.0], [2.5, 1.0], [4.0, 3.0], [5.0, 0.0]]).unwrap();
    let xs = [0.0, 0.7, 1.1, 2.9, 4.0];
    for (end, knots) in [
        (EndCondition::Natural, KnotPlacement::Auto),
        (EndCondition::Free, KnotPlacement::Uniform),
        (
            EndCondition::FirstDerivatives {
                start: vec![1.0, 0.0],
                end: vec![0.0, -1.0],
            },
            KnotPlacement::Averaged,
        ),
    ] {
        let curve = CurveInterpolation::new(3)
            .end_condition(end.clone())
            .knot_placement(knots)
            .interpolate_at(q.as_view(), &xs)
            .unwrap();
        let t = TensorInterpolation::new(vec![3])
            .end_conditions(vec![end])
            .knot_placements(vec![knots])
            .interpolate_at(&[&xs], q.as_view())
            .unwrap();
        assert_eq!(t.to_curve().unwrap(), curve, "curve options");
    }
}

#[test]
fn conversions_are_bit_for_bit_and_serde_validates() {
    let c = BSplineCurve::new(
        2,
        vec![0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0],
        Points::from_2d(&[[0.0, 0.0], [1.0, 1.0], [2.0, 0.0], [3.0, 1.0]]).unwrap(),
    )
    .unwrap();
    let t = TensorBSpline::from(&c);
    assert_eq!(t.to_curve().unwrap(), c, "curve round trip");
    assert!(
        matches!(
            t.to_surface(),
            Err(Error::LengthMismatch {
                expected: 2,
                got: 1,
                ..
            })
        ),
        "a curve is no surface"
    );
    let net = Points::from_flat(1, (0..12).map(f64::from).collect()).unwrap();
    let s = BSplineSurface::from_knot_vectors(
        2,
        1,
        KnotVector::clamped_uniform(2, 4).unwrap(),
        KnotVector::clamped_uniform(1, 3).unwrap(),
        net,
        (4, 3),
    )
    .unwrap();
    let t = TensorBSpline::from(&s);
    assert_eq!(t.to_surface().unwrap(), s, "surface round trip");
    for (u, v) in [(0.0, 0.0), (0.3, 0.8), (1.0, 0.45)] {
        let d = s.eval_derivatives(u, v, 2).unwrap();
        for k in 0..=2 {
            for l in 0..=2 {
                assert_near(
                    &t.eval_partial(&[u, v], &[k, l]).unwrap(),
                    d.point(k * 3 + l),
                    1e-13,
                    12.0,
                    "partials against the surface",
                );
            }
        }
    }
    let json = serde_json::to_string(&t).unwrap();
    let back: TensorBSpline = serde_json::from_str(&json).unwrap();
    assert_eq!(back, t, "serde round trip");
    let bad = json.replace(
        "[0.0,0.0,0.0,0.5,1.0,1.0,1.0]",
        "[0.0,0.0,0.0,1.0,0.5,1.0,1.0]",
    );
    assert!(bad != json, "the test edits the knots");
    assert!(
        serde_json::from_str::<TensorBSpline>(&bad).is_err(),
        "deserialisation validates the knots"
    );
}

/// `f(x) = Π_a cos(x_a + a)·(1 + x_a)` plus `offset`: smooth, not a polynomial.
fn field(x: &[f64], offset: f64) -> f64 {
    offset
        + x.iter()
            .enumerate()
            .map(|(a, &t)| (t + a as f64).cos() * (1.0 + t))
            .product::<f64>()
}

/// Interpolates `field` on an uneven grid with `sizes` and checks the nodes.
fn check_nodes(sizes: &[usize], degrees: Vec<usize>, offset: f64) {
    let lists: Vec<Vec<f64>> = sizes
        .iter()
        .map(|&m| {
            (0..m)
                .map(|k| {
                    let t = k as f64 / (m - 1) as f64;
                    t + 0.1 * t * t
                })
                .collect()
        })
        .collect();
    let xs = grid_points(&lists);
    let n = sizes.len();
    let values: Vec<f64> = xs
        .chunks_exact(n)
        .flat_map(|x| [field(x, offset), -field(x, 0.0)])
        .collect();
    let axes: Vec<&[f64]> = lists.iter().map(Vec::as_slice).collect();
    let s = TensorInterpolation::new(degrees)
        .interpolate_at(&axes, PointsRef::from_flat(2, &values).unwrap())
        .unwrap();
    let scale = values.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    let mut at = vec![0.0; values.len()];
    s.eval_grid(&axes, None, &mut at).unwrap();
    assert_near(&at, &values, 1e-12, scale, "interpolant at the grid nodes");
    // and between the nodes it approximates the field
    let mid: Vec<f64> = lists.iter().map(|l| 0.5 * (l[1] + l[2])).collect();
    let v = s.eval(&mid).unwrap();
    assert!(
        (v[0] - field(&mid, offset)).abs() < 1e-3 * scale,
        "approximation between nodes"
    );
}

#[test]
fn interpolation_reproduces_three_and_four_variable_grids() {
    check_nodes(&[7, 5, 6], vec![3, 2, 3], 0.0);
    check_nodes(&[7, 5, 6], vec![3, 2, 3], 1e8);
    check_nodes(&[5, 4, 6, 5], vec![3, 3, 2, 3], 0.0);
    check_nodes(&[5, 4, 6, 5], vec![3, 3, 2, 3], 1e8);
    check_nodes(&[4, 3, 3, 5], vec![1, 2, 1, 4], 1e8);
}

#[test]
fn interpolation_from_points_reproduces_the_grid() {
    // a 3-D grid of 3-D points (a deformed box), chord-length parameters
    let (m0, m1, m2) = (5, 4, 6);
    let mut data = Vec::new();
    for i in 0..m0 {
        for j in 0..m1 {
            for k in 0..m2 {
                let (x, y, z) = (i as f64, j as f64 * 1.5, (k * k) as f64 * 0.3);
                data.extend([x + 0.1 * y, y + 0.05 * z * x, z + 0.2 * (x * y).sin()]);
            }
        }
    }
    let grid = PointsRef::from_flat(3, &data).unwrap();
    let fit = TensorInterpolation::new(vec![3, 3, 3]).parametrization(Parametrization::Centripetal);
    let s = fit.interpolate(grid, &[m0, m1, m2]).unwrap();
    let params = fit.grid_parameters(grid, &[m0, m1, m2]).unwrap();
    let axes: Vec<&[f64]> = params.iter().map(Vec::as_slice).collect();
    let mut at = vec![0.0; data.len()];
    s.eval_grid(&axes, None, &mut at).unwrap();
    let scale = grid.to_owned().max_abs();
    assert_near(&at, &data, 1e-12, scale, "interpolant at the grid nodes");
}

#[test]
fn nurbs_is_the_rational_quotient_and_its_partials_match_differences() {
    let h = std::f64::consts::FRAC_1_SQRT_2;
    let arc = [[1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
    let mut net = Vec::new();
    let mut weights = Vec::new();
    for z in [0.0, 1.0, 3.0] {
        for (c, p) in arc.iter().enumerate() {
            net.extend([p[0], p[1], z]);
            weights.push(if c == 1 { h * (1.0 + z) } else { 1.0 + z * z });
        }
    }
    let k2 = vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0];
    let s = TensorNurbs::new(
        vec![2, 2],
        vec![k2.clone(), k2],
        Points::from_flat(3, net).unwrap(),
        &weights,
    )
    .unwrap();
    let x = [0.35, 0.6];
    for orders in [[1, 0], [0, 1], [1, 1], [2, 0], [2, 1]] {
        let d = s.eval_partial(&x, &orders).unwrap();
        // differences of the next lower order in the first direction that has one
        let a = if orders[0] > 0 { 0 } else { 1 };
        let mut lower = orders;
        lower[a] -= 1;
        let e = 1e-5;
        let (mut xp, mut xm) = (x, x);
        xp[a] += e;
        xm[a] -= e;
        let (fp, fm) = (
            s.eval_partial(&xp, &lower).unwrap(),
            s.eval_partial(&xm, &lower).unwrap(),
        );
        let fd: Vec<f64> = fp
            .iter()
            .zip(&fm)
            .map(|(p, m)| (p - m) / (2.0 * e))
            .collect();
        assert_near(&d, &fd, 1e-6, 10.0, "rational partials");
    }
    let mut grid = vec![0.0; 2 * 3 * 3];
    s.eval_grid(&[&[0.1, 0.9], &[0.0, 0.5, 1.0]], &mut grid)
        .unwrap();
    assert_eq!(
        &grid[3 * 4..3 * 5],
        s.eval(&[0.9, 0.5]).unwrap().as_slice(),
        "grid point"
    );
    let pts = [0.1, 0.0, 0.9, 0.5, 0.35, 1.0];
    let (mut seq, mut par) = (vec![0.0; 9], vec![0.0; 9]);
    s.eval_batch(&pts, &mut seq).unwrap();
    s.par_eval_batch(&pts, &mut par).unwrap();
    assert_eq!(seq, par, "parallel batch");
    assert_eq!(&seq[3..6], &grid[3 * 4..3 * 5], "batch and grid");
    let json = serde_json::to_string(&s).unwrap();
    let back: TensorNurbs = serde_json::from_str(&json).unwrap();
    assert_near(
        back.homogeneous().control_points().as_slice(),
        s.homogeneous().control_points().as_slice(),
        1e-15,
        10.0,
        "serde round trip",
    );
}

#[test]
fn every_error_is_named() {
    let v = vec![0.0; 12];
    let values = PointsRef::from_flat(1, &v).unwrap();
    let fit = TensorInterpolation::new(vec![1, 1]);
    let e = fit.interpolate(values, &[3, 5]).unwrap_err();
    assert!(
        matches!(
            e,
            Error::LengthMismatch {
                expected: 15,
                got: 12,
                ..
            }
        ),
        "{e:?}"
    );
    let e = TensorInterpolation::new(vec![4, 1])
        .interpolate(values, &[4, 3])
        .unwrap_err();
    assert!(matches!(e, Error::Degree { degree: 4, .. }), "{e:?}");
    let e = fit.interpolate(values, &[1 << 40, 1 << 40]).unwrap_err();
    assert!(
        matches!(
            e,
            Error::TooLarge {
                size: usize::MAX,
                ..
            }
        ),
        "{e:?}"
    );
    let e = fit
        .interpolate_at(&[&[0.0, 1.0, 2.0, 3.0], &[0.0, f64::NAN, 2.0]], values)
        .unwrap_err();
    assert!(matches!(e, Error::NonFinite { index: 1, .. }), "{e:?}");
    let e = fit
        .interpolate_at(&[&[0.0, 2.0, 1.0, 3.0], &[0.0, 1.0, 2.0]], values)
        .unwrap_err();
    assert!(matches!(e, Error::NotIncreasing { index: 2, .. }), "{e:?}");
    let e = fit
        .interpolate_at(&[&[0.0, 1.0, 1.0, 3.0], &[0.0, 1.0, 2.0]], values)
        .unwrap_err();
    assert!(
        matches!(e, Error::Repeated { what, index: 2, .. } if what.words() == "parameters"),
        "{e:?}"
    );
    let e = TensorInterpolation::new(vec![])
        .interpolate(values, &[])
        .unwrap_err();
    assert!(matches!(e, Error::TooFew { .. }), "{e:?}");
    let e = fit
        .clone()
        .end_conditions(vec![
            EndCondition::FirstDerivatives {
                start: vec![0.0],
                end: vec![0.0],
            },
            EndCondition::Free,
        ])
        .interpolate(values, &[4, 3])
        .unwrap_err();
    assert!(
        matches!(e, Error::InvalidArgument { what, .. } if what.words() == "end conditions"),
        "{e:?}"
    );
    let e = fit
        .clone()
        .end_conditions(vec![EndCondition::Free])
        .grid_parameters(values, &[4, 3])
        .unwrap_err();
    assert!(
        matches!(
            e,
            Error::LengthMismatch {
                expected: 2,
                got: 1,
                ..
            }
        ),
        "{e:?}"
    );
    // the spline's own checks
    let k = vec![0.0, 0.0, 1.0, 1.0];
    let e = TensorBSpline::new(
        vec![1, 1],
        vec![k.clone()],
        Points::from_flat(1, vec![0.0; 4]).unwrap(),
    )
    .unwrap_err();
    assert!(
        matches!(
            e,
            Error::LengthMismatch {
                expected: 2,
                got: 1,
                ..
            }
        ),
        "{e:?}"
    );
    let s = TensorBSpline::new(
        vec![1, 1],
        vec![k.clone(), k],
        Points::from_flat(1, vec![0.0; 4]).unwrap(),
    )
    .unwrap();
    let e = s.eval(&[0.5, 1.5]).unwrap_err();
    assert!(matches!(e, Error::ParameterOutOfDomain { .. }), "{e:?}");
    let e = s.eval(&[0.5]).unwrap_err();
    assert!(
        matches!(
            e,
            Error::LengthMismatch {
                expected: 2,
                got: 1,
                ..
            }
        ),
        "{e:?}"
    );
    let big: Vec<f64> = vec![0.5; 3];
    let huge: Vec<&[f64]> = vec![&big, &big];
    let e = s.eval_grid(&huge, None, &mut [0.0; 8]).unwrap_err();
    assert!(
        matches!(
            e,
            Error::LengthMismatch {
                expected: 9,
                got: 8,
                ..
            }
        ),
        "{e:?}"
    );
    let e = s.slice(&[Some(0.5), Some(0.5)]).unwrap_err();
    assert!(matches!(e, Error::InvalidArgument { .. }), "{e:?}");
    let e = s.insert_knot(2, 0.5, 1).unwrap_err();
    assert!(matches!(e, Error::InvalidArgument { .. }), "{e:?}");
    let e = s.eval_partial(&[0.5, 0.5], &[1, usize::MAX]).unwrap_err();
    assert!(matches!(e, Error::TooLarge { .. }), "{e:?}");
}

#[test]
fn grid_least_squares_is_the_interpolation_with_as_many_control_points() {
    let lists: Vec<Vec<f64>> = [6usize, 5, 7]
        .iter()
        .map(|&m| {
            (0..m)
                .map(|k| (k as f64 / (m - 1) as f64).powf(1.3))
                .collect()
        })
        .collect();
    let xs = grid_points(&lists);
    let values: Vec<f64> = xs.chunks_exact(3).map(|x| field(x, 1e3)).collect();
    let axes: Vec<&[f64]> = lists.iter().map(Vec::as_slice).collect();
    let q = PointsRef::from_flat(1, &values).unwrap();
    let interp = TensorInterpolation::new(vec![3, 2, 3])
        .interpolate_at(&axes, q)
        .unwrap();
    let lsq =
        crate::tensor::tensor_grid_least_squares(&axes, q, &[3, 2, 3], interp.knots().to_vec())
            .unwrap();
    assert_near(
        lsq.control_points().as_slice(),
        interp.control_points().as_slice(),
        1e-12,
        1e3,
        "least squares with n = m interpolates",
    );
}

#[test]
fn grid_least_squares_agrees_with_the_surface_fit() {
    let (nu, nv) = (14, 11);
    let mut data = Vec::new();
    for i in 0..nu {
        for j in 0..nv {
            let (x, y) = (i as f64, j as f64);
            data.extend([x, y, (x * 0.3).sin() * (y * 0.2).cos()]);
        }
    }
    let grid = PointsRef::from_flat(3, &data).unwrap();
    let surf = crate::fit::surface_grid_least_squares(
        grid,
        (nu, nv),
        (3, 2),
        (7, 5),
        Parametrization::Uniform,
    )
    .unwrap();
    let uu: Vec<f64> = (0..nu).map(|k| k as f64 / (nu - 1) as f64).collect();
    let vv: Vec<f64> = (0..nv).map(|k| k as f64 / (nv - 1) as f64).collect();
    let t = crate::tensor::tensor_grid_least_squares(
        &[&uu, &vv],
        grid,
        &[3, 2],
        vec![surf.knots_u().clone(), surf.knots_v().clone()],
    )
    .unwrap();
    assert_near(
        t.control_points().as_slice(),
        surf.control_points().as_slice(),
        1e-12,
        14.0,
        "tensor and surface least squares",
    );
    // more control points than coordinates in a direction
    let e = crate::tensor::tensor_grid_least_squares(
        &[&uu, &vv],
        grid,
        &[3, 2],
        vec![
            KnotVector::clamped_uniform(3, 15).unwrap(),
            surf.knots_v().clone(),
        ],
    )
    .unwrap_err();
    assert!(matches!(e, Error::SchoenbergWhitney { .. }), "{e:?}");
}

#[test]
fn nurbs_converts_with_the_surface_and_agrees_with_its_derivatives() {
    use crate::surface::nurbs::NurbsSurface;
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
    let weights: Vec<f64> = (0..12).map(|k| 1.0 + 0.25 * f64::from(k % 5)).collect();
    let ku = KnotVector::clamped_uniform(2, 4).unwrap().into_vec();
    let kv = KnotVector::clamped_uniform(1, 3).unwrap().into_vec();
    let surf = NurbsSurface::new(2, 1, ku, kv, net, weights, (4, 3)).unwrap();
    let t = TensorNurbs::from_nurbs_surface(&surf);
    assert_eq!(t.to_nurbs_surface().unwrap(), surf, "surface round trip");
    assert!(t.to_nurbs_curve().is_err(), "a surface is no curve");
    for (u, v) in [(0.0, 0.0), (0.3, 0.8), (1.0, 0.45)] {
        let d = surf.eval_derivatives(u, v, 2).unwrap();
        for k in 0..=2 {
            for l in 0..=2 {
                assert_near(
                    &t.eval_partial(&[u, v], &[k, l]).unwrap(),
                    d.point(k * 3 + l),
                    1e-12,
                    100.0,
                    "rational partials against the surface",
                );
            }
        }
    }
}

#[test]
fn natural_and_periodic_directions_on_grids() {
    use std::f64::consts::TAU;
    // f(x, θ, z): periodic in θ (direction 1), natural cubic in x (direction 0)
    let xs: Vec<f64> = (0..7)
        .map(|k| f64::from(k) * 0.4 + 0.05 * f64::from(k * k))
        .collect();
    let m = 9;
    let thetas: Vec<f64> = (0..=m).map(|k| TAU * k as f64 / m as f64).collect();
    let zs = [0.0, 0.5, 1.5, 2.0];
    let f = |x: f64, t: f64, z: f64| (1.0 + 0.3 * x) * t.cos() + 0.5 * (2.0 * t).sin() * z + x * z;
    let mut values = Vec::new();
    for &x in &xs {
        for &t in &thetas[..m] {
            for &z in &zs {
                values.push(f(x, t, z));
            }
        }
    }
    let q = PointsRef::from_flat(1, &values).unwrap();
    let s = TensorInterpolation::new(vec![3, 3, 2])
        .end_conditions(vec![
            EndCondition::Natural,
            EndCondition::Periodic,
            EndCondition::Free,
        ])
        .interpolate_at(&[&xs, &thetas, &zs], q)
        .unwrap();
    assert_eq!(
        s.shape(),
        &[7 + 2, m + 3, 4],
        "natural adds 2, periodic adds p"
    );
    let scale = values.iter().fold(0.0_f64, |a, v| a.max(v.abs()));
    let mut at = vec![0.0; values.len()];
    s.eval_grid(&[&xs, &thetas[..m], &zs], None, &mut at)
        .unwrap();
    assert_near(&at, &values, 1e-12, scale, "nodes");
    for &x in &[xs[0], xs[3], xs[6]] {
        for &z in &zs {
            // periodic: the value and the first two θ-derivatives close up
            for k in 0..=2 {
                let a = s.eval_partial(&[x, thetas[0], z], &[0, k, 0]).unwrap();
                let b = s.eval_partial(&[x, thetas[m], z], &[0, k, 0]).unwrap();
                assert_near(&a, &b, 1e-11, scale, "periodic closure");
            }
        }
    }
    for &t in &[0.3, 2.0, 5.0] {
        for &z in &zs {
            // natural: the second x-derivative vanishes at both x ends
            for &x in &[xs[0], xs[6]] {
                let d2 = s.eval_partial(&[x, t, z], &[2, 0, 0]).unwrap();
                assert!(d2[0].abs() < 1e-10 * scale, "natural end: {d2:?}");
            }
        }
    }
    // computed parameters close the periodic lines too
    let p = TensorInterpolation::new(vec![3, 3, 2])
        .parametrization(Parametrization::Uniform)
        .end_conditions(vec![
            EndCondition::Natural,
            EndCondition::Periodic,
            EndCondition::Free,
        ])
        .grid_parameters(q, &[7, m, 4])
        .unwrap();
    assert_eq!(p[1].len(), m + 1, "one parameter more for the return");
    assert_eq!(p[0].len(), 7, "natural direction");
}

proptest! {
    #![proptest_config(proptest_config(48))]

    #[test]
    fn interpolants_hit_random_grids(
        dirs in prop::collection::vec((2usize..=6, 1usize..=4, 0.2f64..2.0), 2..=4),
        dim in 1usize..=2,
        offset in prop_oneof![Just(0.0), Just(1e8), -1e3f64..1e3],
        seed in prop::collection::vec(-1.0f64..1.0, 64),
    ) {
        // coordinates with uneven steps, degrees below the counts, values from the seed
        let lists: Vec<Vec<f64>> = dirs
            .iter()
            .map(|&(m, _, s)| (0..m).map(|k| (k as f64).powf(s)).collect())
            .collect();
        let degrees: Vec<usize> = dirs.iter().map(|&(m, p, _)| p.min(m - 1)).collect();
        let count: usize = dirs.iter().map(|d| d.0).product();
        let values: Vec<f64> = (0..count * dim)
            .map(|i| offset + seed[i % seed.len()] * (1.0 + (i / seed.len()) as f64))
            .collect();
        let axes: Vec<&[f64]> = lists.iter().map(Vec::as_slice).collect();
        let q = PointsRef::from_flat(dim, &values).unwrap();
        let s = TensorInterpolation::new(degrees).interpolate_at(&axes, q).unwrap();
        let mut at = vec![0.0; values.len()];
        s.eval_grid(&axes, None, &mut at).unwrap();
        let scale = values.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        for (a, v) in at.iter().zip(&values) {
            prop_assert!((a - v).abs() <= 1e-12 * scale, "{a} against {v}");
        }
    }
}

#[test]
fn a_condition_limit_leaves_the_spline_unchanged_or_refuses_it() {
    let lists: Vec<Vec<f64>> = [6usize, 5, 4]
        .iter()
        .map(|&m| (0..m).map(|k| (k as f64).powf(1.2)).collect())
        .collect();
    let xs = grid_points(&lists);
    let values: Vec<f64> = xs.chunks_exact(3).map(|x| field(x, 3.0)).collect();
    let axes: Vec<&[f64]> = lists.iter().map(Vec::as_slice).collect();
    let q = PointsRef::from_flat(1, &values).unwrap();
    let fit = TensorInterpolation::new(vec![3, 2, 3]);
    let free = fit.interpolate_at(&axes, q).unwrap();
    let limited = fit
        .clone()
        .max_condition(1e6)
        .interpolate_at(&axes, q)
        .unwrap();
    assert_eq!(free, limited, "a limit that is not reached changes nothing");
    let e = fit
        .clone()
        .max_condition(1.0)
        .interpolate_at(&axes, q)
        .unwrap_err();
    assert!(matches!(e, Error::IllConditioned { .. }), "{e:?}");
    let e = fit
        .clone()
        .max_condition(f64::NAN)
        .interpolate_at(&axes, q)
        .unwrap_err();
    assert!(matches!(e, Error::InvalidArgument { .. }), "{e:?}");
    let e = fit
        .max_condition(1e6)
        .end_conditions(vec![
            EndCondition::Natural,
            EndCondition::Free,
            EndCondition::Free,
        ])
        .interpolate_at(&axes, q)
        .unwrap_err();
    assert!(matches!(e, Error::InvalidArgument { .. }), "{e:?}");
}

#[test]
fn both_grid_paths_give_the_point_values_bitwise() {
    // a fine grid on a small net takes the shared contraction, a coarse grid on a large net
    // goes point by point; each value must be the point kernel's
    let net = |shape: &[usize], dim: usize| -> Points {
        let count: usize = shape.iter().product::<usize>() * dim;
        Points::from_flat(dim, (0..count).map(|k| (k as f64 * 0.37).sin()).collect()).unwrap()
    };
    let make = |shape: [usize; 3], p: usize| {
        let knots = shape
            .iter()
            .map(|&n| KnotVector::clamped_uniform(p, n).unwrap())
            .collect();
        TensorBSpline::from_knot_vectors(vec![p; 3], knots, net(&shape, 2)).unwrap()
    };
    for (s, m) in [(make([5, 4, 6], 3), 12usize), (make([40, 30, 35], 2), 2)] {
        let lists: Vec<Vec<f64>> = (0..3)
            .map(|a| {
                (0..m + a)
                    .map(|k| (k as f64 / (m + a - 1) as f64).powi(2))
                    .collect()
            })
            .collect();
        let axes: Vec<&[f64]> = lists.iter().map(Vec::as_slice).collect();
        let xs = grid_points(&lists);
        let mut grid = vec![0.0; xs.len() / 3 * 2];
        s.eval_grid(&axes, Some(&[0, 1, 2]), &mut grid).unwrap();
        for (x, g) in xs.chunks_exact(3).zip(grid.chunks_exact(2)) {
            let v = s.eval_partial(x, &[0, 1, 2]).unwrap();
            assert_eq!(
                g.iter().map(|f| f.to_bits()).collect::<Vec<_>>(),
                v.iter().map(|f| f.to_bits()).collect::<Vec<_>>(),
                "grid value at {x:?}"
            );
        }
    }
}

/// Not-a-knot knots of degree `p` (odd) at the sites `x` (de Boor XIII (12)).
fn not_a_knot(x: &[f64], p: usize) -> KnotVector {
    let half = p.div_ceil(2);
    let mut t = vec![x[0]; p + 1];
    t.extend_from_slice(&x[half..x.len() - half]);
    t.extend(std::iter::repeat_n(x[x.len() - 1], p + 1));
    KnotVector::new(t).unwrap()
}

#[test]
fn given_knot_vectors_are_used_as_given() {
    let lists = [
        vec![0.0, 0.4, 1.0, 1.7, 2.0, 3.1, 4.0],
        vec![-1.0, 0.0, 0.5, 2.0, 2.5],
        vec![1e8, 1e8 + 1.0, 1e8 + 3.0, 1e8 + 3.5, 1e8 + 5.0, 1e8 + 6.0],
    ];
    let xs = grid_points(&lists);
    let axes: Vec<&[f64]> = lists.iter().map(Vec::as_slice).collect();
    // a polynomial of degree (3, 1, 3) in its variables: not-a-knot cubics reproduce it
    let poly = |x: &[f64]| {
        let z = x[2] - 1e8;
        x[0].powi(3) - 2.0 * x[0] * x[1] + 0.5 * x[1] * z * z + z.powi(3) / 10.0
    };
    let values: Vec<f64> = xs.chunks_exact(3).map(poly).collect();
    let q = PointsRef::from_flat(1, &values).unwrap();
    let degrees = vec![3, 1, 3];
    let given = vec![
        Some(not_a_knot(&lists[0], 3)),
        None,
        Some(not_a_knot(&lists[2], 3)),
    ];
    let s = TensorInterpolation::new(degrees.clone())
        .knot_vectors(given.clone())
        .interpolate_at(&axes, q)
        .unwrap();
    assert_eq!(s.knots()[0], given[0].clone().unwrap());
    assert_eq!(s.knots()[2], given[2].clone().unwrap());
    for x in [
        [0.3, 0.7, 1e8 + 0.2],
        [3.9, -0.5, 1e8 + 5.5],
        [2.2, 2.4, 1e8 + 3.2],
    ] {
        let v = s.eval(&x).unwrap()[0];
        assert!(
            (v - poly(&x)).abs() < 1e-11 * 70.0,
            "{x:?}: {v} vs {}",
            poly(&x)
        );
    }
    // the placed knots, given, give the same spline bit for bit
    let placed = TensorInterpolation::new(degrees.clone())
        .interpolate_at(&axes, q)
        .unwrap();
    let same = TensorInterpolation::new(degrees.clone())
        .knot_vectors(placed.knots().iter().cloned().map(Some).collect())
        .interpolate_at(&axes, q)
        .unwrap();
    assert_eq!(same, placed);
    // one variable: the given knots, as the curve interpolation's own
    let curve = CurveInterpolation::new(3)
        .interpolate_at(PointsRef::from_flat(1, &values[..7]).unwrap(), &lists[0])
        .unwrap();
    let one = TensorInterpolation::new(vec![3])
        .knot_vectors(vec![Some(curve.knots().clone())])
        .interpolate_at(&[&lists[0]], PointsRef::from_flat(1, &values[..7]).unwrap())
        .unwrap();
    assert_near(
        one.control_points().as_slice(),
        curve.control_points().as_slice(),
        1e-14,
        1.0,
        "one variable",
    );
    // errors: count, domain, Schoenberg–Whitney, end condition
    let wrong = |kv: KnotVector| {
        TensorInterpolation::new(degrees.clone())
            .knot_vectors(vec![Some(kv), None, None])
            .interpolate_at(&axes, q)
            .unwrap_err()
            .to_string()
    };
    let e = wrong(KnotVector::averaged(&lists[0][..6], 3).unwrap());
    assert!(
        e.contains("1st direction: 10 knots for 7 values") && e.contains("give 11"),
        "{e}"
    );
    let mut narrow = vec![0.5; 4];
    narrow.extend([1.0, 1.7, 2.0]);
    narrow.extend([4.0; 4]);
    let e = wrong(KnotVector::new(narrow).unwrap());
    assert!(e.contains("leave the knots' domain"), "{e}");
    let mut crowded = vec![0.0; 4];
    crowded.extend([0.1, 0.2, 0.3]);
    crowded.extend([4.0; 4]);
    let e = wrong(KnotVector::new(crowded).unwrap());
    assert!(e.contains("Schoenberg"), "{e}");
    let e = TensorInterpolation::new(degrees.clone())
        .knot_vectors(given.clone())
        .end_conditions(vec![
            EndCondition::Natural,
            EndCondition::Free,
            EndCondition::Free,
        ])
        .interpolate_at(&axes, q)
        .unwrap_err()
        .to_string();
    assert!(e.contains("given knots go with free ends"), "{e}");
    let e = TensorInterpolation::new(degrees)
        .knot_vectors(vec![None])
        .interpolate_at(&axes, q)
        .unwrap_err()
        .to_string();
    assert!(e.contains("knot vectors (one per grid direction)"), "{e}");
}

/// The fixed-size kernel of three scalar directions gives the bits of the general
/// contraction: the same net as the first column of a 2-D net takes the general path.
#[test]
fn the_trivariate_scalar_kernel_has_the_general_bits() {
    let mut rng = 0x2545_f491_u64;
    let mut next = || {
        rng ^= rng << 13;
        rng ^= rng >> 7;
        rng ^= rng << 17;
        (rng >> 11) as f64 / (1u64 << 53) as f64
    };
    for p in 1..=5 {
        let sizes = [p + 2, p + 3, p + 1];
        let knots: Vec<Vec<f64>> = sizes
            .iter()
            .map(|&m| {
                let mut t = vec![0.0; p + 1];
                let mut inner: Vec<f64> = (0..m - p - 1).map(|_| next()).collect();
                inner.sort_by(f64::total_cmp);
                t.extend(inner);
                t.extend(vec![1.0; p + 1]);
                t
            })
            .collect();
        let count: usize = sizes.iter().product();
        let scalar: Vec<f64> = (0..count).map(|_| 1e3 * next() - 500.0).collect();
        let pair: Vec<f64> = scalar.iter().flat_map(|&v| [v, -v]).collect();
        let one = TensorBSpline::new(
            vec![p; 3],
            knots.clone(),
            Points::from_flat(1, scalar).unwrap(),
        )
        .unwrap();
        let two =
            TensorBSpline::new(vec![p; 3], knots, Points::from_flat(2, pair).unwrap()).unwrap();
        let xs: Vec<f64> = (0..300).map(|_| next()).collect();
        let mut a = vec![0.0; 100];
        let mut b = vec![0.0; 200];
        one.eval_batch(&xs, None, &mut a).unwrap();
        two.eval_batch(&xs, None, &mut b).unwrap();
        for (k, (x, y)) in a.iter().zip(b.chunks_exact(2)).enumerate() {
            assert_eq!(x.to_bits(), y[0].to_bits(), "degree {p}, point {k}");
        }
        // beyond the domain too (the batch of values continues the end polynomials)
        let wide: Vec<f64> = xs.iter().map(|x| 2.0 * x - 0.5).collect();
        one.par_eval_batch_extrapolated(&wide, None, &mut a)
            .unwrap();
        two.par_eval_batch_extrapolated(&wide, None, &mut b)
            .unwrap();
        for (k, (x, y)) in a.iter().zip(b.chunks_exact(2)).enumerate() {
            assert_eq!(
                x.to_bits(),
                y[0].to_bits(),
                "degree {p}, extrapolated point {k}"
            );
        }
    }
}

/// Outside the domain the extrapolated batch continues the end polynomials: a spline that is
/// one cubic polynomial continues as that polynomial, derivatives included; inside it has the
/// bits of the plain batch; a NaN coordinate is refused.
#[test]
fn extrapolation_continues_the_end_polynomials() {
    let lists = [
        vec![0.0, 0.3, 0.7, 1.0, 1.4, 2.0],
        vec![-1.0, 0.0, 0.5, 1.0, 2.0],
        vec![0.0, 1.0, 1.5, 2.5, 3.0],
    ];
    let f = |x: &[f64]| x[0].powi(3) - 2.0 * x[0] * x[1] + x[1] * x[1] * x[2] + x[2].powi(3);
    let fx = |x: &[f64]| 3.0 * x[0] * x[0] - 2.0 * x[1];
    let xs = grid_points(&lists);
    let values: Vec<f64> = xs.chunks_exact(3).map(f).collect();
    let axes: Vec<&[f64]> = lists.iter().map(Vec::as_slice).collect();
    let s = TensorInterpolation::new(vec![3, 3, 3])
        .interpolate_at(&axes, PointsRef::from_flat(1, &values).unwrap())
        .unwrap();
    let outside = [
        -0.5, 0.2, 1.0, 2.5, 3.0, -0.2, 1.0, -2.0, 4.0, 0.1, 0.1, 0.1,
    ];
    let mut out = [0.0; 4];
    s.par_eval_batch_extrapolated(&outside, None, &mut out)
        .unwrap();
    let mut d = [0.0; 4];
    s.par_eval_batch_extrapolated(&outside, Some(&[1, 0, 0]), &mut d)
        .unwrap();
    for (k, x) in outside.chunks_exact(3).enumerate() {
        assert!(
            (out[k] - f(x)).abs() < 1e-11 * 100.0,
            "{x:?}: {} vs {}",
            out[k],
            f(x)
        );
        assert!(
            (d[k] - fx(x)).abs() < 1e-10 * 100.0,
            "{x:?}: {} vs {}",
            d[k],
            fx(x)
        );
    }
    let inside = [0.1, 0.2, 0.3, 1.9, 1.9, 2.9];
    let (mut a, mut b) = ([0.0; 2], [0.0; 2]);
    s.par_eval_batch(&inside, None, &mut a).unwrap();
    s.par_eval_batch_extrapolated(&inside, None, &mut b)
        .unwrap();
    assert_eq!(a.map(f64::to_bits), b.map(f64::to_bits));
    assert!(s.par_eval_batch(&outside[..3], None, &mut a[..1]).is_err());
    let e = s
        .par_eval_batch_extrapolated(&[0.1, f64::NAN, 0.2], None, &mut a[..1])
        .unwrap_err();
    assert!(matches!(e, Error::NonFinite { index: 1, .. }), "{e}");
}

/// The derivative spline has the values of the partial derivative, degrees lowered by the
/// orders; an order above a degree is refused.
#[test]
fn derivative_splines_agree_with_partial_derivatives() {
    let lists = [
        vec![0.0, 0.3, 0.7, 1.0, 1.4, 2.0, 2.2],
        vec![-1.0, 0.0, 0.5, 1.0, 2.0, 2.5],
        vec![0.0, 1.0, 1.5, 2.5, 3.0],
    ];
    let xs = grid_points(&lists);
    let values: Vec<f64> = xs
        .chunks_exact(3)
        .flat_map(|x| [field(x, 3.0), x[0] * x[1] - x[2]])
        .collect();
    let axes: Vec<&[f64]> = lists.iter().map(Vec::as_slice).collect();
    let s = TensorInterpolation::new(vec![3, 2, 3])
        .interpolate_at(&axes, PointsRef::from_flat(2, &values).unwrap())
        .unwrap();
    for orders in [[1, 0, 0], [0, 2, 1], [3, 1, 2], [0, 0, 0]] {
        let d = s.derivative(&orders).unwrap();
        let want: Vec<usize> = s.degrees().iter().zip(orders).map(|(p, k)| p - k).collect();
        assert_eq!(d.degrees(), &want[..]);
        for x in [[0.1, -0.5, 0.2], [1.2, 0.7, 2.9], [2.1, 2.4, 1.1]] {
            let a = d.eval(&x).unwrap();
            let b = s.eval_partial(&x, &orders).unwrap();
            let scale = b.iter().fold(1.0_f64, |m, v| m.max(v.abs()));
            assert_near(&a, &b, 1e-12, scale, "derivative spline");
        }
    }
    // above the degree: zero, of degree 0 on the distinct knots
    let z = s.derivative(&[0, 3, 1]).unwrap();
    assert_eq!(z.degrees(), &[3, 0, 2]);
    assert_eq!(z.domain(), s.domain());
    assert!(z.control_points().as_slice().iter().all(|&v| v == 0.0));
    assert_eq!(z.eval(&[1.2, 0.7, 2.9]).unwrap(), vec![0.0, 0.0]);
    assert!(s.derivative(&[1, 0]).is_err());
}

/// A large batch on a large net is evaluated in the order of a grid of cells: every value has
/// the bits of the sequential batch, inside and beyond the domain, for the fixed trivariate
/// kernel and the general one; a point outside the domain is still the error of the first such
/// point.
#[test]
fn a_large_batch_in_cell_order_has_the_bits_of_the_sequential_one() {
    let mut rng = 0x9e37_79b9_u64;
    let mut next = || {
        rng ^= rng << 13;
        rng ^= rng >> 7;
        rng ^= rng << 17;
        (rng >> 11) as f64 / (1u64 << 53) as f64
    };
    for (degrees, sizes, dim) in [
        (vec![3, 3, 3], vec![33, 33, 33], 1),
        (vec![2, 3, 1, 2], vec![14, 12, 10, 9], 2),
    ] {
        let knots: Vec<Vec<f64>> = sizes
            .iter()
            .zip(&degrees)
            .map(|(&m, &p)| {
                let mut t = vec![0.0; p + 1];
                t.extend((1..m - p).map(|i| i as f64 / (m - p) as f64));
                t.extend(vec![1.0; p + 1]);
                t
            })
            .collect();
        let count: usize = sizes.iter().product::<usize>() * dim;
        let net: Vec<f64> = (0..count).map(|_| 2.0 * next() - 1.0).collect();
        let s = TensorBSpline::new(degrees, knots, Points::from_flat(dim, net).unwrap()).unwrap();
        let n = s.n_vars();
        let points = 20_000;
        let xs: Vec<f64> = (0..points * n).map(|_| next()).collect();
        let bits = |v: &[f64]| v.iter().map(|f| f.to_bits()).collect::<Vec<_>>();
        let mut seq = vec![0.0; points * dim];
        let mut par = vec![0.0; points * dim];
        s.eval_batch(&xs, None, &mut seq).unwrap();
        s.par_eval_batch(&xs, None, &mut par).unwrap();
        assert_eq!(bits(&seq), bits(&par), "{n} variables");
        // beyond the domain: the sorted batch against small (unsorted) batches
        let wide: Vec<f64> = xs.iter().map(|x| 1.6 * x - 0.3).collect();
        s.par_eval_batch_extrapolated(&wide, None, &mut par)
            .unwrap();
        for (x, v) in wide.chunks(1000 * n).zip(par.chunks(1000 * dim)) {
            let mut small = vec![0.0; v.len()];
            s.par_eval_batch_extrapolated(x, None, &mut small).unwrap();
            assert_eq!(bits(&small), bits(v), "{n} variables, extrapolated");
        }
        // one point outside: the sequential error, not the sorted path
        let mut bad = xs.clone();
        bad[(points / 2) * n] = 1.5;
        bad[(points - 1) * n] = -0.5;
        let e = s.par_eval_batch(&bad, None, &mut par).unwrap_err();
        assert_eq!(e, s.eval_batch(&bad, None, &mut seq).unwrap_err());
    }
}

#[test]
fn a_rational_spline_continued_stays_on_its_conic_and_tensor_operations_keep_the_kind() {
    // a quarter circle in the first direction, lifted linearly in z by the second: the
    // numerator and the weight continued beyond the domain stay on the unit circle
    let h = std::f64::consts::FRAC_1_SQRT_2;
    let mut net = Vec::new();
    for p in [[1.0, 0.0], [1.0, 1.0], [0.0, 1.0]] {
        for z in [0.0, 2.0] {
            net.extend([p[0], p[1], z]);
        }
    }
    let s = TensorNurbs::new(
        vec![2, 1],
        vec![vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0], vec![0.0, 0.0, 1.0, 1.0]],
        Points::from_flat(3, net).unwrap(),
        &[1.0, 1.0, h, h, 1.0, 1.0],
    )
    .unwrap();
    let inside = [0.3, 0.4, 0.9, 0.1];
    let outside = [-0.4, 0.5, 1.7, 1.3, 0.5, -0.25];
    let (mut a, mut b) = (vec![0.0; 6], vec![0.0; 6]);
    s.par_eval_batch(&inside, &mut a).unwrap();
    s.par_eval_batch_extrapolated(&inside, &mut b).unwrap();
    assert_eq!(a, b, "inside the domain the same bits");
    assert!(s.par_eval_batch(&outside, &mut [0.0; 9]).is_err());
    let mut c = vec![0.0; 9];
    s.par_eval_batch_extrapolated(&outside, &mut c).unwrap();
    for (p, x) in c.chunks_exact(3).zip(outside.chunks_exact(2)) {
        assert!(
            (p[0].hypot(p[1]) - 1.0).abs() < 1e-14,
            "on the circle: {p:?}"
        );
        assert!((p[2] - 2.0 * x[1]).abs() < 1e-14, "z linear: {p:?}");
    }
    // partials outside against differences of the continued values
    let x = [1.7, 1.3];
    let d = s.eval_partial_extrapolated(&x, &[1, 0]).unwrap();
    assert!(s.eval_partial(&x, &[1, 0]).is_err());
    let e = 1e-6;
    let (mut fp, mut fm) = (vec![0.0; 3], vec![0.0; 3]);
    s.par_eval_batch_extrapolated(&[x[0] + e, x[1]], &mut fp)
        .unwrap();
    s.par_eval_batch_extrapolated(&[x[0] - e, x[1]], &mut fm)
        .unwrap();
    let fd: Vec<f64> = fp
        .iter()
        .zip(&fm)
        .map(|(p, m)| (p - m) / (2.0 * e))
        .collect();
    assert_near(&d, &fd, 1e-7, 10.0, "continued partial");
    // the kind-independent operations of `Tensor` keep the rational kind and the values
    let t = crate::Tensor::from(s.clone());
    let r = t.insert_knot(0, 0.3, 2).unwrap();
    assert!(matches!(r, crate::Tensor::Nurbs(_)));
    assert_eq!(r.shape(), &[5, 2]);
    let (mut v0, mut v1) = (vec![0.0; 6], vec![0.0; 6]);
    t.eval_batch(&inside, &mut v0).unwrap();
    r.eval_batch(&inside, &mut v1).unwrap();
    assert_near(&v0, &v1, 1e-15, 10.0, "inserted");
    let line = t.slice(&[None, Some(0.5)]).unwrap();
    assert_eq!((line.n_vars(), line.weights().is_some()), (1, true));
    let mut p = vec![0.0; 3];
    line.eval_batch(&[0.3], &mut p).unwrap();
    assert_near(&p, &s.eval(&[0.3, 0.5]).unwrap(), 1e-15, 10.0, "sliced");
}
