//! Claims of section 2 (microscopic dynamics) and Appendix A (KKT), checked
//! on one [`Case`]: statements and the steps of their proofs, literally as
//! printed, with the paper's normalisations (`‖x‖² = (1/N) Σ x_i²`,
//! `⟨x, y⟩ = Σ x_i y_i`).
//!
//! One file per group of claims, every checker re-exported here:
//! `proj_micro.rs` (the projection formulas and the steps of their proofs),
//! `multipliers.rs` (`eq:dyn-micro`, the bounds on `λ`), `bounds.rs`
//! (`prop:bound-micro`, `prop:Oleinik`), `semigroup.rs` (the semigroup and
//! the growth of the contact set), `pressure.rs` (`prop:micro-pressure`),
//! `kkt.rs` (Appendix A), `characterization.rs` (`lem:proj-characterization`
//! for `K^N` and `H`), `cones.rs` (`C_x = T_xK`, `N_x = (T_xK)°`, `df:tKN`).
//! The shared helpers (norms, rendering) are here.

use super::{Case, Violation};
use crate::cluster::Cluster;
use crate::scalar::Scalar;
use crate::state::State;
use crate::trajectory::Trajectory;

type R = Result<(), Violation>;

mod bounds;
mod characterization;
mod cones;
mod kkt;
mod multipliers;
mod pressure;
mod proj_micro;
mod semigroup;

pub use bounds::{
    oleinik, oleinik_characteristics, position_contraction, position_nonexpansive, velocity_bound,
};
pub use characterization::{
    characterization, normal_coefficients, proj_characterization_h, proj_characterization_k,
    ConvexSet,
};
pub use cones::{polar_cone, tangent_cone, translated_cone};
pub use kkt::{
    kkt_corrected, kkt_printed, uniqueness_identity_corrected, uniqueness_identity_printed,
};
pub(crate) use multipliers::augmented_lambda;
pub use multipliers::{
    delta_lambda, dyn_micro, dyn_micro_at, lambda_cs, lambda_from_history,
    multiplier_relation_corrected, multiplier_relation_printed, multiplier_signs,
    sup_u_and_increments,
};
pub use pressure::{lambda_integral, micro_pressure, pressure_sign};
pub use proj_micro::{
    admissible, incl_hsn, incl_hsn_printed, ineg_projortho, orthogonality, proj_micro,
    proj_u_micro_literal, projection_formula, u_in_h, u_projection, velo_step1, w_hs_perp,
};
pub use semigroup::{contacts_grow_corrected, contacts_grow_printed, projortho_sg, semigroup};

fn render_vec<S: Scalar>(v: &[S]) -> String {
    format!(
        "[{}]",
        v.iter().map(|x| x.render()).collect::<Vec<_>>().join(", ")
    )
}

fn render_state<S: Scalar>(s: &State<S>) -> String {
    format!(
        "x = {}, u = {}, λ = {}, clusters = {:?}",
        render_vec(&s.positions),
        render_vec(&s.velocities),
        render_vec(&s.multipliers),
        s.clusters
            .iter()
            .map(|c: &Cluster| (c.first, c.size))
            .collect::<Vec<_>>()
    )
}

/// `⟨a, b⟩ = Σ a_i b_i` (the paper's non-rescaled inner product).
pub fn dot<S: Scalar>(a: &[S], b: &[S]) -> S {
    S::sum_of_products(a, b)
}

/// `‖a‖² = (1/N) Σ a_i²` (the paper's rescaled norm).
pub fn norm2<S: Scalar>(a: &[S]) -> S {
    dot(a, a) / S::from_usize(a.len().max(1))
}

pub(crate) fn sub<S: Scalar>(a: &[S], b: &[S]) -> Vec<S> {
    a.iter().zip(b).map(|(x, y)| x.clone() - y).collect()
}

fn state<S: Scalar>(case: &Case<S>, t: &S, id: &'static str) -> Result<State<S>, Violation> {
    case.state(t).map_err(|e| Violation::new(id, e.to_string()))
}

fn positive_times<S: Scalar>(case: &Case<S>) -> impl Iterator<Item = &S> {
    case.times
        .iter()
        .filter(|t| t.total_cmp(&S::zero()).is_gt())
}

pub use crate::trajectory::probe_times;

/// `⟨g, v⟩ ≤ 0` on the generators `v` of the tangent cone `T_xK`:
/// `±(1, …, 1)`, `±s_j` for a pair apart and `s_j` for a contact, with
/// `s_j = Σ_{k > j} e_k` (`eq:ineg-projortho`, and the inclusion
/// `ξ ∈ ∂I_K(x)` of Appendix C). `None` when it holds on all of them, else
/// the first generator that fails, described with `name` for `g`.
pub(crate) fn tangent_cone_violation<S: Scalar>(
    name: &str,
    g: &[S],
    x: &[S],
    two_r: &S,
) -> Option<String> {
    let total = g.iter().fold(S::zero(), |a, v| a + v);
    if !total.is_zero() {
        return Some(format!("⟨{name}, ±1⟩ = ±{} ≠ 0", total.render()));
    }
    let mut tail = total; // Σ_{k > j} g_k, for j = 0 first
    for j in 0..g.len().saturating_sub(1) {
        tail = tail - &g[j];
        let contact = x[j + 1].clone() - &x[j] == *two_r;
        if (contact && tail > S::zero()) || (!contact && !tail.is_zero()) {
            return Some(format!(
                "⟨{name}, s[{j}]⟩ = {} with pair ({j}, {}) {}",
                tail.render(),
                j + 1,
                if contact { "in contact" } else { "apart" }
            ));
        }
    }
    None
}

/// Runs the core section-2 checkers (`prop:proj-micro`, `eq:dyn-micro`,
/// `prop:micro-pressure`) on one trajectory at the probe times (all of them,
/// or a spread of `limit` collision instants); returns the number of checks
/// made.
pub fn check_trajectory<S: Scalar>(
    traj: &Trajectory<S>,
    limit: Option<usize>,
) -> Result<usize, Violation> {
    let mut count = 0;
    for t in probe_times(traj, limit) {
        let s = projection_formula(traj, &t)?;
        multiplier_signs(traj.data(), &s)?;
        count += 2;
    }
    for imp in traj.impulses() {
        pressure_sign(imp)?;
        count += 1;
    }
    Ok(count)
}
