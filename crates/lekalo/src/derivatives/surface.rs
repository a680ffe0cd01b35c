//! JVP, VJP and linearisation of tensor-product B-spline surface batch evaluation
//! `S(u_i, v_i) = Σ_k Σ_l N_{k,p}(u_i) N_{l,q}(v_i) P_{kl}` with respect to the control net and
//! the parameters `(u, v)` (`docs/theory/derivatives.md`).

use super::checks::{
    check_cotangent, check_input, check_len, check_output, check_scalars, zeroed_output,
};
use super::curve::PointBasis;
use crate::error::Result;
use crate::surface::BSplineSurface;

/// The linearisation of a surface's batch evaluation at pairs `(u_i, v_i)`, what
/// [`BSplineSurface::eval_batch_linearize`] returns: with `(p, q)` the degrees and `nv` the
/// net's second size,
/// `S(u_i, v_i) = Σ_k Σ_l basis_u[i·(p+1)+k] · basis_v[i·(q+1)+l] · P_{first_u_i + k, first_v_i + l}`.
#[derive(Debug, Clone, PartialEq)]
pub struct SurfaceLinearization {
    /// `S(u_i, v_i)`, point-major (`m × dim`): bit-for-bit [`BSplineSurface::eval_batch`].
    pub values: Vec<f64>,
    /// `∂S/∂u (u_i, v_i)` (`m × dim`; right-hand at interior knots).
    pub derivatives_u: Vec<f64>,
    /// `∂S/∂v (u_i, v_i)` (`m × dim`; right-hand at interior knots).
    pub derivatives_v: Vec<f64>,
    /// First row of the net with a non-zero `u` basis function (`span_u − p`).
    pub first_u: Vec<usize>,
    /// First column of the net with a non-zero `v` basis function (`span_v − q`).
    pub first_v: Vec<usize>,
    /// The `p + 1` non-zero `u` basis functions at each `u_i` (`m × (p + 1)`).
    pub basis_u: Vec<f64>,
    /// The `q + 1` non-zero `v` basis functions at each `v_i` (`m × (q + 1)`).
    pub basis_v: Vec<f64>,
}

/// Basis values and first derivatives in both directions at one pair.
pub(super) struct PairBasis {
    pub(super) u: PointBasis,
    pub(super) v: PointBasis,
    /// One point, the inner sum of the tensor combination.
    pub(super) tmp: Vec<f64>,
}

impl PairBasis {
    pub(super) fn new(s: &BSplineSurface) -> Self {
        let (p, q) = s.degree();
        PairBasis {
            u: PointBasis::new(p),
            v: PointBasis::new(q),
            tmp: vec![0.0; s.dim()],
        }
    }
}

/// `out = Σ_k bu[k] · (Σ_l bv[l] · net[(first_u + k)·nv + first_v + l])`, both sums from zero
/// in index order: the order of the forward evaluation (P&T A3.5 as `BSplineSurface::eval`
/// runs it), so the same bits.
#[allow(clippy::too_many_arguments)] // a net, its layout, a corner, two bases and two buffers
pub(super) fn combine(
    net: &[f64],
    nv: usize,
    dim: usize,
    (first_u, first_v): (usize, usize),
    bu: &[f64],
    bv: &[f64],
    tmp: &mut [f64],
    out: &mut [f64],
) {
    out.fill(0.0);
    for (k, &a) in bu.iter().enumerate() {
        tmp.fill(0.0);
        let start = ((first_u + k) * nv + first_v) * dim;
        for (&b, c) in bv
            .iter()
            .zip(net[start..start + bv.len() * dim].chunks_exact(dim))
        {
            for (t, x) in tmp.iter_mut().zip(c) {
                *t += b * x;
            }
        }
        for (o, t) in out.iter_mut().zip(tmp.iter()) {
            *o += a * t;
        }
    }
}

impl BSplineSurface {
    /// Spans, basis values and derivatives at `(u, v)`; returns the net's corner `(row, col)`.
    pub(super) fn pair_basis(
        &self,
        cursors: &mut (crate::SpanCursor<'_>, crate::SpanCursor<'_>),
        [u, v]: [f64; 2],
        b: &mut PairBasis,
    ) -> Result<(usize, usize)> {
        let (p, q) = self.degree();
        let (ku, kv) = self.knots();
        let su = cursors.0.find(u)?;
        let sv = cursors.1.find(v)?;
        Ok((
            b.u.at(ku.as_slice(), p, su, u),
            b.v.at(kv.as_slice(), q, sv, v),
        ))
    }

    pub(super) fn cursors(&self) -> (crate::SpanCursor<'_>, crate::SpanCursor<'_>) {
        let (p, q) = self.degree();
        (self.knots_u().span_cursor(p), self.knots_v().span_cursor(q))
    }

    /// Forward-mode derivative (JVP) of [`BSplineSurface::eval_batch`]: `out` receives
    /// `S(u_i, v_i)` (bit-for-bit `eval_batch`) and `tangent_out` receives
    ///
    /// `Ṡ_i = Σ_k Σ_l N_{k,p}(u_i) N_{l,q}(v_i) Ṗ_{kl} + S_u(u_i, v_i) u̇_i + S_v(u_i, v_i) v̇_i`
    ///
    /// for a net tangent `Ṗ` (`control_tangent`, laid out as the control net; `None` is zero)
    /// and parameter tangents `(u̇_i, v̇_i)` (`parameter_tangent`, one pair a point; `None` is
    /// zero). Basis functions and derivatives by P&T A2.3 in each direction; each pair touches
    /// `(p + 1)(q + 1)` control points. O(m·(p² + q² + p·q·dim)).
    ///
    /// # Errors
    /// [`crate::Error::LengthMismatch`] for a buffer of the wrong length;
    /// [`crate::Error::NonFinite`] for a non-finite tangent;
    /// [`crate::Error::ParameterOutOfDomain`] at the first pair outside the domain.
    pub fn eval_batch_jvp(
        &self,
        uv: &[[f64; 2]],
        control_tangent: Option<&[f64]>,
        parameter_tangent: Option<&[[f64; 2]]>,
        out: &mut [f64],
        tangent_out: &mut [f64],
    ) -> Result<()> {
        let dim = self.dim();
        let n = uv.len().saturating_mul(dim);
        check_len("output buffer (parameter pairs × dimension)", n, out.len())?;
        check_len(
            "tangent output buffer (parameter pairs × dimension)",
            n,
            tangent_out.len(),
        )?;
        let ctrl = self.control_points().as_slice();
        check_input(
            "control-net tangent (as the control net)",
            ctrl.len(),
            control_tangent,
        )?;
        if let Some(dt) = parameter_tangent {
            check_input(
                "parameter tangent (one pair a point)",
                uv.len() * 2,
                Some(dt.as_flattened()),
            )?;
        }
        let nv = self.net_size().1;
        let mut cursors = self.cursors();
        let mut b = PairBasis::new(self);
        let (mut su, mut sv) = (vec![0.0; dim], vec![0.0; dim]);
        let points = out
            .chunks_exact_mut(dim)
            .zip(tangent_out.chunks_exact_mut(dim));
        for (i, (&pair, (o, d))) in uv.iter().zip(points).enumerate() {
            let corner = self.pair_basis(&mut cursors, pair, &mut b)?;
            let (bu, bv) = (b.u.values(), b.v.values());
            combine(ctrl, nv, dim, corner, bu, bv, &mut b.tmp, o);
            match control_tangent {
                Some(dp) => combine(dp, nv, dim, corner, bu, bv, &mut b.tmp, d),
                None => d.fill(0.0),
            }
            if let Some(dt) = parameter_tangent {
                let (bu1, bv1) = (b.u.slopes(), b.v.slopes());
                combine(ctrl, nv, dim, corner, bu1, bv, &mut b.tmp, &mut su);
                combine(ctrl, nv, dim, corner, bu, bv1, &mut b.tmp, &mut sv);
                let [du, dv] = dt[i];
                for ((x, a), c) in d.iter_mut().zip(&su).zip(&sv) {
                    *x += a * du + c * dv;
                }
            }
        }
        Ok(())
    }

    /// Reverse-mode derivative (VJP) of [`BSplineSurface::eval_batch`]: for a cotangent `ḡ`
    /// (`uv.len() × dim`, point-major),
    ///
    /// `P̄_{kl} = Σ_i N_{k,p}(u_i) N_{l,q}(v_i) ḡ_i` into `control_cotangent` (as the net) and
    /// `(ū_i, v̄_i) = (ḡ_i · S_u, ḡ_i · S_v)` into `parameter_cotangent`,
    ///
    /// each when given; the buffers are overwritten. The transpose of
    /// [`BSplineSurface::eval_batch_jvp`]. O(m·(p² + q² + p·q·dim)) plus the zeroing.
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
        mut parameter_cotangent: Option<&mut [[f64; 2]]>,
    ) -> Result<()> {
        let dim = self.dim();
        check_cotangent(
            "cotangent (parameter pairs × dimension)",
            uv.len(),
            dim,
            cotangent,
        )?;
        let ctrl = self.control_points().as_slice();
        zeroed_output(
            "control-net cotangent buffer (as the control net)",
            ctrl.len(),
            control_cotangent.as_deref_mut(),
        )?;
        check_output(
            "parameter cotangent buffer (one pair a point)",
            uv.len(),
            parameter_cotangent.as_deref(),
        )?;
        let nv = self.net_size().1;
        let mut cursors = self.cursors();
        let mut b = PairBasis::new(self);
        let (mut su, mut sv) = (vec![0.0; dim], vec![0.0; dim]);
        for (i, (&pair, g)) in uv.iter().zip(cotangent.chunks_exact(dim)).enumerate() {
            let (fu, fv) = self.pair_basis(&mut cursors, pair, &mut b)?;
            let (bu, bv) = (b.u.values(), b.v.values());
            if let Some(gp) = control_cotangent.as_deref_mut() {
                for (k, &a) in bu.iter().enumerate() {
                    let start = ((fu + k) * nv + fv) * dim;
                    let cells = gp[start..start + bv.len() * dim].chunks_exact_mut(dim);
                    for (&c, cell) in bv.iter().zip(cells) {
                        let w = a * c;
                        for (x, gi) in cell.iter_mut().zip(g) {
                            *x += w * gi;
                        }
                    }
                }
            }
            if let Some(gt) = parameter_cotangent.as_deref_mut() {
                let (bu1, bv1) = (b.u.slopes(), b.v.slopes());
                combine(ctrl, nv, dim, (fu, fv), bu1, bv, &mut b.tmp, &mut su);
                combine(ctrl, nv, dim, (fu, fv), bu, bv1, &mut b.tmp, &mut sv);
                let dot = |s: &[f64]| s.iter().zip(g).map(|(x, y)| x * y).sum::<f64>();
                gt[i] = [dot(&su), dot(&sv)];
            }
        }
        Ok(())
    }

    /// The linearisation of [`BSplineSurface::eval_batch`] at `uv`: values (bit-for-bit
    /// `eval_batch`), both partial derivatives, and the sparse rows of the two basis matrices,
    /// as a [`SurfaceLinearization`]. P&T A2.3 in each direction; O(m·(p² + q² + p·q·dim)).
    ///
    /// ```
    /// use lekalo::{BSplineSurface, Points};
    /// // S(u, v) = (u, v, u·v)
    /// let net = Points::from_3d(&[[0.0, 0.0, 0.0], [0.0, 1.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 1.0]])?;
    /// let s = BSplineSurface::new(1, 1, vec![0.0, 0.0, 1.0, 1.0], vec![0.0, 0.0, 1.0, 1.0], net, (2, 2))?;
    /// let lin = s.eval_batch_linearize(&[[0.25, 0.5]])?;
    /// assert_eq!(lin.derivatives_u, vec![1.0, 0.0, 0.5]);
    /// assert_eq!(lin.derivatives_v, vec![0.0, 1.0, 0.25]);
    /// assert_eq!((lin.basis_u, lin.basis_v), (vec![0.75, 0.25], vec![0.5, 0.5]));
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`crate::Error::TooLarge`] if the arrays would exceed [`crate::MAX_SCALARS`];
    /// [`crate::Error::ParameterOutOfDomain`] at the first pair outside the domain.
    pub fn eval_batch_linearize(&self, uv: &[[f64; 2]]) -> Result<SurfaceLinearization> {
        let ((p, q), dim) = (self.degree(), self.dim());
        let n = check_scalars("linearisation (pairs × dimension)", uv.len(), dim)?;
        check_scalars(
            "linearisation (pairs × (degree + 1))",
            uv.len(),
            p.max(q) + 1,
        )?;
        let (wu, wv) = (p + 1, q + 1);
        let mut lin = SurfaceLinearization {
            values: vec![0.0; n],
            derivatives_u: vec![0.0; n],
            derivatives_v: vec![0.0; n],
            first_u: vec![0; uv.len()],
            first_v: vec![0; uv.len()],
            basis_u: vec![0.0; uv.len() * wu],
            basis_v: vec![0.0; uv.len() * wv],
        };
        let ctrl = self.control_points().as_slice();
        let nv = self.net_size().1;
        let mut cursors = self.cursors();
        let mut b = PairBasis::new(self);
        for (i, &pair) in uv.iter().enumerate() {
            let corner = self.pair_basis(&mut cursors, pair, &mut b)?;
            let (bu, bv) = (b.u.values(), b.v.values());
            let (bu1, bv1) = (b.u.slopes(), b.v.slopes());
            let pt = i * dim..(i + 1) * dim;
            combine(
                ctrl,
                nv,
                dim,
                corner,
                bu,
                bv,
                &mut b.tmp,
                &mut lin.values[pt.clone()],
            );
            combine(
                ctrl,
                nv,
                dim,
                corner,
                bu1,
                bv,
                &mut b.tmp,
                &mut lin.derivatives_u[pt.clone()],
            );
            combine(
                ctrl,
                nv,
                dim,
                corner,
                bu,
                bv1,
                &mut b.tmp,
                &mut lin.derivatives_v[pt],
            );
            (lin.first_u[i], lin.first_v[i]) = corner;
            lin.basis_u[i * wu..(i + 1) * wu].copy_from_slice(bu);
            lin.basis_v[i * wv..(i + 1) * wv].copy_from_slice(bv);
        }
        Ok(lin)
    }
}
