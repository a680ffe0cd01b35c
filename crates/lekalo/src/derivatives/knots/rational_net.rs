//! The knot derivatives of rational nets, [`NurbsSurface`] and [`TensorNurbs`]
//! (`docs/theory/derivatives.md`, "Knots"): as for a NURBS curve, the homogeneous net
//! `H = (w P, w)` is a B-spline net in `dim + 1`, whose knot derivatives `∂(A, W)/∂τᵃ_k` are
//! the kernel of `net.rs`; the quotient rule `∂S/∂τᵃ_k = (∂A/∂τᵃ_k − S ∂W/∂τᵃ_k) / W` gives
//! the JVP, and the VJP folds the quotient into the homogeneous cotangent
//! `ĝ = (ḡ / W, −(ḡ · S) / W)`, one a point.

use crate::derivatives::checks::{check_cotangent, check_len, check_scalars};
use crate::error::Result;
use crate::surface::NurbsSurface;
use crate::tensor::TensorNurbs;

/// `Ṡ = (Ȧ − S Ẇ) / W` at every point: `values` the rational values `S` (`dim` a point),
/// `hom` and `hom_tangent` the homogeneous values `(A, W)` and their tangent (`dim + 1` a
/// point).
fn quotient_tangent(
    dim: usize,
    values: &[f64],
    hom: &[f64],
    hom_tangent: &[f64],
    tangent_out: &mut [f64],
) {
    let hd = dim + 1;
    let points = values
        .chunks_exact(dim)
        .zip(hom.chunks_exact(hd).zip(hom_tangent.chunks_exact(hd)));
    for (d, (s, (h, hdot))) in tangent_out.chunks_exact_mut(dim).zip(points) {
        let (w, dw) = (h[dim], hdot[dim]);
        for ((x, a), c) in d.iter_mut().zip(hdot).zip(s) {
            *x = (a - c * dw) / w;
        }
    }
}

/// `S = A / W` at every point from the homogeneous values `hom` (`dim + 1` a point) into
/// `out`, one division a coordinate: the values the evaluation itself computes, since it
/// projects the same homogeneous values (P&T eq. 4.5).
fn project(dim: usize, hom: &[f64], out: &mut [f64]) {
    for (o, h) in out.chunks_exact_mut(dim).zip(hom.chunks_exact(dim + 1)) {
        for (x, a) in o.iter_mut().zip(h) {
            *x = a / h[dim];
        }
    }
}

/// The homogeneous cotangent `ĝ = (ḡ / W, −(ḡ · S) / W)` at every point, `S = A / W`, from
/// the homogeneous values `hom` (`dim + 1` a point) and the cotangent `g` (`dim` a point),
/// written over `hom`.
fn homogeneous_cotangent(dim: usize, g: &[f64], hom: &mut [f64]) {
    for (h, g) in hom.chunks_exact_mut(dim + 1).zip(g.chunks_exact(dim)) {
        let w = h[dim];
        let gs: f64 = g.iter().zip(&h[..dim]).map(|(a, x)| a * (x / w)).sum();
        for (x, a) in h.iter_mut().zip(g) {
            *x = a / w;
        }
        h[dim] = -gs / w;
    }
}

impl NurbsSurface {
    /// Forward-mode derivative (JVP) of [`NurbsSurface::eval_batch`] with respect to the knots
    /// of each direction: `out` receives `S(u_i, v_i)` (bit-for-bit `eval_batch`) and
    /// `tangent_out`
    ///
    /// `Ṡ_i = Σ_k τ̇ᵘ_k ∂S/∂τᵘ_k + Σ_l τ̇ᵛ_l ∂S/∂τᵛ_l`, `∂S/∂τ = (∂A/∂τ − S ∂W/∂τ) / W`,
    ///
    /// with `(A, W) = Σ N_k(u) N_l(v) (w_kl P_kl, w_kl)` the homogeneous surface, whose knot
    /// derivative is [`crate::BSplineSurface::eval_batch_knot_jvp`]'s
    /// (`docs/theory/derivatives.md`, "Knots"). `knot_tangent_u` (`knot_tangent_v`) has one
    /// number a knot of that direction (`None` is zero); the tangents of each direction's
    /// `p + 1` first and last knots are ignored, and at a knot of multiplicity `μ > 1` the
    /// derivative is one-sided, as for a curve. O(m·(p³ + q³ + (p² + q²)·dim +
    /// (p + 1)(q + 1)·dim)).
    ///
    /// ```
    /// use lekalo::{NurbsSurface, Points};
    /// // equal weights: the NURBS is the B-spline f(u, v) = g(u) with g the hat of
    /// // [0, 0, ½, 1, 1], so g(¼) = ¼ / τ_2 and ∂f/∂τᵘ_2 = −¼ / τ_2² = −1
    /// let ku = vec![0.0, 0.0, 0.5, 1.0, 1.0];
    /// let kv = vec![0.0, 0.0, 1.0, 1.0];
    /// let net = Points::from_flat(1, vec![0.0, 0.0, 1.0, 1.0, 0.0, 0.0])?;
    /// let s = NurbsSurface::new(1, 1, ku, kv, net, vec![3.0; 6], (3, 2))?;
    /// let (mut out, mut tan) = ([0.0], [0.0]);
    /// let du = [0.0, 0.0, 1.0, 0.0, 0.0];
    /// s.eval_batch_knot_jvp(&[[0.25, 0.5]], Some(&du), None, &mut out, &mut tan)?;
    /// assert_eq!((out[0], tan[0]), (0.5, -1.0));
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`crate::Error::LengthMismatch`] for a buffer of the wrong length;
    /// [`crate::Error::NonFinite`] for a non-finite tangent;
    /// [`crate::Error::TooLarge`] if the homogeneous values would not fit in memory;
    /// [`crate::Error::ParameterOutOfDomain`] at the first pair outside the domain.
    pub fn eval_batch_knot_jvp(
        &self,
        uv: &[[f64; 2]],
        knot_tangent_u: Option<&[f64]>,
        knot_tangent_v: Option<&[f64]>,
        out: &mut [f64],
        tangent_out: &mut [f64],
    ) -> Result<()> {
        let dim = self.dim();
        let m = uv.len().saturating_mul(dim);
        check_len("output buffer (parameter pairs × dimension)", m, out.len())?;
        check_len(
            "tangent output buffer (parameter pairs × dimension)",
            m,
            tangent_out.len(),
        )?;
        let len = check_scalars("homogeneous values (parameter pairs)", uv.len(), dim + 1)?;
        let (mut hom, mut hom_tangent) = (vec![0.0; len], vec![0.0; len]);
        self.homogeneous().eval_batch_knot_jvp(
            uv,
            knot_tangent_u,
            knot_tangent_v,
            &mut hom,
            &mut hom_tangent,
        )?;
        project(dim, &hom, out);
        quotient_tangent(dim, out, &hom, &hom_tangent, tangent_out);
        Ok(())
    }

    /// Reverse-mode derivative (VJP) of [`NurbsSurface::eval_batch`] with respect to the
    /// knots: for a cotangent `ḡ` (`uv.len() × dim`), `τ̄ᵘ_k = Σ_i ḡ_i · ∂S(u_i, v_i)/∂τᵘ_k`
    /// into `knot_cotangent_u` and likewise along `v` (each when given; overwritten), as
    /// `Σ_i ĝ_i · ∂(A, W)/∂τ` with `ĝ_i = (ḡ_i / W, −(ḡ_i · S) / W)`: the transpose of
    /// [`NurbsSurface::eval_batch_knot_jvp`] (`docs/theory/derivatives.md`, "Knots"). Each
    /// direction's `p + 1` first and last knots get zero.
    ///
    /// # Errors
    /// [`crate::Error::LengthMismatch`] for a buffer of the wrong length;
    /// [`crate::Error::NonFinite`] for a non-finite cotangent;
    /// [`crate::Error::TooLarge`] if the homogeneous values would not fit in memory;
    /// [`crate::Error::ParameterOutOfDomain`] at the first pair outside the domain.
    pub fn eval_batch_knot_vjp(
        &self,
        uv: &[[f64; 2]],
        cotangent: &[f64],
        knot_cotangent_u: Option<&mut [f64]>,
        knot_cotangent_v: Option<&mut [f64]>,
    ) -> Result<()> {
        let dim = self.dim();
        check_cotangent(
            "cotangent (parameter pairs × dimension)",
            uv.len(),
            dim,
            cotangent,
        )?;
        let len = check_scalars("homogeneous values (parameter pairs)", uv.len(), dim + 1)?;
        let mut hom = vec![0.0; len];
        let h = self.homogeneous();
        h.eval_batch(uv, &mut hom)?;
        homogeneous_cotangent(dim, cotangent, &mut hom);
        h.eval_batch_knot_vjp(uv, &hom, knot_cotangent_u, knot_cotangent_v)
    }
}

impl TensorNurbs {
    /// Forward-mode derivative (JVP) of [`TensorNurbs::eval_batch`] with respect to the knots
    /// of each direction, at the points `xs` (`N` coordinates a point, flat): `out` receives
    /// `R(x_r)` (bit-for-bit `eval_batch`) and `tangent_out`
    /// `Ṙ_r = Σ_a Σ_k τ̇ᵃ_k (∂A/∂τᵃ_k − R ∂W/∂τᵃ_k) / W`, with `(A, W)` the homogeneous
    /// spline, whose knot derivatives are [`crate::TensorBSpline::eval_batch_knot_jvp`]'s
    /// (`docs/theory/derivatives.md`, "Knots"). `knot_tangents` has one entry a direction (one
    /// number a knot, or `None`); the conventions are the B-spline's (interior knots only,
    /// one-sided at multiple knots).
    ///
    /// # Errors
    /// [`crate::Error::LengthMismatch`] for a buffer of the wrong length (`xs` not a multiple
    /// of `N`, `knot_tangents` not one a direction, a tangent not one a knot of its direction);
    /// [`crate::Error::NonFinite`] for a non-finite tangent;
    /// [`crate::Error::TooLarge`] if the homogeneous values would not fit in memory;
    /// [`crate::Error::ParameterOutOfDomain`] at the first point outside the domain.
    pub fn eval_batch_knot_jvp(
        &self,
        xs: &[f64],
        knot_tangents: &[Option<&[f64]>],
        out: &mut [f64],
        tangent_out: &mut [f64],
    ) -> Result<()> {
        let h = self.homogeneous();
        let (dim, m) = (self.dim(), h.points_in(xs)?);
        let len = m.saturating_mul(dim);
        check_len("output buffer (points × dimension)", len, out.len())?;
        check_len(
            "tangent output buffer (points × dimension)",
            len,
            tangent_out.len(),
        )?;
        let hlen = check_scalars("homogeneous values (points)", m, dim + 1)?;
        let (mut hom, mut hom_tangent) = (vec![0.0; hlen], vec![0.0; hlen]);
        h.eval_batch_knot_jvp(xs, knot_tangents, &mut hom, &mut hom_tangent)?;
        project(dim, &hom, out);
        quotient_tangent(dim, out, &hom, &hom_tangent, tangent_out);
        Ok(())
    }

    /// Reverse-mode derivative (VJP) of [`TensorNurbs::eval_batch`] with respect to the knots:
    /// for a cotangent `ḡ` (`m × dim`), `τ̄ᵃ_k = Σ_r ḡ_r · ∂R(x_r)/∂τᵃ_k` into
    /// `knot_cotangents[a]` (one entry a direction, overwritten, or `None`), as
    /// `Σ_r ĝ_r · ∂(A, W)/∂τᵃ_k` with `ĝ_r = (ḡ_r / W, −(ḡ_r · R) / W)`: the transpose of
    /// [`TensorNurbs::eval_batch_knot_jvp`] (`docs/theory/derivatives.md`, "Knots"). Each
    /// direction's `p_a + 1` first and last knots get zero.
    ///
    /// # Errors
    /// [`crate::Error::LengthMismatch`] for a buffer of the wrong length;
    /// [`crate::Error::NonFinite`] for a non-finite cotangent;
    /// [`crate::Error::TooLarge`] if the homogeneous values would not fit in memory;
    /// [`crate::Error::ParameterOutOfDomain`] at the first point outside the domain.
    pub fn eval_batch_knot_vjp(
        &self,
        xs: &[f64],
        cotangent: &[f64],
        knot_cotangents: &mut [Option<&mut [f64]>],
    ) -> Result<()> {
        let h = self.homogeneous();
        let (dim, m) = (self.dim(), h.points_in(xs)?);
        check_cotangent("cotangent (points × dimension)", m, dim, cotangent)?;
        let hlen = check_scalars("homogeneous values (points)", m, dim + 1)?;
        let mut hom = vec![0.0; hlen];
        h.eval_batch(xs, None, &mut hom)?;
        homogeneous_cotangent(dim, cotangent, &mut hom);
        h.eval_batch_knot_vjp(xs, &hom, knot_cotangents)
    }
}
