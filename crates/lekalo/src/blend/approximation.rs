//! Piecewise Hermite–Bezier approximation with measured error; documented on [`Approximation`].

use crate::blend::deformation::ParametricCurve;
use crate::blend::spline::BlendSpline;
use crate::curve::bspline::BSplineCurve;
use crate::error::readable;
use crate::error::{Error, Result};
use crate::points::Points;
use crate::Arg;

const SAMPLES_PER_PIECE: usize = Approximation::SAMPLES_PER_PIECE;
const MAX_PIECES: usize = Approximation::MAX_PIECES;

/// A polynomial approximation and its measured error.
///
/// Piecewise Hermite–Bezier approximation of curves without an exact Bezier form (blends of
/// angle-parametrised arcs, user curves), with the error measured and reported.
///
/// On a piece `[a, b]` (`h = b − a`) of a smooth curve `c`, the Bezier curve of degree
/// `q = 2r + 1` that matches `c` and its first `r` derivatives at both ends has control points
/// (two-point Hermite interpolation in Bernstein form; Farin, *Curves and Surfaces for CAGD*,
/// §5.3 derivative formula `c^{(i)}(0) = q!/(q−i)! Δ^i B_0` solved for the `B_j`)
///
/// ```text
/// B_j     = Σ_{i=0}^{j} C(j,i) (q−i)!/q! · h^i c^{(i)}(a)
/// B_{q−j} = Σ_{i=0}^{j} C(j,i) (q−i)!/q! · (−h)^i c^{(i)}(b),      j = 0 … r.
/// ```
///
/// Its error is `O(h^{2r+2})` (the Hermite remainder
/// `c^{(2r+2)}(ξ)/(2r+2)! · ((u−a)(b−u))^{r+1}`), and because neighbouring pieces share the
/// end data, the approximation is `C^r` at the piece joins and reproduces the derivatives up to
/// order `r` at every breakpoint exactly. Pieces are halved until the error, **measured** at
/// [`Approximation::SAMPLES_PER_PIECE`] interior points of every piece, is below the tolerance.
/// The remainder is a smooth function vanishing to order `r + 1` at both ends of a piece, so
/// this estimate converges to the true maximum as pieces shrink (a test checks it on a grid ten
/// times finer); it is a measured error, not a proven bound.
#[derive(Debug, Clone, PartialEq)]
pub struct Approximation {
    curve: BSplineCurve,
    max_error: f64,
}

impl Approximation {
    /// Interior points per piece at which the error is measured.
    pub const SAMPLES_PER_PIECE: usize = 16;

    /// Largest number of pieces one interval is split into before giving up.
    pub const MAX_PIECES: usize = 1 << 12;

    /// The approximating B-spline (piecewise Bezier: interior knots of multiplicity = degree).
    #[must_use]
    pub fn curve(&self) -> &BSplineCurve {
        &self.curve
    }

    /// Largest distance to the approximated curve found at the sample points
    /// ([`Approximation::SAMPLES_PER_PIECE`] per piece, same parameter).
    #[must_use]
    pub fn max_error(&self) -> f64 {
        self.max_error
    }

    /// The B-spline, owned.
    #[must_use]
    pub fn into_curve(self) -> BSplineCurve {
        self.curve
    }
}

/// Largest Hermite order `r` (degree `2r + 1`): beyond it the Hermite basis is too
/// ill-conditioned for the approximation to be useful.
const MAX_ORDER: usize = 20;

fn check_order(r: usize) -> Result<()> {
    if r > MAX_ORDER {
        return Err(Error::InvalidArgument {
            what: "Hermite order r".into(),
            reason: format!("{r} is above {MAX_ORDER} (degree 2r + 1); use a lower order"),
        });
    }
    Ok(())
}

fn check_tolerance(tolerance: f64) -> Result<()> {
    if !(tolerance.is_finite() && tolerance > 0.0) {
        return Err(Error::InvalidArgument {
            what: Arg::Tolerance.into(),
            reason: format!(
                "{tolerance} must be positive and finite",
                tolerance = readable(&tolerance)
            ),
        });
    }
    Ok(())
}

/// Hermite control points of `curve` on `[a, b]`, appended to `ctrl` (all `q + 1` of them, or
/// all but the first when `skip_first`).
fn hermite_piece(
    curve: &dyn ParametricCurve,
    a: f64,
    b: f64,
    r: usize,
    ctrl: &mut Vec<f64>,
    skip_first: bool,
) -> Result<()> {
    let dim = curve.dim();
    let q = 2 * r + 1;
    let h = b - a;
    let mut d0 = vec![0.0; (r + 1) * dim];
    let mut d1 = vec![0.0; (r + 1) * dim];
    curve.eval_derivatives_into(a, r, &mut d0)?;
    curve.eval_derivatives_into(b, r, &mut d1)?;
    let mut scale = (1.0, 1.0);
    for i in 1..=r {
        scale.0 *= h;
        scale.1 *= -h;
        d0[i * dim..(i + 1) * dim]
            .iter_mut()
            .for_each(|x| *x *= scale.0);
        d1[i * dim..(i + 1) * dim]
            .iter_mut()
            .for_each(|x| *x *= scale.1);
    }
    // ratio[i] = (q − i)!/q!
    let mut ratio = vec![1.0; r + 1];
    for i in 1..=r {
        ratio[i] = ratio[i - 1] / (q + 1 - i) as f64;
    }
    let mut pts = vec![0.0; (q + 1) * dim];
    for j in 0..=r {
        let mut binom = 1.0;
        for i in 0..=j {
            if i > 0 {
                binom = binom * (j + 1 - i) as f64 / i as f64;
            }
            for d in 0..dim {
                pts[j * dim + d] += binom * ratio[i] * d0[i * dim + d];
                pts[(q - j) * dim + d] += binom * ratio[i] * d1[i * dim + d];
            }
        }
    }
    ctrl.extend_from_slice(if skip_first { &pts[dim..] } else { &pts });
    Ok(())
}

/// Approximates `curve` on `[a, b]` by `m` Hermite pieces, halving until the measured error is
/// at most `tolerance`. Appends control points and returns `(pieces, error)`.
fn approximate_interval(
    curve: &dyn ParametricCurve,
    (a, b): (f64, f64),
    r: usize,
    tolerance: f64,
    ctrl: &mut Vec<f64>,
    skip_first: bool,
) -> Result<(usize, f64)> {
    let dim = curve.dim();
    let q = 2 * r + 1;
    let mut m = 1;
    loop {
        let mut local = Vec::with_capacity(m * q * dim + dim);
        let mut error = 0.0_f64;
        let mut scratch = Vec::new();
        let mut approx = vec![0.0; dim];
        for p in 0..m {
            let x0 = a + (b - a) * p as f64 / m as f64;
            let x1 = if p + 1 == m {
                b
            } else {
                a + (b - a) * (p + 1) as f64 / m as f64
            };
            let start = local.len();
            hermite_piece(curve, x0, x1, r, &mut local, p > 0)?;
            let first = if p > 0 { start - dim } else { start };
            let piece = &local[first..];
            for s in 1..=SAMPLES_PER_PIECE {
                let u = s as f64 / (SAMPLES_PER_PIECE + 1) as f64;
                crate::blend::bernstein::derivatives_at(
                    piece,
                    dim,
                    u,
                    0,
                    &mut approx,
                    &mut scratch,
                );
                let exact = curve.eval(x0 + u * (x1 - x0))?;
                let e = approx
                    .iter()
                    .zip(&exact)
                    .map(|(x, y)| (x - y) * (x - y))
                    .sum::<f64>()
                    .sqrt();
                error = error.max(e);
            }
        }
        if error <= tolerance {
            ctrl.extend_from_slice(if skip_first { &local[dim..] } else { &local });
            return Ok((m, error));
        }
        if m >= MAX_PIECES || error.is_nan() {
            return Err(Error::InvalidArgument {
                what: Arg::Tolerance.into(),
                reason: format!(
                    "{tolerance:e} not reached with {m} pieces on [{a}, {b}] (error {error:e}); \
                     raise the tolerance or the order",
                    a = readable(&a),
                    b = readable(&b)
                ),
            });
        }
        m *= 2;
    }
}

/// Assembles `(interval, pieces)` lists into a piecewise Bezier B-spline of degree `q`.
fn assemble(
    intervals: &[((f64, f64), usize)],
    q: usize,
    ctrl: Vec<f64>,
    dim: usize,
) -> Result<BSplineCurve> {
    let mut knots = vec![intervals[0].0 .0; q + 1];
    for (idx, &((a, b), m)) in intervals.iter().enumerate() {
        for p in 1..=m {
            let x = if p == m {
                b
            } else {
                a + (b - a) * p as f64 / m as f64
            };
            let last = idx + 1 == intervals.len() && p == m;
            knots.extend(std::iter::repeat_n(x, if last { q + 1 } else { q }));
        }
    }
    BSplineCurve::new(q, knots, Points::from_flat(dim, ctrl)?)
}

/// Approximates a smooth curve on its whole domain by a piecewise Bezier curve of degree
/// `2r + 1` matching derivatives up to order `r` at the breakpoints (see [`Approximation`]), refined until
/// the measured error is at most `tolerance`.
///
/// ```
/// use lekalo::{approximate_curve, FnCurve, ParametricCurve};
/// // the unit circle by angle on [0, 2π]
/// let circle = FnCurve::new(2, (0.0, std::f64::consts::TAU), |t: f64, order: usize, out: &mut [f64]| {
///     for l in 0..=order {
///         let phase = t + l as f64 * std::f64::consts::FRAC_PI_2;
///         out[2 * l] = phase.cos();
///         out[2 * l + 1] = phase.sin();
///     }
///     Ok(())
/// })?;
/// let a = approximate_curve(&circle, 2, 1e-8)?;
/// assert!(a.max_error() <= 1e-8 && a.curve().degree() == 5);
/// # Ok::<(), lekalo::Error>(())
/// ```
///
/// # Errors
/// [`Error::InvalidArgument`] if `tolerance` is not positive and finite, or is not reached
/// with [`Approximation::MAX_PIECES`] pieces, or if `r > 20`; evaluation errors of the curve.
pub fn approximate_curve(
    curve: &dyn ParametricCurve,
    r: usize,
    tolerance: f64,
) -> Result<Approximation> {
    check_tolerance(tolerance)?;
    check_order(r)?;
    let mut ctrl = Vec::new();
    let domain = curve.domain();
    let (m, max_error) = approximate_interval(curve, domain, r, tolerance, &mut ctrl, false)?;
    let curve = assemble(&[(domain, m)], 2 * r + 1, ctrl, curve.dim())?;
    Ok(Approximation { curve, max_error })
}

impl BlendSpline {
    /// A polynomial B-spline approximation in the global parameter `s`, for splines whose local
    /// curves have no exact Bezier form (angle-parametrised arcs, user curves): every segment is
    /// approximated separately by Hermite–Bezier pieces of degree `2k + 1` that reproduce the
    /// segment's derivatives up to order `k` at its ends, so the approximation has **the same
    /// `C^k`/`G^k` joins as the spline**. The error is measured ([`Approximation::max_error`]).
    /// For parabolas and rational arcs prefer the exact [`BlendSpline::to_nurbs`].
    ///
    /// # Errors
    /// As [`approximate_curve`].
    pub fn approximate(&self, tolerance: f64) -> Result<Approximation> {
        check_tolerance(tolerance)?;
        let r = self.continuity_degree();
        check_order(r)?;
        let params = self.parameters();
        let mut ctrl = Vec::new();
        let mut intervals = Vec::with_capacity(self.segment_count());
        let mut max_error = 0.0_f64;
        for i in 0..self.segment_count() {
            let Some(seg) = self.segment(i) else { break };
            let (m, e) = approximate_interval(seg, (0.0, 1.0), r, tolerance, &mut ctrl, i > 0)?;
            intervals.push(((params[i], params[i + 1]), m));
            max_error = max_error.max(e);
        }
        let curve = assemble(&intervals, 2 * r + 1, ctrl, self.dim())?;
        Ok(Approximation { curve, max_error })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::blend::deformation::FnCurve;

    // a cubic is reproduced exactly by one Hermite piece with r = 1 (degree 3)
    #[test]
    fn hermite_reproduces_cubics() {
        let cubic = FnCurve::new(1, (1.0, 3.0), |t: f64, order: usize, out: &mut [f64]| {
            let v = [t * t * t - 2.0 * t, 3.0 * t * t - 2.0, 6.0 * t, 6.0];
            for l in 0..=order {
                out[l] = if l < 4 { v[l] } else { 0.0 };
            }
            Ok(())
        })
        .unwrap();
        let a = approximate_curve(&cubic, 1, 1e-12).unwrap();
        assert_eq!(a.curve().control_points().len(), 4, "one piece");
        assert!(a.max_error() < 1e-13);
        for step in 0..=8 {
            let t = 1.0 + f64::from(step) / 4.0;
            let got = a.curve().eval(t).unwrap()[0];
            assert!((got - (t * t * t - 2.0 * t)).abs() < 1e-12, "t = {t}");
        }
    }

    // the error decreases like h^{2r+2}: halving the pieces divides it by about 2^{2r+2}
    #[test]
    fn convergence_order() {
        let exp = FnCurve::new(1, (0.0, 2.0), |t: f64, order: usize, out: &mut [f64]| {
            out[..=order].fill(t.exp());
            Ok(())
        })
        .unwrap();
        for r in 1..=2 {
            let mut ctrl = Vec::new();
            let (m1, e1) =
                approximate_interval(&exp, (0.0, 2.0), r, 1e-9, &mut ctrl, false).unwrap();
            let (m, e2) =
                approximate_interval(&exp, (0.0, 2.0), r, e1 / 2.0, &mut ctrl, false).unwrap();
            assert!(m1 >= 4 && m == 2 * m1, "r = {r}: {m1} then {m} pieces");
            let expected = 2f64.powi(i32::try_from(2 * r + 2).unwrap());
            let ratio = e1 / e2;
            assert!(
                ratio > 0.7 * expected && ratio < 1.4 * expected,
                "r = {r}: {ratio}"
            );
        }
    }

    #[test]
    fn errors() {
        let line = FnCurve::new(1, (0.0, 1.0), |t: f64, _: usize, out: &mut [f64]| {
            out.fill(0.0);
            out[0] = t;
            Ok(())
        })
        .unwrap();
        assert!(matches!(
            approximate_curve(&line, 1, 0.0),
            Err(Error::InvalidArgument { .. })
        ));
        assert!(matches!(
            approximate_curve(&line, 21, 1e-3),
            Err(Error::InvalidArgument { what, .. }) if what.words() == "Hermite order r"
        ));
        assert!(matches!(
            approximate_curve(&line, 1, f64::NAN),
            Err(Error::InvalidArgument { .. })
        ));
        // |t|^{1/2}-like kink cannot be reached to 1e-300
        let kink = FnCurve::new(1, (-1.0, 1.0), |t: f64, order: usize, out: &mut [f64]| {
            out.fill(0.0);
            out[0] = t.abs().sqrt();
            if order >= 1 && t != 0.0 {
                out[1] = 0.5 * t.signum() / t.abs().sqrt();
            }
            Ok(())
        })
        .unwrap();
        assert!(matches!(
            approximate_curve(&kink, 1, 1e-300),
            Err(Error::InvalidArgument { .. })
        ));
    }
}
