//! Precomputed Bezier degree elevation for many curves of one degree (document 004 eq. 8), the
//! fast path for batch work such as elevating every piece of a large model.

use crate::bezier_degree::{binomial_row, check_size, elevation_weights_into};
use crate::error::{Error, Result};
use crate::points::Points;
use crate::BezierCurve;

/// Precomputed one-step elevation from degree `n` to `n + r` (document 004 eq. 8, closed form
/// `C(n,i) C(r,j−i) / C(n+r,j)`), for elevating many curves of the same degree. Stores the
/// `(n+1)(r+1)` non-zero weights as a band, `band[i·(r+1) + l]` = weight of old point `i` in new
/// point `i + l`, so that [`ElevationPlan::apply_into`] runs fixed-length inner loops and does not
/// allocate (10 → 20 in 3-D: 121 weights, 363 multiply-adds).
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
                what: "elevation target degree",
                size: to,
                max: crate::MAX_DEGREE,
            });
        }
        // saturating: `to = usize::MAX` must be refused as too large, not overflow
        check_size(
            "elevation weights",
            from.saturating_add(1),
            r.saturating_add(1),
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
                what: "control points",
                expected: 1,
                got: 0,
            });
        }
        if control.len() != (self.from + 1) * dim {
            return Err(Error::LengthMismatch {
                what: "control point coordinates ((from degree + 1) × dim)",
                expected: (self.from + 1) * dim,
                got: control.len(),
            });
        }
        if out.len() != (self.to + 1) * dim {
            return Err(Error::LengthMismatch {
                what: "output coordinates ((to degree + 1) × dim)",
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

/// The weights of elevation from degree `n` by `r` as a band: `band[i·(r+1) + l]` is the weight
/// `C(n,i) C(r,l) / C(n+r,i+l)` of old point `i` in new point `i + l` (document 004 eq. 8).
///
/// Up to `n + r = 131` from the binomial table, with the reciprocal of each denominator
/// computed once (`n + r + 1` divisions in all): up to `n + r = 56` the table and the numerator
/// are exact integers, so each weight is within an ulp (two roundings); above, the three
/// binomials are correctly rounded and each weight is within about three ulps. Beyond 131, row
/// by row with [`elevation_weights_into`].
pub(crate) fn elevation_band(n: usize, r: usize) -> Vec<f64> {
    let mut band = vec![0.0; (n + 1) * (r + 1)];
    if let (Some(row_n), Some(row_r), Some(row_nr)) =
        (binomial_row(n), binomial_row(r), binomial_row(n + r))
    {
        let inv: Vec<f64> = row_nr[..=n + r].iter().map(|c| 1.0 / c).collect();
        for ((w, &cn), inv) in band
            .chunks_exact_mut(r + 1)
            .zip(&row_n[..=n])
            .zip(inv.windows(r + 1))
        {
            for ((x, &cr), &v) in w.iter_mut().zip(&row_r[..=r]).zip(inv) {
                *x = cn * cr * v;
            }
        }
        return band;
    }
    let mut scratch = vec![0.0; n + 1];
    for j in 0..=n + r {
        let lo = elevation_weights_into(n, r, j, &mut scratch);
        for i in lo..=j.min(n) {
            band[i * (r + 1) + (j - i)] = scratch[i - lo];
        }
    }
    band
}

/// Applies an [`elevation_band`] for elevation by `r`: scatters each old point of `control`
/// (point-major, `dim ≥ 1` coordinates) into its `r + 1` new points of `out`, which is
/// overwritten. Every new point is summed over the old points in increasing order, as a direct
/// evaluation of eq. 8 would. Dimensions 1 to 4 use loops specialised at compile time. The
/// caller checks the lengths.
pub(crate) fn apply_band(band: &[f64], r: usize, control: &[f64], dim: usize, out: &mut [f64]) {
    match dim {
        1 => apply_band_fixed::<1>(band, r, control, out),
        2 => apply_band_fixed::<2>(band, r, control, out),
        3 => apply_band_fixed::<3>(band, r, control, out),
        4 => apply_band_fixed::<4>(band, r, control, out),
        _ => {
            let width = r + 1;
            out.fill(0.0);
            for (i, (p, w)) in control
                .chunks_exact(dim)
                .zip(band.chunks_exact(width))
                .enumerate()
            {
                let o = &mut out[i * dim..(i + width) * dim];
                for (oc, &wl) in o.chunks_exact_mut(dim).zip(w) {
                    for (x, y) in oc.iter_mut().zip(p) {
                        *x += wl * y;
                    }
                }
            }
        }
    }
}

/// [`apply_band`] for a dimension known at compile time.
fn apply_band_fixed<const D: usize>(band: &[f64], r: usize, control: &[f64], out: &mut [f64]) {
    let width = r + 1;
    out.fill(0.0);
    for (i, (p, w)) in control
        .chunks_exact(D)
        .zip(band.chunks_exact(width))
        .enumerate()
    {
        let mut pt = [0.0; D];
        pt.copy_from_slice(p);
        let o = &mut out[i * D..(i + width) * D];
        for (oc, &wl) in o.chunks_exact_mut(D).zip(w) {
            for k in 0..D {
                oc[k] += wl * pt[k];
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn net(n: usize, dim: usize) -> Points {
        let data = (0..(n + 1) * dim)
            .map(|i| ((i as f64) * 12.9898).sin() * 4.0)
            .collect();
        Points::new(data, dim).unwrap()
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
