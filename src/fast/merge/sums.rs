//! Cluster sums: the words they are kept in (`i64` or `i128`, the narrowest
//! the width bound allows), the per-particle nodes of the event loop, and
//! the candidate time of two adjacent clusters.

use crate::fast::int::pair_bound;

use super::time::Time;

/// The word a cluster sum is kept in: `i64` when `N · M < 2^63` (every
/// cluster sum then fits), else `i128` (see the width bound).
pub(super) trait SumWord:
    Copy + Default + std::ops::AddAssign + std::ops::Add<Output = Self>
{
    /// `self · k` exactly, as `i128`.
    fn times(self, k: u32) -> i128;
}

impl SumWord for i64 {
    #[inline]
    fn times(self, k: u32) -> i128 {
        // |self| < 2^63 and k < 2^32: the product is below 2^95, so the
        // wrapping product is the exact one (one machine multiplication).
        i128::from(self).wrapping_mul(i128::from(k))
    }
}

impl SumWord for i128 {
    #[inline]
    fn times(self, k: u32) -> i128 {
        // Below 2^126 by the width bound (k_L k_R M ≤ B).
        self * i128::from(k)
    }
}

/// One entry per particle. A cluster `f .. e` keeps its sums and size at
/// both ends, `f` and `e − 1` (the same node when `e = f + 1`); interior
/// nodes have `size = 0`. The pair at boundary `b` is thus read from the
/// neighbouring nodes `b − 1` and `b`, and a merge touches memory only
/// around the boundary it joins and the two outer ends.
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct Node<W> {
    pub(super) sum_x: W,
    pub(super) sum_u: W,
    /// Number of particles of the cluster this node ends; 0 inside.
    pub(super) size: u32,
    /// Bumped whenever the pair at boundary `i` changes: queued entries
    /// with an older stamp are stale. (It is bumped at most twice per merge
    /// next to the boundary, fewer than `2N < 2^32` times: it never wraps
    /// around to a queued value.)
    pub(super) stamp: u32,
}

/// The candidate collision time of adjacent clusters, if they approach.
#[inline]
pub(super) fn meeting<W: SumWord>(l: &Node<W>, r: &Node<W>) -> Option<Time> {
    let closing = l.sum_u.times(r.size) - r.sum_u.times(l.size);
    if closing <= 0 {
        return None;
    }
    Some(Time::new(
        r.sum_x.times(l.size) - l.sum_x.times(r.size),
        closing,
    ))
}

/// `true` when `max(N, ⌊N²/4⌋) · M < 2^126` (the width bound of the module
/// docs), for `n` particles and `m = M = max(max|X_i|, max|U_i|)`.
pub(super) fn within_bound(n: usize, m: u128) -> bool {
    pair_bound(n)
        .checked_mul(m)
        .is_some_and(|b| b < 1u128 << 126)
}

/// `true` when `N · M < 2^63`: every cluster sum then fits `i64`
/// ([`SumWord`]).
pub(super) fn narrow_sums(n: usize, m: u128) -> bool {
    (n as u128).checked_mul(m).is_some_and(|b| b < 1u128 << 63)
}

/// The scaled data in the narrowest word that holds them.
#[derive(Debug, Clone)]
pub(super) enum Words {
    I64(Vec<i64>, Vec<i64>),
    I128(Vec<i128>, Vec<i128>),
}

impl Words {
    pub(super) fn x(&self, i: usize) -> i128 {
        match self {
            Words::I64(x, _) => i128::from(x[i]),
            Words::I128(x, _) => x[i],
        }
    }
    pub(super) fn u(&self, i: usize) -> i128 {
        match self {
            Words::I64(_, u) => i128::from(u[i]),
            Words::I128(_, u) => u[i],
        }
    }
    pub(super) fn len(&self) -> usize {
        match self {
            Words::I64(x, _) => x.len(),
            Words::I128(x, _) => x.len(),
        }
    }
}
