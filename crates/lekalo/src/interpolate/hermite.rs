//! Cubic Hermite splines (document 002, Hermite segment) and the lecture's cubic through four
//! points (document 002, four-point cubic).
//!
//! A cubic Hermite spline through points `p_0 … p_n` at parameters `t_0 < … < t_n` with tangents
//! `D_0 … D_n` is, on segment `k` with `h = t_{k+1} − t_k` and `u = (t − t_k)/h ∈ [0, 1]`,
//! `P(t) = h00(u) p_k + h01(u) p_{k+1} + h10(u) h D_k + h11(u) h D_{k+1}` with the Hermite basis
//! `[h00 h01 h10 h11] = [u³ u² u 1]·M_H` (docs/theory/interpolation.md#the-hermite-matrix-row: the
//! printed inverse `M_H`, which is the inverse of the *corrected* forward matrix whose last row is
//! `[3 2 1 0]`). With `t_k = k` this is exactly the lecture's segment. The curve is C¹;
//! [`CubicHermite::to_bspline`] gives the equal cubic B-spline with double interior knots and
//! [`CubicHermite::to_bezier_segments`] its Bezier pieces.
//!
//! Natural and clamped C² cubic splines are B-spline interpolants: see
//! [`CurveInterpolation`](crate::CurveInterpolation) and
//! [`natural_cubic_spline`](crate::natural_cubic_spline).

use crate::curve::bezier::BezierCurve;
use crate::curve::bspline::BSplineCurve;
use crate::error::readable;
use crate::error::{check_finite, Error, Result};
use crate::interpolate::parametrization::{
    check_strictly_increasing, parametrize, Parametrization,
};
use crate::points::{Points, PointsRef};
use crate::{Arg, What};

/// The Hermite basis matrix `M_H` of document 002, Hermite segment: `[a b c d]ᵀ = M_H·[p_k p_{k+1}
/// Dp_k Dp_{k+1}]ᵀ` for `P(u) = a u³ + b u² + c u + d`. It is the inverse of the corrected forward
/// matrix `[[0,0,0,1],[1,1,1,1],[0,0,1,0],[3,2,1,0]]` (the source prints the last row as
/// `[3 2 1 1]`, which is wrong: `P'(1) = 3a + 2b + c`).
pub const HERMITE_MATRIX: [[f64; 4]; 4] = [
    [2.0, -2.0, 1.0, 1.0],
    [-3.0, 3.0, -2.0, -1.0],
    [0.0, 0.0, 1.0, 0.0],
    [1.0, 0.0, 0.0, 0.0],
];

/// Inverse of the lecture's matrix `A` with rows `[u³ u² u 1]` at `u = 0, 1/3, 2/3, 1`
/// (document 002, four-point cubic; the exact inverse,
/// docs/theory/interpolation.md#the-lectures-four-point-cubic).
const FOUR_POINT_INVERSE: [[f64; 4]; 4] = [
    [-4.5, 13.5, -13.5, 4.5],
    [9.0, -22.5, 18.0, -4.5],
    [-5.5, 9.0, -4.5, 1.0],
    [1.0, 0.0, 0.0, 0.0],
];

/// Power-basis coefficients `a, b, c, d` (rows of the result) of the Hermite segment
/// `P(u) = a u³ + b u² + c u + d`, `u ∈ [0, 1]`, with `P(0) = p0`, `P(1) = p1`, `P'(0) = d0`,
/// `P'(1) = d1`: the product `M_H·[p0 p1 d0 d1]ᵀ` of document 002, Hermite segment
/// ([`HERMITE_MATRIX`]).
///
/// ```
/// use lekalo::hermite_segment_coefficients;
/// let c = hermite_segment_coefficients(&[0.0], &[1.0], &[0.0], &[0.0])?;
/// // smoothstep 3u² − 2u³
/// assert_eq!(c.as_slice(), &[-2.0, 3.0, 0.0, 0.0]);
/// # Ok::<(), lekalo::Error>(())
/// ```
///
/// # Errors
/// [`Error::Dimension`] if the four vectors differ in length or are empty; [`Error::NonFinite`].
pub fn hermite_segment_coefficients(
    p0: &[f64],
    p1: &[f64],
    d0: &[f64],
    d1: &[f64],
) -> Result<Points> {
    let dim = p0.len();
    if dim == 0 {
        return Err(Error::Dimension {
            what: "Hermite segment end point".into(),
            expected: 1,
            got: 0,
        });
    }
    let inputs = [("p0", p0), ("p1", p1), ("d0", d0), ("d1", d1)];
    for (what, v) in inputs {
        if v.len() != dim {
            return Err(Error::Dimension {
                what: what.into(),
                expected: dim,
                got: v.len(),
            });
        }
        check_finite(what, v)?;
    }
    let mut out = vec![0.0; 4 * dim];
    for (row, m) in HERMITE_MATRIX.iter().enumerate() {
        for (&coef, (_, v)) in m.iter().zip(inputs) {
            for k in 0..dim {
                out[row * dim + k] += coef * v[k];
            }
        }
    }
    Ok(Points::from_raw(out, dim))
}

/// The lecture's single cubic through four points at `u = 0, 1/3, 2/3, 1` (document 002,
/// four-point cubic): power-basis coefficients `a, b, c, d` (rows of the result) of
/// `p(u) = a u³ + b u² + c u + d`, computed as `C = A⁻¹·P` with the exact inverse. This is
/// cubic Lagrange interpolation, not a natural spline (for that see
/// [`natural_cubic_spline`](crate::natural_cubic_spline)).
///
/// # Errors
/// [`Error::LengthMismatch`] unless exactly 4 points are given.
pub fn four_point_cubic_coefficients(points: PointsRef<'_>) -> Result<Points> {
    check_four(points)?;
    let dim = points.dim();
    let mut out = vec![0.0; 4 * dim];
    for (row, m) in FOUR_POINT_INVERSE.iter().enumerate() {
        for (j, &coef) in m.iter().enumerate() {
            for (o, x) in out[row * dim..(row + 1) * dim]
                .iter_mut()
                .zip(points.point(j))
            {
                *o += coef * x;
            }
        }
    }
    Ok(Points::from_raw(out, dim))
}

/// The same cubic as [`four_point_cubic_coefficients`] in Bezier form on `[0, 1]`:
/// `b_0 = p_0`, `b_1 = (−5p_0 + 18p_1 − 9p_2 + 2p_3)/6`, `b_2 = (2p_0 − 9p_1 + 18p_2 − 5p_3)/6`,
/// `b_3 = p_3` (the power form converted by `b_1 = d + c/3`, `b_2 = d + 2c/3 + b/3`), so that it
/// evaluates stably by de Casteljau.
///
/// ```
/// use lekalo::{cubic_through_four_points, Points};
/// let p = Points::from_2d(&[[0.0, 0.0], [1.0, 2.0], [2.0, 2.0], [3.0, 0.0]])?;
/// let c = cubic_through_four_points(p.as_view())?;
/// let m = c.eval(1.0 / 3.0)?;
/// assert!((m[0] - 1.0).abs() < 1e-15 && (m[1] - 2.0).abs() < 1e-15);
/// # Ok::<(), lekalo::Error>(())
/// ```
///
/// # Errors
/// [`Error::LengthMismatch`] unless exactly 4 points are given.
pub fn cubic_through_four_points(points: PointsRef<'_>) -> Result<BezierCurve> {
    check_four(points)?;
    let dim = points.dim();
    let (p0, p1, p2, p3) = (
        points.point(0),
        points.point(1),
        points.point(2),
        points.point(3),
    );
    let mut out = Vec::with_capacity(4 * dim);
    out.extend_from_slice(p0);
    out.extend((0..dim).map(|k| (-5.0 * p0[k] + 18.0 * p1[k] - 9.0 * p2[k] + 2.0 * p3[k]) / 6.0));
    out.extend((0..dim).map(|k| (2.0 * p0[k] - 9.0 * p1[k] + 18.0 * p2[k] - 5.0 * p3[k]) / 6.0));
    out.extend_from_slice(p3);
    BezierCurve::new(Points::from_raw(out, dim))
}

fn check_four(points: PointsRef<'_>) -> Result<()> {
    if points.len() != 4 {
        return Err(Error::LengthMismatch {
            what: "points of the four-point cubic".into(),
            expected: 4,
            got: points.len(),
        });
    }
    Ok(())
}

/// How [`CubicHermite`] estimates tangents that are not given (`δ_k = (p_{k+1} − p_k)/h_k` are
/// the secant slopes, `h_k = t_{k+1} − t_k`; the end tangents are the end secants `δ_0`,
/// `δ_{n−1}` unless stated otherwise).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum TangentEstimate {
    /// Three-point finite difference `D_k = (δ_{k−1} + δ_k)/2`.
    FiniteDifference,
    /// Catmull–Rom: `D_k = (p_{k+1} − p_{k−1}) / (t_{k+1} − t_{k−1})` (Catmull & Rom 1974).
    /// Equal to [`TangentEstimate::FiniteDifference`] for uniform parameters.
    CatmullRom,
    /// Cardinal spline: `(1 − tension)` times the Catmull–Rom tangents (ends included);
    /// `tension ∈ [0, 1]`, 0 is Catmull–Rom, 1 gives zero tangents.
    Cardinal {
        /// The tension `c ∈ [0, 1]`.
        tension: f64,
    },
    /// Monotone interpolation of Fritsch & Carlson (SIAM J. Numer. Anal. 17, 1980), applied to
    /// each coordinate as a function of the parameter: finite-difference tangents, set to zero
    /// where the data turn (`δ_{k−1}·δ_k ≤ 0`), then scaled by `τ = 3/√(α² + β²)` on any segment
    /// with `α² + β² > 9` (`α = D_k/δ_k`, `β = D_{k+1}/δ_k`). Monotone data give a monotone
    /// interpolant; meant for functions `y(x)` ([`CubicHermite::function`]).
    Monotone,
}

/// A C¹ piecewise cubic Hermite curve (see the module documentation), of any dimension.
///
/// ```
/// use lekalo::{CubicHermite, Points, TangentEstimate};
/// let x = [0.0, 1.0, 2.0, 3.0];
/// let y = Points::from_flat(1, vec![0.0, 1.0, 1.0, 2.0])?;
/// let h = CubicHermite::function(&x, y.as_view(), TangentEstimate::Monotone)?;
/// assert_eq!(h.eval(1.5)?, vec![1.0]); // flat where the data are flat
/// let b = h.to_bspline();
/// assert!((b.eval(2.5)?[0] - h.eval(2.5)?[0]).abs() < 1e-14);
/// # Ok::<(), lekalo::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct CubicHermite {
    params: Vec<f64>,
    points: Points,
    tangents: Points,
}

impl CubicHermite {
    /// A Hermite spline from strictly increasing parameters, points and tangents (derivatives
    /// with respect to the parameter).
    ///
    /// # Errors
    /// [`Error::TooFew`] for fewer than 2 points; [`Error::LengthMismatch`] if the counts
    /// differ; [`Error::Dimension`] if points and tangents differ in dimension;
    /// [`Error::NonFinite`], [`Error::NotIncreasing`], [`Error::InvalidArgument`] for bad
    /// parameters.
    pub fn new(params: Vec<f64>, points: Points, tangents: Points) -> Result<Self> {
        check_data(&params, points.as_view())?;
        if tangents.len() != points.len() {
            return Err(Error::LengthMismatch {
                what: What::of(Arg::Tangents, "tangents (one per point)"),
                expected: points.len(),
                got: tangents.len(),
            });
        }
        if tangents.dim() != points.dim() {
            return Err(Error::Dimension {
                what: "tangents".into(),
                expected: points.dim(),
                got: tangents.dim(),
            });
        }
        Ok(CubicHermite {
            params,
            points,
            tangents,
        })
    }

    /// A Hermite spline at the given parameters with tangents estimated by `estimate`.
    ///
    /// # Errors
    /// As [`CubicHermite::new`]; [`Error::InvalidArgument`] for a tension outside `[0, 1]`.
    pub fn with_estimated_tangents(
        params: Vec<f64>,
        points: PointsRef<'_>,
        estimate: TangentEstimate,
    ) -> Result<Self> {
        check_data(&params, points)?;
        let tangents = estimate_tangents(&params, points, estimate)?;
        Ok(CubicHermite {
            params,
            points: points.to_owned(),
            tangents,
        })
    }

    /// A parametric Hermite curve through `points`, parameters by `parametrization` on
    /// `[0, 1]` ([`parametrize`]) and tangents by `estimate`.
    ///
    /// # Errors
    /// As [`parametrize`] and [`CubicHermite::with_estimated_tangents`].
    pub fn from_points(
        points: PointsRef<'_>,
        parametrization: Parametrization,
        estimate: TangentEstimate,
    ) -> Result<Self> {
        let params = parametrize(points, parametrization)?;
        Self::with_estimated_tangents(params, points, estimate)
    }

    /// The function `y(x)` through `(x_k, y_k)`, `x` strictly increasing, tangents by
    /// `estimate` ([`TangentEstimate::Monotone`] keeps monotone data monotone). Each coordinate
    /// of `y` is one function of `x`.
    ///
    /// # Errors
    /// As [`CubicHermite::with_estimated_tangents`].
    pub fn function(x: &[f64], y: PointsRef<'_>, estimate: TangentEstimate) -> Result<Self> {
        Self::with_estimated_tangents(x.to_vec(), y, estimate)
    }

    /// The parameters `t_0 < … < t_n`.
    #[must_use]
    pub fn params(&self) -> &[f64] {
        &self.params
    }

    /// The points `p_k`.
    #[must_use]
    pub fn points(&self) -> &Points {
        &self.points
    }

    /// The tangents `D_k`.
    #[must_use]
    pub fn tangents(&self) -> &Points {
        &self.tangents
    }

    /// The parameter domain `[t_0, t_n]`.
    #[must_use]
    pub fn domain(&self) -> (f64, f64) {
        (self.params[0], self.params[self.params.len() - 1])
    }

    /// `P(t)` by the Hermite basis (document 002, Hermite segment) on the segment containing `t`
    /// (`[t_k, t_{k+1})`, the last one closed). O(log n + dim).
    ///
    /// # Errors
    /// [`Error::ParameterOutOfDomain`] outside `[t_0, t_n]` or for NaN; [`Error::NonFinite`] if
    /// the point overflows (data and tangents near `f64::MAX`).
    pub fn eval(&self, t: f64) -> Result<Vec<f64>> {
        let (min, max) = self.domain();
        if !(t >= min && t <= max) {
            return Err(Error::ParameterOutOfDomain { t, min, max });
        }
        let n = self.params.len() - 1;
        let k = (self.params.partition_point(|&x| x <= t) - 1).min(n - 1);
        let h = self.params[k + 1] - self.params[k];
        let u = (t - self.params[k]) / h;
        let (u2, u3) = (u * u, u * u * u);
        let h00 = 2.0 * u3 - 3.0 * u2 + 1.0;
        let h01 = -2.0 * u3 + 3.0 * u2;
        let h10 = (u3 - 2.0 * u2 + u) * h;
        let h11 = (u3 - u2) * h;
        let (p0, p1) = (self.points.point(k), self.points.point(k + 1));
        let (d0, d1) = (self.tangents.point(k), self.tangents.point(k + 1));
        let p: Vec<f64> = (0..self.points.dim())
            .map(|i| h00 * p0[i] + h01 * p1[i] + h10 * d0[i] + h11 * d1[i])
            .collect();
        // h·D overflows for tangents and segments near f64::MAX (found by the `interpolation`
        // fuzz target): an error, never NaN inside an Ok
        crate::error::check_finite("Hermite curve point (overflow: rescale the data)", &p)?;
        Ok(p)
    }

    /// Bezier control points of segment `k` on `[0, 1]`: `p_k`, `p_k + h D_k/3`,
    /// `p_{k+1} − h D_{k+1}/3`, `p_{k+1}` (the Hermite-to-Bezier change of basis).
    fn bezier_points(&self, k: usize, out: &mut Vec<f64>) {
        let h = self.params[k + 1] - self.params[k];
        let (p0, p1) = (self.points.point(k), self.points.point(k + 1));
        let (d0, d1) = (self.tangents.point(k), self.tangents.point(k + 1));
        out.extend_from_slice(p0);
        out.extend(p0.iter().zip(d0).map(|(p, d)| p + h * d / 3.0));
        out.extend(p1.iter().zip(d1).map(|(p, d)| p - h * d / 3.0));
        out.extend_from_slice(p1);
    }

    /// The `n` cubic Bezier segments; segment `k` maps `[t_k, t_{k+1}]` to `[0, 1]`.
    #[must_use]
    pub fn to_bezier_segments(&self) -> Vec<BezierCurve> {
        let dim = self.points.dim();
        (0..self.params.len() - 1)
            .map(|k| {
                let mut v = Vec::with_capacity(4 * dim);
                self.bezier_points(k, &mut v);
                BezierCurve::from_raw(Points::from_raw(v, dim))
            })
            .collect()
    }

    /// The same curve as a cubic B-spline with knots `t_0` (×4), `t_1 … t_{n−1}` (×2 each, hence
    /// C¹), `t_n` (×4) and control points `p_0`, then the two inner Bezier points of every
    /// segment, then `p_n` (the junction points `p_k` are the knot-insertion combination of their
    /// neighbours, which the tangent continuity guarantees). `2n + 2` control points.
    #[must_use]
    pub fn to_bspline(&self) -> BSplineCurve {
        let dim = self.points.dim();
        let n = self.params.len() - 1;
        let mut knots = Vec::with_capacity(2 * n + 6);
        knots.extend([self.params[0]; 4]);
        for &t in &self.params[1..n] {
            knots.extend([t, t]);
        }
        knots.extend([self.params[n]; 4]);
        let mut control = Vec::with_capacity((2 * n + 2) * dim);
        let mut seg = Vec::with_capacity(4 * dim);
        control.extend_from_slice(self.points.point(0));
        for k in 0..n {
            seg.clear();
            self.bezier_points(k, &mut seg);
            control.extend_from_slice(&seg[dim..3 * dim]);
        }
        control.extend_from_slice(self.points.point(n));
        BSplineCurve::from_raw(3, knots, Points::from_raw(control, dim))
    }
}

fn check_data(params: &[f64], points: PointsRef<'_>) -> Result<()> {
    if points.len() < 2 {
        return Err(Error::TooFew {
            what: "Hermite points".into(),
            min: 2,
            got: points.len(),
        });
    }
    if params.len() != points.len() {
        return Err(Error::LengthMismatch {
            what: What::of(Arg::Parameters, "parameters (one per point)"),
            expected: points.len(),
            got: params.len(),
        });
    }
    check_strictly_increasing(params)?;
    Ok(())
}

/// Tangents by `estimate` (see [`TangentEstimate`]). O(n·dim).
fn estimate_tangents(
    params: &[f64],
    points: PointsRef<'_>,
    estimate: TangentEstimate,
) -> Result<Points> {
    let n = params.len() - 1;
    let dim = points.dim();
    let slope = |k: usize, i: usize| {
        (points.point(k + 1)[i] - points.point(k)[i]) / (params[k + 1] - params[k])
    };
    let mut d = vec![0.0; (n + 1) * dim];
    match estimate {
        TangentEstimate::FiniteDifference | TangentEstimate::Monotone => {
            for i in 0..dim {
                d[i] = slope(0, i);
                d[n * dim + i] = slope(n - 1, i);
                for k in 1..n {
                    d[k * dim + i] = 0.5 * (slope(k - 1, i) + slope(k, i));
                }
            }
            if estimate == TangentEstimate::Monotone {
                fritsch_carlson(n, dim, &slope, &mut d);
            }
        }
        TangentEstimate::CatmullRom | TangentEstimate::Cardinal { .. } => {
            let scale = match estimate {
                TangentEstimate::Cardinal { tension } => {
                    if !(0.0..=1.0).contains(&tension) {
                        return Err(Error::InvalidArgument {
                            what: "tension".into(),
                            reason: format!(
                                "{tension} does not lie in [0, 1] (0 is Catmull–Rom)",
                                tension = readable(&tension)
                            ),
                        });
                    }
                    1.0 - tension
                }
                _ => 1.0,
            };
            for i in 0..dim {
                d[i] = scale * slope(0, i);
                d[n * dim + i] = scale * slope(n - 1, i);
                for k in 1..n {
                    let chord = points.point(k + 1)[i] - points.point(k - 1)[i];
                    d[k * dim + i] = scale * chord / (params[k + 1] - params[k - 1]);
                }
            }
        }
    }
    // finite data can still overflow (slopes of points near ±f64::MAX, or tiny parameter
    // steps): refuse instead of returning infinite or NaN tangents
    if let Some((index, &value)) = d.iter().enumerate().find(|(_, v)| !v.is_finite()) {
        return Err(Error::NonFinite {
            what: "estimated tangents (the data's slopes overflow f64)".into(),
            index,
            value,
        });
    }
    Ok(Points::from_raw(d, dim))
}

/// Fritsch–Carlson limiting of the tangents `d` (see [`TangentEstimate::Monotone`]).
fn fritsch_carlson(n: usize, dim: usize, slope: &impl Fn(usize, usize) -> f64, d: &mut [f64]) {
    for i in 0..dim {
        for k in 1..n {
            if slope(k - 1, i) * slope(k, i) <= 0.0 {
                d[k * dim + i] = 0.0;
            }
        }
        for k in 0..n {
            let delta = slope(k, i);
            if delta == 0.0 {
                d[k * dim + i] = 0.0;
                d[(k + 1) * dim + i] = 0.0;
                continue;
            }
            let alpha = d[k * dim + i] / delta;
            let beta = d[(k + 1) * dim + i] / delta;
            let r2 = alpha * alpha + beta * beta;
            if r2 > 9.0 {
                let tau = 3.0 / r2.sqrt();
                d[k * dim + i] = tau * alpha * delta;
                d[(k + 1) * dim + i] = tau * beta * delta;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hermite_matrix_inverts_the_corrected_forward_matrix() {
        let forward = [
            [0.0, 0.0, 0.0, 1.0],
            [1.0, 1.0, 1.0, 1.0],
            [0.0, 0.0, 1.0, 0.0],
            [3.0, 2.0, 1.0, 0.0],
        ];
        for i in 0..4 {
            for j in 0..4 {
                let s: f64 = (0..4).map(|k| HERMITE_MATRIX[i][k] * forward[k][j]).sum();
                let e = if i == j { 1.0 } else { 0.0 };
                assert_eq!(s, e, "M_H·F at ({i},{j})");
            }
        }
    }

    #[test]
    fn four_point_inverse_inverts_a() {
        let us = [0.0, 1.0 / 3.0, 2.0 / 3.0, 1.0_f64];
        // row k of A: [u_k³, u_k², u_k, 1]
        let a: Vec<[f64; 4]> = us.iter().map(|&u| [u * u * u, u * u, u, 1.0]).collect();
        for i in 0..4 {
            for j in 0..4 {
                let s: f64 = (0..4).map(|k| FOUR_POINT_INVERSE[i][k] * a[k][j]).sum();
                let e = if i == j { 1.0 } else { 0.0 };
                assert!((s - e).abs() < 1e-14, "A⁻¹·A at ({i},{j}) = {s}");
            }
        }
    }
}
