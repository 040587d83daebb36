//! The rows of a CSV particle file in one scan of their bytes: a line of
//! the plain form `[-]digits[.digits | /digits],[-]digits[.digits | /digits]`
//! (what `sticky generate` and most writers produce) is read as it is
//! scanned, straight into [`Small`] pairs; any other line (white space, a
//! sign `+`, an exponent, a blank line, …) goes to the line reader of
//! record, [`csv_line_small`]. Both give the same values: the plain form is
//! a case of [`crate::columns::parse_small`]'s grammar, read with the same
//! 64-bit words and reduced by the same [`small_of`].

use crate::columns::{csv_line_small, small_of, CsvLine, Small};

/// Calls `f(x, u)` on every row of `text` (whole lines of a CSV particle
/// file after its header, the last one with or without its `'\n'`), in
/// order; the number of rows, or `None` when a line is neither blank nor
/// two [`Small`] values, or `f` answers `None`.
pub(crate) fn rows(text: &[u8], f: &mut dyn FnMut(Small, Small) -> Option<()>) -> Option<usize> {
    let cap = crate::rational::max_digits();
    let (mut at, mut count) = (0usize, 0usize);
    while at < text.len() {
        if let Some((x, u, next)) = plain_row(text, at, cap) {
            f(x, u)?;
            count += 1;
            at = next;
            continue;
        }
        // `str::lines`: the line ends at '\n', one '\r' before it dropped.
        let end = text[at..]
            .iter()
            .position(|&b| b == b'\n')
            .map_or(text.len(), |k| at + k);
        let line = &text[at..end];
        let line = line.strip_suffix(b"\r").unwrap_or(line);
        if let CsvLine::Row(x, u) = csv_line_small(line)? {
            f(x, u)?;
            count += 1;
        }
        at = end + 1;
    }
    Some(count)
}

/// The line of `text` from `at` when it has the plain form: its two
/// values and where the next line starts; `None` for any other line.
#[inline]
fn plain_row(text: &[u8], at: usize, cap: usize) -> Option<(Small, Small, usize)> {
    let (x, comma) = plain_value(text, at, cap)?;
    if text.get(comma) != Some(&b',') {
        return None;
    }
    let (u, end) = plain_value(text, comma + 1, cap)?;
    let next = match text.get(end) {
        None => end,
        Some(b'\n') => end + 1,
        Some(b'\r') => match text.get(end + 1) {
            None => end + 1,
            Some(b'\n') => end + 2,
            Some(_) => return None,
        },
        Some(_) => return None,
    };
    Some((x, u, next))
}

/// The digits from `at` on as a `u64`: the value and where they end; `None`
/// for no digit or an overflow.
#[inline]
fn digits(text: &[u8], mut at: usize) -> Option<(u64, usize)> {
    let start = at;
    let mut v = 0u64;
    while let Some(&b) = text.get(at) {
        if !b.is_ascii_digit() {
            break;
        }
        v = v.checked_mul(10)?.checked_add(u64::from(b - b'0'))?;
        at += 1;
    }
    (at > start).then_some((v, at))
}

/// A plain value from `at` on — `[-]digits`, `[-]digits.digits` or
/// `[-]digits/digits` — and where it ends; `None` when the text there is
/// not one, does not fit [`Small`], or is longer than `cap` bytes (the
/// digit cap of [`crate::rational::max_digits`]).
#[inline]
fn plain_value(text: &[u8], at: usize, cap: usize) -> Option<(Small, usize)> {
    let negative = text.get(at) == Some(&b'-');
    let start = at;
    let (int, mut end) = digits(text, at + usize::from(negative))?;
    let value = match text.get(end) {
        Some(b'.') => {
            let (mut v, frac_end) = (int, end + 1);
            let mut k = frac_end;
            while let Some(&b) = text.get(k) {
                if !b.is_ascii_digit() {
                    break;
                }
                v = v.checked_mul(10)?.checked_add(u64::from(b - b'0'))?;
                k += 1;
            }
            if k == frac_end {
                return None;
            }
            end = k;
            if v == 0 {
                (0, 1)
            } else {
                let places = u32::try_from(k - frac_end).ok()?;
                small_decimal(negative, v, places)?
            }
        }
        Some(b'/') => {
            let (den, den_end) = digits(text, end + 1)?;
            if den == 0 {
                return None;
            }
            end = den_end;
            small_of(negative, int, den)?
        }
        _ => small_of(negative, int, 1)?,
    };
    (end - start <= cap).then_some((value, end))
}

/// `±v / 10^places` in lowest terms, [`small_of`]'s value (`None` when
/// `10^places` or the numerator leaves the words): the gcd of `v` and a
/// power of ten is a power of two times a power of five, found by a shift
/// and a few divisions by 5 instead of a gcd loop.
#[inline]
fn small_decimal(negative: bool, v: u64, places: u32) -> Option<Small> {
    10u64.checked_pow(places)?;
    if v == 0 {
        return Some((0, 1));
    }
    let twos = v.trailing_zeros().min(places);
    let mut v = v >> twos;
    let mut fives = 0;
    while fives < places && v % 5 == 0 {
        v /= 5;
        fives += 1;
    }
    // 5^(places − fives) 2^(places − twos) divides 10^places: on words.
    let den = 5u64.pow(places - fives) << (places - twos);
    let num = i64::try_from(v).ok()?;
    Some((if negative { -num } else { num }, den))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::columns::parse_small;
    use crate::generate::SplitMix64;

    /// The rows the line reader of record gives ([`csv_line_small`] on each
    /// line, as `ColumnFile` read them before).
    /// The decimal reduction is `small_of`'s: every count of places, at
    /// the powers of two and five and at random.
    #[test]
    fn decimal_reduction_is_small_of() {
        let mut rng = SplitMix64::new(11);
        for places in 0..=20u32 {
            let mut values = vec![0u64, 1, 2, 5, 10, 125, 1 << 40, u64::MAX, i64::MAX as u64];
            values.extend((0..=27).map(|k| 5u64.pow(k)));
            values.extend((0..=27).map(|k| 5u64.pow(k) << (k + 3)));
            for _ in 0..300 {
                let r = rng.next_u64();
                values.push(r >> (r % 64));
            }
            for v in values {
                for negative in [false, true] {
                    let want = 10u64
                        .checked_pow(places)
                        .and_then(|ten| small_of(negative, v, ten));
                    assert_eq!(
                        small_decimal(negative, v, places),
                        want,
                        "{v} / 10^{places}"
                    );
                }
            }
        }
    }

    fn of_record(text: &[u8]) -> Option<Vec<(Small, Small)>> {
        let mut out = Vec::new();
        let body = text.strip_suffix(b"\n").unwrap_or(text);
        if text.is_empty() {
            return Some(out);
        }
        for line in body.split(|&b| b == b'\n') {
            let line = line.strip_suffix(b"\r").unwrap_or(line);
            if let CsvLine::Row(x, u) = csv_line_small(line)? {
                out.push((x, u));
            }
        }
        Some(out)
    }

    fn scanned(text: &[u8]) -> Option<Vec<(Small, Small)>> {
        let mut out = Vec::new();
        let count = rows(text, &mut |x, u| {
            out.push((x, u));
            Some(())
        })?;
        assert_eq!(count, out.len());
        Some(out)
    }

    /// A random value, plain or not: signs, decimals, fractions, white
    /// space, exponents, zeros, overflows, stray characters.
    fn value(rng: &mut SplitMix64) -> String {
        let r = rng.next_u64();
        let digits = |rng: &mut SplitMix64, k: u64| -> String {
            let len = 1 + rng.next_u64() % k;
            (0..len)
                .map(|_| char::from(b'0' + (rng.next_u64() % 10) as u8))
                .collect()
        };
        if r % 3 != 0 {
            // Plain: what writers produce.
            let sign = ["", "-"][(r >> 4) as usize % 2];
            return match (r >> 8) % 3 {
                0 => format!("{sign}{}", digits(rng, 7)),
                1 => format!("{sign}{}.{}", digits(rng, 4), digits(rng, 4)),
                _ => format!("{sign}{}/{}", digits(rng, 4), digits(rng, 3)),
            };
        }
        let sign = ["", "", "-", "+"][(r % 4) as usize];
        let body = match (r >> 8) % 9 {
            0 | 1 => digits(rng, 6),
            2 | 3 => format!("{}.{}", digits(rng, 5), digits(rng, 5)),
            4 => format!("{}/{}", digits(rng, 4), digits(rng, 4)),
            5 => digits(rng, 25),
            6 => format!("{}.{}", digits(rng, 3), digits(rng, 22)),
            7 => format!("{}e{}", digits(rng, 3), digits(rng, 2)),
            _ => ["", ".5", "1.", "0/0", "00.000", "1/0", "x", "-"][(r >> 16) as usize % 8]
                .to_string(),
        };
        let pad = [("", ""), ("", ""), ("", ""), (" ", ""), ("", "\t")][(r >> 24) as usize % 5];
        format!("{}{sign}{body}{}", pad.0, pad.1)
    }

    /// Random files of plain and other lines read as the line reader of
    /// record reads them: the same rows, the same refusals.
    #[test]
    fn plain_rows_are_read_as_the_line_reader_reads_them() {
        let mut rng = SplitMix64::new(5);
        let (mut plain, mut refused) = (0, 0);
        for k in 0..3000 {
            let mut text = String::new();
            for _ in 0..1 + rng.next_u64() % 4 {
                match rng.next_u64() % 12 {
                    0 => text.push_str("  "),
                    1 => text.push_str(&format!("{},{},{}", value(&mut rng), value(&mut rng), 1)),
                    _ => text.push_str(&format!("{},{}", value(&mut rng), value(&mut rng))),
                }
                text.push_str(["\n", "\r\n", "\n", "\r\r\n"][(rng.next_u64() % 4) as usize]);
            }
            if k % 3 == 0 {
                text.pop();
            }
            let want = of_record(text.as_bytes());
            assert_eq!(scanned(text.as_bytes()), want, "{text:?}");
            plain += usize::from(plain_row(text.as_bytes(), 0, usize::MAX).is_some());
            refused += usize::from(want.is_none());
        }
        assert!(
            plain > 300 && refused > 300,
            "{plain} plain, {refused} refused"
        );
    }

    /// Each plain value is `parse_small`'s, at the edges of the words too.
    #[test]
    fn plain_values_are_parse_small() {
        for v in [
            "0",
            "-0",
            "007",
            "18446744073709551615",
            "9223372036854775807",
            "9223372036854775808",
            "-9223372036854775808",
            "0.000000000000000000000000",
            "1.0000000000000000000",
            "0.5",
            "-2.50",
            "12/8",
            "-0/3",
            "3/0",
            "1/18446744073709551615",
            "1.",
            "1/",
        ] {
            let got = plain_value(v.as_bytes(), 0, usize::MAX)
                .filter(|&(_, end)| end == v.len())
                .map(|(s, _)| s);
            assert_eq!(got, parse_small(v.as_bytes()), "{v}");
        }
        assert_eq!(plain_value(b"12345", 0, 4), None);
    }
}
