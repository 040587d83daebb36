//! Arbitrary bytes → the scene parser: a scene or an error, never a panic.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| sticky::claims::fuzz::scene_parser(data));
