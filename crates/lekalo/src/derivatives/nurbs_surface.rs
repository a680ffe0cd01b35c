//! JVP, VJP and linearisation of NURBS surface batch evaluation
//! `S(u, v) = A(u, v) / W(u, v)`, `A = Σ_k Σ_l N_{k,p}(u) N_{l,q}(v) w_kl P_kl`,
//! `W = Σ_k Σ_l N_{k,p}(u) N_{l,q}(v) w_kl`, with respect to the (Euclidean) control net `P`,
//! the weights `w` and the parameters `(u, v)` (`docs/theory/derivatives.md`, "NURBS surfaces
//! and N-variate NURBS"):
//!
//! - `∂S/∂P_kl = R_kl = N_k M_l w_kl / W` (the rational basis, times the identity);
//! - `∂S/∂w_kl = N_k M_l (P_kl − S) / W`;
//! - `∂S/∂u = (A_u − W_u S) / W`, `∂S/∂v = (A_v − W_v S) / W` (P&T eq. 4.20 with one
//!   derivative).
//!
//! The homogeneous sums `(A, W)` and their derivatives are `surface.rs`'s [`combine`] on the
//! homogeneous net, whose order of sums is the forward evaluation's, so the values `A / W` are
//! [`NurbsSurface::eval_batch`]'s bits.

use super::checks::{
    check_cotangent, check_input, check_len, check_output, check_scalars, zeroed_output,
};
use super::nurbs::{jvp_cell, vjp_cell};
use super::surface::{combine, PairBasis};
use crate::error::Result;
use crate::surface::{BSplineSurface, NurbsSurface};

/// The linearisation of a NURBS surface's batch evaluation at pairs `(u_i, v_i)`, what
/// [`NurbsSurface::eval_batch_linearize`] returns: with `(p, q)` the degrees and `nv` the net's
/// second size, `S(u_i, v_i) = Σ_k Σ_l basis[i·(p+1)(q+1) + k·(q+1) + l] ·
/// P_{first_u_i + k, first_v_i + l}` (the rational basis `R_kl = N_k M_l w_kl / W` is not a
/// product of one basis a direction), and `∂S/∂w_kl = R_kl (P_kl − S) / w_kl`.
#[derive(Debug, Clone, PartialEq)]
pub struct NurbsSurfaceLinearization {
    /// `S(u_i, v_i)`, point-major (`m × dim`): bit-for-bit [`NurbsSurface::eval_batch`].
    pub values: Vec<f64>,
    /// `∂S/∂u (u_i, v_i)` (`m × dim`; right-hand at interior knots).
    pub derivatives_u: Vec<f64>,
    /// `∂S/∂v (u_i, v_i)` (`m × dim`; right-hand at interior knots).
    pub derivatives_v: Vec<f64>,
    /// First row of the net with a non-zero `u` basis function (`span_u − p`).
    pub first_u: Vec<usize>,
    /// First column of the net with a non-zero `v` basis function (`span_v − q`).
    pub first_v: Vec<usize>,
    /// The `(p + 1)(q + 1)` non-zero rational basis functions at each pair, row-major in
    /// `(k, l)` (`m × (p + 1)(q + 1)`).
    pub basis: Vec<f64>,
}

/// One pair's homogeneous sums and rational values: scratch sized once for a surface.
struct PairSums {
    b: PairBasis,
    /// `(A, W)`, then `(A_u, W_u)` and `(A_v, W_v)` (`dim + 1` numbers each).
    h: Vec<f64>,
    hu: Vec<f64>,
    hv: Vec<f64>,
    /// `S`, `S_u`, `S_v` (`dim` numbers each).
    value: Vec<f64>,
    su: Vec<f64>,
    sv: Vec<f64>,
}

impl PairSums {
    fn new(hom: &BSplineSurface) -> Self {
        let hd = hom.dim();
        PairSums {
            b: PairBasis::new(hom),
            h: vec![0.0; hd],
            hu: vec![0.0; hd],
            hv: vec![0.0; hd],
            value: vec![0.0; hd - 1],
            su: vec![0.0; hd - 1],
            sv: vec![0.0; hd - 1],
        }
    }

    /// The sums at `pair`: `S = A / W` (one division a coordinate, as `NurbsSurface::eval_batch`
    /// projects), and with `slopes` `S_u`, `S_v` by the quotient rule. Returns the net's corner.
    fn at(
        &mut self,
        hom: &BSplineSurface,
        cursors: &mut (crate::SpanCursor<'_>, crate::SpanCursor<'_>),
        pair: [f64; 2],
        slopes: bool,
    ) -> Result<(usize, usize)> {
        let (hd, nv) = (hom.dim(), hom.net_size().1);
        let dim = hd - 1;
        let h = hom.control_points().as_slice();
        let corner = hom.pair_basis(cursors, pair, &mut self.b)?;
        let b = &mut self.b;
        let (bu, bv) = (b.u.values(), b.v.values());
        combine(h, nv, hd, corner, bu, bv, &mut b.tmp, &mut self.h);
        let w = self.h[dim];
        for (s, a) in self.value.iter_mut().zip(&self.h) {
            *s = a / w;
        }
        if slopes {
            let (bu1, bv1) = (b.u.slopes(), b.v.slopes());
            combine(h, nv, hd, corner, bu1, bv, &mut b.tmp, &mut self.hu);
            combine(h, nv, hd, corner, bu, bv1, &mut b.tmp, &mut self.hv);
            for (d, hd) in [(&mut self.su, &self.hu), (&mut self.sv, &self.hv)] {
                let dw = hd[dim];
                for ((x, a), s) in d.iter_mut().zip(hd.iter()).zip(&self.value) {
                    *x = (a - dw * s) / w;
                }
            }
        }
        Ok(corner)
    }

    /// `W` at the last pair.
    fn weight(&self) -> f64 {
        self.h[self.h.len() - 1]
    }

    /// Calls `f(flat index, N_k M_l)` for the `(p + 1)(q + 1)` net points of the last pair, `k`
    /// slowest.
    fn for_each_cell(&self, nv: usize, (fu, fv): (usize, usize), mut f: impl FnMut(usize, f64)) {
        for (k, &a) in self.b.u.values().iter().enumerate() {
            for (l, &c) in self.b.v.values().iter().enumerate() {
                f((fu + k) * nv + fv + l, a * c);
            }
        }
    }
}

impl NurbsSurface {
    /// Forward-mode derivative (JVP) of [`NurbsSurface::eval_batch`]: `out` receives
    /// `S(u_i, v_i)` (bit-for-bit `eval_batch`) and `tangent_out`
    ///
    /// `Ṡ_i = Σ_kl R_kl Ṗ_kl + Σ_kl N_k M_l (P_kl − S_i) ẇ_kl / W_i + S_u u̇_i + S_v v̇_i`
    ///
    /// for tangents of the Euclidean control net (`control_tangent`, laid out as the net,
    /// `dim` numbers a point), of the weights (`weight_tangent`, one a net point) and of the
    /// pairs (`parameter_tangent`, one pair a point); `None` is zero. `R_kl = N_k M_l w_kl / W`
    /// is the rational basis, the parameter derivatives the quotient rule on the homogeneous
    /// sums (P&T eq. 4.20 with one derivative; `docs/theory/derivatives.md`, "NURBS surfaces
    /// and N-variate NURBS"). Basis functions and derivatives by P&T A2.3 in each direction;
    /// each pair touches `(p + 1)(q + 1)` control points. O(m·(p² + q² + p·q·dim)).
    ///
    /// ```
    /// use lekalo::{NurbsSurface, Points};
    /// // S(u, v) = (u, v, u·v) with weights: raising w_11 pulls S towards P_11 = (1, 1, 1)
    /// let net = Points::from_3d(&[[0.0, 0.0, 0.0], [0.0, 1.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 1.0]])?;
    /// let k = vec![0.0, 0.0, 1.0, 1.0];
    /// let s = NurbsSurface::new(1, 1, k.clone(), k, net, vec![1.0; 4], (2, 2))?;
    /// let (mut out, mut tan) = (vec![0.0; 3], vec![0.0; 3]);
    /// let dw = [0.0, 0.0, 0.0, 1.0];
    /// s.eval_batch_jvp(&[[0.5, 0.5]], None, Some(&dw), None, &mut out, &mut tan)?;
    /// // ∂S/∂w_11 = N_1 M_1 (P_11 − S) / W = ¼ (1 − ½, 1 − ½, 1 − ¼)
    /// assert_eq!(tan, vec![0.125, 0.125, 0.1875]);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`crate::Error::LengthMismatch`] for a buffer of the wrong length;
    /// [`crate::Error::NonFinite`] for a non-finite tangent;
    /// [`crate::Error::ParameterOutOfDomain`] at the first pair outside the domain.
    pub fn eval_batch_jvp(
        &self,
        uv: &[[f64; 2]],
        control_tangent: Option<&[f64]>,
        weight_tangent: Option<&[f64]>,
        parameter_tangent: Option<&[[f64; 2]]>,
        out: &mut [f64],
        tangent_out: &mut [f64],
    ) -> Result<()> {
        let dim = self.dim();
        let hom = self.homogeneous();
        let (nu, nv) = hom.net_size();
        let n = uv.len().saturating_mul(dim);
        check_len("output buffer (parameter pairs × dimension)", n, out.len())?;
        check_len(
            "tangent output buffer (parameter pairs × dimension)",
            n,
            tangent_out.len(),
        )?;
        check_input(
            "control-net tangent (as the control net)",
            nu * nv * dim,
            control_tangent,
        )?;
        check_input("weight tangent (one a net point)", nu * nv, weight_tangent)?;
        if let Some(dt) = parameter_tangent {
            check_input(
                "parameter tangent (one pair a point)",
                uv.len() * 2,
                Some(dt.as_flattened()),
            )?;
        }
        let h = hom.control_points().as_slice();
        let hd = dim + 1;
        let mut cursors = hom.cursors();
        let mut r = PairSums::new(hom);
        let cells = control_tangent.is_some() || weight_tangent.is_some();
        let points = out
            .chunks_exact_mut(dim)
            .zip(tangent_out.chunks_exact_mut(dim));
        for (i, (&pair, (o, d))) in uv.iter().zip(points).enumerate() {
            let corner = r.at(hom, &mut cursors, pair, parameter_tangent.is_some())?;
            o.copy_from_slice(&r.value);
            d.fill(0.0);
            if cells {
                let sums = (r.weight(), r.value.as_slice());
                r.for_each_cell(nv, corner, |j, nkl| {
                    let tangents = (
                        control_tangent.map(|dp| &dp[j * dim..(j + 1) * dim]),
                        weight_tangent.map(|dw| dw[j]),
                    );
                    jvp_cell(&h[j * hd..(j + 1) * hd], nkl, sums, tangents, d);
                });
            }
            if let Some(dt) = parameter_tangent {
                let [du, dv] = dt[i];
                for ((x, a), c) in d.iter_mut().zip(&r.su).zip(&r.sv) {
                    *x += a * du + c * dv;
                }
            }
        }
        Ok(())
    }

    /// Reverse-mode derivative (VJP) of [`NurbsSurface::eval_batch`]: for a cotangent `ḡ`
    /// (`uv.len() × dim`, point-major),
    ///
    /// `P̄_kl = Σ_i R_kl(u_i, v_i) ḡ_i`, `w̄_kl = Σ_i N_k M_l ḡ_i · (P_kl − S_i) / W_i`,
    /// `(ū_i, v̄_i) = (ḡ_i · S_u, ḡ_i · S_v)`,
    ///
    /// into `control_cotangent` (as the Euclidean net), `weight_cotangent` (one a net point) and
    /// `parameter_cotangent` (one pair a point), each when given; the buffers are overwritten.
    /// The transpose of [`NurbsSurface::eval_batch_jvp`]. O(m·(p² + q² + p·q·dim)).
    ///
    /// # Errors
    /// [`crate::Error::LengthMismatch`] for a buffer of the wrong length;
    /// [`crate::Error::NonFinite`] for a non-finite cotangent;
    /// [`crate::Error::ParameterOutOfDomain`] at the first pair outside the domain.
    pub fn eval_batch_vjp(
        &self,
        uv: &[[f64; 2]],
        cotangent: &[f64],
        mut control_cotangent: Option<&mut [f64]>,
        mut weight_cotangent: Option<&mut [f64]>,
        mut parameter_cotangent: Option<&mut [[f64; 2]]>,
    ) -> Result<()> {
        let dim = self.dim();
        let hom = self.homogeneous();
        let (nu, nv) = hom.net_size();
        check_cotangent(
            "cotangent (parameter pairs × dimension)",
            uv.len(),
            dim,
            cotangent,
        )?;
        zeroed_output(
            "control-net cotangent buffer (as the control net)",
            nu * nv * dim,
            control_cotangent.as_deref_mut(),
        )?;
        zeroed_output(
            "weight cotangent buffer (one a net point)",
            nu * nv,
            weight_cotangent.as_deref_mut(),
        )?;
        check_output(
            "parameter cotangent buffer (one pair a point)",
            uv.len(),
            parameter_cotangent.as_deref(),
        )?;
        let h = hom.control_points().as_slice();
        let hd = dim + 1;
        let mut cursors = hom.cursors();
        let mut r = PairSums::new(hom);
        let cells = control_cotangent.is_some() || weight_cotangent.is_some();
        for (i, (&pair, g)) in uv.iter().zip(cotangent.chunks_exact(dim)).enumerate() {
            let corner = r.at(hom, &mut cursors, pair, parameter_cotangent.is_some())?;
            if cells {
                let sums = (r.weight(), r.value.as_slice());
                r.for_each_cell(nv, corner, |j, nkl| {
                    let outs = (
                        control_cotangent
                            .as_deref_mut()
                            .map(|gp| &mut gp[j * dim..(j + 1) * dim]),
                        weight_cotangent.as_deref_mut().map(|gw| &mut gw[j]),
                    );
                    vjp_cell(&h[j * hd..(j + 1) * hd], nkl, sums, g, outs);
                });
            }
            if let Some(gt) = parameter_cotangent.as_deref_mut() {
                let dot = |s: &[f64]| s.iter().zip(g).map(|(x, y)| x * y).sum::<f64>();
                gt[i] = [dot(&r.su), dot(&r.sv)];
            }
        }
        Ok(())
    }

    /// The linearisation of [`NurbsSurface::eval_batch`] at `uv`: values (bit-for-bit
    /// `eval_batch`), both partial derivatives (P&T eq. 4.20), and the sparse rows of the
    /// rational basis `R_kl = N_k M_l w_kl / W`, as a [`NurbsSurfaceLinearization`].
    /// O(m·(p² + q² + p·q·dim)).
    ///
    /// # Errors
    /// [`crate::Error::TooLarge`] if the arrays would exceed [`crate::MAX_SCALARS`];
    /// [`crate::Error::ParameterOutOfDomain`] at the first pair outside the domain.
    pub fn eval_batch_linearize(&self, uv: &[[f64; 2]]) -> Result<NurbsSurfaceLinearization> {
        let ((p, q), dim) = (self.degree(), self.dim());
        let n = check_scalars("linearisation (pairs × dimension)", uv.len(), dim)?;
        let w = (p + 1).saturating_mul(q + 1);
        let nb = check_scalars("linearisation (pairs × (p + 1)(q + 1))", uv.len(), w)?;
        let mut lin = NurbsSurfaceLinearization {
            values: vec![0.0; n],
            derivatives_u: vec![0.0; n],
            derivatives_v: vec![0.0; n],
            first_u: vec![0; uv.len()],
            first_v: vec![0; uv.len()],
            basis: vec![0.0; nb],
        };
        let hom = self.homogeneous();
        let (h, nv, hd) = (hom.control_points().as_slice(), hom.net_size().1, dim + 1);
        let mut cursors = hom.cursors();
        let mut r = PairSums::new(hom);
        for (i, &pair) in uv.iter().enumerate() {
            let corner = r.at(hom, &mut cursors, pair, true)?;
            let pt = i * dim..(i + 1) * dim;
            lin.values[pt.clone()].copy_from_slice(&r.value);
            lin.derivatives_u[pt.clone()].copy_from_slice(&r.su);
            lin.derivatives_v[pt].copy_from_slice(&r.sv);
            (lin.first_u[i], lin.first_v[i]) = corner;
            let row = &mut lin.basis[i * w..(i + 1) * w];
            let weight = r.weight();
            let mut cell = 0;
            r.for_each_cell(nv, corner, |j, nkl| {
                row[cell] = nkl * h[j * hd + dim] / weight;
                cell += 1;
            });
        }
        Ok(lin)
    }
}

#[cfg(test)]
#[path = "nurbs_surface_tests.rs"]
mod tests;
