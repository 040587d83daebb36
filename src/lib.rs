//! # sticky
//!
//! Exact dynamics of N solid particles on a line that stick together when
//! they collide (a Signorini non-overlap constraint), after C. Perrin,
//! *Microscopic derivation of the one-dimensional constrained Euler
//! equations* (the paper; its `\label`s are cited next to the code that
//! implements or checks them).
//!
//! ## Layers
//!
//! The folders are layers; a layer imports only the layers above it in this
//! list (checked by `tests/layers.rs`).
//!
//! 1. **The model core**, at the top of `src/`, in the paper's vocabulary:
//!    [`scalar`] (the numeric trait everything is written over), [`rational`],
//!    [`initial`] data, [`state`], [`cluster`] (`df:Omega-micro`,
//!    `df:H-micro`), [`projection`] (`x(t) = P_K(x⁰ + t u⁰)` by
//!    pool-adjacent-violators, `prop:proj-micro`), [`trajectory`] (the
//!    event-driven cluster merge), [`contact`] (the multipliers `λ` of
//!    `eq:dyn-micro`, Appendix A's KKT multipliers, the pressure of
//!    `prop:micro-pressure`), [`scene`] and [`quantile`] (scene files and
//!    quantile sampling), [`generate`], [`violation`], [`text`], [`error`].
//! 2. [`fast`] — the exact integer engines (kernel, adaptive, integer merge).
//! 3. [`reference`] — the `f64` solvers, and [`reference::measure`], the one
//!    owner of every error metric.
//! 4. [`limit`] — the hydrodynamic limit (section 3, Appendix C).
//! 5. [`claims`] — one checker per claim of the paper, the ledger.
//! 6. [`prove`] — the symbolic prover: the engine and the checkers on a
//!    symbolic scalar, every comparison decided by an SMT solver (z3).
//! 7. [`report`] — JSON output, and (feature `report`) charts, atlas, bench.
//!
//! The `sticky` command line (feature `cli`, on by default) sits above all
//! of them, in `src/bin/sticky/`, one module per command.
#![forbid(unsafe_code)]
#![deny(missing_docs)]

// 1. The model core.
pub mod cluster;
pub mod contact;
pub mod error;
pub mod generate;
pub mod initial;
pub mod projection;
pub mod quantile;
pub mod rational;
pub mod scalar;
pub mod scene;
pub mod state;
pub mod text;
pub mod trajectory;
pub mod violation;

// 2–7. The layers above it.
pub mod claims;
pub mod fast;
pub mod limit;
pub mod prove;
pub mod reference;
pub mod report;

pub use error::Error;
pub use initial::InitialData;
pub use scalar::Scalar;
pub use state::State;
