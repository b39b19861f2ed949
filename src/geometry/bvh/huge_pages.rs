//! Large build buffers backed by transparent huge pages where the system offers them.
//!
//! A 1M-triangle build writes about 150 MB of fresh memory (primitive records, binary
//! nodes, leaf blocks); with 4 KB pages the kernel's page faults took about a tenth of the
//! build. Asking for 2 MB pages (`madvise(MADV_HUGEPAGE)`, as Embree's allocator does on
//! Linux) turns 512 faults into one. Elsewhere, or when the kernel declines, the vector
//! is an ordinary one.

/// An empty vector with room for `capacity` elements, whose memory the kernel is asked
/// to back with huge pages before anything touches it.
pub(crate) fn with_capacity<T>(capacity: usize) -> Vec<T> {
    let v: Vec<T> = Vec::with_capacity(capacity);
    #[cfg(target_os = "linux")]
    {
        /// Buffers smaller than this keep ordinary pages.
        const MIN_BYTES: usize = 4 << 20;
        let bytes = capacity * std::mem::size_of::<T>();
        if bytes >= MIN_BYTES {
            const HUGE: usize = 2 << 20;
            let start = (v.as_ptr() as usize).next_multiple_of(HUGE);
            let end = (v.as_ptr() as usize + bytes) & !(HUGE - 1);
            if end > start {
                // SAFETY: [start, end) lies inside the vector's allocation (2 MB-aligned,
                // so whole pages); the advice changes how pages are backed, not their
                // contents, and its failure is harmless. (It pays only for pages not yet
                // touched, which a fresh large allocation's are.)
                unsafe {
                    libc::madvise(start as *mut libc::c_void, end - start, libc::MADV_HUGEPAGE);
                }
            }
        }
    }
    v
}
