//! Every exact engine against the oracle extracted from the Coq proofs,
//! `proofs/coq/oracle` (issue 26): field by field, exactly.
//!
//! The oracle's positions are the extracted lexicographic PAVA, proved in
//! Coq to equal `P_K(x⁰ + t u⁰)` for every N (`Sticky.Oracle.
//! state_positions_spec`, `prop:proj-micro`), its velocities proved to be
//! the right derivative (`Sticky.RightDerivative.state_velocities_spec`),
//! its multipliers `Multipliers.multiplier`
//! (`Sticky.OracleMultipliers.oracle_multipliers_are_multiplier`), its
//! clusters the contact clusters of its positions
//! (`Sticky.ContactClusters.state_clusters_spec`; proofs/coq/README.md).
//!
//! Scenes: [`sticky::generate::initial_data`] — contacts, separating
//! contacts, simultaneous collisions — many small ones (N ≤ 60) and a few
//! big ones (N = 10³ and 10⁴). Times: 0, every collision instant of the
//! generic event history (all of them for small scenes, a sample for big
//! ones), midpoints, random rationals, one after the last collision.
//!
//! The oracle has a second extracted path, the event-driven dynamics with its
//! multipliers and contact clusters (`--dynamics`,
//! `Sticky.DynamicsState.dynamics_state`, proved equal to the first path for
//! `t > 0` by `Sticky.DynamicsState.dynamics_state_is_state_at`); it is
//! quadratic in N or worse, so the engines are compared with it on the small
//! scenes only.
//!
//! Without the oracle built the test prints how to build it and passes,
//! except under `CI=true`, where that is a failure.

use std::io::Write;
use std::path::Path;
use std::process::{Command, Stdio};
use std::time::Instant;

use num_bigint::BigInt;
use num_rational::BigRational;
use serde_json::Value;
use sticky::fast::engine::ENGINES;
use sticky::generate::{initial_data, Limits, SplitMix64};
use sticky::initial::InitialData;
use sticky::rational::{parse_exact, render_exact};
use sticky::state::State;
use sticky::trajectory::Trajectory;

const ORACLE: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/proofs/coq/oracle");

/// Small scenes: this many, N ≤ [`SMALL_N`].
const SMALL_SCENES: u64 = 150;
const SMALL_N: usize = 60;
/// Big scenes: their sizes.
const BIG_NS: [usize; 4] = [1_000, 1_000, 10_000, 10_000];
/// At most this many collision instants per big scene.
const BIG_COLLISION_TIMES: usize = 4;

/// `true` when the oracle executable exists; otherwise prints how to build
/// it and returns `false`, or panics under `CI=true`.
fn oracle_built() -> bool {
    if Path::new(ORACLE).is_file() {
        return true;
    }
    let how = "build it with `make -C proofs/coq oracle` (Debian: `apt-get install -y coq \
               ocaml ocaml-findlib libzarith-ocaml-dev`)";
    if std::env::var("CI").is_ok_and(|v| v == "true") {
        panic!("coq_oracle: {ORACLE} is missing under CI=true; {how}");
    }
    eprintln!(
        "SKIPPED coq_oracle: {ORACLE} is missing, so the engines were NOT compared with \
         the Coq-extracted oracle; {how}."
    );
    false
}

/// The oracle's input: `N r`, then `x_i u_i` per line.
fn oracle_input(data: &InitialData<BigRational>) -> String {
    let mut s = format!("{} {}\n", data.n(), render_exact(data.radius()));
    for (x, u) in data.positions().iter().zip(data.velocities()) {
        s.push_str(&format!("{} {}\n", render_exact(x), render_exact(u)));
    }
    s
}

/// Which extracted computation the oracle prints.
#[derive(Debug, Clone, Copy)]
enum OraclePath {
    /// The proved PAVA (the default; O(N) per time).
    Pava,
    /// The event-driven dynamics (`--dynamics`; small N only).
    Dynamics,
}

/// Runs the oracle on `data` at `times`: one JSON value per time.
fn run_oracle(
    data: &InitialData<BigRational>,
    times: &[BigRational],
    path: OraclePath,
) -> Vec<Value> {
    let flag = match path {
        OraclePath::Pava => None,
        OraclePath::Dynamics => Some("--dynamics".to_string()),
    };
    let mut child = Command::new(ORACLE)
        .args(flag.into_iter().chain(times.iter().map(render_exact)))
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("start proofs/coq/oracle");
    let input = oracle_input(data);
    let shown = if data.n() <= 20 {
        format!("\ninput:\n{input}")
    } else {
        String::new()
    };
    let mut stdin = child.stdin.take().expect("oracle stdin");
    let writer = std::thread::spawn(move || stdin.write_all(input.as_bytes()));
    let out = child.wait_with_output().expect("wait for the oracle");
    writer
        .join()
        .expect("writer thread")
        .expect("write the scene to the oracle");
    assert!(
        out.status.success(),
        "oracle ({path:?}) failed on N = {}: {}{shown}",
        data.n(),
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8(out.stdout).expect("oracle output is UTF-8");
    let lines: Vec<Value> = text
        .lines()
        .map(|l| serde_json::from_str(l).expect("oracle line is JSON"))
        .collect();
    assert_eq!(lines.len(), times.len(), "one oracle line per time");
    lines
}

/// An exact rational string of the oracle, checked to be in lowest terms
/// (it re-renders to itself).
fn exact(v: &Value, what: &str) -> BigRational {
    let s = v
        .as_str()
        .unwrap_or_else(|| panic!("{what}: not a string: {v}"));
    let q = parse_exact(s).unwrap_or_else(|e| panic!("{what}: {s:?}: {e}"));
    assert_eq!(render_exact(&q), s, "{what}: not in lowest terms");
    q
}

fn exact_list(v: &Value, what: &str) -> Vec<BigRational> {
    v.as_array()
        .unwrap_or_else(|| panic!("{what}: not an array"))
        .iter()
        .enumerate()
        .map(|(i, x)| exact(x, &format!("{what}[{i}]")))
        .collect()
}

/// One oracle line, parsed once (every engine is compared with it).
struct OracleState {
    n: u64,
    radius: BigRational,
    t: BigRational,
    positions: Vec<BigRational>,
    velocities: Vec<BigRational>,
    multipliers: Vec<BigRational>,
    /// `[first, size]`, particles indexed from 0.
    clusters: Vec<(usize, usize)>,
}

fn parse_line(line: &Value) -> OracleState {
    let clusters = line["clusters"]
        .as_array()
        .expect("clusters array")
        .iter()
        .map(|c| {
            let pair = c.as_array().expect("cluster [first, size]");
            assert_eq!(pair.len(), 2, "cluster [first, size]");
            let get = |k: usize| pair[k].as_u64().expect("cluster entry") as usize;
            (get(0), get(1))
        })
        .collect();
    OracleState {
        n: line["n"].as_u64().expect("n"),
        radius: exact(&line["radius"], "radius"),
        t: exact(&line["t"], "t"),
        positions: exact_list(&line["positions"], "positions"),
        velocities: exact_list(&line["velocities"], "velocities"),
        multipliers: exact_list(&line["multipliers"], "multipliers"),
        clusters,
    }
}

/// Compares one engine's state with one oracle state, field by field.
fn compare(
    engine: &str,
    data: &InitialData<BigRational>,
    state: &State<BigRational>,
    oracle: &OracleState,
) {
    let at = format!(
        "engine {engine}, N = {}, t = {}",
        data.n(),
        render_exact(&state.t)
    );
    assert_eq!(oracle.n, data.n() as u64, "{at}: n");
    assert_eq!(&oracle.radius, data.radius(), "{at}: radius");
    assert_eq!(oracle.t, state.t, "{at}: t");
    let fields = [
        ("positions", &state.positions, &oracle.positions),
        ("velocities", &state.velocities, &oracle.velocities),
        ("multipliers", &state.multipliers, &oracle.multipliers),
    ];
    for (name, ours, theirs) in fields {
        assert_eq!(theirs.len(), ours.len(), "{at}: length of {name}");
        if let Some(i) = (0..ours.len()).find(|&i| theirs[i] != ours[i]) {
            panic!(
                "{at}: {name}[{i}] (indices from 0): engine {} vs Coq oracle {}",
                render_exact(&ours[i]),
                render_exact(&theirs[i])
            );
        }
    }
    let ours: Vec<(usize, usize)> = state.clusters.iter().map(|c| (c.first, c.size)).collect();
    assert_eq!(
        ours, oracle.clusters,
        "{at}: clusters [first, size] (indices from 0)"
    );
}

/// The times of a scene: 0, collision instants (at most `max_collisions`,
/// spread), midpoints, a random rational, one after the last collision.
fn times_of(
    data: &InitialData<BigRational>,
    max_collisions: usize,
    rng: &mut SplitMix64,
) -> Vec<BigRational> {
    let traj = Trajectory::new(data.clone());
    let mut instants: Vec<BigRational> = traj.impulses().iter().map(|i| i.t.clone()).collect();
    instants.dedup();
    let step = instants.len().div_ceil(max_collisions.max(1)).max(1);
    let picked: Vec<BigRational> = instants.iter().step_by(step).cloned().collect();
    let mut times = vec![BigRational::from_integer(BigInt::from(0))];
    for w in picked.windows(2) {
        times.push((w[0].clone() + &w[1]) / BigInt::from(2));
    }
    times.extend(picked.iter().cloned());
    if let Some(last) = instants.last() {
        times.push(last.clone() + BigRational::from_integer(BigInt::from(1)));
    }
    let num = BigInt::from(rng.next_u64() % 97);
    let den = BigInt::from(1 + rng.next_u64() % 16);
    times.push(BigRational::new(num, den));
    times
}

/// Runs every engine of [`ENGINES`] on `data` at `times` and compares each
/// state with the oracle's line (computed along `path`).
fn check_scene(data: &InitialData<BigRational>, times: &[BigRational], path: OraclePath) -> usize {
    let lines: Vec<OracleState> = run_oracle(data, times, path)
        .iter()
        .map(parse_line)
        .collect();
    let mut compared = 0;
    for engine in ENGINES {
        let prepared = engine.prepare(data);
        for (t, line) in times.iter().zip(&lines) {
            let state = prepared
                .state_at(t)
                .unwrap_or_else(|e| panic!("engine {}: state_at: {e}", engine.name()));
            compare(
                &format!("{} vs {path:?}", engine.name()),
                data,
                &state,
                line,
            );
            compared += 1;
        }
    }
    compared
}

#[test]
fn every_engine_equals_the_coq_oracle_on_small_scenes() {
    if !oracle_built() {
        return;
    }
    let start = Instant::now();
    let limits = Limits {
        max_n: SMALL_N,
        ..Default::default()
    };
    let mut rng = SplitMix64::new(26);
    let (mut compared, mut times_asked) = (0, 0);
    for seed in 0..SMALL_SCENES {
        let len = 8 + (seed as usize % 200);
        let data = initial_data(&SplitMix64::new(seed).bytes(len), limits);
        let times = times_of(&data, usize::MAX, &mut rng);
        times_asked += times.len();
        compared += check_scene(&data, &times, OraclePath::Pava);
        compared += check_scene(&data, &times, OraclePath::Dynamics);
    }
    eprintln!(
        "coq_oracle: {SMALL_SCENES} small scenes, {times_asked} times, {compared} engine states \
         equal to the Coq oracle (both paths) in {:.1?}",
        start.elapsed()
    );
}

#[test]
fn every_engine_equals_the_coq_oracle_on_big_scenes() {
    if !oracle_built() {
        return;
    }
    let start = Instant::now();
    let mut rng = SplitMix64::new(2026);
    let mut compared = 0;
    for (k, &n) in BIG_NS.iter().enumerate() {
        let limits = Limits {
            max_n: n,
            ..Default::default()
        };
        let data = initial_data(&SplitMix64::new(1000 + k as u64).bytes(8 * n), limits);
        assert_eq!(data.n(), n, "the generator fills N = {n}");
        let times = times_of(&data, BIG_COLLISION_TIMES, &mut rng);
        compared += check_scene(&data, &times, OraclePath::Pava);
    }
    eprintln!(
        "coq_oracle: big scenes N = {BIG_NS:?}, {compared} engine states equal to the Coq \
         oracle in {:.1?}",
        start.elapsed()
    );
}
