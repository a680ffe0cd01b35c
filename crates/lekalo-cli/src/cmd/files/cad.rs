//! Objects of any kind in and out: one shape from a file, JSON Lines of shapes (curves and
//! surfaces mixed), and CAD files (STEP) as input of `convert`.

use std::path::{Path, PathBuf};

use anyhow::Result;
use lekalo_io::{Shape, StepWriter};

use crate::context::Context;
use crate::exit::bad_input;
use crate::items::{is_iges, is_json_lines, is_step, open, read_cad, Items};
use crate::output::{emit, format_of};

/// Reads exactly one object of any kind (curve, surface, piecewise polynomial).
pub(crate) fn load_shape(path: &Path, cx: &Context) -> Result<Shape> {
    match open(cx, path, false)? {
        Items::One(o) => Ok(Shape::Curve(o)),
        Items::Other(s) => Ok(s),
        Items::Lines(mut m) if m.len() == 1 => Ok(Shape::Curve(m.remove(0).1?)),
        Items::Lines(m) => bad_input(format!(
            "{}: holds {} objects; this command takes one (`lekalo knot join` joins pieces)",
            path.display(),
            m.len()
        )),
        Items::Parquet(_) => crate::items::not_a_batch_command(path),
    }
}

/// Every object of a file: JSON Lines of any kinds (one object per non-blank line, `#`
/// comments), a STEP file's curves and surfaces, or a single JSON object.
pub(crate) fn load_shapes(path: &Path, cx: &Context) -> Result<Vec<Shape>> {
    let (text, name) = lekalo_io::read_input(path)?;
    shapes_of_text(cx, path, &text, &name)
}

/// [`load_shapes`] of `text`, the input `path` read once and named `name` (standard input
/// read before to see whether it holds faces: [`face_input`]).
pub(crate) fn shapes_of_text(
    cx: &Context,
    path: &Path,
    text: &str,
    name: &str,
) -> Result<Vec<Shape>> {
    if let Some(shapes) = read_cad(cx, path, text, name)? {
        return Ok(shapes);
    }
    if !crate::items::lines_input(path, false, text) {
        return Ok(vec![Shape::from_json_str(text, name)?]);
    }
    let mut out = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let t = line.trim();
        if t.is_empty() || t.starts_with('#') {
            continue;
        }
        let s = Shape::from_json_str(t, &format!("{name}:{}", i + 1))?;
        out.push(s);
    }
    if out.is_empty() {
        return bad_input(format!("{name}: no objects"));
    }
    Ok(out)
}

/// `convert` of a file of several shapes (STEP, or JSON Lines holding surfaces) to json (one
/// shape), jsonl or step.
pub(crate) fn convert_shapes(
    input: &Path,
    output: Option<&Path>,
    to: Option<&str>,
    step_name: &str,
    timestamp: &str,
    read: Option<&(String, String)>,
    cx: &Context,
) -> Result<()> {
    let shapes = match read {
        Some((text, name)) => shapes_of_text(cx, input, text, name)?,
        None => load_shapes(input, cx)?,
    };
    let format = format_of(to, output, "jsonl");
    let bytes = match format.as_str() {
        "jsonl" => shapes
            .iter()
            .map(|s| s.to_json_line() + "\n")
            .collect::<String>(),
        "json" => match shapes.as_slice() {
            [one] => one.to_json_pretty(),
            _ => {
                return bad_input(format!(
                    "{}: {} objects; json output takes one (use -o FILE.jsonl or -o FILE.step)",
                    input.display(),
                    shapes.len()
                ))
            }
        },
        "step" => {
            let mut w = StepWriter::new(step_name);
            for s in &shapes {
                match s {
                    Shape::Curve(o) => {
                        w.add_object(o)?;
                    }
                    Shape::Surface(f) => {
                        w.add_any_surface(f)?;
                    }
                    other => {
                        return bad_input(format!(
                            "a {} cannot go into a STEP file",
                            other.type_name()
                        ))
                    }
                }
            }
            w.finish(timestamp)
        }
        "iges" | "igs" => {
            let mut w = lekalo_io::IgesWriter::new();
            for s in &shapes {
                match s {
                    Shape::Curve(o) => w.add_object(o)?,
                    Shape::Surface(f) => w.add_surface(f)?,
                    other => {
                        return bad_input(format!(
                            "a {} cannot go into an IGES file",
                            other.type_name()
                        ))
                    }
                }
            }
            w.finish(step_name, "20000101.000000")
        }
        other => {
            return bad_input(format!(
                "{}: several objects convert to jsonl, json (one object), step or iges, not \"{other}\"",
                input.display()
            ))
        }
    };
    let inputs: Vec<PathBuf> = vec![input.to_path_buf()];
    emit(output, bytes.as_bytes(), &inputs, cx)
}

/// The faces of a STEP file, or the trimmed surfaces of an IGES file (`--faces` of `convert`
/// and `info`), with how many were read and which were skipped and why reported on standard
/// error (not with `-q`). IGES faces come in the same record, ids being directory-entry
/// sequence numbers.
pub(crate) fn read_faces(path: &Path, cx: &Context) -> Result<lekalo_io::StepRead> {
    read_faces_of(path, None, false, cx)
}

/// [`read_faces`] of the input `path`, or of its text and name `read` already (standard input,
/// read once: [`face_input`]), a STEP or IGES file by its extension or its first bytes; with
/// `all_skipped` every skipped face is kept to be listed (else the first
/// [`lekalo_io::SKIPPED_LISTED`], the rest counted by reason).
pub(crate) fn read_faces_of(
    path: &Path,
    read: Option<(String, String)>,
    all_skipped: bool,
    cx: &Context,
) -> Result<lekalo_io::StepRead> {
    let listed = crate::items::listed(cx, all_skipped);
    let sniffed = read.as_ref().map(|(text, _)| text.as_str());
    let iges = is_iges(path) || sniffed.is_some_and(crate::items::is_iges_text);
    let step = is_step(path) || sniffed.is_some_and(crate::items::is_step_text);
    if !step && !iges {
        return bad_input(format!(
            "{}: --faces reads the faces of a STEP file (.step, .stp, .p21) or the trimmed surfaces of an IGES file (.igs, .iges)",
            path.display()
        ));
    }
    let (text, name) = match read {
        Some(read) => read,
        None => lekalo_io::read_input(path)?,
    };
    let r = if iges {
        let r = crate::items::read_with_progress(cx, &name, &text, |p| {
            lekalo_io::read_iges_with_progress(&text, &name, cx.max_size, true, listed, p)
        })?;
        lekalo_io::StepRead {
            shapes: r.shapes,
            skipped: r.skipped,
            faces: r.faces,
            triangulations: Vec::new(),
            skipped_faces: r.skipped_faces,
            schema: None,
            length_unit: r.length_unit,
            scale_to_mm: r.scale_to_mm,
        }
    } else {
        crate::items::read_with_progress(cx, &name, &text, |p| {
            lekalo_io::read_step_with_progress(&text, &name, cx.max_size, true, listed, p)
        })?
    };
    if !cx.is_quiet() {
        let with = r.faces.iter().filter(|f| f.pcurves.is_none()).count();
        let tessellated = match r.triangulations.len() {
            0 => String::new(),
            n => format!(
                ", and {n} face(s) of triangles ({} triangles: tessellated, written by `lekalo mesh`)",
                r.triangulations
                    .iter()
                    .map(|t| t.triangles.len())
                    .sum::<usize>()
            ),
        };
        crate::output::report(&format!(
            "{name}: read {} face(s), {with} with pcurves{tessellated}; length unit {}",
            r.faces.len(),
            r.length_unit
        ));
        crate::items::report_skipped(cx, &name, &r.skipped_faces, if iges { "D" } else { "#" });
    }
    Ok(r)
}

/// The faces of a JSON Lines file of face envelopes (docs/formats.md, "Faces"; its first
/// object is a `"type": "face"`), or `None` for any other input. Blank lines and `#` comments
/// are skipped; a line that is not a face is an error naming the line.
pub(crate) fn face_lines(path: &Path) -> Result<Option<Vec<lekalo_io::StepFace>>> {
    if !is_json_lines(path, false) || path.as_os_str() == "-" {
        return Ok(None);
    }
    let (text, name) = lekalo_io::read_input(path)?;
    face_lines_in(&text, &name)
}

/// The input of a command that reads faces or anything else (`info`, `convert`, `mesh`):
/// the faces of face JSON Lines, or else, for standard input, its text and name, read here
/// once (it cannot be read twice) for [`crate::items::open_text`]; a file other than face
/// JSON Lines is left unread (`(None, None)`), for its reader to open by its kind.
pub(crate) type FaceInput = (Option<Vec<lekalo_io::StepFace>>, Option<(String, String)>);

/// Reads `path` as [`FaceInput`] says: standard input is taken for faces when its first line
/// is a face envelope (docs/formats.md, "Faces"), as a file named `.jsonl` is.
pub(crate) fn face_input(path: &Path) -> Result<FaceInput> {
    if !crate::items::is_stdin(path) {
        return Ok((face_lines(path)?, None));
    }
    let (text, name) = lekalo_io::read_input(path)?;
    match face_lines_in(&text, &name)? {
        Some(faces) => Ok((Some(faces), None)),
        None => Ok((None, Some((text, name)))),
    }
}

/// The faces of `text` (read from `name`) when its first line is a face envelope, `None`
/// otherwise: for input read once whatever it is, as standard input must be.
pub(crate) fn face_lines_in(text: &str, name: &str) -> Result<Option<Vec<lekalo_io::StepFace>>> {
    let mut lines = text
        .lines()
        .enumerate()
        .map(|(i, l)| (i, l.trim()))
        .filter(|(_, l)| !l.is_empty() && !l.starts_with('#'))
        .peekable();
    match lines.peek() {
        Some((_, first)) if lekalo_io::envelope_type(first).as_deref() == Some("face") => {}
        _ => return Ok(None),
    }
    let faces = lines
        .map(|(i, l)| lekalo_io::read_face(l, &format!("{name}:{}", i + 1)))
        .collect::<Result<Vec<_>, _>>()?;
    Ok(Some(faces))
}

/// `convert --faces` (and `convert` of face JSON Lines): the faces of a STEP or IGES file, or
/// of a JSON Lines file of faces, written as JSON Lines (one face envelope a line), STEP (a
/// boundary representation: shared edges once, a closed shell when the faces close a volume)
/// or IGES (trimmed surfaces, entity 144).
pub(crate) fn convert_faces(
    input: &Path,
    faces: Option<Vec<lekalo_io::StepFace>>,
    read: Option<(String, String)>,
    output: Option<&Path>,
    to: Option<&str>,
    (name, timestamp): (&str, &str),
    cx: &Context,
) -> Result<()> {
    let format = format_of(to, output, "jsonl");
    if !matches!(format.as_str(), "jsonl" | "step" | "iges" | "igs") {
        return bad_input(format!(
            "faces are written as jsonl (one face a line), step or iges, not \"{format}\": use -o FILE.jsonl, FILE.step or FILE.igs"
        ));
    }
    let (faces, tessellated) = match faces {
        Some(f) => (f, 0),
        None => {
            let r = read_faces_of(input, read, false, cx)?;
            (r.faces, r.triangulations.len())
        }
    };
    if faces.is_empty() && format != "jsonl" {
        // faces of triangles are meshes, not faces bounded by curves on a surface
        let only = if tessellated > 0 {
            format!(
                "; its {tessellated} face(s) of triangles are written by `lekalo mesh {} -o mesh.obj`",
                input.display()
            )
        } else {
            String::new()
        };
        return bad_input(format!("{}: no faces to write{only}", input.display()));
    }
    let text: String = match format.as_str() {
        "step" => {
            let mut w = StepWriter::new(name);
            w.add_faces(&faces)?;
            w.finish(timestamp)
        }
        "iges" | "igs" => {
            let mut w = lekalo_io::IgesWriter::new();
            w.add_faces(&faces)?;
            w.finish(name, "20000101.000000")
        }
        _ => faces
            .iter()
            .map(|f| lekalo_io::face_to_json_line(f) + "\n")
            .collect(),
    };
    emit(output, text.as_bytes(), &[input.to_path_buf()], cx)
}

/// True when `convert` should take the many-shapes path: a STEP input, or JSON Lines holding
/// something other than curves.
pub(crate) fn wants_shapes(
    input: &Path,
    jsonl: bool,
    out_format: &str,
    stdin: Option<&str>,
) -> bool {
    if is_step(input) || is_iges(input) {
        return true;
    }
    if matches!(out_format, "iges" | "igs") {
        return true;
    }
    if let Some(text) = stdin {
        return crate::items::is_step_text(text)
            || crate::items::is_iges_text(text)
            || (crate::items::lines_input(input, jsonl, text)
                && (text.contains("_surface\"") || text.contains("piecewise_polynomial")));
    }
    if !is_json_lines(input, jsonl) || input.as_os_str() == "-" {
        return false;
    }
    // through the input limit: a named pipe or a device here must not be read without end
    lekalo_io::read_input(input)
        .map(|(t, _)| t.contains("_surface\"") || t.contains("piecewise_polynomial"))
        .unwrap_or(false)
}
