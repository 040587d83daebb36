//! The nearest double of `num · 2^exp / den` on machine words: one integer
//! division, no `BigInt`, correctly rounded (to nearest, ties to even),
//! subnormals and overflow included.
//!
//! The magnitude `|num|` is shifted left until its top bit is bit 127, so
//! that the quotient `q = ⌊|num| 2^s / den⌋` has at least 64 significant
//! bits (`den < 2^64`); the remainder is the sticky bit. The value is then
//! `(q + ρ) 2^(exp − s)` with `0 ≤ ρ < 1`, `ρ > 0` exactly when the
//! remainder is not zero, and rounding `q` at the double's last place with
//! `ρ` as sticky bit is rounding the exact value: the dropped part is
//! compared with half a unit of the last place, and it is exactly half only
//! when the dropped bits of `q` are `10…0` and `ρ = 0`.

/// The nearest double of `num · 2^exp / den` (round to nearest, ties to
/// even; `±∞` when the value rounds beyond the largest finite double, `0.0`
/// for `num = 0`). `den` must be positive.
pub fn nearest(num: i128, den: u64, exp: i64) -> f64 {
    debug_assert!(den > 0);
    if num == 0 {
        return 0.0;
    }
    let negative = num < 0;
    let a = num.unsigned_abs();
    let s = i64::from(a.leading_zeros());
    let a = a << s;
    // Division by a power of two is a shift of the exponent: no remainder.
    let (q, sticky, exp) = if den.is_power_of_two() {
        (a, false, exp - i64::from(den.trailing_zeros()))
    } else {
        let d = u128::from(den);
        (a / d, a % d != 0, exp)
    };
    let magnitude = round_scaled(q, sticky, exp - s);
    if negative {
        -magnitude
    } else {
        magnitude
    }
}

/// The nearest double of `(q + ρ) 2^e` with `q ≥ 2^63` and `0 ≤ ρ < 1`,
/// `sticky` telling `ρ > 0`.
fn round_scaled(q: u128, sticky: bool, e: i64) -> f64 {
    debug_assert!(q >= 1 << 63);
    let bits = 128 - i64::from(q.leading_zeros());
    // The value lies in [2^top, 2^(top+1)).
    let top = bits - 1 + e;
    if top > 1023 {
        return f64::INFINITY;
    }
    // The last place kept: 53 significant bits, or 2^-1074 for subnormals.
    let last = (top - 52).max(-1074);
    let drop = last - e;
    // `bits ≥ 64`: a normal value drops at least 11 bits; a subnormal may
    // drop all of them (then the kept part is 0).
    debug_assert!(drop >= 1);
    let (kept, round_up) = if drop > bits {
        // Below half of 2^-1074.
        (0u128, false)
    } else {
        let kept = if drop >= 128 { 0 } else { q >> drop };
        let rest = if drop >= 128 {
            q
        } else {
            q & ((1u128 << drop) - 1)
        };
        let half = 1u128 << (drop - 1);
        let up = rest > half || (rest == half && (sticky || kept & 1 == 1));
        (kept, up)
    };
    let m = kept + u128::from(round_up);
    // m ≤ 2^53: exact as a double; m 2^last is exact (or overflows to ∞
    // when it is 2^1024, the correct rounding there).
    debug_assert!(m <= 1 << 53);
    (m as f64) * pow2(last)
}

/// `2^e` as a double, for `−1074 ≤ e ≤ 1023`.
fn pow2(e: i64) -> f64 {
    debug_assert!((-1074..=1023).contains(&e));
    if e >= -1022 {
        f64::from_bits(((e + 1023) as u64) << 52)
    } else {
        f64::from_bits(1u64 << (e + 1074))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::SplitMix64;
    use num_bigint::BigInt;
    use num_rational::BigRational;
    use num_traits::{One, ToPrimitive};

    fn exact(num: i128, den: u64, exp: i64) -> BigRational {
        let two = BigRational::from_integer(BigInt::from(2));
        let scale = if exp >= 0 {
            num_traits::pow(two, exp as usize)
        } else {
            BigRational::one() / num_traits::pow(two, (-exp) as usize)
        };
        BigRational::new(BigInt::from(num), BigInt::from(den)) * scale
    }

    /// The oracle: the exactly checked nearest double of the rational
    /// ([`crate::rational::nearest_f64`]), `∞` where it is beyond range.
    fn oracle(num: i128, den: u64, exp: i64) -> f64 {
        let q = exact(num, den, exp);
        match crate::rational::nearest_f64(&q) {
            Some(f) => f,
            None => {
                let f = q.to_f64().unwrap_or(f64::NAN);
                assert!(f.is_infinite(), "{q}");
                f
            }
        }
    }

    fn check(num: i128, den: u64, exp: i64) {
        let got = nearest(num, den, exp);
        let want = oracle(num, den, exp);
        assert_eq!(
            got.to_bits(),
            want.to_bits(),
            "{num} 2^{exp} / {den}: {got:e} vs {want:e}"
        );
    }

    /// Random numerators, denominators and exponents of every size, the
    /// ranges of subnormals and of overflow included.
    #[test]
    fn agrees_with_the_exact_nearest_double() {
        let mut rng = SplitMix64::new(0x5eed);
        for _ in 0..20_000 {
            let nb = rng.next_u64() % 128;
            let num = (((u128::from(rng.next_u64()) << 64) | u128::from(rng.next_u64()))
                >> (128 - nb.max(1))) as i128;
            let num = if rng.next_u64() % 2 == 0 { num } else { -num };
            let db = rng.next_u64() % 64 + 1;
            let den = (rng.next_u64() >> (64 - db)).max(1);
            let exp = match rng.next_u64() % 4 {
                0 => (rng.next_u64() % 200) as i64 - 100,
                1 => -1074 - (rng.next_u64() % 130) as i64 + 64,
                2 => 1024 - (rng.next_u64() % 130) as i64,
                _ => (rng.next_u64() % 2400) as i64 - 1200,
            };
            check(num, den, exp);
        }
    }

    /// Exact midpoints between two doubles round to the even one, and one
    /// unit of the remainder more or less decides: the sticky bit counts.
    #[test]
    fn ties_go_to_even_and_the_remainder_breaks_them() {
        // (2^53 + 1) / 2^53 · 2 ... : midpoints between 1 + k 2^-52 and the
        // next double, written with a non-power-of-two denominator.
        for k in 0..50i128 {
            let mid = (1i128 << 53) + 2 * k + 1; // odd: a midpoint at scale 2^-53
            for den in [3u64, 5, 7, 1 << 20, 12_345] {
                let d = i128::from(den);
                check(mid * d, den, -53);
                check(mid * d + 1, den, -53);
                check(mid * d - 1, den, -53);
                check(-mid * d, den, -53);
                // Subnormal midpoints.
                check((2 * k + 1) * d, den, -1075);
                check((2 * k + 1) * d + 1, den, -1075);
            }
        }
        // A remainder below the quotient's last bit: the dropped bits of the
        // quotient are exactly 10…0 and only the sticky bit says the value
        // is above (or below) the midpoint.
        for d in [(1u64 << 63) - 25, 3 << 61 | 1, 1_000_000_007 << 32 | 5] {
            for k in 0..20i128 {
                let mid = (1i128 << 53) + 2 * k + 1;
                let base = (mid * i128::from(d)) << 9;
                for num in [base + 1, base - 1, base, -base - 1] {
                    check(num, d, -53 - 9);
                }
            }
        }
        assert_eq!(nearest(3, 2, -1075), f64::from_bits(1)); // 3/4 of the least
        assert_eq!(nearest(1, 2, -1074), 0.0); // half the least subnormal: even
        assert_eq!(nearest(1, 1, 1024), f64::INFINITY);
        assert_eq!(nearest(-1, 1, 1024), f64::NEG_INFINITY);
        assert_eq!(nearest(i128::MIN, 1, 0), -(2f64.powi(127)));
        assert_eq!(
            nearest(i128::MAX, u64::MAX, 0),
            oracle(i128::MAX, u64::MAX, 0)
        );
        assert_eq!(nearest(0, 7, 5), 0.0);
    }
}
