//! `sticky claims --json`, typed with serde: one [`ClaimJson`] per claim,
//! so the keys cannot drift and no JSON is built by hand. Documented in
//! `docs/guide/json.md` ("sticky claims --json"), schema
//! `docs/guide/schema/claims.json`.

use serde::Serialize;

use super::coq::{rows, CoqRow, Statement};
use super::ledger::{Entry, Outcome, Status};
use super::proved::{decimal, proved, Tightness};
use super::witness::WitnessData;
use crate::scalar::Scalar;

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

/// The measured tightness against a proved constant on one datum.
#[derive(Debug, Clone, Serialize)]
#[cfg_attr(test, derive(schemars::JsonSchema))]
pub struct TightnessJson {
    /// The datum (a shipped scene, or the tightest random datum).
    pub scene: String,
    /// The N where measured / constant is largest.
    pub n: usize,
    /// The constant's value on the datum at that N (exact).
    pub value: String,
    /// The measured value there (exact).
    pub measured: String,
    /// `measured / value`, exact.
    pub tightness: String,
    /// The same, truncated to four decimals.
    pub tightness_decimal: String,
}

impl TightnessJson {
    fn of(t: &Tightness) -> Self {
        TightnessJson {
            scene: t.scene.clone(),
            n: t.n,
            value: t.constant.render(),
            measured: t.measured.render(),
            tightness: t.ratio().render(),
            tightness_decimal: decimal(&t.ratio()),
        }
    }
}

/// The constant proved in Coq for every N (`claims::proved`), and how
/// tight the ledger's measurements are against it.
#[derive(Debug, Clone, Serialize)]
#[cfg_attr(test, derive(schemars::JsonSchema))]
pub struct ProvedJson {
    /// The Coq theorem, `Module.name` in `proofs/coq/theories/`.
    pub theorem: &'static str,
    /// The quantity bounded.
    pub quantity: &'static str,
    /// The constant, as a formula in the datum's data.
    pub constant: &'static str,
    /// Per datum measured (empty when no measurement of the ledger is
    /// this quantity).
    pub scenes: Vec<TightnessJson>,
    /// The largest tightness over `scenes`, exact (`null` when empty).
    pub tightness: Option<String>,
    /// The same, truncated to four decimals.
    pub tightness_decimal: Option<String>,
}

impl ProvedJson {
    fn of(id: &str, statement: Statement, o: &Outcome) -> Option<Self> {
        let p = proved(id, statement)?;
        let max = o
            .tightness
            .iter()
            .map(Tightness::ratio)
            .max_by(|a, b| a.cmp(b));
        Some(ProvedJson {
            theorem: p.theorem,
            quantity: p.quantity,
            constant: p.constant,
            scenes: o.tightness.iter().map(TightnessJson::of).collect(),
            tightness: max.as_ref().map(|q| q.render()),
            tightness_decimal: max.as_ref().map(decimal),
        })
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
    /// The constant proved in Coq for the corrected statement.
    pub proved: Option<ProvedJson>,
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
    /// The constant proved in Coq for the printed statement.
    pub proved: Option<ProvedJson>,
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
                proved: ProvedJson::of(e.id, Statement::Corrected, o),
            }),
            coq: rows(e.id),
            proved: ProvedJson::of(e.id, Statement::Printed, &e.outcome),
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
