//! Tables of samples of a surface: parameters `(u, v)`, the point, partial derivatives, unit
//! normals and curvatures, in the [`SampleTable`] that curves use (CSV or JSON).
//!
//! Every value is the library's own: points from the surface's `eval`, partial derivatives from
//! its `eval_derivatives`, normals from its `normal`, curvatures from
//! [`lekalo::surface_curvature`] on those derivatives.

use crate::samples::SampleTable;
use crate::shape::Surface;

/// What to compute at each `(u, v)`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct SurfaceSampleSpec {
    /// Highest total order of the partial derivatives `∂^(a+b) S / ∂u^a ∂v^b` (0 = points only).
    pub derivatives: usize,
    /// Add the unit normal `nx, ny, nz` (3-D surfaces).
    pub normals: bool,
    /// Add the principal curvatures `k1 ≥ k2`, `gaussian` and `mean` (3-D surfaces).
    pub curvature: bool,
}

/// Column names of the coordinates: `x, y, z` up to 3-D, `x1 … xd` above.
fn coord_names(dim: usize) -> Vec<String> {
    if dim <= 3 {
        ["x", "y", "z"][..dim]
            .iter()
            .map(|s| (*s).to_string())
            .collect()
    } else {
        (1..=dim).map(|k| format!("x{k}")).collect()
    }
}

/// Evaluates `s` at every `(u, v)` of `uv`. Columns: `u, v`, the point, then for each total
/// order `k = 1 … derivatives` the partials `du{a}v{b}{coord}` with `a = k … 0`, `b = k − a`
/// (`du1v0x` is `∂x/∂u`), then `nx, ny, nz` and `k1, k2, gaussian, mean`. A normal or
/// curvature that is undefined at a degenerate point (pole, collapsed edge) is empty.
///
/// # Errors
/// [`lekalo::Error::ParameterOutOfDomain`] for a parameter outside the domain;
/// [`lekalo::Error::Dimension`] for normals or curvature of a surface that is not 3-D.
pub fn surface_sample_table(
    s: &Surface,
    uv: &[[f64; 2]],
    spec: SurfaceSampleSpec,
) -> lekalo::Result<SampleTable> {
    let dim = s.dim();
    if (spec.normals || spec.curvature) && dim != 3 {
        return Err(lekalo::Error::Dimension {
            what: "surface for normals and curvature".into(),
            expected: 3,
            got: dim,
        });
    }
    let names = coord_names(dim);
    let mut header = vec!["u".to_string(), "v".to_string()];
    header.extend(names.iter().cloned());
    for k in 1..=spec.derivatives {
        for a in (0..=k).rev() {
            header.extend(names.iter().map(|n| format!("du{a}v{}{n}", k - a)));
        }
    }
    if spec.normals {
        header.extend(["nx", "ny", "nz"].map(String::from));
    }
    if spec.curvature {
        header.extend(["k1", "k2", "gaussian", "mean"].map(String::from));
    }
    let order = if spec.curvature {
        spec.derivatives.max(2)
    } else {
        spec.derivatives
    };
    let side = order + 1;
    let mut rows = Vec::with_capacity(uv.len());
    for &[u, v] in uv {
        let mut row = vec![Some(u), Some(v)];
        row.extend(s.eval(u, v)?.into_iter().map(Some));
        if order > 0 {
            let d = s.eval_derivatives(u, v, order)?;
            for k in 1..=spec.derivatives {
                for a in (0..=k).rev() {
                    row.extend(d.point(a * side + (k - a)).iter().map(|x| Some(*x)));
                }
            }
            if spec.normals {
                push_normal(s, u, v, &mut row)?;
            }
            if spec.curvature {
                let p = |a: usize, b: usize| d.point(a * side + b);
                match lekalo::surface_curvature(p(1, 0), p(0, 1), p(2, 0), p(1, 1), p(0, 2)) {
                    Ok(c) => row.extend([c.k1, c.k2, c.gaussian, c.mean].map(Some)),
                    Err(lekalo::Error::InvalidArgument { .. }) => row.extend([None; 4]),
                    Err(e) => return Err(e),
                }
            }
        } else if spec.normals {
            push_normal(s, u, v, &mut row)?;
        }
        rows.push(row);
    }
    Ok(SampleTable { header, rows })
}

fn push_normal(s: &Surface, u: f64, v: f64, row: &mut Vec<Option<f64>>) -> lekalo::Result<()> {
    match s.normal(u, v) {
        Ok(n) => row.extend(n.map(Some)),
        Err(lekalo::Error::InvalidArgument { .. }) => row.extend([None; 3]),
        Err(e) => return Err(e),
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use lekalo::{BSplineSurface, BezierSurface, NurbsSurface, Points};

    fn bilinear() -> BSplineSurface {
        let net = Points::from_3d(&[
            [0.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 1.0],
        ])
        .unwrap();
        BSplineSurface::new(
            1,
            1,
            vec![0.0, 0.0, 1.0, 1.0],
            vec![0.0, 0.0, 1.0, 1.0],
            net,
            (2, 2),
        )
        .unwrap()
    }

    #[test]
    fn columns_and_values_are_the_librarys() {
        let b = bilinear();
        let s = Surface::BSpline(b.clone());
        let spec = SurfaceSampleSpec {
            derivatives: 2,
            normals: true,
            curvature: true,
        };
        let t = surface_sample_table(&s, &[[0.3, 0.6]], spec).unwrap();
        assert_eq!(
            t.header[..8],
            ["u", "v", "x", "y", "z", "du1v0x", "du1v0y", "du1v0z"]
        );
        assert!(t.header.contains(&"du1v1z".to_string()));
        let col = |name: &str| t.rows[0][t.header.iter().position(|h| h == name).unwrap()];
        let p = b.eval(0.3, 0.6).unwrap();
        assert_eq!(col("z").unwrap().to_bits(), p[2].to_bits());
        assert_eq!(col("du1v1z"), Some(1.0));
        assert_eq!(col("du0v1z"), Some(0.3));
        let n = b.normal(0.3, 0.6).unwrap();
        assert_eq!(col("nz").unwrap().to_bits(), n[2].to_bits());
        // z = uv: K = −1/(1 + u² + v²)²
        let k = col("gaussian").unwrap();
        let expect = -1.0 / (1.0f64 + 0.09 + 0.36).powi(2);
        assert!((k - expect).abs() < 1e-14, "{k} vs {expect}");
        assert!(surface_sample_table(&s, &[[1.5, 0.0]], spec).is_err());
    }

    #[test]
    fn every_kind_and_the_grid() {
        let b = bilinear();
        let kinds = [
            Surface::Bezier(BezierSurface::new(b.control_points().clone(), (2, 2)).unwrap()),
            Surface::Nurbs(NurbsSurface::from_bspline(&b)),
            Surface::BSpline(b),
        ];
        for s in &kinds {
            let g = s.grid_parameters(3, 2);
            assert_eq!(
                g,
                vec![
                    [0.0, 0.0],
                    [0.0, 1.0],
                    [0.5, 0.0],
                    [0.5, 1.0],
                    [1.0, 0.0],
                    [1.0, 1.0]
                ]
            );
            let t = surface_sample_table(s, &g, SurfaceSampleSpec::default()).unwrap();
            assert_eq!(t.rows.len(), 6);
            assert_eq!(t.rows[5][4], Some(1.0));
        }
        let flat = Surface::BSpline(
            BSplineSurface::new(
                1,
                1,
                vec![0.0, 0.0, 1.0, 1.0],
                vec![0.0, 0.0, 1.0, 1.0],
                Points::from_2d(&[[0.0, 0.0], [0.0, 1.0], [1.0, 0.0], [1.0, 1.0]]).unwrap(),
                (2, 2),
            )
            .unwrap(),
        );
        let spec = SurfaceSampleSpec {
            normals: true,
            ..SurfaceSampleSpec::default()
        };
        assert!(surface_sample_table(&flat, &[[0.0, 0.0]], spec).is_err());
    }
}
