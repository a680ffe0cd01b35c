//! Every option of `lekalo` is documented, and every option the documentation names is real.
//! The options are read from the argument grammar itself (`lekalo_cli::command()`, every
//! subcommand at every depth, global options included), not from a list: an option added to a
//! command must appear in `docs/cli.md` (the server's in `docs/serve.md`, the page that
//! `docs/cli.md` sends `serve` to), and an option written in `docs/cli.md` must be one of some
//! command (a hidden one too: the deprecated spellings the page lists still work).

use std::collections::BTreeSet;
use std::fs;

/// The long options (`--name`) written in `text`: `--` not preceded by a letter, digit or `-`,
/// followed by a lower-case word.
fn options_in(text: &str) -> BTreeSet<String> {
    let bytes = text.as_bytes();
    let mut out = BTreeSet::new();
    for (i, _) in text.match_indices("--") {
        if i > 0 && (bytes[i - 1].is_ascii_alphanumeric() || bytes[i - 1] == b'-') {
            continue;
        }
        let name: String = text[i + 2..]
            .chars()
            .take_while(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || *c == '-')
            .collect();
        if name.starts_with(|c: char| c.is_ascii_lowercase()) {
            out.insert(format!("--{name}"));
        }
    }
    out
}

/// Every subcommand's long options: `(command path, option, hidden)`; an old spelling kept as
/// an alias (`fit --tol`) counts as hidden.
fn grammar_options() -> Vec<(String, String, bool)> {
    fn walk(cmd: &clap::Command, path: &str, out: &mut Vec<(String, String, bool)>) {
        for arg in cmd.get_arguments() {
            if let Some(long) = arg.get_long() {
                out.push((path.to_string(), format!("--{long}"), arg.is_hide_set()));
            }
            for alias in arg.get_all_aliases().unwrap_or_default() {
                out.push((path.to_string(), format!("--{alias}"), true));
            }
        }
        for sub in cmd.get_subcommands() {
            let name = sub.get_name();
            let sub_path = if path.is_empty() {
                name.to_string()
            } else {
                format!("{path} {name}")
            };
            walk(sub, &sub_path, out);
        }
    }
    let mut out = Vec::new();
    walk(&lekalo_cli::command(), "", &mut out);
    out
}

#[test]
fn every_option_is_documented_and_every_documented_option_is_real() {
    let root = concat!(env!("CARGO_MANIFEST_DIR"), "/../..");
    let cli = fs::read_to_string(format!("{root}/docs/cli.md")).expect("docs/cli.md");
    let serve = fs::read_to_string(format!("{root}/docs/serve.md")).expect("docs/serve.md");
    let in_cli = options_in(&cli);
    let in_serve = options_in(&serve);
    let grammar = grammar_options();
    assert!(
        grammar.len() > 200,
        "only {} options found in the grammar",
        grammar.len()
    );

    let mut failures = Vec::new();
    for (path, option, hidden) in &grammar {
        if *hidden || option == "--help" || option == "--version" {
            continue;
        }
        let page = if path == "serve" { &in_serve } else { &in_cli };
        if !page.contains(option) {
            let where_ = if path == "serve" {
                "serve.md"
            } else {
                "cli.md"
            };
            failures.push(format!("`lekalo {path} {option}` is not in docs/{where_}"));
        }
    }
    // clap adds --help and --version itself
    let real: BTreeSet<&str> = grammar
        .iter()
        .map(|(_, o, _)| o.as_str())
        .chain(["--help", "--version"])
        .collect();
    for option in &in_cli {
        if !real.contains(option.as_str()) {
            failures.push(format!(
                "docs/cli.md names `{option}`, which no command has"
            ));
        }
    }
    failures.dedup();
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn options_are_read_from_text() {
    let found = options_in("`--grid 5x7`, x--y, ---z, --Upper, a -- b, (--knots-u LIST)");
    let want: BTreeSet<String> = ["--grid", "--knots-u"].map(String::from).into();
    assert_eq!(found, want);
}
