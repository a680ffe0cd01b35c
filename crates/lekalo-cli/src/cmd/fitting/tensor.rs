//! `lekalo fit --grid AxBxC…` and `--scattered` in three or more variables: least squares of a
//! tensor-product spline with given knots (or control-point counts) per direction, written as
//! `interpolate --grid` writes splines in `N` parameters, and `--grid AxB… --smooth` (two
//! directions or more), the smoothing spline on a grid. Parsing and presentation only; the
//! fits are the library's ([`lekalo::tensor_grid_least_squares`],
//! [`lekalo::tensor_grid_smoothing_spline`],
//! [`lekalo::tensor_scattered_penalized_least_squares`]).

use std::cmp::Ordering;
use std::path::PathBuf;

use anyhow::Result;
use lekalo::fit::{
    check_schoenberg_whitney, constrained_surface_grid_smoothing_condition,
    constrained_surface_grid_smoothing_spline, place_knots, Lambda, SurfaceShapeConstraints,
};
use lekalo::{
    tensor_grid_least_squares, tensor_grid_smoothing, tensor_grid_smoothing_spline,
    tensor_scattered_penalized_least_squares, tensor_scattered_smoothing, KnotLimit, KnotVector,
    PointsRef, RankDeficiency, ScatteredSmoothingOptions, Tensor, TensorBSpline,
    TensorGridSmoothingSpline, TensorInterpolation,
};
use serde_json::{json, Value};

use super::args::{clamped, smoothing_weights, span, with_ends, FitArgs};
use super::shapes::surface_shape_constraints;
use super::surface::table_of_grid;
use crate::cmd::tensor::{
    checked_grid_values, degrees_for, direction_of, given_knots, given_parameters, grid_factors,
    grid_parameters, Given,
};
use crate::context::Context;
use crate::exit::{bad_input, BadInput};
use crate::output::emit;

/// The number of variables of a tensor fit (three or more, or any number for `--scattered
/// --s` and `--grid --smooth`), or `None` for curves and surfaces: the factors of `--grid`; for `--scattered`, the
/// factors of `--ctrl-grid`, or else the last direction whose knots are given; for
/// `--scattered --s` without knots, the entries of `--degree` (two or more), or else the
/// intervals of `--bbox`, or else 2.
pub(super) fn variables(a: &FitArgs) -> Result<Option<usize>> {
    if let (Some(g), Some(_)) = (&a.grid, &a.smooth) {
        // the smoothing spline on a grid, surfaces included (lekalo::tensor_grid_smoothing_spline)
        return Ok(Some(grid_factors(g)?.len()));
    }
    if let (Some(g), Some(_), true) = (&a.grid, &a.s, a.shape_given()) {
        // a surface's smoothing condition in shape: the grid's smoothing spline
        // (lekalo::fit::constrained_surface_grid_smoothing_condition)
        return Ok(Some(grid_factors(g)?.len()));
    }
    let per_direction = !a.knots_in.is_empty() || !a.params_in.is_empty();
    let knots_given = a.ctrl_grid.is_some()
        || a.knots_u.is_some()
        || a.knots_v.is_some()
        || !a.knots_in.is_empty();
    if a.scattered && a.s.is_some() && !knots_given {
        let n = if a.degrees.len() > 1 {
            a.degrees.len()
        } else {
            a.bbox.as_deref().map_or(2, |b| b.split(',').count())
        };
        return Ok(Some(n));
    }
    let n = if let Some(g) = &a.grid {
        grid_factors(g)?.len()
    } else if a.scattered {
        match &a.ctrl_grid {
            Some(cg) => sizes(cg, "--ctrl-grid")?.len(),
            None => {
                let mut n =
                    usize::from(a.knots_u.is_some()).max(2 * usize::from(a.knots_v.is_some()));
                for given in &a.knots_in {
                    n = n.max(direction_of(given, "--knots-in")?.0);
                }
                n
            }
        }
    } else {
        return Ok(None);
    };
    if n >= 3 || (a.scattered && a.s.is_some()) {
        return Ok(Some(n.max(2)));
    }
    if per_direction {
        return bad_input(
            "--knots-in and --params-in are for fits in 3 or more variables (--grid AxBxC, or \
             --scattered with --ctrl-grid AxBxC); a surface takes --knots-u, --knots-v, \
             --params-u and --params-v",
        );
    }
    Ok(None)
}

/// The fit in `n ≥ 3` variables asked by `a`, written with its report.
pub(super) fn run(a: &FitArgs, n: usize, cx: &Context) -> Result<()> {
    let shapes = grid_shapes(a, n)?;
    refuse_curve_options(a, !shapes.is_empty())?;
    let (to, out) = (a.out.to.as_deref(), a.out.output.as_deref());
    if crate::output::objects::tensor_format(n, to, out)? == "npz" && a.json {
        return bad_input(
            "--json writes the spline with its report as JSON; drop --json to write the .npz",
        );
    }
    let degrees = degrees_for(&a.degrees, n)?;
    let counts = match &a.ctrl_grid {
        Some(cg) => {
            let c = sizes(cg, "--ctrl-grid")?;
            if c.len() != n {
                return bad_input(format!(
                    "--ctrl-grid {cg}: {} sizes for a fit in {n} variables; give one control-point \
                     count per direction (e.g. --ctrl-grid {})",
                    c.len(),
                    vec!["4"; n].join("x")
                ));
            }
            c.into_iter().map(Some).collect()
        }
        None => vec![None; n],
    };
    let inner: Vec<Given> = given_knots(n, a.grid_knots())?;
    let ranges = match &a.bbox {
        Some(b) => boxes(b, n)?.into_iter().map(Some).collect(),
        None => vec![None; n],
    };
    let dirs: Vec<Direction> = (0..n)
        .map(|k| Direction {
            k: k + 1,
            degree: degrees[k],
            inner: inner[k].clone(),
            count: counts[k],
            range: ranges[k],
        })
        .collect();
    if a.s.is_some() {
        if a.ctrl_grid.is_some() || dirs.iter().any(|d| d.inner.is_some()) {
            return bad_input(
                "--s places the knots of the smoothing itself (FITPACK's regrid on a grid, \
                 surfit on scattered data): drop --ctrl-grid and --knots-u/--knots-v/--knots-in",
            );
        }
    } else if a.smooth.is_none() {
        for d in &dirs {
            d.check_given()?;
        }
    }
    let mut inputs = vec![a.points.clone()];
    if a.penalty != 0.0 && (a.grid.is_some() || a.s.is_some()) {
        return bad_input(
            "--penalty smooths the least squares of scattered data on given knots (--scattered \
             with --ctrl-grid or knots); a grid's fit and --s take none: drop --penalty, or \
             use --s to smooth",
        );
    }
    if a.grid.is_some() {
        return run_grid(a, &dirs, &shapes, &inputs, cx);
    }
    let weights = match &a.weights {
        Some(p) => {
            let (t, name) = lekalo_io::read_input(p)?;
            inputs.push(p.clone());
            Some(lekalo_io::read_points(&t, &name)?.into_vec())
        }
        None => None,
    };
    run_scattered(a, &dirs, weights.as_deref(), &inputs, cx)
}

/// One direction of a tensor fit (`k` counted from 1): its degree, its interior knots given
/// (with the option that gave them) or its control-point count, and its `--bbox` interval.
struct Direction {
    k: usize,
    degree: usize,
    inner: Given,
    count: Option<usize>,
    range: Option<(f64, f64)>,
}

impl Direction {
    /// The option that sets this direction's knots, for messages.
    fn knots_option(&self) -> String {
        match (&self.inner, self.k) {
            (Some((option, _)), _) => option.clone(),
            (None, 1) => "--knots-u".into(),
            (None, 2) => "--knots-v".into(),
            (None, k) => format!("--knots-in {k}"),
        }
    }

    /// Knots or a count, and the two agreeing when both are given.
    fn check_given(&self) -> Result<()> {
        let (k, p) = (self.k, self.degree);
        match (&self.inner, self.count) {
            (None, None) => bad_input(format!(
                "direction {k} has neither knots nor a control-point count; give --ctrl-grid \
                 (one count per direction) or its interior knots ({})",
                self.knots_option()
            )),
            (Some((option, t)), Some(c)) if t.len() + p + 1 != c => bad_input(format!(
                "--ctrl-grid and {option} disagree: {} interior knots of degree {p} make {} \
                 control points in direction {k}, not {c}; drop one of them",
                t.len(),
                t.len() + p + 1
            )),
            _ => Ok(()),
        }
    }

    /// The domain of this direction: `--bbox` (which must hold `lo..hi`, the data's range,
    /// named `what`) or the data's range.
    fn domain(&self, (lo, hi): (f64, f64), what: &str) -> Result<(f64, f64)> {
        match self.range {
            Some((a, b)) if a > lo || b < hi => bad_input(format!(
                "--bbox: the {what} run from {lo} to {hi}, outside {a}:{b}, the interval of \
                 direction {}; give one around them, e.g. {}:{}",
                self.k,
                a.min(lo),
                b.max(hi)
            )),
            Some(r) => Ok(r),
            None => Ok((lo, hi)),
        }
    }

    /// The clamped knot vector on `range` from the interior knots given, or from
    /// `place(count)`.
    fn knots(
        &self,
        range: (f64, f64),
        place: impl FnOnce(usize) -> Result<KnotVector>,
    ) -> Result<KnotVector> {
        match (&self.inner, self.count) {
            (Some((option, t)), _) => {
                let within = if self.range.is_some() {
                    format!("--bbox, direction {}", self.k)
                } else {
                    format!("the range of direction {}'s data, or --bbox", self.k)
                };
                clamped(self.degree, range, t, option, &within)
            }
            (None, Some(c)) => place(c),
            (None, None) => self
                .check_given()
                .and_then(|()| bad_input(format!("direction {} needs knots or a count", self.k))),
        }
    }
}

/// Least squares on the grid of `a.grid`: its values one row per node, the first direction
/// slowest (or a `.npy` array), at the parameters given (`--params-u`, `--params-v`,
/// `--params-in K=LIST`) or those of `--param` averaged over the grid's lines.
fn run_grid(
    a: &FitArgs,
    dirs: &[Direction],
    shapes: &SurfaceShapeConstraints,
    inputs: &[PathBuf],
    cx: &Context,
) -> Result<()> {
    if a.weights.is_some() {
        return bad_input(
            "--weights is for scattered data; a grid's least squares weighs every node alike \
             (give the grid as --scattered rows to weigh them)",
        );
    }
    let g = a.grid.as_deref().unwrap_or_default();
    let shape = grid_factors(g)?;
    let degrees: Vec<usize> = dirs.iter().map(|d| d.degree).collect();
    let values = checked_grid_values(g, &shape, &a.points, cx)?;
    let given = given_parameters(a.grid_params(), &shape, g, cx)?;
    if !shapes.is_empty() {
        return run_grid_in_shape(a, dirs, shapes, (&values, given, &shape), inputs, cx);
    }
    let interp = TensorInterpolation::new(degrees.clone()).parametrization(a.grid_param());
    let params = grid_parameters(&interp, given, &values, &shape)?;
    let refs: Vec<&[f64]> = params.iter().map(Vec::as_slice).collect();
    let mut extra = None;
    let (s, net) = if let Some(sm) = &a.smooth {
        let f = smoothing_spline_on_grid(a, dirs, sm, &refs, &values)?;
        extra =
            Some(json!({ "lambda": f.lambdas, "gcv": finite_or_null(f.gcv), "trace": f.trace }));
        let net = f.spline.shape().to_vec();
        (f.spline, net)
    } else if let Some(target) = a.s {
        // the fewest knots whose residual is at most S (lekalo::tensor_grid_smoothing)
        let bbox = dirs
            .iter()
            .zip(&params)
            .map(|(d, t)| {
                d.domain(
                    (t[0], t[t.len() - 1]),
                    &format!("parameters of direction {}", d.k),
                )
            })
            .collect::<Result<Vec<_>>>()?;
        let f = tensor_grid_smoothing(&refs, values.as_view(), &degrees, target, Some(&bbox))?;
        let net = f.spline.shape().to_vec();
        (f.spline, net)
    } else {
        least_squares_on_grid(dirs, &params, &refs, &values, &degrees)?
    };
    // the residual of each node: the fitted spline evaluated on the grid against the values
    let mut fitted = vec![0.0; values.as_slice().len()];
    s.eval_grid(&refs, None, &mut fitted)?;
    let residuals: Vec<f64> = fitted
        .chunks_exact(values.dim())
        .zip(values.iter())
        .map(|(f, q)| {
            f.iter()
                .zip(q)
                .map(|(x, y)| (x - y) * (x - y))
                .sum::<f64>()
                .sqrt()
        })
        .collect();
    let rss = residuals.iter().map(|r| r * r).sum::<f64>();
    finish_with(a, &s, &net, &residuals, rss, extra, inputs, cx)
}

/// `--smooth` on a grid: the cubic smoothing spline with a knot at every grid line and the
/// weights λ given or chosen by GCV (`lekalo::tensor_grid_smoothing_spline`).
fn smoothing_spline_on_grid(
    a: &FitArgs,
    dirs: &[Direction],
    sm: &str,
    refs: &[&[f64]],
    values: &lekalo::Points,
) -> Result<TensorGridSmoothingSpline> {
    check_smoothing_space(a, dirs, "--smooth")?;
    let lambdas = grid_weights(dirs, sm)?;
    Ok(tensor_grid_smoothing_spline(
        refs,
        values.as_view(),
        &lambdas,
    )?)
}

/// The space of the grid's smoothing spline (cubic, a knot at every grid line) is the only one
/// `--smooth` (and `--s` in shape) fits on: no knots, count, box or other degree.
fn check_smoothing_space(a: &FitArgs, dirs: &[Direction], mode: &str) -> Result<()> {
    if a.ctrl_grid.is_some() || dirs.iter().any(|d| d.inner.is_some() || d.range.is_some()) {
        return bad_input(format!(
            "{mode} on a grid fits the cubic smoothing spline with a knot at every grid line: \
             drop --ctrl-grid, --bbox and --knots-u/--knots-v/--knots-in"
        ));
    }
    if let Some(d) = dirs.iter().find(|d| d.degree != 3) {
        return bad_input(format!(
            "--degree: {mode} on a grid fits cubic splines (the smoothing spline of each \
             direction), not degree {} in direction {}; drop --degree",
            d.degree, d.k
        ));
    }
    Ok(())
}

/// The shape constraints of a fit in `n` variables: those of a surface's grid smoothed by
/// `--smooth` or `--s` (`lekalo::fit::constrained_surface_grid_smoothing_spline`); refused
/// with the reason for any other fit routed here.
fn grid_shapes(a: &FitArgs, n: usize) -> Result<SurfaceShapeConstraints> {
    if !a.shape_given() {
        return Ok(SurfaceShapeConstraints::new());
    }
    if a.grid.is_some() && n == 2 && (a.smooth.is_some() || a.s.is_some()) {
        return surface_shape_constraints(a);
    }
    if a.scattered && a.s.is_some() {
        return bad_input(
            "--s on scattered rows places FITPACK's knots (surfit) and keeps no shape \
             constraints; to smooth scattered rows in shape give the net (--ctrl-grid NUxNV or \
             --knots-u/--knots-v) with --penalty W instead of --s",
        );
    }
    bad_input(format!(
        "shape constraints keep surfaces z(u, v) (--grid NUxNV or --scattered rows u, v, z); a \
         fit in {n} variables takes none: drop --increasing, --decreasing, --min, --max"
    ))
}

/// A surface's grid smoothed in shape: the table `z(u, v)` the grid holds (rows `u, v, z`, or
/// one value per node at `--params-u`, `--params-v`, as least squares in shape reads it), its
/// smoothing spline that keeps `shapes` (`--smooth` with λ given or by GCV,
/// `lekalo::fit::constrained_surface_grid_smoothing_spline`; or `--s S`, the weights scaled
/// from GCV's until the residual is S, `lekalo::fit::constrained_surface_grid_smoothing_condition`),
/// and the report of its residuals at the nodes.
fn run_grid_in_shape(
    a: &FitArgs,
    dirs: &[Direction],
    shapes: &SurfaceShapeConstraints,
    (values, given, shape): (&lekalo::Points, Vec<Given>, &[usize]),
    inputs: &[PathBuf],
    cx: &Context,
) -> Result<()> {
    let g = a.grid.as_deref().unwrap_or_default();
    let [gu, gv] = [0, 1].map(|k| given.get(k).cloned().flatten().map(|(_, t)| t));
    let (uu, vv, z) = table_of_grid(values, (shape[0], shape[1]), gu, gv, g)?;
    let f = match &a.smooth {
        Some(sm) => {
            check_smoothing_space(a, dirs, "--smooth")?;
            let w = grid_weights(dirs, sm)?;
            constrained_surface_grid_smoothing_spline(
                z.as_view(),
                (&uu, &vv),
                [w[0], w[1]],
                shapes,
            )?
        }
        None => {
            check_smoothing_space(a, dirs, "--s with shape constraints")?;
            let target = a.s.unwrap_or_default();
            constrained_surface_grid_smoothing_condition(z.as_view(), (&uu, &vv), target, shapes)?
        }
    };
    let described: Vec<String> = (0..shapes.len()).map(|i| shapes.describe(i)).collect();
    let extra = json!({ "lambda": f.lambdas, "constraints": described });
    let net = [f.surface.net_size().0, f.surface.net_size().1];
    let s = TensorBSpline::from_surface(&f.surface);
    let mut fitted = vec![0.0; z.len()];
    s.eval_grid(&[&uu, &vv], None, &mut fitted)?;
    let residuals: Vec<f64> = fitted
        .iter()
        .zip(z.as_slice())
        .map(|(f, y)| (f - y).abs())
        .collect();
    finish_with(a, &s, &net, &residuals, f.residual, Some(extra), inputs, cx)
}

/// The weights of `--smooth` for the directions of a grid: one for all or one per direction.
fn grid_weights(dirs: &[Direction], sm: &str) -> Result<Vec<Lambda>> {
    let n = dirs.len();
    let weights = smoothing_weights(sm)?;
    let lambdas = match weights.len() {
        1 => vec![weights[0]; n],
        k if k == n => weights,
        k => {
            return bad_input(format!(
                "--smooth: {k} weights for a grid of {n} directions; give one for all, or one \
                 per direction (e.g. --smooth {})",
                vec!["gcv"; n].join(",")
            ))
        }
    };
    Ok(lambdas)
}

/// A JSON number, or `null` for `±∞` and NaN (a GCV score within rounding of `0/0`).
fn finite_or_null(v: f64) -> Value {
    if v.is_finite() {
        json!(v)
    } else {
        Value::Null
    }
}

/// Least squares on the grid with the knots (or control-point counts) of each direction.
fn least_squares_on_grid(
    dirs: &[Direction],
    params: &[Vec<f64>],
    refs: &[&[f64]],
    values: &lekalo::Points,
    degrees: &[usize],
) -> Result<(TensorBSpline, Vec<usize>)> {
    let n = dirs.len();
    let mut knots = Vec::with_capacity(n);
    let mut net = Vec::with_capacity(n);
    for (d, t) in dirs.iter().zip(params) {
        let (m, p, k) = (t.len(), d.degree, d.k);
        if p >= m {
            return bad_input(format!(
                "--degree: direction {k} has {m} grid values and takes a degree below {m}"
            ));
        }
        let range = d.domain((t[0], t[m - 1]), &format!("parameters of direction {k}"))?;
        let option = match (&d.inner, d.count) {
            (None, Some(_)) => "--ctrl-grid".to_string(),
            _ => d.knots_option(),
        };
        let count = d.count.unwrap_or(0);
        if d.inner.is_none() && count > m {
            return bad_input(format!(
                "--ctrl-grid: {count} control points in direction {k}, more than its {m} grid \
                 values; give at most {m}"
            ));
        }
        let kv = d.knots(range, |c| with_ends(&place_knots(t, p, c)?, p, range))?;
        let c = kv.len() - p - 1;
        if c > m {
            return bad_input(format!(
                "{option}: {} interior knots of degree {p} make {c} control points in direction \
                 {k}, more than its {m} grid values; give at most {} interior knots",
                c - p - 1,
                m - p - 1
            ));
        }
        check_schoenberg_whitney(t, p, &kv).map_err(|e| {
            BadInput(format!(
                "{option} (direction {k}, {m} grid parameters from {} to {}): {e}",
                t[0],
                t[m - 1]
            ))
        })?;
        net.push(c);
        knots.push(kv);
    }
    let s = tensor_grid_least_squares(refs, values.as_view(), degrees, knots)?;
    Ok((s, net))
}

/// Least squares on scattered rows `x1 … xN` followed by the values.
fn run_scattered(
    a: &FitArgs,
    dirs: &[Direction],
    weights: Option<&[f64]>,
    inputs: &[PathBuf],
    cx: &Context,
) -> Result<()> {
    let n = dirs.len();
    let (pts, name) = crate::items::read_points(cx, &a.points)?;
    let dim = pts.dim();
    if dim <= n {
        return bad_input(format!(
            "{name}: --scattered in {n} variables reads rows x1 … x{n} followed by the values: \
             at least {} columns; found {dim}",
            n + 1
        ));
    }
    if let Some(target) = a.s {
        let (mut xs, mut ys) = (Vec::with_capacity(pts.len() * n), Vec::new());
        for row in pts.iter() {
            xs.extend_from_slice(&row[..n]);
            ys.extend_from_slice(&row[n..]);
        }
        return smooth_scattered(a, dirs, (&xs, &ys), weights, target, inputs, cx);
    }
    let column = |c: usize| pts.iter().map(|r| r[c]).collect::<Vec<f64>>();
    let mut knots = Vec::with_capacity(n);
    let mut net = Vec::with_capacity(n);
    for d in dirs {
        let x = column(d.k - 1);
        let data = x
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), &u| {
                (l.min(u), h.max(u))
            });
        let what = format!("values of x{} (column {})", d.k, d.k);
        let (lo, hi) = d.domain(data, &what)?;
        if lo.partial_cmp(&hi) != Some(Ordering::Less) {
            return bad_input(format!(
                "{name}: every {what} is {lo}; give --bbox with an interval A:B, A < B, around it"
            ));
        }
        let p = d.degree;
        let kv = d.knots((lo, hi), |c| {
            let k = KnotVector::clamped_uniform(p, c)?;
            Ok(KnotVector::new(
                k.as_slice().iter().map(|t| lo + (hi - lo) * t).collect(),
            )?)
        })?;
        net.push(kv.len().saturating_sub(p + 1));
        knots.push(kv);
    }
    // The normal matrix is banded: Π n_a rows of Σ p_a·(Π_{b>a} n_b) + 1 numbers. Its size is
    // refused here, before the library allocates it.
    // A penalty's second differences reach 2·Π_{b>a} n_b along direction a.
    let mut stride = 1usize;
    let mut band = 0usize;
    let mut reach = 0usize;
    for (d, &c) in dirs.iter().zip(&net).rev() {
        band = band.saturating_add(d.degree.saturating_mul(stride));
        if a.penalty != 0.0 && c >= 3 {
            reach = reach.max(stride.saturating_mul(2));
        }
        stride = stride.saturating_mul(c);
    }
    let band = band.max(reach);
    let entries = stride.saturating_mul(band.saturating_add(1));
    if entries > cx.max_size {
        return bad_input(format!(
            "a {} control net (--ctrl-grid, --knots-u, --knots-v, --knots-in): the scattered \
             fit's least-squares system holds {entries} numbers ({} bytes), above the size \
             limit {}; use a smaller control net, or raise the limit with --max-size {entries} \
             if the machine has the memory",
            shape_text(&net),
            lekalo_io::fmt_number(entries as f64 * 8.0),
            cx.max_size
        ));
    }
    let (mut xs, mut ys) = (Vec::with_capacity(pts.len() * n), Vec::new());
    ys.reserve(pts.len() * (dim - n));
    for row in pts.iter() {
        xs.extend_from_slice(&row[..n]);
        ys.extend_from_slice(&row[n..]);
    }
    let degrees: Vec<usize> = dirs.iter().map(|d| d.degree).collect();
    let f = tensor_scattered_penalized_least_squares(
        PointsRef::from_flat(n, &xs)?,
        PointsRef::from_flat(dim - n, &ys)?,
        weights,
        &degrees,
        knots,
        a.penalty,
    )
    .map_err(|e| match e {
        lekalo::Error::EmptySupport { support, points } => {
            let index: Vec<String> = support.index.iter().map(|i| (i + 1).to_string()).collect();
            let sides: Vec<String> = (0..n)
                .map(|a| format!("x{} in [{}, {}]", a + 1, support.lower[a], support.upper[a]))
                .collect();
            let options: Vec<String> = dirs.iter().map(Direction::knots_option).collect();
            let many = if points > 0 {
                ", too few or too nearly aligned"
            } else {
                ""
            };
            let fill = if a.penalty == 0.0 {
                ", or give --penalty L (e.g. 1e-3) to fill it from its neighbours"
            } else {
                ""
            };
            anyhow::Error::from(BadInput(format!(
                "{name}: control point ({}) of the {} net (counted from 1 in each direction) is \
                 not determined by the data: its region {} holds {points} data points of \
                 positive weight{many}; remove knots there ({} or a smaller --ctrl-grid), or \
                 add data inside it{fill}",
                index.join(", "),
                shape_text(&net),
                sides.join(", "),
                options.join(", ")
            )))
        }
        other => other.into(),
    })?;
    let extra = (a.penalty != 0.0).then(|| json!({ "penalty": a.penalty }));
    finish_with(
        a,
        &f.spline,
        &net,
        &f.residuals,
        f.weighted_rss,
        extra,
        inputs,
        cx,
    )
}

/// `--scattered --s S`: the spline with FITPACK surfit's knots whose weighted residual sum of
/// squares is S ([`lekalo::tensor_scattered_smoothing`]), on the box of the data or `--bbox`, a
/// rank-deficient least-squares round answered by FITPACK's minimal-norm solution (the knots
/// are the method's, not the user's, so a region they leave without data is not refused).
fn smooth_scattered(
    a: &FitArgs,
    dirs: &[Direction],
    (xs, ys): (&[f64], &[f64]),
    weights: Option<&[f64]>,
    target: f64,
    inputs: &[PathBuf],
    cx: &Context,
) -> Result<()> {
    let n = dirs.len();
    let x = PointsRef::from_flat(n, xs)?;
    let y = PointsRef::from_flat(ys.len() / x.len().max(1), ys)?;
    let mut bbox = Vec::with_capacity(n);
    for d in dirs {
        let data = x
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), r| {
                (l.min(r[d.k - 1]), h.max(r[d.k - 1]))
            });
        let what = format!("values of x{} (column {})", d.k, d.k);
        bbox.push(d.domain(data, &what)?);
    }
    let degrees: Vec<usize> = dirs.iter().map(|d| d.degree).collect();
    let options = ScatteredSmoothingOptions {
        bbox: Some(bbox),
        max_knots: None,
        rank: RankDeficiency::MinimumNorm { eps: 1e-16 },
    };
    let f = tensor_scattered_smoothing(x, y, weights, &degrees, target, &options)?;
    let mut fitted = vec![0.0; ys.len()];
    f.spline.par_eval_batch(xs, None, &mut fitted)?;
    let residuals: Vec<f64> = fitted
        .chunks_exact(y.dim())
        .zip(y.iter())
        .map(|(f, q)| {
            f.iter()
                .zip(q)
                .map(|(a, b)| (a - b) * (a - b))
                .sum::<f64>()
                .sqrt()
        })
        .collect();
    let net = f.spline.shape().to_vec();
    let limit = f.limit.map(|l| match l {
        KnotLimit::MaxKnots => "max-knots",
        KnotLimit::CoefficientsExceedData => "coefficients-exceed-data",
        KnotLimit::KnotsCoincide => "knots-coincide",
    });
    if let (Some(l), false) = (limit, cx.is_quiet()) {
        crate::output::report(&format!(
            "fit: no knot could be added ({l}); the least-squares spline on the knots found \
             has weighted RSS {} > --s {target}",
            lekalo_io::fmt_number(f.residual)
        ));
    }
    let extra = json!({ "s": target, "p": f.p, "rank": f.rank, "knot_limit": limit });
    finish_with(
        a,
        &f.spline,
        &net,
        &residuals,
        f.residual,
        Some(extra),
        inputs,
        cx,
    )
}

/// Writes the fitted spline (or `{"object", "report"}` with `--json`) and its report, with
/// `extra` fields in the report.
#[allow(clippy::too_many_arguments)]
pub(super) fn finish_with(
    a: &FitArgs,
    s: &TensorBSpline,
    net: &[usize],
    residuals: &[f64],
    weighted_rss: f64,
    extra: Option<Value>,
    inputs: &[PathBuf],
    cx: &Context,
) -> Result<()> {
    let (max_index, max) =
        residuals.iter().enumerate().fold(
            (0, 0.0_f64),
            |(i, m), (k, &r)| if r > m { (k, r) } else { (i, m) },
        );
    let rms = (residuals.iter().map(|r| r * r).sum::<f64>() / residuals.len().max(1) as f64).sqrt();
    let count: usize = net.iter().product();
    let mut report = json!({ "max_residual": max, "max_index": max_index, "rms": rms,
        "weighted_rss": weighted_rss, "control_points": count, "shape": net });
    if let Some(Value::Object(fields)) = extra {
        for (k, v) in fields {
            report[k] = v;
        }
    }
    if a.per_point {
        report["residuals"] = json!(residuals);
    }
    let tensor = Tensor::BSpline(s.clone());
    if a.json {
        let object: Value = serde_json::from_str(&lekalo_io::tensor_to_json(&tensor))?;
        let text = serde_json::to_string_pretty(&json!({ "object": object, "report": report }))?;
        return emit(a.out.output.as_deref(), text.as_bytes(), inputs, cx);
    }
    if !cx.is_quiet() {
        crate::output::report(&format!(
            "fit: {} = {count} control points, residual max {} (point {max_index}), RMS {}, \
             weighted RSS {}",
            shape_text(net),
            report["max_residual"],
            report["rms"],
            report["weighted_rss"]
        ));
    }
    let (to, out) = (a.out.to.as_deref(), a.out.output.as_deref());
    crate::output::objects::write_tensor(&tensor, (to, out), inputs, cx)
}

/// `5x4x4`.
fn shape_text(net: &[usize]) -> String {
    net.iter()
        .map(usize::to_string)
        .collect::<Vec<_>>()
        .join("x")
}

/// The options of curve fits, refused in `N` variables (least squares with given knots only).
fn refuse_curve_options(a: &FitArgs, in_shape: bool) -> Result<()> {
    let s_of_a_curve = a.s.is_some() && a.grid.is_none() && !a.scattered;
    let given: Vec<&str> = std::iter::once((s_of_a_curve, "--s"))
        .chain(a.curve_options())
        // a grid is smoothed by --smooth (tensor_grid_smoothing_spline); a surface's grid
        // smoothed in shape keeps its constraints (read by `grid_shapes`)
        .filter(|&(on, name)| {
            on && !(name == "--smooth" && a.grid.is_some())
                && !(name == "shape constraints" && in_shape)
        })
        .map(|(_, name)| name)
        .collect();
    if given.is_empty() {
        return Ok(());
    }
    bad_input(format!(
        "{} {} for curves; a fit in 3 or more variables is least squares with --ctrl-grid or \
         the knots of each direction (--knots-u, --knots-v, --knots-in K=LIST)",
        given.join(", "),
        if given.len() == 1 { "is" } else { "are" }
    ))
}

/// The sizes `AxBxC…` of `option`, each at least 1.
fn sizes(text: &str, option: &str) -> Result<Vec<usize>> {
    text.split(['x', 'X', '×'])
        .map(|s| match s.trim().parse::<usize>() {
            Ok(c) if c >= 1 => Ok(c),
            _ => bad_input(format!(
                "{option}: \"{}\" in \"{text}\" is not a positive integer; write one size per \
                 direction, e.g. 5x4x3",
                s.trim()
            )),
        })
        .collect()
}

/// `A:B,C:D,…` of `--bbox`, one interval per each of `n` directions.
fn boxes(text: &str, n: usize) -> Result<Vec<(f64, f64)>> {
    let example = vec!["0:1"; n].join(",");
    let example = format!("--bbox {example}");
    let parts: Vec<&str> = text.split(',').collect();
    if parts.len() != n {
        return bad_input(format!(
            "--bbox: {} intervals in \"{text}\" for a fit in {n} variables; give one A:B per \
             direction (e.g. {example})",
            parts.len()
        ));
    }
    parts.iter().map(|p| span(p, "--bbox", &example)).collect()
}
