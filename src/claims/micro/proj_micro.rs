//! The projection formula and the velocity projection (section 2,
//! `prop:proj-micro`, `eq:proj-micro-x`, `eq:proj-u-micro`,
//! `prop:proj-velo-micro`, `lem:incl-HSN`, `eq:ineg-projortho`): the sticky
//! history equals `x(t) = P_K(x⁰ + t u⁰)`, `u(t) = P_{H_{x(t)}}(u⁰)`, and the
//! steps of their proofs.

use super::{dot, positive_times, render_state, render_vec, state, sub, tangent_cone_violation, R};
use crate::claims::{Case, Violation};
use crate::cluster::{contact_clusters, project_h};
use crate::error::Error;
use crate::initial::shift;
use crate::projection::{free_flight, state_at};
use crate::scalar::Scalar;
use crate::state::State;
use crate::trajectory::Trajectory;

/// `prop:proj-micro` (`eq:proj-micro-x`, `eq:proj-u-micro`): the event-driven
/// sticky history equals the projection formula at time `t` — positions,
/// right-derivative velocities, multipliers and contact clusters, exactly.
/// Returns the (common) state.
pub fn projection_formula<S: Scalar>(traj: &Trajectory<S>, t: &S) -> Result<State<S>, Violation> {
    agree(
        traj.at(t),
        state_at(traj.data(), t),
        t,
        &traj.data().two_r(),
    )
}

/// The two engines' states at `t`, compared (`prop:proj-micro`); the
/// clusters they report must be the contact clusters of the positions
/// (`df:Omega-micro`), not merely the same list from both.
fn agree<S: Scalar>(
    events: Result<State<S>, Error>,
    proj: Result<State<S>, Error>,
    t: &S,
    two_r: &S,
) -> Result<State<S>, Violation> {
    const ID: &str = "prop:proj-micro";
    let events = events
        .map_err(|e| Violation::new(ID, format!("event engine refused t = {}: {e}", t.render())))?;
    let proj = proj
        .map_err(|e| Violation::new(ID, format!("projection refused t = {}: {e}", t.render())))?;
    if events == proj {
        let contact = contact_clusters(&proj.positions, two_r);
        if contact == proj.clusters {
            return Ok(proj);
        }
        return Err(Violation::new(
            ID,
            format!(
                "at t = {}: clusters {:?} reported, but the contact clusters of x(t) are {:?}",
                t.render(),
                proj.clusters,
                contact
            ),
        ));
    }
    Err(Violation::new(
        ID,
        format!(
            "at t = {}: event-driven {} vs projection {}",
            t.render(),
            render_state(&events),
            render_state(&proj)
        ),
    ))
}

/// `prop:proj-micro` on every probe time of the case.
pub fn proj_micro<S: Scalar>(case: &Case<S>) -> R {
    for t in &case.times {
        agree(
            case.history_state(t),
            case.state(t),
            t,
            &case.data().two_r(),
        )?;
    }
    Ok(())
}

/// `df:KN`: `x(t) ∈ K^N` at every probe time.
pub fn admissible<S: Scalar>(case: &Case<S>) -> R {
    const ID: &str = "df:KN";
    let two_r = case.data().two_r();
    for t in &case.times {
        let s = state(case, t, ID)?;
        for i in 0..s.positions.len().saturating_sub(1) {
            let gap = s.positions[i + 1].clone() - &s.positions[i];
            if gap < two_r {
                return Err(Violation::new(
                    ID,
                    format!(
                        "t = {}: x[{}] − x[{i}] = {} < 2r = {}",
                        t.render(),
                        i + 1,
                        gap.render(),
                        two_r.render()
                    ),
                ));
            }
        }
    }
    Ok(())
}

/// `prop:proj-micro#u-in-H`: `u(t) ∈ H_{x(t)}` for (almost every) `t > 0`.
pub fn u_in_h<S: Scalar>(case: &Case<S>) -> R {
    const ID: &str = "prop:proj-micro#u-in-H";
    let two_r = case.data().two_r();
    for t in positive_times(case) {
        let s = state(case, t, ID)?;
        if let Some(j) = crate::cluster::h_violation(&s.positions, &s.velocities, &two_r) {
            return Err(Violation::new(
                ID,
                format!(
                    "t = {}: pair ({j}, {}) touches but u[{j}] = {} ≠ u[{}] = {}",
                    t.render(),
                    j + 1,
                    s.velocities[j].render(),
                    j + 1,
                    s.velocities[j + 1].render()
                ),
            ));
        }
    }
    Ok(())
}

/// `eq:proj-micro-u`: `u(t) = P_{H_{x(t)}}(u⁰)` (cluster means) for `t > 0`.
pub fn u_projection<S: Scalar>(case: &Case<S>) -> R {
    const ID: &str = "eq:proj-micro-u";
    let two_r = case.data().two_r();
    for t in positive_times(case) {
        let s = state(case, t, ID)?;
        let expected = project_h(
            case.data().velocities(),
            &contact_clusters(&s.positions, &two_r),
        );
        if expected != s.velocities {
            return Err(Violation::new(
                ID,
                format!(
                    "t = {}: u(t) = {} but P_H(u⁰) = {}",
                    t.render(),
                    render_vec(&s.velocities),
                    render_vec(&expected)
                ),
            ));
        }
    }
    Ok(())
}

/// `eq:proj-u-micro`, read literally: with `Ω` split into runs of pair
/// indices `J_k = ⟦j_k, j_k + L_k⟧`, `u_i = u⁰_i` if `i ∉ Ω` and
/// `u_i = (1/L_k) Σ_{l=1}^{L_k} u⁰_{j_k + l}` if `i ∈ J_k`.
pub fn proj_u_micro_literal<S: Scalar>(case: &Case<S>) -> R {
    const ID: &str = "eq:proj-u-micro";
    let two_r = case.data().two_r();
    let u0 = case.data().velocities();
    for t in positive_times(case) {
        let s = state(case, t, ID)?;
        let omega = crate::cluster::contact_set(&s.positions, &two_r); // 0-based pairs
                                                                       // Runs of consecutive pair indices, 1-based as in the paper.
        let runs = crate::cluster::runs(omega.len(), |k| omega[k + 1] == omega[k] + 1);
        for i in 1..=s.positions.len() {
            let run = runs
                .iter()
                .find(|r| omega[r.first] < i && i <= omega[r.end() - 1] + 1);
            let printed = match run {
                None => u0[i - 1].clone(),
                Some(r) => {
                    let j_k = omega[r.first] + 1;
                    let l_k = r.size - 1;
                    if l_k == 0 {
                        // A single contact: L_k = 0 is outside the paper's
                        // range L_k ∈ ⟦1, N⟧ (the mean would be 0/0); such
                        // a particle is not read, the other branch is.
                        continue;
                    }
                    let sum = (1..=l_k).fold(S::zero(), |a, l| a + &u0[j_k + l - 1]);
                    sum / S::from_usize(l_k)
                }
            };
            if printed != s.velocities[i - 1] {
                return Err(Violation::new(
                    ID,
                    format!(
                        "t = {}: printed formula (paper's numbering: i = {i}) gives u[{}] = {} but u[{}](t) = {}",
                        t.render(),
                        i - 1,
                        printed.render(),
                        i - 1,
                        s.velocities[i - 1].render()
                    ),
                )
                .at(t.render())
                .indices(&[i - 1])
                .sides(
                    "the printed formula",
                    printed.render(),
                    "u_i(t)",
                    s.velocities[i - 1].render(),
                ));
            }
        }
    }
    Ok(())
}

/// Indicator vectors of the contact clusters of `x`: a basis of `H_x`.
fn h_basis<S: Scalar>(x: &[S], two_r: &S) -> Vec<Vec<S>> {
    contact_clusters(x, two_r)
        .into_iter()
        .map(|c| {
            (0..x.len())
                .map(|i| {
                    if c.range().contains(&i) {
                        S::one()
                    } else {
                        S::zero()
                    }
                })
                .collect()
        })
        .collect()
}

/// The vector of `ℝ^N` that a statement says is orthogonal to `H_{x(t)}`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Orthogonal {
    /// The free flight `x⁰ + t u⁰` (the proof of `lem:incl-HSN`,
    /// `eq:w-Hs-perp`).
    FreeFlight,
    /// Its distance to the motion, `x⁰ + t u⁰ − x(t)` (`lem:incl-HSN`).
    FreeFlightMinusPosition,
}

impl Orthogonal {
    /// The vector in words.
    fn formula(self) -> &'static str {
        match self {
            Orthogonal::FreeFlight => "x⁰ + t u⁰",
            Orthogonal::FreeFlightMinusPosition => "x⁰ + t u⁰ − x(t)",
        }
    }
}

/// `⟨v, w⟩ = 0` for every `w` of a basis of `H_{x(t)}`, `v` the vector
/// `orthogonal` names, at every probe time.
fn orthogonal_to_h<S: Scalar>(case: &Case<S>, id: &'static str, orthogonal: Orthogonal) -> R {
    let two_r = case.data().two_r();
    for t in &case.times {
        let s = state(case, t, id)?;
        let flight = free_flight(case.data(), t);
        let v = match orthogonal {
            Orthogonal::FreeFlight => flight,
            Orthogonal::FreeFlightMinusPosition => sub(&flight, &s.positions),
        };
        for w in h_basis(&s.positions, &two_r) {
            let d = dot(&v, &w);
            if !d.is_zero() {
                let first = w.iter().position(|x| !x.is_zero()).unwrap_or(0);
                let size = w.iter().filter(|x| !x.is_zero()).count();
                return Err(Violation::new(
                    id,
                    format!(
                        "t = {}: w = indicator of the cluster of particles [{first}..{}] ∈ H_x(t), ⟨{}, w⟩ = {} ≠ 0",
                        t.render(),
                        first + size - 1,
                        orthogonal.formula(),
                        d.render()
                    ),
                )
                .at(t.render())
                .indices(&[first, first + size - 1])
                .sides("⟨x⁰ + t u⁰ (− x(t)), w⟩", d.render(), "0", "0"));
            }
        }
    }
    Ok(())
}

/// `lem:incl-HSN`: `H_{x(t)} ⊂ [x⁰ + t u⁰ − x(t)]^⊥` (checked on a basis of
/// `H`; the inclusion in the tangent cone is immediate).
pub fn incl_hsn<S: Scalar>(case: &Case<S>) -> R {
    orthogonal_to_h(case, "lem:incl-HSN", Orthogonal::FreeFlightMinusPosition)
}

/// `lem:incl-HSN#proof-second-inclusion`: the proof announces
/// "H_{x̃(t)} ⊂ [x⁰ + t u⁰]^⊥".
pub fn incl_hsn_printed<S: Scalar>(case: &Case<S>) -> R {
    orthogonal_to_h(
        case,
        "lem:incl-HSN#proof-second-inclusion",
        Orthogonal::FreeFlight,
    )
}

/// `eq:w-Hs-perp`: `⟨x⁰ + t u⁰, w⟩ = 0` for `w ∈ H_{x(t)}`, as printed.
pub fn w_hs_perp<S: Scalar>(case: &Case<S>) -> R {
    orthogonal_to_h(case, "eq:w-Hs-perp", Orthogonal::FreeFlight)
}

/// `prop:proj-velo-micro#step1`: `⟨u⁰ − u(t), u(t)⟩ ≥ 0`.
pub fn velo_step1<S: Scalar>(case: &Case<S>) -> R {
    const ID: &str = "prop:proj-velo-micro#step1";
    for t in &case.times {
        let s = state(case, t, ID)?;
        let d = dot(&sub(case.data().velocities(), &s.velocities), &s.velocities);
        if d < S::zero() {
            return Err(Violation::new(
                ID,
                format!("t = {}: ⟨u⁰ − u, u⟩ = {} < 0", t.render(), d.render()),
            ));
        }
    }
    Ok(())
}

/// `eq:ineg-projortho`: `⟨u⁰ − u(t), y − x(t)⟩ ≤ 0` for all `y ∈ K^N`,
/// checked exactly on the generators of the tangent cone `T_{x(t)}K`:
/// `±(1, …, 1)`, `±s_j` for pairs not in contact and `s_j` for contacts,
/// where `s_j = Σ_{k > j} e_k`.
pub fn ineg_projortho<S: Scalar>(case: &Case<S>) -> R {
    const ID: &str = "eq:ineg-projortho";
    let two_r = case.data().two_r();
    for t in &case.times {
        let s = state(case, t, ID)?;
        let g = sub(case.data().velocities(), &s.velocities);
        if let Some(what) = tangent_cone_violation("u⁰ − u", &g, &s.positions, &two_r) {
            return Err(Violation::new(ID, format!("t = {}: {what}", t.render())));
        }
    }
    Ok(())
}

/// `prop:proj-micro#orthogonality`: `⟨u(t) − u⁰, x̃(t)⟩ = 0` (proof of
/// `prop:proj-micro`, "Definition and properties of the multipliers").
pub fn orthogonality<S: Scalar>(case: &Case<S>) -> R {
    const ID: &str = "prop:proj-micro#orthogonality";
    let two_r = case.data().two_r();
    for t in &case.times {
        let s = state(case, t, ID)?;
        let d = dot(
            &sub(&s.velocities, case.data().velocities()),
            &shift(&s.positions, &two_r),
        );
        if !d.is_zero() {
            return Err(Violation::new(
                ID,
                format!("t = {}: ⟨u − u⁰, x̃⟩ = {} ≠ 0", t.render(), d.render()),
            ));
        }
    }
    Ok(())
}
