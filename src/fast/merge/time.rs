//! Candidate collision times `gap / closing` and their exact comparison
//! behind a certified `f64` filter ([`FILTER`]); the bracket `[lo, hi]`
//! that keys the queue.

use std::cmp::Ordering;

use crate::fast::int::MulSmall;
use crate::fast::wide::I256;

/// Relative margin of the float filter: `τ_a` and `τ_b` decide the order
/// alone when `τ_a < τ_b (1 − FILTER)` (or the reverse).
///
/// Why this is exact. Let `u = 2^-53`. `to_f64` converts an integer
/// `|v| < 2^127` with relative error at most `3u` (two correctly rounded
/// halves and one correctly rounded sum of same-sign terms; exactly
/// `|δ| ≤ (1+u)² − 1 + u < 3.1u`), the division adds one rounding, so
/// `τ = t (1+δ₁)(1+δ₃)/(1+δ₂)` with `|δ₁|, |δ₂| < 3.1u`, `|δ₃| ≤ u`, and
/// `t (1 − 8u) ≤ τ ≤ t (1 + 8u)` for `t = gap/closing ≥ 0` (`τ ≥ 2^-127`
/// when `t > 0`, far from the subnormal range; `τ = 0` iff `t = 0`). If
/// `τ_a < τ_b (1 − FILTER)` then
/// `t_a (1 − 8u) ≤ τ_a < τ_b (1 − FILTER) ≤ t_b (1 + 8u)(1 − FILTER)`, and
/// `(1 + 8u)(1 − FILTER) < 1 − 8u` because `16u ≈ 1.8·10⁻¹⁵ < FILTER (1 + 8u)`:
/// hence `t_a < t_b` exactly (the products `τ_b (1 − FILTER)` are themselves
/// rounded, by a relative `u` that the margin absorbs as well). When neither
/// strict inequality holds the exact cross-multiplication decides (equal
/// times always land there).
pub const FILTER: f64 = 1e-9;
pub(super) const KEEP: f64 = 1.0 - FILTER;

/// Compares `a·b` with `c·d` exactly.
pub(super) fn cmp_products(a: i128, b: i128, c: i128, d: i128) -> Ordering {
    if let (Some(p), Some(q)) = (a.mul_small(b), c.mul_small(d)) {
        return p.cmp(&q);
    }
    // |a b|, |c d| ≤ 2^254: exact on 256 bits.
    I256::product(a, b).cmp(&I256::product(c, d))
}

/// `v` as a double, within a relative `3.1 · 2^-53` (see [`FILTER`]): one
/// correctly rounded conversion when `|v| < 2^63`, else the two 64-bit
/// halves of `|v|` converted separately — no slow `i128 → f64` library
/// call.
#[inline]
pub(super) fn to_f64(v: i128) -> f64 {
    const TWO64: f64 = 18_446_744_073_709_551_616.0;
    let m = v.unsigned_abs();
    let f = match i64::try_from(m) {
        // One correctly rounded conversion.
        Ok(small) => small as f64,
        Err(_) => (m >> 64) as u64 as f64 * TWO64 + m as u64 as f64,
    };
    if v < 0 {
        -f
    } else {
        f
    }
}

/// A candidate time `gap / closing` (`closing > 0`) with its float
/// approximation (the common factor `D_u / D_x` left aside).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Time {
    pub(super) gap: i128,
    pub(super) closing: i128,
    pub(super) approx: f64,
}

impl Time {
    #[inline]
    pub(super) fn new(gap: i128, closing: i128) -> Self {
        Time {
            gap,
            closing,
            approx: to_f64(gap) / to_f64(closing),
        }
    }
    /// Exact comparison, through the float filter ([`FILTER`]).
    #[inline]
    pub(super) fn cmp(&self, other: &Time) -> Ordering {
        if self.approx < other.approx * KEEP {
            Ordering::Less
        } else if other.approx < self.approx * KEEP {
            Ordering::Greater
        } else {
            self.cmp_exact(other)
        }
    }
    /// `gap₁ / closing₁` against `gap₂ / closing₂` by cross-multiplication
    /// (both closings are positive).
    pub(super) fn cmp_exact(&self, other: &Time) -> Ordering {
        cmp_products(self.gap, other.closing, other.gap, self.closing)
    }
}

impl Time {
    /// A lower bound `lo ≤ t` and an upper bound `hi ≥ t` of the exact time
    /// (in the units of `gap / closing`), as doubles: `τ (1 ∓ 2^-40)`. With
    /// `τ ∈ [t (1 − 8u), t (1 + 8u)]` ([`FILTER`]) and one more rounding,
    /// `lo ≤ t (1 + 8u)(1 − 2^-40)(1 + u) < t` because `2^-40 > 10u`; `hi`
    /// likewise. Both are non-negative (`gap ≥ 0`), so their bit patterns
    /// order like their values.
    #[inline]
    pub(super) fn lo(&self) -> u64 {
        (self.approx.abs() * (1.0 - BRACKET)).to_bits() >> KEY_SHIFT
    }
    #[inline]
    pub(super) fn hi(&self) -> u64 {
        (self.approx.abs() * (1.0 + BRACKET)).to_bits() >> KEY_SHIFT
    }
}

/// Queue keys drop the last 12 bits of the doubles' patterns (monotone, and
/// far below the bracket's width of about `2^13` units in the last place):
/// fewer levels for the radix queue to sort.
pub(super) const KEY_SHIFT: u32 = 12;

/// Relative half-width of the bracket `[lo, hi]` around a candidate time.
pub(super) const BRACKET: f64 = 1.0 / (1u64 << 40) as f64;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::SplitMix64;
    use num_bigint::BigInt;
    use num_rational::BigRational;
    use num_traits::{One, Signed};

    #[test]
    fn products_compare_exactly() {
        let mut rng = SplitMix64::new(3);
        let edge = [0i128, 1, -1, i128::MAX, i128::MIN + 1, 1 << 64, -(1 << 100)];
        let mut values: Vec<i128> = edge.to_vec();
        for _ in 0..200 {
            let v = (i128::from(rng.next_u64()) << 64 | i128::from(rng.next_u64()))
                >> (rng.next_u64() % 127);
            values.push(if rng.next_u64() % 2 == 0 {
                v
            } else {
                v.wrapping_neg()
            });
        }
        for (&a, &b) in values.iter().zip(values.iter().skip(1)) {
            for (&c, &d) in values.iter().skip(2).zip(values.iter().skip(3)).take(50) {
                let exact = (BigInt::from(a) * b).cmp(&(BigInt::from(c) * d));
                assert_eq!(cmp_products(a, b, c, d), exact);
            }
        }
    }

    #[test]
    fn conversion_within_the_filter_bound() {
        let mut rng = SplitMix64::new(17);
        for _ in 0..2000 {
            // to_f64 within 3.1 u of the exact value.
            let big = (i128::from(rng.next_u64()) << 63) | i128::from(rng.next_u64());
            let big = big >> (rng.next_u64() % 126);
            let f = to_f64(big);
            let err = (BigRational::from_float(f).unwrap() - big_int(big)).abs()
                / big_int(big).abs().max(BigRational::one());
            assert!(
                err <= BigRational::new(BigInt::from(31), BigInt::from(10) << 53u32),
                "{big}"
            );
            assert_eq!(to_f64(-big), -f);
        }
        assert_eq!(to_f64(0), 0.0);
        assert_eq!(to_f64(i128::MAX), 2f64.powi(127));
    }

    fn big_int(v: i128) -> BigRational {
        BigRational::from_integer(BigInt::from(v))
    }

    #[test]
    fn float_filter_is_exact() {
        // 2^100 / 3 against (2^100 + 1) / 3 and against 2^101 / 6: the doubles
        // coincide, the exact comparison separates or equates them.
        let a = Time::new(1 << 100, 3);
        let b = Time::new((1 << 100) + 1, 3);
        let c = Time::new(1 << 101, 6);
        assert_eq!(a.approx, b.approx);
        assert_eq!(a.cmp(&b), Ordering::Less);
        assert_eq!(b.cmp(&a), Ordering::Greater);
        assert_eq!(a.cmp(&c), Ordering::Equal);
        assert_eq!(Time::new(0, 5).cmp(&Time::new(0, 7)), Ordering::Equal);
        assert_eq!(Time::new(0, 5).cmp(&Time::new(1, 1 << 120)), Ordering::Less);
        let mut rng = SplitMix64::new(9);
        for _ in 0..2000 {
            let g = |rng: &mut SplitMix64| i128::from(rng.next_u64() >> (rng.next_u64() % 64));
            let (g1, c1) = (g(&mut rng) << 60, g(&mut rng).max(1));
            let (g2, c2) = (g1 + (g(&mut rng) % 3 - 1), c1 + (g(&mut rng) % 2));
            let (x, y) = (Time::new(g1, c1), Time::new(g2, c2));
            let exact = (BigInt::from(g1) * c2).cmp(&(BigInt::from(g2) * c1));
            assert_eq!(x.cmp(&y), exact);
        }
    }
}
