//! `BigRational` arithmetic reduced by [`crate::gcd::gcd`].
//!
//! `num-rational`'s operators reduce every result with `num-bigint`'s
//! Stein gcd, one shift and one subtraction of the whole number per bit:
//! `O(bits · words)` even when the other operand is a single word (a
//! denominator of a few bits, or `1`). On data with big numerators and
//! small denominators (positions `i·10^4000`, velocities `i/(i+1)`) those
//! gcds were nine tenths of `sticky run` and `sticky events`. The
//! functions here give the same lowest-terms values (Knuth, TAOCP vol. 2,
//! §4.5.1: the gcds are taken on the denominators and on one word-sized
//! cofactor where possible) with [`crate::gcd::gcd`], which takes a
//! remainder by a word-sized operand first. [`crate::scalar::Scalar`]'s
//! `plus`/`minus`/`times`/`over` use them for `BigRational`.

use num_bigint::{BigInt, Sign};
use num_rational::BigRational;
use num_traits::{One, Signed, Zero};

use crate::gcd::gcd;

/// `gcd(|a|, |b|)` as a non-negative `BigInt`.
fn gcd_int(a: &BigInt, b: &BigInt) -> BigInt {
    BigInt::from_biguint(Sign::Plus, gcd(a.magnitude(), b.magnitude()))
}

/// `a / g` when `g` is not one (no division by one).
fn divided(a: &BigInt, g: &BigInt) -> BigInt {
    if g.is_one() {
        a.clone()
    } else {
        a / g
    }
}

/// `a + b` in lowest terms.
pub fn sum(a: &BigRational, b: &BigRational) -> BigRational {
    combine(a, b.numer(), b.denom())
}

/// `a − b` in lowest terms.
pub fn difference(a: &BigRational, b: &BigRational) -> BigRational {
    combine(a, &-b.numer(), b.denom())
}

/// `a + c/d` for `c/d` in lowest terms, `d > 0` (Knuth's addition: with
/// `g = gcd(b, d)`, `t = a·(d/g) + c·(b/g)`, the result is
/// `(t/h) / ((b/g)·(d/h))`, `h = gcd(t, g)`).
fn combine(a: &BigRational, c: &BigInt, d: &BigInt) -> BigRational {
    let (p, b) = (a.numer(), a.denom());
    if c.is_zero() {
        return a.clone();
    }
    if p.is_zero() {
        return BigRational::new_raw(c.clone(), d.clone());
    }
    if let Some(r) = combine_binary(p, b, c, d) {
        return r;
    }
    let g = gcd_int(b, d);
    if g.is_one() {
        return BigRational::new_raw(p * d + c * b, b * d);
    }
    let (bg, dg) = (b / &g, d / &g);
    let t = p * &dg + c * &bg;
    if t.is_zero() {
        return BigRational::zero();
    }
    let h = gcd_int(&t, &g);
    BigRational::new_raw(divided(&t, &h), bg * divided(d, &h))
}

/// `k` when `v > 0` is `2^k`.
fn power_of_two(v: &BigInt) -> Option<u64> {
    let z = v.trailing_zeros()?;
    (v.bits() == z + 1).then_some(z)
}

/// Knuth's addition `p/b + c/d` ([`combine`]) when `b` or `d` is a power
/// of two (a double's denominator, the dyadic path's): then
/// `g = gcd(b, d) = 2^{min(tz b, tz d)}` and `h = gcd(t, g)` are read off
/// the trailing zeros, and the divisions by them are shifts — no gcd, no
/// division. `None` when neither denominator is a power of two.
fn combine_binary(p: &BigInt, b: &BigInt, c: &BigInt, d: &BigInt) -> Option<BigRational> {
    let (zb, zd) = (b.trailing_zeros()?, d.trailing_zeros()?);
    power_of_two(b).or_else(|| power_of_two(d))?;
    let g = zb.min(zd);
    let (bg, dg) = (b >> g, d >> g);
    let t = p * &dg + c * &bg;
    let Some(zt) = t.trailing_zeros() else {
        return Some(BigRational::zero());
    };
    let h = zt.min(g);
    Some(BigRational::new_raw(t >> h, bg * (d >> h)))
}

/// `a · b` in lowest terms (the cross gcds `gcd(p, s)`, `gcd(r, q)` of
/// `p/q · r/s`).
pub fn product(a: &BigRational, b: &BigRational) -> BigRational {
    let (p, q, r, s) = (a.numer(), a.denom(), b.numer(), b.denom());
    if p.is_zero() || r.is_zero() {
        return BigRational::zero();
    }
    let g1 = gcd_int(p, s);
    let g2 = gcd_int(r, q);
    BigRational::new_raw(
        divided(p, &g1) * divided(r, &g2),
        divided(q, &g2) * divided(s, &g1),
    )
}

/// `a / b` in lowest terms; `b` must not be zero (as `BigRational`'s `/`,
/// which panics: the callers divide by a positive closing speed or size).
pub fn quotient(a: &BigRational, b: &BigRational) -> BigRational {
    debug_assert!(!b.is_zero());
    let (r, s) = (b.numer(), b.denom());
    let reciprocal = if r.is_negative() {
        BigRational::new_raw(-s, -r)
    } else {
        BigRational::new_raw(s.clone(), r.clone())
    };
    product(a, &reciprocal)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Deterministic big values (xorshift words, signs, small, `1`,
    /// power-of-two and `k 2^s` denominators, zeros, planted common factors): every operation equals
    /// `num-rational`'s, field by field (so the result is in lowest terms
    /// with a positive denominator).
    #[test]
    fn equals_num_rational() {
        let mut state = 0x2545_f491_4f6c_dd1du64;
        let mut next = move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state
        };
        let big = |words: u64, next: &mut dyn FnMut() -> u64| -> BigInt {
            let digits: Vec<u32> = (0..2 * words).map(|_| next() as u32).collect();
            BigInt::from_biguint(Sign::Plus, num_bigint::BigUint::from_slice(&digits))
        };
        let value = |k: u64, next: &mut dyn FnMut() -> u64| -> BigRational {
            let factor = BigInt::from(1 + next() % 60);
            let n = match k % 4 {
                0 => BigInt::zero(),
                1 => BigInt::from(next() % 1000) * &factor,
                _ => big(1 + next() % 12, next) * &factor,
            };
            let n = if next() % 2 == 0 { -n } else { n };
            // Powers of two (doubles) and odd multiples of them (the
            // dyadic path's `k 2^s`) take `combine_binary`.
            let d = match next() % 6 {
                0 => BigInt::one(),
                1 => BigInt::from(1 + next() % 40_000) * &factor,
                2 => BigInt::one() << (next() % 300),
                3 => BigInt::from(1 + next() % 40_000) << (next() % 300),
                _ => big(1 + next() % 6, next) + 1,
            };
            BigRational::new(n, d)
        };
        let same = |x: BigRational, y: BigRational, what: &str| {
            assert_eq!((x.numer(), x.denom()), (y.numer(), y.denom()), "{what}");
        };
        for k in 0..4000u64 {
            let a = value(k, &mut next);
            let b = value(k / 4 + next() % 3, &mut next);
            same(sum(&a, &b), &a + &b, &format!("{a} + {b}"));
            same(difference(&a, &b), &a - &b, &format!("{a} - {b}"));
            same(difference(&a, &a), BigRational::zero(), "a - a");
            same(sum(&a, &-&a), BigRational::zero(), "a + (-a)");
            same(product(&a, &b), &a * &b, &format!("{a} * {b}"));
            if !b.is_zero() {
                same(quotient(&a, &b), &a / &b, &format!("{a} / {b}"));
            }
        }
    }
}
