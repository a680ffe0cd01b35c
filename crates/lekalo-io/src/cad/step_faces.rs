//! Faces written to STEP (ISO 10303-42 §5.4, the topology of AP214/AP242 boundary
//! representations): each face an `ADVANCED_FACE` over its B-spline surface, bounded by a
//! `FACE_OUTER_BOUND` and `FACE_BOUND`s of `EDGE_LOOP`s of `ORIENTED_EDGE`s; each edge an
//! `EDGE_CURVE` between `VERTEX_POINT`s whose geometry is a `SURFACE_CURVE` (a `SEAM_CURVE` for
//! an edge used twice by one face) holding the 3-D curve and, for each face that uses it, its
//! `PCURVE` in that face's `(u, v)` through a `DEFINITIONAL_REPRESENTATION` in a 2-D parametric
//! context.
//!
//! Edges and vertices shared by faces are written once ([`lekalo::topology::Shell`]) when the
//! faces' curves of the edge are one curve (else each keeps its own `EDGE_CURVE` between the
//! shared vertices). A vertex whose edges' ends differ lies past every end along its curve, so
//! that a reader trimming each edge at the vertex keeps the whole curve; where no point does
//! (edges overlapping along a line at a crossing), each edge there gets a `VERTEX_POINT` of its
//! own at its curve's end (`docs/theory/topology.md`, "The point of a vertex"). The `EDGE_CURVE` runs as the first face that uses it runs it, the other use is an
//! `ORIENTED_EDGE` with orientation `.F.`, and its pcurve is written reversed to run along the
//! edge. Faces that close a volume (every edge used twice, once each way) go into a
//! `CLOSED_SHELL` of a `MANIFOLD_SOLID_BREP` in an `ADVANCED_BREP_SHAPE_REPRESENTATION`; other
//! face sets into an `OPEN_SHELL` of a `SHELL_BASED_SURFACE_MODEL` in a
//! `MANIFOLD_SURFACE_SHAPE_REPRESENTATION`, as CAD systems write them. Face names are kept.
//!
//! Read back by [`crate::read_step_faces`], a face has the same surface, loops, edge curves and
//! pcurves bit for bit, except the curves of a use that runs an edge backwards, which are
//! reversed twice (knots within a rounding unit of the domain).

use std::collections::HashMap;

use lekalo::topology::{Edge, EdgeUse, Shell};
use lekalo::{Curve, Surface};

use crate::error::{IoError, IoResult, Location};
use crate::step::{step_real, step_string, CurveNet, StepWriter, SurfaceNet, CONTEXT_ID};
use crate::step_read::StepFace;
use crate::wireframe::Grid;

fn refs(ids: &[usize]) -> String {
    let v: Vec<String> = ids.iter().map(|i| format!("#{i}")).collect();
    format!("({})", v.join(","))
}

/// The edge of a use.
fn edge_at(faces: &[StepFace], u: EdgeUse) -> Option<&Edge> {
    faces
        .get(u.face)?
        .face
        .loops()
        .nth(u.lp)?
        .edges()
        .get(u.edge)
}

/// Whether two edge curves are one curve, `a` run forwards or (`!same`) backwards: equal at
/// nine parameters spread over their domains within `1e-12` of their size (a curve and its
/// reverse agree to rounding).
fn same_curve(a: &Curve, b: &Curve, same: bool) -> bool {
    let (a0, a1) = a.domain();
    let (b0, b1) = b.domain();
    let mut pairs = Vec::with_capacity(9);
    for k in 0..9 {
        let s = f64::from(k) / 8.0;
        let t = if same { s } else { 1.0 - s };
        // clamped: a0 + (a1 - a0) rounds past a1 on some domains
        let ta = (a0 + (a1 - a0) * s).clamp(a0.min(a1), a0.max(a1));
        let tb = (b0 + (b1 - b0) * t).clamp(b0.min(b1), b0.max(b1));
        match (a.eval(ta), b.eval(tb)) {
            (Ok(p), Ok(q)) => pairs.push((p, q)),
            _ => return false,
        }
    }
    let size = pairs
        .iter()
        .flat_map(|(p, _)| p.iter())
        .fold(0.0f64, |m, x| m.max(x.abs()));
    pairs.iter().all(|(p, q)| {
        p.iter()
            .zip(q)
            .all(|(x, y)| (x - y).abs() <= 1e-12 * size.max(f64::MIN_POSITIVE))
    })
}

fn flag(b: bool) -> &'static str {
    if b {
        ".T."
    } else {
        ".F."
    }
}

impl StepWriter {
    /// Writes `c` (points of `coords` coordinates) without listing it in a geometric set.
    fn write_any_curve(&mut self, c: &Curve, coords: usize) -> IoResult<usize> {
        let knots = c.knots();
        let ctrl = c.control_points();
        let weights = c.weights();
        self.write_curve(
            &CurveNet {
                degree: c.degree(),
                knots: knots.as_slice(),
                points: ctrl.as_view(),
                weights: weights.as_deref(),
            },
            coords,
        )
    }

    /// Writes `s` without listing it in a geometric set.
    fn write_any_surface(&mut self, s: &Surface) -> IoResult<usize> {
        let (ku, kv) = s.knots();
        let ctrl = s.control_points();
        let (nu, nv) = s.net_size();
        let weights = s.weights();
        let net = Grid::new(nu, nv, ctrl.dim(), ctrl.as_slice()).map_err(|e| IoError::Invalid {
            at: Location::new("face").at_field("surface"),
            error: e,
        })?;
        self.write_surface(&SurfaceNet {
            degrees: s.degrees(),
            knots: (ku.as_slice(), kv.as_slice()),
            net,
            weights: weights.as_deref(),
        })
    }

    /// Writes `faces` as a boundary representation (see the module docs): shared edges and
    /// vertices once, the faces in a closed shell of a solid when they close a volume, else in
    /// an open shell of a surface model. A file holds one set of faces and nothing else.
    ///
    /// ```
    /// let text = "ISO-10303-21;HEADER;ENDSEC;DATA;
    /// #1=CARTESIAN_POINT('',(0.,0.,0.));#2=DIRECTION('',(0.,0.,1.));#3=DIRECTION('',(1.,0.,0.));
    /// #4=AXIS2_PLACEMENT_3D('',#1,#2,#3);#5=PLANE('',#4);#6=CIRCLE('',#4,1.);
    /// #7=CARTESIAN_POINT('',(1.,0.,0.));#8=VERTEX_POINT('',#7);#9=EDGE_CURVE('',#8,#8,#6,.T.);
    /// #10=ORIENTED_EDGE('',*,*,#9,.T.);#11=EDGE_LOOP('',(#10));#12=FACE_OUTER_BOUND('',#11,.T.);
    /// #13=ADVANCED_FACE('disc',(#12),#5,.T.);ENDSEC;END-ISO-10303-21;";
    /// let faces = lekalo_io::read_step_faces(text, "disc.step", usize::MAX)?.faces;
    /// let mut w = lekalo_io::StepWriter::new("disc");
    /// w.add_faces(&faces)?;
    /// let again = lekalo_io::read_step_faces(&w.finish("2000-01-01T00:00:00"), "again.step", usize::MAX)?;
    /// assert_eq!(again.faces[0].face, faces[0].face);
    /// assert_eq!(again.faces[0].name, "disc");
    /// # Ok::<(), lekalo_io::IoError>(())
    /// ```
    ///
    /// # Errors
    /// [`IoError::Unsupported`] when curves or surfaces were added, faces were already written,
    /// or for a surface or curve of more than 3 coordinates (a pcurve has 2); the writer's
    /// errors for the nets.
    pub fn add_faces(&mut self, faces: &[StepFace]) -> IoResult<()> {
        if self.has_loose_geometry() || self.faces_rep.is_some() {
            return Err(IoError::Unsupported {
                what: "a STEP file holds one set of faces and nothing else: write the faces together, and curves or surfaces to another file".into(),
            });
        }
        if faces.is_empty() {
            return Err(IoError::Unsupported {
                what: "no faces to write".into(),
            });
        }
        let lib = |error: lekalo::Error| IoError::Invalid {
            at: Location::new("faces"),
            error,
        };
        let refs_faces: Vec<&lekalo::topology::Face> = faces.iter().map(|f| &f.face).collect();
        let shell = Shell::new(&refs_faces).map_err(lib)?;
        let surfaces = faces
            .iter()
            .map(|f| self.write_any_surface(f.face.surface()))
            .collect::<IoResult<Vec<_>>>()?;
        let ctx2 = self.add(
            "(GEOMETRIC_REPRESENTATION_CONTEXT(2)PARAMETRIC_REPRESENTATION_CONTEXT()REPRESENTATION_CONTEXT('2D SPACE',''))".into(),
        );
        // each vertex's VERTEX_POINT, written where an edge first uses it
        let mut vertices: Vec<Option<usize>> = vec![None; shell.vertices().len()];
        // each use's EDGE_CURVE and whether the use runs it forwards
        let mut edge_of: HashMap<EdgeUse, (usize, bool)> = HashMap::new();
        for e in shell.edges() {
            // the uses whose 3-D curves are one curve share an EDGE_CURVE; uses the shell
            // joined within its tolerance but whose curves differ (two trimmed surfaces of an
            // IGES file, each bounded by its own curve) get one each, so that every face keeps
            // its curves
            let mut groups: Vec<Vec<(EdgeUse, bool)>> = Vec::new();
            for &(u, same) in &e.uses {
                let Some(edge) = edge_at(faces, u) else {
                    continue;
                };
                let mut found = None;
                for (i, g) in groups.iter().enumerate() {
                    if let Some(first) = edge_at(faces, g[0].0) {
                        if same_curve(first.curve(), edge.curve(), g[0].1 == same) {
                            found = Some(i);
                            break;
                        }
                    }
                }
                match found {
                    Some(i) => groups[i].push((u, same)),
                    None => groups.push(vec![(u, same)]),
                }
            }
            for g in groups {
                let (first, first_same) = g[0];
                let Some(first_edge) = edge_at(faces, first) else {
                    continue;
                };
                let c3 = self.write_any_curve(first_edge.curve(), 3)?;
                let mut pcurves = Vec::new();
                for &(u, same) in &g {
                    let Some(p) = edge_at(faces, u).and_then(|e| e.pcurve()) else {
                        continue;
                    };
                    let p = if same == first_same {
                        p.clone()
                    } else {
                        p.reverse().map_err(lib)?
                    };
                    let c2 = self.write_any_curve(&p, 2)?;
                    let rep = self.add(format!("DEFINITIONAL_REPRESENTATION('',(#{c2}),#{ctx2})"));
                    pcurves.push(self.add(format!("PCURVE('',#{},#{rep})", surfaces[u.face])));
                }
                let geometry = if pcurves.is_empty() {
                    c3
                } else {
                    let seam = g.len() == 2 && g[0].0.face == g[1].0.face;
                    let kind = if seam { "SEAM_CURVE" } else { "SURFACE_CURVE" };
                    self.add(format!("{kind}('',#{c3},{},.CURVE_3D.)", refs(&pcurves)))
                };
                let [v0, v1] = if first_same {
                    e.vertices
                } else {
                    [e.vertices[1], e.vertices[0]]
                };
                // a vertex no point of which keeps every edge there whole (its ends overlap
                // along a line) is written at each curve's own end, its tolerance the gap
                let (t0, t1) = first_edge.curve().domain();
                let mut ends = [0; 2];
                for (k, (v, t)) in [(v0, t0), (v1, t1)].into_iter().enumerate() {
                    ends[k] = match vertices[v] {
                        Some(id) if shell.vertex_meets_ends(v) => id,
                        _ if shell.vertex_meets_ends(v) => {
                            let pt = self.add_point(&shell.vertices()[v]);
                            let id = self.add(format!("VERTEX_POINT('',#{pt})"));
                            vertices[v] = Some(id);
                            id
                        }
                        _ => {
                            let p = first_edge.curve().eval(t).map_err(lib)?;
                            let pt = self.add_point(&p);
                            self.add(format!("VERTEX_POINT('',#{pt})"))
                        }
                    };
                }
                let id = self.add(format!(
                    "EDGE_CURVE('',#{},#{},#{geometry},.T.)",
                    ends[0], ends[1]
                ));
                for &(u, same) in &g {
                    edge_of.insert(u, (id, same == first_same));
                }
            }
        }
        let mut face_ids = Vec::with_capacity(faces.len());
        for (fi, f) in faces.iter().enumerate() {
            let mut bounds = Vec::new();
            for (li, lp) in f.face.loops().enumerate() {
                let mut oriented = Vec::with_capacity(lp.edges().len());
                for k in 0..lp.edges().len() {
                    let u = EdgeUse {
                        face: fi,
                        lp: li,
                        edge: k,
                    };
                    let Some(&(id, same)) = edge_of.get(&u) else {
                        continue;
                    };
                    oriented.push(self.add(format!("ORIENTED_EDGE('',*,*,#{id},{})", flag(same))));
                }
                let lp_id = self.add(format!("EDGE_LOOP('',{})", refs(&oriented)));
                let kind = if li == 0 {
                    "FACE_OUTER_BOUND"
                } else {
                    "FACE_BOUND"
                };
                bounds.push(self.add(format!("{kind}('',#{lp_id},.T.)")));
            }
            face_ids.push(self.add(format!(
                "ADVANCED_FACE({},{},#{},{})",
                step_string(&f.name),
                refs(&bounds),
                surfaces[fi],
                flag(f.face.same_sense())
            )));
        }
        let origin = self.add_point(&[0.0, 0.0, 0.0]);
        let z = self.add(format!(
            "DIRECTION('',({},{},{}))",
            step_real(0.0),
            step_real(0.0),
            step_real(1.0)
        ));
        let x = self.add(format!(
            "DIRECTION('',({},{},{}))",
            step_real(1.0),
            step_real(0.0),
            step_real(0.0)
        ));
        let axis = self.add(format!("AXIS2_PLACEMENT_3D('',#{origin},#{z},#{x})"));
        let rep = if shell.is_closed() {
            let sh = self.add(format!("CLOSED_SHELL('',{})", refs(&face_ids)));
            let solid = self.add(format!("MANIFOLD_SOLID_BREP('',#{sh})"));
            self.add(format!(
                "ADVANCED_BREP_SHAPE_REPRESENTATION('',(#{axis},#{solid}),#{CONTEXT_ID})"
            ))
        } else {
            let sh = self.add(format!("OPEN_SHELL('',{})", refs(&face_ids)));
            let model = self.add(format!("SHELL_BASED_SURFACE_MODEL('',(#{sh}))"));
            self.add(format!(
                "MANIFOLD_SURFACE_SHAPE_REPRESENTATION('',(#{axis},#{model}),#{CONTEXT_ID})"
            ))
        };
        self.faces_rep = Some(rep);
        Ok(())
    }
}
