//! Run-time choice of the instruction set for the few kernels compiled twice (the fused cubic
//! interpolation sweeps of `interpolate_fast` and `cubic_sweep`).
//!
//! The crate is built for the baseline of its target (SSE2 on x86-64), so that one binary runs
//! anywhere. Where a kernel is bound by instruction throughput, a second copy compiled with AVX2
//! (`#[target_feature(enable = "avx2")]`: three-operand VEX encoding, 4-wide vectors) is taken
//! when the processor has it. FMA is deliberately not enabled, and Rust never contracts or
//! reassociates floating point, so both copies perform the same IEEE operations in the same
//! order and return the same bits (tested in `interpolate_fast`).

/// Whether the processor running this code has AVX2 (`is_x86_feature_detected!`, a cached
/// atomic load after the first call); `false` off x86-64.
#[inline]
pub(crate) fn has_avx2() -> bool {
    #[cfg(target_arch = "x86_64")]
    {
        std::arch::is_x86_feature_detected!("avx2")
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        false
    }
}

/// Defines `fn $name(args) -> ret` that calls `$body(args)` compiled with AVX2 where the
/// processor has it ([`has_avx2`]) and as built otherwise. `$body` must be `#[inline(always)]`
/// (with what it calls in its hot loops), so that the AVX2 copy, a nested
/// `#[target_feature(enable = "avx2")]` function, compiles it again. The one `unsafe` call
/// of every such pair is here, with its safety argument. One `const` generic parameter is
/// supported.
///
/// ```ignore
/// avx2_dispatch! {
///     /// docs of the dispatcher
///     pub(crate) fn solve_free_cubic<const D: usize>(q: &[f64]) -> bool = solve_free_cubic_body;
/// }
/// ```
macro_rules! avx2_dispatch {
    (
        $(#[$meta:meta])*
        $vis:vis fn $name:ident $(<const $c:ident: usize>)?
            ($($arg:ident: $ty:ty),* $(,)?) $(-> $ret:ty)? = $body:ident;
    ) => {
        $(#[$meta])*
        #[allow(unsafe_code)]
        $vis fn $name $(<const $c: usize>)? ($($arg: $ty),*) $(-> $ret)? {
            #[cfg(target_arch = "x86_64")]
            {
                #[target_feature(enable = "avx2")]
                unsafe fn avx2 $(<const $c: usize>)? ($($arg: $ty),*) $(-> $ret)? {
                    $body $(::<$c>)? ($($arg),*)
                }
                if $crate::numeric::isa::has_avx2() {
                    // SAFETY: the one requirement of a `target_feature` function is that the
                    // processor has the feature, checked just above.
                    return unsafe { avx2 $(::<$c>)? ($($arg),*) };
                }
            }
            $body $(::<$c>)? ($($arg),*)
        }
    };
}
pub(crate) use avx2_dispatch;
