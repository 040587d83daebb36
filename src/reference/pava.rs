//! `f64` PAVA at one time: the exact engine's own code run on `f64`.
//!
//! `prop:proj-micro` / `eq:proj-micro-x`: "x(t) = P_{K^N}(x_0 + t u_0)".
//! [`crate::projection::state_at`] computes it by pool-adjacent-violators on
//! the translated positions (`df:translat-x`), with the lexicographic
//! right-derivative trick for `u(t)` (`eq:proj-u-micro`); here that generic
//! code is instantiated at `S = f64` — there is no second copy of PAVA.
//!
//! **Rounding.** PAVA pools blocks by comparing cross-multiplied sums
//! (`Σ_A ỹ · |B|` against `Σ_B ỹ · |A|`) and averages them once at the end,
//! so every output position is one block mean `Σ ỹ_i / k` of free-flight
//! values `ỹ_i = x̃⁰_i + t u⁰_i`, plus the shift `2r(i−1)`. Each `ỹ_i` carries
//! a rounding error of about `2ε·X` (`X` the position scale), a sum of `k`
//! terms adds `k ε X` in the worst case, the shift adds `ε X`: the position
//! error is `O(k ε X)` with `k` the largest block, and `O(ε X)` on benign
//! scenes. The danger is in the pooling decisions: two block means that
//! are equal in exact arithmetic (a collision exactly at `t`) may compare
//! either way in `f64`, which changes the contact clusters and the right
//! derivative (velocity) — the position is continuous in the decision, the
//! velocity is not.
//!
//! Contact set reported: the contact clusters of the `f64` result
//! (`State::clusters`: equal translated block means, bit for bit).

use crate::initial::InitialData;
use crate::projection::{project_at, state_at};

use super::{check_data, check_time, kkt_from_positions, Output, Solver, SolverError, Work};

/// The exact engine's PAVA (`eq:proj-micro-x`) run on `f64`.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct PavaF64;

impl Solver for PavaF64 {
    fn method(&self) -> &'static str {
        "pava-f64"
    }

    fn parameters(&self) -> String {
        String::new()
    }

    fn solve(&self, data: &InitialData<f64>, t: f64) -> Result<Output, SolverError> {
        check_time(t)?;
        check_data(data)?;
        let state = state_at(data, &t).map_err(|e| SolverError::Exact {
            message: e.to_string(),
        })?;
        let projected = project_at(data, &t);
        let kkt = kkt_from_positions(&projected.shifted_free, &projected.shifted);
        let mut contacts = vec![false; data.n().saturating_sub(1)];
        for c in &state.clusters {
            for flag in &mut contacts[c.first..c.end() - 1] {
                *flag = true;
            }
        }
        super::check_finite(&state.positions, 0)?;
        Ok(Output {
            t,
            positions: state.positions,
            velocities: Some(state.velocities),
            contacts,
            lambda: Some(state.multipliers),
            kkt: Some(kkt),
            min_pressure_jump: None,
            work: Work {
                steps: 1,
                iterations: 0,
                unconverged: 0,
            },
            converged: true,
            residual: 0.0,
        })
    }
}
