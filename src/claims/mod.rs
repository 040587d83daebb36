//! One checker per claim of the paper.
//!
//! Every checker is a plain function returning `Result<(), Violation>`; the
//! `Violation` names the claim by the paper's `\label` (plus `#step` for a
//! step inside a proof) and carries the exact witness. Unit tests, proptest
//! (`prop_*`), quickcheck (`qc_*`), the bounded-exhaustive proofs
//! (`verify_*`) and the fuzz targets all call these same functions.

use std::fmt;

pub mod micro;

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
