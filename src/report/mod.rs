//! The report layer: what turns the engines, the reference solvers, the
//! claims and the hydrodynamic limit into files a person reads — the
//! machine-readable JSON of the interop contract (`json`, feature `json`), the CSV files of
//! the convergence study ([`converge`](mod@converge)), the file helpers
//! ([`io`]: whole writes, CSV fields), the exact reading of another solver's
//! answer ([`solution`]) and the export of a scene as a peer reads it
//! ([`export`]), another solver's answer measured and judged
//! ([`compare`](mod@compare): the report of `sticky compare`, its JSON with
//! the `json` feature), and, with the
//! `report` feature, the charts (`plot`, `figures`), the speed-vs-accuracy
//! atlas (`atlas`), the benchmark (`bench`), the peer solvers' runner
//! (`peers`) and the terminal progress bar (`progress`).
//!
//! Nothing below this layer imports it.

#[cfg(feature = "report")]
pub mod atlas;
#[cfg(feature = "report")]
pub mod bench;
pub mod compare;
pub mod converge;
pub mod export;
#[cfg(feature = "report")]
pub mod figures;
pub mod io;
#[cfg(feature = "json")]
pub mod json;
#[cfg(feature = "report")]
pub mod peers;
#[cfg(feature = "report")]
pub mod plot;
#[cfg(feature = "report")]
pub mod progress;
#[cfg(all(test, feature = "json"))]
mod schema;
pub mod solution;
