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

/// The collision markers of the space-time diagram sit at the exact contact
/// points: on three-cluster-simultaneous, the merge of 3 parts at t = 1/2
/// has two contact points (x = 4 and x = 6), the late joiner one (t = 2,
/// x = 19/2); each equals the midpoint of the two touching particles of
/// `traj.at(t)`.
#[test]
fn collision_markers_are_the_exact_contact_points() {
    use num_rational::BigRational;
    use sticky::report::figures::contact_points;
    let scene = sticky::scene::load(
        &Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/three-cluster-simultaneous.toml"),
    )
    .expect("scene loads");
    let traj = sticky::fast::merge::trajectory(&scene.data);
    let t_end = scene.t_end.clone().expect("t_end");
    let got = contact_points(&traj, &t_end);
    let q = |n: i64, d: i64| BigRational::new(n.into(), d.into());
    // Independently: every pair of consecutive parts of every impulse, the
    // midpoint between its two touching particles in the full state at t.
    let mut expected = Vec::new();
    for imp in traj.impulses() {
        let s = traj.at(&imp.t).expect("state");
        for left in &imp.parts[..imp.parts.len() - 1] {
            let a = left.first + left.size - 1;
            assert_eq!(
                &s.positions[a + 1] - &s.positions[a],
                q(1, 1),
                "the two particles touch (2r = 1)"
            );
            expected.push((
                imp.t.clone(),
                (&s.positions[a] + &s.positions[a + 1]) / q(2, 1),
            ));
        }
    }
    assert_eq!(got, expected);
    assert_eq!(
        got,
        vec![(q(1, 2), q(4, 1)), (q(1, 2), q(6, 1)), (q(2, 1), q(19, 2))]
    );
    // And the figure draws exactly these, as f64.
    let dir = std::env::temp_dir().join(format!("sticky-markers-{}", std::process::id()));
    run(&[
        "plot",
        "scenes/three-cluster-simultaneous.toml",
        "--out",
        dir.to_str().unwrap(),
    ]);
    let svg = std::fs::read_to_string(dir.join("spacetime.svg")).expect("spacetime.svg");
    assert!(svg.contains("collision: contact point where two parts meet (3)"));
    let _ = std::fs::remove_dir_all(&dir);
}

/// Every text of the SVG charts `sticky converge` writes on the shipped
/// `[macro]` scenes is words and numbers: no "NaN", no "inf".
#[test]
fn converge_charts_never_say_nan() {
    let mut checked = 0;
    for entry in std::fs::read_dir(Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes")).unwrap() {
        let path = entry.unwrap().path();
        let text = std::fs::read_to_string(&path).unwrap_or_default();
        if path.extension().is_none_or(|e| e != "toml") || !text.contains("[macro]") {
            continue;
        }
        let name = path.file_stem().unwrap().to_string_lossy().into_owned();
        let dir = std::env::temp_dir().join(format!("sticky-nan-{name}-{}", std::process::id()));
        run(&[
            "converge",
            path.to_str().unwrap(),
            "--out",
            dir.to_str().unwrap(),
            "--n-max",
            "64",
        ]);
        for stem in ["convergence-errors", "convergence-bounded"] {
            let Ok(svg) = std::fs::read_to_string(dir.join(format!("{stem}.svg"))) else {
                continue;
            };
            checked += 1;
            for text in svg_texts(&svg) {
                let lower = text.to_lowercase();
                assert!(
                    !lower.contains("nan") && !lower.contains("inf"),
                    "{name}/{stem}.svg says {text:?}"
                );
            }
        }
        let _ = std::fs::remove_dir_all(&dir);
    }
    assert!(checked >= 3, "only {checked} charts checked");
}

/// The contents of every `<text>` element of an SVG file.
fn svg_texts(svg: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut rest = svg;
    while let Some(i) = rest.find("<text") {
        rest = &rest[i..];
        let Some(open) = rest.find('>') else { break };
        let Some(close) = rest.find("</text>") else {
            break;
        };
        out.push(rest[open + 1..close].trim().to_string());
        rest = &rest[close..];
    }
    out
}

/// The particle and continuum density maps of a scene share one colour
/// scale: the same colour bar (label and ticks, every text but the title),
/// drawn with the viridis ends.
#[test]
fn density_maps_share_one_labelled_colour_scale() {
    let dir = std::env::temp_dir().join(format!("sticky-density-{}", std::process::id()));
    run(&[
        "plot",
        "scenes/riemann-compression.toml",
        "--out",
        dir.to_str().unwrap(),
    ]);
    let read = |stem: &str| std::fs::read_to_string(dir.join(format!("{stem}.svg"))).unwrap();
    let (p, c) = (read("density-particles"), read("density-continuum"));
    for svg in [&p, &c] {
        assert!(
            svg_texts(svg).iter().any(|t| t == "density ρ"),
            "no colour bar label"
        );
        let upper = svg.to_uppercase();
        assert!(
            upper.contains("#440154") && upper.contains("#FDE725"),
            "not viridis"
        );
    }
    let (tp, tc) = (svg_texts(&p), svg_texts(&c));
    assert_eq!(tp[1..], tc[1..], "the two maps differ beyond their titles");
    let _ = std::fs::remove_dir_all(&dir);
}

/// Without a TrueType font the PNGs are skipped, SVGs still written, and
/// stderr says so once, with how to get them.
#[test]
fn missing_font_is_said_once_on_stderr() {
    let dir = std::env::temp_dir().join(format!("sticky-nofont-{}", std::process::id()));
    let out = Command::new(env!("CARGO_BIN_EXE_sticky"))
        .args([
            "plot",
            "scenes/three-cluster-simultaneous.toml",
            "--out",
            dir.to_str().unwrap(),
        ])
        .env("STICKY_FONT", "none")
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("sticky runs");
    assert!(out.status.success());
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(stderr.matches("PNG charts skipped").count(), 1, "{stderr}");
    assert!(stderr.contains("fonts-dejavu-core"), "{stderr}");
    assert!(dir.join("spacetime.svg").exists());
    assert!(!dir.join("spacetime.png").exists());
    let _ = std::fs::remove_dir_all(&dir);
}
