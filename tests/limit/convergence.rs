//! Convergence as N grows: measured rates, CSV output, progress and Ctrl-C.

use super::*;

fn study(name: &str) -> ConvergenceReport {
    let opts = ConvergeOptions {
        n_min: 8,
        n_max: 2048,
        exact_max: 512,
        panels: 4,
        ..ConvergeOptions::default()
    };
    converge(&load(name), &opts).unwrap()
}

fn slope(r: &ConvergenceReport, q: Quantity) -> f64 {
    r.rates.iter().find(|x| x.quantity == q).unwrap().slope_all
}

fn all_zero(r: &ConvergenceReport, q: Quantity) -> bool {
    r.rows.iter().all(|row| row.get(q).unwrap().value == 0.0)
}

/// The common properties of every study: ρ ≤ 1, Oleinik, exact engine up
/// to `exact_max` and f64 beyond, engines agreeing, continuum residuals at
/// quadrature level, `(1 − ρ)p = 0` for the continuum.
fn common(r: &ConvergenceReport) {
    for row in &r.rows {
        assert_eq!(row.engine == Engine::Exact, row.n <= 512);
        // ρ̃_N ≤ 1: exactly on the exact engine, up to its rounding bound on f64.
        let rho = row.get(Quantity::MaxDensity).unwrap();
        assert!(rho.value <= 1.0 + rho.bound, "{} {rho:?}", row.n);
        if row.engine == Engine::Exact {
            assert_eq!(rho.bound, 0.0);
        }
        assert!(row.get(Quantity::Oleinik).unwrap().value < 1.0);
        assert_eq!(row.get(Quantity::ResidualMass).unwrap().value, 0.0);
    }
    let c = &r.continuum;
    assert!(c.max_density.value <= 1.0);
    assert!(c.oleinik.unwrap() < 1.0);
    assert_eq!(c.complementarity_defect.value, 0.0);
    for (m, p) in &c.residuals {
        assert!(
            m.value.abs() < 1e-10 && p.value.abs() < 1e-10,
            "{m:?} {p:?}"
        );
    }
    let check = r.engine_check.as_ref().unwrap();
    assert_eq!(check.n, 512);
    for (q, d) in &check.differences {
        assert!(*d < 1e-9, "engines differ on {q:?}: {d}");
    }
}

#[test]
fn convergence_two_blocks() {
    let r = study("appendix-c-two-blocks");
    common(&r);
    assert!(slope(&r, Quantity::XL2) <= -0.8 * 1.000);
    assert!(slope(&r, Quantity::LambdaL2) <= -0.8 * 1.000);
    assert!(slope(&r, Quantity::ResidualMomentum) <= -0.8 * 1.000);
    assert!(slope(&r, Quantity::Complementarity) <= -0.8 * 1.902);
    assert!(
        slope(&r, Quantity::NLambda) >= 0.8 * 1.000,
        "N sup λ grows like N"
    );
    for qy in [
        Quantity::UL1,
        Quantity::PressureMassError,
        Quantity::BvXError,
        Quantity::TvUError,
    ] {
        assert!(all_zero(&r, qy), "{qy:?}");
    }
    assert_eq!(r.continuum.pressure_mass.exact.as_deref(), Some("1/4"));
    assert!(r.continuum.rational);
}

#[test]
fn convergence_riemann_compression() {
    let r = study("riemann-compression");
    common(&r);
    assert!(slope(&r, Quantity::XL2) <= -0.8 * 1.000);
    assert!(slope(&r, Quantity::UL1) <= -0.8 * 1.000);
    assert!(slope(&r, Quantity::LambdaL2) <= -0.8 * 1.001);
    assert!(slope(&r, Quantity::BvXError) <= -0.8 * 1.000);
    assert!(slope(&r, Quantity::ResidualMomentum) <= -0.8 * 0.999);
    assert!(slope(&r, Quantity::Complementarity) <= -0.8 * 0.975);
    assert!(slope(&r, Quantity::NLambda) >= 0.8 * 1.000);
    assert!(all_zero(&r, Quantity::PressureMassError));
    assert!(slope(&r, Quantity::PressureMass).abs() < 0.05, "bounded");
    assert!(slope(&r, Quantity::BvX).abs() < 0.05, "eq:BV_XN: bounded");
    assert!(slope(&r, Quantity::TvU).abs() < 0.05, "pwUN-L1: bounded");
}

#[test]
fn convergence_expansion_affine() {
    let r = study("riemann-expansion-affine");
    common(&r);
    assert!(
        !r.continuum.rational,
        "the pooled level is a quadratic surd"
    );
    assert!(slope(&r, Quantity::XL2) <= -0.8 * 0.997);
    assert!(slope(&r, Quantity::UL1) <= -0.8 * 1.027);
    assert!(slope(&r, Quantity::LambdaL2) <= -0.8 * 1.021);
    assert!(slope(&r, Quantity::PressureMassError) <= -0.8 * 1.066);
    assert!(slope(&r, Quantity::BvXError) <= -0.8 * 0.999);
    assert!(slope(&r, Quantity::TvUError) <= -0.8 * 1.024);
    assert!(slope(&r, Quantity::ResidualMomentum) <= -0.8 * 1.023);
    assert!(slope(&r, Quantity::Complementarity) <= -0.8 * 1.078);
    assert!(slope(&r, Quantity::NLambda) >= 0.8 * 0.962);
    assert!(slope(&r, Quantity::PressureMass).abs() < 0.1);
    // The f64 comparisons carry a tiny rounding bound.
    for row in &r.rows {
        let m = row.get(Quantity::XL2).unwrap();
        assert!(!row.exact_comparisons);
        assert!(m.bound < 1e-6 * m.value, "{m:?}");
    }
}

/// The CSV files: written whole, one row per N, every quantity.
#[test]
fn csv_files() {
    let opts = ConvergeOptions {
        n_max: 64,
        exact_max: 32,
        panels: 2,
        time_samples: 2,
        ..ConvergeOptions::default()
    };
    let r = converge(&load("riemann-compression"), &opts).unwrap();
    let dir = std::env::temp_dir().join(format!("sticky-limit-csv-{}", std::process::id()));
    let paths = write_csv(&r, &dir).unwrap();
    assert_eq!(paths.len(), 4);
    let conv = std::fs::read_to_string(dir.join("convergence.csv")).unwrap();
    let lines: Vec<&str> = conv.lines().collect();
    assert_eq!(lines.len(), 1 + 4, "header + N = 8, 16, 32, 64");
    assert!(lines[0]
        .starts_with("n,engine,exact_comparisons,seconds,collisions,x_l2,x_l2_bound,x_l2_exact"));
    assert!(lines[1].starts_with("8,exact,true,"));
    assert!(lines[4].starts_with("64,f64,false,"));
    let cols = lines[0].split(',').count();
    assert_eq!(cols, 5 + 3 * Quantity::ALL.len());
    let rates = std::fs::read_to_string(dir.join("rates.csv")).unwrap();
    assert_eq!(rates.lines().count(), 1 + Quantity::ALL.len());
    let res = std::fs::read_to_string(dir.join("residuals.csv")).unwrap();
    assert_eq!(res.lines().count(), 1 + 12);
    assert!(!std::fs::read_dir(&dir).unwrap().any(|e| e
        .unwrap()
        .file_name()
        .to_string_lossy()
        .contains(".tmp")));
    std::fs::remove_dir_all(&dir).unwrap();
    let particles =
        scene::parse("[particles]\npositions = [\"0\", \"1\"]\nvelocities = [\"0\", \"0\"]\n")
            .unwrap();
    assert!(
        converge(&particles, &opts).is_err(),
        "a [particles] scene is refused"
    );
}

/// What `converge_with_progress` tells its observer, and a stop asked
/// after `stop_after` steps.
struct Observer {
    stop_after: u64,
    steps: std::sync::atomic::AtomicU64,
    said: std::sync::Mutex<Vec<String>>,
}

impl Observer {
    fn new(stop_after: u64) -> Self {
        Observer {
            stop_after,
            steps: 0.into(),
            said: Vec::new().into(),
        }
    }
    fn steps(&self) -> u64 {
        self.steps.load(std::sync::atomic::Ordering::Relaxed)
    }
}

impl sticky::progress::Progress for Observer {
    fn stage(&self, what: &str, total: Option<u64>) {
        self.said
            .lock()
            .unwrap()
            .push(format!("stage {what} ({total:?})"));
    }
    fn advance(&self, steps: u64) {
        self.steps
            .fetch_add(steps, std::sync::atomic::Ordering::Relaxed);
    }
    fn note(&self, what: &str) {
        self.said.lock().unwrap().push(what.to_string());
    }
    fn cancelled(&self) -> bool {
        self.steps() >= self.stop_after
    }
}

/// The study tells its observer the scene, each N and its engine, one step
/// per N plus the engine check; a stop asked after the first N ends it
/// there, with that one row.
#[test]
fn converge_reports_progress_and_stops_when_cancelled() {
    use sticky::limit::converge::converge_with_progress;
    let opts = ConvergeOptions {
        n_max: 64,
        exact_max: 32,
        panels: 2,
        time_samples: 2,
        ..ConvergeOptions::default()
    };
    let scene = load("riemann-compression");
    let all = Observer::new(u64::MAX);
    let r = converge_with_progress(&scene, &opts, &all).unwrap();
    assert_eq!(r.rows.len(), 4);
    assert_eq!(
        all.steps(),
        4 + 1,
        "N = 8 … 64 and the engine check at N = 32"
    );
    let said = all.said.lock().unwrap().clone();
    assert_eq!(said[0], "stage riemann-compression: N = 8 … 64 (Some(5))");
    assert_eq!(said[1], "riemann-compression: N = 8 (exact)");
    assert!(said.contains(&"riemann-compression: N = 64 (f64)".to_string()));
    assert!(said.contains(&"engine check: N = 32 on f64".to_string()));
    let first = Observer::new(1);
    let r = converge_with_progress(&scene, &opts, &first).unwrap();
    assert_eq!(r.rows.iter().map(|row| row.n).collect::<Vec<_>>(), [8]);
    assert_eq!(first.steps(), 1);
}
