//! The `sticky` command line: a thin layer over the library.
//!
//! * `sticky` — runs the embedded default scene (Appendix C's two blocks) and
//!   prints a short summary: collisions, final clusters, checks passed.
//! * `sticky run SCENE --at T [--at T2 …] [--json]` — the state at each time.
//! * `sticky events SCENE [--json]` — every collision.
//! * `sticky check SCENE` — the summary of the default run, for any scene.
//!
//! Errors go to stderr as one line `error: SCENE: message`, exit code 1.

use std::io::{self, BufWriter, Write};
use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, Subcommand, ValueEnum};
use num_rational::BigRational;

use sticky::claims::ledger::{self, Budget};
use sticky::claims::micro::{check_trajectory, probe_times};
use sticky::cluster::Cluster;
use sticky::kernel::{self, IntegerData};
use sticky::projection::state_at;
use sticky::rational::parse_exact;
use sticky::scene::{self, Scene, SceneKind};
use sticky::trajectory::Trajectory;
use sticky::{json, Scalar, State};

#[derive(Parser)]
#[command(
    name = "sticky",
    version,
    about = "Exact sticky particles on a line (Signorini constraint), after C. Perrin's 'Microscopic derivation of the one-dimensional constrained Euler equations'.",
    long_about = None
)]
struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
}

#[derive(Subcommand)]
enum Command {
    /// The state x(t), u(t), λ(t) and the contact clusters at each requested time.
    Run {
        /// Scene file (TOML, see DESIGN.md §2).
        scene: PathBuf,
        /// A time t ≥ 0, exact: "3/2", "0.125", "1e-3" (repeat for several).
        #[arg(long = "at", required = true, allow_hyphen_values = true, value_parser = parse_time)]
        at: Vec<BigRational>,
        /// One JSON object per time (the interop contract, DESIGN.md §3).
        #[arg(long)]
        json: bool,
        /// Which exact algorithm answers: the one-shot projection P_K(x⁰+tu⁰)
        /// (O(N) per time, on the integer kernel) or the event-driven merge
        /// (O(N log N) once).
        #[arg(long, value_enum, default_value_t = Engine::Projection)]
        engine: Engine,
        /// Which model answers: the N particles of the scene, or (for a
        /// `[macro]` scene) the continuum solution of its macroscopic datum,
        /// block by block, whose cost does not grow with N.
        #[arg(long, value_enum, default_value_t = Model::Particles)]
        model: Model,
    },
    /// Every collision: time, cluster formed, sizes of the clusters that merged.
    Events {
        /// Scene file (TOML).
        scene: PathBuf,
        /// `{"events": [...]}` (the interop contract, DESIGN.md §3).
        #[arg(long)]
        json: bool,
    },
    /// Summary of a scene: collisions, final clusters, and the section-2
    /// checks (event-driven = projection, signs of λ and of the pressure).
    Check {
        /// Scene file (TOML).
        scene: PathBuf,
    },
    /// Prints a random admissible `[particles]` scene (exact rationals, with
    /// contacts, separating contacts and simultaneous collisions on purpose).
    Generate {
        /// Number of particles.
        #[arg(long, default_value_t = 1000)]
        n: usize,
        /// Seed of the generator (same seed, same scene).
        #[arg(long, default_value_t = 1)]
        seed: u64,
    },
    /// PAVA at one time on random scenes: every method timed in one run on
    /// fresh inputs, with the ratio to our f64 PAVA and the Python peers.
    Bench {
        /// Number of particles.
        #[arg(long, default_value_t = 1_000_000)]
        n: usize,
        /// Repetitions, each on a fresh scene (default 3; 2 with --quick).
        #[arg(long)]
        reps: Option<usize>,
        /// Quick run (under two minutes at N = 10^6): no event-driven
        /// trajectory, 2 repetitions.
        #[arg(long)]
        quick: bool,
        /// Skip the Python peers.
        #[arg(long)]
        no_peers: bool,
        /// Print JSON.
        #[arg(long)]
        json: bool,
        /// The time t of the projection (small: few clusters; large: few
        /// large clusters).
        #[arg(long, default_value = "1/100", value_parser = parse_time)]
        at: BigRational,
        /// Measure peak memory (cold allocator, no warm-up: timings then
        /// include page faults).
        #[arg(long)]
        memory: bool,
        /// The scaling study: N = 10^3, 10^4, … up to --max-n, both regimes
        /// (t = 1/100: almost no clusters; t = 20: few large clusters);
        /// CSV, log-log charts and fitted slopes in --out.
        #[arg(long)]
        scaling: bool,
        /// Largest N of the scaling study.
        #[arg(long, default_value_t = 10_000_000)]
        max_n: usize,
        /// Output folder of the scaling study (default ./out/bench/).
        #[arg(long)]
        out: Option<PathBuf>,
    },
    /// The hydrodynamic limit: distances between the particles and the
    /// continuum solution for N = 8 … 2^16, with fitted rates; CSV and charts.
    Converge {
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
    },
    /// Pictures of a scene: space-time diagram of the worldlines, density
    /// heat map, pressure impulses (SVG and PNG).
    Plot {
        /// Scene file (TOML).
        scene: PathBuf,
        /// Output folder (default ./out/plot/).
        #[arg(long)]
        out: Option<PathBuf>,
        /// Horizon (default: the scene's t_end, else 1 after the last collision).
        #[arg(long, value_parser = parse_time)]
        t_end: Option<BigRational>,
    },
    /// The speed-vs-accuracy atlas of the floating-point reference solvers
    /// against the exact engine: CSV, charts and the stability table.
    Atlas {
        /// The small suite (well under a minute).
        #[arg(long)]
        quick: bool,
        /// Output folder (default ./out/atlas/).
        #[arg(long)]
        out: Option<PathBuf>,
    },
    /// The claims ledger: runs every checker of the paper's claims and prints
    /// the computed statuses.
    Claims {
        /// Print the ledger as JSON.
        #[arg(long, conflicts_with = "markdown")]
        json: bool,
        /// Print the ledger as a Markdown document (CLAIMS.md).
        #[arg(long)]
        markdown: bool,
        /// Random cases per claim.
        #[arg(long, default_value_t = Budget::default().cases)]
        cases: usize,
        /// Largest N of a random case.
        #[arg(long, default_value_t = Budget::default().max_n)]
        max_n: usize,
        /// Largest N of the checks across N (a power of two).
        #[arg(long, default_value_t = Budget::default().scaling_max_n)]
        scaling_max_n: usize,
    },
}

#[derive(Clone, Copy, PartialEq, Eq, ValueEnum)]
enum Model {
    /// The N particles (exact).
    Particles,
    /// The continuum solution X(t) = P_K(X⁰ + tU⁰) of a `[macro]` datum
    /// (exact: rationals and quadratic surds).
    Continuum,
}

#[derive(Clone, Copy, ValueEnum)]
enum Engine {
    /// x(t) = P_K(x⁰ + t u⁰) by pool-adjacent-violators.
    Projection,
    /// The event-driven cluster merge.
    Events,
}

fn parse_time(s: &str) -> Result<BigRational, String> {
    let t = parse_exact(s).map_err(|e| e.to_string())?;
    if t < <BigRational as Scalar>::zero() {
        return Err(format!("time {s} is negative"));
    }
    Ok(t)
}

/// What went wrong, already phrased for the user.
struct Failure(String);

fn load(path: &std::path::Path) -> Result<Scene, Failure> {
    scene::load(path).map_err(|e| Failure(format!("{}: {e}", path.display())))
}

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        // --help, --version: clap's own output on stdout.
        Err(e) if !e.use_stderr() => {
            let _ = e.print();
            return ExitCode::SUCCESS;
        }
        // One line, as for every other error: clap's first paragraph (no
        // usage or help hints), joined.
        Err(e) => {
            let text = e.render().to_string();
            let lines: Vec<&str> = text
                .lines()
                .take_while(|l| !l.trim().is_empty())
                .map(str::trim)
                .collect();
            let message = lines.join(" ");
            let message = message.strip_prefix("error: ").unwrap_or(&message);
            eprintln!("error: {message}");
            return ExitCode::from(2);
        }
    };
    if let Some(Command::Bench { memory, .. }) = &cli.command {
        let mode = if *memory {
            sticky::bench::Memory::Cold
        } else {
            sticky::bench::Memory::Warm
        };
        if let Some(code) = sticky::bench::reexec_with_malloc(mode) {
            return code;
        }
    }
    let stdout = io::stdout();
    let mut out = BufWriter::new(stdout.lock());
    let result = match cli.command {
        None => scene::default_scene()
            .map_err(|e| Failure(format!("embedded default scene: {e}")))
            .and_then(|s| summary(&mut out, &s, "embedded default scene")),
        Some(Command::Run {
            scene,
            at,
            json,
            engine,
            model: Model::Particles,
        }) => load(&scene).and_then(|s| run(&mut out, &s, &at, json, engine)),
        Some(Command::Run {
            scene: path,
            at,
            json,
            model: Model::Continuum,
            ..
        }) => load(&path).and_then(|s| run_continuum(&mut out, &s, &path, &at, json)),
        Some(Command::Events { scene, json }) => {
            load(&scene).and_then(|s| events(&mut out, &s, json))
        }
        Some(Command::Claims {
            json,
            markdown,
            cases,
            max_n,
            scaling_max_n,
        }) => claims(
            &mut out,
            Budget {
                cases,
                max_n: max_n.max(1),
                scaling_max_n: scaling_max_n.max(8),
                ..Budget::default()
            },
            json,
            markdown,
        ),
        Some(Command::Bench {
            reps,
            no_peers,
            memory,
            scaling: true,
            max_n,
            out: dir,
            ..
        }) => {
            let mut ns = Vec::new();
            let mut n = 1000usize;
            while n <= max_n {
                ns.push(n);
                n = n.saturating_mul(10);
            }
            let opts = sticky::bench::ScalingOptions {
                ns,
                reps: reps.unwrap_or(3),
                peers: !no_peers,
                memory,
                out: dir.unwrap_or_else(|| PathBuf::from("out/bench")),
            };
            let scripts = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scripts");
            sticky::bench::scaling(&opts, &scripts, |msg| eprintln!("bench: {msg}"))
                .map_err(|e| Failure(e.to_string()))
                .and_then(|(rows, paths)| {
                    for &(regime, _, _) in &sticky::bench::REGIMES {
                        let line = sticky::bench::slopes(&rows, regime, memory)
                            .iter()
                            .map(|(m, s)| format!("{m} {s:.2}"))
                            .collect::<Vec<_>>()
                            .join(", ");
                        writeln!(
                            out,
                            "{regime}: log-log slope of the total {} against N: {line}",
                            if memory { "memory" } else { "time" }
                        )
                        .map_err(io_err)?;
                    }
                    print_paths(&mut out, &paths)
                })
        }
        Some(Command::Bench {
            n,
            reps,
            quick,
            no_peers,
            json,
            at,
            memory,
            scaling: false,
            ..
        }) => {
            let opts = sticky::bench::BenchOptions {
                n,
                reps: reps.unwrap_or(if quick { 2 } else { 3 }),
                peers: !no_peers,
                events: !quick,
                memory,
            };
            let scripts = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scripts");
            let report = sticky::bench::run(&opts, &at, &scripts);
            let text = if json {
                sticky::bench::json(&report)
            } else {
                sticky::bench::table(&report)
            };
            writeln!(out, "{}", text.trim_end()).map_err(io_err)
        }
        Some(Command::Converge {
            scene,
            out: dir,
            n_max,
            exact_max,
        }) => load(&scene).and_then(|s| {
            converge(
                &mut out,
                &s,
                dir.unwrap_or_else(|| PathBuf::from("out/converge")),
                n_max,
                exact_max,
            )
        }),
        Some(Command::Plot {
            scene,
            out: dir,
            t_end,
        }) => load(&scene).and_then(|s| {
            plot(
                &mut out,
                &s,
                dir.unwrap_or_else(|| PathBuf::from("out/plot")),
                t_end,
            )
        }),
        Some(Command::Atlas { quick, out: dir }) => {
            let opts = sticky::atlas::AtlasOptions {
                quick,
                out: dir.unwrap_or_else(|| PathBuf::from("out/atlas")),
            };
            let tty = io::IsTerminal::is_terminal(&io::stderr());
            sticky::atlas::run(&opts, tty)
                .map_err(|e| Failure(e.to_string()))
                .and_then(|paths| print_paths(&mut out, &paths))
        }
        Some(Command::Generate { n, seed }) => generate(&mut out, n, seed),
        Some(Command::Check { scene }) => {
            load(&scene).and_then(|s| summary(&mut out, &s, &scene.display().to_string()))
        }
    };
    let flushed = out.flush();
    match result {
        Ok(()) if flushed.is_ok() || is_broken_pipe(&flushed) => ExitCode::SUCCESS,
        Ok(()) => {
            eprintln!("error: cannot write the output: {:?}", flushed.err());
            ExitCode::FAILURE
        }
        Err(Failure(msg)) if msg.is_empty() => ExitCode::SUCCESS,
        Err(Failure(msg)) => {
            eprintln!("error: {msg}");
            ExitCode::FAILURE
        }
    }
}

fn is_broken_pipe(r: &io::Result<()>) -> bool {
    matches!(r, Err(e) if e.kind() == io::ErrorKind::BrokenPipe)
}

/// Maps a write error to a failure; a closed pipe ends the output quietly.
fn io_err(e: io::Error) -> Failure {
    if e.kind() == io::ErrorKind::BrokenPipe {
        Failure(String::new())
    } else {
        Failure(format!("cannot write the output: {e}"))
    }
}

fn run(
    out: &mut impl Write,
    scene: &Scene,
    times: &[BigRational],
    as_json: bool,
    engine: Engine,
) -> Result<(), Failure> {
    let data = &scene.data;
    let traj = match engine {
        Engine::Events => Some(sticky::merge::trajectory(data)),
        Engine::Projection => None,
    };
    // The projection runs on the integer kernel (common denominators, i128
    // when the data fit): the same exact result as the generic path.
    let ints = traj.is_none().then(|| IntegerData::new(data));
    for t in times {
        let state = match (&traj, &ints) {
            (Some(traj), _) => traj.at(t),
            (None, Some(ints)) => kernel::state_at(ints, t),
            (None, None) => state_at(data, t),
        }
        .map_err(|e| Failure(e.to_string()))?;
        if as_json {
            writeln!(out, "{}", json::state(&state, data.radius())).map_err(io_err)?;
        } else {
            write_state_table(out, &state, data.radius()).map_err(io_err)?;
        }
    }
    Ok(())
}

/// `sticky run --model continuum`: the block-level continuum solution.
fn run_continuum(
    out: &mut impl Write,
    scene: &Scene,
    path: &std::path::Path,
    times: &[BigRational],
    as_json: bool,
) -> Result<(), Failure> {
    let SceneKind::Macro { datum, particles } = &scene.kind else {
        return Err(Failure(format!(
            "{}: --model continuum needs a [macro] scene (a [particles] scene has no macroscopic datum)",
            path.display()
        )));
    };
    let c = sticky::limit::continuum::Continuum::new(datum);
    for t in times {
        let p = c.profile(t).map_err(|e| Failure(e.to_string()))?;
        if as_json {
            writeln!(out, "{}", json::continuum_profile(&p)).map_err(io_err)?;
            continue;
        }
        writeln!(
            out,
            "model: continuum — X(t) = P_K(X⁰ + tU⁰) on the macroscopic datum ({} blocks), exact; the scene's N = {particles} is not used",
            datum.blocks().len()
        )
        .map_err(io_err)?;
        writeln!(out, "t = {}", sticky::rational::render_exact(t)).map_err(io_err)?;
        let poly = |c: &[sticky::limit::surd::Surd]| -> String {
            let mut terms = Vec::new();
            for (k, v) in c.iter().enumerate() {
                if v.to_string() == "0" {
                    continue;
                }
                terms.push(match k {
                    0 => format!("{v}"),
                    1 => format!("({v})·w"),
                    _ => format!("({v})·w²"),
                });
            }
            if terms.is_empty() {
                "0".into()
            } else {
                terms.join(" + ")
            }
        };
        let rows: Vec<Vec<String>> = p
            .segments
            .iter()
            .map(|g| {
                vec![
                    format!("[{}, {}]", g.w0, g.w1),
                    (g.block + 1).to_string(),
                    g.plateau.map_or("—".into(), |k| (k + 1).to_string()),
                    poly(&g.x),
                    poly(&g.u),
                    poly(&g.lambda),
                ]
            })
            .collect();
        write_table(
            out,
            &[
                "w (mass)",
                "block",
                "congested",
                "X(t, w)",
                "U(t, w)",
                "Λ(t, w)",
            ],
            &rows,
        )
        .map_err(io_err)?;
    }
    Ok(())
}

fn range_1based(c: &Cluster) -> String {
    if c.size == 1 {
        format!("{}", c.first + 1)
    } else {
        format!("{}–{}", c.first + 1, c.end())
    }
}

/// Left-aligned columns, two spaces apart.
fn write_table(out: &mut impl Write, header: &[&str], rows: &[Vec<String>]) -> io::Result<()> {
    let mut widths: Vec<usize> = header.iter().map(|h| h.chars().count()).collect();
    for row in rows {
        for (w, cell) in widths.iter_mut().zip(row) {
            *w = (*w).max(cell.chars().count());
        }
    }
    let line = |cells: Vec<&str>| -> String {
        let padded: Vec<String> = cells
            .iter()
            .zip(&widths)
            .map(|(c, w)| format!("{c}{}", " ".repeat(w - c.chars().count())))
            .collect();
        format!("  {}", padded.join("  ").trim_end())
    };
    writeln!(out, "{}", line(header.to_vec()))?;
    for row in rows {
        writeln!(out, "{}", line(row.iter().map(String::as_str).collect()))?;
    }
    Ok(())
}

fn write_state_table(
    out: &mut impl Write,
    s: &State<BigRational>,
    radius: &BigRational,
) -> io::Result<()> {
    writeln!(
        out,
        "t = {}   N = {}   r = {}   {} contact cluster{}",
        s.t.render(),
        s.positions.len(),
        radius.render(),
        s.clusters.len(),
        if s.clusters.len() == 1 { "" } else { "s" }
    )?;
    let mut rows = Vec::with_capacity(s.positions.len());
    for c in &s.clusters {
        for i in c.range() {
            rows.push(vec![
                (i + 1).to_string(),
                s.positions[i].render(),
                s.velocities[i].render(),
                s.multipliers
                    .get(i)
                    .map_or_else(|| "—".into(), |l| l.render()),
                range_1based(c),
            ]);
        }
    }
    write_table(out, &["i", "x_i", "u_i", "λ_i", "cluster"], &rows)?;
    writeln!(out)
}

fn events(out: &mut impl Write, scene: &Scene, as_json: bool) -> Result<(), Failure> {
    let traj = sticky::merge::trajectory(&scene.data);
    if as_json {
        writeln!(out, "{}", json::events(traj.impulses())).map_err(io_err)?;
        return Ok(());
    }
    write_events_table(out, &traj).map_err(io_err)
}

fn write_events_table(out: &mut impl Write, traj: &Trajectory<BigRational>) -> io::Result<()> {
    let n = traj.impulses().len();
    writeln!(out, "{n} collision{}", if n == 1 { "" } else { "s" })?;
    if n == 0 {
        return Ok(());
    }
    let rows: Vec<Vec<String>> = traj
        .impulses()
        .iter()
        .map(|i| {
            vec![
                i.t.render(),
                range_1based(&i.cluster),
                i.cluster.size.to_string(),
                i.parts
                    .iter()
                    .map(|p| p.size.to_string())
                    .collect::<Vec<_>>()
                    .join(" + "),
                i.velocity.render(),
            ]
        })
        .collect();
    write_table(
        out,
        &["t", "particles", "size", "parts", "velocity after"],
        &rows,
    )
}

fn summary(out: &mut impl Write, scene: &Scene, origin: &str) -> Result<(), Failure> {
    let data = &scene.data;
    let name = scene.name.as_deref().unwrap_or("(unnamed)");
    let kind = match &scene.kind {
        SceneKind::Particles => "particles".to_string(),
        SceneKind::Macro { datum, .. } => format!(
            "quantile sampling of {} macroscopic block{}",
            datum.blocks().len(),
            if datum.blocks().len() == 1 { "" } else { "s" }
        ),
    };
    let traj = sticky::merge::trajectory(data);
    let w = |out: &mut dyn Write, s: String| writeln!(out, "{s}").map_err(io_err);
    w(out, format!("sticky — scene \"{name}\" ({origin})"))?;
    if let Some(d) = &scene.description {
        w(out, format!("  {}", d.trim()))?;
    }
    w(
        out,
        format!(
            "  N = {} particles, r = {}, {kind}",
            data.n(),
            data.radius().render()
        ),
    )?;
    w(out, String::new())?;
    write_events_table(out, &traj).map_err(io_err)?;
    let t_final = traj
        .last_collision()
        .cloned()
        .unwrap_or_else(<BigRational as Scalar>::zero);
    let last = traj.at(&t_final).map_err(|e| Failure(e.to_string()))?;
    let clusters: Vec<String> = last
        .clusters
        .iter()
        .map(|c| format!("[{}]", range_1based(c)))
        .collect();
    w(out, String::new())?;
    w(
        out,
        format!(
            "final clusters (t ≥ {}): {}",
            t_final.render(),
            abbreviate(&clusters, 12)
        ),
    )?;
    let limit = (data.n() > 200).then_some(50);
    let times = probe_times(&traj, limit).len();
    match check_trajectory(&traj, limit) {
        Ok(count) => {
            w(out, format!("checks: all {count} passed"))?;
            w(out, format!("  ✓ event-driven merge = projection P_K(x⁰ + t u⁰), exactly, at {times} times   [prop:proj-micro]"))?;
            w(out, "  ✓ λ_0 = λ_N = 0, λ ≥ 0, λ_i·(x_{i+1} − x_i − 2r) = 0 at the same times        [eq:dyn-micro]".to_string())?;
            w(out, format!("  ✓ all {} pressure impulses ≥ 0 (λ never decreases)                         [prop:micro-pressure]", traj.impulses().len()))
        }
        Err(v) => Err(Failure(format!("check failed: {v}"))),
    }
}

fn abbreviate(items: &[String], keep: usize) -> String {
    if items.len() <= keep {
        items.join(" ")
    } else {
        format!(
            "{} … {} ({} clusters)",
            items[..keep / 2].join(" "),
            items[items.len() - keep / 2..].join(" "),
            items.len()
        )
    }
}

fn claims(
    out: &mut impl Write,
    budget: Budget,
    as_json: bool,
    as_markdown: bool,
) -> Result<(), Failure> {
    let tty = io::IsTerminal::is_terminal(&io::stderr());
    let entries = ledger::run(budget, |id| {
        if tty {
            eprint!("\r\x1b[2Kchecking {id}");
        }
    });
    if tty {
        eprint!("\r\x1b[2K");
    }
    let text = if as_json {
        ledger::json(&entries)
    } else if as_markdown {
        ledger::markdown(&entries, budget)
    } else {
        ledger::table(&entries)
    };
    writeln!(out, "{}", text.trim_end()).map_err(io_err)
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

fn lib_err(e: sticky::Error) -> Failure {
    Failure(e.to_string())
}

fn print_paths(out: &mut impl Write, paths: &[PathBuf]) -> Result<(), Failure> {
    for p in paths {
        writeln!(out, "wrote {}", p.display()).map_err(io_err)?;
    }
    Ok(())
}

fn converge(
    out: &mut impl Write,
    scene: &Scene,
    dir: PathBuf,
    n_max: usize,
    exact_max: usize,
) -> Result<(), Failure> {
    use sticky::limit::converge::{converge_with_progress, write_csv, ConvergeOptions};
    let opts = ConvergeOptions {
        n_max: n_max.max(8),
        exact_max,
        ..ConvergeOptions::default()
    };
    let tty = io::IsTerminal::is_terminal(&io::stderr());
    let report = converge_with_progress(scene, &opts, &mut |row| {
        if tty {
            eprint!(
                "\r\x1b[2Kconverge: N = {} done ({})",
                row.n,
                row.engine.name()
            );
        }
    })
    .map_err(lib_err)?;
    if tty {
        eprint!("\r\x1b[2K");
    }
    std::fs::create_dir_all(&dir)
        .map_err(|e| Failure(format!("cannot create {}: {e}", dir.display())))?;
    writeln!(out, "{}", report.summary().trim_end()).map_err(io_err)?;
    let mut paths = write_csv(&report, &dir).map_err(lib_err)?;
    paths.extend(sticky::figures::convergence(&report, &dir).map_err(lib_err)?);
    print_paths(out, &paths)
}

fn plot(
    out: &mut impl Write,
    scene: &Scene,
    dir: PathBuf,
    t_end: Option<BigRational>,
) -> Result<(), Failure> {
    use sticky::limit::eulerian::{
        continuum_density_grid, particle_density_grid, particle_pressure_atoms,
    };
    let traj = sticky::merge::trajectory(&scene.data);
    let t_end = t_end.or_else(|| scene.t_end.clone()).unwrap_or_else(|| {
        traj.last_collision()
            .cloned()
            .unwrap_or_else(<BigRational as Scalar>::zero)
            + <BigRational as Scalar>::one()
    });
    std::fs::create_dir_all(&dir)
        .map_err(|e| Failure(format!("cannot create {}: {e}", dir.display())))?;
    let mut paths =
        sticky::figures::spacetime(&traj, &t_end, &dir, "spacetime").map_err(lib_err)?;
    // The x range: everything the particles visit on [0, t_end], with a margin.
    let (mut lo, mut hi) = (None::<BigRational>, None::<BigRational>);
    for t in [<BigRational as Scalar>::zero(), t_end.clone()] {
        let s = traj.at(&t).map_err(lib_err)?;
        for x in [s.positions.first(), s.positions.last()]
            .into_iter()
            .flatten()
        {
            lo = Some(lo.map_or(x.clone(), |l| if *x < l { x.clone() } else { l }));
            hi = Some(hi.map_or(x.clone(), |h| if *x > h { x.clone() } else { h }));
        }
    }
    let (lo, hi) = (lo.unwrap_or_default(), hi.unwrap_or_default());
    let margin = (hi.clone() - &lo) / BigRational::from_i64(20) + scene.data.two_r();
    let (lo, hi) = (lo - &margin, hi + &margin);
    let delta = <BigRational as Scalar>::one();
    let grid =
        particle_density_grid(&traj, &delta, &t_end, 60, (&lo, &hi), 160).map_err(lib_err)?;
    paths.extend(
        sticky::figures::density(
            &grid,
            "particle density ρ_N = 1/∂_w X̃_N",
            &dir,
            "density-particles",
        )
        .map_err(lib_err)?,
    );
    if let SceneKind::Macro { datum, .. } = &scene.kind {
        let c = sticky::limit::continuum::Continuum::new(datum);
        let grid = continuum_density_grid(&c, &t_end, 60, (&lo, &hi), 160).map_err(lib_err)?;
        paths.extend(
            sticky::figures::density(
                &grid,
                "continuum density ρ = X(t)#Leb",
                &dir,
                "density-continuum",
            )
            .map_err(lib_err)?,
        );
    }
    if scene.data.n() <= 5000 {
        let atoms = particle_pressure_atoms(&traj, &t_end);
        paths.extend(sticky::figures::pressure(&atoms, &dir, "pressure").map_err(lib_err)?);
    }
    print_paths(out, &paths)
}
