//! One interface for every exact engine, and the one list of them.
//!
//! Every engine computes the same exact answer — the state of
//! `prop:proj-micro`, `x(t) = P_K(x⁰ + t u⁰)` and `u(t) = P_{H_{x(t)}}(u⁰)`
//! (`eq:proj-micro-x`, `eq:proj-u-micro`), with the multipliers `λ` of
//! `eq:dyn-micro` — by a different algorithm or on different numbers. An
//! engine is [prepared](ExactEngine::prepare) once for an initial datum
//! (scaling to integers, or the whole event history), then asked for the
//! [state at](Prepared::state_at) any number of times. History engines (the
//! event-driven merges) also give their [`Trajectory`]: the impulses and the
//! join times.
//!
//! [`ENGINES`] lists them all; the oracle battery ([`crate::fast::battery`])
//! runs every engine of the list against the generic `BigRational`
//! projection (and the history engines against the generic event merge).
//! Which engine answers a caller is [`crate::solver::Solver`]'s decision
//! (its cost model, its work check, its fallbacks); adding an engine is one
//! line in [`ENGINES`].

use num_rational::BigRational;

use crate::error::Error;
use crate::fast::{adaptive, kernel, merge};
use crate::initial::InitialData;
use crate::progress::{Progress, Silent};
use crate::projection;
use crate::state::State;
use crate::trajectory::Trajectory;

/// An exact engine: prepared once per initial datum, then asked for states.
pub trait ExactEngine: Sync {
    /// The engine's stable name (the command line's `--engine NAME`).
    fn name(&self) -> &'static str;
    /// Other names the command line accepts for it.
    fn aliases(&self) -> &'static [&'static str] {
        &[]
    }
    /// One line: the algorithm and the numbers it runs on.
    fn summary(&self) -> &'static str;
    /// Prepares the engine for `data` (scaling, or the whole history).
    fn prepare(&self, data: &InitialData<BigRational>) -> Box<dyn Prepared>;
}

/// An engine prepared for one initial datum (shared across threads: the
/// [`crate::solver::Solver`] keeps it for every later question).
pub trait Prepared: Send + Sync {
    /// The exact state at `t` (an error for `t < 0`).
    fn state_at(&self, t: &BigRational) -> Result<State<BigRational>, Error>;
    /// [`Prepared::state_at`], telling `progress` of the work and stopping
    /// with [`Error::Interrupted`] when it asks (engines whose one state is
    /// quick ignore it).
    fn state_at_with_progress(
        &self,
        t: &BigRational,
        progress: &dyn Progress,
    ) -> Result<State<BigRational>, Error> {
        let _ = progress;
        self.state_at(t)
    }
    /// The whole history (impulses, join times), for a history engine;
    /// `None` for a one-shot projection.
    fn trajectory(&self) -> Option<&Trajectory<BigRational>> {
        None
    }
}

/// The generic projection on `BigRational` ([`projection::state_at`]): the
/// oracle.
#[derive(Debug, Clone, Copy)]
pub struct GenericProjection;

/// The projection on `BigRational` with one common denominator per block
/// ([`crate::blockwise`]): for data whose denominators are small one by one
/// and large together.
#[derive(Debug, Clone, Copy)]
pub struct Blockwise;

/// The generic event-driven cluster merge on `BigRational`
/// ([`Trajectory::new`]): the history oracle.
#[derive(Debug, Clone, Copy)]
pub struct GenericEvents;

/// The integer PAVA kernel ([`kernel`]): `i128`, 256-bit or `BigInt`.
#[derive(Debug, Clone, Copy)]
pub struct Kernel;

/// The adaptive solver ([`adaptive`]): certified `f64` decisions, exact
/// integers where the bound cannot settle them.
#[derive(Debug, Clone, Copy)]
pub struct Adaptive;

/// The event-driven merge on fixed-width integers ([`merge`]).
#[derive(Debug, Clone, Copy)]
pub struct Merge;

/// Every exact engine, the oracle first. Adding an engine is one line here.
pub static ENGINES: &[&dyn ExactEngine] = &[
    &GenericProjection,
    &GenericEvents,
    &Kernel,
    &Adaptive,
    &Merge,
    &Blockwise,
];

/// A prepared engine that answers from a closure of `t`.
struct OneShot<F>(F);

impl<F: Fn(&BigRational) -> Result<State<BigRational>, Error> + Send + Sync> Prepared
    for OneShot<F>
{
    fn state_at(&self, t: &BigRational) -> Result<State<BigRational>, Error> {
        (self.0)(t)
    }
}

/// A prepared history engine: the trajectory answers.
struct History(Trajectory<BigRational>);

impl Prepared for History {
    fn state_at(&self, t: &BigRational) -> Result<State<BigRational>, Error> {
        self.0.at(t)
    }
    fn trajectory(&self) -> Option<&Trajectory<BigRational>> {
        Some(&self.0)
    }
}

impl ExactEngine for GenericProjection {
    fn name(&self) -> &'static str {
        "generic-projection"
    }
    fn summary(&self) -> &'static str {
        "P_K(x⁰ + t u⁰) by pool-adjacent-violators on BigRational (the oracle)"
    }
    fn prepare(&self, data: &InitialData<BigRational>) -> Box<dyn Prepared> {
        let data = data.clone();
        Box::new(OneShot(move |t: &BigRational| {
            projection::state_at(&data, t)
        }))
    }
}

/// A prepared [`Blockwise`] engine.
struct BlockwiseData(InitialData<BigRational>);

impl Prepared for BlockwiseData {
    fn state_at(&self, t: &BigRational) -> Result<State<BigRational>, Error> {
        crate::blockwise::state_at(&self.0, t, &Silent)
    }
    fn state_at_with_progress(
        &self,
        t: &BigRational,
        progress: &dyn Progress,
    ) -> Result<State<BigRational>, Error> {
        crate::blockwise::state_at(&self.0, t, progress)
    }
}

impl ExactEngine for Blockwise {
    fn name(&self) -> &'static str {
        "blockwise"
    }
    fn summary(&self) -> &'static str {
        "P_K(x⁰ + t u⁰) by PAVA on BigInt numerators over one common denominator per block (BigRational answers)"
    }
    fn prepare(&self, data: &InitialData<BigRational>) -> Box<dyn Prepared> {
        Box::new(BlockwiseData(data.clone()))
    }
}

impl ExactEngine for GenericEvents {
    fn name(&self) -> &'static str {
        "generic-events"
    }
    fn summary(&self) -> &'static str {
        "the event-driven cluster merge on BigRational"
    }
    fn prepare(&self, data: &InitialData<BigRational>) -> Box<dyn Prepared> {
        Box::new(History(Trajectory::new(data.clone())))
    }
}

impl ExactEngine for Kernel {
    fn name(&self) -> &'static str {
        "kernel"
    }
    fn aliases(&self) -> &'static [&'static str] {
        &["projection"]
    }
    fn summary(&self) -> &'static str {
        "P_K(x⁰ + t u⁰) by PAVA on integers (i128, 256-bit or BigInt), O(N) per time"
    }
    fn prepare(&self, data: &InitialData<BigRational>) -> Box<dyn Prepared> {
        let d = kernel::IntegerData::new(data);
        Box::new(OneShot(move |t: &BigRational| kernel::state_at(&d, t)))
    }
}

impl ExactEngine for Adaptive {
    fn name(&self) -> &'static str {
        "adaptive"
    }
    fn summary(&self) -> &'static str {
        "the integer PAVA with certified f64 decisions, exact integers where needed"
    }
    fn prepare(&self, data: &InitialData<BigRational>) -> Box<dyn Prepared> {
        let d = kernel::IntegerData::new(data);
        Box::new(OneShot(move |t: &BigRational| adaptive::state_at(&d, t)))
    }
}

impl ExactEngine for Merge {
    fn name(&self) -> &'static str {
        "merge"
    }
    fn aliases(&self) -> &'static [&'static str] {
        &["events"]
    }
    fn summary(&self) -> &'static str {
        "the event-driven cluster merge on i64/i128 integers, O(N log N) once"
    }
    fn prepare(&self, data: &InitialData<BigRational>) -> Box<dyn Prepared> {
        Box::new(History(merge::trajectory(data)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_distinct() {
        let mut names: Vec<&str> = ENGINES
            .iter()
            .flat_map(|e| std::iter::once(e.name()).chain(e.aliases().iter().copied()))
            .collect();
        let count = names.len();
        names.sort_unstable();
        names.dedup();
        assert_eq!(names.len(), count, "{names:?}");
    }

    /// The names are the command line's interface (`--engine NAME`): stable,
    /// in the documented order, the oracle first. Every summary is one line
    /// that names the numbers the engine runs on.
    #[test]
    fn names_and_summaries_are_the_interface() {
        let names: Vec<&str> = ENGINES.iter().map(|e| e.name()).collect();
        assert_eq!(
            names,
            [
                "generic-projection",
                "generic-events",
                "kernel",
                "adaptive",
                "merge",
                "blockwise"
            ]
        );
        for e in ENGINES {
            let s = e.summary();
            assert!(!s.contains('\n'), "{s}");
            assert!(
                s.contains("BigRational") || s.contains("integers"),
                "{}: {s}",
                e.name()
            );
        }
        let mut summaries: Vec<&str> = ENGINES.iter().map(|e| e.summary()).collect();
        summaries.sort_unstable();
        summaries.dedup();
        assert_eq!(summaries.len(), ENGINES.len());
    }

    /// Every engine, prepared once, gives the oracle's state at every probe
    /// time; exactly the history engines give a trajectory, and it is the
    /// generic event merge's (impulses, join times).
    #[test]
    fn prepared_engines_give_the_oracle_state_and_history() {
        use crate::trajectory::probe_times;
        let q = |n: i64, d: i64| BigRational::new(n.into(), d.into());
        // Two collisions at different instants, one cluster that stays
        // apart, a contact at t = 0 that separates.
        let data = InitialData::new(
            q(1, 4),
            vec![q(0, 1), q(1, 1), q(3, 1), q(9, 2), q(6, 1), q(13, 2)],
            vec![q(2, 1), q(0, 1), q(-1, 1), q(0, 1), q(1, 1), q(3, 1)],
        )
        .unwrap();
        let oracle = Trajectory::new(data.clone());
        assert!(oracle.impulses().len() >= 2);
        let times = probe_times(&oracle, None);
        for e in ENGINES {
            let p = e.prepare(&data);
            for t in &times {
                assert_eq!(
                    p.state_at(t).unwrap(),
                    projection::state_at(&data, t).unwrap(),
                    "{} at {t}",
                    e.name()
                );
            }
            let history = matches!(e.name(), "generic-events" | "merge");
            match p.trajectory() {
                Some(h) => {
                    assert!(history, "{}", e.name());
                    assert_eq!(h.impulses(), oracle.impulses(), "{}", e.name());
                    assert_eq!(h.join_times(), oracle.join_times(), "{}", e.name());
                }
                None => assert!(!history, "{}", e.name()),
            }
        }
    }
}
