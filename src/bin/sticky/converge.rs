//! `sticky converge SCENE`: the hydrodynamic limit, rates and charts.

use std::io::Write;
use std::path::{Path, PathBuf};

use sticky::campaign::jobs::run_units;
use sticky::limit::converge::campaign::ConvergeSetup;
use sticky::limit::converge::{ConvergenceReport, Study, Unit, UnitResult};
use sticky::progress::Progress;
use sticky::report::progress::Bar;

use crate::campaign::{setup_value, Split};
use crate::{io_err, lib_err, load, print_paths, Failure};

/// The hydrodynamic limit: distances between the particles and the
/// continuum solution for N = 8 … 2^16, with fitted rates; CSV and charts.
#[derive(clap::Args)]
pub struct Args {
    /// A `[macro]` scene.
    scene: PathBuf,
    /// Output folder (default ./out/converge/).
    #[arg(long)]
    out: Option<PathBuf>,
    /// Largest N (a power of two).
    #[arg(long, default_value_t = 65536)]
    n_max: usize,
    /// Largest N computed exactly (beyond: f64 through the same code).
    #[arg(long, default_value_t = 4096)]
    exact_max: usize,
    #[command(flatten)]
    split: Split,
}

/// The output folder when none is given.
pub const DEFAULT_OUT: &str = "out/converge";

/// Runs `sticky converge`.
pub fn exec(args: Args, out: &mut impl Write) -> Result<(), Failure> {
    use sticky::limit::converge::{converge_with_progress, ConvergeOptions};
    let scene = load(&args.scene)?;
    let dir = args.out.unwrap_or_else(|| PathBuf::from(DEFAULT_OUT));
    if args.split.shard.is_none() && args.split.jobs.get() == 1 {
        let opts = ConvergeOptions {
            n_max: args.n_max.max(8),
            exact_max: args.exact_max,
            ..ConvergeOptions::default()
        };
        // The scene, the N being computed, the count and the time left, on
        // a terminal only (hidden when stderr is piped or redirected).
        let bar = Bar::for_command("converge");
        let report = converge_with_progress(&scene, &opts, &bar);
        bar.finish();
        let report = report.map_err(lib_err)?;
        if bar.cancelled() {
            return Err(Failure("converge: interrupted".to_string()));
        }
        return publish(out, &report, &dir);
    }
    let text = std::fs::read_to_string(&args.scene)
        .map_err(|e| Failure(format!("{}: {e}", args.scene.display())))?;
    let setup = ConvergeSetup {
        scene: text,
        n_max: args.n_max,
        exact_max: args.exact_max,
    };
    let study = Study::new(&scene, &setup.options()).map_err(lib_err)?;
    let units = study.units();
    let work = |&u: &Unit| study.run_unit(u).map_err(|e| e.to_string());
    match args.split.shard {
        Some(shard) => {
            let value = setup_value(&setup)?;
            args.split
                .run_shard(shard, "converge", value, &units, out, work)
        }
        None => {
            let results = run_units(&units, args.split.jobs, work)
                .into_iter()
                .collect::<Result<Vec<UnitResult>, String>>()
                .map_err(Failure)?;
            publish(out, &study.report(&results).map_err(lib_err)?, &dir)
        }
    }
}

/// Prints the summary and writes the CSV files and the charts into `dir`
/// (a single run's output, and the merge's).
pub fn publish(
    out: &mut impl Write,
    report: &ConvergenceReport,
    dir: &Path,
) -> Result<(), Failure> {
    use sticky::report::converge::write_csv;
    std::fs::create_dir_all(dir)
        .map_err(|e| Failure(format!("cannot create {}: {e}", dir.display())))?;
    writeln!(out, "{}", report.summary().trim_end()).map_err(io_err)?;
    let mut paths = write_csv(report, dir).map_err(lib_err)?;
    paths.extend(sticky::report::figures::convergence(report, dir).map_err(lib_err)?);
    print_paths(out, &paths)
}
