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
