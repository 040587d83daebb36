//! `sticky claims [--json|--markdown]`: the claims ledger.

use std::io::Write;

use sticky::claims::campaign::{self, ClaimsSetup};
use sticky::claims::ledger::{self, Budget, Entry};
use sticky::report::progress::Bar;

use crate::campaign::{setup_value, write_shard, Split};
use crate::{io_err, Failure};

/// The claims ledger: runs every checker of the paper's claims and prints
/// the computed statuses.
#[derive(clap::Args)]
pub struct Args {
    /// Print the ledger as JSON.
    #[arg(long, conflicts_with_all = ["markdown", "shard"])]
    json: bool,
    /// Print the ledger as a Markdown document (CLAIMS.md).
    #[arg(long, conflicts_with = "shard")]
    markdown: bool,
    /// Random cases per claim.
    #[arg(long, default_value_t = Budget::default().cases)]
    cases: usize,
    /// Largest N of a random case.
    #[arg(long, default_value_t = Budget::default().max_n)]
    max_n: usize,
    /// Largest N of the checks across N (a power of two).
    #[arg(long, default_value_t = Budget::default().scaling_max_n)]
    scaling_max_n: usize,
    #[command(flatten)]
    split: Split,
}

/// Runs `sticky claims`.
pub fn exec(args: Args, out: &mut impl Write) -> Result<(), Failure> {
    let budget = Budget::asked(
        Some(args.cases),
        Some(args.max_n),
        Some(args.scaling_max_n),
        None,
    );
    // The claim being checked, the count and the time left, on a terminal
    // only (the bar is hidden when stderr is piped or redirected).
    let bar = Bar::for_command("claims");
    let setup = ClaimsSetup::from(budget);
    if let Some(shard) = args.split.shard {
        let lines = campaign::run_shard(&setup, shard, args.split.jobs, &bar);
        return write_shard("claims", setup_value(&setup)?, shard, &lines, out);
    }
    let entries = if args.split.jobs.get() > 1 {
        campaign::run_jobs(budget, args.split.jobs, &bar).map_err(Failure)?
    } else {
        ledger::run(budget, &bar)
    };
    render(
        out,
        &entries,
        budget,
        Layout::of_flags(args.json, args.markdown),
    )
}

/// How the ledger is printed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Layout {
    /// A table for people.
    Table,
    /// The JSON contract (`--json`).
    Json,
    /// The Markdown of `CLAIMS.md`, with the proof record's column
    /// (`--markdown`).
    Markdown,
}

impl Layout {
    /// The layout the flags ask for (`--json` wins, as it always has).
    pub fn of_flags(json: bool, markdown: bool) -> Layout {
        match (json, markdown) {
            (true, _) => Layout::Json,
            (false, true) => Layout::Markdown,
            (false, false) => Layout::Table,
        }
    }
}

/// Prints the ledger in `layout`.
pub fn render(
    out: &mut impl Write,
    entries: &[Entry],
    budget: Budget,
    layout: Layout,
) -> Result<(), Failure> {
    let text = match layout {
        Layout::Json => ledger::json(entries),
        Layout::Markdown => {
            let proofs = sticky::prove::record::ledger_proofs().map_err(Failure)?;
            ledger::markdown(entries, budget, &proofs)
        }
        Layout::Table => ledger::table(entries),
    };
    writeln!(out, "{}", text.trim_end()).map_err(io_err)
}
