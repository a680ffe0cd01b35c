//! The elementary surfaces of CAD exchange (ISO 10303-42 §4.5.1: plane, cylindrical, conical,
//! spherical and toroidal surfaces) as exact NURBS patches over given parameter ranges, placed by
//! a right-handed orthonormal frame ([`Placement`], the `axis2_placement_3d` of §4.4.3).
//!
//! Each takes the parametrisation of ISO 10303-42 and builds the patch by the constructions of
//! P&T chapter 8: the plane is a bilinear patch on the plane's own parameters; cylinders and
//! cones are straight segments, spheres and tori circular arcs, turned about the axis by
//! [`NurbsSurface::revolve`] (so `u` runs along the rational arc on `[0, 1]`, not the angle,
//! and `v` is the parameter of ISO 10303-42 for cylinders and cones, the arc parameter on
//! `[0, 1]` for spheres and tori).

use crate::error::readable;
use crate::What;
use std::f64::consts::{FRAC_PI_2, TAU};

use crate::curve::nurbs::NurbsCurve;
use crate::error::{check_finite, Error, Result};
use crate::points::Points;
use crate::surface::bspline::BSplineSurface;
use crate::surface::nurbs::NurbsSurface;
use crate::surface::revolution::{cross, dot3, segment, unit3};

/// Slack on the latitude range of a sphere: `|v| ≤ π/2 · (1 + LATITUDE_SLACK)` is accepted
/// (and clamped), so that bounds written as `±π/2` in decimal are read.
const LATITUDE_SLACK: f64 = 1e-12;

/// A right-handed orthonormal frame: origin, `x`, `y` and `z = x × y` (ISO 10303-42
/// `axis2_placement_3d`, §4.4.3, with the directions built by its function `build_axes`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Placement {
    /// The origin (`location`).
    pub origin: [f64; 3],
    /// The first axis (`ref_direction` made orthogonal to `z`).
    pub x: [f64; 3],
    /// `z × x`.
    pub y: [f64; 3],
    /// The axis.
    pub z: [f64; 3],
}

impl Placement {
    /// The frame of an `axis2_placement_3d` (ISO 10303-42 §4.4.3 and its functions
    /// `build_axes`, `first_proj_axis`): `z` the unit `axis` (default `(0, 0, 1)`), `x` the
    /// unit projection of `ref_direction` on the plane orthogonal to `z` (default `(1, 0, 0)`,
    /// or `(0, 1, 0)` when `z` is along `(1, 0, 0)`), `y = z × x`.
    ///
    /// ```
    /// use lekalo::surface::Placement;
    /// let p = Placement::new([1.0, 2.0, 3.0], Some([0.0, 0.0, 2.0]), Some([1.0, 1.0, 1.0]))?;
    /// let h = 0.5_f64.sqrt();
    /// assert!((p.x[0] - h).abs() < 1e-15 && (p.x[1] - h).abs() < 1e-15 && p.x[2] == 0.0);
    /// assert!((p.y[0] + h).abs() < 1e-15 && (p.y[1] - h).abs() < 1e-15);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for a zero axis or a reference direction along the axis;
    /// [`Error::NonFinite`].
    pub fn new(
        origin: [f64; 3],
        axis: Option<[f64; 3]>,
        ref_direction: Option<[f64; 3]>,
    ) -> Result<Self> {
        check_finite("placement location", &origin)?;
        let z = unit3(axis.unwrap_or([0.0, 0.0, 1.0]), "placement axis")?;
        let r = match ref_direction {
            Some(r) => unit3(r, "placement ref_direction")?,
            None if (z[0] - 1.0).abs() <= f64::EPSILON => [0.0, 1.0, 0.0],
            None if (z[0] + 1.0).abs() <= f64::EPSILON => [0.0, 1.0, 0.0],
            None => [1.0, 0.0, 0.0],
        };
        let c = dot3(r, z);
        let x = [r[0] - c * z[0], r[1] - c * z[1], r[2] - c * z[2]];
        let x = unit3(x, "placement ref_direction").map_err(|_| Error::InvalidArgument {
            what: "placement ref_direction".into(),
            reason: "the reference direction is along the axis; give one across it".into(),
        })?;
        let y = cross(z, x);
        Ok(Placement { origin, x, y, z })
    }

    /// The point `origin + a x + b y + c z`.
    #[must_use]
    pub fn point(&self, a: f64, b: f64, c: f64) -> [f64; 3] {
        let mut p = self.origin;
        for (k, pk) in p.iter_mut().enumerate() {
            *pk += a * self.x[k] + b * self.y[k] + c * self.z[k];
        }
        p
    }

    /// The coordinates `(x·d, y·d, z·d)` of `p` in the frame, `d = p − origin`.
    #[must_use]
    pub fn coordinates(&self, p: [f64; 3]) -> [f64; 3] {
        let d = [
            p[0] - self.origin[0],
            p[1] - self.origin[1],
            p[2] - self.origin[2],
        ];
        [dot3(d, self.x), dot3(d, self.y), dot3(d, self.z)]
    }
}

fn check_range(what: impl Into<What>, (a, b): (f64, f64)) -> Result<()> {
    let what: What = what.into();
    check_finite(what, &[a, b])?;
    if a < b {
        Ok(())
    } else {
        Err(Error::InvalidArgument {
            what,
            reason: format!(
                "the range [{a}, {b}] is empty; give a lower bound below the upper",
                a = readable(&a),
                b = readable(&b)
            ),
        })
    }
}

fn check_positive(what: impl Into<What>, x: f64) -> Result<()> {
    let what: What = what.into();
    if x > 0.0 && x.is_finite() {
        Ok(())
    } else {
        Err(Error::InvalidArgument {
            what,
            reason: format!("{x} is not a positive finite length", x = readable(&x)),
        })
    }
}

impl BSplineSurface {
    /// The patch `[u0, u1] × [v0, v1]` of the plane `O + u X + v Y` (ISO 10303-42 `plane`,
    /// §4.5.1.1, parametrised by its placement's `x` and `y`): a bilinear B-spline with the
    /// four corners as control points, exact on the same parameters.
    ///
    /// ```
    /// use lekalo::{surface::Placement, BSplineSurface};
    /// let f = Placement::new([0.0, 0.0, 1.0], None, None)?;
    /// let s = BSplineSurface::plane_patch(&f, (-1.0, 1.0), (0.0, 2.0))?;
    /// assert_eq!(s.eval(0.5, 1.5)?, vec![0.5, 1.5, 1.0]);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for an empty range; [`Error::NonFinite`].
    pub fn plane_patch(frame: &Placement, u: (f64, f64), v: (f64, f64)) -> Result<Self> {
        check_range("plane u range", u)?;
        check_range("plane v range", v)?;
        let mut data = Vec::with_capacity(12);
        for a in [u.0, u.1] {
            for b in [v.0, v.1] {
                data.extend(frame.point(a, b, 0.0));
            }
        }
        BSplineSurface::new(
            1,
            1,
            vec![u.0, u.0, u.1, u.1],
            vec![v.0, v.0, v.1, v.1],
            Points::from_flat(3, data)?,
            (2, 2),
        )
    }
}

impl NurbsSurface {
    /// The piece of the cylinder `O + R (cos u X + sin u Y) + v Z` (ISO 10303-42
    /// `cylindrical_surface`, §4.5.1.2) with `u ∈ angles` (radians, at most a full turn) and
    /// `v ∈ heights`: the segment at distance `R` turned about the axis (P&T §8.5).
    ///
    /// ```
    /// use lekalo::{surface::Placement, NurbsSurface};
    /// let f = Placement::new([0.0; 3], None, None)?;
    /// let s = NurbsSurface::cylinder(&f, 2.0, (0.0, std::f64::consts::TAU), (-1.0, 1.0))?;
    /// let p = s.eval(0.7, 0.5)?;
    /// assert!((p[0].hypot(p[1]) - 2.0).abs() < 1e-14 && (p[2] - 0.5).abs() < 1e-15);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for a radius that is not positive or an empty range;
    /// errors of [`NurbsSurface::revolve`].
    pub fn cylinder(
        frame: &Placement,
        radius: f64,
        angles: (f64, f64),
        heights: (f64, f64),
    ) -> Result<Self> {
        check_positive("cylinder radius", radius)?;
        check_range("cylinder heights", heights)?;
        let g = segment(frame.point(radius, 0.0, 0.0), frame.z, heights.0, heights.1)?;
        Self::revolve(&g, frame.origin, frame.z, angles.0, angles.1)
    }

    /// The piece of the cone `O + (R + v tan α)(cos u X + sin u Y) + v Z` (ISO 10303-42
    /// `conical_surface`, §4.5.1.3: `R` the radius at `v = 0`, `α` the semi-angle) with
    /// `u ∈ angles` and `v ∈ heights`: the straight generator turned about the axis
    /// (P&T §8.5). A range that crosses the apex gives both nappes.
    ///
    /// ```
    /// use lekalo::{surface::Placement, NurbsSurface};
    /// use std::f64::consts::{FRAC_PI_4, TAU};
    /// let f = Placement::new([0.0; 3], None, None)?;
    /// let s = NurbsSurface::cone(&f, 1.0, FRAC_PI_4, (0.0, TAU), (0.0, 2.0))?;
    /// let p = s.eval(0.3, 2.0)?;
    /// assert!((p[0].hypot(p[1]) - 3.0).abs() < 1e-14);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for a negative radius, a semi-angle outside `(0, π/2)` or an
    /// empty range; errors of [`NurbsSurface::revolve`].
    pub fn cone(
        frame: &Placement,
        radius: f64,
        semi_angle: f64,
        angles: (f64, f64),
        heights: (f64, f64),
    ) -> Result<Self> {
        check_finite("cone radius", &[radius, semi_angle])?;
        if radius < 0.0 || !(semi_angle > 0.0 && semi_angle < FRAC_PI_2) {
            return Err(Error::InvalidArgument {
                what: "cone".into(),
                reason: format!(
                    "radius {radius} must be at least 0 and the semi-angle {semi_angle} between 0 and π/2 (radians)", radius = readable(&radius)),
            });
        }
        check_range("cone heights", heights)?;
        let t = semi_angle.tan();
        let d = [
            t * frame.x[0] + frame.z[0],
            t * frame.x[1] + frame.z[1],
            t * frame.x[2] + frame.z[2],
        ];
        let g = segment(frame.point(radius, 0.0, 0.0), d, heights.0, heights.1)?;
        Self::revolve(&g, frame.origin, frame.z, angles.0, angles.1)
    }

    /// The piece of the sphere `O + R cos v (cos u X + sin u Y) + R sin v Z` (ISO 10303-42
    /// `spherical_surface`, §4.5.1.4) with longitude `u ∈ angles` and latitude
    /// `v ∈ latitudes ⊂ [−π/2, π/2]`: the meridian arc turned about the axis (P&T §8.5,
    /// Example Ex8.2), rational of degree (2, 2).
    ///
    /// ```
    /// use lekalo::{surface::Placement, NurbsSurface};
    /// use std::f64::consts::{FRAC_PI_2, TAU};
    /// let f = Placement::new([1.0, 0.0, 0.0], None, None)?;
    /// let s = NurbsSurface::sphere(&f, 3.0, (0.0, TAU), (-FRAC_PI_2, FRAC_PI_2))?;
    /// let p = s.eval(0.2, 0.7)?;
    /// assert!(((p[0] - 1.0).hypot(p[1]).hypot(p[2]) - 3.0).abs() < 1e-14);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for a radius that is not positive or a latitude range that is
    /// empty or leaves `[−π/2, π/2]`; errors of [`NurbsSurface::revolve`].
    pub fn sphere(
        frame: &Placement,
        radius: f64,
        angles: (f64, f64),
        latitudes: (f64, f64),
    ) -> Result<Self> {
        check_positive("sphere radius", radius)?;
        check_range("sphere latitudes", latitudes)?;
        let limit = FRAC_PI_2 * (1.0 + LATITUDE_SLACK);
        if latitudes.0 < -limit || latitudes.1 > limit {
            return Err(Error::InvalidArgument {
                what: "sphere latitudes".into(),
                reason: format!(
                    "[{}, {}] leaves [−π/2, π/2]; latitudes are radians from the equator",
                    latitudes.0, latitudes.1
                ),
            });
        }
        let (a, b) = (latitudes.0.max(-FRAC_PI_2), latitudes.1.min(FRAC_PI_2));
        let g = NurbsCurve::circular_arc(&frame.origin, &frame.x, &frame.z, radius, a, b)?;
        Self::revolve(&g, frame.origin, frame.z, angles.0, angles.1)
    }

    /// The piece of the torus `O + (R + r cos v)(cos u X + sin u Y) + r sin v Z` (ISO 10303-42
    /// `toroidal_surface`, §4.5.1.5: `R` the major, `r` the minor radius) with `u ∈ angles` and
    /// `v ∈ minor_angles` (each at most a full turn): the minor circle's arc turned about the
    /// axis (P&T §8.5), rational of degree (2, 2).
    ///
    /// ```
    /// use lekalo::{surface::Placement, NurbsSurface};
    /// use std::f64::consts::TAU;
    /// let f = Placement::new([0.0; 3], None, None)?;
    /// let s = NurbsSurface::torus(&f, 5.0, 1.0, (0.0, TAU), (0.0, TAU))?;
    /// let p = s.eval(0.3, 0.6)?;
    /// assert!(((p[0].hypot(p[1]) - 5.0).hypot(p[2]) - 1.0).abs() < 1e-14);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for radii that are not positive; errors of
    /// [`NurbsCurve::circular_arc`] and [`NurbsSurface::revolve`].
    pub fn torus(
        frame: &Placement,
        major_radius: f64,
        minor_radius: f64,
        angles: (f64, f64),
        minor_angles: (f64, f64),
    ) -> Result<Self> {
        check_positive("torus major radius", major_radius)?;
        check_positive("torus minor radius", minor_radius)?;
        let c = frame.point(major_radius, 0.0, 0.0);
        let g = NurbsCurve::circular_arc(
            &c,
            &frame.x,
            &frame.z,
            minor_radius,
            minor_angles.0,
            minor_angles.1,
        )?;
        Self::revolve(&g, frame.origin, frame.z, angles.0, angles.1)
    }
}

/// The full turn `(0, 2π)`, the angular range of closed elementary surfaces.
pub const FULL_TURN: (f64, f64) = (0.0, TAU);

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    fn frame() -> Placement {
        Placement::new(
            [1.5, -2.0, 0.25],
            Some([1.0, 2.0, 2.0]),
            Some([0.0, 1.0, -1.0]),
        )
        .unwrap()
    }

    /// Evaluates at a grid, maps each point to frame coordinates and checks `f(x, y, z) ≈ 0`
    /// relative to `scale`.
    fn check(s: &NurbsSurface, scale: f64, f: impl Fn([f64; 3]) -> f64) {
        let ((u0, u1), (v0, v1)) = s.domain();
        let fr = frame();
        for i in 0..=20 {
            for j in 0..=20 {
                let u = u0 + (u1 - u0) * i as f64 / 20.0;
                let v = v0 + (v1 - v0) * j as f64 / 20.0;
                let p = s.eval(u, v).unwrap();
                let c = fr.coordinates([p[0], p[1], p[2]]);
                let e = f(c);
                assert!(e.abs() <= 1e-12 * scale, "residual {e} at ({u}, {v})");
            }
        }
    }

    #[test]
    fn elementary_surfaces_lie_on_their_implicit_equations() {
        let f = frame();
        let r = 3.0;
        let cyl = NurbsSurface::cylinder(&f, r, (0.3, 2.0), (-1.0, 4.0)).unwrap();
        check(&cyl, r, |c| c[0].hypot(c[1]) - r);
        let (r0, a) = (2.0, 0.4_f64);
        let cone = NurbsSurface::cone(&f, r0, a, FULL_TURN, (-1.0, 3.0)).unwrap();
        check(&cone, r0, |c| c[0].hypot(c[1]) - (r0 + c[2] * a.tan()));
        let sph = NurbsSurface::sphere(&f, r, (-1.0, 4.0), (-FRAC_PI_2, 0.5)).unwrap();
        check(&sph, r, |c| c[0].hypot(c[1]).hypot(c[2]) - r);
        let (big, small) = (5.0, 1.5);
        let tor = NurbsSurface::torus(&f, big, small, FULL_TURN, (-PI, PI)).unwrap();
        check(&tor, big, |c| (c[0].hypot(c[1]) - big).hypot(c[2]) - small);
        let pl = NurbsSurface::from_bspline(
            &BSplineSurface::plane_patch(&f, (-2.0, 1.0), (0.5, 3.0)).unwrap(),
        );
        check(&pl, 3.0, |c| c[2]);
    }

    #[test]
    fn boundaries_follow_the_iso_parametrisation() {
        // the corners of the patch are the points of the ISO parametrisation at the range ends
        let f = frame();
        let (r, a) = (2.0, 0.3_f64);
        let cone = NurbsSurface::cone(&f, r, a, (0.5, 2.5), (-1.0, 2.0)).unwrap();
        let iso = |u: f64, v: f64| {
            let rr = r + v * a.tan();
            f.point(rr * u.cos(), rr * u.sin(), v)
        };
        let ((u0, u1), (v0, v1)) = cone.domain();
        for (u, v, au, av) in [(u0, v0, 0.5, -1.0), (u1, v1, 2.5, 2.0), (u0, v1, 0.5, 2.0)] {
            let p = cone.eval(u, v).unwrap();
            let q = iso(au, av);
            for k in 0..3 {
                assert!((p[k] - q[k]).abs() < 1e-13 * r, "{p:?} {q:?}");
            }
        }
        let tor = NurbsSurface::torus(&f, 4.0, 1.0, (0.0, 1.0), (2.0, 3.0)).unwrap();
        let p = tor.eval(0.0, 0.0).unwrap();
        let q = f.point((4.0 + 2f64.cos()) * 1.0, 0.0, 2f64.sin());
        for k in 0..3 {
            assert!((p[k] - q[k]).abs() < 1e-13 * 4.0, "{p:?} {q:?}");
        }
    }

    #[test]
    fn bad_shapes_are_refused_with_the_reason() {
        let f = frame();
        assert!(NurbsSurface::cylinder(&f, 0.0, FULL_TURN, (0.0, 1.0)).is_err());
        assert!(NurbsSurface::cylinder(&f, 1.0, FULL_TURN, (1.0, 1.0)).is_err());
        assert!(NurbsSurface::sphere(&f, 1.0, FULL_TURN, (0.0, 2.0)).is_err());
        assert!(NurbsSurface::cone(&f, 1.0, FRAC_PI_2, FULL_TURN, (0.0, 1.0)).is_err());
        assert!(Placement::new([0.0; 3], Some([0.0, 0.0, 1.0]), Some([0.0, 0.0, 2.0])).is_err());
        assert!(Placement::new([0.0; 3], Some([0.0; 3]), None).is_err());
    }
}
