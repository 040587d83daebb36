//! `--jobs K`: K units at once on one machine (scoped threads pulling the
//! next unit from a shared counter), the results in unit order whatever K.

use std::num::NonZeroUsize;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;

/// Runs `work` on every unit of `units`, `jobs` at a time, and returns the
/// results in the order of `units`. With `jobs = 1` everything runs on the
/// calling thread, in order. A unit is run exactly once; the result of a
/// unit depends on the unit alone, so the output is the same for every K.
pub fn run_units<U, R, F>(units: &[U], jobs: NonZeroUsize, work: F) -> Vec<R>
where
    U: Sync,
    R: Send,
    F: Fn(&U) -> R + Sync,
{
    let jobs = jobs.get().min(units.len().max(1));
    if jobs == 1 {
        return units.iter().map(&work).collect();
    }
    let next = AtomicUsize::new(0);
    let slots: Mutex<Vec<Option<R>>> = Mutex::new((0..units.len()).map(|_| None).collect());
    std::thread::scope(|scope| {
        for _ in 0..jobs {
            scope.spawn(|| loop {
                let k = next.fetch_add(1, Ordering::Relaxed);
                let Some(unit) = units.get(k) else { break };
                let r = work(unit);
                if let Ok(mut slots) = slots.lock() {
                    slots[k] = Some(r);
                }
            });
        }
    });
    let slots = slots.into_inner().unwrap_or_else(|p| p.into_inner());
    debug_assert!(slots.iter().all(Option::is_some), "a unit was not run");
    slots.into_iter().flatten().collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn same_results_in_order_whatever_k() {
        let units: Vec<u64> = (0..50).collect();
        let one = run_units(&units, NonZeroUsize::MIN, |u| u * u + 1);
        for k in [2, 3, 8, 64] {
            let many = run_units(&units, NonZeroUsize::new(k).unwrap(), |u| u * u + 1);
            assert_eq!(one, many, "{k} jobs");
        }
        assert_eq!(one.len(), 50);
        assert_eq!(one[7], 50);
    }
}
