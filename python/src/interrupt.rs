//! Long work off the interpreter's thread, so that the GIL is free while it
//! runs and Ctrl-C reaches the caller.
//!
//! The work runs on a thread of its own; the calling thread waits for it
//! with the GIL released, waking every [`POLL`] to ask Python whether a
//! signal arrived ([`Python::check_signals`]). On Ctrl-C the caller gets
//! `KeyboardInterrupt` at once and the work's [`Progress::cancelled`] answers
//! `true` from then on: a loop of the library that polls it stops early; one
//! that does not runs to its end on its thread and its answer is dropped.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{self, RecvTimeoutError};
use std::sync::Arc;
use std::time::Duration;

use pyo3::exceptions::PyRuntimeError;
use pyo3::prelude::*;
use sticky::progress::Progress;

/// How often the waiting thread asks Python for signals.
const POLL: Duration = Duration::from_millis(20);

/// The observer handed to the library: it shows nothing and reports the
/// caller's Ctrl-C as a cancellation.
#[derive(Debug, Default)]
pub struct Interrupt {
    cancelled: AtomicBool,
}

impl Progress for Interrupt {
    fn cancelled(&self) -> bool {
        self.cancelled.load(Ordering::Relaxed)
    }
}

/// Work of at most this many steps (particles times requests) runs on the
/// calling thread: it ends in well under a millisecond, less than starting
/// a thread costs.
pub const INLINE_STEPS: usize = 1 << 14;

/// [`run`] for work of about `steps` steps: small work on the calling
/// thread (GIL released), the rest on a thread of its own.
pub fn run_sized<R, F>(py: Python<'_>, steps: usize, work: F) -> PyResult<R>
where
    R: Send + 'static,
    F: FnOnce(&Interrupt) -> R + Send + 'static,
{
    if steps <= INLINE_STEPS {
        let observer = Interrupt::default();
        return Ok(py.detach(move || work(&observer)));
    }
    run(py, work)
}

/// Runs `work` on its own thread with the GIL released, and returns its
/// answer; `KeyboardInterrupt` (or whatever exception a signal handler
/// raised) as soon as the user presses Ctrl-C.
pub fn run<R, F>(py: Python<'_>, work: F) -> PyResult<R>
where
    R: Send + 'static,
    F: FnOnce(&Interrupt) -> R + Send + 'static,
{
    let observer = Arc::new(Interrupt::default());
    let (tx, rx) = mpsc::channel();
    let theirs = Arc::clone(&observer);
    std::thread::Builder::new()
        .name("sticky-work".into())
        .spawn(move || {
            // The receiver is gone when the caller was interrupted.
            let _ = tx.send(work(&theirs));
        })
        .map_err(|e| PyRuntimeError::new_err(format!("cannot start a worker thread: {e}")))?;
    let mut rx = rx;
    loop {
        let (back, got) = py.detach(move || {
            let got = rx.recv_timeout(POLL);
            (rx, got)
        });
        rx = back;
        match got {
            Ok(answer) => return Ok(answer),
            Err(RecvTimeoutError::Timeout) => {
                if let Err(signal) = py.check_signals() {
                    observer.cancelled.store(true, Ordering::Relaxed);
                    return Err(signal);
                }
            }
            Err(RecvTimeoutError::Disconnected) => {
                return Err(PyRuntimeError::new_err(
                    "the computation stopped without an answer (a bug in sticky: please report it)",
                ))
            }
        }
    }
}
