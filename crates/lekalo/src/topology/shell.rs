//! [`Shell`]: which edges of a set of faces are one edge used by two faces (or twice by one face,
//! a seam), and which edge ends are one vertex (ISO 10303-42 §5.4, `connected_face_set`,
//! `edge_curve`, `vertex_point`); what a writer needs to share `EDGE_CURVE`s and
//! `VERTEX_POINT`s, and a mesher to sample an edge once for both its faces.
//!
//! Two uses are the same edge when their 3-D curves have the same degree and the same control
//! points (and weights), bit for bit, in the same order or in reverse order: a face set read from
//! a file holds each shared edge as one curve, reversed where a loop runs it backwards
//! ([`crate::Curve::reverse`] copies the control points in reverse order). Edges that collapse to
//! a point (a pole) are never shared. An edge used more than twice keeps its first two uses and
//! starts a new edge for the others. See `docs/theory/topology.md`, "Shells".

use std::collections::HashMap;

use super::face::{Edge, Face};
use super::vertex::{vertex_point, EdgeEnd};
use crate::{Curve, Result};

/// One use of an edge: the face (its index in the set), the loop (0 for the outer loop, `i` for
/// inner loop `i − 1`) and the edge's place in the loop.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct EdgeUse {
    /// Index of the face in the set.
    pub face: usize,
    /// Index of the loop in the face: 0 the outer loop, then the inner loops.
    pub lp: usize,
    /// Index of the edge in the loop.
    pub edge: usize,
}

/// An edge of a [`Shell`]: its uses, each with whether it runs the way the first use does, and
/// its start and end vertices as the first use runs it.
#[derive(Debug, Clone, PartialEq)]
pub struct SharedEdge {
    /// The uses, the first one defining the edge's direction; `true` for a use that runs the same
    /// way, `false` for one that runs it backwards.
    pub uses: Vec<(EdgeUse, bool)>,
    /// The indices in [`Shell::vertices`] of the start and end of the first use.
    pub vertices: [usize; 2],
    /// True when the edge's curve collapses to a point (all its control points equal: the
    /// pole of a surface); such edges are not shared.
    pub collapsed: bool,
}

/// Faces with their shared edges and vertices.
#[derive(Debug, Clone, PartialEq)]
pub struct Shell {
    edges: Vec<SharedEdge>,
    vertices: Vec<Vec<f64>>,
    meets_ends: Vec<bool>,
    of_use: HashMap<EdgeUse, (usize, bool)>,
}

/// The bits of a curve's degree, control points and weights, in the order given or reversed: a
/// key that two uses of one edge share.
fn key(c: &Curve, reversed: bool) -> Vec<u64> {
    let pts = c.control_points();
    let dim = pts.dim();
    let w = c.weights();
    let n = pts.len();
    let mut k = Vec::with_capacity(1 + n * (dim + 1));
    k.push(c.degree() as u64);
    for i in 0..n {
        let j = if reversed { n - 1 - i } else { i };
        k.extend(pts.point(j).iter().map(|x| x.to_bits()));
        if let Some(w) = &w {
            k.push(w[j].to_bits());
        }
    }
    k
}

/// True when every control point of `c` is the first: the edge collapses to a point.
fn collapsed(c: &Curve) -> bool {
    let pts = c.control_points();
    let first = pts.point(0).to_vec();
    pts.iter().all(|p| p == first.as_slice())
}

/// The unit direction in which `c` runs away from its end at `t` (`C'(t)` at its last end,
/// `−C'(t)` at its first), or from its middle to the end where the derivative vanishes there
/// (a curve whose end control points coincide); zero for a curve that does not move.
fn outward(c: &Curve, t: f64, last: bool) -> Result<Vec<f64>> {
    let d = c.eval_derivatives(t, 1)?;
    let norm = |v: &[f64]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
    let sign = if last { 1.0 } else { -1.0 };
    let mut dir: Vec<f64> = d.point(1).iter().map(|x| sign * x).collect();
    if !(norm(&dir) > 0.0 && norm(&dir).is_finite()) {
        let (a, b) = c.domain();
        let mid = c.eval(0.5 * (a + b))?;
        dir = d.point(0).iter().zip(&mid).map(|(p, m)| p - m).collect();
    }
    let n = norm(&dir);
    Ok(if n > 0.0 && n.is_finite() {
        dir.iter().map(|x| x / n).collect()
    } else {
        vec![0.0; dir.len()]
    })
}

/// Union-find with path halving.
fn find(parent: &mut [usize], mut x: usize) -> usize {
    while parent[x] != x {
        parent[x] = parent[parent[x]];
        x = parent[x];
    }
    x
}

impl Shell {
    /// The shell of `faces`: uses of one edge found by their curves (see the module docs), the
    /// ends of edges that follow each other in a loop, or that are the same point bit for bit,
    /// joined into vertices. A vertex's point is the ends' point where they coincide; where they
    /// do not (a file's edges meet within its tolerance), a point past every end along its
    /// curve, so that each edge's nearest point to it is the edge's own end (see
    /// `docs/theory/topology.md`, "The point of a vertex"), or the first edge's end when there
    /// is none.
    ///
    /// ```
    /// use lekalo::topology::{Edge, Face, Loop, Shell, LOOP_CLOSURE_RTOL};
    /// use lekalo::{BSplineCurve, BSplineSurface, Curve, Points, Surface};
    /// // two unit squares side by side in z = 0, sharing the edge x = 1
    /// let square = |x0: f64| -> lekalo::Result<Face> {
    ///     let s = Surface::from(BSplineSurface::new(1, 1, vec![0.0, 0.0, 1.0, 1.0],
    ///         vec![0.0, 0.0, 1.0, 1.0], Points::from_3d(&[[x0, 0.0, 0.0], [x0, 1.0, 0.0],
    ///         [x0 + 1.0, 0.0, 0.0], [x0 + 1.0, 1.0, 0.0]])?, (2, 2))?);
    ///     let c = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
    ///     let edges = (0..4).map(|k| {
    ///         let (a, b) = (c[k], c[(k + 1) % 4]);
    ///         let pts = Points::from_3d(&[[x0 + a[0], a[1], 0.0], [x0 + b[0], b[1], 0.0]])?;
    ///         Edge::new(Curve::from(BSplineCurve::new(1, vec![0.0, 0.0, 1.0, 1.0], pts)?),
    ///             Some(Curve::from(BSplineCurve::line_segment(&a, &[b[0] - a[0], b[1] - a[1]], 0.0, 1.0)?)))
    ///     }).collect::<lekalo::Result<Vec<_>>>()?;
    ///     Face::new(s, Loop::new(edges)?, vec![], true, LOOP_CLOSURE_RTOL)
    /// };
    /// let (a, b) = (square(0.0)?, square(1.0)?);
    /// let shell = Shell::new(&[&a, &b])?;
    /// assert_eq!(shell.edges().len(), 7); // 4 + 4 edges, one of them shared
    /// assert_eq!(shell.vertices().len(), 6);
    /// assert!(!shell.is_closed());
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// As [`Curve::eval`] at the ends of the edges' curves (not expected on their own domains).
    pub fn new(faces: &[&Face]) -> Result<Shell> {
        let mut edges: Vec<SharedEdge> = Vec::new();
        let mut of_use = HashMap::new();
        // the keys of each edge's first use, in its own order and reversed
        let mut by_key: HashMap<Vec<u64>, (usize, bool)> = HashMap::new();
        let mut uses_in_order: Vec<Vec<Vec<(EdgeUse, &Edge)>>> = Vec::with_capacity(faces.len());
        for (fi, f) in faces.iter().enumerate() {
            let mut loops = Vec::new();
            for (li, lp) in f.loops().enumerate() {
                let mut list = Vec::with_capacity(lp.edges().len());
                for (ei, e) in lp.edges().iter().enumerate() {
                    let u = EdgeUse {
                        face: fi,
                        lp: li,
                        edge: ei,
                    };
                    list.push((u, e));
                    let c = e.curve();
                    let shared = if collapsed(c) {
                        None
                    } else {
                        by_key
                            .get(&key(c, false))
                            .copied()
                            .filter(|&(g, _)| edges[g].uses.len() < 2)
                    };
                    let (g, same) = match shared {
                        Some(gs) => gs,
                        None => {
                            let g = edges.len();
                            edges.push(SharedEdge {
                                uses: Vec::new(),
                                vertices: [0, 0],
                                collapsed: collapsed(c),
                            });
                            if !collapsed(c) {
                                // a later use with these control points runs the same way, one
                                // with them reversed runs backwards (a palindrome: the same way)
                                by_key.insert(key(c, true), (g, false));
                                by_key.insert(key(c, false), (g, true));
                            }
                            (g, true)
                        }
                    };
                    edges[g].uses.push((u, same));
                    of_use.insert(u, (g, same));
                }
                loops.push(list);
            }
            uses_in_order.push(loops);
        }
        // vertices: the ends 2g (start of the first use) and 2g + 1 (its end), joined where one
        // edge ends and the next starts in a loop, and where two ends are the same point
        let mut parent: Vec<usize> = (0..2 * edges.len()).collect();
        let end_of = |u: EdgeUse, last: bool| -> usize {
            let (g, same) = of_use[&u];
            2 * g + usize::from(last == same)
        };
        for face in &uses_in_order {
            for lp in face {
                for k in 0..lp.len() {
                    let a = end_of(lp[k].0, true);
                    let b = end_of(lp[(k + 1) % lp.len()].0, false);
                    let (ra, rb) = (find(&mut parent, a), find(&mut parent, b));
                    parent[ra.max(rb)] = ra.min(rb);
                }
            }
        }
        let mut ends: Vec<Option<EdgeEnd>> = vec![None; 2 * edges.len()];
        let mut at_point: HashMap<Vec<u64>, usize> = HashMap::new();
        for (g, e) in edges.iter().enumerate() {
            let (u, _) = e.uses[0];
            let c = faces[u.face]
                .loops()
                .nth(u.lp)
                .map(|l| l.edges()[u.edge].curve());
            let Some(c) = c else { continue };
            let (a, b) = c.domain();
            for (end, t) in [(0, a), (1, b)] {
                let p = c.eval(t)?;
                let bits: Vec<u64> = p.iter().map(|x| x.to_bits()).collect();
                let node = 2 * g + end;
                if let Some(&other) = at_point.get(&bits) {
                    let (ra, rb) = (find(&mut parent, node), find(&mut parent, other));
                    parent[ra.max(rb)] = ra.min(rb);
                } else {
                    at_point.insert(bits, node);
                }
                let outward = outward(c, t, end == 1)?;
                ends[node] = Some(EdgeEnd { point: p, outward });
            }
        }
        // the ends of each vertex, the first edge's first
        let mut index: HashMap<usize, usize> = HashMap::new();
        let mut classes: Vec<Vec<EdgeEnd>> = Vec::new();
        for node in 0..2 * edges.len() {
            let root = find(&mut parent, node);
            let v = match index.get(&root) {
                Some(&v) => v,
                None => {
                    let v = classes.len();
                    index.insert(root, v);
                    classes.push(Vec::new());
                    v
                }
            };
            if let Some(e) = ends[node].take() {
                classes[v].push(e);
            }
            edges[node / 2].vertices[node % 2] = v;
        }
        let (vertices, meets_ends) = classes.iter().map(|c| vertex_point(c)).unzip();
        Ok(Shell {
            edges,
            vertices,
            meets_ends,
            of_use,
        })
    }

    /// The edges, in the order of their first uses (faces, then loops, then edges in a loop).
    #[must_use]
    pub fn edges(&self) -> &[SharedEdge] {
        &self.edges
    }

    /// The vertices' points.
    #[must_use]
    pub fn vertices(&self) -> &[Vec<f64>] {
        &self.vertices
    }

    /// True when every edge end joined at vertex `v` is the vertex's point or has it past the
    /// end along its curve (the curve's nearest point to it is the end): a reader that trims
    /// each edge at the nearest point of its curve to its vertices keeps every curve whole.
    /// False where no point does (two edges of one line overlapping at a crossing), and for an
    /// index past the vertices.
    #[must_use]
    pub fn vertex_meets_ends(&self, v: usize) -> bool {
        self.meets_ends.get(v).copied().unwrap_or(false)
    }

    /// The edge a use belongs to (its index in [`Shell::edges`]) and whether the use runs the way
    /// the edge's first use does.
    #[must_use]
    pub fn edge_of(&self, u: EdgeUse) -> Option<(usize, bool)> {
        self.of_use.get(&u).copied()
    }

    /// True when the faces close a volume as far as the edges tell: every edge that does not
    /// collapse to a point is used twice, once each way (ISO 10303-42 `closed_shell`, the edge
    /// condition of a 2-manifold; Mäntylä, "An Introduction to Solid Modeling", 1988, §3.3).
    #[must_use]
    pub fn is_closed(&self) -> bool {
        !self.edges.is_empty()
            && self
                .edges
                .iter()
                .all(|e| e.collapsed || (e.uses.len() == 2 && e.uses[0].1 != e.uses[1].1))
    }
}
