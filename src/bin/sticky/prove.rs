//! `sticky prove [--n N] [--claim ID] [--json]`: every per-case claim of the
//! paper proved for all real data at N = 1 … N, or refuted with an exact,
//! replayed counterexample (issue 11; the library's `sticky::prove`).

use std::io::Write;

use sticky::campaign::jobs::run_units;
use sticky::progress::Progress;
use sticky::prove::campaign::{self, ProveSetup, ProveUnit};
use sticky::prove::{self};
use sticky::report::progress::Bar;

use crate::campaign::{setup_value, Split};
use crate::{io_err, Failure};

/// Proves the section-2 claims for all real initial data at N = 1 … N.
#[derive(clap::Args)]
pub struct Args {
    /// Largest N (every N from --from to this one is done).
    #[arg(long, default_value_t = 3)]
    n: usize,
    /// Smallest N.
    #[arg(long, default_value_t = 1)]
    from: usize,
    /// Only this claim: a registry id (printed and corrected) or an id as
    /// printed in the output (with " (corrected)").
    #[arg(long)]
    claim: Option<String>,
    /// One JSON object per claim and N, one per line.
    #[arg(long, conflicts_with = "shard")]
    json: bool,
    /// Wall-clock budget per claim and N, in seconds (then `unknown`).
    #[arg(long, default_value_t = 600)]
    seconds: u64,
    /// Solver time limit per query, in milliseconds.
    #[arg(long, default_value_t = 20_000)]
    query_ms: u64,
    /// Memory cap of the solver process, in megabytes (z3's `-memory:`).
    #[arg(long, default_value_t = 2048)]
    solver_mb: u64,
    #[command(flatten)]
    split: Split,
}

/// The bar of one claim at one N: every note of the explorer is shown after
/// the claim's id and N.
struct ClaimBar<'a> {
    bar: &'a Bar,
    claim: String,
}

impl Progress for ClaimBar<'_> {
    fn advance(&self, steps: u64) {
        self.bar.advance(steps);
    }
    fn note(&self, what: &str) {
        self.bar.note(&format!("{}: {what}", self.claim));
    }
}

/// Runs `sticky prove`.
pub fn exec(args: Args, out: &mut impl Write) -> Result<(), Failure> {
    if args.n == 0 || args.n > 12 {
        return Err(Failure(format!("--n {} out of range (1 … 12)", args.n)));
    }
    let Some(version) = prove::solver_available() else {
        return Err(Failure(
            "the SMT solver z3 is not installed (Debian/Ubuntu: `apt-get install z3`; or set STICKY_Z3 to its path)".into(),
        ));
    };
    let setup = ProveSetup {
        from: args.from.max(1),
        n: args.n,
        claim: args.claim,
        seconds: args.seconds,
        query_ms: args.query_ms,
        solver_mb: args.solver_mb,
        solver: version,
    };
    let Some(units) = campaign::units(&setup) else {
        return Err(Failure(format!(
            "no per-case claim {:?} (see `sticky claims`)",
            setup.claim.unwrap_or_default()
        )));
    };
    let bar = Bar::for_command("prove");
    let work = |u: &ProveUnit| {
        let claim = format!("{}, N = {}", u.target.id, u.n);
        bar.stage(&claim, None);
        campaign::run_unit(u, &setup, &ClaimBar { bar: &bar, claim })
    };
    let result = match args.split.shard {
        Some(shard) => {
            let value = setup_value(&setup)?;
            args.split
                .run_shard(shard, "prove", value, &units, out, work)
        }
        None if args.split.jobs.get() > 1 => {
            let lines = run_units(&units, args.split.jobs, work);
            let text = campaign::render(&setup, &lines, campaign::Layout::of_flag(args.json));
            out.write_all(text.as_bytes()).map_err(io_err)
        }
        None => {
            if !args.json {
                out.write_all(campaign::table_head(&setup.solver).as_bytes())
                    .map_err(io_err)?;
            }
            for u in &units {
                let text = campaign::report_line(&work(u), campaign::Layout::of_flag(args.json));
                // The bar is lifted while the line is written, so that the
                // two do not interleave on a terminal.
                bar.indicatif()
                    .suspend(|| out.write_all(text.as_bytes()).and_then(|()| out.flush()))
                    .map_err(io_err)?;
            }
            Ok(())
        }
    };
    bar.finish();
    result
}
