//! The exact fast engines: the same answers as the generic `BigRational`
//! code of the model core ([`crate::projection`], [`crate::trajectory`]),
//! computed on integers over common denominators.
//!
//! * [`kernel`] — exact PAVA on `i128`, 256- or 512-bit ([`wide`]) or `BigInt`
//!   integers, the narrowest width a proved bit-length bound allows;
//! * [`adaptive`] — the same PAVA with `f64` decisions certified by an error
//!   bound, exact integers for the decisions the bound cannot settle;
//! * [`merge`] — the event-driven cluster merge on fixed-width integers
//!   (`i64`/`i128` sums, 256-bit time comparisons);
//! * `scaling` — the one scaling to common denominators both use;
//! * `int` — the integer helpers they share (gcd and reduction, checked
//!   products, narrowing to the smallest width, the block-size bound);
//! * [`dyadic`] — columns of doubles on `i128` over dyadic scales, PAVA
//!   and the nearest doubles with no big number per value (Python);
//! * [`stream`] — the streaming path from a column file to the answer on
//!   machine words, value by value, no `BigRational` per value;
//! * [`engine`] — the one interface every exact engine implements (the
//!   generic `BigRational` ones of the core included) and the one list of
//!   them, [`engine::ENGINES`];
//! * [`battery`] — the oracle battery: every engine of the list against the
//!   generic `BigRational` projection and event merge.

pub mod adaptive;
pub mod battery;
pub mod dyadic;
pub mod engine;
pub mod filter;
pub(crate) mod int;
pub mod kernel;
pub mod merge;
pub(crate) mod scaling;
pub mod stream;
pub mod wide;
