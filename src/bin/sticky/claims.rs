//! `sticky claims [--json|--markdown]`: the claims ledger.

use std::io::Write;

use sticky::claims::ledger::{self, Budget};
use sticky::report::progress::Bar;

use crate::{io_err, Failure};

/// The claims ledger: runs every checker of the paper's claims and prints
/// the computed statuses.
#[derive(clap::Args)]
pub struct Args {
    /// Print the ledger as JSON.
    #[arg(long, conflicts_with = "markdown")]
    json: bool,
    /// Print the ledger as a Markdown document (CLAIMS.md).
    #[arg(long)]
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
}

/// Runs `sticky claims`.
pub fn exec(args: Args, out: &mut impl Write) -> Result<(), Failure> {
    let budget = Budget::asked(
        Some(args.cases),
        Some(args.max_n),
        Some(args.scaling_max_n),
        None,
    );
    claims(out, budget, args.json, args.markdown)
}

fn claims(
    out: &mut impl Write,
    budget: Budget,
    as_json: bool,
    as_markdown: bool,
) -> Result<(), Failure> {
    // The claim being checked, the count and the time left, on a terminal
    // only (the bar is hidden when stderr is piped or redirected).
    let bar = Bar::for_command("claims");
    let entries = ledger::run(budget, &bar);
    let text = if as_json {
        ledger::json(&entries)
    } else if as_markdown {
        let proofs = sticky::prove::record::ledger_proofs().map_err(Failure)?;
        ledger::markdown(&entries, budget, &proofs)
    } else {
        ledger::table(&entries)
    };
    writeln!(out, "{}", text.trim_end()).map_err(io_err)
}
