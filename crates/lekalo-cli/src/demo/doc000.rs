//! Gallery: document 000, interpolation of curves and surfaces (docs/theory/interpolation.md, test
//! vectors in docs/theory/interpolation.md#test-vectors).

use anyhow::Result;
use lekalo::{
    BSplineCurve, CurveInterpolation, EndCondition, KnotPlacement, Parametrization, Points,
    SurfaceInterpolation,
};
use lekalo_io::{Figure, Object, Series, Style, PALETTE};

use crate::demo::{trim, Caption, Section};
use crate::output::objects::surface_figure;

/// Reference numbers given with 6 decimals (docs/theory/interpolation.md#test-vectors).
const SIX_DECIMALS: f64 = 5e-7;
/// Interpolation conditions hold to rounding (data of size O(1)).
const ROUNDING: f64 = 1e-12;

/// P&T Example 9.1 (docs/theory/interpolation.md#test-vectors).
pub(super) fn example_9_1() -> Result<Points> {
    Ok(Points::from_2d(&[
        [0.0, 0.0],
        [3.0, 4.0],
        [-1.0, 4.0],
        [-4.0, 0.0],
        [-4.0, -3.0],
    ])?)
}

/// Adds a curve (sampled) to a figure.
pub(super) fn add_curve(fig: &mut Figure, obj: &Object, label: &str, color: &str) -> Result<()> {
    let pts = obj.sample(300)?;
    let line = pts.iter().map(|p| [p[0], p[1]]).collect();
    fig.series
        .push(Series::new(Some(label), line, Style::Line, color));
    Ok(())
}

/// Adds points as markers (`dashed` also joins them as a polygon).
pub(super) fn add_points(fig: &mut Figure, pts: &Points, label: &str, color: &str, dashed: bool) {
    let p: Vec<[f64; 2]> = pts.iter().map(|p| [p[0], p[1]]).collect();
    if dashed {
        fig.series
            .push(Series::new(Some(label), p.clone(), Style::Dashed, color));
        fig.series.push(Series::new(None, p, Style::Markers, color));
    } else {
        fig.series
            .push(Series::new(Some(label), p, Style::Markers, color));
    }
}

/// The first stretch of `c` from its start, while it stays within `reach` of it (sampled finely:
/// the figure magnifies it).
fn near_start(c: &BSplineCurve, reach: f64) -> Result<Vec<[f64; 2]>> {
    let (a, b) = c.domain();
    let start = c.eval(a)?;
    let mut line = Vec::new();
    for i in 0..=4000 {
        let p = c.eval(a + 0.05 * (b - a) * f64::from(i) / 4000.0)?;
        if (p[0] - start[0]).hypot(p[1] - start[1]) > reach {
            break;
        }
        line.push([p[0], p[1]]);
    }
    Ok(line)
}

/// An arrow from `from` along `direction`, `length` long (in the figure's units, for figures of
/// equal aspect): its shaft and its head as two polylines of one series.
fn arrow(label: &str, from: [f64; 2], direction: [f64; 2], length: f64, color: &str) -> Series {
    let norm = direction[0].hypot(direction[1]);
    let u = [direction[0] / norm, direction[1] / norm];
    let tip = [from[0] + length * u[0], from[1] + length * u[1]];
    let (head, half) = (0.14 * length, 0.05 * length);
    let wing = |side: f64| {
        [
            tip[0] - head * u[0] - side * half * u[1],
            tip[1] - head * u[1] + side * half * u[0],
        ]
    };
    let mut s = Series::new(Some(label), vec![from, tip], Style::Line, color);
    s.paths.push(vec![wing(1.0), tip, wing(-1.0)]);
    s
}

/// Control points as flat numbers.
fn flat(c: &BSplineCurve) -> Vec<f64> {
    c.control_points().as_slice().to_vec()
}

/// Control points `(x, y); …` for tables.
pub(super) fn show(p: &Points) -> String {
    p.iter()
        .map(|q| format!("({}, {})", trim(q[0]), trim(q[1])))
        .collect::<Vec<_>>()
        .join("; ")
}

pub(super) fn curves(s: &mut Section) -> Result<()> {
    s.caption = "Global interpolation of P&T Example 9.1: q0..q4 = (0,0), (3,4), (−1,4), \
        (−4,0), (−4,−3), cubic, averaged knots (eq. 3), with the three parametrisations; the \
        control points are the library's and are checked against the reference values of the theory \
        reference (interpolation, test vectors)."
        .into();
    let q = example_9_1()?;
    let mut fig = Figure::new("Cubic interpolation of P&T Example 9.1", true);
    fig.axis_labels = ("x".into(), "y".into());
    let mut rows = Vec::new();
    let cases = [
        (
            "uniform",
            Parametrization::Uniform,
            vec![
                0.0,
                0.0,
                58.0 / 9.0,
                67.0 / 18.0,
                -8.0 / 3.0,
                7.5,
                -46.0 / 9.0,
                -49.0 / 18.0,
                -4.0,
                -3.0,
            ],
            "(0,0); (58/9, 67/18); (−8/3, 15/2); (−46/9, −49/18); (−4,−3)",
        ),
        (
            "chord length",
            Parametrization::ChordLength,
            vec![
                0.0, 0.0, 7.316964, 3.686778, -2.958131, 6.678277, -4.494953, -0.673692, -4.0, -3.0,
            ],
            "(0,0); (7.316964, 3.686778); (−2.958131, 6.678277); (−4.494953, −0.673692); (−4,−3)",
        ),
        (
            "centripetal",
            Parametrization::Centripetal,
            vec![
                0.0, 0.0, 6.844809, 3.683071, -2.780244, 7.092664, -4.754979, -1.614238, -4.0, -3.0,
            ],
            "(0,0); (6.844809, 3.683071); (−2.780244, 7.092664); (−4.754979, −1.614238); (−4,−3)",
        ),
    ];
    for (k, (name, param, expected, shown)) in cases.iter().enumerate() {
        let c = CurveInterpolation::new(3)
            .parametrization(*param)
            .interpolate(q.as_view())?;
        s.check_all(
            &format!("p = 3, {name}: control points"),
            &flat(&c),
            expected,
            shown,
            SIX_DECIMALS,
        );
        rows.push(vec![name.to_string(), show(c.control_points())]);
        let obj = Object::BSpline(c);
        add_curve(&mut fig, &obj, &format!("cubic, {name}"), PALETTE[k])?;
        if *param == Parametrization::ChordLength {
            let Object::BSpline(c) = &obj else {
                continue;
            };
            let r: Vec<f64> = [0.25, 0.5, 0.75]
                .iter()
                .map(|t| c.eval(*t))
                .collect::<lekalo::Result<Vec<_>>>()?
                .concat();
            s.check_all(
                "chord length: r(0.25), r(0.5), r(0.75)",
                &r,
                &[3.407028, 3.663345, -0.474156, 4.175193, -3.627509, 1.253884],
                "(3.407028, 3.663345), (−0.474156, 4.175193), (−3.627509, 1.253884)",
                SIX_DECIMALS,
            );
        }
    }
    let quad = CurveInterpolation::new(2).interpolate(q.as_view())?;
    s.check_all(
        "p = 2, chord length: control points",
        &flat(&quad),
        &[
            0.0, 0.0, 5.767270, 4.323172, -1.627371, 4.418936, -4.616510, -0.163975, -4.0, -3.0,
        ],
        "(0,0); (5.767270, 4.323172); (−1.627371, 4.418936); (−4.616510, −0.163975); (−4,−3)",
        SIX_DECIMALS,
    );
    rows.push(vec![
        "chord length, p = 2".into(),
        show(quad.control_points()),
    ]);
    add_curve(
        &mut fig,
        &Object::BSpline(quad),
        "quadratic, chord length",
        PALETTE[3],
    )?;
    add_points(&mut fig, &q, "data points", PALETTE[7], false);
    s.figure(
        fig,
        Caption::new(
            "Four interpolants of the same five points: cubics with uniform, chord-length and \
             centripetal parameters, and the quadratic with chord length. The parametrisation \
             alone changes the curve: chord length swings widest past (3, 4), uniform \
             parameters bulge below (−4, 0) on the way to the last point, and the quadratic \
             keeps tightest to the data.",
        )
        .theory("interpolation.md#parametrisation"),
    );
    s.tables.push((
        "Control points computed by lekalo".into(),
        vec!["parametrisation".into(), "p0..p4".into()],
        rows,
    ));
    Ok(())
}

/// Name, degree, knots, end condition, reference control points
/// (docs/theory/interpolation.md#test-vectors).
type EndCase = (
    &'static str,
    usize,
    KnotPlacement,
    EndCondition,
    Vec<f64>,
    &'static str,
);

pub(super) fn end_conditions(s: &mut Section) -> Result<()> {
    s.caption = "The same points with end conditions, chord-length parameters: given end \
        derivatives d0 = (1,2), dn = (−3,−1) with averaged knots (eq. 4, p = 3 and 2) and \
        with knots at the parameters (C² cubic, tridiagonal system); given second \
        derivatives d″0 = (2,−1), d″n = (0.5,4); the natural spline (d″ = 0)."
        .into();
    let q = example_9_1()?;
    let (d0, dn) = (vec![1.0, 2.0], vec![-3.0, -1.0]);
    let first = EndCondition::FirstDerivatives {
        start: d0.clone(),
        end: dn.clone(),
    };
    let cases: [EndCase; 5] = [
        (
            "end derivatives, p = 3",
            3,
            KnotPlacement::Averaged,
            first.clone(),
            vec![
                0.0, 0.0, 0.091503, 0.183007, 5.814921, 5.233246, -1.946712, 4.199996, -4.505986,
                1.863104, -3.784314, -2.928105, -4.0, -3.0,
            ],
            "(0,0); (0.091503, 0.183007); (5.814921, 5.233246); … (−3.784314, −2.928105); (−4,−3)",
        ),
        (
            "end derivatives, p = 2",
            2,
            KnotPlacement::Averaged,
            first.clone(),
            vec![
                0.0, 0.0, 0.073529, 0.147059, 4.523123, 4.612808, -1.685332, 4.316488, -4.293624,
                0.852796, -3.867647, -2.955882, -4.0, -3.0,
            ],
            "(0,0); (0.073529, 0.147059); (4.523123, 4.612808); … (−3.867647, −2.955882); (−4,−3)",
        ),
        (
            "end derivatives, knots at the parameters",
            3,
            KnotPlacement::AtParameters,
            first,
            vec![
                0.0, 0.0, 0.098039, 0.196078, 5.671017, 5.171684, -2.242701, 4.219889, -4.453199,
                1.460911, -3.823529, -2.941176, -4.0, -3.0,
            ],
            "(0,0); (0.098039, 0.196078); (5.671017, 5.171684); … (−3.823529, −2.941176); (−4,−3)",
        ),
        (
            "second derivatives",
            3,
            KnotPlacement::Auto,
            EndCondition::SecondDerivatives {
                start: vec![2.0, -1.0],
                end: vec![0.5, 4.0],
            },
            vec![
                0.0, 0.0, 1.792028, 1.645498, 5.069581, 4.581444, -2.098122, 4.573864, -4.285399,
                0.690131, -4.079724, -2.008700, -4.0, -3.0,
            ],
            "(0,0); (1.792028, 1.645498); (5.069581, 4.581444); … (−4.079724, −2.008700); (−4,−3)",
        ),
        (
            "natural spline (d″ = 0)",
            3,
            KnotPlacement::Auto,
            EndCondition::Natural,
            vec![
                0.0, 0.0, 1.808397, 1.637040, 5.063510, 4.583713, -2.095936, 4.575376, -4.286914,
                0.680423, -4.078249, -1.996248, -4.0, -3.0,
            ],
            "(0,0); (1.808397, 1.637040); (5.063510, 4.583713); … (−4.078249, −1.996248); (−4,−3)",
        ),
    ];
    let mut fig = Figure::new("End conditions on P&T Example 9.1", true);
    fig.axis_labels = ("x".into(), "y".into());
    let mut rows = Vec::new();
    let mut curves = Vec::new();
    for (k, (name, p, knots, end, expected, shown)) in cases.into_iter().enumerate() {
        let c = CurveInterpolation::new(p)
            .parametrization(Parametrization::ChordLength)
            .knot_placement(knots)
            .end_condition(end.clone())
            .interpolate(q.as_view())?;
        s.check_all(
            &format!("{name}: control points"),
            &flat(&c),
            &expected,
            shown,
            SIX_DECIMALS,
        );
        let (a, b) = c.domain();
        let ends = [c.eval_derivatives(a, 2)?, c.eval_derivatives(b, 2)?];
        let order = match end {
            EndCondition::FirstDerivatives { .. } => Some(1),
            EndCondition::SecondDerivatives { .. } | EndCondition::Natural => Some(2),
            _ => None,
        };
        let shown_ends = order.map_or_else(String::new, |o| {
            format!(
                "C{}(0) = ({}, {}), C{}(1) = ({}, {})",
                "′".repeat(o),
                trim(ends[0].point(o)[0]),
                trim(ends[0].point(o)[1]),
                "′".repeat(o),
                trim(ends[1].point(o)[0]),
                trim(ends[1].point(o)[1])
            )
        });
        rows.push(vec![
            name.to_string(),
            c.knots().len().to_string(),
            shown_ends,
        ]);
        add_curve(&mut fig, &Object::BSpline(c.clone()), name, PALETTE[k])?;
        curves.push((name, c));
    }
    add_points(&mut fig, &q, "data points", PALETTE[7], false);
    s.figure(
        fig,
        Caption::new(
            "Five interpolants of the same points with conditions at the ends: first \
             derivatives d0 = (1, 2) and dn = (−3, −1) (cubic and quadratic on averaged knots, \
             and the C² cubic with knots at the parameters), second derivatives (2, −1) and \
             (0.5, 4), and the natural spline with zero second derivatives. At this scale the \
             end conditions change the shape of the first and last pieces; the direction in \
             which each curve leaves (0, 0) is seen in the next figure, magnified.",
        )
        .theory("interpolation.md#end-derivatives-of-any-degree"),
    );
    // the start magnified: a derivative of length |d0| = √5 on a curve some 17 units long
    // (chord-length parameters on [0, 1]) holds the curve to its direction for a few hundredths
    // of a unit only, so the leaving direction shows only near (0, 0)
    let reach = 0.02;
    let mut zoom = Figure::new("Leaving (0, 0): the start magnified", true);
    zoom.axis_labels = ("x".into(), "y".into());
    for (k, (name, c)) in curves.iter().enumerate() {
        zoom.series.push(Series::new(
            Some(name),
            near_start(c, reach)?,
            Style::Line,
            PALETTE[k],
        ));
    }
    zoom.series.push(arrow(
        "given direction d0 = (1, 2)",
        [0.0, 0.0],
        [d0[0], d0[1]],
        0.9 * reach,
        "#777777",
    ));
    s.figure(
        zoom,
        Caption::new(
            "The same five curves within 0.02 of the first point (0, 0), magnified some 400 \
             times. The three with given first derivatives, blue, red and dashed green \
             (which lies on the blue), leave along the grey arrow, the given direction d0 = (1, 2), and turn within a few hundredths \
             towards the next point: |d0| = √5 is small beside the curve's length, 17 on the \
             parameter interval [0, 1]. The two with conditions on second derivatives (pink, \
             orange, nearly one line) leave in a direction of their own, about 20° lower.",
        )
        .theory("interpolation.md#end-derivatives-of-any-degree"),
    );
    s.tables.push((
        "End derivatives of the computed curves (from the library)".into(),
        vec![
            "construction".into(),
            "knots".into(),
            "end derivatives".into(),
        ],
        rows,
    ));
    Ok(())
}

pub(super) fn surface(s: &mut Section) -> Result<()> {
    s.caption = "Surface interpolation: a 5 × 4 grid on z = sin(x)·cos(y) interpolated \
        by a bicubic × quadratic B-spline surface, chord-length parameters averaged over the \
        rows and columns, knots by averaging; two passes of curve interpolation."
        .into();
    let (nu, nv) = (5, 4);
    let mut data = Vec::new();
    for i in 0..nu {
        for j in 0..nv {
            let (x, y) = (i as f64 * 0.75, j as f64 * 0.8);
            data.extend([x, y, x.sin() * y.cos()]);
        }
    }
    let grid = Points::from_flat(3, data)?;
    let (surf, report) = SurfaceInterpolation::new(3, 2)
        .parametrization(Parametrization::ChordLength)
        .interpolate_with_report(grid.as_view(), nu, nv)?;
    let (pu, pv) = (report.params_u(), report.params_v());
    let mut dev = 0.0_f64;
    for (i, u) in pu.iter().enumerate() {
        for (j, v) in pv.iter().enumerate() {
            let p = surf.eval(*u, *v)?;
            for (a, b) in p.iter().zip(grid.point(i * nv + j)) {
                dev = dev.max((a - b).abs());
            }
        }
    }
    s.check(
        "max |S(ū_k, v̄_l) − q_kl| over the grid",
        dev,
        0.0,
        "0 (interpolation)",
        ROUNDING,
    );
    s.tables.push((
        "Parameters and knots (computed)".into(),
        vec!["direction".into(), "parameters".into(), "knots".into()],
        vec![
            vec![
                "u".into(),
                pu.iter().map(|x| trim(*x)).collect::<Vec<_>>().join(", "),
                surf.knots_u()
                    .as_slice()
                    .iter()
                    .map(|x| trim(*x))
                    .collect::<Vec<_>>()
                    .join(", "),
            ],
            vec![
                "v".into(),
                pv.iter().map(|x| trim(*x)).collect::<Vec<_>>().join(", "),
                surf.knots_v()
                    .as_slice()
                    .iter()
                    .map(|x| trim(*x))
                    .collect::<Vec<_>>()
                    .join(", "),
            ],
        ],
    ));
    let fig = surface_figure(&surf, "Surface through a 5 × 4 grid")?;
    s.figure(
        fig,
        Caption::new(
            "The bicubic × quadratic B-spline surface through a 5 × 4 grid of points on \
             z = sin x · cos y, shaded by height with eight isoparametric lines each way, and its \
             control net (dashed). The surface passes through the grid points; the net's corners \
             are the corner data points, its other points stand off the surface.",
        )
        .theory("interpolation.md#surface-interpolation"),
    );
    Ok(())
}
