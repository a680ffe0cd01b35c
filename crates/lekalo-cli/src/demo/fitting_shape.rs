//! Gallery: the shape constraints that the dose–response figure of `fitting.rs` leaves out —
//! decreasing, convex, concave on an interval, a value prescribed at a point and a bound at a
//! point — each beside the data and the unconstrained fit
//! (`docs/theory/fitting.md#shape-constraints`); and a table z(u, v) fitted monotone in both
//! directions and bounded (`docs/theory/fitting.md#shape-constraints-of-surfaces`).

use anyhow::Result;
use lekalo::fit::{
    constrained_least_squares, constrained_surface_grid_least_squares, least_squares,
    shape_violations, surface_grid_least_squares_at, surface_shape_violations, EndConstraints,
    FitData, Shape, ShapeConstraints, SurfaceShape, SurfaceShapeConstraints,
};
use lekalo::{BSplineCurve, BSplineSurface, Direction, KnotVector, PointsRef};
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

/// A lookup table z(u, v) on a 25 × 5 grid (an efficiency map: rising fast in `u`, then
/// levelling off, scaled up by `v`, with fixed pseudo-noise), fitted by cubic × quadratic
/// least squares with 11 × 4 control points, free and constrained to rise in `u` and in `v` and
/// to stay in `[0, 1]`; drawn as sections at `v = 0` and `v = 1`.
pub(super) fn surfaces(s: &mut Section) -> Result<()> {
    s.caption = "A table z(u, v) that must rise in both variables and stay in [0, 1] (an \
        efficiency map: rising in speed u, then levelling off, higher at larger load v), noisy, \
        on a 25 × 5 grid. The unconstrained least-squares surface (cubic in u, quadratic in v, \
        11 × 4 control points) dips where the noise does, along u where the table is flat, \
        below 0 at its start and above 1 at its end; the constrained one keeps every condition at every (u, v), \
        checked exactly cell by cell. Drawn as sections at v = 0 and v = 1."
        .into();
    let (nu, nv) = (25_usize, 5_usize);
    let uu: Vec<f64> = (0..25_u32).map(|i| f64::from(i) / 24.0).collect();
    let vv: Vec<f64> = (0..5_u32).map(|j| f64::from(j) / 4.0).collect();
    let table = |u: f64, v: f64| (1.0 - (-4.0 * u).exp()) * (0.55 + 0.45 * v);
    let mut z = Vec::with_capacity(nu * nv);
    for (i, &u) in uu.iter().enumerate() {
        for (j, &v) in vv.iter().enumerate() {
            #[allow(clippy::cast_precision_loss)]
            let e = 0.16 * (((i * nv + j) as f64 * 0.618_033_988_7).fract() - 0.5);
            z.push(table(u, v) + e);
        }
    }
    let (ku, kv) = (
        KnotVector::clamped_uniform(3, 11)?,
        KnotVector::clamped_uniform(2, 4)?,
    );
    let rules = SurfaceShapeConstraints::new()
        .with(SurfaceShape::Increasing(Direction::U))
        .with(SurfaceShape::Increasing(Direction::V))
        .with(SurfaceShape::AtLeast(0.0))
        .with(SurfaceShape::AtMost(1.0));
    let values = PointsRef::from_flat(1, &z)?;
    let free = surface_grid_least_squares_at(values, (nu, nv), (3, 2), (&uu, &vv), (&ku, &kv))?;
    let kept = constrained_surface_grid_least_squares(
        values,
        (nu, nv),
        (3, 2),
        (&uu, &vv),
        (&ku, &kv),
        &rules,
    )?;
    let title = "Efficiency map: rising in u and v, within [0, 1]";
    s.check(
        &format!("{title}: the unconstrained fit breaks a constraint (violation > 1e-3)"),
        f64::from(u8::from(
            surface_shape_violations(&free, &rules)?
                .iter()
                .any(|&v| v > 1e-3),
        )),
        1.0,
        "1",
        0.0,
    );
    s.check(
        &format!("{title}: every constraint holds (largest violation)"),
        surface_shape_violations(&kept, &rules)?
            .iter()
            .fold(0.0_f64, |m, &v| m.max(v)),
        0.0,
        "0",
        1e-12,
    );
    let section = |f: &BSplineSurface, v: f64| -> Result<Vec<[f64; 2]>> {
        (0..=300)
            .map(|i| {
                let u = f64::from(i) / 300.0;
                Ok([u, f.eval(u, v)?[0]])
            })
            .collect()
    };
    let mut fig = Figure::new(title, false);
    fig.axis_labels = ("speed u".into(), "efficiency z".into());
    for (j, color) in [(0_usize, PALETTE[0]), (4, PALETTE[1])] {
        let v = vv[j];
        let pts: Vec<[f64; 2]> = uu
            .iter()
            .enumerate()
            .map(|(i, &u)| [u, z[i * nv + j]])
            .collect();
        fig.series.push(Series::new(
            Some(&format!("data, v = {v}")),
            pts,
            Style::Dots,
            color,
        ));
        fig.series.push(Series::new(
            Some(&format!("least squares, v = {v}")),
            section(&free, v)?,
            Style::Dashed,
            color,
        ));
        fig.series.push(Series::new(
            Some(&format!("rising, within [0, 1], v = {v}")),
            section(&kept, v)?,
            Style::Line,
            color,
        ));
    }
    s.figure(
        fig,
        Caption::new(
            "Sections of the table at v = 0 (blue) and v = 1 (vermillion): the noisy data \
             (dots), the unconstrained least-squares surface (dashed), which falls where the \
             table levels off, goes below 0 near u = 0 and above 1 near u = 1, and the surface \
             constrained to rise in u and in v and to stay within [0, 1] (solid).",
        )
        .theory("fitting.md#shape-constraints-of-surfaces"),
    );
    Ok(())
}
