//! Closed (periodic) curves through points: the cyclic banded collocation system
//! (see [`EndCondition::Periodic`](crate::EndCondition::Periodic)).

use crate::basis::{basis_funs_into, BasisScratch};
use crate::curve::bspline::BSplineCurve;
use crate::error::{Error, Result};
use crate::knots::KnotVector;
use crate::numeric::linalg::{solve_dense, BandedCrout};
use crate::points::{Points, PointsRef};

/// Closed curve through `N` points (`params` has `N + 1` entries, the last for the return to
/// `q_0`). See [`EndCondition::Periodic`] for the knots. Unknowns `X_0 … X_{N−1}` with control
/// points `P_i = X_{(i − r) mod N}`, `r = ⌊p/2⌋`, so that row `k` has its non-zeros in the
/// cyclic band `X_{k−r} … X_{k+r}`. The cyclic system is split as `[[A11, A12], [A21, A22]]`
/// with `A22` of size `r × r`: `A11` (banded, no wrap) is eliminated without pivoting with
/// right-hand sides `[b_1 | A12]`, then the `r × r` Schur complement `A22 − A21·A11⁻¹·A12` is
/// solved by partial pivoting (block elimination, Golub & Van Loan §4.5.4 / the cyclic
/// reduction of banded periodic splines). O(N·p²).
pub(crate) fn periodic(points: PointsRef<'_>, params: &[f64], p: usize) -> Result<BSplineCurve> {
    let n = points.len();
    let dim = points.dim();
    // `p >= n`, not `n < p + 1`: p may be usize::MAX (found by the `interpolation` fuzz target)
    if p >= n {
        return Err(Error::Degree {
            degree: p,
            reason: format!(
                "a closed curve through {n} points has degree at most {}",
                n - 1
            ),
        });
    }
    let period = params[n] - params[0];
    let ext = |i: isize| -> f64 {
        let ni = n as isize;
        let q = i.div_euclid(ni);
        params[i.rem_euclid(ni) as usize] + q as f64 * period
    };
    let n_knots = n + 2 * p + 1;
    let knots: Vec<f64> = (0..n_knots as isize)
        .map(|j| {
            let i = j - p as isize;
            if p % 2 == 1 {
                ext(i)
            } else {
                0.5 * (ext(i - 1) + ext(i))
            }
        })
        .collect();
    if let Some(j) = (1..n_knots).find(|&j| knots[j] < knots[j - 1]) {
        return Err(Error::IllConditioned {
            reason: format!(
                "periodic knots {} and {j} are out of order after rounding",
                j - 1
            ),
        });
    }
    let r = p / 2;
    let nb = r; // size of the coupling block A22
    let n1 = n - nb; // rows of A11
    let width = dim + nb; // right-hand sides of the A11 solve: b_1 and the columns of A12
    let reference = points.point(0);
    let mut work = vec![0.0; n1 * width];
    for k in 0..n1 {
        for d in 0..dim {
            work[k * width + d] = points.point(k)[d] - reference[d];
        }
    }
    let kv = KnotVector::from_raw(knots);
    let mut cursor = kv.span_cursor(p);
    let mut scratch = BasisScratch::new(p);
    let mut basis = vec![0.0; p + 1];
    let mut lu = BandedCrout::new(n1, r, r, false);
    let mut row = vec![0.0; lu.width()];
    // bottom rows: sparse (column, value) entries and their right-hand sides
    let mut bottom: Vec<Vec<(usize, f64)>> = Vec::with_capacity(nb);
    let too_close = || Error::IllConditioned {
        reason: "periodic parameters too close for distinct knot spans".into(),
    };
    for k in 0..n {
        let t = params[k];
        let span = cursor.find_unchecked(t);
        if span != k + p {
            return Err(too_close());
        }
        basis_funs_into(kv.as_slice(), p, span, t, &mut scratch, &mut basis);
        if k < n1 {
            row.fill(0.0);
            for (j, &v) in basis.iter().enumerate() {
                if v == 0.0 {
                    continue;
                }
                let c = (span - p + j + n - r) % n;
                if c >= n1 {
                    work[k * width + dim + (c - n1)] += v;
                } else {
                    let off = (c + r)
                        .checked_sub(k)
                        .filter(|&o| o <= 2 * r)
                        .ok_or_else(too_close)?;
                    row[off] += v;
                }
            }
            lu.push_row(&mut row, &mut work, width, 1.0)?;
        } else {
            let entries = basis
                .iter()
                .enumerate()
                .filter(|(_, &v)| v != 0.0)
                .map(|(j, &v)| ((span - p + j + n - r) % n, v))
                .collect();
            bottom.push(entries);
        }
    }
    lu.back_substitute(&mut work, width);
    // Schur complement S = A22 − A21·Y and its right-hand side b_2 − A21·y
    let mut s = vec![0.0; nb * nb];
    let mut rhs2 = vec![0.0; nb * dim];
    for (i, entries) in bottom.iter().enumerate() {
        let q = points.point(n1 + i);
        for d in 0..dim {
            rhs2[i * dim + d] = q[d] - reference[d];
        }
        for &(c, v) in entries {
            if c >= n1 {
                s[i * nb + (c - n1)] += v;
            } else {
                let w = &work[c * width..(c + 1) * width];
                for d in 0..dim {
                    rhs2[i * dim + d] -= v * w[d];
                }
                for j in 0..nb {
                    s[i * nb + j] -= v * w[dim + j];
                }
            }
        }
    }
    if nb > 0 {
        solve_dense(&mut s, &mut rhs2, nb, dim)?;
    }
    let mut x = vec![0.0; n * dim];
    for c in 0..n1 {
        let w = &work[c * width..(c + 1) * width];
        for d in 0..dim {
            let mut v = w[d];
            for j in 0..nb {
                v -= w[dim + j] * rhs2[j * dim + d];
            }
            x[c * dim + d] = v;
        }
    }
    x[n1 * dim..].copy_from_slice(&rhs2);
    let mut control = Vec::with_capacity((n + p) * dim);
    for i in 0..n + p {
        let c = (i + n - r) % n;
        control.extend(
            x[c * dim..(c + 1) * dim]
                .iter()
                .zip(reference)
                .map(|(a, b)| a + b),
        );
    }
    Ok(BSplineCurve::from_raw(
        p,
        kv.into_vec(),
        Points::from_raw(control, dim),
    ))
}
