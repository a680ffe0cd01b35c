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

    /// The surface with its patches joined where they meet within `tolerance`: at each interior
    /// knot of multiplicity `degree + 1` (patches that meet with a gap, as
    /// [`BSplineSurface::from_power_patches`] keeps them), when the last control row of the one
    /// side and the first of the other are within `tolerance` of each other point by point,
    /// both are replaced by their mean and the knot's multiplicity lowered to the degree. The
    /// surface is then continuous there (Piegl & Tiller, *The NURBS Book*, 2nd ed., §5.4: a
    /// knot of multiplicity `m` leaves `C^(p−m)`), and moves by at most `tolerance / 2`: only
    /// those two rows move, by half their distance, and the basis functions sum to one (P&T
    /// §2.2; the convex hull property). A jump above `tolerance` is kept. This is what a CAD
    /// system's reader does with patches a file prints to a few digits (Open CASCADE's IGES
    /// reader averages the two rows of poles), and what ISO 10303-42's
    /// `constraints_param_b_spline` asks (interior multiplicities at most the degree).
    /// Returns the surface and the number of knots joined, in `u` and `v` together.
    ///
    /// ```
    /// use lekalo::BSplineSurface;
    /// // two bilinear patches along u, the second's first row 1e-6 from the first's last
    /// let net = lekalo::Points::from_3d(&[
    ///     [0.0, 0.0, 0.0], [0.0, 1.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0],
    ///     [1.0, 0.0, 1e-6], [1.0, 1.0, 1e-6], [2.0, 0.0, 0.0], [2.0, 1.0, 0.0],
    /// ])?;
    /// let s = BSplineSurface::new(1, 1, vec![0., 0., 1., 1., 2., 2.], vec![0., 0., 1., 1.], net, (4, 2))?;
    /// let (joined, n) = s.join_patches_within(1e-5)?;
    /// assert_eq!((n, joined.net_size()), (1, (3, 2)));
    /// assert_eq!(joined.knots_u().as_slice(), &[0., 0., 1., 2., 2.]);
    /// assert_eq!(joined.eval(1.0, 0.0)?, vec![1.0, 0.0, 5e-7]);
    /// assert_eq!(s.join_patches_within(1e-7)?.1, 0); // the jump is kept
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for a `tolerance` that is negative or not finite.
    pub fn join_patches_within(&self, tolerance: f64) -> Result<(BSplineSurface, usize)> {
        if !(tolerance.is_finite() && tolerance >= 0.0) {
            return Err(Error::InvalidArgument {
                what: crate::What::of(crate::Arg::Tolerance, "tolerance of joined patches"),
                reason: format!(
                    "{} must be finite and not negative",
                    crate::error::readable(&tolerance)
                ),
            });
        }
        let dim = self.dim();
        let (p, q) = self.degree();
        let nv = self.net_size().1;
        let mut rows: Vec<Vec<f64>> = self
            .control_points()
            .as_slice()
            .chunks_exact(nv * dim)
            .map(<[f64]>::to_vec)
            .collect();
        let (ku, joined_u) = join_rows(self.knots_u().as_slice(), p, &mut rows, dim, tolerance);
        // along v: the columns as rows
        let nu2 = rows.len();
        let mut cols: Vec<Vec<f64>> = (0..nv)
            .map(|j| {
                rows.iter()
                    .flat_map(|r| r[j * dim..(j + 1) * dim].iter().copied())
                    .collect()
            })
            .collect();
        let (kv, joined_v) = join_rows(self.knots_v().as_slice(), q, &mut cols, dim, tolerance);
        let nv2 = cols.len();
        let mut net = Vec::with_capacity(nu2 * nv2 * dim);
        for i in 0..nu2 {
            for c in &cols {
                net.extend_from_slice(&c[i * dim..(i + 1) * dim]);
            }
        }
        let s = BSplineSurface::new(p, q, ku, kv, Points::from_flat(dim, net)?, (nu2, nv2))?;
        Ok((s, joined_u + joined_v))
    }
}

/// The knots and control rows (each a row of `dim`-points) of one direction of degree `p` with
/// each interior knot of multiplicity `p + 1` whose two rows are within `tol` point by point
/// joined (see [`BSplineSurface::join_patches_within`]), and the number joined.
fn join_rows(
    knots: &[f64],
    p: usize,
    rows: &mut Vec<Vec<f64>>,
    dim: usize,
    tol: f64,
) -> (Vec<f64>, usize) {
    let mut out_knots = knots.to_vec();
    let mut joined = 0;
    // from the last interior knot down, so the indices of those before stay
    let n = rows.len();
    let mut s = n; // the first index of a run of knots, from the right
    while s > p + 1 {
        s -= 1;
        let x = knots[s];
        let mut first = s;
        while first > 0 && knots[first - 1] == x {
            first -= 1;
        }
        let m = s + 1 - first;
        // the run knots[first..=s]: rows first − 1 and first are its two sides
        if m == p + 1 && first > p && s < n {
            let (a, b) = (&rows[first - 1], &rows[first]);
            let within = a.chunks_exact(dim).zip(b.chunks_exact(dim)).all(|(x, y)| {
                x.iter()
                    .zip(y)
                    .map(|(u, v)| (u - v) * (u - v))
                    .sum::<f64>()
                    .sqrt()
                    <= tol
            });
            if within {
                let mean: Vec<f64> = a.iter().zip(b).map(|(u, v)| 0.5 * (u + v)).collect();
                rows[first - 1] = mean;
                rows.remove(first);
                out_knots.remove(first);
                joined += 1;
            }
        }
        s = first;
    }
    (out_knots, joined)
}
