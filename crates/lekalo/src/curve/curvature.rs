//! Differential geometry of curves from their derivatives.

/// Curvature `κ = |C' × C''| / |C'|³` from the first two derivatives, in any dimension through
/// Lagrange's identity `|a × b|² = |a|²|b|² − (a·b)²` (do Carmo, *Differential Geometry of Curves
/// and Surfaces*, §1-5). `None` where `C' = 0` (curvature undefined) or the slices differ in
/// length.
///
/// ```
/// use lekalo::curvature;
/// // circle of radius 2: C' = (0, 2), C'' = (−2, 0) at t = 0 for C(t) = 2(cos t, sin t)
/// assert!((curvature(&[0.0, 2.0], &[-2.0, 0.0]).unwrap() - 0.5).abs() < 1e-15);
/// assert_eq!(curvature(&[0.0, 0.0], &[1.0, 0.0]), None);
/// ```
#[must_use]
pub fn curvature(d1: &[f64], d2: &[f64]) -> Option<f64> {
    if d1.len() != d2.len() {
        return None;
    }
    let aa: f64 = d1.iter().map(|x| x * x).sum();
    let bb: f64 = d2.iter().map(|x| x * x).sum();
    let ab: f64 = d1.iter().zip(d2).map(|(x, y)| x * y).sum();
    if aa == 0.0 || !aa.is_finite() {
        return None;
    }
    let cross2 = (aa * bb - ab * ab).max(0.0);
    Some(cross2.sqrt() / (aa * aa.sqrt()))
}

/// Unit principal normal `N = (C'' − (C''·T)T) / |C'' − (C''·T)T|` with `T = C'/|C'|`: the
/// direction towards the centre of curvature, in any dimension (do Carmo §1-5, the Frenet
/// frame; the curvature comb draws `−κN`). `None` where `C' = 0` or `C''` is parallel to `C'`
/// (a straight piece has no principal normal) or the slices differ in length.
///
/// ```
/// use lekalo::principal_normal;
/// // circle C(t) = 2(cos t, sin t) at t = 0: the normal points to the centre
/// assert_eq!(principal_normal(&[0.0, 2.0], &[-2.0, 0.0]), Some(vec![-1.0, 0.0]));
/// assert_eq!(principal_normal(&[1.0, 0.0], &[3.0, 0.0]), None);
/// ```
#[must_use]
pub fn principal_normal(d1: &[f64], d2: &[f64]) -> Option<Vec<f64>> {
    if d1.len() != d2.len() {
        return None;
    }
    let len = d1.iter().map(|x| x * x).sum::<f64>().sqrt();
    if len == 0.0 || !len.is_finite() {
        return None;
    }
    let tangent: Vec<f64> = d1.iter().map(|x| x / len).collect();
    let along: f64 = d2.iter().zip(&tangent).map(|(a, b)| a * b).sum();
    let n: Vec<f64> = d2
        .iter()
        .zip(&tangent)
        .map(|(a, b)| a - along * b)
        .collect();
    let nl = n.iter().map(|x| x * x).sum::<f64>().sqrt();
    (nl > 0.0 && nl.is_finite()).then(|| n.iter().map(|x| x / nl).collect())
}

/// Torsion `τ = (C' × C'')·C''' / |C' × C''|²` of a 3-D curve from its first three derivatives
/// (do Carmo, *Differential Geometry of Curves and Surfaces*, §1-5; `docs/theory/queries.md#curvature`): the rate at which the
/// osculating plane turns, positive for a right-handed helix. It does not depend on the
/// parametrisation. `None` where the curvature is zero (`C' × C'' = 0`: no osculating plane) or
/// unless all three slices have length 3.
///
/// ```
/// use lekalo::torsion;
/// // helix (cos t, sin t, t): τ = 1/2
/// let (d1, d2, d3) = ([0.0, 1.0, 1.0], [-1.0, 0.0, 0.0], [0.0, -1.0, 0.0]);
/// assert!((torsion(&d1, &d2, &d3).unwrap() - 0.5).abs() < 1e-15);
/// // a planar curve has none; a straight line has no osculating plane
/// assert_eq!(torsion(&[1.0, 0.0, 0.0], &[0.0, 1.0, 0.0], &[1.0, 1.0, 0.0]), Some(0.0));
/// assert_eq!(torsion(&[1.0, 0.0, 0.0], &[2.0, 0.0, 0.0], &[0.0, 0.0, 1.0]), None);
/// ```
#[must_use]
pub fn torsion(d1: &[f64], d2: &[f64], d3: &[f64]) -> Option<f64> {
    let (&[a0, a1, a2], &[b0, b1, b2], &[c0, c1, c2]) = (d1, d2, d3) else {
        return None;
    };
    let x = [a1 * b2 - a2 * b1, a2 * b0 - a0 * b2, a0 * b1 - a1 * b0];
    let xx = x[0] * x[0] + x[1] * x[1] + x[2] * x[2];
    if !(xx > 0.0 && xx.is_finite()) {
        return None;
    }
    Some((x[0] * c0 + x[1] * c1 + x[2] * c2) / xx)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn helix_curvature() {
        // helix (a cos t, a sin t, b t): κ = a / (a² + b²)
        let (a, b, t): (f64, f64, f64) = (3.0, 4.0, 0.7);
        let d1 = [-a * t.sin(), a * t.cos(), b];
        let d2 = [-a * t.cos(), -a * t.sin(), 0.0];
        let k = curvature(&d1, &d2).unwrap();
        assert!((k - a / (a * a + b * b)).abs() < 1e-15, "κ = {k}");
        assert_eq!(curvature(&[1.0], &[1.0, 2.0]), None);
        // a straight line has zero curvature
        assert_eq!(curvature(&[1.0, 1.0], &[2.0, 2.0]), Some(0.0));
    }

    #[test]
    fn helix_torsion_and_its_sign() {
        // helix (a cos t, a sin t, b t): τ = b / (a² + b²), negative when mirrored
        let (a, b, t): (f64, f64, f64) = (3.0, 4.0, 0.7);
        let d1 = [-a * t.sin(), a * t.cos(), b];
        let d2 = [-a * t.cos(), -a * t.sin(), 0.0];
        let d3 = [a * t.sin(), -a * t.cos(), 0.0];
        let tau = torsion(&d1, &d2, &d3).unwrap();
        assert!((tau - b / (a * a + b * b)).abs() < 1e-15, "τ = {tau}");
        let mirrored = |v: [f64; 3]| [v[0], v[1], -v[2]];
        let tau_m = torsion(&mirrored(d1), &mirrored(d2), &mirrored(d3)).unwrap();
        assert!(
            (tau_m + b / (a * a + b * b)).abs() < 1e-15,
            "mirror τ = {tau_m}"
        );
        // independent of the parametrisation: t = 2s scales C^(k) by 2^k
        let sc = |v: [f64; 3], f: f64| v.map(|x| x * f);
        let tau_s = torsion(&sc(d1, 2.0), &sc(d2, 4.0), &sc(d3, 8.0)).unwrap();
        assert!((tau_s - tau).abs() < 1e-15);
        // not 3-D
        assert_eq!(torsion(&[1.0, 0.0], &[0.0, 1.0], &[0.0, 0.0]), None);
    }
}
