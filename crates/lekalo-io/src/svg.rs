//! SVG figures: a small plotting layer (axes, ticks, legend) and the standard lekalo plots —
//! a curve with its control polygon, data points and knot marks; B-spline basis functions; a
//! knot vector; a surface wireframe in a simple projection (see [`crate::wireframe`]).
//!
//! A [`Figure`] is data (series of polylines or markers in world coordinates); [`Figure::to_svg`]
//! maps it to the page. Figures are deterministic: the same input gives the same bytes.

use std::fmt::Write as _;

use lekalo::{basis::basis_function_recursive, KnotVector, Points};

use crate::object::Object;

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
        }
    }
}

/// A 2-D plot.
#[derive(Debug, Clone, PartialEq)]
pub struct Figure {
    /// Title above the plot.
    pub title: String,
    /// Width and height in pixels.
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
}

/// The palette of the plots (colour-blind safe, Okabe–Ito).
pub const PALETTE: [&str; 8] = [
    "#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#56B4E9", "#F0E442", "#000000",
];

const MARGIN_LEFT: f64 = 60.0;
const MARGIN_RIGHT: f64 = 20.0;
const MARGIN_TOP: f64 = 54.0;
const MARGIN_BOTTOM: f64 = 44.0;

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
        for p in self.series.iter().flat_map(|s| s.paths.iter().flatten()) {
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
        let fix = |lo: f64, hi: f64| {
            let span = hi - lo;
            let pad = if span > 0.0 {
                0.05 * span
            } else {
                0.5 * lo.abs().max(1.0)
            };
            (lo - pad, hi + pad)
        };
        let (x0, x1) = fix(b.0, b.1);
        let (y0, y1) = fix(b.2, b.3);
        (x0, x1, y0, y1)
    }

    /// The figure as a standalone SVG document.
    #[must_use]
    pub fn to_svg(&self) -> String {
        let (w, h) = self.size;
        let (mut x0, mut x1, mut y0, mut y1) = self.bounds();
        let pw = w - MARGIN_LEFT - MARGIN_RIGHT;
        let ph = h - MARGIN_TOP - MARGIN_BOTTOM;
        if self.equal_aspect {
            let sx = (x1 - x0) / pw;
            let sy = (y1 - y0) / ph;
            let s = sx.max(sy);
            let (cx, cy) = (0.5 * (x0 + x1), 0.5 * (y0 + y1));
            x0 = cx - 0.5 * s * pw;
            x1 = cx + 0.5 * s * pw;
            y0 = cy - 0.5 * s * ph;
            y1 = cy + 0.5 * s * ph;
        }
        let tx = |x: f64| MARGIN_LEFT + (x - x0) / (x1 - x0) * pw;
        let ty = |y: f64| MARGIN_TOP + (y1 - y) / (y1 - y0) * ph;
        let mut s = String::new();
        let _ = writeln!(
            s,
            r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}" font-family="DejaVu Sans, Arial, sans-serif" font-size="12">"#
        );
        let _ = writeln!(s, r#"<rect width="{w}" height="{h}" fill="white"/>"#);
        let _ = writeln!(
            s,
            r#"<text x="{}" y="22" text-anchor="middle" font-size="15">{}</text>"#,
            w / 2.0,
            escape(&self.title)
        );
        if let Some((a, b, label)) = &self.band {
            let _ = writeln!(
                s,
                r##"<rect x="{:.2}" y="{MARGIN_TOP}" width="{:.2}" height="{ph}" fill="#fff3c4"/><text x="{:.2}" y="{}" text-anchor="middle" fill="#8a6d00">{}</text>"##,
                tx(*a),
                tx(*b) - tx(*a),
                0.5 * (tx(*a) + tx(*b)),
                MARGIN_TOP + 14.0,
                escape(label)
            );
        }
        if self.axes {
            let _ = writeln!(
                s,
                r##"<rect x="{MARGIN_LEFT}" y="{MARGIN_TOP}" width="{pw}" height="{ph}" fill="none" stroke="#888"/>"##
            );
            for v in nice_ticks(x0, x1) {
                let x = tx(v);
                let _ = writeln!(
                    s,
                    r##"<line x1="{x:.2}" y1="{:.2}" x2="{x:.2}" y2="{:.2}" stroke="#888"/><text x="{x:.2}" y="{:.2}" text-anchor="middle">{}</text>"##,
                    MARGIN_TOP + ph,
                    MARGIN_TOP + ph + 5.0,
                    MARGIN_TOP + ph + 18.0,
                    fmt_tick(v)
                );
            }
            for v in nice_ticks(y0, y1) {
                let y = ty(v);
                let _ = writeln!(
                    s,
                    r##"<line x1="{:.2}" y1="{y:.2}" x2="{MARGIN_LEFT}" y2="{y:.2}" stroke="#888"/><text x="{:.2}" y="{:.2}" text-anchor="end">{}</text>"##,
                    MARGIN_LEFT - 5.0,
                    MARGIN_LEFT - 8.0,
                    y + 4.0,
                    fmt_tick(v)
                );
            }
            let (xl, yl) = &self.axis_labels;
            let _ = writeln!(
                s,
                r#"<text x="{:.2}" y="{:.2}" text-anchor="middle">{}</text><text x="14" y="{:.2}" text-anchor="middle" transform="rotate(-90 14 {:.2})">{}</text>"#,
                MARGIN_LEFT + pw / 2.0,
                h - 8.0,
                escape(xl),
                MARGIN_TOP + ph / 2.0,
                MARGIN_TOP + ph / 2.0,
                escape(yl)
            );
        }
        for series in &self.series {
            let c = &series.color;
            for path in &series.paths {
                match series.style {
                    Style::Line | Style::Dashed => {
                        let dash = if series.style == Style::Dashed {
                            r#" stroke-dasharray="6 4""#
                        } else {
                            ""
                        };
                        let pts: Vec<String> = path
                            .iter()
                            .map(|p| format!("{:.2},{:.2}", tx(p[0]), ty(p[1])))
                            .collect();
                        let _ = writeln!(
                            s,
                            r#"<polyline points="{}" fill="none" stroke="{c}" stroke-width="{}"{dash}/>"#,
                            pts.join(" "),
                            if series.style == Style::Line {
                                2.0
                            } else {
                                1.2
                            }
                        );
                    }
                    Style::Markers => {
                        for p in path {
                            let _ = writeln!(
                                s,
                                r#"<circle cx="{:.2}" cy="{:.2}" r="4" fill="white" stroke="{c}" stroke-width="1.8"/>"#,
                                tx(p[0]),
                                ty(p[1])
                            );
                        }
                    }
                    Style::Ticks => {
                        for p in path {
                            let (x, y) = (tx(p[0]), ty(p[1]));
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
        }
        // legend: one row in the top margin, under the title
        let mut x = MARGIN_LEFT;
        let y = MARGIN_TOP - 12.0;
        for series in self.series.iter().filter(|s| s.label.is_some()) {
            let label = series.label.as_deref().unwrap_or_default();
            let c = &series.color;
            match series.style {
                Style::Markers => {
                    let _ = writeln!(
                        s,
                        r#"<circle cx="{:.2}" cy="{y:.2}" r="4" fill="white" stroke="{c}" stroke-width="1.8"/>"#,
                        x + 10.0
                    );
                }
                _ => {
                    let dash = if series.style == Style::Dashed {
                        r#" stroke-dasharray="6 4""#
                    } else {
                        ""
                    };
                    let _ = writeln!(
                        s,
                        r#"<line x1="{x:.2}" y1="{y:.2}" x2="{:.2}" y2="{y:.2}" stroke="{c}" stroke-width="2"{dash}/>"#,
                        x + 20.0
                    );
                }
            }
            let _ = writeln!(
                s,
                r#"<text x="{:.2}" y="{:.2}">{}</text>"#,
                x + 26.0,
                y + 4.0,
                escape(label)
            );
            x += 40.0 + 7.0 * label.chars().count() as f64;
        }
        s.push_str("</svg>\n");
        s
    }
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
fn nice_ticks(lo: f64, hi: f64) -> Vec<f64> {
    let span = hi - lo;
    if span.is_nan() || span <= 0.0 || !span.is_finite() {
        return Vec::new();
    }
    let raw = span / 5.0;
    let mag = 10f64.powf(raw.log10().floor());
    let step = [1.0, 2.0, 5.0, 10.0]
        .iter()
        .map(|m| m * mag)
        .find(|s| *s >= raw)
        .unwrap_or(10.0 * mag);
    let first = (lo / step).ceil();
    let last = (hi / step).floor();
    let mut out = Vec::new();
    let mut k = first;
    while k <= last && out.len() < 50 {
        out.push(k * step);
        k += 1.0;
    }
    out
}

fn fmt_tick(v: f64) -> String {
    let r = (v * 1e9).round() / 1e9;
    let s = format!("{r}");
    if s == "-0" {
        "0".into()
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

/// Maps a point of any dimension to the plane: 1-D as `(index-free) (x, 0)`, 2-D as is, 3-D or
/// more through `projection` (first three coordinates).
fn to_plane(p: &[f64], projection: &crate::wireframe::Projection) -> [f64; 2] {
    match p.len() {
        1 => [p[0], 0.0],
        2 => [p[0], p[1]],
        _ => projection.project([p[0], p[1], p[2]]),
    }
}

/// Plot of a curve: the curve over its domain, its control polygon, knot marks and data points.
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
        let ctrl: Vec<[f64; 2]> = obj
            .control_points()
            .iter()
            .map(|p| to_plane(p, proj))
            .collect();
        fig.series.push(Series::new(
            Some("control polygon"),
            ctrl.clone(),
            Style::Dashed,
            "#777777",
        ));
        fig.series
            .push(Series::new(None, ctrl, Style::Markers, "#777777"));
    }
    fig.series
        .push(Series::new(Some("curve"), curve, Style::Line, PALETTE[0]));
    if opts.knot_marks {
        let (a, b) = obj.domain();
        let mut marks = Vec::new();
        for (t, _) in obj.knots().distinct() {
            if t >= a && t <= b {
                marks.push(to_plane(&obj.eval(t)?, proj));
            }
        }
        fig.series.push(Series::new(
            Some("points at knots"),
            marks,
            Style::Markers,
            PALETTE[1],
        ));
    }
    if let Some(data) = opts.data_points {
        let pts = data.iter().map(|p| to_plane(p, proj)).collect();
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
        fig.series.push(Series::new(
            Some(&label),
            pts,
            Style::Line,
            PALETTE[i % PALETTE.len()],
        ));
    }
    let ticks: Vec<[f64; 2]> = k.iter().map(|&t| [t, 0.0]).collect();
    fig.series
        .push(Series::new(None, ticks, Style::Ticks, "#000000"));
    if n_basis > 8 {
        // the legend would cover the plot
        for s in &mut fig.series {
            s.label = None;
        }
    }
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
