//! The `sticky` binary against an independent exact oracle,
//! `scripts/oracle.py` (Python 3 standard library, written from the model,
//! with a different algorithm: repeated scans of adjacent cluster pairs
//! instead of a priority queue, no pool-adjacent-violators), bit for bit on
//! stdout — the JSON contract of docs/guide/json.md.
//!
//! * every scene in `scenes/`: `events --json`, and `run --json` at t = 0,
//!   `t_end`, every collision time, midpoints between consecutive collision
//!   times and one time after the last collision (both `--engine`s);
//! * 200 random `[particles]` scenes from [`sticky::generate::initial_data`]
//!   (N ≤ 60, many simultaneous multi-cluster collisions and initial
//!   contacts), written with [`sticky::scene::particles_toml`].
//!
//! When no Python ≥ 3.11 is available the tests print why on stderr and
//! return early; set `STICKY_REQUIRE_ORACLE=1` to make that a failure
//! instead. `STICKY_PYTHON` overrides the interpreter (default `python3`).

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Output, Stdio};
use std::time::Instant;

use num_bigint::BigInt;
use num_rational::BigRational;
use serde_json::Value;
use sticky::generate::{initial_data, Limits, SplitMix64};
use sticky::rational::{parse_exact, render_exact};
use sticky::scene::{self, particles_toml};

const STICKY: &str = env!("CARGO_BIN_EXE_sticky");
const ORACLE: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/scripts/oracle.py");
const SCENES: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/scenes");

/// At most this many midpoints per scene (spread over the collision times).
const MAX_MIDPOINTS: usize = 100;
/// The `--engine events` run uses at most this many of the times.
const MAX_EVENT_ENGINE_TIMES: usize = 200;
/// Number of random scenes.
const RANDOM_SCENES: u64 = 200;

// ------------------------------------------------------------ python

fn python() -> String {
    std::env::var("STICKY_PYTHON").unwrap_or_else(|_| "python3".to_string())
}

/// `true` when a Python with `tomllib` (≥ 3.11) runs. Otherwise prints the
/// reason and returns `false`, or panics under `STICKY_REQUIRE_ORACLE=1`.
fn oracle_available() -> bool {
    let py = python();
    let reason = match Command::new(&py)
        .args([
            "-c",
            "import sys, tomllib, fractions, json; print(sys.version)",
        ])
        .output()
    {
        Ok(out) if out.status.success() => return true,
        Ok(out) => format!(
            "`{py}` runs but cannot import tomllib (Python ≥ 3.11 needed): {}",
            String::from_utf8_lossy(&out.stderr).trim()
        ),
        Err(e) => format!("`{py}` cannot be started: {e}"),
    };
    if std::env::var_os("STICKY_REQUIRE_ORACLE").is_some_and(|v| v != "0") {
        panic!("oracle test: {reason} (STICKY_REQUIRE_ORACLE is set)");
    }
    eprintln!(
        "SKIPPED oracle comparison: {reason}. The binary was NOT compared with \
         scripts/oracle.py; install Python 3.11+ (or set STICKY_PYTHON) to run it."
    );
    false
}

/// One request to the oracle (a line of its batch file).
enum Job {
    Events(PathBuf),
    Run(PathBuf, Vec<BigRational>),
}

impl Job {
    fn line(&self) -> String {
        match self {
            Job::Events(p) => format!("events\t{}", p.display()),
            Job::Run(p, ts) => {
                let mut s = format!("run\t{}", p.display());
                for t in ts {
                    s.push('\t');
                    s.push_str(&render_exact(t));
                }
                s
            }
        }
    }
    /// Lines of output the job produces.
    fn lines(&self) -> usize {
        match self {
            Job::Events(_) => 1,
            Job::Run(_, ts) => ts.len(),
        }
    }
}

/// Starts `oracle.py batch` on `jobs` (written to `dir/jobs.tsv`, output to
/// `dir/oracle.out`, so that a full pipe never stalls it); the caller runs
/// the binary meanwhile and then calls [`finish_oracle`].
fn start_oracle(dir: &Path, jobs: &[Job]) -> Child {
    let path = dir.join("jobs.tsv");
    let text: String = jobs.iter().map(|j| j.line() + "\n").collect();
    std::fs::write(&path, text).expect("write the oracle job file");
    let out = std::fs::File::create(dir.join("oracle.out")).expect("create the oracle output");
    Command::new(python())
        .arg(ORACLE)
        .arg("batch")
        .arg(&path)
        .stdout(out)
        .stderr(Stdio::piped())
        .spawn()
        .expect("start the oracle")
}

/// Waits for the oracle and splits its output per job.
fn finish_oracle(child: Child, dir: &Path, jobs: &[Job]) -> Vec<Vec<String>> {
    let out = child.wait_with_output().expect("wait for the oracle");
    let stdout = std::fs::read_to_string(dir.join("oracle.out")).expect("oracle output (UTF-8)");
    assert!(
        out.status.success(),
        "scripts/oracle.py batch failed ({}):\nstderr: {}\nerror lines: {:?}",
        out.status,
        String::from_utf8_lossy(&out.stderr),
        stdout
            .lines()
            .filter(|l| l.starts_with("error:"))
            .take(5)
            .collect::<Vec<_>>()
    );
    let mut lines = stdout.lines().map(str::to_string);
    let split: Vec<Vec<String>> = jobs
        .iter()
        .map(|j| lines.by_ref().take(j.lines()).collect())
        .collect();
    assert!(
        lines.next().is_none(),
        "oracle printed more lines than asked"
    );
    for (job, got) in jobs.iter().zip(&split) {
        assert_eq!(got.len(), job.lines(), "oracle output too short");
    }
    split
}

// ------------------------------------------------------------ binary

fn sticky(args: &[String]) -> Output {
    Command::new(STICKY)
        .args(args)
        .output()
        .expect("run the sticky binary")
}

fn sticky_ok(args: &[String]) -> String {
    let out = sticky(args);
    assert!(
        out.status.success() && out.stderr.is_empty(),
        "sticky {} failed ({}): {}",
        short(&args.join(" ")),
        out.status,
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).expect("sticky output is UTF-8")
}

fn events_json(scene: &Path) -> String {
    sticky_ok(&[
        "events".into(),
        scene.display().to_string(),
        "--json".into(),
    ])
}

fn run_json(scene: &Path, times: &[BigRational], engine: &str) -> String {
    let mut args = vec![
        "run".to_string(),
        scene.display().to_string(),
        "--json".into(),
        format!("--engine={engine}"),
    ];
    args.extend(times.iter().map(|t| format!("--at={}", render_exact(t))));
    sticky_ok(&args)
}

// ------------------------------------------------------------ times

fn q(n: i64, d: i64) -> BigRational {
    BigRational::new(BigInt::from(n), BigInt::from(d))
}

/// Distinct collision times of an `events --json` line.
fn collision_times(events_line: &str) -> Vec<BigRational> {
    let v: Value = serde_json::from_str(events_line).expect("events output is JSON");
    let set: BTreeSet<BigRational> = v["events"]
        .as_array()
        .expect("an events array")
        .iter()
        .map(|e| parse_exact(e["t"].as_str().expect("t is a string")).expect("t is exact"))
        .collect();
    set.into_iter().collect()
}

/// 0, `t_end`, every collision time, midpoints between consecutive
/// collision times (from 0; at most [`MAX_MIDPOINTS`], evenly spread) and
/// one time after the last collision; sorted, distinct.
fn probe_times(collisions: &[BigRational], t_end: Option<&BigRational>) -> Vec<BigRational> {
    let zero = q(0, 1);
    let mut set: BTreeSet<BigRational> = collisions.iter().cloned().collect();
    set.insert(zero.clone());
    if let Some(t) = t_end {
        set.insert(t.clone());
    }
    let mut knots = vec![zero];
    knots.extend(collisions.iter().cloned());
    let gaps = knots.len() - 1;
    let stride = gaps.div_ceil(MAX_MIDPOINTS).max(1);
    for k in (0..gaps).step_by(stride) {
        set.insert((knots[k].clone() + &knots[k + 1]) / q(2, 1));
    }
    let last = knots.last().cloned().unwrap_or_else(|| q(0, 1));
    set.insert(last + q(1, 1));
    set.into_iter().collect()
}

fn subsample(times: &[BigRational], max: usize) -> Vec<BigRational> {
    let stride = times.len().div_ceil(max).max(1);
    times.iter().step_by(stride).cloned().collect()
}

// ------------------------------------------------------------ comparison

fn short(s: &str) -> String {
    const MAX: usize = 1500;
    match s.char_indices().nth(MAX) {
        Some((cut, _)) => format!("{}… ({} bytes)", &s[..cut], s.len()),
        None => s.to_string(),
    }
}

/// The first JSON field where two lines differ, for the failure message.
fn first_difference(a: &str, b: &str) -> String {
    match (
        serde_json::from_str::<Value>(a),
        serde_json::from_str::<Value>(b),
    ) {
        (Ok(Value::Object(x)), Ok(Value::Object(y))) => {
            for (k, vx) in &x {
                match y.get(k) {
                    Some(vy) if vx == vy => {}
                    Some(Value::Array(ay)) if vx.is_array() => {
                        let ax = vx.as_array().map(Vec::as_slice).unwrap_or(&[]);
                        let i = ax
                            .iter()
                            .zip(ay)
                            .position(|(p, q)| p != q)
                            .unwrap_or(ax.len().min(ay.len()));
                        return format!(
                            "field {k:?} first differs at index {i}: sticky {} vs oracle {} (lengths {} and {})",
                            ax.get(i).map_or("—".into(), |v| v.to_string()),
                            ay.get(i).map_or("—".into(), |v| v.to_string()),
                            ax.len(),
                            ay.len()
                        );
                    }
                    other => {
                        return format!("field {k:?}: sticky {vx} vs oracle {other:?}");
                    }
                }
            }
            "same values, different text (key order or spacing)".to_string()
        }
        _ => "not both JSON objects".to_string(),
    }
}

/// Compares the binary's lines with the oracle's, panicking with the scene,
/// the time and both lines at the first difference.
fn compare(what: &str, scene: &Path, times: Option<&[BigRational]>, ours: &str, theirs: &[String]) {
    let ours: Vec<&str> = ours.lines().collect();
    assert_eq!(
        ours.len(),
        theirs.len(),
        "{what} {}: sticky printed {} lines, the oracle {}",
        scene.display(),
        ours.len(),
        theirs.len()
    );
    for (k, (a, b)) in ours.iter().zip(theirs).enumerate() {
        if a == b {
            continue;
        }
        let at = times.map_or(String::new(), |ts| {
            format!(" at t = {}", render_exact(&ts[k]))
        });
        let text = std::fs::read_to_string(scene).unwrap_or_default();
        let text = if text.len() <= 20_000 {
            text
        } else {
            short(&text)
        };
        panic!(
            "DISAGREEMENT {what} {}{at}\n  {}\n  sticky: {}\n  oracle: {}\n  scene:\n{text}",
            scene.display(),
            first_difference(a, b),
            short(a),
            short(b),
        );
    }
}

/// A scratch directory under the system temp dir, removed on drop.
struct TempDir(PathBuf);

impl TempDir {
    fn new(tag: &str) -> Self {
        let nanos = std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .map_or(0, |d| d.as_nanos());
        let path = std::env::temp_dir().join(format!(
            "sticky-oracle-{tag}-{}-{nanos}",
            std::process::id()
        ));
        std::fs::create_dir_all(&path).expect("create a temp dir");
        TempDir(path)
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// Compares `events` and `run` (both engines) on every scene of `scenes`.
/// Returns (scenes, run times compared, collisions, collisions of three or
/// more clusters at one instant).
fn compare_scenes(
    dir: &Path,
    scenes: &[(PathBuf, Option<BigRational>)],
) -> (usize, usize, usize, usize) {
    // The binary's collision times choose the probe times; its `events`
    // output is itself compared with the oracle's below.
    let events: Vec<String> = scenes.iter().map(|(p, _)| events_json(p)).collect();
    let mut jobs = Vec::new();
    let mut all_times = Vec::new();
    let (mut collisions, mut multiple) = (0, 0);
    for ((path, t_end), ev) in scenes.iter().zip(&events) {
        let ct = collision_times(ev);
        let list = serde_json::from_str::<Value>(ev).expect("JSON")["events"]
            .as_array()
            .cloned()
            .unwrap_or_default();
        collisions += list.len();
        multiple += list
            .iter()
            .filter(|e| e["parts"].as_array().is_some_and(|p| p.len() >= 3))
            .count();
        let times = probe_times(&ct, t_end.as_ref());
        jobs.push(Job::Events(path.clone()));
        jobs.push(Job::Run(path.clone(), times.clone()));
        all_times.push(times);
    }
    let child = start_oracle(dir, &jobs);
    // The binary runs while the oracle works.
    let runs: Vec<(String, Vec<BigRational>, String)> = scenes
        .iter()
        .zip(&all_times)
        .map(|((path, _), times)| {
            let few = subsample(times, MAX_EVENT_ENGINE_TIMES);
            (
                run_json(path, times, "projection"),
                few.clone(),
                run_json(path, &few, "events"),
            )
        })
        .collect();
    let oracle = finish_oracle(child, dir, &jobs);
    let mut compared = 0;
    for (k, (path, _)) in scenes.iter().enumerate() {
        compare("events", path, None, &events[k], &oracle[2 * k]);
        let (proj, few, by_events) = &runs[k];
        compare(
            "run --engine projection",
            path,
            Some(&all_times[k]),
            proj,
            &oracle[2 * k + 1],
        );
        // The oracle's lines at the subsampled times.
        let index: Vec<usize> = few
            .iter()
            .map(|t| all_times[k].binary_search(t).expect("a subsampled time"))
            .collect();
        let expected: Vec<String> = index
            .iter()
            .map(|&i| oracle[2 * k + 1][i].clone())
            .collect();
        compare("run --engine events", path, Some(few), by_events, &expected);
        compared += all_times[k].len();
    }
    (scenes.len(), compared, collisions, multiple)
}

// ------------------------------------------------------------ tests

#[test]
fn every_scene_matches_the_oracle() {
    if !oracle_available() {
        return;
    }
    let start = Instant::now();
    let mut paths: Vec<PathBuf> = std::fs::read_dir(SCENES)
        .expect("scenes/ exists")
        .map(|e| e.expect("a directory entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    paths.sort();
    assert!(
        paths.len() >= 6,
        "expected the scenes of scenes/, found {paths:?}"
    );
    let scenes: Vec<(PathBuf, Option<BigRational>)> = paths
        .into_iter()
        .map(|p| {
            let s = scene::load(&p).unwrap_or_else(|e| panic!("{}: {e}", p.display()));
            (p, s.t_end)
        })
        .collect();
    let tmp = TempDir::new("scenes");
    let (n, times, collisions, multiple) = compare_scenes(&tmp.0, &scenes);
    eprintln!(
        "oracle: {n} scenes of scenes/, {times} run times, {collisions} collisions \
         ({multiple} of three or more clusters): identical ({:.1?})",
        start.elapsed()
    );
}

#[test]
fn random_scenes_match_the_oracle() {
    if !oracle_available() {
        return;
    }
    let start = Instant::now();
    let tmp = TempDir::new("random");
    let limits = Limits {
        max_n: 60,
        ..Default::default()
    };
    let mut scenes = Vec::new();
    let mut multi = 0;
    for seed in 0..RANDOM_SCENES {
        let len = 8 + (seed as usize * 37) % 400;
        let data = initial_data(&SplitMix64::new(seed).bytes(len), limits);
        let text = particles_toml(&data, Some(&format!("random-{seed}")));
        let path = tmp.0.join(format!("random-{seed}.toml"));
        std::fs::write(&path, text).expect("write a random scene");
        scenes.push((path, None));
        multi += usize::from(data.n() > 1);
    }
    assert!(
        multi > RANDOM_SCENES as usize / 2,
        "the generator gave trivial scenes"
    );
    let (n, times, collisions, multiple) = compare_scenes(&tmp.0, &scenes);
    assert!(
        collisions > 1000,
        "too few collisions ({collisions}) to mean much"
    );
    assert!(
        multiple > 50,
        "too few simultaneous collisions ({multiple})"
    );
    eprintln!(
        "oracle: {n} random scenes, {times} run times, {collisions} collisions \
         ({multiple} of three or more clusters): identical ({:.1?})",
        start.elapsed()
    );
}

/// The probe times include 0, the collision times, midpoints and a time
/// after the last collision (a check of this file's own helper).
#[test]
fn probe_times_cover_the_collisions() {
    let ts = probe_times(&[q(1, 2), q(1, 1)], Some(&q(3, 1)));
    let want = [
        q(0, 1),
        q(1, 4),
        q(1, 2),
        q(3, 4),
        q(1, 1),
        q(2, 1),
        q(3, 1),
    ];
    assert_eq!(ts, want);
    assert_eq!(probe_times(&[], None), vec![q(0, 1), q(1, 1)]);
}
