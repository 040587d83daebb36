//! `--shard I/N` and `--jobs K`, shared by the campaign commands (`claims`,
//! `prove`, `converge`, `atlas`), and `sticky merge FILES…` (issue 38, item 3).

use std::io::Write;
use std::num::NonZeroUsize;

use sticky::campaign::file::{self, Header, ShardLines, UnitLine};
use sticky::campaign::jobs::run_units;
use sticky::campaign::Shard;

use crate::{io_err, Failure};

/// How a campaign command splits its work.
#[derive(clap::Args, Debug, Clone, Copy)]
pub struct Split {
    /// Run only shard I of N (I = 0 … N−1: the units u with u mod N = I)
    /// and print its results as JSON lines, for `sticky merge`.
    #[arg(long, value_name = "I/N")]
    pub shard: Option<Shard>,
    /// Units run at once on this machine (the output is the same for
    /// every K).
    #[arg(long, value_name = "K", default_value = "1")]
    pub jobs: NonZeroUsize,
}

impl Split {
    /// Runs this shard's units of `units` (`K` at a time) and writes the
    /// shard's file to `out`.
    pub fn run_shard<U, R, F>(
        self,
        shard: Shard,
        campaign: &str,
        setup: serde_json::Value,
        units: &[U],
        out: &mut impl Write,
        work: F,
    ) -> Result<(), Failure>
    where
        U: Sync,
        R: Send + serde::Serialize,
        F: Fn(&U) -> R + Sync,
    {
        let mine = shard.units(units.len());
        let results = run_units(&mine, self.jobs, |&u| work(&units[u]));
        let lines: Vec<UnitLine<R>> = mine
            .into_iter()
            .zip(results)
            .map(|(unit, result)| UnitLine { unit, result })
            .collect();
        let run = ShardLines {
            units: units.len(),
            lines,
        };
        write_shard(campaign, setup, shard, &run, out)
    }
}

/// Writes a shard's file.
pub fn write_shard<R: serde::Serialize>(
    campaign: &str,
    setup: serde_json::Value,
    shard: Shard,
    run: &ShardLines<R>,
    out: &mut impl Write,
) -> Result<(), Failure> {
    let header = Header {
        campaign: campaign.to_string(),
        setup,
        shard,
        units: run.units,
    };
    file::write(out, &header, &run.lines).map_err(io_err)
}

/// The setup as the header's JSON value.
pub fn setup_value(setup: &impl serde::Serialize) -> Result<serde_json::Value, Failure> {
    serde_json::to_value(setup).map_err(|e| Failure(format!("cannot write the setup: {e}")))
}
