//! `sticky prove --json`: one [`ProofRecord`] per claim and N
//! (docs/guide/json.md), one line each, in the contract's spelling ([`crate::json`]).

use serde::Serialize;

use super::{ProofResult, Status};
use crate::json::Fixed;

/// One claim at one N: the outcome of a proof attempt.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(test, derive(schemars::JsonSchema))]
#[cfg_attr(test, schemars(rename = "ProofRecord"))]
pub struct ProofRecord {
    /// The claim's id: its `\label`, `#step` for a step, ` (corrected)`
    /// for a corrected statement.
    pub id: String,
    /// N.
    pub n: usize,
    /// `proved` (for every real input satisfying the hypotheses),
    /// `refuted` (a counterexample replayed exactly) or `unknown`.
    pub status: Status,
    /// The number of paths explored.
    pub paths: usize,
    /// The number of solver queries.
    pub queries: usize,
    /// Wall-clock time, to the millisecond.
    pub seconds: Fixed<3>,
    /// The hypotheses proved under, in words.
    pub hypotheses: String,
    /// A counterexample scene (TOML text), `null` unless refuted.
    pub witness: Option<String>,
    /// Whether the ledger lists the claim as an erratum (the printed claim
    /// is false).
    pub erratum: bool,
    /// Why the status is `unknown`, or the exact checker's message on the
    /// witness.
    pub note: Option<String>,
}

impl ProofRecord {
    /// The record of `r`; `erratum`: the ledger reports the printed claim
    /// false.
    pub fn of(r: &ProofResult, erratum: bool) -> ProofRecord {
        ProofRecord {
            id: r.id.clone(),
            n: r.n,
            status: r.status,
            paths: r.paths,
            queries: r.queries,
            seconds: Fixed(r.seconds),
            hypotheses: r.hypotheses.clone(),
            witness: r.witness.clone(),
            erratum,
            note: r.note.clone(),
        }
    }
}

/// [`ProofRecord::of`] as one line of JSON (no newline).
pub fn line(r: &ProofResult, erratum: bool) -> String {
    crate::json::to_string(&ProofRecord::of(r, erratum))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_committed_spelling() {
        let r = ProofResult {
            id: "prop:Oleinik".into(),
            n: 2,
            status: Status::Refuted,
            paths: 3,
            queries: 4,
            seconds: 0.0314,
            hypotheses: "N = 2, \"all\" real".into(),
            witness: Some("a = 1\nb = 2\n".into()),
            note: None,
        };
        assert_eq!(
            line(&r, true),
            r#"{"id": "prop:Oleinik", "n": 2, "status": "refuted", "paths": 3, "queries": 4, "seconds": 0.031, "hypotheses": "N = 2, \"all\" real", "witness": "a = 1\nb = 2\n", "erratum": true, "note": null}"#
        );
    }
}
