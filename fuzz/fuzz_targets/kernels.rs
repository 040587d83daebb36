//! Arbitrary bytes → admissible data in every integer width → every exact
//! engine of `sticky::fast::engine::ENGINES` against the generic
//! `BigRational` oracle (the oracle battery, `sticky::fast::battery`).
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| sticky::claims::fuzz::kernels(data));
