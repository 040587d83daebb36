//! Real peer solvers, run on our scenes: the drivers of `scripts/peers/`
//! (Python), each invoked as a subprocess on a `sticky export --format json`
//! file, its SOLUTION read back exactly ([`super::solution`]).
//!
//! [`run_peer`] is the one entry point (for `sticky compare` scripts, the
//! peer tests and the atlas): it runs a named peer on a scene at given times
//! and returns the solution and the wall time of the whole call (export,
//! interpreter start, imports, the solver's own setup and solves — what a
//! user of that peer pays), plus the driver's own timing of its solves. A
//! peer whose packages are not installed is [`PeerOutcome::Skipped`] with the
//! driver's message, never an error.
//!
//! Interpreters: PyPI peers run with `python3` from `PATH` (or
//! `$STICKY_PYTHON`); Siconos, Debian's `python3-siconos`, with the system
//! `/usr/bin/python3` (or `$STICKY_SYSTEM_PYTHON`). `scripts/peers/install.sh`
//! installs both kinds.

use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

use num_rational::BigRational;

use super::export;
use super::solution::{self, Frame};
use crate::scalar::Scalar;
use crate::scene::Scene;

/// Where a peer's packages come from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Source {
    /// PyPI (pip): must install in CI.
    PyPi,
    /// Debian's `python3-siconos` (apt), for the system Python.
    Debian,
}

/// One peer and one setting.
#[derive(Debug, Clone, PartialEq)]
pub struct Peer {
    /// Stable name for CSV columns: `<peer>(<setting>)`.
    pub name: &'static str,
    /// Where its packages come from.
    pub source: Source,
    /// The driver, relative to the scripts directory.
    pub script: &'static str,
    /// The driver's options.
    pub args: &'static [&'static str],
    /// For a time-stepper (an `--h` option), the measured cost of one
    /// particle-step in seconds (the atlas predicts `N · ⌈t/h⌉` times this
    /// and skips a run beyond its budget); `0` for the one-shot solvers.
    pub step_seconds: f64,
}

/// The measured start-up cost of a driver in seconds (interpreter start and
/// imports: 0.3–1.5 s here for the PyPI peers, up to 2.8 s for cromosim,
/// 0.4 s for Siconos; `sticky atlas --peers` adds it to every prediction).
pub const STARTUP_SECONDS: f64 = 1.0;

/// Every peer and setting the drivers offer.
pub fn peers() -> Vec<Peer> {
    let p = |name, source, script, args| Peer {
        name,
        source,
        script,
        args,
        step_seconds: 0.0,
    };
    // Seconds per particle-step, measured by `sticky atlas --quick --peers`
    // on random-1000 (N = 1000, 1001 steps of 1e-3 / 101 steps of 1e-2):
    // Siconos's Moreau–Jean 10 s, cromosim 2 s (CVXOPT) and 5 s (Uzawa).
    // Stiff scenes cost more (velocities-12-decades: 16×, 160× for
    // cromosim); the atlas's time limit stops those.
    let stepper = |name, source, script, args, step_seconds| Peer {
        step_seconds,
        ..p(name, source, script, args)
    };
    use Source::{Debian, PyPi};
    vec![
        stepper(
            "siconos-mj(h=1e-2)",
            Debian,
            "siconos_mj.py",
            &["--h", "1e-2"],
            1e-5,
        ),
        stepper(
            "siconos-mj(h=1e-3)",
            Debian,
            "siconos_mj.py",
            &["--h", "1e-3"],
            1e-5,
        ),
        stepper(
            "siconos-mj(h=1e-4)",
            Debian,
            "siconos_mj.py",
            &["--h", "1e-4"],
            1e-5,
        ),
        p(
            "siconos-lcp(lemke)",
            Debian,
            "siconos_lcp.py",
            &["--solver", "lemke"],
        ),
        p(
            "siconos-lcp(pgs)",
            Debian,
            "siconos_lcp.py",
            &["--solver", "pgs"],
        ),
        p(
            "siconos-lcp(enum)",
            Debian,
            "siconos_lcp.py",
            &["--solver", "enum"],
        ),
        p("osqp(default)", PyPi, "qp.py", &["--solver", "osqp"]),
        p("osqp(tight)", PyPi, "qp.py", &["--solver", "osqp-tight"]),
        p("clarabel", PyPi, "qp.py", &["--solver", "clarabel"]),
        p("proxsuite", PyPi, "qp.py", &["--solver", "proxsuite"]),
        p("quadprog", PyPi, "qp.py", &["--solver", "quadprog"]),
        p("cvxopt", PyPi, "qp.py", &["--solver", "cvxopt"]),
        p(
            "scipy-isotonic",
            PyPi,
            "qp.py",
            &["--solver", "scipy-isotonic"],
        ),
        stepper(
            "cromosim(cvxopt,h=1e-2)",
            PyPi,
            "cromosim_proj.py",
            &["--h", "1e-2"],
            2e-5,
        ),
        stepper(
            "cromosim(cvxopt,h=1e-2,tight)",
            PyPi,
            "cromosim_proj.py",
            &["--h", "1e-2", "--tight"],
            2e-5,
        ),
        stepper(
            "cromosim(uzawa,h=1e-2)",
            PyPi,
            "cromosim_proj.py",
            &["--h", "1e-2", "--method", "uzawa"],
            5e-5,
        ),
    ]
}

/// The peer called `name` (see [`peers`]).
pub fn peer(name: &str) -> Option<Peer> {
    peers().into_iter().find(|p| p.name == name)
}

/// The drivers' directory of this source tree.
pub fn default_scripts_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("scripts/peers")
}

/// The exit status by which a driver says its solver is not installed.
pub const SKIP_STATUS: i32 = 3;

/// A peer's answer.
#[derive(Debug, Clone, PartialEq)]
pub struct PeerRun {
    /// The solution, one frame per requested time, read exactly.
    pub frames: Vec<Frame>,
    /// Wall time of the whole call: interpreter start, imports, setup and
    /// solves (the export of the scene is not included).
    pub wall_seconds: f64,
    /// The driver's own timing of its solves (setup included, imports not),
    /// when it reports one.
    pub solver_seconds: Option<f64>,
    /// The SOLUTION file the driver wrote (readable by `sticky compare`).
    pub solution: PathBuf,
}

/// What running a peer gave.
#[derive(Debug, Clone, PartialEq)]
pub enum PeerOutcome {
    /// It ran.
    Ran(PeerRun),
    /// Not installed: the driver's message.
    Skipped(String),
    /// Stopped (killed) at the time limit of [`run_peer_within`]: the
    /// limit in seconds.
    OverTime(f64),
}

/// Why a peer run failed (an installed peer that crashed, or wrote a
/// solution `sticky compare` refuses).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct PeerError {
    /// The peer's name.
    pub peer: String,
    /// What went wrong.
    pub message: String,
}

impl std::fmt::Display for PeerError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}: {}", self.peer, self.message)
    }
}

impl std::error::Error for PeerError {}

fn interpreter(source: Source) -> String {
    let var = match source {
        Source::PyPi => "STICKY_PYTHON",
        Source::Debian => "STICKY_SYSTEM_PYTHON",
    };
    std::env::var(var).unwrap_or_else(|_| match source {
        Source::PyPi => "python3".into(),
        Source::Debian => "/usr/bin/python3".into(),
    })
}

/// Runs `peer` on `scene` at `times` (each `≥ 0`), with the drivers in
/// `scripts` and scratch files in `work` (created if needed; the export and
/// the solution are left there).
pub fn run_peer(
    peer: &Peer,
    scene: &Scene,
    times: &[BigRational],
    scripts: &Path,
    work: &Path,
) -> Result<PeerOutcome, PeerError> {
    run_peer_within(peer, scene, times, scripts, work, None)
}

/// [`run_peer`] with a time limit: a driver still running after `limit` is
/// killed (its process, started here) and the outcome is
/// [`PeerOutcome::OverTime`].
pub fn run_peer_within(
    peer: &Peer,
    scene: &Scene,
    times: &[BigRational],
    scripts: &Path,
    work: &Path,
    limit: Option<Duration>,
) -> Result<PeerOutcome, PeerError> {
    let fail = |message: String| PeerError {
        peer: peer.name.to_string(),
        message,
    };
    std::fs::create_dir_all(work).map_err(|e| fail(format!("{}: {e}", work.display())))?;
    let e = export::export(scene).map_err(|e| fail(e.to_string()))?;
    let stem: String = peer
        .name
        .chars()
        .map(|c| if c.is_ascii_alphanumeric() { c } else { '_' })
        .collect();
    let input = work.join("export.json");
    std::fs::write(&input, export::json(scene, &e))
        .map_err(|e| fail(format!("{}: {e}", input.display())))?;
    let out = work.join(format!("{stem}.json"));
    let _ = std::fs::remove_file(&out);
    let mut cmd = Command::new(interpreter(peer.source));
    cmd.arg(scripts.join(peer.script)).arg(&input);
    for t in times {
        cmd.arg("--at").arg(t.render());
    }
    cmd.arg("--out").arg(&out).args(peer.args);
    let start = Instant::now();
    let o = match output_within(&mut cmd, work, &stem, limit) {
        Ok(Some(o)) => o,
        Ok(None) => {
            return Ok(PeerOutcome::OverTime(
                limit.map_or(0.0, |l| l.as_secs_f64()),
            ))
        }
        // No interpreter at all: the peer is not installed either.
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
            return Ok(PeerOutcome::Skipped(format!(
                "SKIP {}: no interpreter {:?}",
                peer.name,
                cmd.get_program()
            )))
        }
        Err(e) => return Err(fail(format!("cannot start {:?}: {e}", cmd.get_program()))),
    };
    let wall_seconds = start.elapsed().as_secs_f64();
    let stdout = String::from_utf8_lossy(&o.stdout);
    if o.status.code() == Some(SKIP_STATUS) {
        let msg = stdout
            .lines()
            .find(|l| l.starts_with("SKIP"))
            .unwrap_or("not installed")
            .to_string();
        return Ok(PeerOutcome::Skipped(msg));
    }
    if !o.status.success() {
        let err = String::from_utf8_lossy(&o.stderr);
        let last = err
            .lines()
            .rev()
            .find(|l| !l.trim().is_empty())
            .unwrap_or("");
        return Err(fail(format!("driver failed ({}): {last}", o.status)));
    }
    let text =
        std::fs::read_to_string(&out).map_err(|e| fail(format!("{}: {e}", out.display())))?;
    let frames =
        solution::parse(&text, scene.n()).map_err(|e| fail(format!("{}:{e}", out.display())))?;
    let solver_seconds = text
        .lines()
        .next()
        .and_then(|l| l.split("\"wall_seconds\": ").nth(1))
        .and_then(|s| s.trim_end_matches(['}', ' ']).parse().ok());
    Ok(PeerOutcome::Ran(PeerRun {
        frames,
        wall_seconds,
        solver_seconds,
        solution: out,
    }))
}

/// Runs `cmd` to completion, its standard output and error captured in
/// files `work/<stem>.stdout|stderr`; `None` when it was still running after
/// `limit` (then killed and reaped).
fn output_within(
    cmd: &mut Command,
    work: &Path,
    stem: &str,
    limit: Option<Duration>,
) -> std::io::Result<Option<Output>> {
    let out_path = work.join(format!("{stem}.stdout"));
    let err_path = work.join(format!("{stem}.stderr"));
    cmd.stdin(Stdio::null())
        .stdout(std::fs::File::create(&out_path)?)
        .stderr(std::fs::File::create(&err_path)?);
    let start = Instant::now();
    let mut child = cmd.spawn()?;
    let status = loop {
        if let Some(status) = child.try_wait()? {
            break status;
        }
        if limit.is_some_and(|l| start.elapsed() >= l) {
            // Our own child, by its handle (its pid).
            let _ = child.kill();
            let _ = child.wait();
            return Ok(None);
        }
        std::thread::sleep(Duration::from_millis(5));
    };
    Ok(Some(Output {
        status,
        stdout: std::fs::read(&out_path)?,
        stderr: std::fs::read(&err_path)?,
    }))
}
