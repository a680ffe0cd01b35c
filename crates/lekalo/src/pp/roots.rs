//! Real roots of a piecewise polynomial: every `x` with `f_d(x) = y`, piece by piece, with SciPy's
//! conventions for `PPoly.solve` (`docs/theory/pp.md#roots`).

use super::ppform::PiecewisePolynomial;

/// One solution of `f(x) = y` ([`PiecewisePolynomial::solve`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Solution {
    /// A point `x` with `f(x) = y`.
    At(f64),
    /// A whole piece `[start, end]` on which `f` is identically `y` (SciPy writes `start, nan`).
    Piece {
        /// The piece's left breakpoint.
        start: f64,
        /// The piece's right breakpoint.
        end: f64,
    },
}

/// Bisection steps at most per root: enough to shrink any bracket of doubles to adjacent
/// values (the exponent range is 2·1023 + 52 halvings).
const MAX_BISECTIONS: usize = 2200;

impl PiecewisePolynomial {
    /// The real solutions of `f_d(x) = y` for each coordinate `d` (SciPy's `PPoly.solve` and,
    /// for `y = 0`, `PPoly.roots`; `docs/theory/pp.md#roots`), in increasing order piece by
    /// piece:
    ///
    /// - on each piece `[ξ_i, ξ_{i+1}]` the real roots of the local polynomial, found by
    ///   isolating them between the real roots of its derivative (recursively, down to degree 1)
    ///   and bisecting each sign change to adjacent doubles, then one Newton step as SciPy;
    ///   degrees 1 and 2 by the closed formulas (the quadratic without cancellation);
    /// - a piece identically equal to `y` is [`Solution::Piece`];
    /// - with `discontinuity`, a breakpoint where `f − y` changes sign across a jump is a root;
    /// - with `extrapolate`, the first piece's polynomial is searched on `(−∞, ξ_1]` and the
    ///   last's on `[ξ_{l}, ∞)`, a single piece's on the whole line (the roots lie within
    ///   Cauchy's bound `|s| ≤ 1 + max_r |c_r / c_top|` of the local variable);
    /// - a root equal to the one just reported (a root on a breakpoint, found in both pieces)
    ///   is reported once.
    ///
    /// A double root where `f − y` touches zero without a sign change is found only when
    /// the polynomial's value there is exactly `y` (SciPy's eigenvalue method reports it only
    /// when LAPACK rounds the pair to real).
    ///
    /// ```
    /// use lekalo::pp::Solution;
    /// use lekalo::PiecewisePolynomial;
    /// // 0.25 − (x − 0), zero, 0.25 − (x − 0.6) on breakpoints 0, 0.4, 0.6, 1
    /// let f = PiecewisePolynomial::new(
    ///     vec![0.0, 0.4, 0.6, 1.0], 2, 1, vec![0.25, -1.0, 0.0, 0.0, 0.25, -1.0],
    /// )?;
    /// let r = f.solve(0.0, true, true);
    /// assert_eq!(
    ///     r[0],
    ///     vec![Solution::At(0.25), Solution::Piece { start: 0.4, end: 0.6 }, Solution::At(0.85)]
    /// );
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    #[must_use]
    pub fn solve(&self, y: f64, discontinuity: bool, extrapolate: bool) -> Vec<Vec<Solution>> {
        (0..self.dim())
            .map(|d| self.solve_coordinate(d, y, discontinuity, extrapolate))
            .collect()
    }

    fn solve_coordinate(
        &self,
        d: usize,
        y: f64,
        discontinuity: bool,
        extrapolate: bool,
    ) -> Vec<Solution> {
        let (k, dim) = (self.order(), self.dim());
        let x = self.breakpoints();
        let m = self.n_pieces();
        let c = self.coefficients();
        let piece = |i: usize| -> Vec<f64> { (0..k).map(|r| c[(i * k + r) * dim + d]).collect() };
        let mut out = Vec::new();
        let mut last = f64::NAN;
        let mut roots = Vec::with_capacity(k);
        for i in 0..m {
            let a = piece(i);
            if i > 0 && discontinuity {
                let va = power_sum(&piece(i - 1), x[i] - x[i - 1]) - y;
                let vb = a[0] - y;
                if ((va < 0.0 && vb > 0.0) || (va > 0.0 && vb < 0.0)) && x[i] != last {
                    last = x[i];
                    out.push(Solution::At(last));
                }
            }
            let h = x[i + 1] - x[i];
            let first = i == 0 && extrapolate;
            let final_piece = i == m - 1 && extrapolate;
            roots.clear();
            match local_roots(&a, y, first, final_piece, h, &mut roots) {
                Local::Identical => {
                    out.push(Solution::Piece {
                        start: x[i],
                        end: x[i + 1],
                    });
                    last = f64::NAN;
                    continue;
                }
                Local::Roots => {}
            }
            for &s in &roots {
                let s = newton_step(&a, y, s);
                let r = s + x[i];
                let inside = if first && final_piece {
                    true
                } else if first {
                    r <= x[i + 1]
                } else if final_piece {
                    r >= x[i]
                } else {
                    x[i] <= r && r <= x[i + 1]
                };
                if inside && r != last {
                    last = r;
                    out.push(Solution::At(r));
                }
            }
        }
        out
    }
}

/// What [`local_roots`] found.
enum Local {
    /// The polynomial is identically `y`.
    Identical,
    /// The candidate roots (local variable) are in the output vector.
    Roots,
}

/// Candidate roots `s` of `Σ a_r s^r = y` (ascending coefficients) for the piece `[0, h]`,
/// extended to `(−∞, h]` (`left`) or `[0, ∞)` (`right`).
fn local_roots(a: &[f64], y: f64, left: bool, right: bool, h: f64, out: &mut Vec<f64>) -> Local {
    // the degree from the coefficients before y is subtracted, as SciPy
    let Some(deg) = a.iter().rposition(|&v| v != 0.0) else {
        return if y == 0.0 {
            Local::Identical
        } else {
            Local::Roots
        };
    };
    let mut p = a[..=deg].to_vec();
    p[0] -= y;
    match deg {
        0 => {
            if a[0] == y {
                return Local::Identical;
            }
        }
        1 => out.push(-p[0] / p[1]),
        2 => quadratic(p[2], p[1], p[0], out),
        _ => {
            let bound = 1.0
                + p[..deg]
                    .iter()
                    .map(|v| (v / p[deg]).abs())
                    .fold(0.0, f64::max);
            let lo = if left { -bound } else { 0.0 };
            let hi = if right { bound.max(h) } else { h };
            isolate(&p, lo, hi, out);
        }
    }
    Local::Roots
}

/// The real roots of `a2 s² + a1 s + a0` without cancellation (SciPy's `croots_poly1` order).
fn quadratic(a2: f64, a1: f64, a0: f64, out: &mut Vec<f64>) {
    let disc = a1 * a1 - 4.0 * a2 * a0;
    if disc < 0.0 {
        return;
    }
    let d = disc.sqrt();
    if d == 0.0 {
        out.extend([-a1 / (2.0 * a2); 2]);
    } else if a1 < 0.0 {
        out.extend([(2.0 * a0) / (-a1 + d), (-a1 + d) / (2.0 * a2)]);
    } else {
        out.extend([(-a1 - d) / (2.0 * a2), (2.0 * a0) / (-a1 - d)]);
    }
}

/// The real roots of `p` (ascending, degree ≥ 1, leading coefficient non-zero) in `[lo, hi]`,
/// increasing: the extrema (roots of `p'`) split the interval into monotone parts, each with at
/// most one root, bisected to adjacent doubles.
fn isolate(p: &[f64], lo: f64, hi: f64, out: &mut Vec<f64>) {
    let deg = p.len() - 1;
    if deg == 1 {
        let r = -p[0] / p[1];
        if lo <= r && r <= hi {
            out.push(r);
        }
        return;
    }
    let dp: Vec<f64> = (1..=deg).map(|r| p[r] * r as f64).collect();
    let mut cuts = vec![lo];
    isolate(&dp, lo, hi, &mut cuts);
    cuts.push(hi);
    let f = |s: f64| horner(p, s);
    for w in cuts.windows(2) {
        let (mut u, mut v) = (w[0], w[1]);
        let (fu, fv) = (f(u), f(v));
        if fu == 0.0 {
            if out.last() != Some(&u) {
                out.push(u);
            }
            continue;
        }
        if fv == 0.0 || (fu < 0.0) == (fv < 0.0) || fv.is_nan() || fu.is_nan() {
            continue;
        }
        let up = fu < 0.0;
        for _ in 0..MAX_BISECTIONS {
            let mid = 0.5 * (u + v);
            if mid <= u || mid >= v {
                break;
            }
            let fm = f(mid);
            if fm == 0.0 {
                (u, v) = (mid, mid);
                break;
            }
            if (fm < 0.0) == up {
                u = mid;
            } else {
                v = mid;
            }
        }
        let r = if f(u).abs() <= f(v).abs() { u } else { v };
        if out.last() != Some(&r) {
            out.push(r);
        }
    }
    if f(hi) == 0.0 && out.last() != Some(&hi) {
        out.push(hi);
    }
}

fn horner(p: &[f64], s: f64) -> f64 {
    p.iter().rev().fold(0.0, |acc, &c| acc * s + c)
}

/// `Σ a_r s^r` summed from the constant term up, as SciPy's `evaluate_poly1`.
fn power_sum(a: &[f64], s: f64) -> f64 {
    let (mut res, mut z) = (0.0, 1.0);
    for &c in a {
        res += c * z;
        z *= s;
    }
    res
}

/// SciPy's refinement of a root: one Newton step, kept when it is smaller than the root.
fn newton_step(a: &[f64], y: f64, s: f64) -> f64 {
    let f = power_sum(a, s) - y;
    let (mut df, mut z) = (0.0, 1.0);
    for (r, &c) in a.iter().enumerate().skip(1) {
        df += c * z * r as f64;
        z *= s;
    }
    if df != 0.0 {
        let dx = f / df;
        if dx.abs() < s.abs() {
            return s - dx;
        }
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn points(v: &[Solution]) -> Vec<f64> {
        v.iter()
            .map(|s| match s {
                Solution::At(x) => *x,
                Solution::Piece { start, .. } => *start,
            })
            .collect()
    }

    #[test]
    fn a_root_shared_by_two_pieces_is_reported_once_and_extrapolation_adds_the_outer_one() {
        // (x + 1)² − 1 on [−1, 0], −x² on [0, 1]
        let f = PiecewisePolynomial::new(
            vec![-1.0, 0.0, 1.0],
            3,
            1,
            vec![-1.0, 0.0, 1.0, 0.0, 0.0, -1.0],
        )
        .unwrap();
        assert_eq!(points(&f.solve(0.0, true, true)[0]), vec![-2.0, 0.0]);
        assert_eq!(points(&f.solve(0.0, true, false)[0]), vec![0.0]);
    }

    #[test]
    fn a_sign_change_across_a_jump_is_a_root_only_when_asked() {
        let f = PiecewisePolynomial::new(vec![0.0, 0.5, 1.0], 1, 1, vec![1.0, -1.0]).unwrap();
        assert_eq!(f.solve(0.0, true, true)[0], vec![Solution::At(0.5)]);
        assert!(f.solve(0.0, false, true)[0].is_empty());
        assert!(f.solve(1.5, true, true)[0].is_empty());
    }

    #[test]
    fn a_single_extrapolated_cubic_gives_all_three_roots() {
        // (s − 1)(s + 2)(s − 3) about 0 on [0, 4]: roots −2, 1, 3 (−2 by extrapolation)
        let f = PiecewisePolynomial::new(vec![0.0, 4.0], 4, 1, vec![6.0, -5.0, -2.0, 1.0]).unwrap();
        let r = points(&f.solve(0.0, false, true)[0]);
        let want = [-2.0, 1.0, 3.0];
        assert_eq!(r.len(), 3, "{r:?}");
        for (a, b) in r.iter().zip(want) {
            assert!((a - b).abs() < 1e-14, "{r:?}");
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]
        /// Every reported root solves f(x) = y to the accuracy its derivative allows, and lies
        /// in the searched range.
        #[test]
        fn reported_roots_are_roots(
            c in proptest::collection::vec(-1.0f64..1.0, 3 * 8),
            y in -0.5f64..0.5,
            extrapolate in any::<bool>(),
        ) {
            let x: Vec<f64> = (0..4).map(|i| f64::from(i) * 0.7).collect();
            let f = PiecewisePolynomial::new(x.clone(), 8, 1, c).unwrap();
            for s in &f.solve(y, false, extrapolate)[0] {
                let Solution::At(r) = *s else { continue };
                if !extrapolate {
                    prop_assert!(x[0] <= r && r <= x[3], "{} outside", r);
                }
                let i = if r < x[1] { 0 } else if r < x[2] { 1 } else { 2 };
                let a: Vec<f64> = f.coefficients()[i * 8..(i + 1) * 8].to_vec();
                let s = r - x[i];
                let val = power_sum(&a, s) - y;
                let scale: f64 = a.iter().zip(0..).map(|(v, j)| (v * s.abs().powi(j)).abs()).sum();
                prop_assert!(val.abs() <= 1e-12 * scale.max(1.0), "f({}) − y = {}", r, val);
            }
        }
    }
}
