//! The column readers on machine words: every value a [`Small`] pair
//! `p / d` in lowest terms, read with no `BigRational`, or a refusal that
//! sends the file to the exact readers of record ([`super::read_csv`],
//! [`super::read_npy`]), which read it or name what is wrong. What the
//! streaming path ([`crate::fast::stream`]) reads.

#[cfg(doc)]
use super::{read_csv, read_npy};
#[cfg(doc)]
use crate::rational::parse_exact;

use super::{npy_columns, npy_layout};

/// A column value on machine words: `p / d` in lowest terms, `d > 0`.
pub type Small = (i64, u64);

/// The columns on machine words, when every value is [`Small`].
pub type SmallColumns = (Vec<Small>, Vec<Small>);

fn gcd_u64(mut a: u64, mut b: u64) -> u64 {
    if a == 0 {
        return b;
    }
    if b == 0 {
        return a;
    }
    let shift = (a | b).trailing_zeros();
    a >>= a.trailing_zeros();
    loop {
        b >>= b.trailing_zeros();
        if a > b {
            std::mem::swap(&mut a, &mut b);
        }
        b -= a;
        if b == 0 {
            return a << shift;
        }
    }
}

/// `negative · num / den` in lowest terms, when it fits [`Small`].
pub(crate) fn small_of(negative: bool, num: u64, den: u64) -> Option<Small> {
    if num == 0 {
        return Some((0, 1));
    }
    // A power of two (every double's denominator, and many files'): the
    // gcd is the common power of two, no division needed.
    let g = if den.is_power_of_two() {
        1 << num.trailing_zeros().min(den.trailing_zeros())
    } else {
        gcd_u64(num, den)
    };
    let (num, den) = (num / g, den / g);
    let num = i64::try_from(num).ok()?;
    Some((if negative { -num } else { num }, den))
}

fn digits_u64(s: &[u8]) -> Option<u64> {
    if s.is_empty() {
        return None;
    }
    s.iter().try_fold(0u64, |acc, &b| {
        b.is_ascii_digit()
            .then(|| acc.checked_mul(10)?.checked_add(u64::from(b - b'0')))
            .flatten()
    })
}

/// [`parse_exact`] on machine words: the same value, or `None` when the
/// text is not a plain integer, fraction, decimal or scientific form whose
/// value is [`Small`] (then [`parse_exact`] reads it, or says what is wrong).
/// No white space is trimmed.
pub fn parse_small(text: &[u8]) -> Option<Small> {
    if text.len() > crate::rational::max_digits() {
        return None;
    }
    let (negative, body) = match text.first()? {
        b'-' => (true, &text[1..]),
        b'+' => (false, &text[1..]),
        _ => (false, text),
    };
    if let Some(k) = body.iter().position(|&b| b == b'/') {
        let (num, den) = (digits_u64(&body[..k])?, digits_u64(&body[k + 1..])?);
        return if den == 0 {
            None
        } else {
            small_of(negative, num, den)
        };
    }
    let (mantissa, exponent) = match body.iter().position(|&b| b == b'e' || b == b'E') {
        Some(k) => (&body[..k], Some(&body[k + 1..])),
        None => (body, None),
    };
    let (int_part, frac_part) = match mantissa.iter().position(|&b| b == b'.') {
        Some(k) => (&mantissa[..k], Some(&mantissa[k + 1..])),
        None => (mantissa, None),
    };
    let mut digits = digits_u64(int_part)?;
    let mut exp: i64 = 0;
    if let Some(frac) = frac_part {
        digits_u64(frac)?;
        for &b in frac {
            digits = digits.checked_mul(10)?.checked_add(u64::from(b - b'0'))?;
        }
        exp -= i64::try_from(frac.len()).ok()?;
    }
    if let Some(e) = exponent {
        let (eneg, edigits) = match e.first()? {
            b'-' => (true, &e[1..]),
            b'+' => (false, &e[1..]),
            _ => (false, e),
        };
        let magnitude = digits_u64(edigits)?;
        if magnitude > u64::from(crate::rational::MAX_EXPONENT) {
            return None;
        }
        let magnitude = i64::try_from(magnitude).ok()?;
        exp += if eneg { -magnitude } else { magnitude };
    }
    if digits == 0 {
        return Some((0, 1));
    }
    let pow = |e: u64| 10u64.checked_pow(u32::try_from(e).ok()?);
    if exp >= 0 {
        small_of(negative, digits.checked_mul(pow(exp.unsigned_abs())?)?, 1)
    } else {
        small_of(negative, digits, pow(exp.unsigned_abs())?)
    }
}

/// `char::is_whitespace` on ASCII bytes (what `str::trim` removes).
pub(crate) fn trim_ascii(mut s: &[u8]) -> &[u8] {
    let ws = |b: &u8| matches!(b, b' ' | b'\t' | b'\n' | b'\x0b' | b'\x0c' | b'\r');
    while s.first().is_some_and(ws) {
        s = &s[1..];
    }
    while s.last().is_some_and(ws) {
        s = &s[..s.len() - 1];
    }
    s
}

/// One line of a CSV particle file, on machine words (see [`csv_line_small`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum CsvLine {
    /// A line of white space only (allowed anywhere).
    Blank,
    /// The two values of one particle.
    Row(Small, Small),
}

/// `true` for the header line `position,velocity` (white space around the
/// names allowed).
pub(crate) fn csv_header_small(line: &[u8]) -> bool {
    let mut names = line.split(|&b| b == b',').map(trim_ascii);
    names.next() == Some(b"position") && names.next() == Some(b"velocity") && names.next().is_none()
}

/// One line of a CSV particle file after its header (its `'\n'` and one
/// `'\r'` before it removed), when it is blank or two [`Small`] values;
/// `None` when it is anything else (then [`read_csv`] names the error).
pub(crate) fn csv_line_small(line: &[u8]) -> Option<CsvLine> {
    if !line.is_ascii() {
        return None;
    }
    if trim_ascii(line).is_empty() {
        return Some(CsvLine::Blank);
    }
    let comma = line.iter().position(|&b| b == b',')?;
    let (x, u) = (&line[..comma], &line[comma + 1..]);
    if u.contains(&b',') {
        return None;
    }
    Some(CsvLine::Row(
        parse_small(trim_ascii(x))?,
        parse_small(trim_ascii(u))?,
    ))
}

/// [`read_csv`] on machine words: the same columns as [`Small`] pairs, or
/// `None` when the file is not plain ASCII, a value is not [`Small`] or
/// anything is wrong (then [`read_csv`] reads it, or names the error).
pub fn read_csv_small(bytes: &[u8]) -> Option<SmallColumns> {
    if !bytes.is_ascii() {
        return None;
    }
    // `str::lines`: split at '\n', drop one '\r' before it, no empty last line.
    let mut lines = bytes
        .split(|&b| b == b'\n')
        .map(|l| l.strip_suffix(b"\r").unwrap_or(l));
    let header = lines.by_ref().find(|l| !trim_ascii(l).is_empty())?;
    if !csv_header_small(header) {
        return None;
    }
    let rows = bytes.len() / 4;
    let mut positions = Vec::with_capacity(rows.min(1 << 24));
    let mut velocities = Vec::with_capacity(rows.min(1 << 24));
    for line in lines {
        if let CsvLine::Row(x, u) = csv_line_small(line)? {
            positions.push(x);
            velocities.push(u);
        }
    }
    positions.shrink_to_fit();
    velocities.shrink_to_fit();
    Some((positions, velocities))
}

/// A finite double as [`Small`] (its exact binary value), when it fits.
pub fn f64_small(v: f64) -> Option<Small> {
    if !v.is_finite() {
        return None;
    }
    if v == 0.0 {
        return Some((0, 1));
    }
    let bits = v.to_bits();
    let negative = bits >> 63 == 1;
    let biased = ((bits >> 52) & 0x7ff) as i64;
    let fraction = bits & ((1 << 52) - 1);
    // v = m · 2^e
    let (m, e) = if biased == 0 {
        (fraction, -1074)
    } else {
        (fraction | (1 << 52), biased - 1075)
    };
    let z = m.trailing_zeros();
    let (m, e) = (m >> z, e + i64::from(z));
    if e >= 0 {
        let v = m.checked_shl(u32::try_from(e).ok()?)?;
        (v >> e == m).then_some(())?;
        small_of(negative, v, 1)
    } else if e >= -63 {
        small_of(negative, m, 1u64 << e.unsigned_abs())
    } else {
        None
    }
}

/// [`read_npy`] on machine words: the same columns as [`Small`] pairs, or
/// `None` when a value is not [`Small`] or anything is wrong.
pub fn read_npy_small(bytes: &[u8]) -> Option<SmallColumns> {
    let (n, fortran, end) = npy_layout(bytes).ok()?;
    let body = &bytes[end..];
    let value = |k: usize| -> Result<Small, ()> {
        let mut b = [0u8; 8];
        b.copy_from_slice(body.get(8 * k..8 * k + 8).ok_or(())?);
        f64_small(f64::from_le_bytes(b)).ok_or(())
    };
    npy_columns(n, fortran, value).ok()
}
#[cfg(test)]
mod tests {
    use num_rational::BigRational;

    use super::*;
    use crate::columns::{f64_exact, read_csv};
    use crate::rational::parse_exact;
    /// The word readers give the values of the exact readers, or decline.
    #[test]
    fn small_readers_equal_the_exact_ones() {
        let mut rng = crate::generate::SplitMix64::new(99);
        let pieces = [
            "0",
            "1",
            "7",
            "12",
            "007",
            "999999999999",
            "18446744073709551615",
            "9223372036854775807",
            "9223372036854775808",
            "",
            "-",
            "+",
            ".",
            "/",
            "e",
            "E",
            "-3",
            "e-",
            "e+",
            "4096",
            "4097",
            "19",
            "20",
            "x",
            " ",
        ];
        let mut seen = 0;
        for _ in 0..20000 {
            let k = 1 + rng.next_u64() % 5;
            let text: String = (0..k)
                .map(|_| pieces[(rng.next_u64() % pieces.len() as u64) as usize])
                .collect();
            let small = parse_small(text.as_bytes());
            let exact = parse_exact(&text);
            if let Some((p, d)) = small {
                seen += 1;
                assert_eq!(Ok(BigRational::new(p.into(), d.into())), exact, "{text:?}");
                assert!(d > 0);
            }
        }
        assert!(seen > 1000, "{seen}");
        for v in [
            0.1,
            -2.5,
            0.0,
            -0.0,
            1e300,
            1e-300,
            3.0e18,
            9.3e18,
            f64::from_bits(1),
        ] {
            match f64_small(v) {
                Some((p, d)) => {
                    assert_eq!(Some(BigRational::new(p.into(), d.into())), f64_exact(v))
                }
                None => assert!(v.abs() > 9e18 || v.abs() < 1e-18, "{v}"),
            }
        }
        // The CSV reader on words agrees with the exact one, or declines.
        let text = "position, velocity\r\n 0.125 , 1.5e-3\n\n-7/4,+2\n";
        let (x, u) = read_csv_small(text.as_bytes()).expect("on words");
        let c = read_csv(text).unwrap();
        let big = |v: &[Small]| -> Vec<BigRational> {
            v.iter()
                .map(|&(p, d)| BigRational::new(p.into(), d.into()))
                .collect()
        };
        assert_eq!((big(&x), big(&u)), (c.positions, c.velocities));
        for bad in [
            "x,u\n1,2\n",
            "position,velocity\n1,2,3\n",
            "position,velocity\n1\n",
            "position,velocity\n1/0,2\n",
        ] {
            assert!(read_csv_small(bad.as_bytes()).is_none(), "{bad:?}");
        }
    }
}
