//! `sticky atlas [--quick] [--peers] [--scene NAME]… [--shard I/N] [--jobs K]`:
//! the speed-vs-accuracy atlas.

use std::io::Write;
use std::path::PathBuf;

use sticky::campaign::jobs::run_units;
use sticky::report::atlas::campaign::{AtlasSetup, Campaign, UnitRow};
use sticky::report::atlas::{Feedback, Size};

use crate::campaign::{setup_value, Split};
use crate::{print_paths, Failure};

/// The speed-vs-accuracy atlas of the floating-point reference solvers
/// against the exact engine: CSV, charts and the stability table.
#[derive(clap::Args)]
pub struct Args {
    /// The small suite (well under a minute).
    #[arg(long)]
    quick: bool,
    /// Also run the real peer solvers (scripts/peers/, N ≤ 1000) as rows
    /// `peer:<name>`; a peer that is not installed is skipped with a message.
    #[arg(long)]
    peers: bool,
    /// Only this scene (of the suite or the stability section); repeatable.
    #[arg(long = "scene", value_name = "NAME")]
    scenes: Vec<String>,
    /// Output folder (default ./out/atlas/).
    #[arg(long)]
    out: Option<PathBuf>,
    #[command(flatten)]
    split: Split,
}

/// The atlas's size from `--quick`.
fn size(quick: bool) -> Size {
    if quick {
        Size::Quick
    } else {
        Size::Full
    }
}

/// The output folder when none is given.
pub const DEFAULT_OUT: &str = "out/atlas";

/// Runs `sticky atlas`.
pub fn exec(args: Args, out: &mut impl Write) -> Result<(), Failure> {
    let dir = args.out.unwrap_or_else(|| PathBuf::from(DEFAULT_OUT));
    if args.split.shard.is_none() && args.split.jobs.get() == 1 {
        let opts = sticky::report::atlas::AtlasOptions {
            size: size(args.quick),
            out: dir,
            peers: args.peers,
            scenes: args.scenes,
        };
        return sticky::report::atlas::run(&opts, Feedback::Bar)
            .map_err(|e| Failure(e.to_string()))
            .and_then(|paths| print_paths(out, &paths));
    }
    if args.peers {
        return Err(Failure(
            "--peers runs in a single atlas only, not with --shard or --jobs".to_string(),
        ));
    }
    let setup = AtlasSetup {
        size: size(args.quick),
        scenes: args.scenes,
    };
    let campaign = Campaign::new(&setup).map_err(|e| Failure(e.to_string()))?;
    let units = campaign.units();
    let work = |&u: &_| campaign.run_unit(u);
    match args.split.shard {
        Some(shard) => {
            let value = setup_value(&setup)?;
            args.split
                .run_shard(shard, "atlas", value, &units, out, work)
        }
        None => {
            let rows = run_units(&units, args.split.jobs, work)
                .into_iter()
                .collect::<Result<Vec<UnitRow>, String>>()
                .map_err(Failure)?;
            publish(out, &campaign, rows, &dir)
        }
    }
}

/// Writes the atlas's files from every unit's row and prints their paths
/// (the run with `--jobs`, and the merge of the shards).
pub fn publish(
    out: &mut impl Write,
    campaign: &Campaign,
    rows: Vec<UnitRow>,
    dir: &std::path::Path,
) -> Result<(), Failure> {
    if rows.len() != campaign.units().len() {
        return Err(Failure(format!(
            "{} rows for the atlas's {} units: the shards were run by another version",
            rows.len(),
            campaign.units().len()
        )));
    }
    let paths = campaign
        .publish(dir, rows)
        .map_err(|e| Failure(e.to_string()))?;
    print_paths(out, &paths)
}
