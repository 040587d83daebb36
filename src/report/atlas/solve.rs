//! Running and measuring: each job solved and timed alone, then measured
//! exactly by [`crate::reference::measure()`] (the floating-point methods)
//! or [`crate::reference::measure_state`] (the exact engines, each against
//! the other).

use std::fmt;
use std::time::{Duration, Instant};

use indicatif::ProgressBar;
use num_rational::BigRational;
use serde::{Deserialize, Serialize};

use crate::fast::kernel::{self, IntegerData};
use crate::fast::merge::IntegerTrajectory;
use crate::projection::state_at;
use crate::reference::{measure, measure_state, ErrorsF64, Output, Work};
use crate::state::State;
use crate::trajectory::Trajectory;

use super::jobs::{Engine, Job, Setting};
use super::suite::{data_err, Case};
use super::AtlasError;

/// How a row ended.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub(super) enum Status {
    Ok,
    NoConvergence,
    Refused(String),
    /// Not run (a peer on a scene larger than it is run on): why.
    Skipped(String),
}

impl fmt::Display for Status {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Status::Ok => write!(f, "ok"),
            Status::NoConvergence => write!(f, "no-convergence"),
            Status::Refused(m) => write!(f, "refused: {m}"),
            Status::Skipped(m) => write!(f, "skipped: {m}"),
        }
    }
}

/// One measured (scene, method, parameter); in a shard's file
/// ([`super::campaign`]) each double is its bit pattern.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub(super) struct Row {
    pub(super) scene: String,
    pub(super) n: usize,
    #[serde(with = "crate::campaign::bits::one")]
    pub(super) t: f64,
    #[serde(with = "crate::campaign::bits::one")]
    pub(super) two_r: f64,
    #[serde(with = "crate::campaign::bits::one")]
    pub(super) v: f64,
    pub(super) setting: Setting,
    pub(super) status: Status,
    #[serde(with = "crate::campaign::bits::one")]
    pub(super) wall: f64,
    pub(super) repeats: usize,
    pub(super) errors: Option<ErrorsF64>,
    pub(super) work: Option<Work>,
    pub(super) converged: Option<bool>,
    #[serde(with = "crate::campaign::bits::maybe")]
    pub(super) residual: Option<f64>,
    /// A peer's whole process, seconds (see [`super::CSV_COLUMNS`]).
    #[serde(with = "crate::campaign::bits::maybe")]
    pub(super) process_seconds: Option<f64>,
    /// A peer's set-up done apart from its solver call, seconds.
    #[serde(with = "crate::campaign::bits::maybe")]
    pub(super) setup_seconds: Option<f64>,
}

impl Row {
    /// A row of `case` for `setting`, not yet run: status `Ok`, no time,
    /// no errors.
    pub(super) fn blank(case: &Case, setting: Setting) -> Row {
        Row {
            scene: case.name.clone(),
            n: case.n,
            t: case.t,
            two_r: case.two_r,
            v: case.v,
            setting,
            status: Status::Ok,
            wall: 0.0,
            repeats: 0,
            errors: None,
            work: None,
            converged: None,
            residual: None,
            process_seconds: None,
            setup_seconds: None,
        }
    }
}

/// Runs `f` once, then again until `min` has passed in total (at most
/// `max_reps` runs); returns the first result, the mean time per run and
/// the number of runs.
pub(super) fn timed<T>(
    min: Duration,
    max_reps: usize,
    mut f: impl FnMut() -> T,
) -> (T, f64, usize) {
    let start = Instant::now();
    let first = f();
    let mut reps = 1;
    while start.elapsed() < min && reps < max_reps {
        std::hint::black_box(f());
        reps += 1;
    }
    (first, start.elapsed().as_secs_f64() / reps as f64, reps)
}

/// The two exact engines' states at `t`, computed once per scene.
pub(super) struct ExactStates {
    pava: State<BigRational>,
    events: State<BigRational>,
    /// The smallest pressure jump of the collisions up to `t`.
    min_jump: Option<BigRational>,
}

pub(super) fn exact_states(case: &Case) -> Result<ExactStates, AtlasError> {
    let err = data_err(&case.name);
    let pava = state_at(&case.exact, &case.tq).map_err(&err)?;
    let traj = Trajectory::new(case.exact.clone());
    let events = traj.at(&case.tq).map_err(&err)?;
    let min_jump = traj
        .impulses()
        .iter()
        .filter(|i| i.t <= case.tq)
        .flat_map(|i| i.jumps())
        .min();
    Ok(ExactStates {
        pava,
        events,
        min_jump,
    })
}

/// Runs (and times) one job. The exact engines' rows are complete; a
/// floating-point solver's output is returned for [`measure_all`].
fn solve_job(
    case: &Case,
    exact: Option<&ExactStates>,
    job: &Job,
    min_time: Duration,
) -> (Row, Option<Output>) {
    let mut row = Row::blank(case, job.setting.clone());
    match &job.engine {
        Engine::ExactPava => {
            // The fastest exact engine for one time: the integer kernel. As
            // the f64 methods get their data converted to f64 untimed, the
            // kernel gets its data scaled to integers untimed; the timed part
            // is the exact answer itself (the partition and the integer block
            // sums, every x_i(t), u_i(t) exactly). That answer, as a state, is
            // measured against the generic BigRational event merge, so an
            // error of 0 is checked, not assumed.
            let ints = IntegerData::new(&case.exact);
            let (_, wall, reps) = timed(min_time, 1000, || kernel::blocks_at(&ints, &case.tq));
            row.wall = wall;
            row.repeats = reps;
            match kernel::state_at(&ints, &case.tq) {
                Err(e) => row.status = Status::Refused(e.to_string()),
                Ok(state) => {
                    row.errors = exact.map(|x| {
                        measure_state(&state, &x.events, &case.exact.two_r(), &case.tq, None)
                            .to_f64()
                    });
                }
            }
        }
        Engine::ExactEvents => {
            // The whole history on integers (the integer merge), timed from
            // the exact data; measured against the generic projection.
            let (_, wall, reps) = timed(min_time, 1000, || IntegerTrajectory::new(&case.exact));
            row.wall = wall;
            row.repeats = reps;
            let traj = IntegerTrajectory::new(&case.exact).into_trajectory();
            match traj.at(&case.tq) {
                Err(e) => row.status = Status::Refused(e.to_string()),
                Ok(state) => {
                    row.errors = exact.map(|x| {
                        let min_jump = x.min_jump.clone();
                        measure_state(&state, &x.pava, &case.exact.two_r(), &case.tq, min_jump)
                            .to_f64()
                    });
                }
            }
        }
        Engine::Float(solver) => {
            let (out, wall, reps) = timed(min_time, 1000, || solver.solve(&case.data, case.t));
            row.wall = wall;
            row.repeats = reps;
            match out {
                Err(e) => row.status = Status::Refused(e.to_string()),
                Ok(out) => {
                    row.work = Some(out.work);
                    row.converged = Some(out.converged);
                    row.residual = Some(out.residual);
                    if !out.converged {
                        row.status = Status::NoConvergence;
                    }
                    return (row, Some(out));
                }
            }
        }
    }
    (row, None)
}

/// Measures every solved output of one scene exactly (`reference::measure`),
/// on up to [`MEASURE_THREADS`] threads: the solves are all timed before,
/// one at a time, so the measurement does not disturb the timings.
fn measure_all(case: &Case, solved: Vec<(Row, Option<Output>)>, bar: &ProgressBar) -> Vec<Row> {
    let threads = std::thread::available_parallelism()
        .map_or(1, |n| n.get())
        .clamp(1, MEASURE_THREADS);
    let mut slots: Vec<(Row, Option<Output>)> = solved;
    let mut parts: Vec<Vec<&mut (Row, Option<Output>)>> =
        (0..threads).map(|_| Vec::new()).collect();
    for (i, slot) in slots.iter_mut().enumerate() {
        parts[i % threads].push(slot);
    }
    std::thread::scope(|scope| {
        for part in parts {
            scope.spawn(move || {
                for (row, out) in part {
                    if let Some(out) = out.take() {
                        measure_one(case, row, &out);
                    }
                    bar.inc(1);
                }
            });
        }
    });
    slots.into_iter().map(|(row, _)| row).collect()
}

/// Measures one solved output exactly into its row.
fn measure_one(case: &Case, row: &mut Row, out: &Output) {
    match measure(out, &case.exact, &case.tq) {
        Ok(e) => row.errors = Some(e.to_f64()),
        Err(e) => row.status = Status::Refused(format!("measure: {e}")),
    }
}

/// Solves (timed) and measures one job: the row [`run_case`] gives it.
pub(super) fn solve_unit(
    case: &Case,
    exact: Option<&ExactStates>,
    job: &Job,
    min_time: Duration,
) -> Row {
    let (mut row, out) = solve_job(case, exact, job, min_time);
    if let Some(out) = out {
        measure_one(case, &mut row, &out);
    }
    row
}

/// Solves every job of one scene (timed, one at a time), then measures.
/// What a case's rows are measured against.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Reference {
    /// The exact states, computed first (the suite).
    Exact,
    /// Nothing exact ahead: each row is measured on its own (the
    /// stability section).
    None,
}

pub(super) fn run_case(
    case: &Case,
    jobs: &[Job],
    reference: Reference,
    min_time: Duration,
    bar: &ProgressBar,
) -> Result<Vec<Row>, AtlasError> {
    let exact = match reference {
        Reference::Exact => {
            bar.set_message(format!("{}: exact reference", case.name));
            Some(exact_states(case)?)
        }
        Reference::None => None,
    };
    let mut solved = Vec::with_capacity(jobs.len());
    for job in jobs {
        bar.set_message(format!(
            "{}: {} {}",
            case.name, job.setting.method, job.setting.parameter
        ));
        solved.push(solve_job(case, exact.as_ref(), job, min_time));
        bar.inc(1);
    }
    bar.set_message(format!("{}: measuring exactly", case.name));
    Ok(measure_all(case, solved, bar))
}

/// Threads used by the exact measurement.
const MEASURE_THREADS: usize = 4;
