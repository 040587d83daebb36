//! The Eulerian fields at a point: density, velocity, momentum and pressure
//! of the continuum and of the particles, and the pointwise checks on them
//! (complementarity of `Λ`, the Oleinik bound).

use super::particles::ClusterPositions;
use crate::limit::continuum::Profile;
use crate::limit::interpolation::{abs, max_of, Snapshot};
use crate::scalar::Scalar;
use crate::trajectory::Trajectory;

/// The largest `|Λ(t, w)|` over the segments outside the plateaus, where
/// `∂_w X > 1` (it must be 0: `(∂_w X − 1) Λ = 0` of `eq:Lagr-1`, whence
/// `(1 − ρ)p = 0`), evaluated at both ends of each segment.
pub fn complementarity_defect<V: Scalar>(profile: &Profile<V>) -> V {
    profile
        .segments
        .iter()
        .filter(|s| s.plateau.is_none())
        .flat_map(|s| {
            [s.w0.clone(), s.w1.clone()]
                .into_iter()
                .map(move |w| (s, w))
        })
        .map(|(s, w)| {
            abs(s.lambda[0].clone()
                + &(s.lambda[1].clone() * &w)
                + &(s.lambda[2].clone() * &w * &w))
        })
        .fold(V::zero(), max_of)
}

/// `t · sup ∂_x u` for the continuum profile (see the module
/// documentation); `None` when `u` jumps up with no gap in `X` (an
/// infinite `∂_x u`, violating `eq:Oleinik-Lagr`). A gap `|[X]| ≤ tol` is
/// treated as no gap: pass 0 for an exact profile, the rounding bound of
/// the profile for a rounded one (where `X`, continuous at a plateau end,
/// may come out with a gap of `±1e-16`).
pub fn oleinik_margin<V: Scalar>(profile: &Profile<V>, t: &V, tol: &V) -> Option<V> {
    let mut m = V::zero();
    let mut prev: Option<(V, V)> = None; // (X, U) at the previous right end
    for s in &profile.segments {
        if !s.x[1].is_zero() {
            m = max_of(m, t.clone() * &s.u[1] / &s.x[1]);
        }
        let xl = s.x[0].clone() + &(s.x[1].clone() * &s.w0);
        let ul = s.u[0].clone() + &(s.u[1].clone() * &s.w0);
        if let Some((xp, up)) = prev {
            let dx = xl.clone() - &xp;
            let du = ul.clone() - &up;
            if abs(dx.clone()).total_cmp(tol).is_le() {
                if du.total_cmp(tol).is_gt() {
                    return None;
                }
            } else {
                m = max_of(m, t.clone() * &du / &dx);
            }
        }
        prev = Some((
            s.x[0].clone() + &(s.x[1].clone() * &s.w1),
            s.u[0].clone() + &(s.u[1].clone() * &s.w1),
        ));
    }
    Some(m)
}

/// The continuum density `ρ(t, x)` (0 in vacuum, `1/∂_w X` on the image of
/// a segment; on a plateau, 1).
pub fn continuum_density<V: Scalar>(profile: &Profile<V>, x: &V) -> V {
    for s in &profile.segments {
        let a = s.x[0].clone() + &(s.x[1].clone() * &s.w0);
        let b = s.x[0].clone() + &(s.x[1].clone() * &s.w1);
        if a.total_cmp(x).is_le() && x.total_cmp(&b).is_lt() && !s.x[1].is_zero() {
            return V::one() / &s.x[1];
        }
    }
    V::zero()
}

/// The continuum velocity `u(t, x) = U(t, W(t, x))` on the support
/// (`None` in vacuum).
pub fn continuum_velocity<V: Scalar>(profile: &Profile<V>, x: &V) -> Option<V> {
    for s in &profile.segments {
        let a = s.x[0].clone() + &(s.x[1].clone() * &s.w0);
        let b = s.x[0].clone() + &(s.x[1].clone() * &s.w1);
        if a.total_cmp(x).is_le() && x.total_cmp(&b).is_lt() && !s.x[1].is_zero() {
            let w = (x.clone() - &s.x[0]) / &s.x[1];
            return Some(s.u[0].clone() + &(s.u[1].clone() * &w));
        }
    }
    None
}

/// The continuum momentum density `ρu(t, x)` (0 in vacuum), the density of
/// `X(t)#(U L¹)`.
pub fn continuum_momentum<V: Scalar>(profile: &Profile<V>, x: &V) -> V {
    match continuum_velocity(profile, x) {
        Some(u) => continuum_density(profile, x) * &u,
        None => V::zero(),
    }
}

/// `Λ(t, W(t, x))`, `W` the generalised inverse of `X(t)` (0 in vacuum and
/// outside the support): the Eulerian pressure potential, whose time
/// derivative is `p = ∂_t Λ(t, W(t, x))` (the remark after the proposition
/// "Eulerian formulation").
pub fn continuum_pressure_potential<V: Scalar>(profile: &Profile<V>, x: &V) -> V {
    for s in &profile.segments {
        let a = s.x[0].clone() + &(s.x[1].clone() * &s.w0);
        let b = s.x[0].clone() + &(s.x[1].clone() * &s.w1);
        if a.total_cmp(x).is_le() && x.total_cmp(&b).is_lt() && !s.x[1].is_zero() {
            let w = (x.clone() - &s.x[0]) / &s.x[1];
            return s.lambda[0].clone()
                + &(s.lambda[1].clone() * &w)
                + &(s.lambda[2].clone() * &w * &w);
        }
    }
    V::zero()
}

/// The particle pressure `p_N = (Id, X_N)#P_N` as its atoms
/// `(t_k, x_i(t_k), [λ_i]_k / N)` (mass of the pair `(i, i+1)` placed at
/// `x_i`, as `X_N = x_i` on the cell of `P_N = p_i`), for the collisions
/// with `t_k ≤ t_end` and non-zero jumps. Cost: the total size of the
/// merged clusters (up to `O(N²)`), so meant for pictures at moderate N.
pub fn particle_pressure_atoms<S: Scalar>(traj: &Trajectory<S>, t_end: &S) -> Vec<(S, S, S)> {
    let n = S::from_usize(traj.data().n());
    let pos = ClusterPositions::new(traj);
    let mut out = Vec::new();
    for imp in traj.impulses() {
        if imp.t.total_cmp(t_end).is_gt() {
            break;
        }
        for (k, jump) in imp.jumps().into_iter().enumerate() {
            if !jump.is_zero() {
                let i = imp.cluster.first + k;
                out.push((
                    imp.t.clone(),
                    pos.position(imp.cluster, i, &imp.t),
                    jump / &n,
                ));
            }
        }
    }
    out
}

/// The particle density `ρ̃_N(t, x) = 1/(N(x_i − x_{i−1}))` on
/// `[x_{i−1}, x_i)` (`X̃_N # L¹`), 0 elsewhere.
pub fn particle_density<S: Scalar>(snap: &Snapshot<S>, x: &S) -> S {
    let k = snap.x.partition_point(|xi| xi.total_cmp(x).is_le());
    if k == 0 || k > snap.n {
        return S::zero();
    }
    let slope = snap.dw_x_tilde(k);
    if slope.is_zero() {
        S::zero()
    } else {
        S::one() / &slope
    }
}
