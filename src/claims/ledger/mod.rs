//! The ledger runner: runs every claim of the [`registry`](fn@super::registry)
//! and computes its status — never typed in.
//!
//! * [`Kind::Case`](super::Kind::Case) claims run on the shipped scenes and
//!   on random admissible data decoded by [`crate::generate`]; the first
//!   violation is shrunk (greedy byte-level shrinking of the generator
//!   input: drop chunks, then lower bytes) to a small exact witness scene.
//! * [`Kind::Scaling`](super::Kind::Scaling) claims run across N on
//!   quantile-sampled data.
//! * [`Kind::Formula`](super::Kind::Formula) claims are checked once, exactly.
//!
//! Statuses: `holds` (no counterexample in all cases run), `counterexample`
//! (with the witness), `not checkable` (with the reason).

mod budget;
mod counterexample;
mod found;
mod outcome;
mod render;
mod run;
mod shrink;

pub use budget::Budget;
pub(crate) use counterexample::timeless;
pub use found::{failure_in_domain, Found};
pub use outcome::{counts, Counts, Entry, Outcome, Proof, Proofs, Status};
pub use render::{markdown, summary, table, NUMBERING};
pub(crate) use run::{engines, run_case_range, run_kind, shipped_cases, CORRECTION_DOMAIN};
pub use run::{run, run_claim, CASE_ENGINES};

#[cfg(feature = "json")]
pub use super::json::json;
