//! Surfaces given as a grid of polynomial patches in local power form (the parametric spline
//! surfaces of IGES entity 114) converted exactly to tensor-product B-splines.

use crate::curve::bspline::BSplineCurve;
use crate::error::{Error, Result, MAX_SCALARS};
use crate::points::Points;
use crate::pp::ppform::PiecewisePolynomial;
use crate::surface::bspline::BSplineSurface;

impl BSplineSurface {
    /// The tensor-product B-spline of a grid of polynomial patches in local power form: patch
    /// `(i, j)` on `[ξ_i, ξ_{i+1}] × [η_j, η_{j+1}]` is
    /// `S(u, v) = Σ_{r<ku} Σ_{s<kv} a_{ijrs} (u − ξ_i)^r (v − η_j)^s`, with
    /// `a_{ijrs}` at `coefficients[(((i·nj + j)·ku + r)·kv + s)·dim + d]` (`nj` patches along `v`).
    ///
    /// The conversion is that of [`BSplineCurve::from_piecewise_polynomial`] applied along each
    /// direction (a tensor-product spline is a spline in `v` whose coefficients are splines in
    /// `u`, de Boor "A Practical Guide to Splines" XVII): first in `v`, all patch rows and
    /// powers of `u` at once so that they share one knot vector, then in `u` on the resulting
    /// control net. Exact to rounding; the knots follow the patches' smoothness (continuity
    /// found with [`crate::curve::POWER_FORM_CONTINUITY_RTOL`]), and patches that meet with a
    /// gap keep it (a knot of multiplicity `ku` or `kv`).
    ///
    /// ```
    /// use lekalo::BSplineSurface;
    /// // the saddle z = u·v on [0, 1] × [0, 2] as 1 × 2 bilinear patches (order 2 × 2), 3-D
    /// let mut c = Vec::new();
    /// for v0 in [0.0, 1.0] {
    ///     // (u, v0 + t, u·(v0 + t)): powers u^r t^s, (r, s) = (0,0), (0,1), (1,0), (1,1)
    ///     c.extend([0.0, v0, 0.0,  0.0, 1.0, 0.0,  1.0, 0.0, v0,  0.0, 0.0, 1.0]);
    /// }
    /// let s = BSplineSurface::from_power_patches(&[0.0, 1.0], &[0.0, 1.0, 2.0], (2, 2), 3, &c)?;
    /// let p = s.eval(0.5, 1.5)?;
    /// assert!((p[0] - 0.5).abs() < 1e-15 && (p[1] - 1.5).abs() < 1e-15 && (p[2] - 0.75).abs() < 1e-15);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::LengthMismatch`] for a wrong number of coefficients; [`Error::TooLarge`]; errors
    /// of [`PiecewisePolynomial::new`] (breakpoints not increasing, non-finite coefficients).
    pub fn from_power_patches(
        u_breakpoints: &[f64],
        v_breakpoints: &[f64],
        (ku, kv): (usize, usize),
        dim: usize,
        coefficients: &[f64],
    ) -> Result<Self> {
        let ni = u_breakpoints.len().saturating_sub(1);
        let nj = v_breakpoints.len().saturating_sub(1);
        let expected = [ni, nj, ku, kv, dim]
            .iter()
            .try_fold(1usize, |a, &b| a.checked_mul(b))
            .filter(|&n| n <= MAX_SCALARS)
            .ok_or(Error::TooLarge {
                what: "power-form patch coefficients".into(),
                size: usize::MAX,
                max: MAX_SCALARS,
            })?;
        if coefficients.len() != expected {
            return Err(Error::LengthMismatch {
                what: "patch coefficients (u patches × v patches × u order × v order × dim)".into(),
                expected,
                got: coefficients.len(),
            });
        }
        // along v: one piecewise polynomial with every (patch row i, power r, coordinate d) as a
        // coordinate, c_v[(j·kv + s)·dv + (i·ku + r)·dim + d]
        let dv = ni * ku * dim;
        let mut cv = vec![0.0; expected];
        for i in 0..ni {
            for j in 0..nj {
                for r in 0..ku {
                    for s in 0..kv {
                        for d in 0..dim {
                            let src = (((i * nj + j) * ku + r) * kv + s) * dim + d;
                            cv[(j * kv + s) * dv + (i * ku + r) * dim + d] = coefficients[src];
                        }
                    }
                }
            }
        }
        let along_v = PiecewisePolynomial::new(v_breakpoints.to_vec(), kv, dv, cv)?;
        let bv = BSplineCurve::from_piecewise_polynomial(&along_v)?;
        let nv = bv.control_points().len();
        // along u: coordinates (l, d) of the v control point l, c_u[(i·ku + r)·du + l·dim + d]
        let du = nv * dim;
        let mut cu = vec![0.0; ni * ku * du];
        for (l, row) in bv.control_points().as_slice().chunks_exact(dv).enumerate() {
            for (ir, vals) in row.chunks_exact(dim).enumerate() {
                let at = ir * du + l * dim;
                cu[at..at + dim].copy_from_slice(vals);
            }
        }
        let along_u = PiecewisePolynomial::new(u_breakpoints.to_vec(), ku, du, cu)?;
        let bu = BSplineCurve::from_piecewise_polynomial(&along_u)?;
        let nu = bu.control_points().len();
        let (pu, ku_vec, net) = bu.into_parts();
        BSplineSurface::from_knot_vectors(
            pu,
            bv.degree(),
            ku_vec,
            bv.knots().clone(),
            Points::from_flat(dim, net.into_vec())?,
            (nu, nv),
        )
    }
}
