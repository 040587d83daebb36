//! The `i128` loop on `i64` columns: PAVA on `Y_i = a X_i + b U_i` with the
//! block being grown kept out of the stack (in registers).
//!
//! It pools exactly as [`super::pava_words`] does — the decision of
//! [`projection::pools`] on the same sums, the left block against the
//! right one — so it returns the same blocks (the tests compare the two).
//! What it saves: the entry read is compared with the block being grown
//! without a store and a load of the stack top, and a block of one entry
//! (most of them at small `t`) is compared with no multiplication at all.
//!
//! **Width.** The caller proved the `i128` bound of the module
//! documentation of [`super`]: `|a|, |b|, |X_i|, |U_i| < 2^63` (each product
//! `< 2^126`, one machine multiplication of two words), and every block sum
//! times a block size below `2^127`, so the wrapping operations never wrap.
//! The `U` sums are kept in `i64` ([`USum`]) when the caller proved
//! `N max|U| < 2^63` (every `|ΣU| ≤ k max|U|` then fits): a block is 32
//! bytes instead of 48, less memory written. Their products with a block
//! size are formed on `i128`, as the `Y` sums'.

use crate::projection;

use super::Run;

/// The word of the `U` sums: `i64` (under `N max|U| < 2^63`) or `i128`.
pub(crate) trait USum: Copy + Ord + Into<i128> + Send {
    /// `U_i`.
    fn of(u: i64) -> Self;
    /// `self + o` (wrapping; exact under the caller's bound).
    fn plus(self, o: Self) -> Self;
}

impl USum for i64 {
    #[inline]
    fn of(u: i64) -> Self {
        u
    }
    #[inline]
    fn plus(self, o: Self) -> Self {
        self.wrapping_add(o)
    }
}

impl USum for i128 {
    #[inline]
    fn of(u: i64) -> Self {
        i128::from(u)
    }
    #[inline]
    fn plus(self, o: Self) -> Self {
        self.wrapping_add(o)
    }
}

/// `Y_i = a X_i + b U_i` and `U_i` (exact: see the module docs).
#[inline]
fn entry<V: USum>(a: i64, b: i64, x: i64, u: i64) -> (i128, V) {
    (
        i128::from(a)
            .wrapping_mul(i128::from(x))
            .wrapping_add(i128::from(b).wrapping_mul(i128::from(u))),
        V::of(u),
    )
}

/// `s · k` for a block size `k` (wrapping; exact under the bound).
#[inline]
fn times(s: i128, k: u64) -> i128 {
    s.wrapping_mul(i128::from(k))
}

/// [`projection::pools`] on two blocks of `i128` sums: is `l`'s mean `≥`
/// `r`'s in the lexicographic order on `(Y, U)` (cross-multiplied)?
#[inline]
pub(crate) fn pools<V: USum>(l: &Run<i128, V>, r: &Run<i128, V>) -> bool {
    projection::pools(times(l.sy, r.k).cmp(&times(r.sy, l.k)), || {
        times(l.su.into(), r.k).cmp(&times(r.su.into(), l.k))
    })
}

/// PAVA on the entries `(a X_i + b U_i, U_i)` of `xs`, `us` (same length),
/// under the bound of the module docs: the blocks of
/// [`super::pava_words`], left to right.
pub(crate) fn pava<V: USum>(xs: &[i64], us: &[i64], a: i64, b: i64) -> Vec<Run<i128, V>> {
    pava_into(Vec::with_capacity(xs.len()), xs, us, a, b)
}

/// [`pava`], the blocks written to `stack` (emptied first; its capacity
/// kept, grown if it is short): a caller may allocate it on another thread
/// (the allocator's arena of the thread that allocates serves the memory,
/// and the calling thread's is the one already warm).
pub(crate) fn pava_into<V: USum>(
    mut stack: Vec<Run<i128, V>>,
    xs: &[i64],
    us: &[i64],
    a: i64,
    b: i64,
) -> Vec<Run<i128, V>> {
    debug_assert_eq!(xs.len(), us.len());
    stack.clear();
    let mut entries = xs.iter().zip(us).map(|(&x, &u)| entry::<V>(a, b, x, u));
    let Some((sy, su)) = entries.next() else {
        return stack;
    };
    let mut cur = Run { k: 1, sy, su };
    for (y, u) in entries {
        // [`pools`] of `cur` and the one-entry block `(y, u)`: `cur.sy · 1`
        // against `y · cur.k`, no product when `cur` has one entry.
        let pool = if cur.k == 1 {
            projection::pools(cur.sy.cmp(&y), || cur.su.cmp(&u))
        } else {
            projection::pools(cur.sy.cmp(&times(y, cur.k)), || {
                cur.su.into().cmp(&times(u.into(), cur.k))
            })
        };
        if !pool {
            stack.push(std::mem::replace(&mut cur, Run { k: 1, sy: y, su: u }));
            continue;
        }
        cur.k += 1;
        cur.sy = cur.sy.wrapping_add(y);
        cur.su = cur.su.plus(u);
        // The grown block's mean went down: it may violate with the blocks
        // below it.
        while let Some(top) = stack.last() {
            if !pools(top, &cur) {
                break;
            }
            if let Some(top) = stack.pop() {
                cur.k += top.k;
                cur.sy = cur.sy.wrapping_add(top.sy);
                cur.su = cur.su.plus(top.su);
            }
        }
    }
    stack.push(cur);
    stack
}
