//! A signed 256-bit integer for the exact kernels, just wide enough for
//! 30-digit decimal data at N = 10^7.
//!
//! Arithmetic is two's complement modulo `2^256` (wrapping), which is exact
//! whenever the true result lies in `[−2^255, 2^255)`. The callers prove that
//! before they use it: [`crate::fast::kernel`] bounds every sum and cross product of
//! its loop by the bit lengths of the data and takes this
//! width only when the bound is below `2^254`. Nothing here checks overflow:
//! that is the callers' obligation, stated where they take this path.

use std::cmp::Ordering;

use num_bigint::{BigInt, BigUint, Sign};
use num_traits::Signed;

/// A signed 256-bit integer: four little-endian 64-bit limbs, two's
/// complement.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct I256([u64; 4]);

impl I256 {
    /// Zero.
    pub const ZERO: I256 = I256([0; 4]);

    /// From an `i128` (sign-extended).
    pub fn from_i128(v: i128) -> Self {
        let ext = if v < 0 { u64::MAX } else { 0 };
        I256([v as u64, (v >> 64) as u64, ext, ext])
    }

    /// From an `i64` (sign-extended).
    pub fn from_i64(v: i64) -> Self {
        Self::from_i128(i128::from(v))
    }

    /// From a `BigInt` whose magnitude is below `2^255`; `None` otherwise.
    pub fn from_bigint(v: &BigInt) -> Option<Self> {
        if v.bits() > 255 {
            return None;
        }
        let mut limbs = [0u64; 4];
        for (l, d) in limbs.iter_mut().zip(v.magnitude().iter_u64_digits()) {
            *l = d;
        }
        let m = I256(limbs);
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
    pub fn is_negative(self) -> bool {
        (self.0[3] as i64) < 0
    }

    /// `−v` (wrapping).
    pub fn wrapping_neg(self) -> Self {
        let mut out = [0u64; 4];
        let mut carry = true;
        for (o, &l) in out.iter_mut().zip(&self.0) {
            let (v, c) = (!l).overflowing_add(u64::from(carry));
            *o = v;
            carry = c;
        }
        I256(out)
    }

    /// `a + b` (wrapping).
    #[inline]
    pub fn wrapping_add(self, o: Self) -> Self {
        let mut out = [0u64; 4];
        let mut carry = 0u64;
        for ((r, &a), &b) in out.iter_mut().zip(&self.0).zip(&o.0) {
            let (s1, c1) = a.overflowing_add(b);
            let (s2, c2) = s1.overflowing_add(carry);
            *r = s2;
            carry = u64::from(c1) + u64::from(c2);
        }
        I256(out)
    }

    /// `a · k` for an unsigned 64-bit `k` (wrapping).
    #[inline]
    pub fn wrapping_mul_u64(self, k: u64) -> Self {
        let mut out = [0u64; 4];
        let mut carry = 0u128;
        for (r, &a) in out.iter_mut().zip(&self.0) {
            let p = u128::from(a) * u128::from(k) + carry;
            *r = p as u64;
            carry = p >> 64;
        }
        I256(out)
    }

    /// `a · b` exactly, for any two `i128` (`|a b| ≤ 2^254` is in range):
    /// the 256-bit products of the kernel and of the merge's time
    /// comparisons.
    #[inline]
    pub fn product(a: i128, b: i128) -> Self {
        Self::from_i128(a).wrapping_mul(Self::from_i128(b))
    }

    /// `a · b` (wrapping): the low 256 bits of the product, which is the
    /// exact product when it lies in range (two's complement multiplication
    /// is the same modulo `2^256` for signed and unsigned operands).
    #[inline]
    pub fn wrapping_mul(self, o: Self) -> Self {
        let mut out = [0u64; 4];
        for i in 0..4 {
            let mut carry = 0u128;
            for j in 0..4 - i {
                let p = u128::from(self.0[i]) * u128::from(o.0[j]) + u128::from(out[i + j]) + carry;
                out[i + j] = p as u64;
                carry = p >> 64;
            }
        }
        I256(out)
    }
}

impl Ord for I256 {
    fn cmp(&self, o: &Self) -> Ordering {
        (self.0[3] as i64)
            .cmp(&(o.0[3] as i64))
            .then_with(|| self.0[2].cmp(&o.0[2]))
            .then_with(|| self.0[1].cmp(&o.0[1]))
            .then_with(|| self.0[0].cmp(&o.0[0]))
    }
}

impl PartialOrd for I256 {
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

    /// Every operation agrees with `BigInt` on random operands whose exact
    /// results stay in range, including the edges `±(2^255 − 1)`.
    #[test]
    fn agrees_with_bigint() {
        let mut rng = SplitMix64::new(7);
        let edge: BigInt = (BigInt::from(1) << 255u32) - 1;
        for e in [
            edge.clone(),
            -edge.clone(),
            BigInt::from(-1),
            BigInt::from(0),
        ] {
            let w = I256::from_bigint(&e).unwrap();
            assert_eq!(w.to_bigint(), e);
        }
        assert!(I256::from_bigint(&(BigInt::from(1) << 255u32)).is_none());
        for _ in 0..20_000 {
            let a = random_big(&mut rng, 127);
            let b = random_big(&mut rng, 127);
            let (wa, wb) = (
                I256::from_bigint(&a).unwrap(),
                I256::from_bigint(&b).unwrap(),
            );
            assert_eq!(wa.wrapping_mul(wb).to_bigint(), &a * &b);
            assert_eq!(wa.wrapping_add(wb).to_bigint(), &a + &b);
            assert_eq!(wa.cmp(&wb), a.cmp(&b));
            let k = rng.next_u64() >> (rng.next_u64() % 64);
            assert_eq!(wa.wrapping_mul_u64(k).to_bigint(), &a * BigInt::from(k));
            let c = random_big(&mut rng, 254);
            let d = random_big(&mut rng, 254);
            let (wc, wd) = (
                I256::from_bigint(&c).unwrap(),
                I256::from_bigint(&d).unwrap(),
            );
            assert_eq!(wc.wrapping_add(wd).to_bigint(), &c + &d);
            assert_eq!(wc.cmp(&wd), c.cmp(&d));
            assert_eq!(wc.wrapping_neg().to_bigint(), -&c);
            let small = random_big(&mut rng, 60);
            let ws = I256::from_bigint(&small).unwrap();
            if c.bits() + small.bits() <= 254 {
                assert_eq!(wc.wrapping_mul(ws).to_bigint(), &c * &small);
            }
        }
        for v in [i128::MIN, i128::MAX, -1, 0, 1] {
            assert_eq!(I256::from_i128(v).to_bigint(), BigInt::from(v));
            for w in [i128::MIN, i128::MAX, -1, 0, 1, 1 << 64] {
                assert_eq!(I256::product(v, w).to_bigint(), BigInt::from(v) * w);
            }
        }
    }
}
