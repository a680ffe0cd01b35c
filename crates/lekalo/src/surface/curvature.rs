//! Curvatures of a surface in 3-D from its first and second partial derivatives: Gaussian,
//! mean and principal curvatures through the first and second fundamental forms (do Carmo,
//! *Differential Geometry of Curves and Surfaces*, §3-3; Piegl & Tiller do not cover it, Farin
//! *Curves and Surfaces for CAGD* §22.3 uses the same formulas).

use crate::error::{Error, Result};

/// Relative tolerance below which the tangent plane is degenerate: `EG − F² ≤ 1e-24·E·G`, the
/// square of the normal's `|S_u × S_v| ≤ 1e-12·|S_u|·|S_v|`, so that curvature is defined exactly
/// where the surface's unit normal is.
const DEGENERACY_TOL_SQ: f64 = 1e-24;

/// Curvatures of a surface at a point, for the unit normal `n = (S_u × S_v) / |S_u × S_v|`.
///
/// A curvature is positive where the surface bends towards `n` (a sphere with outward
/// normal has curvature `−1/r`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfaceCurvature {
    /// Gaussian curvature `K = (LN − M²) / (EG − F²) = κ₁κ₂`.
    pub gaussian: f64,
    /// Mean curvature `H = (EN − 2FM + GL) / (2(EG − F²)) = (κ₁ + κ₂) / 2`.
    pub mean: f64,
    /// The larger principal curvature `κ₁ = H + √(H² − K)`.
    pub k1: f64,
    /// The smaller principal curvature `κ₂ = H − √(H² − K)`.
    pub k2: f64,
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// Gaussian, mean and principal curvatures from the partial derivatives `S_u`, `S_v`, `S_uu`,
/// `S_uv`, `S_vv` at a point of a surface in 3-D (do Carmo §3-3, eqs. for `K` and `H` in terms
/// of the coefficients `E, F, G` of the first and `L, M, N` of the second fundamental form).
/// `H² − K` is clamped at 0 against rounding, so `κ₁ ≥ κ₂` always.
///
/// ```
/// use lekalo::surface_curvature;
/// // the paraboloid z = (x² + y²)/2 at the origin: κ₁ = κ₂ = 1, K = 1, H = 1
/// let k = surface_curvature(&[1.0, 0.0, 0.0], &[0.0, 1.0, 0.0],
///                           &[0.0, 0.0, 1.0], &[0.0, 0.0, 0.0], &[0.0, 0.0, 1.0])?;
/// assert_eq!((k.gaussian, k.mean, k.k1, k.k2), (1.0, 1.0, 1.0, 1.0));
/// # Ok::<(), lekalo::Error>(())
/// ```
///
/// # Errors
/// [`Error::Dimension`] unless every slice has 3 values; [`Error::InvalidArgument`] where the
/// tangent plane is degenerate (`EG − F² ≤ 1e-24·E·G`, the normal's own test) or a value is not
/// finite.
pub fn surface_curvature(
    su: &[f64],
    sv: &[f64],
    suu: &[f64],
    suv: &[f64],
    svv: &[f64],
) -> Result<SurfaceCurvature> {
    for s in [su, sv, suu, suv, svv] {
        if s.len() != 3 {
            return Err(Error::Dimension {
                what: "surface derivative for curvature".into(),
                expected: 3,
                got: s.len(),
            });
        }
    }
    let n = [
        su[1] * sv[2] - su[2] * sv[1],
        su[2] * sv[0] - su[0] * sv[2],
        su[0] * sv[1] - su[1] * sv[0],
    ];
    let (e, f, g) = (dot(su, su), dot(su, sv), dot(sv, sv));
    let det = e * g - f * f;
    let ln = dot(&n, &n).sqrt();
    if !det.is_finite() || !ln.is_finite() || det <= DEGENERACY_TOL_SQ * e * g || ln == 0.0 {
        return Err(Error::InvalidArgument {
            what: "surface point for curvature".into(),
            reason: format!(
                "the tangent plane is degenerate: EG − F² = {det:e} with E = {e:e}, G = {g:e} \
                 (a pole, collapsed edge or cusp) — evaluate nearby"
            ),
        });
    }
    let l = dot(suu, &n) / ln;
    let m = dot(suv, &n) / ln;
    let nn = dot(svv, &n) / ln;
    let gaussian = (l * nn - m * m) / det;
    let mean = (e * nn - 2.0 * f * m + g * l) / (2.0 * det);
    if !gaussian.is_finite() || !mean.is_finite() {
        return Err(Error::NonFinite {
            what: "surface curvature".into(),
            index: 0,
            value: if gaussian.is_finite() { mean } else { gaussian },
        });
    }
    let root = (mean * mean - gaussian).max(0.0).sqrt();
    Ok(SurfaceCurvature {
        gaussian,
        mean,
        k1: mean + root,
        k2: mean - root,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sphere_and_cylinder() {
        // sphere of radius r: S(u, v) = r(cos u cos v, sin u cos v, sin v), S_u × S_v points
        // inwards here, so κ₁ = κ₂ = 1/r
        let (r, u, v): (f64, f64, f64) = (2.0, 0.4, 0.3);
        let (cu, su_, cv, sv_) = (u.cos(), u.sin(), v.cos(), v.sin());
        let su = [-r * su_ * cv, r * cu * cv, 0.0];
        let sv = [-r * cu * sv_, -r * su_ * sv_, r * cv];
        let suu = [-r * cu * cv, -r * su_ * cv, 0.0];
        let suv = [r * su_ * sv_, -r * cu * sv_, 0.0];
        let svv = [-r * cu * cv, -r * su_ * cv, -r * sv_];
        let k = surface_curvature(&su, &sv, &suu, &suv, &svv).unwrap();
        for x in [k.k1, k.k2, k.mean] {
            assert!((x.abs() - 0.5).abs() < 1e-14, "{k:?}");
        }
        assert!((k.gaussian - 0.25).abs() < 1e-14, "{k:?}");
        // cylinder of radius 3: (3 cos u, 3 sin u, v): K = 0, |H| = 1/6
        let su = [-3.0 * u.sin(), 3.0 * u.cos(), 0.0];
        let suu = [-3.0 * u.cos(), -3.0 * u.sin(), 0.0];
        let k = surface_curvature(&su, &[0.0, 0.0, 1.0], &suu, &[0.0; 3], &[0.0; 3]).unwrap();
        assert!(k.gaussian.abs() < 1e-15, "{k:?}");
        assert!((k.mean.abs() - 1.0 / 6.0).abs() < 1e-15, "{k:?}");
        assert!(k.k1 >= k.k2, "{k:?}");
    }

    #[test]
    fn saddle_and_errors() {
        // z = xy at the origin: κ = ±1, K = −1, H = 0
        let k = surface_curvature(
            &[1.0, 0.0, 0.0],
            &[0.0, 1.0, 0.0],
            &[0.0; 3],
            &[0.0, 0.0, 1.0],
            &[0.0; 3],
        )
        .unwrap();
        assert_eq!((k.gaussian, k.mean, k.k1, k.k2), (-1.0, 0.0, 1.0, -1.0));
        let e = surface_curvature(
            &[1.0, 0.0, 0.0],
            &[2.0, 0.0, 0.0],
            &[0.0; 3],
            &[0.0; 3],
            &[0.0; 3],
        );
        assert!(matches!(e, Err(Error::InvalidArgument { .. })), "{e:?}");
        let e = surface_curvature(&[1.0, 0.0], &[0.0, 1.0], &[0.0; 2], &[0.0; 2], &[0.0; 2]);
        assert!(matches!(e, Err(Error::Dimension { .. })), "{e:?}");
        let e = surface_curvature(
            &[f64::NAN, 0.0, 0.0],
            &[0.0, 1.0, 0.0],
            &[0.0; 3],
            &[0.0; 3],
            &[0.0; 3],
        );
        assert!(e.is_err(), "{e:?}");
    }
}
