//! JVP, VJP and linearisation of the batch evaluation of an `N`-variate tensor-product B-spline
//! `S(x) = Σ_{k_0 … k_{N−1}} Π_a N_{k_a, p_a}(x_a) P_{k_0 … k_{N−1}}` with respect to the control
//! net and the points `x` (`docs/theory/derivatives.md#tensor-product-splines`).
//!
//! The values and the partial derivatives `∂S/∂x_a` are those of
//! [`TensorBSpline::eval_batch`] (with the derivative orders `e_a`), so the values are its bits;
//! the net's Jacobian is the product of the `N` basis vectors, non-zero on a
//! `Π_a (p_a + 1)` block of the net, walked by an odometer.

use super::checks::{check_cotangent, check_input, check_len, check_scalars};
use crate::basis::{basis_funs_into, BasisScratch};
use crate::error::Result;
use crate::tensor::TensorBSpline;

/// The linearisation of a tensor spline's batch evaluation at `m` points, what
/// [`TensorBSpline::eval_batch_linearize`] returns: with `N` directions of degrees `p_a`,
/// `S(x_r) = Σ_k Π_a basis[r][off_a + k_a] · P[first[r·N + a] + k_a …]`, `off_a = Σ_{b<a}
/// (p_b + 1)`.
#[derive(Debug, Clone, PartialEq)]
pub struct TensorLinearization {
    /// `S(x_r)`, point-major (`m × dim`): bit-for-bit [`TensorBSpline::eval_batch`].
    pub values: Vec<f64>,
    /// `∂S/∂x_a (x_r)`, `m × N × dim` (right-hand at interior knots): bit-for-bit
    /// [`TensorBSpline::eval_batch`] with the orders `e_a`.
    pub partials: Vec<f64>,
    /// Per point and direction, the first net index with a non-zero basis function
    /// (`span_a − p_a`), `m × N`.
    pub first: Vec<usize>,
    /// Per point, the `p_a + 1` non-zero basis functions of every direction one after the
    /// other, `m × Σ_a (p_a + 1)`.
    pub basis: Vec<f64>,
}

/// Per point: the spans' first indices and the basis vectors of every direction.
pub(super) struct PointBases {
    scratch: Vec<BasisScratch>,
    offsets: Vec<usize>,
    values: Vec<f64>,
    pub(super) first: Vec<usize>,
    /// The multi-index of the odometer over the `Π_a (p_a + 1)` block.
    odometer: Vec<usize>,
}

impl PointBases {
    pub(super) fn new(s: &TensorBSpline) -> Self {
        let mut offsets = Vec::with_capacity(s.n_vars());
        let mut total = 0;
        for &p in s.degrees() {
            offsets.push(total);
            total += p + 1;
        }
        PointBases {
            scratch: s.degrees().iter().map(|&p| BasisScratch::new(p)).collect(),
            offsets,
            values: vec![0.0; total],
            first: vec![0; s.n_vars()],
            odometer: vec![0; s.n_vars()],
        }
    }

    /// Spans and basis vectors at `x` (P&T A2.2 per direction).
    pub(super) fn at(&mut self, s: &TensorBSpline, x: &[f64]) -> Result<()> {
        for (a, (&p, kv)) in s.degrees().iter().zip(s.knots()).enumerate() {
            let span = kv.find_span(p, x[a])?;
            let out = &mut self.values[self.offsets[a]..self.offsets[a] + p + 1];
            basis_funs_into(kv.as_slice(), p, span, x[a], &mut self.scratch[a], out);
            self.first[a] = span - p;
        }
        Ok(())
    }

    /// Calls `f(offset, weight)` for every net point of the block at the current point:
    /// `offset` its first number in the flat net, `weight = Π_a N_{k_a}(x_a)`.
    pub(super) fn for_each_cell(&mut self, s: &TensorBSpline, mut f: impl FnMut(usize, f64)) {
        let n = s.n_vars();
        let degrees = s.degrees();
        self.odometer.fill(0);
        loop {
            let mut offset = 0;
            let mut weight = 1.0;
            for a in 0..n {
                let k = self.odometer[a];
                offset += (self.first[a] + k) * s.stride(a);
                weight *= self.values[self.offsets[a] + k];
            }
            f(offset, weight);
            // advance the last direction fastest
            let mut a = n;
            loop {
                if a == 0 {
                    return;
                }
                a -= 1;
                self.odometer[a] += 1;
                if self.odometer[a] <= degrees[a] {
                    break;
                }
                self.odometer[a] = 0;
            }
        }
    }
}

impl TensorBSpline {
    /// The partial derivatives `∂S/∂x_a` at every point of `xs`, `m × N × dim`.
    pub(super) fn batch_partials(&self, xs: &[f64], m: usize) -> Result<Vec<f64>> {
        let (n, dim) = (self.n_vars(), self.dim());
        let total = check_scalars("partial derivatives (points × directions)", m, n * dim)?;
        let mut partials = vec![0.0; total];
        let mut one = vec![0.0; m * dim];
        let mut orders = vec![0; n];
        for a in 0..n {
            orders.fill(0);
            orders[a] = 1;
            self.eval_batch(xs, Some(&orders), &mut one)?;
            for (r, v) in one.chunks_exact(dim).enumerate() {
                partials[(r * n + a) * dim..(r * n + a + 1) * dim].copy_from_slice(v);
            }
        }
        Ok(partials)
    }

    /// Forward-mode derivative (JVP) of [`TensorBSpline::eval_batch`] at the points `xs` (`N`
    /// coordinates a point, flat): `out` receives `S(x_r)` (bit-for-bit `eval_batch`) and
    /// `tangent_out`
    ///
    /// `Ṡ_r = Σ_k Π_a N_{k_a,p_a}(x_{r,a}) Ṗ_k + Σ_a ∂S/∂x_a(x_r) ẋ_{r,a}`
    ///
    /// for a net tangent `Ṗ` (`control_tangent`, laid out as the net; `None` is zero) and point
    /// tangents `ẋ` (`point_tangent`, laid out as `xs`; `None` is zero). The partial derivatives
    /// are `eval_batch` with the orders `e_a` (P&T A2.3 in direction `a`); each point touches
    /// `Π_a (p_a + 1)` control points. `O(m·N·Π_a(p_a + 1)·dim)`.
    ///
    /// ```
    /// use lekalo::{Points, TensorBSpline};
    /// // f(x, y, z) = x·y·z, trilinear
    /// let k = vec![0.0, 0.0, 1.0, 1.0];
    /// let net = vec![0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0];
    /// let s = TensorBSpline::new(vec![1, 1, 1], vec![k.clone(), k.clone(), k], Points::from_flat(1, net)?)?;
    /// let (mut out, mut tan) = ([0.0], [0.0]);
    /// // d/dε f((0.5, 0.5, 0.5) + ε (1, 0, 0)) = y·z
    /// s.eval_batch_jvp(&[0.5, 0.5, 0.5], None, Some(&[1.0, 0.0, 0.0]), &mut out, &mut tan)?;
    /// assert_eq!((out[0], tan[0]), (0.125, 0.25));
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`crate::Error::LengthMismatch`] for a buffer of the wrong length (or `xs` not a
    /// multiple of `N`); [`crate::Error::NonFinite`] for a non-finite tangent;
    /// [`crate::Error::ParameterOutOfDomain`] at the first point outside the domain.
    pub fn eval_batch_jvp(
        &self,
        xs: &[f64],
        control_tangent: Option<&[f64]>,
        point_tangent: Option<&[f64]>,
        out: &mut [f64],
        tangent_out: &mut [f64],
    ) -> Result<()> {
        let (n, dim) = (self.n_vars(), self.dim());
        let m = self.points_in(xs)?;
        let len = m.saturating_mul(dim);
        check_len("output buffer (points × dimension)", len, out.len())?;
        check_len(
            "tangent buffer (points × dimension)",
            len,
            tangent_out.len(),
        )?;
        let net_len = self.control_points().as_slice().len();
        check_input(
            "control-net tangent (as the control net)",
            net_len,
            control_tangent,
        )?;
        check_input("point tangent (as the points)", xs.len(), point_tangent)?;
        self.eval_batch(xs, None, out)?;
        tangent_out.fill(0.0);
        if let Some(dp) = control_tangent {
            let mut b = PointBases::new(self);
            for (x, t) in xs.chunks_exact(n).zip(tangent_out.chunks_exact_mut(dim)) {
                b.at(self, x)?;
                b.for_each_cell(self, |o, w| {
                    for (ti, pi) in t.iter_mut().zip(&dp[o..o + dim]) {
                        *ti += w * pi;
                    }
                });
            }
        }
        if let Some(dx) = point_tangent {
            let partials = self.batch_partials(xs, m)?;
            for (r, t) in tangent_out.chunks_exact_mut(dim).enumerate() {
                for a in 0..n {
                    let d = &partials[(r * n + a) * dim..(r * n + a + 1) * dim];
                    for (ti, di) in t.iter_mut().zip(d) {
                        *ti += di * dx[r * n + a];
                    }
                }
            }
        }
        Ok(())
    }

    /// Reverse-mode derivative (VJP) of [`TensorBSpline::eval_batch`]: for a cotangent `ḡ` of
    /// the values (`m × dim`), `control_cotangent` (when given, laid out as the net) receives
    /// `P̄_k = Σ_r Π_a N_{k_a,p_a}(x_{r,a}) ḡ_r` (a scatter of `Π_a (p_a + 1)` terms a point)
    /// and `point_cotangent` (when given, laid out as `xs`) `x̄_{r,a} = ḡ_r · ∂S/∂x_a(x_r)`:
    /// the transpose of [`TensorBSpline::eval_batch_jvp`].
    ///
    /// # Errors
    /// As [`TensorBSpline::eval_batch_jvp`]; [`crate::Error::NonFinite`] for a non-finite
    /// cotangent.
    pub fn eval_batch_vjp(
        &self,
        xs: &[f64],
        cotangent: &[f64],
        control_cotangent: Option<&mut [f64]>,
        point_cotangent: Option<&mut [f64]>,
    ) -> Result<()> {
        let (n, dim) = (self.n_vars(), self.dim());
        let m = self.points_in(xs)?;
        check_cotangent("cotangent (points × dimension)", m, dim, cotangent)?;
        if let Some(gp) = control_cotangent {
            check_len(
                "control-net cotangent buffer (as the control net)",
                self.control_points().as_slice().len(),
                gp.len(),
            )?;
            gp.fill(0.0);
            let mut b = PointBases::new(self);
            for (x, g) in xs.chunks_exact(n).zip(cotangent.chunks_exact(dim)) {
                b.at(self, x)?;
                b.for_each_cell(self, |o, w| {
                    for (pi, gi) in gp[o..o + dim].iter_mut().zip(g) {
                        *pi += w * gi;
                    }
                });
            }
        }
        if let Some(gx) = point_cotangent {
            check_len("point cotangent buffer (as the points)", xs.len(), gx.len())?;
            let partials = self.batch_partials(xs, m)?;
            for (r, g) in cotangent.chunks_exact(dim).enumerate() {
                for a in 0..n {
                    let d = &partials[(r * n + a) * dim..(r * n + a + 1) * dim];
                    gx[r * n + a] = d.iter().zip(g).map(|(x, y)| x * y).sum();
                }
            }
        }
        Ok(())
    }

    /// The linearisation of [`TensorBSpline::eval_batch`] at `xs`: values and partial
    /// derivatives (bit-for-bit `eval_batch`), the first net index and the basis vector of
    /// every direction at every point, as a [`TensorLinearization`]: the sparse Jacobian,
    /// from which a framework builds its own gather (JVP) and scatter (VJP).
    ///
    /// # Errors
    /// [`crate::Error::LengthMismatch`] if `xs.len()` is not a multiple of `N`;
    /// [`crate::Error::TooLarge`] if the arrays would exceed [`crate::MAX_SCALARS`];
    /// [`crate::Error::ParameterOutOfDomain`] at the first point outside the domain.
    pub fn eval_batch_linearize(&self, xs: &[f64]) -> Result<TensorLinearization> {
        let (n, dim) = (self.n_vars(), self.dim());
        let m = self.points_in(xs)?;
        let width: usize = self.degrees().iter().map(|p| p + 1).sum();
        let mut values = vec![0.0; check_scalars("values (points × dimension)", m, dim)?];
        check_scalars("basis (points × Σ (degree + 1))", m, width)?;
        self.eval_batch(xs, None, &mut values)?;
        let partials = self.batch_partials(xs, m)?;
        let mut first = Vec::with_capacity(m * n);
        let mut basis = Vec::with_capacity(m * width);
        let mut b = PointBases::new(self);
        for x in xs.chunks_exact(n) {
            b.at(self, x)?;
            first.extend_from_slice(&b.first);
            basis.extend_from_slice(&b.values);
        }
        Ok(TensorLinearization {
            values,
            partials,
            first,
            basis,
        })
    }

    /// The number of points in `xs` (`N` coordinates each).
    pub(super) fn points_in(&self, xs: &[f64]) -> Result<usize> {
        let n = self.n_vars();
        check_len(
            "points (a multiple of the number of directions)",
            xs.len().div_ceil(n) * n,
            xs.len(),
        )?;
        Ok(xs.len() / n)
    }
}

#[cfg(test)]
mod tests {
    use crate::error::Error;
    use crate::oracle::proptest_config;
    use crate::points::Points;
    use crate::tensor::TensorBSpline;
    use proptest::prelude::*;

    /// A spline of `degrees` with interior knots at thirds, clamped on `[0, 1]`, and a net from
    /// `seed`.
    fn spline(degrees: &[usize], dim: usize, seed: &[f64]) -> TensorBSpline {
        let knots: Vec<Vec<f64>> = degrees
            .iter()
            .map(|&p| [vec![0.0; p + 1], vec![0.3, 0.7], vec![1.0; p + 1]].concat())
            .collect();
        let size: usize = degrees.iter().map(|p| p + 3).product::<usize>() * dim;
        let net = seed
            .iter()
            .cycle()
            .take(size)
            .enumerate()
            .map(|(i, v)| v + (i % 7) as f64 * 0.1)
            .collect();
        TensorBSpline::new(
            degrees.to_vec(),
            knots,
            Points::from_flat(dim, net).unwrap(),
        )
        .unwrap()
    }

    proptest! {
        #![proptest_config(proptest_config(48))]

        /// The JVP matches central differences (exact in the net, `h²` in the points, away
        /// from the knots), the values are `eval_batch`'s bits, the VJP is the transpose and
        /// the linearisation rebuilds both.
        #[test]
        fn jvp_matches_differences_and_vjp_is_its_transpose(
            degrees in prop::collection::vec(1usize..=3, 1..=4),
            dim in 1usize..=2,
            seed in prop::collection::vec(-1.0f64..1.0, 64),
            pts in prop::collection::vec(0.02f64..0.27, 12),
        ) {
            let s = spline(&degrees, dim, &seed);
            let n = degrees.len();
            // coordinates in [0.02, 0.27] + {0, 0.35, 0.72}: at least 0.02 from every knot
            let xs: Vec<f64> = pts.iter().take(3 * n).enumerate()
                .map(|(i, v)| v + [0.0, 0.35, 0.72][i % 3]).collect();
            let m = xs.len() / n;
            let net = s.control_points().as_slice().to_vec();
            let dp: Vec<f64> = net.iter().enumerate().map(|(i, _)| ((i * 37 % 11) as f64 - 5.0) / 5.0).collect();
            let dx: Vec<f64> = (0..xs.len()).map(|i| ((i * 13 % 7) as f64 - 3.0) / 3.0).collect();
            let (mut out, mut tan) = (vec![0.0; m * dim], vec![0.0; m * dim]);
            s.eval_batch_jvp(&xs, Some(&dp), Some(&dx), &mut out, &mut tan).unwrap();
            let mut plain = vec![0.0; m * dim];
            s.eval_batch(&xs, None, &mut plain).unwrap();
            prop_assert!(out.iter().zip(&plain).all(|(a, b)| a.to_bits() == b.to_bits()));
            let h = 1e-6;
            let at = |e: f64| {
                let net: Vec<f64> = net.iter().zip(&dp).map(|(a, b)| a + e * b).collect();
                let x: Vec<f64> = xs.iter().zip(&dx).map(|(a, b)| a + e * b).collect();
                let t = TensorBSpline::new(degrees.clone(), s.knots().iter().map(|k| k.as_slice().to_vec()).collect(), Points::from_flat(dim, net).unwrap()).unwrap();
                let mut o = vec![0.0; m * dim];
                t.eval_batch(&x, None, &mut o).unwrap();
                o
            };
            let (plus, minus) = (at(h), at(-h));
            for (i, t) in tan.iter().enumerate() {
                let fd = (plus[i] - minus[i]) / (2.0 * h);
                prop_assert!((fd - t).abs() <= 1e-7 * t.abs().max(1.0), "{}: {} against {}", i, t, fd);
            }
            let g: Vec<f64> = (0..m * dim).map(|i| ((i * 5 % 9) as f64 - 4.0) / 4.0).collect();
            let (mut gp, mut gx) = (vec![0.0; net.len()], vec![0.0; xs.len()]);
            s.eval_batch_vjp(&xs, &g, Some(&mut gp), Some(&mut gx)).unwrap();
            let lhs: f64 = g.iter().zip(&tan).map(|(a, b)| a * b).sum();
            let rhs: f64 = gp.iter().zip(&dp).chain(gx.iter().zip(&dx)).map(|(a, b)| a * b).sum();
            prop_assert!((lhs - rhs).abs() <= 1e-12 * lhs.abs().max(1.0), "{} against {}", lhs, rhs);
            let lin = s.eval_batch_linearize(&xs).unwrap();
            prop_assert_eq!(&lin.values, &plain);
            prop_assert_eq!(lin.first.len(), m * n);
            prop_assert_eq!(lin.partials.len(), m * n * dim);
        }
    }

    #[test]
    fn errors_name_the_argument() {
        let s = spline(&[1, 2], 1, &[0.5, -0.25]);
        let (mut out, mut tan) = ([0.0], [0.0]);
        let e = s
            .eval_batch_jvp(&[0.5, 0.5, 0.5], None, None, &mut out, &mut tan)
            .unwrap_err();
        assert!(matches!(e, Error::LengthMismatch { .. }), "{e:?}");
        let e = s
            .eval_batch_jvp(&[0.5, 1.5], None, None, &mut out, &mut tan)
            .unwrap_err();
        assert!(matches!(e, Error::ParameterOutOfDomain { .. }), "{e:?}");
        let e = s
            .eval_batch_jvp(
                &[0.5, 0.5],
                None,
                Some(&[f64::NAN, 0.0]),
                &mut out,
                &mut tan,
            )
            .unwrap_err();
        assert!(matches!(e, Error::NonFinite { .. }), "{e:?}");
        let e = s
            .eval_batch_vjp(&[0.5, 0.5], &[1.0, 2.0], None, None)
            .unwrap_err();
        assert!(matches!(e, Error::LengthMismatch { .. }), "{e:?}");
        let mut gp = vec![0.0; 3];
        let e = s
            .eval_batch_vjp(&[0.5, 0.5], &[1.0], Some(&mut gp), None)
            .unwrap_err();
        assert!(matches!(e, Error::LengthMismatch { .. }), "{e:?}");
    }
}
