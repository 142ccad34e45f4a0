//! Software prefetch hints: ask the CPU to start loading memory that a
//! traversal will read a little later, so that several cache misses overlap.
//!
//! A prefetch never changes a result; on targets without one this is a no-op.

/// Bytes per cache line.
const LINE: usize = 64;

/// Bytes [`span`] covers from its start, wherever that lies in a line.
pub(crate) const SPAN: usize = 2 * LINE + 16;

/// True when this CPU has the prefetch instruction used by [`span`]
/// (checked at run time; SSE on x86_64).
pub(crate) fn available() -> bool {
    #[cfg(target_arch = "x86_64")]
    {
        std::arch::is_x86_feature_detected!("sse")
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        false
    }
}

/// Hints that the cache lines holding the bytes at `start`, `start + 64`
/// and `start + SPAN - 1` will be read soon: all of a BVH node or triangle
/// packet (up to [`SPAN`] bytes) from `start`, with no loop and so no branch
/// to mispredict. `start` need not point to anything: a prefetch never reads.
#[inline(always)]
pub(crate) fn span(start: *const u8) {
    #[cfg(all(target_arch = "x86_64", target_feature = "sse"))]
    {
        use std::arch::x86_64::{_MM_HINT_T0, _mm_prefetch};
        let start = start.cast::<i8>();
        for offset in [0, LINE, SPAN - 1] {
            // SAFETY: this code is compiled only for targets with SSE (the
            // x86_64 baseline), which `_mm_prefetch` needs; a prefetch never
            // faults whatever the address, and `wrapping_add` never
            // dereferences.
            unsafe { _mm_prefetch::<_MM_HINT_T0>(start.wrapping_add(offset)) }
        }
    }
    #[cfg(not(all(target_arch = "x86_64", target_feature = "sse")))]
    {
        let _ = start;
    }
}
