//! `sticky generate [--n N] [--seed S] [--format toml|csv|npy] [--out DIR]`:
//! a random admissible scene.

use std::io::Write;
use std::path::PathBuf;

use clap::ValueEnum;
use num_rational::BigRational;

use sticky::columns;
use sticky::generate::{dyadic_doubles, initial_data, Limits, SplitMix64};
use sticky::report::io::write_whole;
use sticky::{scene, InitialData, Scalar};

use crate::{io_err, print_paths, Failure};

/// Prints a random admissible `[particles]` scene (exact rationals, with
/// contacts, separating contacts and simultaneous collisions on purpose);
/// with `--format csv|npy`, writes the scene and its column file to --out
/// (with `--format toml --out DIR`, the scene to DIR).
#[derive(clap::Args)]
pub struct Args {
    /// Number of particles.
    #[arg(long, default_value_t = 1000)]
    n: usize,
    /// Seed of the generator (same seed, same scene).
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// `toml`: the whole scene on stdout (in --out when given); `csv`: a TOML scene naming a CSV
    /// column file of exact strings; `npy`: the same with an f64 `.npy` file
    /// (the data snapped to the grid 2^-32 so that every value is a double).
    #[arg(long, value_enum, default_value_t = Format::Toml)]
    format: Format,
    /// Folder for the scene and its column file (csv, npy; default
    /// ./out/generate/), or for the TOML scene (toml; default: stdout).
    #[arg(long)]
    out: Option<PathBuf>,
}

#[derive(Clone, Copy, PartialEq, Eq, ValueEnum)]
enum Format {
    /// One TOML file, printed.
    Toml,
    /// TOML + CSV of exact strings.
    Csv,
    /// TOML + NPY of doubles.
    Npy,
}

/// Runs `sticky generate`.
pub fn exec(args: Args, out: &mut impl Write) -> Result<(), Failure> {
    let n = args.n;
    if n == 0 || n > 10_000_000 {
        return Err(Failure(format!("--n must be in 1 ..= 10000000, got {n}")));
    }
    let data = random(n, args.seed);
    let mut name = format!("random-{n}-seed-{}", args.seed);
    if args.format == Format::Toml && args.out.is_none() {
        return write!(out, "{}", scene::particles_toml(&data, Some(&name))).map_err(io_err);
    }
    let dir = args.out.unwrap_or_else(|| PathBuf::from("out/generate"));
    std::fs::create_dir_all(&dir)
        .map_err(|e| Failure(format!("cannot create {}: {e}", dir.display())))?;
    if args.format == Format::Toml {
        let path = dir.join(format!("{name}.toml"));
        let toml = scene::particles_toml(&data, Some(&name));
        write_whole(&path, toml.as_bytes()).map_err(|e| Failure(e.to_string()))?;
        return print_paths(out, &[path]);
    }
    let (file, bytes, radius) = match args.format {
        Format::Npy => {
            name.push_str("-f64");
            let (radius, rows) = dyadic_doubles(&data, 32).ok_or_else(|| {
                Failure(format!(
                    "the scene of seed {} does not survive snapping to doubles (grid 2^-32); use --format csv or another seed",
                    args.seed
                ))
            })?;
            (format!("{name}.npy"), columns::write_npy(&rows), radius)
        }
        _ => {
            let csv = columns::write_csv(data.positions(), data.velocities());
            (
                format!("{name}.csv"),
                csv.into_bytes(),
                data.radius().clone(),
            )
        }
    };
    let toml = scene_toml(&name, &radius, &file, n);
    let scene_path = dir.join(format!("{name}.toml"));
    let data_path = dir.join(&file);
    write_whole(&data_path, &bytes).map_err(|e| Failure(e.to_string()))?;
    write_whole(&scene_path, toml.as_bytes()).map_err(|e| Failure(e.to_string()))?;
    print_paths(out, &[scene_path, data_path])
}

/// A random admissible datum of exactly `n` particles.
fn random(n: usize, seed: u64) -> InitialData<BigRational> {
    let mut rng = SplitMix64::new(seed);
    let limits = Limits {
        max_n: n,
        ..Default::default()
    };
    // Enough bytes for n particles even when every group is a single one.
    let mut bytes = rng.bytes(16 * n + 16);
    let mut data = initial_data(&bytes, limits);
    while data.n() < n {
        bytes.extend(rng.bytes(16 * n));
        data = initial_data(&bytes, limits);
    }
    data
}

/// The TOML of a scene whose columns live in `file`.
fn scene_toml(name: &str, radius: &BigRational, file: &str, n: usize) -> String {
    format!(
        "name = {}\ndescription = {}\n\n[particles]\nradius = \"{}\"\ndata = {}\n",
        sticky::text::string(name),
        sticky::text::string(&format!("{n} random particles (sticky generate)")),
        radius.render(),
        sticky::text::string(file)
    )
}
