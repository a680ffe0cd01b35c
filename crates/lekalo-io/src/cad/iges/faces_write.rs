//! Faces written to IGES as trimmed surfaces (entity 144, IGES 5.3 §4.34): the surface as
//! entity 128, each loop a curve on a parametric surface (entity 142, §4.32) whose model-space
//! curve (`CPTR`) and parameter-space curve (`BPTR`) are composite curves (entity 102, §4.4) of
//! one rational B-spline curve (entity 126) per edge, or that curve itself for a loop of one
//! edge. Parameter-space curves are written with `z = 0` in the surface's parameters; `PREF` is 0
//! (both representations given). A loop with an edge without a pcurve has `BPTR = 0`.
//!
//! The referenced entities are marked physically dependent (status `01`), the parameter-space
//! curves with use flag `05` (2-D parametric), so that readers take the 144s as the file's
//! roots. IGES shares no edges between trimmed surfaces and has no orientation flag: each face
//! has its own curves, and the face's normal is its surface's (read back, `same_sense` is true).

use lekalo::topology::Loop;

use super::IgesWriter;
use crate::error::{IoError, IoResult};
use crate::step_read::StepFace;

/// Status numbers (IGES 5.3 §2.2.4.4.9): physically dependent geometry, and physically dependent
/// 2-D parametric geometry.
const DEPENDENT: &str = "00010000";
const PARAMETRIC: &str = "00010500";

impl IgesWriter {
    /// Writes `faces` as trimmed surfaces (see the module docs).
    ///
    /// ```
    /// let text = "ISO-10303-21;HEADER;ENDSEC;DATA;
    /// #1=CARTESIAN_POINT('',(0.,0.,0.));#2=DIRECTION('',(0.,0.,1.));#3=DIRECTION('',(1.,0.,0.));
    /// #4=AXIS2_PLACEMENT_3D('',#1,#2,#3);#5=PLANE('',#4);#6=CIRCLE('',#4,1.);
    /// #7=CARTESIAN_POINT('',(1.,0.,0.));#8=VERTEX_POINT('',#7);#9=EDGE_CURVE('',#8,#8,#6,.T.);
    /// #10=ORIENTED_EDGE('',*,*,#9,.T.);#11=EDGE_LOOP('',(#10));#12=FACE_OUTER_BOUND('',#11,.T.);
    /// #13=ADVANCED_FACE('disc',(#12),#5,.T.);ENDSEC;END-ISO-10303-21;";
    /// let faces = lekalo_io::read_step_faces(text, "disc.step", usize::MAX)?.faces;
    /// let mut w = lekalo_io::IgesWriter::new();
    /// w.add_faces(&faces)?;
    /// let again = lekalo_io::read_iges_faces(&w.finish("disc", "20000101.000000"), "disc.igs", usize::MAX)?;
    /// assert_eq!(again.faces[0].face, faces[0].face);
    /// # Ok::<(), lekalo_io::IoError>(())
    /// ```
    ///
    /// # Errors
    /// [`IoError::Unsupported`] for no faces, or a surface or curve of more than 3 coordinates.
    pub fn add_faces(&mut self, faces: &[StepFace]) -> IoResult<()> {
        if faces.is_empty() {
            return Err(IoError::Unsupported {
                what: "no faces to write".into(),
            });
        }
        for f in faces {
            let s = Self::surface_params(f.face.surface())?;
            let surface = self.push(128, s, DEPENDENT);
            let mut bounds = Vec::with_capacity(1 + f.face.inner().len());
            for lp in f.face.loops() {
                bounds.push(self.boundary(lp, surface)?);
            }
            let mut t: Vec<String> = vec![
                "144".into(),
                surface.to_string(),
                "1".into(),
                (bounds.len() - 1).to_string(),
            ];
            t.extend(bounds.iter().map(usize::to_string));
            self.push(144, t, super::INDEPENDENT);
        }
        Ok(())
    }

    /// Entity 142 of loop `lp` on the surface at directory entry `surface`.
    fn boundary(&mut self, lp: &Loop, surface: usize) -> IoResult<usize> {
        let mut model = Vec::with_capacity(lp.edges().len());
        for e in lp.edges() {
            let t = Self::curve_params(e.curve())?;
            model.push(self.push(126, t, DEPENDENT));
        }
        let cptr = self.composite(&model, DEPENDENT);
        let bptr = if lp.has_pcurves() {
            let mut plane = Vec::with_capacity(lp.edges().len());
            for p in lp.edges().iter().filter_map(|e| e.pcurve()) {
                let t = Self::curve_params(p)?;
                plane.push(self.push(126, t, PARAMETRIC));
            }
            self.composite(&plane, PARAMETRIC)
        } else {
            0
        };
        let t = [
            "142",
            "0",
            &surface.to_string(),
            &bptr.to_string(),
            &cptr.to_string(),
            "0",
        ]
        .map(String::from)
        .to_vec();
        Ok(self.push(142, t, DEPENDENT))
    }

    /// The curve of one piece, or a composite curve (entity 102) of several.
    fn composite(&mut self, pieces: &[usize], status: &'static str) -> usize {
        if let [one] = pieces {
            return *one;
        }
        let mut t: Vec<String> = vec!["102".into(), pieces.len().to_string()];
        t.extend(pieces.iter().map(usize::to_string));
        self.push(102, t, status)
    }
}
