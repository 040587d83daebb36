//! The symbolic scalar: a rational function `num / den` of the inputs
//! (`x⁰ᵢ`, `u⁰ᵢ`, `t`, `s`) with exact rational coefficients.
//!
//! Arithmetic builds the expression (in a normal form: polynomials as
//! coefficient maps, constant denominators folded into the numerator, equal
//! denominators kept once). Every comparison — `==`, `<`, `total_cmp`,
//! `is_zero` … — is sent to the path oracle of [`mod@super::explore`]: a
//! comparison of constants is answered at once; one whose outcome the path
//! condition decides is answered from it; any other is a branch point of
//! the exploration. A division by an expression that may vanish is also a
//! branch point, whose zero side is a fault (the exact engine would panic).

use std::cmp::Ordering;
use std::fmt;
use std::ops::{Add, Div, Mul, Neg, Sub};

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Signed, ToPrimitive, Zero};

use super::explore::{decide, names, Rel};
use super::poly::{Poly, Var};

/// A rational function of the inputs; see the module documentation.
#[derive(Clone)]
pub struct Sym {
    num: Poly,
    /// `1` or a non-constant polynomial.
    den: Poly,
}

impl fmt::Debug for Sym {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&crate::scalar::Scalar::render(self))
    }
}

fn one_poly() -> Poly {
    Poly::constant(BigRational::one())
}

impl Sym {
    /// The variable `v` (an index into the prover's names).
    pub fn var(v: Var) -> Self {
        Sym {
            num: Poly::var(v),
            den: one_poly(),
        }
    }
    /// The exact constant `q`.
    pub fn constant(q: BigRational) -> Self {
        Sym {
            num: Poly::constant(q),
            den: one_poly(),
        }
    }
    /// The numerator.
    pub fn num(&self) -> &Poly {
        &self.num
    }
    /// The denominator (`1` when the value is a polynomial).
    pub fn den(&self) -> &Poly {
        &self.den
    }
    /// `num / den` in normal form (`den ≠ 0` is the caller's business).
    fn frac(num: Poly, den: Poly) -> Self {
        if num.is_zero() {
            return Sym::constant(BigRational::zero());
        }
        if let Some(c) = den.as_constant() {
            if c.is_zero() {
                // Unreachable through `Div`, which branches on a zero divisor.
                return Sym::constant(BigRational::zero());
            }
            return Sym {
                num: num.scale(&(BigRational::one() / c)),
                den: one_poly(),
            };
        }
        let (pn, cn) = num.normalized();
        let (pd, cd) = den.normalized();
        if pn == pd {
            return Sym::constant(cn / cd);
        }
        // Keep the denominator's first coefficient 1.
        Sym {
            num: num.scale(&(BigRational::one() / &cd)),
            den: pd,
        }
    }
    /// The exact value when the expression is a constant.
    pub fn as_constant(&self) -> Option<BigRational> {
        if self.den.as_constant().is_some() {
            self.num.as_constant()
        } else {
            None
        }
    }
    /// The value at a point.
    pub fn eval(&self, point: &[BigRational]) -> Option<BigRational> {
        let d = self.den.eval(point);
        (!d.is_zero()).then(|| self.num.eval(point) / d)
    }
    /// `self − other`, and the polynomial whose sign is the sign of the
    /// difference wherever the denominators do not vanish.
    fn sign_poly(&self, other: &Sym) -> (Sym, Poly) {
        // The quotients compared (collision instants), for the lifting of
        // an undecided query (`lift`).
        for q in [self, other] {
            if q.den.as_constant().is_none() {
                super::explore::note_quotient(&q.num, &q.den);
            }
        }
        let d = self.clone() - other;
        let p = if d.den.as_constant().is_some() {
            d.num.clone()
        } else {
            // sign(num/den) = sign(num) when the path condition already
            // fixes den > 0 (a collision time's closing speed, say): a
            // lower degree for the solver. Otherwise sign(num · den).
            match super::explore::known_strict_sign(&d.den) {
                Some(true) => d.num.clone(),
                Some(false) => d.num.neg(),
                None => d.num.mul(&d.den),
            }
        };
        (d, p)
    }
    fn three_way(&self, other: &Sym) -> Ordering {
        let (_, p) = self.sign_poly(other);
        match decide(&p, &[Rel::Lt, Rel::Eq, Rel::Gt]) {
            0 => Ordering::Less,
            1 => Ordering::Equal,
            _ => Ordering::Greater,
        }
    }
    fn holds(&self, other: &Sym, yes: Rel, no: Rel) -> bool {
        let (_, p) = self.sign_poly(other);
        decide(&p, &[yes, no]) == 0
    }
}

impl PartialEq for Sym {
    fn eq(&self, other: &Self) -> bool {
        for q in [self, other] {
            if q.den.as_constant().is_none() {
                super::explore::note_quotient(&q.num, &q.den);
            }
        }
        let d = self.clone() - other;
        decide(&d.num, &[Rel::Eq, Rel::Ne]) == 0
    }
}

impl PartialOrd for Sym {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.three_way(other))
    }
    fn lt(&self, other: &Self) -> bool {
        self.holds(other, Rel::Lt, Rel::Ge)
    }
    fn le(&self, other: &Self) -> bool {
        self.holds(other, Rel::Le, Rel::Gt)
    }
    fn gt(&self, other: &Self) -> bool {
        self.holds(other, Rel::Gt, Rel::Le)
    }
    fn ge(&self, other: &Self) -> bool {
        self.holds(other, Rel::Ge, Rel::Lt)
    }
}

fn add(a: &Sym, b: &Sym) -> Sym {
    if a.den == b.den {
        Sym::frac(a.num.add(&b.num), a.den.clone())
    } else {
        Sym::frac(a.num.mul(&b.den).add(&b.num.mul(&a.den)), a.den.mul(&b.den))
    }
}

fn mul(a: &Sym, b: &Sym) -> Sym {
    // A polynomial squared: its base, for the relaxation's `(p ± q)² ≥ 0`
    // (`relax::linearize`).
    if a.num == b.num && a.den == b.den && a.den.as_constant().is_some() && a.num.degree() > 0 {
        super::explore::note_square(&a.num);
    }
    if a.den == b.num && !a.den.is_zero() {
        return Sym::frac(a.num.clone(), b.den.clone());
    }
    if b.den == a.num && !b.den.is_zero() {
        return Sym::frac(b.num.clone(), a.den.clone());
    }
    Sym::frac(a.num.mul(&b.num), a.den.mul(&b.den))
}

fn div(a: &Sym, b: &Sym) -> Sym {
    // A zero divisor is a fault of the path (the exact engine would panic);
    // the zero side is explored like any other branch.
    if decide(&b.num, &[Rel::Ne, Rel::Eq]) == 1 {
        super::explore::fault("division by zero");
        return Sym::constant(BigRational::zero());
    }
    mul(
        a,
        &Sym {
            num: b.den.clone(),
            den: b.num.clone(),
        }
        .renormalized(),
    )
}

impl Sym {
    fn renormalized(self) -> Sym {
        Sym::frac(self.num, self.den)
    }
}

macro_rules! binop {
    ($tr:ident, $m:ident, $f:expr) => {
        impl $tr for Sym {
            type Output = Sym;
            fn $m(self, rhs: Sym) -> Sym {
                $f(&self, &rhs)
            }
        }
        impl<'a> $tr<&'a Sym> for Sym {
            type Output = Sym;
            fn $m(self, rhs: &'a Sym) -> Sym {
                $f(&self, rhs)
            }
        }
    };
}

binop!(Add, add, add);
binop!(Mul, mul, mul);
binop!(Div, div, div);
binop!(Sub, sub, |a: &Sym, b: &Sym| add(a, &-b.clone()));

impl Neg for Sym {
    type Output = Sym;
    fn neg(self) -> Sym {
        Sym {
            num: self.num.neg(),
            den: self.den,
        }
    }
}

impl crate::scalar::Scalar for Sym {
    const EXACT: bool = true;
    fn zero() -> Self {
        Sym::constant(<BigRational as Zero>::zero())
    }
    fn one() -> Self {
        Sym::constant(<BigRational as One>::one())
    }
    fn from_i64(n: i64) -> Self {
        Sym::constant(BigRational::from_integer(BigInt::from(n)))
    }
    fn from_usize(n: usize) -> Self {
        Sym::constant(BigRational::from_integer(BigInt::from(n)))
    }
    fn is_zero(&self) -> bool {
        decide(&self.num, &[Rel::Eq, Rel::Ne]) == 0
    }
    fn total_cmp(&self, other: &Self) -> Ordering {
        self.three_way(other)
    }
    fn to_f64_lossy(&self) -> f64 {
        self.as_constant()
            .and_then(|q| q.to_f64())
            .unwrap_or(f64::NAN)
    }
    fn from_big_rational(q: &BigRational) -> Option<Self> {
        Some(Sym::constant(q.clone()))
    }
    fn to_big_rational(&self) -> Option<BigRational> {
        self.as_constant()
    }
    fn render(&self) -> String {
        let names = names();
        if let Some(q) = self.as_constant() {
            return q.to_string();
        }
        let num = self.num.render(&names);
        if self.den.as_constant().is_some() {
            num
        } else {
            format!("({num})/({})", self.den.render(&names))
        }
    }
}

impl Sym {
    /// `true` when the expression has a non-constant denominator.
    pub fn is_fraction(&self) -> bool {
        self.den.as_constant().is_none()
    }
    /// The sign of a constant expression (`None` when it is not constant).
    pub fn constant_sign(&self) -> Option<Ordering> {
        self.as_constant().map(|q| {
            if q.is_negative() {
                Ordering::Less
            } else if q.is_zero() {
                Ordering::Equal
            } else {
                Ordering::Greater
            }
        })
    }
}
