//! Parameters of the data points: uniform, chord length, centripetal or any exponent
//! (document 000 §1; P&T eq. 9.3–9.6), and the overflow-safe distances they are built from.

use crate::error::readable;
use crate::error::{check_finite, Error, Result};
use crate::points::PointsRef;
use crate::Arg;

/// How data points are assigned parameters `t̄_0 = 0 < … < t̄_n = 1`
/// (docs/theory/interpolation.md#parametrisation, P&T eq. 9.3–9.6): `t̄_k − t̄_{k−1} ∝ |q_k −
/// q_{k−1}|^e`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Parametrization {
    /// `t̄_k = k / n` (exponent 0). Accepts coincident consecutive points.
    Uniform,
    /// Chord length, exponent 1 (P&T eq. 9.5). The usual choice.
    ChordLength,
    /// Centripetal, exponent 1/2 (P&T eq. 9.6; E. T. Y. Lee 1989): better for sharp turns.
    Centripetal,
    /// The general form with exponent `e ≥ 0` (finite).
    Exponent(f64),
}

impl Parametrization {
    pub(crate) fn exponent(self) -> Result<f64> {
        let e = match self {
            Parametrization::Uniform => 0.0,
            Parametrization::ChordLength => 1.0,
            Parametrization::Centripetal => 0.5,
            Parametrization::Exponent(e) => e,
        };
        if !(e.is_finite() && e >= 0.0) {
            return Err(Error::InvalidArgument {
                what: Arg::Exponent.into(),
                reason: format!(
                    "{e} is not a finite number ≥ 0 (0 uniform, 0.5 centripetal, 1 chord length)",
                    e = readable(&e)
                ),
            });
        }
        Ok(e)
    }
}

/// Parameters `t̄_0 = 0 < … < t̄_n = 1` of the points by `method`
/// (docs/theory/interpolation.md#parametrisation; P&T eq. 9.3–9.6): `t̄_k = t̄_{k−1} + |q_k −
/// q_{k−1}|^e / Σ_j |q_j − q_{j−1}|^e`, with `e = 0` (uniform, `t̄_k = k/n`), 1 (chord length), 1/2
/// (centripetal) or any `e ≥ 0`.
///
/// Only differences of points enter, so the result does not change when the data are offset
/// or scaled. O(n·dim).
///
/// ```
/// use lekalo::{parametrize, Parametrization, Points};
/// let q = Points::from_2d(&[[0.0, 0.0], [3.0, 4.0], [-1.0, 4.0], [-4.0, 0.0], [-4.0, -3.0]])?;
/// let t = parametrize(q.as_view(), Parametrization::ChordLength)?;
/// assert_eq!(t[4], 1.0);
/// assert!((t[1] - 5.0 / 17.0).abs() < 1e-15 && (t[3] - 14.0 / 17.0).abs() < 1e-15);
/// # Ok::<(), lekalo::Error>(())
/// ```
///
/// # Errors
/// [`Error::TooFew`] for fewer than 2 points; [`Error::CoincidentPoints`] naming the first
/// pair of equal consecutive points (for `e > 0`); [`Error::InvalidArgument`] for a negative
/// or non-finite exponent, or distances that overflow.
pub fn parametrize(points: PointsRef<'_>, method: Parametrization) -> Result<Vec<f64>> {
    parametrize_impl(points, method, false)
}

/// As [`parametrize`]; with `closed`, one more parameter for the chord back to the first point.
pub(crate) fn parametrize_impl(
    points: PointsRef<'_>,
    method: Parametrization,
    closed: bool,
) -> Result<Vec<f64>> {
    let n_pts = points.len();
    if n_pts < 2 {
        return Err(Error::TooFew {
            what: "points to parametrise".into(),
            min: 2,
            got: n_pts,
        });
    }
    let steps = n_pts - 1 + usize::from(closed);
    let mut t = vec![0.0; steps + 1];
    let data = points.as_slice();
    let dim = points.dim();
    // k = n_pts only for the closing chord of a closed polygon
    let point = |k: usize| {
        if k < n_pts {
            &data[k * dim..(k + 1) * dim]
        } else {
            &data[..dim]
        }
    };
    let e = method.exponent()?;
    parametrize_into(steps, point, e, |k| (k % n_pts, (k + 1) % n_pts), &mut t)?;
    Ok(t)
}

/// Fills `t[0..=steps]` with normalised parameters of the polygon `point(0), …, point(steps)`;
/// `names(k)` gives the point indices reported for a zero step `k → k+1`.
pub(crate) fn parametrize_into<'a>(
    steps: usize,
    point: impl Fn(usize) -> &'a [f64],
    e: f64,
    names: impl Fn(usize) -> (usize, usize),
    t: &mut [f64],
) -> Result<()> {
    debug_assert_eq!(t.len(), steps + 1, "parameter buffer");
    t[0] = 0.0;
    if e == 0.0 {
        for (k, tk) in t.iter_mut().enumerate() {
            *tk = k as f64 / steps as f64;
        }
        t[steps] = 1.0;
        return Ok(());
    }
    // running sums of the distances into t[1..] (one pass for chord length); other exponents
    // and sums that overflow take the increments (d / d_max)^e in a second pass
    let mut dmax = 0.0_f64;
    let mut sum = 0.0;
    for k in 0..steps {
        let d = distance(point(k), point(k + 1));
        if d == 0.0 {
            let (first, second) = names(k);
            return Err(Error::CoincidentPoints { first, second });
        }
        if !d.is_finite() {
            let (first, second) = names(k);
            return Err(Error::InvalidArgument {
                what: "points".into(),
                reason: format!("the distance between points {first} and {second} overflows"),
            });
        }
        dmax = dmax.max(d);
        sum += d;
        t[k + 1] = sum;
    }
    if e != 1.0 || !sum.is_finite() {
        let mut acc = 0.0;
        for k in 0..steps {
            let d = distance(point(k), point(k + 1));
            acc += (d / dmax).powf(e);
            t[k + 1] = acc;
        }
        sum = acc;
    }
    let inv = 1.0 / sum;
    for k in 1..steps {
        t[k] *= inv;
        if t[k] <= t[k - 1] {
            return Err(too_close(names(k - 1)));
        }
    }
    t[steps] = 1.0;
    if t[steps] <= t[steps - 1] {
        return Err(too_close(names(steps - 1)));
    }
    Ok(())
}

/// Two consecutive points whose chord is lost in the rounding of the parameters' sum: the
/// message names the fix, and for the closing chord of a closed polygon (`second` = 0) that
/// the data need not repeat their first point.
#[cold]
fn too_close((first, second): (usize, usize)) -> Error {
    let seam = if second == 0 && first > 0 {
        "; a closed curve joins the last point to the first itself, so leave out a repeated first point at the end"
    } else {
        ""
    };
    Error::InvalidArgument {
        what: "points".into(),
        reason: format!(
            "points {first} and {second} are too close relative to the others for distinct parameters: \
             merge or remove one of them, or use uniform parameters{seam}"
        ),
    }
}

pub(crate) fn check_strictly_increasing(params: &[f64]) -> Result<()> {
    check_finite("parameters", params)?;
    for i in 1..params.len() {
        if params[i] < params[i - 1] {
            return Err(Error::NotIncreasing {
                what: "parameters".into(),
                index: i,
                value: params[i],
                previous: params[i - 1],
            });
        }
        if params[i] == params[i - 1] {
            return Err(Error::Repeated {
                what: "parameters".into(),
                index: i,
                value: params[i],
            });
        }
    }
    Ok(())
}

/// Euclidean distance without overflow or underflow in the squares.
#[inline]
pub(crate) fn distance(a: &[f64], b: &[f64]) -> f64 {
    let ss: f64 = a.iter().zip(b).map(|(x, y)| (x - y) * (x - y)).sum();
    if ss.is_normal() && ss < 1e300 {
        return ss.sqrt();
    }
    let m = a
        .iter()
        .zip(b)
        .fold(0.0_f64, |m, (x, y)| m.max((x - y).abs()));
    if m == 0.0 || !m.is_finite() {
        return m;
    }
    m * a
        .iter()
        .zip(b)
        .map(|(x, y)| ((x - y) / m) * ((x - y) / m))
        .sum::<f64>()
        .sqrt()
}

/// [`distance`] with the dimension `D` fixed at compile time (`0`: any length): the same
/// operations in the same order, unrolled, with the same fallback for sums of squares that
/// underflow or approach overflow.
#[inline(always)]
pub(crate) fn distance_fixed<const D: usize>(a: &[f64], b: &[f64]) -> f64 {
    if D == 0 {
        return distance(a, b);
    }
    let (a, b) = (&a[..D], &b[..D]);
    let mut ss = 0.0;
    for k in 0..D {
        ss += (a[k] - b[k]) * (a[k] - b[k]);
    }
    if plain_square_sum(ss) {
        ss.sqrt()
    } else {
        distance(a, b)
    }
}

/// Whether a sum of squares can be square-rooted as it is: normal and below 1e300 (a sum of
/// squares is never negative, and NaN fails), else [`distance`]'s scaled sum is needed.
#[inline(always)]
fn plain_square_sum(ss: f64) -> bool {
    (f64::MIN_POSITIVE..1e300).contains(&ss)
}

/// The distances between the points of `a` and those of `b` (`dim` coordinates each; `D` is
/// `dim` or 0 for a run-time `dim`) into `out`, the same numbers as
/// [`distance_fixed`] point by point. The usual case (every
/// sum of squares normal and below 1e300) runs without branches, so that it vectorises; a row
/// with any other sum is redone point by point with the scaled fallback.
#[inline(always)]
pub(crate) fn distances<const D: usize>(a: &[f64], b: &[f64], dim: usize, out: &mut [f64]) {
    if D > 0 {
        let mut plain = true;
        for ((p, q), o) in a.chunks_exact(D).zip(b.chunks_exact(D)).zip(out.iter_mut()) {
            let mut ss = 0.0;
            for k in 0..D {
                ss += (p[k] - q[k]) * (p[k] - q[k]);
            }
            plain &= plain_square_sum(ss);
            *o = ss.sqrt();
        }
        if plain {
            return;
        }
    }
    for ((p, q), o) in a
        .chunks_exact(dim)
        .zip(b.chunks_exact(dim))
        .zip(out.iter_mut())
    {
        *o = distance_fixed::<D>(p, q);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::points::Points;

    /// Closed data that repeat their first point to rounding: the closing chord is lost in the
    /// sum, and the message names the seam and the fix; an open polygon's pair gets the fix
    /// without the seam.
    #[test]
    fn points_too_close_for_distinct_parameters_name_the_fix() {
        let mut pts: Vec<[f64; 2]> = (0..40)
            .map(|k| {
                let a = std::f64::consts::TAU * k as f64 / 40.0;
                [a.cos(), 0.6 * a.sin()]
            })
            .collect();
        pts.push([1.0, -1.5e-16]);
        let q = Points::from_2d(&pts).expect("finite points");
        let msg = parametrize_impl(q.as_view(), Parametrization::ChordLength, true)
            .expect_err("the closing chord is below the parameters' rounding")
            .to_string();
        assert!(msg.contains("points 40 and 0"), "{msg}");
        assert!(msg.contains("leave out a repeated first point"), "{msg}");
        let open = Points::from_2d(&[[0.0, 0.0], [1.0, 0.0], [1.0, 1e-17], [2.0, 0.0]])
            .expect("finite points");
        let msg = parametrize(open.as_view(), Parametrization::ChordLength)
            .expect_err("the chord 1 -> 2 is below the parameters' rounding")
            .to_string();
        assert!(
            msg.contains("points 1 and 2") && msg.contains("merge or remove one of them"),
            "{msg}"
        );
        assert!(!msg.contains("closed curve"), "{msg}");
    }
}
