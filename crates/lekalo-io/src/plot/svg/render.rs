//! A figure on the page as SVG text: axes and nice ticks, series, legend, colour bar.
use std::fmt::Write as _;

use super::figure::{ColorBar, Figure, Series, Style};
use super::page::*;
use super::ticks::{fmt_legend, fmt_tick, nice_ticks};
use crate::layout::{
    text_extent, text_width, LegendPlace, LEGEND_FONT, LEGEND_GAP, LEGEND_ROW, LEGEND_SAMPLE,
};
use crate::palette::{height_color, Marker};

/// The attribute of tick labels, so that the figure check can tell them from other texts.
const TICK: &str = r#" class="tick""#;

/// Writes a `<text>` element with its estimated box as `data-bbox="x y w h"`.
pub(super) fn text(
    s: &mut String,
    x: f64,
    y: f64,
    anchor: &str,
    size: f64,
    body: &str,
    extra: &str,
) {
    let w = text_width(body, size);
    let (asc, desc) = text_extent(size);
    let x0 = match anchor {
        "middle" => x - 0.5 * w,
        "end" => x - w,
        _ => x,
    };
    let size_attr = if (size - FONT).abs() > f64::EPSILON {
        format!(r#" font-size="{size}""#)
    } else {
        String::new()
    };
    let _ = writeln!(
        s,
        r#"<text x="{x:.2}" y="{y:.2}" text-anchor="{anchor}"{size_attr}{extra} data-bbox="{x0:.2} {:.2} {w:.2} {:.2}">{}</text>"#,
        y - asc,
        asc + desc,
        escape(body)
    );
}

/// A marker of `shape` centred at `(x, y)`.
pub(super) fn marker(
    s: &mut String,
    shape: Marker,
    x: f64,
    y: f64,
    r: f64,
    color: &str,
    fill: &str,
) {
    let common = format!(r#"fill="{fill}" stroke="{color}" stroke-width="1.8""#);
    let _ = match shape {
        Marker::Circle => writeln!(s, r#"<circle cx="{x:.2}" cy="{y:.2}" r="{r}" {common}/>"#),
        Marker::Square => writeln!(
            s,
            r#"<rect x="{:.2}" y="{:.2}" width="{:.2}" height="{:.2}" {common}/>"#,
            x - 0.85 * r,
            y - 0.85 * r,
            1.7 * r,
            1.7 * r
        ),
        Marker::Triangle => writeln!(
            s,
            r#"<polygon points="{x:.2},{:.2} {:.2},{:.2} {:.2},{:.2}" {common}/>"#,
            y - 1.1 * r,
            x - r,
            y + 0.8 * r,
            x + r,
            y + 0.8 * r
        ),
        Marker::Diamond => writeln!(
            s,
            r#"<polygon points="{x:.2},{:.2} {:.2},{y:.2} {x:.2},{:.2} {:.2},{y:.2}" {common}/>"#,
            y - 1.2 * r,
            x + 1.2 * r,
            y + 1.2 * r,
            x - 1.2 * r
        ),
    };
}

impl Figure {
    /// The figure as a standalone SVG document. Text elements and legend entries carry their
    /// boxes as `data-bbox="x y width height"`, series groups their label, so that tests can
    /// check the layout without a font.
    #[must_use]
    pub fn to_svg(&self) -> String {
        let f = self.frame();
        let (w, h, left, top, pw, ph) = (f.w, f.h, f.left, f.top, f.pw, f.ph);
        let hidden = self.hidden_pairs(&f);
        let mut s = String::new();
        let _ = writeln!(
            s,
            r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}" font-family="DejaVu Sans, Arial, sans-serif" font-size="12">"#
        );
        let _ = writeln!(s, r#"<rect width="{w}" height="{h}" fill="white"/>"#);
        text(
            &mut s,
            w / 2.0,
            TITLE_Y,
            "middle",
            TITLE_FONT,
            &self.title,
            "",
        );
        if let Some((a, b, label)) = &self.band {
            let _ = writeln!(
                s,
                r##"<rect x="{:.2}" y="{top}" width="{:.2}" height="{ph}" fill="#fff3c4"/>"##,
                f.tx(*a),
                f.tx(*b) - f.tx(*a),
            );
            let (x, y) = self.free_spot(&f, label, (f.tx(*a), f.tx(*b)));
            text(
                &mut s,
                x,
                y,
                "middle",
                FONT,
                label,
                r##" class="note" fill="#8a6d00""##,
            );
        }
        if self.axes {
            self.axes_svg(&mut s, &f);
        }
        if !self.faces.is_empty() {
            s.push_str("<g class=\"surface\" stroke-linejoin=\"round\">\n");
            for face in &self.faces {
                if face.points.len() >= 3 {
                    let pts: Vec<String> = face
                        .points
                        .iter()
                        .map(|p| format!("{:.2},{:.2}", f.tx(p[0]), f.ty(p[1])))
                        .collect();
                    let _ = writeln!(
                        s,
                        r#"<polygon points="{}" fill="{c}" stroke="{c}" stroke-width="0.7"/>"#,
                        pts.join(" "),
                        c = face.fill
                    );
                }
                let (ec, ew) = &face.edge_style;
                for e in &face.edges {
                    let _ = writeln!(
                        s,
                        r#"<line x1="{:.2}" y1="{:.2}" x2="{:.2}" y2="{:.2}" stroke="{ec}" stroke-width="{ew}" stroke-linecap="round"/>"#,
                        f.tx(e[0][0]),
                        f.ty(e[0][1]),
                        f.tx(e[1][0]),
                        f.ty(e[1][1])
                    );
                }
            }
            s.push_str("</g>\n");
        }
        for (k, series) in self.series.iter().enumerate() {
            let over = hidden.iter().find(|(_, j)| *j == k).map(|(i, _)| *i);
            self.series_svg(&mut s, &f, series, over);
        }
        for a in &self.annotations {
            text(
                &mut s,
                f.tx(a.at[0]) + a.offset.0,
                f.ty(a.at[1]) + a.offset.1,
                a.anchor,
                FONT,
                &a.text,
                r##" class="note" fill="#444""##,
            );
        }
        if let Some(bar) = &self.colorbar {
            colorbar_svg(&mut s, bar, left + pw + 20.0, top + 20.0, ph - 20.0);
        }
        self.legend_svg(&mut s, &f, &hidden);
        s.push_str("</svg>\n");
        s
    }

    /// Where a label centred between the page abscissae `span` stands clear of every series:
    /// the baseline `(x, y)` of the first free place, scanning from the top of the plot down
    /// and from the middle of the span outward (the top middle if none is free).
    pub(super) fn free_spot(&self, f: &Frame, label: &str, span: (f64, f64)) -> (f64, f64) {
        let w = text_width(label, FONT);
        let (asc, desc) = text_extent(FONT);
        let segs: Vec<([f64; 2], [f64; 2])> = self
            .series
            .iter()
            .flat_map(|s| s.paths.iter())
            .flat_map(|p| {
                let pts: Vec<[f64; 2]> = p.iter().map(|q| f.page(*q)).collect();
                let mut v: Vec<_> = pts.windows(2).map(|w| (w[0], w[1])).collect();
                if pts.len() == 1 {
                    v.push((pts[0], pts[0]));
                }
                v
            })
            .collect();
        // clear by 3 px of a line's middle (its half width and a little air)
        let clear = |x0: f64, y0: f64| {
            let bx = [x0 - 3.0, y0 - 3.0, x0 + w + 3.0, y0 + asc + desc + 3.0];
            !segs
                .iter()
                .any(|(p, q)| super::overlap::seg_hits_box(*p, *q, bx))
        };
        let mid = 0.5 * (span.0 + span.1);
        let room = (0.5 * (span.1 - span.0 - w)).max(0.0);
        let mut y = f.top + 14.0;
        while y + desc <= f.top + f.ph - 4.0 {
            for k in 0..=8 {
                for side in [1.0, -1.0] {
                    let x = mid + side * room * f64::from(k) / 8.0;
                    if clear(x - 0.5 * w, y - asc) {
                        return (x, y);
                    }
                }
            }
            y += 6.0;
        }
        (mid, f.top + 14.0)
    }

    /// Frame, ticks and axis names.
    pub(super) fn axes_svg(&self, s: &mut String, f: &Frame) {
        let (left, top, pw, ph) = (f.left, f.top, f.pw, f.ph);
        let _ = writeln!(
            s,
            r##"<rect class="frame" x="{left}" y="{top}" width="{pw}" height="{ph}" fill="none" stroke="#888"/>"##
        );
        for v in nice_ticks(f.x0, f.x1) {
            let x = f.tx(v);
            let _ = writeln!(
                s,
                r##"<line x1="{x:.2}" y1="{:.2}" x2="{x:.2}" y2="{:.2}" stroke="#888"/>"##,
                top + ph,
                top + ph + 5.0,
            );
            text(s, x, top + ph + 18.0, "middle", FONT, &fmt_tick(v), TICK);
        }
        for v in nice_ticks(f.y0, f.y1) {
            let y = f.ty(v);
            let _ = writeln!(
                s,
                r##"<line x1="{:.2}" y1="{y:.2}" x2="{left}" y2="{y:.2}" stroke="#888"/>"##,
                left - 5.0,
            );
            text(s, left - 8.0, y + 4.0, "end", FONT, &fmt_tick(v), TICK);
        }
        let (xl, yl) = &self.axis_labels;
        if !xl.is_empty() {
            text(
                s,
                left + pw / 2.0,
                top + ph + 36.0,
                "middle",
                FONT,
                xl,
                r#" class="axis-label" data-axis="x""#,
            );
        }
        if !yl.is_empty() {
            // rotated: the box of the turned text, for the checks
            let cy = top + ph / 2.0;
            let wl = text_width(yl, FONT);
            let (asc, desc) = text_extent(FONT);
            let _ = writeln!(
                s,
                r#"<text class="axis-label" data-axis="y" x="16" y="{cy:.2}" text-anchor="middle" transform="rotate(-90 16 {cy:.2})" data-bbox="{:.2} {:.2} {:.2} {wl:.2}">{}</text>"#,
                16.0 - asc,
                cy - wl / 2.0,
                asc + desc,
                escape(yl)
            );
        }
    }

    /// One series; `over` is the series it would hide, if any (then it is drawn dashed).
    pub(super) fn series_svg(
        &self,
        s: &mut String,
        f: &Frame,
        series: &Series,
        over: Option<usize>,
    ) {
        let c = &series.color;
        let label = series.label.as_deref().unwrap_or_default();
        let note = over
            .and_then(|i| self.series[i].label.as_deref())
            .map(|l| format!(r#" data-coincides="{}""#, escape(l)))
            .unwrap_or_default();
        let _ = writeln!(
            s,
            r#"<g class="series" data-label="{}" data-width="{}"{note}>"#,
            escape(label),
            series.width()
        );
        let dash = if over.is_some() && !matches!(series.style, Style::Markers | Style::Dots) {
            "5 5"
        } else {
            series.dash_pattern()
        };
        let dash_attr = if dash.is_empty() {
            String::new()
        } else {
            format!(r#" stroke-dasharray="{dash}""#)
        };
        for path in &series.paths {
            match series.style {
                Style::Line | Style::Dashed => {
                    let pts: Vec<String> = path
                        .iter()
                        .map(|p| format!("{:.2},{:.2}", f.tx(p[0]), f.ty(p[1])))
                        .collect();
                    let _ = writeln!(
                        s,
                        r#"<polyline points="{}" fill="none" stroke="{c}" stroke-width="{}"{dash_attr} stroke-linejoin="round"/>"#,
                        pts.join(" "),
                        series.width()
                    );
                    if let (Some(m), true) = (series.marker, path.len() > 1) {
                        // three markers where the line is its own: off its lowest level (the
                        // zero line a family of basis functions shares), staggered by label so
                        // that lines of one family put theirs at different abscissae
                        let low = path.iter().fold(f64::INFINITY, |m, p| m.min(p[1]));
                        let own: Vec<&[f64; 2]> = path.iter().filter(|p| p[1] > low).collect();
                        let own = if own.is_empty() {
                            path.iter().collect()
                        } else {
                            own
                        };
                        let shift = 1 + label.len() % 3;
                        for q in 0..3 {
                            let p = own[((2 * q + shift) * own.len() / 8).min(own.len() - 1)];
                            marker(s, m, f.tx(p[0]), f.ty(p[1]), 3.5, c, "white");
                        }
                    }
                }
                Style::Markers | Style::Dots => {
                    let (r, fill) = if over.is_some() || series.style == Style::Dots {
                        (2.2, c.as_str())
                    } else {
                        (4.0, "white")
                    };
                    for p in path {
                        let m = series.marker.unwrap_or(Marker::Circle);
                        marker(s, m, f.tx(p[0]), f.ty(p[1]), r, c, fill);
                    }
                }
                Style::Ticks => {
                    for p in path {
                        let (x, y) = (f.tx(p[0]), f.ty(p[1]));
                        let _ = writeln!(
                            s,
                            r#"<line x1="{x:.2}" y1="{:.2}" x2="{x:.2}" y2="{:.2}" stroke="{c}" stroke-width="2"/>"#,
                            y - 7.0,
                            y + 7.0
                        );
                    }
                }
            }
        }
        s.push_str("</g>\n");
    }

    /// The legend: rows under the title, or a column right of the plot.
    pub(super) fn legend_svg(&self, s: &mut String, f: &Frame, hidden: &[(usize, usize)]) {
        let place = |s: &mut String, k: usize, x: f64, y: f64| {
            let (i, width) = f.entries[k];
            let series = &self.series[i];
            let c = &series.color;
            let (asc, desc) = text_extent(LEGEND_FONT);
            let _ = writeln!(
                s,
                r#"<g class="legend" data-bbox="{x:.2} {:.2} {width:.2} {:.2}">"#,
                y + 4.0 - asc,
                asc + desc
            );
            let over = hidden.iter().any(|(_, j)| *j == i);
            match series.style {
                Style::Markers | Style::Dots => {
                    let m = series.marker.unwrap_or(Marker::Circle);
                    let (r, fill) = if over || series.style == Style::Dots {
                        (2.2, c.as_str())
                    } else {
                        (4.0, "white")
                    };
                    marker(s, m, x + 11.0, y, r, c, fill);
                }
                _ => {
                    let dash = if over { "5 5" } else { series.dash_pattern() };
                    let dash = if dash.is_empty() {
                        String::new()
                    } else {
                        format!(r#" stroke-dasharray="{dash}""#)
                    };
                    let _ = writeln!(
                        s,
                        r#"<line x1="{x:.2}" y1="{y:.2}" x2="{:.2}" y2="{y:.2}" stroke="{c}" stroke-width="{}"{dash}/>"#,
                        x + 22.0,
                        series.width()
                    );
                    if let Some(m) = series.marker {
                        marker(s, m, x + 11.0, y, 3.5, c, "white");
                    }
                }
            }
            let label = series.label.as_deref().unwrap_or_default();
            text(
                s,
                x + LEGEND_SAMPLE,
                y + 4.0,
                "start",
                LEGEND_FONT,
                label,
                "",
            );
            s.push_str("</g>\n");
        };
        match &f.legend {
            LegendPlace::None => {}
            LegendPlace::Rows(rows) => {
                for (r, row) in rows.iter().enumerate() {
                    let used: f64 = row.iter().map(|k| f.entries[*k].1).sum::<f64>()
                        + LEGEND_GAP * (row.len() as f64 - 1.0);
                    // aligned with the plot if the row fits there, else from the left edge
                    let mut x = if f.left + used <= f.w - 12.0 {
                        f.left
                    } else {
                        12.0
                    };
                    let y = LEGEND_Y + LEGEND_ROW * r as f64;
                    for k in row {
                        place(s, *k, x, y);
                        x += f.entries[*k].1 + LEGEND_GAP;
                    }
                }
            }
            LegendPlace::Column(_) => {
                let x = f.w - f.entries.iter().fold(0.0_f64, |m, e| m.max(e.1)) - 12.0;
                for k in 0..f.entries.len() {
                    place(s, k, x, f.top + 8.0 + LEGEND_ROW * k as f64);
                }
            }
        }
    }
}

/// A vertical colour bar with ticks at `(x, top)`, `height` pixels tall.
pub(super) fn colorbar_svg(s: &mut String, bar: &ColorBar, x: f64, top: f64, height: f64) {
    let (lo, hi) = bar.range;
    let steps = 48;
    // the range in full (shortest round-trip) precision for readers of the SVG; the ticks are
    // rounded for the eye
    let _ = writeln!(
        s,
        r#"<g class="colorbar" data-label="{}" data-bar="{x:.2} {top:.2} {BAR} {height:.2}" data-range="{} {}">"#,
        escape(&bar.label),
        crate::fmt_number(lo),
        crate::fmt_number(hi)
    );
    for k in 0..steps {
        let a = f64::from(k) / f64::from(steps);
        let y = top + height * (1.0 - a - 1.0 / f64::from(steps));
        let _ = writeln!(
            s,
            r#"<rect x="{x:.2}" y="{y:.2}" width="{BAR}" height="{:.2}" fill="{}"/>"#,
            height / f64::from(steps) + 0.5,
            height_color(a + 0.5 / f64::from(steps))
        );
    }
    let _ = writeln!(
        s,
        r##"<rect x="{x:.2}" y="{top:.2}" width="{BAR}" height="{height:.2}" fill="none" stroke="#888"/>"##
    );
    for (v, label) in colorbar_ticks(lo, hi, height) {
        let y = if hi > lo {
            top + height * (hi - v) / (hi - lo)
        } else {
            top + height / 2.0
        };
        let _ = writeln!(
            s,
            r##"<line x1="{:.2}" y1="{y:.2}" x2="{:.2}" y2="{y:.2}" stroke="#888"/>"##,
            x + BAR,
            x + BAR + 4.0
        );
        text(s, x + BAR + 6.0, y + 4.0, "start", FONT, &label, TICK);
    }
    // the name a line above the top value
    text(s, x, top - 12.0, "start", FONT, &bar.label, "");
    s.push_str("</g>\n");
}

/// The labelled ticks of a colour bar `height` pixels tall over `[lo, hi]`: both ends with
/// their values (four significant digits), and the round values between them that stand at
/// least a line (1.5 × the font size) from the ends and from each other.
pub(super) fn colorbar_ticks(lo: f64, hi: f64, height: f64) -> Vec<(f64, String)> {
    if hi.partial_cmp(&lo) != Some(std::cmp::Ordering::Greater) {
        return vec![(lo, fmt_legend(lo))];
    }
    let line = 1.5 * FONT;
    let y = |v: f64| height * (hi - v) / (hi - lo);
    let mut out = vec![(hi, fmt_legend(hi))];
    let inner: Vec<f64> = nice_ticks(lo, hi)
        .into_iter()
        .filter(|v| y(*v) >= line && y(*v) <= height - line)
        .collect();
    // every k-th round value, so that neighbours stand a line apart
    let gap = if inner.len() > 1 {
        (y(inner[0]) - y(inner[1])).abs()
    } else {
        height
    };
    let every = (line / gap.max(f64::MIN_POSITIVE)).ceil().max(1.0);
    // a count of ticks (at most 50), so the cast is exact
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    let every = every.min(64.0) as usize;
    out.extend(inner.into_iter().step_by(every).map(|v| (v, fmt_tick(v))));
    out.push((lo, fmt_legend(lo)));
    out
}

/// Escapes text for SVG/HTML.
#[must_use]
pub fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}
