//! A correctly rounded answer is never `invalid`: sticky's own nearest
//! doubles, compared with default tolerances, are `rounding` even where the
//! rounding makes neighbours overlap (by ~10⁻¹⁷) — and one ulp more is not.

use num_rational::BigRational;
use sticky::columns::f64_exact;
use sticky::report::compare::{compare_solution, CompareOptions, Verdict};
use sticky::report::solution::Frame;
use sticky::InitialData;

fn q(n: i64, d: i64) -> BigRational {
    BigRational::new(n.into(), d.into())
}

/// The nearest double of `v`, as the rational it is.
fn rounded(v: &BigRational) -> BigRational {
    let d = sticky::Scalar::to_f64_lossy(v);
    f64_exact(d).expect("finite")
}

/// Three particles at rest in one cluster, 2r = 1/3: the nearest doubles of
/// 0, 1/3, 2/3 overlap (0.333…31 − 0 < 1/3).
fn cluster() -> InitialData<BigRational> {
    InitialData::new(q(1, 6), vec![q(0, 1), q(1, 3), q(2, 3)], vec![q(0, 1); 3]).unwrap()
}

fn verdict(positions: Vec<BigRational>, velocities: Option<Vec<BigRational>>) -> Verdict {
    let mut frame = Frame::new(q(1, 1), positions);
    frame.velocities = velocities;
    compare_solution(&cluster(), &[frame], &CompareOptions::default())
        .unwrap()
        .verdict
}

#[test]
fn nearest_doubles_are_rounding_with_default_tolerances() {
    let data = cluster();
    let x: Vec<BigRational> = data.positions().iter().map(rounded).collect();
    assert!(
        x[1] < q(1, 3),
        "the rounding overlaps: the case is the one meant"
    );
    let u: Vec<BigRational> = data.velocities().iter().map(rounded).collect();
    assert_eq!(verdict(x.clone(), Some(u)), Verdict::Rounding);
    assert_eq!(verdict(x, None), Verdict::Rounding);
}

#[test]
fn one_ulp_off_the_nearest_double_is_judged_as_before() {
    let data = cluster();
    let mut x: Vec<BigRational> = data.positions().iter().map(rounded).collect();
    // The double below the nearest one: a deeper overlap, not a rounding.
    let below = f64::from_bits(sticky::Scalar::to_f64_lossy(&x[1]).to_bits() - 1);
    x[1] = f64_exact(below).unwrap();
    assert_eq!(verdict(x, None), Verdict::Invalid);
}

#[test]
fn exact_values_stay_exact() {
    let data = cluster();
    assert_eq!(verdict(data.positions().to_vec(), None), Verdict::Exact);
}

/// `sticky compare` gives the same verdict: the nearest doubles of the
/// cluster, written as JSON numbers, are `rounding` with no tolerance.
#[test]
fn the_command_line_agrees() {
    let dir = std::env::temp_dir().join(format!("sticky-rounded-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let scene = dir.join("s.toml");
    let solution = dir.join("sol.json");
    std::fs::write(
        &scene,
        "[particles]\nradius = \"1/6\"\npositions = [\"0\", \"1/3\", \"2/3\"]\nvelocities = [\"0\", \"0\", \"0\"]\n",
    )
    .unwrap();
    let x: Vec<f64> = [q(0, 1), q(1, 3), q(2, 3)]
        .iter()
        .map(sticky::Scalar::to_f64_lossy)
        .collect();
    let line = serde_json::json!({"t": "1", "positions": x, "velocities": [0.0, 0.0, 0.0]});
    std::fs::write(&solution, line.to_string()).unwrap();
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_sticky"))
        .arg("compare")
        .arg(&scene)
        .arg(&solution)
        .arg("--json")
        .output()
        .unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).expect("JSON");
    assert_eq!(v["verdict"], "rounding", "{v}");
    assert_eq!(v["times"][0]["overlaps"].as_array().map(Vec::len), Some(2));
}
