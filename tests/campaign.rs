//! Campaigns split into shards (issue 38, item 3): `--shard I/N` of every
//! shard, then `sticky merge`, prints the single run's report; `--jobs K`
//! too. The fast tests use `prove` at N = 1, `converge` to N = 64 and
//! `atlas --quick` on three scenes (seconds each); the ledger, `prove` at
//! N ≤ 2 and the whole `atlas --quick` are campaigns (`cargo test --release
//! --test campaign -- --ignored`).

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

/// The converge campaign of the tests: the smallest study with an exact
/// and an `f64` part (N = 8 … 64, exact to 32, and the engine check).
fn converge_args() -> Vec<String> {
    let scene = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/riemann-compression.toml");
    [
        "converge",
        scene.to_str().expect("UTF-8 path"),
        "--n-max",
        "64",
        "--exact-max",
        "32",
    ]
    .map(String::from)
    .to_vec()
}

/// A converge summary without its `seconds` column (each N's wall time,
/// the one measurement) and with the output folder's name taken out.
fn converge_text(text: &str, dir: &Path) -> String {
    let dir = format!("{}/", dir.display());
    text.lines()
        .map(|l| {
            let row = matches!(l.split_whitespace().nth(1), Some("exact" | "f64"));
            match (row, l.get(..15), l.get(23..)) {
                (true, Some(head), Some(tail)) => format!("{head}{tail}\n"),
                _ => format!("{}\n", l.replace(&dir, "")),
            }
        })
        .collect()
}

/// A campaign that writes into a folder (`--out`): run once into
/// `DIR/single`, then as the guide's Slurm array over four shards merged
/// into `DIR/merged`; what each printed, and the two folders.
struct FolderRuns {
    single: String,
    single_dir: PathBuf,
    merged: String,
    merged_dir: PathBuf,
}

impl FolderRuns {
    fn of<S: AsRef<str>>(dir: &Path, args: &[S]) -> FolderRuns {
        let args: Vec<&str> = args.iter().map(AsRef::as_ref).collect();
        let single_dir = dir.join("single");
        let single = stdout(sticky().args(&args).arg("--out").arg(&single_dir));
        std::fs::create_dir_all(dir.join("work")).expect("work folder");
        let merged_dir = dir.join("merged");
        let merged = slurm_campaign(
            &dir.join("work"),
            &args.join(" "),
            4,
            &["--out", merged_dir.to_str().expect("UTF-8 path")],
        );
        FolderRuns {
            single,
            single_dir,
            merged,
            merged_dir,
        }
    }
}

/// The names of the files in `dir`, sorted.
fn file_names(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .expect("the run's files")
        .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

/// `convergence.csv` without its `seconds` column (the fourth).
fn without_seconds_column(csv: &str) -> Vec<String> {
    csv.lines()
        .map(|l| {
            let mut fields: Vec<&str> = l.split(',').collect();
            assert_eq!(fields[3].trim(), fields[3]);
            fields.remove(3);
            fields.join(",")
        })
        .collect()
}

#[test]
fn converge_shards_merge_to_the_single_run() {
    let dir = scratch("converge");
    let args = converge_args();
    let FolderRuns {
        single,
        single_dir,
        merged,
        merged_dir,
    } = FolderRuns::of(&dir, &args);
    assert!(single.contains("engine check at N = 32"), "{single}");
    assert_eq!(
        converge_text(&merged, &merged_dir),
        converge_text(&single, &single_dir)
    );
    let names = file_names(&single_dir);
    assert!(names.len() >= 6, "{names:?}");
    for name in &names {
        let a = std::fs::read(single_dir.join(name)).expect("single file");
        let b = std::fs::read(merged_dir.join(name)).expect("merged file");
        if name == "convergence.csv" {
            let text = |v: Vec<u8>| String::from_utf8(v).expect("UTF-8");
            assert_eq!(
                without_seconds_column(&text(b)),
                without_seconds_column(&text(a))
            );
        } else {
            assert!(a == b, "{name} differs");
        }
    }
    // Two units at a time in one process: the same report.
    let jobs_dir = dir.join("jobs");
    let jobs = stdout(
        sticky()
            .args(&args)
            .args(["--jobs", "2", "--out"])
            .arg(&jobs_dir),
    );
    assert_eq!(
        converge_text(&jobs, &jobs_dir),
        converge_text(&single, &single_dir)
    );
    // A shard missing, and a shard of another study.
    let shards = |k: usize| dir.join("work/shards").join(format!("{k}.jsonl"));
    let e = refusal(
        sticky()
            .arg("merge")
            .args([shards(0), shards(1), shards(3)]),
    );
    assert!(e.contains("missing shard: 2/4"), "{e}");
    let other = dir.join("other.jsonl");
    let text = stdout(
        sticky()
            .args(&args[..4])
            .args(["--exact-max", "16", "--shard", "2/4"]),
    );
    std::fs::write(&other, text).expect("shard written");
    let e = refusal(
        sticky()
            .arg("merge")
            .args([shards(0), shards(1), other, shards(3)]),
    );
    assert!(
        e.contains("not a shard of the same campaign") && e.contains("setup"),
        "{e}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// The rows of an atlas CSV (`atlas.csv`, `stability.csv`) without the
/// columns measured on the clock, `wall_seconds` and `repeats` (each row
/// split on commas outside double quotes).
fn atlas_rows_without_clock(csv: &str) -> Vec<Vec<String>> {
    let fields = |line: &str| -> Vec<String> {
        let (mut out, mut cell, mut quoted) = (Vec::new(), String::new(), false);
        for c in line.chars() {
            match c {
                '"' => quoted = !quoted,
                ',' if !quoted => out.push(std::mem::take(&mut cell)),
                _ => {}
            }
            if c != ',' || quoted {
                cell.push(c);
            }
        }
        out.push(cell);
        out
    };
    let mut lines = csv.lines();
    let header = fields(lines.next().expect("a header"));
    let clock: Vec<usize> = ["wall_seconds", "repeats"]
        .iter()
        .map(|c| header.iter().position(|h| h == c).expect("clock column"))
        .collect();
    std::iter::once(header.clone())
        .chain(lines.map(fields))
        .map(|row| {
            assert_eq!(row.len(), header.len(), "{row:?}");
            row.into_iter()
                .enumerate()
                .filter(|(i, _)| !clock.contains(i))
                .map(|(_, cell)| cell)
                .collect()
        })
        .collect()
}

/// `sticky atlas ARGS` once, then as the guide's Slurm array over four
/// shards and `sticky merge --out`: the same paths printed, and every file
/// equal — byte for byte but for what the clock measures: the
/// `wall_seconds` and `repeats` columns of the two CSV files, and the
/// charts drawn against the wall time (`pareto-*`, `cost-vs-n`).
fn atlas_shards_merge_to_the_single_run(name: &str, args: &[&str]) {
    let dir = scratch(name);
    let FolderRuns {
        single,
        single_dir,
        merged,
        merged_dir,
    } = FolderRuns::of(&dir, args);
    let relative = |text: &str, d: &Path| text.replace(&format!("{}/", d.display()), "");
    assert_eq!(
        relative(&merged, &merged_dir),
        relative(&single, &single_dir)
    );
    let names = file_names(&single_dir);
    assert!(names.contains(&"stability.md".to_string()), "{names:?}");
    let mut equal = 0;
    for name in &names {
        let a = std::fs::read(single_dir.join(name)).expect("single file");
        let b = std::fs::read(merged_dir.join(name)).expect("merged file");
        if name.ends_with(".csv") {
            let text = |v: Vec<u8>| String::from_utf8(v).expect("UTF-8");
            assert_eq!(
                atlas_rows_without_clock(&text(b)),
                atlas_rows_without_clock(&text(a)),
                "{name}"
            );
        } else if !(name.starts_with("pareto-") || name.starts_with("cost-vs-n")) {
            assert!(a == b, "{name} differs");
            equal += 1;
        }
    }
    assert!(equal >= 2, "{names:?}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// Two suite scenes and one stability scene of `atlas --quick`: seconds.
#[test]
fn atlas_scene_shards_merge_to_the_single_run() {
    atlas_shards_merge_to_the_single_run(
        "atlas-scenes",
        &[
            "atlas",
            "--quick",
            "--scene",
            "random-10",
            "--scene",
            "three-cluster-simultaneous",
            "--scene",
            "near-simultaneous",
        ],
    );
}

#[test]
#[ignore = "campaign: atlas --quick twice (single, 4 shards), about a minute"]
fn atlas_quick_shards_merge_to_the_single_run() {
    atlas_shards_merge_to_the_single_run("atlas-quick", &["atlas", "--quick"]);
}

#[test]
fn atlas_shards_refuse_the_peers() {
    let err = refusal(sticky().args(["atlas", "--quick", "--peers", "--shard", "0/2"]));
    assert!(err.contains("--peers runs in a single atlas only"), "{err}");
}
