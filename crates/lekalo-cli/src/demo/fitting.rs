//! Gallery: fitting noisy points by least squares, a smoothing spline chosen by GCV, and a fit
//! within a tolerance (`docs/theory/fitting.md`).

use anyhow::Result;
use lekalo::fit::{
    constrained_least_squares, fit_tolerance, least_squares, place_knots, shape_violations,
    smoothing_spline, EndConstraints, FitData, Lambda, Shape, ShapeConstraints, ToleranceOptions,
};
use lekalo::{parametrize, Parametrization, Points};
use lekalo_io::{Figure, Object, Series, Style, PALETTE};

use super::doc000::add_curve;
use crate::demo::{trim, Caption, Section};

pub(super) fn fitting(s: &mut Section) -> Result<()> {
    s.caption = "60 noisy points near a spiral (fixed pseudo-noise of amplitude 0.03). Least \
        squares with 10 cubic control points (knots by P&T eq. 9.68–9.69, end points \
        interpolated exactly); the cubic smoothing spline with λ chosen by generalised \
        cross-validation; and the fewest control points found that keep every point within \
        0.02 of the curve (distance by closest-point projection)."
        .into();
    let pts: Vec<[f64; 2]> = (0..60)
        .map(|k| {
            let t = 5.0 * f64::from(k) / 59.0;
            let e = 0.03 * ((f64::from(k) * 0.618_033_988_7).fract() - 0.5);
            let r = 1.0 + 0.3 * t + e;
            [r * t.cos(), r * t.sin()]
        })
        .collect();
    let q = Points::from_2d(&pts)?;
    let u = parametrize(q.as_view(), Parametrization::ChordLength)?;
    let data = FitData::new(q.as_view(), &u)?;
    let lsq = least_squares(
        &data,
        3,
        &place_knots(&u, 3, 10)?,
        &EndConstraints::points(),
    )?;
    let smooth = smoothing_spline(&data, Lambda::Gcv)?;
    let tol = 0.02;
    let within = fit_tolerance(q.as_view(), &ToleranceOptions::new(3, tol))?;
    let n_tol = within.curve.control_points().len();
    // the data as small dots under the fit, so that the curve shows between and over them; at
    // the spiral's scale the three fits are one line (they differ by less than 0.01), so the
    // first figure draws one and the second shows how each departs from the data
    let mut fig = Figure::new("60 noisy points and a fit within 0.02", true);
    fig.axis_labels = ("x".into(), "y".into());
    fig.series.push(Series::new(
        Some("data"),
        pts.clone(),
        Style::Dots,
        PALETTE[2],
    ));
    add_curve(
        &mut fig,
        &Object::BSpline(within.curve.clone()),
        &format!("within {tol}: {n_tol} control points"),
        PALETTE[0],
    )?;
    s.figure(
        fig,
        Caption::new(format!(
            "Sixty noisy samples of a spiral (green dots) and the cubic B-spline with the fewest \
             control points, {n_tol}, that keeps every sample within {tol} of it (blue). At this \
             scale the least-squares and smoothing fits of the next figure lie on the same line."
        ))
        .theory("fitting.md#tolerance"),
    );
    // a distance per data point, drawn as what it is: a stem from 0 up to the distance at
    // each point (the three fits' stems side by side), not a line joining the points
    let mut res = Figure::new("How far each point lies from each fit", false);
    res.size = (960.0, 340.0);
    res.axis_labels = ("data point k".into(), "distance to the fit".into());
    for (i, (label, d)) in [
        (
            "least squares, 10 control points".to_string(),
            &lsq.report.residuals,
        ),
        (
            "smoothing spline (GCV)".to_string(),
            &smooth.report.residuals,
        ),
        (
            format!("within {tol}: {n_tol} control points"),
            &within.deviations,
        ),
    ]
    .into_iter()
    .enumerate()
    {
        res.series
            .push(stems(&label, d, STEM_SHIFT[i], PALETTE[[0, 1, 3][i]]));
    }
    res.series.push(Series::new(
        Some(&format!("tolerance {tol}")),
        vec![[-0.5, tol], [pts.len() as f64 - 0.5, tol]],
        Style::Dashed,
        "#777777",
    ));
    s.figure(
        res,
        Caption::new(
            "The distance from each data point to each fit, one stem per point and fit: least \
             squares (blue, left) and the smoothing spline (orange, middle) at the point's \
             parameter, the tolerance fit (pink, right) to its closest point. The grey dashed \
             line is the tolerance, which no pink stem passes; the heights are the noise, which \
             the fits follow more or less closely (table below).",
        )
        .theory("fitting.md#residuals"),
    );
    s.tables.push((
        "Residuals at the data parameters (tolerance fit: distance to the curve).".into(),
        vec![
            "fit".into(),
            "control points".into(),
            "max".into(),
            "RMS".into(),
        ],
        vec![
            vec![
                "least squares".into(),
                lsq.report.n_ctrl.to_string(),
                trim(lsq.report.max_residual),
                trim(lsq.report.rms),
            ],
            vec![
                format!("smoothing, λ = {:.3e}", smooth.report.lambda.unwrap_or(0.0)),
                smooth.report.n_ctrl.to_string(),
                trim(smooth.report.max_residual),
                trim(smooth.report.rms),
            ],
            vec![
                format!("tolerance {tol}"),
                n_tol.to_string(),
                trim(within.max_deviation),
                "".into(),
            ],
        ],
    ));
    // inequalities, checked as max(value, bound) = bound
    s.check(
        "tolerance fit: max deviation ≤ 0.02",
        within.max_deviation.max(tol),
        tol,
        "≤ 0.02",
        0.0,
    );
    let p0 = lsq.curve.eval(lsq.curve.domain().0)?;
    s.check(
        "least squares: C(a) = Q_0 (x)",
        p0[0],
        pts[0][0],
        &trim(pts[0][0]),
        1e-12,
    );
    Ok(())
}

/// Where the stems of the three fits stand beside their data point's index.
const STEM_SHIFT: [f64; 3] = [-0.27, 0.0, 0.27];

/// A stem plot: a vertical segment from 0 to `d[k]` at `k + shift` for every point `k`.
fn stems(label: &str, d: &[f64], shift: f64, color: &str) -> Series {
    let mut s = Series::new(Some(label), Vec::new(), Style::Line, color);
    s.paths = d
        .iter()
        .enumerate()
        .map(|(k, &v)| {
            let x = k as f64 + shift;
            vec![[x, 0.0], [x, v]]
        })
        .collect();
    s
}

/// A dose–response curve: noisy samples of a rising, saturating response between 0 and 1,
/// fitted by least squares with and without the constraints the quantity obeys.
pub(super) fn shape(s: &mut Section) -> Result<()> {
    s.caption = "40 noisy samples of a response that rises from 0 and saturates at 1 (fixed \
        pseudo-noise of amplitude 0.12). Least squares with 12 cubic control points follows the \
        noise: it dips and overshoots 1. The same fit constrained to increase and to stay in \
        [0, 1] on the whole domain (exact conditions per knot span, solved by Clarabel) keeps \
        the shape the quantity must have."
        .into();
    let x: Vec<f64> = (0..40).map(|k| f64::from(k) / 39.0).collect();
    let y: Vec<f64> = x
        .iter()
        .enumerate()
        .map(|(k, t)| {
            #[allow(clippy::cast_precision_loss)]
            let e = 0.12 * ((k as f64 * 0.618_033_988_7).fract() - 0.5);
            (1.0 - (-6.0 * t).exp()) + e
        })
        .collect();
    let data = FitData::new(lekalo::PointsRef::from_flat(1, &y)?, &x)?;
    let knots = lekalo::KnotVector::clamped_uniform(3, 12)?;
    let free = least_squares(&data, 3, &knots, &EndConstraints::none())?;
    let rules = ShapeConstraints::new()
        .with(Shape::Increasing)
        .with(Shape::AtLeast(0.0))
        .with(Shape::AtMost(1.0));
    let kept = constrained_least_squares(&data, 3, &knots, &rules)?;
    let broken = shape_violations(&free.curve, &rules)?;
    let held = shape_violations(&kept.curve, &rules)?;
    s.check(
        "unconstrained fit breaks the shape (largest violation > 0.01)",
        f64::from(u8::from(broken.iter().any(|&v| v > 0.01))),
        1.0,
        "1",
        0.0,
    );
    s.check(
        "constrained fit: every constraint holds (largest violation)",
        held.iter().fold(0.0_f64, |m, &v| m.max(v)),
        0.0,
        "0",
        1e-12,
    );
    let graph = |c: &lekalo::BSplineCurve| -> Result<Vec<[f64; 2]>> {
        (0..=400)
            .map(|i| {
                let t = f64::from(i) / 400.0;
                Ok([t, c.eval(t)?[0]])
            })
            .collect()
    };
    let mut fig = Figure::new(
        "A dose–response curve fitted with and without its shape",
        false,
    );
    fig.axis_labels = ("dose x".into(), "response y".into());
    let pts: Vec<[f64; 2]> = x.iter().zip(&y).map(|(a, b)| [*a, *b]).collect();
    fig.series
        .push(Series::new(Some("data"), pts, Style::Dots, PALETTE[2]));
    // the bounds, so that the overshoot of the free fit and the constrained one at 1 are seen
    for (label, v) in [(Some("bounds 0 and 1"), 0.0), (None, 1.0)] {
        let mut bound = Series::new(label, vec![[0.0, v], [1.0, v]], Style::Line, "#777777");
        bound.dash = Some("2 4".into());
        fig.series.push(bound);
    }
    fig.series.push(Series::new(
        Some("least squares"),
        graph(&free.curve)?,
        Style::Dashed,
        PALETTE[1],
    ));
    fig.series.push(Series::new(
        Some("increasing, in [0, 1]"),
        graph(&kept.curve)?,
        Style::Line,
        PALETTE[0],
    ));
    s.figure(
        fig,
        Caption::new(
            "Noisy samples (green dots), the unconstrained least-squares cubic with 12 control \
             points (orange, dashed), which falls where the noise falls and rises above the \
             bound 1 (grey, dotted), and the same fit constrained to increase and to stay between \
             0 and 1 (blue): the optimum of the constrained problem, exact on every span.",
        )
        .theory("fitting.md#shape-constraints"),
    );
    Ok(())
}
