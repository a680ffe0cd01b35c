//! The budget of one request ([`Limits`]): every curve a request sends (as points to build
//! from, as an object in the CLI's format, as an expression with its breakpoints and order) or
//! asks for (a drawing, an elevation, a blend) is checked against the limits before anything is
//! computed, and refused with 400 naming the request field and the limit, with the option of
//! `lekalo serve` that raises it.
//!
//! The work of a drawing is counted as evaluations × `(degree + 1)²`: de Casteljau's algorithm
//! (Farin, *Curves and Surfaces for CAGD*, §4.2) and Cox–de Boor (Piegl & Tiller, *The NURBS
//! Book*, A2.2) take O(`(p + 1)²`) operations per point, so a degree-3000 curve drawn at 10,000
//! samples is 9·10^10 operations, refused, while the editor's curves are a few thousand.

use lekalo_io::Object;

use crate::error::{ApiError, ApiResult};
use crate::view::ViewOptions;
use crate::Limits;

/// Default [`Limits::max_work`]: 2^27 evaluations × `(degree + 1)²`, about a tenth of a second.
pub const MAX_WORK: u64 = 1 << 27;

impl Limits {
    /// `p` if it is at most [`Limits::max_degree`].
    ///
    /// # Errors
    /// 400 naming `field`.
    pub fn check_degree(&self, p: usize, field: &str) -> ApiResult<usize> {
        if p > self.max_degree {
            return Err(ApiError::bad(
                field,
                format!(
                    "{field} = {p} is above the server's limit {} (lekalo serve --max-degree); \
                     use the CLI for higher degrees",
                    self.max_degree
                ),
            ));
        }
        Ok(p)
    }

    /// `n` points are at most [`Limits::max_points`].
    ///
    /// # Errors
    /// 400 naming `field`.
    pub fn check_points(&self, n: usize, field: &str) -> ApiResult<()> {
        if n > self.max_points {
            return Err(ApiError::bad(
                field,
                format!(
                    "{n} points: at most {} per request (lekalo serve --max-points; use the \
                     CLI for more)",
                    self.max_points
                ),
            ));
        }
        Ok(())
    }

    /// `n` if it lies in `2 ..= max_samples`.
    ///
    /// # Errors
    /// 400 naming `field`.
    pub fn check_samples(&self, n: usize, field: &str) -> ApiResult<usize> {
        if !(2..=self.max_samples).contains(&n) {
            return Err(ApiError::bad(
                field,
                format!(
                    "{field} = {n}: give between 2 and {} samples (lekalo serve --max-samples)",
                    self.max_samples
                ),
            ));
        }
        Ok(n)
    }

    /// A curve sent in `field` or built by the request: its degree (`field.degree`) and its
    /// number of control points (`field.control`) within the limits.
    ///
    /// # Errors
    /// 400 naming the field.
    pub fn check_curve(&self, obj: &Object, field: &str) -> ApiResult<()> {
        self.check_degree(obj.degree(), &format!("{field}.degree"))?;
        self.check_points(obj.control_points().len(), &format!("{field}.control"))
    }

    /// `evaluations × (degree + 1)²` within [`Limits::max_work`].
    ///
    /// # Errors
    /// 400 naming `field`, the request field that sets the number of evaluations.
    pub fn check_work(&self, evaluations: usize, degree: usize, field: &str) -> ApiResult<()> {
        let w = degree as u64 + 1;
        let work = (evaluations as u64).saturating_mul(w.saturating_mul(w));
        if work > self.max_work {
            return Err(ApiError::bad(
                field,
                format!(
                    "{evaluations} evaluations of a degree-{degree} curve cost {work:.3e} \
                     operations (evaluations × (degree + 1)²), above the server's limit {:.3e} \
                     (lekalo serve --max-work); ask for fewer {field}",
                    self.max_work
                ),
            ));
        }
        Ok(())
    }

    /// The drawing `opt` of the curve `obj` (sent in or built from `field`): the curve
    /// ([`Limits::check_curve`]), the sample counts and the work of samples, comb, basis panel
    /// and knot marks together.
    ///
    /// # Errors
    /// 400 naming the field at fault.
    pub fn check_view(&self, obj: &Object, opt: &ViewOptions, field: &str) -> ApiResult<()> {
        self.check_curve(obj, field)?;
        let samples = self.check_samples(opt.samples, "samples")?;
        let basis = match opt.basis_samples {
            Some(m) => self.check_samples(m, "basis_samples")?,
            None => 0,
        };
        let evaluations = samples
            .saturating_mul(1 + usize::from(opt.comb))
            .saturating_add(basis)
            .saturating_add(obj.knots().len());
        self.check_work(evaluations, obj.degree(), "samples")
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use lekalo::{BezierCurve, Points};

    /// A Bezier curve of degree `n` (its degree comes from its control points).
    fn bezier(n: usize) -> Object {
        let rows: Vec<[f64; 2]> = (0..=n).map(|i| [i as f64, (i % 3) as f64]).collect();
        Object::Bezier(BezierCurve::new(Points::from_2d(&rows).expect("points")).expect("curve"))
    }

    #[test]
    fn every_default_drawing_fits_and_the_hostile_one_is_refused() {
        let l = Limits::default();
        let most = ViewOptions {
            samples: l.max_samples,
            comb: true,
            basis_samples: Some(l.max_samples),
            at: None,
        };
        assert_eq!(l.check_view(&bezier(l.max_degree), &most, "curve"), Ok(()));
        // a degree-3000 curve at 10,000 samples: the degree is named
        let hostile = ViewOptions {
            samples: 10_000,
            ..ViewOptions::default()
        };
        let e = l
            .check_view(&bezier(3000), &hostile, "curve")
            .expect_err("refused");
        assert_eq!(e.field.as_deref(), Some("curve.degree"));
        assert!(e.message.contains("--max-degree"), "{}", e.message);
        // with the degree limit raised, the work limit refuses it
        let raised = Limits {
            max_degree: 4000,
            ..l
        };
        let e = raised
            .check_view(&bezier(3000), &hostile, "curve")
            .expect_err("refused");
        assert_eq!(e.field.as_deref(), Some("samples"));
        assert!(e.message.contains("--max-work"), "{}", e.message);
        let e = l
            .check_view(
                &bezier(3),
                &ViewOptions {
                    samples: 1,
                    ..hostile
                },
                "curve",
            )
            .expect_err("refused");
        assert_eq!(e.field.as_deref(), Some("samples"));
    }
}
