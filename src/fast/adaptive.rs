//! Adaptive precision: PAVA whose pooling decisions are taken in `f64` when
//! a certified error bound proves them right, and in exact integers only for
//! the decisions the bound cannot settle — "a scene gets no more precision
//! than it needs", and the answer is still exact.
//!
//! **Which path.** When the data fit the fixed-width kernels
//! ([`crate::fast::kernel::Width::I128`], [`crate::fast::kernel::Width::I256`]
//! or [`crate::fast::kernel::Width::I512`]) the
//! exact kernel is as cheap as a float PAVA or within a small factor of it
//! (the figures: docs/guide/performance.md), so it answers
//! ([`Path::Integer`]). Only data that need `BigInt` take the filter: the
//! decisions run in `f64` ([`Path::Certified`]) and the exact block sums are
//! accumulated once over the final partition; if the uncertain decisions
//! would cost more exact work than `4N` summed entries, the whole scene goes
//! to the exact kernel instead ([`Path::Exact`]). The result is a [`Blocks`], equal to
//! [`crate::fast::kernel::blocks_at`]'s on every scene (the tests check it).
//!
//! **The certificate** (`u = 2^−53`, `Y_i = a X_i + b U_i` as in
//! [`crate::fast::kernel`]). The inputs `X_i, U_i, a, b` are rounded to `f64` with
//! relative error `≤ 2u` each (`BigInt::to_f64` keeps the top 64 bits, then
//! rounds). Then `ŷ_i = fl(fl(â x̂_i) + fl(b̂ û_i))` satisfies
//! `|ŷ_i − Y_i| ≤ ((1+2u)²(1+u)² − 1)(|aX_i| + |bU_i|) ≤ 6.1u A`, with
//! `A = |a| max|X| + |b| max|U|`; we use `E = 8u Â` (`Â` the `f64` value of
//! `A`, itself within a factor `1 + 8u` of `A`). A block sum `s` formed by
//! `f64` additions carries a bound `e` with `e = E` for one entry and
//! `e = e_a + e_b + u|s_a + s_b|` on a merge (one rounding per addition).
//! Pooling asks for the sign of `D = S_a k_b − S_b k_a` (exact sums `S`);
//! `d̂ = fl(fl(s_a k_b) − fl(s_b k_a))` satisfies
//! `|d̂ − D| ≤ B = e_a k_b + e_b k_a + 3u(|s_a| k_b + |s_b| k_a)` (block sizes
//! are exact in `f64` below `2^53`). The decision is taken in `f64` when
//! `|d̂| > 2B`: the factor 2 absorbs the rounding of the bound's own
//! evaluation (`O(N)` operations of relative error `u`, `N u ≪ 1`). Ties
//! (`D = 0`, and the lexicographic tie-break on `U`) are never certified in
//! `f64`: they go to the exact comparison.

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{Signed, ToPrimitive};

use crate::error::Error;
use crate::fast::kernel::{
    blocks_at, pools, state_of_blocks, AtTime, Blocks, IntegerData, Run, Sums, Width,
};
use crate::state::State;

/// `u = 2^−53`, the unit roundoff of `f64`.
const U: f64 = f64::EPSILON / 2.0;

/// How the adaptive solver answered.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Path {
    /// The data fit a fixed-width kernel, which answered.
    Integer(Width),
    /// Decisions in `f64`, certified; `exact` of the `decisions` needed the
    /// exact comparison.
    Certified {
        /// Pooling decisions taken.
        decisions: usize,
        /// Decisions the `f64` bound could not settle (decided exactly).
        exact: usize,
    },
    /// The filter gave up (non-finite values, or too many uncertain
    /// decisions): the exact kernel answered.
    Exact(Width),
}

/// The adaptive solver's answer: the exact blocks and the path taken.
#[derive(Debug, Clone)]
pub struct Adaptive {
    /// The PAVA blocks at `t + ε`, exact.
    pub blocks: Blocks,
    /// Which path answered.
    pub path: Path,
}

/// A block of the `f64` loop: sum `s` with error bound `e`, size `k` (as an
/// exact `f64`), first index.
#[derive(Debug, Clone, Copy)]
struct Approx {
    s: f64,
    e: f64,
    k: f64,
    first: usize,
}

/// `Â = |â| max|x̂| + |b̂| max|û|`, the `f64` value of the input term `A`
/// (module documentation), from which `E = 8u Â`.
fn input_term(a: f64, b: f64, xf: &[f64], uf: &[f64]) -> f64 {
    let max = |v: &[f64]| v.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    a.abs() * max(xf) + b.abs() * max(uf)
}

/// `E = 8u Â`, the error bound of every entry `ŷ_i` (module documentation).
fn entry_bound(big_a: f64) -> f64 {
    8.0 * U * big_a
}

impl Approx {
    /// Entry `i`: `ŷ_i = fl(fl(â x̂_i) + fl(b̂ û_i))` with the bound `E`.
    fn entry(a: f64, b: f64, x: f64, u: f64, e0: f64, i: usize) -> Approx {
        Approx {
            s: a * x + b * u,
            e: e0,
            k: 1.0,
            first: i,
        }
    }

    /// `d̂ = fl(fl(s_a k_b) − fl(s_b k_a))` for this block (`a`, on the
    /// left) against `cur` (`b`, its right neighbour), and its bound
    /// `B = e_a k_b + e_b k_a + 3u(|s_a| k_b + |s_b| k_a)` (module
    /// documentation).
    fn compare(&self, cur: &Approx) -> (f64, f64) {
        let diff = self.s * cur.k - cur.s * self.k;
        let bound = self.e * cur.k
            + cur.e * self.k
            + 3.0 * U * (self.s.abs() * cur.k + cur.s.abs() * self.k);
        (diff, bound)
    }

    /// This block pooled with `cur`, its right neighbour: `s = fl(s_a + s_b)`
    /// carries `e = e_a + e_b + u|s|` (one rounding).
    fn merge(&self, cur: &Approx) -> Approx {
        let s = self.s + cur.s;
        Approx {
            s,
            e: self.e + cur.e + U * s.abs(),
            k: self.k + cur.k,
            first: self.first,
        }
    }
}

/// The sign of `D` when `d̂` settles it (`|d̂ − D| ≤ B`): pool (`D > 0`)
/// when `d̂ > 2B`, not (`D < 0`) when `d̂ < −2B`; `None` otherwise, for the
/// exact comparison. The factor 2 absorbs the rounding of `B`'s own
/// evaluation (module documentation).
fn settled(diff: f64, bound: f64) -> Option<bool> {
    if diff > 2.0 * bound {
        Some(true)
    } else if diff < -2.0 * bound {
        Some(false)
    } else {
        None
    }
}

/// Exact comparison of two adjacent blocks `[f, m)` and `[m, end)` in
/// `BigInt` (the filter only runs on data that need it): `true` when the
/// left one pools with the right (its mean is `≥` in the lexicographic order
/// on `(Y, U)`).
struct Exact<'a> {
    d: &'a IntegerData,
    at: &'a AtTime,
    /// Entries summed so far (the budget).
    work: usize,
    /// Exact comparisons made.
    calls: usize,
}

impl Exact<'_> {
    fn pools(&mut self, f: usize, m: usize, end: usize) -> bool {
        self.work += end - f;
        self.calls += 1;
        let (ka, kb) = ((m - f) as u64, (end - m) as u64);
        let sum = |v: &[BigInt], r: std::ops::Range<usize>| -> BigInt { v[r].iter().sum() };
        let (xa, ua) = (sum(&self.d.x, f..m), sum(&self.d.u, f..m));
        let (xb, ub) = (sum(&self.d.x, m..end), sum(&self.d.u, m..end));
        let run = |k: u64, x: BigInt, u: BigInt| Run {
            k,
            sy: &self.at.a * x + &self.at.b * &u,
            su: u,
        };
        pools(&run(ka, xa, ua), &run(kb, xb, ub))
    }
}

/// The `f64` loop; `None` when the exact work exceeds its budget.
fn certified_partition(
    d: &IntegerData,
    at: &AtTime,
    exact: &mut Exact<'_>,
) -> Option<(Vec<Approx>, usize)> {
    let n = d.n();
    let (a, b) = (at.a.to_f64()?, at.b.to_f64()?);
    let (xf, uf) = d.approx();
    let big_a = input_term(a, b, xf, uf);
    let e0 = entry_bound(big_a);
    // Every |ŷ_i| ≤ A(1 + 7u) and every |s| ≤ N A(1 + …): finite when
    // N A is well inside the f64 range; block sizes exact below 2^53.
    if !(big_a * (n as f64) * 4.0).is_finite() || n as f64 > 2f64.powi(52) {
        return None;
    }
    let budget = 4 * n + 64;
    let mut decisions = 0usize;
    let mut stack: Vec<Approx> = Vec::with_capacity(n);
    for i in 0..n {
        let mut cur = Approx::entry(a, b, xf[i], uf[i], e0, i);
        while let Some(top) = stack.last() {
            decisions += 1;
            let (diff, bound) = top.compare(&cur);
            let pool = match settled(diff, bound) {
                Some(pool) => pool,
                None => {
                    if exact.work > budget {
                        return None;
                    }
                    exact.pools(top.first, cur.first, i + 1)
                }
            };
            if !pool {
                break;
            }
            cur = top.merge(&cur);
            stack.pop();
        }
        stack.push(cur);
    }
    Some((stack, decisions))
}

/// Exact PAVA at time `t`, deciding in `f64` where a certified bound allows
/// (module documentation). The blocks equal [`blocks_at`]'s.
pub fn adaptive_blocks_at(d: &IntegerData, t: &BigRational) -> Adaptive {
    let at = AtTime::new(d, t);
    if at.width != Width::Big {
        return Adaptive {
            blocks: blocks_at(d, t),
            path: Path::Integer(at.width),
        };
    }
    let mut exact = Exact {
        d,
        at: &at,
        work: 0,
        calls: 0,
    };
    let Some((stack, decisions)) = certified_partition(d, &at, &mut exact) else {
        let blocks = blocks_at(d, t);
        let width = blocks.width();
        return Adaptive {
            blocks,
            path: Path::Exact(width),
        };
    };
    // The exact sums over the certified partition: ΣY = a ΣX + b ΣU per
    // block.
    let ends = stack.iter().skip(1).map(|b| b.first).chain([d.n()]);
    let sums = Sums::Big(
        stack
            .iter()
            .zip(ends)
            .map(|(blk, end)| {
                let r = blk.first..end;
                let sx: BigInt = d.x[r.clone()].iter().sum();
                let su: BigInt = d.u[r].iter().sum();
                Run {
                    k: (end - blk.first) as u64,
                    sy: &at.a * sx + &at.b * &su,
                    su,
                }
            })
            .collect(),
    );
    Adaptive {
        blocks: Blocks::new(sums, at.dy.clone(), d.du.clone()),
        path: Path::Certified {
            decisions,
            exact: exact.calls,
        },
    }
}

/// The state at `t ≥ 0` from the adaptive solver's blocks, built by the
/// kernel's one construction ([`state_of_blocks`]): equal, field by field,
/// to [`crate::projection::state_at`] on `BigRational`.
pub fn state_at(d: &IntegerData, t: &BigRational) -> Result<State<BigRational>, Error> {
    if t.is_negative() {
        return Err(Error::NegativeTime { t: t.to_string() });
    }
    Ok(state_of_blocks(d, &adaptive_blocks_at(d, t).blocks, t))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::{initial_data, Limits, SplitMix64};
    use crate::initial::InitialData;
    use crate::trajectory::Trajectory;
    use num_traits::{One, Zero};

    use crate::rational::ratio as q;

    fn offset_by(
        data: &InitialData<BigRational>,
        offset: &BigRational,
    ) -> InitialData<BigRational> {
        let x = data.positions().iter().map(|x| x + offset).collect();
        InitialData::new(data.radius().clone(), x, data.velocities().to_vec()).unwrap()
    }

    /// `1.234…` with 30 significant digits.
    fn decimal30() -> BigRational {
        BigRational::new(
            BigInt::parse_bytes(b"123456789012345678901234567891", 10).unwrap(),
            BigInt::from(10u32).pow(29),
        )
    }

    /// A position that needs `BigInt` (beyond the 512-bit kernel).
    fn beyond_512() -> BigRational {
        BigRational::from_integer(BigInt::one() << 600u32) + decimal30()
    }

    /// The oracle battery: random scenes at every collision instant (exact
    /// ties) and between, shifted into each width, against the exact
    /// kernel.
    #[test]
    fn equals_the_exact_kernel() {
        let mut rng = SplitMix64::new(23);
        let offsets = [
            q(0, 1),
            decimal30(),
            BigRational::from_integer(BigInt::one() << 200u32) + decimal30(),
            BigRational::from_integer(BigInt::one() << 400u32) + q(1, 3),
            BigRational::from_integer(BigInt::one() << 700u32) + q(1, 3),
            BigRational::from_integer(BigInt::one() << 1100u32),
        ];
        let mut seen = [0usize; 3];
        for k in 0..240 {
            let data = initial_data(
                &rng.bytes(300),
                Limits {
                    max_n: 1 + k % 60,
                    ..Limits::default()
                },
            );
            let traj = Trajectory::new(data.clone());
            let times = crate::trajectory::probe_times(&traj, Some(8));
            let data = offset_by(&data, &offsets[k % offsets.len()]);
            let d = IntegerData::new(&data);
            for t in &times {
                let got = adaptive_blocks_at(&d, t);
                seen[match got.path {
                    Path::Integer(_) => 0,
                    Path::Certified { .. } => 1,
                    Path::Exact(_) => 2,
                }] += 1;
                assert_eq!(
                    got.blocks,
                    blocks_at(&d, t),
                    "case {k}, t = {t}, {:?}",
                    got.path
                );
            }
        }
        // Every path was exercised.
        assert!(seen.iter().all(|&c| c > 0), "{seen:?}");
    }

    /// Scene `k` of the data near `f64` resolution (described at
    /// `certified_decisions_in_f64_are_right`, which they were written for):
    /// a random scene beyond the 512-bit kernel and its probe times
    /// (collision instants and between).
    fn near_f64_resolution(rng: &mut SplitMix64, k: u64) -> (IntegerData, Vec<BigRational>) {
        let big = |e: u32| BigRational::from_integer(BigInt::from(10u32).pow(e));
        let (scale, fine) = (big(100), big(160));
        let data = initial_data(
            &rng.bytes(300),
            Limits {
                max_n: 2 + (k % 40) as usize,
                ..Limits::default()
            },
        );
        let traj = Trajectory::new(data.clone());
        let times = crate::trajectory::probe_times(&traj, Some(8));
        let data = if k % 2 == 0 {
            // Everything scaled by c = 1 + 7/10^100: the collision
            // times (gap over closing speed) are unchanged, so the
            // instants probed are exact ties.
            let c = q(1, 1) + q(7, 1) / &scale;
            let x = data.positions().iter().map(|x| x * &c).collect();
            let u = data.velocities().iter().map(|u| u * &c).collect();
            InitialData::new(data.radius() * &c, x, u).unwrap()
        } else {
            // Non-decreasing perturbations (contacts stay admissible).
            let mut d = 7u64;
            let x = (data.positions().iter().zip(0u64..))
                .map(|(x, i)| {
                    d += (i * 7919 + k) % 9973;
                    x + BigRational::from_integer(BigInt::from(d)) / &fine
                })
                .collect();
            InitialData::new(data.radius().clone(), x, data.velocities().to_vec()).unwrap()
        };
        // Every other pair of cases, a Galilean boost that leaves the
        // collision instants alone: x⁰ + Mτ, u⁰ − M (M = 10^8), so that
        // at the probed instant τ the free-flight values cancel M and
        // the rounding of the inputs (the bound's `E` term), not that
        // of the sums, is what the certificate must cover.
        let data = if k % 4 >= 2 && !times.is_empty() {
            let tau = &times[times.len() / 2];
            let m = q(100_000_000, 1);
            // With near-ties of 10^-11 … 10^-7 (below the inputs'
            // rounding, ~10^-8 here, above the sums').
            let mut d = 0u64;
            let x = (data.positions().iter().zip(0u64..))
                .map(|(x, i)| {
                    d += (i * 104_729 + k) % 9973;
                    x + &m * tau + q(d as i64, 100_000_000_000)
                })
                .collect();
            let u = data.velocities().iter().map(|u| u - &m).collect();
            InitialData::new(data.radius().clone(), x, u).unwrap()
        } else {
            data
        };
        (IntegerData::new(&data), times)
    }

    /// Data beyond the 512-bit kernel whose values still differ at the top
    /// of their `f64` mantissas, so that most pooling decisions are taken in
    /// `f64`: random scenes scaled by `1 + 7/10^100` (the collision instants
    /// of the unscaled scene stay exact ties), or with positions perturbed by
    /// non-decreasing `δ_i / 10^160` (near-ties, one part in ~10^150). Both
    /// need more than 512 bits and stay well inside the `f64` range. At every
    /// collision instant and between: the answer equals the exact kernel's,
    /// the certified path answers almost every probe (not the budget's
    /// fallback), most decisions are taken in `f64` (measured: 23 % exact,
    /// the ties and near-ties), and some are left to the exact comparison.
    /// Half the cases are boosted so that the free-flight values cancel at
    /// a probed instant: there the inputs' rounding dominates, and a bound
    /// without its `E` term certifies wrong decisions.
    /// The oracle battery above shifts its big-width scenes by `2^700`, where
    /// no decision is within `f64` resolution, so it never reaches the `f64`
    /// certificate: this test checks it (a bound made smaller decides a
    /// near-tie the wrong way; a bound made much larger sends the decisions
    /// to the exact comparison). Found by cargo-mutants on `src/fast/`
    /// (docs/mutants.md).
    #[test]
    fn certified_decisions_in_f64_are_right() {
        let mut rng = SplitMix64::new(41);
        let (mut decided, mut exact_calls) = (0usize, 0usize);
        let (mut probes, mut certified) = (0usize, 0usize);
        for k in 0..120u64 {
            let (d, times) = near_f64_resolution(&mut rng, k);
            for t in &times {
                let got = adaptive_blocks_at(&d, t);
                assert_eq!(got.blocks, blocks_at(&d, t), "case {k}, t = {t}");
                probes += 1;
                if let Path::Certified { decisions, exact } = got.path {
                    certified += 1;
                    decided += decisions;
                    exact_calls += exact;
                }
            }
        }
        // One particle, or data whose offsets cancel in the translation,
        // may still fit the 512-bit kernel; every other probe is certified.
        assert!(
            10 * certified > 9 * probes,
            "{certified} of {probes} probes certified"
        );
        assert!(exact_calls > 0, "no decision needed the exact comparison");
        assert!(
            4 * exact_calls < decided,
            "{exact_calls} of {decided} decisions exact: the f64 certificate settles too few"
        );
    }

    /// Two particles whose free-flight positions differ by one part in
    /// 10^40: far below f64 resolution, so the decision is exact, and right
    /// on both sides of the tie.
    #[test]
    fn differences_below_f64_resolution() {
        let tiny = BigRational::new(BigInt::one(), BigInt::from(10u32).pow(40));
        for (gap, pooled) in [
            (tiny.clone(), false),
            (-tiny.clone(), true),
            (q(0, 1), true),
        ] {
            // x̃ = (c, c + gap): pooled exactly when gap ≤ 0 (equal
            // velocities, so the tie-break pools).
            let c = beyond_512();
            let x = vec![c.clone(), c + q(1, 1) + gap];
            let data = InitialData::new(q(1, 2), x, vec![q(0, 1), q(0, 1)]);
            let Ok(data) = data else {
                // An overlapping pair (gap < 0) is not admissible data;
                // probe the same decision through the velocities instead.
                let c = beyond_512();
                let x = vec![c.clone(), c + q(2, 1)];
                let u = vec![q(1, 1) + tiny.clone(), q(0, 1)];
                let data = InitialData::new(q(1, 2), x, u).unwrap();
                let d = IntegerData::new(&data);
                // Meet at t = 1/(1 + 10^−40) < 1: pooled at t = 1.
                let got = adaptive_blocks_at(&d, &q(1, 1));
                assert_eq!(got.blocks.len(), 1);
                assert_eq!(got.blocks, blocks_at(&d, &q(1, 1)));
                assert!(
                    matches!(got.path, Path::Certified { exact: 1.., .. }),
                    "{:?}",
                    got.path
                );
                continue;
            };
            let d = IntegerData::new(&data);
            let got = adaptive_blocks_at(&d, &q(0, 1));
            assert_eq!(got.blocks.len() == 1, pooled);
            assert_eq!(got.blocks, blocks_at(&d, &q(0, 1)));
            assert!(
                matches!(got.path, Path::Certified { exact: 1.., .. }),
                "{:?}",
                got.path
            );
        }
    }

    /// A long resting cluster (every decision a tie) exhausts the exact
    /// budget: the exact kernel answers, and the answer is the same.
    #[test]
    fn too_many_ties_fall_back_to_the_exact_kernel() {
        let n = 400;
        let x = (0..n).map(|i| beyond_512() + q(i, 1)).collect();
        let data = InitialData::new(q(1, 2), x, vec![q(1, 3); n as usize]).unwrap();
        let d = IntegerData::new(&data);
        let got = adaptive_blocks_at(&d, &q(5, 7));
        assert_eq!(got.path, Path::Exact(Width::Big));
        assert_eq!(got.blocks.len(), 1);
        assert_eq!(got.blocks, blocks_at(&d, &q(5, 7)));
    }

    /// `v` exactly, as a rational.
    fn exactly(v: f64) -> BigRational {
        BigRational::from_float(v).expect("a finite f64")
    }

    /// The bounds the `f64` loop tracks, on the scenes near `f64` resolution
    /// at every probe time, checked against the module documentation in
    /// exact arithmetic: the input term `Â` is within `8u A` of
    /// `A = |a| max|X| + |b| max|U|`, `E` is `8u Â`, and every entry `ŷ_i`
    /// is within `E` of `Y_i`; then adjacent blocks are pooled in a random
    /// order until one is left (any order PAVA can take, and more), and at
    /// every step the tracked `e` of the pooled block and the `B` of the
    /// decision are valid (`|s − S| ≤ e`, `|d̂ − D| ≤ B` with `S`, `D` the
    /// exact sums of the `Y_i` and their cross difference), a settled
    /// decision has the sign of `D` (never a tie), and `e`, `B` equal the
    /// documented `e_a + e_b + u|s_a + s_b|` and
    /// `e_a k_b + e_b k_a + 3u(|s_a| k_b + |s_b| k_a)` evaluated exactly from
    /// the same `f64` values, up to the rounding of their own evaluation
    /// (`4u` and `5u` relative: 2 and 4 roundings of non-negative terms). A
    /// term dropped, shrunk or inflated fails the last check even where no
    /// datum makes the smaller bound certify a wrong decision (the margin
    /// `2B` and the input term leave slack;
    /// `block_sums_rounded_up_at_every_addition` has data where a smaller
    /// sum term does).
    #[test]
    fn the_tracked_bounds_are_valid_and_as_documented() {
        let u = BigRational::new(BigInt::one(), BigInt::one() << 53u32);
        // `|got − want| ≤ r u want`.
        let close = |got: f64, want: &BigRational, r: i64| {
            (exactly(got) - want).abs() <= q(r, 1) * &u * want
        };
        let mut rng = SplitMix64::new(43);
        let (mut probes, mut merges, mut settled_right) = (0usize, 0usize, 0usize);
        for k in 0..60u64 {
            let (d, times) = near_f64_resolution(&mut rng, k);
            for t in &times {
                let at = AtTime::new(&d, t);
                if at.width != Width::Big {
                    continue;
                }
                probes += 1;
                let (a, b) = (at.a.to_f64().unwrap(), at.b.to_f64().unwrap());
                let (xf, uf) = d.approx();
                let big_a = input_term(a, b, xf, uf);
                let max = |v: &[BigInt]| v.iter().map(BigInt::abs).max().unwrap_or_default();
                let want =
                    BigRational::from_integer(at.a.abs() * max(&d.x) + at.b.abs() * max(&d.u));
                assert!(
                    close(big_a, &want, 8),
                    "Â = {big_a:e}, A = {:e}",
                    want.to_f64().unwrap_or(f64::NAN)
                );
                // E = 8u Â exactly (8u is a power of 2).
                let e0 = entry_bound(big_a);
                assert_eq!(exactly(e0), q(8, 1) * &u * exactly(big_a));
                // Blocks with their exact sums ΣY.
                let mut row: Vec<(Approx, BigInt)> = (0..d.n())
                    .map(|i| {
                        let y = &at.a * &d.x[i] + &at.b * &d.u[i];
                        let entry = Approx::entry(a, b, xf[i], uf[i], e0, i);
                        let err = exactly(entry.s) - BigRational::from_integer(y.clone());
                        assert!(err.abs() <= exactly(entry.e), "entry {i}, t = {t}");
                        (entry, y)
                    })
                    .collect();
                while row.len() > 1 {
                    let j = (rng.next_u64() % (row.len() as u64 - 1)) as usize;
                    let ((l, sl), (r, sr)) = (&row[j], &row[j + 1]);
                    let (kl, kr) = (BigInt::from(l.k as u64), BigInt::from(r.k as u64));
                    let (ekl, ekr) = (
                        BigRational::from_integer(kl.clone()),
                        BigRational::from_integer(kr.clone()),
                    );
                    // The decision.
                    let (diff, bound) = l.compare(r);
                    let exact_d = BigRational::from_integer(sl * &kr - sr * &kl);
                    let want = exactly(l.e) * &ekr
                        + exactly(r.e) * &ekl
                        + q(3, 1) * &u * (exactly(l.s).abs() * &ekr + exactly(r.s).abs() * &ekl);
                    assert!(
                        close(bound, &want, 5),
                        "B = {bound:e}, documented {:e}",
                        want.to_f64().unwrap_or(f64::NAN)
                    );
                    assert!((exactly(diff) - &exact_d).abs() <= exactly(bound));
                    if let Some(pool) = settled(diff, bound) {
                        assert!(!exact_d.is_zero() && pool == exact_d.is_positive());
                        settled_right += 1;
                    }
                    // The pooled block.
                    let m = l.merge(r);
                    let sum = sl + sr;
                    let want =
                        exactly(l.e) + exactly(r.e) + &u * (exactly(l.s) + exactly(r.s)).abs();
                    assert!(
                        close(m.e, &want, 4),
                        "e = {:e}, documented {:e}",
                        m.e,
                        want.to_f64().unwrap_or(f64::NAN)
                    );
                    let err = exactly(m.s) - BigRational::from_integer(sum.clone());
                    assert!(err.abs() <= exactly(m.e));
                    assert_eq!((m.k, m.first), (l.k + r.k, l.first));
                    row[j] = (m, sum);
                    row.remove(j + 1);
                    merges += 1;
                }
            }
        }
        // Not vacuous: the scenes reach the certificate, and many of the
        // decisions are settled in `f64`.
        assert!(
            probes > 100 && merges > 1000,
            "{probes} probes, {merges} merges"
        );
        assert!(
            5 * settled_right > merges,
            "{settled_right} of {merges} settled"
        );
    }

    /// The margin: a decision is settled in `f64` only when `|d̂| > 2B`, so
    /// that `B` evaluated with rounding still bounds `|d̂ − D|`; inside
    /// `(−2B, 2B)` (a tie `d̂ = 0` included) it goes to the exact comparison.
    /// On bounds of every magnitude the `f64` loop meets (`B` is about
    /// `u N² max|Y|`, far above 1 on data beyond 512 bits).
    #[test]
    fn decided_in_f64_only_beyond_twice_the_bound() {
        for e in [-40, -1, 0, 1, 10, 100, 600, 1000] {
            let bound = 2f64.powi(e) * 1.375;
            for x in [0.0, 0.5, 1.0, 1.5, 1.99] {
                assert_eq!(settled(x * bound, bound), None, "{x} B, B = {bound:e}");
                assert_eq!(settled(-x * bound, bound), None, "−{x} B, B = {bound:e}");
            }
            for x in [2.01, 3.0, 1e6] {
                assert_eq!(settled(x * bound, bound), Some(true), "{x} B");
                assert_eq!(settled(-x * bound, bound), Some(false), "−{x} B");
            }
        }
        assert_eq!(settled(0.0, 0.0), None, "a tie is never settled in f64");
    }

    /// Particles apart at `t = 0` (`r = 1/2`, translated positions
    /// `x̃_i = (2^52 + i) 2^548`) with velocities `U_i = (y_i − 2^52 − i) 2^548`,
    /// so that at `t = 1` (`a = b = 1`) `Y_i = y_i 2^548`: beyond the 512-bit
    /// kernel, every input and every `ŷ_i` exact in `f64`, and the `f64`
    /// additions of the `ŷ_i` round as those of the `y_i` do.
    fn at_one(y: &[i128]) -> IntegerData {
        let unit = |v: i128| BigRational::from_integer(BigInt::from(v) << 548u32);
        let top = 1i128 << 52;
        let x = (0..y.len() as i128)
            .map(|i| unit(top + i) + q(i as i64, 1))
            .collect();
        let u = (y.iter().zip(0i128..))
            .map(|(&y, i)| unit(y - top - i))
            .collect();
        IntegerData::new(&InitialData::new(q(1, 2), x, u).unwrap())
    }

    /// `k` decreasing values `y_j ∈ [2^52 + (k + 1 − j) 2^11, + 2^11)`
    /// (so that they pool into one block) whose running `f64` sum rounds up
    /// at every addition by as much as the low bits allow (about half a unit
    /// in the last place, chosen greedily): the values, the `f64` sum and
    /// the exact one.
    fn rounded_up(k: usize) -> (Vec<i128>, f64, i128) {
        let step = 1i128 << 11;
        let (mut y, mut s, mut exact) = (Vec::with_capacity(k), 0.0f64, 0i128);
        for j in 0..k as i128 {
            let base = (1i128 << 52) + (k as i128 + 1 - j) * step;
            let up = |v: i128| (s + v as f64) as i128 - (s as i128 + v);
            let v = (base..base + step)
                .max_by_key(|&v| (up(v), -v))
                .unwrap_or(base);
            y.push(v);
            s += v as f64;
            exact += v;
        }
        (y, s, exact)
    }

    /// 64 values summing to `total` that pool into one block (63 decreasing
    /// values `2^16` above the mean, then one far below), all multiples of
    /// 64, so that every `f64` partial sum (below `2^59`) is exact.
    fn summed_exactly(total: i128) -> Vec<i128> {
        let w = total / 64 / 64 * 64 + (1 << 16);
        let mut y: Vec<i128> = (0..63).map(|j| w - 64 * j).collect();
        y.push(total - y.iter().sum::<i128>());
        y
    }

    /// Adversarial data for the bound's sum terms: a block of `k = 512`
    /// values whose `f64` sum rounds up at every addition, so that its error
    /// grows like `u k² max|Y|` (measured: 43,946 units of `2^548`, where
    /// `u k max|Y| = 256`) and only the tracked `u|s|` of every merge covers
    /// it — the input term `kE` (2,048) and the rounding term of the cross
    /// products do not. Its neighbour is one value just above its mean
    /// (`D < 0` by at most `k`: they stay apart), or a block of 64 values
    /// whose `f64` sums are exact and whose mean is just above, on its right
    /// (`D < 0`: apart) or on its left (`D > 0`: they pool); in the last two
    /// the error is multiplied by the other block's size, and only the term
    /// `e_a k_b` (right) or `e_b k_a` (left) covers it (`|d̂ − D| = 2.8 · 10^6`
    /// against `1.5 · 10^6` for twice the bound's other terms). Each time the
    /// `f64` cross difference has the wrong sign: the certificate must leave
    /// that one decision to the exact comparison, and it settles every other
    /// in `f64`.
    #[test]
    fn block_sums_rounded_up_at_every_addition() {
        let k = 512usize;
        let (rounded, s, exact) = rounded_up(k);
        // The datum is what it claims: an error past u k² max|Y| / 8.
        let max_y = rounded[0] as f64;
        assert!(
            (s as i128 - exact) as f64 > U * (k * k) as f64 * max_y / 8.0,
            "{}",
            s as i128 - exact
        );
        // k y_k just above ΣY: the last particle separates.
        let one = [rounded.clone(), vec![exact / k as i128 + 1]].concat();
        // 64 values with 8 Σ just above ΣY of the rounded block: a mean
        // above its mean by at most 1.
        let beside = 64 * (exact / 512 + 1);
        let right = [rounded.clone(), summed_exactly(beside)].concat();
        let left = [summed_exactly(beside), rounded].concat();
        for (y, blocks) in [(one, 2), (right, 2), (left, 1)] {
            let d = at_one(&y);
            let t = q(1, 1);
            let got = adaptive_blocks_at(&d, &t);
            assert_eq!(got.blocks, blocks_at(&d, &t), "{} values", y.len());
            assert_eq!(got.blocks.len(), blocks);
            assert!(
                matches!(got.path, Path::Certified { exact: 1, decisions } if decisions >= y.len() - 1),
                "{:?}",
                got.path
            );
        }
    }
}
