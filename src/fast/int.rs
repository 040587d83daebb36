//! The integer helpers every fast engine shares, written once: the gcd and
//! the reduction of an integer fraction to lowest terms, checked machine
//! products, the narrowing of a column of integers to a smaller width, and
//! the bound on products of adjacent block sizes that both width choices
//! (the kernel's [`crate::fast::kernel::Width`], the merge's word size) start
//! from. The 256-bit products are [`crate::fast::wide::I256`]'s.

use num_bigint::BigInt;
use num_integer::Integer;
use num_rational::BigRational;
use num_traits::Zero;

/// `gcd(a, b)` (`gcd(0, b) = b`), on 64-bit words when both fit.
#[inline]
pub(crate) fn gcd(a: u128, b: u128) -> u128 {
    match (u64::try_from(a), u64::try_from(b)) {
        (Ok(a), Ok(b)) => u128::from(a.gcd(&b)),
        _ => a.gcd(&b),
    }
}

/// `num / den` in lowest terms (`den > 0`), reduced on `i128`.
pub(crate) fn ratio(num: i128, den: i128) -> BigRational {
    let g = gcd(num.unsigned_abs(), den.unsigned_abs());
    if g == 0 {
        return BigRational::zero();
    }
    // `g` divides both and is at most `|den| ≤ i128::MAX`.
    let g = g as i128;
    BigRational::new_raw(BigInt::from(num / g), BigInt::from(den / g))
}

/// `num / (k d)` in lowest terms (`k, d > 0`; `d_small` is `d` when it fits
/// `i128`): reduced on `i128` when `k d` fits, by `BigRational::new`
/// otherwise.
pub(crate) fn ratio_over(num: i128, k: i128, d: &BigInt, d_small: Option<i128>) -> BigRational {
    match d_small.and_then(|d| d.checked_mul(k)) {
        Some(den) => ratio(num, den),
        None => crate::gcd::ratio(BigInt::from(num), d * BigInt::from(k)),
    }
}

/// `a · b` checked, with a fast path for factors that fit `i64`.
pub(crate) trait MulSmall: Sized {
    /// The product, `None` on overflow.
    fn mul_small(self, b: Self) -> Option<Self>;
}

impl MulSmall for i128 {
    #[inline]
    fn mul_small(self, b: i128) -> Option<i128> {
        match (i64::try_from(self), i64::try_from(b)) {
            // |a|, |b| ≤ 2^63: the product is at most 2^126, the wrapping
            // product is the exact one.
            (Ok(a), Ok(b)) => Some(i128::from(a).wrapping_mul(i128::from(b))),
            _ => self.checked_mul(b),
        }
    }
}

/// The column `v` in a narrower type, when every value fits it (`narrow`
/// says whether one does): the narrowest-width choice of both engines.
pub(crate) fn narrowed<T, U>(v: &[T], narrow: impl Fn(&T) -> Option<U>) -> Option<Vec<U>> {
    v.iter().map(narrow).collect()
}

/// `max(N, ⌊N²/4⌋)`: every block size `k ≤ N` and every product of the
/// sizes of two adjacent blocks `k_a k_b ≤ ⌊N²/4⌋` (`k_a + k_b ≤ N`) is at
/// most this. The width bounds of the kernel and of the merge both start
/// here.
pub(crate) fn pair_bound(n: usize) -> u128 {
    let n = n as u128;
    n.max(n * n / 4)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::SplitMix64;

    #[test]
    fn reduction_equals_bigrational() {
        let mut rng = SplitMix64::new(13);
        for _ in 0..5000 {
            let num = (rng.next_u64() as i64 >> (rng.next_u64() % 64)) as i128
                * (rng.next_u64() % 1000) as i128;
            let k = 1 + (rng.next_u64() % 50) as i128;
            let d = 1 + (rng.next_u64() >> (rng.next_u64() % 64)) as i128;
            let want = BigRational::new(BigInt::from(num), BigInt::from(d * k));
            let big_d = BigInt::from(d);
            assert_eq!(ratio_over(num, k, &big_d, Some(d)), want);
            assert_eq!(ratio_over(num, k, &big_d, None), want);
            assert_eq!(ratio(num, d * k), want);
            let (a, b) = (num.unsigned_abs(), d.unsigned_abs());
            assert_eq!(
                BigInt::from(gcd(a, b)),
                BigInt::from(a).gcd(&BigInt::from(b))
            );
        }
        assert_eq!(gcd(0, 6), 6);
        assert_eq!(gcd(1 << 100, 3 << 70), 1 << 70);
        assert_eq!(pair_bound(1), 1);
        assert_eq!(pair_bound(5), 6);
        assert_eq!(
            narrowed(&[1i128, -3, 1 << 62], |v| i64::try_from(*v).ok()),
            Some(vec![1i64, -3, 1 << 62])
        );
        assert_eq!(narrowed(&[1i128 << 63], |v| i64::try_from(*v).ok()), None);
    }

    /// `pair_bound(N)` is the largest block size or product of two adjacent
    /// block sizes: `max(N, max_{a + b ≤ N} a b)`, no more, no less.
    #[test]
    fn pair_bound_is_the_largest_pair_product() {
        for n in 1..200usize {
            let pairs = (1..n).map(|a| a * (n - a)).max().unwrap_or(0);
            assert_eq!(pair_bound(n), n.max(pairs) as u128, "N = {n}");
        }
    }

    /// Checked products agree with the exact product: `Some` exactly when
    /// it fits `i128`, on both paths (factors within `i64` and beyond).
    #[test]
    fn checked_products_are_exact() {
        let mut rng = SplitMix64::new(29);
        for _ in 0..5000 {
            let mut v = || {
                (rng.next_u64() as i128 | (rng.next_u64() as i128) << 64) >> (rng.next_u64() % 128)
            };
            let (a, b) = (v(), v());
            let exact = BigInt::from(a) * BigInt::from(b);
            let fits = exact >= BigInt::from(i128::MIN) && exact <= BigInt::from(i128::MAX);
            assert_eq!(
                a.mul_small(b).map(BigInt::from),
                fits.then_some(exact),
                "{a} · {b}"
            );
        }
        for (a, b) in [
            (i128::from(i64::MIN), i128::from(i64::MIN)),
            (i128::from(i64::MAX), -3),
            (-1, i128::MIN + 1),
            (2, i128::MAX / 2),
        ] {
            assert_eq!(a.mul_small(b), a.checked_mul(b));
            assert!(a.mul_small(b).is_some());
        }
        assert_eq!((-1i128).mul_small(i128::MIN), None);
        assert_eq!((1i128 << 64).mul_small(1 << 63), None);
    }
}
