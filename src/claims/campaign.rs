//! `sticky claims` as a campaign (issue 38, item 3). The units are the
//! ledger's statements (each claim as printed, then its correction) cut
//! into blocks of cases: a [`Kind::Case`] statement has up to
//! [`CASE_BLOCKS`] blocks of its random cases and one unit per shipped
//! scene (the order [`ledger::run`](super::ledger::run) runs them in); a statement across N, a
//! formula or a claim not checkable is one unit.
//!
//! A shard runs its blocks of one statement in order and, once one of them
//! has a violation (shrunk to its witness as the single run does), marks
//! its later blocks of that statement [`UnitResult::Skipped`]: the single
//! run stops at the first violation too. [`entries`] walks each
//! statement's blocks in order, adds up the cases that applied and stops
//! at the first violation, so the merged ledger has the single run's
//! statuses, case counts and witnesses.

use std::ops::Range;

use num_rational::BigRational;
use serde::{Deserialize, Serialize};

use super::coq::Statement;
use super::ledger::{engines, run_case_range, run_kind, shipped_cases};
use super::ledger::{Budget, Entry, Outcome, Status};
use super::proved::with_proved;
use super::proved::Tightness;
use super::witness::WitnessData;
use super::{registry, Case, Claim, Kind};
use crate::campaign::file::{ShardLines, UnitLine};
use crate::campaign::jobs::run_units;
use crate::campaign::Shard;
use crate::progress::Progress;
use crate::rational::{parse_exact, render_exact};

/// The most blocks a statement's random cases are cut into.
pub const CASE_BLOCKS: usize = 64;

/// The budget, as every shard of one campaign has it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct ClaimsSetup {
    /// Random cases per claim.
    pub cases: usize,
    /// Largest N of a random case.
    pub max_n: usize,
    /// Largest N of the scaling checks.
    pub scaling_max_n: usize,
    /// Seed of the random cases.
    pub seed: u64,
}

impl From<Budget> for ClaimsSetup {
    fn from(b: Budget) -> Self {
        ClaimsSetup {
            cases: b.cases,
            max_n: b.max_n,
            scaling_max_n: b.scaling_max_n,
            seed: b.seed,
        }
    }
}

impl From<ClaimsSetup> for Budget {
    fn from(s: ClaimsSetup) -> Self {
        Budget {
            cases: s.cases,
            max_n: s.max_n,
            scaling_max_n: s.scaling_max_n,
            seed: s.seed,
        }
    }
}

/// One statement of the ledger.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct LedgerStatement {
    /// The claim's index in the registry.
    pub claim: usize,
    /// Printed or corrected.
    pub version: Statement,
}

/// One unit: a block of a case statement's sequence, or a whole statement.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ClaimsUnit {
    /// The statement.
    pub statement: LedgerStatement,
    /// The cases of the block (random cases `0 … cases − 1`, then the
    /// shipped scenes), or `None` for a whole statement.
    pub cases: Option<Range<usize>>,
}

/// The blocks of a case statement: the random cases cut into at most
/// [`CASE_BLOCKS`] equal blocks, then one per shipped scene.
fn blocks(cases: usize, shipped: usize) -> Vec<Range<usize>> {
    let size = cases.div_ceil(CASE_BLOCKS).max(1);
    let mut out: Vec<Range<usize>> = (0..cases)
        .step_by(size)
        .map(|a| a..(a + size).min(cases))
        .collect();
    out.extend((cases..cases + shipped).map(|k| k..k + 1));
    out
}

/// Every unit of the ledger, in the single run's order.
pub fn units(
    claims: &[Claim<BigRational>],
    setup: &ClaimsSetup,
    shipped: usize,
) -> Vec<ClaimsUnit> {
    let mut out = Vec::new();
    for (claim, c) in claims.iter().enumerate() {
        for version in [Statement::Printed, Statement::Corrected] {
            let Some(kind) = c.checker(version) else {
                continue;
            };
            let statement = LedgerStatement { claim, version };
            match kind {
                Kind::Case(_) => {
                    out.extend(
                        blocks(setup.cases, shipped)
                            .into_iter()
                            .map(|r| ClaimsUnit {
                                statement,
                                cases: Some(r),
                            }),
                    )
                }
                _ => out.push(ClaimsUnit {
                    statement,
                    cases: None,
                }),
            }
        }
    }
    out
}

/// A status as a shard writes it: the label and the reason.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct OutcomeLine {
    /// `holds`, `counterexample`, `not checkable` or `identity`.
    pub status: String,
    /// The reason of `not checkable` or `identity`.
    pub reason: Option<String>,
    /// Cases run.
    pub cases: usize,
    /// The violation and its witness scene.
    pub witness: Option<String>,
    /// The witness, machine-readable.
    pub witness_data: Option<WitnessData>,
    /// The tightness against a proved constant, per datum.
    #[serde(default)]
    pub tightness: Vec<TightnessLine>,
    /// Measurements.
    pub note: Option<String>,
}

impl From<&Outcome> for OutcomeLine {
    fn from(o: &Outcome) -> Self {
        let reason = match &o.status {
            Status::NotCheckable(r) | Status::Identity(r) => Some(r.clone()),
            Status::Holds | Status::Counterexample => None,
        };
        OutcomeLine {
            status: o.status.label().to_string(),
            reason,
            cases: o.cases,
            witness: o.witness.clone(),
            witness_data: o.witness_data.clone(),
            tightness: o.tightness.iter().map(TightnessLine::from).collect(),
            note: o.note.clone(),
        }
    }
}

/// A [`Tightness`] as a shard writes it: the numbers as exact strings.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct TightnessLine {
    /// The datum.
    pub scene: String,
    /// The N where the ratio is largest.
    pub n: usize,
    /// The measured value there.
    pub measured: String,
    /// The proved constant there.
    pub constant: String,
}

impl From<&Tightness> for TightnessLine {
    fn from(t: &Tightness) -> Self {
        TightnessLine {
            scene: t.scene.clone(),
            n: t.n,
            measured: render_exact(&t.measured),
            constant: render_exact(&t.constant),
        }
    }
}

impl TightnessLine {
    /// The tightness back.
    fn tightness(&self) -> Result<Tightness, String> {
        let num = |s: &str| parse_exact(s).map_err(|e| format!("tightness {s:?}: {e}"));
        Ok(Tightness {
            scene: self.scene.clone(),
            n: self.n,
            measured: num(&self.measured)?,
            constant: num(&self.constant)?,
        })
    }
}

impl OutcomeLine {
    /// The outcome back.
    pub fn outcome(&self) -> Result<Outcome, String> {
        let reason = || self.reason.clone().unwrap_or_default();
        let status = match self.status.as_str() {
            "holds" => Status::Holds,
            "counterexample" => Status::Counterexample,
            "not checkable" => Status::NotCheckable(reason()),
            "identity" => Status::Identity(reason()),
            other => return Err(format!("unknown status {other:?}")),
        };
        Ok(Outcome {
            status,
            cases: self.cases,
            witness: self.witness.clone(),
            witness_data: self.witness_data.clone(),
            tightness: self
                .tightness
                .iter()
                .map(TightnessLine::tightness)
                .collect::<Result<_, _>>()?,
            note: self.note.clone(),
        })
    }
}

/// One unit's result.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub enum UnitResult {
    /// A block of cases: how many applied up to the first violation
    /// (included), and its outcome.
    Cases {
        /// Cases that applied.
        applied: usize,
        /// The first violation of the block, with its witness.
        counterexample: Option<OutcomeLine>,
        /// The statement's last block, when every case of it holds: the
        /// tightness against the constant proved in Coq, per datum
        /// (`proved::with_proved`; empty for a statement without one).
        #[serde(default)]
        tightness: Vec<TightnessLine>,
    },
    /// Not run: an earlier block of the same statement in this shard has a
    /// violation, so the merged ledger stops before this block.
    Skipped,
    /// A whole statement.
    Whole(OutcomeLine),
}

/// Runs one unit.
fn run_unit(
    claims: &[Claim<BigRational>],
    unit: &ClaimsUnit,
    budget: Budget,
    shipped: &[(&'static str, Case<BigRational>)],
) -> UnitResult {
    let claim = &claims[unit.statement.claim];
    let Some(kind) = claim.checker(unit.statement.version) else {
        return UnitResult::Skipped;
    };
    let domain = claim.domain_of(unit.statement.version);
    match (kind, &unit.cases) {
        (Kind::Case(check), Some(range)) => {
            let (applied, failure) = run_case_range(
                *check,
                claim.applies,
                domain,
                budget,
                shipped,
                range.clone(),
            );
            let last = range.end == budget.cases + shipped.len();
            // The single run compares a statement that holds with its
            // proved constant after its last case; so does the last block.
            let (failure, tightness) = match failure {
                None if last => {
                    let held = Outcome {
                        status: Status::Holds,
                        cases: applied,
                        witness: None,
                        witness_data: None,
                        tightness: Vec::new(),
                        note: None,
                    };
                    let o =
                        with_proved(kind, domain, claim.id, unit.statement.version, held, budget);
                    match o.status {
                        Status::Holds => (None, o.tightness),
                        _ => (Some(o), Vec::new()),
                    }
                }
                other => (other, Vec::new()),
            };
            UnitResult::Cases {
                applied,
                counterexample: failure.as_ref().map(OutcomeLine::from),
                tightness: tightness.iter().map(TightnessLine::from).collect(),
            }
        }
        _ => UnitResult::Whole(OutcomeLine::from(
            &run_kind(kind, claim.applies, domain, budget, shipped).0,
        )),
    }
}

/// Runs shard `shard` of the ledger, `jobs` statements at a time (each
/// statement's blocks in order), telling `progress` of each statement done.
pub fn run_shard(
    setup: &ClaimsSetup,
    shard: Shard,
    jobs: std::num::NonZeroUsize,
    progress: &dyn Progress,
) -> ShardLines<UnitResult> {
    let claims: Vec<Claim<BigRational>> = registry();
    let shipped = shipped_cases();
    let all = units(&claims, setup, shipped.len());
    let mut groups: Vec<Vec<usize>> = Vec::new();
    for u in shard.units(all.len()) {
        match groups.last_mut() {
            Some(g) if all[g[0]].statement == all[u].statement => g.push(u),
            _ => groups.push(vec![u]),
        }
    }
    let budget = Budget::from(*setup);
    progress.stage("claims", Some(groups.len() as u64));
    let results = run_units(&groups, jobs, |group| {
        progress.note(claims[all[group[0]].statement.claim].id);
        let mut failed = false;
        let lines: Vec<UnitLine<UnitResult>> = group
            .iter()
            .map(|&unit| {
                let result = if failed {
                    UnitResult::Skipped
                } else {
                    run_unit(&claims, &all[unit], budget, &shipped)
                };
                failed |= matches!(
                    result,
                    UnitResult::Cases {
                        counterexample: Some(_),
                        ..
                    }
                );
                UnitLine { unit, result }
            })
            .collect();
        progress.advance(1);
        lines
    });
    progress.finish();
    ShardLines {
        units: all.len(),
        lines: results.into_iter().flatten().collect(),
    }
}

/// The outcome of one statement from its units' results, in order.
fn statement_outcome<'a>(results: impl Iterator<Item = &'a UnitResult>) -> Result<Outcome, String> {
    let mut applied = 0;
    let mut last_tightness: &[TightnessLine] = &[];
    for r in results {
        match r {
            UnitResult::Whole(o) => return o.outcome(),
            UnitResult::Cases {
                applied: k,
                counterexample,
                tightness,
            } => {
                applied += k;
                last_tightness = tightness;
                if let Some(o) = counterexample {
                    let mut outcome = o.outcome()?;
                    outcome.cases = applied;
                    return Ok(outcome);
                }
            }
            UnitResult::Skipped => {
                return Err("a block was skipped with no violation before it".to_string())
            }
        }
    }
    let tightness: Vec<Tightness> = last_tightness
        .iter()
        .map(TightnessLine::tightness)
        .collect::<Result<_, _>>()?;
    Ok(Outcome {
        status: Status::Holds,
        cases: applied,
        witness: None,
        witness_data: None,
        note: super::proved::note(&tightness),
        tightness,
    })
}

/// The ledger's entries from every unit's result, in unit order (what
/// [`ledger::run`](super::ledger::run) returns for the same budget).
pub fn entries(setup: &ClaimsSetup, results: &[UnitResult]) -> Result<Vec<Entry>, String> {
    let claims: Vec<Claim<BigRational>> = registry();
    let all = units(&claims, setup, shipped_cases().len());
    if all.len() != results.len() {
        return Err(format!(
            "{} results for the {} units of this budget (another version of sticky?)",
            results.len(),
            all.len()
        ));
    }
    let outcome = |statement: LedgerStatement| {
        let of_it = all
            .iter()
            .zip(results)
            .filter(|(u, _)| u.statement == statement)
            .map(|(_, r)| r);
        statement_outcome(of_it).map_err(|e| format!("{}: {e}", claims[statement.claim].id))
    };
    let mut out = Vec::with_capacity(claims.len());
    for (claim, c) in claims.iter().enumerate() {
        let mut printed = outcome(LedgerStatement {
            claim,
            version: Statement::Printed,
        })?;
        if let (Status::Holds, Some(why)) = (&printed.status, c.identity) {
            printed.status = Status::Identity(why.to_string());
        }
        let correction = match &c.correction {
            Some(corr) => Some((
                corr.statement,
                outcome(LedgerStatement {
                    claim,
                    version: Statement::Corrected,
                })?,
                corr.conclusion,
            )),
            None => None,
        };
        out.push(Entry {
            id: c.id,
            section: c.section,
            statement: c.statement,
            engines: engines(&c.kind),
            outcome: printed,
            correction,
        });
    }
    Ok(out)
}

/// [`ledger::run`](super::ledger::run) with `jobs` statements at a time: the whole campaign as
/// one shard, merged.
pub fn run_jobs(
    budget: Budget,
    jobs: std::num::NonZeroUsize,
    progress: &dyn Progress,
) -> Result<Vec<Entry>, String> {
    let setup = ClaimsSetup::from(budget);
    let lines = run_shard(&setup, Shard::WHOLE, jobs, progress);
    let results: Vec<UnitResult> = lines.lines.into_iter().map(|l| l.result).collect();
    entries(&setup, &results)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn blocks_cover_the_cases_once() {
        for (cases, shipped) in [(0, 3), (1, 0), (5, 2), (200, 9), (1000, 1), (64, 0)] {
            let b = blocks(cases, shipped);
            assert!(b.len() <= CASE_BLOCKS + shipped);
            let flat: Vec<usize> = b.iter().flat_map(Clone::clone).collect();
            assert_eq!(flat, (0..cases + shipped).collect::<Vec<_>>(), "{cases}");
        }
    }
}

#[cfg(test)]
mod shard_tests {
    use super::*;

    /// The outcome of one statement when its units are spread over
    /// `count` shards, each skipping its later blocks after a violation.
    fn sharded(
        claims: &[Claim<BigRational>],
        all: &[ClaimsUnit],
        statement: LedgerStatement,
        count: usize,
        budget: Budget,
        shipped: &[(&'static str, Case<BigRational>)],
    ) -> Outcome {
        let mut results = vec![None; all.len()];
        for index in 0..count {
            let mut failed = false;
            for u in (Shard { index, count }).units(all.len()) {
                if all[u].statement != statement {
                    continue;
                }
                let r = if failed {
                    UnitResult::Skipped
                } else {
                    run_unit(claims, &all[u], budget, shipped)
                };
                failed |= matches!(
                    r,
                    UnitResult::Cases {
                        counterexample: Some(_),
                        ..
                    }
                );
                results[u] = Some(r);
            }
        }
        statement_outcome(results.iter().flatten()).unwrap()
    }

    /// Blocks of every case statement of the first claims, spread over 1, 3
    /// and 4 shards, add up to the single run's outcome (status, cases,
    /// witness): one that holds and one refuted by a shrunk random witness
    /// at least.
    #[test]
    #[ignore = "campaign: twelve claims' case statements, 4 times each, about 70 s"]
    fn blocks_merge_to_the_single_run_outcome() {
        let claims: Vec<Claim<BigRational>> = registry();
        let shipped = shipped_cases();
        let setup = ClaimsSetup {
            cases: 10,
            max_n: 4,
            scaling_max_n: 8,
            seed: 0x5EED,
        };
        let budget = Budget::from(setup);
        let all = units(&claims, &setup, shipped.len());
        let mut seen = (false, false);
        for (claim, c) in claims.iter().enumerate().take(12) {
            for version in [Statement::Printed, Statement::Corrected] {
                let Some(kind @ Kind::Case(_)) = c.checker(version) else {
                    continue;
                };
                let domain = c.domain_of(version);
                let single = run_kind(kind, c.applies, domain, budget, &shipped).0;
                let single = with_proved(kind, domain, c.id, version, single, budget);
                seen.0 |= single.status == Status::Holds;
                seen.1 |= single.status == Status::Counterexample;
                for count in [1, 3, 4] {
                    let merged = sharded(
                        &claims,
                        &all,
                        LedgerStatement { claim, version },
                        count,
                        budget,
                        &shipped,
                    );
                    assert_eq!(
                        OutcomeLine::from(&merged),
                        OutcomeLine::from(&single),
                        "{} {version:?}, {count} shards",
                        c.id
                    );
                }
            }
        }
        assert_eq!(seen, (true, true), "a claim that holds and one refuted");
    }
}
