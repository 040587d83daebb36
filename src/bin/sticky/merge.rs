//! `sticky merge FILES…`: the shards' files of one campaign (`--shard I/N`
//! of `claims` or `prove`) combined into the report a single
//! run prints.

use std::io::Write;
use std::path::PathBuf;

use serde::de::DeserializeOwned;
use sticky::campaign::file::{self, Merged};
use sticky::claims::campaign::{ClaimsSetup, UnitResult};

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
    if how.markdown && campaign != "claims" {
        return Err(Failure(format!(
            "--markdown is for the claims ledger, not `{campaign}`"
        )));
    }
    match campaign.as_str() {
        "prove" => {
            let (setup, lines) = merged(&files)?;
            let text = sticky::prove::campaign::render(&setup, &lines, how.json);
            out.write_all(text.as_bytes()).map_err(io_err)
        }
        "claims" => {
            let (setup, results) = merged::<ClaimsSetup, UnitResult>(&files)?;
            let entries = sticky::claims::campaign::entries(&setup, &results)
                .map_err(|e| Failure(format!("the shards do not make one ledger: {e}")))?;
            crate::claims::render(out, &entries, setup.into(), how.json, how.markdown)
        }
        other => Err(Failure(format!(
            "{name}: unknown campaign `{other}` (claims or prove)"
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
