//! Cooperative interruption: long runs (the pellet's time steps, a transient tied-heat scene)
//! check [`requested`] between steps and stop cleanly, saying how far they got, instead of
//! dying mid-write. The `mortar` command's Ctrl-C handler calls [`request`]; a program of one's
//! own may call it from its own handler or thread.
//!
//! ```
//! use mortar_scenes::interrupt;
//! assert!(!interrupt::requested());
//! interrupt::request();
//! assert!(interrupt::requested());
//! interrupt::clear();
//! ```

use std::sync::atomic::{AtomicBool, Ordering};

static REQUESTED: AtomicBool = AtomicBool::new(false);

/// Asks the running computation to stop at its next step.
pub fn request() {
    REQUESTED.store(true, Ordering::SeqCst);
}

/// Whether a stop was asked for.
pub fn requested() -> bool {
    REQUESTED.load(Ordering::SeqCst)
}

/// Withdraws a request (before a new run).
pub fn clear() {
    REQUESTED.store(false, Ordering::SeqCst);
}
