//! Curve–plane and curve–surface intersections (`docs/theory/queries.md#intersections`).

use super::super::pieces::{bern_roots, check_tolerance, dist, dot, Bern, QueryCurve};
use super::super::project::check_query;
use super::super::surface::{split_curve, QuerySurface};
use super::{boxes_overlap, SurfaceHit, MAX_DEPTH, MAX_PAIRS};
use crate::error::{Error, Result};
use crate::numeric::damped::{levenberg_marquardt, Residual};

impl QueryCurve {
    /// Points where the curve meets the plane (hyperplane) through `origin` with normal
    /// `normal`: the roots of the signed distance `(C(s) − origin)·n`, whose Bernstein
    /// coefficients are those of the control points, so none is missed; a touching root is one
    /// answer. Returns `(t, point)` sorted by `t`; a curve lying in the plane gives its pieces'
    /// middles.
    ///
    /// # Errors
    /// [`Error::Dimension`] / [`Error::NonFinite`] for bad plane data; [`Error::InvalidArgument`]
    /// for a zero normal.
    pub fn intersect_plane(&self, origin: &[f64], normal: &[f64]) -> Result<Vec<(f64, Vec<f64>)>> {
        check_query("plane origin", origin, self.dim)?;
        check_query("plane normal", normal, self.dim)?;
        let nn = normal.iter().map(|x| x * x).sum::<f64>().sqrt();
        if !(nn > 0.0) {
            return Err(Error::InvalidArgument {
                what: "plane normal",
                reason: "it is the zero vector".into(),
            });
        }
        let n: Vec<f64> = normal.iter().map(|x| x / nn).collect();
        let mut o = vec![0.0; self.dim];
        self.normalise(origin, &mut o);
        let mut out: Vec<(f64, Vec<f64>)> = Vec::new();
        let mut scratch = Vec::new();
        for k in 0..self.piece_count() {
            let piece = self.piece(k);
            let mut mag = 0.0_f64;
            let coef: Vec<f64> = piece
                .chunks_exact(self.hd)
                .map(|p| {
                    let w = if self.rational { p[self.dim] } else { 1.0 };
                    let v: f64 = (0..self.dim).map(|d| (p[d] - w * o[d]) * n[d]).sum();
                    mag = mag.max(
                        (0..self.dim).map(|d| (p[d] * n[d]).abs()).sum::<f64>()
                            + w * o.iter().map(|x| x.abs()).sum::<f64>(),
                    );
                    v
                })
                .collect();
            for s in bern_roots(&Bern(coef), 64.0 * f64::EPSILON * mag) {
                let t = self.global(k, s);
                if out
                    .last()
                    .is_some_and(|(u, _)| (t - u).abs() <= 1e-12 * (1.0 + t.abs()))
                {
                    continue;
                }
                out.push((t, self.eval_global(t, 0, &mut scratch)));
            }
        }
        Ok(out)
    }

    /// Points where the curve meets a surface within `tolerance`: subdivision of the curve's
    /// pieces and the surface's patches while their boxes overlap, then Levenberg–Marquardt on
    /// `C(t) = S(u, v)`. Returns `(t, (u, v), point)` sorted by `t`, nearby solutions (closer
    /// than the tolerance) merged.
    ///
    /// # Errors
    /// [`Error::Dimension`] for different dimensions; [`Error::InvalidArgument`] for a bad
    /// tolerance; [`Error::TooLarge`] beyond 2^20 examined pairs.
    pub fn intersect_surface(
        &self,
        surface: &QuerySurface,
        tolerance: f64,
    ) -> Result<Vec<SurfaceHit>> {
        if surface.dim != self.dim {
            return Err(Error::Dimension {
                what: "surface for a curve–surface intersection",
                expected: self.dim,
                got: surface.dim,
            });
        }
        check_tolerance("intersection tolerance", tolerance)?;
        let mut found: Vec<(f64, (f64, f64), Vec<f64>)> = Vec::new();
        let mut scratch = Vec::new();
        let mut visited = 0;
        for k in 0..self.piece_count() {
            for pk in 0..surface.patch_count() {
                // both in original coordinates: sub-curve nets and sub-patch nets
                let cnet = to_original(
                    self.piece(k),
                    self.hd,
                    self.dim,
                    self.rational,
                    &self.centre,
                    self.scale,
                );
                let snet = to_original(
                    surface.patch(pk),
                    surface.hd,
                    surface.dim,
                    surface.rational,
                    &surface.centre,
                    surface.scale,
                );
                let mut stack = vec![((0.0, 1.0), cnet, (0.0, 1.0), (0.0, 1.0), snet, 0_u32)];
                while let Some((cs, cn, us, vs, sn, depth)) = stack.pop() {
                    visited += 1;
                    if visited > MAX_PAIRS {
                        return Err(Error::TooLarge {
                            what: "curve-surface sub-pairs",
                            size: visited,
                            max: MAX_PAIRS,
                        });
                    }
                    let cb = cart_box(&cn, self.hd, self.dim, self.rational);
                    let sb = cart_box(&sn, surface.hd, surface.dim, surface.rational);
                    if !boxes_overlap(&cb, &sb, self.dim, tolerance) {
                        continue;
                    }
                    let cd = dist(&cb[..self.dim], &cb[self.dim..]);
                    let sd = dist(&sb[..self.dim], &sb[self.dim..]);
                    let big = cd.max(sd);
                    if big <= 1e-2 * self.scale.max(surface.scale) || depth >= MAX_DEPTH {
                        let x0 = [
                            0.5 * (cs.0 + cs.1),
                            0.5 * (us.0 + us.1),
                            0.5 * (vs.0 + vs.1),
                        ];
                        if let Some((t, u, v, p)) =
                            self.curve_surface_newton(k, surface, pk, x0, &mut scratch)
                        {
                            if dist(&p.0, &p.1) <= tolerance {
                                found.push((t, surface.global_uv(pk, u, v), p.0));
                            }
                        }
                        continue;
                    }
                    if cd >= sd {
                        let n = cn.len() / self.hd - 1;
                        let (l, r) = split_curve(&cn, self.hd, n);
                        let m = 0.5 * (cs.0 + cs.1);
                        stack.push(((cs.0, m), l, us, vs, sn.clone(), depth + 1));
                        stack.push(((m, cs.1), r, us, vs, sn, depth + 1));
                    } else {
                        for (u, v, net) in surface.split4(&sn, us, vs) {
                            stack.push((cs, cn.clone(), u, v, net, depth + 1));
                        }
                    }
                }
            }
        }
        found.sort_by(|a, b| a.0.total_cmp(&b.0));
        let mut out: Vec<(f64, (f64, f64), Vec<f64>)> = Vec::new();
        for f in found {
            if out.last().is_some_and(|o| dist(&o.2, &f.2) <= tolerance) {
                continue;
            }
            out.push(f);
        }
        Ok(out)
    }

    /// Levenberg–Marquardt for `C(s) = S(u, v)` (local parameters of piece `k` and patch `pk`;
    /// `numeric::damped`, with its bounds on steps and trials); returns the global `t`, local `(u, v)` and both points (original
    /// coordinates).
    #[allow(clippy::type_complexity)]
    fn curve_surface_newton(
        &self,
        k: usize,
        surf: &QuerySurface,
        pk: usize,
        x0: [f64; 3],
        scratch: &mut Vec<f64>,
    ) -> Option<(f64, f64, f64, (Vec<f64>, Vec<f64>))> {
        let dim = self.dim;
        let eval = |x: &[f64; 3], scratch: &mut Vec<f64>| {
            let mut buf = vec![0.0; 3 * dim];
            self.eval_local(k, x[0], 1, scratch, &mut buf);
            let (sp, sd) = surf.eval_patch(pk, x[1], x[2]);
            let mut c = vec![0.0; dim];
            let mut s = vec![0.0; dim];
            self.denormalise(&buf[..dim], &mut c);
            surf.denormalise(&sp, &mut s);
            let dc: Vec<f64> = buf[dim..2 * dim].iter().map(|v| v * self.scale).collect();
            let su: Vec<f64> = sd[..dim].iter().map(|v| v * surf.scale).collect();
            let sv: Vec<f64> = sd[dim..2 * dim].iter().map(|v| v * surf.scale).collect();
            (c, s, dc, su, sv)
        };
        let (x, _) = levenberg_marquardt(x0, |x| {
            let (c, s, dc, su, sv) = eval(x, scratch);
            let r: Vec<f64> = c.iter().zip(&s).map(|(a, b)| a - b).collect();
            // J = [C', −S_u, −S_v]
            let cols = [
                dc,
                su.iter().map(|v| -v).collect::<Vec<_>>(),
                sv.iter().map(|v| -v).collect(),
            ];
            let mut normal = [[0.0; 3]; 3];
            let mut gradient = [0.0; 3];
            for i in 0..3 {
                for j in 0..3 {
                    normal[i][j] = dot(&cols[i], &cols[j]);
                }
                gradient[i] = dot(&cols[i], &r);
            }
            Residual {
                gap: dist(&c, &s),
                normal,
                gradient,
            }
        });
        let (c, s, ..) = eval(&x, scratch);
        Some((self.global(k, x[0]), x[1], x[2], (c, s)))
    }
}

fn to_original(
    net: &[f64],
    hd: usize,
    dim: usize,
    rational: bool,
    centre: &[f64],
    scale: f64,
) -> Vec<f64> {
    let mut out = net.to_vec();
    for p in out.chunks_exact_mut(hd) {
        let w = if rational { p[dim] } else { 1.0 };
        for d in 0..dim {
            p[d] = w * centre[d] + scale * p[d];
        }
    }
    out
}

fn cart_box(net: &[f64], hd: usize, dim: usize, rational: bool) -> Vec<f64> {
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

#[cfg(test)]
mod tests {
    use crate::{BSplineCurve, Points, QueryCurve};

    #[test]
    fn plane_crossings() {
        let c = BSplineCurve::new(
            2,
            vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
            Points::from_3d(&[[0.0, 0.0, -1.0], [1.0, 0.0, 3.0], [2.0, 0.0, -1.0]]).unwrap(),
        )
        .unwrap();
        let q = QueryCurve::from_bspline(&c).unwrap();
        let hits = q
            .intersect_plane(&[0.0, 0.0, 0.0], &[0.0, 0.0, 2.0])
            .unwrap();
        assert_eq!(hits.len(), 2, "{hits:?}");
        for (_, p) in &hits {
            assert!(p[2].abs() < 1e-15, "{p:?}");
        }
        // touching the plane z = 1 at the top: one answer
        let touch = q
            .intersect_plane(&[0.0, 0.0, 1.0], &[0.0, 0.0, 1.0])
            .unwrap();
        assert_eq!(touch.len(), 1, "{touch:?}");
        assert!((touch[0].0 - 0.5).abs() < 1e-6, "{touch:?}");
    }
}
