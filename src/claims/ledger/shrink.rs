//! The ledger's random cases, drawn from the generator's bytes, and the
//! greedy shrinking of those bytes to a small witness scene.

use num_rational::BigRational;

use super::found::{failure_in_domain, Found};
use crate::claims::domain::Domain;
use crate::claims::{Case, CaseCheck};
use crate::fast::kernel;
use crate::generate::{initial_data, Limits, SplitMix64};

/// A random case from `seed`, with the generator bytes (for shrinking).
pub(super) fn random_bytes(rng: &mut SplitMix64, max_n: usize) -> (Vec<u8>, Limits) {
    let n = 1 + (rng.next_u64() % max_n.max(1) as u64) as usize;
    let limits = Limits {
        max_n: n,
        max_den: 6,
        max_speed: 8,
    };
    (rng.bytes(6 * n + 8), limits)
}

/// The ledger's cases compute their states with the integer kernel
/// ([`kernel::state_of_data`]): the projection formula, equal field by field
/// to the generic one and cheaper (timing in `docs/journal.md`).
pub(super) fn case_of(bytes: &[u8], limits: Limits) -> Case<BigRational> {
    Case::new(initial_data(bytes, limits), None).with_engine(kernel::state_of_data)
}

/// Greedy shrinking of the generator input while `check` still fails
/// inside `domain` ([`failure_in_domain`]).
pub(super) fn shrink(
    bytes: Vec<u8>,
    limits: Limits,
    check: CaseCheck<BigRational>,
    domain: &Domain,
) -> (Vec<u8>, Limits, Found) {
    let fails =
        |b: &[u8], l: Limits| -> Option<Found> { failure_in_domain(check, &case_of(b, l), domain) };
    let mut best = bytes;
    let mut lim = limits;
    let Some(mut v) = fails(&best, lim) else {
        unreachable_shrink()
    };
    let mut budget = 3000usize;
    // Fewer particles first.
    while lim.max_n > domain.min_n.max(1) && budget > 0 {
        budget -= 1;
        let l = Limits {
            max_n: lim.max_n - 1,
            ..lim
        };
        match fails(&best, l) {
            Some(w) => {
                lim = l;
                v = w;
            }
            None => break,
        }
    }
    let mut chunk = best.len().max(1);
    while chunk >= 1 && budget > 0 {
        let mut i = 0;
        while i < best.len() && budget > 0 {
            budget -= 1;
            let mut cand = best.clone();
            cand.drain(i..(i + chunk).min(best.len()));
            if let Some(w) = fails(&cand, lim) {
                best = cand;
                v = w;
            } else {
                i += chunk;
            }
        }
        chunk /= 2;
    }
    for i in 0..best.len() {
        for target in [0u8, best[i] / 2, best[i].saturating_sub(1)] {
            if budget == 0 || target >= best[i] {
                continue;
            }
            budget -= 1;
            let mut cand = best.clone();
            cand[i] = target;
            if let Some(w) = fails(&cand, lim) {
                best = cand;
                v = w;
            }
        }
    }
    (best, lim, v)
}

#[cold]
fn unreachable_shrink() -> ! {
    panic!("shrink called on a passing input")
}
