//! Multivariate polynomials with exact rational coefficients: the normal
//! form of the symbolic scalar's numerators and denominators.
//!
//! A monomial is the sorted list of its variables, with repetition for
//! powers (`x₁² t` is `[x₁, x₁, t]`); a polynomial maps monomials to non-zero
//! coefficients. Two polynomials are equal as functions exactly when they
//! are equal as maps, so an identity of the engine (for example the
//! projection and the event merge giving the same cluster sum) is decided
//! here without a solver.

use std::collections::BTreeMap;
use std::fmt::Write as _;

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Signed, Zero};

use super::budget;

/// A variable: an index into the prover's list of names.
pub type Var = u16;

/// A polynomial with exact rational coefficients.
#[derive(Clone, Debug, Default, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Poly {
    terms: BTreeMap<Vec<Var>, BigRational>,
}

impl Poly {
    /// The zero polynomial.
    pub fn zero() -> Self {
        Poly::default()
    }
    /// The constant `q`.
    pub fn constant(q: BigRational) -> Self {
        let mut terms = BTreeMap::new();
        if !q.is_zero() {
            terms.insert(Vec::new(), q);
        }
        Poly { terms }
    }
    /// The variable `v`.
    pub fn var(v: Var) -> Self {
        let mut terms = BTreeMap::new();
        terms.insert(vec![v], BigRational::one());
        Poly { terms }
    }
    /// `true` for the zero polynomial.
    pub fn is_zero(&self) -> bool {
        self.terms.is_empty()
    }
    /// The value when the polynomial is a constant.
    pub fn as_constant(&self) -> Option<BigRational> {
        match self.terms.len() {
            0 => Some(BigRational::zero()),
            1 => self.terms.get(&Vec::new()).cloned(),
            _ => None,
        }
    }
    /// The total degree (0 for constants).
    pub fn degree(&self) -> usize {
        self.terms.keys().map(Vec::len).max().unwrap_or(0)
    }
    /// Number of monomials.
    pub fn len(&self) -> usize {
        self.terms.len()
    }
    /// `true` when there is no monomial (the zero polynomial).
    pub fn is_empty(&self) -> bool {
        self.terms.is_empty()
    }
    /// The monomials (sorted variable lists, a power repeated) with their
    /// non-zero coefficients, in the map's order.
    pub fn terms(&self) -> impl Iterator<Item = (&[Var], &BigRational)> {
        self.terms.iter().map(|(m, c)| (m.as_slice(), c))
    }
    fn add_term(&mut self, m: Vec<Var>, c: BigRational) {
        budget::tick();
        if c.is_zero() {
            return;
        }
        let sum = match self.terms.remove(&m) {
            Some(old) => old + c,
            None => c,
        };
        if !sum.is_zero() {
            self.terms.insert(m, sum);
        }
    }
    /// `self + other`.
    pub fn add(&self, other: &Poly) -> Poly {
        let mut out = self.clone();
        for (m, c) in &other.terms {
            out.add_term(m.clone(), c.clone());
        }
        budget::check_size(out.len());
        out
    }
    /// `−self`.
    pub fn neg(&self) -> Poly {
        Poly {
            terms: self
                .terms
                .iter()
                .map(|(m, c)| {
                    budget::tick();
                    (m.clone(), -c.clone())
                })
                .collect(),
        }
    }
    /// `self − other`.
    pub fn sub(&self, other: &Poly) -> Poly {
        self.add(&other.neg())
    }
    /// `q · self`.
    pub fn scale(&self, q: &BigRational) -> Poly {
        if q.is_zero() {
            return Poly::zero();
        }
        Poly {
            terms: self
                .terms
                .iter()
                .map(|(m, c)| {
                    budget::tick();
                    (m.clone(), c.clone() * q)
                })
                .collect(),
        }
    }
    /// `self · other`.
    pub fn mul(&self, other: &Poly) -> Poly {
        if let Some(c) = other.as_constant() {
            return self.scale(&c);
        }
        if let Some(c) = self.as_constant() {
            return other.scale(&c);
        }
        let mut out = Poly::zero();
        for (ma, ca) in &self.terms {
            for (mb, cb) in &other.terms {
                let mut m = Vec::with_capacity(ma.len() + mb.len());
                m.extend_from_slice(ma);
                m.extend_from_slice(mb);
                m.sort_unstable();
                out.add_term(m, ca.clone() * cb);
            }
            budget::check_size(out.len());
        }
        out
    }
    /// `(p, c)` with `self = c · p` and the first coefficient of `p` equal
    /// to 1 (`c = 0`, `p = 0` for the zero polynomial): two polynomials
    /// that differ by a constant factor share `p`.
    pub fn normalized(&self) -> (Poly, BigRational) {
        match self.terms.values().next() {
            None => (Poly::zero(), BigRational::zero()),
            Some(lead) => {
                let lead = lead.clone();
                (self.scale(&(BigRational::one() / &lead)), lead)
            }
        }
    }
    /// The variables that occur, each once, in increasing order.
    pub fn variables(&self) -> Vec<Var> {
        let mut vars: Vec<Var> = self.terms.keys().flatten().copied().collect();
        vars.sort_unstable();
        vars.dedup();
        vars
    }
    /// The degree of the polynomial in the variable `v` alone.
    pub fn degree_in(&self, v: Var) -> usize {
        self.terms
            .keys()
            .map(|m| m.iter().filter(|&&w| w == v).count())
            .max()
            .unwrap_or(0)
    }
    /// The coefficients `c₀ … c_d` of `self = Σ_k c_k v^k` as polynomials
    /// free of `v` (`d` = [`Poly::degree_in`]).
    pub fn coefficients_in(&self, v: Var) -> Vec<Poly> {
        let mut out = vec![Poly::zero(); self.degree_in(v) + 1];
        for (m, c) in &self.terms {
            let k = m.iter().filter(|&&w| w == v).count();
            let rest: Vec<Var> = m.iter().copied().filter(|&w| w != v).collect();
            out[k].add_term(rest, c.clone());
        }
        out
    }
    /// `self` with the variable `v` replaced by `num / den`, multiplied by
    /// `den^e` (so that it stays a polynomial): `Σ_k c_k num^k den^(e−k)`.
    /// `e` must be at least [`Poly::degree_in`]`(v)`; `num`, `den` free of `v`.
    pub fn substitute(&self, v: Var, num: &Poly, den: &Poly, e: usize) -> Poly {
        let coefficients = self.coefficients_in(v);
        debug_assert!(e + 1 >= coefficients.len(), "den^e must clear every power");
        let mut num_powers = vec![Poly::constant(BigRational::one())];
        let mut den_powers = vec![Poly::constant(BigRational::one())];
        for k in 1..=e {
            num_powers.push(num_powers[k - 1].mul(num));
            den_powers.push(den_powers[k - 1].mul(den));
        }
        let mut out = Poly::zero();
        for (k, c) in coefficients.iter().enumerate() {
            if c.is_zero() {
                continue;
            }
            out = out.add(&c.mul(&num_powers[k]).mul(&den_powers[e - k]));
        }
        out
    }
    /// The value at a point (`point[v]` for the variable `v`).
    pub fn eval(&self, point: &[BigRational]) -> BigRational {
        let mut acc = BigRational::zero();
        for (m, c) in &self.terms {
            budget::tick();
            let mut term = c.clone();
            for &v in m {
                term *= point
                    .get(usize::from(v))
                    .cloned()
                    .unwrap_or_else(BigRational::zero);
            }
            acc += term;
        }
        acc
    }
    /// SMT-LIB text of the polynomial, naming variable `v` by `names[v]`.
    pub fn smt(&self, names: &[String]) -> String {
        if self.terms.is_empty() {
            return "0.0".into();
        }
        let mut parts: Vec<String> = Vec::with_capacity(self.terms.len());
        for (m, c) in &self.terms {
            budget::tick();
            let mut factors: Vec<String> = Vec::with_capacity(m.len() + 1);
            if !c.is_one() || m.is_empty() {
                factors.push(smt_rational(c));
            }
            for &v in m {
                factors.push(name(names, v));
            }
            parts.push(if factors.len() == 1 {
                factors.remove(0)
            } else {
                format!("(* {})", factors.join(" "))
            });
        }
        if parts.len() == 1 {
            parts.remove(0)
        } else {
            format!("(+ {})", parts.join(" "))
        }
    }
    /// Human-readable text (`3/2*x1*t - u2`).
    pub fn render(&self, names: &[String]) -> String {
        if self.terms.is_empty() {
            return "0".into();
        }
        let mut out = String::new();
        for (k, (m, c)) in self.terms.iter().enumerate() {
            let negative = c.is_negative();
            let abs = c.abs();
            if k == 0 {
                if negative {
                    out.push('-');
                }
            } else {
                out.push_str(if negative { " - " } else { " + " });
            }
            let mut first = true;
            if !abs.is_one() || m.is_empty() {
                let _ = write!(out, "{abs}");
                first = false;
            }
            for &v in m {
                if !first {
                    out.push('*');
                }
                out.push_str(&name(names, v));
                first = false;
            }
        }
        out
    }
}

fn name(names: &[String], v: Var) -> String {
    names
        .get(usize::from(v))
        .cloned()
        .unwrap_or_else(|| format!("v{v}"))
}

/// SMT-LIB real literal of an exact rational: `3.0`, `(- 3.0)`,
/// `(/ 3.0 4.0)`, `(- (/ 3.0 4.0))`.
pub fn smt_rational(q: &BigRational) -> String {
    let abs = q.abs();
    let body = if abs.denom() == &BigInt::one() {
        format!("{}.0", abs.numer())
    } else {
        format!("(/ {}.0 {}.0)", abs.numer(), abs.denom())
    };
    if q.is_negative() {
        format!("(- {body})")
    } else {
        body
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    use crate::rational::ratio as q;

    #[test]
    fn ring_and_normal_form() {
        let x = Poly::var(0);
        let t = Poly::var(1);
        let a = x.add(&t.scale(&q(3, 2)));
        let b = x.sub(&t);
        let prod = a.mul(&b);
        // (x + 3/2 t)(x − t) = x² + 1/2 x t − 3/2 t²
        let expected = x
            .mul(&x)
            .add(&x.mul(&t).scale(&q(1, 2)))
            .sub(&t.mul(&t).scale(&q(3, 2)));
        assert_eq!(prod, expected);
        assert_eq!(prod.degree(), 2);
        assert!(a.sub(&a).is_zero());
        let (p, c) = b.scale(&q(-4, 1)).normalized();
        assert_eq!(p, b);
        assert_eq!(c, q(-4, 1));
        let names = vec!["x".to_string(), "t".to_string()];
        assert_eq!(a.render(&names), "x + 3/2*t");
        assert_eq!(a.smt(&names), "(+ x (* (/ 3.0 2.0) t))");
        assert_eq!(prod.eval(&[q(1, 1), q(2, 1)]), q(4, 1) * q(-1, 1));
        assert_eq!(Poly::constant(q(-1, 3)).smt(&names), "(- (/ 1.0 3.0))");
    }
}
