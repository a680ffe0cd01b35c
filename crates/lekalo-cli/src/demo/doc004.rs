//! Gallery: document 004, order change of Bezier curves and surfaces (docs/theory/degree.md).

use anyhow::Result;
use lekalo::{BezierCurve, BezierSurface, Points};
use lekalo_io::{Figure, Marker, Object, PALETTE};

use super::doc000::{add_curve, add_points, show};
use crate::demo::{Caption, Section};
use crate::output::objects::surface_figure;

/// Exact results computed in floating point (coordinates O(10)).
const EXACT: f64 = 1e-12;

/// Draws the polygon just added (its line and its points, the last two series) dotted with
/// square markers, so that where it runs along the old polygon the two stay apart.
fn distinguish_new_polygon(fig: &mut Figure) {
    let n = fig.series.len();
    if let [line, points] = &mut fig.series[n.saturating_sub(2)..] {
        line.dash = Some("2 3".into());
        points.marker = Some(Marker::Square);
    }
}

/// `Σ w_i u_i` for the document's formulas `u'_j = Σ w_i u_i`.
fn combo(u: &Points, w: &[f64]) -> Vec<f64> {
    let mut out = vec![0.0; u.dim()];
    for (i, wi) in w.iter().enumerate() {
        for (o, x) in out.iter_mut().zip(u.point(i)) {
            *o += wi * x;
        }
    }
    out
}

/// Name, curve, elevation, old polygon, the document's weights per new vertex, as printed.
type Task<'a> = (
    &'a str,
    &'a BezierCurve,
    usize,
    &'a Points,
    Vec<Vec<f64>>,
    &'a str,
);

pub(super) fn elevation(s: &mut Section) -> Result<()> {
    s.caption = "Example 1 (Fig. 1): elevating a 2-leg polygon to 3 legs (task 1), a 3-leg to 4 \
        legs (task 2) and a 3-leg directly to 5 legs (task 3) by U′ = U·H_n·K_{n,n′}. The \
        document gives the new vertices as combinations of the old ones; lekalo's polygons are \
        checked against them on sample polygons, and the curves coincide."
        .into();
    let quad = BezierCurve::new(Points::from_2d(&[[0.0, 0.0], [2.0, 4.0], [5.0, 1.0]])?)?;
    let cubic = BezierCurve::new(Points::from_2d(&[
        [0.0, 0.0],
        [1.0, 3.0],
        [4.0, 4.0],
        [6.0, 0.0],
    ])?)?;
    let u2 = quad.control_points().clone();
    let u3 = cubic.control_points().clone();
    let tasks: [Task<'_>; 3] = [
        (
            "task 1: n = 2 → 3",
            &quad,
            1,
            &u2,
            vec![
                vec![1.0],
                vec![1.0 / 3.0, 2.0 / 3.0],
                vec![0.0, 2.0 / 3.0, 1.0 / 3.0],
                vec![0.0, 0.0, 1.0],
            ],
            "u0, (u0 + 2u1)/3, (2u1 + u2)/3, u2",
        ),
        (
            "task 2: n = 3 → 4",
            &cubic,
            1,
            &u3,
            vec![
                vec![1.0],
                vec![0.25, 0.75],
                vec![0.0, 0.5, 0.5],
                vec![0.0, 0.0, 0.75, 0.25],
                vec![0.0, 0.0, 0.0, 1.0],
            ],
            "u0, u0/4 + 3u1/4, (u1 + u2)/2, 3u2/4 + u3/4, u3",
        ),
        (
            "task 3: n = 3 → 5",
            &cubic,
            2,
            &u3,
            vec![
                vec![1.0],
                vec![0.4, 0.6],
                vec![0.1, 0.6, 0.3],
                vec![0.0, 0.3, 0.6, 0.1],
                vec![0.0, 0.0, 0.6, 0.4],
                vec![0.0, 0.0, 0.0, 1.0],
            ],
            "u0, (4u0 + 6u1)/10, (u0 + 6u1 + 3u2)/10, (3u1 + 6u2 + u3)/10, (6u2 + 4u3)/10, u3",
        ),
    ];
    let mut rows = Vec::new();
    for (n, (name, c, by, u, weights, shown)) in tasks.into_iter().enumerate() {
        let e = c.elevate_degree(by)?;
        let expected: Vec<f64> = weights.iter().flat_map(|w| combo(u, w)).collect();
        s.check_all(
            &format!("{name}: new polygon"),
            e.control_points().as_slice(),
            &expected,
            shown,
            EXACT,
        );
        let dev = (0..=20)
            .map(|j| {
                let t = f64::from(j) / 20.0;
                let (a, b) = (c.eval(t)?, e.eval(t)?);
                Ok((a[0] - b[0]).hypot(a[1] - b[1]))
            })
            .collect::<lekalo::Result<Vec<f64>>>()?
            .into_iter()
            .fold(0.0_f64, f64::max);
        s.check(
            &format!("{name}: max |p(t) − p′(t)|"),
            dev,
            0.0,
            "0 (the curves coincide)",
            EXACT,
        );
        rows.push(vec![
            name.to_string(),
            show(c.control_points()),
            show(e.control_points()),
        ]);
        let mut fig = Figure::new(&format!("Example 1, {name}"), true);
        fig.axis_labels = ("x".into(), "y".into());
        add_points(&mut fig, u, "old polygon", "#777777", true);
        add_points(
            &mut fig,
            e.control_points(),
            "new polygon",
            PALETTE[n + 1],
            true,
        );
        distinguish_new_polygon(&mut fig);
        add_curve(&mut fig, &Object::Bezier(e.clone()), "curve", PALETTE[0])?;
        let where_ = if by == 1 {
            "each new vertex lies on a leg of the old polygon, cutting its corners"
        } else {
            "the inner new vertices combine up to three old ones and lie inside the old polygon"
        };
        s.figure(
            fig,
            Caption::new(format!(
                "Example 1, {name}: the old polygon (grey) and the elevated one with {by} more {vertices} \
                 define the same Bezier curve (blue); {where_}. The new polygon lies closer to \
                 the curve, which is what elevation is for.",
                vertices = if by == 1 { "vertex" } else { "vertices" }
            ))
            .theory("degree.md#degree-elevation"),
        );
    }
    s.tables.push((
        "Elevated polygons (computed)".into(),
        vec!["task".into(), "U".into(), "U′".into()],
        rows,
    ));
    Ok(())
}

pub(super) fn reduction(s: &mut Section) -> Result<()> {
    s.caption = "Example 2 (Fig. 2): the quintic on (10,0), (22,6), (19,12), (11,15), (8,12), \
        (20,0) has monomial coefficients S_5 = U·H_5 with two zero columns on the right: real \
        degree 3, defect 2, and eq. (9) gives the cubic polygon (10,0), (30,10), (0,20), (20,0). \
        Reducing below the real degree is refused rather than silently changing the shape."
        .into();
    let u = Points::from_2d(&[
        [10.0, 0.0],
        [22.0, 6.0],
        [19.0, 12.0],
        [11.0, 15.0],
        [8.0, 12.0],
        [20.0, 0.0],
    ])?;
    let c = BezierCurve::new(u.clone())?;
    let mono = c.to_monomial()?;
    s.check_all(
        "S_5 = U·H_5 (x row, then y row)",
        &(0..6)
            .map(|i| mono.point(i)[0])
            .chain((0..6).map(|i| mono.point(i)[1]))
            .collect::<Vec<_>>(),
        &[
            10.0, 60.0, -150.0, 100.0, 0.0, 0.0, 0.0, 30.0, 0.0, -30.0, 0.0, 0.0,
        ],
        "[10 60 −150 100 0 0; 0 30 0 −30 0 0]",
        EXACT,
    );
    s.check_all(
        "real degree n′, defect d",
        &[c.real_degree() as f64, c.degree_defect() as f64],
        &[3.0, 2.0],
        "3, 2",
        0.0,
    );
    let r = c.reduce_degree_exact();
    s.check_all(
        "minimal polygon u′_0..u′_3",
        r.control_points().as_slice(),
        &[10.0, 0.0, 30.0, 10.0, 0.0, 20.0, 20.0, 0.0],
        "(10,0), (30,10), (0,20), (20,0)",
        EXACT,
    );
    let refusal = match c.change_degree(2) {
        Ok(_) => "accepted (wrong)".to_string(),
        Err(e) => e.to_string(),
    };
    s.checks.push(crate::demo::Check {
        what: "change_degree(2) is refused, naming the real degree".into(),
        ours: refusal.clone(),
        expected: "refused: real degree 3".into(),
        ok: refusal.contains("real degree is 3"),
    });
    s.tables.push((
        "Degree change of the quintic (computed)".into(),
        vec!["operation".into(), "result".into()],
        vec![
            vec!["real_degree()".into(), c.real_degree().to_string()],
            vec!["reduce_degree_exact()".into(), show(r.control_points())],
            vec!["change_degree(2)".into(), refusal],
        ],
    ));
    let mut fig = Figure::new("Example 2: the quintic is a cubic", true);
    fig.axis_labels = ("x".into(), "y".into());
    add_points(&mut fig, &u, "quintic polygon", "#777777", true);
    add_points(
        &mut fig,
        r.control_points(),
        "cubic polygon",
        PALETTE[1],
        true,
    );
    distinguish_new_polygon(&mut fig);
    add_curve(&mut fig, &Object::Bezier(c), "curve", PALETTE[0])?;
    s.figure(
        fig,
        Caption::new(
            "A formally quintic Bezier polygon (grey) and the cubic polygon (orange) of the same \
             curve (blue): the quintic's monomial coefficients of degrees 4 and 5 vanish, so its \
             real degree is 3. Both polygons hold the curve in their convex hulls; the cubic one \
             is the minimal description.",
        )
        .theory("degree.md#exact-degree-reduction"),
    );
    Ok(())
}

pub(super) fn surface(s: &mut Section) -> Result<()> {
    s.caption = "Order change of a Bezier surface (document 004, eq. (14), Fig. 5): a 5 × 4 net \
        U_{4,3} whose monomial matrix has one zero bottom row (a bicubic net elevated in t), so \
        its real orders are (3, 3). It is rebuilt on nets of orders (3, 3), (3, 6) and (4, 6) \
        without changing the shape; lowering m without a defect is refused."
        .into();
    let mut net = Vec::new();
    for i in 0..4_u8 {
        for j in 0..4_u8 {
            let (x, y) = (f64::from(i), f64::from(j));
            let z = [0.0, 1.5, -0.5, 1.0][usize::from(i + j) % 4] + 0.2 * x * y;
            net.extend([x, y, z]);
        }
    }
    let bicubic = BezierSurface::new(Points::from_flat(3, net)?, (4, 4))?;
    let original = bicubic.elevate_degree(1, 0)?;
    s.check_all(
        "net size, real degrees (n′, m′)",
        &[
            original.net_size().0 as f64,
            original.net_size().1 as f64,
            original.real_degrees().0 as f64,
            original.real_degrees().1 as f64,
        ],
        &[5.0, 4.0, 3.0, 3.0],
        "5 × 4 net, (3, 3)",
        0.0,
    );
    let mut rows = Vec::new();
    for (n, m) in [(3, 3), (3, 6), (4, 6)] {
        let c = original.change_degree(n, m)?;
        let mut dev = 0.0_f64;
        for a in 0..=10 {
            for b in 0..=10 {
                let (t, tau) = (f64::from(a) / 10.0, f64::from(b) / 10.0);
                let (p, q) = (original.eval(t, tau)?, c.eval(t, tau)?);
                for (x, y) in p.iter().zip(&q) {
                    dev = dev.max((x - y).abs());
                }
            }
        }
        s.check(
            &format!("(n′, m′) = ({n}, {m}): max shape change"),
            dev,
            0.0,
            "0",
            EXACT,
        );
        rows.push(vec![
            format!("({n}, {m})"),
            format!("{} × {}", c.net_size().0, c.net_size().1),
            format!("{dev:.1e}"),
        ]);
    }
    let refused = original.change_degree(6, 2);
    let msg = refused
        .as_ref()
        .map_or_else(ToString::to_string, |_| "accepted".to_string());
    s.checks.push(crate::demo::Check {
        what: "(6, 2): lowering m without a defect is refused".into(),
        ours: msg.clone(),
        expected: "refused".into(),
        ok: refused.is_err(),
    });
    rows.push(vec!["(6, 2)".into(), "—".into(), msg]);
    s.tables.push((
        "Order changes of the surface (computed)".into(),
        vec!["(n′, m′)".into(), "net".into(), "max shape change".into()],
        rows,
    ));
    let low = original.change_degree(3, 3)?;
    s.figure(
        surface_figure(
            &original.to_bspline(),
            "Bezier surface on a 5 × 4 net U_{4,3}",
        )?,
        Caption::new(
            "The Bezier surface on its 5 × 4 control net U_{4,3} (Fig. 5a), shaded by height. \
             The net has five rows in t although the surface is cubic in t: one row is spare.",
        )
        .theory("degree.md#degree-change-of-surfaces"),
    );
    s.figure(
        surface_figure(&low.to_bspline(), "The same surface on a 4 × 4 net U_{3,3}")?,
        Caption::new(format!(
            "The same surface on the minimal 4 × 4 net (Fig. 5b), real degrees ({}, {}): the \
             shape is unchanged, to rounding, while the net has lost its spare row. Compare the \
             two nets over the same shading.",
            low.real_degrees().0,
            low.real_degrees().1
        ))
        .theory("degree.md#degree-change-of-surfaces"),
    );
    Ok(())
}
