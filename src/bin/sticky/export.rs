//! `sticky export SCENE --format json|csv|npy [--out FILE]`: the scene's data
//! as a peer solver reads it (nearest doubles, their exact rounding errors,
//! the exact values alongside; see [`sticky::report::export`]).

use std::io::Write;
use std::path::PathBuf;

use clap::ValueEnum;

use sticky::report::export;

use crate::{io_err, load, print_paths, Failure};

/// The scene's data as a peer solver reads it.
#[derive(clap::Args)]
pub struct Args {
    /// Scene file (TOML; docs/guide/scenes.md).
    scene: PathBuf,
    /// json: exact strings, nearest doubles and rounding errors; csv: the
    /// same, one row per particle; npy: the (N, 2) '<f8' array of positions
    /// and velocities.
    #[arg(long, value_enum)]
    format: Format,
    /// Write here (whole: temporary name, then rename) instead of stdout.
    #[arg(long)]
    out: Option<PathBuf>,
}

#[derive(Clone, Copy, ValueEnum)]
enum Format {
    /// One JSON object.
    Json,
    /// CSV with a `#` comment line for the radius.
    Csv,
    /// NumPy .npy, (N, 2) little-endian f64.
    Npy,
}

/// Runs `sticky export`.
pub fn exec(args: Args, out: &mut impl Write) -> Result<(), Failure> {
    let scene = load(&args.scene)?;
    let e =
        export::export(&scene).map_err(|e| Failure(format!("{}: {e}", args.scene.display())))?;
    let bytes = match args.format {
        Format::Json => {
            let mut s = export::json(&scene, &e);
            s.push('\n');
            s.into_bytes()
        }
        Format::Csv => export::csv(&scene, &e).into_bytes(),
        Format::Npy => export::npy(&e),
    };
    match &args.out {
        None => {
            if matches!(args.format, Format::Npy)
                && std::io::IsTerminal::is_terminal(&std::io::stdout())
            {
                return Err(Failure(
                    "--format npy is binary: give --out FILE (or redirect stdout)".into(),
                ));
            }
            out.write_all(&bytes).map_err(io_err)
        }
        Some(path) => {
            let fail = |e: std::io::Error| Failure(format!("{}: {e}", path.display()));
            let name = path
                .file_name()
                .map(|n| n.to_string_lossy().into_owned())
                .unwrap_or_else(|| "export".into());
            let tmp = path.with_file_name(format!(".{name}.tmp"));
            std::fs::write(&tmp, &bytes).map_err(fail)?;
            std::fs::rename(&tmp, path).map_err(fail)?;
            print_paths(out, std::slice::from_ref(path))
        }
    }
}
