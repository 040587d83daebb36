use std::io;

use super::*;
use crate::fast::int::gcd;
use crate::fast::int::narrowed;
use crate::fast::kernel::{state_at, IntegerData};
use crate::fast::scaling::small_word;
use crate::generate::{initial_data, Limits, SplitMix64};
use crate::initial::InitialData;
use crate::rational::ratio as q;
use crate::trajectory::{probe_times, Trajectory};

/// A visitor of values, as `LeanBlocks` calls it.
type Sink<'a> = dyn FnMut(&Exact) -> io::Result<()> + 'a;

/// The value of `v`, checked to be in lowest terms with `den > 0`.
fn value(v: &Exact) -> BigRational {
    if let Exact::Small(n, d) = *v {
        assert!(
            d > 0 && gcd(n.unsigned_abs(), d.unsigned_abs()) == 1,
            "{v:?}"
        );
    }
    let (n, d) = v.numer_denom();
    BigRational::new(n, d)
}

/// `data` as word pairs, the radius given (`None`: the paper's `1/(2N)`).
fn lean(data: &InitialData<BigRational>, radius: bool) -> Option<Lean> {
    let col = |v: &[BigRational]| narrowed(v, small_word);
    let r = radius.then(|| data.radius().clone());
    Lean::new(r, 0, col(data.positions())?, col(data.velocities())?)
}

/// The streaming path's state — positions, velocities, multipliers,
/// clusters, row by row as well — is the kernel's at every probe time
/// (collision instants and between), each value in lowest terms, and
/// its event history is the generic event merge's.
#[test]
fn lean_state_and_history_are_the_kernels() {
    let mut rng = SplitMix64::new(31);
    for k in 0..120 {
        let data = initial_data(
            &rng.bytes(200),
            Limits {
                max_n: 1 + k % 25,
                max_den: 1 + (k % 6) as u32,
                max_speed: 1 + (k % 7) as u32,
            },
        );
        let n = data.n();
        let l = lean(&data, true).expect("small data on words");
        assert_eq!((l.n(), l.radius()), (n, data.radius()));
        let d = IntegerData::new(&data);
        let history = Trajectory::new(data.clone());
        for t in probe_times(&history, Some(6)) {
            let want = state_at(&d, &t).unwrap();
            let b = l.blocks_at(&t).expect("within the i128 bound");
            assert_eq!((b.t(), b.n()), (&t, n));
            let collect = |visit: &dyn Fn(&mut Sink)| {
                let mut v = Vec::new();
                visit(&mut |e| {
                    v.push(value(e));
                    Ok(())
                });
                v
            };
            let xs = collect(&|f| b.positions(f).unwrap());
            let us = collect(&|f| b.velocities(f).unwrap());
            let ls = collect(&|f| b.multipliers(f).unwrap());
            assert_eq!(xs, want.positions, "scene {k}, t = {t}");
            assert_eq!(us, want.velocities, "scene {k}, t = {t}");
            assert_eq!(ls, want.multipliers, "scene {k}, t = {t}");
            assert_eq!(b.clusters(), want.clusters, "scene {k}, t = {t}");
            let mut rows = 0;
            b.rows(|i, x, u, lambda| {
                assert_eq!(i, rows);
                assert_eq!((value(x), value(u)), (xs[i].clone(), us[i].clone()));
                assert_eq!(lambda.map(value), ls.get(i).cloned());
                rows += 1;
                Ok(())
            })
            .unwrap();
            assert_eq!(rows, n);
        }
        let events = lean_events(&l);
        let want: Vec<_> = history
            .impulses()
            .iter()
            .map(|i| {
                let parts = i.parts.iter().map(|c| c.size as u32).collect();
                (i.t.clone(), i.cluster.first, i.cluster.size, parts)
            })
            .collect();
        assert_eq!(events, want, "scene {k}");
    }
}

/// Without a radius the scene takes the paper's `r = 1/(2N)`; data that
/// `InitialData::new` refuses (overlap, crossing velocities at a
/// contact), columns of different lengths, no particles, a negative time
/// and values beyond the number budget are declined (`None`).
#[test]
fn lean_declines_what_the_general_path_refuses() {
    let xs = vec![(0, 1), (1, 2), (3, 1)];
    let us = vec![(1, 1), (-1, 3), (0, 1)];
    let l = Lean::new(None, 0, xs.clone(), us.clone()).unwrap();
    assert_eq!(l.radius(), &q(1, 6));
    let general = InitialData::with_paper_radius(
        vec![q(0, 1), q(1, 2), q(3, 1)],
        vec![q(1, 1), q(-1, 3), q(0, 1)],
    )
    .unwrap();
    let t = q(1, 5);
    let b = l.blocks_at(&t).unwrap();
    let mut got = Vec::new();
    b.positions(|v| {
        got.push(value(v));
        Ok(())
    })
    .unwrap();
    assert_eq!(
        got,
        state_at(&IntegerData::new(&general), &t).unwrap().positions
    );
    assert!(l.blocks_at(&q(-1, 5)).is_none());
    // r = 1/4: 0 and 1/3 overlap.
    assert!(Lean::new(Some(q(1, 4)), 0, xs.clone(), us.clone()).is_none());
    // A contact (0, 1/2 at r = 1/4) with crossing velocities.
    assert!(Lean::new(Some(q(1, 4)), 0, vec![(0, 1), (1, 2)], vec![(1, 1), (0, 1)]).is_none());
    assert!(Lean::new(Some(q(1, 4)), 0, vec![(0, 1), (1, 2)], vec![(0, 1), (1, 1)]).is_some());
    assert!(Lean::new(Some(q(1, 4)), 0, vec![(0, 1), (1, 2)], vec![(0, 1), (0, 1)]).is_some());
    assert!(Lean::new(None, 0, xs.clone(), us[..2].to_vec()).is_none());
    assert!(Lean::new(None, 0, Vec::new(), Vec::new()).is_none());
    assert!(Lean::new(Some(q(0, 1)), 0, xs.clone(), us.clone()).is_none());
    // The number budget: charged bits push the total over it.
    assert!(Lean::new(None, MAX_NUMBER_BITS - 10, xs.clone(), us.clone()).is_none());
    // The six numbers cost their bits (numerators 0, 1, 2, 1, 1, 0;
    // denominators 1, 2, 1, 1, 2, 1) and 64 each: 5 + 8 + 384.
    let cost = 397;
    assert!(Lean::new(None, MAX_NUMBER_BITS - cost, xs.clone(), us.clone()).is_some());
    assert!(Lean::new(None, MAX_NUMBER_BITS - cost + 1, xs, us).is_none());
}

/// `Exact`: lowest terms, the contract's rendering (`p/q`, `p` when
/// `q = 1`) and the nearest double.
#[test]
fn exact_values_render_and_round() {
    assert_eq!(Exact::ratio(0, 7), Exact::Small(0, 1));
    assert_eq!(Exact::ratio(6, 4), Exact::Small(3, 2));
    assert_eq!(Exact::ratio(-6, 3), Exact::Small(-2, 1));
    assert_eq!(Exact::ratio(5, 3), Exact::Small(5, 3));
    let text = |v: &Exact| {
        let mut out = Vec::new();
        v.write(&mut out).unwrap();
        String::from_utf8(out).unwrap()
    };
    assert_eq!(text(&Exact::ratio(-6, 4)), "-3/2");
    assert_eq!(text(&Exact::ratio(8, 4)), "2");
    let big = BigRational::new(BigInt::from(1) << 130, BigInt::from(3));
    assert_eq!(text(&Exact::Big(big.clone())), big.to_string());
    assert_eq!(Exact::ratio(1, 3).to_f64_lossy(), 1.0 / 3.0);
    assert_eq!(Exact::ratio(-7, 2).to_f64_lossy(), -3.5);
    // Beyond 2^53 the division of doubles would round twice.
    let (n, d) = ((1i128 << 60) + 1, 3i128);
    let want = crate::scalar::Scalar::to_f64_lossy(&q(n as i64, d as i64));
    assert_eq!(Exact::Small(n, d).to_f64_lossy(), want);
    assert_eq!(Exact::Small(1 << 53, 1).to_f64_lossy(), 2f64.powi(53));
    // A numerator beyond 2^53 whose rounding before the division moves
    // the quotient to another double: 579832826712306748/510 =
    // 1136927111200601.466…, whose nearest double is …601.5; rounding
    // the numerator first gives …601.25.
    let (n, d) = (579_832_826_712_306_748i128, 510i128);
    assert_eq!(Exact::Small(n, d).to_f64_lossy(), 1_136_927_111_200_601.5);
    // The same with the denominator beyond 2^53.
    let (n, d) = (41_260_899_282i128, 996_700_932_334_889_006i128);
    let want = crate::scalar::Scalar::to_f64_lossy(&BigRational::new(n.into(), d.into()));
    assert_ne!(want, n as f64 / d as f64);
    assert_eq!(Exact::Small(n, d).to_f64_lossy(), want);
    assert_eq!(Exact::Big(big.clone()).to_f64_lossy(), 2f64.powi(130) / 3.0);
}

/// `Lean::load` reads a `[particles]` scene whose columns are in a CSV
/// or an NPY file into the same scaled columns as the values given
/// directly; a directory, a missing file and a scene that is not a
/// column scene are declined.
#[test]
fn load_reads_csv_and_npy_scenes() {
    let dir = std::env::temp_dir().join(format!("sticky-lean-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let scene = |name: &str, data: &str| {
        let path = dir.join(format!("{name}.toml"));
        let text = format!("[particles]\nradius = \"1/8\"\ndata = \"{data}\"\n");
        std::fs::write(&path, text).unwrap();
        path
    };
    std::fs::write(
        dir.join("a.csv"),
        format!("{}\n0,1\n1/2,-1/4\n3,0\n", crate::columns::CSV_HEADER),
    )
    .unwrap();
    let rows = [(0.0, 1.0), (0.5, -0.25), (3.0, 0.0)];
    std::fs::write(dir.join("a.npy"), crate::columns::write_npy(&rows)).unwrap();
    let want = Lean::new(
        Some(q(1, 8)),
        0,
        vec![(0, 1), (1, 2), (3, 1)],
        vec![(1, 1), (-1, 4), (0, 1)],
    )
    .unwrap();
    for data in ["a.csv", "a.npy"] {
        let l =
            Lean::load(&scene(&data.replace('.', "-"), data)).unwrap_or_else(|| panic!("{data}"));
        assert_eq!(
            (&l.x, &l.u, l.dx, l.du, &l.radius, l.two_r),
            (&want.x, &want.u, want.dx, want.du, &want.radius, want.two_r),
            "{data}"
        );
    }
    assert!(Lean::load(&dir).is_none());
    assert!(Lean::load(&dir.join("missing.toml")).is_none());
    std::fs::write(dir.join("a.txt"), "0,1\n").unwrap();
    assert!(Lean::load(&scene("txt", "a.txt")).is_none());
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The event history of `l` (time, first, size, part sizes).
fn lean_events(l: &Lean) -> Vec<(BigRational, usize, usize, Vec<u32>)> {
    let mut events = Vec::new();
    l.history()
        .expect("within the merge's bound")
        .for_each_event(|t, first, size, parts| {
            events.push((value(t), first, size, parts.to_vec()));
            Ok(())
        })
        .unwrap();
    events
}

/// The same, from the generic event merge on `data`.
fn generic_events(data: InitialData<BigRational>) -> Vec<(BigRational, usize, usize, Vec<u32>)> {
    Trajectory::new(data)
        .impulses()
        .iter()
        .map(|i| {
            let parts = i.parts.iter().map(|c| c.size as u32).collect();
            (i.t.clone(), i.cluster.first, i.cluster.size, parts)
        })
        .collect()
}

/// Word columns near the top of `i64`: cluster sums beyond `i64` (the
/// merge must take `i128` sums when `N·max|X| ≥ 2^63`, the boundary
/// included) and event times whose `gap·D_u` leaves `i128` (reduced on
/// `BigInt`): the history is still the generic one.
#[test]
fn large_word_histories_are_the_generic() {
    let big = |v: i128| BigRational::from_integer(BigInt::from(v));
    // N·M = 2 · 2^62 = 2^63: two particles in contact, one cluster.
    let xs = vec![(1i64 << 62, 1u64), ((1 << 62) + 1, 1)];
    let l = Lean::new(Some(q(1, 2)), 0, xs, vec![(0, 1), (0, 1)]).unwrap();
    assert!(lean_events(&l).is_empty());
    assert_eq!(l.x, [1 << 62, 1 << 62]);
    // Eight particles 2^58 apart, at 1/3 past the integers (D_x = 3),
    // velocities (100 s₁ + 10 s₂ + s₃)/2^62 (D_u = 2^62; s₁, s₂, s₃ = ±1
    // alternating by particle, by pair, by half): pairs meet, then pairs
    // of pairs, then the halves, whose `gap = k_L k_R (X̄_R − X̄_L) =
    // 16 · 3 · 2^60` gives `gap·D_u > 2^127`.
    // And N·M > 2^63: sums in `i128`.
    let n = 8;
    let positions: Vec<_> = (0..n).map(|i| big(i * (1 << 58)) + q(1, 3)).collect();
    let sign = |b: bool| if b { 1 } else { -1 };
    let velocities: Vec<_> = (0..n)
        .map(|i| {
            let v = 100 * sign(i % 2 == 0) + 10 * sign(i / 2 % 2 == 0) + sign(i < 4);
            BigRational::new(BigInt::from(v), BigInt::from(1u64 << 62))
        })
        .collect();
    let data = InitialData::new(q(1, 2), positions, velocities).unwrap();
    let l = lean(&data, true).unwrap();
    assert_eq!((l.dx, l.du), (3, 1 << 62));
    let m =
        l.x.iter()
            .chain(&l.u)
            .map(|v| v.unsigned_abs())
            .max()
            .unwrap();
    assert!(u128::from(m) * n as u128 > 1 << 63);
    let events = lean_events(&l);
    assert_eq!(events.len(), 7, "{events:?}");
    assert_eq!(events[6].1..events[6].2, 0..8);
    assert_eq!(events, generic_events(data));
}

/// `blocks_at` answers exactly where the kernel's `i128` bound
/// `b_Y + b_K < 128` holds (`b_Y = max(bits a + bits max|X|,
/// bits b + bits max|U|) + 1`), and then with the kernel's state.
#[test]
fn blocks_at_answers_within_the_i128_bound() {
    let big = |v: i128| BigRational::from_integer(BigInt::from(v));
    // X = (0, 2^61 − 1, 2^62 − 2): 62 bits; U = (1, 0, −1); b_K = 2.
    let data = InitialData::new(
        q(1, 2),
        vec![big(0), big(1 << 61), big(1 << 62)],
        vec![q(1, 1), q(0, 1), q(-1, 1)],
    )
    .unwrap();
    let l = lean(&data, true).unwrap();
    let d = IntegerData::new(&data);
    let at = |e: u32| BigRational::new(BigInt::from(1), BigInt::from(1i128 << e));
    // t = 1/2^61: a = 2^61, b_Y = 62 + 62 + 1 = 125, 125 + 2 < 128.
    let b = l.blocks_at(&at(61)).expect("within the bound");
    let mut xs = Vec::new();
    b.positions(|v| {
        xs.push(value(v));
        Ok(())
    })
    .unwrap();
    assert_eq!(xs, state_at(&d, &at(61)).unwrap().positions);
    // t = 1/2^62: a = 2^62 (63 bits), 126 + 2 = 128: declined.
    assert!(l.blocks_at(&at(62)).is_none());
}

/// Denominators whose product leaves `i128` while every scaled value
/// fits `i64` (`D_x = p₁ p₂ ≈ 2^100`, `D_u = 2^30`, so `D_y = q D_x D_u`
/// is beyond `i128`): the block means and positions are reduced on
/// `BigInt`, and are still the kernel's.
#[test]
fn lean_values_beyond_i128_denominators() {
    let (p1, p2) = (1_125_899_906_842_597i64, 1_125_899_906_842_589i64);
    // 2r = 1/3; x̃ = (0, 1/p₁, 1/p₂, 1/p₂): particles 2 and 3 in contact
    // with one velocity (one block of two at t = 0).
    let xs = vec![
        (0, 1),
        (p1 + 3, 3 * p1 as u64),
        (2 * p2 + 3, 3 * p2 as u64),
        (p2 + 1, p2 as u64),
    ];
    let us = vec![(3, 1 << 30), (-5, 1 << 30), (-1, 1 << 30), (-1, 1 << 30)];
    let l = Lean::new(Some(q(1, 6)), 0, xs.clone(), us.clone()).unwrap();
    assert!(l.dx > 1 << 99);
    assert!(l.blocks_at(&q(1, 3)).is_none());
    let rat = |&(p, d): &(i64, u64)| BigRational::new(p.into(), d.into());
    let data = InitialData::new(
        q(1, 6),
        xs.iter().map(rat).collect(),
        us.iter().map(rat).collect(),
    )
    .unwrap();
    let d = IntegerData::new(&data);
    // `b = p D_x` must fit a word: t = 0 (then `D_y = D_x D_u`).
    let t = q(0, 1);
    let want = state_at(&d, &t).unwrap();
    let b = l.blocks_at(&t).expect("within the i128 bound");
    let mut rows = 0;
    b.rows(|i, x, u, lambda| {
        assert_eq!(value(x), want.positions[i], "t = {t}, i = {i}");
        assert_eq!(value(u), want.velocities[i], "t = {t}, i = {i}");
        assert_eq!(lambda.map(value), want.multipliers.get(i).cloned());
        rows += 1;
        Ok(())
    })
    .unwrap();
    assert_eq!(rows, 4);
    assert_eq!(b.clusters(), want.clusters);
    assert_eq!(b.runs.iter().map(|r| r.k).collect::<Vec<_>>(), [1, 1, 2]);
}

/// `Lean::from_doubles` reads each double as its exact binary value: the
/// same scene as `Lean::from_data` on those values (same state at several
/// times), and `None` for a NaN, an infinity, an overlap and a length
/// mismatch, which the general path then names.
#[test]
fn doubles_are_read_exactly() {
    let xs = [0.0, 0.3, 0.7, 1.0e-3 + 2.0];
    let us = [1.0, 0.5, -0.25, -1.0 / 3.0];
    let exact = |v: &[f64]| {
        v.iter()
            .map(|&d| crate::columns::f64_exact(d).unwrap())
            .collect::<Vec<_>>()
    };
    let r = q(1, 8);
    let data = InitialData::new(r.clone(), exact(&xs), exact(&us)).unwrap();
    let a = Lean::from_doubles(Some(r.clone()), &xs, &us).expect("doubles on words");
    let b = Lean::from_data(&data).expect("the same data on words");
    let d = IntegerData::new(&data);
    for t in [q(0, 1), q(1, 3), q(1, 1), q(5, 1)] {
        let want = state_at(&d, &t).unwrap();
        for l in [&a, &b] {
            let blocks = l.blocks_at(&t).unwrap();
            let mut got = Vec::new();
            blocks
                .positions(|e| {
                    got.push(value(e));
                    Ok(())
                })
                .unwrap();
            assert_eq!(got, want.positions, "t = {t}");
            assert_eq!(blocks.clusters(), want.clusters, "t = {t}");
        }
    }
    assert!(Lean::from_doubles(Some(r.clone()), &[0.0, f64::NAN], &[0.0, 0.0]).is_none());
    assert!(Lean::from_doubles(Some(r.clone()), &[0.0, f64::INFINITY], &[0.0, 0.0]).is_none());
    assert!(Lean::from_doubles(Some(r.clone()), &[0.0, 0.2], &[0.0, 0.0]).is_none());
    assert!(Lean::from_doubles(Some(r), &[0.0, 1.0], &[0.0]).is_none());
}

/// `nearest_ratio` is the nearest double, ties to even, against the
/// integer-only `rational::nearest_f64` (the one nearest-double routine):
/// small and 128-bit terms, exact ties, signs.
#[test]
fn nearest_ratio_rounds_to_nearest_even() {
    use crate::rational::nearest_f64;
    let mut rng = SplitMix64::new(7);
    let mut cases: Vec<(i128, i128)> = vec![
        (1, 3),
        (-1, 3),
        (2, 3),
        ((1 << 53) + 1, 1), // a tie: to even, 2^53
        ((1 << 53) + 3, 1), // a tie: to even, 2^53 + 4
        (((1 << 53) + 1) << 20, 1 << 20),
        ((1 << 100) + 1, 1 << 47),
        (i128::MAX, 3),
        (-i128::MAX, i128::MAX - 1),
        (1, i128::MAX),
    ];
    for _ in 0..20_000 {
        let width = 1 + rng.next_u64() % 126;
        let mask = (1u128 << width) - 1;
        let word = |rng: &mut SplitMix64| {
            ((u128::from(rng.next_u64()) << 64) | u128::from(rng.next_u64())) & mask
        };
        let num = word(&mut rng) as i128 * if rng.next_u64() % 2 == 0 { 1 } else { -1 };
        let den = (word(&mut rng) >> (rng.next_u64() % 100)).max(1) as i128;
        cases.push((num, den));
    }
    let mut answered = 0;
    for (num, den) in cases {
        if let Some(v) = nearest_ratio(num, den) {
            let want = nearest_f64(&BigRational::new(num.into(), den.into())).unwrap();
            assert_eq!(v.to_bits(), want.to_bits(), "{num}/{den}");
            answered += 1;
        }
    }
    assert!(answered > 15_000, "{answered}");
}

/// `LeanBlocks::nearest` gives the nearest doubles of the exact state, the
/// same bits as rounding each exact value of the visitors.
#[test]
fn nearest_is_the_rounded_exact_state() {
    let mut rng = SplitMix64::new(77);
    for k in 0..120 {
        let data = initial_data(
            &rng.bytes(200),
            Limits {
                max_n: 1 + k % 25,
                max_den: 1 + (k % 6) as u32,
                max_speed: 1 + (k % 7) as u32,
            },
        );
        let l = lean(&data, true).expect("small data on words");
        let history = Trajectory::new(data.clone());
        for t in probe_times(&history, Some(6)) {
            let b = l.blocks_at(&t).unwrap();
            let exact = state_at(&IntegerData::new(&data), &t).unwrap();
            let round = |v: &[BigRational]| -> Vec<u64> {
                v.iter()
                    .map(|q| crate::rational::nearest_f64(q).unwrap().to_bits())
                    .collect()
            };
            let got = b.nearest();
            let bits = |v: &[f64]| -> Vec<u64> { v.iter().map(|d| d.to_bits()).collect() };
            assert_eq!(bits(&got.positions), round(&exact.positions), "t = {t}");
            assert_eq!(bits(&got.velocities), round(&exact.velocities), "t = {t}");
            assert_eq!(bits(&got.multipliers), round(&exact.multipliers), "t = {t}");
        }
    }
}

/// The `(N, 3)` rows `run --format npy` writes, from the kernel's exact
/// state: `x_i, u_i, λ_{i+1}` (0 for the last particle), each the nearest
/// double, little-endian.
fn npy_rows_of(exact: &crate::state::State<BigRational>) -> Vec<u8> {
    let near = |q: &BigRational| crate::rational::nearest_f64(q).unwrap();
    let mut out = Vec::new();
    for (i, (x, u)) in exact.positions.iter().zip(&exact.velocities).enumerate() {
        let l = exact.multipliers.get(i).map_or(0.0, near);
        for v in [near(x), near(u), l] {
            out.extend_from_slice(&v.to_le_bytes());
        }
    }
    out
}

/// The rows of `b` in pieces of `particles`, formatted apart and joined.
fn rows_in_pieces(b: &LeanBlocks<'_>, particles: usize) -> Vec<u8> {
    let mut out = Vec::new();
    for piece in b.pieces(particles) {
        b.push_nearest_rows(&piece, &mut out);
    }
    out
}

/// `LeanBlocks::push_nearest_rows` on pieces of any size, put back in
/// order, gives the bytes of the rows of the exact state rounded value by
/// value, on words and (a scene whose unreduced fractions leave `i128`)
/// on the reduced path.
#[test]
fn nearest_rows_in_pieces_are_the_exact_rows() {
    let mut rng = SplitMix64::new(78);
    for k in 0..80 {
        let data = initial_data(
            &rng.bytes(200),
            Limits {
                max_n: 1 + k % 25,
                max_den: 1 + (k % 6) as u32,
                max_speed: 1 + (k % 7) as u32,
            },
        );
        let l = lean(&data, true).expect("small data on words");
        let history = Trajectory::new(data.clone());
        for t in probe_times(&history, Some(4)) {
            let b = l.blocks_at(&t).unwrap();
            let want = npy_rows_of(&state_at(&IntegerData::new(&data), &t).unwrap());
            assert_eq!(want.len(), 24 * data.n());
            for particles in [1, 2, 5, data.n()] {
                assert_eq!(rows_in_pieces(&b, particles), want, "scene {k}, t = {t}");
            }
        }
    }
    // D_y beyond i128: every piece on the reduced path.
    let (p1, p2) = (1_125_899_906_842_597i64, 1_125_899_906_842_589i64);
    let xs = vec![
        (0, 1),
        (p1 + 3, 3 * p1 as u64),
        (2 * p2 + 3, 3 * p2 as u64),
        (p2 + 1, p2 as u64),
    ];
    let us = vec![(3, 1 << 30), (-5, 1 << 30), (-1, 1 << 30), (-1, 1 << 30)];
    let l = Lean::new(Some(q(1, 6)), 0, xs.clone(), us.clone()).unwrap();
    let rat = |&(p, d): &(i64, u64)| BigRational::new(p.into(), d.into());
    let data = InitialData::new(
        q(1, 6),
        xs.iter().map(rat).collect(),
        us.iter().map(rat).collect(),
    )
    .unwrap();
    let t = q(0, 1);
    let b = l.blocks_at(&t).unwrap();
    assert!(b.dy.is_none(), "the unreduced fractions leave i128");
    let want = npy_rows_of(&state_at(&IntegerData::new(&data), &t).unwrap());
    for particles in [1, 2, 4] {
        assert_eq!(rows_in_pieces(&b, particles), want);
    }
}

/// A file of `bytes` in a fresh temporary folder.
fn temp_file(tag: &str, name: &str, bytes: &[u8]) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("sticky-lean-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(name);
    std::fs::write(&path, bytes).unwrap();
    path
}

/// The columns of a [`Lean`], for comparing two of them.
fn fields(l: &Lean) -> (Vec<i64>, Vec<i64>, i128, i128, u64, u64, BigRational) {
    let (x, u) = (l.x.clone(), l.u.clone());
    (x, u, l.dx, l.du, l.x_bits, l.u_bits, l.radius.clone())
}

/// A column file read in segments on every core (NPY in C and Fortran
/// order, CSV with blank lines and `\r\n`), at segment sizes that cut the
/// file at many places, gives the scene [`Lean::new`] gives on the whole file's
/// values.
#[test]
fn chunked_files_read_as_whole_files() {
    let mut rng = SplitMix64::new(7);
    let mut npy_cases = 0;
    for k in 0..40 {
        // Denominators 1 and 2: every value is a double.
        let data = initial_data(
            &rng.bytes(300),
            Limits {
                max_n: 2 + k % 30,
                max_den: 1 + (k % 2) as u32,
                max_speed: 1 + (k % 7) as u32,
            },
        );
        let n = data.n();
        let doubles = |v: &[BigRational]| -> Vec<f64> {
            v.iter().map(crate::scalar::Scalar::to_f64_lossy).collect()
        };
        let (xs, us) = (doubles(data.positions()), doubles(data.velocities()));
        let rows: Vec<(f64, f64)> = xs.iter().copied().zip(us.iter().copied()).collect();
        let c_order = crate::columns::write_npy(&rows);
        let mut fortran = crate::columns::npy_header(&[n, 2]);
        let at = fortran.windows(5).position(|w| w == b"False").unwrap();
        fortran[at..at + 5].copy_from_slice(b"True ");
        for v in xs.iter().chain(&us) {
            fortran.extend_from_slice(&v.to_le_bytes());
        }
        let mut csv = String::from("\n position , velocity\r\n");
        for (i, (x, u)) in data.positions().iter().zip(data.velocities()).enumerate() {
            csv.push_str(&format!("{x}, {u}\n"));
            if i % 3 == 1 {
                csv.push_str("  \r\n");
            }
        }
        let radius = data.radius().clone();
        let whole_npy = crate::columns::read_npy_small(&c_order).unwrap();
        let whole_csv = crate::columns::read_csv_small(csv.as_bytes()).unwrap();
        let cases = [
            ("c.npy", c_order.clone(), whole_npy.clone()),
            ("f.npy", fortran, whole_npy),
            ("rows.csv", csv.into_bytes(), whole_csv),
        ];
        let all_doubles = data
            .positions()
            .iter()
            .chain(data.velocities())
            .all(crate::columns::is_f64);
        for (name, bytes, (wx, wu)) in cases {
            if name.ends_with("npy") && !all_doubles {
                continue;
            }
            npy_cases += usize::from(name.ends_with("npy"));
            let want = Lean::new(Some(radius.clone()), 0, wx, wu).map(|l| fields(&l));
            assert!(want.is_some(), "case {k} {name}");
            let path = temp_file("chunks", name, &bytes);
            for chunk in [16, 48, 4096] {
                let file = ColumnFile::open(&path).unwrap().with_chunk(chunk);
                let got = Lean::from_file(Some(radius.clone()), &file).map(|l| fields(&l));
                assert_eq!(got, want, "case {k}, {name}, chunk {chunk}");
            }
        }
    }
    assert!(npy_cases >= 20, "{npy_cases} NPY cases");
}

/// The scaling of values one at a time is [`scale_pairs`]'s, also when the
/// common divisor `g` shrinks midway (the values stored before are then
/// multiplied up) and when a value does not fit `i64`.
#[test]
fn the_column_scaler_is_scale_pairs() {
    let mut rng = SplitMix64::new(11);
    for k in 0..300 {
        let n = 1 + (rng.next_u64() % 12) as usize;
        let big = k % 10 == 0;
        let pair = |rng: &mut SplitMix64| -> Small {
            let d = [1u64, 2, 4, 8, 3, 12, 1 << 40][(rng.next_u64() % 7) as usize];
            let p = (rng.next_u64() % 64) as i64 - 32;
            if big {
                (p << 40, d)
            } else {
                (p, d)
            }
        };
        let xs: Vec<Small> = (0..n).map(|_| pair(&mut rng)).collect();
        let us: Vec<Small> = (0..n).map(|_| pair(&mut rng)).collect();
        let two_r = (1i128, [1u128, 4, 6][k % 3]);
        let want = scale_pairs(two_r, &xs, &us).and_then(|s| {
            let x = (s.x_range.narrow(&s.x)?, s.dx.to_u128()?);
            let u = (s.u_range.narrow(&s.u)?, s.du.to_u128()?);
            Some((x, u))
        });
        let scaled = |col: &[Small], two_r: Option<(i128, u128)>| {
            let mut lcm = scale::Lcm::new();
            for &(_, d) in col {
                lcm.add(d)?;
            }
            let mut s = lcm.scaler(two_r, col.len())?;
            for &(p, d) in col {
                s.push(p, d)?;
            }
            let c = s.finish()?;
            Some((c.values, c.den))
        };
        let got = scaled(&xs, Some(two_r)).zip(scaled(&us, None));
        assert_eq!(got, want, "case {k}: {xs:?} {us:?}");
        // The same column read in stretches, each from its first row on:
        // lcms merged, stretches joined in order.
        let cuts: Vec<usize> = {
            let mut c: Vec<usize> = (0..rng.next_u64() % 4)
                .map(|_| (rng.next_u64() % (n as u64 + 1)) as usize)
                .chain([0, n])
                .collect();
            c.sort_unstable();
            c
        };
        let in_stretches = |col: &[Small], two_r: Option<(i128, u128)>| {
            let mut lcm = scale::Lcm::new();
            for w in cuts.windows(2) {
                let mut part = scale::Lcm::new();
                for &(_, d) in &col[w[0]..w[1]] {
                    part.add(d)?;
                }
                lcm.merge(&part)?;
            }
            let scale = lcm.scale(two_r)?;
            let mut whole = scale.joined(n);
            for w in cuts.windows(2) {
                let mut s = scale.part(w[0], w[1] - w[0])?;
                for &(p, d) in &col[w[0]..w[1]] {
                    s.push(p, d)?;
                }
                whole.take(s);
            }
            let c = whole.finish()?;
            Some((c.values, c.den))
        };
        let got = in_stretches(&xs, Some(two_r)).zip(in_stretches(&us, None));
        assert_eq!(got, want, "case {k} in stretches {cuts:?}: {xs:?} {us:?}");
    }
}
