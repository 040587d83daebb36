//! The report layer: what turns the engines, the reference solvers, the
//! claims and the hydrodynamic limit into files a person reads — the
//! machine-readable JSON of the interop contract ([`json`]), and, with the
//! `report` feature, the charts ([`plot`], [`figures`]), the speed-vs-accuracy
//! atlas ([`atlas`]) and the benchmark ([`bench`]).
//!
//! Nothing below this layer imports it.

#[cfg(feature = "report")]
pub mod atlas;
#[cfg(feature = "report")]
pub mod bench;
pub mod export;
#[cfg(feature = "report")]
pub mod figures;
pub mod json;
#[cfg(feature = "report")]
pub mod peers;
#[cfg(feature = "report")]
pub mod plot;
pub mod solution;
