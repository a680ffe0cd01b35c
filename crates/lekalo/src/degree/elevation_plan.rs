//! Precomputed Bezier degree elevation for many curves of one degree (document 004 eq. 8), the
//! fast path for batch work such as elevating every piece of a large model.

use crate::degree::elevation::{apply_band, check_size, elevation_band, BAND_PAD};
use crate::error::{Error, Result};
use crate::points::Points;
use crate::Arg;
use crate::BezierCurve;

/// Precomputed one-step elevation from degree `n` to `n + r` (document 004 eq. 8, closed form
/// `C(n,i) C(r,j−i) / C(n+r,j)`), for elevating many curves of the same degree. Stores the
/// `(n+1)(r+1)` non-zero weights as a zero-padded band ([`elevation_band`]), so that
/// [`ElevationPlan::apply_into`] runs fixed-length vector loops and does not allocate
/// (10 → 20 in 3-D: 121 weights, 363 multiply-adds).
///
/// ```
/// use lekalo::ElevationPlan;
/// let plan = ElevationPlan::new(10, 20)?;
/// let ctrl: Vec<f64> = (0..33).map(|i| f64::from(i).sin()).collect(); // 11 points in 3-D
/// let mut out = vec![0.0; 21 * 3];
/// plan.apply_into(&ctrl, 3, &mut out)?;
/// assert_eq!(&out[..3], &ctrl[..3]);
/// assert_eq!(&out[60..], &ctrl[30..]);
/// # Ok::<(), lekalo::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct ElevationPlan {
    from: usize,
    to: usize,
    band: Vec<f64>,
}

impl ElevationPlan {
    /// Plan for elevating degree `from` to degree `to`.
    ///
    /// # Errors
    /// [`Error::Degree`] if `to < from`; [`Error::TooLarge`] if the weight table would exceed
    /// [`MAX_SCALARS`](crate::MAX_SCALARS).
    pub fn new(from: usize, to: usize) -> Result<Self> {
        let r = to.checked_sub(from).ok_or_else(|| Error::Degree {
            degree: to,
            reason: format!(
                "an elevation plan needs a target degree of at least {from}; reduce with \
                 BezierCurve::change_degree"
            ),
        })?;
        // degrees above MAX_DEGREE would pass the size check and then loop `to` times
        if to > crate::MAX_DEGREE {
            return Err(Error::TooLarge {
                what: "elevation target degree".into(),
                size: to,
                max: crate::MAX_DEGREE,
            });
        }
        // saturating: `to = usize::MAX` must be refused as too large, not overflow
        check_size(
            "elevation weights",
            from.saturating_add(1),
            r.saturating_add(1 + 2 * BAND_PAD),
        )?;
        Ok(ElevationPlan {
            from,
            to,
            band: elevation_band(from, r),
        })
    }

    /// Degree of the input curves.
    #[must_use]
    pub fn from_degree(&self) -> usize {
        self.from
    }

    /// Degree of the output curves.
    #[must_use]
    pub fn to_degree(&self) -> usize {
        self.to
    }

    /// Elevates the flat point-major control points `control` (`from + 1` points of dimension
    /// `dim`) into `out` (`to + 1` points). No allocation; the input is not checked for
    /// finiteness (finite input gives finite output). Dimensions 1 to 4 use loops specialised
    /// at compile time.
    ///
    /// # Errors
    /// [`Error::Dimension`] if `dim == 0`; [`Error::LengthMismatch`] for wrong buffer lengths.
    pub fn apply_into(&self, control: &[f64], dim: usize, out: &mut [f64]) -> Result<()> {
        if dim == 0 {
            return Err(Error::Dimension {
                what: Arg::ControlPoints.into(),
                expected: 1,
                got: 0,
            });
        }
        if control.len() != (self.from + 1) * dim {
            return Err(Error::LengthMismatch {
                what: "control point coordinates ((from degree + 1) × dim)".into(),
                expected: (self.from + 1) * dim,
                got: control.len(),
            });
        }
        if out.len() != (self.to + 1) * dim {
            return Err(Error::LengthMismatch {
                what: "output coordinates ((to degree + 1) × dim)".into(),
                expected: (self.to + 1) * dim,
                got: out.len(),
            });
        }
        apply_band(&self.band, self.to - self.from, control, dim, out);
        Ok(())
    }

    /// Elevates a curve of degree [`ElevationPlan::from_degree`].
    ///
    /// # Errors
    /// [`Error::Degree`] if the curve has another degree.
    pub fn apply(&self, curve: &BezierCurve) -> Result<BezierCurve> {
        if curve.degree() != self.from {
            return Err(Error::Degree {
                degree: curve.degree(),
                reason: format!("this elevation plan is for curves of degree {}", self.from),
            });
        }
        let dim = curve.dim();
        let mut out = vec![0.0; (self.to + 1) * dim];
        self.apply_into(curve.control_points().as_slice(), dim, &mut out)?;
        Ok(BezierCurve::from_raw(Points::from_raw(out, dim)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::degree::elevation::{band_stride, gather_band_body, scatter_band};

    fn net(n: usize, dim: usize) -> Points {
        let data = (0..(n + 1) * dim)
            .map(|i| ((i as f64) * 12.9898).sin() * 4.0)
            .collect();
        Points::from_flat(dim, data).unwrap()
    }

    /// The block gather (both instruction-set copies where the processor has AVX2) returns the
    /// bits of the term-by-term scatter, in every specialised dimension, for elevations of
    /// every size class: fewer new points than a block, a partial last block, rows shorter and
    /// longer than a block, and weights from the row-by-row fallback (n + r > 131).
    #[test]
    fn gather_matches_scatter_bit_for_bit() {
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        let cases = [
            (0, 0),
            (0, 3),
            (1, 1),
            (3, 4),
            (10, 10),
            (50, 50),
            (7, 200),
            (2, 9),
        ];
        for dim in 1..=4 {
            for (n, r) in cases {
                let p = net(n, dim);
                let band = elevation_band(n, r);
                assert_eq!(band.len(), (n + 1) * band_stride(r));
                let fresh = || vec![f64::NAN; (n + r + 1) * dim];
                let (mut scattered, mut gathered, mut baseline) = (fresh(), fresh(), fresh());
                scatter_band(&band, r, p.as_slice(), dim, &mut scattered);
                apply_band(&band, r, p.as_slice(), dim, &mut gathered);
                match dim {
                    1 => gather_band_body::<1>(&band, r, p.as_slice(), &mut baseline),
                    2 => gather_band_body::<2>(&band, r, p.as_slice(), &mut baseline),
                    3 => gather_band_body::<3>(&band, r, p.as_slice(), &mut baseline),
                    _ => gather_band_body::<4>(&band, r, p.as_slice(), &mut baseline),
                }
                let case = format!("dim {dim}, {n} -> {}", n + r);
                assert_eq!(bits(&gathered), bits(&scattered), "{case}");
                assert_eq!(bits(&baseline), bits(&scattered), "{case}");
            }
        }
    }

    #[test]
    fn plan_matches_curve_elevation_and_checks() {
        for dim in [1, 2, 3, 5] {
            let c = BezierCurve::new(net(10, dim)).unwrap();
            let plan = ElevationPlan::new(10, 20).unwrap();
            let a = plan.apply(&c).unwrap();
            let b = c.elevate_degree(10).unwrap();
            assert_eq!(a, b, "plan = elevate_degree, dim {dim}");
        }
        let plan = ElevationPlan::new(2, 4).unwrap();
        assert_eq!((plan.from_degree(), plan.to_degree()), (2, 4));
        assert!(matches!(
            ElevationPlan::new(4, 2),
            Err(Error::Degree { degree: 2, .. })
        ));
        let mut out = vec![0.0; 10];
        assert!(matches!(
            plan.apply_into(&[0.0; 6], 0, &mut out),
            Err(Error::Dimension { .. })
        ));
        assert!(matches!(
            plan.apply_into(&[0.0; 5], 2, &mut out),
            Err(Error::LengthMismatch { expected: 6, .. })
        ));
        assert!(matches!(
            plan.apply_into(&[0.0; 6], 2, &mut out[..9]),
            Err(Error::LengthMismatch { expected: 10, .. })
        ));
        let c = BezierCurve::new(net(3, 2)).unwrap();
        assert!(matches!(
            plan.apply(&c),
            Err(Error::Degree { degree: 3, .. })
        ));
    }
}
