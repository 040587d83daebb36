//! `sticky events SCENE [--json]`: every collision.

use std::io::Write;
use std::path::PathBuf;

use sticky::progress::Progress;
use sticky::report::json;
use sticky::report::progress::Bar;

use crate::table::write_events_table;
use crate::{io_err, load, Failure};

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
    if args.json {
        // The streaming path (`fast::stream`): the same bytes, or the
        // general way below.
        if let Some(h) = sticky::fast::stream::Lean::load(&args.scene).and_then(|l| l.history()) {
            return json::write_word_events(out, &h).map_err(io_err);
        }
    }
    let scene = load(&args.scene)?;
    if args.explain {
        // The history always comes from the integer event merge (which
        // falls back to the generic merge when its widths do not suffice).
        let cost = sticky::fast::engine::Cost::of(&scene.data);
        eprintln!("{}", cost.explain(&sticky::fast::engine::Merge));
    }
    // The merge shows its progress (merges done of at most N − 1, time
    // left) on a terminal and stops on Ctrl-C: only hopeless work is
    // refused.
    sticky::fast::engine::check_work_watched(&scene.data, &sticky::fast::engine::Merge)
        .map_err(|e| Failure(format!("{}: {e}", args.scene.display())))?;
    let bar = Bar::for_command("events");
    let traj = sticky::fast::merge::trajectory_with_progress(&scene.data, &bar)
        .map_err(|e| Failure(format!("{}: {e}", args.scene.display())))?;
    bar.finish();
    if args.json {
        writeln!(out, "{}", json::events(traj.impulses())).map_err(io_err)?;
        return Ok(());
    }
    write_events_table(out, &traj).map_err(io_err)
}
