//! The speed-vs-accuracy atlas (issue 4): every floating-point reference
//! solver of [`crate::reference`], at a sweep of its parameters, on a suite of
//! scenes, timed and measured *exactly* against the exact engine; and a
//! stability section of scenes built to break the methods.
//!
//! `sticky atlas [--quick] [--out DIR]` calls [`run`]. It writes, under the
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
//! per sweep and `Δt = 2^-4, 2^-6, 2^-8`): the exact engines (`exact-pava`:
//! `projection::state_at` on `BigRational`; `exact-events`:
//! `Trajectory::new` then `at`), `pava-f64`, `events-f64` over its contact
//! tolerance (`1e-4 … 1e-16`), `moreau-jean` and `catching-up` over
//! `Δt = 2^-k` (`k = 2 … 14`, inner tolerance `1e-12`, cap `10⁵`), over the
//! inner tolerance at `Δt = 2^-8` and over the iteration cap at `Δt = 2^-8`,
//! `iterative-projection` over the sweep count (tolerance `1e-15`, i.e. at
//! the rounding floor) and over the tolerance (cap `min(10⁶, 4·B/N)`). A
//! run whose work (`N × steps` or `N × sweeps`) exceeds the budget `B`
//! (`5·10⁸`; `2·10⁷` with `--quick`) is left out of the grid of that scene
//! (the CSV lists what ran). The `parameter` column is the solver's own
//! [`Solver::parameters`] string, so each row names every setting.
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

use std::fmt;
use std::fs;
use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use indicatif::{ProgressBar, ProgressStyle};
use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{Signed, Zero};

use crate::generate::{initial_data, Limits, SplitMix64};
use crate::initial::{unshift, InitialData};
use crate::projection::state_at;
use crate::reference::{
    measure, round_to_f64, velocity_scale, CatchingUp, Errors, ErrorsF64, EventsF64,
    IterativeProjection, MoreauJean, Output, PavaF64, Solver, Work,
};
use crate::report::plot::{
    palette, png_support, write_chart, write_grid, write_whole, Axis, Cell, Chart, Grid, Marker,
    PlotError, PngSupport, Rgb, Series, BLACK_RGB,
};
use crate::scalar::Scalar;
use crate::scene;
use crate::state::State;
use crate::trajectory::Trajectory;

/// What to run and where to write it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct AtlasOptions {
    /// The small suite (N ≤ 1000, three values per parameter, small
    /// stability scenes): well under a minute.
    pub quick: bool,
    /// The output folder (created if needed).
    pub out: PathBuf,
}

impl Default for AtlasOptions {
    /// The full atlas into `./out/atlas/`.
    fn default() -> Self {
        AtlasOptions {
            quick: false,
            out: PathBuf::from("out/atlas"),
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
/// counters `steps, iterations, unconverged, converged, residual`. Empty
/// cells are values the method does not produce.
pub const CSV_COLUMNS: [&str; 29] = [
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

// ---------------------------------------------------------------------------
// Failure kinds.

/// An overlap deeper than this fraction of the contact length `2r` counts
/// as [`Failure::Overlap`] (a millionth of a diameter; shallower ones are
/// mostly the rounding of touching particles, `ε·X` with `X` the size of
/// the coordinates; the CSV has every depth).
pub const OVERLAP_TOLERANCE: f64 = 1e-6;

/// `λ` or a pressure jump below `−SIGN_TOLERANCE · V` (`V = max |u⁰|`)
/// counts as negative.
pub const SIGN_TOLERANCE: f64 = 1e-12;

/// A position error above this fraction of `2r` counts as
/// [`Failure::LargeError`].
pub const LARGE_ERROR: f64 = 0.1;

/// A velocity error above this fraction of `V` counts as
/// [`Failure::WrongVelocities`].
pub const VELOCITY_TOLERANCE: f64 = 1e-6;

/// What went wrong for one (scene, method) of the stability section.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum Failure {
    /// The solver refused or failed (too many steps, NaN, …): its message.
    Refused(String),
    /// An inner iterative solve stopped at its iteration cap.
    NoConvergence {
        /// How many inner solves did not converge.
        unconverged: usize,
    },
    /// Particles overlap (`df:KN` violated) by more than
    /// [`OVERLAP_TOLERANCE`]`·2r`.
    Overlap {
        /// The deepest overlap, in units of `2r`.
        depth: f64,
    },
    /// The contact set at `t` differs from the exact `Ω_{x(t)}`
    /// (`df:Omega-micro`): collisions missed (exact contacts not reported)
    /// or spurious (reported contacts that do not exist).
    WrongClusters {
        /// Exact contacts the method misses.
        missed: usize,
        /// Contacts the method reports that are not exact contacts.
        spurious: usize,
    },
    /// Velocities off by more than [`VELOCITY_TOLERANCE`]`·V`: a collision
    /// missed, spurious or not yet resolved changes the post-collision
    /// velocity (`eq:proj-u-micro`).
    WrongVelocities {
        /// The velocity error, in units of `V`.
        error: f64,
    },
    /// A multiplier `λ_i < 0` (`eq:dyn-micro`).
    NegativeLambda {
        /// The smallest `λ`.
        min: f64,
    },
    /// A pressure jump `< 0` (`prop:micro-pressure`).
    NegativePressure {
        /// The smallest jump.
        min: f64,
    },
    /// Pairs violating `prop:Oleinik`.
    Oleinik {
        /// How many pairs.
        pairs: usize,
    },
    /// Position error above [`LARGE_ERROR`]`·2r`.
    LargeError {
        /// The position error, in units of `2r`.
        error: f64,
    },
}

impl Failure {
    /// The kind's short name (the legend of the stability chart).
    pub fn kind(&self) -> &'static str {
        match self {
            Failure::Refused(_) => "refused",
            Failure::NoConvergence { .. } => "no convergence",
            Failure::Overlap { .. } => "overlap",
            Failure::WrongClusters { .. } => "wrong clusters",
            Failure::WrongVelocities { .. } => "wrong velocities",
            Failure::NegativeLambda { .. } => "negative λ",
            Failure::NegativePressure { .. } => "negative p",
            Failure::Oleinik { .. } => "Oleinik violated",
            Failure::LargeError { .. } => "position error > 2r/10",
        }
    }

    fn index(&self) -> usize {
        match self {
            Failure::Refused(_) => 0,
            Failure::NoConvergence { .. } => 1,
            Failure::Overlap { .. } => 2,
            Failure::WrongClusters { .. } => 3,
            Failure::WrongVelocities { .. } => 4,
            Failure::NegativeLambda { .. } => 5,
            Failure::NegativePressure { .. } => 6,
            Failure::Oleinik { .. } => 7,
            Failure::LargeError { .. } => 8,
        }
    }
}

impl fmt::Display for Failure {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Failure::Refused(m) => write!(f, "refused ({m})"),
            Failure::NoConvergence { unconverged } => {
                write!(f, "no convergence ({unconverged} solves at the cap)")
            }
            Failure::Overlap { depth } => write!(f, "overlap ({depth:.1e}·2r)"),
            Failure::WrongClusters { missed, spurious } => {
                write!(f, "wrong clusters ({missed} missed, {spurious} spurious)")
            }
            Failure::WrongVelocities { error } => write!(f, "wrong velocities ({error:.1e}·V)"),
            Failure::NegativeLambda { min } => write!(f, "negative λ ({min:.1e})"),
            Failure::NegativePressure { min } => write!(f, "negative p ({min:.1e})"),
            Failure::Oleinik { pairs } => write!(f, "Oleinik violated ({pairs} pairs)"),
            Failure::LargeError { error } => write!(f, "position error {error:.1e}·2r"),
        }
    }
}

/// Colours of the failure kinds (by [`Failure`] order) and of "OK".
const FAILURE_COLORS: [Rgb; 9] = [
    Rgb(0, 0, 0),
    Rgb(148, 103, 189),
    Rgb(214, 39, 40),
    Rgb(255, 127, 14),
    Rgb(227, 119, 194),
    Rgb(140, 86, 75),
    Rgb(188, 189, 34),
    Rgb(23, 190, 207),
    Rgb(127, 127, 127),
];
const FAILURE_NAMES: [&str; 9] = [
    "refused",
    "no convergence",
    "overlap",
    "wrong clusters",
    "wrong velocities",
    "negative λ",
    "negative p",
    "Oleinik violated",
    "position error > 2r/10",
];
const OK_COLOR: Rgb = Rgb(44, 160, 44);

// ---------------------------------------------------------------------------
// Scenes.

/// One scene at one time, exact and rounded.
struct Case {
    name: String,
    description: String,
    exact: InitialData<BigRational>,
    data: InitialData<f64>,
    t: f64,
    tq: BigRational,
    n: usize,
    two_r: f64,
    v: f64,
    /// `Δt` of the time-steppers in the stability section.
    step: f64,
    /// Sweep cap of the one-time iterative projection in the stability
    /// section.
    cap: usize,
    /// Sweep cap of the time-steppers' inner solves in the stability
    /// section.
    step_cap: usize,
}

impl Case {
    fn new(
        name: &str,
        description: &str,
        exact: InitialData<BigRational>,
        t: f64,
    ) -> Result<Case, AtlasError> {
        let scene_err = |message: String| AtlasError::Scene {
            scene: name.to_string(),
            message,
        };
        let data = round_to_f64(&exact).map_err(|e| scene_err(e.to_string()))?;
        let tq = t
            .to_big_rational()
            .ok_or_else(|| scene_err(format!("time {t} is not finite")))?;
        let v = velocity_scale(&data);
        Ok(Case {
            name: name.to_string(),
            description: description.to_string(),
            n: data.n(),
            two_r: data.two_r(),
            v,
            step: t / 1024.0,
            cap: 100_000,
            step_cap: STEP_CAP,
            exact,
            data,
            t,
            tq,
        })
    }
}

fn q(n: i64, d: i64) -> BigRational {
    BigRational::new(BigInt::from(n), BigInt::from(d))
}

fn data_err(name: &str) -> impl Fn(crate::Error) -> AtlasError + '_ {
    move |e| AtlasError::Scene {
        scene: name.to_string(),
        message: e.to_string(),
    }
}

/// Random scene of `N` particles (fixed seed per `N`).
fn random_case(n: usize, t: f64) -> Result<Case, AtlasError> {
    let mut rng = SplitMix64::new(0x5EED_0000 + n as u64);
    let bytes = rng.bytes(32 * n + 64);
    let limits = Limits {
        max_n: n,
        ..Limits::default()
    };
    let exact = initial_data(&bytes, limits);
    Case::new(
        &format!("random-{n}"),
        "generate::initial_data (groups of clusters, chains meeting at one instant)",
        exact,
        t,
    )
}

/// A shipped scene, at its `t_end`.
fn shipped_case(name: &str, text: &str) -> Result<Case, AtlasError> {
    let s = scene::parse(text).map_err(data_err(name))?;
    let t = s
        .t_end
        .as_ref()
        .map(Scalar::to_f64_lossy)
        .ok_or_else(|| AtlasError::Scene {
            scene: name.to_string(),
            message: "no t_end".to_string(),
        })?;
    let description = s.description.clone().unwrap_or_default();
    Case::new(name, &description, s.data, t)
}

/// The speed-vs-accuracy suite.
fn suite(quick: bool) -> Result<Vec<Case>, AtlasError> {
    let sizes: &[usize] = if quick {
        &[10, 100, 1000]
    } else {
        &[10, 100, 1000, 10_000, 100_000]
    };
    let mut out = Vec::new();
    for &n in sizes {
        out.push(random_case(n, 1025.0 / 1024.0)?);
    }
    out.push(shipped_case(
        "appendix-c-two-blocks",
        include_str!("../../scenes/appendix-c-two-blocks.toml"),
    )?);
    out.push(shipped_case(
        "three-cluster-simultaneous",
        include_str!("../../scenes/three-cluster-simultaneous.toml"),
    )?);
    out.push(shipped_case(
        "riemann-compression",
        include_str!("../../scenes/riemann-compression.toml"),
    )?);
    Ok(out)
}

/// Pairs colliding at `1 + (j − m/2)·2⁻⁶⁰`: collision times closer than the
/// resolution of `f64` near `t = 1` (`2⁻⁵²`), measured at `t = 1`.
fn near_simultaneous() -> Result<Case, AtlasError> {
    let name = "near-simultaneous";
    let m: i64 = 64;
    let two_r = q(1, 2);
    let tiny = BigRational::new(BigInt::from(1), BigInt::from(1) << 60usize);
    let mut x = Vec::new();
    let mut u = Vec::new();
    for j in 0..m {
        let tau = q(1, 1) + &(tiny.clone() * q(j - m / 2, 1));
        let left = q(10 * j, 1);
        let right = left.clone() + &two_r + &(q(2, 1) * &tau);
        x.extend([left, right]);
        u.extend([q(1, 1), q(-1, 1)]);
    }
    let exact = InitialData::new(q(1, 4), x, u).map_err(data_err(name))?;
    Case::new(
        name,
        "64 pairs closing at speed 2, pair j colliding at t = 1 + (j − 32)·2^-60 (closer than one ulp of t = 1); measured at t = 1, when exactly 33 pairs have collided",
        exact,
        1.0,
    )
}

/// Chains of 3 or 4 clusters meeting at one instant `T = 1` (velocities in
/// thirds and sevenths, 2r = 1/3: nothing is a dyadic rational), measured
/// at `t = T`.
fn multi_cluster_instant() -> Result<Case, AtlasError> {
    let name = "multi-cluster-instant";
    let chains: i64 = 100;
    let two_r = q(1, 3);
    let mut shifted = Vec::new();
    let mut u = Vec::new();
    for j in 0..chains {
        let k = 3 + (j % 2);
        let w = q(1, 3) + &q(j % 7, 7);
        let meet = q(100 * j, 1);
        for c in 0..k {
            let v = w.clone() * q(k - 1 - 2 * c, 1);
            let size = 1 + ((j + c) % 3);
            let p = meet.clone() - &v; // T = 1
            for _ in 0..size {
                shifted.push(p.clone());
                u.push(v.clone());
            }
        }
    }
    let x = unshift(&shifted, &two_r);
    let exact = InitialData::new(q(1, 6), x, u).map_err(data_err(name))?;
    Case::new(
        name,
        "100 chains of 3 or 4 clusters (sizes 1–3) meeting at the single instant t = 1 (velocities multiples of 1/3 + k/7, 2r = 1/3); measured at t = 1",
        exact,
        1.0,
    )
}

/// A Riemann compression at coordinates `10⁹ + 2(i − 1)/N` with `2r = 1/N`
/// (excess gaps `1/N`), measured at `t = 1/4`.
fn offset_1e9(n: usize) -> Result<Case, AtlasError> {
    let name = "offset-1e9";
    let nn = n as i64;
    let base = q(1_000_000_000, 1);
    let x: Vec<BigRational> = (0..nn).map(|i| base.clone() + &q(2 * i, nn)).collect();
    let u: Vec<BigRational> = (0..nn)
        .map(|i| if i < nn / 2 { q(1, 1) } else { q(-1, 1) })
        .collect();
    let exact = InitialData::new(q(1, 2 * nn), x, u).map_err(data_err(name))?;
    Case::new(
        name,
        &format!("N = {n}, x_i = 1e9 + 2(i−1)/N, 2r = 1/N (gaps 1/N beyond contact), velocities +1 then −1 (a compression); measured at t = 1/4"),
        exact,
        0.25,
    )
}

/// `N` particles with `2r = 1/N`, excess gaps `k·10⁻⁶·2r` (`k = 1 … 9`)
/// and velocities in `[−1, 1]`, measured at `t = 2⁻²⁰` (about one
/// diameter of travel).
fn tiny_gaps(n: usize) -> Result<Case, AtlasError> {
    let name = if n >= 1_000_000 {
        "tiny-gaps-1e6".to_string()
    } else {
        format!("tiny-gaps-{n}")
    };
    let nn = n as i64;
    let mut rng = SplitMix64::new(0x7172_0000 + n as u64);
    let mut shifted = Vec::with_capacity(n);
    let mut u = Vec::with_capacity(n);
    let mut acc = <BigRational as Zero>::zero();
    for i in 0..n {
        if i > 0 {
            let k = 1 + (rng.next_u64() % 9) as i64;
            acc += q(k, nn * 1_000_000);
        }
        shifted.push(acc.clone());
        let v = (rng.next_u64() % 2001) as i64 - 1000;
        u.push(q(v, 1000));
    }
    let two_r = q(1, nn);
    let x = unshift(&shifted, &two_r);
    let exact = InitialData::new(q(1, 2 * nn), x, u).map_err(data_err(&name))?;
    Case::new(
        &name,
        &format!("N = {n}, 2r = 1/N, gaps k·1e-6·2r beyond contact (k = 1…9), velocities k/1000 in [−1, 1]; measured at t = 2^-20 (about one diameter of travel)"),
        exact,
        1.0 / 1_048_576.0,
    )
}

/// A random scene of 20 particles measured at `t = 10⁶`.
fn long_horizon(quick: bool) -> Result<Case, AtlasError> {
    let mut rng = SplitMix64::new(0x10C6);
    let bytes = rng.bytes(1000);
    let exact = initial_data(
        &bytes,
        Limits {
            max_n: 20,
            ..Limits::default()
        },
    );
    let mut case = Case::new(
        "long-horizon",
        "a random scene of 20 particles (generate::initial_data) measured at t = 1e6",
        exact,
        1e6,
    )?;
    case.step = if quick { 4.0 } else { 0.25 };
    Ok(case)
}

/// `N = 1000` particles at unit spacing (2r = 1/2) with velocities
/// `±10^e`, `e ∈ {−6, …, 6}`: twelve orders of magnitude, measured at `t = 1`.
fn velocity_decades() -> Result<Case, AtlasError> {
    let name = "velocities-12-decades";
    let mut rng = SplitMix64::new(0x1E12);
    let n = 1000;
    let mut x = Vec::with_capacity(n);
    let mut u = Vec::with_capacity(n);
    for i in 0..n {
        x.push(q(i as i64, 1));
        let e = (rng.next_u64() % 13) as i32 - 6;
        let sign = if rng.next_u64() % 2 == 0 { 1 } else { -1 };
        let mag = if e >= 0 {
            q(sign * 10i64.pow(e as u32), 1)
        } else {
            q(sign, 10i64.pow((-e) as u32))
        };
        u.push(mag);
    }
    let exact = InitialData::new(q(1, 4), x, u).map_err(data_err(name))?;
    Case::new(
        name,
        "N = 1000 at unit spacing, 2r = 1/2, velocities ±10^e with e uniform in −6…6 (twelve orders of magnitude); measured at t = 1",
        exact,
        1.0,
    )
}

/// The stability scenes.
fn stability_suite(quick: bool) -> Result<Vec<Case>, AtlasError> {
    let mut out = vec![
        near_simultaneous()?,
        multi_cluster_instant()?,
        offset_1e9(if quick { 1000 } else { 10_000 })?,
        tiny_gaps(if quick { 10_000 } else { 1_000_000 })?,
        long_horizon(quick)?,
        velocity_decades()?,
    ];
    // Time-steppers: a power of two of steps, at most `max_steps` and about
    // `steps_budget` particle-steps (at least 4 steps); inner sweep caps of
    // about `sweeps_budget / N` (between 100 and STABILITY_STEP_CAP).
    let (max_steps, steps_budget, sweeps_budget, budget) = if quick {
        (256usize, 256_000usize, 2_500_000usize, 200_000_000usize)
    } else {
        (1024, 4_000_000, 100_000_000, 2_000_000_000)
    };
    for case in &mut out {
        if case.name != "long-horizon" {
            let mut steps = 4usize;
            while steps * 2 <= max_steps && steps * 2 * case.n <= steps_budget {
                steps *= 2;
            }
            case.step = case.t / steps as f64;
        }
        case.step_cap = (sweeps_budget / case.n.max(1)).clamp(100, STABILITY_STEP_CAP);
        // A work budget of pair updates for the one-time iterative
        // projection (full sweeps over N − 1 pairs).
        case.cap = (budget / case.n.max(1)).clamp(1000, 1_000_000);
    }
    Ok(out)
}

// ---------------------------------------------------------------------------
// Jobs.

enum Engine {
    ExactPava,
    ExactEvents,
    Float(Box<dyn Solver>),
}

struct Job {
    method: &'static str,
    parameter: String,
    sweep: &'static str,
    dt: Option<f64>,
    tol: Option<f64>,
    cap: Option<usize>,
    engine: Engine,
}

impl Job {
    fn exact(pava: bool) -> Job {
        Job {
            method: if pava { "exact-pava" } else { "exact-events" },
            parameter: String::new(),
            sweep: "",
            dt: None,
            tol: None,
            cap: None,
            engine: if pava {
                Engine::ExactPava
            } else {
                Engine::ExactEvents
            },
        }
    }

    fn float(
        solver: Box<dyn Solver>,
        sweep: &'static str,
        dt: Option<f64>,
        tol: Option<f64>,
        cap: Option<usize>,
    ) -> Job {
        Job {
            method: solver.method(),
            parameter: solver.parameters(),
            sweep,
            dt,
            tol,
            cap,
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
const STEP_CAP: usize = 100_000;
/// The step of the tolerance and cap sweeps, and of `cost-vs-n`.
const SWEEP_DT: f64 = 1.0 / 256.0;
/// The contact tolerance of `events-f64` shown in `cost-vs-n`.
const EVENTS_TOL: f64 = 1e-12;
/// The tolerance of `iterative-projection` shown in `cost-vs-n`.
const ITERATIVE_TOL: f64 = 1e-9;

/// The parameter grid of one suite scene.
fn jobs(case: &Case, quick: bool) -> Vec<Job> {
    let n = case.n as f64;
    let budget: f64 = if quick { 2e7 } else { 5e8 };
    let mut out = vec![Job::exact(true), Job::exact(false)];
    out.push(Job::float(Box::new(PavaF64), "", None, None, None));
    let event_tols: &[f64] = if quick {
        &[1e-6, 1e-12, 1e-16]
    } else {
        &[1e-4, 1e-6, 1e-8, 1e-10, 1e-12, 1e-14, 1e-16]
    };
    for &tol in event_tols {
        out.push(Job::float(
            Box::new(EventsF64 { tol }),
            "tol",
            None,
            Some(tol),
            None,
        ));
    }
    let ks: &[i32] = if quick {
        &[4, 6, 8]
    } else {
        &[2, 4, 6, 8, 10, 12, 14]
    };
    let step_tols: &[f64] = if quick {
        &[1e-2, 1e-5, 1e-8]
    } else {
        &[1e-1, 1e-3, 1e-6, 1e-9]
    };
    let step_caps: &[usize] = if quick {
        &[1, 10, 100]
    } else {
        &[1, 4, 16, 64, 256]
    };
    let steps = |dt: f64| (case.t / dt).ceil().max(1.0);
    type Make = fn(f64, f64, usize) -> Box<dyn Solver>;
    for make in [moreau_jean as Make, catching_up as Make] {
        for &k in ks {
            let dt = 2f64.powi(-k);
            if n * steps(dt) <= budget {
                out.push(Job::float(
                    make(dt, STEP_TOL, STEP_CAP),
                    "dt",
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
                    "tol",
                    Some(SWEEP_DT),
                    Some(tol),
                    Some(STEP_CAP),
                ));
            }
            for &cap in step_caps {
                out.push(Job::float(
                    make(SWEEP_DT, STEP_TOL, cap),
                    "cap",
                    Some(SWEEP_DT),
                    Some(STEP_TOL),
                    Some(cap),
                ));
            }
        }
    }
    let sweeps: &[usize] = if quick {
        &[1, 16, 256]
    } else {
        &[1, 4, 16, 64, 256, 1024, 4096, 16384]
    };
    for &cap in sweeps {
        if n * cap as f64 <= budget {
            out.push(Job::float(
                Box::new(IterativeProjection {
                    tol: 1e-15,
                    max_iterations: cap,
                }),
                "cap",
                None,
                Some(1e-15),
                Some(cap),
            ));
        }
    }
    let iter_tols: &[f64] = if quick {
        &[1e-3, 1e-6, 1e-9]
    } else {
        &[1e-2, 1e-4, 1e-6, 1e-9, 1e-12]
    };
    let cap = ((budget * 4.0 / n) as usize).clamp(1000, 1_000_000);
    for &tol in iter_tols {
        out.push(Job::float(
            Box::new(IterativeProjection {
                tol,
                max_iterations: cap,
            }),
            "tol",
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
fn stability_jobs(case: &Case) -> Vec<Job> {
    let dt = case.step;
    let cap = case.cap;
    let step_cap = case.step_cap;
    vec![
        Job::float(Box::new(PavaF64), "", None, None, None),
        Job::float(
            Box::new(EventsF64::default()),
            "",
            None,
            Some(EventsF64::default().tol),
            None,
        ),
        Job::float(
            moreau_jean(dt, STEP_TOL, step_cap),
            "",
            Some(dt),
            Some(STEP_TOL),
            Some(step_cap),
        ),
        Job::float(
            catching_up(dt, STEP_TOL, step_cap),
            "",
            Some(dt),
            Some(STEP_TOL),
            Some(step_cap),
        ),
        Job::float(
            Box::new(IterativeProjection {
                tol: 1e-12,
                max_iterations: cap,
            }),
            "",
            None,
            Some(1e-12),
            Some(cap),
        ),
    ]
}

// ---------------------------------------------------------------------------
// Running and measuring.

/// How a row ended.
#[derive(Debug, Clone, PartialEq)]
enum Status {
    Ok,
    NoConvergence,
    Refused(String),
}

impl fmt::Display for Status {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Status::Ok => write!(f, "ok"),
            Status::NoConvergence => write!(f, "no-convergence"),
            Status::Refused(m) => write!(f, "refused: {m}"),
        }
    }
}

/// One measured (scene, method, parameter).
#[derive(Debug, Clone)]
struct Row {
    scene: String,
    n: usize,
    t: f64,
    two_r: f64,
    v: f64,
    method: &'static str,
    parameter: String,
    sweep: &'static str,
    dt: Option<f64>,
    tol: Option<f64>,
    cap: Option<usize>,
    status: Status,
    wall: f64,
    repeats: usize,
    errors: Option<ErrorsF64>,
    work: Option<Work>,
    converged: Option<bool>,
    residual: Option<f64>,
}

/// Runs `f` once, then again until `min` has passed in total (at most
/// `max_reps` runs); returns the first result, the mean time per run and
/// the number of runs.
fn timed<T>(min: Duration, max_reps: usize, mut f: impl FnMut() -> T) -> (T, f64, usize) {
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
struct ExactStates {
    pava: State<BigRational>,
    events: State<BigRational>,
    /// The smallest pressure jump of the collisions up to `t`.
    min_jump: Option<BigRational>,
}

fn exact_states(case: &Case) -> Result<ExactStates, AtlasError> {
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

fn max_diff(a: &[BigRational], b: &[BigRational]) -> BigRational {
    a.iter()
        .zip(b)
        .map(|(p, q)| (p - q).abs())
        .max()
        .unwrap_or_else(<BigRational as Zero>::zero)
}

fn contact_flags(state: &State<BigRational>, pairs: usize) -> Vec<bool> {
    let mut flags = vec![false; pairs];
    for c in &state.clusters {
        for f in &mut flags[c.first..c.end() - 1] {
            *f = true;
        }
    }
    flags
}

/// The exact errors of one exact engine's state `own` against the other's
/// `other`, and its own constraint, sign and Oleinik values, all exact.
fn exact_errors(
    case: &Case,
    own: &State<BigRational>,
    other: &State<BigRational>,
    min_jump: Option<BigRational>,
) -> Errors {
    let n = case.exact.n();
    let pairs = n.saturating_sub(1);
    let (a, b) = (contact_flags(own, pairs), contact_flags(other, pairs));
    let two_r = case.exact.two_r();
    let x = &own.positions;
    let u = &own.velocities;
    let oleinik = if case.tq.is_positive() {
        Some(
            (1..n)
                .filter(|&i| {
                    let dx = x[i].clone() - &x[i - 1];
                    let du = u[i].clone() - &u[i - 1];
                    !dx.is_positive() || case.tq.clone() * du >= dx
                })
                .count(),
        )
    } else {
        None
    };
    Errors {
        position: max_diff(x, &other.positions),
        velocity: Some(max_diff(u, &other.velocities)),
        lambda: (pairs > 0).then(|| max_diff(&own.multipliers, &other.multipliers)),
        kkt: None,
        missed_contacts: (0..pairs).filter(|&j| b[j] && !a[j]).count(),
        spurious_contacts: (0..pairs).filter(|&j| a[j] && !b[j]).count(),
        min_gap: (0..pairs).map(|j| x[j + 1].clone() - &x[j] - &two_r).min(),
        min_lambda: own.multipliers.iter().min().cloned(),
        min_pressure_jump: min_jump,
        oleinik_violations: oleinik,
    }
}

/// Runs (and times) one job. The exact engines' rows are complete; a
/// floating-point solver's output is returned for [`measure_all`].
fn solve_job(
    case: &Case,
    exact: Option<&ExactStates>,
    job: &Job,
    min_time: Duration,
) -> (Row, Option<Output>) {
    let mut row = Row {
        scene: case.name.clone(),
        n: case.n,
        t: case.t,
        two_r: case.two_r,
        v: case.v,
        method: job.method,
        parameter: job.parameter.clone(),
        sweep: job.sweep,
        dt: job.dt,
        tol: job.tol,
        cap: job.cap,
        status: Status::Ok,
        wall: 0.0,
        repeats: 0,
        errors: None,
        work: None,
        converged: None,
        residual: None,
    };
    match &job.engine {
        Engine::ExactPava => {
            let (_, wall, reps) = timed(min_time, 1000, || state_at(&case.exact, &case.tq));
            row.wall = wall;
            row.repeats = reps;
            row.errors = exact.map(|x| exact_errors(case, &x.pava, &x.events, None).to_f64());
        }
        Engine::ExactEvents => {
            let (_, wall, reps) = timed(min_time, 1000, || {
                Trajectory::new(case.exact.clone()).at(&case.tq)
            });
            row.wall = wall;
            row.repeats = reps;
            row.errors =
                exact.map(|x| exact_errors(case, &x.events, &x.pava, x.min_jump.clone()).to_f64());
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
                        match measure(&out, &case.exact, &case.tq) {
                            Ok(e) => row.errors = Some(e.to_f64()),
                            Err(e) => row.status = Status::Refused(format!("measure: {e}")),
                        }
                    }
                    bar.inc(1);
                }
            });
        }
    });
    slots.into_iter().map(|(row, _)| row).collect()
}

/// Solves every job of one scene (timed, one at a time), then measures.
fn run_case(
    case: &Case,
    jobs: &[Job],
    with_exact: bool,
    min_time: Duration,
    bar: &ProgressBar,
) -> Result<Vec<Row>, AtlasError> {
    let exact = if with_exact {
        bar.set_message(format!("{}: exact reference", case.name));
        Some(exact_states(case)?)
    } else {
        None
    };
    let mut solved = Vec::with_capacity(jobs.len());
    for job in jobs {
        bar.set_message(format!("{}: {} {}", case.name, job.method, job.parameter));
        solved.push(solve_job(case, exact.as_ref(), job, min_time));
        bar.inc(1);
    }
    bar.set_message(format!("{}: measuring exactly", case.name));
    Ok(measure_all(case, solved, bar))
}

/// Threads used by the exact measurement.
const MEASURE_THREADS: usize = 4;

/// The failures of one stability row.
fn classify(row: &Row) -> Vec<Failure> {
    let mut out = Vec::new();
    if let Status::Refused(m) = &row.status {
        out.push(Failure::Refused(m.clone()));
        return out;
    }
    if row.converged == Some(false) {
        out.push(Failure::NoConvergence {
            unconverged: row.work.map_or(0, |w| w.unconverged),
        });
    }
    let Some(e) = row.errors else {
        return out;
    };
    let v = row.v.max(f64::MIN_POSITIVE);
    if let Some(g) = e.min_gap {
        if g < -OVERLAP_TOLERANCE * row.two_r {
            out.push(Failure::Overlap {
                depth: -g / row.two_r,
            });
        }
    }
    if e.cluster_mismatch() > 0 {
        out.push(Failure::WrongClusters {
            missed: e.missed_contacts,
            spurious: e.spurious_contacts,
        });
    }
    if let Some(ve) = e.velocity {
        if ve > VELOCITY_TOLERANCE * v {
            out.push(Failure::WrongVelocities { error: ve / v });
        }
    }
    if let Some(m) = e.min_lambda {
        if m < -SIGN_TOLERANCE * v {
            out.push(Failure::NegativeLambda { min: m });
        }
    }
    if let Some(m) = e.min_pressure_jump {
        if m < -SIGN_TOLERANCE * v {
            out.push(Failure::NegativePressure { min: m });
        }
    }
    if let Some(k) = e.oleinik_violations {
        if k > 0 {
            out.push(Failure::Oleinik { pairs: k });
        }
    }
    if e.position > LARGE_ERROR * row.two_r {
        out.push(Failure::LargeError {
            error: e.position / row.two_r,
        });
    }
    out
}

// ---------------------------------------------------------------------------
// CSV.

/// A time or step for text: plain decimals in `[10⁻³, 10⁷)`, else
/// scientific.
fn short(v: f64) -> String {
    if v == 0.0 || (1e-3..1e7).contains(&v.abs()) {
        format!("{v}")
    } else {
        format!("{v:e}")
    }
}

fn num(v: f64) -> String {
    if v == 0.0 {
        "0".to_string()
    } else {
        format!("{v:e}")
    }
}

fn opt<T>(v: Option<T>, f: impl Fn(T) -> String) -> String {
    v.map(f).unwrap_or_default()
}

fn csv_field(s: &str) -> String {
    if s.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.to_string()
    }
}

fn csv_row(row: &Row) -> Vec<String> {
    let e = row.errors;
    let int = |k: usize| k.to_string();
    vec![
        row.scene.clone(),
        row.n.to_string(),
        num(row.t),
        row.method.to_string(),
        row.parameter.clone(),
        row.sweep.to_string(),
        opt(row.dt, num),
        opt(row.tol, num),
        opt(row.cap, int),
        row.status.to_string(),
        num(row.wall),
        row.repeats.to_string(),
        opt(e.map(|e| e.position), num),
        opt(e.and_then(|e| e.velocity), num),
        opt(e.and_then(|e| e.lambda), num),
        opt(e.and_then(|e| e.kkt), num),
        opt(e.map(|e| e.missed_contacts), int),
        opt(e.map(|e| e.spurious_contacts), int),
        opt(e.map(|e| e.cluster_mismatch()), int),
        opt(e.and_then(|e| e.min_gap), num),
        opt(e.and_then(|e| e.min_gap).map(|g| g / row.two_r), num),
        opt(e.and_then(|e| e.min_lambda), num),
        opt(e.and_then(|e| e.min_pressure_jump), num),
        opt(e.and_then(|e| e.oleinik_violations), int),
        opt(row.work.map(|w| w.steps), int),
        opt(row.work.map(|w| w.iterations), int),
        opt(row.work.map(|w| w.unconverged), int),
        opt(row.converged, |c| c.to_string()),
        opt(row.residual, num),
    ]
}

fn write_csv(
    path: &Path,
    rows: &[Row],
    failures: Option<&[Vec<Failure>]>,
) -> Result<(), AtlasError> {
    let mut text = CSV_COLUMNS.join(",");
    if failures.is_some() {
        text.push_str(",failures");
    }
    text.push('\n');
    for (i, row) in rows.iter().enumerate() {
        let mut fields = csv_row(row);
        if let Some(f) = failures {
            let cell = f.get(i).map_or(String::new(), |fs| {
                if fs.is_empty() {
                    "OK".to_string()
                } else {
                    fs.iter()
                        .map(ToString::to_string)
                        .collect::<Vec<_>>()
                        .join("; ")
                }
            });
            fields.push(cell);
        }
        let line: Vec<String> = fields.iter().map(|s| csv_field(s)).collect();
        text.push_str(&line.join(","));
        text.push('\n');
    }
    write_whole(path, text.as_bytes()).map_err(AtlasError::from)
}

// ---------------------------------------------------------------------------
// Charts.

fn style(method: &str) -> (Rgb, Marker) {
    match method {
        "exact-pava" => (BLACK_RGB, Marker::Square),
        "exact-events" => (Rgb(90, 90, 90), Marker::Ring),
        "pava-f64" => (palette(0), Marker::Circle),
        "events-f64" => (palette(1), Marker::Triangle),
        "moreau-jean" => (palette(2), Marker::Circle),
        "catching-up" => (palette(3), Marker::Square),
        "iterative-projection" => (palette(4), Marker::Cross),
        _ => (palette(7), Marker::Ring),
    }
}

/// The floor at which errors of exactly 0 are drawn on a log axis: the
/// power of ten a decade below the smallest positive value (`1e-20` when
/// there is none).
fn floor_for(values: impl Iterator<Item = f64>) -> f64 {
    let min = values
        .filter(|v| v.is_finite() && *v > 0.0)
        .fold(f64::INFINITY, f64::min);
    if min.is_finite() {
        10f64.powf(min.log10().floor() - 1.0)
    } else {
        1e-20
    }
}

fn all_methods() -> impl Iterator<Item = &'static str> {
    EXACT_METHODS.iter().chain(METHODS.iter()).copied()
}

fn pareto_chart(case: &str, rows: &[&Row], velocity: bool) -> Option<Chart> {
    let err = |r: &Row| -> Option<f64> {
        let e = r.errors?;
        if velocity {
            e.velocity
        } else {
            Some(e.position)
        }
    };
    let usable: Vec<&Row> = rows
        .iter()
        .copied()
        .filter(|r| err(r).is_some() && r.wall > 0.0)
        .collect();
    if usable.is_empty() {
        return None;
    }
    let floor = floor_for(usable.iter().filter_map(|r| err(r)));
    let first = usable[0];
    let what = if velocity {
        "max velocity error |u − u(t)|"
    } else {
        "max position error |x − x(t)|"
    };
    let mut chart = Chart::new(
        format!(
            "{case}, N = {}, t = {}: {} vs wall time (error 0 drawn at {floor:.0e})",
            first.n,
            short(first.t),
            if velocity {
                "velocity error"
            } else {
                "position error"
            }
        ),
        Axis::log("wall time per solve [s]"),
        Axis::log(what),
    );
    let mut points_all = Vec::new();
    for method in all_methods() {
        let pts: Vec<(f64, f64)> = usable
            .iter()
            .filter(|r| r.method == method)
            .filter_map(|r| err(r).map(|e| (r.wall, if e > 0.0 { e } else { floor })))
            .collect();
        if pts.is_empty() {
            continue;
        }
        points_all.extend(pts.iter().copied());
        let (color, marker) = style(method);
        let label = if EXACT_METHODS.contains(&method) {
            format!("{method} (error 0, drawn at {floor:.0e})")
        } else {
            method.to_string()
        };
        let mut s = Series::scatter(label, color, marker, pts);
        s.marker_size = 5;
        chart.series.push(s);
    }
    points_all.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
    // The smallest error reachable within a given time: a staircase
    // through the non-dominated points.
    let mut front: Vec<(f64, f64)> = Vec::new();
    let mut best = f64::INFINITY;
    for p in points_all {
        if p.1 < best {
            if best.is_finite() {
                front.push((p.0, best));
            }
            best = p.1;
            front.push(p);
        }
    }
    let mut s = Series::line("Pareto front", Rgb(60, 60, 60), front);
    s.width = 1;
    chart.series.insert(0, s);
    Some(chart)
}

fn dt_chart(case: &str, rows: &[&Row]) -> Option<Chart> {
    let steppers = ["moreau-jean", "catching-up"];
    let sel: Vec<&Row> = rows
        .iter()
        .copied()
        .filter(|r| steppers.contains(&r.method) && r.sweep == "dt" && r.errors.is_some())
        .collect();
    if sel.is_empty() {
        return None;
    }
    let floor = floor_for(sel.iter().flat_map(|r| {
        let e = r.errors.unwrap_or_else(zero_errors);
        [e.position, e.velocity.unwrap_or(0.0)]
    }));
    let first = sel[0];
    let mut chart = Chart::new(
        format!(
            "{case}, N = {}, t = {}: time-steppers' error vs Δt (error 0 drawn at {floor:.0e})",
            first.n,
            short(first.t)
        ),
        Axis::log("time step Δt"),
        Axis::log("max error"),
    );
    for (i, m) in steppers.iter().enumerate() {
        for velocity in [false, true] {
            let mut pts: Vec<(f64, f64)> = sel
                .iter()
                .filter(|r| r.method == *m)
                .filter_map(|r| {
                    let e = r.errors?;
                    let v = if velocity { e.velocity? } else { e.position };
                    Some((r.dt?, if v > 0.0 { v } else { floor }))
                })
                .collect();
            if pts.is_empty() {
                continue;
            }
            pts.sort_by(|a, b| a.0.total_cmp(&b.0));
            let color = palette(2 + i);
            let label = format!("{m}: {}", if velocity { "velocity" } else { "position" });
            let marker = if velocity {
                Marker::Ring
            } else {
                Marker::Circle
            };
            chart
                .series
                .push(Series::line(label, color, pts).with_marker(marker));
        }
    }
    Some(chart)
}

fn zero_errors() -> ErrorsF64 {
    ErrorsF64 {
        position: 0.0,
        velocity: None,
        lambda: None,
        kkt: None,
        missed_contacts: 0,
        spurious_contacts: 0,
        min_gap: None,
        min_lambda: None,
        min_pressure_jump: None,
        oleinik_violations: None,
    }
}

/// The representative row of each method in `cost-vs-n`, and its legend.
fn representative(r: &Row) -> Option<String> {
    match r.method {
        "exact-pava" | "exact-events" | "pava-f64" => Some(r.method.to_string()),
        "events-f64" if r.tol == Some(EVENTS_TOL) => {
            Some(format!("events-f64 (tol {EVENTS_TOL:e})"))
        }
        "moreau-jean" | "catching-up" if r.sweep == "dt" && r.dt == Some(SWEEP_DT) => {
            Some(format!("{} (Δt = 2^-8)", r.method))
        }
        "iterative-projection" if r.sweep == "tol" && r.tol == Some(ITERATIVE_TOL) => {
            Some(format!("iterative-projection (tol {ITERATIVE_TOL:e})"))
        }
        _ => None,
    }
}

fn cost_chart(rows: &[Row]) -> Chart {
    let mut chart = Chart::new(
        "cost vs N on the random scenes (t = 1025/1024): wall time per solve",
        Axis::log("number of particles N"),
        Axis::log("wall time per solve [s]"),
    );
    for method in all_methods() {
        let mut label = None;
        let mut pts = Vec::new();
        for r in rows
            .iter()
            .filter(|r| r.scene.starts_with("random-") && r.method == method)
        {
            if let Some(l) = representative(r) {
                if !matches!(r.status, Status::Refused(_)) {
                    label = Some(l);
                    pts.push((r.n as f64, r.wall));
                }
            }
        }
        if let Some(label) = label {
            pts.sort_by(|a, b| a.0.total_cmp(&b.0));
            let (color, marker) = style(method);
            chart
                .series
                .push(Series::line(label, color, pts).with_marker(marker));
        }
    }
    chart
}

fn stability_grid(cases: &[Case], rows: &[Row], failures: &[Vec<Failure>]) -> Grid {
    let mut cells = Vec::new();
    for (i, case) in cases.iter().enumerate() {
        for (j, method) in METHODS.iter().enumerate() {
            let found = rows
                .iter()
                .zip(failures)
                .find(|(r, _)| r.scene == case.name && r.method == *method);
            let Some((_, fs)) = found else {
                continue;
            };
            let colors = if fs.is_empty() {
                vec![OK_COLOR]
            } else {
                fs.iter().map(|f| FAILURE_COLORS[f.index()]).collect()
            };
            cells.push(Cell {
                row: i,
                column: j,
                colors,
                text: None,
            });
        }
    }
    let mut legend = vec![("OK".to_string(), OK_COLOR)];
    legend.extend(
        FAILURE_NAMES
            .iter()
            .zip(FAILURE_COLORS)
            .map(|(n, c)| (n.to_string(), c)),
    );
    Grid {
        title: "Where methods fail: one square per failure kind (stability scenes)".to_string(),
        rows: cases.iter().map(|c| c.name.clone()).collect(),
        columns: METHODS.iter().map(|m| m.to_string()).collect(),
        cells,
        legend,
    }
}

fn stability_markdown(cases: &[Case], rows: &[Row], failures: &[Vec<Failure>]) -> String {
    let mut md = String::new();
    md.push_str("# Where methods fail\n\n");
    md.push_str(
        "Each floating-point method once per scene, with its default tolerances; the \
         time-steppers with the step Δt and every iterative solve with the sweep cap given \
         below. Errors are measured exactly against the exact solution of the rational scene \
         (`reference::measure`); `stability.csv` has every number.\n\n",
    );
    md.push_str("| scene |");
    for m in METHODS {
        md.push_str(&format!(" {m} |"));
    }
    md.push_str("\n|---|");
    for _ in METHODS {
        md.push_str("---|");
    }
    md.push('\n');
    for case in cases {
        md.push_str(&format!("| {} |", case.name));
        for m in METHODS {
            let found = rows
                .iter()
                .zip(failures)
                .find(|(r, _)| r.scene == case.name && r.method == m);
            let cell = match found {
                None => "—".to_string(),
                Some((_, fs)) if fs.is_empty() => "OK".to_string(),
                Some((_, fs)) => fs
                    .iter()
                    .map(|f| f.to_string().replace('|', "\\|"))
                    .collect::<Vec<_>>()
                    .join("; "),
            };
            md.push_str(&format!(" {cell} |"));
        }
        md.push('\n');
    }
    md.push_str("\n## Scenes\n\n");
    for case in cases {
        md.push_str(&format!(
            "- **{}** (N = {}, t = {}): {}. Time-steppers: Δt = {} ({} steps), at most {} sweeps per inner solve; iterative projection: at most {} sweeps.\n",
            case.name,
            case.n,
            short(case.t),
            case.description,
            short(case.step),
            (case.t / case.step).ceil(),
            case.step_cap,
            case.cap
        ));
    }
    md.push_str(&format!(
        "\n## Failure kinds\n\n\
         - **refused**: the solver returned an error (too many steps, NaN, …).\n\
         - **no convergence**: an inner iterative solve stopped at its sweep cap (the result is still measured).\n\
         - **overlap**: `min x_{{i+1}} − x_i − 2r < −{OVERLAP_TOLERANCE:e}·2r` (`df:KN`); the depth is given in units of 2r.\n\
         - **wrong clusters**: the method's contact set at t differs from the exact Ω(x(t)) (`df:Omega-micro`): collisions missed or spurious.\n\
         - **wrong velocities**: max |u − u(t)| > {VELOCITY_TOLERANCE:e}·V (V = max |u⁰|): a collision missed, spurious or not resolved in time changes the post-collision velocity.\n\
         - **negative λ / negative p**: a multiplier or a pressure jump below −{SIGN_TOLERANCE:e}·V (`eq:dyn-micro`, `prop:micro-pressure`).\n\
         - **Oleinik violated**: pairs with t(u_i − u_{{i−1}}) ≥ x_i − x_{{i−1}} (`prop:Oleinik`), counted exactly.\n\
         - **position error > 2r/10**: max |x − x(t)| above a tenth of a particle diameter.\n"
    ));
    md
}

// ---------------------------------------------------------------------------
// The driver.

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
/// written (CSV and Markdown files first, then the charts). With `progress`
/// a progress bar is drawn on standard error when it is a terminal.
///
/// The PNG files are skipped (SVG only) when no TrueType font is found on
/// the machine ([`crate::report::plot::png_support`]).
pub fn run(opts: &AtlasOptions, progress: bool) -> Result<Vec<PathBuf>, AtlasError> {
    let out_dir = &opts.out;
    fs::create_dir_all(out_dir).map_err(|e| AtlasError::Io {
        path: out_dir.clone(),
        message: e.to_string(),
    })?;
    let bar = if progress && std::io::stderr().is_terminal() {
        let bar = ProgressBar::new(0);
        let style = ProgressStyle::with_template("atlas {bar:30} {pos}/{len} [{elapsed}] {msg}")
            .unwrap_or_else(|_| ProgressStyle::default_bar());
        bar.set_style(style);
        bar
    } else {
        ProgressBar::hidden()
    };
    bar.set_message("building scenes");
    let suite = suite(opts.quick)?;
    let stability = stability_suite(opts.quick)?;
    let main_jobs: Vec<Vec<Job>> = suite.iter().map(|c| jobs(c, opts.quick)).collect();
    let stab_jobs: Vec<Vec<Job>> = stability.iter().map(stability_jobs).collect();
    // Each job counts twice: solved, then measured.
    let total: usize = main_jobs.iter().chain(&stab_jobs).map(Vec::len).sum();
    bar.set_length(2 * total as u64);
    let min_time = Duration::from_millis(if opts.quick { 2 } else { 20 });

    let mut rows = Vec::new();
    for (case, jobs) in suite.iter().zip(&main_jobs) {
        rows.extend(run_case(case, jobs, true, min_time, &bar)?);
    }
    let mut stab_rows = Vec::new();
    for (case, jobs) in stability.iter().zip(&stab_jobs) {
        stab_rows.extend(run_case(case, jobs, false, min_time, &bar)?);
    }
    bar.set_message("writing files");
    let failures: Vec<Vec<Failure>> = stab_rows.iter().map(classify).collect();

    let mut written = Vec::new();
    let atlas_csv = out_dir.join("atlas.csv");
    write_csv(&atlas_csv, &rows, None)?;
    written.push(atlas_csv);
    let stab_csv = out_dir.join("stability.csv");
    write_csv(&stab_csv, &stab_rows, Some(&failures))?;
    written.push(stab_csv);
    let stab_md = out_dir.join("stability.md");
    let mut md = stability_markdown(&stability, &stab_rows, &failures);
    if let PngSupport::Skipped(why) = png_support() {
        md.push_str(&format!("\nCharts: {why}.\n"));
    }
    write_whole(&stab_md, md.as_bytes())?;
    written.push(stab_md);

    for case in &suite {
        let case_rows: Vec<&Row> = rows.iter().filter(|r| r.scene == case.name).collect();
        let stem = file_stem(&case.name);
        for velocity in [false, true] {
            if let Some(chart) = pareto_chart(&case.name, &case_rows, velocity) {
                let kind = if velocity { "velocity" } else { "position" };
                let w = write_chart(&chart, out_dir, &format!("pareto-{kind}-{stem}"))?;
                written.extend(w.paths());
            }
        }
        if let Some(chart) = dt_chart(&case.name, &case_rows) {
            let w = write_chart(&chart, out_dir, &format!("error-vs-dt-{stem}"))?;
            written.extend(w.paths());
        }
    }
    let w = write_chart(&cost_chart(&rows), out_dir, "cost-vs-n")?;
    written.extend(w.paths());
    let w = write_grid(
        &stability_grid(&stability, &stab_rows, &failures),
        out_dir,
        "stability",
    )?;
    written.extend(w.paths());
    bar.finish_and_clear();
    Ok(written)
}
