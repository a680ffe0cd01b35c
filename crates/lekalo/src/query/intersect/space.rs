//! The search behind curve–curve intersection outside the plane (`docs/theory/queries.md#intersections`):
//! pairs of sub-curves halved while their boxes overlap, then Levenberg–Marquardt on
//! `A(s) = B(u)`; the solutions are grouped into crossings, contacts and overlaps by
//! [`QueryCurve::assemble`] as in the plane.

use super::super::pieces::{dist, dot, QueryCurve};
use super::super::surface::split_curve;
use super::curves::Solution;
use super::{boxes_overlap, MAX_DEPTH, MAX_PAIRS};
use crate::error::{Error, Result};
use crate::numeric::damped::{levenberg_marquardt, Residual};

/// A sub-curve is small enough to solve from once its box is this fraction of the larger
/// curve's scale (or at [`MAX_DEPTH`]).
const SMALL: f64 = 1e-2;
/// The probe step (fraction of the first curve's domain) of the transversality test, as in the
/// plane.
const PROBE: f64 = 1e-6;

/// A sub-curve in original coordinates: its piece, its local interval and its net.
type SubNet = (usize, (f64, f64), Vec<f64>);

impl QueryCurve {
    /// The solutions of `A(s) = B(u)` within `tolerance` for curves of equal dimension other
    /// than 2: the pairs of pieces, halved (the larger sub-curve, de Casteljau) while their
    /// boxes overlap within the tolerance until both are within 1% of the larger scale (or at
    /// depth 48), then Levenberg–Marquardt from the middles. A solution is transversal when the
    /// first-order gap `|A'|·h·sin θ` at the probe step `h = 10⁻⁶` of the first curve's domain
    /// is at least ten times the tolerance.
    ///
    /// # Errors
    /// [`Error::TooLarge`] beyond 2^20 examined pairs.
    pub(super) fn space_solutions(
        &self,
        other: &QueryCurve,
        tolerance: f64,
    ) -> Result<Vec<Solution>> {
        let scale = self.scale.max(other.scale);
        let nets = |c: &QueryCurve, k: usize| -> Vec<f64> {
            let mut out = c.piece(k).to_vec();
            for p in out.chunks_exact_mut(c.hd) {
                let w = if c.rational { p[c.dim] } else { 1.0 };
                for d in 0..c.dim {
                    p[d] = w * c.centre[d] + c.scale * p[d];
                }
            }
            out
        };
        let mut stack: Vec<(SubNet, SubNet, u32)> = Vec::new();
        for i in 0..self.piece_count() {
            for j in 0..other.piece_count() {
                stack.push((
                    (i, (0.0, 1.0), nets(self, i)),
                    (j, (0.0, 1.0), nets(other, j)),
                    0,
                ));
            }
        }
        let mut found = Vec::new();
        let mut visited = 0_usize;
        let h = PROBE * (self.domain().1 - self.domain().0);
        while let Some((x, y, depth)) = stack.pop() {
            visited += 1;
            if visited > MAX_PAIRS {
                return Err(Error::TooLarge {
                    what: "sub-curve pairs examined by the intersection".into(),
                    size: visited,
                    max: MAX_PAIRS,
                });
            }
            let xb = net_box(&x.2, self.hd, self.dim, self.rational);
            let yb = net_box(&y.2, other.hd, other.dim, other.rational);
            if !boxes_overlap(&xb, &yb, self.dim, tolerance) {
                continue;
            }
            let xd = dist(&xb[..self.dim], &xb[self.dim..]);
            let yd = dist(&yb[..self.dim], &yb[self.dim..]);
            if xd.max(yd) <= SMALL * scale || depth >= MAX_DEPTH {
                let s0 = 0.5 * (x.1 .0 + x.1 .1);
                let u0 = 0.5 * (y.1 .0 + y.1 .1);
                if let Some((ta, tb, gap, sin, speed)) = self.solve_space(other, x.0, y.0, s0, u0) {
                    if gap <= tolerance {
                        found.push((ta, tb, gap, speed * h * sin >= 10.0 * tolerance));
                    }
                }
                continue;
            }
            let halve = |s: SubNet, c: &QueryCurve| -> [SubNet; 2] {
                let n = s.2.len() / c.hd - 1;
                let (l, r) = split_curve(&s.2, c.hd, n);
                let m = 0.5 * (s.1 .0 + s.1 .1);
                [(s.0, (s.1 .0, m), l), (s.0, (m, s.1 .1), r)]
            };
            if xd >= yd {
                for half in halve(x, self) {
                    stack.push((half, (y.0, y.1, y.2.clone()), depth + 1));
                }
            } else {
                for half in halve(y, other) {
                    stack.push(((x.0, x.1, x.2.clone()), half, depth + 1));
                }
            }
        }
        Ok(found)
    }

    /// Levenberg–Marquardt for `A(s) = B(u)` on pieces `ka`, `kb` from local `(s0, u0)`;
    /// returns the global parameters, the gap (original units), the sine of the angle between
    /// the tangents and `|A'|` per unit of the global parameter.
    fn solve_space(
        &self,
        other: &QueryCurve,
        ka: usize,
        kb: usize,
        s0: f64,
        u0: f64,
    ) -> Option<(f64, f64, f64, f64, f64)> {
        let dim = self.dim;
        let mut scratch = Vec::new();
        let mut eval = |s: f64, u: f64| {
            let mut a = vec![0.0; 3 * dim];
            let mut b = vec![0.0; 3 * dim];
            self.eval_local(ka, s, 1, &mut scratch, &mut a);
            other.eval_local(kb, u, 1, &mut scratch, &mut b);
            let mut pa = vec![0.0; dim];
            let mut pb = vec![0.0; dim];
            self.denormalise(&a[..dim], &mut pa);
            other.denormalise(&b[..dim], &mut pb);
            let da: Vec<f64> = a[dim..2 * dim].iter().map(|v| v * self.scale).collect();
            let db: Vec<f64> = b[dim..2 * dim].iter().map(|v| v * other.scale).collect();
            (pa, pb, da, db)
        };
        let ([s, u], _) = levenberg_marquardt([s0, u0], |&[s, u]| {
            let (pa, pb, da, db) = eval(s, u);
            let r: Vec<f64> = pa.iter().zip(&pb).map(|(p, q)| p - q).collect();
            let cross = -dot(&da, &db);
            Residual {
                gap: dist(&pa, &pb),
                normal: [[dot(&da, &da), cross], [cross, dot(&db, &db)]],
                gradient: [dot(&da, &r), -dot(&db, &r)],
            }
        });
        let (pa, pb, da, db) = eval(s, u);
        let (la, lb) = (dot(&da, &da).sqrt(), dot(&db, &db).sqrt());
        let sin = if la > 0.0 && lb > 0.0 {
            let c = (dot(&da, &db) / (la * lb)).clamp(-1.0, 1.0);
            (1.0 - c * c).sqrt()
        } else {
            0.0
        };
        let (a0, a1) = self.spans[ka];
        Some((
            self.global(ka, s),
            other.global(kb, u),
            dist(&pa, &pb),
            sin,
            la / (a1 - a0),
        ))
    }
}

/// Box of a net's Cartesian control points: minima then maxima.
fn net_box(net: &[f64], hd: usize, dim: usize, rational: bool) -> Vec<f64> {
    let mut b = vec![f64::INFINITY; dim];
    b.extend(std::iter::repeat_n(f64::NEG_INFINITY, dim));
    for p in net.chunks_exact(hd) {
        let w = if rational { p[dim] } else { 1.0 };
        for d in 0..dim {
            b[d] = b[d].min(p[d] / w);
            b[dim + d] = b[dim + d].max(p[d] / w);
        }
    }
    b
}
