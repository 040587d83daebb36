//! The exact event-driven cluster merge on fixed-width integers.
//!
//! [`IntegerTrajectory`] computes the same history as
//! [`Trajectory::<BigRational>::new`](crate::trajectory::Trajectory::new) —
//! the sticky dynamics whose positions are the projection formula
//! `x(t) = P_K(x⁰ + t u⁰)` of `prop:proj-micro` (`eq:proj-micro-x`), with the
//! velocities `u(t) = P_{H_{x(t)}}(u⁰)` of `eq:proj-u-micro` — but with no
//! `BigInt` or `BigRational` in the event loop, and converts it to a
//! [`Trajectory<BigRational>`] on request ([`IntegerTrajectory::into_trajectory`]),
//! equal field by field to the generic engine's (the tests check impulses,
//! join times and the states at the probe times).
//!
//! **Scaling.** The translated initial positions (`df:translat-x`) and the
//! velocities are written once over their least common denominators,
//! `x̃⁰_i = X_i / D_x`, `u⁰_i = U_i / D_u`, with integers `X_i`, `U_i`
//! (stored as `i64` when every value fits, else `i128`). A cluster `C` of `k`
//! particles moves rigidly, `x̃_C(t) = (Σ_C X_i + t D_x/D_u Σ_C U_i) / (k D_x)`,
//! so two adjacent clusters `L`, `R` (sizes `k_L`, `k_R`, integer sums
//! `SX`, `SU`) approach iff
//!
//! `closing = SU_L k_R − SU_R k_L > 0`
//!
//! and then meet at `t = (gap · D_u) / (closing · D_x)` with
//! `gap = SX_R k_L − SX_L k_R ≥ 0` (`gap = k_L k_R (X̄_R − X̄_L)` and the `X_i`
//! are non-decreasing, `df:tKN`). The factor `D_u / D_x` is common to every
//! candidate, so two candidate times compare as `gap₁ closing₂` against
//! `gap₂ closing₁` — a 256-bit product (`mul_wide`), never an overflow.
//! An event time is stored unreduced as the pair `(gap, closing)` and turned
//! into a lowest-terms [`BigRational`] only by
//! [`IntegerTrajectory::into_trajectory`].
//!
//! **Width bound.** Let `M = max(max|X_i|, max|U_i|)` and
//! `B = max(N, ⌊N²/4⌋) · M`. The engine runs on `i128` only when `B < 2^126`;
//! otherwise [`IntegerTrajectory::new`] falls back to the generic
//! [`Trajectory::<BigRational>::new`](crate::trajectory::Trajectory::new)
//! and [`IntegerTrajectory::engine`] says so ([`Engine::BigRational`]).
//! With `B < 2^126`:
//! * a cluster sum has `|S_C| ≤ k M ≤ N M ≤ B < 2^126` (merged clusters too);
//! * two adjacent clusters have `k_L + k_R ≤ N`, hence `k_L k_R ≤ ⌊N²/4⌋`, and
//!   each product `|SX_R k_L|`, `|SX_L k_R|`, `|SU_L k_R|`, `|SU_R k_L|` is
//!   at most `k_L k_R M ≤ B < 2^126`;
//! * so `|gap|`, `|closing| < 2 · 2^126 = 2^127`: every intermediate value
//!   fits `i128` (and the release profile's overflow checks would report a
//!   mistake in this bound rather than wrap);
//! * the cross products `gap₁ closing₂ < 2^254` are computed exactly on 256
//!   bits.
//!
//! When moreover `N M < 2^63` the cluster sums are kept in `i64` (then
//! `|S_C| k < 2^95` and one machine multiplication gives each product).
//!
//! **Float filter.** Each candidate also carries `τ = fl(fl(gap) / fl(closing))`,
//! compared first; the exact 256-bit comparison runs only when two `τ` are
//! within a relative `10⁻⁹` of each other ([`FILTER`] explains why the answer
//! is still exact). The queue itself orders candidates by a lower bound of
//! `τ` only; exactness is restored around each instant (see below).
//!
//! **Semantics** (identical to [`crate::trajectory`]): initial clusters are
//! the runs of contacts (`X_i = X_{i+1}`) with equal velocities
//! (`U_i = U_{i+1}`); candidates are ordered by time, then by the first
//! particle of the left cluster; every pair meeting at the same instant is
//! merged in the same step (chains of three or more clusters included), and
//! one [`Impulse`] is recorded per cluster formed at that instant, with all
//! its pre-collision parts left to right.
//!
//! **Event loop** (memory is the bottleneck at large N, so the layout is
//! chosen for it):
//! * one node per particle; a cluster keeps its sums and size at both of its
//!   ends, so the pair at a boundary `b` is read from the neighbouring nodes
//!   `b − 1`, `b`, and a merge touches only the boundary's neighbourhood and
//!   the two outer ends;
//! * candidates wait in a monotone radix queue keyed by a lower bound of
//!   their time (lazy deletion: re-keying a boundary bumps its stamp, stale
//!   entries are dropped when they come out), taken out 16 at a time so that
//!   the cache misses of coming events overlap;
//! * the exact order is restored in a small window around the earliest
//!   candidate (see `run`): the queue only needs approximate keys.
//!
//! Every event costs O(1) node accesses and O(1) amortized queue work (an
//! entry moves at most 16 times between buckets); candidates whose times
//! agree with the current instant to about 12 digits without being equal go
//! through a binary heap, O(log N) each. At most N − 1 merges: O(N log N) in
//! all, O(N) memory (the parts of every impulse are kept as a flat list of
//! part boundaries, the times as unreduced `(gap, closing)` pairs).

use std::cmp::Ordering;
use std::collections::BinaryHeap;

use num_bigint::BigInt;
use num_integer::Integer;
use num_rational::BigRational;
use num_traits::{ToPrimitive, Zero};

use crate::cluster::Cluster;
use crate::contact::Impulse;
use crate::fast::scaling::{scale_i128, MulSmall, Scaled};
use crate::initial::InitialData;
use crate::trajectory::Trajectory;

/// Which engine computed an [`IntegerTrajectory`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Engine {
    /// The integer engine; every scaled datum `X_i`, `U_i` fitted `i64`.
    Int64,
    /// The integer engine; the scaled data needed `i128`.
    Int128,
    /// The generic [`Trajectory::<BigRational>::new`](Trajectory::new): the
    /// data were too large for the `i128` bound (see the module docs).
    BigRational,
}

/// Particle indices, instants and join codes are `u32`: larger systems
/// take the generic engine.
const MAX_N: usize = (u32::MAX / 2) as usize;
/// `join` code: never joined.
const JOIN_NEVER: u32 = u32::MAX;
/// `join` code: joined at `t = 0` (an initial cluster).
const JOIN_ZERO: u32 = u32::MAX - 1;

/// Relative margin of the float filter: `τ_a` and `τ_b` decide the order
/// alone when `τ_a < τ_b (1 − FILTER)` (or the reverse).
///
/// Why this is exact. Let `u = 2^-53`. `to_f64` converts an integer
/// `|v| < 2^127` with relative error at most `3u` (two correctly rounded
/// halves and one correctly rounded sum of same-sign terms; exactly
/// `|δ| ≤ (1+u)² − 1 + u < 3.1u`), the division adds one rounding, so
/// `τ = t (1+δ₁)(1+δ₃)/(1+δ₂)` with `|δ₁|, |δ₂| < 3.1u`, `|δ₃| ≤ u`, and
/// `t (1 − 8u) ≤ τ ≤ t (1 + 8u)` for `t = gap/closing ≥ 0` (`τ ≥ 2^-127`
/// when `t > 0`, far from the subnormal range; `τ = 0` iff `t = 0`). If
/// `τ_a < τ_b (1 − FILTER)` then
/// `t_a (1 − 8u) ≤ τ_a < τ_b (1 − FILTER) ≤ t_b (1 + 8u)(1 − FILTER)`, and
/// `(1 + 8u)(1 − FILTER) < 1 − 8u` because `16u ≈ 1.8·10⁻¹⁵ < FILTER (1 + 8u)`:
/// hence `t_a < t_b` exactly (the products `τ_b (1 − FILTER)` are themselves
/// rounded, by a relative `u` that the margin absorbs as well). When neither
/// strict inequality holds the exact cross-multiplication decides (equal
/// times always land there).
pub const FILTER: f64 = 1e-9;
const KEEP: f64 = 1.0 - FILTER;

/// `a · b` exactly on 256 bits: `(negative, hi, lo)` with
/// `|a b| = hi · 2^128 + lo` (`negative` is false for a zero product).
fn mul_wide(a: i128, b: i128) -> (bool, u128, u128) {
    const MASK: u128 = (1u128 << 64) - 1;
    let negative = a != 0 && b != 0 && ((a < 0) != (b < 0));
    let (x, y) = (a.unsigned_abs(), b.unsigned_abs());
    let (x1, x0) = (x >> 64, x & MASK);
    let (y1, y0) = (y >> 64, y & MASK);
    // Each partial product is below 2^128.
    let p00 = x0 * y0;
    let p01 = x0 * y1;
    let p10 = x1 * y0;
    let p11 = x1 * y1;
    // Below 3 · 2^64: no overflow.
    let mid = (p00 >> 64) + (p01 & MASK) + (p10 & MASK);
    let lo = (p00 & MASK) | ((mid & MASK) << 64);
    // The whole product is below 2^256, so the high word fits.
    let hi = p11 + (p01 >> 64) + (p10 >> 64) + (mid >> 64);
    (negative, hi, lo)
}

/// Compares `a·b` with `c·d` exactly.
fn cmp_products(a: i128, b: i128, c: i128, d: i128) -> Ordering {
    if let (Some(p), Some(q)) = (a.mul_small(b), c.mul_small(d)) {
        return p.cmp(&q);
    }
    let (sp, hp, lp) = mul_wide(a, b);
    let (sq, hq, lq) = mul_wide(c, d);
    match (sp, sq) {
        (false, false) => (hp, lp).cmp(&(hq, lq)),
        (true, true) => (hq, lq).cmp(&(hp, lp)),
        (false, true) => Ordering::Greater,
        (true, false) => Ordering::Less,
    }
}

/// `v` as a double, within a relative `3.1 · 2^-53` (see [`FILTER`]): one
/// correctly rounded conversion when `|v| < 2^63`, else the two 64-bit
/// halves of `|v|` converted separately — no slow `i128 → f64` library
/// call.
#[inline]
fn to_f64(v: i128) -> f64 {
    const TWO64: f64 = 18_446_744_073_709_551_616.0;
    let m = v.unsigned_abs();
    let f = match i64::try_from(m) {
        // One correctly rounded conversion.
        Ok(small) => small as f64,
        Err(_) => (m >> 64) as u64 as f64 * TWO64 + m as u64 as f64,
    };
    if v < 0 {
        -f
    } else {
        f
    }
}

/// A candidate time `gap / closing` (`closing > 0`) with its float
/// approximation (the common factor `D_u / D_x` left aside).
#[derive(Debug, Clone, Copy, PartialEq)]
struct Time {
    gap: i128,
    closing: i128,
    approx: f64,
}

impl Time {
    #[inline]
    fn new(gap: i128, closing: i128) -> Self {
        Time {
            gap,
            closing,
            approx: to_f64(gap) / to_f64(closing),
        }
    }
    /// Exact comparison, through the float filter ([`FILTER`]).
    #[inline]
    fn cmp(&self, other: &Time) -> Ordering {
        if self.approx < other.approx * KEEP {
            Ordering::Less
        } else if other.approx < self.approx * KEEP {
            Ordering::Greater
        } else {
            self.cmp_exact(other)
        }
    }
    /// `gap₁ / closing₁` against `gap₂ / closing₂` by cross-multiplication
    /// (both closings are positive).
    fn cmp_exact(&self, other: &Time) -> Ordering {
        cmp_products(self.gap, other.closing, other.gap, self.closing)
    }
}

impl Time {
    /// A lower bound `lo ≤ t` and an upper bound `hi ≥ t` of the exact time
    /// (in the units of `gap / closing`), as doubles: `τ (1 ∓ 2^-40)`. With
    /// `τ ∈ [t (1 − 8u), t (1 + 8u)]` ([`FILTER`]) and one more rounding,
    /// `lo ≤ t (1 + 8u)(1 − 2^-40)(1 + u) < t` because `2^-40 > 10u`; `hi`
    /// likewise. Both are non-negative (`gap ≥ 0`), so their bit patterns
    /// order like their values.
    #[inline]
    fn lo(&self) -> u64 {
        (self.approx.abs() * (1.0 - BRACKET)).to_bits() >> KEY_SHIFT
    }
    #[inline]
    fn hi(&self) -> u64 {
        (self.approx.abs() * (1.0 + BRACKET)).to_bits() >> KEY_SHIFT
    }
}

/// Queue keys drop the last 12 bits of the doubles' patterns (monotone, and
/// far below the bracket's width of about `2^13` units in the last place):
/// fewer levels for the radix queue to sort.
const KEY_SHIFT: u32 = 12;

/// Relative half-width of the bracket `[lo, hi]` around a candidate time.
const BRACKET: f64 = 1.0 / (1u64 << 40) as f64;

/// A queued candidate: the lower bound of its time ([`Time::lo`]), its
/// boundary, and the stamp the boundary had when it was queued (the entry is
/// stale once the stamp moved on).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
struct Entry {
    key: u64,
    slot: u32,
    stamp: u32,
}

/// An entry set aside with its exact time, in a max-heap reversed to pop the
/// earliest exact time first (then the leftmost boundary).
#[derive(Debug, Clone, Copy)]
struct Near {
    t: Time,
    entry: Entry,
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
struct RadixQueue {
    buckets: Vec<Vec<Entry>>,
    /// The smallest key of each non-empty bucket.
    min: Vec<u64>,
    /// Bit `i % 64` of word `i / 64` set iff bucket `i` is non-empty.
    occupied: [u64; 5],
    last: u64,
}

/// Buckets of a [`RadixQueue`]: bucket 0, then 16 digits for each of the 16
/// digit positions.
const BUCKETS: usize = 1 + 16 * 16;

impl RadixQueue {
    fn new() -> Self {
        RadixQueue {
            buckets: (0..BUCKETS).map(|_| Vec::new()).collect(),
            min: vec![u64::MAX; BUCKETS],
            occupied: [0; 5],
            last: 0,
        }
    }

    #[inline]
    fn bucket(&self, key: u64) -> usize {
        let x = key ^ self.last;
        if x == 0 {
            return 0;
        }
        let level = (63 - x.leading_zeros()) / 4;
        1 + 16 * level as usize + ((key >> (4 * level)) & 15) as usize
    }

    /// Queues `e`; `e.key ≥ last` is the caller's duty.
    #[inline]
    fn push(&mut self, e: Entry) {
        debug_assert!(e.key >= self.last);
        let b = self.bucket(e.key);
        self.buckets[b].push(e);
        self.min[b] = self.min[b].min(e.key);
        self.occupied[b / 64] |= 1 << (b % 64);
    }

    /// The lowest non-empty bucket.
    fn lowest(&self) -> Option<usize> {
        self.occupied
            .iter()
            .enumerate()
            .find(|(_, w)| **w != 0)
            .map(|(i, w)| 64 * i + w.trailing_zeros() as usize)
    }

    /// Takes out an entry of the smallest key if that key is at most
    /// `bound`. `last` never moves beyond `bound`, so that new keys down to
    /// the current instant can still be pushed.
    fn pop_if_le(&mut self, bound: u64) -> Option<Entry> {
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
/// of the clusters (measured: a gain at N = 10^6, a loss at N = 10^5).
const DEEP_BYTES: usize = 8 << 20;

/// How many queued entries are taken out ahead of time.
const AHEAD: usize = 16;

/// The next [`AHEAD`] entries of the queue, taken out in key order so that
/// their nodes are loaded together: the cache misses of the coming events
/// overlap instead of following one another. Every key still in the queue
/// is at least as large as these; a new entry whose key is below the
/// queue's `last` goes to the small heap `early` instead, and the smaller
/// of the two fronts comes first.
#[derive(Debug, Default)]
struct Lookahead {
    entries: std::collections::VecDeque<Entry>,
    early: BinaryHeap<std::cmp::Reverse<Entry>>,
    /// Also touch the outer ends of the clusters (worth it only when the
    /// nodes do not fit in the caches).
    deep: bool,
}

impl Lookahead {
    /// The entry of smallest key if that key is at most `bound`.
    #[inline]
    fn take_le<W>(
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

    fn refill<W>(&mut self, queue: &mut RadixQueue, nodes: &[Node<W>], tags: &[u8]) {
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
        for e in self.entries.iter().filter(|_| self.deep) {
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
    fn insert(&mut self, e: Entry) {
        self.early.push(std::cmp::Reverse(e));
    }
}

/// The word a cluster sum is kept in: `i64` when `N · M < 2^63` (every
/// cluster sum then fits), else `i128` (see the width bound).
trait SumWord: Copy + Default + std::ops::AddAssign + std::ops::Add<Output = Self> {
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
struct Node<W> {
    sum_x: W,
    sum_u: W,
    /// Number of particles of the cluster this node ends; 0 inside.
    size: u32,
    /// The join code of the pair `(i − 1, i)`, for the node at index `i`.
    join: u32,
    /// Bumped whenever the pair at boundary `i` changes: queued entries
    /// with an older stamp are stale. (It is bumped at most twice per merge
    /// next to the boundary, fewer than `2N < 2^32` times: it never wraps
    /// around to a queued value.)
    stamp: u32,
}

/// The candidate collision time of adjacent clusters, if they approach.
#[inline]
fn meeting<W: SumWord>(l: &Node<W>, r: &Node<W>) -> Option<Time> {
    let closing = l.sum_u.times(r.size) - r.sum_u.times(l.size);
    if closing <= 0 {
        return None;
    }
    Some(Time::new(
        r.sum_x.times(l.size) - l.sum_x.times(r.size),
        closing,
    ))
}

/// The history found by the integer engine, before conversion.
#[derive(Debug, Clone, Default, PartialEq)]
struct History {
    /// Distinct collision instants `(gap, closing)`, increasing.
    instants: Vec<(i128, i128)>,
    /// One entry per cluster formed: `(instant, offset into parts)`.
    impulses: Vec<(u32, u32)>,
    /// For each impulse, the first particle of each part, left to right,
    /// then one past the cluster's last particle.
    parts: Vec<u32>,
    /// For each pair `(j, j+1)`: the instant it joins, or [`JOIN_ZERO`],
    /// [`JOIN_NEVER`].
    join: Vec<u32>,
}

/// The event loop (see the module docs); `x`, `u` satisfy the width bound.
///
/// **Finding an instant.** Every live candidate `e` has a key
/// `lo(e) ≤ t(e) ≤ hi(e)` ([`Time::lo`]). The earliest instant is found in
/// three steps:
/// 1. `e₁`, the live entry of smallest key (the first live entry of the
///    [`Lookahead`], which holds the smallest keys of the queue);
/// 2. the *window*: every live entry with `lo ≤ hi(e₁)`. It contains every
///    entry whose exact time is at most `t(e₁)` — such an entry has
///    `lo ≤ t ≤ t(e₁) ≤ hi(e₁)` — hence the earliest exact time `t*` and all
///    the pairs meeting at `t*`;
/// 3. the exact times of the window entries (recomputed from the clusters,
///    unchanged since the entry was queued since its stamp is current):
///    those equal to `t*` merge now; the others, later than `t*` but within
///    the bracket, wait in `near`, a binary heap ordered by exact time whose
///    top takes part in steps 2 and 3 (`hi` of the top bounds the window
///    too).
///
/// Both `near` and the lookahead's `early` heap (new candidates whose key
/// falls below the queue's last key) are almost always empty: they need
/// times equal to within the bracket `2^-40`.
fn run<T: Copy + PartialEq + Into<W>, W: SumWord>(x: &[T], u: &[T]) -> History {
    let n = x.len();
    // At most N − 1 merges: reserving that much costs address space only
    // (untouched pages are never mapped) and spares the copies of growth.
    let mut hist = History {
        instants: Vec::with_capacity(n),
        impulses: Vec::with_capacity(n),
        parts: Vec::with_capacity(3 * n),
        join: Vec::new(),
    };
    let mut nodes = vec![
        Node::<W> {
            join: JOIN_NEVER,
            ..Node::default()
        };
        n
    ];
    // Initial clusters: contacts with equal velocities.
    let mut first = 0usize;
    for j in 0..n {
        if j + 1 == n || x[j] != x[j + 1] || u[j] != u[j + 1] {
            let (mut sx, mut su) = (W::default(), W::default());
            for i in first..=j {
                sx += x[i].into();
                su += u[i].into();
            }
            for end in [first, j] {
                let node = &mut nodes[end];
                node.sum_x = sx;
                node.sum_u = su;
                node.size = (j + 1 - first) as u32;
            }
            for node in &mut nodes[first + 1..=j] {
                node.join = JOIN_ZERO;
            }
            first = j + 1;
        }
    }
    // The exact time of the pair at a live boundary `b`, if it approaches.
    let time_of = |nodes: &[Node<W>], b: usize| meeting(&nodes[b - 1], &nodes[b]);
    // The low byte of every stamp, in a compact array (one byte a particle
    // stays in cache where the nodes do not): most stale entries are
    // rejected here; a matching byte is confirmed by the full stamp.
    let mut tags = vec![0u8; n];
    let mut queue = RadixQueue::new();
    let mut near: BinaryHeap<Near> = BinaryHeap::new();
    let mut b = nodes.first().map_or(n, |node| node.size as usize);
    while b < n {
        if let Some(t) = time_of(&nodes, b) {
            queue.push(Entry {
                key: t.lo(),
                slot: b as u32,
                stamp: 0,
            });
        }
        b += nodes[b].size as usize;
    }

    let mut ahead = Lookahead {
        deep: std::mem::size_of_val(nodes.as_slice()) > DEEP_BYTES,
        ..Lookahead::default()
    };
    let mut window: Vec<(Entry, Time)> = Vec::new();
    let mut pending: Vec<u32> = Vec::new();
    let mut fresh: Vec<u32> = Vec::new();
    let mut bounds: Vec<u32> = Vec::new();
    loop {
        let live = |nodes: &[Node<W>], tags: &[u8], e: &Entry| {
            tags[e.slot as usize] == e.stamp as u8 && nodes[e.slot as usize].stamp == e.stamp
        };
        while near.peek().is_some_and(|w| !live(&nodes, &tags, &w.entry)) {
            near.pop();
        }
        // 1. The first live entry of the queue (smallest `lo`).
        window.clear();
        while let Some(e) = ahead.take_le(&mut queue, u64::MAX, &nodes, &tags) {
            if live(&nodes, &tags, &e) {
                if let Some(t) = time_of(&nodes, e.slot as usize) {
                    window.push((e, t));
                    break;
                }
            }
        }
        // 2. An upper bound of the earliest time `t*`, and every queued
        //    entry whose `lo` is below it.
        let bound = match (window.first(), near.peek()) {
            (None, None) => break,
            (Some(w), None) => w.1.hi(),
            (None, Some(m)) => m.t.hi(),
            (Some(w), Some(m)) => w.1.hi().min(m.t.hi()),
        };
        while let Some(e) = ahead.take_le(&mut queue, bound, &nodes, &tags) {
            if live(&nodes, &tags, &e) {
                if let Some(t) = time_of(&nodes, e.slot as usize) {
                    window.push((e, t));
                }
            }
        }
        // 3. `t*` exactly; the later window entries wait in `near`. (The
        //    usual window is one entry and `near` is empty: nothing to
        //    compare.)
        pending.clear();
        let t = match (window.as_slice(), near.peek()) {
            ([(entry, t)], None) => {
                pending.push(entry.slot);
                *t
            }
            _ => {
                let mut t = match (window.first(), near.peek()) {
                    (Some(w), _) => w.1,
                    (None, Some(m)) => m.t,
                    (None, None) => break,
                };
                for tw in window.iter().map(|w| &w.1).chain(near.peek().map(|m| &m.t)) {
                    if tw.cmp(&t) == Ordering::Less {
                        t = *tw;
                    }
                }
                for &(entry, tw) in &window {
                    if tw.cmp(&t) == Ordering::Greater {
                        near.push(Near { t: tw, entry });
                    } else {
                        pending.push(entry.slot);
                    }
                }
                while let Some(m) = near.peek() {
                    if live(&nodes, &tags, &m.entry) {
                        if m.t.cmp(&t) == Ordering::Greater {
                            break;
                        }
                        pending.push(m.entry.slot);
                    }
                    near.pop();
                }
                t
            }
        };
        let instant = hist.instants.len() as u32;
        hist.instants.push((t.gap, t.closing));
        fresh.clear();
        bounds.clear();
        while !pending.is_empty() {
            // Left to right: a chain of pairs meeting at `t` becomes one
            // cluster (the left part of a later pair may have been formed
            // earlier in this loop; it ends at the boundary all the same).
            pending.sort_unstable();
            let batch = fresh.len();
            for &r in &pending {
                let ri = r as usize;
                let (left, right) = (nodes[ri - 1], nodes[ri]);
                if left.size == 0 || right.size == 0 {
                    continue;
                }
                // Merge `f .. r` and `r .. e`; the boundary `r` is gone.
                let f = ri - left.size as usize;
                let e = ri + right.size as usize;
                nodes[ri].join = instant;
                nodes[ri].stamp = nodes[ri].stamp.wrapping_add(1);
                tags[ri] = nodes[ri].stamp as u8;
                if ri - 1 != f {
                    nodes[ri - 1].size = 0;
                }
                if ri != e - 1 {
                    nodes[ri].size = 0;
                }
                let (sx, su) = (left.sum_x + right.sum_x, left.sum_u + right.sum_u);
                for end in [f, e - 1] {
                    let node = &mut nodes[end];
                    node.sum_x = sx;
                    node.sum_u = su;
                    node.size = left.size + right.size;
                }
                bounds.push(r);
                fresh.push(f as u32);
            }
            pending.clear();
            // New candidates on both sides of every cluster formed. One
            // meeting at `t` or before would join this instant, as in
            // `Trajectory::new` (it cannot happen with exact times).
            for k in batch..fresh.len() {
                let f = fresh[k] as usize;
                if nodes[f].size == 0 || (k > batch && fresh[k - 1] == fresh[k]) {
                    continue;
                }
                let e = f + nodes[f].size as usize;
                for b in [f, e] {
                    if b == 0 || b >= n {
                        continue;
                    }
                    let stamp = nodes[b].stamp.wrapping_add(1);
                    nodes[b].stamp = stamp;
                    tags[b] = stamp as u8;
                    let Some(tb) = time_of(&nodes, b) else {
                        continue;
                    };
                    let entry = Entry {
                        key: tb.lo(),
                        slot: b as u32,
                        stamp,
                    };
                    if tb.cmp(&t) != Ordering::Greater {
                        pending.push(b as u32);
                        nodes[b].stamp = stamp.wrapping_add(1);
                        tags[b] = nodes[b].stamp as u8;
                    } else if entry.key >= queue.last {
                        queue.push(entry);
                    } else {
                        ahead.insert(entry);
                    }
                }
            }
            pending.sort_unstable();
            pending.dedup();
        }
        // One impulse per cluster formed at `t`: its parts are split at the
        // boundaries joined at `t`.
        fresh.retain(|&f| nodes[f as usize].size != 0);
        fresh.sort_unstable();
        fresh.dedup();
        bounds.sort_unstable();
        let mut b = 0;
        for &f in &fresh {
            let end = f + nodes[f as usize].size;
            hist.impulses.push((instant, hist.parts.len() as u32));
            hist.parts.push(f);
            while b < bounds.len() && bounds[b] < end {
                debug_assert!(bounds[b] > f);
                hist.parts.push(bounds[b]);
                b += 1;
            }
            hist.parts.push(end);
        }
    }
    hist.join = nodes.iter().skip(1).map(|node| node.join).collect();
    hist.instants.shrink_to_fit();
    hist.impulses.shrink_to_fit();
    hist.parts.shrink_to_fit();
    hist
}

/// `true` when `max(N, ⌊N²/4⌋) · M < 2^126` (the width bound of the module
/// docs).
fn within_bound(s: &Scaled) -> bool {
    let n = s.x.len() as u128;
    let m =
        s.x.iter()
            .chain(&s.u)
            .map(|v| v.unsigned_abs())
            .max()
            .unwrap_or(0);
    let pairs = n.max(n * n / 4);
    pairs.checked_mul(m).is_some_and(|b| b < 1u128 << 126)
}

/// The scaled data in the narrowest word that holds them.
#[derive(Debug, Clone)]
enum Words {
    I64(Vec<i64>, Vec<i64>),
    I128(Vec<i128>, Vec<i128>),
}

impl Words {
    fn x(&self, i: usize) -> i128 {
        match self {
            Words::I64(x, _) => i128::from(x[i]),
            Words::I128(x, _) => x[i],
        }
    }
    fn u(&self, i: usize) -> i128 {
        match self {
            Words::I64(_, u) => i128::from(u[i]),
            Words::I128(_, u) => u[i],
        }
    }
    fn len(&self) -> usize {
        match self {
            Words::I64(x, _) => x.len(),
            Words::I128(x, _) => x.len(),
        }
    }
}

/// `M = max(max|X_i|, max|U_i|)`.
fn max_abs(w: &Words) -> u128 {
    match w {
        Words::I64(x, u) => x
            .iter()
            .chain(u)
            .map(|v| u128::from(v.unsigned_abs()))
            .max(),
        Words::I128(x, u) => x.iter().chain(u).map(|v| v.unsigned_abs()).max(),
    }
    .unwrap_or(0)
}

/// The integer engine's result, with what the conversion needs.
#[derive(Debug, Clone)]
struct IntegerHistory {
    words: Words,
    dx: BigInt,
    du: BigInt,
    radius: BigRational,
    hist: History,
}

#[derive(Debug, Clone)]
enum Inner {
    Integer(Box<IntegerHistory>),
    Generic(Box<Trajectory<BigRational>>),
}

/// The sticky history of one initial datum, computed on fixed-width
/// integers (see the module docs); [`IntegerTrajectory::into_trajectory`]
/// gives the same [`Trajectory<BigRational>`] as
/// [`Trajectory::new`](crate::trajectory::Trajectory::new).
#[derive(Debug, Clone)]
pub struct IntegerTrajectory {
    inner: Inner,
}

impl IntegerTrajectory {
    /// Computes every collision of the sticky dynamics started from `data`:
    /// on `i128` when the width bound holds, otherwise with the generic
    /// `BigRational` engine ([`IntegerTrajectory::engine`] tells which).
    pub fn new(data: &InitialData<BigRational>) -> IntegerTrajectory {
        let scaled = if data.n() < MAX_N {
            scale_i128(data)
        } else {
            None
        };
        let Some(s) = scaled.filter(within_bound) else {
            return IntegerTrajectory {
                inner: Inner::Generic(Box::new(Trajectory::new(data.clone()))),
            };
        };
        let Scaled { x, u, dx, du } = s;
        let narrow = |v: &[i128]| v.iter().map(|&a| i64::try_from(a).ok()).collect();
        let words = match (narrow(&x), narrow(&u)) {
            (Some(x), Some(u)) => Words::I64(x, u),
            _ => Words::I128(x, u),
        };
        // Cluster sums in i64 when N · M < 2^63.
        let narrow_sums = (words.len() as u128)
            .checked_mul(max_abs(&words))
            .is_some_and(|b| b < 1u128 << 63);
        let hist = match (&words, narrow_sums) {
            (Words::I64(x, u), true) => run::<i64, i64>(x, u),
            (Words::I64(x, u), false) => run::<i64, i128>(x, u),
            (Words::I128(x, u), _) => run::<i128, i128>(x, u),
        };
        IntegerTrajectory {
            inner: Inner::Integer(Box::new(IntegerHistory {
                words,
                dx,
                du,
                radius: data.radius().clone(),
                hist,
            })),
        }
    }

    /// The engine that ran.
    pub fn engine(&self) -> Engine {
        match &self.inner {
            Inner::Integer(h) => match h.words {
                Words::I64(..) => Engine::Int64,
                Words::I128(..) => Engine::Int128,
            },
            Inner::Generic(_) => Engine::BigRational,
        }
    }

    /// The number of clusters formed (one [`Impulse`] each).
    pub fn events(&self) -> usize {
        match &self.inner {
            Inner::Integer(h) => h.hist.impulses.len(),
            Inner::Generic(t) => t.impulses().len(),
        }
    }

    /// The number of distinct collision instants.
    pub fn instants(&self) -> usize {
        match &self.inner {
            Inner::Integer(h) => h.hist.instants.len(),
            Inner::Generic(t) => {
                let mut count = 0;
                let mut last: Option<&BigRational> = None;
                for imp in t.impulses() {
                    if last != Some(&imp.t) {
                        count += 1;
                        last = Some(&imp.t);
                    }
                }
                count
            }
        }
    }

    /// The exact history as a [`Trajectory<BigRational>`]: every time and
    /// velocity reduced to lowest terms, equal to
    /// [`Trajectory::new`](crate::trajectory::Trajectory::new) on the same
    /// data.
    pub fn into_trajectory(self) -> Trajectory<BigRational> {
        match self.inner {
            Inner::Generic(t) => *t,
            Inner::Integer(h) => h.convert(),
        }
    }
}

/// The exact sticky history of `data`, computed by the integer engine and
/// converted: equal to [`Trajectory::new`](crate::trajectory::Trajectory::new)
/// (the tests check it), and the way the CLI computes every trajectory.
pub fn trajectory(data: &InitialData<BigRational>) -> Trajectory<BigRational> {
    IntegerTrajectory::new(data).into_trajectory()
}

/// `num / den` in lowest terms (`den > 0`), on `i128` when possible.
fn ratio(num: i128, den: i128) -> BigRational {
    let g = num.unsigned_abs().gcd(&den.unsigned_abs());
    if g == 0 {
        return BigRational::zero();
    }
    // `g` divides both and is at most `|den| ≤ i128::MAX`.
    let g = g as i128;
    BigRational::new_raw(BigInt::from(num / g), BigInt::from(den / g))
}

/// `num / (k d)` in lowest terms, `d > 0`.
fn ratio_scaled(num: i128, k: i128, d: &BigInt, d_small: Option<i128>) -> BigRational {
    match d_small.and_then(|d| d.checked_mul(k)) {
        Some(den) => ratio(num, den),
        None => BigRational::new(BigInt::from(num), d * BigInt::from(k)),
    }
}

impl IntegerHistory {
    fn convert(self) -> Trajectory<BigRational> {
        let IntegerHistory {
            words,
            dx,
            du,
            radius,
            hist,
        } = self;
        let n = words.len();
        let two_r = &radius + &radius;
        // The initial data, rebuilt exactly: x⁰_i = X_i / D_x + 2r i.
        let (rn, rd) = (two_r.numer(), two_r.denom());
        let den = &dx * rd;
        let rn_dx = rn * &dx;
        let mut positions = Vec::with_capacity(n);
        let mut velocities = Vec::with_capacity(n);
        let du_small = du.to_i128();
        for i in 0..n {
            positions.push(BigRational::new(
                BigInt::from(words.x(i)) * rd + &rn_dx * BigInt::from(i),
                den.clone(),
            ));
            velocities.push(ratio_scaled(words.u(i), 1, &du, du_small));
        }
        let data = match InitialData::new(radius, positions, velocities) {
            Ok(d) => d,
            Err(e) => unreachable_data(e),
        };
        // t = gap D_u / (closing D_x).
        let times: Vec<BigRational> = hist
            .instants
            .iter()
            .map(|&(gap, closing)| {
                match (
                    du_small.and_then(|d| gap.checked_mul(d)),
                    dx.to_i128().and_then(|d| closing.checked_mul(d)),
                ) {
                    (Some(a), Some(b)) => ratio(a, b),
                    _ => BigRational::new(BigInt::from(gap) * &du, BigInt::from(closing) * &dx),
                }
            })
            .collect();
        let join_time = hist
            .join
            .iter()
            .map(|&code| match code {
                JOIN_NEVER => None,
                JOIN_ZERO => Some(BigRational::zero()),
                k => Some(times[k as usize].clone()),
            })
            .collect();
        // Prefix sums of U: |Σ| ≤ N M < 2^126.
        let mut prefix_u = Vec::with_capacity(n + 1);
        let mut acc = 0i128;
        prefix_u.push(acc);
        for i in 0..n {
            acc += words.u(i);
            prefix_u.push(acc);
        }
        let velocity = |first: usize, end: usize| {
            let k = (end - first) as i128;
            ratio_scaled(prefix_u[end] - prefix_u[first], k, &du, du_small)
        };
        let mut impulses = Vec::with_capacity(hist.impulses.len());
        for (k, &(instant, off)) in hist.impulses.iter().enumerate() {
            let stop = hist
                .impulses
                .get(k + 1)
                .map_or(hist.parts.len(), |&(_, o)| o as usize);
            let bounds = &hist.parts[off as usize..stop];
            let mut parts = Vec::with_capacity(bounds.len() - 1);
            let mut part_velocities = Vec::with_capacity(bounds.len() - 1);
            for w in bounds.windows(2) {
                let (a, b) = (w[0] as usize, w[1] as usize);
                parts.push(Cluster {
                    first: a,
                    size: b - a,
                });
                part_velocities.push(velocity(a, b));
            }
            let (first, end) = (bounds[0] as usize, bounds[bounds.len() - 1] as usize);
            impulses.push(Impulse {
                t: times[instant as usize].clone(),
                cluster: Cluster {
                    first,
                    size: end - first,
                },
                parts,
                part_velocities,
                velocity: velocity(first, end),
                n,
            });
        }
        Trajectory::from_parts(data, join_time, impulses)
    }
}

#[cold]
fn unreachable_data(e: crate::Error) -> InitialData<BigRational> {
    // The data are rebuilt from admissible data, value for value.
    panic!("merge: rebuilt initial data are invalid: {e}")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::{initial_data, Limits, SplitMix64};
    use crate::trajectory::probe_times;
    use num_traits::{One, Signed};

    fn q(n: i64, d: i64) -> BigRational {
        BigRational::new(BigInt::from(n), BigInt::from(d))
    }

    fn big(v: &BigInt) -> BigRational {
        BigRational::from_integer(v.clone())
    }

    /// Both engines on `data`: impulses, join times and states at the probe
    /// times must agree.
    fn agree(data: &InitialData<BigRational>) -> IntegerTrajectory {
        let it = IntegerTrajectory::new(data);
        let events = it.events();
        let fast = it.clone().into_trajectory();
        let slow = Trajectory::new(data.clone());
        assert_eq!(fast.data(), data);
        assert_eq!(events, slow.impulses().len());
        assert_eq!(fast.impulses(), slow.impulses());
        assert_eq!(fast.join_times(), slow.join_times());
        for t in probe_times(&slow, Some(8)) {
            assert_eq!(fast.at(&t).unwrap(), slow.at(&t).unwrap(), "t = {t}");
        }
        it
    }

    #[test]
    fn mul_wide_matches_bigint() {
        let mut rng = SplitMix64::new(3);
        let edge = [0i128, 1, -1, i128::MAX, i128::MIN + 1, 1 << 64, -(1 << 100)];
        let mut values: Vec<i128> = edge.to_vec();
        for _ in 0..200 {
            let v = (i128::from(rng.next_u64()) << 64 | i128::from(rng.next_u64()))
                >> (rng.next_u64() % 127);
            values.push(if rng.next_u64() % 2 == 0 {
                v
            } else {
                v.wrapping_neg()
            });
        }
        for &a in &values {
            for &b in values.iter().take(40) {
                let (neg, hi, lo) = mul_wide(a, b);
                let magnitude = (BigInt::from(hi) << 128u32) + BigInt::from(lo);
                let exact = BigInt::from(a) * BigInt::from(b);
                assert_eq!(if neg { -magnitude } else { magnitude }, exact, "{a} * {b}");
            }
        }
        for (&a, &b) in values.iter().zip(values.iter().skip(1)) {
            for (&c, &d) in values.iter().skip(2).zip(values.iter().skip(3)).take(50) {
                let exact = (BigInt::from(a) * b).cmp(&(BigInt::from(c) * d));
                assert_eq!(cmp_products(a, b, c, d), exact);
            }
        }
    }

    use crate::fast::scaling::{Divisibility, ExactDiv};

    #[test]
    fn exact_division_and_conversion() {
        let mut rng = SplitMix64::new(17);
        for _ in 0..2000 {
            let g =
                u128::from(rng.next_u64() >> (rng.next_u64() % 64)).max(1) << (rng.next_u64() % 20);
            let k = i128::from(rng.next_u64() as i64 >> (rng.next_u64() % 64));
            let Some(v) = k.checked_mul(g as i128) else {
                continue;
            };
            assert_eq!(ExactDiv::new(g).apply(v), k, "{v} / {g}");
            let test = Divisibility::new(g);
            assert!(test.divides(v.unsigned_abs()), "{g} | {v}");
            let w = v.unsigned_abs() + 1 + u128::from(rng.next_u64() % 5);
            assert_eq!(test.divides(w), w % g == 0, "{g} | {w}?");
            // to_f64 within 3.1 u of the exact value.
            let big = (i128::from(rng.next_u64()) << 63) | i128::from(rng.next_u64());
            let big = big >> (rng.next_u64() % 126);
            let f = to_f64(big);
            let err = (BigRational::from_float(f).unwrap() - big_int(big)).abs()
                / big_int(big).abs().max(BigRational::one());
            assert!(
                err <= BigRational::new(BigInt::from(31), BigInt::from(10) << 53u32),
                "{big}"
            );
            assert_eq!(to_f64(-big), -f);
        }
        assert_eq!(to_f64(0), 0.0);
        assert_eq!(to_f64(i128::MAX), 2f64.powi(127));
    }

    fn big_int(v: i128) -> BigRational {
        BigRational::from_integer(BigInt::from(v))
    }

    #[test]
    fn float_filter_is_exact() {
        // 2^100 / 3 against (2^100 + 1) / 3 and against 2^101 / 6: the doubles
        // coincide, the exact comparison separates or equates them.
        let a = Time::new(1 << 100, 3);
        let b = Time::new((1 << 100) + 1, 3);
        let c = Time::new(1 << 101, 6);
        assert_eq!(a.approx, b.approx);
        assert_eq!(a.cmp(&b), Ordering::Less);
        assert_eq!(b.cmp(&a), Ordering::Greater);
        assert_eq!(a.cmp(&c), Ordering::Equal);
        assert_eq!(Time::new(0, 5).cmp(&Time::new(0, 7)), Ordering::Equal);
        assert_eq!(Time::new(0, 5).cmp(&Time::new(1, 1 << 120)), Ordering::Less);
        let mut rng = SplitMix64::new(9);
        for _ in 0..2000 {
            let g = |rng: &mut SplitMix64| i128::from(rng.next_u64() >> (rng.next_u64() % 64));
            let (g1, c1) = (g(&mut rng) << 60, g(&mut rng).max(1));
            let (g2, c2) = (g1 + (g(&mut rng) % 3 - 1), c1 + (g(&mut rng) % 2));
            let (x, y) = (Time::new(g1, c1), Time::new(g2, c2));
            let exact = (BigInt::from(g1) * c2).cmp(&(BigInt::from(g2) * c1));
            assert_eq!(x.cmp(&y), exact);
        }
    }

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
        ] {
            let t = Time::new(gap, closing);
            let exact = BigRational::new(BigInt::from(gap), BigInt::from(closing));
            assert!(BigRational::from_float(f64::from_bits(t.lo() << KEY_SHIFT)).unwrap() <= exact);
            let above = f64::from_bits(((t.hi() + 1) << KEY_SHIFT) - 1);
            assert!(BigRational::from_float(above).unwrap() >= exact);
            assert!(t.lo() <= t.hi());
        }
    }

    #[test]
    fn equal_times_straddling_a_queue_key() {
        // Three particles with velocities 8, 5, 0 and gaps 3m, 5m: both
        // pairs meet at t = m exactly, one impulse with three parts. Pick m
        // so that the doubles of 3m/3 and 5m/5 round to different queue
        // keys: the window must still gather both pairs.
        let base = 1i128 << 58;
        let m = (0..1_000_000)
            .map(|k| base + 7919 * k)
            .find(|&m| Time::new(3 * m, 3).lo() != Time::new(5 * m, 5).lo())
            .expect("a straddling m");
        let x = |v: i128| BigRational::from_integer(BigInt::from(v));
        let data = InitialData::new(
            q(1, 2),
            vec![x(0), x(3 * m + 1), x(8 * m + 2)],
            vec![q(8, 1), q(5, 1), q(0, 1)],
        )
        .unwrap();
        let it = agree(&data);
        assert_eq!((it.events(), it.instants()), (1, 1));
        assert_eq!(it.into_trajectory().impulses()[0].parts.len(), 3);
        // The same two times on separate pairs: two impulses at one instant
        // (then the two clusters meet, a second instant).
        let data = InitialData::new(
            q(1, 2),
            vec![x(0), x(3 * m + 1), x(9 * m + 2), x(14 * m + 3)],
            vec![q(8, 1), q(5, 1), q(5, 1), q(0, 1)],
        )
        .unwrap();
        let it = agree(&data);
        assert_eq!((it.events(), it.instants()), (3, 2));
        let traj = it.into_trajectory();
        assert_eq!(traj.impulses()[0].t, traj.impulses()[1].t);
    }

    #[test]
    fn random_scenes_agree() {
        let mut rng = SplitMix64::new(2024);
        for k in 0..400 {
            let data = initial_data(
                &rng.bytes(600),
                Limits {
                    max_n: 1 + k % 120,
                    ..Limits::default()
                },
            );
            let it = agree(&data);
            assert_ne!(it.engine(), Engine::BigRational);
        }
    }

    #[test]
    fn degenerate_scenes_agree() {
        // N = 1.
        let one = InitialData::new(q(1, 2), vec![q(3, 1)], vec![q(-2, 1)]).unwrap();
        assert_eq!(agree(&one).events(), 0);
        // Three clusters meeting at t = 1 (one impulse, three parts).
        let x = [0, 1, 3, 4, 5, 7, 8].map(|v| q(v, 1)).to_vec();
        let u = [1, 1, 0, 0, 0, -1, -1].map(|v| q(v, 1)).to_vec();
        let it = agree(&InitialData::new(q(1, 2), x, u).unwrap());
        assert_eq!((it.events(), it.instants()), (1, 1));
        let traj = it.into_trajectory();
        assert_eq!(traj.impulses()[0].parts.len(), 3);
    }

    #[test]
    fn fallback_when_the_bound_fails() {
        // max|X| ≈ 2^125 with N = 10 breaks max(N, N²/4) M < 2^126.
        let huge = big(&(BigInt::one() << 125u32));
        let x: Vec<BigRational> = (0..10)
            .map(|i| q(i, 1) + if i > 6 { huge.clone() } else { q(0, 1) })
            .collect();
        let u: Vec<BigRational> = (0..10).map(|i| q(5 - i, 1)).collect();
        let data = InitialData::new(q(1, 4), x, u).unwrap();
        assert_eq!(agree(&data).engine(), Engine::BigRational);
        // Values far beyond i128.
        let huge = big(&(BigInt::one() << 140u32));
        let data = InitialData::new(
            q(1, 2),
            vec![q(0, 1), q(3, 1), huge.clone(), huge + q(5, 1)],
            vec![q(1, 1), q(-1, 1), q(1, 3), q(-1, 7)],
        )
        .unwrap();
        assert_eq!(agree(&data).engine(), Engine::BigRational);
    }
}
