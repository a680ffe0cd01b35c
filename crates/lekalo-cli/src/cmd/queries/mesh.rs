//! `lekalo mesh`: a surface as a triangle mesh (OBJ, ASCII STL or PLY) or a curve as a polyline
//! (OBJ), within a proved deviation.

use std::path::PathBuf;

use anyhow::Result;
use clap::Args;
use lekalo_io::Shape;
use serde_json::json;

use crate::cmd::measure::{query_curve, query_surface};
use crate::context::Context;
use crate::exit::bad_input;
use crate::output::{emit, format_of};
use crate::words::in_file;

/// Arguments of `lekalo mesh`.
#[derive(Args, Debug)]
#[command(after_help = "\
Surfaces (B-spline, Bezier or NURBS): a triangle mesh whose deviation from the surface is at most
the tolerance, a bound proved from the control net (and the weights). Curves: a polyline within the tolerance. The
format follows the output's extension (.obj, .stl, .ply) or --format; --json prints the counts
and the bound instead of writing geometry to standard output.

Faces (a JSON Lines file of face envelopes, as `convert --faces` writes, or the faces of a STEP
or IGES file): one mesh of all faces,
each trimmed by its loops, the faces meeting at the same points along their shared edges. An
edge without its curve in the surface's (u, v) gets one by projecting it onto the surface; a
face whose loops go round a closed surface without a seam edge (a band between two circles, a
cap round a pole) is cut along a seam; a face that cannot be meshed (an edge off its surface,
loops outside the surface's domain, crossing themselves or each other, a hole outside its
outer loop) is listed with the reason and left out. Pcurves past the domain by at most 1e-4 of
its width are clipped to it, and edges and holes of no length dropped: listed as repaired.

Normals: OBJ writes a unit normal per vertex (`vn`, faces `f v//vn`): on a meshed surface or
face the surface's exact normal S_u x S_v at the vertex, turned with the face's sense; at a
pole, where it is undefined, the area-weighted average of the vertex's triangles' normals; on
a face of triangles the normals the file gives (none if it gives none). PLY writes them (nx ny
nz) when every vertex has one; STL writes each triangle's own normal.

Examples:
  lekalo mesh surface.json --tolerance 1e-3 -o surface.obj
  lekalo mesh faces.jsonl --tolerance 1e-3 -o faces.obj
  lekalo mesh surface.json --tolerance 1e-4 -o surface.stl
  lekalo mesh curve.json --tolerance 1e-3 -o curve.obj")]
pub(crate) struct MeshArgs {
    /// Surface or curve file (JSON), or faces (JSON Lines of face envelopes, or a STEP or IGES
    /// file).
    input: PathBuf,
    /// Largest deviation (in the object's units).
    #[arg(long, short = 't')]
    tolerance: f64,
    /// Output format: obj, stl or ply (default: from the output's extension, else obj).
    #[arg(long)]
    format: Option<String>,
    /// Print a JSON summary (vertices, triangles, deviation) to standard error... and standard
    /// output when no file is written.
    #[arg(long)]
    json: bool,
    /// Output file (default: standard output).
    #[arg(short, long, value_name = "FILE")]
    output: Option<PathBuf>,
}

pub(crate) fn run(a: &MeshArgs, cx: &Context) -> Result<()> {
    // kept in the chain: a refused tolerance (too small, or a mesh too large to make) carries
    // the key of the tolerance and is written under --tolerance; other errors as they are
    let bad = |e: lekalo::Error| in_file(&a.input, e);
    let fmt = format_of(a.format.as_deref(), a.output.as_deref(), "obj");
    // the faces of a STEP or IGES file as those of a face JSON Lines file (`convert --faces`)
    // any other input is read once (standard input cannot be read twice) and holds faces when
    // its first line is a face envelope, whatever the file's name
    let (faces, read) = if crate::items::is_step(&a.input) || crate::items::is_iges(&a.input) {
        let r = crate::cmd::files::cad::read_faces(&a.input, cx)?;
        (Some((r.faces, r.triangulations)), None)
    } else {
        let (text, name) = lekalo_io::read_input(&a.input)?;
        let faces = crate::cmd::files::cad::face_lines_in(&text, &name)?;
        (faces.map(|f| (f, Vec::new())), Some((text, name)))
    };
    if let Some((faces, triangulations)) = faces {
        // an edge without its (u, v) curve gets one by projection; a face that still cannot be
        // meshed is counted with the reason
        let mut ready: Vec<(usize, lekalo::Face)> = Vec::with_capacity(faces.len());
        let mut skipped: Vec<(usize, String)> = Vec::new();
        for (k, f) in faces.iter().enumerate() {
            if f.face.has_pcurves() {
                ready.push((k, f.face.clone()));
                continue;
            }
            match f.face.with_projected_pcurves(a.tolerance) {
                Ok(g) => ready.push((k, g)),
                // a bad tolerance fails every face alike: refused, not listed per face
                Err(e) if e.arg() == Some(lekalo::Arg::Tolerance) => return Err(bad(e)),
                Err(e) => skipped.push((k, e.to_string())),
            }
        }
        // one pass: each face meshed once, a face that fails listed with its error and the
        // others meshed as they are without it (a file of faces of triangles only has none)
        let meshed = if ready.is_empty() {
            None
        } else {
            Some(
                lekalo::topology::mesh_faces_each(
                    &ready.iter().map(|(_, f)| f).collect::<Vec<_>>(),
                    a.tolerance,
                )
                .map_err(bad)?,
            )
        };
        let (failures, above, repairs) = match &meshed {
            Some(m) => (&m.failures[..], &m.above_tolerance[..], &m.repairs[..]),
            None => (&[][..], &[][..], &[][..]),
        };
        let meshed_faces = meshed.as_ref().map_or(0, |m| m.meshes.len());
        skipped.extend(failures.iter().map(|(i, e)| (ready[*i].0, e.to_string())));
        skipped.sort_by_key(|(k, _)| *k);
        let name = |k: usize| {
            let f = &faces[k];
            if f.name.is_empty() {
                format!("#{}", f.id)
            } else {
                format!("#{} ({})", f.id, f.name)
            }
        };
        if meshed_faces == 0 && triangulations.is_empty() {
            if faces.is_empty() {
                // nothing bounded by curves, and no face of triangles read: the reader listed
                // what it skipped, with the reasons, on standard error
                return bad_input(format!(
                    "{}: no face to mesh (the faces the file holds could not be read: see the \
                     reasons listed above)",
                    a.input.display()
                ));
            }
            let first = skipped
                .first()
                .map(|(k, r)| format!("; face {}: {r}", name(*k)))
                .unwrap_or_default();
            return bad_input(format!(
                "{}: none of the {} faces can be meshed{first}",
                a.input.display(),
                skipped.len()
            ));
        }
        if !skipped.is_empty() {
            crate::output::report(&format!(
                "warning: {}: {} of {} faces not meshed:",
                a.input.display(),
                skipped.len(),
                faces.len()
            ));
            for (k, r) in &skipped {
                crate::output::report(&format!("  face {}: {r}", name(*k)));
            }
        }
        // trims repaired before meshing (clipped to the domain within the tolerance, edges
        // and holes of no length dropped): named, and listed in the summary
        let repaired: Vec<(usize, String)> = repairs
            .iter()
            .map(|(i, r)| (ready[*i].0, r.to_string()))
            .collect();
        for (k, r) in &repaired {
            crate::output::report(&format!("note: face {}: {r}", name(*k)));
        }
        // faces whose proved bound stayed above the tolerance: written, named, and exit 2
        let coarse: Vec<(usize, String)> = above
            .iter()
            .map(|(i, e)| (ready[*i].0, e.to_string()))
            .collect();
        for (k, r) in &coarse {
            crate::output::report(&format!("warning: face {}: {r}", name(*k)));
        }
        // the faces meshed, then the faces of triangles as the file gives them (their triangles
        // are the geometry), as one mesh with the normals of its vertices (none when no vertex
        // has one)
        let tessellated_triangles: usize = triangulations.iter().map(|t| t.triangles.len()).sum();
        let joined = lekalo_io::join_cad_mesh(
            meshed.as_ref(),
            &ready.iter().map(|(_, f)| f).collect::<Vec<_>>(),
            &triangulations,
        )
        .map_err(bad)?;
        drop(meshed);
        let (m, normals) = (joined.mesh, joined.normals);
        let listed = |l: &[(usize, String)]| -> Vec<serde_json::Value> {
            l.iter()
                .map(|(k, r)| json!({"id": faces[*k].id, "name": faces[*k].name, "reason": r}))
                .collect()
        };
        let summary = json!({"faces": meshed_faces, "tessellated": triangulations.len(), "tessellated_triangles": tessellated_triangles, "skipped": skipped.len(), "skipped_faces": listed(&skipped), "above_tolerance": listed(&coarse), "repaired": listed(&repaired), "vertices": m.vertices.len(), "triangles": m.triangles.len(), "deviation": m.deviation});
        write_mesh(a, cx, &m, &normals, &fmt, &summary)?;
        if let Some((k, _)) = coarse.first() {
            // the joined mesh's deviation is the largest of its faces'
            let worst = m.deviation;
            return bad_input(format!(
                "{}: --tolerance {}: the mesh is written, but {} of its faces (first face {}) \
                 could not be refined within it: their proved deviation bound reaches {}; \
                 use --tolerance {} or more for a mesh within its tolerance",
                a.input.display(),
                lekalo_io::fmt_number(a.tolerance),
                coarse.len(),
                name(*k),
                lekalo_io::fmt_number(worst),
                lekalo_io::fmt_number(worst)
            ));
        }
        return Ok(());
    }
    let (text, name) = match read {
        Some(read) => read,
        None => lekalo_io::read_input(&a.input)?,
    };
    let objects = text.lines().filter(|l| !l.trim().is_empty()).count();
    if crate::items::is_json_lines(&a.input, false) && objects > 1 {
        // JSON Lines that are not face envelopes (a batch of curves or surfaces): one object a call
        return bad_input(format!(
            "{}: {objects} objects; mesh reads one curve or surface, or faces (JSON Lines of face \
             envelopes, as `convert --faces` writes): write each line to a .json file and mesh each",
            a.input.display()
        ));
    }
    let shape = Shape::from_json_str(&text, &name)?;
    let (body, summary) = match shape {
        Shape::Surface(s) => {
            let q = query_surface(&s, &a.input)?;
            // a bar on a terminal; Ctrl-C stops the mesh between two parts of its work
            let m = crate::cancel::with_progress(cx, "meshing", true, |p| {
                q.mesh_with_progress(a.tolerance, p)
            })
            .map_err(bad)?;
            let summary = json!({"vertices": m.vertices.len(), "triangles": m.triangles.len(), "deviation": m.deviation});
            let normals = m.surface_normals(&s, true);
            return write_mesh(a, cx, &m, &normals, &fmt, &summary);
        }
        Shape::Curve(obj) => {
            let q = query_curve(&obj, &a.input)?;
            let poly = q.polyline(a.tolerance).map_err(bad)?;
            if fmt != "obj" {
                return bad_input(format!(
                    "--format {fmt}: a curve is written as an OBJ polyline"
                ));
            }
            let s = lekalo_io::polyline_text(&poly);
            let summary = json!({"vertices": poly.points.len(), "deviation": poly.deviation});
            (s, summary)
        }
        _ => return bad_input(format!("{}: mesh curves and surfaces", a.input.display())),
    };
    finish(a, cx, &body, &summary)
}

/// A triangle mesh in the format asked for, with the normals of its vertices (OBJ `vn`, PLY
/// `nx ny nz`; none when empty), written with its summary.
fn write_mesh(
    a: &MeshArgs,
    cx: &Context,
    m: &lekalo::query::Mesh,
    normals: &[Option<[f64; 3]>],
    fmt: &str,
    summary: &serde_json::Value,
) -> Result<()> {
    let format = match lekalo_io::MeshFormat::from_name(fmt) {
        Ok(f) => f,
        Err(_) => return bad_input(format!("--format {fmt}: use obj, stl or ply")),
    };
    let body = match lekalo_io::mesh_text_with_normals(m, normals, format) {
        Ok(b) => b,
        Err(_) => return bad_input("meshes are written for 3-D surfaces"),
    };
    finish(a, cx, &body, summary)
}

/// Writes `body` to the output (or the summary alone with `--json` and no output).
fn finish(a: &MeshArgs, cx: &Context, body: &str, summary: &serde_json::Value) -> Result<()> {
    if a.json && a.output.is_none() {
        return emit(
            None,
            format!("{summary:#}\n").as_bytes(),
            std::slice::from_ref(&a.input),
            cx,
        );
    }
    if a.json {
        crate::output::report(&summary.to_string());
    }
    emit(
        a.output.as_deref(),
        body.as_bytes(),
        std::slice::from_ref(&a.input),
        cx,
    )
}
