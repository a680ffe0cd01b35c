//! Gallery: document 001, polynomial deformation of curves (docs/theory/blending.md).

use anyhow::Result;
use lekalo::{
    smooth_polyline_corners, ArcParametrization, BlendSpline, BlendSplineOptions, CircularArcs,
    Continuity, CornerWindow, Deformation, JumpPolynomial, NurbsCurve, Parabolas, ParametricCurve,
    Points,
};
use lekalo_io::{Figure, Object, Series, PALETTE};

use super::doc000::{add_curve, add_points};
use crate::demo::{trim, Caption, Section};

/// Differences of derivatives that agree in exact arithmetic (values O(1)–O(10)).
const ROUNDING: f64 = 1e-10;

pub(super) fn jump(s: &mut Section) -> Result<()> {
    s.caption = "The jump-smoothing polynomials w_k(u) = Σ_{i=k+1}^{2k+1} b_{2k+1,i}(u) (§B.1): \
        Bezier ordinates k + 1 zeros then k + 1 ones, degree 2k + 1. Their derivatives up to \
        order k vanish at both ends, the (k+1)-th does not; ∫_0^{1/2} w_k → 0 (Property 3), so \
        w_k tends to the step function; w_k minimises the energy J_{k+1} (Property 4)."
        .into();
    let mut fig = Figure::new("Jump-smoothing polynomials w_0 … w_5", false);
    fig.axis_labels = ("u".into(), "w_k(u)".into());
    let mut rows = Vec::new();
    let derivs = [1.0, 6.0, 60.0, 840.0, 15120.0, 332640.0];
    let halves = [
        (1.0 / 8.0, "1/8"),
        (3.0 / 32.0, "3/32"),
        (5.0 / 64.0, "5/64"),
        (35.0 / 512.0, "35/512"),
        (63.0 / 1024.0, "63/1024"),
        (231.0 / 4096.0, "231/4096"),
    ];
    let energies = ["1", "12", "720", "100800"];
    for k in 0..=5 {
        let w = JumpPolynomial::new(k)?;
        let mut line = Vec::new();
        for j in 0..=200 {
            let u = f64::from(j) / 200.0;
            line.push([u, w.eval(u)?]);
        }
        fig.series
            .push(Series::nth(Some(&format!("w_{k}")), line, k));
        let mut d0 = vec![0.0; k + 2];
        let mut d1 = vec![0.0; k + 2];
        w.eval_derivatives(0.0, &mut d0)?;
        w.eval_derivatives(1.0, &mut d1)?;
        let low = d0[1..=k]
            .iter()
            .chain(&d1[1..=k])
            .fold(0.0_f64, |m, x| m.max(x.abs()));
        let sign = if k % 2 == 0 { 1.0 } else { -1.0 };
        s.check_all(
            &format!("w_{k}^({})(0), w_{k}^({})(1)", k + 1, k + 1),
            &[d0[k + 1], d1[k + 1]],
            &[derivs[k], sign * derivs[k]],
            &format!("{}, {}", derivs[k], sign * derivs[k]),
            ROUNDING * derivs[k],
        );
        s.check(
            &format!("w_{k}: max |w^(l)| at the ends, l = 1..k"),
            low,
            0.0,
            "0",
            ROUNDING * derivs[k],
        );
        let half = w.integral_to_half_f64();
        s.check(
            &format!("∫_0^1/2 w_{k}"),
            half,
            halves[k].0,
            halves[k].1,
            1e-15,
        );
        let energy = w.energy().to_string();
        if let Some(e) = energies.get(k) {
            s.checks.push(crate::demo::Check {
                what: format!("J_{}(w_{k})", k + 1),
                ours: energy.clone(),
                expected: (*e).to_string(),
                ok: energy == *e,
            });
        }
        rows.push(vec![
            k.to_string(),
            w.degree().to_string(),
            format!("{}, {}", trim(d0[k + 1]), trim(d1[k + 1])),
            trim(half),
            energy,
        ]);
    }
    s.tables.push((
        "w_k computed by lekalo (exact integers for J)".into(),
        vec![
            "k".into(),
            "degree".into(),
            "w^(k+1)(0), w^(k+1)(1)".into(),
            "∫_0^1/2 w_k".into(),
            "J_(k+1)(w_k)".into(),
        ],
        rows,
    ));
    s.figure(
        fig,
        Caption::new(
            "The jump-smoothing polynomials w_0 … w_5 on [0, 1] (document 001, Fig. 1): w_k \
             rises from 0 to 1 with its first k derivatives zero at both ends. As k grows the \
             rise gathers at u = 1/2 and w_k tends to the unit step.",
        )
        .theory("blending.md#jump-smoothing-polynomials"),
    );
    Ok(())
}

pub(super) fn deformation(s: &mut Section) -> Result<()> {
    s.caption = "Deformation of two circular arcs with common end points (§B.2): \
        p(u) = (1 − w_{k−1}(u)) p_1(u) + w_{k−1}(u) p_2(u) has contact of order k with p_1 at \
        u = 0 and with p_2 at u = 1. The arcs are rational quadratics, so p is exactly a \
        rational Bezier curve of degree (2k − 1) + 2 + 2."
        .into();
    let a1 = NurbsCurve::arc_through_points(&[0.0, 0.0], &[1.0, 0.4], &[2.0, 0.0])?;
    let a2 = NurbsCurve::arc_through_points(&[0.0, 0.0], &[1.0, -0.35], &[2.0, 0.0])?;
    let mut fig = Figure::new("Deformation of an arc into another arc", true);
    fig.axis_labels = ("x".into(), "y".into());
    add_curve(
        &mut fig,
        &Object::Nurbs(a1.clone()),
        "upper arc p1",
        "#777777",
    )?;
    add_curve(
        &mut fig,
        &Object::Nurbs(a2.clone()),
        "lower arc p2",
        "#AAAAAA",
    )?;
    let mut rows = Vec::new();
    for k in 1..=3 {
        let d = Deformation::new(&a1, &a2, k)?;
        let exact = d.to_nurbs()?;
        s.check(
            &format!("k = {k}: degree of the exact NURBS"),
            exact.degree() as f64,
            (2 * k - 1 + 4) as f64,
            &format!("(2k − 1) + 4 = {}", 2 * k - 1 + 4),
            0.0,
        );
        // contact of order k: derivatives of p and p_1 at 0, of p and p_2 at 1
        let dp0 = d.eval_derivatives(0.0, k)?;
        let dp1 = d.eval_derivatives(1.0, k)?;
        let mut e1 = vec![0.0; (k + 1) * 2];
        let mut e2 = vec![0.0; (k + 1) * 2];
        a1.eval_derivatives_into(0.0, k, &mut e1)?;
        a2.eval_derivatives_into(1.0, k, &mut e2)?;
        let dev = dp0
            .as_slice()
            .iter()
            .zip(&e1)
            .chain(dp1.as_slice().iter().zip(&e2))
            .fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()));
        s.check(
            &format!("k = {k}: contact, max |p^(l) − p_i^(l)|, l ≤ k"),
            dev,
            0.0,
            "0",
            ROUNDING,
        );
        let mid = d.eval(0.5)?;
        let mid_exact = exact.eval(0.5)?;
        rows.push(vec![
            k.to_string(),
            exact.degree().to_string(),
            format!("({}, {})", trim(mid[0]), trim(mid[1])),
            format!(
                "{:.1e}",
                (mid[0] - mid_exact[0]).hypot(mid[1] - mid_exact[1])
            ),
        ]);
        add_curve(
            &mut fig,
            &Object::Nurbs(exact),
            &format!("p, k = {k}"),
            PALETTE[k - 1],
        )?;
    }
    s.tables.push((
        "Deformations (computed)".into(),
        vec![
            "k".into(),
            "NURBS degree".into(),
            "p(1/2)".into(),
            "|p(1/2) − NURBS(1/2)|".into(),
        ],
        rows,
    ));
    s.figure(
        fig,
        Caption::new(
            "An upper circular arc deformed into a lower one through the same end points (0, 0) \
             and (2, 0): p = (1 − w_{k−1}) p1 + w_{k−1} p2 for k = 1, 2, 3. Each blend starts \
             along the upper arc and ends along the lower one, and the larger k, the longer it \
             hugs each arc (contact of order k) and the steeper it crosses between them.",
        )
        .theory("blending.md#deformation-of-curves"),
    );
    Ok(())
}

/// Points of the spline examples.
fn spline_points() -> Result<Points> {
    Ok(Points::from_2d(&[
        [0.0, 0.0],
        [1.0, 2.0],
        [3.0, 2.5],
        [4.0, 0.5],
        [6.0, 1.0],
        [7.0, 3.0],
    ])?)
}

/// Largest jump of derivatives of order 1..=k between consecutive segments, in the global
/// parameter (segment i spans `[s_i, s_{i+1}]`; local derivatives scale by `1/Δ_i^l`).
fn join_jump(sp: &BlendSpline, k: usize) -> Result<f64> {
    let s = sp.parameters();
    let mut worst = 0.0_f64;
    for i in 0..sp.segment_count().saturating_sub(1) {
        let a = sp.segment_derivatives(i, 1.0, k)?;
        let b = sp.segment_derivatives(i + 1, 0.0, k)?;
        let (da, db) = (s[i + 1] - s[i], s[i + 2] - s[i + 1]);
        for l in 1..=k {
            let exp = i32::try_from(l).unwrap_or(i32::MAX);
            for (x, y) in a.point(l).iter().zip(b.point(l)) {
                let scale = 1.0 + x.abs().max(y.abs());
                worst = worst.max((x / da.powi(exp) - y / db.powi(exp)).abs() / scale);
            }
        }
    }
    Ok(worst)
}

pub(super) fn spline(s: &mut Section) -> Result<()> {
    s.caption = "A spline through points by blending local three-point curves (§B.3): segment i \
        deforms the curve through P_{i−1}, P_i, P_{i+1} into the one through P_i, P_{i+1}, \
        P_{i+2} with w_{k−1}. Parabolas give C^k in the parameter and an exact NURBS of degree \
        2k + 1; circular arcs (the document's example) give G^k; closed curves use cyclic \
        indices."
        .into();
    let pts = spline_points()?;
    let mut fig = Figure::new("Open splines by blended arcs and parabolas, k = 2", true);
    fig.axis_labels = ("x".into(), "y".into());
    let mut closed_fig = None;
    let mut rows = Vec::new();
    let arcs = CircularArcs::new(ArcParametrization::UniformAngle);
    let rational = CircularArcs::new(ArcParametrization::RationalQuadratic);
    let cases: [(&str, &dyn lekalo::LocalCurves, bool); 4] = [
        ("parabolas, open", &Parabolas, false),
        ("arcs, open", &arcs, false),
        ("rational arcs, open", &rational, false),
        ("parabolas, closed", &Parabolas, true),
    ];
    for (n, (name, local, closed)) in cases.into_iter().enumerate() {
        let opts = BlendSplineOptions {
            continuity: 2,
            closed,
            ..BlendSplineOptions::default()
        };
        let sp = BlendSpline::new(pts.as_view(), local, opts)?;
        let mut dev = 0.0_f64;
        for (i, p) in pts.iter().enumerate() {
            let q = sp.eval(sp.parameters()[i])?;
            dev = dev.max((q[0] - p[0]).hypot(q[1] - p[1]));
        }
        s.check(
            &format!("{name}: max distance to the points"),
            dev,
            0.0,
            "0 (interpolation)",
            ROUNDING,
        );
        let jump = join_jump(&sp, 2)?;
        let param = sp.continuity() == Continuity::Parametric;
        if param {
            s.check(
                &format!("{name}: C² joins, max relative jump of C′, C″"),
                jump,
                0.0,
                "0",
                ROUNDING,
            );
        }
        let exact = sp.to_nurbs();
        let (obj, form) = match exact {
            Ok(nurbs) => {
                let d = nurbs.degree();
                (Object::Nurbs(nurbs), format!("exact NURBS, degree {d}"))
            }
            Err(_) => {
                let a = sp.approximate(1e-9)?;
                let form = format!(
                    "B-spline approximation, degree {}, error {:.1e}",
                    a.curve().degree(),
                    a.max_error()
                );
                (Object::BSpline(a.curve().clone()), form)
            }
        };
        rows.push(vec![
            name.to_string(),
            if param { "C^2" } else { "G^2" }.to_string(),
            format!("{jump:.1e}"),
            form,
        ]);
        if closed {
            let mut fig = Figure::new("Closed spline by parabolas, k = 2", true);
            fig.axis_labels = ("x".into(), "y".into());
            add_curve(&mut fig, &obj, name, PALETTE[n])?;
            add_points(&mut fig, &pts, "points", PALETTE[7], false);
            closed_fig = Some(fig);
        } else {
            add_curve(&mut fig, &obj, name, PALETTE[n])?;
        }
    }
    add_points(&mut fig, &pts, "points", PALETTE[7], false);
    s.tables.push((
        "Blended splines through six points, k = 2 (computed)".into(),
        vec![
            "local curves".into(),
            "continuity".into(),
            "max relative C′/C″ jump in s".into(),
            "output form".into(),
        ],
        rows,
    ));
    s.figure(
        fig,
        Caption::new(
            "Open splines through six points, each segment blending the local curve through \
             three consecutive points into the next one with w_1: parabolas give a C² curve, \
             circular arcs a G² one. The arcs with uniform-angle and with rational quadratic \
             parametrisation trace the same curve.",
        )
        .theory("blending.md#blend-splines"),
    );
    if let Some(fig) = closed_fig {
        s.figure(
            fig,
            Caption::new(
                "The closed spline through the same six points by blended parabolas: the \
                 indices wrap around, so the last segment blends back into the first and the \
                 curve is C² everywhere, with no start or end.",
            )
            .theory("blending.md#blend-splines"),
        );
    }
    Ok(())
}

pub(super) fn corner(s: &mut Section) -> Result<()> {
    s.caption = "Smoothing a corner (named in document 001's conclusion): the last part of the \
        segment before the corner and the first part after it are replaced by one Bezier curve \
        of degree 2k + 1 with contact of order k at both ends, whose control points lie on the \
        two legs; its curvature keeps one sign (document 001's deformation of the legs, \
        CornerTransition, has the same contact but inflects twice)."
        .into();
    let corner = Points::from_2d(&[[0.0, 0.0], [2.0, 0.0], [2.0, 2.0]])?;
    let mut fig = Figure::new("Corner smoothing of a right angle", true);
    fig.axis_labels = ("x".into(), "y".into());
    add_points(&mut fig, &corner, "corner", "#777777", true);
    let mut rows = Vec::new();
    for k in 1..=3 {
        let smooth = smooth_polyline_corners(corner.as_view(), CornerWindow::Length(1.0), k)?;
        let curve = smooth.curve();
        s.check(
            &format!("k = {k}: degree of the curve"),
            curve.degree() as f64,
            (2 * k + 1) as f64,
            &format!("2k + 1 = {}", 2 * k + 1),
            0.0,
        );
        // the transition runs over [1, 3] (arc length 1 to the corner's window end), from
        // (1, 0) to (2, 1): unit-speed contact of order k with the legs at both ends
        let (t0, t1) = (smooth.straight_spans()[0].1, smooth.straight_spans()[1].0);
        let d0 = curve.eval_derivatives(t0, k)?;
        let d1 = curve.eval_derivatives(t1, k)?;
        let dev = (d0.point(1)[0] - 1.0)
            .abs()
            .max(d0.point(1)[1].abs())
            .max(d1.point(1)[0].abs())
            .max((d1.point(1)[1] - 1.0).abs())
            .max(
                (2..=k)
                    .flat_map(|l| [d0.point(l), d1.point(l)])
                    .flatten()
                    .fold(0.0_f64, |m, x| m.max(x.abs())),
            );
        s.check(
            &format!("k = {k}: contact with the legs (C′ = direction, higher = 0)"),
            dev,
            0.0,
            "0",
            ROUNDING,
        );
        // fair: the curvature x′y″ − x″y′ of the left turn is never negative in the window
        let least = (0..=200)
            .map(|i| {
                let t = t0 + (t1 - t0) * f64::from(i) / 200.0;
                curve.eval_derivatives(t, 2).map(|d| {
                    let (a, b) = (d.point(1), d.point(2));
                    a[0] * b[1] - a[1] * b[0]
                })
            })
            .collect::<lekalo::Result<Vec<f64>>>()?
            .into_iter()
            .fold(f64::INFINITY, f64::min);
        s.check(
            &format!("k = {k}: no inflection (least curvature in the window ≥ 0)"),
            least.min(0.0),
            0.0,
            "0",
            ROUNDING,
        );
        let m = curve.eval((t0 + t1) / 2.0)?;
        rows.push(vec![
            k.to_string(),
            curve.degree().to_string(),
            format!("({}, {})", trim(m[0]), trim(m[1])),
        ]);
        add_curve(
            &mut fig,
            &Object::BSpline(curve.clone()),
            &format!("k = {k}"),
            PALETTE[k - 1],
        )?;
    }
    s.tables.push((
        "Transitions on the window [1, 2] × [0, 1] (computed)".into(),
        vec!["k".into(), "degree".into(), "midpoint".into()],
        rows,
    ));
    s.figure(
        fig,
        Caption::new(
            "A right-angle corner (grey, dashed) smoothed over the last half of the first leg \
             and the first half of the second by one Bezier transition of degree 2k + 1, for \
             k = 1, 2, 3: it leaves the first leg at (1, 0) and joins the second at (2, 1), \
             turning one way throughout. The larger k, the higher the order of contact at both \
             ends: the transition clings to the legs longer and turns more sharply at the \
             corner.",
        )
        .theory("blending.md#polyline-corners"),
    );
    Ok(())
}
