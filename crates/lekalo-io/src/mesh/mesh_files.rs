//! Triangle meshes and polylines as files: Wavefront OBJ, ASCII STL and ASCII PLY of a
//! [`lekalo::query::Mesh`], OBJ of a [`lekalo::query::Polyline`]. The header of each names the
//! proved deviation of the mesh from the surface; facet normals are the library's
//! ([`lekalo::query::Mesh::facet_normal`]), vertex normals when given
//! ([`lekalo::query::Mesh::surface_normals`], [`lekalo::query::Mesh::vertex_normals`]) written
//! as OBJ `vn` and PLY `nx ny nz`.

use std::fmt::Write as _;

use lekalo::query::{Mesh, Polyline};

use crate::error::{IoError, IoResult, Location};

/// A mesh file format.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MeshFormat {
    /// Wavefront OBJ: `v x y z` lines, `vn x y z` lines of the vertex normals given, and
    /// `f i j k` (1-based) faces, `f i//a j//b k//c` where each vertex has a normal.
    Obj,
    /// ASCII STL: one `facet normal … outer loop … endloop endfacet` per triangle.
    Stl,
    /// ASCII PLY: a header, the vertices (with `nx ny nz` when every vertex has a normal), then
    /// `3 i j k` (0-based) faces.
    Ply,
}

impl MeshFormat {
    /// The format of a file extension or `--format` value (`obj`, `stl`, `ply`).
    ///
    /// # Errors
    /// [`IoError::Syntax`] naming the formats for any other name.
    pub fn from_name(name: &str) -> IoResult<MeshFormat> {
        match name.to_ascii_lowercase().as_str() {
            "obj" => Ok(MeshFormat::Obj),
            "stl" => Ok(MeshFormat::Stl),
            "ply" => Ok(MeshFormat::Ply),
            other => Err(IoError::syntax(
                Location::new("--format"),
                format!("\"{other}\" is not a mesh format; use obj, stl or ply"),
            )),
        }
    }
}

/// The text of a 3-D mesh in `format`, without vertex normals ([`mesh_text_with_normals`]).
///
/// # Errors
/// [`IoError::Invalid`] for a mesh whose vertices are not 3-D.
pub fn mesh_text(m: &Mesh, format: MeshFormat) -> IoResult<String> {
    mesh_text_with_normals(m, &[], format)
}

/// The text of a 3-D mesh in `format` with the unit normals of its vertices, `normals[k]` the
/// normal of vertex `k` or `None` (as [`lekalo::query::Mesh::surface_normals`] gives them; an
/// empty slice for none). OBJ: one `vn` line per normal given, in the order of the vertices,
/// and each triangle whose three vertices have one as `f i//a j//b k//c`, the others as
/// `f i j k`. PLY: the properties `nx ny nz` when every vertex has a normal, none otherwise.
/// STL: the facet normals of the triangles, whatever the vertices' (STL has no other).
///
/// # Errors
/// [`IoError::Invalid`] for a mesh whose vertices are not 3-D, or normals neither empty nor
/// one per vertex.
pub fn mesh_text_with_normals(
    m: &Mesh,
    normals: &[Option<[f64; 3]>],
    format: MeshFormat,
) -> IoResult<String> {
    if !normals.is_empty() && normals.len() != m.vertices.len() {
        return Err(IoError::Invalid {
            at: Location::new("mesh"),
            error: lekalo::Error::LengthMismatch {
                what: "vertex normals (one per vertex of the mesh)".into(),
                expected: m.vertices.len(),
                got: normals.len(),
            },
        });
    }
    if m.vertices.dim() != 3 {
        return Err(IoError::Invalid {
            at: Location::new("mesh"),
            error: lekalo::Error::Dimension {
                what: "mesh vertices (meshes are written for 3-D surfaces)".into(),
                expected: 3,
                got: m.vertices.dim(),
            },
        });
    }
    let mut s = String::new();
    match format {
        MeshFormat::Obj => {
            let _ = writeln!(s, "# lekalo mesh: deviation <= {:e}", m.deviation);
            for p in m.vertices.iter() {
                let _ = writeln!(s, "v {} {} {}", p[0], p[1], p[2]);
            }
            // the 1-based `vn` index of each vertex that has a normal
            let mut vn = vec![0_usize; normals.len()];
            let mut next = 0;
            for (k, n) in normals.iter().enumerate() {
                if let Some(n) = n {
                    next += 1;
                    vn[k] = next;
                    let _ = writeln!(s, "vn {} {} {}", n[0], n[1], n[2]);
                }
            }
            for t in &m.triangles {
                let a = t.map(|i| vn.get(i as usize).copied().unwrap_or(0));
                if a.iter().all(|&x| x > 0) {
                    let _ = writeln!(
                        s,
                        "f {}//{} {}//{} {}//{}",
                        t[0] + 1,
                        a[0],
                        t[1] + 1,
                        a[1],
                        t[2] + 1,
                        a[2]
                    );
                } else {
                    let _ = writeln!(s, "f {} {} {}", t[0] + 1, t[1] + 1, t[2] + 1);
                }
            }
        }
        MeshFormat::Stl => {
            s.push_str("solid lekalo\n");
            for (k, t) in m.triangles.iter().enumerate() {
                // a degenerate triangle gets a zero normal, as STL readers expect
                let n = m.facet_normal(k).unwrap_or([0.0; 3]);
                let _ = writeln!(s, "facet normal {} {} {}\n outer loop", n[0], n[1], n[2]);
                for &i in t {
                    let p = m.vertices.point(i as usize);
                    let _ = writeln!(s, "  vertex {} {} {}", p[0], p[1], p[2]);
                }
                s.push_str(" endloop\nendfacet\n");
            }
            s.push_str("endsolid lekalo\n");
        }
        MeshFormat::Ply => {
            let all: Option<Vec<[f64; 3]>> = if normals.is_empty() {
                None
            } else {
                normals.iter().copied().collect()
            };
            let _ = write!(
                s,
                "ply\nformat ascii 1.0\ncomment lekalo mesh, deviation <= {:e}\nelement vertex {}\n\
                 property double x\nproperty double y\nproperty double z\n{}element face {}\n\
                 property list uchar int vertex_indices\nend_header\n",
                m.deviation,
                m.vertices.len(),
                if all.is_some() {
                    "property double nx\nproperty double ny\nproperty double nz\n"
                } else {
                    ""
                },
                m.triangles.len()
            );
            for (k, p) in m.vertices.iter().enumerate() {
                match &all {
                    Some(n) => {
                        let n = n[k];
                        let _ =
                            writeln!(s, "{} {} {} {} {} {}", p[0], p[1], p[2], n[0], n[1], n[2]);
                    }
                    None => {
                        let _ = writeln!(s, "{} {} {}", p[0], p[1], p[2]);
                    }
                }
            }
            for t in &m.triangles {
                let _ = writeln!(s, "3 {} {} {}", t[0], t[1], t[2]);
            }
        }
    }
    Ok(s)
}

/// OBJ text of a polyline within a proved deviation of a curve: `v` lines (coordinates beyond
/// the third dropped, missing ones 0) and one `l` element.
#[must_use]
pub fn polyline_text(poly: &Polyline) -> String {
    let mut s = format!("# lekalo polyline: deviation <= {:e}\n", poly.deviation);
    for p in poly.points.iter() {
        let c: Vec<String> = (0..3)
            .map(|d| p.get(d).copied().unwrap_or(0.0).to_string())
            .collect();
        let _ = writeln!(s, "v {}", c.join(" "));
    }
    s.push('l');
    for i in 1..=poly.points.len() {
        let _ = write!(s, " {i}");
    }
    s.push('\n');
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use lekalo::Points;

    fn square() -> Mesh {
        Mesh {
            vertices: Points::from_3d(&[
                [0.0, 0.0, 0.0],
                [1.0, 0.0, 0.0],
                [1.0, 1.0, 0.0],
                [0.0, 1.0, 0.0],
            ])
            .unwrap(),
            uv: vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]],
            triangles: vec![[0, 1, 2], [0, 2, 3]],
            deviation: 0.5,
        }
    }

    #[test]
    fn every_format_holds_every_vertex_and_face() {
        let m = square();
        let obj = mesh_text(&m, MeshFormat::Obj).unwrap();
        assert_eq!(
            obj.lines().filter(|l| l.starts_with("v ")).count(),
            4,
            "{obj}"
        );
        assert!(obj.contains("f 1 3 4\n"), "1-based faces: {obj}");
        let stl = mesh_text(&m, MeshFormat::Stl).unwrap();
        assert_eq!(
            stl.matches("facet normal 0 0 1\n").count(),
            2,
            "up normals: {stl}"
        );
        let ply = mesh_text(&m, MeshFormat::Ply).unwrap();
        assert!(
            ply.contains("element vertex 4\n") && ply.contains("3 0 2 3\n"),
            "{ply}"
        );
        assert!(obj.starts_with("# lekalo mesh: deviation <= 5e-1"), "{obj}");
    }

    /// Vertex normals: a `vn` line for each vertex that has one, `f i//a …` for the triangles
    /// whose vertices all have one; PLY's `nx ny nz` only when every vertex has one; STL keeps
    /// its facet normals, on the side of the vertices'; normals of the wrong count refused.
    #[test]
    fn vertex_normals_are_written_where_given() {
        let m = square();
        let up = Some([0.0, 0.0, 1.0]);
        let obj = mesh_text_with_normals(&m, &[up, up, up, None], MeshFormat::Obj).unwrap();
        assert_eq!(obj.matches("vn 0 0 1\n").count(), 3, "{obj}");
        assert!(obj.contains("f 1//1 2//2 3//3\n"), "{obj}");
        assert!(obj.contains("f 1 3 4\n"), "vertex 4 has none: {obj}");
        let ply = mesh_text_with_normals(&m, &[up, up, up, None], MeshFormat::Ply).unwrap();
        assert!(!ply.contains("nx"), "not every vertex has one: {ply}");
        let ply = mesh_text_with_normals(&m, &[up; 4], MeshFormat::Ply).unwrap();
        assert!(
            ply.contains("property double nz\nelement face 2\n") && ply.contains("1 1 0 0 0 1\n"),
            "{ply}"
        );
        let stl = mesh_text_with_normals(&m, &[up; 4], MeshFormat::Stl).unwrap();
        assert_eq!(stl, mesh_text(&m, MeshFormat::Stl).unwrap());
        assert_eq!(
            mesh_text_with_normals(&m, &[], MeshFormat::Obj).unwrap(),
            mesh_text(&m, MeshFormat::Obj).unwrap()
        );
        assert!(mesh_text_with_normals(&m, &[up; 3], MeshFormat::Obj).is_err());
    }

    #[test]
    fn formats_by_name_and_2d_refused() {
        assert_eq!(MeshFormat::from_name("STL").unwrap(), MeshFormat::Stl);
        assert!(MeshFormat::from_name("gltf").is_err(), "unknown format");
        let mut m = square();
        m.vertices = Points::from_2d(&[[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]).unwrap();
        assert!(mesh_text(&m, MeshFormat::Obj).is_err(), "2-D vertices");
    }
}
