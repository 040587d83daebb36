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

/// Fuzz target `lean_toml`: the streaming path's TOML reader
/// ([`crate::scene::inline_scene`], a strict subset of TOML read straight
/// into machine words) against the general parser ([`crate::scene::parse`]),
/// on any bytes. Whenever the lean reader takes a text: if the general
/// parser accepts it, both give the same radius, positions and velocities,
/// value for value; if the general parser rejects it, the streaming path
/// must decline it too ([`crate::fast::stream::Lean`] validates the same
/// data), so that the general path's error message is the one shown.
/// Panics on any difference.
pub fn lean_toml(bytes: &[u8]) {
    use crate::fast::stream::Lean;
    use num_bigint::BigInt;
    let Some(lean) = crate::scene::inline_scene(bytes) else {
        return;
    };
    // The lean reader takes ASCII only.
    let Ok(text) = std::str::from_utf8(bytes) else {
        panic!("the lean reader took bytes that are not UTF-8");
    };
    let as_ratio = |&(p, d): &(i64, u64)| BigRational::new(BigInt::from(p), BigInt::from(d));
    match crate::scene::parse(text) {
        Ok(scene) => {
            let d = &scene.data;
            let xs: Vec<BigRational> = lean.positions.iter().map(as_ratio).collect();
            let us: Vec<BigRational> = lean.velocities.iter().map(as_ratio).collect();
            assert!(xs == d.positions(), "positions differ:\n{text}");
            assert!(us == d.velocities(), "velocities differ:\n{text}");
            if let Some(r) = &lean.radius {
                assert!(r == d.radius(), "radius differs:\n{text}");
            }
        }
        Err(e) => {
            let taken = Lean::new(
                lean.radius,
                lean.charged_bits,
                lean.positions,
                lean.velocities,
            );
            assert!(
                taken.is_none(),
                "the streaming path takes a scene the general parser rejects ({e}):\n{text}"
            );
        }
    }
}

/// Fuzz target `kernels`: the oracle battery ([`crate::fast::battery`])
/// on every exact engine of [`crate::fast::engine::ENGINES`]. The first two
/// bytes pick a scale `2^s` and an offset `2^o + 1/3` (so that the data land
/// in every integer width of [`crate::fast::kernel`]: `i128`, 256-bit,
/// `BigInt`), the rest decode into admissible data (N ≤ 40); then, at the
/// collision instants (exact ties) and between them, every engine must equal
/// the generic `BigRational` projection, and every history engine the
/// generic event-driven merge. Panics on any difference.
pub fn kernels(bytes: &[u8]) {
    use num_bigint::BigInt;
    use num_traits::One;
    let (scale, offset) = match bytes {
        [a, b, ..] => (u32::from(*a) % 200, u32::from(*b) % 330),
        _ => (0, 0),
    };
    let data = initial_data(
        bytes.get(2..).unwrap_or(&[]),
        Limits {
            max_n: 40,
            max_den: 8,
            max_speed: 16,
        },
    );
    let s = BigRational::from_integer(BigInt::one() << scale);
    let o = BigRational::from_integer(BigInt::one() << offset)
        + BigRational::new(BigInt::one(), BigInt::from(3));
    let x = data.positions().iter().map(|x| x * &s + &o).collect();
    let u = data.velocities().iter().map(|u| u * &s).collect();
    let Ok(data) = crate::InitialData::new(data.radius() * &s, x, u) else {
        panic!("scaling and shifting admissible data must keep it admissible");
    };
    if let Err(m) = crate::fast::battery::check_probes(&data, Some(6)).map(drop) {
        panic!("{m}");
    }
}
