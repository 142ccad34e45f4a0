//! Software prefetch hints: ask the CPU to start loading memory that a
//! traversal will read a little later, so that several cache misses overlap.
//!
//! A prefetch never changes a result; on targets without one this is a no-op.

/// Bytes per cache line.
const LINE: usize = 64;

/// True when this CPU has the prefetch instruction used by [`lines`]
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

/// Hints that every cache line `items` spans will be read soon.
#[inline(always)]
pub(crate) fn lines<T>(items: &[T]) {
    #[cfg(all(target_arch = "x86_64", target_feature = "sse"))]
    {
        use std::arch::x86_64::{_MM_HINT_T0, _mm_prefetch};
        let start = items.as_ptr().cast::<i8>();
        let skew = start as usize % LINE;
        let mut offset = 0;
        while offset < skew + size_of_val(items) {
            // SAFETY: this code is compiled only for targets with SSE (part of
            // the x86_64 baseline), which `_mm_prefetch` needs; a prefetch is a
            // hint that never faults and has no visible effect, whatever the
            // address, and `wrapping_sub`/`wrapping_add` never dereference.
            unsafe {
                _mm_prefetch::<_MM_HINT_T0>(start.wrapping_sub(skew).wrapping_add(offset));
            }
            offset += LINE;
        }
    }
    #[cfg(not(all(target_arch = "x86_64", target_feature = "sse")))]
    {
        let _ = (items, LINE);
    }
}
