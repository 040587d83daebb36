//! The nearest double of `num 2^e / d` with no division per value (a
//! certified filter: the answer is [`round::nearest`]'s, bit for bit).
//!
//! * When `|num| ≤ 2^53` and `d ≤ 2^53`, both are doubles exactly and the
//!   IEEE 754 division is correctly rounded: its quotient is the answer.
//! * Otherwise one multiplication by a reciprocal of `d` prepared once,
//!   whose error is bounded, decides the rounding except in a narrow band
//!   below each midpoint (ties included), where the exact division
//!   ([`round::nearest`]) answers.
//!
//! Multiplying by `2^e` is exact while the result stays a normal double;
//! subnormal and overflowing results go to the exact division too.
//!
//! **The bound.** Let `d` have `b` bits and `B = 2^{63+b}/d ∈ (2^63, 2^64]`,
//! `inv = min(⌊B⌋, 2^64 − 1)`, so `B − 1 ≤ inv ≤ B`. For `a > 0` with
//! `128 − z` bits, `A = a 2^{z−64} ∈ [2^63, 2^64)` and `top = ⌊A⌋`
//! (`A − 1 < top ≤ A`). The product `P = top · inv` then satisfies
//! `AB − A − B ≤ P ≤ AB`, and with `A, B ≤ 2^64`, `X − 2 ≤ P/2^64 ≤ X` for
//! `X = AB/2^64 = (a/d) 2^{z+b−65} ∈ (2^62, 2^64)`: the high word
//! `h = ⌊P/2^64⌋` has `X ∈ [h, h + 3)`.
//!
//! **The decision.** Write `h = K 2^D + g` with `K` the top 53 bits of `h`
//! (`D = bits(h) − 53 ∈ {9, 10, 11}`, `0 ≤ g < 2^D`, half `H = 2^{D−1}`) and
//! `X = h + θ`, `0 ≤ θ < 3`. If `g > H`, `X` is above the midpoint
//! `K 2^D + H` and below `(K + 1) 2^D + 2`: it rounds to `(K + 1) 2^D`
//! (past `(K + 1) 2^D` by less than 2, far under half a unit even when
//! that is a power of two). If `g + 3 ≤ H`, `K 2^D ≤ X < K 2^D + H`: it
//! rounds to `K 2^D`. Otherwise (`g` on `H` or within 2 below) the filter
//! does not decide. Then `(a/d) 2^e = X 2^{e + 65 − b − z}`.

use super::round;

/// A denominator `d > 0` prepared for many quotients.
#[derive(Debug, Clone, Copy)]
pub struct Denominator {
    /// `d`.
    d: u64,
    /// `d` as a double, when `d ≤ 2^53` (exactly); `None` otherwise.
    exact: Option<f64>,
    /// `min(⌊2^{63+b}/d⌋, 2^64 − 1)`, `b` the bits of `d`.
    inv: u64,
    /// `65 − b`: `a/d = X 2^{65 − b − z}` (module documentation).
    shift: i64,
}

impl Denominator {
    /// `d > 0`: one division.
    pub fn new(d: u64) -> Denominator {
        debug_assert!(d > 0);
        let b = 64 - d.leading_zeros();
        let inv = ((1u128 << (63 + b)) / u128::from(d)).min(u128::from(u64::MAX)) as u64;
        Denominator {
            d,
            exact: (d <= 1 << 53).then_some(d as f64),
            inv,
            shift: 65 - i64::from(b),
        }
    }
}

/// The nearest double of `num 2^e / d` (round to nearest, ties to even;
/// `±∞` beyond the largest finite double, `0.0` for `num = 0`): the value
/// of [`round::nearest`], with no division when the filter decides
/// (module documentation).
#[inline(always)]
pub fn nearest(num: i128, den: &Denominator, e: i64) -> f64 {
    match filtered(num, den, e) {
        Some(v) => v,
        None => round::nearest(num, den.d, e),
    }
}

/// [`nearest`] when the filter decides, `None` when it does not.
#[inline(always)]
fn filtered(num: i128, den: &Denominator, e: i64) -> Option<f64> {
    if num == 0 {
        return Some(0.0);
    }
    let a = num.unsigned_abs();
    let magnitude = match den.exact {
        Some(d) if a <= 1 << 53 => {
            // Both operands are doubles exactly: the division is correctly
            // rounded (IEEE 754); `a/d ∈ [2^−53, 2^53]` is normal.
            scaled((a as u64 as f64) / d, e)?
        }
        _ => by_reciprocal(a, den, e)?,
    };
    Some(if num < 0 { -magnitude } else { magnitude })
}

/// `q 2^e` for a positive normal double `q`, when it is a normal double
/// (then exactly); `None` otherwise.
#[inline]
fn scaled(q: f64, e: i64) -> Option<f64> {
    let bits = q.to_bits();
    let field = (bits >> 52) as i64;
    debug_assert!(q > 0.0 && (1..=2046).contains(&field));
    let moved = field.checked_add(e)?;
    if (1..=2046).contains(&moved) {
        Some(f64::from_bits(
            bits & ((1 << 52) - 1) | (moved as u64) << 52,
        ))
    } else {
        None
    }
}

/// The high word `h` of [`Denominator::inv`] times the top 64 bits of
/// `a > 0`, and `z`, the leading zeros of `a`: `X ∈ [h, h + 3)` (module
/// documentation).
#[inline]
fn estimate(a: u128, den: &Denominator) -> (u64, u32) {
    debug_assert!(a > 0);
    let z = a.leading_zeros();
    let top = ((a << z) >> 64) as u64;
    (((u128::from(top) * u128::from(den.inv)) >> 64) as u64, z)
}

/// The nearest double of `(a/d) 2^e` for `a > 0` when the filter decides
/// and the result is a normal double (module documentation).
#[inline]
fn by_reciprocal(a: u128, den: &Denominator, e: i64) -> Option<f64> {
    let (h, z) = estimate(a, den);
    // X > 2^62 and X < h + 3: h has 62 to 64 bits, D = bits(h) − 53.
    let drop = 11u32.wrapping_sub(h.leading_zeros());
    debug_assert!((9..=11).contains(&drop));
    let kept = h >> drop;
    let g = h & ((1 << drop) - 1);
    let half = 1u64 << (drop - 1);
    let up = g > half;
    if !up && g + 3 > half {
        return None;
    }
    // K 2^D 2^{e + shift − z} has its top bit at 52 + D + e + shift − z.
    let field = 1023 + 52 + i64::from(drop) + e + den.shift - i64::from(z);
    if !(1..=2046).contains(&field) {
        return None;
    }
    // kept ∈ [2^52, 2^53); a carry into 2^53 moves into the exponent field
    // (to ∞ past the largest double: the correct rounding there).
    let bits = ((field as u64) << 52) + (kept - (1 << 52)) + u64::from(up);
    Some(f64::from_bits(bits))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fast::dyadic::round::tests::{oracle, Quotient};
    use crate::generate::SplitMix64;
    use num_bigint::BigInt;

    fn check(num: i128, d: u64, e: i64) {
        let got = nearest(num, &Denominator::new(d), e);
        let want = oracle(num, d, e);
        assert_eq!(
            got.to_bits(),
            want.to_bits(),
            "{num} 2^{e} / {d}: {got:e} vs {want:e}"
        );
    }

    /// Random numerators and denominators of every size (each side of
    /// `2^53`: the IEEE division and the reciprocal), exponents
    /// in the normal range and past it (subnormals, overflow).
    #[test]
    fn agrees_with_the_exact_nearest_double() {
        let mut rng = SplitMix64::new(0x907);
        for _ in 0..40_000 {
            let q = Quotient::random(&mut rng);
            check(q.num, q.den, q.exp);
        }
    }

    /// Quotients on a midpoint, and one unit of the numerator either side
    /// of it: ties go to even, and the check tells the three apart (the
    /// estimate cannot: they round to the same double). At `M = 2^52` the
    /// midpoint below is a quarter unit closer.
    #[test]
    fn midpoints_are_decided_exactly() {
        let mut rng = SplitMix64::new(0x3ad);
        let mut ds = vec![
            1u64,
            3,
            5,
            7,
            12_345,
            (1 << 53) + 1,
            (1 << 63) - 25,
            u64::MAX,
        ];
        for _ in 0..200 {
            ds.push((rng.next_u64() >> (rng.next_u64() % 64)).max(1));
        }
        for &d in &ds {
            for j in 0..20u128 {
                // Odd multiples of 2^{E−1}: midpoints between two doubles
                // with M = 2^52 + j (and the ones just below 2^53).
                let mids = [
                    (1u128 << 53) + 2 * j + 1,
                    (1u128 << 54) - 2 * j - 1,
                    // (4M − 1) at M = 2^52: the midpoint below a binade.
                    (1u128 << 54) - 1,
                ];
                for (which, &mid) in mids.iter().enumerate() {
                    // `mid` in units of 2^{E−1} (2^{E−2} for the last),
                    // scaled up so that num stays an integer.
                    let shift = 8 + (rng.next_u64() % 8) as u32;
                    let Some(base) = (mid * u128::from(d)).checked_shl(shift) else {
                        continue;
                    };
                    if base >> 126 != 0 {
                        continue;
                    }
                    let unit = -i64::from(shift) - if which == 2 { 2 } else { 1 };
                    for num in [base, base + 1, base - 1] {
                        let num = num as i128;
                        for e in [unit, unit - 900, unit + 900, unit - 1000, unit - 1100] {
                            check(num, d, e);
                            check(-num, d, e);
                        }
                    }
                }
            }
        }
        // Ties beyond 2^53 are left to the exact division, which takes
        // the even double of the two.
        let tie = (((1i128 << 53) + 1) * 3) << 20;
        let den = Denominator::new(6);
        assert_eq!(filtered(tie, &den, -20), None);
        assert_eq!(nearest(tie, &den, -20), 2f64.powi(52));
        assert_eq!(nearest(tie + 1, &den, -20), 2f64.powi(52) + 1.0);
        let tie = (((1i128 << 53) + 3) * 7) << 20;
        let den = Denominator::new(14);
        assert_eq!(filtered(tie, &den, -20), None);
        assert_eq!(nearest(tie, &den, -20), 2f64.powi(52) + 2.0);
        // Below 2^53 the IEEE division breaks them.
        assert_eq!(nearest(3, &Denominator::new(2), 0), 1.5);
        assert_eq!(
            nearest(5, &Denominator::new(2), -1074),
            2.0 * 2f64.powi(-1074)
        );
    }

    /// `X ∈ [h, h + 3)` (module documentation), checked on big integers:
    /// `h d ≤ a 2^{z+b−65} < (h + 3) d`, for random numerators and
    /// denominators of every size, `d` a power of two (`inv` capped), `1`,
    /// `2^64 − 1`, `a` near `2^127` and below `2^64`.
    #[test]
    fn the_estimate_is_within_three_units() {
        let mut rng = SplitMix64::new(0xb0d);
        let mut ds = vec![1u64, 2, 3, 1 << 63, u64::MAX, (1 << 63) + 1, (1 << 53) + 1];
        for _ in 0..300 {
            ds.push((rng.next_u64() >> (rng.next_u64() % 64)).max(1));
            ds.push(1 << (rng.next_u64() % 64));
        }
        for &d in &ds {
            let den = Denominator::new(d);
            let b = i64::from(64 - d.leading_zeros());
            let mut nums = vec![
                1u128,
                u128::MAX >> 1,
                (1 << 127) - 3,
                1 << 64,
                (1 << 64) - 1,
            ];
            for _ in 0..40 {
                let a = (u128::from(rng.next_u64()) << 64 | u128::from(rng.next_u64()))
                    >> (1 + rng.next_u64() % 127);
                nums.push(a.max(1));
            }
            for a in nums {
                let (h, z) = estimate(a, &den);
                let s = i64::from(z) + b - 65;
                let (mut left, mut right) = (BigInt::from(a), BigInt::from(d));
                if s >= 0 {
                    left <<= s as usize;
                } else {
                    right <<= (-s) as usize;
                }
                // left / right = X.
                assert!(BigInt::from(h) * &right <= left, "h > X: {a} / {d}");
                assert!(
                    left < (BigInt::from(h) + 3) * &right,
                    "X ≥ h + 3: {a} / {d}"
                );
            }
        }
    }

    /// The filter decides nearly every quotient (it declines only in a
    /// band of width 3 of 2^9 or more below a midpoint), and what it
    /// decides is the nearest double.
    #[test]
    fn the_filter_decides_almost_always() {
        let mut rng = SplitMix64::new(0xf11);
        let (mut decided, total) = (0, 20_000);
        for _ in 0..total {
            let a = (u128::from(rng.next_u64()) << 64 | u128::from(rng.next_u64()))
                >> (1 + rng.next_u64() % 60);
            let d = (rng.next_u64() >> (rng.next_u64() % 64)).max(1);
            if let Some(v) = filtered(a as i128, &Denominator::new(d), -30) {
                decided += 1;
                assert_eq!(
                    v.to_bits(),
                    oracle(a as i128, d, -30).to_bits(),
                    "{a} / {d}"
                );
            }
        }
        assert!(decided * 100 > total * 99, "{decided} of {total}");
    }
}
