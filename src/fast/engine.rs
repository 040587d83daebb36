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
//! projection (and the history engines against the generic event merge),
//! and the command line chooses from it by name ([`by_name`], [`auto`]).
//! Adding an engine is one line in [`ENGINES`].

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

/// An engine prepared for one initial datum.
pub trait Prepared {
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

/// The engine called `name` (or one of its aliases) in [`ENGINES`].
pub fn by_name(name: &str) -> Option<&'static dyn ExactEngine> {
    ENGINES
        .iter()
        .copied()
        .find(|e| e.name() == name || e.aliases().contains(&name))
}

/// Beyond this many bits the running lcm of [`Cost::of`] stops: the common
/// denominator is then known to be at least this large (2^16 bits, 1,024
/// words: past it the common-denominator engines are out of the question).
pub const LCM_BITS_LIMIT: u64 = 1 << 16;

/// The size of a common denominator: exact, or a lower bound when the
/// running lcm stopped at [`LCM_BITS_LIMIT`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Bits {
    /// The common denominator has exactly this many bits.
    Exact(u64),
    /// The common denominator has at least this many bits.
    AtLeast(u64),
}

impl Bits {
    /// The bits known (exact, or the lower bound).
    pub fn bits(self) -> u64 {
        match self {
            Bits::Exact(b) | Bits::AtLeast(b) => b,
        }
    }
}

impl std::fmt::Display for Bits {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Bits::Exact(b) => write!(f, "{b} bits"),
            Bits::AtLeast(b) => write!(f, "more than {b} bits"),
        }
    }
}

/// What the choice of an engine rests on: `N`, the size of the common
/// denominators the integer engines scale to (`df:translat-x`), of the
/// largest single denominator and numerator, and the estimated word
/// operations of each kind of engine.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Cost {
    /// The number of particles.
    pub n: usize,
    /// The common denominator of the translated positions or of the
    /// velocities (the larger), radius included.
    pub common_denominator: Bits,
    /// Bits of the largest single denominator of the data.
    pub largest_denominator_bits: u64,
    /// Bits of the largest numerator of the data.
    pub largest_numerator_bits: u64,
    /// Word operations of the common-denominator engines (kernel, adaptive,
    /// merge): `N · w²`, `w` the words of a scaled value (common
    /// denominator plus numerator), each answer reduced by a gcd on them.
    pub common: u64,
    /// Word operations of the generic engines on local denominators:
    /// `N · w²` on the largest single value, times [`GENERIC_OVERHEAD`].
    pub local: u64,
}

/// The generic `BigRational` engines reduce after every operation: a
/// handful of gcds per particle where the integer kernels run one. Measured
/// on the hostile scene at `t = 100` (0.9 s generic, 3.5 s kernel with
/// 450-word common denominators) and on word-sized data (the kernel tens of
/// times faster), 32 puts the switch between the two.
pub const GENERIC_OVERHEAD: u64 = 32;

/// Past this many words of a scaled value the common-denominator engines
/// leave their fixed widths (`i128`, 256 bits) for `BigInt`.
const FIXED_WIDTH_WORDS: u64 = 4;

impl Cost {
    /// The cost model of `data`: a running lcm of the denominators (with a
    /// remainder by each small denominator, [`crate::gcd`]), stopped once
    /// past [`LCM_BITS_LIMIT`].
    pub fn of(data: &InitialData<BigRational>) -> Cost {
        let radius = data.radius().denom().magnitude();
        let running = |values: &[BigRational]| -> Bits {
            let denoms = values.iter().map(|q| q.denom().magnitude());
            match crate::gcd::running_lcm(radius, denoms, LCM_BITS_LIMIT) {
                crate::gcd::RunningLcm::Exact(lcm) => Bits::Exact(lcm.bits()),
                crate::gcd::RunningLcm::Past(bits) => Bits::AtLeast(bits),
            }
        };
        let x = running(data.positions());
        let u = running(data.velocities());
        let largest_denominator_bits = largest_denominator_bits(data);
        // Stopped early, the lcm is at least the bits reached and at least
        // every single denominator.
        let common_denominator = match (x, u) {
            (Bits::AtLeast(b), _) | (_, Bits::AtLeast(b)) => {
                Bits::AtLeast(b.max(largest_denominator_bits))
            }
            (Bits::Exact(a), Bits::Exact(b)) => Bits::Exact(a.max(b)),
        };
        let largest_numerator_bits = std::iter::once(data.radius())
            .chain(data.positions())
            .chain(data.velocities())
            .map(|q| q.numer().bits())
            .max()
            .unwrap_or(0);
        let n = data.n() as u64;
        let square = |bits: u64| {
            let w = bits.div_ceil(64).max(1);
            n.saturating_mul(w.saturating_mul(w))
        };
        Cost {
            n: data.n(),
            common_denominator,
            largest_denominator_bits,
            largest_numerator_bits,
            common: square(common_denominator.bits() + largest_numerator_bits),
            local: square(largest_denominator_bits + largest_numerator_bits)
                .saturating_mul(GENERIC_OVERHEAD),
        }
    }

    /// Whether the common-denominator engines are the cheaper: their values
    /// fit fixed widths, or their estimate is below the generic one.
    pub fn common_is_cheaper(&self) -> bool {
        (self.common_denominator.bits() + self.largest_numerator_bits).div_ceil(64)
            <= FIXED_WIDTH_WORDS
            || self.common <= self.local
    }

    /// One line for `--explain`: the engine chosen, `N`, the common
    /// denominator and each candidate's estimate.
    pub fn explain(&self, chosen: &dyn ExactEngine) -> String {
        format!(
            "engine: {} (N = {}, common denominator {}, largest single denominator {} bits, largest numerator {} bits; estimated word operations: common-denominator integer engines ~{:.2e}, generic BigRational on local denominators ~{:.2e})",
            chosen.name(),
            self.n,
            self.common_denominator,
            self.largest_denominator_bits,
            self.largest_numerator_bits,
            self.common as f64,
            self.local as f64,
        )
    }
}

/// The cheapest exact engine for one-shot states of `data`, by the cost
/// model [`Cost::of`]: the integer kernel, which runs on the narrowest
/// integer width the data allow at each time (`i128`, 256-bit, `BigInt`),
/// when the common denominator is small enough; else the generic
/// projection with one common denominator per block ([`Blockwise`]).
pub fn auto(data: &InitialData<BigRational>) -> &'static dyn ExactEngine {
    auto_for(&Cost::of(data))
}

/// [`auto`]'s choice for a cost already computed.
pub fn auto_for(cost: &Cost) -> &'static dyn ExactEngine {
    if cost.common_is_cheaper() {
        &Kernel
    } else {
        &Blockwise
    }
}

/// The default cap of [`check_work`], in 64-bit word operations: `2^29`
/// (at the rate of the `BigInt` arithmetic here, minutes of work).
pub const MAX_WORK: u64 = 1 << 29;

/// The environment variable that sets the cap of [`check_work`].
pub const WORK_VAR: &str = "STICKY_MAX_WORK";

/// The bits of the largest denominator of the data (radius, positions,
/// velocities).
fn largest_denominator_bits(data: &InitialData<BigRational>) -> u64 {
    std::iter::once(data.radius())
        .chain(data.positions())
        .chain(data.velocities())
        .map(|q| q.denom().bits())
        .max()
        .unwrap_or(0)
}

/// A lower bound on the word operations of the common-denominator engines
/// on `data`: `N · ⌈b/64⌉²`, `b` the bits of the common denominator of the
/// data (radius, positions, velocities: [`Cost::of`]), at least the largest
/// single one. Both fast engines scale the data to common denominators
/// (`df:translat-x`) and reduce each answer to lowest terms (a gcd on
/// numbers of that size, quadratic in their length): 20,000 velocities
/// `1/(i+1)` have a common denominator of ~28,800 bits (~4·10⁹ word
/// operations).
pub fn work_estimate(data: &InitialData<BigRational>) -> u64 {
    let words = Cost::of(data).common_denominator.bits().div_ceil(64);
    (data.n() as u64).saturating_mul(words.saturating_mul(words))
}

/// Refuses, up front, data whose exact answer by the common-denominator
/// engines needs more than the cap of word operations ([`work_estimate`]
/// against `$STICKY_MAX_WORK`, default [`MAX_WORK`]) with a message that
/// says why and what to do, instead of a run that does not end in any
/// reasonable time.
pub fn check_work(data: &InitialData<BigRational>) -> Result<(), Error> {
    check_work_for(data, &Kernel)
}

/// [`check_work`] for the engine that will run: the generic projection
/// works on local denominators ([`Cost::local`]), the others on the common
/// denominator.
pub fn check_work_for(
    data: &InitialData<BigRational>,
    engine: &dyn ExactEngine,
) -> Result<(), Error> {
    check_work_capped(data, engine, MAX_WORK)
}

/// The default cap of [`check_work_watched`]: `2^35` word operations, 64
/// times [`MAX_WORK`] — tens of minutes, long but not hopeless.
pub const MAX_WATCHED_WORK: u64 = 1 << 35;

/// [`check_work_for`] for work that shows its progress and can be
/// interrupted (the command line's bar, Python's Ctrl-C): only what is
/// hopeless is refused, above [`MAX_WATCHED_WORK`] (or
/// `$STICKY_MAX_WORK` when set).
pub fn check_work_watched(
    data: &InitialData<BigRational>,
    engine: &dyn ExactEngine,
) -> Result<(), Error> {
    check_work_capped(data, engine, MAX_WATCHED_WORK)
}

/// The guard of [`check_work_for`] with `default_cap` when
/// `$STICKY_MAX_WORK` is not set.
fn check_work_capped(
    data: &InitialData<BigRational>,
    engine: &dyn ExactEngine,
    default_cap: u64,
) -> Result<(), Error> {
    let cap = std::env::var(WORK_VAR)
        .ok()
        .and_then(|v| v.trim().parse::<u64>().ok())
        .unwrap_or(default_cap);
    let local = [GenericProjection.name(), Blockwise.name()].contains(&engine.name());
    // The engines on local denominators need only the largest one: the
    // running lcm of `Cost::of` (up to 2^16 bits, over a second on hostile
    // data, and not interruptible) is computed for the others alone.
    let (bits, cost) = if local {
        (largest_denominator_bits(data), None)
    } else {
        let cost = Cost::of(data);
        (cost.common_denominator.bits(), Some(cost))
    };
    let words = bits.div_ceil(64);
    let work = (data.n() as u64).saturating_mul(words.saturating_mul(words));
    if work <= cap {
        return Ok(());
    }
    let what = match cost {
        None => format!("a largest single denominator of {bits} bits"),
        Some(cost) => format!("a common denominator of {}", cost.common_denominator),
    };
    Err(Error::WorkLimit {
        work,
        cap,
        message: format!(
            "the exact answer by the engine {} needs at least ~{work:.3e} word operations (N = {} particles over {what}, N·(its 64-bit words)²), more than the cap of {cap:.3e}: this would run for a very long time. Use data with smaller or fewer distinct denominators, or set the environment variable {WORK_VAR} to a larger number of operations to run it anyway",
            engine.name(),
            data.n(),
            work = work as f64,
            cap = cap as f64,
        ),
    })
}

/// A prepared engine that answers from a closure of `t`.
struct OneShot<F>(F);

impl<F: Fn(&BigRational) -> Result<State<BigRational>, Error>> Prepared for OneShot<F> {
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
    fn names_are_distinct_and_found() {
        let mut names: Vec<&str> = ENGINES
            .iter()
            .flat_map(|e| std::iter::once(e.name()).chain(e.aliases().iter().copied()))
            .collect();
        let count = names.len();
        names.sort_unstable();
        names.dedup();
        assert_eq!(names.len(), count, "{names:?}");
        assert!(!names.contains(&"auto"));
        for e in ENGINES {
            assert_eq!(by_name(e.name()).map(|f| f.name()), Some(e.name()));
        }
        assert_eq!(by_name("projection").map(|e| e.name()), Some("kernel"));
        assert_eq!(by_name("events").map(|e| e.name()), Some("merge"));
        assert!(by_name("nope").is_none());
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

    /// The work estimate is `N · ⌈b/64⌉²` with `b` the bits of the largest
    /// denominator, wherever it is (radius, positions, velocities), and the
    /// cap refuses exactly the data above it (this test assumes
    /// `$STICKY_MAX_WORK` unset: the default cap `2^29`).
    #[test]
    fn work_estimate_and_its_cap() {
        use num_bigint::BigInt;
        let over = |bits: usize| BigRational::new(1.into(), BigInt::from(1) << bits);
        let int = |n: i64| BigRational::from_integer(n.into());
        // `n` particles, the denominator `2^bits` in the radius (`at = 0`),
        // the positions (1) or the velocities (2); elsewhere denominators of
        // at most 2 bits (r = 1/2).
        let scene = |n: usize, bits: usize, at: usize| {
            let d = |k: usize| if k == at { over(bits) } else { int(0) };
            let radius = if at == 0 { over(bits) } else { over(1) };
            let positions = (0..n as i64).map(|i| int(2 * i) + d(1)).collect();
            let velocities = (0..n).map(|_| d(2)).collect();
            InitialData::new(radius, positions, velocities).unwrap()
        };
        assert_eq!(largest_denominator_bits(&scene(3, 0, 2)), 2); // r = 1/2
        for at in 0..3 {
            // 2^129 has 130 bits: 3 words.
            assert_eq!(largest_denominator_bits(&scene(3, 129, at)), 130);
            assert_eq!(work_estimate(&scene(5, 129, at)), 5 * 9);
        }
        assert_eq!(MAX_WORK, 1 << 29);
        // N · w² = 2 · (2^14)² = 2^29: at the cap, accepted; one more particle
        // or one more word, refused.
        let words = |w: usize| 64 * w - 1;
        assert_eq!(work_estimate(&scene(2, words(1 << 14), 2)), MAX_WORK);
        assert!(check_work(&scene(2, words(1 << 14), 2)).is_ok());
        assert!(check_work(&scene(3, words(1 << 14), 2)).is_err());
        let e = check_work(&scene(2, words((1 << 14) + 1), 2)).unwrap_err();
        assert!(e.to_string().contains("N = 2"), "{e}");
    }
}
