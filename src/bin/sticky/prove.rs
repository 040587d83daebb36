//! `sticky prove [--n N] [--claim ID] [--json]`: every per-case claim of the
//! paper proved for all real data at N = 1 … N, or refuted with an exact,
//! replayed counterexample (issue 11; the library's `sticky::prove`).

use std::io::Write;
use std::time::Duration;

use sticky::progress::Progress;
use sticky::prove::{self, ProofLimits, Status};
use sticky::report::progress::Bar;

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
    #[arg(long)]
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
    let targets: Vec<_> = prove::targets()
        .into_iter()
        .filter(|t| {
            args.claim
                .as_deref()
                .is_none_or(|c| t.id == c || t.registry_id == c)
        })
        .collect();
    if targets.is_empty() {
        return Err(Failure(format!(
            "no per-case claim {:?} (see `sticky claims`)",
            args.claim.unwrap_or_default()
        )));
    }
    let limits = ProofLimits {
        time: Duration::from_secs(args.seconds.max(1)),
        query_ms: args.query_ms.max(100),
        solver_memory_mb: args.solver_mb.max(64),
        ..ProofLimits::default()
    };
    let bar = Bar::for_command("prove");
    if !args.json {
        writeln!(out, "solver: {version}").map_err(io_err)?;
        writeln!(
            out,
            "hypotheses: all real x⁰ ∈ K^N, u⁰ ∈ C_x⁰, 2r = 1/N; all real t ≥ 0 (0 ≤ s ≤ t for two-time claims)"
        )
        .map_err(io_err)?;
        writeln!(
            out,
            "{:<52} {:>2} {:>8} {:>7} {:>8} {:>8}  erratum",
            "claim", "N", "status", "paths", "queries", "seconds"
        )
        .map_err(io_err)?;
    }
    for n in args.from.max(1)..=args.n {
        for t in &targets {
            let claim = format!("{}, N = {n}", t.id);
            bar.stage(&claim, None);
            let r = prove::prove_target_observed(t, n, limits, &ClaimBar { bar: &bar, claim });
            let mut text = String::new();
            if args.json {
                text.push_str(&prove::json::line(&r, t.erratum));
                text.push('\n');
            } else {
                text.push_str(&format!(
                    "{:<52} {:>2} {:>8} {:>7} {:>8} {:>8.2}  {}\n",
                    r.id,
                    r.n,
                    r.status.as_str(),
                    r.paths,
                    r.queries,
                    r.seconds,
                    if t.erratum { "yes" } else { "" }
                ));
                if r.status == Status::Unknown {
                    if let Some(note) = &r.note {
                        text.push_str(&format!("    unknown: {note}\n"));
                    }
                }
            }
            // The bar is lifted while the line is written, so that the two
            // do not interleave on a terminal.
            bar.indicatif()
                .suspend(|| out.write_all(text.as_bytes()).and_then(|()| out.flush()))
                .map_err(io_err)?;
        }
    }
    bar.finish();
    Ok(())
}
