//! The space of bicubic splines on the sphere: clamped in the colatitude `θ ∈ [0, π]`, periodic
//! in the longitude `φ ∈ [φ₀, φ₀ + 2π]`, one value at each pole and, optionally, a derivative
//! across each pole of the form `∂s/∂θ = a cos φ + b sin φ` (`docs/theory/sphere.md#space`;
//! Dierckx, *Curve and Surface Fitting with Splines*, 1993, §11.1–11.2).
//!
//! The tensor coefficients `c_{i,j}` (`i < nθ` the θ B-splines, `j < n_φ + 3` the φ B-splines,
//! the last three repeating the first three) are affine in the free interior rows and the six
//! pole parameters `d = (v₀, a₀, b₀, v₁, a₁, b₁)` (value, cosine and sine coefficient of the
//! derivative at `θ = 0` and at `θ = π`):
//!
//! ```text
//!   c_{0,j}      = v₀                      c_{nθ−1,j} = v₁
//!   c_{1,j}      = v₀ + h₀/3 (a₀ γ_j + b₀ σ_j)      (continuity at θ = 0)
//!   c_{nθ−2,j}   = v₁ − h₁/3 (a₁ γ_j + b₁ σ_j)      (continuity at θ = π)
//! ```
//!
//! with `h₀` (`h₁`) the first (last) θ knot span and `γ`, `σ` the coefficients of the periodic
//! cubic splines interpolating `cos φ`, `sin φ` at the φ knots (FITPACK `fpsphe`, `fpgrsp`).

use crate::error::{Error, Result};
use crate::fit::cyclic::CyclicQr;
use crate::points::Points;
use crate::tensor::TensorBSpline;

/// What a fit imposes at one pole.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PoleCondition {
    /// The value at the pole: `None` to fit it; a number with [`exact`](Self::exact) to impose
    /// it, without to fit it with the value counted as one more datum (SciPy's `pole_values`).
    pub value: Option<f64>,
    /// Impose [`value`](Self::value) exactly (SciPy's `pole_exact`).
    pub exact: bool,
    /// Continuity of the first derivative across the pole: `∂s/∂θ = a cos φ + b sin φ` there
    /// (SciPy's `pole_continuity`).
    pub continuity: bool,
    /// With [`continuity`](Self::continuity), `a = b = 0`: the spline is flat at the pole
    /// (SciPy's `pole_flat`).
    pub flat: bool,
}

/// The spline space of a fit on the sphere: knots, pole structure and the periodic cubic
/// splines of `cos φ` and `sin φ` (module docs).
#[derive(Debug, Clone)]
pub(crate) struct SphereSpace {
    /// Full θ knots: `0` four times, the interior knots, `π` four times.
    pub(crate) tt: Vec<f64>,
    /// Full φ knots: the period `[φ₀, φ₀ + 2π]` with its breakpoints, extended by three
    /// knots each side periodically.
    pub(crate) tp: Vec<f64>,
    /// Number of φ spans in a period (free coefficients per θ row).
    pub(crate) npp: usize,
    /// Number of θ B-splines.
    pub(crate) nt: usize,
    /// Derivative rows at `θ = 0` and `θ = π` (continuity across the pole).
    pub(crate) c1: [bool; 2],
    /// `(γ_j, σ_j)` for `j < npp`.
    pub(crate) cos_sin: Vec<[f64; 2]>,
}

/// `π` as FITPACK writes its knots.
pub(crate) const PI: f64 = std::f64::consts::PI;
/// The period of the longitude.
pub(crate) const TWO_PI: f64 = 2.0 * std::f64::consts::PI;

impl SphereSpace {
    /// The space with the interior θ knots `theta_knots` (in `(0, π)`, increasing), the period
    /// starting at `phi0` and the interior φ breakpoints `phi_knots` (in `(φ₀, φ₀ + 2π)`,
    /// increasing), with derivative rows at the poles where `c1` says. The caller has checked
    /// the knots.
    pub(crate) fn new(
        theta_knots: &[f64],
        phi0: f64,
        phi_knots: &[f64],
        c1: [bool; 2],
    ) -> Result<Self> {
        let mut tt = vec![0.0; 4];
        tt.extend_from_slice(theta_knots);
        tt.extend([PI; 4]);
        let nt = tt.len() - 4;
        let npp = phi_knots.len() + 1;
        // tp[3] = φ₀, tp[3 + npp] = φ₀ + 2π; the three knots beyond each end repeat the
        // period (recursively, so a period of fewer than three spans works too)
        let np = npp + 7;
        let mut tp = vec![0.0; np];
        tp[3] = phi0;
        tp[4..3 + npp].copy_from_slice(phi_knots);
        tp[3 + npp] = phi0 + TWO_PI;
        for l in (0..3).rev() {
            tp[l] = tp[l + npp] - TWO_PI;
        }
        for l in 4 + npp..np {
            tp[l] = tp[l - npp] + TWO_PI;
        }
        let c1 = [c1[0] && nt >= 4, c1[1] && nt >= 4];
        if nt < 2 + usize::from(c1[0]) + usize::from(c1[1]) {
            return Err(Error::InvalidArgument {
                what: "theta knots".into(),
                reason: format!(
                    "{nt} θ B-splines cannot carry the pole rows; give more interior knots"
                ),
            });
        }
        let cos_sin = if c1[0] || c1[1] {
            periodic_cos_sin(&tp, npp)?
        } else {
            vec![[0.0; 2]; npp]
        };
        Ok(SphereSpace {
            tt,
            tp,
            npp,
            nt,
            c1,
            cos_sin,
        })
    }

    /// The free θ rows `first..end` (between the pole rows).
    pub(crate) fn free_rows(&self) -> std::ops::Range<usize> {
        let first = 1 + usize::from(self.c1[0]);
        let end = self.nt - 1 - usize::from(self.c1[1]);
        first..end.max(first)
    }

    /// The factor of `(a γ_j + b σ_j)` in the derivative row of pole `pole` (`h/3`, negative at
    /// `θ = π`: the derivative there is `3 (c_{nθ−1} − c_{nθ−2}) / h₁`).
    pub(crate) fn derivative_factor(&self, pole: usize) -> f64 {
        if pole == 0 {
            (self.tt[4] - self.tt[3]) / 3.0
        } else {
            (self.tt[self.nt - 1] - self.tt[self.nt]) / 3.0
        }
    }

    /// The derivative row of pole `pole` (1 or `nθ − 2`), if it has one.
    pub(crate) fn derivative_row(&self, pole: usize) -> Option<usize> {
        self.c1[pole].then(|| if pole == 0 { 1 } else { self.nt - 2 })
    }

    /// The coefficient `c_{i,j}` of a pole row `i` (`j < npp`) as `(pole, [∂/∂v, ∂/∂a, ∂/∂b])`,
    /// `None` for a free row.
    pub(crate) fn pole_row(&self, i: usize, j: usize) -> Option<(usize, [f64; 3])> {
        let [g, s] = self.cos_sin[j];
        if i == 0 {
            Some((0, [1.0, 0.0, 0.0]))
        } else if i + 1 == self.nt {
            Some((1, [1.0, 0.0, 0.0]))
        } else if i == 1 && self.c1[0] {
            let f = self.derivative_factor(0);
            Some((0, [1.0, f * g, f * s]))
        } else if i + 2 == self.nt && self.c1[1] {
            let f = self.derivative_factor(1);
            Some((1, [1.0, f * g, f * s]))
        } else {
            None
        }
    }

    /// The tensor coefficients (`nθ × (npp + 3)`, θ slowest) of the pole parameters `d` and
    /// the free rows `free` (`free_rows().len() × npp`).
    pub(crate) fn expand(&self, d: &[f64; 6], free: &[f64]) -> Vec<f64> {
        let (nt, npp) = (self.nt, self.npp);
        let np4 = npp + 3;
        let rows = self.free_rows();
        let mut c = vec![0.0; nt * np4];
        for i in 0..nt {
            for j in 0..np4 {
                let jj = j % npp;
                c[i * np4 + j] = match self.pole_row(i, jj) {
                    Some((p, g)) => g[0] * d[3 * p] + g[1] * d[3 * p + 1] + g[2] * d[3 * p + 2],
                    None => free[(i - rows.start) * npp + jj],
                };
            }
        }
        c
    }

    /// The tensor-product spline of the coefficients `c` of [`SphereSpace::expand`].
    pub(crate) fn spline(&self, c: Vec<f64>) -> Result<TensorBSpline> {
        TensorBSpline::new(
            vec![3, 3],
            vec![self.tt.clone(), self.tp.clone()],
            Points::from_flat(1, c)?,
        )
    }
}

/// The coefficients `(γ_j, σ_j)` of the periodic cubic splines on the knots `tp` that
/// interpolate `cos φ` and `sin φ` at the `npp` knots of a period (FITPACK `fpsphe`): a cyclic
/// tridiagonal system (three B-splines are non-zero at a knot), solved by the cyclic banded QR
/// in O(npp). Fewer than four spans: zero (FITPACK's choice; the spline is then too coarse to
/// carry a derivative across the pole).
fn periodic_cos_sin(tp: &[f64], npp: usize) -> Result<Vec<[f64; 2]>> {
    if npp < 4 {
        return Ok(vec![[0.0; 2]; npp]);
    }
    let mut qr = CyclicQr::new(npp, 3, 3, 2);
    let mut scratch = crate::basis::BasisScratch::new(3);
    let mut b = [0.0; 4];
    // the two rows that wrap around the corner first, so that first band columns never
    // decrease; B-spline l − 3 + q is coefficient (i + q) mod npp at the knot l = i + 3
    for i in [npp - 2, npp - 1].into_iter().chain(0..npp - 2) {
        let l = i + 3;
        let arg = tp[l];
        crate::basis::basis_funs_into(tp, 3, l, arg, &mut scratch, &mut b);
        let mut y = [arg.cos(), arg.sin()];
        qr.add_cyclic(i, &b[..3], &mut y);
    }
    let mut x = vec![0.0; 2 * npp];
    qr.solve(&mut x).map_err(|_| Error::SingularSystem {
        reason: "the periodic spline interpolating cos φ and sin φ at the φ knots".into(),
    })?;
    Ok(x.chunks_exact(2).map(|v| [v[0], v[1]]).collect())
}
