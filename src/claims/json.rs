//! `sticky claims --json`, typed with serde: one [`ClaimJson`] per claim,
//! so the keys cannot drift and no JSON is built by hand. Documented in
//! `docs/guide/json.md` ("sticky claims --json"), schema
//! `docs/guide/schema/claims.json`.

use serde::Serialize;

use super::coq::{rows, CoqRow};
use super::ledger::{Entry, Outcome, Status};
use super::witness::WitnessData;

/// The outcome of one statement (as printed, or its correction).
#[derive(Debug, Clone, Serialize)]
#[cfg_attr(test, derive(schemars::JsonSchema))]
pub struct OutcomeJson {
    /// `holds`, `counterexample`, `not checkable` or `identity`.
    pub status: &'static str,
    /// Cases run.
    pub cases: usize,
    /// The counterexample in words, with the witness scene.
    pub witness: Option<String>,
    /// The counterexample in machine-readable form (`null` unless the
    /// status is `counterexample`).
    pub witness_data: Option<WitnessData>,
    /// Measurements, or the reason of `not checkable` / `identity`.
    pub note: Option<String>,
}

impl OutcomeJson {
    fn of(o: &Outcome) -> Self {
        OutcomeJson {
            status: o.status.label(),
            cases: o.cases,
            witness: o.witness.clone(),
            witness_data: o.witness_data.clone(),
            note: o.note.clone().or_else(|| match &o.status {
                Status::NotCheckable(r) | Status::Identity(r) => Some(r.clone()),
                Status::Holds | Status::Counterexample => None,
            }),
        }
    }
}

/// A corrected statement and its outcome.
#[derive(Debug, Clone, Serialize)]
#[cfg_attr(test, derive(schemars::JsonSchema))]
pub struct CorrectionJson {
    /// The corrected statement.
    pub statement: &'static str,
    /// Its outcome.
    #[serde(flatten)]
    pub outcome: OutcomeJson,
    /// Whether the enclosing result's conclusion survives.
    pub conclusion: &'static str,
}

/// One claim of `sticky claims --json`.
#[derive(Debug, Clone, Serialize)]
#[cfg_attr(test, derive(schemars::JsonSchema))]
#[cfg_attr(test, schemars(rename = "Claim"))]
pub struct ClaimJson {
    /// `\label` or `\label#step`.
    pub id: &'static str,
    /// The section.
    pub section: &'static str,
    /// The statement as printed.
    pub statement: &'static str,
    /// Its outcome.
    #[serde(flatten)]
    pub outcome: OutcomeJson,
    /// The engines that check it.
    pub engines: Vec<&'static str>,
    /// The corrected statement, for a counterexample.
    pub correction: Option<CorrectionJson>,
    /// The Coq theorems about it.
    pub coq: Vec<CoqRow>,
}

impl ClaimJson {
    /// The JSON of one ledger entry.
    pub fn of(e: &Entry) -> Self {
        ClaimJson {
            id: e.id,
            section: e.section,
            statement: e.statement,
            outcome: OutcomeJson::of(&e.outcome),
            engines: e.engines.clone(),
            correction: e.correction.as_ref().map(|(st, o, concl)| CorrectionJson {
                statement: st,
                outcome: OutcomeJson::of(o),
                conclusion: concl,
            }),
            coq: rows(e.id),
        }
    }
}

/// The ledger as JSON: an array of [`ClaimJson`], one claim per line in
/// the contract's spelling ([`crate::json`]).
pub fn json(entries: &[Entry]) -> String {
    let items: Vec<String> = entries
        .iter()
        .map(|e| crate::json::to_string(&ClaimJson::of(e)))
        .collect();
    format!("[\n{}\n]", items.join(",\n"))
}
