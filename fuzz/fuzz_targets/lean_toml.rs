//! Arbitrary bytes → the lean TOML reader against the general parser: the
//! same scene, or both decline (`sticky::claims::fuzz::lean_toml`).
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| sticky::claims::fuzz::lean_toml(data));
