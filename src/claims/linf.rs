//! `prop:Linf-micro` per trajectory, at fixed N, with the constants of its
//! proof: under `cond:Linfty` with its smallest constant
//! `C'_0 = (x⁰_N − x⁰_0) + sup_i |u⁰_i|` (artificial particle
//! `x⁰_0 = x⁰_1 − 1/N − δ`, `δ = 1`, and the paper's normalisation
//! `x⁰_0 = 0`, i.e. positions measured from `x⁰_0`), at every probe time
//! `t` taken as `T`:
//! * `sup_i |u_i(t)| ≤ sup_i |u⁰_i|` (`eq:sup-micro-u-L`, used by the proof);
//! * `∫|∂_w X̃_N| = x_N − x_0 ≤ (x⁰_N − x⁰_0) + 2T sup|u⁰| ≤ (1 + 2T) C'_0`;
//! * `‖X_N‖_∞ + ‖X̃_N‖_∞ ≤ 2 max(|x_0(t)|, |x_N(t)|) ≤ 2(T sup|u⁰| + (1 + 2T) C'_0) ≤ 2(1 + 3T) C'_0`
//!   (`x_0` moves with particle 1);
//! * `‖Λ_N‖_∞ + ‖Λ̃_N‖_∞ = 2 max_i |λ_i| ≤ 4 sup|u⁰| ≤ 4 C'_0`
//!   (`|λ_i| ≤ Σ_{j ≤ i} |u⁰_j − u_j|/N`).

use super::discrete::{abs, states, Augmented};
use super::{Case, Violation};
use crate::scalar::Scalar;

const ID: &str = "prop:Linf-micro";

type R = Result<(), Violation>;

fn sup_abs<S: Scalar>(v: &[S]) -> S {
    v.iter().fold(S::zero(), |m, x| {
        let a = abs(x.clone());
        if a > m {
            a
        } else {
            m
        }
    })
}

/// The bounds at one augmented state `a` (`x_0 … x_N`, `u_0 … u_N`,
/// `λ_0 … λ_N`), from the initial augmented positions `x0` and
/// `sup_u0 = sup_i |u⁰_i|`.
pub(super) fn linf_at<S: Scalar>(a: &Augmented<S>, x0: &[S], sup_u0: &S) -> Result<(), String> {
    let n = x0.len() - 1;
    let t = &a.t;
    let spread0 = x0[n].clone() - &x0[0];
    let c0 = spread0.clone() + sup_u0;
    let two = S::from_i64(2);
    let su = sup_abs(&a.u[1..]);
    if su > *sup_u0 {
        return Err(format!(
            "sup|u(t)| = {} > sup|u⁰| = {}",
            su.render(),
            sup_u0.render()
        ));
    }
    let spread = a.x[n].clone() - &a.x[0];
    let bv = spread0 + &(two.clone() * t * sup_u0);
    let bv_c = (S::one() + &(two.clone() * t)) * &c0;
    if spread > bv || bv > bv_c {
        return Err(format!(
            "x_N − x_0 = {}, (x⁰_N − x⁰_0) + 2T sup|u⁰| = {}, (1 + 2T)C'_0 = {}",
            spread.render(),
            bv.render(),
            bv_c.render()
        ));
    }
    let from0: Vec<S> = a.x.iter().map(|x| x.clone() - &x0[0]).collect();
    let x_n = sup_abs(&from0[1..]);
    let x_tilde = sup_abs(&from0);
    let x_sum = x_n.clone() + &x_tilde;
    let x_mid = two.clone() * &(t.clone() * sup_u0 + &bv);
    let x_c = two.clone() * &(S::one() + &(S::from_i64(3) * t)) * &c0;
    if x_sum > x_mid || x_mid > x_c {
        return Err(format!(
            "‖X_N‖_∞ + ‖X̃_N‖_∞ = {} + {}, 2(T sup|u⁰| + (x⁰_N − x⁰_0) + 2T sup|u⁰|) = {}, 2(1 + 3T)C'_0 = {}",
            x_n.render(),
            x_tilde.render(),
            x_mid.render(),
            x_c.render()
        ));
    }
    let l_n = sup_abs(&a.lambda[1..]);
    let l_tilde = sup_abs(&a.lambda);
    let l_sum = l_n.clone() + &l_tilde;
    let l_mid = S::from_i64(4) * sup_u0;
    if l_sum > l_mid || l_mid > S::from_i64(4) * &c0 {
        return Err(format!(
            "‖Λ_N‖_∞ + ‖Λ̃_N‖_∞ = {} + {} > 4 sup|u⁰| = {}",
            l_n.render(),
            l_tilde.render(),
            l_mid.render()
        ));
    }
    Ok(())
}

/// `prop:Linf-micro` at every probe time (`T = t`), with the constants
/// above (`δ = 1`).
pub fn linf_micro<S: Scalar>(case: &Case<S>) -> R {
    let all = states(case, ID)?;
    let Some(first) = all.first() else {
        return Ok(());
    };
    debug_assert!(first.t.is_zero());
    let sup_u0 = sup_abs(case.data().velocities());
    for a in &all {
        linf_at(a, &first.x, &sup_u0).map_err(|e| {
            Violation::new(
                ID,
                format!("t = T = {}, N = {}: {e}", a.t.render(), case.n()),
            )
        })?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::initial::InitialData;
    use num_rational::BigRational;

    fn q(n: i64, d: i64) -> BigRational {
        BigRational::new(n.into(), d.into())
    }

    /// N = 2, 2r = 1/2: a head-on collision at t = 1/4, λ_1 = 1/2 after.
    #[test]
    fn bounds_hold_and_tampering_fails() {
        let data = InitialData::with_paper_radius(vec![q(0, 1), q(1, 1)], vec![q(1, 1), q(-1, 1)])
            .unwrap();
        let case = Case::new(data, None);
        linf_micro(&case).unwrap();
        let all = states(&case, ID).unwrap();
        let x0 = all[0].x.clone();
        let sup_u0 = q(1, 1);
        let last = all.last().unwrap();
        assert_eq!(last.lambda[1], q(1, 2));
        linf_at(last, &x0, &sup_u0).unwrap();
        // λ not divided by N, and then some: Λ_N beyond 4 sup|u⁰|.
        let mut big = states(&case, ID).unwrap().pop().unwrap();
        big.lambda = big.lambda.iter().map(|l| l * q(10, 1)).collect();
        assert!(linf_at(&big, &x0, &sup_u0).is_err());
        // A particle flown off: x_N far beyond the spread bound.
        let mut far = states(&case, ID).unwrap().pop().unwrap();
        far.x[2] = far.x[2].clone() + q(100, 1);
        assert!(linf_at(&far, &x0, &sup_u0).is_err());
        // A velocity above sup|u⁰|.
        let mut fast = states(&case, ID).unwrap().pop().unwrap();
        fast.u[1] = q(2, 1);
        assert!(linf_at(&fast, &x0, &sup_u0).is_err());
    }
}
