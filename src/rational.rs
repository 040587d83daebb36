//! Exact reading and writing of rational numbers.
//!
//! Accepted text (DESIGN.md §2), always read exactly:
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
//! `q = 1`: the JSON contract of DESIGN.md §3.

use std::fmt;

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{Pow, Signed, ToPrimitive, Zero};

use crate::scalar::Scalar;

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
    // `numer/denom`, or `numer` alone when `denom == 1`.
    q.to_string()
}

/// The nearest double of `q` (round to nearest, ties to even), or `None`
/// when `q` is beyond the largest finite double (it would round to an
/// infinity). Checked exactly against both neighbours, so the answer does
/// not rest on any library's rounding.
pub fn nearest_f64(q: &BigRational) -> Option<f64> {
    let f = q.to_f64()?;
    if !f.is_finite() {
        return None;
    }
    let dist = |g: f64| g.to_big_rational().map(|r| (&r - q).abs());
    let mut best = f;
    let mut best_d = dist(f)?;
    for g in [
        next_toward(f, f64::INFINITY),
        next_toward(f, f64::NEG_INFINITY),
    ] {
        if let Some(d) = dist(g) {
            let even = g.to_bits() & 1 == 0;
            if d < best_d || (d == best_d && even) {
                best = g;
                best_d = d;
            }
        }
    }
    Some(best)
}

/// The next double after `f` toward `dir` (finite `f`).
fn next_toward(f: f64, dir: f64) -> f64 {
    if f == 0.0 {
        let tiny = f64::from_bits(1);
        return if dir > 0.0 { tiny } else { -tiny };
    }
    let bits = f.to_bits();
    let up = (dir > f) == (f > 0.0);
    f64::from_bits(if up { bits + 1 } else { bits - 1 })
}

#[cfg(test)]
mod tests {
    use super::*;

    use super::ratio as q;

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
