//! Slow, transparent reference evaluators on plain numbers, for comparison with the fast kernels
//! (P&T A2.1/A2.2/A3.1, de Casteljau).
//!
//! - B-spline curves by the recursive Cox–de Boor definition (document 002, B-splines; P&T eq.
//!   2.5) summed over **all** control points, with no span search and no triangular scheme. The
//!   basis is right-continuous, `N_{i,0} = 1` on `[t_i, t_{i+1})`, with the last non-empty
//!   interval closed at the last knot. At the right end of an unclamped domain
//!   (`t = t_{n+1} < t_m`) the right-continuous definition would use the span beyond the domain,
//!   so there the oracle uses the left-continuous variant (`N_{i,0} = 1` on `(t_i, t_{i+1}]`),
//!   i.e. the left limit, which is the value the library defines at the end of the domain.
//! - Bezier curves by the Bernstein formula with explicit binomial coefficients and powers
//!   (document 002, Bezier curves): `P(t) = Σ C(n,i) t^i (1 − t)^{n−i} P_i`.
//!
//! Control points are stored point after point (`dim` coordinates each), as the library's
//! `Points::as_slice` gives them.

/// `N_{i,p}(t)` by the right-continuous Cox–de Boor recursion, the last non-empty interval closed
/// at the last knot; zero denominators give zero terms.
///
/// # Panics
/// When `i + p + 1` is not a knot index.
pub fn basis(knots: &[f64], i: usize, p: usize, t: f64) -> f64 {
    if p == 0 {
        let last = knots[knots.len() - 1];
        let closed_end = t == last && knots[i] < knots[i + 1] && knots[i + 1] == last;
        return if (knots[i] <= t && t < knots[i + 1]) || closed_end {
            1.0
        } else {
            0.0
        };
    }
    recurse(knots, i, p, t, basis)
}

/// `N_{i,p}(t)` by the left-continuous recursion: `N_{i,0} = 1` on `(t_i, t_{i+1}]`.
///
/// # Panics
/// When `i + p + 1` is not a knot index.
pub fn basis_left(knots: &[f64], i: usize, p: usize, t: f64) -> f64 {
    if p == 0 {
        return if knots[i] < t && t <= knots[i + 1] {
            1.0
        } else {
            0.0
        };
    }
    recurse(knots, i, p, t, basis_left)
}

/// One step of the recursion: `(t − t_i)/(t_{i+p} − t_i) N_{i,p−1} + (t_{i+p+1} − t)/(t_{i+p+1}
/// − t_{i+1}) N_{i+1,p−1}`.
fn recurse(k: &[f64], i: usize, p: usize, t: f64, n: fn(&[f64], usize, usize, f64) -> f64) -> f64 {
    let mut v = 0.0;
    let d1 = k[i + p] - k[i];
    if d1 != 0.0 {
        v += (t - k[i]) / d1 * n(k, i, p - 1, t);
    }
    let d2 = k[i + p + 1] - k[i + 1];
    if d2 != 0.0 {
        v += (k[i + p + 1] - t) / d2 * n(k, i + 1, p - 1, t);
    }
    v
}

/// `C(t) = Σ_i N_{i,p}(t) P_i` over all control points (`control` holds `dim` coordinates per
/// point), with the left limit at the right end of an unclamped domain (see the module docs). `t`
/// must lie in the domain `[t_p, t_{n+1}]`.
///
/// # Panics
/// When the knots, degree and control points do not fit together (`knots.len() = n + p + 2`).
pub fn bspline(knots: &[f64], degree: usize, control: &[f64], dim: usize, t: f64) -> Vec<f64> {
    let n = control.len() / dim;
    assert_eq!(knots.len(), n + degree + 1, "knots for {n} control points");
    let hi = knots[n];
    let left_limit = t == hi && hi < knots[knots.len() - 1];
    let mut out = vec![0.0; dim];
    for (i, pt) in control.chunks_exact(dim).enumerate() {
        let b = if left_limit {
            basis_left(knots, i, degree, t)
        } else {
            basis(knots, i, degree, t)
        };
        for (o, x) in out.iter_mut().zip(pt) {
            *o += b * x;
        }
    }
    out
}

/// `C(t) = Σ_i N_{i,p}(t) w_i P_i / Σ_i N_{i,p}(t) w_i` over all control points (rational
/// B-spline, P&T eq. 4.2), with the basis of [`bspline`].
///
/// # Panics
/// When the knots, degree, weights and control points do not fit together.
pub fn nurbs(
    knots: &[f64],
    degree: usize,
    control: &[f64],
    weights: &[f64],
    dim: usize,
    t: f64,
) -> Vec<f64> {
    let n = control.len() / dim;
    assert_eq!(weights.len(), n, "one weight a point");
    assert_eq!(knots.len(), n + degree + 1, "knots for {n} control points");
    let hi = knots[n];
    let left_limit = t == hi && hi < knots[knots.len() - 1];
    let mut num = vec![0.0; dim];
    let mut den = 0.0;
    for (i, (pt, w)) in control.chunks_exact(dim).zip(weights).enumerate() {
        let b = if left_limit {
            basis_left(knots, i, degree, t)
        } else {
            basis(knots, i, degree, t)
        };
        let nw = b * w;
        den += nw;
        for (o, x) in num.iter_mut().zip(pt) {
            *o += nw * x;
        }
    }
    num.iter().map(|x| x / den).collect()
}

/// Binomial coefficient `C(n, i)` as a float, by the multiplicative formula.
pub fn binomial(n: usize, i: usize) -> f64 {
    (0..i).fold(1.0, |acc, j| acc * (n - j) as f64 / (j + 1) as f64)
}

/// `P(t) = Σ C(n,i) t^i (1 − t)^{n−i} P_i` term by term (`control` holds `dim` coordinates per
/// point, `n + 1` points for degree `n`).
pub fn bezier(control: &[f64], dim: usize, t: f64) -> Vec<f64> {
    let n = control.len() / dim - 1;
    let mut out = vec![0.0; dim];
    for (i, pt) in control.chunks_exact(dim).enumerate() {
        let b = binomial(n, i) * t.powf(i as f64) * (1.0 - t).powf((n - i) as f64);
        for (o, x) in out.iter_mut().zip(pt) {
            *o += b * x;
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn partition_of_unity_with_closed_end() {
        let k = [0.0, 0.0, 0.0, 1.0, 2.0, 2.0, 2.0];
        for t in [0.0, 0.5, 1.0, 1.5, 2.0] {
            let s: f64 = (0..4).map(|i| basis(&k, i, 2, t)).sum();
            assert!((s - 1.0).abs() < 1e-15, "sum at {t}: {s}");
        }
    }

    #[test]
    fn lecture_table_quadratic() {
        // control points at the Greville abscissae (knot averages) reproduce the identity
        let k = [0.0, 0.0, 0.0, 1.0, 2.0, 3.0, 3.0, 3.0];
        let ctrl = [0.0, 0.5, 1.5, 2.5, 3.0];
        for t in [0.0, 0.7, 1.5, 2.9, 3.0] {
            let c = bspline(&k, 2, &ctrl, 1, t);
            assert!((c[0] - t).abs() < 1e-15, "C({t}) = {}", c[0]);
        }
    }

    #[test]
    fn unclamped_end_is_the_left_limit() {
        // uniform linear knots: domain [1, 3], the hat functions reproduce the identity there
        let k = [0.0, 1.0, 2.0, 3.0, 4.0];
        let ctrl = [1.0, 2.0, 3.0];
        let c = bspline(&k, 1, &ctrl, 1, 3.0);
        assert_eq!(c, vec![3.0], "left limit at the right end");
    }

    #[test]
    fn bernstein_reproduces_the_line() {
        let ctrl = [0.0, 1.0 / 3.0, 2.0 / 3.0, 1.0];
        for t in [0.0, 0.25, 1.0] {
            assert!((bezier(&ctrl, 1, t)[0] - t).abs() < 1e-15, "P({t})");
        }
        assert_eq!(binomial(5, 2), 10.0, "C(5, 2)");
    }
}
