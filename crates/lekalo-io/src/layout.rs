//! Text metrics and legend layout of the figures.
//!
//! SVG figures are laid out before a browser sees them, so text widths are estimated from the
//! advance widths of DejaVu Sans (the figures' first font; `scripts/font_widths.py` printed the
//! table). The estimate errs wide: characters outside the table count as 0.84 em, the width of
//! DejaVu's widest common symbols, and narrower fallback fonts (Arial) only leave more room.

/// Advance widths of DejaVu Sans for the printable ASCII characters `' '..='~'`, in em.
const ASCII_WIDTHS: [f64; 95] = [
    0.318, 0.401, 0.460, 0.838, 0.636, 0.950, 0.780, 0.275, 0.390, 0.390, 0.500, 0.838, 0.318,
    0.361, 0.318, 0.337, 0.636, 0.636, 0.636, 0.636, 0.636, 0.636, 0.636, 0.636, 0.636, 0.636,
    0.337, 0.337, 0.838, 0.838, 0.838, 0.531, 1.000, 0.684, 0.686, 0.698, 0.770, 0.632, 0.575,
    0.775, 0.752, 0.295, 0.295, 0.656, 0.557, 0.863, 0.748, 0.787, 0.603, 0.787, 0.695, 0.635,
    0.611, 0.732, 0.684, 0.989, 0.685, 0.611, 0.685, 0.390, 0.337, 0.390, 0.838, 0.500, 0.500,
    0.613, 0.635, 0.550, 0.635, 0.615, 0.352, 0.635, 0.634, 0.278, 0.278, 0.579, 0.278, 0.974,
    0.634, 0.612, 0.635, 0.635, 0.411, 0.521, 0.392, 0.634, 0.592, 0.818, 0.592, 0.592, 0.525,
    0.636, 0.337, 0.636, 0.838,
];

/// Advance widths of DejaVu Sans for symbols the figures use, in em.
const OTHER_WIDTHS: [(char, f64); 26] = [
    ('ν', 0.559),
    ('Σ', 0.632),
    ('′', 0.227),
    ('″', 0.374),
    ('→', 0.838),
    ('·', 0.318),
    ('≤', 0.838),
    ('−', 0.838),
    ('²', 0.401),
    ('³', 0.401),
    ('¹', 0.401),
    ('ξ', 0.558),
    ('τ', 0.602),
    ('λ', 0.592),
    ('…', 1.000),
    ('×', 0.838),
    ('ū', 0.634),
    ('—', 1.000),
    ('–', 0.500),
    ('“', 0.518),
    ('”', 0.518),
    ('‘', 0.318),
    ('’', 0.318),
    ('°', 0.500),
    ('±', 0.838),
    ('≈', 0.838),
];

/// Width assumed for a character outside the tables, in em.
const OTHER_WIDTH: f64 = 0.84;

/// Estimated width in pixels of `text` set in DejaVu Sans at `font_size` pixels.
#[must_use]
pub fn text_width(text: &str, font_size: f64) -> f64 {
    let em: f64 = text
        .chars()
        .map(|c| {
            let code = c as u32;
            if (32..127).contains(&code) {
                ASCII_WIDTHS[(code - 32) as usize]
            } else {
                OTHER_WIDTHS
                    .iter()
                    .find(|(o, _)| *o == c)
                    .map_or(OTHER_WIDTH, |(_, w)| *w)
            }
        })
        .sum();
    em * font_size
}

/// Height of a line of text of `font_size` pixels: ascent above the baseline and descent
/// below it (DejaVu Sans: 0.93 em and 0.24 em).
#[must_use]
pub fn text_extent(font_size: f64) -> (f64, f64) {
    (0.93 * font_size, 0.24 * font_size)
}

/// Width of a legend entry's sample (line or marker) and the gap before its text, pixels.
pub(crate) const LEGEND_SAMPLE: f64 = 30.0;
/// Horizontal space between legend entries in a row, pixels.
pub(crate) const LEGEND_GAP: f64 = 18.0;
/// Height of a legend row, pixels.
pub(crate) const LEGEND_ROW: f64 = 18.0;
/// Font size of legend text, pixels.
pub(crate) const LEGEND_FONT: f64 = 12.0;

/// Where the legend goes.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum LegendPlace {
    /// No labelled series.
    None,
    /// Rows above the plot: each row's entry indices.
    Rows(Vec<Vec<usize>>),
    /// A column to the right of the plot, of the given width.
    Column(f64),
}

/// The most rows a legend takes above the plot before it moves beside it.
const MAX_ROWS: usize = 3;

/// Places legend entries of the given widths: in rows of at most `row_width` pixels above the
/// plot (at most three rows), else in a column beside it.
pub(crate) fn place_legend(widths: &[f64], row_width: f64) -> LegendPlace {
    if widths.is_empty() {
        return LegendPlace::None;
    }
    let mut rows: Vec<Vec<usize>> = vec![Vec::new()];
    let mut used = 0.0;
    for (i, w) in widths.iter().enumerate() {
        let need = if used > 0.0 { LEGEND_GAP + w } else { *w };
        let row_full = rows.last().is_some_and(|r| !r.is_empty());
        if row_full && used + need > row_width {
            rows.push(Vec::new());
            used = *w;
        } else {
            used += need;
        }
        if let Some(r) = rows.last_mut() {
            r.push(i);
        }
    }
    let widest = widths.iter().fold(0.0_f64, |m, w| m.max(*w));
    if rows.len() <= MAX_ROWS && widest <= row_width {
        LegendPlace::Rows(rows)
    } else {
        LegendPlace::Column(widest)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn widths() {
        // DejaVu Sans: "M" is 0.863 em, "i" 0.278 em
        assert!((text_width("Mi", 10.0) - 11.41).abs() < 1e-9, "width of Mi");
        assert!((text_width("ν", 12.0) - 0.559 * 12.0).abs() < 1e-9, "nu");
        assert!(
            (text_width("ж", 10.0) - 8.4).abs() < 1e-9,
            "unknown characters count wide"
        );
        assert!(text_width("", 12.0).abs() < f64::EPSILON, "empty text");
    }

    #[test]
    fn legends_wrap_then_move_aside() {
        assert_eq!(place_legend(&[], 500.0), LegendPlace::None);
        assert_eq!(
            place_legend(&[100.0, 100.0, 100.0], 500.0),
            LegendPlace::Rows(vec![vec![0, 1, 2]])
        );
        // 100 + 18 + 100 + 18 + 100 = 336 > 300: the third entry starts a second row
        assert_eq!(
            place_legend(&[100.0, 100.0, 100.0], 300.0),
            LegendPlace::Rows(vec![vec![0, 1], vec![2]])
        );
        assert_eq!(
            place_legend(&[150.0; 8], 300.0),
            LegendPlace::Column(150.0),
            "eight wide entries need four rows"
        );
        assert_eq!(place_legend(&[400.0], 300.0), LegendPlace::Column(400.0));
    }
}
