//! Both cores for the `i128` loop: PAVA on the two halves of the entries at
//! once, then the halves' blocks joined where they meet, with no copy.
//!
//! **Why the join gives the one-thread blocks.** PAVA may pool adjacent
//! violators in any order: pooling two adjacent blocks whose means are in
//! the wrong order keeps every prefix mean of the pooled block `≥` its mean
//! (the multipliers of `eq:dyn-micro` stay `≥ 0`), so when no violator is
//! left the blocks have strictly increasing means and nonnegative
//! multipliers — the optimality conditions of the projection onto the
//! closed convex cone `K` (`prop:proj-micro`), whose solution is unique
//! (with the lexicographic tie-break on `U`, the projection of `Y + εU` for
//! all small `ε > 0`). The right half's blocks are such pooled blocks:
//! pushing them one by one on the left half's stack, pooling while the top
//! violates, is PAVA carried on from a legal intermediate state. Once a
//! right block is pushed without pooling, the blocks after it have larger
//! means (the right half's output is strictly increasing) and nothing more
//! pools: the rest of the right half's blocks stay where they are, in their
//! own vector ([`Parts`]).
//!
//! The kernel's width bound holds for the sums of every contiguous range of
//! entries, so it covers the joined blocks too.

use super::small::{pava, pava_into, pools, USum};
use super::Run;

/// Below this many entries one thread runs the whole (starting a thread
/// costs tens of microseconds).
pub(crate) const PARALLEL_MIN: usize = 1 << 16;

/// Blocks left to right, held as the left part's vector followed by the
/// right part's from index `skip` on (the join pooled the right part's
/// first `skip` blocks into the left part).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Parts<R> {
    left: Vec<R>,
    right: Vec<R>,
    skip: usize,
}

impl<R> From<Vec<R>> for Parts<R> {
    fn from(left: Vec<R>) -> Self {
        Parts {
            left,
            right: Vec::new(),
            skip: 0,
        }
    }
}

impl<R> Parts<R> {
    /// The number of blocks.
    pub(crate) fn len(&self) -> usize {
        self.left.len() + self.right.len() - self.skip
    }
    /// Block `j` (`j < len`).
    #[inline]
    pub(crate) fn get(&self, j: usize) -> &R {
        match self.left.get(j) {
            Some(r) => r,
            None => &self.right[j - self.left.len() + self.skip],
        }
    }
    /// The blocks, left to right.
    #[cfg(test)]
    pub(crate) fn iter(&self) -> impl Iterator<Item = &R> {
        self.left.iter().chain(&self.right[self.skip..])
    }
}

impl<V: USum> Parts<Run<i128, V>> {
    /// The blocks, left to right, in one vector with `i128` `U` sums (the
    /// left part's vector reused when it already holds them).
    pub(crate) fn into_wide(self) -> Vec<Run<i128>> {
        let wide = |r: Run<i128, V>| Run {
            k: r.k,
            sy: r.sy,
            su: r.su.into(),
        };
        let Parts { left, right, skip } = self;
        left.into_iter()
            .chain(right.into_iter().skip(skip))
            .map(wide)
            .collect()
    }
}

/// [`pava`] of `xs`, `us`, on two threads (the two halves) when there are
/// at least `parallel_min` entries (and at least 2): the same blocks.
pub(crate) fn pava_parts<V: USum>(
    xs: &[i64],
    us: &[i64],
    a: i64,
    b: i64,
    parallel_min: usize,
) -> Parts<Run<i128, V>> {
    let n = xs.len().min(us.len());
    if n < parallel_min.max(2) {
        return Parts::from(pava(xs, us, a, b));
    }
    let h = n / 2;
    let ((xl, xr), (ul, ur)) = (xs.split_at(h), us.split_at(h));
    // Both stacks allocated here: memory from this thread's (warm) arena.
    let stack = Vec::with_capacity(n - h);
    let (left, right) = crate::parallel::join(
        || pava(xl, ul, a, b),
        move || pava_into(stack, xr, ur, a, b),
    );
    join(left, right)
}

/// The blocks of the entries of `left` followed by those of `right` (each
/// PAVA's blocks of its entries): the right blocks pushed on the left
/// stack while they pool (module documentation).
pub(crate) fn join<V: USum>(
    mut left: Vec<Run<i128, V>>,
    right: Vec<Run<i128, V>>,
) -> Parts<Run<i128, V>> {
    let mut skip = 0;
    while let Some(first) = right.get(skip) {
        let mut b = first.clone();
        let mut pooled = false;
        while let Some(top) = left.last() {
            if !pools(top, &b) {
                break;
            }
            pooled = true;
            if let Some(top) = left.pop() {
                b = Run {
                    k: top.k + b.k,
                    sy: top.sy.wrapping_add(b.sy),
                    su: top.su.plus(b.su),
                };
            }
        }
        if !pooled {
            break;
        }
        left.push(b);
        skip += 1;
    }
    Parts { left, right, skip }
}
