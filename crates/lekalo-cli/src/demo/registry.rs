//! The gallery's registry: one entry per construction of the documents. The other issues'
//! constructions (interpolation, Bezier degree change, blending, piecewise polynomials,
//! surfaces) are added here as they land: write a build function and list it in [`ENTRIES`].

use anyhow::Result;
use lekalo::basis::{basis_function_recursive, basis_functions};
use lekalo::{BSplineCurve, KnotVector, Points};
use lekalo_io::{basis_figure, curve_figure, CurvePlot, Object, Series, Style, PALETTE};

use super::{trim, Caption, Section};

// the documents' constructions: interpolation, blending, pp-form, degree change
#[path = "doc000.rs"]
mod doc000;
#[path = "doc001.rs"]
mod doc001;
#[path = "doc003.rs"]
mod doc003;
#[path = "doc004.rs"]
mod doc004;
#[path = "fitting.rs"]
mod fitting;
#[path = "fitting_shape.rs"]
mod fitting_shape;
#[path = "queries.rs"]
mod queries;

/// A gallery entry: identity and the function that builds it.
pub(crate) struct Entry {
    /// File-name id.
    pub(crate) id: &'static str,
    /// Title.
    pub(crate) title: &'static str,
    /// Document and section.
    pub(crate) source: &'static str,
    /// Fills the section: caption, figures, tables, checks.
    pub(crate) build: fn(&mut Section) -> Result<()>,
}

/// Every construction shown by `lekalo demo`, in gallery order.
pub(crate) const ENTRIES: &[Entry] = &[
    Entry {
        id: "doc002-bspline",
        title: "B-spline curve by the Cox–de Boor recursion",
        source: "document 002, B-splines; theory: foundations, the lecture's worked example",
        build: lecture_bspline,
    },
    Entry {
        id: "doc000-knots",
        title: "Knot vectors for interpolation",
        source: "document 000 eqs. (2), (3), (4), (8); theory: interpolation, test vectors",
        build: interpolation_knots,
    },
    Entry {
        id: "doc003-curry-schoenberg",
        title: "Curry–Schoenberg knots and B-spline basis",
        source: "document 003 Theorem 4.5 and the practical task (§4.2, §5.3)",
        build: curry_schoenberg,
    },
    Entry {
        id: "doc000-curves",
        title: "Curves through points: P&T Example 9.1",
        source: "document 000 §1; theory: interpolation, test vectors",
        build: doc000::curves,
    },
    Entry {
        id: "doc000-ends",
        title: "End derivatives, second derivatives, natural spline",
        source: "document 000 §2–4; theory: interpolation, test vectors",
        build: doc000::end_conditions,
    },
    Entry {
        id: "doc000-surface",
        title: "Surface through a grid of points",
        source: "document 000, surface interpolation",
        build: doc000::surface,
    },
    Entry {
        id: "doc001-jump",
        title: "Jump-smoothing polynomials w_k, k = 0 … 5",
        source: "document 001 §1, Properties 1–4",
        build: doc001::jump,
    },
    Entry {
        id: "doc001-deformation",
        title: "Deformation of two circular arcs",
        source: "document 001 §2",
        build: doc001::deformation,
    },
    Entry {
        id: "doc001-spline",
        title: "Splines through points by blended arcs and parabolas",
        source: "document 001 §3",
        build: doc001::spline,
    },
    Entry {
        id: "doc001-corner",
        title: "Corner smoothing",
        source: "document 001, conclusion (construction: lekalo CornerTransition)",
        build: doc001::corner,
    },
    Entry {
        id: "doc002-hermite",
        title: "Hermite segment and the four-point cubic",
        source: "document 002, the Hermite form and the four-point cubic",
        build: doc003::hermite,
    },
    Entry {
        id: "doc003-quasi",
        title: "Quasi-interpolation of x·cos x (thesis Figure 1)",
        source: "document 003 §5.3, practical task",
        build: doc003::quasi,
    },
    Entry {
        id: "doc004-elevation",
        title: "Degree elevation: Example 1",
        source: "document 004 Example 1, eq. (7)–(8)",
        build: doc004::elevation,
    },
    Entry {
        id: "doc004-reduction",
        title: "Real degree and exact reduction: Example 2",
        source: "document 004 Example 2, eq. (9)–(10)",
        build: doc004::reduction,
    },
    Entry {
        id: "doc004-surface",
        title: "Order change of a Bezier surface",
        source: "document 004 eq. (14), Fig. 5",
        build: doc004::surface,
    },
    Entry {
        id: "fitting",
        title: "Fitting noisy points: least squares, smoothing, tolerance",
        source: "docs/theory/fitting.md; P&T §9.4.1",
        build: fitting::fitting,
    },
    Entry {
        id: "fitting-shape",
        title: "Fits that keep their shape: increasing and bounded",
        source: "docs/theory/fitting.md#shape-constraints",
        build: fitting::shape,
    },
    Entry {
        id: "fitting-shape-kinds",
        title: "Fits that keep their shape: decreasing, convex, concave on an interval, at points",
        source: "docs/theory/fitting.md#shape-constraints",
        build: fitting_shape::kinds,
    },
    Entry {
        id: "fitting-shape-surfaces",
        title: "Surfaces that keep their shape: a table rising in both variables, within bounds",
        source: "docs/theory/fitting.md#shape-constraints-of-surfaces",
        build: fitting_shape::surfaces,
    },
    Entry {
        id: "queries",
        title: "Geometric queries: intersections, closest points, offsets, curvature",
        source: "docs/theory/queries.md",
        build: queries::queries,
    },
];

/// Tolerance of checks against exact fractions (the values are O(1)).
const EXACT: f64 = 1e-14;
/// Tolerance of checks against reference numbers given with 6 decimals
/// (docs/theory/interpolation.md#test-vectors).
const SIX_DECIMALS: f64 = 5e-7;

fn lecture_bspline(s: &mut Section) -> Result<()> {
    let ctrl = Points::from_2d(&[[1.0, 1.0], [2.0, 3.0], [4.0, 3.0]])?;
    let knots = KnotVector::new(vec![0.0, 0.0, 1.0, 2.0, 3.0, 3.0])?;
    let curve = BSplineCurve::from_knot_vector(2, knots.clone(), ctrl.clone())?;
    s.caption = "Control points P0 = (1,1), P1 = (2,3), P2 = (4,3), knots T = [0,0,1,2,3,3], \
        degree 2 = 6 − 3 − 1 (the notes call 3 the degree; it is the order). The end knots have \
        multiplicity 2 < p + 1, so the curve is not clamped: the basis sums to 1 only on \
        [t2, t3] = [1, 2], where the curve runs from the midpoint of P0P1 to the midpoint of P1P2. \
        The table evaluates the basis over all of [0, 3) as the notes do."
        .into();
    let obj = Object::BSpline(curve.clone());
    let mut fig = curve_figure(
        &obj,
        &CurvePlot {
            title: Some("The lecture's B-spline on its domain [1, 2]".into()),
            ..CurvePlot::default()
        },
    )?;
    // the notes evaluate Σ N_{i,2}(t) P_i over all of [0, 3]: outside [1, 2] the basis does not
    // sum to 1 and the "curve" leaves the convex hull towards the origin
    let mut full = Vec::new();
    for t in lekalo_io::uniform(0.0, 3.0, 301) {
        let mut p = [0.0; 2];
        for i in 0..3 {
            let n = basis_function_recursive(&knots, i, 2, t)?;
            p[0] += n * ctrl.point(i)[0];
            p[1] += n * ctrl.point(i)[1];
        }
        full.push(p);
    }
    fig.series.insert(
        0,
        Series::new(Some("Σ N P over [0, 3]"), full, Style::Dashed, PALETTE[3]),
    );
    s.figure(
        fig,
        Caption::new(
            "The lecture's quadratic B-spline with control points (1,1), (2,3), (4,3) and knots \
             [0,0,1,2,3,3], on its domain [1, 2] (blue): it runs from the midpoint (3/2, 2) of \
             the first leg to the midpoint (3, 3) of the second (orange: the points at the \
             knots). The dashed pink curve is Σ N_i,2(t) P_i over all of [0, 3], as the notes \
             evaluate it: outside the domain the basis no longer sums to 1, and the curve leaves \
             the convex hull and runs to the origin.",
        )
        .theory("curves.md#b-spline-curves"),
    );
    let mut basis = basis_figure(&knots, 2, 301)?;
    basis.title = "N0,2, N1,2, N2,2 on T = [0, 0, 1, 2, 3, 3]".into();
    s.figure(
        basis,
        Caption::new(
            "The three quadratic B-splines N0,2, N1,2, N2,2 of the knots [0, 0, 1, 2, 3, 3] by \
             the Cox–de Boor recursion, over the whole knot range; the ticks on the axis are the \
             knots. Only on the shaded domain [1, 2] do they sum to 1, which is why the curve \
             is drawn there and nowhere else.",
        )
        .theory("foundations.md#cox-de-boor-recursion")
        .command(
            "printf '1 1\\n2 3\\n4 3\\n' | lekalo make bspline --control - --degree 2 \
             --knots 0,0,1,2,3,3 -o lecture.json && lekalo plot lecture.json --basis -o basis.svg",
        ),
    );
    // the notes' table: P(t) = Σ N_{i,2}(t) P_i over [0, 3), also outside the domain
    let mut rows = Vec::new();
    let mut at = |t: f64| -> Result<(Vec<f64>, [f64; 2])> {
        let n: Vec<f64> = (0..3)
            .map(|i| basis_function_recursive(&knots, i, 2, t))
            .collect::<lekalo::Result<_>>()?;
        let mut p = [0.0; 2];
        for (i, ni) in n.iter().enumerate() {
            p[0] += ni * ctrl.point(i)[0];
            p[1] += ni * ctrl.point(i)[1];
        }
        rows.push(vec![
            trim(t),
            format!("({}, {}, {})", trim(n[0]), trim(n[1]), trim(n[2])),
            format!("({}, {})", trim(p[0]), trim(p[1])),
        ]);
        Ok((n, p))
    };
    let _ = at(0.0)?;
    let (_, p05) = at(0.5)?;
    let (n1, _) = at(1.0)?;
    let (n15, p15) = at(1.5)?;
    let _ = at(2.0)?;
    let (_, p25) = at(2.5)?;
    s.tables.push((
        "Sample values (the lecture's example, completed)".into(),
        vec!["t".into(), "(N0,2, N1,2, N2,2)".into(), "P(t)".into()],
        rows,
    ));
    s.check_all(
        "(N0,2, N1,2, N2,2)(1)",
        &n1,
        &[0.5, 0.5, 0.0],
        "(1/2, 1/2, 0)",
        EXACT,
    );
    s.check_all(
        "(N0,2, N1,2, N2,2)(1.5)",
        &n15,
        &[0.125, 0.75, 0.125],
        "(1/8, 3/4, 1/8)",
        EXACT,
    );
    s.check_all(
        "P(0.5) = Σ N P (outside the domain)",
        &p05,
        &[0.875, 1.0],
        "(7/8, 1)",
        EXACT,
    );
    s.check_all(
        "P(2.5) = Σ N P (outside the domain)",
        &p25,
        &[2.75, 2.25],
        "(11/4, 9/4)",
        EXACT,
    );
    s.check_all(
        "P(1.5) by the Cox–de Boor sum",
        &p15,
        &[17.0 / 8.0, 11.0 / 4.0],
        "(17/8, 11/4)",
        EXACT,
    );
    s.check_all(
        "P(1.5) by BSplineCurve::eval (de Boor)",
        &curve.eval(1.5)?,
        &[17.0 / 8.0, 11.0 / 4.0],
        "(17/8, 11/4)",
        EXACT,
    );
    let (a, b) = curve.domain();
    s.check_all("domain [t_p, t_{n+1}]", &[a, b], &[1.0, 2.0], "[1, 2]", 0.0);
    s.check_all(
        "P(1), P(2): leg midpoints",
        &[curve.eval(a)?, curve.eval(b)?].concat(),
        &[1.5, 2.0, 3.0, 3.0],
        "(3/2, 2), (3, 3)",
        EXACT,
    );
    let d = curve.eval_derivatives(1.25, 2)?;
    // on [1, 2): P = (t²/2 + 1, −t² + 4t − 1), P' = (t, 4 − 2t), P'' = (1, −2)
    s.check_all(
        "P'(1.25), P''(1.25)",
        &[d.point(1), d.point(2)].concat(),
        &[1.25, 1.5, 1.0, -2.0],
        "(5/4, 3/2), (1, −2)",
        1e-13,
    );
    Ok(())
}

/// P&T Example 9.1 data, chord lengths 5, 4, 5, 3 (total 17)
/// (docs/theory/interpolation.md#test-vectors).
const CHORD: [f64; 5] = [0.0, 5.0 / 17.0, 9.0 / 17.0, 14.0 / 17.0, 1.0];
/// Centripetal parameters of P&T Example 9.1, 6 decimals
/// (docs/theory/interpolation.md#test-vectors).
const CENTRIPETAL: [f64; 5] = [0.0, 0.272552, 0.516330, 0.788882, 1.0];
const UNIFORM: [f64; 5] = [0.0, 0.25, 0.5, 0.75, 1.0];

/// Interior knots (between the clamped ends) of a knot vector of `degree`.
fn interior(kv: &KnotVector, degree: usize) -> Vec<f64> {
    let k = kv.as_slice();
    k[degree + 1..k.len() - degree - 1].to_vec()
}

fn interpolation_knots(s: &mut Section) -> Result<()> {
    s.caption = "Knots for global interpolation of the points q0..q4 = (0,0), (3,4), (−1,4), \
        (−4,0), (−4,−3) (P&T Example 9.1; chord lengths 5, 4, 5, 3). Uniform knots (eq. 2) \
        ignore the parameters; averaged knots (eq. 3) make the collocation matrix banded and \
        totally positive; eq. (4) adds two knots for the end derivatives; eq. (8) puts the knots \
        at the parameters (cubic C² interpolation, §A.3–A.4). The curves themselves are in the \
        interpolation section."
        .into();
    let mut rows = Vec::new();
    let mut add = |s: &mut Section,
                   rule: &str,
                   params: &str,
                   p: usize,
                   kv: &KnotVector,
                   expected: &[f64],
                   shown: &str,
                   tol: f64| {
        let inner = interior(kv, p);
        let r: Vec<String> = inner.iter().map(|x| trim(*x)).collect();
        rows.push(vec![
            rule.to_string(),
            params.to_string(),
            p.to_string(),
            r.join(", "),
        ]);
        s.check_all(
            &format!("{rule}, {params}, p = {p}: interior knots"),
            &inner,
            expected,
            shown,
            tol,
        );
    };
    let uni = KnotVector::clamped_uniform(3, 5)?;
    add(s, "uniform (2)", "—", 3, &uni, &[0.5], "1/2", EXACT);
    let kv = KnotVector::averaged(&UNIFORM, 3)?;
    add(s, "averaged (3)", "uniform", 3, &kv, &[0.5], "1/2", EXACT);
    let chord3 = KnotVector::averaged(&CHORD, 3)?;
    add(
        s,
        "averaged (3)",
        "chord",
        3,
        &chord3,
        &[28.0 / 51.0],
        "28/51",
        EXACT,
    );
    let kv = KnotVector::averaged(&CENTRIPETAL, 3)?;
    add(
        s,
        "averaged (3)",
        "centripetal",
        3,
        &kv,
        &[0.525921],
        "0.525921",
        SIX_DECIMALS,
    );
    let kv = KnotVector::averaged(&CHORD, 2)?;
    add(
        s,
        "averaged (3)",
        "chord",
        2,
        &kv,
        &[7.0 / 17.0, 23.0 / 34.0],
        "7/17, 23/34",
        EXACT,
    );
    let ends3 = KnotVector::averaged_with_end_derivatives(&CHORD, 3)?;
    add(
        s,
        "end derivatives (4)",
        "chord",
        3,
        &ends3,
        &[14.0 / 51.0, 28.0 / 51.0, 40.0 / 51.0],
        "14/51, 28/51, 40/51",
        EXACT,
    );
    let kv = KnotVector::averaged_with_end_derivatives(&CHORD, 2)?;
    add(
        s,
        "end derivatives (4)",
        "chord",
        2,
        &kv,
        &[5.0 / 34.0, 7.0 / 17.0, 23.0 / 34.0, 31.0 / 34.0],
        "5/34, 7/17, 23/34, 31/34",
        EXACT,
    );
    let at3 = KnotVector::from_parameters(&CHORD, 3)?;
    add(
        s,
        "at the parameters (8)",
        "chord",
        3,
        &at3,
        &[5.0 / 17.0, 9.0 / 17.0, 14.0 / 17.0],
        "5/17, 9/17, 14/17",
        EXACT,
    );
    s.tables.push((
        "Interior knots (the ends are clamped: p + 1 zeros and ones)".into(),
        vec![
            "rule (eq.)".into(),
            "parameters".into(),
            "p".into(),
            "interior knots".into(),
        ],
        rows,
    ));
    for (kv, title, caption) in [
        (&chord3, "Cubic basis on averaged chord-length knots (eq. 3)", "The five cubic B-splines for interpolating five points with chord-length parameters, on the averaged knots {0,0,0,0, 28/51, 1,1,1,1} (eq. 3). Averaging puts the interior knot among the parameters it serves (5/17, 9/17, 14/17), which keeps the interpolation matrix banded and well conditioned."),
        (&ends3, "Cubic basis with end-derivative knots (eq. 4)", "Seven cubic B-splines for interpolation with given end derivatives: eq. (4) adds two knots, 14/51 and 40/51, and with them two functions whose coefficients carry the derivatives. Compare with the five functions above: the extra two crowd in next to the ends."),
        (&at3, "Cubic basis on knots at the parameters (eq. 8)", "Seven cubic B-splines on knots placed at the parameters themselves, {0,0,0,0, 5/17, 9/17, 14/17, 1,1,1,1} (eq. 8): the basis of C² cubic interpolation with two end conditions. Each interior tick is a data point's parameter, so every piece of the curve runs between two data points."),
    ] {
        let mut fig = basis_figure(kv, 3, 301)?;
        fig.title = title.into();
        s.figure(fig, Caption::new(caption).theory("interpolation.md#averaged-knots"));
    }
    // partition of unity on the domain (what makes the knots usable)
    let (_, n) = basis_functions(&chord3, 3, 0.4)?;
    s.check(
        "Σ N_i,3(0.4) on the chord knots",
        n.iter().sum(),
        1.0,
        "1",
        1e-15,
    );
    Ok(())
}

fn curry_schoenberg(s: &mut Section) -> Result<()> {
    let xi = [0.0, 0.5, 0.9, 1.4, 2.1, 2.7, 3.0];
    s.caption = "For breakpoints ξ1 < … < ξ(l+1), continuity conditions ν_i (how many \
        derivatives, counting the value, are continuous at ξ_i) and order k, the knots are k \
        copies of ξ1, each interior ξ_i repeated k − ν_i times, and k copies of ξ(l+1); the \
        B-splines on them are a basis of the piecewise polynomials P(k, ξ, ν), of dimension \
        n = k + Σ(k − ν_i). The thesis's practical task: k = 3, C¹ quadratics (ν = 2) on seven \
        breakpoints."
        .into();
    let kv = KnotVector::from_breakpoints(&xi, &[2; 5], 3)?;
    let n = kv.len() - 3;
    s.check_all(
        "knots, k = 3, ν = 2",
        kv.as_slice(),
        &[0.0, 0.0, 0.0, 0.5, 0.9, 1.4, 2.1, 2.7, 3.0, 3.0, 3.0],
        "{0,0,0,0.5,0.9,1.4,2.1,2.7,3,3,3}",
        0.0,
    );
    s.check("dimension n = k + Σ(k − ν_i)", n as f64, 8.0, "8", 0.0);
    let mut fig = basis_figure(&kv, 2, 301)?;
    fig.title = "Curry–Schoenberg basis: k = 3, ν = 2 at every breakpoint".into();
    s.figure(
        fig,
        Caption::new(
            "The eight C¹ quadratic B-splines (order k = 3, ν = 2 at every breakpoint) on the \
             breakpoints 0, 0.5, 0.9, 1.4, 2.1, 2.7, 3 of the thesis's practical task. Every \
             interior breakpoint is a single knot, so each function is smooth across it; the \
             shaded domain is where they sum to 1.",
        )
        .theory("pp.md#curry-schoenberg-knots"),
    );
    let nu = [2, 1, 2, 0, 2];
    let kv2 = KnotVector::from_breakpoints(&xi, &nu, 3)?;
    let n2 = kv2.len() - 3;
    s.check(
        "dimension with ν = (2, 1, 2, 0, 2)",
        n2 as f64,
        11.0,
        "3 + 1+2+1+3+1 = 11",
        0.0,
    );
    let mut fig = basis_figure(&kv2, 2, 601)?;
    fig.title = "Lower continuity: ν = (2, 1, 2, 0, 2)".into();
    s.figure(
        fig,
        Caption::new(
            "The same breakpoints with lower continuity, ν = (2, 1, 2, 0, 2): the double knot at \
             0.9 lets the functions have a kink there and the triple knot at 2.1 a jump, and the \
             space grows to eleven functions. Look at 2.1: one function drops from 1 to 0 and \
             the next rises from 0 to 1. Beyond seven colours, dashes and markers tell the \
             functions apart.",
        )
        .theory("pp.md#curry-schoenberg-knots"),
    );
    let rows = [("ν = 2 everywhere", &kv), ("ν = (2, 1, 2, 0, 2)", &kv2)]
        .iter()
        .map(|(name, k)| {
            let m: Vec<String> = k
                .distinct()
                .iter()
                .map(|(t, m)| format!("{}×{m}", trim(*t)))
                .collect();
            vec![name.to_string(), m.join("  ")]
        })
        .collect();
    s.tables.push((
        "Knots with multiplicities, k = 3".into(),
        vec!["continuity".into(), "knots".into()],
        rows,
    ));
    Ok(())
}
