//! What the two kernels of the control-point cotangent share (`control_cotangent.rs`,
//! `power_sums.rs`): the span of every parameter through the bucket table of the pieces
//! ([`SpanTable`], O(1) a parameter for spread-out knots, in any order, where the binary search
//! of P&T Algorithm A2.1 costs `log2 n` unpredictable branches), and the monomorphised common
//! orders and dimensions ([`common_orders`]).

use crate::curve::BSplineCurve;
use crate::error::{check_finite, Error, Result};
use crate::tensor::SpanTable;

/// `f!(W, D)` for the common orders `W = p + 1` (degree 1 to 3) and dimensions `D` (1 to 3), with
/// `W` and `D` literals so that the kernel is monomorphised; `$dynamic` otherwise.
macro_rules! common_orders {
    ($p:expr, $dim:expr, $fixed:ident, $dynamic:expr) => {
        match ($p, $dim) {
            (1, 1) => $fixed!(2, 1),
            (1, 2) => $fixed!(2, 2),
            (1, 3) => $fixed!(2, 3),
            (2, 1) => $fixed!(3, 1),
            (2, 2) => $fixed!(3, 2),
            (2, 3) => $fixed!(3, 3),
            (3, 1) => $fixed!(4, 1),
            (3, 2) => $fixed!(4, 2),
            (3, 3) => $fixed!(4, 3),
            _ => $dynamic,
        }
    };
}
pub(super) use common_orders;

/// The parameters and their cotangents, to be walked in their spans.
pub(super) struct Located<'a> {
    table: SpanTable,
    domain: (f64, f64),
    ts: &'a [f64],
    cotangent: &'a [f64],
}

impl<'a> Located<'a> {
    pub(super) fn new(curve: &BSplineCurve, ts: &'a [f64], cotangent: &'a [f64]) -> Self {
        let p = curve.degree();
        Located {
            table: SpanTable::new(curve.knots().as_slice(), p),
            domain: curve.domain(),
            ts,
            cotangent,
        }
    }

    /// `f(span, t_i, ḡ_i)` for every parameter in order (`ḡ_i` the `dim` numbers of parameter
    /// `i`; `dim` a literal in the monomorphised kernels, so the slices have a known length).
    ///
    /// # Errors
    /// [`Error::NonFinite`] if the cotangent is not finite, else
    /// [`Error::ParameterOutOfDomain`], at the first parameter outside the domain.
    #[inline(always)]
    pub(super) fn walk(&self, dim: usize, mut f: impl FnMut(usize, f64, &[f64])) -> Result<()> {
        let (min, max) = self.domain;
        for (&t, g) in self.ts.iter().zip(self.cotangent.chunks_exact(dim)) {
            if !(t >= min && t <= max) {
                check_finite("cotangent", self.cotangent)?;
                return Err(Error::ParameterOutOfDomain { t, min, max });
            }
            f(self.table.find(t), t, g);
        }
        Ok(())
    }
}
