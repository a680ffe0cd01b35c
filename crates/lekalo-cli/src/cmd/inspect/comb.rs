//! `lekalo plot --comb`: the curvature comb of a planar curve, from the library's curvature
//! vector (`QueryCurve::curvature_vector_at`, `docs/theory/queries.md#curvature`).

use anyhow::Result;
use lekalo_io::{Object, Series, Style};

use crate::cmd::measure::query_curve;
use crate::exit::bad_input;

/// Longest tooth, as a fraction of the larger side of the curve's bounding box.
const TOOTH: f64 = 0.2;

/// The comb's teeth (from the curve outward, away from the centre of curvature) and the line
/// through their ends, at `samples` parameters evenly spaced over the domain.
pub(crate) fn comb_series(
    obj: &Object,
    path: &std::path::Path,
    samples: usize,
) -> Result<Vec<Series>> {
    let q = query_curve(obj, path)?;
    if q.dim() != 2 {
        return bad_input(format!(
            "--comb draws planar curves; {} is {}-D",
            path.display(),
            q.dim()
        ));
    }
    let (a, b) = q.domain();
    let mut at = Vec::with_capacity(samples);
    for i in 0..samples {
        let t = a + (b - a) * i as f64 / (samples - 1) as f64;
        let p = q.point(t.min(b))?;
        at.push((p, q.curvature_vector_at(t.min(b))?));
    }
    let (lo, hi) = q.bounding_box();
    let size = (hi[0] - lo[0]).max(hi[1] - lo[1]);
    let kmax = at
        .iter()
        .filter_map(|(_, k)| k.as_ref())
        .map(|k| k[0].hypot(k[1]))
        .fold(0.0_f64, f64::max);
    let s = if kmax > 0.0 && size > 0.0 {
        TOOTH * size / kmax
    } else {
        0.0
    };
    let (mut teeth, mut ends) = (Vec::new(), Vec::new());
    for (p, k) in &at {
        let k = k.as_deref().unwrap_or(&[0.0, 0.0]);
        let end = [p[0] - s * k[0], p[1] - s * k[1]];
        teeth.push(vec![[p[0], p[1]], end]);
        ends.push(end);
    }
    let mut comb = Series::new(Some("curvature comb"), Vec::new(), Style::Line, "#9a9a9a");
    comb.paths = teeth;
    Ok(vec![comb, Series::new(None, ends, Style::Line, "#5f5f5f")])
}
