//! Second-derivative bounds of a face's surface patch by patch, and the grid spacing they give
//! (`docs/theory/topology.md`, "Meshing a trimmed face"): a parameter box is bounded by the
//! largest bounds of the patches it meets, so a short knot span or a patch bent sharply (near
//! a collapsed edge) makes small triangles there and nowhere else.

use super::pcurve::SurfaceClosure;
use crate::query::triangle_bound;
use crate::{Arg, Error, Result, Surface, What};

/// Halvings of each Bezier patch in each direction before its bounds are taken: the bounds of
/// a part's net (a rational one's above all, whose weights' spread and distance from the affine
/// map through its corners shrink with it) come closer to the surface's own derivatives there,
/// at `4^SUB_LEVELS` nets a patch.
const SUB_LEVELS: usize = 3;

/// The `u` and `v` ranges of a part of a patch.
type Ranges = ((f64, f64), (f64, f64));

/// Parameters within this fraction of the domain's width of a breakpoint are at it (a
/// parameter brought back into the domain by a period is a few ulps off).
const BREAK_RTOL: f64 = 1e-12;

/// The patches' breakpoints along one parameter, with its period when the surface closes in it.
/// A parameter outside the domain is brought back by whole periods in a closed direction (the
/// unwrapped pcurves of a closed surface leave the domain so), and belongs to the first or
/// last span otherwise (a pcurve leaves the domain by rounding, and the surface is taken at the
/// nearest point of its domain there).
#[derive(Debug, Clone)]
struct Spans {
    /// Distinct breakpoints, increasing; at least two.
    at: Vec<f64>,
    period: Option<f64>,
}

impl Spans {
    fn count(&self) -> usize {
        self.at.len() - 1
    }

    /// The span holding `x` (`at[i] ≤ x < at[i + 1]`, the last span closed) and the shift from
    /// the domain back to `x` (whole periods, or zero).
    fn locate(&self, x: f64) -> (usize, f64) {
        let (a, n) = (self.at[0], self.count());
        let (w, shift) = match self.period {
            // the domain's end is its start's next copy
            Some(p) if p > 0.0 && (x < a || x >= self.at[n]) => {
                let w = a + (x - a).rem_euclid(p);
                (w, x - w)
            }
            _ => (x, 0.0),
        };
        let i = self.at.partition_point(|&t| t <= w).saturating_sub(1);
        (i.min(n - 1), shift)
    }

    /// The end of the span holding `x`, in `x`'s copy of the domain (`∞` past the last span
    /// of an open direction).
    fn end_of(&self, x: f64) -> (usize, f64) {
        let (i, shift) = self.locate(x);
        let end = if i + 1 == self.count() && self.period.is_none() {
            f64::INFINITY
        } else {
            self.at[i + 1] + shift
        };
        (i, end)
    }

    /// Calls `f` with each span that the closed interval `[lo, hi]` enters (a span it only
    /// touches at its end is left out: the bounds of a span hold on its closed span).
    fn each_in(&self, lo: f64, hi: f64, mut f: impl FnMut(usize)) {
        // NaN ends (not expected) take every span
        let whole = self.period.is_some_and(|p| hi - lo >= p)
            || lo.partial_cmp(&hi).is_none_or(|o| o.is_gt());
        if whole {
            (0..self.count()).for_each(f);
            return;
        }
        // a parameter brought back by a period is a few ulps off: within this of a span's end
        // it is at the end
        let eps = BREAK_RTOL * (self.at[self.count()] - self.at[0]);
        let mut x = lo;
        let mut any = false;
        // each step ends a span, so at most two periods' spans (the interval is shorter than one)
        for _ in 0..=2 * self.count() {
            let (i, end) = self.end_of(x);
            let touches = end - x <= eps && end < hi;
            if !touches {
                f(i);
                any = true;
            }
            // the interval's end reached, or no progress (rounding)
            if end >= hi - eps || end <= x {
                if !any {
                    f(i);
                }
                return;
            }
            x = end;
        }
    }
}

/// Bounds on the second derivatives of a surface in its own parameters and units, one
/// `[A, B, C] ≥ [|S_uu|, |S_uv|, |S_vv|]` per part of a Bezier patch (each patch halved
/// [`SUB_LEVELS`] times in each direction), from the part's net
/// (`QuerySurface::net_bounds`, `docs/theory/queries.md#tessellation`) scaled back from its
/// unit square and the normalised coordinates; and the grid spacing of each span that keeps a
/// grid cell's two triangles within a tolerance.
#[derive(Debug, Clone)]
pub(super) struct Curvature {
    u: Spans,
    v: Spans,
    /// `[A, B, C]` of patch `(i, j)` at `i·(v spans) + j`.
    abc: Vec<[f64; 3]>,
    /// Grid spacing of each `u` span and each `v` span.
    h: [Vec<f64>; 2],
}

impl Curvature {
    /// The bounds of each patch of `s` and the grid spacing at `tolerance`, with the surface's
    /// size (the scale of its normalised coordinates). The spacing of a `u` span is
    /// `h_u = √(2ε / A)` with `A` the largest over its column of patches, of a `v` span
    /// `h_v = √(2ε / C)` likewise, both shrunk by `√r` for the patch with the least
    /// `r = ε / (B h_u h_v)` below 1 in their row and column, so that every cell has `A h_u²`,
    /// `C h_v²` and `2B h_u h_v` at most `2ε`: its two triangles have `M ≤ 6ε` along each side
    /// and are within `ε` ([`triangle_bound`] `≤ max M / 6` for a right triangle's sides).
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for a rational surface with a weight that is not positive.
    pub(super) fn of(s: &Surface, closure: &SurfaceClosure, tolerance: f64) -> Result<(Self, f64)> {
        let q = s.to_query()?;
        // each patch cut into 2^SUB_LEVELS × 2^SUB_LEVELS equal parts, each with its own net
        let mut parts: Vec<(Ranges, Vec<f64>)> = Vec::new();
        for (k, &((a0, a1), (b0, b1))) in q.ranges.iter().enumerate() {
            let mut rows = vec![(a0, a1, q.patch(k).to_vec())];
            for _ in 0..SUB_LEVELS {
                rows = rows
                    .into_iter()
                    .flat_map(|(x0, x1, n)| {
                        let (l, h) = q.halve_u(&n);
                        let m = 0.5 * (x0 + x1);
                        [(x0, m, l), (m, x1, h)]
                    })
                    .collect();
            }
            for (x0, x1, n) in rows {
                let mut cols = vec![(b0, b1, n)];
                for _ in 0..SUB_LEVELS {
                    cols = cols
                        .into_iter()
                        .flat_map(|(y0, y1, n)| {
                            let (l, h) = q.halve_v(&n);
                            let m = 0.5 * (y0 + y1);
                            [(y0, m, l), (m, y1, h)]
                        })
                        .collect();
                }
                parts.extend(
                    cols.into_iter()
                        .map(|(y0, y1, n)| (((x0, x1), (y0, y1)), n)),
                );
            }
        }
        let mut us: Vec<f64> = parts.iter().flat_map(|r| [r.0 .0 .0, r.0 .0 .1]).collect();
        let mut vs: Vec<f64> = parts.iter().flat_map(|r| [r.0 .1 .0, r.0 .1 .1]).collect();
        let ((u0, u1), (v0, v1)) = s.domain();
        us.extend([u0, u1]);
        vs.extend([v0, v1]);
        for a in [&mut us, &mut vs] {
            a.sort_by(f64::total_cmp);
            a.dedup();
            if a.len() < 2 {
                let x = a.first().copied().unwrap_or(0.0);
                a.push(x + 1.0);
            }
        }
        let u = Spans {
            at: us,
            period: closure.period[0],
        };
        let v = Spans {
            at: vs,
            period: closure.period[1],
        };
        let (nu, nv) = (u.count(), v.count());
        let mut abc = vec![[0.0_f64; 3]; nu * nv];
        for &(((a0, a1), (b0, b1)), ref net) in &parts {
            let (pa, pb, pc) = q.net_bounds(net).ok_or(Error::InvalidArgument {
                what: "face surface".into(),
                reason: "a weight is not positive; a rational surface needs positive weights"
                    .into(),
            })?;
            let (du, dv) = (a1 - a0, b1 - b0);
            if du > 0.0 && dv > 0.0 {
                let (i, _) = u.locate(0.5 * (a0 + a1));
                let (j, _) = v.locate(0.5 * (b0 + b1));
                let x = &mut abc[i * nv + j];
                x[0] = x[0].max(pa * q.scale / (du * du));
                x[1] = x[1].max(pb * q.scale / (du * dv));
                x[2] = x[2].max(pc * q.scale / (dv * dv));
            }
        }
        let spacing = |c: f64, w: f64| {
            if c > 0.0 {
                (2.0 * tolerance / c).sqrt().min(w)
            } else {
                w
            }
        };
        let mut hu: Vec<f64> = (0..nu)
            .map(|i| {
                let a = (0..nv).map(|j| abc[i * nv + j][0]).fold(0.0, f64::max);
                spacing(a, u.at[nu] - u.at[0])
            })
            .collect();
        let mut hv: Vec<f64> = (0..nv)
            .map(|j| {
                let c = (0..nu).map(|i| abc[i * nv + j][2]).fold(0.0, f64::max);
                spacing(c, v.at[nv] - v.at[0])
            })
            .collect();
        let (mut su, mut sv) = (vec![1.0_f64; nu], vec![1.0_f64; nv]);
        for i in 0..nu {
            for j in 0..nv {
                let b = abc[i * nv + j][1];
                if b * hu[i] * hv[j] > tolerance {
                    let r = (tolerance / (b * hu[i] * hv[j])).sqrt();
                    su[i] = su[i].min(r);
                    sv[j] = sv[j].min(r);
                }
            }
        }
        for (h, s) in hu.iter_mut().zip(&su).chain(hv.iter_mut().zip(&sv)) {
            *h = (*h * s).max(f64::MIN_POSITIVE);
        }
        Ok((
            Curvature {
                u,
                v,
                abc,
                h: [hu, hv],
            },
            q.scale,
        ))
    }

    /// The largest `[A, B, C]` of the patches the box `[lo, hi]` meets.
    fn over(&self, lo: [f64; 2], hi: [f64; 2]) -> [f64; 3] {
        let nv = self.v.count();
        let mut out = [0.0_f64; 3];
        self.u.each_in(lo[0], hi[0], |i| {
            self.v.each_in(lo[1], hi[1], |j| {
                let x = self.abc[i * nv + j];
                for k in 0..3 {
                    out[k] = out[k].max(x[k]);
                }
            });
        });
        out
    }

    /// `M(e) = A e_u² + 2B |e_u e_v| + C e_v² ≥ max |D²S[e, e]|` over the segment from `a` to
    /// `b` (the bounds of the patches its box meets), for its step `e = b − a`.
    pub(super) fn segment(&self, a: [f64; 2], b: [f64; 2]) -> f64 {
        let lo = [a[0].min(b[0]), a[1].min(b[1])];
        let hi = [a[0].max(b[0]), a[1].max(b[1])];
        let m = self.over(lo, hi);
        let (eu, ev) = (b[0] - a[0], b[1] - a[1]);
        m[0] * eu * eu + 2.0 * m[1] * (eu * ev).abs() + m[2] * ev * ev
    }

    /// The deviation bound of the linear interpolant over a parameter triangle
    /// ([`triangle_bound`] of its edges' `M`, the bounds of the patches its box meets).
    pub(super) fn triangle(&self, p: [[f64; 2]; 3]) -> f64 {
        let lo = [0, 1].map(|d| p[0][d].min(p[1][d]).min(p[2][d]));
        let hi = [0, 1].map(|d| p[0][d].max(p[1][d]).max(p[2][d]));
        let m = self.over(lo, hi);
        let along = |i: usize, j: usize| {
            let (eu, ev) = (p[j][0] - p[i][0], p[j][1] - p[i][1]);
            m[0] * eu * eu + 2.0 * m[1] * (eu * ev).abs() + m[2] * ev * ev
        };
        triangle_bound([along(0, 1), along(0, 2), along(1, 2)])
    }

    /// The least grid spacing in direction `d` (0 = `u`) over the spans `[lo, hi]` enters.
    pub(super) fn spacing_over(&self, d: usize, lo: f64, hi: f64) -> f64 {
        let spans = if d == 0 { &self.u } else { &self.v };
        let mut h = f64::INFINITY;
        spans.each_in(lo.min(hi), lo.max(hi), |i| h = h.min(self.h[d][i]));
        h
    }

    /// The grid lines in direction `d` over `[lo, hi]`, `lo` and `hi` first and last: from
    /// each line the next is a step of the least spacing of the spans between them, the last
    /// step shared with the one before it when it would be short. `budget` lines at most, else
    /// [`Error::TooLarge`].
    pub(super) fn lines(&self, d: usize, lo: f64, hi: f64, budget: usize) -> Result<Vec<f64>> {
        let mut out = vec![lo];
        let mut x = lo;
        while x < hi {
            let mut h = self.spacing_over(d, x, x);
            // the least spacing over the step: each pass takes a finer span's, so it ends
            for _ in 0..64 {
                let g = self.spacing_over(d, x, x + h);
                if g >= h {
                    break;
                }
                h = g;
            }
            if x + 1.5 * h >= hi {
                // the rest in one or two equal steps
                if x + h < hi {
                    out.push(0.5 * (x + hi));
                }
                out.push(hi);
                break;
            }
            x += h;
            out.push(x);
            if out.len() > budget {
                return Err(Error::TooLarge {
                    what: What::of(
                        Arg::Tolerance,
                        "grid lines of a face's mesh (make the tolerance larger)",
                    ),
                    size: out.len(),
                    max: budget,
                });
            }
        }
        Ok(out)
    }

    /// The number of grid cells over the surface's whole domain.
    pub(super) fn cells(&self) -> f64 {
        let count = |s: &Spans, h: &[f64]| -> f64 {
            let steps: f64 = (0..s.count()).map(|i| (s.at[i + 1] - s.at[i]) / h[i]).sum();
            steps.ceil().max(1.0)
        };
        count(&self.u, &self.h[0]) * count(&self.v, &self.h[1])
    }
}
