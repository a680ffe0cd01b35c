//! Gallery: geometric queries (length, closest points, intersections, offsets, curvature) on a
//! cubic B-spline and a circle.

use anyhow::Result;
use lekalo::query::CurveIntersection;
use lekalo::{BSplineCurve, NurbsCurve, Points, QueryCurve};
use lekalo_io::{Figure, Object, Series, Style, PALETTE};

use super::doc000::add_curve;
use crate::demo::{Caption, Section};

pub(super) fn queries(s: &mut Section) -> Result<()> {
    s.caption = "A cubic B-spline and a circle: their intersections (crossing points, with \
        parameters on both), the closest points of a few query points (the segment to each foot \
        is normal to the curve), the offset of the spline at distance 0.3 with its cusps, and \
        the curvature maxima. Checks: the arc length of the circle is 2πr; every intersection \
        lies on both curves; every projection's residual is orthogonal to the tangent."
        .into();
    let spline = BSplineCurve::new(
        3,
        vec![0.0, 0.0, 0.0, 0.0, 0.3, 0.6, 1.0, 1.0, 1.0, 1.0],
        Points::from_2d(&[
            [-1.0, 1.0],
            [2.0, -2.0],
            [3.0, 3.0],
            [6.0, -1.0],
            [8.0, 2.0],
            [10.0, 0.5],
        ])?,
    )?;
    let circle = NurbsCurve::circle(&[4.0, 0.5], &[1.0, 0.0], &[0.0, 1.0], 2.0)?;
    let (qs, qc) = (
        QueryCurve::from_bspline(&spline)?,
        QueryCurve::from_nurbs(&circle)?,
    );
    s.check(
        "length of the circle (r = 2)",
        qc.length()?,
        4.0 * std::f64::consts::PI,
        "2πr = 12.566371",
        1e-13,
    );
    let mut fig = Figure::new("Intersections, closest points, offset", true);
    fig.axis_labels = ("x".into(), "y".into());
    add_curve(
        &mut fig,
        &Object::BSpline(spline.clone()),
        "cubic B-spline",
        PALETTE[0],
    )?;
    add_curve(
        &mut fig,
        &Object::Nurbs(circle.clone()),
        "circle",
        PALETTE[1],
    )?;
    let mut hits = Vec::new();
    let mut worst = 0.0_f64;
    for h in qs.intersect(&qc, 1e-10)? {
        if let CurveIntersection::Point {
            t_a, t_b, point, ..
        } = h
        {
            let (a, b) = (qs.point(t_a)?, qc.point(t_b)?);
            worst = worst.max((a[0] - b[0]).hypot(a[1] - b[1]));
            hits.push([point[0], point[1]]);
        }
    }
    s.check(
        "largest gap between the two curves' intersection points",
        worst,
        0.0,
        "≤ 1e-10",
        1e-10,
    );
    let mut feet = Vec::new();
    let mut cos_max = 0.0_f64;
    for q in [
        [1.0, 2.5],
        [5.0, -2.5],
        [9.0, 3.0],
        [-1.5, -1.0],
        [4.0, 0.5],
    ] {
        let p = qs.project(&q)?;
        let d = spline.eval_derivatives(p.t, 1)?;
        let tan = d.point(1);
        let r = [q[0] - p.point[0], q[1] - p.point[1]];
        if p.distance > 0.0 && p.t > 0.0 && p.t < 1.0 {
            cos_max = cos_max
                .max(((r[0] * tan[0] + r[1] * tan[1]) / (p.distance * tan[0].hypot(tan[1]))).abs());
        }
        feet.push(vec![q, [p.point[0], p.point[1]]]);
    }
    s.check(
        "largest |cos| between residual and tangent",
        cos_max,
        0.0,
        "0",
        1e-9,
    );
    let off = qs.offset(0.3, 1e-5)?;
    for (i, part) in off.trimmed.iter().enumerate() {
        let pts = Object::BSpline(part.clone()).sample(200)?;
        fig.series.push(Series::new(
            (i == 0).then_some("offset d = 0.3 (loops trimmed)"),
            pts.iter().map(|p| [p[0], p[1]]).collect(),
            Style::Dashed,
            PALETTE[2],
        ));
    }
    fig.series.push(Series {
        label: Some("closest points".into()),
        paths: feet,
        style: Style::Line,
        color: PALETTE[3].into(),
        dash: None,
        marker: None,
    });
    fig.series.push(Series::new(
        Some("intersections"),
        hits,
        Style::Markers,
        PALETTE[4],
    ));
    let maxima: Vec<[f64; 2]> = qs
        .curvature_extrema()?
        .iter()
        .filter(|e| e.maximum)
        .map(|e| qs.point(e.t).map(|p| [p[0], p[1]]))
        .collect::<lekalo::Result<_>>()?;
    fig.series.push(Series::new(
        Some("curvature maxima"),
        maxima,
        Style::Markers,
        PALETTE[5],
    ));
    s.figure(
        fig,
        Caption::new(format!(
            "A planar cubic with its offset at d = 0.3, the closest points of a few query points, \
             its intersections with a second curve and its curvature maxima. The offset has {} \
             cusps where 0.3·κ = 1; {} loop(s) between them are trimmed.",
            off.cusps.len(),
            off.loops.len()
        ))
        .theory("queries.md#offsets"),
    );
    Ok(())
}
