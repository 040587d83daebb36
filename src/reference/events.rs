//! `f64` event-driven cluster merge, written the way a floating-point
//! event-driven code is written.
//!
//! The sticky dynamics (`prop:proj-micro`: perfectly inelastic collisions,
//! momentum conserved, clusters only grow) is simulated event by event:
//!
//! 1. Every cluster stores the position `x_ref` of its leftmost particle at
//!    its own reference time `t_ref` and its velocity `v`; its particles sit
//!    at `x_ref + (t − t_ref) v + 2r·k`, `k = 0 … size − 1` (touching).
//! 2. For each adjacent pair of clusters `L`, `R` with `v_L > v_R` the
//!    excess gap `e(t) = x_R(t) − x_L(t) − 2r·size_L` is evaluated at the
//!    current time `t_now` and the collision time is predicted as
//!    `t_now + e/(v_L − v_R)`. A priority queue holds the predictions.
//! 3. The earliest prediction is popped, both clusters are advanced to it
//!    and merged: velocity `(k_L v_L + k_R v_R)/(k_L + k_R)`, particles
//!    snapped to touching around the common centre of mass (which the snap
//!    preserves). The new cluster's predictions with its two neighbours are
//!    pushed.
//!
//! **Contact tolerance.** Positions computed in `f64` are only known to a
//! few `ε·X` (`X` = [`super::position_scale`], the magnitude of the
//! coordinates) and every event re-rounds them, so an exact contact may
//! show as a tiny gap or a tiny overlap. A pair of clusters that approach
//! (`v_L > v_R`) is therefore *in contact* as soon as
//!
//! `e ≤ δ = tol · X`
//!
//! and is then merged at the current time instead of at the predicted one.
//! The same rule groups near-simultaneous collisions: a pair whose own
//! collision time is within `δ/(v_L − v_R)` of the event being processed is
//! merged in the same instant — this is how three or more clusters meeting
//! at one instant (an exact tie that rounding splits) are merged together,
//! and how a negative predicted time (an overlap created by rounding) is
//! resolved. Predictions earlier than the current time are clamped to it.
//! Default `tol = 1e-12` (about 4500 ε): wide enough for the rounding of
//! hundreds of events touching one cluster, narrow enough that the timing
//! error it allows, `δ/(closing speed)`, stays far below any scale of the
//! scenes. A merge made early by `τ` moves the cluster's particles by at
//! most `τ·|v_L − v_R| ≤ δ`; since sticky dynamics conserves each cluster's
//! centre of mass, such errors do not grow afterwards.
//!
//! At `t = 0`, pairs in contact within `δ` whose velocities do not separate
//! (`u⁰_{i+1} ≤ u⁰_i`) start in one cluster; pairs in contact with
//! `u⁰_{i+1} > u⁰_i` separate (`def:velcone`).
//!
//! Collisions predicted at or before `t` are applied, so the velocities
//! returned are the right derivative at `t` (post-collision), as in the
//! exact engine.
//!
//! Reported: contact set = pairs inside one cluster; `λ` from the final
//! velocities by `eq:dyn-micro` (the generic [`crate::contact::multipliers`]
//! on `f64`); `μ` by Appendix A's formula; the pressure jump of each merge
//! (`prop:micro-pressure`): merging `L` and `R` into velocity `v` raises
//! `λ` by `(v_L − v)/N` per particle of `L` to the left of a pair and by
//! `(v − v_R)/N` per particle of `R` to its right, so the smallest jump of
//! the merge is `min((v_L − v)/N, (v − v_R)/N)` over the pairs present.

use std::cmp::Ordering;
use std::collections::BinaryHeap;

use crate::initial::InitialData;
use crate::projection::free_flight;

use super::{
    check_data, check_finite, check_positive, check_time, kkt_from_positions,
    lambda_from_velocities, position_scale, Output, Solver, SolverError, Work,
};

/// The `f64` event-driven cluster merge with a relative contact tolerance.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EventsF64 {
    /// Contact tolerance relative to the position scale `X`: approaching
    /// clusters with an excess gap `≤ tol·X` are in contact (see the module
    /// documentation).
    pub tol: f64,
}

impl Default for EventsF64 {
    /// `tol = 1e-12`.
    fn default() -> Self {
        EventsF64 { tol: 1e-12 }
    }
}

#[derive(Debug, Clone)]
struct Node {
    first: usize,
    size: usize,
    t_ref: f64,
    x_ref: f64,
    v: f64,
    prev: Option<usize>,
    next: Option<usize>,
    alive: bool,
}

impl Node {
    fn left_at(&self, t: f64) -> f64 {
        self.x_ref + (t - self.t_ref) * self.v
    }
}

#[derive(Debug, Clone, Copy)]
struct Candidate {
    t: f64,
    first: usize,
    left: usize,
    right: usize,
}

impl PartialEq for Candidate {
    fn eq(&self, other: &Self) -> bool {
        self.cmp(other) == Ordering::Equal
    }
}
impl Eq for Candidate {}
impl PartialOrd for Candidate {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}
impl Ord for Candidate {
    /// Reversed: the heap pops the earliest time, then the leftmost pair.
    fn cmp(&self, other: &Self) -> Ordering {
        other
            .t
            .total_cmp(&self.t)
            .then_with(|| other.first.cmp(&self.first))
    }
}

/// The excess gap between adjacent clusters at time `t`.
fn excess(l: &Node, r: &Node, t: f64, two_r: f64) -> f64 {
    r.left_at(t) - l.left_at(t) - two_r * l.size as f64
}

/// The predicted collision of adjacent clusters seen from `t_now`.
fn predict(l: &Node, r: &Node, t_now: f64, two_r: f64, delta: f64) -> Option<f64> {
    // Only `Greater` approaches; NaN velocities never enter the queue.
    if l.v.partial_cmp(&r.v) != Some(Ordering::Greater) {
        return None;
    }
    let e = excess(l, r, t_now, two_r);
    if e <= delta {
        Some(t_now)
    } else {
        Some(t_now + e / (l.v - r.v))
    }
}

/// Merges the adjacent alive clusters `l` and `r` at `t_now`: momentum
/// mean velocity, particles snapped to touching around the common centre of
/// mass; records the smallest pressure jump times N. `None` on overflow.
fn merge(
    nodes: &mut Vec<Node>,
    l: usize,
    r: usize,
    t_now: f64,
    two_r: f64,
    min_jump: &mut Option<f64>,
) -> Option<usize> {
    let (a, b) = (&nodes[l], &nodes[r]);
    let (ka, kb) = (a.size as f64, b.size as f64);
    let k = ka + kb;
    let v = (ka * a.v + kb * b.v) / k;
    let com_a = a.left_at(t_now) + two_r * (ka - 1.0) / 2.0;
    let com_b = b.left_at(t_now) + two_r * (kb - 1.0) / 2.0;
    let com = (ka * com_a + kb * com_b) / k;
    // λ jumps (times N): (v_L − v) per particle of L left of a pair inside
    // L, (v − v_R) inside R, k_L (v_L − v) at the junction.
    let mut jump = ka * (a.v - v);
    if a.size >= 2 {
        jump = jump.min(a.v - v);
    }
    if b.size >= 2 {
        jump = jump.min(v - b.v);
    }
    let merged = Node {
        first: a.first,
        size: a.size + b.size,
        t_ref: t_now,
        x_ref: com - two_r * (k - 1.0) / 2.0,
        v,
        prev: a.prev,
        next: b.next,
        alive: true,
    };
    if !(merged.x_ref.is_finite() && v.is_finite()) {
        return None;
    }
    *min_jump = Some(min_jump.map_or(jump, |m: f64| m.min(jump)));
    nodes[l].alive = false;
    nodes[r].alive = false;
    let id = nodes.len();
    if let Some(p) = merged.prev {
        nodes[p].next = Some(id);
    }
    if let Some(q) = merged.next {
        nodes[q].prev = Some(id);
    }
    nodes.push(merged);
    Some(id)
}

impl Solver for EventsF64 {
    fn method(&self) -> &'static str {
        "events-f64"
    }

    fn parameters(&self) -> String {
        format!("tol={:e}", self.tol)
    }

    fn solve(&self, data: &InitialData<f64>, t: f64) -> Result<Output, SolverError> {
        check_positive("tol", self.tol)?;
        check_time(t)?;
        check_data(data)?;
        let n = data.n();
        let nf = n as f64;
        let two_r = data.two_r();
        let x0 = data.positions();
        let u0 = data.velocities();
        let delta = self.tol * position_scale(data, t);

        // Initial clusters: contact within δ and velocities not separating.
        let mut nodes: Vec<Node> = Vec::with_capacity(2 * n);
        let mut i = 0;
        while i < n {
            let first = i;
            let mut momentum = u0[i];
            while i + 1 < n && (x0[i + 1] - x0[i]) - two_r <= delta && u0[i + 1] <= u0[i] {
                i += 1;
                momentum += u0[i];
            }
            let size = i + 1 - first;
            // Centre of mass of the run, particles snapped to touching.
            let com = x0[first..=i].iter().sum::<f64>() / size as f64;
            let id = nodes.len();
            nodes.push(Node {
                first,
                size,
                t_ref: 0.0,
                x_ref: com - two_r * (size as f64 - 1.0) / 2.0,
                v: momentum / size as f64,
                prev: id.checked_sub(1),
                next: None,
                alive: true,
            });
            if id > 0 {
                nodes[id - 1].next = Some(id);
            }
            i += 1;
        }

        let mut heap = BinaryHeap::new();
        let push = |heap: &mut BinaryHeap<Candidate>, nodes: &[Node], l: usize, r: usize, now| {
            if let Some(tc) = predict(&nodes[l], &nodes[r], now, two_r, delta) {
                heap.push(Candidate {
                    t: tc,
                    first: nodes[l].first,
                    left: l,
                    right: r,
                });
            }
        };
        for k in 1..nodes.len() {
            push(&mut heap, &nodes, k - 1, k, 0.0);
        }

        let mut t_now = 0.0f64;
        let mut events = 0usize;
        let mut min_jump: Option<f64> = None;
        while let Some(top) = heap.peek().copied() {
            // Collisions at or before `t` are applied (right derivative).
            if matches!(top.t.partial_cmp(&t), None | Some(Ordering::Greater)) {
                break;
            }
            heap.pop();
            let (l, r) = (top.left, top.right);
            if !(nodes[l].alive && nodes[r].alive && nodes[l].next == Some(r)) {
                continue;
            }
            t_now = t_now.max(top.t);
            let id = merge(&mut nodes, l, r, t_now, two_r, &mut min_jump)
                .ok_or(SolverError::Diverged { step: events })?;
            events += 1;
            if let Some(p) = nodes[id].prev {
                push(&mut heap, &nodes, p, id, t_now);
            }
            if let Some(q) = nodes[id].next {
                push(&mut heap, &nodes, id, q, t_now);
            }
        }

        // Contact detection at t itself: a pair predicted to meet just after
        // t, but approaching and within δ at t, is in contact at t (its
        // predicted time exceeds t only by rounding); merging it gives the
        // right derivative. One left-to-right pass handles chains.
        let mut cur = nodes.iter().position(|c| c.alive && c.prev.is_none());
        while let Some(start) = cur {
            let mut id = start;
            while let Some(p) = nodes[id].prev {
                let approaching = nodes[p].v.partial_cmp(&nodes[id].v) == Some(Ordering::Greater);
                if !approaching || excess(&nodes[p], &nodes[id], t, two_r) > delta {
                    break;
                }
                id = merge(&mut nodes, p, id, t, two_r, &mut min_jump)
                    .ok_or(SolverError::Diverged { step: events })?;
                events += 1;
            }
            cur = nodes[id].next;
        }

        // Read the state at t.
        let mut positions = Vec::with_capacity(n);
        let mut velocities = Vec::with_capacity(n);
        let mut contacts = vec![false; n.saturating_sub(1)];
        let mut cur = nodes.iter().position(|c| c.alive && c.prev.is_none());
        while let Some(id) = cur {
            let c = &nodes[id];
            let left = c.left_at(t);
            for k in 0..c.size {
                positions.push(left + two_r * k as f64);
                velocities.push(c.v);
            }
            for flag in &mut contacts[c.first..c.first + c.size - 1] {
                *flag = true;
            }
            cur = c.next;
        }
        check_finite(&positions, events)?;
        let lambda = lambda_from_velocities(u0, &velocities);
        let kkt = kkt_from_positions(&free_flight(data, &t), &positions);
        Ok(Output {
            t,
            positions,
            velocities: Some(velocities),
            contacts,
            lambda: Some(lambda),
            kkt: Some(kkt),
            min_pressure_jump: min_jump.map(|j| j / nf),
            work: Work {
                steps: events,
                iterations: 0,
                unconverged: 0,
            },
            converged: true,
            residual: 0.0,
        })
    }
}
