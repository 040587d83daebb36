//! Contact sets, contact clusters and the subspace `H_x`.
//!
//! * `Ω_x = { j : x_{j+1} = x_j + 2r }` — `df:Omega-micro` (0-based here:
//!   `j` stands for the pair `(j, j+1)`);
//! * a contact cluster is a maximal run of particles joined by contacts;
//! * `H_x = { u : u_{j+1} = u_j for j ∈ Ω_x }` — `df:H-micro`; the orthogonal
//!   projection onto it replaces `u` by its mean over each cluster
//!   (`eq:proj-u-micro`).

use crate::scalar::Scalar;

/// A run of consecutive particles `first, …, first + size − 1` (0-based).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Cluster {
    /// Index of the leftmost particle (0-based).
    pub first: usize,
    /// Number of particles (at least 1).
    pub size: usize,
}

impl Cluster {
    /// One past the rightmost particle.
    pub fn end(&self) -> usize {
        self.first + self.size
    }
    /// The particle indices of the cluster.
    pub fn range(&self) -> std::ops::Range<usize> {
        self.first..self.end()
    }
}

/// The partition of `0..n` into maximal runs where `joined(j)` holds for every
/// pair `(j, j+1)` inside the run.
pub fn runs(n: usize, mut joined: impl FnMut(usize) -> bool) -> Vec<Cluster> {
    let mut out = Vec::new();
    let mut first = 0;
    for j in 0..n {
        if j + 1 == n || !joined(j) {
            out.push(Cluster {
                first,
                size: j + 1 - first,
            });
            first = j + 1;
        }
    }
    out
}

/// `Ω_x` (`df:Omega-micro`): the pairs `j` (0-based, for particles `j, j+1`)
/// in contact, `x_{j+1} − x_j = 2r`.
pub fn contact_set<S: Scalar>(x: &[S], two_r: &S) -> Vec<usize> {
    (0..x.len().saturating_sub(1))
        .filter(|&j| (x[j + 1].clone() - &x[j]) == *two_r)
        .collect()
}

/// Contact clusters of `x`: maximal runs joined by contacts.
pub fn contact_clusters<S: Scalar>(x: &[S], two_r: &S) -> Vec<Cluster> {
    runs(x.len(), |j| (x[j + 1].clone() - &x[j]) == *two_r)
}

/// The mean of `v` over each cluster, written back on every particle of the
/// cluster: the orthogonal projection onto `H` (`df:H-micro`) for the
/// partition `clusters` (`eq:proj-u-micro`).
pub fn project_h<S: Scalar>(v: &[S], clusters: &[Cluster]) -> Vec<S> {
    let mut out = Vec::with_capacity(v.len());
    for c in clusters {
        let mean = mean(&v[c.range()]);
        out.extend(std::iter::repeat_n(mean, c.size));
    }
    out
}

/// The arithmetic mean of a non-empty slice.
pub fn mean<S: Scalar>(v: &[S]) -> S {
    let sum = v.iter().fold(S::zero(), |acc, x| acc + x);
    sum / S::from_usize(v.len().max(1))
}

/// `u ∈ C_x` (`def:velcone`): `u_{j+1} ≥ u_j` wherever `x_{j+1} = x_j + 2r`.
/// Returns the first pair (0-based) that violates it.
pub fn velocity_cone_violation<S: Scalar>(x: &[S], u: &[S], two_r: &S) -> Option<usize> {
    contact_set(x, two_r)
        .into_iter()
        .find(|&j| u[j].total_cmp(&u[j + 1]).is_gt())
}

/// `u ∈ H_x` (`df:H-micro`): returns the first contact pair (0-based) on which
/// `u_{j+1} ≠ u_j`.
pub fn h_violation<S: Scalar>(x: &[S], u: &[S], two_r: &S) -> Option<usize> {
    contact_set(x, two_r)
        .into_iter()
        .find(|&j| u[j] != u[j + 1])
}

#[cfg(test)]
mod tests {
    use super::*;
    use num_rational::{BigRational, Rational64};

    fn checks<S: Scalar>() {
        let q = |n: i64, d: i64| S::from_i64(n) / S::from_i64(d);
        let x = vec![q(0, 1), q(1, 2), q(1, 1), q(3, 1), q(7, 2)];
        let two_r = q(1, 2);
        assert_eq!(contact_set(&x, &two_r), vec![0, 1, 3]);
        assert_eq!(
            contact_clusters(&x, &two_r),
            vec![Cluster { first: 0, size: 3 }, Cluster { first: 3, size: 2 }]
        );
        let u = vec![q(1, 1), q(2, 1), q(6, 1), q(0, 1), q(1, 1)];
        let p = project_h(&u, &contact_clusters(&x, &two_r));
        assert_eq!(p, vec![q(3, 1), q(3, 1), q(3, 1), q(1, 2), q(1, 2)]);
        assert_eq!(velocity_cone_violation(&x, &u, &two_r), None);
        assert_eq!(h_violation(&x, &u, &two_r), Some(0));
        assert_eq!(h_violation(&x, &p, &two_r), None);
        let u_bad = vec![q(1, 1), q(0, 1), q(6, 1), q(0, 1), q(1, 1)];
        assert_eq!(velocity_cone_violation(&x, &u_bad, &two_r), Some(0));
        assert_eq!(runs(1, |_| true), vec![Cluster { first: 0, size: 1 }]);
        assert_eq!(runs(0, |_| true), vec![]);
    }

    #[test]
    fn clusters_rational64() {
        checks::<Rational64>();
    }
    #[test]
    fn clusters_bigrational() {
        checks::<BigRational>();
    }
}
