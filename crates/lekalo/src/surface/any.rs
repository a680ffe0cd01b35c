//! [`Surface`]: one value for a tensor-product surface of any kind (Bezier, B-spline, NURBS),
//! with every shared capability delegated once; [`Direction`] names a parameter direction.
//!
//! Conventions (`docs/theory.md`, "Curves and surfaces of any kind"): a Bezier surface is the
//! B-spline surface on clamped knots over `[0, 1]²`; knot operations keep a NURBS surface
//! rational and give a polynomial surface back as a B-spline surface.

use std::borrow::Cow;

use serde::{Deserialize, Serialize};

use crate::surface::{BSplineSurface, BezierSurface, NurbsSurface};
use crate::{Curve, Error, KnotVector, Points, QuerySurface, Result};

/// A parameter direction of a surface: `u` (the first, rows of the net) or `v` (the second).
///
/// Spelled `u` and `v` in every front end (`FromStr`, `Display` by
/// [`crate::vocabulary::DIRECTION`], serde).
///
/// ```
/// use lekalo::Direction;
/// assert_eq!("v".parse::<Direction>()?, Direction::V);
/// assert_eq!(Direction::U.to_string(), "u");
/// assert!("w".parse::<Direction>().is_err());
/// # Ok::<(), lekalo::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Direction {
    /// The first parameter, `u`.
    #[default]
    U,
    /// The second parameter, `v`.
    V,
}

/// A tensor-product surface of any kind.
///
/// Serialised with its kind in a `type` field (`"bezier_surface"`, `"bspline_surface"`,
/// `"nurbs_surface"`) beside the kind's fields, and read back through its validating
/// constructor.
///
/// ```
/// use lekalo::{BezierSurface, Direction, Points, Surface};
/// let net = Points::from_3d(&[[0.0, 0.0, 0.0], [0.0, 1.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 1.0]])?;
/// let s = Surface::from(BezierSurface::new(net, (2, 2))?);
/// assert_eq!(s.eval(1.0, 1.0)?, vec![1.0, 1.0, 1.0]);
/// let (lo, hi) = s.split_at(Direction::U, 0.5)?;
/// assert_eq!((lo.domain().0, hi.domain().0), ((0.0, 0.5), (0.5, 1.0)));
/// # Ok::<(), lekalo::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "type")]
pub enum Surface {
    /// A Bezier surface on `[0, 1]²`.
    #[serde(rename = "bezier_surface")]
    Bezier(BezierSurface),
    /// A B-spline surface.
    #[serde(rename = "bspline_surface")]
    BSpline(BSplineSurface),
    /// A NURBS surface.
    #[serde(rename = "nurbs_surface")]
    Nurbs(NurbsSurface),
}

impl From<BezierSurface> for Surface {
    fn from(s: BezierSurface) -> Self {
        Surface::Bezier(s)
    }
}

impl From<BSplineSurface> for Surface {
    fn from(s: BSplineSurface) -> Self {
        Surface::BSpline(s)
    }
}

impl From<NurbsSurface> for Surface {
    fn from(s: NurbsSurface) -> Self {
        Surface::Nurbs(s)
    }
}

/// A surface for the knot operations: polynomial as B-spline, rational as NURBS.
enum Spline<'a> {
    Poly(Cow<'a, BSplineSurface>),
    Rational(&'a NurbsSurface),
}

/// Applies the same operation in direction `u` or `v` to both spline kinds, whose methods
/// share names (`insert_knot_u`, `insert_knot_v`, …), giving the result back as a [`Surface`].
macro_rules! on_spline_dir {
    ($self:expr, $dir:expr, |$s:ident| $u:expr, $v:expr) => {
        match ($self.spline(), $dir) {
            (Spline::Poly($s), Direction::U) => $u.map(Surface::BSpline),
            (Spline::Poly($s), Direction::V) => $v.map(Surface::BSpline),
            (Spline::Rational($s), Direction::U) => $u.map(Surface::Nurbs),
            (Spline::Rational($s), Direction::V) => $v.map(Surface::Nurbs),
        }
    };
}

/// Delegates a method with the same signature on all three kinds.
macro_rules! delegate {
    ($self:expr, |$s:ident| $body:expr) => {
        match $self {
            Surface::Bezier($s) => $body,
            Surface::BSpline($s) => $body,
            Surface::Nurbs($s) => $body,
        }
    };
}

impl Surface {
    /// The kind's name in the JSON envelope: `"bezier_surface"`, `"bspline_surface"` or
    /// `"nurbs_surface"` (`docs/formats.md`).
    #[must_use]
    pub fn type_name(&self) -> &'static str {
        match self {
            Surface::Bezier(_) => "bezier_surface",
            Surface::BSpline(_) => "bspline_surface",
            Surface::Nurbs(_) => "nurbs_surface",
        }
    }

    /// The kind's name for people: "Bezier surface", "B-spline surface", "NURBS surface".
    #[must_use]
    pub fn display_name(&self) -> &'static str {
        match self {
            Surface::Bezier(_) => "Bezier surface",
            Surface::BSpline(_) => "B-spline surface",
            Surface::Nurbs(_) => "NURBS surface",
        }
    }

    /// Whether the surface is rational (NURBS).
    #[must_use]
    pub fn is_rational(&self) -> bool {
        matches!(self, Surface::Nurbs(_))
    }

    /// Degrees `(p_u, p_v)`.
    #[must_use]
    pub fn degrees(&self) -> (usize, usize) {
        delegate!(self, |s| s.degree())
    }

    /// Control net size `(n_u, n_v)`.
    #[must_use]
    pub fn net_size(&self) -> (usize, usize) {
        delegate!(self, |s| s.net_size())
    }

    /// Dimension of the points (Euclidean, without the weight).
    #[must_use]
    pub fn dim(&self) -> usize {
        delegate!(self, |s| s.dim())
    }

    /// Parameter domain `((u0, u1), (v0, v1))`.
    #[must_use]
    pub fn domain(&self) -> ((f64, f64), (f64, f64)) {
        delegate!(self, |s| s.domain())
    }

    /// Knot vectors `(U, V)`; a Bezier surface's are the clamped `[0…0, 1…1]` of its degrees.
    #[must_use]
    pub fn knots(&self) -> (Cow<'_, KnotVector>, Cow<'_, KnotVector>) {
        match self {
            Surface::Bezier(s) => (
                Cow::Owned(KnotVector::clamped_bezier(s.degree_u())),
                Cow::Owned(KnotVector::clamped_bezier(s.degree_v())),
            ),
            Surface::BSpline(s) => (Cow::Borrowed(s.knots_u()), Cow::Borrowed(s.knots_v())),
            Surface::Nurbs(s) => (Cow::Borrowed(s.knots_u()), Cow::Borrowed(s.knots_v())),
        }
    }

    /// Euclidean control points, row by row (`(i·n_v + j)` is point `(i, j)`).
    #[must_use]
    pub fn control_points(&self) -> Cow<'_, Points> {
        match self {
            Surface::Bezier(s) => Cow::Borrowed(s.control_points()),
            Surface::BSpline(s) => Cow::Borrowed(s.control_points()),
            Surface::Nurbs(s) => Cow::Owned(s.control_points()),
        }
    }

    /// The surface of the same kind, degrees, knots and weights on another net of the same
    /// size, row by row, of any dimension: as [`Curve::with_control_points`], a linear or affine
    /// map of the net is that map of the surface (affine invariance, P&T §4.4).
    ///
    /// ```
    /// use lekalo::{BezierSurface, Points, Surface};
    /// let net = Points::from_flat(2, vec![0.0, 0.0, 0.0, 1.0, 1.0, 0.0, 1.0, 1.0])?;
    /// let s = Surface::from(BezierSurface::new(net, (2, 2))?);
    /// let up = Points::from_flat(3, vec![0.0, 0.0, 5.0, 0.0, 1.0, 5.0, 1.0, 0.0, 5.0, 1.0, 1.0, 5.0])?;
    /// assert_eq!(s.with_control_points(up)?.eval(0.5, 0.25)?, vec![0.5, 0.25, 5.0]);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::LengthMismatch`] when the number of points differs from the net's; as the
    /// kind's constructor for non-finite points.
    pub fn with_control_points(&self, points: Points) -> Result<Surface> {
        let (nu, nv) = self.net_size();
        if points.len() != nu * nv {
            return Err(Error::LengthMismatch {
                what: "control points (one for each of the surface's)".into(),
                expected: nu * nv,
                got: points.len(),
            });
        }
        let (du, dv) = self.degrees();
        let (ku, kv) = self.knots();
        Ok(match self {
            Surface::Bezier(_) => Surface::Bezier(BezierSurface::new(points, (nu, nv))?),
            Surface::BSpline(_) => Surface::BSpline(BSplineSurface::new(
                du,
                dv,
                ku.as_slice().to_vec(),
                kv.as_slice().to_vec(),
                points,
                (nu, nv),
            )?),
            Surface::Nurbs(s) => Surface::Nurbs(NurbsSurface::new(
                du,
                dv,
                ku.as_slice().to_vec(),
                kv.as_slice().to_vec(),
                points,
                s.weights(),
                (nu, nv),
            )?),
        })
    }

    /// Weights of a NURBS surface, row by row; `None` for polynomial surfaces.
    #[must_use]
    pub fn weights(&self) -> Option<Vec<f64>> {
        match self {
            Surface::Nurbs(s) => Some(s.weights()),
            _ => None,
        }
    }

    /// The point at `(u, v)` (P&T A3.5, A4.3 for NURBS).
    ///
    /// # Errors
    /// [`Error::ParameterOutOfDomain`].
    pub fn eval(&self, u: f64, v: f64) -> Result<Vec<f64>> {
        delegate!(self, |s| s.eval(u, v))
    }

    /// The point at `(u, v)` written into `out` (`dim` values).
    ///
    /// # Errors
    /// [`Error::ParameterOutOfDomain`], [`Error::LengthMismatch`].
    pub fn eval_into(&self, u: f64, v: f64, out: &mut [f64]) -> Result<()> {
        delegate!(self, |s| s.eval_into(u, v, out))
    }

    /// Partial derivatives `S_{u^k v^l}` for `k + l ≤ order` (P&T A3.6, A4.4), in the table
    /// layout of [`BSplineSurface::eval_derivatives`].
    ///
    /// # Errors
    /// [`Error::ParameterOutOfDomain`], [`Error::TooLarge`].
    pub fn eval_derivatives(&self, u: f64, v: f64, order: usize) -> Result<Points> {
        delegate!(self, |s| s.eval_derivatives(u, v, order))
    }

    /// Unit normal `S_u × S_v / |S_u × S_v|` at `(u, v)` (3-D surfaces).
    ///
    /// # Errors
    /// [`Error::Dimension`] for a surface that is not 3-D; a degenerate point's error.
    pub fn normal(&self, u: f64, v: f64) -> Result<[f64; 3]> {
        delegate!(self, |s| s.normal(u, v))
    }

    /// The iso-parametric curve with the parameter of `dir` free and the other fixed at
    /// `value`: `dir = U` gives `u ↦ S(u, value)`, `dir = V` gives `v ↦ S(value, v)`.
    ///
    /// # Errors
    /// [`Error::ParameterOutOfDomain`] for `value` outside the other direction's domain.
    pub fn iso_curve(&self, dir: Direction, value: f64) -> Result<Curve> {
        // the kinds' `iso_curve_u(v)` fixes v and leaves u free
        match (self, dir) {
            (Surface::Bezier(s), Direction::U) => s.iso_curve_u(value).map(Curve::Bezier),
            (Surface::Bezier(s), Direction::V) => s.iso_curve_v(value).map(Curve::Bezier),
            (Surface::BSpline(s), Direction::U) => s.iso_curve_u(value).map(Curve::BSpline),
            (Surface::BSpline(s), Direction::V) => s.iso_curve_v(value).map(Curve::BSpline),
            (Surface::Nurbs(s), Direction::U) => s.iso_curve_u(value).map(Curve::Nurbs),
            (Surface::Nurbs(s), Direction::V) => s.iso_curve_v(value).map(Curve::Nurbs),
        }
    }

    /// The `n_u × n_v` parameter grid of [`Surface::sample_grid`], `u` outer: `(u_i, v_j)` at
    /// `i·n_v + j`, each direction from its domain start to exactly its end
    /// ([`crate::uniform_parameters`]).
    #[must_use]
    pub fn grid_parameters(&self, nu: usize, nv: usize) -> Vec<[f64; 2]> {
        let ((u0, u1), (v0, v1)) = self.domain();
        let vs = crate::uniform_parameters(v0, v1, nv);
        crate::uniform_parameters(u0, u1, nu)
            .into_iter()
            .flat_map(|u| vs.iter().map(move |&v| [u, v]))
            .collect()
    }

    /// Samples an `n_u × n_v` grid of points evenly over the domain (ends exact,
    /// [`crate::uniform_parameters`]), point `(i, j)` at `(i·n_v + j)·dim`; with `normals`,
    /// also the unit normals (3 values per point).
    ///
    /// # Errors
    /// [`Error::TooFew`] for fewer than 2 samples per direction; [`Error::TooLarge`] for a
    /// grid that cannot be held; the surface's errors.
    pub fn sample_grid(
        &self,
        nu: usize,
        nv: usize,
        normals: bool,
    ) -> Result<(Vec<f64>, Option<Vec<f64>>)> {
        if nu < 2 || nv < 2 {
            return Err(Error::TooFew {
                what: "samples per direction".into(),
                min: 2,
                got: nu.min(nv),
            });
        }
        let dim = self.dim();
        let count = nu.saturating_mul(nv);
        let values = count.saturating_mul(dim.max(3));
        if values > crate::MAX_SCALARS {
            return Err(Error::TooLarge {
                what: "surface samples".into(),
                size: values,
                max: crate::MAX_SCALARS,
            });
        }
        let ((u0, u1), (v0, v1)) = self.domain();
        let us = crate::uniform_parameters(u0, u1, nu);
        let vs = crate::uniform_parameters(v0, v1, nv);
        let mut pts = vec![0.0; count * dim];
        let mut nrm = normals.then(|| Vec::with_capacity(count * 3));
        for (i, &u) in us.iter().enumerate() {
            for (j, &v) in vs.iter().enumerate() {
                let at = (i * nv + j) * dim;
                self.eval_into(u, v, &mut pts[at..at + dim])?;
                if let Some(n) = nrm.as_mut() {
                    n.extend(self.normal(u, v)?);
                }
            }
        }
        Ok((pts, nrm))
    }

    /// The surface prepared for geometric queries (projection, meshing, curvature): its
    /// Bezier patches with a bounding-box tree ([`QuerySurface`]).
    ///
    /// # Errors
    /// [`Error::Degree`] above the query degree limit.
    pub fn to_query(&self) -> Result<QuerySurface> {
        match self.spline() {
            Spline::Poly(s) => QuerySurface::from_bspline(&s),
            Spline::Rational(s) => QuerySurface::from_nurbs(s),
        }
    }

    fn spline(&self) -> Spline<'_> {
        match self {
            Surface::Bezier(s) => Spline::Poly(Cow::Owned(s.to_bspline())),
            Surface::BSpline(s) => Spline::Poly(Cow::Borrowed(s)),
            Surface::Nurbs(s) => Spline::Rational(s),
        }
    }

    /// Inserts the knot `t` `times` times in direction `dir` (P&T A5.3), the shape unchanged.
    ///
    /// # Errors
    /// As [`BSplineSurface::insert_knot_u`].
    pub fn insert_knot(&self, dir: Direction, t: f64, times: usize) -> Result<Surface> {
        on_spline_dir!(
            self,
            dir,
            |s| s.insert_knot_u(t, times),
            s.insert_knot_v(t, times)
        )
    }

    /// Inserts all knots of the sorted `x` in direction `dir` (P&T A5.5).
    ///
    /// # Errors
    /// As [`BSplineSurface::refine_knots_u`].
    pub fn refine_knots(&self, dir: Direction, x: &[f64]) -> Result<Surface> {
        on_spline_dir!(self, dir, |s| s.refine_knots_u(x), s.refine_knots_v(x))
    }

    /// Splits at `t` in direction `dir` into the two surfaces on either side.
    ///
    /// # Errors
    /// As [`BSplineSurface::split_at_u`].
    pub fn split_at(&self, dir: Direction, t: f64) -> Result<(Surface, Surface)> {
        match (self.spline(), dir) {
            (Spline::Poly(s), Direction::U) => s
                .split_at_u(t)
                .map(|(a, b)| (Surface::BSpline(a), Surface::BSpline(b))),
            (Spline::Poly(s), Direction::V) => s
                .split_at_v(t)
                .map(|(a, b)| (Surface::BSpline(a), Surface::BSpline(b))),
            (Spline::Rational(s), Direction::U) => s
                .split_at_u(t)
                .map(|(a, b)| (Surface::Nurbs(a), Surface::Nurbs(b))),
            (Spline::Rational(s), Direction::V) => s
                .split_at_v(t)
                .map(|(a, b)| (Surface::Nurbs(a), Surface::Nurbs(b))),
        }
    }

    /// The same surface with the parameter of `dir` reversed (knots reflected).
    ///
    /// # Errors
    /// As [`BSplineSurface::reverse_u`].
    pub fn reverse(&self, dir: Direction) -> Result<Surface> {
        on_spline_dir!(self, dir, |s| s.reverse_u(), s.reverse_v())
    }

    /// The surface's Bezier patches over its non-empty knot rectangles (P&T §5.4), `u`-major,
    /// each a surface on its own rectangle: B-spline surfaces on clamped knots for a
    /// polynomial surface, NURBS for a rational one.
    ///
    /// # Errors
    /// As [`BSplineSurface::new`] (none for a valid surface).
    pub fn to_bezier_pieces(&self) -> Result<Vec<Surface>> {
        match self.spline() {
            Spline::Poly(s) => s
                .to_bezier_patches()
                .into_iter()
                .map(|((u0, u1), (v0, v1), patch)| {
                    let (p, q) = (patch.degree_u(), patch.degree_v());
                    let clamp = |a: f64, b: f64, d: usize| {
                        let mut k = vec![a; d + 1];
                        k.extend(std::iter::repeat_n(b, d + 1));
                        k
                    };
                    let net = patch.net_size();
                    BSplineSurface::new(
                        p,
                        q,
                        clamp(u0, u1, p),
                        clamp(v0, v1, q),
                        patch.control_points().clone(),
                        net,
                    )
                    .map(Surface::BSpline)
                })
                .collect(),
            Spline::Rational(s) => Ok(s
                .to_bezier_patches()
                .into_iter()
                .map(|(_, _, patch)| Surface::Nurbs(patch))
                .collect()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn net() -> Points {
        Points::from_3d(&[
            [0.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 2.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 1.0],
            [1.0, 2.0, 0.0],
            [2.0, 0.0, 0.0],
            [2.0, 1.0, 0.0],
            [2.0, 2.0, 0.0],
        ])
        .unwrap()
    }

    fn all() -> Vec<Surface> {
        let knots = vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0];
        let b = BSplineSurface::new(2, 2, knots.clone(), knots.clone(), net(), (3, 3)).unwrap();
        let weights = vec![1.0, 2.0, 1.0, 1.0, 0.5, 1.0, 1.0, 2.0, 1.0];
        let n = NurbsSurface::new(2, 2, knots.clone(), knots, net(), weights, (3, 3)).unwrap();
        vec![
            Surface::from(BezierSurface::new(net(), (3, 3)).unwrap()),
            Surface::from(b),
            Surface::from(n),
        ]
    }

    #[test]
    fn delegation_and_names() {
        let s = all();
        assert_eq!(
            s.iter().map(Surface::type_name).collect::<Vec<_>>(),
            ["bezier_surface", "bspline_surface", "nurbs_surface"],
            "type names"
        );
        // the dome's top (the README's surface): z = 1/4 at the middle
        assert_eq!(
            s[0].eval(0.5, 0.5).unwrap(),
            s[1].eval(0.5, 0.5).unwrap(),
            "Bezier = B-spline"
        );
        assert_eq!(
            s[1].eval(0.5, 0.5).unwrap(),
            vec![1.0, 1.0, 0.25],
            "dome top"
        );
        assert_eq!(
            s[0].knots().0.as_slice(),
            s[1].knots().0.as_slice(),
            "Bezier knots"
        );
        assert!(
            s[2].weights().is_some() && s[1].weights().is_none(),
            "weights"
        );
    }

    #[test]
    fn knot_operations_keep_the_shape_in_both_directions() {
        for s in all() {
            for dir in [Direction::U, Direction::V] {
                let refined = s.insert_knot(dir, 0.3, 1).unwrap();
                assert_eq!(refined.is_rational(), s.is_rational(), "kind kept");
                let (a, b) = (s.eval(0.2, 0.7).unwrap(), refined.eval(0.2, 0.7).unwrap());
                for (x, y) in a.iter().zip(&b) {
                    assert!((x - y).abs() < 1e-14, "{dir}: insertion moved the surface");
                }
                let rev = s.reverse(dir).unwrap();
                let (u, v) = match dir {
                    Direction::U => (0.8, 0.7),
                    Direction::V => (0.2, 0.3),
                };
                let (c, d) = (s.eval(0.2, 0.7).unwrap(), rev.eval(u, v).unwrap());
                for (x, y) in c.iter().zip(&d) {
                    assert!((x - y).abs() < 1e-14, "{dir}: reversal");
                }
                let (lo, hi) = s.split_at(dir, 0.5).unwrap();
                let pick = |s: &Surface| match dir {
                    Direction::U => s.domain().0,
                    Direction::V => s.domain().1,
                };
                assert_eq!(
                    (pick(&lo), pick(&hi)),
                    ((0.0, 0.5), (0.5, 1.0)),
                    "{dir}: split"
                );
            }
            let pieces = s
                .insert_knot(Direction::U, 0.5, 2)
                .unwrap()
                .to_bezier_pieces()
                .unwrap();
            assert_eq!(pieces.len(), 2, "two patches");
        }
    }

    #[test]
    fn iso_curves_and_samples_agree_with_evaluation() {
        for s in all() {
            let close = |a: Vec<f64>, b: Vec<f64>, what: &str| {
                for (x, y) in a.iter().zip(&b) {
                    assert!((x - y).abs() < 1e-14, "{what}: {a:?} against {b:?}");
                }
            };
            let c = s.iso_curve(Direction::U, 0.7).unwrap();
            close(
                c.eval(0.2).unwrap(),
                s.eval(0.2, 0.7).unwrap(),
                "u free, v fixed",
            );
            let c = s.iso_curve(Direction::V, 0.2).unwrap();
            close(
                c.eval(0.7).unwrap(),
                s.eval(0.2, 0.7).unwrap(),
                "v free, u fixed",
            );
            let (p, n) = s.sample_grid(3, 4, true).unwrap();
            assert_eq!(&p[p.len() - 3..], &[2.0, 2.0, 0.0], "last corner exact");
            for q in n.unwrap().chunks(3) {
                let len = (q[0] * q[0] + q[1] * q[1] + q[2] * q[2]).sqrt();
                assert!((len - 1.0).abs() < 1e-12, "unit normal {len}");
            }
            assert!(s.sample_grid(1, 4, false).is_err(), "too few samples");
            assert!(
                s.sample_grid(usize::MAX, 4, false).is_err(),
                "too many samples"
            );
        }
    }

    #[test]
    fn serde_and_direction_vocabulary() {
        for s in all() {
            let text = serde_json::to_string(&s).unwrap();
            assert_eq!(serde_json::from_str::<Surface>(&text).unwrap(), s, "{text}");
        }
        assert_eq!(
            serde_json::to_string(&Direction::V).unwrap(),
            "\"v\"",
            "serde spelling"
        );
        assert_eq!(
            " U ".parse::<Direction>().unwrap(),
            Direction::U,
            "case and spaces"
        );
    }
}
