//! Polynomials in one variable with exact coefficients, `p[k]` the
//! coefficient of `x^k`: the few operations the exact checks of the limit
//! and of the claims integrate and compare with (Appendix C's piecewise
//! profiles, the bumps and moments of `prop:eulerian-formulation#mass`).

use crate::scalar::Scalar;

/// `p(x)` (Horner).
pub fn eval<S: Scalar>(p: &[S], x: &S) -> S {
    p.iter().rev().fold(S::zero(), |acc, c| acc * x + c)
}

/// `p'`.
pub fn deriv<S: Scalar>(p: &[S]) -> Vec<S> {
    p.iter()
        .enumerate()
        .skip(1)
        .map(|(k, c)| c.clone() * &S::from_usize(k))
        .collect()
}

/// The coefficients `f(a_k, b_k)` (a missing coefficient is 0).
pub fn combine<S: Scalar>(a: &[S], b: &[S], f: impl Fn(&S, &S) -> S) -> Vec<S> {
    let n = a.len().max(b.len());
    let z = S::zero();
    (0..n)
        .map(|k| f(a.get(k).unwrap_or(&z), b.get(k).unwrap_or(&z)))
        .collect()
}

/// `a + b` into `acc`.
pub fn add_into<S: Scalar>(acc: &mut Vec<S>, p: &[S]) {
    if acc.len() < p.len() {
        acc.resize(p.len(), S::zero());
    }
    for (a, x) in acc.iter_mut().zip(p) {
        *a = a.clone() + x;
    }
}

/// `a b`.
pub fn mul<S: Scalar>(a: &[S], b: &[S]) -> Vec<S> {
    let mut out = vec![S::zero(); (a.len() + b.len()).saturating_sub(1)];
    for (i, x) in a.iter().enumerate() {
        for (j, y) in b.iter().enumerate() {
            out[i + j] = out[i + j].clone() + &(x.clone() * y);
        }
    }
    out
}

/// `true` when every coefficient is 0.
pub fn is_zero<S: Scalar>(p: &[S]) -> bool {
    p.iter().all(|c| c.is_zero())
}

/// `∫_0^h p(x) dx`.
pub fn integral<S: Scalar>(p: &[S], h: &S) -> S {
    let mut hk = h.clone();
    let mut total = S::zero();
    for (k, c) in p.iter().enumerate() {
        total = total + &(c.clone() * &hk / &S::from_usize(k + 1));
        hk = hk * h;
    }
    total
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rational::ratio as q;
    use num_rational::BigRational as Q;

    #[test]
    fn the_operations_agree_with_evaluation() {
        let a = vec![q(1, 1), q(-2, 3), q(0, 1), q(5, 2)];
        let b = vec![q(3, 4), q(1, 1)];
        let x = q(-7, 5);
        let ab = mul(&a, &b);
        assert_eq!(eval(&ab, &x), eval(&a, &x) * eval(&b, &x));
        let mut s = a.clone();
        add_into(&mut s, &b);
        assert_eq!(eval(&s, &x), eval(&a, &x) + eval(&b, &x));
        assert_eq!(combine(&a, &b, |u, v| u.clone() + v), s);
        // p' of 1 − 2x/3 + 5x³/2 is −2/3 + 15x²/2.
        assert_eq!(deriv(&a), vec![q(-2, 3), q(0, 1), q(15, 2)]);
        // ∫_0^2 (1 + 3τ²) dτ = 2 + 8 = 10.
        assert_eq!(integral(&[q(1, 1), q(0, 1), q(3, 1)], &q(2, 1)), q(10, 1));
        assert!(is_zero::<Q>(&[q(0, 1), q(0, 1)]) && !is_zero(&a));
        assert!(is_zero(&mul::<Q>(&[], &b)));
    }
}
