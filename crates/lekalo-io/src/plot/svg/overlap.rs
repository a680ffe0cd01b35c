//! Series that hide each other: the one-sided distance between two drawn series, and the
//! coincidences a figure's legend and caption must mention.

use super::figure::{Coincidence, Figure, Series, Style};
use super::page::Frame;

/// Distance from `p` to the segment `[a, b]`.
pub(super) fn seg_dist(p: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
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
pub(super) fn one_sided(a: &[Vec<[f64; 2]>], b: &[Vec<[f64; 2]>], lines: bool, stop: f64) -> f64 {
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

/// Does the segment `[a, b]` meet the box `[x0, y0, x1, y1]`? (Liang–Barsky clipping.)
pub(super) fn seg_hits_box(a: [f64; 2], b: [f64; 2], bx: [f64; 4]) -> bool {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let (mut t0, mut t1) = (0.0_f64, 1.0_f64);
    for (p, q) in [
        (-dx, a[0] - bx[0]),
        (dx, bx[2] - a[0]),
        (-dy, a[1] - bx[1]),
        (dy, bx[3] - a[1]),
    ] {
        if p == 0.0 {
            if q < 0.0 {
                return false;
            }
        } else {
            let r = q / p;
            if p < 0.0 {
                t0 = t0.max(r);
            } else {
                t1 = t1.min(r);
            }
        }
    }
    t0 <= t1
}

/// Bounding box `(xmin, xmax, ymin, ymax)` of paths.
pub(super) fn bbox(paths: &[Vec<[f64; 2]>]) -> (f64, f64, f64, f64) {
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
                let lines = !matches!(b.style, Style::Markers | Style::Dots);
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
    pub(super) fn hidden_pairs(&self, frame: &Frame) -> Vec<(usize, usize)> {
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
            Style::Markers | Style::Dots => Some(false),
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
}
