//! The state at `t` on `BigRational` data with one common denominator per
//! block: the projection formula of `prop:proj-micro` (`eq:proj-micro-x`,
//! `eq:proj-u-micro`, the multipliers of `eq:dyn-micro`) computed so that
//! data whose denominators are small one by one but large together (issue
//! 29: 20,000 velocities `(−1)^i/(i+1)`, a common denominator of 28,821
//! bits) cost a few big gcds per block instead of several per particle.
//!
//! The lexicographic PAVA is the one of [`crate::projection`] (the same
//! [`pools`] decision), but a block keeps its sums `Σ ỹ` and `Σ u⁰` as
//! numerators over the lcm of its members' denominators, never reduced:
//! adding one particle costs a remainder by its (small) denominator, not a
//! gcd of two big numbers. When the data share their denominators (the
//! lcm of the positions' and of the velocities' is at most
//! `COMMON_EXTRA_BITS` wider than the widest one: data scaled by one wide
//! factor), the free flight is computed over those common denominators,
//! numerators only, and the PAVA adds and compares numerators: no gcd
//! before the answers. The answers are then reduced once per block:
//!
//! - every position of a block is its mean `P/Q` (one gcd) plus `2r·i`; with
//!   `2r = a/b`, `x_i = (P b + a i Q)/(Q b)`, and since `gcd(P, Q) = 1` the
//!   common factor of that fraction divides `m = b·gcd(b, Q)` — a remainder
//!   by `m`, no big gcd (`m = 1` when `2r` is an integer);
//! - the velocity of a block is one reduced mean for all its particles;
//! - the multipliers of a block are `λ = (k A_m − m A_k)/(k N D)`
//!   ([`crate::contact::cluster_multiplier_numerators`]), `D` the block's
//!   common denominator, reduced by Lehmer's gcd ([`crate::gcd`]).
//!
//! The work is told to a [`Progress`] (one step per particle) and stops with
//! [`Error::Interrupted`] when it asks.

use std::cmp::Ordering;

use num_bigint::{BigInt, BigUint, Sign};
use num_integer::Integer;
use num_rational::BigRational;
use num_traits::{One, Zero};

use crate::cluster::Cluster;
use crate::error::Error;
use crate::gcd;
use crate::initial::InitialData;
use crate::progress::Progress;
use crate::projection::pools;
use crate::reduced;
use crate::state::State;

/// Steps (particles) between two polls of [`Progress::cancelled`] and two
/// reports of progress.
const POLL_STEPS: usize = 256;

/// A sum of fractions as `numer / denom`, not reduced: `denom` is the lcm
/// of the summands' denominators.
#[derive(Debug, Clone)]
struct Sum {
    numer: BigInt,
    denom: BigUint,
}

impl Sum {
    /// The sum of one fraction.
    fn of(q: &BigRational) -> Sum {
        Sum {
            numer: q.numer().clone(),
            denom: q.denom().magnitude().clone(),
        }
    }

    /// `self + other` over `lcm` of the denominators (`g` their gcd: a
    /// remainder by a word when one of them is small).
    fn add(self, other: &Sum) -> Sum {
        if self.denom == other.denom {
            // Over the data's common denominator (module documentation).
            return Sum {
                numer: self.numer + &other.numer,
                denom: self.denom,
            };
        }
        let g = gcd::gcd(&self.denom, &other.denom);
        let to_other = &other.denom / &g;
        let to_self = &self.denom / &g;
        let numer = self.numer * BigInt::from_biguint(Sign::Plus, to_other.clone())
            + &other.numer * BigInt::from_biguint(Sign::Plus, to_self);
        Sum {
            numer,
            denom: self.denom * to_other,
        }
    }

    /// The mean `self / k`, reduced.
    fn mean(&self, k: usize) -> BigRational {
        let d = BigInt::from_biguint(Sign::Plus, &self.denom * BigUint::from(k));
        gcd::ratio(self.numer.clone(), d)
    }
}

/// `Σ_a / k_a` against `Σ_b / k_b`, cross-multiplied (denominators are
/// positive): a product by a small number when one block is a single
/// particle.
fn cmp_means(a: &Sum, ka: usize, b: &Sum, kb: usize) -> Ordering {
    if a.denom == b.denom {
        let left = &a.numer * BigInt::from(kb);
        let right = &b.numer * BigInt::from(ka);
        return left.cmp(&right);
    }
    let left = &a.numer * BigInt::from_biguint(Sign::Plus, &b.denom * BigUint::from(kb));
    let right = &b.numer * BigInt::from_biguint(Sign::Plus, &a.denom * BigUint::from(ka));
    left.cmp(&right)
}

/// One pooled block: `size` particles from `first`, with the sums of the
/// translated free flight `ỹ` and of `u⁰` over it.
#[derive(Debug, Clone)]
struct Block {
    first: usize,
    size: usize,
    sum_y: Sum,
    sum_u: Sum,
}

/// Polls `progress` every [`POLL_STEPS`] steps: reports them done, and
/// stops the work when the watcher asked.
fn poll(progress: &dyn Progress, step: usize) -> Result<(), Error> {
    if step % POLL_STEPS == 0 && step > 0 {
        progress.advance(POLL_STEPS as u64);
        if progress.cancelled() {
            return Err(Error::Interrupted {
                during: "the state's computation",
            });
        }
    }
    Ok(())
}

/// The terms of the PAVA: the translated free flight `ỹ_i = x̃⁰_i + t u⁰_i`
/// (the values of [`crate::projection::shifted_free_flight`]) and the
/// velocities `u⁰_i`, each as a [`Sum`] of one term.
struct Flight {
    y: Vec<Sum>,
    u: Vec<Sum>,
}

/// The free flight at `t`, polling `progress`: over the data's common
/// denominators when they are small ([`common_denominator`]), else one
/// reduced fraction per particle ([`reduced_flight`]).
fn free_flight(
    data: &InitialData<BigRational>,
    two_r: &BigRational,
    t: &BigRational,
    progress: &dyn Progress,
) -> Result<Flight, Error> {
    let positions = data
        .positions()
        .iter()
        .chain(std::iter::once(two_r))
        .map(|x| x.denom().magnitude());
    let velocities = data.velocities().iter().map(|u| u.denom().magnitude());
    match (
        common_denominator(positions),
        common_denominator(velocities),
    ) {
        (Some(d), Some(e)) => common_flight(data, two_r, t, &d, &e, progress),
        _ => reduced_flight(data, t, progress),
    }
}

/// The lcm of `denoms` when it has at most [`COMMON_EXTRA_BITS`] more bits
/// than the largest of them (data scaled by one factor, or with a few
/// denominators); `None` when it grows past that (the hostile
/// denominators `1 … n`), found by a running lcm that stops there. A
/// denominator that divides the running lcm costs one remainder.
fn common_denominator<'a>(denoms: impl Iterator<Item = &'a BigUint> + Clone) -> Option<BigUint> {
    let widest = denoms.clone().map(BigUint::bits).max().unwrap_or(0);
    match gcd::running_lcm(&BigUint::one(), denoms, widest + COMMON_EXTRA_BITS) {
        gcd::RunningLcm::Exact(lcm) => Some(lcm),
        gcd::RunningLcm::Past(_) => None,
    }
}

/// How many bits the common denominator of [`common_denominator`] may have
/// beyond the widest single denominator.
const COMMON_EXTRA_BITS: u64 = 64;

/// `n/d` as a numerator over `common`, a multiple of `d`.
fn over(n: &BigInt, d: &BigUint, common: &BigUint) -> BigInt {
    if d == common {
        n.clone()
    } else {
        n * BigInt::from_biguint(Sign::Plus, common / d)
    }
}

/// The free flight over common denominators, no gcd at all: with the
/// positions and `2r` over `D`, the velocities over `E` and `t = p/q`,
/// `ỹ_i = (q E (X_i − A i) + p D U_i) / (q D E)` — every term of the PAVA
/// over one denominator, so that its additions and comparisons are of
/// numerators only.
fn common_flight(
    data: &InitialData<BigRational>,
    two_r: &BigRational,
    t: &BigRational,
    d: &BigUint,
    e: &BigUint,
    progress: &dyn Progress,
) -> Result<Flight, Error> {
    let q = t.denom().magnitude();
    let a = over(two_r.numer(), two_r.denom().magnitude(), d);
    let qe = BigInt::from_biguint(Sign::Plus, q * e);
    let pd = t.numer() * BigInt::from_biguint(Sign::Plus, d.clone());
    let denom = q * d * e;
    let n = data.n();
    let mut flight = Flight {
        y: Vec::with_capacity(n),
        u: Vec::with_capacity(n),
    };
    for (i, (x, u)) in data.positions().iter().zip(data.velocities()).enumerate() {
        poll(progress, i)?;
        let shifted = over(x.numer(), x.denom().magnitude(), d) - &a * BigInt::from(i);
        let velocity = over(u.numer(), u.denom().magnitude(), e);
        flight.y.push(Sum {
            numer: &qe * shifted + &pd * &velocity,
            denom: denom.clone(),
        });
        flight.u.push(Sum {
            numer: velocity,
            denom: e.clone(),
        });
    }
    Ok(flight)
}

/// The free flight one reduced fraction per particle (on hostile
/// denominators each term is a big reduction, and a long state must stop
/// on Ctrl-C here too).
fn reduced_flight(
    data: &InitialData<BigRational>,
    t: &BigRational,
    progress: &dyn Progress,
) -> Result<Flight, Error> {
    // `x̃⁰_i = x⁰_i − 2r i` term by term inside the polled loop (as
    // [`crate::initial::shift`] computes it): on hostile data the shift
    // alone is half a second of reductions.
    let two_r = data.two_r();
    let n = data.n();
    let mut offset = BigRational::zero();
    let mut flight = Flight {
        y: Vec::with_capacity(n),
        u: Vec::with_capacity(n),
    };
    for (i, (x, u)) in data.positions().iter().zip(data.velocities()).enumerate() {
        poll(progress, i)?;
        let shifted = reduced::difference(x, &offset);
        offset = reduced::sum(&offset, &two_r);
        flight
            .y
            .push(Sum::of(&reduced::sum(&shifted, &reduced::product(t, u))));
        flight.u.push(Sum::of(u));
    }
    Ok(flight)
}

/// `2r` in lowest terms without a gcd: `r = n/d` is, so `2n/d` is unless
/// `d` is even, and then `n/(d/2)` is.
fn double(r: &BigRational) -> BigRational {
    let (n, d) = (r.numer(), r.denom());
    if d.is_even() {
        BigRational::new_raw(n.clone(), d / 2)
    } else {
        BigRational::new_raw(n * 2, d.clone())
    }
}

/// The lexicographic PAVA on `(ỹ_i, u⁰_i)` (module documentation).
fn pava(flight: &Flight, progress: &dyn Progress) -> Result<Vec<Block>, Error> {
    let mut stack: Vec<Block> = Vec::new();
    // One particle can pool many blocks, each pooling a big addition: the
    // pools are polled too (without counting them as steps done).
    let mut pooled = 0usize;
    for (i, (yi, ui)) in flight.y.iter().zip(&flight.u).enumerate() {
        poll(progress, i)?;
        let mut cur = Block {
            first: i,
            size: 1,
            sum_y: yi.clone(),
            sum_u: ui.clone(),
        };
        while let Some(top) = stack.pop() {
            let joins = pools(
                cmp_means(&top.sum_y, top.size, &cur.sum_y, cur.size),
                || cmp_means(&top.sum_u, top.size, &cur.sum_u, cur.size),
            );
            if !joins {
                stack.push(top);
                break;
            }
            pooled += 1;
            if pooled % POLL_STEPS == 0 && progress.cancelled() {
                return Err(Error::Interrupted {
                    during: "the state's computation",
                });
            }
            cur = Block {
                first: top.first,
                size: top.size + cur.size,
                sum_y: top.sum_y.add(&cur.sum_y),
                sum_u: top.sum_u.add(&cur.sum_u),
            };
        }
        stack.push(cur);
    }
    Ok(stack)
}

/// `mean + 2r·i` for the particles `i` of a block, reduced without a big
/// gcd (module documentation): `mean = P/Q` and `2r = a/b` in lowest terms.
fn positions_of(
    mean: &BigRational,
    two_r: &BigRational,
    block: &Block,
    out: &mut Vec<BigRational>,
) {
    let (p, q) = (mean.numer(), mean.denom());
    let (a, b) = (two_r.numer(), two_r.denom());
    let denom = q * b;
    // Every common factor of `P b + a i Q` and `Q b` divides `m`.
    let m = BigInt::from_biguint(Sign::Plus, gcd::gcd(q.magnitude(), b.magnitude())) * b;
    let pb = p * b;
    let aq = a * q;
    for i in block.first..block.first + block.size {
        let numer = &pb + &aq * BigInt::from(i);
        let g = if m.is_one() {
            BigInt::one()
        } else {
            let r = numer.mod_floor(&m);
            BigInt::from_biguint(Sign::Plus, gcd::gcd(r.magnitude(), m.magnitude()))
        };
        let x = if g.is_one() {
            BigRational::new_raw(numer, denom.clone())
        } else {
            BigRational::new_raw(numer / &g, &denom / &g)
        };
        debug_assert!(gcd::gcd(x.numer().magnitude(), x.denom().magnitude()).is_one());
        out.push(x);
    }
}

/// The multipliers `λ` of the pairs inside a block (all but its last
/// particle; the pair that closes a block has `λ = 0`, pushed by the
/// caller): `(k A_m − m A_k)/(k N D)` with `u⁰_j = a_j / D` over the
/// block's common denominator `D` (`eq:dyn-micro`).
fn multipliers_of(
    u0: &[Sum],
    block: &Block,
    n: usize,
    progress: &dyn Progress,
    done: &mut usize,
    out: &mut Vec<BigRational>,
) -> Result<(), Error> {
    let d = &block.sum_u.denom;
    let k = BigInt::from(block.size);
    let total = &block.sum_u.numer;
    let denom = BigInt::from_biguint(Sign::Plus, d * BigUint::from(block.size) * BigUint::from(n));
    let mut prefix = BigInt::zero();
    let members = &u0[block.first..block.first + block.size];
    for (m, u) in members.iter().enumerate().take(block.size - 1) {
        poll(progress, *done)?;
        *done += 1;
        prefix += over(&u.numer, &u.denom, d);
        let numer = &k * &prefix - BigInt::from(m + 1) * total;
        out.push(gcd::ratio(numer, denom.clone()));
    }
    Ok(())
}

/// The state at time `t ≥ 0` by the projection formula, with one common
/// denominator per block (module documentation): the same [`State`] as
/// [`crate::projection::state_at`], which the oracle battery checks.
pub fn state_at(
    data: &InitialData<BigRational>,
    t: &BigRational,
    progress: &dyn Progress,
) -> Result<State<BigRational>, Error> {
    if t < &BigRational::zero() {
        return Err(Error::NegativeTime {
            t: crate::Scalar::render(t),
        });
    }
    let n = data.n();
    let two_r = double(data.radius());
    progress.stage("free flight", Some(n as u64));
    let flight = free_flight(data, &two_r, t, progress)?;
    progress.stage("projection", Some(n as u64));
    let blocks = pava(&flight, progress)?;
    progress.stage("positions, velocities, multipliers", Some(n as u64));
    let mut positions = Vec::with_capacity(n);
    let mut velocities = Vec::with_capacity(n);
    let mut multipliers = Vec::with_capacity(n.saturating_sub(1));
    let mut means: Vec<BigRational> = Vec::with_capacity(blocks.len());
    let mut done = 0;
    for block in &blocks {
        let mean = block.sum_y.mean(block.size);
        positions_of(&mean, &two_r, block, &mut positions);
        means.push(mean);
        velocities.extend(std::iter::repeat_n(
            block.sum_u.mean(block.size),
            block.size,
        ));
        multipliers_of(&flight.u, block, n, progress, &mut done, &mut multipliers)?;
        multipliers.push(BigRational::zero());
        done += 1;
    }
    // The pair closing the last block is not a pair.
    multipliers.pop();
    // Contact clusters: adjacent blocks with the same translated position
    // (at `t = 0` touching particles that separate are two blocks).
    let mut clusters: Vec<Cluster> = Vec::new();
    let mut previous: Option<&BigRational> = None;
    for (b, mean) in blocks.iter().zip(&means) {
        match clusters.last_mut() {
            Some(c) if previous == Some(mean) => c.size += b.size,
            _ => clusters.push(Cluster {
                first: b.first,
                size: b.size,
            }),
        }
        previous = Some(mean);
    }
    Ok(State {
        t: t.clone(),
        positions,
        velocities,
        multipliers,
        clusters,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::progress::Silent;

    fn q(n: i64, d: i64) -> BigRational {
        BigRational::new(n.into(), d.into())
    }

    /// The hostile shape of issue 29 at small N, and variations of its
    /// radius, against the generic projection at several times.
    #[test]
    fn equals_the_generic_projection() {
        for (n, radius) in [(1, q(1, 2)), (7, q(1, 2)), (40, q(1, 3)), (60, q(2, 7))] {
            let positions = (0..n).map(|i| q(3 * i, 1)).collect();
            let velocities = (0..n)
                .map(|i| q(if i % 2 == 0 { 1 } else { -1 }, i + 1))
                .collect();
            let data = InitialData::new(radius, positions, velocities).unwrap();
            for t in [q(0, 1), q(1, 3), q(100, 1), q(10_i64.pow(12), 1), q(7, 1)] {
                let want = crate::projection::state_at(&data, &t).unwrap();
                let got = state_at(&data, &t, &Silent).unwrap();
                assert_eq!(got, want, "n = {n}, t = {t}");
                lowest_terms(&got);
            }
        }
    }

    /// Data scaled by `3^-k` (wide denominators shared by every value, as
    /// the `kernels` fuzz target makes them) take the common-denominator
    /// free flight, the hostile denominators `1 … 60` the reduced one, and
    /// both answer the generic projection's states.
    #[test]
    fn common_denominators_when_shared() {
        let wide = BigRational::new(1.into(), num_traits::Pow::pow(BigInt::from(3), 200u32));
        let small = InitialData::new(
            q(1, 4),
            vec![q(0, 1), q(1, 1), q(2, 1), q(19, 6), q(5, 1)],
            vec![q(2, 1), q(1, 3), q(-1, 5), q(0, 1), q(-3, 7)],
        )
        .unwrap();
        let scaled = InitialData::new(
            small.radius() * &wide,
            small
                .positions()
                .iter()
                .map(|x| x * &wide + q(1, 3))
                .collect(),
            small.velocities().iter().map(|u| u * &wide).collect(),
        )
        .unwrap();
        let denoms = |v: &[BigRational]| {
            v.iter()
                .map(|x| x.denom().magnitude().clone())
                .collect::<Vec<_>>()
        };
        let shared = denoms(scaled.velocities());
        assert!(common_denominator(shared.iter()).is_some());
        let hostile = denoms(spread_denominators(60).velocities());
        assert!(common_denominator(hostile.iter()).is_none());
        for data in [&small, &scaled] {
            for t in [q(0, 1), q(1, 3), q(2, 1), q(7, 2), q(100, 1)] {
                let want = crate::projection::state_at(data, &t).unwrap();
                let got = state_at(data, &t, &Silent).unwrap();
                assert_eq!(got, want, "t = {t}");
                lowest_terms(&got);
            }
        }
    }

    /// Every value is in lowest terms with a positive denominator, as
    /// `BigRational::new` leaves it (equality of ratios compares values, so
    /// `assert_eq!` alone would let a fraction left unreduced through, and
    /// it would print unreduced).
    fn lowest_terms(s: &State<BigRational>) {
        for v in s
            .positions
            .iter()
            .chain(&s.velocities)
            .chain(&s.multipliers)
        {
            assert!(v.denom() > &BigInt::zero(), "{v}");
            assert!(
                gcd::gcd(v.numer().magnitude(), v.denom().magnitude()).is_one(),
                "{}/{} is not reduced",
                v.numer(),
                v.denom()
            );
        }
    }

    /// Touching particles that separate at `t = 0` are one contact cluster
    /// and two blocks.
    #[test]
    fn contact_at_zero() {
        let data =
            InitialData::new(q(1, 2), vec![q(0, 1), q(1, 1)], vec![q(0, 1), q(1, 1)]).unwrap();
        let s = state_at(&data, &q(0, 1), &Silent).unwrap();
        assert_eq!(s, crate::projection::state_at(&data, &q(0, 1)).unwrap());
        assert_eq!(s.clusters, vec![Cluster { first: 0, size: 2 }]);
    }

    /// `n` particles `x_i = 3i`, `r = 1/2`, `u_i = 1/(i + 1)`: the hostile
    /// scene's denominators 1 … n, without its alternating signs.
    fn spread_denominators(n: i64) -> InitialData<BigRational> {
        InitialData::new(
            q(1, 2),
            (0..n).map(|i| q(3 * i, 1)).collect(),
            (0..n).map(|i| q(1, i + 1)).collect(),
        )
        .unwrap()
    }

    /// A watcher that has asked to stop gets [`Error::Interrupted`].
    #[test]
    fn stops_when_cancelled() {
        struct Stop;
        impl Progress for Stop {
            fn cancelled(&self) -> bool {
                true
            }
        }
        let data = spread_denominators(3 * POLL_STEPS as i64);
        assert!(matches!(
            state_at(&data, &q(5, 1), &Stop),
            Err(Error::Interrupted { .. })
        ));
        assert!(state_at(&data, &q(-1, 1), &Silent).is_err());
    }

    /// The free flight polls too: a watcher that asks to stop at once
    /// stops the work before the PAVA's stage begins.
    #[test]
    fn stops_during_the_free_flight() {
        struct Stop(std::sync::Mutex<Vec<String>>);
        impl Progress for Stop {
            fn stage(&self, name: &str, _total: Option<u64>) {
                self.0.lock().unwrap().push(name.to_string());
            }
            fn cancelled(&self) -> bool {
                true
            }
        }
        let data = spread_denominators(3 * POLL_STEPS as i64);
        let stop = Stop(Default::default());
        assert!(matches!(
            state_at(&data, &q(5, 1), &stop),
            Err(Error::Interrupted { .. })
        ));
        assert_eq!(stop.0.lock().unwrap().as_slice(), ["free flight"]);
    }

    /// The pools are polled too: the last particle below all the others
    /// pools every block in one step, and a watcher that asks to stop only
    /// after the PAVA's two step polls is heard inside those pools.
    #[test]
    fn stops_inside_the_pools_of_one_step() {
        struct Late {
            stage: std::sync::Mutex<String>,
            calls: std::sync::atomic::AtomicUsize,
        }
        impl Progress for Late {
            fn stage(&self, name: &str, _total: Option<u64>) {
                *self.stage.lock().unwrap() = name.to_string();
            }
            fn cancelled(&self) -> bool {
                if *self.stage.lock().unwrap() != "projection" {
                    return false;
                }
                let calls = self.calls.fetch_add(1, std::sync::atomic::Ordering::SeqCst);
                calls >= 2
            }
        }
        let n = 3 * POLL_STEPS as i64;
        let mut x: Vec<BigRational> = (0..n - 1).map(|i| q(3 * i, 1)).collect();
        x.push(q(3 * n, 1));
        let mut u = vec![q(0, 1); n as usize - 1];
        u.push(q(-1000 * n, 1));
        let data = InitialData::new(q(1, 2), x, u).unwrap();
        let late = Late {
            stage: Default::default(),
            calls: Default::default(),
        };
        assert!(matches!(
            state_at(&data, &q(1, 1), &late),
            Err(Error::Interrupted { .. })
        ));
        // Without the watcher the same state is one block.
        let s = state_at(&data, &q(1, 1), &Silent).unwrap();
        assert_eq!(s.clusters.len(), 1);
    }
}
