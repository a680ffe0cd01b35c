//! Knot insertion, refinement, splitting, Bezier decomposition, transposition and reversal of
//! tensor-product B-spline and NURBS surfaces.
//!
//! A `u`-direction operation acts on every column `P_{·,j}` of the net as on the control
//! points of a curve (P&T §5.2, Algorithms A5.3 and A5.5). Because the net is stored row-major
//! (`P_{i,j}` at `i·nv + j`), the rows `(P_{i,0}, …, P_{i,nv−1})` are the control points of one
//! curve of dimension `nv·dim`, and the curve algorithm of [`BSplineCurve`] runs once on it — the
//! same arithmetic as column by column. A `v`-direction operation is the `u` operation on the
//! transposed surface. NURBS surfaces apply the same operations to their homogeneous net.

use crate::curve::bspline::BSplineCurve;
use crate::error::Result;
use crate::knots::KnotVector;
use crate::points::Points;
use crate::surface::bezier::BezierSurface;
use crate::surface::bspline::BSplineSurface;
use crate::surface::nurbs::NurbsSurface;

/// A Bezier patch of a B-spline surface: its `u` interval, its `v` interval and the patch as a
/// Bezier surface on `[0, 1]²` (`S(u, v) = patch(ū, v̄)` with `ū = (u − u₀)/(u₁ − u₀)`,
/// `v̄ = (v − v₀)/(v₁ − v₀)`).
pub type BezierPatch = ((f64, f64), (f64, f64), BezierSurface);

/// A rational Bezier patch of a NURBS surface: its `u` interval, its `v` interval and the patch
/// as a NURBS surface of degrees `(p, q)` on exactly those intervals (knots
/// `[u₀^{(p+1)}, u₁^{(p+1)}]`, `[v₀^{(q+1)}, v₁^{(q+1)}]`), so it keeps the original parameters.
pub type RationalBezierPatch = ((f64, f64), (f64, f64), NurbsSurface);

/// The surface's `u` direction as one curve whose points are the rows of the net.
fn rows_as_curve(s: &BSplineSurface) -> BSplineCurve {
    let (_, nv) = s.net_size();
    BSplineCurve::from_raw(
        s.degree_u(),
        s.knots_u().as_slice().to_vec(),
        Points::from_raw(s.control_points().as_slice().to_vec(), nv * s.dim()),
    )
}

/// The surface with `u` data from `c` (rows as points) and the `v` data of `template`.
fn surface_from_rows(c: BSplineCurve, template: &BSplineSurface) -> BSplineSurface {
    let (p, knots, points) = c.into_parts();
    BSplineSurface::from_raw(
        p,
        template.degree_v(),
        knots,
        template.knots_v().clone(),
        Points::from_raw(points.into_vec(), template.dim()),
    )
}

/// Applies a curve operation to the `u` direction.
fn map_u(
    s: &BSplineSurface,
    f: impl FnOnce(&BSplineCurve) -> Result<BSplineCurve>,
) -> Result<BSplineSurface> {
    Ok(surface_from_rows(f(&rows_as_curve(s))?, s))
}

/// Applies a curve operation to the `v` direction (through the transpose).
fn map_v(
    s: &BSplineSurface,
    f: impl FnOnce(&BSplineCurve) -> Result<BSplineCurve>,
) -> Result<BSplineSurface> {
    Ok(map_u(&s.transpose(), f)?.transpose())
}

/// Transposes a row-major `nu × nv` net of `dim`-points.
fn transpose_net(data: &[f64], (nu, nv): (usize, usize), dim: usize) -> Vec<f64> {
    let mut out = Vec::with_capacity(data.len());
    for j in 0..nv {
        for i in 0..nu {
            out.extend_from_slice(&data[(i * nv + j) * dim..(i * nv + j + 1) * dim]);
        }
    }
    out
}

impl BSplineSurface {
    /// The same surface with `u` and `v` swapped: `S^T(v, u) = S(u, v)`, degrees and knot
    /// vectors exchanged and the net transposed. O(nu·nv·dim).
    ///
    /// ```
    /// use lekalo::{BSplineSurface, KnotVector, Points};
    /// let net = Points::from_flat(1, (0..4 * 3).map(|k| (k as f64).sin()).collect())?;
    /// let s = BSplineSurface::from_knot_vectors(
    ///     2, 1, KnotVector::clamped_uniform(2, 4)?, KnotVector::clamped_uniform(1, 3)?, net, (4, 3))?;
    /// let t = s.transpose();
    /// assert_eq!((t.degree_u(), t.degree_v(), t.net_size()), (1, 2, (3, 4)));
    /// assert!((t.eval(0.7, 0.2)?[0] - s.eval(0.2, 0.7)?[0]).abs() < 1e-15);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    #[must_use]
    pub fn transpose(&self) -> BSplineSurface {
        let data = transpose_net(
            self.control_points().as_slice(),
            self.net_size(),
            self.dim(),
        );
        BSplineSurface::from_raw(
            self.degree_v(),
            self.degree_u(),
            self.knots_v().clone(),
            self.knots_u().clone(),
            Points::from_raw(data, self.dim()),
        )
    }

    /// Inserts the knot `u` `times` times in the `u` direction (P&T Algorithm A5.3: Boehm's
    /// A5.1 on every column of the net). The surface is unchanged. O((nu + times·p)·nv·dim).
    ///
    /// ```
    /// use lekalo::{BSplineSurface, KnotVector, Points};
    /// let net = Points::from_flat(1, (0..4 * 3).map(|k| (k as f64).sin()).collect())?;
    /// let s = BSplineSurface::from_knot_vectors(
    ///     2, 1, KnotVector::clamped_uniform(2, 4)?, KnotVector::clamped_uniform(1, 3)?, net, (4, 3))?;
    /// let r = s.insert_knot_u(0.3, 2)?;
    /// assert_eq!(r.net_size(), (6, 3));
    /// assert!((r.eval(0.4, 0.6)?[0] - s.eval(0.4, 0.6)?[0]).abs() < 1e-15);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// As [`BSplineCurve::insert_knot`] for the `u` knots and degree.
    pub fn insert_knot_u(&self, u: f64, times: usize) -> Result<BSplineSurface> {
        map_u(self, |c| c.insert_knot(u, times))
    }

    /// Inserts the knot `v` `times` times in the `v` direction (P&T Algorithm A5.3 on every
    /// row). The surface is unchanged.
    ///
    /// # Errors
    /// As [`BSplineCurve::insert_knot`] for the `v` knots and degree.
    pub fn insert_knot_v(&self, v: f64, times: usize) -> Result<BSplineSurface> {
        map_v(self, |c| c.insert_knot(v, times))
    }

    /// Knot refinement in `u` (P&T Algorithm A5.5: A5.4 on every column): inserts all of `x`
    /// (non-decreasing, inside the `u` domain). The surface is unchanged.
    ///
    /// # Errors
    /// As [`BSplineCurve::refine_knots`] for the `u` knots and degree.
    pub fn refine_knots_u(&self, x: &[f64]) -> Result<BSplineSurface> {
        map_u(self, |c| c.refine_knots(x))
    }

    /// Knot refinement in `v` (P&T Algorithm A5.5 on every row). The surface is unchanged.
    ///
    /// # Errors
    /// As [`BSplineCurve::refine_knots`] for the `v` knots and degree.
    pub fn refine_knots_v(&self, x: &[f64]) -> Result<BSplineSurface> {
        map_v(self, |c| c.refine_knots(x))
    }

    /// Splits at `u` into the surfaces on `[u_min, u] × [v_min, v_max]` and
    /// `[u, u_max] × [v_min, v_max]` (P&T §5.3: `u` inserted up to multiplicity `p`); the
    /// pieces keep the original parameters.
    ///
    /// # Errors
    /// As [`BSplineCurve::split_at`] for the `u` domain.
    pub fn split_at_u(&self, u: f64) -> Result<(BSplineSurface, BSplineSurface)> {
        let (a, b) = rows_as_curve(self).split_at(u)?;
        Ok((surface_from_rows(a, self), surface_from_rows(b, self)))
    }

    /// Splits at `v` into the surfaces on `[u_min, u_max] × [v_min, v]` and
    /// `[u_min, u_max] × [v, v_max]`.
    ///
    /// # Errors
    /// As [`BSplineCurve::split_at`] for the `v` domain.
    pub fn split_at_v(&self, v: f64) -> Result<(BSplineSurface, BSplineSurface)> {
        let (a, b) = self.transpose().split_at_u(v)?;
        Ok((a.transpose(), b.transpose()))
    }

    /// Decomposition into Bezier patches (P&T §5.3, Algorithm A5.7: the curve decomposition
    /// A5.6 in `u` on every column, then in `v` on every row of each strip): one patch per
    /// pair of non-empty knot spans of the domain, `u`-major (all `v` patches of the first `u`
    /// span first). Each patch has `(p + 1) × (q + 1)` control points. O(nu·nv·p·q·dim).
    ///
    /// ```
    /// use lekalo::{BSplineSurface, Points};
    /// let net = Points::from_flat(1, (0..4 * 3).map(|k| (k as f64).cos()).collect())?;
    /// let s = BSplineSurface::new(2, 1, vec![0., 0., 0., 0.5, 1., 1., 1.], vec![0., 0., 0.5, 1., 1.], net, (4, 3))?;
    /// let patches = s.to_bezier_patches();
    /// assert_eq!(patches.len(), 4);
    /// let ((u0, u1), (v0, v1), patch) = &patches[1];
    /// assert_eq!(((*u0, *u1), (*v0, *v1)), ((0.0, 0.5), (0.5, 1.0)));
    /// let (a, b) = (patch.eval(0.5, 0.5)?[0], s.eval(0.25, 0.75)?[0]);
    /// assert!((a - b).abs() < 1e-15);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    #[must_use]
    pub fn to_bezier_patches(&self) -> Vec<BezierPatch> {
        let (p, q) = (self.degree_u(), self.degree_v());
        let dim = self.dim();
        let mut out = Vec::new();
        for strip in rows_as_curve(self).to_bezier_segments() {
            // the strip: (p + 1) rows of nv points; decompose it in v through its transpose
            let strip_net = strip.curve.control_points().as_slice();
            let strip_t = transpose_net(strip_net, (p + 1, self.net_size().1), dim);
            let v_curve = BSplineCurve::from_raw(
                q,
                self.knots_v().as_slice().to_vec(),
                Points::from_raw(strip_t, (p + 1) * dim),
            );
            for piece in v_curve.to_bezier_segments() {
                // piece: (q + 1) points of (p + 1)·dim, i.e. the transposed patch net
                let net =
                    transpose_net(piece.curve.control_points().as_slice(), (q + 1, p + 1), dim);
                out.push((
                    (strip.start, strip.end),
                    (piece.start, piece.end),
                    BezierSurface::from_raw(Points::from_raw(net, dim), (p + 1, q + 1)),
                ));
            }
        }
        out
    }

    /// The surface reversed in `u`: `S̃(u, v) = S(a + b − u, v)` on the same domain (see
    /// [`BSplineCurve::reverse`]).
    ///
    /// # Errors
    /// As [`BSplineCurve::reverse`] for the `u` knots.
    pub fn reverse_u(&self) -> Result<BSplineSurface> {
        map_u(self, BSplineCurve::reverse)
    }

    /// The surface reversed in `v`: `S̃(u, v) = S(u, c + d − v)` on the same domain.
    ///
    /// # Errors
    /// As [`BSplineCurve::reverse`] for the `v` knots.
    pub fn reverse_v(&self) -> Result<BSplineSurface> {
        map_v(self, BSplineCurve::reverse)
    }
}

impl NurbsSurface {
    /// Wraps a homogeneous result (weights are positive: every operation here takes convex
    /// combinations of the homogeneous points, or permutes them).
    fn wrap(h: BSplineSurface) -> NurbsSurface {
        NurbsSurface::from_homogeneous_unchecked(h)
    }

    /// The same surface with `u` and `v` swapped (see [`BSplineSurface::transpose`]).
    #[must_use]
    pub fn transpose(&self) -> NurbsSurface {
        Self::wrap(self.homogeneous().transpose())
    }

    /// Inserts `u` `times` times in the `u` direction (P&T A5.3 on the homogeneous net). The
    /// rational surface is unchanged.
    ///
    /// # Errors
    /// As [`BSplineSurface::insert_knot_u`].
    pub fn insert_knot_u(&self, u: f64, times: usize) -> Result<NurbsSurface> {
        Ok(Self::wrap(self.homogeneous().insert_knot_u(u, times)?))
    }

    /// Inserts `v` `times` times in the `v` direction (P&T A5.3 on the homogeneous net).
    ///
    /// # Errors
    /// As [`BSplineSurface::insert_knot_v`].
    pub fn insert_knot_v(&self, v: f64, times: usize) -> Result<NurbsSurface> {
        Ok(Self::wrap(self.homogeneous().insert_knot_v(v, times)?))
    }

    /// Knot refinement in `u` (P&T A5.5 on the homogeneous net).
    ///
    /// # Errors
    /// As [`BSplineSurface::refine_knots_u`].
    pub fn refine_knots_u(&self, x: &[f64]) -> Result<NurbsSurface> {
        Ok(Self::wrap(self.homogeneous().refine_knots_u(x)?))
    }

    /// Knot refinement in `v` (P&T A5.5 on the homogeneous net).
    ///
    /// # Errors
    /// As [`BSplineSurface::refine_knots_v`].
    pub fn refine_knots_v(&self, x: &[f64]) -> Result<NurbsSurface> {
        Ok(Self::wrap(self.homogeneous().refine_knots_v(x)?))
    }

    /// Splits at `u` (see [`BSplineSurface::split_at_u`]).
    ///
    /// # Errors
    /// As [`BSplineSurface::split_at_u`].
    pub fn split_at_u(&self, u: f64) -> Result<(NurbsSurface, NurbsSurface)> {
        let (a, b) = self.homogeneous().split_at_u(u)?;
        Ok((Self::wrap(a), Self::wrap(b)))
    }

    /// Splits at `v` (see [`BSplineSurface::split_at_v`]).
    ///
    /// # Errors
    /// As [`BSplineSurface::split_at_v`].
    pub fn split_at_v(&self, v: f64) -> Result<(NurbsSurface, NurbsSurface)> {
        let (a, b) = self.homogeneous().split_at_v(v)?;
        Ok((Self::wrap(a), Self::wrap(b)))
    }

    /// Decomposition into rational Bezier patches (P&T A5.7 on the homogeneous net): each a
    /// NURBS surface of degrees `(p, q)` with `(p + 1) × (q + 1)` control points on its own
    /// `u` and `v` intervals, so `patch.eval(u, v)` equals `self.eval(u, v)` there
    /// ([`RationalBezierPatch`]). `u`-major order.
    ///
    /// ```
    /// use lekalo::{NurbsSurface, Points};
    /// const H: f64 = std::f64::consts::FRAC_1_SQRT_2;
    /// let net = Points::from_3d(&[
    ///     [1.0, 0.0, 0.0], [1.0, 0.0, 2.0],
    ///     [1.0, 1.0, 0.0], [1.0, 1.0, 2.0],
    ///     [0.0, 1.0, 0.0], [0.0, 1.0, 2.0],
    /// ])?;
    /// let s = NurbsSurface::new(2, 1, vec![0., 0., 0., 1., 1., 1.], vec![0., 0., 1., 1.], net,
    ///                           vec![1.0, 1.0, H, H, 1.0, 1.0], (3, 2))?;
    /// let s = s.insert_knot_u(0.5, 1)?.insert_knot_v(0.25, 1)?;
    /// let patches = s.to_bezier_patches();
    /// assert_eq!(patches.len(), 4);
    /// let ((_, _), (_, _), patch) = &patches[3];
    /// let (a, b) = (patch.eval(0.75, 0.5)?, s.eval(0.75, 0.5)?);
    /// assert!(a.iter().zip(&b).all(|(x, y)| (x - y).abs() < 1e-15));
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    #[must_use]
    pub fn to_bezier_patches(&self) -> Vec<RationalBezierPatch> {
        let h = self.homogeneous();
        let (p, q) = (h.degree_u(), h.degree_v());
        let bezier_knots = |(a, b): (f64, f64), deg: usize| {
            let mut k = vec![a; deg + 1];
            k.extend(std::iter::repeat_n(b, deg + 1));
            KnotVector::from_raw(k)
        };
        h.to_bezier_patches()
            .into_iter()
            .map(|(ur, vr, patch)| {
                let control = patch.control_points().clone();
                let surface = BSplineSurface::from_raw(
                    p,
                    q,
                    bezier_knots(ur, p),
                    bezier_knots(vr, q),
                    control,
                );
                (ur, vr, Self::wrap(surface))
            })
            .collect()
    }

    /// The surface reversed in `u` (see [`BSplineSurface::reverse_u`]).
    ///
    /// # Errors
    /// As [`BSplineSurface::reverse_u`].
    pub fn reverse_u(&self) -> Result<NurbsSurface> {
        Ok(Self::wrap(self.homogeneous().reverse_u()?))
    }

    /// The surface reversed in `v` (see [`BSplineSurface::reverse_v`]).
    ///
    /// # Errors
    /// As [`BSplineSurface::reverse_v`].
    pub fn reverse_v(&self) -> Result<NurbsSurface> {
        Ok(Self::wrap(self.homogeneous().reverse_v()?))
    }
}
