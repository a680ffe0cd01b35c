//! The integral of a tensor-product spline over a box: the integrals of each direction's basis
//! functions, contracted with the control net. `docs/theory/tensor.md#integrals-over-boxes`.

use crate::basis::{basis_funs_into, BasisScratch};
use crate::error::{Error, Result};
use crate::knots::KnotVector;
use crate::tensor::spline::{check_len, TensorBSpline};

impl TensorBSpline {
    /// `∫_{a_0}^{b_0} ⋯ ∫_{a_{N−1}}^{b_{N−1}} S(x) dx` (one number per coordinate of the values)
    /// for limits `bounds[a] = (a_a, b_a)` in the domain of each direction; `a_a > b_a` changes
    /// the sign, as for [`BSplineCurve::integral`](crate::BSplineCurve::integral).
    ///
    /// The integral is `Σ_i c_i Π_a w_{a,i_a}` with `w_{a,i} = ∫_{a_a}^{b_a} N_{i,p_a}`. Each
    /// weight is a difference of values of the antiderivative of the basis function,
    /// `∫_{t_0}^x N_{i,p} = (t_{i+p+1} − t_i)/(p + 1)·Σ_{j>i} Ñ_{j,p+1}(x)` with `Ñ` the
    /// B-splines of degree `p + 1` on the knots with each end knot once more (de Boor, *A
    /// Practical Guide to Splines*, ch. X, eq. (31); FITPACK `fpintb`/`dblint`), and the net is
    /// contracted one direction at a time, the last first. Cost `O(Σ_a n_a·p_a + Π_a n_a·dim)`.
    ///
    /// ```
    /// use lekalo::{Points, TensorBSpline};
    /// // f(x, y) = x·y on [0, 1]² (bilinear): ∫_0^1 ∫_0^0.5 x·y dy dx = 1/2 · 1/8
    /// let k = vec![0.0, 0.0, 1.0, 1.0];
    /// let s = TensorBSpline::new(vec![1, 1], vec![k.clone(), k], Points::from_flat(1, vec![0.0, 0.0, 0.0, 1.0])?)?;
    /// assert!((s.integral(&[(0.0, 1.0), (0.0, 0.5)])?[0] - 0.0625).abs() < 1e-15);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::LengthMismatch`] if `bounds` has not one interval per direction;
    /// [`Error::ParameterOutOfDomain`] for a limit outside its direction's domain (or NaN).
    pub fn integral(&self, bounds: &[(f64, f64)]) -> Result<Vec<f64>> {
        let n = self.n_vars();
        check_len(
            "integration limits (one interval per direction)",
            n,
            bounds.len(),
        )?;
        let weights: Vec<Vec<f64>> = self
            .knots()
            .iter()
            .zip(self.degrees())
            .zip(bounds)
            .map(|((kv, &p), &(a, b))| basis_integrals(kv, p, a, b))
            .collect::<Result<_>>()?;
        let dim = self.dim();
        let mut cur = self.control_points().as_slice().to_vec();
        for w in weights.iter().rev() {
            let block = w.len() * dim;
            cur = cur
                .chunks_exact(block)
                .flat_map(|line| {
                    (0..dim).map(move |d| {
                        w.iter()
                            .enumerate()
                            .map(|(i, wi)| wi * line[i * dim + d])
                            .sum::<f64>()
                    })
                })
                .collect();
        }
        Ok(cur)
    }
}

/// `∫_a^b N_{i,p}` for every basis function of `kv`, `a` and `b` in the domain.
fn basis_integrals(kv: &KnotVector, p: usize, a: f64, b: f64) -> Result<Vec<f64>> {
    let (lo, hi) = kv.domain(p);
    for t in [a, b] {
        if !(t >= lo && t <= hi) {
            return Err(Error::ParameterOutOfDomain {
                t,
                min: lo,
                max: hi,
            });
        }
    }
    let t = kv.as_slice();
    let n = t.len() - p - 1;
    let mut ext = Vec::with_capacity(t.len() + 2);
    ext.push(t[0]);
    ext.extend_from_slice(t);
    ext.push(t[t.len() - 1]);
    let ext = KnotVector::new(ext)?;
    let q = p + 1;
    let mut scratch = BasisScratch::new(q);
    let mut values = vec![0.0; q + 1];
    // Σ_{j>i} Ñ_j(x) for every i: 1 before the non-zero window, partial sums in it, 0 after
    let mut tails = |x: f64| -> Result<Vec<f64>> {
        let span = ext.find_span(q, x)?;
        basis_funs_into(ext.as_slice(), q, span, x, &mut scratch, &mut values);
        let first = span - q;
        let mut out = vec![0.0; n];
        for (i, o) in out.iter_mut().enumerate() {
            *o = if i < first {
                1.0
            } else if i >= span {
                0.0
            } else {
                values[i + 1 - first..].iter().sum()
            };
        }
        Ok(out)
    };
    let (fa, fb) = (tails(a)?, tails(b)?);
    Ok((0..n)
        .map(|i| (t[i + p + 1] - t[i]) / q as f64 * (fb[i] - fa[i]))
        .collect())
}

#[cfg(test)]
mod tests {
    use crate::{BSplineCurve, Points, TensorBSpline};

    /// Each direction's integral agrees with the curve integral of a slice of the net, and a
    /// product of 1-D splines integrates to the product of their integrals.
    #[test]
    fn products_integrate_to_products_of_curve_integrals() {
        let tx = vec![0.0, 0.0, 0.0, 0.3, 0.7, 1.0, 1.0, 1.0];
        let ty = vec![-1.0, -1.0, -1.0, -1.0, 0.5, 2.0, 2.0, 2.0, 2.0];
        let cx = [1.0, -2.0, 0.5, 3.0, 0.25];
        let cy = [0.3, 1.1, -0.7, 2.0, 0.9];
        let fx =
            BSplineCurve::new(2, tx.clone(), Points::from_flat(1, cx.to_vec()).unwrap()).unwrap();
        let fy =
            BSplineCurve::new(3, ty.clone(), Points::from_flat(1, cy.to_vec()).unwrap()).unwrap();
        let net: Vec<f64> = cx
            .iter()
            .flat_map(|a| cy.iter().map(move |b| a * b))
            .collect();
        let s = TensorBSpline::new(vec![2, 3], vec![tx, ty], Points::from_flat(1, net).unwrap())
            .unwrap();
        for &((a, b), (c, d)) in &[
            ((0.0, 1.0), (-1.0, 2.0)),
            ((0.1, 0.65), (0.2, -0.4)),
            ((0.7, 0.7), (0.0, 1.0)),
        ] {
            let want = fx.integral(a, b).unwrap()[0] * fy.integral(c, d).unwrap()[0];
            let got = s.integral(&[(a, b), (c, d)]).unwrap()[0];
            assert!(
                (got - want).abs() <= 1e-14 * (1.0 + want.abs()),
                "{got} vs {want}"
            );
        }
        assert!(s.integral(&[(0.0, 1.5), (0.0, 1.0)]).is_err());
        assert!(s.integral(&[(0.0, 1.0)]).is_err());
    }
}
