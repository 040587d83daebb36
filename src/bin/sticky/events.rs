//! `sticky events SCENE [--json]`: every collision.

use std::io::Write;
use std::path::PathBuf;

use sticky::progress::Progress;
use sticky::report::json;
use sticky::report::progress::Bar;
use sticky::solver::{History, Options, Solver, WorkCap};

use crate::table::write_events_table;
use crate::{io_err, scene_err, Failure};

/// Every collision: time, cluster formed, sizes of the clusters that merged.
#[derive(clap::Args)]
pub struct Args {
    /// Scene file (TOML).
    scene: PathBuf,
    /// `{"events": [...]}` (the interop contract: docs/guide/json.md).
    #[arg(long)]
    json: bool,
    /// Print on stderr which engine answers and why (N, the common
    /// denominator's bits, the estimated cost).
    #[arg(long)]
    explain: bool,
}

/// Runs `sticky events`.
pub fn exec(args: Args, out: &mut impl Write) -> Result<(), Failure> {
    let at = scene_err(&args.scene);
    // The merge shows its progress (merges done of at most N − 1, time
    // left) on a terminal and stops on Ctrl-C: only hopeless work is
    // refused.
    let solver = Solver::load(&args.scene)
        .map_err(&at)?
        .with_options(Options {
            work: WorkCap::Watched,
            ..Options::default()
        });
    if args.explain {
        eprintln!("{}", solver.explain_events().map_err(&at)?);
    }
    let bar = Bar::for_command("events");
    // The table needs the whole trajectory; the JSON takes the streaming
    // path where the data allow.
    let history = if args.json {
        solver.events(&bar)
    } else {
        solver.trajectory(&bar).map(History::Exact)
    }
    .map_err(&at)?;
    bar.finish();
    match history {
        History::Words(h) => json::write_word_events(out, &h),
        History::Exact(traj) if args.json => writeln!(out, "{}", json::events(traj.impulses())),
        History::Exact(traj) => write_events_table(out, &traj),
    }
    .map_err(io_err)
}
