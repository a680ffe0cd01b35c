//! Closed (periodic) curves through points: the cyclic banded collocation system
//! (see [`EndCondition::Periodic`](crate::EndCondition::Periodic)).

use crate::basis::{basis_funs_into, BasisScratch};
use crate::curve::bspline::BSplineCurve;
use crate::error::{check_degree_bound, Error, Result};
use crate::knots::KnotVector;
use crate::numeric::linalg::{solve_dense, BandedCrout};
use crate::points::{Points, PointsRef};

/// Closed curve through `N ≥ 2` points (`params` has `N + 1` entries, the last for the return to
/// `q_0`), of any degree `p`. See [`EndCondition::Periodic`] for the knots. Unknowns
/// `X_0 … X_{N−1}` with control points `P_i = X_{(i − r) mod N}`, `r = ⌊p/2⌋`, so that row `k`
/// has its non-zeros in the cyclic band `X_{k−r} … X_{k+r}`. For `N > p` the cyclic system is
/// split as `[[A11, A12], [A21, A22]]` with `A22` of size `r × r`: `A11` (banded, no wrap) is
/// eliminated without pivoting with right-hand sides `[b_1 | A12]`, then the `r × r` Schur
/// complement `A22 − A21·A11⁻¹·A12` is solved by partial pivoting (block elimination, Golub &
/// Van Loan §4.5.4 / the cyclic reduction of banded periodic splines). O(N·p²). For `N ≤ p`
/// each basis function covers the period more than once and the band wraps onto itself: the
/// `N × N` system, whose entry `(k, j)` sums the basis functions with `i ≡ j (mod N)` at `t̄_k`,
/// is solved densely ([`wrapped`]; SciPy solves `N ≤ p` with a full matrix too). Three points
/// and a cubic (`N = 2`) is SciPy's periodic `CubicSpline` through three points: both slopes
/// `(h_1·m_0 + h_0·m_1)/(h_0 + h_1)`, the 2×2 cyclic system of the slopes having equal rows.
pub(crate) fn periodic(points: PointsRef<'_>, params: &[f64], p: usize) -> Result<BSplineCurve> {
    let n = points.len();
    let dim = points.dim();
    // before any `p + 1`: p may be usize::MAX (found by the `interpolation` fuzz target)
    check_degree_bound(p)?;
    if n < 2 {
        return Err(Error::TooFew {
            what: "points of a closed curve (any degree)".into(),
            min: 2,
            got: n,
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
    if p >= n {
        return wrapped(points, params, p, knots);
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

/// [`periodic`] for `N ≤ p` points: the dense `N × N` collocation system with the control
/// points `P_i = X_{i mod N}` (so `P_{i+N} = P_i`), its entry `(k, j)` the sum of the basis
/// functions `N_{i,p}(t̄_k)` with `i ≡ j (mod N)`, solved by partial pivoting. O(N³ + N·p²),
/// `N ≤ p ≤ MAX_DEGREE`.
fn wrapped(
    points: PointsRef<'_>,
    params: &[f64],
    p: usize,
    knots: Vec<f64>,
) -> Result<BSplineCurve> {
    let (n, dim) = (points.len(), points.dim());
    let reference = points.point(0);
    let kv = KnotVector::from_raw(knots);
    let mut cursor = kv.span_cursor(p);
    let mut scratch = BasisScratch::new(p);
    let mut basis = vec![0.0; p + 1];
    let mut a = vec![0.0; n * n];
    let mut x = vec![0.0; n * dim];
    for k in 0..n {
        let t = params[k];
        let span = cursor.find_unchecked(t);
        if span != k + p {
            return Err(Error::IllConditioned {
                reason: "periodic parameters too close for distinct knot spans".into(),
            });
        }
        basis_funs_into(kv.as_slice(), p, span, t, &mut scratch, &mut basis);
        for (j, &v) in basis.iter().enumerate() {
            a[k * n + (span - p + j) % n] += v;
        }
        for (d, (q, o)) in points.point(k).iter().zip(reference).enumerate() {
            x[k * dim + d] = q - o;
        }
    }
    solve_dense(&mut a, &mut x, n, dim)?;
    let control = (0..n + p)
        .flat_map(|i| {
            let c = i % n;
            x[c * dim..(c + 1) * dim]
                .iter()
                .zip(reference)
                .map(|(v, o)| v + o)
                .collect::<Vec<f64>>()
        })
        .collect();
    Ok(BSplineCurve::from_raw(
        p,
        kv.into_vec(),
        Points::from_raw(control, dim),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The closed curve at `u` (any real: reduced into the period).
    fn at(c: &BSplineCurve, u: f64) -> Vec<f64> {
        let (a, b) = c.domain();
        c.eval(a + (u - a).rem_euclid(b - a)).unwrap()
    }

    /// SciPy's `CubicSpline(x, y, bc_type="periodic")` through three points `x = [1, 2, 3.5]`,
    /// `y = [2, 5, 2]`: on `[1, 2]` the cubic `2 + (t−1) + 6(t−1)² − 4(t−1)³` (SciPy's
    /// coefficients `[-4, 6, 1, 2]`), on `[2, 3.5]` `5 + (t−2) − 6(t−2)² + (8/3)(t−2)³`,
    /// both slopes `(h_1·m_0 + h_0·m_1)/(h_0 + h_1) = (1.5·3 + 1·(−2))/2.5 = 1`.
    #[test]
    fn cubic_through_two_points_of_a_period_is_scipys() {
        let y = [2.0, 5.0];
        let c = periodic(PointsRef::from_flat(1, &y).unwrap(), &[1.0, 2.0, 3.5], 3).unwrap();
        for &t in &[1.0, 1.2, 1.5, 1.9, 2.0, 2.4, 3.0, 3.4, 3.5] {
            let want = if t <= 2.0 {
                let h = t - 1.0;
                2.0 + h + 6.0 * h * h - 4.0 * h * h * h
            } else {
                let h = t - 2.0;
                5.0 + h - 6.0 * h * h + 8.0 / 3.0 * h * h * h
            };
            let got = at(&c, t)[0];
            assert!((got - want).abs() < 1e-13, "t = {t}: {got} vs {want}");
        }
    }

    /// Fewer points than the degree: the curve passes through every point and closes with
    /// `C^{p−1}` continuity, for every degree up to 7 and 2 to `p` points (uneven spacing).
    #[test]
    fn fewer_points_than_the_degree_interpolate_and_close() {
        for p in 1..=7usize {
            for n in 2..=p {
                let params: Vec<f64> = (0..=n)
                    .map(|i| i as f64 + 0.3 * (i * i % 3) as f64)
                    .collect();
                let q: Vec<f64> = (0..n)
                    .flat_map(|i| [(i as f64).cos(), (i * i) as f64 - 1.5])
                    .collect();
                let c = periodic(PointsRef::from_flat(2, &q).unwrap(), &params, p).unwrap();
                for i in 0..n {
                    let got = at(&c, params[i]);
                    for d in 0..2 {
                        assert!(
                            (got[d] - q[2 * i + d]).abs() < 1e-10,
                            "p = {p}, n = {n}, point {i}"
                        );
                    }
                }
                let (a, b) = c.domain();
                for order in 0..p {
                    let left = c.eval_derivatives(a, order).unwrap();
                    let right = c.eval_derivatives(b, order).unwrap();
                    let (l, r) = (left.point(order), right.point(order));
                    let scale = l.iter().chain(r).fold(1.0f64, |m, v| m.max(v.abs()));
                    for d in 0..2 {
                        assert!(
                            (l[d] - r[d]).abs() < 1e-8 * scale,
                            "p = {p}, n = {n}, order {order}"
                        );
                    }
                }
            }
        }
    }
}
