//! The bodies of the fuzz targets (`fuzz/fuzz_targets/*.rs`), kept in the
//! library so that `cargo test` replays every committed crash input through
//! exactly the same code (`tests/fuzz_replay.rs`).

use num_rational::BigRational;

use crate::claims::{check_case, registry, Case};
use crate::fast::battery::Similarity;
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

/// Fuzz target `kernels`: the oracle battery ([`crate::fast::battery`]) on
/// every exact engine of [`crate::fast::engine::ENGINES`], through a
/// similarity ([`crate::fast::battery::check_similar`]). The first three
/// bytes pick the similarity `x ↦ a·x + b` ([`similarity`]) that puts the
/// data in every integer width of [`crate::fast::kernel`] (`i128`, 256-bit,
/// 512-bit, `BigInt`) and of [`crate::fast::merge`] (`i64`, `i128`, the
/// generic fallback); the rest decode into small admissible data
/// (N ≤ [`KERNELS_MAX_N`]). The generic `BigRational` oracles run on the
/// small data, at the collision instants (exact ties) and between them
/// ([`KERNELS_PROBES`] instants); every other engine runs on the image of
/// the data and must answer the image of the oracles' answer — but the
/// merge where it would run the generic `BigRational` event merge on more
/// than [`KERNELS_GENERIC_MAX_N`] particles ([`kernels_asks`]). Panics on
/// any difference.
pub fn kernels(bytes: &[u8]) {
    let (similarity, data) = kernels_input(bytes);
    if let Err(m) = crate::fast::battery::check_similar_asking(
        &data,
        &similarity,
        Some(KERNELS_PROBES),
        &kernels_asks,
    )
    .map(drop)
    {
        panic!("{m}\n(similarity {similarity}, on {data:?})");
    }
}

/// The input of the `kernels` target: the similarity from the first three
/// bytes, the small admissible data (N ≤ [`KERNELS_MAX_N`]) from the rest.
fn kernels_input(bytes: &[u8]) -> (Similarity, crate::InitialData<BigRational>) {
    let (head, rest) = bytes.split_at(bytes.len().min(3));
    let data = initial_data(
        rest,
        Limits {
            max_n: KERNELS_MAX_N,
            max_den: 8,
            max_speed: 16,
        },
    );
    (similarity(head), data)
}

/// The largest N on which the `kernels` target asks the merge engine for
/// image data wider than [`MERGE_WORD_BITS`]: the merge then runs the
/// generic `BigRational` event merge, whose every operation is a gcd by
/// `num-bigint`'s binary algorithm on the wide values (a third of an
/// input's time at N ≤ 12). On small N it is still asked, so that its
/// wide fallback stays checked.
pub const KERNELS_GENERIC_MAX_N: usize = 6;

/// Above this many bits ([`scaled_bits`]) the merge's scaled values
/// cannot fit its `i128` words with the room its sums need (it takes them
/// up to ~121 bits at N ≤ 12; the estimate is at most 7 bits above).
pub const MERGE_WORD_BITS: u64 = 128;

/// An upper bound of the bits of the integers `X_i = x̃⁰_i·D`, `U_i = u⁰_i·E`
/// the merge scales the data to (`D`, `E` the common denominators of the
/// translated positions and of the velocities), within a few bits: per
/// column, the lcm of the denominators (`2r`'s with the positions') plus
/// the largest `bits(numerator) − bits(denominator)`, plus the carries of
/// `x⁰_i − 2r·i` (`i < 16`).
pub fn scaled_bits(data: &crate::InitialData<BigRational>) -> u64 {
    use num_bigint::BigUint;
    use num_traits::One;
    let column = |values: &mut dyn Iterator<Item = (&BigRational, u64)>| -> u64 {
        let mut widest: i64 = 0;
        let lcm = crate::gcd::lcm_of(
            &BigUint::one(),
            values.map(|(q, extra)| {
                let d = q.denom().magnitude();
                widest = widest.max((q.numer().bits() + extra) as i64 - d.bits() as i64);
                d
            }),
        );
        (lcm.bits() as i64 + widest + 2).max(0) as u64
    };
    let two_r = data.two_r();
    let x = column(
        &mut data
            .positions()
            .iter()
            .map(|q| (q, 0))
            .chain(std::iter::once((&two_r, 4))),
    );
    let u = column(&mut data.velocities().iter().map(|q| (q, 0)));
    x.max(u)
}

/// Whether the `kernels` target asks `engine` on the `image` data: every
/// engine, but the merge on data wider than [`MERGE_WORD_BITS`] only up to
/// [`KERNELS_GENERIC_MAX_N`] particles (issue 29: "the slow generic engine
/// only on small N").
pub fn kernels_asks(
    engine: &dyn crate::fast::engine::ExactEngine,
    image: &crate::InitialData<BigRational>,
) -> bool {
    use crate::fast::engine::{ExactEngine, Merge};
    engine.name() != Merge.name()
        || image.n() <= KERNELS_GENERIC_MAX_N
        || scaled_bits(image) <= MERGE_WORD_BITS
}

/// The largest N of the `kernels` target: the generic `BigRational` oracles
/// cost `O(N)` gcds per time, and 12 particles already make chains of
/// simultaneous collisions (the decoder's groups) and ties.
pub const KERNELS_MAX_N: usize = 12;

/// The collision instants probed per input by the `kernels` target (the
/// first, the last and spread between them, each with the midpoint before
/// it; with 0 and a time after the last: at most `2·3 + 2` times).
pub const KERNELS_PROBES: usize = 3;

/// The similarity `x ↦ a·x + b` of the `kernels` target, from (up to) three
/// bytes. Byte 0 picks the class: the identity, then powers of 3 (dense
/// bits, so that carries cross every limb) up to ~63, ~127, ~254 and ~523
/// bits — the ranges of `i64`/`i128`, 256-bit, 512-bit and `BigInt`
/// scaled values — and powers of 2 up to 2^330. Byte 1 is the exponent of
/// the ratio `a` (its inverse when byte 2 is odd: wide denominators
/// instead of wide numerators), byte 2 also the exponent and sign of the shift
/// `b = ±c + 1/3` (the `1/3` makes the denominators of the positions and
/// of the velocities differ).
pub fn similarity(head: &[u8]) -> Similarity {
    use num_bigint::BigInt;
    use num_traits::{One, Pow};
    let byte = |i: usize| head.get(i).copied().unwrap_or(0);
    let (class, e, f) = (byte(0) % 8, u32::from(byte(1)), u32::from(byte(2)));
    let (base, top): (u32, u32) = match class {
        0 | 7 => return Similarity::identity(),
        1 | 2 => (3, 40),
        3 => (3, 80),
        4 => (3, 160),
        5 => (3, 330),
        _ => (2, 330),
    };
    let power = |k: u32| BigRational::from_integer(Pow::pow(BigInt::from(base), k));
    let mut ratio = power(e % (top + 1));
    if f % 2 == 1 {
        ratio = ratio.recip();
    }
    let mut shift = power((f >> 2) * top / 63);
    if f & 2 != 0 {
        shift = -shift;
    }
    shift += BigRational::new(BigInt::one(), BigInt::from(3));
    Similarity::new(ratio, shift).unwrap_or_else(Similarity::identity)
}

#[cfg(test)]
mod tests {
    use std::collections::BTreeMap;

    use super::*;
    use crate::fast::adaptive::{adaptive_blocks_at, Path};
    use crate::fast::kernel::{blocks_at, IntegerData};
    use crate::fast::merge::IntegerTrajectory;
    use crate::generate::SplitMix64;
    use crate::trajectory::{probe_times, Trajectory};

    /// A fixed corpus of the `kernels` target: random bytes of random
    /// lengths (3 header bytes and up to 80 bytes of data).
    fn corpus(len: usize) -> Vec<Vec<u8>> {
        let mut rng = SplitMix64::new(29);
        (0..len)
            .map(|_| {
                let n = 3 + (rng.next_u64() % 81) as usize;
                rng.bytes(n)
            })
            .collect()
    }

    /// The kernel widths the image data of `bytes` reach at the target's
    /// probe times, and the number of particles.
    fn widths(bytes: &[u8]) -> (std::collections::BTreeSet<String>, usize) {
        let (similarity, small) = kernels_input(bytes);
        let d = IntegerData::new(&similarity.data(&small));
        let times = probe_times(&Trajectory::new(small.clone()), Some(KERNELS_PROBES));
        let seen = times
            .iter()
            .map(|t| format!("{:?}", blocks_at(&d, t).width()))
            .collect();
        (seen, small.n())
    }

    /// The committed seeds of `tests/fuzz_inputs/kernels/` reach the width
    /// in their name (`seed-long`: the largest N).
    #[test]
    fn seeds_reach_their_widths() {
        let dir =
            std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fuzz_inputs/kernels");
        let read = |name: &str| std::fs::read(dir.join(name)).expect("a committed seed");
        for (name, width) in [
            ("seed-i128", "I128"),
            ("seed-i256", "I256"),
            ("seed-i512", "I512"),
            ("seed-big", "Big"),
        ] {
            let (seen, _) = widths(&read(name));
            assert!(seen.contains(width), "{name} reaches {seen:?}");
        }
        assert_eq!(widths(&read("seed-long")).1, KERNELS_MAX_N);
    }

    /// How many inputs of a fixed corpus reach each path of each engine
    /// (the kernel's width, the adaptive solver's path, the merge's
    /// integer width) at the target's probe times, on the image data the
    /// engines see. Every path must be reached: the similarity, not the
    /// size of the data, brings the wide widths. `--nocapture` prints the
    /// counts.
    #[test]
    fn kernels_reaches_every_engine_and_width() {
        let mut reach: BTreeMap<String, usize> = BTreeMap::new();
        let mut count = |key: String| *reach.entry(key).or_default() += 1;
        let inputs = corpus(400);
        for bytes in &inputs {
            let (similarity, small) = kernels_input(bytes);
            let image = similarity.data(&small);
            let times = probe_times(&Trajectory::new(small.clone()), Some(KERNELS_PROBES));
            let d = IntegerData::new(&image);
            let mut seen = std::collections::BTreeSet::new();
            for t in &times {
                seen.insert(format!("kernel {:?}", blocks_at(&d, t).width()));
                seen.insert(match adaptive_blocks_at(&d, t).path {
                    Path::Integer(w) => format!("adaptive Integer({w:?})"),
                    Path::Certified { exact, .. } if exact > 0 => {
                        "adaptive Certified, some exact".into()
                    }
                    Path::Certified { .. } => "adaptive Certified, all f64".into(),
                    Path::Exact(w) => format!("adaptive Exact({w:?})"),
                });
            }
            // The merge is asked on every input where it computes on
            // integers; left out only where it would run the generic
            // `BigRational` merge on more than `KERNELS_GENERIC_MAX_N`.
            let merge = IntegerTrajectory::new(&image).engine();
            if kernels_asks(&crate::fast::engine::Merge, &image) {
                seen.insert(format!("merge {merge:?}"));
            } else {
                assert_eq!(merge, crate::fast::merge::Engine::BigRational, "{bytes:?}");
                assert!(image.n() > KERNELS_GENERIC_MAX_N);
                seen.insert("merge BigRational, not asked".into());
            }
            seen.into_iter().for_each(&mut count);
            // The target itself passes on every input of the corpus.
            kernels(bytes);
        }
        eprintln!("inputs reaching each path (of {}):", inputs.len());
        for (path, n) in &reach {
            eprintln!("  {path}: {n}");
        }
        for path in [
            "kernel I128",
            "kernel I256",
            "kernel I512",
            "kernel Big",
            "adaptive Integer(I128)",
            "adaptive Integer(I256)",
            "adaptive Integer(I512)",
            "adaptive Certified, all f64",
            "adaptive Certified, some exact",
            "adaptive Exact(Big)",
            "merge Int64",
            "merge Int128",
            "merge BigRational",
        ] {
            assert!(
                reach.get(path).is_some_and(|&n| n > 0),
                "no input reaches {path}: {reach:?}"
            );
        }
    }
}
