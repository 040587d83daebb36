//! Campaigns split into shards (issue 38, item 3): the long jobs
//! (`sticky claims`, `prove`, `converge`, `atlas`) are sets of independent *units*;
//! a [`Shard`] `I/N` runs a deterministic share of them and writes its
//! results as JSON lines (module `file`, with the `json` feature), whose
//! `merge` checks that the shards' files make one whole campaign and hands back every unit's result in unit
//! order, from which each campaign renders exactly the report a single run
//! prints. [`jobs::run_units`] runs K units at once on one machine, with the
//! results in unit order whatever K.
//!
//! Each campaign keeps its units and its rendering beside its code:
//! `claims::campaign`, `prove::campaign`, `limit::converge::campaign`,
//! `report::atlas::campaign`.

#[cfg(feature = "json")]
pub mod bits;
#[cfg(feature = "json")]
pub mod file;
pub mod jobs;
pub mod shard;

pub use shard::{Shard, ShardError};
