//! The speed-vs-accuracy atlas (issue 4): every floating-point reference
//! solver of [`crate::reference`], at a sweep of its parameters, on a suite of
//! scenes, timed and measured *exactly* against the exact engine; and a
//! stability section of scenes built to break the methods.
//!
//! `sticky atlas [--quick] [--peers] [--scene NAME]… [--out DIR]` calls
//! [`run`]. It writes, under the
//! output folder (each file whole: temporary name, then rename):
//!
//! * `atlas.csv` — one row per (scene, method, parameter), columns
//!   [`CSV_COLUMNS`];
//! * `pareto-position-SCENE` and `pareto-velocity-SCENE` (`.svg`, `.png`) —
//!   max error against wall time, every method and parameter, with the
//!   Pareto front; the exact engines have error 0, which a log axis cannot
//!   show, so they (and any `f64` result that is exactly right) are drawn at
//!   a floor value named in the title and the legend;
//! * `error-vs-dt-SCENE` — position and velocity errors of the two
//!   time-steppers against `Δt`;
//! * `cost-vs-n` — wall time against `N` on the random scenes, one
//!   representative parameter per method (named in the legend);
//! * `stability.csv`, `stability.md` and `stability` (`.svg`, `.png`) — the
//!   "where methods fail" section: for each (scene, method) the failure
//!   kinds observed ([`Failure`]), as a table and as a grid of markers
//!   coloured by kind.
//!
//! **The suite.** Random scenes of `generate::initial_data` with
//! `N = 10, 100, 1000, 10⁴, 10⁵` (`--quick`: up to 1000), measured at
//! `t = 1025/1024` (random scenes put many exact collisions at `t = 1`; the
//! stability section covers that case); the shipped scenes
//! `appendix-c-two-blocks`, `three-cluster-simultaneous` and
//! `riemann-compression`, at their `t_end`.
//!
//! **Methods and parameters** (the full grid; `--quick` takes three values
//! per sweep and `Δt = 2^-4, 2^-6, 2^-8`): the exact engines, each the
//! fastest exact one for its task (`exact-pava`: the integer kernel's exact
//! answer at `t`, its data scaled to integers untimed as the f64 methods'
//! data are converted to f64 untimed; `exact-events`: the integer merge's
//! whole history from the exact data), each measured against the other
//! generic `BigRational` oracle, `pava-f64`, `events-f64` over its contact
//! tolerance (`1e-4 … 1e-16`), `moreau-jean` and `catching-up` over
//! `Δt = 2^-k` (`k = 2 … 14`, inner tolerance `1e-12`, cap `10⁵`), over the
//! inner tolerance at `Δt = 2^-8` and over the iteration cap at `Δt = 2^-8`,
//! `iterative-projection` over the sweep count (tolerance `1e-15`, i.e. at
//! the rounding floor) and over the tolerance (cap `min(10⁶, 4·B/N)`). A
//! run whose work (`N × steps` or `N × sweeps`) exceeds the budget `B`
//! (`5·10⁸`; `2·10⁷` with `--quick`) is left out of the grid of that scene
//! (the CSV lists what ran). The `parameter` column is the solver's own
//! [`Solver::parameters`](crate::reference::Solver::parameters) string, so
//! each row names every setting.
//!
//! **The stability section** runs each floating-point method once per
//! scene with its default tolerances: the time-steppers with a power-of-two
//! number of steps (at most 1024, 256 with `--quick`, down to 4 for large
//! `N`: about `4·10⁶/N`, `2.56·10⁵/N` with `--quick`) and at most
//! [`STABILITY_STEP_CAP`] sweeps per inner solve (`10⁸/N` for large `N`,
//! `2.5·10⁶/N` with `--quick`, at least 100), the iterative projection with
//! a cap of about `2·10⁹/N` sweeps (`2·10⁸/N` with `--quick`);
//! `stability.md` lists the values used for each scene. The failure kinds
//! and their thresholds are those of [`Failure`].
//!
//! **Errors** are those of [`crate::reference::measure()`], computed exactly
//! (each `f64` converted to the rational it denotes) against the exact
//! solution of the *original rational scene* at the exact value of the
//! `f64` time, so the rounding of the input is part of every error. They
//! become `f64` only in the CSV and the charts. The exact engines' rows are
//! measured too, each against the other engine, exactly: their errors are
//! `0` because the two agree, not by assumption.
//!
//! **Wall time** is the time of the solve alone (not of the measurement),
//! averaged over repeated solves for fast runs (at least 20 ms of work in
//! total, 2 ms with `--quick`; the `repeats` column).
//!
//! **Peers** (`--peers`, [`AtlasOptions::peers`]): every peer solver of
//! [`crate::report::peers`] that is installed runs once per scene with
//! `N ≤` [`PEER_MAX_N`] at the scene's time (suite and stability section),
//! as rows `method = peer:<name>` (`parameter`: the driver's options), in
//! the same CSV, Pareto charts (a colour and marker per peer) and stability
//! table (a column per peer, classified as ours). Its wall time is that of
//! the whole call (interpreter, imports, its own setup and solve), once;
//! its errors are those of [`crate::reference::measure::compare`], exact,
//! against the exact solution of the original rational scene; without the
//! peer's own contact set, gaps within [`OVERLAP_TOLERANCE`]`·2r` of
//! contact count as its contacts. `kkt_err`, `min_pressure_jump` and the
//! work counters stay empty. Larger suite scenes get one `skipped: N > …`
//! row per peer, and so does a run beyond its cost budget
//! ([`PEER_BUDGET_QUICK`] / [`PEER_BUDGET`] seconds: predicted from `N` and
//! the number of steps, or stopped at the budget); `stability.md` shows
//! them as `—` with the reason. A peer
//! that is not installed is named once on standard error and left out.
//! `--scene NAME` ([`AtlasOptions::scenes`]) keeps only the named scenes.
//!
//! **Files.** This one: options, errors, the CSV columns and the driver
//! ([`run`]); `suite.rs`: the scenes; `jobs.rs`: the grid of methods and
//! parameters; `solve.rs`: timing and exact measurement; `failure.rs`: the
//! failure kinds ([`Failure`]) and their classification; `csv.rs`,
//! `charts.rs`, `stability.rs`: the files written; `peers.rs`: the peers'
//! rows; `campaign.rs`: the jobs as the units of `sticky atlas --shard I/N`
//! and `sticky merge` ([`campaign`]).

use std::fmt;
use std::fs;
use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::time::Duration;

use indicatif::{ProgressBar, ProgressStyle};
use serde::{Deserialize, Serialize};

use crate::report::peers::STARTUP_SECONDS;
use crate::report::plot::{
    png_support, write_chart, write_grid, write_whole, PlotError, PngSupport,
};

pub mod campaign;
mod charts;
mod csv;
mod failure;
mod jobs;
mod peers;
mod solve;
mod stability;
mod suite;

pub use failure::{Failure, LARGE_ERROR, OVERLAP_TOLERANCE, SIGN_TOLERANCE, VELOCITY_TOLERANCE};
pub use jobs::STABILITY_STEP_CAP;
pub use peers::{PEER_BUDGET, PEER_BUDGET_QUICK, PEER_MAX_N};

use charts::{cost_chart, dt_chart, pareto_chart, Unknown};
use csv::write_csv;
use failure::classify;
use jobs::{jobs, stability_jobs, Job};
use peers::PeerRunner;
use solve::{run_case, Reference, Row};
use stability::{stability_grid, stability_markdown};
use suite::{stability_suite, suite};

/// How much of the atlas runs: the scenes' sizes, the parameter grids,
/// the time budgets.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Size {
    /// The small suite (`--quick`: N ≤ 1000, three values per parameter,
    /// small stability scenes): well under a minute.
    Quick,
    /// The whole suite (N up to 10⁵, the full grids).
    Full,
}

impl Size {
    /// `quick` for the small suite, `full` for the whole one.
    fn pick<T>(self, quick: T, full: T) -> T {
        match self {
            Size::Quick => quick,
            Size::Full => full,
        }
    }
}

/// Whether [`run`] draws a progress bar.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Feedback {
    /// A bar on standard error when it is a terminal.
    Bar,
    /// Nothing drawn.
    Quiet,
}

/// What to run and where to write it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct AtlasOptions {
    /// How much of the atlas runs.
    pub size: Size,
    /// The output folder (created if needed).
    pub out: PathBuf,
    /// Also run the real peer solvers ([`crate::report::peers`]) on every
    /// scene with `N ≤` [`PEER_MAX_N`], as rows `peer:<name>` of the CSV,
    /// the Pareto charts and the stability table.
    pub peers: bool,
    /// Only the scenes (of the suite and of the stability section) with
    /// these names; empty: every scene.
    pub scenes: Vec<String>,
}

impl Default for AtlasOptions {
    /// The full atlas into `./out/atlas/`.
    fn default() -> Self {
        AtlasOptions {
            size: Size::Full,
            out: PathBuf::from("out/atlas"),
            peers: false,
            scenes: Vec::new(),
        }
    }
}

/// Why the atlas could not be written.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum AtlasError {
    /// A scene of the suite could not be built (a shipped scene that does
    /// not parse, data that does not round to admissible `f64` data, …).
    Scene {
        /// The scene's name.
        scene: String,
        /// What went wrong.
        message: String,
    },
    /// A file or folder could not be written.
    Io {
        /// The path.
        path: PathBuf,
        /// What the operating system said.
        message: String,
    },
    /// A chart could not be drawn or written.
    Plot(PlotError),
}

impl fmt::Display for AtlasError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            AtlasError::Scene { scene, message } => write!(f, "atlas scene {scene}: {message}"),
            AtlasError::Io { path, message } => write!(f, "{}: {message}", path.display()),
            AtlasError::Plot(e) => write!(f, "{e}"),
        }
    }
}

impl std::error::Error for AtlasError {}

impl From<PlotError> for AtlasError {
    fn from(e: PlotError) -> Self {
        match e {
            PlotError::Io { path, message } => AtlasError::Io { path, message },
            other => AtlasError::Plot(other),
        }
    }
}

/// The columns of `atlas.csv` and (followed by `failures`) of
/// `stability.csv`, in order.
///
/// `scene, n, t, method, parameter, sweep` identify the row (`sweep` names
/// the parameter varied: `dt`, `tol`, `cap` or empty); `dt, tol, cap` are the
/// solver's parameters (empty when it has none); `status` is `ok`,
/// `no-convergence` (an inner solve stopped at its cap; the result is still
/// measured) or `refused: …` (the solver returned an error; no errors
/// then). `wall_seconds` per solve, averaged over `repeats`. The errors
/// ([`crate::reference::Errors`], exact, shown rounded): `pos_err`,
/// `vel_err`, `lambda_err`, `kkt_err` (max abs errors), `missed_contacts`,
/// `spurious_contacts`, `cluster_mismatch` (their sum), `min_gap`
/// (`min x_{i+1} − x_i − 2r`, negative = overlap) and `min_gap_over_2r`,
/// `min_lambda`, `min_pressure_jump`, `oleinik_violations`; then work
/// counters `steps, iterations, unconverged, converged, residual`; then,
/// for the peers, `process_seconds` (the wall time of the driver's whole
/// process: interpreter start-up, imports, file input and output, set-up and
/// the warm-up and timed calls) and `setup_seconds` (the median set-up done
/// apart from the call — a model to build —, empty when the peer has none).
/// A peer's `wall_seconds` is the solver call alone as the driver timed it
/// (a warm-up call, then `repeats` repetitions, the median: the clock
/// discipline of `sticky bench`), which the charts draw. Empty cells are
/// values the method does not produce.
pub const CSV_COLUMNS: [&str; 31] = [
    "scene",
    "n",
    "t",
    "method",
    "parameter",
    "sweep",
    "dt",
    "tol",
    "cap",
    "status",
    "wall_seconds",
    "repeats",
    "pos_err",
    "vel_err",
    "lambda_err",
    "kkt_err",
    "missed_contacts",
    "spurious_contacts",
    "cluster_mismatch",
    "min_gap",
    "min_gap_over_2r",
    "min_lambda",
    "min_pressure_jump",
    "oleinik_violations",
    "steps",
    "iterations",
    "unconverged",
    "converged",
    "residual",
    "process_seconds",
    "setup_seconds",
];

/// The floating-point methods, in the order of the tables.
pub const METHODS: [&str; 5] = [
    "pava-f64",
    "events-f64",
    "moreau-jean",
    "catching-up",
    "iterative-projection",
];

/// The exact engines' method names.
pub const EXACT_METHODS: [&str; 2] = ["exact-pava", "exact-events"];

/// The wall-time budget of one peer run.
fn peer_budget(size: Size) -> f64 {
    size.pick(PEER_BUDGET_QUICK, PEER_BUDGET)
}

/// The least time each job is timed for (repeated solves until then).
fn min_time(size: Size) -> Duration {
    Duration::from_millis(size.pick(2, 20))
}

fn file_stem(scene: &str) -> String {
    scene
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' {
                c
            } else {
                '_'
            }
        })
        .collect()
}

/// Runs the atlas and writes its files under `opts.out`; returns the paths
/// written (CSV and Markdown files first, then the charts). With
/// [`Feedback::Bar`] a progress bar is drawn on standard error when it is a
/// terminal.
///
/// The PNG files are skipped (SVG only) when no TrueType font is found on
/// the machine ([`crate::report::plot::png_support`]).
pub fn run(opts: &AtlasOptions, feedback: Feedback) -> Result<Vec<PathBuf>, AtlasError> {
    let out_dir = &opts.out;
    fs::create_dir_all(out_dir).map_err(|e| AtlasError::Io {
        path: out_dir.clone(),
        message: e.to_string(),
    })?;
    let bar = if feedback == Feedback::Bar && std::io::stderr().is_terminal() {
        let bar = ProgressBar::new(0);
        let style = ProgressStyle::with_template("atlas {bar:30} {pos}/{len} [{elapsed}] {msg}")
            .unwrap_or_else(|_| ProgressStyle::default_bar());
        bar.set_style(style);
        bar
    } else {
        ProgressBar::hidden()
    };
    bar.set_message("building scenes");
    let keep = |c: &suite::Case| opts.scenes.is_empty() || opts.scenes.contains(&c.name);
    let mut suite = suite(opts.size)?;
    suite.retain(keep);
    let mut stability = stability_suite(opts.size)?;
    stability.retain(keep);
    let main_jobs: Vec<Vec<Job>> = suite.iter().map(|c| jobs(c, opts.size)).collect();
    let stab_jobs: Vec<Vec<Job>> = stability.iter().map(stability_jobs).collect();
    // Each job counts twice: solved, then measured.
    let total: usize = main_jobs.iter().chain(&stab_jobs).map(Vec::len).sum();
    bar.set_length(2 * total as u64);
    let min_time = min_time(opts.size);

    let mut rows = Vec::new();
    for (case, jobs) in suite.iter().zip(&main_jobs) {
        rows.extend(run_case(case, jobs, Reference::Exact, min_time, &bar)?);
    }
    let mut stab_rows = Vec::new();
    for (case, jobs) in stability.iter().zip(&stab_jobs) {
        stab_rows.extend(run_case(case, jobs, Reference::None, min_time, &bar)?);
    }
    if opts.peers {
        let mut runner = PeerRunner::new(peer_budget(opts.size));
        let work = out_dir.join("peers");
        for case in &suite {
            bar.set_message(format!("{}: peers", case.name));
            rows.extend(runner.rows(case, &work.join("suite")));
        }
        for case in &stability {
            bar.set_message(format!("{}: peers", case.name));
            stab_rows.extend(runner.rows(case, &work.join("stability")));
        }
    }
    bar.set_message("writing files");
    let budget = opts.peers.then(|| peer_budget(opts.size));
    let written = write_files(out_dir, &suite, &stability, &rows, &stab_rows, budget)?;
    bar.finish_and_clear();
    Ok(written)
}

/// Writes the atlas's files under `out_dir` from its rows (suite, then
/// stability section), in the order of [`run`]'s result: the one writer of
/// a single run and of a merge of shards ([`campaign`]). `peer_budget`,
/// when the rows include the peers' (with this budget per run, seconds),
/// adds the note on them to `stability.md`.
fn write_files(
    out_dir: &Path,
    suite: &[suite::Case],
    stability: &[suite::Case],
    rows: &[Row],
    stab_rows: &[Row],
    peer_budget: Option<f64>,
) -> Result<Vec<PathBuf>, AtlasError> {
    let failures: Vec<Vec<Failure>> = stab_rows.iter().map(classify).collect();

    let mut written = Vec::new();
    let atlas_csv = out_dir.join("atlas.csv");
    write_csv(&atlas_csv, rows, None)?;
    written.push(atlas_csv);
    let stab_csv = out_dir.join("stability.csv");
    write_csv(&stab_csv, stab_rows, Some(&failures))?;
    written.push(stab_csv);
    let stab_md = out_dir.join("stability.md");
    let mut md = stability_markdown(stability, stab_rows, &failures);
    if let Some(budget) = peer_budget {
        md.push_str(&format!(
            "\nPeers (`--peers`): run once per scene with N ≤ {PEER_MAX_N} (wall time of the \
             whole call, interpreter and setup included; errors exact, \
             `reference::measure::compare`), each run within a budget of {budget} s: a run \
             predicted beyond it (start-up {STARTUP_SECONDS} s plus N·⌈t/h⌉ particle-steps \
             at the peer's measured cost) is not started, a run still going at the budget \
             is stopped; both are `—` with the reason. A peer that is not installed has no \
             column.\n"
        ));
    }
    if let PngSupport::Skipped(why) = png_support() {
        md.push_str(&format!("\nCharts: {why}.\n"));
    }
    write_whole(&stab_md, md.as_bytes())?;
    written.push(stab_md);

    for case in suite {
        let case_rows: Vec<&Row> = rows.iter().filter(|r| r.scene == case.name).collect();
        let stem = file_stem(&case.name);
        for of in Unknown::BOTH {
            if let Some(chart) = pareto_chart(&case.name, &case_rows, of) {
                let kind = of.name();
                let w = write_chart(&chart, out_dir, &format!("pareto-{kind}-{stem}"))?;
                written.extend(w.paths());
            }
        }
        if let Some(chart) = dt_chart(&case.name, &case_rows) {
            let w = write_chart(&chart, out_dir, &format!("error-vs-dt-{stem}"))?;
            written.extend(w.paths());
        }
    }
    let w = write_chart(&cost_chart(rows), out_dir, "cost-vs-n")?;
    written.extend(w.paths());
    if !stability.is_empty() {
        let w = write_grid(
            &stability_grid(stability, stab_rows, &failures),
            out_dir,
            "stability",
        )?;
        written.extend(w.paths());
    }
    Ok(written)
}
