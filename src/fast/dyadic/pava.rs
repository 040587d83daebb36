//! The PAVA of `prop:proj-micro` on integer pairs with the block being
//! grown kept out of the stack (in registers): an entry pooled into it
//! costs a comparison with one multiplication by a block size and no
//! stack traffic, the common case when blocks are large. It pools exactly
//! as [`crate::fast::kernel::pava_words`] does (the same decision,
//! [`crate::projection::pools`], on the same sums), so it returns the same
//! blocks; the tests compare the two.
//!
//! The sums are `i64` ([`Sum`]) when the caller proved that every sum and
//! every product of a sum and a block size fits 63 bits (grid data: one
//! machine multiplication per comparison, half the registers), `i128`
//! otherwise, [`Int`] (256 bits) when the `i128` bound fails (a double
//! time with a full mantissa).

use crate::fast::kernel::{Run, Word};
use crate::fast::wide::Int;
use crate::projection;

/// The integer type of the PAVA's sums: wrapping arithmetic, exact under
/// the caller's width bound.
pub(crate) trait Sum: Copy + Ord {
    /// `k` (a block size).
    fn size(k: u64) -> Self;
    /// `self · k` for a block size `k` (wrapping).
    #[inline]
    fn times_size(self, k: u64) -> Self {
        self.times(Self::size(k))
    }
    /// `self + o` (wrapping).
    fn plus(self, o: Self) -> Self;
    /// `self · o` (wrapping).
    fn times(self, o: Self) -> Self;
    /// `self · 2^j` (wrapping).
    fn shifted(self, j: u32) -> Self;
}

impl Sum for i64 {
    #[inline]
    fn size(k: u64) -> i64 {
        k as i64
    }
    #[inline]
    fn plus(self, o: i64) -> i64 {
        self.wrapping_add(o)
    }
    #[inline]
    fn times(self, o: i64) -> i64 {
        self.wrapping_mul(o)
    }
    #[inline]
    fn shifted(self, j: u32) -> i64 {
        self.wrapping_shl(j)
    }
}

impl Sum for i128 {
    #[inline]
    fn size(k: u64) -> i128 {
        i128::from(k)
    }
    #[inline]
    fn plus(self, o: i128) -> i128 {
        self.wrapping_add(o)
    }
    #[inline]
    fn times(self, o: i128) -> i128 {
        self.wrapping_mul(o)
    }
    #[inline]
    fn shifted(self, j: u32) -> i128 {
        self.wrapping_shl(j)
    }
}

impl<const L: usize> Sum for Int<L> {
    #[inline]
    fn size(k: u64) -> Self {
        Int::from_i128(i128::from(k))
    }
    #[inline]
    fn times_size(self, k: u64) -> Self {
        self.mul_k(k)
    }
    #[inline]
    fn plus(self, o: Self) -> Self {
        self.wrapping_add(o)
    }
    #[inline]
    fn times(self, o: Self) -> Self {
        self.wrapping_mul(o)
    }
    #[inline]
    fn shifted(self, j: u32) -> Self {
        self.wrapping_shl(j)
    }
}

/// [`crate::fast::kernel::pools`] on sums of type `W`: is `a`'s mean `≥`
/// `b`'s in the lexicographic order on `(Y, U)`?
#[inline]
fn pools<W: Sum, V: Sum>(a: &Run<W, V>, b: &Run<W, V>) -> bool {
    projection::pools(a.sy.times_size(b.k).cmp(&b.sy.times_size(a.k)), || {
        a.su.times_size(b.k).cmp(&b.su.times_size(a.k))
    })
}

/// The blocks on `i128` sums (exact: a sum of `W` fits `i128`).
pub(crate) fn widened<W: Sum + Into<i128>>(runs: Vec<Run<W>>) -> Vec<Run<i128>> {
    runs.into_iter()
        .map(|r| Run {
            k: r.k,
            sy: r.sy.into(),
            su: r.su.into(),
        })
        .collect()
}

/// PAVA on the pairs `(y(x_i, u_i), u_i)` in lexicographic order:
/// adjacent blocks pooled while the left mean is `≥` the right one. The
/// sums must satisfy the width bound of `W` (the products of a sum and a
/// block size fit `W`): the arithmetic wraps, it never checks. The
/// columns are `i64` or `i128` ([`super::Columns`]). The `U` sums are on
/// their own words `V` (the 256-bit `Y` sums keep `i128` `U` sums: their
/// bound does not depend on `t`), so the blocks come out in the words their
/// users read, with no second pass over them.
pub(crate) fn pava<T: Copy + Into<V>, W: Sum, V: Sum>(
    xs: &[T],
    us: &[T],
    y: impl Fn(T, T) -> W,
) -> Vec<Run<W, V>> {
    debug_assert_eq!(xs.len(), us.len());
    let mut stack: Vec<Run<W, V>> = Vec::with_capacity(1024);
    // Iterators over the two columns: no bounds check per entry.
    let mut entries = xs.iter().zip(us).map(|(&x, &u)| (y(x, u), u.into()));
    let Some((sy, su)) = entries.next() else {
        return stack;
    };
    let mut cur = Run { k: 1, sy, su };
    for (y, u) in entries {
        // [`pools`] of `cur` and the one-entry block `(y, u)`.
        let k = cur.k;
        let pool = projection::pools(cur.sy.cmp(&y.times_size(k)), || {
            cur.su.cmp(&u.times_size(k))
        });
        if !pool {
            stack.push(std::mem::replace(&mut cur, Run { k: 1, sy: y, su: u }));
            continue;
        }
        cur.k += 1;
        cur.sy = cur.sy.plus(y);
        cur.su = cur.su.plus(u);
        // The grown block's mean went down: it may violate with the blocks
        // below it.
        while let Some(top) = stack.last() {
            if !pools(top, &cur) {
                break;
            }
            if let Some(top) = stack.pop() {
                cur.k += top.k;
                cur.sy = cur.sy.plus(top.sy);
                cur.su = cur.su.plus(top.su);
            }
        }
    }
    stack.push(cur);
    stack
}
