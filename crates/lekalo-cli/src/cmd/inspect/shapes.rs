//! What `info`, `convert` and `plot` do with objects that are not curves: tensor-product
//! surfaces ([`Surface`]) and piecewise polynomials. The curve-only helpers (evaluation at `t`,
//! derivatives, curvature) are never asked of these; each command dispatches on the kind.

use std::fmt::Write as _;

use anyhow::Result;
use lekalo::{PiecewisePolynomial, Points};
use lekalo_io::{
    grid_to_obj, surface_plot, Figure, Grid, Series, Shape, StepWriter, Style, Surface,
    SurfacePlot, PALETTE,
};
use serde_json::{json, Value};

use crate::exit::bad_input;

fn bbox(p: &Points) -> Value {
    p.bounding_box()
        .map_or(Value::Null, |(lo, hi)| json!({"min": lo, "max": hi}))
}

fn distinct(knots: &[f64]) -> Vec<Value> {
    let mut out: Vec<(f64, usize)> = Vec::new();
    for &t in knots {
        match out.last_mut() {
            Some((x, m)) if *x == t => *m += 1,
            _ => out.push((t, 1)),
        }
    }
    out.iter()
        .map(|(t, m)| json!({"knot": t, "multiplicity": m}))
        .collect()
}

/// The facts about a surface: degrees, knots, net size, domain, control and sampled boxes.
pub(crate) fn surface_info_json(s: &Surface, samples: usize) -> lekalo::Result<Value> {
    let (pu, pv) = s.degrees();
    let (nu, nv) = s.net_size();
    let (ku, kv) = s.knots();
    let ((u0, u1), (v0, v1)) = s.domain();
    // a square grid of about `samples` points
    let side = samples.max(4).isqrt().clamp(2, 1000);
    let (pts, _) = s.sample_grid(side, side, false)?;
    let sampled = Points::from_flat(s.dim(), pts)?;
    Ok(json!({
        "type": s.type_name(),
        "name": s.display_name(),
        "dim": s.dim(),
        "degree": [pu, pv],
        "order": [pu + 1, pv + 1],
        "net": [nu, nv],
        "control_points": nu * nv,
        "rational": s.weights().is_some(),
        "weights": s.weights(),
        "knots_u": ku,
        "knots_v": kv,
        "distinct_knots_u": distinct(ku.as_slice()),
        "distinct_knots_v": distinct(kv.as_slice()),
        "domain": [[u0, u1], [v0, v1]],
        "control_box": bbox(&s.control_points()),
        "sampled_box": bbox(&sampled),
    }))
}

/// The facts about a pp-form: order, breakpoints, dimension, continuity at each interior
/// breakpoint, sampled box.
pub(crate) fn pp_info_json(p: &PiecewisePolynomial, samples: usize) -> lekalo::Result<Value> {
    let xi = p.breakpoints();
    let mut cont = Vec::new();
    // ν at each interior breakpoint, by the library's test (also `pp convert`'s default)
    let nu = p.continuity(lekalo::DEFAULT_CONTINUITY_RTOL);
    for (&x, &m) in xi[1..xi.len() - 1].iter().zip(&nu) {
        cont.push(json!({"breakpoint": x, "continuous_derivatives": m,
            "smoothness": if m >= p.order() { "C^inf".to_string() } else if m == 0 { "discontinuous".to_string() } else { format!("C^{}", m - 1) }}));
    }
    let (a, b) = p.domain();
    let sampled = pp_samples(p, samples)?;
    Ok(json!({
        "type": "piecewise_polynomial",
        "name": "piecewise polynomial (pp-form)",
        "dim": p.dim(),
        "order": p.order(),
        "degree": p.order() - 1,
        "pieces": p.n_pieces(),
        "breakpoints": xi,
        "domain": [a, b],
        "continuity": cont,
        "start": p.eval(a)?,
        "end": p.eval(b)?,
        "sampled_box": bbox(&sampled.1),
    }))
}

/// A JSON value as text for the human-readable reports: lists in brackets, numbers as
/// [`lekalo_io::fmt_number`] writes them (exponent notation for the very small and large).
pub(crate) fn fmt(v: &Value) -> String {
    match v {
        Value::Array(a) => {
            let s: Vec<String> = a.iter().map(fmt).collect();
            format!("[{}]", s.join(", "))
        }
        Value::Number(n) => n
            .as_f64()
            .map_or_else(|| n.to_string(), lekalo_io::fmt_number),
        Value::String(s) => s.clone(),
        other => other.to_string(),
    }
}

/// Human-readable text of [`surface_info_json`] or [`pp_info_json`].
pub(crate) fn info_text(j: &Value) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "type            {} ({})",
        fmt(&j["name"]),
        fmt(&j["type"])
    );
    let _ = writeln!(s, "dimension       {}", j["dim"]);
    let bx = |b: &Value| format!("{} .. {}", fmt(&b["min"]), fmt(&b["max"]));
    let mults = |d: &Value| {
        d.as_array()
            .map(|a| {
                a.iter()
                    .map(|d| format!("{}×{}", fmt(&d["knot"]), d["multiplicity"]))
                    .collect::<Vec<_>>()
                    .join("  ")
            })
            .unwrap_or_default()
    };
    if j["type"] == "piecewise_polynomial" {
        let _ = writeln!(s, "order           {} (degree {})", j["order"], j["degree"]);
        let _ = writeln!(s, "pieces          {}", j["pieces"]);
        let _ = writeln!(s, "breakpoints     {}", fmt(&j["breakpoints"]));
        let c: Vec<String> = j["continuity"]
            .as_array()
            .map(|a| {
                a.iter()
                    .map(|c| format!("{}: {}", fmt(&c["breakpoint"]), fmt(&c["smoothness"])))
                    .collect()
            })
            .unwrap_or_default();
        let _ = writeln!(s, "continuity      {}", c.join("  "));
        let _ = writeln!(s, "domain          {}", fmt(&j["domain"]));
        let _ = writeln!(
            s,
            "start, end      {}, {}",
            fmt(&j["start"]),
            fmt(&j["end"])
        );
    } else {
        let _ = writeln!(
            s,
            "degree          {} (order {})",
            fmt(&j["degree"]),
            fmt(&j["order"])
        );
        let _ = writeln!(s, "net             {}", fmt(&j["net"]));
        if j["rational"] == Value::Bool(true) {
            let _ = writeln!(s, "weights         {}", fmt(&j["weights"]));
        }
        let _ = writeln!(s, "knots u         {}", fmt(&j["knots_u"]));
        let _ = writeln!(s, "multiplicities  {}", mults(&j["distinct_knots_u"]));
        let _ = writeln!(s, "knots v         {}", fmt(&j["knots_v"]));
        let _ = writeln!(s, "multiplicities  {}", mults(&j["distinct_knots_v"]));
        let _ = writeln!(s, "domain          {}", fmt(&j["domain"]));
        let _ = writeln!(s, "control box     {}", bx(&j["control_box"]));
    }
    let _ = writeln!(s, "sampled box     {}", bx(&j["sampled_box"]));
    s
}

/// `n` evenly spaced parameters in `[a, b]` (the last exactly `b`) and the pp's values there.
fn pp_samples(p: &PiecewisePolynomial, n: usize) -> lekalo::Result<(Vec<f64>, Points)> {
    let n = n.max(2);
    let (a, b) = p.domain();
    let xs: Vec<f64> = (0..n)
        .map(|i| {
            if i + 1 == n {
                b
            } else {
                a + (b - a) * (i as f64) / ((n - 1) as f64)
            }
        })
        .collect();
    let mut data = vec![0.0; n * p.dim()];
    for (x, out) in xs.iter().zip(data.chunks_exact_mut(p.dim())) {
        p.eval_into(*x, out)?;
    }
    Ok((xs, Points::from_flat(p.dim(), data)?))
}

/// CSV of `n` samples of a pp: `x,f` (one column per component `f0, f1, …` for dim > 1).
pub(crate) fn pp_csv(p: &PiecewisePolynomial, n: usize) -> lekalo::Result<String> {
    let (xs, pts) = pp_samples(p, n)?;
    let mut s = String::from("x");
    if p.dim() == 1 {
        s.push_str(",f");
    } else {
        for d in 0..p.dim() {
            let _ = write!(s, ",f{d}");
        }
    }
    s.push('\n');
    for (x, q) in xs.iter().zip(pts.iter()) {
        let _ = write!(s, "{x}");
        for c in q {
            let _ = write!(s, ",{c}");
        }
        s.push('\n');
    }
    Ok(s)
}

/// Graph of a pp: each component against `x`, with the breakpoints marked.
pub(crate) fn pp_figure(p: &PiecewisePolynomial, n: usize, title: Option<&str>) -> Result<Figure> {
    let (xs, pts) = pp_samples(p, n)?;
    let mut fig = Figure::new(title.unwrap_or("piecewise polynomial"), false);
    fig.axis_labels = ("x".into(), "f(x)".into());
    for d in 0..p.dim() {
        let path: Vec<[f64; 2]> = xs.iter().zip(pts.iter()).map(|(x, q)| [*x, q[d]]).collect();
        let label = if p.dim() == 1 {
            "f".to_string()
        } else {
            format!("f{d}")
        };
        fig.series.push(Series::new(
            Some(&label),
            path,
            Style::Line,
            PALETTE[d % PALETTE.len()],
        ));
    }
    let mut marks = Vec::new();
    for &x in p.breakpoints() {
        for q in p.eval(x)?.chunks(1) {
            marks.push([x, q[0]]);
        }
    }
    fig.series.push(Series::new(
        Some("breakpoints"),
        marks,
        Style::Markers,
        PALETTE[7],
    ));
    Ok(fig)
}

/// A surface drawn from an `n × n` grid of its points (shaded or as a wireframe, as `opts`
/// say), with its control net if `net`.
pub(crate) fn surface_figure(
    s: &Surface,
    n: usize,
    net: bool,
    opts: &SurfacePlot,
) -> Result<Figure> {
    let side = n.clamp(2, 1000);
    let (pts, _) = s.sample_grid(side, side, false)?;
    let grid = Grid::new(side, side, s.dim(), &pts)?;
    let ctrl = s.control_points();
    let (nu, nv) = s.net_size();
    let net = if net {
        Some(Grid::new(nu, nv, ctrl.dim(), ctrl.as_slice())?)
    } else {
        None
    };
    Ok(surface_plot(&grid, net.as_ref(), opts))
}

/// OBJ tessellation of a surface on an `n × n` grid, normals from the surface's `normal(u, v)`.
pub(crate) fn surface_obj(s: &Surface, n: usize) -> Result<String> {
    if s.dim() != 3 {
        return bad_input(format!(
            "OBJ output needs a surface in 3-D; this {} has dimension {}",
            s.display_name(),
            s.dim()
        ));
    }
    let side = n.clamp(2, 1000);
    let (pts, normals) = s.sample_grid(side, side, true)?;
    let normals = normals.unwrap_or_default();
    let grid = Grid::new(side, side, 3, &pts)?;
    let ngrid = Grid::new(side, side, 3, &normals)?;
    Ok(grid_to_obj(&grid, Some(&ngrid))?)
}

/// One-object STEP file of a surface.
pub(crate) fn surface_step(s: &Surface, name: &str, timestamp: &str) -> Result<String> {
    let mut w = StepWriter::new(name);
    w.add_any_surface(s)?;
    Ok(w.finish(timestamp))
}

/// `convert` of a surface or pp-form to `format`, `samples` controlling tessellation/sampling.
pub(crate) fn convert(
    shape: &Shape,
    format: &str,
    samples: usize,
    step_name: &str,
    timestamp: &str,
) -> Result<Vec<u8>> {
    let plot = |fig: &Figure| crate::output::encode(fig, format, 2.0);
    match (shape, format) {
        (_, "json") => Ok(shape.to_json_pretty().into_bytes()),
        (Shape::Surface(s), "step") => Ok(surface_step(s, step_name, timestamp)?.into_bytes()),
        (Shape::Surface(s), "obj") => Ok(surface_obj(s, samples_side(samples))?.into_bytes()),
        (Shape::Surface(s), "svg" | "png") => plot(&surface_figure(
            s,
            samples_side(samples),
            false,
            &SurfacePlot::new(s.display_name()),
        )?),
        (Shape::Pp(p), "csv") => Ok(pp_csv(p, samples)?.into_bytes()),
        (Shape::Pp(p), "svg" | "png") => plot(&pp_figure(p, samples, None)?),
        (Shape::Tensor(t), "npz") => Ok(lekalo_io::tensor_to_npz(t)?),
        (Shape::Tensor(t), other) => bad_input(format!(
            "a spline in {} parameters converts to json or npz, not \"{other}\"",
            t.n_vars()
        )),
        (Shape::Surface(_), other) => bad_input(format!(
            "a surface converts to json, csv, step, obj, svg or png, not \"{other}\""
        )),
        (_, other) => bad_input(format!(
            "a {} converts to json, csv, svg or png, not \"{other}\"",
            shape.type_name()
        )),
    }
}

/// Grid side for a sample count: `--samples 200` means a 200-point polyline for curves but
/// would be 40 000 surface points; a surface gets `√samples` per direction, at least 8.
fn samples_side(samples: usize) -> usize {
    samples.isqrt().max(8)
}

/// True when `convert` is asked for CSV (by `--to` or the output's extension).
pub(crate) fn surface_csv_wanted(to: Option<&str>, out: Option<&std::path::Path>) -> bool {
    crate::output::format_of(to, out, "json") == "csv"
}
