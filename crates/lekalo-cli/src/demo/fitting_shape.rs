//! Gallery: the shape constraints that the dose–response figure of `fitting.rs` leaves out —
//! decreasing, convex, concave on an interval, a value prescribed at a point and a bound at a
//! point — each beside the data and the unconstrained fit
//! (`docs/theory/fitting.md#shape-constraints`).

use anyhow::Result;
use lekalo::fit::{
    constrained_least_squares, least_squares, shape_violations, EndConstraints, FitData, Shape,
    ShapeConstraints,
};
use lekalo::BSplineCurve;
use lekalo_io::{Figure, Series, Style, PALETTE};

use crate::demo::{Caption, Section};

/// 40 samples of `f` on `[0, x_max]` with a fixed pseudo-noise of amplitude `noise`.
fn samples(x_max: f64, noise: f64, f: impl Fn(f64) -> f64) -> (Vec<f64>, Vec<f64>) {
    let x: Vec<f64> = (0..40).map(|k| x_max * f64::from(k) / 39.0).collect();
    let y = x
        .iter()
        .enumerate()
        .map(|(k, &t)| {
            #[allow(clippy::cast_precision_loss)]
            let e = noise * ((k as f64 * 0.618_033_988_7).fract() - 0.5);
            f(t) + e
        })
        .collect();
    (x, y)
}

/// One figure: the data, the least-squares fit with 12 cubic control points, and the same fit
/// under `rules` (labelled `kept_label`), with checks that the free fit breaks the rules and
/// the constrained one keeps them to 1e-12.
fn figure(
    s: &mut Section,
    (title, axes): (&str, (&str, &str)),
    (x, y): (&[f64], &[f64]),
    rules: &ShapeConstraints,
    kept_label: &str,
    caption: &str,
) -> Result<()> {
    let data = FitData::new(lekalo::PointsRef::from_flat(1, y)?, x)?;
    let (lo, hi) = (x[0], x[x.len() - 1]);
    let unit = lekalo::KnotVector::clamped_uniform(3, 12)?;
    let knots =
        lekalo::KnotVector::new(unit.as_slice().iter().map(|t| lo + (hi - lo) * t).collect())?;
    let free = least_squares(&data, 3, &knots, &EndConstraints::none())?;
    let kept = constrained_least_squares(&data, 3, &knots, rules)?;
    let broken = shape_violations(&free.curve, rules)?;
    let held = shape_violations(&kept.curve, rules)?;
    s.check(
        &format!("{title}: the unconstrained fit breaks a constraint (violation > 1e-3)"),
        f64::from(u8::from(broken.iter().any(|&v| v > 1e-3))),
        1.0,
        "1",
        0.0,
    );
    s.check(
        &format!("{title}: every constraint holds (largest violation)"),
        held.iter().fold(0.0_f64, |m, &v| m.max(v)),
        0.0,
        "0",
        1e-12,
    );
    let graph = |c: &BSplineCurve| -> Result<Vec<[f64; 2]>> {
        (0..=400)
            .map(|i| {
                let t = lo + (hi - lo) * f64::from(i) / 400.0;
                Ok([t, c.eval(t)?[0]])
            })
            .collect()
    };
    let mut fig = Figure::new(title, false);
    fig.axis_labels = (axes.0.into(), axes.1.into());
    let pts: Vec<[f64; 2]> = x.iter().zip(y).map(|(a, b)| [*a, *b]).collect();
    fig.series
        .push(Series::new(Some("data"), pts, Style::Dots, PALETTE[2]));
    fig.series.push(Series::new(
        Some("least squares"),
        graph(&free.curve)?,
        Style::Dashed,
        PALETTE[1],
    ));
    fig.series.push(Series::new(
        Some(kept_label),
        graph(&kept.curve)?,
        Style::Line,
        PALETTE[0],
    ));
    s.figure(
        fig,
        Caption::new(caption).theory("fitting.md#shape-constraints"),
    );
    Ok(())
}

/// Discount factors (decreasing, convex, equal to 1 at time 0) and a production curve
/// (increasing, concave on an interval, capped at one point).
pub(super) fn kinds(s: &mut Section) -> Result<()> {
    s.caption = "The other shape constraints, each figure with its noisy data (40 samples, \
        fixed pseudo-noise), the unconstrained least-squares cubic with 12 control points and \
        the same fit constrained: decreasing, convex and a value prescribed at a point; concave \
        on an interval and a bound at a single point. Each constraint holds for every x, checked \
        exactly span by span."
        .into();
    let (x, y) = samples(30.0, 0.05, |t| (-0.06 * t).exp());
    let rules = ShapeConstraints::new()
        .with(Shape::Decreasing)
        .with(Shape::Convex)
        .with_point(0.0, 0, 1.0);
    figure(
        s,
        (
            "Discount factors: decreasing, convex, 1 at time 0",
            ("years", "discount factor"),
        ),
        (&x, &y),
        &rules,
        "decreasing, convex, y(0) = 1",
        "Noisy discount factors (green dots), the unconstrained fit (orange, dashed), which \
         rises and bends the wrong way where the noise does and misses 1 at time 0, and the fit \
         constrained to decrease, to be convex and to start at 1 (blue).",
    )?;
    let (x, y) = samples(1.0, 0.12, |t| 1.0 - (1.0 - t).powi(3));
    let rules = ShapeConstraints::new()
        .with_on(Shape::Concave, 0.3, 1.0)
        .with_on(Shape::AtMost(0.6), 0.25, 0.25);
    figure(
        s,
        (
            "Output against input: concave on [0.3, 1], at most 0.6 at 0.25",
            ("input", "output"),
        ),
        (&x, &y),
        &rules,
        "concave on [0.3, 1], y(0.25) ≤ 0.6",
        "Noisy output of a process with diminishing returns (green dots), the unconstrained fit \
         (orange, dashed), and the fit constrained to be concave from 0.3 on and to stay at most \
         0.6 at input 0.25 (blue): the interval's end and the single point are where the fit \
         is asked, not knots.",
    )
}
