//! The initial data on common denominators: `x̃⁰_i = X_i / D_x`,
//! `u⁰_i = U_i / D_u` with integers `X_i`, `U_i` and `D_x`, `D_u` the least
//! common denominators of the translated positions (`df:translat-x`) and of
//! the velocities. Both fast exact engines start here: the integer PAVA
//! ([`crate::fast::kernel`]) and the integer event merge ([`crate::fast::merge`]).
//!
//! [`scale_words`] does it on machine words (a running lcm with a memo of
//! `lcm / d`, divisibility tests and exact divisions without a division
//! instruction), many times faster than through `BigInt`
//! (`docs/journal.md`). [`scale_big`] is the `BigInt` path, for data whose scaled
//! values do not fit `i128`.

use num_bigint::{BigInt, BigUint};
use num_rational::BigRational;
use num_traits::{One, ToPrimitive, Zero};

use crate::fast::int::{gcd, narrowed, MulSmall};
use crate::initial::InitialData;

/// The scaled data `x̃⁰_i = x[i] / dx`, `u⁰_i = u[i] / du`, with the range
/// of each column (found while scaling: the engines choose their word
/// widths from it without another pass).
#[derive(Debug, Clone)]
pub(crate) struct Scaled {
    pub(crate) x: Vec<i128>,
    pub(crate) u: Vec<i128>,
    pub(crate) dx: BigInt,
    pub(crate) du: BigInt,
    pub(crate) x_range: Range,
    pub(crate) u_range: Range,
}

impl Scaled {
    /// `M = max(max|X_i|, max|U_i|)`.
    pub(crate) fn max_abs(&self) -> u128 {
        self.x_range.max_abs().max(self.u_range.max_abs())
    }
}

/// The least and the greatest value of a column (`0, 0` when it is empty).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Range {
    pub(crate) lo: i128,
    pub(crate) hi: i128,
}

impl Range {
    /// The range of `v`, in one pass.
    pub(crate) fn of(v: &[i128]) -> Range {
        let mut r = Range::EMPTY;
        for &a in v {
            r.take(a);
        }
        r.or_zero()
    }
    pub(crate) const EMPTY: Range = Range {
        lo: i128::MAX,
        hi: i128::MIN,
    };
    #[inline]
    pub(crate) fn take(&mut self, a: i128) {
        self.lo = self.lo.min(a);
        self.hi = self.hi.max(a);
    }
    /// `0, 0` for a range that took no value.
    pub(crate) fn or_zero(self) -> Range {
        if self.lo > self.hi {
            Range { lo: 0, hi: 0 }
        } else {
            self
        }
    }
    /// `max |v|` over the column.
    pub(crate) fn max_abs(&self) -> u128 {
        self.lo.unsigned_abs().max(self.hi.unsigned_abs())
    }
    /// The column narrowed to `i64`, when every value fits: one pass with
    /// no test per value (the range was found while scaling).
    pub(crate) fn narrow(&self, v: &[i128]) -> Option<Vec<i64>> {
        let fits = i64::try_from(self.lo).is_ok() && i64::try_from(self.hi).is_ok();
        fits.then(|| v.iter().map(|&a| a as i64).collect())
    }
}

/// Numerator and denominator of a rational, when they fit.
fn small(q: &BigRational) -> Option<(i128, u128)> {
    Some((q.numer().to_i128()?, q.denom().to_u128()?))
}

/// Numerator and denominator of a rational, when they fit 64 bits: half the
/// memory of [`small`]'s pair, for a column the scaling reads twice.
pub(crate) fn small_word(q: &BigRational) -> Option<(i64, u64)> {
    Some((q.numer().to_i64()?, q.denom().to_u64()?))
}

/// `a / b` and `a % b`, on 64-bit words when both fit (`b > 0`).
#[inline]
pub(crate) fn div_rem(a: u128, b: u128) -> (u128, u128) {
    match (u64::try_from(a), u64::try_from(b)) {
        (Ok(a), Ok(b)) => (u128::from(a / b), u128::from(a % b)),
        _ => (a / b, a % b),
    }
}

/// Common denominators on machine words: the running `lcm` of the
/// denominators seen, with a small direct-mapped memo of `lcm / d` (random
/// data have few distinct denominators, and a division per particle would
/// cost more than the rest of the scaling).
#[derive(Clone)]
pub(crate) struct Denominators {
    pub(crate) lcm: u128,
    memo: [(u128, u128); 64],
}

impl Denominators {
    pub(crate) fn new() -> Self {
        Denominators {
            lcm: 1,
            memo: [(0, 0); 64],
        }
    }
    fn slot(d: u128) -> usize {
        ((d ^ (d >> 6) ^ (d >> 12)) & 63) as usize
    }
    /// Takes `d > 0` into the lcm; `None` on overflow.
    pub(crate) fn add(&mut self, d: u128) -> Option<()> {
        let h = Self::slot(d);
        if self.memo[h].0 == d {
            return Some(());
        }
        if div_rem(self.lcm, d).1 != 0 {
            self.lcm = (self.lcm / gcd(self.lcm, d)).checked_mul(d)?;
        }
        // A multiple of the lcm stays a multiple as it grows; the quotient
        // is filled in by `factor` once the lcm is final.
        self.memo[h] = (d, 0);
        Some(())
    }
    /// Freezes the lcm: forgets the memo (its quotients are recomputed).
    pub(crate) fn finish(&mut self) {
        self.memo = [(0, 0); 64];
    }
    /// `lcm / d` for a denominator taken in.
    pub(crate) fn factor(&mut self, d: u128) -> u128 {
        let h = Self::slot(d);
        if self.memo[h].0 != d {
            self.memo[h] = (d, div_rem(self.lcm, d).0);
        }
        self.memo[h].1
    }
}

/// "Does `g` divide `v`?" for a fixed `g > 0` without a division when `g`
/// and `v` fit 64 bits (Granlund and Montgomery): with `g = 2^z g_odd`,
/// `g | v` iff `2^z | v` and `(v / 2^z) · g_odd⁻¹ mod 2^64 ≤ ⌊(2^64 − 1) / g_odd⌋`
/// (multiplication by `g_odd⁻¹` maps the multiples of `g_odd` below `2^64`
/// one-to-one onto `0 ..= ⌊(2^64 − 1)/g_odd⌋`).
pub(crate) struct Divisibility {
    g: u128,
    small: Option<(u32, u64, u64)>,
}

impl Divisibility {
    pub(crate) fn new(g: u128) -> Self {
        let small = u64::try_from(g).ok().map(|g| {
            let shift = g.trailing_zeros();
            let odd = g >> shift;
            // Newton's iteration: 3 → 6 → … → 96 ≥ 64 correct low bits.
            let mut inverse = odd;
            for _ in 0..5 {
                inverse = inverse.wrapping_mul(2u64.wrapping_sub(odd.wrapping_mul(inverse)));
            }
            (shift, inverse, u64::MAX / odd)
        });
        Divisibility { g, small }
    }
    #[inline]
    pub(crate) fn divides(&self, v: u128) -> bool {
        match (self.small, u64::try_from(v)) {
            (Some((shift, inverse, limit)), Ok(v)) => {
                v.trailing_zeros() >= shift && (v >> shift).wrapping_mul(inverse) <= limit
            }
            _ => div_rem(v, self.g).1 == 0,
        }
    }
}

/// Division by a fixed `g > 0` of multiples of `g`, without a division
/// instruction: `v / g = (v / 2^z) · g_odd⁻¹ mod 2^128` for `g = 2^z g_odd`
/// (exact because `g_odd` divides `v / 2^z`, and `g_odd` is invertible
/// modulo `2^128`).
pub(crate) struct ExactDiv {
    shift: u32,
    inverse: u128,
}

impl ExactDiv {
    pub(crate) fn new(g: u128) -> Self {
        let shift = g.trailing_zeros();
        let odd = g >> shift;
        // Newton's iteration doubles the number of correct low bits; `odd`
        // is its own inverse modulo 8 (3 bits): 3 → 6 → … → 192 ≥ 128.
        let mut inverse = odd;
        for _ in 0..6 {
            inverse = inverse.wrapping_mul(2u128.wrapping_sub(odd.wrapping_mul(inverse)));
        }
        ExactDiv { shift, inverse }
    }
    /// `v / g` for a multiple `v` of `g`.
    #[inline]
    pub(crate) fn apply(&self, v: i128) -> i128 {
        let a = v.unsigned_abs() >> self.shift;
        // A multiple below 2^64 has its quotient below 2^64: the low word of
        // the product by the inverse's low word (the inverse mod 2^64), one
        // machine multiplication instead of a 128-bit product.
        let q = match u64::try_from(a) {
            Ok(a) => i128::from(a.wrapping_mul(self.inverse as u64)),
            Err(_) => a.wrapping_mul(self.inverse) as i128,
        };
        if v < 0 {
            -q
        } else {
            q
        }
    }
}

/// Scales on machine words: `None` when an intermediate value overflows.
/// Positions and velocities are read and scaled on two threads when there
/// are many ([`PARALLEL_MIN`]).
pub(crate) fn scale_words(data: &InitialData<BigRational>) -> Option<Scaled> {
    let two_r = small(&data.two_r())?;
    let (x, u) = both(
        Cores::from_size(data.n(), PARALLEL_MIN),
        || match narrowed(data.positions(), small_word) {
            Some(xs) => scale_positions(two_r, &xs),
            None => scale_positions(two_r, &narrowed(data.positions(), small)?),
        },
        || match narrowed(data.velocities(), small_word) {
            Some(us) => scale_velocities(&us),
            None => scale_velocities(&narrowed(data.velocities(), small)?),
        },
    );
    let ((x, dx, x_range), (u, du, u_range)) = (x?, u?);
    Some(Scaled {
        x,
        u,
        dx: BigInt::from(dx),
        du: BigInt::from(du),
        x_range,
        u_range,
    })
}

/// Above this many particles the two columns are scaled on two threads.
pub(crate) const PARALLEL_MIN: usize = 1 << 15;

/// How many cores a piece of work runs on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Cores {
    /// This thread alone.
    One,
    /// This thread and a second one.
    Two,
}

impl Cores {
    /// [`Cores::Two`] from `min` items of work on, [`Cores::One`] below.
    pub(crate) fn from_size(n: usize, min: usize) -> Cores {
        if n >= min {
            Cores::Two
        } else {
            Cores::One
        }
    }
}

/// `(a(), b())`, on two threads when `parallel`.
pub(crate) fn both<A: Send, B: Send>(
    cores: Cores,
    a: impl FnOnce() -> A + Send,
    b: impl FnOnce() -> B + Send,
) -> (A, B) {
    if cores == Cores::One {
        return (a(), b());
    }
    std::thread::scope(|s| {
        let second = s.spawn(b);
        let first = a();
        // A panic on the second thread is a panic of this call.
        let second = second
            .join()
            .unwrap_or_else(|e| std::panic::resume_unwind(e));
        (first, second)
    })
}

/// A rational as a (numerator, positive denominator) pair of machine words.
pub(crate) trait Pair: Copy {
    /// The pair, widened.
    fn wide(self) -> (i128, u128);
}

impl Pair for (i128, u128) {
    #[inline]
    fn wide(self) -> (i128, u128) {
        self
    }
}

impl Pair for (i64, u64) {
    #[inline]
    fn wide(self) -> (i128, u128) {
        (i128::from(self.0), u128::from(self.1))
    }
}

/// [`scale_words`] on the pairs `(p, d)` of `2r`, `x⁰` and `u⁰` (each
/// `p/d` with `d > 0`, in any terms): the streaming readers of
/// [`crate::fast::stream`] give their columns this way, with no `BigRational`.
pub(crate) fn scale_pairs<P: Pair>(two_r: (i128, u128), xs: &[P], us: &[P]) -> Option<Scaled> {
    let (x, dx, x_range) = scale_positions(two_r, xs)?;
    let (u, du, u_range) = scale_velocities(us)?;
    Some(Scaled {
        x,
        u,
        dx: BigInt::from(dx),
        du: BigInt::from(du),
        x_range,
        u_range,
    })
}

/// The translated positions `X_i` over their least common denominator
/// `D_x` (see [`scale_pairs`]), and their range.
fn scale_positions<P: Pair>(two_r: (i128, u128), xs: &[P]) -> Option<(Vec<i128>, u128, Range)> {
    let (rn, rd) = two_r;
    // D = lcm(denominators of x⁰, denominator of 2r).
    let mut den = Denominators::new();
    den.add(rd)?;
    for q in xs {
        den.add(q.wide().1)?;
    }
    den.finish();
    // X'_i = x⁰_i D − i (2r) D, then divided by the gcd g of D and every X'_i:
    // D / g is the least common denominator of the x̃⁰_i.
    let step = rn.checked_mul(i128::try_from(den.factor(rd)).ok()?)?;
    let mut x = Vec::with_capacity(xs.len());
    let mut range = Range::EMPTY;
    let mut offset = 0i128;
    let mut g = den.lcm;
    let mut test = Divisibility::new(g);
    for q in xs {
        let (p, d) = q.wide();
        let v = p
            .mul_small(i128::try_from(den.factor(d)).ok()?)?
            .checked_sub(offset)?;
        offset = offset.checked_add(step)?;
        if g != 1 && !test.divides(v.unsigned_abs()) {
            g = gcd(g, div_rem(v.unsigned_abs(), g).1);
            test = Divisibility::new(g);
        }
        range.take(v);
        x.push(v);
    }
    Some((divided(x, g), den.lcm / g, divided_range(range, g)))
}

/// The velocities `U_i` over their least common denominator `D_u` (the
/// gcd step too: pairs in any terms give the least common denominator),
/// and their range.
fn scale_velocities<P: Pair>(us: &[P]) -> Option<(Vec<i128>, u128, Range)> {
    let mut den = Denominators::new();
    for q in us {
        den.add(q.wide().1)?;
    }
    den.finish();
    let mut u = Vec::with_capacity(us.len());
    let mut range = Range::EMPTY;
    let mut g = den.lcm;
    let mut test = Divisibility::new(g);
    for q in us {
        let (p, d) = q.wide();
        let v = p.mul_small(i128::try_from(den.factor(d)).ok()?)?;
        if g != 1 && !test.divides(v.unsigned_abs()) {
            g = gcd(g, div_rem(v.unsigned_abs(), g).1);
            test = Divisibility::new(g);
        }
        range.take(v);
        u.push(v);
    }
    Some((divided(u, g), den.lcm / g, divided_range(range, g)))
}

/// Every value of `v` divided by `g > 0`, a common divisor of them all.
fn divided(mut v: Vec<i128>, g: u128) -> Vec<i128> {
    if g > 1 {
        let div = ExactDiv::new(g);
        for a in &mut v {
            *a = div.apply(*a);
        }
    }
    v
}

/// The range of a column divided by `g > 0`, a common divisor of its
/// values: the ends divided (exactly; dividing by `g > 0` keeps the order).
pub(crate) fn divided_range(r: Range, g: u128) -> Range {
    let r = r.or_zero();
    if g > 1 {
        let div = ExactDiv::new(g);
        Range {
            lo: div.apply(r.lo),
            hi: div.apply(r.hi),
        }
    } else {
        r
    }
}

/// The same scaling on `BigInt`, for any data.
pub(crate) fn scale_big(
    data: &InitialData<BigRational>,
) -> (Vec<BigInt>, Vec<BigInt>, BigInt, BigInt) {
    let lcm = |v: &[BigRational]| {
        BigInt::from(crate::gcd::lcm_of(
            &BigUint::from(1u32),
            v.iter().map(|q| q.denom().magnitude()),
        ))
    };
    let scale = |v: &[BigRational], d: &BigInt| -> Vec<BigInt> {
        v.iter().map(|q| q.numer() * (d / q.denom())).collect()
    };
    let (x, dx) = scale_shifted_big(data);
    let du = lcm(data.velocities());
    (x, scale(data.velocities(), &du), dx, du)
}

/// The translated positions `x_i − 2r·i` (`df:translat-x`) on their least
/// common denominator, without reducing one `BigRational` per particle: on
/// a common denominator `D` of the positions and of `r`, `x_i − 2r·i =
/// n_i / D` with integer `n_i`, and the lcm of the reduced denominators
/// `D / gcd(D, n_i)` is `D / g` with `g = gcd(D, n_0, …)`; the scaled
/// values are then `n_i / g`. Any common multiple `D` gives the same `g`
/// quotient, so `D` need not be the least.
fn scale_shifted_big(data: &InitialData<BigRational>) -> (Vec<BigInt>, BigInt) {
    let r = data.radius();
    let d = crate::gcd::lcm_of(
        r.denom().magnitude(),
        data.positions().iter().map(|q| q.denom().magnitude()),
    );
    let d = BigInt::from(d);
    let two_r = r.numer() * (&d / r.denom()) * 2u32;
    let mut offset = BigInt::zero();
    let n: Vec<BigInt> = data
        .positions()
        .iter()
        .map(|q| {
            let v = q.numer() * (&d / q.denom()) - &offset;
            offset += &two_r;
            v
        })
        .collect();
    let g = n.iter().fold(d.magnitude().clone(), |acc, v| {
        if acc.is_one() {
            acc
        } else {
            crate::gcd::gcd(&acc, v.magnitude())
        }
    });
    if g.is_one() {
        return (n, d);
    }
    let g = BigInt::from(g);
    let dx = &d / &g;
    (n.into_iter().map(|v| v / &g).collect(), dx)
}

/// The scaling in `i128` by whichever path applies; `None` when a scaled
/// value does not fit `i128`.
pub(crate) fn scale_i128(data: &InitialData<BigRational>) -> Option<Scaled> {
    scale_words(data).or_else(|| {
        let (x, u, dx, du) = scale_big(data);
        let (x, u) = (
            narrowed(&x, ToPrimitive::to_i128)?,
            narrowed(&u, ToPrimitive::to_i128)?,
        );
        Some(Scaled {
            x_range: Range::of(&x),
            u_range: Range::of(&u),
            x,
            u,
            dx,
            du,
        })
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::{initial_data, Limits, SplitMix64};
    use num_integer::Integer;
    use num_traits::{One, Zero};

    /// `s` is the data on their least common denominators: `x[i] / dx` are
    /// the translated positions, `u[i] / du` the velocities (`df:translat-x`),
    /// and no common factor is left (`gcd(dx, X_0, …) = 1`, the same for `du`).
    fn is_the_scaling(s: &Scaled, data: &InitialData<BigRational>) {
        let shifted = data.shifted_positions();
        for (col, d, want) in [
            (&s.x, &s.dx, &shifted[..]),
            (&s.u, &s.du, data.velocities()),
        ] {
            assert_eq!(col.len(), want.len());
            let mut g = d.clone();
            for (v, w) in col.iter().zip(want) {
                assert_eq!(&BigRational::new(BigInt::from(*v), d.clone()), w);
                g = g.gcd(&BigInt::from(*v));
            }
            assert!(g.is_one(), "common factor {g} left in {col:?} / {d}");
        }
        // The ranges found while scaling are the columns' ranges.
        let range = |v: &[i128]| match (v.iter().min(), v.iter().max()) {
            (Some(&lo), Some(&hi)) => Range { lo, hi },
            _ => Range { lo: 0, hi: 0 },
        };
        assert_eq!((s.x_range, s.u_range), (range(&s.x), range(&s.u)));
        assert_eq!(Range::of(&s.x), s.x_range);
        let m = s.x.iter().chain(&s.u).map(|v| v.unsigned_abs()).max();
        assert_eq!(s.max_abs(), m.unwrap_or(0));
    }

    /// Both scalings, the machine-word one and the `BigInt` one, give the
    /// least common denominators on random data: many denominators sharing
    /// a memo slot, contacts, large and tiny radii, and the same numbers
    /// given as pairs in any terms (the streaming readers' input).
    #[test]
    fn words_and_bigint_scale_to_the_least_common_denominators() {
        let mut rng = SplitMix64::new(23);
        let mut words = 0;
        for k in 0..300 {
            let max_den = [1, 8, 200, 1 << 20, u32::MAX][k % 5];
            let data = initial_data(
                &rng.bytes(80),
                Limits {
                    max_n: 1 + k % 25,
                    max_den,
                    max_speed: 1000,
                },
            );
            let lcm = |v: &[BigRational]| v.iter().fold(BigInt::one(), |l, q| l.lcm(q.denom()));
            let mut xs = data.positions().to_vec();
            xs.push(data.two_r());
            let Some(s) = scale_words(&data) else {
                // Refused only when a common denominator is far beyond
                // machine words (the numerators here are below 2^20).
                assert!(lcm(&xs).bits() > 100 || lcm(data.velocities()).bits() > 100);
                continue;
            };
            words += 1;
            is_the_scaling(&s, &data);
            assert_eq!(
                scale_i128(&data).map(|t| (t.x, t.u, t.dx, t.du)),
                Some((s.x.clone(), s.u.clone(), s.dx.clone(), s.du.clone()))
            );
            let (bx, bu, bdx, bdu) = scale_big(&data);
            let big = |v: &[i128]| v.iter().map(|&a| BigInt::from(a)).collect::<Vec<_>>();
            assert_eq!((big(&s.x), big(&s.u), &s.dx, &s.du), (bx, bu, &bdx, &bdu));
            // The same numbers as pairs in non-lowest terms, `(p m, d m)`.
            let m = 1 + i128::from(rng.next_u64() % 7);
            let pair = |q: &BigRational| {
                (
                    q.numer().to_i128().unwrap() * m,
                    q.denom().to_u128().unwrap() * m as u128,
                )
            };
            let xs: Vec<_> = data.positions().iter().map(pair).collect();
            let us: Vec<_> = data.velocities().iter().map(pair).collect();
            let p = scale_pairs(pair(&data.two_r()), &xs, &us).unwrap();
            assert_eq!(
                (p.x, p.u, p.dx, p.du),
                (s.x.clone(), s.u.clone(), s.dx.clone(), s.du.clone())
            );
            // And as 64-bit pairs, when they fit.
            let narrow = |v: &[(i128, u128)]| {
                v.iter()
                    .map(|&(p, d)| Some((i64::try_from(p).ok()?, u64::try_from(d).ok()?)))
                    .collect::<Option<Vec<_>>>()
            };
            if let (Some(xs), Some(us)) = (narrow(&xs), narrow(&us)) {
                let p = scale_pairs(pair(&data.two_r()), &xs, &us).unwrap();
                assert_eq!((p.x, p.u), (s.x, s.u));
            }
        }
        assert!(words > 250, "{words}");
    }

    /// Data whose common denominator overflows machine words: the word
    /// scaling refuses them, the `BigInt` one is still the scaling, and the
    /// `i128` scaling is given exactly when its values fit.
    #[test]
    fn overflow_is_refused_not_wrapped() {
        let q = |n: i128, d: u64| BigRational::new(BigInt::from(n), BigInt::from(d));
        // Five distinct primes near 2^31: their lcm is above 2^150.
        let primes = [
            2147483647u64,
            2147483629,
            2147483587,
            2147483579,
            2147483563,
        ];
        let positions: Vec<_> = (0..5).map(|i| q(3 * i as i128 + 1, primes[i])).collect();
        let positions: Vec<_> = positions
            .iter()
            .enumerate()
            .map(|(i, p)| p + q(4 * i as i128, 1))
            .collect();
        let data = InitialData::new(q(1, 2), positions, vec![q(0, 1); 5]).unwrap();
        assert!(scale_words(&data).is_none());
        assert!(scale_i128(&data).is_none());
        let (x, u, dx, du) = scale_big(&data);
        assert_eq!(
            dx,
            primes.iter().map(|&p| BigInt::from(p)).product::<BigInt>()
        );
        assert!(u.iter().all(Zero::is_zero) && du.is_one());
        for (v, w) in x.iter().zip(data.shifted_positions()) {
            assert_eq!(BigRational::new(v.clone(), dx.clone()), w);
        }
        // Denominators 2, 4, …, 2^60: the running lcm must stay the lcm
        // (2^60), not a multiple of it, or the word scaling overflows.
        let dyadic = InitialData::new(
            q(1, 2),
            (1..=60)
                .map(|i| q(i128::from(i) * 2, 1) + q(1, 1 << i))
                .collect(),
            (1..=60).map(|i| q(1, 1 << (60 - i))).collect(),
        )
        .unwrap();
        let s = scale_words(&dyadic).unwrap();
        is_the_scaling(&s, &dyadic);
        assert_eq!(
            (s.dx.clone(), s.du.clone()),
            (BigInt::from(1u64 << 60), BigInt::from(1u64 << 59))
        );
        // Three of them: the lcm is above 2^64 (the 128-bit divisions) and
        // every scaled value fits `i128`: the word scaling takes it.
        let three =
            InitialData::new(q(1, 2), data.positions()[..3].to_vec(), vec![q(0, 1); 3]).unwrap();
        let s = scale_words(&three).unwrap();
        is_the_scaling(&s, &three);
        assert_eq!(
            s.dx,
            primes[..3]
                .iter()
                .map(|&p| BigInt::from(p))
                .product::<BigInt>()
        );
        // Two of them: the lcm fits 64 bits, the word scaling takes it.
        let two = InitialData::new(
            q(1, 2),
            data.positions()[..2].to_vec(),
            vec![q(1, 3), q(-1, 7)],
        )
        .unwrap();
        let s = scale_words(&two).unwrap();
        is_the_scaling(&s, &two);
        assert_eq!(s.du, BigInt::from(21));
        // Numerators beyond i128 on a small denominator: only `BigInt`.
        let huge = BigRational::from_integer(BigInt::from(1) << 130);
        let far = InitialData::new(q(1, 2), vec![q(0, 1), huge], vec![q(0, 1); 2]).unwrap();
        assert!(scale_words(&far).is_none() && scale_i128(&far).is_none());
    }

    /// The columns are scaled on two threads above [`PARALLEL_MIN`]
    /// particles: the same answer.
    #[test]
    fn two_threads_scale_the_same() {
        let n = 32_771;
        assert!(n >= PARALLEL_MIN);
        let q = |n: i64, d: i64| BigRational::new(n.into(), d.into());
        let positions = (0..n as i64)
            .map(|i| q(2 * i, 1) + q(1, 1 + i % 9))
            .collect();
        let velocities = (0..n as i64).map(|i| q(i % 13 - 6, 1 + i % 11)).collect();
        let data = InitialData::new(q(1, 2), positions, velocities).unwrap();
        let s = scale_words(&data).unwrap();
        assert_eq!(s.dx, BigInt::from(2520));
        assert_eq!(s.du, BigInt::from(27720));
        is_the_scaling(&s, &data);
    }

    /// A column narrows to `i64` only when both ends of its range fit.
    #[test]
    fn narrowing_needs_both_ends() {
        let (min, max) = (i128::from(i64::MIN), i128::from(i64::MAX));
        for (v, fits) in [
            (vec![min, 0, max], true),
            (vec![min - 1, 0, 5], false),
            (vec![-5, 0, max + 1], false),
            (vec![], true),
        ] {
            let r = Range::of(&v);
            let want = fits.then(|| v.iter().map(|&a| a as i64).collect::<Vec<_>>());
            assert_eq!(r.narrow(&v), want, "{v:?}");
        }
        assert_eq!(Range::of(&[min - 1, 3]).max_abs(), min.unsigned_abs() + 1);
    }

    #[test]
    fn exact_division_and_divisibility() {
        let mut rng = SplitMix64::new(17);
        for _ in 0..2000 {
            let g =
                u128::from(rng.next_u64() >> (rng.next_u64() % 64)).max(1) << (rng.next_u64() % 20);
            let k = i128::from(rng.next_u64() as i64 >> (rng.next_u64() % 64));
            let Some(v) = k.checked_mul(g as i128) else {
                continue;
            };
            assert_eq!(ExactDiv::new(g).apply(v), k, "{v} / {g}");
            let test = Divisibility::new(g);
            assert!(test.divides(v.unsigned_abs()), "{g} | {v}");
            let w = v.unsigned_abs() + 1 + u128::from(rng.next_u64() % 5);
            assert_eq!(test.divides(w), w % g == 0, "{g} | {w}?");
        }
    }
}
