//! The knot derivatives of tensor-product nets in `N` directions: [`BSplineSurface`] (`N = 2`)
//! and [`TensorBSpline`], by one kernel (`docs/theory/derivatives.md`, "Knots").
//!
//! Along direction `a`, at a point `x`, `S` is the curve in `x_a` whose coefficients are the
//! net contracted with the other directions' basis functions,
//! `Q_j = Σ_{k_b, b ≠ a} Π_{b≠a} N_{k_b,p_b}(x_b) P_{k_0 … j … k_{N−1}}` (`j` at position `a`),
//! so `∂S(x)/∂τᵃ_k` is the curve formula of [`KnotWeights`] on the `p_a + 3` coefficients
//! `Q_{s_a−p_a−1} … Q_{s_a+1}`: the same one-direction kernel, along each direction in turn.

use super::KnotWeights;
use crate::basis::{basis_funs_into, BasisScratch};
use crate::derivatives::checks::{check_cotangent, check_input, check_len, zeroed_output};
use crate::error::Result;
use crate::knots::SpanCursor;
use crate::surface::BSplineSurface;
use crate::tensor::TensorBSpline;

/// A net of coefficients in `N` directions, borrowed from a surface or a tensor spline (already
/// validated): direction `a` has degree `degrees[a]`, the knots `knots[a]` and `shape[a]`
/// coefficients; the net is flat, point-major, the first direction slowest (`dim` numbers a
/// point), so that index `k_a` of direction `a` is `strides[a]` numbers from `k_a + 1`.
struct Net<'a> {
    degrees: &'a [usize],
    knots: &'a [&'a [f64]],
    shape: &'a [usize],
    net: &'a [f64],
    dim: usize,
    strides: Vec<usize>,
}

/// The scratch of one pass over the points, sized once for a net.
struct Scratch<'a> {
    cursors: Vec<SpanCursor<'a>>,
    /// The span of every coordinate of the current point.
    spans: Vec<usize>,
    /// The `p_a + 1` non-zero basis functions of every direction at the current point.
    bases: Vec<Vec<f64>>,
    basis_scratch: Vec<BasisScratch>,
    /// The knot weights of every direction at the current point.
    weights: Vec<KnotWeights>,
    /// The block of the directions other than the current one: each cell's first number in
    /// the net and its product of basis functions.
    cells: Vec<(usize, f64)>,
    odometer: Vec<usize>,
    /// The curve along the current direction `a`: `Q_j` at slot `j − (s_a − p_a − 1)`,
    /// `p_a + 3` points of `dim` numbers (clipped to the net, unset slots zero).
    columns: Vec<f64>,
}

impl<'a> Net<'a> {
    fn new(
        degrees: &'a [usize],
        knots: &'a [&'a [f64]],
        shape: &'a [usize],
        net: &'a [f64],
        dim: usize,
    ) -> Self {
        let strides = (0..shape.len())
            .map(|a| shape[a + 1..].iter().product::<usize>() * dim)
            .collect();
        Net {
            degrees,
            knots,
            shape,
            net,
            dim,
            strides,
        }
    }

    fn scratch(&self) -> Scratch<'a> {
        let block: usize = self.degrees.iter().map(|p| p + 1).product();
        let widest = self.degrees.iter().max().map_or(0, |p| p + 3);
        Scratch {
            cursors: (self.knots.iter().zip(self.degrees))
                .map(|(k, &p)| SpanCursor::over(k, p))
                .collect(),
            spans: vec![0; self.degrees.len()],
            bases: self.degrees.iter().map(|p| vec![0.0; p + 1]).collect(),
            basis_scratch: self.degrees.iter().map(|&p| BasisScratch::new(p)).collect(),
            weights: self.degrees.iter().map(|&p| KnotWeights::new(p)).collect(),
            cells: Vec::with_capacity(block),
            odometer: vec![0; self.degrees.len()],
            columns: vec![0.0; widest * self.dim],
        }
    }

    /// The spans and basis functions of every direction at `x` (P&T A2.1, A2.2).
    fn locate(&self, sc: &mut Scratch<'a>, x: &[f64]) -> Result<()> {
        for (a, (&p, &xa)) in self.degrees.iter().zip(x).enumerate() {
            let span = sc.cursors[a].find(xa)?;
            sc.spans[a] = span;
            let (scratch, out) = (&mut sc.basis_scratch[a], &mut sc.bases[a]);
            basis_funs_into(self.knots[a], p, span, xa, scratch, out);
        }
        Ok(())
    }

    /// Direction `a` at the located point with coordinate `xa`: its knot weights, and its
    /// curve's coefficients `Q_j` into `sc.columns`.
    fn along(&self, sc: &mut Scratch<'a>, a: usize, xa: f64) {
        let (p, n, dim) = (self.degrees[a], self.shape[a], self.dim);
        let span = sc.spans[a];
        sc.weights[a].at(self.knots[a], n, span, xa);
        // the other directions' block, the last direction fastest (direction a held at 0)
        sc.cells.clear();
        sc.odometer.fill(0);
        'block: loop {
            let (mut offset, mut product) = (0, 1.0);
            for (b, &k) in sc.odometer.iter().enumerate() {
                if b != a {
                    offset += (sc.spans[b] - self.degrees[b] + k) * self.strides[b];
                    product *= sc.bases[b][k];
                }
            }
            sc.cells.push((offset, product));
            let mut b = self.degrees.len();
            loop {
                if b == 0 {
                    break 'block;
                }
                b -= 1;
                if b == a {
                    continue;
                }
                sc.odometer[b] += 1;
                if sc.odometer[b] <= self.degrees[b] {
                    break;
                }
                sc.odometer[b] = 0;
            }
        }
        let columns = &mut sc.columns[..(p + 3) * dim];
        columns.fill(0.0);
        let stride = self.strides[a];
        for j in span.saturating_sub(p + 1)..=(span + 1).min(n - 1) {
            let slot = j + p + 1 - span; // j ≥ s − p − 1
            let q = &mut columns[slot * dim..(slot + 1) * dim];
            for &(offset, product) in &sc.cells {
                let start = j * stride + offset;
                for (x, y) in q.iter_mut().zip(&self.net[start..start + dim]) {
                    *x += product * y;
                }
            }
        }
    }

    /// `Ṡ_r = Σ_a Σ_k τ̇ᵃ_k ∂S(x_r)/∂τᵃ_k` into `tangent_out` (`m × dim`), `tangents` one
    /// optional knot tangent a direction (lengths checked by the caller).
    fn knot_jvp(
        &self,
        xs: &[f64],
        tangents: &[Option<&[f64]>],
        tangent_out: &mut [f64],
    ) -> Result<()> {
        let (n_vars, dim) = (self.degrees.len(), self.dim);
        let mut sc = self.scratch();
        for (x, d) in xs
            .chunks_exact(n_vars)
            .zip(tangent_out.chunks_exact_mut(dim))
        {
            d.fill(0.0);
            self.locate(&mut sc, x)?;
            for (a, tangent) in tangents.iter().enumerate() {
                let Some(tangent) = tangent else { continue };
                self.along(&mut sc, a, x[a]);
                let (weights, cols) = (&sc.weights[a], &sc.columns);
                // Q_j is at slot j − (s − p − 1) = j − first_diff + 1
                let base = weights.first_diff;
                let col = move |j: usize| &cols[(j + 1 - base) * dim..(j + 2 - base) * dim];
                for k in weights.knots() {
                    if tangent[k] != 0.0 {
                        weights.add_derivative(k, tangent[k], col, d);
                    }
                }
            }
        }
        Ok(())
    }

    /// `τ̄ᵃ_k = Σ_r ḡ_r · ∂S(x_r)/∂τᵃ_k` into the buffers of `cotangents` given (one a
    /// direction, zeroed and checked by the caller).
    fn knot_vjp(
        &self,
        xs: &[f64],
        cotangent: &[f64],
        cotangents: &mut [Option<&mut [f64]>],
    ) -> Result<()> {
        let (n_vars, dim) = (self.degrees.len(), self.dim);
        let mut sc = self.scratch();
        for (x, g) in xs.chunks_exact(n_vars).zip(cotangent.chunks_exact(dim)) {
            self.locate(&mut sc, x)?;
            for (a, buf) in cotangents.iter_mut().enumerate() {
                let Some(buf) = buf.as_deref_mut() else {
                    continue;
                };
                self.along(&mut sc, a, x[a]);
                let (weights, cols) = (&sc.weights[a], &sc.columns);
                let base = weights.first_diff;
                let col = move |j: usize| &cols[(j + 1 - base) * dim..(j + 2 - base) * dim];
                for k in weights.knots() {
                    buf[k] += weights.cotangent(k, g, col);
                }
            }
        }
        Ok(())
    }
}

impl BSplineSurface {
    /// Forward-mode derivative (JVP) of [`BSplineSurface::eval_batch`] with respect to the
    /// knots of each direction: `out` receives `S(u_i, v_i)` (bit-for-bit `eval_batch`) and
    /// `tangent_out` `Ṡ_i = Σ_k τ̇ᵘ_k ∂S/∂τᵘ_k + Σ_l τ̇ᵛ_l ∂S/∂τᵛ_l`. Along `u`, `S(·, v)` is the
    /// curve with coefficients `Q_j(v) = Σ_l N_{l,q}(v) P_{jl}`, so
    /// `∂S/∂τᵘ_k = − Σ_{j=k−p}^{k} (Q_j − Q_{j−1}) / (τᵘ_{j+p} − τᵘ_j) · N_{j,p,τᵘ*}(u)`,
    /// the curve formula of [`crate::BSplineCurve::eval_batch_knot_jvp`]
    /// (`docs/theory/derivatives.md`, "Knots"), and along `v` likewise: the kernel of
    /// [`TensorBSpline::eval_batch_knot_jvp`] for two directions. `knot_tangent_u`
    /// (`knot_tangent_v`) has one number a knot of that direction (`None` is zero); the tangents
    /// of each direction's `p + 1` first and last knots are ignored.
    /// O(m·(p³ + q³ + (p² + q²)·dim + (p + 1)(q + 1)·dim)).
    ///
    /// # Errors
    /// [`crate::Error::LengthMismatch`] for a buffer of the wrong length;
    /// [`crate::Error::NonFinite`] for a non-finite tangent;
    /// [`crate::Error::ParameterOutOfDomain`] at the first pair outside the domain.
    pub fn eval_batch_knot_jvp(
        &self,
        uv: &[[f64; 2]],
        knot_tangent_u: Option<&[f64]>,
        knot_tangent_v: Option<&[f64]>,
        out: &mut [f64],
        tangent_out: &mut [f64],
    ) -> Result<()> {
        let dim = self.dim();
        let m = uv.len().saturating_mul(dim);
        check_len("output buffer (parameter pairs × dimension)", m, out.len())?;
        check_len(
            "tangent output buffer (parameter pairs × dimension)",
            m,
            tangent_out.len(),
        )?;
        let (ku, kv) = (self.knots_u().len(), self.knots_v().len());
        check_input("u knot tangent (one a u knot)", ku, knot_tangent_u)?;
        check_input("v knot tangent (one a v knot)", kv, knot_tangent_v)?;
        self.eval_batch(uv, out)?;
        let (degrees, shape) = (<[usize; 2]>::from(self.degree()), self.net_size().into());
        let knots = [self.knots_u().as_slice(), self.knots_v().as_slice()];
        let net = self.net(&degrees, &knots, &shape);
        net.knot_jvp(
            uv.as_flattened(),
            &[knot_tangent_u, knot_tangent_v],
            tangent_out,
        )
    }

    /// Reverse-mode derivative (VJP) of [`BSplineSurface::eval_batch`] with respect to the
    /// knots: for a cotangent `ḡ` (`uv.len() × dim`), `τ̄ᵘ_k = Σ_i ḡ_i · ∂S(u_i, v_i)/∂τᵘ_k`
    /// into `knot_cotangent_u` and likewise along `v` (each when given; overwritten), with the
    /// derivatives of [`BSplineSurface::eval_batch_knot_jvp`], whose transpose this is
    /// (`docs/theory/derivatives.md`, "Knots"). Each direction's `p + 1` first and last knots
    /// get zero. O(m·(p³ + q³ + (p² + q²)·dim + (p + 1)(q + 1)·dim)).
    ///
    /// # Errors
    /// [`crate::Error::LengthMismatch`] for a buffer of the wrong length;
    /// [`crate::Error::NonFinite`] for a non-finite cotangent;
    /// [`crate::Error::ParameterOutOfDomain`] at the first pair outside the domain.
    pub fn eval_batch_knot_vjp(
        &self,
        uv: &[[f64; 2]],
        cotangent: &[f64],
        mut knot_cotangent_u: Option<&mut [f64]>,
        mut knot_cotangent_v: Option<&mut [f64]>,
    ) -> Result<()> {
        check_cotangent(
            "cotangent (parameter pairs × dimension)",
            uv.len(),
            self.dim(),
            cotangent,
        )?;
        let (ku, kv) = (self.knots_u().len(), self.knots_v().len());
        zeroed_output(
            "u knot cotangent buffer (one a u knot)",
            ku,
            knot_cotangent_u.as_deref_mut(),
        )?;
        zeroed_output(
            "v knot cotangent buffer (one a v knot)",
            kv,
            knot_cotangent_v.as_deref_mut(),
        )?;
        let (degrees, shape) = (<[usize; 2]>::from(self.degree()), self.net_size().into());
        let knots = [self.knots_u().as_slice(), self.knots_v().as_slice()];
        let net = self.net(&degrees, &knots, &shape);
        net.knot_vjp(
            uv.as_flattened(),
            cotangent,
            &mut [knot_cotangent_u, knot_cotangent_v],
        )
    }

    /// The net of two directions, `u` first (the layout `(i·nv + j)·dim` is the tensor's).
    fn net<'a>(
        &'a self,
        degrees: &'a [usize; 2],
        knots: &'a [&'a [f64]; 2],
        shape: &'a [usize; 2],
    ) -> Net<'a> {
        let net = self.control_points().as_slice();
        Net::new(degrees, knots, shape, net, self.dim())
    }
}

impl TensorBSpline {
    /// Forward-mode derivative (JVP) of [`TensorBSpline::eval_batch`] with respect to the knots
    /// of each direction, at the points `xs` (`N` coordinates a point, flat): `out` receives
    /// `S(x_r)` (bit-for-bit `eval_batch`) and `tangent_out`
    ///
    /// `Ṡ_r = Σ_a Σ_k τ̇ᵃ_k ∂S(x_r)/∂τᵃ_k`,
    /// `∂S/∂τᵃ_k = − Σ_{j=k−p_a}^{k} (Q_j − Q_{j−1}) / (τᵃ_{j+p_a} − τᵃ_j) · N_{j,p_a,τᵃ*}(x_a)`,
    ///
    /// with `Q_j = Σ Π_{b≠a} N_{k_b,p_b}(x_b) P_{k_0 … j … k_{N−1}}` the coefficients of the
    /// curve along direction `a` through `x` (the net contracted with the other directions'
    /// basis functions): [`crate::BSplineCurve::eval_batch_knot_jvp`]'s formula along each
    /// direction (`docs/theory/derivatives.md`, "Knots"). `knot_tangents` has one entry a
    /// direction, the tangent of its knots (one number a knot) or `None` (zero). Only the
    /// interior knots count (the tangents of each direction's `p_a + 1` first and last knots
    /// are ignored), and at a knot of multiplicity `μ > 1` the derivative is one-sided, as for a
    /// curve. `O(m·Σ_a (p_a³ + p_a²·dim + Π_b (p_b + 1)·dim))` for the directions with a
    /// tangent.
    ///
    /// ```
    /// use lekalo::{Points, TensorBSpline};
    /// // f(x, y) = g(x)·y with g the hat of the knots [0, 0, ½, 1, 1]: g(¼) = ¼ / τ_2
    /// let k = vec![0.0, 0.0, 0.5, 1.0, 1.0];
    /// let ky = vec![0.0, 0.0, 1.0, 1.0];
    /// let net = vec![0.0, 0.0, 0.0, 1.0, 0.0, 0.0];
    /// let s = TensorBSpline::new(vec![1, 1], vec![k, ky], Points::from_flat(1, net)?)?;
    /// let (mut out, mut tan) = ([0.0], [0.0]);
    /// let dk = [0.0, 0.0, 1.0, 0.0, 0.0];
    /// s.eval_batch_knot_jvp(&[0.25, 0.5], &[Some(&dk), None], &mut out, &mut tan)?;
    /// // ∂f/∂τ_2 = −¼ / τ_2² · y = −½
    /// assert_eq!((out[0], tan[0]), (0.25, -0.5));
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`crate::Error::LengthMismatch`] for a buffer of the wrong length (`xs` not a multiple
    /// of `N`, `knot_tangents` not one a direction, a tangent not one a knot of its direction);
    /// [`crate::Error::NonFinite`] for a non-finite tangent;
    /// [`crate::Error::ParameterOutOfDomain`] at the first point outside the domain.
    pub fn eval_batch_knot_jvp(
        &self,
        xs: &[f64],
        knot_tangents: &[Option<&[f64]>],
        out: &mut [f64],
        tangent_out: &mut [f64],
    ) -> Result<()> {
        let len = self.points_in(xs)?.saturating_mul(self.dim());
        check_len("output buffer (points × dimension)", len, out.len())?;
        check_len(
            "tangent output buffer (points × dimension)",
            len,
            tangent_out.len(),
        )?;
        check_len(
            "knot tangents (one a direction)",
            self.n_vars(),
            knot_tangents.len(),
        )?;
        for (kv, &tangent) in self.knots().iter().zip(knot_tangents) {
            check_input(
                "knot tangent (one a knot of its direction)",
                kv.len(),
                tangent,
            )?;
        }
        self.eval_batch(xs, None, out)?;
        let knots: Vec<&[f64]> = self.knots().iter().map(|k| k.as_slice()).collect();
        let net = self.knot_net(&knots);
        net.knot_jvp(xs, knot_tangents, tangent_out)
    }

    /// Reverse-mode derivative (VJP) of [`TensorBSpline::eval_batch`] with respect to the
    /// knots: for a cotangent `ḡ` of the values (`m × dim`), `τ̄ᵃ_k = Σ_r ḡ_r · ∂S(x_r)/∂τᵃ_k`
    /// into `knot_cotangents[a]` (one entry a direction, a buffer of one number a knot of that
    /// direction, overwritten, or `None`), with the derivatives of
    /// [`TensorBSpline::eval_batch_knot_jvp`], whose transpose this is
    /// (`docs/theory/derivatives.md`, "Knots"). Each direction's `p_a + 1` first and last knots
    /// get zero. `O(m·Σ_a (p_a³ + p_a²·dim + Π_b (p_b + 1)·dim))` for the directions asked.
    ///
    /// # Errors
    /// [`crate::Error::LengthMismatch`] for a buffer of the wrong length;
    /// [`crate::Error::NonFinite`] for a non-finite cotangent;
    /// [`crate::Error::ParameterOutOfDomain`] at the first point outside the domain.
    pub fn eval_batch_knot_vjp(
        &self,
        xs: &[f64],
        cotangent: &[f64],
        knot_cotangents: &mut [Option<&mut [f64]>],
    ) -> Result<()> {
        let m = self.points_in(xs)?;
        check_cotangent("cotangent (points × dimension)", m, self.dim(), cotangent)?;
        check_len(
            "knot cotangent buffers (one a direction)",
            self.n_vars(),
            knot_cotangents.len(),
        )?;
        for (kv, buf) in self.knots().iter().zip(knot_cotangents.iter_mut()) {
            zeroed_output(
                "knot cotangent buffer (one a knot of its direction)",
                kv.len(),
                buf.as_deref_mut(),
            )?;
        }
        let knots: Vec<&[f64]> = self.knots().iter().map(|k| k.as_slice()).collect();
        let net = self.knot_net(&knots);
        net.knot_vjp(xs, cotangent, knot_cotangents)
    }

    /// The spline's net on `knots` (its knot vectors as slices).
    fn knot_net<'a>(&'a self, knots: &'a [&'a [f64]]) -> Net<'a> {
        let net = self.control_points().as_slice();
        Net::new(self.degrees(), knots, self.shape(), net, self.dim())
    }
}
