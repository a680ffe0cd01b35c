//! [`QuerySurface::mesh`]: the size check before meshing, the rounds of matching the parts'
//! sides and splitting them, and the mesh's vertices and triangles.

use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;

use rayon::prelude::*;

#[cfg(doc)]
use super::bounds::{triangle_bound, SecondNets};
use super::plan::{PatchGrid, Plan};
use super::strips::Lattice;
use super::{Leaf, Rule, MAX_ROUNDS, PATCH_WIDTH};
use crate::error::{Error, Result};
use crate::query::surface::QuerySurface;
use crate::query::tessellate::{
    check_deviation, check_tol, Mesh, MAX_MESH_TRIANGLES, MAX_MESH_VERTICES, MESH_VERTICES,
    TESSELLATION_TOLERANCE,
};
use crate::{Points, Progress};

/// What a mesh reports to its [`Progress`] hook: the work in thousandths, the first split of
/// the patches taking `[0, 400)`, the rounds of matching `[400, 600)` and the mesh with its
/// thinning `[600, 1000]`. The shares are those of the benchmark surface of
/// `docs/performance.md` (geometric queries), where the first split, the rounds and the
/// thinning take about 2 : 1 : 2 of the time.
pub(super) struct MeshProgress<'a, 'p> {
    progress: &'a Progress<'p>,
    last: Mutex<u64>,
}

impl<'a, 'p> MeshProgress<'a, 'p> {
    const TOTAL: u64 = 1000;
    const ROUNDS: u64 = 400;
    const EMIT: u64 = 600;

    pub(super) fn new(progress: &'a Progress<'p>) -> Self {
        MeshProgress {
            progress,
            last: Mutex::new(0),
        }
    }

    /// Reports `done` of `total` of the stage `[from, to)`, never going back (the patches
    /// finish in any order on the pool's threads), and checks the cancel flag.
    pub(super) fn stage(&self, from: u64, to: u64, done: u64, total: u64) -> Result<()> {
        let at = from + (to - from) * done / total.max(1);
        let at = {
            let mut last = self
                .last
                .lock()
                .unwrap_or_else(std::sync::PoisonError::into_inner);
            *last = (*last).max(at);
            *last
        };
        self.progress.step("meshing", at, Self::TOTAL)
    }

    /// Reports `done` of `total` vertices of the thinning, every [`Progress::STRIDE`].
    pub(super) fn thinning(&self, done: u64, total: u64) -> Result<()> {
        if done % Progress::STRIDE == 0 {
            self.stage(Self::EMIT, Self::TOTAL, done, total)
        } else {
            Ok(())
        }
    }
}

impl QuerySurface {
    /// A triangle mesh within `tolerance` of a surface, polynomial or rational, adaptive
    /// (`docs/theory/queries.md#tessellation`), so flat regions get large triangles and curved
    /// ones small. Each patch is cut into parts until every part is within `tolerance` as two
    /// triangles:
    ///
    /// * polynomial: a triangle whose edge vectors `e` have `M_e ≥ max |D²S[e, e]|` over it
    ///   deviates by at most `½ max (λ0 λ1 M01 + λ0 λ2 M02 + λ1 λ2 M12)` over its barycentric
    ///   coordinates ([`triangle_bound`]), and `M_e` comes for any `e` from the part's nets of
    ///   `S_uu`, `S_uv`, `S_vv` elevated to one degree ([`SecondNets`]), so the cross term
    ///   cancels where it can: each part takes the diagonal, `(1, 1)` or `(1, −1)`, with the
    ///   smaller bound; it is halved in the direction whose halves' bound is the smaller, or
    ///   cut into the fewest equal parts (at most nine) once that reaches the tolerance and
    ///   halving would not;
    /// * rational: `(A + 2B + C)/8` from its own net's differences (Leibniz for the weight,
    ///   [`QuerySurface::net_bounds`]), halved in `u` where the `u` terms dominate, in `v`
    ///   otherwise.
    ///
    /// Parts are matched along their sides, across patches too: a part whose sides carry
    /// corners of smaller neighbours is meshed through all of them, any other as two
    /// triangles, so the mesh has no cracks and no T-junctions. On a polynomial surface such a
    /// part is a strip of triangles between its sides with no interior point, its rungs along
    /// its diagonal, each triangle's bound computed from its own edge vectors; where one is
    /// above the tolerance the strip whose largest bound is least is taken (of either
    /// diagonal), else a fan about the part's centre, else the part is split and the sides
    /// matched again (at most [`MAX_ROUNDS`] rounds, then every part is cut until
    /// `(A + 2B + C)/8`, which holds for any triangle inside it, is within the tolerance). The
    /// polynomial mesh is then thinned: a vertex is removed, its polygon fanned from one corner,
    /// where every new triangle is within the tolerance with `M_e` the largest of the parts it
    /// covers ([`QuerySurface::decimate`]). On a rational surface, whose parts are accepted by
    /// `(A + 2B + C)/8` (bounds on the surface's own second derivatives, which hold for any
    /// triangle inside the part), such a part is a fan about its centre. Vertices are
    /// the parts' corner control points (points of the surface) and the fans' centres. The
    /// reported deviation is the largest triangle bound. Patches are split in parallel; the
    /// mesh does not depend on the thread count.
    ///
    /// ```
    /// use lekalo::{BSplineSurface, Points, QuerySurface};
    /// // z = x² on [0, 1]²: M along (1, 0) and the diagonals 2, along (0, 1) 0: two triangles
    /// // deviate by 2/8, so 2/(8·4^k) ≤ 1e-3 after k = 4 halvings in u, none in v
    /// let net = Points::from_3d(&[[0., 0., 0.], [0., 1., 0.], [0.5, 0., 0.], [0.5, 1., 0.], [1., 0., 1.], [1., 1., 1.]])?;
    /// let s = BSplineSurface::new(2, 1, vec![0., 0., 0., 1., 1., 1.], vec![0., 0., 1., 1.], net, (3, 2))?;
    /// let mesh = QuerySurface::from_bspline(&s)?.mesh(1e-3)?;
    /// assert!(mesh.deviation <= 1e-3);
    /// assert_eq!(mesh.triangles.len(), 2 * 16);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for a rational surface with a weight that is not positive, or
    /// a tolerance below [`MIN_RELATIVE_TOLERANCE`](crate::query::MIN_RELATIVE_TOLERANCE) times
    /// the size, or a tolerance whose mesh is estimated (before meshing) at more than
    /// [`MAX_MESH_TRIANGLES`] triangles;
    /// [`Error::TooLarge`] beyond [`MAX_MESH_VERTICES`]; [`Error::ToleranceNotMet`] when a
    /// part reached the most halvings ([`MAX_LEVELS`](super::MAX_LEVELS) in each direction)
    /// with its bound still above the tolerance.
    pub fn mesh(&self, tolerance: f64) -> Result<Mesh> {
        self.mesh_with_progress(tolerance, &Progress::new())
    }

    /// [`QuerySurface::mesh`] reporting to `progress` (thousandths of the work: the patches'
    /// first split, the rounds, the mesh and its thinning) and stopping when its cancel flag
    /// is set. The mesh is the same.
    ///
    /// # Errors
    /// As [`QuerySurface::mesh`]; [`Error::Cancelled`] when cancelled.
    pub fn mesh_with_progress(&self, tolerance: f64, progress: &Progress<'_>) -> Result<Mesh> {
        check_tol(tolerance, self.scale)?;
        let tol = tolerance / self.scale;
        self.check_mesh_size(tolerance, tol)?;
        let grid = PatchGrid::new(self);
        let hook = MeshProgress::new(progress);
        hook.stage(0, MeshProgress::ROUNDS, 0, 1)?;
        let mesh = if self.rational {
            self.mesh_rational(tol, &grid, &hook)
        } else {
            self.mesh_polynomial(tol, &grid, 0, &hook)
        }?;
        hook.stage(MeshProgress::EMIT, MeshProgress::TOTAL, 1, 1)?;
        check_deviation("surface mesh", mesh.deviation, tolerance)?;
        Ok(mesh)
    }

    /// Refuses a tolerance whose mesh would be too large to make, before any part is made:
    /// each patch is estimated at the `(A + 2B + C) / (8·tol)` parts (two triangles each) of
    /// its uniform split within the normalised tolerance `tol`, the bounds of
    /// [`Self::net_bounds`] shrinking with the square of a part's size. The adaptive split
    /// needs no more than a few times fewer where the curvature is concentrated.
    fn check_mesh_size(&self, tolerance: f64, tol: f64) -> Result<()> {
        let parts: f64 = (0..self.patch_count())
            .map(|k| {
                self.net_bounds(self.patch(k))
                    .map_or(1.0, |(a, b, c)| ((a + 2.0 * b + c) / (8.0 * tol)).max(1.0))
            })
            .sum();
        let triangles = 2.0 * parts;
        #[allow(clippy::cast_precision_loss)] // 2^25 is exact
        let max = MAX_MESH_TRIANGLES as f64;
        if triangles > max {
            return Err(Error::InvalidArgument {
                what: TESSELLATION_TOLERANCE,
                reason: format!(
                    "{tolerance:e} needs about {triangles:.1e} triangles, more than the \
                     {MAX_MESH_TRIANGLES} a mesh may have; use a tolerance of at least {:.1e}",
                    tolerance * triangles / max
                ),
            });
        }
        Ok(())
    }

    /// The vertices of the lattice (the corners of the parts they come from) and their
    /// parameters.
    fn lattice_vertices(
        &self,
        grid: &PatchGrid,
        lat: &Lattice,
        leaves: &[Leaf],
    ) -> (Vec<f64>, Vec<[f64; 2]>) {
        let dim = self.dim;
        let mut verts = Vec::with_capacity(dim * (lat.keys.len() + leaves.len() / 4));
        let mut uv = Vec::with_capacity(lat.keys.len() + leaves.len() / 4);
        let mut buf = vec![0.0; dim];
        for &(u, v, n, c) in &lat.keys {
            let l = &leaves[n as usize];
            self.denormalise(&l.corners[c as usize * dim..][..dim], &mut buf);
            verts.extend_from_slice(&buf);
            uv.push(grid.param(u, v));
        }
        (verts, uv)
    }

    /// A new vertex at the centre of part `l` (integer, so on the lattice): its index.
    fn centre_vertex(
        &self,
        grid: &PatchGrid,
        l: &Leaf,
        verts: &mut Vec<f64>,
        uv: &mut Vec<[f64; 2]>,
    ) -> Result<u32> {
        let centre = u32::try_from(uv.len()).map_err(|_| Error::TooLarge {
            what: MESH_VERTICES,
            size: uv.len(),
            max: MAX_MESH_VERTICES,
        })?;
        let ((u0, u1), (v0, v1)) = grid.rect(l);
        let (cu, cv) = ((u0 + u1) / 2, (v0 + v1) / 2);
        let local = |g: u64| (g % PATCH_WIDTH) as f64 / PATCH_WIDTH as f64;
        let mut scratch = Vec::new();
        let pt = self.point_on(l.patch, local(cu), local(cv), &mut scratch);
        let mut buf = vec![0.0; self.dim];
        self.denormalise(&pt, &mut buf);
        verts.extend_from_slice(&buf);
        uv.push(grid.param(cu, cv));
        Ok(centre)
    }

    fn finish(
        &self,
        verts: Vec<f64>,
        uv: Vec<[f64; 2]>,
        triangles: Vec<[u32; 3]>,
        deviation: f64,
    ) -> Result<Mesh> {
        if uv.len() > MAX_MESH_VERTICES {
            return Err(Error::TooLarge {
                what: MESH_VERTICES,
                size: uv.len(),
                max: MAX_MESH_VERTICES,
            });
        }
        Ok(Mesh {
            vertices: Points::from_flat(self.dim, verts)?,
            uv,
            triangles,
            deviation: deviation * self.scale,
        })
    }

    fn mesh_rational(&self, tol: f64, grid: &PatchGrid, hook: &MeshProgress) -> Result<Mesh> {
        let count = AtomicUsize::new(0);
        let patches = self.patch_count() as u64;
        let finished = AtomicUsize::new(0);
        let leaves: Vec<Leaf> = (0..self.patch_count())
            .into_par_iter()
            .map(|k| {
                let leaves = self.rational_leaves(k, tol, &count)?;
                let done = finished.fetch_add(1, Ordering::Relaxed) as u64 + 1;
                hook.stage(0, MeshProgress::EMIT, done, patches)?;
                Ok(leaves)
            })
            .collect::<Result<Vec<_>>>()?
            .into_iter()
            .flatten()
            .collect();
        let lat = Lattice::new(leaves.iter().map(|l| grid.rect(l)))?;
        let (mut verts, mut uv) = self.lattice_vertices(grid, &lat, &leaves);
        let mut triangles = Vec::with_capacity(2 * leaves.len());
        let mut ring: Vec<u32> = Vec::new();
        let mut deviation = 0.0_f64;
        for l in &leaves {
            deviation = deviation.max(l.bound);
            lat.ring(grid.rect(l), &mut ring);
            if ring.len() == 4 {
                triangles.push([ring[0], ring[1], ring[2]]);
                triangles.push([ring[0], ring[2], ring[3]]);
                continue;
            }
            // (A + 2B + C)/8 holds for any triangle inside the part: a fan about the centre
            let centre = self.centre_vertex(grid, l, &mut verts, &mut uv)?;
            for i in 0..ring.len() {
                triangles.push([centre, ring[i], ring[(i + 1) % ring.len()]]);
            }
        }
        self.finish(verts, uv, triangles, deviation)
    }

    /// The polynomial mesh: parts under [`Rule::Edges`], their sides matched, each part planned
    /// ([`QuerySurface::plan_part`]); the parts to split are split (at least once each) and
    /// the round repeated, at most [`MAX_ROUNDS`] times, then every part is refined under
    /// [`Rule::Any`], whose strips are all within the tolerance, for a last round. In the first
    /// `forced` rounds every part with points on its sides is split (tests of the rounds).
    pub(super) fn mesh_polynomial(
        &self,
        tol: f64,
        grid: &PatchGrid,
        forced: usize,
        hook: &MeshProgress,
    ) -> Result<Mesh> {
        let count = AtomicUsize::new(0);
        let whole = ((0, PATCH_WIDTH), (0, PATCH_WIDTH));
        let patches = self.patch_count() as u64;
        let finished = AtomicUsize::new(0);
        let mut leaves: Vec<Leaf> = (0..self.patch_count())
            .into_par_iter()
            .map(|k| {
                let net = self.patch(k).to_vec();
                let leaves = self.poly_leaves(k, net, whole, tol, Rule::Edges, false, &count)?;
                let done = finished.fetch_add(1, Ordering::Relaxed) as u64 + 1;
                hook.stage(0, MeshProgress::ROUNDS, done, patches)?;
                Ok(leaves)
            })
            .collect::<Result<Vec<_>>>()?
            .into_iter()
            .flatten()
            .collect();
        let mut rule = Rule::Edges;
        for round in 0..=MAX_ROUNDS {
            hook.stage(
                MeshProgress::ROUNDS,
                MeshProgress::EMIT,
                round as u64,
                MAX_ROUNDS as u64 + 1,
            )?;
            let lat = Lattice::new(leaves.iter().map(|l| grid.rect(l)))?;
            let may_split = rule == Rule::Edges;
            let force = may_split && round < forced;
            let plans: Vec<(Plan, f64)> = leaves
                .par_iter()
                .map(|l| self.plan_part(l, grid.rect(l), &lat, tol, may_split, force))
                .collect();
            let split: Vec<bool> = plans.iter().map(|p| matches!(p.0, Plan::Split)).collect();
            if !split.contains(&true) {
                return self.emit(grid, &lat, &leaves, plans, tol, hook);
            }
            let refine_all = round + 1 >= MAX_ROUNDS;
            if refine_all {
                rule = Rule::Any;
            }
            let old = std::mem::take(&mut leaves);
            let refined: Vec<Vec<Leaf>> = old
                .into_par_iter()
                .zip(split.into_par_iter())
                .map(|(l, s)| {
                    if !(s || refine_all) {
                        return Ok(vec![l]);
                    }
                    count.fetch_sub(1, Ordering::Relaxed);
                    let net = self.sub_net(l.patch, l.u, l.v);
                    self.poly_leaves(l.patch, net, (l.u, l.v), tol, rule, s, &count)
                })
                .collect::<Result<_>>()?;
            leaves = refined.into_iter().flatten().collect();
        }
        unreachable!("the last round (Rule::Any) splits no part")
    }

    /// The mesh of the planned parts, then [`QuerySurface::decimate`]d.
    fn emit(
        &self,
        grid: &PatchGrid,
        lat: &Lattice,
        leaves: &[Leaf],
        plans: Vec<(Plan, f64)>,
        tol: f64,
        hook: &MeshProgress,
    ) -> Result<Mesh> {
        let (mut verts, mut uv) = self.lattice_vertices(grid, lat, leaves);
        let mut at: Vec<(u64, u64)> = lat.keys.iter().map(|k| (k.0, k.1)).collect();
        let mut triangles = Vec::with_capacity(2 * leaves.len());
        let mut owner: Vec<u32> = Vec::with_capacity(2 * leaves.len());
        let mut ring: Vec<u32> = Vec::new();
        let mut deviation = 0.0_f64;
        for (n, (l, (plan, bound))) in leaves.iter().zip(plans).enumerate() {
            deviation = deviation.max(bound);
            match plan {
                Plan::Two => {
                    lat.ring(grid.rect(l), &mut ring);
                    let [a, b, c, d] = [ring[0], ring[1], ring[2], ring[3]];
                    if l.anti {
                        triangles.extend([[a, b, d], [b, c, d]]);
                    } else {
                        triangles.extend([[a, b, c], [a, c, d]]);
                    }
                }
                Plan::Strip(t) => triangles.extend(t),
                Plan::Fan => {
                    let r = grid.rect(l);
                    lat.ring(r, &mut ring);
                    let centre = self.centre_vertex(grid, l, &mut verts, &mut uv)?;
                    at.push(((r.0 .0 + r.0 .1) / 2, (r.1 .0 + r.1 .1) / 2));
                    for i in 0..ring.len() {
                        triangles.push([centre, ring[i], ring[(i + 1) % ring.len()]]);
                    }
                }
                Plan::Split => unreachable!("emitted only when no part is to be split"),
            }
            #[allow(clippy::cast_possible_truncation)] // parts: below MAX_MESH_VERTICES < 2^32
            owner.resize(triangles.len(), n as u32);
        }
        {
            let worst = self.decimate(leaves, &at, &mut triangles, &owner, tol, hook)?;
            deviation = deviation.max(worst);
            // drop the vertices no triangle uses any more
            let mut map = vec![u32::MAX; uv.len()];
            for t in &triangles {
                for &i in t {
                    map[i as usize] = 0;
                }
            }
            let mut next = 0_u32;
            let dim = self.dim;
            let mut kept_v = Vec::with_capacity(verts.len());
            let mut kept_uv = Vec::with_capacity(uv.len());
            for i in 0..uv.len() {
                if map[i] == 0 {
                    map[i] = next;
                    next += 1;
                    kept_v.extend_from_slice(&verts[i * dim..(i + 1) * dim]);
                    kept_uv.push(uv[i]);
                }
            }
            for t in &mut triangles {
                for i in t.iter_mut() {
                    *i = map[*i as usize];
                }
            }
            verts = kept_v;
            uv = kept_uv;
        }
        self.finish(verts, uv, triangles, deviation)
    }
}
