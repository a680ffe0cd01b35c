//! Exact conics: circles, circular and elliptic arcs of any sweep up to 2π as rational
//! quadratic NURBS (P&T §7.5, Algorithm A7.1), in any dimension ≥ 2; straight segments as
//! linear B-splines.

use crate::curve::bspline::BSplineCurve;
use crate::curve::nurbs::NurbsCurve;
use crate::error::readable;
use crate::error::{check_finite, Error, Result};
use crate::numeric::linalg::norm2;
use crate::points::Points;

/// Relative tolerance for the orthogonality of the axes of an arc: after normalisation,
/// `|x̂ · ŷ| ≤ ARC_AXIS_ORTHOGONALITY_TOL` is accepted (and `ŷ` is then made exactly orthogonal
/// by one Gram–Schmidt step); anything larger is refused rather than silently changed.
const ARC_AXIS_ORTHOGONALITY_TOL: f64 = 1e-9;

/// Relative slack on a sweep of `2π`: `|end − start| ≤ 2π·(1 + ARC_SWEEP_SLACK)` is a full turn,
/// so that sums such as `start + 2.0 * PI` are accepted despite rounding.
const ARC_SWEEP_SLACK: f64 = 8.0 * f64::EPSILON;

/// Points closer than `ARC_COINCIDENT_TOL` times the largest pairwise distance of the three
/// points of [`NurbsCurve::arc_through_points`] count as coincident.
const ARC_COINCIDENT_TOL: f64 = 1e-12;

/// Three points whose inscribed angle at the middle point has `|sin β| ≤ ARC_COLLINEAR_TOL` count
/// as collinear: the radius `|a − c| / (2 |sin β|)` would exceed `5·10⁹ |a − c|` and the centre
/// would lose more than ten digits.
const ARC_COLLINEAR_TOL: f64 = 1e-10;

impl NurbsCurve {
    /// The full circle `C + r (cos θ X + sin θ Y)`, `θ ∈ [0, 2π]`, as an exact rational
    /// quadratic of four 90° pieces (P&T §7.5, Algorithm A7.1 with `θ_s = 0`, `θ_e = 2π`): nine
    /// control points (the last equal to the first), weights `1, 1/√2, 1, …`, knots
    /// `[0,0,0, ¼,¼, ½,½, ¾,¾, 1,1,1]`. The parameter is not proportional to the angle.
    ///
    /// `center`, `x_axis` and `y_axis` have the same dimension `dim ≥ 2`; the axes span the plane
    /// of the circle, need not have unit length, and must be orthogonal (see
    /// [`NurbsCurve::circular_arc`]). In the plane use `x_axis = [1, 0]`, `y_axis = [0, 1]`.
    ///
    /// ```
    /// use lekalo::NurbsCurve;
    /// // a circle of radius 2 about (1, 1, 1) in the plane x + y + z = 3
    /// let c = NurbsCurve::circle(&[1.0, 1.0, 1.0], &[1.0, -1.0, 0.0], &[1.0, 1.0, -2.0], 2.0)?;
    /// for k in 0..=100 {
    ///     let p = c.eval(k as f64 / 100.0)?;
    ///     let r = ((p[0] - 1.0).powi(2) + (p[1] - 1.0).powi(2) + (p[2] - 1.0).powi(2)).sqrt();
    ///     assert!((r - 2.0).abs() < 2e-14);
    ///     assert!((p[0] + p[1] + p[2] - 3.0).abs() < 1e-14);
    /// }
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// As [`NurbsCurve::circular_arc`].
    pub fn circle(center: &[f64], x_axis: &[f64], y_axis: &[f64], radius: f64) -> Result<Self> {
        Self::circular_arc(center, x_axis, y_axis, radius, 0.0, std::f64::consts::TAU)
    }

    /// The full circle of `radius` about `center` in the plane through `center` with the given
    /// `normal` (3-D), as [`NurbsCurve::circle`] with the frame `X = normalise(e × n)`,
    /// `Y = n̂ × X`, where `e` is the coordinate axis least aligned with `n` (so the frame is
    /// deterministic and well conditioned). The circle runs counter-clockwise seen from the tip
    /// of `normal`.
    ///
    /// ```
    /// use lekalo::NurbsCurve;
    /// let c = NurbsCurve::circle_with_normal([0.0, 0.0, 5.0], [0.0, 0.0, 2.0], 3.0)?;
    /// for k in 0..=16 {
    ///     let p = c.eval(k as f64 / 16.0)?;
    ///     assert!((p[0].hypot(p[1]) - 3.0).abs() < 1e-14 && (p[2] - 5.0).abs() < 1e-15);
    /// }
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for a zero normal or a radius that is not positive;
    /// [`Error::NonFinite`].
    pub fn circle_with_normal(center: [f64; 3], normal: [f64; 3], radius: f64) -> Result<Self> {
        check_finite("normal", &normal)?;
        let n = norm2(&normal);
        if n == 0.0 || !n.is_finite() {
            return Err(Error::InvalidArgument {
                what: "normal".into(),
                reason: "the normal is the zero vector; give the direction of the circle's axis"
                    .into(),
            });
        }
        let nh = [normal[0] / n, normal[1] / n, normal[2] / n];
        // the coordinate axis least aligned with the normal
        let mut e = [0.0; 3];
        let k = (0..3)
            .min_by(|&i, &j| nh[i].abs().total_cmp(&nh[j].abs()))
            .unwrap_or(0);
        e[k] = 1.0;
        let cross = |a: &[f64; 3], b: &[f64; 3]| {
            [
                a[1] * b[2] - a[2] * b[1],
                a[2] * b[0] - a[0] * b[2],
                a[0] * b[1] - a[1] * b[0],
            ]
        };
        let x = cross(&e, &nh);
        let lx = norm2(&x);
        let x = [x[0] / lx, x[1] / lx, x[2] / lx];
        let y = cross(&nh, &x);
        Self::circle(&center, &x, &y, radius)
    }

    /// The circular arc `C + r (cos θ X + sin θ Y)`, `θ` from `start_angle` to `end_angle`, as
    /// an exact rational quadratic on the parameter domain `[0, 1]` (P&T §7.5, Algorithm A7.1).
    ///
    /// The sweep `Δ = end − start` (positive: from `X` towards `Y`; negative: the other way) is
    /// split into `n = ⌈|Δ| / 90°⌉ ≤ 4` equal pieces of angle `δ = Δ/n`. Piece `i` has the end
    /// control points on the circle at `θ_i`, `θ_{i+1}` and the middle one at the intersection of
    /// the end tangents, `C + r/cos(δ/2) · (cos θ_m X + sin θ_m Y)` (`θ_m` the mid angle), with
    /// weight `cos(δ/2)`; interior knots `i/n` are double. Every point of the curve lies on the
    /// circle up to rounding: `| |P − C| − r | ≲ 10 ε (r + |C|)`, i.e. within `1e-14·r` when the
    /// centre is not far from the origin compared to `r` (the tests check both bounds). With
    /// `|Δ| = 2π` the last control point is set equal to the first, so the curve closes exactly.
    ///
    /// The axes need not be unit vectors; they are normalised. They must be orthogonal up to
    /// `|x̂·ŷ| ≤ 1e-9`, after which `ŷ` is made exactly orthogonal to `x̂`. Points of dimension 2
    /// or more are accepted (for `dim > 3` the circle lies in the plane `C + span(X, Y)`).
    ///
    /// ```
    /// use lekalo::NurbsCurve;
    /// use std::f64::consts::PI;
    /// // upper half of the unit circle, from (1, 0) to (−1, 0): two 90° pieces
    /// let c = NurbsCurve::circular_arc(&[0.0, 0.0], &[1.0, 0.0], &[0.0, 1.0], 1.0, 0.0, PI)?;
    /// assert_eq!(c.degree(), 2);
    /// assert_eq!(c.knots().as_slice(), &[0.0, 0.0, 0.0, 0.5, 0.5, 1.0, 1.0, 1.0]);
    /// let top = c.eval(0.5)?;
    /// assert!(top[0].abs() < 1e-15 && (top[1] - 1.0).abs() < 1e-15);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::Dimension`] if `dim < 2` or the three vectors differ in length;
    /// [`Error::NonFinite`] for NaN or infinite input (or a result that overflows);
    /// [`Error::InvalidArgument`] for a radius that is not positive, a zero axis, axes that are
    /// not orthogonal, or a sweep of zero or of more than a full turn.
    pub fn circular_arc(
        center: &[f64],
        x_axis: &[f64],
        y_axis: &[f64],
        radius: f64,
        start_angle: f64,
        end_angle: f64,
    ) -> Result<Self> {
        let (x, y) = arc_frame(center, x_axis, y_axis)?;
        check_radius(radius)?;
        check_finite("start_angle", &[start_angle])?;
        check_finite("end_angle", &[end_angle])?;
        let sweep = end_angle - start_angle;
        let full = std::f64::consts::TAU;
        if sweep == 0.0 || sweep.abs() > full * (1.0 + ARC_SWEEP_SLACK) {
            return Err(Error::InvalidArgument {
                what: "arc angles".into(),
                reason: format!(
                    "the sweep end_angle − start_angle = {sweep} must be non-zero and at most 2π \
                     in magnitude"
                ),
            });
        }
        let closed = sweep.abs() >= full;
        let sweep = sweep.clamp(-full, full);
        let homogeneous = arc_homogeneous(center, &x, &y, radius, start_angle, sweep, closed)?;
        Ok(NurbsCurve { homogeneous })
    }

    /// The circular arc from `a` through `b` to `c` (the circle through three points, document
    /// 001 §3's local curves), as in [`NurbsCurve::circular_arc`]: `C(0) = a` and `C(1) = c`
    /// exactly, and `b` lies on the curve. Any dimension ≥ 2; the arc lies in the plane of the
    /// three points and may sweep up to (not including) a full turn.
    ///
    /// The centre is the circumcentre `b + α u + β v` with `u = a − b`, `v = c − b`, solving the
    /// 2×2 Gram system `[u·u u·v; u·v v·v] (α, β) = ½ (u·u, v·v)`; its determinant is computed as
    /// the squared norm of the exterior product `u ∧ v`, free of cancellation. The relative
    /// error of the centre grows like `ε / |sin β|`, `β` the angle at `b`.
    ///
    /// Tolerances, relative to the scale of the points: two points coincide if their distance is
    /// at most `1e-12` times the largest pairwise distance; the points are collinear if
    /// `|sin β| ≤ 1e-10` (the radius would exceed `5·10⁹ |a − c|`).
    ///
    /// ```
    /// use lekalo::NurbsCurve;
    /// // three points of the circle of radius 5 about (1, 2): a 270° arc
    /// let c = NurbsCurve::arc_through_points(&[6.0, 2.0], &[1.0, -3.0], &[1.0, 7.0])?;
    /// assert_eq!(c.eval(0.0)?, vec![6.0, 2.0]);
    /// assert_eq!(c.eval(1.0)?, vec![1.0, 7.0]);
    /// let m = c.eval(0.5)?;
    /// assert!(((m[0] - 1.0).hypot(m[1] - 2.0) - 5.0).abs() < 1e-14);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::Dimension`] if `dim < 2` or the points differ in dimension; [`Error::NonFinite`];
    /// [`Error::InvalidArgument`] if two points coincide or the three are collinear.
    pub fn arc_through_points(a: &[f64], b: &[f64], c: &[f64]) -> Result<Self> {
        Self::arc_through_points_with_parameter(a, b, c).map(|(arc, _)| arc)
    }

    /// As [`NurbsCurve::arc_through_points`], also returning the parameter `t_b` with
    /// `C(t_b) = b` (up to rounding), e.g. to split the arc at `b` or to blend local arcs
    /// (document 001 §3).
    ///
    /// The arc's pieces are symmetric rational quadratics of half-angle `α = δ/2`, on which the
    /// local parameter `s ∈ [0, 1]` and the angle `φ` from the piece's middle satisfy
    /// `tan(φ/2) = (2s − 1) tan(α/2)` (the tangent-half-angle form of the conic, P&T §7.5), so
    /// `t_b` follows in closed form from the angle of `b`.
    ///
    /// ```
    /// use lekalo::NurbsCurve;
    /// let (arc, tb) = NurbsCurve::arc_through_points_with_parameter(&[6.0, 2.0], &[1.0, -3.0], &[1.0, 7.0])?;
    /// let p = arc.eval(tb)?;
    /// assert!((p[0] - 1.0).abs() < 1e-14 && (p[1] + 3.0).abs() < 1e-14);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// As [`NurbsCurve::arc_through_points`].
    pub fn arc_through_points_with_parameter(
        a: &[f64],
        b: &[f64],
        c: &[f64],
    ) -> Result<(Self, f64)> {
        let dim = a.len();
        check_arc_dims(
            "arc point a",
            dim,
            &[("arc point b", b), ("arc point c", c)],
        )?;
        check_finite("arc point a", a)?;
        check_finite("arc point b", b)?;
        check_finite("arc point c", c)?;
        let u: Vec<f64> = a.iter().zip(b).map(|(p, q)| p - q).collect();
        let v: Vec<f64> = c.iter().zip(b).map(|(p, q)| p - q).collect();
        let w: Vec<f64> = a.iter().zip(c).map(|(p, q)| p - q).collect();
        if !u.iter().chain(&v).chain(&w).all(|x| x.is_finite()) {
            return Err(Error::NonFinite {
                what: "arc point differences (overflow)".into(),
                index: 0,
                value: f64::INFINITY,
            });
        }
        let (lu, lv, lw) = (norm2(&u), norm2(&v), norm2(&w));
        let scale = lu.max(lv).max(lw);
        for (len, names) in [(lu, "a and b"), (lv, "b and c"), (lw, "a and c")] {
            if len <= ARC_COINCIDENT_TOL * scale {
                return Err(Error::InvalidArgument {
                    what: "arc points".into(),
                    reason: format!(
                        "points {names} coincide (distance {len:e} ≤ {ARC_COINCIDENT_TOL:e} × \
                         {scale:e}, the largest distance between the points); a circle needs \
                         three distinct points"
                    ),
                });
            }
        }
        // |sin β| = |û ∧ v̂| from the exterior product of the unit vectors
        let uh: Vec<f64> = u.iter().map(|x| x / lu).collect();
        let vh: Vec<f64> = v.iter().map(|x| x / lv).collect();
        let sin_beta = wedge_norm(&uh, &vh);
        if sin_beta <= ARC_COLLINEAR_TOL {
            return Err(Error::InvalidArgument {
                what: "arc points".into(),
                reason: format!(
                    "the three points are collinear (sine of the angle at b is {sin_beta:e} ≤ \
                     {ARC_COLLINEAR_TOL:e}); no circle passes through them — use a line"
                ),
            });
        }
        // Gram system in scaled form: u = lu·û, v = lv·v̂, D = (lu·lv·sinβ)²
        let uu = lu * lu;
        let vv = lv * lv;
        let d = (lu * lv * sin_beta).powi(2);
        let uw: f64 = u.iter().zip(&w).map(|(p, q)| p * q).sum();
        let vw: f64 = v.iter().zip(&w).map(|(p, q)| p * q).sum();
        let alpha = vv * uw / (2.0 * d);
        let beta = -uu * vw / (2.0 * d);
        let center: Vec<f64> = (0..dim)
            .map(|k| b[k] + alpha * u[k] + beta * v[k])
            .collect();
        // frame: X towards a; Y in the plane, oriented so that b comes before c
        let ca: Vec<f64> = a.iter().zip(&center).map(|(p, q)| p - q).collect();
        let radius = norm2(&ca);
        let x: Vec<f64> = ca.iter().map(|p| p / radius).collect();
        let cb: Vec<f64> = b.iter().zip(&center).map(|(p, q)| p - q).collect();
        let cc: Vec<f64> = c.iter().zip(&center).map(|(p, q)| p - q).collect();
        let yb = reject(&cb, &x);
        let yc = reject(&cc, &x);
        let mut y = if norm2(&yb) >= norm2(&yc) { yb } else { yc };
        let ly = norm2(&y);
        for p in &mut y {
            *p /= ly;
        }
        let angle = |q: &[f64], y: &[f64]| {
            let a = dot(q, y).atan2(dot(q, &x));
            if a < 0.0 {
                a + std::f64::consts::TAU
            } else {
                a
            }
        };
        if angle(&cb, &y) > angle(&cc, &y) {
            for p in &mut y {
                *p = -*p;
            }
        }
        let sweep = angle(&cc, &y);
        let t_b = arc_parameter(angle(&cb, &y), sweep);
        let mut homogeneous = arc_homogeneous(&center, &x, &y, radius, 0.0, sweep, false)?;
        // the end points exactly (weight 1 there)
        let hd = dim + 1;
        let (degree, knots, ctrl) = homogeneous.into_parts();
        let mut h = ctrl.into_vec();
        let last = h.len() - hd;
        h[..dim].copy_from_slice(a);
        h[last..last + dim].copy_from_slice(c);
        homogeneous = BSplineCurve::from_raw(degree, knots.into_vec(), Points::from_raw(h, hd));
        Ok((NurbsCurve { homogeneous }, t_b))
    }
}

impl NurbsCurve {
    /// The elliptic arc `C + a cos θ X + b sin θ Y`, `θ` from `start_angle` to `end_angle`
    /// (`X`, `Y` the unit axes, `a`, `b` the semi-axes), as an exact rational quadratic on
    /// `[0, 1]`: the image of the circular arc of [`NurbsCurve::circular_arc`] under the affine
    /// map `(cos θ, sin θ) ↦ C + a cos θ X + b sin θ Y` (P&T §7.5: NURBS are invariant under
    /// affine maps, which act on the control points with the weights unchanged). The angle `θ`
    /// is the eccentric angle of ISO 10303-42 `ellipse` (§4.4.17), not the polar angle.
    ///
    /// ```
    /// use lekalo::NurbsCurve;
    /// use std::f64::consts::TAU;
    /// let e = NurbsCurve::elliptic_arc(&[1.0, 2.0], &[0.0, 1.0], &[-1.0, 0.0], 3.0, 1.0, 0.0, TAU)?;
    /// for k in 0..=64 {
    ///     let p = e.eval(k as f64 / 64.0)?;
    ///     // in the frame: u along (0, 1), v along (−1, 0)
    ///     let (u, v) = (p[1] - 2.0, -(p[0] - 1.0));
    ///     assert!(((u / 3.0).powi(2) + v.powi(2) - 1.0).abs() < 1e-14);
    /// }
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// As [`NurbsCurve::circular_arc`], with both semi-axes checked as the radius.
    pub fn elliptic_arc(
        center: &[f64],
        x_axis: &[f64],
        y_axis: &[f64],
        semi_x: f64,
        semi_y: f64,
        start_angle: f64,
        end_angle: f64,
    ) -> Result<Self> {
        let (x, y) = arc_frame(center, x_axis, y_axis)?;
        check_radius(semi_x)?;
        check_radius(semi_y)?;
        check_finite("start_angle", &[start_angle])?;
        check_finite("end_angle", &[end_angle])?;
        let sweep = end_angle - start_angle;
        let full = std::f64::consts::TAU;
        if sweep == 0.0 || sweep.abs() > full * (1.0 + ARC_SWEEP_SLACK) {
            return Err(Error::InvalidArgument {
                what: "arc angles".into(),
                reason: format!(
                    "the sweep end_angle − start_angle = {sweep} must be non-zero and at most 2π \
                     in magnitude"
                ),
            });
        }
        let closed = sweep.abs() >= full;
        let sweep = sweep.clamp(-full, full);
        let xa: Vec<f64> = x.iter().map(|v| v * semi_x).collect();
        let yb: Vec<f64> = y.iter().map(|v| v * semi_y).collect();
        let homogeneous = arc_homogeneous(center, &xa, &yb, 1.0, start_angle, sweep, closed)?;
        Ok(NurbsCurve { homogeneous })
    }

    /// The full ellipse `C + a cos θ X + b sin θ Y`, `θ ∈ [0, 2π]`: [`NurbsCurve::elliptic_arc`]
    /// over a full turn (nine control points, four 90° pieces).
    ///
    /// # Errors
    /// As [`NurbsCurve::elliptic_arc`].
    pub fn ellipse(
        center: &[f64],
        x_axis: &[f64],
        y_axis: &[f64],
        semi_x: f64,
        semi_y: f64,
    ) -> Result<Self> {
        Self::elliptic_arc(
            center,
            x_axis,
            y_axis,
            semi_x,
            semi_y,
            0.0,
            std::f64::consts::TAU,
        )
    }
}

impl BSplineCurve {
    /// The straight segment `P + t D`, `t ∈ [t0, t1]`, as a linear B-spline on the same
    /// parameter (control points `P + t0 D`, `P + t1 D`, knots `[t0, t0, t1, t1]`): the line of
    /// ISO 10303-42 §4.4.14 restricted to a trim, exact (a degree-1 B-spline is the linear
    /// interpolant of its control points, P&T §2.2).
    ///
    /// ```
    /// use lekalo::BSplineCurve;
    /// let l = BSplineCurve::line_segment(&[1.0, 0.0, 0.0], &[0.0, 2.0, 0.0], -1.0, 3.0)?;
    /// assert_eq!(l.domain(), (-1.0, 3.0));
    /// assert_eq!(l.eval(0.5)?, vec![1.0, 1.0, 0.0]);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::Dimension`] if `point` and `direction` differ in length or are empty;
    /// [`Error::NonFinite`]; [`Error::InvalidArgument`] for a zero direction;
    /// [`Error::EmptyDomain`] or [`Error::KnotsNotSorted`] unless `t0 < t1`.
    pub fn line_segment(point: &[f64], direction: &[f64], t0: f64, t1: f64) -> Result<Self> {
        if point.is_empty() || direction.len() != point.len() {
            return Err(Error::Dimension {
                what: "line direction".into(),
                expected: point.len().max(1),
                got: direction.len(),
            });
        }
        check_finite("line point", point)?;
        check_finite("line direction", direction)?;
        check_finite("line parameters", &[t0, t1])?;
        if norm2(direction) == 0.0 {
            return Err(Error::InvalidArgument {
                what: "line direction".into(),
                reason: "the direction is the zero vector; give the direction of the line".into(),
            });
        }
        let mut data = Vec::with_capacity(2 * point.len());
        for t in [t0, t1] {
            data.extend(point.iter().zip(direction).map(|(p, d)| p + t * d));
        }
        BSplineCurve::new(
            1,
            vec![t0, t0, t1, t1],
            Points::from_flat(point.len(), data)?,
        )
    }
}

/// Number of pieces of at most 90° for a sweep (a sweep that exceeds k·90° by rounding only
/// still takes k pieces).
fn arc_pieces(sweep: f64) -> usize {
    let quarters = sweep.abs() / std::f64::consts::FRAC_PI_2 * (1.0 - 4.0 * f64::EPSILON);
    if quarters <= 1.0 {
        1
    } else if quarters <= 2.0 {
        2
    } else if quarters <= 3.0 {
        3
    } else {
        4
    }
}

/// Parameter in `[0, 1]` of the point at angle `theta ∈ [0, sweep]` (`sweep > 0`) of the arc
/// built by [`arc_homogeneous`]: piece `k = ⌊θ/δ⌋`, angle `φ` from the piece's middle, local
/// parameter `s = (1 + tan(φ/2) / tan(δ/4)) / 2`.
fn arc_parameter(theta: f64, sweep: f64) -> f64 {
    let n = arc_pieces(sweep);
    let nf = n as f64;
    let delta = sweep / nf;
    let mut k = 0;
    while k + 1 < n && theta >= delta * (k + 1) as f64 {
        k += 1;
    }
    let phi = theta - delta * (k as f64 + 0.5);
    let s = 0.5 * (1.0 + (0.5 * phi).tan() / (0.25 * delta).tan());
    ((k as f64 + s.clamp(0.0, 1.0)) / nf).clamp(0.0, 1.0)
}

/// Homogeneous control points and knots of the arc (P&T Algorithm A7.1, with the middle
/// control points in closed form instead of a tangent intersection). `x`, `y` orthonormal,
/// `0 < |sweep| ≤ 2π`.
fn arc_homogeneous(
    center: &[f64],
    x: &[f64],
    y: &[f64],
    radius: f64,
    start: f64,
    sweep: f64,
    closed: bool,
) -> Result<BSplineCurve> {
    let dim = center.len();
    let hd = dim + 1;
    let pieces = arc_pieces(sweep);
    let nf = pieces as f64;
    let weight = (sweep / (2.0 * nf)).cos();
    let mut h = Vec::with_capacity((2 * pieces + 1) * hd);
    let push = |angle: f64, w: f64, h: &mut Vec<f64>| {
        // homogeneous point (w·C + r(cos θ X + sin θ Y), w); the middle point's r/w cancels w
        let (s, c) = angle.sin_cos();
        for k in 0..dim {
            h.push(w * center[k] + radius * (c * x[k] + s * y[k]));
        }
        h.push(w);
    };
    push(start, 1.0, &mut h);
    for i in 0..pieces {
        let fi = i as f64;
        push(
            start + sweep * (2.0 * fi + 1.0) / (2.0 * nf),
            weight,
            &mut h,
        );
        push(start + sweep * (fi + 1.0) / nf, 1.0, &mut h);
    }
    if closed {
        let last = h.len() - hd;
        let first: Vec<f64> = h[..hd].to_vec();
        h[last..].copy_from_slice(&first);
    }
    let mut knots = vec![0.0; 3];
    for i in 1..pieces {
        let k = i as f64 / nf;
        knots.push(k);
        knots.push(k);
    }
    knots.extend_from_slice(&[1.0; 3]);
    // Points::from_flat catches an overflow of r·cos θ + C
    BSplineCurve::new(2, knots, Points::from_flat(hd, h)?)
}

/// Validates the centre and axes of an arc and returns the orthonormal frame `(x̂, ŷ)`.
fn arc_frame(center: &[f64], x_axis: &[f64], y_axis: &[f64]) -> Result<(Vec<f64>, Vec<f64>)> {
    check_arc_dims(
        "arc centre",
        center.len(),
        &[("x_axis", x_axis), ("y_axis", y_axis)],
    )?;
    check_finite("arc centre", center)?;
    check_finite("x_axis", x_axis)?;
    check_finite("y_axis", y_axis)?;
    let unit = |v: &[f64], what: &'static str| -> Result<Vec<f64>> {
        let n = norm2(v);
        if !(n > 0.0 && n.is_finite()) {
            return Err(Error::InvalidArgument {
                what: what.into(),
                reason: "the axis is the zero vector; give a direction in the plane of the arc"
                    .into(),
            });
        }
        Ok(v.iter().map(|p| p / n).collect())
    };
    let x = unit(x_axis, "x_axis")?;
    let y = unit(y_axis, "y_axis")?;
    let c = dot(&x, &y);
    if c.abs() > ARC_AXIS_ORTHOGONALITY_TOL {
        return Err(Error::InvalidArgument {
            what: "y_axis".into(),
            reason: format!(
                "the axes must be orthogonal, but the cosine of their angle is {c:e} (more than \
                 {ARC_AXIS_ORTHOGONALITY_TOL:e}); pass y_axis − (x̂·y_axis) x̂"
            ),
        });
    }
    let y = unit(&reject(&y, &x), "y_axis")?;
    Ok((x, y))
}

/// `dim ≥ 2` and all `others` of length `dim`.
fn check_arc_dims(
    first: &'static str,
    dim: usize,
    others: &[(&'static str, &[f64])],
) -> Result<()> {
    if dim < 2 {
        return Err(Error::Dimension {
            what: first.into(),
            expected: 2,
            got: dim,
        });
    }
    for &(what, v) in others {
        if v.len() != dim {
            return Err(Error::Dimension {
                what: what.into(),
                expected: dim,
                got: v.len(),
            });
        }
    }
    Ok(())
}

fn check_radius(radius: f64) -> Result<()> {
    if !(radius > 0.0 && radius.is_finite()) {
        return Err(Error::InvalidArgument {
            what: "radius".into(),
            reason: format!(
                "{radius} is not a positive finite number",
                radius = readable(&radius)
            ),
        });
    }
    Ok(())
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(p, q)| p * q).sum()
}

/// `v − (v·e) e` for a unit vector `e`.
fn reject(v: &[f64], e: &[f64]) -> Vec<f64> {
    let c = dot(v, e);
    v.iter().zip(e).map(|(p, q)| p - c * q).collect()
}

/// `|a ∧ b| = sqrt(Σ_{i<j} (a_i b_j − a_j b_i)²)`: the area of the parallelogram, accurate
/// also for nearly parallel vectors (unlike `sqrt(|a|²|b|² − (a·b)²)`).
fn wedge_norm(a: &[f64], b: &[f64]) -> f64 {
    let mut s = 0.0;
    for i in 0..a.len() {
        for j in i + 1..a.len() {
            let m = a[i] * b[j] - a[j] * b[i];
            s += m * m;
        }
    }
    s.sqrt()
}
