//! Contact forces: the multipliers `λ`, Appendix A's KKT multipliers, and the
//! pressure `p = dλ/dt` as Dirac masses in time.
//!
//! `eq:dyn-micro`:
//! > "u(t) = u_0 − N Σ_{i=1}^{N−1} λ_i(t)(e_i − e_{i+1}), λ_0(t) = λ_N(t) = 0,
//! > and λ_i(t)(x_{i+1}(t) − x_i(t) − 2r) = 0."
//!
//! Componentwise `u_i − u⁰_i = −N(λ_i − λ_{i−1})`, so
//! `λ_i = λ_{i−1} + (u⁰_i − u_i)/N` from `λ_0 = 0`; `λ_N = 0` is then a
//! consequence (momentum is conserved in every cluster) and is returned so
//! that callers can check it.
//!
//! Appendix A (`app:KKT`) writes the optimality conditions of
//! `min ½‖x − (x⁰ + t u⁰)‖²` over `K^N` as
//! `x(t) − (x⁰ + t u⁰) + N Σ μ_i (e_i − e_{i+1}) = 0`. These KKT multipliers
//! `μ` are a different object from `λ`: `μ_i = μ_{i−1} + (y_i − x_i)/N`, and
//! `μ(t) = ∫_0^t λ(s) ds`.
//!
//! `prop:micro-pressure`: `p_i = dλ_i/dt`. Between collisions every cluster
//! moves rigidly and `λ` is constant, so `p_i` is a sum of Dirac masses at the
//! collision times, with weights the jumps of `λ_i` ([`Impulse`]).

use std::ops::{AddAssign, Mul, Sub};

use num_traits::Zero;

use crate::cluster::Cluster;
use crate::scalar::Scalar;

/// Prefix sums `m_i = m_{i−1} + (a_i − b_i)/N`, `m_0 = 0`, for
/// `i = 1 … N`: returns `(m_1 … m_{N−1}, m_N)`.
fn scaled_prefix<S: Scalar>(a: &[S], b: &[S]) -> (Vec<S>, S) {
    let n = S::from_usize(a.len());
    let mut acc = S::zero();
    let mut out = Vec::with_capacity(a.len().saturating_sub(1));
    for (ai, bi) in a.iter().zip(b) {
        acc = acc + &((ai.clone() - bi) / &n);
        out.push(acc.clone());
    }
    let last = out.pop().unwrap_or_else(S::zero);
    (out, last)
}

/// The multipliers of `eq:dyn-micro`: `(λ_1 … λ_{N−1}, λ_N)` from `u⁰` and
/// `u(t)`. `λ_N` must be zero; it is returned, not assumed.
pub fn multipliers<S: Scalar>(u0: &[S], u: &[S]) -> (Vec<S>, S) {
    scaled_prefix(u0, u)
}

/// The multipliers of `eq:dyn-micro` on one cluster, in closed form: the
/// cluster moves with the mean `ū = S/k` of `u⁰` over it (`S = Σ a_j`,
/// `k` particles), and `λ` vanishes at both of its ends, so the recurrence
/// above gives, for the `m`-th particle of the cluster (`m = 1 … k`),
/// `N k λ = k Σ_{j ≤ m} a_j − m S` — with the velocities written as
/// `u⁰_j = a_j / D` over any common denominator `D`, `λ` is this numerator
/// over `k D N`. Returns the `k` numerators (the last one, at the cluster's
/// right end, is zero). The exact integer kernel builds `λ` with it.
pub fn cluster_multiplier_numerators<T>(a: &[T]) -> Vec<T>
where
    T: Zero + From<usize> + for<'x> AddAssign<&'x T>,
    for<'x> &'x T: Mul<&'x T, Output = T> + Sub<&'x T, Output = T>,
{
    let k = T::from(a.len());
    let mut sum = T::zero();
    for v in a {
        sum += v;
    }
    let mut prefix = T::zero();
    a.iter()
        .enumerate()
        .map(|(m, v)| {
            prefix += v;
            &(&k * &prefix) - &(&T::from(m + 1) * &sum)
        })
        .collect()
}

/// Appendix A's KKT multipliers of the position projection:
/// `(μ_1 … μ_{N−1}, μ_N)` from `y = x⁰ + t u⁰` and `x(t) = P_K(y)`
/// (both may be given in translated coordinates: only `y − x` enters).
pub fn kkt_multipliers<S: Scalar>(y: &[S], x: &[S]) -> (Vec<S>, S) {
    scaled_prefix(y, x)
}

/// One Dirac mass of the pressure: at the collision time `t`, the clusters
/// `parts` (with pre-collision velocities `part_velocities`) merge into
/// `cluster`, which moves with `velocity` afterwards.
#[derive(Debug, Clone, PartialEq)]
pub struct Impulse<S> {
    /// The collision time.
    pub t: S,
    /// The cluster formed.
    pub cluster: Cluster,
    /// The clusters that merged into it, left to right (two or more).
    pub parts: Vec<Cluster>,
    /// Velocity of each part just before `t`.
    pub part_velocities: Vec<S>,
    /// Velocity of the merged cluster from `t` on.
    pub velocity: S,
    /// The number of particles N of the whole system (λ is scaled by N).
    pub n: usize,
}

impl<S: Scalar> Impulse<S> {
    /// The jumps `λ_i(t) − λ_i(t⁻)` for the pairs `i` (0-based, pair
    /// `(i, i+1)`) inside the merged cluster, left to right (`size − 1`
    /// values). Every other `λ_j` is continuous at `t`.
    ///
    /// `jump_i = (1/N) Σ_{j = first}^{i} (u_j(t⁻) − u_j(t))`.
    pub fn jumps(&self) -> Vec<S> {
        let n = S::from_usize(self.n);
        let mut out = Vec::with_capacity(self.cluster.size.saturating_sub(1));
        let mut acc = S::zero();
        for (part, v) in self.parts.iter().zip(&self.part_velocities) {
            let step = (v.clone() - &self.velocity) / &n;
            for _ in 0..part.size {
                acc = acc + &step;
                out.push(acc.clone());
            }
        }
        // The last entry is the pair to the right of the cluster: its sum is
        // zero by conservation of momentum and it is not part of the cluster.
        out.pop();
        out
    }

    /// The sum of the jumps over the cluster: the total mass of this Dirac
    /// mass of `Σ_i p_i`.
    pub fn total(&self) -> S {
        self.jumps().into_iter().fold(S::zero(), |a, b| a + &b)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use num_rational::{BigRational, Rational64};

    fn checks<S: Scalar>() {
        let q = |n: i64, d: i64| S::from_i64(n) / S::from_i64(d);
        let u0 = vec![q(1, 1), q(1, 1), q(-1, 1), q(-1, 1)];
        let u = vec![S::zero(); 4];
        let (lambda, lambda_n) = multipliers(&u0, &u);
        assert_eq!(lambda, vec![q(1, 4), q(1, 2), q(1, 4)]);
        assert_eq!(lambda_n, S::zero());
        let imp = Impulse {
            t: q(1, 8),
            cluster: Cluster { first: 0, size: 4 },
            parts: vec![Cluster { first: 0, size: 2 }, Cluster { first: 2, size: 2 }],
            part_velocities: vec![q(1, 1), q(-1, 1)],
            velocity: S::zero(),
            n: 4,
        };
        assert_eq!(
            imp.jumps(),
            lambda,
            "all of λ is created by this one collision"
        );
        assert_eq!(imp.total(), q(1, 1));
        let (mu, mu_n) = kkt_multipliers(&[q(1, 1), q(0, 1)], &[q(1, 2), q(1, 2)]);
        assert_eq!(mu, vec![q(1, 4)]);
        assert_eq!(mu_n, S::zero());
    }

    /// A collision after which the cluster still moves: the jumps are
    /// `(1/N) Σ_{j ≤ i} (u_j(t⁻) − ū)` with `ū ≠ 0`, parts of unequal sizes,
    /// and the pairs outside the cluster get no jump. From rest (`λ = 0`
    /// before), the jumps are the multipliers just after.
    #[test]
    fn jumps_of_a_moving_cluster() {
        let q = |n: i64, d: i64| BigRational::from_i64(n) / BigRational::from_i64(d);
        // N = 4: particle 1 alone, then particles 2 (u = 3) and 3, 4 (u = 0)
        // merge into a cluster moving at 1.
        let imp = Impulse {
            t: q(1, 1),
            cluster: Cluster { first: 1, size: 3 },
            parts: vec![Cluster { first: 1, size: 1 }, Cluster { first: 2, size: 2 }],
            part_velocities: vec![q(3, 1), q(0, 1)],
            velocity: q(1, 1),
            n: 4,
        };
        assert_eq!(imp.jumps(), vec![q(1, 2), q(1, 4)]);
        assert_eq!(imp.total(), q(3, 4));
        let u0 = vec![q(-5, 1), q(3, 1), q(0, 1), q(0, 1)];
        let u = vec![q(-5, 1), q(1, 1), q(1, 1), q(1, 1)];
        let (lambda, last) = multipliers(&u0, &u);
        assert_eq!(lambda, vec![q(0, 1), q(1, 2), q(1, 4)]);
        assert_eq!(last, q(0, 1));
    }

    /// The closed form on a cluster is the recurrence: on integer data
    /// (`D = 1`), `N k λ` from both.
    #[test]
    fn cluster_form_is_the_recurrence() {
        use num_bigint::BigInt;
        let a: Vec<i64> = vec![5, -3, 2, 2, -7, 4];
        let k = a.len();
        let mean = BigRational::new(BigInt::from(a.iter().sum::<i64>()), BigInt::from(k));
        let u0: Vec<BigRational> = a
            .iter()
            .map(|&v| BigRational::from(BigInt::from(v)))
            .collect();
        let (lambda, last) = multipliers(&u0, &vec![mean; k]);
        let nums =
            cluster_multiplier_numerators(&a.iter().map(|&v| BigInt::from(v)).collect::<Vec<_>>());
        let scale = BigRational::from(BigInt::from(k * k));
        let mut want: Vec<BigRational> = lambda.iter().map(|l| l * &scale).collect();
        want.push(last * &scale);
        let got: Vec<BigRational> = nums.into_iter().map(BigRational::from).collect();
        assert_eq!(got, want);
        assert_eq!(got.last(), Some(&BigRational::from(BigInt::from(0))));
    }

    #[test]
    fn contact_rational64() {
        checks::<Rational64>();
    }
    #[test]
    fn contact_bigrational() {
        checks::<BigRational>();
    }
}
