//! Reading inputs, writing outputs, exit codes and progress for the subcommands.

use std::io::{IsTerminal, Write};
use std::path::{Path, PathBuf};
use std::sync::RwLock;
use std::time::Instant;

use anyhow::{Context, Result};
use lekalo_io::{IoError, Object, Shape};

use crate::Verbosity;

/// Default of `--max-size`.
pub(crate) const DEFAULT_MAX_SIZE: usize = 10_000_000;

/// Default of `--max-degree`.
pub(crate) const DEFAULT_MAX_DEGREE: usize = 2_000;

/// `--header`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub(crate) enum HeaderArg {
    /// A header only if no field on the first line is a number.
    Auto,
    /// The first line is a header.
    Yes,
    /// No header.
    No,
}

/// The global options that the input and output helpers follow.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Settings {
    pub(crate) header: HeaderArg,
    pub(crate) force: bool,
    pub(crate) max_size: usize,
    pub(crate) max_degree: usize,
}

const DEFAULT_SETTINGS: Settings = Settings {
    header: HeaderArg::Auto,
    force: false,
    max_size: DEFAULT_MAX_SIZE,
    max_degree: DEFAULT_MAX_DEGREE,
};

/// The global options of the command being run (set by [`configure`] at the start of every
/// command, read by the helpers on any thread).
static SETTINGS: RwLock<Settings> = RwLock::new(DEFAULT_SETTINGS);

static GROUP_COLUMN: RwLock<String> = RwLock::new(String::new());

/// Records `--group-column` for the command being run.
pub(crate) fn configure_group_column(name: String) {
    *GROUP_COLUMN
        .write()
        .unwrap_or_else(std::sync::PoisonError::into_inner) = name;
}

/// The key column of Parquet batches (`--group-column`).
pub(crate) fn group_column() -> String {
    let name = GROUP_COLUMN
        .read()
        .unwrap_or_else(std::sync::PoisonError::into_inner);
    if name.is_empty() {
        lekalo_io::DEFAULT_KEY.to_string()
    } else {
        name.clone()
    }
}

/// Records the global options for the command being run.
pub(crate) fn configure(s: Settings) {
    *SETTINGS
        .write()
        .unwrap_or_else(std::sync::PoisonError::into_inner) = s;
}

pub(crate) fn settings() -> Settings {
    *SETTINGS
        .read()
        .unwrap_or_else(std::sync::PoisonError::into_inner)
}

/// Writes a line to standard error, ignoring a closed stderr (never panics).
pub(crate) fn report(line: &str) {
    let _ = writeln!(std::io::stderr().lock(), "{line}");
}

/// The last-resort handler: a panic prints a short report and exits with code 3 (it is a bug;
/// every input error has its own message); the signal handlers are `cancel`'s.
pub(crate) fn install_handlers() {
    std::panic::set_hook(Box::new(|info| {
        lekalo_io::remove_temporary_files();
        let at = info
            .location()
            .map(|l| format!(" at {}:{}", l.file(), l.line()))
            .unwrap_or_default();
        let what = info
            .payload()
            .downcast_ref::<&str>()
            .map(|s| (*s).to_string())
            .or_else(|| info.payload().downcast_ref::<String>().cloned())
            .unwrap_or_default();
        report(&format!(
            "internal error{at}: {what}\nThis is a bug in lekalo: please report it with the command and input that caused it."
        ));
        std::process::exit(i32::from(EXIT_INTERNAL));
    }));
}

/// True if the error is a write to a closed pipe (`lekalo eval … | head`): the reader has
/// what it wanted, so the command stops quietly.
pub(crate) fn is_broken_pipe(e: &anyhow::Error) -> bool {
    e.chain().any(|c| {
        c.downcast_ref::<std::io::Error>()
            .is_some_and(|io| io.kind() == std::io::ErrorKind::BrokenPipe)
    })
}

/// `Err(BadInput)` if `n` (given by `option`) is above `--max-size`.
pub(crate) fn check_size(n: usize, option: &str) -> Result<()> {
    let limit = settings().max_size;
    if n > limit {
        return bad_input(format!(
            "{option} {n} is above the size limit {limit}; raise the limit with --max-size {n} if the machine has the memory"
        ));
    }
    Ok(())
}

/// `Err(BadInput)` if a Bezier curve's degree is above `--max-degree` for `what` (work that
/// grows as the degree squared or cubed).
pub(crate) fn check_bezier_degree(obj: &Object, what: &str) -> Result<()> {
    let limit = settings().max_degree;
    if let Object::Bezier(c) = obj {
        if c.degree() > limit {
            return bad_input(format!(
                "{what} of a Bezier curve of degree {} is above the degree limit {limit} (its cost grows as the degree squared or faster); raise it with --max-degree {}, or convert the curve to a B-spline of lower degree",
                c.degree(),
                c.degree()
            ));
        }
    }
    Ok(())
}

/// `n` given by `option` if it is in `[min, max]`, else `Err(BadInput)` naming the option and
/// the bound (never a silent clamp). `max` above `--max-size` is lowered to it.
pub(crate) fn in_range(n: usize, min: usize, max: usize, option: &str) -> Result<usize> {
    if n < min {
        return bad_input(format!("{option} {n}: at least {min} are needed"));
    }
    let limit = settings().max_size;
    if max >= limit {
        check_size(n, option)?;
    } else if n > max {
        return bad_input(format!(
            "{option} {n} is above {max}, the most this output can use; give at most {max}"
        ));
    }
    Ok(n)
}

/// Checks that `n` values of `T` can be allocated before a library call allocates them (an
/// allocation failure there would abort the process): `Err` naming `option` and `--max-size`.
pub(crate) fn check_memory<T>(n: usize, option: &str) -> Result<()> {
    let mut probe: Vec<T> = Vec::new();
    if probe.try_reserve_exact(n).is_err() {
        return bad_input(format!(
            "{option}: cannot reserve memory for {n} values ({} bytes); lower {option}",
            n.saturating_mul(std::mem::size_of::<T>())
        ));
    }
    Ok(())
}

/// Reads a points file (CSV, whitespace text, JSON; `-` is standard input) with `--header`,
/// or a NumPy `.npy` float64 array (by the extension).
pub(crate) fn read_points(path: &Path) -> Result<(lekalo::Points, String)> {
    if path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("npy"))
    {
        return Ok(lekalo_io::read_npy_file(path)?);
    }
    // bytes, checked as UTF-8 by the parallel parse part by part (not whole before it)
    let (bytes, name) = lekalo_io::read_input_bytes(path)?;
    let points = lekalo_io::read_points_bytes(&bytes, &name, header_rule())?;
    Ok((points, name))
}

/// The header rule of `--header`.
fn header_rule() -> lekalo_io::Header {
    match settings().header {
        HeaderArg::Auto => lekalo_io::Header::Auto,
        HeaderArg::Yes => lekalo_io::Header::Yes,
        HeaderArg::No => lekalo_io::Header::No,
    }
}

/// The points of the text of a points file named `name` (CSV, whitespace text, JSON), with
/// `--header`.
pub(crate) fn points_from_text(text: &str, name: &str) -> Result<lekalo::Points> {
    Ok(lekalo_io::read_points_with(text, name, header_rule())?)
}

/// Exit code for bad input.
pub(crate) const EXIT_BAD_INPUT: u8 = 2;
/// Exit code for an internal failure.
pub(crate) const EXIT_INTERNAL: u8 = 3;

/// A problem with the user's input or arguments (exit code 2).
#[derive(Debug)]
pub(crate) struct BadInput(pub(crate) String);

impl std::fmt::Display for BadInput {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for BadInput {}

/// An internal failure (exit code 3), e.g. a demo check that did not reproduce its document.
#[derive(Debug)]
pub(crate) struct Internal(pub(crate) String);

impl std::fmt::Display for Internal {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for Internal {}

/// `Err(BadInput)` with a message.
pub(crate) fn bad_input<T>(msg: impl Into<String>) -> Result<T> {
    Err(BadInput(msg.into()).into())
}

/// Exit code of an error: 2 if anything in its chain is the user's input, 3 otherwise.
pub(crate) fn exit_code(e: &anyhow::Error) -> u8 {
    for cause in e.chain() {
        if let Some(io) = cause.downcast_ref::<IoError>() {
            return if io.is_bad_input() {
                EXIT_BAD_INPUT
            } else {
                EXIT_INTERNAL
            };
        }
        if cause.downcast_ref::<BadInput>().is_some()
            || cause.downcast_ref::<lekalo::Error>().is_some()
        {
            return EXIT_BAD_INPUT;
        }
        if cause.downcast_ref::<Internal>().is_some() {
            return EXIT_INTERNAL;
        }
    }
    EXIT_INTERNAL
}

/// True for JSON Lines input: a `.jsonl`/`.ndjson` file, or `force`.
pub(crate) fn is_json_lines(path: &Path, force: bool) -> bool {
    force
        || matches!(
            path.extension().and_then(|e| e.to_str()),
            Some("jsonl" | "ndjson")
        )
}

/// The objects of an input: one curve, one surface or pp-form, or every line of JSON Lines
/// (curves) as `(line, object)`.
pub(crate) enum Loaded {
    One(Object),
    /// A single object that is not a curve (surface, piecewise polynomial).
    Other(Shape),
    Many(Vec<(usize, std::result::Result<Object, IoError>)>),
}

/// Reads an object file or JSON Lines (`-` is standard input).
pub(crate) fn load(path: &Path, jsonl: bool, v: Verbosity) -> Result<Loaded> {
    let start = Instant::now();
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
        return Ok(Loaded::One(lekalo_io::read_npz_curve(&bytes, &name)?));
    }
    let (text, name) = lekalo_io::read_input(path)?;
    // a CAD file: one shape as the JSON of that shape, several curves as a batch
    if let Some(mut shapes) = read_cad(path, &text, &name, v)? {
        return match shapes.len() {
            0 => bad_input(format!("{name}: no curve or surface lekalo reads")),
            1 => Ok(match shapes.remove(0) {
                Shape::Curve(o) => Loaded::One(o),
                other => Loaded::Other(other),
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
                Ok(Loaded::Many(curves))
            }
        };
    }
    let loaded = if is_json_lines(path, jsonl) {
        Loaded::Many(lekalo_io::read_json_lines(&text, &name))
    } else {
        match Shape::from_json_str(&text, &name)? {
            Shape::Curve(o) => Loaded::One(o),
            other => Loaded::Other(other),
        }
    };
    if v == Verbosity::Verbose {
        let n = match &loaded {
            Loaded::One(_) | Loaded::Other(_) => 1,
            Loaded::Many(m) => m.len(),
        };
        eprintln!("read {n} object(s) from {name} in {:.1?}", start.elapsed());
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

/// What a STEP file gave: curves, surfaces, schema, unit, skipped entities (not with `-q`).
fn report_step(name: &str, r: &lekalo_io::StepRead, v: Verbosity) {
    if v == Verbosity::Quiet {
        return;
    }
    let curves = r
        .shapes
        .iter()
        .filter(|(_, s)| matches!(s, lekalo_io::Shape::Curve(_)))
        .count();
    eprintln!(
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
    );
    report_skipped(name, &r.skipped, "#", v);
}

/// The entities a CAD file holds that were not read: one line per type and reason with the
/// count and the first id, and with `-v` every entity.
fn report_skipped(name: &str, skipped: &[lekalo_io::StepSkipped], prefix: &str, v: Verbosity) {
    if skipped.is_empty() {
        return;
    }
    eprintln!("{name}: skipped {} entities:", skipped.len());
    for k in lekalo_io::skipped_by_kind(skipped) {
        eprintln!(
            "  {:>6} {}: {} (first {prefix}{})",
            k.count, k.entity, k.reason, k.first_id
        );
    }
    if v == Verbosity::Verbose {
        for s in skipped {
            eprintln!("  {prefix}{} {}: {}", s.id, s.entity, s.reason);
        }
    }
}

/// The curves and surfaces of a STEP or IGES file, by its extension (`None` for any other
/// file), with what was read and skipped reported on standard error (not with `-q`).
pub(crate) fn read_cad(
    path: &Path,
    text: &str,
    name: &str,
    v: Verbosity,
) -> Result<Option<Vec<lekalo_io::Shape>>> {
    if is_step(path) {
        let r = lekalo_io::read_step(text, name)?;
        report_step(name, &r, v);
        return Ok(Some(r.shapes.into_iter().map(|(_, s)| s).collect()));
    }
    if is_iges(path) {
        let r = lekalo_io::read_iges(text, name)?;
        if v != Verbosity::Quiet {
            let curves = r
                .shapes
                .iter()
                .filter(|(_, s)| matches!(s, Shape::Curve(_)))
                .count();
            eprintln!(
                "{name}: read {curves} curve(s) and {} surface(s); length unit {}",
                r.shapes.len() - curves,
                r.length_unit
            );
            report_skipped(name, &r.skipped, "D", v);
        }
        return Ok(Some(r.shapes.into_iter().map(|(_, s)| s).collect()));
    }
    Ok(None)
}

/// Reads exactly one object (JSON Lines with one line is accepted too).
pub(crate) fn load_one(path: &Path, v: Verbosity) -> Result<Object> {
    match load(path, false, v)? {
        Loaded::One(o) => Ok(o),
        Loaded::Other(s) => not_a_curve(path, &s),
        Loaded::Many(mut m) if m.len() == 1 => Ok(m.remove(0).1?),
        Loaded::Many(m) => bad_input(format!(
            "{}: holds {} objects; this command takes one (keep one line of the file, e.g. `head -n 1 FILE > one.json`; `eval`, `info` and `convert` take whole batches)",
            path.display(),
            m.len()
        )),
    }
}

/// `Err(BadInput)` for a curve-only command given a surface or pp-form.
pub(crate) fn not_a_curve<T>(path: &Path, s: &Shape) -> Result<T> {
    bad_input(format!(
        "{}: field `type`: \"{}\" is not a curve; this command takes curves (info, convert and plot take surfaces and piecewise polynomials too)",
        path.display(),
        s.type_name()
    ))
}

/// The file an `-o` names: `None` for standard output (no `-o`, or `-`).
fn output_file(out: Option<&Path>) -> Option<&Path> {
    out.filter(|p| p.as_os_str() != "-")
}

/// The atomic write of one output file with the run's `--force`, then the `--verbose` report:
/// the frame of [`emit`], [`emit_stream`] and [`emit_seek`], whose `write` picks the writer.
fn write_file<E>(
    p: &Path,
    v: Verbosity,
    what: &str,
    write: impl FnOnce(lekalo_io::WriteOptions) -> std::result::Result<(), E>,
) -> Result<()>
where
    anyhow::Error: From<E>,
{
    write(lekalo_io::WriteOptions {
        force: settings().force,
    })?;
    if v == Verbosity::Verbose {
        report(&format!("wrote {}{what}", p.display()));
    }
    Ok(())
}

/// Writes `bytes` to `out` atomically, or to standard output when `out` is `None` or `-`.
pub(crate) fn emit(
    out: Option<&Path>,
    bytes: &[u8],
    inputs: &[PathBuf],
    v: Verbosity,
) -> Result<()> {
    if let Some(p) = output_file(out) {
        let size = format!(" ({} bytes)", bytes.len());
        return write_file(p, v, &size, |o| {
            lekalo_io::write_atomic_with(p, bytes, inputs, o)
        });
    }
    let mut stdout = std::io::stdout().lock();
    stdout
        .write_all(bytes)
        .and_then(|()| stdout.flush())
        .context("cannot write to standard output")?;
    // (a closed pipe is recognised by `is_broken_pipe` in the chain of this error)
    Ok(())
}

/// [`emit`] for output made piece by piece by `fill`: streamed into the temporary file (or to
/// standard output), never held whole in memory.
pub(crate) fn emit_stream(
    out: Option<&Path>,
    inputs: &[PathBuf],
    v: Verbosity,
    fill: impl FnOnce(&mut dyn Write) -> std::io::Result<()>,
) -> Result<()> {
    if let Some(p) = output_file(out) {
        return write_file(p, v, "", |o| {
            lekalo_io::write_atomic_stream(p, inputs, o, fill)
        });
    }
    let mut stdout = std::io::BufWriter::new(std::io::stdout().lock());
    fill(&mut stdout)
        .and_then(|()| stdout.flush())
        .context("cannot write to standard output")?;
    Ok(())
}

/// [`emit`] for output that seeks back in what it wrote (an `.npz` archive): written straight
/// into the temporary file; standard output is given it made in memory.
pub(crate) fn emit_seek(
    out: Option<&Path>,
    inputs: &[PathBuf],
    v: Verbosity,
    fill: impl FnOnce(&mut dyn lekalo_io::WriteSeek) -> std::io::Result<()>,
) -> Result<()> {
    if let Some(p) = output_file(out) {
        return write_file(p, v, "", |o| {
            lekalo_io::write_atomic_seek(p, inputs, o, fill)
        });
    }
    let mut made = std::io::Cursor::new(Vec::new());
    fill(&mut made).context("cannot make the output")?;
    emit(out, made.get_ref(), inputs, v)
}

/// A progress bar on standard error, shown only if stderr is a terminal and not `--quiet`.
pub(crate) fn progress(n: usize, v: Verbosity) -> indicatif::ProgressBar {
    if v == Verbosity::Quiet || !std::io::stderr().is_terminal() {
        return indicatif::ProgressBar::hidden();
    }
    let bar = indicatif::ProgressBar::new(n as u64);
    bar.set_style(
        indicatif::ProgressStyle::with_template("{msg} {bar:40} {pos}/{len} ({eta} left)")
            .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
    );
    bar
}

/// A spinner with a message on standard error for one long step (a large interpolation, a
/// high-degree reduction), shown only if stderr is a terminal, not `--quiet`, and the work is
/// `large`; cleared by `finish_and_clear`.
pub(crate) fn spinner(msg: String, large: bool, v: Verbosity) -> indicatif::ProgressBar {
    if !large || v == Verbosity::Quiet || !std::io::stderr().is_terminal() {
        return indicatif::ProgressBar::hidden();
    }
    let bar = indicatif::ProgressBar::new_spinner();
    bar.set_style(
        indicatif::ProgressStyle::with_template("{spinner} {msg} ({elapsed})")
            .unwrap_or_else(|_| indicatif::ProgressStyle::default_spinner()),
    );
    bar.set_message(msg);
    bar.enable_steady_tick(std::time::Duration::from_millis(120));
    bar
}

/// Output format chosen by `--to` or by the output file's extension.
pub(crate) fn format_of(to: Option<&str>, out: Option<&Path>, default: &str) -> String {
    if let Some(t) = to {
        return t.to_ascii_lowercase();
    }
    out.and_then(|p| p.extension())
        .and_then(|e| e.to_str())
        .map(|e| match e.to_ascii_lowercase().as_str() {
            "stp" | "step" | "p21" => "step".to_string(),
            "ndjson" => "jsonl".to_string(),
            other => other.to_string(),
        })
        .unwrap_or_else(|| default.to_string())
}

/// Parses a number list argument (`0,0.5,1`; fractions `5/17` allowed).
pub(crate) fn numbers(text: &str, what: &str) -> Result<Vec<f64>> {
    let mut out = Vec::new();
    for (i, s) in text
        .split([',', ' '])
        .filter(|s| !s.trim().is_empty())
        .enumerate()
    {
        let s = s.trim();
        let v = if let Some((a, b)) = s.split_once('/') {
            let parsed = (a.trim().parse::<f64>(), b.trim().parse::<f64>());
            match parsed {
                (Ok(a), Ok(b)) if b != 0.0 => Some(a / b),
                _ => None,
            }
        } else {
            s.parse::<f64>().ok()
        };
        match v.filter(|v| v.is_finite()) {
            Some(v) => out.push(v),
            None => {
                return bad_input(format!(
                    "{what}: value {} is \"{s}\", not a finite number (write e.g. 0.5 or 5/17)",
                    i + 1
                ))
            }
        }
    }
    if out.is_empty() {
        return bad_input(format!("{what}: no numbers given"));
    }
    Ok(out)
}

/// Parses a list of non-negative integers (`2,2,1`).
pub(crate) fn integers(text: &str, what: &str) -> Result<Vec<usize>> {
    text.split([',', ' '])
        .filter(|s| !s.trim().is_empty())
        .enumerate()
        .map(|(i, s)| {
            s.trim().parse::<usize>().map_err(|_| {
                BadInput(format!(
                    "{what}: value {} is \"{}\", not a non-negative integer",
                    i + 1,
                    s.trim()
                ))
                .into()
            })
        })
        .collect()
}

/// Encodes a figure as SVG or PNG bytes.
pub(crate) fn encode(fig: &lekalo_io::Figure, format: &str, scale: f32) -> Result<Vec<u8>> {
    match format {
        "svg" => Ok(fig.to_svg().into_bytes()),
        "png" => {
            if !(scale > 0.0 && scale <= 16.0) {
                return bad_input("--scale must be in (0, 16]");
            }
            Ok(lekalo_io::svg_to_png(&fig.to_svg(), scale)?)
        }
        other => bad_input(format!("cannot plot to {other}: use .svg or .png")),
    }
}

/// Writes the JSON lines of a batch, then reports failed lines (exit code 2 if any).
pub(crate) fn finish_batch(
    lines: Vec<(bool, String)>,
    out: Option<&std::path::Path>,
    inputs: &[PathBuf],
    v: Verbosity,
) -> Result<()> {
    let failed: Vec<String> = lines
        .iter()
        .filter(|(ok, _)| !ok)
        .filter_map(|(_, l)| serde_json::from_str::<serde_json::Value>(l).ok())
        .filter_map(|j| j["error"].as_str().map(str::to_string))
        .collect();
    let mut text = String::new();
    for (_, l) in &lines {
        text.push_str(l);
        text.push('\n');
    }
    emit(out, text.as_bytes(), inputs, v)?;
    failures(
        &failed,
        format!(
            "{} of {} objects failed (listed above and as \"error\" lines in the output)",
            failed.len(),
            lines.len()
        ),
        v,
    )
}

/// After a batch is written: each failure on its own line (unless quiet), then the batch's
/// error with `summary` (exit code 2); nothing when every object went through.
pub(crate) fn failures(failed: &[String], summary: String, v: Verbosity) -> Result<()> {
    if failed.is_empty() {
        return Ok(());
    }
    if v != Verbosity::Quiet {
        for e in failed {
            report(&format!("  {e}"));
        }
    }
    bad_input(summary)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn number_lists_and_codes() {
        assert_eq!(
            numbers("0, 5/17 1", "p").unwrap(),
            vec![0.0, 5.0 / 17.0, 1.0]
        );
        let e = numbers("0,x", "--params").unwrap_err();
        assert_eq!(exit_code(&e), EXIT_BAD_INPUT);
        assert!(e.to_string().contains("--params: value 2 is \"x\""), "{e}");
        assert!(numbers("1/0", "p").is_err());
        assert_eq!(integers("2,1", "c").unwrap(), vec![2, 1]);
        assert!(integers("-1", "c").is_err());
        assert_eq!(exit_code(&anyhow::anyhow!("plain")), EXIT_INTERNAL);
        let lib: anyhow::Error = lekalo::KnotVector::new(vec![1.0, 0.0]).unwrap_err().into();
        assert_eq!(exit_code(&lib), EXIT_BAD_INPUT);
        assert_eq!(format_of(None, Some(Path::new("a.STP")), "json"), "step");
        assert_eq!(format_of(Some("PNG"), None, "json"), "png");
        assert_eq!(format_of(None, None, "csv"), "csv");
    }
}
