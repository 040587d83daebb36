//! The semigroup property (`eq:semigroup`, `eq:projortho-sg`) and the
//! growth of the contact set in time (`df:H-micro`).

use super::{render_vec, state, R};
use crate::claims::coq::Statement;
use crate::claims::{Case, Violation};
use crate::cluster::{contact_clusters, project_h};
use crate::projection::project_k;
use crate::scalar::Scalar;
use crate::state::State;

/// The half of the semigroup property a check reads.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Half {
    /// `eq:semigroup`: `x(t) = P_K(x(s) + (t − s)u(s))`.
    Positions,
    /// `eq:projortho-sg`: `u(t) = P_{H_{x(t)}}(u(s))`.
    Velocities,
}

/// `eq:semigroup` or `eq:projortho-sg` (the `half`) for probe times `s < t`.
fn semigroup_half<S: Scalar>(case: &Case<S>, half: Half) -> R {
    let id = match half {
        Half::Positions => "eq:semigroup",
        Half::Velocities => "eq:projortho-sg",
    };
    let two_r = case.data().two_r();
    let states: Vec<State<S>> = case
        .times
        .iter()
        .map(|t| state(case, t, id))
        .collect::<Result<_, _>>()?;
    for (a, s) in states.iter().enumerate() {
        for st in &states[a + 1..] {
            if st.t <= s.t {
                continue;
            }
            let dt = st.t.clone() - &s.t;
            match half {
                Half::Positions => {
                    let y: Vec<S> = s
                        .positions
                        .iter()
                        .zip(&s.velocities)
                        .map(|(x, u)| x.clone() + &(dt.clone() * u))
                        .collect();
                    let x = project_k(&y, &two_r);
                    if x != st.positions {
                        return Err(Violation::new(
                            id,
                            format!(
                                "s = {}, t = {}: P_K(x(s) + (t−s)u(s)) = {} but x(t) = {}",
                                s.t.render(),
                                st.t.render(),
                                render_vec(&x),
                                render_vec(&st.positions)
                            ),
                        ));
                    }
                }
                Half::Velocities => {
                    let u = project_h(&s.velocities, &contact_clusters(&st.positions, &two_r));
                    if u != st.velocities {
                        return Err(Violation::new(
                            id,
                            format!(
                                "s = {}, t = {}: P_H(u(s)) = {} but u(t) = {}",
                                s.t.render(),
                                st.t.render(),
                                render_vec(&u),
                                render_vec(&st.velocities)
                            ),
                        ));
                    }
                }
            }
        }
    }
    Ok(())
}

/// `eq:semigroup`.
pub fn semigroup<S: Scalar>(case: &Case<S>) -> R {
    semigroup_half(case, Half::Positions)
}

/// `eq:projortho-sg`.
pub fn projortho_sg<S: Scalar>(case: &Case<S>) -> R {
    semigroup_half(case, Half::Velocities)
}

/// `df:H-micro#contacts-grow` as printed (`Ω` grows from `s = 0` on) or
/// corrected (from `s = 0` only when `u⁰ ∈ H_{x⁰}`, else for `s > 0`).
fn contacts_grow<S: Scalar>(case: &Case<S>, id: &'static str, statement: Statement) -> R {
    let two_r = case.data().two_r();
    let from_zero = statement == Statement::Printed;
    let h0 = crate::cluster::h_violation(case.data().positions(), case.data().velocities(), &two_r)
        .is_none();
    let times: Vec<&S> = case
        .times
        .iter()
        .filter(|t| from_zero || t.total_cmp(&S::zero()).is_gt() || h0)
        .collect();
    let mut prev: Option<(&S, Vec<usize>)> = None;
    for t in times {
        let s = state(case, t, id)?;
        let omega = crate::cluster::contact_set(&s.positions, &two_r);
        if let Some((ps, pomega)) = &prev {
            if let Some(j) = pomega.iter().find(|j| !omega.contains(j)) {
                return Err(Violation::new(
                    id,
                    format!(
                        "pair ({j}, {}) is in contact at s = {} but not at t = {} (u⁰ ∈ C_x⁰ \\ H_x⁰: u⁰[{j}] = {} < u⁰[{}] = {})",
                        j + 1,
                        ps.render(),
                        t.render(),
                        case.data().velocities()[*j].render(),
                        j + 1,
                        case.data().velocities()[j + 1].render()
                    ),
                ));
            }
        }
        prev = Some((t, omega));
    }
    Ok(())
}

/// `df:H-micro#contacts-grow`: "the set of active constraints is
/// non-decreasing in time … N_{x(s)}K ⊂ N_{x(t)}K for all s ≤ t" (stated
/// for data `x⁰ ∈ K`, `u⁰ ∈ C_{x⁰}`).
pub fn contacts_grow_printed<S: Scalar>(case: &Case<S>) -> R {
    contacts_grow(case, "df:H-micro#contacts-grow", Statement::Printed)
}

/// Corrected: `Ω_{x(s)} ⊂ Ω_{x(t)}` for `0 < s ≤ t`, and from `s = 0` when
/// `u⁰ ∈ H_{x⁰}`.
pub fn contacts_grow_corrected<S: Scalar>(case: &Case<S>) -> R {
    contacts_grow(
        case,
        "df:H-micro#contacts-grow (corrected)",
        Statement::Corrected,
    )
}
