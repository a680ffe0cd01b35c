//! `lekalo mesh`: a surface as a triangle mesh (OBJ, ASCII STL or PLY) or a curve as a polyline
//! (OBJ), within a proved deviation.

use std::fmt::Write as _;
use std::path::PathBuf;

use anyhow::Result;
use clap::Args;
use lekalo_io::Shape;
use serde_json::json;

use crate::cmd::measure::{query_curve, query_surface};
use crate::io::{bad_input, emit, format_of, BadInput};
use crate::Verbosity;

/// Arguments of `lekalo mesh`.
#[derive(Args, Debug)]
#[command(after_help = "\
Surfaces (B-spline, Bezier or NURBS): a triangle mesh whose deviation from the surface is at most
the tolerance, a bound proved from the control net (and the weights). Curves: a polyline within the tolerance. The
format follows the output's extension (.obj, .stl, .ply) or --format; --json prints the counts
and the bound instead of writing geometry to standard output.

Examples:
  lekalo mesh surface.json --tolerance 1e-3 -o surface.obj
  lekalo mesh surface.json --tolerance 1e-4 -o surface.stl
  lekalo mesh curve.json --tolerance 1e-3 -o curve.obj")]
pub(crate) struct MeshArgs {
    /// Surface or curve file (JSON).
    input: PathBuf,
    /// Largest deviation (in the object's units).
    #[arg(long, short = 't')]
    tolerance: f64,
    /// Output format: obj, stl or ply (default: from the output's extension, else obj).
    #[arg(long)]
    format: Option<String>,
    /// Print a JSON summary (vertices, triangles, deviation) to standard error... and standard
    /// output when no file is written.
    #[arg(long)]
    json: bool,
    /// Output file (default: standard output).
    #[arg(short, long, value_name = "FILE")]
    output: Option<PathBuf>,
}

pub(crate) fn run(a: &MeshArgs, v: Verbosity) -> Result<()> {
    let (text, name) = lekalo_io::read_input(&a.input)?;
    let shape = Shape::from_json_str(&text, &name)?;
    // the tolerance alone sets the size of the result: its refusals name the option
    let bad = |e: lekalo::Error| {
        BadInput(format!(
            "{}: --tolerance {}: {e}",
            a.input.display(),
            lekalo_io::fmt_number(a.tolerance)
        ))
    };
    let fmt = format_of(a.format.as_deref(), a.output.as_deref(), "obj");
    let (body, summary) = match shape {
        Shape::Surface(s) => {
            let q = query_surface(&s, &a.input)?;
            let m = q.mesh(a.tolerance).map_err(bad)?;
            if m.vertices.dim() != 3 {
                return bad_input("meshes are written for 3-D surfaces");
            }
            let body = match fmt.as_str() {
                "obj" => {
                    let mut s = format!("# lekalo mesh: deviation <= {:e}\n", m.deviation);
                    for p in m.vertices.iter() {
                        let _ = writeln!(s, "v {} {} {}", p[0], p[1], p[2]);
                    }
                    for t in &m.triangles {
                        let _ = writeln!(s, "f {} {} {}", t[0] + 1, t[1] + 1, t[2] + 1);
                    }
                    s
                }
                "stl" => {
                    let mut s = String::from("solid lekalo\n");
                    for t in &m.triangles {
                        let [a, b, c] = t.map(|i| m.vertices.point(i as usize).to_vec());
                        let (u, w) = (
                            [b[0] - a[0], b[1] - a[1], b[2] - a[2]],
                            [c[0] - a[0], c[1] - a[1], c[2] - a[2]],
                        );
                        let n = [
                            u[1] * w[2] - u[2] * w[1],
                            u[2] * w[0] - u[0] * w[2],
                            u[0] * w[1] - u[1] * w[0],
                        ];
                        let l = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2])
                            .sqrt()
                            .max(f64::MIN_POSITIVE);
                        let _ = writeln!(
                            s,
                            "facet normal {} {} {}\n outer loop",
                            n[0] / l,
                            n[1] / l,
                            n[2] / l
                        );
                        for p in [&a, &b, &c] {
                            let _ = writeln!(s, "  vertex {} {} {}", p[0], p[1], p[2]);
                        }
                        s.push_str(" endloop\nendfacet\n");
                    }
                    s.push_str("endsolid lekalo\n");
                    s
                }
                "ply" => {
                    let mut s = format!(
                        "ply\nformat ascii 1.0\ncomment lekalo mesh, deviation <= {:e}\nelement vertex {}\nproperty double x\nproperty double y\nproperty double z\nelement face {}\nproperty list uchar int vertex_indices\nend_header\n",
                        m.deviation,
                        m.vertices.len(),
                        m.triangles.len()
                    );
                    for p in m.vertices.iter() {
                        let _ = writeln!(s, "{} {} {}", p[0], p[1], p[2]);
                    }
                    for t in &m.triangles {
                        let _ = writeln!(s, "3 {} {} {}", t[0], t[1], t[2]);
                    }
                    s
                }
                other => return bad_input(format!("--format {other}: use obj, stl or ply")),
            };
            let summary = json!({"vertices": m.vertices.len(), "triangles": m.triangles.len(), "deviation": m.deviation});
            (body, summary)
        }
        Shape::Curve(obj) => {
            let q = query_curve(&obj, &a.input)?;
            let poly = q.polyline(a.tolerance).map_err(bad)?;
            if fmt != "obj" {
                return bad_input(format!(
                    "--format {fmt}: a curve is written as an OBJ polyline"
                ));
            }
            let mut s = format!("# lekalo polyline: deviation <= {:e}\n", poly.deviation);
            for p in poly.points.iter() {
                let c: Vec<String> = (0..3)
                    .map(|d| p.get(d).copied().unwrap_or(0.0).to_string())
                    .collect();
                let _ = writeln!(s, "v {}", c.join(" "));
            }
            s.push('l');
            for i in 1..=poly.points.len() {
                let _ = write!(s, " {i}");
            }
            s.push('\n');
            let summary = json!({"vertices": poly.points.len(), "deviation": poly.deviation});
            (s, summary)
        }
        _ => return bad_input(format!("{}: mesh curves and surfaces", a.input.display())),
    };
    if a.json && a.output.is_none() {
        return emit(
            None,
            format!("{summary:#}\n").as_bytes(),
            std::slice::from_ref(&a.input),
            v,
        );
    }
    if a.json {
        eprintln!("{summary}");
    }
    emit(
        a.output.as_deref(),
        body.as_bytes(),
        std::slice::from_ref(&a.input),
        v,
    )
}
