//! The jobs of one scene: every method at every parameter of its sweeps
//! (the atlas grid, within the work budget), and one run per method for the
//! stability section.

use crate::reference::{CatchingUp, EventsF64, IterativeProjection, MoreauJean, PavaF64, Solver};

use serde::{Deserialize, Serialize};

use super::suite::Case;
use super::Size;

pub(super) enum Engine {
    ExactPava,
    ExactEvents,
    Float(Box<dyn Solver>),
}

/// What identifies a job, and the row it becomes: the method and its
/// settings.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub(super) struct Setting {
    /// One of [`super::EXACT_METHODS`] or [`super::METHODS`], or
    /// `peer:<name>` for a peer solver ([`crate::report::peers`]).
    pub(super) method: String,
    /// The solver's own [`Solver::parameters`] string (empty for the exact
    /// engines).
    pub(super) parameter: String,
    /// The parameter varied.
    pub(super) sweep: Sweep,
    /// The time step, when the method has one.
    #[serde(with = "crate::campaign::bits::maybe")]
    pub(super) dt: Option<f64>,
    /// The tolerance, when the method has one.
    #[serde(with = "crate::campaign::bits::maybe")]
    pub(super) tol: Option<f64>,
    /// The iteration cap, when the method has one.
    pub(super) cap: Option<usize>,
}

/// The parameter a job's row varies (the `sweep` column).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub(super) enum Sweep {
    /// None: a single run (the exact engines, `pava-f64`, the stability
    /// section, the peers).
    Single,
    /// The time step `Δt`.
    Dt,
    /// The tolerance.
    Tol,
    /// The iteration cap.
    Cap,
}

impl Sweep {
    /// Its name in the CSV: empty, `dt`, `tol` or `cap`.
    pub(super) fn as_str(self) -> &'static str {
        match self {
            Sweep::Single => "",
            Sweep::Dt => "dt",
            Sweep::Tol => "tol",
            Sweep::Cap => "cap",
        }
    }
}

pub(super) struct Job {
    pub(super) setting: Setting,
    pub(super) engine: Engine,
}

impl Job {
    fn exact(engine: Engine) -> Job {
        debug_assert!(matches!(engine, Engine::ExactPava | Engine::ExactEvents));
        Job {
            setting: Setting {
                method: match engine {
                    Engine::ExactPava => "exact-pava",
                    _ => "exact-events",
                }
                .to_string(),
                parameter: String::new(),
                sweep: Sweep::Single,
                dt: None,
                tol: None,
                cap: None,
            },
            engine,
        }
    }

    fn float(
        solver: Box<dyn Solver>,
        sweep: Sweep,
        dt: Option<f64>,
        tol: Option<f64>,
        cap: Option<usize>,
    ) -> Job {
        Job {
            setting: Setting {
                method: solver.method().to_string(),
                parameter: solver.parameters(),
                sweep,
                dt,
                tol,
                cap,
            },
            engine: Engine::Float(solver),
        }
    }
}

fn moreau_jean(dt: f64, tol: f64, cap: usize) -> Box<dyn Solver> {
    Box::new(MoreauJean {
        tol,
        max_iterations: cap,
        ..MoreauJean::new(dt)
    })
}

fn catching_up(dt: f64, tol: f64, cap: usize) -> Box<dyn Solver> {
    Box::new(CatchingUp {
        tol,
        max_iterations: cap,
        ..CatchingUp::new(dt)
    })
}

/// The default inner tolerance and cap of the time-steppers.
const STEP_TOL: f64 = 1e-12;
pub(super) const STEP_CAP: usize = 100_000;
/// The step of the tolerance and cap sweeps, and of `cost-vs-n`.
pub(super) const SWEEP_DT: f64 = 1.0 / 256.0;
/// The contact tolerance of `events-f64` shown in `cost-vs-n`.
pub(super) const EVENTS_TOL: f64 = 1e-12;
/// The tolerance of `iterative-projection` shown in `cost-vs-n`.
pub(super) const ITERATIVE_TOL: f64 = 1e-9;

/// The parameter grid of one suite scene.
pub(super) fn jobs(case: &Case, size: Size) -> Vec<Job> {
    let n = case.n as f64;
    let budget: f64 = size.pick(2e7, 5e8);
    let mut out = vec![
        Job::exact(Engine::ExactPava),
        Job::exact(Engine::ExactEvents),
    ];
    out.push(Job::float(
        Box::new(PavaF64),
        Sweep::Single,
        None,
        None,
        None,
    ));
    let event_tols: &[f64] = size.pick(
        &[1e-6, 1e-12, 1e-16],
        &[1e-4, 1e-6, 1e-8, 1e-10, 1e-12, 1e-14, 1e-16],
    );
    for &tol in event_tols {
        out.push(Job::float(
            Box::new(EventsF64 { tol }),
            Sweep::Tol,
            None,
            Some(tol),
            None,
        ));
    }
    let ks: &[i32] = size.pick(&[4, 6, 8], &[2, 4, 6, 8, 10, 12, 14]);
    let step_tols: &[f64] = size.pick(&[1e-2, 1e-5, 1e-8], &[1e-1, 1e-3, 1e-6, 1e-9]);
    let step_caps: &[usize] = size.pick(&[1, 10, 100], &[1, 4, 16, 64, 256]);
    let steps = |dt: f64| (case.t / dt).ceil().max(1.0);
    type Make = fn(f64, f64, usize) -> Box<dyn Solver>;
    for make in [moreau_jean as Make, catching_up as Make] {
        for &k in ks {
            let dt = 2f64.powi(-k);
            if n * steps(dt) <= budget {
                out.push(Job::float(
                    make(dt, STEP_TOL, STEP_CAP),
                    Sweep::Dt,
                    Some(dt),
                    Some(STEP_TOL),
                    Some(STEP_CAP),
                ));
            }
        }
        if n * steps(SWEEP_DT) <= budget {
            for &tol in step_tols {
                out.push(Job::float(
                    make(SWEEP_DT, tol, STEP_CAP),
                    Sweep::Tol,
                    Some(SWEEP_DT),
                    Some(tol),
                    Some(STEP_CAP),
                ));
            }
            for &cap in step_caps {
                out.push(Job::float(
                    make(SWEEP_DT, STEP_TOL, cap),
                    Sweep::Cap,
                    Some(SWEEP_DT),
                    Some(STEP_TOL),
                    Some(cap),
                ));
            }
        }
    }
    let sweeps: &[usize] = size.pick(&[1, 16, 256], &[1, 4, 16, 64, 256, 1024, 4096, 16384]);
    for &cap in sweeps {
        if n * cap as f64 <= budget {
            out.push(Job::float(
                Box::new(IterativeProjection {
                    tol: 1e-15,
                    max_iterations: cap,
                }),
                Sweep::Cap,
                None,
                Some(1e-15),
                Some(cap),
            ));
        }
    }
    let iter_tols: &[f64] = size.pick(&[1e-3, 1e-6, 1e-9], &[1e-2, 1e-4, 1e-6, 1e-9, 1e-12]);
    let cap = ((budget * 4.0 / n) as usize).clamp(1000, 1_000_000);
    for &tol in iter_tols {
        out.push(Job::float(
            Box::new(IterativeProjection {
                tol,
                max_iterations: cap,
            }),
            Sweep::Tol,
            None,
            Some(tol),
            Some(cap),
        ));
    }
    out
}

/// The largest sweep cap of the time-steppers in the stability section (per
/// run of coupled contacts, per step); large scenes get less (down to 100).
pub const STABILITY_STEP_CAP: usize = 1000;

/// One run of each floating-point method on a stability scene: default
/// tolerances, `Δt = case.step`, the time-steppers capped at
/// `case.step_cap` sweeps, the iterative projection at `case.cap`.
pub(super) fn stability_jobs(case: &Case) -> Vec<Job> {
    let dt = case.step;
    let cap = case.cap;
    let step_cap = case.step_cap;
    vec![
        Job::float(Box::new(PavaF64), Sweep::Single, None, None, None),
        Job::float(
            Box::new(EventsF64::default()),
            Sweep::Single,
            None,
            Some(EventsF64::default().tol),
            None,
        ),
        Job::float(
            moreau_jean(dt, STEP_TOL, step_cap),
            Sweep::Single,
            Some(dt),
            Some(STEP_TOL),
            Some(step_cap),
        ),
        Job::float(
            catching_up(dt, STEP_TOL, step_cap),
            Sweep::Single,
            Some(dt),
            Some(STEP_TOL),
            Some(step_cap),
        ),
        Job::float(
            Box::new(IterativeProjection {
                tol: 1e-12,
                max_iterations: cap,
            }),
            Sweep::Single,
            None,
            Some(1e-12),
            Some(cap),
        ),
    ]
}
