//! `lekalo demo`: the documents' constructions on built-in data. Every gallery entry builds its
//! objects with the library, draws figures and checks its key numbers against the documents
//! (docs/theory/foundations.md#the-lectures-worked-example,
//! docs/theory/interpolation.md#test-vectors, docs/theory/pp.md#the-practical-task); the summary
//! table lists every check, the HTML gallery shows the figures with captions and the same numbers.
//!
//! To add a construction, write a `fn(&mut Section) -> Result<()>` and list it in
//! [`registry::ENTRIES`].

use std::fmt::Write as _;
use std::path::Path;

use anyhow::{Context, Result};
use lekalo_io::{escape, Figure};

use crate::io::Internal;
use crate::Verbosity;

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
    pub(crate) figures: Vec<(Figure, String)>,
    /// Tables: (caption, header, rows).
    pub(crate) tables: Vec<(String, Vec<String>, Vec<Vec<String>>)>,
    /// Checked numbers.
    pub(crate) checks: Vec<Check>,
}

/// A number compared with the document's value.
pub(crate) struct Check {
    pub(crate) what: String,
    pub(crate) ours: String,
    pub(crate) expected: String,
    pub(crate) ok: bool,
}

impl Section {
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

/// Runs every entry, prints the summary table, writes the gallery if `out` is given.
pub(crate) fn run(out: Option<&Path>, v: Verbosity) -> Result<()> {
    let mut sections = Vec::new();
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
        (entry.build)(&mut s).with_context(|| format!("demo entry {}", entry.id))?;
        sections.push(s);
    }
    let mut stdout = std::io::stdout().lock();
    std::io::Write::write_all(&mut stdout, summary(&sections, v).as_bytes())?;
    if let Some(dir) = out {
        std::fs::create_dir_all(dir).map_err(|error| lekalo_io::IoError::Write {
            path: dir.to_path_buf(),
            error,
        })?;
        let mut n_files = 0;
        for s in &sections {
            for (k, (fig, _)) in s.figures.iter().enumerate() {
                let path = dir.join(format!("{}-{}.svg", s.id, k + 1));
                lekalo_io::write_atomic(&path, fig.to_svg().as_bytes(), &[])?;
                n_files += 1;
            }
        }
        let index = dir.join("index.html");
        lekalo_io::write_atomic(&index, gallery(&sections).as_bytes(), &[])?;
        if v != Verbosity::Quiet {
            eprintln!(
                "gallery: {} ({} figures); open it in a browser",
                index.display(),
                n_files
            );
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

/// The printed summary: every entry's tables and checks.
fn summary(sections: &[Section], v: Verbosity) -> String {
    let mut s = String::from("lekalo demo: the documents' constructions on built-in data\n");
    let (mut n, mut ok) = (0, 0);
    for sec in sections {
        let _ = writeln!(s, "\n{} — {} [{}]", sec.source, sec.title, sec.id);
        if v == Verbosity::Verbose {
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

/// The HTML gallery: one section per entry with figures, captions, tables and checks.
fn gallery(sections: &[Section]) -> String {
    let mut h = String::from(
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>lekalo gallery</title>\n<style>body{font-family:sans-serif;max-width:1000px;margin:2em auto;padding:0 1em;color:#222}figure{margin:1em 0}figcaption{color:#555;font-size:90%}table{border-collapse:collapse;margin:.5em 0}td,th{border:1px solid #ccc;padding:2px 8px;text-align:right;font-family:monospace}.ok{color:#080}.fail{color:#c00;font-weight:bold}nav a{margin-right:1em}</style></head><body>\n<h1>lekalo gallery</h1>\n<p>The constructions of the source documents, built by the library on built-in data, with the documents' numbers checked. Regenerate with <code>lekalo demo --out DIR</code>.</p>\n<nav>",
    );
    for s in sections {
        let _ = write!(h, "<a href=\"#{}\">{}</a>", s.id, escape(s.title));
    }
    h.push_str("</nav>\n");
    for s in sections {
        let _ = writeln!(
            h,
            "<section id=\"{}\"><h2>{}</h2><p><em>{}</em></p><p>{}</p>",
            s.id,
            escape(s.title),
            escape(s.source),
            escape(&s.caption)
        );
        for (k, (_, caption)) in s.figures.iter().enumerate() {
            let _ = writeln!(
                h,
                "<figure><img src=\"{}-{}.svg\" alt=\"{}\"><figcaption>Figure {}. {}</figcaption></figure>",
                s.id,
                k + 1,
                escape(caption),
                k + 1,
                escape(caption)
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
