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
}
