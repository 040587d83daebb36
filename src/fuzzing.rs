//! The bodies of the fuzz targets (`fuzz/fuzz_targets/*.rs`), kept in the
//! library so that `cargo test` replays every committed crash input through
//! exactly the same code (`tests/fuzz_replay.rs`).

use num_rational::BigRational;

use crate::claims::{check_case, registry, Case};
use crate::generate::{initial_data, Limits};

/// Fuzz target `claims`: decode arbitrary bytes into admissible initial
/// data (N ≤ 12, so that the fuzzer runs many inputs per second), run the exact event-driven merge, and run every case
/// checker of the registry. Panics (a fuzz finding) if a claim without a
/// correction, or a correction, is violated.
pub fn claims(bytes: &[u8]) {
    let data = initial_data(
        bytes,
        Limits {
            max_n: 12,
            max_den: 8,
            max_speed: 16,
        },
    );
    let case: Case<BigRational> = Case::new(data, Some(6));
    if let Err(v) = check_case(&registry(), &case) {
        panic!("{v}");
    }
}

/// Fuzz target `scene_parser`: any bytes, read as (lossy) UTF-8, are either a
/// valid scene or a clear error — never a panic. A scene that parses is
/// admissible by construction; that is re-checked.
pub fn scene_parser(bytes: &[u8]) {
    let text = String::from_utf8_lossy(bytes);
    if let Ok(scene) = crate::scene::parse(&text) {
        let d = &scene.data;
        if let Err(e) = crate::InitialData::new(
            d.radius().clone(),
            d.positions().to_vec(),
            d.velocities().to_vec(),
        ) {
            panic!("parsed scene is not admissible: {e}");
        }
    }
}
