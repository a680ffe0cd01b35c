//! The value at one point of a scalar tensor-product B-spline whose knots and coefficients are
//! read through accessors ([`tensor_value_by`]): the scalar call of SciPy's `NdBSpline` and
//! `RectBivariateSpline.ev` on arrays read in place, with no spline built and nothing checked
//! beyond what the few numbers read need. The `N`-variate twin of
//! [`bspline_value_by`](crate::bspline_value_by).

use crate::basis::{basis_funs_fixed, basis_funs_into, BasisScratch};
use crate::error::{readable, Error, NthDirection, Result};
use crate::knots::span_by;
use crate::tensor::contract::contract3;
use crate::tensor::locate::{beyond_defined, Beyond};

/// Largest number of directions of [`tensor_value_by`] (the window of `Π_a (p_a + 1)`
/// coefficients is gathered on the heap, its size checked).
pub const MAX_POINT_VALUE_VARS: usize = 32;

/// `S(x) = Σ_{i_0…i_{N−1}} c_{i_0…i_{N−1}} Π_a N_{i_a,p_a}(x_a)` at one point of a scalar
/// tensor-product B-spline given by accessors: `knot(a, i)` for `i < n_knots[a]`, the knots of
/// direction `a` (degree `degrees[a]`), and `coefficient(f)` for `f < n_coefficients`, the
/// coefficient of `(i_0, …, i_{N−1})` at the row-major index
/// `f = ((i_0·n_1 + i_1)·n_2 + …)·n_{N−1} + i_{N−1}` (`n_a = n_knots[a] − p_a − 1`; extra
/// coefficients beyond `Π_a n_a`, as FITPACK pads them, are not read).
///
/// Per direction the span by binary search (P&T *The NURBS Book*, Algorithm A2.1) and the
/// `p_a + 1` basis functions by the Cox–de Boor triangle (Algorithm A2.2), then the window of
/// `Π_a (p_a + 1)` coefficients contracted one direction after the other (sum factorisation,
/// `docs/theory/tensor.md#tensor-product-splines`): the operations of
/// [`TensorBSpline::eval`](crate::TensorBSpline::eval) in the same order, so for valid knots the
/// same bits. About `Σ_a (log2 |T_a| + 2p_a) + Π_a (p_a + 1)` reads.
///
/// Beyond the domain `[t_{p_a}, t_{n_a}]` of a direction: [`Beyond::Continue`] continues the
/// polynomial of the end span, [`Beyond::Clamp`] takes the coordinate at the nearest end,
/// [`Beyond::Nan`] gives NaN; a NaN coordinate gives NaN, an infinite one NaN except under
/// [`Beyond::Clamp`], which takes it at its end (FITPACK's `fpbisp`). The knots are not checked
/// sorted (that costs `O(|T_a|)`): unsorted knots give some number, never a panic, as SciPy's
/// evaluation gives some number.
///
/// ```
/// use lekalo::tensor::{tensor_value_by, Beyond};
/// use lekalo::{Points, TensorBSpline};
/// // f(x, y) = x + 2y on [0, 1]², bilinear
/// let k = [0.0, 0.0, 1.0, 1.0];
/// let c = [0.0, 2.0, 1.0, 3.0];
/// let s = TensorBSpline::new(vec![1, 1], vec![k.to_vec(), k.to_vec()], Points::from_flat(1, c.to_vec())?)?;
/// let v = tensor_value_by(&[1, 1], &[4, 4], |_, i| k[i], 4, |f| c[f], &[0.25, 0.5], Beyond::Nan)?;
/// assert_eq!(v, s.eval(&[0.25, 0.5])?[0]);
/// assert_eq!(v, 1.25);
/// let clamped = tensor_value_by(&[1, 1], &[4, 4], |_, i| k[i], 4, |f| c[f], &[2.0, 0.5], Beyond::Clamp)?;
/// assert_eq!(clamped, 2.0);
/// # Ok::<(), lekalo::Error>(())
/// ```
///
/// # Errors
/// [`Error::LengthMismatch`] if `n_knots` or `x` does not have one entry per direction of
/// `degrees`; [`Error::InvalidArgument`] for no direction or more than
/// [`MAX_POINT_VALUE_VARS`], fewer than `2p_a + 2` knots, an empty (or NaN) domain
/// `t_{p_a} ≥ t_{n_a}`, or fewer than `Π_a n_a` coefficients.
#[allow(clippy::neg_cmp_op_on_partial_ord)] // NaN knots must read as an empty domain
pub fn tensor_value_by(
    degrees: &[usize],
    n_knots: &[usize],
    knot: impl Fn(usize, usize) -> f64,
    n_coefficients: usize,
    coefficient: impl Fn(usize) -> f64,
    x: &[f64],
    beyond: Beyond,
) -> Result<f64> {
    let n = degrees.len();
    for (what, got) in [
        ("knot vector lengths (one per direction)", n_knots.len()),
        ("point coordinates (one per direction)", x.len()),
    ] {
        if got != n {
            return Err(Error::LengthMismatch {
                what: what.into(),
                expected: n,
                got,
            });
        }
    }
    let invalid = |reason: String| Error::InvalidArgument {
        what: "tensor spline (knots, degrees, coefficients)".into(),
        reason,
    };
    if n == 0 || n > MAX_POINT_VALUE_VARS {
        return Err(invalid(format!(
            "{n} directions: give between 1 and {MAX_POINT_VALUE_VARS}"
        )));
    }
    // sizes, domains and the window's size, before anything is read beyond the ends
    let mut sizes = Vec::with_capacity(n);
    let mut window = 1usize;
    let mut total = 1usize;
    for (a, (&p, &len)) in degrees.iter().zip(n_knots).enumerate() {
        if len < 2 * p + 2 {
            return Err(invalid(format!(
                "{}: {len} knots for degree {p}: at least {} are needed",
                NthDirection(a),
                2 * p + 2
            )));
        }
        let size = len - p - 1;
        sizes.push(size);
        total = total.saturating_mul(size);
        window = window.saturating_mul(p + 1);
    }
    if total > n_coefficients {
        return Err(invalid(format!(
            "{n_coefficients} coefficients for a net of {sizes:?}: at least {total} are needed"
        )));
    }
    // the window is at most the net, which the caller holds
    let mut point = Vec::with_capacity(n);
    let mut spans = Vec::with_capacity(n);
    for (a, (&p, &size)) in degrees.iter().zip(&sizes).enumerate() {
        let (lo, hi) = (knot(a, p), knot(a, size));
        if !(lo < hi) {
            return Err(invalid(format!(
                "{}: the domain [t_k, t_n] = [{}, {}] is empty",
                NthDirection(a),
                readable(&lo),
                readable(&hi)
            )));
        }
        let t = x[a];
        if !beyond_defined(t, beyond, lo, hi) {
            return Ok(f64::NAN);
        }
        point.push(if beyond == Beyond::Clamp {
            t.clamp(lo, hi)
        } else {
            t
        });
        spans.push(span_by(&|i| knot(a, i), p, size, t.clamp(lo, hi)));
    }
    if n == 3 && degrees.iter().all(|&p| p == degrees[0]) {
        let at = |a: usize| (spans[a], point[a]);
        let sizes = [sizes[1], sizes[2]];
        match degrees[0] {
            1 => {
                return Ok(value3::<2>(
                    [at(0), at(1), at(2)],
                    sizes,
                    &knot,
                    &coefficient,
                ))
            }
            2 => {
                return Ok(value3::<3>(
                    [at(0), at(1), at(2)],
                    sizes,
                    &knot,
                    &coefficient,
                ))
            }
            3 => {
                return Ok(value3::<4>(
                    [at(0), at(1), at(2)],
                    sizes,
                    &knot,
                    &coefficient,
                ))
            }
            4 => {
                return Ok(value3::<5>(
                    [at(0), at(1), at(2)],
                    sizes,
                    &knot,
                    &coefficient,
                ))
            }
            5 => {
                return Ok(value3::<6>(
                    [at(0), at(1), at(2)],
                    sizes,
                    &knot,
                    &coefficient,
                ))
            }
            _ => {}
        }
    }
    // the basis vectors, direction a at offsets[a]..
    let top = degrees.iter().copied().max().unwrap_or(0);
    // the fixed-order triangle up to degree 5 (no scratch), the general one above
    let mut scratch: Option<BasisScratch> = None;
    let mut knots = Vec::with_capacity(2 * top + 1);
    let mut bases = vec![0.0; degrees.iter().map(|p| p + 1).sum()];
    let mut start = 0;
    for (a, (&p, &i)) in degrees.iter().zip(&spans).enumerate() {
        // t_{i−p+1} ..= t_{i+p} after one unused slot: t_i at index p, the span given to A2.2
        knots.clear();
        knots.push(f64::NAN);
        knots.extend((i + 1 - p..=i + p).map(|j| knot(a, j)));
        let out = &mut bases[start..start + p + 1];
        let t = point[a];
        match p {
            0 => out[0] = 1.0,
            1 => out.copy_from_slice(&basis_funs_fixed::<2>(&knots, p, t)),
            2 => out.copy_from_slice(&basis_funs_fixed::<3>(&knots, p, t)),
            3 => out.copy_from_slice(&basis_funs_fixed::<4>(&knots, p, t)),
            4 => out.copy_from_slice(&basis_funs_fixed::<5>(&knots, p, t)),
            5 => out.copy_from_slice(&basis_funs_fixed::<6>(&knots, p, t)),
            _ => {
                let scratch = scratch.get_or_insert_with(|| BasisScratch::new(top));
                basis_funs_into(&knots, p, p, t, scratch, out);
            }
        }
        start += p + 1;
    }
    // the window of coefficients, first direction slowest: runs of p_{N−1} + 1 consecutive
    // coefficients, one for each position of an odometer over the other directions
    let last = n - 1;
    let run = degrees[last] + 1;
    let mut strides = vec![1usize; n];
    for a in (0..last).rev() {
        strides[a] = strides[a + 1] * sizes[a + 1];
    }
    let mut values = Vec::with_capacity(window);
    let mut odometer = vec![0usize; n];
    'runs: loop {
        let mut f = spans[last] - degrees[last];
        for a in 0..last {
            f += (spans[a] - degrees[a] + odometer[a]) * strides[a];
        }
        values.extend((f..f + run).map(&coefficient));
        let mut a = last;
        loop {
            if a == 0 {
                break 'runs;
            }
            a -= 1;
            odometer[a] += 1;
            if odometer[a] <= degrees[a] {
                break;
            }
            odometer[a] = 0;
        }
    }
    // contract the leading direction, one after the other, each sum from its first term
    let mut next = vec![0.0; window / (degrees[0] + 1)];
    let mut offset = 0;
    for &p in degrees {
        let basis = &bases[offset..offset + p + 1];
        offset += p + 1;
        let len = values.len() / (p + 1);
        next.truncate(len);
        for (r, &v) in next.iter_mut().zip(&values[..len]) {
            *r = basis[0] * v;
        }
        for (j, &b) in basis.iter().enumerate().skip(1) {
            for (r, &v) in next.iter_mut().zip(&values[j * len..(j + 1) * len]) {
                *r += b * v;
            }
        }
        std::mem::swap(&mut values, &mut next);
    }
    Ok(values[0])
}

/// [`tensor_value_by`] of a trivariate spline of one degree `p = W − 1 ≤ 5` at a located point
/// (`(span, coordinate)` per direction; `sizes`, the net sizes of directions 1 and 2): the basis
/// vectors by the fixed-order triangle ([`basis_funs_fixed`]) and the window of `W³`
/// coefficients gathered on the stack and contracted by the batch kernels' [`contract3`], the
/// same operations in the same order as the general contraction below (direction 0 first,
/// each sum from its first term), so the same bits, with nothing allocated.
#[inline(always)]
fn value3<const W: usize>(
    at: [(usize, f64); 3],
    sizes: [usize; 2],
    knot: &impl Fn(usize, usize) -> f64,
    coefficient: &impl Fn(usize) -> f64,
) -> f64 {
    let p = W - 1;
    let bases: [[f64; W]; 3] = std::array::from_fn(|a| {
        let (i, t) = at[a];
        // t_{i−p+1} ..= t_{i+p} after one unused slot: t_i at index p, the span given to A2.2
        let mut local = [f64::NAN; 12];
        for (j, k) in local[1..2 * W - 1].iter_mut().enumerate() {
            *k = knot(a, i + 1 - p + j);
        }
        basis_funs_fixed::<W>(&local[..2 * W - 1], p, t)
    });
    let first = at.map(|(i, _)| i - p);
    let mut window = [[[0.0; W]; W]; W];
    for (j0, plane) in window.iter_mut().enumerate() {
        for (j1, run) in plane.iter_mut().enumerate() {
            let f = ((first[0] + j0) * sizes[0] + first[1] + j1) * sizes[1] + first[2];
            for (j2, v) in run.iter_mut().enumerate() {
                *v = coefficient(f + j2);
            }
        }
    }
    let flat = window.as_flattened().as_flattened();
    contract3::<W>(flat, [0, 0, 0], [W * W, W], &bases[0], &bases[1], &bases[2])
}

#[cfg(test)]
mod tests {
    use proptest::prelude::*;

    use super::*;
    use crate::oracle::proptest_config;
    use crate::points::Points;
    use crate::tensor::tests::spline;
    use crate::tensor::TensorBSpline;

    fn value(s: &TensorBSpline, coefficients: &[f64], x: &[f64], beyond: Beyond) -> Result<f64> {
        let knots = s.knots();
        let lens: Vec<usize> = knots.iter().map(|k| k.len()).collect();
        tensor_value_by(
            s.degrees(),
            &lens,
            |a, i| knots[a].as_slice()[i],
            coefficients.len(),
            |f| coefficients[f],
            x,
            beyond,
        )
    }

    proptest! {
        #![proptest_config(proptest_config(64))]

        /// For scalar splines, the value read through accessors has the bits of the batch
        /// beyond the domain, at points inside, outside and with NaN or infinite coordinates.
        #[test]
        fn point_value_has_the_bits_of_the_batch(
            s in spline(),
            raw in prop::collection::vec(-0.5f64..1.5, 1..=40),
        ) {
            prop_assume!(s.dim() == 1);
            let n = s.n_vars();
            let domains = s.domain();
            let mut xs: Vec<f64> = raw.iter().enumerate().map(|(i, u)| {
                let (lo, hi) = domains[i % n];
                lo + (hi - lo) * u
            }).collect();
            xs.truncate(xs.len() / n * n);
            if xs.len() >= n {
                xs[0] = f64::NAN;
            }
            // infinite coordinates: NaN, or the domain's end when clamped
            if xs.len() >= 3 * n {
                xs[n] = f64::INFINITY;
                xs[2 * n + n - 1] = f64::NEG_INFINITY;
            }
            let c = s.control_points().as_slice();
            for rule in [Beyond::Continue, Beyond::Clamp, Beyond::Nan] {
                let mut want = vec![0.0; xs.len() / n];
                s.view().par_eval_batch_beyond(&xs, None, rule, &mut want).unwrap();
                for (x, w) in xs.chunks_exact(n).zip(&want) {
                    let got = value(&s, c, x, rule).unwrap();
                    prop_assert_eq!(got.to_bits(), w.to_bits(), "{:?} at {:?}", rule, x);
                }
            }
        }
    }

    /// Trivariate splines of one degree (the stack path, degrees 1 to 5) and of mixed degrees
    /// (the general path): the bits of the batch, inside and beyond the box, under every rule,
    /// on uneven knots with a repeated interior knot.
    #[test]
    fn trivariate_point_values_have_the_bits_of_the_batch() {
        let mut rng = 0x5851_f42d_u64;
        let mut next = move || {
            rng ^= rng << 13;
            rng ^= rng >> 7;
            rng ^= rng << 17;
            (rng >> 11) as f64 / (1u64 << 53) as f64
        };
        for degrees in [
            [1, 1, 1],
            [2, 2, 2],
            [3, 3, 3],
            [4, 4, 4],
            [5, 5, 5],
            [3, 2, 3],
        ] {
            let knots: Vec<Vec<f64>> = degrees
                .iter()
                .enumerate()
                .map(|(a, &p)| {
                    let mut t = vec![-1.0 - a as f64; p + 1];
                    let mut inner: Vec<f64> = (0..3 + a).map(|_| 2.0 * next() - 1.0).collect();
                    inner.push(inner[0]);
                    inner.sort_by(f64::total_cmp);
                    t.extend(inner);
                    t.extend(vec![1.5; p + 1]);
                    t
                })
                .collect();
            let size: usize = knots
                .iter()
                .zip(&degrees)
                .map(|(t, p)| t.len() - p - 1)
                .product();
            let net: Vec<f64> = (0..size).map(|_| next() - 0.5).collect();
            let s = TensorBSpline::new(degrees.to_vec(), knots, Points::from_flat(1, net).unwrap())
                .unwrap();
            let domains = s.domain();
            let xs: Vec<f64> = (0..3 * 200)
                .map(|i| {
                    let (lo, hi) = domains[i % 3];
                    lo + (hi - lo) * (1.6 * next() - 0.3)
                })
                .collect();
            let c = s.control_points().as_slice();
            for rule in [Beyond::Continue, Beyond::Clamp, Beyond::Nan] {
                let mut want = vec![0.0; 200];
                s.view()
                    .par_eval_batch_beyond(&xs, None, rule, &mut want)
                    .unwrap();
                for (x, w) in xs.chunks_exact(3).zip(&want) {
                    let got = value(&s, c, x, rule).unwrap();
                    assert_eq!(got.to_bits(), w.to_bits(), "{degrees:?} {rule:?} at {x:?}");
                }
            }
        }
    }

    #[test]
    fn bad_arrays_give_errors_or_numbers_never_panics() {
        let k = [0.0, 0.0, 1.0, 1.0];
        let c = [1.0, 2.0, 3.0, 4.0];
        let at = |knots: &[f64], coefficients: &[f64], x: &[f64]| {
            tensor_value_by(
                &[1, 1],
                &[knots.len(), knots.len()],
                |_, i| knots[i],
                coefficients.len(),
                |f| coefficients[f],
                x,
                Beyond::Continue,
            )
        };
        assert!(matches!(
            at(&k, &c[..3], &[0.5, 0.5]),
            Err(Error::InvalidArgument { .. })
        ));
        assert!(matches!(
            at(&k[..3], &c, &[0.5, 0.5]),
            Err(Error::InvalidArgument { .. })
        ));
        assert!(matches!(
            at(&[0.0, 1.0, 1.0, 1.0], &c, &[0.5, 0.5]),
            Err(Error::InvalidArgument { .. })
        ));
        assert!(matches!(
            at(&[0.0, f64::NAN, 1.0, 1.0], &c, &[0.5, 0.5]),
            Err(Error::InvalidArgument { .. })
        ));
        assert!(matches!(
            at(&k, &c, &[0.5]),
            Err(Error::LengthMismatch { .. })
        ));
        // unsorted knots: some number, no panic
        let wild = [0.0, 0.0, 2.0, -1.0, 1.0, 1.0];
        let v = tensor_value_by(
            &[1, 1],
            &[6, 6],
            |_, i| wild[i],
            16,
            |f| f as f64,
            &[0.7, 0.2],
            Beyond::Continue,
        );
        assert!(v.is_ok());
        let none = tensor_value_by(&[], &[], |_, _| 0.0, 1, |_| 0.0, &[], Beyond::Nan);
        assert!(matches!(none, Err(Error::InvalidArgument { .. })));
    }
}
