//! Every peer of `scripts/peers/` on a small scene, through the Rust runner
//! (`report::peers::run_peer`) and `sticky compare --json`.
//!
//! A peer that is not installed is skipped with a message; under `CI=true`
//! a missing PyPI peer fails (CI installs them with
//! `scripts/peers/install.sh`). Siconos (Debian) may be missing anywhere.
//! The errors are printed (`cargo test --test peers -- --nocapture`), and
//! loosely bounded: each peer must land near the exact answer (position
//! error < 1/10 on this scene, at times that are not collision instants:
//! 1/5, 1, 3 — collisions at 1/8, 1/4, 3/5, 17/10, 69/40); exactness is
//! reported, not required.

use std::path::Path;
use std::process::Command;

use num_rational::BigRational;
use sticky::fast::kernel::{self, IntegerData};
use sticky::rational::parse_exact;
use sticky::reference::measure::{compare, Candidate};
use sticky::report::peers::{default_scripts_dir, peers, run_peer, PeerOutcome, Source};
use sticky::report::solution::decimal;

const SCENE: &str = "name = \"peers-small\"\n[particles]\nradius = \"1/16\"\npositions = [\"0\", \"1/4\", \"1\", \"5/4\", \"2\", \"3\"]\nvelocities = [\"1\", \"1/2\", \"0\", \"-1\", \"-1/2\", \"-1\"]\n";

#[test]
fn every_installed_peer_lands_near_the_exact_answer() {
    let dir = std::env::temp_dir().join(format!("sticky-peers-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let scene_path = dir.join("scene.toml");
    std::fs::write(&scene_path, SCENE).unwrap();
    let scene = sticky::scene::parse(SCENE).unwrap();
    let times: Vec<BigRational> = ["1/5", "1", "3"]
        .iter()
        .map(|t| parse_exact(t).unwrap())
        .collect();
    let ints = IntegerData::new(&scene.data);
    let ci = std::env::var("CI").is_ok_and(|v| v == "true");
    let mut missing = Vec::new();
    let mut failures = Vec::new();
    for p in peers() {
        let outcome = match run_peer(&p, &scene, &times, &default_scripts_dir(), &dir) {
            Ok(o) => o,
            Err(e) => {
                failures.push(e.to_string());
                continue;
            }
        };
        let run = match outcome {
            PeerOutcome::Skipped(msg) => {
                println!("{:<32} skipped: {msg}", p.name);
                if p.source == Source::PyPi {
                    missing.push(p.name);
                }
                continue;
            }
            PeerOutcome::Ran(run) => run,
        };
        let mut worst_x = BigRational::from_integer(0.into());
        let mut worst_u = BigRational::from_integer(0.into());
        let mut overlaps = 0;
        let mut wrong = 0;
        for f in &run.frames {
            let exact = kernel::state_at(&ints, &f.t).unwrap();
            let c = compare(
                &Candidate {
                    positions: &f.positions,
                    velocities: f.velocities.as_deref(),
                    multipliers: f.multipliers.as_deref(),
                    contacts: f.contacts.as_deref(),
                },
                &exact,
                &scene.data.two_r(),
                &BigRational::from_integer(0.into()),
            )
            .unwrap();
            worst_x = worst_x.max(c.position_max.value.clone());
            if let Some(m) = &c.velocity_max {
                worst_u = worst_u.max(m.value.clone());
            }
            overlaps += c.overlaps.len();
            wrong += c.missed_clusters.len() + c.spurious_clusters.len();
        }
        println!(
            "{:<32} max |x − x(t)| {:<10} max |u − u(t)| {:<10} overlaps {overlaps} wrong clusters {wrong}  wall {:.2} s",
            p.name,
            decimal(&worst_x, 3, false),
            decimal(&worst_u, 3, false),
            run.wall_seconds
        );
        if worst_x >= BigRational::new(1.into(), 10.into()) {
            failures.push(format!("{}: position error {worst_x} ≥ 1/10", p.name));
        }
        // The same solution through the command line.
        let o = Command::new(env!("CARGO_BIN_EXE_sticky"))
            .args([
                Path::new("compare"),
                &scene_path,
                &run.solution,
                Path::new("--json"),
            ])
            .output()
            .unwrap();
        let out = String::from_utf8_lossy(&o.stdout);
        if !o.status.success() || !out.contains("\"verdict\": ") {
            failures.push(format!(
                "{}: sticky compare failed: {}",
                p.name,
                String::from_utf8_lossy(&o.stderr)
            ));
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
    assert!(failures.is_empty(), "{failures:#?}");
    if ci {
        assert!(
            missing.is_empty(),
            "CI=true and PyPI peers are missing (run scripts/peers/install.sh): {missing:?}"
        );
    }
}
