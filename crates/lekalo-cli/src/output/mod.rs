//! Writing results: to a file atomically (never over an input, `--force` for a write-protected
//! one) or to standard output; the output format by `--to` or extension; figures as SVG/PNG;
//! notes, progress bars and spinners on standard error.
//!
//! - `mod.rs`: the writes themselves, the format, notes and progress;
//! - `objects.rs`: one curve or surface in the format asked for (JSON, SVG/PNG, STEP, CSV,
//!   OBJ, NPZ).

pub(crate) mod objects;

use std::io::{IsTerminal, Write};
use std::path::{Path, PathBuf};

use anyhow::{Context as _, Result};

use crate::context::Context;
use crate::exit::bad_input;

/// Writes a line to standard error, ignoring a closed stderr (never panics), its control
/// characters shown as escapes ([`printable`]).
pub(crate) fn report(line: &str) {
    let _ = writeln!(std::io::stderr().lock(), "{}", printable(line));
}

/// `line` with its control characters other than newline and tab written as `\u{1b}`: a
/// message quotes names from the user's files (a JSON key, a Parquet column, a STEP entity's
/// name), and one holding an escape sequence (`\u{1b}[2J` clears the screen) or a NUL must
/// reach the terminal as text, not as a command to it.
fn printable(line: &str) -> std::borrow::Cow<'_, str> {
    let control = |c: char| c.is_control() && c != '\n' && c != '\t';
    if !line.chars().any(control) {
        return line.into();
    }
    line.chars()
        .map(|c| {
            if control(c) {
                c.escape_unicode().to_string()
            } else {
                c.to_string()
            }
        })
        .collect::<String>()
        .into()
}

/// The file an `-o` names: `None` for standard output (no `-o`, or `-`).
fn output_file(out: Option<&Path>) -> Option<&Path> {
    out.filter(|p| p.as_os_str() != "-")
}

/// The atomic write of one output file with the run's `--force`, then the `--verbose` report:
/// the frame of [`emit`], [`emit_stream`] and [`emit_seek`], whose `write` picks the writer.
fn write_file<E>(
    cx: &Context,
    p: &Path,
    what: &str,
    write: impl FnOnce(lekalo_io::WriteOptions) -> std::result::Result<(), E>,
) -> Result<()>
where
    anyhow::Error: From<E>,
{
    write(cx.write_options())?;
    if cx.is_verbose() {
        report(&format!("wrote {}{what}", p.display()));
    }
    Ok(())
}

/// Writes `bytes` to `out` atomically, or to standard output when `out` is `None` or `-`.
pub(crate) fn emit(
    out: Option<&Path>,
    bytes: &[u8],
    inputs: &[PathBuf],
    cx: &Context,
) -> Result<()> {
    if let Some(p) = output_file(out) {
        let size = format!(" ({} bytes)", bytes.len());
        return write_file(cx, p, &size, |o| {
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
    cx: &Context,
    fill: impl FnOnce(&mut dyn Write) -> std::io::Result<()>,
) -> Result<()> {
    if let Some(p) = output_file(out) {
        return write_file(cx, p, "", |o| {
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
    cx: &Context,
    fill: impl FnOnce(&mut dyn lekalo_io::WriteSeek) -> std::io::Result<()>,
) -> Result<()> {
    if let Some(p) = output_file(out) {
        return write_file(cx, p, "", |o| {
            lekalo_io::write_atomic_seek(p, inputs, o, fill)
        });
    }
    let mut made = std::io::Cursor::new(Vec::new());
    fill(&mut made).context("cannot make the output")?;
    emit(out, made.get_ref(), inputs, cx)
}

/// A progress bar on standard error, shown only if stderr is a terminal and not `--quiet`.
pub(crate) fn progress(cx: &Context, n: usize) -> indicatif::ProgressBar {
    if cx.is_quiet() || !std::io::stderr().is_terminal() {
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
pub(crate) fn spinner(cx: &Context, msg: String, large: bool) -> indicatif::ProgressBar {
    if !large || cx.is_quiet() || !std::io::stderr().is_terminal() {
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn formats_by_option_or_extension() {
        assert_eq!(format_of(None, Some(Path::new("a.STP")), "json"), "step");
        assert_eq!(format_of(Some("PNG"), None, "json"), "png");
        assert_eq!(format_of(None, None, "csv"), "csv");
    }

    #[test]
    fn control_characters_of_a_message_are_shown_as_escapes() {
        assert_eq!(
            printable("plain: é, ∞\ttab\nline"),
            "plain: é, ∞\ttab\nline"
        );
        assert_eq!(
            printable("unknown field `\u{1b}[2J\u{0}x\u{7f}\u{9b}`"),
            "unknown field `\\u{1b}[2J\\u{0}x\\u{7f}\\u{9b}`"
        );
    }
}
