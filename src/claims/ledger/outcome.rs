//! What the ledger records: the status computed for each statement, its
//! outcome and witness, a row per claim, the prover's cell, and the counts
//! by status.

use crate::claims::witness::WitnessData;

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
    /// checks of [`crate::claims::proved::PROVED`] quantities; empty otherwise).
    pub tightness: Vec<crate::claims::proved::Tightness>,
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
