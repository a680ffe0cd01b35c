//! A figure as data: series of polylines, markers and faces in world coordinates, notes,
//! a colour bar.

use crate::palette::{look, Marker};

/// How a series is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Style {
    /// Solid polyline.
    Line,
    /// Dashed polyline (control polygons).
    Dashed,
    /// A marker at every point (data and control points).
    Markers,
    /// A small filled dot at every point: many data points under the curves fitted to them,
    /// drawn first so that the curves stay visible over them.
    Dots,
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
    pub(super) fn width(&self) -> f64 {
        match self.style {
            Style::Line | Style::Ticks => 2.0,
            Style::Dashed => 1.2,
            Style::Markers => 1.8,
            Style::Dots => 1.0,
        }
    }

    /// The dash pattern drawn ("" for solid).
    pub(super) fn dash_pattern(&self) -> &str {
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
}
