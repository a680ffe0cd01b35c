use super::*;

/// Dense reference: `A·x` for a banded matrix given by rows of `(first column, values)`.
fn mat_vec(rows: &[(usize, Vec<f64>)], x: &[f64], ncols: usize) -> Vec<f64> {
    let mut out = vec![0.0; rows.len() * ncols];
    for (r, (c0, vals)) in rows.iter().enumerate() {
        for (t, v) in vals.iter().enumerate() {
            for k in 0..ncols {
                out[r * ncols + k] += v * x[(c0 + t) * ncols + k];
            }
        }
    }
    out
}

fn factor_rows(
    rows: &[(usize, Vec<f64>)],
    kl: usize,
    ku: usize,
    rhs: &mut [f64],
    ncols: usize,
    keep: bool,
) -> Result<BandedCrout> {
    let mut lu = BandedCrout::new(rows.len(), kl, ku, keep);
    let mut buf = vec![0.0; lu.width()];
    for (r, (c0, vals)) in rows.iter().enumerate() {
        buf.fill(0.0);
        for (t, v) in vals.iter().enumerate() {
            buf[c0 + t + kl - r] = *v;
        }
        lu.push_row(&mut buf, rhs, ncols, 0.0)?;
    }
    Ok(lu)
}

#[test]
fn solves_the_uniform_collocation_matrix_of_example_9_1() {
    // exact matrix of eq. (1) for uniform parameters, p = 3 (docs/theory/interpolation.md#test-vectors)
    let rows = vec![
        (0, vec![1.0]),
        (0, vec![1.0 / 8.0, 19.0 / 32.0, 1.0 / 4.0, 1.0 / 32.0]),
        (1, vec![1.0 / 4.0, 1.0 / 2.0, 1.0 / 4.0]),
        (1, vec![1.0 / 32.0, 1.0 / 4.0, 19.0 / 32.0, 1.0 / 8.0]),
        (4, vec![1.0]),
    ];
    let q = [0.0, 0.0, 3.0, 4.0, -1.0, 4.0, -4.0, 0.0, -4.0, -3.0];
    let mut x = q.to_vec();
    let lu = factor_rows(&rows, 2, 2, &mut x, 2, false).unwrap();
    lu.back_substitute(&mut x, 2);
    let expect = [
        0.0,
        0.0,
        58.0 / 9.0,
        67.0 / 18.0,
        -8.0 / 3.0,
        7.5,
        -46.0 / 9.0,
        -49.0 / 18.0,
        -4.0,
        -3.0,
    ];
    for (a, b) in x.iter().zip(expect) {
        assert!((a - b).abs() < 1e-14, "{a} vs {b}");
    }
    let back = mat_vec(&rows, &x, 2);
    for (a, b) in back.iter().zip(q) {
        assert!((a - b).abs() < 1e-14, "residual {a} vs {b}");
    }
}

#[test]
fn kept_factors_solve_further_rhs_and_thomas_matches() {
    // tridiagonal (Thomas) system with a known solution
    let n = 7;
    let rows: Vec<(usize, Vec<f64>)> = (0..n)
        .map(|r| match r {
            0 => (0, vec![4.0, 1.0]),
            r if r == n - 1 => (r - 1, vec![1.0, 3.0]),
            r => (r - 1, vec![1.0, 5.0, 2.0]),
        })
        .collect();
    let x_true: Vec<f64> = (0..n).map(|i| (i as f64).sin() + 2.0).collect();
    let b = mat_vec(&rows, &x_true, 1);
    let mut first = b.clone();
    let lu = factor_rows(&rows, 1, 1, &mut first, 1, true).unwrap();
    lu.back_substitute(&mut first, 1);
    let mut again = b.clone();
    lu.solve(&mut again, 1);
    for i in 0..n {
        assert!((first[i] - x_true[i]).abs() < 1e-14, "fused {i}");
        assert!((again[i] - x_true[i]).abs() < 1e-14, "kept {i}");
    }
}

#[test]
fn zero_pivot_is_singular_system() {
    let rows = vec![(0, vec![1.0, 1.0]), (0, vec![1.0, 1.0])];
    let mut rhs = vec![1.0, 2.0];
    let e = factor_rows(&rows, 1, 1, &mut rhs, 1, false).unwrap_err();
    assert!(matches!(e, Error::SingularSystem { .. }), "{e:?}");
}

#[test]
fn pivot_growth_is_ill_conditioned() {
    // tiny first pivot: no pivoting makes the factors explode
    let rows = vec![(0, vec![1e-12, 1.0]), (0, vec![1.0, 1.0])];
    let mut rhs = vec![1.0, 2.0];
    let e = factor_rows(&rows, 1, 1, &mut rhs, 1, false).unwrap_err();
    assert!(matches!(e, Error::IllConditioned { .. }), "{e:?}");
}

/// Dense `n × n` matrix of banded rows `(first column, values)`, row-major.
fn dense(rows: &[(usize, Vec<f64>)]) -> Vec<f64> {
    let n = rows.len();
    let mut a = vec![0.0; n * n];
    for (r, (c0, vals)) in rows.iter().enumerate() {
        for (t, v) in vals.iter().enumerate() {
            a[r * n + c0 + t] = *v;
        }
    }
    a
}

/// Exact (to rounding) `κ_1 = ‖A‖_1·‖A⁻¹‖_1` of a dense matrix: the inverse by Gauss–Jordan
/// elimination with partial pivoting (test-only reference, O(n³)).
fn dense_kappa1(a: &[f64], n: usize) -> f64 {
    let col_norm = |m: &[f64]| {
        (0..n)
            .map(|c| (0..n).map(|r| m[r * n + c].abs()).sum::<f64>())
            .fold(0.0_f64, f64::max)
    };
    let mut inv = vec![0.0; n * n];
    for c in 0..n {
        // column c of A⁻¹: solve A·x = e_c with the pivoting dense solver
        let mut m = a.to_vec();
        let mut e = vec![0.0; n];
        e[c] = 1.0;
        solve_dense(&mut m, &mut e, n, 1).unwrap();
        for r in 0..n {
            inv[r * n + c] = e[r];
        }
    }
    col_norm(a) * col_norm(&inv)
}

fn estimate(rows: &[(usize, Vec<f64>)], kl: usize, ku: usize) -> Result<f64> {
    let mut lu = BandedCrout::new_estimating(rows.len(), kl, ku);
    let mut buf = vec![0.0; lu.width()];
    let mut rhs = vec![0.0; rows.len()];
    for (r, (c0, vals)) in rows.iter().enumerate() {
        buf.fill(0.0);
        for (t, v) in vals.iter().enumerate() {
            buf[c0 + t + kl - r] = *v;
        }
        lu.push_row(&mut buf, &mut rhs, 1, 0.0)?;
    }
    Ok(lu.condition_estimate().unwrap())
}

/// Banded rows with `kl`, `ku` from row-major band values `band[r][0..kl+1+ku]`.
fn band_rows(band: &[Vec<f64>], kl: usize) -> Vec<(usize, Vec<f64>)> {
    let n = band.len();
    band.iter()
        .enumerate()
        .map(|(r, b)| {
            let c0 = r.saturating_sub(kl);
            let skip = c0 + kl - r;
            let end = (b.len()).min(n + kl - r);
            (c0, b[skip..end].to_vec())
        })
        .collect()
}

#[test]
fn single_vector_and_transposed_solves_match_the_dense_matrix() {
    // nonsymmetric; band widths with fixed kernels and without (generic loops)
    let n = 9;
    for (kl, ku) in [(2, 1), (1, 1), (2, 2), (3, 2), (0, 2), (4, 4), (1, 0)] {
        let band: Vec<Vec<f64>> = (0..n)
            .map(|r| {
                let x = r as f64;
                (0..kl + 1 + ku)
                    .map(|m| {
                        if m == kl {
                            6.0 + x.cos()
                        } else {
                            (x * 0.7 + m as f64).sin()
                        }
                    })
                    .collect()
            })
            .collect();
        let rows = band_rows(&band, kl);
        let a = dense(&rows);
        let mut rhs = vec![0.0; n];
        let lu = factor_rows(&rows, kl, ku, &mut rhs, 1, true).unwrap();
        let x_true: Vec<f64> = (0..n).map(|i| 1.0 + (i as f64 * 0.7).cos()).collect();
        // b = A·x and c = Aᵀ·x
        let (mut b, mut c) = (vec![0.0; n], vec![0.0; n]);
        for r in 0..n {
            for col in 0..n {
                b[r] += a[r * n + col] * x_true[col];
                c[col] += a[r * n + col] * x_true[r];
            }
        }
        lu.solve_vector(&mut b);
        lu.solve_transposed(&mut c);
        for i in 0..n {
            assert!(
                (b[i] - x_true[i]).abs() < 1e-14,
                "({kl}, {ku}) A: x[{i}] = {}",
                b[i]
            );
            assert!(
                (c[i] - x_true[i]).abs() < 1e-14,
                "({kl}, {ku}) Aᵀ: x[{i}] = {}",
                c[i]
            );
        }
    }
}

#[test]
fn condition_estimate_of_the_second_difference_matrix_is_exact() {
    // T = tridiag(−1, 2, −1): (T⁻¹)_ij = min(i,j)·(n+1−max(i,j))/(n+1) (1-based), so
    // ‖T‖_1 = 4 and ‖T⁻¹‖_1 = max_j j·(n+1−j)/2: κ_1 = 2·⌊(n+1)/2⌋·⌈(n+1)/2⌉ ~ n²/2
    for n in [3usize, 4, 10, 31, 100] {
        let rows: Vec<(usize, Vec<f64>)> = (0..n)
            .map(|r| match r {
                0 => (0, vec![2.0, -1.0]),
                r if r == n - 1 => (r - 1, vec![-1.0, 2.0]),
                r => (r - 1, vec![-1.0, 2.0, -1.0]),
            })
            .collect();
        let half = n.div_ceil(2);
        let closed = 2.0 * (half * (n + 1 - half)) as f64;
        let exact = dense_kappa1(&dense(&rows), n);
        assert!(
            (exact - closed).abs() <= 1e-12 * closed,
            "dense {exact} vs {closed}"
        );
        let est = estimate(&rows, 1, 1).unwrap();
        assert!(
            est >= exact / 3.0 && est <= exact * (1.0 + 1e-12),
            "n {n}: estimate {est}, exact {exact}"
        );
    }
}

#[test]
fn condition_estimate_of_small_systems() {
    // 1 × 1: κ = 1; 0 rows: 1 by convention; identity: 1
    assert_eq!(estimate(&[(0, vec![-3.0])], 0, 0).unwrap(), 1.0);
    assert_eq!(estimate(&[], 1, 1).unwrap(), 1.0);
    let eye: Vec<(usize, Vec<f64>)> = (0..5).map(|r| (r, vec![1.0])).collect();
    assert_eq!(estimate(&eye, 2, 2).unwrap(), 1.0);
    // without the estimating constructor there is no estimate
    let lu = BandedCrout::new(3, 1, 1, true);
    assert!(lu.condition_estimate().is_none());
}

#[test]
fn condition_estimate_of_a_nearly_singular_collocation_pair() {
    // two rows that differ by 1e-10: κ_1 ≈ 2e10, which the estimate finds
    let rows = vec![
        (0, vec![1.0, 0.0, 0.0]),
        (0, vec![0.25, 0.5, 0.25]),
        (0, vec![0.25, 0.5 + 1e-10, 0.25 - 1e-10]),
    ];
    let exact = dense_kappa1(&dense(&rows), 3);
    let est = estimate(&rows, 2, 2).unwrap();
    assert!(exact > 1e10, "{exact}");
    assert!(
        est >= exact / 3.0 && est <= exact * (1.0 + 1e-5),
        "{est} vs {exact}"
    );
}

/// A random banded matrix, diagonally dominant by the factor `dom` (so that elimination
/// without pivoting applies and `κ_1` is moderate): rows of `kl + 1 + ku` band entries.
fn dominant_band(kl: usize, ku: usize, raw: &[(Vec<f64>, f64, bool)]) -> Vec<Vec<f64>> {
    raw.iter()
        .map(|(v, dom, neg)| {
            let mut b: Vec<f64> = v[3 - kl..4 + ku].to_vec();
            let off: f64 = b.iter().map(|x| x.abs()).sum::<f64>() - b[kl].abs();
            let d = dom * off.max(0.1);
            b[kl] = if *neg { -d } else { d };
            b
        })
        .collect()
}

/// The estimate is a lower bound of the dense `κ_1` by construction (it is `‖A‖_1` times the
/// norm of a computed column combination of A⁻¹), and `‖A‖_1` is exact. How close the bound
/// comes is not guaranteed (Higham 1988 shows matrices where Hager's method is off by any
/// factor), so the quality is checked on a fixed sample in
/// `condition_estimate_is_usually_within_three`, not per random case.
fn check_estimate(band: &[Vec<f64>], kl: usize, ku: usize) -> (f64, f64) {
    let n = band.len();
    let rows = band_rows(band, kl);
    let a = dense(&rows);
    let exact = dense_kappa1(&a, n);
    let est = estimate(&rows, kl, ku).unwrap();
    let mut lu = BandedCrout::new_estimating(n, kl, ku);
    let mut rhs = vec![0.0; n];
    for (r, b) in band.iter().enumerate() {
        let mut row: Vec<f64> = b.clone();
        for (m, v) in row.iter_mut().enumerate() {
            if r + m < kl || r + m >= n + kl {
                *v = 0.0;
            }
        }
        lu.push_row(&mut row, &mut rhs, 1, 0.0).unwrap();
    }
    let dense_norm = (0..n)
        .map(|c| (0..n).map(|r| a[r * n + c].abs()).sum::<f64>())
        .fold(0.0_f64, f64::max);
    // ‖A‖_1 from the ring of open column sums: the same sums as the dense ones
    assert_eq!(lu.norm1(), Some(dense_norm));
    assert!(
        est <= exact * (1.0 + 1e-12),
        "estimate {est} above exact {exact}"
    );
    (est, exact)
}

proptest::proptest! {
    #![proptest_config(crate::oracle::proptest_config(64))]

    /// Random banded matrices: `‖A‖_1` exact, the estimate never above the dense `κ_1`.
    #[test]
    fn condition_estimate_is_a_lower_bound(
        kl in 0usize..4,
        ku in 0usize..4,
        raw in proptest::collection::vec(
            (proptest::collection::vec(-1.0_f64..1.0, 7), 1.01_f64..3.0, proptest::bool::ANY),
            1..25,
        ),
    ) {
        check_estimate(&dominant_band(kl, ku, &raw), kl, ku);
    }
}

/// On a fixed sample of 2000 random banded matrices (a deterministic generator), the
/// estimate is within a factor 3 of the dense `κ_1` in at least 99 % of cases and within a
/// factor 10 in all (Higham's observation for Hager's method). Measured: all 2000 within 3,
/// worst ratio 0.36; a random draw once gave 0.30, which is why the per-case property
/// test checks only the lower-bound side.
#[test]
fn condition_estimate_is_usually_within_three() {
    let mut state: u64 = 0x2545_f491_4f6c_dd1d;
    let mut next = move || {
        state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        state >> 11
    };
    let scale = 1.0 / (1u64 << 53) as f64;
    let (mut within3, mut worst) = (0, f64::INFINITY);
    let cases = 2000;
    for _ in 0..cases {
        let kl = usize::try_from(next() % 4).unwrap_or(0);
        let ku = usize::try_from(next() % 4).unwrap_or(0);
        let n = 1 + usize::try_from(next() % 24).unwrap_or(0);
        let raw: Vec<(Vec<f64>, f64, bool)> = (0..n)
            .map(|_| {
                let v = (0..7)
                    .map(|_| 2.0 * (next() as f64 * scale) - 1.0)
                    .collect();
                (
                    v,
                    1.01 + 1.99 * (next() as f64 * scale),
                    (next() as f64 * scale) < 0.5,
                )
            })
            .collect();
        let (est, exact) = check_estimate(&dominant_band(kl, ku, &raw), kl, ku);
        let ratio = est / exact;
        worst = worst.min(ratio);
        if ratio >= 1.0 / 3.0 {
            within3 += 1;
        }
    }
    assert!(
        within3 * 100 >= cases * 99,
        "{within3} of {cases} within 3; worst {worst}"
    );
    assert!(worst >= 0.1, "worst ratio {worst}");
}

#[test]
fn dense_solver_pivots_and_detects_singularity() {
    let mut a = vec![0.0, 1.0, 2.0, 1.0];
    let mut b = vec![3.0, 5.0];
    solve_dense(&mut a, &mut b, 2, 1).unwrap();
    // x + 2·y... rows: [0 1; 2 1] x = [3; 5] → y = 3, x = 1
    assert!(
        (b[0] - 1.0).abs() < 1e-15 && (b[1] - 3.0).abs() < 1e-15,
        "{b:?}"
    );
    let mut a = vec![1.0, 2.0, 2.0, 4.0];
    let mut b = vec![1.0, 1.0];
    assert!(matches!(
        solve_dense(&mut a, &mut b, 2, 1),
        Err(Error::SingularSystem { .. })
    ));
}
