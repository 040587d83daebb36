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

    #[test]
    fn contact_rational64() {
        checks::<Rational64>();
    }
    #[test]
    fn contact_bigrational() {
        checks::<BigRational>();
    }
}
