//! # sticky
//!
//! Exact dynamics of N solid particles on a line that stick together when
//! they collide (a Signorini non-overlap constraint), after C. Perrin,
//! *Microscopic derivation of the one-dimensional constrained Euler
//! equations* (the paper; its `\label`s are cited next to the code that
//! implements or checks them).
//!
//! * [`projection`] — `x(t) = P_K(x⁰ + t u⁰)` by pool-adjacent-violators
//!   (`prop:proj-micro`, `eq:proj-micro-x`), with the right derivative
//!   `u(t) = P_{H_{x(t)}}(u⁰)` (`eq:proj-u-micro`);
//! * [`trajectory`] — the event-driven cluster merge, every collision exact;
//! * [`merge`] — the same merge on fixed-width integers (`i128` sums, 256-bit
//!   time comparisons), converted to a [`trajectory::Trajectory`] on demand;
//! * [`kernel`], [`adaptive`] — exact PAVA on integers over common
//!   denominators (`i128`, 256-bit, `BigInt`), and with `f64` decisions
//!   certified by an error bound;
//! * [`contact`] — the multipliers `λ` (`eq:dyn-micro`), Appendix A's KKT
//!   multipliers, and the pressure `p = dλ/dt` as Dirac masses
//!   (`prop:micro-pressure`);
//! * [`cluster`] — contact sets `Ω_x` (`df:Omega-micro`), clusters, `H_x`
//!   (`df:H-micro`);
//! * [`scene`] and [`quantile`] — the TOML scene format and quantile sampling
//!   of macroscopic data;
//! * [`scalar`] — the numeric trait all of it is written over.
#![forbid(unsafe_code)]
#![deny(missing_docs)]

pub mod adaptive;
pub mod atlas;
pub mod bench;
pub mod claims;
pub mod cluster;
pub mod contact;
pub mod error;
pub mod figures;
pub mod fuzzing;
pub mod generate;
pub mod initial;
pub mod json;
pub mod kernel;
pub mod limit;
pub mod merge;
pub mod plot;
pub mod projection;
pub mod quantile;
pub mod rational;
pub mod reference;
pub mod scalar;
pub(crate) mod scaling;
pub mod scene;
pub mod state;
pub mod trajectory;
pub mod wide;

pub use error::Error;
pub use initial::InitialData;
pub use scalar::Scalar;
pub use state::State;
