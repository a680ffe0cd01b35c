//! Thinning of the polynomial mesh: vertices removed where the fan of the polygon around one
//! stays within the tolerance.

use super::bounds::{triangle_bound, SecondNets};
use super::driver::MeshProgress;
use super::Leaf;
use crate::error::Result;
use crate::query::surface::QuerySurface;

impl QuerySurface {
    /// Removes vertices while the mesh stays within `tol`: for each vertex in turn whose
    /// triangles all lie in parts of one patch (`owner`: the part of each triangle) and close
    /// around it, the fan of the polygon around it from the corner whose fan has the least
    /// largest bound replaces them (two triangles fewer) if every fan triangle is
    /// counter-clockwise with positive area (the fan then covers the same polygon) and within
    /// `tol`. A new triangle lies inside the removed ones, hence inside their parts, so
    /// `M_e` over it is at most the largest of those parts' `M_e` ([`SecondNets`]); its parts
    /// are theirs (`docs/theory/queries.md#tessellation`). Returns the largest bound of a new
    /// triangle.
    // triangles, parts and vertices: each below 4·MAX_MESH_VERTICES < 2^32, and a removal
    // adds at most ten
    #[allow(clippy::cast_possible_truncation)]
    pub(super) fn decimate(
        &self,
        leaves: &[Leaf],
        at: &[(u64, u64)],
        triangles: &mut Vec<[u32; 3]>,
        owner: &[u32],
        tol: f64,
        hook: &MeshProgress,
    ) -> Result<f64> {
        use std::collections::HashMap;
        let nl = leaves.len();
        // the parts of each triangle: its owner, or a set in `unions` for new triangles
        let mut part: Vec<u32> = owner.to_vec();
        let mut unions: Vec<Vec<u32>> = Vec::new();
        let mut alive = vec![true; triangles.len()];
        let mut inc: Vec<Vec<u32>> = vec![Vec::new(); at.len()];
        for (t, tri) in triangles.iter().enumerate() {
            for &v in tri {
                inc[v as usize].push(t as u32);
            }
        }
        let mut cache: HashMap<u32, SecondNets> = HashMap::new();
        let mut worst = 0.0_f64;
        let mut parts: Vec<u32> = Vec::new();
        let mut next: HashMap<u32, u32> = HashMap::new();
        let mut memo: Vec<f64> = Vec::new();
        for h in 0..at.len() {
            hook.thinning(h as u64, at.len() as u64)?;
            let ts = &inc[h];
            if ts.len() < 3 || ts.len() > 12 {
                continue;
            }
            parts.clear();
            for &t in ts {
                let p = part[t as usize] as usize;
                if p < nl {
                    parts.push(p as u32);
                } else {
                    parts.extend_from_slice(&unions[p - nl]);
                }
            }
            parts.sort_unstable();
            parts.dedup();
            let patch = leaves[parts[0] as usize].patch;
            if parts.len() > 16 || parts.iter().any(|&p| leaves[p as usize].patch != patch) {
                continue;
            }
            // the polygon around h, counter-clockwise
            next.clear();
            let mut ok = true;
            for &t in ts {
                let [a, b, c] = triangles[t as usize];
                let h32 = h as u32;
                let (x, y) = if a == h32 {
                    (b, c)
                } else if b == h32 {
                    (c, a)
                } else {
                    (a, b)
                };
                if next.insert(x, y).is_some() {
                    ok = false;
                }
            }
            if !ok {
                continue;
            }
            let m = ts.len();
            let mut poly = Vec::with_capacity(m);
            let start = triangles[ts[0] as usize]
                .into_iter()
                .find(|&v| v as usize != h)
                .expect("a triangle has other vertices");
            let mut cur = start;
            for k in 0..m {
                poly.push(cur);
                match next.get(&cur) {
                    // one cycle through all m: back at the start only after the last
                    Some(&n) if (n == start) == (k + 1 == m) => cur = n,
                    _ => {
                        ok = false;
                        break;
                    }
                }
            }
            if !ok {
                continue;
            }
            if cache.len() > 4096 {
                cache.clear();
            }
            for &p in &parts {
                cache.entry(p).or_insert_with(|| {
                    let l = &leaves[p as usize];
                    self.second_nets(&self.sub_net(l.patch, l.u, l.v))
                });
            }
            let sns: Vec<(&SecondNets, f64, f64)> = parts
                .iter()
                .map(|p| {
                    let l = &leaves[*p as usize];
                    (&cache[p], (l.u.1 - l.u.0) as f64, (l.v.1 - l.v.0) as f64)
                })
                .collect();
            // M along each segment between two corners of the polygon, on demand
            memo.clear();
            memo.resize(m * m, f64::NAN);
            let mut edge = |i: usize, j: usize| {
                let (i, j) = (i.min(j), i.max(j));
                if memo[i * m + j].is_nan() {
                    let (a, b) = (at[poly[i] as usize], at[poly[j] as usize]);
                    let (du, dv) = (b.0 as f64 - a.0 as f64, b.1 as f64 - a.1 as f64);
                    memo[i * m + j] = sns
                        .iter()
                        .map(|(sn, wu, wv)| sn.along(du / wu, dv / wv))
                        .fold(0.0, f64::max);
                }
                memo[i * m + j]
            };
            let area = |i: u32, j: u32, k: u32| {
                let (a, b, c) = (at[i as usize], at[j as usize], at[k as usize]);
                let d = |x: u64, y: u64| i128::from(x) - i128::from(y);
                d(b.0, a.0) * d(c.1, a.1) - d(c.0, a.0) * d(b.1, a.1)
            };
            let mut best: Option<(usize, f64)> = None;
            'apex: for i in 0..m {
                let mut worst_here = 0.0_f64;
                for j in 1..m - 1 {
                    let (x, y, z) = (poly[i], poly[(i + j) % m], poly[(i + j + 1) % m]);
                    if area(x, y, z) <= 0 {
                        continue 'apex;
                    }
                }
                for j in 1..m - 1 {
                    let (y, z) = ((i + j) % m, (i + j + 1) % m);
                    let b = triangle_bound([edge(i, y), edge(i, z), edge(y, z)]);
                    worst_here = worst_here.max(b);
                    if worst_here > tol || best.is_some_and(|(_, w)| worst_here >= w) {
                        continue 'apex;
                    }
                }
                best = Some((i, worst_here));
            }
            let Some((i, b)) = best else { continue };
            worst = worst.max(b);
            let old: Vec<u32> = inc[h].drain(..).collect();
            for &t in &old {
                alive[t as usize] = false;
                for v in triangles[t as usize] {
                    inc[v as usize].retain(|&x| x != t);
                }
            }
            unions.push(parts.clone());
            let id = (nl + unions.len() - 1) as u32;
            for j in 1..m - 1 {
                let tri = [poly[i], poly[(i + j) % m], poly[(i + j + 1) % m]];
                let t = triangles.len() as u32;
                triangles.push(tri);
                alive.push(true);
                part.push(id);
                for v in tri {
                    inc[v as usize].push(t);
                }
            }
        }
        let mut k = 0;
        triangles.retain(|_| {
            k += 1;
            alive[k - 1]
        });
        Ok(worst)
    }
}
