//! Progress of long work, told to whoever watches.
//!
//! The library reports what it is doing (the claim being checked, the size
//! `N` of a study, the scene being drawn) through the [`Progress`] trait and
//! never draws anything itself: it carries no terminal dependency. The
//! command line hands it a bar on stderr (`report::progress`, feature
//! `report`) that shows nothing when stderr is not a terminal; the Python
//! package hands it an observer that checks for Ctrl-C; a program that does
//! not care passes [`Silent`].
//!
//! A long loop calls [`Progress::cancelled`] between units of work and
//! returns early with its own "interrupted" error when it answers `true`.

/// An observer of long work: a stage with an optional number of steps, the
/// steps as they are done, and whether the watcher asked to stop.
///
/// Every method has a default that does nothing, so an observer implements
/// only what it shows. Implementations are `Sync`: work on two threads
/// reports through one observer.
pub trait Progress: Sync {
    /// A new stage begins: `what` names it (a claim's label, `N = 4096`, a
    /// scene's name); `total` is its number of steps when known.
    fn stage(&self, what: &str, total: Option<u64>) {
        let _ = (what, total);
    }

    /// `steps` more steps of the current stage are done.
    fn advance(&self, steps: u64) {
        let _ = steps;
    }

    /// A short note on the step under way (shown beside the bar).
    fn note(&self, what: &str) {
        let _ = what;
    }

    /// All stages are over (the bar is cleared).
    fn finish(&self) {}

    /// Whether the watcher asked the work to stop (Ctrl-C in Python). Long
    /// loops ask between steps and end with an "interrupted" error.
    fn cancelled(&self) -> bool {
        false
    }
}

/// The observer that shows nothing and never cancels.
#[derive(Clone, Copy, Debug, Default)]
pub struct Silent;

impl Progress for Silent {}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::atomic::{AtomicU64, Ordering};

    /// Counts the steps it is told of, to check the defaults compose.
    struct Counter(AtomicU64);

    impl Progress for Counter {
        fn advance(&self, steps: u64) {
            self.0.fetch_add(steps, Ordering::Relaxed);
        }
    }

    #[test]
    fn defaults_do_nothing_and_never_cancel() {
        let silent = Silent;
        silent.stage("claims", Some(3));
        silent.advance(2);
        silent.note("df:KN");
        silent.finish();
        assert!(!silent.cancelled());
    }

    #[test]
    fn an_observer_sees_the_steps() {
        let counter = Counter(AtomicU64::new(0));
        let observer: &dyn Progress = &counter;
        observer.stage("N = 8", Some(5));
        observer.advance(2);
        observer.advance(3);
        assert_eq!(counter.0.load(Ordering::Relaxed), 5);
        assert!(!observer.cancelled());
    }
}
