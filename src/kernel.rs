//! Exact PAVA on integers over a common denominator — the fast exact path.
//!
//! The generic [`crate::projection`] code on `BigRational` reduces a fraction
//! (a gcd) at every addition and comparison. Here the data are scaled once
//! to integers: with `x̃⁰_i = X_i / D_x`, `u⁰_i = U_i / D_u` and `t = p/q`,
//!
//! `ỹ_i = x̃⁰_i + t u⁰_i = Y_i / D_y`, `Y_i = q D_u X_i + p D_x U_i`,
//! `D_y = q D_x D_u`,
//!
//! and pool-adjacent-violators runs on the integer pairs `(Y_i, U_i)`: a block
//! is `(k, ΣY, ΣU)`, block means are compared by cross-multiplication
//! (`ΣY_a k_b` against `ΣY_b k_a`, then the same for `U` on ties — the
//! lexicographic order that gives the right derivative, see
//! [`crate::projection`]), with no gcd in the loop and one reduction per
//! block at the end.
//!
//! **Width.** Before the loop, `max|Y| · N²/4` and `max|U| · N²/4` are
//! compared with `2^126`: when both fit, every sum and cross product of the
//! run fits an `i128` (a block sum is at most `k max|Y|` and
//! `k_a k_b ≤ N²/4`), so the loop runs on `i128` without overflow checks.
//! Otherwise the same loop runs on `BigInt`. The result is identical either
//! way and equal to the generic `BigRational` path, which the tests use as
//! the oracle.

use num_bigint::{BigInt, Sign};
use num_integer::Integer;
use num_rational::BigRational;
use num_traits::{One, Signed, ToPrimitive, Zero};

use crate::cluster::{runs, Cluster};
use crate::error::Error;
use crate::initial::InitialData;
use crate::state::State;

/// The integer type the PAVA loop ran on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Width {
    /// 128-bit integers (the data fitted, see the module documentation).
    I128,
    /// Arbitrary-precision integers.
    Big,
}

/// Initial data on common denominators: `x̃⁰_i = x[i] / dx`,
/// `u⁰_i = u[i] / du` (`df:translat-x`).
#[derive(Debug, Clone)]
pub struct IntegerData {
    x: Vec<BigInt>,
    u: Vec<BigInt>,
    /// `x` and `u` as `i64`, when every value fits.
    small: Option<(Vec<i64>, Vec<i64>)>,
    dx: BigInt,
    du: BigInt,
    two_r: BigRational,
}

fn lcm_of<'a>(it: impl Iterator<Item = &'a BigRational>) -> BigInt {
    it.fold(BigInt::one(), |acc, q| acc.lcm(q.denom()))
}

fn scale(v: &[BigRational], d: &BigInt) -> Vec<BigInt> {
    v.iter().map(|q| q.numer() * (d / q.denom())).collect()
}

impl IntegerData {
    /// Scales the data once.
    pub fn new(data: &InitialData<BigRational>) -> Self {
        let shifted = data.shifted_positions();
        let dx = lcm_of(shifted.iter());
        let du = lcm_of(data.velocities().iter());
        let x = scale(&shifted, &dx);
        let u = scale(data.velocities(), &du);
        let small = x
            .iter()
            .map(ToPrimitive::to_i64)
            .collect::<Option<Vec<_>>>()
            .zip(
                u.iter()
                    .map(ToPrimitive::to_i64)
                    .collect::<Option<Vec<_>>>(),
            );
        IntegerData {
            x,
            u,
            small,
            dx,
            du,
            two_r: data.two_r(),
        }
    }
    /// N.
    pub fn n(&self) -> usize {
        self.x.len()
    }
}

/// The PAVA blocks at `t + ε`, exact: `mean_y` is the translated position
/// `x̃(t)` of the block, `mean_u` its velocity (right derivative).
#[derive(Debug, Clone, PartialEq)]
pub struct Blocks {
    /// The blocks, left to right.
    pub clusters: Vec<Cluster>,
    /// `x̃(t)` on each block, in lowest terms.
    pub mean_y: Vec<BigRational>,
    /// `u(t)` on each block, in lowest terms.
    pub mean_u: Vec<BigRational>,
    /// The integer width the loop ran on.
    pub width: Width,
}

/// The integer operations the loop needs.
trait Word: Clone + Ord {
    fn add(&self, o: &Self) -> Self;
    fn mul_k(&self, k: usize) -> Self;
}

impl Word for i128 {
    #[inline]
    fn add(&self, o: &Self) -> Self {
        self + o
    }
    #[inline]
    fn mul_k(&self, k: usize) -> Self {
        self * k as i128
    }
}

impl Word for BigInt {
    fn add(&self, o: &Self) -> Self {
        self + o
    }
    fn mul_k(&self, k: usize) -> Self {
        self * BigInt::from(k)
    }
}

/// PAVA on `(y_i, u_i)` pairs in lexicographic order; returns
/// `(first, size, Σy, Σu)` per block.
fn pava_words<W: Word>(y: &[W], u: &[W]) -> Vec<(usize, usize, W, W)> {
    let mut stack: Vec<(usize, usize, W, W)> = Vec::with_capacity(y.len());
    for i in 0..y.len() {
        let mut cur = (i, 1usize, y[i].clone(), u[i].clone());
        while let Some(top) = stack.last() {
            let a = top.2.mul_k(cur.1);
            let b = cur.2.mul_k(top.1);
            let pool = match a.cmp(&b) {
                std::cmp::Ordering::Greater => true,
                std::cmp::Ordering::Less => false,
                std::cmp::Ordering::Equal => top.3.mul_k(cur.1) >= cur.3.mul_k(top.1),
            };
            if !pool {
                break;
            }
            if let Some(top) = stack.pop() {
                cur = (top.0, top.1 + cur.1, top.2.add(&cur.2), top.3.add(&cur.3));
            }
        }
        stack.push(cur);
    }
    stack
}

/// `2^126 / (N²/4)`: the largest magnitude for which the `i128` loop cannot
/// overflow.
fn i128_limit(n: usize) -> BigInt {
    let quarter = (BigInt::from(n) * BigInt::from(n) / 4u32).max(BigInt::one());
    (BigInt::one() << 126u32) / quarter
}

fn fits(v: &[BigInt], limit: &BigInt) -> bool {
    v.iter().all(|x| x.magnitude() <= limit.magnitude())
}

fn to_i128(v: &[BigInt]) -> Vec<i128> {
    v.iter().map(|x| x.to_i128().unwrap_or(0)).collect()
}

/// `Y_i = qdu·X_i + pdx·U_i` in `i128` when the factors fit `i64` and no
/// product or sum overflows, with the largest `|Y_i|`.
fn small_y(d: &IntegerData, qdu: &BigInt, pdx: &BigInt) -> Option<(Vec<i128>, Vec<i128>, u128)> {
    let (xs, us) = d.small.as_ref()?;
    let (a, b) = (i128::from(qdu.to_i64()?), i128::from(pdx.to_i64()?));
    let mut y = Vec::with_capacity(xs.len());
    let mut max = 0u128;
    for (x, u) in xs.iter().zip(us) {
        // |a|, |x|, |b|, |u| < 2^63: each product < 2^126, the sum < 2^127.
        let v = a * i128::from(*x) + b * i128::from(*u);
        max = max.max(v.unsigned_abs());
        y.push(v);
    }
    let u = us.iter().map(|&v| i128::from(v)).collect();
    Some((y, u, max))
}

/// Exact PAVA at time `t` on the integer data (see the module docs).
pub fn blocks_at(d: &IntegerData, t: &BigRational) -> Blocks {
    let (p, q) = (t.numer(), t.denom());
    let qdu = q * &d.du;
    let pdx = p * &d.dx;
    let dy = &qdu * &d.dx;
    let limit = i128_limit(d.n());
    let limit_u = limit.to_u128().unwrap_or(u128::MAX);
    let fast = small_y(d, &qdu, &pdx)
        .filter(|(_, u, max)| *max <= limit_u && u.iter().all(|v| v.unsigned_abs() <= limit_u));
    let (dy_small, du_small) = (dy.to_i128(), d.du.to_i128());
    let mut out = Blocks {
        clusters: Vec::new(),
        mean_y: Vec::new(),
        mean_u: Vec::new(),
        width: Width::I128,
    };
    let mut push = |first: usize, size: usize, y: BigRational, u: BigRational| {
        out.clusters.push(Cluster { first, size });
        out.mean_y.push(y);
        out.mean_u.push(u);
    };
    // The i128 words: directly when the factors fit (`small_y`), else from
    // the BigInt values when those fit the no-overflow bound; otherwise the
    // BigInt values themselves (computed once).
    let words = match fast {
        Some((y, u, _)) => Ok((y, u)),
        None => {
            let y: Vec<BigInt> =
                d.x.iter()
                    .zip(&d.u)
                    .map(|(x, u)| &qdu * x + &pdx * u)
                    .collect();
            if fits(&y, &limit) && fits(&d.u, &limit) {
                Ok((to_i128(&y), to_i128(&d.u)))
            } else {
                Err(y)
            }
        }
    };
    match words {
        Ok((y, u)) => {
            for (first, size, sy, su) in pava_words(&y, &u) {
                push(
                    first,
                    size,
                    reduce_small(sy, &dy, dy_small, size),
                    reduce_small(su, &d.du, du_small, size),
                );
            }
        }
        Err(y) => {
            for (first, size, sy, su) in pava_words(&y, &d.u) {
                let k = BigInt::from(size);
                push(
                    first,
                    size,
                    BigRational::new(sy, &k * &dy),
                    BigRational::new(su, &k * &d.du),
                );
            }
            out.width = Width::Big;
        }
    }
    out
}

/// `s / (k d)` in lowest terms for an `i128` sum `s`: `i128` arithmetic and
/// a binary gcd when `k d` fits, `BigRational::new` otherwise.
fn reduce_small(s: i128, d: &BigInt, d_small: Option<i128>, k: usize) -> BigRational {
    if let Some(den) = d_small.and_then(|d| d.checked_mul(k as i128)) {
        if den > 0 {
            // `g` divides both exactly and `den / g > 0`: lowest terms.
            let g = gcd_u128(s.unsigned_abs(), den.unsigned_abs()) as i128;
            return BigRational::new_raw(BigInt::from(s / g), BigInt::from(den / g));
        }
    }
    BigRational::new(BigInt::from(s), d * BigInt::from(k))
}

/// Binary gcd (`gcd(0, b) = b`); `b > 0` here.
fn gcd_u128(mut a: u128, mut b: u128) -> u128 {
    if a == 0 {
        return b;
    }
    let shift = (a | b).trailing_zeros();
    a >>= a.trailing_zeros();
    loop {
        b >>= b.trailing_zeros();
        if a > b {
            std::mem::swap(&mut a, &mut b);
        }
        b -= a;
        if b == 0 {
            return a << shift;
        }
    }
}

/// The state at `t ≥ 0` from the integer kernel: equal, field by field, to
/// [`crate::projection::state_at`] on `BigRational` (the tests check it).
pub fn state_at(d: &IntegerData, t: &BigRational) -> Result<State<BigRational>, Error> {
    if t.is_negative() {
        return Err(Error::NegativeTime { t: t.to_string() });
    }
    let b = blocks_at(d, t);
    let n = d.n();
    let mut shifted = Vec::with_capacity(n);
    let mut positions = Vec::with_capacity(n);
    let mut velocities = Vec::with_capacity(n);
    let mut multipliers = Vec::with_capacity(n.saturating_sub(1));
    let big_n = BigInt::from(n);
    for (j, c) in b.clusters.iter().enumerate() {
        // λ_i = (1/N) Σ_{j ≤ i}(u⁰_j − u_j): zero at block ends, and inside a
        // block of size k with ΣU = S:
        // λ_i = (k Σ_{first..=i} U_j − (i − first + 1) S) / (k du N).
        let k = BigInt::from(c.size);
        let den = &k * &d.du * &big_n;
        let sum_u: BigInt = d.u[c.range()].iter().sum();
        let mut prefix = BigInt::zero();
        for (m, i) in c.range().enumerate() {
            shifted.push(b.mean_y[j].clone());
            // x_i = x̃ + 2r·i as one fraction (a single reduction).
            let (yn, yd) = (b.mean_y[j].numer(), b.mean_y[j].denom());
            let (rn, rd) = (d.two_r.numer(), d.two_r.denom());
            positions.push(BigRational::new(
                yn * rd + rn * yd * BigInt::from(i),
                yd * rd,
            ));
            velocities.push(b.mean_u[j].clone());
            prefix += &d.u[i];
            if i + 1 < n {
                let num = &k * &prefix - BigInt::from(m + 1) * &sum_u;
                multipliers.push(if num.sign() == Sign::NoSign {
                    BigRational::zero()
                } else {
                    BigRational::new(num, den.clone())
                });
            }
        }
    }
    let clusters = runs(n, |j| shifted[j] == shifted[j + 1]);
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
    use crate::generate::{initial_data, Limits, SplitMix64};
    use crate::projection;

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
            for t in crate::claims::micro::probe_times(&traj, Some(6)) {
                assert_eq!(
                    state_at(&d, &t).unwrap(),
                    projection::state_at(&data, &t).unwrap(),
                    "t = {t}"
                );
            }
        }
    }

    #[test]
    fn big_fallback_equals_i128() {
        // Numbers far beyond 2^126 force the BigInt loop.
        let huge = BigRational::from_integer(BigInt::one() << 140u32);
        let q = |n: i64, d: i64| BigRational::new(BigInt::from(n), BigInt::from(d));
        let data = InitialData::new(
            q(1, 2),
            vec![q(0, 1), q(3, 1), huge.clone(), huge.clone() + q(5, 1)],
            vec![q(1, 1), q(-1, 1), q(1, 3), q(-1, 7)],
        )
        .unwrap();
        let d = IntegerData::new(&data);
        for t in [q(0, 1), q(1, 1), q(5, 2), huge.clone()] {
            let b = blocks_at(&d, &t);
            assert_eq!(b.width, Width::Big);
            assert_eq!(
                state_at(&d, &t).unwrap(),
                projection::state_at(&data, &t).unwrap()
            );
        }
        let small =
            InitialData::new(q(1, 2), vec![q(0, 1), q(3, 1)], vec![q(1, 1), q(-1, 1)]).unwrap();
        assert_eq!(
            blocks_at(&IntegerData::new(&small), &q(2, 1)).width,
            Width::I128
        );
    }
}
