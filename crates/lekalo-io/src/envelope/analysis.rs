//! The curve analysis the writers and the CLI share is the library's own ([`lekalo::Curve`]:
//! domain, points, derivatives, sampling; [`lekalo::curvature`]); this module only re-exports
//! what older callers of `lekalo_io` named.

/// `n` evenly spaced values from `a` to `b` inclusive: [`lekalo::uniform_parameters`].
pub use lekalo::uniform_parameters as uniform;

pub use lekalo::curvature;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::object::Object;
    use lekalo::{BezierCurve, NurbsCurve, Points};

    #[test]
    fn circle_curvature_and_rational_derivatives() {
        // quarter circle of radius 2: curvature 1/2 everywhere, |C'| from finite differences
        let w = std::f64::consts::FRAC_1_SQRT_2;
        let ctrl = Points::from_2d(&[[2.0, 0.0], [2.0, 2.0], [0.0, 2.0]]).unwrap();
        let c = Object::Nurbs(
            NurbsCurve::new(
                2,
                vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
                ctrl,
                vec![1.0, w, 1.0],
            )
            .unwrap(),
        );
        for t in [0.1, 0.5, 0.9] {
            let d = c.eval_derivatives(t, 2).unwrap();
            let k = curvature(d.point(1), d.point(2)).unwrap();
            assert!((k - 0.5).abs() < 1e-12, "curvature {k} at {t}");
            let h = 1e-6;
            let (a, b) = (c.eval(t - h).unwrap(), c.eval(t + h).unwrap());
            for i in 0..2 {
                let fd = (b[i] - a[i]) / (2.0 * h);
                assert!((fd - d.point(1)[i]).abs() < 1e-7, "C' at {t}");
            }
            // tangent is orthogonal to the radius
            let p = d.point(0);
            assert!(
                (p[0] * d.point(1)[0] + p[1] * d.point(1)[1]).abs() < 1e-12,
                "tangent"
            );
        }
    }

    #[test]
    fn bezier_derivatives_match_hodograph() {
        // P(t) = (2t, 2t(1−t)·2): P'(t) = (2, 4 − 8t)
        let c = Object::Bezier(
            BezierCurve::new(Points::from_2d(&[[0.0, 0.0], [1.0, 2.0], [2.0, 0.0]]).unwrap())
                .unwrap(),
        );
        let d = c.eval_derivatives(0.25, 2).unwrap();
        assert_eq!(d.point(0), c.eval(0.25).unwrap().as_slice());
        assert!(
            (d.point(1)[0] - 2.0).abs() < 1e-14 && (d.point(1)[1] - 2.0).abs() < 1e-14,
            "P'"
        );
        assert!((d.point(2)[1] + 8.0).abs() < 1e-13, "P''");
        assert!(curvature(&[0.0, 0.0], &[1.0, 0.0]).is_none());
        assert_eq!(uniform(0.0, 1.0, 3), vec![0.0, 0.5, 1.0]);
    }
}
