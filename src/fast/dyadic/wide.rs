//! The dyadic path beyond the `i128` bound (issue 38): a double time with
//! a full mantissa, or a double radius, keeps the data dyadic but makes
//! `Y_i = A X̃_i + B U_i` wider than 127 bits (`b_Y + b_K > 127`). The same
//! PAVA then runs on 256-bit sums ([`I256`]), under the same kind of bound
//! (`b_Y + b_K ≤ 254`), and the positions are rounded from 256-bit
//! numerators: exact, no `f64` on the way, no big number per value.
//!
//! * `A = a_o 2^{a_s}`, `B = b_o 2^{b_s}` ([`Factor`]) are built exactly in
//!   256 bits; `Y_i` is two 256-bit products (one row each when the odd
//!   parts fit 64 bits).
//! * The `U` sums stay within `i128` (`u_bits + b_K ≤ 127`, independent of
//!   `t`): the velocities and multipliers are the narrow path's.
//! * `x_i 2^{−ey} k b_o q_o = S + k C i` with `C = A R`: every numerator is
//!   below `2^{b_Y + b_K} + 2^{bits(C) + 2 bits(N)} ≤ 2^255` by the checks
//!   of [`Wide::new`].

use super::bits;
use super::halves;
use super::pava::Sum;
use super::round::{self, Fraction64, Split};
use crate::fast::kernel::{size_bits, Run};
use crate::fast::wide::{Top, I256};

/// The widest `Y` bound (`b_Y + b_K`) this path takes: sums and cross
/// products below `2^254`, so that a sum of two of them stays in range.
pub(crate) const WIDE_BITS: u64 = 254;

/// A non-negative factor `odd 2^shift` (`odd` on 128 bits).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Factor {
    /// The odd part (or 0).
    pub(crate) odd: u128,
    /// The power of two.
    pub(crate) shift: u64,
}

impl Factor {
    /// Bits of the factor (0 for 0).
    pub(crate) fn bits(&self) -> u64 {
        if self.odd == 0 {
            0
        } else {
            bits(self.odd) + self.shift
        }
    }

    /// The factor on 256 bits; `None` beyond [`WIDE_BITS`].
    fn wide(&self) -> Option<I256> {
        if self.bits() > WIDE_BITS {
            return None;
        }
        if self.odd == 0 {
            return Some(I256::ZERO);
        }
        Some(I256::from_u128(self.odd).wrapping_shl(self.shift as u32))
    }
}

/// `f · v` for a factor prepared on 256 bits: a shift when its odd part
/// is 1, a multiplication by a word when it fits 64 bits.
#[derive(Debug, Clone, Copy)]
enum Times {
    /// `v 2^j`.
    Shift(u32),
    /// `(v k) 2^j`.
    Word(u64, u32),
    /// `v f` (the whole factor).
    Full(I256),
}

impl Times {
    fn new(f: &Factor) -> Option<Times> {
        let whole = f.wide()?;
        let j = u32::try_from(f.shift).ok()?;
        Some(match u64::try_from(f.odd) {
            Ok(0) => Times::Full(I256::ZERO),
            Ok(1) => Times::Shift(j),
            Ok(k) => Times::Word(k, j),
            Err(_) => Times::Full(whole),
        })
    }

    #[inline]
    fn apply(&self, v: I256) -> I256 {
        match *self {
            Times::Shift(j) => v.wrapping_shl(j),
            Times::Word(k, j) => v.wrapping_mul_u64(k).wrapping_shl(j),
            Times::Full(f) => f.wrapping_mul(v),
        }
    }
}

/// The blocks of one time on 256-bit `ΣY` sums, and `C = A R`.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Wide {
    pub(crate) runs: Vec<Run<I256, i128>>,
    pub(crate) c: I256,
}

impl Wide {
    /// The PAVA on `Y_i = A X̃_i + B U_i` in 256 bits; `None` when a bound
    /// of the module documentation fails. `x_bits`, `u_bits`: bits of the
    /// largest `|X̃_i|`, `|U_i|`; `two_r`: `R`.
    pub(crate) fn new<T: Copy + Into<I256> + Into<i128> + Sync>(
        xs: &[T],
        us: &[T],
        a: &Factor,
        b: &Factor,
        two_r: i128,
        (x_bits, u_bits): (u64, u64),
        parallel_min: usize,
    ) -> Option<Wide> {
        let n = xs.len();
        let b_k = size_bits(n);
        let b_y = (a.bits() + x_bits).max(b.bits() + u_bits) + 1;
        if b_y + b_k > WIDE_BITS || u_bits + b_k > 127 {
            return None;
        }
        let c_bits = a.bits() + bits(two_r.unsigned_abs());
        let n_bits = bits(u128::try_from(n).ok()?);
        if c_bits > WIDE_BITS || c_bits + 2 * n_bits > WIDE_BITS {
            return None;
        }
        let c = a.wide()?.wrapping_mul(I256::from_i128(two_r));
        let (ta, tb) = (Times::new(a)?, Times::new(b)?);
        // `|ΣU| < 2^{u_bits + b_K} ≤ 2^127` (checked above): the `U` sums
        // on `i128`, exact.
        let runs = halves::pava_in(xs, us, parallel_min, |x: T, u: T| {
            ta.apply(x.into()).plus(tb.apply(u.into()))
        });
        Some(Wide { runs, c })
    }

    /// Blocks on `i128` sums, on 256-bit ones (exact: every `i128` is an
    /// [`I256`]).
    pub(crate) fn widen(runs: &[Run<i128>], c: i128) -> Wide {
        Wide {
            runs: runs
                .iter()
                .map(|r| Run {
                    k: r.k,
                    sy: I256::from_i128(r.sy),
                    su: r.su,
                })
                .collect(),
            c: I256::from_i128(c),
        }
    }
}

/// `|v|` (`v > −2^255`).
fn abs(v: I256) -> I256 {
    if v.is_negative() {
        v.wrapping_neg()
    } else {
        v
    }
}

/// The nearest double of `num 2^exp / den` (`den > 0`; ties to even).
pub(crate) fn nearest(num: I256, den: u64, exp: i64) -> f64 {
    if let Some(v) = num.to_i128() {
        return round::nearest(v, den, exp);
    }
    // |num| ≥ 2^127: its top 128 bits have bit 127 set.
    let Top { top, shift, lost } = abs(num).top();
    let m = round::magnitude(top, lost, den, exp + i64::from(shift));
    if num.is_negative() {
        -m
    } else {
        m
    }
}

/// `s / k` as `⌊s/k⌋` and the fraction of [`Split`] (whose `floor` is not
/// used by [`nearest_plus`]).
fn split(s: I256, k: u64) -> (I256, Split) {
    if k == 1 {
        // A block of one entry (most of them when few particles collide):
        // no division.
        return (s, Split::of(0, Fraction64::ZERO));
    }
    let (floor, rem) = s.div_rem_floor(k);
    let up = if rem == 0 {
        Fraction64::ZERO
    } else {
        Fraction64::new(rem, k)
    };
    (floor, Split::of(0, up))
}

/// [`round::nearest_plus`] for a 256-bit `w`: the nearest double of
/// `(w + f) 2^exp`; `None` where that one answers `None`.
fn nearest_plus(w: I256, split: &Split, exp: i64) -> Option<f64> {
    if let Some(v) = w.to_i128() {
        return round::nearest_plus(v, split, exp);
    }
    // |w + f| = i + g: i = |w|, g = f for w ≥ 0; i = |w| − 1, g = 1 − f
    // for w < 0 and f > 0. With |w| ≥ 2^127, g is only a sticky bit below
    // the last of `i`'s 128 top bits.
    let negative = w.is_negative();
    let mut i = abs(w);
    if negative && !split.whole {
        i = i.wrapping_add(I256::from_i64(-1));
    }
    let Top { top, shift, lost } = i.top();
    let m = round::round_scaled(top, lost || !split.whole, exp + i64::from(shift));
    Some(if negative { -m } else { m })
}

/// The positions of the particles of `runs` (the first one is particle
/// `first`) into `out`: `x_i = (S + k C i) 2^{ey} / (k den_y)`.
pub(crate) fn fill_positions(
    runs: &[Run<I256, i128>],
    first: usize,
    c: I256,
    den_y: u64,
    ey: i64,
    out: &mut [f64],
) -> Option<()> {
    let mut first = u64::try_from(first).ok()?;
    let mut o = 0usize;
    for r in runs {
        let k = r.k;
        let block = out.get_mut(o..o + k as usize)?;
        let den = k.checked_mul(den_y)?;
        let kc = c.wrapping_mul_u64(k);
        let num_at = |i: u64| r.sy.wrapping_add(kc.wrapping_mul_u64(i));
        if den_y == 1 {
            // x_i 2^{−ey} = ⌊S/k⌋ + C i + (S mod k)/k: one division per
            // block.
            let (floor, split) = split(r.sy, k);
            let mut w = floor.wrapping_add(c.wrapping_mul_u64(first));
            for (i, x) in (first..).zip(block.iter_mut()) {
                *x = match nearest_plus(w, &split, ey) {
                    Some(v) => v,
                    None => nearest(num_at(i), den, ey),
                };
                w = w.wrapping_add(c);
            }
        } else {
            for (i, x) in (first..).zip(block.iter_mut()) {
                *x = nearest(num_at(i), den, ey);
            }
        }
        first += k;
        o += k as usize;
    }
    Some(())
}

#[cfg(test)]
mod tests {
    use num_bigint::BigInt;
    use num_rational::BigRational;
    use num_traits::One;

    use super::*;
    use crate::generate::SplitMix64;

    /// `v 2^exp` exactly.
    fn scaled(v: BigRational, exp: i64) -> BigRational {
        let p = BigRational::from_integer(BigInt::one() << exp.unsigned_abs() as usize);
        if exp >= 0 {
            v * p
        } else {
            v / p
        }
    }

    /// The nearest double of `q` by [`crate::rational::nearest_f64`],
    /// `±∞` beyond the range.
    fn oracle(q: &BigRational) -> f64 {
        crate::rational::nearest_f64(q).unwrap_or_else(|| {
            if q > &BigRational::from_integer(0.into()) {
                f64::INFINITY
            } else {
                f64::NEG_INFINITY
            }
        })
    }

    /// A 256-bit value of `bits` bits whose bits below the double's last
    /// place are `tail`: `10…0` (a tie), `10…01`, `01…1`, or random.
    fn value(rng: &mut SplitMix64, bits: u32, tail: u64) -> BigInt {
        let top = BigInt::from((1u64 << 52) | (rng.next_u64() >> 12));
        let below = bits - 53;
        let half = BigInt::one() << (below - 1) as usize;
        let low = match tail {
            0 => half,
            1 => half + 1,
            2 => half - 1,
            _ => {
                let mut r = BigInt::from(0);
                for _ in 0..4 {
                    r = (r << 64usize) + BigInt::from(rng.next_u64());
                }
                r % (BigInt::one() << below as usize)
            }
        };
        (top << below as usize) + low
    }

    /// [`nearest`] and [`nearest_plus`] against the oracle on 256-bit
    /// values built around the double's midpoints (ties to even, one unit
    /// above and below), with and without a fraction, of either sign, and
    /// at exponents where the result is subnormal or infinite.
    #[test]
    fn wide_roundings_are_the_nearest_doubles() {
        let mut rng = SplitMix64::new(256);
        for case in 0..6_000u64 {
            let bits = 100 + (rng.next_u64() % 150) as u32;
            let mut v = value(&mut rng, bits, case % 4);
            if case % 3 == 0 {
                v = -v;
            }
            let w = I256::from_bigint(&v).unwrap();
            let exp = match case % 5 {
                0 => -1100 - i64::from(bits) + (rng.next_u64() % 60) as i64,
                1 => 1000 - i64::from(bits) + (rng.next_u64() % 60) as i64,
                _ => -(i64::from(bits)) + (rng.next_u64() % 40) as i64 - 20,
            };
            let k = match case % 3 {
                0 => 1,
                1 => 3,
                _ => 1 + rng.next_u64() % 1_000_000,
            };
            // `nearest`: w 2^exp / k.
            let q = scaled(BigRational::new(v.clone(), BigInt::from(k)), exp);
            assert_eq!(
                nearest(w, k, exp).to_bits(),
                oracle(&q).to_bits(),
                "{v} 2^{exp} / {k}"
            );
            // `nearest_plus`: (w + rem/k) 2^exp.
            let rem = rng.next_u64() % k;
            let (_, sp) = split(I256::from_i64(rem as i64), k);
            let q = scaled(
                BigRational::from_integer(v.clone()) + BigRational::new(rem.into(), k.into()),
                exp,
            );
            if let Some(x) = nearest_plus(w, &sp, exp) {
                assert_eq!(
                    x.to_bits(),
                    oracle(&q).to_bits(),
                    "{v} + {rem}/{k}, 2^{exp}"
                );
            }
        }
    }
}
