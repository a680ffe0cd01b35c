//! Tangent contacts (`docs/theory/queries.md#tangent-contacts-and-overlaps`): the starting
//! points where the normals are parallel and the ends of branches that stopped at a tangency,
//! thinned, grouped into single contacts and lines of contact, and a line's points put in
//! order along it.
//!
//! A surface touched along a curve (a plane on a torus's top circle) gives tens of thousands of
//! candidates, one or more for every leaf of the subdivision along the curve; every step here
//! finds neighbours through a hash grid of cubes, so the work grows with their number, not its
//! square.

use super::super::super::pieces::dist;
use super::system::K;
use std::collections::HashMap;

/// A tangent candidate: the system's unknowns, the point in space, and the sine of the angle
/// between the normals there.
pub(super) type Touch = ([f64; K], [f64; 3], f64);

/// One tangent answer: its points (one for a single contact; in order along the line for a
/// line of contact) and whether the line closes.
pub(super) struct ContactGroup {
    pub(super) members: Vec<Touch>,
    pub(super) closed: bool,
}

/// Points hashed by the cube of side `cell` that holds them.
struct Grid {
    cell: f64,
    cells: HashMap<[i64; 3], Vec<usize>>,
}

impl Grid {
    fn new(cell: f64) -> Self {
        Grid {
            cell,
            cells: HashMap::new(),
        }
    }

    // `as` saturates: a coordinate beyond 2^63 cells (not met: coordinates are finite and the
    // cell a fraction of the scale) shares the last cell, which only costs comparisons
    #[allow(clippy::cast_possible_truncation)]
    fn key(&self, p: &[f64; 3]) -> [i64; 3] {
        std::array::from_fn(|c| (p[c] / self.cell).floor() as i64)
    }

    fn insert(&mut self, i: usize, p: &[f64; 3]) {
        let k = self.key(p);
        self.cells.entry(k).or_default().push(i);
    }

    /// The points in the 27 cubes around `p`: every point within `cell` of it, and others.
    fn near(&self, p: &[f64; 3]) -> impl Iterator<Item = usize> + '_ {
        let k = self.key(p);
        (0..27).flat_map(move |n: i64| {
            let key = [k[0] + n % 3 - 1, k[1] + (n / 3) % 3 - 1, k[2] + n / 9 - 1];
            self.cells.get(&key).into_iter().flatten().copied()
        })
    }
}

/// The root of `i` in a union-find forest, with path halving.
fn root(parent: &mut [usize], mut i: usize) -> usize {
    while parent[i] != i {
        parent[i] = parent[parent[i]];
        i = parent[i];
    }
    i
}

/// Groups the candidates: first thinned so that no two kept points are within `spacing` (the
/// most tangent kept first, so a single contact keeps its best point), then single-linkage
/// groups of points within `merge` of each other. A group whose two farthest members (found by
/// two sweeps: the member farthest from the first, then the one farthest from that) are within
/// `merge` is one contact, its most tangent point; a wider group is a line of contact, its
/// points chained from that far member to the nearest one not yet taken, and closed when the
/// chain returns to within `4 spacing` of its start.
pub(super) fn group(mut touch: Vec<Touch>, merge: f64, spacing: f64) -> Vec<ContactGroup> {
    touch.sort_by(|a, b| a.2.total_cmp(&b.2));
    let mut kept: Vec<Touch> = Vec::new();
    let mut fine = Grid::new(spacing);
    for t in touch {
        if fine.near(&t.1).any(|i| dist(&kept[i].1, &t.1) <= spacing) {
            continue;
        }
        fine.insert(kept.len(), &t.1);
        kept.push(t);
    }
    let mut coarse = Grid::new(merge);
    for (i, t) in kept.iter().enumerate() {
        coarse.insert(i, &t.1);
    }
    let mut parent: Vec<usize> = (0..kept.len()).collect();
    for (i, t) in kept.iter().enumerate() {
        for j in coarse.near(&t.1) {
            if j < i && dist(&kept[j].1, &t.1) <= merge {
                let (a, b) = (root(&mut parent, i), root(&mut parent, j));
                if a != b {
                    parent[a.max(b)] = a.min(b);
                }
            }
        }
    }
    // members of each group in the order kept (most tangent first), groups by their first
    let mut groups: Vec<Vec<usize>> = Vec::new();
    let mut slot: HashMap<usize, usize> = HashMap::new();
    for i in 0..kept.len() {
        let r = root(&mut parent, i);
        let s = *slot.entry(r).or_insert_with(|| {
            groups.push(Vec::new());
            groups.len() - 1
        });
        groups[s].push(i);
    }
    groups
        .into_iter()
        .map(|m| {
            let farthest = |from: usize| {
                m.iter()
                    .copied()
                    .max_by(|&a, &b| {
                        dist(&kept[a].1, &kept[from].1).total_cmp(&dist(&kept[b].1, &kept[from].1))
                    })
                    .unwrap_or(from)
            };
            let a = farthest(m[0]);
            let b = farthest(a);
            if dist(&kept[a].1, &kept[b].1) <= merge {
                return ContactGroup {
                    members: vec![kept[m[0]]],
                    closed: false,
                };
            }
            let order = chain(&kept, &m, a, spacing);
            let closed = order.len() > 2
                && dist(&kept[order[0]].1, &kept[order[order.len() - 1]].1) <= 4.0 * spacing;
            ContactGroup {
                members: order.into_iter().map(|i| kept[i]).collect(),
                closed,
            }
        })
        .collect()
}

/// The members `m` in the order of a nearest-neighbour walk from `start`: the nearest untaken
/// member among the grid's neighbours (cubes of `4 spacing`), else the nearest of all.
fn chain(kept: &[Touch], m: &[usize], start: usize, spacing: f64) -> Vec<usize> {
    let mut grid = Grid::new(4.0 * spacing);
    for &i in m {
        grid.insert(i, &kept[i].1);
    }
    let mut taken: HashMap<usize, bool> = m.iter().map(|&i| (i, false)).collect();
    let mut order = Vec::with_capacity(m.len());
    let mut at = start;
    loop {
        taken.insert(at, true);
        order.push(at);
        let p = kept[at].1;
        let free = |i: &usize| taken.get(i) == Some(&false);
        let nearest = |it: &mut dyn Iterator<Item = usize>| {
            it.min_by(|&a, &b| dist(&kept[a].1, &p).total_cmp(&dist(&kept[b].1, &p)))
        };
        let next = nearest(&mut grid.near(&p).filter(free))
            .or_else(|| nearest(&mut m.iter().copied().filter(free)));
        match next {
            Some(n) => at = n,
            None => return order,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn touch(p: [f64; 3], sine: f64) -> Touch {
        ([p[0], p[1], p[2], 0.0], p, sine)
    }

    #[test]
    fn a_cluster_is_one_contact_at_its_most_tangent_point() {
        let t = vec![
            touch([0.0, 0.0, 0.0], 3e-5),
            touch([0.001, 0.0, 0.0], 1e-7),
            touch([0.0, 0.002, 0.0], 2e-6),
            touch([5.0, 0.0, 0.0], 1e-6),
        ];
        let g = group(t, 0.1, 1e-4);
        assert_eq!(g.len(), 2);
        let near = g.iter().find(|x| x.members[0].1[0] < 1.0).unwrap();
        assert_eq!(near.members.len(), 1);
        assert_eq!(near.members[0].2, 1e-7, "the most tangent point is kept");
    }

    #[test]
    fn a_circle_of_candidates_is_one_closed_line_in_order() {
        // 20,000 candidates on a circle of radius 3 (several at every place): thinned to the
        // spacing, chained in order around the circle and closed
        let n = 20_000;
        let t: Vec<Touch> = (0..n)
            .map(|i| {
                let a = std::f64::consts::TAU * f64::from((i * 7919) % n) / f64::from(n);
                touch([3.0 * a.cos(), 3.0 * a.sin(), 1.0], 1e-6)
            })
            .collect();
        let spacing = 0.01;
        let g = group(t, 0.1, spacing);
        assert_eq!(g.len(), 1);
        assert!(g[0].closed);
        let m = &g[0].members;
        // kept points are more than `spacing` apart, and every candidate is within `spacing`
        // of one: between L / (2 spacing) and L / spacing of them on the circle's length L
        let l = std::f64::consts::TAU * 3.0;
        assert!(
            m.len() as f64 >= l / (2.0 * spacing) && m.len() as f64 <= l / spacing,
            "{}",
            m.len()
        );
        // neighbours on the circle are at most 2 spacing apart, and the candidates' own gap
        let gap = 2.0 * spacing + l / f64::from(n);
        let jumps = m
            .windows(2)
            .filter(|w| dist(&w[0].1, &w[1].1) > gap)
            .count();
        assert_eq!(jumps, 0, "the walk follows the circle");
    }

    #[test]
    fn an_open_line_starts_at_an_end() {
        let t: Vec<Touch> = (0..500)
            .map(|i| touch([f64::from((i * 37) % 500) * 0.004, 0.0, 0.0], 1e-6))
            .collect();
        let g = group(t, 0.1, 0.001);
        assert_eq!(g.len(), 1);
        assert!(!g[0].closed);
        let xs: Vec<f64> = g[0].members.iter().map(|m| m.1[0]).collect();
        assert!(
            xs.windows(2).all(|w| w[0] < w[1]) || xs.windows(2).all(|w| w[0] > w[1]),
            "{xs:?}"
        );
    }
}
