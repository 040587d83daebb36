//! `sticky generate [--n N] [--seed S]`: a random admissible scene.

use std::io::Write;

use sticky::scene;

use crate::{io_err, Failure};

/// Prints a random admissible `[particles]` scene (exact rationals, with
/// contacts, separating contacts and simultaneous collisions on purpose).
#[derive(clap::Args)]
pub struct Args {
    /// Number of particles.
    #[arg(long, default_value_t = 1000)]
    n: usize,
    /// Seed of the generator (same seed, same scene).
    #[arg(long, default_value_t = 1)]
    seed: u64,
}

/// Runs `sticky generate`.
pub fn exec(args: Args, out: &mut impl Write) -> Result<(), Failure> {
    generate(out, args.n, args.seed)
}

fn generate(out: &mut impl Write, n: usize, seed: u64) -> Result<(), Failure> {
    if n == 0 || n > 10_000_000 {
        return Err(Failure(format!("--n must be in 1 ..= 10000000, got {n}")));
    }
    let mut rng = sticky::generate::SplitMix64::new(seed);
    let limits = sticky::generate::Limits {
        max_n: n,
        ..Default::default()
    };
    // Enough bytes for n particles even when every group is a single one.
    let mut bytes = rng.bytes(16 * n + 16);
    let mut data = sticky::generate::initial_data(&bytes, limits);
    while data.n() < n {
        bytes.extend(rng.bytes(16 * n));
        data = sticky::generate::initial_data(&bytes, limits);
    }
    let name = format!("random-{n}-seed-{seed}");
    write!(out, "{}", scene::particles_toml(&data, Some(&name))).map_err(io_err)
}
