//! Density maps `ρ(t_j, x_k)` on a grid (for heat maps), for the continuum
//! and for the particles.

use num_bigint::BigInt;
use num_rational::BigRational;

use super::fields::{continuum_density, particle_density};
use crate::error::Error;
use crate::limit::continuum::Continuum;
use crate::limit::interpolation::Snapshot;
use crate::scalar::Scalar;
use crate::trajectory::Trajectory;

/// A density map `ρ(t_j, x_k)` on a grid, for heat maps.
#[derive(Debug, Clone, PartialEq)]
pub struct DensityGrid {
    /// The times (rows).
    pub times: Vec<f64>,
    /// The positions (columns).
    pub xs: Vec<f64>,
    /// `values[j][k] = ρ(times[j], xs[k])`, in `[0, 1]`.
    pub values: Vec<Vec<f64>>,
}

/// `x_k = x_min + (k + 1/2)(x_max − x_min)/nx` and
/// `t_j = j T/(nt − 1)`, rational.
fn grids(
    t_end: &BigRational,
    nt: usize,
    x_range: (&BigRational, &BigRational),
    nx: usize,
) -> (Vec<BigRational>, Vec<BigRational>) {
    let times = (0..nt)
        .map(|j| t_end * BigRational::new(BigInt::from(j), BigInt::from(nt.max(2) - 1)))
        .collect();
    let width = x_range.1 - x_range.0;
    let xs = (0..nx)
        .map(|k| {
            x_range.0
                + &width * BigRational::new(BigInt::from(2 * k + 1), BigInt::from(2 * nx.max(1)))
        })
        .collect();
    (times, xs)
}

/// The continuum density on an `nt × nx` grid over `[0, T] × [x_min, x_max]`
/// (the profile at each time is exact, then rounded).
pub fn continuum_density_grid(
    continuum: &Continuum,
    t_end: &BigRational,
    nt: usize,
    x_range: (&BigRational, &BigRational),
    nx: usize,
) -> Result<DensityGrid, Error> {
    let (times, xs) = grids(t_end, nt, x_range, nx);
    let xf: Vec<f64> = xs.iter().map(|x| x.to_f64_lossy()).collect();
    let mut values = Vec::with_capacity(times.len());
    for t in &times {
        let (p, _) = continuum.profile(t)?.to_f64();
        values.push(xf.iter().map(|x| continuum_density(&p, x)).collect());
    }
    Ok(DensityGrid {
        times: times.iter().map(|t| t.to_f64_lossy()).collect(),
        xs: xf,
        values,
    })
}

/// The particle density `ρ̃_N` on the same kind of grid.
pub fn particle_density_grid<S: Scalar>(
    traj: &Trajectory<S>,
    delta: &S,
    t_end: &BigRational,
    nt: usize,
    x_range: (&BigRational, &BigRational),
    nx: usize,
) -> Result<DensityGrid, Error> {
    let (times, xs) = grids(t_end, nt, x_range, nx);
    let conv = |q: &BigRational| {
        S::from_big_rational(q).ok_or_else(|| Error::Unsupported {
            message: format!("{} does not fit the scalar type", q.to_f64_lossy()),
        })
    };
    let xs_s: Vec<S> = xs.iter().map(conv).collect::<Result<_, _>>()?;
    let mut values = Vec::with_capacity(times.len());
    for t in &times {
        let s = traj.at(&conv(t)?)?;
        let snap = Snapshot::new(&s, traj.data().velocities(), delta.clone())?;
        values.push(
            xs_s.iter()
                .map(|x| particle_density(&snap, x).to_f64_lossy())
                .collect(),
        );
    }
    Ok(DensityGrid {
        times: times.iter().map(|t| t.to_f64_lossy()).collect(),
        xs: xs.iter().map(|x| x.to_f64_lossy()).collect(),
        values,
    })
}
