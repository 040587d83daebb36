//! `sticky atlas [--quick] [--peers] [--scene NAME]…`: the speed-vs-accuracy atlas.

use std::io::{self, Write};
use std::path::PathBuf;

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
}

/// Runs `sticky atlas`.
pub fn exec(args: Args, out: &mut impl Write) -> Result<(), Failure> {
    let opts = sticky::report::atlas::AtlasOptions {
        quick: args.quick,
        out: args.out.unwrap_or_else(|| PathBuf::from("out/atlas")),
        peers: args.peers,
        scenes: args.scenes,
    };
    let tty = io::IsTerminal::is_terminal(&io::stderr());
    sticky::report::atlas::run(&opts, tty)
        .map_err(|e| Failure(e.to_string()))
        .and_then(|paths| print_paths(out, &paths))
}
