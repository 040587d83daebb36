//! Two cores for large scenes: the PAVA of `prop:proj-micro` run on the two
//! halves of the entries at once and joined, and the outputs filled by two
//! threads, each on a range of whole blocks.
//!
//! **Why the join gives the one-thread blocks.** PAVA pools adjacent
//! violators (a block whose mean is `≥` its right neighbour's, in the
//! lexicographic order on `(Y, U)`), starting from one block per entry.
//! Pooling two adjacent blocks whose means are in the wrong order keeps,
//! inside the pooled block, every prefix mean `≥` the block's mean (each
//! part had it, and the left part's mean is `≥` the right part's): the
//! multipliers of the block are `≥ 0` (`eq:dyn-micro`). So whatever order
//! the violators are pooled in, when none is left the blocks have strictly
//! increasing means and nonnegative multipliers: the optimality conditions
//! of the projection onto the closed convex cone `K` (`prop:proj-micro`),
//! whose solution is unique (the lexicographic tie-break on `U` is the
//! projection of `Y + εU` for all small `ε > 0`, unique as well). The
//! blocks are the maximal runs of equal values of that unique solution,
//! hence the same as the one-thread PAVA's. The right half's blocks are
//! such pooled blocks, so pushing them one by one on the left half's final
//! stack, pooling while the top violates, is PAVA carried on from a legal
//! intermediate state. The tests compare the two on random data and on
//! data built to pool across the junction.
//!
//! The kernel's width bound (`b_Y + b_K ≤ 127`) holds for the sums of every
//! contiguous range of entries, so it covers the joined blocks too.

use super::pava::{pava as pava_columns, widened, Sum};
use crate::fast::kernel::{pools, Run, Word};

/// Below this many entries one thread does everything (a thread costs
/// tens of microseconds to start).
pub(crate) const PARALLEL_MIN: usize = 1 << 16;

/// PAVA on the pairs `(y(x_i, u_i), u_i)`: the blocks of
/// [`crate::fast::kernel::pava_words`], computed on the two halves by two
/// threads when `n ≥ parallel_min`.
pub(crate) fn pava<T: Copy + Into<W> + Sync, W: Sum + Into<i128> + Send>(
    xs: &[T],
    us: &[T],
    parallel_min: usize,
    y: impl Fn(T, T) -> W + Sync,
) -> Vec<Run<i128>> {
    match halves::<T, W, W>(xs, us, parallel_min, y) {
        Halves::One(runs) => widened(runs),
        Halves::Two(left, right) => {
            // The join pools sums of blocks of both halves: on `i128`.
            let mut left = widened(left);
            join(&mut left, widened(right));
            left
        }
    }
}

/// [`pava`] on `Y` sums of type `W` and `U` sums of type `V` kept as they
/// are (the 256-bit `Y` sums of a time beyond the `i128` bound, with `i128`
/// `U` sums).
pub(crate) fn pava_in<T, W, V>(
    xs: &[T],
    us: &[T],
    parallel_min: usize,
    y: impl Fn(T, T) -> W + Sync,
) -> Vec<Run<W, V>>
where
    T: Copy + Into<V> + Sync,
    W: Sum + Word + Send,
    V: Sum + Word + Send,
{
    match halves(xs, us, parallel_min, y) {
        Halves::One(runs) => runs,
        Halves::Two(mut left, right) => {
            join(&mut left, right);
            left
        }
    }
}

/// The blocks of all the entries, or of each half.
enum Halves<W, V> {
    /// One thread ran on all of them.
    One(Vec<Run<W, V>>),
    /// The left half's blocks and the right half's, still to be joined.
    Two(Vec<Run<W, V>>, Vec<Run<W, V>>),
}

/// [`pava_columns`] on the two halves by two threads when
/// `n ≥ parallel_min`, on all the entries by one otherwise.
fn halves<T: Copy + Into<V> + Sync, W: Sum + Send, V: Sum + Send>(
    xs: &[T],
    us: &[T],
    parallel_min: usize,
    y: impl Fn(T, T) -> W + Sync,
) -> Halves<W, V> {
    let n = xs.len().min(us.len());
    if n < parallel_min.max(2) {
        return Halves::One(pava_columns(xs, us, &y));
    }
    let h = n / 2;
    let (y, (xl, xr), (ul, ur)) = (&y, xs.split_at(h), us.split_at(h));
    let (left, right) =
        crate::parallel::join(|| pava_columns(xl, ul, y), move || pava_columns(xr, ur, y));
    Halves::Two(left, right)
}

/// Pushes the blocks of `right` (PAVA's blocks of the entries that follow
/// `stack`'s) on `stack`, pooling while the top violates (module
/// documentation).
pub(crate) fn join<W: Word, V: Word>(stack: &mut Vec<Run<W, V>>, right: Vec<Run<W, V>>) {
    let mut rest = right.into_iter();
    while let Some(mut b) = rest.next() {
        let mut pooled = false;
        while let Some(top) = stack.last() {
            if !pools(top, &b) {
                break;
            }
            pooled = true;
            if let Some(top) = stack.pop() {
                b = Run {
                    k: top.k + b.k,
                    sy: top.sy.add(&b.sy),
                    su: top.su.add(&b.su),
                };
            }
        }
        stack.push(b);
        if !pooled {
            // `b`'s mean is unchanged and the blocks after it have larger
            // means (PAVA's output is strictly increasing): nothing more
            // pools.
            stack.extend(rest);
            return;
        }
    }
}

/// The index of the first block of the second half (the block holding
/// entry `n / 2` starts it) and the entry it starts at; `(runs.len(), n)`
/// when there is one block or none.
fn midpoint<W, V>(runs: &[Run<W, V>], n: usize) -> (usize, usize) {
    let mut first = 0usize;
    for (j, r) in runs.iter().enumerate() {
        if first >= n / 2 && j > 0 {
            return (j, first);
        }
        first += r.k as usize;
    }
    (runs.len(), n)
}

/// `len` values (`len ≥` the first entry of the last block) written by
/// `fill(blocks, first, out)` — `blocks` the blocks from entry `first` on,
/// `out` the values from index `first` on — by two threads on two ranges of
/// whole blocks when `n ≥ parallel_min`. `None` when a fill answers `None`.
pub(crate) fn fill_by_halves<W: Sync, V: Sync>(
    runs: &[Run<W, V>],
    n: usize,
    len: usize,
    parallel_min: usize,
    fill: impl Fn(&[Run<W, V>], usize, &mut [f64]) -> Option<()> + Sync,
) -> Option<Vec<f64>> {
    let mut out = vec![0.0; len];
    let (j, first) = if n < parallel_min {
        (runs.len(), n)
    } else {
        midpoint(runs, n)
    };
    if j == runs.len() {
        fill(runs, 0, &mut out)?;
        return Some(out);
    }
    debug_assert!(first <= len);
    let (lo, hi) = out.split_at_mut(first);
    let fill = &fill;
    let (a, b) = crate::parallel::join(
        || fill(&runs[..j], 0, lo),
        move || fill(&runs[j..], first, hi),
    );
    a?;
    b?;
    Some(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fast::kernel::pava_words;
    use crate::generate::SplitMix64;

    /// The two-thread PAVA and the one-thread [`pava_columns`] against the
    /// kernel's [`pava_words`] on `pairs` cut at every length (the split is
    /// always at `n / 2`).
    fn same_blocks(pairs: &[(i128, i128)]) {
        for len in 1..=pairs.len() {
            let p = &pairs[..len];
            let want = pava_words(len, |i| p[i]);
            let (ys, us): (Vec<i128>, Vec<i128>) = p.iter().copied().unzip();
            let got = pava(&ys, &us, 2, |y, _| y);
            assert_eq!(got, want, "{p:?}");
            let one = pava(&ys, &us, usize::MAX, |y, _| y);
            assert_eq!(one, want, "one thread, {p:?}");
            // On `i64` columns and sums (the test values are small).
            let ys64: Vec<i64> = ys.iter().map(|&v| v as i64).collect();
            let us64: Vec<i64> = us.iter().map(|&v| v as i64).collect();
            assert_eq!(pava(&ys64, &us64, 2, |y, _| y), want, "i64, {p:?}");
            let one = pava(&ys64, &us64, usize::MAX, |y, _| y);
            assert_eq!(one, want, "i64, one thread, {p:?}");
        }
    }

    #[test]
    fn halves_give_the_one_thread_blocks_on_random_pairs() {
        let mut rng = SplitMix64::new(0x4a1f);
        for case in 0..2_000 {
            let n = 1 + (rng.next_u64() % 40) as usize;
            let spread = 1 + rng.next_u64() % if case % 2 == 0 { 4 } else { 1 << 20 };
            let pairs: Vec<(i128, i128)> = (0..n)
                .map(|i| {
                    let y = (rng.next_u64() % spread) as i128 - (spread / 2) as i128;
                    let u = (rng.next_u64() % 5) as i128 - 2;
                    (y + (i as i128) * (case % 3) as i128, u)
                })
                .collect();
            same_blocks(&pairs);
        }
    }

    /// One block across the junction (a decreasing run), ties at the
    /// junction decided by `U` either way, equal means everywhere, and a
    /// right half whose first blocks pool with the left's stack only after
    /// growing.
    #[test]
    fn halves_give_the_one_thread_blocks_at_the_junction() {
        let down: Vec<(i128, i128)> = (0..20).map(|i| (100 - i, 0)).collect();
        same_blocks(&down);
        let flat: Vec<(i128, i128)> = (0..20).map(|_| (7, 0)).collect();
        same_blocks(&flat);
        let ties_up: Vec<(i128, i128)> = (0..20).map(|i| (7, i)).collect();
        same_blocks(&ties_up);
        let ties_down: Vec<(i128, i128)> = (0..20).map(|i| (7, -i)).collect();
        same_blocks(&ties_down);
        // Left: increasing steps; right: a deep dip then a rise, so that
        // its first block pools with several of the left's, and its later
        // blocks again.
        let mut dip: Vec<(i128, i128)> = (0..10).map(|i| (10 * i, 0)).collect();
        dip.extend([(-50, 0), (95, 0), (-300, 0), (1000, 0)]);
        dip.extend((0..6).map(|i| (2000 + i, 0)));
        same_blocks(&dip);
    }
}
