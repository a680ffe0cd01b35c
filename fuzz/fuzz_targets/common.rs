//! Shared pieces of the lekalo fuzz targets: hostile numbers and sizes, and "exercise" functions
//! that call every inspector and operation of a validated object.
//!
//! The contract checked everywhere: no panic, no hang, no huge allocation (libFuzzer's
//! `-rss_limit_mb` / `-malloc_limit_mb` catch those), and values returned as `Ok` from an
//! evaluation of finite data are finite (no silent NaN).

#![allow(dead_code)]

use arbitrary::{Arbitrary, Result, Unstructured};
use lekalo::{
    BSplineCurve, BSplineSurface, BezierCurve, BezierSurface, KnotVector, NurbsCurve, NurbsSurface,
    PiecewisePolynomial, Points, PpSpace,
};

/// A float biased towards the values that break numerical code.
#[derive(Debug, Clone, Copy)]
pub struct Num(pub f64);

impl<'a> Arbitrary<'a> for Num {
    fn arbitrary(u: &mut Unstructured<'a>) -> Result<Self> {
        let tag: u8 = u.arbitrary()?;
        Ok(Num(match tag % 24 {
            0 => f64::NAN,
            1 => f64::INFINITY,
            2 => f64::NEG_INFINITY,
            3 => 0.0,
            4 => -0.0,
            5 => f64::MAX,
            6 => f64::MIN,
            7 => f64::MIN_POSITIVE,
            8 => 5e-324,
            9 => 1e300,
            10 => -1e-300,
            11 => 1e8,
            12 => 1.0 + f64::EPSILON,
            13 => 1.0 - f64::EPSILON / 2.0,
            14..=19 => f64::from(u.int_in_range(-8i8..=8)?) / 4.0,
            _ => u.arbitrary::<f64>()?,
        }))
    }
}

/// A size (degree, order, count) biased towards small values but sometimes absurd.
#[derive(Debug, Clone, Copy)]
pub struct Size(pub usize);

impl<'a> Arbitrary<'a> for Size {
    fn arbitrary(u: &mut Unstructured<'a>) -> Result<Self> {
        let tag: u8 = u.arbitrary()?;
        Ok(Size(match tag % 16 {
            0 => usize::MAX,
            1 => usize::MAX / 2,
            2 => 1 << 40,
            3 => 1_000_000_000_000,
            4 => 1_000_000_000,
            5 => (1 << 31) + 1,
            6 => u.int_in_range(0..=300)?,
            _ => u.int_in_range(0..=8)?,
        }))
    }
}

/// Raw floats of a list of hostile numbers.
pub fn floats(v: &[Num]) -> Vec<f64> {
    v.iter().map(|n| n.0).collect()
}

/// The floats sorted (total order) when `sort` is set, to get past the knot validation more often.
pub fn maybe_sorted(v: &[Num], sort: bool) -> Vec<f64> {
    let mut f = floats(v);
    if sort {
        f.sort_by(f64::total_cmp);
    }
    f
}

/// Panics if an `Ok` evaluation of finite data holds a NaN.
pub fn assert_no_nan(what: &str, values: &[f64]) {
    assert!(
        values.iter().all(|v| !v.is_nan()),
        "{what} returned NaN as Ok: {values:?}"
    );
}

/// Parameters inside and around a domain, plus the hostile ones given.
pub fn params(domain: (f64, f64), extra: &[Num]) -> Vec<f64> {
    let (a, b) = domain;
    let mut t = vec![
        a,
        b,
        0.5 * a + 0.5 * b,
        a + 0.25 * (b - a),
        b - 1e-3 * (b - a),
    ];
    t.extend(extra.iter().map(|n| n.0));
    t
}

/// Derivative orders to try: small, the degree, and a hostile one.
pub fn orders(degree: usize, hostile: Size) -> [usize; 4] {
    [0, 1, degree.saturating_add(1), hostile.0]
}

pub fn exercise_points(p: &Points) {
    let _ = p.bounding_box();
    let _ = p.max_abs();
    let _ = p.extent();
    for q in p.iter() {
        assert_eq!(q.len(), p.dim(), "chunk length");
    }
    let _ = p.point2(0);
    let _ = p.point3(p.len().saturating_sub(1));
}

pub fn exercise_knots(kv: &KnotVector, degree: Size, ts: &[f64]) {
    let _ = kv.distinct();
    let _ = kv.is_clamped(degree.0);
    for &t in ts {
        let _ = kv.multiplicity(t);
        let a = kv.find_span(degree.0, t);
        let mut cursor = kv.span_cursor(degree.0);
        let b = cursor.find(t);
        assert_eq!(
            a.is_ok(),
            b.is_ok(),
            "cursor and binary search disagree at {t}"
        );
        if let (Ok(a), Ok(b)) = (a, b) {
            assert_eq!(a, b, "cursor and binary search disagree at {t}");
        }
    }
}

pub fn exercise_bspline(c: &BSplineCurve, extra: &[Num], order: Size, times: Size) {
    let ts = params(c.domain(), extra);
    exercise_knots(c.knots(), Size(c.degree()), &ts);
    let _ = c.bounding_box();
    let _ = c.is_clamped();
    let dim = c.dim();
    let mut out = vec![0.0; dim * ts.len()];
    let batch = c.eval_batch(&ts, &mut out);
    for (i, &t) in ts.iter().enumerate() {
        if let Ok(p) = c.eval(t) {
            assert_no_nan("BSplineCurve::eval", &p);
            if batch.is_ok() {
                assert_eq!(
                    p.iter().map(|x| x.to_bits()).collect::<Vec<_>>(),
                    out[i * dim..(i + 1) * dim]
                        .iter()
                        .map(|x| x.to_bits())
                        .collect::<Vec<_>>(),
                    "batch and single evaluation differ at {t}"
                );
            }
        }
        for k in orders(c.degree(), order) {
            if let Ok(d) = c.eval_derivatives(t, k) {
                assert_no_nan("eval_derivatives", d.as_slice());
            }
        }
        let _ = c.insert_knot(t, times.0);
        let _ = c.insert_knot(t, 1);
        if let Ok((l, r)) = c.split_at(t) {
            let _ = l.eval(l.domain().1);
            let _ = r.eval(r.domain().0);
        }
    }
    let _ = c.refine_knots(&ts);
    let mut sorted = ts.clone();
    sorted.sort_by(f64::total_cmp);
    let _ = c.refine_knots(&sorted);
    let _ = c.derivative();
    let segs = c.to_bezier_segments();
    let _ = BSplineCurve::from_bezier_segments(&segs);
    for s in &segs {
        let _ = s.eval(0.5);
    }
    let _ = c.reverse();
    if extra.len() >= 2 {
        let _ = c.reparametrize(extra[0].0, extra[1].0);
    }
    let _ = PiecewisePolynomial::from_bspline(c);
}

pub fn exercise_bezier(c: &BezierCurve, extra: &[Num], order: Size) {
    let ts = params((0.0, 1.0), extra);
    let dim = c.dim();
    let mut out = vec![0.0; dim * ts.len()];
    let _ = c.eval_batch(&ts, &mut out);
    let mut one = vec![0.0; dim];
    for &t in &ts {
        if let Ok(p) = c.eval(t) {
            assert_no_nan("BezierCurve::eval", &p);
        }
        let _ = c.eval_bernstein_into(t, &mut one);
        for k in orders(c.degree(), order) {
            if let Ok(d) = c.eval_derivatives(t, k) {
                assert_no_nan("eval_derivatives", d.as_slice());
            }
        }
        let _ = c.split_at(t);
    }
    let _ = c.derivative();
    let b = c.to_bspline();
    let _ = b.eval(0.5);
}

pub fn exercise_nurbs(c: &NurbsCurve, extra: &[Num], order: Size, times: Size) {
    let ts = params(c.domain(), extra);
    let _ = c.weights();
    let _ = c.control_points();
    let dim = c.dim();
    let mut out = vec![0.0; dim * ts.len()];
    let _ = c.eval_batch(&ts, &mut out);
    for &t in &ts {
        if let Ok(p) = c.eval(t) {
            assert_no_nan("NurbsCurve::eval", &p);
        }
        for k in orders(c.degree(), order) {
            if k <= 64 || k == order.0 {
                if let Ok(d) = c.eval_derivatives(t, k) {
                    assert_no_nan("eval_derivatives", d.as_slice());
                }
            }
        }
    }
    exercise_bspline(c.homogeneous(), extra, order, times);
}

pub fn exercise_bspline_surface(s: &BSplineSurface, extra: &[Num], order: Size) {
    let ((u0, u1), (v0, v1)) = s.domain();
    let us = params((u0, u1), extra);
    let vs = params((v0, v1), extra);
    let dim = s.dim();
    let mut grid = vec![0.0; us.len() * vs.len() * dim];
    let _ = s.eval_grid(&us, &vs, &mut grid);
    let uv: Vec<[f64; 2]> = us.iter().zip(&vs).map(|(&u, &v)| [u, v]).collect();
    let mut batch = vec![0.0; uv.len() * dim];
    let _ = s.eval_batch(&uv, &mut batch);
    for &[u, v] in &uv {
        if let Ok(p) = s.eval(u, v) {
            assert_no_nan("BSplineSurface::eval", &p);
        }
        for k in orders(s.degree_u().max(s.degree_v()), order) {
            if let Ok(d) = s.eval_derivatives(u, v, k) {
                assert_no_nan("eval_derivatives", d.as_slice());
            }
        }
        let _ = s.normal(u, v);
        let _ = s.iso_curve_u(v);
        let _ = s.iso_curve_v(u);
    }
    let (nu, nv) = s.net_size();
    let _ = s.control_point(nu, nv);
    let _ = s.control_point(nu.saturating_sub(1), nv.saturating_sub(1));
}

pub fn exercise_nurbs_surface(s: &NurbsSurface, extra: &[Num], order: Size) {
    let ((u0, u1), (v0, v1)) = s.domain();
    let us = params((u0, u1), extra);
    let vs = params((v0, v1), extra);
    let dim = s.dim();
    let mut grid = vec![0.0; us.len() * vs.len() * dim];
    let _ = s.eval_grid(&us, &vs, &mut grid);
    let uv: Vec<[f64; 2]> = us.iter().zip(&vs).map(|(&u, &v)| [u, v]).collect();
    let mut batch = vec![0.0; uv.len() * dim];
    let _ = s.eval_batch(&uv, &mut batch);
    let _ = s.weights();
    let _ = s.control_points();
    for &[u, v] in &uv {
        if let Ok(p) = s.eval(u, v) {
            assert_no_nan("NurbsSurface::eval", &p);
        }
        for k in orders(s.degree_u().max(s.degree_v()), order) {
            if k <= 16 || k == order.0 {
                if let Ok(d) = s.eval_derivatives(u, v, k) {
                    assert_no_nan("eval_derivatives", d.as_slice());
                }
            }
        }
        let _ = s.normal(u, v);
        let _ = s.iso_curve_u(v);
        let _ = s.iso_curve_v(u);
    }
    let (nu, nv) = s.net_size();
    let _ = s.weight(nu, 0);
    let _ = s.control_point(0, nv);
}

pub fn exercise_bezier_surface(s: &BezierSurface, extra: &[Num], order: Size) {
    let ts = params((0.0, 1.0), extra);
    for (&u, &v) in ts.iter().zip(ts.iter().rev()) {
        if let Ok(p) = s.eval(u, v) {
            assert_no_nan("BezierSurface::eval", &p);
        }
        for k in orders(s.degree_u().max(s.degree_v()), order) {
            if let Ok(d) = s.eval_derivatives(u, v, k) {
                assert_no_nan("eval_derivatives", d.as_slice());
            }
        }
        let _ = s.normal(u, v);
        let _ = s.iso_curve_u(v);
        let _ = s.iso_curve_v(u);
    }
    let b = s.to_bspline();
    let _ = b.eval(0.5, 0.5);
}

pub fn exercise_pp(f: &PiecewisePolynomial, extra: &[Num], order: Size) {
    let xs = params(f.domain(), extra);
    for &x in &xs {
        if let Ok(p) = f.eval(x) {
            assert_no_nan("PiecewisePolynomial::eval", &p);
        }
        let _ = f.piece_index(x);
        for k in orders(f.order(), order) {
            if let Ok(d) = f.eval_derivatives(x, k) {
                assert_no_nan("eval_derivatives", d.as_slice());
            }
            if let Ok(d) = f.eval_derivatives_left(x, k) {
                assert_no_nan("eval_derivatives_left", d.as_slice());
            }
        }
    }
    for j in [0, 1, f.order(), order.0] {
        let _ = f.derivative(j);
        for i in [0, 1, f.n_pieces().saturating_sub(1), f.n_pieces()] {
            let _ = f.jump(i, j);
        }
    }
}

pub fn exercise_space(s: &PpSpace, f: Option<&PiecewisePolynomial>) {
    let _ = s.dimension();
    let _ = s.knots();
    // quasi-interpolation costs O(n·k²) for n B-splines of order k, by design: the fuzzer keeps
    // to moderate spaces (orders up to MAX_DEGREE + 1 are accepted by the constructors)
    if s.order() > 64 || s.dimension() > 4096 {
        return;
    }
    if s.dimension() <= 64 {
        let basis = s.truncated_power_basis();
        for b in basis.iter().take(4) {
            let _ = s.contains(b, lekalo::DEFAULT_CONTINUITY_RTOL);
        }
    }
    for rule in [
        lekalo::TauRule::FirstKnotAfter,
        lekalo::TauRule::LeftEndOfSupport,
        lekalo::TauRule::Midpoint,
        lekalo::TauRule::Greville,
    ] {
        let _ = rule.points(s.knots(), s.order());
        let _ = lekalo::quasi_interpolate(s, rule, |x, r| if r == 0 { x.sin() } else { 0.0 });
        if let Some(f) = f {
            let _ = f.to_bspline(s, rule);
        }
    }
}
