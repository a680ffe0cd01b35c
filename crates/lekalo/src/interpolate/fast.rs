//! The fused fast path of global cubic interpolation (document 000 §1 with chord-length
//! parameters and averaged knots, eq. 3), for 1–3 dimensions: parameters, knots, banded
//! elimination and back substitution in three sweeps, agreeing with the general path of
//! [`crate::interpolate::curve`] to rounding (the same parameters and knots bit for bit; the control
//! points within `κ·ε`, tested there), which it falls back to whenever it does not apply.

use crate::interpolate::cubic_sweep::solve_free_cubic;
use crate::interpolate::parametrization::distances;
use crate::numeric::large_buffer::reuse_or_zeroed;
use crate::{BSplineCurve, Points, PointsRef};
use std::cell::RefCell;

/// The fast path of [`free_end`](crate::interpolate::curve) for cubics with averaged knots in 1–3 dimensions
/// ([`solve_free_cubic`](crate::interpolate::cubic_sweep::solve_free_cubic)): the control points, or `None` when it does not apply or a check
/// fails, so that the general path reports the error.
pub(crate) fn free_end_cubic(
    points: PointsRef<'_>,
    params: &[f64],
    knots: &[f64],
) -> Option<Points> {
    let dim = points.dim();
    let mut control = crate::numeric::large_buffer::zeroed(points.as_slice().len());
    for (c, t) in control.chunks_exact_mut(dim).zip(params) {
        c[0] = *t;
    }
    let mut upper = Vec::new();
    let q = points.as_slice();
    let done = match dim {
        1 => solve_free_cubic::<1>(q, knots, &mut control, &mut upper),
        2 => solve_free_cubic::<2>(q, knots, &mut control, &mut upper),
        3 => solve_free_cubic::<3>(q, knots, &mut control, &mut upper),
        _ => false,
    };
    done.then(|| Points::from_raw(control, dim))
}

/// Buffers kept between calls of
/// [`CurveInterpolation::interpolate_with`](crate::CurveInterpolation::interpolate_with), so
/// that repeated interpolation of large data sets does not ask the operating system for fresh
/// memory each time.
///
/// New memory costs page faults on first touch. On the 2-core VM of `docs/performance.md`, a
/// first 3-D cubic interpolation through 10^6 points in a process runs at about 25 ns a point
/// on new memory (on transparent huge pages; 38 ns without them), against 16 ns with a
/// workspace. [`CurveInterpolation::interpolate`](crate::CurveInterpolation::interpolate)
/// keeps its `U` scratch per thread, so that its later calls come close to the workspace's
/// speed; a workspace reuses the result buffers as well and keeps nothing behind the caller's
/// back.
///
/// The workspace holds the `U` factor of the fused solve. Once
/// [`InterpolationWorkspace::recycle`] has given them back, it also holds the knot and
/// control-point buffers of a previous result, which the next result then reuses.
///
/// ```
/// use lekalo::{CurveInterpolation, InterpolationWorkspace, Points};
/// let interp = CurveInterpolation::new(3);
/// let mut ws = InterpolationWorkspace::new();
/// for shift in [0.0, 0.5, 1.0] {
///     let q = Points::from_2d(&[[0.0, shift], [1.0, 1.0], [2.0, 0.0], [3.0, 1.0], [4.0, shift]])?;
///     let curve = interp.interpolate_with(q.as_view(), &mut ws)?;
///     assert_eq!(curve, interp.interpolate(q.as_view())?);
///     ws.recycle(curve);
/// }
/// # Ok::<(), lekalo::Error>(())
/// ```
#[derive(Debug, Clone, Default)]
pub struct InterpolationWorkspace {
    control: Vec<f64>,
    knots: Vec<f64>,
    upper: Vec<[f64; 2]>,
}

/// Most bytes of `U` storage [`InterpolationWorkspace::return_to_thread`] keeps for a thread:
/// 32 MiB, the factor of 2·10^6 points.
const THREAD_UPPER_MAX_BYTES: usize = 32 << 20;

thread_local! {
    /// The `U` storage of this thread's last fused interpolation without a workspace
    /// ([`CurveInterpolation::interpolate`](crate::CurveInterpolation::interpolate)), kept for
    /// the next one.
    static THREAD_UPPER: RefCell<Vec<[f64; 2]>> = const { RefCell::new(Vec::new()) };
}

impl InterpolationWorkspace {
    /// An empty workspace (buffers grow on first use).
    #[must_use]
    pub fn new() -> Self {
        Self::default()
    }

    /// A workspace with no result buffers and the `U` storage this thread kept from its last
    /// interpolation, if any (taken out of the thread's slot until
    /// [`Self::return_to_thread`]).
    ///
    /// Why: `U` is scratch, 16 bytes a point, freed at the end of each call. Freeing it is what
    /// tips glibc into handing its heap back to the operating system after every call, so
    /// that the next call faults every page of its result again. At 10^5 points that cost twice
    /// the arithmetic: 30 ns a point against 15 (`docs/performance.md`). Kept, the
    /// result buffers come from memory the allocator already holds.
    pub(crate) fn from_thread() -> Self {
        let upper = THREAD_UPPER
            .try_with(|slot| {
                slot.try_borrow_mut()
                    .map(|mut v| std::mem::take(&mut *v))
                    .unwrap_or_default()
            })
            .unwrap_or_default();
        Self {
            upper,
            ..Self::default()
        }
    }

    /// Gives the `U` storage back to this thread's slot, keeping the larger of it and what the
    /// slot holds, up to [`THREAD_UPPER_MAX_BYTES`]. The result buffers are not kept: they
    /// belong to the returned curve.
    pub(crate) fn return_to_thread(self) {
        let upper = self.upper;
        if upper.capacity() * std::mem::size_of::<[f64; 2]>() > THREAD_UPPER_MAX_BYTES {
            return;
        }
        // (a thread being torn down, or a slot in use, keeps nothing)
        let _ = THREAD_UPPER.try_with(|slot| {
            if let Ok(mut held) = slot.try_borrow_mut() {
                if upper.capacity() > held.capacity() {
                    *held = upper;
                }
            }
        });
    }

    /// Takes back the knot and control-point storage of a curve that is no longer needed, for
    /// the next result to reuse (the larger of the held and the given buffers is kept).
    pub fn recycle(&mut self, curve: BSplineCurve) {
        let (_, knots, control) = curve.into_parts();
        let (knots, control) = (knots.into_vec(), control.into_vec());
        if knots.capacity() > self.knots.capacity() {
            self.knots = knots;
        }
        if control.capacity() > self.control.capacity() {
            self.control = control;
        }
    }

    /// Bytes of storage currently held.
    #[must_use]
    pub fn capacity_bytes(&self) -> usize {
        (self.control.capacity() + self.knots.capacity() + 2 * self.upper.capacity())
            * std::mem::size_of::<f64>()
    }
}

/// The whole free-end chord-length cubic in three sweeps over the data and no buffers besides
/// the result and `U`: chord lengths (P&T eq. 9.5, as [`parametrize_into`](crate::interpolate::curve::parametrize_into), the same numbers)
/// go straight into the first slot of each control point's row, the averaged knots (document
/// 000 eq. 3, as [`KnotVector::averaged`](crate::KnotVector::averaged), the same numbers) are formed as the lengths are
/// normalised, then [`solve_free_cubic`](crate::interpolate::cubic_sweep::solve_free_cubic). `None` (take the general path, which reports the
/// problem) for coincident or overflowing points, a dimension above 3, fewer than 5 points or
/// a failed check of the solve.
///
/// The result's buffers and the `U` factor come from `ws` (taken out of it; a failed attempt
/// puts them back).
pub(crate) fn chord_cubic(
    points: PointsRef<'_>,
    ws: &mut InterpolationWorkspace,
) -> Option<BSplineCurve> {
    let dim = points.dim();
    let q = points.as_slice();
    let n = points.len().checked_sub(1)?;
    if n < 4 || dim > 3 {
        return None;
    }
    // every entry of both buffers is written before it is read, so stale values from a
    // recycled curve need no clearing (`resize` writes only the growth)
    let mut control = reuse_or_zeroed(&mut ws.control, q.len());
    let mut knots = reuse_or_zeroed(&mut ws.knots, n + 5);
    let upper = &mut ws.upper;
    let done = match dim {
        1 => chord_sweeps::<1>(q, &mut control, &mut knots, upper),
        2 => chord_sweeps::<2>(q, &mut control, &mut knots, upper),
        _ => chord_sweeps::<3>(q, &mut control, &mut knots, upper),
    };
    if done {
        Some(BSplineCurve::from_raw(
            3,
            knots,
            Points::from_raw(control, dim),
        ))
    } else {
        (ws.control, ws.knots) = (control, knots);
        None
    }
}

/// The three sweeps of [`chord_cubic`] for `D` coordinates: parameters and knots
/// ([`chord_params`]), then the fused solve ([`solve_free_cubic`]); `false` when either declines.
fn chord_sweeps<const D: usize>(
    q: &[f64],
    control: &mut [f64],
    knots: &mut [f64],
    upper: &mut Vec<[f64; 2]>,
) -> bool {
    chord_params::<D>(q, control, knots) && solve_free_cubic::<D>(q, knots, control, upper)
}

crate::numeric::isa::avx2_dispatch! {
    /// [`chord_params_body`] compiled with AVX2 where the processor has it, else as built
    /// ([`crate::numeric::isa`]: the same bits, tested below).
    fn chord_params<const D: usize>(q: &[f64], control: &mut [f64], knots: &mut [f64]) -> bool
        = chord_params_body;
}

/// The first two sweeps of [`chord_cubic`] for `D` coordinates: the parameters into
/// `control[r·D]` and the knots, as [`solve_free_cubic`](crate::interpolate::cubic_sweep::solve_free_cubic)
/// takes them. `control` and `knots` have the result's sizes and any content (every entry is
/// written before it is read). `false` for coincident or overflowing points. Inlined into both
/// copies of [`chord_params`].
#[inline(always)]
fn chord_params_body<const D: usize>(q: &[f64], control: &mut [f64], knots: &mut [f64]) -> bool {
    let n = q.len() / D - 1;
    // sweep 1: the running sums s_r of the chord lengths, r = 1 … n, into knots[r + 4]
    // (contiguous; their slots are free until the knots are formed from them below)
    // (the lengths of a block first, branch-free so that the square roots vectorise)
    const ROWS: usize = 256;
    let mut sum = 0.0;
    let mut lengths = [0.0_f64; ROWS];
    let mut start = 0;
    while start < n {
        let end = (start + ROWS).min(n);
        let d = &mut lengths[..end - start];
        distances::<D>(
            &q[start * D..end * D],
            &q[(start + 1) * D..(end + 1) * D],
            D,
            d,
        );
        let mut ok = true;
        for (s, &d) in knots[start + 5..end + 5].iter_mut().zip(d.iter()) {
            // zero and NaN fail here; an infinite length makes the sum infinite (checked below)
            ok &= d > 0.0;
            sum += d;
            *s = sum;
        }
        if !ok {
            return false;
        }
        start = end;
    }
    if !sum.is_finite() {
        return false;
    }
    let inv = 1.0 / sum;
    // sweep 2, a block of rows at a time so that each step vectorises: t̄_r = s_r / s (t̄_n = 1
    // exactly), strictly increasing, into control[r·D]; u_{r+1} = (t̄_{r−2} + t̄_{r−1} + t̄_r) / 3
    // for r = 3 … n − 1, written at indices below those of the sums still to be read
    // t̄_{a−2}, t̄_{a−1}, then the block's t̄_a … t̄_{b−1}
    let mut t = [0.0_f64; ROWS + 2];
    let mut ok = true;
    let mut a = 1;
    while a <= n {
        let b = (a + ROWS).min(n + 1);
        let m = b - a;
        let tb = &mut t[..m + 2];
        for (dst, s) in tb[2..].iter_mut().zip(&knots[a + 4..b + 4]) {
            *dst = s * inv;
        }
        if b == n + 1 {
            tb[m + 1] = 1.0;
        }
        for w in tb[1..].windows(2) {
            ok &= w[1] > w[0];
        }
        for (c, &v) in control[a * D..b * D].chunks_exact_mut(D).zip(&tb[2..]) {
            c[0] = v;
        }
        let (lo, hi) = (a.max(3), b.min(n));
        if lo < hi {
            for (u, w) in knots[lo + 1..hi + 1]
                .iter_mut()
                .zip(tb[lo - a..].windows(3))
            {
                // the sum in the order of `KnotVector::averaged`
                *u = (w[0] + w[1] + w[2]) / 3.0;
            }
        }
        (t[0], t[1]) = (t[m], t[m + 1]);
        a = b;
    }
    knots[..4].fill(0.0);
    knots[n + 1..].fill(1.0);
    ok
}

#[cfg(all(test, target_arch = "x86_64"))]
mod tests {
    use super::*;
    use crate::numeric::isa::has_avx2;
    use proptest::prelude::*;

    /// Parameters, knots and control points of both copies of the fused sweeps (the bodies as
    /// built, then the dispatchers, which take the AVX2 copies where `has_avx2`), and their
    /// success.
    fn both_copies<const D: usize>(q: &[f64]) -> [(bool, Vec<f64>, Vec<f64>); 2] {
        let n = q.len() / D - 1;
        let run = |dispatched: bool| {
            let (mut control, mut knots) = (vec![0.0; q.len()], vec![0.0; n + 5]);
            let mut upper = Vec::new();
            let done = if dispatched {
                chord_sweeps::<D>(q, &mut control, &mut knots, &mut upper)
            } else {
                chord_params_body::<D>(q, &mut control, &mut knots)
                    && crate::interpolate::cubic_sweep::solve_free_cubic_body::<D>(
                        q,
                        &knots,
                        &mut control,
                        &mut upper,
                    )
            };
            (done, knots, control)
        };
        [run(false), run(true)]
    }

    fn bits(v: &[f64]) -> Vec<u64> {
        v.iter().map(|x| x.to_bits()).collect()
    }

    /// Points with uneven random steps (so that both band placements of the rows occur), from
    /// a seed: `n` points of `D` coordinates.
    fn walk<const D: usize>(n: usize, seed: u64) -> Vec<f64> {
        let mut state = seed | 1;
        let mut next = move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut p = [0.0; D];
        let mut q = Vec::with_capacity(n * D);
        for _ in 0..n {
            for x in &mut p {
                *x += (next() - 0.3) * (1.0 + 30.0 * next().powi(4));
            }
            q.extend_from_slice(&p);
        }
        q
    }

    fn check<const D: usize>(n: usize, seed: u64) -> Result<(), TestCaseError> {
        let q = walk::<D>(n, seed);
        let [base, avx2] = both_copies::<D>(&q);
        prop_assert!(
            base.0,
            "the fused path declined a random walk of {} points",
            n
        );
        prop_assert_eq!(base.0, avx2.0);
        prop_assert_eq!(bits(&base.1), bits(&avx2.1), "knots differ");
        prop_assert_eq!(bits(&base.2), bits(&avx2.2), "control points differ");
        Ok(())
    }

    proptest! {
        /// The AVX2 copies return the baseline's bits: knots and control points, in 1–3
        /// dimensions, across several reciprocal blocks.
        #[test]
        fn avx2_copies_return_the_baseline_bits(n in 5usize..1200, seed in any::<u64>(), dim in 1usize..=3) {
            if !has_avx2() {
                return Ok(());
            }
            match dim {
                1 => check::<1>(n, seed)?,
                2 => check::<2>(n, seed)?,
                _ => check::<3>(n, seed)?,
            }
        }
    }
}

#[cfg(test)]
mod thread_scratch_tests {
    use super::*;
    use crate::{CurveInterpolation, Points};

    fn held_capacity() -> usize {
        THREAD_UPPER.with(|slot| slot.borrow().capacity())
    }

    #[test]
    fn interpolate_keeps_the_u_storage_for_the_thread() {
        THREAD_UPPER.with(|slot| *slot.borrow_mut() = Vec::new());
        let data: Vec<f64> = (0..300)
            .flat_map(|i| {
                let s = f64::from(i) * 0.1;
                [s.cos(), s.sin(), 0.05 * s]
            })
            .collect();
        let q = Points::from_flat(3, data).unwrap();
        let first = CurveInterpolation::new(3).interpolate(q.as_view()).unwrap();
        assert!(held_capacity() >= 299, "U kept after the call");
        // the kept (stale) storage changes nothing
        let second = CurveInterpolation::new(3).interpolate(q.as_view()).unwrap();
        assert_eq!(first, second, "same curve with kept scratch");
        let mut ws = InterpolationWorkspace::new();
        assert_eq!(
            first,
            CurveInterpolation::new(3)
                .interpolate_with(q.as_view(), &mut ws)
                .unwrap(),
            "same curve as with a fresh workspace"
        );
    }

    #[test]
    fn the_slot_keeps_the_larger_buffer_up_to_the_cap() {
        // empty the slot (tests may share a thread with --test-threads=1)
        THREAD_UPPER.with(|slot| *slot.borrow_mut() = Vec::new());
        let with_upper = |rows: usize| InterpolationWorkspace {
            upper: Vec::with_capacity(rows),
            ..InterpolationWorkspace::default()
        };
        with_upper(100).return_to_thread();
        assert_eq!(held_capacity(), 100, "kept");
        with_upper(50).return_to_thread();
        assert_eq!(held_capacity(), 100, "the larger kept");
        // over the cap: not kept (the capacity is reserved, never touched)
        with_upper(THREAD_UPPER_MAX_BYTES / 16 + 1).return_to_thread();
        assert_eq!(held_capacity(), 100, "over the cap");
        // taking leaves the slot empty until the storage comes back
        let ws = InterpolationWorkspace::from_thread();
        assert_eq!(ws.upper.capacity(), 100, "taken");
        assert_eq!(held_capacity(), 0, "slot empty while taken");
        ws.return_to_thread();
        assert_eq!(held_capacity(), 100, "given back");
    }
}
