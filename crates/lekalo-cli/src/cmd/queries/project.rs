//! `lekalo project`: closest points of query points on a curve or a surface.

use std::path::{Path, PathBuf};

use anyhow::Result;
use clap::Args;
use lekalo::Points;
use lekalo_io::{Object, Shape};
use serde_json::json;

use crate::cmd::measure::{query_curve, query_surface};
use crate::context::Context;
use crate::exit::{bad_input, BadInput};
use crate::output::emit;
use crate::values::numbers;

/// Arguments of `lekalo project`.
#[derive(Args, Debug)]
#[command(after_help = "\
Projects points onto a curve (any dimension) or a surface: the closest point, its parameter(s)
and distance. A batch of points comes from --points (CSV, whitespace columns or JSON, as for
`make`); batches run in parallel with results independent of the thread count. With --all TOL
every local minimum within TOL of the least distance is listed (one row each).

Output CSV: a header row, then the columns index (of the query point), t (or u, v), the closest
point's coordinates, distance: `index,t,x,y,distance` for a planar curve.

Examples:
  lekalo project curve.json --point 1,2
  lekalo project curve.json --points queries.csv -o closest.csv
  lekalo project curve.json --point 0,2 --all 1e-9 --json
  lekalo project surface.json --points queries.csv")]
pub(crate) struct ProjectArgs {
    /// Curve or surface file (JSON; `-` for standard input).
    input: PathBuf,
    /// One query point, comma-separated coordinates.
    #[arg(long, allow_hyphen_values = true)]
    point: Option<String>,
    /// File of query points (a batch).
    #[arg(long, value_name = "FILE")]
    points: Option<PathBuf>,
    /// List every local minimum within this distance of the least (curves only).
    #[arg(long, value_name = "TOL")]
    all: Option<f64>,
    /// Output JSON instead of CSV.
    #[arg(long)]
    json: bool,
    /// Output file (default: standard output).
    #[arg(short, long, value_name = "FILE")]
    output: Option<PathBuf>,
}

/// The closest point on the curve `obj` (read from `path`) of every point of `data` (read from
/// `data_path`), in parallel (`QueryCurve::project_batch`,
/// docs/theory/queries.md#closest-points).
pub(crate) fn closest_points(
    obj: &Object,
    path: &Path,
    data: &Points,
    data_path: &Path,
) -> Result<Points> {
    let q = query_curve(obj, path)?;
    if data.dim() != q.dim() {
        return bad_input(other_dimension(
            &format!("{}: the points are {}-D", data_path.display(), data.dim()),
            "curve",
            path,
            q.dim(),
        ));
    }
    let bad = |e: lekalo::Error| BadInput(format!("{}: {e}", path.display()));
    let feet = q.project_batch(data.as_view()).map_err(bad)?;
    Points::from_flat(q.dim(), feet.into_iter().flat_map(|r| r.point).collect())
        .map_err(|e| bad(e).into())
}

/// The message of query points (`what`: where they come from and their dimension) that are
/// not of the dimension `dim` of the `kind` (curve or surface) in `path`, with the fix.
fn other_dimension(what: &str, kind: &str, path: &Path, dim: usize) -> String {
    format!(
        "{what}, but the {kind} {} is {dim}-D: give points of {dim} coordinates ({}), or a {kind} \
         of the points' dimension",
        path.display(),
        lekalo_io::coord_names(dim).join(",")
    )
}

/// Refuses query points (`--point`, the rows of `--points`) not of the dimension `dim` of the
/// `kind` read from `a.input`, naming the option or file, both dimensions and the fix.
fn check_dimension(
    a: &ProjectArgs,
    single: &[f64],
    file: Option<&Points>,
    kind: &str,
    dim: usize,
) -> Result<()> {
    if !single.is_empty() && single.len() != dim {
        let given = a.point.as_deref().unwrap_or_default();
        return bad_input(other_dimension(
            &format!(
                "--point {given} has {} coordinate{}",
                single.len(),
                if single.len() == 1 { "" } else { "s" }
            ),
            kind,
            &a.input,
            dim,
        ));
    }
    if let (Some(pts), Some(path)) = (file, &a.points) {
        if pts.dim() != dim {
            return bad_input(other_dimension(
                &format!("{}: the points are {}-D", path.display(), pts.dim()),
                kind,
                &a.input,
                dim,
            ));
        }
    }
    Ok(())
}

pub(crate) fn run(a: &ProjectArgs, cx: &Context) -> Result<()> {
    let (text, name) = lekalo_io::read_input(&a.input)?;
    let shape = Shape::from_json_str(&text, &name)?;
    let mut rows: Vec<f64> = Vec::new();
    if let Some(p) = &a.point {
        rows.extend(numbers(p, "--point")?);
    }
    let file_points = match &a.points {
        Some(f) => {
            let (t, n) = lekalo_io::read_input(f)?;
            Some(lekalo_io::read_points(&t, &n)?)
        }
        None => None,
    };
    let bad = |e: lekalo::Error| BadInput(format!("{}: {e}", a.input.display()));
    let mut out_rows: Vec<(usize, Vec<f64>, Vec<f64>, f64)> = Vec::new();
    // the query points: --point first, then the rows of --points
    let mut pts = Vec::new();
    if !rows.is_empty() {
        pts.push(rows.clone());
    }
    if let Some(fp) = &file_points {
        pts.extend(fp.iter().map(<[f64]>::to_vec));
    }
    if pts.is_empty() && matches!(shape, Shape::Curve(_) | Shape::Surface(_)) {
        return bad_input("give --point or --points");
    }
    match shape {
        Shape::Curve(obj) => {
            let q = query_curve(&obj, &a.input)?;
            check_dimension(a, &rows, file_points.as_ref(), "curve", q.dim())?;
            if let Some(tol) = a.all {
                for (i, p) in pts.iter().enumerate() {
                    for r in q.project_all(p, tol).map_err(bad)? {
                        out_rows.push((i, vec![r.t], r.point, r.distance));
                    }
                }
            } else {
                let flat = Points::from_flat(q.dim(), pts.concat()).map_err(bad)?;
                for (i, r) in q
                    .project_batch(flat.as_view())
                    .map_err(bad)?
                    .into_iter()
                    .enumerate()
                {
                    out_rows.push((i, vec![r.t], r.point, r.distance));
                }
            }
        }
        Shape::Surface(s) => {
            let q = query_surface(&s, &a.input)?;
            check_dimension(a, &rows, file_points.as_ref(), "surface", q.dim())?;
            for (i, p) in pts.iter().enumerate() {
                let r = q.project(p).map_err(bad)?;
                out_rows.push((i, vec![r.uv.0, r.uv.1], r.point, r.distance));
            }
        }
        _ => {
            return bad_input(format!(
                "{}: project onto curves and surfaces",
                a.input.display()
            ))
        }
    }
    let text = if a.json {
        let j: Vec<_> = out_rows
            .iter()
            .map(|(i, par, p, d)| json!({"index": i, "parameters": par, "point": p, "distance": d}))
            .collect();
        format!("{:#}\n", json!(j))
    } else {
        // a header row, as `eval` writes: index, t (or u, v), the coordinates, distance
        let mut s = String::new();
        if let Some((_, par, p, _)) = out_rows.first() {
            let params: &[&str] = if par.len() == 1 { &["t"] } else { &["u", "v"] };
            let names: Vec<String> = std::iter::once("index")
                .chain(params.iter().copied())
                .map(String::from)
                .chain(lekalo_io::coord_names(p.len()))
                .chain(std::iter::once("distance".to_string()))
                .collect();
            s.push_str(&names.join(","));
            s.push('\n');
        }
        for (i, par, p, d) in &out_rows {
            let cols: Vec<String> = std::iter::once(i.to_string())
                .chain(par.iter().chain(p).copied().map(lekalo_io::fmt_number))
                .chain(std::iter::once(lekalo_io::fmt_number(*d)))
                .collect();
            s.push_str(&cols.join(","));
            s.push('\n');
        }
        s
    };
    emit(
        a.output.as_deref(),
        text.as_bytes(),
        std::slice::from_ref(&a.input),
        cx,
    )
}
