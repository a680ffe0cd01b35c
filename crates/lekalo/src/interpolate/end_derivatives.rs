//! Interpolation on given knots with any set of derivative conditions at each end, chosen per
//! end (`docs/theory/interpolation.md#derivative-conditions-per-end`).

use crate::basis::{basis_ders_into, BasisScratch};
use crate::curve::bspline::BSplineCurve;
use crate::error::readable;
use crate::error::{Error, Result};
use crate::fit::banded::BandedQr;
use crate::interpolate::collocation::{solve_collocation, Factors};
use crate::interpolate::fast::free_end_cubic;
use crate::knots::KnotVector;
use crate::points::{Points, PointsRef};
use crate::{Arg, What};

/// A prescribed derivative at one end of an interpolating curve: `C^{(order)}(t̄) = value`,
/// derivatives with respect to the curve parameter; `value` has the points' dimension.
#[derive(Debug, Clone, PartialEq)]
pub struct EndDerivative {
    /// The order of the derivative, `0 ≤ order ≤ p` (order 0 prescribes the end value).
    pub order: usize,
    /// The prescribed derivative.
    pub value: Vec<f64>,
}

impl EndDerivative {
    /// `C^{(order)} = value` at one end.
    #[must_use]
    pub fn new(order: usize, value: Vec<f64>) -> Self {
        EndDerivative { order, value }
    }
}

/// The B-spline of degree `p` on the given `knots` that interpolates `points` at the increasing
/// `params` and satisfies the derivative conditions `start` at `params[0]` and `end` at the last
/// parameter: a condition for each end on its own (none, one, or several of any orders), e.g.
/// a clamped start and a natural end, or conditions at one end only. The unknowns are the
/// `n = knots − p − 1` control points; the conditions must number exactly `n`:
/// `params.len() + start.len() + end.len() = n`.
///
/// The square collocation system (de Boor, *A Practical Guide to Splines*, rev. ed. 2001,
/// ch. XIII; the system of SciPy's `make_interp_spline`) has the rows, in this order, of the
/// start conditions `Σ_i N^{(r)}_{i,p}(t̄_0) P_i = d_r` (P&T Algorithm A2.3 for the derivatives),
/// the data `Σ_i N_{i,p}(t̄_j) P_i = q_j`, and the end conditions. Its derivative rows are not
/// totally positive, so elimination without pivoting is not safe; the rows are instead rotated
/// into a banded triangle by Givens rotations (orthogonal, stable for any non-singular square
/// matrix; `docs/theory/fitting.md#banded-qr`), in O(n·p·(p + dim)). Without conditions at
/// either end the matrix is the collocation matrix alone, totally positive, and is eliminated
/// without pivoting instead (half the work; `docs/theory/interpolation.md#collocation-by-elimination-without-pivoting`).
///
/// # Errors
/// [`Error::TooFew`] for no point; [`Error::Dimension`] for a condition whose value does not
/// have the points' dimension; [`Error::LengthMismatch`] if the conditions do not number the
/// control points; [`Error::NotIncreasing`] for decreasing parameters;
/// [`Error::InvalidArgument`] for an order above `p` or repeated parameters; [`Error::ParameterOutOfDomain`] for a parameter outside the knots' domain;
/// [`Error::NonFinite`] for non-finite input; [`Error::SingularSystem`] if the conditions do not
/// determine the spline (e.g. a parameter-free knot span, Schoenberg–Whitney, or two conditions
/// of one order at one end).
pub fn interpolate_with_end_derivatives(
    points: PointsRef<'_>,
    params: &[f64],
    knots: &KnotVector,
    degree: usize,
    start: &[EndDerivative],
    end: &[EndDerivative],
) -> Result<BSplineCurve> {
    let p = degree;
    let dim = points.dim();
    let m = points.len();
    if m == 0 {
        return Err(Error::TooFew {
            what: "points to interpolate".into(),
            min: 1,
            got: 0,
        });
    }
    if params.len() != m {
        return Err(Error::LengthMismatch {
            what: What::of(Arg::Parameters, "parameters (one per point)"),
            expected: m,
            got: params.len(),
        });
    }
    knots.check_degree(p)?;
    let n = knots.len() - p - 1;
    let conditions = m + start.len() + end.len();
    if conditions != n {
        return Err(Error::LengthMismatch {
            what: "conditions (points + end derivatives) to equal the control points \
                   (knots − degree − 1)"
                .into(),
            expected: n,
            got: conditions,
        });
    }
    for d in start.iter().chain(end) {
        if d.value.len() != dim {
            return Err(Error::Dimension {
                what: "an end derivative (the points' dimension)".into(),
                expected: dim,
                got: d.value.len(),
            });
        }
        if d.order > p {
            return Err(Error::InvalidArgument {
                what: "end derivative order".into(),
                reason: format!(
                    "order {} exceeds the degree {p}: the derivative of that order is zero; \
                     use orders 0 … {p}",
                    d.order
                ),
            });
        }
        if let Some(index) = d.value.iter().position(|v| !v.is_finite()) {
            return Err(Error::NonFinite {
                what: Arg::EndDerivative.into(),
                index,
                value: d.value[index],
            });
        }
    }
    // one pass over the parameters: each exceeds the one before (a pair with a NaN compares as
    // neither), so with finite ends every parameter is finite; the first non-finite parameter up
    // to the first pair out of order is reported as such
    let non_finite = |upto: usize| {
        params[..upto]
            .iter()
            .position(|v| !v.is_finite())
            .map(|index| Error::NonFinite {
                what: "parameters".into(),
                index,
                value: params[index],
            })
    };
    let disorder = params
        .windows(2)
        .position(|w| w[1].partial_cmp(&w[0]) != Some(std::cmp::Ordering::Greater));
    if let Some(e) = non_finite(disorder.map_or(m, |w| w + 2)) {
        return Err(e);
    }
    if let Some(w) = disorder {
        if params[w + 1] < params[w] {
            return Err(Error::NotIncreasing {
                what: "parameters".into(),
                index: w + 1,
                value: params[w + 1],
                previous: params[w],
            });
        }
        return Err(Error::InvalidArgument {
            what: "parameters".into(),
            reason: format!(
                "parameter {} = {} does not exceed parameter {w} = {}; pass strictly \
                 increasing parameters (one per point)",
                w + 1,
                readable(&params[w + 1]),
                readable(&params[w])
            ),
        });
    }
    if let Some(index) = points.as_slice().iter().position(|v| !v.is_finite()) {
        return Err(Error::NonFinite {
            what: "points".into(),
            index,
            value: points.as_slice()[index],
        });
    }
    let kn = knots.as_slice();
    if start.is_empty() && end.is_empty() {
        return collocation_only(points, params, knots, p);
    }
    let spans = params
        .iter()
        .map(|&t| knots.find_span(p, t))
        .collect::<Result<Vec<_>>>()?;
    let width = p + 1;
    let max_order = start.iter().chain(end).map(|d| d.order).max().unwrap_or(0);
    let mut qr = BandedQr::new(n, width, dim);
    let mut scratch = BasisScratch::new(p);
    let mut ders = vec![0.0; (max_order + 1) * width];
    let mut row = vec![0.0; width];
    let mut rhs = vec![0.0; dim];
    let mut derivative_rows =
        |qr: &mut BandedQr, sc: &mut BasisScratch, span: usize, t: f64, conds: &[EndDerivative]| {
            basis_ders_into(kn, p, span, t, max_order, sc, &mut ders);
            for d in conds {
                row.copy_from_slice(&ders[d.order * width..(d.order + 1) * width]);
                rhs.copy_from_slice(&d.value);
                qr.add_row(span - p, &mut row, &mut rhs);
            }
        };
    derivative_rows(&mut qr, &mut scratch, spans[0], params[0], start);
    let mut basis = vec![0.0; width];
    let mut y = vec![0.0; dim];
    for (j, (&t, &span)) in params.iter().zip(&spans).enumerate() {
        basis_ders_into(kn, p, span, t, 0, &mut scratch, &mut basis);
        y.copy_from_slice(points.point(j));
        qr.add_row(span - p, &mut basis, &mut y);
    }
    derivative_rows(&mut qr, &mut scratch, spans[m - 1], params[m - 1], end);
    let mut control = vec![0.0; n * dim];
    qr.solve(&mut control)
        .map_err(|col| Error::SingularSystem {
            reason: format!(
                "the points and end derivatives do not determine control point {col}: a knot \
             span holds no parameter (Schoenberg–Whitney), or two conditions at one end have \
             the same order; move the knots or change the conditions"
            ),
        })?;
    BSplineCurve::new(p, kn.to_vec(), Points::from_flat(dim, control)?)
}

/// The square collocation system without derivative rows, `Σ_i N_{i,p}(t̄_j) P_i = q_j`, by
/// banded Gaussian elimination without pivoting ([`solve_collocation`]): the collocation matrix
/// of increasing parameters is totally positive (Karlin; de Boor, "Total positivity of the
/// spline collocation matrix", *Indiana Univ. Math. J.* 25, 1976), non-singular exactly when
/// the Schoenberg–Whitney condition `N_{j,p}(t̄_j) > 0` holds (checked), and then elimination
/// without pivoting is stable (de Boor & Pinkus, "Backward error analysis for totally positive
/// linear systems", *Numer. Math.* 27, 1977; de Boor, *A Practical Guide to Splines*, ch. XIII)
/// — SciPy's `make_interp_spline` solves the same band by LU (`gbsv`). O(n·p·(p + dim)), half
/// the work of the Givens rotations, one row eliminated as it is built. A cubic in 1–3
/// dimensions on knots clamped at the first and last parameters (SciPy's not-a-knot knots,
/// FITPACK's for `s = 0`) takes the fused sweep of the same elimination (`cubic_sweep.rs`,
/// `docs/theory/interpolation.md#collocation-by-elimination-without-pivoting`), the rows built
/// and eliminated in registers; it agrees with the general elimination to rounding.
fn collocation_only(
    points: PointsRef<'_>,
    params: &[f64],
    knots: &KnotVector,
    p: usize,
) -> Result<BSplineCurve> {
    let dim = points.dim();
    let (lo, hi) = knots.domain(p);
    // the parameters increase (checked by the caller): all lie in the domain when the first
    // and the last do; else the first outside is reported
    let last = params[params.len() - 1];
    if params[0] < lo || last > hi {
        let t = if params[0] < lo {
            params[0]
        } else {
            params.iter().copied().find(|&t| t > hi).unwrap_or(last)
        };
        return Err(Error::ParameterOutOfDomain {
            t,
            min: lo,
            max: hi,
        });
    }
    let kn = knots.as_slice();
    let m = params.len();
    // the cubic on clamped knots whose ends are the first and last parameters (SciPy's
    // not-a-knot and FITPACK's s = 0 knots among them) in 1–3 dimensions: the fused sweep of the
    // same elimination (`cubic_sweep`), which hands anything it cannot do to the general path
    if p == 3
        && (1..=3).contains(&dim)
        && m >= 5
        && kn.len() == m + 4
        && kn[0] == params[0]
        && kn[3] == params[0]
        && kn[m] == params[m - 1]
        && kn[m + 3] == params[m - 1]
    {
        if let Some(control) = free_end_cubic(points, params, kn) {
            return BSplineCurve::new(p, kn.to_vec(), control);
        }
    }
    let mut control = points.as_slice().to_vec();
    solve_collocation(knots, p, params, 0, &mut control, dim, Factors::Discard)?;
    BSplineCurve::new(
        p,
        knots.as_slice().to_vec(),
        Points::from_flat(dim, control)?,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn knots_for(x: &[f64], p: usize) -> KnotVector {
        // the data sites with end knots of multiplicity p + 1 (n = m + p − 1 control points)
        let mut k = vec![x[0]; p];
        k.extend_from_slice(x);
        k.extend(std::iter::repeat_n(x[x.len() - 1], p));
        KnotVector::new(k).unwrap()
    }

    fn derivative(c: &BSplineCurve, t: f64, order: usize) -> f64 {
        c.eval_derivatives(t, order).unwrap().point(order)[0]
    }

    /// A polynomial of degree ≤ p is reproduced exactly, whatever the conditions, when they are
    /// its own values: a clamped start with a natural end, and conditions at one end only.
    #[test]
    fn reproduces_a_cubic_with_mixed_ends() {
        let f = |x: f64| 1.0 - 2.0 * x + 0.5 * x * x + 0.25 * x * x * x;
        let f1 = |x: f64| -2.0 + x + 0.75 * x * x;
        let f2 = |x: f64| 1.0 + 1.5 * x;
        let x = [0.0, 0.5, 1.3, 2.0, 2.4, 3.0];
        let y: Vec<f64> = x.iter().map(|&v| f(v)).collect();
        let pts = PointsRef::from_flat(1, &y).unwrap();
        let kv = knots_for(&x, 3);
        let cases: [(Vec<EndDerivative>, Vec<EndDerivative>); 3] = [
            (
                vec![EndDerivative::new(1, vec![f1(0.0)])],
                vec![EndDerivative::new(2, vec![f2(3.0)])],
            ),
            (
                vec![
                    EndDerivative::new(1, vec![f1(0.0)]),
                    EndDerivative::new(2, vec![f2(0.0)]),
                ],
                vec![],
            ),
            (
                vec![],
                vec![
                    EndDerivative::new(2, vec![f2(3.0)]),
                    EndDerivative::new(1, vec![f1(3.0)]),
                ],
            ),
        ];
        for (start, end) in cases {
            let c = interpolate_with_end_derivatives(pts, &x, &kv, 3, &start, &end).unwrap();
            for i in 0..=30 {
                let t = 3.0 * f64::from(i) / 30.0;
                let v = c.eval(t).unwrap()[0];
                assert!((v - f(t)).abs() < 1e-12, "{t}: {v} vs {}", f(t));
            }
        }
    }

    /// The fused cubic sweep (SciPy's not-a-knot knots, 1–3 dimensions) and the general
    /// elimination (the same data as the first column of 4-D points) give the same spline to
    /// rounding, and it interpolates.
    #[test]
    fn fused_cubic_sweep_matches_general_elimination() {
        let m = 40;
        let x: Vec<f64> = (0..m)
            .map(|i| f64::from(i) + 0.3 * (f64::from(i) * 1.7).sin())
            .collect();
        let y: Vec<f64> = x.iter().map(|v| (0.4 * v).sin() + 0.1 * v).collect();
        let mut k = vec![x[0]; 4];
        k.extend_from_slice(&x[2..m as usize - 2]);
        k.extend([x[m as usize - 1]; 4]);
        let kv = KnotVector::new(k).unwrap();
        let fused = interpolate_with_end_derivatives(
            PointsRef::from_flat(1, &y).unwrap(),
            &x,
            &kv,
            3,
            &[],
            &[],
        )
        .unwrap();
        let wide: Vec<f64> = y.iter().flat_map(|&v| [v, 1.0, -v, 2.0 * v]).collect();
        let general = interpolate_with_end_derivatives(
            PointsRef::from_flat(4, &wide).unwrap(),
            &x,
            &kv,
            3,
            &[],
            &[],
        )
        .unwrap();
        let a = fused.control_points().as_slice();
        let b = general.control_points().as_slice();
        for i in 0..a.len() {
            assert!(
                (a[i] - b[4 * i]).abs() < 1e-13,
                "{i}: {} vs {}",
                a[i],
                b[4 * i]
            );
        }
        for (&t, &v) in x.iter().zip(&y) {
            assert!((fused.eval(t).unwrap()[0] - v).abs() < 1e-13);
        }
    }

    /// A spline (not a polynomial) meets every condition it was given: the values, a first
    /// derivative at the start and a second at the end, for degree 2 (one condition in all).
    #[test]
    fn meets_its_conditions_quadratic_one_end() {
        let x = [0.0, 1.0, 1.5, 2.5, 4.0];
        let y = [1.0, -1.0, 2.0, 0.5, 3.0, 3.0, -2.0, 1.0, 0.0, 4.0];
        let pts = PointsRef::from_flat(2, &y).unwrap();
        let kv = knots_for(&x, 2);
        let end = [EndDerivative::new(1, vec![8.0, -3.0])];
        let c = interpolate_with_end_derivatives(pts, &x, &kv, 2, &[], &end).unwrap();
        for (j, &t) in x.iter().enumerate() {
            let v = c.eval(t).unwrap();
            assert!((v[0] - y[2 * j]).abs() < 1e-12 && (v[1] - y[2 * j + 1]).abs() < 1e-12);
        }
        let d = c.eval_derivatives(4.0, 1).unwrap();
        assert!((d.point(1)[0] - 8.0).abs() < 1e-11 && (d.point(1)[1] + 3.0).abs() < 1e-11);
    }

    /// The result agrees with the symmetric natural cubic of [`EndCondition::Natural`] where
    /// both describe the same spline.
    #[test]
    fn natural_both_ends_matches_natural_cubic() {
        let x = [0.0, 0.7, 1.1, 2.0, 3.5, 4.0];
        let y = [0.3, 1.0, -0.5, 2.0, 1.0, 0.0];
        let pts = PointsRef::from_flat(1, &y).unwrap();
        let kv = knots_for(&x, 3);
        let zero = || vec![EndDerivative::new(2, vec![0.0])];
        let c = interpolate_with_end_derivatives(pts, &x, &kv, 3, &zero(), &zero()).unwrap();
        assert!(derivative(&c, 0.0, 2).abs() < 1e-10 && derivative(&c, 4.0, 2).abs() < 1e-10);
        let reference = crate::natural_cubic_spline(&x, pts).unwrap();
        for i in 0..=40 {
            let t = 4.0 * f64::from(i) / 40.0;
            let (a, b) = (c.eval(t).unwrap()[0], reference.eval(t).unwrap()[0]);
            assert!((a - b).abs() < 1e-12, "{t}: {a} vs {b}");
        }
    }

    /// Without end conditions (odd and even degrees on SciPy's not-a-knot knots) the elimination
    /// without pivoting solves the square system: the spline passes through every point to
    /// rounding; a knot span without parameter is refused.
    #[test]
    fn collocation_alone_by_elimination_interpolates() {
        let x: Vec<f64> = (0..60)
            .map(|i| f64::from(i) * 0.37 + (f64::from(i) * 1.3).sin() * 0.1)
            .collect();
        let y: Vec<f64> = x.iter().flat_map(|&v| [v.sin(), (2.0 * v).cos()]).collect();
        let pts = Points::from_flat(2, y.clone()).unwrap();
        for p in [2usize, 3, 5] {
            // SciPy's not-a-knot knots: the ends p + 1 times, interior knots at the data (odd p)
            // or at the midpoints (even p)
            let m = x.len();
            let mut t = vec![x[0]; p + 1];
            if p % 2 == 1 {
                t.extend_from_slice(&x[p.div_ceil(2)..m - p.div_ceil(2)]);
            } else {
                t.extend((p / 2..m - p / 2 - 1).map(|i| 0.5 * (x[i] + x[i + 1])));
            }
            t.extend(std::iter::repeat_n(x[m - 1], p + 1));
            let kv = KnotVector::new(t).unwrap();
            let lu = interpolate_with_end_derivatives(pts.as_view(), &x, &kv, p, &[], &[]).unwrap();
            for (j, &xj) in x.iter().enumerate() {
                let v = lu.eval(xj).unwrap();
                assert!(
                    (v[0] - y[2 * j]).abs() < 1e-12 && (v[1] - y[2 * j + 1]).abs() < 1e-12,
                    "degree {p}, point {j}: {v:?}"
                );
            }
        }
        // four cubic coefficients, but no parameter in the span [2, 3]: Schoenberg–Whitney fails
        let kv = KnotVector::new(vec![0.0, 0.0, 0.0, 0.0, 3.0, 3.0, 3.0, 3.0]).unwrap();
        let pts = Points::from_flat(1, vec![1.0, 2.0, 3.0, 4.0]).unwrap();
        let err = interpolate_with_end_derivatives(
            pts.as_view(),
            &[0.0, 0.1, 0.2, 3.0],
            &kv,
            3,
            &[],
            &[],
        );
        assert!(
            err.is_ok(),
            "a single cubic span takes any four distinct parameters"
        );
        let kv = KnotVector::new(vec![0.0, 0.0, 0.0, 0.0, 2.0, 3.0, 3.0, 3.0, 3.0]).unwrap();
        let pts = Points::from_flat(1, vec![1.0, 2.0, 3.0, 4.0, 5.0]).unwrap();
        let err = interpolate_with_end_derivatives(
            pts.as_view(),
            &[0.0, 0.1, 0.2, 0.3, 0.4],
            &kv,
            3,
            &[],
            &[],
        );
        assert!(matches!(err, Err(Error::SingularSystem { .. })));
    }

    /// The one pass over the parameters names the first non-finite one up to the first pair out
    /// of order, else that pair; the domain is checked at the ends of the increasing parameters.
    #[test]
    fn parameter_checks_of_one_pass_name_the_first_fault() {
        let x: Vec<f64> = (0..8).map(f64::from).collect();
        let y: Vec<f64> = x.iter().map(|v| v * v).collect();
        let mut t = knots_for(&x, 3).as_slice().to_vec();
        // the knots of two fewer conditions: collocation alone needs m + p − 1 = n control points
        t.remove(4);
        t.remove(t.len() - 5);
        let kv0 = KnotVector::new(t).unwrap();
        let run = |params: &[f64], kv: &KnotVector| {
            let pts = PointsRef::from_flat(1, &y).unwrap();
            interpolate_with_end_derivatives(pts, params, kv, 3, &[], &[])
        };
        assert!(run(&x, &kv0).is_ok(), "the clean case");
        for (at, bad) in [
            (0, f64::NEG_INFINITY),
            (7, f64::INFINITY),
            (7, f64::NAN),
            (3, f64::NAN),
        ] {
            let mut p = x.clone();
            p[at] = bad;
            let e = run(&p, &kv0).unwrap_err();
            assert!(
                matches!(e, Error::NonFinite { index, .. } if index == at),
                "{at}: {e:?}"
            );
        }
        let mut p = x.clone();
        p[2] = 5.5;
        p[6] = f64::NAN;
        let e = run(&p, &kv0).unwrap_err();
        assert!(matches!(e, Error::NotIncreasing { index: 3, .. }), "{e:?}");
        p = x.clone();
        p[4] = p[3];
        let e = run(&p, &kv0).unwrap_err();
        assert!(matches!(e, Error::InvalidArgument { .. }), "{e:?}");
        p = x.clone();
        p[7] = 7.5;
        let e = run(&p, &kv0).unwrap_err();
        assert!(
            matches!(e, Error::ParameterOutOfDomain { t, .. } if t == 7.5),
            "{e:?}"
        );
        p = x.clone();
        p[0] = -0.5;
        let e = run(&p, &kv0).unwrap_err();
        assert!(
            matches!(e, Error::ParameterOutOfDomain { t, .. } if t == -0.5),
            "{e:?}"
        );
    }

    #[test]
    fn refuses_wrong_counts_orders_and_repeated_orders() {
        let x = [0.0, 1.0, 2.0, 3.0];
        let y = [0.0, 1.0, 0.0, 1.0];
        let pts = PointsRef::from_flat(1, &y).unwrap();
        let kv = knots_for(&x, 3);
        let one = |o| vec![EndDerivative::new(o, vec![0.0])];
        assert!(matches!(
            interpolate_with_end_derivatives(pts, &x, &kv, 3, &one(1), &[]),
            Err(Error::LengthMismatch {
                expected: 6,
                got: 5,
                ..
            })
        ));
        assert!(matches!(
            interpolate_with_end_derivatives(pts, &x, &kv, 3, &one(4), &one(1)),
            Err(Error::InvalidArgument { .. })
        ));
        let two = [
            EndDerivative::new(1, vec![0.0]),
            EndDerivative::new(1, vec![1.0]),
        ];
        assert!(matches!(
            interpolate_with_end_derivatives(pts, &x, &kv, 3, &two, &[]),
            Err(Error::SingularSystem { .. })
        ));
        let wide = [EndDerivative::new(1, vec![0.0, 0.0])];
        assert!(matches!(
            interpolate_with_end_derivatives(pts, &x, &kv, 3, &wide, &one(1)),
            Err(Error::Dimension { .. })
        ));
    }

    proptest::proptest! {
        /// Whatever the degree, the spline passes through every point and has every prescribed
        /// end derivative (relative to the data's scale). The conditions are split evenly
        /// between the ends (one more at either) and the mesh ratio is at most 3: piling them
        /// at one end makes the problem an initial-value one whose error grows geometrically
        /// along the data, a property of the problem, not of the solver.
        #[test]
        fn every_condition_is_met(
            p in 2usize..=5,
            m in 6usize..20,
            gaps in proptest::collection::vec(0.5f64..1.5, 19),
            values in proptest::collection::vec(-3.0f64..3.0, 20 + 10),
            more_at_start in proptest::bool::ANY,
        ) {
            let mut x = vec![0.0];
            for g in &gaps[..m - 1] {
                x.push(x[x.len() - 1] + g);
            }
            let y = &values[..m];
            let kv = knots_for(&x, p);
            // p − 1 conditions in all (m + p − 1 control points), orders 1, 2, … at each end
            let extra = p - 1;
            let left = if more_at_start { extra.div_ceil(2) } else { extra / 2 };
            let start: Vec<_> = (0..left).map(|r| EndDerivative::new(r + 1, vec![values[20 + r]])).collect();
            let end: Vec<_> = (0..extra - left)
                .map(|r| EndDerivative::new(r + 1, vec![values[25 + r]]))
                .collect();
            let pts = PointsRef::from_flat(1, y).unwrap();
            let c = interpolate_with_end_derivatives(pts, &x, &kv, p, &start, &end).unwrap();
            let scale = 1.0 + y.iter().chain(&values[20..]).fold(0.0f64, |a, v| a.max(v.abs()));
            for (j, &t) in x.iter().enumerate() {
                let v = c.eval(t).unwrap()[0];
                proptest::prop_assert!((v - y[j]).abs() < 1e-11 * scale, "point {}: {} vs {}", j, v, y[j]);
            }
            for (t, conds) in [(x[0], &start), (x[m - 1], &end)] {
                for d in conds.iter() {
                    let v = derivative(&c, t, d.order);
                    proptest::prop_assert!((v - d.value[0]).abs() < 1e-9 * scale, "order {}: {} vs {}", d.order, v, d.value[0]);
                }
            }
        }
    }
}
