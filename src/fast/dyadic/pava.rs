//! The PAVA of `prop:proj-micro` on `i128` pairs with the block being
//! grown kept out of the stack (in registers): an entry pooled into it
//! costs a comparison with one multiplication by a block size and no
//! stack traffic, the common case when blocks are large. It pools exactly
//! as [`crate::fast::kernel::pava_words`] does (the same decision,
//! [`crate::projection::pools`], on the same sums), so it returns the same
//! blocks; the tests compare the two.

use crate::fast::kernel::{pools, Run};
use crate::projection;

/// PAVA on the pairs `(y(x_i, u_i), u_i)` in lexicographic order:
/// adjacent blocks pooled while the left mean is `≥` the right one. The
/// sums must satisfy the kernel's width bound (the products of a sum and a
/// block size fit `i128`): the arithmetic wraps, it never checks.
pub(crate) fn pava(xs: &[i128], us: &[i128], y: impl Fn(i128, i128) -> i128) -> Vec<Run<i128>> {
    debug_assert_eq!(xs.len(), us.len());
    let mut stack: Vec<Run<i128>> = Vec::with_capacity(1024);
    // Iterators over the two columns: no bounds check per entry.
    let mut entries = xs.iter().zip(us).map(|(&x, &u)| (y(x, u), u));
    let Some((sy, su)) = entries.next() else {
        return stack;
    };
    let mut cur = Run { k: 1, sy, su };
    for (y, u) in entries {
        // [`pools`] of `cur` and the one-entry block `(y, u)`.
        let k = i128::from(cur.k);
        let pool = projection::pools(cur.sy.cmp(&y.wrapping_mul(k)), || {
            cur.su.cmp(&u.wrapping_mul(k))
        });
        if !pool {
            stack.push(std::mem::replace(&mut cur, Run { k: 1, sy: y, su: u }));
            continue;
        }
        cur.k += 1;
        cur.sy = cur.sy.wrapping_add(y);
        cur.su = cur.su.wrapping_add(u);
        // The grown block's mean went down: it may violate with the blocks
        // below it.
        while let Some(top) = stack.last() {
            if !pools(top, &cur) {
                break;
            }
            if let Some(top) = stack.pop() {
                cur.k += top.k;
                cur.sy = cur.sy.wrapping_add(top.sy);
                cur.su = cur.su.wrapping_add(top.su);
            }
        }
    }
    stack.push(cur);
    stack
}
