//! `sticky prove` as a campaign (issue 38, item 3): one unit per claim and
//! N, in the order a single run prints them (every claim at `from`, then at
//! `from + 1`, …), each unit's [`ProofLine`] written by its shard and the
//! single run's report rendered from the lines ([`render`]).

use serde::{Deserialize, Serialize};

use super::{prove_target_observed, targets, ProofLimits, ProofResult, Status, Target};
use crate::progress::Progress;

/// Everything the proofs depend on: equal in every shard of one campaign.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct ProveSetup {
    /// Smallest N.
    pub from: usize,
    /// Largest N.
    pub n: usize,
    /// Only this claim (registry id or printed id).
    pub claim: Option<String>,
    /// Wall-clock budget per claim and N, seconds.
    pub seconds: u64,
    /// Solver time limit per query, milliseconds.
    pub query_ms: u64,
    /// Solver memory cap, megabytes.
    pub solver_mb: u64,
    /// The solver's version line (`z3 -version`).
    pub solver: String,
}

impl ProveSetup {
    /// The limits of every proof attempt.
    pub fn limits(&self) -> ProofLimits {
        ProofLimits {
            time: std::time::Duration::from_secs(self.seconds.max(1)),
            query_ms: self.query_ms.max(100),
            solver_memory_mb: self.solver_mb.max(64),
            ..ProofLimits::default()
        }
    }
}

/// One unit: a claim at one N.
#[derive(Debug, Clone)]
pub struct ProveUnit {
    /// N.
    pub n: usize,
    /// The claim.
    pub target: Target,
}

/// The units of a campaign, in the single run's order; `None` when the
/// claim filter matches no per-case claim.
pub fn units(setup: &ProveSetup) -> Option<Vec<ProveUnit>> {
    let chosen: Vec<Target> = targets()
        .into_iter()
        .filter(|t| {
            setup
                .claim
                .as_deref()
                .is_none_or(|c| t.id == c || t.registry_id == c)
        })
        .collect();
    if chosen.is_empty() {
        return None;
    }
    Some(
        (setup.from.max(1)..=setup.n)
            .flat_map(|n| {
                // Below the statement's least N (`N > 1` in the paper) there
                // is nothing to prove or refute.
                chosen
                    .iter()
                    .filter(move |t| n >= t.domain.min_n)
                    .map(move |t| ProveUnit {
                        n,
                        target: t.clone(),
                    })
            })
            .collect(),
    )
}

/// A unit's result as a shard writes it: the [`ProofResult`] and whether
/// the ledger reports the printed claim false.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ProofLine {
    /// Claim id.
    pub id: String,
    /// N.
    pub n: usize,
    /// `proved`, `refuted` or `unknown`.
    pub status: String,
    /// Paths explored.
    pub paths: usize,
    /// Solver queries.
    pub queries: usize,
    /// Wall-clock seconds (the only field that differs between runs).
    pub seconds: f64,
    /// The hypotheses, in words.
    pub hypotheses: String,
    /// The counterexample scene.
    pub witness: Option<String>,
    /// Why unknown, or the checker's message on the witness.
    pub note: Option<String>,
    /// The ledger reports the printed claim false.
    pub erratum: bool,
}

impl ProofLine {
    /// The line of one result.
    pub fn new(r: &ProofResult, erratum: bool) -> Self {
        ProofLine {
            id: r.id.clone(),
            n: r.n,
            status: r.status.as_str().to_string(),
            paths: r.paths,
            queries: r.queries,
            seconds: r.seconds,
            hypotheses: r.hypotheses.clone(),
            witness: r.witness.clone(),
            note: r.note.clone(),
            erratum,
        }
    }

    /// The result back (an unknown status word reads as `unknown`).
    pub fn result(&self) -> ProofResult {
        let status = match self.status.as_str() {
            "proved" => Status::Proved,
            "refuted" => Status::Refuted,
            _ => Status::Unknown,
        };
        ProofResult {
            id: self.id.clone(),
            n: self.n,
            status,
            paths: self.paths,
            queries: self.queries,
            seconds: self.seconds,
            hypotheses: self.hypotheses.clone(),
            witness: self.witness.clone(),
            note: self.note.clone(),
        }
    }
}

/// Runs one unit.
pub fn run_unit(unit: &ProveUnit, setup: &ProveSetup, progress: &dyn Progress) -> ProofLine {
    let r = prove_target_observed(&unit.target, unit.n, setup.limits(), progress);
    ProofLine::new(&r, unit.target.erratum)
}

/// The head of the text report: the solver, the hypotheses and the column
/// names.
pub fn table_head(solver: &str) -> String {
    format!(
        "solver: {solver}\nhypotheses: all real x⁰ ∈ K^N, u⁰ ∈ C_x⁰, 2r = 1/N; all real t ≥ 0 (0 ≤ s ≤ t for two-time claims)\n{:<52} {:>2} {:>8} {:>7} {:>8} {:>8}  erratum\n",
        "claim", "N", "status", "paths", "queries", "seconds"
    )
}

/// One claim at one N in the text report (two lines when unknown, with the
/// reason).
pub fn table_row(r: &ProofResult, erratum: bool) -> String {
    let mut text = format!(
        "{:<52} {:>2} {:>8} {:>7} {:>8} {:>8.2}  {}\n",
        r.id,
        r.n,
        r.status.as_str(),
        r.paths,
        r.queries,
        r.seconds,
        if erratum { "yes" } else { "" }
    );
    if r.status == Status::Unknown {
        if let Some(note) = &r.note {
            text.push_str(&format!("    unknown: {note}\n"));
        }
    }
    text
}

/// How the report of `sticky prove` is written.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Layout {
    /// A table for people: a head naming the solver, one row per claim and N.
    Table,
    /// One [`ProofRecord`](super::json::ProofRecord) per line (`--json`).
    JsonLines,
}

impl Layout {
    /// [`Layout::JsonLines`] when `json` (the `--json` flag), else the table.
    pub fn of_flag(json: bool) -> Layout {
        if json {
            Layout::JsonLines
        } else {
            Layout::Table
        }
    }
}

/// One line of the report: JSON (`sticky prove --json`) or the table row.
pub fn report_line(line: &ProofLine, layout: Layout) -> String {
    let r = line.result();
    match layout {
        Layout::JsonLines => {
            let mut text = super::json::line(&r, line.erratum);
            text.push('\n');
            text
        }
        Layout::Table => table_row(&r, line.erratum),
    }
}

/// The whole report of a single run, from every unit's line in unit order.
pub fn render(setup: &ProveSetup, lines: &[ProofLine], layout: Layout) -> String {
    let mut out = match layout {
        Layout::JsonLines => String::new(),
        Layout::Table => table_head(&setup.solver),
    };
    for line in lines {
        out.push_str(&report_line(line, layout));
    }
    out
}
