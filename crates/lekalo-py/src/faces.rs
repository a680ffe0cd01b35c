//! `Face` and `read_step`: the faces of a STEP file (a surface trimmed by loops of edges, each
//! edge a 3-D curve with its pcurve in the surface's `(u, v)`), with the point-in-face test on
//! NumPy arrays; `read_step` also gives the file's curves and surfaces; `mesh_faces` meshes
//! faces together.

use lekalo::topology::TrimRegion;
use lekalo_io::{Shape, StepFace};
use numpy::{PyArray1, PyArrayMethods, PyUntypedArrayMethods};
use pyo3::exceptions::PyUserWarning;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyTuple};

use crate::convert::IntArg;
use crate::convert::{array, floats, points_into_array, uv_args};
use crate::curves::curve_to_py;
use crate::error::{bad, io_err, lib_err};
use crate::surfaces::surface_to_py;

/// A face of a CAD model: a surface trimmed by an outer loop and inner loops (holes). Each edge
/// is a pair ``(curve, pcurve)``: its 3-D curve and its curve in the surface's ``(u, v)`` (or
/// ``None``), both directed along the loop.
#[pyclass(module = "lekalo", name = "Face", frozen)]
pub(crate) struct PyFace {
    inner: StepFace,
    /// The trim polygons, made on first use of `contains`.
    region: std::sync::OnceLock<Result<TrimRegion, lekalo::Error>>,
}

impl PyFace {
    fn region(&self) -> PyResult<&TrimRegion> {
        self.region
            .get_or_init(|| self.inner.face.trim_region())
            .as_ref()
            .map_err(|e| lib_err(e.clone()))
    }
}

fn loop_to_py<'py>(py: Python<'py>, lp: &lekalo::Loop) -> PyResult<Bound<'py, PyList>> {
    let mut edges = Vec::with_capacity(lp.edges().len());
    for e in lp.edges() {
        let c = curve_to_py(py, e.curve().clone())?;
        let p = match e.pcurve() {
            Some(p) => curve_to_py(py, p.clone())?,
            None => py.None(),
        };
        edges.push(PyTuple::new(py, [c, p])?);
    }
    PyList::new(py, edges)
}

#[pymethods]
impl PyFace {
    /// The face's instance id in its file (``#id``).
    #[getter]
    fn id(&self) -> u64 {
        self.inner.id
    }

    /// The face's name in its file.
    #[getter]
    fn name(&self) -> String {
        self.inner.name.clone()
    }

    /// The id of the surface's instance in the file.
    #[getter]
    fn surface_id(&self) -> u64 {
        self.inner.surface_id
    }

    /// True when the face's normal is the surface's.
    #[getter]
    fn same_sense(&self) -> bool {
        self.inner.face.same_sense()
    }

    /// The surface (``BSplineSurface`` or ``NurbsSurface``).
    #[getter]
    fn surface(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        surface_to_py(py, self.inner.face.surface().clone())
    }

    /// The outer loop: a list of ``(curve, pcurve)`` edges in loop order.
    #[getter]
    fn outer<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyList>> {
        loop_to_py(py, self.inner.face.outer())
    }

    /// The inner loops (holes), each a list of ``(curve, pcurve)`` edges.
    #[getter]
    fn inner<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyList>> {
        let loops = self
            .inner
            .face
            .inner()
            .iter()
            .map(|lp| loop_to_py(py, lp))
            .collect::<PyResult<Vec<_>>>()?;
        PyList::new(py, loops)
    }

    /// The ``EDGE_CURVE`` ids of each loop's edges, outer loop first.
    #[getter]
    fn edge_ids(&self) -> Vec<Vec<u64>> {
        self.inner.edge_ids.clone()
    }

    /// Why the edges have no pcurves (e.g. a cylinder's), or ``None`` when they all have one.
    #[getter]
    fn pcurves(&self) -> Option<String> {
        self.inner.pcurves.clone()
    }

    /// The loops in ``(u, v)`` as closed polygons through points of the pcurves (16 per knot
    /// span): a list of ``(n, 2)`` arrays, outer loop first.
    fn trim_polygons<'py>(&self, py: Python<'py>) -> PyResult<Vec<Bound<'py, PyAny>>> {
        let region = self.region()?;
        region
            .polygons()
            .iter()
            .map(|p| array(py, p.as_slice().to_vec(), &[p.len(), 2]))
            .collect()
    }

    /// A triangle mesh of the face's trimmed region within ``tolerance`` (in the model's units):
    /// ``(vertices, triangles)``, an ``(n, 3)`` float array of points and an ``(m, 3)`` uint32
    /// array of vertex indices, the triangles' normals the face's. Each loop is sampled through
    /// its pcurves, grid points inside the trims are added and the whole triangulated by a
    /// constrained Delaunay triangulation, refined until every triangle's deviation bound is
    /// within the tolerance (``lekalo::topology::mesh_faces``; docs/theory/topology.md,
    /// "Meshing a trimmed face"). Edges without a pcurve get one by projection first, as
    /// ``with_projected_pcurves(tolerance)``; an edge off the surface raises ``ValueError``.
    /// A face whose loops go once round a closed surface without a seam edge (a band between
    /// two circles, a cap round a pole) is cut along a seam, without a crack there
    /// (docs/theory/topology.md, "Bands and caps without a seam edge").
    fn mesh<'py>(
        &self,
        py: Python<'py>,
        tolerance: f64,
    ) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>)> {
        let m = py
            .detach(|| {
                if self.inner.face.has_pcurves() {
                    self.inner.face.mesh(tolerance)
                } else {
                    self.inner
                        .face
                        .with_projected_pcurves(tolerance)
                        .and_then(|f| f.mesh(tolerance))
                }
            })
            .map_err(lib_err)?;
        let nt = m.triangles.len();
        let tri: Vec<u32> = m.triangles.iter().flatten().copied().collect();
        let tri = PyArray1::from_vec(py, tri).reshape([nt, 3])?.into_any();
        Ok((points_into_array(py, m.vertices)?, tri))
    }

    /// Checks the loops in ``(u, v)`` bound one region of the surface's domain
    /// (``lekalo::Face::checked_trims``; docs/theory/topology.md, "Faces with bad trims"), as
    /// ``mesh`` does first: raises ``ValueError`` naming the loop and the defect (a pcurve
    /// outside the domain, an outer loop of no length, loops crossing themselves or each
    /// other, a hole outside the outer loop or inside another hole); returns the repairs
    /// ``mesh`` makes (pcurves clipped to the domain within 1e-4 of its width, edges and holes
    /// of no length dropped) as a list of sentences, empty for a valid face. A face with an
    /// edge without pcurve is not checked (``with_projected_pcurves`` first).
    fn check_trims(&self, py: Python<'_>) -> PyResult<Vec<String>> {
        let (_, repairs) = py
            .detach(|| self.inner.face.checked_trims())
            .map_err(lib_err)?;
        Ok(repairs.iter().map(ToString::to_string).collect())
    }

    /// The face with a pcurve for every edge: each edge without one gets the projection of its
    /// 3-D curve onto the surface, a degree-1 B-spline over the curve's parameters whose image
    /// is within ``tolerance`` of the projected edge, unwrapped across the seams of closed
    /// surfaces (``lekalo::Face::with_projected_pcurves``; docs/theory/topology.md, "Pcurves
    /// by projection"). Raises ``ValueError`` for an edge off the surface (by more than the
    /// tolerance or 1e-4 of the model size), naming the edge and its distance.
    fn with_projected_pcurves(&self, py: Python<'_>, tolerance: f64) -> PyResult<Self> {
        let f = py
            .detach(|| self.inner.face.with_projected_pcurves(tolerance))
            .map_err(lib_err)?;
        let mut inner = self.inner.clone();
        inner.face = f;
        inner.pcurves = None;
        Ok(face(inner))
    }

    /// Whether ``(u, v)`` lies inside the face: the outer polygon winds around it and no inner
    /// one does (winding numbers, Hormann and Agathos 2001). ``u`` and ``v`` are numbers (a
    /// ``bool`` back) or arrays of one shape (a boolean array of that shape).
    fn contains<'py>(
        &self,
        py: Python<'py>,
        u: &Bound<'py, PyAny>,
        v: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let region = self.region()?;
        let (ua, pairs) = uv_args(u, v)?;
        let shape = ua.shape().to_vec();
        let inside: Vec<bool> =
            py.detach(|| pairs.iter().map(|&[a, b]| region.contains(a, b)).collect());
        if shape.is_empty() {
            return Ok(pyo3::types::PyBool::new(py, inside[0])
                .to_owned()
                .into_any());
        }
        let a = PyArray1::from_vec(py, inside);
        Ok(a.reshape(shape)?.into_any())
    }

    /// The face as its JSON line (``"type": "face"``, docs/formats.md).
    fn to_json(&self) -> String {
        lekalo_io::face_to_json_line(&self.inner)
    }

    /// A face from its JSON line.
    #[staticmethod]
    fn from_json(text: &str) -> PyResult<Self> {
        Ok(face(lekalo_io::read_face(text, "json").map_err(io_err)?))
    }

    fn __repr__(&self) -> String {
        let f = &self.inner.face;
        format!(
            "Face(id={}, name={:?}, surface={}, outer={} edges, inner={} loops, pcurves={})",
            self.inner.id,
            self.inner.name,
            f.surface().type_name(),
            f.outer().edges().len(),
            f.inner().len(),
            self.inner.pcurves.is_none()
        )
    }
}

fn face(inner: StepFace) -> PyFace {
    PyFace {
        inner,
        region: std::sync::OnceLock::new(),
    }
}

/// The file at `path` (or standard input for `-`), of at most `max_input_bytes` bytes, read by
/// `read(text, name)` with the GIL released, as both CAD readers do.
fn read_cad<R: Send>(
    py: Python<'_>,
    path: &std::path::Path,
    max_input_bytes: u64,
    read: impl FnOnce(&str, &str) -> lekalo_io::IoResult<R> + Send,
) -> PyResult<R> {
    py.detach(|| {
        let (text, name) = lekalo_io::read_input_within(path, max_input_bytes)?;
        read(&text, &name)
    })
    .map_err(io_err)
}

/// Reads a STEP file: ``{"shapes": [...], "skipped": [...], "length_unit": str, "schema":
/// str | None}``, and with ``faces=True`` also ``"faces"`` (a list of ``Face``),
/// ``"tessellated"`` (the faces of triangles of AP242, ``TRIANGULATED_FACE``,
/// ``COMPLEX_TRIANGULATED_FACE`` and the triangulated surface sets, as the file gives them:
/// dicts ``{"id", "entity", "name", "link", "vertices", "triangles", "normals", "dropped"}``,
/// ``vertices`` an ``(n, 3)`` float64 array in millimetres, ``triangles`` ``(m, 3)`` int64
/// 0-based, ``normals`` the ``(n, 3)`` unit normals of the vertices from the file's or
/// ``None``) and ``"skipped_faces"``. Skipped entries are dicts ``{"id", "entity", "reason"}``: the first
/// ``skipped_listed`` by id (default 1000; ``None`` keeps every one); ``"skipped_total"`` counts
/// them all and ``"skipped_kinds"`` counts them by type and reason (dicts ``{"entity",
/// "reason", "count", "first_id"}``, the most frequent first); with ``faces=True`` likewise
/// ``"skipped_faces_total"`` and ``"skipped_faces_kinds"``. ``max_size`` bounds the entities
/// and the control points and knots of the file, as the CLI's ``--max-size``, and
/// ``max_input_bytes`` its bytes (default 1 GiB), as the CLI's ``--max-input-bytes``: a file
/// above either is refused with ``lekalo.InputError`` naming the keyword to raise, before its
/// geometry is allocated.
#[pyfunction]
#[pyo3(signature = (path, *, faces = false, max_size = IntArg::of(10_000_000), skipped_listed = Some(IntArg::of(1000)), max_input_bytes = IntArg::of(1 << 30)), text_signature = "(path, *, faces=False, max_size=10000000, skipped_listed=1000, max_input_bytes=1073741824)")]
pub(crate) fn read_step<'py>(
    py: Python<'py>,
    path: std::path::PathBuf,
    faces: bool,
    max_size: IntArg,
    skipped_listed: Option<IntArg>,
    max_input_bytes: IntArg,
) -> PyResult<Bound<'py, PyDict>> {
    let max_size = max_size.count("max_size")?;
    let listed = listed(skipped_listed)?;
    let max_bytes = max_input_bytes.count("max_input_bytes")? as u64;
    let r = read_cad(py, &path, max_bytes, |text, name| {
        let none = lekalo::Progress::new();
        lekalo_io::read_step_with_progress(text, name, max_size, faces, listed, &none)
    })?;
    let out = cad_dict(
        py,
        r.shapes,
        &r.skipped,
        r.length_unit,
        faces,
        r.faces,
        &r.skipped_faces,
    )?;
    if faces {
        out.set_item("tessellated", tessellated(py, &r.triangulations)?)?;
    }
    out.set_item("schema", r.schema)?;
    Ok(out)
}

/// Reads an IGES file: ``{"shapes": [...], "skipped": [...], "length_unit": str,
/// "scale_to_mm": float}``, and with ``faces=True`` also ``"faces"`` (the trimmed and bounded
/// surfaces, entities 144 and 143, and the independent surfaces nothing trims, untrimmed, as
/// ``Face``), ``"tessellated"`` (empty: IGES has no faces of triangles) and
/// ``"skipped_faces"``; as ``read_step`` otherwise (ids are directory-entry sequence numbers).
#[pyfunction]
#[pyo3(signature = (path, *, faces = false, max_size = IntArg::of(10_000_000), skipped_listed = Some(IntArg::of(1000)), max_input_bytes = IntArg::of(1 << 30)), text_signature = "(path, *, faces=False, max_size=10000000, skipped_listed=1000, max_input_bytes=1073741824)")]
pub(crate) fn read_iges<'py>(
    py: Python<'py>,
    path: std::path::PathBuf,
    faces: bool,
    max_size: IntArg,
    skipped_listed: Option<IntArg>,
    max_input_bytes: IntArg,
) -> PyResult<Bound<'py, PyDict>> {
    let max_size = max_size.count("max_size")?;
    let listed = listed(skipped_listed)?;
    let max_bytes = max_input_bytes.count("max_input_bytes")? as u64;
    let r = read_cad(py, &path, max_bytes, |text, name| {
        let none = lekalo::Progress::new();
        lekalo_io::read_iges_with_progress(text, name, max_size, faces, listed, &none)
    })?;
    let out = cad_dict(
        py,
        r.shapes,
        &r.skipped,
        r.length_unit,
        faces,
        r.faces,
        &r.skipped_faces,
    )?;
    if faces {
        // IGES has no faces of triangles: the same keys as read_step's
        out.set_item("tessellated", PyList::empty(py))?;
    }
    out.set_item("scale_to_mm", r.scale_to_mm)?;
    Ok(out)
}

/// The faces of triangles of a STEP file as dicts of NumPy arrays (`read_step`'s
/// ``"tessellated"``, the word of ``lekalo info --faces --json``): ``id``, ``entity``,
/// ``name``, ``link`` (the id of the surface or face approximated, or ``None``), ``vertices``
/// (``(n, 3)`` float64, millimetres), ``triangles`` (``(m, 3)`` int64, 0-based, each turning
/// counter-clockwise about the side the normals point to), ``normals`` (``(n, 3)`` float64
/// unit normals of the vertices from the file's, as ``lekalo mesh`` writes them in OBJ
/// (`lekalo_io::StepTriangulation::vertex_normals`), or ``None`` when the file gives none),
/// ``dropped`` (triangles of no area left out).
fn tessellated<'py>(
    py: Python<'py>,
    list: &[lekalo_io::StepTriangulation],
) -> PyResult<Bound<'py, PyList>> {
    let items = list
        .iter()
        .map(|t| {
            let d = PyDict::new(py);
            d.set_item("id", t.id)?;
            d.set_item("entity", &t.entity)?;
            d.set_item("name", &t.name)?;
            d.set_item("link", t.link)?;
            let n = t.vertices.len();
            d.set_item(
                "vertices",
                array(py, t.vertices.as_slice().to_vec(), &[n, 3])?,
            )?;
            let m = t.triangles.len();
            let tri: Vec<i64> = t
                .triangles
                .iter()
                .flatten()
                .map(|&k| i64::from(k))
                .collect();
            d.set_item("triangles", PyArray1::from_vec(py, tri).reshape([m, 3])?)?;
            let normals = t.vertex_normals();
            if normals.is_empty() {
                d.set_item("normals", py.None())?;
            } else {
                // a vertex of no triangle with a zero normal in the file has none: (0, 0, 0)
                let flat: Vec<f64> = normals.iter().flat_map(|v| v.unwrap_or([0.0; 3])).collect();
                d.set_item("normals", array(py, flat, &[n, 3])?)?;
            }
            d.set_item("dropped", t.dropped)?;
            Ok(d)
        })
        .collect::<PyResult<Vec<_>>>()?;
    PyList::new(py, items)
}

/// How many skipped entities a read lists: `skipped_listed`, every one for `None`.
fn listed(skipped_listed: Option<IntArg>) -> PyResult<usize> {
    skipped_listed.map_or(Ok(usize::MAX), |n| n.count("skipped_listed"))
}

/// The dictionary `read_step` and `read_iges` share: shapes, what was skipped, the length unit,
/// and with `faces` the faces and the faces skipped.
#[allow(clippy::too_many_arguments)]
fn cad_dict<'py>(
    py: Python<'py>,
    shapes: Vec<(u64, Shape)>,
    skipped_entities: &lekalo_io::Skips,
    length_unit: String,
    faces: bool,
    read_faces: Vec<StepFace>,
    skipped_faces: &lekalo_io::Skips,
) -> PyResult<Bound<'py, PyDict>> {
    let kinds = |list: &lekalo_io::Skips| -> PyResult<Bound<'py, PyList>> {
        let items = list
            .kinds()
            .iter()
            .map(|k| {
                let d = PyDict::new(py);
                d.set_item("entity", &k.entity)?;
                d.set_item("reason", &k.reason)?;
                d.set_item("count", k.count)?;
                d.set_item("first_id", k.first_id)?;
                Ok(d)
            })
            .collect::<PyResult<Vec<_>>>()?;
        PyList::new(py, items)
    };
    let skipped = |list: &lekalo_io::Skips| -> PyResult<Bound<'py, PyList>> {
        let items = list
            .iter()
            .map(|s| {
                let d = PyDict::new(py);
                d.set_item("id", s.id)?;
                d.set_item("entity", &s.entity)?;
                d.set_item("reason", &s.reason)?;
                Ok(d)
            })
            .collect::<PyResult<Vec<_>>>()?;
        PyList::new(py, items)
    };
    let out = PyDict::new(py);
    let shapes = shapes
        .into_iter()
        .map(|(_, s)| match s {
            Shape::Curve(c) => curve_to_py(py, c),
            Shape::Surface(s) => surface_to_py(py, s),
            other => crate::objects::shape_to_py(py, other),
        })
        .collect::<PyResult<Vec<_>>>()?;
    out.set_item("shapes", shapes)?;
    out.set_item("skipped", skipped(skipped_entities)?)?;
    out.set_item("skipped_total", skipped_entities.len())?;
    out.set_item("skipped_kinds", kinds(skipped_entities)?)?;
    out.set_item("length_unit", length_unit)?;
    if faces {
        let list = read_faces
            .into_iter()
            .map(|f| Py::new(py, face(f)))
            .collect::<PyResult<Vec<_>>>()?;
        out.set_item("faces", list)?;
        out.set_item("skipped_faces", skipped(skipped_faces)?)?;
        out.set_item("skipped_faces_total", skipped_faces.len())?;
        out.set_item("skipped_faces_kinds", kinds(skipped_faces)?)?;
    }
    Ok(out)
}

/// The faces of a Python sequence of `Face`.
fn step_faces(faces: &[Bound<'_, PyFace>]) -> Vec<StepFace> {
    faces.iter().map(|f| f.get().inner.clone()).collect()
}

/// Writes faces to a STEP file (AP214) as a boundary representation: each face an
/// ``ADVANCED_FACE`` over its surface with its loops, an edge shared by two faces (the same
/// control points, in the same or reverse order) one ``EDGE_CURVE`` with both faces' pcurves,
/// the faces in a closed shell of a solid when they close a volume, else in an open shell of a
/// surface model; names kept (docs/formats.md, "Writing faces"). ``name`` is the product's
/// (default: the file's stem).
#[pyfunction]
#[pyo3(signature = (path, faces, *, name = None))]
pub(crate) fn write_step(
    py: Python<'_>,
    path: std::path::PathBuf,
    faces: Vec<Bound<'_, PyFace>>,
    name: Option<String>,
) -> PyResult<()> {
    let list = step_faces(&faces);
    let name = name.unwrap_or_else(|| stem(&path));
    let text = py
        .detach(|| {
            let mut w = lekalo_io::StepWriter::new(&name);
            w.add_faces(&list)?;
            Ok::<_, lekalo_io::IoError>(w.finish("2000-01-01T00:00:00"))
        })
        .map_err(io_err)?;
    lekalo_io::write_atomic(&path, text.as_bytes(), &[]).map_err(io_err)
}

/// The vertices, triangles and vertex normals of a mesh of faces, and the faces not meshed
/// with the reasons.
type MeshedFaces<'py> = (
    Bound<'py, PyAny>,
    Bound<'py, PyAny>,
    Option<Bound<'py, PyAny>>,
    Vec<(usize, String)>,
);

/// Meshes faces together within ``tolerance`` (in the model's units), as ``lekalo mesh`` does
/// with a STEP file: ``(vertices, triangles, normals, failures)``, the faces that can be meshed
/// as one mesh (an ``(n, 3)`` float64 array and an ``(m, 3)`` uint32 array, the faces meeting
/// at the same points along their shared edges), the unit normal of each vertex (``(n, 3)``
/// float64) and, for each face that cannot, ``(index, reason)`` with its index in ``faces``.
///
/// A face's normals are its surface's exact ``S_u × S_v`` at each vertex, turned with the face's
/// sense, so on the side its triangles turn about; at a pole, where that is undefined, the mean
/// of the normals inside the vertex's triangles (``lekalo::query::Mesh::surface_normals``).
/// ``tessellated``: faces of triangles as ``read_step(path, faces=True)["tessellated"]`` gives
/// them (dicts with ``"vertices"`` ``(k, 3)``, ``"triangles"`` ``(j, 3)`` integers 0-based,
/// ``"normals"`` ``(k, 3)`` or ``None``; ``"id"`` optional), joined after the meshed faces with
/// their triangles as given and their normals made unit. A vertex without a normal has
/// ``(0, 0, 0)``: one of a face of triangles whose file gives none, or a copy of a pole that no
/// triangle uses; ``normals`` is ``None`` when no vertex has one. The mesh,
/// normals and order are those ``lekalo mesh FILE -o mesh.obj`` writes
/// (``lekalo_io::join_cad_mesh``).
///
/// Edges without a pcurve get one by projection first, as
/// ``Face.with_projected_pcurves(tolerance)``. Each face is meshed once and a face that fails
/// leaves the others as they are without it (``lekalo::topology::mesh_faces_each``;
/// docs/theory/topology.md, "Faces that cannot be meshed"). A face whose proved deviation bound
/// stays above the tolerance (refinement stopped at its limit) is in the mesh, and a
/// ``UserWarning`` names it (its index), its bound and the tolerance that would do; so does a
/// face whose trims were repaired (``Face.check_trims``). A face whose loops do not bound one
/// region of its surface's domain is among the failures, its reason naming the loop. Raises
/// ``ValueError`` for a tolerance that is not positive and finite, or too small for the faces'
/// sizes together, and for a face of triangles that does not hold together (naming its place
/// in ``tessellated``).
#[pyfunction]
#[pyo3(signature = (faces, tolerance, *, tessellated = None))]
pub(crate) fn mesh_faces<'py>(
    py: Python<'py>,
    faces: Vec<Bound<'py, PyFace>>,
    tolerance: f64,
    tessellated: Option<Vec<Bound<'py, PyAny>>>,
) -> PyResult<MeshedFaces<'py>> {
    let list: Vec<&lekalo::Face> = faces.iter().map(|f| &f.get().inner.face).collect();
    let triangulations = tessellated
        .unwrap_or_default()
        .iter()
        .enumerate()
        .map(|(k, d)| triangulation(k, d))
        .collect::<PyResult<Vec<_>>>()?;
    let (joined, failures, coarse) = py
        .detach(|| {
            let mut ready = Vec::with_capacity(list.len());
            let mut failures = Vec::new();
            for (k, f) in list.iter().enumerate() {
                match f.with_projected_pcurves(tolerance) {
                    Ok(g) => ready.push((k, g)),
                    Err(e) => failures.push((k, e.to_string())),
                }
            }
            let ready_faces: Vec<&lekalo::Face> = ready.iter().map(|(_, f)| f).collect();
            let r = lekalo::topology::mesh_faces_each(&ready_faces, tolerance)?;
            failures.extend(r.failures.iter().map(|(i, e)| (ready[*i].0, e.to_string())));
            // bounds above the tolerance, then trims repaired before meshing
            let coarse: Vec<(usize, String)> = r
                .above_tolerance
                .iter()
                .map(|(i, e)| (ready[*i].0, e.to_string()))
                .chain(r.repairs.iter().map(|(i, x)| (ready[*i].0, x.to_string())))
                .collect();
            failures.sort_by_key(|(k, _)| *k);
            let joined = lekalo_io::join_cad_mesh(Some(&r), &ready_faces, &triangulations)?;
            Ok::<_, lekalo::Error>((joined, failures, coarse))
        })
        .map_err(lib_err)?;
    // a face whose proved bound stayed above the tolerance is kept, with a warning (the CLI
    // writes the mesh and exits with 2)
    for (k, reason) in &coarse {
        PyErr::warn(
            py,
            &py.get_type::<PyUserWarning>(),
            &std::ffi::CString::new(format!("face {k}: {reason}")).unwrap_or_default(),
            1,
        )?;
    }
    let m = joined.mesh;
    let n = m.vertices.len();
    let normals = if joined.normals.is_empty() {
        None
    } else {
        let flat: Vec<f64> = joined
            .normals
            .iter()
            .flat_map(|v| v.unwrap_or([0.0; 3]))
            .collect();
        Some(array(py, flat, &[n, 3])?)
    };
    let nt = m.triangles.len();
    let tri: Vec<u32> = m.triangles.iter().flatten().copied().collect();
    let tri = PyArray1::from_vec(py, tri).reshape([nt, 3])?.into_any();
    Ok((points_into_array(py, m.vertices)?, tri, normals, failures))
}

/// A face of triangles from a dict of ``read_step``'s ``"tessellated"`` (item `k`): its
/// vertices, triangles and normals read as arrays; their consistency is checked by
/// `lekalo_io::join_cad_mesh`.
fn triangulation(k: usize, d: &Bound<'_, PyAny>) -> PyResult<lekalo_io::StepTriangulation> {
    let what = |key: &str| format!("tessellated[{k}]['{key}']");
    let item = |key: &str| -> PyResult<Bound<'_, PyAny>> {
        d.get_item(key).map_err(|_| {
            bad(format!(
                "tessellated[{k}]: no '{key}'; give the faces of triangles as \
                 read_step(path, faces=True)[\"tessellated\"] gives them"
            ))
        })
    };
    let rows = |a: &crate::convert::FloatArray<'_>, key: &str| -> PyResult<usize> {
        match a.shape() {
            [n, 3] => Ok(*n),
            s => Err(bad(format!("{}: shape {s:?}; expected (n, 3)", what(key)))),
        }
    };
    let v = floats(&item("vertices")?, &what("vertices"))?;
    let n = rows(&v, "vertices")?;
    let vertices = lekalo::Points::from_flat(3, v.data().to_vec()).map_err(lib_err)?;
    let t = item("triangles")?;
    let triangles: Vec<[i64; 3]> = match t.cast::<numpy::PyArray2<i64>>() {
        Ok(a) if a.shape()[1] == 3 && a.is_c_contiguous() => a
            .to_vec()?
            .chunks_exact(3)
            .map(|c| [c[0], c[1], c[2]])
            .collect(),
        _ => t
            .extract()
            .map_err(|_| bad(format!("{}: expected (m, 3) integers", what("triangles"))))?,
    };
    let triangles = triangles
        .into_iter()
        .enumerate()
        .map(|(j, tri)| {
            let mut out = [0_u32; 3];
            for (o, i) in out.iter_mut().zip(tri) {
                *o = u32::try_from(i).map_err(|_| {
                    bad(format!(
                        "{}: triangle {j} has index {i}; indices run from 0 to {}",
                        what("triangles"),
                        n.saturating_sub(1)
                    ))
                })?;
            }
            Ok(out)
        })
        .collect::<PyResult<Vec<_>>>()?;
    let normals = match d.get_item("normals").ok().filter(|x| !x.is_none()) {
        None => Vec::new(),
        Some(x) => {
            let a = floats(&x, &what("normals"))?;
            rows(&a, "normals")?;
            a.data()
                .chunks_exact(3)
                .map(|c| [c[0], c[1], c[2]])
                .collect()
        }
    };
    let id = match d.get_item("id").ok().filter(|x| !x.is_none()) {
        None => 0,
        Some(x) => x
            .extract::<u64>()
            .map_err(|_| bad(format!("{}: expected a non-negative integer", what("id"))))?,
    };
    Ok(lekalo_io::StepTriangulation {
        id,
        entity: String::new(),
        name: String::new(),
        link: None,
        vertices,
        triangles,
        normals,
        dropped: 0,
    })
}

/// Writes faces to an IGES file as trimmed surfaces (entity 144 over 128, each loop a 142 with
/// its curves in space and in (u, v)); IGES shares no edges and keeps no orientation flag
/// (docs/formats.md, section 6a).
#[pyfunction]
pub(crate) fn write_iges(
    py: Python<'_>,
    path: std::path::PathBuf,
    faces: Vec<Bound<'_, PyFace>>,
) -> PyResult<()> {
    let list = step_faces(&faces);
    let name = stem(&path);
    let text = py
        .detach(|| {
            let mut w = lekalo_io::IgesWriter::new();
            w.add_faces(&list)?;
            Ok::<_, lekalo_io::IoError>(w.finish(&name, "20000101.000000"))
        })
        .map_err(io_err)?;
    lekalo_io::write_atomic(&path, text.as_bytes(), &[]).map_err(io_err)
}

fn stem(path: &std::path::Path) -> String {
    path.file_stem()
        .and_then(|s| s.to_str())
        .unwrap_or("lekalo")
        .to_string()
}
