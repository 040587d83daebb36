//! Running the registry: each claim's checker over its cases (random data,
//! then the shipped scenes), its correction, and the whole ledger.

use num_rational::BigRational;

use super::counterexample::{random_counterexample, shipped_counterexample, timeless};
use super::found::failure_in_domain;
use super::shrink::{case_of, random_bytes};
use super::{Budget, Entry, Outcome, Status};
use crate::claims::coq::Statement;
use crate::claims::domain::Domain;
use crate::claims::proved::with_proved;
use crate::claims::{scaling, Case, CaseCheck, Claim, Kind};
use crate::fast::kernel;
use crate::generate::SplitMix64;
use crate::progress::Progress;
use crate::scene;

/// The engines that call every [`Kind::Case`] checker of the registry
/// (kept in step with the test suites: see README "Claims").
pub const CASE_ENGINES: &[&str] = &["ledger", "proptest", "quickcheck", "exhaustive", "fuzz"];

pub(crate) fn shipped_cases() -> Vec<(&'static str, Case<BigRational>)> {
    scene::SHIPPED
        .iter()
        .filter_map(|(name, text)| {
            let s = scene::parse(text).ok()?;
            let limit = Some(if s.data.n() > 100 { 4 } else { 8 });
            Some((
                *name,
                Case::new(s.data, limit).with_engine(kernel::state_of_data),
            ))
        })
        .collect()
}

/// Runs one case-checker over the random cases then the shipped scenes,
/// keeping only failures inside `domain`.
fn run_case_check(
    check: CaseCheck<BigRational>,
    applies: fn(&Case<BigRational>) -> bool,
    domain: &Domain,
    budget: Budget,
    shipped: &[(&'static str, Case<BigRational>)],
) -> Outcome {
    let mut rng = SplitMix64::new(budget.seed);
    let mut cases = 0;
    for _ in 0..budget.cases {
        let (bytes, limits) = random_bytes(&mut rng, budget.max_n);
        let case = case_of(&bytes, limits);
        if !applies(&case) {
            continue;
        }
        cases += 1;
        if failure_in_domain(check, &case, domain).is_some() {
            return random_counterexample(cases, bytes, limits, check, domain);
        }
    }
    for (name, case) in shipped {
        if !applies(case) {
            continue;
        }
        cases += 1;
        if let Some(found) = failure_in_domain(check, case, domain) {
            return shipped_counterexample(cases, name, &found, domain);
        }
    }
    Outcome {
        status: Status::Holds,
        cases,
        witness: None,
        note: None,
        witness_data: None,
        tightness: Vec::new(),
    }
}

pub(crate) fn run_kind(
    kind: &Kind<BigRational>,
    applies: fn(&Case<BigRational>) -> bool,
    domain: &Domain,
    budget: Budget,
    shipped: &[(&'static str, Case<BigRational>)],
) -> (Outcome, Vec<&'static str>) {
    match kind {
        Kind::Case(check) => (
            run_case_check(*check, applies, domain, budget, shipped),
            engines(kind),
        ),
        Kind::Scaling(check) => {
            let sb = scaling::Budget::up_to(budget.scaling_max_n);
            let outcome = match check(sb) {
                Ok(reports) => Outcome {
                    status: Status::Holds,
                    cases: reports.iter().map(|r| r.cases).sum(),
                    witness: None,
                    witness_data: None,
                    tightness: reports.iter().filter_map(|r| r.tightness.clone()).collect(),
                    note: Some(
                        reports
                            .iter()
                            .map(|r| r.summary())
                            .collect::<Vec<_>>()
                            .join("; "),
                    ),
                },
                Err(v) => Outcome {
                    status: Status::Counterexample,
                    // The values of the scene that failed, one per N.
                    cases: scaling::ns(sb).len(),
                    witness_data: Some(timeless(&v, domain)),
                    tightness: Vec::new(),
                    witness: Some(v.witness),
                    note: None,
                },
            };
            (outcome, engines(kind))
        }
        Kind::Formula(check) => {
            let outcome = match check() {
                Ok(()) => Outcome {
                    status: Status::Holds,
                    cases: 1,
                    witness: None,
                    note: None,
                    witness_data: None,
                    tightness: Vec::new(),
                },
                Err(v) => Outcome {
                    status: Status::Counterexample,
                    cases: 1,
                    witness_data: Some(timeless(&v, domain)),
                    tightness: Vec::new(),
                    witness: Some(v.witness),
                    note: None,
                },
            };
            (outcome, engines(kind))
        }
        Kind::NotCheckable(reason) => (
            Outcome {
                status: Status::NotCheckable((*reason).to_string()),
                cases: 0,
                witness: None,
                note: None,
                witness_data: None,
                tightness: Vec::new(),
            },
            engines(kind),
        ),
    }
}

/// The domain of every corrected statement: a correction must hold on
/// every case, at every probe time.
pub(crate) const CORRECTION_DOMAIN: Domain = Domain::EVERY_T;

/// Runs one claim of the registry (and its correction) with `budget`,
/// as [`run`] does for each.
pub fn run_claim(claim: &Claim<BigRational>, budget: Budget) -> Entry {
    entry(claim, budget, &shipped_cases())
}

fn entry(
    claim: &Claim<BigRational>,
    budget: Budget,
    shipped: &[(&'static str, Case<BigRational>)],
) -> Entry {
    let (outcome, engines) = run_kind(&claim.kind, claim.applies, &claim.domain, budget, shipped);
    let mut outcome = with_proved(
        &claim.kind,
        &claim.domain,
        claim.id,
        Statement::Printed,
        outcome,
        budget,
    );
    if let (Status::Holds, Some(why)) = (&outcome.status, claim.identity) {
        outcome.status = Status::Identity(why.to_string());
    }
    let correction = claim.correction.as_ref().map(|c| {
        let (o, _) = run_kind(&c.check, claim.applies, &CORRECTION_DOMAIN, budget, shipped);
        let o = with_proved(
            &c.check,
            &CORRECTION_DOMAIN,
            claim.id,
            Statement::Corrected,
            o,
            budget,
        );
        (c.statement, o, c.conclusion)
    });
    Entry {
        id: claim.id,
        section: claim.section,
        statement: claim.statement,
        engines,
        outcome,
        correction,
    }
}

/// The engines that check a statement of this kind.
pub(crate) fn engines(kind: &Kind<BigRational>) -> Vec<&'static str> {
    match kind {
        Kind::Case(_) => CASE_ENGINES.to_vec(),
        Kind::Scaling(_) => vec!["ledger (across N)"],
        Kind::Formula(_) => vec!["ledger (exact formula)", "cargo test"],
        Kind::NotCheckable(_) => vec![],
    }
}

/// A block of a case-checker's sequence (as [`run_case_check`] runs it:
/// the random cases `0 … cases − 1`, then the shipped scenes): how many of
/// the cases in `range` applied up to the first violation (included), and
/// that violation's outcome, whose `cases` is that count. A campaign's
/// shard runs blocks; `claims::campaign` adds the counts up.
#[cfg_attr(not(feature = "json"), allow(dead_code))]
pub(crate) fn run_case_range(
    check: CaseCheck<BigRational>,
    applies: fn(&Case<BigRational>) -> bool,
    domain: &Domain,
    budget: Budget,
    shipped: &[(&'static str, Case<BigRational>)],
    range: std::ops::Range<usize>,
) -> (usize, Option<Outcome>) {
    let mut rng = SplitMix64::new(budget.seed);
    let mut cases = 0;
    for k in 0..range.end {
        if k < budget.cases && k < range.start {
            // The generator's draws of case k, skipped: its size, then its
            // bytes (as `random_bytes` draws them).
            let n = 1 + (rng.next_u64() % budget.max_n.max(1) as u64) as usize;
            rng.skip(6 * n + 8);
        } else if k < budget.cases {
            let (bytes, limits) = random_bytes(&mut rng, budget.max_n);
            let case = case_of(&bytes, limits);
            if !applies(&case) {
                continue;
            }
            cases += 1;
            if failure_in_domain(check, &case, domain).is_some() {
                let outcome = random_counterexample(cases, bytes, limits, check, domain);
                return (cases, Some(outcome));
            }
        } else if k >= range.start {
            let Some((name, case)) = shipped.get(k - budget.cases) else {
                break;
            };
            if !applies(case) {
                continue;
            }
            cases += 1;
            if let Some(found) = failure_in_domain(check, case, domain) {
                let outcome = shipped_counterexample(cases, name, &found, domain);
                return (cases, Some(outcome));
            }
        }
    }
    (cases, None)
}

/// Runs the whole registry, telling `progress` of each claim as it starts
/// (one stage, `claims`, with one step per claim). When `progress` asks to
/// stop ([`Progress::cancelled`], Ctrl-C in Python) the run ends between two
/// claims and the entries so far are returned.
pub fn run(budget: Budget, progress: &dyn Progress) -> Vec<Entry> {
    let shipped = shipped_cases();
    let claims: Vec<Claim<BigRational>> = crate::claims::registry();
    let mut out = Vec::with_capacity(claims.len());
    progress.stage("claims", Some(claims.len() as u64));
    for claim in &claims {
        if progress.cancelled() {
            break;
        }
        progress.note(claim.id);
        out.push(entry(claim, budget, &shipped));
        progress.advance(1);
    }
    progress.finish();
    out
}
