//! The parts of a rational patch: halved in the direction whose terms dominate its bound until
//! within the tolerance.

use std::sync::atomic::{AtomicUsize, Ordering};

#[cfg(doc)]
use super::MAX_LEVELS;
use super::{Leaf, PATCH_WIDTH};
use crate::error::{Error, Result};
use crate::query::surface::QuerySurface;
use crate::query::tessellate::{MAX_MESH_VERTICES, MESH_VERTICES};

impl QuerySurface {
    /// The parts of patch `k` of a rational surface within the normalised tolerance `tol`:
    /// halved (de Casteljau at the middle) in the direction whose terms dominate the bound
    /// `(A + 2B + C)/8` ([`QuerySurface::net_bounds`]), at most [`MAX_LEVELS`] times in each
    /// direction. `count` is the number of parts of every patch so far: past
    /// [`MAX_MESH_VERTICES`] this stops with [`Error::TooLarge`].
    pub(super) fn rational_leaves(
        &self,
        k: usize,
        tol: f64,
        count: &AtomicUsize,
    ) -> Result<Vec<Leaf>> {
        let (p, q, hd, dim) = (self.p, self.q, self.hd, self.dim);
        let mut out = Vec::new();
        let mut stack = vec![(self.patch(k).to_vec(), (0, PATCH_WIDTH), (0, PATCH_WIDTH))];
        while let Some((net, u, v)) = stack.pop() {
            let (a, b, c) = self
                .net_bounds(&net)
                .ok_or_else(|| Error::InvalidArgument {
                    what: "surface to mesh".into(),
                    reason: format!(
                        "patch {k} has a weight that is not positive; the deviation bound needs \
                     positive weights"
                    ),
                })?;
            let bound = (a + 2.0 * b + c) / 8.0;
            let (eu, ev) = (a + b, c + b);
            let (can_u, can_v) = (u.1 - u.0 > 2, v.1 - v.0 > 2);
            // one direction at a time: each halving then cuts the bound by less than a
            // quartering would, so the parts end closer to the tolerance (fewer triangles)
            let split_u = can_u && eu > 0.0 && (eu >= ev || !can_v);
            let split_v = can_v && ev > 0.0 && !split_u;
            if bound <= tol || !(split_u || split_v) {
                let n = count.fetch_add(1, Ordering::Relaxed) + 1;
                if n > MAX_MESH_VERTICES {
                    return Err(Error::TooLarge {
                        what: MESH_VERTICES,
                        size: n,
                        max: MAX_MESH_VERTICES,
                    });
                }
                let mut corners = Vec::with_capacity(4 * dim);
                for (i, j) in [(0, 0), (p, 0), (p, q), (0, q)] {
                    let x = &net[(i * (q + 1) + j) * hd..][..hd];
                    corners.extend(x[..dim].iter().map(|c| c / x[dim]));
                }
                out.push(Leaf {
                    patch: k,
                    u,
                    v,
                    bound,
                    anti: false,
                    corners,
                });
                continue;
            }
            let (l, h, u_parts, v_parts) = if split_u {
                let m = (u.0 + u.1) / 2;
                let (l, h) = self.halve_u(&net);
                (l, h, [(u.0, m), (m, u.1)], [v, v])
            } else {
                let m = (v.0 + v.1) / 2;
                let (l, h) = self.halve_v(&net);
                (l, h, [u, u], [(v.0, m), (m, v.1)])
            };
            stack.push((l, u_parts[0], v_parts[0]));
            stack.push((h, u_parts[1], v_parts[1]));
        }
        Ok(out)
    }
}
