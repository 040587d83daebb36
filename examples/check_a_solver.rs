//! Checking another solver's answer against the exact one.
//!
//! A toy "solver" computes the positions at time `t` in `f64` (free flight,
//! then one pass that pushes overlapping neighbours apart). Its doubles are
//! read back exactly (every `f64` is a binary rational) and compared with the
//! exact projection `x(t) = P_K(x⁰ + t u⁰)` (`prop:proj-micro`), computed by
//! the generic `BigRational` engine and by the integer kernel, which agree
//! exactly.
//!
//! ```text
//! cargo run --example check_a_solver
//! ```

use num_rational::BigRational;
use sticky::fast::kernel::{self, IntegerData};
use sticky::{projection, InitialData, Scalar};

fn q(n: i64, d: i64) -> BigRational {
    BigRational::new(n.into(), d.into())
}

/// A deliberately naive solver: free flight, then a left-to-right sweep.
fn naive_solver(x0: &[f64], u0: &[f64], two_r: f64, t: f64) -> Vec<f64> {
    let mut x: Vec<f64> = x0.iter().zip(u0).map(|(x, u)| x + t * u).collect();
    for i in 1..x.len() {
        if x[i] - x[i - 1] < two_r {
            x[i] = x[i - 1] + two_r;
        }
    }
    x
}

fn main() -> Result<(), sticky::Error> {
    // Three particles, radius 1/10; the outer two run into the middle one.
    let data = InitialData::new(
        q(1, 10),
        vec![q(0, 1), q(1, 2), q(1, 1)],
        vec![q(1, 1), q(0, 1), q(-1, 1)],
    )?;
    let t = q(1, 2);
    let exact = projection::state_at(&data, &t)?;
    let fast = kernel::state_at(&IntegerData::new(&data), &t)?;
    assert_eq!(exact, fast, "two exact engines, one answer");

    let as_f64 = |v: &[BigRational]| v.iter().map(Scalar::to_f64_lossy).collect::<Vec<_>>();
    let x0 = as_f64(data.positions());
    let u0 = as_f64(data.velocities());
    let theirs = naive_solver(&x0, &u0, data.two_r().to_f64_lossy(), 0.5);
    for (i, (got, want)) in theirs.iter().zip(&exact.positions).enumerate() {
        let got = BigRational::from_float(*got).expect("finite");
        println!(
            "x_{} : exact {:>6}   solver {:>6}   error {}",
            i + 1,
            want.render(),
            got.render(),
            (got.clone() - want).render()
        );
    }
    println!("clusters at t = 1/2: {:?}", exact.clusters);
    Ok(())
}
