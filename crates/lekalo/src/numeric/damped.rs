//! Levenberg–Marquardt refinement of a small nonlinear least-squares problem `min ‖r(x)‖` over
//! the unit box `[0, 1]^N` (Marquardt, "An algorithm for least-squares estimation of nonlinear
//! parameters", SIAM J. Appl. Math. 11, 1963; Nocedal & Wright, *Numerical Optimization*,
//! §10.3), crate-private. The intersection finders fall back to it where Newton's method from a
//! flat pair has not converged (`docs/theory/queries.md#intersections`): the curve–curve gap in
//! the plane (`N = 2`) and the curve–surface gap in space (`N = 3`).
//!
//! A step solves `(JᵀJ + λ·diag(JᵀJ)) δ = −Jᵀr` (Marquardt's scaling; `1e-300` on the diagonal
//! keeps a zero column solvable), clamps `x + δ` to the box and is taken only if the gap
//! decreases; then `λ` shrinks tenfold (not below `1e-15`), otherwise it grows tenfold and the
//! step is tried again. It stops when no trial of a step improves the gap, when a step moves the
//! point by at most `1e-16`, at a zero gap, or after [`MAX_STEPS`] steps of at most
//! [`MAX_TRIALS`] trials: every loop has a bound, whatever the residual.

/// Most steps of one refinement.
pub(crate) const MAX_STEPS: usize = 60;
/// Most damping trials of one step.
pub(crate) const MAX_TRIALS: usize = 20;
/// Largest damping tried before a step gives up.
const MAX_DAMPING: f64 = 1e12;

/// The residual at a point, as the refinement needs it: its norm `‖r‖`, the normal matrix `JᵀJ`
/// and the gradient `Jᵀr` of `½‖r‖²`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Residual<const N: usize> {
    pub(crate) gap: f64,
    pub(crate) normal: [[f64; N]; N],
    pub(crate) gradient: [f64; N],
}

/// Refines `x0` (in `[0, 1]^N`) as the module describes; `eval` gives the residual at a point of
/// the box. Returns the best point found and its gap (never worse than `x0`'s).
pub(crate) fn levenberg_marquardt<const N: usize>(
    x0: [f64; N],
    mut eval: impl FnMut(&[f64; N]) -> Residual<N>,
) -> ([f64; N], f64) {
    let mut x = x0;
    let mut gap = eval(&x).gap;
    let mut lambda = 1e-12;
    for _ in 0..MAX_STEPS {
        let Residual {
            normal: a,
            gradient: g,
            ..
        } = eval(&x);
        let mut improved = false;
        for _ in 0..MAX_TRIALS {
            let mut m = a;
            for i in 0..N {
                m[i][i] = a[i][i] * (1.0 + lambda) + 1e-300;
            }
            let Some(d) = solve(m, g.map(|v| -v)) else {
                lambda *= 10.0;
                continue;
            };
            let mut nx = x;
            for i in 0..N {
                nx[i] = (x[i] + d[i]).clamp(0.0, 1.0);
            }
            let trial = eval(&nx).gap;
            if trial < gap {
                let moved: f64 = (0..N).map(|i| (nx[i] - x[i]).abs()).sum();
                x = nx;
                gap = trial;
                lambda = (lambda * 0.1).max(1e-15);
                improved = moved > 1e-16;
                break;
            }
            lambda *= 10.0;
            if lambda > MAX_DAMPING {
                break;
            }
        }
        if !improved || gap == 0.0 {
            break;
        }
    }
    (x, gap)
}

/// Solves the small system `m x = b` by Gaussian elimination with partial pivoting; `None` when a
/// pivot is zero or a result is not finite (the caller then damps more).
fn solve<const N: usize>(mut m: [[f64; N]; N], mut b: [f64; N]) -> Option<[f64; N]> {
    for c in 0..N {
        let pivot = (c..N).max_by(|&i, &j| m[i][c].abs().total_cmp(&m[j][c].abs()))?;
        if m[pivot][c] == 0.0 || m[pivot][c].is_nan() {
            return None;
        }
        m.swap(c, pivot);
        b.swap(c, pivot);
        for r in c + 1..N {
            let f = m[r][c] / m[c][c];
            for k in c..N {
                m[r][k] -= f * m[c][k];
            }
            b[r] -= f * b[c];
        }
    }
    let mut x = [0.0; N];
    for c in (0..N).rev() {
        let s: f64 = (c + 1..N).map(|k| m[c][k] * x[k]).sum();
        x[c] = (b[c] - s) / m[c][c];
    }
    x.iter().all(|v| v.is_finite()).then_some(x)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `r(x) = (x0² + x1² − 0.5, x0 − x1)`: the zero `(½, ½)` from a far start, to rounding.
    #[test]
    fn reaches_the_zero_of_a_circle_and_a_line() {
        let (x, gap) = levenberg_marquardt([0.9, 0.1], |x: &[f64; 2]| {
            let r = [x[0] * x[0] + x[1] * x[1] - 0.5, x[0] - x[1]];
            let j = [[2.0 * x[0], 2.0 * x[1]], [1.0, -1.0]];
            residual(r, j)
        });
        assert!(gap < 1e-15, "{gap:e}");
        assert!(
            (x[0] - 0.5).abs() < 1e-15 && (x[1] - 0.5).abs() < 1e-15,
            "{x:?}"
        );
    }

    /// The zero lies outside the box: the refinement stays in it and stops at the nearest
    /// point of the boundary's gap, with a bounded number of evaluations.
    #[test]
    fn stays_in_the_box_and_stops() {
        let mut evaluations = 0;
        let (x, gap) = levenberg_marquardt([0.5, 0.5, 0.5], |x: &[f64; 3]| {
            evaluations += 1;
            let r = [x[0] - 2.0, x[1] + 1.0, x[2] - 0.25];
            let j = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
            residual(r, j)
        });
        // x and y clamped to the box; z short of 0.25 by the damping's factor 1/(1 + λ) of the
        // first step (λ = 1e-12), which no later step can better in the gap's last bit
        assert_eq!((x[0], x[1]), (1.0, 0.0));
        assert!((x[2] - 0.25).abs() <= 0.25e-12 * 1.01, "{x:?}");
        assert!((gap - 2f64.sqrt()).abs() < 1e-15, "{gap}");
        assert!(evaluations <= 1 + MAX_STEPS * (1 + MAX_TRIALS));
    }

    /// A residual that is NaN everywhere: no step is ever taken, the start comes back.
    #[test]
    fn a_nan_residual_returns_the_start() {
        let (x, gap) = levenberg_marquardt([0.3, 0.7], |_: &[f64; 2]| Residual {
            gap: f64::NAN,
            normal: [[f64::NAN; 2]; 2],
            gradient: [f64::NAN; 2],
        });
        assert_eq!(x, [0.3, 0.7]);
        assert!(gap.is_nan());
    }

    #[test]
    fn solve_pivots_and_refuses_singular_systems() {
        let x = solve([[0.0, 1.0], [2.0, 0.0]], [3.0, 4.0]).unwrap();
        assert_eq!(x, [2.0, 3.0]);
        assert!(solve([[1.0, 2.0], [2.0, 4.0]], [1.0, 1.0]).is_none());
    }

    fn residual<const N: usize, const M: usize>(r: [f64; M], j: [[f64; N]; M]) -> Residual<N> {
        let mut normal = [[0.0; N]; N];
        let mut gradient = [0.0; N];
        for a in 0..N {
            for b in 0..N {
                normal[a][b] = (0..M).map(|k| j[k][a] * j[k][b]).sum();
            }
            gradient[a] = (0..M).map(|k| j[k][a] * r[k]).sum();
        }
        Residual {
            gap: r.iter().map(|v| v * v).sum::<f64>().sqrt(),
            normal,
            gradient,
        }
    }
}
