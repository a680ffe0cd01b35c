//! Text metrics and legend layout of the figures.
//!
//! SVG figures are laid out before a browser sees them, so text widths are estimated from the
//! advance widths of `DejaVu Sans` (the figures' first font; `scripts/font_widths.py` printed the
//! table). The estimate errs wide: characters outside the table count as 0.84 em, the width of
//! the font's widest common symbols, and narrower fallback fonts (Arial) only leave more room.

/// Advance widths of `DejaVu Sans` for the printable ASCII characters `' '..='~'`, in font
/// units ([`UNITS_PER_EM`] to the em).
const ASCII_WIDTHS: [u16; 95] = [
    651, 821, 942, 1716, 1303, 1946, 1597, 563, 799, 799, 1024, 1716, 651, 739, 651, 690, 1303,
    1303, 1303, 1303, 1303, 1303, 1303, 1303, 1303, 1303, 690, 690, 1716, 1716, 1716, 1087, 2048,
    1401, 1405, 1430, 1577, 1294, 1178, 1587, 1540, 604, 604, 1343, 1141, 1767, 1532, 1612, 1235,
    1612, 1423, 1300, 1251, 1499, 1401, 2025, 1403, 1251, 1403, 799, 690, 799, 1716, 1024, 1024,
    1255, 1300, 1126, 1300, 1260, 721, 1300, 1298, 569, 569, 1186, 569, 1995, 1298, 1253, 1300,
    1300, 842, 1067, 803, 1298, 1212, 1675, 1212, 1212, 1075, 1303, 690, 1303, 1716,
];

/// Advance widths of `DejaVu Sans` for symbols the figures use, in font units.
const OTHER_WIDTHS: [(char, u16); 26] = [
    ('ν', 1144),
    ('Σ', 1294),
    ('′', 465),
    ('″', 765),
    ('→', 1716),
    ('·', 651),
    ('≤', 1716),
    ('−', 1716),
    ('²', 821),
    ('³', 821),
    ('¹', 821),
    ('ξ', 1142),
    ('τ', 1233),
    ('λ', 1212),
    ('…', 2048),
    ('×', 1716),
    ('ū', 1298),
    ('—', 2048),
    ('–', 1024),
    ('“', 1061),
    ('”', 1061),
    ('‘', 651),
    ('’', 651),
    ('°', 1024),
    ('±', 1716),
    ('≈', 1716),
];

/// Font units per em of `DejaVu Sans`.
const UNITS_PER_EM: f64 = 2048.0;

/// Width assumed for a character outside the tables, in em.
const OTHER_WIDTH: f64 = 0.84;

/// Estimated width in pixels of `text` set in `DejaVu Sans` at `font_size` pixels.
#[must_use]
pub fn text_width(text: &str, font_size: f64) -> f64 {
    let em: f64 = text
        .chars()
        .map(|c| {
            let code = c as u32;
            if (32..127).contains(&code) {
                f64::from(ASCII_WIDTHS[(code - 32) as usize]) / UNITS_PER_EM
            } else {
                OTHER_WIDTHS
                    .iter()
                    .find(|(o, _)| *o == c)
                    .map_or(OTHER_WIDTH, |(_, w)| f64::from(*w) / UNITS_PER_EM)
            }
        })
        .sum();
    em * font_size
}

/// Height of a line of text of `font_size` pixels: ascent above the baseline and descent
/// below it (`DejaVu Sans`: 0.93 em and 0.24 em).
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
        // `DejaVu Sans`: "M" is 1767 units, "i" 569 (2048 to the em)
        assert!(
            (text_width("Mi", 2048.0) - 2336.0).abs() < 1e-9,
            "width of Mi"
        );
        assert!((text_width("ν", 2048.0) - 1144.0).abs() < 1e-9, "nu");
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
