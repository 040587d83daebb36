//! The peers in the atlas (`--peers`): every peer solver of
//! [`crate::report::peers`] run once per scene (up to [`PEER_MAX_N`]
//! particles) at the scene's time, its answer scored exactly by
//! [`crate::reference::measure::compare`] against the exact solution of the
//! original rational scene, as a [`Row`] like our methods' rows.
//!
//! **Cost budget.** Each (peer, scene) run has a budget of wall time
//! ([`PEER_BUDGET_QUICK`] seconds with `--quick`, [`PEER_BUDGET`] without).
//! A run whose predicted cost exceeds it is not started: the prediction is
//! the driver's start-up ([`STARTUP_SECONDS`]) plus, for a time-stepper,
//! `N · ⌈t/h⌉` particle-steps at its measured [`Peer::step_seconds`]. A run
//! still going at the budget is stopped. Both get a `skipped` row with the
//! reason (`—` and the reason in `stability.md`).
//!
//! **Timing.** A peer's row carries the solver call alone as its driver
//! timed it (warm-up, repetitions, median: `wall_seconds`, `repeats`), the
//! set-up done apart (`setup_seconds`) and the whole process
//! (`process_seconds`: interpreter start-up and imports included); the
//! charts draw the first, as they draw our methods' in-process times.

use std::collections::BTreeSet;
use std::path::Path;
use std::time::Duration;

use num_rational::BigRational;
use num_traits::Zero;

use crate::fast::kernel::{self, IntegerData};
use crate::reference::measure::compare;
use crate::reference::ErrorsF64;
use crate::report::peers::{
    default_scripts_dir, peers, run_peer_within, Peer, PeerOutcome, STARTUP_SECONDS,
};
use crate::scalar::Scalar;
use crate::scene::{Scene, SceneKind};

use super::failure::OVERLAP_TOLERANCE;
use super::jobs::{Setting, Sweep};
use super::solve::{Row, Status};
use super::suite::Case;

/// The largest `N` the peers are run on (they are slow: interpreters,
/// dense QPs, small time steps); larger scenes get a `skipped` row per peer.
pub const PEER_MAX_N: usize = 1000;

/// The wall-time budget of one peer run with `--quick`, in seconds.
pub const PEER_BUDGET_QUICK: f64 = 10.0;

/// The wall-time budget of one peer run without `--quick`, in seconds.
pub const PEER_BUDGET: f64 = 300.0;

/// The predicted wall time of `peer` on `case`: start-up plus, for a
/// time-stepper, `N · ⌈t/h⌉` particle-steps at [`Peer::step_seconds`].
pub(super) fn predicted_seconds(peer: &Peer, case: &Case) -> f64 {
    let h: Option<f64> = peer
        .args
        .iter()
        .position(|a| *a == "--h")
        .and_then(|i| peer.args.get(i + 1))
        .and_then(|h| h.parse().ok());
    let steps = h.map_or(0.0, |h| (case.t / h).ceil());
    STARTUP_SECONDS + peer.step_seconds * case.n as f64 * steps
}

/// Why `peer` is not run on `case` within `budget` seconds, if it is not.
fn not_run(peer: &Peer, case: &Case, budget: f64) -> Option<String> {
    if case.n > PEER_MAX_N {
        return Some(format!("N = {} > {PEER_MAX_N}", case.n));
    }
    let p = predicted_seconds(peer, case);
    (p > budget).then(|| format!("predicted {p:.0} s > {budget} s budget"))
}

/// The `method` of a peer's rows: `peer:<name>`.
pub(super) fn peer_method(peer: &Peer) -> String {
    format!("peer:{}", peer.name)
}

/// The peers' methods in the order of [`peers`].
pub(super) fn peer_methods() -> Vec<String> {
    peers().iter().map(peer_method).collect()
}

/// Runs the peers on scenes; a peer found not installed is reported once on
/// standard error and not run again.
pub(super) struct PeerRunner {
    skipped: BTreeSet<&'static str>,
    budget: f64,
}

impl PeerRunner {
    /// A runner with a budget of `budget` seconds per run.
    pub(super) fn new(budget: f64) -> PeerRunner {
        PeerRunner {
            skipped: BTreeSet::new(),
            budget,
        }
    }

    /// One row per installed peer on `case` (scratch files under `work`).
    /// A scene larger than [`PEER_MAX_N`], a run predicted beyond the
    /// budget and a run stopped at the budget get a `skipped` row with the
    /// reason (each peer not known to be missing).
    pub(super) fn rows(&mut self, case: &Case, work: &Path) -> Vec<Row> {
        let mut out = Vec::new();
        let scripts = default_scripts_dir();
        let large = case.n > PEER_MAX_N;
        let scene = Scene {
            name: Some(case.name.clone()),
            description: None,
            t_end: None,
            kind: SceneKind::Particles,
            data: case.exact.clone(),
        };
        let exact = if large {
            None
        } else {
            kernel::state_at(&IntegerData::new(&case.exact), &case.tq).ok()
        };
        for peer in peers() {
            if self.skipped.contains(peer.name) {
                continue;
            }
            let mut row = Row::blank(
                case,
                Setting {
                    method: peer_method(&peer),
                    parameter: peer.args.join(" "),
                    sweep: Sweep::Single,
                    dt: None,
                    tol: None,
                    cap: None,
                },
            );
            if let Some(why) = not_run(&peer, case, self.budget) {
                row.status = Status::Skipped(why);
                out.push(row);
                continue;
            }
            let dir = work.join(super::file_stem(&case.name));
            match run_peer_within(
                &peer,
                &scene,
                std::slice::from_ref(&case.tq),
                &scripts,
                &dir,
                Some(Duration::from_secs_f64(self.budget)),
            ) {
                Ok(PeerOutcome::OverTime(s)) => {
                    row.status = Status::Skipped(format!("stopped at the {s} s budget"));
                }
                Ok(PeerOutcome::Skipped(msg)) => {
                    eprintln!("atlas --peers: {msg}");
                    self.skipped.insert(peer.name);
                    continue;
                }
                Err(e) => row.status = Status::Refused(e.message),
                Ok(PeerOutcome::Ran(run)) => {
                    let timing = DriverTiming::read(&run.solution);
                    row.process_seconds = Some(run.wall_seconds);
                    row.setup_seconds = timing.setup_seconds;
                    match timing.solve {
                        Some((median, repetitions)) => {
                            row.wall = median;
                            row.repeats = repetitions;
                        }
                        None => {
                            row.status = Status::Refused(
                                "the driver did not time its solver call (solve_seconds)"
                                    .to_string(),
                            );
                            out.push(row);
                            continue;
                        }
                    }
                    match (&exact, run.frames.first()) {
                        (None, _) => {
                            row.status = Status::Refused("no exact state at t".to_string())
                        }
                        (_, None) => row.status = Status::Refused("no frame".to_string()),
                        (Some(state), Some(f)) => match score(case, state, f) {
                            Ok(e) => row.errors = Some(e),
                            Err(m) => row.status = Status::Refused(format!("compare: {m}")),
                        },
                    }
                }
            }
            out.push(row);
        }
        out
    }
}

/// The driver's own timing of its solver call, from the first line of its
/// SOLUTION (`scripts/peers/common.py`, `timed`): the median of the timed
/// calls and their number, and the set-up done apart.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
struct DriverTiming {
    /// `(solve_seconds, solve_repetitions)`.
    solve: Option<(f64, usize)>,
    /// `setup_seconds` (`null` when the peer has no set-up apart).
    setup_seconds: Option<f64>,
}

impl DriverTiming {
    fn read(solution: &Path) -> DriverTiming {
        let text = std::fs::read_to_string(solution).unwrap_or_default();
        DriverTiming::parse(text.lines().next().unwrap_or(""))
    }

    /// The fields are numbers (or `null`) that the driver writes with
    /// Python's `json.dumps`; a line that is not a JSON object, or lacks
    /// them, gives no timing.
    fn parse(line: &str) -> DriverTiming {
        let object: serde_json::Value =
            serde_json::from_str(line).unwrap_or(serde_json::Value::Null);
        let field = |key: &str| object.get(key);
        let seconds = field("solve_seconds")
            .and_then(serde_json::Value::as_f64)
            .filter(|s| s.is_finite() && *s >= 0.0);
        let repetitions = field("solve_repetitions")
            .and_then(serde_json::Value::as_u64)
            .and_then(|k| usize::try_from(k).ok())
            .filter(|k| *k > 0);
        DriverTiming {
            solve: seconds.zip(repetitions),
            setup_seconds: field("setup_seconds").and_then(serde_json::Value::as_f64),
        }
    }
}

/// A peer's frame scored exactly, rounded to the atlas's `f64` columns.
/// Without the solver's own contact set, pairs with a gap within
/// [`OVERLAP_TOLERANCE`]`·2r` of contact count as its contacts.
fn score(
    case: &Case,
    state: &crate::state::State<BigRational>,
    f: &crate::report::solution::Frame,
) -> Result<ErrorsF64, String> {
    let two_r = case.exact.two_r();
    let tol = OVERLAP_TOLERANCE
        .to_big_rational()
        .map(|t| t * &two_r)
        .unwrap_or_else(<BigRational as Zero>::zero);
    let cand = f.candidate();
    let c = compare(&cand, state, &two_r, &tol).map_err(|e| e.to_string())?;
    let lossy = |q: &BigRational| q.to_f64_lossy();
    let min_gap = f
        .positions
        .windows(2)
        .map(|w| &w[1] - &w[0] - &two_r)
        .min()
        .map(|g| lossy(&g));
    let min_lambda = f
        .multipliers
        .as_ref()
        .and_then(|l| l.iter().min().cloned())
        .map(|m| lossy(&m));
    Ok(ErrorsF64 {
        position: lossy(&c.position_max.value),
        velocity: c.velocity_max.as_ref().map(|m| lossy(&m.value)),
        lambda: c.multiplier_max.as_ref().map(|m| lossy(&m.value)),
        kkt: None,
        missed_contacts: c.missed_contacts,
        spurious_contacts: c.spurious_contacts,
        min_gap,
        min_lambda,
        min_pressure_jump: None,
        oleinik_violations: c.oleinik.as_ref().map(Vec::len),
    })
}

#[cfg(test)]
mod tests {
    use super::DriverTiming;

    #[test]
    fn the_drivers_timing_is_read_from_its_first_line() {
        let line = r#"{"t": "1", "positions": [0.0], "peer": "osqp", "setting": "default", "velocity_method": "x", "solve_seconds": 0.0025, "solve_repetitions": 80, "setup_seconds": null, "wall_seconds": 0.004}"#;
        assert_eq!(
            DriverTiming::parse(line),
            DriverTiming {
                solve: Some((0.0025, 80)),
                setup_seconds: None
            }
        );
        let with_setup = line.replace(r#""setup_seconds": null"#, r#""setup_seconds": 0.5"#);
        assert_eq!(DriverTiming::parse(&with_setup).setup_seconds, Some(0.5));
        // A driver that did not time its call (the old format) gives none.
        let old = r#"{"t": "1", "positions": [0.0], "wall_seconds": 0.004}"#;
        assert_eq!(DriverTiming::parse(old).solve, None);
        assert_eq!(DriverTiming::parse("not json").solve, None);
    }
}
