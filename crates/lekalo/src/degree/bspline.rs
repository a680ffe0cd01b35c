//! Degree change of B-spline curves and surfaces, composed from the Bezier operations of document
//! 004 (docs/theory/degree.md#b-spline-degree-change) and Bezier decomposition (STYLE §7; as
//! `ricosjp/truck` `BSplineCurve::elevate_degree` and `msteinbeck/tinyspline`
//! `ts_bspline_elevate_degree`):
//!
//! 1. split the curve into its polynomial pieces ([`BSplineCurve::to_bezier_segments`]);
//! 2. change the degree of every piece (elevation, exact reduction or approximate reduction);
//! 3. join the pieces again ([`BSplineCurve::from_bezier_segments`]).
//!
//! A surface is changed along `u` as the B-spline curve whose control points are the rows of the
//! net (dimension `nv·dim`), then along `v` on the transposed net.
//!
//! The shape is kept (exactly for elevation and exact reduction), and so is continuity at the
//! breakpoints where the pieces share their end points. Joining the pieces gives every interior
//! breakpoint the multiplicity of the new degree (a C0 representation of a possibly smoother
//! curve). [`BSplineCurve::elevate_degree`] does not join: it reads its control points off the
//! elevated pieces as blossom values at the knots of P&T Algorithm A5.9 (multiplicities
//! `m_i + r`), which keeps the curve's continuity in its representation. Degree reduction keeps
//! the C0 form.

use crate::degree::approx_reduction::EndConditions;
use crate::degree::elevation::check_size;
use crate::degree::reduction::{absolute_tolerance, real_degree_and_net, try_reduce_exact};
use crate::error::{Error, Result};
use crate::points::Points;
use crate::{BSplineCurve, BSplineSurface, BezierCurve, BezierSegment, DEFAULT_DEGREE_TOLERANCE};

/// Result of [`BSplineCurve::reduce_degree_approx`].
#[derive(Debug, Clone, PartialEq)]
pub struct BSplineApproximateReduction {
    /// The reduced curve.
    pub curve: BSplineCurve,
    /// Upper bound of `max_t ‖c(t) − c̃(t)‖` over the whole domain (the largest bound of the
    /// pieces, see [`crate::ApproximateReduction::max_deviation_bound`]).
    pub max_deviation_bound: f64,
    /// Largest sampled deviation of the pieces (a lower bound of the true maximum).
    pub max_deviation_sampled: f64,
}

impl BSplineCurve {
    /// Degree elevation by `by` to the knot vector of P&T Algorithm A5.9 (every interior knot of
    /// multiplicity `m` gets `m + by`, the ends `p + by + 1`), in two local passes:
    ///
    /// 1. every polynomial piece is elevated by the closed form of document 004 eq. 8 (one
    ///    [`ElevationPlan`](crate::ElevationPlan) for all pieces);
    /// 2. every control point of the result is the blossom (polar form) of its piece at its
    ///    knots, `P_i = b(u_{i+1}, …, u_{i+p'})` (Ramshaw 1989; de Boor's "B-spline coefficients
    ///    are blossom values"), evaluated by de Casteljau's algorithm with one parameter per
    ///    level on the piece from whose interval those knots stick out least, relative to its
    ///    length.
    ///
    /// Time O(pieces · (p+1)(r+1) · dim + n · p'² · dim), linear in the number of pieces. The
    /// curve is unchanged to a few ulps of its scale: the arguments stick out of the chosen
    /// interval by no more than they do from the longest of the `p' + 1` candidates, which is
    /// at most about `p'` of its lengths.
    ///
    /// ```
    /// use lekalo::{BSplineCurve, Points};
    /// let ctrl = Points::from_2d(&[[0., 0.], [1., 2.], [3., 2.], [4., 0.], [5., 1.]])?;
    /// let c = BSplineCurve::new(2, vec![0., 0., 0., 1., 2., 3., 3., 3.], ctrl)?;
    /// let e = c.elevate_degree(1)?;
    /// assert_eq!(e.degree(), 3);
    /// // simple interior knots stay simple + 1: knots of P&T Algorithm A5.9
    /// assert_eq!(e.knots().as_slice(), &[0., 0., 0., 0., 1., 1., 2., 2., 3., 3., 3., 3.]);
    /// for t in [0.0, 0.4, 1.0, 2.5, 3.0] {
    ///     let (a, b) = (c.eval(t)?, e.eval(t)?);
    ///     assert!((a[0] - b[0]).abs() < 1e-14 && (a[1] - b[1]).abs() < 1e-14);
    /// }
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::TooLarge`] if the result is too large to allocate.
    pub fn elevate_degree(&self, by: usize) -> Result<BSplineCurve> {
        let p = self.degree();
        let segments = self.to_bezier_segments();
        let dim = self.dim();
        let (a, b) = self.domain();
        let q = p.checked_add(by).ok_or(Error::TooLarge {
            what: "elevated degree".into(),
            size: usize::MAX,
            max: crate::MAX_DEGREE,
        })?;
        let plan = crate::ElevationPlan::new(p, q)?;
        // knots of A5.9: multiplicity m + r inside, so a discontinuity (m = p + 1) stays one
        // (m + r = q + 1) and the blossoms of its two control points come from its two sides
        let mut knots = vec![a; q + 1];
        for (t, m) in self.knots().distinct() {
            if t > a && t < b {
                knots.extend(std::iter::repeat_n(t, m + by));
            }
        }
        knots.extend(std::iter::repeat_n(b, q + 1));
        let n_ctrl = knots.len() - q - 1;
        check_size("elevated control points", n_ctrl, dim)?;
        let width = (q + 1) * dim;
        check_size("elevated pieces", segments.len(), width)?;
        let mut nets = vec![0.0; segments.len() * width];
        for (s, net) in segments.iter().zip(nets.chunks_exact_mut(width)) {
            plan.apply_into(s.curve.control_points().as_slice(), dim, net)?;
        }
        // piece of each non-empty knot interval [u_k, u_{k+1}) of the domain
        let mut piece_of = vec![usize::MAX; knots.len()];
        let mut next = 0;
        for k in q..n_ctrl {
            if knots[k] < knots[k + 1] {
                piece_of[k] = next;
                next += 1;
            }
        }
        if next != segments.len() {
            return Err(Error::InvalidArgument {
                what: "curve to elevate".into(),
                reason: format!(
                    "its {} Bezier pieces do not match the {next} knot intervals of the \
                     elevated curve",
                    segments.len()
                ),
            });
        }
        let mut control = vec![0.0; n_ctrl * dim];
        let mut scratch = vec![0.0; width];
        for (i, out) in control.chunks_exact_mut(dim).enumerate() {
            let args = &knots[i + 1..=i + q];
            // the non-empty interval among k = i ..= i + q from which the arguments stick out
            // least, relative to its length (de Casteljau outside [0, 1] amplifies rounding by
            // about the distance outside): never a tiny interval between two close knots when
            // a longer one is at hand
            let outside = |k: usize| {
                let (lo, hi) = (knots[k], knots[k + 1]);
                let far = args.iter().fold(0.0_f64, |m, &x| m.max(lo - x).max(x - hi));
                far / (hi - lo)
            };
            let k = (i..=i + q)
                .filter(|&k| piece_of.get(k).is_some_and(|&j| j != usize::MAX))
                .map(|k| (k, outside(k)))
                .min_by(|a, b| a.1.total_cmp(&b.1))
                .map(|(k, _)| k)
                // B_i is positive somewhere in the domain, so one of its intervals is non-empty
                .ok_or_else(|| Error::InvalidArgument {
                    what: "curve to elevate".into(),
                    reason: format!("control point {i} of the elevated curve has no piece"),
                })?;
            let j = piece_of[k];
            let (lo, hi) = (segments[j].start, segments[j].end);
            scratch.copy_from_slice(&nets[j * width..(j + 1) * width]);
            blossom_in_place(&mut scratch, dim, args, lo, hi);
            out.copy_from_slice(&scratch[..dim]);
        }
        BSplineCurve::new(q, knots, Points::from_flat(dim, control)?)
    }

    /// Changes the degree to `target` without changing the shape, with the default tolerance
    /// [`DEFAULT_DEGREE_TOLERANCE`]; see [`BSplineCurve::change_degree_with_tolerance`].
    ///
    /// # Errors
    /// As [`BSplineCurve::change_degree_with_tolerance`].
    pub fn change_degree(&self, target: usize) -> Result<BSplineCurve> {
        self.change_degree_with_tolerance(target, DEFAULT_DEGREE_TOLERANCE)
    }

    /// Changes the degree from `p` to `target` per Bezier piece (document 004 eq. 10 on every
    /// piece, by the stable path of [`BezierCurve::change_degree_with_tolerance`]). Raising is
    /// always possible. Lowering is exact and possible only if every piece has a real degree of
    /// at most `target`, judged with `tolerance ×` the largest absolute control-point coordinate
    /// of the whole curve; otherwise it is refused, naming the largest real degree of the pieces.
    /// For an approximation use [`BSplineCurve::reduce_degree_approx`].
    ///
    /// ```
    /// use lekalo::{BSplineCurve, Error, Points};
    /// let ctrl = Points::from_2d(&[[0., 0.], [1., 2.], [3., 2.], [4., 0.], [5., 1.]])?;
    /// let c = BSplineCurve::new(2, vec![0., 0., 0., 1., 2., 3., 3., 3.], ctrl)?;
    /// let back = c.elevate_degree(3)?.change_degree(2)?;
    /// assert!((back.eval(1.7)?[1] - c.eval(1.7)?[1]).abs() < 1e-12);
    /// let e = c.change_degree(1).unwrap_err();
    /// assert!(matches!(e, Error::DegreeReductionRefused { real_degree: 2, .. }));
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::DegreeReductionRefused`]; [`Error::InvalidArgument`] for a bad tolerance;
    /// [`Error::TooLarge`] for an elevation too large to allocate.
    pub fn change_degree_with_tolerance(
        &self,
        target: usize,
        tolerance: f64,
    ) -> Result<BSplineCurve> {
        let p = self.degree();
        let tol = absolute_tolerance(tolerance, self.control_points().as_slice())?;
        if target >= p {
            return self.elevate_degree(target - p);
        }
        let dim = self.dim();
        let segments = self.to_bezier_segments();
        let mut pieces = Vec::with_capacity(segments.len());
        let mut refused = None;
        for s in &segments {
            let net = s.curve.control_points().as_slice();
            match try_reduce_exact(net, dim, target, tol) {
                Some(q) => pieces.push(BezierSegment {
                    start: s.start,
                    end: s.end,
                    curve: BezierCurve::from_raw(Points::from_raw(q, dim)),
                }),
                None => {
                    let (real, _) = real_degree_and_net(net, dim, tol, target + 1);
                    refused = Some(refused.map_or(real, |r: usize| r.max(real)));
                }
            }
        }
        if let Some(real_degree) = refused {
            return Err(Error::DegreeReductionRefused {
                requested: target,
                real_degree,
                direction: "curve",
            });
        }
        BSplineCurve::from_bezier_segments(&pieces)
    }

    /// Approximate degree reduction per Bezier piece ([`BezierCurve::reduce_degree_approx`]:
    /// the L2-best piece of degree `target` with the chosen end conditions). Keeping the end
    /// points keeps the curve continuous; keeping the end tangents also keeps the first
    /// derivative at every breakpoint, so a C1 curve stays C1.
    ///
    /// ```
    /// use lekalo::{BSplineCurve, EndConditions, Points};
    /// let ctrl = Points::from_2d(&[[0., 0.], [1., 2.], [2., 3.], [3., 2.], [4., 0.], [5., 1.]])?;
    /// let c = BSplineCurve::new(4, vec![0., 0., 0., 0., 0., 1., 2., 2., 2., 2., 2.], ctrl)?;
    /// let r = c.reduce_degree_approx(3, EndConditions::Tangents)?;
    /// assert_eq!(r.curve.degree(), 3);
    /// assert!(r.max_deviation_sampled <= r.max_deviation_bound);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for [`EndConditions::Free`] on a curve of more than one piece
    /// (the pieces would no longer meet); otherwise as [`BezierCurve::reduce_degree_approx`].
    pub fn reduce_degree_approx(
        &self,
        target: usize,
        ends: EndConditions,
    ) -> Result<BSplineApproximateReduction> {
        let segments = self.to_bezier_segments();
        if ends == EndConditions::Free && segments.len() > 1 {
            return Err(Error::InvalidArgument {
                what: "end conditions".into(),
                reason: format!(
                    "free ends would tear the {} pieces of the B-spline apart at their joins; \
                     keep the end points or the end tangents",
                    segments.len()
                ),
            });
        }
        let mut pieces = Vec::with_capacity(segments.len());
        let (mut bound, mut sampled) = (0.0_f64, 0.0_f64);
        for s in segments {
            let r = s.curve.reduce_degree_approx(target, ends)?;
            bound = bound.max(r.max_deviation_bound);
            sampled = sampled.max(r.max_deviation_sampled);
            pieces.push(BezierSegment {
                curve: r.curve,
                ..s
            });
        }
        Ok(BSplineApproximateReduction {
            curve: BSplineCurve::from_bezier_segments(&pieces)?,
            max_deviation_bound: bound,
            max_deviation_sampled: sampled,
        })
    }
}

/// The net of a surface with `u` and `v` exchanged (`rows × cols` points to `cols × rows`).
fn transpose(data: &[f64], rows: usize, cols: usize, dim: usize) -> Vec<f64> {
    let mut out = vec![0.0; data.len()];
    for i in 0..rows {
        for j in 0..cols {
            let (src, dst) = ((i * cols + j) * dim, (j * rows + i) * dim);
            out[dst..dst + dim].copy_from_slice(&data[src..src + dim]);
        }
    }
    out
}

/// Names the direction in a refusal of a surface operation done as a curve operation.
fn in_direction(e: Error, direction: &'static str) -> Error {
    match e {
        Error::DegreeReductionRefused {
            requested,
            real_degree,
            ..
        } => Error::DegreeReductionRefused {
            requested,
            real_degree,
            direction,
        },
        other => other,
    }
}

impl BSplineSurface {
    /// Raises the degrees by `by_u` and `by_v` without changing the surface; see
    /// [`BSplineSurface::change_degree_with_tolerance`].
    ///
    /// ```
    /// use lekalo::{BSplineSurface, KnotVector, Points};
    /// let net = Points::from_flat(1, (0..4 * 3).map(|k| f64::from(k * k % 5)).collect())?;
    /// let s = BSplineSurface::from_knot_vectors(
    ///     2, 1, KnotVector::clamped_uniform(2, 4)?, KnotVector::clamped_uniform(1, 3)?, net, (4, 3))?;
    /// let e = s.elevate_degree(1, 2)?;
    /// assert_eq!((e.degree_u(), e.degree_v()), (3, 3));
    /// assert!((e.eval(0.3, 0.6)?[0] - s.eval(0.3, 0.6)?[0]).abs() < 1e-13);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::TooLarge`] if the result is too large to allocate.
    pub fn elevate_degree(&self, by_u: usize, by_v: usize) -> Result<BSplineSurface> {
        let new_u = self.degree_u().saturating_add(by_u);
        let new_v = self.degree_v().saturating_add(by_v);
        self.change_degree_with_tolerance(new_u, new_v, 0.0)
    }

    /// Changes the degrees to `(new_u, new_v)` with the default tolerance
    /// [`DEFAULT_DEGREE_TOLERANCE`]; see [`BSplineSurface::change_degree_with_tolerance`].
    ///
    /// # Errors
    /// As [`BSplineSurface::change_degree_with_tolerance`].
    pub fn change_degree(&self, new_u: usize, new_v: usize) -> Result<BSplineSurface> {
        self.change_degree_with_tolerance(new_u, new_v, DEFAULT_DEGREE_TOLERANCE)
    }

    /// Changes the degrees from `(p, q)` to `(new_u, new_v)` without changing the surface: the
    /// tensor-product form of document 004 eq. 14 on B-splines. Along `u` the rows of the net are
    /// the control points of one B-spline curve of dimension `nv·dim` on the `u` knots, whose
    /// degree is changed per Bezier piece by [`BSplineCurve::change_degree_with_tolerance`];
    /// then the same along `v` on the transposed net. Lowering is exact and refused (naming the
    /// direction and the largest real degree of its pieces) when a piece has no sufficient
    /// defect; `tolerance` is relative to the largest absolute coordinate of the net. As for
    /// curves, the new knot vectors have every interior breakpoint with multiplicity equal to
    /// the new degree.
    ///
    /// # Errors
    /// [`Error::DegreeReductionRefused`] with `direction` "u direction" or "v direction";
    /// [`Error::InvalidArgument`] for a bad tolerance; [`Error::TooLarge`].
    pub fn change_degree_with_tolerance(
        &self,
        new_u: usize,
        new_v: usize,
        tolerance: f64,
    ) -> Result<BSplineSurface> {
        let nv = self.net_size().1;
        let dim = self.dim();
        let rows = BSplineCurve::from_knot_vector(
            self.degree_u(),
            self.knots_u().clone(),
            Points::from_raw(self.control_points().as_slice().to_vec(), nv * dim),
        )?;
        let (pu, knots_u, rows) = rows
            .change_degree_with_tolerance(new_u, tolerance)
            .map_err(|e| in_direction(e, "u direction"))?
            .into_parts();
        let nu_new = rows.len();
        let cols = BSplineCurve::from_knot_vector(
            self.degree_v(),
            self.knots_v().clone(),
            Points::from_raw(transpose(rows.as_slice(), nu_new, nv, dim), nu_new * dim),
        )?;
        let (pv, knots_v, cols) = cols
            .change_degree_with_tolerance(new_v, tolerance)
            .map_err(|e| in_direction(e, "v direction"))?
            .into_parts();
        let nv_new = cols.len();
        let net = Points::from_raw(transpose(cols.as_slice(), nv_new, nu_new, dim), dim);
        BSplineSurface::from_knot_vectors(pu, pv, knots_u, knots_v, net, (nu_new, nv_new))
    }
}

/// The blossom of the Bezier piece with control points `net` (point-major, `args.len() + 1`
/// points) over `[lo, hi]` at `args`, left in the first point of `net`: de Casteljau's algorithm
/// with parameter `args[l]` at level `l` (Ramshaw 1989; P&T §3.3 for the one-parameter case).
/// The weights `(x − lo)/(hi − lo)` and `(hi − x)/(hi − lo)` are formed separately, so that an
/// argument at an end of the interval picks a point exactly.
fn blossom_in_place(net: &mut [f64], dim: usize, args: &[f64], lo: f64, hi: f64) {
    let h = hi - lo;
    let q = args.len();
    for (l, &x) in args.iter().enumerate() {
        let (w0, w1) = ((hi - x) / h, (x - lo) / h);
        for j in 0..q - l {
            for c in 0..dim {
                net[j * dim + c] = w0 * net[j * dim + c] + w1 * net[(j + 1) * dim + c];
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn elevation_gives_the_minimal_knot_vector_of_a5_9() {
        let c = curve();
        for by in 1..=3 {
            let e = c.elevate_degree(by).unwrap();
            // interior knot 1 (simple) → 1 + by copies, knot 2 (double) → 2 + by copies
            assert_eq!(e.knots().multiplicity(1.0), 1 + by, "by = {by}");
            assert_eq!(e.knots().multiplicity(2.0), 2 + by, "by = {by}");
            assert_eq!(e.control_points().len(), c.control_points().len() + by * 3);
            let scale = c.control_points().max_abs();
            let (a, b) = c.domain();
            for k in 0..=60 {
                let t = a + (b - a) * f64::from(k) / 60.0;
                let (p, q) = (c.eval(t).unwrap(), e.eval(t).unwrap());
                for d in 0..3 {
                    assert!((p[d] - q[d]).abs() <= 1e-13 * scale, "t = {t}, by = {by}");
                }
            }
        }
    }

    fn curve() -> BSplineCurve {
        // cubic, interior knots 1 (simple) and 2 (double): C2 at 1, C1 at 2
        let ctrl = Points::from_3d(&[
            [0.0, 0.0, 0.0],
            [1.0, 2.0, -1.0],
            [2.5, 3.0, 0.5],
            [4.0, 1.0, 2.0],
            [5.0, -1.0, 1.0],
            [6.5, 0.5, -0.5],
            [8.0, 2.0, 0.0],
        ])
        .unwrap();
        let knots = vec![0., 0., 0., 0., 1., 2., 2., 3., 3., 3., 3.];
        BSplineCurve::new(3, knots, ctrl).unwrap()
    }

    fn dev(a: &BSplineCurve, b: &BSplineCurve) -> f64 {
        (0..=300)
            .map(|k| {
                let t = 3.0 * f64::from(k) / 300.0;
                let (pa, pb) = (a.eval(t).unwrap(), b.eval(t).unwrap());
                pa.iter()
                    .zip(&pb)
                    .fold(0.0_f64, |m, (x, y)| m.max((x - y).abs()))
            })
            .fold(0.0, f64::max)
    }

    #[test]
    fn elevation_and_exact_reduction() {
        let c = curve();
        for by in 1..=4 {
            let e = c.elevate_degree(by).unwrap();
            assert_eq!(e.degree(), 3 + by, "degree");
            assert!(dev(&c, &e) < 1e-14 * 8.0, "elevation by {by}");
            let back = e.change_degree(3).unwrap();
            assert!(dev(&c, &back) < 1e-12 * 8.0, "reduction after {by}");
            assert_eq!(
                e.change_degree(2).unwrap_err(),
                Error::DegreeReductionRefused {
                    requested: 2,
                    real_degree: 3,
                    direction: "curve"
                }
            );
        }
        assert!(matches!(
            c.change_degree_with_tolerance(2, -1.0),
            Err(Error::InvalidArgument { .. })
        ));
    }

    #[test]
    fn surface_degree_change() {
        use crate::KnotVector;
        let net = Points::from_flat(
            2,
            (0..5 * 4 * 2)
                .map(|k| (f64::from(k) * 12.9898).sin() * 3.0)
                .collect(),
        )
        .unwrap();
        let ku = KnotVector::new(vec![0., 0., 0., 0.4, 0.4, 1., 1., 1.]).unwrap();
        let kv = KnotVector::new(vec![0., 0., 0., 0.5, 1., 1., 1.]).unwrap();
        let s = BSplineSurface::from_knot_vectors(2, 2, ku, kv, net, (5, 4)).unwrap();
        let e = s.elevate_degree(2, 1).unwrap();
        assert_eq!((e.degree_u(), e.degree_v()), (4, 3));
        let back = e.change_degree(2, 2).unwrap();
        for (u, v) in [(0.0, 0.0), (0.2, 0.7), (0.4, 0.5), (0.9, 1.0)] {
            let a = s.eval(u, v).unwrap();
            for other in [&e, &back] {
                let b = other.eval(u, v).unwrap();
                for (x, y) in a.iter().zip(&b) {
                    assert!((x - y).abs() < 1e-12 * 3.0, "({u}, {v})");
                }
            }
        }
        assert_eq!(
            e.change_degree(4, 1).unwrap_err(),
            Error::DegreeReductionRefused {
                requested: 1,
                real_degree: 2,
                direction: "v direction"
            }
        );
        assert_eq!(
            e.change_degree(1, 3).unwrap_err(),
            Error::DegreeReductionRefused {
                requested: 1,
                real_degree: 2,
                direction: "u direction"
            }
        );
    }

    #[test]
    fn approximate_reduction_keeps_tangents() {
        let c = curve();
        let r = c.reduce_degree_approx(2, EndConditions::Tangents);
        // a quadratic piece cannot keep two end tangents
        assert!(matches!(r, Err(Error::Degree { degree: 2, .. })));
        let e = c.elevate_degree(2).unwrap(); // degree 5
        let noisy = {
            let (p, knots, ctrl) = e.into_parts();
            let mut data = ctrl.into_vec();
            data[7] += 0.01; // breaks the degree defect of one piece
            BSplineCurve::from_knot_vector(p, knots, Points::from_flat(3, data).unwrap()).unwrap()
        };
        assert!(matches!(
            noisy.change_degree(3),
            Err(Error::DegreeReductionRefused { .. })
        ));
        let r = noisy
            .reduce_degree_approx(3, EndConditions::Tangents)
            .unwrap();
        assert!(
            r.max_deviation_bound < 0.01,
            "small: {}",
            r.max_deviation_bound
        );
        assert!(
            dev(&noisy, &r.curve) <= r.max_deviation_bound * (1.0 + 1e-9),
            "bound"
        );
        for t in [1.0, 2.0] {
            let (a, b) = (
                noisy.eval_derivatives(t, 1).unwrap(),
                r.curve.eval_derivatives(t, 1).unwrap(),
            );
            for (x, y) in a.as_slice().iter().zip(b.as_slice()) {
                assert!((x - y).abs() < 1e-12, "point and tangent at {t}");
            }
        }
        assert!(matches!(
            noisy.reduce_degree_approx(3, EndConditions::Free),
            Err(Error::InvalidArgument { .. })
        ));
    }
}
