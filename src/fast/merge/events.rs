//! The event loop on integer cluster sums: every instant found exactly,
//! every pair meeting at it merged in one step, its join time recorded
//! (see the module documentation of [`crate::fast::merge`]; the clusters
//! formed are read off the join times, [`super::history`]).

use std::cmp::Ordering;
use std::collections::BinaryHeap;

use super::queue::{Entry, Lookahead, Near, RadixQueue, Reach, DEEP_BYTES};
use super::sums::{meeting, Node, SumWord};
use super::time::Time;

/// Particle indices, instants, join codes and offsets into the parts of
/// the impulses are `u32`: larger systems take the generic engine. (The
/// parts hold at most `3 (N − 1)` bounds: each impulse has one bound per
/// pair joining at its instant, at least one, and two ends.)
pub(super) const MAX_N: usize = (u32::MAX / 3) as usize;
/// `join` code: never joined.
pub(super) const JOIN_NEVER: u32 = u32::MAX;
/// `join` code: joined at `t = 0` (an initial cluster).
pub(super) const JOIN_ZERO: u32 = u32::MAX - 1;

/// What the event loop finds: every instant, and when each pair joins
/// (the clusters formed follow, [`super::history`]).
#[derive(Debug, Clone, Default, PartialEq)]
pub(super) struct Joins {
    /// Collision instants `(gap, closing)`, increasing.
    pub(super) instants: Vec<(i128, i128)>,
    /// For each pair `(j, j+1)`: the instant it joins, or [`JOIN_ZERO`],
    /// [`JOIN_NEVER`].
    pub(super) join: Vec<u32>,
}

/// The event loop (see the module docs); `x`, `u` satisfy the width bound.
///
/// **Finding an instant.** Every live candidate `e` has a key
/// `lo(e) ≤ t(e) ≤ hi(e)` ([`Time::lo`]). The earliest instant is found in
/// three steps:
/// 1. `e₁`, the live entry of smallest key (the first live entry of the
///    [`Lookahead`], which holds the smallest keys of the queue);
/// 2. the *window*: every live entry with `lo ≤ hi(e₁)`. It contains every
///    entry whose exact time is at most `t(e₁)` — such an entry has
///    `lo ≤ t ≤ t(e₁) ≤ hi(e₁)` — hence the earliest exact time `t*` and all
///    the pairs meeting at `t*`;
/// 3. the exact times of the window entries (recomputed from the clusters,
///    unchanged since the entry was queued since its stamp is current):
///    those equal to `t*` merge now; the others, later than `t*` but within
///    the bracket, wait in `near`, a binary heap ordered by exact time whose
///    top takes part in steps 2 and 3 (`hi` of the top bounds the window
///    too).
///
/// Both `near` and the lookahead's `early` heap (new candidates whose key
/// falls below the queue's last key) are almost always empty: they need
/// times equal to within the bracket `2^-40`.
pub(super) fn run<T: Copy + PartialEq + Into<W>, W: SumWord>(x: &[T], u: &[T]) -> Joins {
    run_touching::<T, W>(x, u, None)
}

/// [`run`], with the lookahead's reach ([`Reach`]) forced, or chosen by the
/// size of the nodes ([`DEEP_BYTES`]) when `None`. The loads only warm the
/// caches: the history is the same either way.
fn run_touching<T: Copy + PartialEq + Into<W>, W: SumWord>(
    x: &[T],
    u: &[T],
    reach: Option<Reach>,
) -> Joins {
    let n = x.len();
    // At most N − 1 merges: reserving that much costs address space only
    // (untouched pages are never mapped) and spares the copies of growth.
    let mut instants = Vec::with_capacity(n);
    let mut nodes = vec![Node::<W>::default(); n];
    // The join code of each pair `(j, j + 1)`, written once per merge: kept
    // out of the nodes, so that a node of `i64` sums is 24 bytes, not 32.
    let mut join = vec![JOIN_NEVER; n.saturating_sub(1)];
    // Initial clusters: contacts with equal velocities.
    let mut first = 0usize;
    for j in 0..n {
        if j + 1 == n || x[j] != x[j + 1] || u[j] != u[j + 1] {
            let (mut sx, mut su) = (W::default(), W::default());
            for i in first..=j {
                sx += x[i].into();
                su += u[i].into();
            }
            for end in [first, j] {
                let node = &mut nodes[end];
                node.sum_x = sx;
                node.sum_u = su;
                node.size = (j + 1 - first) as u32;
            }
            for code in &mut join[first..j] {
                *code = JOIN_ZERO;
            }
            first = j + 1;
        }
    }
    // The exact time of the pair at a live boundary `b`, if it approaches.
    let time_of = |nodes: &[Node<W>], b: usize| meeting(&nodes[b - 1], &nodes[b]);
    // The low byte of every stamp, in a compact array (one byte a particle
    // stays in cache where the nodes do not): most stale entries are
    // rejected here; a matching byte is confirmed by the full stamp.
    let mut tags = vec![0u8; n];
    let mut queue = RadixQueue::new();
    let mut near: BinaryHeap<Near> = BinaryHeap::new();
    let mut b = nodes.first().map_or(n, |node| node.size as usize);
    while b < n {
        if let Some(t) = time_of(&nodes, b) {
            queue.push(Entry {
                key: t.lo(),
                slot: b as u32,
                stamp: 0,
            });
        }
        b += nodes[b].size as usize;
    }

    let mut ahead = Lookahead {
        reach: reach.unwrap_or(if std::mem::size_of_val(nodes.as_slice()) > DEEP_BYTES {
            Reach::OuterEnds
        } else {
            Reach::Boundary
        }),
        ..Lookahead::default()
    };
    let mut window: Vec<(Entry, Time)> = Vec::new();
    let mut pending: Vec<u32> = Vec::new();
    let mut fresh: Vec<u32> = Vec::new();
    loop {
        let live = |nodes: &[Node<W>], tags: &[u8], e: &Entry| {
            tags[e.slot as usize] == e.stamp as u8 && nodes[e.slot as usize].stamp == e.stamp
        };
        while near.peek().is_some_and(|w| !live(&nodes, &tags, &w.entry)) {
            near.pop();
        }
        // 1. The first live entry of the queue (smallest `lo`).
        window.clear();
        while let Some(e) = ahead.take_le(&mut queue, u64::MAX, &nodes, &tags) {
            if live(&nodes, &tags, &e) {
                if let Some(t) = time_of(&nodes, e.slot as usize) {
                    window.push((e, t));
                    break;
                }
            }
        }
        // 2. An upper bound of the earliest time `t*`, and every queued
        //    entry whose `lo` is below it.
        let bound = match (window.first(), near.peek()) {
            (None, None) => break,
            (Some(w), None) => w.1.hi(),
            (None, Some(m)) => m.t.hi(),
            (Some(w), Some(m)) => w.1.hi().min(m.t.hi()),
        };
        while let Some(e) = ahead.take_le(&mut queue, bound, &nodes, &tags) {
            if live(&nodes, &tags, &e) {
                if let Some(t) = time_of(&nodes, e.slot as usize) {
                    window.push((e, t));
                }
            }
        }
        // 3. `t*` exactly; the later window entries wait in `near`. (The
        //    usual window is one entry and `near` is empty: nothing to
        //    compare.)
        pending.clear();
        let t = match (window.as_slice(), near.peek()) {
            ([(entry, t)], None) => {
                pending.push(entry.slot);
                *t
            }
            _ => {
                let mut t = match (window.first(), near.peek()) {
                    (Some(w), _) => w.1,
                    (None, Some(m)) => m.t,
                    (None, None) => break,
                };
                for tw in window.iter().map(|w| &w.1).chain(near.peek().map(|m| &m.t)) {
                    if tw.cmp(&t) == Ordering::Less {
                        t = *tw;
                    }
                }
                for &(entry, tw) in &window {
                    if tw.cmp(&t) == Ordering::Greater {
                        near.push(Near { t: tw, entry });
                    } else {
                        pending.push(entry.slot);
                    }
                }
                while let Some(m) = near.peek() {
                    if live(&nodes, &tags, &m.entry) {
                        if m.t.cmp(&t) == Ordering::Greater {
                            break;
                        }
                        pending.push(m.entry.slot);
                    }
                    near.pop();
                }
                t
            }
        };
        let instant = instants.len() as u32;
        instants.push((t.gap, t.closing));
        fresh.clear();
        while !pending.is_empty() {
            // Left to right: a chain of pairs meeting at `t` becomes one
            // cluster (the left part of a later pair may have been formed
            // earlier in this loop; it ends at the boundary all the same).
            pending.sort_unstable();
            let batch = fresh.len();
            for &r in &pending {
                let ri = r as usize;
                let (left, right) = (nodes[ri - 1], nodes[ri]);
                if left.size == 0 || right.size == 0 {
                    continue;
                }
                // Merge `f .. r` and `r .. e`; the boundary `r` is gone.
                let f = ri - left.size as usize;
                let e = ri + right.size as usize;
                join[ri - 1] = instant;
                nodes[ri].stamp = nodes[ri].stamp.wrapping_add(1);
                tags[ri] = nodes[ri].stamp as u8;
                if ri - 1 != f {
                    nodes[ri - 1].size = 0;
                }
                if ri != e - 1 {
                    nodes[ri].size = 0;
                }
                let (sx, su) = (left.sum_x + right.sum_x, left.sum_u + right.sum_u);
                for end in [f, e - 1] {
                    let node = &mut nodes[end];
                    node.sum_x = sx;
                    node.sum_u = su;
                    node.size = left.size + right.size;
                }
                fresh.push(f as u32);
            }
            pending.clear();
            // New candidates on both sides of every cluster formed. One
            // meeting at `t` or before would join this instant, as in
            // `Trajectory::new` (it cannot happen with exact times).
            for k in batch..fresh.len() {
                let f = fresh[k] as usize;
                if nodes[f].size == 0 || (k > batch && fresh[k - 1] == fresh[k]) {
                    continue;
                }
                let e = f + nodes[f].size as usize;
                for b in [f, e] {
                    if b == 0 || b >= n {
                        continue;
                    }
                    let stamp = nodes[b].stamp.wrapping_add(1);
                    nodes[b].stamp = stamp;
                    tags[b] = stamp as u8;
                    let Some(tb) = time_of(&nodes, b) else {
                        continue;
                    };
                    let entry = Entry {
                        key: tb.lo(),
                        slot: b as u32,
                        stamp,
                    };
                    if tb.cmp(&t) != Ordering::Greater {
                        pending.push(b as u32);
                        nodes[b].stamp = stamp.wrapping_add(1);
                        tags[b] = nodes[b].stamp as u8;
                    } else if entry.key >= queue.last {
                        queue.push(entry);
                    } else {
                        ahead.insert(entry);
                    }
                }
            }
            pending.sort_unstable();
            pending.dedup();
        }
    }
    instants.shrink_to_fit();
    Joins { instants, join }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fast::scaling::scale_i128;
    use crate::generate::{initial_data, Limits, SplitMix64};

    #[test]
    fn the_second_wave_of_loads_changes_nothing() {
        // Below DEEP_BYTES the outer ends are not touched; forced on, on
        // small scenes (contacts, chains, clusters of every size, the two
        // ends of the line), the loads stay in bounds and the history is
        // the same.
        let mut rng = SplitMix64::new(31);
        for k in 0..120 {
            let data = initial_data(
                &rng.bytes(500),
                Limits {
                    max_n: 1 + k % 90,
                    max_den: 1 + (k % 3) as u32,
                    max_speed: 1 + (k % 6) as u32,
                },
            );
            let Some(s) = scale_i128(&data) else {
                continue;
            };
            let plain = run_touching::<i128, i128>(&s.x, &s.u, Some(Reach::Boundary));
            let deep = run_touching::<i128, i128>(&s.x, &s.u, Some(Reach::OuterEnds));
            assert_eq!(plain, deep, "scene {k}");
            assert_eq!(plain, run::<i128, i128>(&s.x, &s.u), "scene {k}");
        }
    }
}
