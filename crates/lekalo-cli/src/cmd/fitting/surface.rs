//! `lekalo fit --grid` and `--scattered`: surfaces through a grid of points or scattered
//! `(u, v, z)` rows, with the knots, bounding box, degrees and parameters of each direction.

use std::path::PathBuf;

use anyhow::Result;
use lekalo::fit::{
    constrained_surface_grid_least_squares, constrained_surface_scattered_least_squares,
    place_knots, surface_grid_least_squares_at, surface_grid_parameters,
    surface_scattered_least_squares_with_progress, SurfaceShapeConstraints,
};
use lekalo::{KnotVector, Points};
use serde_json::{json, Value};

use super::args::{bounding_box, clamped, with_ends, FitArgs};
use super::shapes::surface_shape_constraints;
use crate::context::Context;
use crate::exit::bad_input;
use crate::output::emit;
use crate::output::objects::write_surface;
use crate::values::net_size;
use crate::values::numbers;

pub(super) fn run_surface(
    a: &FitArgs,
    pts: &Points,
    weights: Option<&[f64]>,
    inputs: &[PathBuf],
    cx: &Context,
) -> Result<()> {
    let (p, q) = a.surface_degrees()?;
    let shapes = surface_shape_constraints(a)?;
    // (a grid smoothed in shape, by --smooth or --s, is the tensor fit's: see tensor::grid_shapes)
    let counts = match &a.ctrl_grid {
        Some(cg) => {
            let (ncu, ncv) = net_size(cg, "--ctrl-grid")?;
            (Some(ncu), Some(ncv))
        }
        None => (None, None),
    };
    let bbox = a.bbox.as_deref().map(bounding_box).transpose()?;
    let dirs = [
        Direction {
            name: "u",
            degree: p,
            inner: a
                .knots_u
                .as_deref()
                .map(|t| numbers(t, "--knots-u"))
                .transpose()?,
            knots_option: "--knots-u",
            count: counts.0,
            range: bbox.map(|b| b.0),
        },
        Direction {
            name: "v",
            degree: q,
            inner: a
                .knots_v
                .as_deref()
                .map(|t| numbers(t, "--knots-v"))
                .transpose()?,
            knots_option: "--knots-v",
            count: counts.1,
            range: bbox.map(|b| b.1),
        },
    ];
    for d in &dirs {
        d.check_count(counts)?;
    }
    if let Some(g) = &a.grid {
        let (nu, nv) = net_size(g, "--grid")?;
        let given = [
            (&a.params_u, "--params-u", nu, "rows"),
            (&a.params_v, "--params-v", nv, "columns"),
        ]
        .map(|(text, option, n, lines)| -> Result<Option<Vec<f64>>> {
            let Some(text) = text else { return Ok(None) };
            let t = crate::cmd::explicit::parameters(cx, text, option)?;
            if t.len() != n {
                return bad_input(format!(
                    "{option}: {} values for the {n} {lines} of --grid {g}; give one parameter \
                     per grid line",
                    t.len()
                ));
            }
            Ok(Some(t))
        });
        let [gu, gv] = given;
        let (gu, gv) = (gu?, gv?);
        // a table z(u, v) with shapes: its coordinates and values
        let table = if shapes.is_empty() {
            None
        } else {
            Some(table_of_grid(pts, (nu, nv), gu.clone(), gv.clone(), g)?)
        };
        // the parameters not given: --param averaged over the grid lines (P&T §9.2.5)
        let (uu, vv) = match (&table, gu, gv) {
            (Some((u, v, _)), _, _) => (u.clone(), v.clone()),
            (None, Some(u), Some(v)) => (u, v),
            (None, gu, gv) => {
                let (cu, cv) = surface_grid_parameters(pts.as_view(), (nu, nv), a.param())?;
                (gu.unwrap_or(cu), gv.unwrap_or(cv))
            }
        };
        let place = |d: &Direction, params: &[f64], n: usize, range: (f64, f64)| {
            let mut sorted = params.to_vec();
            sorted.sort_by(f64::total_cmp);
            let k = place_knots(&sorted, d.degree, n)?;
            with_ends(&k, d.degree, range)
        };
        let ku = dirs[0].knots(&uu, "u parameters of the grid's rows", &place)?;
        let kv = dirs[1].knots(&vv, "v parameters of the grid's columns", &place)?;
        let s = match &table {
            Some((_, _, z)) => constrained_surface_grid_least_squares(
                z.as_view(),
                (nu, nv),
                (p, q),
                (&uu, &vv),
                (&ku, &kv),
                &shapes,
            )?,
            None => surface_grid_least_squares_at(
                pts.as_view(),
                (nu, nv),
                (p, q),
                (&uu, &vv),
                (&ku, &kv),
            )?,
        };
        if a.json {
            // the residuals at the grid: |z(u_i, v_j) − z_ij| for a table, the distances to the
            // grid's points otherwise
            let data = table.as_ref().map_or(pts, |(_, _, z)| z);
            let dim = data.dim();
            let mut at = vec![0.0; uu.len() * vv.len() * dim];
            s.eval_grid(&uu, &vv, &mut at)?;
            let residuals: Vec<f64> = at
                .chunks_exact(dim)
                .zip(data.iter())
                .map(|(f, d)| {
                    f.iter()
                        .zip(d)
                        .map(|(x, y)| (x - y) * (x - y))
                        .sum::<f64>()
                        .sqrt()
                })
                .collect();
            return emit_report(a, &s, &residuals, None, &shapes, inputs, cx);
        }
        return write_surface(&s, &a.out, inputs, cx);
    }
    if pts.dim() < 3 {
        return bad_input("--scattered needs rows u, v, z (three columns or more)");
    }
    let column = |c: usize| pts.iter().map(|r| r[c]).collect::<Vec<f64>>();
    let uniform = |d: &Direction, _: &[f64], n: usize, (lo, hi): (f64, f64)| {
        let k = KnotVector::clamped_uniform(d.degree, n)?;
        Ok(KnotVector::new(
            k.as_slice().iter().map(|t| lo + (hi - lo) * t).collect(),
        )?)
    };
    let (ncu, ncv) = (dirs[0].net_count(), dirs[1].net_count());
    // The system solved is banded: NU·NV rows of about p·NV + q + 1 numbers (twice NV with a
    // penalty). Its size is refused here, before the library allocates it.
    let band = p
        .saturating_mul(ncv)
        .saturating_add(q)
        .max(ncv.saturating_mul(2));
    let entries = ncu
        .saturating_mul(ncv)
        .saturating_mul(band.saturating_add(1));
    let limit = cx.max_size;
    if entries > limit {
        let net = match &a.ctrl_grid {
            Some(cg) if a.knots_u.is_none() && a.knots_v.is_none() => format!("--ctrl-grid {cg}"),
            _ => format!("a {ncu}x{ncv} control net (--ctrl-grid, --knots-u, --knots-v)"),
        };
        return bad_input(format!(
            "{net}: the scattered fit's least-squares system holds {entries} numbers ({} bytes), above the size limit {limit}; use a smaller control net, or raise the limit with --max-size {entries} if the machine has the memory",
            lekalo_io::fmt_number(entries as f64 * 8.0)
        ));
    }
    let ku = dirs[0].knots(
        &column(0),
        "u values of the data (the first column)",
        &uniform,
    )?;
    let kv = dirs[1].knots(
        &column(1),
        "v values of the data (the second column)",
        &uniform,
    )?;
    // a bar on a terminal for many points or a large net; Ctrl-C stops the fit between blocks
    let large = pts.len() > super::args::LARGE || entries > super::args::LARGE * 100;
    let f = if shapes.is_empty() {
        crate::cancel::with_progress(cx, "scattered surface fit", large, |pr| {
            surface_scattered_least_squares_with_progress(
                pts.as_view(),
                weights,
                (p, q),
                (&ku, &kv),
                a.penalty,
                pr,
            )
        })?
    } else {
        if pts.dim() != 3 {
            return bad_input(format!(
                "--increasing, --decreasing, --min, --max: a surface z(u, v) keeps them; give \
                 rows u, v, z (three columns, not {})",
                pts.dim()
            ));
        }
        constrained_surface_scattered_least_squares(
            pts.as_view(),
            weights,
            (p, q),
            (&ku, &kv),
            a.penalty,
            &shapes,
        )?
    };
    if a.json {
        let scattered = Some((f.weighted_rss, a.penalty));
        return emit_report(a, &f.surface, &f.residuals, scattered, &shapes, inputs, cx);
    }
    let max = f.residuals.iter().fold(0.0_f64, |m, &r| m.max(r));
    let rms = (f.residuals.iter().map(|r| r * r).sum::<f64>() / f.residuals.len() as f64).sqrt();
    if !cx.is_quiet() {
        crate::output::report(&format!(
            "fit: {ncu}x{ncv} control points, residual max {max}, RMS {rms}"
        ));
    }
    write_surface(&f.surface, &a.out, inputs, cx)
}

/// `{"object", "report"}` of a surface fit (`--json`): the largest and RMS residual, the
/// control points, the constraints kept, and for scattered rows the weighted residual sum and
/// the penalty; `--per-point` adds every residual.
fn emit_report(
    a: &FitArgs,
    surface: &lekalo::BSplineSurface,
    residuals: &[f64],
    scattered: Option<(f64, f64)>,
    shapes: &SurfaceShapeConstraints,
    inputs: &[PathBuf],
    cx: &Context,
) -> Result<()> {
    let max = residuals.iter().fold(0.0_f64, |m, &r| m.max(r));
    let rms = (residuals.iter().map(|r| r * r).sum::<f64>() / residuals.len().max(1) as f64).sqrt();
    let (ncu, ncv) = surface.net_size();
    let mut report = json!({ "max_residual": max, "rms": rms, "control_points": ncu * ncv });
    if let Some((weighted_rss, penalty)) = scattered {
        report["weighted_rss"] = json!(weighted_rss);
        report["penalty"] = json!(penalty);
    }
    if !shapes.is_empty() {
        report["constraints"] = json!((0..shapes.len())
            .map(|i| shapes.describe(i))
            .collect::<Vec<_>>());
    }
    if a.per_point {
        report["residuals"] = json!(residuals);
    }
    let object: Value = serde_json::from_str(&lekalo_io::bspline_surface_to_json(surface))?;
    let text = serde_json::to_string_pretty(&json!({ "object": object, "report": report }))?;
    emit(a.out.output.as_deref(), text.as_bytes(), inputs, cx)
}

/// The table `z(u, v)` a grid with shape constraints holds: one value per node at the
/// coordinates `--params-u`, `--params-v` (equally spaced on [0, 1] when not given), or rows
/// `u, v, z` whose `u` is the same along each grid row and `v` along each column.
pub(super) fn table_of_grid(
    pts: &Points,
    (nu, nv): (usize, usize),
    gu: Option<Vec<f64>>,
    gv: Option<Vec<f64>>,
    grid: &str,
) -> Result<(Vec<f64>, Vec<f64>, Points)> {
    let even =
        |n: usize| -> Vec<f64> { (0..n).map(|i| i as f64 / (n - 1).max(1) as f64).collect() };
    if pts.len() != nu * nv {
        return bad_input(format!(
            "--grid {grid}: {} rows for {nu}x{nv} nodes; give one row per node",
            pts.len()
        ));
    }
    match pts.dim() {
        1 => Ok((
            gu.unwrap_or_else(|| even(nu)),
            gv.unwrap_or_else(|| even(nv)),
            pts.clone(),
        )),
        3 if gu.is_none() && gv.is_none() => {
            let u: Vec<f64> = (0..nu).map(|i| pts.point(i * nv)[0]).collect();
            let v: Vec<f64> = (0..nv).map(|j| pts.point(j)[1]).collect();
            for (k, row) in pts.iter().enumerate() {
                let (i, j) = (k / nv, k % nv);
                if row[0] != u[i] || row[1] != v[j] {
                    return bad_input(format!(
                        "--grid {grid} with shape constraints: row {} is ({}, {}), off the table's \
                         lines u = {}, v = {}; give rows u, v, z with u fixed along each grid \
                         row and v along each column (u slowest), or one value per node with \
                         --params-u and --params-v",
                        k + 1,
                        row[0],
                        row[1],
                        u[i],
                        v[j]
                    ));
                }
            }
            let z: Vec<f64> = pts.iter().map(|r| r[2]).collect();
            Ok((u, v, Points::from_flat(1, z)?))
        }
        3 => bad_input(
            "--params-u/--params-v with rows u, v, z: the rows already give the coordinates; \
             drop the options or give one value per node",
        ),
        d => bad_input(format!(
            "--grid {grid} with shape constraints fits a table z(u, v): give rows u, v, z or one \
             value per node, not {d} columns"
        )),
    }
}

/// How a direction without given knots places `count` of them over its data's parameters,
/// clamped at the ends of its range: `place(direction, params, count, range)`.
type PlaceKnots = dyn Fn(&Direction, &[f64], usize, (f64, f64)) -> Result<KnotVector>;

/// One direction of a surface fit: its degree, and its knots given (`inner`, interior) or its
/// control-point count (`count`, from `--ctrl-grid`), with the domain `range` of `--bbox`.
pub(super) struct Direction {
    name: &'static str,
    degree: usize,
    inner: Option<Vec<f64>>,
    knots_option: &'static str,
    count: Option<usize>,
    range: Option<(f64, f64)>,
}

impl Direction {
    /// The number of control points in this direction: set by its knots, or its count.
    fn net_count(&self) -> usize {
        match &self.inner {
            Some(k) => k.len() + self.degree + 1,
            None => self.count.unwrap_or(0),
        }
    }

    /// A direction needs interior knots or a count; given both, they must agree.
    fn check_count(&self, (ncu, ncv): (Option<usize>, Option<usize>)) -> Result<()> {
        let (name, option, p) = (self.name, self.knots_option, self.degree);
        match (&self.inner, self.count) {
            (None, None) => bad_input(format!(
                "surfaces need the control net's size --ctrl-grid NUxNV, or the interior knots of \
                 each direction (--knots-u, --knots-v); {name} has neither"
            )),
            (Some(k), Some(n)) if k.len() + p + 1 != n => {
                let implied = k.len() + p + 1;
                let (u, v) = if name == "u" {
                    (implied, ncv.unwrap_or(0))
                } else {
                    (ncu.unwrap_or(0), implied)
                };
                bad_input(format!(
                    "--ctrl-grid and {option} disagree: {} interior knots of degree {p} make \
                     {implied} control points in {name}, not {n}; drop --ctrl-grid or write \
                     --ctrl-grid {u}x{v}",
                    k.len()
                ))
            }
            _ => Ok(()),
        }
    }

    /// The knots of this direction over the data's parameters `params` (named `what` in
    /// messages): the interior knots given, or `place(self, params, count, range)`, clamped at
    /// the ends of `--bbox` (which must hold the data) or of the data.
    fn knots(&self, params: &[f64], what: &str, place: &PlaceKnots) -> Result<KnotVector> {
        let data = params
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), &u| {
                (l.min(u), h.max(u))
            });
        let range = match self.range {
            Some((lo, hi)) => {
                if lo > data.0 || hi < data.1 {
                    return bad_input(format!(
                        "--bbox: the {what} run from {} to {}, outside {lo}:{hi}, the bbox's \
                         {name} interval; give one around them, e.g. {}:{}",
                        data.0,
                        data.1,
                        lo.min(data.0),
                        hi.max(data.1),
                        name = self.name
                    ));
                }
                (lo, hi)
            }
            None => data,
        };
        match (&self.inner, self.count) {
            (Some(inner), _) => {
                let within = if self.range.is_some() {
                    "--bbox"
                } else {
                    "the range of the data's parameters, or --bbox"
                };
                clamped(self.degree, range, inner, self.knots_option, within)
            }
            (None, Some(n)) => place(self, params, n, range),
            (None, None) => bad_input("surfaces need --ctrl-grid NUxNV (the control net size)"),
        }
    }
}
