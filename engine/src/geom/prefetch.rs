//! Software prefetch hints: ask the CPU to start loading memory that a
//! traversal will read a little later, so that several cache misses overlap.
//!
//! A prefetch never changes a result; on targets without one this is a no-op.

/// Bytes per cache line.
const LINE: usize = 64;

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

/// Hints that the cache lines holding the bytes at `start`, `start + 64`,
/// ... below `start + bytes` will be read soon: all of an object of up to
/// `bytes` bytes that starts at a line boundary (a BVH node), or of up to
/// `bytes - 48` bytes at a 16-byte boundary (a triangle packet). `bytes` is
/// meant to be a constant, so that the hints unroll with no loop and so no
/// branch to mispredict. `start` need not point to anything: a prefetch
/// never reads.
#[inline(always)]
pub(crate) fn span(start: *const u8, bytes: usize) {
    #[cfg(all(target_arch = "x86_64", target_feature = "sse"))]
    {
        use std::arch::x86_64::{_MM_HINT_T0, _mm_prefetch};
        let start = start.cast::<i8>();
        for offset in (0..bytes).step_by(LINE) {
            // SAFETY: this code is compiled only for targets with SSE (the
            // x86_64 baseline), which `_mm_prefetch` needs; a prefetch never
            // faults whatever the address, and `wrapping_add` never
            // dereferences.
            unsafe { _mm_prefetch::<_MM_HINT_T0>(start.wrapping_add(offset)) }
        }
    }
    #[cfg(not(all(target_arch = "x86_64", target_feature = "sse")))]
    {
        let _ = (start, bytes);
    }
}
