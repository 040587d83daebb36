//! The budget of one proof attempt, enforced inside our own symbolic
//! algebra: a wall-clock deadline and a cap on the size of a polynomial.
//!
//! The solver's share of the budget is enforced by [`super::smt`] (every
//! answer is awaited with a deadline, the process killed when it passes, and
//! `z3` started with `-memory:` and `-T:`). What this module bounds is the
//! rest: a path whose symbolic arithmetic grows without end (integrals of
//! high-degree polynomials whose coefficients are rational functions of the
//! data, say) would otherwise run for as long as it takes, whatever the
//! budget says.
//!
//! The explorer [`install`]s a budget for the duration of one exploration on
//! its thread; the polynomial arithmetic calls [`tick`] once per term it
//! builds and [`check_size`] on every polynomial it returns. When the
//! deadline has passed or a polynomial is larger than the cap, the current
//! path is abandoned by unwinding with an [`Overrun`] payload
//! (`std::panic::resume_unwind`, which runs no panic hook and prints
//! nothing); the explorer catches it around the program and ends the
//! attempt `unknown` with the reason. Outside an exploration (no budget
//! installed) both calls do nothing.

use std::cell::Cell;
use std::time::Instant;

/// Why a path was abandoned.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum Overrun {
    /// The attempt's wall-clock deadline passed.
    Time,
    /// A polynomial of our own algebra grew past the cap on its number of
    /// terms (the memory bound of the symbolic side).
    Size {
        /// Its number of terms.
        terms: usize,
        /// The cap.
        cap: usize,
    },
}

impl std::fmt::Display for Overrun {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Overrun::Time => f.write_str("the time budget ran out inside the symbolic algebra"),
            Overrun::Size { terms, cap } => write!(
                f,
                "a polynomial of the symbolic algebra reached {terms} terms (cap {cap}): the memory bound"
            ),
        }
    }
}

/// The limits enforced on this thread.
#[derive(Debug, Clone, Copy)]
struct Active {
    deadline: Instant,
    max_terms: usize,
}

/// How many [`tick`]s between two reads of the clock. A tick can be slow
/// (an operation on coefficients of thousands of digits), so the clock is
/// read often: a sparser reading let a claim overrun its budget by
/// seconds (`docs/journal.md`), while a read is cheap beside any tick.
const TICKS_PER_CLOCK_READ: u32 = 16;

thread_local! {
    static ACTIVE: Cell<Option<Active>> = const { Cell::new(None) };
    static TICKS: Cell<u32> = const { Cell::new(0) };
}

/// The budget stays installed while this guard lives.
#[derive(Debug)]
pub struct Installed {
    previous: Option<Active>,
}

impl Drop for Installed {
    fn drop(&mut self) {
        ACTIVE.with(|a| a.set(self.previous));
    }
}

/// Installs a deadline and a cap on the number of terms of a polynomial for
/// the current thread, until the returned guard is dropped.
pub fn install(deadline: Instant, max_terms: usize) -> Installed {
    let previous = ACTIVE.with(|a| {
        a.replace(Some(Active {
            deadline,
            max_terms,
        }))
    });
    TICKS.with(|t| t.set(0));
    Installed { previous }
}

/// Abandons the current path (see the module documentation).
fn abandon(why: Overrun) -> ! {
    std::panic::resume_unwind(Box::new(why))
}

/// One unit of symbolic work: every `TICKS_PER_CLOCK_READ`-th call reads
/// the clock and abandons the path once the deadline has passed.
pub fn tick() {
    let Some(active) = ACTIVE.with(Cell::get) else {
        return;
    };
    let n = TICKS.with(|t| {
        let n = t.get().wrapping_add(1);
        t.set(n);
        n
    });
    if n % TICKS_PER_CLOCK_READ == 0 && Instant::now() > active.deadline {
        abandon(Overrun::Time);
    }
}

/// Abandons the path when a polynomial of `terms` terms exceeds the cap.
pub fn check_size(terms: usize) {
    if let Some(active) = ACTIVE.with(Cell::get) {
        if terms > active.max_terms {
            abandon(Overrun::Size {
                terms,
                cap: active.max_terms,
            });
        }
    }
}

/// The overrun carried by a caught unwinding payload, if it is one.
pub fn overrun(payload: &(dyn std::any::Any + Send)) -> Option<Overrun> {
    payload.downcast_ref::<Overrun>().copied()
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::panic::{catch_unwind, AssertUnwindSafe};
    use std::time::Duration;

    #[test]
    fn nothing_is_enforced_without_a_budget() {
        for _ in 0..10 * TICKS_PER_CLOCK_READ {
            tick();
        }
        check_size(usize::MAX);
    }

    #[test]
    fn a_passed_deadline_abandons_the_work() {
        let _guard = install(Instant::now(), 1_000);
        let caught = catch_unwind(AssertUnwindSafe(|| loop {
            tick();
        }));
        let payload = caught.expect_err("the loop must be abandoned");
        assert_eq!(overrun(payload.as_ref()), Some(Overrun::Time));
    }

    #[test]
    fn the_size_cap_abandons_the_work_and_the_guard_lifts_it() {
        {
            let _guard = install(Instant::now() + Duration::from_secs(3600), 10);
            check_size(10);
            let caught = catch_unwind(AssertUnwindSafe(|| check_size(11)));
            let payload = caught.expect_err("11 terms exceed the cap of 10");
            assert_eq!(
                overrun(payload.as_ref()),
                Some(Overrun::Size { terms: 11, cap: 10 })
            );
        }
        check_size(11);
    }
}
