//! B-spline curve evaluation `C(t_i) = Σ_j N_{j,p}(t_i) P_j`, its JVP and its VJP on borrowed
//! knots and control points, for a few parameters: nothing is copied and only the numbers the
//! values need are read and checked (`docs/theory/derivatives.md`, "Curves").
//!
//! Building a [`BSplineCurve`] validates every knot and control point (finite, sorted,
//! multiplicities): O(n) work a call, which dominates when a handful of parameters is evaluated
//! on a long curve. Here each parameter reads its span's `2p + 2` knots `t_{i−p} ..= t_{i+p+1}`
//! and `p + 1` control points `P_{i−p} ..= P_i`, and checks exactly those: finite, the knots
//! non-decreasing, `t_i ≤ t ≤ t_{i+1}` with `t_i < t_{i+1}`. Those numbers are the whole
//! definition of the values there (P&T A2.2 reads nothing else), so an inconsistency elsewhere
//! cannot change them. When a check fails, the error is the one [`BSplineCurve::new`] gives for
//! the whole input (built then, on the error path only), so a caller sees lekalo's usual
//! message; a parameter outside the domain gives [`Error::ParameterOutOfDomain`], as
//! [`BSplineCurve::eval_batch`] does. The values are bit-for-bit those of
//! [`BSplineCurve::eval_batch`], [`BSplineCurve::eval_batch_jvp`] and (below its large-batch
//! path) [`BSplineCurve::eval_batch_vjp`]: the same basis (`slopes.rs`) and the same code,
//! the built curve's buffer checks and per-parameter bodies (`derivatives/curve.rs`,
//! `check_jvp_buffers`, `jvp_point`, `check_vjp_buffers`, `vjp_point`, forced inline), so
//! only the location of the span differs.

use super::{invalid_span, locate_span, window_counts};
use crate::curve::BSplineCurve;
use crate::derivatives::checks::check_len;
use crate::derivatives::curve::{
    check_jvp_buffers, check_vjp_buffers, combine, jvp_point, vjp_point, PointBasis,
};
use crate::error::{check_finite, Error, Result};
use crate::points::Points;

/// A B-spline curve of degree `p` on borrowed knots (`n + p + 1`) and point-major control
/// points (`n × dim`), checked only where read (module docs).
///
/// ```
/// use lekalo::derivatives::BorrowedCurve;
/// use lekalo::{BSplineCurve, Points};
/// let knots = [0.0, 0.0, 0.0, 1.0, 2.0, 3.0, 3.0, 3.0];
/// let control = [0.0, 0.0, 1.0, 2.0, 3.0, 2.0, 4.0, 0.0, 5.0, 1.0];
/// let view = BorrowedCurve::new(2, &knots, &control, 2)?;
/// let curve = BSplineCurve::new(2, knots.to_vec(), Points::from_flat(2, control.to_vec())?)?;
/// let (mut a, mut b) = ([0.0; 4], [0.0; 4]);
/// view.eval_batch(&[0.5, 2.25], &mut a)?;
/// curve.eval_batch(&[0.5, 2.25], &mut b)?;
/// assert_eq!(a, b);
/// # Ok::<(), lekalo::Error>(())
/// ```
#[derive(Debug, Clone, Copy)]
pub struct BorrowedCurve<'a> {
    degree: usize,
    knots: &'a [f64],
    control: &'a [f64],
    dim: usize,
    /// The number of control points `n`.
    n: usize,
}

impl<'a> BorrowedCurve<'a> {
    /// The curve of `degree` on `knots` and `control` (`dim` numbers a point), after the O(1)
    /// checks of the counts: `dim ≥ 1`, whole points, `n ≥ p + 1`, `n + p + 1` knots.
    ///
    /// # Errors
    /// [`Error::Dimension`] for `dim = 0`; [`Error::LengthMismatch`] for a partial point or a
    /// wrong number of knots; [`Error::Degree`] for fewer than `p + 1` control points.
    pub fn new(degree: usize, knots: &'a [f64], control: &'a [f64], dim: usize) -> Result<Self> {
        let n = window_counts(degree, knots, control, dim)?;
        Ok(BorrowedCurve {
            degree,
            knots,
            control,
            dim,
            n,
        })
    }

    /// The span `i` of `t` (`t_i ≤ t ≤ t_{i+1}`, `t_i < t_{i+1}`) after checking `t` in the
    /// domain `[t_p, t_n]` and the knots and control points the span reads (module docs).
    fn locate(&self, t: f64) -> Result<usize> {
        let (p, dim) = (self.degree, self.dim);
        let i = locate_span(self.knots, p, self.n, t).map_err(|e| self.explain(e))?;
        let points = &self.control[(i - p) * dim..(i + 1) * dim];
        if !points.iter().all(|x| x.is_finite()) {
            return Err(self.explain(invalid_span(t)));
        }
        Ok(i)
    }

    /// The error of [`BSplineCurve::new`] on the whole input if it has one, else `local` (a
    /// parameter outside the domain of a valid curve).
    fn explain(&self, local: Error) -> Error {
        let built = Points::from_flat(self.dim, self.control.to_vec())
            .and_then(|c| BSplineCurve::new(self.degree, self.knots.to_vec(), c));
        built.err().unwrap_or(local)
    }

    /// `C(t_i)` into `out` (`ts.len() × dim`, point-major), as [`BSplineCurve::eval_batch`].
    /// O(m·(log n + p² + p·dim)), no allocation beyond the basis scratch.
    ///
    /// # Errors
    /// [`Error::LengthMismatch`] for `out`; the errors of the module docs.
    pub fn eval_batch(&self, ts: &[f64], out: &mut [f64]) -> Result<()> {
        let dim = self.dim;
        check_len(
            "output buffer (parameters × dimension)",
            ts.len().saturating_mul(dim),
            out.len(),
        )?;
        let mut basis = PointBasis::new(self.degree);
        for (&t, o) in ts.iter().zip(out.chunks_exact_mut(dim)) {
            let first = basis.at(self.knots, self.degree, self.locate(t)?, t);
            combine(self.control, dim, first, basis.values(), o);
        }
        Ok(())
    }

    /// `Ċ_i = Σ_j N_{j,p}(t_i) Ṗ_j + C'(t_i) ṫ_i` into `tangent_out`, as the tangent of
    /// [`BSplineCurve::eval_batch_jvp`] (`None` tangents are zero).
    ///
    /// # Errors
    /// [`Error::LengthMismatch`] for a buffer of the wrong length, [`Error::NonFinite`] for a
    /// non-finite tangent; the errors of the module docs.
    pub fn eval_batch_jvp(
        &self,
        ts: &[f64],
        control_tangent: Option<&[f64]>,
        parameter_tangent: Option<&[f64]>,
        tangent_out: &mut [f64],
    ) -> Result<()> {
        let (p, dim) = (self.degree, self.dim);
        let sizes = (ts.len(), dim, self.control.len());
        check_jvp_buffers(sizes, control_tangent, parameter_tangent, tangent_out)?;
        let mut basis = PointBasis::new(p);
        let mut slope = vec![0.0; dim];
        for (i, (&t, d)) in ts.iter().zip(tangent_out.chunks_exact_mut(dim)).enumerate() {
            let first = basis.at(self.knots, p, self.locate(t)?, t);
            let dt = parameter_tangent.map(|dt| dt[i]);
            jvp_point(
                self.control,
                dim,
                first,
                &basis,
                control_tangent,
                dt,
                &mut slope,
                d,
            );
        }
        Ok(())
    }

    /// `P̄_j = Σ_i N_{j,p}(t_i) ḡ_i` into `control_cotangent` (zeroed first) and
    /// `t̄_i = ḡ_i · C'(t_i)` into `parameter_cotangent`, each when given, as
    /// [`BSplineCurve::eval_batch_vjp`]: each parameter scatters into `p + 1` control points.
    ///
    /// # Errors
    /// [`Error::LengthMismatch`] for a buffer of the wrong length, [`Error::NonFinite`] for a
    /// non-finite cotangent; the errors of the module docs (the outputs are then unspecified).
    pub fn eval_batch_vjp(
        &self,
        ts: &[f64],
        cotangent: &[f64],
        mut control_cotangent: Option<&mut [f64]>,
        mut parameter_cotangent: Option<&mut [f64]>,
    ) -> Result<()> {
        let (p, dim) = (self.degree, self.dim);
        check_vjp_buffers(
            (ts.len(), dim, self.control.len()),
            cotangent,
            control_cotangent.as_deref_mut(),
            parameter_cotangent.as_deref(),
        )?;
        check_finite("cotangent", cotangent)?;
        let mut basis = PointBasis::new(p);
        let mut slope = vec![0.0; dim];
        for (i, (&t, g)) in ts.iter().zip(cotangent.chunks_exact(dim)).enumerate() {
            let first = basis.at(self.knots, p, self.locate(t)?, t);
            let gt = parameter_cotangent.as_deref_mut().map(|gt| &mut gt[i]);
            let gp = control_cotangent.as_deref_mut();
            vjp_point(self.control, dim, first, &basis, g, gp, gt, &mut slope);
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::BorrowedCurve;
    use crate::curve::BSplineCurve;
    use crate::error::Error;
    use crate::oracle::proptest_config;
    use crate::points::Points;
    use proptest::prelude::*;

    /// A curve of degree `p` with `n` control points in `dim`, interior knots of multiplicity
    /// up to `p` from `gaps` (a zero gap repeats a knot).
    fn sample(p: usize, n: usize, dim: usize, gaps: &[f64], seed: f64) -> (Vec<f64>, Vec<f64>) {
        let mut knots = vec![0.0; p + 1];
        let mut x = 0.0;
        for j in 0..n - p - 1 {
            let run = knots.iter().rev().take_while(|&&k| k == x).count();
            let g = gaps[j % gaps.len()];
            x += if g == 0.0 && run >= p { 0.5 } else { g };
            knots.push(x);
        }
        x += 1.0;
        knots.extend(vec![x; p + 1]);
        #[allow(clippy::cast_precision_loss)]
        let control = (0..n * dim)
            .map(|i| (i as f64 * 0.7 + seed).sin() * 3.0)
            .collect();
        (knots, control)
    }

    proptest! {
        #![proptest_config(proptest_config(128))]

        /// Values, JVP and VJP are bit-for-bit the built curve's, at any parameters of the
        /// domain, for knots with repeated interior values.
        #[test]
        fn matches_the_built_curve(
            p in 0usize..5,
            extra in 1usize..12,
            dim in 1usize..4,
            gaps in prop::collection::vec(prop_oneof![Just(0.0), 0.1f64..2.0], 1..6),
            fractions in prop::collection::vec(0.0f64..=1.0, 1..6),
            seed in -3.0f64..3.0,
        ) {
            let n = p + extra;
            let (knots, control) = sample(p, n, dim, &gaps, seed);
            let curve = BSplineCurve::new(
                p, knots.clone(), Points::from_flat(dim, control.clone()).unwrap(),
            ).unwrap();
            let view = BorrowedCurve::new(p, &knots, &control, dim).unwrap();
            let (lo, hi) = (knots[p], knots[n]);
            let mut ts: Vec<f64> = fractions.iter().map(|f| lo + f * (hi - lo)).collect();
            ts.extend([lo, hi, knots[(p + n) / 2]]);
            let m = ts.len();
            let (mut a, mut b) = (vec![0.0; m * dim], vec![0.0; m * dim]);
            view.eval_batch(&ts, &mut a).unwrap();
            curve.eval_batch(&ts, &mut b).unwrap();
            prop_assert_eq!(&a, &b);
            let dc: Vec<f64> = control.iter().map(|x| x.cos()).collect();
            let dt: Vec<f64> = ts.iter().map(|x| 1.0 + x).collect();
            let (mut ta, mut tb) = (vec![0.0; m * dim], vec![0.0; m * dim]);
            view.eval_batch_jvp(&ts, Some(&dc), Some(&dt), &mut ta).unwrap();
            curve.eval_batch_jvp(&ts, Some(&dc), Some(&dt), &mut b, &mut tb).unwrap();
            prop_assert_eq!(&ta, &tb);
            let g: Vec<f64> = ta.iter().map(|x| x.sin() - 0.25).collect();
            let (mut ca, mut cb) = (vec![1.0; n * dim], vec![2.0; n * dim]);
            let (mut pa, mut pb) = (vec![0.0; m], vec![0.0; m]);
            view.eval_batch_vjp(&ts, &g, Some(&mut ca), Some(&mut pa)).unwrap();
            curve.eval_batch_vjp(&ts, &g, Some(&mut cb), Some(&mut pb)).unwrap();
            prop_assert_eq!(&ca, &cb);
            prop_assert_eq!(&pa, &pb);
        }
    }

    /// Every bad input gives the built curve's error (or the domain error), never a value.
    #[test]
    fn bad_input_gives_the_curve_error() {
        let (knots, control) = sample(3, 12, 2, &[1.0], 0.3);
        // as messages: NaN in an error is not equal to itself
        let built = |k: &[f64], c: &[f64]| {
            Points::from_flat(2, c.to_vec())
                .and_then(|c| BSplineCurve::new(3, k.to_vec(), c))
                .unwrap_err()
                .to_string()
        };
        let eval = |k: &[f64], c: &[f64], t: f64| {
            let mut out = [0.0; 2];
            BorrowedCurve::new(3, k, c, 2)
                .and_then(|c| c.eval_batch(&[t], &mut out))
                .map_err(|e| e.to_string())
        };
        // a NaN knot, an unsorted knot and a NaN control point in the span of t = 4.5
        let mut k = knots.clone();
        k[6] = f64::NAN;
        assert_eq!(eval(&k, &control, 4.5).unwrap_err(), built(&k, &control));
        let mut k = knots.clone();
        k[7] = 100.0;
        assert_eq!(eval(&k, &control, 4.5).unwrap_err(), built(&k, &control));
        let mut c = control.clone();
        c[9] = f64::INFINITY;
        assert_eq!(eval(&knots, &c, 4.5).unwrap_err(), built(&knots, &c));
        // knots out of order elsewhere send the search astray: still the curve's error
        let mut k = knots.clone();
        k.swap(4, 10);
        for t in [0.5, 2.5, 4.5, 6.5] {
            match eval(&k, &control, t) {
                Ok(()) => {} // the span of t is intact: the value is the local polynomial's
                Err(e) => assert_eq!(e, built(&k, &control), "t = {t}"),
            }
        }
        // outside the domain, NaN, empty domain
        let outside = |t: f64| {
            let mut out = [0.0; 2];
            BorrowedCurve::new(3, &knots, &control, 2)
                .and_then(|c| c.eval_batch(&[t], &mut out))
                .unwrap_err()
        };
        assert!(matches!(outside(9.5), Error::ParameterOutOfDomain { .. }));
        assert!(matches!(
            outside(f64::NAN),
            Error::ParameterOutOfDomain { .. }
        ));
        let flat = vec![1.0; knots.len()];
        assert_eq!(
            eval(&flat, &control, 1.0).unwrap_err(),
            built(&flat, &control)
        );
        // counts
        assert!(BorrowedCurve::new(3, &knots[1..], &control, 2).is_err());
        assert!(BorrowedCurve::new(3, &knots, &control[1..], 2).is_err());
        assert!(BorrowedCurve::new(3, &knots, &control, 0).is_err());
        assert!(BorrowedCurve::new(12, &knots, &control, 2).is_err());
    }
}
