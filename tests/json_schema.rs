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

/// The published schema `name`, compiled.
fn validator(name: &str) -> jsonschema::Validator {
    let path = root().join(format!("docs/guide/schema/{name}.json"));
    let text = std::fs::read_to_string(&path).expect("a published schema");
    let schema: Value = serde_json::from_str(&text).expect("a schema is JSON");
    jsonschema::validator_for(&schema).expect("a valid JSON Schema")
}

/// The errors of `instance` against the schema `name` (empty: valid).
fn errors(name: &str, instance: &Value) -> Vec<String> {
    validator(name)
        .iter_errors(instance)
        .map(|e| format!("{} at {}", e, e.instance_path()))
        .collect()
}

/// Parses one line of output and validates it against `name`.
fn check(name: &str, line: &str) {
    let v: Value = serde_json::from_str(line).unwrap_or_else(|e| panic!("{name}: {e}: {line}"));
    let errs = errors(name, &v);
    assert!(errs.is_empty(), "{name}: {errs:?}\n{line}");
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
    lines.iter().for_each(|l| check(name, l));
    lines.len()
}

#[test]
fn states_validate_on_both_paths() {
    let scene = "scenes/collision-cascade.toml";
    // `auto` takes the streaming writer, `projection` the general one.
    for engine in ["auto", "projection"] {
        let args = [
            "run", scene, "--at", "0", "--at", "1/2", "--at", "3", "--json", "--engine", engine,
        ];
        assert_eq!(check_lines("state", &args), 3);
    }
    check_lines("state", &["run", "scenes/random-1000.toml", "--at", "1/3", "--json"]);
}

#[test]
fn continuum_profiles_validate() {
    for scene in [
        "scenes/riemann-compression.toml",
        "scenes/appendix-c-two-blocks.toml",
    ] {
        let args = ["run", scene, "--at", "1/4", "--model", "continuum", "--json"];
        check_lines("continuum", &args);
    }
}

#[test]
fn events_validate() {
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
    for scene in [
        "docs/guide/examples/thirds.toml",
        "scenes/collision-cascade.toml",
    ] {
        check_lines("export", &["export", scene, "--format", "json"]);
    }
}

#[test]
fn compare_reports_validate() {
    for solution in [
        "docs/guide/examples/cascade-planted.csv",
        "docs/guide/examples/cascade-float.json",
        "docs/guide/examples/cascade-exact.json",
    ] {
        let args = ["compare", "scenes/collision-cascade.toml", solution, "--json"];
        check_lines("compare", &args);
    }
}

#[test]
fn committed_proof_records_validate() {
    // The record `sticky prove --json` printed (tests/prove.rs re-runs
    // the prover against it); src/prove/json.rs pins the spelling.
    let mut lines = 0;
    for file in ["docs/prove-n1-3.jsonl", "docs/prove-n4.jsonl"] {
        let text = std::fs::read_to_string(root().join(file)).expect("the record");
        for line in text.lines().filter(|l| !l.trim().is_empty()) {
            check("prove", line);
            lines += 1;
        }
    }
    assert!(lines > 100, "{lines} records");
}

#[test]
fn coq_rows_validate() {
    let mut claims: Vec<&str> = sticky::claims::coq::all().iter().map(|r| r.claim).collect();
    claims.dedup();
    assert!(claims.len() > 10);
    for id in claims {
        check("coq", &sticky::json::to_string(&sticky::claims::coq::rows(id)));
    }
}

#[test]
fn the_schemas_reject_a_renamed_key_and_an_inexact_number() {
    let line = sticky(&["run", "scenes/collision-cascade.toml", "--at", "1", "--json"]);
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
