//! Exact PAVA on integers over a common denominator — the fast exact path.
//!
//! The generic [`crate::projection`] code on `BigRational` reduces a fraction
//! (a gcd) at every addition and comparison. Here the data are scaled once
//! to integers: with `x̃⁰_i = X_i / D_x`, `u⁰_i = U_i / D_u` and `t = p/q`,
//!
//! `ỹ_i = x̃⁰_i + t u⁰_i = Y_i / D_y`, `Y_i = q D_u X_i + p D_x U_i`,
//! `D_y = q D_x D_u`,
//!
//! and pool-adjacent-violators runs on the integer pairs `(Y_i, U_i)`: a block
//! is `(k, ΣY, ΣU)`, block means are compared by cross-multiplication
//! (`ΣY_a k_b` against `ΣY_b k_a`, then the same for `U` on ties — the
//! lexicographic order that gives the right derivative, see
//! [`crate::projection`]), with no gcd and no division in the loop.
//!
//! **The result** ([`Blocks`]) is the partition into blocks with the exact
//! integer sums `(k, ΣY, ΣU)` of each block: the exact answer, in the form
//! the loop produced it. The block means `ΣY / (k D_y)` are reduced to lowest
//! terms only when asked for ([`Blocks::mean_y`], [`Blocks::mean_u`],
//! [`state_at`]), so that a caller who needs a few of them does not pay for a
//! gcd per block. On 512 bits the result is sparse (`Sparse`): a block of
//! one entry is stored as that entry's index and its sums are recomputed
//! from the data when asked for, since writing a 96-byte block per particle
//! cost more in page faults on fresh memory than the loop's arithmetic.
//!
//! **Width.** The loop runs on the narrowest of three integer types that
//! provably cannot overflow (decided before the loop from bit lengths, with
//! `|v| < 2^bits(v)`):
//!
//! * with `b_Y = max(bits(q D_u) + bits(max|X|), bits(p D_x) + bits(max|U|)) + 1`
//!   (so `|Y_i| < 2^b_Y`) and `b_K = bits(max(N, ⌊N²/4⌋))`, every block sum
//!   is at most `k max|Y| ≤ N max|Y|` and every cross product
//!   `|ΣY_a| k_b ≤ k_a k_b max|Y| ≤ (N²/4) max|Y|`, both `< 2^(b_Y + b_K)`;
//!   the same with `bits(max|U|)` for the `U` sums;
//! * `i128` when `X_i`, `U_i`, `q D_u`, `p D_x` all fit `i64` (each product
//!   `< 2^126`) and `b_Y + b_K ≤ 127`, `bits(max|U|) + b_K ≤ 127`;
//! * [`I256`] when the data fit 255 bits and the same bounds hold with 256
//!   (`b_Y + b_K < 256`, `bits(max|U|) + b_K < 256`);
//! * [`I512`] when the data fit 511 bits and the same bounds hold with 512
//!   (100-digit decimal data);
//! * `BigInt` otherwise.
//!
//! Inside the proved range the fixed-width loops use wrapping operations (the
//! release profile checks overflow everywhere else). The result is identical
//! whatever the width and equal to the generic `BigRational` path, which the
//! tests use as the oracle, on both sides of each width's bound.

use std::sync::Arc;

use num_bigint::{BigInt, Sign};
use num_rational::BigRational;
use num_traits::{Signed, ToPrimitive, Zero};

use crate::cluster::{runs, Cluster};
use crate::contact::cluster_multiplier_numerators;
use crate::error::Error;
use crate::fast::int::{narrowed, pair_bound, ratio_over};
use crate::fast::wide::{Int, I256, I512};
use crate::initial::InitialData;
use crate::projection;
use crate::state::State;

mod halves;
mod small;

use halves::Parts;

/// The integer type the PAVA loop ran on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Width {
    /// 128-bit integers.
    I128,
    /// 256-bit integers ([`I256`]).
    I256,
    /// 512-bit integers ([`I512`]).
    I512,
    /// Arbitrary-precision integers.
    Big,
}

/// The scaled values in the narrowest representation that holds all of them.
#[derive(Debug, Clone)]
pub(crate) enum Column {
    /// Every value fits `i64`.
    Small(Vec<i64>),
    /// Every value fits 254 bits.
    W256(Vec<I256>),
    /// Every value fits 510 bits.
    W512(Vec<I512>),
    /// Only the `BigInt` values.
    Big,
}

impl Column {
    fn of(v: &[BigInt]) -> Column {
        let bits = v.iter().map(BigInt::bits).max().unwrap_or(0);
        if bits <= 63 {
            if let Some(s) = narrowed(v, ToPrimitive::to_i64) {
                return Column::Small(s);
            }
        }
        if bits <= 254 {
            if let Some(w) = narrowed(v, I256::from_bigint) {
                return Column::W256(w);
            }
        }
        if bits <= 510 {
            if let Some(w) = narrowed(v, I512::from_bigint) {
                return Column::W512(w);
            }
        }
        Column::Big
    }
    /// The widest fixed width whose values the column holds, in 64-bit
    /// limbs (`usize::MAX` for `BigInt` values).
    fn limbs(&self) -> usize {
        match self {
            Column::Small(_) => 1,
            Column::W256(_) => 4,
            Column::W512(_) => 8,
            Column::Big => usize::MAX,
        }
    }
    /// Value `i` in `L` limbs; the caller has checked `self.limbs() ≤ L`
    /// (zero for `BigInt` columns).
    #[inline]
    pub(crate) fn get<const L: usize>(&self, i: usize) -> Int<L> {
        match self {
            Column::Small(v) => Int::from_i64(v[i]),
            Column::W256(v) => v[i].resize(),
            Column::W512(v) => v[i].resize(),
            Column::Big => Int::ZERO,
        }
    }
}

/// Initial data on common denominators: `x̃⁰_i = x[i] / dx`,
/// `u⁰_i = u[i] / du` (`df:translat-x`).
#[derive(Debug, Clone)]
pub struct IntegerData {
    pub(crate) x: Vec<BigInt>,
    pub(crate) u: Vec<BigInt>,
    /// Shared with the 512-bit [`Blocks`], which recompute a block of one
    /// entry from them instead of storing it.
    pub(crate) x_col: Arc<Column>,
    pub(crate) u_col: Arc<Column>,
    /// `bits(max|X|)`, `bits(max|U|)`.
    pub(crate) x_bits: u64,
    pub(crate) u_bits: u64,
    pub(crate) dx: BigInt,
    pub(crate) du: BigInt,
    /// `X_i`, `U_i` rounded to `f64` (relative error at most `2^−52`; ±∞
    /// beyond the range), for the adaptive solver's filter: computed the
    /// first time it runs (only data that need `BigInt` take it).
    approx: std::sync::OnceLock<(Vec<f64>, Vec<f64>)>,
    two_r: BigRational,
}

impl IntegerData {
    /// Scales the data once.
    pub fn new(data: &InitialData<BigRational>) -> Self {
        // Machine words when every scaled value fits `i128` (the common
        // case, no allocation per value), `BigInt` otherwise: the same
        // integers.
        let (x, u, dx, du) = match crate::fast::scaling::scale_words(data) {
            Some(s) => {
                let big = |v: &[i128]| v.iter().map(|&a| BigInt::from(a)).collect::<Vec<_>>();
                (big(&s.x), big(&s.u), s.dx, s.du)
            }
            None => crate::fast::scaling::scale_big(data),
        };
        let max_bits = |v: &[BigInt]| v.iter().map(BigInt::bits).max().unwrap_or(0);
        IntegerData {
            approx: std::sync::OnceLock::new(),
            x_col: Arc::new(Column::of(&x)),
            u_col: Arc::new(Column::of(&u)),
            x_bits: max_bits(&x),
            u_bits: max_bits(&u),
            x,
            u,
            dx,
            du,
            two_r: data.two_r(),
        }
    }
    /// N.
    pub fn n(&self) -> usize {
        self.x.len()
    }
    /// `(X_i, U_i)` rounded to `f64` (see the field).
    pub(crate) fn approx(&self) -> &(Vec<f64>, Vec<f64>) {
        self.approx.get_or_init(|| {
            let round = |v: &[BigInt]| -> Vec<f64> {
                v.iter()
                    .map(|x| x.to_f64().unwrap_or(f64::INFINITY))
                    .collect()
            };
            (round(&self.x), round(&self.u))
        })
    }
}

/// One block of the loop: `k` entries with the sums `sy = ΣY`, `su = ΣU`
/// (`ΣU` in a narrower word `V` when its bound allows: a smaller block is
/// less memory to write).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Run<W, V = W> {
    pub(crate) k: u64,
    pub(crate) sy: W,
    pub(crate) su: V,
}

/// The contact clusters of `x(t)` (`df:Omega-micro`) from `i128` block
/// sums: runs of adjacent blocks with equal `x̃ = ΣY/k`, compared by
/// cross-multiplication. Exact under the bound the callers proved before
/// their PAVA (`|ΣY|·k` fits `i128`), so the wrapping products never wrap.
pub(crate) fn i128_clusters(blocks: &[Run<i128>]) -> Vec<Cluster> {
    word_clusters(blocks)
}

/// [`i128_clusters`] on sums of any fixed width ([`Word`]), under the same
/// kind of bound (`|ΣY|·k` in range).
pub(crate) fn word_clusters<W: Word, V>(blocks: &[Run<W, V>]) -> Vec<Cluster> {
    let equal = runs(blocks.len(), |j| {
        let (a, b) = (&blocks[j], &blocks[j + 1]);
        a.sy.mul_k(b.k) == b.sy.mul_k(a.k)
    });
    let mut first = 0usize;
    equal
        .into_iter()
        .map(|c| {
            let size: u64 = blocks[c.first..c.first + c.size].iter().map(|r| r.k).sum();
            let start = first;
            first += size as usize;
            Cluster {
                first: start,
                size: size as usize,
            }
        })
        .collect()
}

/// The block sums in the width the loop ran on.
#[derive(Debug, Clone)]
pub(crate) enum Sums {
    /// `i128` sums, in the parts the threads left them ([`Parts`]).
    I128(Parts<Run<i128>>),
    /// `i128` `ΣY`, `ΣU` in `i64` (`N max|U| < 2^63`).
    I128U64(Parts<Run<i128, i64>>),
    I256(Vec<Run<I256>>),
    I512(Sparse<8, I512>),
    /// 512-bit `ΣY`, `ΣU` in `i128` (`bits(max|U|) + b_K < 128`).
    I512U128(Sparse<8, i128>),
    Big(Vec<Run<BigInt>>),
}

/// The PAVA blocks at `t + ε`, exact: the partition and the integer sums of
/// every block (see the module documentation). Block `j`'s translated
/// position `x̃(t)` is [`Blocks::mean_y`]`(j)`, its velocity (the right
/// derivative) [`Blocks::mean_u`]`(j)`. Two `Blocks` are equal when they
/// have the same clusters and the same means, whatever the width.
#[derive(Debug, Clone)]
pub struct Blocks {
    sums: Sums,
    /// `D_y = q D_x D_u` and `D_u`.
    dy: BigInt,
    du: BigInt,
    /// `D_y`, `D_u` as `i128` when they fit.
    dy_small: Option<i128>,
    du_small: Option<i128>,
}

impl PartialEq for Blocks {
    fn eq(&self, o: &Self) -> bool {
        self.clusters() == o.clusters()
            && (0..self.len())
                .all(|j| self.mean_y(j) == o.mean_y(j) && self.mean_u(j) == o.mean_u(j))
    }
}

impl Blocks {
    /// Blocks from their sums and the denominators `D_y`, `D_u`.
    pub(crate) fn new(sums: Sums, dy: BigInt, du: BigInt) -> Blocks {
        Blocks {
            sums,
            dy_small: dy.to_i128(),
            du_small: du.to_i128(),
            dy,
            du,
        }
    }
    /// The integer width the block sums are held in.
    pub fn width(&self) -> Width {
        match self.sums {
            Sums::I128(_) | Sums::I128U64(_) => Width::I128,
            Sums::I256(_) => Width::I256,
            Sums::I512(_) | Sums::I512U128(_) => Width::I512,
            Sums::Big(_) => Width::Big,
        }
    }
    /// The number of blocks.
    pub fn len(&self) -> usize {
        match &self.sums {
            Sums::I128(v) => v.len(),
            Sums::I128U64(v) => v.len(),
            Sums::I256(v) => v.len(),
            Sums::I512(v) => v.len(),
            Sums::I512U128(v) => v.len(),
            Sums::Big(v) => v.len(),
        }
    }
    /// `true` when there are no particles.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
    fn size(&self, j: usize) -> u64 {
        match &self.sums {
            Sums::I128(v) => v.get(j).k,
            Sums::I128U64(v) => v.get(j).k,
            Sums::I256(v) => v[j].k,
            Sums::I512(v) => v.size(j),
            Sums::I512U128(v) => v.size(j),
            Sums::Big(v) => v[j].k,
        }
    }
    /// The blocks as clusters, left to right.
    pub fn clusters(&self) -> Vec<Cluster> {
        let mut first = 0;
        (0..self.len())
            .map(|j| {
                let size = self.size(j) as usize;
                first += size;
                Cluster {
                    first: first - size,
                    size,
                }
            })
            .collect()
    }
    /// `x̃(t)` on block `j`, in lowest terms.
    pub fn mean_y(&self, j: usize) -> BigRational {
        self.mean(j, true)
    }
    /// `u(t)` on block `j` (the right derivative), in lowest terms.
    pub fn mean_u(&self, j: usize) -> BigRational {
        self.mean(j, false)
    }
    fn mean(&self, j: usize, y: bool) -> BigRational {
        let (d, d_small) = if y {
            (&self.dy, self.dy_small)
        } else {
            (&self.du, self.du_small)
        };
        let pick = |r: &Run<BigInt>| if y { r.sy.clone() } else { r.su.clone() };
        match &self.sums {
            Sums::I128(v) => {
                let r = v.get(j);
                ratio_over(if y { r.sy } else { r.su }, i128::from(r.k), d, d_small)
            }
            Sums::I128U64(v) => {
                let r = v.get(j);
                let s = if y { r.sy } else { i128::from(r.su) };
                ratio_over(s, i128::from(r.k), d, d_small)
            }
            Sums::I256(v) => {
                let s = if y { v[j].sy } else { v[j].su };
                crate::gcd::ratio(s.to_bigint(), d * BigInt::from(v[j].k))
            }
            Sums::I512(v) => {
                let r = v.run(j);
                let s = if y { r.sy } else { r.su };
                crate::gcd::ratio(s.to_bigint(), d * BigInt::from(r.k))
            }
            Sums::I512U128(v) => {
                let r = v.run(j);
                let s = if y {
                    r.sy.to_bigint()
                } else {
                    BigInt::from(r.su)
                };
                crate::gcd::ratio(s, d * BigInt::from(r.k))
            }
            Sums::Big(v) => crate::gcd::ratio(pick(&v[j]), d * BigInt::from(v[j].k)),
        }
    }
}

/// The integer operations the loop needs. Fixed widths wrap: the caller
/// has proved that no value leaves the range (module documentation).
pub(crate) trait Word: Clone + Ord {
    fn add(&self, o: &Self) -> Self;
    fn mul_k(&self, k: u64) -> Self;
}

impl Word for i128 {
    #[inline]
    fn add(&self, o: &Self) -> Self {
        self.wrapping_add(*o)
    }
    #[inline]
    fn mul_k(&self, k: u64) -> Self {
        self.wrapping_mul(i128::from(k))
    }
}

impl<const L: usize> Word for Int<L> {
    #[inline]
    fn add(&self, o: &Self) -> Self {
        self.wrapping_add(*o)
    }
    #[inline]
    fn mul_k(&self, k: u64) -> Self {
        // Most comparisons involve a block of one entry.
        if k == 1 {
            *self
        } else {
            self.wrapping_mul_u64(k)
        }
    }
}

impl Word for BigInt {
    fn add(&self, o: &Self) -> Self {
        self + o
    }
    fn mul_k(&self, k: u64) -> Self {
        self * BigInt::from(k)
    }
}

/// The pooling decision of PAVA ([`projection::pools`], the one
/// definition) on two blocks of integer sums: is the left block's mean `≥`
/// in the lexicographic order on `(Y, U)` (cross-multiplied, no division)?
#[inline]
pub(crate) fn pools<W: Word, V: Word>(a: &Run<W, V>, b: &Run<W, V>) -> bool {
    projection::pools(a.sy.mul_k(b.k).cmp(&b.sy.mul_k(a.k)), || {
        a.su.mul_k(b.k).cmp(&b.su.mul_k(a.k))
    })
}

/// PAVA on the pairs `(y_i, u_i)` (produced by `item`) in lexicographic
/// order: adjacent blocks are pooled while the left mean is `≥` the right
/// one, so the blocks returned have strictly increasing means.
#[inline]
pub(crate) fn pava_words<W: Word, V: Word>(
    n: usize,
    mut item: impl FnMut(usize) -> (W, V),
) -> Vec<Run<W, V>> {
    let mut stack: Vec<Run<W, V>> = Vec::with_capacity(n);
    for i in 0..n {
        // The decision of [`projection::pools`] on loose variables: no
        // `Run` is built for the entry being pooled.
        let (mut sy, mut su) = item(i);
        let mut k = 1u64;
        while let Some(top) = stack.last() {
            let pool = projection::pools(top.sy.mul_k(k).cmp(&sy.mul_k(top.k)), || {
                top.su.mul_k(k).cmp(&su.mul_k(top.k))
            });
            if !pool {
                break;
            }
            if let Some(top) = stack.pop() {
                sy = top.sy.add(&sy);
                su = top.su.add(&su);
                k += top.k;
            }
        }
        stack.push(Run { k, sy, su });
    }
    stack
}

/// `bits(max(N, ⌊N²/4⌋))`: every block size `k ≤ N` and every product of
/// two adjacent block sizes `k_a k_b ≤ N²/4` is below `2^b_K`.
pub(crate) fn size_bits(n: usize) -> u64 {
    u64::from(128 - pair_bound(n).leading_zeros())
}

/// The scaling at one time `t = p/q`: `Y_i = a X_i + b U_i` with
/// `a = q D_u`, `b = p D_x`, over `D_y = q D_x D_u`, and the width the data
/// need at that time (module documentation).
#[derive(Debug, Clone)]
pub(crate) struct AtTime {
    pub(crate) a: BigInt,
    pub(crate) b: BigInt,
    pub(crate) dy: BigInt,
    pub(crate) width: Width,
}

impl AtTime {
    pub(crate) fn new(d: &IntegerData, t: &BigRational) -> AtTime {
        let (p, q) = (t.numer(), t.denom());
        let a = q * &d.du;
        let b = p * &d.dx;
        let dy = &a * &d.dx;
        let b_k = size_bits(d.n());
        let b_y = (a.bits() + d.x_bits).max(b.bits() + d.u_bits) + 1;
        let fits = |w: u64| b_y + b_k < w && d.u_bits + b_k < w;
        let limbs = d.x_col.limbs().max(d.u_col.limbs());
        let width = if limbs <= 1 && a.to_i64().is_some() && b.to_i64().is_some() && fits(128) {
            Width::I128
        } else if limbs <= 4 && fits(256) {
            Width::I256
        } else if limbs <= 8 && fits(512) {
            Width::I512
        } else {
            Width::Big
        };
        AtTime { a, b, dy, width }
    }
}

/// Exact PAVA at time `t` on the integer data (see the module docs).
pub fn blocks_at(d: &IntegerData, t: &BigRational) -> Blocks {
    blocks_on(d, t, halves::PARALLEL_MIN)
}

/// [`blocks_at`], the `i128` loop on two threads from `parallel_min`
/// entries on ([`halves`]).
pub(crate) fn blocks_on(d: &IntegerData, t: &BigRational, parallel_min: usize) -> Blocks {
    let at = AtTime::new(d, t);
    let n = d.n();
    let sums = match (&*d.x_col, &*d.u_col, at.width) {
        (Column::Small(xs), Column::Small(us), Width::I128) => {
            let (a, b) = (at.a.to_i64().unwrap_or(0), at.b.to_i64().unwrap_or(0));
            // |a|, |X_i|, |b|, |U_i| < 2^63: each product < 2^126, and
            // |Y_i| < 2^b_Y with b_Y + b_K < 128 (module docs).
            // |ΣU| ≤ N max|U| < 2^(bits(N) + bits(max|U|)) ≤ 2^63.
            if u64::from(usize::BITS - n.leading_zeros()) + d.u_bits <= 63 {
                Sums::I128U64(halves::pava_parts(xs, us, a, b, parallel_min))
            } else {
                Sums::I128(halves::pava_parts(xs, us, a, b, parallel_min))
            }
        }
        (_, _, Width::I128 | Width::I256) => {
            let e = Entries::<4>::new(d, &at);
            Sums::I256(pava_words(n, |i| e.at(i)))
        }
        // |ΣU| k ≤ k_a k_b max|U| < 2^(bits(max|U|) + b_K) ≤ 2^127.
        (_, Column::Small(_), Width::I512) if d.u_bits + size_bits(n) < 128 => {
            Sums::I512U128(pava_sparse(n, Entries::new(d, &at)))
        }
        (_, _, Width::I512) => Sums::I512(pava_sparse(n, Entries::new(d, &at))),
        (_, _, Width::Big) => Sums::Big(pava_words(n, |i| {
            (&at.a * &d.x[i] + &at.b * &d.u[i], d.u[i].clone())
        })),
    };
    Blocks::new(sums, at.dy, d.du.clone())
}

/// The `i128` loop of [`blocks_at`] on `i64` columns with `Y_i = a X_i + b U_i`,
/// on both cores from [`halves::PARALLEL_MIN`] entries on, its blocks in one
/// vector with `i128` `U` sums: the streaming path's PAVA
/// ([`crate::fast::stream`]). The caller proved the `i128` bound of the
/// module documentation (`b_Y + b_K < 128`, `u_bits + b_K < 128`, `a`, `b`
/// and the columns on `i64`, `u_bits ≥ bits(max|U_i|)`); the `U` sums run in
/// `i64` when `N max|U| < 2^63`.
pub(crate) fn word_runs(xs: &[i64], us: &[i64], a: i64, b: i64, u_bits: u64) -> Vec<Run<i128>> {
    word_runs_on(xs, us, a, b, u_bits, halves::PARALLEL_MIN)
}

/// [`word_runs`], on two threads from `parallel_min` entries on.
pub(crate) fn word_runs_on(
    xs: &[i64],
    us: &[i64],
    a: i64,
    b: i64,
    u_bits: u64,
    parallel_min: usize,
) -> Vec<Run<i128>> {
    let n = xs.len();
    // |ΣU| ≤ N max|U| < 2^(bits(N) + bits(max|U|)) ≤ 2^63.
    if u64::from(usize::BITS - n.leading_zeros()) + u_bits <= 63 {
        halves::pava_parts::<i64>(xs, us, a, b, parallel_min).into_wide()
    } else {
        halves::pava_parts::<i128>(xs, us, a, b, parallel_min).into_wide()
    }
}

/// The word `V` of a loop's `U` sums, read from the `U` column.
pub(crate) trait FromColumn: Word {
    /// `U_i`; the caller has checked that the column's values fit `Self`
    /// (zero otherwise, like [`Column::get`]).
    fn from_column(c: &Column, i: usize) -> Self;
}

impl FromColumn for i128 {
    #[inline]
    fn from_column(c: &Column, i: usize) -> Self {
        match c {
            Column::Small(v) => i128::from(v[i]),
            _ => 0,
        }
    }
}

impl<const L: usize> FromColumn for Int<L> {
    #[inline]
    fn from_column(c: &Column, i: usize) -> Self {
        c.get::<L>(i)
    }
}

/// The loop's entries `(Y_i, U_i)` at one time on `L` limbs,
/// `Y_i = a X_i + b U_i`, computed from the shared columns: what the loop
/// reads, and what a 512-bit block of one entry recomputes ([`Sparse`]).
/// The width was proved by [`AtTime::new`]: the columns hold at most `L`
/// limbs and `b_Y + b_K < 64 L`.
#[derive(Debug, Clone)]
pub(crate) struct Entries<const L: usize> {
    x: Arc<Column>,
    u: Arc<Column>,
    a: Int<L>,
    b: Int<L>,
    /// `a` when it is a word: one 64-bit row instead of a full product.
    a_word: Option<i64>,
}

impl<const L: usize> Entries<L> {
    fn new(d: &IntegerData, at: &AtTime) -> Self {
        Entries {
            x: Arc::clone(&d.x_col),
            u: Arc::clone(&d.u_col),
            a: Int::from_bigint(&at.a).unwrap_or_default(),
            b: Int::from_bigint(&at.b).unwrap_or_default(),
            a_word: at.a.to_i64(),
        }
    }
    /// `(Y_i, U_i)`.
    #[inline]
    pub(crate) fn at<V: FromColumn>(&self, i: usize) -> (Int<L>, V) {
        // Both factors of each product and the products themselves are
        // below 2^(b_Y − 1) < 2^(64L − 2); `a, b ≥ 0`, so the product
        // skips their zero high limbs.
        let x = self.x.get::<L>(i);
        let ax = match self.a_word {
            Some(k) => x.wrapping_mul_i64(k),
            None => self.a.wrapping_mul(x),
        };
        let bu = match &*self.u {
            Column::Small(v) => self.b.wrapping_mul_i64(v[i]),
            c => self.b.wrapping_mul(c.get::<L>(i)),
        };
        (ax.wrapping_add(bu), V::from_column(&self.u, i))
    }
}

/// The tag of a [`Sparse`] block whose sums are stored.
const POOLED: u64 = 1 << 63;

/// PAVA blocks that store only what the data do not already hold: a block
/// of one entry (most of them, at small `t`) is the index of that entry,
/// its sums recomputed from the columns ([`Entries`]) when asked for; a
/// block of several entries keeps its sums. 8 bytes per block instead of
/// a 96-byte [`Run`]: the loop writes less fresh memory, and each fresh
/// page costs a page fault, more than the arithmetic of the particles on
/// it (docs/guide/performance.md).
#[derive(Debug, Clone)]
pub(crate) struct Sparse<const L: usize, V> {
    /// Block `j`, left to right: `POOLED | s` when its sums are
    /// `pooled[s]`, the index of its one entry otherwise.
    tags: Vec<u64>,
    /// The sums of the blocks of several entries, left to right.
    pooled: Vec<Run<Int<L>, V>>,
    entries: Entries<L>,
}

impl<const L: usize, V: FromColumn> Sparse<L, V> {
    fn len(&self) -> usize {
        self.tags.len()
    }
    fn of_tag(&self, tag: u64) -> Run<Int<L>, V> {
        if tag & POOLED == 0 {
            let (sy, su) = self.entries.at(tag as usize);
            Run { k: 1, sy, su }
        } else {
            self.pooled[(tag & !POOLED) as usize].clone()
        }
    }
    /// Block `j`'s sums.
    fn run(&self, j: usize) -> Run<Int<L>, V> {
        self.of_tag(self.tags[j])
    }
    /// Block `j`'s number of entries.
    fn size(&self, j: usize) -> u64 {
        let tag = self.tags[j];
        if tag & POOLED == 0 {
            1
        } else {
            self.pooled[(tag & !POOLED) as usize].k
        }
    }
}

/// [`pava_words`] on the entries `e`, the blocks kept [`Sparse`]: the
/// same pooling decisions on the same sums (the top block's sums are held
/// in locals, a block of one entry below it recomputed when the top is
/// pooled into the entry being read; after the entry is pushed, the top is
/// that entry's block).
fn pava_sparse<const L: usize, V: FromColumn>(n: usize, entries: Entries<L>) -> Sparse<L, V> {
    let mut s = Sparse {
        tags: Vec::with_capacity(n),
        pooled: Vec::new(),
        entries,
    };
    let mut top: Option<Run<Int<L>, V>> = None;
    for i in 0..n {
        let (mut sy, mut su) = s.entries.at::<V>(i);
        let mut k = 1u64;
        while let Some(t) = top.take() {
            let pool = projection::pools(t.sy.mul_k(k).cmp(&sy.mul_k(t.k)), || {
                t.su.mul_k(k).cmp(&su.mul_k(t.k))
            });
            if !pool {
                break;
            }
            sy = t.sy.add(&sy);
            su = t.su.add(&su);
            k += t.k;
            if s.tags.pop().is_some_and(|tag| tag & POOLED != 0) {
                s.pooled.pop();
            }
            top = s.tags.last().map(|&tag| s.of_tag(tag));
        }
        if k == 1 {
            s.tags.push(i as u64);
        } else {
            s.tags.push(POOLED | s.pooled.len() as u64);
            s.pooled.push(Run {
                k,
                sy,
                su: su.clone(),
            });
        }
        top = Some(Run { k, sy, su });
    }
    s
}

/// The state at `t ≥ 0` from the integer kernel: equal, field by field, to
/// [`crate::projection::state_at`] on `BigRational` (the tests check it).
pub fn state_at(d: &IntegerData, t: &BigRational) -> Result<State<BigRational>, Error> {
    if t.is_negative() {
        return Err(Error::NegativeTime { t: t.to_string() });
    }
    Ok(state_of_blocks(d, &blocks_at(d, t), t))
}

/// [`state_at`] for `data`, scaled here ([`IntegerData::new`], O(N)): the
/// one-shot form, equal field by field to [`crate::projection::state_at`].
pub fn state_of_data(
    data: &InitialData<BigRational>,
    t: &BigRational,
) -> Result<State<BigRational>, Error> {
    state_at(&IntegerData::new(data), t)
}

/// The [`State`] at `t` from exact PAVA blocks at `t + ε` on `d` (the
/// kernel's, or the adaptive solver's: the same blocks, one construction):
/// positions `x_i = x̃ + 2r i`, velocities the block means
/// (`eq:proj-u-micro`), the multipliers `λ` of `eq:dyn-micro` and the
/// contact clusters (`df:Omega-micro`).
pub fn state_of_blocks(d: &IntegerData, b: &Blocks, t: &BigRational) -> State<BigRational> {
    let n = d.n();
    let mut shifted = Vec::with_capacity(n);
    let mut positions = Vec::with_capacity(n);
    let mut velocities = Vec::with_capacity(n);
    let mut multipliers = Vec::with_capacity(n.saturating_sub(1));
    let big_n = BigInt::from(n);
    for (j, c) in b.clusters().into_iter().enumerate() {
        let (mean_y, mean_u) = (b.mean_y(j), b.mean_u(j));
        // λ on the block (`eq:dyn-micro`, one definition in
        // [`crate::contact`]): numerators over k D_u N.
        let den = BigInt::from(c.size) * &d.du * &big_n;
        let lambda = cluster_multiplier_numerators(&d.u[c.range()]);
        for (num, i) in lambda.into_iter().zip(c.range()) {
            shifted.push(mean_y.clone());
            // x_i = x̃ + 2r·i as one fraction (a single reduction).
            let (yn, yd) = (mean_y.numer(), mean_y.denom());
            let (rn, rd) = (d.two_r.numer(), d.two_r.denom());
            positions.push(crate::gcd::ratio(
                yn * rd + rn * yd * BigInt::from(i),
                yd * rd,
            ));
            velocities.push(mean_u.clone());
            if i + 1 < n {
                multipliers.push(if num.sign() == Sign::NoSign {
                    BigRational::zero()
                } else {
                    crate::gcd::ratio(num, den.clone())
                });
            }
        }
    }
    let clusters = runs(n, |j| shifted[j] == shifted[j + 1]);
    State {
        t: t.clone(),
        positions,
        velocities,
        multipliers,
        clusters,
    }
}

#[cfg(test)]
mod tests;
