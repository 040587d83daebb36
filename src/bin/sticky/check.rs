//! `sticky check SCENE` (and plain `sticky` on the embedded default scene):
//! collisions, final clusters and the section-2 checks.

use std::io::Write;
use std::path::PathBuf;

use num_rational::BigRational;

use sticky::claims::micro::check_trajectory;
use sticky::progress::Silent;
use sticky::scene::SceneKind;
use sticky::solver::{Options, Solver, WorkCap};
use sticky::trajectory::probe_times;
use sticky::Scalar;

use crate::table::{abbreviate, particle_range, write_events_table, INDICES_FROM_0};
use crate::{io_err, scene_err, Failure};

/// Summary of a scene: collisions, final clusters, and the section-2
/// checks (event-driven = projection, signs of λ and of the pressure).
#[derive(clap::Args)]
pub struct Args {
    /// Scene file (TOML).
    scene: PathBuf,
}

/// Runs `sticky check`.
pub fn exec(args: Args, out: &mut impl Write) -> Result<(), Failure> {
    let solver = Solver::load(&args.scene)
        .map_err(scene_err(&args.scene))?
        .with_options(Options {
            work: WorkCap::Watched,
            ..Options::default()
        });
    summary(out, &solver, &args.scene.display().to_string())
}

/// The summary of the scene `solver` answers for, read from `origin`.
pub fn summary(out: &mut impl Write, solver: &Solver, origin: &str) -> Result<(), Failure> {
    let at = |e: sticky::Error| Failure(format!("{origin}: {e}"));
    let scene = solver.scene().map_err(at)?;
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
    // Only hopeless work is refused (the merge runs without a bar here).
    let traj = solver.trajectory(&Silent).map_err(at)?;
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
        .map(|c| format!("[{}]", particle_range(c)))
        .collect();
    w(out, String::new())?;
    w(
        out,
        format!(
            "final clusters (t ≥ {}): {}   {INDICES_FROM_0}",
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
