//! `lekalo make bezier-surface|bspline-surface|nurbs-surface`: a surface from a control net.

use lekalo_io::SurfaceJson;
use std::path::{Path, PathBuf};

use anyhow::Result;
use lekalo::{BSplineSurface, BezierSurface, KnotVector, NurbsSurface};
use lekalo_io::Surface;

use crate::cmd::surface_eval::grid_size;
use crate::context::Context;
use crate::exit::bad_input;
use crate::output::emit;
use crate::values::numbers;

/// The kind of surface.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum SurfaceKind {
    Bezier,
    BSpline,
    Nurbs,
}

/// What `make` was given for a surface.
pub(crate) struct SurfaceMake<'a> {
    pub(crate) kind: SurfaceKind,
    pub(crate) control: &'a Path,
    pub(crate) net: Option<&'a str>,
    pub(crate) degree: Option<usize>,
    pub(crate) degree_v: Option<usize>,
    pub(crate) knots_u: Option<&'a str>,
    pub(crate) knots_v: Option<&'a str>,
    pub(crate) weights: Option<&'a str>,
    pub(crate) output: Option<&'a Path>,
}

pub(crate) fn run(m: &SurfaceMake<'_>, cx: &Context) -> Result<()> {
    let (ctrl, name) = crate::items::read_points(cx, m.control)?;
    let Some(net) = m.net else {
        return bad_input(format!(
            "a surface needs --net NUxNV: the {} control points of {name} are rows of the net, NV points per row",
            ctrl.len()
        ));
    };
    let (nu, nv) = grid_size(net, "--net")?;
    if nu.saturating_mul(nv) != ctrl.len() {
        return bad_input(format!(
            "--net {nu}x{nv} needs {} control points; {name} has {}",
            nu.saturating_mul(nv),
            ctrl.len()
        ));
    }
    let knots = |text: Option<&str>, p: usize, n: usize, what: &str| -> Result<KnotVector> {
        Ok(match text {
            Some(k) => KnotVector::new(numbers(k, what)?)?,
            None => KnotVector::clamped_uniform(p, n)?,
        })
    };
    let degrees = || -> Result<(usize, usize)> {
        match m.degree {
            Some(p) => Ok((p, m.degree_v.unwrap_or(p))),
            None => bad_input(
                "--degree is required for B-spline and NURBS surfaces (--degree-v sets v apart)",
            ),
        }
    };
    let surface = match m.kind {
        SurfaceKind::Bezier => {
            if m.degree.is_some()
                || m.knots_u.is_some()
                || m.knots_v.is_some()
                || m.weights.is_some()
            {
                return bad_input("a Bezier surface takes only --control and --net (its degrees are NU − 1 and NV − 1)");
            }
            Surface::Bezier(BezierSurface::new(ctrl, (nu, nv))?)
        }
        SurfaceKind::BSpline => {
            if m.weights.is_some() {
                return bad_input(
                    "--weights make a rational surface: use `lekalo make nurbs-surface`",
                );
            }
            let (p, q) = degrees()?;
            let ku = knots(m.knots_u, p, nu, "--knots-u")?;
            let kv = knots(m.knots_v, q, nv, "--knots-v")?;
            Surface::BSpline(BSplineSurface::new(
                p,
                q,
                ku.into_vec(),
                kv.into_vec(),
                ctrl,
                (nu, nv),
            )?)
        }
        SurfaceKind::Nurbs => {
            let (p, q) = degrees()?;
            let Some(w) = m.weights else {
                return bad_input(
                    "a NURBS surface needs --weights, one per control point, row by row",
                );
            };
            let w = crate::cmd::explicit::parameters(cx, w, "--weights")?;
            let ku = knots(m.knots_u, p, nu, "--knots-u")?;
            let kv = knots(m.knots_v, q, nv, "--knots-v")?;
            Surface::Nurbs(NurbsSurface::new(
                p,
                q,
                ku.into_vec(),
                kv.into_vec(),
                ctrl,
                w,
                (nu, nv),
            )?)
        }
    };
    let mut inputs: Vec<PathBuf> = vec![m.control.to_path_buf()];
    inputs.extend(m.weights.map(PathBuf::from).filter(|p| p.is_file()));
    emit(m.output, surface.to_json_pretty().as_bytes(), &inputs, cx)
}
