//! Every JSON output validates against its published schema
//! (`docs/guide/schema/NAME.json`, generated from the serde types by
//! `src/report/schema.rs`, which fails when a file is stale): real outputs
//! of the `sticky` command and of the library, parsed and validated — and
//! a schema that bites (a renamed key, an inexact number, are rejected).

use std::path::Path;
use std::process::Command;

use serde_json::Value;

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// Validates with Python's `jsonschema` (draft 2020-12): a Rust validator
/// costs minutes of build on the CI machine, Python's is installed there.
const VALIDATE: &str = r#"
import json, sys
from jsonschema import Draft202012Validator
schema = json.load(open(sys.argv[1]))
Draft202012Validator.check_schema(schema)
v = Draft202012Validator(schema)
for k, line in enumerate(sys.stdin):
    for e in v.iter_errors(json.loads(line)):
        print(f"instance {k}: {e.message} at {list(e.absolute_path)}")
"#;

/// Whether Python's `jsonschema` is importable; under CI (`CI` set) it
/// must be.
fn validator_available() -> bool {
    let ok = Command::new("python3")
        .args(["-c", "import jsonschema"])
        .output()
        .is_ok_and(|o| o.status.success());
    if !ok {
        assert!(
            std::env::var_os("CI").is_none(),
            "python3 with jsonschema is missing on CI"
        );
        eprintln!("skipped: python3 with jsonschema is not installed");
    }
    ok
}

/// The errors of each instance against the published schema `name`
/// (empty: all valid).
fn errors_all(name: &str, instances: &[Value]) -> Vec<String> {
    use std::io::Write;
    let schema = root().join(format!("docs/guide/schema/{name}.json"));
    let mut child = Command::new("python3")
        .args(["-c", VALIDATE])
        .arg(&schema)
        .stdin(std::process::Stdio::piped())
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("python3 runs");
    {
        let mut stdin = child.stdin.take().expect("a pipe");
        for v in instances {
            writeln!(stdin, "{v}").expect("write an instance");
        }
    }
    let out = child.wait_with_output().expect("python3 ends");
    assert!(
        out.status.success(),
        "{name}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8_lossy(&out.stdout)
        .lines()
        .map(String::from)
        .collect()
}

fn errors(name: &str, instance: &Value) -> Vec<String> {
    errors_all(name, std::slice::from_ref(instance))
}

/// Parses lines of output and validates them against `name`.
fn check_all(name: &str, lines: &[&str]) {
    let values: Vec<Value> = lines
        .iter()
        .map(|l| serde_json::from_str(l).unwrap_or_else(|e| panic!("{name}: {e}: {l}")))
        .collect();
    let errs = errors_all(name, &values);
    assert!(errs.is_empty(), "{name}: {errs:?}");
}

/// `sticky ARGS`' standard output (it must succeed).
fn sticky(args: &[&str]) -> String {
    let out = Command::new(env!("CARGO_BIN_EXE_sticky"))
        .args(args)
        .current_dir(root())
        .output()
        .expect("sticky runs");
    assert!(
        out.status.success(),
        "sticky {args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).expect("UTF-8 output")
}

/// Checks every non-empty line of `sticky ARGS` against `name`; returns how
/// many.
fn check_lines(name: &str, args: &[&str]) -> usize {
    let text = sticky(args);
    let lines: Vec<&str> = text.lines().filter(|l| !l.trim().is_empty()).collect();
    assert!(!lines.is_empty(), "sticky {args:?} printed nothing");
    check_all(name, &lines);
    lines.len()
}

#[test]
fn states_validate_on_both_paths() {
    if !validator_available() {
        return;
    }
    let scene = "scenes/collision-cascade.toml";
    // `auto` takes the streaming writer, `projection` the general one.
    for engine in ["auto", "projection"] {
        let args = [
            "run", scene, "--at", "0", "--at", "1/2", "--at", "3", "--json", "--engine", engine,
        ];
        assert_eq!(check_lines("state", &args), 3);
    }
    check_lines(
        "state",
        &["run", "scenes/random-1000.toml", "--at", "1/3", "--json"],
    );
}

#[test]
fn continuum_profiles_validate() {
    if !validator_available() {
        return;
    }
    for scene in [
        "scenes/riemann-compression.toml",
        "scenes/appendix-c-two-blocks.toml",
    ] {
        let args = [
            "run",
            scene,
            "--at",
            "1/4",
            "--model",
            "continuum",
            "--json",
        ];
        check_lines("continuum", &args);
    }
}

#[test]
fn events_validate() {
    if !validator_available() {
        return;
    }
    for scene in [
        "scenes/collision-cascade.toml",
        "scenes/three-cluster-simultaneous.toml",
        "docs/guide/examples/columns.toml",
    ] {
        assert_eq!(check_lines("events", &["events", scene, "--json"]), 1);
    }
}

#[test]
fn exports_validate() {
    if !validator_available() {
        return;
    }
    for scene in [
        "docs/guide/examples/thirds.toml",
        "scenes/collision-cascade.toml",
    ] {
        check_lines("export", &["export", scene, "--format", "json"]);
    }
}

#[test]
fn compare_reports_validate() {
    if !validator_available() {
        return;
    }
    for solution in [
        "docs/guide/examples/cascade-planted.csv",
        "docs/guide/examples/cascade-float.json",
        "docs/guide/examples/cascade-exact.json",
    ] {
        let args = [
            "compare",
            "scenes/collision-cascade.toml",
            solution,
            "--json",
        ];
        check_lines("compare", &args);
    }
}

#[test]
fn committed_proof_records_validate() {
    // The record `sticky prove --json` printed (tests/prove.rs re-runs
    // the prover against it); src/prove/json.rs pins the spelling.
    if !validator_available() {
        return;
    }
    let mut count = 0;
    for file in ["docs/prove-n1-3.jsonl", "docs/prove-n4.jsonl"] {
        let text = std::fs::read_to_string(root().join(file)).expect("the record");
        let lines: Vec<&str> = text.lines().filter(|l| !l.trim().is_empty()).collect();
        check_all("prove", &lines);
        count += lines.len();
    }
    assert!(count > 100, "{count} records");
}

#[test]
fn coq_rows_validate() {
    if !validator_available() {
        return;
    }
    let mut claims: Vec<&str> = sticky::claims::coq::all().iter().map(|r| r.claim).collect();
    claims.dedup();
    assert!(claims.len() > 10);
    let rows: Vec<String> = claims
        .iter()
        .map(|id| sticky::json::to_string(&sticky::claims::coq::rows(id)))
        .collect();
    let lines: Vec<&str> = rows.iter().map(String::as_str).collect();
    check_all("coq", &lines);
}

/// `sticky claims --json` on a few claims of every shape: a per-case
/// erratum (with its in-domain `witness_data` and a correction), a claim
/// that holds, one checked across N, and one not checkable.
#[test]
fn claims_validate() {
    use sticky::claims::ledger::{self, Budget, Status};
    if !validator_available() {
        return;
    }
    let budget = Budget {
        cases: 40,
        max_n: 4,
        scaling_max_n: 8,
        seed: 0x5EED,
    };
    let wanted = [
        "app:KKT",
        "prop:Oleinik",
        "eq:sup-micro-u-L#N-lambda",
        "prop:2ndorder-LagrPDE#exclusion-pairing",
    ];
    let entries: Vec<ledger::Entry> = sticky::claims::registry()
        .iter()
        .filter(|c| wanted.contains(&c.id))
        .map(|c| ledger::run_claim(c, budget))
        .collect();
    assert_eq!(
        entries.len(),
        wanted.len(),
        "every wanted claim is registered"
    );
    assert!(entries
        .iter()
        .any(|e| e.outcome.status == Status::Counterexample && e.outcome.witness_data.is_some()));
    let text = ledger::json(&entries);
    let value: Value = serde_json::from_str(&text).expect("the ledger is JSON");
    assert!(
        errors("claims", &value).is_empty(),
        "{:?}",
        errors("claims", &value)
    );
}

#[test]
fn the_schemas_reject_a_renamed_key_and_an_inexact_number() {
    if !validator_available() {
        return;
    }
    let line = sticky(&[
        "run",
        "scenes/collision-cascade.toml",
        "--at",
        "1",
        "--json",
    ]);
    let good: Value = serde_json::from_str(line.trim()).expect("JSON");
    assert!(errors("state", &good).is_empty());
    let mut renamed = good.clone();
    let clusters = renamed
        .as_object_mut()
        .and_then(|o| o.remove("clusters"))
        .expect("a clusters key");
    renamed["cluster"] = clusters;
    assert!(!errors("state", &renamed).is_empty());
    let mut inexact = good.clone();
    inexact["positions"][0] = Value::from("0.5");
    assert!(!errors("state", &inexact).is_empty());
    let mut number = good;
    number["t"] = Value::from(1);
    assert!(!errors("state", &number).is_empty());
}
