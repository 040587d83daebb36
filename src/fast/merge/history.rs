//! The history of the clusters formed, read off the join codes of the
//! pairs: the event loops and the repair at the cuts only say *when* each
//! pair `(j, j + 1)` joins; which clusters formed at each instant, and
//! from which parts, follows from that alone.
//!
//! **Why the join times are enough.** Clusters only grow
//! (`prop:proj-micro`: the blocks of the isotonic regression at `t` are
//! unions of those at any earlier time), and two adjacent particles stay
//! together once joined, so at time `t` the clusters are the maximal runs
//! of particles whose pairs have all joined by `t`. A cluster `C` is
//! formed at `t` iff it holds a pair that joins at `t`; `C` then runs from
//! the nearest pair on the left to the nearest pair on the right that join
//! after `t` (or never), and its pre-collision parts are split exactly at
//! its pairs that join at `t`. Two pairs joining at `t` are in the same
//! cluster iff no pair between them joins later.
//!
//! **One scan.** With a stack of pairs whose join times do not increase
//! upwards, scanned left to right, the pairs popped by a later-joining pair
//! `r` are those whose nearest later pair on the right is `r`; a run of
//! equal times at the top of the stack is one cluster, whose nearest later
//! pair on the left is the entry below it. The scan finds every cluster
//! formed, at every instant, in `O(N)`; each instant's clusters come out
//! left to right. Two scans place them: the first counts the impulses and
//! parts of every instant, the second writes each where it belongs
//! (impulses by instant, then first particle, as
//! [`Trajectory::impulses`](crate::trajectory::Trajectory::impulses)).
//!
//! **Two stretches.** The pairs are cut at `mid` and the two stretches
//! scanned at once (two threads from [`TWO_MIN`] pairs). The left one
//! leaves on its stack the pairs whose nearest later pair lies beyond the
//! cut; the right one does not know what lies left of it, so whenever its
//! stack runs empty it records the pair that emptied it, with the run of
//! equal times it popped from the bottom (a cluster whose left end lies
//! further left). Replaying those records on the left stretch's stack is
//! exactly what one scan of the whole would do there, and settles the
//! clusters that cross the cut. Every such cluster holds particle `mid`,
//! so there is at most one per instant, and it comes after the left
//! stretch's clusters of that instant and before the right one's: each
//! instant's impulses stay in the order of their first particles.

use std::sync::atomic::{AtomicU32, AtomicU64, Ordering::Relaxed};

use super::events::{Joins, JOIN_NEVER, JOIN_ZERO};
use crate::fast::scaling::{both, Cores};

/// From this many pairs the clusters are read on two threads.
pub(super) const TWO_MIN: usize = 1 << 15;

/// The history found by the integer engine, before conversion.
#[derive(Debug, Clone, Default, PartialEq)]
pub(super) struct History {
    /// Distinct collision instants `(gap, closing)`, increasing.
    pub(super) instants: Vec<(i128, i128)>,
    /// One entry per cluster formed: `(instant, offset into parts)`.
    pub(super) impulses: Vec<(u32, u32)>,
    /// For each impulse, the first particle of each part, left to right,
    /// then one past the cluster's last particle.
    pub(super) parts: Vec<u32>,
    /// For each pair `(j, j+1)`: the instant it joins, or [`JOIN_ZERO`],
    /// [`JOIN_NEVER`].
    pub(super) join: Vec<u32>,
}

/// A join code as a key in time order: `t = 0` first, then the instants,
/// never last.
#[inline]
fn key(code: u32) -> u32 {
    match code {
        JOIN_ZERO => 0,
        JOIN_NEVER => u32::MAX,
        k => k + 1,
    }
}

/// A stack entry: `(key, pair)`.
type Entry = (u32, u32);

/// What the right stretch leaves to the left one: the pair of key `key`
/// found the stack empty, and one past it is `end`; `runs[from..to]` is the
/// run of equal keys it popped from the bottom, if any.
#[derive(Debug, Clone, Copy)]
struct Open {
    key: u32,
    end: u32,
    from: usize,
    to: usize,
}

/// Pops from `stack` every run of keys below `k`, calling
/// `formed(instant, first, pairs, end)` on each that is a cluster formed
/// (not an initial one, key 0); `floor` is the first particle after the
/// last pair that never joins. With `floor` unknown (`None`, a stretch
/// that does not start the line) the bottom run stays on the stack: its
/// cluster's left end lies further left.
#[inline]
fn pop_below(
    stack: &mut Vec<Entry>,
    k: u32,
    floor: Option<u32>,
    end: u32,
    formed: &mut impl FnMut(usize, u32, &[Entry], u32),
) {
    while let Some(&(top, _)) = stack.last() {
        if top >= k {
            break;
        }
        let start = run_start(stack, top);
        let first = match (start, floor) {
            (0, None) => break,
            (0, Some(f)) => f,
            (s, _) => stack[s - 1].1 + 1,
        };
        if top > 0 {
            formed((top - 1) as usize, first, &stack[start..], end);
        }
        stack.truncate(start);
    }
}

/// Where the run of key `top` at the top of `stack` begins.
#[inline]
fn run_start(stack: &[Entry], top: u32) -> usize {
    let mut start = stack.len();
    while start > 0 && stack[start - 1].0 == top {
        start -= 1;
    }
    start
}

/// Where the line ends, for a stretch of pairs [`scan`] reads.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum LineEnd {
    /// At the stretch's end: every cluster open there closes.
    Here,
    /// Beyond it: the open clusters are returned (its stack).
    Beyond,
}

/// Scans the stretch `join` of pairs `base..` (see the module docs),
/// calling `formed(instant, first, pairs, end)` on every cluster formed
/// that it settles alone: it runs over particles `first..end` and its
/// pairs `(key, j)` joining at `instant` are `pairs`, left to right. The
/// clusters of one instant come left to right. Each code is replaced by
/// `relabel(code)` once read.
///
/// A stretch that starts the line (`base = 0`) settles everything on its
/// left; one that does not calls `open(key, end, run)` whenever its stack
/// runs empty before its first pair that never joins. A stretch that ends
/// the line closes every cluster at its end; one that does not returns its
/// stack. Also returned: the first particle after its last pair that never
/// joins (`base` if none).
fn scan(
    join: &mut [u32],
    base: u32,
    end: LineEnd,
    relabel: impl Fn(u32) -> u32,
    mut formed: impl FnMut(usize, u32, &[Entry], u32),
    mut open: impl FnMut(u32, u32, &[Entry]),
) -> (Vec<Entry>, u32) {
    // Entries `(key, j)`, keys not increasing upwards.
    let mut stack: Vec<Entry> = Vec::new();
    // The first particle after the last pair that never joins: unknown
    // left of a stretch that does not start the line.
    let mut floor = (base == 0).then_some(0);
    let len = join.len();
    for i in 0..len + usize::from(end == LineEnd::Here) {
        let r = base + i as u32;
        // Past the last pair, a pair that never joins closes every cluster.
        let k = join.get_mut(i).map_or(u32::MAX, |c| {
            let k = key(*c);
            *c = relabel(*c);
            k
        });
        pop_below(&mut stack, k, floor, r + 1, &mut formed);
        // Left with nothing, or with a bottom run that `k` closes: what
        // lies left of the stretch is the left one's to settle.
        if floor.is_none() && stack.last().is_none_or(|&(top, _)| top < k) {
            open(k, r + 1, &stack);
            stack.clear();
        }
        if k == u32::MAX {
            floor = Some(r + 1);
        } else {
            stack.push((k, r));
        }
    }
    (stack, floor.unwrap_or(base))
}

/// A cluster that crosses the cut: `instant`, `first`, `end`, and its
/// pairs `pairs[from..to]`.
type Crossing = (usize, u32, u32, usize, usize);

/// Replays the right stretch's records `opens` (pairs of `runs`) on the
/// left stretch's `stack` and `floor`: the clusters that cross the cut,
/// their pairs in `pairs`.
fn settle(
    mut stack: Vec<Entry>,
    floor: u32,
    opens: &[Open],
    runs: &[Entry],
    pairs: &mut Vec<Entry>,
) -> Vec<Crossing> {
    let mut out = Vec::new();
    let mut record = |g: usize, first: u32, run: &[Entry], end: u32| {
        let from = pairs.len();
        pairs.extend_from_slice(run);
        out.push((g, first, end, from, pairs.len()));
    };
    for o in opens {
        let run = &runs[o.from..o.to];
        if let Some(&(top, _)) = run.first() {
            // The right stretch's bottom run goes on with the left one's
            // top run of the same key, if any (keys below were popped).
            let start = run_start(&stack, top);
            if top > 0 {
                let first = match start {
                    0 => floor,
                    s => stack[s - 1].1 + 1,
                };
                let mut all = stack[start..].to_vec();
                all.extend_from_slice(run);
                record((top - 1) as usize, first, &all, o.end);
            }
            stack.truncate(start);
        }
        pop_below(&mut stack, o.key, Some(floor), o.end, &mut record);
    }
    out
}

/// Writes the clusters formed into `impulses` and `parts` at the places
/// `at` (advanced), instants numbered by `rank`.
struct Place<'a> {
    at: &'a mut [(u32, u32)],
    rank: &'a [u32],
    impulses: &'a [AtomicU64],
    parts: &'a [AtomicU32],
}

impl Place<'_> {
    #[inline]
    fn write(&mut self, g: usize, first: u32, pairs: &[Entry], end: u32) {
        let (k, p) = self.at[g];
        let packed = u64::from(self.rank[g]) << 32 | u64::from(p);
        self.impulses[k as usize].store(packed, Relaxed);
        let out = &self.parts[p as usize..p as usize + pairs.len() + 2];
        out[0].store(first, Relaxed);
        for (o, &(_, j)) in out[1..].iter().zip(pairs) {
            o.store(j + 1, Relaxed);
        }
        out[pairs.len() + 1].store(end, Relaxed);
        self.at[g] = (k + 1, p + pairs.len() as u32 + 2);
    }
}

/// Counts the impulse and the parts of a cluster formed at `g`.
#[inline]
fn count(at: &mut [(u32, u32)], g: usize, pairs: &[Entry]) {
    at[g].0 += 1;
    at[g].1 += pairs.len() as u32 + 2;
}

impl History {
    /// The history whose pairs join as `joins` says (see the module docs):
    /// on two threads from [`TWO_MIN`] pairs. The instants at which no
    /// pair joins are dropped (a repaired half keeps the instants of
    /// clusters the run took in), and the codes renumbered.
    pub(super) fn from_joins(joins: Joins) -> History {
        let pairs = joins.join.len();
        match Cores::from_size(pairs, TWO_MIN) {
            Cores::Two => History::from_stretches(joins, pairs / 2, Cores::Two),
            Cores::One => History::from_stretches(joins, pairs, Cores::One),
        }
    }

    /// [`History::from_joins`], the pairs cut at `mid ≤ len`, the two
    /// stretches on `cores`.
    fn from_stretches(joins: Joins, mid: usize, cores: Cores) -> History {
        let Joins {
            mut instants,
            mut join,
        } = joins;
        let len = instants.len();
        let base = mid as u32;
        // 1. The impulses and parts of every instant counted, on each
        //    side (one place per instant: one cache line touched per
        //    cluster); what the right stretch leaves open recorded.
        let (left, right) = join.split_at_mut(mid);
        let ((stack, floor, mut at_l), (opens, runs, mut at_r)) = both(
            cores,
            || {
                let mut at = vec![(0u32, 0u32); len];
                let (stack, floor) = scan(
                    left,
                    0,
                    LineEnd::Beyond,
                    |c| c,
                    |g, _, p, _| count(&mut at, g, p),
                    |_, _, _| {},
                );
                (stack, floor, at)
            },
            || {
                let mut at = vec![(0u32, 0u32); len];
                let (mut opens, mut runs) = (Vec::new(), Vec::new());
                scan(
                    right,
                    base,
                    LineEnd::Here,
                    |c| c,
                    |g, _, p, _| count(&mut at, g, p),
                    |key, end, run| {
                        let from = runs.len();
                        runs.extend_from_slice(run);
                        opens.push(Open {
                            key,
                            end,
                            from,
                            to: runs.len(),
                        });
                    },
                );
                (opens, runs, at)
            },
        );
        // The clusters across the cut, counted with the left side's (they
        // come after them in their instants).
        let mut crossing_pairs = Vec::new();
        let crossing = settle(stack, floor, &opens, &runs, &mut crossing_pairs);
        for &(g, _, _, from, to) in &crossing {
            count(&mut at_l, g, &crossing_pairs[from..to]);
        }
        // Then where each instant's first impulse and part go on each
        // side, and the rank of every instant used.
        let mut rank = vec![JOIN_NEVER; len];
        let (mut impulse_count, mut part_count, mut used) = (0u32, 0u32, 0u32);
        for ((l, r), rk) in at_l.iter_mut().zip(&mut at_r).zip(&mut rank) {
            if l.0 + r.0 > 0 {
                *rk = used;
                used += 1;
            }
            let (a, b) = (*l, *r);
            *l = (impulse_count, part_count);
            *r = (impulse_count + a.0, part_count + a.1);
            impulse_count += a.0 + b.0;
            part_count += a.1 + b.1;
        }
        // 2. Every cluster written where it belongs, on each side; the
        //    codes renumbered on the way when an instant is dropped.
        let impulses: Vec<AtomicU64> = (0..impulse_count).map(|_| AtomicU64::new(0)).collect();
        let parts: Vec<AtomicU32> = (0..part_count).map(|_| AtomicU32::new(0)).collect();
        let all_used = used as usize == len;
        let relabel = |c: u32| match c {
            JOIN_NEVER | JOIN_ZERO => c,
            g if all_used => g,
            g => rank[g as usize],
        };
        let (left, right) = join.split_at_mut(mid);
        let mut place_l = Place {
            at: &mut at_l,
            rank: &rank,
            impulses: &impulses,
            parts: &parts,
        };
        let mut place_r = Place {
            at: &mut at_r,
            rank: &rank,
            impulses: &impulses,
            parts: &parts,
        };
        both(
            cores,
            || {
                scan(
                    left,
                    0,
                    LineEnd::Beyond,
                    relabel,
                    |g, f, p, e| place_l.write(g, f, p, e),
                    |_, _, _| {},
                );
                for &(g, first, end, from, to) in &crossing {
                    place_l.write(g, first, &crossing_pairs[from..to], end);
                }
            },
            || {
                scan(
                    right,
                    base,
                    LineEnd::Here,
                    relabel,
                    |g, f, p, e| place_r.write(g, f, p, e),
                    |_, _, _| {},
                );
            },
        );
        if !all_used {
            let mut g = 0;
            instants.retain(|_| {
                g += 1;
                rank[g - 1] != JOIN_NEVER
            });
        }
        // Freed before the impulses are copied out of their atomics (the
        // peak of memory is the second pass).
        drop((at_l, at_r, rank));
        History {
            instants,
            impulses: impulses
                .into_iter()
                .map(|a| {
                    let v = a.into_inner();
                    ((v >> 32) as u32, v as u32)
                })
                .collect(),
            parts: parts.into_iter().map(AtomicU32::into_inner).collect(),
            join,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The clusters formed, by brute force from the definition: at each
    /// instant `g`, the maximal runs of pairs joined by `g` holding a pair
    /// joined at `g`.
    fn brute(join: &[u32], instants: usize) -> Vec<(usize, Vec<u32>)> {
        let n = join.len() + 1;
        let mut out = Vec::new();
        for g in 0..instants as u32 {
            // Joined by `g`: at `t = 0` or at an instant up to `g` (written
            // out here, not through `key`, which the scan uses).
            let by = |j: usize| join[j] == JOIN_ZERO || join[j] <= g;
            let mut first = 0;
            while first < n {
                let mut end = first + 1;
                while end < n && by(end - 1) {
                    end += 1;
                }
                let at: Vec<usize> = (first..end - 1).filter(|&j| join[j] == g).collect();
                if !at.is_empty() {
                    let mut parts = vec![first as u32];
                    parts.extend(at.iter().map(|&j| j as u32 + 1));
                    parts.push(end as u32);
                    out.push((g as usize, parts));
                }
                first = end;
            }
        }
        out
    }

    #[test]
    fn every_join_pattern_of_small_lines() {
        // Every assignment of codes {never, zero, 0, 1, 2} to up to 6 pairs
        // (5^6 = 15,625 lines), cut at every place: the scan finds the
        // brute-force clusters, and the unused instants are dropped.
        let codes = [JOIN_NEVER, JOIN_ZERO, 0, 1, 2];
        for pairs in 0..=6u32 {
            for pattern in 0..5usize.pow(pairs) {
                let mut w = pattern;
                let join: Vec<u32> = (0..pairs)
                    .map(|_| {
                        let c = codes[w % 5];
                        w /= 5;
                        c
                    })
                    .collect();
                let instants: Vec<(i128, i128)> = (1..=3).map(|t| (t, 1)).collect();
                // Expected: brute force, then the unused instants dropped.
                let want = brute(&join, 3);
                let used: Vec<u32> = (0..3u32).filter(|g| join.contains(g)).collect();
                let rank = |g: u32| used.iter().position(|&u| u == g).unwrap() as u32;
                let mut parts = Vec::new();
                let mut impulses = Vec::new();
                for (g, p) in &want {
                    impulses.push((rank(*g as u32), parts.len() as u32));
                    parts.extend_from_slice(p);
                }
                let renumbered: Vec<u32> = join
                    .iter()
                    .map(|&c| if c < 3 { rank(c) } else { c })
                    .collect();
                let expected = History {
                    instants: used.iter().map(|&g| instants[g as usize]).collect(),
                    impulses,
                    parts,
                    join: renumbered,
                };
                // Cut at every place, on one thread; in the middle, on two.
                let joins = || Joins {
                    instants: instants.clone(),
                    join: join.clone(),
                };
                for mid in 0..=join.len() {
                    let h = History::from_stretches(joins(), mid, Cores::One);
                    assert_eq!(h, expected, "join {join:?}, cut at {mid}");
                }
                if pairs == 6 && pattern % 7 == 0 {
                    let h = History::from_stretches(joins(), 3, Cores::Two);
                    assert_eq!(h, expected, "join {join:?}, two threads");
                }
            }
        }
    }
}
