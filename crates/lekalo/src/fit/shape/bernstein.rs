//! The Bernstein coefficients of a derivative of a spline on a piece of one knot span, as linear
//! functions of the control points (`docs/theory/fitting.md#shape-constraints`), and the exact
//! minimum of a polynomial of degree ≤ 3 given by its Bernstein coefficients.

use crate::basis::{basis_ders_into, BasisScratch};

/// The pieces `[α, β]` of the non-empty knot spans that meet `[a, b]` with positive length, as
/// `(span, α, β)`, spans `p ≤ span < n_ctrl` (the domain `[t_p, t_{n_ctrl}]`). For `a = b` (a
/// shape at one point) the one piece `[a, a]` of the span holding `a` (the last non-empty span
/// at the domain's end): its Bernstein coefficients are all the value there.
pub(crate) fn pieces(
    knots: &[f64],
    degree: usize,
    n_ctrl: usize,
    a: f64,
    b: f64,
) -> Vec<(usize, f64, f64)> {
    if a == b {
        let span = (degree..n_ctrl)
            .rev()
            .find(|&s| knots[s] < knots[s + 1] && knots[s] <= a)
            .unwrap_or(degree);
        return vec![(span, a, a)];
    }
    (degree..n_ctrl)
        .filter_map(|s| {
            let (lo, hi) = (knots[s].max(a), knots[s + 1].min(b));
            (lo < hi).then_some((s, lo, hi))
        })
        .collect()
}

/// `M` with `b_j = Σ_i M[j][i] c_{span−p+i}` the Bernstein coefficients on `[α, β]` of
/// `g(τ) = y⁽ʳ⁾(α + (β − α)τ)`, `τ ∈ [0, 1]`, a polynomial of degree `d = p − r` (`r ≤ p`).
/// From the Taylor coefficients `a_k = h^k y⁽ʳ⁺ᵏ⁾(α)/k!` (`h = β − α`, derivatives of the
/// basis functions of this span by P&T A2.3, so right limits at a knot), by
/// `b_j = Σ_{k≤j} C(j,k)/C(d,k) a_k` (Farouki & Rajan 1988). Rows `d + 1`, columns `p + 1`.
pub(crate) fn bernstein_rows(
    knots: &[f64],
    degree: usize,
    span: usize,
    alpha: f64,
    beta: f64,
    r: usize,
    scratch: &mut BasisScratch,
) -> Vec<Vec<f64>> {
    let p = degree;
    let w = p + 1;
    debug_assert!(r <= p, "derivative order above the degree");
    let d = p - r;
    let mut ders = vec![0.0; w * w];
    basis_ders_into(knots, p, span, alpha, p, scratch, &mut ders);
    let h = beta - alpha;
    // taylor[k][i] = h^k/k! · N_i^{(r+k)}(α)
    let mut taylor = vec![vec![0.0; w]; d + 1];
    let mut f = 1.0;
    for (k, row) in taylor.iter_mut().enumerate() {
        if k > 0 {
            f *= h / k as f64;
        }
        for (i, v) in row.iter_mut().enumerate() {
            *v = f * ders[(r + k) * w + i];
        }
    }
    (0..=d)
        .map(|j| {
            let mut row = vec![0.0; w];
            for (k, t) in taylor.iter().enumerate().take(j + 1) {
                let c = binomial(j, k) / binomial(d, k);
                for (v, tv) in row.iter_mut().zip(t) {
                    *v += c * tv;
                }
            }
            row
        })
        .collect()
}

/// The weights `w` with `g(τ) = Σ w_j b_j` and `g'(τ)/d = Σ w'_j b_j` for the polynomial of
/// degree `d` with Bernstein coefficients `b` (`B^d_j(τ)`, and `B^{d−1}_{j−1}(τ) − B^{d−1}_j(τ)`).
pub(crate) fn bernstein_weights(d: usize, tau: f64) -> (Vec<f64>, Vec<f64>) {
    // (as `2·u·v` for d = 2, u = 1 − τ, v = τ: the rounding of the quadratic's own formula)
    let power = |x: f64, k: usize| (1..k).fold(if k == 0 { 1.0 } else { x }, |acc, _| acc * x);
    let basis = |d: usize, j: usize| {
        let c = binomial(d, j);
        if c == 1.0 {
            power(1.0 - tau, d - j) * power(tau, j)
        } else {
            c * power(1.0 - tau, d - j) * power(tau, j)
        }
    };
    let value = (0..=d).map(|j| basis(d, j)).collect();
    let slope = (0..=d)
        .map(|j| {
            let left = if j > 0 { basis(d - 1, j - 1) } else { 0.0 };
            let right = if j < d { basis(d - 1, j) } else { 0.0 };
            left - right
        })
        .collect();
    (value, slope)
}

/// `C(n, k)` as a float (small arguments: degrees).
pub(crate) fn binomial(n: usize, k: usize) -> f64 {
    (0..k).fold(1.0, |acc, i| acc * (n - i) as f64 / (i + 1) as f64)
}

/// The minimum over `τ ∈ [0, 1]` of the polynomial with Bernstein coefficients `b`: exact for
/// degree ≤ 3 (the end values and the values at the roots of the derivative, by the quadratic
/// formula in its stable form), and for higher degrees the least Bernstein coefficient after
/// splitting into 64 pieces, a lower bound (the convex-hull property).
pub(crate) fn min_on_unit(b: &[f64]) -> f64 {
    let d = b.len() - 1;
    if d > 3 {
        return (0..64)
            .flat_map(|i| {
                let (lo, hi) = (i as f64 / 64.0, (i + 1) as f64 / 64.0);
                sub_bernstein(b, lo, hi)
            })
            .fold(f64::INFINITY, f64::min);
    }
    argmin_on_unit(b).1
}

/// Where on `[0, 1]` the polynomial of degree `d ≤ 3` with Bernstein coefficients `b` takes its
/// minimum, and the minimum: the ends and the roots of the derivative inside (the quadratic
/// formula in its stable form). For `d > 3` the better end only.
pub(crate) fn argmin_on_unit(b: &[f64]) -> (f64, f64) {
    let d = b.len() - 1;
    let ends = if b[0] <= b[d] {
        (0.0, b[0])
    } else {
        (1.0, b[d])
    };
    match interior_min(b) {
        Some(inside) if inside.1 < ends.1 => inside,
        _ => ends,
    }
}

/// The least value of the polynomial of degree `d ≤ 3` with Bernstein coefficients `b` at the
/// roots of its derivative strictly inside `(0, 1)`, and where (`None` without such a root): a
/// cubic can vanish at an end and touch zero inside as well.
pub(crate) fn interior_min(b: &[f64]) -> Option<(f64, f64)> {
    let mut best: Option<(f64, f64)> = None;
    // derivative's Bernstein coefficients d (b_{j+1} − b_j), as a monomial a0 + a1 τ + a2 τ²
    let db: Vec<f64> = b.windows(2).map(|w| w[1] - w[0]).collect();
    let roots: Vec<f64> = match db.len() {
        2 => {
            // linear: db0 (1−τ) + db1 τ
            let den = db[0] - db[1];
            if den == 0.0 {
                vec![]
            } else {
                vec![db[0] / den]
            }
        }
        3 => {
            // db0 (1−τ)² + 2 db1 τ(1−τ) + db2 τ² = a0 + a1 τ + a2 τ²
            let a0 = db[0];
            let a1 = 2.0 * (db[1] - db[0]);
            let a2 = db[0] - 2.0 * db[1] + db[2];
            quadratic_roots(a2, a1, a0)
        }
        _ => vec![],
    };
    for t in roots.into_iter().filter(|t| *t > 0.0 && *t < 1.0) {
        let v = de_casteljau(b, t);
        if best.is_none_or(|(_, m)| v < m) {
            best = Some((t, v));
        }
    }
    best
}

/// Real roots of `a x² + b x + c` (the stable form: `q = −(b + sign(b)√Δ)/2`, roots `q/a`,
/// `c/q`).
fn quadratic_roots(a: f64, b: f64, c: f64) -> Vec<f64> {
    if a == 0.0 {
        return if b == 0.0 { vec![] } else { vec![-c / b] };
    }
    let disc = b * b - 4.0 * a * c;
    if disc < 0.0 {
        return vec![];
    }
    let q = -0.5 * (b + b.signum() * disc.sqrt());
    if q == 0.0 {
        return vec![0.0];
    }
    vec![q / a, c / q]
}

/// The value at `t` of the polynomial with Bernstein coefficients `b` (de Casteljau).
pub(crate) fn de_casteljau(b: &[f64], t: f64) -> f64 {
    let mut v = b.to_vec();
    for k in (1..v.len()).rev() {
        for j in 0..k {
            v[j] = (1.0 - t) * v[j] + t * v[j + 1];
        }
    }
    v[0]
}

/// The Bernstein coefficients on `[lo, hi] ⊂ [0, 1]` (two de Casteljau splits).
fn sub_bernstein(b: &[f64], lo: f64, hi: f64) -> Vec<f64> {
    let right = split(b, lo).1;
    let s = if lo < 1.0 {
        (hi - lo) / (1.0 - lo)
    } else {
        0.0
    };
    split(&right, s).0
}

/// De Casteljau split at `t`: the coefficients on `[0, t]` and on `[t, 1]`.
fn split(b: &[f64], t: f64) -> (Vec<f64>, Vec<f64>) {
    let n = b.len();
    let mut v = b.to_vec();
    let mut left = Vec::with_capacity(n);
    let mut right = vec![0.0; n];
    left.push(v[0]);
    right[n - 1] = v[n - 1];
    for k in (1..n).rev() {
        for j in 0..k {
            v[j] = (1.0 - t) * v[j] + t * v[j + 1];
        }
        left.push(v[0]);
        right[k - 1] = v[k - 1];
    }
    (left, right)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::knots::KnotVector;

    #[test]
    fn bernstein_rows_reproduce_the_derivative_on_the_piece() {
        let kv = KnotVector::new(vec![0.0, 0.0, 0.0, 0.0, 0.3, 0.5, 1.0, 1.0, 1.0, 1.0]).unwrap();
        let ctrl = [0.3, -1.0, 2.0, 0.5, 1.5, -0.7];
        let curve = crate::BSplineCurve::new(
            3,
            kv.as_slice().to_vec(),
            crate::Points::from_flat(1, ctrl.to_vec()).unwrap(),
        )
        .unwrap();
        let mut scratch = BasisScratch::new(3);
        for r in 0..=3 {
            for &(span, a, b) in &pieces(kv.as_slice(), 3, 6, 0.1, 0.9) {
                let m = bernstein_rows(kv.as_slice(), 3, span, a, b, r, &mut scratch);
                let bc: Vec<f64> = m
                    .iter()
                    .map(|row| (0..4).map(|i| row[i] * ctrl[span - 3 + i]).sum())
                    .collect();
                for t in [0.0, 0.25, 0.6, 1.0] {
                    let x = a + (b - a) * t;
                    // inside the span (not at its right knot, where the left limit is meant)
                    let x = x.min(b - 1e-12);
                    let want = curve.eval_derivatives(x, r).unwrap().point(r)[0];
                    let got = de_casteljau(&bc, (x - a) / (b - a));
                    assert!(
                        (got - want).abs() < 1e-9,
                        "r {r} span {span} t {t}: {got} vs {want}"
                    );
                }
            }
        }
    }

    #[test]
    fn exact_minimum_of_low_degrees() {
        // (2τ − 1)² − 0.01 on [0,1]: Bernstein of 4τ² − 4τ + 1 is (1, −1, 1), minimum −0.01 at ½
        let b = [0.99, -1.01, 0.99];
        assert!(
            (min_on_unit(&b) + 0.01).abs() < 1e-15,
            "{}",
            min_on_unit(&b)
        );
        // cubic τ³ − τ/3 +1: minimum at τ = 1/3, value 1 − 2/27
        let mono = [1.0, -1.0 / 3.0, 0.0, 1.0];
        let b: Vec<f64> = (0..4)
            .map(|j| {
                (0..=j)
                    .map(|k| binomial(j, k) / binomial(3, k) * mono[k])
                    .sum()
            })
            .collect();
        assert!(
            (min_on_unit(&b) - (1.0 - 2.0 / 27.0)).abs() < 1e-15,
            "{}",
            min_on_unit(&b)
        );
        // degree 4 lower bound below the true minimum, and close to it
        let b4 = [1.0, -1.0, 1.0, -1.0, 1.0];
        let lb = min_on_unit(&b4);
        let true_min = (0..=10000)
            .map(|i| de_casteljau(&b4, i as f64 / 1e4))
            .fold(f64::INFINITY, f64::min);
        assert!(lb <= true_min && lb > true_min - 1e-2, "{lb} vs {true_min}");
    }
}
