//! Gallery: fitting noisy points by least squares, a smoothing spline chosen by GCV, and a fit
//! within a tolerance (`docs/theory/fitting.md`).

use anyhow::Result;
use lekalo::fit::{
    fit_tolerance, least_squares, place_knots, smoothing_spline, EndConstraints, FitData, Lambda,
    ToleranceOptions,
};
use lekalo::{parametrize, Parametrization, Points};
use lekalo_io::{Figure, Object, PALETTE};

use super::doc000::{add_curve, add_points};
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
    let mut fig = Figure::new("fitting 60 noisy points", true);
    add_curve(
        &mut fig,
        &Object::BSpline(lsq.curve.clone()),
        "least squares, 10 control points",
        PALETTE[0],
    )?;
    add_curve(
        &mut fig,
        &Object::BSpline(smooth.curve.clone()),
        "smoothing spline (GCV)",
        PALETTE[1],
    )?;
    let n_tol = within.curve.control_points().len();
    add_curve(
        &mut fig,
        &Object::BSpline(within.curve.clone()),
        &format!("within {tol}: {n_tol} control points"),
        PALETTE[3],
    )?;
    // the data last, so that its markers are drawn over the curves that pass near them
    add_points(&mut fig, &q, "data", PALETTE[2], false);
    s.figure(
        fig,
        Caption::new(
            "Noisy samples of one curve fitted three ways: least squares with given knots, a \
             smoothing spline with λ chosen by generalised cross-validation, and the fewest \
             control points that stay within the tolerance. Compare how closely each follows the \
             noise and how many control points it needs (table below).",
        )
        .theory("fitting.md#tolerance"),
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
