//! The state of the particle system at one time `t`.

use crate::cluster::Cluster;

/// Positions, velocities, multipliers and contact clusters at time `t` —
/// exactly the fields of the JSON contract (docs/guide/json.md).
#[derive(Debug, Clone, PartialEq)]
pub struct State<S> {
    /// The time `t ≥ 0`.
    pub t: S,
    /// `x(t) = P_K(x⁰ + t u⁰)` (`eq:proj-micro-x`).
    pub positions: Vec<S>,
    /// `u(t)`, the right derivative of `x` (post-collision velocity); for
    /// `t > 0` it is `P_{H_{x(t)}}(u⁰)` (`eq:proj-u-micro`).
    pub velocities: Vec<S>,
    /// `λ_1 … λ_{N−1}` of `eq:dyn-micro` (`λ_0 = λ_N = 0` checked, not stored).
    pub multipliers: Vec<S>,
    /// Contact clusters of `x(t)`: maximal runs joined by contacts
    /// `x_{i+1} − x_i = 2r` (`df:Omega-micro`), left to right.
    pub clusters: Vec<Cluster>,
}
