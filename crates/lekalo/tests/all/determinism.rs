//! Determinism: the same input gives the same output **bits** — on a fresh object or a
//! clone, in a batch or one point at a time, in any order of the parameters, on any thread.
//!
//! Bit-identity of batch and single evaluation holds because both run the same kernel on the
//! same span with the same operation order; the span cursor of the batch only changes how the
//! span is *found*, never which span is used. Parallel batch paths (fast evaluation)
//! must keep this: see `docs/robustness.md`.

use lekalo::{
    BSplineCurve, BSplineSurface, BezierCurve, BezierSurface, KnotVector, NurbsCurve, NurbsSurface,
    PiecewisePolynomial, Points,
};

fn bits(v: &[f64]) -> Vec<u64> {
    v.iter().map(|x| x.to_bits()).collect()
}

/// Parameters on `[a, b]`: sorted, including every knot-like boundary, then a scrambled copy.
fn sorted_params(a: f64, b: f64, n: usize) -> Vec<f64> {
    (0..=n)
        .map(|i| (a + (b - a) * i as f64 / n as f64).min(b))
        .collect()
}

fn scrambled(ts: &[f64]) -> Vec<f64> {
    // a fixed permutation: stride coprime with the length
    let n = ts.len();
    let stride = (1..n).rev().find(|s| gcd(*s, n) == 1).unwrap_or(1);
    (0..n).map(|i| ts[(i * stride) % n]).collect()
}

fn gcd(a: usize, b: usize) -> usize {
    if b == 0 {
        a
    } else {
        gcd(b, a % b)
    }
}

fn data(n: usize, dim: usize) -> Vec<f64> {
    (0..n * dim)
        .map(|i| ((i as f64 + 0.5) * 1.618_033_988_749_895).sin() * 10.0)
        .collect()
}

fn curve() -> BSplineCurve {
    let knots = vec![
        0.0, 0.0, 0.0, 0.0, 0.1, 0.25, 0.25, 0.5, 0.7, 0.7, 0.7, 0.9, 1.0, 1.0, 1.0, 1.0,
    ];
    let n = knots.len() - 4;
    BSplineCurve::new(3, knots, Points::from_flat(3, data(n, 3)).expect("finite")).expect("valid")
}

fn nurbs() -> NurbsCurve {
    let c = curve();
    let w: Vec<f64> = (0..c.control_points().len())
        .map(|i| 0.5 + (i % 4) as f64)
        .collect();
    NurbsCurve::new(
        3,
        c.knots().as_slice().to_vec(),
        c.control_points().clone(),
        w,
    )
    .expect("valid")
}

fn check_batch_matches_single(
    dim: usize,
    ts: &[f64],
    single: impl Fn(f64) -> Vec<f64>,
    batch: impl Fn(&[f64], &mut [f64]),
    what: &str,
) {
    let mut out = vec![0.0; ts.len() * dim];
    batch(ts, &mut out);
    for (i, &t) in ts.iter().enumerate() {
        assert_eq!(
            bits(&single(t)),
            bits(&out[i * dim..(i + 1) * dim]),
            "{what}: batch and single differ at t = {t}"
        );
    }
}

#[test]
fn curves_batch_equals_single_bit_for_bit_in_any_order() {
    let c = curve();
    let n = nurbs();
    let b = BezierCurve::new(Points::from_flat(2, data(8, 2)).expect("finite")).expect("valid");
    let ts = sorted_params(0.0, 1.0, 200);
    for order in [
        ts.clone(),
        scrambled(&ts),
        ts.iter().rev().copied().collect(),
    ] {
        check_batch_matches_single(
            3,
            &order,
            |t| c.eval(t).expect("in domain"),
            |ts, out| c.eval_batch(ts, out).expect("in domain"),
            "BSplineCurve",
        );
        check_batch_matches_single(
            3,
            &order,
            |t| n.eval(t).expect("in domain"),
            |ts, out| n.eval_batch(ts, out).expect("in domain"),
            "NurbsCurve",
        );
        check_batch_matches_single(
            2,
            &order,
            |t| b.eval(t).expect("in domain"),
            |ts, out| b.eval_batch(ts, out).expect("in domain"),
            "BezierCurve",
        );
    }
}

#[test]
fn surfaces_grid_and_batch_equal_single_bit_for_bit() {
    let (nu, nv) = (6, 5);
    let ctrl = Points::from_flat(3, data(nu * nv, 3)).expect("finite");
    let ku = KnotVector::clamped_uniform(3, nu).expect("valid");
    let kv = KnotVector::clamped_uniform(2, nv).expect("valid");
    let s = BSplineSurface::from_knot_vectors(3, 2, ku.clone(), kv.clone(), ctrl.clone(), (nu, nv))
        .expect("valid");
    let w: Vec<f64> = (0..nu * nv).map(|i| 1.0 + (i % 3) as f64).collect();
    let ns = NurbsSurface::new(
        3,
        2,
        ku.into_vec(),
        kv.into_vec(),
        ctrl.clone(),
        w,
        (nu, nv),
    )
    .expect("valid");
    let bz = BezierSurface::new(ctrl, (nu, nv)).expect("valid");
    let us = sorted_params(0.0, 1.0, 23);
    let vs = scrambled(&sorted_params(0.0, 1.0, 17));
    let mut grid = vec![0.0; us.len() * vs.len() * 3];
    let mut ngrid = grid.clone();
    s.eval_grid(&us, &vs, &mut grid).expect("in domain");
    ns.eval_grid(&us, &vs, &mut ngrid).expect("in domain");
    let uv: Vec<[f64; 2]> = us
        .iter()
        .flat_map(|&u| vs.iter().map(move |&v| [u, v]))
        .collect();
    let mut batch = vec![0.0; uv.len() * 3];
    let mut nbatch = batch.clone();
    s.eval_batch(&uv, &mut batch).expect("in domain");
    ns.eval_batch(&uv, &mut nbatch).expect("in domain");
    for (k, &[u, v]) in uv.iter().enumerate() {
        let one = s.eval(u, v).expect("in domain");
        assert_eq!(
            bits(&one),
            bits(&grid[3 * k..3 * k + 3]),
            "grid at ({u}, {v})"
        );
        assert_eq!(
            bits(&one),
            bits(&batch[3 * k..3 * k + 3]),
            "batch at ({u}, {v})"
        );
        let one = ns.eval(u, v).expect("in domain");
        assert_eq!(
            bits(&one),
            bits(&ngrid[3 * k..3 * k + 3]),
            "NURBS grid at ({u}, {v})"
        );
        assert_eq!(
            bits(&one),
            bits(&nbatch[3 * k..3 * k + 3]),
            "NURBS batch at ({u}, {v})"
        );
        // the Bezier surface has no batch API; repeated calls must agree
        assert_eq!(
            bits(&bz.eval(u, v).expect("in domain")),
            bits(&bz.eval(u, v).expect("in domain")),
            "Bezier surface at ({u}, {v})"
        );
    }
}

/// Every operation run twice on independently built equal inputs gives identical bits.
fn fingerprint() -> Vec<u64> {
    let c = curve();
    let mut out = Vec::new();
    let ts = sorted_params(0.0, 1.0, 37);
    for &t in &ts {
        out.extend(bits(&c.eval(t).expect("in domain")));
        out.extend(bits(
            c.eval_derivatives(t, 4).expect("in domain").as_slice(),
        ));
        out.extend(bits(
            nurbs()
                .eval_derivatives(t, 3)
                .expect("in domain")
                .as_slice(),
        ));
    }
    let ins = c.insert_knot(0.33, 2).expect("valid insertion");
    out.extend(bits(ins.control_points().as_slice()));
    let refined = c
        .refine_knots(&[0.05, 0.3, 0.3, 0.8])
        .expect("valid refinement");
    out.extend(bits(refined.control_points().as_slice()));
    let (l, r) = c.split_at(0.6).expect("inside");
    out.extend(bits(l.control_points().as_slice()));
    out.extend(bits(r.knots().as_slice()));
    for s in c.to_bezier_segments() {
        out.extend(bits(s.curve.control_points().as_slice()));
    }
    out.extend(bits(
        c.derivative()
            .expect("derivative")
            .control_points()
            .as_slice(),
    ));
    let pp = PiecewisePolynomial::from_bspline(&c).expect("pp form");
    out.extend(bits(pp.coefficients()));
    for &t in &ts {
        out.extend(bits(&pp.eval(t).expect("in domain")));
    }
    out
}

#[test]
fn same_input_same_bits() {
    let a = fingerprint();
    let b = fingerprint();
    assert!(!a.is_empty(), "the fingerprint covers some output");
    assert_eq!(a, b, "two runs on equal inputs differ");
    // a clone evaluates identically to the original
    let c = curve();
    let d = c.clone();
    for t in sorted_params(0.0, 1.0, 50) {
        assert_eq!(bits(&c.eval(t).expect("ok")), bits(&d.eval(t).expect("ok")));
    }
}

#[test]
fn same_bits_on_every_thread() {
    let reference = fingerprint();
    let handles: Vec<_> = (0..4).map(|_| std::thread::spawn(fingerprint)).collect();
    for h in handles {
        assert_eq!(
            h.join().expect("thread ran"),
            reference,
            "a thread computed other bits"
        );
    }
}

#[test]
fn evaluation_has_no_hidden_state() {
    // the result at t does not depend on what was evaluated before
    let c = curve();
    let t = 0.7; // a knot of multiplicity 3
    let first = bits(&c.eval(t).expect("ok"));
    for s in [0.0, 1.0, 0.69999, 0.70001, 0.25] {
        let _ = c.eval(s).expect("ok");
        assert_eq!(
            bits(&c.eval(t).expect("ok")),
            first,
            "after evaluating at {s}"
        );
    }
    let mut out = vec![0.0; 3 * 3];
    c.eval_batch(&[1.0, 0.0, t], &mut out).expect("ok");
    assert_eq!(bits(&out[6..9]), first, "batch after jumping backwards");
}

#[test]
fn parallel_bits_do_not_depend_on_the_thread_count() {
    // 200,003 parameters: the parallel task size is 25,001 on two threads and 12,501 on four,
    // so the split differs between pools; the bits must not.
    let c = curve();
    let n = nurbs();
    let ts = scrambled(&sorted_params(0.0, 1.0, 200_003));
    let (ev, nev) = (c.evaluator(), n.evaluator());
    let mut want = vec![0.0; ts.len() * 3];
    let mut want_n = vec![0.0; ts.len() * 3];
    ev.eval_batch(&ts, &mut want).expect("in domain");
    nev.eval_batch(&ts, &mut want_n).expect("in domain");
    for threads in 1..=4 {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .expect("a thread pool");
        let mut got = vec![0.0; ts.len() * 3];
        let mut got_n = vec![0.0; ts.len() * 3];
        pool.install(|| {
            ev.par_eval_batch(&ts, &mut got).expect("in domain");
            nev.par_eval_batch(&ts, &mut got_n).expect("in domain");
        });
        assert_eq!(bits(&got), bits(&want), "B-spline, {threads} threads");
        assert_eq!(bits(&got_n), bits(&want_n), "NURBS, {threads} threads");
    }
}
