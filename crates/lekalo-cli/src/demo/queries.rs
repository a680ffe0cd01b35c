//! Gallery: geometric queries (length, closest points, intersections, offsets, curvature) on a
//! cubic B-spline and a circle; the intersection of a sphere and a cylinder.

use anyhow::Result;
use std::f64::consts::{FRAC_PI_2, TAU};

use lekalo::query::{Contact, CurveIntersection};
use lekalo::surface::Placement;
use lekalo::{BSplineCurve, NurbsCurve, NurbsSurface, Points, QueryCurve, QuerySurface};
use lekalo_io::{Figure, Marker, Object, Projection, Series, Style, PALETTE};

use super::doc000::add_curve;
use crate::demo::{Caption, Section};

pub(super) fn queries(s: &mut Section) -> Result<()> {
    s.caption = "A cubic B-spline and a circle: their intersections (crossing points, with \
        parameters on both), the closest points of a few query points (the segment to each foot \
        is normal to the curve), the offset of the spline at distance 1.5 with its cusps and the loop trimmed, and \
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
    let mut queries = Vec::new();
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
        queries.push(q);
    }
    s.check(
        "largest |cos| between residual and tangent",
        cos_max,
        0.0,
        "0",
        1e-9,
    );
    // on the concave side of the sharpest bend (κ ≈ 1.6 at its top, radius ≈ 0.62), 1.5 away:
    // the offset point turns back at two cusps where 1.5·κ = 1 and crosses itself in a loop
    let d = -1.5;
    let off = qs.offset(d, 1e-5)?;
    s.check(
        "cusps of the offset at d = −1.5 (where 1.5·κ = 1)",
        off.cusps.len() as f64,
        2.0,
        "2",
        0.0,
    );
    s.check(
        "loops trimmed from the offset",
        off.loops.len() as f64,
        1.0,
        "1",
        0.0,
    );
    let whole = Object::BSpline(off.curve.clone()).sample(400)?;
    let mut untrimmed = Series::new(
        Some("offset before trimming"),
        whole.iter().map(|p| [p[0], p[1]]).collect(),
        Style::Line,
        "#777777",
    );
    untrimmed.dash = Some("2 3".into());
    fig.series.push(untrimmed);
    for (i, part) in off.trimmed.iter().enumerate() {
        let pts = Object::BSpline(part.clone()).sample(200)?;
        fig.series.push(Series::new(
            (i == 0).then_some("offset d = −1.5, loop trimmed"),
            pts.iter().map(|p| [p[0], p[1]]).collect(),
            Style::Dashed,
            PALETTE[2],
        ));
    }
    let cusps: Vec<[f64; 2]> = off
        .cusps
        .iter()
        .map(|&t| off.curve.eval(t).map(|p| [p[0], p[1]]))
        .collect::<lekalo::Result<_>>()?;
    fig.series.push(Series::new(
        Some("cusps"),
        cusps,
        Style::Markers,
        PALETTE[7],
    ));
    fig.series.push(Series {
        label: Some("closest points".into()),
        paths: feet,
        style: Style::Line,
        color: PALETTE[3].into(),
        dash: None,
        marker: None,
    });
    // the segments alone do not say which end is the query: the queries are marked
    fig.series.push(Series {
        marker: Some(Marker::Square),
        ..Series::new(Some("query points"), queries, Style::Markers, PALETTE[3])
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
            "A planar cubic with its offset at d = −1.5 (to the right of its direction), the \
             closest points of a few query points (pink squares, each joined to its foot on the \
             curve), its intersections with a circle and its \
             curvature maxima. Past the sharpest bend the offset (grey, dotted) turns back at {} \
             cusps (black) where 1.5·κ = 1 and crosses itself; the loop between the crossing \
             points is cut out. Outside the loop “offset d = −1.5, loop trimmed” (green, \
             dashed) coincides with “offset before trimming”.",
            off.cusps.len()
        ))
        .theory("queries.md#offsets"),
    );
    surfaces(s)
}

/// Iso-parameter lines of a surface (`nu` lines of constant `u`, `nv` of constant `v`),
/// projected: the paths of a wireframe.
fn iso_lines(
    s: &NurbsSurface,
    (nu, nv): (u32, u32),
    view: &Projection,
) -> Result<Vec<Vec<[f64; 2]>>> {
    let ((u0, u1), (v0, v1)) = s.domain();
    let at = |a: f64, b: f64| -> Result<[f64; 2]> {
        let p = s.eval(a, b)?;
        Ok(view.project([p[0], p[1], p[2]]))
    };
    let mut paths = Vec::new();
    for i in 0..=nu {
        let u = u0 + (u1 - u0) * f64::from(i) / f64::from(nu);
        paths.push(
            (0..=48)
                .map(|k| at(u, v0 + (v1 - v0) * f64::from(k) / 48.0))
                .collect::<Result<_>>()?,
        );
    }
    for j in 0..=nv {
        let v = v0 + (v1 - v0) * f64::from(j) / f64::from(nv);
        paths.push(
            (0..=96)
                .map(|k| at(u0 + (u1 - u0) * f64::from(k) / 96.0, v))
                .collect::<Result<_>>()?,
        );
    }
    Ok(paths)
}

/// The unit sphere and a cylinder of radius 0.6 about the z axis: two circles at
/// `z = ±0.8`, traced by `QuerySurface::intersect_surface`.
fn surfaces(s: &mut Section) -> Result<()> {
    let f = Placement::new([0.0; 3], None, None)?;
    let sphere = NurbsSurface::sphere(&f, 1.0, (0.0, TAU), (-FRAC_PI_2, FRAC_PI_2))?;
    let cylinder = NurbsSurface::cylinder(&f, 0.6, (0.0, TAU), (-1.2, 1.2))?;
    let (qa, qb) = (
        QuerySurface::from_nurbs(&sphere)?,
        QuerySurface::from_nurbs(&cylinder)?,
    );
    let tol = 1e-6;
    let branches = qa.intersect_surface(&qb, tol)?;
    let mut worst = 0.0_f64;
    for p in branches.iter().flat_map(|b| &b.points) {
        let on_sphere = (p[0].hypot(p[1]).hypot(p[2]) - 1.0).abs();
        let on_cylinder = (p[0].hypot(p[1]) - 0.6).abs();
        worst = worst.max(on_sphere).max(on_cylinder);
    }
    s.check(
        "largest distance of a branch point from the sphere or the cylinder",
        worst,
        0.0,
        "≤ 1e-6",
        tol,
    );
    let length: f64 = branches.iter().map(|b| b.length()).sum();
    s.check(
        "total length of the branches (two circles of radius 0.6)",
        length,
        2.0 * TAU * 0.6,
        "2·2π·0.6 = 7.539822",
        1e-4,
    );
    let view = Projection {
        azimuth: -60.0,
        elevation: 20.0,
    };
    let mut fig = Figure::new("Surface–surface intersection: sphere and cylinder", true);
    fig.axes = false;
    // the surfaces as thin dashed wireframes first, the branches drawn over them
    for (surface, label, color, lines) in [
        (&sphere, "sphere r = 1", PALETTE[0], (12, 8)),
        (&cylinder, "cylinder r = 0.6", PALETTE[1], (12, 4)),
    ] {
        fig.series.push(Series {
            label: Some(label.into()),
            paths: iso_lines(surface, lines, &view)?,
            style: Style::Dashed,
            color: color.into(),
            dash: None,
            marker: None,
        });
    }
    let crossing: Vec<Vec<[f64; 2]>> = branches
        .iter()
        .filter(|b| b.kind == Contact::Crossing)
        .map(|b| b.points.iter().map(|p| view.project(*p)).collect())
        .collect();
    let count = crossing.len();
    let branches = if count == 1 { "branch" } else { "branches" };
    fig.series.push(Series {
        label: Some("intersection branches".into()),
        paths: crossing,
        style: Style::Line,
        color: PALETTE[3].into(),
        dash: None,
        marker: None,
    });
    s.figure(
        fig,
        Caption::new(format!(
            "The unit sphere and a cylinder of radius 0.6 about the same axis (wireframes) meet in \
             two circles at z = ±0.8: {count} crossing {branches} traced by marching from starting \
             points found by subdivision, every point within 1e-6 of both surfaces (a branch \
             is cut where it crosses the seam of a closed surface's parameter domain)."
        ))
        .theory("queries.md#surface-surface-intersection"),
    );
    Ok(())
}
