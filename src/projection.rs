//! The projection onto `K^N` by pool-adjacent-violators, and the one-shot
//! solution `x(t) = P_K(x⁰ + t u⁰)`.
//!
//! `prop:proj-micro` / `eq:proj-micro-x`:
//! > "there exists a unique solution x to (eq:micro-f0-lagr). It is given by
//! > the projection formula x(t) = P_{K^N}(x_0 + t u_0), t ≥ 0."
//!
//! In the translated coordinates `x̃_i = x_i − 2r(i−1)` (`df:translat-x`) the
//! set `K^N` is the cone of non-decreasing vectors (`df:tKN`), so `P_K` is
//! isotonic regression with unit weights, computed in O(N) by
//! pool-adjacent-violators.
//!
//! **Right derivative.** The velocity reported at `t` is the right derivative
//! `u(t) = lim_{h↓0} (x(t+h) − x(t))/h` (post-collision). It is obtained
//! exactly by running the same PAVA on the pairs `(x̃⁰_i + t u⁰_i, u⁰_i)`
//! ordered lexicographically — i.e. PAVA in the ordered field `R(ε)` at the
//! time `t + ε` with `ε` infinitesimal. Pooled blocks are then the clusters
//! that move together just after `t`; the first component of a block mean is
//! `x̃(t)`, the second is the cluster velocity, the mean of `u⁰` over the
//! block (`eq:proj-u-micro`). For `t > 0` these blocks are the contact
//! clusters of `x(t)`; at `t = 0` two particles in contact with
//! `u⁰_{i+1} > u⁰_i` form one contact cluster but two blocks (they separate).

use std::cmp::Ordering;

use crate::cluster::{runs, Cluster};
use crate::contact::multipliers;
use crate::error::Error;
use crate::initial::{unshift, InitialData};
use crate::scalar::Scalar;
use crate::state::State;

/// One pooled block of PAVA: `size` consecutive entries from `first`, with
/// the sums of the two keys over the block.
#[derive(Debug, Clone, PartialEq)]
pub struct Block<S> {
    /// First index (0-based).
    pub first: usize,
    /// Number of entries.
    pub size: usize,
    /// Sum of the primary key (shifted positions) over the block.
    pub sum_y: S,
    /// Sum of the secondary key (initial velocities) over the block.
    pub sum_u: S,
}

impl<S: Scalar> Block<S> {
    /// The block as a [`Cluster`].
    pub fn cluster(&self) -> Cluster {
        Cluster {
            first: self.first,
            size: self.size,
        }
    }
    /// Mean of the primary key.
    pub fn mean_y(&self) -> S {
        self.sum_y.clone() / S::from_usize(self.size)
    }
    /// Mean of the secondary key.
    pub fn mean_u(&self) -> S {
        self.sum_u.clone() / S::from_usize(self.size)
    }
}

/// The pooling decision of PAVA, for every PAVA loop of the crate (this
/// one on any [`Scalar`], the integer kernel, the adaptive solver): the
/// left block `a` pools with the right block `b` iff its mean is `≥` in the
/// lexicographic order on `(ȳ, ū)` — the order at `t + ε` that makes the
/// velocity the right derivative (module documentation, `prop:proj-micro`).
/// `primary` compares `ΣY_a k_b` with `ΣY_b k_a` (the means
/// cross-multiplied, no division); `secondary`, asked only on a tie,
/// compares `ΣU_a k_b` with `ΣU_b k_a`.
#[inline(always)]
pub fn pools(primary: Ordering, secondary: impl FnOnce() -> Ordering) -> bool {
    match primary {
        Ordering::Greater => true,
        Ordering::Less => false,
        Ordering::Equal => secondary() != Ordering::Less,
    }
}

/// [`pools`] on two blocks of scalars.
fn blocks_pool<S: Scalar>(a: &Block<S>, b: &Block<S>) -> bool {
    let ka = S::from_usize(a.size);
    let kb = S::from_usize(b.size);
    pools(
        (a.sum_y.clone() * &kb).total_cmp(&(b.sum_y.clone() * &ka)),
        || (a.sum_u.clone() * &kb).total_cmp(&(b.sum_u.clone() * &ka)),
    )
}

/// Pool-adjacent-violators on the pairs `(y_i, u_i)` in lexicographic order
/// (`u` = all zeros when `None`). Adjacent blocks are pooled while the left
/// mean is `≥` the right one, so the blocks returned have strictly increasing
/// means: they are the maximal level sets of the isotonic regression.
pub fn pava_blocks<S: Scalar>(y: &[S], u: Option<&[S]>) -> Vec<Block<S>> {
    let mut stack: Vec<Block<S>> = Vec::with_capacity(y.len());
    for (i, yi) in y.iter().enumerate() {
        let mut cur = Block {
            first: i,
            size: 1,
            sum_y: yi.clone(),
            sum_u: u.map_or_else(S::zero, |u| u[i].clone()),
        };
        while let Some(top) = stack.pop() {
            if !blocks_pool(&top, &cur) {
                stack.push(top);
                break;
            }
            cur = Block {
                first: top.first,
                size: top.size + cur.size,
                sum_y: top.sum_y + &cur.sum_y,
                sum_u: top.sum_u + &cur.sum_u,
            };
        }
        stack.push(cur);
    }
    stack
}

/// Isotonic regression of `y` (unit weights): the projection onto the cone
/// of non-decreasing vectors `K̃^N` (`df:tKN`).
pub fn isotonic<S: Scalar>(y: &[S]) -> Vec<S> {
    let mut out = Vec::with_capacity(y.len());
    for b in pava_blocks(y, None) {
        out.extend(std::iter::repeat_n(b.mean_y(), b.size));
    }
    out
}

/// `P_{K^N}(y)` for `K^N = { x : x_{i+1} − x_i ≥ 2r }` (`df:KN`).
pub fn project_k<S: Scalar>(y: &[S], two_r: &S) -> Vec<S> {
    let shifted = crate::initial::shift(y, two_r);
    unshift(&isotonic(&shifted), two_r)
}

/// The one-shot solution at time `t`: everything the projection formula
/// gives, before it is packaged as a [`State`].
#[derive(Debug, Clone, PartialEq)]
pub struct Projected<S> {
    /// `y = x⁰ + t u⁰`, translated: `ỹ_i = x̃⁰_i + t u⁰_i`.
    pub shifted_free: Vec<S>,
    /// `x̃(t)`, the translated positions.
    pub shifted: Vec<S>,
    /// The PAVA blocks at `t + ε`: clusters moving together just after `t`.
    pub blocks: Vec<Block<S>>,
}

/// The free flight `y = x⁰ + t u⁰` (untranslated): the point `P_K` projects
/// in `eq:proj-micro-x`. Written once for every scalar; the `f64` reference
/// solvers and the claims checkers both call it.
pub fn free_flight<S: Scalar>(data: &InitialData<S>, t: &S) -> Vec<S> {
    data.positions()
        .iter()
        .zip(data.velocities())
        .map(|(x, u)| x.clone() + &(t.clone() * u))
        .collect()
}

/// The translated free flight `ỹ_i = x̃⁰_i + t u⁰_i` (`x̃⁰_i = x⁰_i − 2r·i`):
/// what the lexicographic PAVA projects on the monotone cone.
pub fn shifted_free_flight<S: Scalar>(data: &InitialData<S>, t: &S) -> Vec<S> {
    data.shifted_positions()
        .into_iter()
        .zip(data.velocities())
        .map(|(x, u)| x + &(t.clone() * u))
        .collect()
}

/// Runs the lexicographic PAVA at time `t` (see the module documentation).
pub fn project_at<S: Scalar>(data: &InitialData<S>, t: &S) -> Projected<S> {
    let u0 = data.velocities();
    let shifted_free = shifted_free_flight(data, t);
    let blocks = pava_blocks(&shifted_free, Some(u0));
    let mut shifted = Vec::with_capacity(data.n());
    for b in &blocks {
        shifted.extend(std::iter::repeat_n(b.mean_y(), b.size));
    }
    Projected {
        shifted_free,
        shifted,
        blocks,
    }
}

/// The state at time `t ≥ 0` from the projection formula alone
/// (`eq:proj-micro-x`, `eq:proj-u-micro`, `eq:dyn-micro`): positions,
/// right-derivative velocities, multipliers `λ` and contact clusters.
pub fn state_at<S: Scalar>(data: &InitialData<S>, t: &S) -> Result<State<S>, Error> {
    if t.total_cmp(&S::zero()).is_lt() {
        return Err(Error::NegativeTime { t: t.render() });
    }
    let p = project_at(data, t);
    let mut velocities = Vec::with_capacity(data.n());
    for b in &p.blocks {
        velocities.extend(std::iter::repeat_n(b.mean_u(), b.size));
    }
    let positions = unshift(&p.shifted, &data.two_r());
    let clusters = runs(data.n(), |j| p.shifted[j] == p.shifted[j + 1]);
    let (multipliers, _lambda_n) = multipliers(data.velocities(), &velocities);
    Ok(State {
        t: t.clone(),
        positions,
        velocities,
        multipliers,
        clusters,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use num_rational::{BigRational, Rational64};

    fn q<S: Scalar>(n: i64, d: i64) -> S {
        S::from_i64(n) / S::from_i64(d)
    }

    fn pava_cases<S: Scalar>() {
        let y: Vec<S> = [3, 1, 2, 5, 4, 4].iter().map(|&v| S::from_i64(v)).collect();
        assert_eq!(
            isotonic(&y),
            vec![q(2, 1), q(2, 1), q(2, 1), q(13, 3), q(13, 3), q(13, 3)]
        );
        // Ties are pooled: the blocks are the maximal level sets.
        let blocks = pava_blocks(&[S::one(), S::one()], None);
        assert_eq!(blocks.len(), 1);
        assert!(isotonic::<S>(&[]).is_empty());
    }

    fn two_blocks<S: Scalar>() {
        // Four particles, 2r = 1/4 (not touching), blocks approach at speed 2.
        let data = InitialData::new(
            q::<S>(1, 8),
            vec![q(0, 1), q(1, 4), q(3, 4), q(1, 1)],
            vec![q(1, 1), q(1, 1), q(-1, 1), q(-1, 1)],
        )
        .unwrap();
        // Gap between particles 2 and 3 is 1/2 - 1/4 = 1/4: collision at 1/8.
        let before = state_at(&data, &q(1, 16)).unwrap();
        assert_eq!(before.clusters.len(), 2);
        assert_eq!(before.velocities, data.velocities());
        let at = state_at(&data, &q(1, 8)).unwrap();
        assert_eq!(at.clusters, vec![Cluster { first: 0, size: 4 }]);
        assert_eq!(at.velocities, vec![S::zero(); 4]);
        assert_eq!(at.positions, vec![q(1, 8), q(3, 8), q(5, 8), q(7, 8)]);
        // λ: u − u⁰ = −N(λ_i − λ_{i−1}), N = 4: λ = (1/4, 1/2, 1/4).
        assert_eq!(at.multipliers, vec![q(1, 4), q(1, 2), q(1, 4)]);
        let late = state_at(&data, &q(7, 1)).unwrap();
        assert_eq!(late.positions, at.positions);
        assert!(state_at(&data, &q(-1, 1)).is_err());
    }

    fn separating_contact_at_zero<S: Scalar>() {
        let data =
            InitialData::new(q::<S>(1, 2), vec![q(0, 1), q(1, 1)], vec![q(0, 1), q(1, 1)]).unwrap();
        let s = state_at(&data, &S::zero()).unwrap();
        assert_eq!(s.clusters, vec![Cluster { first: 0, size: 2 }]);
        assert_eq!(s.velocities, data.velocities(), "right derivative at 0");
        assert_eq!(s.multipliers, vec![S::zero()]);
    }

    /// Isotonic regression by its closed form,
    /// `P(y)_i = max_{j ≤ i} min_{k ≥ i} mean(y_j … y_k)`, in any ordered
    /// field — here pairs `(y, u)` in the lexicographic order, the field
    /// `R(ε)` of the module documentation (means are taken componentwise).
    fn min_max(y: &[(Rational64, Rational64)]) -> Vec<(Rational64, Rational64)> {
        let mean = |j: usize, k: usize| {
            let len = Rational64::from_usize(k + 1 - j);
            let (sy, su) = y[j..=k].iter().fold(
                (Rational64::zero(), Rational64::zero()),
                |(a, b), (p, q)| (a + p, b + q),
            );
            (sy / len, su / len)
        };
        (0..y.len())
            .map(|i| {
                (0..=i)
                    .map(|j| (i..y.len()).map(|k| mean(j, k)).min().unwrap())
                    .max()
                    .unwrap()
            })
            .collect()
    }

    /// PAVA (pooling by cross-multiplied means, lexicographic tie-break)
    /// equals the closed form on every vector of a pseudo-random family with
    /// many ties and blocks of unequal sizes, primary key alone and with a
    /// secondary key.
    #[test]
    fn pava_is_the_min_max_formula() {
        let mut state = 0x2545_F491_4F6C_DD1Du64;
        let mut small = |m: u64| {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state % m) as i64 - (m as i64) / 2
        };
        for round in 0..400 {
            let len = 1 + round % 9;
            let y: Vec<Rational64> = (0..len).map(|_| Rational64::from_i64(small(7))).collect();
            let u: Vec<Rational64> = (0..len).map(|_| Rational64::from_i64(small(5))).collect();
            let pairs: Vec<_> = y.iter().cloned().zip(u.iter().cloned()).collect();
            let want = min_max(&pairs);
            let mut got = Vec::new();
            for b in pava_blocks(&y, Some(&u)) {
                got.extend(std::iter::repeat_n((b.mean_y(), b.mean_u()), b.size));
            }
            assert_eq!(got, want, "y = {y:?}, u = {u:?}");
            let primary: Vec<_> = y.iter().map(|v| (*v, Rational64::zero())).collect();
            let want: Vec<Rational64> = min_max(&primary).into_iter().map(|p| p.0).collect();
            assert_eq!(isotonic(&y), want, "y = {y:?}");
        }
    }

    /// `P_K` on known points: a point of `K` is fixed, two particles at the
    /// same place are pushed apart symmetrically, and `P_K(0)` is the
    /// centred chain `2r·(i − (N−1)/2)`.
    #[test]
    fn project_k_known_points() {
        let q = |n, d| Rational64::new(n, d);
        let inside = vec![q(0, 1), q(1, 1), q(5, 2)];
        assert_eq!(project_k(&inside, &q(1, 1)), inside);
        assert_eq!(
            project_k(&[q(0, 1), q(0, 1)], &q(1, 1)),
            vec![q(-1, 2), q(1, 2)]
        );
        assert_eq!(
            project_k(&[Rational64::zero(); 4], &q(1, 2)),
            vec![q(-3, 4), q(-1, 4), q(1, 4), q(3, 4)]
        );
        assert!(project_k::<Rational64>(&[], &q(1, 1)).is_empty());
    }

    /// The free flight `x⁰ + t u⁰`, and its translated form `x̃⁰ + t u⁰`.
    #[test]
    fn free_flight_values() {
        let q = |n, d| Rational64::new(n, d);
        let data = InitialData::new(
            q(1, 4),
            vec![q(0, 1), q(1, 1), q(3, 1)],
            vec![q(2, 1), q(-1, 1), q(1, 3)],
        )
        .unwrap();
        let t = q(3, 2);
        assert_eq!(free_flight(&data, &t), vec![q(3, 1), q(-1, 2), q(7, 2)]);
        assert_eq!(
            shifted_free_flight(&data, &t),
            vec![q(3, 1), q(-1, 1), q(5, 2)]
        );
        assert_eq!(free_flight(&data, &Rational64::zero()), data.positions());
    }

    #[test]
    fn pava_rational64() {
        pava_cases::<Rational64>();
        two_blocks::<Rational64>();
        separating_contact_at_zero::<Rational64>();
    }
    #[test]
    fn pava_bigrational() {
        pava_cases::<BigRational>();
        two_blocks::<BigRational>();
        separating_contact_at_zero::<BigRational>();
    }
    #[test]
    fn pava_f64() {
        pava_cases::<f64>();
        two_blocks::<f64>();
    }
}
