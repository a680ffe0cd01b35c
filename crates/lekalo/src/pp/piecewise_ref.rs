//! A piecewise polynomial read in place from SciPy's coefficient arrays ([`PiecewiseRef`]),
//! generic over the basis of its pieces ([`PieceBasis`]): the local power basis of `PPoly`
//! ([`PowerFormRef`], `power_form.rs`) or the Bernstein basis of `BPoly` ([`BernsteinFormRef`],
//! `bernstein_form.rs`). The arrays, their checks and the batch drivers (the piece search,
//! extrapolation or NaN, the derivative order, the kernels of fixed order, the thread pool) are
//! written once here; a basis says only how the local coordinate of a piece is formed and how a
//! piece is evaluated at it. `docs/theory/pp.md#extrapolation-in-pp-form`.
//!
//! Layout (SciPy's): coefficients `c` of shape `(k, pieces, dim)`, `c[m, i, d]` at
//! `(m·pieces + i)·dim + d`, on `pieces + 1` monotonic breakpoints (either order, as SciPy
//! allows); repeated breakpoints bound empty pieces, never evaluated (`piece_search.rs`).

use std::fmt::Debug;
use std::marker::PhantomData;

use crate::curve::Beyond;
use crate::error::{check_finite, Error, Result};
use crate::pp::piece_search::PieceSearch;
#[cfg(doc)]
use crate::pp::{BernsteinFormRef, PowerFormRef};
use crate::Arg;

/// The orders up to which the values (`nu = 0`) have a kernel with the order fixed at compile
/// time (the loops over the coefficients unrolled); higher orders and derivatives take the
/// kernel of any order.
pub const FIXED_ORDER_MAX: usize = 6;

/// One piece `j` of a [`PiecewiseRef`]: its coefficients read in place and its breakpoints.
#[derive(Debug, Clone, Copy)]
pub struct Piece<'a> {
    c: &'a [f64],
    breakpoints: &'a [f64],
    order: usize,
    dim: usize,
    j: usize,
}

impl Piece<'_> {
    /// `c[m, j, d]`: coefficient `m` (`0 ≤ m < order`) of coordinate `d` of this piece.
    #[inline(always)]
    #[must_use]
    pub fn coefficient(&self, m: usize, d: usize) -> f64 {
        let pieces = self.breakpoints.len() - 1;
        self.c[(m * pieces + self.j) * self.dim + d]
    }

    /// The coefficients of this piece, `order` of them, for every coordinate.
    #[inline(always)]
    #[must_use]
    pub fn order(&self) -> usize {
        self.order
    }

    /// The breakpoint `x_j` that starts the piece (its left end, or its right end on decreasing
    /// breakpoints).
    #[inline(always)]
    #[must_use]
    pub fn start(&self) -> f64 {
        self.breakpoints[self.j]
    }

    /// `h_j = x_{j+1} − x_j` (negative on decreasing breakpoints, never 0 for a piece that is
    /// evaluated).
    #[inline(always)]
    #[must_use]
    pub fn width(&self) -> f64 {
        self.breakpoints[self.j + 1] - self.breakpoints[self.j]
    }
}

pub(super) mod sealed {
    /// Only the bases of this folder implement [`super::PieceBasis`] (each beside its
    /// definition).
    pub trait Sealed {}
}

/// What differs between the bases of a [`PiecewiseRef`]: the local coordinate `t` of a point
/// `x` in its piece and the evaluation of the piece at `t`. Implemented by
/// [`crate::pp::PowerBasis`] (`t = x − x_j`, Horner's rule) and [`crate::pp::BernsteinBasis`]
/// (`t = (x − x_j)/h_j`, the Bernstein sum or de Casteljau's algorithm); sealed.
pub trait PieceBasis: sealed::Sealed + Debug + Clone + Copy + Send + Sync {
    /// The local coordinate of the finite `x` in `piece`.
    fn local(piece: &Piece<'_>, x: f64) -> f64;

    /// The value (`nu = 0`) at `t` of one coordinate of a piece of order `K` known at compile
    /// time (`1 ≤ K ≤` [`FIXED_ORDER_MAX`]) whose coefficients are `c` (`c[m]` the
    /// coefficient of row `m` of SciPy's array). The same operations in the same order as
    /// [`PieceBasis::derivative`] with `nu = 0`, so the same bits.
    fn value<const K: usize>(c: &[f64; K], t: f64) -> f64;

    /// The values (`nu = 0`) of `piece` at `t` into `o` (`dim` numbers): [`PieceBasis::value`]
    /// on each coordinate's coefficients.
    #[inline(always)]
    fn values<const K: usize>(piece: &Piece<'_>, t: f64, o: &mut [f64]) {
        for (d, v) in o.iter_mut().enumerate() {
            *v = Self::value::<K>(&std::array::from_fn(|m| piece.coefficient(m, d)), t);
        }
    }

    /// `D^nu` (`nu < order`, with respect to `x`) of `piece` at `t` into `o` (`dim` numbers),
    /// `scratch` of [`PieceBasis::scratch_len`] numbers.
    fn derivative(piece: &Piece<'_>, t: f64, nu: usize, scratch: &mut [f64], o: &mut [f64]);

    /// The scratch [`PieceBasis::derivative`] needs for pieces of order `order`.
    fn scratch_len(order: usize) -> usize;

    /// `D^nu` (`nu < order`) of `piece` at any `x` (infinite included) into `o` (`dim`
    /// numbers) by SciPy's own formula for the basis (its `evaluate_poly1` or
    /// `evaluate_bpoly1`, the same operations in the same order), `scratch` of `order`
    /// numbers: what SciPy's values are where IEEE infinities enter, at `x = ±∞` and where a
    /// term overflows ([`PiecewiseRef::par_eval_as_scipy`]).
    fn scipy_derivative(piece: &Piece<'_>, x: f64, nu: usize, scratch: &mut [f64], o: &mut [f64]);
}

/// Borrowed coefficients of a piecewise polynomial in SciPy's layout (see the module
/// documentation), each piece in the basis `B`: on `x_j ≤ x < x_{j+1}` (`x_j ≥ x > x_{j+1}` on
/// decreasing breakpoints) `f(x) = Σ_m c[m, j]·φ_m(t)` in the local coordinate `t` of `B`.
/// [`PowerFormRef`] is SciPy's `PPoly`, [`BernsteinFormRef`] its `BPoly`.
#[derive(Debug, Clone, Copy)]
pub struct PiecewiseRef<'a, B: PieceBasis> {
    c: &'a [f64],
    order: usize,
    breakpoints: &'a [f64],
    dim: usize,
    basis: PhantomData<B>,
}

impl<'a, B: PieceBasis> PiecewiseRef<'a, B> {
    /// The piecewise polynomial of order `order` (`k` coefficients a piece) on `breakpoints`
    /// (`pieces + 1` of them, monotonic, the ends different) with the coefficients `c`
    /// (`k·pieces·dim` numbers, SciPy's layout). The order of the breakpoints is the caller's
    /// to guarantee (SciPy's constructor checks it): only their ends are checked here, so that a
    /// call costs no pass over the arrays. O(1).
    ///
    /// # Errors
    /// [`Error::TooFew`] for fewer than two breakpoints, an order or a dimension of 0;
    /// [`Error::LengthMismatch`] if `c` does not hold `k·pieces·dim` numbers;
    /// [`Error::NonFinite`] for an end breakpoint that is not finite; [`Error::EmptyDomain`]
    /// if the first and the last breakpoint are equal.
    pub fn new(c: &'a [f64], order: usize, breakpoints: &'a [f64], dim: usize) -> Result<Self> {
        if breakpoints.len() < 2 {
            return Err(Error::TooFew {
                what: Arg::Breakpoints.into(),
                min: 2,
                got: breakpoints.len(),
            });
        }
        if order == 0 || dim == 0 {
            return Err(Error::TooFew {
                what: if order == 0 {
                    "coefficients a piece (order)".into()
                } else {
                    "numbers a value (dim)".into()
                },
                min: 1,
                got: 0,
            });
        }
        let pieces = breakpoints.len() - 1;
        let want = order
            .checked_mul(pieces)
            .and_then(|v| v.checked_mul(dim))
            .unwrap_or(usize::MAX);
        if c.len() != want {
            return Err(Error::LengthMismatch {
                what: "coefficients (order × pieces × dim)".into(),
                expected: want,
                got: c.len(),
            });
        }
        let (lo, hi) = (breakpoints[0], breakpoints[pieces]);
        check_finite("breakpoints (the ends)", &[lo, hi])?;
        if lo == hi {
            return Err(Error::EmptyDomain { min: lo, max: hi });
        }
        Ok(PiecewiseRef {
            c,
            order,
            breakpoints,
            dim,
            basis: PhantomData,
        })
    }

    /// The number of pieces (empty ones included).
    #[inline(always)]
    fn pieces(&self) -> usize {
        self.breakpoints.len() - 1
    }

    /// The coefficients of each piece of a scalar piecewise polynomial (`dim = 1`) of order
    /// `K` side by side, `rows[j][m] = c[m, j]`. O(K·pieces).
    fn rows<const K: usize>(&self) -> Vec<[f64; K]> {
        debug_assert!(
            self.dim == 1 && self.order == K,
            "a scalar piece of order K"
        );
        let pieces = self.breakpoints.len() - 1;
        (0..pieces)
            .map(|j| std::array::from_fn(|m| self.c[m * pieces + j]))
            .collect()
    }

    /// Piece `j` (`j < pieces`).
    #[inline(always)]
    fn piece(&self, j: usize) -> Piece<'a> {
        self.piece_of_dim(j, self.dim)
    }

    /// Piece `j` with the dimension `dim` (`self.dim`) given where the caller knows it as a
    /// constant.
    #[inline(always)]
    fn piece_of_dim(&self, j: usize, dim: usize) -> Piece<'a> {
        debug_assert_eq!(dim, self.dim, "the dimension of the arrays");
        Piece {
            c: self.c,
            breakpoints: self.breakpoints,
            order: self.order,
            dim,
            j,
        }
    }

    /// `D^nu f` at every `x` of `xs` into `out` (`dim` numbers a point), the end pieces
    /// continued; every `x` must be finite. As [`PiecewiseRef::par_eval_beyond`] with
    /// [`Beyond::Continue`], which see.
    ///
    /// # Errors
    /// [`Error::LengthMismatch`] if `out` does not hold `dim` numbers a point;
    /// [`Error::NonFinite`] for a NaN or infinite `x`, or a value that overflows.
    pub fn par_eval_extrapolated(&self, xs: &[f64], nu: usize, out: &mut [f64]) -> Result<()> {
        check_finite("x", xs)?;
        self.par_eval_beyond(xs, nu, Beyond::Continue, out)
    }

    /// [`PiecewiseRef::par_eval_beyond`] with SciPy's values where IEEE infinities enter
    /// (`docs/theory/pp.md#infinities-as-scipy-has-them`): at `x = ±∞` with the end pieces
    /// continued, SciPy evaluates its end piece (the first or the last, empty or not) by its own
    /// formula, which gives the constant of a piece of degree 0, `±∞`, or NaN where a zero
    /// coefficient meets an infinite power; a value that overflows is SciPy's `±∞` or NaN, not
    /// an error; and where `|x − x_j|^(k−1)` overflows while Horner's rule stays finite, SciPy's
    /// NaN or `±∞`. Those points (infinite, beyond the bound where the powers overflow, or with
    /// a value that is not finite) are evaluated again by [`PieceBasis::scipy_derivative`] on
    /// SciPy's piece; every other value is [`PiecewiseRef::par_eval_beyond`]'s. One more pass
    /// over the points and values, O(points·dim).
    ///
    /// # Errors
    /// [`Error::LengthMismatch`] if `out` does not hold `dim` numbers a point.
    pub fn par_eval_as_scipy(
        &self,
        xs: &[f64],
        nu: usize,
        beyond: Beyond,
        out: &mut [f64],
    ) -> Result<()> {
        let overflowed = match self.par_eval_beyond(xs, nu, beyond, out) {
            Ok(()) => false,
            // an overflow: every value is written; SciPy's are set below
            Err(Error::NonFinite { .. }) => true,
            Err(e) => return Err(e),
        };
        let (k, dim, pieces) = (self.order, self.dim, self.pieces());
        let (first, last) = (self.breakpoints[0], self.breakpoints[pieces]);
        let (lo, hi) = (first.min(last), first.max(last));
        let continued = beyond == Beyond::Continue;
        // below this |x| no power |x − x_j|^m (m < k) of SciPy's sum overflows
        let reach = first.abs().max(last.abs());
        let bound = 0.5 * f64::MAX.powf(1.0 / (k.max(2) - 1) as f64) - reach;
        // a value that overflowed, or a point that is infinite, NaN or beyond the bound (one
        // branch-free pass over the points): only then the points are looked at one by one
        if !overflowed && xs.iter().fold(true, |ok, &x| ok & (x.abs() < bound)) {
            return Ok(());
        }
        let mut scratch = vec![0.0; k];
        for (&x, o) in xs.iter().zip(out.chunks_exact_mut(dim)) {
            let usual = x.abs() < bound && o.iter().all(|v| v.is_finite());
            let defined = (lo <= x && x <= hi) || (continued && !x.is_nan());
            if usual || !defined {
                continue;
            }
            if nu >= k {
                o.fill(0.0);
                continue;
            }
            let piece = self.piece(self.scipy_piece(x));
            B::scipy_derivative(&piece, x, nu, &mut scratch, o);
        }
        Ok(())
    }

    /// SciPy's piece of a point that is not NaN (`find_interval_ascending` and
    /// `_descending`): beyond the ends the first or the last piece, empty or not; inside the
    /// piece `x_j ≤ x < x_{j+1}` (`x_j ≥ x > x_{j+1}` decreasing), the last one at the far end.
    fn scipy_piece(&self, x: f64) -> usize {
        let pieces = self.pieces();
        let b = self.breakpoints;
        let increasing = b[pieces] > b[0];
        let j = if increasing {
            b.partition_point(|&v| v <= x)
        } else {
            b.partition_point(|&v| v >= x)
        };
        j.saturating_sub(1).min(pieces - 1)
    }

    /// `D^nu f` at every `x` of `xs` into `out` (`dim` numbers a point): on the piece `j` with
    /// `x_j ≤ x < x_{j+1}` (`x_j ≥ x > x_{j+1}` when decreasing, as SciPy) the basis `B`'s
    /// evaluation at the local coordinate of `x` ([`PieceBasis`]). Outside the breakpoints the
    /// end pieces are continued or NaN is written, as `beyond` says (SciPy's `extrapolate`);
    /// NaN at a NaN or infinite `x`. Orders `nu ≥ k` give zeros. The values of orders up to
    /// [`FIXED_ORDER_MAX`] by kernels with the order fixed at compile time. The piece by the
    /// bucket table of the B-spline evaluator when there are at least as many points as pieces
    /// (O(1) a point for spread-out breakpoints), else by binary search; on the rayon pool from
    /// 16384 points. O(points·(cost of a piece)), plus O(pieces) for the table; one scratch of
    /// [`PieceBasis::scratch_len`] numbers a task for derivatives.
    ///
    /// # Errors
    /// [`Error::LengthMismatch`] if `out` does not hold `dim` numbers a point;
    /// [`Error::NonFinite`] for a value that overflows.
    pub fn par_eval_beyond(
        &self,
        xs: &[f64],
        nu: usize,
        beyond: Beyond,
        out: &mut [f64],
    ) -> Result<()> {
        let search = PieceSearch::new(self.breakpoints, xs.len());
        let (k, dim) = (self.order, self.dim);
        if nu >= k {
            return search.for_each_point(xs, dim, beyond, out, || (), |(), _, _, o| o.fill(0.0));
        }
        // the values with the order fixed, and the dimension too when it is 1 (the piece's
        // stride then a constant)
        macro_rules! fixed {
            ($k:literal) => {
                if dim == 1 && search.has_split_table() && xs.len() >= 4 * self.pieces() {
                    // scalar values on a split table, no branch a point; with four points a
                    // piece or more, the coefficients of each piece first laid side by side
                    // (one cache line a point instead of K, for O(K·pieces))
                    let rows = self.rows::<$k>();
                    search.for_each_scalar(xs, beyond, out, |j, x| {
                        let piece = self.piece_of_dim(j, 1);
                        B::value::<$k>(&rows[j], B::local(&piece, x))
                    })
                } else if dim == 1 && search.has_split_table() {
                    search.for_each_scalar(xs, beyond, out, |j, x| {
                        let piece = self.piece_of_dim(j, 1);
                        let c = std::array::from_fn(|m| piece.coefficient(m, 0));
                        B::value::<$k>(&c, B::local(&piece, x))
                    })
                } else if dim == 1 {
                    search.for_each_point(
                        xs,
                        1,
                        beyond,
                        out,
                        || (),
                        |(), j, x, o| {
                            let piece = self.piece_of_dim(j, 1);
                            B::values::<$k>(&piece, B::local(&piece, x), o);
                        },
                    )
                } else {
                    search.for_each_point(
                        xs,
                        dim,
                        beyond,
                        out,
                        || (),
                        |(), j, x, o| {
                            let piece = self.piece(j);
                            B::values::<$k>(&piece, B::local(&piece, x), o);
                        },
                    )
                }
            };
        }
        match (nu, k) {
            (0, 1) => fixed!(1),
            (0, 2) => fixed!(2),
            (0, 3) => fixed!(3),
            (0, 4) => fixed!(4),
            (0, 5) => fixed!(5),
            (0, 6) => fixed!(6),
            _ => search.for_each_point(
                xs,
                dim,
                beyond,
                out,
                || vec![0.0; B::scratch_len(k)],
                |w, j, x, o| {
                    let piece = self.piece(j);
                    B::derivative(&piece, B::local(&piece, x), nu, w, o);
                },
            ),
        }
    }
}
