//! Checks of a written figure, as a reader would make them: every text and legend box inside
//! the canvas, no two legend entries overlapping, no NaN or infinite coordinate, every labelled
//! series visible (somewhere more than a line width away from the series drawn after it, or
//! declared coincident), and a rendered image that is not blank.
//!
//! The figures of [`crate::Figure::to_svg`] carry their layout as attributes (`data-bbox` on
//! texts and legend entries, `data-label` and `data-width` on series groups); texts are also
//! checked as laid out by the renderer with the system's fonts, where there are fonts.

use resvg::usvg::roxmltree::{Document, Node};

use crate::png::render_pixmap;

/// A series as drawn: label, line width, vertices, the label it is declared to coincide with.
/// A labelled series as drawn: label, line width, vertices, the series it declares it
/// coincides with, and whether it is drawn as lines (markers are separate points).
type SeriesSeen = (String, f64, Vec<[f64; 2]>, Option<String>, bool);

/// A box `x, y, width, height`.
type BoxXywh = [f64; 4];

fn parse_box(s: &str) -> Option<BoxXywh> {
    let v: Vec<f64> = s
        .split_whitespace()
        .filter_map(|x| x.parse().ok())
        .collect();
    (v.len() == 4).then(|| [v[0], v[1], v[2], v[3]])
}

/// Vertices of a series group's shapes, in page coordinates.
fn vertices(g: Node<'_, '_>) -> Vec<[f64; 2]> {
    let num = |n: Node<'_, '_>, a: &str| n.attribute(a).and_then(|v| v.parse::<f64>().ok());
    let mut out = Vec::new();
    for n in g.descendants().filter(Node::is_element) {
        match n.tag_name().name() {
            "polyline" | "polygon" => {
                let pts: Vec<[f64; 2]> = n
                    .attribute("points")
                    .unwrap_or_default()
                    .split_whitespace()
                    .filter_map(|p| {
                        let (x, y) = p.split_once(',')?;
                        Some([x.parse().ok()?, y.parse().ok()?])
                    })
                    .collect();
                if n.tag_name().name() == "polygon" && !pts.is_empty() {
                    // a marker: its centre
                    let k = pts.len() as f64;
                    let c = pts
                        .iter()
                        .fold([0.0, 0.0], |a, p| [a[0] + p[0], a[1] + p[1]]);
                    out.push([c[0] / k, c[1] / k]);
                } else {
                    out.extend(pts);
                }
            }
            "circle" => {
                if let (Some(x), Some(y)) = (num(n, "cx"), num(n, "cy")) {
                    out.push([x, y]);
                }
            }
            "rect" => {
                if let (Some(x), Some(y), Some(w), Some(h)) =
                    (num(n, "x"), num(n, "y"), num(n, "width"), num(n, "height"))
                {
                    out.push([x + w / 2.0, y + h / 2.0]);
                }
            }
            "line" => {
                for (a, b) in [("x1", "y1"), ("x2", "y2")] {
                    if let (Some(x), Some(y)) = (num(n, a), num(n, b)) {
                        out.push([x, y]);
                    }
                }
            }
            _ => {}
        }
    }
    out
}

/// Does every vertex of `a` lie within `tol` of the vertices of `b` or the segments between
/// consecutive vertices of `b`?
fn covered(a: &[[f64; 2]], b: &[[f64; 2]], b_is_line: bool, tol: f64) -> bool {
    let seg = |p: [f64; 2], u: [f64; 2], v: [f64; 2]| {
        let (dx, dy) = (v[0] - u[0], v[1] - u[1]);
        let l2 = dx * dx + dy * dy;
        let t = if l2 > 0.0 {
            (((p[0] - u[0]) * dx + (p[1] - u[1]) * dy) / l2).clamp(0.0, 1.0)
        } else {
            0.0
        };
        (p[0] - u[0] - t * dx).hypot(p[1] - u[1] - t * dy)
    };
    a.iter().all(|p| {
        b.iter().any(|q| (p[0] - q[0]).hypot(p[1] - q[1]) <= tol)
            || (b_is_line && b.windows(2).any(|w| seg(*p, w[0], w[1]) <= tol))
    })
}

/// The problems a reader would see in an SVG figure, one sentence each (empty: none).
/// `caption` is the text shown with the figure: a series hidden under another must be named
/// there as coinciding (`“label” coincides`), or, without a caption, marked by the writer
/// (`data-coincides`, drawn dashed).
#[must_use]
pub fn check_svg(svg: &str, caption: Option<&str>) -> Vec<String> {
    let mut problems = Vec::new();
    let doc = match Document::parse(svg) {
        Ok(d) => d,
        Err(e) => return vec![format!("not well-formed SVG: {e}")],
    };
    let root = doc.root_element();
    let dim = |a: &str| root.attribute(a).and_then(|v| v.parse::<f64>().ok());
    let (Some(w), Some(h)) = (dim("width"), dim("height")) else {
        return vec!["the <svg> has no numeric width and height".into()];
    };
    // no NaN or infinity in any attribute
    for n in doc.descendants().filter(Node::is_element) {
        for a in n.attributes() {
            let v = a.value().to_ascii_lowercase();
            if v.contains("nan") || v.contains("inf") {
                problems.push(format!(
                    "<{}> has {}=\"{}\"",
                    n.tag_name().name(),
                    a.name(),
                    a.value()
                ));
            }
        }
    }
    // text and legend boxes inside the canvas
    let eps = 0.5;
    let mut legend: Vec<(String, BoxXywh)> = Vec::new();
    for n in doc.descendants().filter(Node::is_element) {
        let Some(b) = n.attribute("data-bbox").and_then(parse_box) else {
            if n.tag_name().name() == "text" {
                problems.push(format!("text {:?} has no data-bbox", n.text()));
            }
            continue;
        };
        let what = n
            .text()
            .map(str::to_string)
            .or_else(|| {
                n.descendants()
                    .find(|d| d.tag_name().name() == "text")
                    .and_then(|t| t.text().map(str::to_string))
            })
            .unwrap_or_default();
        if b[0] < -eps || b[1] < -eps || b[0] + b[2] > w + eps || b[1] + b[3] > h + eps {
            problems.push(format!(
                "{} {what:?} at {:?} leaves the {w} × {h} canvas",
                n.tag_name().name(),
                b
            ));
        }
        if n.attribute("class") == Some("legend") {
            legend.push((what, b));
        }
    }
    for (i, (la, a)) in legend.iter().enumerate() {
        for (lb, b) in &legend[..i] {
            let overlap = a[0] < b[0] + b[2] - eps
                && b[0] < a[0] + a[2] - eps
                && a[1] < b[1] + b[3] - eps
                && b[1] < a[1] + a[3] - eps;
            if overlap {
                problems.push(format!("legend entries {lb:?} and {la:?} overlap"));
            }
        }
    }
    // every labelled series visible
    let series: Vec<SeriesSeen> = doc
        .descendants()
        .filter(|n| n.attribute("class") == Some("series"))
        .filter_map(|g| {
            let label = g.attribute("data-label").filter(|l| !l.is_empty())?;
            let width = g
                .attribute("data-width")
                .and_then(|v| v.parse().ok())
                .unwrap_or(2.0);
            Some((
                label.to_string(),
                width,
                vertices(g),
                g.attribute("data-coincides").map(str::to_string),
                g.descendants().any(|n| n.tag_name().name() == "polyline"),
            ))
        })
        .collect();
    for (i, (la, wa, va, _, _)) in series.iter().enumerate() {
        if va.is_empty() {
            problems.push(format!("series {la:?} draws nothing"));
            continue;
        }
        for (lb, wb, vb, declared, b_is_line) in &series[i + 1..] {
            if !covered(va, vb, *b_is_line, wa.max(*wb)) {
                continue;
            }
            let said = match caption {
                Some(c) => c.contains(&format!("“{lb}” coincides with “{la}”")),
                None => declared.as_deref() == Some(la.as_str()),
            };
            if !said {
                problems.push(format!(
                    "series {la:?} is hidden under {lb:?} and nothing says they coincide"
                ));
            }
        }
    }
    // the rendered image is not blank, and texts laid out with real fonts stay inside
    match render_pixmap(svg, 1.0) {
        Ok((pixmap, text_boxes)) => {
            let ink = pixmap
                .pixels()
                .iter()
                .filter(|p| p.red() < 230 || p.green() < 230 || p.blue() < 230)
                .count();
            let total = pixmap.pixels().len().max(1);
            if ink * 200 < total {
                problems.push(format!(
                    "the rendered image is blank ({ink} of {total} pixels drawn)"
                ));
            }
            for b in text_boxes {
                if b[0] < -1.0 || b[1] < -1.0 || b[0] + b[2] > w + 1.0 || b[1] + b[3] > h + 1.0 {
                    problems.push(format!("rendered text at {b:?} leaves the canvas"));
                }
            }
        }
        Err(e) => problems.push(format!("cannot render: {e}")),
    }
    problems
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::svg::{Figure, Series, Style};

    #[test]
    fn finds_what_a_reader_would() {
        let mut fig = Figure::new("t", true);
        let line = vec![[0.0, 0.0], [1.0, 1.0], [2.0, 0.0]];
        fig.series
            .push(Series::new(Some("a"), line.clone(), Style::Line, "#000"));
        fig.series.push(Series::new(
            Some("b"),
            vec![[0.0, 1.0], [2.0, 1.0]],
            Style::Line,
            "#00f",
        ));
        assert_eq!(check_svg(&fig.to_svg(), None), Vec::<String>::new());
        // a copy of "a" drawn over it: declared by the writer, and by a caption that says so
        fig.series
            .push(Series::new(Some("a again"), line, Style::Line, "#f00"));
        let svg = fig.to_svg();
        assert!(svg.contains(r#"data-coincides="a""#), "{svg}");
        assert_eq!(check_svg(&svg, None), Vec::<String>::new());
        let note = fig.coincidences()[0].note();
        assert!(
            note.starts_with("“a again” coincides with “a” (exactly)"),
            "{note}"
        );
        assert_eq!(check_svg(&svg, Some(&note)), Vec::<String>::new());
        let p = check_svg(&svg, Some("no note"));
        assert!(p[0].contains("hidden under"), "{p:?}");
        // a text off the canvas, a NaN, overlapping legend entries, a blank picture
        let bad = r##"<svg xmlns="http://www.w3.org/2000/svg" width="100" height="50"><rect width="100" height="50" fill="white"/><text x="90" y="20" data-bbox="90 10 40 14">long</text><line x1="NaN" y1="0" x2="1" y2="1"/><g class="legend" data-bbox="0 0 30 10"/><g class="legend" data-bbox="20 5 30 10"/></svg>"##;
        let p = check_svg(bad, None);
        assert!(
            p.iter().any(|m| m.contains("leaves the 100 × 50 canvas")),
            "{p:?}"
        );
        assert!(p.iter().any(|m| m.contains("x1=\"NaN\"")), "{p:?}");
        assert!(p.iter().any(|m| m.contains("overlap")), "{p:?}");
        let blank = r#"<svg xmlns="http://www.w3.org/2000/svg" width="100" height="50"><rect width="100" height="50" fill="white"/></svg>"#;
        assert!(check_svg(blank, None)[0].contains("blank"), "blank");
        assert!(!check_svg("<svg", None).is_empty(), "malformed");
    }
}
