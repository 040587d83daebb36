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

use super::discrete::{abs, augmented, states, Augmented};
use super::{Case, FromPaper, Violation};
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
    for (i, u) in a.u.iter().enumerate().skip(1) {
        if u > sup_u0 || -u.clone() > *sup_u0 {
            return Err(format!(
                "|u[{}](t)| = {} > sup|u⁰| = {}",
                FromPaper(i),
                abs(u.clone()).render(),
                sup_u0.render()
            ));
        }
    }
    let spread = a.x[n].clone() - &a.x[0];
    let bv = spread0 + &(two.clone() * t * sup_u0);
    let bv_c = (S::one() + &(two.clone() * t)) * &c0;
    if spread > bv || bv > bv_c {
        return Err(format!(
            "x[N−1] − x[−1] = {}, (x⁰[N−1] − x⁰[−1]) + 2T sup|u⁰| = {}, (1 + 2T)C'_0 = {}",
            spread.render(),
            bv.render(),
            bv_c.render()
        ));
    }
    // ‖X_N‖_∞ ≤ ‖X̃_N‖_∞ = max_{0 ≤ i ≤ N} |x_i − x⁰_0|: checked node by node
    // (no maximum is formed, which keeps the symbolic prover's paths few).
    let x_mid = t.clone() * sup_u0 + &bv;
    let x_c = (S::one() + &(S::from_i64(3) * t)) * &c0;
    if x_mid > x_c {
        return Err(format!(
            "T sup|u⁰| + (x⁰[N−1] − x⁰[−1]) + 2T sup|u⁰| = {} > (1 + 3T)C'_0 = {}",
            x_mid.render(),
            x_c.render()
        ));
    }
    for (i, x) in a.x.iter().enumerate() {
        let d = x.clone() - &x0[0];
        if d > x_mid || -d.clone() > x_mid {
            return Err(format!(
                "|x[{}](t) − x⁰[−1]| = {} > T sup|u⁰| + (x⁰[N−1] − x⁰[−1]) + 2T sup|u⁰| = {} (so ‖X_N‖_∞ + ‖X̃_N‖_∞ may exceed 2(1 + 3T)C'_0)",
                FromPaper(i),
                abs(d).render(),
                x_mid.render()
            ));
        }
    }
    // ‖Λ_N‖_∞ = ‖Λ̃_N‖_∞ = max_i |λ_i| ≤ 2 sup|u⁰|, node by node.
    let l_mid = two.clone() * sup_u0;
    for (i, l) in a.lambda.iter().enumerate() {
        if *l > l_mid || -l.clone() > l_mid {
            return Err(format!(
                "|λ[{}]| = {} > 2 sup|u⁰| = {} (so ‖Λ_N‖_∞ + ‖Λ̃_N‖_∞ may exceed 4 sup|u⁰| ≤ 4C'_0)",
                FromPaper(i),
                abs(l.clone()).render(),
                l_mid.render()
            ));
        }
    }
    Ok(())
}

/// `prop:Linf-micro` at every probe time (`T = t`), with the constants
/// above (`δ = 1`).
pub fn linf_micro<S: Scalar>(case: &Case<S>) -> R {
    let initial = case
        .state(&S::zero())
        .map_err(|e| Violation::new(ID, e.to_string()))?;
    let x0 = augmented(case, &initial).x;
    let sup_u0 = sup_abs(case.data().velocities());
    for a in &states(case, ID)? {
        linf_at(a, &x0, &sup_u0).map_err(|e| {
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

    use crate::rational::ratio as q;

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
