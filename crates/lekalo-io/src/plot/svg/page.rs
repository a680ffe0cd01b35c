//! The page of a figure: margins and fonts, the world window of its data and the frame that
//! maps it to the page, with the room the legend and colour bar take.

use super::figure::Figure;
use super::ticks::{fmt_legend, fmt_tick, nice_ticks};
use crate::layout::{
    place_legend, text_width, LegendPlace, LEGEND_FONT, LEGEND_ROW, LEGEND_SAMPLE,
};

pub(super) const MARGIN_LEFT: f64 = 60.0;
pub(super) const MARGIN_RIGHT: f64 = 20.0;
pub(super) const MARGIN_TOP: f64 = 54.0;
pub(super) const MARGIN_BOTTOM: f64 = 44.0;
/// Baseline of the title.
pub(super) const TITLE_Y: f64 = 22.0;
pub(super) const TITLE_FONT: f64 = 15.0;
pub(super) const FONT: f64 = 12.0;
/// Centre line of the first legend row.
pub(super) const LEGEND_Y: f64 = 42.0;
/// Width of the colour bar's strip, pixels.
pub(super) const BAR: f64 = 14.0;

/// The page geometry of a figure: canvas, plot rectangle, world window, legend placement.
pub(super) struct Frame {
    pub(super) w: f64,
    pub(super) h: f64,
    pub(super) left: f64,
    pub(super) top: f64,
    pub(super) pw: f64,
    pub(super) ph: f64,
    pub(super) x0: f64,
    pub(super) x1: f64,
    pub(super) y0: f64,
    pub(super) y1: f64,
    /// Labelled series and their legend widths.
    pub(super) entries: Vec<(usize, f64)>,
    pub(super) legend: LegendPlace,
}

impl Frame {
    // differences taken of halves, so that data spanning ±1.8e308 does not overflow
    pub(super) fn tx(&self, x: f64) -> f64 {
        self.left + (x / 2.0 - self.x0 / 2.0) / (self.x1 / 2.0 - self.x0 / 2.0) * self.pw
    }

    pub(super) fn ty(&self, y: f64) -> f64 {
        self.top + (self.y1 / 2.0 - y / 2.0) / (self.y1 / 2.0 - self.y0 / 2.0) * self.ph
    }

    pub(super) fn page(&self, p: [f64; 2]) -> [f64; 2] {
        [self.tx(p[0]), self.ty(p[1])]
    }
}

impl Figure {
    /// Data bounds `(xmin, xmax, ymin, ymax)`, padded by 5 % and never degenerate.
    pub(super) fn bounds(&self) -> (f64, f64, f64, f64) {
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
    pub(super) fn colorbar_width(&self) -> f64 {
        self.colorbar.as_ref().map_or(0.0, |c| {
            let labels = nice_ticks(c.range.0, c.range.1)
                .into_iter()
                .map(|v| text_width(&fmt_tick(v), FONT))
                .chain(
                    [c.range.0, c.range.1]
                        .into_iter()
                        .map(|v| text_width(&fmt_legend(v), FONT)),
                )
                .chain([text_width(&c.label, FONT) - BAR - 6.0])
                .fold(0.0_f64, f64::max);
            20.0 + BAR + 6.0 + labels + 8.0
        })
    }

    /// Lays the figure out: margins grow to hold tick labels, the canvas grows to hold the
    /// title, the legend (rows above the plot, or a column beside it) and the colour bar; the
    /// plot keeps the size asked for in [`Figure::size`].
    pub(super) fn frame(&self) -> Frame {
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
}
