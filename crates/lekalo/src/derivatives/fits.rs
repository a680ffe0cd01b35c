//! The least-squares fit on given knots and parameters and the smoothing spline with a given
//! `λ > 0` as differentiable functions of their data values, for a caller that holds flat
//! buffers (an automatic-differentiation framework's kernel): the control points bit for bit
//! those of [`crate::fit::least_squares`] (no end constraints) and
//! [`crate::fit::smoothing_spline`] with [`Lambda::Given`], and their derivatives with respect
//! to the data, `Ṗ = G⁻¹ BᵀW Q̇` and `Q̄ = W B G⁻¹ P̄` (`G = BᵀWB`, or `BᵀWB + λΩ`), by
//! `fitting.rs`'s [`LeastSquaresMap`] and [`SmoothingMap`] (`docs/theory/derivatives.md#fits`).
//! The parameters, knots, weights and `λ` are constants. Each type holds the data too and checks
//! all of it as the fit does when made, so a derivative of a fit lekalo refuses (NaN data, say)
//! fails as the fit's values fail, with the fit's error.

use super::fitting::{check_lambda, LeastSquaresMap, SmoothingMap};
use crate::error::Result;
use crate::fit::{
    least_squares, least_squares_values_and_qr, smoothing_spline, smoothing_values_and_system,
    EndConstraints, FitData, Lambda,
};
use crate::knots::KnotVector;
use crate::points::PointsRef;

/// The fit's data: `points` (`m × dim`, point-major) at `params`, with `weights` if given.
///
/// # Errors
/// [`crate::Error::Dimension`] for `dim == 0` or a length not a multiple of `dim`; as [`FitData::new`]
/// and [`FitData::with_weights`].
fn fit_data<'a>(
    points: &'a [f64],
    dim: usize,
    params: &'a [f64],
    weights: Option<&'a [f64]>,
) -> Result<FitData<'a>> {
    let data = FitData::new(PointsRef::from_flat(dim, points)?, params)?;
    match weights {
        Some(w) => data.with_weights(w),
        None => Ok(data),
    }
}

/// The weighted least-squares fit of degree `p` on given knots at given parameters (no end
/// constraints) as a function of the data values `Q`: `P = (BᵀWB)⁻¹ BᵀW Q`, with `B[k][i] =
/// N_{i,p}(ū_k)` and `W = diag(w_k)` (`docs/theory/derivatives.md#fits`).
///
/// ```
/// use lekalo::derivatives::LeastSquaresFit;
/// let params: Vec<f64> = (0..12).map(|k| k as f64 / 11.0).collect();
/// let points: Vec<f64> = params.iter().map(|x| x * x).collect();
/// let knots = [0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0];
/// let fit = LeastSquaresFit::new(2, &knots, &params, &points, 1, None)?;
/// // x² is in the space: the fit reproduces it, and moving every value by 1 moves every control
/// // point by 1 (B 1 = 1)
/// let ctrl = fit.control_points()?;
/// assert!((ctrl[0] - 0.0).abs() < 1e-14 && (ctrl[3] - 1.0).abs() < 1e-14);
/// let dp = fit.jvp(&[1.0; 12])?;
/// assert!(dp.iter().all(|v| (v - 1.0).abs() < 1e-13));
/// # Ok::<(), lekalo::Error>(())
/// ```
#[derive(Debug, Clone)]
pub struct LeastSquaresFit<'a> {
    pub(super) degree: usize,
    pub(super) knots: KnotVector,
    pub(super) data: FitData<'a>,
}

impl<'a> LeastSquaresFit<'a> {
    /// The fit of `degree` on `knots` of `points` (`m × dim`, point-major) at `params` (any
    /// order), with `weights` `w_k ≥ 0` if given.
    ///
    /// # Errors
    /// As [`fit_data`] and [`KnotVector::new`]; the fit's own conditions (degree, domain,
    /// Schoenberg–Whitney) are checked when it is computed.
    pub fn new(
        degree: usize,
        knots: &[f64],
        params: &'a [f64],
        points: &'a [f64],
        dim: usize,
        weights: Option<&'a [f64]>,
    ) -> Result<Self> {
        Ok(LeastSquaresFit {
            degree,
            data: fit_data(points, dim, params, weights)?,
            knots: KnotVector::new(knots.to_vec())?,
        })
    }

    /// Number of control points, `len(knots) − p − 1` (0 when there are too few knots, which
    /// the fit refuses).
    #[must_use]
    pub fn n_ctrl(&self) -> usize {
        self.knots.len().saturating_sub(self.degree + 1)
    }

    /// The control points of the fit, `n × dim`: those of [`crate::fit::least_squares`] with
    /// [`EndConstraints::none`], bit for bit.
    ///
    /// # Errors
    /// As [`crate::fit::least_squares`] ([`crate::Error::SchoenbergWhitney`] when a basis
    /// function has no data of positive weight under it).
    pub fn control_points(&self) -> Result<Vec<f64>> {
        let fit = least_squares(
            &self.data,
            self.degree,
            &self.knots,
            &EndConstraints::none(),
        )?;
        Ok(fit.curve.control_points().as_slice().to_vec())
    }

    /// The fit's linear map from data to control points, factored once.
    ///
    /// # Errors
    /// As [`LeastSquaresMap::new`].
    pub fn map(&self) -> Result<LeastSquaresMap> {
        LeastSquaresMap::new(
            self.degree,
            &self.knots,
            self.data.params(),
            self.data.weights(),
        )
    }

    /// The control points of [`LeastSquaresFit::control_points`] (bit for bit) and the map of
    /// [`LeastSquaresFit::map`] (the same bits) from one banded QR of the data rows: for a
    /// caller that differentiates after the values (JAX's forward pass keeps the map for the
    /// reverse one) and would otherwise factor the rows twice.
    ///
    /// # Errors
    /// As [`LeastSquaresFit::control_points`].
    pub fn control_points_and_map(&self) -> Result<(Vec<f64>, LeastSquaresMap)> {
        let (control, qr) = least_squares_values_and_qr(&self.data, self.degree, &self.knots)?;
        let map = LeastSquaresMap::of_qr(&self.data, self.degree, &self.knots, qr)?;
        Ok((control, map))
    }

    /// Forward-mode derivative: `Ṗ = (BᵀWB)⁻¹ BᵀW Q̇` for a data tangent `Q̇` (`m × dim`).
    ///
    /// # Errors
    /// As [`LeastSquaresMap::new`] and [`LeastSquaresMap::jvp`].
    pub fn jvp(&self, data_tangent: &[f64]) -> Result<Vec<f64>> {
        self.map()?.jvp(data_tangent, self.data.points().dim())
    }

    /// Reverse-mode derivative: `Q̄ = W B (BᵀWB)⁻¹ P̄` for a control-point cotangent `P̄`
    /// (`n × dim`).
    ///
    /// # Errors
    /// As [`LeastSquaresMap::new`] and [`LeastSquaresMap::vjp`].
    pub fn vjp(&self, control_cotangent: &[f64]) -> Result<Vec<f64>> {
        self.map()?.vjp(control_cotangent, self.data.points().dim())
    }
}

/// The cubic smoothing spline with a given `λ > 0` through data values `y` at `x` as a function
/// of `y`: `P = (BᵀWB + λΩ)⁻¹ BᵀW y` on the knots `x` with its ends repeated four times
/// (`docs/theory/fitting.md#penalised`, `docs/theory/derivatives.md#fits`).
///
/// ```
/// use lekalo::derivatives::SmoothingFit;
/// let x = [0.0, 0.2, 0.5, 0.7, 1.0];
/// let y = [1.0, 1.4, 2.0, 2.4, 3.0];
/// let fit = SmoothingFit::new(&x, &y, 1, 1e-2, None)?;
/// // a line has no penalty: the smoothing spline of a line is the line
/// let ctrl = fit.control_points()?;
/// assert_eq!(ctrl.len(), 7);
/// assert!((ctrl[0] - 1.0).abs() < 1e-12 && (ctrl[6] - 3.0).abs() < 1e-12);
/// # Ok::<(), lekalo::Error>(())
/// ```
#[derive(Debug, Clone)]
pub struct SmoothingFit<'a> {
    data: FitData<'a>,
    lambda: f64,
}

impl<'a> SmoothingFit<'a> {
    /// The smoothing spline of `points` (`m × dim`, point-major) at the non-decreasing `params`
    /// with `weights` `w_k ≥ 0` if given, for the penalty weight `lambda > 0`.
    ///
    /// # Errors
    /// [`crate::Error::NegativeSmoothing`] for `lambda < 0` or not finite;
    /// [`crate::Error::InvalidArgument`] for `lambda == 0` (interpolation, not a smoothing
    /// spline here); as [`fit_data`]. The order of the parameters is checked when the fit is
    /// computed.
    pub fn new(
        params: &'a [f64],
        points: &'a [f64],
        dim: usize,
        lambda: f64,
        weights: Option<&'a [f64]>,
    ) -> Result<Self> {
        check_lambda(lambda)?;
        Ok(SmoothingFit {
            data: fit_data(points, dim, params, weights)?,
            lambda,
        })
    }

    /// The control points of the smoothing spline, `(M + 2) × dim` for `M` distinct
    /// parameters: those of [`crate::fit::smoothing_spline`] with [`Lambda::Given`], bit for
    /// bit.
    ///
    /// # Errors
    /// As [`crate::fit::smoothing_spline`].
    pub fn control_points(&self) -> Result<Vec<f64>> {
        let fit = smoothing_spline(&self.data, Lambda::Given(self.lambda))?;
        Ok(fit.curve.control_points().as_slice().to_vec())
    }

    /// The fit's linear map from data to control points, factored once.
    ///
    /// # Errors
    /// As [`SmoothingMap::new`].
    pub fn map(&self) -> Result<SmoothingMap> {
        SmoothingMap::new(self.data.params(), self.lambda, self.data.weights())
    }

    /// The control points of [`SmoothingFit::control_points`] (bit for bit) and the map of
    /// [`SmoothingFit::map`] (the same factors) from one assembly and one factorisation of
    /// `BᵀWB + λΩ`: for a caller that differentiates after the values (JAX's forward pass keeps
    /// the map for the reverse one) and would otherwise factor the system twice.
    ///
    /// # Errors
    /// As [`SmoothingFit::map`]; where the factorisation fails with every weight positive
    /// (`λ` below the rounding of `BᵀWB`), [`SmoothingFit::control_points`] gives the
    /// interpolant, which has no map, and this its error.
    pub fn control_points_and_map(&self) -> Result<(Vec<f64>, SmoothingMap)> {
        let (control, sys) = smoothing_values_and_system(&self.data, self.lambda)?;
        Ok((control, SmoothingMap::of_system(sys)))
    }

    /// Forward-mode derivative: `Ṗ = (BᵀWB + λΩ)⁻¹ BᵀW Q̇` for a data tangent `Q̇` (`m × dim`).
    ///
    /// # Errors
    /// As [`SmoothingMap::new`] and [`SmoothingMap::jvp`].
    pub fn jvp(&self, data_tangent: &[f64]) -> Result<Vec<f64>> {
        self.map()?.jvp(data_tangent, self.data.points().dim())
    }

    /// Reverse-mode derivative: `Q̄ = W B (BᵀWB + λΩ)⁻¹ P̄` for a control-point cotangent
    /// `P̄` (`(M + 2) × dim`).
    ///
    /// # Errors
    /// As [`SmoothingMap::new`] and [`SmoothingMap::vjp`].
    pub fn vjp(&self, control_cotangent: &[f64]) -> Result<Vec<f64>> {
        self.map()?.vjp(control_cotangent, self.data.points().dim())
    }
}

#[cfg(test)]
mod tests {
    use super::{LeastSquaresFit, SmoothingFit};
    use crate::error::Error;

    fn case() -> (Vec<f64>, Vec<f64>, Vec<f64>) {
        let x: Vec<f64> = (0..25).map(|k| (k as f64 / 24.0).powf(1.2)).collect();
        let y: Vec<f64> = x
            .iter()
            .flat_map(|t| [(4.0 * t).sin(), (3.0 * t).cos() + 100.0])
            .collect();
        let w: Vec<f64> = (0..25).map(|k| 0.5 + (k % 4) as f64 * 0.3).collect();
        (x, y, w)
    }

    /// `(a − b) / ε` at the data `y ± ε e_j`, for a map `f` linear in `y`: the JVP of `e_j`,
    /// which a linear map reproduces up to rounding.
    fn column(f: impl Fn(&[f64]) -> Vec<f64>, y: &[f64], j: usize) -> Vec<f64> {
        let eps = 1e-3;
        let (mut up, mut down) = (y.to_vec(), y.to_vec());
        up[j] += eps;
        down[j] -= eps;
        let (a, b) = (f(&up), f(&down));
        a.iter()
            .zip(&b)
            .map(|(p, q)| (p - q) / (2.0 * eps))
            .collect()
    }

    fn assert_close(a: &[f64], b: &[f64], rtol: f64) {
        assert_eq!(a.len(), b.len(), "lengths");
        let scale = b.iter().fold(1.0f64, |m, v| m.max(v.abs()));
        for (i, (p, q)) in a.iter().zip(b).enumerate() {
            assert!((p - q).abs() <= rtol * scale, "entry {i}: {p} against {q}");
        }
    }

    /// The JVP of each unit data vector `e_j` (`j` in `js`) against the central differences of
    /// `values` in `y[j]`, and the VJP of `g` against `g · (∂values/∂y_j)`, both to 1e-8.
    fn check_against_differences(
        values: impl Fn(&[f64]) -> Vec<f64>,
        jvp: impl Fn(&[f64]) -> Vec<f64>,
        gq: &[f64],
        g: &[f64],
        y: &[f64],
        js: [usize; 4],
    ) {
        for j in js {
            let mut e = vec![0.0; y.len()];
            e[j] = 1.0;
            let fd = column(&values, y, j);
            assert_close(&jvp(&e), &fd, 1e-8);
            let dot: f64 = g.iter().zip(&fd).map(|(a, b)| a * b).sum();
            assert!(
                (gq[j] - dot).abs() <= 1e-8 * dot.abs().max(1.0),
                "VJP entry {j}"
            );
        }
    }

    #[test]
    fn least_squares_derivatives_are_differences_of_the_values() {
        let (x, y, w) = case();
        let knots = [0.0, 0.0, 0.0, 0.0, 0.3, 0.6, 1.0, 1.0, 1.0, 1.0];
        for weights in [None, Some(w.as_slice())] {
            let fit = LeastSquaresFit::new(3, &knots, &x, &y, 2, weights).unwrap();
            assert_eq!(fit.n_ctrl(), 6);
            let values = |q: &[f64]| {
                let f = LeastSquaresFit::new(3, &knots, &x, q, 2, weights).unwrap();
                f.control_points().unwrap()
            };
            let g: Vec<f64> = (0..12).map(|i| (i as f64 * 0.7).sin()).collect();
            let gq = fit.vjp(&g).unwrap();
            let jvp = |e: &[f64]| fit.jvp(e).unwrap();
            check_against_differences(values, jvp, &gq, &g, &y, [0, 7, 31, 49]);
        }
    }

    #[test]
    fn smoothing_derivatives_are_differences_of_the_values() {
        let (x, y, w) = case();
        for weights in [None, Some(w.as_slice())] {
            let fit = SmoothingFit::new(&x, &y, 2, 1e-3, weights).unwrap();
            let values = |q: &[f64]| {
                let f = SmoothingFit::new(&x, q, 2, 1e-3, weights).unwrap();
                f.control_points().unwrap()
            };
            assert_eq!(fit.control_points().unwrap().len(), 27 * 2);
            let g: Vec<f64> = (0..54).map(|i| (i as f64 * 0.3).cos()).collect();
            let gq = fit.vjp(&g).unwrap();
            let jvp = |e: &[f64]| fit.jvp(e).unwrap();
            check_against_differences(values, jvp, &gq, &g, &y, [0, 12, 33, 49]);
        }
    }

    /// One factorisation for the values and the map: the values are the fit's and the map's
    /// JVP and VJP those of the map factored on its own, bit for bit, also through the map's
    /// flat form; a flat form of the wrong length or with a first index out of the band is
    /// refused.
    #[test]
    fn values_and_map_from_one_factorisation_have_the_bits_of_each() {
        use crate::derivatives::SmoothingMap;
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        let (x, y, w) = case();
        let t: Vec<f64> = (0..50).map(|i| (i as f64 * 0.37).sin()).collect();
        let g: Vec<f64> = (0..54).map(|i| (i as f64 * 0.3).cos()).collect();
        for weights in [None, Some(w.as_slice())] {
            let fit = SmoothingFit::new(&x, &y, 2, 1e-3, weights).unwrap();
            let (values, map) = fit.control_points_and_map().unwrap();
            assert_eq!(bits(&values), bits(&fit.control_points().unwrap()));
            let alone = fit.map().unwrap();
            let flat = map.to_flat();
            assert_eq!(Some(flat.len()), SmoothingMap::flat_len(25), "flat length");
            let back = SmoothingMap::from_flat(&flat, 25).unwrap();
            for m in [&map, &back] {
                assert_eq!(bits(&m.jvp(&t, 2).unwrap()), bits(&fit.jvp(&t).unwrap()));
                assert_eq!(
                    bits(&m.vjp(&g, 2).unwrap()),
                    bits(&alone.vjp(&g, 2).unwrap())
                );
                assert_eq!(m.knots(), alone.knots(), "knots");
            }
        }
        let flat = SmoothingFit::new(&x, &y, 2, 1e-3, None)
            .unwrap()
            .control_points_and_map()
            .unwrap()
            .1
            .to_flat();
        let e = SmoothingMap::from_flat(&flat[1..], 25).unwrap_err();
        assert!(matches!(e, Error::LengthMismatch { .. }), "{e:?}");
        for bad in [-1.0, 0.5, 24.0, f64::NAN] {
            let mut f = flat.clone();
            f[3] = bad;
            let e = SmoothingMap::from_flat(&f, 25).unwrap_err();
            assert!(matches!(e, Error::InvalidArgument { .. }), "{bad}: {e:?}");
        }
    }

    /// The least-squares fit's values and map from one QR: the values are the fit's, the map
    /// is the map factored on its own (every number of its linearisation, bit for bit; data in
    /// any order, weighted or not), also through its flat form; a flat form of the wrong length
    /// or with a first index out of the band is refused.
    #[test]
    fn least_squares_values_and_map_from_one_qr_have_the_bits_of_each() {
        use crate::derivatives::LeastSquaresMap;
        use crate::KnotVector;
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        let (mut x, y, w) = case();
        x.swap(3, 17);
        let knots = [0.0, 0.0, 0.0, 0.0, 0.3, 0.6, 1.0, 1.0, 1.0, 1.0];
        let kv = KnotVector::new(knots.to_vec()).unwrap();
        let t: Vec<f64> = (0..50).map(|i| (i as f64 * 0.37).sin()).collect();
        let g: Vec<f64> = (0..12).map(|i| (i as f64 * 0.7).sin()).collect();
        for weights in [None, Some(w.as_slice())] {
            let fit = LeastSquaresFit::new(3, &knots, &x, &y, 2, weights).unwrap();
            let (values, map) = fit.control_points_and_map().unwrap();
            assert_eq!(bits(&values), bits(&fit.control_points().unwrap()));
            let alone = LeastSquaresMap::new(3, &kv, &x, weights).unwrap();
            assert_eq!(map.linearize(), alone.linearize(), "the same map");
            let flat = map.to_flat();
            assert_eq!(Some(flat.len()), LeastSquaresMap::flat_len(25, 6, 3));
            let back = LeastSquaresMap::from_flat(&flat, 25, 3).unwrap();
            assert_eq!(back.linearize(), alone.linearize(), "read back");
            for m in [&map, &back] {
                assert_eq!(bits(&m.jvp(&t, 2).unwrap()), bits(&fit.jvp(&t).unwrap()));
                assert_eq!(bits(&m.vjp(&g, 2).unwrap()), bits(&fit.vjp(&g).unwrap()));
            }
        }
        let flat = LeastSquaresFit::new(3, &knots, &x, &y, 2, None)
            .unwrap()
            .control_points_and_map()
            .unwrap()
            .1
            .to_flat();
        for cut in [&flat[1..], &flat[..flat.len() - 1]] {
            let e = LeastSquaresMap::from_flat(cut, 25, 3).unwrap_err();
            assert!(matches!(e, Error::LengthMismatch { .. }), "{e:?}");
        }
        let e = LeastSquaresMap::from_flat(&flat, usize::MAX / 2, 3).unwrap_err();
        assert!(matches!(e, Error::TooLarge { .. }), "{e:?}");
        for bad in [-1.0, 0.5, 3.0, f64::NAN] {
            let mut f = flat.clone();
            f[3] = bad;
            let e = LeastSquaresMap::from_flat(&f, 25, 3).unwrap_err();
            assert!(matches!(e, Error::InvalidArgument { .. }), "{bad}: {e:?}");
        }
        // no data in the last spans: the fit's error, from the values and the map alike
        let few: Vec<f64> = x.iter().map(|t| t * 0.25).collect();
        let fit = LeastSquaresFit::new(3, &knots, &few, &y, 2, None).unwrap();
        let e = fit.control_points_and_map().unwrap_err();
        assert_eq!(e, fit.control_points().unwrap_err());
    }

    #[test]
    fn errors_are_the_fits() {
        let (x, y, _) = case();
        // no data in (0.9, 1): the last basis function has nothing under it
        let knots = [0.0, 0.0, 0.0, 0.0, 0.9, 0.95, 1.0, 1.0, 1.0, 1.0];
        let few: Vec<f64> = x.iter().map(|t| t * 0.85).collect();
        let fit = LeastSquaresFit::new(3, &knots, &few, &y, 2, None).unwrap();
        let e = fit.control_points().unwrap_err();
        assert!(matches!(e, Error::SchoenbergWhitney { .. }), "{e:?}");
        let e = fit.jvp(&y).unwrap_err();
        assert!(matches!(e, Error::SchoenbergWhitney { .. }), "{e:?}");
        let good = [0.0, 0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0, 1.0];
        let mut bad = y.clone();
        bad[3] = f64::NAN;
        let e = LeastSquaresFit::new(3, &good, &x, &bad, 2, None).unwrap_err();
        assert!(matches!(e, Error::NonFinite { index: 3, .. }), "{e:?}");
        let e = SmoothingFit::new(&x, &bad, 2, 1.0, None).unwrap_err();
        assert!(matches!(e, Error::NonFinite { index: 3, .. }), "{e:?}");
        let e = LeastSquaresFit::new(3, &good, &x, &y, 0, None).unwrap_err();
        assert!(matches!(e, Error::Dimension { .. }), "{e:?}");
        let e = LeastSquaresFit::new(3, &[0.0, 1.0, 0.5], &x, &y, 2, None).unwrap_err();
        assert!(matches!(e, Error::KnotsNotSorted { .. }), "{e:?}");
        let e = SmoothingFit::new(&x, &y, 2, -1.0, None).unwrap_err();
        assert!(matches!(e, Error::NegativeSmoothing { .. }), "{e:?}");
        let e = SmoothingFit::new(&x, &y, 2, 0.0, None).unwrap_err();
        assert!(matches!(e, Error::InvalidArgument { .. }), "{e:?}");
        let e = SmoothingFit::new(&x, &y[..48], 2, 1.0, None).unwrap_err();
        assert!(matches!(e, Error::LengthMismatch { .. }), "{e:?}");
        let w = vec![-1.0; 25];
        let e = SmoothingFit::new(&x, &y, 2, 1.0, Some(&w)).unwrap_err();
        assert!(
            matches!(e, Error::InvalidDataWeight { index: 0, .. }),
            "{e:?}"
        );
        // decreasing parameters: the smoothing spline's error, from the values and the map
        let mut rev = x.clone();
        rev.swap(3, 4);
        let fit = SmoothingFit::new(&rev, &y, 2, 1.0, None).unwrap();
        let e = fit.control_points().unwrap_err();
        assert!(matches!(e, Error::NotIncreasing { .. }), "{e:?}");
        let e = fit.vjp(&[0.0; 54]).unwrap_err();
        assert!(matches!(e, Error::NotIncreasing { .. }), "{e:?}");
    }
}
