//! Greatest common divisors of big integers, and fractions reduced with them.
//!
//! `num-bigint`'s `gcd` is Stein's binary algorithm: one shift and one
//! subtraction of the whole number per bit, `O(bits · words)`, which is
//! slow on the common denominators of hostile data (velocities `1/(i+1)`,
//! `i < 20,000`: `lcm(1, …, 20000)`, ~28,800 bits), and every
//! `BigRational::new` of an answer runs one. [`gcd`] here is Lehmer's
//! algorithm (Knuth, TAOCP vol. 2, §4.5.2, Algorithm L): the quotients of
//! Euclid's algorithm are found on the leading 63 bits, and applied to the
//! whole numbers once per ~30 bits of progress, with a remainder by a small
//! operand first when one operand fits a word. Same result, exactly (the
//! tests compare it with `num-bigint`'s on random values).

use num_bigint::{BigInt, BigUint, Sign};
use num_integer::Integer;
use num_rational::BigRational;
use num_traits::{One, ToPrimitive, Zero};

/// Below this many bits both numbers are handed to `num-bigint`'s own gcd
/// (on two or three words Stein's algorithm is as fast).
const SMALL_BITS: u64 = 192;

/// `gcd(a, b)` (non-negative; `gcd(0, 0) = 0`).
pub fn gcd(a: &BigUint, b: &BigUint) -> BigUint {
    // gcd(a, b) = gcd(odd(a), odd(b)) 2^min(tz(a), tz(b)): the powers of two
    // of the denominators of doubles and of dyadic answers come off at
    // once, and what is left is often a word (then one remainder).
    match (a.trailing_zeros(), b.trailing_zeros()) {
        (None, _) => b.clone(),
        (_, None) => a.clone(),
        (Some(0), Some(0)) => odd_gcd(a, b),
        (Some(za), Some(zb)) => odd_gcd(&(a >> za), &(b >> zb)) << za.min(zb),
    }
}

/// `gcd(a, b)` by Lehmer's algorithm (a remainder by a word first when an
/// operand fits one).
fn odd_gcd(a: &BigUint, b: &BigUint) -> BigUint {
    let (mut a, mut b) = if a >= b {
        (a.clone(), b.clone())
    } else {
        (b.clone(), a.clone())
    };
    // Invariant: a ≥ b ≥ 0 and gcd(a, b) is the answer.
    loop {
        debug_assert!(a >= b);
        if b.is_zero() {
            return a;
        }
        if let Some(small) = b.to_u64() {
            // One remainder by the word, then machine gcd.
            let r = (&a % small).to_u64().unwrap_or(0);
            return BigUint::from(r.gcd(&small));
        }
        if a.bits() <= SMALL_BITS {
            return a.gcd(&b);
        }
        match lehmer_step(&a, &b) {
            Some((na, nb)) => {
                a = na;
                b = nb;
            }
            None => {
                let r = &a % &b;
                a = b;
                b = r;
            }
        }
        if a < b {
            std::mem::swap(&mut a, &mut b);
        }
    }
}

/// One round of Lehmer's algorithm on `a ≥ b > 0`: the cofactors of the
/// Euclidean steps that the leading 63 bits decide, applied to `a` and `b`;
/// `None` when not even one step is decided (then a full division).
fn lehmer_step(a: &BigUint, b: &BigUint) -> Option<(BigUint, BigUint)> {
    let shift = a.bits().saturating_sub(63);
    let mut x = i128::from((a >> shift).to_u64()?);
    let mut y = i128::from((b >> shift).to_u64()?);
    // (x, y) = (A·â + B·b̂, C·â + D·b̂) on the leading parts; Knuth's test
    // keeps the quotient q exact for every completion of the low bits.
    let (mut ca, mut cb, mut cc, mut cd) = (1i128, 0i128, 0i128, 1i128);
    loop {
        if y + cc == 0 || y + cd == 0 {
            break;
        }
        let q = (x + ca) / (y + cc);
        if q != (x + cb) / (y + cd) {
            break;
        }
        (ca, cc) = (cc, ca - q * cc);
        (cb, cd) = (cd, cb - q * cd);
        (x, y) = (y, x - q * y);
    }
    if cb == 0 {
        return None;
    }
    let (a, b) = (
        BigInt::from_biguint(Sign::Plus, a.clone()),
        BigInt::from_biguint(Sign::Plus, b.clone()),
    );
    let na = &a * ca + &b * cb;
    let nb = &a * cc + &b * cd;
    debug_assert!(!na.is_negative_value() && !nb.is_negative_value());
    Some((na.into_parts().1, nb.into_parts().1))
}

/// Whether a `BigInt` is below zero (a name for the debug assertion).
trait NegativeValue {
    fn is_negative_value(&self) -> bool;
}

impl NegativeValue for BigInt {
    fn is_negative_value(&self) -> bool {
        self.sign() == Sign::Minus
    }
}

/// `n / d` in lowest terms with a positive denominator, reduced with
/// [`gcd`]: the same value as `BigRational::new(n, d)`, faster on big
/// operands. `d` must not be zero (the callers divide by a positive common
/// denominator times a cluster size).
pub fn ratio(n: BigInt, d: BigInt) -> BigRational {
    debug_assert!(!d.is_zero());
    let g = gcd(n.magnitude(), d.magnitude());
    let (mut n, mut d) = if g.is_one() {
        (n, d)
    } else {
        let g = BigInt::from_biguint(Sign::Plus, g);
        (n / &g, d / &g)
    };
    if d.sign() == Sign::Minus {
        n = -n;
        d = -d;
    }
    BigRational::new_raw(n, d)
}

/// `lcm(a, b)` for positive `a`, `b`, with [`gcd`].
pub fn lcm(a: &BigUint, b: &BigUint) -> BigUint {
    if a.is_zero() || b.is_zero() {
        return BigUint::zero();
    }
    a / gcd(a, b) * b
}

/// What a running lcm reached: the lcm itself, or the size past which it
/// stopped.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum RunningLcm {
    /// Every value was taken in: this is their lcm.
    Exact(BigUint),
    /// The running lcm passed the limit with this many bits; the lcm of all
    /// the values has at least as many.
    Past(u64),
}

/// Takes the positive denominator `d` into the running lcm `acc`: a `d`
/// that divides `acc` costs one remainder (a word remainder when it is
/// small), any other one a [`gcd`].
fn take_in(acc: &mut BigUint, d: &BigUint) {
    debug_assert!(!d.is_zero(), "a denominator is positive");
    if !(d.is_one() || d == acc || (&*acc % d).is_zero()) {
        *acc = lcm(acc, d);
    }
}

/// The lcm of `start` and `values` (positive denominators), taken in one at
/// a time (`take_in`). Stops as soon as the lcm has more than `limit`
/// bits, so that a hostile column (the denominators `1 … n`, whose lcm has
/// ~1.44·n bits) costs no more than the limit allows.
pub fn running_lcm<'a>(
    start: &BigUint,
    values: impl IntoIterator<Item = &'a BigUint>,
    limit: u64,
) -> RunningLcm {
    debug_assert!(!start.is_zero());
    let mut acc = start.clone();
    for d in values {
        take_in(&mut acc, d);
        if acc.bits() > limit {
            return RunningLcm::Past(acc.bits());
        }
    }
    RunningLcm::Exact(acc)
}

/// The lcm of `start` and `values`, with no limit (as [`running_lcm`]).
pub fn lcm_of<'a>(start: &BigUint, values: impl IntoIterator<Item = &'a BigUint>) -> BigUint {
    debug_assert!(!start.is_zero());
    let mut acc = start.clone();
    for d in values {
        take_in(&mut acc, d);
    }
    acc
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A deterministic stream of words (the crate's own generator), for
    /// random big values.
    struct Words(crate::generate::SplitMix64);

    impl Words {
        fn new(seed: u64) -> Words {
            Words(crate::generate::SplitMix64::new(seed))
        }
        fn next(&mut self) -> u64 {
            self.0.next_u64()
        }
        fn big(&mut self, words: usize) -> BigUint {
            BigUint::from_slice(
                &(0..2 * words)
                    .map(|_| self.next() as u32)
                    .collect::<Vec<_>>(),
            ) >> (self.next() % 64)
        }
    }

    /// Random sizes from one bit to 40 words, with a planted common factor
    /// (so that the gcd is big, not 1), a word-sized operand, equal
    /// operands and zeros: the same gcd as `num-bigint`'s.
    #[test]
    fn equals_the_binary_gcd() {
        let mut w = Words::new(0x9e37_79b9_7f4a_7c15);
        for k in 0..600 {
            let size = |w: &mut Words| 1 + (w.next() % 40) as usize;
            let (sa, sb, sg) = (size(&mut w), size(&mut w), size(&mut w) % 8);
            let g = w.big(sg) + 1u32;
            let mut a = w.big(sa) * &g;
            let b = match k % 5 {
                0 => BigUint::from(w.next()),
                1 => a.clone(),
                2 => BigUint::zero(),
                _ => w.big(sb) * &g,
            };
            if k % 7 == 0 {
                a = BigUint::zero();
            }
            assert_eq!(gcd(&a, &b), a.gcd(&b), "gcd({a}, {b})");
            assert_eq!(gcd(&b, &a), a.gcd(&b));
        }
        // Consecutive Fibonacci numbers: every quotient 1, the longest run.
        let (mut f, mut g) = (BigUint::one(), BigUint::one());
        for _ in 0..2000 {
            (f, g) = (g.clone(), f + g);
        }
        assert!(gcd(&f, &g).is_one());
    }

    /// One operand a power of two (the denominators of doubles), the other
    /// with planted powers of two, odd, or itself a power: the same gcd as
    /// `num-bigint`'s.
    #[test]
    fn powers_of_two_equal_the_binary_gcd() {
        let mut w = Words::new(0x2545_f491_4f6c_dd1d);
        for k in 0..600u64 {
            let p = BigUint::one() << (w.next() % 300);
            let other = match k % 4 {
                0 => (w.big(1 + (k % 9) as usize) | BigUint::one()) << (w.next() % 300),
                1 => w.big(1 + (k % 9) as usize) | BigUint::one(),
                2 => BigUint::one() << (w.next() % 300),
                _ => w.big(1 + (k % 9) as usize) + 1u32,
            };
            assert_eq!(gcd(&p, &other), p.gcd(&other), "gcd({p}, {other})");
            assert_eq!(gcd(&other, &p), p.gcd(&other));
        }
    }

    #[test]
    fn ratios_and_lcms_equal_num_rational() {
        let mut w = Words::new(12345);
        for k in 0..200 {
            let g: BigInt = BigInt::from(w.big(1 + k % 5)) + 1;
            let sign = BigInt::from(if k % 2 == 0 { 1 } else { -1 });
            let n: BigInt = BigInt::from(w.big(1 + k % 17)) * &g * sign;
            let d: BigInt = BigInt::from(w.big(1 + k % 13)) * &g + 1;
            let d = if k % 3 == 0 { -d } else { d };
            assert_eq!(ratio(n.clone(), d.clone()), BigRational::new(n, d));
            let (a, b) = (w.big(1 + k % 9) + 1u32, w.big(1 + k % 4) + 1u32);
            assert_eq!(lcm(&a, &b), a.lcm(&b));
        }
        assert_eq!(ratio(BigInt::zero(), BigInt::from(-5)), BigRational::zero());
    }

    /// The running lcm equals `num-integer`'s lcm folded over the values
    /// (divisors, repeats and ones among them), and stops exactly when the
    /// lcm passes the limit, with the bits it reached.
    #[test]
    fn running_lcm_equals_the_fold_and_stops_past_the_limit() {
        let mut w = Words::new(777);
        for k in 0..200 {
            let start = w.big(1 + k % 3) + 1u32;
            let values: Vec<BigUint> = (0..1 + k % 12)
                .map(|j| match j % 4 {
                    0 => BigUint::one(),
                    1 => start.clone(),
                    _ => w.big(1 + j % 3) + 1u32,
                })
                .collect();
            let fold = values.iter().fold(start.clone(), |a, d| a.lcm(d));
            assert_eq!(lcm_of(&start, &values), fold);
            let bits = fold.bits();
            assert_eq!(
                running_lcm(&start, &values, bits),
                RunningLcm::Exact(fold.clone())
            );
            if bits > start.bits() {
                match running_lcm(&start, &values, bits - 1) {
                    RunningLcm::Past(b) => assert!(b > bits - 1 && b <= bits),
                    RunningLcm::Exact(l) => panic!("{l} has {bits} bits > {}", bits - 1),
                }
            }
        }
        // The hostile column 1 … 2000 stops near its limit, not at its end.
        let hostile: Vec<BigUint> = (1u32..=2000).map(BigUint::from).collect();
        match running_lcm(&BigUint::one(), &hostile, 100) {
            RunningLcm::Past(b) => assert!((101..=112).contains(&b), "{b}"),
            RunningLcm::Exact(l) => panic!("lcm(1 … 2000) has {} bits", l.bits()),
        }
    }
}
