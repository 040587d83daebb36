use super::*;
use crate::generate::{initial_data, Limits, SplitMix64};
use num_traits::One;

#[test]
fn equals_the_generic_path() {
    let mut rng = SplitMix64::new(11);
    for k in 0..300 {
        let data = initial_data(
            &rng.bytes(200),
            Limits {
                max_n: 1 + k % 40,
                ..Limits::default()
            },
        );
        let d = IntegerData::new(&data);
        let traj = crate::trajectory::Trajectory::new(data.clone());
        for t in crate::trajectory::probe_times(&traj, Some(6)) {
            assert_eq!(
                state_at(&d, &t).unwrap(),
                projection::state_at(&data, &t).unwrap(),
                "t = {t}"
            );
        }
    }
}

use crate::rational::ratio as q;

/// Four particles around `offset`, two pairs colliding at different
/// times, one contact at `t = 0` that separates.
fn around(offset: &BigRational, spread: &BigRational) -> InitialData<BigRational> {
    let x = [0, 3, 4, 9].map(|v| offset + spread * q(v, 1)).to_vec();
    let u = vec![q(1, 1), q(-1, 1), q(1, 3), q(-1, 7)];
    InitialData::new(q(1, 2), x, u).unwrap()
}

fn pow2(e: u32) -> BigRational {
    BigRational::from_integer(BigInt::one() << e)
}

/// Each width, on both sides of its bound, equals the generic path.
#[test]
fn every_width_equals_the_generic_path() {
    let cases = [
        (pow2(0), pow2(0), Width::I128),
        (pow2(60), pow2(0), Width::I128),
        (pow2(62), pow2(3), Width::I128),
        (pow2(70), pow2(0), Width::I256),
        (pow2(140), pow2(0), Width::I256),
        (pow2(240), pow2(2), Width::I256),
        (pow2(300), pow2(1), Width::I512),
        (pow2(480), pow2(2), Width::I512),
        (pow2(600), pow2(1), Width::Big),
        (pow2(140), pow2(130), Width::I256),
        (pow2(300), pow2(200), Width::I512),
    ];
    for (offset, spread, width) in cases {
        let data = around(&offset, &spread);
        let d = IntegerData::new(&data);
        for t in [
            q(0, 1),
            q(1, 1),
            q(5, 2),
            spread.clone() * q(3, 1),
            offset.clone(),
        ] {
            let b = blocks_at(&d, &t);
            if t == q(0, 1) {
                assert_eq!(b.width(), width, "offset 2^{}", offset.numer().bits());
            }
            assert_eq!(
                state_at(&d, &t).unwrap(),
                projection::state_at(&data, &t).unwrap(),
                "offset 2^{}, t = {t}",
                offset.numer().bits()
            );
        }
    }
}

/// The 512-bit loop keeps `ΣU` in `i128` when every `U_i` fits `i64`
/// (and `bits(max|U|) + b_K < 128`, implied here) and in 512 bits
/// otherwise: both equal the generic path, on both sides of that bound.
#[test]
fn both_u_words_of_the_512_bit_loop() {
    // U_i = 21 u_i 2^e (D_u = 21): max|U| = 21 · 2^e has e + 5 bits.
    for (e, narrow) in [(0u32, true), (58, true), (59, false), (200, false)] {
        let base = around(&pow2(300), &pow2(1));
        let u = base.velocities().iter().map(|v| v * pow2(e)).collect();
        let data = InitialData::new(q(1, 2), base.positions().to_vec(), u).unwrap();
        let d = IntegerData::new(&data);
        for t in [q(0, 1), q(1, 1), q(5, 2), pow2(290)] {
            let b = blocks_at(&d, &t);
            assert_eq!(b.width(), Width::I512, "2^{e}, t = {t}");
            assert_eq!(matches!(b.sums, Sums::I512U128(_)), narrow, "2^{e}");
            assert_eq!(
                state_at(&d, &t).unwrap(),
                projection::state_at(&data, &t).unwrap(),
                "2^{e}, t = {t}"
            );
        }
    }
}

/// The shape of a sparse 512-bit result: the sums of exactly the
/// blocks of several entries are stored, in order, and a block of one
/// entry is that entry's index.
fn sparse_shape<V: FromColumn>(s: &Sparse<8, V>, clusters: &[Cluster]) {
    let several: Vec<u64> = clusters
        .iter()
        .filter(|c| c.size > 1)
        .map(|c| c.size as u64)
        .collect();
    let stored: Vec<u64> = s.pooled.iter().map(|r| r.k).collect();
    assert_eq!(stored, several);
    assert_eq!(s.tags.len(), clusters.len());
    for (&tag, c) in s.tags.iter().zip(clusters) {
        assert_eq!(tag & POOLED == 0, c.size == 1);
        if c.size == 1 {
            assert_eq!(tag, c.first as u64);
        }
    }
}

/// The sparse 512-bit blocks ([`Sparse`]) on random scenes lifted by
/// `2^300` (velocities by `2^200` in every other scene, the wide `ΣU`),
/// where pools reach below blocks of one entry that the loop
/// recomputes: the shape above, and the state equals the generic path.
#[test]
fn sparse_512_bit_blocks_equal_the_generic_path() {
    let mut rng = SplitMix64::new(13);
    let mut checked = [0usize; 2];
    for k in 0..160 {
        let base = initial_data(
            &rng.bytes(200),
            Limits {
                max_n: 2 + k % 30,
                ..Limits::default()
            },
        );
        let x = base.positions().iter().map(|x| x + pow2(300)).collect();
        let lift = if k % 2 == 0 { pow2(0) } else { pow2(200) };
        let u = base.velocities().iter().map(|v| v * &lift).collect();
        let data = InitialData::new(base.radius().clone(), x, u).unwrap();
        let d = IntegerData::new(&data);
        let traj = crate::trajectory::Trajectory::new(data.clone());
        for t in crate::trajectory::probe_times(&traj, Some(6)) {
            let b = blocks_at(&d, &t);
            match &b.sums {
                Sums::I512U128(s) => {
                    sparse_shape(s, &b.clusters());
                    checked[0] += 1;
                }
                Sums::I512(s) => {
                    sparse_shape(s, &b.clusters());
                    checked[1] += 1;
                }
                _ => {}
            }
            assert_eq!(
                state_at(&d, &t).unwrap(),
                projection::state_at(&data, &t).unwrap(),
                "scene {k}, t = {t}"
            );
        }
    }
    // Both `ΣU` words were exercised, many times each.
    assert!(checked.iter().all(|&c| c > 100), "{checked:?}");
}

/// Right at the `i128`, `I256` and `I512` bounds: four particles `2^bits` apart
/// that all meet, so the loop's sums come within a factor 4 of `Y`'s
/// bound, at times whose denominator `q` pushes `b_Y + b_K` to the edge
/// of each width (`b_K = 3` for N = 4). The result equals the generic
/// path on both sides.
#[test]
fn sums_near_the_width_edge() {
    let inv = |e: u32| BigRational::new(BigInt::one(), BigInt::one() << e);
    // (spacing bits, t, expected width)
    let cases = [
        // X_i up to 3·2^59 (61 bits), q D_u = 2^61 (62 bits):
        // b_Y = 62 + 61 + 1 = 124, b_Y + b_K = 127 < 128.
        (60u32, inv(61), Width::I128),
        // q D_u = 2^62 (63 bits, still an i64): 128, not < 128.
        (60, inv(62), Width::I256),
        // q D_u = 2^63 no longer fits i64.
        (60, inv(63), Width::I256),
        // X_i up to 3·2^189 (191 bits), q D_u = 2^60 (61 bits):
        // b_Y + b_K = 61 + 191 + 1 + 3 = 256, not < 256.
        (190, inv(60), Width::I512),
        // One bit less: 255 < 256.
        (190, inv(59), Width::I256),
        // X_i up to 3·2^445 (447 bits), q D_u = 2^60 (61 bits):
        // b_Y + b_K = 61 + 447 + 1 + 3 = 512, not < 512.
        (446, inv(60), Width::Big),
        // One bit less: 511 < 512.
        (446, inv(59), Width::I512),
        // The columns no longer fit 510 bits (X_i up to 3·2^509).
        (510, inv(0), Width::Big),
    ];
    for (bits, t, width) in cases {
        let big = pow2(bits);
        let x = [0, 1, 2, 3].map(|v| big.clone() * q(2 * v - 3, 2)).to_vec();
        let u = vec![q(3, 1), q(1, 1), q(-1, 1), q(-3, 1)];
        let data = InitialData::new(q(1, 2), x, u).unwrap();
        let d = IntegerData::new(&data);
        let b = blocks_at(&d, &t);
        assert_eq!(b.width(), width, "2^{bits}, t = {t}");
        for s in [
            t.clone(),
            t.clone() * big.clone(),
            t.clone() * big.clone() * q(3, 1),
        ] {
            assert_eq!(
                state_at(&d, &s).unwrap(),
                projection::state_at(&data, &s).unwrap()
            );
        }
    }
}

/// Two `Blocks` are equal exactly when their clusters and their means
/// (`x̃` and `u`) are, whatever the width the sums are held in; no
/// particles, no blocks.
#[test]
fn blocks_equal_by_clusters_and_means() {
    let run = |k: u64, sy: i128, su: i128| Run { k, sy, su };
    let big = |v: &[Run<i128>]| {
        Sums::Big(
            v.iter()
                .map(|r| Run {
                    k: r.k,
                    sy: BigInt::from(r.sy),
                    su: BigInt::from(r.su),
                })
                .collect(),
        )
    };
    let blocks = |s: Sums| Blocks::new(s, BigInt::from(6), BigInt::from(3));
    // Means (y, u): (1/6, 1/3), (1/2, 2/3), then the same scaled by 2.
    let a = [run(1, 1, 1), run(2, 6, 4)];
    assert_eq!(blocks(Sums::I128(a.to_vec().into())), blocks(big(&a)));
    let scaled = [run(1, 1, 1), run(2, 6, 4)].map(|r| run(r.k, 2 * r.sy, 2 * r.su));
    let scaled = Blocks::new(
        Sums::I128(scaled.to_vec().into()),
        BigInt::from(12),
        BigInt::from(6),
    );
    assert_eq!(blocks(Sums::I128(a.to_vec().into())), scaled);
    // Other clusters, the same means: one block of three at (1/6, 1/3)
    // against blocks of one and two at (1/6, 1/3).
    let one = blocks(Sums::I128(vec![run(3, 3, 3)].into()));
    let two = blocks(Sums::I128(vec![run(1, 1, 1), run(2, 2, 2)].into()));
    assert_eq!(one.clusters().len(), 1);
    assert_ne!(one, two);
    assert_ne!(two, one);
    // The same clusters and positions, another velocity.
    let other_u = [run(1, 1, 1), run(2, 6, 2)];
    assert_ne!(
        blocks(Sums::I128(a.to_vec().into())),
        blocks(Sums::I128(other_u.to_vec().into()))
    );
    // The same clusters and velocities, another position.
    let other_y = [run(1, 1, 1), run(2, 8, 4)];
    assert_ne!(
        blocks(Sums::I128(a.to_vec().into())),
        blocks(Sums::I128(other_y.to_vec().into()))
    );
    assert!(blocks(Sums::I128(Vec::new().into())).is_empty());
    assert!(!blocks(Sums::I128(a.to_vec().into())).is_empty());
    assert_eq!(blocks(big(&a)).len(), 2);
}

/// The `i128` loop forced onto two threads from two entries on: the
/// kernel engine of the oracle battery with every split.
struct TwoThreads;

impl crate::fast::engine::ExactEngine for TwoThreads {
    fn name(&self) -> &'static str {
        "kernel, two threads from 2 entries"
    }
    fn summary(&self) -> &'static str {
        "the i128 PAVA on integers, halves on two threads"
    }
    fn prepare(&self, data: &InitialData<BigRational>) -> Box<dyn crate::fast::engine::Prepared> {
        struct Two(IntegerData);
        impl crate::fast::engine::Prepared for Two {
            fn state_at(&self, t: &BigRational) -> Result<State<BigRational>, Error> {
                let b = blocks_on(&self.0, t, 2);
                Ok(state_of_blocks(&self.0, &b, t))
            }
        }
        Box::new(Two(IntegerData::new(data)))
    }
}

/// The sums of the `i128` loop's blocks, `ΣU` widened (`None` for the
/// other widths).
fn i128_runs(b: &Blocks) -> Option<Vec<Run<i128>>> {
    match &b.sums {
        Sums::I128(v) => Some(v.iter().cloned().collect()),
        Sums::I128U64(v) => Some(
            v.iter()
                .map(|r| Run {
                    k: r.k,
                    sy: r.sy,
                    su: i128::from(r.su),
                })
                .collect(),
        ),
        _ => None,
    }
}

/// The two-thread loop through the oracle battery, at the probe times of
/// random scenes (contacts, chains, ties broken by `U`), and against the
/// one-thread loop block for block.
#[test]
fn two_threads_pass_the_battery() {
    use crate::fast::battery::check_engines;
    use crate::fast::engine::{ExactEngine, GenericProjection};
    let engines: [&dyn ExactEngine; 2] = [&GenericProjection, &TwoThreads];
    let mut rng = SplitMix64::new(47);
    let mut split = 0;
    for k in 0..240 {
        let data = initial_data(
            &rng.bytes(300),
            Limits {
                max_n: 2 + k % 50,
                max_den: 1 + (k % 3) as u32,
                max_speed: 1 + (k % 5) as u32,
            },
        );
        let d = IntegerData::new(&data);
        let traj = crate::trajectory::Trajectory::new(data.clone());
        let times = crate::trajectory::probe_times(&traj, Some(6));
        if let Err(m) = check_engines(&engines, &data, &times) {
            panic!("scene {k}: {m}");
        }
        for t in &times {
            let (one, two) = (blocks_on(&d, t, usize::MAX), blocks_on(&d, t, 2));
            if let (Some(a), Some(b)) = (i128_runs(&one), i128_runs(&two)) {
                assert_eq!(a, b, "scene {k}, t = {t}");
                split += 1;
            }
        }
    }
    assert!(split > 1000, "{split}");
}

/// Random `i64` columns with few distinct values (ties on `Y` broken by
/// `U`), large entries near the `i128` bound, and runs built to pool
/// across the middle: the two-halves join and the register loop give the
/// blocks of [`pava_words`], for every split point.
#[test]
fn halves_and_register_loop_equal_pava_words() {
    let mut rng = SplitMix64::new(5);
    let mut across = 0;
    for k in 0..400 {
        let n = 1 + k % 37;
        let span = [3u64, 50, 1 << 40][k % 3];
        let mut draw = || (rng.next_u64() % span) as i64 - (span / 2) as i64;
        let mut xs: Vec<i64> = (0..n).map(|_| draw()).collect();
        let us: Vec<i64> = (0..n).map(|_| draw()).collect();
        if k % 4 == 3 {
            // Decreasing: everything pools into one block, across the cut.
            xs.sort_unstable_by(|a, b| b.cmp(a));
        }
        let (a, b) = [(1, 0), (3, 2), (1 << 20, -(1 << 20)), (0, 1)][k % 4];
        let want = pava_words(n, |i| {
            let (x, u) = (i128::from(xs[i]), i128::from(us[i]));
            (a * x + b * u, u)
        });
        assert_eq!(small::pava(&xs, &us, a as i64, b as i64), want, "case {k}");
        let narrow: Vec<Run<i128>> = small::pava::<i64>(&xs, &us, a as i64, b as i64)
            .into_iter()
            .map(|r| Run {
                k: r.k,
                sy: r.sy,
                su: i128::from(r.su),
            })
            .collect();
        assert_eq!(narrow, want, "case {k}, i64 U sums");
        // The streaming path's entry: both halves joined into one vector,
        // U sums in i64 (|U| < 2^40, N < 2^6) or, bound taken loose, i128.
        for u_bits in [41, 63] {
            let got = word_runs_on(&xs, &us, a as i64, b as i64, u_bits, 2);
            assert_eq!(got, want, "case {k}, u_bits {u_bits}");
        }
        for h in 0..=n {
            let left = small::pava(&xs[..h], &us[..h], a as i64, b as i64);
            let right = small::pava(&xs[h..], &us[h..], a as i64, b as i64);
            let pooled = left.len() + right.len() > want.len();
            let parts = halves::join(left, right);
            assert_eq!(parts.len(), want.len(), "case {k}, cut {h}");
            let got: Vec<Run<i128>> = (0..parts.len()).map(|j| parts.get(j).clone()).collect();
            assert_eq!(got, want, "case {k}, cut {h}");
            assert!(parts.iter().eq(want.iter()), "case {k}, cut {h}");
            across += usize::from(pooled);
        }
    }
    assert!(across > 500, "{across}");
}

/// The `i128` loop keeps `ΣU` in `i64` exactly when `bits(N) +
/// bits(max|U|) ≤ 63`: four particles of velocities `c + 3, c + 1, c − 1,
/// c − 3` one unit apart (`r = 1/2`), which all meet at `t = 1/2`, so that
/// at `t ≥ 1/2` one block sums `ΣU = 4c`: with `c = 2^59` (`bits 60 + 3 =
/// 63`) in `i64`; with `c = 2^61` (`62 + 3 = 65`, and `4c = 2^63` would
/// wrap an `i64`) in `i128`. Both equal the generic path.
#[test]
fn both_u_words_of_the_i128_loop() {
    for (e, narrow) in [(59u32, true), (60, false), (61, false)] {
        let c = pow2(e);
        let x = (0..4).map(|i| q(2 * i, 1)).collect();
        let u = [3, 1, -1, -3].map(|v| c.clone() + q(v, 1)).to_vec();
        let data = InitialData::new(q(1, 2), x, u).unwrap();
        let d = IntegerData::new(&data);
        for t in [q(0, 1), q(1, 4), q(1, 2), q(1, 1)] {
            for parallel_min in [2, usize::MAX] {
                let b = blocks_on(&d, &t, parallel_min);
                assert_eq!(b.width(), Width::I128, "2^{e}, t = {t}");
                assert_eq!(matches!(b.sums, Sums::I128U64(_)), narrow, "2^{e}");
                assert_eq!(
                    state_of_blocks(&d, &b, &t),
                    projection::state_at(&data, &t).unwrap(),
                    "2^{e}, t = {t}"
                );
            }
        }
        assert_eq!(blocks_at(&d, &q(1, 1)).len(), 1, "2^{e}");
    }
}
