//! Old option spellings that keep working, with a warning naming the new one (docs/cli.md, "One
//! vocabulary"). clap accepts them as aliases; this table only finds and reports them.

/// `(command path, old spelling, new spelling)`.
const DEPRECATED: &[(&[&str], &str, &str)] = &[
    (&["interpolate"], "--d0", "--start-derivative"),
    (&["interpolate"], "--dn", "--end-derivative"),
    (&["fit"], "--d0", "--start-derivative"),
    (&["fit"], "--dn", "--end-derivative"),
    (&["fit"], "--tol", "--tolerance"),
    (&["measure"], "--tolerance", "--rtol"),
    (&["blend", "spline"], "--params", "--param"),
    (&["blend", "deform"], "-k", "--continuity"),
    (&["blend", "spline"], "-k", "--continuity"),
    (&["blend", "corner"], "-k", "--continuity"),
    (&["knots", "curry-schoenberg"], "-k", "--order"),
];

fn uses(arg: &str, old: &str) -> bool {
    if arg == old || arg.starts_with(&format!("{old}=")) {
        return true;
    }
    // a short option with its value attached: -k2
    old.len() == 2 && arg.len() > 2 && arg.starts_with(old) && !old.starts_with("--")
}

/// Warnings for the deprecated spellings in `args` (the program name first).
pub(crate) fn warnings(args: &[String]) -> Vec<String> {
    let words: Vec<&str> = args
        .iter()
        .skip(1)
        .map(String::as_str)
        .filter(|a| !a.starts_with('-'))
        .collect();
    let mut out = Vec::new();
    for (path, old, new) in DEPRECATED {
        if words.len() < path.len() || words[..path.len()] != **path {
            continue;
        }
        if args.iter().skip(1).any(|a| uses(a, old)) {
            out.push(format!(
                "`{old}` of `lekalo {}` is deprecated; write `{new}` (the old spelling keeps working for now)",
                path.join(" ")
            ));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn w(line: &str) -> Vec<String> {
        warnings(&line.split(' ').map(String::from).collect::<Vec<_>>())
    }

    #[test]
    fn finds_old_spellings_only_in_their_command() {
        assert_eq!(w("lekalo interpolate pts.csv --d0 1,2 --dn 3,4").len(), 2);
        assert!(w("lekalo interpolate pts.csv --start-derivative 1,2")[..].is_empty());
        assert_eq!(w("lekalo blend spline pts.csv -k3").len(), 1);
        assert!(w("lekalo blend spline pts.csv --continuity 3").is_empty());
        assert!(w("lekalo knot insert c.json --at 0.5").is_empty());
        assert!(w("lekalo knots curry-schoenberg -k 3")[0].contains("--order"));
        assert!(w("lekalo fit pts.csv --tol 0.1")[0].contains("--tolerance"));
        assert!(w("lekalo fit pts.csv --tolerance 0.1").is_empty());
    }
}
