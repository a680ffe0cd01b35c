//! `lekalo eval` of a surface: points, partial derivatives, normals and curvatures at `(u, v)`
//! pairs or on a grid.

use std::path::{Path, PathBuf};

use anyhow::Result;
use lekalo_io::{surface_sample_table, Surface, SurfaceSampleSpec};

use crate::context::Context;
use crate::exit::{bad_input, BadInput};
use crate::output::{emit, format_of};
use crate::values::numbers;

/// What `eval` asks of a surface.
pub(crate) struct SurfaceEval<'a> {
    pub(crate) input: &'a Path,
    /// `--uv U,V` pairs.
    pub(crate) uv: &'a [String],
    /// `--uv-file FILE`: two columns.
    pub(crate) uv_file: Option<&'a Path>,
    /// `--grid NUxNV`.
    pub(crate) grid: Option<&'a str>,
    /// `--samples N`: an N × N grid.
    pub(crate) samples: Option<usize>,
    pub(crate) derivatives: usize,
    pub(crate) normals: bool,
    pub(crate) curvature: bool,
    pub(crate) format: Option<&'a str>,
    pub(crate) output: Option<&'a Path>,
}

/// Default grid side when neither pairs nor a grid are given.
const DEFAULT_SIDE: usize = 5;
/// Largest number of `(u, v)` samples.
const MAX_SAMPLES: usize = 10_000_000;

/// Parses `NUxNV` (also `NU,NV` or a single `N` for N × N).
pub(crate) fn grid_size(text: &str, what: &str) -> Result<(usize, usize)> {
    let parts: Vec<&str> = text.split(['x', 'X', ',', '×']).map(str::trim).collect();
    // a size left out ("5x", "x7") is a slip, not a square grid
    if parts.len() > 1 && parts.iter().any(|s| s.is_empty()) {
        return bad_input(format!(
            "{what}: \"{text}\" is missing a size; write NUxNV, e.g. 5x7 (or one number N for N × N)"
        ));
    }
    let parse = |s: &str| {
        s.parse::<usize>().map_err(|_| {
            BadInput(format!(
                "{what}: \"{s}\" is not a positive integer (write e.g. 5x7)"
            ))
        })
    };
    let (a, b) = match parts.as_slice() {
        [n] => (parse(n)?, parse(n)?),
        [a, b] => (parse(a)?, parse(b)?),
        _ => return bad_input(format!("{what}: write NUxNV, e.g. 5x7")),
    };
    if a == 0 || b == 0 {
        return bad_input(format!("{what}: both sizes must be at least 1"));
    }
    Ok((a, b))
}

fn pairs(cx: &Context, e: &SurfaceEval<'_>, s: &Surface) -> Result<Vec<[f64; 2]>> {
    let mut out = Vec::new();
    for (k, text) in e.uv.iter().enumerate() {
        let v = numbers(text, &format!("--uv (pair {})", k + 1))?;
        if v.len() % 2 != 0 {
            return bad_input(format!(
                "--uv (pair {}): \"{text}\" has {} values; give U,V pairs",
                k + 1,
                v.len()
            ));
        }
        out.extend(v.chunks_exact(2).map(|c| [c[0], c[1]]));
    }
    if let Some(f) = e.uv_file {
        let (pts, name) = crate::items::read_points(cx, f)?;
        if pts.dim() != 2 {
            return bad_input(format!(
                "{name}: --uv-file needs two columns u, v; found {}",
                pts.dim()
            ));
        }
        out.extend(pts.iter().map(|p| [p[0], p[1]]));
    }
    if !out.is_empty() {
        return Ok(out);
    }
    let (nu, nv) = match (e.grid, e.samples) {
        (Some(g), _) => grid_size(g, "--grid")?,
        (None, Some(n)) => (n, n),
        (None, None) => (DEFAULT_SIDE, DEFAULT_SIDE),
    };
    if nu.saturating_mul(nv) > MAX_SAMPLES || nu == 0 || nv == 0 {
        return bad_input(format!(
            "a {nu} × {nv} grid: the grid must have between 1 and {MAX_SAMPLES} points"
        ));
    }
    Ok(s.grid_parameters(nu, nv))
}

pub(crate) fn run(e: &SurfaceEval<'_>, s: &Surface, cx: &Context) -> Result<()> {
    let uv = pairs(cx, e, s)?;
    let spec = SurfaceSampleSpec {
        derivatives: e.derivatives,
        normals: e.normals,
        curvature: e.curvature,
    };
    let table = surface_sample_table(s, &uv, spec)
        .map_err(|err| BadInput(format!("{}: {err}", e.input.display())))?;
    let fmt = format_of(e.format, e.output, "csv");
    let text = match fmt.as_str() {
        "csv" => table.to_csv(),
        "json" => format!("{:#}\n", table.to_json()),
        other => return bad_input(format!("--format {other}: use csv or json")),
    };
    let inputs: Vec<PathBuf> = vec![e.input.to_path_buf()];
    emit(e.output, text.as_bytes(), &inputs, cx)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grid_sizes() {
        assert_eq!(grid_size("5x7", "g").unwrap(), (5, 7));
        assert_eq!(grid_size("4", "g").unwrap(), (4, 4));
        assert_eq!(grid_size("3,2", "g").unwrap(), (3, 2));
        assert!(grid_size("0x3", "g").is_err());
        assert!(grid_size("ax3", "g").is_err());
        assert!(grid_size("1x2x3", "g").is_err());
        // a half-written size is refused, not read as a square grid
        assert!(grid_size("5x", "g").is_err(), "5x");
        assert!(grid_size("x7", "g").is_err(), "x7");
        assert!(grid_size("", "g").is_err(), "empty");
    }
}
