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
//! `gap₂ closing₁` — a 256-bit product ([`I256::product`](crate::fast::wide::I256::product)), never an overflow.
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
//!   candidate (see `run`): the queue only needs approximate keys;
//! * the loop records only *when* each pair joins (and the instants); the
//!   clusters formed, and their parts, are read off those join times once,
//!   at the end (`history`: one stack scan, since at each time the clusters
//!   are the maximal runs of joined pairs);
//! * from 2^15 particles on, the two halves run at once on two threads and
//!   the join times of the whole are repaired from theirs and from the one
//!   cluster that crosses the cut (`split`: the clusters of the whole are
//!   the halves' clusters but for that one, `prop:proj-micro`); from 2^16
//!   particles a piece is cut the same way again (a smaller event loop
//!   stays in the caches), and the two threads share out the pieces of
//!   each height of the tree of cuts as they come free.
//!
//! Every event costs O(1) node accesses and O(1) amortized queue work (an
//! entry moves at most 16 times between buckets); candidates whose times
//! agree with the current instant to about 12 digits without being equal go
//! through a binary heap, O(log N) each. At most N − 1 merges: O(N log N) in
//! all, O(N) memory (one join code per pair while the loops run; then the
//! parts of every impulse as a flat list of part boundaries; the times as
//! unreduced `(gap, closing)` pairs).

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{ToPrimitive, Zero};

use crate::cluster::Cluster;
use crate::contact::Impulse;
use crate::fast::int::{ratio, ratio_over};
use crate::fast::scaling::scale_i128;
use crate::initial::InitialData;
use crate::progress::{Progress, Silent};
use crate::trajectory::Trajectory;

mod events;
mod history;
mod queue;
mod split;
mod sums;
mod time;

use events::{JOIN_NEVER, JOIN_ZERO, MAX_N};
use history::History;
use split::run_split;
use sums::{narrow_sums, within_bound, Words};
pub use time::FILTER;

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
        match Self::new_with_progress(data, &Silent) {
            Ok(t) => t,
            Err(_) => unreachable!("`Silent` never cancels"),
        }
    }

    /// [`IntegerTrajectory::new`], telling `progress` of the generic merge
    /// when it runs ([`Trajectory::new_with_progress`]: the integer engine's
    /// own run is bounded and quick) and stopping with
    /// [`crate::Error::Interrupted`] when it asks.
    pub fn new_with_progress(
        data: &InitialData<BigRational>,
        progress: &dyn Progress,
    ) -> Result<IntegerTrajectory, crate::Error> {
        let scaled = if data.n() < MAX_N {
            scale_i128(data)
        } else {
            None
        };
        let Some(s) = scaled.filter(|s| within_bound(s.x.len(), s.max_abs())) else {
            return Ok(IntegerTrajectory {
                inner: Inner::Generic(Box::new(Trajectory::new_with_progress(
                    data.clone(),
                    progress,
                )?)),
            });
        };
        let narrow = narrow_sums(s.x.len(), s.max_abs());
        let words = match (s.x_range.narrow(&s.x), s.u_range.narrow(&s.u)) {
            (Some(x), Some(u)) => Words::I64(x, u),
            _ => Words::I128(s.x, s.u),
        };
        let (dx, du) = (s.dx, s.du);
        let hist = match (&words, narrow) {
            (Words::I64(x, u), true) => run_split::<i64, i64>(x, u),
            (Words::I64(x, u), false) => run_split::<i64, i128>(x, u),
            (Words::I128(x, u), _) => run_split::<i128, i128>(x, u),
        };
        Ok(IntegerTrajectory {
            inner: Inner::Integer(Box::new(IntegerHistory {
                words,
                dx,
                du,
                radius: data.radius().clone(),
                hist,
            })),
        })
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

/// [`trajectory`], telling `progress` of the merges and stopping with
/// [`crate::Error::Interrupted`] when it asks.
pub fn trajectory_with_progress(
    data: &InitialData<BigRational>,
    progress: &dyn Progress,
) -> Result<Trajectory<BigRational>, crate::Error> {
    Ok(IntegerTrajectory::new_with_progress(data, progress)?.into_trajectory())
}

/// The collision history of the streaming path's `i64` columns
/// ([`crate::fast::stream::Lean`]), kept as the integer engine left it: the
/// events are read one by one ([`WordHistory::for_each_event`]) with no
/// `BigRational` per event.
#[derive(Debug, Clone)]
pub struct WordHistory {
    hist: History,
    dx: i128,
    du: i128,
}

/// The history of `x̃⁰_i = x[i] / dx`, `u⁰_i = u[i] / du` on the integer
/// engine; `None` when its bound does not hold (then the general path).
pub(crate) fn history_words(x: &[i64], u: &[i64], dx: i128, du: i128) -> Option<WordHistory> {
    let n = x.len();
    let m = x
        .iter()
        .chain(u)
        .map(|v| u128::from(v.unsigned_abs()))
        .max()
        .unwrap_or(0);
    if n >= MAX_N || !within_bound(n, m) {
        return None;
    }
    let hist = if narrow_sums(n, m) {
        run_split::<i64, i64>(x, u)
    } else {
        run_split::<i64, i128>(x, u)
    };
    Some(WordHistory { hist, dx, du })
}

impl WordHistory {
    /// Calls `f(t, first, size, parts)` on every cluster formed, in the
    /// order of [`Trajectory::impulses`] (time, then `first`): `t` in lowest
    /// terms, `parts` the sizes of the clusters that merged, left to right.
    pub fn for_each_event(
        &self,
        mut f: impl FnMut(&crate::fast::stream::Exact, usize, usize, &[u32]) -> std::io::Result<()>,
    ) -> std::io::Result<()> {
        use crate::fast::stream::Exact;
        let times: Vec<Exact> = self
            .hist
            .instants
            .iter()
            .map(|&(gap, closing)| {
                // t = gap D_u / (closing D_x).
                match (gap.checked_mul(self.du), closing.checked_mul(self.dx)) {
                    (Some(a), Some(b)) => Exact::ratio(a, b),
                    _ => Exact::Big(BigRational::new(
                        BigInt::from(gap) * BigInt::from(self.du),
                        BigInt::from(closing) * BigInt::from(self.dx),
                    )),
                }
            })
            .collect();
        let mut sizes = Vec::new();
        for (k, &(instant, off)) in self.hist.impulses.iter().enumerate() {
            let stop = self
                .hist
                .impulses
                .get(k + 1)
                .map_or(self.hist.parts.len(), |&(_, o)| o as usize);
            let bounds = &self.hist.parts[off as usize..stop];
            sizes.clear();
            sizes.extend(bounds.windows(2).map(|w| w[1] - w[0]));
            let (first, end) = (bounds[0] as usize, bounds[bounds.len() - 1] as usize);
            f(&times[instant as usize], first, end - first, &sizes)?;
        }
        Ok(())
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
            velocities.push(ratio_over(words.u(i), 1, &du, du_small));
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
            ratio_over(prefix_u[end] - prefix_u[first], k, &du, du_small)
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
    use crate::fast::battery;
    use crate::generate::{initial_data, Limits, SplitMix64};
    use num_traits::One;
    use time::Time;

    use crate::rational::ratio as q;

    fn big(v: &BigInt) -> BigRational {
        BigRational::from_integer(v.clone())
    }

    /// Every engine on `data` through the oracle battery (this one's
    /// impulses, join times and states against the generic ones).
    fn agree(data: &InitialData<BigRational>) -> IntegerTrajectory {
        if let Err(m) = battery::check_probes(data, Some(8)) {
            panic!("{m}");
        }
        IntegerTrajectory::new(data)
    }

    #[test]
    fn a_boundary_rekeyed_past_its_tag_byte() {
        // A particle C at rest, D far to its right moving left, and K
        // particles on C's left moving right at speed 1, one unit apart:
        // they catch C one at a time, and every catch speeds C up and
        // re-keys the pair (C, D) to an earlier time, while its older
        // entries wait in the queue with later keys. After 256 re-keyings
        // the one-byte tags repeat: only the full stamps tell those entries
        // are stale, and one taken for live would add an instant after the
        // last collision.
        const K: usize = 600;
        let x = |v: i128| BigRational::from_integer(BigInt::from(v));
        let mut positions: Vec<BigRational> = (0..K).map(|k| x(k as i128 - K as i128)).collect();
        positions.extend([x(0), x(10_000_000)]);
        let mut velocities = vec![q(1, 1); K];
        velocities.extend([q(0, 1), q(-1, 1)]);
        let data = InitialData::new(q(1, 4), positions, velocities).unwrap();
        let it = agree(&data);
        // K catches, then C meets D: K + 1 clusters formed at K + 1 instants.
        assert_eq!((it.events(), it.instants()), (K + 1, K + 1));
        let traj = it.into_trajectory();
        let last = &traj.impulses()[K];
        assert_eq!((last.cluster.size, last.parts.len()), (K + 2, 2));
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

    /// The integer history is the generic one — impulses (times, parts,
    /// velocities), join times, the rebuilt initial data, the counts of
    /// events and instants — on small random scenes with many equal times,
    /// chains of simultaneous meetings and contacts, scaled so that each
    /// word size runs: `i64` data with `i64` and `i128` sums, `i128` data.
    #[test]
    fn small_random_histories_equal_the_generic() {
        let mut rng = SplitMix64::new(99);
        let mut engines = [0; 3];
        for k in 0..240 {
            let data = initial_data(
                &rng.bytes(200),
                Limits {
                    max_n: 2 + k % 30,
                    max_den: 1 + (k % 4) as u32,
                    max_speed: 1 + (k % 5) as u32,
                },
            );
            // Shift every position by 2^s: X_i beyond i64 (s = 70) and
            // N·M beyond 2^63 (s = 59, most scenes) without changing the history.
            let shift = [None, Some(59), Some(70)][k % 3];
            let data = match shift {
                None => data,
                Some(s) => {
                    let off = big(&(BigInt::one() << s));
                    let x = data.positions().iter().map(|p| p + &off).collect();
                    InitialData::new(data.radius().clone(), x, data.velocities().to_vec()).unwrap()
                }
            };
            let it = IntegerTrajectory::new(&data);
            let s = scale_i128(&data).unwrap();
            let m =
                s.x.iter()
                    .chain(&s.u)
                    .map(|v| v.unsigned_abs())
                    .max()
                    .unwrap();
            // 0: i64 data and sums; 1: i64 data, i128 sums; 2: i128 data.
            let class = if m >= 1 << 63 {
                2
            } else {
                usize::from(m * data.n() as u128 >= 1 << 63)
            };
            engines[class] += 1;
            let want_engine = [Engine::Int64, Engine::Int64, Engine::Int128][class];
            assert_eq!(it.engine(), want_engine, "scene {k}");
            let (events, instants) = (it.events(), it.instants());
            let got = it.into_trajectory();
            let want = Trajectory::new(data.clone());
            assert_eq!(got.data(), want.data(), "scene {k}");
            assert_eq!(got.impulses(), want.impulses(), "scene {k}");
            assert_eq!(got.join_times(), want.join_times(), "scene {k}");
            assert_eq!(events, want.impulses().len(), "scene {k}");
            let mut times: Vec<_> = want.impulses().iter().map(|i| &i.t).collect();
            times.dedup();
            assert_eq!(instants, times.len(), "scene {k}");
        }
        assert!(engines.iter().all(|&c| c >= 40), "{engines:?}");
    }

    /// Event times whose unreduced `gap·D_u` leaves `i128` are reduced on
    /// `BigInt`: eight particles 2^58 apart at 1/3 past the integers
    /// (`D_x = 3`), velocities `(100 s₁ + 10 s₂ + s₃)/2^62` (`s₁`, `s₂`,
    /// `s₃ = ±1` alternating by particle, by pair, by half): pairs meet, then
    /// pairs of pairs, then the halves, with `gap = 16 · 3 · 2^60` and
    /// `D_u = 2^62`.
    #[test]
    fn event_times_beyond_machine_products() {
        let sign = |b: bool| if b { 1 } else { -1 };
        let x = (0..8)
            .map(|i| big(&(BigInt::from(i) << 58u32)) + q(1, 3))
            .collect();
        let u = (0..8)
            .map(|i| {
                let v = 100 * sign(i % 2 == 0) + 10 * sign(i / 2 % 2 == 0) + sign(i < 4);
                BigRational::new(BigInt::from(v), BigInt::one() << 62u32)
            })
            .collect();
        let data = InitialData::new(q(1, 2), x, u).unwrap();
        let it = IntegerTrajectory::new(&data);
        assert_eq!(
            (it.engine(), it.events(), it.instants()),
            (Engine::Int64, 7, 3)
        );
        let got = it.into_trajectory();
        let want = Trajectory::new(data);
        assert_eq!(got.impulses(), want.impulses());
        assert_eq!(got.join_times(), want.join_times());
    }

    /// Pairs whose meeting times agree to 12 digits or more but differ (the
    /// float filter cannot order them: the exact window decides), in both
    /// orders and with a third pair between them: the generic history.
    #[test]
    fn near_ties_merge_in_time_order() {
        let x = |v: i128| BigRational::from_integer(BigInt::from(v));
        let base = 1i128 << 50;
        for (da, db, dc) in [(1, 0, 2), (0, 1, 2), (2, 1, 0), (0, 2, 1), (1, 1, 0)] {
            // Pair k: particle at rest at gap g_k to the right of one moving
            // at speed 1, far from the others: they meet at t = g_k.
            let gaps = [base + da, base + db, base + dc];
            let mut pos = Vec::new();
            for (k, g) in gaps.iter().enumerate() {
                let left = 4 * base * k as i128;
                pos.extend([x(left), x(left + 1 + g)]);
            }
            let vel = (0..6).map(|i| q(1 - (i % 2) as i64, 1)).collect();
            let data = InitialData::new(q(1, 2), pos, vel).unwrap();
            let it = IntegerTrajectory::new(&data);
            assert_ne!(it.engine(), Engine::BigRational);
            let got = it.into_trajectory();
            let want = Trajectory::new(data);
            assert_eq!(got.impulses(), want.impulses(), "gaps {gaps:?}");
            assert_eq!(got.join_times(), want.join_times(), "gaps {gaps:?}");
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
    fn the_bound_is_strict() {
        // N = 2: max(N, ⌊N²/4⌋) = 2, so M = 2^125 gives B = 2^126 exactly,
        // which the width bound excludes; M = 2^125 − 1 is inside it.
        let m: BigInt = BigInt::one() << 125u32;
        for (top, engine) in [(m.clone(), Engine::BigRational), (m - 1, Engine::Int128)] {
            // r = 1/2: x̃ = (0, top), u = (1, 0), every denominator 1.
            let data = InitialData::new(
                q(1, 2),
                vec![q(0, 1), big(&top) + q(1, 1)],
                vec![q(1, 1), q(0, 1)],
            )
            .unwrap();
            assert_eq!(agree(&data).engine(), engine, "M = {top}");
        }
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
        let it = agree(&data);
        assert_eq!(it.engine(), Engine::BigRational);
        // The counts of the generic history: clusters formed, and distinct
        // instants (two clusters formed at t = 1/2, which meet later).
        let want = Trajectory::new(data.clone());
        let mut times: Vec<_> = want.impulses().iter().map(|i| &i.t).collect();
        times.dedup();
        assert!(times.len() >= 2 && times.len() < want.impulses().len());
        assert_eq!(
            (it.events(), it.instants()),
            (want.impulses().len(), times.len())
        );
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
