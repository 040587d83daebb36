//! `sticky compare SCENE SOLUTION [--json] [--out DIR] [--contact-tol TOL |
//! --contact-tol-rel K] [--overlap-tol TOL] [--fail-on VERDICT]`: another
//! solver's answer against the exact one, exactly (docs/guide/json.md).
//!
//! Argument parsing, file reading and printing only: the figures, the
//! verdict and both reports are the library's
//! ([`sticky::report::compare`]), shared with the Python package.

use std::io::Write;
use std::path::{Path, PathBuf};

use num_rational::BigRational;
use num_traits::Signed;

use sticky::rational::parse_exact;
use sticky::report::compare::text::figure;
use sticky::report::compare::{
    compare_solution, CompareFailure, CompareOptions, ContactTolerance, Verdict,
};
use sticky::report::solution::{self, Frame};
use sticky::solver::Solver;
use sticky::Scalar;

use crate::{io_err, print_paths, scene_err, Failure};

/// The exit code of `--fail-on` when the verdict is at least that bad (1 is
/// an error, 2 a usage error).
pub const FAIL_ON_EXIT: u8 = 3;

/// Another solver's answer against the exact one, exactly.
#[derive(clap::Args)]
pub struct Args {
    /// Scene file (TOML; README, "Scenes").
    scene: PathBuf,
    /// The other solver's answer: JSON in the `run --json` shape (one object
    /// per line or an array; JSON numbers read as the doubles they denote)
    /// or CSV `t,i,position[,velocity]` (i from 0).
    solution: PathBuf,
    /// One JSON object (each figure exact as a string, and beside it the
    /// nearest double as a number, key `…_f64`) instead of the text report.
    #[arg(long)]
    json: bool,
    /// Also write here compare.csv (per particle and time: exact errors) and
    /// the charts compare-positions / compare-velocities (SVG, PNG).
    #[arg(long)]
    out: Option<PathBuf>,
    /// When the solution gives no `clusters`, pairs with gap ≤ 2r + TOL count
    /// as the solver's contacts (a length, exact; default 0).
    #[arg(long = "contact-tol", value_name = "TOL", value_parser = parse_tol, conflicts_with = "contact_tol_rel")]
    contact_tol: Option<BigRational>,
    /// The same rule with TOL = K·2r (K exact; the peers use 1e-6).
    #[arg(long = "contact-tol-rel", value_name = "K", value_parser = parse_tol)]
    contact_tol_rel: Option<BigRational>,
    /// Rounding tolerance, relative to 2r (exact; default 0): overlaps and
    /// position errors up to TOL·2r (velocity errors up to TOL·max|u⁰|, λ up
    /// to TOL·max λ(t)), with the right contact clusters, give the verdict
    /// `rounding` instead of `invalid` or `inexact`.
    #[arg(long = "overlap-tol", value_name = "TOL", default_value = "0", value_parser = parse_tol)]
    overlap_tol: BigRational,
    /// Exit with code 3 when the verdict is this bad or worse (exact <
    /// rounding < inexact < invalid); by default the exit code is 0 whatever
    /// the verdict.
    #[arg(long = "fail-on", value_name = "VERDICT", value_parser = parse_verdict)]
    fail_on: Option<Verdict>,
}

fn parse_tol(s: &str) -> Result<BigRational, String> {
    let t = parse_exact(s).map_err(|e| e.to_string())?;
    if t.is_negative() {
        return Err(format!("tolerance {s} is negative"));
    }
    Ok(t)
}

fn parse_verdict(s: &str) -> Result<Verdict, String> {
    s.parse()
        .map_err(|e: sticky::report::compare::verdict::UnknownVerdict| e.to_string())
}

/// Runs `sticky compare`. With `--fail-on` and a verdict that bad, flushes
/// the output and exits with [`FAIL_ON_EXIT`].
pub fn exec(args: Args, out: &mut impl Write) -> Result<(), Failure> {
    let solver = Solver::load(&args.scene).map_err(scene_err(&args.scene))?;
    let data = solver.data().map_err(scene_err(&args.scene))?;
    let n = data.n();
    let text = std::fs::read(&args.solution)
        .map_err(|e| Failure(format!("{}: cannot read: {e}", args.solution.display())))?;
    let text = String::from_utf8(text).map_err(|e| {
        Failure(format!(
            "{}: not UTF-8 text (byte {})",
            args.solution.display(),
            e.utf8_error().valid_up_to()
        ))
    })?;
    let sol_err =
        |line: usize, m: String| Failure(format!("{}:{line}: {m}", args.solution.display()));
    let frames = solution::parse(&text, n).map_err(|e| sol_err(e.line, e.message))?;
    let options = CompareOptions {
        contact_tol: match (&args.contact_tol, &args.contact_tol_rel) {
            (_, Some(k)) => ContactTolerance::Relative(k.clone()),
            (Some(t), None) => ContactTolerance::Absolute(t.clone()),
            (None, None) => CompareOptions::default().contact_tol,
        },
        overlap_tol: args.overlap_tol.clone(),
    };
    let report = compare_solution(data, &frames, &options)
        .map_err(|e| match e {
            CompareFailure::Frame { line, error, .. } => sol_err(line, error.to_string()),
            e => Failure(format!("{}: {e}", args.solution.display())),
        })?
        .with_files(
            args.scene.display().to_string(),
            args.solution.display().to_string(),
        );
    if let Some(dir) = &args.out {
        let exact_states = frames
            .iter()
            .map(|f| {
                solver
                    .state(&f.t)
                    .map(|a| a.into_state())
                    .map_err(|e| sol_err(f.line, e.to_string()))
            })
            .collect::<Result<Vec<_>, _>>()?;
        let mut paths = vec![write_csv(dir, &frames, &exact_states)?];
        paths.extend(write_charts(dir, &frames, &exact_states)?);
        if !args.json {
            print_paths(out, &paths)?;
        }
    }
    if args.json {
        writeln!(out, "{}", report.json()).map_err(io_err)?;
    } else {
        write!(out, "{}", report.text()).map_err(io_err)?;
    }
    if args.fail_on.is_some_and(|level| report.verdict >= level) {
        // The exit code follows the verdict: the report is complete, so
        // flush it and leave with the documented code.
        out.flush().map_err(io_err)?;
        std::process::exit(i32::from(FAIL_ON_EXIT));
    }
    Ok(())
}

/// `compare.csv`: `t,i,position_error,velocity_error` (exact, solver minus
/// sticky), written whole (temporary name, then rename).
fn write_csv(
    dir: &Path,
    frames: &[Frame],
    exact: &[sticky::State<BigRational>],
) -> Result<PathBuf, Failure> {
    let mut s = String::from("t,i,position_error,velocity_error\n");
    for (f, e) in frames.iter().zip(exact) {
        for i in 0..f.positions.len() {
            let dx = &f.positions[i] - &e.positions[i];
            let du = f
                .velocities
                .as_ref()
                .map_or(String::new(), |u| (&u[i] - &e.velocities[i]).render());
            s.push_str(&format!("{},{i},{},{du}\n", f.t.render(), dx.render()));
        }
    }
    let fail = |e: std::io::Error| Failure(format!("{}: {e}", dir.display()));
    std::fs::create_dir_all(dir).map_err(fail)?;
    let path = dir.join("compare.csv");
    let tmp = dir.join(".compare.csv.tmp");
    std::fs::write(&tmp, s).map_err(fail)?;
    std::fs::rename(&tmp, &path).map_err(fail)?;
    Ok(path)
}

/// Nonzero errors spanning at least this ratio (two decades) are drawn on
/// a log scale.
const LOG_SPAN: i64 = 100;

/// The charts in `--out`: the error of each particle, positions and
/// velocities, one series per time (the first eight): signed (solver −
/// sticky) on a linear scale, or `|solver − sticky|` on a log scale when
/// the nonzero errors span two decades or more (zero errors are then not
/// drawn). Drawn in `f64`, each the nearest double of the exact error (a
/// picture only: the exact values are in `compare.csv`).
fn write_charts(
    dir: &Path,
    frames: &[Frame],
    exact: &[sticky::State<BigRational>],
) -> Result<Vec<PathBuf>, Failure> {
    use sticky::report::compare::decimal::{nearest_f64, Value};
    use sticky::report::plot::{palette, write_chart, Axis, Chart, Marker, Series};
    let mut paths = Vec::new();
    for (stem, what, velocity) in [
        ("compare-positions", "position", false),
        ("compare-velocities", "velocity", true),
    ] {
        // Per time shown: its label and the exact signed errors.
        let mut series: Vec<(String, Vec<BigRational>)> = Vec::new();
        for (f, e) in frames.iter().zip(exact).take(8) {
            let (mine, theirs) = if velocity {
                match &f.velocities {
                    Some(u) => (u, &e.velocities),
                    None => continue,
                }
            } else {
                (&f.positions, &e.positions)
            };
            let errors = mine.iter().zip(theirs).map(|(a, b)| a - b).collect();
            series.push((format!("t = {}", figure(&f.t)), errors));
        }
        if series.is_empty() {
            continue;
        }
        let nonzero = series
            .iter()
            .flat_map(|(_, e)| e.iter())
            .filter(|e| !num_traits::Zero::is_zero(*e))
            .map(|e| e.abs());
        let (lo, hi) = nonzero.fold(
            (None, None),
            |(lo, hi): (Option<BigRational>, Option<BigRational>), e| {
                (
                    Some(lo.map_or(e.clone(), |l| l.min(e.clone()))),
                    Some(hi.map_or(e.clone(), |h| h.max(e))),
                )
            },
        );
        let log = match (lo, hi) {
            (Some(lo), Some(hi)) => hi >= lo * BigRational::from_integer(LOG_SPAN.into()),
            _ => false,
        };
        let mut chart = if log {
            Chart::new(
                format!("|{what} error| of the solution, |solver − sticky|, log scale; zero errors not drawn (exact values in compare.csv)"),
                Axis::linear("particle i (indices from 0)"),
                Axis::log(format!("|{what} error|")),
            )
        } else {
            Chart::new(
                format!(
                    "{what} error of the solution, solver − sticky (exact values in compare.csv)"
                ),
                Axis::linear("particle i (indices from 0)"),
                Axis::linear(format!("{what} error")),
            )
        };
        for (k, (label, errors)) in series.into_iter().enumerate() {
            let points = errors
                .iter()
                .enumerate()
                .filter(|(_, e)| !log || !num_traits::Zero::is_zero(*e))
                .filter_map(|(i, e)| {
                    let shown = if log { e.abs() } else { e.clone() };
                    nearest_f64(Value::Rational(&shown)).map(|y| (i as f64, y))
                })
                .collect();
            chart
                .series
                .push(Series::line(label, palette(k), points).with_marker(Marker::Circle));
        }
        let written = write_chart(&chart, dir, stem)
            .map_err(|e| Failure(format!("{}: {e}", dir.display())))?;
        paths.extend(written.paths());
    }
    Ok(paths)
}
