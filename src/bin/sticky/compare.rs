//! `sticky compare SCENE SOLUTION [--json] [--out DIR] [--contact-tol TOL]`:
//! another solver's answer against the exact one, exactly (DESIGN.md §3).
//!
//! The exact answer at each time of the solution is the integer kernel's
//! `x(t) = P_K(x⁰ + t u⁰)`, `u(t)` and `λ(t)`; the metrics are
//! [`sticky::reference::measure::compare`]'s. Every number printed is exact
//! (a rational in lowest terms), except `L²` errors that are not the square of
//! a rational, shown as a truncated decimal after `≈` (their squares are
//! exact in `--json`), and long rationals, shown as a truncated decimal after
//! `≈` in the text report (exact in `--json`).

use std::io::Write;
use std::path::{Path, PathBuf};

use num_rational::BigRational;
use num_traits::Signed;

use sticky::fast::kernel::{self, IntegerData};
use sticky::rational::parse_exact;
use sticky::reference::measure::{compare, Comparison, MaxError};
use sticky::report::json::string;
use sticky::report::solution::{self, decimal, sqrt_text, Frame};
use sticky::Scalar;

use crate::{io_err, load, print_paths, Failure};

/// Another solver's answer against the exact one, exactly.
#[derive(clap::Args)]
pub struct Args {
    /// Scene file (TOML; README, "Scenes").
    scene: PathBuf,
    /// The other solver's answer: JSON in the `run --json` shape (one object
    /// per line or an array; JSON numbers read as the doubles they denote)
    /// or CSV `t,i,position[,velocity]` (i 0-based).
    solution: PathBuf,
    /// One JSON object (exact numbers as strings) instead of the text report.
    #[arg(long)]
    json: bool,
    /// Also write here compare.csv (per particle and time: exact errors) and
    /// the charts compare-positions / compare-velocities (SVG, PNG).
    #[arg(long)]
    out: Option<PathBuf>,
    /// When the solution gives no `clusters`, pairs with gap ≤ 2r + TOL count
    /// as the solver's contacts (exact; default 0).
    #[arg(long = "contact-tol", default_value = "0", value_parser = parse_tol)]
    contact_tol: BigRational,
}

fn parse_tol(s: &str) -> Result<BigRational, String> {
    let t = parse_exact(s).map_err(|e| e.to_string())?;
    if t.is_negative() {
        return Err(format!("contact tolerance {s} is negative"));
    }
    Ok(t)
}

/// Runs `sticky compare`.
pub fn exec(args: Args, out: &mut impl Write) -> Result<(), Failure> {
    let scene = load(&args.scene)?;
    let data = &scene.data;
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
    let ints = IntegerData::new(data);
    let two_r = data.two_r();
    let mut results = Vec::with_capacity(frames.len());
    let mut exact_states = Vec::with_capacity(frames.len());
    for f in &frames {
        let state = kernel::state_at(&ints, &f.t).map_err(|e| sol_err(f.line, e.to_string()))?;
        let cand = f.candidate();
        let c = compare(&cand, &state, &two_r, &args.contact_tol)
            .map_err(|e| sol_err(f.line, e.to_string()))?;
        results.push(c);
        exact_states.push(state);
    }
    let verdict = verdict(&results);
    if let Some(dir) = &args.out {
        let mut paths = vec![write_csv(dir, &frames, &exact_states)?];
        paths.extend(write_charts(dir, &frames, &exact_states)?);
        if !args.json {
            print_paths(out, &paths)?;
        }
    }
    if args.json {
        writeln!(out, "{}", to_json(&args, n, &frames, &results, &verdict)).map_err(io_err)?;
    } else {
        write_text(out, &args, n, data.radius(), &frames, &results, &verdict).map_err(io_err)?;
    }
    Ok(())
}

/// The one-line verdict: `exact`, `inexact` (within reach of the exact
/// answer but not equal) or `invalid` (breaks a constraint of the model).
struct Verdict {
    class: &'static str,
    line: String,
}

fn worst<'a>(
    results: &'a [Comparison],
    f: impl Fn(&'a Comparison) -> Option<&'a MaxError>,
) -> Option<(&'a BigRational, &'a BigRational)> {
    results
        .iter()
        .filter_map(|c| f(c).map(|m| (&m.value, &c.t)))
        .fold(None, |best, (v, t)| match best {
            Some((bv, _)) if bv >= v => best,
            _ => Some((v, t)),
        })
}

fn verdict(results: &[Comparison]) -> Verdict {
    if results.iter().all(Comparison::is_exact) {
        return Verdict {
            class: "exact",
            line: format!(
                "exact: the solution equals sticky's answer at all {} time(s), and breaks no constraint",
                results.len()
            ),
        };
    }
    let mut parts = Vec::new();
    if let Some((v, t)) = worst(results, |c| Some(&c.position_max)) {
        parts.push(format!(
            "max position error {} (t = {})",
            short(v),
            short(t)
        ));
    }
    if let Some((v, t)) = worst(results, |c| c.velocity_max.as_ref()) {
        parts.push(format!(
            "max velocity error {} (t = {})",
            short(v),
            short(t)
        ));
    }
    if let Some((v, t)) = worst(results, |c| c.multiplier_max.as_ref()) {
        parts.push(format!("max λ error {} (t = {})", short(v), short(t)));
    }
    let sum = |f: &dyn Fn(&Comparison) -> usize| results.iter().map(f).sum::<usize>();
    let overlaps = sum(&|c| c.overlaps.len());
    let wrong = sum(&|c| c.missed_clusters.len() + c.spurious_clusters.len());
    let neg = sum(&|c| c.negative_multipliers.len());
    let comp = sum(&|c| c.complementarity.len());
    let ole = sum(&|c| c.oleinik.as_ref().map_or(0, Vec::len));
    parts.push(format!("{wrong} wrong contact cluster(s)"));
    parts.push(format!("{overlaps} overlap(s)"));
    parts.push(format!("{neg} λ < 0"));
    parts.push(format!("{comp} complementarity error(s)"));
    parts.push(format!("{ole} Oleinik violation(s)"));
    let invalid = results.iter().any(Comparison::violates_model);
    Verdict {
        class: if invalid { "invalid" } else { "inexact" },
        line: format!(
            "{}: {}",
            if invalid {
                "invalid (breaks a constraint of the model)"
            } else {
                "inexact (admissible, not equal to the exact answer)"
            },
            parts.join(", ")
        ),
    }
}

/// Exact when short, else a truncated 4-digit decimal after `≈`.
fn short(q: &BigRational) -> String {
    let s = q.render();
    if s.len() <= 24 {
        s
    } else {
        format!("≈{}", decimal(q, 4, false))
    }
}

const SHOWN: usize = 8;

fn write_text(
    out: &mut impl Write,
    args: &Args,
    n: usize,
    radius: &BigRational,
    frames: &[Frame],
    results: &[Comparison],
    v: &Verdict,
) -> std::io::Result<()> {
    writeln!(
        out,
        "compare {} against {} (N = {n}, r = {}, {} time(s)); errors exact, L² = ((1/N) Σ e_i²)^(1/2)",
        args.solution.display(),
        args.scene.display(),
        radius.render(),
        frames.len()
    )?;
    for (f, c) in frames.iter().zip(results) {
        writeln!(out, "t = {}  (line {})", c.t.render(), f.line)?;
        writeln!(
            out,
            "  position error   max {} (particle {})   L² {}",
            short(&c.position_max.value),
            c.position_max.index,
            sqrt_text(&c.position_l2_squared, 4)
        )?;
        match (&c.velocity_max, &c.velocity_l2_squared) {
            (Some(m), Some(l2)) => writeln!(
                out,
                "  velocity error   max {} (particle {})   L² {}",
                short(&m.value),
                m.index,
                sqrt_text(l2, 4)
            )?,
            _ => writeln!(out, "  velocity error   — (no velocities given)")?,
        }
        writeln!(
            out,
            "  overlaps         {}",
            list(&c.overlaps, |o| format!(
                "pair ({}, {}) depth {}",
                o.pair,
                o.pair + 1,
                short(&o.depth)
            ))
        )?;
        let cl = |k: &sticky::cluster::Cluster| format!("[{}, {}]", k.first, k.size);
        writeln!(
            out,
            "  contact clusters {} missed pair(s), {} spurious pair(s); exact clusters missed: {}; solver's wrong clusters: {}",
            c.missed_contacts,
            c.spurious_contacts,
            list(&c.missed_clusters, cl),
            list(&c.spurious_clusters, cl)
        )?;
        match (&f.multipliers, &c.multiplier_max) {
            (None, _) => writeln!(out, "  multipliers      — (no multipliers given)")?,
            (Some(_), m) => writeln!(
                out,
                "  multipliers      max error {}; λ < 0: {}; complementarity λ·(gap − 2r) ≠ 0: {}",
                m.as_ref().map_or("—".into(), |m| format!(
                    "{} (pair {})",
                    short(&m.value),
                    m.index
                )),
                list(&c.negative_multipliers, |p| format!(
                    "pair {} λ = {}",
                    p.pair,
                    short(&p.value)
                )),
                list(&c.complementarity, |p| format!(
                    "pair {} product {}",
                    p.pair,
                    short(&p.value)
                ))
            )?,
        }
        match &c.oleinik {
            None => writeln!(out, "  Oleinik          — (no velocities, or t = 0)")?,
            Some(o) => writeln!(
                out,
                "  Oleinik          (u_i − u_(i−1))/(x_i − x_(i−1)) < 1/t fails at: {}",
                list(o, |i| format!("pair ({}, {i})", i - 1))
            )?,
        }
    }
    writeln!(out, "verdict: {}", v.line)
}

fn list<T>(items: &[T], f: impl Fn(&T) -> String) -> String {
    if items.is_empty() {
        return "none".into();
    }
    let mut s: Vec<String> = items.iter().take(SHOWN).map(f).collect();
    if items.len() > SHOWN {
        s.push(format!("… ({} in all)", items.len()));
    }
    s.join(", ")
}

fn q(x: &BigRational) -> String {
    string(&x.render())
}

fn max_json(m: &Option<MaxError>) -> String {
    match m {
        None => "null".into(),
        Some(m) => format!("{{\"value\": {}, \"index\": {}}}", q(&m.value), m.index),
    }
}

fn to_json(args: &Args, n: usize, frames: &[Frame], results: &[Comparison], v: &Verdict) -> String {
    let times: Vec<String> = frames
        .iter()
        .zip(results)
        .map(|(f, c)| {
            let pairs = |items: &[sticky::reference::measure::PairValue]| {
                let s: Vec<String> = items
                    .iter()
                    .map(|p| format!("{{\"pair\": {}, \"value\": {}}}", p.pair, q(&p.value)))
                    .collect();
                format!("[{}]", s.join(", "))
            };
            let clusters = |items: &[sticky::cluster::Cluster]| {
                let s: Vec<String> = items
                    .iter()
                    .map(|k| format!("[{}, {}]", k.first, k.size))
                    .collect();
                format!("[{}]", s.join(", "))
            };
            let overlaps: Vec<String> = c
                .overlaps
                .iter()
                .map(|o| format!("{{\"pair\": {}, \"depth\": {}}}", o.pair, q(&o.depth)))
                .collect();
            format!(
                "{{\"t\": {}, \"line\": {}, \"position_max\": {}, \"position_l2_squared\": {}, \"position_l2\": {}, \"velocity_max\": {}, \"velocity_l2_squared\": {}, \"velocity_l2\": {}, \"multiplier_max\": {}, \"overlaps\": [{}], \"missed_contacts\": {}, \"spurious_contacts\": {}, \"missed_clusters\": {}, \"spurious_clusters\": {}, \"negative_multipliers\": {}, \"complementarity\": {}, \"oleinik\": {}, \"exact\": {}}}",
                q(&c.t),
                f.line,
                max_json(&Some(c.position_max.clone())),
                q(&c.position_l2_squared),
                string(&sqrt_text(&c.position_l2_squared, 17)),
                max_json(&c.velocity_max),
                c.velocity_l2_squared.as_ref().map_or("null".into(), q),
                c.velocity_l2_squared
                    .as_ref()
                    .map_or("null".into(), |l| string(&sqrt_text(l, 17))),
                max_json(&c.multiplier_max),
                overlaps.join(", "),
                c.missed_contacts,
                c.spurious_contacts,
                clusters(&c.missed_clusters),
                clusters(&c.spurious_clusters),
                pairs(&c.negative_multipliers),
                pairs(&c.complementarity),
                c.oleinik.as_ref().map_or("null".into(), |o| format!(
                    "[{}]",
                    o.iter().map(ToString::to_string).collect::<Vec<_>>().join(", ")
                )),
                c.is_exact()
            )
        })
        .collect();
    format!(
        "{{\"scene\": {}, \"solution\": {}, \"n\": {n}, \"times\": [{}], \"verdict\": {}, \"summary\": {}}}",
        string(&args.scene.display().to_string()),
        string(&args.solution.display().to_string()),
        times.join(", "),
        string(v.class),
        string(&v.line)
    )
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

/// The charts in `--out`: the signed error (solver − sticky) of each
/// particle, positions and velocities, one series per time (the first
/// eight). Drawn in `f64` (a picture only: the exact values are in
/// `compare.csv`).
fn write_charts(
    dir: &Path,
    frames: &[Frame],
    exact: &[sticky::State<BigRational>],
) -> Result<Vec<PathBuf>, Failure> {
    use sticky::report::plot::{palette, write_chart, Axis, Chart, Marker, Series};
    let mut paths = Vec::new();
    for (stem, what, velocity) in [
        ("compare-positions", "position", false),
        ("compare-velocities", "velocity", true),
    ] {
        let mut chart = Chart::new(
            format!("{what} error of the solution, solver − sticky (exact values in compare.csv)"),
            Axis::linear("particle i (0-based)"),
            Axis::linear(format!("{what} error")),
        );
        for (k, (f, e)) in frames.iter().zip(exact).take(8).enumerate() {
            let (mine, theirs) = if velocity {
                match &f.velocities {
                    Some(u) => (u, &e.velocities),
                    None => continue,
                }
            } else {
                (&f.positions, &e.positions)
            };
            let points = mine
                .iter()
                .zip(theirs)
                .enumerate()
                .map(|(i, (a, b))| (i as f64, (a - b).to_f64_lossy()))
                .collect();
            chart.series.push(
                Series::line(format!("t = {}", short(&f.t)), palette(k), points)
                    .with_marker(Marker::Circle),
            );
        }
        if chart.series.is_empty() {
            continue;
        }
        let written = write_chart(&chart, dir, stem)
            .map_err(|e| Failure(format!("{}: {e}", dir.display())))?;
        paths.extend(written.paths());
    }
    Ok(paths)
}
