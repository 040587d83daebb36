//! An exact figure, or the square root of one, rounded for reading: a
//! decimal with a few significant digits and the nearest `f64`, both
//! correctly rounded (round half to even) from the exact value with integer
//! arithmetic only — no `f64` on the path.
//!
//! The figures of `sticky compare` are rationals, except the `L²` errors,
//! which are square roots of rationals (their squares are exact): every
//! function here takes a [`Value`], a rational or the root of a rational.

use num_bigint::{BigInt, BigUint};
use num_integer::Integer;
use num_rational::BigRational;
use num_traits::{Signed, Zero};

/// A value given exactly: a rational `q`, or `√q` for a rational `q ≥ 0`.
#[derive(Debug, Clone, Copy)]
pub enum Value<'a> {
    /// The rational itself.
    Rational(&'a BigRational),
    /// Its square root (`q ≥ 0`).
    SquareRoot(&'a BigRational),
}

impl Value<'_> {
    fn radicand(&self) -> &BigRational {
        match self {
            Value::Rational(q) | Value::SquareRoot(q) => q,
        }
    }

    fn is_negative(&self) -> bool {
        matches!(self, Value::Rational(q) if q.is_negative())
    }

    /// `⌊|v| · 2^k⌋` (or `⌊|v| · 10^k⌋` with `base = 10`) and whether the
    /// product is not that integer exactly (a remainder was dropped).
    fn scaled_floor(&self, base: u32, k: i64) -> (BigUint, bool) {
        let q = self.radicand().abs();
        let root = matches!(self, Value::SquareRoot(_));
        // √q · b^k = √(q · b^(2k)).
        let kk = if root { 2 * k } else { k };
        let s = kk.unsigned_abs();
        let (n, d) = match (base, kk >= 0) {
            // Powers of two are shifts.
            (2, true) => (q.numer() << s, q.denom().clone()),
            (2, false) => (q.numer().clone(), q.denom() << s),
            (_, up) => {
                let p = num_traits::pow(BigInt::from(base), s as usize);
                if up {
                    (q.numer() * p, q.denom().clone())
                } else {
                    (q.numer().clone(), q.denom() * p)
                }
            }
        };
        let (f, r) = n.div_rem(&d);
        let f = f.to_biguint().unwrap_or_default();
        if root {
            let s = f.sqrt();
            let inexact = !Zero::is_zero(&r) || &s * &s != f;
            (s, inexact)
        } else {
            (f, !Zero::is_zero(&r))
        }
    }

    /// `|v| · b^k` compared with `(m + 1/2)`: `Less`, `Equal` or `Greater`.
    fn cmp_half(&self, base: u32, k: i64, m: &BigUint) -> std::cmp::Ordering {
        let q = self.radicand().abs();
        let root = matches!(self, Value::SquareRoot(_));
        let kk = if root { 2 * k } else { k };
        let p = BigRational::from_integer(num_traits::pow(
            BigInt::from(base),
            kk.unsigned_abs() as usize,
        ));
        let scaled = if kk >= 0 { q * p } else { q / p };
        let half = BigRational::new(BigInt::from(2u32) * BigInt::from(m.clone()) + 1, 2.into());
        if root {
            scaled.cmp(&(&half * &half))
        } else {
            scaled.cmp(&half)
        }
    }

    /// `⌊log_base |v|⌋` for `v ≠ 0`.
    fn floor_log(&self, base: u32) -> i64 {
        let q = self.radicand().abs();
        let bits = q.numer().bits() as i64 - q.denom().bits() as i64;
        // An estimate from the bit lengths (off by at most a few; log10(2) ≈
        // 0.30103), then corrected exactly: 1 ≤ |v| · base^(−e) < base.
        let mut e = if base == 10 {
            (bits * 30_103).div_euclid(100_000)
        } else {
            bits
        };
        if matches!(self, Value::SquareRoot(_)) {
            e = e.div_euclid(2);
        }
        loop {
            let (m, _) = self.scaled_floor(base, -e);
            if m.is_zero() {
                e -= 1;
            } else if m >= BigUint::from(base) {
                e += 1;
            } else {
                return e;
            }
        }
    }
}

/// The value in scientific notation with `digits ≥ 1` significant digits,
/// correctly rounded (half to even), trailing zeros kept: `1.000e-3`,
/// `-2.500e1`, `0` for zero.
pub fn scientific(v: Value<'_>, digits: u32) -> String {
    if v.radicand().is_zero() {
        return "0".into();
    }
    let digits = i64::from(digits.max(1));
    let mut e = v.floor_log(10);
    let k = digits - 1 - e;
    let (mut m, _) = v.scaled_floor(10, k);
    match v.cmp_half(10, k, &m) {
        std::cmp::Ordering::Greater => m += 1u32,
        std::cmp::Ordering::Equal if m.is_odd() => m += 1u32,
        _ => {}
    }
    let top = num_traits::pow(BigUint::from(10u32), digits as usize);
    if m >= top {
        m /= 10u32;
        e += 1;
    }
    let s = m.to_string();
    let (head, tail) = s.split_at(1);
    let sign = if v.is_negative() { "-" } else { "" };
    if tail.is_empty() {
        format!("{sign}{head}e{e}")
    } else {
        format!("{sign}{head}.{tail}e{e}")
    }
}

/// The `f64` nearest to the value (ties to even, subnormals included), or
/// `None` when it is beyond the largest double (it would round to infinity):
/// the one rounding step of [`crate::rational::nearest_double_of`].
pub fn nearest_f64(v: Value<'_>) -> Option<f64> {
    if v.radicand().is_zero() {
        return Some(0.0);
    }
    if let Value::Rational(q) = v {
        // The exponent from the bit lengths, no search.
        return crate::rational::nearest_f64(q);
    }
    crate::rational::nearest_double_of(v.floor_log(2), v.is_negative(), |k| v.scaled_floor(2, k))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rational::ratio as q;
    use crate::scalar::Scalar;
    use num_traits::ToPrimitive;

    fn sci(n: i64, d: i64) -> String {
        scientific(Value::Rational(&q(n, d)), 4)
    }

    #[test]
    fn four_digits_correctly_rounded() {
        assert_eq!(sci(1, 1000), "1.000e-3");
        assert_eq!(sci(2, 3), "6.667e-1");
        assert_eq!(sci(-12345, 1), "-1.234e4"); // tie 1234.5 → even 1234
        assert_eq!(sci(-12355, 1), "-1.236e4"); // tie 1235.5 → even 1236
        assert_eq!(sci(99_995, 1), "1.000e5"); // tie → 10000 → carried
        assert_eq!(sci(99_994, 1), "9.999e4");
        assert_eq!(sci(0, 1), "0");
        assert_eq!(sci(1, 3), "3.333e-1");
        assert_eq!(
            scientific(Value::SquareRoot(&q(2, 1)), 4),
            "1.414e0" // √2 = 1.41421…
        );
        assert_eq!(scientific(Value::SquareRoot(&q(9, 4)), 4), "1.500e0");
        // √(1/3) = 0.57735…
        assert_eq!(scientific(Value::SquareRoot(&q(1, 3)), 4), "5.774e-1");
    }

    #[test]
    fn nearest_double_agrees_with_num_rational_and_sqrt() {
        // num-rational's conversion is correctly rounded; ours must agree.
        let mut seed = 0x2545_f491_4f6c_dd1du64;
        let mut next = || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            seed
        };
        for _ in 0..2000 {
            let n = (next() >> (next() % 63)) as i64 - (1 << 20);
            let d = (next() >> (next() % 63)).max(1) as i64 & i64::MAX;
            let d = d.max(1);
            let r = q(n, d);
            assert_eq!(nearest_f64(Value::Rational(&r)), r.to_f64(), "{n}/{d}");
        }
        // Every double is its own nearest double, subnormals included.
        for x in [5e-324, 1e-310, f64::MIN_POSITIVE, 0.1, -3.5, f64::MAX] {
            let r = x.to_big_rational().unwrap();
            assert_eq!(nearest_f64(Value::Rational(&r)), Some(x));
        }
        // √ of a perfect square of a double is that double.
        for x in [0.1f64, 3.0, 1e-200, 7e150] {
            let r = x.to_big_rational().unwrap();
            let sq = &r * &r;
            assert_eq!(nearest_f64(Value::SquareRoot(&sq)), Some(x));
        }
        // √2 is f64's own (correctly rounded) sqrt(2).
        assert_eq!(nearest_f64(Value::SquareRoot(&q(2, 1))), Some(2f64.sqrt()));
        // Beyond the range: None.
        let huge = BigRational::from_integer(BigInt::from(2u32).pow(1024u32));
        assert_eq!(nearest_f64(Value::Rational(&huge)), None);
    }
}
