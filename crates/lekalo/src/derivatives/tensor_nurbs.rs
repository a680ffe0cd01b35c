//! JVP, VJP and linearisation of the batch evaluation of an `N`-variate tensor-product NURBS
//! `S(x) = A(x) / W(x)`, `A = Σ_k B_k(x) w_k P_k`, `W = Σ_k B_k(x) w_k` with
//! `B_k(x) = Π_a N_{k_a, p_a}(x_a)`, with respect to the (Euclidean) control net `P`, the
//! weights `w` and the points `x` (`docs/theory/derivatives.md`, "NURBS surfaces and N-variate
//! NURBS"):
//!
//! - `∂S/∂P_k = R_k = B_k w_k / W`; `∂S/∂w_k = B_k (P_k − S) / W`;
//! - `∂S/∂x_a = (A_a − W_a S) / W` (P&T eq. 4.20 with one derivative, in direction `a`).
//!
//! The homogeneous values `(A, W)` are [`TensorBSpline::eval_batch`] of the homogeneous spline
//! and their partials `tensor.rs`'s, so the values `A / W` are [`TensorNurbs::eval_batch`]'s
//! bits; the net's terms walk the `Π_a (p_a + 1)` block of each point by `tensor.rs`'s odometer.

use super::checks::{check_cotangent, check_input, check_len, check_scalars};
use super::nurbs::{jvp_cell, vjp_cell};
use super::tensor::PointBases;
use crate::error::Result;
use crate::tensor::{TensorBSpline, TensorNurbs};

/// The linearisation of a tensor NURBS's batch evaluation at `m` points, what
/// [`TensorNurbs::eval_batch_linearize`] returns: with `N` directions of degrees `p_a`,
/// `S(x_r) = Σ_c basis[r·B + c] · P[first[r·N..(r+1)·N] + k(c)]`, `B = Π_a (p_a + 1)`, the
/// cells `c` of the block in the order of the net (the last direction fastest, `k(c)` their
/// multi-indices), and `∂S/∂w_k = R_k (P_k − S) / w_k`.
#[derive(Debug, Clone, PartialEq)]
pub struct TensorNurbsLinearization {
    /// `S(x_r)`, point-major (`m × dim`): bit-for-bit [`TensorNurbs::eval_batch`].
    pub values: Vec<f64>,
    /// `∂S/∂x_a (x_r)`, `m × N × dim` (right-hand at interior knots).
    pub partials: Vec<f64>,
    /// Per point and direction, the first net index with a non-zero basis function
    /// (`span_a − p_a`), `m × N`.
    pub first: Vec<usize>,
    /// Per point, the `Π_a (p_a + 1)` non-zero rational basis functions
    /// `R_k = B_k w_k / W` of its block, `m × Π_a (p_a + 1)`.
    pub basis: Vec<f64>,
}

/// The homogeneous values `(A, W)` at the points (`m × (dim + 1)`), bit-for-bit
/// [`TensorBSpline::eval_batch`], and the rational values `A / W` into `out` (`m × dim`, one
/// division a coordinate as `TensorNurbs::eval_batch` projects).
fn homogeneous_values(
    hom: &TensorBSpline,
    xs: &[f64],
    m: usize,
    out: &mut [f64],
) -> Result<Vec<f64>> {
    let hd = hom.dim();
    let mut h = vec![0.0; check_scalars("homogeneous values (points × (dim + 1))", m, hd)?];
    hom.eval_batch(xs, None, &mut h)?;
    for (o, a) in out.chunks_exact_mut(hd - 1).zip(h.chunks_exact(hd)) {
        for (x, c) in o.iter_mut().zip(a) {
            *x = c / a[hd - 1];
        }
    }
    Ok(h)
}

/// `∂S/∂x_a = (A_a − W_a S) / W` at every point and direction (`m × N × dim`) from the
/// homogeneous partials (`tensor.rs`), `h` the homogeneous values and `values` the rational.
fn rational_partials(
    hom: &TensorBSpline,
    xs: &[f64],
    m: usize,
    h: &[f64],
    values: &[f64],
) -> Result<Vec<f64>> {
    let (n, hd) = (hom.n_vars(), hom.dim());
    let dim = hd - 1;
    let hp = hom.batch_partials(xs, m)?;
    let mut partials = vec![0.0; m * n * dim];
    for (r, (s, a)) in values.chunks_exact(dim).zip(h.chunks_exact(hd)).enumerate() {
        let w = a[dim];
        for d in 0..n {
            let ha = &hp[(r * n + d) * hd..(r * n + d + 1) * hd];
            let out = &mut partials[(r * n + d) * dim..(r * n + d + 1) * dim];
            for ((x, c), si) in out.iter_mut().zip(ha).zip(s) {
                *x = (c - ha[dim] * si) / w;
            }
        }
    }
    Ok(partials)
}

impl TensorNurbs {
    /// Forward-mode derivative (JVP) of [`TensorNurbs::eval_batch`] at the points `xs` (`N`
    /// coordinates a point, flat): `out` receives `S(x_r)` (bit-for-bit `eval_batch`) and
    /// `tangent_out`
    ///
    /// `Ṡ_r = Σ_k R_k(x_r) Ṗ_k + Σ_k B_k(x_r) (P_k − S_r) ẇ_k / W_r + Σ_a ∂S/∂x_a(x_r) ẋ_{r,a}`
    ///
    /// for tangents of the Euclidean net (`control_tangent`, laid out as the net, `dim` numbers
    /// a point), of the weights (`weight_tangent`, one a net point) and of the points
    /// (`point_tangent`, laid out as `xs`); `None` is zero. `R_k = B_k w_k / W` is the rational
    /// basis, `∂S/∂x_a` the quotient rule on the homogeneous partials (P&T eq. 4.20 with one
    /// derivative; `docs/theory/derivatives.md`, "NURBS surfaces and N-variate NURBS"); each
    /// point touches `Π_a (p_a + 1)` control points. `O(m·N·Π_a(p_a + 1)·dim)`.
    ///
    /// ```
    /// use lekalo::{Points, TensorNurbs};
    /// // bilinear f(x, y) = x·y with unit weights; raising w_11 pulls f towards P_11 = 1
    /// let k = vec![0.0, 0.0, 1.0, 1.0];
    /// let net = Points::from_flat(1, vec![0.0, 0.0, 0.0, 1.0])?;
    /// let s = TensorNurbs::new(vec![1, 1], vec![k.clone(), k], net, &[1.0; 4])?;
    /// let (mut out, mut tan) = ([0.0], [0.0]);
    /// s.eval_batch_jvp(&[0.5, 0.5], None, Some(&[0.0, 0.0, 0.0, 1.0]), None, &mut out, &mut tan)?;
    /// // B_11 (P_11 − S) / W = ¼ (1 − ¼)
    /// assert_eq!((out[0], tan[0]), (0.25, 0.1875));
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
        weight_tangent: Option<&[f64]>,
        point_tangent: Option<&[f64]>,
        out: &mut [f64],
        tangent_out: &mut [f64],
    ) -> Result<()> {
        let hom = self.homogeneous();
        let (n, dim, hd) = (self.n_vars(), self.dim(), hom.dim());
        let m = hom.points_in(xs)?;
        let len = m.saturating_mul(dim);
        check_len("output buffer (points × dimension)", len, out.len())?;
        check_len(
            "tangent buffer (points × dimension)",
            len,
            tangent_out.len(),
        )?;
        let h_net = hom.control_points().as_slice();
        let net_points = h_net.len() / hd;
        check_input(
            "control-net tangent (as the control net)",
            net_points * dim,
            control_tangent,
        )?;
        check_input(
            "weight tangent (one a net point)",
            net_points,
            weight_tangent,
        )?;
        check_input("point tangent (as the points)", xs.len(), point_tangent)?;
        let h = homogeneous_values(hom, xs, m, out)?;
        tangent_out.fill(0.0);
        if control_tangent.is_some() || weight_tangent.is_some() {
            let mut b = PointBases::new(hom);
            let points = xs.chunks_exact(n).zip(tangent_out.chunks_exact_mut(dim));
            for (r, (x, t)) in points.enumerate() {
                b.at(hom, x)?;
                let sums = (h[r * hd + dim], &out[r * dim..(r + 1) * dim]);
                b.for_each_cell(hom, |o, nk| {
                    let j = o / hd;
                    let tangents = (
                        control_tangent.map(|dp| &dp[j * dim..(j + 1) * dim]),
                        weight_tangent.map(|dw| dw[j]),
                    );
                    jvp_cell(&h_net[o..o + hd], nk, sums, tangents, t);
                });
            }
        }
        if let Some(dx) = point_tangent {
            let partials = rational_partials(hom, xs, m, &h, out)?;
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

    /// Reverse-mode derivative (VJP) of [`TensorNurbs::eval_batch`]: for a cotangent `ḡ` of
    /// the values (`m × dim`), `control_cotangent` (laid out as the Euclidean net) receives
    /// `P̄_k = Σ_r R_k(x_r) ḡ_r`, `weight_cotangent` (one a net point)
    /// `w̄_k = Σ_r B_k(x_r) ḡ_r · (P_k − S_r) / W_r` and `point_cotangent` (laid out as `xs`)
    /// `x̄_{r,a} = ḡ_r · ∂S/∂x_a(x_r)`, each when given (overwritten): the transpose of
    /// [`TensorNurbs::eval_batch_jvp`].
    ///
    /// # Errors
    /// As [`TensorNurbs::eval_batch_jvp`]; [`crate::Error::NonFinite`] for a non-finite
    /// cotangent.
    pub fn eval_batch_vjp(
        &self,
        xs: &[f64],
        cotangent: &[f64],
        mut control_cotangent: Option<&mut [f64]>,
        mut weight_cotangent: Option<&mut [f64]>,
        point_cotangent: Option<&mut [f64]>,
    ) -> Result<()> {
        let hom = self.homogeneous();
        let (n, dim, hd) = (self.n_vars(), self.dim(), hom.dim());
        let m = hom.points_in(xs)?;
        check_cotangent("cotangent (points × dimension)", m, dim, cotangent)?;
        let h_net = hom.control_points().as_slice();
        let net_points = h_net.len() / hd;
        if let Some(gp) = control_cotangent.as_deref_mut() {
            check_len(
                "control-net cotangent buffer (as the control net)",
                net_points * dim,
                gp.len(),
            )?;
            gp.fill(0.0);
        }
        if let Some(gw) = weight_cotangent.as_deref_mut() {
            check_len(
                "weight cotangent buffer (one a net point)",
                net_points,
                gw.len(),
            )?;
            gw.fill(0.0);
        }
        if let Some(gx) = point_cotangent.as_deref() {
            check_len("point cotangent buffer (as the points)", xs.len(), gx.len())?;
        }
        let mut values = vec![0.0; m * dim];
        let h = homogeneous_values(hom, xs, m, &mut values)?;
        if control_cotangent.is_some() || weight_cotangent.is_some() {
            let mut b = PointBases::new(hom);
            for (r, (x, g)) in xs
                .chunks_exact(n)
                .zip(cotangent.chunks_exact(dim))
                .enumerate()
            {
                b.at(hom, x)?;
                let sums = (h[r * hd + dim], &values[r * dim..(r + 1) * dim]);
                b.for_each_cell(hom, |o, nk| {
                    let j = o / hd;
                    let outs = (
                        control_cotangent
                            .as_deref_mut()
                            .map(|gp| &mut gp[j * dim..(j + 1) * dim]),
                        weight_cotangent.as_deref_mut().map(|gw| &mut gw[j]),
                    );
                    vjp_cell(&h_net[o..o + hd], nk, sums, g, outs);
                });
            }
        }
        if let Some(gx) = point_cotangent {
            let partials = rational_partials(hom, xs, m, &h, &values)?;
            for (r, g) in cotangent.chunks_exact(dim).enumerate() {
                for a in 0..n {
                    let d = &partials[(r * n + a) * dim..(r * n + a + 1) * dim];
                    gx[r * n + a] = d.iter().zip(g).map(|(x, y)| x * y).sum();
                }
            }
        }
        Ok(())
    }

    /// The linearisation of [`TensorNurbs::eval_batch`] at `xs`: values (bit-for-bit
    /// `eval_batch`), partial derivatives (P&T eq. 4.20), the first net index of every
    /// direction and the rational basis of every point's block, as a
    /// [`TensorNurbsLinearization`]: the sparse Jacobian in the net, the weights and the points.
    ///
    /// # Errors
    /// [`crate::Error::LengthMismatch`] if `xs.len()` is not a multiple of `N`;
    /// [`crate::Error::TooLarge`] if the arrays would exceed [`crate::MAX_SCALARS`];
    /// [`crate::Error::ParameterOutOfDomain`] at the first point outside the domain.
    pub fn eval_batch_linearize(&self, xs: &[f64]) -> Result<TensorNurbsLinearization> {
        let hom = self.homogeneous();
        let (n, dim, hd) = (self.n_vars(), self.dim(), hom.dim());
        let m = hom.points_in(xs)?;
        let block = self
            .degrees()
            .iter()
            .fold(1usize, |b, p| b.saturating_mul(p + 1));
        let mut values = vec![0.0; check_scalars("values (points × dimension)", m, dim)?];
        let nb = check_scalars("basis (points × Π (degree + 1))", m, block)?;
        check_scalars("partials (points × directions × dimension)", m, n * dim)?;
        let h = homogeneous_values(hom, xs, m, &mut values)?;
        let partials = rational_partials(hom, xs, m, &h, &values)?;
        let h_net = hom.control_points().as_slice();
        let mut first = Vec::with_capacity(m * n);
        let mut basis = Vec::with_capacity(nb);
        let mut b = PointBases::new(hom);
        for (r, x) in xs.chunks_exact(n).enumerate() {
            b.at(hom, x)?;
            first.extend_from_slice(&b.first);
            let w = h[r * hd + dim];
            b.for_each_cell(hom, |o, nk| basis.push(nk * h_net[o + dim] / w));
        }
        Ok(TensorNurbsLinearization {
            values,
            partials,
            first,
            basis,
        })
    }
}

#[cfg(test)]
#[path = "tensor_nurbs_tests.rs"]
mod tests;
