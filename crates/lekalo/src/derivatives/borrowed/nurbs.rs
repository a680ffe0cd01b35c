//! NURBS curve evaluation `C(t) = Σ_j N_{j,p}(t) w_j P_j / Σ_j N_{j,p}(t) w_j`, its JVP and its
//! VJP with respect to the control points, the weights and the parameters, on borrowed knots,
//! Euclidean control points and weights, for a few parameters (`docs/theory/derivatives.md`,
//! "NURBS curves").
//!
//! Each parameter reads its span's `2p + 2` knots, `p + 1` control points and `p + 1` weights,
//! checks exactly those (the knots as [`super::BorrowedCurve`] does, the points finite, the
//! weights finite and positive), and forms the span's homogeneous points `(w_j P_j, w_j)` as
//! [`NurbsCurve::new`] forms them (`w_j · x` a coordinate), into a scratch window. The sums are
//! then those of the built curve, by the same code (`derivatives/nurbs.rs`'s `Rational`,
//! `jvp_point` and `vjp_point`), so the values, JVP and VJP are bit-for-bit
//! [`NurbsCurve::eval_batch`]'s, [`NurbsCurve::eval_batch_jvp`]'s and
//! [`NurbsCurve::eval_batch_vjp`]'s. A failed check gives the error [`NurbsCurve::new`] gives
//! for the whole input (built then, on the error path only), or
//! [`Error::ParameterOutOfDomain`] for a parameter outside the domain of a valid curve.

use super::{invalid_span, locate_span, window_counts};
use crate::curve::NurbsCurve;
use crate::derivatives::checks::{check_input, check_len, check_output, zeroed_output};
use crate::derivatives::curve::PointBasis;
use crate::derivatives::nurbs::{jvp_point, vjp_point, Rational};
use crate::error::{check_finite, Error, Result};
use crate::points::Points;
use crate::{Arg, What};

/// A NURBS curve of degree `p` on borrowed knots (`n + p + 1`), Euclidean control points
/// (`n × dim`, point-major) and weights (`n`), checked only where read (module docs).
///
/// ```
/// use lekalo::derivatives::BorrowedNurbs;
/// use lekalo::{NurbsCurve, Points};
/// let knots = [0.0, 0.0, 0.0, 1.0, 2.0, 2.0, 2.0];
/// let control = [0.0, 0.0, 1.0, 2.0, 3.0, 2.0, 4.0, 0.0];
/// let weights = [1.0, 0.5, 2.0, 1.0];
/// let view = BorrowedNurbs::new(2, &knots, &control, &weights, 2)?;
/// let curve = NurbsCurve::new(2, knots.to_vec(), Points::from_flat(2, control.to_vec())?, weights.to_vec())?;
/// let (mut a, mut b) = ([0.0; 4], [0.0; 4]);
/// view.eval_batch(&[0.5, 1.75], &mut a)?;
/// curve.eval_batch(&[0.5, 1.75], &mut b)?;
/// assert_eq!(a, b);
/// # Ok::<(), lekalo::Error>(())
/// ```
#[derive(Debug, Clone, Copy)]
pub struct BorrowedNurbs<'a> {
    degree: usize,
    knots: &'a [f64],
    control: &'a [f64],
    weights: &'a [f64],
    dim: usize,
    /// The number of control points `n`.
    n: usize,
}

/// One parameter's scratch: its basis, the homogeneous points of its span and its sums.
struct Scratch {
    basis: PointBasis,
    net: Vec<f64>,
    sums: Rational,
}

impl<'a> BorrowedNurbs<'a> {
    /// The curve of `degree` on `knots`, `control` (`dim` numbers a point) and `weights` (one a
    /// control point), after the O(1) checks of the counts.
    ///
    /// # Errors
    /// [`Error::Dimension`] for `dim = 0`; [`Error::LengthMismatch`] for a partial point, a
    /// wrong number of knots or of weights; [`Error::Degree`] for fewer than `p + 1` control
    /// points.
    pub fn new(
        degree: usize,
        knots: &'a [f64],
        control: &'a [f64],
        weights: &'a [f64],
        dim: usize,
    ) -> Result<Self> {
        let n = window_counts(degree, knots, control, dim)?;
        check_len(
            What::of(Arg::Weights, "weights (one per control point)"),
            n,
            weights.len(),
        )?;
        Ok(BorrowedNurbs {
            degree,
            knots,
            control,
            weights,
            dim,
            n,
        })
    }

    fn scratch(&self) -> Scratch {
        Scratch {
            basis: PointBasis::new(self.degree),
            net: vec![0.0; (self.degree + 1) * (self.dim + 1)],
            sums: Rational::new(self.dim),
        }
    }

    /// Locates `t` (module docs), fills the scratch's basis, homogeneous window and sums (with
    /// `C'` when `with_slope`), and returns the index of the span's first control point.
    fn at(&self, s: &mut Scratch, t: f64, with_slope: bool) -> Result<usize> {
        let (p, dim) = (self.degree, self.dim);
        let i = locate_span(self.knots, p, self.n, t).map_err(|e| self.explain(e))?;
        let first = i - p;
        let points = &self.control[first * dim..(i + 1) * dim];
        let weights = &self.weights[first..=i];
        let valid = points.iter().all(|x| x.is_finite())
            && weights.iter().all(|w| w.is_finite() && *w > 0.0);
        if !valid {
            return Err(self.explain(invalid_span(t)));
        }
        // (w·x, w): the homogeneous points as `homogenize` forms them
        for ((h, pt), &w) in s
            .net
            .chunks_exact_mut(dim + 1)
            .zip(points.chunks_exact(dim))
            .zip(weights)
        {
            for (hc, x) in h.iter_mut().zip(pt) {
                *hc = x * w;
            }
            h[dim] = w;
        }
        s.basis.at(self.knots, p, i, t);
        s.sums.at(&s.net, dim, 0, &s.basis, with_slope);
        Ok(first)
    }

    /// The error of [`NurbsCurve::new`] on the whole input if it has one, else `local`.
    fn explain(&self, local: Error) -> Error {
        let built = Points::from_flat(self.dim, self.control.to_vec()).and_then(|c| {
            NurbsCurve::new(self.degree, self.knots.to_vec(), c, self.weights.to_vec())
        });
        built.err().unwrap_or(local)
    }

    /// `C(t_i)` into `out` (`ts.len() × dim`, point-major), as [`NurbsCurve::eval_batch`].
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
        let mut s = self.scratch();
        for (&t, o) in ts.iter().zip(out.chunks_exact_mut(dim)) {
            self.at(&mut s, t, false)?;
            o.copy_from_slice(&s.sums.value);
        }
        Ok(())
    }

    /// The tangent of [`NurbsCurve::eval_batch_jvp`] into `tangent_out` (`None` tangents are
    /// zero): `Ċ_i = Σ_j R_j Ṗ_j + Σ_j N_j (P_j − C) ẇ_j / W + C' ṫ_i`.
    ///
    /// # Errors
    /// [`Error::LengthMismatch`] for a buffer of the wrong length, [`Error::NonFinite`] for a
    /// non-finite tangent; the errors of the module docs.
    pub fn eval_batch_jvp(
        &self,
        ts: &[f64],
        control_tangent: Option<&[f64]>,
        weight_tangent: Option<&[f64]>,
        parameter_tangent: Option<&[f64]>,
        tangent_out: &mut [f64],
    ) -> Result<()> {
        let dim = self.dim;
        check_len(
            "tangent output buffer (parameters × dimension)",
            ts.len().saturating_mul(dim),
            tangent_out.len(),
        )?;
        check_input(
            "control-point tangent (as the control points)",
            self.control.len(),
            control_tangent,
        )?;
        check_input(
            "weight tangent (one a control point)",
            self.n,
            weight_tangent,
        )?;
        check_input(
            "parameter tangent (one a parameter)",
            ts.len(),
            parameter_tangent,
        )?;
        let mut s = self.scratch();
        for (i, (&t, d)) in ts.iter().zip(tangent_out.chunks_exact_mut(dim)).enumerate() {
            let first = self.at(&mut s, t, parameter_tangent.is_some())?;
            let dt = parameter_tangent.map(|dt| dt[i]);
            let tangents = (control_tangent, weight_tangent, dt);
            jvp_point(&s.net, dim, first, &s.basis, &s.sums, tangents, d);
        }
        Ok(())
    }

    /// `P̄`, `w̄` and `t̄` of [`NurbsCurve::eval_batch_vjp`] for the cotangent `ḡ`
    /// (`ts.len() × dim`), each into its buffer when given (the control-point and weight
    /// buffers zeroed first).
    ///
    /// # Errors
    /// [`Error::LengthMismatch`] for a buffer of the wrong length, [`Error::NonFinite`] for a
    /// non-finite cotangent; the errors of the module docs (the outputs are then unspecified).
    pub fn eval_batch_vjp(
        &self,
        ts: &[f64],
        cotangent: &[f64],
        mut control_cotangent: Option<&mut [f64]>,
        mut weight_cotangent: Option<&mut [f64]>,
        mut parameter_cotangent: Option<&mut [f64]>,
    ) -> Result<()> {
        let dim = self.dim;
        check_len(
            "cotangent (parameters × dimension)",
            ts.len().saturating_mul(dim),
            cotangent.len(),
        )?;
        zeroed_output(
            "control-point cotangent buffer (as the control points)",
            self.control.len(),
            control_cotangent.as_deref_mut(),
        )?;
        zeroed_output(
            "weight cotangent buffer (one a control point)",
            self.n,
            weight_cotangent.as_deref_mut(),
        )?;
        check_output(
            "parameter cotangent buffer (one a parameter)",
            ts.len(),
            parameter_cotangent.as_deref(),
        )?;
        check_finite("cotangent", cotangent)?;
        let mut s = self.scratch();
        for (i, (&t, g)) in ts.iter().zip(cotangent.chunks_exact(dim)).enumerate() {
            let first = self.at(&mut s, t, parameter_cotangent.is_some())?;
            let outs = (
                control_cotangent.as_deref_mut(),
                weight_cotangent.as_deref_mut(),
            );
            vjp_point(&s.net, dim, first, &s.basis, &s.sums, g, outs);
            if let Some(gt) = parameter_cotangent.as_deref_mut() {
                gt[i] = s.sums.slope.iter().zip(g).map(|(s, gi)| s * gi).sum();
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::BorrowedNurbs;
    use crate::curve::NurbsCurve;
    use crate::error::Error;
    use crate::oracle::proptest_config;
    use crate::points::Points;
    use proptest::prelude::*;

    /// Knots of degree `p` with `n` control points, interior knots of multiplicity up to `p`
    /// from `gaps` (a zero gap repeats a knot), control points and weights from `seed`.
    fn sample(
        p: usize,
        n: usize,
        dim: usize,
        gaps: &[f64],
        seed: f64,
    ) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
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
        #[allow(clippy::cast_precision_loss)]
        let weights = (0..n)
            .map(|i| 0.3 + (i as f64 * 1.3 + seed).cos().abs() * 2.0)
            .collect();
        (knots, control, weights)
    }

    fn built(p: usize, k: &[f64], c: &[f64], w: &[f64], dim: usize) -> Result<NurbsCurve, Error> {
        Points::from_flat(dim, c.to_vec())
            .and_then(|c| NurbsCurve::new(p, k.to_vec(), c, w.to_vec()))
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
            let (knots, control, weights) = sample(p, n, dim, &gaps, seed);
            let curve = built(p, &knots, &control, &weights, dim).unwrap();
            let view = BorrowedNurbs::new(p, &knots, &control, &weights, dim).unwrap();
            let (lo, hi) = (knots[p], knots[n]);
            let mut ts: Vec<f64> = fractions.iter().map(|f| lo + f * (hi - lo)).collect();
            ts.extend([lo, hi, knots[(p + n) / 2]]);
            let m = ts.len();
            let (mut a, mut b) = (vec![0.0; m * dim], vec![0.0; m * dim]);
            view.eval_batch(&ts, &mut a).unwrap();
            curve.eval_batch(&ts, &mut b).unwrap();
            prop_assert_eq!(&a, &b);
            let dc: Vec<f64> = control.iter().map(|x| x.cos()).collect();
            let dw: Vec<f64> = weights.iter().map(|x| x.sin()).collect();
            let dt: Vec<f64> = ts.iter().map(|x| 1.0 + x).collect();
            let (mut ta, mut tb) = (vec![0.0; m * dim], vec![0.0; m * dim]);
            view.eval_batch_jvp(&ts, Some(&dc), Some(&dw), Some(&dt), &mut ta).unwrap();
            curve.eval_batch_jvp(&ts, Some(&dc), Some(&dw), Some(&dt), &mut b, &mut tb).unwrap();
            prop_assert_eq!(&ta, &tb);
            view.eval_batch_jvp(&ts, None, Some(&dw), None, &mut ta).unwrap();
            curve.eval_batch_jvp(&ts, None, Some(&dw), None, &mut b, &mut tb).unwrap();
            prop_assert_eq!(&ta, &tb);
            let g: Vec<f64> = ta.iter().map(|x| x.sin() - 0.25).collect();
            let (mut ca, mut cb) = (vec![1.0; n * dim], vec![2.0; n * dim]);
            let (mut wa, mut wb) = (vec![1.0; n], vec![2.0; n]);
            let (mut pa, mut pb) = (vec![0.0; m], vec![0.0; m]);
            view.eval_batch_vjp(&ts, &g, Some(&mut ca), Some(&mut wa), Some(&mut pa)).unwrap();
            curve.eval_batch_vjp(&ts, &g, Some(&mut cb), Some(&mut wb), Some(&mut pb)).unwrap();
            prop_assert_eq!(&ca, &cb);
            prop_assert_eq!(&wa, &wb);
            prop_assert_eq!(&pa, &pb);
        }
    }

    /// Every bad input gives the built curve's error (or the domain error), never a value.
    #[test]
    fn bad_input_gives_the_curve_error() {
        let (knots, control, weights) = sample(3, 12, 2, &[1.0], 0.3);
        let message =
            |k: &[f64], c: &[f64], w: &[f64]| built(3, k, c, w, 2).unwrap_err().to_string();
        let eval = |k: &[f64], c: &[f64], w: &[f64], t: f64| {
            let mut out = [0.0; 2];
            BorrowedNurbs::new(3, k, c, w, 2)
                .and_then(|c| c.eval_batch(&[t], &mut out))
                .map_err(|e| e.to_string())
        };
        // a NaN knot, a NaN control point, a zero and a NaN weight in the span of t = 4.5
        let mut k = knots.clone();
        k[6] = f64::NAN;
        assert_eq!(
            eval(&k, &control, &weights, 4.5).unwrap_err(),
            message(&k, &control, &weights)
        );
        let mut c = control.clone();
        c[9] = f64::NAN;
        assert_eq!(
            eval(&knots, &c, &weights, 4.5).unwrap_err(),
            message(&knots, &c, &weights)
        );
        for bad in [0.0, -1.0, f64::NAN] {
            let mut w = weights.clone();
            w[4] = bad;
            assert_eq!(
                eval(&knots, &control, &w, 4.5).unwrap_err(),
                message(&knots, &control, &w)
            );
            // the JVP and VJP read the same window: the same error
            let view = BorrowedNurbs::new(3, &knots, &control, &w, 2).unwrap();
            let mut d = [0.0; 2];
            let e = view
                .eval_batch_jvp(&[4.5], None, None, None, &mut d)
                .unwrap_err();
            assert_eq!(e.to_string(), message(&knots, &control, &w));
            let e = view
                .eval_batch_vjp(&[4.5], &[1.0, 1.0], None, None, None)
                .unwrap_err();
            assert_eq!(e.to_string(), message(&knots, &control, &w));
        }
        // a bad weight outside the span used is not read
        let mut w = weights.clone();
        w[11] = -1.0;
        assert!(eval(&knots, &control, &w, 0.5).is_ok());
        let view = BorrowedNurbs::new(3, &knots, &control, &weights, 2).unwrap();
        let mut out = [0.0; 2];
        let e = view.eval_batch(&[99.0], &mut out).unwrap_err();
        assert!(matches!(e, Error::ParameterOutOfDomain { .. }), "{e:?}");
        assert!(BorrowedNurbs::new(3, &knots, &control, &weights[1..], 2).is_err());
        assert!(BorrowedNurbs::new(3, &knots, &control, &weights, 0).is_err());
    }
}
