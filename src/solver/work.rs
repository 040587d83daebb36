//! The work check of the [`Solver`](crate::solver::Solver): data whose
//! exact answer would take hopelessly long are refused up front, with a
//! message that says why and what to do.

use num_rational::BigRational;

use crate::error::Error;
use crate::fast::engine::{Blockwise, ExactEngine, GenericProjection, Kernel};
use crate::initial::InitialData;
use crate::solver::cost::{largest_denominator_bits, Cost};

/// The default cap of [`WorkCap::Plain`], in 64-bit word operations: `2^29`
/// (at the rate of the `BigInt` arithmetic here, minutes of work).
pub const MAX_WORK: u64 = 1 << 29;

/// The default cap of [`WorkCap::Watched`]: `2^35` word operations, 64
/// times [`MAX_WORK`] — tens of minutes, long but not hopeless.
pub const MAX_WATCHED_WORK: u64 = 1 << 35;

/// The environment variable that sets the cap of every work check.
pub const WORK_VAR: &str = "STICKY_MAX_WORK";

/// How much work the caller accepts before it is refused up front.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum WorkCap {
    /// Work that may run unseen: [`MAX_WORK`].
    #[default]
    Plain,
    /// Work that shows its progress and can be interrupted (the command
    /// line's bar, Python's Ctrl-C): only what is hopeless is refused,
    /// above [`MAX_WATCHED_WORK`].
    Watched,
    /// This many word operations, whatever `$STICKY_MAX_WORK` says: a
    /// caller's own cap (the environment variable sets the two defaults
    /// above).
    Operations(u64),
}

impl WorkCap {
    /// The cap in word operations: the caller's own
    /// ([`WorkCap::Operations`]), else `$STICKY_MAX_WORK` when set, else
    /// this kind's default.
    pub fn operations(self) -> u64 {
        let default = match self {
            WorkCap::Plain => MAX_WORK,
            WorkCap::Watched => MAX_WATCHED_WORK,
            WorkCap::Operations(cap) => return cap,
        };
        std::env::var(WORK_VAR)
            .ok()
            .and_then(|v| v.trim().parse::<u64>().ok())
            .unwrap_or(default)
    }
}

/// A lower bound on the word operations of the common-denominator engines
/// on `data`: `N · ⌈b/64⌉²`, `b` the bits of the common denominator of the
/// data (radius, positions, velocities: [`Cost::of`]), at least the largest
/// single one. Both fast engines scale the data to common denominators
/// (`df:translat-x`) and reduce each answer to lowest terms (a gcd on
/// numbers of that size, quadratic in their length).
pub fn work_estimate(data: &InitialData<BigRational>) -> u64 {
    let words = Cost::of(data).common_denominator.bits().div_ceil(64);
    (data.n() as u64).saturating_mul(words.saturating_mul(words))
}

/// The work check of the integer kernel with the plain cap
/// ([`work_estimate`] against [`WorkCap::Plain`]).
pub fn check_work(data: &InitialData<BigRational>) -> Result<(), Error> {
    check_work_for(data, &Kernel, WorkCap::Plain, None)
}

/// Refuses `data` when `engine` needs more than `cap` word operations on
/// them: the generic projections work on local denominators (the largest
/// single one), the others on the common denominator (`cost`'s, computed
/// here when not given).
pub fn check_work_for(
    data: &InitialData<BigRational>,
    engine: &dyn ExactEngine,
    cap: WorkCap,
    cost: Option<&Cost>,
) -> Result<(), Error> {
    let cap = cap.operations();
    let local = [GenericProjection.name(), Blockwise.name()].contains(&engine.name());
    // The engines on local denominators need only the largest one: the
    // running lcm of `Cost::of` (not interruptible, long on hostile data)
    // is computed for the others alone, and only when not given.
    let common = if local {
        None
    } else {
        Some(cost.copied().unwrap_or_else(|| Cost::of(data)))
    };
    let bits = match &common {
        None => largest_denominator_bits(data),
        Some(cost) => cost.common_denominator.bits(),
    };
    let words = bits.div_ceil(64);
    let work = (data.n() as u64).saturating_mul(words.saturating_mul(words));
    if work <= cap {
        return Ok(());
    }
    let what = match common {
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

#[cfg(test)]
mod tests {
    use super::*;
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
