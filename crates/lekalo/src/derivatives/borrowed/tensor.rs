//! Evaluation of a tensor-product B-spline in `N` variables,
//! `S(x) = Σ_k Π_a N_{k_a,p_a}(x_a) P_k`, its JVP and its VJP on borrowed knot vectors and a
//! borrowed net, for a few points: only the numbers the values need are read and checked
//! (`docs/theory/derivatives.md#tensor-product-splines`).
//!
//! Building a [`TensorBSpline`] validates every knot and every point of the net, `Π_a n_a`
//! of them, a call. Here each point `x` reads, in every direction `a`, its span's `2p_a + 2`
//! knots `t_{i_a−p_a} ..= t_{i_a+p_a+1}`, and the `Π_a (p_a + 1)` block of the net at
//! `(i_a − p_a)_a`: the whole definition of the spline on the cell `Π_a [t_{i_a}, t_{i_a+1}]`
//! (P&T A2.2 a direction reads nothing else). Those numbers make the cell's local spline, a
//! [`TensorBSpline`] of one polynomial piece a direction built (and so checked) by
//! [`TensorBSpline::new`], and the point is evaluated on it by the built spline's own kernels
//! ([`TensorBSpline::eval_batch`], [`TensorBSpline::eval_batch_jvp`],
//! [`TensorBSpline::eval_batch_vjp`]): the same basis functions from the same knots, the same
//! contraction in the same order, so the values, JVP and VJP are bit for bit the whole
//! spline's. The net's tangent is read on the block, the net's cotangent is the local one
//! summed into the block. A failed check gives the error [`TensorBSpline::new`] gives for the
//! whole input (built then, on the error path only), or [`Error::ParameterOutOfDomain`] for a
//! point outside the domain of a valid spline.

use super::{add_block, gather_block, invalid_span, locate_span};
use crate::derivatives::checks::{check_cotangent, check_input, check_len};
use crate::error::{Error, Result};
use crate::points::Points;
use crate::tensor::TensorBSpline;

/// A tensor-product B-spline of degrees `p_a` on borrowed knot vectors (`n_a + p_a + 1`
/// each) and a point-major net (`Π_a n_a` points of `dim` numbers, the first direction
/// slowest), checked only where read (module docs).
///
/// ```
/// use lekalo::derivatives::BorrowedTensor;
/// use lekalo::{Points, TensorBSpline};
/// let k = [0.0, 0.0, 0.0, 1.0, 2.0, 2.0, 2.0];
/// let net: Vec<f64> = (0..16).map(|i| f64::from(i).sin()).collect();
/// let view = BorrowedTensor::new(&[2, 2], vec![&k, &k], &net, 1)?;
/// let s = TensorBSpline::new(vec![2, 2], vec![k.to_vec(), k.to_vec()], Points::from_flat(1, net.clone())?)?;
/// let (mut a, mut b) = ([0.0; 2], [0.0; 2]);
/// view.eval_batch(&[0.5, 1.25, 2.0, 0.0], &mut a)?;
/// s.eval_batch(&[0.5, 1.25, 2.0, 0.0], None, &mut b)?;
/// assert_eq!(a, b);
/// # Ok::<(), lekalo::Error>(())
/// ```
#[derive(Debug, Clone)]
pub struct BorrowedTensor<'a> {
    degrees: &'a [usize],
    knots: Vec<&'a [f64]>,
    control: &'a [f64],
    dim: usize,
    /// `n_a`, the net's size in each direction.
    shape: Vec<usize>,
    /// The numbers of the net between consecutive indices of each direction.
    strides: Vec<usize>,
}

/// The local spline of one point's cell and the corner `(i_a − p_a)_a` of its block.
struct Cell {
    spline: TensorBSpline,
    first: Vec<usize>,
}

impl<'a> BorrowedTensor<'a> {
    /// The spline of `degrees` on `knots` (one vector a direction) and the net `control`
    /// (`dim` numbers a point), after the O(N) checks of the counts: at least one direction,
    /// as many knot vectors as degrees, `dim ≥ 1`, at least `2p_a + 2` knots a direction and
    /// `Π_a (|T_a| − p_a − 1)·dim` numbers in the net.
    ///
    /// # Errors
    /// When a count is wrong, the error [`TensorBSpline::new`] gives for the same input
    /// ([`Error::TooFew`], [`Error::LengthMismatch`], [`Error::Degree`], [`Error::Dimension`],
    /// [`Error::TooLarge`]).
    pub fn new(
        degrees: &'a [usize],
        knots: Vec<&'a [f64]>,
        control: &'a [f64],
        dim: usize,
    ) -> Result<Self> {
        let shape: Option<Vec<usize>> = knots
            .iter()
            .zip(degrees)
            .map(|(k, &p)| {
                let n = k.len().checked_sub(p + 1)?;
                (n > p).then_some(n)
            })
            .collect();
        let size = shape
            .as_ref()
            .and_then(|s| s.iter().try_fold(dim, |acc, &n| acc.checked_mul(n)));
        let mut s = BorrowedTensor {
            degrees,
            knots,
            control,
            dim,
            shape: shape.unwrap_or_default(),
            strides: Vec::new(),
        };
        let counts = !degrees.is_empty()
            && s.knots.len() == degrees.len()
            && dim > 0
            && size == Some(control.len());
        if !counts {
            return Err(s.explain(Error::LengthMismatch {
                what: "control net (product of the net sizes, times the dimension)".into(),
                expected: size.unwrap_or(0),
                got: control.len(),
            }));
        }
        let mut stride = dim;
        s.strides = vec![0; degrees.len()];
        for (a, &n) in s.shape.iter().enumerate().rev() {
            s.strides[a] = stride;
            stride *= n;
        }
        Ok(s)
    }

    /// The error of [`TensorBSpline::new`] on the whole input if it has one, else `local`.
    fn explain(&self, local: Error) -> Error {
        let knots = self.knots.iter().map(|k| k.to_vec()).collect();
        let built = Points::from_flat(self.dim, self.control.to_vec())
            .and_then(|c| TensorBSpline::new(self.degrees.to_vec(), knots, c));
        built.err().unwrap_or(local)
    }

    /// The number of points in `xs` (`N` coordinates each), as [`TensorBSpline`] counts them.
    fn points_in(&self, xs: &[f64]) -> Result<usize> {
        let n = self.degrees.len();
        check_len(
            "points (a multiple of the number of directions)",
            xs.len().div_ceil(n) * n,
            xs.len(),
        )?;
        Ok(xs.len() / n)
    }

    /// The widths `p_a + 1` of a block.
    fn widths(&self) -> Vec<usize> {
        self.degrees.iter().map(|p| p + 1).collect()
    }

    /// The local spline of the cell of `x` (module docs), after locating its span in every
    /// direction and checking the knots and net points they read.
    fn cell(&self, x: &[f64], widths: &[usize]) -> Result<Cell> {
        let mut first = Vec::with_capacity(x.len());
        let mut windows = Vec::with_capacity(x.len());
        for (((&t, k), &p), &n) in x.iter().zip(&self.knots).zip(self.degrees).zip(&self.shape) {
            let i = locate_span(k, p, n, t).map_err(|e| self.explain(e))?;
            first.push(i - p);
            windows.push(k[i - p..=i + p + 1].to_vec());
        }
        let block = gather_block(self.control, self.dim, &first, widths, &self.strides);
        let spline = Points::from_flat(self.dim, block)
            .and_then(|c| TensorBSpline::new(self.degrees.to_vec(), windows, c))
            .map_err(|_| self.explain(invalid_span(x[0])))?;
        Ok(Cell { spline, first })
    }

    /// `S(x_r)` into `out` (`dim` numbers a point), as [`TensorBSpline::eval_batch`].
    ///
    /// # Errors
    /// [`Error::LengthMismatch`] for `xs` not a multiple of `N` or `out`; the errors of the
    /// module docs.
    pub fn eval_batch(&self, xs: &[f64], out: &mut [f64]) -> Result<()> {
        let (n, dim) = (self.degrees.len(), self.dim);
        let m = self.points_in(xs)?;
        check_len("output (points × dim)", m.saturating_mul(dim), out.len())?;
        let widths = self.widths();
        for (x, o) in xs.chunks_exact(n).zip(out.chunks_exact_mut(dim)) {
            self.cell(x, &widths)?.spline.eval_batch(x, None, o)?;
        }
        Ok(())
    }

    /// The tangent of [`TensorBSpline::eval_batch_jvp`] into `tangent_out` (`None` tangents
    /// are zero): `Ṡ_r = Σ_k Π_a N_{k_a,p_a}(x_{r,a}) Ṗ_k + Σ_a ∂S/∂x_a(x_r) ẋ_{r,a}`.
    ///
    /// # Errors
    /// [`Error::LengthMismatch`] for a buffer of the wrong length, [`Error::NonFinite`] for a
    /// non-finite tangent; the errors of the module docs.
    pub fn eval_batch_jvp(
        &self,
        xs: &[f64],
        control_tangent: Option<&[f64]>,
        point_tangent: Option<&[f64]>,
        tangent_out: &mut [f64],
    ) -> Result<()> {
        let (n, dim) = (self.degrees.len(), self.dim);
        let m = self.points_in(xs)?;
        check_len(
            "tangent buffer (points × dimension)",
            m.saturating_mul(dim),
            tangent_out.len(),
        )?;
        check_input(
            "control-net tangent (as the control net)",
            self.control.len(),
            control_tangent,
        )?;
        check_input("point tangent (as the points)", xs.len(), point_tangent)?;
        let widths = self.widths();
        let mut value = vec![0.0; dim];
        let points = xs.chunks_exact(n).zip(tangent_out.chunks_exact_mut(dim));
        for (r, (x, d)) in points.enumerate() {
            let cell = self.cell(x, &widths)?;
            let dp = control_tangent
                .map(|dp| gather_block(dp, dim, &cell.first, &widths, &self.strides));
            let dx = point_tangent.map(|dx| &dx[r * n..(r + 1) * n]);
            cell.spline
                .eval_batch_jvp(x, dp.as_deref(), dx, &mut value, d)?;
        }
        Ok(())
    }

    /// `P̄` and `x̄` of [`TensorBSpline::eval_batch_vjp`] for the cotangent `ḡ` (`m × dim`),
    /// each into its buffer when given (the net's zeroed first).
    ///
    /// # Errors
    /// As [`BorrowedTensor::eval_batch_jvp`]; [`Error::NonFinite`] for a non-finite cotangent
    /// (the outputs are then unspecified).
    pub fn eval_batch_vjp(
        &self,
        xs: &[f64],
        cotangent: &[f64],
        mut control_cotangent: Option<&mut [f64]>,
        mut point_cotangent: Option<&mut [f64]>,
    ) -> Result<()> {
        let (n, dim) = (self.degrees.len(), self.dim);
        let m = self.points_in(xs)?;
        check_cotangent("cotangent (points × dimension)", m, dim, cotangent)?;
        if let Some(gp) = control_cotangent.as_deref_mut() {
            check_len(
                "control-net cotangent buffer (as the control net)",
                self.control.len(),
                gp.len(),
            )?;
            gp.fill(0.0);
        }
        if let Some(gx) = point_cotangent.as_deref() {
            check_len("point cotangent buffer (as the points)", xs.len(), gx.len())?;
        }
        let widths = self.widths();
        let block = widths.iter().product::<usize>() * dim;
        let mut local = vec![
            0.0;
            if control_cotangent.is_some() {
                block
            } else {
                0
            }
        ];
        for (r, (x, g)) in xs
            .chunks_exact(n)
            .zip(cotangent.chunks_exact(dim))
            .enumerate()
        {
            let cell = self.cell(x, &widths)?;
            let wanted = control_cotangent.is_some().then_some(&mut local[..]);
            let gx = point_cotangent
                .as_deref_mut()
                .map(|gx| &mut gx[r * n..(r + 1) * n]);
            cell.spline.eval_batch_vjp(x, g, wanted, gx)?;
            if let Some(gp) = control_cotangent.as_deref_mut() {
                add_block(&local, dim, &cell.first, &widths, &self.strides, gp);
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::super::test_nets::{knots, net};
    use super::BorrowedTensor;
    use crate::error::Error;
    use crate::oracle::proptest_config;
    use crate::points::Points;
    use crate::tensor::TensorBSpline;
    use proptest::prelude::*;

    fn built(degrees: &[usize], knots: &[Vec<f64>], ctrl: &[f64], dim: usize) -> TensorBSpline {
        TensorBSpline::new(
            degrees.to_vec(),
            knots.to_vec(),
            Points::from_flat(dim, ctrl.to_vec()).unwrap(),
        )
        .unwrap()
    }

    proptest! {
        #![proptest_config(proptest_config(64))]

        /// Values, JVP and VJP are bit-for-bit the built spline's, at any points of the
        /// domain, knots and corners included, in 1 to 3 directions (the fixed-size kernels of
        /// one degree and scalar values among them).
        #[test]
        fn matches_the_built_spline(
            shape in prop::collection::vec((0usize..4, 1usize..5), 1..=3),
            same_degree in any::<bool>(),
            dim in 1usize..3,
            gaps in prop::collection::vec(prop_oneof![Just(0.0), 0.1f64..2.0], 1..5),
            fractions in prop::collection::vec(0.0f64..=1.0, 3..10),
            seed in -3.0f64..3.0,
        ) {
            let degrees: Vec<usize> = shape.iter().map(|&(p, _)| if same_degree { shape[0].0 } else { p }).collect();
            let sizes: Vec<usize> = shape.iter().zip(&degrees).map(|(&(_, e), &p)| p + e).collect();
            let n = degrees.len();
            let kv: Vec<Vec<f64>> = degrees.iter().zip(&sizes).map(|(&p, &s)| knots(p, s, &gaps)).collect();
            let ctrl = net(sizes.iter().product::<usize>() * dim, seed);
            let s = built(&degrees, &kv, &ctrl, dim);
            let view = BorrowedTensor::new(&degrees, kv.iter().map(Vec::as_slice).collect(), &ctrl, dim).unwrap();
            let domain = s.domain();
            let mut xs: Vec<f64> = fractions.iter().cycle().take(fractions.len() / n * n + 2 * n)
                .enumerate()
                .map(|(i, f)| { let (lo, hi) = domain[i % n]; lo + f * (hi - lo) }).collect();
            // a corner and a point on interior knots
            xs.extend(domain.iter().map(|d| d.1));
            xs.extend(kv.iter().zip(&degrees).zip(&sizes).map(|((k, p), s)| k[(p + s) / 2]));
            let m = xs.len() / n;
            let (mut a, mut b) = (vec![0.0; m * dim], vec![0.0; m * dim]);
            view.eval_batch(&xs, &mut a).unwrap();
            s.eval_batch(&xs, None, &mut b).unwrap();
            prop_assert_eq!(&a, &b);
            let dc: Vec<f64> = ctrl.iter().map(|x| x.cos()).collect();
            let dx: Vec<f64> = xs.iter().map(|x| 1.0 - x).collect();
            let (mut ta, mut tb) = (vec![0.0; m * dim], vec![0.0; m * dim]);
            view.eval_batch_jvp(&xs, Some(&dc), Some(&dx), &mut ta).unwrap();
            s.eval_batch_jvp(&xs, Some(&dc), Some(&dx), &mut b, &mut tb).unwrap();
            prop_assert_eq!(&ta, &tb);
            let g: Vec<f64> = ta.iter().map(|x| x.sin() - 0.25).collect();
            let (mut ca, mut cb) = (vec![1.0; ctrl.len()], vec![2.0; ctrl.len()]);
            let (mut pa, mut pb) = (vec![0.0; xs.len()], vec![1.0; xs.len()]);
            view.eval_batch_vjp(&xs, &g, Some(&mut ca), Some(&mut pa)).unwrap();
            s.eval_batch_vjp(&xs, &g, Some(&mut cb), Some(&mut pb)).unwrap();
            prop_assert_eq!(&ca, &cb);
            prop_assert_eq!(&pa, &pb);
        }
    }

    /// Every bad input gives the built spline's error (or the domain error), never a value.
    #[test]
    fn bad_input_gives_the_spline_error() {
        let degrees = [2, 3];
        let kv = [knots(2, 7, &[1.0]), knots(3, 8, &[1.0])];
        let ctrl = net(7 * 8, 0.1);
        let message = |k: &[Vec<f64>], c: &[f64]| {
            let knots = k.to_vec();
            Points::from_flat(1, c.to_vec())
                .and_then(|c| TensorBSpline::new(degrees.to_vec(), knots, c))
                .unwrap_err()
                .to_string()
        };
        let eval = |k: &[Vec<f64>], c: &[f64], x: &[f64]| {
            let mut out = vec![0.0; x.len() / 2];
            BorrowedTensor::new(&degrees, k.iter().map(Vec::as_slice).collect(), c, 1)
                .and_then(|s| s.eval_batch(x, &mut out))
                .map(|()| out)
                .map_err(|e| e.to_string())
        };
        // (2.5, 3.5) reads knots 0: 2..=7, knots 1: 3..=10, net rows 2..=4, columns 3..=6
        let at = [2.5, 3.5];
        let mut k = kv.clone();
        k[0][4] = f64::NAN;
        assert_eq!(eval(&k, &ctrl, &at).unwrap_err(), message(&k, &ctrl));
        let mut k = kv.clone();
        k[1][8] = -1.0;
        assert_eq!(eval(&k, &ctrl, &at).unwrap_err(), message(&k, &ctrl));
        let mut c = ctrl.clone();
        c[3 * 8 + 5] = f64::NAN;
        assert_eq!(eval(&kv, &c, &at).unwrap_err(), message(&kv, &c));
        // a bad number outside the block is not read
        let mut far = ctrl.clone();
        far[0] = f64::NAN;
        let s = built(&degrees, &kv, &ctrl, 1);
        assert_eq!(eval(&kv, &far, &at).unwrap(), s.eval(&at).unwrap());
        // outside the domain, NaN, a partial point
        for x in [[9.0, 1.0], [1.0, -1.0], [1.0, f64::NAN]] {
            let e = BorrowedTensor::new(&degrees, kv.iter().map(Vec::as_slice).collect(), &ctrl, 1)
                .and_then(|s| s.eval_batch(&x, &mut [0.0]))
                .unwrap_err();
            assert!(matches!(e, Error::ParameterOutOfDomain { .. }), "{e:?}");
        }
        assert!(eval(&kv, &ctrl, &[1.0, 1.0, 1.0]).is_err());
        // counts: the built spline's errors
        assert_eq!(
            eval(&kv, &ctrl[1..], &at).unwrap_err(),
            message(&kv, &ctrl[1..])
        );
        let short = [kv[0][1..].to_vec(), kv[1].clone()];
        assert_eq!(
            eval(&short, &ctrl, &at).unwrap_err(),
            message(&short, &ctrl)
        );
        let tiny = [vec![0.0, 1.0], kv[1].clone()];
        assert_eq!(eval(&tiny, &ctrl, &at).unwrap_err(), message(&tiny, &ctrl));
    }
}
