//! IGES parametric splines in power form: the parametric spline curve (entity 112, IGES 5.3
//! §4.9) and surface (entity 114, §4.11), converted exactly to B-splines by the library
//! ([`BSplineCurve::from_piecewise_polynomial`], [`BSplineSurface::from_power_patches`]).
//!
//! Entity 112: `CTYPE, H, NDIM, N, T(1)…T(N+1)`, then per segment the cubic coefficients
//! `AX BX CX DX AY … DZ` of `X(u) = AX + BX s + CX s² + DX s³`, `s = u − T(i)`, then the
//! terminal derivatives (not needed). Entity 114: `CTYPE, PTYPE, M, N, TU(1)…TU(M+1),
//! TV(1)…TV(N+1)`, then per patch 48 coefficients, 16 for each coordinate in the order
//! `A B C D E F G H K L M N O P Q R` of the monomials `s^a t^b` with `a` fastest; the patches
//! run `v` fastest with `N + 1` per row (the last of each row and the last row describe the
//! far edges and are not patches).

use lekalo::{BSplineCurve, BSplineSurface, PiecewisePolynomial};

use crate::object::Object;
use crate::shape::{Shape, Surface};

/// The number in field `k`, or why not.
type Field<'a> = &'a dyn Fn(usize) -> Result<f64, String>;

/// A count in field `k` (a non-negative integer).
fn count(f: Field<'_>, k: usize, what: &str) -> Result<usize, String> {
    let x = f(k)?;
    if x >= 0.0 && x.fract() == 0.0 && x < 1e12 {
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        Ok(x as usize)
    } else {
        Err(format!("{what} (parameter {k}) is {x}, not a count"))
    }
}

/// `needed` parameters must be present among the `len` of the entity, checked before
/// anything is allocated.
fn check_len(needed: Option<usize>, len: usize, what: &str) -> Result<(), String> {
    match needed {
        Some(n) if n <= len => Ok(()),
        Some(n) => Err(format!(
            "{what} need {n} parameters, the entity has {len}; the counts or the parameter data are wrong"
        )),
        None => Err(format!(
            "{what} need more parameters than any file holds; the counts are wrong"
        )),
    }
}

/// Entity 110 (line, IGES 5.3 §4.13: start `X1 Y1 Z1`, end `X2 Y2 Z2`) as the degree-1
/// B-spline on `[0, 1]`, the entity's own parametrisation; coordinates times `unit_mm`.
pub(super) fn line(f: Field<'_>, unit_mm: f64) -> Result<Shape, String> {
    let p = (1..=3)
        .map(|k| Ok(f(k)? * unit_mm))
        .collect::<Result<Vec<_>, String>>()?;
    let q = (4..=6)
        .map(|k| Ok(f(k)? * unit_mm))
        .collect::<Result<Vec<_>, String>>()?;
    let d: Vec<f64> = q.iter().zip(&p).map(|(a, b)| a - b).collect();
    let c = BSplineCurve::line_segment(&p, &d, 0.0, 1.0).map_err(|e| e.to_string())?;
    Ok(Shape::Curve(Object::BSpline(c)))
}

/// Entity 112 as a 3-D B-spline curve on its own parameter; coordinates times `unit_mm`.
pub(super) fn spline_curve(f: Field<'_>, len: usize, unit_mm: f64) -> Result<Shape, String> {
    let n = count(f, 4, "the number of segments N")?;
    if n == 0 {
        return Err("the number of segments N is 0".into());
    }
    let base = 6 + n;
    check_len(
        n.checked_mul(12).and_then(|c| c.checked_add(base)),
        len,
        &format!("N = {n} segments"),
    )?;
    let breaks = (0..=n).map(|i| f(5 + i)).collect::<Result<Vec<_>, _>>()?;
    let mut coef = Vec::with_capacity(12 * n);
    for j in 0..n {
        for r in 0..4 {
            for d in 0..3 {
                coef.push(f(base + 12 * j + 4 * d + r)? * unit_mm);
            }
        }
    }
    let pp = PiecewisePolynomial::new(breaks, 4, 3, coef).map_err(|e| e.to_string())?;
    let c = BSplineCurve::from_piecewise_polynomial(&pp).map_err(|e| e.to_string())?;
    Ok(Shape::Curve(Object::BSpline(c)))
}

/// Entity 114 as a bicubic B-spline surface on its own parameters; coordinates times
/// `unit_mm`. Neighbouring patches that meet within `resolution_mm` (the file's minimum
/// resolution, 0 for none) are joined ([`BSplineSurface::join_patches_within`]): a file prints
/// each patch's coefficients to a few digits, so patches meant to meet jump by a rounding, and a
/// knot of multiplicity 4 at degree 3 is what neither STEP (ISO 10303-42) nor Open CASCADE
/// accepts. The surface then moves by at most half the resolution.
pub(super) fn spline_surface(
    f: Field<'_>,
    len: usize,
    unit_mm: f64,
    resolution_mm: f64,
) -> Result<Shape, String> {
    let m = count(f, 3, "the number of u segments M")?;
    let n = count(f, 4, "the number of v segments N")?;
    if m == 0 || n == 0 {
        return Err(format!(
            "M = {m}, N = {n}: a grid of patches needs both above 0"
        ));
    }
    let base = 7 + m + n;
    let what = format!("M = {m} × N = {n} patches");
    // patches are stored N + 1 to a row; a file that writes only the M × N patches is read too
    let rows_of = |stride: usize| {
        m.checked_sub(1)
            .and_then(|r| r.checked_mul(stride))
            .and_then(|x| x.checked_add(n))
            .and_then(|x| x.checked_mul(48))
            .and_then(|x| x.checked_add(base))
    };
    let stride = if rows_of(n + 1).is_some_and(|need| need <= len) {
        n + 1
    } else {
        check_len(rows_of(n), len, &what)?;
        n
    };
    let tu = (0..=m).map(|i| f(5 + i)).collect::<Result<Vec<_>, _>>()?;
    let tv = (0..=n)
        .map(|j| f(6 + m + j))
        .collect::<Result<Vec<_>, _>>()?;
    let mut coef = vec![0.0; m * n * 48];
    for i in 0..m {
        for j in 0..n {
            let at = base + 48 * (i * stride + j);
            for d in 0..3 {
                for b in 0..4 {
                    for a in 0..4 {
                        // u^a v^b of coordinate d → (((i·n + j)·4 + a)·4 + b)·3 + d
                        coef[(((i * n + j) * 4 + a) * 4 + b) * 3 + d] =
                            f(at + 16 * d + 4 * b + a)? * unit_mm;
                    }
                }
            }
        }
    }
    let s = BSplineSurface::from_power_patches(&tu, &tv, (4, 4), 3, &coef)
        .map_err(|e| e.to_string())?;
    let (s, _) = s
        .join_patches_within(resolution_mm)
        .map_err(|e| e.to_string())?;
    Ok(Shape::Surface(Surface::BSpline(s)))
}

#[cfg(test)]
mod tests {
    use super::super::read_iges;
    use super::super::tests::one_entity;
    use super::*;

    /// `x` rounded-trip through the IGES number format (the tests write plain decimals).
    fn num(x: f64) -> String {
        format!("{x:?}")
    }

    #[test]
    fn a_line_is_its_segment_on_0_1() {
        let text = one_entity("1H,,1H;;", 110, "110,1.,2.,3.,4.,6.,3.;");
        let r = read_iges(&text, "l.igs").unwrap();
        let Shape::Curve(c) = &r.shapes[0].1 else {
            panic!("110 is a curve")
        };
        assert_eq!(c.domain(), (0.0, 1.0));
        assert_eq!(c.eval(0.5).unwrap(), vec![2.5, 4.0, 3.0]);
        assert_eq!(c.eval(1.0).unwrap(), vec![4.0, 6.0, 3.0]);
    }

    #[test]
    fn parametric_spline_curve_is_read_exactly() {
        // two cubic segments on [1, 2] ∪ [2, 4] meeting with C¹ continuity only, 3-D
        let seg0 = [
            [0.0, 1.0, 0.5, -0.25],
            [1.0, 0.0, 2.0, 1.0],
            [0.5, 0.5, 0.0, 0.0],
        ];
        // values and first derivatives of segment 0 at s = 1, then new second/third terms
        let end = |c: [f64; 4]| (c[0] + c[1] + c[2] + c[3], c[1] + 2.0 * c[2] + 3.0 * c[3]);
        let seg1: Vec<[f64; 4]> = seg0
            .iter()
            .map(|&c| {
                let (v, d) = end(c);
                [v, d, -1.0, 0.125]
            })
            .collect();
        let mut p = vec!["112".into(), "3".into(), "1".into(), "3".into(), "2".into()];
        p.extend([1.0, 2.0, 4.0].map(num));
        for seg in [seg0.to_vec(), seg1.clone()] {
            for c in seg {
                p.extend(c.map(num));
            }
        }
        p.extend([0.0; 12].map(num));
        let text = one_entity("1H,,1H;;", 112, &format!("{};", p.join(",")));
        let r = read_iges(&text, "s.igs").unwrap();
        assert!(r.skipped.is_empty(), "{:?}", r.skipped);
        let Shape::Curve(c) = &r.shapes[0].1 else {
            panic!("112 is a curve")
        };
        assert_eq!(c.domain(), (1.0, 4.0));
        // C¹ at 2: the knot 2 is double
        assert_eq!(c.knots().multiplicity(2.0), 2);
        let pp = |x: f64| -> Vec<f64> {
            let (seg, s): (&[[f64; 4]], f64) = if x < 2.0 {
                (&seg0, x - 1.0)
            } else {
                (&seg1, x - 2.0)
            };
            seg.iter()
                .map(|c| c[0] + s * (c[1] + s * (c[2] + s * c[3])))
                .collect()
        };
        for k in 0..=60 {
            let x = 1.0 + 3.0 * f64::from(k) / 60.0;
            let (got, want) = (c.eval(x).unwrap(), pp(x));
            for (g, w) in got.iter().zip(&want) {
                assert!((g - w).abs() < 1e-14 * 8.0, "at {x}: {got:?} vs {want:?}");
            }
        }
    }

    #[test]
    fn parametric_spline_surface_is_read_exactly_with_its_far_edge_records() {
        // M = 2 × N = 1 patches of X = u-ish, Y = v-ish, Z a bicubic; a gap of 1e-3 in z
        // between the two patch columns stays a gap (a knot of full multiplicity)
        let (tu, tv) = ([0.0, 1.0, 3.0], [0.0, 2.0]);
        let z = |i: usize, a: usize, b: usize| (i * 16 + b * 4 + a) as f64 * 0.01;
        let mut p: Vec<String> = ["114", "3", "1", "2", "1"].map(String::from).to_vec();
        p.extend(tu.map(num));
        p.extend(tv.map(num));
        for i in 0..=2 {
            for j in 0..=1 {
                let mut x = [0.0; 16];
                let mut y = [0.0; 16];
                let mut zz = [0.0; 16];
                if i < 2 && j < 1 {
                    x[0] = tu[i];
                    x[1] = 1.0;
                    y[4] = 1.0;
                    for b in 0..4 {
                        for a in 0..4 {
                            zz[4 * b + a] = z(i, a, b);
                        }
                    }
                }
                for v in x.iter().chain(&y).chain(&zz) {
                    p.push(num(*v));
                }
            }
        }
        let text = one_entity("1H,,1H;;", 114, &format!("{};", p.join(",")));
        let r = read_iges(&text, "s.igs").unwrap();
        let Shape::Surface(s) = &r.shapes[0].1 else {
            panic!("114 is a surface")
        };
        assert_eq!(s.domain(), ((0.0, 3.0), (0.0, 2.0)));
        let want = |u: f64, v: f64| {
            let i = usize::from(u >= 1.0);
            let su = u - tu[i];
            let mut zv = 0.0;
            let (mut vb, mut b) = (1.0, 0);
            while b < 4 {
                let (mut ua, mut a) = (1.0, 0);
                while a < 4 {
                    zv += z(i, a, b) * ua * vb;
                    ua *= su;
                    a += 1;
                }
                vb *= v;
                b += 1;
            }
            [tu[i] + su, v, zv]
        };
        for iu in 0..=30 {
            for iv in 0..=10 {
                let (u, v) = (3.0 * f64::from(iu) / 30.0, 2.0 * f64::from(iv) / 10.0);
                let got = s.eval(u, v).unwrap();
                let w = want(u, v);
                for k in 0..3 {
                    assert!(
                        (got[k] - w[k]).abs() < 1e-13 * 8.0,
                        "({u}, {v}): {got:?} vs {w:?}"
                    );
                }
            }
        }
        // fewer coefficients than the counts need: an error naming them, nothing allocated
        let text = one_entity("1H,,1H;;", 114, "114,3,1,200000,200000,0.,1.;");
        let e = read_iges(&text, "s.igs").unwrap_err().to_string();
        assert!(e.contains("M = 200000 × N = 200000"), "{e}");
    }

    /// Two bicubic patches of the plane `z = 0` over `[0, 1]` and `[1, 2]` in `u`, the second
    /// lifted by 2e-5 (a file's rounding of its coefficients): in a file whose minimum
    /// resolution (Global field 19) is 1e-4 mm they are joined, the knot `u = 1` of
    /// multiplicity 3 at degree 3 and the surface within half the resolution of the patches;
    /// at a resolution of 1e-6 mm the jump is kept (multiplicity 4).
    #[test]
    fn parametric_spline_patches_meeting_within_the_resolution_are_joined() {
        let lift = 2e-5;
        let mut p: Vec<String> = ["114", "3", "1", "2", "1"].map(String::from).to_vec();
        p.extend([0.0, 1.0, 2.0, 0.0, 1.0].map(num));
        for i in 0..=2 {
            for j in 0..=1 {
                let (mut x, mut y, mut z) = ([0.0; 16], [0.0; 16], [0.0; 16]);
                if i < 2 && j < 1 {
                    x[0] = f64::from(u8::try_from(i).unwrap());
                    x[1] = 1.0;
                    y[4] = 1.0;
                    z[0] = if i == 1 { lift } else { 0.0 };
                }
                for v in x.iter().chain(&y).chain(&z) {
                    p.push(num(*v));
                }
            }
        }
        let params = format!("{};", p.join(","));
        let surface = |resolution: &str| {
            let global = format!("1H,,1H;,,,,,,,,,,,1.,2,2HMM,,,,{resolution};");
            let r = read_iges(&one_entity(&global, 114, &params), "s.igs").unwrap();
            let Shape::Surface(Surface::BSpline(s)) = &r.shapes[0].1 else {
                panic!("114 is a B-spline surface")
            };
            s.clone()
        };
        let joined = surface("1.0E-4");
        assert_eq!(joined.knots_u().multiplicity(1.0), 3, "joined at u = 1");
        let mid = joined.eval(1.0, 0.5).unwrap()[2];
        assert!(
            (mid - 0.5 * lift).abs() < 1e-18,
            "the mean of the two sides: {mid}"
        );
        for k in 0..=40 {
            let u = 2.0 * f64::from(k) / 40.0;
            let want = if u < 1.0 { 0.0 } else { lift };
            let got = joined.eval(u, 0.5).unwrap();
            assert!((got[2] - want).abs() <= 0.5 * lift + 1e-18, "{u}: {got:?}");
            assert!(
                (got[0] - u).abs() < 1e-12 && (got[1] - 0.5).abs() < 1e-12,
                "{got:?}"
            );
        }
        let kept = surface("1.0E-6");
        assert_eq!(kept.knots_u().multiplicity(1.0), 4, "the jump is kept");
        let z = kept.eval(1.5, 0.5).unwrap()[2];
        assert!((z - lift).abs() < 1e-18, "the second patch as read: {z}");
    }
}
