//! One mesh of a CAD model's faces: the meshes of its faces bounded by curves
//! ([`lekalo::topology::mesh_faces_each`]) and its faces of triangles (AP242,
//! [`StepTriangulation`]) joined, with the unit normals of their vertices. What `lekalo mesh`
//! writes of a STEP or IGES file and Python's `mesh_faces` returns: both call [`join_cad_mesh`].

use lekalo::query::Mesh;
use lekalo::topology::{join_meshes, FaceMeshes};
use lekalo::{Error, Face, Result};

use crate::StepTriangulation;

/// A mesh of faces and faces of triangles as one ([`join_cad_mesh`]), with the normals of its
/// vertices.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct CadMesh {
    /// The meshes of the faces meshed, in their order, then the faces of triangles, in theirs
    /// ([`lekalo::topology::join_meshes`]; a face of triangles' `uv` all `(0, 0)` and its
    /// deviation 0, [`StepTriangulation::to_mesh`]).
    pub mesh: Mesh,
    /// The unit normal of each vertex of [`CadMesh::mesh`], in its order, or empty when no
    /// vertex has one (only faces of triangles whose file gives no normals): a meshed face's
    /// its surface's exact `S_u × S_v` turned by the face's sense, with the pole fallback
    /// ([`FaceMeshes::surface_normals`], [`lekalo::query::Mesh::surface_normals`]); a face of
    /// triangles' the file's made unit ([`StepTriangulation::vertex_normals`]), `None` for each
    /// of its vertices when the file gives none.
    pub normals: Vec<Option<[f64; 3]>>,
}

/// The meshes of the faces in `meshed` (of the set `faces`, as given to
/// [`lekalo::topology::mesh_faces_each`]; `None` when no face was meshed) and the faces of
/// triangles `triangulations` as one mesh with the unit normals of its vertices
/// ([`CadMesh`]): the faces of triangles join as they are, their triangles the geometry.
///
/// A face of triangles made elsewhere than by the STEP reader (from arrays, in Python) is
/// checked first: 3-D finite points, every triangle's indices among its points, and none, one
/// or a normal per point, each finite.
///
/// # Errors
/// [`Error::InvalidArgument`] naming the face of triangles (its place in `triangulations` and
/// its id) and what is wrong with it; [`Error::Dimension`] when the meshes' points differ in
/// dimension ([`lekalo::topology::join_meshes`]).
pub fn join_cad_mesh(
    meshed: Option<&FaceMeshes>,
    faces: &[&Face],
    triangulations: &[StepTriangulation],
) -> Result<CadMesh> {
    for (k, t) in triangulations.iter().enumerate() {
        check(t).map_err(|reason| Error::InvalidArgument {
            what: "face of triangles".into(),
            reason: format!("{k} (#{}): {reason}", t.id),
        })?;
    }
    let mut normals = meshed.map_or_else(Vec::new, |m| m.surface_normals(faces));
    for t in triangulations {
        let n = t.vertex_normals();
        if n.is_empty() {
            normals.extend(std::iter::repeat_n(None, t.vertices.len()));
        } else {
            normals.extend(n);
        }
    }
    if normals.iter().all(Option::is_none) {
        normals.clear();
    }
    let tessellated: Vec<Mesh> = triangulations
        .iter()
        .map(StepTriangulation::to_mesh)
        .collect();
    let faces_meshed = meshed
        .into_iter()
        .flat_map(|m| m.meshes.iter().map(|(_, m)| m));
    let mesh = join_meshes(faces_meshed.chain(&tessellated))?;
    Ok(CadMesh { mesh, normals })
}

/// What is wrong with a face of triangles, if anything.
fn check(t: &StepTriangulation) -> std::result::Result<(), String> {
    let n = t.vertices.len();
    if t.vertices.dim() != 3 {
        return Err(format!(
            "its points are {}-D; give 3 coordinates a point",
            t.vertices.dim()
        ));
    }
    if let Some(k) = (0..n).find(|&k| t.vertices.point(k).iter().any(|x| !x.is_finite())) {
        return Err(format!("point {k} is not finite"));
    }
    for (j, tri) in t.triangles.iter().enumerate() {
        if let Some(i) = tri.iter().find(|&&i| i as usize >= n) {
            return Err(format!(
                "triangle {j} has index {i}, past its {n} points (indices run from 0)"
            ));
        }
    }
    if !matches!(t.normals.len(), 0 | 1) && t.normals.len() != n {
        return Err(format!(
            "{} normals for {n} points: give none, one for the whole face or one a point",
            t.normals.len()
        ));
    }
    if let Some(k) = t
        .normals
        .iter()
        .position(|v| v.iter().any(|x| !x.is_finite()))
    {
        return Err(format!("normal {k} is not finite"));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use lekalo::Points;

    fn square(normals: Vec<[f64; 3]>) -> StepTriangulation {
        StepTriangulation {
            id: 7,
            entity: "TRIANGULATED_FACE".into(),
            name: String::new(),
            link: None,
            vertices: Points::from_3d(&[
                [0.0, 0.0, 0.0],
                [1.0, 0.0, 0.0],
                [1.0, 1.0, 0.0],
                [0.0, 1.0, 0.0],
            ])
            .unwrap(),
            triangles: vec![[0, 1, 2], [0, 2, 3]],
            normals,
            dropped: 0,
        }
    }

    #[test]
    fn faces_of_triangles_join_with_the_file_s_normals_or_none() {
        let given = square(vec![[0.0, 0.0, 2.0]]);
        let bare = square(Vec::new());
        let j = join_cad_mesh(None, &[], &[given.clone(), bare.clone()]).unwrap();
        assert_eq!(j.mesh.vertices.len(), 8);
        assert_eq!(
            j.mesh.triangles[2],
            [4, 5, 6],
            "the second's indices moved past the first's"
        );
        assert_eq!(j.normals[..4], vec![Some([0.0, 0.0, 1.0]); 4][..]);
        assert!(j.normals[4..].iter().all(Option::is_none));
        // only faces that give no normals: none at all
        let j = join_cad_mesh(None, &[], &[bare]).unwrap();
        assert!(j.normals.is_empty());
        assert_eq!(j.mesh.deviation, 0.0);
    }

    #[test]
    fn a_face_of_triangles_that_does_not_hold_together_is_named() {
        let mut t = square(Vec::new());
        t.triangles[1] = [0, 2, 4];
        let e = join_cad_mesh(None, &[], &[square(Vec::new()), t]).unwrap_err();
        assert_eq!(
            e.to_string(),
            "invalid face of triangles: 1 (#7): triangle 1 has index 4, past its 4 points \
             (indices run from 0)"
        );
        let e = join_cad_mesh(None, &[], &[square(vec![[0.0, 0.0, 1.0]; 3])]).unwrap_err();
        assert!(e.to_string().contains("3 normals for 4 points"), "{e}");
        let e = join_cad_mesh(None, &[], &[square(vec![[0.0, f64::NAN, 1.0]])]).unwrap_err();
        assert!(e.to_string().contains("normal 0 is not finite"), "{e}");
    }
}
