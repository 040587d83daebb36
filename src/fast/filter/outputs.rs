//! The state the filter proved: the positions' nearest doubles, and from
//! the same certified partition the velocities (`eq:proj-u-micro`), the
//! multipliers (`eq:dyn-micro`) and the contact clusters (`df:Omega-micro`),
//! each value rounded once from its exact value.

use std::sync::Arc;

use num_rational::BigRational;
use num_traits::Zero;

use super::eft;
use super::pava::Multi;
use super::Checked;
use crate::cluster::Cluster;

/// The partition the filter proved at one time (module documentation of
/// [`super`]), without the columns it was proved on: every block of one
/// particle but the larger ones it lists, each block its own contact
/// cluster. The outputs that need the initial data read them from the
/// columns passed in, which must be those the partition was proved on.
#[derive(Debug, Clone)]
pub struct Partition {
    checked: Checked,
    t: BigRational,
    tf: f64,
    multi: Vec<Multi>,
}

/// The state at one time whose partition the filter proved, with the
/// columns it was proved on (shared).
#[derive(Debug, Clone)]
pub struct Filtered {
    partition: Partition,
    x: Arc<Vec<f64>>,
    u: Arc<Vec<f64>>,
    positions: Vec<f64>,
}

impl Partition {
    pub(crate) fn new(checked: Checked, t: BigRational, tf: f64, multi: Vec<Multi>) -> Partition {
        Partition {
            checked,
            t,
            tf,
            multi,
        }
    }

    /// The time.
    pub fn t(&self) -> &BigRational {
        &self.t
    }

    /// The time as the double it is.
    pub fn t_double(&self) -> f64 {
        self.tf
    }

    /// N.
    pub fn n(&self) -> usize {
        self.checked.n()
    }

    /// `u(t)`'s nearest doubles written into `out` (`N` values, e.g. a
    /// buffer of the caller's allocator): `u⁰_i` for a particle alone, the
    /// mean of `u⁰` over a larger block (`eq:proj-u-micro`). `u` is the
    /// velocity column the partition was proved on.
    pub fn write_velocities(&self, u: &[f64], out: &mut [f64]) {
        debug_assert_eq!(u.len(), self.n());
        out.copy_from_slice(u);
        for m in &self.multi {
            let (a, k) = (m.start as usize, m.k as usize);
            let v = eft::quotient(&u[a..a + k], k as u64);
            out[a..a + k].fill(v);
        }
    }

    /// `λ(t)`'s nearest doubles written into `out` (`N − 1` values): `0`
    /// between two blocks, `(k Σ_{j<m} u⁰_j − m Σ_j u⁰_j) / (k N)` for the
    /// `m`-th pair of a block of `k` (`eq:dyn-micro`). `u` is the velocity
    /// column the partition was proved on.
    pub fn write_multipliers(&self, u: &[f64], out: &mut [f64]) {
        let n = self.n();
        debug_assert_eq!(u.len(), n);
        out.fill(0.0);
        let mut terms = Vec::new();
        for m in &self.multi {
            let (a, k) = (m.start as usize, m.k as usize);
            let us = &u[a..a + k];
            let den = (k * n) as u64;
            let block = &mut out[a..a + k - 1];
            // `2k` terms a pair, `k ≤ MAX_BLOCK`.
            debug_assert!(m.k <= super::pava::MAX_BLOCK);
            for (p, l) in block.iter_mut().enumerate() {
                let left = p + 1;
                terms.clear();
                for (j, &uj) in us.iter().enumerate() {
                    let c = if j < left {
                        (k - left) as f64
                    } else {
                        -(left as f64)
                    };
                    let (hi, lo) = eft::two_prod(c, uj);
                    terms.extend([hi, lo]);
                }
                *l = eft::quotient(&terms, den);
                // `λ ≥ 0` (the Coq development's `multiplier_nonneg`).
                debug_assert!(*l >= 0.0);
            }
        }
    }

    /// The contact clusters, left to right: the blocks.
    pub fn clusters(&self) -> Vec<Cluster> {
        let n = self.n();
        let mut out =
            Vec::with_capacity(n - self.multi.iter().map(|m| m.k as usize - 1).sum::<usize>());
        let mut i = 0usize;
        for m in &self.multi {
            let a = m.start as usize;
            out.extend((i..a).map(|first| Cluster { first, size: 1 }));
            out.push(Cluster {
                first: a,
                size: m.k as usize,
            });
            i = a + m.k as usize;
        }
        out.extend((i..n).map(|first| Cluster { first, size: 1 }));
        out
    }
}

impl Filtered {
    pub(crate) fn new(partition: Partition, x: Arc<Vec<f64>>, u: Arc<Vec<f64>>) -> Filtered {
        Filtered {
            partition,
            x,
            u,
            positions: Vec::new(),
        }
    }

    pub(crate) fn set_positions(&mut self, positions: Vec<f64>) {
        debug_assert_eq!(positions.len(), self.n());
        self.positions = positions;
    }

    /// The certified partition.
    pub fn partition(&self) -> &Partition {
        &self.partition
    }

    /// The time.
    pub fn t(&self) -> &BigRational {
        self.partition.t()
    }

    /// The time as the double it is.
    pub fn t_double(&self) -> f64 {
        self.partition.t_double()
    }

    /// N.
    pub fn n(&self) -> usize {
        self.partition.n()
    }

    /// `x(t)`'s nearest doubles (ties to even); empty when the state was
    /// made by [`super::Doubles::at_into`] (they are in its buffer).
    pub fn positions(&self) -> &[f64] {
        &self.positions
    }

    /// The positions, moved out (left empty).
    pub fn take_positions(&mut self) -> Vec<f64> {
        std::mem::take(&mut self.positions)
    }

    /// `u(t)`'s nearest doubles: `u⁰_i` for a particle alone, the mean of
    /// `u⁰` over a larger block (`eq:proj-u-micro`).
    pub fn velocities(&self) -> Vec<f64> {
        let mut out = vec![0.0; self.n()];
        self.write_velocities(&mut out);
        out
    }

    /// [`Self::velocities`] written into `out` (`N` values, e.g. a buffer
    /// of the caller's allocator).
    pub fn write_velocities(&self, out: &mut [f64]) {
        self.partition.write_velocities(&self.u, out);
    }

    /// `λ(t)`'s nearest doubles, `N − 1` values ([`Partition::write_multipliers`]).
    pub fn multipliers(&self) -> Vec<f64> {
        let mut out = vec![0.0; self.n().saturating_sub(1)];
        self.write_multipliers(&mut out);
        out
    }

    /// [`Self::multipliers`] written into `out` (`N − 1` values).
    pub fn write_multipliers(&self, out: &mut [f64]) {
        self.partition.write_multipliers(&self.u, out);
    }

    /// The contact clusters, left to right: the blocks.
    pub fn clusters(&self) -> Vec<Cluster> {
        self.partition.clusters()
    }
}

impl Filtered {
    /// The exact state from the certified partition, every value in lowest
    /// terms: `x_i = S/k + 2r i` with `S = Σ_j (x⁰_j + t u⁰_j − 2r j)`,
    /// `u_i = Σ_j u⁰_j / k`, the multipliers as in [`Self::multipliers`].
    pub fn exact_state(&self) -> crate::state::State<BigRational> {
        self.partition.exact_state(&self.x, &self.u)
    }
}

impl Partition {
    /// [`Filtered::exact_state`] from the columns `x`, `u` the partition
    /// was proved on.
    pub fn exact_state(&self, x: &[f64], u: &[f64]) -> crate::state::State<BigRational> {
        let n = self.n();
        let q = |v: f64| BigRational::from_float(v).unwrap_or_else(BigRational::zero);
        let t = self.t.clone();
        let radius = self.checked.radius();
        let two_r = radius + radius;
        let clusters = self.clusters();
        let mut positions = Vec::with_capacity(n);
        let mut velocities = Vec::with_capacity(n);
        let mut multipliers = Vec::with_capacity(n.saturating_sub(1));
        let big_n = BigRational::from_integer(n.into());
        for c in &clusters {
            let (a, k) = (c.first, c.size);
            let kq = BigRational::from_integer(k.into());
            let mut s = BigRational::zero();
            let mut su = BigRational::zero();
            for j in a..a + k {
                let jq = BigRational::from_integer(j.into());
                s += q(x[j]) + &t * q(u[j]) - &two_r * jq;
                su += q(u[j]);
            }
            let mean = &s / &kq;
            for i in a..a + k {
                positions.push(&mean + &two_r * BigRational::from_integer(i.into()));
            }
            let v = &su / &kq;
            velocities.extend(std::iter::repeat_n(v, k));
            let mut prefix = BigRational::zero();
            for m in 1..=k {
                if a + m >= n {
                    break;
                }
                prefix += q(u[a + m - 1]);
                let mq = BigRational::from_integer(m.into());
                multipliers.push((&kq * &prefix - &mq * &su) / (&kq * &big_n));
            }
        }
        crate::state::State {
            t,
            positions,
            velocities,
            multipliers,
            clusters,
        }
    }
}
