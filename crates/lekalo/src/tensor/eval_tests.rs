//! Tests of the borrowed evaluation ([`TensorBSplineRef`]) and of the batches beyond the
//! domain ([`Beyond`]): the same bits as the owned spline's kernels.

use proptest::prelude::*;

use crate::error::Error;
use crate::oracle::proptest_config;
use crate::points::Points;
use crate::tensor::tests::spline;
use crate::tensor::{Beyond, TensorBSpline, TensorBSplineRef};

fn bits(v: &[f64]) -> Vec<u64> {
    v.iter().map(|x| x.to_bits()).collect()
}

/// Points of the spline's box widened by half its width on each side, with now and then a NaN
/// or infinite coordinate: `(points, which are finite, which are inside)`.
fn points(s: &TensorBSpline, raw: &[(f64, u8)]) -> Vec<f64> {
    let domains = s.domain();
    raw.iter()
        .enumerate()
        .map(|(i, &(u, special))| {
            let (lo, hi) = domains[i % s.n_vars()];
            match special {
                0 => f64::NAN,
                1 => f64::INFINITY,
                2 => lo,
                3 => hi,
                4 => f64::NEG_INFINITY,
                _ => lo + (hi - lo) * u,
            }
        })
        .collect()
}

proptest! {
    #![proptest_config(proptest_config(64))]

    /// A spline borrowed from its arrays evaluates as the owned one; beyond the domain,
    /// `Continue` is the extrapolated batch, `Clamp` the plain batch at the clamped point and
    /// `Nan` NaN; a point with a NaN coordinate is NaN, one with an infinite coordinate too but
    /// under `Clamp` (the plain batch at the domain's end); inside, every rule has the
    /// bits of the plain batch, values and partial derivatives.
    #[test]
    fn borrowed_batches_have_the_bits_of_the_owned_kernels(
        s in spline(),
        raw in prop::collection::vec((-0.5f64..1.5, 0u8..40), 4..=80),
        order in 0usize..=2,
    ) {
        let n = s.n_vars();
        let dim = s.dim();
        let knots: Vec<&[f64]> = s.knots().iter().map(|k| k.as_slice()).collect();
        let view = TensorBSplineRef::new(s.degrees(), knots, s.control_points().as_slice(), dim)
            .unwrap();
        let orders: Vec<usize> = (0..n).map(|a| if a == 0 { order } else { 0 }).collect();
        let orders = (order > 0).then_some(&orders[..]);
        let xs = points(&s, &raw[..raw.len() / n * n]);
        let count = xs.len() / n;
        let domains = s.domain();
        let mut out = vec![0.0; count * dim];
        for rule in [Beyond::Continue, Beyond::Clamp, Beyond::Nan] {
            view.par_eval_batch_beyond(&xs, orders, rule, &mut out).unwrap();
            for (x, o) in xs.chunks_exact(n).zip(out.chunks_exact(dim)) {
                let nan = x.iter().any(|t| t.is_nan());
                let finite = x.iter().all(|t| t.is_finite());
                let inside = x.iter().zip(&domains).all(|(&t, &(lo, hi))| t >= lo && t <= hi);
                let mut want = vec![0.0; dim];
                if nan || (!finite && rule != Beyond::Clamp) || (rule == Beyond::Nan && !inside) {
                    prop_assert!(o.iter().all(|v| v.is_nan()), "{rule:?} at {x:?}: {o:?}");
                    continue;
                }
                match rule {
                    Beyond::Continue => s.par_eval_batch_extrapolated(x, orders, &mut want).unwrap(),
                    _ => {
                        let c: Vec<f64> = x.iter().zip(&domains).map(|(&t, &(lo, hi))| t.clamp(lo, hi)).collect();
                        s.eval_batch(&c, orders, &mut want).unwrap();
                    }
                }
                prop_assert_eq!(bits(o), bits(&want), "{:?} at {:?}", rule, x);
            }
        }
        // the borrowed point and grid kernels are the owned ones
        let inside: Vec<f64> = xs.chunks_exact(n).filter(|x| x.iter().zip(&domains).all(|(&t, &(lo, hi))| t >= lo && t <= hi)).flatten().copied().collect();
        for x in inside.chunks_exact(n) {
            prop_assert_eq!(bits(&view.eval(x).unwrap()), bits(&s.eval(x).unwrap()));
        }
    }
}

/// Above the sequential size and the cell-order size, with the parallel rows of the grid path:
/// the bits of the sequential batch and of the point kernel.
#[test]
fn large_borrowed_batches_and_grids_have_the_sequential_bits() {
    let p: usize = 3;
    let m: usize = 40; // control points a direction: 64,000 numbers, above the cell-order net size
    let k: Vec<f64> = (0..m + p + 1)
        .map(|i| (i.saturating_sub(p).min(m - p)) as f64 / (m - p) as f64)
        .collect();
    let net: Vec<f64> = (0..m * m * m)
        .map(|i| ((i * 7919) % 1013) as f64 / 1013.0 - 0.5)
        .collect();
    let s = TensorBSpline::new(
        vec![p; 3],
        vec![k.clone(), k.clone(), k],
        Points::from_flat(1, net).unwrap(),
    )
    .unwrap();
    let count = 20_000;
    let xs: Vec<f64> = (0..3 * count)
        .map(|i| ((i * 104_729) % 9973) as f64 / 9973.0 * 1.4 - 0.2)
        .collect();
    let mut par = vec![0.0; count];
    s.view()
        .par_eval_batch_beyond(&xs, None, Beyond::Continue, &mut par)
        .unwrap();
    let mut seq = vec![0.0; count];
    for (x, o) in xs.chunks_exact(3).zip(seq.iter_mut()) {
        s.par_eval_batch_extrapolated(x, None, std::slice::from_mut(o))
            .unwrap();
    }
    assert_eq!(bits(&par), bits(&seq));
    // a 2-D grid of 200 × 150 values (rows on the thread pool) against the point kernel
    let s2 = TensorBSpline::new(
        vec![3, 2],
        vec![
            vec![0.0, 0.0, 0.0, 0.0, 0.3, 0.5, 1.0, 1.0, 1.0, 1.0],
            vec![0.0, 0.0, 0.0, 0.2, 0.6, 1.0, 1.0, 1.0],
        ],
        Points::from_flat(1, (0..30).map(|i| f64::from(i).sin()).collect()).unwrap(),
    )
    .unwrap();
    let gx: Vec<f64> = (0..200).map(|i| f64::from(i) / 199.0).collect();
    let gy: Vec<f64> = (0..150).map(|i| f64::from(i) / 149.0).collect();
    let mut grid = vec![0.0; 200 * 150];
    s2.eval_grid(&[&gx, &gy], None, &mut grid).unwrap();
    for (i, &x) in gx.iter().enumerate() {
        for (j, &y) in gy.iter().enumerate() {
            assert_eq!(
                grid[i * 150 + j].to_bits(),
                s2.eval(&[x, y]).unwrap()[0].to_bits()
            );
        }
    }
}

/// A borrowed spline is refused as the owned one is, with the same errors.
#[test]
fn borrowed_splines_are_checked_as_owned_ones() {
    let net = [0.0; 4];
    let good: [f64; 4] = [0.0, 0.0, 1.0, 1.0];
    let check = |t: &[f64], p: usize, net: &[f64]| -> Error {
        let e = TensorBSplineRef::new(&[p], vec![t], net, 1).unwrap_err();
        let owned = TensorBSpline::new(
            vec![p],
            vec![t.to_vec()],
            Points::from_flat(1, net.to_vec()).unwrap(),
        )
        .unwrap_err();
        // the same error; the same words for the knots (the net is counted in numbers here,
        // in points there)
        assert_eq!(std::mem::discriminant(&e), std::mem::discriminant(&owned));
        if !matches!(e, Error::LengthMismatch { .. }) {
            assert_eq!(e.to_string(), owned.to_string());
        }
        e
    };
    assert!(matches!(
        check(&[0.0, 1.0, 0.5, 2.0], 1, &net[..2]),
        Error::KnotsNotSorted { .. }
    ));
    assert!(matches!(
        check(&[0.0, 0.0, 0.0, 1.0, 1.0, 1.0], 1, &net),
        Error::KnotMultiplicity {
            multiplicity: 3,
            ..
        }
    ));
    assert!(matches!(
        check(&[0.0, 1.0, 2.0], 1, &net[..1]),
        Error::Degree { .. }
    ));
    assert!(matches!(
        check(&good, 1, &net[..3]),
        Error::LengthMismatch { .. }
    ));
    assert!(matches!(
        check(&[0.0, f64::NAN, 1.0, 1.0], 1, &net[..2]),
        Error::NonFinite { .. }
    ));
    assert!(matches!(
        check(&[1.0, 1.0, 1.0, 1.0], 1, &net[..2]),
        Error::EmptyDomain { .. }
    ));
    let e = TensorBSplineRef::new(&[1], vec![&good], &net[..0], 0).unwrap_err();
    assert!(
        matches!(e, Error::InvalidArgument { what, .. } if what.words() == "dim"),
        "{e}"
    );
}

/// A spline of `n` directions of degree `p` whose net is `net` twice over (`dim = 2`, both
/// coordinates equal) and the scalar spline of `net`: uneven knots, clamped or not, with double
/// interior knots now and then.
fn twin_splines(n: usize, p: usize, gaps: &[f64], net: &[f64]) -> (TensorBSpline, TensorBSpline) {
    let per = gaps.len() / n;
    let knots: Vec<Vec<f64>> = (0..n)
        .map(|a| {
            let mut t = vec![-0.5 * a as f64];
            for &g in &gaps[a * per..(a + 1) * per] {
                t.push(t[t.len() - 1] + g);
            }
            t
        })
        .collect();
    let size: usize = knots.iter().map(|t| t.len() - p - 1).product();
    let scalar = net[..size].to_vec();
    let twice: Vec<f64> = scalar.iter().flat_map(|&v| [v, v]).collect();
    let make = |dim: usize, c: Vec<f64>| {
        TensorBSpline::new(
            vec![p; n],
            knots.clone(),
            Points::from_flat(dim, c).unwrap(),
        )
    };
    (make(1, scalar).unwrap(), make(2, twice).unwrap())
}

proptest! {
    #![proptest_config(proptest_config(64))]

    /// The fixed-size kernels (two or three directions of one degree `p ≤ 5`, scalar values,
    /// the spans by the bucket search) have the bits of the general odometer kernel (the same
    /// net as two equal coordinates), in sequential and parallel batches, inside the domain and
    /// beyond it; and they agree with the naive sum of products to `1e-14` of the net's scale.
    #[test]
    fn fixed_kernels_have_the_bits_of_the_general_kernel(
        n in 2usize..=3,
        p in 1usize..=5,
        gaps in prop::collection::vec(prop_oneof![1 => Just(0.0), 4 => 0.05f64..2.0], 3 * 14),
        net in prop::collection::vec(-10.0f64..10.0, 12usize.pow(3)),
        raw in prop::collection::vec(-0.3f64..1.3, 3 * 40),
    ) {
        // at most p + 1 equal knots in a row: a zero gap only between non-zero ones
        let mut gaps = gaps[..n * (2 * p + 5).min(14)].to_vec();
        for i in 1..gaps.len() {
            if gaps[i] == 0.0 && gaps[i - 1] == 0.0 {
                gaps[i] = 0.5;
            }
        }
        let (one, two) = twin_splines(n, p, &gaps, &net);
        let domains = one.domain();
        let xs: Vec<f64> = raw[..raw.len() / n * n]
            .iter()
            .enumerate()
            .map(|(i, u)| {
                let (lo, hi) = domains[i % n];
                lo + (hi - lo) * u
            })
            .collect();
        let count = xs.len() / n;
        for rule in [Beyond::Continue, Beyond::Clamp, Beyond::Nan] {
            let mut fixed = vec![0.0; count];
            one.view().par_eval_batch_beyond(&xs, None, rule, &mut fixed).unwrap();
            let mut general = vec![0.0; 2 * count];
            two.view().par_eval_batch_beyond(&xs, None, rule, &mut general).unwrap();
            for (k, (&f, g)) in fixed.iter().zip(general.chunks_exact(2)).enumerate() {
                prop_assert_eq!(f.to_bits(), g[0].to_bits(), "{:?}, point {}", rule, k);
            }
        }
        let scale = net.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let inside: Vec<f64> = xs
            .chunks_exact(n)
            .filter(|x| x.iter().zip(&domains).all(|(&t, &(lo, hi))| t >= lo && t <= hi))
            .flatten()
            .copied()
            .collect();
        let mut fixed = vec![0.0; inside.len() / n];
        one.eval_batch(&inside, None, &mut fixed).unwrap();
        for (x, &f) in inside.chunks_exact(n).zip(&fixed) {
            let want = crate::tensor::tests::naive_eval(&one, x)[0];
            prop_assert!((f - want).abs() <= 1e-14 * scale, "{} against {} at {:?}", f, want, x);
        }
    }
}

/// Batches at the cell-order sizes (just below, at and above `2^14` points, on a net above
/// `2^15` numbers) whose points come in every order (random, all in one cell, cells descending,
/// the first direction fastest) with NaN, infinite and out-of-box points, under every
/// [`Beyond`] rule: the bits of the point-by-point batch, which never takes the cell order.
#[test]
fn cell_ordered_batches_have_the_bits_of_single_points_in_any_order() {
    let p: usize = 3;
    let m: usize = 36; // 46,656 numbers
    let k: Vec<f64> = (0..m + p + 1)
        .map(|i| (i.saturating_sub(p).min(m - p)) as f64 / (m - p) as f64)
        .collect();
    let net: Vec<f64> = (0..m * m * m)
        .map(|i| ((i * 7919) % 1013) as f64 / 1013.0 - 0.5)
        .collect();
    let s = TensorBSpline::new(
        vec![p; 3],
        vec![k.clone(), k.clone(), k],
        Points::from_flat(1, net).unwrap(),
    )
    .unwrap();
    let mut rng = 0x2545_f491_u64;
    let mut next = || {
        rng ^= rng << 13;
        rng ^= rng >> 7;
        rng ^= rng << 17;
        (rng >> 11) as f64 / (1u64 << 53) as f64
    };
    for count in [(1 << 14) - 1, 1 << 14, (1 << 14) + 1, 40_000] {
        let random: Vec<f64> = (0..3 * count).map(|_| 1.4 * next() - 0.2).collect();
        let one_cell: Vec<f64> = (0..3 * count).map(|_| 0.5 + 1e-3 * next()).collect();
        // cells descending, and the last direction slowest (against the net's order)
        let descending: Vec<f64> = (0..count)
            .flat_map(|i| {
                let u = 1.0 - i as f64 / count as f64;
                [(7.0 * u).fract(), (31.0 * u).fract(), u]
            })
            .collect();
        for (name, mut xs) in [
            ("random", random),
            ("one cell", one_cell),
            ("descending", descending),
        ] {
            for i in (0..count).step_by(101) {
                xs[3 * i + i % 3] = [f64::NAN, f64::INFINITY, -2.0, 1.0, 0.0][i % 5];
            }
            for beyond in [Beyond::Continue, Beyond::Clamp, Beyond::Nan] {
                let mut batch = vec![0.0; count];
                s.view()
                    .par_eval_batch_beyond(&xs, None, beyond, &mut batch)
                    .unwrap();
                let mut single = vec![0.0; count];
                for (x, o) in xs.chunks_exact(3).zip(single.iter_mut()) {
                    s.view()
                        .par_eval_batch_beyond(x, None, beyond, std::slice::from_mut(o))
                        .unwrap();
                }
                assert_eq!(
                    bits(&batch),
                    bits(&single),
                    "{count} points, {name}, {beyond:?}"
                );
            }
        }
    }
}

/// The fixed-size kernels take their points in blocks (four a triangle of lanes): batches of
/// every size around a block and around the parallel threshold, with a NaN, an infinite and an
/// out-of-box point at every position of a block, in two and three directions of degrees 1 to 5
/// under every [`Beyond`] rule, have the bits of each point evaluated alone (the one-point path)
/// and of the general kernel (the same net as two equal coordinates); the refusing batch names
/// the first point outside the domain, wherever it stands in its block.
#[test]
fn blocked_fixed_kernels_have_the_bits_of_single_points_at_every_size() {
    let mut rng = 0x9e37_79b9_u64;
    let mut next = move || {
        rng ^= rng << 13;
        rng ^= rng >> 7;
        rng ^= rng << 17;
        (rng >> 11) as f64 / (1u64 << 53) as f64
    };
    let gaps: Vec<f64> = (0..3 * 14)
        .map(|i| if i % 7 == 3 { 0.0 } else { 0.1 + next() })
        .collect();
    let net: Vec<f64> = (0..12usize.pow(3)).map(|_| 20.0 * next() - 10.0).collect();
    for n in 2..=3 {
        for p in 1..=5 {
            let (one, two) = twin_splines(n, p, &gaps[..n * (2 * p + 5).min(14)], &net);
            let domains = one.domain();
            for count in (1..=9).chain([2047, 2048, 2049, 2053]) {
                let mut xs: Vec<f64> = (0..count * n)
                    .map(|i| {
                        let (lo, hi) = domains[i % n];
                        lo + (hi - lo) * (1.4 * next() - 0.2)
                    })
                    .collect();
                // a NaN, an infinite and a far point at positions 0..4 of successive blocks
                for (i, bad) in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY, 1e3]
                    .into_iter()
                    .enumerate()
                {
                    let at = 5 * i;
                    if at < count {
                        xs[at * n + i % n] = bad;
                    }
                }
                for rule in [Beyond::Continue, Beyond::Clamp, Beyond::Nan] {
                    let mut batch = vec![0.0; count];
                    one.view()
                        .par_eval_batch_beyond(&xs, None, rule, &mut batch)
                        .unwrap();
                    let mut general = vec![0.0; 2 * count];
                    two.view()
                        .par_eval_batch_beyond(&xs, None, rule, &mut general)
                        .unwrap();
                    for (k, x) in xs.chunks_exact(n).enumerate() {
                        let mut alone = [0.0];
                        one.view()
                            .par_eval_batch_beyond(x, None, rule, &mut alone)
                            .unwrap();
                        assert_eq!(
                            batch[k].to_bits(),
                            alone[0].to_bits(),
                            "n = {n}, p = {p}, {count} points, {rule:?}, point {k} {x:?}"
                        );
                        assert_eq!(
                            batch[k].to_bits(),
                            general[2 * k].to_bits(),
                            "n = {n}, p = {p}, {count} points, {rule:?}, point {k}"
                        );
                    }
                }
                // the refusing batch: the first point outside, in the order of the points
                let clamped: Vec<f64> = xs
                    .iter()
                    .enumerate()
                    .map(|(i, &t)| {
                        let (lo, hi) = domains[i % n];
                        if t.is_nan() {
                            lo
                        } else {
                            t.clamp(lo, hi)
                        }
                    })
                    .collect();
                let mut inside = clamped.clone();
                let first = count.min(6) - 1;
                let second = count - 1;
                if second != first {
                    inside[second * n] = domains[0].1 + 1.0;
                }
                inside[first * n + n - 1] = domains[n - 1].0 - 2.0;
                let mut out = vec![0.0; count];
                let e = one.eval_batch(&inside, None, &mut out).unwrap_err();
                assert_eq!(
                    e,
                    Error::ParameterOutOfDomain {
                        t: inside[first * n + n - 1],
                        min: domains[n - 1].0,
                        max: domains[n - 1].1
                    },
                    "n = {n}, p = {p}, {count} points"
                );
                let mut want = vec![0.0; 2 * count];
                two.eval_batch(&clamped, None, &mut want).unwrap();
                one.eval_batch(&clamped, None, &mut out).unwrap();
                for (k, (o, w)) in out.iter().zip(want.chunks_exact(2)).enumerate() {
                    assert_eq!(o.to_bits(), w[0].to_bits(), "n = {n}, p = {p}, point {k}");
                }
            }
        }
    }
}
