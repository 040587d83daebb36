//! `sticky bench` smoke test: every method measured on a small N, JSON keys
//! as documented (timings are reports, never asserted).

use num_rational::BigRational;
use sticky::report::bench::{json, run, scene, BenchOptions, Events, Metric, Peers};

#[test]
fn bench_reports_every_method() {
    let opts = BenchOptions {
        n: 2000,
        reps: 1,
        peers: Peers::Skip,
        events: Events::Time,
        metric: Metric::Time,
    };
    let t = BigRational::new(1.into(), 100.into());
    let scripts = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scripts");
    let r = run(&opts, &t, &scripts);
    let text = json(&r);
    let v: serde_json::Value = serde_json::from_str(&text).expect("valid JSON");
    assert_eq!(v["n"], 2000);
    for key in [
        "f64",
        "exact_int",
        "exact_bigint",
        "bigrational_naive",
        "adaptive",
        "events",
    ] {
        assert!(v["ns_per_particle"].get(key).is_some(), "missing {key}");
    }
    for key in [
        "f64",
        "exact_int",
        "exact_int_lowest",
        "exact_bigint",
        "exact_bigint_100",
        "bigrational_naive",
        "adaptive",
        "adaptive_bigdata",
        "events",
        "events_columns",
        "events_lowest",
        "events_generic",
    ] {
        assert!(
            v["ns_per_particle"][key].as_f64().is_some_and(|x| x > 0.0),
            "{key} not measured"
        );
    }
    // The bench scene is admissible and exactly N particles.
    assert_eq!(scene(777, 3).n(), 777);
}

/// `sticky bench --e2e` at a small N: every `sticky` pipeline runs as a
/// whole process and reports its wall time and its own peak memory; the
/// scipy rows are empty and say why when skipped, or when the helper
/// script is missing (Python peers absent), while the `sticky` rows still
/// run; the JSON is valid.
#[test]
fn e2e_rows_measure_every_sticky_pipeline() {
    use sticky::report::bench::e2e::{self, E2eOptions, Tool, PIPELINES};
    let empty = std::env::temp_dir().join(format!("sticky-e2e-noscripts-{}", std::process::id()));
    std::fs::create_dir_all(&empty).unwrap();
    for (peers, scripts) in [(Peers::Skip, empty.clone()), (Peers::Run, empty.clone())] {
        let opts = E2eOptions {
            n: 500,
            reps: 2,
            peers,
            sticky: env!("CARGO_BIN_EXE_sticky").into(),
            scripts,
        };
        let r = e2e::run(&opts, |_| {}).expect("inputs written");
        assert_eq!(r.rows.len(), PIPELINES.len());
        for row in &r.rows {
            if row.tool == Tool::Scipy {
                assert!(row.wall_s.is_none(), "{row:?}");
                assert!(r.vs_scipy(row).is_none());
                // Skipped; or the helper missing (python3 fails on it, or
                // python3 itself is absent).
                let why: &[&str] = if peers == Peers::Run {
                    &["failed", "cannot start"]
                } else {
                    &["skipped"]
                };
                assert!(why.iter().any(|w| row.note.contains(w)), "{row:?}");
            } else {
                assert!(row.wall_s.is_some_and(|w| w > 0.0), "{row:?}");
                // The child's own high-water mark (a process holds more
                // than a MiB).
                assert!(row.peak_kib.is_some_and(|k| k > 1024.0), "{row:?}");
                assert!(row.note.starts_with("in "), "{row:?}");
                // An answer was written: N positions at least.
                assert!(row.out_bytes.is_some_and(|b| b > 1000), "{row:?}");
                // The I/O floor of the same bytes, and the ratio to it.
                assert!(row.floor_s.is_some_and(|f| f > 0.0), "{row:?}");
                assert!(r.vs_floor(row).is_some(), "{row:?}");
            }
        }
        let v: serde_json::Value = serde_json::from_str(&e2e::json(&r)).expect("valid JSON");
        assert_eq!(v["n"], 500);
        assert_eq!(v["e2e"].as_array().map(Vec::len), Some(PIPELINES.len()));
        for row in v["e2e"].as_array().unwrap() {
            let sticky = row["pipeline"].as_str().unwrap().starts_with("sticky");
            assert_eq!(row["floor_s"].is_f64(), sticky, "{row}");
            assert_eq!(row["vs_floor"].is_f64(), sticky, "{row}");
        }
        let table = e2e::table(&r);
        assert!(table.contains("sticky events --json"));
        assert!(
            table.contains("floor s") && table.contains("× floor"),
            "{table}"
        );
    }
    let _ = std::fs::remove_dir_all(&empty);
}

/// The I/O floor reads every input whole and writes exactly the answer's
/// number of bytes at the answer's place (replacing what was there).
#[test]
fn e2e_floor_reads_the_inputs_and_writes_the_answer_bytes() {
    use sticky::report::bench::e2e::io_floor;
    let dir = std::env::temp_dir().join(format!("sticky-e2e-floor-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let (input, out) = (dir.join("in.csv"), dir.join("out.json"));
    std::fs::write(&input, "position,velocity\n0,1\n").unwrap();
    std::fs::write(&out, vec![b'x'; 50_000]).unwrap();
    let wall = io_floor(std::slice::from_ref(&input), &out, 12_345).unwrap();
    assert!(wall > 0.0);
    assert_eq!(std::fs::metadata(&out).unwrap().len(), 12_345);
    // A missing input is an error naming it, not a floor.
    let missing = dir.join("missing.csv");
    let err = io_floor(&[missing], &out, 1).unwrap_err();
    assert!(err.contains("missing.csv"), "{err}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// The three inputs of the end-to-end rows hold the same particles: the
/// inline TOML scene equals the CSV scene, and the NPY scene is the CSV
/// scene's integers over 1024 instead of 1000 (radius included).
#[test]
fn e2e_inputs_are_one_scene_three_ways() {
    use num_bigint::BigInt;
    let dir = std::env::temp_dir().join(format!("sticky-e2e-inputs-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    sticky::report::bench::e2e::write_inputs(&dir, 3000, 7).unwrap();
    let load = |name: &str| sticky::scene::load(&dir.join(name)).unwrap().data;
    let (csv, toml, npy) = (load("dec.toml"), load("inline.toml"), load("dyadic.toml"));
    assert_eq!(csv, toml);
    assert_eq!(csv.n(), 3000);
    let k = BigRational::new(BigInt::from(1000), BigInt::from(1024));
    let scaled = |v: &[BigRational]| v.iter().map(|x| x * &k).collect::<Vec<_>>();
    assert_eq!(npy.positions(), &scaled(csv.positions())[..]);
    assert_eq!(npy.velocities(), &scaled(csv.velocities())[..]);
    assert_eq!(npy.radius(), &(csv.radius() * &k));
    // Contacts and collisions both occur (the rows measure real merges).
    let contacts = csv
        .positions()
        .windows(2)
        .filter(|w| &w[1] - &w[0] == csv.radius() * BigRational::from_integer(2.into()))
        .count();
    assert!(contacts > 100 && contacts < 2000, "{contacts}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// What `run_with_progress` tells its observer, which asks to stop after
/// `stop_after` steps.
struct Observer {
    stop_after: u64,
    steps: std::sync::atomic::AtomicU64,
    notes: std::sync::Mutex<Vec<String>>,
}

impl sticky::progress::Progress for Observer {
    fn advance(&self, steps: u64) {
        self.steps
            .fetch_add(steps, std::sync::atomic::Ordering::Relaxed);
    }
    fn note(&self, what: &str) {
        self.notes.lock().unwrap().push(what.to_string());
    }
    fn cancelled(&self) -> bool {
        self.steps.load(std::sync::atomic::Ordering::Relaxed) >= self.stop_after
    }
}

/// One step per repetition (the warm-up included), notes naming N and the
/// repetition, and a stop asked after the warm-up ends the run there.
#[test]
fn bench_reports_progress_and_stops_when_cancelled() {
    use sticky::report::bench::run_with_progress;
    let opts = BenchOptions {
        n: 200,
        reps: 2,
        peers: Peers::Skip,
        events: Events::Skip,
        metric: Metric::Time,
    };
    let t = BigRational::new(1.into(), 100.into());
    let scripts = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scripts");
    let observe = |stop_after| Observer {
        stop_after,
        steps: 0.into(),
        notes: Vec::new().into(),
    };
    let all = observe(u64::MAX);
    run_with_progress(&opts, &t, &scripts, &all);
    assert_eq!(
        all.steps.into_inner(),
        1 + 2,
        "the warm-up and 2 repetitions"
    );
    let notes = all.notes.into_inner().unwrap();
    assert_eq!(notes[0], "N = 200, warm-up: f64, integer kernel, adaptive");
    assert!(notes.contains(&"N = 200, repetition 2/2: generic PAVA on BigRational".to_string()));
    let first = observe(1);
    run_with_progress(&opts, &t, &scripts, &first);
    assert_eq!(first.steps.into_inner(), 1, "stopped after the warm-up");
    assert!(!first
        .notes
        .into_inner()
        .unwrap()
        .iter()
        .any(|n| n.contains("repetition")));
}
