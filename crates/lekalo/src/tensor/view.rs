//! [`TensorBSplineRef`]: a tensor-product B-spline whose degrees, knots and net are borrowed
//! (from a [`TensorBSpline`] or from a caller's arrays, validated in `O(Σ_a |T_a|)`), its sizes
//! and domain. Layout: `docs/theory/tensor.md#tensor-product-splines`.

use crate::error::{check_finite, Error, Result};
use crate::knots::{check_width, KnotVector};
use crate::tensor::spline::{check_knot_count, checked_size, TensorBSpline};
use crate::Arg;

/// A tensor-product B-spline whose degrees, knot vectors and control net are borrowed: the
/// evaluation kernels of [`TensorBSpline`] on data held elsewhere (a [`TensorBSpline`] through
/// [`TensorBSpline::view`], or arrays of a caller, validated by [`TensorBSplineRef::new`] in
/// `O(Σ_a |T_a|)` without copying the net). Same layout and same formulas as
/// [`TensorBSpline`], so the same values bit for bit.
#[derive(Debug, Clone)]
pub struct TensorBSplineRef<'a> {
    pub(super) degrees: &'a [usize],
    pub(super) knots: Vec<&'a [f64]>,
    pub(super) shape: Vec<usize>,
    pub(super) net: &'a [f64],
    pub(super) dim: usize,
}

impl TensorBSpline {
    /// The spline borrowed as a [`TensorBSplineRef`] (no copy, no check).
    #[must_use]
    pub fn view(&self) -> TensorBSplineRef<'_> {
        TensorBSplineRef {
            degrees: &self.degrees,
            knots: self.knots.iter().map(KnotVector::as_slice).collect(),
            shape: self.shape.clone(),
            net: self.control.as_slice(),
            dim: self.control.dim(),
        }
    }
}

impl<'a> TensorBSplineRef<'a> {
    /// A borrowed spline of `degrees`, knot vectors `knots` and the flat net `net` (`dim`
    /// numbers a control point, first direction slowest), with the checks of
    /// [`TensorBSpline::new`] and [`KnotVector::new`] on the knots (`O(Σ_a |T_a|)`; the net is
    /// only measured).
    ///
    /// ```
    /// use lekalo::{Points, TensorBSpline, TensorBSplineRef};
    /// let k = [0.0, 0.0, 1.0, 1.0];
    /// let net = [0.0, 1.0, 2.0, 3.0];
    /// let view = TensorBSplineRef::new(&[1, 1], vec![&k, &k], &net, 1)?;
    /// let owned = TensorBSpline::new(vec![1, 1], vec![k.to_vec(), k.to_vec()], Points::from_flat(1, net.to_vec())?)?;
    /// assert_eq!(view.eval(&[0.25, 0.5])?, owned.eval(&[0.25, 0.5])?);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// As [`TensorBSpline::new`]; [`Error::InvalidArgument`] for `dim = 0`.
    pub fn new(
        degrees: &'a [usize],
        knots: Vec<&'a [f64]>,
        net: &'a [f64],
        dim: usize,
    ) -> Result<Self> {
        check_knot_count(degrees.len(), knots.len())?;
        if dim == 0 {
            return Err(Error::InvalidArgument {
                what: "dim".into(),
                reason: "a control point needs at least one number".into(),
            });
        }
        let mut shape = Vec::with_capacity(degrees.len());
        for (&t, &p) in knots.iter().zip(degrees) {
            let n = check_knots(t, p)?;
            shape.push(n);
        }
        let size = checked_size("control net (product of the net sizes)", &shape, dim)?;
        if net.len() != size {
            return Err(Error::LengthMismatch {
                what: "control net numbers (product of the net sizes knots[a].len() − degrees[a] − 1, times dim)".into(),
                expected: size,
                got: net.len(),
            });
        }
        Ok(TensorBSplineRef {
            degrees,
            knots,
            shape,
            net,
            dim,
        })
    }

    /// Number of parameter directions `N`.
    #[must_use]
    pub fn n_vars(&self) -> usize {
        self.degrees.len()
    }

    /// Dimension of the values.
    #[must_use]
    pub fn dim(&self) -> usize {
        self.dim
    }

    /// Degrees `p_a`, one per direction.
    #[must_use]
    pub fn degrees(&self) -> &[usize] {
        self.degrees
    }

    /// Net size `n_a` in each direction.
    #[must_use]
    pub fn shape(&self) -> &[usize] {
        &self.shape
    }

    /// Domain `[t_{p_a}, t_{n_a}]` of each direction.
    #[must_use]
    pub fn domain(&self) -> Vec<(f64, f64)> {
        self.knots
            .iter()
            .zip(self.degrees)
            .map(|(k, &p)| (k[p], k[k.len() - p - 1]))
            .collect()
    }

    /// Offset between consecutive indices of direction `a` in the flat net, in numbers.
    pub(crate) fn stride(&self, a: usize) -> usize {
        self.shape[a + 1..].iter().product::<usize>() * self.dim
    }
}

/// The checks of [`KnotVector::new`] and [`KnotVector::validate_for`] on a borrowed knot vector
/// of a direction of degree `p`; its number of control points `n = |T| − p − 1`.
fn check_knots(t: &[f64], p: usize) -> Result<usize> {
    if t.len() < 2 {
        return Err(Error::TooFew {
            what: Arg::Knots.into(),
            min: 2,
            got: t.len(),
        });
    }
    check_finite(Arg::Knots, t)?;
    for i in 1..t.len() {
        if t[i] < t[i - 1] {
            return Err(Error::KnotsNotSorted {
                index: i,
                value: t[i],
                previous: t[i - 1],
            });
        }
    }
    let (first, last) = (t[0], t[t.len() - 1]);
    if first >= last {
        return Err(Error::EmptyDomain {
            min: first,
            max: last,
        });
    }
    check_width(Arg::Knots, first, last)?;
    if t.len() / 2 <= p {
        return Err(Error::Degree {
            degree: p,
            reason: format!(
                "{} knots carry a degree of at most {}",
                t.len(),
                (t.len() / 2).saturating_sub(1)
            ),
        });
    }
    let max = p + 1;
    let mut run = 1;
    for i in 1..t.len() {
        run = if t[i] == t[i - 1] { run + 1 } else { 1 };
        if run > max {
            return Err(Error::KnotMultiplicity {
                knot: t[i],
                multiplicity: t[i..].iter().take_while(|&&v| v == t[i]).count() + run - 1,
                max,
            });
        }
    }
    let (min, max) = (t[p], t[t.len() - p - 1]);
    if min >= max {
        return Err(Error::EmptyDomain { min, max });
    }
    Ok(t.len() - p - 1)
}
