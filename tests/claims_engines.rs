//! The claims of the registry run by proptest (`prop_*`) and quickcheck
//! (`qc_*`): both generate byte strings, decoded into admissible initial data
//! by `sticky::generate` (contacts, separating contacts and simultaneous
//! multi-cluster collisions on purpose), and run every case checker through
//! `sticky::claims::check_case`. A claim without a correction, and every
//! correction, must hold; a claim found false as printed is reported by the
//! ledger (`sticky claims`), with its shrunk witness, not here.

use num_rational::BigRational;
use proptest::prelude::*;
use quickcheck::{QuickCheck, TestResult};
use sticky::claims::{check_case, registry, Case, Claim};
use sticky::generate::{initial_data, Limits};

fn case(bytes: &[u8], max_n: usize) -> Case<BigRational> {
    let limits = Limits {
        max_n,
        max_den: 6,
        max_speed: 8,
    };
    Case::new(initial_data(bytes, limits), Some(10))
}

fn claims() -> Vec<Claim<BigRational>> {
    registry()
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: if cfg!(debug_assertions) { 64 } else { 256 },
        ..ProptestConfig::default()
    })]

    /// Every case claim (or its correction) on random admissible data.
    #[test]
    #[ignore = "campaign: every claim on 256 random data, about a minute; CI runs it (cargo test --release -- --ignored)"]
    fn prop_every_claim(bytes in proptest::collection::vec(any::<u8>(), 0..160), max_n in 1usize..16) {
        let c = case(&bytes, max_n);
        if let Err(v) = check_case(&claims(), &c) {
            prop_assert!(false, "{}", v);
        }
    }

    /// The same, on the paper's radius 2r = 1/N only (section 3 claims
    /// apply to every case).
    #[test]
    #[ignore = "campaign: every claim on 256 random data at 2r = 1/N, over a minute; CI runs it (cargo test --release -- --ignored)"]
    fn prop_every_claim_paper_radius(bytes in proptest::collection::vec(any::<u8>(), 1..160), max_n in 2usize..16) {
        let mut b = bytes;
        b[0] &= !0b11; // radius code 0: 2r = 1/N
        let c = case(&b, max_n);
        prop_assert!(c.paper_radius());
        if let Err(v) = check_case(&claims(), &c) {
            prop_assert!(false, "{}", v);
        }
    }
}

fn qc_property(bytes: Vec<u8>, max_n: u8) -> TestResult {
    let max_n = 1 + usize::from(max_n % 16);
    let c = case(&bytes, max_n);
    match check_case(&claims(), &c) {
        Ok(_) => TestResult::passed(),
        Err(v) => TestResult::error(v.to_string()),
    }
}

/// quickcheck's shrinking over the same checkers.
#[test]
#[ignore = "campaign: every claim on 256 quickcheck cases, tens of seconds; CI runs it (cargo test --release -- --ignored)"]
fn qc_every_claim() {
    QuickCheck::new()
        .tests(if cfg!(debug_assertions) { 64 } else { 256 })
        .quickcheck(qc_property as fn(Vec<u8>, u8) -> TestResult);
}

/// The claims found false as printed are really false: each has a
/// counterexample among a few hundred random cases (so the ledger's
/// "counterexample" statuses are reproducible, not an artefact).
#[test]
fn printed_counterexamples_reproduce() {
    use sticky::claims::Kind;
    use sticky::generate::SplitMix64;
    let claims = claims();
    let mut rng = SplitMix64::new(99);
    let cases: Vec<Case<BigRational>> = (0..300)
        .map(|k| {
            let mut b = rng.bytes(96);
            if k % 2 == 0 {
                b[0] &= !0b11;
            }
            case(&b, 2 + k % 10)
        })
        .collect();
    for claim in claims.iter().filter(|c| c.correction.is_some()) {
        if let Kind::Case(check) = &claim.kind {
            let found = cases
                .iter()
                .any(|c| (claim.applies)(c) && check(c).is_err());
            assert!(found, "{}: no counterexample found any more", claim.id);
        }
    }
}
