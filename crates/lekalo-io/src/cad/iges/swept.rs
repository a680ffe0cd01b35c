//! IGES swept surfaces as exact NURBS: the ruled surface (entity 118, IGES 5.3 §4.17), the
//! surface of revolution (entity 120, §4.18) and the tabulated cylinder (entity 122, §4.19).
//! They point at curves by their directory
//! entries, so they are built after every entity is read, from the curves as read (each placed
//! by its own matrix, in the parent's definition space), then placed by their own matrix.
//!
//! Entity 120: `L, C, SA, TA`: the axis, a line (entity 110, from its start to its end), the
//! generatrix `C`, turned counterclockwise about the axis from `SA` to `TA` (radians):
//! [`NurbsSurface::revolve`] (P&T §8.5, A8.1). Entity 122: `DE, LX, LY, LZ`: the directrix and
//! the end of the generatrix line from the directrix's start, `S = C(t) + v (L − C(t₀))`,
//! `v ∈ [0, 1]`: [`NurbsSurface::extrude`] (P&T §8.3). Entity 118: `DE1, DE2, DIRFLG, DEVFLG`:
//! the lines between the points of equal relative parameter of the two curves (the second
//! reversed when `DIRFLG = 1`), [`NurbsSurface::ruled`] (P&T §8.2); form 0 asks for points of
//! equal relative arc length, which no NURBS of the two curves gives exactly, and is read by
//! equal relative parameter too (the same surface when both curves' parameters run
//! proportionally to arc length, as for two lines).
//!
//! Their NURBS parametrisation is not IGES's (the angle of 120 becomes the rational arc
//! parameter), so curves given in their parameter space (the boundaries of a trimmed surface)
//! would land elsewhere: when faces are read, these surfaces are listed as skipped with that
//! reason rather than trimmed wrongly.

use std::collections::HashMap;

use lekalo::NurbsSurface;

use crate::shape::{Shape, Surface};

/// A swept surface waiting for the curves it points at.
#[derive(Debug, Clone)]
pub(super) enum Sweep {
    /// Entity 120: axis line and generatrix (directory entries), start and end angles.
    Revolution {
        axis: u64,
        generatrix: u64,
        angles: (f64, f64),
    },
    /// Entity 122: directrix (directory entry) and the generatrix's end point, in millimetres.
    Cylinder { directrix: u64, end: [f64; 3] },
    /// Entity 118: the two curves (directory entries), the second reversed when `DIRFLG = 1`.
    Ruled {
        first: u64,
        second: u64,
        reversed: bool,
    },
}

impl Sweep {
    /// The entity's kind, as the list of skipped entities names it.
    pub(super) fn entity(&self) -> &'static str {
        match self {
            Sweep::Revolution { .. } => "IGES entity 120",
            Sweep::Cylinder { .. } => "IGES entity 122",
            Sweep::Ruled { .. } => "IGES entity 118",
        }
    }

    /// Entity 118, 120 or 122 from its parameters `v` (`DE1, DE2, DIRFLG, DEVFLG`,
    /// `L, C, SA, TA` or `DE, LX, LY, LZ`, read as numbers); pointers that are not directory
    /// entries are named.
    pub(super) fn from_parameters(ty: &str, v: &[f64], unit_mm: f64) -> Result<Sweep, String> {
        let pointer = |k: usize, what: &str| -> Result<u64, String> {
            let x = v[k];
            if x >= 1.0 && x.fract() == 0.0 && x < 1e15 {
                #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
                Ok(x as u64)
            } else {
                Err(format!(
                    "its {what} (parameter {}) is {x}, not a directory entry",
                    k + 1
                ))
            }
        };
        if ty == "118" {
            return Ok(Sweep::Ruled {
                first: pointer(0, "first curve")?,
                second: pointer(1, "second curve")?,
                reversed: v[2] == 1.0,
            });
        }
        if ty == "120" {
            Ok(Sweep::Revolution {
                axis: pointer(0, "axis")?,
                generatrix: pointer(1, "generatrix")?,
                angles: (v[2], v[3]),
            })
        } else {
            Ok(Sweep::Cylinder {
                directrix: pointer(0, "directrix")?,
                end: [v[1] * unit_mm, v[2] * unit_mm, v[3] * unit_mm],
            })
        }
    }

    /// The surface, from the curves read so far (`curves`: directory entry → index into
    /// `shapes`), or why not.
    pub(super) fn build(
        &self,
        shapes: &[(u64, Shape)],
        curves: &HashMap<u64, usize>,
    ) -> Result<Surface, String> {
        let curve = |id: u64, what: &str| -> Result<&lekalo::Curve, String> {
            match curves.get(&id).map(|&k| &shapes[k].1) {
                Some(Shape::Curve(c)) => Ok(c),
                _ => Err(format!(
                    "its {what} D{id} is not a curve lekalo read (entities 100, 104, 110, 112, 126)"
                )),
            }
        };
        let lib = |e: lekalo::Error| e.to_string();
        match *self {
            Sweep::Revolution {
                axis,
                generatrix,
                angles: (sa, ta),
            } => {
                let line = curve(axis, "axis")?;
                let (t0, t1) = line.domain();
                let (a, b) = (line.eval(t0).map_err(lib)?, line.eval(t1).map_err(lib)?);
                let point = to3(&a);
                let dir = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
                let g = curve(generatrix, "generatrix")?.to_nurbs();
                NurbsSurface::revolve(&g, point, dir, sa, ta)
                    .map(Surface::Nurbs)
                    .map_err(lib)
            }
            Sweep::Ruled {
                first,
                second,
                reversed,
            } => {
                let a = curve(first, "first curve")?.to_nurbs();
                let mut b = curve(second, "second curve")?.to_nurbs();
                if reversed {
                    b = b.reverse().map_err(lib)?;
                }
                NurbsSurface::ruled(&a, &b).map(Surface::Nurbs).map_err(lib)
            }
            Sweep::Cylinder { directrix, end } => {
                let c = curve(directrix, "directrix")?;
                let start = to3(&c.eval(c.domain().0).map_err(lib)?);
                let dir = [end[0] - start[0], end[1] - start[1], end[2] - start[2]];
                NurbsSurface::extrude(&c.to_nurbs(), dir, 0.0, 1.0)
                    .map(Surface::Nurbs)
                    .map_err(lib)
            }
        }
    }
}

/// A point of dimension ≤ 3 padded to 3-D.
fn to3(p: &[f64]) -> [f64; 3] {
    [
        p.first().copied().unwrap_or(0.0),
        p.get(1).copied().unwrap_or(0.0),
        p.get(2).copied().unwrap_or(0.0),
    ]
}

#[cfg(test)]
mod tests {
    use super::super::read_iges;
    use crate::shape::{Shape, Surface};

    /// An IGES file of the given entities (type, parameters), each with its own parameter line
    /// and directory entries `2k + 1`, millimetres, no matrices.
    fn file(entities: &[(u32, &str)]) -> String {
        let mut out = format!("{:<72}S{:>7}\n", "swept", 1);
        out += &format!("{:<72}G{:>7}\n", "1H,,1H;;", 1);
        let (mut d, mut p) = (String::new(), String::new());
        let mut line = 1;
        for (k, (ty, params)) in entities.iter().enumerate() {
            let chunks: Vec<&str> = params
                .as_bytes()
                .chunks(64)
                .map(|c| std::str::from_utf8(c).unwrap())
                .collect();
            let seq = 2 * k + 1;
            let first = [ty.to_string(), line.to_string()]
                .into_iter()
                .chain(["0"; 6].map(String::from))
                .chain(["00000000".to_string()]);
            d += &first.map(|f| format!("{f:>8}")).collect::<String>();
            d += &format!("D{seq:>7}\n");
            let second = [
                ty.to_string(),
                "0".into(),
                "0".into(),
                chunks.len().to_string(),
            ]
            .into_iter()
            .chain(["0", "", "", "", "0"].map(String::from));
            d += &second.map(|f| format!("{f:>8}")).collect::<String>();
            d += &format!("D{:>7}\n", seq + 1);
            for c in chunks {
                p += &format!("{c:<64}{seq:>8}P{line:>7}\n");
                line += 1;
            }
        }
        out += &d;
        out += &p;
        let t = format!("S      1G      1D{:>7}P{:>7}", 2 * entities.len(), line - 1);
        out += &format!("{t:<72}T{:>7}\n", 1);
        out
    }

    fn surfaces(text: &str) -> Vec<Surface> {
        let r = read_iges(text, "s.igs").unwrap();
        assert!(r.skipped.is_empty(), "{:?}", r.skipped);
        r.shapes
            .into_iter()
            .filter_map(|(_, s)| match s {
                Shape::Surface(s) => Some(s),
                _ => None,
            })
            .collect()
    }

    /// A segment at distance 2 from the z axis turned a quarter turn about it: every sample at
    /// radius 2, heights along the segment, in the first quadrant.
    #[test]
    fn a_surface_of_revolution_turns_its_generatrix_about_its_axis() {
        let text = file(&[
            (110, "110,0.,0.,0.,0.,0.,5.;"),
            (110, "110,2.,0.,1.,2.,0.,3.;"),
            (120, "120,1,3,0.,1.5707963267948966;"),
        ]);
        let s = surfaces(&text);
        assert_eq!(s.len(), 1);
        let ((u0, u1), (v0, v1)) = s[0].domain();
        for i in 0..=8 {
            for j in 0..=8 {
                let u = u0 + (u1 - u0) * f64::from(i) / 8.0;
                let v = v0 + (v1 - v0) * f64::from(j) / 8.0;
                let p = s[0].eval(u, v).unwrap();
                assert!((p[0].hypot(p[1]) - 2.0).abs() < 1e-14, "{p:?}");
                assert!(p[0] >= -1e-14 && p[1] >= -1e-14, "{p:?}");
                assert!(
                    (p[2] - (1.0 + 2.0 * (v - v0) / (v1 - v0))).abs() < 1e-14,
                    "{p:?}"
                );
            }
        }
    }

    /// A circular arc swept to a point 4 above its start: the cylinder x² + y² = 1, z ∈ [0, 4].
    #[test]
    fn a_tabulated_cylinder_sweeps_its_directrix_to_the_end_point() {
        let text = file(&[(100, "100,0.,0.,0.,1.,0.,0.,1.;"), (122, "122,1,1.,0.,4.;")]);
        let s = surfaces(&text);
        assert_eq!(s.len(), 1);
        let ((u0, u1), _) = s[0].domain();
        for i in 0..=8 {
            for v in [0.0, 0.25, 1.0] {
                let p = s[0].eval(u0 + (u1 - u0) * f64::from(i) / 8.0, v).unwrap();
                assert!((p[0].hypot(p[1]) - 1.0).abs() < 1e-14, "{p:?}");
                assert!((p[2] - 4.0 * v).abs() < 1e-14, "{p:?}");
            }
        }
    }

    /// Two segments, the second reversed (DIRFLG 1): the ruled surface is the planar
    /// quadrilateral between them, its corners the segments' ends joined start to end.
    #[test]
    fn a_ruled_surface_joins_its_curves_by_lines() {
        let text = file(&[
            (110, "110,0.,0.,0.,4.,0.,0.;"),
            (110, "110,4.,3.,1.,0.,3.,1.;"),
            (118, "118,1,3,1,0;"),
        ]);
        let s = surfaces(&text);
        assert_eq!(s.len(), 1);
        let ((u0, u1), (v0, v1)) = s[0].domain();
        let corner = |u: f64, v: f64| s[0].eval(u, v).unwrap();
        assert_eq!(corner(u0, v0), vec![0.0, 0.0, 0.0]);
        assert_eq!(corner(u0, v1), vec![0.0, 3.0, 1.0]);
        assert_eq!(corner(u1, v1), vec![4.0, 3.0, 1.0]);
        let m = corner(0.5 * (u0 + u1), 0.5 * (v0 + v1));
        assert!(
            (m[0] - 2.0).abs() < 1e-14 && (m[1] - 1.5).abs() < 1e-14 && (m[2] - 0.5).abs() < 1e-14
        );
    }

    /// When faces are read, a swept surface is listed as skipped with the reason (its
    /// parametrisation is not IGES's), not made into a face.
    #[test]
    fn faces_are_not_made_on_swept_surfaces() {
        let text = file(&[
            (110, "110,0.,0.,0.,0.,0.,5.;"),
            (110, "110,2.,0.,1.,2.,0.,3.;"),
            (120, "120,1,3,0.,1.5707963267948966;"),
        ]);
        let r = super::super::read_iges_faces(&text, "s.igs", usize::MAX).unwrap();
        assert!(r.faces.is_empty());
        let listed = r.skipped.listed();
        let swept = listed.iter().find(|s| s.entity == "IGES entity 120");
        assert!(
            swept.is_some_and(|s| s.reason.contains("not as the surface of a face")),
            "{listed:?}"
        );
    }

    /// Pointers at nothing, at a surface, or not directory entries: skipped with the reason.
    #[test]
    fn sweeps_of_missing_curves_are_skipped_naming_why() {
        for (entities, want) in [
            (vec![(120, "120,7,9,0.,1.;")], "axis D7 is not a curve"),
            (vec![(122, "122,0.5,1.,0.,4.;")], "not a directory entry"),
            (
                vec![(110, "110,0.,0.,0.,0.,0.,1.;"), (120, "120,1,3,0.,0.;")],
                "generatrix D3",
            ),
        ] {
            let r = read_iges(&file(&entities), "s.igs").unwrap();
            let reason = &r.skipped.listed().first().expect("skipped").reason;
            assert!(reason.contains(want), "{reason}");
        }
    }
}
