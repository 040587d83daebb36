//! The event loop on two halves at once: each half's join times computed
//! alone (two threads), then those of the whole repaired from them and
//! from the one cluster that crosses the cut.
//!
//! **Why the halves' histories are almost the whole one.** At every time
//! `t` the clusters are the blocks of the isotonic regression of
//! `x̃⁰ + t u⁰` (`prop:proj-micro`, `eq:proj-micro-x`), and the pool
//! adjacent violators algorithm may pool in any order: started from the
//! blocks of the left half `L` and of the right half `R`, it can only pool
//! across the cut, so the clusters of the whole at `t` are those of the
//! halves except one *run* `[p(t), q(t))` around the cut, a union of a
//! suffix of `L`'s clusters and a prefix of `R`'s (or no run). Clusters
//! only grow, so the run only grows. Hence a cluster `C` formed at `t` in a
//! half's history is formed at `t`, from the same parts, in the whole's
//! history iff `C` is not inside the run at `t` (a part inside the run
//! before `t` would put `C` inside it at `t`); and a pair `(j, j + 1)`
//! joins in the whole at the earlier of its half's join time and the time
//! the run first holds both particles.
//!
//! **The run's growth.** Let `N_L` be the left half's cluster at time `T`
//! ending at `p − 1` (the run's left neighbour) and `N_R` the right half's
//! cluster starting at `q`. Until the run meets `N_L`, `N_L` and the
//! clusters to its left move as in the left half alone: the left half's
//! history is valid for them. (If in the left half alone `N_L` met a
//! cluster `X` of the run at `s`, then `N_L ∪ X` is a cluster of the half
//! at `s` and the run, a union of such clusters holding `X`, holds `N_L`:
//! the run meets `N_L` at `s` or before.) So the run grows at the earliest
//! of: the run meeting `N_L` or `N_R` (the two halves' last and first
//! clusters meeting each other while there is no run), computed from the
//! cluster sums as in [`super::events::run`]; and between those events
//! `N_L`, `N_R` grow outwards at their halves' join times. Every step
//! walks particles that join `N_L`, `N_R` or the run for good: the whole
//! repair is linear in the size of the final run, plus one pass over the
//! halves' join times.
//!
//! **Threads.** Each piece of at least [`PART_MIN`] particles is itself cut
//! in two the same way, down to pieces run whole; the pieces of the tree of
//! cuts run height by height (pieces run whole first, then the combines of
//! their pairs, up to the whole), two threads taking the pieces of each
//! height as they come free, so that a slower piece, or a slower core, does
//! not keep the other thread waiting. Only join times are combined: the
//! instants merged, the halves' join codes renumbered (on both threads),
//! the run's written over them; the clusters formed are read off the join
//! times of the whole once, at the end ([`History::from_joins`], on two
//! threads too). (Which impulses of a half stay follows: those whose pairs
//! still join at the half's time.)

use std::cmp::Ordering;

use super::events::{run, Joins, JOIN_NEVER, JOIN_ZERO};
use super::history::History;
use super::sums::{meeting, Node, SumWord};
use super::time::Time;
use crate::fast::scaling::{both, Cores};

/// Below this many particles one thread runs the whole (the threads and
/// the repair cost more than they save).
pub(super) const SPLIT_MIN: usize = 1 << 15;

/// The history of `x`, `u`: the join times of [`run`], on two threads
/// when `n` is at least [`SPLIT_MIN`], then the clusters formed.
pub(super) fn run_split<T, W>(x: &[T], u: &[T]) -> History
where
    T: Copy + PartialEq + Into<W> + Sync,
    W: SumWord,
{
    let n = x.len();
    let joins = match (n >= SPLIT_MIN).then(|| cut(x, u, n / 2)).flatten() {
        Some(m) => run_halves::<T, W>(x, u, m, Cores::Two, PART_MIN),
        None => run::<T, W>(x, u),
    };
    History::from_joins(joins)
}

/// The first `m ≥ from`, `0 < m < n`, where particles `m − 1` and `m` are
/// not in one initial cluster (a contact with equal velocities).
pub(super) fn cut<T: PartialEq>(x: &[T], u: &[T], from: usize) -> Option<usize> {
    (from.max(1)..x.len()).find(|&m| x[m - 1] != x[m] || u[m - 1] != u[m])
}

/// From this many particles a piece is itself cut in two: a smaller event
/// loop keeps more of its nodes in the caches.
pub(super) const PART_MIN: usize = 1 << 16;

/// The join times of the whole from those of `..m` and `m..`, each
/// computed alone, and cut again from `part_min` particles on; `0 < m < n`
/// and the pair `(m − 1, m)` is not an initial contact with equal
/// velocities. On `Cores::Two`, two threads: the pieces of equal height in
/// the tree of cuts are shared out as the threads come free (so that a
/// slower piece or a slower core does not hold the other thread idle),
/// and the join codes of the whole are renumbered on both.
pub(super) fn run_halves<T, W>(x: &[T], u: &[T], m: usize, cores: Cores, part_min: usize) -> Joins
where
    T: Copy + PartialEq + Into<W> + Sync,
    W: SumWord,
{
    let mut pieces = Vec::new();
    plan(x, u, 0..x.len(), Some(m), part_min, &mut pieces);
    run_pieces::<T, W>(x, u, &pieces, cores)
}

/// A piece of the tree of cuts: particles `lo..hi`, either run whole or
/// cut in two ([`Split`]).
#[derive(Debug, Clone)]
struct Piece {
    range: std::ops::Range<usize>,
    cut: Option<Split>,
    /// 0 for a piece run whole; one more than its higher half's otherwise.
    height: u32,
}

/// How a piece is cut: at particle `at` into the pieces numbered `left`
/// (particles `lo..at`) and `right` (`at..hi`), both planned before it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Split {
    at: usize,
    left: usize,
    right: usize,
}

/// Plans the pieces of `range`, cut at `m` (or, from `part_min` particles
/// on, at the first cut from its middle, [`cut`]), children first: the
/// whole is the last piece.
fn plan<T: PartialEq>(
    x: &[T],
    u: &[T],
    range: std::ops::Range<usize>,
    m: Option<usize>,
    part_min: usize,
    out: &mut Vec<Piece>,
) -> usize {
    let (lo, hi) = (range.start, range.end);
    let m = m.or_else(|| {
        (hi - lo >= part_min)
            .then(|| cut(&x[range.clone()], &u[range.clone()], (hi - lo) / 2))
            .flatten()
            .map(|c| lo + c)
    });
    let piece = match m {
        Some(m) => {
            let left = plan(x, u, lo..m, None, part_min, out);
            let right = plan(x, u, m..hi, None, part_min, out);
            Piece {
                range,
                cut: Some(Split { at: m, left, right }),
                height: 1 + out[left].height.max(out[right].height),
            }
        }
        None => Piece {
            range,
            cut: None,
            height: 0,
        },
    };
    out.push(piece);
    out.len() - 1
}

/// Runs the planned pieces, height by height, and returns the join times of
/// the last one (the whole). On `Cores::Two`, a second thread takes pieces of
/// the same height as it comes free; a height with a single piece runs it
/// with both threads (its renumbering).
fn run_pieces<T, W>(x: &[T], u: &[T], pieces: &[Piece], cores: Cores) -> Joins
where
    T: Copy + PartialEq + Into<W> + Sync,
    W: SumWord,
{
    use std::sync::atomic::{AtomicUsize, Ordering::Relaxed};
    use std::sync::Mutex;
    let done: Vec<Mutex<Option<Joins>>> = pieces.iter().map(|_| Mutex::new(None)).collect();
    let take = |k: usize| {
        done[k]
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .take()
            .expect("a piece's halves run before it")
    };
    let solve = |k: usize, cores: Cores| {
        let piece = &pieces[k];
        let (x, u) = (&x[piece.range.clone()], &u[piece.range.clone()]);
        let joins = match piece.cut {
            None => run::<T, W>(x, u),
            Some(split) => {
                let (left, right) = (take(split.left), take(split.right));
                let halves = Halves {
                    m: split.at - piece.range.start,
                    left: &left,
                    right: &right,
                };
                let growth = grow_run::<T, W>(x, u, &halves);
                combine(&halves, &growth, x.len(), cores)
            }
        };
        *done[k].lock().unwrap_or_else(|e| e.into_inner()) = Some(joins);
    };
    let top = pieces.iter().map(|p| p.height).max().unwrap_or(0);
    for height in 0..=top {
        let level: Vec<usize> = (0..pieces.len())
            .filter(|&k| pieces[k].height == height)
            .collect();
        if let [k] = level[..] {
            solve(k, cores);
            continue;
        }
        let next = AtomicUsize::new(0);
        let work = || {
            while let Some(&k) = level.get(next.fetch_add(1, Relaxed)) {
                solve(k, Cores::One);
            }
        };
        both(cores, work, work);
    }
    take(pieces.len() - 1)
}

/// The two halves' join times, `left` of particles `..m`, `right` of
/// `m..` (numbered from 0).
struct Halves<'a> {
    m: usize,
    left: &'a Joins,
    right: &'a Joins,
}

/// A join code of a half as a time: `None` for never.
fn code_time(h: &Joins, code: u32) -> Option<Time> {
    match code {
        JOIN_NEVER => None,
        JOIN_ZERO => Some(Time::new(0, 1)),
        k => {
            let (gap, closing) = h.instants[k as usize];
            Some(Time::new(gap, closing))
        }
    }
}

impl HalfCode {
    /// Did the pair join at time zero or at one of the first `count`
    /// instants of its half?
    fn joined_before(self, count: u32) -> bool {
        self.code == JOIN_ZERO || (self.code != JOIN_NEVER && self.code < count)
    }
}

/// One of the two halves of a piece.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Half {
    /// Particles `..m`.
    Left,
    /// Particles `m..`.
    Right,
}

/// The join code of a pair in the half that holds it.
#[derive(Debug, Clone, Copy)]
struct HalfCode {
    half: Half,
    code: u32,
}

/// How many of each half's instants come before some time (the instants
/// are increasing, so a join code compares with the time as an index).
#[derive(Debug, Clone, Copy)]
struct Counts {
    left: u32,
    right: u32,
}

impl Counts {
    fn of(self, half: Half) -> u32 {
        match half {
            Half::Left => self.left,
            Half::Right => self.right,
        }
    }
}

/// Which instants [`Halves::cut`] counts: those at `t` or before, or those
/// strictly before.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Before {
    AtOrBefore,
    Strictly,
}

/// Where a time `t` falls among each half's instants: `le` counts those at
/// `t` or before, `lt` those before `t`.
#[derive(Debug, Clone, Copy)]
struct Cut {
    le: Counts,
    lt: Counts,
}

impl Halves<'_> {
    /// Where `t` falls among the halves' instants.
    fn cut(&self, t: &Time) -> Cut {
        let count = |h: &Joins, before: Before| {
            h.instants.partition_point(|&(gap, closing)| {
                let c = Time::new(gap, closing).cmp(t);
                c == Ordering::Less || (before == Before::AtOrBefore && c == Ordering::Equal)
            }) as u32
        };
        let counts = |before| Counts {
            left: count(self.left, before),
            right: count(self.right, before),
        };
        Cut {
            le: counts(Before::AtOrBefore),
            lt: counts(Before::Strictly),
        }
    }
    /// The half and join code of the pair `(j, j + 1)` (`None` for the pair
    /// across the cut, which no half joins).
    fn code(&self, j: usize) -> Option<HalfCode> {
        match j.cmp(&(self.m - 1)) {
            Ordering::Less => Some(HalfCode {
                half: Half::Left,
                code: self.left.join[j],
            }),
            Ordering::Equal => None,
            Ordering::Greater => Some(HalfCode {
                half: Half::Right,
                code: self.right.join[j - self.m],
            }),
        }
    }
    /// The half's join time of the pair `(j, j + 1)`.
    fn join(&self, j: usize) -> Option<Time> {
        let c = self.code(j)?;
        let half = match c.half {
            Half::Left => self.left,
            Half::Right => self.right,
        };
        code_time(half, c.code)
    }
    /// Did the pair `(j, j + 1)` join in its half at the time of `cut` or
    /// before?
    fn joined_by(&self, j: usize, cut: &Cut) -> bool {
        self.code(j)
            .is_some_and(|c| c.joined_before(cut.le.of(c.half)))
    }
    /// Did the pair `(j, j + 1)` join in its half before the time of `cut`?
    fn joined_before(&self, j: usize, cut: &Cut) -> bool {
        self.code(j)
            .is_some_and(|c| c.joined_before(cut.lt.of(c.half)))
    }
}

/// One growth of the run: at `t` the run `[p_old, q_old)` (empty when
/// `p_old = q_old = m`) became `[p, q)`.
#[derive(Debug, Clone, Copy)]
struct Growth {
    t: Time,
    cut: Cut,
    p: usize,
    q: usize,
    p_old: usize,
    q_old: usize,
}

impl Growth {
    /// The pairs `(j, j + 1)` the run holds from `t` on and not before,
    /// left to right: those of the clusters it took in and the pairs
    /// between them and the old run.
    fn new_pairs(&self) -> impl Iterator<Item = usize> {
        let right = if self.p_old == self.q_old {
            self.q_old
        } else {
            self.q_old - 1
        };
        (self.p..self.p_old).chain(right..self.q - 1)
    }
}

/// A cluster `[first, end)` with its sums, as a node for [`meeting`].
#[derive(Clone, Copy)]
struct Span<W> {
    first: usize,
    end: usize,
    node: Node<W>,
}

impl<W: SumWord> Span<W> {
    fn empty(at: usize) -> Self {
        Span {
            first: at,
            end: at,
            node: Node::default(),
        }
    }
    fn add<T: Copy + Into<W>>(&mut self, x: &[T], u: &[T], i: usize) {
        self.node.sum_x += x[i].into();
        self.node.sum_u += u[i].into();
        self.node.size += 1;
    }
    fn absorb(&mut self, other: &Span<W>) {
        self.first = self.first.min(other.first);
        self.end = self.end.max(other.end);
        self.node.sum_x += other.node.sum_x;
        self.node.sum_u += other.node.sum_u;
        self.node.size += other.node.size;
    }
    fn is_empty(&self) -> bool {
        self.first == self.end
    }
}

/// The left half's cluster at `t` holding particle `end − 1` (`end > 0`).
fn left_cluster<T: Copy + Into<W>, W: SumWord>(
    x: &[T],
    u: &[T],
    h: &Halves,
    end: usize,
    t: &Cut,
) -> Span<W> {
    let mut s = Span::empty(end);
    s.first -= 1;
    s.add(x, u, end - 1);
    extend_left(x, u, h, &mut s, t);
    s
}

/// Extends `s` leftwards over the pairs joined by `t`.
fn extend_left<T: Copy + Into<W>, W: SumWord>(
    x: &[T],
    u: &[T],
    h: &Halves,
    s: &mut Span<W>,
    t: &Cut,
) {
    while s.first > 0 && h.joined_by(s.first - 1, t) {
        s.first -= 1;
        s.add(x, u, s.first);
    }
}

/// The right half's cluster at `t` starting at particle `first < n`.
fn right_cluster<T: Copy + Into<W>, W: SumWord>(
    x: &[T],
    u: &[T],
    h: &Halves,
    first: usize,
    t: &Cut,
) -> Span<W> {
    let mut s = Span::empty(first);
    s.end += 1;
    s.add(x, u, first);
    extend_right(x, u, h, &mut s, t);
    s
}

/// Extends `s` rightwards over the pairs joined by `t`.
fn extend_right<T: Copy + Into<W>, W: SumWord>(
    x: &[T],
    u: &[T],
    h: &Halves,
    s: &mut Span<W>,
    t: &Cut,
) {
    while s.end < x.len() && h.joined_by(s.end - 1, t) {
        s.add(x, u, s.end);
        s.end += 1;
    }
}

/// The earlier of two optional times.
fn earlier(a: Option<Time>, b: Option<Time>) -> Option<Time> {
    match (a, b) {
        (Some(a), Some(b)) => Some(if b.cmp(&a) == Ordering::Less { b } else { a }),
        (a, None) => a,
        (None, b) => b,
    }
}

fn equal(a: &Option<Time>, t: &Time) -> bool {
    a.as_ref().is_some_and(|a| a.cmp(t) == Ordering::Equal)
}

/// Every growth of the run, in time order (see the module docs).
fn grow_run<T: Copy + Into<W>, W: SumWord>(x: &[T], u: &[T], h: &Halves) -> Vec<Growth> {
    let (n, m) = (x.len(), h.m);
    let zero = h.cut(&Time::new(0, 1));
    let mut out = Vec::new();
    let mut run = Span::<W>::empty(m);
    // The run's neighbours (empty at the ends of the line).
    let mut nl = left_cluster(x, u, h, m, &zero);
    let mut nr = right_cluster(x, u, h, m, &zero);
    loop {
        // N_L, N_R growing outwards in their halves.
        let sl = (!nl.is_empty() && nl.first > 0)
            .then(|| h.join(nl.first - 1))
            .flatten();
        let sr = (!nr.is_empty() && nr.end < n)
            .then(|| h.join(nr.end - 1))
            .flatten();
        // The run meeting them (the two neighbours meeting, while no run).
        let (tl, tr) = if run.is_empty() {
            let t = (!nl.is_empty() && !nr.is_empty())
                .then(|| meeting(&nl.node, &nr.node))
                .flatten();
            (t, t)
        } else {
            (
                (!nl.is_empty())
                    .then(|| meeting(&nl.node, &run.node))
                    .flatten(),
                (!nr.is_empty())
                    .then(|| meeting(&run.node, &nr.node))
                    .flatten(),
            )
        };
        let Some(t) = earlier(earlier(sl, sr), earlier(tl, tr)) else {
            break;
        };
        let cut = h.cut(&t);
        if equal(&sl, &t) {
            extend_left(x, u, h, &mut nl, &cut);
        }
        if equal(&sr, &t) {
            extend_right(x, u, h, &mut nr, &cut);
        }
        let (meet_l, meet_r) = (equal(&tl, &t), equal(&tr, &t));
        if !(meet_l || meet_r) {
            continue;
        }
        let (p_old, q_old) = (run.first, run.end);
        if meet_l {
            run.absorb(&nl);
            nl = if run.first > 0 {
                left_cluster(x, u, h, run.first, &cut)
            } else {
                Span::empty(0)
            };
        }
        if meet_r {
            run.absorb(&nr);
            nr = if run.end < n {
                right_cluster(x, u, h, run.end, &cut)
            } else {
                Span::empty(n)
            };
        }
        out.push(Growth {
            t,
            cut,
            p: run.first,
            q: run.end,
            p_old,
            q_old,
        });
    }
    out
}

/// The instants of the whole: those of the halves merged in time order
/// with the run's growths (equal times are one instant), and where each
/// half's instants and each growth went. (An instant of a half may no
/// longer be used by any pair of the whole: [`History::from_joins`] drops
/// it.)
struct Instants {
    times: Vec<(i128, i128)>,
    map_l: Vec<u32>,
    map_r: Vec<u32>,
    map_g: Vec<u32>,
}

fn merge_instants(h: &Halves, growth: &[Growth]) -> Instants {
    let (left, right) = (&h.left.instants, &h.right.instants);
    let mut out = Instants {
        times: Vec::with_capacity(left.len() + right.len() + growth.len()),
        map_l: Vec::with_capacity(left.len()),
        map_r: Vec::with_capacity(right.len()),
        map_g: Vec::with_capacity(growth.len()),
    };
    let at = |v: &[(i128, i128)], i: usize| v.get(i).map(|&(gap, closing)| Time::new(gap, closing));
    let (mut il, mut ir, mut ig) = (0, 0, 0);
    let (mut tl, mut tr) = (at(left, 0), at(right, 0));
    loop {
        // The earliest head: left, right or both (equal times).
        let (mut t, mut from_l, mut from_r) = match (tl, tr) {
            (Some(a), Some(b)) => match a.cmp(&b) {
                Ordering::Less => (a, true, false),
                Ordering::Greater => (b, false, true),
                Ordering::Equal => (a, true, true),
            },
            (Some(a), None) => (a, true, false),
            (None, Some(b)) => (b, false, true),
            (None, None) => match growth.get(ig) {
                Some(gr) => (gr.t, false, false),
                None => break,
            },
        };
        let mut from_g = false;
        if let Some(gr) = growth.get(ig) {
            match gr.t.cmp(&t) {
                Ordering::Less => (t, from_l, from_r, from_g) = (gr.t, false, false, true),
                Ordering::Equal => from_g = true,
                Ordering::Greater => {}
            }
        }
        let g = out.times.len() as u32;
        out.times.push((t.gap, t.closing));
        if from_l {
            out.map_l.push(g);
            il += 1;
            tl = at(left, il);
        }
        if from_r {
            out.map_r.push(g);
            ir += 1;
            tr = at(right, ir);
        }
        if from_g {
            out.map_g.push(g);
            ig += 1;
        }
    }
    out
}

/// `codes` renumbered by `map` into `out` (`t = 0` and never kept).
fn renumber(out: &mut [u32], codes: &[u32], map: &[u32]) {
    for (o, &code) in out.iter_mut().zip(codes) {
        *o = match code {
            JOIN_NEVER | JOIN_ZERO => code,
            k => map[k as usize],
        };
    }
}

/// The join times of the whole (see the module docs): the instants merged;
/// the halves' join codes renumbered (on `cores`), then the
/// run's where it came first.
fn combine(h: &Halves, growth: &[Growth], n: usize, cores: Cores) -> Joins {
    let instants = merge_instants(h, growth);
    let mut join = vec![JOIN_NEVER; n - 1];
    let (left, right) = join.split_at_mut(h.m);
    both(
        cores,
        || renumber(left, &h.left.join, &instants.map_l),
        || renumber(right, &h.right.join, &instants.map_r),
    );
    for (gr, &g) in growth.iter().zip(&instants.map_g) {
        for j in gr.new_pairs() {
            if !h.joined_before(j, &gr.cut) {
                join[j] = g;
            }
        }
    }
    Joins {
        instants: instants.times,
        join,
    }
}

#[cfg(test)]
mod tests;
