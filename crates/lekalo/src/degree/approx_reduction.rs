//! Approximate degree reduction of Bezier curves (beyond document 004, which reduces only when
//! the curve has a degree defect, document 004, eq. (9)–(10)).
//!
//! The reduced curve `q` of degree `k` minimises the L2 distance `∫₀¹ ‖p(t) − q(t)‖² dt` to the
//! curve `p` of degree `n > k`, optionally with the end points, or the end points and end
//! tangents, kept (Eck, "Least squares degree reduction of Bézier curves", CAD 27(11), 1995;
//! Lutterkort, Peters & Reif, CAGD 16, 1999). The integral is evaluated exactly by
//! `(n+1)`-point Gauss–Legendre quadrature (its integrand has degree `2n`), and the weighted
//! collocation system is solved by Householder QR, which never forms the ill-conditioned
//! Bernstein Gram matrix.
//!
//! The result reports two deviations, both as Euclidean distances:
//! - `max_deviation_bound`: the difference `p − q` (both elevated to a common degree) is
//!   subdivided into 32 pieces by de Casteljau and the largest control-point norm is taken.
//!   Each piece lies in the convex hull of its control points, so this is an upper bound of
//!   `max_t ‖p(t) − q(t)‖` (up to rounding), and a tight one (the net of a piece of length `h`
//!   is within O(h²) of the curve);
//! - `max_deviation_sampled`: `max ‖p(t) − q(t)‖` over dense samples, a lower bound.

use crate::degree::elevation::{check_size, elevate};
use crate::error::{check_finite, Error, Result};
use crate::points::Points;
use crate::BezierCurve;

/// What an approximate degree reduction keeps at the ends of the curve.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum EndConditions {
    /// Nothing: the plain L2 best approximation.
    Free,
    /// The end points `p(0)` and `p(1)` (needs a target degree of at least 1).
    Points,
    /// The end points and the end first derivatives `p'(0)`, `p'(1)` (needs a target degree of
    /// at least 3).
    Tangents,
}

/// Result of [`BezierCurve::reduce_degree_approx`].
#[derive(Debug, Clone, PartialEq)]
pub struct ApproximateReduction {
    /// The reduced curve.
    pub curve: BezierCurve,
    /// Upper bound of `max_t ‖p(t) − q(t)‖` (up to rounding): the largest control-point norm
    /// of the difference curve subdivided into 32 pieces (convex-hull property).
    pub max_deviation_bound: f64,
    /// `max ‖p(t) − q(t)‖` over [`APPROX_SAMPLES`] (or more) equally spaced parameters: a lower
    /// bound of the true maximum, usually within a fraction of a percent of it.
    pub max_deviation_sampled: f64,
}

/// Least number of equally spaced parameters for the sampled deviation (at least `50·n` are used
/// for degree `n`).
pub const APPROX_SAMPLES: usize = 1000;

/// Gauss–Legendre nodes and weights on `[0, 1]` (Newton iteration on the Legendre recurrence;
/// Golub–Welsch accuracy for the degrees used here). `count ≥ 1`.
fn gauss_legendre(count: usize) -> (Vec<f64>, Vec<f64>) {
    let mut nodes = vec![0.0; count];
    let mut weights = vec![0.0; count];
    let nf = count as f64;
    for i in 0..count.div_ceil(2) {
        let mut x = (std::f64::consts::PI * (i as f64 + 0.75) / (nf + 0.5)).cos();
        let mut dp = 1.0;
        for _ in 0..100 {
            let (mut p0, mut p1) = (1.0, x);
            for j in 2..=count {
                let jf = j as f64;
                let p2 = ((2.0 * jf - 1.0) * x * p1 - (jf - 1.0) * p0) / jf;
                p0 = p1;
                p1 = p2;
            }
            let p = if count == 1 { x } else { p1 };
            let prev = if count == 1 { 1.0 } else { p0 };
            dp = nf * (x * p - prev) / (x * x - 1.0);
            let dx = p / dp;
            x -= dx;
            if dx.abs() <= 1e-16 {
                break;
            }
        }
        let w = 2.0 / ((1.0 - x * x) * dp * dp);
        // map [−1, 1] → [0, 1]; x_i > 0 gives the node near 1
        nodes[i] = (1.0 - x) / 2.0;
        nodes[count - 1 - i] = (1.0 + x) / 2.0;
        weights[i] = w / 2.0;
        weights[count - 1 - i] = w / 2.0;
    }
    (nodes, weights)
}

/// Least-squares solution of `A X ≈ B` by Householder QR. `a` is column-major `rows × cols`
/// (`rows ≥ cols`), `b` row-major `rows × nrhs`; returns `X` row-major `cols × nrhs`.
///
/// # Errors
/// [`Error::SingularSystem`] if `A` is rank deficient.
fn least_squares(
    a: &mut [f64],
    rows: usize,
    cols: usize,
    b: &mut [f64],
    nrhs: usize,
) -> Result<Vec<f64>> {
    debug_assert!(rows >= cols && a.len() == rows * cols, "shape");
    let mut diag = vec![0.0; cols];
    let scale = a.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    for i in 0..cols {
        let col = &a[i * rows + i..(i + 1) * rows];
        let norm = col.iter().fold(0.0_f64, |m, x| m.hypot(*x));
        if norm.is_nan() || norm <= 1e-14 * scale {
            return Err(Error::SingularSystem {
                reason: format!("least-squares column {i} is dependent on the previous ones"),
            });
        }
        let alpha = if col[0] > 0.0 { -norm } else { norm };
        let mut v = col.to_vec();
        v[0] -= alpha;
        let tau = 2.0 / v.iter().map(|x| x * x).sum::<f64>();
        diag[i] = alpha;
        for j in i + 1..cols {
            let cj = &mut a[j * rows + i..(j + 1) * rows];
            let dot: f64 = cj.iter().zip(&v).map(|(x, y)| x * y).sum();
            for (x, y) in cj.iter_mut().zip(&v) {
                *x -= tau * dot * y;
            }
        }
        for d in 0..nrhs {
            let dot: f64 = v
                .iter()
                .enumerate()
                .map(|(l, y)| b[(i + l) * nrhs + d] * y)
                .sum();
            for (l, y) in v.iter().enumerate() {
                b[(i + l) * nrhs + d] -= tau * dot * y;
            }
        }
    }
    let mut x = vec![0.0; cols * nrhs];
    for i in (0..cols).rev() {
        for d in 0..nrhs {
            let mut s = b[i * nrhs + d];
            for j in i + 1..cols {
                s -= a[j * rows + i] * x[j * nrhs + d];
            }
            x[i * nrhs + d] = s / diag[i];
        }
    }
    Ok(x)
}

/// Number of pieces the difference curve is subdivided into for the deviation bound.
const BOUND_PIECES: usize = 32;

/// Euclidean deviation bound and sampled deviation between two curves (see the module
/// documentation). The bound subdivides the difference curve into [`BOUND_PIECES`] pieces by de
/// Casteljau ([`BezierCurve::split_at`]) and takes the largest control-point norm: the control
/// net of a piece of length `h` is within O(h²) of the curve, so the bound is tight to about
/// 0.1 % while remaining an upper bound (up to rounding).
pub(crate) fn deviations(p: &BezierCurve, q: &BezierCurve) -> Result<(f64, f64)> {
    let dim = p.dim();
    let degree = p.degree().max(q.degree());
    let pe = elevate(p.control_points().as_slice(), dim, degree - p.degree());
    let qe = elevate(q.control_points().as_slice(), dim, degree - q.degree());
    let diff: Vec<f64> = pe.iter().zip(&qe).map(|(a, b)| a - b).collect();
    if check_finite("curve difference", &diff).is_err() {
        return Err(Error::IllConditioned {
            reason: "the deviation between the curves overflows f64 (coordinates near 1e308)"
                .into(),
        });
    }
    let norm_max = |c: &BezierCurve| {
        c.control_points()
            .iter()
            .map(|e| e.iter().map(|x| x * x).sum::<f64>().sqrt())
            .fold(0.0, f64::max)
    };
    let curve = BezierCurve::from_raw(Points::from_raw(diff, dim));
    let mut bound = 0.0_f64;
    let mut rest = curve.clone();
    for j in 0..BOUND_PIECES - 1 {
        let (piece, right) = rest.split_at(1.0 / (BOUND_PIECES - j) as f64)?;
        bound = bound.max(norm_max(&piece));
        rest = right;
    }
    bound = bound.max(norm_max(&rest));
    let samples = APPROX_SAMPLES.max(50 * degree);
    let mut sampled = 0.0_f64;
    let mut point = vec![0.0; dim];
    for s in 0..=samples {
        curve.eval_into(s as f64 / samples as f64, &mut point)?;
        sampled = sampled.max(point.iter().map(|x| x * x).sum::<f64>().sqrt());
    }
    Ok((bound.max(sampled), sampled))
}

impl BezierCurve {
    /// Best approximation of degree `target` in the L2 norm, `min ∫₀¹ ‖p(t) − q(t)‖² dt`, with
    /// the chosen [`EndConditions`] (Eck 1995; see the module documentation for the method).
    /// The end conditions fix `q_0 = p_0`, `q_k = p_n` and, for tangents,
    /// `q_1 = p_0 + (n/k)(p_1 − p_0)`, `q_{k−1} = p_n − (n/k)(p_n − p_{n−1})`.
    ///
    /// For `target ≥ n` this is the exact elevation (deviations near zero). Use it when
    /// [`BezierCurve::change_degree`] refuses because the curve has no degree defect.
    /// Cost O(n·k²·dim + n²·dim) plus the sampled deviation, O(max(1000, 50n)·n²·dim).
    ///
    /// ```
    /// use lekalo::{BezierCurve, EndConditions, Points};
    /// // a quartic arc reduced to a cubic that keeps the end points and tangents
    /// let p = BezierCurve::new(Points::from_2d(&[[0., 0.], [1., 2.], [2., 3.], [3., 2.], [4., 0.]])?)?;
    /// let r = p.reduce_degree_approx(3, EndConditions::Tangents)?;
    /// assert_eq!(r.curve.degree(), 3);
    /// // the largest deviation is 1/8, at t = 1/2 (quartic y = 17/8, cubic y = 2)
    /// assert!((r.max_deviation_sampled - 0.125).abs() < 1e-12);
    /// assert!(r.max_deviation_bound >= r.max_deviation_sampled);
    /// assert!(r.max_deviation_bound < 0.125 * 1.001);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::Degree`] if `target` is too low for the end conditions (1 for points, 3 for
    /// tangents); [`Error::TooLarge`] for a target too large to allocate;
    /// [`Error::IllConditioned`] if the result or its deviation overflows `f64`.
    pub fn reduce_degree_approx(
        &self,
        target: usize,
        ends: EndConditions,
    ) -> Result<ApproximateReduction> {
        let (n, dim) = (self.degree(), self.dim());
        let min_degree = match ends {
            EndConditions::Free => 0,
            EndConditions::Points => 1,
            EndConditions::Tangents => 3,
        };
        if target < min_degree {
            return Err(Error::Degree {
                degree: target,
                reason: format!(
                    "keeping the end {} needs a target degree of at least {min_degree}",
                    if ends == EndConditions::Points {
                        "points"
                    } else {
                        "tangents"
                    }
                ),
            });
        }
        let curve = if target >= n {
            self.elevate_degree(target - n)?
        } else {
            check_size("reduced control points", target + 1, dim)?;
            self.l2_reduction(target, ends)?
        };
        let (max_deviation_bound, max_deviation_sampled) = deviations(self, &curve)?;
        Ok(ApproximateReduction {
            curve,
            max_deviation_bound,
            max_deviation_sampled,
        })
    }

    /// The constrained L2 reduction for `target < n`.
    fn l2_reduction(&self, k: usize, ends: EndConditions) -> Result<BezierCurve> {
        let (n, dim) = (self.degree(), self.dim());
        let p = self.control_points();
        let mut q = vec![0.0; (k + 1) * dim];
        let mut fixed = vec![false; k + 1];
        if ends != EndConditions::Free {
            q[..dim].copy_from_slice(p.point(0));
            q[k * dim..].copy_from_slice(p.point(n));
            fixed[0] = true;
            fixed[k] = true;
        }
        if ends == EndConditions::Tangents {
            let ratio = n as f64 / k as f64;
            for c in 0..dim {
                q[dim + c] = p.point(0)[c] + ratio * (p.point(1)[c] - p.point(0)[c]);
                q[(k - 1) * dim + c] = p.point(n)[c] - ratio * (p.point(n)[c] - p.point(n - 1)[c]);
            }
            fixed[1] = true;
            fixed[k - 1] = true;
        }
        let free: Vec<usize> = (0..=k).filter(|&i| !fixed[i]).collect();
        if !free.is_empty() {
            let rows = n + 1;
            let (nodes, weights) = gauss_legendre(rows);
            let mut a = vec![0.0; rows * free.len()];
            let mut b = vec![0.0; rows * dim];
            let mut basis = vec![0.0; k + 1];
            for (l, (&t, &w)) in nodes.iter().zip(&weights).enumerate() {
                let sw = w.sqrt();
                crate::basis::bernstein_all_unchecked(k, t, &mut basis);
                let pt = self.eval(t)?;
                for c in 0..dim {
                    let fixed_part: f64 = (0..=k)
                        .filter(|&i| fixed[i])
                        .map(|i| basis[i] * q[i * dim + c])
                        .sum();
                    b[l * dim + c] = sw * (pt[c] - fixed_part);
                }
                for (col, &i) in free.iter().enumerate() {
                    a[col * rows + l] = sw * basis[i];
                }
            }
            let x = least_squares(&mut a, rows, free.len(), &mut b, dim)?;
            for (col, &i) in free.iter().enumerate() {
                q[i * dim..(i + 1) * dim].copy_from_slice(&x[col * dim..(col + 1) * dim]);
            }
        }
        if check_finite("reduced control points", &q).is_err() {
            return Err(Error::IllConditioned {
                reason: "the approximate degree reduction overflowed f64".into(),
            });
        }
        Ok(BezierCurve::from_raw(Points::from_raw(q, dim)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gauss_legendre_integrates_polynomials() {
        for count in 1..=30 {
            let (x, w) = gauss_legendre(count);
            assert!((w.iter().sum::<f64>() - 1.0).abs() < 1e-14, "weights sum");
            // ∫₀¹ t^e dt = 1/(e+1) exactly for e ≤ 2·count − 1
            for e in 0..2 * count {
                let e32 = i32::try_from(e).unwrap();
                let q: f64 = x.iter().zip(&w).map(|(t, w)| w * t.powi(e32)).sum();
                assert!(
                    (q - 1.0 / (e as f64 + 1.0)).abs() < 1e-14,
                    "count {count}, t^{e}"
                );
            }
        }
    }

    #[test]
    fn exact_when_the_curve_has_a_defect() {
        let c =
            BezierCurve::new(Points::from_2d(&[[0., 0.], [1., 3.], [4., -1.], [5., 2.]]).unwrap())
                .unwrap();
        let up = c.elevate_degree(3).unwrap();
        for ends in [
            EndConditions::Free,
            EndConditions::Points,
            EndConditions::Tangents,
        ] {
            let r = up.reduce_degree_approx(3, ends).unwrap();
            let d = crate::degree::reduction::max_abs_diff(
                r.curve.control_points().as_slice(),
                c.control_points().as_slice(),
            );
            assert!(d < 1e-12, "{ends:?}: {d:e}");
            assert!(r.max_deviation_bound < 1e-12, "{ends:?} bound");
        }
    }

    /// The L2-best constant for t² on [0, 1] is its mean 1/3; the best line is t − 1/6
    /// (Legendre truncation). Their max deviations are 2/3 and 1/6.
    #[test]
    fn closed_form_best_approximations() {
        let p = BezierCurve::new(Points::from_flat(1, vec![0.0, 0.0, 1.0]).unwrap()).unwrap(); // t²
        let r0 = p.reduce_degree_approx(0, EndConditions::Free).unwrap();
        assert!(
            (r0.curve.control_points().as_slice()[0] - 1.0 / 3.0).abs() < 1e-14,
            "mean"
        );
        assert!(
            (r0.max_deviation_sampled - 2.0 / 3.0).abs() < 1e-12,
            "deviation"
        );
        let r1 = p.reduce_degree_approx(1, EndConditions::Free).unwrap();
        let q = r1.curve.control_points().as_slice();
        assert!(
            (q[0] + 1.0 / 6.0).abs() < 1e-14 && (q[1] - 5.0 / 6.0).abs() < 1e-14,
            "{q:?}"
        );
        assert!(
            (r1.max_deviation_sampled - 1.0 / 6.0).abs() < 1e-12,
            "line deviation"
        );
        assert!(
            r1.max_deviation_bound >= r1.max_deviation_sampled,
            "bound ≥ sample"
        );
        // keeping the end points gives the chord q = t, deviation 1/4 at t = 1/2
        let rp = p.reduce_degree_approx(1, EndConditions::Points).unwrap();
        assert_eq!(rp.curve.control_points().as_slice(), &[0.0, 1.0]);
        assert!(
            (rp.max_deviation_sampled - 0.25).abs() < 1e-12,
            "chord deviation"
        );
    }

    #[test]
    fn end_conditions_are_kept_and_checked() {
        let p = BezierCurve::new(
            Points::from_flat(3, (0..24).map(|i| (f64::from(i) * 1.3).sin()).collect()).unwrap(),
        )
        .unwrap(); // degree 7
        let r = p.reduce_degree_approx(4, EndConditions::Tangents).unwrap();
        let (a, b) = (p.eval_derivative_ends(), r.curve.eval_derivative_ends());
        for (x, y) in a.iter().zip(&b) {
            assert!((x - y).abs() < 1e-13, "end points and tangents kept");
        }
        assert!(r.max_deviation_sampled <= r.max_deviation_bound, "bound");
        let free = p.reduce_degree_approx(4, EndConditions::Free).unwrap();
        let points = p.reduce_degree_approx(4, EndConditions::Points).unwrap();
        let (l2_free, l2_points, l2_tangents) =
            (l2(&p, &free.curve), l2(&p, &points.curve), l2(&p, &r.curve));
        assert!(
            l2_free <= l2_points && l2_points <= l2_tangents,
            "more constraints cannot lower the L2 error: {l2_free} {l2_points} {l2_tangents}"
        );
        assert!(matches!(
            p.reduce_degree_approx(2, EndConditions::Tangents),
            Err(Error::Degree { degree: 2, .. })
        ));
        assert!(matches!(
            p.reduce_degree_approx(0, EndConditions::Points),
            Err(Error::Degree { degree: 0, .. })
        ));
        let up = p.reduce_degree_approx(9, EndConditions::Free).unwrap();
        assert!(
            up.max_deviation_bound < 1e-14,
            "target above the degree is elevation"
        );
        assert!(matches!(
            p.reduce_degree_approx(usize::MAX, EndConditions::Free),
            Err(Error::TooLarge { .. })
        ));
    }

    /// ∫₀¹ ‖p − q‖² dt by Gauss–Legendre (exact for these degrees).
    fn l2(p: &BezierCurve, q: &BezierCurve) -> f64 {
        let (x, w) = gauss_legendre(p.degree().max(q.degree()) + 1);
        x.iter()
            .zip(&w)
            .map(|(&t, w)| {
                let (a, b) = (p.eval(t).unwrap(), q.eval(t).unwrap());
                w * a
                    .iter()
                    .zip(&b)
                    .map(|(u, v)| (u - v) * (u - v))
                    .sum::<f64>()
            })
            .sum()
    }

    #[test]
    fn overflow_is_reported() {
        let big = BezierCurve::new(
            Points::from_flat(1, vec![1.7e308, -1.7e308, 1.7e308, -1.7e308]).unwrap(),
        )
        .unwrap();
        let e = big
            .reduce_degree_approx(1, EndConditions::Free)
            .unwrap_err();
        assert!(matches!(e, Error::IllConditioned { .. }), "{e:?}");
    }

    #[test]
    fn least_squares_detects_rank_deficiency() {
        let mut a = vec![1.0, 2.0, 3.0, 2.0, 4.0, 6.0];
        let mut b = vec![1.0, 2.0, 3.0];
        assert!(matches!(
            least_squares(&mut a, 3, 2, &mut b, 1),
            Err(Error::SingularSystem { .. })
        ));
    }

    impl BezierCurve {
        /// p(0), p(1), p'(0), p'(1) flattened (test helper).
        fn eval_derivative_ends(&self) -> Vec<f64> {
            let (n, c) = (self.degree() as f64, self.control_points());
            let last = self.degree();
            let mut v = c.point(0).to_vec();
            v.extend_from_slice(c.point(last));
            for k in 0..self.dim() {
                v.push(n * (c.point(1)[k] - c.point(0)[k]));
                v.push(n * (c.point(last)[k] - c.point(last - 1)[k]));
            }
            v
        }
    }
}
