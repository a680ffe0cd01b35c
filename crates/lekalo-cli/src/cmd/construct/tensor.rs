//! Tensor-product splines in `N ≥ 3` parameters in the CLI: `interpolate --grid AxBxC…`
//! (and the grids of any size whose knots are given per direction), `eval` at points and
//! `info` of a `bspline_tensor` / `nurbs_tensor` file. Parsing and
//! presentation only; the spline work is the library's ([`lekalo::TensorInterpolation`],
//! [`lekalo::Tensor`]).

use std::cmp::Ordering;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use anyhow::Result;
use lekalo::fit::check_schoenberg_whitney;
use lekalo::vocabulary::EndKind;
use lekalo::{
    EndCondition, KnotPlacement, KnotVector, Parametrization, Points, Tensor, TensorBSpline,
    TensorInterpolation,
};
use serde_json::{json, Value};

use crate::cmd::fit_args::clamped;
use crate::context::Context;
use crate::exit::{bad_input, BadInput};
use crate::output::{emit, format_of};
use crate::values::numbers;

/// The factors of a `--grid` size `AxBxC…` (also `×`), each at least 1.
pub(crate) fn grid_factors(text: &str) -> Result<Vec<usize>> {
    size_factors(text, "--grid")
}

/// The factors of a size `AxBxC…` (also `×`) given to `option` (`--grid`, `--net`), each at
/// least 1.
pub(crate) fn size_factors(text: &str, option: &str) -> Result<Vec<usize>> {
    text.split(['x', 'X', '×'])
        .map(|s| match s.trim().parse::<usize>() {
            Ok(n) if n >= 1 => Ok(n),
            _ => bad_input(format!(
                "{option}: \"{}\" in \"{text}\" is not a positive integer; write the size in each direction, e.g. 5x4x3",
                s.trim()
            )),
        })
        .collect()
}

/// The degree of each of `n` directions from `--degree` (one value for all, or one each).
pub(crate) fn degrees_for(degree: &[usize], n: usize) -> Result<Vec<usize>> {
    match degree.len() {
        1 => Ok(vec![degree[0]; n]),
        k if k == n => Ok(degree.to_vec()),
        k => bad_input(format!(
            "--degree: {k} degrees for a grid of {n} directions; give one degree, or one per direction (e.g. --degree {})",
            vec!["3"; n].join(",")
        )),
    }
}

/// A list given for one direction, with the option that gave it (for the messages).
pub(crate) type Given = Option<(String, Vec<f64>)>;

/// Lists given per direction of a grid: `--X-u` and `--X-v` (directions 1 and 2, as `fit`
/// spells them) and `--X-in K=LIST` (direction `K`, counted from 1 as the columns `x1 … xN`
/// of `eval`), for the knots (`X` = `knots`) or the parameters (`X` = `params`).
#[derive(Clone, Copy, Default)]
pub(crate) struct GridLists<'a> {
    pub(crate) u: Option<&'a str>,
    pub(crate) v: Option<&'a str>,
    pub(crate) per_direction: &'a [String],
}

impl GridLists<'_> {
    /// Whether any direction's list is given.
    pub(crate) fn any(&self) -> bool {
        self.u.is_some() || self.v.is_some() || !self.per_direction.is_empty()
    }

    /// The files among the lists (a list may be the name of a file of one value a line), so
    /// that the output is never written over one of them.
    pub(crate) fn files(&self) -> Vec<PathBuf> {
        let entries = self
            .per_direction
            .iter()
            .filter_map(|e| e.split_once('=').map(|e| e.1));
        self.u
            .into_iter()
            .chain(self.v)
            .chain(entries)
            .map(Path::new)
            .filter(|p| p.is_file())
            .map(Path::to_path_buf)
            .collect()
    }
}

/// The direction `K` (from 1) and the list of `K=LIST` given to `option`.
pub(crate) fn direction_of<'t>(given: &'t str, option: &str) -> Result<(usize, &'t str)> {
    let Some((k, list)) = given.split_once('=') else {
        return bad_input(format!(
            "{option}: \"{given}\" is not K=LIST; give the direction (from 1) and its list, \
             e.g. {option} 3=0.25,0.5"
        ));
    };
    match k.trim().parse::<usize>() {
        Ok(k) if k >= 1 => Ok((k, list)),
        _ => bad_input(format!(
            "{option}: \"{}\" in \"{given}\" is not a direction number (from 1)",
            k.trim()
        )),
    }
}

/// A list per direction of `n`: from `lists.u` (direction 1), `lists.v` (direction 2) and its
/// `K=LIST` entries, named by the options `(u, v, per direction)` and the `noun` they give
/// (`knots`, `parameters`), read by `read(text, option)`; `None` where none is given.
pub(crate) fn per_direction(
    n: usize,
    lists: GridLists<'_>,
    (u_option, v_option, k_option): (&str, &str, &str),
    noun: &str,
    read: impl Fn(&str, &str) -> Result<Vec<f64>>,
) -> Result<Vec<Given>> {
    let mut out: Vec<Given> = vec![None; n];
    let mut put = |k: usize, option: String, text: &str| -> Result<()> {
        if k > n {
            return bad_input(format!(
                "{option}: the spline has {n} directions, numbered 1 to {n} (x1 … x{n}; in a \
                 grid file, x1 is the slowest)"
            ));
        }
        if let Some((first, _)) = &out[k - 1] {
            return bad_input(format!(
                "{option}: direction {k} already has {noun} from {first}; give each \
                 direction's {noun} once"
            ));
        }
        out[k - 1] = Some((option.clone(), read(text, &option)?));
        Ok(())
    };
    if let Some(t) = lists.u {
        put(1, u_option.into(), t)?;
    }
    if let Some(t) = lists.v {
        put(2, v_option.into(), t)?;
    }
    for given in lists.per_direction {
        let (k, list) = direction_of(given, k_option)?;
        put(k, format!("{k_option} {k}"), list)?;
    }
    Ok(out)
}

/// The interior knots given per direction (`--knots-u`, `--knots-v`, `--knots-in K=LIST`;
/// an empty list is a direction without interior knots).
pub(crate) fn given_knots(n: usize, lists: GridLists<'_>) -> Result<Vec<Given>> {
    let read = |text: &str, option: &str| {
        if text.trim().is_empty() {
            Ok(Vec::new())
        } else {
            numbers(text, option)
        }
    };
    let options = ("--knots-u", "--knots-v", "--knots-in");
    per_direction(n, lists, options, "knots", read)
}

/// The grid parameters given per direction (`--params-u`, `--params-v`, `--params-in
/// K=LIST|FILE`: a list or a file of one value a line), each checked to hold one strictly
/// increasing parameter per grid value of its direction of `shape` (`--grid grid`).
pub(crate) fn given_parameters(
    lists: GridLists<'_>,
    shape: &[usize],
    grid: &str,
    cx: &Context,
) -> Result<Vec<Given>> {
    let options = ("--params-u", "--params-v", "--params-in");
    let read = |text: &str, option: &str| crate::cmd::explicit::parameters(cx, text, option);
    let given = per_direction(shape.len(), lists, options, "parameters", read)?;
    for (i, entry) in given.iter().enumerate() {
        let Some((option, t)) = entry else { continue };
        if t.len() != shape[i] {
            return bad_input(format!(
                "{option}: {} values for the {} grid values of direction {} (--grid {grid}); \
                 give one parameter per grid line",
                t.len(),
                shape[i],
                i + 1
            ));
        }
        if let Some(w) = t
            .windows(2)
            .position(|w| w[0].partial_cmp(&w[1]) != Some(Ordering::Less))
        {
            return bad_input(format!(
                "{option}: parameters {} and {} of direction {} are not increasing; give \
                 strictly increasing parameters",
                t[w],
                t[w + 1],
                i + 1
            ));
        }
    }
    Ok(given)
}

/// The parameters of every direction of a grid: those given, and for the others those of
/// `interp`'s parametrisation averaged over the grid's lines
/// ([`TensorInterpolation::grid_parameters`], whose failure names `--param`).
pub(crate) fn grid_parameters(
    interp: &TensorInterpolation,
    given: Vec<Given>,
    values: &Points,
    shape: &[usize],
) -> Result<Vec<Vec<f64>>> {
    let averaged = if given.iter().any(Option::is_none) {
        interp
            .grid_parameters(values.as_view(), shape)
            .map_err(|e| {
                BadInput(format!(
                    "--param (the parameters of the grid's directions without --params-u, \
                     --params-v or --params-in): {e}"
                ))
            })?
    } else {
        Vec::new()
    };
    Ok(given
        .into_iter()
        .enumerate()
        .map(|(i, entry)| entry.map_or_else(|| averaged[i].clone(), |(_, t)| t))
        .collect())
}

/// The tensor spline of `interp` through a grid of `values` at the parameters and with the
/// interior knots given in some directions: the other directions' parameters are the
/// library's ([`grid_parameters`]), each given direction's knot vector is clamped at the ends
/// of its parameters, and its Schoenberg–Whitney condition is checked direction by direction
/// so that a failure names the option and the direction.
pub(crate) fn interpolate_given(
    interp: TensorInterpolation,
    degrees: &[usize],
    values: &Points,
    (grid, shape): (&str, &[usize]),
    (knots, params): (GridLists<'_>, GridLists<'_>),
    cx: &Context,
) -> Result<TensorBSpline> {
    let given = given_knots(shape.len(), knots)?;
    let given_params = given_parameters(params, shape, grid, cx)?;
    if given.iter().chain(&given_params).all(Option::is_none) {
        return Ok(interp.interpolate(values.as_view(), shape)?);
    }
    let params = grid_parameters(&interp, given_params, values, shape)?;
    let mut vectors = Vec::with_capacity(shape.len());
    for (a, entry) in given.into_iter().enumerate() {
        let Some((option, inner)) = entry else {
            vectors.push(None);
            continue;
        };
        let (m, p, k) = (shape[a], degrees[a], a + 1);
        if p == 0 || p >= m {
            return bad_input(format!(
                "--degree: direction {k} has {m} grid values and takes a degree from 1 to {}",
                m - 1
            ));
        }
        let needed = m - p - 1;
        if inner.len() != needed {
            return bad_input(format!(
                "{option}: {} interior knots for the {m} grid values of direction {k} at degree \
                 {p}; an interpolant takes values − degree − 1 = {needed}",
                inner.len()
            ));
        }
        let t = &params[a];
        let range = (t[0], t[m - 1]);
        let within = format!("the parameters of direction {k}");
        let kv: KnotVector = clamped(p, range, &inner, &option, &within)?;
        check_schoenberg_whitney(t, p, &kv).map_err(|e| {
            let grid: Vec<String> = t.iter().map(|x| format!("{x:.4}")).collect();
            BadInput(format!(
                "{option} (direction {k}, grid parameters {}): {e}",
                grid.join(",")
            ))
        })?;
        vectors.push(Some(kv));
    }
    let refs: Vec<&[f64]> = params.iter().map(Vec::as_slice).collect();
    Ok(interp
        .knot_vectors(vectors)
        .interpolate_at(&refs, values.as_view())?)
}

/// What `interpolate --grid` asks (a surface grid's factors too, when it gives `--end`,
/// `--knots`, or knots or parameters per direction).
pub(crate) struct GridInterpolation<'a> {
    pub(crate) grid: &'a str,
    pub(crate) factors: Vec<usize>,
    pub(crate) degree: &'a [usize],
    pub(crate) param: Parametrization,
    /// `--knots`, the knot placement of every direction.
    pub(crate) placement: KnotPlacement,
    /// `--end`, the end condition of every direction.
    pub(crate) end: EndKind,
    pub(crate) max_condition: Option<f64>,
    pub(crate) knots: GridLists<'a>,
    pub(crate) params: GridLists<'a>,
    pub(crate) output: Option<&'a Path>,
    pub(crate) to: Option<&'a str>,
}

/// The tensor spline through the values of `file` (one row a grid node, the first direction
/// slowest), written as JSON.
pub(crate) fn interpolate(g: &GridInterpolation<'_>, file: &Path, cx: &Context) -> Result<()> {
    let n = g.factors.len();
    crate::output::objects::tensor_format(n, g.to, g.output)?;
    let degrees = degrees_for(g.degree, n)?;
    let interp = grid_interpolation(&degrees, g)?;
    let values = checked_grid_values(g.grid, &g.factors, file, cx)?;
    let s = interpolate_given(
        interp,
        &degrees,
        &values,
        (g.grid, &g.factors),
        (g.knots, g.params),
        cx,
    )
    .map_err(|e| match e.downcast::<lekalo::Error>() {
        Ok(e @ lekalo::Error::Degree { .. }) => {
            BadInput(format!("--degree (grid {}): {e}", g.grid)).into()
        }
        Ok(other) => anyhow::Error::from(other),
        Err(other) => other,
    })?;
    let mut inputs = vec![file.to_path_buf()];
    inputs.extend(g.params.files());
    crate::output::objects::write_tensor(&Tensor::BSpline(s), (g.to, g.output), &inputs, cx)
}

/// The interpolation of a grid in every number of directions (surfaces included) with the
/// degrees `degrees` and `g`'s parametrisation, knot placement, end condition (free, natural
/// or periodic, the same in every direction) and condition limit.
pub(crate) fn grid_interpolation(
    degrees: &[usize],
    g: &GridInterpolation<'_>,
) -> Result<TensorInterpolation> {
    let n = degrees.len();
    let end = match g.end {
        EndKind::Free | EndKind::Natural | EndKind::Periodic => g.end.condition(None, None)?,
        EndKind::Derivatives | EndKind::Second => {
            return bad_input(
                "--end: a grid (--grid) takes free, natural or periodic ends (end derivatives would be \
                 a grid of values themselves); drop --end or choose one of these",
            )
        }
    };
    let periodic = end == EndCondition::Periodic;
    if periodic && (g.knots.any() || g.params.any()) {
        return bad_input(
            "--end periodic places the knots and parameters of every direction itself; drop \
             --knots-u/--knots-v/--knots-in and --params-u/--params-v/--params-in",
        );
    }
    let mut interp = TensorInterpolation::new(degrees.to_vec())
        .parametrization(g.param)
        .knot_placements(vec![g.placement; n])
        .end_conditions(vec![end; n]);
    if let Some(limit) = g.max_condition {
        interp = interp.max_condition(limit);
    }
    Ok(interp)
}

/// The values of the grid `grid` (`factors`) in `file`, their count checked against the grid's
/// (which is refused above the size limit before the file is read).
pub(crate) fn checked_grid_values(
    grid: &str,
    factors: &[usize],
    file: &Path,
    cx: &Context,
) -> Result<Points> {
    checked_values(("--grid", grid), "grid nodes", factors, file, cx)
}

/// The number of nodes of the size `text` (`factors`) given to `option`, refused when it
/// overflows or is above `--max-size` (before anything of that size is allocated); `nodes`
/// names them in the messages (`grid nodes`, `control points`).
pub(crate) fn checked_nodes(
    (option, text): (&str, &str),
    nodes: &str,
    factors: &[usize],
    cx: &Context,
) -> Result<usize> {
    let Some(count) = factors
        .iter()
        .try_fold(1usize, |acc, &n| acc.checked_mul(n))
    else {
        return bad_input(format!(
            "{option} {text}: the number of {nodes} overflows; give a smaller size"
        ));
    };
    let limit = cx.max_size;
    if count > limit {
        return bad_input(format!(
            "{option} {text}: {count} {nodes}, above the size limit {limit}; give a smaller \
             size, or raise the limit with --max-size {count} if the machine has the memory"
        ));
    }
    Ok(count)
}

/// The rows of `file` for the nodes of the size `text` (`factors`) given to `option` (one row
/// a node, the first direction slowest, or a `.npy` array of that shape), their count checked
/// against the size's ([`checked_nodes`], before the file is read).
pub(crate) fn checked_values(
    (option, text): (&str, &str),
    nodes: &str,
    factors: &[usize],
    file: &Path,
    cx: &Context,
) -> Result<Points> {
    let count = checked_nodes((option, text), nodes, factors, cx)?;
    let (values, name) = grid_values(cx, file, factors)?;
    if values.len() != count {
        return bad_input(format!(
            "{option} {text}: {count} {nodes}, but {name} holds {} rows (one row per node, the first direction slowest)",
            values.len()
        ));
    }
    Ok(values)
}

/// The values of a grid file: rows of a points file, or a `.npy` array of shape
/// `(A, B, C, …[, d…])` whose first axes are the grid's (or `(n, d)` / `(n,)` rows).
fn grid_values(cx: &Context, file: &Path, factors: &[usize]) -> Result<(Points, String)> {
    let npy = file
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("npy"));
    if !npy {
        return crate::items::read_points(cx, file);
    }
    let (bytes, name) = lekalo_io::read_input_bytes(file)?;
    let (shape, flat) = lekalo_io::read_npy_array(&bytes, &name)?;
    let n = factors.len();
    let dim = if shape.len() >= n && shape[..n] == *factors {
        shape[n..].iter().product::<usize>()
    } else {
        match shape[..] {
            [_] => 1,
            [_, d] => d,
            _ => {
                return bad_input(format!(
                    "{name}: shape {shape:?} is neither the grid's {factors:?} (with value axes after it) nor rows (n, d)"
                ))
            }
        }
    };
    Ok((Points::from_flat(dim.max(1), flat)?, name))
}

/// What `eval` asks of a tensor spline.
pub(crate) struct TensorEval<'a> {
    pub(crate) input: &'a Path,
    /// `--at x1,…,xN[,x1,…]`.
    pub(crate) at: Option<&'a str>,
    /// `--at-file FILE`: N columns.
    pub(crate) at_file: Option<&'a Path>,
    /// `--grid AxBxC…`: evenly spaced parameters over each direction's domain, every point
    /// of their outer product (after the points of `--at` and `--at-file`).
    pub(crate) grid: Option<&'a str>,
    pub(crate) format: Option<&'a str>,
    pub(crate) output: Option<&'a Path>,
}

/// Evaluates at the points of `--at` and `--at-file`, then on `--grid` (by the library's
/// evaluation on grids, which never forms the grid's points): columns `x1 … xN`, then the value
/// (`y`, or `y1 … yd`); written as CSV, JSON, `.npy` or a Parquet table.
pub(crate) fn eval(e: &TensorEval<'_>, t: &Tensor, cx: &Context) -> Result<()> {
    let n = t.n_vars();
    let mut xs = Vec::new();
    if let Some(at) = e.at {
        let p = numbers(at, "--at")?;
        if p.len() % n != 0 {
            return bad_input(format!(
                "--at: {} values for a spline in {n} parameters; give {n} coordinates a point",
                p.len()
            ));
        }
        xs.extend(p);
    }
    if let Some(f) = e.at_file {
        let (pts, name) = crate::items::read_points(cx, f)?;
        if pts.dim() != n {
            return bad_input(format!(
                "{name}: --at-file needs {n} columns, one per parameter; found {}",
                pts.dim()
            ));
        }
        xs.extend_from_slice(pts.as_slice());
    }
    let axes = match e.grid {
        Some(g) => grid_axes(t, g, cx)?,
        None => Vec::new(),
    };
    if xs.is_empty() && axes.is_empty() {
        return bad_input(format!(
            "{}: a spline in {n} parameters is evaluated at --at x1,…,x{n}, at the rows of --at-file FILE or on --grid {}",
            e.input.display(),
            vec!["5"; n].join("x")
        ));
    }
    let dim = t.dim();
    let on_grid: usize = if axes.is_empty() {
        0
    } else {
        axes.iter().map(Vec::len).product()
    };
    let m = xs.len() / n + on_grid;
    let option = if on_grid > 0 { "--grid" } else { "--at" };
    crate::context::check_memory::<f64>(m.saturating_mul(n + dim), option)?;
    let mut out = vec![0.0; m * dim];
    let (at_points, at_grid) = out.split_at_mut(xs.len() / n * dim);
    let failed = |err: lekalo::Error| BadInput(format!("{}: {err}", e.input.display()));
    t.eval_batch(&xs, at_points).map_err(failed)?;
    if on_grid > 0 {
        let lists: Vec<&[f64]> = axes.iter().map(Vec::as_slice).collect();
        t.eval_grid(&lists, at_grid).map_err(failed)?;
        xs.reserve_exact(on_grid * n);
        grid_points(&axes, &mut xs);
    }
    let mut columns: Vec<String> = (1..=n).map(|a| format!("x{a}")).collect();
    if dim == 1 {
        columns.push("y".into());
    } else {
        columns.extend((1..=dim).map(|k| format!("y{k}")));
    }
    let rows = xs.chunks_exact(n).zip(out.chunks_exact(dim));
    let bytes = match format_of(e.format, e.output, "csv").as_str() {
        "csv" => {
            let mut s = columns.join(",");
            s.push('\n');
            for (x, y) in rows {
                let cells: Vec<String> = x
                    .iter()
                    .chain(y)
                    .map(|&z| lekalo_io::fmt_number(z))
                    .collect();
                s.push_str(&cells.join(","));
                s.push('\n');
            }
            s.into_bytes()
        }
        "json" => {
            let rows: Vec<Vec<f64>> = rows.map(|(x, y)| [x, y].concat()).collect();
            format!("{:#}\n", json!({"columns": columns, "rows": rows})).into_bytes()
        }
        // the rows of the csv, columns x1 … xN then the values, as one (m, N + dim) array
        "npy" => {
            let flat: Vec<f64> = rows.flat_map(|(x, y)| x.iter().chain(y).copied()).collect();
            lekalo_io::npy_bytes(m, n + dim, &flat)?
        }
        "parquet" | "pq" => {
            let flat: Vec<f64> = rows.flat_map(|(x, y)| x.iter().chain(y).copied()).collect();
            lekalo_io::table_to_parquet(&columns, &flat)?
        }
        other => return bad_input(format!("--format {other}: use csv, json, npy or parquet")),
    };
    let inputs: Vec<PathBuf> = vec![e.input.to_path_buf()];
    emit(e.output, &bytes, &inputs, cx)
}

/// The parameters of `--grid AxBxC…`: one evenly spaced list a direction over its domain
/// (ends exact, [`lekalo::uniform_parameters`]), at most `--max-size` points in all.
fn grid_axes(t: &Tensor, grid: &str, cx: &Context) -> Result<Vec<Vec<f64>>> {
    let n = t.n_vars();
    let factors = grid_factors(grid)?;
    if factors.len() != n {
        return bad_input(format!(
            "--grid {grid}: {} sizes for a spline in {n} parameters; give one size a direction, e.g. --grid {}",
            factors.len(),
            vec!["5"; n].join("x")
        ));
    }
    let points = factors.iter().fold(1usize, |a, &m| a.saturating_mul(m));
    if points > cx.max_size {
        return bad_input(format!(
            "--grid {grid}: {points} points, above the size limit {}; raise the limit with --max-size {points} if the machine has the memory",
            cx.max_size
        ));
    }
    Ok(t.domain()
        .into_iter()
        .zip(&factors)
        .map(|((a, b), &m)| lekalo::uniform_parameters(a, b, m))
        .collect())
}

/// Appends the points of the grid `axes[0] × ⋯ × axes[N−1]` to `xs`, the first direction
/// slowest (the order of the library's evaluation on grids).
fn grid_points(axes: &[Vec<f64>], xs: &mut Vec<f64>) {
    let total: usize = axes.iter().map(Vec::len).product();
    let mut index = vec![0usize; axes.len()];
    for _ in 0..total {
        xs.extend(index.iter().zip(axes).map(|(&i, list)| list[i]));
        for a in (0..axes.len()).rev() {
            index[a] += 1;
            if index[a] < axes[a].len() {
                break;
            }
            index[a] = 0;
        }
    }
}

/// The facts `info` reports of a tensor spline.
pub(crate) fn info_json(t: &Tensor) -> Value {
    let control = t.control_points();
    let bbox = |p: &Points| {
        p.bounding_box()
            .map_or(Value::Null, |(lo, hi)| json!({"min": lo, "max": hi}))
    };
    let knots: Vec<&[f64]> = t.knots().iter().map(|k| k.as_slice()).collect();
    let domain: Vec<[f64; 2]> = t.domain().into_iter().map(|(a, b)| [a, b]).collect();
    json!({
        "type": lekalo_io::tensor_type_name(t),
        "parameters": t.n_vars(),
        "dim": t.dim(),
        "degrees": t.degrees(),
        "shape": t.shape(),
        "control_points": control.len(),
        "rational": t.weights().is_some(),
        "knots": knots,
        "domain": domain,
        "control_box": bbox(&control),
    })
}

/// The text form of [`info_json`].
pub(crate) fn info_text(j: &Value) -> String {
    let list = |v: &Value| {
        v.as_array()
            .map(|a| {
                a.iter()
                    .map(Value::to_string)
                    .collect::<Vec<_>>()
                    .join(" × ")
            })
            .unwrap_or_default()
    };
    // numbers as the other objects' info writes them (`[0, 1]`, not JSON's `[0.0, 1.0]`)
    let num = |v: &Value| {
        v.as_f64()
            .map_or_else(|| v.to_string(), lekalo_io::fmt_number)
    };
    let point = |v: &Value| {
        let xs: Vec<String> = v
            .as_array()
            .map(|a| a.iter().map(num).collect())
            .unwrap_or_default();
        format!("[{}]", xs.join(", "))
    };
    let mut s = String::new();
    let kind = if j["rational"].as_bool() == Some(true) {
        "NURBS"
    } else {
        "B-spline"
    };
    let _ = writeln!(
        s,
        "type            {kind} in {} variables ({})",
        j["parameters"],
        j["type"].as_str().unwrap_or("")
    );
    let _ = writeln!(s, "parameters      {}", j["parameters"]);
    let _ = writeln!(s, "dimension       {}", j["dim"]);
    let _ = writeln!(s, "degrees         {}", list(&j["degrees"]));
    let _ = writeln!(
        s,
        "net             {} = {} control points",
        list(&j["shape"]),
        j["control_points"]
    );
    let domain: Vec<String> = j["domain"]
        .as_array()
        .map(|a| {
            a.iter()
                .map(|d| format!("[{}, {}]", num(&d[0]), num(&d[1])))
                .collect()
        })
        .unwrap_or_default();
    let _ = writeln!(s, "domain          {}", domain.join(" × "));
    let _ = writeln!(
        s,
        "control box     {} .. {}",
        point(&j["control_box"]["min"]),
        point(&j["control_box"]["max"])
    );
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grid_factors_and_degrees() {
        assert_eq!(grid_factors("5x4×3").unwrap(), vec![5, 4, 3]);
        assert!(grid_factors("5x0x3").is_err());
        assert!(grid_factors("5xax3").is_err());
        assert_eq!(degrees_for(&[2], 3).unwrap(), vec![2, 2, 2]);
        assert_eq!(degrees_for(&[3, 3, 1], 3).unwrap(), vec![3, 3, 1]);
        let e = degrees_for(&[3, 1], 3).unwrap_err().to_string();
        assert!(e.contains("--degree"), "{e}");
    }
}
