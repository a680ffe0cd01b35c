//! Piece location on breakpoints read in place (SciPy's `PPoly.x`, `BPoly.x`), and the batch
//! loop of the in-place view [`crate::pp::PiecewiseRef`] (either basis).
//!
//! Increasing breakpoints `x_0 ≤ … ≤ x_m` (`x_0 < x_m`) may repeat; the pieces between
//! repeated ones are empty and never evaluated. A point `x_0 ≤ x < x_m` lies in the piece `j`
//! with `x_j ≤ x < x_{j+1}` (the last `j` with `x_j ≤ x`, which is never empty); from `x_m` on
//! the last non-empty piece is continued, below `x_0` the first (SciPy's `extrapolate=True`),
//! or NaN is written (`extrapolate=False`, [`Beyond::Nan`]). Decreasing breakpoints
//! `x_0 ≥ … ≥ x_m` (`x_0 > x_m`) are SciPy's other order: piece `j` holds `x_j ≥ x > x_{j+1}`,
//! the last piece also `x_m`, which is the increasing rule for `−x` on `−x_0 ≤ … ≤ −x_m`
//! (negation is exact), and is searched so. Large batches find their pieces through the bucket
//! table of the B-spline evaluator ([`PieceLocator`], O(1) a point for spread-out breakpoints,
//! O(log m) at worst), built per call in O(m) when there are at least as many points as
//! pieces; smaller ones by binary search, O(log m) a point and nothing built.

use rayon::prelude::*;

use crate::curve::fast_eval::locate::{PieceLocator, SplitLocator};
use crate::curve::Beyond;
use crate::error::{Error, Result};

/// Batches of at least this many points run on the rayon pool (as the B-spline evaluator's
/// batches from Python).
pub(crate) const PAR_MIN_POINTS: usize = 1 << 14;

/// Points whose pieces are found before their values are computed (see `for_each_point`): a
/// stack array of this many piece numbers.
const BLOCK: usize = 64;

/// The piece number of a point whose value is not defined (NaN is written).
const UNDEFINED: usize = usize::MAX;

/// Smallest number of points a parallel task takes (the per-task cost, a wake-up, stays
/// negligible).
const PAR_CHUNK: usize = 1 << 13;

/// The piece of a point on breakpoints read in place (see the module documentation).
#[derive(Debug)]
pub(crate) struct PieceSearch<'a> {
    breakpoints: &'a [f64],
    /// Decreasing breakpoints: the search runs on `−x`.
    descending: bool,
    /// The first and the last non-empty piece.
    first: usize,
    last: usize,
    /// The bucket table, for batches with at least as many points as pieces, and the
    /// breakpoints it is built on (`−x_j` when decreasing, else empty: the breakpoints).
    locator: Option<(PieceLocator, Vec<f64>)>,
    /// The bucket table as one split a bucket ([`SplitLocator`]), when the breakpoints increase
    /// and every bucket holds at most two pieces: then every point, defined or not, has a piece
    /// without a branch, the first and last non-empty pieces beyond the ends
    /// (`for_each_scalar`). Both tables are built on `x_first … x_{last+1}`, without the empty
    /// pieces at the ends (SciPy's `PPoly.from_spline` repeats the end knots).
    split: Option<SplitLocator>,
}

impl<'a> PieceSearch<'a> {
    /// The search on `breakpoints` (at least two, monotonic, the ends different: see
    /// [`crate::pp::PiecewiseRef::new`]) for a batch of `points` points.
    pub(crate) fn new(breakpoints: &'a [f64], points: usize) -> Self {
        let pieces = breakpoints.len() - 1;
        let descending = breakpoints[pieces] < breakpoints[0];
        let non_empty = |j: &usize| breakpoints[*j] != breakpoints[*j + 1];
        let first = (0..pieces).find(non_empty).unwrap_or(0);
        let last = (0..pieces).rev().find(non_empty).unwrap_or(pieces - 1);
        // the tables are built on the breakpoints of the non-empty end pieces and the pieces
        // between them (x_first … x_{last+1}): a piece found there is offset by `first`
        let inner = &breakpoints[first..=last + 1];
        let locator = (points >= pieces).then(|| {
            if descending {
                let negated: Vec<f64> = inner.iter().map(|v| -v).collect();
                (PieceLocator::new(&negated), negated)
            } else {
                (PieceLocator::new(inner), Vec::new())
            }
        });
        let split = match &locator {
            Some((table, _)) if !descending => table.split_table(inner),
            _ => None,
        };
        PieceSearch {
            breakpoints,
            descending,
            first,
            last,
            locator,
            split,
        }
    }

    /// `(min, max)` of the breakpoints.
    #[inline(always)]
    pub(crate) fn domain(&self) -> (f64, f64) {
        let (a, b) = (
            self.breakpoints[0],
            self.breakpoints[self.breakpoints.len() - 1],
        );
        if self.descending {
            (b, a)
        } else {
            (a, b)
        }
    }

    /// The piece that evaluates the finite `x`: its own inside the breakpoints, the end pieces
    /// outside (see the module documentation).
    #[inline(always)]
    pub(crate) fn piece(&self, x: f64) -> usize {
        let b = self.breakpoints;
        let m = b.len() - 1;
        // the increasing rule for y = ±x on the breakpoints ±x_j
        let (y, start, end) = if self.descending {
            (-x, -b[0], -b[m])
        } else {
            (x, b[0], b[m])
        };
        if y >= end {
            return self.last;
        }
        if y < start {
            return self.first;
        }
        match &self.locator {
            Some((table, negated)) => {
                let inner = if self.descending {
                    negated.as_slice()
                } else {
                    &b[self.first..=self.last + 1]
                };
                self.first + table.find(inner, y)
            }
            // start ≤ y < end: at least one breakpoint at or below y, the last one below end
            None if self.descending => b.partition_point(|&v| -v <= y) - 1,
            None => b.partition_point(|&v| v <= y) - 1,
        }
    }

    /// Whether [`PieceSearch::for_each_scalar`] runs (see the field `split`).
    #[inline]
    pub(crate) fn has_split_table(&self) -> bool {
        self.split.is_some()
    }

    /// [`PieceSearch::for_each_point`] for scalar values (`dim = 1`) when the split table
    /// exists ([`PieceSearch::has_split_table`]; else `for_each_point` itself): the value
    /// `value(piece, x)` of every point written, the same pieces and the same NaN as
    /// `for_each_point`, without a branch a point. Every point gets a piece from the table
    /// (the end pieces beyond the ends, some piece at NaN or ±∞), its value is computed, and
    /// NaN is selected where the value is not defined, so the loops are straight and the
    /// searches of a block overlap.
    ///
    /// # Errors
    /// As [`PieceSearch::for_each_point`]'s.
    pub(crate) fn for_each_scalar<F>(
        &self,
        xs: &[f64],
        beyond: Beyond,
        out: &mut [f64],
        value: F,
    ) -> Result<()>
    where
        F: Fn(usize, f64) -> f64 + Sync,
    {
        let Some(split) = &self.split else {
            return self.for_each_point(
                xs,
                1,
                beyond,
                out,
                || (),
                |(), j, x, o| {
                    o[0] = value(j, x);
                },
            );
        };
        if out.len() != xs.len() {
            return Err(Error::LengthMismatch {
                what: "output (points × dim)".into(),
                expected: xs.len(),
                got: out.len(),
            });
        }
        let (lo, hi) = self.domain();
        let continued = beyond == Beyond::Continue;
        // continued: every finite point (the domain's ends are finite); else the domain only
        let defined = |x: f64| {
            if continued {
                x.is_finite()
            } else {
                lo <= x && x <= hi
            }
        };
        let run = |xs: &[f64], out: &mut [f64]| -> bool {
            let mut finite = true;
            let mut pieces = [0usize; BLOCK];
            for (xs, out) in xs.chunks(BLOCK).zip(out.chunks_mut(BLOCK)) {
                for (j, &x) in pieces.iter_mut().zip(xs) {
                    *j = self.first + split.find(x);
                }
                for ((&x, o), &j) in xs.iter().zip(out.iter_mut()).zip(&pieces) {
                    let v = value(j, x);
                    let ok = defined(x);
                    *o = if ok { v } else { f64::NAN };
                    finite &= !ok | (v.abs() < f64::INFINITY);
                }
            }
            finite
        };
        if self.run_blocks(xs, out, 1, run) {
            return Ok(());
        }
        Err(self.overflow(xs, 1, out, defined))
    }

    /// `run` on the batch (`out` of `dim` numbers a point), on the rayon pool from
    /// [`PAR_MIN_POINTS`] points in chunks whose results do not depend on the split; whether
    /// every chunk reported its values finite.
    fn run_blocks<R>(&self, xs: &[f64], out: &mut [f64], dim: usize, run: R) -> bool
    where
        R: Fn(&[f64], &mut [f64]) -> bool + Sync,
    {
        if xs.len() < PAR_MIN_POINTS {
            return run(xs, out);
        }
        let chunk = xs
            .len()
            .div_ceil(4 * rayon::current_num_threads().max(1))
            .max(PAR_CHUNK);
        xs.par_chunks(chunk)
            .zip(out.par_chunks_mut(chunk * dim))
            .map(|(x, o)| run(x, o))
            .reduce(|| true, |a, b| a && b)
    }

    /// The error of the first defined value that is not finite (an overflow), for the message.
    fn overflow(
        &self,
        xs: &[f64],
        dim: usize,
        out: &[f64],
        defined: impl Fn(f64) -> bool,
    ) -> Error {
        let index = xs
            .iter()
            .zip(out.chunks_exact(dim))
            .position(|(&x, o)| defined(x) && !o.iter().all(|v| v.is_finite()))
            .unwrap_or(0);
        Error::NonFinite {
            what: "piecewise polynomial value (overflow: rescale the coefficients)".into(),
            index,
            value: out[index * dim..(index + 1) * dim]
                .iter()
                .copied()
                .find(|v| !v.is_finite())
                .unwrap_or(f64::NAN),
        }
    }

    /// `kernel(scratch, piece, x, row)` for every point of `xs` whose value is defined, its row
    /// of `dim` numbers in `out` (`scratch` made by `new_scratch` once a task); NaN in the rows of NaN or infinite points and, with [`Beyond::Nan`],
    /// of points outside `[x_0, x_m]`. On the rayon pool from [`PAR_MIN_POINTS`] points, in
    /// chunks whose results do not depend on the split (each row is computed from its own
    /// point).
    ///
    /// # Errors
    /// [`Error::LengthMismatch`] if `out` does not hold `dim` numbers a point;
    /// [`Error::NonFinite`] (`what` names the overflow) if a defined value is not finite.
    pub(crate) fn for_each_point<S, N, F>(
        &self,
        xs: &[f64],
        dim: usize,
        beyond: Beyond,
        out: &mut [f64],
        new_scratch: N,
        kernel: F,
    ) -> Result<()>
    where
        N: Fn() -> S + Sync,
        F: Fn(&mut S, usize, f64, &mut [f64]) + Sync,
    {
        let want = xs.len().saturating_mul(dim);
        if out.len() != want || dim == 0 {
            return Err(Error::LengthMismatch {
                what: "output (points × dim)".into(),
                expected: want,
                got: out.len(),
            });
        }
        let (lo, hi) = self.domain();
        let continued = beyond == Beyond::Continue;
        let defined = |x: f64| (lo <= x && x <= hi) || (continued && x.is_finite());
        // true when every defined value is finite. In blocks: the pieces of a block first,
        // then its values, so that the processor overlaps the searches (a chain of dependent
        // loads a point) of many points, and the evaluations of many, instead of the few whose
        // search and evaluation together fit in its window
        let run = |xs: &[f64], out: &mut [f64]| -> bool {
            let mut scratch = new_scratch();
            let mut finite = true;
            let mut pieces = [UNDEFINED; BLOCK];
            for (xs, out) in xs.chunks(BLOCK).zip(out.chunks_mut(BLOCK * dim)) {
                for (j, &x) in pieces.iter_mut().zip(xs) {
                    *j = if defined(x) { self.piece(x) } else { UNDEFINED };
                }
                if dim == 1 {
                    // scalar values (SciPy's 1-D `y`): a row is one number, its length known
                    // to the kernel
                    for ((&x, o), &j) in xs.iter().zip(out.iter_mut()).zip(&pieces) {
                        if j == UNDEFINED {
                            *o = f64::NAN;
                        } else {
                            kernel(&mut scratch, j, x, std::slice::from_mut(o));
                            finite &= o.is_finite();
                        }
                    }
                    continue;
                }
                for ((&x, o), &j) in xs.iter().zip(out.chunks_exact_mut(dim)).zip(&pieces) {
                    if j == UNDEFINED {
                        o.fill(f64::NAN);
                    } else {
                        kernel(&mut scratch, j, x, o);
                        finite &= o.iter().all(|v| v.is_finite());
                    }
                }
            }
            finite
        };
        if self.run_blocks(xs, out, dim, run) {
            return Ok(());
        }
        Err(self.overflow(xs, dim, out, defined))
    }
}

#[cfg(test)]
mod tests {
    use proptest::prelude::*;

    use super::*;
    use crate::oracle::proptest_config;

    /// The piece by definition: increasing, the last `j` with `x_j ≤ x` inside; decreasing,
    /// the last `j` with `x_j ≥ x`; the end pieces outside.
    fn piece_by_definition(b: &[f64], x: f64) -> usize {
        let pieces = b.len() - 1;
        let non_empty: Vec<usize> = (0..pieces).filter(|&j| b[j] != b[j + 1]).collect();
        let (first, last) = (non_empty[0], non_empty[non_empty.len() - 1]);
        let descending = b[pieces] < b[0];
        let beyond_start = if descending { x > b[0] } else { x < b[0] };
        let at_or_beyond_end = if descending {
            x <= b[pieces]
        } else {
            x >= b[pieces]
        };
        if beyond_start {
            first
        } else if at_or_beyond_end {
            last
        } else if descending {
            (0..pieces).rev().find(|&j| b[j] >= x).unwrap_or(0)
        } else {
            (0..pieces).rev().find(|&j| b[j] <= x).unwrap_or(0)
        }
    }

    proptest! {
        #![proptest_config(proptest_config(128))]

        /// The bucket table and the binary search find the piece of the definition, with
        /// repeated breakpoints (empty pieces, also at the ends), at the breakpoints
        /// themselves and beyond the ends, in either order.
        #[test]
        fn both_searches_find_the_piece_of_the_definition(
            gaps in prop::collection::vec(prop_oneof![1 => Just(0.0), 4 => 1e-3f64..3.0], 1..=40),
            start in -1e3f64..1e3,
            us in prop::collection::vec(-0.2f64..1.2, 1..=60),
            descending in any::<bool>(),
        ) {
            let mut b = vec![start];
            for g in &gaps {
                let next = if descending { b[b.len() - 1] - g } else { b[b.len() - 1] + g };
                b.push(next);
            }
            prop_assume!(b[b.len() - 1] != b[0]);
            let (lo, hi) = (b[0], b[b.len() - 1]);
            let xs: Vec<f64> = us.iter().map(|u| lo + (hi - lo) * u).chain(b.iter().copied()).collect();
            let small = PieceSearch::new(&b, 0);
            let large = PieceSearch::new(&b, usize::MAX);
            prop_assert!(small.locator.is_none() && large.locator.is_some(), "the two searches");
            for &x in &xs {
                let want = piece_by_definition(&b, x);
                prop_assert_eq!(small.piece(x), want, "binary search, x = {}", x);
                prop_assert_eq!(large.piece(x), want, "bucket table, x = {}", x);
            }
        }
    }

    /// NaN where nothing is defined, the kernel everywhere else; a parallel batch has the rows
    /// of a sequential one; an overflow and a wrong buffer are refused by name.
    #[test]
    fn batch_rows_nan_and_errors() {
        let b = [0.0, 1.0, 1.0, 3.0];
        let search = PieceSearch::new(&b, 0);
        let kernel = |_: &mut (), j: usize, x: f64, o: &mut [f64]| {
            o[0] = j as f64;
            o[1] = x;
        };
        let xs = [-1.0, 0.5, 1.0, 3.0, 4.0, f64::NAN, f64::INFINITY];
        let mut out = [0.0; 14];
        search
            .for_each_point(&xs, 2, Beyond::Continue, &mut out, || (), kernel)
            .unwrap();
        let pieces: Vec<f64> = out.chunks(2).map(|r| r[0]).collect();
        assert_eq!(&pieces[..5], &[0.0, 0.0, 2.0, 2.0, 2.0], "pieces");
        assert!(out[10..].iter().all(|v| v.is_nan()), "NaN and infinity");
        search
            .for_each_point(&xs, 2, Beyond::Nan, &mut out, || (), kernel)
            .unwrap();
        assert!(out[..2].iter().all(|v| v.is_nan()) && out[8..10].iter().all(|v| v.is_nan()));
        assert_eq!(
            &out[2..8],
            &[0.0, 0.5, 2.0, 1.0, 2.0, 3.0],
            "inside, ends included"
        );

        let many: Vec<f64> = (0..3 * PAR_MIN_POINTS)
            .map(|i| -0.5 + 4.0 * i as f64 / (3 * PAR_MIN_POINTS) as f64)
            .collect();
        let (mut par, mut seq) = (vec![0.0; 2 * many.len()], vec![0.0; 2 * many.len()]);
        PieceSearch::new(&b, many.len())
            .for_each_point(&many, 2, Beyond::Continue, &mut par, || (), kernel)
            .unwrap();
        for (x, o) in many.iter().zip(seq.chunks_exact_mut(2)) {
            search
                .for_each_point(&[*x], 2, Beyond::Continue, o, || (), kernel)
                .unwrap();
        }
        assert_eq!(par, seq, "parallel rows");

        let e = search
            .for_each_point(&xs, 2, Beyond::Continue, &mut out[..3], || (), kernel)
            .unwrap_err();
        assert!(
            matches!(e, Error::LengthMismatch { expected: 14, .. }),
            "{e}"
        );
        let e = search
            .for_each_point(
                &[0.5, 2.0],
                1,
                Beyond::Continue,
                &mut [0.0; 2],
                || (),
                |(), _, x, o| {
                    o[0] = if x > 1.0 { f64::INFINITY } else { x };
                },
            )
            .unwrap_err();
        assert!(matches!(e, Error::NonFinite { index: 1, .. }), "{e}");
    }
}
