//! The catching-up scheme of Maury and Venel (crowd motion), with inertia:
//!
//! `x^{n+1} = P_K(x^n + h u^n)`,   `u^{n+1} = (x^{n+1} − x^n)/h`,
//!
//! started from `x^0 = x⁰`, `u^0 = u⁰`, where `u^n` is the velocity of the
//! *previous* step (not a prescribed desired velocity).
//!
//! **Why this scheme is consistent with the sticky dynamics.** The paper's
//! semigroup property (`eq:semigroup`, `eq:projortho-sg`) says
//! `x(t) = P_K(x(s) + (t − s) u(s))`: one catching-up step from the exact
//! state with the exact right derivative `u(s)` is exact. The scheme uses
//! instead the step-averaged velocity, which differs from `u(t_n)` only by
//! `(1/h) ∫_{t_{n−1}}^{t_n} (u(s) − u(t_n)) ds = (N/h) ∫ Σ_i (λ_i(t_n) − λ_i(s)) (e_i − e_{i+1}) ds`
//! (`eq:dyn-micro`): a combination of `e_i − e_{i+1}` with coefficients
//! `≥ 0` (`λ` is non-decreasing, `prop:micro-pressure`) on pairs in contact
//! at `t_n`, which stay in contact (clusters only grow). That vector lies in
//! the normal cone `N_{x(t_{n+1})} K^N`, and `P_K(z + w) = P_K(z)` for every
//! `w` in the normal cone at `P_K(z)` (`lem:proj-characterization`). By
//! induction, **in exact arithmetic the scheme is exact at every grid time**
//! `t_n = n h`: `x^n = x(t_n)`, and `u^n = u(t_n)` unless a collision
//! happened in `(t_{n−1}, t_n]`, in which case `u^n` is the step average.
//! What remains are the projection tolerance and rounding: the velocity
//! `(x^{n+1} − x^n)/h` is a difference of nearby positions divided by `h`,
//! so a rounding error `ε·X` in positions becomes `ε·X/h` in velocity, and
//! accumulates over the `t/h` steps — the scheme's error grows as `h → 0`.
//!
//! **Projection.** `P_K` is computed iteratively: dual projected
//! Gauss–Seidel on Appendix A's KKT system ([`super::pgs`], cold start
//! `ν = 0`, on runs grown from the violated pairs), stopped when the natural
//! residual `max |min(ν_i, g_i)|` is at most `tol·h·V + 4ε·X`: a residual `δ`
//! in positions becomes `δ/h` in the next velocity, so the tolerance is set
//! on the velocity it induces (`tol·V`, `V = max|u⁰|`), floored at the
//! rounding level of positions (`X` = [`super::position_scale`]).
//!
//! The KKT multipliers of step `n` (`x^{n+1} − y^n = −Σ ν_i (e_i − e_{i+1})`)
//! give the impulses: `u^{n+1} − u^n = −Σ (ν_i/h)(e_i − e_{i+1})`, so by
//! `eq:dyn-micro` `λ^{n+1} = λ^n + ν/(N h)`; reported `λ`, pressure jumps
//! `ν/(N h) ≥ 0`, and `μ = Σ_n h λ^{n+1}` (Appendix A's `μ = ∫ λ`).
//!
//! Contact set reported: pairs with `g_i(x) ≤ max(threshold, c·X)`, the
//! projection threshold or a contact tolerance `c` relative to the position
//! scale (default `c = 1e-9`, for the report only). The tolerance is needed
//! because the velocity noise `ε X/h` of step 1 is never corrected on a
//! resting contact (no impulse acts on a pair that separates, however
//! slowly), so the gaps inside a cluster drift open by about
//! `n^{3/2} ε X` after `n` steps (a twice-integrated random walk): this is
//! the scheme's round-off signature. The step used is `h = t/⌈t/Δt⌉ ≤ Δt`.

use crate::initial::InitialData;

use super::pgs::{gap, solve_grown, Stop};
use super::{
    check_cap, check_data, check_finite, check_positive, check_time, position_scale, steps,
    velocity_scale, Output, Solver, SolverError, Work, ROUNDOFF,
};

/// The catching-up scheme with inertia, `P_K` by dual projected
/// Gauss–Seidel.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CatchingUp {
    /// Time step `Δt > 0` (the step used is `t/⌈t/Δt⌉`).
    pub dt: f64,
    /// Projection tolerance, relative to the displacement scale of one step
    /// `h·V` (so the velocity error it induces is about `tol·V`).
    pub tol: f64,
    /// Sweep cap of one projection (per run of coupled contacts, per step).
    pub max_iterations: usize,
    /// Contact tolerance of the reported contact set, relative to the
    /// position scale `X` (report only; it does not change the dynamics).
    pub contact_tol: f64,
}

impl CatchingUp {
    /// Step `dt` with the defaults `tol = 1e-12`, `max_iterations = 100_000`,
    /// `contact_tol = 1e-9`.
    pub fn new(dt: f64) -> Self {
        CatchingUp {
            dt,
            tol: 1e-12,
            max_iterations: 100_000,
            contact_tol: 1e-9,
        }
    }
}

impl Solver for CatchingUp {
    fn method(&self) -> &'static str {
        "catching-up"
    }

    fn parameters(&self) -> String {
        format!(
            "dt={:e} tol={:e} cap={} contact={:e}",
            self.dt, self.tol, self.max_iterations, self.contact_tol
        )
    }

    fn solve(&self, data: &InitialData<f64>, t: f64) -> Result<Output, SolverError> {
        check_positive("dt", self.dt)?;
        check_positive("tol", self.tol)?;
        check_cap("max_iterations", self.max_iterations)?;
        check_positive("contact_tol", self.contact_tol)?;
        check_time(t)?;
        check_data(data)?;
        let (n_steps, h) = steps(t, self.dt)?;
        let n = data.n();
        let nf = n as f64;
        let pairs = n.saturating_sub(1);
        let two_r = data.two_r();
        let x_scale = position_scale(data, t);
        let stop = Stop {
            threshold: self.tol * h * velocity_scale(data) + ROUNDOFF * x_scale,
            max_sweeps: self.max_iterations,
        };
        let contact = stop.threshold.max(self.contact_tol * x_scale);
        let mut x = data.positions().to_vec();
        let mut u = data.velocities().to_vec();
        let mut y = vec![0.0; n];
        let mut nu = vec![0.0; pairs];
        let mut lambda = vec![0.0; pairs];
        let mut mu = vec![0.0; pairs];
        let mut work = Work::default();
        let mut residual = 0.0f64;
        let mut min_jump: Option<f64> = None;
        for _ in 0..n_steps {
            for ((yi, xi), ui) in y.iter_mut().zip(&x).zip(&u) {
                *yi = xi + h * ui;
            }
            nu.iter_mut().for_each(|v| *v = 0.0);
            let report = solve_grown(&mut y, &mut nu, two_r, stop);
            work.iterations += report.sweeps;
            work.unconverged += report.unconverged;
            residual = residual.max(report.residual);
            for ((ui, yi), xi) in u.iter_mut().zip(&y).zip(&x) {
                *ui = (yi - xi) / h;
            }
            for ((l, m), v) in lambda.iter_mut().zip(mu.iter_mut()).zip(&nu) {
                if *v > 0.0 {
                    let jump = v / (nf * h);
                    *l += jump;
                    min_jump = Some(min_jump.map_or(jump, |m: f64| m.min(jump)));
                }
                *m += h * *l;
            }
            std::mem::swap(&mut x, &mut y);
        }
        check_finite(&x, n_steps)?;
        check_finite(&u, n_steps)?;
        let contacts = (0..pairs).map(|i| gap(&x, i, two_r) <= contact).collect();
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
