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
    /// The same in machine-readable form, when the checker gives it.
    pub detail: Box<Detail>,
}

/// The machine-readable part of a violation: where it fails and the two
/// sides of the statement, every number an exact string (`"p/q"`).
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Detail {
    /// The time of the failure, when there is one.
    pub t: Option<String>,
    /// The particle, pair or cell indices involved (from 0, as every
    /// program output).
    pub indices: Vec<usize>,
    /// The Lagrangian points `w` of the failure, when pointwise in `w`.
    pub w: Vec<String>,
    /// The test function, when the statement pairs with one.
    pub test_function: Option<String>,
    /// The two sides of the statement that differ (or the inequality that
    /// fails).
    pub sides: Option<Sides>,
}

/// The two sides of a failed identity or inequality.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Sides {
    /// What the left side is, in words.
    pub lhs_is: String,
    /// Its exact value.
    pub lhs: String,
    /// What the right side is.
    pub rhs_is: String,
    /// Its exact value.
    pub rhs: String,
}

impl Violation {
    /// A violation of `claim` described by `witness`.
    pub fn new(claim: &'static str, witness: impl Into<String>) -> Self {
        Violation {
            claim,
            witness: witness.into(),
            detail: Box::default(),
        }
    }
    /// The same with the time of the failure.
    pub fn at(mut self, t: impl Into<String>) -> Self {
        self.detail.t = Some(t.into());
        self
    }
    /// The same with the indices involved.
    pub fn indices(mut self, indices: &[usize]) -> Self {
        self.detail.indices = indices.to_vec();
        self
    }
    /// The same with the Lagrangian points of the failure.
    pub fn w(mut self, w: Vec<String>) -> Self {
        self.detail.w = w;
        self
    }
    /// The same with the test function.
    pub fn test_function(mut self, f: impl Into<String>) -> Self {
        self.detail.test_function = Some(f.into());
        self
    }
    /// The same with the two sides: `lhs_is = lhs` against `rhs_is = rhs`.
    pub fn sides(
        mut self,
        lhs_is: impl Into<String>,
        lhs: impl Into<String>,
        rhs_is: impl Into<String>,
        rhs: impl Into<String>,
    ) -> Self {
        self.detail.sides = Some(Sides {
            lhs_is: lhs_is.into(),
            lhs: lhs.into(),
            rhs_is: rhs_is.into(),
            rhs: rhs.into(),
        });
        self
    }
}

impl fmt::Display for Violation {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} violated: {}", self.claim, self.witness)
    }
}

impl std::error::Error for Violation {}
