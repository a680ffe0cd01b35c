//! Run-time choice of the instruction set for the few kernels compiled twice (the fused cubic
//! interpolation sweeps of `interpolate_fast` and the reciprocal blocks of `linalg`).
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
