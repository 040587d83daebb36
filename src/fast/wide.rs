//! Fixed-width signed integers for the exact kernels: [`I256`], just wide
//! enough for 30-digit decimal data at N = 10^7, and [`I512`], for
//! 100-digit decimal data — one const-generic type [`Int`] of `L` 64-bit
//! limbs, so both widths share every line.
//!
//! Arithmetic is two's complement modulo `2^(64L)` (wrapping), which is
//! exact whenever the true result lies in `[−2^(64L−1), 2^(64L−1))`. The
//! callers prove that before they use it: [`crate::fast::kernel`] bounds
//! every sum and cross product of its loop by the bit lengths of the data
//! and takes a width only when the bound is below `2^(64L−1)`. Nothing here
//! checks overflow: that is the callers' obligation, stated where they take
//! this path.

use std::cmp::Ordering;

use num_bigint::{BigInt, BigUint, Sign};
use num_traits::Signed;

/// A signed integer of `L` little-endian 64-bit limbs, two's complement.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Int<const L: usize>([u64; L]);

/// A signed 256-bit integer.
pub type I256 = Int<4>;

/// A signed 512-bit integer.
pub type I512 = Int<8>;

impl<const L: usize> Default for Int<L> {
    fn default() -> Self {
        Self::ZERO
    }
}

impl<const L: usize> Int<L> {
    /// Zero.
    pub const ZERO: Self = Int([0; L]);

    /// The width in bits, `64 L`.
    pub const BITS: u64 = 64 * L as u64;

    /// From an `i128` (sign-extended; `L ≥ 2`).
    pub fn from_i128(v: i128) -> Self {
        let ext = if v < 0 { u64::MAX } else { 0 };
        let mut limbs = [ext; L];
        limbs[0] = v as u64;
        limbs[1] = (v >> 64) as u64;
        Int(limbs)
    }

    /// From a `u128` (`L ≥ 3`, so that the value stays non-negative).
    pub fn from_u128(v: u128) -> Self {
        debug_assert!(L >= 3);
        let mut limbs = [0u64; L];
        limbs[0] = v as u64;
        limbs[1] = (v >> 64) as u64;
        Int(limbs)
    }

    /// From an `i64` (sign-extended).
    pub fn from_i64(v: i64) -> Self {
        Self::from_i128(i128::from(v))
    }

    /// The same value in `M` limbs: sign-extended when `M ≥ L`, the low
    /// `M` limbs otherwise (the same value when it fits).
    #[inline]
    pub fn resize<const M: usize>(self) -> Int<M> {
        let ext = if self.is_negative() { u64::MAX } else { 0 };
        let mut limbs = [ext; M];
        for (o, &l) in limbs.iter_mut().zip(&self.0) {
            *o = l;
        }
        Int(limbs)
    }

    /// From a `BigInt` whose magnitude is below `2^(64L−1)`; `None`
    /// otherwise.
    pub fn from_bigint(v: &BigInt) -> Option<Self> {
        if v.bits() > Self::BITS - 1 {
            return None;
        }
        let mut limbs = [0u64; L];
        for (l, d) in limbs.iter_mut().zip(v.magnitude().iter_u64_digits()) {
            *l = d;
        }
        let m = Int(limbs);
        Some(if v.is_negative() { m.wrapping_neg() } else { m })
    }

    /// The value as a `BigInt`.
    pub fn to_bigint(self) -> BigInt {
        let (sign, mag) = if self.is_negative() {
            (Sign::Minus, self.wrapping_neg())
        } else {
            (Sign::Plus, self)
        };
        let digits: Vec<u32> = mag
            .0
            .iter()
            .flat_map(|&l| [l as u32, (l >> 32) as u32])
            .collect();
        BigInt::from_biguint(sign, BigUint::new(digits))
    }

    /// `v < 0`.
    #[inline]
    pub fn is_negative(self) -> bool {
        (self.0[L - 1] as i64) < 0
    }

    /// `−v` (wrapping).
    #[inline]
    pub fn wrapping_neg(self) -> Self {
        let mut out = [0u64; L];
        let mut carry = true;
        for (o, &l) in out.iter_mut().zip(&self.0) {
            let (v, c) = (!l).overflowing_add(u64::from(carry));
            *o = v;
            carry = c;
        }
        Int(out)
    }

    /// `a + b` (wrapping).
    #[inline]
    pub fn wrapping_add(self, o: Self) -> Self {
        let mut out = [0u64; L];
        let mut carry = false;
        for ((r, &a), &b) in out.iter_mut().zip(&self.0).zip(&o.0) {
            let (s1, c1) = a.overflowing_add(b);
            let (s2, c2) = s1.overflowing_add(u64::from(carry));
            *r = s2;
            carry = c1 | c2;
        }
        Int(out)
    }

    /// `a · k` for an unsigned 64-bit `k` (wrapping).
    #[inline]
    pub fn wrapping_mul_u64(self, k: u64) -> Self {
        let mut out = [0u64; L];
        let mut carry = 0u128;
        for (r, &a) in out.iter_mut().zip(&self.0) {
            let p = u128::from(a) * u128::from(k) + carry;
            *r = p as u64;
            carry = p >> 64;
        }
        Int(out)
    }

    /// `a · k` for a signed 64-bit `k` (wrapping).
    #[inline]
    pub fn wrapping_mul_i64(self, k: i64) -> Self {
        let p = self.wrapping_mul_u64(k.unsigned_abs());
        if k < 0 {
            p.wrapping_neg()
        } else {
            p
        }
    }

    /// `a · b` exactly, for any two `i128` (`|a b| ≤ 2^254` is in range
    /// from 256 bits on): the 256-bit products of the merge's time
    /// comparisons.
    #[inline]
    pub fn product(a: i128, b: i128) -> Self {
        Self::from_i128(a).wrapping_mul(Self::from_i128(b))
    }

    /// `a · b` (wrapping): the low `64 L` bits of the product, which is the
    /// exact product when it lies in range (two's complement multiplication
    /// is the same modulo `2^(64L)` for signed and unsigned operands). The
    /// rows of `a`'s zero limbs are skipped: a small non-negative `a` (the
    /// kernel's scale factors) costs one row per significant limb.
    #[inline]
    pub fn wrapping_mul(self, o: Self) -> Self {
        let mut out = [0u64; L];
        for i in 0..L {
            let ai = self.0[i];
            if ai == 0 {
                continue;
            }
            let mut carry = 0u128;
            for j in 0..L - i {
                let p = u128::from(ai) * u128::from(o.0[j]) + u128::from(out[i + j]) + carry;
                out[i + j] = p as u64;
                carry = p >> 64;
            }
        }
        Int(out)
    }
}

/// The top bits of a non-negative [`Int`]: the value is
/// `(top + ρ) 2^shift` with `0 ≤ ρ < 1`, `ρ > 0` exactly when `lost`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Top {
    /// The value shifted right by `shift` bits: all of it when it fits
    /// 128 bits (`shift = 0`), else its top 128 bits (bit 127 set).
    pub top: u128,
    /// The bits shifted out.
    pub shift: u32,
    /// Some bit shifted out is not zero.
    pub lost: bool,
}

impl<const L: usize> Int<L> {
    /// `v 2^j` (wrapping), `j < 64 L`.
    #[inline]
    pub fn wrapping_shl(self, j: u32) -> Self {
        debug_assert!(u64::from(j) < Self::BITS);
        let (limbs, bits) = ((j / 64) as usize, j % 64);
        let mut out = [0u64; L];
        if limbs >= L {
            return Int(out);
        }
        if bits == 0 {
            out[limbs..].copy_from_slice(&self.0[..L - limbs]);
        } else {
            // Limb `i` of the result takes the low bits of limb `i − limbs`
            // and the high bits of the limb below it.
            out[limbs] = self.0[0] << bits;
            for (o, pair) in out[limbs + 1..].iter_mut().zip(self.0.windows(2)) {
                *o = (pair[1] << bits) | (pair[0] >> (64 - bits));
            }
        }
        Int(out)
    }

    /// The value as an `i128` when it fits.
    #[inline]
    pub fn to_i128(self) -> Option<i128> {
        let low = i128::from(self.0[0]) | (i128::from(self.0[1]) << 64);
        let ext = if low < 0 { u64::MAX } else { 0 };
        self.0[2..].iter().all(|&l| l == ext).then_some(low)
    }

    /// Bits of `|v|` (0 for 0; `v > −2^(64L−1)`).
    pub fn magnitude_bits(self) -> u64 {
        let m = if self.is_negative() {
            self.wrapping_neg()
        } else {
            self
        };
        m.0.iter().rposition(|&l| l != 0).map_or(0, |i| {
            64 * i as u64 + u64::from(64 - m.0[i].leading_zeros())
        })
    }

    /// [`Top`] of `v ≥ 0`.
    pub fn top(self) -> Top {
        debug_assert!(!self.is_negative());
        let bits = self.magnitude_bits();
        if bits <= 128 {
            let top = u128::from(self.0[0]) | (u128::from(self.0[1]) << 64);
            return Top {
                top,
                shift: 0,
                lost: false,
            };
        }
        let shift = (bits - 128) as u32;
        let (limbs, sh) = ((shift / 64) as usize, shift % 64);
        let limb = |i: usize| self.0.get(i).copied().unwrap_or(0);
        let word = |i: usize| -> u64 {
            if sh == 0 {
                limb(i)
            } else {
                (limb(i) >> sh) | (limb(i + 1) << (64 - sh))
            }
        };
        let top = u128::from(word(limbs)) | (u128::from(word(limbs + 1)) << 64);
        let low_limbs = self.0[..limbs].iter().any(|&l| l != 0);
        let low_bits = sh != 0 && limb(limbs) & ((1u64 << sh) - 1) != 0;
        Top {
            top,
            shift,
            lost: low_limbs || low_bits,
        }
    }

    /// `(⌊v/d⌋, v mod d)` for `d > 0`: the floor quotient and the
    /// remainder in `[0, d)` (for `v > −2^(64L−1)`).
    pub fn div_rem_floor(self, d: u64) -> (Self, u64) {
        debug_assert!(d > 0);
        let negative = self.is_negative();
        let m = if negative { self.wrapping_neg() } else { self };
        let mut q = [0u64; L];
        let mut r = 0u128;
        for i in (0..L).rev() {
            let cur = (r << 64) | u128::from(m.0[i]);
            q[i] = (cur / u128::from(d)) as u64;
            r = cur % u128::from(d);
        }
        let (q, r) = (Int(q), r as u64);
        if !negative {
            return (q, r);
        }
        // −m = −q d − r = −(q + 1) d + (d − r).
        if r == 0 {
            (q.wrapping_neg(), 0)
        } else {
            (q.wrapping_add(Int::from_i64(1)).wrapping_neg(), d - r)
        }
    }
}

impl<const L: usize> From<i128> for Int<L> {
    #[inline]
    fn from(v: i128) -> Self {
        Self::from_i128(v)
    }
}

impl<const L: usize> From<i64> for Int<L> {
    #[inline]
    fn from(v: i64) -> Self {
        Self::from_i64(v)
    }
}

impl<const L: usize> Ord for Int<L> {
    #[inline]
    fn cmp(&self, o: &Self) -> Ordering {
        let top = (self.0[L - 1] as i64).cmp(&(o.0[L - 1] as i64));
        if top != Ordering::Equal {
            return top;
        }
        for i in (0..L - 1).rev() {
            let c = self.0[i].cmp(&o.0[i]);
            if c != Ordering::Equal {
                return c;
            }
        }
        Ordering::Equal
    }
}

impl<const L: usize> PartialOrd for Int<L> {
    fn partial_cmp(&self, o: &Self) -> Option<Ordering> {
        Some(self.cmp(o))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::SplitMix64;

    fn random_big(rng: &mut SplitMix64, max_bits: u64) -> BigInt {
        let b = rng.next_u64() % (max_bits + 1);
        let mut v = BigInt::from(0);
        let mut have = 0;
        while have < b {
            v = (v << 64u32) + BigInt::from(rng.next_u64());
            have += 64;
        }
        let v: BigInt = v >> ((have - b.min(have)) as usize);
        if rng.next_u64() % 2 == 0 {
            -v
        } else {
            v
        }
    }

    /// Every operation of `Int<L>` agrees with `BigInt` on random operands
    /// whose exact results stay in range, including the edges
    /// `±(2^(64L−1) − 1)`; `2^(64L−1)` is refused.
    fn agrees_with_bigint<const L: usize>(seed: u64) {
        let w = Int::<L>::BITS;
        let mut rng = SplitMix64::new(seed);
        let edge: BigInt = (BigInt::from(1) << (w - 1)) - 1;
        let of = |v: &BigInt| Int::<L>::from_bigint(v).unwrap();
        for e in [
            edge.clone(),
            -edge.clone(),
            BigInt::from(-1),
            BigInt::from(0),
        ] {
            assert_eq!(of(&e).to_bigint(), e);
        }
        assert!(Int::<L>::from_bigint(&(BigInt::from(1) << (w - 1))).is_none());
        assert!(Int::<L>::from_bigint(&-(BigInt::from(1) << (w - 1))).is_none());
        // The sum and the product right at the edge.
        let half: BigInt = BigInt::from(1) << (w - 2);
        assert_eq!(
            of(&half).wrapping_add(of(&(&half - 1))).to_bigint(),
            edge.clone()
        );
        let root: BigInt = (BigInt::from(1) << ((w - 2) / 2)) + 1;
        let sq = &root * &root;
        assert!(sq.bits() == w - 1);
        assert_eq!(of(&root).wrapping_mul(of(&root)).to_bigint(), sq);
        assert_eq!(of(&-&root).wrapping_mul(of(&root)).to_bigint(), -&sq);
        for _ in 0..10_000 {
            let a = random_big(&mut rng, w / 2 - 1);
            let b = random_big(&mut rng, w / 2 - 1);
            let (wa, wb) = (of(&a), of(&b));
            assert_eq!(wa.wrapping_mul(wb).to_bigint(), &a * &b);
            assert_eq!(wa.wrapping_add(wb).to_bigint(), &a + &b);
            assert_eq!(wa.cmp(&wb), a.cmp(&b));
            let k = rng.next_u64() >> (rng.next_u64() % 64);
            assert_eq!(wa.wrapping_mul_u64(k).to_bigint(), &a * BigInt::from(k));
            let k = k as i64;
            assert_eq!(wa.wrapping_mul_i64(k).to_bigint(), &a * BigInt::from(k));
            let c = random_big(&mut rng, w - 2);
            let d = random_big(&mut rng, w - 2);
            let (wc, wd) = (of(&c), of(&d));
            assert_eq!(wc.wrapping_add(wd).to_bigint(), &c + &d);
            assert_eq!(wc.cmp(&wd), c.cmp(&d));
            assert_eq!(wc.partial_cmp(&wd), Some(c.cmp(&d)));
            assert_eq!(wc.wrapping_neg().to_bigint(), -&c);
            assert_eq!(wc.resize::<16>().to_bigint(), c);
            if c.bits() < 255 {
                assert_eq!(wc.resize::<4>().to_bigint(), c);
            }
            let small = random_big(&mut rng, 60);
            let ws = of(&small);
            if c.bits() + small.bits() < w {
                assert_eq!(wc.wrapping_mul(ws).to_bigint(), &c * &small);
                assert_eq!(ws.wrapping_mul(wc).to_bigint(), &c * &small);
            }
        }
        for v in [i128::MIN, i128::MAX, -1, 0, 1] {
            assert_eq!(Int::<L>::from_i128(v).to_bigint(), BigInt::from(v));
            for u in [i128::MIN, i128::MAX, -1, 0, 1, 1 << 64] {
                assert_eq!(Int::<L>::product(v, u).to_bigint(), BigInt::from(v) * u);
            }
        }
    }

    /// The shift, the conversion, the top bits and the floor division
    /// against `BigInt` on random values of every length.
    #[test]
    fn shifts_tops_and_floor_division_agree_with_bigint() {
        let mut rng = SplitMix64::new(38);
        for case in 0..20_000 {
            let v = random_big(&mut rng, 250);
            let w = I256::from_bigint(&v).unwrap();
            let j = (rng.next_u64() % 256) as u32;
            if v.bits() + u64::from(j) < 255 {
                assert_eq!(
                    w.wrapping_shl(j).to_bigint(),
                    &v << j as usize,
                    "{v} << {j}"
                );
            }
            assert_eq!(w.to_i128(), num_traits::ToPrimitive::to_i128(&v));
            assert_eq!(w.magnitude_bits(), v.bits());
            let u = rng.next_u64() as u128 * rng.next_u64() as u128;
            assert_eq!(I256::from_u128(u).to_bigint(), BigInt::from(u));
            let d = match case % 3 {
                0 => 1 + rng.next_u64() % 7,
                1 => 1 + (rng.next_u64() >> (rng.next_u64() % 64)),
                _ => u64::MAX - rng.next_u64() % 3,
            };
            let (q, r) = w.div_rem_floor(d);
            let db = BigInt::from(d);
            let want_q = num_integer::Integer::div_floor(&v, &db);
            assert_eq!(q.to_bigint(), want_q, "{v} / {d}");
            assert_eq!(BigInt::from(r), &v - &want_q * &db);
            let a = v.abs();
            let t = I256::from_bigint(&a).unwrap().top();
            let back = BigInt::from(t.top) << t.shift as usize;
            assert!(back <= a && &a - &back < (BigInt::from(1) << t.shift as usize));
            assert_eq!(t.lost, back != a);
            assert!(t.shift == 0 || t.top >> 127 == 1);
        }
    }

    #[test]
    fn i256_agrees_with_bigint() {
        agrees_with_bigint::<4>(7);
    }

    #[test]
    fn i512_agrees_with_bigint() {
        agrees_with_bigint::<8>(8);
    }
}
