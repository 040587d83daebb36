//! `lem:proj-characterization` for the two convex sets the paper projects
//! on: `C = K^N` (`df:KN`, the position projection of `eq:proj-micro-x`) and
//! `C = H^N_{x(t)}` (`df:H-micro`, the velocity projection of
//! `eq:proj-micro-u`): `y = P_C(z) ⟺ z − y ∈ N_y C`, both directions, with
//! the crate's projections (`project_k`, `project_h`).
//!
//! The normal cones in coordinates: with `n_j = e_j − e_{j+1}` and the prefix
//! sums `m_i = Σ_{k ≤ i} v_k`, every `v` with `m_N = 0` is
//! `v = Σ_{j<N} m_j n_j`, and
//! * `v ∈ N_y K^N` ⟺ `m_N = 0`, `m_j ≥ 0` and `m_j = 0` off the contacts of `y`;
//! * `v ∈ N_w H_x = H_x^⊥` ⟺ `m_N = 0` and `m_j = 0` off the contacts of `x`.

use super::{positive_times, render_vec, state, sub, R};
use crate::claims::{Case, Violation};
use crate::cluster::{contact_clusters, contact_set, project_h, Cluster};
use crate::projection::{free_flight, project_k};
use crate::scalar::Scalar;

const ID: &str = "lem:proj-characterization";
const ID_H: &str = "lem:proj-characterization#H";

/// The convex set `C` a projection is onto, for the sign its normal cone
/// puts on the coefficients of the contacts.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ConvexSet {
    /// The cone `K^N` (`df:KN`): coefficients `≥ 0` on the contacts.
    Cone,
    /// A subspace, `H_x` (`df:H-micro`): coefficients of any sign.
    Subspace,
}

/// `m_i = Σ_{k ≤ i} v_k`, `i = 1 … N`.
fn prefix<S: Scalar>(v: &[S]) -> Vec<S> {
    let mut acc = S::zero();
    v.iter()
        .map(|x| {
            acc = acc.clone() + x;
            acc.clone()
        })
        .collect()
}

/// Whether `v` lies in the normal cone at a point whose contact pairs are
/// `contacts` (0-based pairs `(j, j+1)`) of the convex `set`: of `K^N` (the
/// coefficients on contacts must be `≥ 0`) or of the subspace `H` (any
/// sign). `Err` says why not.
pub fn normal_coefficients<S: Scalar>(
    v: &[S],
    contacts: &[usize],
    set: ConvexSet,
) -> Result<(), String> {
    let m = prefix(v);
    if let Some(last) = m.last() {
        if !last.is_zero() {
            return Err(format!("Σ v_i = {} ≠ 0", last.render()));
        }
    }
    for (j, mj) in m.iter().enumerate().take(v.len().saturating_sub(1)) {
        let contact = contacts.contains(&j);
        if !contact && !mj.is_zero() {
            return Err(format!(
                "coefficient of e[{j}] − e[{}] is {} ≠ 0 but pair ({j}, {}) is apart",
                j + 1,
                mj.render(),
                j + 1
            ));
        }
        if contact && set == ConvexSet::Cone && mj.total_cmp(&S::zero()).is_lt() {
            return Err(format!(
                "coefficient of e[{j}] − e[{}] is {} < 0",
                j + 1,
                mj.render()
            ));
        }
    }
    Ok(())
}

/// `y + Σ_j μ_j (e_j − e_{j+1})`.
fn add_normal<S: Scalar>(y: &[S], mu: &[(usize, S)]) -> Vec<S> {
    let mut z = y.to_vec();
    for (j, m) in mu {
        z[*j] = z[*j].clone() + m;
        z[*j + 1] = z[*j + 1].clone() - m;
    }
    z
}

/// At most 8 indices of `0..len`, spread evenly (first and last included).
fn spread(len: usize) -> Vec<usize> {
    if len <= 8 {
        return (0..len).collect();
    }
    let mut v: Vec<usize> = (0..8).map(|k| k * (len - 1) / 7).collect();
    v.dedup();
    v
}

/// `lem:proj-characterization` for a convex set `C` with the projection
/// `project`, at the point `z` and the anchor `a ∈ C` whose contact pairs
/// are `contacts` (`set`: `C` is the cone `K^N` or a subspace):
/// * ⟹: `y = project(z)` has `z − y ∈ N_y C` (`contacts_of(y)` its contacts);
/// * ⟸: `z' = a + Σ μ_j n_j` with `μ_j = ((j + k) mod 3)` on the contacts
///   (`− 1` as well for a subspace), `k = 0, 1, 2`, projects back to `a`;
/// * and `z' − a ∉ N_a C` gives `project(z') ≠ a`: `z' = a + (1, …, 1)`,
///   `a + n_j` for a pair apart, `a − n_j` for a contact of `K^N`.
pub fn characterization<S: Scalar>(
    z: &[S],
    a: &[S],
    contacts: &[usize],
    set: ConvexSet,
    project: impl Fn(&[S]) -> Vec<S>,
    contacts_of: impl Fn(&[S]) -> Option<Vec<usize>>,
) -> Result<(), String> {
    // ⟹
    let y = project(z);
    let Some(cy) = contacts_of(&y) else {
        return Err(format!("P_C(z) = {} ∉ C", render_vec(&y)));
    };
    normal_coefficients(&sub(z, &y), &cy, set).map_err(|e| {
        format!(
            "y = P_C(z) = {} for z = {}, but z − y ∉ N_y C: {e}",
            render_vec(&y),
            render_vec(z)
        )
    })?;
    // ⟸
    for k in 0..3usize {
        let mu: Vec<(usize, S)> = contacts
            .iter()
            .map(|&j| {
                let c = ((j + k) % 3) as i64;
                let c = match set {
                    ConvexSet::Cone => c,
                    ConvexSet::Subspace => c - 1,
                };
                (j, S::from_i64(c))
            })
            .collect();
        let z2 = add_normal(a, &mu);
        let y2 = project(&z2);
        if y2 != a {
            return Err(format!(
                "y = {} ∈ C and z − y = Σ μ[j] (e[j] − e[j+1]) ∈ N_y C (μ[j] = {} on the contacts), but P_C(z) = {}",
                render_vec(a),
                match set {
                    ConvexSet::Cone => "(j + k mod 3)",
                    ConvexSet::Subspace => "(j + k mod 3) − 1",
                },
                render_vec(&y2)
            ));
        }
    }
    // z − a ∉ N_a C ⟹ P_C(z) ≠ a.
    let n = a.len();
    let mut outside: Vec<(String, Vec<S>)> = vec![(
        "(1, …, 1)".to_string(),
        a.iter().map(|x| x.clone() + &S::one()).collect(),
    )];
    for j in spread(n.saturating_sub(1)) {
        let contact = contacts.contains(&j);
        if !contact {
            outside.push((
                format!("e[{j}] − e[{}]", j + 1),
                add_normal(a, &[(j, S::one())]),
            ));
        } else if set == ConvexSet::Cone {
            outside.push((
                format!("−(e[{j}] − e[{}])", j + 1),
                add_normal(a, &[(j, -S::one())]),
            ));
        }
    }
    for (what, z3) in outside {
        if project(&z3) == a {
            return Err(format!(
                "z − y = {what} ∉ N_y C, yet P_C(z) = y = {}",
                render_vec(a)
            ));
        }
    }
    Ok(())
}

/// The contact pairs of `y` if `y ∈ K^N`.
fn k_contacts<S: Scalar>(y: &[S], two_r: &S) -> Option<Vec<usize>> {
    let admissible = y
        .windows(2)
        .all(|w| (w[1].clone() - &w[0]).total_cmp(two_r).is_ge());
    admissible.then(|| contact_set(y, two_r))
}

/// The contact pairs of the partition `clusters` if `w ∈ H` (constant on
/// every cluster).
fn h_contacts<S: Scalar>(w: &[S], clusters: &[Cluster]) -> Option<Vec<usize>> {
    let mut pairs = Vec::new();
    for c in clusters {
        for j in c.first..c.end() - 1 {
            if w[j] != w[j + 1] {
                return None;
            }
            pairs.push(j);
        }
    }
    Some(pairs)
}

/// `lem:proj-characterization` for `C = K^N` at every probe time: `z = x⁰ +
/// t u⁰` and `y = P_K(z)` (⟹), the anchor `x(t)` with multipliers on its
/// contacts (⟸), and points outside `x(t) + N_{x(t)}K^N`.
pub fn proj_characterization_k<S: Scalar>(case: &Case<S>) -> R {
    let two_r = case.data().two_r();
    for t in &case.times {
        let s = state(case, t, ID)?;
        let z = free_flight(case.data(), t);
        let contacts = contact_set(&s.positions, &two_r);
        characterization(
            &z,
            &s.positions,
            &contacts,
            ConvexSet::Cone,
            |v| project_k(v, &two_r),
            |y| k_contacts(y, &two_r),
        )
        .map_err(|e| Violation::new(ID, format!("C = K^N, t = {}: {e}", t.render())))?;
    }
    Ok(())
}

/// `lem:proj-characterization` for `C = H^N_{x(t)}` at every probe time
/// `t > 0`: `z = u⁰` and `w = P_H(u⁰)` (⟹), the anchor `u(t) ∈ H` with
/// multipliers of both signs on the contacts (⟸), and points outside
/// `u(t) + H^⊥`.
pub fn proj_characterization_h<S: Scalar>(case: &Case<S>) -> R {
    let two_r = case.data().two_r();
    for t in positive_times(case) {
        let s = state(case, t, ID_H)?;
        let clusters = contact_clusters(&s.positions, &two_r);
        let contacts = contact_set(&s.positions, &two_r);
        characterization(
            case.data().velocities(),
            &s.velocities,
            &contacts,
            ConvexSet::Subspace,
            |v| project_h(v, &clusters),
            |w| h_contacts(w, &clusters),
        )
        .map_err(|e| Violation::new(ID_H, format!("C = H_x(t), t = {}: {e}", t.render())))?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use num_rational::BigRational;

    fn q(n: i64) -> BigRational {
        BigRational::from_integer(n.into())
    }

    /// A configuration with contacts: 2r = 1, x = (0, 1, 3, 4, 6).
    fn setting() -> (Vec<BigRational>, Vec<usize>, BigRational) {
        let x: Vec<_> = [0, 1, 3, 4, 6].into_iter().map(q).collect();
        let two_r = q(1);
        let c = contact_set(&x, &two_r);
        (x, c, two_r)
    }

    #[test]
    fn the_crate_projection_passes() {
        let (x, c, two_r) = setting();
        let z: Vec<_> = [2, 0, 5, 1, 1].into_iter().map(q).collect();
        characterization(
            &z,
            &x,
            &c,
            ConvexSet::Cone,
            |v| project_k(v, &two_r),
            |y| k_contacts(y, &two_r),
        )
        .unwrap();
        let clusters = contact_clusters(&x, &two_r);
        let w: Vec<_> = [1, 1, -2, -2, 5].into_iter().map(q).collect();
        characterization(
            &z,
            &w,
            &c,
            ConvexSet::Subspace,
            |v| project_h(v, &clusters),
            |w| h_contacts(w, &clusters),
        )
        .unwrap();
    }

    /// A wrong projection onto K^N (pushing each violated pair apart
    /// symmetrically, once, left to right) fails.
    #[test]
    fn a_local_fix_is_not_the_projection() {
        let (x, c, two_r) = setting();
        let local = |v: &[BigRational]| {
            let mut y = v.to_vec();
            for j in 0..y.len() - 1 {
                let gap = y[j + 1].clone() - &y[j];
                if gap < two_r {
                    let d = (two_r.clone() - gap) / q(2);
                    y[j] = y[j].clone() - &d;
                    y[j + 1] = y[j + 1].clone() + &d;
                }
            }
            y
        };
        let z: Vec<_> = [3, 0, 0, 10, 11].into_iter().map(q).collect();
        let e = characterization(&z, &x, &c, ConvexSet::Cone, local, |y| {
            k_contacts(y, &two_r)
        });
        assert!(e.is_err(), "{e:?}");
    }

    /// The identity map on K^N (a projection onto a larger set) fails ⟸,
    /// and a "projection onto H" averaging one particle too few fails ⟹.
    #[test]
    fn wrong_projections_fail() {
        let (x, c, two_r) = setting();
        let e = characterization(
            &x.clone(),
            &x,
            &c,
            ConvexSet::Cone,
            |v| v.to_vec(),
            |y| k_contacts(y, &two_r),
        );
        assert!(e.is_err());
        let clusters = contact_clusters(&x, &two_r);
        let short = |v: &[BigRational]| {
            let mut out = project_h(v, &clusters);
            // the first cluster's mean without its last particle
            let m = v[0].clone();
            out[0] = m.clone();
            out[1] = m;
            out
        };
        let z: Vec<_> = [2, 0, 5, 1, 1].into_iter().map(q).collect();
        let e = characterization(
            &z,
            &project_h(&z, &clusters),
            &c,
            ConvexSet::Subspace,
            short,
            |w| h_contacts(w, &clusters),
        );
        assert!(e.is_err());
    }
}
