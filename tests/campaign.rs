//! Campaigns split into shards (issue 38, item 3): `--shard I/N` of every
//! shard, then `sticky merge`, prints the single run's report; `--jobs K`
//! too. The fast tests use `prove` at N = 1 (seconds); the ledger and
//! `prove` at N ≤ 2 are campaigns (`cargo test --release --test campaign
//! -- --ignored`).

use std::path::{Path, PathBuf};
use std::process::Command;

fn sticky() -> Command {
    Command::new(env!("CARGO_BIN_EXE_sticky"))
}

fn solver() -> bool {
    if sticky::prove::solver_available().is_some() {
        return true;
    }
    if std::env::var_os("CI").is_some() {
        panic!("the SMT solver z3 is missing on CI: .ci/run must `apt-get install -y z3`");
    }
    eprintln!("skipped: the SMT solver z3 is not installed (apt-get install z3)");
    false
}

/// Stdout of a successful run.
fn stdout(cmd: &mut Command) -> String {
    let out = cmd.output().expect("sticky runs");
    assert!(
        out.status.success(),
        "{cmd:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).expect("UTF-8")
}

/// Stderr of a failed run.
fn refusal(cmd: &mut Command) -> String {
    let out = cmd.output().expect("sticky runs");
    assert!(!out.status.success(), "{cmd:?} should fail");
    String::from_utf8(out.stderr).expect("UTF-8")
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("sticky-campaign-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("scratch folder");
    dir
}

/// `prove --json` lines without their `seconds` (the one field that is a
/// measurement).
fn without_seconds(jsonl: &str) -> Vec<serde_json::Value> {
    jsonl
        .lines()
        .map(|l| {
            let mut v: serde_json::Value = serde_json::from_str(l).expect("JSON line");
            let seconds = v.as_object_mut().and_then(|o| o.remove("seconds"));
            assert!(seconds.is_some(), "no seconds in {l}");
            v
        })
        .collect()
}

/// The Slurm script of docs/guide/cluster.md (its ```bash block with
/// `--array`).
fn slurm_script() -> String {
    let guide = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/guide/cluster.md"),
    )
    .expect("docs/guide/cluster.md");
    let block = guide
        .split("```bash\n")
        .skip(1)
        .map(|b| b.split("```").next().unwrap_or(""))
        .find(|b| b.contains("#SBATCH --array=0-63"))
        .expect("a ```bash block with #SBATCH --array=0-63");
    block.to_string()
}

/// Runs the guide's Slurm script as each array task of `shards` would
/// (Slurm need not be installed: the script is plain bash), then merges.
fn slurm_campaign(dir: &Path, campaign: &str, shards: usize, merge: &[&str]) -> String {
    let script = dir.join("shard.sh");
    std::fs::write(&script, slurm_script()).expect("script written");
    let bin = Path::new(env!("CARGO_BIN_EXE_sticky"))
        .parent()
        .expect("binary folder")
        .to_path_buf();
    let path = std::env::join_paths(std::iter::once(bin).chain(std::env::split_paths(
        &std::env::var_os("PATH").unwrap_or_default(),
    )))
    .expect("PATH");
    for task in 0..shards {
        let out = Command::new("bash")
            .arg(&script)
            .current_dir(dir)
            .env("PATH", &path)
            .env("SLURM_ARRAY_TASK_ID", task.to_string())
            .env("SLURM_CPUS_PER_TASK", "2")
            .env("SHARDS", shards.to_string())
            .env("CAMPAIGN", campaign)
            .output()
            .expect("bash runs");
        assert!(
            out.status.success(),
            "task {task}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
    }
    let files: Vec<PathBuf> = (0..shards)
        .map(|t| dir.join("shards").join(format!("{t}.jsonl")))
        .collect();
    stdout(sticky().arg("merge").args(&files).args(merge))
}

#[test]
fn prove_shards_from_the_slurm_script_merge_to_the_single_run() {
    if !solver() {
        return;
    }
    let dir = scratch("prove1");
    let single = stdout(sticky().args(["prove", "--n", "1", "--json"]));
    let merged = slurm_campaign(&dir, "prove --n 1", 4, &["--json"]);
    assert!(single.lines().count() > 30, "{single}");
    assert_eq!(without_seconds(&merged), without_seconds(&single));
    // The table: every column but the seconds (the row's characters
    // 82 … 89, after the id, N, status, paths and queries).
    let table = |text: &str| -> Vec<String> {
        text.lines()
            .enumerate()
            .map(|(k, l)| match (k, l.get(..82), l.get(90..)) {
                (3.., Some(head), Some(tail)) => format!("{head}{tail}"),
                _ => l.to_string(),
            })
            .collect()
    };
    let single = stdout(sticky().args(["prove", "--n", "1"]));
    let merged = stdout(
        sticky()
            .arg("merge")
            .arg(dir.join("shards/2.jsonl"))
            .args([0, 1, 3].map(|t| dir.join(format!("shards/{t}.jsonl")))),
    );
    assert_eq!(table(&merged), table(&single));
    // Two units at a time: the same report.
    let jobs = stdout(sticky().args(["prove", "--n", "1", "--json", "--jobs", "2"]));
    assert_eq!(without_seconds(&jobs), without_seconds(&single_json()));
    let _ = std::fs::remove_dir_all(&dir);
}

fn single_json() -> String {
    stdout(sticky().args(["prove", "--n", "1", "--json"]))
}

#[test]
fn merge_refuses_missing_duplicated_and_mixed_shards() {
    if !solver() {
        return;
    }
    let dir = scratch("refuse");
    let shard = |spec: &str, extra: &[&str], name: &str| -> PathBuf {
        let text = stdout(
            sticky()
                .args([
                    "prove",
                    "--n",
                    "1",
                    "--claim",
                    "prop:Oleinik",
                    "--shard",
                    spec,
                ])
                .args(extra),
        );
        let path = dir.join(name);
        std::fs::write(&path, text).expect("shard written");
        path
    };
    let a = shard("0/2", &[], "a.jsonl");
    let b = shard("1/2", &[], "b.jsonl");
    let other = shard("1/2", &["--seconds", "7"], "c.jsonl");
    let thirds = shard("1/3", &[], "d.jsonl");
    assert!(stdout(sticky().arg("merge").args([&b, &a])).contains("prop:Oleinik"));
    let e = refusal(sticky().arg("merge").arg(&a));
    assert!(e.contains("missing shard: 1/2"), "{e}");
    let e = refusal(sticky().arg("merge").args([&a, &b, &b]));
    assert!(e.contains("shard 1/2 given twice"), "{e}");
    let e = refusal(sticky().arg("merge").args([&a, &other]));
    assert!(
        e.contains("not a shard of the same campaign") && e.contains("setup"),
        "{e}"
    );
    let e = refusal(sticky().arg("merge").args([&a, &thirds]));
    assert!(e.contains("not a shard of the same campaign"), "{e}");
    // A file cut short: the header alone.
    let head = std::fs::read_to_string(&a).expect("shard");
    std::fs::write(&a, head.lines().next().expect("header")).expect("cut");
    let e = refusal(sticky().arg("merge").args([&a, &b]));
    assert!(e.contains("missing (did the job stop early?)"), "{e}");
    for bad in ["4/4", "0/0", "1", "a/b"] {
        let e = refusal(sticky().args(["prove", "--n", "1", "--shard", bad]));
        assert!(e.contains("--shard"), "{bad}: {e}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
#[ignore = "campaign: prove at N ≤ 2 twice (single, 4 shards), about a minute"]
fn prove_n2_shards_merge_to_the_single_run() {
    if !solver() {
        return;
    }
    let dir = scratch("prove2");
    let single = stdout(sticky().args(["prove", "--n", "2", "--json"]));
    let merged = slurm_campaign(&dir, "prove --n 2", 4, &["--json"]);
    assert_eq!(without_seconds(&merged), without_seconds(&single));
    let _ = std::fs::remove_dir_all(&dir);
}

const LEDGER: [&str; 7] = [
    "claims",
    "--cases",
    "2",
    "--max-n",
    "3",
    "--scaling-max-n",
    "8",
];

#[test]
#[ignore = "campaign: the claims ledger three times at its smallest budget, about 3 min of CPU"]
fn claims_shards_merge_to_the_single_run_byte_for_byte() {
    let dir = scratch("claims");
    let single = stdout(sticky().args(LEDGER).arg("--json"));
    let merged = slurm_campaign(&dir, &LEDGER.join(" "), 4, &["--json"]);
    assert_eq!(merged, single);
    let files: Vec<PathBuf> = (0..4)
        .map(|t| dir.join("shards").join(format!("{t}.jsonl")))
        .collect();
    let table = stdout(sticky().arg("merge").args(&files));
    assert_eq!(table, stdout(sticky().args(LEDGER)));
    let jobs = stdout(sticky().args(LEDGER).args(["--json", "--jobs", "2"]));
    assert_eq!(jobs, single);
    let _ = std::fs::remove_dir_all(&dir);
}
