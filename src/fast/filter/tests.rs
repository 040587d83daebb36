//! The filter against the exact engines, bit for bit: random scenes,
//! near-ties a few ulps wide, clusters touching exactly, exponents at and
//! beyond the filter's range, full-mantissa `t` and `r`. Each case checks
//! that a certified answer is the exact one, and the counts check that the
//! filter both answers and refuses where it must.

use num_rational::BigRational;
use num_traits::ToPrimitive;

use super::{Checked, Doubles, Refusal};
use crate::fast::dyadic::Dyadic;
use crate::generate::SplitMix64;
use crate::initial::InitialData;
use crate::state::State;

fn q(v: f64) -> BigRational {
    BigRational::from_float(v).unwrap()
}

/// The exact state by the generic projection on the exact data (no
/// filter, no machine words).
fn oracle(r: &BigRational, xs: &[f64], us: &[f64], t: &BigRational) -> State<BigRational> {
    let data = InitialData::new(
        r.clone(),
        xs.iter().map(|&v| q(v)).collect(),
        us.iter().map(|&v| q(v)).collect(),
    )
    .expect("valid data");
    crate::projection::state_at(&data, t).expect("a state")
}

/// The exact state by the dyadic path (what the Solver answers when the
/// filter refuses).
fn dyadic(r: &BigRational, xs: &[f64], us: &[f64], t: &BigRational) -> State<BigRational> {
    let d = Dyadic::from_doubles(Some(r.clone()), xs, us).expect("the dyadic path");
    d.blocks_at(t).expect("its blocks").exact_state()
}

fn bits(v: &[f64]) -> Vec<u64> {
    v.iter().map(|d| d.to_bits()).collect()
}

fn nearest(v: &[BigRational]) -> Vec<u64> {
    v.iter().map(|x| x.to_f64().unwrap().to_bits()).collect()
}

/// Whether the filter certified the state (on one thread); when it did,
/// every output is the exact state's nearest double and its exact state
/// is the exact one. The same of the two-thread run (the halves joined, or
/// one thread again when a block pools across the junction).
fn agrees(r: &BigRational, xs: &[f64], us: &[f64], t: &BigRational) -> bool {
    let d = Doubles::validate(Some(r.clone()), xs.to_vec(), us.to_vec()).expect("valid");
    let one = d.at(t);
    let two = d.at_with(t, 2);
    if one.is_none() && two.is_none() {
        return false;
    }
    let want = oracle(r, xs, us, t);
    for f in one.iter().chain(&two) {
        assert_eq!(bits(f.positions()), nearest(&want.positions), "positions");
        assert_eq!(
            bits(&f.velocities()),
            nearest(&want.velocities),
            "velocities"
        );
        assert_eq!(
            bits(&f.multipliers()),
            nearest(&want.multipliers),
            "multipliers"
        );
        assert_eq!(f.clusters(), want.clusters, "clusters");
        assert_eq!(f.exact_state(), want, "exact state");
    }
    one.is_some()
}

/// `n` particles: exponential gaps of mean `gap` plus `4r`, velocities
/// uniform in `[−1, 1]` (the notebook's data when `gap = 1`).
fn notebook(rng: &mut SplitMix64, n: usize, gap: f64, r: f64) -> (Vec<f64>, Vec<f64>) {
    let mut x = Vec::with_capacity(n);
    let mut acc = 0.0f64;
    for _ in 0..n {
        acc += -gap * (1.0 - rng.unit()).ln() + 4.0 * r;
        x.push(acc);
    }
    let u = (0..n).map(|_| 2.0 * rng.unit() - 1.0).collect();
    (x, u)
}

#[test]
fn random_scenes_are_certified_and_exact() {
    let mut rng = SplitMix64::new(0x38f1);
    let (mut certified, mut multi) = (0, 0);
    for case in 0..120 {
        let n = 2 + (rng.next_u64() % 300) as usize;
        // Gaps from sparse to crowded, times of a few to tens of gaps'
        // travel: many collisions, blocks of up to tens of particles.
        let gap = [1.0, 0.01, 1e-3, 1e-4][case % 4];
        let r = [4e-7, 2f64.powi(-21), 1.0 / 3.0 * 1e-5][case % 3];
        let t = gap * [3.0, 10.0, 30.0][case % 3] * (1.0 + rng.unit());
        let (x, u) = notebook(&mut rng, n, gap, r.min(gap / 8.0));
        let r = r.min(gap / 8.0);
        let ok = agrees(&q(r), &x, &u, &q(t));
        certified += usize::from(ok);
        if ok {
            let d = Doubles::validate(Some(q(r)), x.clone(), u.clone()).unwrap();
            let f = d.at(&q(t)).unwrap();
            multi += f.clusters().iter().filter(|c| c.size > 1).count();
        }
    }
    assert!(certified >= 100, "{certified} of 120 certified");
    assert!(multi >= 500, "{multi} blocks of several particles");
}

/// A block past [`super::pava::MAX_BLOCK`] particles: the filter gives up,
/// the dyadic path answers, the same state.
#[test]
fn a_large_block_is_left_to_the_exact_path() {
    let n = 200;
    let x: Vec<f64> = (0..n).map(f64::from).collect();
    let u: Vec<f64> = (0..n).map(|i| -f64::from(i) / 64.0).collect();
    let (r, t) = (q(0.125), q(1000.0));
    let d = Doubles::validate(Some(r.clone()), x.clone(), u.clone()).unwrap();
    assert!(d.at(&t).is_none());
    assert_eq!(dyadic(&r, &x, &u, &t), oracle(&r, &x, &u, &t));
}

/// A pair whose free flights cross by `2⁻ᵉ` of their gap, `e` from 10 to
/// 70 by `case`, either way (the pair meets just before or just after
/// `t`), from well above to far below the resolution of `ẑ` (`2⁻⁵⁰`
/// here), between two particles at rest, and for half the cases a third
/// one meeting the pair near the same time; `None` when the drawn gap is
/// below `2r`.
fn near_tie(rng: &mut SplitMix64, case: usize) -> Option<(f64, Vec<f64>, Vec<f64>, f64)> {
    let r = 2f64.powi(-20) * (1.0 + rng.unit());
    let x0 = (1.0 + rng.unit()) * 2f64.powi((case % 3) as i32 - 3);
    let g = 2f64.powi(-30) * (1.0 + rng.unit());
    let x1 = x0 + 2.0 * r + g;
    if q(x1) - q(x0) < q(2.0 * r) {
        return None;
    }
    let t = 0.01 + rng.unit() * 0.001;
    // u₁ with t u₁ ≈ −(x₁ − x₀ − 2r)(1 ± 2⁻ᵉ).
    let gap = q(x1) - q(x0) - q(2.0 * r);
    let target = (-gap / q(t)).to_f64().unwrap();
    let e = [10, 14, 18, 22, 26, 70][case % 6];
    let side = if case % 2 == 0 { 1.0 } else { -1.0 };
    let u1 = target * (1.0 + side * (1.0 + rng.unit()) * 2f64.powi(-e));
    let mut x = vec![x0 - 1.0, x0, x1, x1 + 1.0];
    let mut u = vec![0.0, 0.0, u1, 0.0];
    if case % 4 < 2 {
        x.push(x1 + 2.0);
        u.push(0.5);
    }
    Some((r, x, u, t))
}

/// Near-ties ([`near_tie`]): every answer certified must be exact, the
/// closest must be refused.
#[test]
fn near_ties_are_exact_or_refused() {
    let mut rng = SplitMix64::new(0x7e5);
    let (mut yes, mut no) = (0, 0);
    for case in 0..3_000 {
        let Some((r, x, u, t)) = near_tie(&mut rng, case) else {
            continue;
        };
        if agrees(&q(r), &x, &u, &q(t)) {
            yes += 1;
        } else {
            no += 1;
        }
    }
    assert!(yes > 800, "{yes} certified");
    assert!(no > 1_200, "{no} refused");
}

/// The floor only decides when a block is final (the PAVA's module
/// documentation): a floor that makes every block final at once, wrong
/// wherever a later particle pools, must cost refusals, never a wrong
/// answer. Every particle is then emitted alone, and on the near-ties
/// condition 1 between two single particles decides by itself (the
/// floor of the filter never lets a near-tie reach that check), at every
/// place of a run of single particles.
#[test]
fn a_wrong_floor_costs_a_refusal_never_a_wrong_answer() {
    let mut rng = SplitMix64::new(0xf10);
    let (mut yes, mut no) = (0, 0);
    for case in 0..3_000 {
        let Some((r, mut x, mut u, t)) = near_tie(&mut rng, case) else {
            continue;
        };
        // Particles at rest before and after, so that the pair falls at
        // every place of the PAVA's runs of single particles.
        let (before, after) = (case % 11, 4 + case % 7);
        let (first, last) = (x[0], x[x.len() - 1]);
        x.splice(0..0, (0..before).map(|i| first - (before - i) as f64));
        u.splice(0..0, std::iter::repeat_n(0.0, before));
        x.extend((1..=after).map(|i| last + i as f64));
        u.extend(std::iter::repeat_n(0.0, after));
        let checked = Checked::new(Some(q(r)), &x, &u).expect("valid");
        let mut out = vec![f64::NAN; x.len()];
        let cx = super::pava::context(&checked, &x, &u, t).0;
        match super::pava::run(cx, &mut out, usize::MAX, |_, _, _| f64::INFINITY) {
            Some(multi) => {
                assert!(multi.is_empty());
                let want = oracle(&q(r), &x, &u, &q(t));
                assert_eq!(bits(&out), nearest(&want.positions), "case {case}");
                yes += 1;
            }
            None => no += 1,
        }
    }
    assert!(yes > 400, "{yes} certified, {no} refused");
    assert!(no > 2_000, "{no} refused, {yes} certified");
}

/// Clusters touching exactly (a gap of exactly `2r` and equal velocities:
/// two blocks of equal means) and a pair meeting exactly at `t`: ties the
/// filter must refuse, never decide.
#[test]
fn exact_ties_are_refused() {
    let r = 0.25;
    // In contact at 0 with equal velocities.
    let (x, u) = (vec![0.0, 0.5, 3.0], vec![1.0, 1.0, -1.0]);
    assert!(!agrees(&q(r), &x, &u, &q(0.5)));
    // Meeting exactly at t = 1: z₁ = z₀.
    let (x, u) = (vec![0.0, 1.5, 10.0], vec![1.0, 0.0, 0.0]);
    assert!(!agrees(&q(r), &x, &u, &q(1.0)));
    // Two pairs in contact meeting exactly at t = 3/4 (all four `z`
    // equal), and before it (each pair a tie of its own): refused.
    let (x, u) = (vec![0.0, 0.5, 2.5, 3.0], vec![1.0, 1.0, -1.0, -1.0]);
    assert!(!agrees(&q(r), &x, &u, &q(0.75)));
    assert!(!agrees(&q(r), &x, &u, &q(0.5)));
    // After it, one block of four with strict prefix sums: certified.
    assert!(agrees(&q(r), &x, &u, &q(1.0)));
}

/// Exponents beyond the filter's range (huge, tiny, subnormal) are refused
/// and answered by the exact paths; at the edge of the range they are
/// certified and exact.
#[test]
fn exponents_out_of_range_are_refused_and_in_range_exact() {
    let r = 2f64.powi(-400);
    let (x, u) = (vec![0.0, 1.0, 2.0], vec![1.0, -1.0, 0.0]);
    let d = Doubles::validate(Some(q(r)), x.clone(), u.clone()).unwrap();
    assert!(d.at(&q(0.75)).is_none(), "2r out of range");
    let sub = f64::from_bits(3);
    let d = Doubles::validate(Some(q(0.25)), vec![0.0, 1.0], vec![sub, 0.0]).unwrap();
    assert!(d.at(&q(1.0)).is_none(), "a subnormal velocity");
    let big = 2f64.powi(350);
    let d = Doubles::validate(Some(q(0.25)), vec![0.0, big], vec![1.0, 0.0]).unwrap();
    assert!(d.at(&q(1.0)).is_none(), "a huge position");
    // (The Solver answers it by the general path:
    // `solver::tests::the_filter_refuses_and_the_exact_paths_answer`.)
    // The same crowded scene scaled by powers of two (exact, the same
    // blocks): certified near both edges of the range, refused beyond.
    let mut rng = SplitMix64::new(0xed6e);
    let (x, u) = notebook(&mut rng, 60, 1e-3, 1e-4);
    for (e, inside) in [
        (-250, true),
        (-100, true),
        (0, true),
        (250, true),
        (-320, false),
        (320, false),
    ] {
        let s = 2f64.powi(e);
        let xs: Vec<f64> = x.iter().map(|v| v * s).collect();
        let us: Vec<f64> = u.iter().map(|v| v * s).collect();
        assert_eq!(agrees(&q(1e-4 * s), &xs, &us, &q(0.01)), inside, "2^{e}");
    }
}

/// Full-mantissa `t` and `r` (as Python floats are) at many times on one
/// crowded scene.
#[test]
fn full_mantissa_times_and_radii() {
    let mut rng = SplitMix64::new(0xf011);
    let r = 4e-7;
    let (x, u) = notebook(&mut rng, 500, 1e-3, r);
    let mut certified = 0;
    for k in 0..40 {
        let t = 1e-4 * (1.0 + rng.unit()) * f64::from(k);
        certified += usize::from(agrees(&q(r), &x, &u, &q(t)));
    }
    assert!(certified >= 38, "{certified} of 40");
}

/// The validation in doubles decides exactly as `InitialData::new`: gaps
/// of `2r` up to one ulp either way, where `fl(x₁ − x₀) = 2r` hides the
/// sign of the error, and contacts with approaching velocities.
#[test]
fn validation_in_doubles_is_exact() {
    let mut rng = SplitMix64::new(0x5a1d);
    for case in 0..5_000 {
        let x0 = (rng.unit() + 0.5) * 2f64.powi(case % 40 - 10);
        let two_r = (rng.unit() + 0.5) * 2f64.powi(case % 13 - 20);
        let exact = x0 + two_r;
        let ulps = (case % 7) as i64 - 3;
        let x1 = f64::from_bits((exact.to_bits() as i64 + ulps) as u64);
        let (u0, u1) = if case % 3 == 0 {
            (1.0, 0.5)
        } else {
            (0.0, 0.0)
        };
        let r = q(two_r) / BigRational::from_integer(2.into());
        let general = InitialData::new(r.clone(), vec![q(x0), q(x1)], vec![q(u0), q(u1)]).is_ok();
        match Doubles::validate(Some(r), vec![x0, x1], vec![u0, u1]) {
            Ok(_) => assert!(general, "{x0} {x1} {two_r}"),
            Err(e) => {
                assert_eq!(e.reason, Refusal::Invalid);
                assert!(!general, "{x0} {x1} {two_r}");
            }
        }
    }
}

/// The validation's scan on two threads (halves, and the pair across the
/// junction) decides as the one-thread scan and as `InitialData::new`:
/// columns with one defect (a gap 1 ulp below `2r`, a gap of exactly `2r`
/// with approaching velocities, a NaN, an infinity, a value out of the
/// filter's range) at every place, the junction's pair included.
#[test]
fn validation_on_two_threads_is_the_one_thread_one() {
    let mut rng = SplitMix64::new(0x7c4);
    let n = 40;
    let two_r = 0.25;
    let r = q(two_r) / BigRational::from_integer(2.into());
    let (mut valid, mut invalid) = (0, 0);
    for case in 0..600 {
        let mut x: Vec<f64> = (0..n).map(|i| i as f64 + 0.5 * rng.unit()).collect();
        let mut u: Vec<f64> = (0..n).map(|_| 2.0 * rng.unit() - 1.0).collect();
        // The junction of the two-thread scan is between `n/2 − 1` and
        // `n/2`: every third case puts the defect there.
        let at = if case % 3 == 0 {
            n / 2 - 1
        } else {
            (rng.next_u64() % (n as u64 - 1)) as usize
        };
        match case % 6 {
            0 => x[at + 1] = f64::from_bits((x[at] + two_r).to_bits() - 1),
            1 => {
                x[at + 1] = x[at] + two_r;
                u[at + 1] = u[at] - 0.5;
            }
            2 => u[at] = f64::NAN,
            3 => x[at + 1] = f64::INFINITY,
            4 => u[at + 1] = 2f64.powi(-400),
            _ => {}
        }
        let one = super::check_with(&x, &u, two_r, usize::MAX);
        let two = super::check_with(&x, &u, two_r, 2);
        assert_eq!(one, two, "case {case}, defect at {at}");
        // Checked on its copy, in chunks of 1 to 7 (a defect often at a
        // chunk's first pair), on one thread and on two.
        for (parallel_min, chunk) in [(usize::MAX, 1 + case % 7), (2, 1 + case % 5)] {
            let (mut cx, mut cu) = (vec![f64::NAN; n], vec![f64::NAN; n]);
            let into = super::Copies {
                x: &mut cx,
                u: &mut cu,
            };
            let copied = super::copy_and_check_with(
                super::Pair::new(&x, &u),
                into,
                two_r,
                parallel_min,
                chunk,
            );
            assert_eq!(copied, one, "case {case}, defect at {at}, chunk {chunk}");
            if copied.is_some() {
                assert_eq!((bits(&cx), bits(&cu)), (bits(&x), bits(&u)));
            }
        }
        let finite = x.iter().chain(&u).all(|v| v.is_finite());
        let general = finite
            && InitialData::new(
                r.clone(),
                x.iter().map(|&v| q(v)).collect(),
                u.iter().map(|&v| q(v)).collect(),
            )
            .is_ok();
        assert_eq!(one.is_some(), general, "case {case}, defect at {at}");
        if let Some(scan) = one {
            let u_max = u.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            assert_eq!(scan.u_max, u_max);
            assert_eq!(scan.in_range, case % 6 != 4);
            valid += 1;
        } else {
            invalid += 1;
        }
    }
    assert!(
        valid >= 150 && invalid >= 350,
        "{valid} valid, {invalid} invalid"
    );
}

/// The scan's decisions on the range and finiteness (from the ends, the
/// positions next to zero and the velocities' lanes) are those of a value
/// by value test: increasing positions through zero and velocities drawn
/// from magnitudes at and beyond the range's edges, zeros of both signs,
/// subnormals, infinities and NaNs.
#[test]
fn the_scan_decides_the_range_as_each_value_does() {
    let edge = |e: i32| 2f64.powi(e);
    let pool = [
        0.0,
        -0.0,
        f64::from_bits(1),
        edge(-301),
        edge(-300),
        f64::from_bits(edge(-300).to_bits() - 1),
        edge(-299),
        1e-200,
        0.75,
        1.0,
        3.0,
        1e200,
        edge(300),
        f64::from_bits(edge(300).to_bits() + 1),
        edge(301),
        f64::INFINITY,
        f64::NAN,
    ];
    let two_r = edge(-1070);
    let mut rng = SplitMix64::new(0x5ca);
    let (mut valid, mut in_range) = (0, 0);
    for case in 0..4_000 {
        let n = 1 + case % 9;
        let pick = |rng: &mut SplitMix64| {
            let v = pool[(rng.next_u64() % pool.len() as u64) as usize];
            if rng.next_u64() % 2 == 0 {
                -v
            } else {
                v
            }
        };
        let mut x: Vec<f64> = (0..n).map(|_| pick(&mut rng)).collect();
        x.sort_by(f64::total_cmp);
        let mut u: Vec<f64> = (0..n).map(|_| 0.5 + rng.unit()).collect();
        for _ in 0..rng.next_u64() % 3 {
            let at = (rng.next_u64() % n as u64) as usize;
            u[at] = pick(&mut rng);
        }
        let finite = x.iter().chain(&u).all(|v| v.is_finite());
        let want = (finite && super::exact_gaps(&x, &u, two_r).is_some()).then(|| super::Scan {
            u_max: u.iter().fold(0.0f64, |m, v| m.max(v.abs())),
            in_range: x.iter().chain(&u).all(|&v| super::in_range(v)),
        });
        assert_eq!(super::scan(&x, &u, two_r), want, "{x:?} {u:?}");
        if let Some(w) = want {
            valid += 1;
            in_range += usize::from(w.in_range);
        }
    }
    assert!(
        valid > 400 && in_range > 100 && valid - in_range > 100,
        "{valid} valid, {in_range} in range"
    );
}

/// The positions written into a caller's buffer are those of
/// [`Doubles::at`], on one thread and on two; a buffer of the wrong length
/// is refused.
#[test]
fn positions_into_a_buffer_are_those_of_at() {
    let mut rng = SplitMix64::new(0x1b0);
    let mut answered = 0;
    for case in 0..40 {
        let n = 2 + (rng.next_u64() % 400) as usize;
        let gap = [1.0, 0.01][case % 2];
        let r = 4e-7;
        let (x, u) = notebook(&mut rng, n, gap, r);
        let d = Doubles::validate(Some(q(r)), x, u).expect("valid");
        let t = q(gap * 5.0 * (1.0 + rng.unit()));
        let Some(f) = d.at(&t) else { continue };
        answered += 1;
        for parallel_min in [usize::MAX, 2] {
            let mut out = vec![f64::NAN; n];
            let g = d
                .at_into_with(&t, &mut out, parallel_min)
                .expect("certified");
            assert_eq!(bits(&out), bits(f.positions()));
            assert!(g.positions().is_empty());
            assert_eq!(bits(&g.velocities()), bits(&f.velocities()));
            assert_eq!(g.clusters(), f.clusters());
        }
        assert!(d.at_into(&t, &mut vec![0.0; n + 1]).is_none());
    }
    assert!(answered >= 30, "{answered} of 40 answered");
}

/// The filter on borrowed columns ([`Checked`]) validates as
/// [`Doubles::validate`] does and answers as [`Doubles::at`] does (the
/// same positions, velocities, multipliers, clusters and exact state), on
/// one thread and on two; columns or a buffer of another length are
/// refused.
#[test]
fn borrowed_columns_answer_as_owned_ones() {
    let mut rng = SplitMix64::new(0x1b1);
    let mut answered = 0;
    for case in 0..40 {
        let n = 2 + (rng.next_u64() % 400) as usize;
        let gap = [1.0, 0.01][case % 2];
        let r = 4e-7;
        let (x, u) = notebook(&mut rng, n, gap, r);
        let checked = Checked::new(Some(q(r)), &x, &u).expect("valid");
        let d = Doubles::validate(Some(q(r)), x.clone(), u.clone()).expect("valid");
        assert_eq!(checked.n(), d.n());
        let t = q(gap * 5.0 * (1.0 + rng.unit()));
        let Some(f) = d.at(&t) else {
            assert!(checked.at_into(&x, &u, &t, &mut vec![0.0; n]).is_none());
            continue;
        };
        answered += 1;
        for parallel_min in [usize::MAX, 2] {
            let mut out = vec![f64::NAN; n];
            let p = checked
                .at_into_with(&x, &u, &t, &mut out, parallel_min)
                .expect("certified");
            assert_eq!(bits(&out), bits(f.positions()));
            let mut v = vec![f64::NAN; n];
            p.write_velocities(&u, &mut v);
            assert_eq!(bits(&v), bits(&f.velocities()));
            let mut l = vec![f64::NAN; n - 1];
            p.write_multipliers(&u, &mut l);
            assert_eq!(bits(&l), bits(&f.multipliers()));
            assert_eq!(p.clusters(), f.clusters());
            assert_eq!(p.exact_state(&x, &u), f.exact_state());
        }
        let mut out = vec![0.0; n];
        assert!(checked.at_into(&x[1..], &u, &t, &mut out).is_none());
        assert!(checked.at_into(&x, &u[1..], &t, &mut out).is_none());
        assert!(checked.at_into(&x, &u, &t, &mut out[1..]).is_none());
    }
    assert!(answered >= 30, "{answered} of 40 answered");
    // Invalid and undecided columns are refused as `validate` refuses them.
    let r = Some(q(0.25));
    assert_eq!(
        Checked::new(r.clone(), &[0.0, 0.25], &[0.0, 0.0]).err(),
        Some(Refusal::Invalid)
    );
    assert_eq!(
        Checked::new(r.clone(), &[0.0, 1.0], &[0.0]).err(),
        Some(Refusal::Undecided)
    );
    assert_eq!(
        Checked::new(r.clone(), &[], &[]).err(),
        Some(Refusal::Undecided)
    );
    // `Checked::copied` validates as `new` does, and needs copies as long.
    let (x, u) = notebook(&mut rng, 300, 0.01, 4e-7);
    let (mut cx, mut cu) = (vec![0.0; 300], vec![0.0; 300]);
    let copied = Checked::copied(Some(q(4e-7)), &x, &u, &mut cx, &mut cu).expect("valid");
    let checked = Checked::new(Some(q(4e-7)), &x, &u).expect("valid");
    assert_eq!(copied.n(), checked.n());
    assert_eq!((bits(&cx), bits(&cu)), (bits(&x), bits(&u)));
    assert_eq!(
        Checked::copied(
            r.clone(),
            &[0.0, 0.25],
            &[0.0, 0.0],
            &mut cx[..2],
            &mut cu[..2]
        )
        .err(),
        Some(Refusal::Invalid)
    );
    assert_eq!(
        Checked::copied(r, &[0.0, 1.0], &[0.0, 0.0], &mut cx[..2], &mut cu[..1]).err(),
        Some(Refusal::Undecided)
    );
}
