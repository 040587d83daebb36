//! Arbitrary bytes → admissible initial data → every claim checker.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| sticky::claims::fuzz::claims(data));
