//! Cooperative interruption (Ctrl-C): long runs (the pellet's time steps, a transient tied-heat
//! scene) check [`requested`] between steps and stop cleanly, saying how far they got, instead
//! of dying mid-write. The command-line program installs the handler ([`install_handler`]);
//! a program of one's own may call [`request`] from its own handler or thread.
//!
//! The one module that knows the `ctrlc` crate.
//!
//! ```
//! use mortar::interrupt;
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

/// Whether [`install_handler`] has installed the handler in this process.
static INSTALLED: AtomicBool = AtomicBool::new(false);

/// Makes Ctrl-C (SIGINT, and SIGTERM) [`request`] a stop; a second Ctrl-C ends the process at
/// once (status 130), for a computation that does not reach its next step. Calling it again
/// (a program running several commands through [`crate::cli::run_from`]) keeps the handler
/// installed the first time.
///
/// # Errors
/// The message of the `ctrlc` crate when the handler cannot be installed (another one is).
pub fn install_handler() -> Result<(), String> {
    if INSTALLED.swap(true, Ordering::SeqCst) {
        return Ok(());
    }
    ctrlc::set_handler(|| {
        if requested() {
            std::process::exit(130);
        }
        request();
    })
    .map_err(|e| {
        INSTALLED.store(false, Ordering::SeqCst);
        format!("cannot install the Ctrl-C handler: {e}")
    })
}
