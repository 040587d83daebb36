//! `sticky bench`: PAVA at one time on random scenes, every method timed in
//! one run; `--scaling` for the study across N; `--memory` for peak memory.
//!
//! The allocator setting ([`Memory`]) is a property of the process, so it
//! is made here, in the binary: the command re-executes itself with glibc's
//! `malloc` tuned for the measurement before the library runs anything.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use num_rational::BigRational;

use sticky::progress::Progress;
use sticky::report::bench::{self, Memory, MEMORY_MODE_VAR};
use sticky::report::progress::Bar;

use crate::{io_err, parse_time, print_paths, Failure};

/// PAVA at one time on random scenes: every method timed in one run on
/// fresh inputs, with the ratio to our f64 PAVA and the Python peers.
#[derive(clap::Args)]
pub struct Args {
    /// Number of particles.
    #[arg(long, default_value_t = 1_000_000)]
    n: usize,
    /// Repetitions, each on a fresh scene (default 3; 2 with --quick).
    #[arg(long)]
    reps: Option<usize>,
    /// Quick run (under two minutes at N = 10^6): no event-driven
    /// trajectory, 2 repetitions.
    #[arg(long)]
    quick: bool,
    /// Skip the Python peers.
    #[arg(long)]
    no_peers: bool,
    /// Print JSON.
    #[arg(long)]
    json: bool,
    /// The time t of the projection (small: few clusters; large: few
    /// large clusters).
    #[arg(long, default_value = "1/100", value_parser = parse_time)]
    at: BigRational,
    /// Measure peak memory (cold allocator, no warm-up: timings then
    /// include page faults).
    #[arg(long)]
    memory: bool,
    /// The scaling study: N = 10^3, 10^4, … up to --max-n, both regimes
    /// (t = 1/100: almost no clusters; t = 20: few large clusters);
    /// CSV, log-log charts and fitted slopes in --out.
    #[arg(long)]
    scaling: bool,
    /// Largest N of the scaling study.
    #[arg(long, default_value_t = 10_000_000)]
    max_n: usize,
    /// Output folder of the scaling study (default ./out/bench/).
    #[arg(long)]
    out: Option<PathBuf>,
    /// The end-to-end rows instead: `sticky run` and `sticky events` as
    /// whole processes from file to answer to file (TOML, CSV and NPY
    /// input) beside scipy's own pipeline on the same CSV and NPY files;
    /// wall time, ratio to scipy, peak memory per particle (default 3
    /// repetitions, 1 with --quick).
    #[arg(long, conflicts_with_all = ["scaling", "memory", "at"])]
    e2e: bool,
    /// Only the full exact history (from the scaled columns, the
    /// `events_columns` row, and from the BigRational data, the `events`
    /// row) against our f64 PAVA, timed back to back on one scene: each
    /// round's ratios and their medians (default 9 rounds).
    #[arg(long, conflicts_with_all = ["scaling", "memory", "e2e", "quick"])]
    history: bool,
    /// With --scaling: measure nothing, redraw the charts from a CSV that
    /// an earlier `--scaling` run wrote (e.g. docs/scaling.csv).
    #[arg(long, requires = "scaling")]
    charts_from: Option<PathBuf>,
}

/// glibc's allocator settings for a [`Memory`] mode.
fn malloc_env(mode: Memory) -> Vec<(&'static str, &'static str)> {
    match mode {
        Memory::Warm => vec![("MALLOC_MMAP_MAX_", "0"), (MEMORY_MODE_VAR, "Warm")],
        Memory::Resident => vec![
            ("MALLOC_MMAP_MAX_", "0"),
            ("MALLOC_TRIM_THRESHOLD_", "1099511627776"),
            (MEMORY_MODE_VAR, "Resident"),
        ],
        Memory::Cold => vec![
            ("MALLOC_MMAP_THRESHOLD_", "131072"),
            ("MALLOC_TRIM_THRESHOLD_", "131072"),
            (MEMORY_MODE_VAR, "Cold"),
        ],
    }
}

/// Whether `--no-peers` leaves the Python peers out.
fn peers(args: &Args) -> bench::Peers {
    if args.no_peers {
        bench::Peers::Skip
    } else {
        bench::Peers::Run
    }
}

/// What `--memory` asks the benchmark to measure.
fn metric(args: &Args) -> bench::Metric {
    if args.memory {
        bench::Metric::PeakMemory
    } else {
        bench::Metric::Time
    }
}

/// Re-runs the current command with glibc's allocator set up for the mode
/// `args` asks for and returns the child's exit code; `None` when this
/// process is already that child (or not on Linux, where nothing is
/// changed).
pub fn reexec_with_malloc(args: &Args) -> Option<ExitCode> {
    let mode = if args.memory {
        Memory::Cold
    } else if args.history {
        Memory::Resident
    } else {
        Memory::Warm
    };
    // The end-to-end rows time child processes under the allocator's
    // defaults, as a user runs them: nothing to set up.
    if args.e2e || !cfg!(target_os = "linux") || std::env::var_os(MEMORY_MODE_VAR).is_some() {
        return None;
    }
    let exe = std::env::current_exe().ok()?;
    let status = std::process::Command::new(exe)
        .args(std::env::args_os().skip(1))
        .envs(malloc_env(mode))
        .status()
        .ok()?;
    let code = status.code().map_or(1, |c| u8::try_from(c).unwrap_or(1));
    Some(ExitCode::from(code))
}

/// The Python peers' scripts, shipped in the source tree.
fn scripts() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("scripts")
}

/// Runs `sticky bench`.
pub fn exec(args: Args, out: &mut impl Write) -> Result<(), Failure> {
    if args.scaling {
        return scaling(args, out);
    }
    if args.e2e {
        return e2e(args, out);
    }
    if args.history {
        return history(args, out);
    }
    let opts = bench::BenchOptions {
        n: args.n,
        reps: args.reps.unwrap_or(if args.quick { 2 } else { 3 }),
        peers: peers(&args),
        events: if args.quick {
            bench::Events::Skip
        } else {
            bench::Events::Time
        },
        metric: metric(&args),
    };
    // The repetition and the method being timed, the count and the time
    // left, on a terminal only (hidden when stderr is piped).
    let bar = Bar::for_command("bench");
    let report = bench::run_with_progress(&opts, &args.at, &scripts(), &bar);
    bar.finish();
    if bar.cancelled() {
        return Err(Failure("bench: interrupted".to_string()));
    }
    let text = if args.json {
        bench::json(&report)
    } else {
        bench::table(&report)
    };
    writeln!(out, "{}", text.trim_end()).map_err(io_err)
}

/// `sticky bench --e2e`.
fn e2e(args: Args, out: &mut impl Write) -> Result<(), Failure> {
    let opts = bench::e2e::E2eOptions {
        n: args.n,
        reps: args.reps.unwrap_or(if args.quick { 1 } else { 3 }),
        peers: peers(&args),
        sticky: std::env::current_exe()
            .map_err(|e| Failure(format!("cannot find the sticky binary: {e}")))?,
        scripts: scripts(),
    };
    // What is being timed, on a terminal only.
    let bar = Bar::for_command("bench");
    bar.stage("end-to-end rows", None);
    let report = bench::e2e::run(&opts, |msg| bar.note(msg));
    bar.finish();
    let report = report.map_err(Failure)?;
    let text = if args.json {
        bench::e2e::json(&report)
    } else {
        bench::e2e::table(&report)
    };
    writeln!(out, "{}", text.trim_end()).map_err(io_err)
}

/// `sticky bench --history`.
fn history(args: Args, out: &mut impl Write) -> Result<(), Failure> {
    let report = bench::history::run(args.n, args.reps.unwrap_or(9), &args.at).map_err(Failure)?;
    let text = if args.json {
        bench::history::json(&report)
    } else {
        bench::history::table(&report)
    };
    writeln!(out, "{}", text.trim_end()).map_err(io_err)
}

/// `sticky bench --scaling`.
fn scaling(args: Args, out: &mut impl Write) -> Result<(), Failure> {
    let mut ns = Vec::new();
    let mut n = 1000usize;
    while n <= args.max_n {
        ns.push(n);
        n = n.saturating_mul(10);
    }
    let metric = metric(&args);
    if let Some(csv) = &args.charts_from {
        let text = std::fs::read_to_string(csv)
            .map_err(|e| Failure(format!("cannot read {}: {e}", csv.display())))?;
        let rows = bench::read_scaling_csv(&text)
            .map_err(|e| Failure(format!("{}: {e}", csv.display())))?;
        let dir = args.out.unwrap_or_else(|| PathBuf::from("out/bench"));
        let paths =
            bench::scaling_charts(&rows, &dir, metric).map_err(|e| Failure(e.to_string()))?;
        return print_paths(out, &paths);
    }
    let opts = bench::ScalingOptions {
        ns,
        reps: args.reps.unwrap_or(3),
        peers: peers(&args),
        metric,
        out: args.out.unwrap_or_else(|| PathBuf::from("out/bench")),
    };
    // The regime and N being measured (one step each), the count and the
    // time left, on a terminal only.
    let bar = Bar::for_command("bench");
    bar.stage(
        "scaling study",
        Some((bench::REGIMES.len() * opts.ns.len()) as u64),
    );
    let mut started = false;
    let measured = bench::scaling(&opts, &scripts(), |msg| {
        // One message as each (regime, N) starts: the one before is done.
        if started {
            bar.advance(1);
        }
        started = true;
        bar.note(msg);
    });
    bar.finish();
    let (rows, paths) = measured.map_err(|e| Failure(e.to_string()))?;
    for &(regime, _, _) in &bench::REGIMES {
        let line = bench::slopes(&rows, regime, metric)
            .iter()
            .map(|(m, s)| format!("{m} {s:.2}"))
            .collect::<Vec<_>>()
            .join(", ");
        writeln!(
            out,
            "{regime}: log-log slope of the total {} against N: {line}",
            match metric {
                bench::Metric::PeakMemory => "memory",
                bench::Metric::Time => "time",
            }
        )
        .map_err(io_err)?;
    }
    print_paths(out, &paths)
}
