//! Arbitrary bytes → admissible data in every integer width → the integer
//! kernel, the adaptive solver and the integer event engine against the
//! generic `BigRational` oracle.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| sticky::claims::fuzz::kernels(data));
