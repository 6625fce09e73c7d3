//! The worker pools of [`assemble_coupling`](super::assemble_coupling), kept from one call to
//! the next.
//!
//! Starting a rayon pool costs its threads' start-up: on this project's 2-core test machine
//! 0.10-0.15 ms a call, which was a third of coupling a 10^3-face straight line (0.30 ms a
//! call, 0.18 ms of it the coupling's phases) and 14% of a 10^3-face arc
//! (`examples/bench_small_calls.rs`). A contact or gap law re-couples its
//! interface at every Newton step, so a pool is built once per thread count and kept, its
//! threads asleep between calls. A few thread counts are kept ([`POOLS_KEPT`], the most
//! recently used); a call with another one drops the least recently used pool (its threads
//! end once their work is done).
//!
//! Calls with the same thread count share the pool, also when made at the same time from
//! several threads: each call's chunks are then shared among the pool's threads, and D and M
//! stay bit-identical (they do not depend on which thread took which chunk).
//!
//! A process forked after a coupling (Python's `multiprocessing` on Linux, for one) inherits
//! the list but not the threads: a job sent to such a pool would wait forever. The list
//! records the process it was filled in; a call from another process leaves the inherited
//! pools alone (never dropped: their threads are not there to be told) and starts afresh.
//!
//! A call with no thread count made on a rayon pool's thread (a user's `pool.install`) runs
//! on that pool and takes none from here.

use std::sync::{Arc, Mutex, MutexGuard, PoisonError};

use rayon::ThreadPool;

use super::MAX_THREADS_PER_CORE;
use crate::error::{MortarError, Result};

/// Pools kept at once, one per thread count.
const POOLS_KEPT: usize = 4;

/// The kept pools by requested thread count (`None`: rayon's default), most recently used
/// last, and the process that built them.
struct Kept {
    process: u32,
    pools: Vec<(Option<usize>, Arc<ThreadPool>)>,
}

static POOLS: Mutex<Kept> = Mutex::new(Kept {
    process: 0,
    pools: Vec::new(),
});

impl Kept {
    /// The list, locked, emptied first if it was filled in another process: pools inherited
    /// through a fork have no threads, and are forgotten, not dropped (dropping one would
    /// signal threads that are not there).
    fn locked() -> MutexGuard<'static, Kept> {
        // A panic elsewhere while the lock was held leaves the list as valid as before it.
        let mut kept = POOLS.lock().unwrap_or_else(PoisonError::into_inner);
        let process = std::process::id();
        if kept.process != process {
            std::mem::forget(std::mem::take(&mut kept.pools));
            kept.process = process;
        }
        kept
    }

    /// The kept pool of `threads`, moved to the most recently used end.
    fn find(&mut self, threads: Option<usize>) -> Option<Arc<ThreadPool>> {
        let at = self.pools.iter().position(|(t, _)| *t == threads)?;
        let entry = self.pools.remove(at);
        let pool = Arc::clone(&entry.1);
        self.pools.push(entry);
        Some(pool)
    }

    /// Keeps `built` as the pool of `threads`, unless another call kept one in the meantime
    /// (that one is returned): the pool to use, and the one to drop once the lock is released
    /// (`built` when it lost, or the least recently used beyond [`POOLS_KEPT`]).
    fn keep(
        &mut self,
        threads: Option<usize>,
        built: Arc<ThreadPool>,
    ) -> (Arc<ThreadPool>, Option<Arc<ThreadPool>>) {
        if let Some(pool) = self.find(threads) {
            return (pool, Some(built));
        }
        let dropped = (self.pools.len() >= POOLS_KEPT).then(|| self.pools.remove(0).1);
        self.pools.push((threads, Arc::clone(&built)));
        (built, dropped)
    }
}

/// The pool of `threads` worker threads (`None`: rayon's default, the core count or
/// `RAYON_NUM_THREADS`), built on first use and kept.
///
/// # Errors
/// [`MortarError::InvalidOption`] for zero threads, more than [`MAX_THREADS_PER_CORE`] per
/// core, or a pool that cannot start.
pub(super) fn pool(threads: Option<usize>) -> Result<Arc<ThreadPool>> {
    check(threads)?;
    let found = Kept::locked().find(threads);
    if let Some(pool) = found {
        return Ok(pool);
    }
    // Built, and any pool let go dropped, outside the lock: starting or ending threads takes
    // a while, and a process forked meanwhile would inherit the lock held.
    let built = Arc::new(build(threads)?);
    let (pool, dropped) = Kept::locked().keep(threads, built);
    drop(dropped);
    Ok(pool)
}

/// Refuses zero threads and more than [`MAX_THREADS_PER_CORE`] per core.
fn check(threads: Option<usize>) -> Result<()> {
    if threads == Some(0) {
        return Err(MortarError::InvalidOption {
            option: "threads",
            value: "0".into(),
            reason: "at least 1".into(),
        });
    }
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    if let Some(t) = threads.filter(|&t| t > MAX_THREADS_PER_CORE * cores) {
        return Err(MortarError::InvalidOption {
            option: "threads",
            value: t.to_string(),
            reason: format!(
                "at most {} on {cores} cores ({MAX_THREADS_PER_CORE} per core)",
                MAX_THREADS_PER_CORE * cores
            ),
        });
    }
    Ok(())
}

/// A new pool of `threads` worker threads.
fn build(threads: Option<usize>) -> Result<ThreadPool> {
    let mut builder = rayon::ThreadPoolBuilder::new();
    if let Some(t) = threads {
        builder = builder.num_threads(t);
    }
    builder.build().map_err(|e| MortarError::InvalidOption {
        option: "threads",
        value: threads.map_or("default".into(), |t| t.to_string()),
        reason: format!("cannot start a thread pool: {e}"),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The tests of this module one at a time: the fork test must not fork while another
    /// test holds the list's lock (the child would inherit it held).
    static SERIAL: Mutex<()> = Mutex::new(());

    fn serial() -> std::sync::MutexGuard<'static, ()> {
        SERIAL.lock().unwrap_or_else(PoisonError::into_inner)
    }

    /// The same thread count gets the same pool; a fifth thread count drops the least
    /// recently used, so that at most `POOLS_KEPT` pools (and their threads) are alive.
    #[test]
    fn pools_are_kept_per_thread_count_and_bounded() {
        let _serial = serial();
        // Thread counts no other test of this binary asks for, so that the list is this
        // test's alone between its calls (tests run in parallel on one list).
        let first = pool(Some(5)).unwrap();
        assert!(Arc::ptr_eq(&first, &pool(Some(5)).unwrap()));
        assert_eq!(first.current_num_threads(), 5);
        for t in 6..6 + POOLS_KEPT {
            let p = pool(Some(t)).unwrap();
            assert_eq!(p.current_num_threads(), t);
        }
        let kept = Kept::locked();
        assert!(kept.pools.len() <= POOLS_KEPT);
        assert!(
            kept.pools.iter().all(|(t, _)| *t != Some(5)),
            "the oldest was dropped"
        );
        drop(kept);
        assert!(!Arc::ptr_eq(&first, &pool(Some(5)).unwrap()));
    }

    /// Zero threads, and more than the per-core bound, are refused before any pool is built.
    #[test]
    fn invalid_thread_counts_are_refused() {
        let _serial = serial();
        assert!(matches!(
            pool(Some(0)),
            Err(MortarError::InvalidOption {
                option: "threads",
                ..
            })
        ));
        let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
        assert!(pool(Some(MAX_THREADS_PER_CORE * cores + 1)).is_err());
    }

    /// A process forked after a pool was kept gets a new pool that runs its jobs; the
    /// inherited one has no threads, and a job sent to it would never run (the child then
    /// hung until the parent killed it after 20 s).
    #[cfg(target_os = "linux")]
    #[test]
    #[allow(unsafe_code)]
    fn a_forked_process_gets_pools_of_its_own() {
        let _serial = serial();
        // A thread count no other test asks for.
        let parent = pool(Some(11)).unwrap();
        assert_eq!(parent.install(|| 1 + 1), 2);
        // SAFETY: the child only builds a pool, runs one job on it and leaves with `_exit`
        // (no destructor, no test harness); glibc's allocator is usable after a fork.
        let child = unsafe { libc::fork() };
        assert!(child >= 0, "fork failed");
        if child == 0 {
            let ok = pool(Some(11)).is_ok_and(|p| p.install(|| 1 + 1) == 2);
            // SAFETY: ends the child at once, as after any fork.
            unsafe { libc::_exit(if ok { 0 } else { 1 }) };
        }
        let mut status = 0;
        let start = std::time::Instant::now();
        loop {
            // SAFETY: waits for our own child, without blocking.
            let done = unsafe { libc::waitpid(child, &mut status, libc::WNOHANG) };
            if done == child {
                break;
            }
            if start.elapsed().as_secs() >= 20 {
                // SAFETY: our own child, stuck.
                unsafe {
                    libc::kill(child, libc::SIGKILL);
                    libc::waitpid(child, &mut status, 0);
                }
                panic!("the forked process's coupling pool never ran its job");
            }
            std::thread::sleep(std::time::Duration::from_millis(10));
        }
        assert!(
            libc::WIFEXITED(status) && libc::WEXITSTATUS(status) == 0,
            "the forked process failed: status {status}"
        );
    }
}
