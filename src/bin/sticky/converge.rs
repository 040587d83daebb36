//! `sticky converge SCENE`: the hydrodynamic limit, rates and charts.

use std::io::Write;
use std::path::PathBuf;

use sticky::progress::Progress;
use sticky::report::progress::Bar;
use sticky::scene::Scene;

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
}

/// Runs `sticky converge`.
pub fn exec(args: Args, out: &mut impl Write) -> Result<(), Failure> {
    let scene = load(&args.scene)?;
    let dir = args.out.unwrap_or_else(|| PathBuf::from("out/converge"));
    converge(out, &scene, dir, args.n_max, args.exact_max)
}

fn converge(
    out: &mut impl Write,
    scene: &Scene,
    dir: PathBuf,
    n_max: usize,
    exact_max: usize,
) -> Result<(), Failure> {
    use sticky::limit::converge::{converge_with_progress, ConvergeOptions};
    use sticky::report::converge::write_csv;
    let opts = ConvergeOptions {
        n_max: n_max.max(8),
        exact_max,
        ..ConvergeOptions::default()
    };
    // The scene, the N being computed, the count and the time left, on a
    // terminal only (hidden when stderr is piped or redirected).
    let bar = Bar::for_command("converge");
    let report = converge_with_progress(scene, &opts, &bar);
    bar.finish();
    let report = report.map_err(lib_err)?;
    if bar.cancelled() {
        return Err(Failure("converge: interrupted".to_string()));
    }
    std::fs::create_dir_all(&dir)
        .map_err(|e| Failure(format!("cannot create {}: {e}", dir.display())))?;
    writeln!(out, "{}", report.summary().trim_end()).map_err(io_err)?;
    let mut paths = write_csv(&report, &dir).map_err(lib_err)?;
    paths.extend(sticky::report::figures::convergence(&report, &dir).map_err(lib_err)?);
    print_paths(out, &paths)
}
