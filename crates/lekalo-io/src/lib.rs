//! # lekalo-io — file formats of the lekalo spline kernel
//!
//! Reading and writing is kept out of the core library (`lekalo` does mathematics only). Every
//! read goes through the library's validating constructors; every error names the source, the
//! line and the field.
//!
//! | format | read | write | module |
//! |---|---|---|---|
//! | versioned JSON envelope `{"lekalo": 1, "type": …}` (docs/formats.md) | yes | yes | [`Shape`]: curves [`Object`], [`Surface`], pp-forms |
//! | tensor splines in N parameters `bspline_tensor`, `nurbs_tensor` (docs/formats.md) | yes | yes | [`read_tensor`], [`tensor_to_json`] |
//! | JSON Lines of objects (batches) | yes | yes | [`read_json_lines`] |
//! | points: CSV, whitespace text, JSON | yes | — | [`read_points`] |
//! | points: NumPy `.npy` float64 `(n, d)` | yes | yes (samples) | [`read_npy_points`], [`npy_bytes`] |
//! | curves: NumPy `.npz` (degree, knots, control points, weights) | yes | yes | [`read_npz_curve`], [`curve_to_npz`], [`write_npz_curve`] |
//! | tensor splines in N parameters: NumPy `.npz` (degrees, `knots_0` …, control points, weights; SciPy's `NdBSpline` layout) | yes | yes | [`read_npz_tensor`], [`tensor_to_npz`], [`write_npz_tensor`], [`read_npz`] (either kind) |
//! | batches: Parquet point sets in, curves in and out, samples out (batch by batch); point sets from a CSV with a key column | yes | yes | [`read_point_groups`], [`read_curve_groups`], [`ParquetBatchWriter`], [`read_text_point_groups`] |
//! | samples (t, point, derivatives, curvature): CSV, JSON | — | yes | [`sample_table`] |
//! | SVG plots: curve, control polygon, knots, data, basis functions, wireframes | — | yes | [`Figure`] |
//! | PNG (SVG rendered by resvg) | — | yes | [`svg_to_png`] |
//! | STEP ISO 10303-21 AP203/AP214/AP242 B-spline/NURBS curves and surfaces | yes | yes | [`read_step`], [`StepWriter`] |
//! | STEP faces (surfaces trimmed by loops of edges with pcurves), as `"type": "face"` envelopes; written as a B-rep (shared edges, shells) | yes | yes | [`read_step_faces`], [`StepWriter::add_faces`], [`face_to_json_line`], [`read_face`] |
//! | IGES 5.3 rational B-spline curves (126) and surfaces (128) | yes | yes | [`read_iges`], [`IgesWriter`] |
//! | IGES lines, arcs, conics, parametric splines, paths, composite curves, swept, analytic and bounded-plane surfaces (100–122, 190–198) as exact NURBS | yes | — | [`read_iges`] |
//! | IGES trimmed and bounded surfaces (144, 143 with 142, 141 boundaries) as faces; faces written as 144 | yes | yes | [`read_iges_faces`], [`IgesWriter::add_faces`] |
//! | OBJ: tessellated surfaces with normals, polylines | — | yes | [`grid_to_obj`] |
//! | a CAD model's meshed faces and faces of triangles as one mesh with its vertices' normals | — | — | [`join_cad_mesh`] |
//!
//! Outputs are written atomically ([`write_atomic`]) and never over an input.
//!
//! ```
//! use lekalo_io::{CurveJson, Object, sample_table, SampleSpec};
//! let obj = Object::from_json_str(
//!     r#"{"lekalo":1,"type":"bezier_curve","control":[[0,0],[1,2],[2,0]]}"#, "inline")?;
//! let table = sample_table(&obj, &[0.5], SampleSpec::default()).unwrap();
//! assert_eq!(table.to_csv(), "t,x,y\n0.5,1,1\n");
//! # Ok::<(), lekalo_io::IoError>(())
//! ```

mod atomic;
mod cad;
mod envelope;
mod error;
mod mesh;
#[cfg(feature = "parquet")]
mod parquet;
mod plot;
mod points;
mod tables;

// each subject's files keep their short paths inside the crate (`crate::object`, `crate::svg`)
use cad::{iges, step, step_read};
use envelope::{
    analysis, face_json, flat, intersections, json_write, object, object_ext, shape, tensor_json,
};
use mesh::{cad_mesh, mesh_files, obj};
use plot::{figure_check, layout, palette, png, surface_plot, svg, wireframe};
use points::{npy, npz, points_in, tensor_npz, text_points};
use tables::{numfmt, samples, surface_samples};

pub use analysis::{curvature, uniform};
pub use atomic::{
    check_not_input, limit_input_bytes, note_read, protect_files_read, read_input,
    read_input_bytes, read_input_bytes_within, read_input_within, remove_temporary_files,
    strip_bom, strip_bom_str, utf8_text, write_atomic, write_atomic_seek, write_atomic_send,
    write_atomic_stream, write_atomic_with, WriteOptions, WriteSeek, DEFAULT_MAX_INPUT_BYTES,
};
pub use cad_mesh::{join_cad_mesh, CadMesh};
pub use error::{IoError, IoResult, Limit, Location};
pub use face_json::{face_to_json_line, read_face};
pub use figure_check::check_svg;
pub use iges::{
    read_iges, read_iges_faces, read_iges_limited, read_iges_with_progress, IgesRead, IgesWriter,
};
pub use intersections::{
    curve_intersection_json, plane_intersection_json, surface_intersection_json,
};
pub use json_write::write_blend_nurbs_json;
pub use layout::{text_extent, text_width};
pub use mesh_files::{mesh_text, mesh_text_with_normals, polyline_text, MeshFormat};
pub use npy::{npy_bytes, read_npy_array, read_npy_file, read_npy_points};
pub use npz::{curve_to_npz, read_npz_curve, write_npz_curve};
pub use numfmt::fmt_number;
pub use obj::{grid_to_obj, polyline_to_obj};
pub use object::{read_json_lines, CurveJson, Object, FORMAT_VERSION};
pub use object_ext::{
    bezier_surface_to_json, bspline_surface_to_json, envelope_type, piecewise_polynomial_to_json,
    read_bezier_surface, read_bspline_surface, read_piecewise_polynomial,
};
pub use palette::{
    color_names, height_color, look, Marker, COLOR_NAMES, COLOR_WORDS, DASHES, LINE_COLORS, PALETTE,
};
#[cfg(feature = "parquet")]
pub use parquet::{
    read_curve_groups, read_parquet_points, read_point_groups, read_text_point_groups,
    table_to_parquet, GroupKey, ParquetBatchWriter, PointGroup, TextPointGroups, DEFAULT_KEY,
};
pub use png::svg_to_png;
pub use points_in::{
    line_of_point, parse_number_list, read_points, read_points_bytes, read_points_with, Header,
};
pub use samples::{coord_names, sample_table, SampleSpec, SampleTable};
pub use shape::{nurbs_surface_to_json, read_nurbs_surface, Shape, Surface, SurfaceJson};
pub use step::{step_real, CurveNet, StepWriter, SurfaceNet};
pub use step_read::{
    read_step, read_step_faces, read_step_limited, read_step_with_progress, skipped_by_kind,
    SkippedKind, Skips, StepFace, StepRead, StepSkipped, StepTriangulation, OTHER_KINDS,
    SKIPPED_KINDS, SKIPPED_LISTED, STEP_LOOP_RTOL, STEP_SHARED_VERTEX_RTOL,
};
pub use surface_plot::{surface_plot, ColorField, SurfacePlot, SURFACE_SAMPLES};
pub use surface_samples::{surface_sample_table, SurfaceSampleSpec};
pub use svg::{
    basis_figure, curve_figure, escape, knots_figure, residual_series, Annotation, Coincidence,
    ColorBar, CurvePlot, Face, Figure, Series, Style,
};
pub use tensor_json::{read_tensor, tensor_to_json, tensor_type_name};
pub use tensor_npz::{read_npz, read_npz_tensor, tensor_to_npz, write_npz_tensor};
pub use wireframe::{wireframe_figure, Grid, Projection};
