//! `sticky plot` and `sticky converge` from the command line: they write
//! whole, non-empty files into `--out` and print their paths.

use std::path::Path;
use std::process::Command;

fn run(args: &[&str]) -> String {
    let out = Command::new(env!("CARGO_BIN_EXE_sticky"))
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("sticky runs");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8_lossy(&out.stdout).into_owned()
}

fn written(stdout: &str) -> Vec<String> {
    stdout
        .lines()
        .filter_map(|l| l.strip_prefix("wrote "))
        .map(str::to_string)
        .collect()
}

#[test]
fn plot_writes_every_figure() {
    let dir = std::env::temp_dir().join(format!("sticky-plot-{}", std::process::id()));
    let stdout = run(&[
        "plot",
        "scenes/riemann-compression.toml",
        "--out",
        dir.to_str().unwrap(),
    ]);
    let files = written(&stdout);
    for stem in [
        "spacetime",
        "density-particles",
        "density-continuum",
        "pressure",
    ] {
        let svg = dir.join(format!("{stem}.svg"));
        assert!(
            files.iter().any(|f| Path::new(f) == svg),
            "{stem}.svg not reported"
        );
        assert!(std::fs::metadata(&svg)
            .map(|m| m.len() > 1000)
            .unwrap_or(false));
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn converge_writes_csv_and_charts() {
    let dir = std::env::temp_dir().join(format!("sticky-converge-{}", std::process::id()));
    let stdout = run(&[
        "converge",
        "scenes/appendix-c-two-blocks.toml",
        "--out",
        dir.to_str().unwrap(),
        "--n-max",
        "128",
    ]);
    assert!(stdout.contains("x_l2"), "{stdout}");
    let csv = std::fs::read_to_string(dir.join("convergence.csv")).expect("convergence.csv");
    // Header plus N = 8, 16, 32, 64, 128.
    assert_eq!(csv.lines().count(), 6, "{csv}");
    assert!(dir.join("convergence-errors.svg").exists());
    let _ = std::fs::remove_dir_all(&dir);
}
