//! The dyadic path against the generic projection (`BigRational`, the
//! oracle): the exact states field by field, and every double the nearest
//! double of the exact value, bit for bit.

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::ToPrimitive;

use super::*;
use crate::generate::SplitMix64;
use crate::initial::InitialData;
use crate::projection;

fn q(n: i64, d: i64) -> BigRational {
    BigRational::new(BigInt::from(n), BigInt::from(d))
}

fn exact_f64(v: f64) -> BigRational {
    BigRational::from_float(v).unwrap()
}

fn nearest_of(v: &[BigRational]) -> Vec<u64> {
    v.iter()
        .map(|x| x.to_f64().unwrap_or(f64::NAN).to_bits())
        .collect()
}

fn bits_of(v: &[f64]) -> Vec<u64> {
    v.iter().map(|x| x.to_bits()).collect()
}

/// What [`check`] found.
#[derive(Debug, PartialEq)]
enum Outcome {
    /// The data are not valid (both paths refuse them).
    Invalid,
    /// Valid data the dyadic path declined (a width beyond `i128`).
    Declined,
    /// Both paths gave the same answer.
    Agreed,
}

/// Every value of `s` in lowest terms with a positive denominator (`==`
/// on `BigRational` compares values, not fields).
fn lowest_terms(s: &crate::state::State<BigRational>) {
    let columns = [&s.positions, &s.velocities, &s.multipliers];
    for q in columns.into_iter().flatten() {
        let reduced = BigRational::new(q.numer().clone(), q.denom().clone());
        assert_eq!(
            (q.numer(), q.denom()),
            (reduced.numer(), reduced.denom()),
            "{q} in lowest terms"
        );
    }
}

/// [`check`] is [`Outcome::Agreed`].
fn agree(radius: Option<BigRational>, xs: &[f64], us: &[f64], t: &BigRational) -> bool {
    check(radius, xs, us, t) == Outcome::Agreed
}

/// The scene through both paths at `t`: the exact states equal, the
/// doubles the exact values' nearest doubles (panics otherwise).
fn check(radius: Option<BigRational>, xs: &[f64], us: &[f64], t: &BigRational) -> Outcome {
    let x: Vec<BigRational> = xs.iter().map(|&v| exact_f64(v)).collect();
    let u: Vec<BigRational> = us.iter().map(|&v| exact_f64(v)).collect();
    let data = match radius.clone() {
        Some(r) => InitialData::new(r, x, u),
        None => InitialData::with_paper_radius(x, u),
    };
    let lean = Dyadic::from_doubles(radius, xs, us);
    let data = match data {
        Ok(d) => d,
        Err(e) => {
            assert!(lean.is_none(), "invalid data accepted: {e}");
            return Outcome::Invalid;
        }
    };
    let Some(lean) = lean else {
        return Outcome::Declined;
    };
    let Some(blocks) = lean.blocks_at(t) else {
        return Outcome::Declined;
    };
    let want = projection::state_at(&data, t).unwrap();
    let got = blocks.exact_state();
    assert_eq!(got, want, "exact state at t = {t}, x {xs:?}, u {us:?}");
    lowest_terms(&got);
    let near = blocks.nearest().expect("on words");
    // Two threads from two particles on: the same blocks, the same doubles.
    let halves = lean.blocks_with(t, 2).expect("the same bound");
    assert_eq!(halves.sums, blocks.sums, "two-thread PAVA at t = {t}");
    let near2 = halves.nearest().expect("on words");
    assert_eq!(bits_of(&near2.positions), bits_of(&near.positions));
    assert_eq!(bits_of(&near2.velocities), bits_of(&near.velocities));
    assert_eq!(bits_of(&near2.multipliers), bits_of(&near.multipliers));
    // The `i128` columns: the same blocks, the same doubles, the same
    // exact state.
    let wide = lean.widened();
    assert!(!wide.is_narrow());
    let wide = wide.blocks_at(t).expect("the same bound");
    assert_eq!(wide.sums, blocks.sums, "i128 columns at t = {t}");
    assert_eq!(wide.exact_state(), got, "i128 columns at t = {t}");
    let near3 = wide.nearest().expect("on words");
    assert_eq!(bits_of(&near3.positions), bits_of(&near.positions));
    assert_eq!(bits_of(&near3.velocities), bits_of(&near.velocities));
    assert_eq!(bits_of(&near3.multipliers), bits_of(&near.multipliers));
    assert_eq!(
        bits_of(&near.positions),
        nearest_of(&want.positions),
        "x at {t}"
    );
    assert_eq!(
        bits_of(&near.velocities),
        nearest_of(&want.velocities),
        "u at {t}"
    );
    assert_eq!(
        bits_of(&near.multipliers),
        nearest_of(&want.multipliers),
        "λ at {t}"
    );
    Outcome::Agreed
}

/// A random double of `scale`'s order, `bits` significant bits, sign
/// random; sometimes zero.
fn random_double(rng: &mut SplitMix64, exp: i32, bits: u32) -> f64 {
    if rng.next_u64() % 8 == 0 {
        return 0.0;
    }
    let m = (rng.next_u64() >> (64 - bits.clamp(1, 53))) as f64;
    let v = m * 2f64.powi(exp - bits as i32);
    if rng.next_u64() % 2 == 0 {
        v
    } else {
        -v
    }
}

/// A random scene: gaps `2r` (contacts), `2r` plus a random double, or
/// random; velocities random doubles of mixed exponents.
fn random_scene(rng: &mut SplitMix64, n: usize, two_r: f64, exp: i32) -> (Vec<f64>, Vec<f64>) {
    let mut xs = Vec::with_capacity(n);
    let mut us = Vec::with_capacity(n);
    let mut x = random_double(rng, exp, 53);
    for _ in 0..n {
        xs.push(x);
        let bits = 1 + (rng.next_u64() % 53) as u32;
        let e = exp - (rng.next_u64() % 40) as i32;
        us.push(random_double(rng, e, bits));
        let gap = match rng.next_u64() % 3 {
            0 => two_r,
            1 => two_r + random_double(rng, exp, bits).abs(),
            _ => two_r * 3.0 + random_double(rng, exp + 2, 53).abs(),
        };
        x += gap;
    }
    (xs, us)
}

#[test]
fn random_scenes_of_doubles_agree_with_the_generic_projection() {
    let mut rng = SplitMix64::new(27);
    let (mut answered, mut valid, mut cases) = (0, 0, 0);
    for case in 0..600 {
        let n = 1 + (rng.next_u64() % 12) as usize;
        let (radius, two_r) = match case % 4 {
            // Dyadic radii, tiny to large.
            0 => (Some(q(1, 8)), 0.25),
            1 => {
                let e = (rng.next_u64() % 60) as i32 - 50;
                let r = 2f64.powi(e);
                (Some(exact_f64(r)), 2.0 * r)
            }
            // Radii with an odd denominator, and the paper's 1/(2N).
            2 => (Some(q(1, 10)), 0.2),
            _ => (None, 1.0 / n as f64),
        };
        let exp = (rng.next_u64() % 80) as i32 - 40;
        let (xs, us) = random_scene(&mut rng, n, two_r, exp);
        let times = [
            q(0, 1),
            exact_f64(random_double(&mut rng, 0, 53).abs()),
            exact_f64(random_double(&mut rng, 10, 20).abs()),
            q(1, 3),
            q(7, 12),
            q(1_000_001, 1),
        ];
        for t in &times {
            cases += 1;
            match check(radius.clone(), &xs, &us, t) {
                Outcome::Invalid => {}
                Outcome::Declined => valid += 1,
                Outcome::Agreed => {
                    valid += 1;
                    answered += 1;
                }
            }
        }
    }
    // Most valid cases take the dyadic path (the rest: a width the `i128`
    // bound refuses, at the largest times); invalid data come from the
    // rounding of the gaps in doubles.
    assert!(answered * 10 > valid * 9, "{answered} of {valid}");
    assert!(valid * 4 > cases, "{valid} of {cases}");
}

/// The columns are `i64` up to `|U_i| < 2^63` and `i128` from `2^63` on,
/// with the same answers either side of the boundary.
#[test]
fn columns_narrow_below_2_63_and_fall_back_from_it() {
    let xs = [0.0, 10.0, 20.0];
    let top = 2f64.powi(63);
    let below = top - 1024.0; // the largest double below 2^63
    for (us, narrow) in [
        ([1.0, below, -below], true),
        ([1.0, top, 0.0], false),
        ([1.0, 0.0, -top], false),
    ] {
        let lean = Dyadic::from_doubles(Some(q(1, 4)), &xs, &us).unwrap();
        assert_eq!(lean.is_narrow(), narrow, "{us:?}");
        for t in [q(0, 1), q(1, 4), q(1, 3), exact_f64(2f64.powi(-40))] {
            assert!(agree(Some(q(1, 4)), &xs, &us, &t), "{us:?} at {t}");
        }
    }
    // A scene on small integers is narrow.
    let lean = Dyadic::from_doubles(None, &xs, &[0.5, -0.25, 3.0]).unwrap();
    assert!(lean.is_narrow());
}

/// The PAVA's sums are `i64` only under the bound on 63 bits: two
/// particles whose pooled `ΣY = 3·2^61` wraps `i64` take the `i128` sums
/// and agree; on both sides of `b_Y + b_K = 63` (N = 2, `b_K = 2`, at
/// `t = 0` `b_Y` is the bits of `X̃` plus 2) the answers agree too.
#[test]
fn sums_are_i64_only_under_the_63_bit_bound() {
    let us = [2f64.powi(62), 2f64.powi(61)];
    let lean = Dyadic::from_doubles(Some(q(1, 2)), &[0.0, 2.0], &us).unwrap();
    assert!(lean.is_narrow());
    for t in [q(1, 1), q(2, 1), q(1, 2)] {
        assert!(agree(Some(q(1, 2)), &[0.0, 2.0], &us, &t), "t = {t}");
    }
    for x_bits in [58, 59, 60, 61] {
        let top = 2f64.powi(x_bits) - 1024.0;
        let xs = [top - 2048.0, top];
        assert!(agree(Some(q(1, 2)), &xs, &[1.0, -1.0], &q(0, 1)));
        assert!(agree(Some(q(1, 2)), &xs, &[1.0, -1.0], &q(4096, 1)));
    }
}

/// Subnormal positions and velocities, mixed with normal ones.
#[test]
fn subnormals_and_mixed_exponents() {
    let tiny = f64::from_bits(1);
    let r = 2f64.powi(-1070);
    let xs = [-3.0 * tiny, 2.0 * r, 4.0 * r + tiny, 6.0 * r + 5.0 * tiny];
    let us = [2f64.powi(-1000), tiny, -tiny, 0.0];
    for t in [q(0, 1), q(1, 1), exact_f64(2f64.powi(-60)), q(1, 3)] {
        assert!(agree(Some(exact_f64(r)), &xs, &us, &t), "t = {t}");
    }
    let xs = [0.0, 1.0, 2.0 + 2f64.powi(-60), 1e6];
    let us = [1e-10, -1e-10, 3.5, -7.25];
    for t in [q(0, 1), q(1, 2), exact_f64(0.75), q(2, 7), q(1 << 20, 1)] {
        assert!(agree(Some(q(1, 4)), &xs, &us, &t), "t = {t}");
    }
}

/// Exact answers on double midpoints round to even: two particles in
/// contact whose common mean is `1 + 2^-53` (between 1 and its successor).
#[test]
fn midpoints_round_to_even() {
    let eps = 2f64.powi(-52);
    let xs = [1.0, 1.5 + eps];
    let us = [1.0, -1.0];
    assert!(agree(Some(q(1, 4)), &xs, &us, &q(1, 1)));
    let lean = Dyadic::from_doubles(Some(q(1, 4)), &xs, &us).unwrap();
    let near = lean.blocks_at(&q(1, 1)).unwrap().nearest().unwrap();
    // x_0 = 1 + 2^-53 and x_1 = 1.5 + 2^-53: both midpoints, to even.
    assert_eq!(near.positions, vec![1.0, 1.5]);
    // One more unit below the midpoint of three: (3 (1 + 2^-53) + 2^-52)/3 is
    // above the midpoint, the sticky bit decides.
    let xs = [1.0, 1.5 + eps, 2.0 + 2.0 * eps];
    let us = [1.0, 0.0, -1.0];
    assert!(agree(Some(q(1, 4)), &xs, &us, &q(2, 1)));
}

/// Invalid data are declined (the general path names the error); so are
/// non-finite values.
#[test]
fn invalid_and_non_finite_data_are_declined() {
    assert!(Dyadic::from_doubles(Some(q(1, 4)), &[0.0, 0.4], &[0.0, 0.0]).is_none());
    assert!(Dyadic::from_doubles(Some(q(1, 4)), &[0.0, 0.5], &[1.0, 0.0]).is_none());
    assert!(Dyadic::from_doubles(Some(q(1, 4)), &[0.0, 0.5], &[0.0, 1.0]).is_some());
    assert!(Dyadic::from_doubles(Some(q(1, 4)), &[0.0, f64::NAN], &[0.0, 0.0]).is_none());
    assert!(Dyadic::from_doubles(Some(q(1, 4)), &[0.0, 1.0], &[f64::INFINITY, 0.0]).is_none());
    assert!(Dyadic::from_doubles(Some(q(-1, 4)), &[0.0, 1.0], &[0.0, 0.0]).is_none());
    assert!(Dyadic::from_doubles(Some(q(1, 4)), &[], &[]).is_none());
    let d = Dyadic::from_doubles(Some(q(1, 4)), &[0.0, 1.0], &[0.0, 0.0]).unwrap();
    assert!(d.blocks_at(&q(-1, 2)).is_none());
}

/// A scene as a notebook makes it: positions the running sums of random
/// gaps above `2r` (53-bit mantissas at every scale), velocities uniform in
/// `[−v, v]`, a double radius.
fn notebook_scene(rng: &mut SplitMix64, n: usize, r: f64, v: f64) -> (Vec<f64>, Vec<f64>) {
    let mut x = 0.0f64;
    let mut xs = Vec::with_capacity(n);
    let mut us = Vec::with_capacity(n);
    for _ in 0..n {
        // −ln(1 − v): an exponential gap of mean 1/n beyond 2r (the rounding
        // of the sum keeps the gaps above 2r by a margin).
        let gap = -(1.0 - rng.unit()).ln() / n as f64;
        x += 2.0 * r + r * 1e-3 + gap;
        xs.push(x);
        us.push((2.0 * rng.unit() - 1.0) * v);
    }
    (xs, us)
}

/// Full-mantissa double times (0.01 and its like) and double radii: the
/// `i128` bound fails, the 256-bit sums answer, and the answer is the
/// generic projection's, field by field, every double the nearest.
#[test]
fn double_times_take_the_wide_sums_and_agree() {
    let mut rng = SplitMix64::new(38);
    let mut wide = 0;
    for case in 0..40 {
        let n = 2 + (rng.next_u64() % 60) as usize;
        let r = if case % 2 == 0 { 4e-7 } else { 0.1 / n as f64 };
        // Velocities in [−2^-30, 2^-30] on half the cases: at small N the
        // bound fails then as it does at N = 10^6 with velocities in [−1, 1].
        let v = if case % 4 < 2 { 1.0 } else { 2f64.powi(-30) };
        let (xs, us) = notebook_scene(&mut rng, n, r, v);
        let radius = Some(exact_f64(r));
        let lean = Dyadic::from_doubles(radius.clone(), &xs, &us).expect("valid doubles");
        for t in [
            0.01,
            0.3,
            1e-3,
            2f64.powi(-7),
            0.0,
            -0.0,
            123.456,
            1e6,
            7e-9,
        ] {
            let t = exact_f64(t);
            assert_eq!(
                check(radius.clone(), &xs, &us, &t),
                Outcome::Agreed,
                "case {case} at t = {t}"
            );
            if lean.blocks_at(&t).map(|b| b.width()) == Some(Width::I256) {
                wide += 1;
            }
        }
    }
    // t = 0.01, 0.3, 1e-3, 123.456 and 7e-9 have full mantissas: beyond
    // the `i128` bound with the small velocities.
    assert!(wide >= 20 * 5, "{wide}");
}

/// Time and radius whose numerators carry powers of two beyond 64 bits
/// (`t = 2^70`, `2r = 3·2^66`) and tiny ones: the same answers.
#[test]
fn times_and_radii_with_large_powers_of_two() {
    let r = 3.0 * 2f64.powi(65);
    let xs = [0.0, 4.0 * r, 9.0 * r, 12.0 * r + 2f64.powi(60)];
    let us = [1.0, -0.75, 2f64.powi(-30), -1.0];
    for t in [
        2f64.powi(70),
        2f64.powi(64) * 3.0,
        1.0,
        2f64.powi(-40),
        0.01,
    ] {
        assert_eq!(
            check(Some(exact_f64(r)), &xs, &us, &exact_f64(t)),
            Outcome::Agreed,
            "t = {t}"
        );
    }
}

mod random_doubles {
    use super::*;
    use proptest::prelude::*;

    /// Any finite double of the chosen exponent range: subnormals, both
    /// zeros, full mantissas.
    fn double(lo: i32, hi: i32) -> impl Strategy<Value = f64> {
        let subnormals = if lo < -1022 { 1 } else { 0 };
        prop_oneof![
            1 => Just(0.0),
            1 => Just(-0.0),
            subnormals => (1u64..1 << 20).prop_map(f64::from_bits),
            6 => (any::<bool>(), 0u64..1 << 52, lo..=hi).prop_map(|(neg, m, e)| {
                let v = f64::from_bits((1023u64 << 52) | m) * 2f64.powi(e);
                if neg { -v } else { v }
            }),
        ]
    }

    /// A scene: positions by gaps `2r + |g|`, velocities and the time any
    /// doubles of the range.
    fn scene(lo: i32, hi: i32) -> impl Strategy<Value = (f64, Vec<f64>, Vec<f64>, f64)> {
        (1usize..8).prop_flat_map(move |n| {
            (
                double(lo, hi),
                double(lo, hi),
                prop::collection::vec(double(lo, hi), n),
                prop::collection::vec(double(lo, hi), n),
                double(lo, hi),
            )
                .prop_map(move |(r, x0, gaps, us, t)| {
                    let r = r.abs().max(2f64.powi(lo));
                    let mut x = x0;
                    let xs = gaps
                        .iter()
                        .map(|g| {
                            let here = x;
                            x = x + 2.0 * r + g.abs();
                            here
                        })
                        .collect();
                    (r, xs, us, t.abs())
                })
        })
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(400))]

        /// Doubles of every scale (subnormals to 2^1000, both zeros): the
        /// dyadic path agrees with the generic projection or declines
        /// (exponents too far apart for 256 bits); never a different answer.
        #[test]
        fn prop_any_doubles_agree_or_decline((r, xs, us, t) in scene(-1074, 1000)) {
            prop_assume!(xs.iter().all(|x| x.is_finite()));
            check(Some(exact_f64(r)), &xs, &us, &exact_f64(t));
        }

        /// Doubles within 2^±40 of each other: always answered, on 128 or
        /// 256 bits, and agreeing.
        #[test]
        fn prop_doubles_of_one_scale_are_answered((r, xs, us, t) in scene(-40, 0)) {
            prop_assert_ne!(
                check(Some(exact_f64(r)), &xs, &us, &exact_f64(t)),
                Outcome::Declined
            );
        }
    }
}

/// Sums on 127 bits whose positions' numerators `S + k C i` are not (a
/// case found by `prop_doubles_of_one_scale_are_answered`): the positions
/// are rounded from 256-bit numerators, and agree with the exact state.
#[test]
fn positions_beyond_the_narrow_sums_are_answered() {
    let xs = [-2.9920242743265063e-6, 0.9884043073309617];
    let us = [-1.0115314377655297e-5, -1.4448883012625];
    let (r, t) = (0.49420362119883054, 0.0030022068866822254);
    let outcome = check(Some(exact_f64(r)), &xs, &us, &exact_f64(t));
    assert_ne!(outcome, Outcome::Declined);
}
