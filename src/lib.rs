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
//!    quantile sampling), [`columns`] (exact CSV/NPY particle files),
//!    [`generate`], [`rate`] (log-log slopes), [`violation`], [`text`],
//!    [`error`], [`progress`] (the observer of long work).
//! 2. [`fast`] — the exact integer engines (kernel, adaptive, integer merge).
//! 3. [`solver`] — the one front door: [`solver::Solver`] chooses the engine
//!    (fast paths, cost model, work check, fallbacks) and answers states,
//!    events and projections; the command line and Python ask it alone.
//! 4. [`reference`](mod@reference) — the `f64` solvers, and
//!    [`reference::measure`](mod@reference::measure), the one
//!    owner of every error metric.
//! 5. [`limit`] — the hydrodynamic limit (section 3, Appendix C).
//! 6. [`claims`] — one checker per claim of the paper, the ledger.
//! 7. [`prove`] — the symbolic prover: the engine and the checkers on a
//!    symbolic scalar, every comparison decided by an SMT solver (z3).
//! 8. [`report`] — JSON output, and (feature `report`) charts, atlas, bench.
//!
//! The `sticky` command line (feature `cli`, on by default) sits above all
//! of them, in `src/bin/sticky/`, one module per command.
//!
//! ## Features
//!
//! * `cli` (default) — the `sticky` binary (clap); implies `report` and
//!   `json`;
//! * `json` — every JSON output as a serde type (the state, the events,
//!   `compare`'s report, the export, the proof records, the Coq rows),
//!   printed in one spelling by `json` (serde, serde_json);
//! * `report` — charts, the atlas and the benchmark (plotters, indicatif);
//!   implies `json`.
//!
//! `cargo build --lib --no-default-features` builds the library alone, with
//! no command-line or chart dependency.
//!
//! ## A first program
//!
//! ```
//! use num_rational::BigRational;
//! use sticky::{InitialData, Trajectory};
//!
//! let q = |n: i64, d: i64| BigRational::new(n.into(), d.into());
//! // Two particles of radius 1/4 running into each other.
//! let data = InitialData::new(q(1, 4), vec![q(0, 1), q(2, 1)], vec![q(1, 1), q(-1, 1)])?;
//! let traj = Trajectory::new(data.clone());
//! // They meet when the gap 2 closes down to 2r = 1/2, at t = 3/4, and stick.
//! assert_eq!(traj.impulses()[0].t, q(3, 4));
//! let state = sticky::state_at(&data, &q(1, 1))?;
//! assert_eq!(state.positions, vec![q(3, 4), q(5, 4)]);
//! assert_eq!(state.velocities, vec![q(0, 1), q(0, 1)]);
//! assert_eq!(state, traj.at(&q(1, 1))?);
//! # Ok::<(), sticky::Error>(())
//! ```
//!
//! More in `examples/` (`cargo run --example two_blocks`,
//! `cargo run --example check_a_solver`).
#![forbid(unsafe_code)]
#![deny(missing_docs)]

// 1. The model core.
pub mod blockwise;
pub mod campaign;
pub mod checked;
pub mod cluster;
pub mod columns;
pub mod contact;
pub mod error;
pub mod gcd;
pub mod generate;
pub mod initial;
#[cfg(feature = "json")]
pub mod json;
pub mod parallel;
pub mod progress;
pub mod projection;
pub mod quantile;
pub mod rate;
pub mod rational;
pub mod reduced;
pub mod scalar;
pub mod scene;
pub mod state;
pub mod text;
pub mod trajectory;
pub mod violation;

// 2–8. The layers above it.
pub mod claims;
pub mod fast;
pub mod limit;
pub mod prove;
pub mod reference;
pub mod report;
pub mod solver;

// The few types a caller needs: scene → initial data → state at t,
// trajectory, events.
pub use cluster::Cluster;
pub use contact::Impulse;
pub use error::Error;
pub use initial::InitialData;
pub use projection::state_at;
pub use scalar::Scalar;
pub use scene::Scene;
pub use state::State;
pub use trajectory::Trajectory;
