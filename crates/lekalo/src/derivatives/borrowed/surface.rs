//! Tensor-product B-spline surface evaluation `S(u, v) = Σ_k Σ_l N_{k,p}(u) N_{l,q}(v) P_{kl}`,
//! its JVP and its VJP on borrowed knots and a borrowed control net, for a few pairs `(u, v)`:
//! only the numbers the values need are read and checked (`docs/theory/derivatives.md`,
//! "Surfaces").
//!
//! Building a [`BSplineSurface`] validates every knot and every point of the net: O(nu·nv)
//! work a call, which dominates when a handful of pairs is evaluated on a large net. Here each
//! pair `(u, v)` reads its spans' `2p + 2` knots `u_{i−p} ..= u_{i+p+1}` and `2q + 2` knots
//! `v_{j−q} ..= v_{j+q+1}` and the `(p + 1) × (q + 1)` block of the net at `(i − p, j − q)`,
//! which are the whole definition of the surface on the cell `[u_i, u_{i+1}] × [v_j, v_{j+1}]`
//! (P&T A2.2 in each direction and A3.5 read nothing else). Those numbers make the local
//! surface of the cell, a [`BSplineSurface`] of one polynomial piece a direction, built
//! (and so checked) by [`BSplineSurface::new`], and the pair is evaluated on it by the built
//! surface's own kernels ([`BSplineSurface::eval_batch`], [`BSplineSurface::eval_batch_jvp`],
//! [`BSplineSurface::eval_batch_vjp`]): the same basis functions from the same knots, the same
//! sums in the same order, so the values, JVP and VJP are bit for bit the whole surface's.
//! The net's tangent is read on the block; the net's cotangent is the local one summed into the
//! block. A failed check gives the error [`BSplineSurface::new`] gives for the whole input
//! (built then, on the error path only), or [`Error::ParameterOutOfDomain`] for a pair outside
//! the domain of a valid surface.

use super::{add_block, gather_block, invalid_span, locate_span};
use crate::derivatives::checks::{
    check_cotangent, check_input, check_len, check_output, zeroed_output,
};
use crate::error::{Error, Result};
use crate::points::Points;
use crate::surface::BSplineSurface;

/// A B-spline surface of degrees `(p, q)` on borrowed knot vectors (`nu + p + 1` and
/// `nv + q + 1`) and a point-major net (`nu × nv × dim`, point `(k, l)` at `(k·nv + l)·dim`),
/// checked only where read (module docs).
///
/// ```
/// use lekalo::derivatives::BorrowedSurface;
/// use lekalo::{BSplineSurface, Points};
/// let (ku, kv) = ([0.0, 0.0, 0.0, 1.0, 2.0, 2.0, 2.0], [0.0, 0.0, 1.0, 1.0]);
/// let net: Vec<f64> = (0..8).map(|i| f64::from(i) * 0.5).collect();
/// let view = BorrowedSurface::new((2, 1), (&ku, &kv), &net, (4, 2), 1)?;
/// let s = BSplineSurface::new(2, 1, ku.to_vec(), kv.to_vec(), Points::from_flat(1, net.clone())?, (4, 2))?;
/// let (mut a, mut b) = ([0.0; 2], [0.0; 2]);
/// view.eval_batch(&[[0.5, 0.25], [1.75, 1.0]], &mut a)?;
/// s.eval_batch(&[[0.5, 0.25], [1.75, 1.0]], &mut b)?;
/// assert_eq!(a, b);
/// # Ok::<(), lekalo::Error>(())
/// ```
#[derive(Debug, Clone, Copy)]
pub struct BorrowedSurface<'a> {
    degrees: (usize, usize),
    knots: (&'a [f64], &'a [f64]),
    control: &'a [f64],
    net_size: (usize, usize),
    dim: usize,
}

/// The local surface of one pair's cell and the corner `(i − p, j − q)` of its block.
struct Cell {
    surface: BSplineSurface,
    first: [usize; 2],
}

impl<'a> BorrowedSurface<'a> {
    /// The surface of `degrees = (p, q)` on `knots = (knots_u, knots_v)` and the net `control`
    /// of `net_size = (nu, nv)` points of `dim` numbers, after the O(1) checks of the counts:
    /// `dim ≥ 1`, `nu·nv·dim` numbers, `nu ≥ p + 1`, `nv ≥ q + 1`, `nu + p + 1` and
    /// `nv + q + 1` knots.
    ///
    /// # Errors
    /// When a count is wrong, the error [`BSplineSurface::new`] gives for the same input
    /// ([`Error::Dimension`], [`Error::TooFew`], [`Error::LengthMismatch`], [`Error::Degree`]).
    pub fn new(
        degrees: (usize, usize),
        knots: (&'a [f64], &'a [f64]),
        control: &'a [f64],
        net_size: (usize, usize),
        dim: usize,
    ) -> Result<Self> {
        let s = BorrowedSurface {
            degrees,
            knots,
            control,
            net_size,
            dim,
        };
        let ((p, q), (nu, nv)) = (degrees, net_size);
        // the product first: with it, nu and nv are at most the slice's length (no overflow)
        let counts = dim > 0
            && nu.checked_mul(nv).and_then(|x| x.checked_mul(dim)) == Some(control.len())
            && nu > p
            && nv > q
            && knots.0.len() == nu + p + 1
            && knots.1.len() == nv + q + 1;
        if counts {
            Ok(s)
        } else {
            Err(s.explain(Error::LengthMismatch {
                what: "control net (rows × columns × dimension)".into(),
                expected: nu.saturating_mul(nv).saturating_mul(dim),
                got: control.len(),
            }))
        }
    }

    /// The error of [`BSplineSurface::new`] on the whole input if it has one, else `local`.
    fn explain(&self, local: Error) -> Error {
        let ((p, q), (ku, kv)) = (self.degrees, self.knots);
        let built = Points::from_flat(self.dim, self.control.to_vec())
            .and_then(|c| BSplineSurface::new(p, q, ku.to_vec(), kv.to_vec(), c, self.net_size));
        built.err().unwrap_or(local)
    }

    /// The numbers of the net between consecutive rows and columns.
    fn strides(&self) -> [usize; 2] {
        [self.net_size.1 * self.dim, self.dim]
    }

    /// The local surface of the cell of `(u, v)` (module docs), after locating both spans and
    /// checking the knots and net points they read.
    fn cell(&self, [u, v]: [f64; 2]) -> Result<Cell> {
        let ((p, q), (ku, kv), (nu, nv)) = (self.degrees, self.knots, self.net_size);
        let i = locate_span(ku, p, nu, u).map_err(|e| self.explain(e))?;
        let j = locate_span(kv, q, nv, v).map_err(|e| self.explain(e))?;
        let first = [i - p, j - q];
        let block = gather_block(
            self.control,
            self.dim,
            &first,
            &[p + 1, q + 1],
            &self.strides(),
        );
        let (wu, wv) = (&ku[i - p..=i + p + 1], &kv[j - q..=j + q + 1]);
        let surface = Points::from_flat(self.dim, block)
            .and_then(|c| BSplineSurface::new(p, q, wu.to_vec(), wv.to_vec(), c, (p + 1, q + 1)))
            .map_err(|_| self.explain(invalid_span(u)))?;
        Ok(Cell { surface, first })
    }

    /// `S(u_i, v_i)` into `out` (`uv.len() × dim`, point-major), as
    /// [`BSplineSurface::eval_batch`]. O(m·(log nu + log nv + p² + q² + p·q·dim)).
    ///
    /// # Errors
    /// [`Error::LengthMismatch`] for `out`; the errors of the module docs.
    pub fn eval_batch(&self, uv: &[[f64; 2]], out: &mut [f64]) -> Result<()> {
        let dim = self.dim;
        check_len(
            "output buffer (parameter pairs × dimension)",
            uv.len().saturating_mul(dim),
            out.len(),
        )?;
        for (&pair, o) in uv.iter().zip(out.chunks_exact_mut(dim)) {
            self.cell(pair)?.surface.eval_batch(&[pair], o)?;
        }
        Ok(())
    }

    /// The tangent of [`BSplineSurface::eval_batch_jvp`] into `tangent_out` (`None` tangents
    /// are zero): `Ṡ_i = Σ_k Σ_l N_{k,p}(u_i) N_{l,q}(v_i) Ṗ_{kl} + S_u u̇_i + S_v v̇_i`.
    ///
    /// # Errors
    /// [`Error::LengthMismatch`] for a buffer of the wrong length, [`Error::NonFinite`] for a
    /// non-finite tangent; the errors of the module docs.
    pub fn eval_batch_jvp(
        &self,
        uv: &[[f64; 2]],
        control_tangent: Option<&[f64]>,
        parameter_tangent: Option<&[[f64; 2]]>,
        tangent_out: &mut [f64],
    ) -> Result<()> {
        let ((p, q), dim) = (self.degrees, self.dim);
        check_len(
            "tangent output buffer (parameter pairs × dimension)",
            uv.len().saturating_mul(dim),
            tangent_out.len(),
        )?;
        check_input(
            "control-net tangent (as the control net)",
            self.control.len(),
            control_tangent,
        )?;
        if let Some(dt) = parameter_tangent {
            check_input(
                "parameter tangent (one pair a point)",
                uv.len() * 2,
                Some(dt.as_flattened()),
            )?;
        }
        let mut value = vec![0.0; dim];
        for (i, (&pair, d)) in uv.iter().zip(tangent_out.chunks_exact_mut(dim)).enumerate() {
            let cell = self.cell(pair)?;
            let dp = control_tangent
                .map(|dp| gather_block(dp, dim, &cell.first, &[p + 1, q + 1], &self.strides()));
            cell.surface.eval_batch_jvp(
                &[pair],
                dp.as_deref(),
                parameter_tangent.map(|dt| &dt[i..=i]),
                &mut value,
                d,
            )?;
        }
        Ok(())
    }

    /// `P̄` and `(ū, v̄)` of [`BSplineSurface::eval_batch_vjp`] for the cotangent `ḡ`
    /// (`uv.len() × dim`), each into its buffer when given (the net's zeroed first).
    ///
    /// # Errors
    /// [`Error::LengthMismatch`] for a buffer of the wrong length, [`Error::NonFinite`] for a
    /// non-finite cotangent; the errors of the module docs (the outputs are then unspecified).
    pub fn eval_batch_vjp(
        &self,
        uv: &[[f64; 2]],
        cotangent: &[f64],
        mut control_cotangent: Option<&mut [f64]>,
        mut parameter_cotangent: Option<&mut [[f64; 2]]>,
    ) -> Result<()> {
        let ((p, q), dim) = (self.degrees, self.dim);
        check_cotangent(
            "cotangent (parameter pairs × dimension)",
            uv.len(),
            dim,
            cotangent,
        )?;
        zeroed_output(
            "control-net cotangent buffer (as the control net)",
            self.control.len(),
            control_cotangent.as_deref_mut(),
        )?;
        check_output(
            "parameter cotangent buffer (one pair a point)",
            uv.len(),
            parameter_cotangent.as_deref(),
        )?;
        let widths = [p + 1, q + 1];
        let mut local = vec![
            0.0;
            if control_cotangent.is_some() {
                (p + 1) * (q + 1) * dim
            } else {
                0
            }
        ];
        for (i, (&pair, g)) in uv.iter().zip(cotangent.chunks_exact(dim)).enumerate() {
            let cell = self.cell(pair)?;
            let wanted = control_cotangent.is_some().then_some(&mut local[..]);
            let gt = parameter_cotangent.as_deref_mut().map(|gt| &mut gt[i..=i]);
            cell.surface.eval_batch_vjp(&[pair], g, wanted, gt)?;
            if let Some(gp) = control_cotangent.as_deref_mut() {
                add_block(&local, dim, &cell.first, &widths, &self.strides(), gp);
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::super::test_nets::{knots, net};
    use super::BorrowedSurface;
    use crate::error::Error;
    use crate::oracle::proptest_config;
    use crate::points::Points;
    use crate::surface::BSplineSurface;
    use proptest::prelude::*;

    proptest! {
        #![proptest_config(proptest_config(96))]

        /// Values, JVP and VJP are bit-for-bit the built surface's, at any pairs of the
        /// domain, knots and ends included, for knots with repeated interior values.
        #[test]
        fn matches_the_built_surface(
            (p, q) in (0usize..4, 0usize..4),
            (eu, ev) in (1usize..7, 1usize..7),
            dim in 1usize..4,
            gaps in prop::collection::vec(prop_oneof![Just(0.0), 0.1f64..2.0], 1..5),
            fractions in prop::collection::vec((0.0f64..=1.0, 0.0f64..=1.0), 1..5),
            seed in -3.0f64..3.0,
        ) {
            let (nu, nv) = (p + eu, q + ev);
            let (ku, kv) = (knots(p, nu, &gaps), knots(q, nv, &gaps));
            let ctrl = net(nu * nv * dim, seed);
            let s = BSplineSurface::new(
                p, q, ku.clone(), kv.clone(), Points::from_flat(dim, ctrl.clone()).unwrap(), (nu, nv),
            ).unwrap();
            let view = BorrowedSurface::new((p, q), (&ku, &kv), &ctrl, (nu, nv), dim).unwrap();
            let ((u0, u1), (v0, v1)) = ((ku[p], ku[nu]), (kv[q], kv[nv]));
            let mut uv: Vec<[f64; 2]> = fractions.iter()
                .map(|(a, b)| [u0 + a * (u1 - u0), v0 + b * (v1 - v0)]).collect();
            uv.extend([[u0, v1], [u1, v0], [ku[(p + nu) / 2], kv[(q + nv) / 2]]]);
            let m = uv.len();
            let (mut a, mut b) = (vec![0.0; m * dim], vec![0.0; m * dim]);
            view.eval_batch(&uv, &mut a).unwrap();
            s.eval_batch(&uv, &mut b).unwrap();
            prop_assert_eq!(&a, &b);
            let dc: Vec<f64> = ctrl.iter().map(|x| x.cos()).collect();
            let duv: Vec<[f64; 2]> = uv.iter().map(|[u, v]| [1.0 + u, 0.5 - v]).collect();
            let (mut ta, mut tb) = (vec![0.0; m * dim], vec![0.0; m * dim]);
            view.eval_batch_jvp(&uv, Some(&dc), Some(&duv), &mut ta).unwrap();
            s.eval_batch_jvp(&uv, Some(&dc), Some(&duv), &mut b, &mut tb).unwrap();
            prop_assert_eq!(&ta, &tb);
            view.eval_batch_jvp(&uv, None, Some(&duv), &mut ta).unwrap();
            s.eval_batch_jvp(&uv, None, Some(&duv), &mut b, &mut tb).unwrap();
            prop_assert_eq!(&ta, &tb);
            let g: Vec<f64> = ta.iter().map(|x| x.sin() - 0.25).collect();
            let (mut ca, mut cb) = (vec![1.0; ctrl.len()], vec![2.0; ctrl.len()]);
            let (mut pa, mut pb) = (vec![[0.0; 2]; m], vec![[1.0; 2]; m]);
            view.eval_batch_vjp(&uv, &g, Some(&mut ca), Some(&mut pa)).unwrap();
            s.eval_batch_vjp(&uv, &g, Some(&mut cb), Some(&mut pb)).unwrap();
            prop_assert_eq!(&ca, &cb);
            prop_assert_eq!(&pa, &pb);
        }
    }

    /// Every bad input gives the built surface's error (or the domain error), never a value.
    #[test]
    fn bad_input_gives_the_surface_error() {
        let (ku, kv) = (knots(3, 10, &[1.0]), knots(2, 8, &[1.0]));
        let ctrl = net(10 * 8 * 2, 0.3);
        let built = |ku: &[f64], kv: &[f64], c: &[f64], size: (usize, usize)| {
            Points::from_flat(2, c.to_vec())
                .and_then(|c| BSplineSurface::new(3, 2, ku.to_vec(), kv.to_vec(), c, size))
                .unwrap_err()
                .to_string()
        };
        let eval = |ku: &[f64], kv: &[f64], c: &[f64], size: (usize, usize), uv: [f64; 2]| {
            let mut out = [0.0; 2];
            BorrowedSurface::new((3, 2), (ku, kv), c, size, 2)
                .and_then(|s| s.eval_batch(&[uv], &mut out))
                .map_err(|e| e.to_string())
        };
        // the pair (4.5, 2.5) reads u-knots 4..=11, v-knots 2..=7, net rows 4..=7, columns 2..=4
        let at = [4.5, 2.5];
        let mut k = ku.clone();
        k[6] = f64::NAN;
        assert_eq!(
            eval(&k, &kv, &ctrl, (10, 8), at).unwrap_err(),
            built(&k, &kv, &ctrl, (10, 8))
        );
        let mut k = kv.clone();
        k[5] = 100.0;
        assert_eq!(
            eval(&ku, &k, &ctrl, (10, 8), at).unwrap_err(),
            built(&ku, &k, &ctrl, (10, 8))
        );
        let mut c = ctrl.clone();
        c[(5 * 8 + 3) * 2 + 1] = f64::INFINITY;
        assert_eq!(
            eval(&ku, &kv, &c, (10, 8), at).unwrap_err(),
            built(&ku, &kv, &c, (10, 8))
        );
        // a bad point outside the block is not read: the value is the surface's there
        let mut far = ctrl.clone();
        far[0] = f64::NAN;
        let mut want = [0.0; 2];
        let s = BSplineSurface::new(
            3,
            2,
            ku.clone(),
            kv.clone(),
            Points::from_flat(2, ctrl.clone()).unwrap(),
            (10, 8),
        )
        .unwrap();
        s.eval_batch(&[at], &mut want).unwrap();
        let mut got = [0.0; 2];
        BorrowedSurface::new((3, 2), (&ku, &kv), &far, (10, 8), 2)
            .unwrap()
            .eval_batch(&[at], &mut got)
            .unwrap();
        assert_eq!(got, want);
        // outside the domain, NaN
        for uv in [[7.5, 1.0], [1.0, -0.5], [f64::NAN, 1.0]] {
            let e = BorrowedSurface::new((3, 2), (&ku, &kv), &ctrl, (10, 8), 2)
                .and_then(|s| s.eval_batch(&[uv], &mut [0.0; 2]))
                .unwrap_err();
            assert!(matches!(e, Error::ParameterOutOfDomain { .. }), "{e:?}");
        }
        // counts: the built surface's errors
        for (ku, kv, c, size) in [
            (&ku[1..], &kv[..], &ctrl[..], (10, 8)),
            (&ku[..], &kv[1..], &ctrl[..], (10, 8)),
            (&ku[..], &kv[..], &ctrl[2..], (10, 8)),
            (&ku[..], &kv[..], &ctrl[..], (8, 10)),
            (&ku[..4], &kv[..], &ctrl[..2 * 8 * 2], (2, 8)),
        ] {
            assert_eq!(
                eval(ku, kv, c, size, at).unwrap_err(),
                built(ku, kv, c, size)
            );
        }
    }
}
