//! Tests of `piecewise_ref.rs`: the generic view gives the bits of direct loops in both bases,
//! finds the pieces by definition, and refuses malformed arrays by name.

use proptest::prelude::*;

use crate::curve::Beyond;
use crate::oracle::proptest_config;
use crate::pp::{BernsteinFormRef, PowerFormRef};
use crate::{Arg, Error};

/// The piece of `x` by definition: increasing, the last `j` with `x_j ≤ x`; decreasing, the
/// last `j` with `x_j ≥ x`; the first or last non-empty piece beyond the ends.
fn piece_of(b: &[f64], x: f64) -> usize {
    let pieces = b.len() - 1;
    let non_empty: Vec<usize> = (0..pieces).filter(|&j| b[j] != b[j + 1]).collect();
    let descending = b[pieces] < b[0];
    let (before, at_or_after_end) = if descending {
        (x > b[0], x <= b[pieces])
    } else {
        (x < b[0], x >= b[pieces])
    };
    if before {
        non_empty[0]
    } else if at_or_after_end {
        non_empty[non_empty.len() - 1]
    } else if descending {
        (0..pieces).rev().find(|&j| b[j] >= x).unwrap_or(0)
    } else {
        (0..pieces).rev().find(|&j| b[j] <= x).unwrap_or(0)
    }
}

/// SciPy's arrays, as the test's direct loops read them.
#[derive(Clone, Copy)]
struct Arrays<'a> {
    c: &'a [f64],
    order: usize,
    b: &'a [f64],
    dim: usize,
}

/// The power form's kernel as it was written before the view became generic, for
/// coordinate `d` on piece `j`: `Σ_{s≥r} c_s·s!/(s−r)!·u^{s−r}` in `u = x − x_j` by Horner's
/// rule, the highest power first.
fn horner_loop(a: &Arrays<'_>, j: usize, d: usize, x: f64, r: usize) -> f64 {
    let (k, pieces) = (a.order, a.b.len() - 1);
    if r >= k {
        return 0.0;
    }
    let u = x - a.b[j];
    let mut v = 0.0;
    for s in (r..k).rev() {
        let falling: f64 = (s - r + 1..=s).map(|q| q as f64).product();
        v = v * u + falling * a.c[((k - 1 - s) * pieces + j) * a.dim + d];
    }
    v
}

/// The Bernstein form's kernel as it was written before the view became generic, for one
/// coordinate: the forward differences `Δ^nu c` scaled by `k!/(k − nu)!`, then SciPy's
/// written-out sum up to degree 3 or de Casteljau's convex combinations, over `h^nu`.
fn bernstein_loop(arrays: &Arrays<'_>, j: usize, d: usize, x: f64, nu: usize) -> f64 {
    let Arrays { c, order, b, dim } = *arrays;
    let (k, pieces) = (order - 1, b.len() - 1);
    if nu > k {
        return 0.0;
    }
    let h = b[j + 1] - b[j];
    let s = (x - b[j]) / h;
    let s1 = 1.0 - s;
    let mut w: Vec<f64> = (0..=k).map(|a| c[(a * pieces + j) * dim + d]).collect();
    let (falling, h_nu) = if nu == 0 {
        (1.0, 1.0)
    } else {
        (
            (k - nu + 1..=k).map(|v| v as f64).product(),
            (0..nu).fold(1.0, |p, _| p * h),
        )
    };
    for r in 1..=nu {
        for a in 0..=k - r {
            w[a] = w[a + 1] - w[a];
        }
    }
    w.truncate(k - nu + 1);
    if nu > 0 {
        for wa in &mut w {
            *wa *= falling;
        }
    }
    let sum = match w.len() - 1 {
        0 => w[0],
        1 => w[0] * s1 + w[1] * s,
        2 => w[0] * s1 * s1 + w[1] * 2.0 * s1 * s + w[2] * s * s,
        3 => {
            w[0] * s1 * s1 * s1
                + w[1] * 3.0 * s1 * s1 * s
                + w[2] * 3.0 * s1 * s * s
                + w[3] * s * s * s
        }
        _ => {
            for r in 1..w.len() {
                for a in 0..w.len() - r {
                    w[a] = s1 * w[a] + s * w[a + 1];
                }
            }
            w[0]
        }
    };
    if nu == 0 {
        sum
    } else {
        sum / h_nu
    }
}

proptest! {
    #![proptest_config(proptest_config(96))]

    /// The generic view gives, bit for bit, what a direct loop of Horner's rule (power
    /// form) or of the Bernstein sum and de Casteljau's algorithm (Bernstein form) gives on
    /// the piece of each point: random coefficients, orders 1..=8, derivative orders up to
    /// beyond the degree, increasing and decreasing breakpoints with empty pieces, inside
    /// and beyond the ends, continued or NaN.
    #[test]
    fn the_generic_view_has_the_bits_of_the_direct_loops(
        order in 1usize..=8,
        dim in 1usize..=3,
        gaps in prop::collection::vec(prop_oneof![1 => Just(0.0), 4 => 0.05f64..2.0], 1..=9),
        start in -5.0f64..5.0,
        descending in any::<bool>(),
        seed in prop::collection::vec(-4.0f64..4.0, 1..=300),
        us in prop::collection::vec(-0.3f64..1.3, 1..=50),
        nu in 0usize..=9,
        many in any::<bool>(),
        continued in any::<bool>(),
    ) {
        let mut b = vec![start];
        for g in &gaps {
            let last = b[b.len() - 1];
            b.push(if descending { last - g } else { last + g });
        }
        prop_assume!(b[b.len() - 1] != b[0]);
        let pieces = b.len() - 1;
        let c: Vec<f64> = (0..order * pieces * dim).map(|i| seed[i % seed.len()] * (1.0 + i as f64 * 1e-3)).collect();
        let (lo, hi) = (b[0], b[pieces]);
        let mut xs: Vec<f64> = us.iter().map(|u| lo + (hi - lo) * u).chain(b.iter().copied()).collect();
        if many {
            // at least as many points as pieces: the bucket table rather than the bisection
            // (for scalar values on breakpoints without empty end pieces, its split form,
            // which finds a piece for every point and selects NaN afterwards)
            xs.extend([f64::NAN, f64::INFINITY, f64::NEG_INFINITY]);
            while xs.len() < 4 * pieces {
                xs.extend_from_within(..);
            }
        }
        let beyond = if continued { Beyond::Continue } else { Beyond::Nan };
        let (bmin, bmax) = (lo.min(hi), lo.max(hi));
        let power = PowerFormRef::new(&c, order, &b, dim).unwrap();
        let bernstein = BernsteinFormRef::new(&c, order, &b, dim).unwrap();
        let (mut got_p, mut got_b) = (vec![0.0; xs.len() * dim], vec![0.0; xs.len() * dim]);
        power.par_eval_beyond(&xs, nu, beyond, &mut got_p).unwrap();
        bernstein.par_eval_beyond(&xs, nu, beyond, &mut got_b).unwrap();
        let arrays = Arrays { c: &c, order, b: &b, dim };
        for (i, &x) in xs.iter().enumerate() {
            let outside = !(bmin..=bmax).contains(&x);
            let j = if x.is_nan() { 0 } else { piece_of(&b, x) };
            for d in 0..dim {
                let (want_p, want_b) = if !x.is_finite() || (outside && !continued) {
                    (f64::NAN, f64::NAN)
                } else {
                    (
                        horner_loop(&arrays, j, d, x, nu),
                        bernstein_loop(&arrays, j, d, x, nu),
                    )
                };
                let (gp, gb) = (got_p[i * dim + d], got_b[i * dim + d]);
                prop_assert!(gp.to_bits() == want_p.to_bits() || (gp.is_nan() && want_p.is_nan()),
                    "power, x = {}, nu = {}, order = {}: {} against {}", x, nu, order, gp, want_p);
                prop_assert!(gb.to_bits() == want_b.to_bits() || (gb.is_nan() && want_b.is_nan()),
                    "Bernstein, x = {}, nu = {}, order = {}: {} against {}", x, nu, order, gb, want_b);
            }
        }
    }
}

/// The arrays are refused by name: too few breakpoints, an order or dimension of 0, a
/// wrong coefficient count, ends not finite or equal.
#[test]
fn bad_arrays_are_refused_by_name() {
    let c = [1.0; 8];
    let e = PowerFormRef::new(&c, 4, &[0.0], 2).unwrap_err();
    assert!(
        matches!(e, Error::TooFew { what, .. } if what.arg() == Some(Arg::Breakpoints)),
        "{e}"
    );
    let e = BernsteinFormRef::new(&c, 0, &[0.0, 1.0], 2).unwrap_err();
    assert!(matches!(e, Error::TooFew { .. }), "{e}");
    let e = PowerFormRef::new(&c, 4, &[0.0, 1.0], 0).unwrap_err();
    assert!(matches!(e, Error::TooFew { .. }), "{e}");
    let e = PowerFormRef::new(&c[..7], 4, &[0.0, 1.0], 2).unwrap_err();
    assert!(
        matches!(
            e,
            Error::LengthMismatch {
                expected: 8,
                got: 7,
                ..
            }
        ),
        "{e}"
    );
    let e = BernsteinFormRef::new(&c, 4, &[0.0, f64::NAN], 2).unwrap_err();
    assert!(matches!(e, Error::NonFinite { .. }), "{e}");
    let e = BernsteinFormRef::new(&c, 4, &[2.0, 2.0], 2).unwrap_err();
    assert!(matches!(e, Error::EmptyDomain { .. }), "{e}");
}

/// Every point of `xs` evaluated in one batch and alone (the binary search and the general
/// loop) gives the same bits, in both bases, orders 1 to 6 (degrees 0 to 5), continued or NaN.
fn batch_has_the_bits_of_single_points(b: &[f64], xs: &[f64]) {
    let pieces = b.len() - 1;
    for order in 1..=6 {
        let c: Vec<f64> = (0..order * pieces)
            .map(|i| ((i * 7919) % 23) as f64 / 7.0 - 1.5)
            .collect();
        let power = PowerFormRef::new(&c, order, b, 1).unwrap();
        let bernstein = BernsteinFormRef::new(&c, order, b, 1).unwrap();
        for beyond in [Beyond::Continue, Beyond::Nan] {
            let (mut got_p, mut got_b) = (vec![0.0; xs.len()], vec![0.0; xs.len()]);
            power.par_eval_beyond(xs, 0, beyond, &mut got_p).unwrap();
            bernstein
                .par_eval_beyond(xs, 0, beyond, &mut got_b)
                .unwrap();
            for (i, &x) in xs.iter().enumerate() {
                let (mut one_p, mut one_b) = ([0.0], [0.0]);
                power.par_eval_beyond(&[x], 0, beyond, &mut one_p).unwrap();
                bernstein
                    .par_eval_beyond(&[x], 0, beyond, &mut one_b)
                    .unwrap();
                for (got, one, basis) in [
                    (got_p[i], one_p[0], "power"),
                    (got_b[i], one_b[0], "Bernstein"),
                ] {
                    assert!(
                        got.to_bits() == one.to_bits() || (got.is_nan() && one.is_nan()),
                        "{basis}, order {order}, {beyond:?}, x = {x}: {got} against {one}"
                    );
                }
            }
        }
    }
}

/// Scalar values on the split table (a batch of at least as many points as pieces, on the
/// thread pool, and one of fewer than four points a piece, which reads the coefficients in
/// place): the bits of each point evaluated alone, at NaN, ±∞, beyond the ends and at every
/// breakpoint, with and without empty pieces at the ends (SciPy's `PPoly.from_spline` repeats
/// the end knots); an overflow is refused with the index of its point.
#[test]
fn the_split_table_has_the_bits_of_single_points() {
    use crate::pp::piece_search::{PieceSearch, PAR_MIN_POINTS};
    let pieces = 37;
    // uneven breakpoints, none repeated
    let b: Vec<f64> = (0..=pieces)
        .map(|i| {
            let u = i as f64 / pieces as f64;
            -3.0 + 7.0 * u + 0.05 * (7.0 * u).sin()
        })
        .collect();
    let ends_repeated: Vec<f64> = [b[0]; 3]
        .iter()
        .chain(&b)
        .chain(&[b[pieces]; 3])
        .copied()
        .collect();
    for b in [&b, &ends_repeated] {
        let mut xs: Vec<f64> = (0..PAR_MIN_POINTS + 999)
            .map(|i| -4.0 + 9.0 * ((i as f64 * 0.618_033_988_749_895) % 1.0))
            .collect();
        xs.extend(b.iter().copied());
        xs.extend([f64::NAN, f64::INFINITY, f64::NEG_INFINITY, -3.0, 4.0]);
        xs.rotate_right(b.len() + 5);
        for xs in [&xs[..], &xs[..2 * b.len()]] {
            assert!(
                PieceSearch::new(b, xs.len()).has_split_table(),
                "the split table"
            );
            batch_has_the_bits_of_single_points(b, xs);
        }
    }
    // a value that overflows is refused, naming its point
    let mut c = vec![1.0; 4 * pieces];
    for m in 0..4 {
        c[m * pieces + 5] = f64::MAX; // every coefficient of piece 5: Horner overflows for u > 0
    }
    let f = PowerFormRef::new(&c, 4, &b, 1).unwrap();
    let mut xs: Vec<f64> = (0..4 * pieces)
        .map(|i| -3.0 + 7.0 * i as f64 / (4 * pieces) as f64)
        .collect();
    let at = xs
        .iter()
        .position(|&x| x > b[5] + 0.5 * (b[6] - b[5]))
        .unwrap();
    xs[at] = b[5] + 0.99 * (b[6] - b[5]);
    xs[..at].iter_mut().for_each(|x| *x = b[0]);
    let mut out = vec![0.0; xs.len()];
    let e = f
        .par_eval_beyond(&xs, 0, Beyond::Continue, &mut out)
        .unwrap_err();
    assert!(
        matches!(e, Error::NonFinite { index, .. } if index == at),
        "{e}"
    );
}
