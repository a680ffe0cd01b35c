//! Wavefront OBJ: tessellated surfaces with normals (written against plain grids) and curves as
//! polylines.

use std::fmt::Write as _;

use lekalo::Points;

use crate::wireframe::Grid;

/// OBJ text of a grid of surface points: vertices `v`, normals `vn` and two triangles per grid
/// cell (`f a//a b//b c//c`, counter-clockwise seen from the normal side when the normals are
/// `∂S/∂u × ∂S/∂v`). `normals` is a grid of the same shape (dimension 3); when `None` the normal
/// at each point is computed from the grid itself by central differences (one-sided at the
/// borders): `n = (P_{i+1,j} − P_{i−1,j}) × (P_{i,j+1} − P_{i,j−1})`, normalised.
///
/// # Errors
/// [`lekalo::Error::LengthMismatch`] if `normals` has another shape than the grid.
pub fn grid_to_obj(grid: &Grid<'_>, normals: Option<&Grid<'_>>) -> lekalo::Result<String> {
    if let Some(n) = normals {
        if n.nu != grid.nu || n.nv != grid.nv || n.dim != 3 {
            return Err(lekalo::Error::LengthMismatch {
                what: "normals grid (same rows and columns as the surface, dimension 3)".into(),
                expected: grid.nu * grid.nv * 3,
                got: n.data.len(),
            });
        }
    }
    let mut s = String::from("# lekalo surface tessellation\n");
    for i in 0..grid.nu {
        for j in 0..grid.nv {
            let p = grid.point3(i, j);
            let _ = writeln!(s, "v {} {} {}", p[0], p[1], p[2]);
        }
    }
    for i in 0..grid.nu {
        for j in 0..grid.nv {
            let n = match normals {
                Some(n) => n.point3(i, j),
                None => grid_normal(grid, i, j),
            };
            let _ = writeln!(s, "vn {} {} {}", n[0], n[1], n[2]);
        }
    }
    let idx = |i: usize, j: usize| i * grid.nv + j + 1;
    for i in 0..grid.nu - 1 {
        for j in 0..grid.nv - 1 {
            let (a, b, c, d) = (idx(i, j), idx(i + 1, j), idx(i + 1, j + 1), idx(i, j + 1));
            let _ = writeln!(s, "f {a}//{a} {b}//{b} {c}//{c}");
            let _ = writeln!(s, "f {a}//{a} {c}//{c} {d}//{d}");
        }
    }
    Ok(s)
}

fn grid_normal(g: &Grid<'_>, i: usize, j: usize) -> [f64; 3] {
    let sub = |a: [f64; 3], b: [f64; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    let du = sub(
        g.point3((i + 1).min(g.nu - 1), j),
        g.point3(i.saturating_sub(1), j),
    );
    let dv = sub(
        g.point3(i, (j + 1).min(g.nv - 1)),
        g.point3(i, j.saturating_sub(1)),
    );
    let n = [
        du[1] * dv[2] - du[2] * dv[1],
        du[2] * dv[0] - du[0] * dv[2],
        du[0] * dv[1] - du[1] * dv[0],
    ];
    let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
    if len > 0.0 {
        [n[0] / len, n[1] / len, n[2] / len]
    } else {
        [0.0, 0.0, 0.0]
    }
}

/// OBJ text of a polyline (a sampled curve): vertices and one `l` element.
#[must_use]
pub fn polyline_to_obj(points: &Points) -> String {
    let mut s = String::from("# lekalo curve polyline\n");
    for p in points.iter() {
        let mut c = [0.0; 3];
        for (k, v) in p.iter().take(3).enumerate() {
            c[k] = *v;
        }
        let _ = writeln!(s, "v {} {} {}", c[0], c[1], c[2]);
    }
    let idx: Vec<String> = (1..=points.len()).map(|i| i.to_string()).collect();
    let _ = writeln!(s, "l {}", idx.join(" "));
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn plane_grid_has_up_normals() {
        // z = 0 plane, u along x, v along y: normals +z
        let mut data = Vec::new();
        for i in 0..3 {
            for j in 0..2 {
                data.extend([f64::from(i), f64::from(j), 0.0]);
            }
        }
        let g = Grid::new(3, 2, 3, &data).unwrap();
        let obj = grid_to_obj(&g, None).unwrap();
        let count = |prefix: &str| obj.lines().filter(|l| l.starts_with(prefix)).count();
        assert_eq!(count("v "), 6);
        assert_eq!(obj.lines().filter(|l| *l == "vn 0 0 1").count(), 6);
        assert_eq!(count("f "), 4);
        assert!(obj.contains("f 1//1 3//3 4//4\n"));
        let bad = Grid::new(2, 2, 3, &data[..12]).unwrap();
        assert!(grid_to_obj(&g, Some(&bad)).is_err());
        let p = Points::from_2d(&[[0.0, 1.0], [2.0, 3.0]]).unwrap();
        assert_eq!(
            polyline_to_obj(&p),
            "# lekalo curve polyline\nv 0 1 0\nv 2 3 0\nl 1 2\n"
        );
    }
}
