//! The ledger runner: runs every claim of the [`registry`](fn@super::registry)
//! and computes its status — never typed in.
//!
//! * [`Kind::Case`] claims run on the shipped scenes and on random admissible
//!   data decoded by [`crate::generate`]; the first violation is shrunk
//!   (greedy byte-level shrinking of the generator input: drop chunks, then
//!   lower bytes) to a small exact witness scene.
//! * [`Kind::Scaling`] claims run across N on quantile-sampled data.
//! * [`Kind::Formula`] claims are checked once, exactly.
//!
//! Statuses: `holds` (no counterexample in all cases run), `counterexample`
//! (with the witness), `not checkable` (with the reason).

use num_rational::BigRational;

use super::coq::Statement;
use super::domain::{open_intervals, Domain, InTime};
use super::proved::with_proved;
use super::witness::{self, Failure, WitnessData, WitnessScene};
use super::{scaling, Case, Claim, Kind, Violation};
use crate::fast::kernel;
use crate::generate::{initial_data, Limits, SplitMix64};
use crate::progress::Progress;
use crate::scalar::Scalar;
use crate::scene::{self, particles_toml};

/// The engines that call every [`Kind::Case`] checker of the registry
/// (kept in step with the test suites: see README "Claims").
pub const CASE_ENGINES: &[&str] = &["ledger", "proptest", "quickcheck", "exhaustive", "fuzz"];

/// How much work the ledger does.
#[derive(Debug, Clone, Copy)]
pub struct Budget {
    /// Random cases per claim.
    pub cases: usize,
    /// Largest N of a random case.
    pub max_n: usize,
    /// Largest N of the scaling checks.
    pub scaling_max_n: usize,
    /// Seed of the random cases.
    pub seed: u64,
}

impl Budget {
    /// The budget a caller asks for (the command line's flags, Python's
    /// arguments): each field its [default](Budget::default) when not
    /// given, the sizes clamped to what the checks need (a random case
    /// has at least 1 particle, the checks across N go up to at least 8).
    pub fn asked(
        cases: Option<usize>,
        max_n: Option<usize>,
        scaling_max_n: Option<usize>,
        seed: Option<u64>,
    ) -> Budget {
        let d = Budget::default();
        Budget {
            cases: cases.unwrap_or(d.cases),
            max_n: max_n.unwrap_or(d.max_n).max(1),
            scaling_max_n: scaling_max_n.unwrap_or(d.scaling_max_n).max(8),
            seed: seed.unwrap_or(d.seed),
        }
    }
}

impl Default for Budget {
    fn default() -> Self {
        Budget {
            cases: 200,
            max_n: 24,
            scaling_max_n: 4096,
            seed: 0x5EED,
        }
    }
}

/// A computed status.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Status {
    /// No counterexample in all cases run.
    Holds,
    /// A counterexample was found.
    Counterexample,
    /// Not checkable, with the reason.
    NotCheckable(String),
    /// Its checker passed, but the claim holds for any path whatever the
    /// dynamics (with the reason): not counted as "holds".
    Identity(String),
}

impl Status {
    /// `holds`, `counterexample`, `not checkable` or `identity`.
    pub fn label(&self) -> &'static str {
        match self {
            Status::Holds => "holds",
            Status::Counterexample => "counterexample",
            Status::NotCheckable(_) => "not checkable",
            Status::Identity(_) => "identity",
        }
    }
}

/// The result of running one statement.
#[derive(Debug, Clone)]
pub struct Outcome {
    /// The status.
    pub status: Status,
    /// Cases run.
    pub cases: usize,
    /// The violation, with the exact witness scene when there is one.
    pub witness: Option<String>,
    /// Measurements (scaling checks).
    pub note: Option<String>,
    /// The counterexample in machine-readable form.
    pub witness_data: Option<WitnessData>,
    /// The tightness against a constant proved in Coq, per datum (scaling
    /// checks of [`super::proved::PROVED`] quantities; empty otherwise).
    pub tightness: Vec<super::proved::Tightness>,
}

/// One row of the ledger.
#[derive(Debug, Clone)]
pub struct Entry {
    /// Claim id.
    pub id: &'static str,
    /// Section.
    pub section: &'static str,
    /// The statement as printed.
    pub statement: &'static str,
    /// Engines that check it.
    pub engines: Vec<&'static str>,
    /// The outcome for the statement as printed.
    pub outcome: Outcome,
    /// For a counterexample: the corrected statement, its outcome, and
    /// whether the enclosing result's conclusion holds.
    pub correction: Option<(&'static str, Outcome, &'static str)>,
}

/// What the symbolic prover established for one claim (`sticky prove`;
/// the caller fills these from `prove::record`, since the ledger sits below
/// the prover).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Proof {
    /// The ledger cell: `N ≤ 3`, `N ≤ 3 (N = 4: unknown)`, `refuted at N = 2`.
    pub cell: String,
    /// The hypotheses of the largest N proved, in words.
    pub hypotheses: Option<String>,
}

/// Proofs by claim id (` (corrected)` suffix for a corrected statement).
pub type Proofs = std::collections::BTreeMap<String, Proof>;

/// A random case from `seed`, with the generator bytes (for shrinking).
fn random_bytes(rng: &mut SplitMix64, max_n: usize) -> (Vec<u8>, Limits) {
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
/// to the generic one, ~9× cheaper on `N = 1000`.
fn case_of(bytes: &[u8], limits: Limits) -> Case<BigRational> {
    Case::new(initial_data(bytes, limits), None).with_engine(kernel::state_of_data)
}

/// A failure of a checker inside its statement's domain: the violation
/// at each time where it is shown (two times of one open interval between
/// collisions for an a.e.-in-`t` statement; the checker's own probe times
/// otherwise).
#[derive(Debug, Clone)]
pub struct Found {
    /// The violation at each time, in order.
    pub violations: Vec<Violation>,
    /// The times (empty when the checker ran on all its probe times).
    pub times: Vec<BigRational>,
    /// The open interval holding `times`.
    pub interval: Option<super::domain::OpenInterval<BigRational>>,
}

/// The first failure of `check` on `case` inside `domain`, or `None`. A
/// datum outside the domain's hypotheses (`N`, `u⁰ ∈ H`) is skipped; an
/// a.e.-in-`t` statement is run at two times of each open interval between
/// collisions, one time alone at a time, and fails only if it fails at
/// both. Every returned witness passes [`Domain::admits`].
pub fn failure_in_domain(
    check: super::CaseCheck<BigRational>,
    case: &Case<BigRational>,
    domain: &Domain,
) -> Option<Found> {
    domain.admits_datum(&case.traj).ok()?;
    if domain.time != InTime::AlmostEvery {
        return check(case).err().map(|v| Found {
            violations: vec![v],
            times: Vec::new(),
            interval: None,
        });
    }
    let at = |t: &BigRational| {
        check(
            &Case::with_times(case.traj.clone(), vec![t.clone()])
                .with_engine(kernel::state_of_data),
        )
        .err()
    };
    let intervals = open_intervals(&case.traj);
    // One run over every interval's first time first: most cases pass.
    let firsts: Vec<BigRational> = intervals.iter().map(|iv| iv.times[0].clone()).collect();
    check(&Case::with_times(case.traj.clone(), firsts).with_engine(kernel::state_of_data)).err()?;
    for iv in intervals {
        let Some(a) = at(&iv.times[0]) else { continue };
        let Some(b) = at(&iv.times[1]) else { continue };
        let times = iv.times.to_vec();
        debug_assert!(domain.admits(&case.traj, &times).is_ok());
        domain.admits(&case.traj, &times).ok()?;
        return Some(Found {
            violations: vec![a, b],
            times,
            interval: Some(iv),
        });
    }
    None
}

/// Greedy shrinking of the generator input while `check` still fails
/// inside `domain` ([`failure_in_domain`]).
fn shrink(
    bytes: Vec<u8>,
    limits: Limits,
    check: super::CaseCheck<BigRational>,
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

/// The witness text and data of a failure found on `data`.
fn report(
    found: &Found,
    scene: WitnessScene,
    domain: &Domain,
    tail: String,
) -> (String, WitnessData) {
    let mut text = found.violations[0].witness.clone();
    if let (Some(iv), [_, b]) = (&found.interval, found.violations.as_slice()) {
        text.push_str(&format!(
            "\nfor a.e. t: it fails at t = {} and at t = {}, both in the open interval ({}, {}) between collision instants; the second: {}",
            found.times[0].render(),
            found.times[1].render(),
            iv.lo.render(),
            iv.hi.as_ref().map_or("∞".to_string(), |h| h.render()),
            b.witness.lines().next().unwrap_or("")
        ));
    }
    text.push_str(&tail);
    let data = WitnessData {
        scene,
        domain: witness::DomainData::of(domain),
        times: found
            .times
            .iter()
            .map(crate::rational::render_exact)
            .collect(),
        interval: found.interval.as_ref().map(witness::interval),
        failures: found.violations.iter().map(Failure::of).collect(),
    };
    (text, data)
}

/// The outcome of a random case that fails `check` inside `domain`: shrunk
/// to a small witness scene; `cases` counts the cases run, this one included.
fn random_counterexample(
    cases: usize,
    bytes: Vec<u8>,
    limits: Limits,
    check: super::CaseCheck<BigRational>,
    domain: &Domain,
) -> Outcome {
    let (b, l, found) = shrink(bytes, limits, check, domain);
    let data = initial_data(&b, l);
    let (text, wd) = report(
        &found,
        witness::particles(&data),
        domain,
        format!(
            "\nwitness scene (N = {}):\n{}",
            data.n(),
            particles_toml(&data, Some("witness"))
        ),
    );
    Outcome {
        status: Status::Counterexample,
        cases,
        witness: Some(text),
        note: None,
        witness_data: Some(wd),
        tightness: Vec::new(),
    }
}

/// The outcome of a shipped scene that fails inside `domain`: the
/// violation and the file.
fn shipped_counterexample(cases: usize, name: &str, found: &Found, domain: &Domain) -> Outcome {
    let (text, wd) = report(
        found,
        WitnessScene::Shipped {
            name: name.to_string(),
        },
        domain,
        format!("\nwitness: scenes/{name}.toml"),
    );
    Outcome {
        status: Status::Counterexample,
        cases,
        witness: Some(text),
        note: None,
        witness_data: Some(wd),
        tightness: Vec::new(),
    }
}

/// Runs one case-checker over the random cases then the shipped scenes,
/// keeping only failures inside `domain`.
fn run_case_check(
    check: super::CaseCheck<BigRational>,
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

/// The witness data of a claim checked without a particle datum (a
/// formula, or a scaling check on a shipped scene named first in the
/// witness text).
pub(crate) fn timeless(v: &Violation, domain: &Domain) -> WitnessData {
    let name = v.witness.split(':').next().unwrap_or("");
    let scene = if scene::shipped(name).is_some() {
        WitnessScene::Shipped {
            name: name.to_string(),
        }
    } else if let Some((blocks, _)) = v
        .witness
        .strip_prefix("blocks = ")
        .and_then(|rest| rest.split_once(", N = "))
    {
        WitnessScene::Macro {
            blocks: blocks.to_string(),
        }
    } else {
        WitnessScene::Formula
    };
    WitnessData {
        scene,
        domain: witness::DomainData::of(domain),
        times: Vec::new(),
        interval: None,
        failures: vec![Failure::of(v)],
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
    check: super::CaseCheck<BigRational>,
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
    let claims: Vec<Claim<BigRational>> = super::registry();
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

/// The number of claims of each status.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Counts {
    /// `holds`.
    pub holds: usize,
    /// `counterexample`.
    pub counterexamples: usize,
    /// `not checkable`.
    pub not_checkable: usize,
    /// `identity` (a checker that passes whatever the dynamics).
    pub identities: usize,
}

impl std::fmt::Display for Counts {
    /// `54 hold, 19 counterexamples, 0 not checkable, 1 identity`.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{} hold, {} counterexample{}, {} not checkable, {} identit{}",
            self.holds,
            self.counterexamples,
            if self.counterexamples == 1 { "" } else { "s" },
            self.not_checkable,
            self.identities,
            if self.identities == 1 { "y" } else { "ies" }
        )
    }
}

/// Counts by status.
pub fn counts(entries: &[Entry]) -> Counts {
    let mut c = Counts::default();
    for e in entries {
        match e.outcome.status {
            Status::Holds => c.holds += 1,
            Status::Counterexample => c.counterexamples += 1,
            Status::NotCheckable(_) => c.not_checkable += 1,
            Status::Identity(_) => c.identities += 1,
        }
    }
    c
}

fn first_line(s: &str) -> &str {
    s.lines().next().unwrap_or("")
}

/// The ledger as a plain-text table.
pub fn table(entries: &[Entry]) -> String {
    let mut out = String::new();
    out.push_str(&format!(
        "{} claims: {}\n{NUMBERING}\n\n",
        entries.len(),
        counts(entries)
    ));
    let w = entries.iter().map(|e| e.id.len()).max().unwrap_or(10);
    for e in entries {
        out.push_str(&format!(
            "{:<w$}  {:<14}  {:>6} cases\n",
            e.id,
            e.outcome.status.label(),
            e.outcome.cases
        ));
        if let Some(wit) = &e.outcome.witness {
            out.push_str(&format!("{:<w$}    ↳ {}\n", "", first_line(wit)));
        }
        if let Some((_, o, _)) = &e.correction {
            out.push_str(&format!(
                "{:<w$}    corrected statement: {} ({} cases)\n",
                "",
                o.status.label(),
                o.cases
            ));
        }
    }
    out
}

#[cfg(feature = "json")]
pub use super::json::json;

/// The index convention of the ledger's texts, said once at the top of the
/// table and of `CLAIMS.md` (issue 28 item 5: every program output indexes
/// particles from 0). The crate-private `FromPaper` of the claims module
/// turns the paper's subscripts into these indices.
pub const NUMBERING: &str = "Indices: quoted statements (the `>` lines of CLAIMS.md, the `statement` fields of `--json`) keep the paper's numbering, particles 1…N and λ_i for the pair (i, i+1); everything the program writes (witnesses, violations, measured notes) indexes from 0 as `sticky run --json` does: particles x[0] … x[N−1], pair (i, i+1), λ[i] the multiplier of pair (i, i+1) (the paper's λ_{i+1}; λ[−1] = λ[N−1] = 0 at the ends), x[−1] the artificial particle of section 3 (the paper's x_0). A formula with a symbolic i (x_i, λ_{i−1}) is in the paper's notation, and a text that gives a paper index says \"paper's numbering\".";

/// The ledger as a Markdown document (`CLAIMS.md`). It contains no
/// timings, so it is reproducible for a given budget.
/// `proofs` fills the column "proved for all real data" (empty: `—`).
pub fn markdown(entries: &[Entry], budget: Budget, proofs: &Proofs) -> String {
    let mut out = String::new();
    out.push_str("# Claims ledger\n\n");
    out.push_str("Generated by `sticky claims --markdown` (do not edit: `tests/claims_ledger.rs` checks that this file is current).\n");
    out.push_str(&format!(
        "Budget: {} random cases per claim (N ≤ {}, seed {:#x}) plus the shipped scenes; scaling checks for N = 4 … {}.\n\n",
        budget.cases, budget.max_n, budget.seed, budget.scaling_max_n
    ));
    out.push_str(&format!(
        "**{} claims: {}.** Every status below is computed by running the checkers; \"holds\" means no counterexample in the cases run, not a proof; \"identity\" means the checker passed but cannot fail on any consistent path, whatever the dynamics.\n\n",
        entries.len(),
        counts(entries)
    ));
    out.push_str(&format!("{NUMBERING}\n\n"));
    out.push_str("\"Proved for all real data\" is the symbolic prover's record (`sticky prove`, committed in `docs/prove-n1-3.jsonl` and `docs/prove-n4.jsonl`, re-checked at N ≤ 3 by `tests/prove.rs`): for every real datum with that N satisfying the hypotheses printed with the claim, the checker passes.\n\n");
    let corrected = |id: &str| format!("{id} (corrected)");
    let cell = |id: &str| proofs.get(id).map_or("—".to_string(), |p| p.cell.clone());
    out.push_str("| id | status | cases | proved for all real data | corrected statement |\n|---|---|---|---|---|\n");
    for e in entries {
        let corr = match &e.correction {
            Some((_, o, _)) => match proofs.get(&corrected(e.id)) {
                Some(p) => format!(
                    "{} ({} cases); proved {}",
                    o.status.label(),
                    o.cases,
                    p.cell
                ),
                None => format!("{} ({} cases)", o.status.label(), o.cases),
            },
            None => "—".to_string(),
        };
        out.push_str(&format!(
            "| `{}` | {} | {} | {} | {} |\n",
            e.id,
            e.outcome.status.label(),
            e.outcome.cases,
            cell(e.id),
            corr
        ));
    }
    out.push('\n');
    let mut section = "";
    for e in entries {
        if e.section != section {
            section = e.section;
            out.push_str(&format!("## {section}\n\n"));
        }
        out.push_str(&format!(
            "### `{}` — {}\n\n",
            e.id,
            e.outcome.status.label()
        ));
        out.push_str(&format!("> {}\n\n", e.statement));
        out.push_str(&format!(
            "Cases: {}. Engines: {}.\n\n",
            e.outcome.cases,
            if e.engines.is_empty() {
                "none".to_string()
            } else {
                e.engines.join(", ")
            }
        ));
        if let Some(p) = proofs.get(e.id) {
            out.push_str(&proof_line(p));
        }
        out.push_str(&super::coq::markdown_line(e.id));
        if let Status::NotCheckable(r) = &e.outcome.status {
            out.push_str(&format!("Not checkable: {r}\n\n"));
        }
        if let Status::Identity(r) = &e.outcome.status {
            out.push_str(&format!("Identity (not counted as holding): {r}\n\n"));
        }
        if let Some(note) = &e.outcome.note {
            out.push_str(&format!("Measured: {note}\n\n"));
        }
        if let Some(w) = &e.outcome.witness {
            out.push_str(&format!(
                "Counterexample:\n\n```\n{}\n```\n\n",
                w.trim_end()
            ));
        }
        if let Some((st, o, concl)) = &e.correction {
            out.push_str(&format!(
                "Corrected statement ({}, {} cases): {}\n\n",
                o.status.label(),
                o.cases,
                st
            ));
            if let Some(w) = &o.witness {
                out.push_str(&format!(
                    "Counterexample to the correction:\n\n```\n{}\n```\n\n",
                    w.trim_end()
                ));
            }
            if let Some(note) = &o.note {
                out.push_str(&format!("Measured: {note}\n\n"));
            }
            if let Some(p) = proofs.get(&corrected(e.id)) {
                out.push_str(&proof_line(p));
            }
            out.push_str(&format!("Conclusion of the enclosing result: {concl}\n\n"));
        }
    }
    out
}

/// The symbolic prover's line under a claim.
fn proof_line(p: &Proof) -> String {
    match &p.hypotheses {
        Some(h) => format!(
            "Symbolic prover: proved for all real data, {}; hypotheses at the largest N: {h}.\n\n",
            p.cell
        ),
        None => format!(
            "Symbolic prover: {} (a solver-built witness, replayed by the exact checker).\n\n",
            p.cell
        ),
    }
}

/// The README's summary of the ledger: counts by status and each
/// counterexample in one line (kept current by `tests/claims_ledger.rs`).
pub fn summary(entries: &[Entry]) -> String {
    let mut out = format!(
        "{} claims: {} (the corrected statement of every counterexample holds).\n\n",
        entries.len(),
        counts(entries)
    );
    for e in entries {
        if e.outcome.status == Status::Counterexample {
            let w = e.outcome.witness.as_deref().map(first_line).unwrap_or("");
            let w = if w.chars().count() > 160 {
                format!("{}…", w.chars().take(160).collect::<String>())
            } else {
                w.to_string()
            };
            out.push_str(&format!("- `{}`: {w}\n", e.id));
        }
    }
    out
}
