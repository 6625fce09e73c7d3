//! The progress of a run's steps, as the caller wants it shown: the `mortar` command draws a
//! bar ([`set_display`]); a library or Python run shows nothing. The scenes ask for one with
//! [`display`] and tick it.

use std::sync::OnceLock;

/// A progress display of a run's steps.
pub trait Progress: Send + Sync {
    /// `n` more steps done.
    fn inc(&self, n: u64);
    /// A message beside the count.
    fn set_message(&self, message: String);
    /// The run is over: the display goes.
    fn finish_and_clear(&self);
}

/// What makes a display: the number of steps and the run's label (`"pellet"`, say).
pub type ProgressFactory = Box<dyn Fn(u64, &str) -> Box<dyn Progress> + Send + Sync>;

static FACTORY: OnceLock<ProgressFactory> = OnceLock::new();

/// Sets how runs show their progress, once per process (a later call is ignored and returns
/// `false`).
pub fn set_display(factory: ProgressFactory) -> bool {
    FACTORY.set(factory).is_ok()
}

/// No display.
struct Hidden;

impl Progress for Hidden {
    fn inc(&self, _: u64) {}
    fn set_message(&self, _: String) {}
    fn finish_and_clear(&self) {}
}

/// A display of `len` steps labelled `label`: the one [`set_display`] set when `shown`, else
/// none.
pub fn display(shown: bool, len: u64, label: &str) -> Box<dyn Progress> {
    match FACTORY.get() {
        Some(make) if shown => make(len, label),
        _ => Box::new(Hidden),
    }
}
