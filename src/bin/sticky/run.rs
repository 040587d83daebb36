//! `sticky run SCENE --at T … [--json] [--engine E] [--model M]`: the state
//! at each requested time.

use std::io::{self, Write};
use std::path::PathBuf;

use clap::builder::{PossibleValue, PossibleValuesParser, TypedValueParser};
use clap::ValueEnum;
use num_rational::BigRational;

use sticky::progress::{Progress, Silent};
use sticky::report::json;
use sticky::report::progress::Bar;
use sticky::scene::{Scene, SceneKind};
use sticky::solver::{Answer, Engine, Options, Solver, WorkCap};
use sticky::{Scalar, State};

use crate::table::{particle_range, write_table, INDICES_FROM_0};
use crate::{io_err, load, parse_time, scene_err, Failure};

/// The state x(t), u(t), λ(t) and the contact clusters at each requested time.
#[derive(clap::Args)]
pub struct Args {
    /// Scene file (TOML; docs/guide/scenes.md).
    scene: PathBuf,
    /// A time t ≥ 0, exact: "3/2", "0.125", "1e-3" (repeat for several).
    #[arg(long = "at", required = true, allow_hyphen_values = true, value_parser = parse_time)]
    at: Vec<BigRational>,
    /// One JSON object per time (the interop contract: docs/guide/json.md);
    /// the same as `--format json`.
    #[arg(long)]
    json: bool,
    /// Output for big scenes: `json` (the contract), `csv` (header
    /// `t,i,position,velocity,multiplier`, one row per particle and time, `i`
    /// 0-based, exact strings, `multiplier` = λ of the pair (i, i+1), empty
    /// for the last particle), or `npy` (an `(T, N, 3)` `<f8` array of
    /// position, velocity, multiplier (0 for the last particle) — ROUNDED to
    /// the nearest double, so it needs `--lossy`). Default: a table.
    #[arg(long, value_enum)]
    format: Option<Format>,
    /// Accept the rounding of `--format npy` (the exact answer rounded to
    /// the nearest doubles).
    #[arg(long)]
    lossy: bool,
    /// Which exact engine answers (every one gives the same exact state):
    /// `auto` picks the cheapest for the data (the integer kernel's one-shot
    /// projection, O(N) per time); `projection` and `events` name the
    /// kernel and the integer event merge (O(N log N) once).
    #[arg(long, default_value = Engine::Auto.name(), value_parser = engine_names())]
    engine: Engine,
    /// Which model answers: the N particles of the scene, or (for a
    /// `[macro]` scene) the continuum solution of its macroscopic datum,
    /// block by block, whose cost does not grow with N.
    #[arg(long, value_enum, default_value_t = Model::Particles)]
    model: Model,
    /// Print on stderr which engine answers and why (N, the common
    /// denominator's bits, each candidate's estimated cost).
    #[arg(long)]
    explain: bool,
}

/// The output formats of `--format`.
#[derive(Clone, Copy, PartialEq, Eq, ValueEnum)]
enum Format {
    /// One JSON object per time (the contract).
    Json,
    /// Exact strings, one row per particle and time.
    Csv,
    /// `(T, N, 3)` doubles, rounded (needs `--lossy`).
    Npy,
}

/// How `--model continuum` prints each profile.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Layout {
    /// A table of the segments for people.
    Table,
    /// One JSON object per time (`--json`).
    Json,
}

#[derive(Clone, Copy, PartialEq, Eq, ValueEnum)]
enum Model {
    /// The N particles (exact).
    Particles,
    /// The continuum solution X(t) = P_K(X⁰ + tU⁰) of a `[macro]` datum
    /// (exact: rationals and quadratic surds).
    Continuum,
}

/// Every engine the Solver can be asked for ([`Engine::choices`]: `auto`
/// first, aliases accepted), each with its one-line summary for `--help`.
fn engine_names() -> impl TypedValueParser<Value = Engine> {
    PossibleValuesParser::new(Engine::choices().map(|c| {
        PossibleValue::new(c.name)
            .aliases(c.aliases.iter().copied())
            .help(c.summary)
    }))
    .try_map(|name| name.parse::<Engine>().map_err(|e| e.to_string()))
}

/// Runs `sticky run`.
pub fn exec(mut args: Args, out: &mut impl Write) -> Result<(), Failure> {
    match (args.json, args.format) {
        (true, Some(f)) if f != Format::Json => {
            return Err(Failure(
                "--json and --format csv|npy ask for two outputs: give one".into(),
            ))
        }
        (true, _) => args.format = Some(Format::Json),
        (false, Some(Format::Json)) => args.json = true,
        _ => {}
    }
    if args.format == Some(Format::Npy) && !args.lossy {
        return Err(Failure(
            "--format npy rounds the exact answer to doubles: add --lossy to accept that (--format csv keeps every value exact)".into(),
        ));
    }
    if args.lossy && args.format != Some(Format::Npy) {
        return Err(Failure("--lossy only goes with --format npy".into()));
    }
    if matches!(args.format, Some(Format::Csv | Format::Npy)) {
        if args.model != Model::Particles {
            return Err(Failure(
                "--format csv|npy writes particles: it does not go with --model continuum".into(),
            ));
        }
        return columns(out, &args);
    }
    match args.model {
        Model::Particles => run(out, &args),
        Model::Continuum => {
            let scene = load(&args.scene)?;
            let layout = if args.json {
                Layout::Json
            } else {
                Layout::Table
            };
            run_continuum(out, &scene, &args.scene, &args.at, layout)
        }
    }
}

/// The Solver of the scene with the engine of `--engine`; with
/// `--explain`, its choice and why on stderr.
fn solver(args: &Args) -> Result<Solver, Failure> {
    let solver = Solver::load(&args.scene)
        .map_err(scene_err(&args.scene))?
        .with_options(Options {
            engine: args.engine,
            work: WorkCap::Plain,
        });
    if args.explain {
        eprintln!("{}", solver.explain().map_err(scene_err(&args.scene))?);
    }
    Ok(solver)
}

/// The state at each time, as a table or one JSON object per line.
fn run(out: &mut impl Write, args: &Args) -> Result<(), Failure> {
    let solver = solver(args)?;
    // A bar on stderr when it is a terminal (engines that take long on one
    // state tell it their steps; Ctrl-C ends the process).
    let bar = Bar::for_command("run");
    for t in &args.at {
        let answer = solver
            .state_with_progress(t, &bar)
            .map_err(scene_err(&args.scene))?;
        let radius = solver.radius().map_err(scene_err(&args.scene))?;
        match answer {
            Answer::Words(b) if args.json => json::write_lean_state(out, &b, radius),
            answer if args.json => writeln!(out, "{}", json::state(&answer.into_state(), radius)),
            answer => write_state_table(out, &answer.into_state(), radius),
        }
        .map_err(io_err)?;
    }
    bar.finish();
    Ok(())
}

/// One value of a row: its exact text (CSV) or its nearest double (NPY),
/// from the streaming path's values or the general state's.
trait Cell {
    fn write_exact(&self, out: &mut dyn Write) -> io::Result<()>;
    fn lossy(&self) -> f64;
}

impl Cell for sticky::fast::stream::Exact {
    fn write_exact(&self, out: &mut dyn Write) -> io::Result<()> {
        self.write(out)
    }
    fn lossy(&self) -> f64 {
        self.to_f64_lossy()
    }
}

impl Cell for BigRational {
    fn write_exact(&self, out: &mut dyn Write) -> io::Result<()> {
        out.write_all(self.render().as_bytes())
    }
    fn lossy(&self) -> f64 {
        self.to_f64_lossy()
    }
}

/// `--format csv|npy`: every particle at every time, row by row, from the
/// Solver's answer as its path left it (values written one by one on the
/// streaming path).
fn columns(out: &mut impl Write, args: &Args) -> Result<(), Failure> {
    let npy = args.format == Some(Format::Npy);
    let solver = solver(args)?;
    let mut header = false;
    let t_count = args.at.len();
    for t in &args.at {
        let t_text = t.render();
        let mut row = |out: &mut dyn Write,
                       n: usize,
                       i: usize,
                       x: &dyn Cell,
                       u: &dyn Cell,
                       l: Option<&dyn Cell>|
         -> io::Result<()> {
            if !header {
                header = true;
                if npy {
                    out.write_all(&sticky::columns::npy_header(&[t_count, n, 3]))?;
                } else {
                    out.write_all(b"t,i,position,velocity,multiplier\n")?;
                }
            }
            if npy {
                for v in [x.lossy(), u.lossy(), l.map_or(0.0, |l| l.lossy())] {
                    out.write_all(&v.to_le_bytes())?;
                }
                return Ok(());
            }
            write!(out, "{t_text},{i},")?;
            x.write_exact(out)?;
            out.write_all(b",")?;
            u.write_exact(out)?;
            out.write_all(b",")?;
            if let Some(l) = l {
                l.write_exact(out)?;
            }
            out.write_all(b"\n")
        };
        match solver
            .state_with_progress(t, &Silent)
            .map_err(scene_err(&args.scene))?
        {
            Answer::Words(b) if npy => {
                // The rows in pieces of whole blocks, rounded on every core
                // and written in order: the bytes of `row`, value by value.
                let head = sticky::columns::npy_header(&[t_count, b.n(), 3]);
                let head: &[u8] = if std::mem::replace(&mut header, true) {
                    &[]
                } else {
                    &head
                };
                let pieces = b.pieces(sticky::report::json::PIECE_PARTICLES);
                let rows = |piece: &sticky::fast::stream::Piece| {
                    let mut bytes = Vec::new();
                    b.push_nearest_rows(piece, &mut bytes);
                    bytes
                };
                let workers = sticky::parallel::workers();
                out.write_all(head).and_then(|()| {
                    sticky::parallel::in_order(&pieces, workers, rows, |bytes| {
                        out.write_all(&bytes)
                    })
                })
            }
            Answer::Words(b) => {
                let n = b.n();
                b.rows(|i, x, u, l| row(out, n, i, x, u, l.map(|l| l as &dyn Cell)))
            }
            answer => {
                let state = answer.into_state();
                let n = state.positions.len();
                (0..n).try_for_each(|i| {
                    let l = state.multipliers.get(i).map(|l| l as &dyn Cell);
                    row(out, n, i, &state.positions[i], &state.velocities[i], l)
                })
            }
        }
        .map_err(io_err)?;
    }
    Ok(())
}

/// `sticky run --model continuum`: the block-level continuum solution.
fn run_continuum(
    out: &mut impl Write,
    scene: &Scene,
    path: &std::path::Path,
    times: &[BigRational],
    layout: Layout,
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
        if layout == Layout::Json {
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
                    g.block.to_string(),
                    g.plateau.map_or("—".into(), |k| k.to_string()),
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
                "block (from 0)",
                "congested: plateau (from 0)",
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

fn write_state_table(
    out: &mut impl Write,
    s: &State<BigRational>,
    radius: &BigRational,
) -> io::Result<()> {
    writeln!(
        out,
        "t = {}   N = {}   r = {}   {} contact cluster{}   {INDICES_FROM_0}",
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
                i.to_string(),
                s.positions[i].render(),
                s.velocities[i].render(),
                s.multipliers
                    .get(i)
                    .map_or_else(|| "—".into(), |l| l.render()),
                particle_range(c),
            ]);
        }
    }
    write_table(
        out,
        &["i", "position", "velocity", "λ of (i, i+1)", "cluster"],
        &rows,
    )?;
    writeln!(out)
}
