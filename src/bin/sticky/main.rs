//! The `sticky` command line: a thin layer over the library, one module per
//! command.
//!
//! * `sticky` — runs the embedded default scene (Appendix C's two blocks) and
//!   prints a short summary: collisions, final clusters, checks passed.
//! * `sticky run SCENE --at T [--at T2 …] [--json]` — the state at each time.
//! * `sticky events SCENE [--json]` — every collision.
//! * `sticky check SCENE` — the summary of the default run, for any scene.
//! * `sticky compare SCENE SOLUTION [--json]` — another solver's answer
//!   against the exact one; `sticky export SCENE --format json|csv|npy` — the
//!   scene as a peer solver reads it.
//! * `sticky prove [--n N] [--claim ID] [--json]` — claims proved for all
//!   real data at N = 1 … N, or refuted with a replayed counterexample.
//! * `sticky generate`, `claims`, `bench`, `converge`, `plot`, `atlas` — see
//!   `sticky help COMMAND`.
//!
//! Errors go to stderr as one line `error: SCENE: message`, exit code 1.

mod atlas;
mod bench;
mod campaign;
mod check;
mod claims;
mod compare;
mod converge;
mod events;
mod export;
mod generate;
mod merge;
mod plot;
mod prove;
mod run;
mod table;

use std::io::{self, BufWriter, Write};
use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, Subcommand};
use num_rational::BigRational;

use sticky::rational::parse_exact;
use sticky::scene::{self, Scene};
use sticky::Scalar;

#[derive(Parser)]
#[command(
    name = "sticky",
    version,
    about = "Exact sticky particles on a line (Signorini constraint), after C. Perrin's 'Microscopic derivation of the one-dimensional constrained Euler equations'.",
    after_help = "Scene files, every command and the JSON output are described in the user guide, docs/guide/ in the source tree (README.md links it; `cargo doc --open` for the library). Particle indices in every output count from 0.",
    long_about = None
)]
struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
}

#[derive(Subcommand)]
enum Command {
    /// The state x(t), u(t), λ(t) and the contact clusters at each requested time.
    Run(run::Args),
    /// Every collision: time, cluster formed, sizes of the clusters that merged.
    Events(events::Args),
    /// Summary of a scene: collisions, final clusters, and the section-2
    /// checks (event-driven = projection, signs of λ and of the pressure).
    Check(check::Args),
    /// Prints a random admissible `[particles]` scene (exact rationals, with
    /// contacts, separating contacts and simultaneous collisions on purpose).
    Generate(generate::Args),
    /// PAVA at one time on random scenes: every method timed in one run on
    /// fresh inputs, with the ratio to our f64 PAVA and the Python peers.
    Bench(bench::Args),
    /// The hydrodynamic limit: distances between the particles and the
    /// continuum solution for N = 8 … 2^16, with fitted rates; CSV and charts.
    Converge(converge::Args),
    /// Pictures of a scene: space-time diagram of the worldlines, density
    /// heat map, pressure impulses (SVG and PNG).
    Plot(plot::Args),
    /// The speed-vs-accuracy atlas of the floating-point reference solvers
    /// against the exact engine: CSV, charts and the stability table.
    Atlas(atlas::Args),
    /// The claims ledger: runs every checker of the paper's claims and prints
    /// the computed statuses.
    Claims(claims::Args),
    /// Another solver's answer (JSON or CSV) against the exact one: position,
    /// velocity, λ errors, overlaps, wrong clusters, Oleinik, and a verdict.
    Compare(compare::Args),
    /// The scene's data as a peer solver reads it: nearest doubles, their
    /// exact rounding errors, exact values (JSON, CSV or NPY).
    Export(export::Args),
    /// Proves every per-case claim of section 2 for all real initial data
    /// at N = 1 … N (symbolic execution of the engine and the checkers, z3),
    /// or refutes it with an exact, replayed counterexample.
    Prove(prove::Args),
    /// Combines the shards' files of one campaign (`claims` or `prove`
    /// with `--shard I/N`) into exactly the report a single run
    /// prints; refuses missing or duplicated shards and mixed campaigns.
    Merge(merge::Args),
}

fn parse_time(s: &str) -> Result<BigRational, String> {
    let t = parse_exact(s).map_err(|e| e.to_string())?;
    if t < <BigRational as Scalar>::zero() {
        return Err(format!("time {s} is negative"));
    }
    Ok(t)
}

/// What went wrong, already phrased for the user.
struct Failure(String);

fn load(path: &std::path::Path) -> Result<Scene, Failure> {
    scene::load(path).map_err(scene_err(path))
}

/// A library error about the scene at `path`, as a failure that names it.
fn scene_err(path: &std::path::Path) -> impl Fn(sticky::Error) -> Failure + '_ {
    move |e| Failure(format!("{}: {e}", path.display()))
}

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        // --help, --version: clap's own output on stdout.
        Err(e) if !e.use_stderr() => {
            let _ = e.print();
            return ExitCode::SUCCESS;
        }
        // One line, as for every other error: clap's first paragraph (no
        // usage or help hints), joined.
        Err(e) => {
            let text = e.render().to_string();
            let lines: Vec<&str> = text
                .lines()
                .take_while(|l| !l.trim().is_empty())
                .map(str::trim)
                .collect();
            let message = lines.join(" ");
            let message = message.strip_prefix("error: ").unwrap_or(&message);
            eprintln!("error: {message}");
            return ExitCode::from(2);
        }
    };
    if let Some(Command::Bench(args)) = &cli.command {
        if let Some(code) = bench::reexec_with_malloc(args) {
            return code;
        }
    }
    let stdout = io::stdout();
    let mut out = BufWriter::new(stdout.lock());
    let result = match cli.command {
        None => scene::default_scene()
            .map_err(|e| Failure(format!("embedded default scene: {e}")))
            .and_then(|s| {
                let solver = sticky::solver::Solver::from_scene(s);
                check::summary(&mut out, &solver, "embedded default scene")
            }),
        Some(Command::Run(args)) => run::exec(args, &mut out),
        Some(Command::Events(args)) => events::exec(args, &mut out),
        Some(Command::Check(args)) => check::exec(args, &mut out),
        Some(Command::Generate(args)) => generate::exec(args, &mut out),
        Some(Command::Bench(args)) => bench::exec(args, &mut out),
        Some(Command::Converge(args)) => converge::exec(args, &mut out),
        Some(Command::Plot(args)) => plot::exec(args, &mut out),
        Some(Command::Atlas(args)) => atlas::exec(args, &mut out),
        Some(Command::Claims(args)) => claims::exec(args, &mut out),
        Some(Command::Compare(args)) => compare::exec(args, &mut out),
        Some(Command::Export(args)) => export::exec(args, &mut out),
        Some(Command::Prove(args)) => prove::exec(args, &mut out),
        Some(Command::Merge(args)) => merge::exec(args, &mut out),
    };
    let flushed = out.flush();
    // `sticky bench --e2e` runs this binary as a child and asks it for its
    // peak resident memory at exit (hidden: a measurement hook).
    if let Some(path) = std::env::var_os(sticky::report::bench::e2e::PEAK_RSS_VAR) {
        let _ = sticky::report::bench::e2e::write_peak_rss(std::path::Path::new(&path));
    }
    match result {
        Ok(()) if flushed.is_ok() || is_broken_pipe(&flushed) => ExitCode::SUCCESS,
        Ok(()) => {
            eprintln!("error: cannot write the output: {:?}", flushed.err());
            ExitCode::FAILURE
        }
        Err(Failure(msg)) if msg.is_empty() => ExitCode::SUCCESS,
        Err(Failure(msg)) => {
            eprintln!("error: {msg}");
            ExitCode::FAILURE
        }
    }
}

fn is_broken_pipe(r: &io::Result<()>) -> bool {
    matches!(r, Err(e) if e.kind() == io::ErrorKind::BrokenPipe)
}

/// Maps a write error to a failure; a closed pipe ends the output quietly.
fn io_err(e: io::Error) -> Failure {
    if e.kind() == io::ErrorKind::BrokenPipe {
        Failure(String::new())
    } else {
        Failure(format!("cannot write the output: {e}"))
    }
}

fn lib_err(e: sticky::Error) -> Failure {
    Failure(e.to_string())
}

fn print_paths(out: &mut impl Write, paths: &[PathBuf]) -> Result<(), Failure> {
    for p in paths {
        writeln!(out, "wrote {}", p.display()).map_err(io_err)?;
    }
    Ok(())
}
