//! Derivatives of least-squares fits and smoothing splines with respect to the data: both fits
//! are linear in the data values, `P = G⁻¹ BᵀW Q` with the banded `G = BᵀWB` (least squares on
//! given knots and parameters) or `G = BᵀWB + λΩ` (smoothing spline with a given `λ > 0`), so
//! `Ṗ = G⁻¹ BᵀW Q̇` (JVP) and `Q̄ = W B G⁻¹ P̄` (VJP: `G` is symmetric), each one sparse product
//! with the observation rows and one solve with one banded factorisation of `G`: the triangle
//! `R` of the fit's banded QR (`G = RᵀR`) or the fit's `UᵀDU`
//! (`docs/theory/derivatives.md#fits`).

use super::checks::check_len;
use crate::error::{check_finite, Error, Result};
use crate::fit::banded::SymBand;
use crate::fit::banded::{BandedQr, QrRows, RANK_RTOL};
use crate::fit::{
    check_in_domain, check_schoenberg_whitney, for_each_row, smoothing_system, FitData,
    SmoothingSystem,
};
use crate::knots::KnotVector;
use crate::points::PointsRef;
use crate::{Arg, What};

/// The observation rows `B` of a fit (`width` non-zero basis functions a data point, starting at
/// `first[k]`) and the data weights `W`.
#[derive(Debug, Clone)]
struct Rows {
    first: Vec<usize>,
    basis: Vec<f64>,
    width: usize,
    weights: Vec<f64>,
    /// Number of coefficients (columns of `B`).
    n: usize,
}

impl Rows {
    /// `BᵀW y` for `y` of `m × dim`, point-major.
    fn transpose_weighted(&self, y: &[f64], dim: usize) -> Vec<f64> {
        let mut out = vec![0.0; self.n * dim];
        for (k, (&first, row)) in self
            .first
            .iter()
            .zip(self.basis.chunks_exact(self.width))
            .enumerate()
        {
            let w = self.weights[k];
            let yk = &y[k * dim..(k + 1) * dim];
            for (a, &b) in row.iter().enumerate() {
                let o = &mut out[(first + a) * dim..(first + a + 1) * dim];
                for (oc, yc) in o.iter_mut().zip(yk) {
                    *oc += w * b * yc;
                }
            }
        }
        out
    }

    /// `W B x` for `x` of `n × dim`, point-major.
    fn weighted(&self, x: &[f64], dim: usize) -> Vec<f64> {
        let m = self.first.len();
        let mut out = vec![0.0; m * dim];
        for (k, (&first, row)) in self
            .first
            .iter()
            .zip(self.basis.chunks_exact(self.width))
            .enumerate()
        {
            let w = self.weights[k];
            let o = &mut out[k * dim..(k + 1) * dim];
            for (a, &b) in row.iter().enumerate() {
                let xa = &x[(first + a) * dim..(first + a + 1) * dim];
                for (oc, xc) in o.iter_mut().zip(xa) {
                    *oc += b * xc;
                }
            }
            for oc in o.iter_mut() {
                *oc *= w;
            }
        }
        out
    }

    /// The forward-mode derivative of a linear fit, `solve(BᵀW Q̇)` for a data tangent `Q̇`
    /// (`m × dim`, point-major), `solve` applying the inverse of the fit's normal matrix. The
    /// tangent is shifted by its first point before and the control points back after
    /// ([`shifted`], [`unshift`]).
    ///
    /// # Errors
    /// As [`Rows::check`] for `m · dim` numbers.
    fn jvp(
        &self,
        data_tangent: &[f64],
        dim: usize,
        solve: impl FnOnce(&mut [f64], usize),
    ) -> Result<Vec<f64>> {
        Rows::check(
            "data tangent (points × dimension)",
            data_tangent,
            self.first.len(),
            dim,
        )?;
        let (shifted, center) = shifted(data_tangent, dim);
        let mut x = self.transpose_weighted(&shifted, dim);
        solve(&mut x, dim);
        Ok(unshift(x, &center))
    }

    /// The reverse-mode derivative of a linear fit, `W B solve(P̄)` for a control-point
    /// cotangent `P̄` (`n × dim`, point-major), the adjoint of [`Rows::jvp`] with its shift.
    ///
    /// # Errors
    /// As [`Rows::check`] for `n · dim` numbers.
    fn vjp(
        &self,
        control_cotangent: &[f64],
        dim: usize,
        solve: impl FnOnce(&mut [f64], usize),
    ) -> Result<Vec<f64>> {
        Rows::check(
            "control-point cotangent (points × dimension)",
            control_cotangent,
            self.n,
            dim,
        )?;
        let mut x = control_cotangent.to_vec();
        solve(&mut x, dim);
        Ok(unshift_transposed(
            self.weighted(&x, dim),
            control_cotangent,
            dim,
        ))
    }

    /// The length and finiteness of a buffer of `count` points of dimension `dim ≥ 1`.
    fn check(what: impl Into<What>, v: &[f64], count: usize, dim: usize) -> Result<()> {
        let what: What = what.into();
        if dim == 0 {
            return Err(Error::Dimension {
                what,
                expected: 1,
                got: 0,
            });
        }
        check_len(what, count.saturating_mul(dim), v.len())?;
        check_finite(what, v)
    }
}

/// The points of `q` (`dim` numbers each, at least one point) minus the first one, and that
/// point. Both fits reproduce constants (`B 1 = 1`, and a constant has no penalty), so
/// `M q = M (q − 1 q_0) + 1 q_0`: the JVPs solve for the shifted tangent as the fits solve for
/// the shifted data (`docs/theory/fitting.md`, conventions), and large common offsets lose no
/// digits.
fn shifted(q: &[f64], dim: usize) -> (Vec<f64>, Vec<f64>) {
    let center = q[..dim].to_vec();
    let mut out = q.to_vec();
    for p in out.chunks_exact_mut(dim) {
        for (v, c) in p.iter_mut().zip(&center) {
            *v -= c;
        }
    }
    (out, center)
}

/// `x + 1 center` for control points `x`: undoes [`shifted`].
fn unshift(mut x: Vec<f64>, center: &[f64]) -> Vec<f64> {
    for p in x.chunks_exact_mut(center.len()) {
        for (v, c) in p.iter_mut().zip(center) {
            *v += c;
        }
    }
    x
}

/// The transpose of the shift of [`shifted`] and [`unshift`] around `M`: the JVP computes
/// `M (q − 1 q_0) + 1 q_0`, whose transpose maps `p̄` to `y − e_0 Σ_k y_k + e_0 Σ_i p̄_i` with
/// `y = Mᵀ p̄` (per coordinate). The correction vanishes in exact arithmetic (`Mᵀ` maps sums
/// to sums, `1ᵀ Mᵀ = (M 1)ᵀ = 1ᵀ`); in floating point it keeps the VJP the transpose of the
/// JVP as computed.
fn unshift_transposed(mut y: Vec<f64>, p: &[f64], dim: usize) -> Vec<f64> {
    for c in 0..dim {
        let sum_y: f64 = y.iter().skip(c).step_by(dim).sum();
        let sum_p: f64 = p.iter().skip(c).step_by(dim).sum();
        y[c] += sum_p - sum_y;
    }
    y
}

/// The pieces of a fit's map from data to control points, `P = (RᵀR)⁻¹ BᵀW Q`, for a framework
/// that applies it with its own operations (a scatter-add, two banded triangular sweeps, and
/// their transposes): returned by [`LeastSquaresMap::linearize`] and
/// [`SmoothingMap::linearize`] (`docs/theory/derivatives.md#fits`).
#[derive(Debug, Clone, PartialEq)]
pub struct FitLinearization {
    /// Per data point `k`, the index of its first non-zero basis function.
    pub first: Vec<usize>,
    /// Per data point, its `width` non-zero basis functions `B[k][first[k] + a]`, flat.
    pub basis: Vec<f64>,
    /// Non-zero basis functions a data point (`p + 1`; 4 for the smoothing spline).
    pub width: usize,
    /// The weights `W` as the map applies them (the least-squares fit divides them by the
    /// largest, which leaves the fit unchanged).
    pub weights: Vec<f64>,
    /// The upper triangle `R` with `RᵀR = BᵀWB (+ λΩ)`, banded: `triangle[i·bandwidth + k] =
    /// R[i][i + k]`, `n` rows.
    pub triangle: Vec<f64>,
    /// Entries a row of `triangle`.
    pub bandwidth: usize,
    /// Number of control points `n`.
    pub n_ctrl: usize,
}

/// The linear map from data values to control points of the weighted least-squares fit of
/// `degree` on `knots` at fixed `params` (no end constraints; [`crate::fit::least_squares`]
/// with [`crate::fit::EndConstraints::none`]): `P = (BᵀWB)⁻¹ BᵀW Q`. It keeps the triangle `R`
/// of the banded QR of `√W B` (`BᵀWB = RᵀR`, the factorisation the fit uses) and the sparse
/// rows of `B`; [`LeastSquaresMap::jvp`] applies `R⁻¹R⁻ᵀ BᵀW`, [`LeastSquaresMap::vjp`] its
/// transpose `W B R⁻¹R⁻ᵀ`: two banded triangular sweeps and one sparse product, O(N·p·dim) for
/// `N` data points, never a dense inverse (`docs/theory/derivatives.md#fits`).
///
/// ```
/// use lekalo::derivatives::LeastSquaresMap;
/// use lekalo::KnotVector;
/// let x: Vec<f64> = (0..20).map(|k| k as f64 / 19.0).collect();
/// let kv = KnotVector::new(vec![0.0, 0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0, 1.0])?;
/// let map = LeastSquaresMap::new(3, &kv, &x, None)?;
/// // the fit reproduces a spline of its space: the tangent C(x) gives back C's control points
/// let ctrl = [1.0, -2.0, 0.5, 3.0, 2.0];
/// let curve = lekalo::BSplineCurve::new(3, kv.as_slice().to_vec(), lekalo::Points::new(ctrl.to_vec(), 1)?)?;
/// let mut y = vec![0.0; 20];
/// curve.eval_batch(&x, &mut y)?;
/// let back = map.jvp(&y, 1)?;
/// assert!(back.iter().zip(&ctrl).all(|(a, b)| (a - b).abs() < 1e-12));
/// # Ok::<(), lekalo::Error>(())
/// ```
#[derive(Debug, Clone)]
pub struct LeastSquaresMap {
    rows: Rows,
    qr: BandedQr,
    bw: usize,
}

impl LeastSquaresMap {
    /// Factors the least-squares problem of `degree` on `knots` at `params` with optional
    /// weights `w_k ≥ 0` (the fit's `Σ w_k |C(ū_k) − Q_k|²`).
    ///
    /// # Errors
    /// As [`crate::fit::least_squares`]: [`Error::Degree`] and the knot errors of
    /// [`KnotVector::validate_for`]; [`Error::ParameterOutOfDomain`] for a parameter outside
    /// the knots' domain; [`Error::SchoenbergWhitney`] when a basis function has no data under
    /// it (or only data of weight 0); the errors of [`FitData::with_weights`].
    pub fn new(
        degree: usize,
        knots: &KnotVector,
        params: &[f64],
        weights: Option<&[f64]>,
    ) -> Result<Self> {
        crate::error::check_degree_bound(degree)?;
        let zeros = vec![0.0; params.len()];
        let mut data = FitData::new(PointsRef::from_flat(1, &zeros)?, params)?;
        if let Some(w) = weights {
            data = data.with_weights(w)?;
        }
        let n = knots
            .len()
            .checked_sub(degree + 1)
            .ok_or_else(|| Error::Degree {
                degree,
                reason: format!("{} knots carry no spline of this degree", knots.len()),
            })?;
        knots.validate_for(degree, n)?;
        check_schoenberg_whitney(params, degree, knots)?;
        check_in_domain(params, knots.domain(degree))?;
        let width = degree + 1;
        let m = params.len();
        let wmax = data
            .weights()
            .map_or(1.0, |w| w.iter().fold(0.0_f64, |m, &v| m.max(v)));
        let ws: Vec<f64> = (0..m)
            .map(|k| {
                if wmax > 0.0 {
                    data.weight(k) / wmax
                } else {
                    0.0
                }
            })
            .collect();
        let mut first = vec![0; m];
        let mut basis = vec![0.0; m * width];
        // √w·B rotated in data row by data row, in the order of the parameters (as the fit)
        let mut rows_qr = QrRows::new(n, width, 1);
        let mut h = vec![0.0; width];
        let on_row = |k: usize, span: usize, row: &[f64]| {
            first[k] = span - degree;
            basis[k * width..(k + 1) * width].copy_from_slice(row);
            let sw = ws[k].sqrt();
            if sw > 0.0 {
                for (hv, b) in h.iter_mut().zip(row) {
                    *hv = sw * b;
                }
                rows_qr.push(span - degree, &h, &[0.0]);
            }
        };
        match data.order() {
            None => for_each_row(knots, degree, params, 0..m, |_| 1.0, on_row),
            Some(order) => for_each_row(knots, degree, params, order, |_| 1.0, on_row),
        }
        let qr = rows_qr.finish();
        let dmax = (0..n).fold(0.0_f64, |m, i| m.max(qr.r[i * width].abs()));
        if let Some(j) = (0..n).find(|&i| qr.r[i * width].abs() <= RANK_RTOL * dmax) {
            let t = knots.as_slice();
            return Err(Error::SchoenbergWhitney {
                basis: j,
                start: t[j],
                end: t[j + degree + 1],
            });
        }
        Ok(LeastSquaresMap {
            rows: Rows {
                first,
                basis,
                width,
                weights: ws,
                n,
            },
            qr,
            bw: width,
        })
    }

    /// Number of control points of the fit.
    #[must_use]
    pub fn n_ctrl(&self) -> usize {
        self.rows.n
    }

    /// Number of data points.
    #[must_use]
    pub fn n_data(&self) -> usize {
        self.rows.first.len()
    }

    /// Forward-mode derivative: the control-point tangent `Ṗ = (BᵀWB)⁻¹ BᵀW Q̇` for a data
    /// tangent `Q̇` (`N × dim`, point-major): the least-squares fit of `Q̇` itself.
    ///
    /// # Errors
    /// [`Error::LengthMismatch`] unless `data_tangent.len() == N · dim`; [`Error::NonFinite`];
    /// [`Error::Dimension`] for `dim == 0`.
    pub fn jvp(&self, data_tangent: &[f64], dim: usize) -> Result<Vec<f64>> {
        self.rows
            .jvp(data_tangent, dim, |x, dim| self.solve_normal(x, dim))
    }

    /// Reverse-mode derivative: the data cotangent `Q̄ = W B (BᵀWB)⁻¹ P̄` for a control-point
    /// cotangent `P̄` (`n × dim`, point-major), with the same factors as [`Self::jvp`].
    ///
    /// # Errors
    /// [`Error::LengthMismatch`] unless `control_cotangent.len() == n · dim`;
    /// [`Error::NonFinite`]; [`Error::Dimension`] for `dim == 0`.
    pub fn vjp(&self, control_cotangent: &[f64], dim: usize) -> Result<Vec<f64>> {
        self.rows
            .vjp(control_cotangent, dim, |x, dim| self.solve_normal(x, dim))
    }

    /// The sparse rows of `B`, the weights and the triangle `R` of the banded QR
    /// (`RᵀR = BᵀWB`): the whole map, [`FitLinearization`].
    #[must_use]
    pub fn linearize(&self) -> FitLinearization {
        FitLinearization {
            first: self.rows.first.clone(),
            basis: self.rows.basis.clone(),
            width: self.rows.width,
            weights: self.rows.weights.clone(),
            triangle: self.qr.r.clone(),
            bandwidth: self.bw,
            n_ctrl: self.rows.n,
        }
    }

    /// `x ← (RᵀR)⁻¹ x`: a forward sweep with `Rᵀ`, a backward sweep with `R` (banded).
    fn solve_normal(&self, x: &mut [f64], dim: usize) {
        let (n, bw, r) = (self.rows.n, self.bw, &self.qr.r);
        for i in 0..n {
            for c in 0..dim {
                let mut s = x[i * dim + c];
                for k in i.saturating_sub(bw - 1)..i {
                    s -= r[k * bw + i - k] * x[k * dim + c];
                }
                x[i * dim + c] = s / r[i * bw];
            }
        }
        for i in (0..n).rev() {
            for c in 0..dim {
                let mut s = x[i * dim + c];
                for k in 1..bw.min(n - i) {
                    s -= r[i * bw + k] * x[(i + k) * dim + c];
                }
                x[i * dim + c] = s / r[i * bw];
            }
        }
    }
}

/// `λ` of the smoothing-spline derivatives: finite and positive.
///
/// # Errors
/// [`Error::NegativeSmoothing`] for `λ < 0` or not finite; [`Error::InvalidArgument`] for
/// `λ = 0` (the natural interpolating spline: use [`super::InterpolationMap`]).
pub(super) fn check_lambda(lambda: f64) -> Result<()> {
    if !(lambda >= 0.0 && lambda.is_finite()) {
        return Err(Error::NegativeSmoothing {
            what: Arg::Lambda.into(),
            value: lambda,
        });
    }
    if lambda == 0.0 {
        return Err(Error::InvalidArgument {
            what: What::of(Arg::Lambda, "λ of the smoothing-spline derivatives"),
            reason: "λ = 0 is the natural interpolating spline, not covered here; give λ > 0"
                .into(),
        });
    }
    Ok(())
}

/// The linear map from data values to control points of the cubic smoothing spline with a
/// given `λ > 0` ([`crate::fit::smoothing_spline`] with [`crate::fit::Lambda::Given`]): with
/// `B` the clamped cubic B-splines with knots at the `M` distinct data parameters (`M + 2` control
/// points; `M = N` unless a parameter repeats),
/// `P = (BᵀWB + λΩ)⁻¹ BᵀW Q`. It keeps the fit's `UᵀDU` factorisation of the symmetric banded
/// matrix; [`SmoothingMap::jvp`] applies `(BᵀWB + λΩ)⁻¹ BᵀW`, [`SmoothingMap::vjp`] its
/// transpose `W B (BᵀWB + λΩ)⁻¹`, O(N·dim) each (`docs/theory/derivatives.md#fits`).
///
/// ```
/// use lekalo::derivatives::SmoothingMap;
/// let x: Vec<f64> = (0..10).map(|k| k as f64 / 9.0).collect();
/// let map = SmoothingMap::new(&x, 1e-3, None)?;
/// // the smoothing spline of a line is the line: the tangent 1 everywhere gives control points 1
/// let back = map.jvp(&[1.0; 10], 1)?;
/// assert_eq!(back.len(), 12);
/// assert!(back.iter().all(|v| (v - 1.0).abs() < 1e-12));
/// # Ok::<(), lekalo::Error>(())
/// ```
#[derive(Debug, Clone)]
pub struct SmoothingMap {
    rows: Rows,
    matrix: SymBand,
    knots: Vec<f64>,
}

impl SmoothingMap {
    /// Factors the smoothing system of the non-decreasing `params` (a repeated one as the
    /// smoothing spline takes it) with optional weights
    /// `w_k ≥ 0` for the penalty weight `lambda > 0`.
    ///
    /// # Errors
    /// [`Error::NegativeSmoothing`] for `lambda < 0` or not finite; [`Error::InvalidArgument`]
    /// for `lambda == 0` (the natural interpolating spline: use [`super::InterpolationMap`]); as
    /// [`crate::fit::smoothing_spline`] for the parameters and weights.
    pub fn new(params: &[f64], lambda: f64, weights: Option<&[f64]>) -> Result<Self> {
        check_lambda(lambda)?;
        let zeros = vec![0.0; params.len()];
        let mut data = FitData::new(PointsRef::from_flat(1, &zeros)?, params)?;
        if let Some(w) = weights {
            data = data.with_weights(w)?;
        }
        Ok(SmoothingMap::of_system(smoothing_system(&data, lambda)?))
    }

    /// The map of a smoothing system already assembled and factored (the fit's own, from its
    /// values: [`super::SmoothingFit::control_points_and_map`]).
    pub(super) fn of_system(sys: SmoothingSystem) -> Self {
        let basis = sys.basis.iter().flatten().copied().collect();
        SmoothingMap {
            rows: Rows {
                first: sys.first,
                basis,
                width: 4,
                weights: sys.weights,
                n: sys.knots.len() - 4,
            },
            matrix: sys.matrix,
            knots: sys.knots,
        }
    }

    /// Length of [`SmoothingMap::to_flat`] for `n_data` data points of distinct parameters
    /// (`n_data + 2` control points): `11·n_data + 14`; `None` on overflow.
    #[must_use]
    pub fn flat_len(n_data: usize) -> Option<usize> {
        n_data.checked_mul(11)?.checked_add(14)
    }

    /// The whole map as numbers, for a caller that keeps it between the values and their
    /// derivatives (an automatic-differentiation framework's residual): for `N` data points and
    /// `n` control points, `first` (`N`, as floats, exact below 2⁵³), the rows of `B` (`4N`),
    /// the weights (`N`), the factored `UᵀDU` band (`4n`, `D[i]` then `U[i][i+1..i+3]`) and the
    /// knots (`n + 4`): `6N + 5n + 4` numbers. [`SmoothingMap::from_flat`] reads it back into
    /// the same map, so that its JVP and VJP have the same bits.
    #[must_use]
    pub fn to_flat(&self) -> Vec<f64> {
        let r = &self.rows;
        let mut out = Vec::with_capacity(6 * r.first.len() + 5 * r.n + 4);
        out.extend(r.first.iter().map(|&f| f as f64));
        out.extend_from_slice(&r.basis);
        out.extend_from_slice(&r.weights);
        out.extend_from_slice(&self.matrix.a);
        out.extend_from_slice(&self.knots);
        out
    }

    /// The map written by [`SmoothingMap::to_flat`] for `n_data` data points, checked enough
    /// that applying it cannot index out of its bounds.
    ///
    /// # Errors
    /// [`Error::LengthMismatch`] unless `flat` has `6·n_data + 5n + 4` numbers for some
    /// `n ≥ 4`; [`Error::InvalidArgument`] for a first index that is not a whole number in
    /// `0..=n − 4`.
    pub fn from_flat(flat: &[f64], n_data: usize) -> Result<Self> {
        let what = "factors of a smoothing spline (SmoothingMap::to_flat)";
        let rows_len = n_data.checked_mul(6).ok_or(Error::TooLarge {
            what: what.into(),
            size: n_data,
            max: usize::MAX / 6,
        })?;
        let n = flat
            .len()
            .checked_sub(rows_len + 4)
            .map(|rest| rest / 5)
            .filter(|&n| n >= 4 && rows_len + 5 * n + 4 == flat.len())
            .ok_or(Error::LengthMismatch {
                what: what.into(),
                expected: rows_len + 5 * (n_data + 2) + 4,
                got: flat.len(),
            })?;
        let (first, rest) = flat.split_at(n_data);
        let (basis, rest) = rest.split_at(4 * n_data);
        let (weights, rest) = rest.split_at(n_data);
        let (band, knots) = rest.split_at(4 * n);
        let first = first
            .iter()
            .enumerate()
            .map(|(k, &f)| {
                if f >= 0.0 && f.fract() == 0.0 && f <= (n - 4) as f64 {
                    // a whole number in 0..=n − 4: exact
                    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
                    let i = f as usize;
                    Ok(i)
                } else {
                    Err(Error::InvalidArgument {
                        what: what.into(),
                        reason: format!(
                            "data point {k} has first basis function {f}, not a whole number \
                             in 0..={}",
                            n - 4
                        ),
                    })
                }
            })
            .collect::<Result<Vec<_>>>()?;
        Ok(SmoothingMap {
            rows: Rows {
                first,
                basis: basis.to_vec(),
                width: 4,
                weights: weights.to_vec(),
                n,
            },
            matrix: SymBand {
                n,
                b: 3,
                a: band.to_vec(),
            },
            knots: knots.to_vec(),
        })
    }

    /// Number of control points of the fit (`M + 2`).
    #[must_use]
    pub fn n_ctrl(&self) -> usize {
        self.rows.n
    }

    /// Number of data points `N`.
    #[must_use]
    pub fn n_data(&self) -> usize {
        self.rows.first.len()
    }

    /// The fit's knot vector: the distinct data parameters, the end ones repeated four times.
    #[must_use]
    pub fn knots(&self) -> &[f64] {
        &self.knots
    }

    /// The sparse rows of `B`, the weights, and the factor `UᵀDU` of `BᵀWB + λΩ` as one
    /// triangle `R = D^{1/2} U` (`RᵀR = BᵀWB + λΩ`; `D > 0` after the factorisation): the whole
    /// map, [`FitLinearization`].
    #[must_use]
    pub fn linearize(&self) -> FitLinearization {
        let (n, b) = (self.matrix.n, self.matrix.b);
        let w = b + 1;
        let mut triangle = vec![0.0; n * w];
        for i in 0..n {
            let sd = self.matrix.a[i * w].sqrt();
            triangle[i * w] = sd;
            for k in 1..w.min(n - i) {
                triangle[i * w + k] = sd * self.matrix.a[i * w + k];
            }
        }
        FitLinearization {
            first: self.rows.first.clone(),
            basis: self.rows.basis.clone(),
            width: self.rows.width,
            weights: self.rows.weights.clone(),
            triangle,
            bandwidth: w,
            n_ctrl: self.rows.n,
        }
    }

    /// Forward-mode derivative: the control-point tangent `Ṗ = (BᵀWB + λΩ)⁻¹ BᵀW Q̇` for a
    /// data tangent `Q̇` (`N × dim`, point-major): the smoothing spline of `Q̇` itself.
    ///
    /// # Errors
    /// [`Error::LengthMismatch`] unless `data_tangent.len() == N · dim`; [`Error::NonFinite`];
    /// [`Error::Dimension`] for `dim == 0`.
    pub fn jvp(&self, data_tangent: &[f64], dim: usize) -> Result<Vec<f64>> {
        self.rows
            .jvp(data_tangent, dim, |x, dim| self.matrix.solve(x, dim))
    }

    /// Reverse-mode derivative: the data cotangent `Q̄ = W B (BᵀWB + λΩ)⁻¹ P̄` for a
    /// control-point cotangent `P̄` (`(M + 2) × dim`, point-major).
    ///
    /// # Errors
    /// [`Error::LengthMismatch`] unless `control_cotangent.len() == (M + 2) · dim`;
    /// [`Error::NonFinite`]; [`Error::Dimension`] for `dim == 0`.
    pub fn vjp(&self, control_cotangent: &[f64], dim: usize) -> Result<Vec<f64>> {
        self.rows
            .vjp(control_cotangent, dim, |x, dim| self.matrix.solve(x, dim))
    }
}

#[cfg(test)]
mod tests {
    use super::{LeastSquaresMap, SmoothingMap};
    use crate::error::Error;
    use crate::fit::{least_squares, smoothing_spline, EndConstraints, FitData, Lambda};
    use crate::knots::KnotVector;
    use crate::oracle::proptest_config;
    use crate::points::PointsRef;
    use proptest::prelude::*;

    /// Sorted parameters from gaps, starting at 0.
    fn params_of(gaps: &[f64]) -> Vec<f64> {
        let mut ts = vec![0.0];
        for g in gaps {
            ts.push(ts[ts.len() - 1] + g);
        }
        ts
    }

    /// `<a, b>` and the scale against which its rounding is measured.
    fn dot(a: &[f64], b: &[f64]) -> (f64, f64) {
        let s: f64 = a.iter().zip(b).map(|(x, y)| x * y).sum();
        let m: f64 = a.iter().zip(b).map(|(x, y)| (x * y).abs()).sum();
        (s, m)
    }

    fn close(a: &[f64], b: &[f64], rtol: f64) -> std::result::Result<(), TestCaseError> {
        let scale = b.iter().fold(1.0f64, |m, x| m.max(x.abs()));
        for (i, (x, y)) in a.iter().zip(b).enumerate() {
            prop_assert!(
                (x - y).abs() <= rtol * scale,
                "entry {}: {} against {}",
                i,
                x,
                y
            );
        }
        Ok(())
    }

    proptest! {
        #![proptest_config(proptest_config(64))]

        /// The least-squares JVP is the fit of the tangent (the fit is linear in the data), and
        /// the VJP is its transpose.
        #[test]
        fn least_squares_jvp_is_the_fit_and_vjp_its_transpose(
            p in 1usize..=4,
            interior in 0usize..4,
            gaps in prop::collection::vec(0.01f64..1.0, 25..40),
            dim in 1usize..=3,
            weighted in any::<bool>(),
            seed in prop::collection::vec(-1.0f64..1.0, 40 * 3 * 3),
        ) {
            let ts = params_of(&gaps);
            let (a, b) = (ts[0], ts[ts.len() - 1]);
            let mut knots = vec![a; p + 1];
            for j in 1..=interior {
                knots.push(a + (b - a) * j as f64 / (interior + 1) as f64);
            }
            knots.extend(std::iter::repeat_n(b, p + 1));
            let kv = KnotVector::new(knots).unwrap();
            let m = ts.len();
            let w: Vec<f64> = (0..m).map(|k| 0.5 + seed[2 * m * dim + k].abs()).collect();
            let weights = weighted.then_some(w.as_slice());
            let map = LeastSquaresMap::new(p, &kv, &ts, weights).unwrap();
            let dq = &seed[..m * dim];
            let dp = map.jvp(dq, dim).unwrap();
            let mut data = FitData::new(PointsRef::from_flat(dim, dq).unwrap(), &ts).unwrap();
            if let Some(w) = weights {
                data = data.with_weights(w).unwrap();
            }
            let fit = least_squares(&data, p, &kv, &EndConstraints::none()).unwrap();
            close(&dp, fit.curve.control_points().as_slice(), 1e-10)?;
            let g = &seed[m * dim..m * dim + map.n_ctrl() * dim];
            let gq = map.vjp(g, dim).unwrap();
            let ((lhs, l1), (rhs, r1)) = (dot(g, &dp), dot(&gq, dq));
            prop_assert!((lhs - rhs).abs() <= 1e-12 * (l1 + r1), "{} against {}", lhs, rhs);
        }

        /// The smoothing JVP is the smoothing spline of the tangent, and the VJP its transpose;
        /// also with repeated parameters (a zero gap), which share one basis row.
        #[test]
        fn smoothing_jvp_is_the_fit_and_vjp_its_transpose(
            gaps in prop::collection::vec(prop_oneof![4 => 0.01f64..1.0, 1 => Just(0.0)], 4..30),
            log_lambda in -9.0f64..0.0,
            dim in 1usize..=3,
            weighted in any::<bool>(),
            seed in prop::collection::vec(-1.0f64..1.0, 32 * 3 * 3),
        ) {
            let ts = params_of(&gaps);
            let m = ts.len();
            prop_assume!(gaps.iter().filter(|g| **g > 0.0).count() >= 2, "three distinct parameters");
            // λ relative to the data's scale, over the range the GCV scan covers (up to where
            // the fit is all but the least-squares line, `λ ≈ Σw·L³`): beyond it `G` is as
            // ill-conditioned as `λ/(Σw·L³)` and both sides of the checks lose digits to it
            let range = ts[m - 1] - ts[0];
            let lam = 10f64.powf(log_lambda) * m as f64 * range.powi(3);
            let w: Vec<f64> = (0..m).map(|k| 0.5 + seed[2 * 32 * 3 + k].abs()).collect();
            let weights = weighted.then_some(w.as_slice());
            let map = SmoothingMap::new(&ts, lam, weights).unwrap();
            let dq = &seed[..m * dim];
            let dp = map.jvp(dq, dim).unwrap();
            let mut data = FitData::new(PointsRef::from_flat(dim, dq).unwrap(), &ts).unwrap();
            if let Some(w) = weights {
                data = data.with_weights(w).unwrap();
            }
            let fit = smoothing_spline(&data, Lambda::Given(lam)).unwrap();
            prop_assert_eq!(fit.curve.knots().as_slice(), map.knots());
            // the same operations as the fit (shifted data, the same factors): the same bits
            prop_assert_eq!(dp.as_slice(), fit.curve.control_points().as_slice());
            let g = &seed[32 * 3..32 * 3 + map.n_ctrl() * dim];
            let gq = map.vjp(g, dim).unwrap();
            let ((lhs, l1), (rhs, r1)) = (dot(g, &dp), dot(&gq, dq));
            // rounding grows with the condition of G = RᵀR, at least (max R_ii / min R_ii)²
            let lin = map.linearize();
            let diag = lin.triangle.iter().step_by(lin.bandwidth);
            let (hi, lo) = diag.fold((0.0f64, f64::INFINITY), |(h, l), &d| (h.max(d), l.min(d)));
            let kappa = (hi / lo).powi(2);
            let tol = 16.0 * f64::EPSILON * kappa.max(1.0) * (l1 + r1);
            prop_assert!((lhs - rhs).abs() <= tol, "{} against {} (κ ≥ {:e})", lhs, rhs, kappa);
        }
    }

    /// `(RᵀR)⁻¹ BᵀW q` from a [`FitLinearization`], dense: what a framework computes with it.
    fn apply(lin: &super::FitLinearization, q: &[f64]) -> Vec<f64> {
        let (n, bw) = (lin.n_ctrl, lin.bandwidth);
        let mut x = vec![0.0; n];
        for (k, &f) in lin.first.iter().enumerate() {
            for a in 0..lin.width {
                x[f + a] += lin.weights[k] * lin.basis[k * lin.width + a] * q[k];
            }
        }
        let r = |i: usize, j: usize| {
            if j >= i && j - i < bw {
                lin.triangle[i * bw + j - i]
            } else {
                0.0
            }
        };
        for i in 0..n {
            x[i] = (x[i] - (0..i).map(|k| r(k, i) * x[k]).sum::<f64>()) / r(i, i);
        }
        for i in (0..n).rev() {
            x[i] = (x[i] - (i + 1..n).map(|k| r(i, k) * x[k]).sum::<f64>()) / r(i, i);
        }
        x
    }

    #[test]
    fn linearizations_give_the_maps() {
        let ts: Vec<f64> = (0..30).map(|k| (k as f64 / 29.0).powf(1.3)).collect();
        let q: Vec<f64> = ts.iter().map(|t| (5.0 * t).sin()).collect();
        let w: Vec<f64> = (0..30).map(|k| 1.0 + (k % 3) as f64).collect();
        let kv =
            KnotVector::new(vec![0.0, 0.0, 0.0, 0.0, 0.3, 0.5, 0.8, 1.0, 1.0, 1.0, 1.0]).unwrap();
        let lsq = LeastSquaresMap::new(3, &kv, &ts, Some(&w)).unwrap();
        let sm = SmoothingMap::new(&ts, 1e-4, Some(&w)).unwrap();
        for (lin, want) in [
            (lsq.linearize(), lsq.jvp(&q, 1).unwrap()),
            (sm.linearize(), sm.jvp(&q, 1).unwrap()),
        ] {
            let got = apply(&lin, &q);
            assert_eq!(got.len(), want.len());
            for (a, b) in got.iter().zip(&want) {
                assert!((a - b).abs() <= 1e-10 * b.abs().max(1.0), "{a} against {b}");
            }
        }
    }

    #[test]
    fn errors_name_the_problem() {
        let kv = KnotVector::new(vec![0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0]).unwrap();
        let ts = [0.0, 0.2, 0.4, 0.6, 0.8, 1.0];
        let map = LeastSquaresMap::new(2, &kv, &ts, None).unwrap();
        let e = map.jvp(&[1.0; 5], 1).unwrap_err();
        assert!(
            matches!(
                e,
                Error::LengthMismatch {
                    expected: 6,
                    got: 5,
                    ..
                }
            ),
            "{e:?}"
        );
        let e = map.vjp(&[1.0, f64::NAN, 0.0, 0.0], 1).unwrap_err();
        assert!(matches!(e, Error::NonFinite { index: 1, .. }), "{e:?}");
        let e = map.vjp(&[], 0).unwrap_err();
        assert!(matches!(e, Error::Dimension { .. }), "{e:?}");
        // no data under the last basis functions
        let e = LeastSquaresMap::new(2, &kv, &[0.0, 0.1, 0.2, 0.3, 0.4], None).unwrap_err();
        assert!(matches!(e, Error::SchoenbergWhitney { .. }), "{e:?}");
        // weight 0 on the only data of the second span
        let e = LeastSquaresMap::new(
            2,
            &kv,
            &[0.0, 0.1, 0.2, 0.3, 0.7, 0.8],
            Some(&[1.0, 1.0, 1.0, 1.0, 0.0, 0.0]),
        )
        .unwrap_err();
        assert!(matches!(e, Error::SchoenbergWhitney { .. }), "{e:?}");
        let e = LeastSquaresMap::new(2, &kv, &[0.0, 0.2, 0.4, 0.6, 1.5], None).unwrap_err();
        assert!(matches!(e, Error::ParameterOutOfDomain { .. }), "{e:?}");
        let e = SmoothingMap::new(&ts, -1.0, None).unwrap_err();
        assert!(matches!(e, Error::NegativeSmoothing { .. }), "{e:?}");
        let e = SmoothingMap::new(&ts, 0.0, None).unwrap_err();
        assert!(matches!(e, Error::InvalidArgument { .. }), "{e:?}");
        // a repeated parameter is the smoothing spline's (one basis row for both points); a
        // decreasing one, or fewer than three distinct, are refused as the fit refuses them
        let map = SmoothingMap::new(&[0.0, 0.5, 0.5, 1.0], 1.0, None).unwrap();
        assert_eq!((map.n_data(), map.n_ctrl()), (4, 5));
        let e = SmoothingMap::new(&[0.0, 0.5, 0.4, 1.0], 1.0, None).unwrap_err();
        assert!(matches!(e, Error::NotIncreasing { index: 2, .. }), "{e:?}");
        let e = SmoothingMap::new(&[0.0, 0.5, 0.5, 0.5], 1.0, None).unwrap_err();
        assert!(matches!(e, Error::TooFew { got: 2, .. }), "{e:?}");
        let map = SmoothingMap::new(&ts, 1.0, None).unwrap();
        let e = map.vjp(&[1.0; 6], 1).unwrap_err();
        assert!(
            matches!(
                e,
                Error::LengthMismatch {
                    expected: 8,
                    got: 6,
                    ..
                }
            ),
            "{e:?}"
        );
    }
}
