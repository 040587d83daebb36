//! `sticky plot SCENE`: space-time diagram, density maps, pressure.

use std::io::Write;
use std::path::PathBuf;

use num_rational::BigRational;

use sticky::progress::Progress;
use sticky::report::progress::Bar;
use sticky::scene::{Scene, SceneKind};
use sticky::solver::Solver;
use sticky::Scalar;

use crate::{lib_err, load, parse_time, print_paths, Failure};

/// Pictures of a scene: space-time diagram of the worldlines, density
/// heat map, pressure impulses (SVG and PNG).
#[derive(clap::Args)]
pub struct Args {
    /// Scene file (TOML).
    scene: PathBuf,
    /// Output folder (default ./out/plot/).
    #[arg(long)]
    out: Option<PathBuf>,
    /// Horizon (default: the scene's t_end, else 1 after the last collision).
    #[arg(long, value_parser = parse_time)]
    t_end: Option<BigRational>,
}

/// Runs `sticky plot`.
pub fn exec(args: Args, out: &mut impl Write) -> Result<(), Failure> {
    let scene = load(&args.scene)?;
    let dir = args.out.unwrap_or_else(|| PathBuf::from("out/plot"));
    // The scene, N, the chart being drawn, the count and the time left, on
    // a terminal only (hidden when stderr is piped or redirected).
    let bar = Bar::for_command("plot");
    let paths = plot(&scene, dir, args.t_end, &bar);
    bar.finish();
    print_paths(out, &paths?)
}

/// One stage of `sticky plot` on the bar: stops when the bar was
/// cancelled, else says what is being drawn.
struct Stages<'a> {
    bar: &'a Bar,
    label: String,
}

impl Stages<'_> {
    fn start(&self, what: &str) -> Result<(), Failure> {
        if self.bar.cancelled() {
            return Err(Failure("plot: interrupted".to_string()));
        }
        self.bar.note(&format!("{}: {what}", self.label));
        Ok(())
    }

    fn done(&self) {
        self.bar.advance(1);
    }
}

fn plot(
    scene: &Scene,
    dir: PathBuf,
    t_end: Option<BigRational>,
    bar: &Bar,
) -> Result<Vec<PathBuf>, Failure> {
    use sticky::limit::eulerian::{
        continuum_density_grid, particle_density_grid, particle_pressure_atoms,
    };
    let n = scene.data.n();
    let macro_scene = matches!(scene.kind, SceneKind::Macro { .. });
    let charts = 2 + usize::from(macro_scene) + usize::from(n <= 5000);
    let stages = Stages {
        bar,
        label: format!("{}, N = {n}", scene.name.as_deref().unwrap_or("scene")),
    };
    bar.stage(&stages.label, Some(1 + charts as u64));
    stages.start("the exact history")?;
    let traj = Solver::from_data(scene.data.clone())
        .trajectory(bar)
        .map_err(lib_err)?;
    stages.done();
    let t_end = t_end.or_else(|| scene.t_end.clone()).unwrap_or_else(|| {
        traj.last_collision()
            .cloned()
            .unwrap_or_else(<BigRational as Scalar>::zero)
            + <BigRational as Scalar>::one()
    });
    std::fs::create_dir_all(&dir)
        .map_err(|e| Failure(format!("cannot create {}: {e}", dir.display())))?;
    stages.start("space-time diagram")?;
    let mut paths =
        sticky::report::figures::spacetime(&traj, &t_end, &dir, "spacetime").map_err(lib_err)?;
    stages.done();
    // The x range: everything the particles visit on [0, t_end], with a margin.
    // The leftmost and rightmost particles at 0 and at t_end (they move
    // rigidly with their clusters: O(1) each, exactly).
    let mut ends: Vec<BigRational> = Vec::new();
    ends.extend(scene.data.positions().first().cloned());
    ends.extend(scene.data.positions().last().cloned());
    let at_end = traj.clusters_after(&t_end);
    if let Some(c) = at_end.first() {
        ends.push(traj.position_in(c, 0, &t_end));
    }
    if let Some(c) = at_end.last() {
        ends.push(traj.position_in(c, n.saturating_sub(1), &t_end));
    }
    let lo = ends.iter().min().cloned().unwrap_or_default();
    let hi = ends.iter().max().cloned().unwrap_or_default();
    let margin = (hi.clone() - &lo) / BigRational::from_i64(20) + scene.data.two_r();
    let (lo, hi) = (lo - &margin, hi + &margin);
    // One colour scale for both density maps: side by side, one colour is
    // one density.
    let scale = sticky::report::figures::density_scale();
    // The particle density map from the exact history rounded to f64 (a
    // picture: 60 states of N particles in exact arithmetic would take
    // minutes at N = 10^5).
    stages.start("particle density")?;
    let lossy = traj.to_f64_lossy();
    let grid = particle_density_grid(
        &lossy,
        &1.0, // δ = 1
        &t_end,
        60,
        (&lo, &hi),
        160,
    )
    .map_err(lib_err)?;
    // ρ_N is 1 in contact only under the paper's scaling 2r = 1/N; in
    // contact it is 1/(N·2r) in general. Other scenes are drawn as
    // ρ_N·N·2r (1 in contact, on the shared 0…1 scale) and the title says so.
    let n_two_r = BigRational::from_i64(n as i64) * scene.data.two_r();
    let (grid, title) = if n_two_r == BigRational::from_i64(1) {
        (
            grid,
            "particle density ρ_N = 1/∂_w X̃_N (2r = 1/N: 1 in contact)".to_string(),
        )
    } else {
        let k = n_two_r.to_f64_lossy();
        let mut grid = grid;
        for row in &mut grid.values {
            for v in row.iter_mut() {
                *v *= k;
            }
        }
        (
            grid,
            format!(
                "particle density scaled to this scene's 2r: ρ_N·N·2r (1 in contact), ρ_N = 1/∂_w X̃_N, N·2r = {}",
                n_two_r.render()
            ),
        )
    };
    paths.extend(
        sticky::report::figures::density(&grid, &title, &scale, &dir, "density-particles")
            .map_err(lib_err)?,
    );
    stages.done();
    if let SceneKind::Macro { datum, .. } = &scene.kind {
        stages.start("continuum density")?;
        let c = sticky::limit::continuum::Continuum::new(datum);
        let grid = continuum_density_grid(&c, &t_end, 60, (&lo, &hi), 160).map_err(lib_err)?;
        paths.extend(
            sticky::report::figures::density(
                &grid,
                "continuum density ρ = X(t)#Leb",
                &scale,
                &dir,
                "density-continuum",
            )
            .map_err(lib_err)?,
        );
        stages.done();
    }
    if n <= 5000 {
        stages.start("pressure impulses")?;
        let atoms = particle_pressure_atoms(&traj, &t_end);
        paths.extend(sticky::report::figures::pressure(&atoms, &dir, "pressure").map_err(lib_err)?);
        stages.done();
    }
    Ok(paths)
}
