//! SVG figures: a small plotting layer (axes, ticks, legend) and the standard lekalo plots —
//! a curve with its control polygon, data points and knot marks; B-spline basis functions; a
//! knot vector; a surface wireframe in a simple projection (see [`crate::wireframe`]).
//!
//! A [`Figure`] is data (series of polylines or markers in world coordinates); [`Figure::to_svg`]
//! maps it to the page. Figures are deterministic: the same input gives the same bytes.

use std::fmt::Write as _;

use lekalo::{basis::basis_function_recursive, KnotVector, Points};

use crate::layout::{
    place_legend, text_extent, text_width, LegendPlace, LEGEND_FONT, LEGEND_GAP, LEGEND_ROW,
    LEGEND_SAMPLE,
};
use crate::object::Object;
use crate::palette::{height_color, look, Marker, PALETTE};

/// How a series is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Style {
    /// Solid polyline.
    Line,
    /// Dashed polyline (control polygons).
    Dashed,
    /// A marker at every point (data and control points).
    Markers,
    /// Short vertical ticks at every point (knots on a number line).
    Ticks,
}

/// One series: polylines (or markers) in world coordinates.
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    /// Legend text (no legend entry if `None`).
    pub label: Option<String>,
    /// Polylines; markers and ticks use every vertex.
    pub paths: Vec<Vec<[f64; 2]>>,
    /// Drawing style.
    pub style: Style,
    /// CSS colour.
    pub color: String,
    /// Dash pattern (SVG `stroke-dasharray`) instead of the style's own; `Some("")` is solid.
    pub dash: Option<String>,
    /// Marker shape: of a [`Style::Markers`] series (default: circle), or drawn along a line
    /// at a few of its vertices.
    pub marker: Option<Marker>,
}

impl Series {
    /// A series of one polyline.
    #[must_use]
    pub fn new(label: Option<&str>, points: Vec<[f64; 2]>, style: Style, color: &str) -> Self {
        Series {
            label: label.map(str::to_string),
            paths: vec![points],
            style,
            color: color.to_string(),
            dash: None,
            marker: None,
        }
    }

    /// Line `i` of a family (basis functions, a parameter sweep): colour, dash and marker from
    /// [`crate::palette::look`], so that any two of the first 28 lines differ.
    #[must_use]
    pub fn nth(label: Option<&str>, points: Vec<[f64; 2]>, i: usize) -> Self {
        let (color, dash, marker) = look(i);
        Series {
            label: label.map(str::to_string),
            paths: vec![points],
            style: Style::Line,
            color: color.to_string(),
            dash: Some(dash.to_string()),
            marker,
        }
    }

    /// Stroke width in pixels.
    fn width(&self) -> f64 {
        match self.style {
            Style::Line | Style::Ticks => 2.0,
            Style::Dashed => 1.2,
            Style::Markers => 1.8,
        }
    }

    /// The dash pattern drawn ("" for solid).
    fn dash_pattern(&self) -> &str {
        match (&self.dash, self.style) {
            (Some(d), _) => d,
            (None, Style::Dashed) => "6 4",
            _ => "",
        }
    }
}

/// A filled polygon of a shaded surface, in world coordinates.
#[derive(Debug, Clone, PartialEq)]
pub struct Face {
    /// Corners (projected).
    pub points: Vec<[f64; 2]>,
    /// CSS fill colour.
    pub fill: String,
    /// Segments drawn over the fill (isoparametric lines on this face), so that nearer faces
    /// hide them as they hide the face.
    pub edges: Vec<[[f64; 2]; 2]>,
    /// CSS colour and width in pixels of the edges.
    pub edge_style: (String, f64),
}

/// Text placed at a world point, moved by a pixel offset.
#[derive(Debug, Clone, PartialEq)]
pub struct Annotation {
    /// World position.
    pub at: [f64; 2],
    /// Offset in pixels (x right, y down).
    pub offset: (f64, f64),
    /// The text.
    pub text: String,
    /// `start`, `middle` or `end`.
    pub anchor: &'static str,
}

/// A colour scale beside the plot (the height map of shaded surfaces).
#[derive(Debug, Clone, PartialEq)]
pub struct ColorBar {
    /// Name of the quantity (e.g. `z`).
    pub label: String,
    /// Values at the bottom and the top of the bar.
    pub range: (f64, f64),
}

/// Two labelled series that are drawn on top of each other: the later one is drawn dashed so
/// that the earlier one shows through, and captions say so ([`Figure::coincidences`]).
#[derive(Debug, Clone, PartialEq)]
pub struct Coincidence {
    /// Label of the series that would be hidden.
    pub hidden: String,
    /// Label of the series drawn over it.
    pub over: String,
    /// Largest distance from a point of the hidden series to the other, in data units.
    pub distance: f64,
}

impl Coincidence {
    /// A sentence for a caption.
    #[must_use]
    pub fn note(&self) -> String {
        let by = if self.distance == 0.0 {
            "exactly".to_string()
        } else {
            format!("to {:.0e}", self.distance)
        };
        format!(
            "“{}” coincides with “{}” ({by}): it is drawn dashed over it.",
            self.over, self.hidden
        )
    }
}

/// A 2-D plot.
#[derive(Debug, Clone, PartialEq)]
pub struct Figure {
    /// Title above the plot.
    pub title: String,
    /// Width and height in pixels, before the legend, title and labels grow the canvas.
    pub size: (f64, f64),
    /// Same scale on both axes (true for geometry, false for function graphs).
    pub equal_aspect: bool,
    /// Axis labels `(x, y)`.
    pub axis_labels: (String, String),
    /// Draw axes with ticks (false for projected 3-D views).
    pub axes: bool,
    /// The series, drawn in order.
    pub series: Vec<Series>,
    /// Shaded vertical band `[a, b]` with a label (e.g. the parameter domain).
    pub band: Option<(f64, f64, String)>,
    /// Filled polygons drawn before the series, in order (back to front).
    pub faces: Vec<Face>,
    /// Texts at world positions (3-D axis ticks and names).
    pub annotations: Vec<Annotation>,
    /// Colour scale beside the plot.
    pub colorbar: Option<ColorBar>,
}

const MARGIN_LEFT: f64 = 60.0;
const MARGIN_RIGHT: f64 = 20.0;
const MARGIN_TOP: f64 = 54.0;
const MARGIN_BOTTOM: f64 = 44.0;
/// Baseline of the title.
const TITLE_Y: f64 = 22.0;
const TITLE_FONT: f64 = 15.0;
const FONT: f64 = 12.0;
/// Centre line of the first legend row.
const LEGEND_Y: f64 = 42.0;
/// Width of the colour bar's strip, pixels.
const BAR: f64 = 14.0;

/// The page geometry of a figure: canvas, plot rectangle, world window, legend placement.
struct Frame {
    w: f64,
    h: f64,
    left: f64,
    top: f64,
    pw: f64,
    ph: f64,
    x0: f64,
    x1: f64,
    y0: f64,
    y1: f64,
    /// Labelled series and their legend widths.
    entries: Vec<(usize, f64)>,
    legend: LegendPlace,
}

impl Frame {
    // differences taken of halves, so that data spanning ±1.8e308 does not overflow
    fn tx(&self, x: f64) -> f64 {
        self.left + (x / 2.0 - self.x0 / 2.0) / (self.x1 / 2.0 - self.x0 / 2.0) * self.pw
    }

    fn ty(&self, y: f64) -> f64 {
        self.top + (self.y1 / 2.0 - y / 2.0) / (self.y1 / 2.0 - self.y0 / 2.0) * self.ph
    }

    fn page(&self, p: [f64; 2]) -> [f64; 2] {
        [self.tx(p[0]), self.ty(p[1])]
    }
}

/// Writes a `<text>` element with its estimated box as `data-bbox="x y w h"`.
fn text(s: &mut String, x: f64, y: f64, anchor: &str, size: f64, body: &str, extra: &str) {
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
fn marker(s: &mut String, shape: Marker, x: f64, y: f64, r: f64, color: &str, fill: &str) {
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

/// Distance from `p` to the segment `[a, b]`.
fn seg_dist(p: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let len2 = dx * dx + dy * dy;
    let t = if len2 > 0.0 {
        (((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (p[0] - a[0] - t * dx).hypot(p[1] - a[1] - t * dy)
}

/// Largest distance from a vertex of `a` to the nearest polyline of `b` (to the nearest vertex
/// if `b` is markers), stopping early once it exceeds `stop`.
fn one_sided(a: &[Vec<[f64; 2]>], b: &[Vec<[f64; 2]>], lines: bool, stop: f64) -> f64 {
    let mut worst = 0.0_f64;
    for p in a.iter().flatten() {
        let mut best = f64::INFINITY;
        for path in b {
            if lines && path.len() > 1 {
                for w in path.windows(2) {
                    best = best.min(seg_dist(*p, w[0], w[1]));
                }
            } else {
                for q in path {
                    best = best.min((p[0] - q[0]).hypot(p[1] - q[1]));
                }
            }
        }
        worst = worst.max(best);
        if worst > stop {
            break;
        }
    }
    worst
}

/// Bounding box `(xmin, xmax, ymin, ymax)` of paths.
fn bbox(paths: &[Vec<[f64; 2]>]) -> (f64, f64, f64, f64) {
    paths.iter().flatten().fold(
        (
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
        ),
        |b, p| (b.0.min(p[0]), b.1.max(p[0]), b.2.min(p[1]), b.3.max(p[1])),
    )
}

impl Figure {
    /// An empty figure of the given title.
    #[must_use]
    pub fn new(title: &str, equal_aspect: bool) -> Self {
        Figure {
            title: title.to_string(),
            size: (640.0, 420.0),
            equal_aspect,
            axis_labels: (String::new(), String::new()),
            axes: true,
            series: Vec::new(),
            band: None,
            faces: Vec::new(),
            annotations: Vec::new(),
            colorbar: None,
        }
    }

    /// Data bounds `(xmin, xmax, ymin, ymax)`, padded by 5 % and never degenerate.
    fn bounds(&self) -> (f64, f64, f64, f64) {
        let mut b = (
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
        );
        let faces = self.faces.iter().flat_map(|f| f.points.iter());
        let notes = self.annotations.iter().map(|a| &a.at);
        for p in self
            .series
            .iter()
            .flat_map(|s| s.paths.iter().flatten())
            .chain(faces)
            .chain(notes)
            .filter(|p| p[0].is_finite() && p[1].is_finite())
        {
            b.0 = b.0.min(p[0]);
            b.1 = b.1.max(p[0]);
            b.2 = b.2.min(p[1]);
            b.3 = b.3.max(p[1]);
        }
        if let Some((a, c, _)) = &self.band {
            b.0 = b.0.min(*a);
            b.1 = b.1.max(*c);
        }
        if !b.0.is_finite() {
            return (0.0, 1.0, 0.0, 1.0);
        }
        // padded by 5 % of the span, computed from halves and clamped to the finite range so
        // that coordinates near ±1.8e308 neither overflow nor collapse the frame
        let fix = |lo: f64, hi: f64| {
            let half = hi / 2.0 - lo / 2.0;
            let pad = if half > 0.0 {
                0.1 * half
            } else {
                0.5 * lo.abs().max(f64::MIN_POSITIVE)
            };
            let clamp = |v: f64| v.clamp(-f64::MAX, f64::MAX);
            (clamp(lo - pad), clamp(hi + pad))
        };
        let (x0, x1) = fix(b.0, b.1);
        let (y0, y1) = fix(b.2, b.3);
        (x0, x1, y0, y1)
    }

    /// Width of the colour bar with its tick labels, or 0.
    fn colorbar_width(&self) -> f64 {
        self.colorbar.as_ref().map_or(0.0, |c| {
            let labels = nice_ticks(c.range.0, c.range.1)
                .into_iter()
                .map(|v| text_width(&fmt_tick(v), FONT))
                .chain([text_width(&c.label, FONT) - BAR - 6.0])
                .fold(0.0_f64, f64::max);
            20.0 + BAR + 6.0 + labels + 8.0
        })
    }

    /// Lays the figure out: margins grow to hold tick labels, the canvas grows to hold the
    /// title, the legend (rows above the plot, or a column beside it) and the colour bar; the
    /// plot keeps the size asked for in [`Figure::size`].
    fn frame(&self) -> Frame {
        let (bx0, bx1, by0, by1) = self.bounds();
        // the plot's width is what `size` leaves beside the usual margins; wider tick labels,
        // a colour bar or a legend column widen the canvas instead of narrowing the plot
        let usual_left = if self.axes { MARGIN_LEFT } else { 20.0 };
        let pw = (self.size.0 - usual_left - MARGIN_RIGHT).max(100.0);
        let bottom = if self.axes { MARGIN_BOTTOM } else { 16.0 };
        let ph = (self.size.1 - MARGIN_TOP - MARGIN_BOTTOM).max(60.0);
        let (mut x0, mut x1, mut y0, mut y1) = (bx0, bx1, by0, by1);
        if self.equal_aspect {
            // half-extents per pixel, from halves so that nothing overflows
            let s = ((x1 / 2.0 - x0 / 2.0) / pw).max((y1 / 2.0 - y0 / 2.0) / ph);
            let (cx, cy) = (x0 / 2.0 + x1 / 2.0, y0 / 2.0 + y1 / 2.0);
            let clamp = |v: f64| v.clamp(-f64::MAX, f64::MAX);
            x0 = clamp(cx - s * pw);
            x1 = clamp(cx + s * pw);
            y0 = clamp(cy - s * ph);
            y1 = clamp(cy + s * ph);
        }
        let left = if self.axes {
            let labels = nice_ticks(y0, y1)
                .into_iter()
                .map(|v| text_width(&fmt_tick(v), FONT))
                .fold(0.0_f64, f64::max);
            // tick (5) + gap (3) + labels + gap (6) + the rotated axis name (20)
            MARGIN_LEFT.max(labels + 34.0)
        } else {
            20.0
        };
        let entries: Vec<(usize, f64)> = self
            .series
            .iter()
            .enumerate()
            .filter_map(|(i, s)| {
                s.label
                    .as_deref()
                    .map(|l| (i, LEGEND_SAMPLE + text_width(l, LEGEND_FONT)))
            })
            .collect();
        let mut w = left + pw + MARGIN_RIGHT + self.colorbar_width();
        let widths: Vec<f64> = entries.iter().map(|e| e.1).collect();
        let legend = place_legend(&widths, w - 24.0);
        let (top, column) = match &legend {
            LegendPlace::None => (40.0, 0.0),
            LegendPlace::Rows(rows) => (MARGIN_TOP + LEGEND_ROW * (rows.len() as f64 - 1.0), 0.0),
            LegendPlace::Column(cw) => (40.0, cw + 24.0),
        };
        w += column;
        w = w.max(text_width(&self.title, TITLE_FONT) + 24.0);
        let mut h = top + ph + bottom;
        if let LegendPlace::Column(_) = legend {
            h = h.max(top + LEGEND_ROW * entries.len() as f64 + bottom);
        }
        Frame {
            w: w.ceil(),
            h: h.ceil(),
            left,
            top,
            pw,
            ph,
            x0,
            x1,
            y0,
            y1,
            entries,
            legend,
        }
    }

    /// Pairs of labelled series of which the earlier would be hidden under the later on the
    /// page (every point of it within a line width of the other): the later one is drawn dashed
    /// over the earlier, and the caption should carry [`Coincidence::note`].
    #[must_use]
    pub fn coincidences(&self) -> Vec<Coincidence> {
        let frame = self.frame();
        self.hidden_pairs(&frame)
            .into_iter()
            .map(|(i, j)| {
                let (a, b) = (&self.series[i], &self.series[j]);
                let lines = b.style != Style::Markers;
                Coincidence {
                    hidden: a.label.clone().unwrap_or_default(),
                    over: b.label.clone().unwrap_or_default(),
                    distance: one_sided(&a.paths, &b.paths, lines, f64::INFINITY),
                }
            })
            .collect()
    }

    /// `(i, j)`, `i < j`, both labelled, same kind (lines or markers), where series `i` lies
    /// within a line width of series `j` on the page.
    fn hidden_pairs(&self, frame: &Frame) -> Vec<(usize, usize)> {
        let page: Vec<Vec<Vec<[f64; 2]>>> = self
            .series
            .iter()
            .map(|s| {
                s.paths
                    .iter()
                    .map(|p| p.iter().map(|q| frame.page(*q)).collect())
                    .collect()
            })
            .collect();
        let boxes: Vec<_> = page.iter().map(|p| bbox(p)).collect();
        let kind = |s: &Series| match s.style {
            Style::Line | Style::Dashed => Some(true),
            Style::Markers => Some(false),
            Style::Ticks => None,
        };
        let mut out = Vec::new();
        for j in 0..self.series.len() {
            for i in 0..j {
                let (a, b) = (&self.series[i], &self.series[j]);
                if a.label.is_none() || b.label.is_none() || kind(a).is_none() {
                    continue;
                }
                if kind(a) != kind(b) || page[i].iter().all(Vec::is_empty) {
                    continue;
                }
                let tol = a.width().max(b.width()) + if kind(a) == Some(false) { 2.0 } else { 0.0 };
                let (ba, bb) = (boxes[i], boxes[j]);
                if ba.0 < bb.0 - tol || ba.1 > bb.1 + tol || ba.2 < bb.2 - tol || ba.3 > bb.3 + tol
                {
                    continue;
                }
                if one_sided(&page[i], &page[j], kind(a) == Some(true), tol) <= tol {
                    out.push((i, j));
                }
            }
        }
        out
    }

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
            text(
                &mut s,
                0.5 * (f.tx(*a) + f.tx(*b)),
                top + 14.0,
                "middle",
                FONT,
                label,
                r##" fill="#8a6d00""##,
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
                r##" fill="#444""##,
            );
        }
        if let Some(bar) = &self.colorbar {
            colorbar_svg(&mut s, bar, left + pw + 20.0, top + 20.0, ph - 20.0);
        }
        self.legend_svg(&mut s, &f, &hidden);
        s.push_str("</svg>\n");
        s
    }

    /// Frame, ticks and axis names.
    fn axes_svg(&self, s: &mut String, f: &Frame) {
        let (left, top, pw, ph) = (f.left, f.top, f.pw, f.ph);
        let _ = writeln!(
            s,
            r##"<rect x="{left}" y="{top}" width="{pw}" height="{ph}" fill="none" stroke="#888"/>"##
        );
        for v in nice_ticks(f.x0, f.x1) {
            let x = f.tx(v);
            let _ = writeln!(
                s,
                r##"<line x1="{x:.2}" y1="{:.2}" x2="{x:.2}" y2="{:.2}" stroke="#888"/>"##,
                top + ph,
                top + ph + 5.0,
            );
            text(s, x, top + ph + 18.0, "middle", FONT, &fmt_tick(v), "");
        }
        for v in nice_ticks(f.y0, f.y1) {
            let y = f.ty(v);
            let _ = writeln!(
                s,
                r##"<line x1="{:.2}" y1="{y:.2}" x2="{left}" y2="{y:.2}" stroke="#888"/>"##,
                left - 5.0,
            );
            text(s, left - 8.0, y + 4.0, "end", FONT, &fmt_tick(v), "");
        }
        let (xl, yl) = &self.axis_labels;
        if !xl.is_empty() {
            text(s, left + pw / 2.0, top + ph + 36.0, "middle", FONT, xl, "");
        }
        if !yl.is_empty() {
            // rotated: the box of the turned text, for the checks
            let cy = top + ph / 2.0;
            let wl = text_width(yl, FONT);
            let (asc, desc) = text_extent(FONT);
            let _ = writeln!(
                s,
                r#"<text x="16" y="{cy:.2}" text-anchor="middle" transform="rotate(-90 16 {cy:.2})" data-bbox="{:.2} {:.2} {:.2} {wl:.2}">{}</text>"#,
                16.0 - asc,
                cy - wl / 2.0,
                asc + desc,
                escape(yl)
            );
        }
    }

    /// One series; `over` is the series it would hide, if any (then it is drawn dashed).
    fn series_svg(&self, s: &mut String, f: &Frame, series: &Series, over: Option<usize>) {
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
        let dash = if over.is_some() && series.style != Style::Markers {
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
                Style::Markers => {
                    let (r, fill) = if over.is_some() {
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
    fn legend_svg(&self, s: &mut String, f: &Frame, hidden: &[(usize, usize)]) {
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
                Style::Markers => {
                    let m = series.marker.unwrap_or(Marker::Circle);
                    let (r, fill) = if over {
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
fn colorbar_svg(s: &mut String, bar: &ColorBar, x: f64, top: f64, height: f64) {
    let (lo, hi) = bar.range;
    let steps = 48;
    // the range in full (shortest round-trip) precision for readers of the SVG; the ticks are
    // rounded for the eye
    let _ = writeln!(
        s,
        r#"<g class="colorbar" data-label="{}" data-range="{} {}">"#,
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
    if hi > lo {
        for v in nice_ticks(lo, hi) {
            let y = top + height * (hi - v) / (hi - lo);
            let _ = writeln!(
                s,
                r##"<line x1="{:.2}" y1="{y:.2}" x2="{:.2}" y2="{y:.2}" stroke="#888"/>"##,
                x + BAR,
                x + BAR + 4.0
            );
            text(s, x + BAR + 6.0, y + 4.0, "start", FONT, &fmt_tick(v), "");
        }
    } else {
        text(
            s,
            x + BAR + 6.0,
            top + height / 2.0 + 4.0,
            "start",
            FONT,
            &fmt_tick(lo),
            "",
        );
    }
    text(s, x, top - 8.0, "start", FONT, &bar.label, "");
    s.push_str("</g>\n");
}

/// Escapes text for SVG/HTML.
#[must_use]
pub fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// Tick values at 1, 2 or 5 × 10^k covering `[lo, hi]` (about five ticks).
pub(crate) fn nice_ticks(lo: f64, hi: f64) -> Vec<f64> {
    // the span from halves, so that [-1e308, 1e308] does not overflow
    let half = hi / 2.0 - lo / 2.0;
    if half.is_nan() || half <= 0.0 || !half.is_finite() {
        return Vec::new();
    }
    let raw = half / 2.5;
    let mag = 10f64.powf(raw.log10().floor());
    let step = [1.0, 2.0, 5.0, 10.0]
        .iter()
        .map(|m| m * mag)
        .find(|s| *s >= raw)
        .unwrap_or(10.0 * mag);
    if !(step > 0.0 && step.is_finite()) {
        return Vec::new();
    }
    let first = (lo / step).ceil();
    let last = (hi / step).floor();
    let mut out = Vec::new();
    let mut k = first;
    while k <= last && out.len() < 50 {
        let v = k * step;
        if v.is_finite() {
            out.push(v);
        }
        k += 1.0;
    }
    out
}

pub(crate) fn fmt_tick(v: f64) -> String {
    let a = v.abs();
    if a != 0.0 && !(1e-4..1e6).contains(&a) {
        // exponent notation with up to four significant digits: `1.5e300`, `2e-320`, never
        // `inf` or a row of zeros
        let s = format!("{v:.3e}");
        return match s.split_once('e') {
            Some((m, e)) => format!("{}e{e}", m.trim_end_matches('0').trim_end_matches('.')),
            None => s,
        };
    }
    let r = (v * 1e9).round() / 1e9;
    let s = format!("{r}");
    if s == "-0" {
        "0".into()
    } else {
        s
    }
}

/// A figure in a legend: four significant digits (`0.1189`, `3.957e-7`), exponent notation
/// outside `[1e-4, 1e6)` as on the ticks.
fn fmt_legend(v: f64) -> String {
    let a = v.abs();
    if a == 0.0 || !(1e-4..1e6).contains(&a) {
        return fmt_tick(v);
    }
    // a is in [1e-4, 1e6): three decimals from 1 on, one more for each power of ten below
    let (mut decimals, mut bound) = (0, 1000.0);
    while a < bound && decimals < 7 {
        decimals += 1;
        bound /= 10.0;
    }
    let s = format!("{v:.decimals$}");
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    }
}

/// What to draw besides the curve.
#[derive(Debug, Clone, PartialEq)]
pub struct CurvePlot<'a> {
    /// Title (defaults to the object type).
    pub title: Option<String>,
    /// Number of evaluation points along the curve.
    pub samples: usize,
    /// Draw the control polygon and control points.
    pub control_polygon: bool,
    /// Mark the curve's points at the distinct knots inside the domain.
    pub knot_marks: bool,
    /// Data points to show (e.g. the points a curve interpolates).
    pub data_points: Option<&'a Points>,
    /// Projection for curves in 3-D or more (first three coordinates are used).
    pub projection: crate::wireframe::Projection,
}

impl Default for CurvePlot<'_> {
    fn default() -> Self {
        CurvePlot {
            title: None,
            samples: 200,
            control_polygon: true,
            knot_marks: true,
            data_points: None,
            projection: crate::wireframe::Projection::default(),
        }
    }
}

/// Maps a point of any dimension to the plane ([`crate::Projection::to_plane`]).
fn to_plane(p: &[f64], projection: &crate::wireframe::Projection) -> [f64; 2] {
    projection.to_plane(p)
}

/// Most vertices of a control polygon or data series drawn in a curve plot; beyond it every
/// k-th is drawn (first and last kept), as a picture cannot show more.
pub(crate) const PLOT_MAX_VERTICES: usize = 20_000;
/// Most markers (control points, points at knots, data points) drawn per series; beyond it the
/// markers are left out and the legend says so.
pub(crate) const PLOT_MAX_MARKERS: usize = 2_000;

/// Every k-th of `n` indices (first and last kept) so that at most `max` remain.
fn decimated(n: usize, max: usize) -> impl Iterator<Item = usize> {
    let k = n.div_ceil(max.max(2) - 1).max(1);
    (0..n)
        .step_by(k)
        .chain((n > 0 && (n - 1) % k != 0).then_some(n - 1))
}

/// Plot of a curve: the curve over its domain, its control polygon, knot marks and data points.
/// Huge objects are decimated: at most 20,000 vertices of a control polygon and 2,000 markers
/// per series are drawn.
///
/// # Errors
/// Evaluation errors of the library (none for a valid object).
pub fn curve_figure(obj: &Object, opts: &CurvePlot<'_>) -> lekalo::Result<Figure> {
    let title = opts.title.clone().unwrap_or_else(|| {
        format!(
            "{} of degree {} ({} control points)",
            obj.display_name(),
            obj.degree(),
            obj.control_points().len()
        )
    });
    let mut fig = Figure::new(&title, true);
    let proj = &opts.projection;
    let curve: Vec<[f64; 2]> = obj
        .sample(opts.samples.max(2))?
        .iter()
        .map(|p| to_plane(p, proj))
        .collect();
    if opts.control_polygon {
        let cp = obj.control_points();
        let n = cp.len();
        let ctrl: Vec<[f64; 2]> = decimated(n, PLOT_MAX_VERTICES)
            .map(|i| to_plane(cp.point(i), proj))
            .collect();
        let label = if ctrl.len() < n {
            format!("control polygon ({} of {n} points)", ctrl.len())
        } else {
            "control polygon".to_string()
        };
        let markers = (ctrl.len() <= PLOT_MAX_MARKERS).then(|| ctrl.clone());
        fig.series
            .push(Series::new(Some(&label), ctrl, Style::Dashed, "#777777"));
        if let Some(m) = markers {
            fig.series
                .push(Series::new(None, m, Style::Markers, "#777777"));
        }
    }
    fig.series
        .push(Series::new(Some("curve"), curve, Style::Line, PALETTE[0]));
    if opts.knot_marks {
        let (a, b) = obj.domain();
        let inside: Vec<f64> = obj
            .knots()
            .distinct()
            .into_iter()
            .map(|(t, _)| t)
            .filter(|t| *t >= a && *t <= b)
            .collect();
        let mut marks = Vec::new();
        for i in decimated(inside.len(), PLOT_MAX_MARKERS) {
            marks.push(to_plane(&obj.eval(inside[i])?, proj));
        }
        fig.series.push(Series::new(
            Some("points at knots"),
            marks,
            Style::Markers,
            PALETTE[1],
        ));
    }
    if let Some(data) = opts.data_points {
        let pts = decimated(data.len(), PLOT_MAX_MARKERS)
            .map(|i| to_plane(data.point(i), proj))
            .collect();
        fig.series.push(Series::new(
            Some("data points"),
            pts,
            Style::Markers,
            PALETTE[2],
        ));
    }
    fig.axis_labels = if obj.dim() == 2 {
        ("x".into(), "y".into())
    } else {
        (String::new(), String::new())
    };
    fig.axes = obj.dim() <= 2;
    Ok(fig)
}

/// The deviations of data points from a curve: a segment from each point `Q_k` to `feet[k]`, its
/// closest point on the curve (found by the library, `docs/theory/queries.md#closest-points`),
/// in the curve plot's coordinates. The legend gives the largest and the root-mean-square
/// distance `|Q_k − feet[k]|` over every point; the segments are decimated like the data
/// markers (at most 2,000, the same indices), and the segment of the largest distance is always
/// drawn.
///
/// # Errors
/// [`lekalo::Error::Dimension`] if `feet` and `data` differ in dimension or count.
pub fn residual_series(
    data: &Points,
    feet: &Points,
    projection: &crate::wireframe::Projection,
) -> lekalo::Result<Series> {
    if feet.dim() != data.dim() || feet.len() != data.len() {
        return Err(lekalo::Error::Dimension {
            what: "closest points of the data points",
            expected: data.dim() * data.len(),
            got: feet.dim() * feet.len(),
        });
    }
    let dist = |i: usize| {
        data.point(i)
            .iter()
            .zip(feet.point(i))
            .map(|(a, b)| (a - b) * (a - b))
            .sum::<f64>()
            .sqrt()
    };
    let (mut worst, mut max, mut sum_sq) = (0, 0.0_f64, 0.0_f64);
    for i in 0..data.len() {
        let d = dist(i);
        sum_sq += d * d;
        if d > max {
            (worst, max) = (i, d);
        }
    }
    let rms = if data.is_empty() {
        0.0
    } else {
        (sum_sq / data.len() as f64).sqrt()
    };
    let mut drawn: Vec<usize> = decimated(data.len(), PLOT_MAX_MARKERS).collect();
    if !data.is_empty() && !drawn.contains(&worst) {
        drawn.push(worst);
    }
    let mut series = Series::new(
        Some(&format!(
            "deviations: max {}, RMS {}",
            fmt_legend(max),
            fmt_legend(rms)
        )),
        Vec::new(),
        Style::Line,
        PALETTE[3],
    );
    series.paths = drawn
        .into_iter()
        .map(|i| {
            vec![
                projection.to_plane(data.point(i)),
                projection.to_plane(feet.point(i)),
            ]
        })
        .collect();
    Ok(series)
}

/// Graphs of the B-spline basis functions `N_{i,p}(t)`, `i = 0 … n`, over the whole knot range
/// `[t_0, t_m]` by the Cox–de Boor recursion (document 002, B-splines; P&T eq. 2.5), with the valid
/// domain `[t_p, t_{n+1}]` shaded (there, and only there, `Σ N_{i,p} = 1`).
///
/// # Errors
/// [`lekalo::Error::Degree`] if the knots are too few for `degree`; other errors of
/// [`KnotVector::validate_for`].
pub fn basis_figure(knots: &KnotVector, degree: usize, samples: usize) -> lekalo::Result<Figure> {
    let n_basis = knots
        .len()
        .checked_sub(degree + 1)
        .filter(|n| *n > 0)
        .ok_or_else(|| lekalo::Error::Degree {
            degree,
            reason: format!(
                "{} knots give no basis function of this degree",
                knots.len()
            ),
        })?;
    knots.validate_for(degree, n_basis)?;
    let k = knots.as_slice();
    let (lo, hi) = (k[0], k[k.len() - 1]);
    let ts = crate::analysis::uniform(lo, hi, samples.max(2));
    let mut fig = Figure::new(
        &format!("B-spline basis functions of degree {degree}"),
        false,
    );
    fig.size = (640.0, 360.0);
    fig.axis_labels = ("t".into(), "N(t)".into());
    let (a, b) = knots.domain(degree);
    fig.band = Some((a, b, "domain: Σ N = 1".into()));
    for i in 0..n_basis {
        let mut pts = Vec::with_capacity(ts.len());
        for &t in &ts {
            pts.push([t, basis_function_recursive(knots, i, degree, t)?]);
        }
        let label = format!("N{i},{degree}");
        fig.series.push(Series::nth(Some(&label), pts, i));
    }
    let ticks: Vec<[f64; 2]> = k.iter().map(|&t| [t, 0.0]).collect();
    fig.series
        .push(Series::new(None, ticks, Style::Ticks, "#000000"));
    Ok(fig)
}

/// A knot vector on a number line: one tick per knot, stacked by multiplicity.
#[must_use]
pub fn knots_figure(title: &str, knots: &KnotVector) -> Figure {
    let mut fig = Figure::new(title, false);
    fig.size = (640.0, 160.0);
    fig.axis_labels = ("t".into(), "mult.".into());
    let mut pts = Vec::new();
    for (t, m) in knots.distinct() {
        for j in 0..m {
            pts.push([t, j as f64 + 1.0]);
        }
    }
    let base: Vec<[f64; 2]> = knots.distinct().iter().map(|(t, _)| [*t, 0.0]).collect();
    fig.series
        .push(Series::new(None, base, Style::Line, "#888888"));
    fig.series
        .push(Series::new(None, pts, Style::Markers, PALETTE[0]));
    fig
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::CurveJson;

    #[test]
    fn legend_figures_have_four_significant_digits() {
        for (v, want) in [
            (0.118_924_521, "0.1189"),
            (0.039_569_3, "0.03957"),
            (1234.56, "1235"),
            (2.0, "2"),
            (0.0, "0"),
            (3.956_931_7e-7, "3.957e-7"),
            (1.5e300, "1.5e300"),
        ] {
            assert_eq!(fmt_legend(v), want, "{v}");
        }
    }

    #[test]
    fn residual_segments_join_points_to_their_feet() {
        let data = Points::from_2d(&[[0.0, 1.0], [1.0, -2.0], [2.0, 0.5]]).expect("points");
        let feet = Points::from_2d(&[[0.0, 0.0], [1.0, 0.0], [2.0, 0.0]]).expect("points");
        let s = residual_series(&data, &feet, &crate::Projection::default()).expect("series");
        assert_eq!(s.paths.len(), 3, "one segment a point");
        assert_eq!(s.paths[1], vec![[1.0, -2.0], [1.0, 0.0]], "point to foot");
        // max 2, RMS sqrt((1 + 4 + 0.25) / 3)
        assert_eq!(
            s.label.as_deref(),
            Some("deviations: max 2, RMS 1.323"),
            "legend"
        );
        let short = Points::from_2d(&[[0.0, 0.0]]).expect("points");
        assert!(
            residual_series(&data, &short, &crate::Projection::default()).is_err(),
            "counts differ"
        );
    }

    #[test]
    fn the_largest_residual_is_drawn_among_decimated_ones() {
        let n = 10_001;
        let data =
            Points::from_flat(2, (0..n).flat_map(|i| [i as f64, 1.0]).collect()).expect("points");
        let mut feet = data.as_slice().to_vec();
        for i in 0..n {
            feet[2 * i + 1] = if i == 4_567 { -9.0 } else { 0.0 };
        }
        let feet = Points::from_flat(2, feet).expect("points");
        let s = residual_series(&data, &feet, &crate::Projection::default()).expect("series");
        assert!(
            s.paths.len() <= PLOT_MAX_MARKERS + 1,
            "decimated: {}",
            s.paths.len()
        );
        assert!(
            s.paths.iter().any(|p| p[1] == [4_567.0, -9.0]),
            "the largest deviation is drawn"
        );
        assert_eq!(
            s.label
                .as_deref()
                .map(|l| l.starts_with("deviations: max 10,")),
            Some(true),
            "{:?}",
            s.label
        );
    }

    #[test]
    fn ticks_are_nice() {
        assert_eq!(
            nice_ticks(0.0, 1.0),
            vec![0.0, 0.2, 0.4, 0.6000000000000001, 0.8, 1.0]
        );
        assert_eq!(nice_ticks(-3.0, 3.0), vec![-2.0, 0.0, 2.0]);
        assert!(nice_ticks(1.0, 1.0).is_empty());
        assert_eq!(fmt_tick(0.6000000000000001), "0.6");
    }

    #[test]
    fn knot_and_curve_figures() {
        let kv = KnotVector::new(vec![0.0, 0.0, 0.0, 0.5, 0.5, 1.0, 1.0, 1.0]).unwrap();
        let fig = knots_figure("k", &kv);
        // one marker per knot, stacked by multiplicity: 0 three times, 0.5 twice
        let marks = &fig.series[1].paths[0];
        assert_eq!(marks.len(), 8);
        assert_eq!(marks[4], [0.5, 2.0]);
        let obj = Object::from_json_str(
            r#"{"lekalo":1,"type":"nurbs_curve","degree":2,"knots":[0,0,0,0.5,0.5,1,1,1],
               "control":[[1,0,0],[1,1,0],[0,1,0],[-1,1,0],[-1,0,0]],"weights":[1,0.5,1,0.5,1]}"#,
            "t",
        )
        .unwrap();
        let data = Points::from_3d(&[[1.0, 0.0, 0.0]]).unwrap();
        let fig = curve_figure(
            &obj,
            &CurvePlot {
                data_points: Some(&data),
                samples: 11,
                ..CurvePlot::default()
            },
        )
        .unwrap();
        assert!(!fig.axes, "no axes in a projected 3-D view");
        let labels: Vec<_> = fig.series.iter().filter_map(|s| s.label.clone()).collect();
        assert_eq!(
            labels,
            ["control polygon", "curve", "points at knots", "data points"]
        );
        // knot marks at the distinct knots 0, 0.5, 1 of the domain
        assert_eq!(fig.series[3].paths[0].len(), 3);
        assert_eq!(fig.series[2].paths[0].len(), 11);
        assert!(fig.to_svg().contains("NURBS curve of degree 2"));
    }

    #[test]
    fn basis_plot_of_the_lecture() {
        let kv = KnotVector::new(vec![0.0, 0.0, 1.0, 2.0, 3.0, 3.0]).unwrap();
        let fig = basis_figure(&kv, 2, 31).unwrap();
        // three basis functions, the knot ticks, the shaded domain [1, 2]
        assert_eq!(fig.series.len(), 4);
        assert_eq!(fig.band.as_ref().map(|b| (b.0, b.1)), Some((1.0, 2.0)));
        // N_{1,2}(1.5) = 3/4 (document 002, B-splines): sample 15 is t = 1.5
        assert_eq!(fig.series[1].paths[0][15], [1.5, 0.75]);
        let svg = fig.to_svg();
        assert!(svg.starts_with("<svg") && svg.ends_with("</svg>\n"));
        assert_eq!(svg.matches("<polyline").count(), 3);
        assert!(basis_figure(&kv, 5, 10).is_err());
        assert_eq!(escape("a<b & \"c\""), "a&lt;b &amp; &quot;c&quot;");
    }
}
