//! The uniform bounds of `prop:bound-micro` on positions and velocities,
//! and `prop:Oleinik` (the one-sided Lipschitz bound `1/t`).

use super::{norm2, positive_times, render_vec, state, sub, R};
use crate::claims::{Case, Violation};
use crate::projection::{free_flight, project_k};
use crate::scalar::Scalar;

/// `prop:bound-micro#position-contraction`: `‖x(t)‖ ≤ ‖x⁰ + t u⁰‖`.
pub fn position_contraction<S: Scalar>(case: &Case<S>) -> R {
    const ID: &str = "prop:bound-micro#position-contraction";
    for t in &case.times {
        let s = state(case, t, ID)?;
        let y = free_flight(case.data(), t);
        let (lhs, rhs) = (norm2(&s.positions), norm2(&y));
        if lhs > rhs {
            return Err(Violation::new(
                ID,
                format!(
                    "t = {}: ‖x(t)‖² = {} > ‖x⁰ + t u⁰‖² = {} (x⁰ + t u⁰ = {}, x(t) = {})",
                    t.render(),
                    lhs.render(),
                    rhs.render(),
                    render_vec(&y),
                    render_vec(&s.positions)
                ),
            ));
        }
    }
    Ok(())
}

/// Correction of `prop:bound-micro#position-contraction`: `P_K` is
/// non-expansive, so `‖x(t) − P_K(0)‖ ≤ ‖x⁰ + t u⁰ − P_K(0)‖`, and
/// `‖P_K(0)‖² = (2r)²(N² − 1)/12` (independent of N when `2r = 1/N`).
pub fn position_nonexpansive<S: Scalar>(case: &Case<S>) -> R {
    const ID: &str = "prop:bound-micro#position-contraction (corrected)";
    let two_r = case.data().two_r();
    let n = case.n();
    let p0 = project_k(&vec![S::zero(); n], &two_r);
    let expected = two_r.clone() * &two_r * S::from_usize(n * n - 1) / S::from_i64(12);
    if norm2(&p0) != expected {
        return Err(Violation::new(
            ID,
            format!(
                "‖P_K(0)‖² = {} ≠ (2r)²(N²−1)/12 = {}",
                norm2(&p0).render(),
                expected.render()
            ),
        ));
    }
    for t in &case.times {
        let s = state(case, t, ID)?;
        let y = free_flight(case.data(), t);
        let (lhs, rhs) = (norm2(&sub(&s.positions, &p0)), norm2(&sub(&y, &p0)));
        if lhs > rhs {
            return Err(Violation::new(
                ID,
                format!(
                    "t = {}: ‖x − P_K(0)‖² = {} > {}",
                    t.render(),
                    lhs.render(),
                    rhs.render()
                ),
            ));
        }
    }
    Ok(())
}

/// `prop:bound-micro#velocity-bound`: `‖u(t)‖ ≤ ‖u⁰‖`.
pub fn velocity_bound<S: Scalar>(case: &Case<S>) -> R {
    const ID: &str = "prop:bound-micro#velocity-bound";
    let rhs = norm2(case.data().velocities());
    for t in &case.times {
        let s = state(case, t, ID)?;
        let lhs = norm2(&s.velocities);
        if lhs > rhs {
            return Err(Violation::new(
                ID,
                format!(
                    "t = {}: ‖u‖² = {} > ‖u⁰‖² = {}",
                    t.render(),
                    lhs.render(),
                    rhs.render()
                ),
            ));
        }
    }
    Ok(())
}

/// `prop:Oleinik` (`eq:Oleinik-micro`): `(u_i − u_{i−1})/(x_i − x_{i−1}) < 1/t`
/// for `t > 0` and `i = 2 … N`, i.e. `t(u_i − u_{i−1}) < x_i − x_{i−1}`.
pub fn oleinik<S: Scalar>(case: &Case<S>) -> R {
    const ID: &str = "prop:Oleinik";
    for t in positive_times(case) {
        let s = state(case, t, ID)?;
        for i in 1..case.n() {
            let lhs = t.clone() * &(s.velocities[i].clone() - &s.velocities[i - 1]);
            let rhs = s.positions[i].clone() - &s.positions[i - 1];
            if lhs >= rhs {
                return Err(Violation::new(
                    ID,
                    format!(
                        "t = {}, pair ({p}, {i}): t(u[{i}] − u[{p}]) = {} ≥ x[{i}] − x[{p}] = {}",
                        t.render(),
                        lhs.render(),
                        rhs.render(),
                        p = i - 1
                    ),
                ));
            }
        }
    }
    Ok(())
}

/// `prop:Oleinik#backward-characteristics`: if particles `i−1` and `i` are
/// not in contact at `t`, then `x_{i−1}(t) − t u_{i−1}(t) ≤ x_{i−1}(0)` and
/// `x_i(t) − t u_i(t) ≥ x_i(0)`.
pub fn oleinik_characteristics<S: Scalar>(case: &Case<S>) -> R {
    const ID: &str = "prop:Oleinik#backward-characteristics";
    let two_r = case.data().two_r();
    let x0 = case.data().positions();
    for t in positive_times(case) {
        let s = state(case, t, ID)?;
        for i in 1..case.n() {
            if s.positions[i].clone() - &s.positions[i - 1] == two_r {
                continue;
            }
            let xl = s.positions[i - 1].clone() - &(t.clone() * &s.velocities[i - 1]);
            let xr = s.positions[i].clone() - &(t.clone() * &s.velocities[i]);
            if xl > x0[i - 1] || xr < x0[i] {
                return Err(Violation::new(
                    ID,
                    format!(
                        "t = {}, pair ({}, {i}): x_ℓ = {} (x[{}](0) = {}), x_r = {} (x[{i}](0) = {})",
                        t.render(),
                        i - 1,
                        xl.render(),
                        i - 1,
                        x0[i - 1].render(),
                        xr.render(),
                        x0[i].render()
                    ),
                ));
            }
        }
    }
    Ok(())
}
