//! [`Face`], [`Loop`] and [`Edge`]: a surface trimmed by loops of edges (ISO 10303-42 §5.4,
//! `advanced_face`), each edge directed along its loop, with its 3-D curve and, where known,
//! its curve in the surface's parameters (`pcurve`).

use crate::error::readable;
use crate::{Curve, Error, Result, Surface};

/// The default tolerance of [`Face::new`] on the gaps of a loop, relative to the model size
/// (the diagonal of the bounding box of the control points of the surface and of the edges,
/// which contain them: P&T §2.3 and §4.2, convex hull property). `1e-4` accepts the gaps of
/// files exported with a sewing tolerance of 0.01 mm on a part of 100 mm, and refuses edges
/// taken from another loop.
pub const LOOP_CLOSURE_RTOL: f64 = 1e-4;

/// One edge of a loop, directed along the loop: its 3-D curve runs from the edge's start to
/// its end as the loop traverses it (the `same_sense` of the edge and the `orientation` of its
/// use in the loop applied), and so does its curve in the surface's `(u, v)` when there is one.
#[derive(Debug, Clone, PartialEq)]
pub struct Edge {
    curve: Curve,
    pcurve: Option<Curve>,
}

impl Edge {
    /// An edge from its curve (in the surface's space) and its curve in the surface's
    /// parameters, both directed along the loop.
    ///
    /// ```
    /// use lekalo::{topology::Edge, BSplineCurve, Curve};
    /// let c = Curve::from(BSplineCurve::line_segment(&[0.0, 0.0, 0.0], &[1.0, 0.0, 0.0], 0.0, 1.0)?);
    /// let p = Curve::from(BSplineCurve::line_segment(&[0.0, 0.0], &[1.0, 0.0], 0.0, 1.0)?);
    /// assert!(Edge::new(c.clone(), Some(p)).is_ok());
    /// assert!(Edge::new(c.clone(), Some(c)).is_err()); // a pcurve is 2-D
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::Dimension`] when the pcurve is not 2-D.
    pub fn new(curve: Curve, pcurve: Option<Curve>) -> Result<Self> {
        if let Some(p) = &pcurve {
            if p.dim() != 2 {
                return Err(Error::Dimension {
                    what: "pcurve (a curve in the surface's (u, v))".into(),
                    expected: 2,
                    got: p.dim(),
                });
            }
        }
        Ok(Edge { curve, pcurve })
    }

    /// The 3-D curve, directed along the loop.
    #[must_use]
    pub fn curve(&self) -> &Curve {
        &self.curve
    }

    /// The curve in the surface's `(u, v)`, directed along the loop, when known.
    #[must_use]
    pub fn pcurve(&self) -> Option<&Curve> {
        self.pcurve.as_ref()
    }
}

/// A closed chain of edges, each starting where the one before ends (the last closing on the
/// first).
#[derive(Debug, Clone, PartialEq)]
pub struct Loop {
    edges: Vec<Edge>,
}

impl Loop {
    /// A loop of `edges` in their order along it. Closure is checked by [`Face::new`], whose
    /// tolerance depends on the model size.
    ///
    /// # Errors
    /// [`Error::TooFew`] for no edge.
    pub fn new(edges: Vec<Edge>) -> Result<Self> {
        if edges.is_empty() {
            return Err(Error::TooFew {
                what: "edges in a loop".into(),
                min: 1,
                got: 0,
            });
        }
        Ok(Loop { edges })
    }

    /// The edges in their order along the loop.
    #[must_use]
    pub fn edges(&self) -> &[Edge] {
        &self.edges
    }

    /// True when every edge has its curve in the surface's `(u, v)`.
    #[must_use]
    pub fn has_pcurves(&self) -> bool {
        self.edges.iter().all(|e| e.pcurve.is_some())
    }

    /// The largest distance between the end of an edge and the start of the next (the last
    /// edge's end against the first's start), in space or, with `uv`, in the surface's
    /// parameters (`None` then when an edge has no pcurve), and the edge after which it is.
    ///
    /// # Errors
    /// As [`Curve::eval`] (not expected on a curve's own domain).
    pub fn largest_gap(&self, uv: bool) -> Result<Option<(f64, usize)>> {
        let ends = |e: &Edge| -> Result<Option<(Vec<f64>, Vec<f64>)>> {
            let c = if uv {
                e.pcurve.as_ref()
            } else {
                Some(&e.curve)
            };
            let Some(c) = c else { return Ok(None) };
            let (a, b) = c.domain();
            Ok(Some((c.eval(a)?, c.eval(b)?)))
        };
        let mut pts = Vec::with_capacity(self.edges.len());
        for e in &self.edges {
            match ends(e)? {
                Some(p) => pts.push(p),
                None => return Ok(None),
            }
        }
        let mut worst: Option<(f64, usize)> = None;
        for k in 0..pts.len() {
            let next = &pts[(k + 1) % pts.len()].0;
            let d = distance(&pts[k].1, next);
            if worst.is_none_or(|(w, _)| d > w) {
                worst = Some((d, k));
            }
        }
        Ok(worst)
    }
}

/// A face: a surface trimmed by an outer loop and inner loops (holes). `same_sense` says
/// whether the face's normal is the surface's (ISO 10303-42 `advanced_face.same_sense`); the
/// loops are kept as given, so the outer loop may run either way round.
#[derive(Debug, Clone, PartialEq)]
pub struct Face {
    surface: Surface,
    outer: Loop,
    inner: Vec<Loop>,
    same_sense: bool,
}

impl Face {
    /// A face of `surface` bounded by `outer` with the holes `inner`, checked: the edges' curves
    /// have the surface's dimension, and each loop closes in space within `rtol` times the
    /// model size (the diagonal of the bounding box of all control points; see
    /// [`LOOP_CLOSURE_RTOL`]). Loops are not required to close in `(u, v)`: on a closed
    /// surface a loop may go round the seam.
    ///
    /// ```
    /// use lekalo::topology::{Edge, Face, Loop, LOOP_CLOSURE_RTOL};
    /// use lekalo::{BSplineCurve, BSplineSurface, Curve, Points, Surface};
    /// let plane = Surface::from(BSplineSurface::new(1, 1, vec![0.0, 0.0, 1.0, 1.0],
    ///     vec![0.0, 0.0, 1.0, 1.0], Points::from_3d(&[[0.0, 0.0, 0.0], [0.0, 1.0, 0.0],
    ///     [1.0, 0.0, 0.0], [1.0, 1.0, 0.0]])?, (2, 2))?);
    /// let c = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
    /// let edges = (0..4).map(|k| {
    ///     let (a, b) = (c[k], c[(k + 1) % 4]);
    ///     let d = [b[0] - a[0], b[1] - a[1]];
    ///     Edge::new(
    ///         Curve::from(BSplineCurve::line_segment(&[a[0], a[1], 0.0], &[d[0], d[1], 0.0], 0.0, 1.0)?),
    ///         Some(Curve::from(BSplineCurve::line_segment(&a, &d, 0.0, 1.0)?)),
    ///     )
    /// }).collect::<lekalo::Result<Vec<_>>>()?;
    /// let face = Face::new(plane, Loop::new(edges)?, vec![], true, LOOP_CLOSURE_RTOL)?;
    /// assert!(face.trim_region()?.contains(0.5, 0.5));
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for a negative or non-finite `rtol`; [`Error::Dimension`]
    /// for an edge curve whose dimension is not the surface's; [`Error::InvalidArgument`]
    /// (`what` "face loop") naming the loop, the edge and the gap when a loop does not close.
    pub fn new(
        surface: Surface,
        outer: Loop,
        inner: Vec<Loop>,
        same_sense: bool,
        rtol: f64,
    ) -> Result<Self> {
        if !(rtol.is_finite() && rtol >= 0.0) {
            return Err(Error::InvalidArgument {
                what: "loop closure tolerance".into(),
                reason: format!(
                    "{rtol} must be finite and at least 0",
                    rtol = readable(&rtol)
                ),
            });
        }
        let dim = surface.dim();
        let face = Face {
            surface,
            outer,
            inner,
            same_sense,
        };
        for lp in face.loops() {
            for e in &lp.edges {
                if e.curve.dim() != dim {
                    return Err(Error::Dimension {
                        what: "edge curve (the surface's dimension)".into(),
                        expected: dim,
                        got: e.curve.dim(),
                    });
                }
            }
        }
        let tol = rtol * face.model_size();
        for (i, lp) in face.loops().enumerate() {
            if let Some((gap, k)) = lp.largest_gap(false)? {
                if gap > tol {
                    let which = if i == 0 {
                        "the outer loop".to_string()
                    } else {
                        format!("inner loop {i}")
                    };
                    return Err(Error::InvalidArgument {
                        what: "face loop".into(),
                        reason: format!(
                            "{which} does not close: edge {k} ends {gap:.3e} from the start of edge {} (tolerance {tol:.3e}, {rtol:e} of the model size); the edges are not in loop order, or a wrong edge is in the loop",
                            (k + 1) % lp.edges.len()
                        ),
                    });
                }
            }
        }
        Ok(face)
    }

    /// A face from parts already checked by [`Face::new`] (the same surface and 3-D curves).
    pub(super) fn from_parts(
        surface: Surface,
        outer: Loop,
        inner: Vec<Loop>,
        same_sense: bool,
    ) -> Self {
        Face {
            surface,
            outer,
            inner,
            same_sense,
        }
    }

    /// The diagonal of the bounding box of the control points of the surface and of the edges'
    /// curves: the scale of the closure tolerance.
    #[must_use]
    pub fn model_size(&self) -> f64 {
        let dim = self.surface.dim();
        let mut lo = vec![f64::INFINITY; dim];
        let mut hi = vec![f64::NEG_INFINITY; dim];
        let mut add = |p: &[f64]| {
            for k in 0..dim.min(p.len()) {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        };
        self.surface.control_points().iter().for_each(&mut add);
        for lp in self.loops() {
            for e in &lp.edges {
                e.curve.control_points().iter().for_each(&mut add);
            }
        }
        let d: f64 = lo.iter().zip(&hi).map(|(a, b)| (b - a) * (b - a)).sum();
        if d.is_finite() {
            d.sqrt()
        } else {
            0.0
        }
    }

    /// The surface.
    #[must_use]
    pub fn surface(&self) -> &Surface {
        &self.surface
    }

    /// The outer loop.
    #[must_use]
    pub fn outer(&self) -> &Loop {
        &self.outer
    }

    /// The inner loops (holes).
    #[must_use]
    pub fn inner(&self) -> &[Loop] {
        &self.inner
    }

    /// The outer loop, then the inner loops.
    pub fn loops(&self) -> impl Iterator<Item = &Loop> {
        std::iter::once(&self.outer).chain(&self.inner)
    }

    /// True when the face's normal is the surface's.
    #[must_use]
    pub fn same_sense(&self) -> bool {
        self.same_sense
    }

    /// The number of edges over all loops.
    #[must_use]
    pub fn edge_count(&self) -> usize {
        self.loops().map(|l| l.edges.len()).sum()
    }

    /// True when every edge of every loop has its pcurve, as meshing the trimmed region
    /// ([`mesh_faces`](crate::topology::mesh_faces)) needs.
    #[must_use]
    pub fn has_pcurves(&self) -> bool {
        self.loops().all(Loop::has_pcurves)
    }
}

fn distance(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y) * (x - y))
        .sum::<f64>()
        .sqrt()
}
