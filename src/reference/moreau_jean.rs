//! Moreau–Jean time-stepping with a perfectly inelastic impact law
//! (restitution 0) — the standard scheme of nonsmooth contact dynamics
//! software; Siconos' `MoreauJeanOSI` with `NewtonImpactNSL(e = 0)` and
//! `θ = 1` is the reference point.
//!
//! The paper's second-order inclusion `eq:diff-order2` (`ẋ = u`,
//! `u̇ ∈ −∂I_{K^N}(x)`) is discretised at the velocity level. With step `h`,
//! unit masses and no external force, one step reads
//!
//! 1. **Index set** (Siconos `MoreauJeanOSI::addInteractionInIndexSet`): the
//!    pair `(i, i+1)` is active when its gap *predicted* half a step ahead
//!    is closed,
//!
//!    `g_i(x^n) + γ h (u^n_{i+1} − u^n_i) ≤ a·X`,  `g_i(x) = x_{i+1} − x_i − 2r`,
//!
//!    with `γ = 1/2` (Siconos' default when no `γ` is given) and an
//!    activation tolerance `a` relative to the position scale `X`
//!    ([`super::position_scale`]). Siconos tests `≤ 0`; `a = 0` reproduces
//!    that. The default `a = 1e-12` is there because positions are advanced
//!    particle by particle, `x_i + h u_i` rounded separately, so the gap of
//!    a resting contact random-walks by about `√n` ulps of `X` after `n`
//!    steps: with `a = 0` about half of the resting contacts of a cluster
//!    drop out of the index set after the first step, and an impact on the
//!    cluster then travels one particle per step with an `O(h)` overlap at
//!    every contact (a cluster of `k` particles ends up compressed by up to
//!    `k h |ẏ|/2`). `a = 1e-12` (about 4500 ε) covers the drift of up to
//!    about 10^6 steps; it also makes approaching pairs closer than `a·X`
//!    active one step early, an `O(a X)` effect.
//! 2. **Velocity-level complementarity** on the active pairs `I`, Newton's
//!    impact law with `e = 0`:
//!
//!    `u^{n+1} = u^n − Σ_{i∈I} P_i (e_i − e_{i+1})`,
//!    `0 ≤ u^{n+1}_{i+1} − u^{n+1}_i ⊥ P_i ≥ 0` for `i ∈ I`,
//!
//!    solved by projected Gauss–Seidel ([`super::pgs`], cold start `P = 0`)
//!    until the natural residual is at most `(tol + 4ε)·V`
//!    (`V = max|u⁰|`, the velocity scale: every velocity of the dynamics is
//!    a mean of initial ones) or `max_iterations` sweeps per run of coupled
//!    contacts.
//! 3. **Positions**, `θ = 1`: `x^{n+1} = x^n + h u^{n+1}`.
//!
//! The impulses are the multipliers' increments: comparing step 2 with
//! `eq:dyn-micro` (`u − u⁰ = −N Σ λ_i (e_i − e_{i+1})`) gives
//! `λ^{n+1}_i = λ^n_i + P_i/N`; these accumulated impulses are reported as
//! `λ`, `P_i/N ≥ 0` as the pressure jumps (`prop:micro-pressure`), and
//! `μ = Σ_n h λ^{n+1}` as Appendix A's `μ = ∫ λ`.
//!
//! **What to expect.** Contacts are enforced on velocities only: a pair is
//! caught when its predicted gap closes, i.e. up to `γ h |ẏ|` before or
//! `(1 − γ) h |ẏ|` after the exact collision, and then stays at that gap
//! (there is no position correction), so positions are first order in `h`
//! and the constraint may be violated by `O(h)`. Velocities of a cluster are
//! momentum means once the collision is processed. The step used is
//! `h = t/⌈t/Δt⌉ ≤ Δt`, so that the last step lands on `t`.
//!
//! Contact set reported: the index set a next step would use, the rule of
//! step 1 at the final state (a cluster held together at a small positive
//! gap is *not* in it — that is what the scheme sees).

use crate::initial::InitialData;

use super::pgs::{gap, solve_listed, Stop};
use super::{
    check_cap, check_data, check_finite, check_positive, check_time, position_scale, steps,
    velocity_scale, Output, Solver, SolverError, Work, ROUNDOFF,
};

/// Moreau–Jean time-stepping, restitution 0, `θ = 1`, projected
/// Gauss–Seidel on the velocity-level complementarity problem.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MoreauJean {
    /// Time step `Δt > 0` (the step used is `t/⌈t/Δt⌉`).
    pub dt: f64,
    /// PGS tolerance, relative to the velocity scale `V = max|u⁰|`.
    pub tol: f64,
    /// Sweep cap of one PGS solve (per run of coupled contacts, per step).
    pub max_iterations: usize,
    /// Index-set prediction factor `γ ∈ [0, 1]` (Siconos default `1/2`).
    pub gamma: f64,
    /// Activation tolerance `a ≥ 0`, relative to the position scale `X`
    /// (see the module documentation; `0` is Siconos' exact rule).
    pub activation_tol: f64,
}

impl MoreauJean {
    /// Step `dt` with the defaults `tol = 1e-12`, `max_iterations = 100_000`,
    /// `γ = 1/2`, `activation_tol = 1e-12`.
    pub fn new(dt: f64) -> Self {
        MoreauJean {
            dt,
            tol: 1e-12,
            max_iterations: 100_000,
            gamma: 0.5,
            activation_tol: 1e-12,
        }
    }
}

impl Solver for MoreauJean {
    fn method(&self) -> &'static str {
        "moreau-jean"
    }

    fn parameters(&self) -> String {
        format!(
            "dt={:e} tol={:e} cap={} gamma={} activation={:e}",
            self.dt, self.tol, self.max_iterations, self.gamma, self.activation_tol
        )
    }

    fn solve(&self, data: &InitialData<f64>, t: f64) -> Result<Output, SolverError> {
        check_positive("dt", self.dt)?;
        check_positive("tol", self.tol)?;
        check_cap("max_iterations", self.max_iterations)?;
        if !(0.0..=1.0).contains(&self.gamma) {
            return Err(SolverError::BadParameter {
                name: "gamma",
                value: self.gamma,
                requirement: "in [0, 1]",
            });
        }
        if !(self.activation_tol.is_finite() && self.activation_tol >= 0.0) {
            return Err(SolverError::BadParameter {
                name: "activation_tol",
                value: self.activation_tol,
                requirement: "finite and ≥ 0",
            });
        }
        check_time(t)?;
        check_data(data)?;
        let (n_steps, h) = steps(t, self.dt)?;
        let n = data.n();
        let nf = n as f64;
        let pairs = n.saturating_sub(1);
        let two_r = data.two_r();
        let v_scale = velocity_scale(data);
        let activation = self.activation_tol * position_scale(data, t);
        let stop = Stop {
            threshold: (self.tol + ROUNDOFF) * v_scale,
            max_sweeps: self.max_iterations,
        };
        let mut x = data.positions().to_vec();
        let mut u = data.velocities().to_vec();
        let mut lambda = vec![0.0; pairs];
        let mut mu = vec![0.0; pairs];
        let mut impulse = vec![0.0; pairs];
        let mut active: Vec<usize> = Vec::with_capacity(pairs);
        let mut work = Work::default();
        let mut residual = 0.0f64;
        let mut min_jump: Option<f64> = None;
        let index_set =
            |x: &[f64], u: &[f64], active: &mut Vec<usize>| {
                active.clear();
                active.extend((0..pairs).filter(|&i| {
                    gap(x, i, two_r) + self.gamma * h * (u[i + 1] - u[i]) <= activation
                }));
            };
        for _ in 0..n_steps {
            index_set(&x, &u, &mut active);
            if !active.is_empty() {
                for &i in &active {
                    impulse[i] = 0.0;
                }
                let report = solve_listed(&mut u, &mut impulse, &active, 0.0, stop);
                work.iterations += report.sweeps;
                work.unconverged += report.unconverged;
                residual = residual.max(report.residual);
                for &i in &active {
                    let jump = impulse[i] / nf;
                    lambda[i] += jump;
                    min_jump = Some(min_jump.map_or(jump, |m: f64| m.min(jump)));
                }
            }
            for (xi, ui) in x.iter_mut().zip(&u) {
                *xi += h * ui;
            }
            for (m, l) in mu.iter_mut().zip(&lambda) {
                *m += h * l;
            }
        }
        check_finite(&x, n_steps)?;
        check_finite(&u, n_steps)?;
        index_set(&x, &u, &mut active);
        let mut contacts = vec![false; pairs];
        for &i in &active {
            contacts[i] = true;
        }
        work.steps = n_steps;
        Ok(Output {
            t,
            positions: x,
            velocities: Some(u),
            contacts,
            lambda: Some(lambda),
            kkt: Some(mu),
            min_pressure_jump: min_jump,
            converged: work.unconverged == 0,
            work,
            residual,
        })
    }
}
