//! The nearest double of `num · 2^exp / den` on machine words: one integer
//! division, no `BigInt`, correctly rounded (to nearest, ties to even),
//! subnormals and overflow included.
//!
//! The magnitude `|num|` is shifted left until its top bit is bit 127, so
//! that the quotient `q = ⌊|num| 2^s / den⌋` has at least 64 significant
//! bits (`den < 2^64`); the remainder is the sticky bit. The value is then
//! `(q + ρ) 2^(exp − s)` with `0 ≤ ρ < 1`, `ρ > 0` exactly when the
//! remainder is not zero, and rounding `q` at the double's last place with
//! `ρ` as sticky bit is rounding the exact value: the dropped part is
//! compared with half a unit of the last place, and it is exactly half only
//! when the dropped bits of `q` are `10…0` and `ρ = 0`.

/// A numerator scaled for one machine division by `den`: `a2 = ⌊a 2^s⌋`.
struct Normalised {
    /// `⌊a 2^s⌋`, of `63 + bits(den)` bits.
    a2: u128,
    /// Bits of `a` shifted out (`s < 0`) were not all zero.
    lost: bool,
    /// The scale `s`.
    s: i64,
}

/// Scales `a > 0` to `63 + bits(den)` bits, so that the quotient
/// `q = ⌊a2/den⌋` lies in `[2^62, 2^64)` (one machine division). For
/// `s < 0` the bits of `a` shifted out are below `q`'s last unit: `a/den`
/// is `(q + ρ) 2^(−s)` with `ρ > 0` exactly when the remainder or those
/// bits are not zero.
fn normalise(a: u128, den: u64) -> Normalised {
    debug_assert!(a > 0 && den > 0);
    let bits_d = 64 - i64::from(den.leading_zeros());
    let bits_a = 128 - i64::from(a.leading_zeros());
    let s = 63 + bits_d - bits_a;
    if s >= 0 {
        Normalised {
            a2: a << s,
            lost: false,
            s,
        }
    } else {
        let r = (-s) as u32;
        Normalised {
            a2: a >> r,
            lost: a & ((1u128 << r) - 1) != 0,
            s,
        }
    }
}

/// The nearest double of `num · 2^exp / den` (round to nearest, ties to
/// even; `±∞` when the value rounds beyond the largest finite double, `0.0`
/// for `num = 0`). `den` must be positive.
pub fn nearest(num: i128, den: u64, exp: i64) -> f64 {
    debug_assert!(den > 0);
    if num == 0 {
        return 0.0;
    }
    let magnitude = magnitude(num.unsigned_abs(), false, den, exp);
    if num < 0 {
        -magnitude
    } else {
        magnitude
    }
}

/// The nearest double of `(a + ρ) 2^exp / den` for `a > 0`, `0 ≤ ρ < 1`,
/// `ρ > 0` exactly when `lost`; `lost` only with bit 127 of `a` set (the
/// top bits of a wider integer).
pub(crate) fn magnitude(a: u128, lost: bool, den: u64, exp: i64) -> f64 {
    debug_assert!(a > 0 && (!lost || a >> 127 == 1));
    if den.is_power_of_two() {
        // Division by a power of two is a shift of the exponent.
        let s = a.leading_zeros();
        round_scaled(
            a << s,
            lost,
            exp - i64::from(s) - i64::from(den.trailing_zeros()),
        )
    } else {
        // `a` has 128 bits when `lost`: `normalise` shifts it right, and
        // `⌊⌊(a + ρ) 2^s⌋ / d⌋ = ⌊a 2^s / d⌋` for `s < 0`.
        let d = u128::from(den);
        let n = normalise(a, den);
        let q = n.a2 / d;
        round_scaled(q, lost || n.lost || n.a2 != q.wrapping_mul(d), exp - n.s)
    }
}

/// A 64-bit divisor prepared for many divisions (one machine division,
/// then two multiplications per quotient): the reciprocal of Möller and
/// Granlund ("Improved division by invariant integers", 2011, algorithm 4).
/// With `d' = d 2^sh` normalised (top bit set) and
/// `v = ⌊(2^128 − 1)/d'⌋ − 2^64`, the quotient of a 128-bit `u` whose high
/// word is below `d'` is an estimate from `v u₁` off by at most two, which
/// two comparisons correct; the remainder comes out with it, so the result
/// is checked exactly (`q d + r = u`, `0 ≤ r < d`).
#[derive(Debug, Clone, Copy)]
pub struct Divisor {
    /// `d`.
    d: u64,
    /// `d' = d 2^sh`, top bit set.
    norm: u64,
    /// `sh`.
    shift: u32,
    /// `v = ⌊(2^128 − 1)/d'⌋ − 2^64`.
    reciprocal: u64,
}

impl Divisor {
    /// `d > 0`: one machine division.
    pub fn new(d: u64) -> Divisor {
        debug_assert!(d > 0);
        let shift = d.leading_zeros();
        let norm = d << shift;
        // (2^128 − 1)/d' lies in (2^64, 2^65): its low word is v.
        let reciprocal = (u128::MAX / u128::from(norm)) as u64;
        Divisor {
            d,
            norm,
            shift,
            reciprocal,
        }
    }

    /// `d`.
    pub fn get(&self) -> u64 {
        self.d
    }

    /// `(⌊u/d⌋, u mod d)` for `u < d 2^64` (the quotient fits 64 bits).
    pub fn div_rem(&self, u: u128) -> (u64, u64) {
        debug_assert!(u < u128::from(self.d) << 64);
        // u 2^sh < d' 2^64: the high word u₁ is below d'.
        let un = u << self.shift;
        let (u1, u0) = ((un >> 64) as u64, un as u64);
        let d = self.norm;
        let p = u128::from(self.reciprocal) * u128::from(u1);
        let est = p.wrapping_add((u128::from(u1) << 64) | u128::from(u0));
        let est = est.wrapping_add(1 << 64);
        let (mut q, lo) = ((est >> 64) as u64, est as u64);
        let mut r = u0.wrapping_sub(q.wrapping_mul(d));
        if r > lo {
            q = q.wrapping_sub(1);
            r = r.wrapping_add(d);
        }
        if r >= d {
            q = q.wrapping_add(1);
            r -= d;
        }
        debug_assert_eq!(u128::from(q) * u128::from(d) + u128::from(r), un);
        (q, r >> self.shift)
    }
}

/// [`nearest`] with a prepared divisor: no machine division.
pub fn nearest_by(num: i128, den: &Divisor, exp: i64) -> f64 {
    let d = den.get();
    if num == 0 || d.is_power_of_two() {
        return nearest(num, d, exp);
    }
    let a = num.unsigned_abs();
    let Normalised { a2, lost, s } = normalise(a, d);
    let (q, rem) = den.div_rem(a2);
    let magnitude = round_scaled(u128::from(q), lost || rem != 0, exp - s);
    if num < 0 {
        -magnitude
    } else {
        magnitude
    }
}

/// The nearest double of `(q + ρ) 2^e` with `q ≥ 2^53` (so that at least
/// one bit of `q` is dropped) and `0 ≤ ρ < 1`, `sticky` telling `ρ > 0`.
pub fn round_scaled(q: u128, sticky: bool, e: i64) -> f64 {
    debug_assert!(q >= 1 << 53);
    let lz = q.leading_zeros();
    // The value lies in [2^top, 2^(top+1)).
    let top = 127 - i64::from(lz) + e;
    if (-1022..=1023).contains(&top) {
        // A normal double: the top 53 bits of q kept, the 75 below (and
        // ρ) dropped; no variable shift but the normalisation.
        let qn = q << lz;
        let kept = (qn >> 75) as u64;
        let rest = qn << 53;
        const HALF: u128 = 1 << 127;
        let up = rest > HALF || (rest == HALF && (sticky || kept & 1 == 1));
        // kept + up ≤ 2^53; a carry into 2^53 moves into the exponent field
        // (to ∞ past 2^1024: the correct rounding there).
        let field = ((top + 1023) as u64) << 52;
        return f64::from_bits(field + (kept - (1 << 52)) + u64::from(up));
    }
    round_slow(q, sticky, e)
}

/// [`round_scaled`] for values that are subnormal or beyond the range.
fn round_slow(q: u128, sticky: bool, e: i64) -> f64 {
    let bits = 128 - i64::from(q.leading_zeros());
    let top = bits - 1 + e;
    if top > 1023 {
        return f64::INFINITY;
    }
    // The last place kept: 53 significant bits, or 2^-1074 for subnormals.
    let last = (top - 52).max(-1074);
    let drop = last - e;
    // `bits ≥ 54`: a normal value drops at least one bit; a subnormal may
    // drop all of them (then the kept part is 0).
    debug_assert!(drop >= 1);
    let (kept, round_up) = if drop > bits {
        // Below half of 2^-1074.
        (0u128, false)
    } else {
        let kept = if drop >= 128 { 0 } else { q >> drop };
        let rest = if drop >= 128 {
            q
        } else {
            q & ((1u128 << drop) - 1)
        };
        let half = 1u128 << (drop - 1);
        let up = rest > half || (rest == half && (sticky || kept & 1 == 1));
        (kept, up)
    };
    let m = kept + u128::from(round_up);
    // m ≤ 2^53: exact as a double; m 2^last is exact (or overflows to ∞
    // when it is 2^1024, the correct rounding there).
    debug_assert!(m <= 1 << 53);
    (m as u64 as f64) * pow2(last)
}

/// A fraction `num / den` in `[0, 1)` to 64 bits: `⌊num 2^64 / den⌋` and
/// whether the rest is not zero.
#[derive(Debug, Clone, Copy)]
pub struct Fraction64 {
    /// The first 64 bits after the binary point.
    pub bits: u64,
    /// The bits beyond are not all zero.
    pub sticky: bool,
}

impl Fraction64 {
    /// `num / den` for `0 ≤ num < den`.
    pub fn new(num: u64, den: u64) -> Fraction64 {
        debug_assert!(num < den);
        let a = u128::from(num) << 64;
        let d = u128::from(den);
        let q = a / d;
        Fraction64 {
            bits: q as u64,
            sticky: a != q.wrapping_mul(d),
        }
    }

    /// Zero.
    pub const ZERO: Fraction64 = Fraction64 {
        bits: 0,
        sticky: false,
    };
}

/// The mean of a block of `k` values with sum `s`, split as `⌊s/k⌋` and
/// the fractions `f = (s mod k)/k` and `1 − f` (for the values below zero).
#[derive(Debug, Clone, Copy)]
pub struct Split {
    /// `⌊s/k⌋`.
    pub floor: i128,
    /// `f`: zero when `k` divides `s`.
    pub up: Fraction64,
    /// `1 − f` when `f > 0` (unused when `f = 0`).
    pub down: Fraction64,
    /// `f = 0`.
    pub whole: bool,
}

impl Split {
    /// `s / k`, `k > 0`: one division.
    pub fn new(s: i128, k: u64) -> Split {
        let ki = i128::from(k);
        let floor = s.div_euclid(ki);
        let rem = s.wrapping_sub(floor.wrapping_mul(ki)) as u64;
        if rem == 0 {
            return Split::of(floor, Fraction64::ZERO);
        }
        Split::of(floor, Fraction64::new(rem, k))
    }

    /// `floor + up`, the fraction `up` given to 64 bits.
    pub(crate) fn of(floor: i128, up: Fraction64) -> Split {
        let whole = up.bits == 0 && !up.sticky;
        if whole {
            return Split {
                floor,
                up,
                down: Fraction64::ZERO,
                whole,
            };
        }
        // f = (B + δ)/2^64, 0 ≤ δ < 1, B ≥ 1 when δ = 0: 1 − f is
        // (!B + (1 − δ))/2^64 when δ > 0, (!B + 1)/2^64 when δ = 0.
        let down = Fraction64 {
            bits: if up.sticky {
                !up.bits
            } else {
                (!up.bits).wrapping_add(1)
            },
            sticky: up.sticky,
        };
        Split {
            floor,
            up,
            down,
            whole,
        }
    }
}

/// The nearest double of `(w + f) 2^exp` for an integer `w` and the
/// fraction `f` of `split` (`split.floor` is not used): no division. `None`
/// when the value is below `2^(exp−1)` in magnitude and not zero, where 64
/// bits of the fraction may not be enough (the caller divides).
pub fn nearest_plus(w: i128, split: &Split, exp: i64) -> Option<f64> {
    // |w + f| = i + g: i = w, g = f for w ≥ 0; i = |w| − 1, g = 1 − f for
    // w < 0 and f > 0.
    let negative = w < 0;
    let (i, g) = match (negative, split.whole) {
        (_, true) => (w.unsigned_abs(), Fraction64::ZERO),
        (false, false) => (w.unsigned_abs(), split.up),
        (true, false) => (w.unsigned_abs() - 1, split.down),
    };
    let magnitude = if i >= 1 << 63 {
        round_scaled(i, g.bits != 0 || g.sticky, exp)
    } else {
        let v = (i << 64) | u128::from(g.bits);
        if v < 1 << 63 {
            return if v == 0 && !g.sticky { Some(0.0) } else { None };
        }
        round_scaled(v, g.sticky, exp - 64)
    };
    Some(if negative { -magnitude } else { magnitude })
}

/// [`nearest_plus`] of `w + m c` for `m = 0, 1, …` into `out`, as long as
/// the values keep the sign and the binade of the first (the rounding is
/// then the same shift of the same kind of integer, done without a
/// normalisation per value); returns how many were written, `0` when the
/// first value is not a normal double above 1 unit (the caller rounds it
/// with [`nearest_plus`] and asks again from the next). `c ≥ 0`.
///
/// With `|w + f| = i + g` (`i` an integer, `g` the fraction) and
/// `2^(b−1) ≤ i < 2^b`, the double keeps 53 bits: for `b ≤ 53` all of `i`
/// and the top `53 − b` bits of `g`, so that whether it rounds up depends
/// on `g` alone (and on the parity of `i` when `b = 53` and `g` is exactly
/// one half); for `b > 53` the top 53 bits of `i`, `g` only a sticky bit.
pub fn nearest_plus_run(w: i128, c: i128, split: &Split, exp: i64, out: &mut [f64]) -> usize {
    const HALF: u64 = 1 << 63;
    let negative = w < 0;
    let (i, g) = match (negative, split.whole) {
        (_, true) => (w.unsigned_abs(), Fraction64::ZERO),
        (false, false) => (w.unsigned_abs(), split.up),
        (true, false) => (w.unsigned_abs() - 1, split.down),
    };
    if i == 0 || c < 0 {
        return 0;
    }
    let b = 128 - i.leading_zeros();
    let top = i64::from(b) - 1 + exp;
    if !(-1022..=1023).contains(&top) {
        return 0;
    }
    // The binade's bounds; the magnitude moves by `c` away from zero for
    // `w ≥ 0`, towards it for `w < 0`.
    let (lo, hi) = (1u128 << (b - 1), u128::MAX >> (128 - b));
    let step = c.unsigned_abs();
    let next = |i: u128| -> Option<u128> {
        let j = if negative {
            i.checked_sub(step)?
        } else {
            i.checked_add(step)?
        };
        (lo..=hi).contains(&j).then_some(j)
    };
    // The sign bit, and the exponent field less the implicit bit: adding
    // the 53-bit kept part (and a carry out of it) gives the double.
    let sign = if negative { 1u64 << 63 } else { 0 };
    let base = (((top + 1023) as u64) << 52) - (1 << 52);
    let mut i = i;
    let mut filled = 0;
    if b <= 53 {
        let s = 53 - b;
        let g_top = if s == 0 { 0 } else { g.bits >> (64 - s) };
        let dropped = g.bits << s;
        let above = dropped > HALF || (dropped == HALF && g.sticky);
        let tie = dropped == HALF && !g.sticky;
        for o in out.iter_mut() {
            let kept = ((i as u64) << s) | g_top;
            let up = above || (tie && kept & 1 == 1);
            *o = f64::from_bits(sign | (base + kept + u64::from(up)));
            filled += 1;
            match next(i) {
                Some(j) => i = j,
                None => break,
            }
        }
    } else {
        let sh = b - 53;
        let mask = (1u128 << sh) - 1;
        let half = 1u128 << (sh - 1);
        let g_nonzero = g.bits != 0 || g.sticky;
        for o in out.iter_mut() {
            let kept = (i >> sh) as u64;
            let rest = i & mask;
            let up = rest > half || (rest == half && (g_nonzero || kept & 1 == 1));
            *o = f64::from_bits(sign | (base + kept + u64::from(up)));
            filled += 1;
            match next(i) {
                Some(j) => i = j,
                None => break,
            }
        }
    }
    filled
}

/// `2^e` as a double, for `−1074 ≤ e ≤ 1023`.
fn pow2(e: i64) -> f64 {
    debug_assert!((-1074..=1023).contains(&e));
    if e >= -1022 {
        f64::from_bits(((e + 1023) as u64) << 52)
    } else {
        f64::from_bits(1u64 << (e + 1074))
    }
}

#[cfg(test)]
pub(super) mod tests {
    use super::*;
    use crate::generate::SplitMix64;
    use num_bigint::BigInt;
    use num_rational::BigRational;
    use num_traits::{One, ToPrimitive};

    /// `num·2^exp / den`, exactly.
    fn exact(num: i128, den: u64, exp: i64) -> BigRational {
        let two = BigRational::from_integer(BigInt::from(2));
        let scale = if exp >= 0 {
            num_traits::pow(two, exp as usize)
        } else {
            BigRational::one() / num_traits::pow(two, (-exp) as usize)
        };
        BigRational::new(BigInt::from(num), BigInt::from(den)) * scale
    }

    /// The oracle: the exactly checked nearest double of the rational
    /// ([`crate::rational::nearest_f64`]), `±∞` where it is beyond range.
    pub(in crate::fast::dyadic) fn oracle(num: i128, den: u64, exp: i64) -> f64 {
        let q = exact(num, den, exp);
        match crate::rational::nearest_f64(&q) {
            Some(f) => f,
            None => {
                let f = q.to_f64().unwrap_or(f64::NAN);
                assert!(f.is_infinite(), "{q}");
                f
            }
        }
    }

    /// A test case `num·2^exp / den` of the roundings.
    pub(in crate::fast::dyadic) struct Quotient {
        pub num: i128,
        pub den: u64,
        pub exp: i64,
    }

    impl Quotient {
        /// Numerators of 1 to 127 bits of either sign, denominators of 1 to
        /// 64 bits, exponents in the normal range and past it (subnormals,
        /// overflow).
        pub(in crate::fast::dyadic) fn random(rng: &mut SplitMix64) -> Quotient {
            let nb = rng.next_u64() % 128;
            let num = (((u128::from(rng.next_u64()) << 64) | u128::from(rng.next_u64()))
                >> (128 - nb.max(1))) as i128;
            let num = if rng.next_u64() % 2 == 0 { num } else { -num };
            let db = rng.next_u64() % 64 + 1;
            let den = (rng.next_u64() >> (64 - db)).max(1);
            let exp = match rng.next_u64() % 4 {
                0 => (rng.next_u64() % 200) as i64 - 100,
                1 => -1074 - (rng.next_u64() % 130) as i64 + 64,
                2 => 1024 - (rng.next_u64() % 130) as i64,
                _ => (rng.next_u64() % 2400) as i64 - 1200,
            };
            Quotient { num, den, exp }
        }
    }

    fn check(num: i128, den: u64, exp: i64) {
        let got = nearest(num, den, exp);
        let want = oracle(num, den, exp);
        assert_eq!(
            got.to_bits(),
            want.to_bits(),
            "{num} 2^{exp} / {den}: {got:e} vs {want:e}"
        );
    }

    /// Random numerators, denominators and exponents of every size, the
    /// ranges of subnormals and of overflow included.
    #[test]
    fn agrees_with_the_exact_nearest_double() {
        let mut rng = SplitMix64::new(0x5eed);
        for _ in 0..20_000 {
            let q = Quotient::random(&mut rng);
            check(q.num, q.den, q.exp);
        }
    }

    /// Exact midpoints between two doubles round to the even one, and one
    /// unit of the remainder more or less decides: the sticky bit counts.
    /// `nearest_plus` on a block's split mean is `nearest` of the fraction.
    #[test]
    fn split_means_round_as_their_fractions() {
        let mut rng = SplitMix64::new(99);
        let mut answered = 0;
        for case in 0..20_000 {
            let k = 1 + rng.next_u64() % if case % 2 == 0 { 7 } else { 1 << 40 };
            let nb = rng.next_u64() % 100;
            let s = ((u128::from(rng.next_u64()) << 64 | u128::from(rng.next_u64()))
                >> (128 - nb.max(1))) as i128;
            let s = if rng.next_u64() % 2 == 0 { s } else { -s };
            let c = (rng.next_u64() >> (rng.next_u64() % 64)) as i128;
            let i = (rng.next_u64() % 1000) as i128;
            let exp = (rng.next_u64() % 400) as i64 - 200;
            let split = Split::new(s, k);
            let w = split.floor + c * i;
            let num = s + i128::from(k) * c * i;
            if let Some(f) = nearest_plus(w, &split, exp) {
                answered += 1;
                assert_eq!(f.to_bits(), oracle(num, k, exp).to_bits(), "{num} / {k}");
            }
        }
        assert!(answered > 19_000, "{answered}");
    }

    /// The values `w + m c + f`, `m < len`, rounded as the positions of a
    /// block are: runs by [`nearest_plus_run`], the rest one by one.
    fn by_runs(w: i128, c: i128, split: &Split, exp: i64, len: usize) -> (Vec<f64>, usize) {
        let mut out = vec![f64::NAN; len];
        let (mut m, mut w, mut in_runs) = (0, w, 0);
        while m < len {
            let mut done = nearest_plus_run(w, c, split, exp, &mut out[m..]);
            in_runs += done;
            if done == 0 {
                out[m] = nearest_plus(w, split, exp).unwrap_or(f64::NAN);
                done = 1;
            }
            m += done;
            w += c * done as i128;
        }
        (out, in_runs)
    }

    /// A random fraction of 64 bits, often with its last set bit where a
    /// rounding looks (ties), the sticky bit random.
    fn random_fraction(rng: &mut SplitMix64) -> Fraction64 {
        let bits = match rng.next_u64() % 4 {
            0 => 0,
            1 => {
                let p = rng.next_u64() % 64;
                (rng.next_u64() >> p << p) | (1 << p)
            }
            2 => 1 << 63,
            _ => rng.next_u64(),
        };
        Fraction64 {
            bits,
            sticky: rng.next_u64() % 2 == 0,
        }
    }

    /// Runs in one binade round as [`nearest_plus`] does, value by value,
    /// on both sides of zero, across binades, near the ends of the normal
    /// range, on ties decided by the sticky bit or by parity; and as the
    /// exact values' nearest doubles on split means.
    #[test]
    fn runs_in_a_binade_round_as_each_value() {
        let mut rng = SplitMix64::new(0x7a1);
        let (mut in_runs, mut values) = (0, 0);
        for case in 0..20_000 {
            let nb = rng.next_u64() % 120;
            let w = ((u128::from(rng.next_u64()) << 64 | u128::from(rng.next_u64()))
                >> (128 - nb.max(1))) as i128;
            let w = if rng.next_u64() % 2 == 0 { w } else { -w };
            let c = match rng.next_u64() % 4 {
                0 => 0,
                1 => 1 + (rng.next_u64() % 4) as i128,
                2 => (rng.next_u64() >> (rng.next_u64() % 64)) as i128,
                _ => 1i128 << (rng.next_u64() % 60),
            };
            let exp = match rng.next_u64() % 4 {
                0 => (rng.next_u64() % 200) as i64 - 100,
                1 => -1022 - (rng.next_u64() % 140) as i64,
                2 => 1024 - (rng.next_u64() % 140) as i64,
                _ => -64 - (rng.next_u64() % 20) as i64,
            };
            let len = 1 + (rng.next_u64() % 40) as usize;
            let split = if case % 2 == 0 {
                Split::of(0, random_fraction(&mut rng))
            } else {
                Split::new((rng.next_u64() % 1000) as i128, 1 + rng.next_u64() % 8)
            };
            let (got, runs) = by_runs(w, c, &split, exp, len);
            in_runs += runs;
            values += len;
            for (m, x) in got.iter().enumerate() {
                let wm = w + c * m as i128;
                let want = nearest_plus(wm, &split, exp).unwrap_or(f64::NAN);
                assert_eq!(
                    x.to_bits(),
                    want.to_bits(),
                    "w {wm}, c {c}, 2^{exp}, {split:?}"
                );
            }
        }
        assert!(in_runs * 2 > values, "{in_runs} of {values} in runs");
        // Against the exact values: a block's positions from its sum.
        for _ in 0..5_000 {
            let k = 1 + rng.next_u64() % 16;
            let s = (rng.next_u64() >> (rng.next_u64() % 64)) as i128 - (1 << 40);
            let c = (rng.next_u64() % 5) as i128;
            let exp = (rng.next_u64() % 200) as i64 - 150;
            let split = Split::new(s, k);
            let (got, _) = by_runs(split.floor, c, &split, exp, 12);
            for (m, x) in got.iter().enumerate() {
                let num = s + i128::from(k) * c * m as i128;
                assert_eq!(x.to_bits(), oracle(num, k, exp).to_bits(), "{num} / {k}");
            }
        }
        // A run stops at the binade's end and the next one starts there.
        let (got, _) = by_runs((1 << 20) - 3, 1, &Split::new(1, 3), -10, 6);
        let want: Vec<f64> = (0..6)
            .map(|m| oracle(3 * ((1 << 20) - 3 + m) + 1, 3, -10))
            .collect();
        assert_eq!(got, want);
        assert_eq!(
            nearest_plus_run((1 << 20) - 3, 1, &Split::new(1, 3), -10, &mut [0.0; 6]),
            3
        );
    }

    /// The prepared divisor gives the machine's quotient and remainder at
    /// the edges (`u` just below `d 2^64`, `d` a power of two, `d = 1`,
    /// `d = 2^64 − 1`) and on random data; `nearest_by` is `nearest`.
    #[test]
    fn prepared_divisors_divide_exactly() {
        let mut rng = SplitMix64::new(0xd1f);
        let mut ds = vec![1u64, 2, 3, 7, 1 << 63, u64::MAX, (1 << 63) + 1, 1_000_000];
        for _ in 0..1_000 {
            ds.push((rng.next_u64() >> (rng.next_u64() % 64)).max(1));
            ds.push((1 << 63) + rng.next_u64() % 256);
            ds.push(u64::MAX - rng.next_u64() % 256);
        }
        for d in ds {
            let div = Divisor::new(d);
            let top = (u128::from(d) << 64) - 1;
            let mut us = vec![0u128, 1, top, top - 1, u128::from(d), u128::from(d) - 1];
            for _ in 0..50 {
                let u = (u128::from(rng.next_u64()) << 64 | u128::from(rng.next_u64())) % (top + 1);
                us.push(u >> (rng.next_u64() % 128));
                // Exact multiples with a large quotient: the estimate is
                // then one short with a remainder of exactly d (the second
                // correction's equality case).
                let q = u128::from(u64::MAX - rng.next_u64() % 16);
                let q2 = u128::from(rng.next_u64());
                let d = u128::from(d);
                us.extend([q * d, q2 * d, q * d + d - 1, q2 * d + d - 1]);
            }
            for u in us {
                let want = ((u / u128::from(d)) as u64, (u % u128::from(d)) as u64);
                assert_eq!(div.div_rem(u), want, "{u} / {d}");
            }
            for _ in 0..20 {
                let nb = rng.next_u64() % 127 + 1;
                let num = ((u128::from(rng.next_u64()) << 64 | u128::from(rng.next_u64()))
                    >> (128 - nb)) as i128;
                let num = if rng.next_u64() % 2 == 0 { num } else { -num };
                let exp = (rng.next_u64() % 2400) as i64 - 1200;
                assert_eq!(
                    nearest_by(num, &div, exp).to_bits(),
                    nearest(num, d, exp).to_bits(),
                    "{num} 2^{exp} / {d}"
                );
            }
        }
        // Midpoints whose remainder alone breaks the tie, through the oracle.
        for d in [
            (1u64 << 63) - 25,
            3 << 61 | 1,
            1_000_000_007 << 32 | 5,
            12_345,
        ] {
            let div = Divisor::new(d);
            for k in 0..20i128 {
                let mid = (1i128 << 53) + 2 * k + 1;
                let base = (mid * i128::from(d)) << 9;
                for num in [base + 1, base - 1, base, -base - 1] {
                    let want = oracle(num, d, -53 - 9);
                    assert_eq!(nearest_by(num, &div, -62).to_bits(), want.to_bits());
                }
            }
        }
    }

    #[test]
    fn ties_go_to_even_and_the_remainder_breaks_them() {
        // (2^53 + 1) / 2^53 · 2 ... : midpoints between 1 + k 2^-52 and the
        // next double, written with a non-power-of-two denominator.
        for k in 0..50i128 {
            let mid = (1i128 << 53) + 2 * k + 1; // odd: a midpoint at scale 2^-53
            for den in [3u64, 5, 7, 1 << 20, 12_345] {
                let d = i128::from(den);
                check(mid * d, den, -53);
                check(mid * d + 1, den, -53);
                check(mid * d - 1, den, -53);
                check(-mid * d, den, -53);
                // Subnormal midpoints.
                check((2 * k + 1) * d, den, -1075);
                check((2 * k + 1) * d + 1, den, -1075);
            }
        }
        // A remainder below the quotient's last bit: the dropped bits of the
        // quotient are exactly 10…0 and only the sticky bit says the value
        // is above (or below) the midpoint.
        for d in [(1u64 << 63) - 25, 3 << 61 | 1, 1_000_000_007 << 32 | 5] {
            for k in 0..20i128 {
                let mid = (1i128 << 53) + 2 * k + 1;
                let base = (mid * i128::from(d)) << 9;
                for num in [base + 1, base - 1, base, -base - 1] {
                    check(num, d, -53 - 9);
                }
            }
        }
        assert_eq!(nearest(3, 2, -1075), f64::from_bits(1)); // 3/4 of the least
        assert_eq!(nearest(1, 2, -1074), 0.0); // half the least subnormal: even
        assert_eq!(nearest(1, 1, 1024), f64::INFINITY);
        assert_eq!(nearest(-1, 1, 1024), f64::NEG_INFINITY);
        assert_eq!(nearest(i128::MIN, 1, 0), -(2f64.powi(127)));
        assert_eq!(
            nearest(i128::MAX, u64::MAX, 0),
            oracle(i128::MAX, u64::MAX, 0)
        );
        assert_eq!(nearest(0, 7, 5), 0.0);
    }
}
