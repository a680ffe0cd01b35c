//! Gallery: document 002 (Hermite, the four-point cubic) and document 003 (quasi-interpolation
//! of x·cos x, pp-form ↔ B-spline).

use anyhow::Result;
use lekalo::{
    cubic_through_four_points, four_point_cubic_coefficients, quasi_interpolate,
    sample_quasi_interpolant, CubicHermite, Parametrization, PiecewisePolynomial, Points, PpSpace,
    TangentEstimate, TauRule, HERMITE_MATRIX,
};
use lekalo_io::{Figure, Marker, Object, Series, Style, PALETTE};

use super::doc000::{add_curve, add_points, show};
use crate::demo::{trim, Caption, Section};

/// Exact small rationals computed in floating point.
const EXACT: f64 = 1e-13;

pub(super) fn hermite(s: &mut Section) -> Result<()> {
    s.caption = "The lecture's cubic Hermite segment (§C.3): P(u) = [u³ u² u 1]·M_H·[p_k p_k+1 \
        Dp_k Dp_k+1]ᵀ with the Hermite matrix M_H as printed (the printed forward matrix has an \
        error in its last row). A Hermite spline through points with Catmull–Rom tangents; the \
        lecture's single cubic through four points at u = 0, 1/3, 2/3, 1 (§C.2), C = A⁻¹P."
        .into();
    s.check_all(
        "M_H (rows)",
        &HERMITE_MATRIX.concat(),
        &[
            2.0, -2.0, 1.0, 1.0, -3.0, 3.0, -2.0, -1.0, 0.0, 0.0, 1.0, 0.0, 1.0, 0.0, 0.0, 0.0,
        ],
        "[[2,−2,1,1],[−3,3,−2,−1],[0,0,1,0],[1,0,0,0]]",
        0.0,
    );
    // A⁻¹ column by column: the coefficients of the cubic through unit data
    let mut inv = [[0.0; 4]; 4];
    for (j, col) in (0..4).map(|j| {
        let mut e = vec![0.0; 4];
        e[j] = 1.0;
        (j, e)
    }) {
        let c = four_point_cubic_coefficients(Points::from_flat(1, col)?.as_view())?;
        for (i, row) in inv.iter_mut().enumerate() {
            row[j] = c.point(i)[0];
        }
    }
    s.check_all(
        "A⁻¹ (rows)",
        &inv.concat(),
        &[
            -4.5, 13.5, -13.5, 4.5, 9.0, -22.5, 18.0, -4.5, -5.5, 9.0, -4.5, 1.0, 1.0, 0.0, 0.0,
            0.0,
        ],
        "[[−9/2,27/2,−27/2,9/2],[9,−45/2,18,−9/2],[−11/2,9,−9/2,1],[1,0,0,0]]",
        EXACT,
    );
    let four = Points::from_2d(&[[0.0, 0.0], [1.0, 2.0], [3.0, 2.5], [4.0, 0.0]])?;
    let cubic = cubic_through_four_points(four.as_view())?;
    let mut dev = 0.0_f64;
    for (i, p) in four.iter().enumerate() {
        let q = cubic.eval(i as f64 / 3.0)?;
        dev = dev.max((q[0] - p[0]).hypot(q[1] - p[1]));
    }
    s.check("four-point cubic: max |p(i/3) − p_i|", dev, 0.0, "0", EXACT);
    let pts = Points::from_2d(&[[0.0, 0.0], [1.0, 2.0], [3.0, 2.5], [4.0, 0.5], [6.0, 1.0]])?;
    let h = CubicHermite::from_points(
        pts.as_view(),
        Parametrization::Uniform,
        TangentEstimate::CatmullRom,
    )?;
    let b = h.to_bspline();
    let mut dev = 0.0_f64;
    for (i, p) in pts.iter().enumerate() {
        let q = b.eval(h.params()[i])?;
        dev = dev.max((q[0] - p[0]).hypot(q[1] - p[1]));
    }
    s.check(
        "Catmull–Rom Hermite spline: max distance to the points",
        dev,
        0.0,
        "0",
        EXACT,
    );
    let mut fig = Figure::new("Hermite spline and the four-point cubic", true);
    fig.axis_labels = ("x".into(), "y".into());
    add_curve(
        &mut fig,
        &Object::BSpline(b),
        "Hermite, Catmull–Rom tangents",
        PALETTE[0],
    )?;
    add_curve(
        &mut fig,
        &Object::Bezier(cubic.clone()),
        "cubic through 4 points",
        PALETTE[1],
    )?;
    // squares under the Hermite data's circles: the three points the two share show both
    fig.series.push(Series {
        marker: Some(Marker::Square),
        ..Series::new(
            Some("four points"),
            four.iter().map(|p| [p[0], p[1]]).collect(),
            Style::Markers,
            PALETTE[1],
        )
    });
    // the Hermite data's circles over the squares: the square's corners show round them
    add_points(&mut fig, &pts, "Hermite data", PALETTE[2], false);
    s.tables.push((
        "The four-point cubic as a Bezier curve (computed)".into(),
        vec!["data".into(), "Bezier control points".into()],
        vec![vec![show(&four), show(cubic.control_points())]],
    ));
    s.figure(
        fig,
        Caption::new(
            "A C¹ cubic Hermite spline through five points with Catmull–Rom tangents (uniform \
             parameters), and the single cubic through four points taken at u = 0, 1/3, 2/3, 1. \
             The first three points are shared (orange squares \
             peeking out of green circles); between them the curves differ because the \
             Hermite spline chooses its tangents locally and the single cubic has none to choose.",
        )
        .theory("interpolation.md#hermite-splines-and-tangent-estimates"),
    );
    Ok(())
}

/// x·cos x and its derivatives (document 003's example).
fn xcosx(x: f64, r: usize) -> f64 {
    match r {
        0 => x * x.cos(),
        1 => x.cos() - x * x.sin(),
        2 => -2.0 * x.sin() - x * x.cos(),
        _ => -3.0 * x.cos() + x * x.sin(),
    }
}

pub(super) fn quasi(s: &mut Section) -> Result<()> {
    s.caption = "The thesis's practical task (§D.5): f(x) = x·cos x on [0, 3], breakpoints \
        0, 0.5, 0.9, 1.4, 2.1, 2.7, 3, C¹ quadratics (k = 3, ν = 2): the de Boor–Fix \
        coefficients c_i = λ_i f at points τ_i give the quasi-interpolant; the error is measured \
        on 60 intervals of 0.05. The rule τ_i = x_i (left end of the support) reproduces the \
        thesis's printed error 0.204831; the rule it states (first knot after x_i) gives less."
        .into();
    let xi = [0.0, 0.5, 0.9, 1.4, 2.1, 2.7, 3.0];
    let space = PpSpace::new(&xi, &[2; 5], 3)?;
    let mut rows = Vec::new();
    let mut fig = Figure::new("x·cos x and a quasi-interpolant (thesis Fig. 1)", false);
    fig.axis_labels = ("x".into(), "y".into());
    let rules = [
        ("first knot after x_i (stated)", TauRule::FirstKnotAfter),
        ("left end of support x_i", TauRule::LeftEndOfSupport),
        ("midpoint of support", TauRule::Midpoint),
        ("Greville abscissa", TauRule::Greville),
    ];
    let mut errors = Figure::new("The error q − f of each rule", false);
    errors.size = (640.0, 320.0);
    errors.axis_labels = ("x".into(), "q(x) − f(x)".into());
    for (n, (name, rule)) in rules.into_iter().enumerate() {
        let samples = sample_quasi_interpolant(&space, rule, xcosx, 60)?;
        let error: Vec<[f64; 2]> = samples
            .t
            .iter()
            .zip(samples.approx.iter().zip(&samples.exact))
            .map(|(t, (q, f))| [*t, q - f])
            .collect();
        let err = samples.max_error();
        if rule == TauRule::LeftEndOfSupport {
            s.check(
                "max error, τ_i = x_i (LeftEndOfSupport)",
                err,
                0.204831,
                "0.204831",
                5e-7,
            );
            let exact = samples
                .t
                .iter()
                .zip(&samples.exact)
                .map(|(t, y)| [*t, *y])
                .collect();
            fig.series.insert(
                0,
                Series::new(Some("f(x) = x·cos x"), exact, Style::Line, PALETTE[7]),
            );
        }
        let q = quasi_interpolate(&space, rule, xcosx)?;
        let tau = rule.points(space.knots(), 3)?;
        rows.push(vec![
            name.to_string(),
            tau.iter().map(|x| trim(*x)).collect::<Vec<_>>().join(", "),
            trim(err),
        ]);
        let graph: Vec<[f64; 2]> = samples
            .t
            .iter()
            .zip(&samples.approx)
            .map(|(t, y)| [*t, *y])
            .collect();
        let label = format!(
            "q, {}",
            [
                "τ = first knot after x_i",
                "τ = x_i",
                "τ = midpoint",
                "τ = Greville"
            ][n]
        );
        // beside f, only the rule that strays from it: the other three lie on f at this
        // scale, and the next figure draws every error
        if rule == TauRule::LeftEndOfSupport {
            fig.series
                .push(Series::new(Some(&label), graph, Style::Dashed, PALETTE[n]));
        }
        let mut e = Series::nth(Some(&label), error, n);
        e.dash = Some(["", "9 4", "2 3", "9 3 2 3"][n].to_string());
        errors.series.push(e);
        if rule == TauRule::FirstKnotAfter {
            s.check_all(
                "τ for the stated rule",
                &tau,
                &[0.5, 0.5, 0.5, 0.9, 1.4, 2.1, 2.7, 3.0],
                "0.5, 0.5, 0.5, 0.9, 1.4, 2.1, 2.7, 3",
                0.0,
            );
            // pp-form round trip: q → pp → B-spline on the same knots
            let pp = PiecewisePolynomial::from_bspline(&q)?;
            let back = pp.to_bspline(&space, TauRule::Midpoint)?;
            let dev = q
                .control_points()
                .as_slice()
                .iter()
                .zip(back.control_points().as_slice())
                .fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()));
            s.check(
                "B-spline → pp-form → B-spline: max coefficient change",
                dev,
                0.0,
                "0",
                EXACT,
            );
            s.check(
                "pp-form pieces",
                pp.n_pieces() as f64,
                6.0,
                "6 (l = 6 intervals)",
                0.0,
            );
        }
    }
    s.tables.push((
        "Quasi-interpolation of x·cos x by each τ rule (computed; 61 grid points)".into(),
        vec!["τ rule".into(), "τ_1 … τ_8".into(), "max |f − q|".into()],
        rows,
    ));
    s.figure(
        fig,
        Caption::new(
            "f(x) = x·cos x on [0, 3] (black) and its C¹ quadratic quasi-interpolant when the \
             de Boor–Fix functionals sample f at the left ends τ_i = x_i of the supports \
             (orange, dashed): it reproduces the thesis's error 0.204831 and strays visibly. The \
             three other rules for τ_i (the stated one, midpoints, Greville points) stay within \
             a line width of f over most of [0, 3] (their errors are in \
             the table below and in the next figure).",
        )
        .theory("pp.md#quasi-interpolation"),
    );
    // the zero line under the errors
    errors.series.insert(
        0,
        Series::new(
            None,
            vec![[xi[0], 0.0], [xi[xi.len() - 1], 0.0]],
            Style::Dashed,
            "#888888",
        ),
    );
    s.figure(
        errors,
        Caption::new(
            "The error q(x) − f(x) of the four quasi-interpolants, in the colours of the \
             previous figure, with the zero line. The rule τ_i = x_i (orange, dashed) errs by up \
             to 0.2; the stated rule (blue, solid) by about 0.05, most at x = 0; the midpoint \
             (green, dotted) and Greville (pink, dash-dotted) rules stay within a few \
             hundredths.",
        )
        .theory("pp.md#quasi-interpolation"),
    );
    Ok(())
}
