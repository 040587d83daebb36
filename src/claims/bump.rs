//! The polynomial bump `ϕ(t) = (t − a)²(b − t)²` on `[a, b]`, extended by
//! 0: `C¹` with compact support `[a, b]`, positive inside — the explicit
//! test function of every statement quantified over `C¹_c` (in `t` for
//! `prop:pressure-bound`, in `t` and `w` for
//! `prop:2ndorder-LagrPDE#exclusion-pairing`, in `w` for the pressure of
//! `app:uniqueness`).

use crate::scalar::Scalar;

/// `ϕ(t) = (t − a)²(b − t)²` on `[a, b]` as coefficients, and its
/// antiderivative.
pub(crate) struct Bump<S> {
    pub(crate) a: S,
    pub(crate) b: S,
    coeffs: Vec<S>,
}

impl<S: Scalar> Bump<S> {
    pub(crate) fn new(a: S, b: S) -> Self {
        let sq = |c: &S| {
            // (t − c)² = t² − 2c t + c²
            vec![c.clone() * c, -(S::from_i64(2) * c), S::one()]
        };
        let (p, q) = (sq(&a), sq(&b));
        let mut coeffs = vec![S::zero(); 5];
        for (i, x) in p.iter().enumerate() {
            for (j, y) in q.iter().enumerate() {
                coeffs[i + j] = coeffs[i + j].clone() + &(x.clone() * y);
            }
        }
        Bump { a, b, coeffs }
    }
    fn clamp(&self, t: &S) -> S {
        if *t < self.a {
            self.a.clone()
        } else if *t > self.b {
            self.b.clone()
        } else {
            t.clone()
        }
    }
    pub(crate) fn phi(&self, t: &S) -> S {
        let t = self.clamp(t);
        self.coeffs
            .iter()
            .rev()
            .fold(S::zero(), |acc, c| acc * &t + c)
    }
    /// `∫_a^t ϕ`.
    pub(crate) fn big_phi(&self, t: &S) -> S {
        let prim = |t: &S| {
            self.coeffs
                .iter()
                .enumerate()
                .rev()
                .fold(S::zero(), |acc, (k, c)| {
                    acc * t + &(c.clone() / S::from_usize(k + 1))
                })
                * t
        };
        prim(&self.clamp(t)) - &prim(&self.a)
    }
    /// `∫_a^b p ϕ` for the polynomial `p` (coefficients of `1, t, t², …`),
    /// exactly.
    pub(crate) fn integral_times(&self, p: &[S]) -> S {
        let mut prod = vec![S::zero(); p.len() + self.coeffs.len()];
        for (i, x) in p.iter().enumerate() {
            for (j, y) in self.coeffs.iter().enumerate() {
                prod[i + j] = prod[i + j].clone() + &(x.clone() * y);
            }
        }
        let prim = |t: &S| {
            prod.iter()
                .enumerate()
                .rev()
                .fold(S::zero(), |acc, (k, c)| {
                    acc * t + &(c.clone() / S::from_usize(k + 1))
                })
                * t
        };
        prim(&self.b) - &prim(&self.a)
    }
    /// The bump in words, in the variable `var`:
    /// `((var − a)(b − var))² on [a, b], 0 elsewhere`.
    pub(crate) fn describe(&self, var: &str) -> String {
        format!(
            "(({var} − {})({} − {var}))² on [{}, {}], 0 elsewhere",
            self.a.render(),
            self.b.render(),
            self.a.render(),
            self.b.render()
        )
    }
}
