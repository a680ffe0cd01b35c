//! Checks of a written figure, as a reader would make them: every text and legend box inside
//! the canvas, no two legend entries overlapping, no NaN or infinite coordinate, every labelled
//! series visible (a fair part of it showing past everything drawn after it, markers as well as
//! lines, unless declared coincident) and large enough to see (not every line under a pixel
//! and a half), no text on another text, a legend entry or a curve,
//! colour bars with labelled ends, axes with names, captions whose colour and dash words
//! describe the lines as drawn, and a rendered image that is not blank.
//!
//! The figures of [`crate::Figure::to_svg`] carry their layout as attributes (`data-bbox` on
//! texts and legend entries, `data-label` on series groups, classes `tick`, `note`,
//! `axis-label`, `frame` and `colorbar` with `data-bar`); texts are also checked as laid out by
//! the renderer with the system's fonts, where there are fonts. The shapes of series are read
//! from the SVG itself, in page coordinates (docs/formats.md, "the figure check").

use resvg::usvg::roxmltree::{Document, Node};

use crate::png::render_pixmap;

/// A box `x, y, width, height`.
type BoxXywh = [f64; 4];

fn parse_box(s: &str) -> Option<BoxXywh> {
    let v: Vec<f64> = s
        .split_whitespace()
        .filter_map(|x| x.parse().ok())
        .collect();
    (v.len() == 4).then(|| [v[0], v[1], v[2], v[3]])
}

/// A drawn shape that hides what lies under it: a stroke along a segment, or a disc (a marker),
/// with the distance from its centre line that it covers.
#[derive(Debug, Clone, Copy)]
enum Shape {
    /// Segment `a`–`b` and half its stroke width.
    Seg([f64; 2], [f64; 2], f64),
    /// Centre and radius (stroke included).
    Disc([f64; 2], f64),
}

impl Shape {
    /// Distance from `p` to the shape's centre line (or centre), and how far it covers.
    fn reach(&self, p: [f64; 2]) -> (f64, f64) {
        match *self {
            Shape::Seg(a, b, r) => (seg_dist(p, a, b), r),
            Shape::Disc(c, r) => ((p[0] - c[0]).hypot(p[1] - c[1]), r),
        }
    }

    fn bbox(&self) -> BoxXywh {
        match *self {
            Shape::Seg(a, b, r) => [
                a[0].min(b[0]) - r,
                a[1].min(b[1]) - r,
                (a[0] - b[0]).abs() + 2.0 * r,
                (a[1] - b[1]).abs() + 2.0 * r,
            ],
            Shape::Disc(c, r) => [c[0] - r, c[1] - r, 2.0 * r, 2.0 * r],
        }
    }
}

fn seg_dist(p: [f64; 2], u: [f64; 2], v: [f64; 2]) -> f64 {
    let (dx, dy) = (v[0] - u[0], v[1] - u[1]);
    let l2 = dx * dx + dy * dy;
    let t = if l2 > 0.0 {
        (((p[0] - u[0]) * dx + (p[1] - u[1]) * dy) / l2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (p[0] - u[0] - t * dx).hypot(p[1] - u[1] - t * dy)
}

/// A point a reader looks at: where, the half width of its line or the radius of its marker,
/// and whether it is a marker.
type Sample = ([f64; 2], f64, bool);

/// A series group as drawn: its shapes, the points a reader looks at along it (every 2 px of
/// its lines, the centre of each marker, with the marker's radius), its stroke colour and its
/// line style (`solid`, `dashed`, `dotted`, `dash-dotted`, or `markers`).
struct Drawn {
    label: String,
    shapes: Vec<Shape>,
    samples: Vec<Sample>,
    color: String,
    style: &'static str,
    coincides: Option<String>,
    /// The length of each line element (`polyline`, `line`), in page units.
    pieces: Vec<f64>,
    /// The radius of each marker, stroke included.
    radii: Vec<f64>,
}

/// The line style of a `stroke-dasharray`.
fn dash_kind(dash: Option<&str>) -> &'static str {
    let v: Vec<f64> = dash
        .unwrap_or_default()
        .split([' ', ','])
        .filter_map(|x| x.parse().ok())
        .collect();
    let dashes: Vec<f64> = v.iter().step_by(2).copied().collect();
    if dashes.is_empty() {
        "solid"
    } else if dashes.iter().all(|d| *d <= 3.0) {
        "dotted"
    } else if dashes.iter().any(|d| *d <= 3.0) {
        "dash-dotted"
    } else {
        "dashed"
    }
}

fn drawn(g: Node<'_, '_>) -> Drawn {
    let num = |n: Node<'_, '_>, a: &str| n.attribute(a).and_then(|v| v.parse::<f64>().ok());
    let points = |n: Node<'_, '_>| -> Vec<[f64; 2]> {
        n.attribute("points")
            .unwrap_or_default()
            .split_whitespace()
            .filter_map(|p| {
                let (x, y) = p.split_once(',')?;
                Some([x.parse().ok()?, y.parse().ok()?])
            })
            .collect()
    };
    let mut d = Drawn {
        label: g.attribute("data-label").unwrap_or_default().to_string(),
        shapes: Vec::new(),
        samples: Vec::new(),
        color: String::new(),
        style: "markers",
        coincides: g.attribute("data-coincides").map(str::to_string),
        pieces: Vec::new(),
        radii: Vec::new(),
    };
    let mut line_style = None;
    for n in g.descendants().filter(Node::is_element) {
        let sw = num(n, "stroke-width").unwrap_or(1.0);
        let mut segs: Vec<[[f64; 2]; 2]> = Vec::new();
        let mut disc = None;
        match n.tag_name().name() {
            "polyline" => {
                let p = points(n);
                segs.extend(p.windows(2).map(|w| [w[0], w[1]]));
                if p.len() == 1 {
                    segs.push([p[0], p[0]]);
                }
                line_style.get_or_insert(dash_kind(n.attribute("stroke-dasharray")));
            }
            "line" => {
                if let (Some(a), Some(b), Some(c), Some(e)) =
                    (num(n, "x1"), num(n, "y1"), num(n, "x2"), num(n, "y2"))
                {
                    segs.push([[a, b], [c, e]]);
                    line_style.get_or_insert(dash_kind(n.attribute("stroke-dasharray")));
                }
            }
            "circle" => {
                if let (Some(x), Some(y), Some(r)) = (num(n, "cx"), num(n, "cy"), num(n, "r")) {
                    disc = Some(([x, y], r + sw / 2.0));
                }
            }
            "rect" => {
                if let (Some(x), Some(y), Some(w), Some(h)) =
                    (num(n, "x"), num(n, "y"), num(n, "width"), num(n, "height"))
                {
                    disc = Some(([x + w / 2.0, y + h / 2.0], w.max(h) / 2.0 + sw / 2.0));
                }
            }
            "polygon" => {
                let p = points(n);
                if !p.is_empty() {
                    let k = p.len() as f64;
                    let c = p.iter().fold([0.0, 0.0], |a, q| [a[0] + q[0], a[1] + q[1]]);
                    let c = [c[0] / k, c[1] / k];
                    let r = p
                        .iter()
                        .map(|q| (q[0] - c[0]).hypot(q[1] - c[1]))
                        .fold(0.0, f64::max);
                    disc = Some((c, r + sw / 2.0));
                }
            }
            _ => continue,
        }
        if d.color.is_empty() {
            d.color = n.attribute("stroke").unwrap_or_default().to_string();
        }
        if !segs.is_empty() {
            d.pieces.push(
                segs.iter()
                    .map(|[a, b]| (b[0] - a[0]).hypot(b[1] - a[1]))
                    .sum(),
            );
        }
        for [a, b] in segs {
            d.shapes.push(Shape::Seg(a, b, sw / 2.0));
            let len = (b[0] - a[0]).hypot(b[1] - a[1]);
            let steps = (len / 2.0).ceil().max(1.0);
            // at most a few thousand samples a segment: the figures are a few hundred pixels
            let steps = steps.min(4096.0);
            let mut k = 0.0;
            while k < steps {
                let t = k / steps;
                d.samples.push((
                    [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])],
                    sw / 2.0,
                    false,
                ));
                k += 1.0;
            }
            d.samples.push((b, sw / 2.0, false));
        }
        if let Some((c, r)) = disc {
            d.radii.push(r);
            d.shapes.push(Shape::Disc(c, r));
            d.samples.push((c, r, true));
        }
    }
    if let Some(s) = line_style {
        d.style = s;
    }
    d
}

/// Shapes sorted into square cells, so that a point finds the shapes near it quickly.
struct ShapeGrid {
    cell: f64,
    cells: std::collections::HashMap<(i64, i64), Vec<Shape>>,
}

impl ShapeGrid {
    fn new(cell: f64) -> Self {
        ShapeGrid {
            cell,
            cells: std::collections::HashMap::new(),
        }
    }

    // page coordinates of a figure, far inside i64
    #[allow(clippy::cast_possible_truncation)]
    fn key(&self, x: f64, y: f64) -> (i64, i64) {
        (
            (x / self.cell).floor().clamp(-1e9, 1e9) as i64,
            (y / self.cell).floor().clamp(-1e9, 1e9) as i64,
        )
    }

    fn insert(&mut self, s: Shape) {
        let b = s.bbox();
        let (i0, j0) = self.key(b[0], b[1]);
        let (i1, j1) = self.key(b[0] + b[2], b[1] + b[3]);
        // a shape spans a few cells; a huge one (off the page) is clamped to 64 × 64
        for i in i0..=i1.min(i0 + 64) {
            for j in j0..=j1.min(j0 + 64) {
                self.cells.entry((i, j)).or_default().push(s);
            }
        }
    }

    /// Does a shape cover the sample `(p, r, marker)`? A marker of radius `r` counts as
    /// covered when less than half its radius shows past the shape's edge, a line of half
    /// width `r` when less than half of its half width does.
    fn covers(&self, (p, r, marker): Sample) -> bool {
        self.cells.get(&self.key(p[0], p[1])).is_some_and(|v| {
            v.iter().any(|s| {
                let (d, reach) = s.reach(p);
                if marker {
                    d + 0.5 * r <= reach
                } else {
                    d <= reach + 0.5 * r
                }
            })
        })
    }
}

/// Least share of a labelled series that must show past everything drawn after it.
const MIN_VISIBLE: f64 = 0.2;

/// Shortest line a reader sees as a line, and smallest marker radius a reader sees as a
/// marker, in page units (pixels at scale 1).
const MIN_PIECE: f64 = 1.5;
const MIN_RADIUS: f64 = 1.0;

/// Series too small to see: a labelled series whose every line is shorter than [`MIN_PIECE`]
/// (deviations of a fit drawn at scale, far under a pixel) and that has no marker of radius
/// [`MIN_RADIUS`] or more.
fn too_small(groups: &[Drawn], problems: &mut Vec<String>) {
    for g in groups {
        if g.label.is_empty() || (g.pieces.is_empty() && g.radii.is_empty()) {
            continue;
        }
        let longest = g.pieces.iter().copied().fold(0.0, f64::max);
        let largest = g.radii.iter().copied().fold(0.0, f64::max);
        if longest < MIN_PIECE && largest < MIN_RADIUS {
            let what = if g.radii.is_empty() {
                format!(
                    "its {} lines are all under {MIN_PIECE} px long (the longest {longest:.2} px)",
                    g.pieces.len()
                )
            } else {
                format!("its marks are all under {MIN_RADIUS} px across the radius and {MIN_PIECE} px along lines")
            };
            problems.push(format!(
                "series {:?} is too small to see: {what}; draw it stretched by a factor the legend names, or on its own scale",
                g.label
            ));
        }
    }
}

/// Does the caption say that `over` coincides with `hidden` (one sentence naming both, in
/// quotes, with the word "coincide")?
fn caption_says_coincide(caption: &str, over: &str, hidden: &str) -> bool {
    caption.split(". ").any(|sentence| {
        sentence.contains("coincide")
            && sentence.contains(&format!("“{over}”"))
            && sentence.contains(&format!("“{hidden}”"))
    })
}

/// Series hidden by what is drawn after them: a labelled series must show on at least
/// [`MIN_VISIBLE`] of its samples past the shapes of every later series, leaving out those
/// declared to coincide with it (they are drawn dashed over it).
fn hidden_series(groups: &[Drawn], caption: Option<&str>, problems: &mut Vec<String>) {
    for (i, a) in groups.iter().enumerate() {
        if a.label.is_empty() || a.samples.is_empty() {
            continue;
        }
        let mut grid = ShapeGrid::new(16.0);
        let mut over = Vec::new();
        for b in &groups[i + 1..] {
            let declared = !b.label.is_empty()
                && match caption {
                    Some(c) => caption_says_coincide(c, &b.label, &a.label),
                    None => b.coincides.as_deref() == Some(a.label.as_str()),
                };
            if declared {
                continue;
            }
            for s in &b.shapes {
                grid.insert(*s);
            }
            over.push(if b.label.is_empty() {
                "unlabelled marks".to_string()
            } else {
                format!("{:?}", b.label)
            });
        }
        if over.is_empty() {
            continue;
        }
        let seen = a.samples.iter().filter(|x| !grid.covers(**x)).count();
        let share = seen as f64 / a.samples.len() as f64;
        if share < MIN_VISIBLE {
            over.dedup();
            problems.push(format!(
                "series {:?} is hidden: {:.0} % of it shows past what is drawn over it ({})",
                a.label,
                100.0 * share,
                over.join(", ")
            ));
        }
    }
}

fn overlap(a: &BoxXywh, b: &BoxXywh, eps: f64) -> bool {
    a[0] < b[0] + b[2] - eps
        && b[0] < a[0] + a[2] - eps
        && a[1] < b[1] + b[3] - eps
        && b[1] < a[1] + a[3] - eps
}

/// Texts that overlap each other or a legend entry, and labels in the plot (class `note`)
/// that lie on a drawn series.
fn colliding_texts(
    texts: &[(String, BoxXywh, bool)],
    legend: &[(String, BoxXywh)],
    groups: &[Drawn],
    problems: &mut Vec<String>,
) {
    for (i, (ta, a, _)) in texts.iter().enumerate() {
        for (tb, b, _) in &texts[..i] {
            if overlap(a, b, 0.5) {
                problems.push(format!("texts {tb:?} and {ta:?} overlap"));
            }
        }
        for (lb, b) in legend {
            if overlap(a, b, 0.5) {
                problems.push(format!("text {ta:?} overlaps the legend entry {lb:?}"));
            }
        }
    }
    for (t, b, note) in texts {
        if !note {
            continue;
        }
        for g in groups {
            let hit = g.shapes.iter().any(|s| {
                let c = s.bbox();
                if !overlap(b, &c, 0.0) {
                    return false;
                }
                // the nearest point of the shape to the box: sample the box's inside
                let mut k = 0;
                let mut hit = false;
                while k < 49 && !hit {
                    let p = [
                        b[0] + b[2] * f64::from(k % 7) / 6.0,
                        b[1] + b[3] * f64::from(k / 7) / 6.0,
                    ];
                    let (d, reach) = s.reach(p);
                    hit = d <= reach.max(1.0);
                    k += 1;
                }
                hit
            });
            if hit {
                let what = if g.label.is_empty() {
                    "a series".to_string()
                } else {
                    format!("the series {:?}", g.label)
                };
                problems.push(format!("the label {t:?} lies on {what}"));
            }
        }
    }
}

/// A colour bar must carry a value at its top and at its bottom.
fn colorbar_ends(doc: &Document<'_>, problems: &mut Vec<String>) {
    for g in doc
        .descendants()
        .filter(|n| n.attribute("class") == Some("colorbar"))
    {
        let label = g.attribute("data-label").unwrap_or_default();
        let Some(bar) = g.attribute("data-bar").and_then(parse_box) else {
            problems.push(format!("the colour bar {label:?} has no data-bar"));
            continue;
        };
        let centres: Vec<f64> = g
            .descendants()
            .filter(|n| n.attribute("class") == Some("tick"))
            .filter_map(|n| n.attribute("data-bbox").and_then(parse_box))
            .map(|b| b[1] + b[3] / 2.0)
            .collect();
        for (end, y) in [("top", bar[1]), ("bottom", bar[1] + bar[3])] {
            // a label centred within half a line of the end's value
            if !centres.iter().any(|c| (c - y).abs() <= 9.0) {
                problems.push(format!(
                    "the colour bar {label:?} has no value at its {end}"
                ));
            }
        }
    }
}

/// A plot with a frame and ticks names both axes.
fn axis_labels(doc: &Document<'_>, problems: &mut Vec<String>) {
    if !doc
        .descendants()
        .any(|n| n.attribute("class") == Some("frame"))
    {
        return;
    }
    for axis in ["x", "y"] {
        let named = doc.descendants().any(|n| {
            n.attribute("class") == Some("axis-label")
                && n.attribute("data-axis") == Some(axis)
                && n.text().is_some_and(|t| !t.trim().is_empty())
        });
        if !named {
            problems.push(format!("the {axis} axis has no label"));
        }
    }
}

/// Words of line style in captions.
const DASH_WORDS: [&str; 4] = ["dash-dotted", "dashed", "dotted", "solid"];

/// A caption's colour and line-style words (`dashed purple`, `(grey, dashed)`, `orange`) must
/// each describe a series as drawn: some series of that colour (named by
/// [`crate::palette::color_names`]) and, if a style is said, of that style.
fn caption_styles(caption: &str, groups: &[Drawn], problems: &mut Vec<String>) {
    // the caption's prose: before the links and commands that follow it
    let prose = caption
        .split("<span")
        .next()
        .unwrap_or_default()
        .to_lowercase();
    // words, with their byte positions and the parenthesis depth they stand at
    let mut words: Vec<(usize, String, usize)> = Vec::new();
    let mut depth = 0_usize;
    let mut group = 0_usize;
    let mut groups_of = Vec::new();
    let mut cur = String::new();
    for (pos, ch) in prose.char_indices() {
        if ch.is_alphanumeric() || ch == '-' {
            cur.push(ch);
            continue;
        }
        if !cur.is_empty() {
            words.push((pos - cur.len(), std::mem::take(&mut cur), depth));
            groups_of.push(group);
        }
        match ch {
            '(' => {
                depth += 1;
                group += 1;
            }
            ')' => {
                depth = depth.saturating_sub(1);
                group += 1;
            }
            '.' | ';' | ',' | ':' if depth == 0 => group += 1,
            _ => {}
        }
    }
    if !cur.is_empty() {
        words.push((prose.len() - cur.len(), cur, depth));
        groups_of.push(group);
    }
    // colour terms (one or two words), longest first
    let mut colour_at: Vec<Option<&str>> = vec![None; words.len()];
    let mut used = vec![false; words.len()];
    for name in crate::palette::COLOR_WORDS {
        let parts: Vec<&str> = name.split(' ').collect();
        for k in 0..words.len() {
            let fits = (0..parts.len())
                .all(|j| k + j < words.len() && !used[k + j] && words[k + j].1 == parts[j]);
            if fits {
                colour_at[k] = Some(name);
                for j in 0..parts.len() {
                    used[k + j] = true;
                }
            }
        }
    }
    let dash_at: Vec<Option<&str>> = words
        .iter()
        .map(|(_, w, _)| DASH_WORDS.iter().copied().find(|d| d == w))
        .collect();
    // phrases: a colour with the style word just before or after it, or with the style words
    // of its parenthesis; a style word with neither
    let mut phrases: Vec<(Option<&str>, Option<&str>)> = Vec::new();
    let mut dash_used = vec![false; words.len()];
    for k in 0..words.len() {
        let Some(colour) = colour_at[k] else { continue };
        let mut dash = None;
        if k > 0 && dash_at[k - 1].is_some() && !dash_used[k - 1] {
            dash = dash_at[k - 1];
            dash_used[k - 1] = true;
        } else if k + 1 < words.len() && dash_at[k + 1].is_some() && colour_at[k + 1].is_none() {
            dash = dash_at[k + 1];
            dash_used[k + 1] = true;
        } else if words[k].2 > 0 {
            for j in 0..words.len() {
                if groups_of[j] == groups_of[k] && dash_at[j].is_some() && !dash_used[j] {
                    dash = dash_at[j];
                    dash_used[j] = true;
                }
            }
        }
        phrases.push((Some(colour), dash));
    }
    for k in 0..words.len() {
        if dash_at[k].is_some() && !dash_used[k] {
            phrases.push((None, dash_at[k]));
        }
    }
    for (colour, dash) in phrases {
        let fits = groups.iter().any(|g| {
            colour.is_none_or(|c| crate::palette::color_names(&g.color).contains(&c))
                && dash.is_none_or(|d| g.style == d || (d == "dashed" && g.style == "dash-dotted"))
        });
        if !fits {
            let said = [dash, colour]
                .into_iter()
                .flatten()
                .collect::<Vec<_>>()
                .join(" ");
            let drawn: Vec<String> = groups
                .iter()
                .filter(|g| !g.shapes.is_empty())
                .map(|g| {
                    let name = crate::palette::color_names(&g.color)
                        .first()
                        .copied()
                        .unwrap_or(g.color.as_str());
                    if g.label.is_empty() {
                        format!("{} {name}", g.style)
                    } else {
                        format!("{:?} {} {name}", g.label, g.style)
                    }
                })
                .collect();
            problems.push(format!(
                "the caption says {said:?} but no series is drawn so (drawn: {})",
                drawn.join("; ")
            ));
        }
    }
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
    let mut texts: Vec<(String, BoxXywh, bool)> = Vec::new();
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
        } else if n.tag_name().name() == "text"
            && !n
                .ancestors()
                .any(|g| g.attribute("class") == Some("legend"))
        {
            let note = n.attribute("class") == Some("note");
            texts.push((what, b, note));
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
    // and as a reader sees it: every series showing past what is drawn over it, no text on
    // another or on a curve, colour bars with their ends, axes with their names, captions
    // that describe the lines as drawn
    let groups: Vec<Drawn> = doc
        .descendants()
        .filter(|n| n.attribute("class") == Some("series"))
        .map(drawn)
        .collect();
    hidden_series(&groups, caption, &mut problems);
    too_small(&groups, &mut problems);
    colliding_texts(&texts, &legend, &groups, &mut problems);
    colorbar_ends(&doc, &mut problems);
    axis_labels(&doc, &mut problems);
    if let Some(c) = caption {
        caption_styles(c, &groups, &mut problems);
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
        fig.axis_labels = ("x".into(), "y".into());
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
        assert!(p[0].contains("series \"a\" is hidden"), "{p:?}");
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

    /// A figure with both axes named.
    fn named(title: &str, equal: bool) -> Figure {
        let mut fig = Figure::new(title, equal);
        fig.axis_labels = ("x".into(), "y".into());
        fig
    }

    fn has(problems: &[String], what: &str) -> bool {
        problems.iter().any(|p| p.contains(what))
    }

    #[test]
    fn a_series_under_a_pixel_is_too_small_to_see() {
        // a fit's deviations drawn at the data's scale: sticks of 1e-4 on a unit plot
        let y = |x: f64| 0.5 + 0.4 * (3.0 * x).sin();
        let curve: Vec<[f64; 2]> = (0..=100)
            .map(|k| [f64::from(k) / 100.0, y(f64::from(k) / 100.0)])
            .collect();
        let sticks = |scale: f64| -> Vec<Vec<[f64; 2]>> {
            (0..=20)
                .map(|k| {
                    let x = f64::from(k) / 20.0;
                    vec![[x, y(x)], [x, y(x) + scale * (7.0 * x).sin()]]
                })
                .collect()
        };
        let figure = |scale: f64| {
            let mut fig = named("residuals", false);
            fig.series.push(Series::new(
                Some("fit"),
                curve.clone(),
                Style::Line,
                "#0072B2",
            ));
            let mut dev = Series::new(Some("deviations"), Vec::new(), Style::Line, "#D55E00");
            dev.paths = sticks(scale);
            fig.series.push(dev);
            fig.to_svg()
        };
        let p = check_svg(&figure(1e-4), None);
        assert!(
            has(&p, "series \"deviations\" is too small to see"),
            "{p:?}"
        );
        assert!(!has(&p, "\"fit\" is too small"), "{p:?}");
        // stretched to be seen: no problem
        assert_eq!(check_svg(&figure(0.2), None), Vec::<String>::new());
    }

    #[test]
    fn markers_over_a_line_hide_it() {
        // sixty open markers along a line drawn before them cover it
        let line: Vec<[f64; 2]> = (0..=300).map(|k| [f64::from(k) / 300.0, 0.5]).collect();
        let data: Vec<[f64; 2]> = (0..60).map(|k| [f64::from(k) / 59.0, 0.5]).collect();
        let mut bad = named("fit", false);
        bad.series.push(Series::new(
            Some("fit"),
            line.clone(),
            Style::Line,
            "#0072B2",
        ));
        bad.series.push(Series::new(
            Some("data"),
            data.clone(),
            Style::Markers,
            "#009E73",
        ));
        let p = check_svg(&bad.to_svg(), None);
        assert!(has(&p, "series \"fit\" is hidden"), "{p:?}");
        // small dots first, the line over them: both show
        let mut good = named("fit", false);
        good.series
            .push(Series::new(Some("data"), data, Style::Dots, "#009E73"));
        good.series
            .push(Series::new(Some("fit"), line, Style::Line, "#0072B2"));
        assert_eq!(check_svg(&good.to_svg(), None), Vec::<String>::new());
    }

    #[test]
    fn texts_must_not_collide() {
        let svg = |y2: f64, note_y: f64| {
            format!(
                r##"<svg xmlns="http://www.w3.org/2000/svg" width="200" height="100"><rect width="200" height="100" fill="white"/><rect x="0" y="0" width="200" height="60" fill="#333"/><text class="tick" x="10" y="20" data-bbox="10 10 20 14">0</text><text class="tick" x="10" y="{y2}" data-bbox="10 {} 20 14">0.05</text><g class="legend" data-bbox="120 0 60 14"><text x="130" y="10" data-bbox="130 0 20 14">a</text></g><text class="note" x="100" y="{note_y}" data-bbox="100 {} 40 14">domain</text><g class="series" data-label="a" data-width="2"><polyline points="90,80 190,80" stroke="#000" stroke-width="2"/></g></svg>"##,
                y2 - 10.0,
                note_y - 10.0
            )
        };
        // tick labels 7 px apart in a 14 px box, a label on the curve
        let p = check_svg(&svg(27.0, 85.0), None);
        assert!(has(&p, "texts \"0\" and \"0.05\" overlap"), "{p:?}");
        assert!(
            has(&p, "the label \"domain\" lies on the series \"a\""),
            "{p:?}"
        );
        // a line apart, the label off the curve
        let p = check_svg(&svg(40.0, 60.0), None);
        assert!(!has(&p, "overlap") && !has(&p, "lies on"), "{p:?}");
        // a tick label under a legend entry
        let p = check_svg(&svg(40.0, 60.0).replace("120 0 60 14", "15 32 60 14"), None);
        assert!(has(&p, "overlaps the legend entry"), "{p:?}");
    }

    #[test]
    fn colour_bars_show_their_ends() {
        let mut fig = named("bar", true);
        fig.series.push(Series::new(
            Some("a"),
            vec![[0.0, 0.0], [1.0, 1.0]],
            Style::Line,
            "#0072B2",
        ));
        // a range whose ends are not round values
        fig.colorbar = Some(crate::svg::ColorBar {
            label: "K".into(),
            range: (-0.9731, 0.2519),
        });
        let svg = fig.to_svg();
        assert_eq!(check_svg(&svg, None), Vec::<String>::new());
        // the same bar with only its round values labelled
        let start = svg.find("<g class=\"colorbar\"").unwrap();
        let end = start + svg[start..].find("</g>").unwrap();
        let bar = &svg[start..end];
        let mut only_round = String::from(&svg[..start]);
        for l in bar.lines() {
            if !(l.contains("class=\"tick\"")
                && (l.contains(">0.2519<") || l.contains(">-0.9731<")))
            {
                only_round.push_str(l);
                only_round.push('\n');
            }
        }
        only_round.push_str(&svg[end..]);
        let p = check_svg(&only_round, None);
        assert!(has(&p, "no value at its top"), "{p:?}");
        assert!(has(&p, "no value at its bottom"), "{p:?}");
    }

    #[test]
    fn axes_are_named() {
        let mut fig = Figure::new("plain", false);
        fig.series.push(Series::new(
            Some("a"),
            vec![[0.0, 0.0], [1.0, 1.0]],
            Style::Line,
            "#0072B2",
        ));
        let p = check_svg(&fig.to_svg(), None);
        assert!(has(&p, "the x axis has no label"), "{p:?}");
        assert!(has(&p, "the y axis has no label"), "{p:?}");
        fig.axis_labels = ("t".into(), "N(t)".into());
        assert_eq!(check_svg(&fig.to_svg(), None), Vec::<String>::new());
        // a projected view has no frame and needs no names
        fig.axes = false;
        fig.axis_labels = (String::new(), String::new());
        assert_eq!(check_svg(&fig.to_svg(), None), Vec::<String>::new());
    }

    #[test]
    fn captions_name_colours_and_dashes_as_drawn() {
        let mut fig = named("styles", true);
        fig.series.push(Series::new(
            Some("curve"),
            vec![[0.0, 0.0], [1.0, 1.0]],
            Style::Line,
            "#0072B2",
        ));
        fig.series.push(Series::new(
            Some("full sum"),
            vec![[0.0, 1.0], [1.0, 0.0]],
            Style::Dashed,
            "#CC79A7",
        ));
        fig.series.push(Series::new(
            None,
            vec![[0.5, 0.2]],
            Style::Markers,
            "#777777",
        ));
        let svg = fig.to_svg();
        for bad in [
            "The curve (blue). The dashed purple curve is the full sum.",
            "The curve (green) and the full sum.",
            "The dotted pink curve is the full sum.",
            "The curve (blue, dashed).",
        ] {
            let p = check_svg(&svg, Some(bad));
            assert!(has(&p, "the caption says"), "{bad}: {p:?}");
        }
        for good in [
            "The curve (blue). The dashed pink curve is the full sum; a grey point.",
            "The curve (blue, solid) and the full sum (reddish purple, dashed).",
        ] {
            assert_eq!(check_svg(&svg, Some(good)), Vec::<String>::new(), "{good}");
        }
    }
}
