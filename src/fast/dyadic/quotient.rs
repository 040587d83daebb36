//! The nearest double of `num 2^e / d` without an integer division: a
//! floating-point estimate of the quotient, then an exact integer check
//! of it (a certified filter; the answer is the one [`round::nearest`]
//! gives, bit for bit).
//!
//! **Why it is correct.** For `x = a/d > 0` and a positive normal double
//! `c = M 2^E` (`2^52 ≤ M < 2^53`), `c` is the nearest double of `x` (ties
//! to even) exactly when `x` lies between the midpoints of `c` with its two
//! neighbours, `(2M − 1) 2^{E−1}` below (`(4M − 1) 2^{E−2}` when
//! `M = 2^52`: the double below has half the unit) and `(2M + 1) 2^{E−1}`
//! above, and, when `x` equals one of them, `M` is even. Multiplied by `d`
//! these are integer comparisons of `a 2^{2−E}` with `(4M ± 2) d` (or
//! `(4M − 1) d`), exact on `u128` (`4M + 2 < 2^55`, `d < 2^64`).
//!
//! * [`corrected`], the common case: the residual `Z = a 2^{2−E} − 4 M d`
//!   is `4d (x − c)/2^E`, so the nearest double is `j` units from `c` with
//!   `j` the nearest integer to `Z / 4d`, estimated in floating point and
//!   checked exactly (`|Z − 4dj| < 2d`); no branch but the rare ones.
//! * [`settle`], when that check fails or a binade's end is near: each
//!   candidate is compared with its two midpoints, and the neighbour on the
//!   side of `x` is tried next; after a few candidates the exact division
//!   ([`round::nearest`]) answers.
//!
//! The estimate only says where to start. When `a ≤ 2^53` and `d ≤ 2^53`
//! both are doubles exactly and IEEE 754 division is correctly rounded: its
//! quotient is the answer, with no check. Multiplying by `2^e` is exact
//! while the result stays a normal double; outside that range (subnormals,
//! overflow) the exact division answers.

use std::cmp::Ordering;

use super::round;

/// A denominator `d > 0` prepared for many quotients.
#[derive(Debug, Clone, Copy)]
pub struct Denominator {
    /// `d`.
    d: u64,
    /// `d` rounded to a double (exact when `d ≤ 2^53`).
    approx: f64,
    /// `d ≤ 2^53`: `approx` is `d` exactly.
    exact: bool,
    /// `1/d`, rounded (an estimate).
    inverse: f64,
    /// `1/(4d)`, rounded (an estimate).
    quarter_inverse: f64,
    /// `2d`.
    two_d: i128,
    /// `4d`.
    four_d: i128,
}

impl Denominator {
    /// `d > 0`.
    pub fn new(d: u64) -> Denominator {
        debug_assert!(d > 0);
        let approx = d as f64;
        Denominator {
            d,
            approx,
            exact: d <= 1 << 53,
            inverse: 1.0 / approx,
            quarter_inverse: 0.25 / approx,
            two_d: 2 * i128::from(d),
            four_d: 4 * i128::from(d),
        }
    }
}

/// The nearest double of `num 2^e / d` (round to nearest, ties to even;
/// `±∞` beyond the largest finite double, `0.0` for `num = 0`): the value
/// of [`round::nearest`], with floating-point arithmetic checked exactly
/// for the integer division.
#[inline]
pub fn nearest(num: i128, den: &Denominator, e: i64) -> f64 {
    if num == 0 {
        return 0.0;
    }
    let a = num.unsigned_abs();
    let q = if den.exact && a <= 1 << 53 {
        // Both operands are doubles exactly: the division is correctly
        // rounded (IEEE 754), and `x = a/d ∈ [2^−53, 2^53]` is normal.
        Some((a as u64 as f64) / den.approx)
    } else {
        corrected(a, den, approx(a) * den.inverse)
    };
    match q.and_then(|q| scaled(q, e)) {
        Some(v) => {
            if num < 0 {
                -v
            } else {
                v
            }
        }
        None => round::nearest(num, den.d, e),
    }
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
        Some(f64::from_bits(bits & FRACTION | (moved as u64) << 52))
    } else {
        None
    }
}

/// The fraction field of a double.
const FRACTION: u64 = (1 << 52) - 1;

/// The implicit bit of a normal double's significand.
const HIDDEN: u64 = 1 << 52;

/// A double near `a > 0` (within a relative `2^−53 + 2^−62`): its top
/// 63 bits, rounded, times a power of two (no unsigned conversion).
#[inline]
fn approx(a: u128) -> f64 {
    debug_assert!(a > 0);
    let lz = a.leading_zeros();
    let top = ((a << lz) >> 65) as i64;
    // 2^(65 − lz) ∈ [2^−62, 2^65]: a normal double, the product exact.
    (top as f64) * f64::from_bits(u64::from(1023 + 65 - lz) << 52)
}

/// `a` against `b 2^s`, exactly.
#[inline]
fn cmp_scaled(a: u128, b: u128, s: i64) -> Ordering {
    if s >= 0 {
        // a = h 2^s + l, 0 ≤ l < 2^s: h against b, then l against 0.
        let (h, l) = if s >= 128 {
            (0, a)
        } else {
            (a >> s, a & ((1u128 << s) - 1))
        };
        h.cmp(&b).then(l.cmp(&0))
    } else {
        // a 2^{−s} against b; a 2^{−s} ≥ 2^128 > b when it does not fit.
        let r = -s;
        if a == 0 {
            return b.cmp(&0).reverse();
        }
        if r >= 128 || i64::from(a.leading_zeros()) < r {
            return Ordering::Greater;
        }
        (a << r).cmp(&b)
    }
}

/// `2^52 + 2^51`: adding it and taking it away rounds a double below
/// `2^51` in magnitude to an integer (to nearest).
const ROUNDER: f64 = 6_755_399_441_055_744.0;

/// The nearest double of `a/d` for `a > 0` from the estimate `c`, a
/// positive normal double a few units from it (module documentation):
/// `c + j` units with `j` the nearest integer to `Z / 4d`, checked. For
/// `E > 2` the bits of `a` below `2^{E−2}` are a fraction `ε ∈ [0, 1)` of
/// `Z`: the exact residual is `R + ε` with `R = Z − 4dj` an integer, and
/// `−2d < R + ε < 2d` holds exactly when `R < 2d` and either `R > −2d` or
/// `R = −2d` with `ε > 0`. When `R + ε` equals `±2d` (a tie), `Z` does not
/// fit 64 bits, or `c + j` is not strictly inside `c`'s binade above its
/// first double (where the unit below changes), [`settle`] answers.
#[inline]
fn corrected(a: u128, den: &Denominator, c: f64) -> Option<f64> {
    let bits = c.to_bits();
    let field = (bits >> 52) as i64;
    debug_assert!((1..=2046).contains(&field));
    let m = (bits & FRACTION) | HIDDEN;
    // a 2^{2−E}, E = field − 1075.
    let t = 1077 - field;
    let (shifted, fraction) = if t >= 0 {
        // `a 2^t` must not wrap.
        if i64::from(a.leading_zeros()) <= t {
            return settle(a, den.d, c);
        }
        (a << t, false)
    } else if t > -128 {
        let r = -t;
        (a >> r, a & ((1u128 << r) - 1) != 0)
    } else {
        return settle(a, den.d, c);
    };
    // 4 M d < 2^119; Z exact when it fits 64 bits (checked).
    let z = shifted.wrapping_sub(u128::from(m << 2) * u128::from(den.d)) as i128;
    let Ok(z) = i64::try_from(z) else {
        return settle(a, den.d, c);
    };
    let j_estimate = (z as f64) * den.quarter_inverse;
    let j = ((j_estimate + ROUNDER) - ROUNDER) as i64;
    // |j| < 2^62, 4d < 2^66: the product is exact on i128.
    let rest = i128::from(z).wrapping_sub(i128::from(j).wrapping_mul(den.four_d));
    let inside = rest < den.two_d && (rest > -den.two_d || (rest == -den.two_d && fraction));
    let moved = (m as i64).wrapping_add(j);
    if inside && moved > HIDDEN as i64 && moved < 2 * HIDDEN as i64 {
        Some(f64::from_bits(bits.wrapping_add_signed(j)))
    } else {
        settle(a, den.d, c)
    }
}

/// The nearest double of `a/d` (`a > 0`), from the candidate `c`, a
/// positive normal double within a few units of it: each candidate is
/// checked against its two midpoints and, when `a/d` lies beyond one, its
/// neighbour on that side is tried; `None` after [`MOVES`] candidates.
#[inline]
fn settle(a: u128, d: u64, mut c: f64) -> Option<f64> {
    let d = u128::from(d);
    for _ in 0..MOVES {
        let bits = c.to_bits();
        let field = (bits >> 52) as i64;
        debug_assert!((1..=2046).contains(&field));
        // c = M 2^E, E = field − 1075; midpoints in units of 2^{E−2}.
        let m = (bits & FRACTION) | HIDDEN;
        let s = field - 1075 - 2;
        let even = m & 1 == 0;
        match cmp_scaled(a, u128::from(4 * m + 2) * d, s) {
            Ordering::Greater => {
                c = f64::from_bits(bits + 1);
                continue;
            }
            // On the upper midpoint: the even one of c and the next.
            Ordering::Equal => return Some(if even { c } else { f64::from_bits(bits + 1) }),
            Ordering::Less => {}
        }
        let below = if m == HIDDEN { 4 * m - 1 } else { 4 * m - 2 };
        return match cmp_scaled(a, u128::from(below) * d, s) {
            Ordering::Less => {
                c = f64::from_bits(bits - 1);
                continue;
            }
            Ordering::Equal => Some(if even { c } else { f64::from_bits(bits - 1) }),
            Ordering::Greater => Some(c),
        };
    }
    None
}

/// Candidates [`settle`] tries. The estimate of [`nearest`] is within
/// five units of `a/d`: relative errors `2^−53 + 2^−62` for `a`, `2^−53`
/// for `d`, for `1/d` and for the product.
const MOVES: usize = 8;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::SplitMix64;
    use num_bigint::BigInt;
    use num_rational::BigRational;
    use num_traits::{One, ToPrimitive};

    /// The exactly checked nearest double of `num 2^e / d`
    /// ([`crate::rational::nearest_f64`]), `±∞` beyond the range.
    fn oracle(num: i128, d: u64, e: i64) -> f64 {
        let two = BigRational::from_integer(BigInt::from(2));
        let scale = if e >= 0 {
            num_traits::pow(two, e as usize)
        } else {
            BigRational::one() / num_traits::pow(two, (-e) as usize)
        };
        let q = BigRational::new(BigInt::from(num), BigInt::from(d)) * scale;
        match crate::rational::nearest_f64(&q) {
            Some(f) => f,
            None => {
                let f = q.to_f64().unwrap_or(f64::NAN);
                assert!(f.is_infinite(), "{q}");
                f
            }
        }
    }

    fn check(num: i128, d: u64, e: i64) {
        let got = nearest(num, &Denominator::new(d), e);
        let want = oracle(num, d, e);
        assert_eq!(
            got.to_bits(),
            want.to_bits(),
            "{num} 2^{e} / {d}: {got:e} vs {want:e}"
        );
    }

    /// The nearest double of `a/d` by [`corrected`] from the estimate.
    fn decided(a: u128, d: u64) -> Option<f64> {
        let den = Denominator::new(d);
        corrected(a, &den, approx(a) * den.inverse)
    }

    /// Random numerators and denominators of every size (each side of
    /// `2^53`: the unchecked division and the checked estimate), exponents
    /// in the normal range and past it (subnormals, overflow).
    #[test]
    fn agrees_with_the_exact_nearest_double() {
        let mut rng = SplitMix64::new(0x907);
        for _ in 0..40_000 {
            let nb = rng.next_u64() % 128;
            let num = (((u128::from(rng.next_u64()) << 64) | u128::from(rng.next_u64()))
                >> (128 - nb.max(1))) as i128;
            let num = if rng.next_u64() % 2 == 0 { num } else { -num };
            let db = rng.next_u64() % 64 + 1;
            let d = (rng.next_u64() >> (64 - db)).max(1);
            let e = match rng.next_u64() % 4 {
                0 => (rng.next_u64() % 200) as i64 - 100,
                1 => -1074 - (rng.next_u64() % 130) as i64 + 64,
                2 => 1024 - (rng.next_u64() % 130) as i64,
                _ => (rng.next_u64() % 2400) as i64 - 1200,
            };
            check(num, d, e);
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
        // The values on a midpoint go to the even double of the two.
        assert_eq!(decided(3, 2), Some(1.5));
        let tie = ((1u128 << 53) + 1) * 3;
        assert_eq!(decided(tie, 6), Some(2f64.powi(52)));
        assert_eq!(decided(tie + 1, 6), Some(2f64.powi(52) + 1.0));
        let tie = ((1u128 << 53) + 3) * 7;
        assert_eq!(decided(tie, 14), Some(2f64.powi(52) + 2.0));
    }

    /// Estimates off by units: [`corrected`] and [`settle`] find the
    /// nearest double from any start within five units; from farther,
    /// `settle` finds it or gives up (then the exact division answers).
    #[test]
    fn a_wrong_estimate_is_corrected_or_declined() {
        let mut rng = SplitMix64::new(0xe57);
        let mut moved = 0;
        for case in 0..20_000 {
            let a = (u128::from(rng.next_u64()) << 64 | u128::from(rng.next_u64()))
                >> (1 + rng.next_u64() % 100);
            let a = a.max(1);
            let d = (rng.next_u64() >> (rng.next_u64() % 64)).max(1);
            // Every fourth case near a binade's end, where the unit changes.
            let a = if case % 4 == 0 {
                let p = 53 + rng.next_u64() % 60;
                match (1u128 << p).checked_mul(u128::from(d)) {
                    Some(edge) if edge >> 125 == 0 => {
                        // Within four units of 2^p (units of 2^{p−52} above, half
                        // that below), give or take a little.
                        let units = u128::from(rng.next_u64() % 8) << (p - 53);
                        edge + units * u128::from(d) - (u128::from(d) << (p - 51))
                            + u128::from(rng.next_u64() % 3)
                    }
                    _ => a,
                }
            } else {
                a
            };
            let den = Denominator::new(d);
            let want = oracle(a as i128, d, 0);
            let estimate = approx(a) * den.inverse;
            moved += usize::from(estimate.to_bits() != want.to_bits());
            assert_eq!(decided(a, d).map(f64::to_bits), Some(want.to_bits()));
            // Start from a double `off` units away.
            for off in [-9i64, -7, -5, -4, -3, -2, -1, 0, 1, 2, 3, 4, 5, 7, 9] {
                let start = f64::from_bits(want.to_bits().wrapping_add_signed(off));
                let settled = settle(a, d, start);
                assert!(
                    settled.is_none() || settled.map(f64::to_bits) == Some(want.to_bits()),
                    "{a} / {d} settled from {off} units"
                );
                if off.abs() <= 5 {
                    assert_eq!(settled.map(f64::to_bits), Some(want.to_bits()));
                    let got = corrected(a, &den, start);
                    assert_eq!(
                        got.map(f64::to_bits),
                        Some(want.to_bits()),
                        "{a} / {d} corrected from {off} units"
                    );
                }
            }
        }
        // The estimate itself is often a unit off: the correction is used.
        assert!(moved > 1_000, "{moved}");
    }
}
