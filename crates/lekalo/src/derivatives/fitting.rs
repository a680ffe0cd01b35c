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
use crate::fit::banded::{BandedQr, RANK_RTOL};
use crate::fit::{for_each_row, least_squares_qr, smoothing_system, FitData, SmoothingSystem};
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
    /// The banded triangle `R` of the QR of `√W B`, `triangle[i·w + k] = R[i][i + k]`
    /// (`w = rows.width`).
    triangle: Vec<f64>,
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
        let zeros = vec![0.0; params.len()];
        let mut data = FitData::new(PointsRef::from_flat(1, &zeros)?, params)?;
        if let Some(w) = weights {
            data = data.with_weights(w)?;
        }
        let (_, qr) = least_squares_qr(&data, degree, knots)?;
        Self::of_qr(&data, degree, knots, qr)
    }

    /// The map of the fit of `data` whose banded QR is `qr` ([`crate::fit::least_squares_qr`],
    /// on any data values at the same parameters and weights: `R` does not depend on them): the
    /// rows of `B` evaluated, and `R` checked for a rank deficiency.
    ///
    /// # Errors
    /// [`Error::SchoenbergWhitney`] for a basis function with no data of positive weight under
    /// it (a zero pivot of `R`).
    pub(super) fn of_qr(
        data: &FitData<'_>,
        degree: usize,
        knots: &KnotVector,
        qr: BandedQr,
    ) -> Result<Self> {
        let width = degree + 1;
        let n = knots.len() - width;
        let m = data.len();
        let wmax = data
            .weights()
            .map_or(1.0, |w| w.iter().fold(0.0_f64, |m, &v| m.max(v)));
        let weights: Vec<f64> = (0..m)
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
        let on_row = |k: usize, span: usize, row: &[f64]| {
            first[k] = span - degree;
            basis[k * width..(k + 1) * width].copy_from_slice(row);
        };
        match data.order() {
            None => for_each_row(knots, degree, data.params(), 0..m, |_| 1.0, on_row),
            Some(order) => for_each_row(knots, degree, data.params(), order, |_| 1.0, on_row),
        }
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
                weights,
                n,
            },
            triangle: qr.r,
        })
    }

    /// Length of [`LeastSquaresMap::to_flat`] for `n_data` data points and `n_ctrl` control
    /// points of degree `degree`: `(degree + 3)·n_data + (degree + 1)·n_ctrl`; `None` on
    /// overflow.
    #[must_use]
    pub fn flat_len(n_data: usize, n_ctrl: usize, degree: usize) -> Option<usize> {
        let width = degree.checked_add(1)?;
        n_data
            .checked_mul(width.checked_add(2)?)?
            .checked_add(n_ctrl.checked_mul(width)?)
    }

    /// The whole map as numbers, for a caller that keeps it between the values and their
    /// derivatives (an automatic-differentiation framework's residual): for `N` data points, `n`
    /// control points and `w = p + 1`, `first` (`N`, as floats, exact below 2⁵³), the rows of
    /// `B` (`wN`), the weights (`N`) and the banded triangle `R` (`wn`, row `i` holding
    /// `R[i][i..i + w]`): [`LeastSquaresMap::flat_len`] numbers.
    /// [`LeastSquaresMap::from_flat`] reads it back into the same map, so that its JVP and VJP
    /// have the same bits.
    #[must_use]
    pub fn to_flat(&self) -> Vec<f64> {
        let r = &self.rows;
        let mut out = Vec::with_capacity(r.first.len() * (r.width + 2) + self.triangle.len());
        out.extend(r.first.iter().map(|&f| f as f64));
        out.extend_from_slice(&r.basis);
        out.extend_from_slice(&r.weights);
        out.extend_from_slice(&self.triangle);
        out
    }

    /// The map written by [`LeastSquaresMap::to_flat`] for `n_data` data points of degree
    /// `degree`, checked enough that applying it cannot index out of its bounds.
    ///
    /// # Errors
    /// [`Error::LengthMismatch`] unless `flat` has `(p + 3)·n_data + (p + 1)·n` numbers for
    /// some `n ≥ p + 1`; [`Error::InvalidArgument`] for a first index that is not a whole
    /// number in `0..=n − p − 1`; [`Error::TooLarge`] when the sizes overflow.
    pub fn from_flat(flat: &[f64], n_data: usize, degree: usize) -> Result<Self> {
        let what = "factors of a least-squares fit (LeastSquaresMap::to_flat)";
        let too_large = || Error::TooLarge {
            what: what.into(),
            size: n_data,
            max: usize::MAX / degree.saturating_add(3),
        };
        let width = degree.checked_add(1).ok_or_else(too_large)?;
        let rows_len = Self::flat_len(n_data, 0, degree).ok_or_else(too_large)?;
        let n = flat
            .len()
            .checked_sub(rows_len)
            .map(|rest| rest / width)
            .filter(|&n| n >= width && rows_len + width * n == flat.len())
            .ok_or(Error::LengthMismatch {
                what: what.into(),
                expected: rows_len + width * width,
                got: flat.len(),
            })?;
        let (first, rest) = flat.split_at(n_data);
        let (basis, rest) = rest.split_at(width * n_data);
        let (weights, triangle) = rest.split_at(n_data);
        Ok(LeastSquaresMap {
            rows: Rows {
                first: first_indices(first, n - width, what)?,
                basis: basis.to_vec(),
                width,
                weights: weights.to_vec(),
                n,
            },
            triangle: triangle.to_vec(),
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
            triangle: self.triangle.clone(),
            bandwidth: self.rows.width,
            n_ctrl: self.rows.n,
        }
    }

    /// The weights `W` as the map applies them (divided by the largest; `G = BᵀWB` with them).
    pub(super) fn weights(&self) -> &[f64] {
        &self.rows.weights
    }

    /// `BᵀW y` for `y` of `N × dim`, point-major (no shift).
    pub(super) fn transpose_weighted(&self, y: &[f64], dim: usize) -> Vec<f64> {
        self.rows.transpose_weighted(y, dim)
    }

    /// `W B x` for `x` of `n × dim`, point-major (no shift).
    pub(super) fn weighted(&self, x: &[f64], dim: usize) -> Vec<f64> {
        self.rows.weighted(x, dim)
    }

    /// `x ← (RᵀR)⁻¹ x`: a forward sweep with `Rᵀ`, a backward sweep with `R` (banded).
    pub(super) fn solve_normal(&self, x: &mut [f64], dim: usize) {
        let (n, bw, r) = (self.rows.n, self.rows.width, &self.triangle);
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

/// The first basis function of each data point as [`LeastSquaresMap::to_flat`] and
/// [`SmoothingMap::to_flat`] write them (floats), read back as indices in `0..=max`.
///
/// # Errors
/// [`Error::InvalidArgument`] (naming `what`) for a number that is not a whole number in
/// `0..=max`.
fn first_indices(first: &[f64], max: usize, what: &'static str) -> Result<Vec<usize>> {
    first
        .iter()
        .enumerate()
        .map(|(k, &f)| {
            if f >= 0.0 && f.fract() == 0.0 && f <= max as f64 {
                // a whole number in 0..=max: exact
                #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
                let i = f as usize;
                Ok(i)
            } else {
                Err(Error::InvalidArgument {
                    what: what.into(),
                    reason: format!(
                        "data point {k} has first basis function {f}, not a whole number in \
                         0..={max}"
                    ),
                })
            }
        })
        .collect()
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
        Ok(SmoothingMap {
            rows: Rows {
                first: first_indices(first, n - 4, what)?,
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
#[path = "fitting_tests.rs"]
mod tests;
