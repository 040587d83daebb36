//! Claims of section 3 in their discrete form: the interpolations
//! `X_N, U_N, Λ_N` (piecewise constant on `((i−1)/N, i/N]`) and
//! `X̃_N, Ũ_N, Λ̃_N, P̃_N` (piecewise affine, with the artificial particle
//! `x_0 = x_1 − 1/N − δ`, `df:x0`), checked at the probe times of a case.
//! They assume the paper's radius `2r = 1/N`; `δ = 1` here (any `δ > 0`
//! independent of N; the claims below do not depend on its value).
//!
//! This file builds the augmented arrays every checker reads; the checkers
//! are grouped by statement: `pde_lagr_n1` (`eq:PDE-Lagr-N-1`), `exclusion`
//! (the pressure lives at contacts, and its pairing) and `bounds` (the
//! bounds uniform in N).

use super::{Case, Violation};
use crate::scalar::Scalar;
use crate::state::State;

mod bounds;
mod exclusion;
mod pde_lagr_n1;

pub use bounds::{
    bv_xn, diff_lambda_corrected, diff_lambda_printed, gap_delta, oleinik_tun, pw_un_l1,
    un_l1_corrected, un_l1_printed, xn_l1,
};
pub use exclusion::{
    disc_pde2_printed, pairing_printed, pairing_reindexed, pressure_bound_exclusion_printed,
};
pub use pde_lagr_n1::{lagr_n1, lagr_n1_corrected, lagr_n1_printed, reindexed};

type R = Result<(), Violation>;

/// The augmented arrays at one time: `x_0 … x_N`, `u_0 … u_N`, `λ_0 … λ_N`
/// (index 0 is the artificial particle: `x_0 = x_1 − 1/N − δ`, `u_0 = u_1`,
/// `λ_0 = 0`).
pub(super) struct Augmented<S> {
    pub(super) t: S,
    pub(super) x: Vec<S>,
    pub(super) u: Vec<S>,
    pub(super) lambda: Vec<S>,
}

/// `δ` of `df:x0` (the gap added to the artificial particle): 1.
pub(super) fn delta<S: Scalar>() -> S {
    S::one()
}

pub(super) fn augmented<S: Scalar>(case: &Case<S>, s: &State<S>) -> Augmented<S> {
    let n = S::from_usize(case.n());
    let x0 = s.positions[0].clone() - &(S::one() / &n) - &delta::<S>();
    let mut x = vec![x0];
    x.extend(s.positions.iter().cloned());
    let mut u = vec![s.velocities[0].clone()];
    u.extend(s.velocities.iter().cloned());
    // The engine's λ (not recomputed from u: eq:PDE-Lagr-N-1 would then
    // hold by construction), λ_0 = λ_N = 0.
    let lambda = crate::claims::micro::augmented_lambda(s);
    Augmented {
        t: s.t.clone(),
        x,
        u,
        lambda,
    }
}

pub(super) fn states<S: Scalar>(
    case: &Case<S>,
    id: &'static str,
) -> Result<Vec<Augmented<S>>, Violation> {
    case.times
        .iter()
        .map(|t| {
            case.state(t)
                .map(|s| augmented(case, &s))
                .map_err(|e| Violation::new(id, e.to_string()))
        })
        .collect()
}

pub(super) fn abs<S: Scalar>(x: S) -> S {
    if x.total_cmp(&S::zero()).is_lt() {
        -x
    } else {
        x
    }
}

/// `Σ_i |v_i − v_{i−1}|` (for the augmented arrays, index 0 is the
/// artificial particle with `u_0 = u_1`, so its term vanishes).
fn total_variation<S: Scalar>(v: &[S]) -> S {
    v.windows(2)
        .fold(S::zero(), |acc, w| acc + &abs(w[1].clone() - &w[0]))
}

/// The jumps of `λ_i` (0 ≤ i ≤ N, augmented index: `jumps[0] = jumps[N] =
/// 0`) at one collision.
pub(super) fn augmented_jumps<S: Scalar>(n: usize, imp: &crate::contact::Impulse<S>) -> Vec<S> {
    let mut j = vec![S::zero(); n + 1];
    for (k, v) in imp.jumps().into_iter().enumerate() {
        j[imp.cluster.first + k + 1] = v;
    }
    j
}
