//! JVP, VJP and linearisation of NURBS curve batch evaluation
//! `C(t) = A(t) / W(t)`, `A = Σ_j N_{j,p}(t) w_j P_j`, `W = Σ_j N_{j,p}(t) w_j`, with respect to
//! the (Euclidean) control points `P`, the weights `w` and the parameters `t`
//! (`docs/theory/derivatives.md`, "NURBS curves"):
//!
//! - `∂C/∂P_j = R_j = N_j w_j / W` (the rational basis, times the identity);
//! - `∂C/∂w_j = N_j (P_j − C) / W`;
//! - `∂C/∂t = C' = (A' − W' C) / W` (P&T eq. 4.8 with one derivative).

use super::checks::{
    check_cotangent, check_input, check_len, check_output, check_scalars, zeroed_output,
};
use super::curve::{CurveLinearization, PointBasis};
use crate::curve::NurbsCurve;
use crate::error::Result;

/// The linearisation of a NURBS curve's batch evaluation, what
/// [`NurbsCurve::eval_batch_linearize`] returns: the fields of a B-spline's
/// [`CurveLinearization`], with `basis` holding the `p + 1` non-zero rational basis functions
/// `R_j = N_j w_j / W`: `C(t_i) = Σ_k R[i·(p+1)+k] · P_{first_i + k}`, and
/// `∂C(t_i)/∂w_j = R_{ij} (P_j − C(t_i)) / w_j`.
pub type NurbsLinearization = CurveLinearization;

/// One point's sums: `A`, `W`, `C`, `A'`, `W'`, `C'` from the homogeneous net `h`
/// (`dim + 1` numbers a point, weight last).
pub(super) struct Rational {
    /// `C = A / W` (`dim` numbers).
    pub(super) value: Vec<f64>,
    /// `C'` (`dim` numbers).
    pub(super) slope: Vec<f64>,
    /// `W(t)`.
    pub(super) weight: f64,
}

impl Rational {
    pub(super) fn new(dim: usize) -> Self {
        Rational {
            value: vec![0.0; dim],
            slope: vec![0.0; dim],
            weight: 0.0,
        }
    }

    /// The sums at one parameter. `value` is summed as `NurbsCurve::eval_batch` sums it (from
    /// zero, in the order of the control points, then divided by `W`): the same bits.
    pub(super) fn at(
        &mut self,
        h: &[f64],
        dim: usize,
        first: usize,
        b: &PointBasis,
        with_slope: bool,
    ) {
        let hd = dim + 1;
        let net = &h[first * hd..(first + b.values().len()) * hd];
        self.value.fill(0.0);
        let mut w = 0.0;
        for (nj, pt) in b.values().iter().zip(net.chunks_exact(hd)) {
            for (o, c) in self.value.iter_mut().zip(pt) {
                *o += nj * c;
            }
            w += nj * pt[dim];
        }
        for o in &mut self.value {
            *o /= w;
        }
        self.weight = w;
        if with_slope {
            self.slope.fill(0.0);
            let mut dw = 0.0;
            for (dj, pt) in b.slopes().iter().zip(net.chunks_exact(hd)) {
                for (o, c) in self.slope.iter_mut().zip(pt) {
                    *o += dj * c;
                }
                dw += dj * pt[dim];
            }
            for (s, c) in self.slope.iter_mut().zip(&self.value) {
                *s = (*s - dw * c) / w;
            }
        }
    }
}

/// The tangents of one parameter's JVP: of the control points (`n × dim`), of the weights (`n`)
/// and of the parameter itself.
pub(super) type PointTangents<'a> = (Option<&'a [f64]>, Option<&'a [f64]>, Option<f64>);

/// `Ċ = Σ_k R_k Ṗ_{first+k} + Σ_k N_k (P_{first+k} − C) ẇ_{first+k} / W + C' ṫ` at one
/// parameter into `d`: `net` the `p + 1` homogeneous points of its span (`dim + 1` numbers
/// each, weight last), `r` its sums ([`Rational::at`] on `net`, with the slope when `ṫ` is
/// given), `b` its basis. The one body of the built curve's and the borrowed curve's JVP.
#[inline(always)]
pub(super) fn jvp_point(
    net: &[f64],
    dim: usize,
    first: usize,
    b: &PointBasis,
    r: &Rational,
    (control_tangent, weight_tangent, parameter_tangent): PointTangents<'_>,
    d: &mut [f64],
) {
    let hd = dim + 1;
    d.fill(0.0);
    for (k, (&nk, pt)) in b.values().iter().zip(net.chunks_exact(hd)).enumerate() {
        let j = first + k;
        let wj = pt[dim];
        if let Some(dp) = control_tangent {
            let rk = nk * wj / r.weight;
            for (x, v) in d.iter_mut().zip(&dp[j * dim..(j + 1) * dim]) {
                *x += rk * v;
            }
        }
        if let Some(dw) = weight_tangent {
            let s = nk * dw[j] / r.weight;
            for ((x, hc), c) in d.iter_mut().zip(pt).zip(&r.value) {
                *x += s * (hc / wj - c);
            }
        }
    }
    if let Some(dt) = parameter_tangent {
        for (x, s) in d.iter_mut().zip(&r.slope) {
            *x += s * dt;
        }
    }
}

/// `P̄_{first+k} += R_k ḡ` and `w̄_{first+k} += N_k ḡ · (P_{first+k} − C) / W` at one parameter
/// with cotangent `g` (arguments as [`jvp_point`]): the one body of the built curve's and the
/// borrowed curve's VJP (the parameter's cotangent `ḡ · C'` is the caller's).
#[inline(always)]
pub(super) fn vjp_point(
    net: &[f64],
    dim: usize,
    first: usize,
    b: &PointBasis,
    r: &Rational,
    g: &[f64],
    (mut control_cotangent, mut weight_cotangent): (Option<&mut [f64]>, Option<&mut [f64]>),
) {
    let hd = dim + 1;
    for (k, (&nk, pt)) in b.values().iter().zip(net.chunks_exact(hd)).enumerate() {
        let j = first + k;
        let wj = pt[dim];
        if let Some(gp) = control_cotangent.as_deref_mut() {
            let rk = nk * wj / r.weight;
            for (x, gi) in gp[j * dim..(j + 1) * dim].iter_mut().zip(g) {
                *x += rk * gi;
            }
        }
        if let Some(gw) = weight_cotangent.as_deref_mut() {
            let dot: f64 = g
                .iter()
                .zip(pt)
                .zip(&r.value)
                .map(|((gi, hc), c)| gi * (hc / wj - c))
                .sum();
            gw[j] += nk * dot / r.weight;
        }
    }
}

/// One homogeneous control point's share of a rational JVP (`nurbs_surface.rs`,
/// `tensor_nurbs.rs`): `d += R Ṗ + N ẇ (P − S) / W` with `R = N w / W`, for `pt = (w P, w)`
/// (`dim + 1` numbers), `n` the product of its basis functions at the point, `weight` the
/// point's `W` and `value` its `S`: the terms of [`jvp_point`] for a net.
#[inline(always)]
pub(super) fn jvp_cell(
    pt: &[f64],
    n: f64,
    (weight, value): (f64, &[f64]),
    (control_tangent, weight_tangent): (Option<&[f64]>, Option<f64>),
    d: &mut [f64],
) {
    let wj = pt[value.len()];
    if let Some(dp) = control_tangent {
        let r = n * wj / weight;
        for (x, v) in d.iter_mut().zip(dp) {
            *x += r * v;
        }
    }
    if let Some(dw) = weight_tangent {
        let s = n * dw / weight;
        for ((x, hc), c) in d.iter_mut().zip(pt).zip(value) {
            *x += s * (hc / wj - c);
        }
    }
}

/// The transpose of [`jvp_cell`] for a cotangent `g`: `P̄ += R ḡ` into `control_cotangent`
/// (the point's `dim` numbers) and `w̄ += N ḡ · (P − S) / W` into `weight_cotangent`.
#[inline(always)]
pub(super) fn vjp_cell(
    pt: &[f64],
    n: f64,
    (weight, value): (f64, &[f64]),
    g: &[f64],
    (control_cotangent, weight_cotangent): (Option<&mut [f64]>, Option<&mut f64>),
) {
    let wj = pt[value.len()];
    if let Some(gp) = control_cotangent {
        let r = n * wj / weight;
        for (x, gi) in gp.iter_mut().zip(g) {
            *x += r * gi;
        }
    }
    if let Some(gw) = weight_cotangent {
        let dot: f64 = g
            .iter()
            .zip(pt)
            .zip(value)
            .map(|((gi, hc), c)| gi * (hc / wj - c))
            .sum();
        *gw += n * dot / weight;
    }
}

impl NurbsCurve {
    /// Forward-mode derivative (JVP) of [`NurbsCurve::eval_batch`]: `out` receives `C(t_i)`
    /// (bit-for-bit `eval_batch`) and `tangent_out`
    ///
    /// `Ċ_i = Σ_j R_j(t_i) Ṗ_j + Σ_j N_j(t_i) (P_j − C(t_i)) ẇ_j / W(t_i) + C'(t_i) ṫ_i`
    ///
    /// for tangents of the Euclidean control points (`control_tangent`, `n × dim`), of the
    /// weights (`weight_tangent`, `n`) and of the parameters (`parameter_tangent`, `m`); `None`
    /// is zero. `P_j` are the Euclidean control points `(w_j P_j) / w_j` of the stored net.
    /// Basis functions and derivatives in one Cox–de Boor pass (P&T A2.2, eq. 2.9), the
    /// derivative of the quotient by P&T eq. 4.8. O(m·(p² + p·dim)).
    ///
    /// ```
    /// use lekalo::NurbsCurve;
    /// // a quarter circle: raising the middle weight pulls the midpoint towards (1, 1)
    /// let c = NurbsCurve::circle(&[0.0, 0.0], &[1.0, 0.0], &[0.0, 1.0], 1.0)?;
    /// let mut dw = vec![0.0; c.weights().len()];
    /// dw[1] = 1.0;
    /// let (mut out, mut tan) = (vec![0.0; 2], vec![0.0; 2]);
    /// c.eval_batch_jvp(&[0.125], None, Some(&dw), None, &mut out, &mut tan)?;
    /// assert!(tan[0] > 0.0 && tan[1] > 0.0);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`crate::Error::LengthMismatch`] for a buffer of the wrong length;
    /// [`crate::Error::NonFinite`] for a non-finite tangent;
    /// [`crate::Error::ParameterOutOfDomain`] at the first parameter outside the domain.
    pub fn eval_batch_jvp(
        &self,
        ts: &[f64],
        control_tangent: Option<&[f64]>,
        weight_tangent: Option<&[f64]>,
        parameter_tangent: Option<&[f64]>,
        out: &mut [f64],
        tangent_out: &mut [f64],
    ) -> Result<()> {
        let (dim, p) = (self.dim(), self.degree());
        let hom = self.homogeneous();
        let n_ctrl = hom.control_points().len();
        let n = ts.len().saturating_mul(dim);
        check_len("output buffer (parameters × dimension)", n, out.len())?;
        check_len(
            "tangent output buffer (parameters × dimension)",
            n,
            tangent_out.len(),
        )?;
        check_input(
            "control-point tangent (as the control points)",
            n_ctrl.saturating_mul(dim),
            control_tangent,
        )?;
        check_input(
            "weight tangent (one a control point)",
            n_ctrl,
            weight_tangent,
        )?;
        check_input(
            "parameter tangent (one a parameter)",
            ts.len(),
            parameter_tangent,
        )?;
        let (knots, h) = (hom.knots().as_slice(), hom.control_points().as_slice());
        let hd = dim + 1;
        let mut cursor = hom.knots().span_cursor(p);
        let mut b = PointBasis::new(p);
        let mut r = Rational::new(dim);
        let points = out
            .chunks_exact_mut(dim)
            .zip(tangent_out.chunks_exact_mut(dim));
        for (i, (&t, (o, d))) in ts.iter().zip(points).enumerate() {
            let first = b.at(knots, p, cursor.find(t)?, t);
            let net = &h[first * hd..(first + p + 1) * hd];
            r.at(net, dim, 0, &b, parameter_tangent.is_some());
            o.copy_from_slice(&r.value);
            let dt = parameter_tangent.map(|dt| dt[i]);
            let tangents = (control_tangent, weight_tangent, dt);
            jvp_point(net, dim, first, &b, &r, tangents, d);
        }
        Ok(())
    }

    /// Reverse-mode derivative (VJP) of [`NurbsCurve::eval_batch`]: for a cotangent `ḡ`
    /// (`ts.len() × dim`),
    ///
    /// `P̄_j = Σ_i R_j(t_i) ḡ_i`, `w̄_j = Σ_i N_j(t_i) ḡ_i · (P_j − C(t_i)) / W(t_i)`,
    /// `t̄_i = ḡ_i · C'(t_i)`,
    ///
    /// into `control_cotangent` (`n × dim`), `weight_cotangent` (`n`) and
    /// `parameter_cotangent` (`m`), each when given; the buffers are overwritten. The
    /// transpose of [`NurbsCurve::eval_batch_jvp`]. O(m·(p² + p·dim)).
    ///
    /// # Errors
    /// [`crate::Error::LengthMismatch`] for a buffer of the wrong length;
    /// [`crate::Error::NonFinite`] for a non-finite cotangent;
    /// [`crate::Error::ParameterOutOfDomain`] at the first parameter outside the domain.
    pub fn eval_batch_vjp(
        &self,
        ts: &[f64],
        cotangent: &[f64],
        mut control_cotangent: Option<&mut [f64]>,
        mut weight_cotangent: Option<&mut [f64]>,
        mut parameter_cotangent: Option<&mut [f64]>,
    ) -> Result<()> {
        let (dim, p) = (self.dim(), self.degree());
        let hom = self.homogeneous();
        let n_ctrl = hom.control_points().len();
        check_cotangent(
            "cotangent (parameters × dimension)",
            ts.len(),
            dim,
            cotangent,
        )?;
        zeroed_output(
            "control-point cotangent buffer (as the control points)",
            n_ctrl * dim,
            control_cotangent.as_deref_mut(),
        )?;
        zeroed_output(
            "weight cotangent buffer (one a control point)",
            n_ctrl,
            weight_cotangent.as_deref_mut(),
        )?;
        check_output(
            "parameter cotangent buffer (one a parameter)",
            ts.len(),
            parameter_cotangent.as_deref(),
        )?;
        let (knots, h) = (hom.knots().as_slice(), hom.control_points().as_slice());
        let hd = dim + 1;
        let mut cursor = hom.knots().span_cursor(p);
        let mut b = PointBasis::new(p);
        let mut r = Rational::new(dim);
        for (i, (&t, g)) in ts.iter().zip(cotangent.chunks_exact(dim)).enumerate() {
            let first = b.at(knots, p, cursor.find(t)?, t);
            let net = &h[first * hd..(first + p + 1) * hd];
            r.at(net, dim, 0, &b, parameter_cotangent.is_some());
            let outs = (
                control_cotangent.as_deref_mut(),
                weight_cotangent.as_deref_mut(),
            );
            vjp_point(net, dim, first, &b, &r, g, outs);
            if let Some(gt) = parameter_cotangent.as_deref_mut() {
                gt[i] = r.slope.iter().zip(g).map(|(s, gi)| s * gi).sum();
            }
        }
        Ok(())
    }

    /// The linearisation of [`NurbsCurve::eval_batch`] at `ts`: values (bit-for-bit
    /// `eval_batch`), `C'(t_i)`, and the sparse rows of the rational basis `R_j(t_i)`, as a
    /// [`NurbsLinearization`]. O(m·(p² + p·dim)).
    ///
    /// # Errors
    /// [`crate::Error::TooLarge`] if the arrays would exceed [`crate::MAX_SCALARS`];
    /// [`crate::Error::ParameterOutOfDomain`] at the first parameter outside the domain.
    pub fn eval_batch_linearize(&self, ts: &[f64]) -> Result<NurbsLinearization> {
        let (dim, p) = (self.dim(), self.degree());
        let w = p + 1;
        let n = check_scalars("linearisation (parameters × dimension)", ts.len(), dim)?;
        check_scalars("linearisation (parameters × (degree + 1))", ts.len(), w)?;
        let hom = self.homogeneous();
        let (knots, h) = (hom.knots().as_slice(), hom.control_points().as_slice());
        let mut lin = NurbsLinearization {
            values: vec![0.0; n],
            derivatives: vec![0.0; n],
            first: vec![0; ts.len()],
            basis: vec![0.0; ts.len() * w],
        };
        let mut cursor = hom.knots().span_cursor(p);
        let mut b = PointBasis::new(p);
        let mut r = Rational::new(dim);
        for (i, &t) in ts.iter().enumerate() {
            let first = b.at(knots, p, cursor.find(t)?, t);
            r.at(h, dim, first, &b, true);
            lin.values[i * dim..(i + 1) * dim].copy_from_slice(&r.value);
            lin.derivatives[i * dim..(i + 1) * dim].copy_from_slice(&r.slope);
            lin.first[i] = first;
            for (k, (out, &nk)) in lin.basis[i * w..(i + 1) * w]
                .iter_mut()
                .zip(b.values())
                .enumerate()
            {
                *out = nk * h[(first + k) * (dim + 1) + dim] / r.weight;
            }
        }
        Ok(lin)
    }
}
