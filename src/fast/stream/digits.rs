//! Exact values written as decimal text straight into a byte buffer: two
//! digits per step from a table, no formatter, no `String` per value. The
//! bytes are those of `Exact`'s `Display` (`p/q`, or `p` when `q = 1`),
//! which the tests compare.

use super::Exact;

/// `"00" … "99"`.
const PAIRS: &[u8; 200] = b"\
0001020304050607080910111213141516171819\
2021222324252627282930313233343536373839\
4041424344454647484950515253545556575859\
6061626364656667686970717273747576777879\
8081828384858687888990919293949596979899";

/// Appends the decimal digits of `v` to `out`, written in place: the
/// digit count first, then twenty bytes appended at once (a copy of fixed
/// size, no call) and cut to it, then the digits from the last one back.
fn push_u64(out: &mut Vec<u8>, mut v: u64) {
    let len = v.checked_ilog10().map_or(1, |l| l as usize + 1);
    let start = out.len();
    out.extend_from_slice(&[0u8; 20]);
    out.truncate(start + len);
    let buf = &mut out[start..];
    let mut at = len;
    while v >= 100 {
        let pair = (v % 100) as usize * 2;
        v /= 100;
        at -= 2;
        buf[at..at + 2].copy_from_slice(&PAIRS[pair..pair + 2]);
    }
    if v >= 10 {
        let pair = v as usize * 2;
        at -= 2;
        buf[at..at + 2].copy_from_slice(&PAIRS[pair..pair + 2]);
    } else {
        at -= 1;
        buf[at] = b'0' + v as u8;
    }
    debug_assert_eq!(at, 0);
}

/// Appends the decimal digits of `v` to `out`: 19 digits at a time on
/// 64-bit words.
fn push_u128(out: &mut Vec<u8>, v: u128) {
    const TEN19: u128 = 10_000_000_000_000_000_000;
    if let Ok(v) = u64::try_from(v) {
        return push_u64(out, v);
    }
    // v ≥ 2^64 > 10^19: a high part, then exactly 19 digits.
    push_u128(out, v / TEN19);
    let low = (v % TEN19) as u64;
    let mark = out.len();
    push_u64(out, low);
    let written = out.len() - mark;
    // Zeros in front of the low part, up to 19 digits.
    out.splice(mark..mark, std::iter::repeat_n(b'0', 19 - written));
}

/// Appends `v` (a sign, then its digits) to `out`.
fn push_i128(out: &mut Vec<u8>, v: i128) {
    if v < 0 {
        out.push(b'-');
    }
    push_u128(out, v.unsigned_abs());
}

impl Exact {
    /// Appends the value to `out` as its `Display` writes it: `p/q`, or
    /// `p` when `q = 1`.
    pub fn push_text(&self, out: &mut Vec<u8>) {
        match self {
            Exact::Small(n, d) => {
                push_i128(out, *n);
                if *d != 1 {
                    out.push(b'/');
                    push_i128(out, *d);
                }
            }
            Exact::Big(_) => out.extend_from_slice(self.to_string().as_bytes()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::SplitMix64;
    use num_bigint::BigInt;
    use num_rational::BigRational;

    /// The bytes are `Display`'s, at every length of the words and at
    /// their ends.
    #[test]
    fn text_is_display() {
        let mut rng = SplitMix64::new(3);
        let mut values: Vec<i128> = vec![0, 1, -1, 9, 10, 99, 100, 101, i128::MAX, i128::MIN + 1];
        for p in 0..39u32 {
            let t = 10i128.pow(p);
            values.extend([t - 1, t, t + 1, -t, 1 - t]);
        }
        for shift in [0, 20, 40, 63, 64, 65, 90, 126] {
            for _ in 0..50 {
                let r = (u128::from(rng.next_u64()) << 64 | u128::from(rng.next_u64())) >> shift;
                values.push(r as i128);
                values.push((r as i128).wrapping_neg() / 2);
            }
        }
        let mut out = Vec::new();
        for (k, &n) in values.iter().enumerate() {
            let d = values[(k * 7 + 3) % values.len()].unsigned_abs().max(1) as i128;
            let d = if d < 0 { 1 } else { d };
            for v in [Exact::Small(n, 1), Exact::Small(n, d)] {
                out.clear();
                v.push_text(&mut out);
                assert_eq!(String::from_utf8(out.clone()).unwrap(), v.to_string());
            }
        }
        let big = Exact::Big(BigRational::new(BigInt::from(7).pow(60), BigInt::from(3)));
        out.clear();
        big.push_text(&mut out);
        assert_eq!(String::from_utf8(out).unwrap(), big.to_string());
    }
}
