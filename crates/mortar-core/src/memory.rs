//! Giving memory freed by a large phase back to the operating system.
//!
//! glibc's allocator keeps what a thread frees in that thread's arena and returns only the
//! top of each arena to the system, so the part buffers of an assembly, freed before the
//! matrix arrays are filled, would stay resident beside them: the process's peak would be
//! the sum of both, not what is live. `malloc_trim` gives the free pages of every arena
//! back (with `madvise`). Elsewhere (musl, macOS, Windows, or another global allocator in
//! the program) this does nothing. glibc's API stays inside this module.

/// Bytes freed at once from which a release is worth its walk over the arenas and the page
/// faults of what is allocated after it (the parts of a coupling of 10^5 line faces are
/// about this large).
pub(crate) const RELEASE_BYTES: usize = 32 << 20;

/// Asks the C allocator to give the memory it holds free back to the system; whether any
/// came back (always `false` off glibc).
#[cfg(all(target_os = "linux", target_env = "gnu"))]
#[allow(unsafe_code)]
pub(crate) fn release_free_memory() -> bool {
    // SAFETY: malloc_trim has no precondition: it only returns free pages of the allocator's
    // arenas to the system (and takes each arena's lock while it does).
    unsafe { libc::malloc_trim(0) != 0 }
}

/// Asks the C allocator to give the memory it holds free back to the system; whether any
/// came back (always `false` off glibc).
#[cfg(not(all(target_os = "linux", target_env = "gnu")))]
pub(crate) fn release_free_memory() -> bool {
    false
}

/// A vector of `n` zeros (`T::default()`), written by every thread of the pool.
///
/// `vec![0; n]` asks the allocator for zeroed memory (`calloc`). glibc gives a fresh mapping
/// (zero pages, faulted in later by whichever thread writes them) only above its mmap
/// threshold, which rises to 32 MiB once a program has freed large blocks; below it, from
/// a worker thread's arena, it zeroes the block with `memset` on the calling thread. For the
/// arrays of D and M that serial pass was the one part of the assembly that did not scale:
/// line2d at 10^6 on two threads spent 10 ms allocating its rows (0.2 ms on one). Written in
/// parallel, the pages are faulted in and zeroed by both threads, whatever the allocator did.
pub(crate) fn zeroed_in_parallel<T: Default + Copy + Send + Sync>(n: usize) -> Vec<T> {
    use rayon::prelude::*;
    let mut v = Vec::with_capacity(n);
    v.par_extend(rayon::iter::repeat_n(T::default(), n));
    v
}
