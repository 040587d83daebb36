//! What a checker returns when a claim of the paper fails: the claim's
//! `\label` and the exact witness. It lives in the model core so that every
//! layer that checks something (the claims ledger, the hydrodynamic limit,
//! the symbolic prover) shares one type.

use std::fmt;

/// A claim found false on a concrete input, with the exact witness.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Violation {
    /// The claim id: the paper's `\label`, plus `#step` for a proof step.
    pub claim: &'static str,
    /// What failed, with the exact values on both sides.
    pub witness: String,
}

impl Violation {
    /// A violation of `claim` described by `witness`.
    pub fn new(claim: &'static str, witness: impl Into<String>) -> Self {
        Violation {
            claim,
            witness: witness.into(),
        }
    }
}

impl fmt::Display for Violation {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} violated: {}", self.claim, self.witness)
    }
}

impl std::error::Error for Violation {}
