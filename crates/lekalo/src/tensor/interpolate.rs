//! Interpolation of a grid of values by a [`TensorBSpline`]: one banded collocation matrix per
//! direction, factored once, and one sweep of solves along each direction with every line of
//! the grid along it as a right-hand side. `docs/theory/tensor.md#interpolation-on-grids`.

use rayon::prelude::*;

use crate::error::{check_finite, readable, Error, NthDirection, Result};
use crate::interpolate::collocation::{
    check_condition_limit, condition_exceeded, factor_collocation, Factors,
};
use crate::interpolate::parametrization::{
    check_strictly_increasing, parametrize_into, Parametrization,
};
use crate::interpolate::{CurveInterpolation, EndCondition, KnotPlacement};
use crate::knots::KnotVector;
use crate::numeric::linalg::BandedCrout;
use crate::points::{Points, PointsRef};
use crate::tensor::spline::{check_len, check_n_vars, checked_size, TensorBSpline};
use crate::{Arg, What};

/// Numbers of grid data above which the sweeps run on the rayon pool (the lines of a sweep are
/// independent, so the result is the same bit for bit).
const PAR_SWEEP: usize = 1 << 16;

/// Global interpolation of a grid of values by a tensor-product B-spline: the `N`-variate
/// counterpart of [`CurveInterpolation`] and [`SurfaceInterpolation`](crate::SurfaceInterpolation)
/// (document 000 §5, eq. 16–18, there for `N = 2`; `docs/theory/tensor.md#interpolation-on-grids`).
///
/// The grid holds `Π_a m_a` values `q_{k_0…k_{N−1}}` (`m_a = shape[a]`), flat and point-major,
/// the first direction slowest: value `(k_0, …, k_{N−1})` at
/// `((…(k_0·m_1 + k_1)…)·m_{N−1} + k_{N−1})·dim`, as the control net. Its parameters are given
/// per direction ([`TensorInterpolation::interpolate_at`], e.g. the coordinates of a lookup
/// table, as SciPy's `RegularGridInterpolator` and `make_ndbspl` take them) or computed from the
/// values ([`TensorInterpolation::interpolate`]: for each direction the [`Parametrization`] of
/// every grid line along it, averaged over the lines, P&T §9.2.5, which for `N = 2` is exactly
/// what [`SurfaceInterpolation`](crate::SurfaceInterpolation) does). Knots per direction by
/// averaging (eq. 3) or uniform ([`TensorInterpolation::knot_placements`]).
///
/// The system is the Kronecker product `A_0 ⊗ ⋯ ⊗ A_{N−1}` of the curve collocation matrices.
/// Each `A_a` (banded, `m_a` rows) is factored once without pivoting ([`CurveInterpolation`]'s
/// machinery), then the grid is swept once per direction, the last first: the `Π_{b≠a} m_b`
/// lines along direction `a` are the columns of the right-hand side of one banded solve per
/// block. The data are centred on the first value first (affine invariance, no cancellation
/// for data far from the origin) and the value added back at the end. Cost
/// `O(Σ_a m_a·p_a²)` for the factorisations and `O(Π_a m_a·dim·Σ_a (p_a + 1))` for the
/// sweeps, in place in the result when every direction has free ends (memory: the control net,
/// `Π_a m_a·dim` numbers, and `O(Σ_a m_a·p_a)` for the factors).
///
/// For `N = 1` the interpolation is [`CurveInterpolation`] with the same options (the result is
/// its curve, bit for bit, every end condition included); for `N = 2` with free ends
/// [`TensorInterpolation::interpolate`] returns the net of [`SurfaceInterpolation`](crate::SurfaceInterpolation)
/// bit for bit (tested). For `N ≥ 2` a direction has free, natural or periodic ends (conditions
/// that hold for every grid line alike); a natural or periodic direction is swept by
/// [`CurveInterpolation::interpolate_at`] on each block of the grid, read as one curve whose
/// points are the block's columns, and gains the curve's extra control points (2 for natural
/// cubics, `p` for periodic splines, whose knots are not clamped). End derivatives would need
/// one vector per grid line and are refused.
///
/// ```
/// use lekalo::{PointsRef, TensorInterpolation};
/// // a 3-D lookup table of f(x, y, z) = x·y + z² on an uneven grid, tricubic
/// let (xs, ys, zs) = ([0.0, 0.5, 1.5, 2.0, 3.0], [0.0, 1.0, 2.0, 4.0], [-1.0, 0.0, 0.5, 1.0, 2.0]);
/// let mut values = Vec::new();
/// for &x in &xs { for &y in &ys { for &z in &zs { values.push(x * y + z * z); } } }
/// let s = TensorInterpolation::new(vec![3, 3, 3])
///     .interpolate_at(&[&xs, &ys, &zs], PointsRef::from_flat(1, &values)?)?;
/// assert_eq!(s.shape(), &[5, 4, 5]);
/// // it reproduces the table at its nodes, and the polynomial of low degree everywhere
/// assert!((s.eval(&[1.5, 2.0, 0.5])?[0] - 3.25).abs() < 1e-13);
/// assert!((s.eval(&[1.2, 3.1, 1.7])?[0] - (1.2 * 3.1 + 1.7 * 1.7)).abs() < 1e-12);
/// # Ok::<(), lekalo::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct TensorInterpolation {
    degrees: Vec<usize>,
    parametrization: Parametrization,
    knots: Option<Vec<KnotPlacement>>,
    given: Option<Vec<Option<KnotVector>>>,
    ends: Option<Vec<EndCondition>>,
    max_condition: Option<f64>,
}

impl TensorInterpolation {
    /// Interpolation of the given degrees (one per direction), chord-length parameters for
    /// [`TensorInterpolation::interpolate`], averaged knots and free ends in every direction.
    #[must_use]
    pub fn new(degrees: Vec<usize>) -> Self {
        TensorInterpolation {
            degrees,
            parametrization: Parametrization::ChordLength,
            knots: None,
            given: None,
            ends: None,
            max_condition: None,
        }
    }

    /// Sets the parametrisation of the grid lines ([`TensorInterpolation::interpolate`]).
    #[must_use]
    pub fn parametrization(mut self, parametrization: Parametrization) -> Self {
        self.parametrization = parametrization;
        self
    }

    /// Sets the knot placement of each direction (one per direction). With free ends
    /// [`KnotPlacement::Auto`] and [`KnotPlacement::Averaged`] average the parameters (eq. 3),
    /// [`KnotPlacement::Uniform`] spaces the interior knots evenly over the parameters' range
    /// (eq. 2); [`KnotPlacement::AtParameters`] is refused. A direction with natural or
    /// periodic ends (and `N = 1`) takes the placement as [`CurveInterpolation::knot_placement`]
    /// does.
    #[must_use]
    pub fn knot_placements(mut self, knots: Vec<KnotPlacement>) -> Self {
        self.knots = Some(knots);
        self
    }

    /// Sets the knot vector of each direction (one entry per direction): `Some(knots)` is taken
    /// as given, `None` placed by [`TensorInterpolation::knot_placements`]. A given knot vector
    /// goes with free ends, has `m_a + p_a + 1` knots for the `m_a` values of its direction, and
    /// the direction's parameters lie in its domain `[t_p, t_{m_a}]` and satisfy the
    /// Schoenberg–Whitney condition `t_k < u_k < t_{k+p+1}` (de Boor, *A Practical Guide to
    /// Splines*, XIII (2); equality allowed at a clamped end), which the factorisation checks.
    /// SciPy's `make_ndbspl` is this with the not-a-knot knots of every direction (de Boor
    /// XIII (12)).
    ///
    /// ```
    /// use lekalo::{KnotVector, PointsRef, TensorInterpolation};
    /// // not-a-knot in x (the knots at the interior sites but the first and last), averaged in y
    /// let (xs, ys) = ([0.0, 1.0, 2.0, 3.0, 4.0], [0.0, 0.5, 1.5, 2.0]);
    /// let mut values = Vec::new();
    /// for &x in &xs { for &y in &ys { values.push(x * x * x - y * y); } }
    /// let t = KnotVector::new(vec![0.0, 0.0, 0.0, 0.0, 2.0, 4.0, 4.0, 4.0, 4.0])?;
    /// let s = TensorInterpolation::new(vec![3, 3])
    ///     .knot_vectors(vec![Some(t.clone()), None])
    ///     .interpolate_at(&[&xs, &ys], PointsRef::from_flat(1, &values)?)?;
    /// assert_eq!(s.knots()[0], t);
    /// assert!((s.eval(&[2.5, 1.0])?[0] - (2.5f64.powi(3) - 1.0)).abs() < 1e-12);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    #[must_use]
    pub fn knot_vectors(mut self, knots: Vec<Option<KnotVector>>) -> Self {
        self.given = Some(knots);
        self
    }

    /// Sets the end conditions of each direction (one per direction). Every
    /// [`EndCondition`] of [`CurveInterpolation`] for `N = 1`; [`EndCondition::Free`],
    /// [`EndCondition::Natural`] (cubic) and [`EndCondition::Periodic`] for `N ≥ 2`. A periodic
    /// direction's grid does not repeat its first line: the return to it is implied (its
    /// parameters, given to [`TensorInterpolation::interpolate_at`], have one entry more than
    /// its values, the last for the return).
    #[must_use]
    pub fn end_conditions(mut self, ends: Vec<EndCondition>) -> Self {
        self.ends = Some(ends);
        self
    }

    /// Refuses, with [`Error::IllConditioned`], a system whose 1-norm condition number is
    /// estimated above `limit` (a number ≥ 1, e.g. `1e8`). The system is the Kronecker product
    /// of the directions' collocation matrices and `κ_1(A_0 ⊗ ⋯ ⊗ A_{N−1}) = Π_a κ_1(A_a)`
    /// (Horn & Johnson, *Topics in Matrix Analysis*, §4.2), so the estimate is the product of
    /// the directions' estimates (Higham's refinement of Hager's method, as
    /// [`SurfaceInterpolation::max_condition`](crate::SurfaceInterpolation::max_condition)). The
    /// spline, when there is one, is the same bit for bit as without the limit. For `N = 1` it
    /// is [`CurveInterpolation::max_condition`]; for `N ≥ 2` only grids whose directions all have
    /// free ends take a limit.
    ///
    /// ```
    /// use lekalo::{Error, PointsRef, TensorInterpolation};
    /// // two coordinates of the first direction nearly coincide
    /// let xs = [0.0, 1.0, 2.0, 2.0 + 1e-10, 3.0, 4.0];
    /// let (ys, zs) = ([0.0, 1.0, 2.0], [0.0, 1.0]);
    /// let values: Vec<f64> = (0..6 * 3 * 2).map(|k| f64::from(k).sin()).collect();
    /// let q = PointsRef::from_flat(1, &values)?;
    /// let strict = TensorInterpolation::new(vec![3, 2, 1]).max_condition(1e8);
    /// let e = strict.interpolate_at(&[&xs, &ys, &zs], q).unwrap_err();
    /// assert!(matches!(e, Error::IllConditioned { .. }));
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    #[must_use]
    pub fn max_condition(mut self, limit: f64) -> Self {
        self.max_condition = Some(limit);
        self
    }

    /// The spline through the grid `values` (`Π_a shape[a]` values, see the type's
    /// documentation) at parameters computed from the values by the
    /// [`TensorInterpolation::parametrization`], averaged over the grid lines
    /// ([`TensorInterpolation::grid_parameters`]).
    ///
    /// ```
    /// use lekalo::{Parametrization, Points, SurfaceInterpolation, TensorInterpolation};
    /// // the 2-variate case is the surface interpolation, bit for bit
    /// let mut data = Vec::new();
    /// for k in 0..5 { for l in 0..4 { let (x, y) = (f64::from(k), f64::from(l * l)); data.extend([x, y, (x + y).sin()]); } }
    /// let grid = Points::from_flat(3, data)?;
    /// let s = SurfaceInterpolation::new(3, 2).interpolate(grid.as_view(), 5, 4)?;
    /// let t = TensorInterpolation::new(vec![3, 2]).interpolate(grid.as_view(), &[5, 4])?;
    /// assert_eq!(t.to_surface()?, s);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// - [`Error::TooFew`] for zero directions or a direction with fewer than 2 values;
    /// - [`Error::LengthMismatch`] if `degrees`, the knot placements or the end conditions do
    ///   not have one entry per direction, or if `values` does not hold `Π_a shape[a]` values;
    /// - [`Error::TooLarge`] if `Π_a shape[a]·dim` overflows or exceeds
    ///   [`MAX_SCALARS`](crate::MAX_SCALARS) (before anything is allocated);
    /// - [`Error::Degree`] if a degree is 0 or not below its direction's number of values
    ///   (free ends; the curve interpolation's rules for natural and periodic ends);
    /// - [`Error::CoincidentPoints`] (flat value indices) / [`Error::InvalidArgument`] for
    ///   parameters that do not increase along a line; [`Error::InvalidArgument`] for an
    ///   unsupported knot placement or end condition (end derivatives for `N ≥ 2`), for a
    ///   condition limit that is NaN or below 1, or one set with natural or periodic ends;
    /// - [`Error::SingularSystem`] / [`Error::IllConditioned`] from the solves (also when a
    ///   control point overflows, or the condition estimate exceeds
    ///   [`TensorInterpolation::max_condition`]);
    /// - for `N = 1`, the errors of [`CurveInterpolation::interpolate`].
    pub fn interpolate(&self, values: PointsRef<'_>, shape: &[usize]) -> Result<TensorBSpline> {
        self.check_options(shape.len())?;
        check_grid(values, shape)?;
        if shape.len() == 1 {
            let curve = self.curve()?.interpolate(values)?;
            return Ok(TensorBSpline::from_curve(&curve));
        }
        self.check_directions(shape)?;
        let params = self.params_of(values, shape)?;
        self.solve(values, shape, &params)
    }

    /// The spline through the grid `values` at the given parameters: `params[a]` holds the
    /// `shape[a]` strictly increasing coordinates of direction `a` (e.g. the axes of a lookup
    /// table). The spline passes through value `(k_0, …)` at `(params[0][k_0], …)`.
    ///
    /// # Errors
    /// As [`TensorInterpolation::interpolate`], except the parametrisation's; besides
    /// [`Error::NonFinite`] for a coordinate that is NaN or infinite (the values are finite
    /// by construction of [`PointsRef`]), [`Error::NotIncreasing`]
    /// for a coordinate below its predecessor and [`Error::Repeated`] for a repeated
    /// coordinate; for `N = 1` the errors of [`CurveInterpolation::interpolate_at`].
    pub fn interpolate_at(
        &self,
        params: &[&[f64]],
        values: PointsRef<'_>,
    ) -> Result<TensorBSpline> {
        self.check_options(params.len())?;
        if params.len() == 1 && self.given_knots(0).is_none() {
            let curve = self.curve()?.interpolate_at(values, params[0])?;
            return Ok(TensorBSpline::from_curve(&curve));
        }
        // a periodic direction has one parameter more than values (the return to the first)
        let shape: Vec<usize> = params
            .iter()
            .enumerate()
            .map(|(a, p)| p.len().saturating_sub(usize::from(self.is_periodic(a))))
            .collect();
        check_grid(values, &shape)?;
        self.check_directions(&shape)?;
        for p in params {
            check_strictly_increasing(p)?;
        }
        let params: Vec<Vec<f64>> = params.iter().map(|p| p.to_vec()).collect();
        self.solve(values, &shape, &params)
    }

    /// The parameters [`TensorInterpolation::interpolate`] gives the grid: for direction `a`,
    /// the [`Parametrization`] of every line of the grid along `a`, summed in the order of the
    /// lines (the first direction slowest) and divided by their number, the ends pinned to
    /// 0 and 1; a periodic direction's lines are closed (one parameter more, for the return to
    /// the first value). `O(Π_a m_a·dim·N)`.
    ///
    /// # Errors
    /// As [`TensorInterpolation::interpolate`] for the shape and the values; the
    /// parametrisation's errors.
    pub fn grid_parameters(&self, values: PointsRef<'_>, shape: &[usize]) -> Result<Vec<Vec<f64>>> {
        self.check_options(shape.len())?;
        check_grid(values, shape)?;
        for (a, &m) in shape.iter().enumerate() {
            check_count(a, m)?;
        }
        self.params_of(values, shape)
    }

    fn params_of(&self, values: PointsRef<'_>, shape: &[usize]) -> Result<Vec<Vec<f64>>> {
        let e = self.parametrization.exponent()?;
        let dim = values.dim();
        let data = values.as_slice();
        let mut all = Vec::with_capacity(shape.len());
        for a in 0..shape.len() {
            let m = shape[a];
            let outer: usize = shape[..a].iter().product();
            let inner: usize = shape[a + 1..].iter().product();
            // a periodic direction's lines are closed: one step more, back to the first value
            let steps = m - 1 + usize::from(self.is_periodic(a));
            let mut params = vec![0.0; steps + 1];
            let mut tmp = vec![0.0; steps + 1];
            // lines in the order of the grid: outer index slowest, then inner
            for o in 0..outer {
                for i in 0..inner {
                    let index = |k: usize| (o * m + k % m) * inner + i;
                    parametrize_into(
                        steps,
                        |k| &data[index(k) * dim..(index(k) + 1) * dim],
                        e,
                        |k| (index(k), index(k + 1)),
                        &mut tmp,
                    )?;
                    for (s, t) in params.iter_mut().zip(&tmp) {
                        *s += t;
                    }
                }
            }
            let inv = 1.0 / (outer * inner) as f64;
            for t in params.iter_mut() {
                *t *= inv;
            }
            params[0] = 0.0;
            params[steps] = 1.0;
            check_strictly_increasing(&params)?;
            all.push(params);
        }
        Ok(all)
    }

    /// The curve interpolation of `N = 1`.
    fn curve(&self) -> Result<CurveInterpolation> {
        let mut c = CurveInterpolation::new(self.degrees[0]).parametrization(self.parametrization);
        if let Some(k) = &self.knots {
            c = c.knot_placement(k[0]);
        }
        if let Some(e) = &self.ends {
            c = c.end_condition(e[0].clone());
        }
        if let Some(limit) = self.max_condition {
            c = c.max_condition(limit);
        }
        Ok(c)
    }

    /// One degree, knot placement and end condition per direction.
    fn check_options(&self, n: usize) -> Result<()> {
        check_n_vars(n)?;
        check_len("degrees (one per grid direction)", n, self.degrees.len())?;
        if let Some(k) = &self.knots {
            check_len("knot placements (one per grid direction)", n, k.len())?;
        }
        if let Some(e) = &self.ends {
            check_len("end conditions (one per grid direction)", n, e.len())?;
        }
        if let Some(g) = &self.given {
            check_len("knot vectors (one per grid direction)", n, g.len())?;
        }
        Ok(())
    }

    /// The given knot vector of direction `a`, if any.
    fn given_knots(&self, a: usize) -> Option<&KnotVector> {
        self.given.as_ref().and_then(|g| g[a].as_ref())
    }

    /// Direction `a`'s given knots `kv` for its parameters `t` and degree `p`: their count and
    /// domain (the Schoenberg–Whitney condition is the factorisation's).
    fn check_given(a: usize, kv: &KnotVector, p: usize, t: &[f64]) -> Result<()> {
        let expected = t.len() + p + 1;
        if kv.len() != expected {
            return Err(Error::InvalidArgument {
                what: What::of(Arg::Knots, "knot vectors"),
                reason: format!(
                    "{}: {} knots for {} values of degree {p}; give {expected} \
                     (values + degree + 1)",
                    NthDirection(a),
                    kv.len(),
                    t.len()
                ),
            });
        }
        let knots = kv.as_slice();
        let (lo, hi) = (knots[p], knots[t.len()]);
        if t[0] < lo || t[t.len() - 1] > hi {
            return Err(Error::InvalidArgument {
                what: What::of(Arg::Knots, "knot vectors"),
                reason: format!(
                    "{}: the coordinates [{}, {}] leave the knots' domain [{}, {}]; give \
                     knots whose domain covers the grid",
                    NthDirection(a),
                    readable(&t[0]),
                    readable(&t[t.len() - 1]),
                    readable(&lo),
                    readable(&hi)
                ),
            });
        }
        Ok(())
    }

    /// The end condition of direction `a`.
    fn end(&self, a: usize) -> &EndCondition {
        self.ends.as_ref().map_or(&EndCondition::Free, |e| &e[a])
    }

    fn is_periodic(&self, a: usize) -> bool {
        *self.end(a) == EndCondition::Periodic
    }

    /// Counts, degrees and options of every direction, `N ≥ 2` (the curve interpolation checks
    /// the directions with natural or periodic ends).
    fn check_directions(&self, shape: &[usize]) -> Result<()> {
        for (a, (&m, &p)) in shape.iter().zip(&self.degrees).enumerate() {
            check_count(a, m)?;
            match self.end(a) {
                EndCondition::Free => {
                    if p == 0 || p >= m {
                        return Err(Error::Degree {
                            degree: p,
                            reason: format!(
                                "the {} has {m} values and takes a degree from 1 to {}",
                                NthDirection(a),
                                m - 1
                            ),
                        });
                    }
                }
                EndCondition::Natural | EndCondition::Periodic => {}
                EndCondition::FirstDerivatives { .. } | EndCondition::SecondDerivatives { .. } => {
                    return Err(Error::InvalidArgument {
                        what: "end conditions".into(),
                        reason: format!(
                            "{}: prescribed end derivatives are one vector per end, but a grid \
                             of two or more directions would need one per grid line (data on \
                             the grid's faces); use Free, Natural or Periodic",
                            NthDirection(a)
                        ),
                    });
                }
            }
        }
        Ok(())
    }

    /// The knots of each direction, the factorisations and the sweeps.
    fn solve(
        &self,
        values: PointsRef<'_>,
        shape: &[usize],
        params: &[Vec<f64>],
    ) -> Result<TensorBSpline> {
        let n = shape.len();
        let all_free = (0..n).all(|a| *self.end(a) == EndCondition::Free);
        let kind = match self.max_condition {
            None => Factors::Keep,
            Some(limit) => {
                check_condition_limit(limit)?;
                if !all_free {
                    return Err(Error::InvalidArgument {
                        what: "condition limit (max_condition)".into(),
                        reason: "available for grids whose directions all have free ends; drop \
                                 max_condition with natural or periodic ends"
                            .into(),
                    });
                }
                Factors::Estimate
            }
        };
        let mut knots = Vec::with_capacity(n);
        let mut factors = Vec::with_capacity(n);
        for (a, t) in params.iter().enumerate() {
            if *self.end(a) != EndCondition::Free {
                if self.given_knots(a).is_some() {
                    return Err(Error::InvalidArgument {
                        what: What::of(Arg::Knots, "knot vectors"),
                        reason: format!(
                            "{}: given knots go with free ends; drop the knots or the natural \
                             or periodic end condition",
                            NthDirection(a)
                        ),
                    });
                }
                knots.push(None);
                factors.push(None);
                continue;
            }
            let p = self.degrees[a];
            let kv = if let Some(kv) = self.given_knots(a) {
                Self::check_given(a, kv, p, t)?;
                kv.clone()
            } else {
                self.placed_knots(a, p, t)?
            };
            factors.push(Some(factor_collocation(&kv, p, t, kind)?));
            knots.push(Some(kv));
        }
        let dim = values.dim();
        let control = if all_free {
            let lus: Vec<BandedCrout> = factors.into_iter().flatten().collect();
            if let Some(limit) = self.max_condition {
                let kappa: f64 = lus
                    .iter()
                    .map(|lu| lu.condition_estimate().unwrap_or(1.0))
                    .product();
                // an infinite estimate exceeds every limit
                if kappa > limit {
                    return Err(condition_exceeded(kappa, limit));
                }
            }
            solve_sweeps(values.as_slice(), shape, dim, &lus)?
        } else {
            self.solve_mixed(values, shape, params, &factors, &mut knots)?
        };
        Ok(TensorBSpline::from_raw(
            self.degrees.clone(),
            knots.into_iter().flatten().collect(),
            Points::from_raw(control, dim),
        ))
    }

    /// The knots of free direction `a` by its [`KnotPlacement`].
    fn placed_knots(&self, a: usize, p: usize, t: &[f64]) -> Result<KnotVector> {
        let kv = match self.placement(a) {
            KnotPlacement::Auto | KnotPlacement::Averaged => KnotVector::averaged(t, p)?,
            KnotPlacement::Uniform => {
                let u = KnotVector::clamped_uniform(p, t.len())?;
                let (lo, hi) = (t[0], t[t.len() - 1]);
                KnotVector::new(u.as_slice().iter().map(|x| lo + (hi - lo) * x).collect())?
            }
            KnotPlacement::AtParameters => {
                return Err(Error::InvalidArgument {
                    what: "knot placements".into(),
                    reason: format!(
                        "{}: knots at the parameters go with end derivatives or natural ends; \
                         use Averaged or Uniform with free ends",
                        NthDirection(a)
                    ),
                })
            }
        };
        Ok(kv)
    }

    fn placement(&self, a: usize) -> KnotPlacement {
        self.knots.as_ref().map_or(KnotPlacement::Auto, |k| k[a])
    }

    /// The sweeps when some directions have natural or periodic ends: those directions are
    /// swept by [`CurveInterpolation::interpolate_at`] on each block of the grid, read as one
    /// curve whose points are the block's columns (the end conditions hold for every column;
    /// the direction grows to the curve's number of control points); the free ones as in
    /// [`solve_sweeps`]. The knots of the swept directions are filled in.
    fn solve_mixed(
        &self,
        values: PointsRef<'_>,
        shape: &[usize],
        params: &[Vec<f64>],
        factors: &[Option<BandedCrout>],
        knots: &mut [Option<KnotVector>],
    ) -> Result<Vec<f64>> {
        let dim = values.dim();
        let data = values.as_slice();
        let reference = &data[..dim];
        let mut grid = Vec::with_capacity(data.len());
        for q in data.chunks_exact(dim) {
            grid.extend(q.iter().zip(reference).map(|(x, r)| x - r));
        }
        let mut shape = shape.to_vec();
        for a in (0..shape.len()).rev() {
            let inner = shape[a + 1..].iter().product::<usize>() * dim;
            let m = shape[a];
            if let Some(lu) = &factors[a] {
                for b in grid.chunks_exact_mut(m * inner) {
                    lu.solve(b, inner);
                }
                continue;
            }
            let fit = CurveInterpolation::new(self.degrees[a])
                .knot_placement(self.placement(a))
                .end_condition(self.end(a).clone());
            let outer = grid.len() / (m * inner);
            let mut next = Vec::new();
            for block in grid.chunks_exact(m * inner) {
                let curve = fit.interpolate_at(PointsRef::from_flat(inner, block)?, &params[a])?;
                next.extend_from_slice(curve.control_points().as_slice());
                if knots[a].is_none() {
                    knots[a] = Some(curve.knots().clone());
                }
            }
            shape[a] = next.len() / (outer * inner);
            checked_size("control net (product of the net sizes × dim)", &shape, dim)?;
            grid = next;
        }
        uncentre(&mut grid, reference)?;
        Ok(grid)
    }
}

/// A direction needs 2 values at least.
fn check_count(a: usize, m: usize) -> Result<()> {
    if m < 2 {
        return Err(Error::TooFew {
            what: if a == 0 {
                "grid values in the 1st direction".into()
            } else {
                "grid values in a direction (each needs 2)".into()
            },
            min: 2,
            got: m,
        });
    }
    Ok(())
}

/// The size of the grid against its shape (checked multiplication first). The values are
/// finite: [`PointsRef`] is validated when it is made.
fn check_grid(values: PointsRef<'_>, shape: &[usize]) -> Result<()> {
    let count = checked_size("grid values (product of the shape)", shape, 1)?;
    checked_size(
        "control net (product of the shape × dim)",
        shape,
        values.dim(),
    )?;
    if values.len() != count {
        return Err(Error::LengthMismatch {
            what: "grid values (product of the shape)".into(),
            expected: count,
            got: values.len(),
        });
    }
    Ok(())
}

/// The control net `P = (A_0⁻¹ ⊗ ⋯ ⊗ A_{N−1}⁻¹)(Q − q_0) + q_0`: the data centred on the first
/// value, one sweep per direction from the last to the first, each solving the
/// `outer = Π_{b<a} m_b` blocks of `m_a` rows and `Π_{b>a} m_b·dim` columns with the kept factors
/// ([`BandedCrout::solve`]), then `q_0` added back. For `N = 2` these are the operations of
/// the surface interpolation's fused two-sweep solve on each number, in the same order per
/// number: the same bits.
///
/// # Errors
/// [`Error::IllConditioned`] if a control-net number overflows.
fn solve_sweeps(
    data: &[f64],
    shape: &[usize],
    dim: usize,
    lus: &[BandedCrout],
) -> Result<Vec<f64>> {
    let reference = &data[..dim];
    let mut control = crate::numeric::large_buffer::with_capacity(data.len());
    if let [r] = *reference {
        // scalar values: one pass the compiler vectorises (the same subtractions)
        control.extend(data.iter().map(|x| x - r));
    } else {
        for q in data.chunks_exact(dim) {
            control.extend(q.iter().zip(reference).map(|(x, r)| x - r));
        }
    }
    for a in (0..shape.len()).rev() {
        let inner = shape[a + 1..].iter().product::<usize>() * dim;
        let block = shape[a] * inner;
        let lu = &lus[a];
        if control.len() >= PAR_SWEEP {
            control
                .par_chunks_mut(block)
                .for_each(|b| lu.solve(b, inner));
        } else {
            for b in control.chunks_exact_mut(block) {
                lu.solve(b, inner);
            }
        }
    }
    uncentre(&mut control, reference)?;
    Ok(control)
}

/// Adds the reference value back to every point of the net.
///
/// # Errors
/// [`Error::IllConditioned`] if a control-net number overflowed.
fn uncentre(control: &mut [f64], reference: &[f64]) -> Result<()> {
    if let [r] = *reference {
        control.iter_mut().for_each(|x| *x += r);
    } else {
        for c in control.chunks_exact_mut(reference.len()) {
            for (x, r) in c.iter_mut().zip(reference) {
                *x += r;
            }
        }
    }
    // check_finite's vectorised pass, the search for the index only when a number overflowed
    if let Err(Error::NonFinite { index: i, .. }) = check_finite("control net", control) {
        return Err(Error::IllConditioned {
            reason: format!(
                "control net coordinate {i} overflowed to {:e}: the grid's values are too close \
                 to the largest f64 (or differ by more than it); rescale the data",
                control[i]
            ),
        });
    }
    Ok(())
}
