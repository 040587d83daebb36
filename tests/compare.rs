//! `sticky compare` and `sticky export` end to end: a solution perturbed by
//! known amounts is reported with exactly those amounts; one test per error
//! kind and per bad input (one clear `error: FILE:LINE: …` line, non-zero
//! exit, no panic).

use std::path::{Path, PathBuf};
use std::process::Command;

use serde_json::Value;

const BIN: &str = env!("CARGO_BIN_EXE_sticky");

/// 4 particles, 2r = 1/4. At t = 2 the first three form one cluster at
/// 3/4, 1, 5/4 with u = 0 and λ = (1/4, 1/4, 0); particle 3 rests at 4.
const SCENE: &str = "name = \"t4\"\n[particles]\nradius = \"1/8\"\npositions = [\"0\", \"1\", \"2\", \"4\"]\nvelocities = [\"1\", \"0\", \"-1\", \"0\"]\n";

struct Dir(PathBuf);

impl Dir {
    fn new(tag: &str) -> Dir {
        let d = std::env::temp_dir().join(format!("sticky-compare-{tag}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        std::fs::create_dir_all(&d).unwrap();
        std::fs::write(d.join("s.toml"), SCENE).unwrap();
        Dir(d)
    }
    fn file(&self, name: &str, text: &str) -> PathBuf {
        let p = self.0.join(name);
        std::fs::write(&p, text).unwrap();
        p
    }
    fn scene(&self) -> PathBuf {
        self.0.join("s.toml")
    }
}

impl Drop for Dir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

fn run(args: &[&Path]) -> (bool, String, String) {
    let o = Command::new(BIN).args(args).output().unwrap();
    (
        o.status.success(),
        String::from_utf8_lossy(&o.stdout).into_owned(),
        String::from_utf8_lossy(&o.stderr).into_owned(),
    )
}

/// `sticky compare` with extra arguments: exit code, stdout, stderr.
fn run_with(tag: &str, solution: &str, extra: &[&str]) -> (Option<i32>, String, String) {
    let d = Dir::new(tag);
    let s = d.file("sol.json", solution);
    let scene = d.scene();
    let mut args: Vec<&std::ffi::OsStr> =
        vec!["compare".as_ref(), scene.as_os_str(), s.as_os_str()];
    args.extend(extra.iter().map(|a| std::ffi::OsStr::new(*a)));
    let o = Command::new(BIN).args(&args).output().unwrap();
    (
        o.status.code(),
        String::from_utf8_lossy(&o.stdout).into_owned(),
        String::from_utf8_lossy(&o.stderr).into_owned(),
    )
}

fn compare_json(tag: &str, solution: &str) -> Value {
    let d = Dir::new(tag);
    let s = d.file("sol.json", solution);
    let (ok, out, err) = run(&[Path::new("compare"), &d.scene(), &s, Path::new("--json")]);
    assert!(ok, "compare failed: {err}");
    serde_json::from_str(&out).unwrap()
}

fn bad(tag: &str, name: &str, solution: &str, needle: &str) {
    let d = Dir::new(tag);
    let s = d.file(name, solution);
    let (ok, out, err) = run(&[Path::new("compare"), &d.scene(), &s]);
    assert!(!ok, "accepted: {out}");
    assert!(!err.contains("panicked"), "panic: {err}");
    assert_eq!(err.lines().count(), 1, "not one line: {err}");
    let line = err.trim_end();
    assert!(line.starts_with("error: "), "{line}");
    assert!(
        line.contains(&s.display().to_string()),
        "no file name: {line}"
    );
    assert!(line.contains(needle), "{line:?} lacks {needle:?}");
    assert!(out.is_empty(), "partial output: {out}");
}

const EXACT_T2: &str = r#"{"t": "2", "positions": ["3/4", "1", "5/4", "4"], "velocities": ["0", "0", "0", "0"], "multipliers": ["1/4", "1/4", "0"]}"#;

#[test]
fn the_exact_answer_is_exact() {
    let v = compare_json("exact", EXACT_T2);
    assert_eq!(v["verdict"], "exact");
    assert_eq!(v["times"][0]["position_max"]["value"], "0");
}

#[test]
fn known_perturbations_are_reported_exactly() {
    // Particle 3 moved right by 1/1000 (no overlap, no contact change), its
    // velocity by 1/7: max = those amounts; L² = (e²/N)^(1/2) = e/2.
    let v = compare_json(
        "perturbed",
        r#"{"t": "2", "positions": ["3/4", "1", "5/4", "4.001"], "velocities": ["0", "0", "0", "1/7"]}"#,
    );
    let t = &v["times"][0];
    assert_eq!(t["position_max"]["value"], "1/1000");
    assert_eq!(t["position_max"]["index"], 3);
    assert_eq!(t["position_l2_squared"], "1/4000000");
    assert_eq!(t["position_l2"], "1/2000");
    assert_eq!(t["velocity_max"]["value"], "1/7");
    assert_eq!(t["velocity_l2_squared"], "1/196");
    assert_eq!(t["velocity_l2"], "1/14");
    assert_eq!(t["overlaps"].as_array().unwrap().len(), 0);
    assert_eq!(v["verdict"], "inexact");
    // Every particle shifted by the same δ: max = L² = δ.
    let v = compare_json(
        "shifted",
        r#"{"t": "2", "positions": ["0.875", "1.125", "1.375", "4.125"]}"#,
    );
    assert_eq!(v["times"][0]["position_max"]["value"], "1/8");
    assert_eq!(v["times"][0]["position_l2"], "1/8");
    assert_eq!(v["times"][0]["velocity_max"], Value::Null);
}

/// Every string in a JSON value (to check none is a "≈" decimal).
fn strings(v: &Value, out: &mut Vec<String>) {
    match v {
        Value::String(s) => out.push(s.clone()),
        Value::Array(a) => a.iter().for_each(|x| strings(x, out)),
        Value::Object(o) => o.values().for_each(|x| strings(x, out)),
        _ => {}
    }
}

#[test]
fn json_figures_are_exact_strings_and_numbers() {
    let v = compare_json(
        "numbers",
        r#"{"t": "2", "positions": ["3/4", "1", "5/4", "4.001"], "velocities": ["0", "0", "0", "1/7"]}"#,
    );
    let t = &v["times"][0];
    assert_eq!(t["position_max"]["value"], "1/1000");
    assert_eq!(t["position_max"]["value_f64"].as_f64(), Some(0.001));
    assert_eq!(t["position_l2_f64"].as_f64(), Some(0.0005));
    assert_eq!(t["velocity_max"]["value_f64"].as_f64(), Some(1.0 / 7.0));
    assert_eq!(t["velocity_l2_f64"].as_f64(), Some(1.0 / 14.0));
    assert_eq!(t["t_f64"].as_f64(), Some(2.0));
    assert_eq!(v["index_base"], 0);
    // An L² error that is not rational: no exact root, its square exact, the
    // nearest double of the root as a number (√(1/2)/1000 ≈ 7.07e-4).
    let v = compare_json(
        "irrational",
        r#"{"t": "2", "positions": ["3/4", "1", "5/4", "4.001"], "velocities": ["0", "0", "1/1000", "1/1000"]}"#,
    );
    let t = &v["times"][0];
    assert_eq!(t["velocity_l2_squared"], "1/2000000");
    assert_eq!(t["velocity_l2"], Value::Null);
    // √(1/2000000) = 7.0710678118654752440…e-4, whose nearest double is
    // 0.0007071067811865475 (checked with 60-digit decimals); sqrt(0.5)/1000
    // in f64 rounds twice and gives the next double up.
    assert_eq!(t["velocity_l2_f64"].as_f64(), Some(0.0007071067811865475));
    let mut all = Vec::new();
    strings(&v, &mut all);
    assert!(all.iter().all(|s| !s.contains('≈')), "{all:?}");
}

#[test]
fn text_shows_decimals_beside_exact_figures() {
    let (code, out, err) = run_with(
        "decimals",
        r#"{"t": "2", "positions": ["3/4", "1", "1.2", "4.001"]}"#,
        &[],
    );
    assert_eq!(code, Some(0), "{err}");
    assert!(out.contains("max 1/20 (5.000e-2) at positions[2]"), "{out}");
    assert!(
        out.contains("pair (1, 2) depth 1/20 (5.000e-2) = 1/5 (2.000e-1) × 2r"),
        "{out}"
    );
    assert!(out.contains("L² √(2501/4000000) (2.500e-2)"), "{out}");
    assert!(out.lines().next().unwrap().contains("indices from 0"));
}

const OVERLAP: &str = r#"{"t": "2", "positions": ["3/4", "1", "1.2", "4"]}"#;

#[test]
fn fail_on_follows_the_verdict() {
    let inexact = r#"{"t": "2", "positions": ["3/4", "1", "5/4", "4.001"]}"#;
    let code = |tag, sol, extra: &[&str]| run_with(tag, sol, extra).0;
    assert_eq!(code("f1", OVERLAP, &["--fail-on", "invalid"]), Some(3));
    assert_eq!(code("f2", OVERLAP, &[]), Some(0));
    assert_eq!(code("f3", EXACT_T2, &["--fail-on", "invalid"]), Some(0));
    assert_eq!(code("f4", EXACT_T2, &["--fail-on", "rounding"]), Some(0));
    assert_eq!(code("f5", inexact, &["--fail-on", "invalid"]), Some(0));
    assert_eq!(code("f6", inexact, &["--fail-on", "inexact"]), Some(3));
    assert_eq!(code("f7", inexact, &["--fail-on", "rounding"]), Some(3));
    // The report is printed whole before the exit.
    let (c, out, _) = run_with("f8", OVERLAP, &["--fail-on", "invalid", "--json"]);
    assert_eq!(c, Some(3));
    let v: Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["verdict"], "invalid");
    let (c, _, err) = run_with("f9", OVERLAP, &["--fail-on", "bad"]);
    assert_eq!(c, Some(2));
    assert!(err.contains("not a verdict"), "{err}");
}

#[test]
fn overlap_tol_makes_one_ulp_rounding_and_keeps_1_1000_invalid() {
    // 1.2499999999999998 is the double 5/4 − 2^−52: particle 2 one ulp
    // into particle 1 (the exact cluster sits at 3/4, 1, 5/4).
    let ulp = r#"{"t": "2", "positions": [0.75, 1, 1.2499999999999998, 4]}"#;
    let v = compare_json("ulp0", ulp);
    assert_eq!(v["verdict"], "invalid");
    assert_eq!(v["times"][0]["overlaps"][0]["depth"], "1/4503599627370496");
    let (_, out, err) = run_with("ulp1", ulp, &["--json", "--overlap-tol", "1e-12"]);
    let v: Value = serde_json::from_str(&out).expect(&err);
    assert_eq!(v["verdict"], "rounding");
    assert_eq!(v["times"][0]["overlaps"][0]["within_tolerance"], true);
    assert_eq!(v["overlap_tol"], "1/1000000000000");
    // --fail-on inexact lets rounding pass, --fail-on rounding does not.
    let code = |tag, extra: &[&str]| run_with(tag, ulp, extra).0;
    assert_eq!(
        code("ulp2", &["--overlap-tol", "1e-12", "--fail-on", "inexact"]),
        Some(0)
    );
    assert_eq!(
        code("ulp3", &["--overlap-tol", "1e-12", "--fail-on", "rounding"]),
        Some(3)
    );
    // A 1/1000 overlap stays invalid under the same tolerance.
    let deep = r#"{"t": "2", "positions": ["3/4", "1", "1.249", "4"]}"#;
    let (_, out, _) = run_with("deep", deep, &["--json", "--overlap-tol", "1e-12"]);
    let v: Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["verdict"], "invalid");
    assert_eq!(v["times"][0]["overlaps"][0]["depth"], "1/1000");
    assert_eq!(v["times"][0]["overlaps"][0]["depth_relative"], "1/250");
    // One ulp off in a free particle's position, no overlap: rounding too;
    // 1/1000 off: inexact.
    let free = r#"{"t": "2", "positions": ["3/4", "1", "5/4", 4.000000000000001]}"#;
    let (_, out, _) = run_with("free", free, &["--json", "--overlap-tol", "1e-12"]);
    let v: Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["verdict"], "rounding");
}

#[test]
fn wrong_clusters_are_never_rounding() {
    // Exact positions, but the solver calls all four particles one cluster
    // (pair (2, 3) spurious), or splits the exact [0, 3] (pair (1, 2)
    // missed): inexact whatever the rounding tolerance.
    for (tag, clusters) in [("sp", "[[0, 4]]"), ("mi", "[[0, 2], [2, 1], [3, 1]]")] {
        let sol = format!(
            r#"{{"t": "2", "positions": ["3/4", "1", "5/4", "4"], "clusters": {clusters}}}"#
        );
        let (_, out, err) = run_with(tag, &sol, &["--json", "--overlap-tol", "1e-12"]);
        let v: Value = serde_json::from_str(&out).expect(&err);
        assert_eq!(v["verdict"], "inexact", "{clusters}");
    }
}

#[test]
fn relative_contact_tolerance() {
    // Particle 2 is 10⁻¹³ from touching particle 1: no contact with the
    // default tolerance 0, a contact with 10⁻⁶·2r.
    let near = r#"{"t": "2", "positions": ["3/4", "1", "1.2500000000001", "4"]}"#;
    let v = compare_json("near0", near);
    assert_eq!(v["times"][0]["missed_contacts"], 1);
    let (_, out, _) = run_with("near1", near, &["--json", "--contact-tol-rel", "1e-6"]);
    let v: Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["times"][0]["missed_contacts"], 0);
    assert_eq!(v["contact_tol"], "1/4000000");
    assert_eq!(v["verdict"], "inexact");
    let (_, out, _) = run_with(
        "near2",
        near,
        &[
            "--json",
            "--contact-tol-rel",
            "1e-6",
            "--overlap-tol",
            "1e-12",
        ],
    );
    let v: Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["verdict"], "rounding");
}

#[test]
fn json_numbers_are_read_as_the_doubles_they_are() {
    // 0.1 as a JSON number is the double 3602879701896397/2^55, not 1/10:
    // at t = 0 the exact answer is x⁰ = (0, 1, 2, 4), so putting 0.1 at
    // particle 0 gives exactly that double as the error.
    let v = compare_json("double", r#"{"t": 0, "positions": [0.1, 1, 2, 4]}"#);
    assert_eq!(
        v["times"][0]["position_max"]["value"],
        "3602879701896397/36028797018963968"
    );
}

#[test]
fn overlaps_name_the_pair_and_depth() {
    let v = compare_json(
        "overlap",
        r#"{"t": "2", "positions": ["3/4", "1", "1.2", "4"]}"#,
    );
    let o = &v["times"][0]["overlaps"];
    assert_eq!(o.as_array().unwrap().len(), 1);
    assert_eq!(o[0]["pair"], 1);
    assert_eq!(o[0]["depth"], "1/20");
    assert_eq!(v["verdict"], "invalid");
}

#[test]
fn wrong_clusters_are_named() {
    // Particle 2 leaves the cluster by 1/100: exact [0, 3] missed, the
    // solver's [0, 2] spurious.
    let v = compare_json(
        "clusters",
        r#"{"t": "2", "positions": ["3/4", "1", "1.26", "4"]}"#,
    );
    let t = &v["times"][0];
    assert_eq!(t["missed_clusters"], serde_json::json!([[0, 3]]));
    assert_eq!(t["spurious_clusters"], serde_json::json!([[0, 2]]));
    assert_eq!(t["missed_contacts"], 1);
    // The solver's own `clusters` are used when given.
    let v = compare_json(
        "clusters2",
        r#"{"t": "2", "positions": ["3/4", "1", "5/4", "4"], "clusters": [[0, 1], [1, 3]]}"#,
    );
    let t = &v["times"][0];
    assert_eq!(t["missed_clusters"], serde_json::json!([[0, 3]]));
    assert_eq!(t["spurious_clusters"], serde_json::json!([[1, 3]]));
    assert_eq!(t["spurious_contacts"], 1);
    assert_eq!(t["missed_contacts"], 1);
}

#[test]
fn lambda_sign_and_complementarity() {
    let v = compare_json(
        "lambda",
        r#"{"t": "2", "positions": ["3/4", "1", "5/4", "4"], "multipliers": ["-1/4", "1/4", "1/3"]}"#,
    );
    let t = &v["times"][0];
    assert_eq!(t["negative_multipliers"][0]["pair"], 0);
    assert_eq!(t["negative_multipliers"][0]["value"], "-1/4");
    assert_eq!(t["multiplier_max"]["value"], "1/2");
    // Pair 2: gap 4 − 5/4 − 1/4 = 5/2, λ = 1/3: product 5/6.
    assert_eq!(t["complementarity"][0]["pair"], 2);
    assert_eq!(t["complementarity"][0]["value"], "5/6");
    assert_eq!(v["verdict"], "invalid");
}

#[test]
fn oleinik_violations_are_found() {
    // At t = 1/4: x = (1/4, 1, 7/4, 4). Velocities with u_3 − u_2 = 10 over
    // a gap 9/4: 10/(9/4) ≥ 1/t = 4. Pair (2, 3) violates prop:Oleinik.
    let v = compare_json(
        "oleinik",
        r#"{"t": "1/4", "positions": ["1/4", "1", "7/4", "4"], "velocities": ["1", "0", "-1", "9"]}"#,
    );
    assert_eq!(v["times"][0]["oleinik"], serde_json::json!([3]));
    assert_eq!(v["verdict"], "invalid");
}

#[test]
fn csv_solutions_are_read_exactly() {
    let v = {
        let d = Dir::new("csv");
        let s = d.file(
            "sol.csv",
            "t,i,position,velocity\n2,0,0.75,0\n2,1,1,0\n2,2,1.25,0\n2,3,4.5,0\n",
        );
        let (ok, out, err) = run(&[Path::new("compare"), &d.scene(), &s, Path::new("--json")]);
        assert!(ok, "{err}");
        serde_json::from_str::<Value>(&out).unwrap()
    };
    assert_eq!(v["times"][0]["position_max"]["value"], "1/2");
}

#[test]
fn text_report_has_one_verdict_line() {
    let d = Dir::new("text");
    let s = d.file("sol.json", EXACT_T2);
    let (ok, out, _) = run(&[Path::new("compare"), &d.scene(), &s]);
    assert!(ok);
    assert_eq!(
        out.lines().filter(|l| l.starts_with("verdict: ")).count(),
        1
    );
}

#[test]
fn out_dir_gets_a_whole_csv() {
    let d = Dir::new("outdir");
    let s = d.file("sol.json", EXACT_T2);
    let out_dir = d.0.join("out");
    let (ok, out, err) = run(&[
        Path::new("compare"),
        &d.scene(),
        &s,
        Path::new("--out"),
        &out_dir,
    ]);
    assert!(ok, "{err}");
    assert!(out.contains("compare.csv"));
    let csv = std::fs::read_to_string(out_dir.join("compare.csv")).unwrap();
    assert_eq!(csv.lines().count(), 5);
    assert!(out_dir.join("compare-positions.svg").exists());
    assert!(out_dir.join("compare-velocities.svg").exists());
}

#[test]
fn error_chart_turns_log_when_errors_span_decades() {
    let chart = |tag: &str, sol: &str| {
        let d = Dir::new(tag);
        let s = d.file("sol.json", sol);
        let out_dir = d.0.join("out");
        let (ok, _, err) = run(&[
            Path::new("compare"),
            &d.scene(),
            &s,
            Path::new("--out"),
            &out_dir,
        ]);
        assert!(ok, "{err}");
        std::fs::read_to_string(out_dir.join("compare-positions.svg")).unwrap()
    };
    // Errors 1/1000 and 1/10⁶: three decades, log scale.
    let svg = chart(
        "log",
        r#"{"t": "2", "positions": ["3/4", "1.000001", "5/4", "4.001"]}"#,
    );
    assert!(svg.contains("log scale"));
    // Errors 1/1000 and 2/1000: linear.
    let svg = chart(
        "lin",
        r#"{"t": "2", "positions": ["3/4", "1.002", "5/4", "4.001"]}"#,
    );
    assert!(!svg.contains("log scale"));
}

#[test]
fn bad_wrong_n() {
    bad(
        "n",
        "s.json",
        r#"{"t": "1", "positions": ["0", "1", "2"]}"#,
        ":1: positions: 3 values",
    );
}

#[test]
fn bad_wrong_velocity_count() {
    bad(
        "nu",
        "s.json",
        r#"{"t": "1", "positions": ["0", "1", "2", "4"], "velocities": ["0"]}"#,
        "velocities: 1 values",
    );
}

#[test]
fn bad_negative_time() {
    bad(
        "neg",
        "s.json",
        r#"{"t": "-1", "positions": ["0", "1", "2", "4"]}"#,
        "negative",
    );
}

#[test]
fn bad_missing_time() {
    bad(
        "not",
        "s.json",
        r#"{"positions": ["0", "1", "2", "4"]}"#,
        "missing \"t\"",
    );
}

#[test]
fn bad_unknown_time_text() {
    bad(
        "tt",
        "s.json",
        r#"{"t": "soon", "positions": ["0", "1", "2", "4"]}"#,
        "t: \"soon\"",
    );
}

#[test]
fn bad_duplicate_time() {
    bad(
        "dup",
        "s.json",
        "{\"t\": 1, \"positions\": [0, 1, 2, 4]}\n{\"t\": \"1\", \"positions\": [0, 1, 2, 4]}\n",
        ":2: time t = 1 already given at line 1",
    );
}

#[test]
fn bad_nan() {
    bad(
        "nan",
        "s.json",
        "{\"t\": 1, \"positions\": [0, 1, 2, 4]}\n{\"t\": 2, \"positions\": [0, NaN, 2, 4]}\n",
        ":2: positions[1]: NaN is not a finite number",
    );
}

#[test]
fn bad_infinity() {
    bad(
        "inf",
        "s.json",
        r#"{"t": 1, "positions": [0, 1, 2, Infinity]}"#,
        "Infinity",
    );
    bad(
        "big",
        "s.json",
        r#"{"t": 1, "positions": [0, 1, 2, 1e400]}"#,
        "beyond the range",
    );
    bad(
        "sinf",
        "s.json",
        r#"{"t": 1, "positions": [0, 1, 2, "inf"]}"#,
        "positions[3]",
    );
}

#[test]
fn bad_malformed_line() {
    bad(
        "mal",
        "s.json",
        "{\"t\": 1, \"positions\": [0, 1, 2, 4]}\n{\"t\": 2, \"positions\": [0, 1, 2, 4]\n",
        ":2: malformed JSON",
    );
}

#[test]
fn bad_clusters() {
    bad(
        "cl",
        "s.json",
        r#"{"t": 1, "positions": [0, 1, 2, 4], "clusters": [[0, 2], [3, 1]]}"#,
        "partition",
    );
}

#[test]
fn bad_csv_rows() {
    bad(
        "csv1",
        "s.csv",
        "t,i,position\n1,0,0\n1,1,1\n1,2,2\n",
        "no row for particle i = 3",
    );
    bad("csv2", "s.csv", "1,0,0\n1,7,1\n", ":2: i = \"7\"");
    bad(
        "csv3",
        "s.csv",
        "1,0,0\n1,0,1\n",
        ":2: particle i = 0 at t = 1 given twice",
    );
    bad(
        "csv4",
        "s.csv",
        "1,0,abc\n",
        ":1: position of i = 0: \"abc\"",
    );
    bad(
        "csv6",
        "s.csv",
        "1,0,0,1\n1,1,1,0\n1,2,2,0\n1,3,nan,0\n",
        ":4: position of i = 3: \"nan\"",
    );
    bad("csv5", "s.csv", "1,0\n", ":1: 2 columns");
}

#[test]
fn bad_empty() {
    bad("empty", "s.json", "  \n", "empty solution");
}

#[test]
fn export_json_csv_npy() {
    let d = Dir::new("export");
    std::fs::write(
        d.scene(),
        "[particles]\nradius = \"1/20\"\npositions = [\"0\", \"1/3\"]\nvelocities = [\"1/10\", \"-1\"]\n",
    )
    .unwrap();
    let (ok, out, err) = run(&[
        Path::new("export"),
        &d.scene(),
        Path::new("--format"),
        Path::new("json"),
    ]);
    assert!(ok, "{err}");
    let v: Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["n"], 2);
    assert_eq!(v["positions"]["exact"][1], "1/3");
    assert_eq!(v["positions"]["f64"][1].as_f64(), Some(1.0 / 3.0));
    // 1/3 − nearest double = 1/3 − 6004799503160661/2^54.
    assert_eq!(v["positions"]["error"][1], "1/54043195528445952");
    assert_eq!(v["velocities"]["f64"][0].as_f64(), Some(0.1));
    assert_eq!(v["radius"]["f64"].as_f64(), Some(0.05));
    assert_eq!(v["f64_admissible"], true);
    let (ok, out, _) = run(&[
        Path::new("export"),
        &d.scene(),
        Path::new("--format"),
        Path::new("csv"),
    ]);
    assert!(ok);
    assert!(out
        .lines()
        .nth(3)
        .unwrap()
        .starts_with("1,3.333333333333333e-1,-1e0,1/3,-1,"));
    let npy = d.0.join("s.npy");
    let (ok, _, err) = run(&[
        Path::new("export"),
        &d.scene(),
        Path::new("--format"),
        Path::new("npy"),
        Path::new("--out"),
        &npy,
    ]);
    assert!(ok, "{err}");
    let b = std::fs::read(&npy).unwrap();
    assert_eq!(&b[..8], b"\x93NUMPY\x01\x00");
    let hl = u16::from_le_bytes([b[8], b[9]]) as usize;
    assert_eq!((10 + hl) % 64, 0);
    let header = std::str::from_utf8(&b[10..10 + hl]).unwrap();
    assert!(header.contains("'descr': '<f8'") && header.contains("'shape': (2, 2)"));
    let body: Vec<f64> = b[10 + hl..]
        .chunks(8)
        .map(|c| f64::from_le_bytes(c.try_into().unwrap()))
        .collect();
    assert_eq!(body, vec![0.0, 0.1, 1.0 / 3.0, -1.0]);
}
