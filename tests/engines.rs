//! Every exact engine of `sticky::fast::engine::ENGINES` against the generic
//! `BigRational` oracle, through the one oracle battery
//! (`sticky::fast::battery`): `prop:proj-micro`'s `x(t) = P_K(x⁰ + t u⁰)`,
//! the right-derivative velocities and the multipliers of `eq:dyn-micro`
//! must come out the same whatever algorithm and integer type computed
//! them, and the event engines must record the generic merge's impulses and
//! join times. The data: random scenes scaled across the `i128`, 256-bit and
//! `BigInt` widths (the overflow edges included), hand-built degenerate
//! scenes (simultaneous collisions of several clusters, contacts at `t = 0`,
//! times equal in `f64`), the width bound of the integer merge, and
//! proptest-generated scenes.

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Zero};
use proptest::prelude::*;

use sticky::fast::battery;
use sticky::fast::kernel::{blocks_at, IntegerData, Width};
use sticky::fast::merge::{Engine, IntegerTrajectory};
use sticky::generate::{initial_data, Limits, SplitMix64};
use sticky::initial::unshift;
use sticky::trajectory::Trajectory;
use sticky::InitialData;

fn q(n: i64, d: i64) -> BigRational {
    BigRational::new(BigInt::from(n), BigInt::from(d))
}

fn pow2(k: u32) -> BigRational {
    BigRational::from_integer(BigInt::one() << k)
}

/// Admissible data from translated positions `x̃⁰` (`df:translat-x`).
fn from_shifted(
    two_r: BigRational,
    xt: Vec<BigRational>,
    u: Vec<BigRational>,
) -> InitialData<BigRational> {
    let positions = unshift(&xt, &two_r);
    InitialData::new(two_r / q(2, 1), positions, u).expect("admissible test data")
}

/// Every engine on `data` through the oracle battery (panics on the first
/// difference), then what only the integer event engine reports: the width
/// it ran on, its counts of impulses and distinct instants. `limit` bounds
/// the number of probed collision instants (`None`: all of them).
fn agree_with(
    data: &InitialData<BigRational>,
    limit: Option<usize>,
) -> (Engine, Trajectory<BigRational>) {
    let slow = battery::check_probes(data, limit).unwrap_or_else(|m| panic!("{m}"));
    let it = IntegerTrajectory::new(data);
    assert_eq!(it.events(), slow.impulses().len(), "events()");
    let mut distinct = slow.impulses().iter().map(|i| &i.t).collect::<Vec<_>>();
    distinct.dedup();
    assert_eq!(it.instants(), distinct.len(), "instants()");
    (it.engine(), slow)
}

fn agree(data: &InitialData<BigRational>) -> (Engine, Trajectory<BigRational>) {
    agree_with(data, None)
}

#[test]
#[ignore = "campaign: 2,400 random scenes through every engine, minutes; CI runs it (cargo test --release -- --ignored)"]
fn random_scenes() {
    let mut rng = SplitMix64::new(0x5EED_0001);
    let mut engines = [0usize; 3];
    let mut events = 0;
    for k in 0..2400usize {
        let limits = match k % 3 {
            0 => Limits {
                max_n: 1 + k % 200,
                ..Limits::default()
            },
            1 => Limits {
                max_n: 1 + k % 200,
                max_den: 1 + (k % 97) as u32,
                max_speed: 1 + (k % 1000) as u32,
            },
            _ => Limits {
                max_n: 1 + k % 40,
                max_den: 2,
                max_speed: 2,
            },
        };
        let data = initial_data(&rng.bytes(1 + k % 1200), limits);
        let (engine, slow) = agree_with(&data, Some(10));
        events += slow.impulses().len();
        engines[match engine {
            Engine::Int64 => 0,
            Engine::Int128 => 1,
            Engine::BigRational => 2,
        }] += 1;
    }
    // Denominators up to 97 can have an lcm beyond the i128 bound, so a few
    // scenes take the fallback (and are still compared).
    eprintln!("engines (Int64, Int128, BigRational): {engines:?}, {events} impulses");
    assert!(engines[0] > 2000, "most scenes run on the integer engine");
    assert!(events > 20_000, "the scenes collide ({events} impulses)");
}

#[test]
fn one_particle() {
    let data = InitialData::new(q(1, 2), vec![q(3, 1)], vec![q(-2, 1)]).unwrap();
    let (engine, slow) = agree(&data);
    assert_eq!(engine, Engine::Int64);
    assert!(slow.impulses().is_empty());
}

#[test]
fn four_clusters_meet_at_one_instant() {
    // Sizes 1, 2, 1, 3 with velocities 3, 1, 0, −2 all reach x̃ = 10 at t = 2.
    let v = [3, 1, 1, 0, -2, -2, -2];
    let xt: Vec<BigRational> = v.iter().map(|&s| q(10 - 2 * s, 1)).collect();
    let u: Vec<BigRational> = v.iter().map(|&s| q(s, 1)).collect();
    let (_, slow) = agree(&from_shifted(q(1, 3), xt, u));
    assert_eq!(slow.impulses().len(), 1);
    let imp = &slow.impulses()[0];
    assert_eq!(imp.t, q(2, 1));
    assert_eq!(
        imp.parts.iter().map(|c| c.size).collect::<Vec<_>>(),
        vec![1, 2, 1, 3]
    );
}

#[test]
fn two_separate_simultaneous_collisions() {
    // Pairs (0,1) and (2,3) both collide at t = 1; (1,2) separate.
    let xt = [0, 2, 5, 7].map(|v| q(v, 1)).to_vec();
    let u = [1, -1, 1, -1].map(|v| q(v, 1)).to_vec();
    let (_, slow) = agree(&from_shifted(q(1, 1), xt, u));
    let times: Vec<_> = slow.impulses().iter().map(|i| i.t.clone()).collect();
    assert_eq!(times, vec![q(1, 1), q(1, 1)]);
    assert_eq!(slow.impulses()[0].cluster.first, 0);
    assert_eq!(slow.impulses()[1].cluster.first, 2);
}

#[test]
fn contacts_at_zero_that_separate_or_stick() {
    // 0|1 in contact and separating, 2=3 in contact with equal velocities
    // (one initial cluster), later hit by 4.
    let xt = [0, 0, 3, 3, 6].map(|v| q(v, 1)).to_vec();
    let u = [-1, 1, 0, 0, -3].map(|v| q(v, 1)).to_vec();
    let (_, slow) = agree(&from_shifted(q(1, 2), xt, u));
    assert_eq!(slow.join_times()[0], None);
    assert_eq!(slow.join_times()[2], Some(BigRational::zero()));
    assert_eq!(slow.impulses().len(), 2);
}

#[test]
fn times_equal_in_f64_are_ordered_exactly() {
    // Pair (0,1) meets at G + 1, pair (2,3) at G, G = 2^60: the doubles of
    // the two times coincide and the leftmost-first tie-break would put the
    // left pair first; the exact order puts the right pair first.
    let g = pow2(60);
    let h = pow2(62);
    let xt = vec![q(0, 1), g.clone() + q(1, 1), h.clone(), h + &g];
    let u = [1, 0, 1, 0].map(|v| q(v, 1)).to_vec();
    let (engine, slow) = agree(&from_shifted(q(1, 1), xt, u));
    assert_eq!(engine, Engine::Int64);
    let firsts: Vec<_> = slow.impulses().iter().map(|i| i.cluster.first).collect();
    assert_eq!(firsts, vec![2, 0]);
    assert_eq!(slow.impulses()[0].t, g);
}

#[test]
fn equal_times_with_different_representations_form_one_instant() {
    // Clusters of sizes 2, 1, 3 with velocities 5/7, 0, −3/11 all reach m at
    // T = (2^61 + 1)/3; a fifth and sixth cluster further right meet at
    // T + 2^-40 (equal to T in f64), then one more pair at exactly T.
    let t = (pow2(61) + q(1, 1)) / q(3, 1);
    let m = pow2(62);
    let mut xt = Vec::new();
    let mut u = Vec::new();
    for (size, v) in [(2, q(5, 7)), (1, q(0, 1)), (3, q(-3, 11))] {
        for _ in 0..size {
            xt.push(m.clone() - &t * &v);
            u.push(v.clone());
        }
    }
    let m2 = pow2(63);
    let t2 = t.clone() + q(1, 1) / pow2(40);
    for v in [q(1, 3), q(-1, 5)] {
        xt.push(m2.clone() - &t2 * &v);
        u.push(v);
    }
    let m3 = pow2(63) + pow2(62);
    for v in [q(1, 2), q(-1, 2)] {
        xt.push(m3.clone() - &t * &v);
        u.push(v);
    }
    let (engine, slow) = agree(&from_shifted(q(1, 64), xt, u));
    assert_eq!(engine, Engine::Int128);
    let summary: Vec<_> = slow
        .impulses()
        .iter()
        .take(3)
        .map(|i| (i.t.clone(), i.cluster.first, i.parts.len()))
        .collect();
    assert_eq!(
        summary,
        vec![(t.clone(), 0, 3), (t.clone(), 8, 2), (t2, 6, 2)]
    );
}

#[test]
fn wide_words_and_the_bigint_scaling_path() {
    // Positions near 2^80: the scaled data need i128 (still within the bound).
    let base = pow2(80);
    let xt: Vec<BigRational> = [0, 3, 4, 9, 20]
        .iter()
        .map(|&v| base.clone() + q(v, 1))
        .collect();
    let u = [2, 1, 0, -1, -5].map(|v| q(v, 3)).to_vec();
    assert_eq!(agree(&from_shifted(q(1, 2), xt, u)).0, Engine::Int128);
    // 2r = 2^-130: the positions' denominators overflow u128 but the
    // translated positions are integers (the BigInt scaling path).
    let two_r = q(1, 1) / pow2(130);
    let xt = [0, 1, 1, 5, 6].map(|v| q(v, 1)).to_vec();
    let u = [3, 1, 2, -2, -4].map(|v| q(v, 1)).to_vec();
    assert_eq!(agree(&from_shifted(two_r, xt, u)).0, Engine::Int64);
}

#[test]
fn fallback_to_bigrational() {
    // max|X| = 2^124 + …, N = 8: max(N, N²/4) · M ≥ 2^126, so the bound fails
    // although every value fits i128.
    let big = pow2(124);
    let xt: Vec<BigRational> = (0..8)
        .map(|i| {
            if i < 4 {
                q(i, 1)
            } else {
                big.clone() + q(i, 1)
            }
        })
        .collect();
    let u: Vec<BigRational> = (0..8).map(|i| q(4 - i, 1)).collect();
    let (engine, slow) = agree(&from_shifted(q(1, 1), xt, u));
    assert_eq!(engine, Engine::BigRational);
    assert!(!slow.impulses().is_empty());
    // Beyond i128.
    let huge = pow2(200);
    let xt = vec![q(0, 1), q(3, 1), huge.clone(), huge + q(5, 1)];
    let u = vec![q(1, 1), q(-1, 1), q(1, 3), q(-1, 7)];
    assert_eq!(agree(&from_shifted(q(1, 3), xt, u)).0, Engine::BigRational);
    // Just inside the bound: N = 8, M < 2^126 / 16.
    let xt: Vec<BigRational> = (0..8)
        .map(|i| if i < 4 { q(i, 1) } else { pow2(121) + q(i, 1) })
        .collect();
    let u: Vec<BigRational> = (0..8).map(|i| q(4 - i, 1)).collect();
    assert_eq!(agree(&from_shifted(q(1, 1), xt, u)).0, Engine::Int128);
}

#[test]
fn near_ties_at_scale() {
    // Pairs meeting at T + δ with T = 2^50 and |δ| ≤ 3: distinct times that
    // agree to 15 digits (inside the float filter's margin and the queue's
    // bracket), exact ties, and later collisions between the pairs.
    let mut rng = SplitMix64::new(77);
    let big_t = 1i64 << 50;
    for _ in 0..40 {
        let pairs = 1 + (rng.next_u64() % 60) as usize;
        let mut xt = Vec::new();
        let mut u = Vec::new();
        let mut pos = 0i64;
        for _ in 0..pairs {
            let a = (rng.next_u64() % 5) as i64 - 2;
            let b = a - 1 - (rng.next_u64() % 3) as i64;
            let delta = (rng.next_u64() % 7) as i64 - 3;
            pos += 1 + (rng.next_u64() % 4) as i64 * (big_t / 4);
            xt.push(q(pos, 1));
            u.push(q(a, 1));
            pos += (a - b) * (big_t + delta);
            xt.push(q(pos, 1));
            u.push(q(b, 1));
        }
        let (engine, slow) = agree_with(&from_shifted(q(1, 2), xt, u), Some(20));
        assert_eq!(engine, Engine::Int64);
        assert!(!slow.impulses().is_empty());
    }
}

#[test]
fn chain_reaction_ahead_of_the_queue() {
    // A fast particle sweeps up 400 resting ones one by one while 100 pairs
    // far to the right meet much later: every new candidate falls before
    // the entries already taken out of the queue.
    let mut xt = vec![q(0, 1)];
    let mut u = vec![q(50, 1)];
    for i in 0..400 {
        xt.push(q(10 + i, 1));
        u.push(q(0, 1));
    }
    for k in 0..100 {
        let base = 1_000_000 + 10_000 * k;
        xt.push(q(base, 1));
        u.push(q(1, 1));
        xt.push(q(base + 5_000 + k, 1));
        u.push(q(-1, 1));
    }
    let (_, slow) = agree_with(&from_shifted(q(1, 2), xt, u), Some(30));
    assert!(slow.impulses().len() >= 500);
}

#[test]
fn bench_scenes_agree() {
    for (n, seed) in [(1, 1), (2, 2), (50, 3), (300, 4), (2000, 5)] {
        let data = sticky::report::bench::scene(n, seed);
        let (engine, _) = agree_with(&data, Some(12));
        assert_eq!(engine, Engine::Int64);
    }
}

/// The data, every position scaled by `2^scale` and shifted by
/// `2^offset + 1/3`: large scales push `b_Y` across the `i128` and 256-bit
/// bounds, the offset adds digits that no width absorbs by cancellation.
fn scaled(bytes: &[u8], max_n: usize, scale: u32, offset: u32) -> InitialData<BigRational> {
    let data = initial_data(
        bytes,
        Limits {
            max_n,
            ..Limits::default()
        },
    );
    let s = BigRational::from_integer(BigInt::one() << scale);
    let o = BigRational::from_integer(BigInt::one() << offset)
        + BigRational::new(BigInt::one(), BigInt::from(3));
    let x = data.positions().iter().map(|x| x * &s + &o).collect();
    let r = data.radius() * &s;
    let u = data.velocities().iter().map(|u| u * &s).collect();
    InitialData::new(r, x, u).expect("scaling and shifting keep the data admissible")
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: if cfg!(debug_assertions) { 64 } else { 512 },
        ..ProptestConfig::default()
    })]

    /// Every engine equals the generic path, field by field, at a random
    /// time, on data scaled into every integer width.
    #[test]
    fn engines_equal_the_oracle_in_every_width(
        bytes in proptest::collection::vec(any::<u8>(), 0..200),
        max_n in 1usize..40,
        scale in 0u32..300,
        offset in 0u32..660,
        tn in 0i64..1000,
        td in 1i64..1000,
    ) {
        let data = scaled(&bytes, max_n, scale, offset);
        let t = BigRational::new(BigInt::from(tn), BigInt::from(td));
        if let Err(m) = battery::check(&data, &[t]) {
            return Err(TestCaseError::fail(m.to_string()));
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 300,
        failure_persistence: None,
        ..ProptestConfig::default()
    })]

    /// Every engine at the collision instants (exact ties) and between
    /// them, on scenes of every density of denominators and speeds.
    #[test]
    fn prop_engines_agree(
        bytes in proptest::collection::vec(any::<u8>(), 0..600),
        max_n in 1usize..120,
        max_den in 1u32..64,
        max_speed in 1u32..400,
    ) {
        let data = initial_data(&bytes, Limits { max_n, max_den, max_speed });
        if let Err(m) = battery::check_probes(&data, Some(8)).map(drop) {
            return Err(TestCaseError::fail(m.to_string()));
        }
    }
}

/// The proptest ranges above reach every width (a guard against a generator
/// that silently stops exercising one).
#[test]
fn the_ranges_reach_every_width() {
    let bytes: Vec<u8> = (0..120u8).map(|b| b.wrapping_mul(37)).collect();
    let t = BigRational::new(BigInt::from(7), BigInt::from(3));
    let width = |scale, offset| {
        blocks_at(&IntegerData::new(&scaled(&bytes, 30, scale, offset)), &t).width()
    };
    assert_eq!(width(0, 0), Width::I128);
    assert_eq!(width(0, 100), Width::I256);
    assert_eq!(width(250, 0), Width::I512);
    assert_eq!(width(0, 320), Width::I512);
    assert_eq!(width(0, 600), Width::Big);
}

/// The hostile shape of issue 29 at small N: velocities `(-1)^i/(i+1)`, so
/// every denominator is small and their common denominator
/// `lcm(1, …, N)` is not; the particles 3 apart (r = 1/2) collide in
/// cascade. Every engine equals the oracle, and `auto` leaves the
/// common-denominator kernel for the blockwise projection (one common
/// denominator per block, `sticky::blockwise`) on this shape at
/// N = 400 (lcm(1..400): 574 bits) but keeps the kernel at N = 8.
#[test]
fn hostile_common_denominators() {
    use sticky::solver::choice::cheapest;
    use sticky::solver::cost::{Bits, Cost};
    let auto = |d: &InitialData<BigRational>| cheapest(&Cost::of(d));
    let hostile = |n: i64| {
        InitialData::new(
            q(1, 2),
            (0..n).map(|i| q(3 * i, 1)).collect(),
            (0..n)
                .map(|i| q(if i % 2 == 0 { 1 } else { -1 }, i + 1))
                .collect(),
        )
        .unwrap()
    };
    for n in [2, 5, 12, 30] {
        let (_, t) = agree(&hostile(n));
        assert!(t.impulses().len() as i64 >= n / 2, "N = {n}");
    }
    let small = Cost::of(&hostile(8));
    assert_eq!(small.common_denominator, Bits::Exact(10)); // lcm(1..8) = 840
    assert_eq!(auto(&hostile(8)).name(), "kernel");
    let big = Cost::of(&hostile(400));
    assert_eq!(big.common_denominator, Bits::Exact(574));
    assert_eq!(big.largest_denominator_bits, 9);
    assert_eq!(auto(&hostile(400)).name(), "blockwise");
    let line = big.explain(auto(&hostile(400)));
    assert!(
        line.contains("blockwise") && line.contains("574 bits") && line.contains("N = 400"),
        "{line}"
    );
}
