//! Operations along one direction of a [`TensorBSpline`]: knot insertion, slicing (fixing
//! parameters), and conversion to and from [`BSplineCurve`] (`N = 1`) and [`BSplineSurface`]
//! (`N = 2`). `docs/theory/tensor.md#operations-along-one-direction`.
//!
//! An operation along direction `a` sees the net as `outer × n_a × inner` with
//! `outer = Π_{b<a} n_b` and `inner = Π_{b>a} n_b·dim`: each of the `outer` blocks is the control
//! polygon of one curve of degree `p_a` on `T_a` whose points have `inner` coordinates, so every
//! curve operation applies block by block (P&T §5.3 for surfaces).

use crate::curve::bspline::BSplineCurve;
use crate::error::{Error, NthDirection, Result};
use crate::knots::KnotVector;
use crate::points::Points;
use crate::surface::bspline::BSplineSurface;
use crate::tensor::contract::{accumulate, basis_vector};
use crate::tensor::spline::{check_len, TensorBSpline};

impl TensorBSpline {
    /// `(outer, n_a, inner)` of direction `a` (see the module documentation).
    fn blocks(&self, a: usize) -> (usize, usize, usize) {
        let outer = self.shape[..a].iter().product();
        (outer, self.shape[a], self.stride(a))
    }

    /// Checks a direction index.
    fn check_axis(&self, a: usize) -> Result<()> {
        if a >= self.n_vars() {
            return Err(Error::InvalidArgument {
                what: "direction (axis)".into(),
                reason: format!(
                    "there is no {}: the spline has {} (axes 0 to {} in Python)",
                    NthDirection(a),
                    self.n_vars(),
                    self.n_vars() - 1
                ),
            });
        }
        Ok(())
    }

    /// Inserts the knot `t` `times` times into direction `axis` (Boehm's algorithm, P&T
    /// Algorithm A5.1 / A5.3 for surfaces): the same spline with `times` more control points in
    /// that direction. Each of the `outer` blocks of the net (module documentation) is one
    /// [`BSplineCurve::insert_knot`]. O(`Π_a n_a·dim·times·p_axis`).
    ///
    /// ```
    /// use lekalo::{Points, TensorBSpline};
    /// let net = Points::from_flat(1, (0..12).map(f64::from).collect())?;
    /// let k = |n: usize| -> Vec<f64> {
    ///     let mut v = vec![0.0; 3];
    ///     v.extend((1..n - 2).map(|i| i as f64 / (n - 2) as f64));
    ///     v.extend([1.0; 3]);
    ///     v
    /// };
    /// let s = TensorBSpline::new(vec![2, 2], vec![k(3), k(4)], net)?;
    /// let r = s.insert_knot(1, 0.3, 2)?;
    /// assert_eq!(r.shape(), &[3, 6]);
    /// let (a, b) = (s.eval(&[0.4, 0.7])?, r.eval(&[0.4, 0.7])?);
    /// assert!((a[0] - b[0]).abs() < 1e-14);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for a direction that does not exist, and the errors of
    /// [`BSplineCurve::insert_knot`] ([`Error::ParameterOutOfDomain`], [`Error::InvalidArgument`]
    /// when the multiplicity would exceed the degree); [`Error::TooLarge`] if the new net would
    /// exceed [`MAX_SCALARS`](crate::MAX_SCALARS).
    pub fn insert_knot(&self, axis: usize, t: f64, times: usize) -> Result<TensorBSpline> {
        self.check_axis(axis)?;
        let p = self.degrees[axis];
        let (outer, n, inner) = self.blocks(axis);
        let net = self.control.as_slice();
        let mut shape = self.shape.clone();
        shape[axis] = n.saturating_add(times);
        crate::tensor::spline::checked_size(
            "control net after knot insertion",
            &shape,
            self.dim(),
        )?;
        let mut control = Vec::with_capacity(outer * shape[axis] * inner);
        let mut knots = None;
        for o in 0..outer {
            let block = net[o * n * inner..(o + 1) * n * inner].to_vec();
            let curve = BSplineCurve::from_raw(
                p,
                self.knots[axis].as_slice().to_vec(),
                Points::from_raw(block, inner),
            );
            let (_, kv, pts) = curve.insert_knot(t, times)?.into_parts();
            control.extend_from_slice(pts.as_slice());
            knots = Some(kv);
        }
        let mut all = self.knots.clone();
        if let Some(kv) = knots {
            all[axis] = kv;
        }
        Ok(TensorBSpline::from_raw(
            self.degrees.clone(),
            all,
            Points::from_raw(control, self.dim()),
        ))
    }

    /// The partial-derivative spline `∂^{|k|} S / ∂x_0^{k_0} ⋯ ∂x_{N−1}^{k_{N−1}}` as a tensor
    /// product of degrees `p_a − k_a`: along each direction with `k_a > 0`, every block of the
    /// net (module documentation) is differentiated `k_a` times as one curve
    /// ([`BSplineCurve::derivative`], P&T §3.3: `Q_i = p (P_{i+1} − P_i)/(t_{i+p+1} − t_{i+1})`
    /// on the knots without their first and last); a tensor product differentiates direction
    /// by direction (P&T §3.4). Its values are those of [`TensorBSpline::eval_partial`] (right-hand
    /// derivatives at interior knots). SciPy's `NdBSpline.derivative(nu)`.
    ///
    /// ```
    /// use lekalo::{Points, TensorBSpline};
    /// // f(x, y) = x² + y on [0, 1]²: ∂f/∂x = 2x, of degrees (1, 1)
    /// let net = Points::from_flat(1, vec![0.0, 1.0, 0.0, 1.0, 1.0, 2.0])?;
    /// let s = TensorBSpline::new(
    ///     vec![2, 1],
    ///     vec![vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0], vec![0.0, 0.0, 1.0, 1.0]],
    ///     net,
    /// )?;
    /// let d = s.derivative(&[1, 0])?;
    /// assert_eq!(d.degrees(), &[1, 1]);
    /// assert!((d.eval(&[0.3, 0.8])?[0] - 0.6).abs() < 1e-15);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// An order above its direction's degree gives the zero spline of degree 0 on the distinct
    /// knots of that direction's domain (SciPy keeps every knot; lekalo's degree-0 splines take
    /// each knot once).
    ///
    /// # Errors
    /// [`Error::LengthMismatch`] if `orders.len() != N`; [`Error::NonFinite`] if a control
    /// point overflows.
    pub fn derivative(&self, orders: &[usize]) -> Result<TensorBSpline> {
        check_len(
            "derivative orders (one per direction)",
            self.n_vars(),
            orders.len(),
        )?;
        let mut degrees = self.degrees.clone();
        let mut knots = self.knots.clone();
        let mut shape = self.shape.clone();
        let mut net = self.control.as_slice().to_vec();
        let dim = self.dim();
        for (a, &k) in orders.iter().enumerate() {
            if k > degrees[a] {
                // the derivative is zero: degree 0 on the distinct knots of the domain
                let p = degrees[a];
                let t = knots[a].as_slice();
                let n = shape[a];
                let mut breaks: Vec<f64> = t[p..=n].to_vec();
                breaks.dedup();
                let outer: usize = shape[..a].iter().product();
                let inner = shape[a + 1..].iter().product::<usize>() * dim;
                shape[a] = breaks.len() - 1;
                net = vec![0.0; outer * shape[a] * inner];
                knots[a] = KnotVector::new(breaks)?;
                degrees[a] = 0;
                continue;
            }
            for _ in 0..k {
                let outer: usize = shape[..a].iter().product();
                let inner = shape[a + 1..].iter().product::<usize>() * dim;
                let n = shape[a];
                let mut next = Vec::with_capacity(net.len());
                let mut kv = None;
                for block in net.chunks_exact(n * inner).take(outer) {
                    let curve = BSplineCurve::from_raw(
                        degrees[a],
                        knots[a].as_slice().to_vec(),
                        Points::from_raw(block.to_vec(), inner),
                    );
                    let (_, t, pts) = curve.derivative()?.into_parts();
                    next.extend_from_slice(pts.as_slice());
                    kv = Some(t);
                }
                degrees[a] -= 1;
                if let Some(t) = kv {
                    shape[a] = t.len() - degrees[a] - 1;
                    knots[a] = t;
                }
                net = next;
            }
        }
        Ok(TensorBSpline::from_raw(
            degrees,
            knots,
            Points::from_raw(net, dim),
        ))
    }

    /// The spline in the remaining parameters when the parameters `fixed[a] = Some(t_a)` are
    /// held: `S|_{x_a = t_a}`, a tensor-product spline in `N − k` parameters (`k` fixed), whose
    /// net is the contraction of the fixed directions with their basis vectors,
    /// `Q_{…} = Σ_j N_{j,p_a}(t_a)·P_{…j…}` direction by direction (the last fixed direction
    /// first). Slicing a surface at `v` gives its iso-curve. O(`Π_a n_a·dim·(p + 1)`) for the
    /// first contraction, less for the next.
    ///
    /// ```
    /// use lekalo::{Points, TensorBSpline};
    /// let mut net = Vec::new();
    /// for i in 0..2 { for j in 0..2 { for k in 0..2 { net.push(f64::from(i + 2 * j + 3 * k)); } } }
    /// let k = vec![0.0, 0.0, 1.0, 1.0];
    /// let s = TensorBSpline::new(vec![1, 1, 1], vec![k.clone(), k.clone(), k], Points::from_flat(1, net)?)?;
    /// let plane = s.slice(&[None, Some(0.5), None])?;
    /// assert_eq!(plane.n_vars(), 2);
    /// assert_eq!(plane.eval(&[0.25, 1.0])?[0], s.eval(&[0.25, 0.5, 1.0])?[0]);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::LengthMismatch`] if `fixed.len() != N`; [`Error::InvalidArgument`] if every
    /// parameter is fixed (use [`TensorBSpline::eval`]); [`Error::ParameterOutOfDomain`] for a
    /// fixed value outside its domain.
    pub fn slice(&self, fixed: &[Option<f64>]) -> Result<TensorBSpline> {
        check_len(
            "fixed parameters (one per direction, a value or free)",
            self.n_vars(),
            fixed.len(),
        )?;
        if fixed.iter().all(Option::is_some) {
            return Err(Error::InvalidArgument {
                what: "fixed parameters".into(),
                reason: "every parameter is fixed: leave at least one free, or use eval".into(),
            });
        }
        let mut s = self.clone();
        for a in (0..fixed.len()).rev() {
            if let Some(t) = fixed[a] {
                s = s.fix(a, t)?;
            }
        }
        Ok(s)
    }

    /// Contracts direction `a` at `t`: one direction fewer.
    fn fix(&self, a: usize, t: f64) -> Result<TensorBSpline> {
        let p = self.degrees[a];
        let kv = &self.knots[a];
        let span = kv.find_span(p, t)?;
        let mut basis = vec![0.0; p + 1];
        let mut scratch = crate::basis::BasisScratch::new(p);
        basis_vector(
            kv.as_slice(),
            p,
            span,
            t,
            0,
            &mut scratch,
            &mut [],
            &mut basis,
        );
        let (outer, n, inner) = self.blocks(a);
        let net = self.control.as_slice();
        let mut control = vec![0.0; outer * inner];
        for (o, acc) in control.chunks_exact_mut(inner).enumerate() {
            for (j, &v) in basis.iter().enumerate() {
                let at = (o * n + span - p + j) * inner;
                accumulate(acc, v, &net[at..at + inner], j == 0);
            }
        }
        let mut degrees = self.degrees.clone();
        let mut knots = self.knots.clone();
        degrees.remove(a);
        knots.remove(a);
        Ok(TensorBSpline::from_raw(
            degrees,
            knots,
            Points::from_raw(control, self.dim()),
        ))
    }

    /// The curve as a spline in one parameter: the same degree, knots and control points, bit
    /// for bit.
    #[must_use]
    pub fn from_curve(curve: &BSplineCurve) -> TensorBSpline {
        TensorBSpline::from_raw(
            vec![curve.degree()],
            vec![curve.knots().clone()],
            curve.control_points().clone(),
        )
    }

    /// The surface as a spline in two parameters, `(u, v)` = `(x_0, x_1)`: the same degrees,
    /// knots and net (`(i·nv + j)·dim` is the tensor layout), bit for bit.
    #[must_use]
    pub fn from_surface(surface: &BSplineSurface) -> TensorBSpline {
        TensorBSpline::from_raw(
            vec![surface.degree_u(), surface.degree_v()],
            vec![surface.knots_u().clone(), surface.knots_v().clone()],
            surface.control_points().clone(),
        )
    }

    /// The spline in one parameter as a [`BSplineCurve`], bit for bit.
    ///
    /// # Errors
    /// [`Error::LengthMismatch`] if `N ≠ 1`.
    pub fn to_curve(&self) -> Result<BSplineCurve> {
        check_len("parameter directions of a curve", 1, self.n_vars())?;
        Ok(BSplineCurve::from_raw(
            self.degrees[0],
            self.knots[0].as_slice().to_vec(),
            self.control.clone(),
        ))
    }

    /// The spline in two parameters as a [`BSplineSurface`], bit for bit.
    ///
    /// # Errors
    /// [`Error::LengthMismatch`] if `N ≠ 2`.
    pub fn to_surface(&self) -> Result<BSplineSurface> {
        check_len("parameter directions of a surface", 2, self.n_vars())?;
        Ok(BSplineSurface::from_raw(
            self.degrees[0],
            self.degrees[1],
            self.knots[0].clone(),
            self.knots[1].clone(),
            self.control.clone(),
        ))
    }
}

impl From<&BSplineCurve> for TensorBSpline {
    fn from(curve: &BSplineCurve) -> Self {
        TensorBSpline::from_curve(curve)
    }
}

impl From<&BSplineSurface> for TensorBSpline {
    fn from(surface: &BSplineSurface) -> Self {
        TensorBSpline::from_surface(surface)
    }
}
