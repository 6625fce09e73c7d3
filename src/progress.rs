//! The progress bar of the `mortar` command: the display of a run's steps
//! ([`mortar_scenes::progress`]) drawn by `indicatif` on stderr, when stderr is a terminal.
//! The one module that knows the `indicatif` crate.

use std::io::IsTerminal;

use mortar_scenes::progress::{set_display, Progress};

/// An `indicatif` bar as a run's display.
struct Bar(indicatif::ProgressBar);

impl Progress for Bar {
    fn inc(&self, n: u64) {
        self.0.inc(n);
    }

    fn set_message(&self, message: String) {
        self.0.set_message(message);
    }

    fn finish_and_clear(&self) {
        self.0.finish_and_clear();
    }
}

/// Makes runs that ask for it draw a bar `LABEL [====>   ] 3/31 steps  message` on stderr, when
/// stderr is a terminal (nothing otherwise). Once per process; a later call changes nothing.
pub fn install() {
    set_display(Box::new(|len, label| {
        let bar = if std::io::stderr().is_terminal() {
            let bar = indicatif::ProgressBar::new(len);
            let template = format!("{label} {{bar:40}} {{pos}}/{{len}} steps  {{msg}}");
            if let Ok(style) = indicatif::ProgressStyle::with_template(&template) {
                bar.set_style(style);
            }
            bar
        } else {
            indicatif::ProgressBar::hidden()
        };
        Box::new(Bar(bar))
    }));
}
