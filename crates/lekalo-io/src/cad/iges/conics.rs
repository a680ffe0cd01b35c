//! IGES arcs as exact NURBS: the circular arc (entity 100, IGES 5.3 §4.3) and the conic arc
//! (entity 104, §4.5), both in the plane `z = ZT` of their definition space (the entity's
//! matrix, when it has one, places them as for any curve).
//!
//! Entity 100: `ZT, X1, Y1, X2, Y2, X3, Y3`: the centre `(X1, Y1)`, the start `(X2, Y2)` and the
//! end `(X3, Y3)`, counterclockwise from start to end; a start equal to the end is the full
//! circle. [`NurbsCurve::circular_arc`] builds it (P&T §7.5, A7.1).
//!
//! Entity 104: `A, B, C, D, E, F, ZT, X1, Y1, X2, Y2`: the conic
//! `A x² + B xy + C y² + D x + E y + F = 0` and the arc's start and end on it. Which conic it
//! is follows from the coefficients (`B² − 4AC` negative, zero or positive: ellipse, parabola,
//! hyperbola), not from the form number, which only repeats it. An ellipse is brought to its
//! centre and principal axes and built by [`NurbsCurve::elliptic_arc`], counterclockwise (a
//! start equal to the end is the full ellipse); a parabola or hyperbola arc is the rational
//! quadratic Bézier `(P0, w P1, P2)` with `P1` the meeting point of the end tangents and `w`
//! read off the conic's point `S` on the segment from `M = (P0 + P2) / 2` to `P1`,
//! `S = M + s (P1 − M)`, `w = s / (1 − s)` (P&T §7.3, eq. 7.8: the shoulder point).

use lekalo::{NurbsCurve, Points};

use crate::object::Object;
use crate::shape::Shape;

fn lib(e: &lekalo::Error) -> String {
    e.to_string()
}

/// Entity 100 as a degree-2 NURBS on `[0, 1]` from its parameters `ZT, X1, Y1, X2, Y2, X3, Y3`
/// (`v`, in the file's unit); coordinates times `unit_mm`.
pub(super) fn circular_arc(v: &[f64], unit_mm: f64) -> Result<Shape, String> {
    let v: Vec<f64> = v.iter().map(|x| x * unit_mm).collect();
    let (z, c, a, b) = (v[0], [v[1], v[2]], [v[3], v[4]], [v[5], v[6]]);
    let r = (a[0] - c[0]).hypot(a[1] - c[1]);
    let scale = r.max(c[0].abs()).max(c[1].abs()).max(f64::MIN_POSITIVE);
    if r <= 1e-14 * scale {
        return Err(format!(
            "its start ({}, {}) is its centre: a circle of radius 0",
            a[0], a[1]
        ));
    }
    let a0 = (a[1] - c[1]).atan2(a[0] - c[0]);
    let full = (b[0] - a[0]).hypot(b[1] - a[1]) <= 1e-12 * scale;
    let a1 = if full {
        a0 + std::f64::consts::TAU
    } else {
        counterclockwise(a0, (b[1] - c[1]).atan2(b[0] - c[0]))
    };
    let centre = [c[0], c[1], z];
    let arc = NurbsCurve::circular_arc(&centre, &[1.0, 0.0, 0.0], &[0.0, 1.0, 0.0], r, a0, a1)
        .map_err(|e| lib(&e))?;
    Ok(Shape::Curve(Object::Nurbs(arc)))
}

/// The angle `a1 + 2πk` just above `a0` (the end of a counterclockwise sweep from `a0`).
fn counterclockwise(a0: f64, mut a1: f64) -> f64 {
    while a1 <= a0 {
        a1 += std::f64::consts::TAU;
    }
    a1
}

/// Entity 104 as a degree-2 NURBS from its parameters `A, B, C, D, E, F, ZT, X1, Y1, X2, Y2`
/// (`v`, in the file's unit); coordinates times `unit_mm`.
pub(super) fn conic_arc(v: &[f64], unit_mm: f64) -> Result<Shape, String> {
    let k = &v[..6];
    let v: Vec<f64> = v[6..].iter().map(|x| x * unit_mm).collect();
    // the coefficients in millimetres: x_file = x_mm / u
    let u = unit_mm;
    let (a, b, c) = (k[0] / (u * u), k[1] / (u * u), k[2] / (u * u));
    let (d, e, g) = (k[3] / u, k[4] / u, k[5]);
    let conic = Conic {
        a,
        b,
        c,
        d,
        e,
        f: g,
    };
    let (z, p0, p2) = (v[0], [v[1], v[2]], [v[3], v[4]]);
    let disc = b * b - 4.0 * a * c;
    let size = b * b + 4.0 * (a * c).abs();
    if (a == 0.0 && b == 0.0 && c == 0.0) || !size.is_finite() {
        return Err("its coefficients A, B, C are all 0 (or not finite): not a conic".into());
    }
    let curve = if disc < -1e-12 * size {
        conic.ellipse_arc(p0, p2, z)?
    } else {
        conic.open_arc(p0, p2, z)?
    };
    Ok(Shape::Curve(Object::Nurbs(curve)))
}

/// `A x² + B xy + C y² + D x + E y + F`.
struct Conic {
    a: f64,
    b: f64,
    c: f64,
    d: f64,
    e: f64,
    f: f64,
}

impl Conic {
    fn value(&self, p: [f64; 2]) -> f64 {
        let [x, y] = p;
        self.a * x * x + self.b * x * y + self.c * y * y + self.d * x + self.e * y + self.f
    }

    fn gradient(&self, p: [f64; 2]) -> [f64; 2] {
        let [x, y] = p;
        [
            2.0 * self.a * x + self.b * y + self.d,
            self.b * x + 2.0 * self.c * y + self.e,
        ]
    }

    /// An ellipse: its centre (where the gradient vanishes), principal axes (the eigenvectors
    /// of `[[A, B/2], [B/2, C]]`) and semi-axes `√(−F′/λ)`, `F′` the value at the centre; the
    /// arc counterclockwise by eccentric angle.
    fn ellipse_arc(&self, p0: [f64; 2], p2: [f64; 2], z: f64) -> Result<NurbsCurve, String> {
        let det = 4.0 * self.a * self.c - self.b * self.b;
        let centre = [
            (self.b * self.e - 2.0 * self.c * self.d) / det,
            (self.b * self.d - 2.0 * self.a * self.e) / det,
        ];
        let fc = self.value(centre);
        // eigen-decomposition of the symmetric 2 × 2 form (closed form: the rotation angle)
        let theta = 0.5 * self.b.atan2(self.a - self.c);
        let (s, co) = theta.sin_cos();
        let x_axis = [co, s];
        let y_axis = [-s, co];
        let l1 = self.a * co * co + self.b * co * s + self.c * s * s;
        let l2 = self.a * s * s - self.b * co * s + self.c * co * co;
        if !(fc * l1 < 0.0 && fc * l2 < 0.0) {
            return Err(format!(
                "its coefficients describe no real ellipse (the value at the centre, {fc:e}, has the sign of the form's eigenvalues {l1:e}, {l2:e})"
            ));
        }
        let (sa, sb) = ((-fc / l1).sqrt(), (-fc / l2).sqrt());
        let angle = |p: [f64; 2]| {
            let (dx, dy) = (p[0] - centre[0], p[1] - centre[1]);
            ((dx * y_axis[0] + dy * y_axis[1]) / sb).atan2((dx * x_axis[0] + dy * x_axis[1]) / sa)
        };
        self.on_conic(p0, "start", sa.max(sb))?;
        self.on_conic(p2, "end", sa.max(sb))?;
        let t0 = angle(p0);
        let scale = sa.max(sb).max(centre[0].abs()).max(centre[1].abs());
        let full = (p2[0] - p0[0]).hypot(p2[1] - p0[1]) <= 1e-12 * scale;
        let t1 = if full {
            t0 + std::f64::consts::TAU
        } else {
            counterclockwise(t0, angle(p2))
        };
        NurbsCurve::elliptic_arc(
            &[centre[0], centre[1], z],
            &[x_axis[0], x_axis[1], 0.0],
            &[y_axis[0], y_axis[1], 0.0],
            sa,
            sb,
            t0,
            t1,
        )
        .map_err(|e| lib(&e))
    }

    /// A point that should lie on the conic: `|Q(p)| / |∇Q(p)|`, the distance to first order,
    /// within `1e-6` of the conic's size.
    fn on_conic(&self, p: [f64; 2], what: &str, size: f64) -> Result<(), String> {
        let [gx, gy] = self.gradient(p);
        let dist = self.value(p).abs() / gx.hypot(gy);
        if dist <= 1e-6 * size.max(p[0].abs()).max(p[1].abs()) {
            Ok(())
        } else {
            Err(format!(
                "its {what} point ({}, {}) is {dist:e} off the conic",
                p[0], p[1]
            ))
        }
    }

    /// A parabola or hyperbola arc: one rational quadratic Bézier piece.
    fn open_arc(&self, p0: [f64; 2], p2: [f64; 2], z: f64) -> Result<NurbsCurve, String> {
        let size = (p2[0] - p0[0]).hypot(p2[1] - p0[1]);
        if size == 0.0 {
            return Err("its start and end are the same point: an empty arc".into());
        }
        self.on_conic(p0, "start", size)?;
        self.on_conic(p2, "end", size)?;
        // tangents: perpendicular to the gradients; P1 = P0 + s t0 = P2 + r t2
        let (g0, g2) = (self.gradient(p0), self.gradient(p2));
        let (t0, t2) = ([-g0[1], g0[0]], [-g2[1], g2[0]]);
        let cross = t0[0] * t2[1] - t0[1] * t2[0];
        let norms = t0[0].hypot(t0[1]) * t2[0].hypot(t2[1]);
        if cross.abs() <= 1e-12 * norms {
            return Err(
                "the tangents at its start and end are parallel: not an arc of one branch".into(),
            );
        }
        let (dx, dy) = (p2[0] - p0[0], p2[1] - p0[1]);
        let s = (dx * t2[1] - dy * t2[0]) / cross;
        let p1 = [p0[0] + s * t0[0], p0[1] + s * t0[1]];
        // the shoulder point: Q(M + s (P1 − M)) = 0 for s in (0, 1), a quadratic in s
        let m = [(p0[0] + p2[0]) / 2.0, (p0[1] + p2[1]) / 2.0];
        let dir = [p1[0] - m[0], p1[1] - m[1]];
        let qa = self.a * dir[0] * dir[0] + self.b * dir[0] * dir[1] + self.c * dir[1] * dir[1];
        let [gx, gy] = self.gradient(m);
        let qb = gx * dir[0] + gy * dir[1];
        let qc = self.value(m);
        let shoulder = quadratic_roots(qa, qb, qc)
            .into_iter()
            .flatten()
            .filter(|s| *s > 0.0 && *s < 1.0)
            .fold(None, |best: Option<f64>, s| {
                Some(best.map_or(s, |b: f64| if (s - 0.5).abs() < (b - 0.5).abs() { s } else { b }))
            })
            .ok_or("no point of the conic lies between its chord and its tangents: the start and end are on different branches")?;
        let w = shoulder / (1.0 - shoulder);
        let ctrl = Points::from_3d(&[[p0[0], p0[1], z], [p1[0], p1[1], z], [p2[0], p2[1], z]])
            .map_err(|e| lib(&e))?;
        NurbsCurve::new(
            2,
            vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
            ctrl,
            vec![1.0, w, 1.0],
        )
        .map_err(|e| lib(&e))
    }
}

/// The real roots of `a s² + b s + c` (a linear equation when `a` is 0 relative to the
/// others), by the cancellation-free formula `q = −(b + sign(b) √Δ) / 2`, roots `q / a`, `c / q`.
fn quadratic_roots(a: f64, b: f64, c: f64) -> [Option<f64>; 2] {
    if a.abs() <= 1e-14 * (b.abs() + c.abs()) {
        return [(b != 0.0).then(|| -c / b), None];
    }
    let disc = b * b - 4.0 * a * c;
    if disc < 0.0 {
        return [None, None];
    }
    let q = -0.5 * (b + b.signum() * disc.sqrt());
    if q == 0.0 {
        return [Some(0.0), None];
    }
    [Some(q / a), Some(c / q)]
}

#[cfg(test)]
mod tests {
    use super::super::read_iges;
    use super::super::tests::one_entity;
    use crate::object::Object;
    use crate::shape::Shape;
    use lekalo::NurbsCurve;

    fn read_one(ty: u32, params: &str) -> NurbsCurve {
        let r = read_iges(&one_entity("1H,,1H;;", ty, params), "a.igs").unwrap();
        assert!(r.skipped.is_empty(), "{:?}", r.skipped);
        match r.shapes.as_slice() {
            [(_, Shape::Curve(Object::Nurbs(c)))] => c.clone(),
            other => panic!("{other:?}"),
        }
    }

    /// The reason an arc was skipped (the file read, the entity listed as skipped).
    fn skip_reason(ty: u32, params: &str) -> String {
        let r = read_iges(&one_entity("1H,,1H;;", ty, params), "a.igs").unwrap();
        assert!(r.shapes.is_empty());
        r.skipped.listed().first().expect("skipped").reason.clone()
    }

    fn samples(c: &NurbsCurve) -> Vec<Vec<f64>> {
        let (t0, t1) = c.domain();
        (0..=64)
            .map(|k| c.eval(t0 + (t1 - t0) * f64::from(k) / 64.0).unwrap())
            .collect()
    }

    /// A quarter circle about (1, 2) at z = 3, counterclockwise from (3, 2) to (1, 4): every
    /// sample at radius 2 in the plane, in the first quadrant of the centre, ends exact.
    #[test]
    fn circular_arc_is_the_counterclockwise_arc() {
        let c = read_one(100, "100,3.,1.,2.,3.,2.,1.,4.;");
        for p in samples(&c) {
            assert!(
                ((p[0] - 1.0).hypot(p[1] - 2.0) - 2.0).abs() < 1e-14,
                "{p:?}"
            );
            assert!(
                p[0] >= 1.0 - 1e-14 && p[1] >= 2.0 - 1e-14 && (p[2] - 3.0).abs() < 1e-14,
                "{p:?}"
            );
        }
        let (t0, t1) = c.domain();
        let (a, b) = (c.eval(t0).unwrap(), c.eval(t1).unwrap());
        assert!((a[0] - 3.0).abs() < 1e-15 && (a[1] - 2.0).abs() < 1e-15);
        assert!((b[0] - 1.0).abs() < 1e-14 && (b[1] - 4.0).abs() < 1e-14);
        // from (1, 4) to (3, 2) counterclockwise is the other three quarters
        let c = read_one(100, "100,3.,1.,2.,1.,4.,3.,2.;");
        let lower = samples(&c).iter().filter(|p| p[1] < 2.0 - 1e-9).count();
        assert!(lower > 20, "{lower}");
    }

    /// Start equal to end: the full circle, closed, through every quadrant.
    #[test]
    fn a_circle_whose_start_is_its_end_is_full() {
        let c = read_one(100, "100,0.,0.,0.,5.,0.,5.,0.;");
        let s = samples(&c);
        assert!((s[0][0] - s[64][0]).abs() < 1e-14 && (s[0][1] - s[64][1]).abs() < 1e-14);
        for (q, p) in [(16, [0.0, 5.0]), (32, [-5.0, 0.0]), (48, [0.0, -5.0])] {
            let d = (s[q][0] - p[0]).hypot(s[q][1] - p[1]);
            assert!(d < 5.0, "{q}: {:?}", s[q]);
        }
        assert!(s.iter().all(|p| (p[0].hypot(p[1]) - 5.0).abs() < 1e-13));
    }

    /// An ellipse x²/9 + y²/4 = 1 rotated by 30°, written with its B term, from its vertex on
    /// the major axis to its co-vertex: every sample on the conic, counterclockwise.
    #[test]
    fn rotated_ellipse_arc_lies_on_the_conic() {
        let (a2, b2) = (9.0f64, 4.0f64);
        let (s, c) = (
            std::f64::consts::FRAC_PI_6.sin(),
            std::f64::consts::FRAC_PI_6.cos(),
        );
        // x' = c x + s y, y' = −s x + c y; x'²/a² + y'²/b² − 1 = 0
        let qa = c * c / a2 + s * s / b2;
        let qb = 2.0 * c * s / a2 - 2.0 * c * s / b2;
        let qc = s * s / a2 + c * c / b2;
        let start = [3.0 * c, 3.0 * s];
        let end = [-2.0 * s, 2.0 * c];
        let params = format!(
            "104,{qa:e},{qb:e},{qc:e},0.,0.,-1.,0.5,{},{},{},{};",
            start[0], start[1], end[0], end[1]
        );
        let arc = read_one(104, &params);
        for p in samples(&arc) {
            let q = qa * p[0] * p[0] + qb * p[0] * p[1] + qc * p[1] * p[1] - 1.0;
            assert!(q.abs() < 1e-13, "{p:?}: {q}");
            // the first quadrant of the rotated frame
            let (xr, yr) = (c * p[0] + s * p[1], -s * p[0] + c * p[1]);
            assert!(
                xr >= -1e-12 && yr >= -1e-12 && (p[2] - 0.5).abs() < 1e-15,
                "{p:?}"
            );
        }
    }

    /// A parabola y = x² / 4 (A = 1, E = −4) from (−2, 1) to (4, 4) and a hyperbola
    /// x² − y² = 1 from (1, 0) to (√5, 2): one rational quadratic piece each, on the conic.
    #[test]
    fn parabola_and_hyperbola_arcs_lie_on_the_conic() {
        let arc = read_one(104, "104,1.,0.,0.,0.,-4.,0.,0.,-2.,1.,4.,4.;");
        assert!(
            (arc.weights()[1] - 1.0).abs() < 1e-14,
            "{:?}",
            arc.weights()
        );
        for p in samples(&arc) {
            assert!((p[0] * p[0] / 4.0 - p[1]).abs() < 1e-13, "{p:?}");
        }
        let x = 5.0f64.sqrt();
        let arc = read_one(104, &format!("104,1.,0.,-1.,0.,0.,-1.,0.,1.,0.,{x},2.;"));
        assert!(arc.weights()[1] > 1.0);
        let s = samples(&arc);
        for p in &s {
            assert!((p[0] * p[0] - p[1] * p[1] - 1.0).abs() < 1e-12, "{p:?}");
        }
        assert!((s[64][0] - x).abs() < 1e-14 && (s[64][1] - 2.0).abs() < 1e-14);
    }

    /// In a file in inches, coordinates and the conic's coefficients are both converted: the
    /// ellipse x²/4 + y² = 1 (inches) has semi-axes 50.8 and 25.4 mm, and a unit circle 25.4.
    #[test]
    fn arcs_are_read_in_millimetres() {
        let inches = format!("1H,,1H;{}1.,1,2HIN;", ",".repeat(11));
        let read = |ty: u32, params: &str| {
            let r = read_iges(&one_entity(&inches, ty, params), "in.igs").unwrap();
            assert_eq!(r.scale_to_mm, 25.4);
            match r.shapes.as_slice() {
                [(_, Shape::Curve(Object::Nurbs(c)))] => c.clone(),
                other => panic!("{other:?}"),
            }
        };
        let e = read(104, "104,0.25,0.,1.,0.,0.,-1.,0.,2.,0.,0.,1.;");
        for p in samples(&e) {
            let q = (p[0] / 50.8).powi(2) + (p[1] / 25.4).powi(2) - 1.0;
            assert!(q.abs() < 1e-13, "{p:?}");
        }
        let c = read(100, "100,0.,0.,0.,1.,0.,1.,0.;");
        assert!(samples(&c)
            .iter()
            .all(|p| (p[0].hypot(p[1]) - 25.4).abs() < 1e-12));
    }

    #[test]
    fn arcs_that_are_no_arcs_are_skipped_naming_why() {
        let e = skip_reason(100, "100,0.,1.,1.,1.,1.,2.,2.;");
        assert!(e.contains("radius 0"), "{e}");
        let e = skip_reason(104, "104,0.,0.,0.,1.,1.,0.,0.,0.,0.,1.,1.;");
        assert!(e.contains("not a conic"), "{e}");
        let e = skip_reason(104, "104,1.,0.,1.,0.,0.,1.,0.,1.,0.,0.,1.;");
        assert!(e.contains("no real ellipse"), "{e}");
        let e = skip_reason(104, "104,1.,0.,4.,0.,0.,-4.,0.,3.,0.,0.,1.;");
        assert!(e.contains("off the conic"), "{e}");
        // the two branches of x² − y² = 1
        let e = skip_reason(104, "104,1.,0.,-1.,0.,0.,-1.,0.,1.,0.,-1.,0.;");
        assert!(e.contains("parallel"), "{e}");
        // a missing number is a syntax error of the file, naming the entity
        let e = read_iges(&one_entity("1H,,1H;;", 100, "100,0.,0.,0.,1.;"), "a.igs")
            .unwrap_err()
            .to_string();
        assert!(e.contains("entity 100"), "{e}");
    }
}
