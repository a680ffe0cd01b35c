//! The surface as the queries see it: its (rational) Bezier patches, normalised to the unit box,
//! with evaluation of points and second derivatives and subdivision of patch nets
//! (`docs/theory/queries.md#bezier-pieces`).

use super::pieces::MAX_QUERY_DEGREE;
use crate::error::{check_finite, Error, Result};
use crate::Arg;
use crate::{BSplineSurface, NurbsSurface};

/// A surface prepared for geometric queries: its Bezier patches (P&T A5.7), translated and
/// scaled so that the control points fill `[−1, 1]^dim`. Build it once with
/// [`QuerySurface::from_bspline`] or [`QuerySurface::from_nurbs`]; parameters are the
/// surface's, points and distances in its coordinates.
#[derive(Debug, Clone)]
pub struct QuerySurface {
    pub(crate) dim: usize,
    pub(crate) p: usize,
    pub(crate) q: usize,
    pub(crate) rational: bool,
    pub(crate) hd: usize,
    /// `u` and `v` intervals of each patch.
    pub(crate) ranges: Vec<((f64, f64), (f64, f64))>,
    /// Normalised homogeneous nets, `(p + 1)(q + 1)·hd` per patch, row-major in `u`.
    pub(crate) nets: Vec<f64>,
    pub(crate) centre: Vec<f64>,
    pub(crate) scale: f64,
}

impl QuerySurface {
    /// Prepares a B-spline surface.
    ///
    /// # Errors
    /// [`Error::Degree`] above [`MAX_QUERY_DEGREE`].
    pub fn from_bspline(s: &BSplineSurface) -> Result<Self> {
        let mut ranges = Vec::new();
        let mut nets = Vec::new();
        for (u, v, patch) in s.to_bezier_patches() {
            ranges.push((u, v));
            nets.extend_from_slice(patch.control_points().as_slice());
        }
        Self::build(s.dim(), s.degree_u(), s.degree_v(), false, ranges, nets)
    }

    /// Prepares a NURBS surface (rational patches of its homogeneous net).
    ///
    /// # Errors
    /// [`Error::Degree`] above [`MAX_QUERY_DEGREE`].
    pub fn from_nurbs(s: &NurbsSurface) -> Result<Self> {
        let mut ranges = Vec::new();
        let mut nets = Vec::new();
        for (u, v, patch) in s.homogeneous().to_bezier_patches() {
            ranges.push((u, v));
            nets.extend_from_slice(patch.control_points().as_slice());
        }
        Self::build(s.dim(), s.degree_u(), s.degree_v(), true, ranges, nets)
    }

    fn build(
        dim: usize,
        p: usize,
        q: usize,
        rational: bool,
        ranges: Vec<((f64, f64), (f64, f64))>,
        mut nets: Vec<f64>,
    ) -> Result<Self> {
        if p.max(q) > MAX_QUERY_DEGREE {
            return Err(Error::Degree {
                degree: p.max(q),
                reason: format!(
                    "geometric queries accept degree at most {MAX_QUERY_DEGREE} \
                     (lekalo::MAX_QUERY_DEGREE)"
                ),
            });
        }
        check_finite(Arg::ControlPoints, &nets)?;
        let hd = dim + usize::from(rational);
        let (centre, scale) = super::pieces::normalise(&mut nets, dim, rational);
        Ok(QuerySurface {
            dim,
            p,
            q,
            rational,
            hd,
            ranges,
            nets,
            centre,
            scale,
        })
    }

    /// Number of Bezier patches.
    #[must_use]
    pub fn patch_count(&self) -> usize {
        self.ranges.len()
    }

    /// Dimension of the surface's points.
    #[must_use]
    pub fn dim(&self) -> usize {
        self.dim
    }

    /// The parameter domain `((u_min, u_max), (v_min, v_max))`: the union of the patches'.
    #[must_use]
    pub fn domain(&self) -> ((f64, f64), (f64, f64)) {
        let mut d = (
            (f64::INFINITY, f64::NEG_INFINITY),
            (f64::INFINITY, f64::NEG_INFINITY),
        );
        for &(u, v) in &self.ranges {
            d = (
                (d.0 .0.min(u.0), d.0 .1.max(u.1)),
                (d.1 .0.min(v.0), d.1 .1.max(v.1)),
            );
        }
        d
    }

    /// Half the largest extent of the control net (the size tolerances are relative to).
    #[must_use]
    pub fn scale(&self) -> f64 {
        self.scale
    }

    pub(crate) fn patch(&self, k: usize) -> &[f64] {
        let stride = (self.p + 1) * (self.q + 1) * self.hd;
        &self.nets[k * stride..(k + 1) * stride]
    }

    pub(crate) fn normalise(&self, x: &[f64], out: &mut [f64]) {
        for d in 0..self.dim {
            out[d] = (x[d] - self.centre[d]) / self.scale;
        }
    }

    pub(crate) fn denormalise(&self, x: &[f64], out: &mut [f64]) {
        for d in 0..self.dim {
            out[d] = self.centre[d] + self.scale * x[d];
        }
    }

    pub(crate) fn global_uv(&self, k: usize, u: f64, v: f64) -> (f64, f64) {
        let ((u0, u1), (v0, v1)) = self.ranges[k];
        (
            if u >= 1.0 { u1 } else { u0 + u * (u1 - u0) },
            if v >= 1.0 { v1 } else { v0 + v * (v1 - v0) },
        )
    }

    /// Point and derivatives `S_u, S_v, S_uu, S_uv, S_vv` (five rows of `dim`) in original
    /// coordinates and with respect to the global parameters, at global `(u, v)`: those of the
    /// first patch whose range holds it ([`QuerySurface::eval_patch`], scaled to the patch's
    /// range). `None` outside the domain or for NaN.
    pub(crate) fn eval_global(&self, u: f64, v: f64) -> Option<(Vec<f64>, Vec<f64>)> {
        let k = self
            .ranges
            .iter()
            .position(|&((u0, u1), (v0, v1))| (u0..=u1).contains(&u) && (v0..=v1).contains(&v))?;
        let ((u0, u1), (v0, v1)) = self.ranges[k];
        let (hu, hv) = (u1 - u0, v1 - v0);
        let (pn, der) = self.eval_patch(k, (u - u0) / hu, (v - v0) / hv);
        let mut p = vec![0.0; self.dim];
        self.denormalise(&pn, &mut p);
        let factor = [
            1.0 / hu,
            1.0 / hv,
            1.0 / (hu * hu),
            1.0 / (hu * hv),
            1.0 / (hv * hv),
        ];
        let d: Vec<f64> = der
            .chunks(self.dim)
            .zip(factor)
            .flat_map(|(row, f)| row.iter().map(move |x| x * self.scale * f))
            .collect();
        Some((p, d))
    }

    /// Box of the Cartesian points of a (sub-)patch net: minima then maxima.
    pub(crate) fn net_box(&self, net: &[f64]) -> Vec<f64> {
        let dim = self.dim;
        let mut b = vec![f64::INFINITY; dim];
        b.extend(std::iter::repeat_n(f64::NEG_INFINITY, dim));
        for c in net.chunks_exact(self.hd) {
            let w = if self.rational { c[dim] } else { 1.0 };
            for d in 0..dim {
                let x = c[d] / w;
                b[d] = b[d].min(x);
                b[dim + d] = b[dim + d].max(x);
            }
        }
        b
    }

    /// Normalised point and the derivatives `S_u, S_v, S_uu, S_uv, S_vv` (local parameters) of
    /// patch `k` at local `(u, v)`: the `v` curve of every row with its derivatives, then the
    /// `u` curves through those (P&T §3.4), then the rational quotient rule (P&T eq. 4.20).
    pub(crate) fn eval_patch(&self, k: usize, u: f64, v: f64) -> (Vec<f64>, Vec<f64>) {
        self.eval_net(self.patch(k), u, v)
    }

    pub(crate) fn eval_net(&self, net: &[f64], u: f64, v: f64) -> (Vec<f64>, Vec<f64>) {
        let (p, q, hd, dim) = (self.p, self.q, self.hd, self.dim);
        let mut rows = [
            vec![0.0; (p + 1) * hd],
            vec![0.0; (p + 1) * hd],
            vec![0.0; (p + 1) * hd],
        ];
        let mut tmp = Vec::new();
        for i in 0..=p {
            let row = &net[i * (q + 1) * hd..(i + 1) * (q + 1) * hd];
            let (a, a1, a2) = bezier_ders(row, hd, v, &mut tmp);
            rows[0][i * hd..(i + 1) * hd].copy_from_slice(&a);
            rows[1][i * hd..(i + 1) * hd].copy_from_slice(&a1);
            rows[2][i * hd..(i + 1) * hd].copy_from_slice(&a2);
        }
        let (s, su, suu) = bezier_ders(&rows[0], hd, u, &mut tmp);
        let (sv, suv, _) = bezier_ders(&rows[1], hd, u, &mut tmp);
        let (svv, _, _) = bezier_ders(&rows[2], hd, u, &mut tmp);
        if !self.rational {
            let mut der = Vec::with_capacity(5 * dim);
            for x in [&su, &sv, &suu, &suv, &svv] {
                der.extend_from_slice(&x[..dim]);
            }
            return (s[..dim].to_vec(), der);
        }
        let w = s[dim];
        let (wu, wv, wuu, wuv, wvv) = (su[dim], sv[dim], suu[dim], suv[dim], svv[dim]);
        let pt: Vec<f64> = (0..dim).map(|d| s[d] / w).collect();
        let pu: Vec<f64> = (0..dim).map(|d| (su[d] - wu * pt[d]) / w).collect();
        let pv: Vec<f64> = (0..dim).map(|d| (sv[d] - wv * pt[d]) / w).collect();
        let mut der = Vec::with_capacity(5 * dim);
        der.extend_from_slice(&pu);
        der.extend_from_slice(&pv);
        for d in 0..dim {
            der.push((suu[d] - 2.0 * wu * pu[d] - wuu * pt[d]) / w);
        }
        for d in 0..dim {
            der.push((suv[d] - wu * pv[d] - wv * pu[d] - wuv * pt[d]) / w);
        }
        for d in 0..dim {
            der.push((svv[d] - 2.0 * wv * pv[d] - wvv * pt[d]) / w);
        }
        (pt, der)
    }

    /// The four quarters of a sub-patch net covering local `u` and `v` ranges (split at the
    /// middle of each, de Casteljau in `u` on the rows, then in `v`).
    pub(crate) fn split4(&self, net: &[f64], u: (f64, f64), v: (f64, f64)) -> Vec<SubNet> {
        let (p, q, hd) = (self.p, self.q, self.hd);
        let (um, vm) = (0.5 * (u.0 + u.1), 0.5 * (v.0 + v.1));
        // split in u: the rows form a curve of (q + 1)·hd-points
        let (a, b) = split_curve(net, (q + 1) * hd, p);
        let mut out = Vec::with_capacity(4);
        let row = (q + 1) * hd;
        for (ur, half) in [((u.0, um), a), ((um, u.1), b)] {
            // split in v: each row separately, into its place in the two nets
            let mut lo = vec![0.0; half.len()];
            let mut hi = vec![0.0; half.len()];
            for (i, r) in half.chunks_exact(row).enumerate() {
                let span = i * row..(i + 1) * row;
                split_curve_into(r, hd, q, &mut lo[span.clone()], &mut hi[span]);
            }
            out.push((ur, (v.0, vm), lo));
            out.push((ur, (vm, v.1), hi));
        }
        out
    }
}

impl QuerySurface {
    /// Halves of a patch net at `u = 1/2` (de Casteljau; the rows form a curve of
    /// `(q + 1)·hd`-scalar points).
    pub(crate) fn halve_u(&self, net: &[f64]) -> (Vec<f64>, Vec<f64>) {
        split_curve(net, (self.q + 1) * self.hd, self.p)
    }

    /// The parts of a patch net below and above `u = t` (de Casteljau).
    pub(crate) fn split_u_at(&self, net: &[f64], t: f64) -> (Vec<f64>, Vec<f64>) {
        split_curve_at(net, (self.q + 1) * self.hd, self.p, t)
    }

    /// The parts of a patch net below and above `v = t` (de Casteljau on each row).
    pub(crate) fn split_v_at(&self, net: &[f64], t: f64) -> (Vec<f64>, Vec<f64>) {
        let (mut lo, mut hi) = (Vec::with_capacity(net.len()), Vec::with_capacity(net.len()));
        for row in net.chunks_exact((self.q + 1) * self.hd) {
            let (l, h) = split_curve_at(row, self.hd, self.q, t);
            lo.extend(l);
            hi.extend(h);
        }
        (lo, hi)
    }

    /// Halves of a patch net at `v = 1/2` (de Casteljau on each row).
    pub(crate) fn halve_v(&self, net: &[f64]) -> (Vec<f64>, Vec<f64>) {
        let (mut lo, mut hi) = (Vec::with_capacity(net.len()), Vec::with_capacity(net.len()));
        for row in net.chunks_exact((self.q + 1) * self.hd) {
            let (l, h) = split_curve(row, self.hd, self.q);
            lo.extend(l);
            hi.extend(h);
        }
        (lo, hi)
    }
}

/// A sub-patch: its local `u` and `v` ranges and its net.
pub(crate) type SubNet = ((f64, f64), (f64, f64), Vec<f64>);

/// Halves of a Bezier curve of degree `n` with `stride`-scalar points, split at 1/2, written into
/// `left` and `right` (each as long as `ctrl`) without allocating: de Casteljau in place in
/// `right` (after level `l` its first `n − l + 1` points are the level-`l` points, the others
/// already the right half's), the left half's points taken from its front.
pub(crate) fn split_curve_into(
    ctrl: &[f64],
    stride: usize,
    n: usize,
    left: &mut [f64],
    right: &mut [f64],
) {
    right.copy_from_slice(ctrl);
    left[..stride].copy_from_slice(&ctrl[..stride]);
    for level in 1..=n {
        for i in 0..=n - level {
            for d in 0..stride {
                right[i * stride + d] = 0.5 * (right[i * stride + d] + right[(i + 1) * stride + d]);
            }
        }
        left[level * stride..(level + 1) * stride].copy_from_slice(&right[..stride]);
    }
}

/// Halves of a Bezier curve of degree `n` with `stride`-scalar points, split at 1/2.
pub(crate) fn split_curve(ctrl: &[f64], stride: usize, n: usize) -> (Vec<f64>, Vec<f64>) {
    let mut b = ctrl.to_vec();
    let mut left = Vec::with_capacity(ctrl.len());
    let mut right = vec![0.0; ctrl.len()];
    left.extend_from_slice(&b[..stride]);
    right[n * stride..].copy_from_slice(&b[n * stride..]);
    for level in 1..=n {
        for i in 0..=n - level {
            for d in 0..stride {
                b[i * stride + d] = 0.5 * (b[i * stride + d] + b[(i + 1) * stride + d]);
            }
        }
        left.extend_from_slice(&b[..stride]);
        let j = n - level;
        right[j * stride..(j + 1) * stride].copy_from_slice(&b[j * stride..(j + 1) * stride]);
    }
    (left, right)
}

/// The parts `[0, t]` and `[t, 1]` of a Bezier curve of degree `n` with `stride`-scalar points
/// (de Casteljau at `t`).
pub(crate) fn split_curve_at(
    ctrl: &[f64],
    stride: usize,
    n: usize,
    t: f64,
) -> (Vec<f64>, Vec<f64>) {
    let mut b = ctrl.to_vec();
    let mut left = Vec::with_capacity(ctrl.len());
    let mut right = vec![0.0; ctrl.len()];
    left.extend_from_slice(&b[..stride]);
    right[n * stride..].copy_from_slice(&b[n * stride..]);
    for level in 1..=n {
        for i in 0..(n + 1 - level) * stride {
            b[i] = (1.0 - t) * b[i] + t * b[i + stride];
        }
        left.extend_from_slice(&b[..stride]);
        let j = n - level;
        right[j * stride..(j + 1) * stride].copy_from_slice(&b[j * stride..(j + 1) * stride]);
    }
    (left, right)
}

/// Point, first and second derivative of a Bezier curve of `stride`-scalar points at `s`.
pub(crate) fn bezier_ders(
    ctrl: &[f64],
    stride: usize,
    s: f64,
    tmp: &mut Vec<f64>,
) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
    let n = ctrl.len() / stride - 1;
    tmp.clear();
    tmp.extend_from_slice(ctrl);
    let keep = n.min(2);
    for level in 0..n - keep {
        for i in 0..n - level {
            for d in 0..stride {
                tmp[i * stride + d] =
                    (1.0 - s) * tmp[i * stride + d] + s * tmp[(i + 1) * stride + d];
            }
        }
    }
    let nf = n as f64;
    let mut a = vec![0.0; stride];
    let mut a1 = vec![0.0; stride];
    let mut a2 = vec![0.0; stride];
    for d in 0..stride {
        let b0 = tmp[d];
        match keep {
            0 => a[d] = b0,
            1 => {
                let b1 = tmp[stride + d];
                a[d] = (1.0 - s) * b0 + s * b1;
                a1[d] = b1 - b0;
            }
            _ => {
                let (b1, b2) = (tmp[stride + d], tmp[2 * stride + d]);
                let l0 = (1.0 - s) * b0 + s * b1;
                let l1 = (1.0 - s) * b1 + s * b2;
                a[d] = (1.0 - s) * l0 + s * l1;
                a1[d] = nf * (l1 - l0);
                a2[d] = nf * (nf - 1.0) * (b2 - 2.0 * b1 + b0);
            }
        }
    }
    (a, a1, a2)
}
