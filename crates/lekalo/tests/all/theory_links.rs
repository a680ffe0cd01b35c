//! Every citation of the theory reference points at a section that exists.
//!
//! Code and documents cite the mathematics as `docs/theory/<page>.md#<anchor>`; the theory pages
//! link to each other with relative Markdown links (`[x](curves.md#knot-insertion)`,
//! `[x](#averaged-knots)`, `[x](../theory.md#notation)`). This test scans the repository's text
//! files for the first form and the Markdown files under `docs/` for the second, computes the
//! anchors of each cited page from its headings as GitHub does, and fails with the list of
//! citations whose page or anchor is missing.

use std::collections::BTreeSet;
use std::fs;
use std::path::{Component, Path, PathBuf};

/// The repository root (this crate is `crates/lekalo`).
fn repo_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../..")
        .canonicalize()
        .expect("the repository root exists")
}

/// GitHub's heading anchor: lower case, every character that is not a letter, a digit, a space,
/// `-` or `_` dropped, spaces turned into `-` (github-slugger). Inline code and emphasis markers
/// are punctuation and drop out with the rest.
fn slug(heading: &str) -> String {
    heading
        .trim()
        .to_lowercase()
        .chars()
        .filter(|c| c.is_alphanumeric() || matches!(c, ' ' | '-' | '_'))
        .map(|c| if c == ' ' { '-' } else { c })
        .collect()
}

/// The anchors of a Markdown text: ATX headings (`#` to `######`) outside fenced code blocks,
/// with `-1`, `-2`, … appended to repeated ones as GitHub does.
fn anchors(markdown: &str) -> BTreeSet<String> {
    let mut seen = BTreeSet::new();
    let mut in_fence = false;
    for line in markdown.lines() {
        let trimmed = line.trim_start();
        if trimmed.starts_with("```") || trimmed.starts_with("~~~") {
            in_fence = !in_fence;
            continue;
        }
        if in_fence {
            continue;
        }
        let hashes = trimmed.bytes().take_while(|&b| b == b'#').count();
        if !(1..=6).contains(&hashes) || !trimmed[hashes..].starts_with(' ') {
            continue;
        }
        let text = trimmed[hashes..].trim().trim_end_matches('#').trim();
        let base = slug(text);
        let mut anchor = base.clone();
        let mut k = 0;
        while seen.contains(&anchor) {
            k += 1;
            anchor = format!("{base}-{k}");
        }
        seen.insert(anchor);
    }
    seen
}

/// A citation found in a file: the cited page (a path from the repository root), the anchor, and
/// where the citation is (for the failure message).
#[derive(Debug, Clone, PartialEq, Eq, PartialOrd, Ord)]
struct Citation {
    page: PathBuf,
    anchor: String,
    at: String,
}

fn is_anchor_char(c: char) -> bool {
    c.is_alphanumeric() || c == '-' || c == '_'
}

/// Citations of the form `docs/theory/<page>.md#<anchor>` anywhere in `text`.
fn repository_citations(text: &str, at: &str) -> Vec<Citation> {
    const PREFIX: &str = "docs/theory/";
    let mut out = Vec::new();
    for (start, _) in text.match_indices(PREFIX) {
        let rest = &text[start + PREFIX.len()..];
        let name_len = rest
            .find(|c: char| !(c.is_ascii_alphanumeric() || c == '_' || c == '-'))
            .unwrap_or(rest.len());
        let after = &rest[name_len..];
        let Some(tail) = after.strip_prefix(".md#") else {
            continue;
        };
        let anchor: String = tail.chars().take_while(|&c| is_anchor_char(c)).collect();
        // a trailing `-` or `_` is sentence punctuation, not part of an anchor
        let anchor = anchor.trim_end_matches(['-', '_']).to_string();
        out.push(Citation {
            page: PathBuf::from(format!("{PREFIX}{}.md", &rest[..name_len])),
            anchor,
            at: at.to_string(),
        });
    }
    out
}

/// Gallery captions cite a section with `Caption::theory`, given `<page>.md#<anchor>` of a page under
/// `docs/theory/`.
fn caption_citations(text: &str, at: &str) -> Vec<Citation> {
    const PREFIX: &str = ".theory(\"";
    let mut out = Vec::new();
    for (start, _) in text.match_indices(PREFIX) {
        let rest = &text[start + PREFIX.len()..];
        let Some(end) = rest.find('"') else { continue };
        let Some((page, anchor)) = rest[..end].split_once('#') else {
            continue;
        };
        out.push(Citation {
            page: PathBuf::from(format!("docs/theory/{page}")),
            anchor: anchor.to_string(),
            at: at.to_string(),
        });
    }
    out
}

/// Relative Markdown links with an anchor, `](target#anchor)` or `](#anchor)`, in a Markdown file
/// at `file` (a path from the repository root), resolved to pages from the root.
fn markdown_link_citations(text: &str, file: &Path, at: &str) -> Vec<Citation> {
    let mut out = Vec::new();
    for (start, _) in text.match_indices("](") {
        let rest = &text[start + 2..];
        let Some(end) = rest.find(')') else { continue };
        let target = &rest[..end];
        let Some((path, anchor)) = target.split_once('#') else {
            continue;
        };
        if path.contains("://") || !(path.is_empty() || path.ends_with(".md")) {
            continue;
        }
        let page = if path.is_empty() {
            file.to_path_buf()
        } else {
            normalise(&file.parent().unwrap_or(Path::new("")).join(path))
        };
        out.push(Citation {
            page,
            anchor: anchor.to_string(),
            at: at.to_string(),
        });
    }
    out
}

/// `a/b/../c` → `a/c`, without touching the file system.
fn normalise(path: &Path) -> PathBuf {
    let mut out = PathBuf::new();
    for part in path.components() {
        match part {
            Component::ParentDir => {
                out.pop();
            }
            Component::CurDir => {}
            other => out.push(other),
        }
    }
    out
}

/// Text files of the repository, as paths from the root: sources, documents, scripts. Skips
/// build output, version control, virtual environments and hidden directories.
fn text_files(root: &Path) -> Vec<PathBuf> {
    const EXTENSIONS: &[&str] = &[
        "rs", "md", "toml", "py", "sh", "cpp", "hpp", "h", "txt", "yml", "yaml",
    ];
    let mut out = Vec::new();
    let mut stack = vec![PathBuf::new()];
    while let Some(dir) = stack.pop() {
        let Ok(entries) = fs::read_dir(root.join(&dir)) else {
            continue;
        };
        for entry in entries.flatten() {
            let name = entry.file_name().to_string_lossy().into_owned();
            let rel = dir.join(&name);
            let Ok(kind) = entry.file_type() else {
                continue;
            };
            if kind.is_dir() {
                let skip = name.starts_with('.')
                    || matches!(
                        name.as_str(),
                        "target" | "node_modules" | "venv" | "__pycache__"
                    );
                if !skip {
                    stack.push(rel);
                }
            } else if kind.is_file()
                && Path::new(&name)
                    .extension()
                    .is_some_and(|e| EXTENSIONS.contains(&e.to_string_lossy().as_ref()))
            {
                out.push(rel);
            }
        }
    }
    out.sort();
    out
}

/// Every citation in the repository, with line numbers.
fn all_citations(root: &Path) -> Vec<Citation> {
    let mut out = Vec::new();
    for file in text_files(root) {
        let Ok(text) = fs::read_to_string(root.join(&file)) else {
            continue;
        };
        let is_doc = file.starts_with("docs") && file.extension().is_some_and(|e| e == "md");
        for (k, line) in text.lines().enumerate() {
            let at = format!("{}:{}", file.display(), k + 1);
            out.extend(repository_citations(line, &at));
            out.extend(caption_citations(line, &at));
            if is_doc {
                out.extend(markdown_link_citations(line, &file, &at));
            }
        }
    }
    out
}

/// The citations whose page does not exist or has no such anchor.
fn broken(root: &Path, citations: &[Citation]) -> Vec<String> {
    let mut problems = Vec::new();
    for c in citations {
        match fs::read_to_string(root.join(&c.page)) {
            Err(_) => problems.push(format!("{}: no page {}", c.at, c.page.display())),
            Ok(text) => {
                if !anchors(&text).contains(&c.anchor) {
                    problems.push(format!(
                        "{}: {} has no section #{}",
                        c.at,
                        c.page.display(),
                        c.anchor
                    ));
                }
            }
        }
    }
    problems
}

#[test]
fn every_cited_theory_section_exists() {
    let root = repo_root();
    let citations = all_citations(&root);
    let cited_from_code = citations.iter().filter(|c| c.at.contains(".rs:")).count();
    assert!(
        cited_from_code > 0,
        "no `docs/theory/<page>.md#<anchor>` citation found in the Rust sources: the scan is broken"
    );
    let problems = broken(&root, &citations);
    assert!(
        problems.is_empty(),
        "{} broken theory citation(s):\n{}",
        problems.len(),
        problems.join("\n")
    );
}

#[test]
fn every_theory_page_is_listed_in_the_index() {
    let root = repo_root();
    let index = fs::read_to_string(root.join("docs/theory.md")).expect("docs/theory.md exists");
    let pages = fs::read_dir(root.join("docs/theory")).expect("docs/theory/ exists");
    for page in pages.flatten() {
        let name = page.file_name().to_string_lossy().into_owned();
        if name.ends_with(".md") {
            assert!(
                index.contains(&format!("(theory/{name})")),
                "docs/theory/{name} is not linked from the table of contents of docs/theory.md"
            );
        }
    }
}

#[test]
fn anchors_are_computed_as_github_does() {
    assert_eq!(slug("Averaged knots"), "averaged-knots");
    assert_eq!(slug("Cox-de Boor recursion"), "cox-de-boor-recursion");
    assert_eq!(
        slug("The lecture's worked example"),
        "the-lectures-worked-example"
    );
    assert_eq!(slug("Why the index is k-1"), "why-the-index-is-k-1");
    assert_eq!(
        slug("`KnotVector` and C² (tested)"),
        "knotvector-and-c²-tested"
    );
    assert_eq!(slug("Points, knots & bases"), "points-knots--bases");
    let md = "# Title\n## Same\n```\n## Not a heading\n```\n## Same\n#NoSpace\n";
    let got: Vec<String> = anchors(md).into_iter().collect();
    assert_eq!(got, ["same", "same-1", "title"]);
}

#[test]
fn broken_citations_are_reported() {
    // built at run time, so that the scan of this file does not find them
    let dir = ["docs", "theory"].join("/");
    let text = format!("see {dir}/curves.md#no-such-section and {dir}/nowhere.md#x.");
    let cites = repository_citations(&text, "probe.rs:1");
    assert_eq!(cites.len(), 2, "both citations are found: {cites:?}");
    assert_eq!(
        cites[1].anchor, "x",
        "sentence punctuation is not part of the anchor"
    );
    let problems = broken(&repo_root(), &cites);
    assert_eq!(problems.len(), 2, "both are broken: {problems:?}");

    let links = markdown_link_citations(
        "[a](curves.md#knot-insertion), [b](#nope), [c](../theory.md#notation), [d](x.png#y)",
        Path::new("docs/theory/surfaces.md"),
        "probe.md:1",
    );
    let pages: Vec<_> = links.iter().map(|c| c.page.display().to_string()).collect();
    assert_eq!(
        pages,
        [
            "docs/theory/curves.md",
            "docs/theory/surfaces.md",
            "docs/theory.md"
        ],
        "relative links resolve from the citing file"
    );
    let problems = broken(&repo_root(), &links);
    assert_eq!(problems.len(), 1, "only #nope is missing: {problems:?}");
}
