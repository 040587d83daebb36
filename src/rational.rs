//! Exact reading and writing of rational numbers.
//!
//! Accepted text (docs/guide/scenes.md), always read exactly:
//!
//! * an integer: `"3"`, `"-12"`, `"+7"`;
//! * a fraction: `"-7/4"` (the denominator a positive integer, never zero);
//! * a decimal: `"0.125"`, `"-2.5"`;
//! * scientific form: `"1.5e-3"`, `"2E+4"` (exponent at most
//!   [`MAX_EXPONENT`] in absolute value, so that a hostile file cannot ask for
//!   a number with billions of digits);
//! * at most [`max_digits`] digits in all ([`MAX_DIGITS`] = 100,000 unless
//!   the environment variable `STICKY_MAX_DIGITS` says otherwise): a
//!   2,000,000-digit position is refused with a message naming the cap.
//!
//! Output is `"p/q"` in lowest terms with the sign on `p`, or `"p"` when
//! `q = 1`: the JSON contract of docs/guide/json.md.

use std::fmt;

use num_bigint::{BigInt, BigUint};
use num_integer::Integer;
use num_rational::BigRational;
use num_traits::{Pow, Signed, Zero};

/// Largest exponent magnitude accepted in scientific form.
pub const MAX_EXPONENT: u32 = 4096;

/// Why a piece of text is not an exact number.
#[derive(Debug, Clone, PartialEq, Eq)]
#[non_exhaustive]
pub enum NumberError {
    /// The text is empty (or only white space).
    Empty,
    /// The text is not an integer, fraction, decimal or scientific number.
    Malformed,
    /// A fraction with denominator zero.
    ZeroDenominator,
    /// A scientific exponent larger than [`MAX_EXPONENT`] in absolute value.
    ExponentTooLarge,
    /// More digits than the cap ([`max_digits`]).
    TooManyDigits {
        /// The digits of the text.
        digits: usize,
        /// The cap.
        cap: usize,
    },
}

impl fmt::Display for NumberError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            NumberError::Empty => write!(f, "empty number"),
            NumberError::Malformed => write!(
                f,
                "not an exact number (expected an integer, a fraction p/q, a decimal or scientific form such as 1.5e-3)"
            ),
            NumberError::ZeroDenominator => write!(f, "zero denominator"),
            NumberError::ExponentTooLarge => {
                write!(f, "exponent larger than {MAX_EXPONENT} in absolute value")
            }
            NumberError::TooManyDigits { digits, cap } => write!(
                f,
                "{digits} digits, more than the cap of {cap} digits per number (set the environment variable {DIGITS_VAR} to raise it)"
            ),
        }
    }
}

impl std::error::Error for NumberError {}

/// The default cap on the digits of one number ([`max_digits`]): text such
/// as a position with 2,000,000 digits is refused up front with a message
/// naming the cap, rather than stalling the exact arithmetic.
pub const MAX_DIGITS: usize = 100_000;

/// The environment variable that raises (or lowers) the digit cap.
pub const DIGITS_VAR: &str = "STICKY_MAX_DIGITS";

/// The cap on the digits of one number (numerator and denominator, or
/// integer and fractional parts, together): `$STICKY_MAX_DIGITS` when it is
/// set to a number, [`MAX_DIGITS`] otherwise. Read once per process.
pub fn max_digits() -> usize {
    static CAP: std::sync::OnceLock<usize> = std::sync::OnceLock::new();
    *CAP.get_or_init(|| {
        std::env::var(DIGITS_VAR)
            .ok()
            .and_then(|v| v.trim().parse().ok())
            .unwrap_or(MAX_DIGITS)
    })
}

fn is_digits(s: &str) -> bool {
    !s.is_empty() && s.bytes().all(|b| b.is_ascii_digit())
}

fn split_sign(s: &str) -> (bool, &str) {
    if let Some(rest) = s.strip_prefix('-') {
        (true, rest)
    } else if let Some(rest) = s.strip_prefix('+') {
        (false, rest)
    } else {
        (false, s)
    }
}

fn digits_to_int(s: &str) -> BigInt {
    // `s` has been checked to be ASCII digits only.
    BigInt::parse_bytes(s.as_bytes(), 10).unwrap_or_default()
}

/// The rational `n/d` in lowest terms (a literal in code and tests:
/// `ratio(1, 3)`).
///
/// # Panics
///
/// If `d == 0`, as [`BigRational::new`] does.
pub fn ratio(n: i64, d: i64) -> BigRational {
    BigRational::new(BigInt::from(n), BigInt::from(d))
}

/// Reads `text` as an exact rational (see the module documentation).
pub fn parse_exact(text: &str) -> Result<BigRational, NumberError> {
    let s = text.trim();
    if s.is_empty() {
        return Err(NumberError::Empty);
    }
    let (negative, body) = split_sign(s);
    let cap = max_digits();
    if body.len() > cap {
        let digits = body.bytes().filter(u8::is_ascii_digit).count();
        if digits > cap {
            return Err(NumberError::TooManyDigits { digits, cap });
        }
    }
    let value = if let Some((num, den)) = body.split_once('/') {
        if !is_digits(num) || !is_digits(den) {
            return Err(NumberError::Malformed);
        }
        let den = digits_to_int(den);
        if den.is_zero() {
            return Err(NumberError::ZeroDenominator);
        }
        BigRational::new(digits_to_int(num), den)
    } else {
        let (mantissa, exponent) = match body.find(['e', 'E']) {
            Some(k) => (&body[..k], Some(&body[k + 1..])),
            None => (body, None),
        };
        let (int_part, frac_part) = match mantissa.split_once('.') {
            Some((a, b)) => (a, b),
            None => (mantissa, ""),
        };
        if !is_digits(int_part) || (mantissa.contains('.') && !is_digits(frac_part)) {
            return Err(NumberError::Malformed);
        }
        let mut exp: i64 = 0;
        if let Some(e) = exponent {
            let (eneg, edigits) = split_sign(e);
            if !is_digits(edigits) {
                return Err(NumberError::Malformed);
            }
            let magnitude: u32 = edigits
                .trim_start_matches('0')
                .parse::<u32>()
                .ok()
                .or(if edigits.bytes().all(|b| b == b'0') {
                    Some(0)
                } else {
                    None
                })
                .filter(|m| *m <= MAX_EXPONENT)
                .ok_or(NumberError::ExponentTooLarge)?;
            exp = if eneg {
                -i64::from(magnitude)
            } else {
                i64::from(magnitude)
            };
        }
        let digits = format!("{int_part}{frac_part}");
        exp -= frac_part.len() as i64;
        let mantissa = digits_to_int(&digits);
        let ten = BigInt::from(10u32);
        if exp >= 0 {
            BigRational::from_integer(mantissa * Pow::pow(&ten, exp as u64))
        } else {
            BigRational::new(mantissa, Pow::pow(&ten, exp.unsigned_abs()))
        }
    };
    Ok(if negative { -value } else { value })
}

/// Writes `q` as `"p/q"` in lowest terms, or `"p"` when it is an integer.
pub fn render_exact(q: &BigRational) -> String {
    // `BigRational` values built through `BigRational::new` and arithmetic are
    // always reduced with a positive denominator; its `Display` prints
    // `numer/denom`, or `numer` alone when `denom == 1`. The same digits come
    // from machine words when both fit them, without `BigInt`'s formatting.
    use num_traits::ToPrimitive;
    match (q.numer().to_i128(), q.denom().to_u128()) {
        (Some(p), Some(1)) => p.to_string(),
        (Some(p), Some(d)) => format!("{p}/{d}"),
        _ => q.to_string(),
    }
}

/// The nearest double of `q` (round to nearest, ties to even, subnormals
/// included), or `None` when `q` is beyond the largest finite double (it
/// would round to an infinity). Integer arithmetic only: `⌊|q| · 2^k⌋` with
/// 60 significant bits and a sticky bit, rounded by [`nearest_double_of`].
/// The word-sized fast path of the streaming engine
/// (`fast::stream::nearest_ratio`) is tested against it.
pub fn nearest_f64(q: &BigRational) -> Option<f64> {
    if Zero::is_zero(q) {
        return Some(0.0);
    }
    let (n, d) = (q.numer().magnitude(), q.denom().magnitude());
    // 2^E ≤ |q| < 2^(E+1): E is the difference of the bit lengths, or one less.
    let bits = n.bits() as i64 - d.bits() as i64;
    let at_least = if bits >= 0 {
        *n >= d << bits as u64
    } else {
        n << bits.unsigned_abs() >= *d
    };
    let big_e = if at_least { bits } else { bits - 1 };
    nearest_double_of(big_e, Signed::is_negative(q), |k| {
        let (num, den) = if k >= 0 {
            (n << k as u64, d.clone())
        } else {
            (n.clone(), d << k.unsigned_abs())
        };
        let (f, r) = num.div_rem(&den);
        (f, !r.is_zero())
    })
}

/// The nearest double (ties to even, subnormals included) of a non-zero
/// value `v` with `2^big_e ≤ |v| < 2^(big_e + 1)`, given the sign and
/// `scaled_floor(k) = (⌊|v| · 2^k⌋, whether |v| · 2^k is not an integer)`;
/// `None` beyond the largest double. The one rounding step of every exact
/// value to a double (rationals here, square roots of rationals in
/// `report::compare::decimal`).
pub fn nearest_double_of(
    big_e: i64,
    negative: bool,
    scaled_floor: impl FnOnce(i64) -> (BigUint, bool),
) -> Option<f64> {
    if big_e > 1023 {
        return None;
    }
    if big_e < -1075 {
        // |v| < 2^−1075, below half the smallest subnormal: zero, signed.
        return Some(if negative { -0.0 } else { 0.0 });
    }
    // Keep 60 bits: m = ⌊|v|·2^k⌋, 2^59 ≤ m < 2^60.
    let k = 59 - big_e;
    let (m, inexact) = scaled_floor(k);
    debug_assert!(m.bits() == 60, "2^59 ≤ m < 2^60");
    // The precision left at this exponent: 53 bits, fewer below 2^−1022
    // (none at 2^−1075, where only the rounding up to 2^−1074 is left).
    let precision = if big_e >= -1022 {
        53
    } else {
        53 - (-1022 - big_e)
    };
    debug_assert!((0..=53).contains(&precision));
    // Drop `shift = 60 − precision ≥ 7` bits, rounding half to even; the
    // value dropped is `rest + (inexact ? a positive fraction : 0)`.
    let shift = (60 - precision) as u64;
    let kept = &m >> shift;
    let rest = &m - (&kept << shift);
    let half = BigUint::from(1u32) << (shift - 1);
    let up = rest > half || (rest == half && (inexact || kept.is_odd()));
    let kept = if up { kept + 1u32 } else { kept };
    // kept ≤ 2^53 is an exact double; the value is kept · 2^(shift − k).
    let mantissa = u64::try_from(&kept).ok()? as f64;
    let x = times_power_of_two(mantissa, shift as i64 - k);
    let x = if negative { -x } else { x };
    x.is_finite().then_some(x)
}

/// `x · 2^e`, exact when the result is a double (`x` an integer ≤ 2^53):
/// in steps that each stay exact.
fn times_power_of_two(mut x: f64, mut e: i64) -> f64 {
    let pow2 = |k: i64| f64::from_bits(((k + 1023) as u64) << 52);
    while e > 1000 {
        x *= pow2(1000);
        e -= 1000;
    }
    while e < -1000 {
        x *= pow2(-1000);
        e += 1000;
    }
    x * pow2(e)
}

#[cfg(test)]
mod tests {
    use super::*;

    use super::ratio as q;

    /// `render_exact` on machine words writes what `BigRational`'s own
    /// `Display` writes, at and across the words' edges.
    #[test]
    fn render_exact_is_display_on_and_off_words() {
        let big = |v: i128| BigInt::from(v);
        let edges = [
            big(0),
            big(1),
            big(-1),
            big(i128::MAX),
            big(i128::MIN),
            big(i128::MAX) + 1,
            big(i128::MIN) - 1,
        ];
        let denominators = [
            BigInt::from(1),
            BigInt::from(3),
            BigInt::from(u128::MAX),
            BigInt::from(u128::MAX) + 2,
        ];
        for p in &edges {
            for d in &denominators {
                let v = BigRational::new(p.clone(), d.clone());
                assert_eq!(render_exact(&v), v.to_string(), "{p}/{d}");
            }
        }
        assert_eq!(render_exact(&q(-6, 4)), "-3/2");
        assert_eq!(render_exact(&q(8, 4)), "2");
    }

    /// The next double after the finite `f`, toward `+∞` or `−∞`.
    fn neighbour(f: f64, up: bool) -> f64 {
        if f == 0.0 {
            let tiny = f64::from_bits(1);
            return if up { tiny } else { -tiny };
        }
        let bits = f.to_bits();
        f64::from_bits(if up == (f > 0.0) { bits + 1 } else { bits - 1 })
    }

    fn exact(f: f64) -> BigRational {
        crate::scalar::Scalar::to_big_rational(&f).expect("finite")
    }

    /// The definition of the nearest double, checked exactly: neither
    /// neighbour of `f` is closer to `q`, and at a tie `f` is even.
    fn is_nearest(f: f64, q: &BigRational) -> bool {
        let dist = |g: f64| (exact(g) - q).abs();
        let d = dist(f);
        [neighbour(f, true), neighbour(f, false)]
            .into_iter()
            .filter(|g| g.is_finite())
            .all(|g| {
                let e = dist(g);
                e > d || (e == d && f.to_bits() & 1 == 0)
            })
    }

    /// Random rationals over the whole range (subnormals and near-overflow
    /// included), ties between two doubles, and every double itself.
    #[test]
    fn nearest_f64_is_the_nearest_double() {
        let mut seed = 0x9e37_79b9_7f4a_7c15u64;
        let mut next = || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            seed
        };
        let two = BigRational::from_integer(BigInt::from(2));
        let big = |e: u32| BigRational::from_integer(BigInt::from(2).pow(e));
        for _ in 0..3000 {
            let n = BigInt::from(next() >> (next() % 64)) - BigInt::from(1u64 << 40);
            let d = BigInt::from((next() >> (next() % 64)).max(1));
            let e = (next() % 2200) as i32 - 1100;
            let q = BigRational::new(n, d) * Pow::pow(&two, e);
            match nearest_f64(&q) {
                Some(f) => assert!(is_nearest(f, &q), "{q} gave {f:e}"),
                None => assert!(q.abs() > big(1023)),
            }
        }
        for f in [
            5e-324,
            1e-310,
            f64::MIN_POSITIVE,
            0.1,
            -3.5,
            1.0 / 3.0,
            f64::MAX,
        ] {
            assert_eq!(nearest_f64(&exact(f)).map(f64::to_bits), Some(f.to_bits()));
            // The midpoint to the next double up rounds to the even one.
            let g = neighbour(f, true);
            if g.is_finite() {
                let mid = (exact(f) + exact(g)) / &two;
                let want = if f.to_bits() & 1 == 0 { f } else { g };
                assert_eq!(nearest_f64(&mid), Some(want), "midpoint above {f:e}");
            }
        }
        // Half the smallest subnormal is a tie with 0 (even): 0; above it,
        // the subnormal.
        let tiny = exact(5e-324);
        assert_eq!(nearest_f64(&(&tiny / &two)), Some(0.0));
        assert_eq!(nearest_f64(&(&tiny * ratio(3, 4))), Some(5e-324));
        let above_half = &tiny / &two + ratio(1, 1) / big(1200);
        assert_eq!(nearest_f64(&above_half), Some(5e-324));
        // Far below (not a power of two): zero, with the value's sign.
        let far_below = &tiny * ratio(3, 4) / big(40);
        let bits = |q: &BigRational| nearest_f64(q).map(f64::to_bits);
        assert_eq!(bits(&far_below), Some(0.0f64.to_bits()));
        assert_eq!(bits(&-far_below), Some((-0.0f64).to_bits()));
        assert_eq!(nearest_f64(&big(1024)), None);
    }

    #[test]
    fn reads_every_documented_form_exactly() {
        assert_eq!(parse_exact("3"), Ok(q(3, 1)));
        assert_eq!(parse_exact("-7/4"), Ok(q(-7, 4)));
        assert_eq!(parse_exact("6/8"), Ok(q(3, 4)));
        assert_eq!(parse_exact("0.125"), Ok(q(1, 8)));
        assert_eq!(parse_exact("-2.50"), Ok(q(-5, 2)));
        assert_eq!(parse_exact("1.5e-3"), Ok(q(3, 2000)));
        assert_eq!(parse_exact("2E+4"), Ok(q(20000, 1)));
        assert_eq!(parse_exact("+1e0"), Ok(q(1, 1)));
        assert_eq!(parse_exact(" 0.1 "), Ok(q(1, 10)));
    }

    #[test]
    fn refuses_what_is_not_a_number() {
        for bad in [
            "", " ", "abc", "1/", "/2", "1.", ".5", "1e", "1e+", "--1", "1/-2", "0x10", "1,5",
            "inf", "NaN", "1.2.3", "1/2/3",
        ] {
            assert!(parse_exact(bad).is_err(), "{bad:?} was accepted");
        }
        assert_eq!(parse_exact("3/0"), Err(NumberError::ZeroDenominator));
        assert_eq!(parse_exact("1e5000"), Err(NumberError::ExponentTooLarge));
        assert_eq!(
            parse_exact("1e99999999999999999999"),
            Err(NumberError::ExponentTooLarge)
        );
        assert_eq!(parse_exact("1e-0004"), Ok(q(1, 10000)));
    }

    #[test]
    fn writes_lowest_terms() {
        assert_eq!(render_exact(&q(2, 4)), "1/2");
        assert_eq!(render_exact(&q(-3, 1)), "-3");
        assert_eq!(render_exact(&q(3, -6)), "-1/2");
        assert_eq!(render_exact(&q(0, 5)), "0");
    }
}
