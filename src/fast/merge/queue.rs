//! The event queue: a monotone radix queue keyed by a lower bound of each
//! candidate's time, lazy deletion by stamps, and the lookahead that takes
//! entries out 16 at a time so that the cache misses of coming events
//! overlap.

use std::cmp::Ordering;
use std::collections::BinaryHeap;

use super::sums::Node;
use super::time::Time;

/// A queued candidate: the lower bound of its time ([`Time::lo`]), its
/// boundary, and the stamp the boundary had when it was queued (the entry is
/// stale once the stamp moved on).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub(super) struct Entry {
    pub(super) key: u64,
    pub(super) slot: u32,
    pub(super) stamp: u32,
}

/// An entry set aside with its exact time, in a max-heap reversed to pop the
/// earliest exact time first (then the leftmost boundary).
#[derive(Debug, Clone, Copy)]
pub(super) struct Near {
    pub(super) t: Time,
    pub(super) entry: Entry,
}

impl PartialEq for Near {
    fn eq(&self, other: &Self) -> bool {
        self.cmp(other) == Ordering::Equal
    }
}
impl Eq for Near {}
impl PartialOrd for Near {
    fn partial_cmp(&self, other: &Self) -> Option<std::cmp::Ordering> {
        Some(self.cmp(other))
    }
}
impl Ord for Near {
    fn cmp(&self, other: &Self) -> Ordering {
        other
            .t
            .cmp(&self.t)
            .then_with(|| other.entry.slot.cmp(&self.entry.slot))
    }
}

/// A monotone radix queue (a radix heap, Ahuja, Mehlhorn, Orlin and Tarjan,
/// with base-16 digits) on 64-bit keys: no key below the last one taken out
/// may be pushed. A key equal to `last` waits in bucket 0; any other key in
/// the bucket of the highest hexadecimal digit where it differs from
/// `last`, and of its value of that digit. Pushes append; a pop empties the
/// lowest non-empty bucket into lower ones, so an entry moves at most 16
/// times and all accesses are sequential: the event loop's queue touches
/// memory in order, only the clusters are visited at random.
#[derive(Debug)]
pub(super) struct RadixQueue {
    pub(super) buckets: Vec<Vec<Entry>>,
    /// The smallest key of each non-empty bucket.
    pub(super) min: Vec<u64>,
    /// Bit `i % 64` of word `i / 64` set iff bucket `i` is non-empty.
    pub(super) occupied: [u64; 5],
    pub(super) last: u64,
}

/// Buckets of a [`RadixQueue`]: bucket 0, then 16 digits for each of the 16
/// digit positions.
pub(super) const BUCKETS: usize = 1 + 16 * 16;

impl RadixQueue {
    pub(super) fn new() -> Self {
        RadixQueue {
            buckets: (0..BUCKETS).map(|_| Vec::new()).collect(),
            min: vec![u64::MAX; BUCKETS],
            occupied: [0; 5],
            last: 0,
        }
    }

    #[inline]
    pub(super) fn bucket(&self, key: u64) -> usize {
        let x = key ^ self.last;
        if x == 0 {
            return 0;
        }
        let level = (63 - x.leading_zeros()) / 4;
        1 + 16 * level as usize + ((key >> (4 * level)) & 15) as usize
    }

    /// Queues `e`; `e.key ≥ last` is the caller's duty.
    #[inline]
    pub(super) fn push(&mut self, e: Entry) {
        debug_assert!(e.key >= self.last);
        let b = self.bucket(e.key);
        self.buckets[b].push(e);
        self.min[b] = self.min[b].min(e.key);
        self.occupied[b / 64] |= 1 << (b % 64);
    }

    /// The lowest non-empty bucket.
    pub(super) fn lowest(&self) -> Option<usize> {
        self.occupied
            .iter()
            .enumerate()
            .find(|(_, w)| **w != 0)
            .map(|(i, w)| 64 * i + w.trailing_zeros() as usize)
    }

    /// Takes out an entry of the smallest key if that key is at most
    /// `bound`. `last` never moves beyond `bound`, so that new keys down to
    /// the current instant can still be pushed.
    pub(super) fn pop_if_le(&mut self, bound: u64) -> Option<Entry> {
        let i = self.lowest()?;
        if i != 0 {
            if self.min[i] > bound {
                return None;
            }
            let mut moved = std::mem::take(&mut self.buckets[i]);
            self.occupied[i / 64] &= !(1 << (i % 64));
            self.last = self.min[i];
            self.min[i] = u64::MAX;
            for e in moved.drain(..) {
                self.push(e);
            }
            // Keep the allocation for later.
            self.buckets[i] = moved;
        }
        if self.last > bound {
            return None;
        }
        let e = self.buckets[0].pop();
        if self.buckets[0].is_empty() {
            self.occupied[0] &= !1;
            self.min[0] = u64::MAX;
        }
        e
    }
}

/// Above this many bytes of nodes the lookahead also touches the outer ends
/// of the clusters ([`Reach::OuterEnds`]): the extra loads pay only when
/// the nodes miss the caches (the measurements that set it:
/// docs/guide/performance.md).
pub(super) const DEEP_BYTES: usize = 4 << 20;

/// How many queued entries are taken out ahead of time.
pub(super) const AHEAD: usize = 16;

/// The next [`AHEAD`] entries of the queue, taken out in key order so that
/// their nodes are loaded together: the cache misses of the coming events
/// overlap instead of following one another. Every key still in the queue
/// is at least as large as these; a new entry whose key is below the
/// queue's `last` goes to the small heap `early` instead, and the smaller
/// of the two fronts comes first.
#[derive(Debug, Default)]
pub(super) struct Lookahead {
    pub(super) entries: std::collections::VecDeque<Entry>,
    pub(super) early: BinaryHeap<std::cmp::Reverse<Entry>>,
    /// Which nodes a refill touches.
    pub(super) reach: Reach,
}

/// Which nodes [`Lookahead::refill`] loads ahead of time (the loads only
/// warm the caches: the history is the same either way).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub(super) enum Reach {
    /// The two nodes at each boundary taken out.
    #[default]
    Boundary,
    /// Also the outer ends of the two clusters (worth it only when the
    /// nodes do not fit in the caches, [`DEEP_BYTES`]).
    OuterEnds,
}

impl Lookahead {
    /// The entry of smallest key if that key is at most `bound`.
    #[inline]
    pub(super) fn take_le<W>(
        &mut self,
        queue: &mut RadixQueue,
        bound: u64,
        nodes: &[Node<W>],
        tags: &[u8],
    ) -> Option<Entry> {
        if self.entries.is_empty() {
            self.refill(queue, nodes, tags);
        }
        let front = self.entries.front().map(|e| e.key);
        match self.early.peek() {
            Some(std::cmp::Reverse(e)) if e.key <= bound && front.is_none_or(|k| e.key < k) => {
                self.early.pop().map(|r| r.0)
            }
            _ if front.is_some_and(|k| k <= bound) => self.entries.pop_front(),
            _ => None,
        }
    }

    pub(super) fn refill<W>(&mut self, queue: &mut RadixQueue, nodes: &[Node<W>], tags: &[u8]) {
        let mut touched = 0u32;
        while self.entries.len() < AHEAD {
            let Some(e) = queue.pop_if_le(u64::MAX) else {
                break;
            };
            // Independent loads: the processor keeps them all in flight.
            let b = e.slot as usize;
            touched ^= u32::from(tags[b]) ^ nodes[b].stamp ^ nodes[b - 1].size;
            self.entries.push_back(e);
        }
        // Second wave: the outer ends of the two clusters, which the merge
        // at `b` rewrites and whose neighbours it reads (stale entries touch
        // harmless places).
        let n = nodes.len();
        for e in self
            .entries
            .iter()
            .filter(|_| self.reach == Reach::OuterEnds)
        {
            let b = e.slot as usize;
            let f = b.saturating_sub(nodes[b - 1].size as usize);
            let end = (b + nodes[b].size as usize).min(n);
            touched ^= nodes[f.saturating_sub(1)].size
                ^ nodes[f].stamp
                ^ nodes[end - 1].size
                ^ nodes[end.min(n - 1)].stamp;
        }
        std::hint::black_box(touched);
    }

    /// Sets aside an entry whose key is below the queue's `last`.
    pub(super) fn insert(&mut self, e: Entry) {
        self.early.push(std::cmp::Reverse(e));
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fast::merge::time::KEY_SHIFT;
    use crate::generate::SplitMix64;
    use num_bigint::BigInt;
    use num_rational::BigRational;

    #[test]
    fn radix_queue_pops_in_key_order() {
        let mut rng = SplitMix64::new(5);
        let mut queue = RadixQueue::new();
        let mut model: Vec<u64> = Vec::new();
        let mut popped = Vec::new();
        for round in 0..200 {
            for k in 0..(round % 7) {
                // Keys at or above the last one taken out, some equal to it.
                let key = if k % 3 == 0 {
                    queue.last
                } else {
                    queue.last + (rng.next_u64() >> (rng.next_u64() % 64))
                };
                queue.push(Entry {
                    key,
                    slot: k as u32,
                    stamp: 0,
                });
                model.push(key);
            }
            model.sort_unstable();
            let bound = model.first().map_or(0, |&m| m + (rng.next_u64() % 4));
            while let Some(e) = queue.pop_if_le(bound) {
                assert_eq!(Some(e.key), model.first().copied());
                model.remove(0);
                popped.push(e.key);
            }
            assert!(model.first().is_none_or(|&m| m > bound));
        }
        while let Some(e) = queue.pop_if_le(u64::MAX) {
            assert_eq!(e.key, model.remove(0));
            popped.push(e.key);
        }
        assert!(model.is_empty());
        assert!(popped.windows(2).all(|w| w[0] <= w[1]));
        assert!(popped.len() > 300);
        // The bracket: lo ≤ exact time ≤ hi, also where f64 cannot tell
        // neighbouring times apart.
        for (gap, closing) in [
            (0i128, 1i128),
            (1 << 100, 3),
            ((1 << 100) + 1, 3),
            (7, 1 << 90),
            // t = 2^63 − 2^10 + 1 rounds down to τ = 2^63 − 2^10, the top
            // double of its key (its low 12 bits are ones): `hi` must still
            // reach above t.
            ((1 << 63) - (1 << 10) + 1, 1),
        ] {
            let t = Time::new(gap, closing);
            let exact = BigRational::new(BigInt::from(gap), BigInt::from(closing));
            assert!(BigRational::from_float(f64::from_bits(t.lo() << KEY_SHIFT)).unwrap() <= exact);
            let above = f64::from_bits(((t.hi() + 1) << KEY_SHIFT) - 1);
            assert!(BigRational::from_float(above).unwrap() >= exact);
            assert!(t.lo() <= t.hi());
        }
    }
}
