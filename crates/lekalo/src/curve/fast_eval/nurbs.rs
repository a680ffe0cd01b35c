//! Fast batch evaluation of NURBS curves: the homogeneous B-spline's [`CurveEvaluator`]
//! followed by the projection `C(t) = A(t) / w(t)`.

use super::kernels::{power_dyn, power_fixed};
use super::{check_batch, par_chunks, CurveEvaluator, EvalKernel, KernelData};
use crate::curve::nurbs::NurbsCurve;
use crate::error::Result;

/// A NURBS curve prepared for fast evaluation: a [`CurveEvaluator`] of the homogeneous
/// B-spline `(w·P, w)` followed by the projection `C(t) = A(t) / w(t)` (P&T Algorithm A4.1).
///
/// ```
/// use lekalo::{NurbsCurve, Points};
/// let ctrl = Points::from_2d(&[[1.0, 0.0], [1.0, 1.0], [0.0, 1.0]])?;
/// let w = std::f64::consts::FRAC_1_SQRT_2;
/// let arc = NurbsCurve::new(2, vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0], ctrl, vec![1.0, w, 1.0])?;
/// let ts: Vec<f64> = (0..=64).map(|k| f64::from(k) / 64.0).collect();
/// let mut out = vec![0.0; ts.len() * 2];
/// arc.evaluator().eval_batch(&ts, &mut out)?;
/// assert!(out.chunks(2).all(|p| (p[0].hypot(p[1]) - 1.0).abs() < 1e-15));
/// # Ok::<(), lekalo::Error>(())
/// ```
#[derive(Debug, Clone)]
pub struct NurbsEvaluator {
    homogeneous: CurveEvaluator,
}

impl NurbsCurve {
    /// A [`NurbsEvaluator`] for this curve (default kernel). O(n·p²·dim) once.
    #[must_use]
    pub fn evaluator(&self) -> NurbsEvaluator {
        NurbsEvaluator {
            homogeneous: self.homogeneous().evaluator(),
        }
    }
}

impl NurbsEvaluator {
    /// A [`NurbsEvaluator`] with the given kernel for the homogeneous curve.
    ///
    /// # Errors
    /// As [`CurveEvaluator::with_kernel`].
    pub fn with_kernel(curve: &NurbsCurve, kernel: EvalKernel) -> Result<Self> {
        Ok(NurbsEvaluator {
            homogeneous: CurveEvaluator::with_kernel(curve.homogeneous(), kernel)?,
        })
    }

    /// The evaluator of the homogeneous B-spline.
    #[must_use]
    pub fn homogeneous(&self) -> &CurveEvaluator {
        &self.homogeneous
    }

    /// Euclidean dimension.
    #[must_use]
    pub fn dim(&self) -> usize {
        self.homogeneous.dim - 1
    }

    /// Points `C(t)` for every `t` in `ts` into `out` (`ts.len() × dim`); the fast twin of
    /// [`NurbsCurve::eval`] at every parameter. One allocation per call (scratch).
    ///
    /// # Errors
    /// [`Error::LengthMismatch`] if `out.len() != ts.len() · dim`;
    /// [`Error::ParameterOutOfDomain`] at the first parameter outside the domain.
    pub fn eval_batch(&self, ts: &[f64], out: &mut [f64]) -> Result<()> {
        check_batch(ts.len(), self.dim(), out.len())?;
        self.eval_slice(ts, out)
    }

    /// As [`NurbsEvaluator::eval_batch`] over the rayon pool, bit-identical to it.
    ///
    /// # Errors
    /// As [`NurbsEvaluator::eval_batch`].
    pub fn par_eval_batch(&self, ts: &[f64], out: &mut [f64]) -> Result<()> {
        check_batch(ts.len(), self.dim(), out.len())?;
        par_chunks(ts, out, self.dim(), |t, o| self.eval_slice(t, o))
    }

    fn eval_slice(&self, ts: &[f64], out: &mut [f64]) -> Result<()> {
        let h = &self.homogeneous;
        let dim = self.dim();
        if let KernelData::Power { coef } = &h.kernel {
            macro_rules! fixed {
                ($p:literal, $hd:literal) => {
                    return h.drive(ts, out, $hd - 1, None, |j, t, o| {
                        let mut a = [0.0; $hd];
                        power_fixed::<$p, $hd>(coef, j, t, &mut a);
                        project(&a, o);
                    })
                };
            }
            match (h.degree, h.dim) {
                (2, 3) => fixed!(2, 3),
                (2, 4) => fixed!(2, 4),
                (3, 3) => fixed!(3, 3),
                (3, 4) => fixed!(3, 4),
                _ => {}
            }
        }
        let mut a = vec![0.0; dim + 1];
        match &h.kernel {
            KernelData::Power { coef } => h.drive(ts, out, dim, None, |j, t, o| {
                power_dyn(h.degree, coef, j, t, &mut a);
                project(&a, o);
            }),
            KernelData::Basis {
                knots,
                control,
                recip,
            } => {
                let mut n = vec![0.0; 3 * (h.degree + 1)];
                h.drive(ts, out, dim, None, |j, t, o| {
                    h.basis_point(knots, control, recip, j, t, &mut n, &mut a);
                    project(&a, o);
                })
            }
        }
    }
}

/// `o = a[..dim] / a[dim]`, as [`NurbsCurve::eval`] divides.
#[inline(always)]
fn project(a: &[f64], o: &mut [f64]) {
    let w = a[o.len()];
    for (x, &y) in o.iter_mut().zip(a) {
        *x = y / w;
    }
}
