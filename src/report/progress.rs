//! The progress bar of the command line: [`Bar`] shows a
//! [`Progress`] on stderr when stderr is a
//! terminal, and nothing otherwise (piped or redirected output stays clean).

use crate::progress::Progress;
use indicatif::{ProgressBar, ProgressStyle};
use std::io::IsTerminal;

/// A bar on stderr: the stage's name, its steps, the time spent and left.
#[derive(Debug)]
pub struct Bar {
    bar: ProgressBar,
}

impl Bar {
    /// A bar for the command `command` (`claims`, `prove`, …), hidden when
    /// stderr is not a terminal.
    pub fn for_command(command: &str) -> Self {
        let bar = if std::io::stderr().is_terminal() {
            ProgressBar::new_spinner()
        } else {
            ProgressBar::hidden()
        };
        bar.set_prefix(command.to_string());
        Bar { bar }
    }

    /// A bar that never shows (for tests and `--quiet` runs).
    pub fn hidden() -> Self {
        Bar {
            bar: ProgressBar::hidden(),
        }
    }

    /// The underlying indicatif bar, for code that drives it directly.
    pub fn indicatif(&self) -> &ProgressBar {
        &self.bar
    }
}

impl Progress for Bar {
    fn stage(&self, what: &str, total: Option<u64>) {
        let template = match total {
            Some(_) => "{prefix} {wide_msg} {bar:30} {pos}/{len} [{elapsed} spent, ~{eta} left]",
            None => "{prefix} {spinner} {wide_msg} {pos} [{elapsed}]",
        };
        let style =
            ProgressStyle::with_template(template).unwrap_or_else(|_| ProgressStyle::default_bar());
        self.bar.set_style(style);
        self.bar.set_length(total.unwrap_or(0));
        self.bar.set_position(0);
        self.bar.set_message(what.to_string());
    }

    fn advance(&self, steps: u64) {
        self.bar.inc(steps);
    }

    fn note(&self, what: &str) {
        self.bar.set_message(what.to_string());
    }

    fn finish(&self) {
        self.bar.finish_and_clear();
    }
}
