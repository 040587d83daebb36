//! The float PAVA of the filter, streamed over the particles, and the
//! certificate (module documentation of [`super`]) checked on each block
//! the moment it is final: one pass over the columns, a stack that stays in
//! cache. The particles' free flights (their positions if they stay
//! alone), `ẑ` and floors are computed a few hundred at a time by a loop
//! without branches, before the PAVA reads them; a larger block writes its
//! positions over the free flights when it is final. A particle alone
//! between blocks alone costs the PAVA two comparisons.
//!
//! **When a block is final.** `x̃_i = x⁰_i − 2r i` is non-decreasing
//! (`df:KN`), so every later `z_j = x̃_j + t u⁰_j ≥ x̃_i − t max|u⁰|` for
//! `j ≥ i` (`t ≥ 0`). A block at the bottom of the stack whose mean is below
//! that bound can never pool again: the blocks above it have larger means,
//! and any block that later forms to its right averages entries that are
//! all larger. The floats decide this only heuristically: a block emitted
//! too early meets a right neighbour whose mean is not larger, and the
//! certificate's check between the two refuses the whole run.
//!
//! **Two cores.** From [`PARALLEL_MIN`] particles on, each half is streamed
//! and certified by its own thread; the certificate of the whole is the
//! two halves' and condition 1 between the left half's last block and the
//! right half's first. When that check fails (a block pools across the
//! junction) one thread streams everything.

use std::cmp::Ordering;

use super::eft::{self, up, Acc, U};
use super::Checked;

/// A block of the float PAVA: `k` entries from `start`, `sum` the float
/// sum of their `ẑ`.
#[derive(Debug, Clone, Copy)]
struct Block {
    sum: f64,
    k: u32,
    start: u32,
}

/// A block of more than one particle of the certified partition (the
/// others are single particles).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Multi {
    /// Its first particle.
    pub start: u32,
    /// Its number of particles, `≥ 2`.
    pub k: u32,
}

/// Two threads from this many particles on.
pub(crate) const PARALLEL_MIN: usize = 1 << 16;

/// The largest block the filter keeps: past it the filter gives up (a
/// choice of speed, not of correctness). Its per-particle work on a larger
/// block (double-double positions, multipliers quadratic in the block)
/// costs more than the exact dyadic path, which is fast on the data that
/// pool a lot (short dyadic grids), and a scene of a few large blocks is
/// not the one the filter is for.
pub(crate) const MAX_BLOCK: u32 = 64;

/// The certificate of a range of particles: its larger blocks, and the
/// mean and size of its first and last blocks (for condition 1 across a
/// junction).
struct Part {
    multi: Vec<Multi>,
    first: Option<BlockMean>,
    last: Option<BlockMean>,
}

/// A block's mean `μ̂` (in floating point) and its number of entries `k`:
/// what condition 1 compares across a block end.
#[derive(Clone, Copy, Debug)]
struct BlockMean {
    mean: f64,
    k: u32,
}

/// `β(k) = (4 + 2k) u G`: the bound of a mean of `k` consecutive `ẑ`
/// (module documentation of [`super`]), `ug = u G`.
#[inline]
fn beta(ug: f64, k: u32) -> f64 {
    (4.0 + 2.0 * f64::from(k)) * ug
}

/// What every range's certificate shares.
#[derive(Clone, Copy)]
pub(crate) struct Context<'a> {
    x: &'a [f64],
    u: &'a [f64],
    t: f64,
    two_r: f64,
    /// `u G`.
    ug: f64,
    /// `up(β(1) + β(1))`: condition 1's bound between two blocks of one
    /// particle.
    m11: f64,
}

/// The larger blocks' certificate (condition 2) and their positions.
struct Certifier<'a, 'o> {
    /// The data and the bound's scale.
    cx: Context<'a>,
    /// The positions of the range, from particle `base` on.
    out: &'o mut [f64],
    base: usize,
    multi: Vec<Multi>,
    /// `ẑ` of a block, its prefix and suffix sums, its exact terms.
    scratch: Vec<f64>,
    prefix: Vec<f64>,
    suffix: Vec<f64>,
    terms: Vec<f64>,
}

/// Condition 1 along the emitted blocks, left to right: the first block's
/// mean and size, and the last one's.
#[derive(Clone, Copy, Default)]
struct Chain {
    first: Option<BlockMean>,
    prev: Option<BlockMean>,
}

impl Chain {
    /// Condition 1 between the previous block and `this`:
    /// `fl(μ̂_B − μ̂_A) > up(β(k_A) + β(k_B))`, the bound of two blocks of one
    /// particle being `m11` (the same expression, computed once).
    #[inline(always)]
    fn follow(&mut self, ug: f64, m11: f64, this: BlockMean) -> Option<()> {
        match self.prev {
            Some(p) => {
                let margin = if p.k == 1 && this.k == 1 {
                    m11
                } else {
                    up(beta(ug, p.k) + beta(ug, this.k))
                };
                // A NaN fails it too.
                if (this.mean - p.mean).partial_cmp(&margin) != Some(Ordering::Greater) {
                    return None;
                }
            }
            None => self.first = Some(this),
        }
        self.prev = Some(this);
        Some(())
    }
}

impl Certifier<'_, '_> {
    /// `ẑ_i = fl(fl(x_i + fl(t u_i)) − fl(2r i))`.
    #[inline]
    fn z(&self, i: usize) -> f64 {
        (self.cx.x[i] + self.cx.t * self.cx.u[i]) - self.cx.two_r * i as f64
    }

    /// A block of `k ≥ 2` particles: condition 2 at every split, then each
    /// position `(Σ_j z_j)/k + 2r i` as the quotient by `k` of the exact
    /// terms `x_j`, `t u_j` (two each), `2r (k i − Σ_j j)` (two), written
    /// over the free flights. Its mean and size, for condition 1.
    #[cold]
    #[inline(never)]
    fn multi(&mut self, b: Block) -> Option<BlockMean> {
        let (a, k) = (b.start as usize, b.k as usize);
        let mut zs = std::mem::take(&mut self.scratch);
        zs.clear();
        zs.extend((a..a + k).map(|i| self.z(i)));
        // prefix[m] = ẑ_a + … + ẑ_{a+m−1}; suffix[m] = ẑ_{a+m} + … (each a
        // recursive sum in its own order).
        let (prefix, suffix) = (&mut self.prefix, &mut self.suffix);
        prefix.clear();
        prefix.push(0.0);
        for m in 0..k {
            prefix.push(prefix[m] + zs[m]);
        }
        suffix.clear();
        suffix.resize(k + 1, 0.0);
        for m in (0..k).rev() {
            suffix[m] = zs[m] + suffix[m + 1];
        }
        self.scratch = zs;
        let (prefix, suffix) = (&self.prefix, &self.suffix);
        for m in 1..k {
            let (ml, mr) = (m as u32, (k - m) as u32);
            let left = prefix[m] / f64::from(ml);
            let right = suffix[m] / f64::from(mr);
            let margin = up(beta(self.cx.ug, ml) + beta(self.cx.ug, mr));
            // A NaN fails it too.
            if (left - right).partial_cmp(&margin) != Some(Ordering::Greater) {
                return None;
            }
        }
        let mut base = Acc::default();
        self.terms.clear();
        for j in a..a + k {
            base.add(self.cx.x[j]);
            base.add_product(self.cx.t, self.cx.u[j]);
            let (p, e) = eft::two_prod(self.cx.t, self.cx.u[j]);
            self.terms.extend([self.cx.x[j], p, e]);
        }
        // Σ j over the block, exact (< 2⁵³: `k N < 2⁵²`).
        let sum_j = (k * a + k * (k - 1) / 2) as i64;
        let d = k as f64;
        for i in a..a + k {
            let c = (k * i) as i64 - sum_j;
            let mut acc = base;
            acc.add_product(self.cx.two_r, c as f64);
            let p = match acc.nearest_quotient(d) {
                Some(p) => p,
                None => {
                    let (p, e) = eft::two_prod(self.cx.two_r, c as f64);
                    let mut terms = self.terms.clone();
                    terms.extend([p, e]);
                    eft::exact_quotient(&terms, k as u64)
                }
            };
            self.out[i - self.base] = p;
        }
        self.multi.push(Multi {
            start: b.start,
            k: b.k,
        });
        Some(BlockMean {
            mean: prefix[k] / d,
            k: b.k,
        })
    }

    /// Checks the final block `b` (conditions 1 and 2); a block of one
    /// particle keeps the free flight already written, a larger one has
    /// its positions written.
    #[inline(always)]
    fn emit(&mut self, chain: &mut Chain, b: Block) -> Option<()> {
        let this = if b.k == 1 {
            BlockMean { mean: b.sum, k: 1 }
        } else {
            self.multi(b)?
        };
        chain.follow(self.cx.ug, self.cx.m11, this)
    }
}

/// Condition 1 between consecutive blocks `(mean, size)`:
/// `fl(μ̂_B − μ̂_A) > up(β(k_A) + β(k_B))` (a NaN fails it too).
#[inline]
fn increasing(ug: f64, a: BlockMean, b: BlockMean) -> Option<()> {
    let margin = up(beta(ug, a.k) + beta(ug, b.k));
    (b.mean - a.mean > margin).then_some(())
}

/// Does block `a` pool with the block `b` to its right (mean `≥`)?
#[inline]
fn pools(a: &Block, b: &Block) -> bool {
    a.sum * f64::from(b.k) >= b.sum * f64::from(a.k)
}

/// The float PAVA at `t` (a double in range) and its certificate, on two
/// threads from `parallel_min` particles on: the larger blocks of the
/// certified partition, every position's nearest double written into
/// `positions` (`N` of them); `None` when a check fails (`positions` then
/// holds anything).
pub(crate) fn certified(
    d: &Checked,
    x: &[f64],
    u: &[f64],
    t: f64,
    positions: &mut [f64],
    parallel_min: usize,
) -> Option<Vec<Multi>> {
    let (cx, tu) = context(d, x, u, t);
    // Every later `ẑ_j ≥ x̃_i − t max|u⁰|` (module documentation).
    let slack = tu + 64.0 * cx.ug;
    let floor = move |_: usize, xi: f64, s: f64| (xi - s) - slack;
    run(cx, positions, parallel_min, floor)
}

/// The context of [`certified`], and `fl(t max|u⁰|)`.
pub(crate) fn context<'a>(d: &Checked, x: &'a [f64], u: &'a [f64], t: f64) -> (Context<'a>, f64) {
    let n = x.len();
    debug_assert!(n == d.n && u.len() == n);
    // G ≥ max|x⁰| + t max|u⁰| + 2r N (x⁰ sorted: its extremes are its ends).
    let x_max = x[0].abs().max(x[n - 1].abs());
    let tu = t * d.u_max;
    let g = up(x_max + tu + d.two_r * n as f64);
    (Context::new(x, u, t, d.two_r, g), tu)
}

/// A heuristic lower bound of every `ẑ_j`, `j ≥ i` (the floor at `i`): a
/// block whose mean is below it is final. Wrong bounds cost a refusal,
/// never a wrong answer (module documentation).
pub(crate) trait Floor: Copy + Send {
    /// The floor at `i` from `(i, x_i, fl(2r i))`, computed in the loop
    /// without branches of [`Context::flights`].
    fn at(&self, i: usize, x: f64, s: f64) -> f64;

    /// The floors `lows` of the run of particles from `i0` on, once their
    /// `ẑ` (`zs`) are known and [`Self::at`] has given each its own: a
    /// floor that needs the run's `ẑ` replaces them here.
    #[inline(always)]
    fn run(&self, i0: usize, zs: &[f64], lows: &mut [f64]) {
        let _ = (i0, zs, lows);
    }
}

impl<F: Fn(usize, f64, f64) -> f64 + Copy + Send> Floor for F {
    #[inline(always)]
    fn at(&self, i: usize, x: f64, s: f64) -> f64 {
        self(i, x, s)
    }
}

/// The certified float PAVA of `cx` on two threads from `parallel_min`
/// particles on, blocks made final by `floor` ([`certified`]).
pub(crate) fn run(
    cx: Context<'_>,
    positions: &mut [f64],
    parallel_min: usize,
    floor: impl Floor,
) -> Option<Vec<Multi>> {
    let n = cx.x.len();
    debug_assert!(cx.u.len() == n && positions.len() == n);
    if n >= parallel_min.max(2) {
        // The right half from a multiple of `FLIGHTS` when there is one (a
        // floor by runs then meets whole runs).
        let h = match n / 2 / FLIGHTS * FLIGHTS {
            0 => n / 2,
            aligned => aligned,
        };
        let (lo, hi) = positions.split_at_mut(h);
        let (left, right) =
            crate::parallel::join(|| cx.stream(0, lo, floor), move || cx.stream(h, hi, floor));
        if let (Some(mut left), Some(right)) = (left, right) {
            let joined = match (left.last, right.first) {
                (Some(a), Some(b)) => increasing(cx.ug, a, b).is_some(),
                _ => false,
            };
            if joined {
                left.multi.extend(right.multi);
                return Some(left.multi);
            }
        }
    }
    Some(cx.stream(0, positions, floor)?.multi)
}

impl<'a> Context<'a> {
    /// The data `x`, `u` at `t`, with `G = g ≥ max_i |ẑ_i|` bounding every
    /// term (module documentation).
    pub(crate) fn new(x: &'a [f64], u: &'a [f64], t: f64, two_r: f64, g: f64) -> Context<'a> {
        let ug = up(U * g);
        Context {
            x,
            u,
            t,
            two_r,
            ug,
            m11: up(beta(ug, 1) + beta(ug, 1)),
        }
    }

    /// `u G`.
    pub(crate) fn ug(&self) -> f64 {
        self.ug
    }
}

/// The particles whose free flights, `ẑ` and floors are computed at a time
/// ([`Context::flights`]): a few kilobytes, in the first-level cache while
/// the PAVA reads them.
pub(crate) const FLIGHTS: usize = 256;

/// What [`Context::flights`] computes for a run of particles, read by the
/// PAVA: `ẑ_i` and the floor of the blocks final at `i`.
struct Flights {
    z: [f64; FLIGHTS],
    low: [f64; FLIGHTS],
}

impl Context<'_> {
    /// For the `out.len() ≤ FLIGHTS` particles from `i0` on: each free
    /// flight `x⁰_i + t u⁰_i` rounded to its nearest double into `out`
    /// ([`eft::nearest_free_flight_of`], from the `fl(t u)` and
    /// `fl(x + t u)` that `ẑ_i` is made of), `ẑ_i` and `floor` into `f`.
    /// Branch-free (the compiler vectorizes it): the rare free flight the
    /// test does not prove is rounded again, exactly, afterwards.
    #[inline(always)]
    fn flights(&self, i0: usize, out: &mut [f64], f: &mut Flights, floor: impl Floor) {
        let m = out.len();
        debug_assert!(m <= FLIGHTS && i0 + m <= self.x.len());
        let (xs, us) = (&self.x[i0..i0 + m], &self.u[i0..i0 + m]);
        let (zs, lows) = (&mut f.z[..m], &mut f.low[..m]);
        // `i0 + j` as a double: exact, `i < 2⁵³`.
        let i0_f64 = i0 as f64;
        let mut proved = true;
        for j in 0..m {
            let (xi, ui) = (xs[j], us[j]);
            let p = self.t * ui;
            let (w, e) = eft::two_sum(xi, p);
            let s = self.two_r * (i0_f64 + f64::from(j as u32));
            out[j] = w;
            zs[j] = w - s;
            lows[j] = floor.at(i0 + j, xi, s);
            proved &= eft::is_nearest_free_flight(p, w, e);
        }
        floor.run(i0, zs, lows);
        if !proved {
            for j in 0..m {
                let (xi, ui) = (xs[j], us[j]);
                let p = self.t * ui;
                let (w, e) = eft::two_sum(xi, p);
                out[j] = eft::nearest_free_flight_of(xi, self.t, ui, p, w, e);
            }
        }
    }

    /// The float PAVA on the particles from `base` on (`out.len()` of
    /// them), its positions into `out`, its certificate checked.
    ///
    /// Each particle's free flight is written first, `FLIGHTS` particles
    /// at a time ([`Self::flights`]): it is the position when the particle
    /// stays alone, and a larger block writes its own over it when it is
    /// emitted. The top of the stack stays in registers (`top`, `k = 0`
    /// when there is none): on sparse data a particle is pushed, then
    /// emitted by the next one, without the stack in memory; a run of such
    /// particles is crossed by a loop of two comparisons each.
    fn stream(self, base: usize, out: &mut [f64], floor: impl Floor) -> Option<Part> {
        let len = out.len();
        let m11 = self.m11;
        let mut c = Certifier {
            cx: self,
            out,
            base,
            multi: Vec::new(),
            scratch: Vec::new(),
            prefix: Vec::new(),
            suffix: Vec::new(),
            terms: Vec::new(),
        };
        let mut chain = Chain::default();
        // The blocks below `top`, the final ones before `bottom`.
        let mut stack: Vec<Block> = Vec::with_capacity(256);
        let mut bottom = 0usize;
        let none = Block {
            sum: 0.0,
            k: 0,
            start: 0,
        };
        let mut top = none;
        let mut f = Flights {
            z: [0.0; FLIGHTS],
            low: [0.0; FLIGHTS],
        };
        debug_assert!(base + len < 1 << 32);
        for from in (0..len).step_by(FLIGHTS) {
            let m = FLIGHTS.min(len - from);
            let i0 = base + from;
            self.flights(i0, &mut c.out[from..from + m], &mut f, floor);
            let (zs, lows) = (&f.z[..m], &f.low[..m]);
            let mut j = 0;
            while j < m {
                // A run of particles each alone and final at the next:
                // the steps below, taken without the stack (the top is
                // emitted, condition 1 checked with the bound `m11` of two
                // blocks of one particle, the next particle pushed).
                if let (1, true, Some(BlockMean { mean, k: 1 })) =
                    (top.k, stack.is_empty(), chain.prev)
                {
                    let (mut prev, mut z, first) = (mean, top.sum, j);
                    // Four steps at a time, then one.
                    while j + 4 <= m {
                        let (z1, z2, z3) = (zs[j], zs[j + 1], zs[j + 2]);
                        let steps = (z < lows[j])
                            & (z - prev > m11)
                            & (z1 < lows[j + 1])
                            & (z1 - z > m11)
                            & (z2 < lows[j + 2])
                            & (z2 - z1 > m11)
                            & (z3 < lows[j + 3])
                            & (z3 - z2 > m11);
                        if !steps {
                            break;
                        }
                        prev = z3;
                        z = zs[j + 3];
                        j += 4;
                    }
                    while j < m && z < lows[j] && z - prev > m11 {
                        prev = z;
                        z = zs[j];
                        j += 1;
                    }
                    if j > first {
                        chain.prev = Some(BlockMean { mean: prev, k: 1 });
                        top = Block {
                            sum: z,
                            k: 1,
                            start: (i0 + j - 1) as u32,
                        };
                        continue;
                    }
                }
                let i = i0 + j;
                let low = lows[j];
                // Emit the blocks that are final, from the bottom.
                if bottom < stack.len() {
                    while let Some(&b) = stack.get(bottom) {
                        if b.sum >= low * f64::from(b.k) {
                            break;
                        }
                        c.emit(&mut chain, b)?;
                        bottom += 1;
                    }
                    if bottom == stack.len() {
                        stack.clear();
                        bottom = 0;
                    }
                }
                if top.k != 0 && stack.is_empty() && top.sum < low * f64::from(top.k) {
                    c.emit(&mut chain, top)?;
                    top = none;
                }
                let mut cur = Block {
                    sum: zs[j],
                    k: 1,
                    start: i as u32,
                };
                if top.k != 0 {
                    if pools(&top, &cur) {
                        cur = Block {
                            sum: top.sum + cur.sum,
                            k: top.k + cur.k,
                            start: top.start,
                        };
                        while stack.len() > bottom {
                            let below = stack[stack.len() - 1];
                            if !pools(&below, &cur) {
                                break;
                            }
                            stack.pop();
                            cur = Block {
                                sum: below.sum + cur.sum,
                                k: below.k + cur.k,
                                start: below.start,
                            };
                        }
                        if cur.k > MAX_BLOCK {
                            return None;
                        }
                    } else {
                        stack.push(top);
                    }
                }
                top = cur;
                j += 1;
            }
        }
        for b in stack[bottom..].iter().chain((top.k != 0).then_some(&top)) {
            c.emit(&mut chain, *b)?;
        }
        Some(Part {
            multi: c.multi,
            first: chain.first,
            last: chain.prev,
        })
    }
}
