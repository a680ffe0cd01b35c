//! The knot derivatives of NURBS curve evaluation `C = A / W` (`docs/theory/derivatives.md`,
//! "Knots"): [`KnotWeights`] applied to the homogeneous control points `(w_j P_j, w_j)` gives
//! `∂A/∂τ_k` and `∂W/∂τ_k` at once (the homogeneous curve is a B-spline in `dim + 1`), and the
//! quotient rule `∂C/∂τ_k = (∂A/∂τ_k − C ∂W/∂τ_k) / W` the rest. The VJP folds the quotient
//! into the cotangent instead: `ḡ · ∂C/∂τ_k = ĝ · ∂(A, W)/∂τ_k` with
//! `ĝ = (ḡ / W, −(ḡ · C) / W)`, one homogeneous cotangent a parameter.

use super::KnotWeights;
use crate::curve::NurbsCurve;
use crate::derivatives::checks::{check_cotangent, check_input, check_len};
use crate::derivatives::curve::PointBasis;
use crate::derivatives::nurbs::Rational;
use crate::error::Result;

impl NurbsCurve {
    /// Forward-mode derivative (JVP) of [`NurbsCurve::eval_batch`] with respect to the knots:
    /// `out` receives `C(t_i)` (bit-for-bit `eval_batch`) and `tangent_out`
    ///
    /// `Ċ_i = Σ_k τ̇_k ∂C(t_i)/∂τ_k`, `∂C/∂τ_k = (∂A/∂τ_k − C ∂W/∂τ_k) / W`,
    ///
    /// for a knot tangent `τ̇` (`knot_tangent`, one number a knot), `A = Σ_j N_j w_j P_j` and
    /// `W = Σ_j N_j w_j` the homogeneous curve, whose knot derivative is
    /// [`crate::BSplineCurve::eval_batch_knot_jvp`]'s formula on the homogeneous control points
    /// `(w_j P_j, w_j)`: `∂(A, W)/∂τ_k = − Σ_{j=k−p}^{k} (H_j − H_{j−1}) / (τ_{j+p} − τ_j) ·
    /// N_{j,p,τ*}(t)` (`docs/theory/derivatives.md`, "Knots"). The conventions are the
    /// B-spline's: only the interior knots `τ_{p+1} … τ_{n−1}` count (the tangents of the
    /// `p + 1` first and last are ignored), and at a knot of multiplicity `μ > 1` the derivative
    /// is one-sided. O(m·p·(p² + p·dim)).
    ///
    /// ```
    /// use lekalo::{NurbsCurve, Points};
    /// // equal weights: the NURBS curve is the B-spline, and so is its knot derivative
    /// let ctrl = Points::from_flat(1, vec![0.0, 1.0, 0.0])?;
    /// let c = NurbsCurve::new(1, vec![0.0, 0.0, 0.5, 1.0, 1.0], ctrl, vec![2.0; 3])?;
    /// let (mut out, mut tan) = (vec![0.0; 1], vec![0.0; 1]);
    /// c.eval_batch_knot_jvp(&[0.25], &[0.0, 0.0, 1.0, 0.0, 0.0], &mut out, &mut tan)?;
    /// // C(0.25) = 0.25 / τ_2, so ∂C/∂τ_2 = −0.25 / τ_2² = −1
    /// assert_eq!((out[0], tan[0]), (0.5, -1.0));
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`crate::Error::LengthMismatch`] for a buffer of the wrong length (`out` and
    /// `tangent_out`: `ts.len() · dim`; `knot_tangent`: as the knots);
    /// [`crate::Error::NonFinite`] for a non-finite tangent;
    /// [`crate::Error::ParameterOutOfDomain`] at the first parameter outside the domain.
    pub fn eval_batch_knot_jvp(
        &self,
        ts: &[f64],
        knot_tangent: &[f64],
        out: &mut [f64],
        tangent_out: &mut [f64],
    ) -> Result<()> {
        let (p, dim) = (self.degree(), self.dim());
        let hom = self.homogeneous();
        let (knots, h) = (hom.knots().as_slice(), hom.control_points().as_slice());
        let (n, hd) = (hom.control_points().len(), dim + 1);
        let m = ts.len().saturating_mul(dim);
        check_len("output buffer (parameters × dimension)", m, out.len())?;
        check_len(
            "tangent output buffer (parameters × dimension)",
            m,
            tangent_out.len(),
        )?;
        check_input("knot tangent (one a knot)", knots.len(), Some(knot_tangent))?;
        let mut cursor = hom.knots().span_cursor(p);
        let mut basis = PointBasis::new(p);
        let mut r = Rational::new(dim);
        let mut weights = KnotWeights::new(p);
        // `(Ȧ, Ẇ)`, the homogeneous curve's tangent at one parameter
        let mut hdot = vec![0.0; hd];
        let point = move |j: usize| &h[j * hd..(j + 1) * hd];
        let points = out
            .chunks_exact_mut(dim)
            .zip(tangent_out.chunks_exact_mut(dim));
        for (&t, (o, d)) in ts.iter().zip(points) {
            let span = cursor.find(t)?;
            let first = basis.at(knots, p, span, t);
            r.at(h, dim, first, &basis, false);
            o.copy_from_slice(&r.value);
            hdot.fill(0.0);
            weights.at(knots, n, span, t);
            for k in weights.knots() {
                if knot_tangent[k] != 0.0 {
                    weights.add_derivative(k, knot_tangent[k], point, &mut hdot);
                }
            }
            let dw = hdot[dim];
            for ((x, a), c) in d.iter_mut().zip(&hdot).zip(&r.value) {
                *x = (a - c * dw) / r.weight;
            }
        }
        Ok(())
    }

    /// Reverse-mode derivative (VJP) of [`NurbsCurve::eval_batch`] with respect to the knots:
    /// for a cotangent `ḡ` (`ts.len() × dim`, point-major), `τ̄_k = Σ_i ḡ_i · ∂C(t_i)/∂τ_k`
    /// into `knot_cotangent` (one a knot, overwritten), with the derivative of
    /// [`NurbsCurve::eval_batch_knot_jvp`], as `Σ_i ĝ_i · ∂(A, W)(t_i)/∂τ_k` for the homogeneous
    /// cotangent `ĝ_i = (ḡ_i / W, −(ḡ_i · C(t_i)) / W)` (`docs/theory/derivatives.md`,
    /// "Knots"): the transpose of the JVP, `⟨ḡ, J τ̇⟩ = ⟨Jᵀ ḡ, τ̇⟩`. The `p + 1` first and last
    /// knots get zero. O(m·p·(p² + p·dim)).
    ///
    /// ```
    /// use lekalo::NurbsCurve;
    /// // the unit circle: four quarter arcs on the knots [0,0,0, ¼,¼, ½,½, ¾,¾, 1,1,1]
    /// let c = NurbsCurve::circle(&[0.0, 0.0], &[1.0, 0.0], &[0.0, 1.0], 1.0)?;
    /// let p = c.eval(0.3)?;
    /// // the radial cotangent C(t): how the knots move |C(t)|² / 2
    /// let mut grad = vec![f64::NAN; c.knots().len()];
    /// c.eval_batch_knot_vjp(&[0.3], &p, &mut grad)?;
    /// // one copy of the double knot ¼ moved alone leaves the circle; the two moved together
    /// // only reparametrise the quarter arc
    /// assert!(grad[3].abs() > 0.1 && (grad[3] + grad[4]).abs() < 1e-14);
    /// // the end knots are held fixed
    /// assert!(grad[..3].iter().chain(&grad[9..]).all(|&g| g == 0.0));
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`crate::Error::LengthMismatch`] for a buffer of the wrong length;
    /// [`crate::Error::NonFinite`] for a non-finite cotangent;
    /// [`crate::Error::ParameterOutOfDomain`] at the first parameter outside the domain.
    pub fn eval_batch_knot_vjp(
        &self,
        ts: &[f64],
        cotangent: &[f64],
        knot_cotangent: &mut [f64],
    ) -> Result<()> {
        let (p, dim) = (self.degree(), self.dim());
        let hom = self.homogeneous();
        let (knots, h) = (hom.knots().as_slice(), hom.control_points().as_slice());
        let (n, hd) = (hom.control_points().len(), dim + 1);
        check_cotangent(
            "cotangent (parameters × dimension)",
            ts.len(),
            dim,
            cotangent,
        )?;
        check_len(
            "knot cotangent buffer (one a knot)",
            knots.len(),
            knot_cotangent.len(),
        )?;
        knot_cotangent.fill(0.0);
        let mut cursor = hom.knots().span_cursor(p);
        let mut basis = PointBasis::new(p);
        let mut r = Rational::new(dim);
        let mut weights = KnotWeights::new(p);
        let mut g_hom = vec![0.0; hd];
        let point = move |j: usize| &h[j * hd..(j + 1) * hd];
        for (&t, g) in ts.iter().zip(cotangent.chunks_exact(dim)) {
            let span = cursor.find(t)?;
            let first = basis.at(knots, p, span, t);
            r.at(h, dim, first, &basis, false);
            let gc: f64 = g.iter().zip(&r.value).map(|(a, c)| a * c).sum();
            for (x, a) in g_hom.iter_mut().zip(g) {
                *x = a / r.weight;
            }
            g_hom[dim] = -gc / r.weight;
            weights.at(knots, n, span, t);
            for k in weights.knots() {
                knot_cotangent[k] += weights.cotangent(k, &g_hom, point);
            }
        }
        Ok(())
    }
}
