//! The exact fast engines: the same answers as the generic `BigRational`
//! code of the model core ([`crate::projection`], [`crate::trajectory`]),
//! computed on integers over common denominators.
//!
//! * [`kernel`] — exact PAVA on `i128`, 256-bit ([`wide`]) or `BigInt`
//!   integers, the narrowest width a proved bit-length bound allows;
//! * [`adaptive`] — the same PAVA with `f64` decisions certified by an error
//!   bound, exact integers for the decisions the bound cannot settle;
//! * [`merge`] — the event-driven cluster merge on fixed-width integers
//!   (`i64`/`i128` sums, 256-bit time comparisons);
//! * `scaling` — the one scaling to common denominators both use.

pub mod adaptive;
pub mod kernel;
pub mod merge;
pub(crate) mod scaling;
pub mod wide;
