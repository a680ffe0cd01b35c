//! The source of items: what a command reads. One object (a curve, or a surface, tensor or
//! pp-form), the lines of JSON Lines, the curves of a STEP or IGES file, or a points file;
//! each read once, by its kind (by the extension, `--jsonl`, `--header`).

use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::Result;
use lekalo_io::{IoError, Object, Shape};

use crate::context::Context;
use crate::exit::bad_input;

/// Reads a points file (CSV, whitespace text, JSON; `-` is standard input) with `--header`,
/// a NumPy `.npy` float64 array or a Parquet table of one row per point (by the extension;
/// at most `--max-size` rows).
pub(crate) fn read_points(cx: &Context, path: &Path) -> Result<(lekalo::Points, String)> {
    if path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("npy"))
    {
        return Ok(lekalo_io::read_npy_file(path)?);
    }
    // one table, without a key: one row per point (docs/formats.md#parquet-tables)
    if is_parquet(path) {
        let (points, _, name) = lekalo_io::read_parquet_points(path, cx.max_size)?;
        return Ok((points, name));
    }
    // bytes, checked as UTF-8 by the parallel parse part by part (not whole before it)
    let (bytes, name) = lekalo_io::read_input_bytes(path)?;
    let points = lekalo_io::read_points_bytes(&bytes, &name, cx.header_rule())?;
    Ok((points, name))
}

/// `e` with the lines of the points it names, where it is the library's error about points by
/// their index (two that coincide) and `path` a CSV or whitespace points file that can be read
/// again: `pts.csv lines 4 and 5: points 2 and 3 coincide: …`. Any other error is returned as
/// it is.
pub(crate) fn at_point_lines(cx: &Context, path: &Path, e: anyhow::Error) -> anyhow::Error {
    let Some(&lekalo::Error::CoincidentPoints { first, second }) = e.downcast_ref() else {
        return e;
    };
    if path.as_os_str() == "-" {
        return e;
    }
    let Ok(bytes) = std::fs::read(path) else {
        return e;
    };
    let line = |i| lekalo_io::line_of_point(&bytes, cx.header_rule(), i);
    match (line(first), line(second)) {
        (Some(a), Some(b)) => e.context(format!("{} lines {a} and {b}", path.display())),
        _ => e,
    }
}

/// The points of the text of a points file named `name` (CSV, whitespace text, JSON), with
/// `--header`.
pub(crate) fn points_from_text(cx: &Context, text: &str, name: &str) -> Result<lekalo::Points> {
    Ok(lekalo_io::read_points_with(text, name, cx.header_rule())?)
}

/// True for a Parquet batch: a `.parquet` (or `.pq`) path (docs/formats.md#parquet-batches).
pub(crate) fn is_parquet(path: &Path) -> bool {
    path.extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("parquet") || e.eq_ignore_ascii_case("pq"))
}

/// True for JSON Lines input: a `.jsonl`/`.ndjson` file, or `force`.
pub(crate) fn is_json_lines(path: &Path, force: bool) -> bool {
    force
        || matches!(
            path.extension().and_then(|e| e.to_str()),
            Some("jsonl" | "ndjson")
        )
}

/// The items of an input: one curve, one surface or pp-form, the curves of JSON Lines or of a
/// CAD file, or a Parquet batch of curves.
pub(crate) enum Items {
    /// One curve.
    One(Object),
    /// A single object that is not a curve (surface, tensor spline, piecewise polynomial).
    Other(Shape),
    /// Curves numbered by their line (or entity), each read or why it could not be: the lines
    /// of JSON Lines, the curves of a STEP or IGES file.
    Lines(Vec<(usize, std::result::Result<Object, IoError>)>),
    /// A Parquet batch of curves, not read here: the batch runner reads it a few MiB at a
    /// time (`batch::parquet`).
    Parquet(PathBuf),
}

/// Opens an object file, JSON Lines, a STEP or IGES file, or a Parquet batch (`-` is
/// standard input).
pub(crate) fn open(cx: &Context, path: &Path, jsonl: bool) -> Result<Items> {
    let start = Instant::now();
    if is_parquet(path) {
        return Ok(Items::Parquet(path.to_path_buf()));
    }
    if path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("npz"))
    {
        let bytes = std::fs::read(path).map_err(|error| IoError::Read {
            path: path.to_path_buf(),
            error,
        })?;
        lekalo_io::note_read(path);
        let name = path.display().to_string();
        return Ok(match lekalo_io::read_npz(&bytes, &name)? {
            lekalo_io::Shape::Curve(o) => Items::One(o),
            other => Items::Other(other),
        });
    }
    let (text, name) = lekalo_io::read_input(path)?;
    open_text(cx, path, jsonl, &text, &name, start)
}

/// True for standard input (`-`).
pub(crate) fn is_stdin(path: &Path) -> bool {
    path.as_os_str() == "-"
}

/// True for JSON Lines on standard input, which has no extension to tell: more than one
/// non-blank line, the first of them a whole object envelope (`{"lekalo": 1, "type": …}` on
/// one line), as `mesh -` decides. A pretty-printed object's first line is `{` alone.
fn stdin_lines(text: &str) -> bool {
    let mut lines = text
        .lines()
        .map(str::trim)
        .filter(|l| !l.is_empty() && !l.starts_with('#'));
    let first = lines.next();
    first.is_some_and(|l| lekalo_io::envelope_type(l).is_some()) && lines.next().is_some()
}

/// True for JSON Lines input: a `.jsonl`/`.ndjson` file, `jsonl` (`--jsonl`), or standard
/// input whose first line says so ([`stdin_lines`]).
pub(crate) fn lines_input(path: &Path, jsonl: bool, text: &str) -> bool {
    is_json_lines(path, jsonl) || (is_stdin(path) && stdin_lines(text))
}

/// The items of `text`, the input `path` read once and named `name` ([`open`]): for standard
/// input, which cannot be read twice, read before by the caller to see whether it holds faces
/// (`crate::cmd::files::cad::face_input`). On standard input, JSON Lines are recognised by
/// their first line ([`stdin_lines`]) and STEP and IGES files by their first bytes.
pub(crate) fn open_text(
    cx: &Context,
    path: &Path,
    jsonl: bool,
    text: &str,
    name: &str,
    start: Instant,
) -> Result<Items> {
    // a CAD file: one shape as the JSON of that shape, several curves as a batch
    if let Some(mut shapes) = read_cad(cx, path, text, name)? {
        return match shapes.len() {
            0 => bad_input(format!("{name}: no curve or surface lekalo reads")),
            1 => Ok(match shapes.remove(0) {
                Shape::Curve(o) => Items::One(o),
                other => Items::Other(other),
            }),
            n => {
                let curves: Vec<(usize, std::result::Result<Object, IoError>)> = shapes
                    .into_iter()
                    .enumerate()
                    .filter_map(|(i, s)| match s {
                        Shape::Curve(o) => Some((i + 1, Ok(o))),
                        _ => None,
                    })
                    .collect();
                if curves.len() < n {
                    return bad_input(format!(
                        "{name}: holds {n} shapes, {} of them surfaces; this command takes one \
                         surface or a batch of curves (`lekalo convert {name} -o shapes.jsonl` \
                         writes one shape a line)",
                        n - curves.len()
                    ));
                }
                Ok(Items::Lines(curves))
            }
        };
    }
    let loaded = if lines_input(path, jsonl, text) {
        Items::Lines(lekalo_io::read_json_lines(text, name))
    } else {
        match Shape::from_json_str(text, name)? {
            Shape::Curve(o) => Items::One(o),
            other => Items::Other(other),
        }
    };
    if cx.is_verbose() {
        let n = match &loaded {
            Items::Lines(m) => m.len(),
            _ => 1,
        };
        crate::output::report(&format!(
            "read {n} object(s) from {name} in {:.1?}",
            start.elapsed()
        ));
    }
    Ok(loaded)
}

fn extension(path: &Path) -> Option<String> {
    path.extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase)
}

/// True for a STEP input (`.step`, `.stp`, `.p21`).
pub(crate) fn is_step(path: &Path) -> bool {
    matches!(extension(path).as_deref(), Some("step" | "stp" | "p21"))
}

/// True for an IGES input (`.igs`, `.iges`).
pub(crate) fn is_iges(path: &Path) -> bool {
    matches!(extension(path).as_deref(), Some("igs" | "iges"))
}

/// True for STEP text: it opens with the keyword of ISO 10303-21 (§5), `ISO-10303-21;`.
pub(crate) fn is_step_text(text: &str) -> bool {
    text.trim_start().starts_with("ISO-10303-21")
}

/// True for IGES text: its first record is 72 columns and the Start section's letter `S` in
/// column 73 (IGES 5.3 §2.2), as every IGES file opens.
pub(crate) fn is_iges_text(text: &str) -> bool {
    text.lines()
        .next()
        .and_then(|l| l.as_bytes().get(72))
        .is_some_and(|&c| c == b'S')
}

/// What a STEP file gave: curves, surfaces, schema, unit, skipped entities (not with `-q`).
fn report_step(cx: &Context, name: &str, r: &lekalo_io::StepRead) {
    if cx.is_quiet() {
        return;
    }
    let curves = r
        .shapes
        .iter()
        .filter(|(_, s)| matches!(s, lekalo_io::Shape::Curve(_)))
        .count();
    crate::output::report(&format!(
        "{name}: read {curves} curve(s) and {} surface(s); schema {}; length unit {}{}",
        r.shapes.len() - curves,
        r.schema.as_deref().unwrap_or("not named"),
        r.length_unit,
        if r.scale_to_mm == 1.0 {
            String::new()
        } else {
            format!(
                " (coordinates × {} to millimetres)",
                lekalo_io::fmt_number(r.scale_to_mm)
            )
        }
    ));
    report_skipped(cx, name, &r.skipped, "#");
}

/// Kinds of skipped entities listed on standard error (the most frequent first); the rest are
/// counted on one line.
const SKIPPED_KINDS_LISTED: usize = 20;

/// How many skipped entities a CAD read keeps one by one: every one with `-v` (which lists
/// them) or when `all` is asked for, else the reader's default (the rest are counted by kind).
pub(crate) fn listed(cx: &Context, all: bool) -> usize {
    if all || cx.is_verbose() {
        usize::MAX
    } else {
        lekalo_io::SKIPPED_LISTED
    }
}

/// The entities a CAD file holds that were not read: one line per type and reason (the
/// entities a reason names aside: [`lekalo_io::Skips::kinds`]) with the count and the
/// first id, at most [`SKIPPED_KINDS_LISTED`] of them, and with `-v` every entity.
pub(crate) fn report_skipped(cx: &Context, name: &str, skipped: &lekalo_io::Skips, prefix: &str) {
    if skipped.is_empty() {
        return;
    }
    crate::output::report(&format!("{name}: skipped {} entities:", skipped.len()));
    let kinds = skipped.kinds();
    for k in kinds.iter().take(SKIPPED_KINDS_LISTED) {
        crate::output::report(&format!(
            "  {:>6} {}: {} (first {prefix}{})",
            k.count, k.entity, k.reason, k.first_id
        ));
    }
    if let Some(rest) = kinds.get(SKIPPED_KINDS_LISTED..).filter(|r| !r.is_empty()) {
        let n: usize = rest.iter().map(|k| k.count).sum();
        crate::output::report(&format!(
            "  … and {} more kinds of {n} entities{}",
            rest.len(),
            if cx.is_verbose() {
                ", listed below"
            } else {
                " (-v lists every entity)"
            }
        ));
    }
    if cx.is_verbose() {
        for s in skipped {
            crate::output::report(&format!("  {prefix}{} {}: {}", s.id, s.entity, s.reason));
        }
    }
}

/// CAD files from this size on show a progress bar while they are read (on a terminal, not
/// with `-q`).
const LARGE_CAD_BYTES: usize = 4 << 20;

/// Runs the read `f` of the CAD file `name` (its `text`) with a progress bar for a large file
/// and the cancel flag of Ctrl-C: an interrupted read leaves nothing written.
pub(crate) fn read_with_progress<R>(
    cx: &Context,
    name: &str,
    text: &str,
    f: impl FnOnce(&lekalo::Progress<'_>) -> R,
) -> R {
    crate::cancel::with_progress(
        cx,
        &format!("reading {name}"),
        text.len() >= LARGE_CAD_BYTES,
        f,
    )
}

/// The curves and surfaces of a STEP or IGES file, by its extension or, on standard input, by
/// its first bytes (`None` for any other file), with what was read and skipped reported on standard error (not with `-q`).
pub(crate) fn read_cad(
    cx: &Context,
    path: &Path,
    text: &str,
    name: &str,
) -> Result<Option<Vec<lekalo_io::Shape>>> {
    let stdin = is_stdin(path);
    if is_step(path) || (stdin && is_step_text(text)) {
        let r = read_with_progress(cx, name, text, |p| {
            lekalo_io::read_step_with_progress(text, name, cx.max_size, false, listed(cx, false), p)
        })?;
        report_step(cx, name, &r);
        return Ok(Some(r.shapes.into_iter().map(|(_, s)| s).collect()));
    }
    if is_iges(path) || (stdin && is_iges_text(text)) {
        let r = read_with_progress(cx, name, text, |p| {
            lekalo_io::read_iges_with_progress(text, name, cx.max_size, false, listed(cx, false), p)
        })?;
        if !cx.is_quiet() {
            let curves = r
                .shapes
                .iter()
                .filter(|(_, s)| matches!(s, lekalo_io::Shape::Curve(_)))
                .count();
            crate::output::report(&format!(
                "{name}: read {curves} curve(s) and {} surface(s); length unit {}",
                r.shapes.len() - curves,
                r.length_unit
            ));
            report_skipped(cx, name, &r.skipped, "D");
        }
        return Ok(Some(r.shapes.into_iter().map(|(_, s)| s).collect()));
    }
    Ok(None)
}

/// Reads exactly one object (JSON Lines with one line is accepted too).
pub(crate) fn load_one(cx: &Context, path: &Path) -> Result<Object> {
    match open(cx, path, false)? {
        Items::One(o) => Ok(o),
        Items::Other(s) => not_a_curve(path, &s),
        Items::Lines(mut m) if m.len() == 1 => Ok(m.remove(0).1?),
        Items::Lines(m) => bad_input(format!(
            "{}: holds {} objects; this command takes one (keep one line of the file, e.g. `head -n 1 FILE > one.json`; `eval`, `info` and `convert` take whole batches)",
            path.display(),
            m.len()
        )),
        Items::Parquet(_) => not_a_batch_command(path),
    }
}

/// `Err(BadInput)` for a command that reads one object given a Parquet batch.
pub(crate) fn not_a_batch_command<T>(path: &Path) -> Result<T> {
    bad_input(format!(
        "{}: a Parquet batch is read by interpolate, fit, eval and convert; `lekalo convert {} -o curves.jsonl` writes its curves as JSON Lines, which this command reads",
        path.display(),
        path.display()
    ))
}

/// `Err(BadInput)` for a curve-only command given a surface or pp-form.
pub(crate) fn not_a_curve<T>(path: &Path, s: &Shape) -> Result<T> {
    bad_input(format!(
        "{}: field `type`: \"{}\" is not a curve; this command takes curves (info, convert and plot take surfaces and piecewise polynomials too)",
        path.display(),
        s.type_name()
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::context::HeaderArg;

    /// A Parquet batch is recognised by its name and left to the batch runner unread; a
    /// command that reads one object says which commands read batches.
    #[test]
    fn a_parquet_batch_is_an_item_source_of_its_own() {
        let cx = Context::default();
        let path = Path::new("no-such-dir/curves.parquet");
        assert!(matches!(open(&cx, path, false), Ok(Items::Parquet(p)) if p == path));
        let e = load_one(&cx, path).unwrap_err();
        assert_eq!(crate::exit::exit_code(&e), crate::exit::EXIT_BAD_INPUT);
        assert!(
            e.to_string().contains("read by interpolate, fit, eval"),
            "{e}"
        );
    }

    /// Points are read with the context's `--header`.
    #[test]
    fn points_follow_the_header_of_the_context() {
        let text = "x,y\n1,2\n3,4\n";
        let auto = points_from_text(&Context::default(), text, "t").unwrap();
        assert_eq!(auto.len(), 2);
        let no = Context {
            header: HeaderArg::No,
            ..Context::default()
        };
        assert!(
            points_from_text(&no, text, "t").is_err(),
            "x is not a number"
        );
        let yes = Context {
            header: HeaderArg::Yes,
            ..Context::default()
        };
        assert_eq!(points_from_text(&yes, "1,2\n3,4\n", "t").unwrap().len(), 1);
    }
}
