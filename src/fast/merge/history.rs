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

use super::events::{Joins, JOIN_NEVER, JOIN_ZERO};

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

/// Calls `formed(instant, first, pairs, end)` on every cluster formed (see
/// the module docs): it runs over particles `first..end` and its pairs
/// `(key, j)` joining at `instant` are `pairs`, left to right. The
/// clusters of one instant come left to right. Each code is replaced by
/// `relabel(code)` once read.
fn clusters_formed(
    join: &mut [u32],
    relabel: impl Fn(u32) -> u32,
    mut formed: impl FnMut(usize, u32, &[(u32, u32)], u32),
) {
    // Entries `(key, j)`, keys not increasing upwards.
    let mut stack: Vec<(u32, u32)> = Vec::new();
    // The first particle after the last pair that never joins.
    let mut floor = 0u32;
    for r in 0..=join.len() {
        // Past the last pair, a pair that never joins closes every cluster.
        let k = join.get_mut(r).map_or(u32::MAX, |c| {
            let k = key(*c);
            *c = relabel(*c);
            k
        });
        while let Some(&(top, _)) = stack.last() {
            if top >= k {
                break;
            }
            let mut start = stack.len() - 1;
            while start > 0 && stack[start - 1].0 == top {
                start -= 1;
            }
            // Key 0: an initial cluster, formed at no instant.
            if top > 0 {
                let first = match start {
                    0 => floor,
                    s => stack[s - 1].1 + 1,
                };
                formed((top - 1) as usize, first, &stack[start..], r as u32 + 1);
            }
            stack.truncate(start);
        }
        if k == u32::MAX {
            floor = r as u32 + 1;
        } else {
            stack.push((k, r as u32));
        }
    }
}

impl History {
    /// The history whose pairs join as `joins` says (see the module docs).
    /// The instants at which no pair joins are dropped (a repaired half
    /// keeps the instants of clusters the run took in), and the codes
    /// renumbered.
    pub(super) fn from_joins(joins: Joins) -> History {
        let Joins {
            mut instants,
            mut join,
        } = joins;
        let len = instants.len();
        // 1. The impulses and parts of every instant counted (one place
        //    per instant: one cache line touched per cluster).
        let mut at = vec![(0u32, 0u32); len];
        clusters_formed(
            &mut join,
            |c| c,
            |g, _, pairs, _| {
                at[g].0 += 1;
                at[g].1 += pairs.len() as u32 + 2;
            },
        );
        // Then where each instant's first impulse and part go, and the
        // rank of every instant used.
        let mut rank = vec![JOIN_NEVER; len];
        let (mut impulse_count, mut part_count, mut used) = (0u32, 0u32, 0u32);
        for (a, r) in at.iter_mut().zip(&mut rank) {
            if a.0 > 0 {
                *r = used;
                used += 1;
            }
            let next = (impulse_count + a.0, part_count + a.1);
            *a = (impulse_count, part_count);
            (impulse_count, part_count) = next;
        }
        // 2. Every cluster written where it belongs; the codes renumbered
        //    on the way when an instant is dropped.
        let mut impulses = vec![(0u32, 0u32); impulse_count as usize];
        let mut parts = vec![0u32; part_count as usize];
        let mut write = |g: usize, first: u32, pairs: &[(u32, u32)], end: u32| {
            let (k, p) = at[g];
            impulses[k as usize] = (rank[g], p);
            let out = &mut parts[p as usize..p as usize + pairs.len() + 2];
            out[0] = first;
            for (o, &(_, j)) in out[1..].iter_mut().zip(pairs) {
                *o = j + 1;
            }
            out[pairs.len() + 1] = end;
            at[g] = (k + 1, p + pairs.len() as u32 + 2);
        };
        if used as usize == len {
            clusters_formed(&mut join, |c| c, &mut write);
        } else {
            let relabel = |c: u32| match c {
                JOIN_NEVER | JOIN_ZERO => c,
                g => rank[g as usize],
            };
            clusters_formed(&mut join, relabel, &mut write);
            let mut g = 0;
            instants.retain(|_| {
                g += 1;
                rank[g - 1] != JOIN_NEVER
            });
        }
        History {
            instants,
            impulses,
            parts,
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
        // (5^6 = 15,625 lines): the scan finds the brute-force clusters,
        // and the unused instants are dropped.
        let codes = [JOIN_NEVER, JOIN_ZERO, 0, 1, 2];
        for pairs in 0..=6u32 {
            for mut w in 0..5usize.pow(pairs) {
                let join: Vec<u32> = (0..pairs)
                    .map(|_| {
                        let c = codes[w % 5];
                        w /= 5;
                        c
                    })
                    .collect();
                let instants: Vec<(i128, i128)> = (1..=3).map(|t| (t, 1)).collect();
                let h = History::from_joins(Joins {
                    instants: instants.clone(),
                    join: join.clone(),
                });
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
                assert_eq!(h, expected, "join {join:?}");
            }
        }
    }
}
