//! Exact quadratic surds `a + b√d` (`a`, `b` rational, `d` a square-free-ish
//! positive integer): the numbers the continuum solution is made of.
//!
//! The isotonic regression behind `X(t) = P_K(X⁰ + tU⁰)` (see
//! [`super::continuum`]) pools intervals whose level `M` solves one
//! quadratic equation with rational coefficients; when its discriminant is
//! not the square of a rational, `M` (and the pooled interval's ends, affine
//! in `M`) lie in `Q(√d)`. Every such number is kept exactly here:
//! arithmetic inside one field `Q(√d)` is exact ([`Surd::checked_add`] and
//! friends refuse to mix two different fields), comparisons are exact across
//! fields ([`Surd::cmp_exact`]), and the conversion to `f64` comes with a
//! rigorous error bound ([`Surd::to_f64_bounded`]): `√d` is enclosed between
//! two rationals `s/2^k ≤ √d < (s+1)/2^k` by an integer square root, the
//! enclosure of `a + b√d` is rounded to the nearest double, and the bound is
//! the rounding error plus the half-width of the enclosure.

use std::cmp::Ordering;
use std::fmt;

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Signed, ToPrimitive, Zero};

use crate::rational::render_exact;

/// Bits of the rational enclosure of `√d` used by [`Surd::to_f64_bounded`].
const ENCLOSURE_BITS: u32 = 96;

/// The exact number `a + b√d`. Invariant: `d = 0` when `b = 0` (a rational),
/// otherwise `d ≥ 2` is an integer that is not a perfect square.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Surd {
    a: BigRational,
    b: BigRational,
    d: BigInt,
}

/// `√n` when `n ≥ 0` is a perfect square.
fn exact_int_sqrt(n: &BigInt) -> Option<BigInt> {
    if n.is_negative() {
        return None;
    }
    let s = n.sqrt();
    (&s * &s == *n).then_some(s)
}

/// `√q` when it is rational.
pub fn rational_sqrt(q: &BigRational) -> Option<BigRational> {
    let p = exact_int_sqrt(q.numer())?;
    let d = exact_int_sqrt(q.denom())?;
    Some(BigRational::new(p, d))
}

/// The square factors of small primes, removed from `n` and returned as
/// their root: `n = k² · n'`.
fn strip_squares(mut n: BigInt) -> (BigInt, BigInt) {
    let mut k = BigInt::one();
    let mut p = 2u32;
    while p < 1000 {
        let pp = BigInt::from(p * p);
        while (&n % &pp).is_zero() && !n.is_zero() {
            n /= &pp;
            k *= BigInt::from(p);
        }
        p += if p == 2 { 1 } else { 2 };
    }
    (k, n)
}

/// The sign of `a + b√d` (`d ≥ 0`, not a perfect square when `b ≠ 0`).
fn sign_ab(a: &BigRational, b: &BigRational, d: &BigInt) -> Ordering {
    let zero = BigRational::zero();
    let sa = a.cmp(&zero);
    let sb = if d.is_zero() {
        Ordering::Equal
    } else {
        b.cmp(&zero)
    };
    if sb == Ordering::Equal {
        return sa;
    }
    if sa == Ordering::Equal || sa == sb {
        return sb;
    }
    // Opposite signs: the larger magnitude wins (never equal: √d ∉ Q).
    let lhs = a * a;
    let rhs = b * b * BigRational::from_integer(d.clone());
    match lhs.cmp(&rhs) {
        Ordering::Greater => sa,
        Ordering::Less => sb,
        Ordering::Equal => Ordering::Equal,
    }
}

impl Surd {
    /// The rational `q`.
    pub fn from_rational(q: BigRational) -> Self {
        Surd {
            a: q,
            b: BigRational::zero(),
            d: BigInt::zero(),
        }
    }

    /// `√q` (`None` when `q < 0`): rational when `q` is the square of a
    /// rational, otherwise `(k/s)·√n` with `q = k²n/s²`.
    pub fn sqrt_of(q: &BigRational) -> Option<Self> {
        if q.is_negative() {
            return None;
        }
        if let Some(r) = rational_sqrt(q) {
            return Some(Surd::from_rational(r));
        }
        // √(p/s) = √(p s)/s.
        let n = q.numer() * q.denom();
        let (k, n) = strip_squares(n);
        if let Some(r) = exact_int_sqrt(&n) {
            return Some(Surd::from_rational(BigRational::new(
                k * r,
                q.denom().clone(),
            )));
        }
        Some(Surd {
            a: BigRational::zero(),
            b: BigRational::new(k, q.denom().clone()),
            d: n,
        })
    }

    fn make(a: BigRational, b: BigRational, d: BigInt) -> Self {
        if b.is_zero() || d.is_zero() {
            Surd::from_rational(a)
        } else {
            Surd { a, b, d }
        }
    }

    /// The rational part `a`.
    pub fn a(&self) -> &BigRational {
        &self.a
    }
    /// The coefficient `b` of `√d`.
    pub fn b(&self) -> &BigRational {
        &self.b
    }
    /// The radicand `d` (0 for a rational).
    pub fn d(&self) -> &BigInt {
        &self.d
    }
    /// `true` when the number is rational (`b = 0`).
    pub fn is_rational(&self) -> bool {
        self.b.is_zero()
    }
    /// The value when it is rational.
    pub fn as_rational(&self) -> Option<&BigRational> {
        self.is_rational().then_some(&self.a)
    }

    /// The common field of two surds: `Some(d)` when at most one radicand
    /// is non-zero or both are equal.
    fn common(&self, o: &Surd) -> Option<BigInt> {
        match (self.d.is_zero(), o.d.is_zero()) {
            (true, _) => Some(o.d.clone()),
            (_, true) => Some(self.d.clone()),
            _ => (self.d == o.d).then(|| self.d.clone()),
        }
    }

    /// `self + o`, when both lie in one field `Q(√d)`.
    pub fn checked_add(&self, o: &Surd) -> Option<Surd> {
        let d = self.common(o)?;
        Some(Surd::make(&self.a + &o.a, &self.b + &o.b, d))
    }
    /// `self − o`, when both lie in one field `Q(√d)`.
    pub fn checked_sub(&self, o: &Surd) -> Option<Surd> {
        let d = self.common(o)?;
        Some(Surd::make(&self.a - &o.a, &self.b - &o.b, d))
    }
    /// `self · o`, when both lie in one field `Q(√d)`.
    pub fn checked_mul(&self, o: &Surd) -> Option<Surd> {
        let d = self.common(o)?;
        let dq = BigRational::from_integer(d.clone());
        Some(Surd::make(
            &self.a * &o.a + &self.b * &o.b * dq,
            &self.a * &o.b + &self.b * &o.a,
            d,
        ))
    }
    /// `self / o`, when both lie in one field and `o ≠ 0`.
    pub fn checked_div(&self, o: &Surd) -> Option<Surd> {
        let d = self.common(o)?;
        let dq = BigRational::from_integer(d.clone());
        let norm = &o.a * &o.a - &o.b * &o.b * &dq;
        if norm.is_zero() {
            return None;
        }
        // (a + b√d)(c − e√d) / (c² − e²d).
        let conj = Surd::make(o.a.clone(), -o.b.clone(), d);
        let num = self.checked_mul(&conj)?;
        Some(Surd::make(&num.a / &norm, &num.b / &norm, num.d))
    }
    /// `self²` (always defined).
    pub fn square(&self) -> Surd {
        let dq = BigRational::from_integer(self.d.clone());
        Surd::make(
            &self.a * &self.a + &self.b * &self.b * dq,
            BigRational::from_integer(2.into()) * &self.a * &self.b,
            self.d.clone(),
        )
    }
    /// `−self`.
    pub fn neg(&self) -> Surd {
        Surd::make(-self.a.clone(), -self.b.clone(), self.d.clone())
    }
    /// `self + q`.
    pub fn add_rational(&self, q: &BigRational) -> Surd {
        Surd::make(&self.a + q, self.b.clone(), self.d.clone())
    }
    /// `self · q`.
    pub fn mul_rational(&self, q: &BigRational) -> Surd {
        Surd::make(&self.a * q, &self.b * q, self.d.clone())
    }
    /// `c0 + c1·self + c2·self²`, exact (always in the field of `self`).
    pub fn eval_quadratic(&self, c: &[BigRational; 3]) -> Surd {
        let lin = self.mul_rational(&c[1]).add_rational(&c[0]);
        let sq = self.square().mul_rational(&c[2]);
        // Same field: cannot fail.
        Surd::make(&lin.a + &sq.a, &lin.b + &sq.b, self.d.clone())
    }

    /// The sign of the number, exactly.
    pub fn signum(&self) -> Ordering {
        sign_ab(&self.a, &self.b, &self.d)
    }

    /// Exact comparison with a rational.
    pub fn cmp_rational(&self, q: &BigRational) -> Ordering {
        sign_ab(&(&self.a - q), &self.b, &self.d)
    }

    /// Exact comparison of two surds, in the same field or not: the sign of
    /// `x + y + z` with `x = a₁ − a₂`, `y = b₁√d₁`, `z = −b₂√d₂`, decided by
    /// comparing squares (at most two squarings, all rational).
    pub fn cmp_exact(&self, o: &Surd) -> Ordering {
        if self.common(o).is_some() {
            return self.checked_sub(o).map_or(Ordering::Equal, |s| s.signum());
        }
        let zero = BigRational::zero();
        let x = &self.a - &o.a;
        let d1 = BigRational::from_integer(self.d.clone());
        let d2 = BigRational::from_integer(o.d.clone());
        let y2 = &self.b * &self.b * &d1;
        let z2 = &o.b * &o.b * &d2;
        let sy = self.b.cmp(&zero);
        let sz = zero.cmp(&o.b);
        let s_yz = if sy == sz || sz == Ordering::Equal {
            sy
        } else if sy == Ordering::Equal {
            sz
        } else {
            match y2.cmp(&z2) {
                Ordering::Greater => sy,
                Ordering::Less => sz,
                Ordering::Equal => Ordering::Equal,
            }
        };
        let sx = x.cmp(&zero);
        if s_yz == Ordering::Equal {
            return sx;
        }
        if sx == Ordering::Equal || sx == s_yz {
            return s_yz;
        }
        // Opposite signs: compare x² with (y + z)² = y² + z² − 2 b₁ b₂ √(d₁d₂).
        let r = &x * &x - &y2 - &z2;
        let c = BigRational::from_integer(2.into()) * &self.b * &o.b;
        let e = BigRational::from_integer(&self.d * &o.d);
        let cross = match Surd::sqrt_of(&e) {
            Some(s) => s.mul_rational(&c).add_rational(&r).signum(),
            None => Ordering::Equal,
        };
        match cross {
            Ordering::Greater => sx,
            Ordering::Less => s_yz,
            Ordering::Equal => Ordering::Equal,
        }
    }

    /// Rationals `lo ≤ self ≤ hi` with `hi − lo ≤ |b|·2^{−bits}` (equal
    /// for a rational).
    pub fn enclosure(&self, bits: u32) -> (BigRational, BigRational) {
        if self.is_rational() {
            return (self.a.clone(), self.a.clone());
        }
        let scale = BigInt::one() << (2 * bits as usize);
        let s = (&self.d * &scale).sqrt();
        let den = BigInt::one() << bits as usize;
        let lo = BigRational::new(s.clone(), den.clone());
        let hi = BigRational::new(s + 1, den);
        let (l, h) = (&self.a + &self.b * &lo, &self.a + &self.b * &hi);
        if l <= h {
            (l, h)
        } else {
            (h, l)
        }
    }

    /// The nearest-ish double and a rigorous bound on its distance to the
    /// exact value (0 when the rational value is a double).
    pub fn to_f64_bounded(&self) -> (f64, f64) {
        let (lo, hi) = self.enclosure(ENCLOSURE_BITS);
        let two = BigRational::from_integer(2.into());
        let mid = (&lo + &hi) / &two;
        let v = mid.to_f64().unwrap_or(f64::NAN);
        let Some(vq) = BigRational::from_float(v) else {
            return (v, f64::INFINITY);
        };
        let err = (&mid - vq).abs() + (&hi - &lo) / two;
        let bound = err.to_f64().unwrap_or(f64::INFINITY);
        // Round the bound up by a relative 2⁻⁵⁰ to cover its own rounding.
        (v, bound * (1.0 + 2f64.powi(-50)))
    }

    /// The value as a double (see [`Surd::to_f64_bounded`]).
    pub fn to_f64(&self) -> f64 {
        self.to_f64_bounded().0
    }
}

impl fmt::Display for Surd {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.is_rational() {
            return write!(f, "{}", render_exact(&self.a));
        }
        if self.a.is_zero() {
            write!(f, "{}·√{}", render_exact(&self.b), self.d)
        } else if self.b.is_negative() {
            write!(
                f,
                "{} − {}·√{}",
                render_exact(&self.a),
                render_exact(&-self.b.clone()),
                self.d
            )
        } else {
            write!(
                f,
                "{} + {}·√{}",
                render_exact(&self.a),
                render_exact(&self.b),
                self.d
            )
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    use crate::rational::ratio as q;

    #[test]
    fn sqrt_and_fields() {
        assert_eq!(
            Surd::sqrt_of(&q(9, 4)).unwrap(),
            Surd::from_rational(q(3, 2))
        );
        let s45 = Surd::sqrt_of(&q(45, 1)).unwrap();
        assert_eq!(s45.d(), &BigInt::from(5));
        assert_eq!(s45.b(), &q(3, 1));
        let s = Surd::sqrt_of(&q(5, 3)).unwrap(); // √15 / 3
        assert_eq!(s.d(), &BigInt::from(15));
        assert_eq!(s.square(), Surd::from_rational(q(5, 3)));
        let inv = Surd::from_rational(q(1, 1)).checked_div(&s).unwrap();
        assert_eq!(inv.checked_mul(&s).unwrap(), Surd::from_rational(q(1, 1)));
        assert!(s.checked_add(&Surd::sqrt_of(&q(2, 1)).unwrap()).is_none());
        assert!(Surd::sqrt_of(&q(-1, 1)).is_none());
    }

    #[test]
    fn exact_comparisons() {
        let r2 = Surd::sqrt_of(&q(2, 1)).unwrap();
        let r3 = Surd::sqrt_of(&q(3, 1)).unwrap();
        assert_eq!(r2.cmp_exact(&r3), Ordering::Less);
        // 1 + √2 ≈ 2.414 vs √3 + 0.7 ≈ 2.432
        let a = r2.add_rational(&q(1, 1));
        let b = r3.add_rational(&q(7, 10));
        assert_eq!(a.cmp_exact(&b), Ordering::Less);
        assert_eq!(b.cmp_exact(&a), Ordering::Greater);
        // √2 − 1.4142 > 0, √2 − 1.4143 < 0
        assert_eq!(r2.cmp_rational(&q(14142, 10000)), Ordering::Greater);
        assert_eq!(r2.cmp_rational(&q(14143, 10000)), Ordering::Less);
        let (v, bound) = r2.to_f64_bounded();
        assert!((v - std::f64::consts::SQRT_2).abs() <= bound + 1e-300);
        assert!(bound < 1e-15);
        assert_eq!(
            format!("{}", r2.mul_rational(&q(-1, 2)).add_rational(&q(1, 1))),
            "1 − 1/2·√2"
        );
    }
}
