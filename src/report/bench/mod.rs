//! `sticky bench`: PAVA at one time `t` on random scenes, every method timed
//! in the same run on fresh inputs (a new scene for each repetition, so that
//! the branch predictor cannot learn one input), in ns per particle, with
//! the ratio to our own f64 PAVA; the peers (scipy, scikit-learn) through
//! `scripts/peers.py` on identical data.
//!
//! Methods:
//! * `f64` — [`crate::projection::isotonic`] on `f64` (the generic code,
//!   one value per particle);
//! * `exact_int` — [`crate::fast::kernel::blocks_at`] on data that fit `i128`: the
//!   exact partition and integer block sums, means reduced on demand;
//! * `exact_int_lowest` — the same, then every block mean reduced to a
//!   `BigRational` in lowest terms (what a caller that wants all of them
//!   pays);
//! * `exact_bigint` — the same kernel on data with 30-digit decimals, which
//!   need the 256-bit loop; `exact_bigint_100` on 100-digit decimals (the
//!   512-bit loop);
//! * `adaptive`, `adaptive_bigdata` — [`crate::fast::adaptive::adaptive_blocks_at`]
//!   on the `exact_int` scene and on the 100-digit one (the path taken is in
//!   the note);
//! * `bigrational_naive` — the generic PAVA on `BigRational` (measured on
//!   N/10 particles and reported per particle, saying so);
//! * `events` — the full exact event-driven trajectory on the integer engine
//!   ([`crate::fast::merge::IntegerTrajectory::new`], from the
//!   `BigRational` data: the scaling to common denominators included);
//!   `events_columns` the same history from the scaled `i64` columns, the
//!   path `sticky events` takes on a CSV, NPY or TOML file; `events_lowest` the
//!   conversion of that history to a `Trajectory<BigRational>`;
//!   `events_generic` the generic engine on `BigRational`
//!   ([`crate::trajectory::Trajectory::new`], on N/10 particles).
//!
//! Timings are whole calls measured with `std::time::Instant` (median of the
//! repetitions); they are reports, never test assertions. Memory is the
//! growth of the resident set during the call (peak minus before).
//!
//! [`e2e`]: the end-to-end rows (`sticky bench --e2e`), whole `sticky` and
//! scipy processes from file to answer to file. [`history`]: the
//! `events_columns` and `events` rows against the `f64` row alone, timed
//! back to back on one scene (`sticky bench --history`).

pub mod e2e;
pub mod history;
mod study;

pub use study::{
    read_scaling_csv, scaling, scaling_charts, slopes, ScalingOptions, ScalingRow, REGIMES,
};

use std::path::Path;
use std::process::Command;
use std::time::Instant;

use num_bigint::BigInt;
use num_rational::BigRational;

use crate::fast::adaptive::{adaptive_blocks_at, Path as Path_};
use crate::fast::kernel::{blocks_at, IntegerData};
use crate::fast::merge::IntegerTrajectory;
use crate::generate::{initial_data, Limits, SplitMix64};
use crate::initial::InitialData;
use crate::progress::{Progress, Silent};
use crate::projection::{isotonic, pava_blocks, shifted_free_flight};
use crate::scalar::Scalar;
use crate::trajectory::Trajectory;

/// What a benchmark measures of each method.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Metric {
    /// Warm timings (the allocator keeps pages, one untimed warm-up).
    Time,
    /// Peak memory (cold allocator, no warm-up: [`Memory::Cold`]).
    PeakMemory,
}

/// Whether the Python peers run beside our methods.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Peers {
    /// Run them (skipped with a message when Python is absent).
    Run,
    /// Leave them out (`--no-peers`).
    Skip,
}

/// Whether the full event-driven trajectory is timed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Events {
    /// Time it, with the event rows.
    Time,
    /// Leave it out (`--quick`).
    Skip,
}

/// What to measure.
#[derive(Debug, Clone)]
pub struct BenchOptions {
    /// Number of particles.
    pub n: usize,
    /// Repetitions (each on a fresh scene).
    pub reps: usize,
    /// Run the Python peers or not.
    pub peers: Peers,
    /// Time the full event-driven trajectory or not.
    pub events: Events,
    /// Timings or peak memory.
    pub metric: Metric,
}

/// One measured method.
#[derive(Debug, Clone)]
pub struct Measure {
    /// Method name.
    pub method: &'static str,
    /// Median ns per particle (`None` when not measured).
    pub ns_per_particle: Option<f64>,
    /// Median growth of the resident set during the call, MiB (`None`
    /// when not measured).
    pub peak_mib: Option<f64>,
    /// A remark (e.g. measured on a smaller N, or why skipped).
    pub note: String,
}

/// The benchmark result.
#[derive(Debug, Clone)]
pub struct BenchReport {
    /// N.
    pub n: usize,
    /// Our methods.
    pub ours: Vec<Measure>,
    /// The peers.
    pub peers: Vec<Measure>,
}

/// The median (the mean of the two middle values for an even count).
fn median(mut v: Vec<f64>) -> Option<f64> {
    if v.is_empty() {
        return None;
    }
    v.sort_by(f64::total_cmp);
    let m = v.len() / 2;
    Some(if v.len() % 2 == 0 {
        (v[m - 1] + v[m]) / 2.0
    } else {
        v[m]
    })
}

/// A random admissible scene of exactly `n` particles with dyadic data
/// (gaps in `{0, …, 1023}/1024` beyond `2r = 1/N`, one in eight a contact;
/// velocities in `{−512, …, 512}/256`, raised on contacts to stay in the
/// velocity cone), so that `f64` holds the initial data exactly and the
/// peers see the same numbers.
pub fn scene(n: usize, seed: u64) -> InitialData<BigRational> {
    let mut rng = SplitMix64::new(seed);
    let q = |a: i64, b: i64| BigRational::new(BigInt::from(a), BigInt::from(b));
    let mut shifted = Vec::with_capacity(n);
    let mut velocities: Vec<BigRational> = Vec::with_capacity(n);
    let mut pos = 0i64;
    for i in 0..n {
        let r = rng.next_u64();
        let contact = i > 0 && r % 8 == 0;
        if i > 0 && !contact {
            pos += 1 + ((r >> 3) % 1023) as i64;
        }
        let mut v = ((r >> 16) % 1025) as i64 - 512;
        if contact {
            if let Some(prev) = velocities.last() {
                let prev = (prev * BigRational::from_integer(BigInt::from(256)))
                    .to_integer()
                    .to_string()
                    .parse::<i64>()
                    .unwrap_or(v);
                v = v.max(prev);
            }
        }
        shifted.push(q(pos, 1024));
        velocities.push(q(v, 256));
    }
    let two_r = q(1, n.max(1) as i64);
    let positions = crate::initial::unshift(&shifted, &two_r);
    InitialData::new(
        two_r / BigRational::from_integer(BigInt::from(2)),
        positions,
        velocities,
    )
    .unwrap_or_else(|_| initial_data(&[], Limits::default()))
}

/// The same scene with every position shifted by a decimal of `digits`
/// significant digits (`1.2345678901234…`), so that the common denominators
/// no longer fit `i128` (30 digits: the 256-bit loop; 100 digits: the 512-bit loop).
pub fn decimal_scene(d: &InitialData<BigRational>, digits: usize) -> InitialData<BigRational> {
    let text: String = (0..digits)
        .map(|i| char::from(b'0' + ((i + 1) % 10) as u8))
        .collect();
    let offset = BigRational::new(
        BigInt::parse_bytes(text.as_bytes(), 10).unwrap_or_default(),
        BigInt::from(10u32).pow(digits.saturating_sub(1) as u32),
    );
    let positions = d.positions().iter().map(|x| x + &offset).collect();
    InitialData::new(d.radius().clone(), positions, d.velocities().to_vec())
        .unwrap_or_else(|_| d.clone())
}

/// The scaled columns `x̃⁰_i = x[i] / dx`, `u⁰_i = u[i] / du` of `data` as
/// `sticky events` reads them from a file (`None` when they do not fit
/// `i64`).
#[allow(clippy::type_complexity)]
fn scaled_columns(data: &InitialData<BigRational>) -> Option<(Vec<i64>, Vec<i64>, i128, i128)> {
    let s = crate::fast::scaling::scale_i128(data)?;
    Some((
        s.x_range.narrow(&s.x)?,
        s.u_range.narrow(&s.u)?,
        num_traits::ToPrimitive::to_i128(&s.dx)?,
        num_traits::ToPrimitive::to_i128(&s.du)?,
    ))
}

/// `ỹ = x̃⁰ + t u⁰` in f64 (the peers' input).
fn free_f64(d: &InitialData<BigRational>, t: &BigRational) -> Vec<f64> {
    shifted_free_flight(d, t)
        .iter()
        .map(Scalar::to_f64_lossy)
        .collect()
}

fn time<R>(f: impl FnOnce() -> R) -> (f64, R) {
    let t0 = Instant::now();
    let r = f();
    (t0.elapsed().as_secs_f64() * 1e9, r)
}

/// How `sticky bench` sets up glibc's allocator before measuring (it
/// binary re-runs itself with the setting in the environment and names it
/// in [`MEMORY_MODE_VAR`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Memory {
    /// Timing: `malloc` serves large buffers from its heap instead of
    /// mapping fresh pages for each (`MALLOC_MMAP_MAX_=0`), and one untimed
    /// warm-up repetition runs first, so that methods reuse resident memory
    /// rather than pay page faults: on this machine kind a page fault costs
    /// ~1.5 µs, faulting a method's buffers in would otherwise dominate (a
    /// cold f64 PAVA is 3–4× slower than a warm one), and with glibc's
    /// default, adaptive mmap threshold whether a buffer is resident depends
    /// on what ran before it. (A huge `MALLOC_TRIM_THRESHOLD_` as well made
    /// the `BigInt` loop 3× slower here; it is left at its default.)
    /// A call that writes more than the heap has free still faults its
    /// fresh pages in (the kernel's 512-bit blocks were once 90 MB at
    /// N = 10⁶: 75–263 ns per particle depending on the machine's state).
    Warm,
    /// Rounds timed back to back (`sticky bench --history`):
    /// [`Memory::Warm`], and freed memory is never handed back to the
    /// system (`MALLOC_TRIM_THRESHOLD_` of 2^40), so that no call of a round
    /// faults in pages another one freed. Measured at N = 10⁶: with the default threshold the f64 pass
    /// after a history ran at 31–41 ns per particle, with this one at
    /// 19–20 (the history unchanged, 395–419). The full bench keeps the
    /// default (see [`Memory::Warm`]); the history mode runs no `BigInt`
    /// arithmetic (its third call only reads the `BigRational` scene).
    Resident,
    /// Peak memory: every allocation above 128 KiB is mapped afresh and
    /// returned on free (`MALLOC_MMAP_THRESHOLD_`, `MALLOC_TRIM_THRESHOLD_`),
    /// so the growth of the resident set during a call is the memory it
    /// touched; no warm-up, and timings then include page faults.
    Cold,
}

/// The environment variable through which the `sticky` binary tells the
/// benchmark which allocator setting ([`Memory`]) it re-executed itself
/// under (`Warm` or `Cold`); the setting itself belongs to the binary.
pub const MEMORY_MODE_VAR: &str = "STICKY_BENCH_MALLOC";

/// The allocator setting this process runs under (`None`: not set up).
pub fn current_memory_mode() -> Option<Memory> {
    match std::env::var(MEMORY_MODE_VAR).ok()?.as_str() {
        "Warm" => Some(Memory::Warm),
        "Resident" => Some(Memory::Resident),
        "Cold" => Some(Memory::Cold),
        _ => None,
    }
}

/// A `/proc/self/status` field in kB.
fn status_kib(field: &str) -> Option<f64> {
    let text = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = text.lines().find(|l| l.starts_with(field))?;
    line.split_whitespace().nth(1)?.parse().ok()
}

/// Times `f` and measures the growth of the resident set while it runs
/// (peak minus resident before, in MiB; Linux only: the peak is reset
/// through `/proc/self/clear_refs`, `None` elsewhere).
fn measured<R>(f: impl FnOnce() -> R) -> (f64, Option<f64>, R) {
    let reset = std::fs::write("/proc/self/clear_refs", "5").is_ok();
    let before = status_kib("VmRSS:");
    let (ns, r) = time(f);
    let peak = status_kib("VmHWM:");
    let mib = match (reset, before, peak) {
        (true, Some(b), Some(p)) => Some((p - b).max(0.0) / 1024.0),
        _ => None,
    };
    (ns, mib, r)
}

/// Timings of one method over the repetitions.
#[derive(Debug, Default)]
struct Acc {
    ns: Vec<f64>,
    mib: Vec<f64>,
    note: String,
}

impl Acc {
    fn push(&mut self, ns_per_particle: f64, mib: Option<f64>) {
        self.ns.push(ns_per_particle);
        // Resident-set growth means peak memory only with the cold
        // allocator.
        if current_memory_mode() == Some(Memory::Cold) {
            self.mib.extend(mib);
        }
    }
}

/// Runs the benchmark at time `t` (`t` small: few clusters; `t` large: few
/// large clusters).
pub fn run(opts: &BenchOptions, t: &BigRational, scripts: &Path) -> BenchReport {
    run_with_progress(opts, t, scripts, &Silent)
}

/// [`run`], telling `progress` which repetition and which method is being
/// timed (one step per repetition, warm-up included, and one for the
/// peers). Between two repetitions it asks [`Progress::cancelled`]: on a
/// stop the report holds the repetitions done so far (the warm-up's
/// figures when the stop came right after it) and no peers.
pub fn run_with_progress(
    opts: &BenchOptions,
    t: &BigRational,
    scripts: &Path,
    progress: &dyn Progress,
) -> BenchReport {
    let n = opts.n.max(1);
    let nf = n as f64;
    let names = [
        "f64",
        "exact_int",
        "exact_int_lowest",
        "exact_bigint",
        "exact_bigint_100",
        "bigrational_naive",
        "adaptive",
        "adaptive_bigdata",
        "events",
        "events_columns",
        "events_lowest",
        "events_generic",
    ];
    let mut acc: Vec<Acc> = names.iter().map(|_| Acc::default()).collect();
    let at = |name: &str| names.iter().position(|m| *m == name).unwrap_or(0);
    // The naive and generic engines on N/10 particles, at most 10^5 (they
    // are linear-time per particle; reported per particle, saying so).
    let naive_n = (n / 10).clamp(1, 100_000);
    let mut peer_inputs: Vec<Vec<f64>> = Vec::new();
    // One untimed warm-up repetition (on its own scene) unless measuring
    // memory: see [`Memory`].
    let warmups = usize::from(opts.metric == Metric::Time);
    let rounds = opts.reps.max(1) + warmups;
    progress.stage(
        &format!("N = {n}: repetitions"),
        Some((rounds + usize::from(opts.peers == Peers::Run)) as u64),
    );
    let mut stopped = false;
    for rep in 0..rounds {
        if progress.cancelled() {
            stopped = true;
            break;
        }
        let round = if rep < warmups {
            "warm-up".to_string()
        } else {
            format!("repetition {}/{}", rep + 1 - warmups, rounds - warmups)
        };
        let doing = |method: &str| progress.note(&format!("N = {n}, {round}: {method}"));
        doing("f64, integer kernel, adaptive");
        if rep == warmups && warmups > 0 {
            acc.iter_mut().for_each(|a| {
                a.ns.clear();
                a.mib.clear();
            });
            peer_inputs.clear();
        }
        let data = scene(n, 1000 + rep as u64);
        let y = free_f64(&data, t);
        let (ns, mib, out) = measured(|| isotonic::<f64>(&y));
        std::hint::black_box(out);
        acc[at("f64")].push(ns / nf, mib);

        let ints = IntegerData::new(&data);
        let (ns, mib, b) = measured(|| blocks_at(&ints, t));
        acc[at("exact_int")].note = format!(
            "integer kernel, width {:?}; exact block sums, means reduced on demand",
            b.width()
        );
        acc[at("exact_int")].push(ns / nf, mib);
        let (ns, mib, means) = measured(|| {
            let b = blocks_at(&ints, t);
            (0..b.len())
                .map(|j| (b.mean_y(j), b.mean_u(j)))
                .collect::<Vec<_>>()
        });
        std::hint::black_box(means);
        acc[at("exact_int_lowest")].note =
            "integer kernel, and every block mean reduced to a BigRational in lowest terms".into();
        acc[at("exact_int_lowest")].push(ns / nf, mib);

        let (ns, mib, a) = measured(|| adaptive_blocks_at(&ints, t));
        acc[at("adaptive")].note = format!("adaptive on the same scene: {:?}", a.path);
        acc[at("adaptive")].push(ns / nf, mib);

        doing("integer kernel on 30- and 100-digit decimals");
        let big = IntegerData::new(&decimal_scene(&data, 30));
        let (ns, mib, b) = measured(|| blocks_at(&big, t));
        acc[at("exact_bigint")].note =
            format!("integer kernel on 30-digit decimals, width {:?}", b.width());
        acc[at("exact_bigint")].push(ns / nf, mib);
        let huge = IntegerData::new(&decimal_scene(&data, 100));
        // The f64 copy of the data the adaptive filter reads is prepared
        // once per scene, like the scaling itself: not timed.
        huge.approx();
        let (ns, mib, b) = measured(|| blocks_at(&huge, t));
        acc[at("exact_bigint_100")].note = format!(
            "integer kernel on 100-digit decimals, width {:?}",
            b.width()
        );
        acc[at("exact_bigint_100")].push(ns / nf, mib);
        let (ns, mib, a) = measured(|| adaptive_blocks_at(&huge, t));
        acc[at("adaptive_bigdata")].note =
            format!("adaptive on the 100-digit scene: {}", path_note(&a.path));
        acc[at("adaptive_bigdata")].push(ns / nf, mib);

        doing("generic PAVA on BigRational");
        let small = scene(naive_n, 5000 + rep as u64);
        let ys = shifted_free_flight(&small, t);
        let (ns, mib, out) = measured(|| pava_blocks(&ys, Some(small.velocities())));
        std::hint::black_box(out);
        acc[at("bigrational_naive")].note = format!(
            "generic PAVA on BigRational, measured on N = {naive_n} and reported per particle"
        );
        acc[at("bigrational_naive")].push(ns / naive_n as f64, mib);
        if opts.events == Events::Time {
            doing("event-driven histories");
            let (ns, mib, traj) = measured(|| IntegerTrajectory::new(&data));
            acc[at("events")].note = format!(
                "full exact event-driven trajectory, integer engine ({:?}): {} clusters formed at {} instants, times kept as exact unreduced fractions",
                traj.engine(),
                traj.events(),
                traj.instants()
            );
            acc[at("events")].push(ns / nf, mib);
            // The path `sticky events` takes on a CSV, NPY or TOML file:
            // the history straight from the scaled integer columns (read
            // from the file into machine words, `fast::stream`), no
            // `BigRational` datum. The columns are prepared untimed, like
            // the kernel rows' `IntegerData`.
            match scaled_columns(&data) {
                Some((x, u, dx, du)) => {
                    let (ns, mib, h) =
                        measured(|| crate::fast::merge::history_words(&x, &u, dx, du));
                    acc[at("events_columns")].note = format!(
                        "the same history from the scaled i64 columns, as `sticky events` computes it from a CSV, NPY or TOML file ({})",
                        if h.is_some() { "integer engine" } else { "bound failed: not measured" }
                    );
                    if h.is_some() {
                        acc[at("events_columns")].push(ns / nf, mib);
                    }
                }
                None => {
                    acc[at("events_columns")].note =
                        "the scene's scaled columns do not fit i64: not measured".into();
                }
            }
            let (ns, mib, t) = measured(|| traj.into_trajectory());
            std::hint::black_box(t.impulses().len());
            acc[at("events_lowest")].note =
                "converting that history to a Trajectory<BigRational> (every time and velocity in lowest terms)".into();
            acc[at("events_lowest")].push(ns / nf, mib);
            let (ns, mib, traj) = measured(|| Trajectory::new(small.clone()));
            std::hint::black_box(traj.impulses().len());
            acc[at("events_generic")].note = format!(
                "the generic event engine on BigRational, measured on N = {naive_n} and reported per particle"
            );
            acc[at("events_generic")].push(ns / naive_n as f64, mib);
        } else {
            for name in [
                "events",
                "events_columns",
                "events_lowest",
                "events_generic",
            ] {
                acc[at(name)].note = "skipped (--quick)".into();
            }
        }
        peer_inputs.push(y);
        progress.advance(1);
    }
    acc[at("f64")].note = "generic PAVA on f64 (per-particle output)".into();
    let ours = names
        .iter()
        .zip(acc)
        .map(|(method, a)| Measure {
            method,
            ns_per_particle: median(a.ns),
            peak_mib: median(a.mib),
            note: a.note,
        })
        .collect();
    let peers = if opts.peers == Peers::Run && !stopped {
        progress.note(&format!("N = {n}: the Python peers"));
        run_peers(&peer_inputs, scripts)
    } else {
        vec![]
    };
    BenchReport { n, ours, peers }
}

fn path_note(p: &Path_) -> String {
    match p {
        Path_::Certified { decisions, exact } => format!(
            "{decisions} decisions, {exact} decided exactly ({:.2}%)",
            100.0 * *exact as f64 / (*decisions).max(1) as f64
        ),
        other => format!("{other:?}"),
    }
}

/// Writes the inputs as raw little-endian f64 and runs `scripts/peers.py`,
/// which prints `name ns_per_particle` lines.
fn run_peers(inputs: &[Vec<f64>], scripts: &Path) -> Vec<Measure> {
    let skipped = |why: String| {
        vec![
            Measure {
                method: "scipy",
                ns_per_particle: None,
                peak_mib: None,
                note: why.clone(),
            },
            Measure {
                method: "sklearn",
                ns_per_particle: None,
                peak_mib: None,
                note: why,
            },
        ]
    };
    let dir = std::env::temp_dir().join(format!("sticky-bench-{}", std::process::id()));
    if let Err(e) = std::fs::create_dir_all(&dir) {
        return skipped(format!("cannot create {}: {e}", dir.display()));
    }
    let mut files = Vec::new();
    for (k, y) in inputs.iter().enumerate() {
        let path = dir.join(format!("y{k}.f64"));
        let bytes: Vec<u8> = y.iter().flat_map(|v| v.to_le_bytes()).collect();
        if let Err(e) = std::fs::write(&path, bytes) {
            return skipped(format!("cannot write {}: {e}", path.display()));
        }
        files.push(path);
    }
    let out = Command::new("python3")
        .arg(scripts.join("peers.py"))
        .args(&files)
        .output();
    let _ = std::fs::remove_dir_all(&dir);
    let out = match out {
        Ok(o) if o.status.success() => o,
        Ok(o) => {
            return skipped(format!(
                "peers.py failed: {}",
                String::from_utf8_lossy(&o.stderr)
                    .lines()
                    .last()
                    .unwrap_or("")
            ))
        }
        Err(e) => return skipped(format!("python3 not available: {e}")),
    };
    let text = String::from_utf8_lossy(&out.stdout);
    ["scipy", "sklearn"]
        .iter()
        .map(|name| {
            let v = text
                .lines()
                .find_map(|l| l.strip_prefix(&format!("{name} ")))
                .map(str::trim);
            let parsed = v.and_then(|s| s.parse::<f64>().ok());
            Measure {
                method: name,
                ns_per_particle: parsed,
                peak_mib: None,
                note: match (parsed, v) {
                    (Some(_), _) => "same data, same run".into(),
                    (None, Some(s)) => s.to_string(),
                    (None, None) => "no result".into(),
                },
            }
        })
        .collect()
}

/// Method name → median ns per particle (`null`: not measured), in the
/// order measured.
#[derive(Debug, Clone, Copy)]
pub struct NsPerParticle<'a>(pub &'a [Measure]);

impl serde::Serialize for NsPerParticle<'_> {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.collect_map(
            self.0
                .iter()
                .map(|m| (m.method, m.ns_per_particle.map(crate::json::Fixed::<2>))),
        )
    }
}

/// `sticky bench --json`: one object.
#[derive(Debug, Clone, serde::Serialize)]
pub struct BenchJson<'a> {
    /// N.
    pub n: usize,
    /// Ours.
    pub ns_per_particle: NsPerParticle<'a>,
    /// The peer solvers'.
    pub peers: NsPerParticle<'a>,
}

/// [`BenchJson`] as one line.
pub fn json(r: &BenchReport) -> String {
    crate::json::to_string(&BenchJson {
        n: r.n,
        ns_per_particle: NsPerParticle(&r.ours),
        peers: NsPerParticle(&r.peers),
    })
}

/// A table with the ratio to our f64 PAVA.
pub fn table(r: &BenchReport) -> String {
    let base = r
        .ours
        .iter()
        .find(|m| m.method == "f64")
        .and_then(|m| m.ns_per_particle);
    let mut out = format!(
        "N = {}\n  {:<18} {:>12} {:>10} {:>9}  note\n",
        r.n, "method", "ns/particle", "× f64", "peak MiB"
    );
    for m in r.ours.iter().chain(&r.peers) {
        let ratio = match (m.ns_per_particle, base) {
            (Some(v), Some(b)) if b > 0.0 => format!("{:.2}", v / b),
            _ => "—".into(),
        };
        out.push_str(&format!(
            "  {:<18} {:>12} {:>10} {:>9}  {}\n",
            m.method,
            m.ns_per_particle.map_or("—".into(), |v| format!("{v:.1}")),
            ratio,
            m.peak_mib.map_or("—".into(), |v| format!("{v:.0}")),
            m.note
        ));
    }
    out
}
