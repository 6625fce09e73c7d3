//! Ctrl-C for the `mortar` command: the handler that turns SIGINT (and SIGTERM) into a
//! request to stop at the next step ([`mortar_scenes::interrupt`]). The one module that knows
//! the `ctrlc` crate.

use std::sync::atomic::{AtomicBool, Ordering};

use mortar_scenes::interrupt::{request, requested};

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
