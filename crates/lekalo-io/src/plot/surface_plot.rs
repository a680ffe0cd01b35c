//! Surfaces that read as surfaces: a grid of surface points drawn as shaded quadrilaterals in
//! an orthographic view, back to front (the painter's algorithm), coloured by height and lit by
//! a fixed light, with isoparametric lines, the control net, 3-D axes with ticks, and a colour
//! scale. The same figure renders to SVG and, through resvg, to PNG.
//!
//! Shading is flat (one colour per quadrilateral, Lambert's cosine law with the light above
//! the viewer's left shoulder, lit from both sides so that the underside of a surface is not
//! black). The painter's algorithm is exact for the small, nearly planar faces of a sampled
//! smooth surface except where a surface passes through itself.

use crate::palette::{height_rgb, hex, PALETTE};
use crate::svg::{fmt_tick, nice_ticks, Annotation, ColorBar, Face, Figure, Series, Style};
use crate::wireframe::{dot, Grid, Projection};

/// How a surface is drawn.
#[derive(Debug, Clone, PartialEq)]
pub struct SurfacePlot {
    /// Title of the figure.
    pub title: String,
    /// The view.
    pub projection: Projection,
    /// Shaded faces coloured by height (else a hidden-line wireframe of every grid line).
    pub shaded: bool,
    /// Isoparametric lines drawn on the shaded surface, per direction (0: none).
    pub iso_lines: usize,
    /// 3-D axes with ticks along the bounding box.
    pub axes: bool,
    /// Values at the grid's points that colour the shaded faces instead of the height (a
    /// curvature map); `None` colours by height.
    pub colors: Option<ColorField>,
}

/// A scalar field on the plotted grid, one value a grid point (`u` outer, as the grid), that
/// colours a shaded surface: each face takes the mean of its four corners' values on the
/// colour bar from the least to the largest finite value. A face with an undefined corner
/// (`None` or not finite: a curvature where the normal is undefined) is drawn grey.
#[derive(Debug, Clone, PartialEq)]
pub struct ColorField {
    /// The colour bar's label, e.g. `Gaussian curvature`.
    pub label: String,
    /// One value a grid point.
    pub values: Vec<Option<f64>>,
}

impl SurfacePlot {
    /// Shaded, eight isoparametric lines each way, with axes, in the default view.
    #[must_use]
    pub fn new(title: &str) -> Self {
        SurfacePlot {
            title: title.to_string(),
            projection: Projection::default(),
            shaded: true,
            iso_lines: 8,
            axes: true,
            colors: None,
        }
    }
}

/// Grid points per direction of a surface plot by default: 32 × 32 faces look smooth at the
/// figure's size and stay readable (and small) as SVG.
pub const SURFACE_SAMPLES: usize = 33;

/// Cross product.
fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// Indices `0 = k_0 < k_1 < … = n − 1` of `lines + 1` evenly spread grid lines (none for 0).
fn iso_indices(n: usize, lines: usize) -> Vec<bool> {
    let mut on = vec![false; n];
    if lines == 0 || n < 2 {
        return on;
    }
    let lines = lines.min(n - 1);
    for k in 0..=lines {
        on[(k * (n - 1) + lines / 2) / lines] = true;
    }
    on[0] = true;
    on[n - 1] = true;
    on
}

/// The figure of a surface sampled on `grid` (points of dimension 2 or 3; 2-D grids lie in the
/// plane z = 0), with its control net if given. Faces with a non-finite corner are left out.
#[must_use]
pub fn surface_plot(grid: &Grid<'_>, net: Option<&Grid<'_>>, opts: &SurfacePlot) -> Figure {
    let proj = &opts.projection;
    let mut fig = Figure::new(&opts.title, true);
    fig.axes = false;
    fig.size = (560.0, 440.0);
    let (nu, nv) = (grid.nu, grid.nv);
    let mut pts: Vec<[f64; 3]> = (0..nu)
        .flat_map(|i| (0..nv).map(move |j| (i, j)))
        .map(|(i, j)| grid.point3(i, j))
        .collect();

    let finite = |p: &[f64; 3]| p.iter().all(|x| x.is_finite());
    // bounding box of the finite points (and of the net)
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    let mut net_pts: Vec<[f64; 3]> = net
        .map(|n| {
            (0..n.nu)
                .flat_map(|i| (0..n.nv).map(move |j| (i, j)))
                .map(|(i, j)| n.point3(i, j))
                .collect()
        })
        .unwrap_or_default();
    for p in pts.iter().chain(&net_pts).filter(|p| finite(p)) {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    if !lo[0].is_finite() {
        return fig;
    }
    // a flat surface is drawn with its heights stretched (the z ticks keep the true values)
    let zscale = z_stretch(lo, hi);
    for p in pts.iter_mut().chain(net_pts.iter_mut()) {
        p[2] *= zscale;
    }
    lo[2] *= zscale;
    hi[2] *= zscale;
    // colours span the surface's heights (the net may reach beyond them)
    let (zlo, zhi) = pts
        .iter()
        .filter(|p| finite(p))
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| {
            (a.min(p[2]), b.max(p[2]))
        });
    let zspan = zhi - zlo;
    let height = |z: f64| if zspan > 0.0 { (z - zlo) / zspan } else { 0.5 };
    // a colour field given for every grid point, and the range of its finite values
    let field = opts
        .colors
        .as_ref()
        .filter(|f| f.values.len() == nu * nv)
        .map(|f| {
            let (lo, hi) = f
                .values
                .iter()
                .flatten()
                .filter(|x| x.is_finite())
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| {
                    (a.min(*x), b.max(*x))
                });
            (f, lo, hi)
        });
    let face_value = |i: usize, j: usize| -> Option<f64> {
        let (f, _, _) = field?;
        let mut sum = 0.0;
        for (a, b) in [(i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1)] {
            let x = f.values[a * nv + b]?;
            if !x.is_finite() {
                return None;
            }
            sum += x;
        }
        Some(0.25 * sum)
    };
    let at = |i: usize, j: usize| pts[i * nv + j];
    let [r, u, t] = proj.frame();
    let light = {
        let l = [
            -0.45 * r[0] + 0.65 * u[0] + 0.6 * t[0],
            -0.45 * r[1] + 0.65 * u[1] + 0.6 * t[1],
            -0.45 * r[2] + 0.65 * u[2] + 0.6 * t[2],
        ];
        let n = dot(l, l).sqrt();
        [l[0] / n, l[1] / n, l[2] / n]
    };
    let iso_u = iso_indices(nu, if opts.shaded { opts.iso_lines } else { nu });
    let iso_v = iso_indices(nv, if opts.shaded { opts.iso_lines } else { nv });
    let (edge_color, fill_plain) = if opts.shaded {
        ("#2a2a2a".to_string(), None)
    } else {
        (PALETTE[0].to_string(), Some("white".to_string()))
    };
    let mut faces: Vec<(f64, Face)> = Vec::with_capacity((nu - 1) * (nv - 1));
    for i in 0..nu - 1 {
        for j in 0..nv - 1 {
            let c = [at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)];
            if !c.iter().all(finite) {
                continue;
            }
            let n = cross(sub(c[2], c[0]), sub(c[3], c[1]));
            let len = dot(n, n).sqrt();
            let lambert = if len > 0.0 {
                (dot(n, light) / len).abs()
            } else {
                1.0
            };
            let mean_z = 0.25 * (c[0][2] + c[1][2] + c[2][2] + c[3][2]);
            let shade = 0.45 + 0.6 * lambert;
            let fill = match (&fill_plain, field) {
                (Some(plain), _) => plain.clone(),
                (None, Some((_, lo, hi))) => match face_value(i, j) {
                    Some(x) if hi > lo => hex(height_rgb((x - lo) / (hi - lo)), shade),
                    Some(_) => hex(height_rgb(0.5), shade),
                    None => hex([190.0, 190.0, 190.0], shade),
                },
                (None, None) => hex(height_rgb(height(mean_z)), shade),
            };
            let p: Vec<[f64; 2]> = c.iter().map(|q| proj.project(*q)).collect();
            let mut edges = Vec::new();
            if iso_u[i] {
                edges.push([p[0], p[3]]);
            }
            if iso_u[i + 1] {
                edges.push([p[1], p[2]]);
            }
            if iso_v[j] {
                edges.push([p[0], p[1]]);
            }
            if iso_v[j + 1] {
                edges.push([p[3], p[2]]);
            }
            let centre = [
                0.25 * (c[0][0] + c[1][0] + c[2][0] + c[3][0]),
                0.25 * (c[0][1] + c[1][1] + c[2][1] + c[3][1]),
                mean_z,
            ];
            faces.push((
                proj.depth(centre),
                Face {
                    points: p,
                    fill,
                    edges,
                    edge_style: (edge_color.clone(), if opts.shaded { 0.7 } else { 1.0 }),
                },
            ));
        }
    }
    faces.sort_by(|a, b| a.0.total_cmp(&b.0));
    if opts.axes {
        axes_3d(&mut fig, proj, lo, hi, zscale);
    }
    fig.faces.extend(faces.into_iter().map(|(_, f)| f));
    match field {
        Some((f, lo, hi)) if opts.shaded && lo <= hi => {
            fig.colorbar = Some(ColorBar {
                label: f.label.clone(),
                range: (lo, hi),
            });
        }
        _ if opts.shaded && zspan > 0.0 => {
            fig.colorbar = Some(ColorBar {
                label: "z".into(),
                range: (zlo / zscale, zhi / zscale),
            });
        }
        _ => {}
    }
    if let Some(n) = net {
        let mut paths = Vec::with_capacity(n.nu + n.nv);
        let at = |i: usize, j: usize| proj.project(net_pts[i * n.nv + j]);
        for i in 0..n.nu {
            paths.push((0..n.nv).map(|j| at(i, j)).collect());
        }
        for j in 0..n.nv {
            paths.push((0..n.nu).map(|i| at(i, j)).collect());
        }
        let mut s = Series::new(Some("control net"), Vec::new(), Style::Dashed, "#555555");
        s.paths = paths;
        fig.series.push(s);
        let points = net_pts.iter().map(|p| proj.project(*p)).collect();
        fig.series
            .push(Series::new(None, points, Style::Markers, "#555555"));
    }
    fig
}

/// The factor that stretches the heights of a flat surface so that its box is at least
/// [`MIN_BOX_HEIGHT`] as tall as it is wide: 1, or a round 1, 2, 2.5, 4 or 5 × 10^k (matplotlib's
/// 3-D axes, by comparison, scale every axis to a cube).
fn z_stretch(lo: [f64; 3], hi: [f64; 3]) -> f64 {
    let wide = (hi[0] - lo[0]).max(hi[1] - lo[1]);
    let tall = hi[2] - lo[2];
    if !(tall > 0.0 && wide.is_finite()) || tall >= MIN_BOX_HEIGHT * wide {
        return 1.0;
    }
    let want = MIN_BOX_HEIGHT * wide / tall;
    let mag = 10f64.powf(want.log10().floor());
    [1.0, 2.0, 2.5, 4.0, 5.0, 10.0]
        .iter()
        .map(|m| m * mag)
        .find(|f| *f >= want)
        .filter(|f| f.is_finite())
        .unwrap_or(1.0)
}

/// Least height of the plotted box relative to its width ([`z_stretch`]).
const MIN_BOX_HEIGHT: f64 = 0.4;

/// Least distance on the page between two tick labels of the vertical axis, pixels (a line
/// of the 12 px font).
const TICK_GAP: f64 = 18.0;

/// The floor of the bounding box, its vertical edge at the back, ticks with values on the
/// front floor edges and on the vertical edge, and the axis names; drawn behind the surface.
/// Heights are drawn `zscale` times their value ([`z_stretch`]); the ticks show the values.
fn axes_3d(fig: &mut Figure, proj: &Projection, lo: [f64; 3], hi: [f64; 3], zscale: f64) {
    let t = proj.frame()[2];
    // the back corner is the one farther from the eye
    let back = |k: usize| if t[k] > 0.0 { lo[k] } else { hi[k] };
    let front = |k: usize| if t[k] > 0.0 { hi[k] } else { lo[k] };
    let (xb, yb, xf, yf, z0) = (back(0), back(1), front(0), front(1), lo[2]);
    let pr = |p: [f64; 3]| proj.project(p);
    // the vertical axis stands at the floor's leftmost corner on the screen, beside the
    // surface rather than behind it
    let (xz, yz) = [(xb, yb), (xf, yb), (xb, yf), (xf, yf)]
        .into_iter()
        .min_by(|a, b| pr([a.0, a.1, z0])[0].total_cmp(&pr([b.0, b.1, z0])[0]))
        .unwrap_or((xb, yb));
    let mut edges = vec![
        [pr([xb, yb, z0]), pr([xf, yb, z0])],
        [pr([xb, yb, z0]), pr([xb, yf, z0])],
        [pr([xf, yb, z0]), pr([xf, yf, z0])],
        [pr([xb, yf, z0]), pr([xf, yf, z0])],
        [pr([xz, yz, z0]), pr([xz, yz, hi[2]])],
    ];
    let span = |k: usize| (hi[k] - lo[k]).max(1e-300);
    let out_y = 0.04 * span(0).max(span(1)) * (yf - yb).signum();
    let out_x = 0.04 * span(0).max(span(1)) * (xf - xb).signum();
    let screen_centre = pr([
        0.5 * (lo[0] + hi[0]),
        0.5 * (lo[1] + hi[1]),
        0.5 * (lo[2] + hi[2]),
    ]);
    // a label goes on the side of the tick away from the picture's centre
    let place = |tip: [f64; 2]| {
        if tip[0] < screen_centre[0] {
            ("end", (-4.0, 9.0))
        } else {
            ("start", (4.0, 9.0))
        }
    };
    let mut notes = Vec::new();
    // a floor tick at the foot of the vertical axis would stand in the column of its labels and
    // read as a height: it is left out, as the y axis's tick at the front corner is
    let near = |k: usize| 0.05 * span(k);
    if hi[0] > lo[0] {
        for v in nice_ticks(lo[0], hi[0])
            .into_iter()
            .filter(|v| yz != yf || (v - xz).abs() > near(0))
        {
            let (a, b) = (pr([v, yf, z0]), pr([v, yf + out_y, z0]));
            edges.push([a, b]);
            let (anchor, offset) = place(b);
            notes.push((b, offset, fmt_tick(v), anchor));
        }
        let m = pr([0.5 * (lo[0] + hi[0]), yf + 3.5 * out_y, z0]);
        let (anchor, offset) = place(m);
        notes.push((m, (offset.0, offset.1 + 8.0), "x".into(), anchor));
    }
    if hi[1] > lo[1] {
        // the tick at the front corner would collide with the x axis's
        for v in nice_ticks(lo[1], hi[1])
            .into_iter()
            .filter(|v| (v - yf).abs() > near(1) && (xz != xf || (v - yz).abs() > near(1)))
        {
            let (a, b) = (pr([xf, v, z0]), pr([xf + out_x, v, z0]));
            edges.push([a, b]);
            let (anchor, offset) = place(b);
            notes.push((b, offset, fmt_tick(v), anchor));
        }
        let m = pr([xf + 3.5 * out_x, 0.5 * (lo[1] + hi[1]), z0]);
        let (anchor, offset) = place(m);
        notes.push((m, (offset.0, offset.1 + 8.0), "y".into(), anchor));
    }
    if hi[2] > lo[2] {
        // ticks on the vertical axis point away from the floor's centre
        let d = 0.03 * span(0).max(span(1));
        let (dx, dy) = (
            (xz - 0.5 * (lo[0] + hi[0])).signum() * d,
            (yz - 0.5 * (lo[1] + hi[1])).signum() * d,
        );
        // pixels per unit on the page, as the figure will be laid out (the plot's width and
        // height over the projected box, padded by 5 % a side)
        let corners: Vec<[f64; 2]> = (0..8)
            .map(|k| {
                pr([
                    if k & 1 == 0 { lo[0] } else { hi[0] },
                    if k & 2 == 0 { lo[1] } else { hi[1] },
                    if k & 4 == 0 { lo[2] } else { hi[2] },
                ])
            })
            .collect();
        let extent = |k: usize| {
            let (a, b) = corners
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| {
                    (a.min(p[k]), b.max(p[k]))
                });
            (b - a).max(1e-300)
        };
        let (pw, ph) = (fig.size.0 - 80.0, fig.size.1 - 98.0);
        let px = (pw / extent(0)).min(ph / extent(1)) / 1.1;
        // page distance of a height above the floor
        let rise = |v: f64| (v * zscale - lo[2]) * proj.frame()[1][2] * px;
        let ticks = nice_ticks(lo[2] / zscale, hi[2] / zscale);
        let step = if ticks.len() > 1 {
            rise(ticks[1]) - rise(ticks[0])
        } else {
            f64::INFINITY
        };
        // every k-th round value, a line apart; none at the floor, where the floor's own tick
        // labels stand
        let every = (TICK_GAP / step.max(f64::MIN_POSITIVE))
            .ceil()
            .clamp(1.0, 64.0);
        // at most 64, so the cast is exact
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let every = every as usize;
        let top_index = ticks.len().saturating_sub(1);
        for (k, v) in ticks.iter().enumerate() {
            // the highest tick is kept, the others counted down from it
            if (top_index - k) % every != 0 || rise(*v) < TICK_GAP {
                continue;
            }
            let (a, b) = (pr([xz, yz, v * zscale]), pr([xz + dx, yz + dy, v * zscale]));
            edges.push([a, b]);
            let (anchor, offset) = place(b);
            notes.push((b, (offset.0, 4.0), fmt_tick(*v), anchor));
        }
        let m = pr([xz, yz, hi[2]]);
        let name = if zscale == 1.0 {
            "z".to_string()
        } else {
            format!("z (drawn ×{})", fmt_tick(zscale))
        };
        // beside the axis's top, on the side away from its tick labels: above it the name
        // would stand in the legend's row and read as part of the last entry
        let (side, _) = place(pr([xz + dx, yz + dy, hi[2]]));
        let (anchor, side) = if side == "end" {
            ("start", 6.0)
        } else {
            ("end", -6.0)
        };
        notes.push((m, (side, 4.0), name, anchor));
    }
    fig.faces.push(Face {
        points: Vec::new(),
        fill: "none".into(),
        edges,
        edge_style: ("#999999".into(), 1.0),
    });
    fig.annotations.extend(
        notes
            .into_iter()
            .map(|(at, offset, text, anchor)| Annotation {
                at,
                offset,
                text,
                anchor,
            }),
    );
}

#[cfg(test)]
mod tests {
    use super::*;

    fn saddle(n: usize) -> Vec<f64> {
        let mut data = Vec::new();
        for i in 0..n {
            for j in 0..n {
                let (x, y) = (i as f64 / (n - 1) as f64, j as f64 / (n - 1) as f64);
                data.extend([x, y, (x - 0.5) * (y - 0.5)]);
            }
        }
        data
    }

    #[test]
    fn faces_back_to_front_with_iso_lines() {
        let data = saddle(9);
        let g = Grid::new(9, 9, 3, &data).unwrap();
        let opts = SurfacePlot::new("saddle");
        let fig = surface_plot(&g, Some(&g), &opts);
        // the axes' lines come first, then 8 × 8 faces
        assert_eq!(fig.faces.len(), 1 + 64);
        assert!(fig.faces[0].points.is_empty(), "axes behind the surface");
        assert!(
            fig.faces[1..].iter().all(|f| f.points.len() == 4),
            "quadrilaterals"
        );
        assert!(
            opts.projection.frame()[2][2] > 0.0,
            "the eye is above the xy plane"
        );
        // 8 iso lines each way on 9 grid lines: every grid line is an iso line
        let n_edges: usize = fig.faces[1..].iter().map(|f| f.edges.len()).sum();
        assert_eq!(n_edges, 4 * 64, "every face edge on an iso line");
        assert!(fig.colorbar.is_some(), "height scale");
        let svg = fig.to_svg();
        assert!(!svg.contains("NaN") && svg.contains("control net"), "{svg}");
    }

    #[test]
    fn painter_order_and_bad_points() {
        let mut data = saddle(5);
        data[2] = f64::NAN;
        let g = Grid::new(5, 5, 3, &data).unwrap();
        let mut opts = SurfacePlot::new("s");
        opts.axes = false;
        opts.iso_lines = 0;
        let fig = surface_plot(&g, None, &opts);
        assert_eq!(
            fig.faces.len(),
            15,
            "the face at the NaN corner is left out"
        );
        assert!(fig.faces.iter().all(|f| f.edges.is_empty()), "no iso lines");
        // the nearest face is drawn last: the eye is at +x, −y (azimuth −60°), so the face
        // at the grid's corner (1, 0) comes after the one at (0, 1)
        let proj = opts.projection;
        let near = proj.depth([1.0, 0.0, 0.0]);
        let far = proj.depth([0.0, 1.0, 0.0]);
        assert!(near > far, "depth");
        let last = fig.faces.last().unwrap().points[0];
        assert!(
            (last[0] - proj.project([0.75, 0.0, data[(3 * 5) * 3 + 2]])[0]).abs() < 1e-12,
            "{last:?}"
        );
        assert_eq!(
            iso_indices(9, 2),
            [true, false, false, false, true, false, false, false, true]
        );
        assert_eq!(iso_indices(3, 0), [false; 3]);
    }

    /// The numbers written beside one another in a column (texts of one anchor at the same
    /// `x`, within 2 px), bottom to top: what a reader reads as one axis's scale.
    fn columns(svg: &str) -> Vec<Vec<f64>> {
        let mut notes: Vec<(String, f64, f64, f64)> = Vec::new();
        for t in svg.split("<text ").skip(1) {
            let attr = |name: &str| {
                t.split(&format!("{name}=\"")[..])
                    .nth(1)
                    .and_then(|v| v.split('"').next())
                    .map(str::to_string)
            };
            let text = t.split('>').nth(1).and_then(|v| v.split('<').next());
            if attr("class").as_deref() != Some("note") {
                continue;
            }
            let (Some(x), Some(y), Some(anchor), Some(Ok(v))) = (
                attr("x").and_then(|v| v.parse().ok()),
                attr("y").and_then(|v| v.parse().ok()),
                attr("text-anchor"),
                text.map(str::parse::<f64>),
            ) else {
                continue;
            };
            notes.push((anchor, x, y, v));
        }
        let mut out: Vec<Vec<f64>> = Vec::new();
        let mut used = vec![false; notes.len()];
        for i in 0..notes.len() {
            if used[i] {
                continue;
            }
            let mut col: Vec<(f64, f64)> = Vec::new();
            for j in i..notes.len() {
                if !used[j] && notes[j].0 == notes[i].0 && (notes[j].1 - notes[i].1).abs() < 2.0 {
                    used[j] = true;
                    col.push((notes[j].2, notes[j].3));
                }
            }
            // bottom (largest page y) to top
            col.sort_by(|a, b| b.0.total_cmp(&a.0));
            out.push(col.into_iter().map(|c| c.1).collect());
        }
        out
    }

    #[test]
    fn the_vertical_axis_reads_as_one_increasing_scale() {
        // the gallery's surface through a 5 × 4 grid on z = sin x · cos y: its vertical axis
        // stands at the foot of the x axis, whose tick 0 once stood in the column of the
        // heights and read as a second "0" under z = 0
        let mut data = Vec::new();
        for i in 0..5 {
            for j in 0..4 {
                let (x, y) = (0.75 * f64::from(i), 0.7 * f64::from(j));
                data.extend([x, y, x.sin() * y.cos()]);
            }
        }
        let g = Grid::new(5, 4, 3, &data).unwrap();
        for azimuth in [-60.0, -30.0, 30.0, 120.0, 210.0] {
            let mut opts = SurfacePlot::new("sin x cos y");
            opts.projection = Projection {
                azimuth,
                elevation: 25.0,
            };
            let svg = surface_plot(&g, None, &opts).to_svg();
            for col in columns(&svg) {
                assert!(
                    col.windows(2).all(|w| w[1] > w[0]),
                    "azimuth {azimuth}: a column of labels reads {col:?} upwards\n{svg}"
                );
            }
            // the axis's name is beside its top, not in the legend's row above the plot
            let z = svg
                .split("<text ")
                .find(|t| t.contains(">z</text>") && t.contains("class=\"note\""))
                .expect("the vertical axis is named");
            assert!(!z.contains("text-anchor=\"middle\""), "{z}");
        }
    }
}
