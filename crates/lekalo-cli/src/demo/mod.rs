//! `lekalo demo`: the documents' constructions on built-in data. Every gallery entry builds its
//! objects with the library, draws figures and checks its key numbers against the documents;
//! the summary table lists every check, the HTML gallery shows the figures (SVG and PNG) with
//! captions, links to the theory reference and the command that redraws them.
//!
//! To add a construction, write a `fn(&mut Section) -> Result<()>` and list it in
//! [`registry::ENTRIES`]. A captioned figure is one call:
//!
//! ```ignore
//! s.figure(fig, Caption::new("Two or three sentences: what it is, what to look at.")
//!     .theory("fitting.md#least-squares"));
//! ```

use std::fmt::Write as _;
use std::path::Path;

use anyhow::{Context as _, Result};
use lekalo_io::{escape, Figure};
use rayon::prelude::*;

use crate::context::Context;
use crate::exit::Internal;

mod registry;

/// One gallery entry, filled by its build function.
pub(crate) struct Section {
    /// Short id, used for file names (`doc002-bspline`).
    pub(crate) id: &'static str,
    /// Title.
    pub(crate) title: &'static str,
    /// Source: document and section.
    pub(crate) source: &'static str,
    /// Paragraph describing the construction.
    pub(crate) caption: String,
    /// Figures with their captions.
    pub(crate) figures: Vec<(Figure, Caption)>,
    /// Tables: (caption, header, rows).
    pub(crate) tables: Vec<(String, Vec<String>, Vec<Vec<String>>)>,
    /// Checked numbers.
    pub(crate) checks: Vec<Check>,
}

/// What the gallery shows under a figure: what the construction is and what to look at, the
/// section of the theory reference it illustrates, and the command that redraws it.
#[derive(Debug, Clone, Default)]
pub(crate) struct Caption {
    /// Two or three sentences.
    pub(crate) text: String,
    /// Page and anchor under `docs/theory/` (`interpolation.md#end-conditions`).
    pub(crate) theory: Option<String>,
    /// A `lekalo …` command that draws the figure from its data (default: `lekalo demo --only`).
    pub(crate) command: Option<String>,
}

impl Caption {
    /// A caption of the given text.
    pub(crate) fn new(text: impl Into<String>) -> Self {
        Caption {
            text: text.into(),
            ..Caption::default()
        }
    }

    /// The section of the theory reference: a page under `docs/theory/` and its anchor.
    #[must_use]
    pub(crate) fn theory(mut self, page_and_anchor: &str) -> Self {
        self.theory = Some(page_and_anchor.to_string());
        self
    }

    /// A command that draws the figure from its data.
    #[must_use]
    pub(crate) fn command(mut self, command: &str) -> Self {
        self.command = Some(command.to_string());
        self
    }
}

impl From<&str> for Caption {
    fn from(text: &str) -> Self {
        Caption::new(text)
    }
}

impl From<String> for Caption {
    fn from(text: String) -> Self {
        Caption::new(text)
    }
}

/// A number compared with the document's value.
pub(crate) struct Check {
    pub(crate) what: String,
    pub(crate) ours: String,
    pub(crate) expected: String,
    pub(crate) ok: bool,
}

impl Section {
    /// Adds a figure with its caption. Curves the figure draws on top of each other are named
    /// in the caption (the figure draws the later one dashed over the earlier).
    pub(crate) fn figure(&mut self, fig: Figure, caption: impl Into<Caption>) {
        self.figures.push((fig, caption.into()));
    }

    /// Checks `ours` against `expected` within `tol` (absolute; the values are O(1)).
    pub(crate) fn check(&mut self, what: &str, ours: f64, expected: f64, shown: &str, tol: f64) {
        self.checks.push(Check {
            what: what.to_string(),
            ours: trim(ours),
            expected: shown.to_string(),
            ok: (ours - expected).abs() <= tol,
        });
    }

    /// Checks a vector element-wise.
    pub(crate) fn check_all(
        &mut self,
        what: &str,
        ours: &[f64],
        expected: &[f64],
        shown: &str,
        tol: f64,
    ) {
        let ok = ours.len() == expected.len()
            && ours.iter().zip(expected).all(|(a, b)| (a - b).abs() <= tol);
        let o: Vec<String> = ours.iter().map(|x| trim(*x)).collect();
        self.checks.push(Check {
            what: what.to_string(),
            ours: o.join(", "),
            expected: shown.to_string(),
            ok,
        });
    }
}

/// A number with at most 6 decimals, trailing zeros removed.
pub(crate) fn trim(x: f64) -> String {
    let s = format!("{x:.6}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" {
        "0".into()
    } else {
        s.to_string()
    }
}

/// Runs every entry (or the one named by `only`), prints the summary table, writes the gallery
/// if `out` is given: `index.html` and every figure as SVG and PNG. With `only`, an existing
/// `index.html` keeps its other entries: only the entry's section is replaced.
pub(crate) fn run(cx: &Context, out: Option<&Path>, only: Option<&str>, json: bool) -> Result<()> {
    if let Some(id) = only {
        if !registry::ENTRIES.iter().any(|e| e.id == id) {
            let ids: Vec<&str> = registry::ENTRIES.iter().map(|e| e.id).collect();
            return crate::exit::bad_input(format!(
                "--only {id}: no such demo entry; the entries are {}",
                ids.join(", ")
            ));
        }
    }
    let mut sections = Vec::new();
    let bar = crate::output::progress(cx, registry::ENTRIES.len());
    for entry in registry::ENTRIES {
        bar.inc(1);
        if only.is_some_and(|id| id != entry.id) {
            continue;
        }
        let mut s = Section {
            id: entry.id,
            title: entry.title,
            source: entry.source,
            caption: String::new(),
            figures: Vec::new(),
            tables: Vec::new(),
            checks: Vec::new(),
        };
        (entry.build)(&mut s).with_context(|| format!("demo entry {}", entry.id))?;
        sections.push(s);
    }
    bar.finish_and_clear();
    crate::report::print_report(
        json,
        &summary_json(&sections),
        |_| summary(&sections, cx),
        None,
        &[],
        cx,
    )?;
    if let Some(dir) = out {
        std::fs::create_dir_all(dir).map_err(|error| lekalo_io::IoError::Write {
            path: dir.to_path_buf(),
            error,
        })?;
        let figures: Vec<(String, &Figure)> = sections
            .iter()
            .flat_map(|s| {
                s.figures
                    .iter()
                    .enumerate()
                    .map(move |(k, (fig, _))| (format!("{}-{}", s.id, k + 1), fig))
            })
            .collect();
        // the PNGs are most of the time: render them on every core
        figures
            .par_iter()
            .try_for_each(|(name, fig)| -> Result<()> {
                let svg = fig.to_svg();
                lekalo_io::write_atomic(&dir.join(format!("{name}.svg")), svg.as_bytes(), &[])?;
                let png = lekalo_io::svg_to_png(&svg, PNG_SCALE)?;
                lekalo_io::write_atomic(&dir.join(format!("{name}.png")), &png, &[])?;
                Ok(())
            })?;
        let index = dir.join("index.html");
        let theory = theory_base(dir);
        let mut html = gallery(&sections, theory.as_deref());
        // `--only` redraws one entry: in an existing gallery, only its section is replaced
        if let (Some(id), Ok(old)) = (only, std::fs::read_to_string(&index)) {
            if let Some(updated) = replace_section(&old, &html, id) {
                html = updated;
            }
        }
        lekalo_io::write_atomic(&index, html.as_bytes(), &[])?;
        if !cx.is_quiet() {
            // a note: a closed standard error (`lekalo demo --out g 2>&1 | head`) does not stop
            // the command
            crate::output::report(&format!(
                "gallery: {} ({} figures, SVG and PNG); open it in a browser",
                index.display(),
                figures.len()
            ));
        }
    }
    let failed: Vec<String> = sections
        .iter()
        .flat_map(|s| {
            s.checks
                .iter()
                .filter(|c| !c.ok)
                .map(move |c| format!("{}: {}", s.id, c.what))
        })
        .collect();
    if failed.is_empty() {
        Ok(())
    } else {
        Err(Internal(format!(
            "{} check(s) did not reproduce the documents: {}",
            failed.len(),
            failed.join("; ")
        ))
        .into())
    }
}

/// The gallery `old` with the section of entry `id` taken from the gallery `fresh` (in place,
/// or before the end of the page if `old` has none); `None` if `old` is not a gallery or
/// `fresh` has no such section.
fn replace_section(old: &str, fresh: &str, id: &str) -> Option<String> {
    let open = format!("<section id=\"{id}\">");
    let close = "</section>\n";
    let span = |h: &str| -> Option<(usize, usize)> {
        let start = h.find(&open)?;
        let end = start + h[start..].find(close)? + close.len();
        Some((start, end))
    };
    let (fs, fe) = span(fresh)?;
    let section = &fresh[fs..fe];
    if let Some((os, oe)) = span(old) {
        return Some(format!("{}{section}{}", &old[..os], &old[oe..]));
    }
    let end = old.rfind("</body>")?;
    Some(format!("{}{section}{}", &old[..end], &old[end..]))
}

/// Scale of the gallery's PNGs (2: sharp on slides and high-density screens).
const PNG_SCALE: f32 = 2.0;

/// The relative path from the gallery directory to the repository's `docs/theory/`, if the
/// gallery is written inside a checkout (else the captions name the page without a link).
fn theory_base(dir: &Path) -> Option<String> {
    let dir = dir.canonicalize().ok()?;
    let mut up = String::new();
    for anc in dir.ancestors() {
        if anc.join("docs").join("theory").is_dir() {
            return Some(format!("{up}docs/theory/"));
        }
        up.push_str("../");
    }
    None
}

/// The caption of a figure as shown: its text, then the note of every pair of curves drawn
/// on top of each other.
pub(crate) fn full_caption(fig: &Figure, caption: &Caption) -> String {
    let mut text = caption.text.clone();
    for c in fig.coincidences() {
        text.push(' ');
        text.push_str(&c.note());
    }
    text
}

/// The command that redraws figure `k` (1-based) of entry `id`.
pub(crate) fn command_of(id: &str, caption: &Caption) -> String {
    caption
        .command
        .clone()
        .unwrap_or_else(|| format!("lekalo demo --only {id} -o gallery"))
}

/// The gallery's document groups: (id prefix, heading).
const DOCUMENTS: &[(&str, &str)] = &[
    (
        "doc000",
        "Document 000: interpolation of curves and surfaces",
    ),
    ("doc001", "Document 001: blending by polynomial deformation"),
    ("doc002", "Document 002: B-splines and the Hermite form"),
    (
        "doc003",
        "Document 003: piecewise polynomials and their B-spline bases",
    ),
    (
        "doc004",
        "Document 004: order change of Bezier curves and surfaces",
    ),
];

/// Heading of the group of an entry id: its document, or the id's first word.
fn group_of(id: &str) -> String {
    let prefix = id.split('-').next().unwrap_or(id);
    DOCUMENTS
        .iter()
        .find(|(p, _)| *p == prefix)
        .map_or_else(|| format!("More: {prefix}"), |(_, h)| (*h).to_string())
}

/// The summary as JSON (`--json`): every entry's tables and checks, and the count of checks
/// that reproduce the documents.
fn summary_json(sections: &[Section]) -> serde_json::Value {
    let entries: Vec<serde_json::Value> = sections
        .iter()
        .map(|sec| {
            serde_json::json!({
                "id": sec.id,
                "title": sec.title,
                "source": sec.source,
                "tables": sec.tables.iter().map(|(caption, header, rows)| {
                    serde_json::json!({"caption": caption, "header": header, "rows": rows})
                }).collect::<Vec<_>>(),
                "checks": sec.checks.iter().map(|c| serde_json::json!({
                    "what": c.what, "ours": c.ours, "expected": c.expected, "ok": c.ok,
                })).collect::<Vec<_>>(),
            })
        })
        .collect();
    let checks = sections.iter().flat_map(|s| &s.checks);
    serde_json::json!({
        "entries": entries,
        "checks": checks.clone().count(),
        "reproduced": checks.filter(|c| c.ok).count(),
    })
}

/// The printed summary: every entry's tables and checks.
fn summary(sections: &[Section], cx: &Context) -> String {
    let mut s = String::from("lekalo demo: the documents' constructions on built-in data\n");
    let (mut n, mut ok) = (0, 0);
    for sec in sections {
        let _ = writeln!(s, "\n{} — {} [{}]", sec.source, sec.title, sec.id);
        if cx.is_verbose() {
            let _ = writeln!(s, "  {}", sec.caption);
        }
        for (caption, header, rows) in &sec.tables {
            let _ = writeln!(s, "  {caption}");
            let widths: Vec<usize> = (0..header.len())
                .map(|k| {
                    rows.iter()
                        .map(|r| r[k].chars().count())
                        .chain([header[k].chars().count()])
                        .max()
                        .unwrap_or(0)
                })
                .collect();
            let line = |cells: &[String]| {
                let c: Vec<String> = cells
                    .iter()
                    .zip(&widths)
                    .map(|(c, w)| format!("{c:>w$}"))
                    .collect();
                format!("    {}\n", c.join("  "))
            };
            s.push_str(&line(header));
            for r in rows {
                s.push_str(&line(r));
            }
        }
        for c in &sec.checks {
            n += 1;
            ok += usize::from(c.ok);
            let _ = writeln!(
                s,
                "  [{}] {:<44} {}   (document: {})",
                if c.ok { "ok" } else { "FAIL" },
                c.what,
                c.ours,
                c.expected
            );
        }
    }
    let _ = writeln!(s, "\n{ok} of {n} checks reproduce the documents.");
    s
}

/// The HTML gallery: thumbnails grouped by document, then one section per entry with its
/// figures, captions, tables and checks.
fn gallery(sections: &[Section], theory: Option<&str>) -> String {
    let mut h = String::from(
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>lekalo gallery</title>\n<style>body{font-family:sans-serif;max-width:1000px;margin:2em auto;padding:0 1em;color:#222}figure{margin:1.5em 0}figure img{max-width:100%;height:auto}figcaption{color:#444;font-size:92%;max-width:760px}figcaption .meta{display:block;margin-top:.3em;color:#666}table{border-collapse:collapse;margin:.5em 0}td,th{border:1px solid #ccc;padding:2px 8px;text-align:right;font-family:monospace}.ok{color:#080}.fail{color:#c00;font-weight:bold}.thumbs{display:flex;flex-wrap:wrap;gap:12px}.thumbs a{width:230px;text-decoration:none;color:#333;font-size:85%}.thumbs img{width:230px;height:auto;border:1px solid #ddd;display:block}code{background:#f4f4f4;padding:0 3px}</style></head><body>\n<h1>lekalo gallery</h1>\n<p>The constructions of the source documents, built by the library on built-in data, with the documents' numbers checked. Every figure is here as SVG and as PNG. Regenerate with <code>lekalo demo -o DIR</code>.</p>\n",
    );
    // thumbnails, grouped by document
    let mut groups: Vec<(String, Vec<&Section>)> = Vec::new();
    for s in sections {
        let g = group_of(s.id);
        match groups.iter_mut().find(|(name, _)| *name == g) {
            Some((_, list)) => list.push(s),
            None => groups.push((g, vec![s])),
        }
    }
    groups.sort_by(|a, b| {
        let rank = |g: &str| {
            DOCUMENTS
                .iter()
                .position(|(_, h)| *h == g)
                .unwrap_or(usize::MAX)
        };
        rank(&a.0).cmp(&rank(&b.0))
    });
    for (name, list) in &groups {
        let _ = writeln!(h, "<h2>{}</h2><div class=\"thumbs\">", escape(name));
        for s in list {
            for (k, (fig, _)) in s.figures.iter().enumerate() {
                let _ = writeln!(
                    h,
                    "<a href=\"#{id}-{n}\"><img src=\"{id}-{n}.png\" alt=\"{t}\" loading=\"lazy\">{t}</a>",
                    id = s.id,
                    n = k + 1,
                    t = escape(&fig.title)
                );
            }
        }
        h.push_str("</div>\n");
    }
    for s in sections {
        let _ = writeln!(
            h,
            "<section id=\"{}\"><h2>{}</h2><p><em>{}</em></p><p>{}</p>",
            s.id,
            escape(s.title),
            escape(s.source),
            escape(&s.caption)
        );
        for (k, (fig, caption)) in s.figures.iter().enumerate() {
            let name = format!("{}-{}", s.id, k + 1);
            let text = full_caption(fig, caption);
            let link = caption.theory.as_deref().map_or_else(String::new, |t| {
                let shown = format!("docs/theory/{t}");
                match theory {
                    Some(base) => format!(
                        "Theory: <a href=\"{}\">{}</a>. ",
                        escape(&format!("{base}{t}")),
                        escape(&shown)
                    ),
                    None => format!("Theory: <code>{}</code>. ", escape(&shown)),
                }
            });
            let _ = writeln!(
                h,
                "<figure id=\"{name}\"><img src=\"{name}.svg\" alt=\"{alt}\"><figcaption>Figure {n}. {text}<span class=\"meta\">{link}Redraw: <code>{cmd}</code>. Download: <a href=\"{name}.svg\">SVG</a>, <a href=\"{name}.png\">PNG</a>.</span></figcaption></figure>",
                alt = escape(&fig.title),
                n = k + 1,
                text = escape(&text),
                cmd = escape(&command_of(s.id, caption)),
            );
        }
        for (caption, header, rows) in &s.tables {
            let _ = write!(h, "<table><caption>{}</caption><tr>", escape(caption));
            for c in header {
                let _ = write!(h, "<th>{}</th>", escape(c));
            }
            h.push_str("</tr>");
            for r in rows {
                h.push_str("<tr>");
                for c in r {
                    let _ = write!(h, "<td>{}</td>", escape(c));
                }
                h.push_str("</tr>");
            }
            h.push_str("</table>\n");
        }
        if !s.checks.is_empty() {
            h.push_str("<table><caption>Key numbers</caption><tr><th>quantity</th><th>lekalo</th><th>document</th><th></th></tr>");
            for c in &s.checks {
                let _ = write!(
                    h,
                    "<tr><td style=\"text-align:left\">{}</td><td>{}</td><td>{}</td><td class=\"{}\">{}</td></tr>",
                    escape(&c.what),
                    escape(&c.ours),
                    escape(&c.expected),
                    if c.ok { "ok" } else { "fail" },
                    if c.ok { "✓" } else { "✗" }
                );
            }
            h.push_str("</table>\n");
        }
        h.push_str("</section>\n");
    }
    h.push_str("</body></html>\n");
    h
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn redrawing_one_entry_keeps_the_others() {
        let page = |sections: &str| format!("<html><body>\n<h1>g</h1>\n{sections}</body></html>\n");
        let old = page("<section id=\"a\">A1</section>\n<section id=\"b\">B1</section>\n<section id=\"c\">C1</section>\n");
        let fresh = page("<section id=\"b\">B2</section>\n");
        assert_eq!(
            replace_section(&old, &fresh, "b").unwrap(),
            page("<section id=\"a\">A1</section>\n<section id=\"b\">B2</section>\n<section id=\"c\">C1</section>\n")
        );
        // an entry the old gallery lacks goes at the end
        let fresh_d = page("<section id=\"d\">D</section>\n");
        assert!(replace_section(&old, &fresh_d, "d").unwrap().ends_with(
            "<section id=\"c\">C1</section>\n<section id=\"d\">D</section>\n</body></html>\n"
        ));
        // not a gallery: the fresh page is written as it is
        assert_eq!(replace_section("notes", &fresh, "b"), None);
    }

    #[test]
    fn every_entry_reproduces_its_document() {
        let mut all = 0;
        for entry in registry::ENTRIES {
            let mut s = Section {
                id: entry.id,
                title: entry.title,
                source: entry.source,
                caption: String::new(),
                figures: Vec::new(),
                tables: Vec::new(),
                checks: Vec::new(),
            };
            (entry.build)(&mut s).unwrap();
            assert!(
                !s.caption.is_empty() && !s.figures.is_empty(),
                "{}",
                entry.id
            );
            for c in &s.checks {
                assert!(
                    c.ok,
                    "{}: {} = {} (document {})",
                    entry.id, c.what, c.ours, c.expected
                );
            }
            all += s.checks.len();
        }
        assert!(all >= 15, "only {all} checks");
        assert_eq!(trim(0.125), "0.125");
        assert_eq!(trim(-0.0000001), "0");
    }
}
