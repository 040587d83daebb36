//! The event-driven cluster merge: the whole history of sticky collisions.
//!
//! Collisions are perfectly inelastic: colliding clusters stick and move on
//! with their mean velocity (momentum is conserved, all masses are equal).
//! Hence a cluster `C` of `k` particles, once formed, moves rigidly and its
//! translated position (`df:translat-x`) is affine in `t` *from time 0*:
//!
//! `x̃_C(t) = (Σ_{i∈C} x̃⁰_i + t Σ_{i∈C} u⁰_i) / k`,
//!
//! so collision times are ratios of cluster sums of the initial data and never
//! accumulate digits. Two adjacent clusters `L`, `R` approach when
//! `ū_L > ū_R` and meet at
//!
//! `t = (S^x_R k_L − S^x_L k_R) / (S^u_L k_R − S^u_R k_L)`.
//!
//! A priority queue holds the next collision time of every adjacent pair;
//! all pairs meeting at the same instant are merged in one step (a chain of
//! three or more clusters becomes one cluster, recorded as one event with all
//! its parts). There are at most N − 1 merges; the cost is O(N log N)
//! arithmetic operations.
//!
//! `prop:proj-micro` asserts that this history is the projection formula
//! `x(t) = P_K(x⁰ + t u⁰)`: [`Trajectory::at`] and
//! [`crate::projection::state_at`] are compared exactly by the tests.
//!
//! **Initial clusters.** At `t = 0`, particles in contact with equal velocities
//! form a cluster; particles in contact with `u⁰_{i+1} > u⁰_i` (allowed by the
//! velocity cone `def:velcone`) separate at once and are different clusters.

use std::cmp::Ordering;
use std::collections::BinaryHeap;
use std::sync::OnceLock;

use crate::cluster::{runs, Cluster};
use crate::contact::{multipliers, Impulse};
use crate::error::Error;
use crate::initial::{unshift, InitialData};
use crate::progress::{Progress, Silent};
use crate::scalar::Scalar;
use crate::state::State;

/// A cluster during the merge, with the sums that fix its motion.
#[derive(Debug, Clone)]
struct Node<S> {
    first: usize,
    size: usize,
    sum_x: S,
    sum_u: S,
    alive: bool,
    prev: Option<usize>,
    next: Option<usize>,
    /// Set while the current instant lasts for a cluster formed at it: the
    /// pre-collision clusters that merged into it, with their velocities.
    born: Option<Vec<(Cluster, S)>>,
}

impl<S: Scalar> Node<S> {
    fn cluster(&self) -> Cluster {
        Cluster {
            first: self.first,
            size: self.size,
        }
    }
    fn velocity(&self) -> S {
        self.sum_u.over(&S::from_usize(self.size))
    }
}

/// A candidate collision between the adjacent clusters `left` and `right`.
#[derive(Debug, Clone)]
struct Candidate<S> {
    t: S,
    first: usize,
    left: usize,
    right: usize,
}

impl<S: Scalar> PartialEq for Candidate<S> {
    fn eq(&self, other: &Self) -> bool {
        self.cmp(other) == Ordering::Equal
    }
}
impl<S: Scalar> Eq for Candidate<S> {}
impl<S: Scalar> PartialOrd for Candidate<S> {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}
impl<S: Scalar> Ord for Candidate<S> {
    /// Reversed, so that `BinaryHeap` pops the earliest time (then the
    /// leftmost pair) first.
    fn cmp(&self, other: &Self) -> Ordering {
        other
            .t
            .total_cmp(&self.t)
            .then_with(|| other.first.cmp(&self.first))
    }
}

/// The complete sticky history of one initial datum.
#[derive(Debug, Clone)]
pub struct Trajectory<S> {
    data: InitialData<S>,
    /// The prefix sums of `x̃⁰` and `u⁰` that [`Trajectory::at`] and
    /// [`Trajectory::position_in`] read, computed on first use: over
    /// BigRational their denominators grow to the common denominator of
    /// the whole datum (`lcm(1, …, 20001)`, ~28,800 bits, for velocities
    /// `1/(i+1)`), so the event merge itself never builds them.
    prefix: OnceLock<Prefix<S>>,
    join_time: Vec<Option<S>>,
    impulses: Vec<Impulse<S>>,
}

/// The prefix sums `Σ_{j<i} x̃⁰_j` and `Σ_{j<i} u⁰_j` (N + 1 entries each):
/// cluster sums are differences of them.
#[derive(Debug, Clone)]
struct Prefix<S> {
    x: Vec<S>,
    u: Vec<S>,
}

/// The collision time of adjacent clusters, if they approach.
fn meeting_time<S: Scalar>(l: &Node<S>, r: &Node<S>) -> Option<S> {
    let kl = S::from_usize(l.size);
    let kr = S::from_usize(r.size);
    let closing = l.sum_u.times(&kr).minus(&r.sum_u.times(&kl));
    if closing.total_cmp(&S::zero()).is_le() {
        return None;
    }
    let gap = r.sum_x.times(&kl).minus(&l.sum_x.times(&kr));
    Some(gap.over(&closing))
}

/// The prefix sums of the translated positions `x̃⁰` and of the velocities
/// `u⁰` of `data`.
fn prefix_sums<S: Scalar>(data: &InitialData<S>) -> Prefix<S> {
    Prefix {
        x: prefix(&data.shifted_positions()),
        u: prefix(data.velocities()),
    }
}

/// `Σ_{i∈c} v_i`, summed as a balanced tree: over BigRational the partial
/// sums of a run keep the denominators of that run only, and the big
/// additions are few (a left-to-right sum would reduce every partial sum
/// over the growing common denominator).
fn tree_sum<S: Scalar>(v: &[S]) -> S {
    match v.len() {
        0 => S::zero(),
        1 => v[0].clone(),
        len => tree_sum(&v[..len / 2]).plus(&tree_sum(&v[len / 2..])),
    }
}

fn prefix<S: Scalar>(v: &[S]) -> Vec<S> {
    let mut out = Vec::with_capacity(v.len() + 1);
    let mut acc = S::zero();
    out.push(acc.clone());
    for x in v {
        acc = acc.plus(x);
        out.push(acc.clone());
    }
    out
}

impl<S: Scalar> Trajectory<S> {
    /// Computes every collision of the sticky dynamics started from `data`.
    pub fn new(data: InitialData<S>) -> Self {
        match Self::new_with_progress(data, &Silent) {
            Ok(t) => t,
            Err(_) => unreachable!("`Silent` never cancels"),
        }
    }

    /// [`Trajectory::new`], telling `progress` of the merges as they are
    /// done (one stage of at most `N − 1` steps) and stopping with
    /// [`Error::Interrupted`] when it asks, between two collision instants.
    pub fn new_with_progress(data: InitialData<S>, progress: &dyn Progress) -> Result<Self, Error> {
        let n = data.n();
        let shifted = data.shifted_positions();
        let u0 = data.velocities();
        let mut join_time: Vec<Option<S>> = vec![None; n.saturating_sub(1)];

        // Initial clusters: contacts with equal velocities.
        let initial = runs(n, |j| shifted[j] == shifted[j + 1] && u0[j] == u0[j + 1]);
        let mut nodes: Vec<Node<S>> = Vec::with_capacity(2 * initial.len());
        for (k, c) in initial.iter().enumerate() {
            for jt in &mut join_time[c.first..c.end() - 1] {
                *jt = Some(S::zero());
            }
            nodes.push(Node {
                first: c.first,
                size: c.size,
                sum_x: tree_sum(&shifted[c.first..c.end()]),
                sum_u: tree_sum(&u0[c.first..c.end()]),
                alive: true,
                prev: k.checked_sub(1),
                next: (k + 1 < initial.len()).then_some(k + 1),
                born: None,
            });
        }
        let mut heap = BinaryHeap::new();
        let push = |heap: &mut BinaryHeap<Candidate<S>>, nodes: &[Node<S>], l: usize, r: usize| {
            if let Some(t) = meeting_time(&nodes[l], &nodes[r]) {
                heap.push(Candidate {
                    t,
                    first: nodes[l].first,
                    left: l,
                    right: r,
                });
            }
        };
        for k in 1..nodes.len() {
            push(&mut heap, &nodes, k - 1, k);
        }

        let mut impulses = Vec::new();
        progress.stage(
            "the event merge: clusters merged",
            Some(n.saturating_sub(1) as u64),
        );
        while let Some(head) = heap.pop() {
            if !(nodes[head.left].alive && nodes[head.right].alive) {
                continue;
            }
            if progress.cancelled() {
                return Err(Error::Interrupted {
                    during: "the event merge",
                });
            }
            let t = head.t.clone();
            let mut pending = vec![head];
            let mut born_now: Vec<usize> = Vec::new();
            loop {
                // Every pair meeting at `t` (or, in floating point, computed
                // at or before `t`) joins this instant.
                while heap
                    .peek()
                    .is_some_and(|c| c.t.total_cmp(&t) != Ordering::Greater)
                {
                    if let Some(c) = heap.pop() {
                        if nodes[c.left].alive && nodes[c.right].alive {
                            pending.push(c);
                        }
                    }
                }
                if pending.is_empty() {
                    break;
                }
                pending.sort_by_key(|c| c.first);
                let mut fresh: Vec<usize> = Vec::new();
                let mut last_new: Option<usize> = None;
                for c in pending.drain(..) {
                    // The left cluster may already have been absorbed, as a
                    // right part, into the cluster formed just before.
                    let l = if nodes[c.left].alive {
                        c.left
                    } else {
                        match last_new {
                            Some(id) => id,
                            None => continue,
                        }
                    };
                    if !nodes[c.right].alive || nodes[l].next != Some(c.right) {
                        continue;
                    }
                    let id = merge(&mut nodes, l, c.right, &t, &mut join_time);
                    progress.advance(1);
                    last_new = Some(id);
                    fresh.push(id);
                }
                for &id in &fresh {
                    if !nodes[id].alive {
                        continue;
                    }
                    born_now.push(id);
                    if let Some(p) = nodes[id].prev {
                        push(&mut heap, &nodes, p, id);
                    }
                    if let Some(q) = nodes[id].next {
                        push(&mut heap, &nodes, id, q);
                    }
                }
            }
            born_now.retain(|&id| nodes[id].alive);
            born_now.sort_by_key(|&id| nodes[id].first);
            for id in born_now {
                let parts = nodes[id].born.take().unwrap_or_default();
                let (parts, part_velocities) = parts.into_iter().unzip();
                impulses.push(Impulse {
                    t: t.clone(),
                    cluster: nodes[id].cluster(),
                    parts,
                    part_velocities,
                    velocity: nodes[id].velocity(),
                    n,
                });
            }
        }
        Ok(Self::assemble(data, join_time, impulses))
    }

    /// A trajectory from a history computed elsewhere (the integer engine
    /// [`crate::fast::merge`]): `join_time` and `impulses` exactly as
    /// [`Trajectory::new`] records them. Both constructors end in
    /// [`Trajectory::assemble`]. Public but hidden for one more
    /// caller: `tests/claims_mutants.rs` builds histories tampered on
    /// purpose with it; nothing checks that the parts are consistent.
    #[doc(hidden)]
    pub fn from_parts(
        data: InitialData<S>,
        join_time: Vec<Option<S>>,
        impulses: Vec<Impulse<S>>,
    ) -> Self {
        Self::assemble(data, join_time, impulses)
    }

    /// The one place a trajectory is put together.
    fn assemble(
        data: InitialData<S>,
        join_time: Vec<Option<S>>,
        impulses: Vec<Impulse<S>>,
    ) -> Self {
        debug_assert_eq!(join_time.len(), data.n().saturating_sub(1));
        Trajectory {
            data,
            prefix: OnceLock::new(),
            join_time,
            impulses,
        }
    }

    /// The same history with every number rounded to `f64`, for pictures: the
    /// collision order and the clusters are the exact ones (computed
    /// before), each recorded number (prefix sums, join times, impulses) is
    /// rounded once, so positions evaluated from it are within a few ulps of
    /// the sums involved. O(N) once; after it, [`Trajectory::at`] and
    /// [`Trajectory::position_in`] cost f64 arithmetic instead of exact
    /// rational arithmetic (a 10⁵-particle state in milliseconds). Not for
    /// checks: the exact trajectory is the answer.
    pub fn to_f64_lossy(&self) -> Trajectory<f64> {
        let f = |v: &S| v.to_f64_lossy();
        Trajectory {
            data: self.data.to_f64_lossy(),
            prefix: OnceLock::from(Prefix {
                x: self.prefix().x.iter().map(f).collect(),
                u: self.prefix().u.iter().map(f).collect(),
            }),
            join_time: self.join_time.iter().map(|j| j.as_ref().map(f)).collect(),
            impulses: self
                .impulses
                .iter()
                .map(|i| Impulse {
                    t: f(&i.t),
                    cluster: i.cluster,
                    parts: i.parts.clone(),
                    part_velocities: i.part_velocities.iter().map(f).collect(),
                    velocity: f(&i.velocity),
                    n: i.n,
                })
                .collect(),
        }
    }

    /// The prefix sums, computed on the first call.
    fn prefix(&self) -> &Prefix<S> {
        self.prefix.get_or_init(|| prefix_sums(&self.data))
    }

    /// The initial data.
    pub fn data(&self) -> &InitialData<S> {
        &self.data
    }

    /// Every collision, sorted by time then by first particle: one
    /// [`Impulse`] per cluster formed, with its parts. These are the Dirac
    /// masses of the pressure `p = dλ/dt` (`prop:micro-pressure`).
    pub fn impulses(&self) -> &[Impulse<S>] {
        &self.impulses
    }

    /// For each pair `(j, j+1)`, the time from which particles `j` and `j+1`
    /// belong to one cluster (`Some(0)` for initial clusters, `None` if
    /// never).
    pub fn join_times(&self) -> &[Option<S>] {
        &self.join_time
    }

    /// The clusters moving together just after `t` (right-continuous: merges
    /// at `t` included).
    pub fn clusters_after(&self, t: &S) -> Vec<Cluster> {
        runs(self.data.n(), |j| {
            self.join_time[j]
                .as_ref()
                .is_some_and(|jt| jt.total_cmp(t).is_le())
        })
    }

    /// The position at `t` of particle `i` (0-based) of the block `c`, for a
    /// block that moves rigidly at `t`: a contact cluster of `x(t)`, or a part
    /// of a merge happening at `t` (its position is continuous there).
    /// `x_i = (Σ_c x̃⁰ + t Σ_c u⁰)/|c| + 2r·i` (`df:translat-x`), in O(1)
    /// from the recorded prefix sums, without building the state at `t`.
    pub fn position_in(&self, c: &Cluster, i: usize, t: &S) -> S {
        let k = S::from_usize(c.size.max(1));
        let p = self.prefix();
        let sum_x = p.x[c.end()].clone() - &p.x[c.first];
        let sum_u = p.u[c.end()].clone() - &p.u[c.first];
        (sum_x + &(t.clone() * &sum_u)) / &k + &(self.data.two_r() * &S::from_usize(i))
    }

    /// The state at time `t ≥ 0`: positions, right-derivative velocities,
    /// multipliers and contact clusters, from the recorded history.
    pub fn at(&self, t: &S) -> Result<State<S>, Error> {
        if t.total_cmp(&S::zero()).is_lt() {
            return Err(Error::NegativeTime { t: t.render() });
        }
        let n = self.data.n();
        let shifted0 = if self.prefix.get().is_some() {
            Vec::new()
        } else {
            self.data.shifted_positions()
        };
        let mut shifted = Vec::with_capacity(n);
        let mut velocities = Vec::with_capacity(n);
        for c in self.clusters_after(t) {
            let k = S::from_usize(c.size);
            // The prefix sums when they are at hand (always for the f64
            // copy, whose rounding they fix); else each cluster's own sum.
            let (sum_x, sum_u) = match self.prefix.get() {
                Some(p) => (
                    p.x[c.end()].clone() - &p.x[c.first],
                    p.u[c.end()].clone() - &p.u[c.first],
                ),
                None => (
                    tree_sum(&shifted0[c.first..c.end()]),
                    tree_sum(&self.data.velocities()[c.first..c.end()]),
                ),
            };
            let x = (sum_x + &(t.clone() * &sum_u)) / &k;
            let v = sum_u / &k;
            shifted.extend(std::iter::repeat_n(x, c.size));
            velocities.extend(std::iter::repeat_n(v, c.size));
        }
        let clusters = runs(n, |j| shifted[j] == shifted[j + 1]);
        let positions = unshift(&shifted, &self.data.two_r());
        let (multipliers, _lambda_n) = multipliers(self.data.velocities(), &velocities);
        Ok(State {
            t: t.clone(),
            positions,
            velocities,
            multipliers,
            clusters,
        })
    }

    /// The time of the last collision (`None` when nothing ever collides).
    pub fn last_collision(&self) -> Option<&S> {
        self.impulses.last().map(|i| &i.t)
    }
}

/// Merges the adjacent alive clusters `l` and `r` at time `t`; returns the new
/// cluster's id.
fn merge<S: Scalar>(
    nodes: &mut Vec<Node<S>>,
    l: usize,
    r: usize,
    t: &S,
    join_time: &mut [Option<S>],
) -> usize {
    let parts_of = |node: &mut Node<S>| -> Vec<(Cluster, S)> {
        node.born
            .take()
            .unwrap_or_else(|| vec![(node.cluster(), node.velocity())])
    };
    let mut parts = parts_of(&mut nodes[l]);
    parts.extend(parts_of(&mut nodes[r]));
    let id = nodes.len();
    let (left, right) = (&nodes[l], &nodes[r]);
    join_time[left.first + left.size - 1] = Some(t.clone());
    let node = Node {
        first: left.first,
        size: left.size + right.size,
        sum_x: left.sum_x.plus(&right.sum_x),
        sum_u: left.sum_u.plus(&right.sum_u),
        alive: true,
        prev: left.prev,
        next: right.next,
        born: Some(parts),
    };
    if let Some(p) = node.prev {
        nodes[p].next = Some(id);
    }
    if let Some(q) = node.next {
        nodes[q].prev = Some(id);
    }
    nodes[l].alive = false;
    nodes[r].alive = false;
    nodes.push(node);
    id
}

/// The times at which a trajectory is worth checking: 0, the distinct
/// collision times, the midpoint of every pair of consecutive collision
/// times, and a time after the last collision. With `limit = Some(k)`, only
/// `k` collision instants spread evenly over the history (always including
/// the first and the last) and their midpoints are kept.
pub fn probe_times<S: Scalar>(traj: &Trajectory<S>, limit: Option<usize>) -> Vec<S> {
    let mut instants: Vec<&S> = Vec::new();
    for imp in traj.impulses() {
        if instants.last() != Some(&&imp.t) {
            instants.push(&imp.t);
        }
    }
    let keep: Vec<usize> = match limit {
        Some(k) if instants.len() > k && k >= 2 => {
            let m = instants.len() - 1;
            let mut idx: Vec<usize> = (0..k).map(|j| j * m / (k - 1)).collect();
            idx.dedup();
            idx
        }
        _ => (0..instants.len()).collect(),
    };
    let mut times = vec![S::zero()];
    for &j in &keep {
        let before = if j == 0 {
            S::zero()
        } else {
            instants[j - 1].clone()
        };
        times.push((before + instants[j]) / S::from_i64(2));
        times.push(instants[j].clone());
    }
    let last = instants.last().map_or_else(S::zero, |t| (*t).clone());
    times.push(last + &S::one());
    times
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::projection::state_at;
    use num_rational::{BigRational, Rational64};

    fn q<S: Scalar>(n: i64, d: i64) -> S {
        S::from_i64(n) / S::from_i64(d)
    }

    fn three_clusters_at_once<S: Scalar>() {
        // 2r = 1. Clusters {0,1} (v = 1), {2,3,4} (v = 0), {5,6} (v = −1),
        // gaps of 1 on each side: both contacts close at t = 1.
        let x: Vec<S> = [0, 1, 3, 4, 5, 7, 8]
            .iter()
            .map(|&v| S::from_i64(v))
            .collect();
        let u: Vec<S> = [1, 1, 0, 0, 0, -1, -1]
            .iter()
            .map(|&v| S::from_i64(v))
            .collect();
        let data = InitialData::new(q::<S>(1, 2), x, u).unwrap();
        let traj = Trajectory::new(data.clone());
        assert_eq!(traj.impulses().len(), 1);
        let imp = &traj.impulses()[0];
        assert_eq!(imp.t, S::one());
        assert_eq!(imp.cluster, Cluster { first: 0, size: 7 });
        assert_eq!(
            imp.parts.iter().map(|c| c.size).collect::<Vec<_>>(),
            vec![2, 3, 2]
        );
        for t in [q(0, 1), q(1, 2), q(1, 1), q(3, 1)] {
            assert_eq!(traj.at(&t).unwrap(), state_at(&data, &t).unwrap());
        }
        // λ just after the collision equals the sum of the jumps.
        assert_eq!(traj.at(&S::one()).unwrap().multipliers, imp.jumps());
    }

    fn single_particle<S: Scalar>() {
        let data = InitialData::new(q::<S>(1, 2), vec![q(3, 1)], vec![q(-2, 1)]).unwrap();
        let traj = Trajectory::new(data.clone());
        assert!(traj.impulses().is_empty());
        let s = traj.at(&q(5, 2)).unwrap();
        assert_eq!(s.positions, vec![q(-2, 1)]);
        assert!(s.multipliers.is_empty());
        assert_eq!(s, state_at(&data, &q(5, 2)).unwrap());
    }

    /// Collisions at distinct times, the later candidates pushed before the
    /// earlier ones pop: each collision at its own time, in time order; the
    /// join time of every pair (`None`: never joined); and the state from
    /// the history equals the projection at every probe time.
    #[test]
    fn cascade_in_time_order() {
        let q = |n, d| BigRational::from_i64(n) / BigRational::from_i64(d);
        // 2r = 1. Pair (1,2) meets at 1/2; (4,5) would at 3 but the cluster
        // {1,2} (velocity 1) reaches 3 at 5/2 and {1,2,3} (velocity 2/3)
        // reaches 4 at 14/5; particle 5 runs away.
        let x = vec![q(0, 1), q(2, 1), q(5, 1), q(9, 1), q(20, 1)];
        let u = vec![q(2, 1), q(0, 1), q(0, 1), q(-1, 1), q(5, 1)];
        let data = InitialData::new(q(1, 2), x, u).unwrap();
        let traj = Trajectory::new(data.clone());
        let times: Vec<_> = traj.impulses().iter().map(|i| i.t.clone()).collect();
        assert_eq!(times, vec![q(1, 2), q(5, 2), q(14, 5)]);
        let sizes: Vec<_> = traj.impulses().iter().map(|i| i.cluster.size).collect();
        assert_eq!(sizes, vec![2, 3, 4]);
        assert_eq!(
            traj.join_times(),
            &[Some(q(1, 2)), Some(q(5, 2)), Some(q(14, 5)), None]
        );
        assert_eq!(traj.last_collision(), Some(&q(14, 5)));
        // 0, each collision instant preceded by the midpoint since the
        // previous one, and one time unit after the last.
        let probes = [
            (0, 1),
            (1, 4),
            (1, 2),
            (3, 2),
            (5, 2),
            (53, 20),
            (14, 5),
            (19, 5),
        ];
        let probes: Vec<_> = probes.iter().map(|&(n, d)| q(n, d)).collect();
        assert_eq!(probe_times(&traj, None), probes);
        // A spread of 2 instants keeps the first and the last (each with
        // the midpoint since the collision before it).
        let spread = [(0, 1), (1, 4), (1, 2), (53, 20), (14, 5), (19, 5)];
        let spread: Vec<_> = spread.iter().map(|&(n, d)| q(n, d)).collect();
        assert_eq!(probe_times(&traj, Some(2)), spread);
        // A spread needs two instants: fewer asked for means all of them.
        assert_eq!(probe_times(&traj, Some(1)), probes);
        assert_eq!(probe_times(&traj, Some(0)), probes);
        for t in probe_times(&traj, None) {
            assert_eq!(traj.at(&t).unwrap(), state_at(&data, &t).unwrap());
        }
    }

    /// The history equals the projection on random scenes (contacts and
    /// simultaneous collisions on purpose), and [`Trajectory::position_in`]
    /// gives every particle's position from its cluster's sums.
    #[test]
    fn history_is_the_projection_on_random_scenes() {
        use crate::generate::{initial_data, Limits, SplitMix64};
        let mut rng = SplitMix64::new(0x7EA5);
        let mut spreads = 0;
        for k in 0..60 {
            let limits = Limits {
                max_n: 2 + k % 12,
                max_den: 6,
                max_speed: 8,
            };
            let data = initial_data(&rng.bytes(96), limits);
            let traj = Trajectory::new(data.clone());
            let all = probe_times(&traj, None);
            // A spread of 3 instants among more: 0, three instants with their
            // midpoints, the time after — all of them probe times, the first
            // and the last instant among them.
            let instants = (all.len() - 2) / 2;
            if instants > 3 {
                let spread = probe_times(&traj, Some(3));
                assert_eq!(spread.len(), 8);
                assert!(spread.iter().all(|t| all.contains(t)));
                assert_eq!(spread[2], all[2]);
                assert_eq!(spread[6..], all[all.len() - 2..]);
                spreads += 1;
            }
            for t in all {
                let s = traj.at(&t).unwrap();
                assert_eq!(s, state_at(&data, &t).unwrap(), "scene {k}, t = {t}");
                for c in traj.clusters_after(&t) {
                    for i in c.range() {
                        assert_eq!(traj.position_in(&c, i, &t), s.positions[i]);
                    }
                }
            }
        }
        assert!(
            spreads > 5,
            "only {spreads} scenes with more than 3 collision instants"
        );
    }

    #[test]
    fn events_rational64() {
        three_clusters_at_once::<Rational64>();
        single_particle::<Rational64>();
    }
    #[test]
    fn events_bigrational() {
        three_clusters_at_once::<BigRational>();
        single_particle::<BigRational>();
    }
}
