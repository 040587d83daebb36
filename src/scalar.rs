//! The numeric trait every algorithm of the crate is written over.
//!
//! One generic implementation, several scalars: the projection, the cluster
//! merge and the multipliers are written once over [`Scalar`] and run on
//!
//! * [`BigRational`] — the exact engine (no rounding, no overflow);
//! * [`Rational64`] (`Ratio<i64>`) — a fixed-width rational used by the
//!   bounded proofs, where every input is small and an overflow is a bug that
//!   the debug build (and Kani) reports rather than hides;
//! * [`f64`] — the floating-point reference path.
//!
//! The trait asks for `Clone`, never `Copy`: a `Copy` bound would lock out
//! big numbers.

use std::cmp::Ordering;
use std::fmt;
use std::ops::{Add, Div, Mul, Neg, Sub};

use num_bigint::BigInt;
use num_integer::Integer;
use num_rational::{BigRational, Ratio, Rational64};
use num_traits::{One, ToPrimitive, Zero};

/// An ordered field (exact or not) the algorithms are generic over.
///
/// Arithmetic is available by value and with a borrowed right-hand side, so
/// that big numbers are not cloned more than needed.
pub trait Scalar:
    Clone
    + fmt::Debug
    + PartialEq
    + PartialOrd
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
    + for<'a> Add<&'a Self, Output = Self>
    + for<'a> Sub<&'a Self, Output = Self>
    + for<'a> Mul<&'a Self, Output = Self>
    + for<'a> Div<&'a Self, Output = Self>
{
    /// `true` when every operation is exact (rationals), `false` for floats.
    const EXACT: bool;
    /// The additive identity.
    fn zero() -> Self;
    /// The multiplicative identity.
    fn one() -> Self;
    /// The integer `n` (exact for rationals; nearest double for `f64`).
    fn from_i64(n: i64) -> Self;
    /// The integer `n` (exact for rationals; nearest double for `f64`).
    fn from_usize(n: usize) -> Self {
        // usize fits i64 on every supported platform for particle counts.
        Self::from_i64(i64::try_from(n).unwrap_or(i64::MAX))
    }
    /// `self == 0`.
    fn is_zero(&self) -> bool;
    /// A total order (the usual one for rationals, IEEE `totalOrder` for f64).
    fn total_cmp(&self, other: &Self) -> Ordering;
    /// The value as the nearest `f64` — for charts and reports only, never on
    /// an exact path.
    fn to_f64_lossy(&self) -> f64;
    /// Converts an exact rational into this scalar: exact for the rational
    /// types (or `None` when it does not fit), nearest double for `f64`.
    fn from_big_rational(q: &BigRational) -> Option<Self>;
    /// The exact rational value of this scalar (`None` for NaN or infinity).
    fn to_big_rational(&self) -> Option<BigRational>;
    /// The value as text: `"p/q"` or `"p"` in lowest terms for rationals, the
    /// shortest round-trip decimal for `f64`.
    fn render(&self) -> String;

    /// `Σ_i a_i b_i` (pairs up to the shorter slice): the value of the plain
    /// loop `0 + a_1 b_1 + a_2 b_2 + …`, which is this default. An exact
    /// type may compute the same value with fewer reductions.
    fn sum_of_products(a: &[Self], b: &[Self]) -> Self {
        a.iter()
            .zip(b)
            .fold(Self::zero(), |acc, (x, y)| acc + &(x.clone() * y))
    }

    /// `self^k` (`1` for `k = 0`): the value of `k − 1` products, which is
    /// this default. An exact type may skip the reductions.
    fn powi(&self, k: u32) -> Self {
        (1..k).fold(if k == 0 { Self::one() } else { self.clone() }, |p, _| {
            p * self
        })
    }

    /// `self + other`: the operator, which this default is. An exact type
    /// may reduce faster (`BigRational`: [`crate::reduced`]).
    fn plus(&self, other: &Self) -> Self {
        self.clone() + other
    }

    /// `self − other` ([`Scalar::plus`]).
    fn minus(&self, other: &Self) -> Self {
        self.clone() - other
    }

    /// `self · other` ([`Scalar::plus`]).
    fn times(&self, other: &Self) -> Self {
        self.clone() * other
    }

    /// `self / other` ([`Scalar::plus`]).
    fn over(&self, other: &Self) -> Self {
        self.clone() / other
    }

    /// The smaller of two values (the left one on ties).
    fn min_of(a: Self, b: Self) -> Self {
        if b.total_cmp(&a) == Ordering::Less {
            b
        } else {
            a
        }
    }
}

impl Scalar for BigRational {
    const EXACT: bool = true;
    fn zero() -> Self {
        Zero::zero()
    }
    fn one() -> Self {
        One::one()
    }
    fn from_i64(n: i64) -> Self {
        BigRational::from_integer(BigInt::from(n))
    }
    fn from_usize(n: usize) -> Self {
        BigRational::from_integer(BigInt::from(n))
    }
    fn is_zero(&self) -> bool {
        Zero::is_zero(self)
    }
    fn total_cmp(&self, other: &Self) -> Ordering {
        self.cmp(other)
    }
    fn to_f64_lossy(&self) -> f64 {
        self.to_f64().unwrap_or(f64::NAN)
    }
    fn from_big_rational(q: &BigRational) -> Option<Self> {
        Some(q.clone())
    }
    fn to_big_rational(&self) -> Option<BigRational> {
        Some(self.clone())
    }
    fn render(&self) -> String {
        crate::rational::render_exact(self)
    }
    /// Over a running common denominator (the lcm of the products'
    /// denominators, no gcd while a product's denominator divides it) and one
    /// reduction at the end: `BigRational` addition reduces at every term, and
    /// those gcds were most of the cost of the claims' inner products. The
    /// partial sum is reduced and restarted when its denominator passes
    /// `SUM_DENOMINATOR_BITS`, so coprime denominators cannot make it grow
    /// without bound. The value is exact, so it is the plain loop's.
    fn sum_of_products(a: &[Self], b: &[Self]) -> Self {
        let mut total: BigRational = Zero::zero();
        let (mut num, mut den) = (BigInt::zero(), BigInt::one());
        for (x, y) in a.iter().zip(b) {
            if Zero::is_zero(x) || Zero::is_zero(y) {
                continue;
            }
            let n = x.numer() * y.numer();
            let d = x.denom() * y.denom();
            let (q, r) = den.div_rem(&d);
            if Zero::is_zero(&r) {
                num += n * q;
                continue;
            }
            let g = den.gcd(&d);
            let (dg, deng) = (&d / &g, &den / &g);
            num = num * &dg + n * deng;
            den *= dg;
            if den.bits() > SUM_DENOMINATOR_BITS {
                total += BigRational::new(std::mem::take(&mut num), den);
                den = BigInt::one();
            }
        }
        total + BigRational::new(num, den)
    }
    fn plus(&self, other: &Self) -> Self {
        crate::reduced::sum(self, other)
    }
    fn minus(&self, other: &Self) -> Self {
        crate::reduced::difference(self, other)
    }
    fn times(&self, other: &Self) -> Self {
        crate::reduced::product(self, other)
    }
    fn over(&self, other: &Self) -> Self {
        crate::reduced::quotient(self, other)
    }
    /// `p^k / q^k` is already in lowest terms when `p/q` is (no gcd).
    fn powi(&self, k: u32) -> Self {
        BigRational::new_raw(self.numer().pow(k), self.denom().pow(k))
    }
}

/// The largest denominator, in bits, of the unreduced partial sums of
/// `BigRational`'s [`Scalar::sum_of_products`].
const SUM_DENOMINATOR_BITS: u64 = 4096;

impl Scalar for Rational64 {
    const EXACT: bool = true;
    fn zero() -> Self {
        Zero::zero()
    }
    fn one() -> Self {
        One::one()
    }
    fn from_i64(n: i64) -> Self {
        Ratio::from_integer(n)
    }
    fn is_zero(&self) -> bool {
        Zero::is_zero(self)
    }
    fn total_cmp(&self, other: &Self) -> Ordering {
        self.cmp(other)
    }
    fn to_f64_lossy(&self) -> f64 {
        self.to_f64().unwrap_or(f64::NAN)
    }
    fn from_big_rational(q: &BigRational) -> Option<Self> {
        let n = q.numer().to_i64()?;
        let d = q.denom().to_i64()?;
        Some(Ratio::new(n, d))
    }
    fn to_big_rational(&self) -> Option<BigRational> {
        Some(BigRational::new(
            BigInt::from(*self.numer()),
            BigInt::from(*self.denom()),
        ))
    }
    fn render(&self) -> String {
        self.to_string()
    }
}

impl Scalar for f64 {
    const EXACT: bool = false;
    fn zero() -> Self {
        0.0
    }
    fn one() -> Self {
        1.0
    }
    fn from_i64(n: i64) -> Self {
        n as f64
    }
    fn is_zero(&self) -> bool {
        *self == 0.0
    }
    fn total_cmp(&self, other: &Self) -> Ordering {
        f64::total_cmp(self, other)
    }
    fn to_f64_lossy(&self) -> f64 {
        *self
    }
    fn from_big_rational(q: &BigRational) -> Option<Self> {
        q.to_f64()
    }
    fn to_big_rational(&self) -> Option<BigRational> {
        BigRational::from_float(*self)
    }
    fn render(&self) -> String {
        format!("{self:?}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// num-rational style: every arithmetic test runs on `Ratio<i64>` and again
    /// on `BigRational`.
    fn field_laws<S: Scalar>() {
        let a = S::from_i64(3) / S::from_i64(4);
        let b = S::from_i64(-5) / S::from_i64(6);
        let sum = a.clone() + &b;
        assert_eq!(sum, S::from_i64(-1) / S::from_i64(12));
        assert_eq!(a.clone() * &b, S::from_i64(-5) / S::from_i64(8));
        assert!((a.clone() - &a).is_zero());
        assert_eq!(a.total_cmp(&b), Ordering::Greater);
        assert_eq!(S::min_of(a.clone(), b.clone()), b);
        let back = S::from_big_rational(&a.to_big_rational().unwrap()).unwrap();
        assert_eq!(back, a);
        assert_eq!(S::from_usize(7), S::from_i64(7));
        assert_eq!(-S::one() + &S::one(), S::zero());
    }

    #[test]
    fn field_laws_rational64() {
        field_laws::<Rational64>();
    }

    #[test]
    fn field_laws_bigrational() {
        field_laws::<BigRational>();
    }

    /// The plain loop, the oracle of [`Scalar::sum_of_products`].
    fn plain_sum(a: &[BigRational], b: &[BigRational]) -> BigRational {
        a.iter()
            .zip(b)
            .fold(<BigRational as Scalar>::zero(), |acc, (x, y)| {
                acc + &(x.clone() * y)
            })
    }

    #[test]
    fn bigrational_sum_of_products_is_the_plain_loop() {
        let q = |n: i64, d: i64| BigRational::new(BigInt::from(n), BigInt::from(d));
        // Shared, nested and coprime denominators, zeros, signs, unequal
        // lengths (pairs up to the shorter).
        let a: Vec<BigRational> = (1..60).map(|i| q(i * 7 - 200, (i % 9) + 1)).collect();
        let b: Vec<BigRational> = (1..58).map(|i| q(3 - i, 2 * (i % 5) + 1)).collect();
        assert_eq!(
            <BigRational as Scalar>::sum_of_products(&a, &b),
            plain_sum(&a, &b)
        );
        assert_eq!(
            <BigRational as Scalar>::sum_of_products(&a, &[]),
            <BigRational as Scalar>::zero()
        );
        // 80 distinct 64-bit prime-ish denominators: the partial sum passes
        // SUM_DENOMINATOR_BITS and is reduced and restarted.
        let big: Vec<BigRational> = (0..80u64)
            .map(|i| {
                let d = BigInt::from((1u64 << 63) - 25 - 2 * i);
                BigRational::new(BigInt::from(i as i64 - 40), d)
            })
            .collect();
        let ones = vec![<BigRational as Scalar>::one(); big.len()];
        assert_eq!(
            <BigRational as Scalar>::sum_of_products(&big, &ones),
            plain_sum(&big, &ones)
        );
        assert_eq!(
            <BigRational as Scalar>::sum_of_products(&big, &big),
            plain_sum(&big, &big)
        );
    }

    #[test]
    fn powi_is_repeated_product() {
        let x = BigRational::new(BigInt::from(-6), BigInt::from(4));
        for k in 0..5 {
            let plain = (0..k).fold(<BigRational as Scalar>::one(), |p, _| p * &x);
            assert_eq!(x.powi(k), plain);
            assert_eq!(
                Rational64::new(-3, 2).powi(k).to_big_rational(),
                Some(plain)
            );
        }
    }

    #[test]
    fn f64_round_trip_is_exact() {
        let x = 0.1f64;
        let q = x.to_big_rational().unwrap();
        assert_eq!(f64::from_big_rational(&q), Some(x));
        assert!(f64::NAN.to_big_rational().is_none());
    }

    #[test]
    fn rational64_refuses_what_does_not_fit() {
        let big = BigRational::from_integer(BigInt::from(u64::MAX));
        assert_eq!(Rational64::from_big_rational(&big), None);
    }
}
