//! Bounds "with C independent of N", checked across N on quantile-sampled
//! macroscopic data (the shipped `[macro]` scenes), exactly.
//!
//! For each N in `4, 8, …, N_max` the quantity `q(N)` is computed in rational
//! arithmetic. The verdict is exact too:
//!
//! * a bound claimed independent of N is reported as a **counterexample**
//!   when `q(N_max)² · N_min ≥ q(N_min)² · N_max`, i.e. when it grows at
//!   least like `√N` over the range (with the witness values);
//! * a quantity claimed to tend to 0 **holds** when
//!   `q(N_max)² · N_max ≤ q(N_min)² · N_min` (it decays at least like
//!   `1/√N`).
//!
//! The fitted log-log slope is reported as an `f64` for reading only.

use num_rational::BigRational;

use super::micro::norm2;
use super::Violation;
use crate::contact::multipliers;
use crate::projection::state_at;
use crate::quantile::MacroDatum;
use crate::rate::log_log_slope;
use crate::scalar::Scalar;
use crate::scene::{self, SceneKind};
use crate::trajectory::Trajectory;

/// How far to go in N.
#[derive(Debug, Clone, Copy)]
pub struct Budget {
    /// Largest N (a power of two ≥ 8).
    pub max_n: usize,
}

/// What a scaling check measured.
#[derive(Debug, Clone)]
pub struct ScalingReport {
    /// The scene.
    pub scene: &'static str,
    /// `(N, q(N))`, exact.
    pub values: Vec<(usize, BigRational)>,
    /// Least-squares slope of `log q` against `log N` (reading aid).
    pub slope: f64,
}

impl ScalingReport {
    /// One line: the values and the slope.
    pub fn summary(&self) -> String {
        let vals: Vec<String> = self
            .values
            .iter()
            .map(|(n, q)| format!("N={n}: {}", short(q)))
            .collect();
        format!(
            "{}: {} (log-log slope {:.3})",
            self.scene,
            vals.join(", "),
            self.slope
        )
    }
}

fn short(q: &BigRational) -> String {
    let s = q.render();
    if s.len() <= 24 {
        s
    } else {
        format!("≈{:.6e}", q.to_f64_lossy())
    }
}

/// A scaling checker: the measurements, or the violation.
pub type ScalingCheck = fn(Budget) -> Result<Vec<ScalingReport>, Violation>;

/// The shipped scenes ([`scene::SHIPPED`]) checked, by name.
const SCENES: [&str; 2] = ["appendix-c-two-blocks", "riemann-compression"];

fn datum(text: &str, id: &'static str) -> Result<(MacroDatum, BigRational), Violation> {
    let s = scene::parse(text).map_err(|e| Violation::new(id, e.to_string()))?;
    let t_end = s.t_end.clone().unwrap_or_else(<BigRational as Scalar>::one);
    match s.kind {
        SceneKind::Macro { datum, .. } => Ok((datum, t_end)),
        SceneKind::Particles => Err(Violation::new(id, "not a macro scene")),
    }
}

/// The N values of a budget: `4, 8, …, max_n`.
pub fn ns(budget: Budget) -> Vec<usize> {
    let mut v = Vec::new();
    let mut n = 4;
    while n <= budget.max_n.max(8) {
        v.push(n);
        n *= 2;
    }
    v
}

fn slope(values: &[(usize, BigRational)]) -> f64 {
    let pts: Vec<(f64, f64)> = values
        .iter()
        .filter(|(_, q)| q.to_f64_lossy() > 0.0)
        .map(|(n, q)| (*n as f64, q.to_f64_lossy()))
        .collect();
    log_log_slope(&pts)
}

/// Runs `q` on every shipped macro scene for every N and applies the
/// verdict (`bounded = true`: must not grow like √N; `false`: must decay
/// like 1/√N).
fn measure(
    id: &'static str,
    budget: Budget,
    bounded: bool,
    q: impl Fn(&MacroDatum, &BigRational, usize) -> Result<BigRational, Violation>,
) -> Result<Vec<ScalingReport>, Violation> {
    let mut reports = Vec::new();
    for name in SCENES {
        let text = scene::shipped(name)
            .ok_or_else(|| Violation::new(id, format!("{name} is not a shipped scene")))?;
        let (d, t_end) = datum(text, id)?;
        let mut values = Vec::new();
        for n in ns(budget) {
            values.push((n, q(&d, &t_end, n)?));
        }
        let report = ScalingReport {
            scene: name,
            slope: slope(&values),
            values,
        };
        let (n0, q0) = report.values[0].clone();
        let (n1, q1) = report.values[report.values.len() - 1].clone();
        let (a, b) = (
            q1.clone() * &q1 * BigRational::from_usize(n0),
            q0.clone() * &q0 * BigRational::from_usize(n1),
        );
        let fails = if bounded {
            a >= b && !q1.is_zero()
        } else {
            q1.clone() * &q1 * BigRational::from_usize(n1)
                > q0.clone() * &q0 * BigRational::from_usize(n0)
        };
        if fails {
            return Err(Violation::new(
                id,
                format!(
                    "{} — {}",
                    report.summary(),
                    if bounded {
                        "grows at least like √N: not bounded independently of N"
                    } else {
                        "does not decay like 1/√N"
                    }
                ),
            ));
        }
        reports.push(report);
    }
    Ok(reports)
}

fn sampled(
    d: &MacroDatum,
    n: usize,
    id: &'static str,
) -> Result<Trajectory<BigRational>, Violation> {
    d.sample(n)
        .map(Trajectory::new)
        .map_err(|e| Violation::new(id, e.to_string()))
}

fn abs(q: BigRational) -> BigRational {
    if q < BigRational::zero() {
        -q
    } else {
        q
    }
}

/// The states just after each collision (a spread of at most 24 of them)
/// and at 0: `λ` and `u` are piecewise constant in time, so sups over
/// `[0, T]` are maxima over these.
fn after_collisions(
    traj: &Trajectory<BigRational>,
    t_end: &BigRational,
) -> Vec<crate::state::State<BigRational>> {
    let times = super::micro::probe_times(traj, Some(24));
    times
        .iter()
        .filter(|t| *t <= t_end)
        .filter_map(|t| state_at(traj.data(), t).ok())
        .collect()
}

/// `eq:sup-micro-u-L#N-lambda`: `sup_{t ≤ T} sup_i N|λ_i(t)| ≤ C'` with C'
/// independent of N.
pub fn n_lambda(budget: Budget) -> Result<Vec<ScalingReport>, Violation> {
    const ID: &str = "eq:sup-micro-u-L#N-lambda";
    measure(ID, budget, true, |d, t_end, n| {
        let traj = sampled(d, n, ID)?;
        let nn = BigRational::from_usize(n);
        Ok(after_collisions(&traj, t_end)
            .iter()
            .flat_map(|s| s.multipliers.iter().map(|l| abs(l.clone()) * &nn))
            .fold(BigRational::zero(), |m, x| if x > m { x } else { m }))
    })
}

/// Corrected: `sup_{t ≤ T} sup_i |λ_i(t)| ≤ C'` (without the factor N).
pub fn lambda_sup(budget: Budget) -> Result<Vec<ScalingReport>, Violation> {
    const ID: &str = "eq:sup-micro-u-L#N-lambda (corrected)";
    measure(ID, budget, true, |d, t_end, n| {
        let traj = sampled(d, n, ID)?;
        Ok(after_collisions(&traj, t_end)
            .iter()
            .flat_map(|s| s.multipliers.iter().map(|l| abs(l.clone())))
            .fold(BigRational::zero(), |m, x| if x > m { x } else { m }))
    })
}

/// `prop:pressure-bound`: `‖P̃_N‖_{M(0,T; L¹(0,1))} ≤ C`: the total mass
/// `Σ_k ∫_0^1 P̃_N(t_k, w) dw = Σ_k (1/N) Σ_i [λ_i]_{t_k}` over collisions
/// `t_k ≤ T`.
pub fn pressure_mass(budget: Budget) -> Result<Vec<ScalingReport>, Violation> {
    const ID: &str = "prop:pressure-bound";
    measure(ID, budget, true, |d, t_end, n| {
        let traj = sampled(d, n, ID)?;
        let nn = BigRational::from_usize(n);
        Ok(traj
            .impulses()
            .iter()
            .filter(|i| i.t <= *t_end)
            .map(|i| i.total() / &nn)
            .fold(BigRational::zero(), |a, b| a + b))
    })
}

/// `prop:L2-micro`: `sup_t (‖X_N‖² + ‖U_N‖² + ‖Λ_N‖²) ≤ C` (squared norms
/// of the piecewise-constant interpolations, `= ‖x‖² + ‖u‖² + ‖L‖²`).
pub fn l2_bounds(budget: Budget) -> Result<Vec<ScalingReport>, Violation> {
    const ID: &str = "prop:L2-micro";
    measure(ID, budget, true, |d, t_end, n| {
        let traj = sampled(d, n, ID)?;
        Ok(after_collisions(&traj, t_end)
            .iter()
            .map(|s| {
                let (mut l, ln) = multipliers(traj.data().velocities(), &s.velocities);
                l.push(ln);
                norm2(&s.positions) + norm2(&s.velocities) + norm2(&l)
            })
            .fold(BigRational::zero(), |m, x| if x > m { x } else { m }))
    })
}

/// `pwUN-L1`: `sup_{t ∈ [α, T]} ‖∂_w Ũ_N(t)‖_{L¹} ≤ C_α`, at `α = T/2`
/// (`= Σ|u_i − u_{i−1}|`, the total variation of `u`).
pub fn tv_u(budget: Budget) -> Result<Vec<ScalingReport>, Violation> {
    const ID: &str = "pwUN-L1";
    measure(ID, budget, true, |d, t_end, n| {
        let traj = sampled(d, n, ID)?;
        let alpha = t_end.clone() / BigRational::from_i64(2);
        let states: Vec<_> = after_collisions(&traj, t_end)
            .into_iter()
            .filter(|s| s.t >= alpha)
            .chain(state_at(traj.data(), &alpha).ok())
            .collect();
        Ok(states
            .iter()
            .map(|s| {
                s.velocities
                    .windows(2)
                    .map(|w| abs(w[1].clone() - &w[0]))
                    .fold(BigRational::zero(), |a, b| a + b)
            })
            .fold(BigRational::zero(), |m, x| if x > m { x } else { m }))
    })
}

/// `thm:main#discretisation` (i): `‖X⁰_N − X⁰‖²_{L²(0,1)} → 0`, computed
/// exactly (`X⁰` is piecewise affine in `w`; on each piece the square of an
/// affine function integrates in closed form).
pub fn discretisation(budget: Budget) -> Result<Vec<ScalingReport>, Violation> {
    const ID: &str = "thm:main#discretisation";
    measure(ID, budget, false, |d, _t_end, n| {
        let nn = BigRational::from_usize(n);
        let breaks = d.mass_breakpoints();
        let mut total = BigRational::zero();
        for i in 1..=n {
            let a = BigRational::from_usize(i - 1) / &nn;
            let b = BigRational::from_usize(i) / &nn;
            let xi = d.x0(&b);
            let mut cuts = vec![a.clone()];
            cuts.extend(breaks.iter().filter(|m| **m > a && **m < b).cloned());
            cuts.push(b);
            for w in cuts.windows(2) {
                // X⁰ is affine on (w0, w1): take its one-sided values there.
                let h = w[1].clone() - &w[0];
                let eps = h.clone() / BigRational::from_i64(4);
                let f_mid1 = d.x0(&(w[0].clone() + &eps)) - &xi;
                let f_mid2 = d.x0(&(w[1].clone() - &eps)) - &xi;
                // Affine f through (w0+h/4, f1) and (w1−h/4, f2): endpoints.
                let slope = (f_mid2.clone() - &f_mid1) / (h.clone() / BigRational::from_i64(2));
                let f0 = f_mid1 - &(slope.clone() * &eps);
                let f1 = f0.clone() + &(slope * &h);
                total +=
                    h * (f0.clone() * &f0 + f0 * &f1 + f1.clone() * &f1) / BigRational::from_i64(3);
            }
        }
        Ok(total)
    })
}
