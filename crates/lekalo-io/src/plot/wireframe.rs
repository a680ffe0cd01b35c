//! Surfaces as wireframes in a simple projection, written against plain point grids so that
//! any surface type plugs in by sampling itself into a [`Grid`].

use crate::palette::PALETTE;
use crate::svg::{Figure, Series, Style};

/// A grid of `nu × nv` points of dimension `dim`, point `(i, j)` at
/// `data[(i * nv + j) * dim ..]` (the layout of lekalo's surface nets).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Grid<'a> {
    /// Rows (first parameter direction).
    pub nu: usize,
    /// Columns (second parameter direction).
    pub nv: usize,
    /// Dimension of each point (3 for surfaces in space).
    pub dim: usize,
    /// Point-major coordinates, `nu · nv · dim` values.
    pub data: &'a [f64],
}

impl<'a> Grid<'a> {
    /// A grid view, checking the length.
    ///
    /// # Errors
    /// [`lekalo::Error::LengthMismatch`] if `data.len() != nu · nv · dim`;
    /// [`lekalo::Error::TooFew`] for fewer than 2 × 2 points.
    pub fn new(nu: usize, nv: usize, dim: usize, data: &'a [f64]) -> lekalo::Result<Self> {
        if nu < 2 || nv < 2 {
            return Err(lekalo::Error::TooFew {
                what: "grid rows and columns".into(),
                min: 2,
                got: nu.min(nv),
            });
        }
        let expected = nu.saturating_mul(nv).saturating_mul(dim);
        if data.len() != expected || dim == 0 {
            return Err(lekalo::Error::LengthMismatch {
                what: "grid data (rows × columns × dimension)".into(),
                expected,
                got: data.len(),
            });
        }
        Ok(Grid { nu, nv, dim, data })
    }

    /// Point `(i, j)` padded to 3-D (missing coordinates are 0).
    #[must_use]
    pub fn point3(&self, i: usize, j: usize) -> [f64; 3] {
        let base = (i * self.nv + j) * self.dim;
        let mut p = [0.0; 3];
        for (k, v) in p.iter_mut().enumerate().take(self.dim) {
            *v = self.data[base + k];
        }
        p
    }
}

/// Orthographic view from the direction given by azimuth (about the z axis) and elevation
/// (above the xy plane), in degrees. The default (azimuth −60°, elevation 30°) is the usual
/// engineering view.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Projection {
    /// Rotation about the z axis, degrees.
    pub azimuth: f64,
    /// Angle of the eye above the xy plane, degrees.
    pub elevation: f64,
}

impl Default for Projection {
    fn default() -> Self {
        Projection {
            azimuth: -60.0,
            elevation: 30.0,
        }
    }
}

impl Projection {
    /// The view's right-handed frame: screen right, screen up, and the unit vector toward the
    /// eye (right × up = toward the eye, so the picture is never a mirror image).
    #[must_use]
    pub fn frame(&self) -> [[f64; 3]; 3] {
        let (sa, ca) = self.azimuth.to_radians().sin_cos();
        let (se, ce) = self.elevation.to_radians().sin_cos();
        [
            [ca, -sa, 0.0],
            [se * sa, se * ca, ce],
            [-ce * sa, -ce * ca, se],
        ]
    }

    /// Screen coordinates of a 3-D point: rotate by −azimuth about z, then tilt by the
    /// elevation about the screen's x axis, and drop the depth.
    #[must_use]
    pub fn project(&self, p: [f64; 3]) -> [f64; 2] {
        let [r, u, _] = self.frame();
        [dot(r, p), dot(u, p)]
    }

    /// Plot coordinates of a point of any dimension, as curve plots place it: 1-D as `(x, 0)`,
    /// 2-D as is, 3-D or more through [`Projection::project`] of the first three coordinates.
    #[must_use]
    pub fn to_plane(&self, p: &[f64]) -> [f64; 2] {
        match p {
            [] => [0.0, 0.0],
            [x] => [*x, 0.0],
            [x, y] => [*x, *y],
            [x, y, z, ..] => self.project([*x, *y, *z]),
        }
    }

    /// Distance toward the eye (larger is nearer): the sort key of the painter's algorithm.
    #[must_use]
    pub fn depth(&self, p: [f64; 3]) -> f64 {
        dot(self.frame()[2], p)
    }
}

/// Dot product in 3-D.
pub(crate) fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

impl Projection {
    /// `(right × up) · toward`: 1 for a right-handed frame.
    #[cfg(test)]
    fn handed(&self) -> f64 {
        let [r, u, t] = self.frame();
        let c = [
            r[1] * u[2] - r[2] * u[1],
            r[2] * u[0] - r[0] * u[2],
            r[0] * u[1] - r[1] * u[0],
        ];
        dot(c, t)
    }
}

/// Wireframe of a grid: one polyline per row and per column, projected.
#[must_use]
pub fn wireframe_figure(title: &str, grid: &Grid<'_>, projection: &Projection) -> Figure {
    let mut fig = Figure::new(title, true);
    fig.axes = false;
    let mut paths = Vec::with_capacity(grid.nu + grid.nv);
    for i in 0..grid.nu {
        paths.push(
            (0..grid.nv)
                .map(|j| projection.project(grid.point3(i, j)))
                .collect(),
        );
    }
    for j in 0..grid.nv {
        paths.push(
            (0..grid.nu)
                .map(|i| projection.project(grid.point3(i, j)))
                .collect(),
        );
    }
    fig.series.push(Series {
        label: None,
        paths,
        style: Style::Line,
        color: PALETTE[0].to_string(),
        dash: None,
        marker: None,
    });
    fig
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn projection_and_wireframe() {
        let top = Projection {
            azimuth: 0.0,
            elevation: 90.0,
        };
        // from above, x goes right and y up the screen: a right-handed view, not a mirror
        let p = top.project([1.0, 2.0, 5.0]);
        assert!(
            (p[0] - 1.0).abs() < 1e-15 && (p[1] - 2.0).abs() < 1e-12,
            "{p:?}"
        );
        assert!(
            (Projection::default().handed() - 1.0).abs() < 1e-12,
            "right × up = toward the eye"
        );
        assert!(
            top.depth([0.0, 0.0, 1.0]) > top.depth([0.0, 0.0, 0.0]),
            "z nearer from above"
        );
        let front = Projection {
            azimuth: 0.0,
            elevation: 0.0,
        };
        assert_eq!(front.project([1.0, 2.0, 5.0]), [1.0, 5.0]);
        let data: Vec<f64> = (0..12).map(f64::from).collect();
        let g = Grid::new(2, 2, 3, &data).unwrap();
        assert_eq!(g.point3(1, 0), [6.0, 7.0, 8.0]);
        let fig = wireframe_figure("w", &g, &Projection::default());
        assert_eq!(fig.series[0].paths.len(), 4);
        assert!(Grid::new(2, 2, 3, &data[1..]).is_err());
        assert!(Grid::new(1, 12, 1, &data).is_err());
    }
}
