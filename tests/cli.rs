//! The command-line contract of `sticky` (docs/guide/scenes.md and json.md): the summary of
//! the embedded default scene, the shape of `run --json` and
//! `events --json`, one clean error line per bad input, and no panic on a
//! closed pipe.

use std::io::Read;
use std::path::PathBuf;
use std::process::{Command, Output, Stdio};

use num_bigint::BigInt;
use num_integer::Integer;
use num_rational::BigRational;
use num_traits::{One, Zero};
use serde_json::Value;

const STICKY: &str = env!("CARGO_BIN_EXE_sticky");
const SCENES: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/scenes");

fn scene_path(name: &str) -> String {
    format!("{SCENES}/{name}")
}

fn sticky(args: &[&str]) -> Output {
    Command::new(STICKY)
        .args(args)
        .output()
        .expect("run the sticky binary")
}

fn stdout_ok(args: &[&str]) -> String {
    let out = sticky(args);
    assert!(
        out.status.success(),
        "sticky {args:?} failed ({}): {}",
        out.status,
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(
        out.stderr.is_empty(),
        "sticky {args:?} wrote to stderr: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).expect("UTF-8 output")
}

/// A scratch file under the system temp dir, removed on drop.
struct TempFile(PathBuf);

impl TempFile {
    fn new(tag: &str, text: &str) -> Self {
        let nanos = std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .map_or(0, |d| d.as_nanos());
        let path = std::env::temp_dir().join(format!(
            "sticky-cli-{tag}-{}-{nanos}.toml",
            std::process::id()
        ));
        std::fs::write(&path, text).expect("write a temp scene");
        TempFile(path)
    }
    fn path(&self) -> &str {
        self.0.to_str().expect("a UTF-8 temp path")
    }
}

impl Drop for TempFile {
    fn drop(&mut self) {
        let _ = std::fs::remove_file(&self.0);
    }
}

// ------------------------------------------------------------ rationals

/// An integer as the contract writes it: `0`, or an optional `-` and digits
/// without a leading zero.
fn canonical_integer(s: &str) -> Option<BigInt> {
    let digits = s.strip_prefix('-').unwrap_or(s);
    if digits.is_empty() || !digits.bytes().all(|b| b.is_ascii_digit()) {
        return None;
    }
    if digits.len() > 1 && digits.starts_with('0') {
        return None;
    }
    if s.starts_with('-') && digits == "0" {
        return None; // "-0"
    }
    BigInt::parse_bytes(digits.as_bytes(), 10).map(|v| if s.starts_with('-') { -v } else { v })
}

/// Checks that `v` is a JSON string holding a rational in lowest terms,
/// `"p/q"` (q > 1, gcd(p, q) = 1, sign on p) or `"p"`, and returns it.
fn rational(v: &Value, what: &str) -> BigRational {
    let s = v
        .as_str()
        .unwrap_or_else(|| panic!("{what}: {v} is not a string"));
    match s.split_once('/') {
        None => {
            let p = canonical_integer(s).unwrap_or_else(|| panic!("{what}: {s:?} is not p or p/q"));
            BigRational::from_integer(p)
        }
        Some((p, q)) => {
            let p =
                canonical_integer(p).unwrap_or_else(|| panic!("{what}: bad numerator in {s:?}"));
            assert!(
                !q.starts_with('-'),
                "{what}: sign on the denominator in {s:?}"
            );
            let q =
                canonical_integer(q).unwrap_or_else(|| panic!("{what}: bad denominator in {s:?}"));
            assert!(q > BigInt::one(), "{what}: denominator ≤ 1 in {s:?}");
            assert!(!p.is_zero(), "{what}: zero written as a fraction {s:?}");
            assert!(p.gcd(&q).is_one(), "{what}: {s:?} is not in lowest terms");
            BigRational::new(p, q)
        }
    }
}

/// The keys of a one-line JSON object in text order, checked against
/// `want` (serde_json's map does not keep the order, so read the text).
fn assert_key_order(line: &str, value: &Value, want: &[&str]) {
    let obj = value.as_object().expect("a JSON object");
    let mut keys: Vec<&str> = obj.keys().map(String::as_str).collect();
    keys.sort_unstable();
    let mut sorted_want = want.to_vec();
    sorted_want.sort_unstable();
    assert_eq!(keys, sorted_want, "keys of {line}");
    let positions: Vec<usize> = want
        .iter()
        .map(|k| {
            line.find(&format!("\"{k}\": "))
                .unwrap_or_else(|| panic!("key {k:?} not written as \"{k}\": in {line}"))
        })
        .collect();
    assert!(
        positions.windows(2).all(|w| w[0] < w[1]),
        "keys not in the order {want:?}: {line}"
    );
}

fn q(n: i64, d: i64) -> BigRational {
    BigRational::new(BigInt::from(n), BigInt::from(d))
}

// ------------------------------------------------------------ summary

#[test]
fn no_arguments_prints_the_default_summary() {
    let out = stdout_ok(&[]);
    assert!(out.contains("appendix-c-two-blocks"), "{out}");
    assert!(out.contains("1 collision"), "{out}");
    assert!(!out.contains("1 collisions"), "{out}");
    assert!(out.contains("checks: all"), "{out}");
}

#[test]
fn check_prints_a_summary_for_a_scene_file() {
    let path = scene_path("collision-cascade.toml");
    let out = stdout_ok(&["check", &path]);
    assert!(out.contains("collision-cascade"), "{out}");
    assert!(out.contains("4 collisions"), "{out}");
    assert!(out.contains("checks: all"), "{out}");
}

// ------------------------------------------------------------ run --json

const STATE_KEYS: [&str; 7] = [
    "n",
    "radius",
    "t",
    "positions",
    "velocities",
    "multipliers",
    "clusters",
];

/// Checks one `run --json` line; returns the parsed value.
fn check_state_line(line: &str, n: usize, t: &BigRational) -> Value {
    let v: Value = serde_json::from_str(line).unwrap_or_else(|e| panic!("{e}: {line}"));
    assert_key_order(line, &v, &STATE_KEYS);
    assert_eq!(v["n"].as_u64(), Some(n as u64), "{line}");
    let r = rational(&v["radius"], "radius");
    assert!(r > BigRational::zero());
    assert_eq!(&rational(&v["t"], "t"), t, "t echoes the requested time");
    let arr = |k: &str| {
        v[k].as_array()
            .unwrap_or_else(|| panic!("{k} is not an array"))
            .clone()
    };
    let x: Vec<BigRational> = arr("positions")
        .iter()
        .map(|e| rational(e, "positions"))
        .collect();
    let u: Vec<BigRational> = arr("velocities")
        .iter()
        .map(|e| rational(e, "velocities"))
        .collect();
    let lam: Vec<BigRational> = arr("multipliers")
        .iter()
        .map(|e| rational(e, "multipliers"))
        .collect();
    assert_eq!(x.len(), n);
    assert_eq!(u.len(), n);
    assert_eq!(lam.len(), n - 1, "multipliers are λ_1 … λ_(N−1)");
    assert!(
        lam.iter().all(|l| *l >= BigRational::zero()),
        "λ ≥ 0: {line}"
    );
    let two_r = r.clone() + &r;
    // Clusters: [first, size] pairs covering 0..N left to right, each a
    // maximal run of exact contacts.
    let mut next = 0usize;
    for c in arr("clusters") {
        let c = c.as_array().expect("[first, size]");
        assert_eq!(c.len(), 2, "{line}");
        let first = c[0].as_u64().expect("first is an integer") as usize;
        let size = c[1].as_u64().expect("size is an integer") as usize;
        assert_eq!(first, next, "clusters do not tile 0..N: {line}");
        assert!(size >= 1, "{line}");
        for i in first..first + size - 1 {
            assert_eq!(
                x[i + 1].clone() - &x[i],
                two_r,
                "contact inside a cluster: {line}"
            );
        }
        if first + size < n {
            assert!(
                x[first + size].clone() - &x[first + size - 1] > two_r,
                "{line}"
            );
        }
        next = first + size;
    }
    assert_eq!(next, n, "clusters cover 0..N: {line}");
    v
}

#[test]
fn run_json_follows_the_contract() {
    let path = scene_path("collision-cascade.toml");
    let times = ["0", "1/2", "0.75", "5/6", "2/2", "1.5e0", "14/9", "3"];
    let mut args = vec!["run", path.as_str(), "--json"];
    for t in &times {
        args.push("--at");
        args.push(t);
    }
    let out = stdout_ok(&args);
    let lines: Vec<&str> = out.lines().collect();
    assert_eq!(lines.len(), times.len(), "one line per --at: {out}");
    let want_t = [
        q(0, 1),
        q(1, 2),
        q(3, 4),
        q(5, 6),
        q(1, 1),
        q(3, 2),
        q(14, 9),
        q(3, 1),
    ];
    for (line, t) in lines.iter().zip(&want_t) {
        check_state_line(line, 6, t);
    }
    // The documented example state of the scene at t = 1 (hand-checked in
    // the scene's comment: clusters {1,2,3} and {4,5}, particle 6 alone).
    let v: Value = serde_json::from_str(lines[4]).unwrap();
    assert_eq!(v["clusters"], serde_json::json!([[0, 3], [3, 2], [5, 1]]));
    assert_eq!(
        v["velocities"],
        serde_json::json!(["1", "1", "1", "-1/2", "-1/2", "1"])
    );
    // At t = 0 particles 5 and 6 touch (same contact cluster) though they
    // separate at once.
    let v0: Value = serde_json::from_str(lines[0]).unwrap();
    assert_eq!(v0["clusters"][4], serde_json::json!([4, 2]));
    assert!(lines[0].starts_with(
        "{\"n\": 6, \"radius\": \"1/4\", \"t\": \"0\", \"positions\": [\"0\", \"1\", "
    ));
}

#[test]
fn run_json_on_every_scene_at_t_end() {
    for entry in std::fs::read_dir(SCENES).expect("scenes/") {
        let path = entry.expect("entry").path();
        if path.extension().is_none_or(|e| e != "toml") {
            continue;
        }
        let scene = sticky::scene::load(&path).expect("a valid scene");
        let t = scene.t_end.clone().unwrap_or_else(|| q(1, 1));
        let t_text = t.to_string();
        let p = path.to_str().unwrap();
        let out = stdout_ok(&["run", p, "--at", &t_text, "--at", "0", "--json"]);
        let lines: Vec<&str> = out.lines().collect();
        assert_eq!(lines.len(), 2);
        check_state_line(lines[0], scene.n(), &t);
        check_state_line(lines[1], scene.n(), &q(0, 1));
    }
}

// ------------------------------------------------------------ events --json

fn check_events_line(line: &str, n: usize) -> Vec<Value> {
    let v: Value = serde_json::from_str(line).unwrap_or_else(|e| panic!("{e}: {line}"));
    assert_key_order(line, &v, &["events"]);
    let events = v["events"].as_array().expect("an array").clone();
    let mut previous: Option<(BigRational, u64)> = None;
    for e in &events {
        let text = e.to_string();
        let t = rational(&e["t"], "t");
        assert!(t > BigRational::zero(), "collision at t ≤ 0: {text}");
        let first = e["first"].as_u64().expect("first");
        let size = e["size"].as_u64().expect("size");
        let parts: Vec<u64> = e["parts"]
            .as_array()
            .expect("parts")
            .iter()
            .map(|p| p.as_u64().expect("a part size"))
            .collect();
        assert!(parts.len() >= 2, "parts has at least two entries: {text}");
        assert!(parts.iter().all(|&p| p >= 1), "{text}");
        assert_eq!(parts.iter().sum::<u64>(), size, "parts sum to size: {text}");
        assert!(first + size <= n as u64, "{text}");
        let key = (t, first);
        if let Some(prev) = &previous {
            assert!(*prev < key, "events not sorted by (t, first): {line}");
        }
        previous = Some(key);
    }
    // Each event object's keys appear in the documented order in the text.
    let mut rest = line;
    for _ in &events {
        let start = rest
            .find("{\"t\": ")
            .expect("an event written as {\"t\": ...");
        let obj = &rest[start..];
        let end = obj.find('}').expect("end of event");
        let obj = &obj[..=end];
        let v: Value = serde_json::from_str(obj).expect("event JSON");
        assert_key_order(obj, &v, &["t", "first", "size", "parts"]);
        rest = &rest[start + end..];
    }
    events
}

#[test]
fn events_json_follows_the_contract() {
    let path = scene_path("collision-cascade.toml");
    let out = stdout_ok(&["events", &path, "--json"]);
    assert_eq!(out.lines().count(), 1, "{out}");
    let events = check_events_line(out.trim_end(), 6);
    assert_eq!(events.len(), 4);
    assert_eq!(
        out.trim_end(),
        r#"{"events": [{"t": "1/2", "first": 0, "size": 2, "parts": [1, 1]}, {"t": "5/6", "first": 0, "size": 3, "parts": [2, 1]}, {"t": "1", "first": 3, "size": 2, "parts": [1, 1]}, {"t": "14/9", "first": 0, "size": 5, "parts": [3, 2]}]}"#
    );
    // Three clusters meeting at one instant: one event with three parts.
    let path = scene_path("three-cluster-simultaneous.toml");
    let out = stdout_ok(&["events", &path, "--json"]);
    let events = check_events_line(out.trim_end(), 8);
    assert_eq!(events[0]["parts"], serde_json::json!([3, 2, 2]));
    assert_eq!(events[0]["t"], "1/2");
    for entry in std::fs::read_dir(SCENES).expect("scenes/") {
        let path = entry.expect("entry").path();
        if path.extension().is_none_or(|e| e != "toml") {
            continue;
        }
        let n = sticky::scene::load(&path).expect("valid").n();
        let out = stdout_ok(&["events", path.to_str().unwrap(), "--json"]);
        check_events_line(out.trim_end(), n);
    }
}

// ------------------------------------------------------------ errors

/// Runs `args`, expects a failure with no stdout and exactly one stderr line
/// `error: …` containing every string of `needles`.
fn expect_error(args: &[&str], needles: &[&str]) -> String {
    let out = sticky(args);
    let stderr = String::from_utf8_lossy(&out.stderr).to_string();
    assert!(
        !out.status.success(),
        "sticky {args:?} succeeded; stderr: {stderr}"
    );
    assert_ne!(
        out.status.code(),
        Some(101),
        "sticky {args:?} panicked: {stderr}"
    );
    assert!(
        out.stdout.is_empty(),
        "sticky {args:?} printed on stdout: {}",
        String::from_utf8_lossy(&out.stdout)
    );
    let lines: Vec<&str> = stderr.lines().collect();
    assert_eq!(
        lines.len(),
        1,
        "sticky {args:?}: expected exactly one stderr line, got:\n{stderr}"
    );
    assert!(lines[0].starts_with("error:"), "{stderr}");
    for needle in needles {
        assert!(
            lines[0].to_lowercase().contains(&needle.to_lowercase()),
            "sticky {args:?}: the error does not mention {needle:?}: {stderr}"
        );
    }
    stderr
}

/// A bad scene through `run`, `events` and `check`: each fails the same way
/// and names the scene path.
fn bad_scene(tag: &str, text: &str, needles: &[&str]) {
    let file = TempFile::new(tag, text);
    let p = file.path();
    let mut with_path = vec![p];
    with_path.extend_from_slice(needles);
    expect_error(&["run", p, "--at", "1", "--json"], &with_path);
    expect_error(&["events", p, "--json"], &with_path);
    expect_error(&["check", p], &with_path);
}

#[test]
fn error_nonexistent_file() {
    let path = std::env::temp_dir().join(format!("sticky-cli-missing-{}.toml", std::process::id()));
    let p = path.to_str().unwrap();
    expect_error(&["run", p, "--at", "1", "--json"], &[p, "no such file"]);
    expect_error(&["events", p, "--json"], &[p, "no such file"]);
}

#[test]
fn error_overlapping_positions() {
    bad_scene(
        "overlap",
        "[particles]\nradius = \"1/8\"\npositions = [\"0\", \"1/2\", \"5/8\"]\nvelocities = [0, 0, 0]\n",
        &["positions[1] and positions[2] overlap", "1/8", "2r = 1/4"],
    );
}

#[test]
fn error_approaching_contact() {
    bad_scene(
        "approach",
        "[particles]\nradius = \"1/8\"\npositions = [\"0\", \"1/4\"]\nvelocities = [\"1\", \"0\"]\n",
        &["particles 0 and 1 (indices from 0)", "approach"],
    );
}

#[test]
fn error_toml_float() {
    bad_scene(
        "float",
        "[particles]\npositions = [0, 0.5]\nvelocities = [0, 0]\n",
        &["particles.positions[1]", "float", "quote"],
    );
}

#[test]
fn error_bad_number() {
    bad_scene(
        "badnum",
        "[particles]\npositions = [\"0\", \"one\"]\nvelocities = [0, 0]\n",
        &["particles.positions[1]", "\"one\"", "not an exact number"],
    );
}

#[test]
fn error_zero_denominator() {
    bad_scene(
        "zeroden",
        "[particles]\npositions = [\"0\", \"1\"]\nvelocities = [\"0\", \"1/0\"]\n",
        &["particles.velocities[1]", "zero denominator"],
    );
}

#[test]
fn error_length_mismatch() {
    bad_scene(
        "length",
        "[particles]\npositions = [\"0\", \"1\", \"2\"]\nvelocities = [\"0\", \"1\"]\n",
        &["length mismatch", "3 positions", "2 velocities"],
    );
}

#[test]
fn error_no_particles() {
    bad_scene(
        "empty",
        "[particles]\npositions = []\nvelocities = []\n",
        &["no particles"],
    );
    bad_scene(
        "macro-zero",
        "[macro]\nparticles = 0\nblocks = [{ from = 0, to = 1, density = 1, velocity = 0 }]\n",
        &["no particles"],
    );
}

#[test]
fn error_non_positive_radius() {
    bad_scene(
        "radius0",
        "[particles]\nradius = 0\npositions = [\"0\", \"1\"]\nvelocities = [0, 0]\n",
        &["radius must be positive", "0"],
    );
    bad_scene(
        "radiusneg",
        "[particles]\nradius = \"-1/2\"\npositions = [\"0\", \"1\"]\nvelocities = [0, 0]\n",
        &["radius must be positive", "-1/2"],
    );
}

#[test]
fn error_density_above_one() {
    bad_scene(
        "density",
        "[macro]\nparticles = 4\nblocks = [{ from = 0, to = \"2/3\", density = \"3/2\", velocity = 0 }]\n",
        &["macro.blocks[0]", "density 3/2"],
    );
}

#[test]
fn error_mass_not_one() {
    bad_scene(
        "mass",
        "[macro]\nparticles = 4\nblocks = [{ from = 0, to = 1, density = \"1/2\", velocity = 0 }]\n",
        &["mass 1/2", "not 1"],
    );
}

#[test]
fn error_unsorted_blocks() {
    bad_scene(
        "unsorted",
        "[macro]\nparticles = 4\nblocks = [\n  { from = 2, to = \"5/2\", density = 1, velocity = 0 },\n  { from = 0, to = \"1/2\", density = 1, velocity = 0 },\n]\n",
        &["macro.blocks[1]", "unsorted"],
    );
}

#[test]
fn error_overlapping_blocks() {
    bad_scene(
        "overlapblocks",
        "[macro]\nparticles = 4\nblocks = [\n  { from = 0, to = 1, density = \"1/2\", velocity = 0 },\n  { from = \"1/2\", to = 1, density = 1, velocity = 0 },\n]\n",
        &["macro.blocks[1]", "overlaps macro.blocks[0]"],
    );
}

#[test]
fn error_negative_time() {
    let path = scene_path("collision-cascade.toml");
    expect_error(&["run", &path, "--at=-1", "--json"], &["-1", "negative"]);
    expect_error(
        &["run", &path, "--at", "-1/2", "--json"],
        &["-1/2", "negative"],
    );
}

#[test]
fn error_malformed_time() {
    let path = scene_path("collision-cascade.toml");
    expect_error(
        &["run", &path, "--at", "soon", "--json"],
        &["soon", "not an exact number"],
    );
    expect_error(
        &["run", &path, "--at", "1/0", "--json"],
        &["1/0", "zero denominator"],
    );
    expect_error(&["run", &path, "--at", "0.5.1", "--json"], &["0.5.1"]);
}

// ------------------------------------------------------------ broken pipe

/// Reads a few bytes of the output, then closes the pipe: the binary must
/// not panic (exit 101) nor complain.
fn closed_pipe(args: &[&str]) {
    let mut child = Command::new(STICKY)
        .args(args)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("spawn sticky");
    let mut stdout = child.stdout.take().expect("stdout");
    let mut head = [0u8; 10];
    stdout.read_exact(&mut head).expect("the first bytes");
    drop(stdout);
    let out = child.wait_with_output().expect("wait");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_ne!(
        out.status.code(),
        Some(101),
        "sticky {args:?} panicked on a closed pipe: {stderr}"
    );
    assert!(!stderr.contains("panicked"), "sticky {args:?}: {stderr}");
}

#[test]
fn closed_pipe_does_not_panic() {
    let big = scene_path("random-1000.toml");
    // Much more than a pipe buffer: 1000 particles at 20 times.
    let mut args = vec!["run", big.as_str(), "--json"];
    let times: Vec<String> = (0..20).map(|k| format!("{k}/20")).collect();
    for t in &times {
        args.push("--at");
        args.push(t);
    }
    closed_pipe(&args);
    let mut table = args.clone();
    table.retain(|a| *a != "--json");
    closed_pipe(&table);
    closed_pipe(&["events", big.as_str(), "--json"]);
    closed_pipe(&["events", big.as_str()]);
    closed_pipe(&[]);
}

// ------------------------------------------------------------ round trip

#[test]
fn particles_toml_round_trips_through_the_binary() {
    use sticky::generate::{initial_data, Limits, SplitMix64};
    let mut rng = SplitMix64::new(99);
    for len in [0usize, 5, 50, 500] {
        let data = initial_data(&rng.bytes(len), Limits::default());
        let text = sticky::scene::particles_toml(&data, Some("round-trip"));
        let parsed = sticky::scene::parse(&text).expect("parses");
        assert_eq!(parsed.data, data);
        let file = TempFile::new("roundtrip", &text);
        let out = stdout_ok(&["run", file.path(), "--at", "0", "--json"]);
        let v = check_state_line(out.trim_end(), data.n(), &q(0, 1));
        let xs: Vec<BigRational> = v["positions"]
            .as_array()
            .unwrap()
            .iter()
            .map(|e| rational(e, "x"))
            .collect();
        assert_eq!(xs, data.positions());
    }
}

/// `run --model continuum`: the block-level continuum solution of a
/// `[macro]` scene, marked as such, and equal to the continuum module's
/// profile; a `[particles]` scene is refused with one clean line.
#[test]
fn run_model_continuum() {
    let path = scene_path("riemann-compression.toml");
    let text = stdout_ok(&["run", &path, "--at", "1", "--model", "continuum", "--json"]);
    let v: Value = serde_json::from_str(text.trim()).expect("one JSON object");
    assert_eq!(v["model"], "continuum");
    assert_eq!(v["t"], "1");
    // Two blocks of mass 1/2 meeting head on at speeds ±1 are fully
    // congested at t = 1: one plateau [0, 1] at rest, X = w + 1/2.
    let plateaus = v["plateaus"].as_array().expect("plateaus");
    assert_eq!(plateaus.len(), 1);
    assert_eq!(plateaus[0]["w0"], "0");
    assert_eq!(plateaus[0]["w1"], "1");
    assert_eq!(plateaus[0]["level"], "1/2");
    assert_eq!(plateaus[0]["velocity"], "0");
    let table = stdout_ok(&["run", &path, "--at", "1/4", "--model", "continuum"]);
    assert!(table.starts_with("model: continuum"), "{table}");
    expect_error(
        &[
            "run",
            &scene_path("random-1000.toml"),
            "--at",
            "1",
            "--model",
            "continuum",
        ],
        &["needs a [macro] scene"],
    );
}

/// `sticky generate`: the TOML scene on stdout, or in `--out` when given
/// (it used to be printed and `--out` ignored); the CSV form names a column
/// file holding the same exact data.
#[test]
fn generate_writes_where_it_is_told() {
    let printed = stdout_ok(&["generate", "--n", "7", "--seed", "3"]);
    let from_stdout = sticky::scene::parse(&printed).expect("a scene");
    let dir = std::env::temp_dir().join(format!("sticky-cli-generate-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let d = dir.to_str().expect("UTF-8 temp dir");
    for format in ["toml", "csv"] {
        let paths = stdout_ok(&[
            "generate", "--n", "7", "--seed", "3", "--format", format, "--out", d,
        ]);
        let first = paths.lines().next().expect("a path");
        let scene_file = first.strip_prefix("wrote ").unwrap_or(first);
        assert!(scene_file.ends_with(".toml"), "{paths}");
        let scene =
            sticky::scene::load(std::path::Path::new(scene_file)).expect("the written scene loads");
        assert_eq!(scene.data, from_stdout.data, "--format {format}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// One index convention (issue 28): every text output counts particles from
/// 0, as the JSON does, and says so in its header. On
/// three-cluster-simultaneous the first collision forms the cluster of the
/// JSON's `{"first": 0, "size": 7}`: particles 0–6.
#[test]
fn text_outputs_index_particles_from_0_and_say_so() {
    let path = scene_path("three-cluster-simultaneous.toml");
    let events = stdout_ok(&["events", &path]);
    let mut lines = events.lines();
    assert_eq!(
        lines.next(),
        Some("2 collisions   (particle indices from 0)")
    );
    assert!(lines.any(|l| l.starts_with("  1/2  0–6 ")), "{events}");
    let table = stdout_ok(&["run", &path, "--at", "1/2"]);
    assert!(table
        .lines()
        .next()
        .unwrap_or("")
        .ends_with("(particle indices from 0)"));
    let rows: Vec<&str> = table.lines().skip(2).collect();
    assert!(rows[0].starts_with("  0  3/2 "), "{table}");
    assert!(rows[7].starts_with("  7  23/2 "), "{table}");
    assert!(rows[7].ends_with("  7"), "{table}");
    let check = stdout_ok(&["check", &path]);
    assert!(
        check.contains("final clusters (t ≥ 2): [0–7]   (particle indices from 0)"),
        "{check}"
    );
}
