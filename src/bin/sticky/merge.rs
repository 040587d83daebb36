//! `sticky merge FILES…`: the shards' files of one campaign (`--shard I/N`
//! of `claims`, `prove`, `converge` or `atlas`) combined into the report a
//! single run prints (for `converge` and `atlas`, with their files under
//! `--out`).

use std::io::Write;
use std::path::PathBuf;

use serde::de::DeserializeOwned;
use sticky::campaign::file::{self, Merged};
use sticky::claims::campaign::{self as ledger, ClaimsSetup};
use sticky::limit::converge::campaign::ConvergeSetup;
use sticky::limit::converge::UnitResult;
use sticky::report::atlas::campaign::{AtlasSetup, Campaign, UnitRow};

use crate::{io_err, Failure};

/// Combines the shards' files of one campaign into the single run's report.
#[derive(clap::Args)]
pub struct Args {
    /// Every shard's file (`sticky COMMAND --shard I/N > FILE`), any order.
    #[arg(required = true)]
    files: Vec<PathBuf>,
    /// The report as JSON (`claims --json`, `prove --json`).
    #[arg(long, conflicts_with = "markdown")]
    json: bool,
    /// The claims ledger as Markdown (`claims --markdown`).
    #[arg(long)]
    markdown: bool,
    /// The output folder of a campaign that writes files (`converge`,
    /// `atlas`; default, as for the single run, ./out/converge/ or
    /// ./out/atlas/).
    #[arg(long)]
    out: Option<PathBuf>,
}

/// How the merged report is printed.
pub struct Rendering {
    /// `--json`.
    pub json: bool,
    /// `--markdown`.
    pub markdown: bool,
}

/// Runs `sticky merge`.
pub fn exec(args: Args, out: &mut impl Write) -> Result<(), Failure> {
    let mut files = Vec::with_capacity(args.files.len());
    for path in &args.files {
        let text = std::fs::read_to_string(path)
            .map_err(|e| Failure(format!("{}: {e}", path.display())))?;
        files.push((path.display().to_string(), text));
    }
    let (name, text) = &files[0];
    let campaign = file::header(name, text)
        .map_err(|e| Failure(e.to_string()))?
        .campaign;
    let how = Rendering {
        json: args.json,
        markdown: args.markdown,
    };
    let writes_files = ["converge", "atlas"].contains(&campaign.as_str());
    if args.out.is_some() && !writes_files {
        return Err(Failure(format!(
            "--out is for campaigns that write files (converge, atlas), not `{campaign}`"
        )));
    }
    if how.json && writes_files {
        return Err(Failure(format!(
            "--json is for the claims ledger and prove, not `{campaign}`"
        )));
    }
    if how.markdown && campaign != "claims" {
        return Err(Failure(format!(
            "--markdown is for the claims ledger, not `{campaign}`"
        )));
    }
    match campaign.as_str() {
        "prove" => {
            let (setup, lines) = merged(&files)?;
            let text = sticky::prove::campaign::render(
                &setup,
                &lines,
                sticky::prove::campaign::Layout::of_flag(how.json),
            );
            out.write_all(text.as_bytes()).map_err(io_err)
        }
        "claims" => {
            let (setup, results) = merged::<ClaimsSetup, ledger::UnitResult>(&files)?;
            let entries = sticky::claims::campaign::entries(&setup, &results)
                .map_err(|e| Failure(format!("the shards do not make one ledger: {e}")))?;
            crate::claims::render(
                out,
                &entries,
                setup.into(),
                crate::claims::Layout::of_flags(how.json, how.markdown),
            )
        }
        "converge" => {
            let (setup, results) = merged::<ConvergeSetup, Result<UnitResult, String>>(&files)?;
            let results = results
                .into_iter()
                .collect::<Result<Vec<_>, _>>()
                .map_err(|e| Failure(format!("a shard's unit failed: {e}")))?;
            let study = setup
                .study()
                .map_err(|e| Failure(format!("{name}: the campaign's scene: {e}")))?;
            let report = study.report(&results).map_err(crate::lib_err)?;
            let dir = args
                .out
                .unwrap_or_else(|| PathBuf::from(crate::converge::DEFAULT_OUT));
            crate::converge::publish(out, &report, &dir)
        }
        "atlas" => {
            let (setup, results) = merged::<AtlasSetup, Result<UnitRow, String>>(&files)?;
            let rows = results
                .into_iter()
                .collect::<Result<Vec<_>, _>>()
                .map_err(|e| Failure(format!("a shard's unit failed: {e}")))?;
            let campaign = Campaign::new(&setup)
                .map_err(|e| Failure(format!("{name}: the campaign's scenes: {e}")))?;
            let dir = args
                .out
                .unwrap_or_else(|| PathBuf::from(crate::atlas::DEFAULT_OUT));
            crate::atlas::publish(out, &campaign, rows, &dir)
        }
        other => Err(Failure(format!(
            "{name}: unknown campaign `{other}` (claims, prove, converge or atlas)"
        ))),
    }
}

/// The merged results and the campaign's setup, typed.
fn merged<S: DeserializeOwned, R: DeserializeOwned>(
    files: &[(String, String)],
) -> Result<(S, Vec<R>), Failure> {
    let Merged { setup, results, .. } =
        file::merge::<R>(files).map_err(|e| Failure(e.to_string()))?;
    let setup = serde_json::from_value(setup)
        .map_err(|e| Failure(format!("{}: not this campaign's setup: {e}", files[0].0)))?;
    Ok((setup, results))
}
