//! What the [`Solver`](crate::solver::Solver) answers: a state at one time
//! and the collision history, each from whichever path computed it — the
//! caller reads the values, never the engine.

use num_bigint::BigInt;
use num_rational::BigRational;

use crate::fast::dyadic::DyadicBlocks;
use crate::fast::filter::Filtered;
use crate::fast::merge::WordHistory;
use crate::fast::stream::{Exact, LeanBlocks};
use crate::state::State;
use crate::trajectory::Trajectory;

/// The exact state at one time (`prop:proj-micro`), as the path that
/// computed it left it.
pub enum Answer<'a> {
    /// The certified `f64` filter's state ([`crate::fast::filter`]): the
    /// nearest doubles, from a partition proved optimal.
    Filtered(Filtered),
    /// The dyadic path's PAVA blocks over columns of doubles
    /// ([`crate::fast::dyadic`]): nearest doubles with no big number.
    Dyadic(DyadicBlocks),
    /// The streaming path's PAVA blocks on machine words
    /// ([`crate::fast::stream`]): exact values written one by one.
    Words(LeanBlocks<'a>),
    /// An exact engine's state, every value a `BigRational`.
    Exact(State<BigRational>),
}

impl Answer<'_> {
    /// The time of the state.
    pub fn t(&self) -> &BigRational {
        match self {
            Answer::Filtered(f) => f.t(),
            Answer::Dyadic(b) => b.t(),
            Answer::Words(b) => b.t(),
            Answer::Exact(s) => &s.t,
        }
    }

    /// The exact state, every value in lowest terms (the same whatever the
    /// path: the library's tests compare them).
    pub fn into_state(self) -> State<BigRational> {
        match self {
            Answer::Filtered(f) => f.exact_state(),
            Answer::Dyadic(b) => b.exact_state(),
            Answer::Words(b) => words_state(&b),
            Answer::Exact(s) => s,
        }
    }
}

/// A value of the streaming path as a `BigRational` (already in lowest
/// terms).
fn rational(e: &Exact) -> BigRational {
    match e {
        Exact::Small(n, d) => BigRational::new_raw(BigInt::from(*n), BigInt::from(*d)),
        Exact::Big(q) => q.clone(),
    }
}

/// The visitor of one column of the streaming path's values.
type Visitor<'v> = dyn FnMut(&Exact) -> std::io::Result<()> + 'v;

/// The values a visitor of the streaming path gives, as `BigRational`s.
fn values(visit: impl FnOnce(&mut Visitor<'_>) -> std::io::Result<()>) -> Vec<BigRational> {
    let mut out = Vec::new();
    // The visitors fail only when their callback does; this one never does.
    let _ = visit(&mut |e| {
        out.push(rational(e));
        Ok(())
    });
    out
}

/// The exact state of the streaming path's blocks.
fn words_state(b: &LeanBlocks<'_>) -> State<BigRational> {
    State {
        t: b.t().clone(),
        positions: values(|f| b.positions(f)),
        velocities: values(|f| b.velocities(f)),
        multipliers: values(|f| b.multipliers(f)),
        clusters: b.clusters(),
    }
}

/// The whole collision history (`prop:micro-pressure`'s impulses), as the
/// path that computed it left it.
pub enum History {
    /// The integer event merge on the streaming path's `i64` columns:
    /// events read one by one, no `BigRational` per event.
    Words(WordHistory),
    /// The event merge's trajectory on the validated data.
    Exact(Trajectory<BigRational>),
}

/// One cluster formed by a collision: the data of `sticky events`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Collision {
    /// The collision time, in lowest terms.
    pub t: BigRational,
    /// The first particle of the cluster formed (from 0).
    pub first: usize,
    /// Its number of particles.
    pub size: usize,
    /// The sizes of the clusters that merged into it, left to right.
    pub parts: Vec<usize>,
}

impl History {
    /// Every cluster formed, sorted by time then by its first particle.
    pub fn collisions(&self) -> Vec<Collision> {
        match self {
            History::Exact(traj) => traj
                .impulses()
                .iter()
                .map(|i| Collision {
                    t: i.t.clone(),
                    first: i.cluster.first,
                    size: i.cluster.size,
                    parts: i.parts.iter().map(|p| p.size).collect(),
                })
                .collect(),
            History::Words(h) => {
                let mut out = Vec::new();
                // The callback never fails.
                let _ = h.for_each_event(|t, first, size, parts| {
                    out.push(Collision {
                        t: rational(t),
                        first,
                        size,
                        parts: parts.iter().map(|&p| p as usize).collect(),
                    });
                    Ok(())
                });
                out
            }
        }
    }
}
