//! Tensor-product B-spline surfaces `S(u, v) = Σ_i Σ_j N_{i,p}(u) N_{j,q}(v) P_{i,j}`
//! (P&T §3.4), of any dimension.
//!
//! Conventions, stated once for all surfaces ([`BSplineSurface`], [`crate::NurbsSurface`],
//! [`crate::BezierSurface`]):
//! - The control net of `nu × nv` points is stored flat and point-major, `i` along `u`:
//!   point `P_{i,j}` is `data[(i·nv + j)·dim ..][..dim]` ([`Points`], `net_size = (nu, nv)`).
//! - Knot conventions per direction are those of [`crate::knots`]: domain `[u_p, u_{nu}]`,
//!   half-open spans, the right end evaluated by the last non-empty span. Derivatives at an
//!   interior knot are right-hand ones.
//! - Partial derivatives come as a square table: [`BSplineSurface::eval_derivatives`] with
//!   `order = d` returns `(d + 1)²` points, point `k·(d + 1) + l` being
//!   `S_{u^k v^l} = ∂^{k+l} S / ∂u^k ∂v^l` for `0 ≤ k, l ≤ d`.
//! - Batch evaluation writes into a caller buffer, reusing one scratch space.
//!
//! This file holds the surface, its validation and its evaluation; `bspline/derivatives.rs`
//! its partial derivatives and normals.

mod derivatives;

use serde::{Deserialize, Serialize};

use crate::basis::{basis_funs_into, BasisScratch};
use crate::curve::bspline::BSplineCurve;
use crate::error::{Error, Result, MAX_SCALARS};
use crate::knots::KnotVector;
use crate::numeric::progress::Progress;
use crate::points::Points;
use crate::surface::Direction;
pub(crate) use derivatives::{check_normal_dim, unit_normal};

/// A tensor-product B-spline surface of degrees `(p, q)` on knot vectors `U` (`nu + p + 1`
/// knots) and `V` (`nv + q + 1` knots) with an `nu × nv` control net.
///
/// ```
/// use lekalo::{BSplineSurface, Points};
/// // the bilinear patch through four corners: S(u, v) = (u, v, u·v)
/// let net = Points::from_3d(&[[0.0, 0.0, 0.0], [0.0, 1.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 1.0]])?;
/// let s = BSplineSurface::new(1, 1, vec![0.0, 0.0, 1.0, 1.0], vec![0.0, 0.0, 1.0, 1.0], net, (2, 2))?;
/// assert_eq!(s.eval(0.5, 0.25)?, vec![0.5, 0.25, 0.125]);
/// # Ok::<(), lekalo::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "BSplineSurfaceRepr", into = "BSplineSurfaceRepr")]
pub struct BSplineSurface {
    degree_u: usize,
    degree_v: usize,
    knots_u: KnotVector,
    knots_v: KnotVector,
    control: Points,
}

#[derive(Serialize, Deserialize)]
struct BSplineSurfaceRepr {
    degree_u: usize,
    degree_v: usize,
    knots_u: Vec<f64>,
    knots_v: Vec<f64>,
    net_size: (usize, usize),
    control: Points,
}

impl TryFrom<BSplineSurfaceRepr> for BSplineSurface {
    type Error = Error;
    fn try_from(r: BSplineSurfaceRepr) -> Result<Self> {
        BSplineSurface::new(
            r.degree_u, r.degree_v, r.knots_u, r.knots_v, r.control, r.net_size,
        )
    }
}

impl From<BSplineSurface> for BSplineSurfaceRepr {
    fn from(s: BSplineSurface) -> Self {
        let net_size = s.net_size();
        BSplineSurfaceRepr {
            degree_u: s.degree_u,
            degree_v: s.degree_v,
            knots_u: s.knots_u.into_vec(),
            knots_v: s.knots_v.into_vec(),
            net_size,
            control: s.control,
        }
    }
}

/// Scratch space for surface evaluation: basis values in both directions and one point.
#[derive(Debug, Clone)]
pub(crate) struct SurfaceScratch {
    basis_u: BasisScratch,
    basis_v: BasisScratch,
    nu: Vec<f64>,
    nv: Vec<f64>,
    tmp: Vec<f64>,
}

impl SurfaceScratch {
    pub(crate) fn new(degree_u: usize, degree_v: usize, dim: usize) -> Self {
        SurfaceScratch {
            basis_u: BasisScratch::new(degree_u),
            basis_v: BasisScratch::new(degree_v),
            nu: vec![0.0; degree_u + 1],
            nv: vec![0.0; degree_v + 1],
            tmp: vec![0.0; dim],
        }
    }
}

/// Checks the net size against the number of control points; returns `nu · nv`.
///
/// # Errors
/// [`Error::TooFew`] for an empty direction; [`Error::TooLarge`] if `nu · nv` overflows;
/// [`Error::LengthMismatch`] if `control.len() != nu · nv`.
pub(crate) fn check_net(control: &Points, (nu, nv): (usize, usize)) -> Result<usize> {
    for (n, what) in [
        (nu, "rows of the control net (u direction)"),
        (nv, "columns of the control net (v direction)"),
    ] {
        if n == 0 {
            return Err(Error::TooFew {
                what: what.into(),
                min: 1,
                got: 0,
            });
        }
    }
    let count = nu
        .checked_mul(nv)
        .filter(|&c| c <= MAX_SCALARS)
        .ok_or(Error::TooLarge {
            what: "control net (rows × columns)".into(),
            size: nu.saturating_mul(nv),
            max: MAX_SCALARS,
        })?;
    if control.len() != count {
        return Err(Error::LengthMismatch {
            what: "control points (rows × columns of the net)".into(),
            expected: count,
            got: control.len(),
        });
    }
    Ok(count)
}

/// Validates a knot vector for one direction of a surface with `n` control points in that
/// direction, with errors that name the direction.
fn check_direction(knots: &KnotVector, degree: usize, n: usize, dir: Direction) -> Result<()> {
    if n <= degree {
        return Err(Error::Degree {
            degree,
            reason: format!(
                "{}: {n} control points in this direction ({}) carry a degree of at most {}",
                dir.name(),
                dir.net(),
                n.saturating_sub(1)
            ),
        });
    }
    // n > degree, so only the sum can overflow (and then cannot match any length)
    let expected = n.saturating_add(degree).saturating_add(1);
    if knots.len() != expected {
        return Err(Error::LengthMismatch {
            what: dir.knot_count().into(),
            expected,
            got: knots.len(),
        });
    }
    knots.validate_for(degree, n)
}

// the names of a direction in the constructor's error messages
impl Direction {
    fn name(self) -> &'static str {
        match self {
            Direction::U => "u direction",
            Direction::V => "v direction",
        }
    }
    fn net(self) -> &'static str {
        match self {
            Direction::U => "rows of the net",
            Direction::V => "columns of the net",
        }
    }
    fn knot_count(self) -> &'static str {
        match self {
            Direction::U => "knots in u (rows of the net + u degree + 1)",
            Direction::V => "knots in v (columns of the net + v degree + 1)",
        }
    }
    fn knots(self) -> &'static str {
        match self {
            Direction::U => "knots_u",
            Direction::V => "knots_v",
        }
    }
}

/// Renames the `what` of a knot-vector error to the direction's knot vector.
fn name_knots(e: Error, dir: Direction) -> Error {
    match e {
        Error::NonFinite { index, value, .. } => Error::NonFinite {
            what: dir.knots().into(),
            index,
            value,
        },
        Error::TooFew { min, got, .. } => Error::TooFew {
            what: dir.knots().into(),
            min,
            got,
        },
        other => other,
    }
}

impl BSplineSurface {
    /// A B-spline surface from its degrees, knot vectors and control net (`net_size = (nu, nv)`,
    /// point `(i, j)` at index `i·nv + j` of `control`).
    ///
    /// # Errors
    /// - [`Error::TooFew`] for an empty net direction or too few knots;
    /// - [`Error::LengthMismatch`] if `control.len() != nu·nv`, or if a knot vector does not
    ///   have `nu + p + 1` (resp. `nv + q + 1`) knots (the message names `knots_u`/`knots_v`);
    /// - [`Error::Degree`] if a direction has fewer than `degree + 1` control points;
    /// - [`Error::NonFinite`], [`Error::KnotsNotSorted`], [`Error::KnotMultiplicity`],
    ///   [`Error::EmptyDomain`] for bad knots (as [`KnotVector::new`]).
    pub fn new(
        degree_u: usize,
        degree_v: usize,
        knots_u: impl Into<Vec<f64>>,
        knots_v: impl Into<Vec<f64>>,
        control: Points,
        net_size: (usize, usize),
    ) -> Result<Self> {
        check_net(&control, net_size)?;
        let knots_u = KnotVector::new(knots_u.into()).map_err(|e| name_knots(e, Direction::U))?;
        let knots_v = KnotVector::new(knots_v.into()).map_err(|e| name_knots(e, Direction::V))?;
        Self::from_knot_vectors(degree_u, degree_v, knots_u, knots_v, control, net_size)
    }

    /// As [`BSplineSurface::new`] with already validated knot vectors.
    ///
    /// ```
    /// use lekalo::{BSplineSurface, KnotVector, Points};
    /// let net = Points::from_flat(1, (0..4 * 3).map(|k| k as f64).collect())?;
    /// let s = BSplineSurface::from_knot_vectors(
    ///     2, 1, KnotVector::clamped_uniform(2, 4)?, KnotVector::clamped_uniform(1, 3)?, net, (4, 3))?;
    /// assert_eq!(s.net_size(), (4, 3));
    /// assert_eq!(s.domain(), ((0.0, 1.0), (0.0, 1.0)));
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// As [`BSplineSurface::new`].
    pub fn from_knot_vectors(
        degree_u: usize,
        degree_v: usize,
        knots_u: KnotVector,
        knots_v: KnotVector,
        control: Points,
        net_size: (usize, usize),
    ) -> Result<Self> {
        check_net(&control, net_size)?;
        check_direction(&knots_u, degree_u, net_size.0, Direction::U)?;
        check_direction(&knots_v, degree_v, net_size.1, Direction::V)?;
        Ok(BSplineSurface {
            degree_u,
            degree_v,
            knots_u,
            knots_v,
            control,
        })
    }

    /// Trusted constructor for results built inside the crate (debug-checked).
    pub(crate) fn from_raw(
        degree_u: usize,
        degree_v: usize,
        knots_u: KnotVector,
        knots_v: KnotVector,
        control: Points,
    ) -> Self {
        debug_assert_eq!(
            control.len(),
            (knots_u.len() - degree_u - 1) * (knots_v.len() - degree_v - 1),
            "raw surface counts"
        );
        BSplineSurface {
            degree_u,
            degree_v,
            knots_u,
            knots_v,
            control,
        }
    }

    /// Degrees `(p, q)` in `u` and `v` (the pair of [`BSplineCurve::degree`](crate::BSplineCurve::degree)).
    #[must_use]
    pub fn degree(&self) -> (usize, usize) {
        (self.degree_u, self.degree_v)
    }

    /// Knot vectors in `u` and `v` (the pair of [`BSplineCurve::knots`](crate::BSplineCurve::knots)).
    #[must_use]
    pub fn knots(&self) -> (&KnotVector, &KnotVector) {
        (&self.knots_u, &self.knots_v)
    }

    /// Degree `p` in `u`.
    #[must_use]
    pub fn degree_u(&self) -> usize {
        self.degree_u
    }

    /// Degree `q` in `v`.
    #[must_use]
    pub fn degree_v(&self) -> usize {
        self.degree_v
    }

    /// Knot vector in `u`.
    #[must_use]
    pub fn knots_u(&self) -> &KnotVector {
        &self.knots_u
    }

    /// Knot vector in `v`.
    #[must_use]
    pub fn knots_v(&self) -> &KnotVector {
        &self.knots_v
    }

    /// The control net, flat point-major (`(i·nv + j)` is point `P_{i,j}`).
    #[must_use]
    pub fn control_points(&self) -> &Points {
        &self.control
    }

    /// Control point `P_{i,j}`, or `None` outside the net.
    #[must_use]
    pub fn control_point(&self, i: usize, j: usize) -> Option<&[f64]> {
        let (nu, nv) = self.net_size();
        (i < nu && j < nv).then(|| self.control.point(i * nv + j))
    }

    /// Net size `(nu, nv)`, derived from the knot counts: `nu = |U| − p − 1`, `nv = |V| − q − 1`.
    #[must_use]
    pub fn net_size(&self) -> (usize, usize) {
        (
            self.knots_u.len() - self.degree_u - 1,
            self.knots_v.len() - self.degree_v - 1,
        )
    }

    /// Dimension of the points.
    #[must_use]
    pub fn dim(&self) -> usize {
        self.control.dim()
    }

    /// Parameter domain `((u_min, u_max), (v_min, v_max))`.
    #[must_use]
    pub fn domain(&self) -> ((f64, f64), (f64, f64)) {
        (
            self.knots_u.domain(self.degree_u),
            self.knots_v.domain(self.degree_v),
        )
    }

    /// Point `S(u, v)`.
    ///
    /// # Errors
    /// As [`BSplineSurface::eval_into`].
    pub fn eval(&self, u: f64, v: f64) -> Result<Vec<f64>> {
        let mut out = vec![0.0; self.dim()];
        self.eval_into(u, v, &mut out)?;
        Ok(out)
    }

    /// Point `S(u, v)` into `out` (length `dim`): the spans in both directions, the `p + 1` and
    /// `q + 1` non-zero basis functions (P&T A2.2), and the tensor combination of the
    /// `(p + 1)(q + 1)` control points involved (P&T Algorithm A3.5). O(p² + q² + p·q·dim).
    ///
    /// # Errors
    /// [`Error::ParameterOutOfDomain`] for `u` or `v` outside [`BSplineSurface::domain`] (the
    /// error carries the direction's bounds); [`Error::LengthMismatch`] if `out.len() != dim`.
    pub fn eval_into(&self, u: f64, v: f64, out: &mut [f64]) -> Result<()> {
        check_out(out.len(), self.dim())?;
        let su = self.knots_u.find_span(self.degree_u, u)?;
        let sv = self.knots_v.find_span(self.degree_v, v)?;
        let mut scratch = SurfaceScratch::new(self.degree_u, self.degree_v, self.dim());
        self.eval_span(su, sv, u, v, &mut scratch, out);
        Ok(())
    }

    /// Evaluates at known spans with caller scratch (no allocation).
    pub(crate) fn eval_span(
        &self,
        su: usize,
        sv: usize,
        u: f64,
        v: f64,
        scratch: &mut SurfaceScratch,
        out: &mut [f64],
    ) {
        let (p, q) = (self.degree_u, self.degree_v);
        basis_funs_into(
            self.knots_u.as_slice(),
            p,
            su,
            u,
            &mut scratch.basis_u,
            &mut scratch.nu,
        );
        basis_funs_into(
            self.knots_v.as_slice(),
            q,
            sv,
            v,
            &mut scratch.basis_v,
            &mut scratch.nv,
        );
        self.combine(su, sv, &scratch.nu, &scratch.nv, &mut scratch.tmp, out);
    }

    /// `out = Σ_k bu[k] Σ_l bv[l] P_{su−p+k, sv−q+l}`: the tensor combination with given basis
    /// values (rows of the net are contiguous along `v`, so the inner sum runs along memory).
    fn combine(
        &self,
        su: usize,
        sv: usize,
        bu: &[f64],
        bv: &[f64],
        tmp: &mut [f64],
        out: &mut [f64],
    ) {
        let (p, q) = (self.degree_u, self.degree_v);
        let nv = self.net_size().1;
        let dim = self.dim();
        let ctrl = self.control.as_slice();
        out.fill(0.0);
        for (k, &a) in bu.iter().enumerate() {
            tmp.fill(0.0);
            let row = (su - p + k) * nv;
            for (l, &b) in bv.iter().enumerate() {
                let base = (row + sv - q + l) * dim;
                for (t, c) in tmp.iter_mut().zip(&ctrl[base..base + dim]) {
                    *t += b * c;
                }
            }
            for (o, t) in out.iter_mut().zip(tmp.iter()) {
                *o += a * t;
            }
        }
    }

    /// Evaluates on the grid `us × vs` into `out` (`us.len() · vs.len() · dim`), point
    /// `(i, j)` = `S(us[i], vs[j])` at index `i·vs.len() + j`, like a control net. The `v` basis
    /// functions are computed once per `vs[j]` (one allocation of `vs.len()·(q + 1)` values per
    /// call), the `u` ones once per row; nothing is allocated per point.
    ///
    /// ```
    /// use lekalo::{BSplineSurface, Points};
    /// let net = Points::from_3d(&[[0.0, 0.0, 0.0], [0.0, 1.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 1.0]])?;
    /// let s = BSplineSurface::new(1, 1, vec![0.0, 0.0, 1.0, 1.0], vec![0.0, 0.0, 1.0, 1.0], net, (2, 2))?;
    /// let mut out = vec![0.0; 3 * 2 * 3];
    /// s.eval_grid(&[0.0, 0.5, 1.0], &[0.0, 1.0], &mut out)?;
    /// assert_eq!(&out[9..12], &[0.5, 1.0, 0.5]); // (u, v) = (0.5, 1)
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::LengthMismatch`] for a wrong buffer length; [`Error::ParameterOutOfDomain`] for
    /// the first parameter outside the domain (the contents of `out` are then unspecified).
    pub fn eval_grid(&self, us: &[f64], vs: &[f64], out: &mut [f64]) -> Result<()> {
        let dim = self.dim();
        check_buffer(
            out.len(),
            us.len().saturating_mul(vs.len()).saturating_mul(dim),
        )?;
        let mut chunks = out.chunks_exact_mut(dim);
        self.grid_with(us, vs, |point| {
            if let Some(o) = chunks.next() {
                o.copy_from_slice(point);
            }
        })
    }

    /// Calls `f` with `S(us[i], vs[j])` for every grid point in the order `i·vs.len() + j`; the
    /// engine of the grid evaluations of all surfaces (one allocation per call, none per point).
    pub(crate) fn grid_with(
        &self,
        us: &[f64],
        vs: &[f64],
        mut f: impl FnMut(&[f64]),
    ) -> Result<()> {
        let dim = self.dim();
        let (p, q) = (self.degree_u, self.degree_v);
        let w = q + 1;
        let mut spans_v = Vec::with_capacity(vs.len());
        let mut basis_v = vec![0.0; vs.len() * w];
        let mut scratch = SurfaceScratch::new(p, q, dim);
        let mut point = vec![0.0; dim];
        let mut cursor = self.knots_v.span_cursor(q);
        for (&v, b) in vs.iter().zip(basis_v.chunks_exact_mut(w)) {
            let sv = cursor.find(v)?;
            basis_funs_into(self.knots_v.as_slice(), q, sv, v, &mut scratch.basis_v, b);
            spans_v.push(sv);
        }
        let mut cursor = self.knots_u.span_cursor(p);
        for &u in us {
            let su = cursor.find(u)?;
            basis_funs_into(
                self.knots_u.as_slice(),
                p,
                su,
                u,
                &mut scratch.basis_u,
                &mut scratch.nu,
            );
            for (&sv, b) in spans_v.iter().zip(basis_v.chunks_exact(w)) {
                self.combine(su, sv, &scratch.nu, b, &mut scratch.tmp, &mut point);
                f(&point);
            }
        }
        Ok(())
    }

    /// Evaluates at a list of parameter pairs into `out` (`uv.len() · dim`, point-major), with
    /// one scratch space and span cursors in both directions (amortised O(1) span search when
    /// consecutive pairs are close).
    ///
    /// # Errors
    /// [`Error::LengthMismatch`] for a wrong buffer length; [`Error::ParameterOutOfDomain`] for
    /// the first pair outside the domain (the contents of `out` are then unspecified).
    pub fn eval_batch(&self, uv: &[[f64; 2]], out: &mut [f64]) -> Result<()> {
        self.eval_batch_with_progress(uv, out, &Progress::new())
    }

    /// [`BSplineSurface::eval_batch`] reporting to `progress` (`done` of `uv.len()` pairs) and
    /// stopping when it is cancelled. A point costs about `(p + 1)(q + 1)·dim` operations plus
    /// the two bases, so the hook is called about every [`Progress::STRIDE`] of them. The points
    /// are bit-for-bit those of [`BSplineSurface::eval_batch`].
    ///
    /// # Errors
    /// As [`BSplineSurface::eval_batch`]; [`Error::Cancelled`] when `progress` is cancelled.
    pub fn eval_batch_with_progress(
        &self,
        uv: &[[f64; 2]],
        out: &mut [f64],
        progress: &Progress<'_>,
    ) -> Result<()> {
        let dim = self.dim();
        check_buffer(out.len(), uv.len().saturating_mul(dim))?;
        let mut chunks = out.chunks_exact_mut(dim);
        self.batch_with(uv, progress, |point| {
            if let Some(o) = chunks.next() {
                o.copy_from_slice(point);
            }
        })
    }

    /// Calls `f` with `S(u, v)` for every pair of `uv` in order (one scratch space, span
    /// cursors in both directions; nothing allocated per point), reporting to `progress`.
    pub(crate) fn batch_with(
        &self,
        uv: &[[f64; 2]],
        progress: &Progress<'_>,
        mut f: impl FnMut(&[f64]),
    ) -> Result<()> {
        let dim = self.dim();
        let mut cu = self.knots_u.span_cursor(self.degree_u);
        let mut cv = self.knots_v.span_cursor(self.degree_v);
        let mut scratch = SurfaceScratch::new(self.degree_u, self.degree_v, dim);
        let mut point = vec![0.0; dim];
        let (wu, wv) = (self.degree_u as u64 + 1, self.degree_v as u64 + 1);
        let cost = wu
            .saturating_mul(wv)
            .saturating_mul(dim as u64)
            .saturating_add(wu * wu + wv * wv);
        progress.chunks("B-spline surface evaluation", uv, cost, |uv| {
            for &[u, v] in uv {
                let su = cu.find(u)?;
                let sv = cv.find(v)?;
                self.eval_span(su, sv, u, v, &mut scratch, &mut point);
                f(&point);
            }
            Ok(())
        })
    }

    /// The iso-parametric curve `C(u) = S(u, v)` at fixed `v`: degree `p`, knots `U`, control
    /// points `Q_i = Σ_j N_{j,q}(v) P_{i,j}` (P&T §3.4). O(nu·q·dim).
    ///
    /// # Errors
    /// [`Error::ParameterOutOfDomain`] if `v` is outside the `v` domain.
    pub fn iso_curve_u(&self, v: f64) -> Result<BSplineCurve> {
        let (nu, nv) = self.net_size();
        let (p, q) = (self.degree_u, self.degree_v);
        let dim = self.dim();
        let (sv, bv) = crate::basis::basis_functions(&self.knots_v, q, v)?;
        let ctrl = self.control.as_slice();
        let mut out = vec![0.0; nu * dim];
        for (i, o) in out.chunks_exact_mut(dim).enumerate() {
            for (l, &b) in bv.iter().enumerate() {
                let base = (i * nv + sv - q + l) * dim;
                for (x, c) in o.iter_mut().zip(&ctrl[base..base + dim]) {
                    *x += b * c;
                }
            }
        }
        BSplineCurve::from_knot_vector(p, self.knots_u.clone(), Points::from_flat(dim, out)?)
    }

    /// The iso-parametric curve `C(v) = S(u, v)` at fixed `u`: degree `q`, knots `V`, control
    /// points `Q_j = Σ_i N_{i,p}(u) P_{i,j}` (P&T §3.4). O(nv·p·dim).
    ///
    /// # Errors
    /// [`Error::ParameterOutOfDomain`] if `u` is outside the `u` domain.
    pub fn iso_curve_v(&self, u: f64) -> Result<BSplineCurve> {
        let nv = self.net_size().1;
        let (p, q) = (self.degree_u, self.degree_v);
        let dim = self.dim();
        let (su, bu) = crate::basis::basis_functions(&self.knots_u, p, u)?;
        let ctrl = self.control.as_slice();
        let mut out = vec![0.0; nv * dim];
        for (k, &b) in bu.iter().enumerate() {
            let row = &ctrl[(su - p + k) * nv * dim..(su - p + k + 1) * nv * dim];
            for (x, c) in out.iter_mut().zip(row) {
                *x += b * c;
            }
        }
        BSplineCurve::from_knot_vector(q, self.knots_v.clone(), Points::from_flat(dim, out)?)
    }
}

pub(crate) fn check_out(got: usize, dim: usize) -> Result<()> {
    if got != dim {
        return Err(Error::LengthMismatch {
            what: "output point (dimension)".into(),
            expected: dim,
            got,
        });
    }
    Ok(())
}

/// Checks `t ∈ [0, 1]` (NaN fails), the domain of Bezier surfaces.
pub(crate) fn check_unit(t: f64) -> Result<()> {
    if !(0.0..=1.0).contains(&t) {
        return Err(Error::ParameterOutOfDomain {
            t,
            min: 0.0,
            max: 1.0,
        });
    }
    Ok(())
}

pub(crate) fn check_buffer(got: usize, expected: usize) -> Result<()> {
    if got != expected {
        return Err(Error::LengthMismatch {
            what: "output buffer (number of parameter points × dimension)".into(),
            expected,
            got,
        });
    }
    Ok(())
}

#[cfg(test)]
mod tests;
