//! Colours and line looks of the plots.
//!
//! Series are told apart first by colour, from the Okabe–Ito palette (Okabe & Ito, *Color
//! Universal Design*, 2008: distinguishable under the common colour-vision deficiencies), then,
//! beyond its size, by dash pattern and marker shape: [`look`] gives series `i` a combination
//! no earlier series has. Surfaces are coloured by height with a sequential map (viridis,
//! perceptually uniform and colour-blind safe) and shaded by a fixed light.

/// The palette of the plots (colour-blind safe, Okabe–Ito): blue, vermillion, bluish green,
/// reddish purple, orange, sky blue, yellow, black.
pub const PALETTE: [&str; 8] = [
    "#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#56B4E9", "#F0E442", "#000000",
];

/// The palette's colours that read as lines on white (its yellow is too light for a 2-pixel
/// line), in the order [`look`] uses them.
pub const LINE_COLORS: [&str; 7] = [
    PALETTE[0], PALETTE[1], PALETTE[2], PALETTE[3], PALETTE[4], PALETTE[5], PALETTE[7],
];

/// Dash patterns (SVG `stroke-dasharray`, pixels), in the order [`look`] uses them once the
/// colours are used up; the first is a solid line.
pub const DASHES: [&str; 4] = ["", "9 4", "2 3", "9 3 2 3"];

/// Marker shapes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Marker {
    /// Open circle (data and control points).
    Circle,
    /// Open square.
    Square,
    /// Open triangle, point up.
    Triangle,
    /// Open diamond.
    Diamond,
}

/// How series `i` of a figure is drawn: `(colour, dash pattern, marker)`. The first seven get
/// the seven line colours, solid; the next seven the same colours dashed with square markers;
/// then dotted with triangles, dash-dotted with diamonds, and round again. Any two of the first
/// 28 series differ in colour or in dash and marker.
#[must_use]
pub fn look(i: usize) -> (&'static str, &'static str, Option<Marker>) {
    let round = i / LINE_COLORS.len();
    let marker = match round % DASHES.len() {
        0 => None,
        1 => Some(Marker::Square),
        2 => Some(Marker::Triangle),
        _ => Some(Marker::Diamond),
    };
    (
        LINE_COLORS[i % LINE_COLORS.len()],
        DASHES[round % DASHES.len()],
        marker,
    )
}

/// The names a reader gives each colour of [`PALETTE`] (first the one captions should use):
/// Okabe and Ito's own names, and the everyday word for how the colour looks on a screen
/// (their "reddish purple" reads as pink, their "vermillion" as orange-red).
pub const COLOR_NAMES: [(&str, &[&str]); 8] = [
    ("#0072B2", &["blue"]),
    (
        "#D55E00",
        &[
            "vermillion",
            "vermilion",
            "orange-red",
            "red-orange",
            "red",
            "orange",
        ],
    ),
    ("#009E73", &["green", "bluish green"]),
    ("#CC79A7", &["pink", "reddish purple"]),
    ("#E69F00", &["orange"]),
    ("#56B4E9", &["sky blue", "light blue"]),
    ("#F0E442", &["yellow"]),
    ("#000000", &["black"]),
];

/// Every colour word the figure check looks for in captions, longer names first so that "sky
/// blue" is read before "blue".
pub const COLOR_WORDS: [&str; 21] = [
    "reddish purple",
    "bluish green",
    "orange-red",
    "red-orange",
    "sky blue",
    "light blue",
    "vermillion",
    "vermilion",
    "magenta",
    "purple",
    "violet",
    "yellow",
    "orange",
    "black",
    "green",
    "brown",
    "grey",
    "gray",
    "pink",
    "blue",
    "red",
];

/// The names a reader may give a drawn CSS colour (`#rrggbb` or `#rgb`): the palette's names
/// for its colours, "black" for black, "grey"/"gray" for any other neutral colour; none for a
/// colour that is neither.
#[must_use]
pub fn color_names(css: &str) -> &'static [&'static str] {
    let hex = css.trim().trim_start_matches('#');
    let full: String = if hex.len() == 3 {
        hex.chars().flat_map(|c| [c, c]).collect()
    } else {
        hex.to_string()
    };
    if let Some((_, names)) = COLOR_NAMES
        .iter()
        .find(|(c, _)| c[1..].eq_ignore_ascii_case(&full))
    {
        return names;
    }
    let channel = |k: usize| {
        full.get(2 * k..2 * k + 2)
            .and_then(|s| u8::from_str_radix(s, 16).ok())
    };
    match (channel(0), channel(1), channel(2)) {
        (Some(r), Some(g), Some(b)) if r.abs_diff(g) < 16 && g.abs_diff(b) < 16 => {
            if r < 40 {
                &["black"]
            } else {
                &["grey", "gray"]
            }
        }
        _ => &[],
    }
}

/// Viridis at 0, 1/4, 1/2, 3/4 and 1 (sRGB); [`height_color`] interpolates linearly.
const VIRIDIS: [[f64; 3]; 5] = [
    [68.0, 1.0, 84.0],
    [59.0, 82.0, 139.0],
    [33.0, 145.0, 140.0],
    [94.0, 201.0, 98.0],
    [253.0, 231.0, 37.0],
];

/// Colour of the sequential height map at `s` in `[0, 1]` (clamped; NaN as 0), as RGB in
/// `[0, 255]`. The darkest fifth of viridis is left out so that shading stays visible.
#[must_use]
pub(crate) fn height_rgb(s: f64) -> [f64; 3] {
    let s = if s.is_nan() { 0.0 } else { s.clamp(0.0, 1.0) };
    let x = (0.2 + 0.8 * s) * 4.0;
    // x is in [0.8, 4]: the stop below it, at most the last but one
    let k = [1.0, 2.0, 3.0].iter().filter(|b| x >= **b).count();
    let f = x - k as f64;
    let (a, b) = (VIRIDIS[k], VIRIDIS[k + 1]);
    [
        a[0] + f * (b[0] - a[0]),
        a[1] + f * (b[1] - a[1]),
        a[2] + f * (b[2] - a[2]),
    ]
}

/// `#rrggbb` of an RGB triple in `[0, 255]` scaled by `shade` (clamped to the range).
#[must_use]
pub(crate) fn hex(rgb: [f64; 3], shade: f64) -> String {
    let c = |v: f64| {
        let x = (v * shade).round().clamp(0.0, 255.0);
        // in [0, 255] after the clamp
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let b = x as u8;
        b
    };
    format!("#{:02x}{:02x}{:02x}", c(rgb[0]), c(rgb[1]), c(rgb[2]))
}

/// The height map's colour at `s` in `[0, 1]`, unshaded.
#[must_use]
pub fn height_color(s: f64) -> String {
    hex(height_rgb(s), 1.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn looks_are_distinct() {
        let looks: Vec<_> = (0..28).map(look).collect();
        for (i, a) in looks.iter().enumerate() {
            for b in &looks[..i] {
                assert_ne!(a, b, "series {i} looks like an earlier one");
            }
        }
        assert_eq!(look(0), ("#0072B2", "", None));
        assert_eq!(look(7), ("#0072B2", "9 4", Some(Marker::Square)));
    }

    #[test]
    fn colours_have_names() {
        assert_eq!(color_names("#CC79A7")[0], "pink");
        assert!(!color_names("#cc79a7").contains(&"purple"), "it looks pink");
        assert_eq!(color_names("#777777"), ["grey", "gray"]);
        assert_eq!(color_names("#000"), ["black"]);
        assert!(color_names("#123456").is_empty());
        for (c, names) in COLOR_NAMES {
            assert_eq!(color_names(c), names);
            for n in names {
                assert!(COLOR_WORDS.contains(n), "{n} is looked for");
            }
        }
    }

    #[test]
    fn height_map() {
        assert_eq!(height_color(1.0), "#fde725");
        assert_eq!(height_color(f64::NAN), height_color(0.0));
        assert_eq!(hex([255.0, 0.0, 128.0], 0.5), "#800040");
        assert_eq!(hex([255.0, 0.0, 128.0], 9.0), "#ff00ff");
    }
}
