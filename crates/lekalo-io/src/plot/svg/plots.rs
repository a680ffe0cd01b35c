//! The standard lekalo plots: a curve with its control polygon, data and knots; residuals;
//! the B-spline basis functions; a knot vector.

use lekalo::{basis::basis_functions_full_range, KnotVector, Points};

use super::figure::{Figure, Series, Style};
use super::ticks::fmt_legend;
use crate::object::Object;
use crate::palette::PALETTE;

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
pub(super) fn to_plane(p: &[f64], projection: &crate::wireframe::Projection) -> [f64; 2] {
    projection.to_plane(p)
}

/// Most vertices of a control polygon or data series drawn in a curve plot; beyond it every
/// k-th is drawn (first and last kept), as a picture cannot show more.
pub(crate) const PLOT_MAX_VERTICES: usize = 20_000;
/// Most markers (control points, points at knots, data points) drawn per series; beyond it the
/// markers are left out and the legend says so.
pub(crate) const PLOT_MAX_MARKERS: usize = 2_000;

/// Most data points drawn as open markers; more are drawn as small dots.
pub(crate) const MAX_OPEN_MARKERS: usize = 20;

/// Every k-th of `n` indices (first and last kept) so that at most `max` remain.
pub(super) fn decimated(n: usize, max: usize) -> impl Iterator<Item = usize> {
    let k = n.div_ceil(max.max(2) - 1).max(1);
    (0..n)
        .step_by(k)
        .chain((n > 0 && (n - 1) % k != 0).then_some(n - 1))
}

/// Plot of a curve: the curve over its domain, its control polygon, knot marks and data points
/// (drawn under the curve: open markers, or small dots beyond 20 points).
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
    if let Some(data) = opts.data_points {
        // under the curve, so that the curve shows over them; many as small dots, so that
        // they do not cover it between them
        let pts: Vec<[f64; 2]> = decimated(data.len(), PLOT_MAX_MARKERS)
            .map(|i| to_plane(data.point(i), proj))
            .collect();
        let style = if pts.len() > MAX_OPEN_MARKERS {
            Style::Dots
        } else {
            Style::Markers
        };
        fig.series
            .push(Series::new(Some("data points"), pts, style, PALETTE[2]));
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
            what: "closest points of the data points".into(),
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
    // Deviations far below the drawing's size would be shorter than a pixel: each segment is
    // then drawn from the foot towards its point stretched by a round factor (1, 2, 5 × 10^k)
    // that makes the largest about 5 % of the data's extent, and the legend says so.
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for i in 0..data.len() {
        let q = projection.to_plane(data.point(i));
        for c in 0..2 {
            lo[c] = lo[c].min(q[c]);
            hi[c] = hi[c].max(q[c]);
        }
    }
    let extent = (hi[0] - lo[0]).hypot(hi[1] - lo[1]);
    let stretch = deviation_stretch(max, extent);
    let label = if stretch > 1.0 {
        format!(
            "deviations (drawn ×{}): max {}, RMS {}",
            fmt_legend(stretch),
            fmt_legend(max),
            fmt_legend(rms)
        )
    } else {
        format!(
            "deviations: max {}, RMS {}",
            fmt_legend(max),
            fmt_legend(rms)
        )
    };
    let mut series = Series::new(Some(&label), Vec::new(), Style::Line, PALETTE[3]);
    series.paths = drawn
        .into_iter()
        .map(|i| {
            let (q, f) = (data.point(i), feet.point(i));
            let tip: Vec<f64> = q
                .iter()
                .zip(f)
                .map(|(q, f)| f + stretch * (q - f))
                .collect();
            vec![projection.to_plane(&tip), projection.to_plane(f)]
        })
        .collect();
    Ok(series)
}

/// The round factor (1, 2 or 5 times a power of ten, at least 1) that makes a largest deviation
/// `max` about 5 % of a drawing of size `extent`.
pub(super) fn deviation_stretch(max: f64, extent: f64) -> f64 {
    if !(max > 0.0 && extent.is_finite() && extent > 0.0) || max >= 0.02 * extent {
        return 1.0;
    }
    let want = 0.05 * extent / max;
    let p = 10f64.powf(want.log10().floor());
    let f = [5.0, 2.0, 1.0]
        .into_iter()
        .map(|m| m * p)
        .find(|&f| f <= want)
        .unwrap_or(p);
    f.max(1.0)
}

/// Graphs of the B-spline basis functions `N_{i,p}(t)`, `i = 0 … n`, over the whole knot range
/// `[t_0, t_m]` by the Cox–de Boor table ([`basis_functions_full_range`]; document 002, B-splines;
/// P&T eq. 2.5), with the valid
/// domain `[t_p, t_{n+1}]` shaded (there, and only there, `Σ N_{i,p} = 1`). Each function is
/// drawn over its support, the zero line once; the domain's label stands where no graph is.
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
    let mut graphs = vec![Vec::with_capacity(ts.len()); n_basis];
    for &t in &ts {
        for (graph, v) in graphs
            .iter_mut()
            .zip(basis_functions_full_range(knots, degree, t)?)
        {
            graph.push([t, v]);
        }
    }
    for (i, pts) in graphs.into_iter().enumerate() {
        let label = format!("N{i},{degree}");
        // each function over its support, from and back to the axis: the zero line they all
        // share outside it is drawn once, under none of them
        let first = pts.iter().position(|p| p[1] != 0.0).unwrap_or(0);
        let last = pts
            .iter()
            .rposition(|p| p[1] != 0.0)
            .unwrap_or(pts.len() - 1);
        let own = pts[first.saturating_sub(1)..=(last + 1).min(pts.len() - 1)].to_vec();
        fig.series.push(Series::nth(Some(&label), own, i));
    }
    let mut axis = Series::new(None, vec![[lo, 0.0], [hi, 0.0]], Style::Dashed, "#888888");
    axis.dash = Some(String::new());
    fig.series.push(axis);
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
