//! Appendix A: the KKT multipliers `μ(t)` of the projection (`app:KKT`),
//! and the identity of the uniqueness proof of `prop:proj-micro`
//! (`prop:proj-micro#uniqueness-identity`).

use super::{dot, lambda_integral, render_vec, state, sub, R};
use crate::claims::coq::Statement;
use crate::claims::{Case, Violation};
use crate::contact::kkt_multipliers;
use crate::initial::InitialData;
use crate::projection::free_flight;
use crate::scalar::Scalar;

/// `app:KKT`, as printed: "the KKT conditions apply and yield the existence
/// of multipliers λ_i(t) ≥ 0 such that x(t) − (x⁰ + t u⁰) + N Σ λ_i(t)(e_i −
/// e_{i+1}) = 0 … This provides directly the multipliers … introduced in the
/// main text" — checked with the `λ` of `eq:dyn-micro`.
pub fn kkt_printed<S: Scalar>(case: &Case<S>) -> R {
    const ID: &str = "app:KKT";
    for t in &case.times {
        let s = state(case, t, ID)?;
        let y = free_flight(case.data(), t);
        let (mu, _) = kkt_multipliers(&y, &s.positions);
        if mu != s.multipliers {
            return Err(Violation::new(
                ID,
                format!(
                    "t = {}: the stationarity condition needs multipliers {} but eq:dyn-micro's λ(t) = {}",
                    t.render(),
                    render_vec(&mu),
                    render_vec(&s.multipliers)
                ),
            )
            .at(t.render())
            .sides(
                "KKT multipliers μ(t)",
                render_vec(&mu),
                "λ(t) of eq:dyn-micro",
                render_vec(&s.multipliers),
            ));
        }
    }
    Ok(())
}

/// Corrected `app:KKT`: the KKT multipliers `μ(t)` of the position
/// projection satisfy stationarity, `μ ≥ 0`, `μ_N = 0`, complementarity, and
/// `μ(t) = ∫_0^t λ(s) ds`.
pub fn kkt_corrected<S: Scalar>(case: &Case<S>) -> R {
    const ID: &str = "app:KKT (corrected)";
    let two_r = case.data().two_r();
    for t in &case.times {
        let s = state(case, t, ID)?;
        let y = free_flight(case.data(), t);
        let (mu, mu_n) = kkt_multipliers(&y, &s.positions);
        let integral = lambda_integral(&case.traj, t);
        if mu != integral || !mu_n.is_zero() {
            return Err(Violation::new(
                ID,
                format!(
                    "t = {}: μ = {} (μ[N−1] = {}) but ∫λ = {}",
                    t.render(),
                    render_vec(&mu),
                    mu_n.render(),
                    render_vec(&integral)
                ),
            ));
        }
        for (i, m) in mu.iter().enumerate() {
            let slack = s.positions[i + 1].clone() - &s.positions[i] - &two_r;
            if *m < S::zero() || (!m.is_zero() && !slack.is_zero()) {
                return Err(Violation::new(
                    ID,
                    format!(
                        "t = {}: μ[{i}] = {}, slack {}",
                        t.render(),
                        m.render(),
                        slack.render()
                    ),
                ));
            }
        }
    }
    Ok(())
}

/// `prop:proj-micro#uniqueness-identity`: for two solutions with the same
/// `u⁰`, "(N²/2) d/dt ‖x¹ − x²‖² = −⟨ξ¹ − ξ², x¹ − x²⟩". The second solution
/// starts from `x⁰ + (0, r, 2r, …)` (still in `K`); derivatives are right
/// derivatives at the probe times.
pub fn uniqueness_identity_printed<S: Scalar>(case: &Case<S>) -> R {
    uniqueness(
        case,
        "prop:proj-micro#uniqueness-identity",
        Statement::Printed,
    )
}

/// Corrected: `(N/2) d/dt ‖x¹ − x²‖² = −⟨ξ¹ − ξ², x¹ − x²⟩ ≤ 0`
/// (monotonicity of `∂I_K`).
pub fn uniqueness_identity_corrected<S: Scalar>(case: &Case<S>) -> R {
    uniqueness(
        case,
        "prop:proj-micro#uniqueness-identity (corrected)",
        Statement::Corrected,
    )
}

fn uniqueness<S: Scalar>(case: &Case<S>, id: &'static str, statement: Statement) -> R {
    let corrected = statement == Statement::Corrected;
    let data = case.data();
    let r = data.radius().clone();
    let mut off = S::zero();
    let x2: Vec<S> = data
        .positions()
        .iter()
        .map(|x| {
            let v = x.clone() + &off;
            off = off.clone() + &r;
            v
        })
        .collect();
    let other = InitialData::new(r, x2, data.velocities().to_vec())
        .map_err(|e| Violation::new(id, format!("second datum: {e}")))?;
    let n = S::from_usize(case.n());
    for t in &case.times {
        let s1 = state(case, t, id)?;
        let s2 = case
            .state_of(&other, t)
            .map_err(|e| Violation::new(id, e.to_string()))?;
        let d = sub(&s1.positions, &s2.positions);
        let dd = sub(&s1.velocities, &s2.velocities);
        // ξ^a = u⁰ − u^a, so −⟨ξ¹ − ξ², d⟩ = ⟨u¹ − u², d⟩.
        let rhs = dot(&dd, &d);
        // d/dt ‖d‖² = (2/N)⟨d', d⟩.
        let deriv = S::from_i64(2) / &n * &rhs;
        let factor = if corrected { n.clone() } else { n.clone() * &n };
        let lhs = factor / S::from_i64(2) * &deriv;
        if lhs != rhs || (corrected && rhs > S::zero()) {
            return Err(Violation::new(
                id,
                format!(
                    "t = {}: {} d/dt‖x¹−x²‖² = {} but −⟨ξ¹−ξ², x¹−x²⟩ = {}",
                    t.render(),
                    if corrected { "(N/2)" } else { "(N²/2)" },
                    lhs.render(),
                    rhs.render()
                ),
            )
            .at(t.render())
            .sides(
                "(N²/2) d/dt‖x¹−x²‖² (N/2 corrected)",
                lhs.render(),
                "−⟨ξ¹−ξ², x¹−x²⟩",
                rhs.render(),
            ));
        }
    }
    Ok(())
}
