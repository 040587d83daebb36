//! Floating-point reference solvers: the methods a practitioner would use,
//! each an independent algorithm on `f64`, measured exactly against the
//! exact engine.
//!
//! The paper's uniqueness argument (`prop:proj-micro`, proof of uniqueness:
//! `∂I_{K^N}` is monotone, so two solutions of `eq:micro-f0-lagr` contract)
//! says that every correct solver must converge to the one trajectory
//! `x(t) = P_K(x⁰ + t u⁰)`. The solvers here are that claim's test subjects:
//!
//! | module | method | parameters |
//! |---|---|---|
//! | [`pava`] | the exact engine's PAVA run on `f64` (`eq:proj-micro-x`) | none |
//! | [`events`] | event-driven cluster merge with a contact tolerance | `tol` |
//! | [`moreau_jean`] | Moreau–Jean time-stepping, impact law with restitution 0 | `dt`, `tol`, cap, `γ`, activation |
//! | [`catching_up`] | Maury–Venel catching-up scheme `x^{n+1} = P_K(x^n + Δt u^n)` | `dt`, `tol`, cap, contact |
//! | [`iterative`] | Appendix A's KKT system solved by dual projected Gauss–Seidel | `tol`, cap |
//!
//! [`pgs`] is the projected Gauss–Seidel kernel the last three share, and
//! [`mod@measure`] converts every `f64` result exactly to a rational and compares
//! it with the exact solution.
//!
//! Every solver implements [`Solver`]: it takes `f64` initial data and a time
//! `t ≥ 0` and returns an [`Output`] (positions, velocities when the method
//! has them, its own contact set, multipliers, work counters), or a
//! [`SolverError`] for bad parameters or non-finite numbers — never a panic.
//! A solver that stops at its iteration cap still returns its result, with
//! [`Output::converged`] `false` ([`Output::require_converged`] turns that
//! into [`SolverError::NoConvergence`]), so that failures can be measured.

use std::fmt;

use crate::initial::InitialData;

pub mod catching_up;
pub mod events;
pub mod iterative;
pub mod measure;
pub mod moreau_jean;
pub mod pava;
pub mod pgs;

pub use catching_up::CatchingUp;
pub use events::EventsF64;
pub use iterative::IterativeProjection;
pub use measure::{measure, measure_state, Errors, ErrorsF64};
pub use moreau_jean::MoreauJean;
pub use pava::PavaF64;

/// Largest number of time steps a time-stepping solver accepts (`t/Δt`):
/// beyond it the request is refused rather than left running for days.
pub const MAX_STEPS: f64 = 4_294_967_296.0;

/// A floating-point solver of the sticky dynamics.
pub trait Solver {
    /// The method's short name, stable for CSV columns: `pava-f64`,
    /// `events-f64`, `moreau-jean`, `catching-up`, `iterative-projection`.
    fn method(&self) -> &'static str;

    /// The parameters, as `key=value` pairs separated by spaces (empty when
    /// the method has none).
    fn parameters(&self) -> String;

    /// `method` followed by the parameters in parentheses.
    fn name(&self) -> String {
        let p = self.parameters();
        if p.is_empty() {
            self.method().to_string()
        } else {
            format!("{}({})", self.method(), p)
        }
    }

    /// The state at time `t ≥ 0` of the dynamics started from `data`.
    fn solve(&self, data: &InitialData<f64>, t: f64) -> Result<Output, SolverError>;
}

/// What a solver computed at one time `t`.
#[derive(Debug, Clone, PartialEq)]
pub struct Output {
    /// The time reached (the `t` asked for).
    pub t: f64,
    /// Positions `x_1 … x_N`.
    pub positions: Vec<f64>,
    /// Velocities `u_1 … u_N`, as the method defines them (`None` for a
    /// method that computes positions only). The exact reference is the right
    /// derivative `u(t)` (post-collision).
    pub velocities: Option<Vec<f64>>,
    /// The method's own contact set `Ω` (`df:Omega-micro`): `contacts[j]` for
    /// the pair `(j, j+1)` (0-based, `N − 1` entries). Each method documents
    /// how it decides (a tolerance, an index set, its cluster list).
    pub contacts: Vec<bool>,
    /// The multipliers `λ_1 … λ_{N−1}` of `eq:dyn-micro`, as the method
    /// produces them (accumulated impulses for the time-steppers).
    pub lambda: Option<Vec<f64>>,
    /// Appendix A's KKT multipliers `μ_1 … μ_{N−1}` of the position
    /// projection (`app:KKT`: `x − y + N Σ μ_i (e_i − e_{i+1}) = 0`), which
    /// equal `∫_0^t λ(s) ds`.
    pub kkt: Option<Vec<f64>>,
    /// The smallest jump of any `λ_i` over the method's history: the
    /// smallest weight of a Dirac mass of the pressure `p = dλ/dt`
    /// (`prop:micro-pressure` requires `p ≥ 0`). `None` for one-time methods
    /// or when nothing ever collided.
    pub min_pressure_jump: Option<f64>,
    /// Work done.
    pub work: Work,
    /// `true` when every inner iterative solve met its tolerance.
    pub converged: bool,
    /// The largest final residual of an inner iterative solve, in the units
    /// of that solve (`0` for direct methods).
    pub residual: f64,
}

impl Output {
    /// `Ok(self)` when every inner solve converged, else
    /// [`SolverError::NoConvergence`].
    pub fn require_converged(self) -> Result<Output, SolverError> {
        if self.converged {
            Ok(self)
        } else {
            Err(SolverError::NoConvergence {
                unconverged: self.work.unconverged,
                residual: self.residual,
            })
        }
    }
}

/// Work counters of one solve.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
#[cfg_attr(feature = "json", derive(serde::Serialize, serde::Deserialize))]
pub struct Work {
    /// Time steps taken (time-steppers) or collision events processed
    /// (event-driven); `1` for one-shot projections.
    pub steps: usize,
    /// Inner iterations: Gauss–Seidel sweeps, summed over all steps (a sweep
    /// covers one run of coupled contacts for the time-steppers, all `N − 1`
    /// pairs for the iterative projection).
    pub iterations: usize,
    /// Inner solves stopped by the iteration cap before meeting the
    /// tolerance.
    pub unconverged: usize,
}

/// Why a reference solver refused or failed.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum SolverError {
    /// A parameter is out of its range (`Δt ≤ 0`, `tol ≤ 0`, NaN, a zero
    /// iteration cap, …).
    BadParameter {
        /// The parameter's name.
        name: &'static str,
        /// The value given.
        value: f64,
        /// What it must satisfy.
        requirement: &'static str,
    },
    /// The requested time is negative, NaN or infinite.
    BadTime {
        /// The time given.
        t: f64,
    },
    /// More than [`MAX_STEPS`] time steps would be needed.
    TooManySteps {
        /// `t / Δt`.
        steps: f64,
    },
    /// An input number (radius, position or velocity) is NaN or infinite.
    NonFiniteInput {
        /// What it is: `radius`, `position` or `velocity`.
        what: &'static str,
        /// 0-based particle index (0 for the radius).
        index: usize,
    },
    /// A NaN or infinity appeared during the computation (overflow).
    Diverged {
        /// The step at which it was detected.
        step: usize,
    },
    /// An inner iterative solve stopped at its iteration cap (only from
    /// [`Output::require_converged`]).
    NoConvergence {
        /// How many inner solves did not converge.
        unconverged: usize,
        /// The largest final residual.
        residual: f64,
    },
    /// An [`Output`] does not fit the data it is measured against.
    Mismatch {
        /// What differs.
        what: &'static str,
        /// Expected length.
        expected: usize,
        /// Length found.
        found: usize,
    },
    /// An [`Output`] holds a NaN or infinity, so it has no exact value.
    NonFiniteOutput {
        /// Which field.
        what: &'static str,
        /// 0-based index in it.
        index: usize,
    },
    /// The exact reference could not be computed (the exact engine's error).
    Exact {
        /// The exact engine's message.
        message: String,
    },
}

impl fmt::Display for SolverError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SolverError::BadParameter {
                name,
                value,
                requirement,
            } => write!(f, "parameter {name} = {value:?}: it must be {requirement}"),
            SolverError::BadTime { t } => {
                write!(f, "time t = {t:?}: it must be finite and ≥ 0")
            }
            SolverError::TooManySteps { steps } => write!(
                f,
                "t/Δt = {steps:e} time steps: more than the limit {MAX_STEPS:e}"
            ),
            SolverError::NonFiniteInput { what, index } => {
                write!(f, "input {what} {index} is NaN or infinite")
            }
            SolverError::Diverged { step } => {
                write!(f, "NaN or infinity appeared at step {step}")
            }
            SolverError::NoConvergence {
                unconverged,
                residual,
            } => write!(
                f,
                "{unconverged} inner solve(s) stopped at the iteration cap (largest residual {residual:e})"
            ),
            SolverError::Mismatch {
                what,
                expected,
                found,
            } => write!(f, "{what}: expected {expected} values, found {found}"),
            SolverError::NonFiniteOutput { what, index } => {
                write!(f, "output {what}[{index}] is NaN or infinite")
            }
            SolverError::Exact { message } => write!(f, "exact reference: {message}"),
        }
    }
}

impl std::error::Error for SolverError {}

/// Every solver of this module with the given step, tolerance and iteration
/// cap (the one-time methods ignore `dt`), in the order of the table above:
/// the oracle battery runs the same checks on each.
pub fn battery(dt: f64, tol: f64, max_iterations: usize) -> Vec<Box<dyn Solver>> {
    vec![
        Box::new(PavaF64),
        Box::new(EventsF64::default()),
        Box::new(MoreauJean {
            dt,
            tol,
            max_iterations,
            ..MoreauJean::new(dt)
        }),
        Box::new(CatchingUp {
            dt,
            tol,
            max_iterations,
            ..CatchingUp::new(dt)
        }),
        Box::new(IterativeProjection {
            tol,
            max_iterations,
        }),
    ]
}

// ---------------------------------------------------------------------------
// Shared checks and scales (crate-internal).

/// `t` finite and `≥ 0`.
pub(crate) fn check_time(t: f64) -> Result<(), SolverError> {
    if t.is_finite() && t >= 0.0 {
        Ok(())
    } else {
        Err(SolverError::BadTime { t })
    }
}

/// Every number of the data finite.
pub(crate) fn check_data(data: &InitialData<f64>) -> Result<(), SolverError> {
    if !data.radius().is_finite() {
        return Err(SolverError::NonFiniteInput {
            what: "radius",
            index: 0,
        });
    }
    if let Some(i) = data.positions().iter().position(|x| !x.is_finite()) {
        return Err(SolverError::NonFiniteInput {
            what: "position",
            index: i,
        });
    }
    if let Some(i) = data.velocities().iter().position(|u| !u.is_finite()) {
        return Err(SolverError::NonFiniteInput {
            what: "velocity",
            index: i,
        });
    }
    Ok(())
}

/// A strictly positive finite parameter.
pub(crate) fn check_positive(name: &'static str, value: f64) -> Result<(), SolverError> {
    if value.is_finite() && value > 0.0 {
        Ok(())
    } else {
        Err(SolverError::BadParameter {
            name,
            value,
            requirement: "finite and > 0",
        })
    }
}

/// A non-zero iteration cap.
pub(crate) fn check_cap(name: &'static str, value: usize) -> Result<(), SolverError> {
    if value > 0 {
        Ok(())
    } else {
        Err(SolverError::BadParameter {
            name,
            value: 0.0,
            requirement: "at least 1",
        })
    }
}

/// The number of steps `n = ⌈t/Δt⌉` and the step actually used `h = t/n ≤ Δt`,
/// so that `n·h` lands on `t` (up to one rounding of `t/n`).
pub(crate) fn steps(t: f64, dt: f64) -> Result<(usize, f64), SolverError> {
    let ratio = t / dt;
    if !ratio.is_finite() || ratio > MAX_STEPS {
        return Err(SolverError::TooManySteps { steps: ratio });
    }
    let n = ratio.ceil();
    if n < 1.0 {
        return Ok((0, dt));
    }
    // n ≤ 2^32 fits usize on every supported platform.
    let n_usize = n as usize;
    Ok((n_usize, t / n))
}

/// `V = max_i |u⁰_i|`: every velocity of the sticky dynamics is a mean of
/// initial velocities (`eq:proj-u-micro`), so `|u_i(t)| ≤ V`.
pub fn velocity_scale(data: &InitialData<f64>) -> f64 {
    data.velocities().iter().fold(0.0f64, |m, u| m.max(u.abs()))
}

/// A bound `X` on the magnitude of every position over `[0, t]`:
/// `max_i |x⁰_i| + t·V + 2·N·2r` (the projection moves a particle by at most
/// its cluster's extent beyond free flight).
pub fn position_scale(data: &InitialData<f64>, t: f64) -> f64 {
    let x = data.positions().iter().fold(0.0f64, |m, x| m.max(x.abs()));
    x + t * velocity_scale(data) + 2.0 * data.n() as f64 * data.two_r()
}

/// `4ε`: gaps and relative velocities computed in `f64` from numbers of
/// magnitude `X` carry a rounding error of a few `ε·X`; a residual below
/// `ROUNDOFF·X` is noise, so every iterative tolerance is floored there.
pub(crate) const ROUNDOFF: f64 = 4.0 * f64::EPSILON;

/// `Err(Diverged)` if any value is not finite.
pub(crate) fn check_finite(v: &[f64], step: usize) -> Result<(), SolverError> {
    if v.iter().all(|x| x.is_finite()) {
        Ok(())
    } else {
        Err(SolverError::Diverged { step })
    }
}

/// `(λ_1 … λ_{N−1})` from `u⁰` and `u` by the generic exact-path code
/// (`eq:dyn-micro`, [`crate::contact::multipliers`]) run on `f64`.
pub(crate) fn lambda_from_velocities(u0: &[f64], u: &[f64]) -> Vec<f64> {
    crate::contact::multipliers(u0, u).0
}

/// `(μ_1 … μ_{N−1})` of Appendix A from `y = x⁰ + t u⁰` and `x`
/// ([`crate::contact::kkt_multipliers`] run on `f64`).
pub(crate) fn kkt_from_positions(y: &[f64], x: &[f64]) -> Vec<f64> {
    crate::contact::kkt_multipliers(y, x).0
}

/// The next `f64` above a finite `x`.
fn next_up(x: f64) -> f64 {
    if x == 0.0 {
        f64::from_bits(1)
    } else if x > 0.0 {
        f64::from_bits(x.to_bits() + 1)
    } else {
        f64::from_bits(x.to_bits() - 1)
    }
}

/// Rounds exact initial data to admissible `f64` data, as every
/// floating-point code must before it starts.
///
/// Rounding each number to the nearest `f64` may break admissibility: a
/// contact `x⁰_{i+1} − x⁰_i = 2r` becomes a gap one ulp short of `2r` (an
/// overlap, `df:KN`) or a contact of approaching particles (`def:velcone`)
/// about half the time. So, left to right: the radius and velocities are
/// rounded to nearest; a particle in exact contact with its left neighbour
/// is placed at `x_{i−1} + 2r` computed in `f64`; then any particle whose
/// `f64` gap to its left neighbour is below `2r`, or equal to `2r` while
/// the pair approaches, is moved up one ulp at a time until the pair is
/// admissible both under the `f64` test of [`InitialData::new`] and in the
/// exact rational values of the `f64` numbers
/// ([`measure::exact_input`] then succeeds). Every position moves by at most
/// a few ulps beyond nearest rounding.
///
/// Errors: a number that does not fit `f64` (overflow), or no admissible
/// position within 64 ulps (only when `2r` is far below the resolution of
/// the positions, e.g. `2r` rounding to zero).
pub fn round_to_f64(
    data: &InitialData<num_rational::BigRational>,
) -> Result<InitialData<f64>, SolverError> {
    use crate::scalar::Scalar;
    let to_f64 = |q: &num_rational::BigRational, what: &'static str, index: usize| {
        f64::from_big_rational(q)
            .filter(|v| v.is_finite())
            .ok_or(SolverError::NonFiniteInput { what, index })
    };
    let radius = to_f64(data.radius(), "radius", 0)?;
    let two_r = radius + radius;
    let exact_two_r = data.two_r();
    let x0 = data.positions();
    let velocities = data
        .velocities()
        .iter()
        .enumerate()
        .map(|(i, u)| to_f64(u, "velocity", i))
        .collect::<Result<Vec<f64>, _>>()?;
    let two_r_q = two_r.to_big_rational();
    let mut positions: Vec<f64> = Vec::with_capacity(data.n());
    for (i, xq) in x0.iter().enumerate() {
        let mut xi = to_f64(xq, "position", i)?;
        if let Some(&prev) = positions.last() {
            if x0[i].clone() - &x0[i - 1] == exact_two_r {
                xi = prev + two_r;
            }
            // Admissible in f64 (the test of `InitialData::new`) and in the
            // exact values of the f64 numbers (so that the problem the
            // solver is given has an exact solution to compare with).
            let admissible = |xi: f64| {
                let gap = xi - prev;
                let f64_ok = gap > two_r || (gap == two_r && velocities[i - 1] <= velocities[i]);
                let exact_gap = xi
                    .to_big_rational()
                    .zip(prev.to_big_rational())
                    .map(|(a, b)| a - b);
                let exact_ok = match (exact_gap, &two_r_q) {
                    (Some(g), Some(c)) => g > *c || (g == *c && velocities[i - 1] <= velocities[i]),
                    _ => false,
                };
                f64_ok && exact_ok
            };
            let mut guard = 0;
            while !admissible(xi) {
                xi = next_up(xi);
                guard += 1;
                if guard > 64 || !xi.is_finite() {
                    return Err(SolverError::Exact {
                        message: format!(
                            "position {}: no admissible f64 within 64 ulps of the exact value",
                            i + 1
                        ),
                    });
                }
            }
        }
        positions.push(xi);
    }
    InitialData::new(radius, positions, velocities).map_err(|e| SolverError::Exact {
        message: e.to_string(),
    })
}
