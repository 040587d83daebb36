//! Iterative projection at one time: Appendix A's KKT system solved by dual
//! projected Gauss–Seidel, as a generic QP/LCP solver would do it.
//!
//! Appendix A (`app:KKT`): `x(t)` minimises `½‖x − y‖²`, `y = x⁰ + t u⁰`,
//! subject to `x_{i+1} − x_i ≥ 2r` (`df:KN`), with multipliers `μ_i ≥ 0`:
//!
//! `x − y + N Σ_i μ_i (e_i − e_{i+1}) = 0`,  `μ_i (x_{i+1} − x_i − 2r) = 0`,
//!
//! i.e. `μ_i = μ_{i−1} + (y_i − x_i)/N` — the quantity
//! [`crate::contact::kkt_multipliers`] computes exactly from `P_K(y)`.
//! Eliminating `x` leaves the dual LCP in `ν = N μ` with Delassus matrix
//! `tridiag(−1, 2, −1)`; it is solved by projected Gauss–Seidel
//! ([`super::pgs::solve_full`]): full sweeps over all `N − 1` pairs, from
//! `ν = 0`, until the natural residual `max_i |min(ν_i, g_i(x))|` is at most
//! `tol·2r + 4ε·X` (relative to the contact length `2r`, floored at the
//! rounding level of positions, `X` = [`super::position_scale`]) or
//! `max_iterations` sweeps. With `tol` tiny and `max_iterations = k` it is
//! "k iterations of PGS".
//!
//! The primal iterate is always `x = y − Σ ν_i (e_i − e_{i+1})` with `ν ≥ 0`,
//! so stationarity and dual feasibility hold at every sweep; the residual
//! measures primal feasibility and complementarity. Each sweep contracts the
//! error of a run of `m` coupled contacts by about `1 − π²/m²`.
//!
//! Reported: positions, `μ = ν/N`, the contact set `{ i : g_i(x) ≤ threshold }`
//! (the projection's active set up to its tolerance); no velocities and no
//! `λ` (one projection does not give the right derivative).

use crate::initial::InitialData;

use super::pgs::{gap, solve_full, Stop};
use super::{
    check_cap, check_data, check_finite, check_positive, check_time, position_scale, Output,
    Solver, SolverError, Work, ROUNDOFF,
};
use crate::projection::free_flight;

/// Dual projected Gauss–Seidel on Appendix A's KKT system at one time.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct IterativeProjection {
    /// Tolerance on the natural residual, relative to the contact length `2r`.
    pub tol: f64,
    /// Sweep cap.
    pub max_iterations: usize,
}

impl Default for IterativeProjection {
    /// `tol = 1e-12`, `max_iterations = 1_000_000`.
    fn default() -> Self {
        IterativeProjection {
            tol: 1e-12,
            max_iterations: 1_000_000,
        }
    }
}

impl Solver for IterativeProjection {
    fn method(&self) -> &'static str {
        "iterative-projection"
    }

    fn parameters(&self) -> String {
        format!("tol={:e} cap={}", self.tol, self.max_iterations)
    }

    fn solve(&self, data: &InitialData<f64>, t: f64) -> Result<Output, SolverError> {
        check_positive("tol", self.tol)?;
        check_cap("max_iterations", self.max_iterations)?;
        check_time(t)?;
        check_data(data)?;
        let n = data.n();
        let two_r = data.two_r();
        let stop = Stop {
            threshold: self.tol * two_r + ROUNDOFF * position_scale(data, t),
            max_sweeps: self.max_iterations,
        };
        let mut x = free_flight(data, &t);
        let mut nu = vec![0.0; n.saturating_sub(1)];
        let report = solve_full(&mut x, &mut nu, two_r, stop);
        check_finite(&x, report.sweeps)?;
        let nf = n as f64;
        let kkt: Vec<f64> = nu.iter().map(|v| v / nf).collect();
        let contacts = (0..n.saturating_sub(1))
            .map(|i| gap(&x, i, two_r) <= stop.threshold)
            .collect();
        Ok(Output {
            t,
            positions: x,
            velocities: None,
            contacts,
            lambda: None,
            kkt: Some(kkt),
            min_pressure_jump: None,
            work: Work {
                steps: 1,
                iterations: report.sweeps,
                unconverged: report.unconverged,
            },
            converged: report.unconverged == 0,
            residual: report.residual,
        })
    }
}
