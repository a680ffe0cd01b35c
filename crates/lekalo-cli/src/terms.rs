//! The library's error messages in the command line's words.
//!
//! The library (`lekalo`) writes its errors for Rust callers, so a few of them name Rust items:
//! `KnotPlacement::Auto`, `quasi_interpolate`, `net_size.0`. Printed by the CLI, those names mean
//! nothing to the user; [`cli_terms`] replaces each by the command or option that does the same.

/// `(library wording, CLI wording)`, longest first where one contains another.
const TERMS: [(&str, &str); 10] = [
    ("invalid knots: ", "--knots: "),
    ("use the placement auto", "use --knots auto"),
    (
        "approximate it by quasi-interpolation instead",
        "give a lower --continuity, or leave --continuity out to infer it from the pp-form; \
         `lekalo pp quasi` approximates a function instead",
    ),
    (
        "knots_u (net_size.0 + degree_u + 1)",
        "--knots-u (net rows + u degree + 1)",
    ),
    (
        "knots_v (net_size.1 + degree_v + 1)",
        "--knots-v (net columns + v degree + 1)",
    ),
    ("net_size.0 × net_size.1", "rows × columns of --net"),
    ("net_size.0", "rows of --net"),
    ("net_size.1", "columns of --net"),
    ("(degree_u)", "(--degree)"),
    ("(degree_v)", "(--degree-v)"),
];

/// `message` with every library item of [`TERMS`] replaced by its command-line counterpart.
pub(crate) fn cli_terms(message: &str) -> String {
    let mut out = message.to_string();
    for (library, cli) in TERMS {
        if out.contains(library) {
            out = out.replace(library, cli);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn no_library_item_survives() {
        let messages = [
            "invalid knots: 5 knots do not go with natural end conditions; use the placement auto",
            "invalid piecewise polynomial: not in the space; approximate it by quasi-interpolation instead",
            "control net (net_size.0 × net_size.1) has 6 points",
            "knots_u (net_size.0 + degree_u + 1): expected 7, got 6",
            "control net rows (net_size.0) and columns (net_size.1)",
            "u direction (degree_u) and v direction (degree_v)",
        ];
        for m in messages {
            let t = cli_terms(m);
            for item in [
                "placement auto",
                "quasi-interpolation instead",
                "net_size",
                "degree_u",
                "degree_v",
                "knots_u ",
            ] {
                assert!(!t.contains(item), "{item} left in: {t}");
            }
        }
        assert_eq!(
            cli_terms("plain message"),
            "plain message",
            "others unchanged"
        );
    }
}
