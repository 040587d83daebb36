//! `lem:discPDE2` (`eq:PDE-Lagr-N-2`) in its discrete form: `∂_t X_N = U_N`,
//! `∂_t U_N + ∂_w P̃_N = 0`, `∂_w X̃_N ≥ 1`, `P_N ≥ 0`. Between collisions
//! every `x_i` moves with `u_i` and `λ` is constant; `P_N = ∂_t Λ_N` is a sum
//! of Dirac masses at the collision instants with weights the jumps `[λ_i]`,
//! and on `((i−1)/N, i/N)` `∂_w P̃_N = N(p_i − p_{i−1})`, so the momentum
//! equation is, at each collision instant `t_k`,
//! `u_i(t_k) − u_i(t_k⁻) = −N([λ_i] − [λ_{i−1}])`, `[λ_0] = [λ_N] = 0`
//! (`eq:micro-2nd-ID`). Velocities come from the projection formula at
//! `t_k` and at a time before it; the jumps from the event history.

use super::discrete::augmented_jumps;
use super::{Case, FromPaper, Violation};
use crate::scalar::Scalar;

const ID: &str = "lem:discPDE2";

type R = Result<(), Violation>;

/// The momentum equation at one collision instant: `du` the velocity jumps
/// `u_i(t_k) − u_i(t_k⁻)` (`i = 1 … N`), `jumps` the jumps `[λ_0] … [λ_N]`.
/// Also `P_N ≥ 0` (`[λ_i] ≥ 0`) and `[λ_0] = [λ_N] = 0`.
pub(super) fn momentum_at<S: Scalar>(du: &[S], jumps: &[S]) -> Result<(), String> {
    let n = du.len();
    let nn = S::from_usize(n);
    if !jumps[0].is_zero() || !jumps[n].is_zero() {
        return Err("the boundary pressures p[−1], p[N−1] do not vanish".to_string());
    }
    for i in 1..=n {
        let rhs = -(nn.clone() * &(jumps[i].clone() - &jumps[i - 1]));
        if du[i - 1] != rhs {
            return Err(format!(
                "particle [{}] (i = {i} in the paper's numbering): u_i(t) − u_i(t⁻) = {} but −N([λ_i] − [λ_{{i−1}}]) = {}",
                i - 1,
                du[i - 1].render(),
                rhs.render()
            ));
        }
        if jumps[i].total_cmp(&S::zero()).is_lt() {
            return Err(format!(
                "the jump of λ[{}] is {} < 0 (P_N ≥ 0)",
                FromPaper(i),
                jumps[i].render()
            ));
        }
    }
    Ok(())
}

/// `lem:discPDE2` on a case with `2r = 1/N`: at every collision instant (a
/// spread of 40 when there are more), the momentum equation, `P_N ≥ 0`,
/// `∂_t X_N = U_N` on the interval before it (`x(t_k) − x(s) = (t_k − s)
/// u(s)`, `s` the midpoint since the previous instant) and `∂_w X̃_N ≥ 1`
/// (`N(x_{i+1} − x_i) ≥ 1`); and `∂_t X_N = U_N` after the last collision.
pub fn disc_pde2<S: Scalar>(case: &Case<S>) -> R {
    let n = case.n();
    let nn = S::from_usize(n);
    let at = |t: &S| case.state(t).map_err(|e| Violation::new(ID, e.to_string()));
    let mut instants: Vec<S> = Vec::new();
    for imp in case.traj.impulses() {
        if instants.last() != Some(&imp.t) {
            instants.push(imp.t.clone());
        }
    }
    let keep: Vec<usize> = if instants.len() <= 40 {
        (0..instants.len()).collect()
    } else {
        let m = instants.len() - 1;
        let mut v: Vec<usize> = (0..40).map(|j| j * m / 39).collect();
        v.dedup();
        v
    };
    let flight = |s0: &crate::state::State<S>, s1: &crate::state::State<S>| -> R {
        let dt = s1.t.clone() - &s0.t;
        for i in 0..n {
            let moved = s1.positions[i].clone() - &s0.positions[i];
            if moved != dt.clone() * &s0.velocities[i] {
                return Err(Violation::new(
                    ID,
                    format!(
                        "∂_t X_N = U_N: x[{i}]({}) − x[{i}]({}) = {} but (t − s) u[{i}](s) = {}",
                        s1.t.render(),
                        s0.t.render(),
                        moved.render(),
                        (dt.clone() * &s0.velocities[i]).render()
                    ),
                ));
            }
        }
        Ok(())
    };
    for k in keep {
        let t = &instants[k];
        let prev = if k == 0 {
            S::zero()
        } else {
            instants[k - 1].clone()
        };
        let mid = (prev + t) / S::from_i64(2);
        let (before, after) = (at(&mid)?, at(t)?);
        flight(&before, &after)?;
        let mut jumps = vec![S::zero(); n + 1];
        for imp in case.traj.impulses().iter().filter(|i| i.t == *t) {
            for (i, j) in augmented_jumps(n, imp).into_iter().enumerate() {
                jumps[i] = jumps[i].clone() + &j;
            }
        }
        let du: Vec<S> = after
            .velocities
            .iter()
            .zip(&before.velocities)
            .map(|(a, b)| a.clone() - b)
            .collect();
        momentum_at(&du, &jumps)
            .map_err(|e| Violation::new(ID, format!("collision at t = {}: {e}", t.render())))?;
        for i in 0..n.saturating_sub(1) {
            let slope = nn.clone() * &(after.positions[i + 1].clone() - &after.positions[i]);
            if slope < S::one() {
                return Err(Violation::new(
                    ID,
                    format!(
                        "t = {}: ∂_w X̃_N = N(x[{}] − x[{i}]) = {} < 1",
                        t.render(),
                        i + 1,
                        slope.render()
                    ),
                ));
            }
        }
    }
    let last = instants.last().cloned().unwrap_or_else(S::zero);
    flight(&at(&last)?, &at(&(last.clone() + &S::one()))?)
}

/// The argument that proves `prop:pressure-bound` with the pair-indexed
/// pressure (where the exclusion is exact): at each collision instant
/// `t_k` (a spread of 40), testing `eq:micro-2nd-ID` with
/// `φ_i = (x_N − x_0) i/N − x_i` (`i = 0 … N`, the test function of the
/// proof at the nodes) and summing by parts (`[λ_0] = [λ_N] = 0`):
/// `(1/N) Σ_{i=1}^N [u_i] φ_i = Σ_{i=1}^{N−1} [λ_i] (φ_{i+1} − φ_i)
///  = Σ_i [λ_i] ((x_N − x_0)/N − (x_{i+1} − x_i)) = ((x_N − x_0) − 1)/N · Σ_i [λ_i]
///  ≥ (δ/N) Σ_i [λ_i] ≥ 0`,
/// the third equality because `[λ_i] > 0` only where `x_{i+1} − x_i = 1/N`;
/// and `(1/N) Σ_i [λ_i]` is the mass of both `P_N` and `P̃_N` at `t_k`.
/// Velocity jumps from the projection formula, `[λ]` from the history.
pub fn pressure_bound_by_parts<S: Scalar>(case: &Case<S>) -> R {
    const ID: &str = "prop:pressure-bound#exclusion (corrected)";
    let n = case.n();
    let at = |t: &S| case.state(t).map_err(|e| Violation::new(ID, e.to_string()));
    let mut prev = S::zero();
    let mut done: Option<S> = None;
    for imp in case.impulse_spread() {
        let t = &imp.t;
        if done.as_ref() == Some(t) {
            continue;
        }
        done = Some(t.clone());
        // The latest collision instant before t (over all impulses).
        for other in case.traj.impulses() {
            if other.t < *t && other.t > prev {
                prev = other.t.clone();
            }
        }
        let mid = (prev.clone() + t) / S::from_i64(2);
        let (before, after) = (at(&mid)?, at(t)?);
        let mut jumps = vec![S::zero(); n + 1];
        for i in case.traj.impulses().iter().filter(|i| i.t == *t) {
            for (k, j) in augmented_jumps(n, i).into_iter().enumerate() {
                jumps[k] = jumps[k].clone() + &j;
            }
        }
        pressure_bound_at(
            &before.velocities,
            &after.velocities,
            &after.positions,
            &jumps,
        )
        .map_err(|e| Violation::new(ID, format!("collision at t = {}: {e}", t.render())))?;
    }
    Ok(())
}

/// One instant of [`pressure_bound_by_parts`]: `u⁻`, `u` the velocities
/// before and at `t_k`, `x` the positions (`2r = 1/N`), `jumps` `[λ_0] …
/// [λ_N]`.
pub(super) fn pressure_bound_at<S: Scalar>(
    u_before: &[S],
    u: &[S],
    x: &[S],
    jumps: &[S],
) -> Result<(), String> {
    let n = x.len();
    let nn = S::from_usize(n);
    let delta = super::discrete::delta::<S>();
    let x0 = x[0].clone() - &(S::one() / &nn) - &delta;
    let spread = x[n - 1].clone() - &x0;
    let phi = |i: usize| -> S {
        let xi = if i == 0 { x0.clone() } else { x[i - 1].clone() };
        spread.clone() * &S::from_usize(i) / &nn - &xi
    };
    let lhs = (1..=n).fold(S::zero(), |acc, i| {
        acc + &((u[i - 1].clone() - &u_before[i - 1]) * &phi(i))
    }) / &nn;
    let by_parts = (1..n).fold(S::zero(), |acc, i| {
        acc + &(jumps[i].clone() * &(phi(i + 1) - &phi(i)))
    });
    let mass = (1..n).fold(S::zero(), |acc, i| acc + &jumps[i]);
    let contact = (spread.clone() - &S::one()) / &nn * &mass;
    let lower = delta / &nn * &mass;
    if lhs != by_parts || by_parts != contact || contact < lower || lower < S::zero() {
        return Err(format!(
            "(1/N) Σ [u_i] φ_i = {}, Σ [λ_i](φ_{{i+1}} − φ_i) = {}, ((x[N−1] − x[−1]) − 1)/N · Σ[λ_i] = {}, (δ/N) Σ[λ_i] = {}",
            lhs.render(),
            by_parts.render(),
            contact.render(),
            lower.render()
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::initial::InitialData;

    use crate::rational::ratio as q;

    /// N = 3, 2r = 1/3: particles 1, 2 meet, then 3 joins.
    #[test]
    fn momentum_holds_and_tampered_jumps_fail() {
        let data = InitialData::with_paper_radius(
            vec![q(0, 1), q(1, 1), q(2, 1)],
            vec![q(2, 1), q(0, 1), q(-1, 1)],
        )
        .unwrap();
        let case = Case::new(data, None);
        disc_pde2(&case).unwrap();
        let imp = &case.traj.impulses()[0];
        let jumps = augmented_jumps(3, imp);
        let before = case.state(&(imp.t.clone() / q(2, 1))).unwrap();
        let after = case.state(&imp.t).unwrap();
        let du: Vec<_> = after
            .velocities
            .iter()
            .zip(&before.velocities)
            .map(|(a, b)| a - b)
            .collect();
        momentum_at(&du, &jumps).unwrap();
        // λ not divided by N, λ with its sign flipped: the equation fails.
        let times_n: Vec<_> = jumps.iter().map(|j| j * q(3, 1)).collect();
        assert!(momentum_at(&du, &times_n).is_err());
        let flipped: Vec<_> = jumps.iter().map(|j| -j).collect();
        assert!(momentum_at(&du, &flipped).is_err());
        // A velocity that leaves one particle out of the cluster mean.
        let mut short = du.clone();
        short[1] = short[1].clone() + q(1, 2);
        assert!(momentum_at(&short, &jumps).is_err());
        // The summation by parts of prop:pressure-bound: exact, and blind
        // neither to the sign nor to the scale of λ.
        pressure_bound_by_parts(&case).unwrap();
        let (ub, ua, x) = (&before.velocities, &after.velocities, &after.positions);
        pressure_bound_at(ub, ua, x, &jumps).unwrap();
        assert!(pressure_bound_at(ub, ua, x, &flipped).is_err());
        assert!(pressure_bound_at(ub, ua, x, &times_n).is_err());
    }
}
