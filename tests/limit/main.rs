//! The hydrodynamic limit (paper §3 and Appendix C): the interpolation
//! identities of §3.1, the exact continuum solution against an independent
//! bound and the particle trend, the convergence rates (asserted with
//! margins taken from the measured rates), `ρ ≤ 1`, and the Appendix C
//! checks.
//!
//! Measured rates (least-squares log-log slope over N = 8 … 2048, exact
//! engine up to 512, sample times 0, T(3j−1)/24, T) on the shipped scenes:
//!
//! | scene | x_l2 | u_l1 | λ_l2 | pm_err | bv_err | tv_err | R_mom | (1−ρ)p | Nλ |
//! |---|---|---|---|---|---|---|---|---|---|
//! | appendix-c-two-blocks | −1.000 | 0 | −1.000 | 0 | 0 | 0 | −1.000 | −1.902 | +1.000 |
//! | riemann-compression | −1.000 | −1.000 | −1.001 | 0 | −1.000 | 0 (N≥16) | −0.999 | −0.975 | +1.000 |
//! | riemann-expansion-affine | −0.997 | −1.027 | −1.021 | −1.066 | −0.999 | −1.024 | −1.023 | −1.078 | +0.962 |
//!
//! The assertions require at least 80 % of each measured rate.

// The checks index arrays with the paper's subscripts (`x_i`, `λ_{i−1}`).
#![allow(clippy::needless_range_loop)]

use std::cmp::Ordering;
use std::path::Path;

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::Signed;
use sticky::limit::appendix_c::{
    all_findings, projection_selects_sticky, sticky_is_particle_limit,
    sticky_pressure_is_continuum, Continuation, Printing, TwoBlocks,
};
use sticky::limit::continuum::{Continuum, Profile, Segment};
use sticky::limit::converge::{
    converge, u_l1, x_l2_squared, ConvergeOptions, ConvergenceReport, Engine, Quantity,
};
use sticky::limit::eulerian::{
    continuum_density, continuum_density_grid, continuum_momentum, continuum_pressure_potential,
    continuum_velocity, oleinik_margin, particle_complementarity, particle_density_grid,
    particle_momentum_residuals, particle_pressure_atoms, support_window, test_family,
    TestFunction,
};
use sticky::limit::interpolation::{Interpolations, PressureMeasure, Snapshot};
use sticky::limit::sampling::{check_blocks, check_datum, check_sampling, Hypothesis};
use sticky::limit::surd::Surd;
use sticky::projection::isotonic;
use sticky::quantile::{Block, BlockVelocity, MacroDatum};
use sticky::report::converge::write_csv;
use sticky::scalar::Scalar;
use sticky::scene::{self, Scene, SceneKind};
use sticky::trajectory::Trajectory;

type Q = BigRational;

fn q(n: i64, d: i64) -> Q {
    BigRational::new(n.into(), d.into())
}

const SCENES: [&str; 3] = [
    "appendix-c-two-blocks",
    "riemann-compression",
    "riemann-expansion-affine",
];

fn load(name: &str) -> Scene {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("scenes/{name}.toml"));
    scene::load(&path).unwrap()
}

fn datum_of(sc: &Scene) -> MacroDatum {
    match &sc.kind {
        SceneKind::Macro { datum, .. } => datum.clone(),
        SceneKind::Particles => panic!("not a macro scene"),
    }
}

/// 0, every collision instant, the midpoints, and one time after the last.
fn probe_times(traj: &Trajectory<Q>) -> Vec<Q> {
    let mut ts: Vec<Q> = vec![q(0, 1)];
    ts.extend(traj.impulses().iter().map(|i| i.t.clone()));
    ts.dedup();
    let mut out = Vec::new();
    for w in ts.windows(2) {
        out.push(w[0].clone());
        out.push((&w[0] + &w[1]) / q(2, 1));
    }
    let last = ts.last().cloned().unwrap_or_else(|| q(0, 1));
    out.push(last.clone());
    out.push(last + q(1, 3));
    out
}

mod appendix_c;
mod continuum;
mod convergence;
mod eulerian;
mod interpolation;
mod sampling;
