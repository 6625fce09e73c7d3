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
///
/// A large block's pages are first faulted in by the kernel, a few megabytes per task
/// ([`populate_in_parallel`]), rather than one page fault per 4 KiB as the writes reach them.
pub(crate) fn zeroed_in_parallel<T: Default + Copy + Send + Sync>(n: usize) -> Vec<T> {
    use rayon::prelude::*;
    let mut v: Vec<T> = Vec::with_capacity(n);
    populate_in_parallel(v.as_mut_ptr().cast(), n * std::mem::size_of::<T>());
    v.par_extend(rayon::iter::repeat_n(T::default(), n));
    v
}

/// Bytes from which glibc's allocator always maps a block afresh (its largest dynamic mmap
/// threshold on 64-bit targets): a block this large never comes back from the heap with its
/// pages already backed, so populating it first never duplicates work.
const FRESH_BYTES: usize = 32 << 20;

/// The items of `items` in a vector whose pages, from [`FRESH_BYTES`], the kernel has
/// faulted in first, a block per task ([`populate_in_parallel`]): what `collect` gives, for
/// a large temporary array or output that would otherwise take one page fault per 4 KiB as
/// it is written.
pub(crate) fn collect_populated<T: Send>(
    items: impl rayon::iter::IndexedParallelIterator<Item = T>,
) -> Vec<T> {
    use rayon::prelude::*;
    let mut v = populated(items.len());
    v.par_extend(items);
    v
}

/// An empty vector of capacity `n` whose pages the kernel has faulted in, from
/// [`FRESH_BYTES`] ([`populate_in_parallel`]). Smaller blocks may come from the allocator's
/// heap already backed (line2d at 10^6 faces: its temporary arrays of 4-24 MB populated
/// made the first call 4.5 % slower); they are left to the writes.
pub(crate) fn populated<T>(n: usize) -> Vec<T> {
    let mut v: Vec<T> = Vec::with_capacity(n);
    let bytes = n * std::mem::size_of::<T>();
    if bytes >= FRESH_BYTES {
        populate_in_parallel(v.as_mut_ptr().cast(), bytes);
    }
    v
}

/// Arrays of an earlier coupling handed back for the next one to write into
/// ([`assemble_coupling_reusing`](crate::assemble_coupling_reusing)): their pages are
/// already the process's, so filling them costs a pass over resident memory instead of the
/// kernel's page faults (allocation and zeroing of each 4 KiB page), which is what a large
/// coupling's fresh output costs most on a virtual machine.
#[derive(Debug, Default)]
pub(crate) struct Spare {
    /// Index arrays (row pointers, column indices).
    usizes: Vec<Vec<usize>>,
    /// Value arrays.
    floats: Vec<Vec<f64>>,
}

impl Spare {
    /// Keeps `v` for a later [`zeroed_usize`](Self::zeroed_usize).
    pub(crate) fn keep_usize(&mut self, v: Vec<usize>) {
        if v.capacity() > 0 {
            self.usizes.push(v);
        }
    }

    /// Keeps `v` for a later [`zeroed_f64`](Self::zeroed_f64).
    pub(crate) fn keep_f64(&mut self, v: Vec<f64>) {
        if v.capacity() > 0 {
            self.floats.push(v);
        }
    }

    /// `n` zeros, in the kept index array of the smallest capacity that holds them, else in
    /// a new one ([`zeroed_in_parallel`]).
    pub(crate) fn zeroed_usize(&mut self, n: usize) -> Vec<usize> {
        zeroed_from(&mut self.usizes, n)
    }

    /// `n` zeros, in the kept value array of the smallest capacity that holds them, else in
    /// a new one ([`zeroed_in_parallel`]).
    pub(crate) fn zeroed_f64(&mut self, n: usize) -> Vec<f64> {
        zeroed_from(&mut self.floats, n)
    }
}

/// `n` zeros in the vector of `kept` of the smallest capacity of at least `n` (taken out of
/// `kept`), zeroed by every thread of the pool, or in a new vector. Which vector is taken
/// does not change a value: the result is `n` zeros either way.
fn zeroed_from<T: Default + Copy + Send + Sync>(kept: &mut Vec<Vec<T>>, n: usize) -> Vec<T> {
    use rayon::prelude::*;
    let best = kept
        .iter()
        .enumerate()
        .filter(|(_, v)| v.capacity() >= n)
        .min_by_key(|(_, v)| v.capacity())
        .map(|(i, _)| i);
    let Some(i) = best else {
        return zeroed_in_parallel(n);
    };
    let mut v = kept.swap_remove(i);
    v.truncate(n);
    v.par_chunks_mut(1 << 16).for_each(|c| c.fill(T::default()));
    let have = v.len();
    v.par_extend(rayon::iter::repeat_n(T::default(), n - have));
    v
}

/// Bytes from which a block is worth populating in one call per task.
#[cfg_attr(not(target_os = "linux"), allow(dead_code))]
const POPULATE_BYTES: usize = 4 << 20;

/// Bytes populated per task.
#[cfg_attr(not(target_os = "linux"), allow(dead_code))]
const POPULATE_BLOCK: usize = 2 << 20;

/// Has the kernel fault in the pages of the `bytes` at `ptr` (a block of ours, not yet
/// written) now, a block of [`POPULATE_BLOCK`] per task of the pool (`MADV_POPULATE_WRITE`,
/// Linux 5.14). A page fault costs its trap on top of the page's allocation and zeroing:
/// on this project's benchmark machine (a virtual machine) a 1 GiB array written after one
/// call per block took 0.58 s against 0.84 s page by page, and line2d at 10^6 spends a fifth
/// of its coupling getting the pages of D and M. Only whole pages inside the block are
/// touched, aligned to 64 KiB (a multiple of the page size of every Linux target); an
/// error (an older kernel, another page size) leaves the pages to the writes, as before.
#[cfg(target_os = "linux")]
#[allow(unsafe_code)]
fn populate_in_parallel(ptr: *mut u8, bytes: usize) {
    use rayon::prelude::*;
    const ALIGN: usize = 64 << 10;
    if bytes < POPULATE_BYTES {
        return;
    }
    let start = (ptr as usize).next_multiple_of(ALIGN);
    let end = (ptr as usize).saturating_add(bytes) / ALIGN * ALIGN;
    if end <= start {
        return;
    }
    (start..end)
        .into_par_iter()
        .step_by(POPULATE_BLOCK)
        .for_each(|a| {
            let z = a.saturating_add(POPULATE_BLOCK).min(end);
            // SAFETY: MADV_POPULATE_WRITE faults in the pages of the range as a write would,
            // without writing: whole pages inside one live allocation of ours, whose contents
            // (not yet initialised, or whatever the allocator left) are not changed. Its
            // result is only a hint's: ignored.
            unsafe {
                libc::madvise(a as *mut libc::c_void, z - a, libc::MADV_POPULATE_WRITE);
            }
        });
}

/// Does nothing off Linux (the writes fault the pages in).
#[cfg(not(target_os = "linux"))]
fn populate_in_parallel(_ptr: *mut u8, _bytes: usize) {}

#[cfg(test)]
mod tests {
    use super::*;

    /// Runs `f` on a pool of one thread, then on a pool of two.
    fn on_one_and_two_threads(f: impl Fn() + Send + Sync) {
        for threads in [1, 2] {
            rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap()
                .install(&f);
        }
    }

    /// Above the populating size, on two threads and on one: `n` zeros, whatever the block
    /// held before (the allocator may hand back a block just freed with values in it).
    #[test]
    fn zeroed_blocks_are_zero_at_every_size() {
        on_one_and_two_threads(|| {
            for n in [0, 1, 1000, POPULATE_BYTES / 8 + 3, 3 * POPULATE_BYTES / 8] {
                drop(vec![1.5f64; n]);
                let v = zeroed_in_parallel::<f64>(n);
                assert_eq!(v.len(), n);
                assert!(v.iter().all(|&x| x.to_bits() == 0), "n = {n}");
                let u = zeroed_in_parallel::<usize>(n);
                assert!(u.len() == n && u.iter().all(|&x| x == 0), "n = {n}");
            }
        });
    }

    /// `collect_populated` gives `collect`'s vector below and above the populating size, on
    /// one thread and two.
    #[test]
    fn populated_collects_are_plain_collects() {
        use rayon::prelude::*;
        on_one_and_two_threads(|| {
            for n in [0, 5, FRESH_BYTES / 8 - 1, FRESH_BYTES / 8 + 1000] {
                let f = |i: usize| (i as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15);
                let want: Vec<u64> = (0..n).into_par_iter().map(f).collect();
                let got = collect_populated((0..n).into_par_iter().map(f));
                assert!(got == want, "n = {n}");
                assert!(populated::<u64>(n).is_empty() && populated::<u64>(n).capacity() >= n);
            }
        });
    }

    /// A kept array comes back as `n` zeros whatever it held, the smallest that holds `n`
    /// first; a size no kept array holds gets a new one, and the kept arrays stay.
    #[test]
    fn spare_arrays_come_back_zeroed_smallest_first() {
        let mut spare = Spare::default();
        spare.keep_f64(vec![2.5; 1000]);
        spare.keep_f64(vec![-1.0; 300]);
        spare.keep_usize(vec![7; 50]);
        spare.keep_f64(Vec::new()); // nothing to keep
        assert_eq!(spare.floats.len(), 2);
        let a = spare.zeroed_f64(200);
        assert!(a.len() == 200 && a.iter().all(|x| x.to_bits() == 0));
        assert_eq!(a.capacity(), 300, "the smallest that holds 200");
        let b = spare.zeroed_f64(2000);
        assert!(b.len() == 2000 && b.iter().all(|x| x.to_bits() == 0));
        assert_eq!(
            spare.floats.len(),
            1,
            "the 1000 stays when a new array is taken"
        );
        let c = spare.zeroed_f64(1000);
        assert!(c.len() == 1000 && c.iter().all(|x| x.to_bits() == 0));
        assert_eq!(c.capacity(), 1000);
        let u = spare.zeroed_usize(40);
        assert!(u.len() == 40 && u.iter().all(|&x| x == 0));
        assert!(spare.floats.is_empty() && spare.usizes.is_empty());
    }

    /// Populating a block changes nothing a program can read in it (a block already written,
    /// with its ends not on page boundaries).
    #[test]
    fn populating_keeps_what_a_block_holds() {
        let n = 3 * POPULATE_BYTES / 8 + 5;
        let want: Vec<u64> = (0..n as u64).map(|i| i.wrapping_mul(0x9E37_79B9)).collect();
        let mut v = want.clone();
        populate_in_parallel(v.as_mut_ptr().cast(), n * 8);
        populate_in_parallel(v[7..].as_mut_ptr().cast(), (n - 9) * 8);
        assert!(v == want);
    }
}
